"""The family slider in the viewer (headless Chromium): a synthesised slider-crank's or crank-rocker's page shows
it, and moving it redraws the mechanism with the member's crank (the drawn crank's length is the member's)."""

from __future__ import annotations

import math
import shutil

import numpy as np
import pytest

playwright = pytest.importorskip("playwright.sync_api")

import linkwork as lw  # noqa: E402
from linkwork.synthesis import synthesize  # noqa: E402
from linkwork.web import create_app  # noqa: E402

pytestmark = pytest.mark.browser


@pytest.mark.parametrize(
    ("kind", "requirements", "pivot", "shown"),
    [
        ("slider-crank", {"stroke": 0.4, "time_ratio": 1.3, "min_transmission_angle": 0.5}, "O", "largest pressure"),
        (
            "crank-rocker",
            {"swing": math.radians(50), "time_ratio": 1.3, "rocker": 0.3, "min_transmission_angle": 0.2},
            "O2",
            "least transmission",
        ),
    ],
)
def test_moving_the_family_slider_redraws_the_member(tmp_path, kind, requirements, pivot, shown):
    from webserver import serving

    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    if chromium is None:
        pytest.skip("chromium is not installed (.ci/run installs it)")
    path = synthesize(kind, **requirements).write(tmp_path / "mechanism.yaml")
    family = create_app(lw.load(str(path)))
    with serving(family) as (host, port), playwright.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=chromium, args=["--headless", "--no-sandbox", "--disable-gpu"])
        page = browser.new_page(viewport={"width": 1400, "height": 1000})
        errors: list[str] = []
        page.on("pageerror", lambda exc: errors.append(str(exc)))
        page.goto(f"http://{host}:{port}/")
        page.wait_for_selector("#family-slider")
        members = page.evaluate("fetch('api/family').then(r => r.json())")
        last = len(members["overrides"]) - 1
        page.locator("#family-slider").fill(str(last))
        want = members["overrides"][last]["links.crank.length"]

        def crank() -> float:
            where = "e => [e.getAttribute('cx'), e.getAttribute('cy')]"
            xy = [page.eval_on_selector(f'#scheme circle[data-point="{q}"]', where) for q in (pivot, "A")]
            (x0, y0), (x1, y1) = (np.array(v, dtype=float) / 1000 for v in xy)
            return float(np.hypot(x1 - x0, y1 - y0))

        page.wait_for_function(
            "([w, p]) => { const a = document.querySelector('#scheme circle[data-point=\"A\"]'), "
            'o = document.querySelector(`#scheme circle[data-point="${p}"]`); '
            "return Math.abs(Math.hypot(a.getAttribute('cx') - o.getAttribute('cx'), "
            "a.getAttribute('cy') - o.getAttribute('cy')) / 1000 - w) < 1e-5; }",
            arg=[want, pivot],
            timeout=60_000,
        )
        assert crank() == pytest.approx(want, abs=1e-5)
        assert shown in page.text_content("#family-text")
        assert not errors
        browser.close()
