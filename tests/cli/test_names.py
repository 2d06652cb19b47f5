"""Names in any script (Cyrillic, Greek, CJK, combining accents) through every output, and back the same:
the tables (CSV, NetCDF, JSON), the report (HTML, SVG, DXF, the figures' file names) in the C locale, and
the viewer; the same tests with the bundled English names."""

from __future__ import annotations

import csv
import json
import os
import re
import subprocess
import sys
from pathlib import Path
from urllib.parse import unquote

import pytest
from typer.testing import CliRunner

from linkwork.cli.main import app
from linkwork.examples import text

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[2]

#: The double-cut shears' names, and the names they get in several scripts (a combining acute in two).
SCRIPTS = {
    "double-cut-shears": "Ножницы — ψαλίδι 剪刀 e\u0301",
    "crank": "кривошип",
    "rod": "шатун",
    "rocker": "μοχλός",
    "rod_DE": "连杆_DE",
    "rod_CF": "连杆_CF",
    "knife_upper": "нож_верхний",
    "knife_lower": "刀_下",
    "guide_E": "направляющая_E",
    "guide_F": "направляющая_F",
    "cutting": "резание",
    "edge": "кромка",
    "A": "А\u0301",
    "B": "Β",
    "C": "Ц",
    "D": "Δ",
    "E": "e\u0301",
    "F": "Ф",
    "O1": "О₁",
    "O3": "О₃",
}
LINKS = ["crank", "rod", "rocker", "rod_DE", "knife_upper", "rod_CF", "knife_lower"]
JOINTS = ["O1", "A", "B", "O3", "D", "E", "guide_E", "C", "F", "guide_F"]


def _source(script: str) -> tuple[str, dict[str, str]]:
    """The double-cut shears' file in ``script`` (``english``: as bundled, else renamed, its description in
    Russian), and its names by their English ones."""
    if script == "english":
        return text("double-cut-shears"), {k: k for k in SCRIPTS}
    lines = []
    for line in text("double-cut-shears").splitlines():
        code = line.split("#", 1)[0]
        if code.startswith("  ") and not code.startswith("    ") and lines and lines[-1] == "description: |":
            continue  # the description's lines, written anew below
        for old, new in SCRIPTS.items():
            code = re.sub(rf"(?<![\w\-]){re.escape(old)}(?![\w\-])", new, code)
        lines.append(code.replace(f"name: {SCRIPTS['double-cut-shears']}", f'name: "{SCRIPTS["double-cut-shears"]}"'))
    source = "\n".join(lines).replace("description: |", "description: |\n  Ножницы с параллельными ножами; 剪刀.")
    return source, SCRIPTS


@pytest.fixture(params=["english", "scripts"])
def named(request, tmp_path):
    source, names = _source(request.param)
    path = tmp_path / f"{re.sub(r'[ —]+', '_', names['double-cut-shears'])}.yaml"  # Ножницы_ψαλίδι_剪刀_é
    path.write_text(source, encoding="utf-8")
    return path, names


def test_the_tables_carry_the_names(named, tmp_path):
    """`check --json`, `kinematics --out` (CSV, NetCDF) and `forces --out` (CSV, JSON) read back."""
    import linkwork.cli.forces  # noqa: F401 - registers the commands
    import linkwork.cli.motion  # noqa: F401

    path, n = named
    result = runner.invoke(app, ["check", str(path), "--json"])
    assert result.exit_code == 0, result.output
    assert [g["links"] for g in json.loads(result.stdout)["groups"]] == [[1], [2, 3], [4, 5], [6, 7]]
    for command in ("kinematics", "forces"):
        result = runner.invoke(app, [command, str(path), "--steps", "36", "--out", str(tmp_path / "t")])
        assert result.exit_code == 0, result.output
    with open(tmp_path / "t" / "kinematics.csv", encoding="utf-8", newline="") as fh:
        header = next(csv.reader(fh))
    points = {n[p] for p in ("O1", "A", "B", "O3", "C", "D", "E", "F")}
    assert points <= {h.split(".")[0] for h in header}
    xr = pytest.importorskip("xarray")
    with xr.open_dataset(tmp_path / "t" / "kinematics.nc") as ds:
        assert ds.attrs["mechanism"] == n["double-cut-shears"]
        assert points <= set(ds["point"].values.tolist())
        assert ds["link"].values.tolist() == [n[k] for k in LINKS]
    forces = json.loads((tmp_path / "t" / "forces.json").read_text(encoding="utf-8"))
    assert forces["name"] == n["double-cut-shears"]
    assert list(forces["joints"]) == [n[j] for j in JOINTS]
    assert list(forces["loads"]) == [n["cutting"]]
    with open(tmp_path / "t" / "forces.csv", encoding="utf-8", newline="") as fh:
        header = next(csv.reader(fh))
    assert f"{n['guide_E']} (frame on {n['knife_upper']}).moment [N m]" in header


def test_the_report_carries_the_names_in_the_c_locale(named, tmp_path):
    """`analyze --dxf` in its own process under LC_ALL=C: the report, its SVG figures' texts, its DXF
    drawings' texts and the figures named after points carry the names as the file writes them."""
    pytest.importorskip("ezdxf")
    import ezdxf

    from linkwork.scene.geometry import text_runs

    path, n = named
    env = {**os.environ, "LC_ALL": "C", "LANG": "C", "PYTHONPATH": str(ROOT / "src"), "LINKWORK_NUMBA": "0"}
    env.pop("PYTHONIOENCODING", None)
    out = tmp_path / "report"
    args = [str(path), "--out", str(out), "--steps", "36", "--no-animation", "--dxf"]
    done = subprocess.run(
        [sys.executable, "-m", "linkwork.cli", "analyze", *args], env=env, capture_output=True, timeout=300
    )
    assert done.returncode == 0, done.stderr.decode("utf-8", "replace")[-3000:]
    html = (out / "report.html").read_text(encoding="utf-8")
    assert html.count(n["double-cut-shears"]) >= 2 and n["crank"] in html
    svg = (out / "figures" / "scheme.svg").read_text(encoding="utf-8")
    msp = ezdxf.readfile(out / "figures" / "scheme.dxf").modelspace()
    texts = {e.dxf.text for e in msp.query("TEXT")} | {e.plain_text() for e in msp.query("MTEXT")}
    for name in (n["O1"], n["A"], n["E"], n["F"], n["edge"]):
        runs = text_runs(name)  # a trailing number is drawn as a subscript (O1: O and 1 below): every run is drawn
        assert all(run in svg for run, _ in runs), name
        assert "".join(("^" if sub else "") + run for run, sub in runs) in texts, name  # MTEXT's stacked index
    assert any(t.startswith(f"{n['double-cut-shears']}: ") for t in texts)
    assert {p.name for p in (out / "figures").glob("hodograph_*.svg")} == {
        f"hodograph_{n['O1']}.svg",
        f"hodograph_{n['O3']}.svg",
    }


def test_the_viewer_carries_the_names(named):
    """The viewer's cycle names the links and points; the file it saves is offered under the file's name in
    its script, and holds the names."""
    pytest.importorskip("fastapi")
    from fastapi.testclient import TestClient

    import linkwork as lw
    from linkwork.web import create_app

    path, n = named
    client = TestClient(create_app(lw.load(path)), base_url="http://127.0.0.1")
    cycle = client.get("/api/cycle")
    assert cycle.status_code == 200
    body = cycle.json()
    assert n["double-cut-shears"] in json.dumps(body, ensure_ascii=False)
    assert n["knife_upper"] in json.dumps(body, ensure_ascii=False)
    saved = client.post("/api/save", json={"overrides": {}})
    assert saved.status_code == 200
    offered = re.search(r"filename\*=UTF-8''([^;\s]+)", saved.headers["content-disposition"])
    assert offered is not None and unquote(offered.group(1)) == f"{path.stem}-edited.yaml"
    assert all(n[k] in saved.text for k in ("crank", "E", "cutting"))
