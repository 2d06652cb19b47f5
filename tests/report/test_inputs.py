"""What a report says it computed: its input section, the flywheel of Wittenbauer's tangents, and why the
simulated delta is not the one asked for."""

from __future__ import annotations

import html
import math
import re
import sys
from pathlib import Path

import numpy as np
import pytest
from ruamel.yaml import YAML

pytest.importorskip("matplotlib")

import linkwork as lw  # noqa: E402
from commandline import linkwork  # noqa: E402
from linkwork import figures  # noqa: E402
from linkwork.examples import names, text  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from drawing_checks import overlaps  # noqa: E402


def _html(page: str, key: str) -> str:
    start = page.index(f"<section id='{key}'>")
    return re.sub(r"<pre>.*?</pre>", "", page[start : page.index("</section>", start)], flags=re.S)


def _section(page: str, key: str) -> str:
    """The text of a section of the report: each cell, paragraph and row as ``| text |``, entities read."""
    part = re.sub(r"</?code>", "", _html(page, key))
    part = re.sub(r"</?(tr|thead|tbody|table|p|details|summary|h2|section)[^>]*>", "\n", part)
    part = re.sub(r"</td><td>", " | ", part)
    return html.unescape(re.sub(r"<[^>]+>", " | ", part))


def _rows(page: str, key: str) -> dict[str, list[str]]:
    """The rows of a section's tables by their first cell."""
    rows = re.findall(r"<tr>(.*?)</tr>", _html(page, key))
    cells = [[html.unescape(re.sub(r"<[^>]+>", "", c)) for c in re.findall(r"<td>(.*?)</td>", r)] for r in rows]
    return {c[0]: c for c in cells if c}


@pytest.fixture(scope="module")
def report(report, tmp_path_factory):
    """The page of a bundled example's report: without options the run's shared one (tests/conftest.py), with
    options written by the command in a process of its own."""
    root = tmp_path_factory.mktemp("inputs")

    def make(name: str, *extra: str) -> str:
        if not extra:
            return (report(name) / "report.html").read_text(encoding="utf-8")
        out = root / f"{name}{len(extra)}"
        result = linkwork("analyze", name, "--out", str(out), "--steps", "36", "--no-animation", *extra)
        assert result.returncode == 0, result.stderr
        return (out / "report.html").read_text(encoding="utf-8")

    return make


@pytest.mark.parametrize("name", names())
def test_every_report_says_what_it_computed(report, name):
    """The drive's speed and the links' masses as the file gives them (read here from the YAML itself), the
    number of steps, and the file."""
    data = YAML(typ="safe").load(text(name))
    page = report(name)
    assert "<nav><a href='#input'>" in page
    section = _section(page, "input")
    assert "over 36 equal steps of the crank's turn" in section
    speed = data["drives"][0]["speed"]
    rpm = float(speed.split()[0]) if str(speed).endswith("rpm") else None
    if rpm is not None:
        assert f"{rpm:g} rpm" in section
    rows = _rows(page, "input")
    for link, given in data["links"].items():
        if "mass" in given:
            assert float(rows[link][2]) == pytest.approx(float(given["mass"])), link
    assert f"The file {name}.yaml" in section
    for load in data.get("loads", {}):
        assert load in rows
    if "machine" in data:
        motor = data["machine"]["motor"]
        assert f"power {motor['power']}" in section


@pytest.mark.slow  # over the default lane's budget on the NumPy kernels (tests/conftest.py)
def test_the_input_section_gives_dimensions_in_mm_and_the_speed_solved(report):
    """The four-bar's crank of 100 mm, coupler point M at (175, 80) mm, its rocker of 0.25 m as 250 mm, at
    the 120 rpm of --speed (not the file's 60)."""
    page = report("four-bar", "--speed", "120 rpm")
    section, rows = _section(page, "input"), _rows(page, "input")
    assert rows["crank"][1] == "O2 (0, 0), A (100, 0)"
    assert "M (175, 80)" in rows["coupler"][1] and rows["rocker"][1] == "O4 (0, 0), B (250, 0)"
    assert f"120 rpm ({4 * math.pi:.6g} rad/s) counter-clockwise" in section


@pytest.mark.slow  # over the default lane's budget on the NumPy kernels (tests/conftest.py)
def test_wittenbauer_tangents_give_the_flywheel_in_the_figure():
    """The two tangents drawn touch the diagram from above and below; the segment ab they cut on the energy
    axis over the difference of their slopes (omega_max^2/2 - omega_min^2/2, from the delta asked) is the
    constant inertia, and the exact cycle under a constant drive moment with that inertia has that delta."""
    mech = lw.compile("double-cut-shears")
    result = lw.dynamics(mech, steps=720)
    fig = figures.dynamics_diagrams(result)
    assert overlaps(fig) == []
    ax = next(a for a in fig.axes if any(line.get_gid() == "wittenbauer" for line in a.get_lines()))
    lines = {line.get_gid(): line.get_xydata() for line in ax.get_lines() if line.get_gid()}
    j, energy = lines["wittenbauer"].T
    scale = 1e-3 if "kJ" in ax.get_ylabel() else 1.0
    omega, delta = result.flywheel.omega_mean, 0.05
    slopes = {"max": 0.5 * (omega * (1 + delta / 2)) ** 2, "min": 0.5 * (omega * (1 - delta / 2)) ** 2}
    intercept = {}
    for key, sign in (("max", 1.0), ("min", -1.0)):
        (x0, y0), (x1, y1) = lines[f"tangent:{key}"]
        assert x0 == 0.0 and (y1 - y0) / (x1 - x0) == pytest.approx(slopes[key] * scale, rel=1e-12)
        gap = sign * (y0 + slopes[key] * scale * j - energy)  # the line minus the diagram, outward
        # it touches the diagram between the samples (the energy's extreme refined there): no sample beyond
        # it, the nearest within the sampling's reach (the diagram's change over a step, 3e-4 of its range)
        assert -1e-9 * np.ptp(energy) <= gap.min() <= 1e-3 * np.ptp(energy)
        intercept[key] = y0 / scale
    ab = lines["tangent:ab"][:, 1] / scale
    assert sorted(ab) == pytest.approx(sorted(intercept.values()), rel=1e-12)
    need = (intercept["max"] - intercept["min"]) / (slopes["max"] - slopes["min"])
    assert need == pytest.approx(result.flywheel.inertia, rel=1e-12)
    legend = " ".join(t.get_text() for t in ax.get_legend().get_texts())
    assert f"= {need:.5g} kg·m²" in legend
    _, exact = lw.machine.constant_moment_cycle(result.reduced, need, omega)
    assert exact == pytest.approx(delta, rel=2e-3)


@pytest.mark.slow  # over the default lane's budget on the NumPy kernels (tests/conftest.py)
def test_the_report_says_why_the_simulated_delta_differs(report):
    """Both deltas, the one asked for (the file's 0.05) and the simulation's (dynamics.json's), with the why."""
    page = report("double-cut-shears")
    section, rows = _section(page, "dynamics"), _rows(page, "dynamics")
    true = float(rows["δ of the simulated steady cycle"][1])
    assert rows["δ asked for (the flywheel sized for it by Wittenbauer's tangents)"][1] == "0.05"
    run = lw.dynamics("double-cut-shears")
    assert true == pytest.approx(run.delta, rel=1e-3) and abs(true - 0.05) > 1e-4
    assert f"Why the simulated δ = {run.delta:.4g} differs from the δ = 0.05 asked for" in section
    assert "approximate method" in section and "true δ" in section


def test_a_file_in_inches_is_reported_in_mm_and_says_so(tmp_path):
    """The four-bar with ``length: in``: its crank of 100 in is 2540 mm in the report, which says lengths are
    in mm whatever the file declares."""
    (tmp_path / "inch.yaml").write_text(text("four-bar").replace("length: mm", "length: in"))
    result = linkwork("analyze", "inch.yaml", "--out", "r", "--steps", "36", "--no-animation", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    page = (tmp_path / "r" / "report.html").read_text(encoding="utf-8")
    assert _rows(page, "input")["crank"][1] == "O2 (0, 0), A (2540, 0)"
    assert "Lengths in mm, angles in degrees" in _section(page, "input")
    assert "whatever units the file declares" in _section(page, "input")


def test_the_russian_input_section_writes_the_files_loads_and_machine_in_russian():
    """The double-cut shears' loads and machine as the file gives them, in Russian: the keys and units in
    Russian (кН, кВт, об/мин, кг·м², °), decimal commas, the values of a list apart by semicolons; the file's
    own names (cutting, knife_upper.edge) as they are; in English as the file writes them."""
    import re

    import linkwork as lw
    from linkwork.lang import t
    from linkwork.report.inputs import input_section

    class Run:
        def __init__(self, lang: str) -> None:
            self.lang = lang

        def t(self, key: str, **values: object) -> str:
            return t(key, self.lang, **values)

    mech = lw.compile(lw.example("double-cut-shears"))
    ru = " ".join(input_section(mech, 72, Run("ru").t)).split("<details>")[0]  # the file's own text apart
    for word in ("rpm", "kN", "kW", "deg", "kg*m^2", "power", "speed", "penetration", "process", "induction"):
        assert not re.search(rf"(?<![\w.]){re.escape(word)}(?![\w])", ru), word
    assert "относительное внедрение 0; 0,15; 0,3; 0,45" in ru
    assert "сила 0 кН; 250 кН; 250 кН; 0 кН" in ru and "ось 90°" in ru
    assert "мощность 5,5 кВт" in ru and "частота вращения 1450 об/мин" in ru and "0,03 кг·м²" in ru
    assert "cutting" in ru and "knife_upper.edge" in ru
    en = " ".join(input_section(mech, 72, Run("en").t))
    assert "penetration 0, 0.15, 0.3, 0.45" in en and "speed 1450 rpm" in en
