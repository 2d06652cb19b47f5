"""What the manual's site promises a reader, checked from its sources without building it: it opens from disk and
loads nothing from the network, its search stems Russian, its formulas have a renderer shipped with it, every
public function of the Python reference has its parameters and an example, and the user's pages show pictures
drawn from the code."""

from __future__ import annotations

import ast
import inspect
import re

import yaml

from manual import DOCS, ROOT, page

#: The sections of the manual that explain by showing: at least half of their pages show a picture.
SHOWN = ("getting-started", "guide", "how-to", "examples", "concepts")


def _config() -> dict:
    return yaml.safe_load((ROOT / "mkdocs.yml").read_text(encoding="utf-8"))


def _plugins(config: dict) -> dict:
    return {
        next(iter(p)) if isinstance(p, dict) else p: (p[next(iter(p))] if isinstance(p, dict) else {}) or {}
        for p in config["plugins"]
    }


def test_the_site_opens_from_disk_and_stems_russian():
    plugins = _plugins(_config())
    assert "offline" in plugins, "the offline plugin makes the site work from file://"
    assert {"en", "ru"} <= set(plugins["search"].get("lang", [])), plugins["search"]


def test_every_script_and_style_the_site_loads_is_shipped_with_it():
    """No CDN: each of extra_javascript, extra_css and the polyfills is a file under docs/ (the offline plugin
    adds iframe-worker from a CDN unless a polyfill of that name is there)."""
    config = _config()
    loaded = [*config.get("extra_javascript", []), *config.get("extra_css", []), *config["extra"]["polyfills"]]
    assert any("iframe-worker" in s for s in config["extra"]["polyfills"])
    for src in loaded:
        assert not re.match(r"^(https?:)?//", src), src
        assert (DOCS / src).is_file(), f"{src} is not in docs/"
        assert (DOCS / src).stat().st_size > 0, src


def test_a_math_renderer_is_shipped_and_the_theory_pages_use_it():
    config = _config()
    scripts = [DOCS / s for s in config["extra_javascript"]]
    assert any(s.name.startswith("tex-") and s.stat().st_size > 1_000_000 for s in scripts), "MathJax's bundle"
    extensions = {next(iter(e)) if isinstance(e, dict) else e for e in config["markdown_extensions"]}
    assert "pymdownx.arithmatex" in extensions
    for name in ("how-to/synthesize.md", "guide/sizing.md", "guide/force-plans.md", "how-to/dynamics.md"):
        assert "$$" in page(name), f"{name}: its formulas as LaTeX"


def _groups() -> list:
    """docs/gen/reference.py's GROUPS, read from its source (the script writes the pages when it runs)."""
    tree = ast.parse((DOCS / "gen" / "reference.py").read_text(encoding="utf-8"))
    for node in tree.body:
        if isinstance(node, ast.AnnAssign) and getattr(node.target, "id", "") == "GROUPS":
            return ast.literal_eval(node.value)
    raise AssertionError("GROUPS not found")


def test_every_public_name_is_in_a_group_of_the_reference():
    import linkwork

    grouped = {e for _, _, entries in _groups() for e in entries if isinstance(e, str)}
    assert set(linkwork.__all__) - {"__version__"} <= grouped
    titles = [title for title, _, _ in _groups()]
    assert titles == [
        "Load and build",
        "Analyse",
        "Design and synthesise",
        "Size",
        "Draw and report",
        "Viewer",
        "Design on Dask",
    ]


def _sections(doc: str) -> set[str]:
    return set(re.findall(r"^\s*(\w[\w ]*)\n\s*-{3,}\s*$", doc, re.M))


def test_every_function_of_the_reference_has_parameters_returns_and_an_example():
    """The numpydoc sections mkdocstrings renders under each function's signature."""
    import linkwork

    missing = []
    for name in linkwork.__all__:
        obj = getattr(linkwork, name, None)
        if name == "__version__" or inspect.isclass(obj):
            continue
        sections = _sections(inspect.getdoc(inspect.unwrap(obj)) or "")
        missing += [f"lw.{name}: {s}" for s in ("Parameters", "Returns", "Examples") if s not in sections]
    assert missing == []


def _documented(doc: str) -> list[str] | None:
    """The names a numpydoc Parameters section documents (``p5, p4 : int`` documents two), None without one."""
    m = re.search(r"^Parameters\n-{3,}\n(.*?)(?=^\w[\w ]*\n-{3,}$|\Z)", doc, re.S | re.M)
    if m is None:
        return None
    heads = [re.match(r"^([*\w]+(?:, [*\w]+)*)\s*(?::|$)", line) for line in m.group(1).splitlines()]
    return [name.strip("*") for h in heads if h for name in h.group(1).split(", ")]


def _options() -> dict:
    return _plugins(_config())["mkdocstrings"]["handlers"]["python"]["options"]


def test_every_page_of_the_reference_shows_the_signature_and_documents_each_parameter():
    """A function's or a class's Parameters name exactly the parameters of its signature (a class's: its
    constructor's, shown on its page with the class, ``merge_init_into_class``); a pydantic model's page has them
    from the model's fields (``docs/gen/fields.py``), as its constructor takes them."""
    import linkwork

    options = _options()
    assert options.get("show_signature", True) and options["merge_init_into_class"] is True
    assert "docs/gen/roles.py:ModelFields" in options["extensions"]
    wrong = []
    for name in sorted(set(linkwork.__all__) - {"__version__"}):
        obj = inspect.unwrap(getattr(linkwork, name))
        if hasattr(obj, "model_fields"):  # lw.Spec: its fields are its keyword-only parameters
            assert list(inspect.signature(obj).parameters) == list(obj.model_fields), name
            continue
        signature = [p for p in inspect.signature(obj).parameters if p != "self"]
        documented = _documented(inspect.getdoc(obj) or "")
        if documented is None or sorted(documented) != sorted(signature):
            wrong.append(f"lw.{name}: documents {documented}, its signature has {signature}")
    assert wrong == []


def test_a_model_page_has_every_field_with_its_type_default_and_meaning():
    """``lw.Spec``'s page: the Parameters that ``docs/gen/fields.py`` reads from the model, each field with the
    type a file takes, its default where it has one, and a sentence; ``roles.py``'s ``ModelFields`` shows them."""
    import importlib.util

    import linkwork as lw

    spec = importlib.util.spec_from_file_location("fields", DOCS / "gen" / "fields.py")
    fields = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(fields)
    rows = {name: (kind, default, meaning) for name, kind, default, meaning in fields.model_parameters(lw.Spec)}
    assert list(rows) == list(lw.Spec.model_fields)
    assert rows["gravity"][:2] == ("Gravity or float or str (an acceleration)", "9.81")
    assert rows["links"][:2] == ("dict[str, Link]", None)  # required
    assert rows["units"][1] == "Units()" and rows["machine"][:2] == ("Machine or None", "None")
    assert all(len(meaning.split()) >= 3 for _, _, meaning in rows.values()), rows
    section = fields.parameters_section(list(fields.model_parameters(lw.Spec)))
    assert _documented(section) == list(lw.Spec.model_fields)
    assert "class ModelFields(griffe.Extension)" in (DOCS / "gen" / "roles.py").read_text(encoding="utf-8")


def test_forces_lists_its_own_parameters():
    import linkwork as lw

    doc = inspect.getdoc(inspect.unwrap(lw.forces)) or ""
    params = doc.split("Parameters", 1)[1].split("Returns", 1)[0]
    for name in ("angles", "steps", "speed", "variants"):
        assert re.search(rf"^{name} :", params, re.M), name
    assert "as for" not in doc


def _pictures() -> set[str]:
    text = (DOCS / "gen" / "pictures.py").read_text(encoding="utf-8")
    return set(re.findall(r'^    "([\w-]+)": \(', text, re.M)) | set(re.findall(r'"pictures/([\w-]+)\.png"', text))


def test_half_the_pages_that_explain_show_a_picture_drawn_from_the_code():
    pages = [p for section in SHOWN for p in sorted((DOCS / section).glob("*.md"))]
    shown, unknown = [], []
    for path in pages:
        used = re.findall(r"!\[[^\]]*\]\(([^)]+\.(?:svg|png|gif))\)", path.read_text(encoding="utf-8"))
        shown += [path] if used else []
        unknown += [f"{path.name}: {u}" for u in used if "pictures/" in u and u.split("/")[-1][:-4] not in _pictures()]
    assert unknown == [], "a picture that docs/gen/pictures.py does not draw"
    assert len(shown) * 2 >= len(pages), f"{len(shown)} of {len(pages)} pages show a picture"


def test_no_page_cites_a_file_that_does_not_exist():
    for path in [ROOT / "README.md", *DOCS.rglob("*.md")]:
        assert "example-data.md" not in path.read_text(encoding="utf-8"), path


def test_the_user_pages_cite_no_test_or_source_file_as_evidence():
    """A reader checks a figure by the method the page gives, not by a test's name or a source path (the pages
    for developers, and the install page's command for the test suite, aside; HTML comments are not shown)."""
    aside = {"development.md", "benchmarks.md", "changelog.md", "getting-started/install.md"}
    cited = []
    for path in DOCS.rglob("*.md"):
        if path.relative_to(DOCS).as_posix() in aside:
            continue
        text = re.sub(r"<!--.*?-->", "", path.read_text(encoding="utf-8"), flags=re.S)
        cited += [f"{path.name}: {m}" for m in re.findall(r"\btest_\w+|tests/[\w/]+\.py|src/linkwork/[\w/.]+", text)]
    assert cited == []


def test_the_search_stems_the_word_a_reader_types():
    """The search box queries each term as a prefix (``маховика*``), which lunr's parser keeps out of the stemmers:
    the theme's lunr.ru is replaced by one that stems such a term, and the stemmers are in the pipeline."""
    plugins = _plugins(_config())
    assert "stemmer" in plugins["search"]["pipeline"]
    override = ROOT / _config()["theme"]["custom_dir"] / "assets/javascripts/lunr/min/lunr.ru.min.js"
    text = override.read_text(encoding="utf-8")
    assert "QueryParser.prototype.nextClause" in text and 'registeredFunctions["stemmer-ru"]' in text


def test_the_bundled_examples_name_their_papers_by_authors_and_title():
    """``linkwork examples`` and the reports quote a file's description: a paper is named as a reader finds it,
    not by a number of the project's own."""
    from linkwork.examples import load_example, names

    for name in names():
        description = load_example(name).description or ""
        assert not re.search(r"\bseed\b", description, re.I), name
    assert "Klyushnik" in (load_example("double-cut-shears").description or "")


def test_the_commands_a_new_reader_copies_fit_a_narrow_screen():
    """The install page's commands are split with ``\\`` so that no line runs past a phone's code box (about 40
    characters of code fit at 400 px): the one-liner was cut at ``&& lin...``.  The other pages' commands, one
    a line (the tests run each), stay within a laptop's half screen."""
    from manual import blocks

    for path in sorted((DOCS / "getting-started").glob("*.md")):
        width = 40 if path.name == "install.md" else 60
        for lang, code, line in blocks(path.read_text(encoding="utf-8")):
            if lang == "bash":
                long = [c for c in code.splitlines() if len(c) > width]
                assert long == [], f"{path.name}:{line}: {long}"


def test_no_paragraph_of_the_user_pages_runs_on_for_more_than_fifteen_lines():
    """Prose in paragraphs a reader takes in at a glance: the pages had paragraphs of 20 to 35 lines (lists,
    tables, code and the pages for developers aside; 8 lines is the aim, a few run to 15)."""
    aside = {"development.md", "benchmarks.md", "changelog.md"}
    long = []
    for path in sorted(DOCS.rglob("*.md")):
        if path.relative_to(DOCS).as_posix() in aside:
            continue
        text = re.sub(r"^```.*?^```|<!--.*?-->", "", path.read_text(encoding="utf-8"), flags=re.S | re.M)
        for para in re.split(r"\n\s*\n", text):
            lines = para.strip("\n").splitlines()
            if len(lines) > 15 and not para.lstrip().startswith(("|", "-", "*", "1.", "#", "$$")):
                long.append(f"{path.relative_to(DOCS)}: {len(lines)} lines from {lines[0][:40]!r}")
    assert long == []
