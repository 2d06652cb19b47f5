"""The compiled kernels against the NumPy kernels they mirror."""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkwork as lw
from linkwork import threads
from linkwork.motion import kernels_numba
from linkwork.structure.parameters import apply
from mechanisms import SOLVED, TEXTBOOK, angles_around, circle_intersection, compiled, four_bar_spec, hydraulic_boom

pytestmark = pytest.mark.numba  # the compiled kernels' lane: each test runs them (tests/conftest.py)


def _both(mech, angles, monkeypatch, **kw):
    assert kernels_numba.available()  # the lane's fixture turned them on: no comparison of NumPy with itself
    compiled = lw.kinematics(mech, angles, **kw)
    with monkeypatch.context() as m:
        m.setenv("LINKWORK_NUMBA", "0")
        reference = lw.kinematics(mech, angles, **kw)
    return compiled, reference


def _same(compiled, reference, scale=1.0):
    np.testing.assert_array_equal(compiled.valid_all, reference.valid_all)
    for kin in (compiled, reference):  # the cosines and sines the points are placed with are the angles'
        np.testing.assert_allclose(kin.cos, np.cos(kin.q[:, 2]), rtol=0, atol=1e-14)
        np.testing.assert_allclose(kin.sin, np.sin(kin.q[:, 2]), rtol=0, atol=1e-14)
    for name in ("q", "v", "a", "cos", "sin"):
        got, want = getattr(compiled, name), getattr(reference, name)
        np.testing.assert_array_equal(np.isnan(got), np.isnan(want))
        size = np.nanmax(np.abs(want), axis=-1, keepdims=True) + scale
        np.testing.assert_allclose(got / size, want / size, rtol=0, atol=1e-11, equal_nan=True, err_msg=name)
    assert [e.message for e in compiled.events] == [e.message for e in reference.events]


CLOSED_FORM = [m for m in SOLVED if compiled(*m).program_table is not None] + [("textbook", "boom")]


def test_every_closed_form_program_is_compiled():
    """Only the groups without a closed form (class III and IV, the redundant link) go to Newton."""
    assert {name for _, name in SOLVED} - {name for _, name in CLOSED_FORM} == {
        "class3-triad",
        "class IV",
        "parallelogram",
    }


def _textbook_or_example(kind, name):
    if name == "boom":
        return lw.compile(hydraulic_boom().build())
    return compiled(kind, name)


@pytest.mark.parametrize("kind, name", CLOSED_FORM)
def test_compiled_kernels_equal_numpy_kernels(kind, name, monkeypatch):
    mech = _textbook_or_example(kind, name)
    compiled, reference = _both(mech, angles_around(mech, n=181), monkeypatch)
    _same(compiled, reference, float(np.abs(mech.point_local).max()))


def test_design_variants_that_fail_to_assemble_agree(monkeypatch):
    mech = lw.compile(lw.example("four-bar"))
    crank = np.linspace(0.05, 0.3, 40)  # beyond 0.15 the four-bar is no longer a crank-rocker
    compiled, reference = _both(mech, angles_around(mech, n=90), monkeypatch, variants={"links.crank.length": crank})
    assert not compiled.valid_all.all() and compiled.valid_all.any()
    _same(compiled, reference)


def test_dead_points_agree(monkeypatch):
    """The four-bar driven by its rocker: dead points where crank and coupler line up, some on samples."""
    data = TEXTBOOK["four-bar"][0]().to_dict()
    pa = (0.1 * math.cos(math.radians(60)), 0.1 * math.sin(math.radians(60)))
    pb = circle_intersection(pa, 0.35, (0.3, 0.0), 0.25, left=False)
    data["drives"] = [{"joint": "O4", "angle": math.degrees(math.atan2(pb[1], pb[0] - 0.3))}]
    data["hints"] = {"A": list(pa)}
    mech = lw.compile(lw.from_dict(data))
    cos_t = (0.3**2 + 0.25**2 - 0.45**2) / (2 * 0.3 * 0.25)
    dead = math.pi - math.acos(cos_t)  # |O2 B| = a + b
    angles = np.sort(np.concatenate([np.linspace(-np.pi, np.pi, 721), [dead, -dead]]))
    compiled, reference = _both(mech, angles, monkeypatch)
    _same(compiled, reference)
    assert any(e.kind in ("dead-point", "singular") for e in compiled.events)


def test_threads_split_the_samples_without_changing_a_bit(monkeypatch):
    mech = lw.compile(lw.example("double-cut-shears"))
    angles = mech.drive_start[0] + np.linspace(0, 2 * np.pi, 5000, endpoint=False)
    monkeypatch.setattr(threads, "THREADS", 1)
    one = lw.kinematics(mech, angles)
    monkeypatch.setattr(threads, "THREADS", 3)
    monkeypatch.setattr(threads, "PER_THREAD", 100)
    three = lw.kinematics(mech, angles)
    for name in ("q", "v", "a"):
        np.testing.assert_array_equal(getattr(one, name), getattr(three, name))


def test_change_points_go_to_the_numpy_path(monkeypatch):
    """The isosceles slider-crank: the compiled path sees the two modes meet and hands over."""
    mech = lw.compile(lw.example("shears-slider-crank"))
    values = mech.drive_start[0] + np.linspace(0, 2 * np.pi, 360, endpoint=False)[:, None]
    res = kernels_numba.run(mech, apply(mech)[0], values, np.ones_like(values), np.zeros_like(values))
    assert res.near.any()
    compiled, reference = _both(mech, values[:, 0], monkeypatch)
    _same(compiled, reference)
    assert any(e.kind == "change-point" for e in compiled.events)


def test_samples_on_a_singular_position_go_to_the_numpy_path(monkeypatch):
    """A rhombus with its crank on the frame (A on O4) and a kite at its change point, both on a
    sample: the compiled path reports them and hands over, and the two paths agree."""
    from mechanisms import RHOMBUS

    rhombus = lw.compile(lw.loads(RHOMBUS))
    kite_data, _ = four_bar_spec(0.5, 0.5, 0.625, 0.625, 0.25, True)
    kite = lw.compile(lw.from_dict(kite_data))
    for mech, values in ((rhombus, np.radians([0.0, 10.0, 20.0])), (kite, np.array([0.0, 0.1, 0.2]))):
        res = kernels_numba.run(mech, apply(mech)[0], values[:, None], np.ones((3, 1)), np.zeros((3, 1)))
        assert [step.kind for step in mech.program] == ["crank", "RRR"]
        assert res.limit[:, 0].tolist() == [False, True]  # per step
        compiled, reference = _both(mech, np.linspace(0.3, -0.3, 61), monkeypatch)
        _same(compiled, reference)


def test_the_kernels_say_what_their_arrays_hold(monkeypatch):
    """``some_near``, ``some_limit``, ``some_invalid`` and ``some_trouble`` of :func:`kernels_numba.run` (set by the
    kernels as they go) are ``near.any()``, ``limit.any()``, ``not valid.all()`` and ``trouble.any()``, on
    one thread and split over three: variants that fail to assemble, change points, a dyad on its
    singular position, and none of these."""
    from mechanisms import RHOMBUS

    four, shears = lw.compile(lw.example("four-bar")), lw.compile(lw.example("shears-slider-crank"))
    rhombus = lw.compile(lw.loads(RHOMBUS))
    turn = np.linspace(0, 2 * np.pi, 360, endpoint=False)
    cases = [
        (four, {"links.crank.length": np.linspace(0.05, 0.3, 40)}, four.drive_start[0] + turn[::4]),
        (four, None, four.drive_start[0] + turn),
        (shears, None, shears.drive_start[0] + turn),
        (rhombus, None, np.radians([0.0, 10.0, 20.0])),
    ]
    seen = set()
    for count in (1, 3):
        monkeypatch.setattr(threads, "THREADS", count)
        monkeypatch.setattr(threads, "PER_THREAD", 100)
        for mech, variants, angles in cases:
            values = angles[:, None]
            res = kernels_numba.run(mech, apply(mech, variants)[0], values, np.ones_like(values), np.zeros_like(values))
            found = {
                "near": res.near.any(),
                "limit": res.limit.any(),
                "invalid": not res.valid.all(),
                "trouble": res.trouble.any(),
            }
            assert (res.some_near, res.some_limit, res.some_invalid, res.some_trouble) == tuple(found.values())
            seen |= {name for name, there in found.items() if there}
    assert seen == {"near", "limit", "invalid", "trouble"}


def test_the_tolerance_of_the_change_point_test_is_of_the_largest_point_of_any_variant():
    """The kernels find it themselves: 1e-12 of 1 m plus the largest coordinate of any point of any
    variant (here the crank's end in the last variant)."""
    mech = lw.compile(lw.example("four-bar"))
    local = apply(mech, {"links.crank.length": np.linspace(0.05, 2.0, 5)})[0].point_local
    assert np.abs(local[-1]).max() == 2.0 > np.abs(local[:-1]).max()
    assert kernels_numba._tolerance(local) == 1e-12 * (1 + 2.0)


@pytest.mark.parametrize("kind, name", CLOSED_FORM)
def test_points_read_by_the_compiled_kernel_are_the_numpy_readings(kind, name, monkeypatch):
    """Every point's position, velocity and acceleration, read in one compiled pass over the samples, equal
    the same arithmetic done by NumPy (to the last bit, as compiled without fused multiply-adds), and the
    NumPy readings equal the link's motion carried to the point, written out here: ``r = R(theta) p``,
    ``x + r``, ``v + omega k x r``, ``a + epsilon k x r - omega^2 r``."""
    mech = _textbook_or_example(kind, name)
    kin = lw.kinematics(mech, angles_around(mech, n=37))
    compiled = {p: kin.motion_of(p) for p in mech.point_names}
    monkeypatch.setenv("LINKWORK_NUMBA", "0")
    for p in mech.point_names:
        link, (lx, ly) = mech.point_link[mech.point_index(p)], mech.point_local[mech.point_index(p)]
        (x, y, theta), (vx, vy, w), (ax, ay, e) = kin.q[link, :, 0], kin.v[link, :, 0], kin.a[link, :, 0]
        rx, ry = np.cos(theta) * lx - np.sin(theta) * ly, np.sin(theta) * lx + np.cos(theta) * ly
        closed = ([x + rx, y + ry], [vx - w * ry, vy + w * rx], [ax - e * ry - w * w * rx, ay + e * rx - w * w * ry])
        size = 1.0 + np.abs(mech.point_local).max()
        for got, want, by_numpy in zip(compiled[p], closed, kin.motion_of(p), strict=True):
            np.testing.assert_array_equal(got, by_numpy, err_msg=p)
            scale = size * (1.0 + np.nanmax(np.abs(want)))
            np.testing.assert_allclose(got[0], np.transpose(want), rtol=0, atol=1e-14 * scale, err_msg=p)


def test_points_of_design_variants_and_of_picked_samples_read_as_the_whole(monkeypatch):
    """Every point of seven design variants of the four-bar (crank 80 to 120 mm), read by the compiled pass:
    each variant's readings are those of the four-bar solved alone with that crank, the readings of picked
    samples (an index array, a strided slice: arrays that are not contiguous) are those samples of the
    whole, and the NumPy readings are the same to the last bit."""
    mech = lw.compile(lw.example("four-bar"))
    angles, cranks = angles_around(mech, n=41), np.linspace(0.08, 0.12, 7)
    kin = lw.kinematics(mech, angles, variants={"links.crank.length": cranks})
    compiled = {p: kin.motion_of(p) for p in mech.point_names}
    for k in (0, 4):
        alone = lw.kinematics(mech, angles, variants={"links.crank.length": cranks[k : k + 1]})
        for p in mech.point_names:
            for got, want in zip(compiled[p], alone.motion_of(p), strict=True):
                np.testing.assert_allclose(got[k], want[0], rtol=0, atol=1e-12, err_msg=p)
    for index in (np.array([3, 17, 40, 0]), slice(5, 30, 4)):
        part = kin.samples(index)
        for p in mech.point_names:
            for got, whole in zip(part.motion_of(p), compiled[p], strict=True):
                np.testing.assert_array_equal(got, whole[:, index], err_msg=p)
    monkeypatch.setenv("LINKWORK_NUMBA", "0")
    for p in mech.point_names:
        for got, by_numpy in zip(compiled[p], kin.motion_of(p), strict=True):
            np.testing.assert_array_equal(got, by_numpy, err_msg=p)
