"""Structural analysis: DOF, redundant constraints, Assur groups, assembly."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import linkwork as lw
from linkwork.errors import StructureError, UnassemblableError
from linkwork.examples import names
from linkwork.structure.constraints import residuals_and_jacobian
from linkwork.structure.model import PairType, global_points
from mechanisms import (
    TEXTBOOK,
    circle_intersection,
    four_bar_spec,
    four_bars,
    hydraulic_boom,
    parallelogram_with_redundant_link,
)


@pytest.mark.parametrize("name", sorted(TEXTBOOK))
def test_textbook_mechanism_structure(name):
    factory, n, p5, p4, w, redundant, groups = TEXTBOOK[name]
    mech = lw.compile(factory().build())
    s = mech.structure
    assert (s.n_links, s.p5, s.p4, s.dof, s.redundant) == (n, p5, p4, w, redundant)
    assert s.dof == 3 * s.n_links - 2 * s.p5 - s.p4
    assert s.mobility == mech.n_drives
    got = [
        (g.klass, g.order, g.kind if kind is not None else None)
        for g, (_, _, kind) in zip(s.groups, groups, strict=False)
    ]
    assert got == groups
    # every link is placed exactly once, the frame never
    placed = [i for g in s.groups for i in g.links]
    assert sorted(placed) == list(range(1, mech.n_links_total))


# The structures the papers and textbooks give for the bundled examples.
EXAMPLES = {
    "double-cut-shears": (7, 10, 1, "I(0,1) -> II(2,3) -> II(4,5) -> II(6,7)", ["R", "RRR", "RRP", "RRP"]),
    "shears-slider-crank": (3, 4, 1, "I(0,1) -> II(2,3)", ["R", "RRP"]),
    "percussion-rocker": (3, 4, 1, "I(0,1) -> II(2,3)", ["R", "RRR"]),
    "four-bar": (3, 4, 1, "I(0,1) -> II(2,3)", ["R", "RRR"]),
    "watt-six-bar": (5, 7, 1, "I(0,1) -> II(2,3) -> II(4,5)", ["R", "RRR", "RRR"]),
    "stephenson-six-bar": (5, 7, 1, "I(0,1) -> II(2,3) -> II(4,5)", ["R", "RRR", "RRR"]),
    "class3-triad": (5, 7, 1, "I(0,1) -> III(2,3,4,5)", ["R", None]),
}


def test_every_example_is_covered():
    from linkwork.examples import names

    assert sorted(EXAMPLES) == names()


@pytest.mark.parametrize("name", sorted(EXAMPLES))
def test_example_structure(name):
    n, p5, w, formula, kinds = EXAMPLES[name]
    s = lw.compile(lw.example(name)).structure
    assert (s.n_links, s.p5, s.p4, s.dof, s.redundant) == (n, p5, 0, w, 0)
    assert s.formula == formula
    assert [g.kind if k is not None else None for g, k in zip(s.groups, kinds, strict=False)] == kinds
    assert s.warnings == ()


def test_double_cut_shears_groups_follow_the_paper():
    """Seed 002: B from A and O3 (eq. 3), E from D and the guide (eq. 4), F from C and the guide (eq. 5)."""
    s = lw.compile(lw.example("double-cut-shears")).structure
    assert [set(g.joints) for g in s.groups] == [{"O1"}, {"A", "B", "O3"}, {"D", "E", "guide_E"}, {"C", "F", "guide_F"}]
    assert [g.internal for g in s.groups] == [(), ("B",), ("E",), ("F",)]


def test_triad_is_class_three_of_order_three():
    g = lw.compile(lw.example("class3-triad")).structure.groups[1]
    assert (g.klass, g.order, len(g.links)) == (3, 3, 4)
    assert set(g.internal) == {"B", "C", "D"}


def test_class_four_group_has_a_closed_contour_of_four_pairs():
    g = lw.compile(TEXTBOOK["class IV"][0]().build()).structure.groups[1]
    assert (g.klass, g.order) == (4, 2)
    assert set(g.internal) == {"B", "C", "D", "E"}


def test_redundant_link_found_from_geometry_not_counting():
    """A parallel third crank moves with the parallelogram (q = 1); a slightly longer one locks it."""
    mech = lw.compile(parallelogram_with_redundant_link().build())
    assert (mech.structure.dof, mech.structure.redundant, mech.structure.mobility) == (0, 1, 1)
    builder = parallelogram_with_redundant_link()
    builder.link("extra", ends=("O6", "C"), length=0.101)
    with pytest.raises(StructureError, match="rigid structure"):
        lw.compile(builder.build())


def test_linear_actuator_drive_makes_one_driving_group():
    s = lw.compile(hydraulic_boom().build()).structure
    assert s.dof == 1
    assert [(g.klass, g.links, g.driven) for g in s.groups] == [(1, (1, 2, 3), True)]


MECHANISMS = [("example", n) for n in sorted(EXAMPLES)] + [("textbook", n) for n in sorted(TEXTBOOK)]


def _mech(kind, name):
    return lw.compile(lw.example(name) if kind == "example" else TEXTBOOK[name][0]().build())


@pytest.mark.parametrize("kind, name", MECHANISMS)
def test_jacobian_matches_finite_differences(kind, name):
    mech = _mech(kind, name)
    rng = np.random.default_rng(1)
    q = mech.pose0 + rng.normal(scale=0.05, size=mech.pose0.shape)
    q[0] = 0
    _, jac = residuals_and_jacobian(q, mech)
    h = 1e-6
    fd = np.zeros_like(jac)
    for j in range(q.size):
        dq = np.zeros(q.size)
        dq[j] = h
        rp, _ = residuals_and_jacobian(q + dq.reshape(q.shape), mech)
        rm, _ = residuals_and_jacobian(q - dq.reshape(q.shape), mech)
        fd[:, j] = (rp - rm) / (2 * h)
    np.testing.assert_allclose(jac, fd, atol=1e-7)


@pytest.mark.parametrize("kind, name", MECHANISMS)
def test_assembly_closes_every_pair(kind, name):
    """Loop closure checked geometrically, independently of the residual function."""
    mech = _mech(kind, name)
    pts = mech.points0()
    for k in range(mech.n_pairs):
        a, b = mech.pair_links[k]
        if mech.pair_type[k] == PairType.REVOLUTE:
            pa, pb = pts[mech.pair_points[k]]
            assert np.hypot(*(pa - pb)) < 1e-9
        else:
            assert mech.pair_type[k] == PairType.PRISMATIC
            assert abs(mech.pose0[b, 2] - mech.pose0[a, 2]) % (2 * math.pi) < 1e-9
            th = mech.pose0[a, 2]
            rot = np.array([[math.cos(th), -math.sin(th)], [math.sin(th), math.cos(th)]])
            origin = mech.pose0[a, :2] + rot @ mech.pair_origin[k]
            u = rot @ mech.pair_axis[k]
            d = pts[mech.pair_points[k, 1]] - origin
            assert abs(u[0] * d[1] - u[1] * d[0]) < 1e-9
    # link dimensions are kept: distances between points of one link equal the local ones
    for i in range(mech.n_links_total):
        idx = np.flatnonzero(mech.point_link == i)
        for a in idx:
            for b in idx:
                assert np.hypot(*(pts[a] - pts[b])) == pytest.approx(
                    np.hypot(*(mech.point_local[a] - mech.point_local[b])), abs=1e-9
                )


def test_double_cut_shears_assembly_by_circle_construction():
    mech = lw.compile(lw.example("double-cut-shears"))
    pts = dict(zip(mech.point_names, mech.points0(), strict=False))
    a = (0.6, 0.4)  # crank angle 0
    b = circle_intersection(a, 0.4, (0.0, 0.0), 0.5, left=True)  # the branch near (0.5, 0)
    assert abs(b[1]) < 0.1
    np.testing.assert_allclose(pts["rocker.B"], b, atol=1e-12)
    psi = math.atan2(b[1], b[0])
    d = (-0.3 * math.cos(psi), -0.3 * math.sin(psi))
    c = (0.3 * math.cos(psi), 0.3 * math.sin(psi))
    np.testing.assert_allclose(pts["knife_upper.E"], (0, d[1] + math.sqrt(0.35**2 - d[0] ** 2)), atol=1e-12)
    np.testing.assert_allclose(pts["knife_lower.F"], (0, c[1] - math.sqrt(0.35**2 - c[0] ** 2)), atol=1e-12)
    np.testing.assert_allclose(pts["knife_upper.edge"][1], pts["knife_upper.E"][1] - 0.135, atol=1e-12)


def test_percussion_rocker_is_assembled_in_the_pose_of_impact():
    mech = lw.compile(lw.example("percussion-rocker"))
    pts = dict(zip(mech.point_names, mech.points0(), strict=False))
    np.testing.assert_allclose(pts["rocker.N"], (0.10, 0.02), atol=1e-9)
    np.testing.assert_allclose(pts["rocker.K"], (0.30, -0.02), atol=1e-9)
    # J about O = 0.30 kg m^2 given; about the centre of mass by the parallel-axis theorem
    rocker = mech.link_names.index("rocker")
    assert mech.link_inertia[rocker] == pytest.approx(0.30 - 6.0 * (0.16**2 + 0.01**2), rel=1e-12)


def test_slider_crank_shears_assembly():
    mech = lw.compile(lw.example("shears-slider-crank"))
    pts = dict(zip(mech.point_names, mech.points0(), strict=False))
    np.testing.assert_allclose(pts["knife.B"], (0, 2 * 0.15 * math.sin(math.pi / 2)), atol=1e-12)
    crank = mech.link_names.index("crank")
    assert mech.link_inertia[crank] == pytest.approx(10 * 0.15**2 / 12)


def test_rrp_dyad_that_cannot_reach_its_guide_says_why():
    b = TEXTBOOK["offset slider-crank"][0]()
    b.link("rod", ends=("A", "B"), length=10)  # mm
    spec = b.to_dict()
    spec["drives"][0]["angle"] = -90  # A = (0, -100) mm: 150 mm below the guide y = 50 mm
    with pytest.raises(UnassemblableError, match=r"the joint A is 0\.15 m from the line .* more than the 0\.01 m"):
        lw.compile(lw.from_dict(spec))


@settings(max_examples=40, deadline=None)
@given(four_bars, st.floats(-2, 2), st.floats(-2, 2), st.floats(-math.pi, math.pi))
def test_random_four_bars_assemble_on_the_hinted_branch_whatever_the_frame(dims, dx, dy, rot):
    a, b, c, d, phi, left = dims
    data, pb = four_bar_spec(a, b, c, d, phi, left, (dx, dy, rot))
    mech = lw.compile(lw.from_dict(data))
    s = mech.structure
    assert (s.dof, s.redundant, s.formula) == (1, 0, "I(0,1) -> II(2,3)")
    np.testing.assert_allclose(mech.points0()[mech.point_names.index("rocker.B")], pb, atol=1e-8)


def test_units_do_not_change_the_compiled_model():
    """The four-bar example in mm, kg and deg equals the same file rewritten in m, g and rad."""
    from linkwork.examples import text as example_text

    swaps = [
        ("units: {length: mm, mass: kg, angle: deg}", "units: {length: m, mass: g, angle: rad}"),
        ("length: 100", "length: 0.1"),
        ("length: 350", "length: 0.35"),
        ("length: 250", "length: 0.25"),
        ("[300, 0]", "[0.3, 0]"),
        ("[175, 80]", "[0.175, 0.08]"),
        ("[330, 240]", "[0.33, 0.24]"),
        ("mass: 1.0", "mass: 1000"),
        ("mass: 2.5", "mass: 2500"),
        ("mass: 1.8", "mass: 1800"),
        ("angle: 60 deg", f"angle: {math.pi / 3!r}"),
    ]
    text = example_text("four-bar")
    for old, new in swaps:
        assert old in text
        text = text.replace(old, new)
    mm, si = lw.compile(lw.example("four-bar")), lw.compile(lw.loads(text))
    for field in ("point_local", "link_mass", "link_inertia", "link_com", "pose0", "drive_speed", "drive_start"):
        np.testing.assert_allclose(getattr(si, field), getattr(mm, field), rtol=1e-12, atol=1e-15, err_msg=field)


def test_arrays_are_frozen():
    mech = lw.compile(lw.example("four-bar"))
    with pytest.raises(ValueError):
        mech.point_local[0, 0] = 1.0
    with pytest.raises(AttributeError):
        mech.name = "x"


def test_global_points_broadcast_over_batches():
    mech = lw.compile(lw.example("double-cut-shears"))
    q = np.stack([mech.pose0, mech.pose0 + 0.1])
    batch = global_points(q, mech.point_link, mech.point_local)
    assert batch.shape == (2, len(mech.point_names), 2)
    np.testing.assert_allclose(batch[0], mech.points0())


def test_assembly_at_a_dead_point_is_reported():
    """Non-Grashof four-bar a, b, c, d = 0.1, 0.2, 0.15, 0.3 at its limit angle, where coupler and
    rocker are stretched in line: cos(phi) = (a^2 + d^2 - (b + c)^2) / (2 a d) by the cosine law."""
    a, b, c, d = 0.1, 0.2, 0.15, 0.3
    phi = math.acos((a * a + d * d - (b + c) ** 2) / (2 * a * d))
    pa = (a * math.cos(phi), a * math.sin(phi))
    pb = (pa[0] + b / (b + c) * (d - pa[0]), pa[1] * (1 - b / (b + c)))
    data, _ = four_bar_spec(a, 0.35, 0.25, d, phi, False)
    data["links"]["coupler"]["length"], data["links"]["rocker"]["length"] = b, c
    data["hints"] = {"B": [pb[0], pb[1] + 0.01]}
    mech = lw.compile(lw.from_dict(data))
    assert mech.structure.redundant == 0
    assert any("singular position (dead point)" in w for w in mech.structure.warnings)
    np.testing.assert_allclose(mech.points0()[mech.point_names.index("rocker.B")], pb, atol=1e-6)
    data["drives"][0]["angle"] = phi - 0.3  # away from it: no such warning
    assert not any("dead point" in w for w in lw.compile(lw.from_dict(data)).structure.warnings)


def test_compound_hinge_structure_does_not_depend_on_the_listed_order():
    from mechanisms import compound_hinge

    for order in (("coupler", "rocker", "rod"), ("rod", "coupler", "rocker"), ("rocker", "rod", "coupler")):
        b = compound_hinge()
        b.revolute("B", *order)
        s = lw.compile(b.build()).structure
        assert s.formula == "I(0,1) -> II(2,3) -> II(4,5)"
        assert [g.kind for g in s.groups] == ["R", "RRR", "RRP"]


def test_a_repeated_pair_is_redundant_not_a_bigger_group():
    data, _ = four_bar_spec(0.1, 0.35, 0.25, 0.3, 1.0, False)
    data["joints"]["A2"] = {"type": "revolute", "links": ["coupler", "crank"], "point": "A"}
    s = lw.compile(lw.from_dict(data)).structure
    assert (s.dof, s.redundant, s.mobility) == (-1, 2, 1)
    assert [(g.klass, g.kind) for g in s.groups] == [(1, "R"), (2, "RRR")]
    assert s.groups[1].redundant == 2


def test_a_link_may_be_named_like_a_slot_block():
    from mechanisms import pin_in_slot

    b = pin_in_slot()
    data = b.to_dict()
    data["links"]["slot_block"] = {"ends": ["T", "Q"], "length": 0.2}
    data["joints"]["T"] = {"type": "revolute", "links": ["rocker", "slot_block"]}
    data["links"]["slider"] = {"points": {"Q": [0, 0]}}
    data["joints"]["Q"] = {"type": "revolute", "links": ["slot_block", "slider"]}
    data["frame"]["points"]["G"] = [0, 0.6]
    data["joints"]["guide"] = {
        "type": "prismatic",
        "links": ["frame", "slider"],
        "point": "Q",
        "through": "G",
        "axis": 0,
    }
    data["hints"]["Q"] = [0.1, 0.6]
    s = lw.compile(lw.from_dict(data)).structure
    assert s.formula == "I(0,1) -> II(2,5) -> II(3,4)"


def test_rrr_dyad_whose_links_differ_by_more_than_the_distance_of_its_joints_says_why():
    # crank 100 mm at 60 deg: A = (50, 86.6) mm, 264.6 mm from O4 = (300, 0); coupler 50 mm and rocker 500 mm
    # cannot meet: their difference, 450 mm, is more than that
    data = {
        "units": {"length": "mm", "angle": "deg"},
        "frame": {"points": {"O2": [0, 0], "O4": [300, 0]}},
        "links": {
            "crank": {"ends": ["O2", "A"], "length": 100},
            "coupler": {"ends": ["A", "B"], "length": 50},
            "rocker": {"ends": ["O4", "B"], "length": 500},
        },
        "joints": {
            "O2": {"type": "revolute", "links": ["frame", "crank"]},
            "A": {"type": "revolute", "links": ["crank", "coupler"]},
            "B": {"type": "revolute", "links": ["coupler", "rocker"]},
            "O4": {"type": "revolute", "links": ["frame", "rocker"]},
        },
        "drives": [{"joint": "O2", "speed": "60 rpm", "angle": 60}],
        "hints": {"B": [330, 240]},
    }
    d = math.hypot(300 - 100 * math.cos(math.radians(60)), 100 * math.sin(math.radians(60))) / 1000
    with pytest.raises(
        UnassemblableError, match=rf"the joints A and O4 are {d:.4g} m apart, less than the difference 0\.45 m"
    ):
        lw.compile(lw.from_dict(data))


def test_the_least_squares_of_the_assembly_find_the_intersection_of_two_circles():
    """A point at r1 from c1 and r2 from c2: the closed form to the last bits from a guess on the left; two
    circles apart leave the gap d - r1 - r2 split on the line of centres, the least residual there is."""
    from linkwork.structure.assemble import least_squares

    c1, c2 = np.array([0.0, 0.0]), np.array([0.7, 0.2])

    def solve(r1, r2, guess):
        def fun(x):
            return np.array([np.hypot(*(x - c1)) - r1, np.hypot(*(x - c2)) - r2])

        def jac(x):
            return np.array([(x - c1) / np.hypot(*(x - c1)), (x - c2) / np.hypot(*(x - c2))])

        return least_squares(fun, jac, np.array(guess)), fun

    x, _ = solve(0.5, 0.4, [0.2, 0.5])
    np.testing.assert_allclose(x, circle_intersection(c1, 0.5, c2, 0.4, left=True), rtol=0, atol=1e-15)
    x, fun = solve(0.3, 0.2, [0.3, 0.3])
    d = math.hypot(*c2)
    assert abs(fun(x)).sum() == pytest.approx(d - 0.5, rel=1e-12)  # the gap, shared by the two residuals
    u = (c2 - c1) / d
    assert abs(u[0] * x[1] - u[1] * x[0]) < 1e-7  # on the line of the centres (flat across it: slowly)


def test_the_assembly_pose_is_minpacks_to_the_rounding():
    """The assembly of every bundled example, solved group by group, is the pose scipy's MINPACK
    Levenberg-Marquardt (all tolerances 1e-15) finds from the same guesses, to 2e-15 m (rad)."""
    from scipy.optimize import least_squares as minpack

    import linkwork.structure.assemble as assemble
    from linkwork.examples import names

    def scipy_ls(fun, jac, x0, steps=400):
        return minpack(fun, x0, jac=jac, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=400).x

    for name in names():
        ours = lw.compile(lw.example(name)).pose0
        with pytest.MonkeyPatch.context() as m:
            m.setattr(assemble, "least_squares", scipy_ls)
            theirs = lw.compile(lw.example(name)).pose0
        np.testing.assert_allclose(ours, theirs, rtol=0, atol=2e-15, err_msg=name)


# --- the compile boundary: the model keeps its document as plain data, and no object of the file format --------


def _objects(value, seen=None):
    """Every object reachable from ``value`` through dataclass fields, named tuples, tuples, lists and dicts."""
    import dataclasses

    seen = set() if seen is None else seen
    if id(value) in seen:
        return
    seen.add(id(value))
    yield value
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        children = [getattr(value, f.name) for f in dataclasses.fields(value)]
    elif isinstance(value, dict):
        children = [*value.keys(), *value.values()]
    elif isinstance(value, tuple | list):
        children = list(value)
    else:
        children = []
    for child in children:
        yield from _objects(child, seen)


@pytest.mark.parametrize("name", names())
def test_the_compiled_model_holds_no_object_of_the_file_format_and_reads_its_document_back(name):
    """A compiled mechanism's fields, their records and everything in them down to the plain data of its document
    are arrays, records and plain values: no pydantic model among them.  Its document reads back
    (``described``) as the description it was compiled from, line numbers and all."""
    from pydantic import BaseModel

    from linkwork.spec.reader import described, validate

    spec = lw.load(name)
    mech = lw.compile(spec)
    found = [type(x).__name__ for x in _objects(mech) if isinstance(x, BaseModel)]
    assert found == []
    assert mech.description is spec.source
    again = validate(mech.description)  # what a process that did not read the file reads back
    assert again == spec and again is not spec
    assert described(mech.description) == spec
    assert again.source.line(("links",)) == spec.source.line(("links",)) > 1


def test_a_description_changed_in_code_reads_back_as_changed_not_as_its_file():
    """A Spec changed in code (``model_copy(update=...)``) is no longer the file it was read from: its mechanism's
    document is its own values (in SI), and reads back as them, not as the file's."""
    from linkwork.spec.reader import described
    from linkwork.units import SI_UNITS

    spec = lw.load("double-cut-shears")
    assert spec.loads
    changed = spec.model_copy(update={"loads": {}})
    assert changed.source is None and spec.source is not None
    mech = lw.compile(changed)
    back = described(mech.description)
    assert back.loads == {} and back.links == spec.links and back.drives == spec.drives
    assert back.units.length == "m"  # its values in SI, declared so
    assert mech.loads == () and lw.compile(spec).loads != ()
    made = lw.Spec.model_validate(changed.model_dump(), context={"units": SI_UNITS})  # by pydantic: no document
    assert described(lw.compile(made).description).joints == spec.joints


def test_a_mechanism_without_its_document_is_a_model_of_arrays_alone():
    """Taken off (``description=None``), nothing reads a file: the analyses run, and what needs the file says so."""
    import dataclasses

    from linkwork.errors import ParameterError
    from linkwork.structure.parameters import file_text

    mech = dataclasses.replace(lw.compile("four-bar"), description=None)
    assert lw.kinematics(mech, steps=12).valid_all.all()
    with pytest.raises(ParameterError, match="no file to edit"):
        file_text(mech, {})
