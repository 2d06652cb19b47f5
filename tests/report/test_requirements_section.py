"""The report of a synthesised file opens with its requirements and what the mechanism achieves, with the
limit positions drawn and theta marked (the figure, its DXF), in English and Russian."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

pytest.importorskip("matplotlib")

import linkwork as lw  # noqa: E402
from linkwork.report import build  # noqa: E402
from linkwork.scene.limits import limits_scene  # noqa: E402
from linkwork.synthesis import synthesize  # noqa: E402
from linkwork.synthesis.achieved import requirement_rows  # noqa: E402


@pytest.fixture(scope="module")
def slider_crank(tmp_path_factory):
    out = tmp_path_factory.mktemp("synth") / "sc.yaml"
    synthesize(
        "slider-crank", stroke="400 mm", time_ratio=1.3, max_pressure_angle="60 deg", min_transmission_angle="30 deg"
    ).write(out)
    return out


def test_the_file_carries_its_requirements_and_the_analysis_finds_each_met(slider_crank):
    spec = lw.load(str(slider_crank))
    kind, rows = requirement_rows(lw.kinematics(spec, steps=720), spec)
    assert kind == "slider-crank"
    got = {r.name: r for r in rows}
    assert got["stroke"].asked == pytest.approx(0.4, rel=1e-12)
    # the lengths written to 0.1 mm: within the tolerance the file states, which the rounding needs
    assert got["stroke"].achieved == pytest.approx(0.4, abs=got["stroke"].tolerance)
    assert got["stroke"].achieved != pytest.approx(0.4, rel=1e-6)
    assert got["time_ratio"].met and got["stroke"].met and got["max_pressure_angle"].met
    assert got["max_pressure_angle"].sense == "at most" and got["max_pressure_angle"].achieved < math.radians(60)


def test_theta_between_the_limit_positions_is_the_closed_forms():
    """theta = 180 deg (K - 1) / (K + 1), for a slider-crank and a crank-rocker: the angle of the scene's rays."""
    for kind, req, k in (
        ("slider-crank", {"stroke": 0.3, "max_pressure_angle": math.radians(70), "min_transmission_angle": 0.3}, 1.6),
        ("crank-rocker", {"swing": math.radians(40), "frame": 0.4}, 1.25),
    ):
        s = synthesize(kind, time_ratio=k, **req)
        scene = limits_scene(lw.kinematics(s.spec, steps=720))
        assert scene is not None
        # theta = pi (K - 1) / (K + 1) moves by 2 pi / (K + 1)^2 per K: the tolerance of K the rounding implies
        tol = 2 * math.pi / (k + 1) ** 2 * s.tolerances["time_ratio"]
        assert scene.theta == pytest.approx(math.pi * (k - 1) / (k + 1), abs=tol)
        (a, b) = (ray[1] - ray[0] for ray in scene.rays)
        between = math.acos(float(a @ b) / math.hypot(*a) / math.hypot(*b))
        assert between == pytest.approx(scene.theta, rel=1e-9)


@pytest.mark.parametrize(("lang", "title", "yes"), [("en", "Requirements", "yes"), ("ru", "Требования", "да")])
def test_the_report_opens_with_the_requirements_and_the_limit_positions(slider_crank, tmp_path, lang, title, yes):
    folder = tmp_path / "report"
    build.analyze(lw.compile(lw.load(str(slider_crank))), folder, steps=36, animation=False, lang=lang, dxf=True)
    text = (folder / "report.html").read_text()
    sections = re.findall(r"<h2[^>]*>(.*?)</h2>", text)
    assert sections[0] == title
    start = text.index("<section id='requirements'>")
    part = text[start : text.index("</section>", start)]
    assert part.count(f"<td>{yes}</td>") == 4  # stroke, time ratio, pressure angle, the transmission rule
    # 180 (1.3 - 1) / (1.3 + 1) = 23.4783 deg, within what the file's K tolerance allows: 2 pi / 2.3^2 tol_K; a
    # decimal comma in Russian
    shown = re.search(r"θ = (\S+)°", part).group(1)
    assert ("," in shown) == (lang == "ru")
    theta = float(shown.replace(",", "."))
    k_tol = float(lw.load(str(slider_crank)).requirements["time_ratio_tolerance"])
    assert abs(theta - 23.4783) <= math.degrees(2 * math.pi / 2.3**2 * k_tol) + 5e-4
    # the working member named by its kind (in Russian, the genitive of the limits' title), then as the file names it
    assert (
        "при крайних положениях ползуна на направляющей guide" if lang == "ru" else "with the slider on guide"
    ) in part
    if lang == "ru":  # no English but the names from the file (the kind is the mechanism's name)
        words = set(re.findall(r"[A-Za-z]{2,}", re.sub(r"<[^>]+>|data:[^'\"]+", " ", part)))
        assert words <= {"slider", "crank", "guide"}
    assert (folder / "figures" / "limits.svg").exists() and (folder / "figures" / "limits.dxf").exists()
    import ezdxf

    doc = ezdxf.readfile(folder / "figures" / "limits.dxf")
    assert len(doc.modelspace().query('LWPOLYLINE[layer=="LIMITS"]')) == 3  # the two rays of theta and its arc
    msp = doc.modelspace()
    stroke = [np.asarray(e.get_points("xy")) for e in msp.query('LWPOLYLINE[layer=="DIMENSIONS"]')]
    assert stroke  # the slider's stroke H dimensioned: its extension lines and dimension line
    texts = [e.dxf.text for e in msp.query("TEXT")] + [e.plain_text() for e in msp.query("MTEXT")]
    drawn = f"θ = {theta:.2f}°"
    drawn = drawn.replace(".", ",") if lang == "ru" else drawn  # a decimal comma in Russian
    assert any(drawn in text for text in texts), texts


def test_a_file_without_requirements_has_no_such_section():
    spec = lw.load("double-cut-shears")
    assert requirement_rows(lw.kinematics(spec, steps=72), spec) is None
