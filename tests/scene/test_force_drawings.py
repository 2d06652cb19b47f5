"""Force plans and Zhukovsky's lever drawn: read back from the figures and the DXF, against the data."""

from __future__ import annotations

import functools
import re

import numpy as np
import pytest

import linkwork as lw
from drawing_checks import overlaps
from linkwork.kinetostatics.force_polygons import force_plans
from linkwork.kinetostatics.zhukovsky import lever
from linkwork.scene.positions import position_angles

pytest.importorskip("matplotlib")

from linkwork.figures.force_plans import force_plans_figure, lever_figure, lever_sheet  # noqa: E402


@functools.cache
def _shears() -> tuple[lw.Kinematics, lw.Forces]:
    mech = lw.compile(lw.load("double-cut-shears"))
    kin = lw.kinematics(mech, position_angles(mech))
    return kin, lw.forces(kin)


def _scale(text: str) -> float:
    """μF (N/mm or Н/мм) read from a drawn text."""
    found = re.search(r"μF = ([0-9.e+]+)", text)
    assert found, text
    return float(found.group(1))


@pytest.mark.parametrize("lang", ["en", "ru"])
def test_each_groups_plan_draws_its_forces_head_to_tail_to_the_scale_in_its_title(lang):
    kin, f = _shears()
    plans = force_plans(f)
    fig = force_plans_figure(plans, 9, 9, lang)
    assert len(fig.axes) == 4  # the double-cut shears: four groups, the driving link last
    for ax, g in zip(fig.axes, plans.groups, strict=True):
        scale = _scale(ax.get_title())
        lines = {line.get_gid(): np.asarray(line.get_xydata()) for line in ax.lines if line.get_gid()}
        ends = []
        for p in g.polygon:
            if not np.any(p.vector[0, 9]):  # a force of no size (the cutting force before the cut): not drawn
                assert f"{p.kind}:{p.name(lang)}" not in lines
                continue
            xy = lines[f"{p.kind}:{p.name(lang)}"]
            assert np.hypot(*(xy[1] - xy[0])) * scale == pytest.approx(np.hypot(*p.vector[0, 9]), rel=1e-9)
            assert np.allclose((xy[1] - xy[0]) * scale, p.vector[0, 9], rtol=0, atol=1e-9 * scale)
            ends.append(xy)
        joins = [np.asarray(line.get_xydata()) for line in ax.lines if not line.get_gid()]
        for a, b in zip(ends, ends[1:] + ends[:1], strict=True):  # head to tail, and closed
            # or, where an arrow runs back over the one before it, beside it, a thin line joining each end to its
            # vertex (scene.force_plans.APART)
            meet = np.allclose(a[1], b[0], atol=1e-9)
            joined = [j for j in joins if len(j) == 2 and np.allclose(j[0], a[1], atol=1e-9)]
            assert meet or any(np.allclose(j[1], b[0], atol=1e-9) for j in joined), (a, b)
    assert overlaps(fig) == []


@pytest.mark.parametrize("lang", ["en", "ru"])
def test_the_lever_puts_each_force_at_its_points_turned_velocity_image(lang):
    kin, f = _shears()
    lv = lever(f)
    fig = lever_figure(lv, kin, 9, 9, lang)
    ax = fig.axes[0]
    # the Russian title writes decimal commas (0,005)
    mu_v = float(re.search(r"μv = ([0-9.,e+-]+)", ax.get_title()).group(1).replace(",", "."))
    lines = {line.get_gid(): np.asarray(line.get_xydata()) for line in ax.lines if line.get_gid()}
    v = kin.velocity("rod_DE.E")[9]  # the weight G5 of the upper knife acts at E (its centre of mass)
    g5 = lines["weight:G5"]
    assert np.allclose(g5[0] * mu_v, [-v[1], v[0]], rtol=0, atol=1e-12)  # v turned by +90 degrees
    assert g5[1][1] < g5[0][1] and np.isclose(g5[1][0], g5[0][0])  # pointing down
    name = "balancing:" + ("Fу" if lang == "ru" else "Fb")
    pin = kin.velocity("crank.A")[9]
    assert np.allclose(lines[name][0] * mu_v, [-pin[1], pin[0]], rtol=0, atol=1e-12)
    assert overlaps(fig) == []
    assert overlaps(lever_sheet(lv, kin, lang)) == []


@pytest.mark.parametrize("lang", ["en", "ru"])
def test_the_dxf_force_plans_are_the_forces_to_each_groups_scale(tmp_path, lang):
    ezdxf = pytest.importorskip("ezdxf")
    from linkwork.io.dxf_forces import write_force_plans, write_lever

    kin, f = _shears()
    plans = force_plans(f)
    doc = ezdxf.readfile(write_force_plans(plans, 9, tmp_path / "force_plans.dxf", lang))
    msp = doc.modelspace()
    notes = [e.dxf.text for e in msp.query("TEXT") if e.dxf.layer == "NOTES"]
    scales = [_scale(n) for n in notes if "μF" in n]
    assert len(scales) == 4
    assert any(("планы сил" if lang == "ru" else "force plans") in n for n in notes)
    by_name: dict[str, list[float]] = {}
    for line in msp.query("LINE"):
        if line.has_xdata("LINKWORK"):
            tag = line.get_xdata("LINKWORK")[0].value
            by_name.setdefault(tag, []).append(float(np.hypot(*(np.array(line.dxf.end) - line.dxf.start)[:2])))
    for g, scale in zip(plans.groups, scales, strict=True):
        for p in g.polygon:
            if not np.any(p.vector[0, 9]):
                continue
            drawn = by_name.pop(f"{p.kind}:{p.name(lang)}")[0] * scale
            assert drawn == pytest.approx(np.hypot(*p.vector[0, 9]), rel=1e-9, abs=1e-6)
    assert {"WEIGHTS", "INERTIA", "TANGENTIAL_R", "NORMAL_R", "REACTIONS", "KNOWN_REACTIONS"} <= {
        layer.dxf.name for layer in doc.layers
    }
    lever_doc = ezdxf.readfile(write_lever(lever(f), kin, 9, tmp_path / "lever.dxf", lang))
    assert any("Жуковского" in e.dxf.text or "Zhukovsky" in e.dxf.text for e in lever_doc.modelspace().query("TEXT"))


@pytest.mark.parametrize("lang", ["en", "ru"])
def test_the_sheet_of_a_groups_plans_draws_each_position_to_the_scale_above_it(lang):
    from linkwork.figures.force_plans import force_plan_sheet

    kin, f = _shears()
    plans = force_plans(f)
    g = plans.groups[2]  # II(2,3): R43 and R63 of the two groups taken before it
    fig = force_plan_sheet(plans, 2, lang)
    assert len(fig.axes) == 12
    for k, ax in enumerate(fig.axes):
        scale = _scale(ax.get_title())
        lines = {line.get_gid(): np.asarray(line.get_xydata()) for line in ax.lines if line.get_gid()}
        for p in g.polygon:
            if np.any(p.vector[0, k]):
                xy = lines[f"{p.kind}:{p.name(lang)}"]
                assert np.allclose((xy[1] - xy[0]) * scale, p.vector[0, k], rtol=0, atol=1e-9 * scale)
    assert overlaps(fig) == []


def test_a_dead_point_of_the_sheet_says_so_where_its_plan_would_be():
    """The slider-crank shears (rod as long as the crank, the guide through O): at crank 0 and 180 deg (positions
    9 and 3) B falls on O and the rod lies across the guide, so the rod's and the knife's reactions are
    indeterminate: those two cells carry the dead-point note and no arrow, every other cell its plan."""
    from linkwork.figures.force_plans import force_plan_sheet
    from linkwork.lang import t

    kin = lw.kinematics("shears-slider-crank", steps=12)
    plans = force_plans(lw.forces(kin))
    fig = force_plan_sheet(plans, len(plans.groups) - 1)
    note = t("forceplans.singular", "en")
    dead = {k for k, ax in enumerate(fig.axes) if note in ax.get_title()}
    assert dead == {3, 9}
    assert all(not [line for line in ax.lines if line.get_gid()] for k, ax in enumerate(fig.axes) if k in dead)
    assert all([line for line in ax.lines if line.get_gid()] for k, ax in enumerate(fig.axes) if k not in dead)


def test_a_short_arrow_is_named_under_the_plan_and_no_two_names_cover_each_other():
    """The double-cut shears under the cutting load (φ = 86.6°): weights and inertia forces of 5 to 3000 N
    beside reactions of 490 kN, a few tenths of a millimetre on the plans.  Every arrow shorter than the names'
    height carries no name beside it and is listed under its plan with its value (to 4 digits of the force the
    kinetostatics gives); every longer one is named beside it, no two names' boxes overlapping."""
    import itertools

    from linkwork.motion.analysis import zero_angle
    from linkwork.scene.force_plans import SHORT, force_plan_scene, short_note
    from linkwork.scene.geometry import text_size

    mech = lw.compile(lw.load("double-cut-shears"))
    one = lw.forces(lw.kinematics(mech, [zero_angle(mech) + np.radians(86.6)]))
    listed = 0
    for g in force_plans(one).groups:
        scene = force_plan_scene(g, 0, lang="en", em=3.5)
        note = short_note(scene, "en").replace("\u00a0", " ")
        sizes = {f.name("en"): float(np.hypot(*f.vector[0, 0])) for f in (*g.polygon, *g.reactions)}
        boxes = []
        for a in scene.arrows:
            length = float(np.hypot(*(a.end - a.start)))
            if length < SHORT * 3.5:
                assert not np.isfinite(a.centre).all(), a.text
                drawn = a.text.replace("Phi", "Φ")  # listed as its label draws it: Φ6
                found = re.search(rf"(?<![\w]){re.escape(drawn)} = ([\d.]+) N", note)
                assert found and float(found.group(1)) == pytest.approx(sizes[a.text], rel=6e-4), (a.text, note)
                listed += 1
            else:
                assert np.isfinite(a.centre).all(), a.text
                w, h = text_size(a.text, 3.5)
                boxes.append((a.text, a.centre - [w / 2, h / 2], a.centre + [w / 2, h / 2]))
        for (s, a0, a1), (u, b0, b1) in itertools.combinations(boxes, 2):
            assert (a1 <= b0).any() or (b1 <= a0).any(), (s, u)
    assert listed >= 10  # G and Φ of every link but the knives' cutting force


def test_every_force_of_the_lever_is_drawn_or_listed_under_it_with_its_value():
    """Under the cutting load the lever's inertia forces and weights (5 to 3000 N beside 250 kN) are too short to
    draw at the lever's force scale: each is listed under the lever with its value, none is lost."""
    from linkwork.kinetostatics.zhukovsky import lever
    from linkwork.motion.analysis import zero_angle
    from linkwork.motion.plans import plan_series
    from linkwork.scene.force_plans import lever_scene, short_note

    mech = lw.compile(lw.load("double-cut-shears"))
    one = lw.forces(lw.kinematics(mech, [zero_angle(mech) + np.radians(86.6)]))
    lv = lever(one)
    scene = lever_scene(lv, plan_series(one.kinematics)[0], 0, lang="ru")
    drawn = {a.text for a in scene.arrows}
    left = dict(scene.left_out)
    note = short_note(scene, "ru").replace("\u00a0", " ")
    for lf in lv.forces:
        name, size = lf.force.name("ru"), float(np.hypot(*lf.force.vector[0, 0]))
        if size > 0:
            assert (name in drawn) != (name in left), name
        if name in left:
            assert left[name] == pytest.approx(size, rel=1e-12)
            assert f"{name} = {size:.4g} Н".replace(".", ",") in note
    assert any(name.startswith("Φ") for name in left)
