"""The built manual, as a reader gets it: every page of the Python reference shows a signature and its
Parameters, no navigation file is built as a page, no two files differ only by case (one file on macOS and
Windows), and the site opened from disk (file://) in headless Chromium searches a Russian word form and loads
nothing from the network.

The site is the one ``LINKWORK_SITE`` names (CI builds it in the docs extra's environment), else it is built here
(``mkdocs build --strict``, a few minutes: the slow lane's); without mkdocs and without ``LINKWORK_SITE`` the
tests are skipped.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from manual import ROOT

pytestmark = [pytest.mark.slow, pytest.mark.browser]

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking", "--no-first-run"]


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    given = os.environ.get("LINKWORK_SITE")
    if given:
        return Path(given)
    pytest.importorskip("mkdocs", reason="the manual's build: pip install '.[docs]', or set LINKWORK_SITE")
    out = tmp_path_factory.mktemp("site")
    env = {**os.environ, "NO_MKDOCS_2_WARNING": "1", "DISABLE_MKDOCS_2_WARNING": "true", "LINKWORK_NUMBA": "0"}
    command = [sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(out)]
    done = subprocess.run(command, cwd=ROOT, env=env, capture_output=True, text=True, timeout=1800)
    assert done.returncode == 0, done.stderr[-3000:]
    return out


def _text(html: str) -> str:
    return re.sub(r"\s+", " ", re.sub(r"<[^>]+>", " ", html))


def test_every_page_of_the_python_reference_shows_a_signature_and_its_parameters(site: Path):
    pages = sorted(p for p in (site / "reference" / "api").glob("*.html") if p.name != "index.html")
    assert len(pages) >= 30, [p.name for p in pages]
    missing = []
    for path in pages:
        content = path.read_text(encoding="utf-8").split('data-md-component="content"', 1)[1]
        if "doc-signature" not in content:
            missing.append(f"{path.name}: no signature")
        if not re.search(r"doc-section-title\">\s*Parameters", content):
            missing.append(f"{path.name}: no Parameters")
    assert missing == []
    spec = _text((site / "reference" / "api" / "Spec-class.html").read_text(encoding="utf-8"))
    for field in ("links", "joints", "drives", "gravity", "hints"):
        assert re.search(rf"\b{field}\b", spec.split("Parameters", 1)[1]), field


def test_no_navigation_file_is_built_as_a_page(site: Path):
    assert sorted(p.relative_to(site).as_posix() for p in site.rglob("SUMMARY.html")) == []


def test_no_two_files_of_the_site_differ_only_by_case(site: Path):
    seen: dict[str, str] = {}
    clashes = []
    for path in site.rglob("*"):
        name = path.relative_to(site).as_posix()
        if seen.setdefault(name.lower(), name) != name:
            clashes.append((seen[name.lower()], name))
    assert clashes == []


def _chromium() -> str:
    path = shutil.which("chromium") or shutil.which("chromium-browser")
    if path is None and os.environ.get("CI"):
        pytest.fail("chromium is not installed")
    if path is None:
        pytest.skip("chromium is not installed (.ci/run installs it)")
    return path


def test_the_site_opened_from_disk_finds_a_russian_word_form_and_loads_nothing_from_the_network(site: Path):
    """``кривошипа`` (genitive; the pages say ``кривошип``, ``кривошипа``, ``кривошипом``...) finds the Russian
    tutorials; the theme's search runs in a worker the iframe-worker polyfill starts from file://."""
    sync_api = pytest.importorskip("playwright.sync_api")
    with sync_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=_chromium(), args=FLAGS)
        try:
            page = browser.new_context(viewport={"width": 1200, "height": 900}).new_page()
            requests: list[str] = []
            page.on("request", lambda r: requests.append(r.url))
            page.goto((site / "index.html").as_uri())
            box = page.locator("input.md-search__input")
            if not box.is_visible():  # a narrow window: the header's button opens the search
                page.locator("label.md-header__button[for=__search]").click()
            box.fill("кривошипа")
            results = page.locator(".md-search-result__item")
            sync_api.expect(results.first).to_be_visible(timeout=60_000)
            found = results.all_inner_texts()
            hrefs = page.locator("a.md-search-result__link").evaluate_all("links => links.map(a => a.href)")
        finally:
            browser.close()
    assert any("/ru/" in href for href in hrefs), hrefs
    assert any("кривошип" in text.lower() for text in found), found
    assert [u for u in requests if not u.startswith(("file:", "data:", "blob:", "about:"))] == []
