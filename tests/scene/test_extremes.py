"""The extremes of the working member on the plan of positions and the limit positions, read back from the drawn
figures: the crank's turns over the working and idle strokes against the closed forms of an offset slider-crank
(phi_w = 180 deg + theta, theta = asin(e / (l - r)) - asin(e / (l + r))), the letters at the points where a dense
search of the cycle finds the extremes, the stroke H = sqrt((l + r)^2 - e^2) - sqrt((l - r)^2 - e^2) dimensioned,
decimal commas in Russian, and no text on another or cut off."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import linkwork as lw
from drawing_checks import drawn_texts, overlaps
from linkwork.scene.positions import position_angles
from linkwork.structure.model import PairType

pytest.importorskip("matplotlib")

from linkwork import figures  # noqa: E402

#: An offset slider-crank: crank r, rod l, the guide e below the crank's pivot (m).
R, L, E = 0.1, 0.3, 0.05

OFFSET = f"""
name: offset-slider-crank
units: {{length: m, mass: kg, angle: deg}}
frame:
  points: {{O: [0, 0], G: [0, {-E}]}}
links:
  crank: {{ends: [O, A], length: {R}, mass: 1}}
  rod: {{ends: [A, B], length: {L}, mass: 1}}
  block: {{points: {{B: [0, 0]}}, mass: 1, inertia: 0}}
joints:
  O: {{type: revolute, links: [frame, crank]}}
  A: {{type: revolute, links: [crank, rod]}}
  B: {{type: revolute, links: [rod, block]}}
  guide: {{type: prismatic, links: [frame, block], point: B, through: G, axis: 0 deg}}
drives:
  - {{joint: O, speed: 10 rad/s, direction: ccw, angle: 0 deg}}
hints:
  B: [0.38, {-E}]
"""

#: The closed forms of the offset slider-crank: the angle between the crank's limit positions and the stroke.
THETA = math.degrees(math.asin(E / (L - R)) - math.asin(E / (L + R)))
STROKE = math.sqrt((L + R) ** 2 - E**2) - math.sqrt((L - R) ** 2 - E**2)


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    """The offset slider-crank (a quick return: theta = 7.30 deg, H = 203.2 mm) over a whole turn."""
    path = tmp_path_factory.mktemp("offset") / "offset.yaml"
    path.write_text(OFFSET, encoding="utf-8")
    return lw.kinematics(str(path), steps=360)


def _texts(fig):
    """Every drawn text: (text without mathtext's markup, its centre in display pixels)."""
    out = []
    texts = drawn_texts(fig)  # draws it on an Agg canvas
    renderer = fig.canvas.get_renderer()
    for text in texts:
        box = text.get_window_extent(renderer)
        plain = re.sub(r"\$_\{\\mathregular\{(.*?)\}\}\$", r"_\1", text.get_text())
        out.append((plain, np.array([(box.x0 + box.x1) / 2, (box.y0 + box.y1) / 2])))
    return out


def _extremes(kin):
    """The slider's point (index) and the samples of a dense turn at its two ends along its guide, found by brute
    force (the ends of its positions along the line of the stroke), the one of position 0 first."""
    mech = kin.mechanism
    p = next(int(mech.pair_points[k, 1]) for k in range(mech.n_pairs) if mech.pair_type[k] != PairType.REVOLUTE)
    dense = lw.kinematics(mech, steps=720)
    xy = dense.points()[:, p]
    u = xy[np.argmax(np.hypot(*(xy - xy[0]).T))] - xy[0]  # along the line of the stroke
    s = xy @ (u / np.hypot(*u))
    ends = [int(np.argmax(s)), int(np.argmin(s))]
    zero = lw.kinematics(mech, position_angles(mech)[:1]).points()[0, p]  # position 0 is the high end
    if np.hypot(*(xy[ends[0]] - zero)) > np.hypot(*(xy[ends[1]] - zero)):
        ends.reverse()
    return p, dense, ends


def test_positions_mark_the_strokes_angles_and_letter_the_extremes(quick):
    """phi_w = 180 + theta and phi_i = 180 - theta of the offset slider-crank (the slower stroke works), read back
    from the figure; A', A'', B', B'' drawn at the points a dense search puts at the extremes; nothing overlaps."""
    kin = quick
    fig = figures.draw_positions(kin, lang="en")
    texts = _texts(fig)
    values = {m.group(1): float(m.group(2)) for s, _ in texts if (m := re.fullmatch(r"φ_(w|i) = ([\d.]+)°", s))}
    assert values["w"] == pytest.approx(180.0 + THETA, abs=0.051)  # printed to 0.1 deg
    assert values["i"] == pytest.approx(180.0 - THETA, abs=0.051)
    assert values["w"] + values["i"] == pytest.approx(360.0, abs=0.11)
    assert overlaps(fig) == []
    # the letters beside the points of the extremes (within 3 ems of the text, in display pixels)
    p, dense, (high, low) = _extremes(kin)
    to_px = fig.axes[0].transData.transform
    em = 3 * fig.axes[0].texts[0].get_fontsize() * fig.dpi / 72
    found = {s: c for s, c in texts}
    name = kin.mechanism.point_names[p].split(".", 1)[1]
    for mark, sample in (("′", high), ("″", low)):
        at = to_px(dense.points()[sample, p])
        assert np.hypot(*(found[f"{name}{mark}"] - at)) < em, (mark, found[f"{name}{mark}"], at)


def test_the_russian_positions_write_decimal_commas_and_keep_their_title_on_the_figure():
    """The shears' slider-crank in Russian: its subtitle fits the figure (it was cut at both sides), its angles
    with a decimal comma (φ_р.х, φ_х.х, the crank's angle of position 0)."""
    kin = lw.kinematics("shears-slider-crank", steps=360)
    fig = figures.draw_positions(kin, lang="ru")
    texts = [s for s, _ in _texts(fig)]
    title = fig.axes[0].title
    box = title.get_window_extent(fig.canvas.get_renderer())
    assert box.x0 >= 0 and box.x1 <= fig.bbox.x1
    assert re.search(r"угле кривошипа \d+,\d°", title.get_text())
    assert any(re.fullmatch(r"φ_р\.х = \d+,\d°", s) for s in texts), texts
    assert any(re.fullmatch(r"φ_х\.х = \d+,\d°", s) for s in texts), texts


@pytest.mark.parametrize("lang", ["en", "ru"])
def test_limits_dimension_the_stroke_and_letter_the_extremes(quick, lang):
    """H read back from the drawing's text is the closed form's stroke, its dimension line as
    long as the distance between the slider's two extremes and along it; B', B'', A', A'' drawn; nothing
    overlaps."""
    kin = quick
    fig = figures.draw_limits(kin, lang=lang)
    texts = _texts(fig)
    unit, comma = ("mm", ".") if lang == "en" else ("мм", ",")
    stroke = [m for s, _ in texts if (m := re.fullmatch(rf"H = (\d+)\{comma}(\d) {unit}", s))]
    assert len(stroke) == 1
    h = float(f"{stroke[0].group(1)}.{stroke[0].group(2)}")
    assert h == pytest.approx(1000 * STROKE, abs=0.051)
    assert any(re.fullmatch(rf"θ = \d+\{comma}\d\d°", s) for s, _ in texts)
    lines = [a for a in fig.axes[0].get_children() if getattr(a, "get_gid", lambda: None)() == "limits:dimension"]
    assert len(lines) == 3  # two extension lines, then the dimension line
    a, b = (np.array(v) for v in zip(*lines[-1].get_data(), strict=True))
    p, dense, (high, low) = _extremes(kin)
    ends = dense.points()[[high, low], p]
    assert np.hypot(*(b - a)) == pytest.approx(np.hypot(*(ends[1] - ends[0])), rel=1e-4)
    (dx, dy), (ex, ey) = b - a, ends[1] - ends[0]
    assert abs(dx * ey - dy * ex) < 1e-6 * np.hypot(dx, dy) ** 2  # along the stroke
    name = kin.mechanism.point_names[p].split(".", 1)[1]
    assert {f"{name}′", f"{name}″"} <= {s for s, _ in texts}
    assert overlaps(fig) == []


@pytest.mark.parametrize(
    ("lang", "words"),
    [("ru", "крайние положения ползуна на направляющей guide"), ("en", "limit positions of the slider on guide")],
)
def test_the_limits_title_names_the_working_member_by_its_kind_and_its_own_name(quick, lang, words):
    """The title says what the working member is in the drawing's language (a slider on its guide), then the
    guide's name as the file writes it; never a bare name where the program's word belongs."""
    fig = figures.draw_limits(quick, lang=lang)
    title = fig.axes[0].get_title()
    assert title.startswith(f"offset-slider-crank: {words}\n"), title


#: The four-bar example (mm): frame O2O4, crank, coupler, rocker.  Its rocker's extremes are where the crank and the
#: coupler lie on one line: O2B = coupler + crank or coupler - crank, and the rocker's angle at O4 follows from the
#: triangle O2 O4 B by the law of cosines.
FRAME, CRANK, COUPLER, ROCKER = 300.0, 100.0, 350.0, 250.0


def _at_o4(d: float) -> float:
    return math.degrees(math.acos((FRAME**2 + ROCKER**2 - d**2) / (2 * FRAME * ROCKER)))


PSI_FOUR_BAR = _at_o4(COUPLER + CRANK) - _at_o4(COUPLER - CRANK)  # 56.34 deg


def _swing_by_brute_force(mech, pivot: str, far: str) -> float:
    """The rocker's swing (deg): the direction pivot -> far over a dense turn, unwrapped, its range."""
    dense = lw.kinematics(mech, steps=3600)
    names = [n.split(".", 1)[1] for n in mech.point_names]
    d = dense.points()[:, names.index(far)] - dense.points()[:, names.index(pivot)]
    angle = np.unwrap(np.arctan2(d[:, 1], d[:, 0]))
    return math.degrees(float(np.ptp(angle)))


def _psi(texts, comma):
    found = [m for s in texts if (m := re.fullmatch(rf"ψ = (\d+)\{comma}(\d)°", s))]
    assert len(found) == 1, texts
    return float(f"{found[0].group(1)}.{found[0].group(2)}")


@pytest.mark.parametrize("lang", ["en", "ru"])
@pytest.mark.parametrize(("example", "pivot", "far"), [("four-bar", "O4", "B"), ("double-cut-shears", "O3", "B")])
def test_limits_dimension_a_rockers_swing_in_the_figure_and_the_dxf(tmp_path, example, pivot, far, lang):
    """ψ read back from the figure's text and from the DXF's DIMENSIONS layer (its text and the angle its arc
    turns through about the rocker's pivot) is the rocker's swing: the four-bar's closed form, and for the
    shears (whose working member is a knife: H is dimensioned too) the range of the rocker's direction over a
    dense turn; the arc's ends lie on the rocker's lines at its two extremes; nothing overlaps."""
    ezdxf = pytest.importorskip("ezdxf")
    from linkwork.io.dxf import write_limits
    from linkwork.scene.limits import limits_scene

    kin = lw.kinematics(example, steps=360)
    mech = kin.mechanism
    swing = PSI_FOUR_BAR if example == "four-bar" else _swing_by_brute_force(mech, pivot, far)
    if example == "four-bar":
        assert _swing_by_brute_force(mech, pivot, far) == pytest.approx(swing, abs=0.01)
    comma = "." if lang == "en" else ","
    fig = figures.draw_limits(kin, lang=lang)
    texts = [s for s, _ in _texts(fig)]
    assert _psi(texts, comma) == pytest.approx(swing, abs=0.051)
    assert (example == "double-cut-shears") == any(s.startswith("H = ") for s in texts)
    assert overlaps(fig) == []

    path = write_limits(limits_scene(kin, lang), tmp_path / "limits.dxf", lang)
    msp = ezdxf.readfile(path).modelspace()
    words = [e.plain_text().replace("\u00a0", " ") for e in msp.query("MTEXT")]
    assert _psi(words, comma) == pytest.approx(swing, abs=0.051)
    arcs = [np.array(e.get_points("xy")) for e in msp.query("LWPOLYLINE[layer=='DIMENSIONS']") if len(e) > 2]
    assert len(arcs) == 1
    names = [n.split(".", 1)[1] for n in mech.point_names]
    o = 1000 * lw.kinematics(mech, kin.angles[:1]).points()[0, names.index(pivot)]
    d = arcs[0] - o
    turned = np.diff(np.unwrap(np.arctan2(d[:, 1], d[:, 0])))
    assert math.degrees(abs(float(turned.sum()))) == pytest.approx(swing, abs=0.01)
    assert np.ptp(np.hypot(d[:, 0], d[:, 1])) < 1e-6 * np.hypot(*d[0])  # an arc about the pivot
    # its ends on the rocker's lines at the two extremes: the far joint's directions at the swing's ends
    dense = lw.kinematics(mech, steps=3600)
    e = dense.points()[:, names.index(far)] - dense.points()[:, names.index(pivot)]
    angle = np.unwrap(np.arctan2(e[:, 1], e[:, 0]))
    drawn = [math.atan2(v[1], v[0]) for v in (d[0], d[-1])]
    for extreme in (angle.min(), angle.max()):
        off = min(abs((a - extreme + math.pi) % (2 * math.pi) - math.pi) for a in drawn)
        assert math.degrees(off) < 0.05
