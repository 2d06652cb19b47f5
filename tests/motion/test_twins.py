"""Every kind of group has both twins, the NumPy kernels and their numba twin, and they agree on a random case.

The twins and how to add a kind to both: the docstring of :mod:`linkwork.motion`.
"""

from __future__ import annotations

import numpy as np
import pytest

import linkwork as lw
from linkwork.kinetostatics import reactions_numba
from linkwork.kinetostatics.reactions import foundation, inertia_and_gravity, solve_reactions
from linkwork.motion import groups, kernels, kernels_numba, newton, solve
from linkwork.spec.builder import MechanismBuilder
from linkwork.structure.model import PairType
from linkwork.structure.parameters import apply
from mechanisms import SOLVED, compiled

numba = pytest.mark.numba  # the compiled kernels' lane: each test runs them (tests/conftest.py)


def pushed_rocker():
    """A ram driven along the frame's guide (a ``slide``) pushes a rocker through a rod (an RRR dyad)."""
    return (
        MechanismBuilder("pushed rocker")
        .frame(points={"G": (0, 0), "O": (0.4, 0.3)})
        .link("ram", points={"P": (0, 0)})
        .link("rod", ends=("P", "B"), length=0.35)
        .link("rocker", ends=("O", "B"), length=0.25)
        .prismatic("guide", "frame", "ram", point="P", through="G", axis=0)
        .revolute("P", "ram", "rod")
        .revolute("B", "rod", "rocker")
        .revolute("O", "frame", "rocker")
        .drive("guide", position=0.1, speed="0.05 m/s")
        .hint("B", 0.35, 0.1)
    )


@pytest.fixture(scope="module")
def by_kind():
    """The first mechanism of the test set that has a step of each kind."""
    out = {}
    for mech in [compiled(*m) for m in SOLVED] + [lw.compile(pushed_rocker().build())]:
        for step in mech.program:
            out.setdefault(step.kind, mech)
    return out


def _random_case(mech, seed):
    """Drive values near the assembly pose, and random rates and accelerations of the drive, ``(A, 1)`` each."""
    rng = np.random.default_rng(seed)
    half = 0.02 if mech.pair_type[mech.drive_pair[0]] == PairType.PRISMATIC else 0.3
    values = mech.drive_start[0] + np.sort(rng.uniform(-half, half, 24))[:, None]
    return values, rng.uniform(-3.0, 3.0, values.shape), rng.uniform(-20.0, 20.0, values.shape)


def test_every_kind_has_a_mechanism_that_uses_it(by_kind):
    assert set(by_kind) == set(groups.KINDS)


@pytest.mark.parametrize("kind", groups.CLOSED_FORM)
def test_every_closed_form_kind_has_a_compiled_twin_inlined_into_the_dispatch(kind):
    """Its scalar kernel is a function of the numba module compiled inline, and the dispatch on codes calls it."""
    import inspect

    record = groups.KINDS[kind]
    twin = getattr(kernels_numba, record.twin)
    assert callable(twin) and record.twin in kernels_numba._INLINE
    step = inspect.getsource(getattr(kernels_numba._step, "py_func", kernels_numba._step))
    assert f"{record.twin}(" in step


def test_the_driving_links_take_the_lowest_codes():
    """``kernels_numba`` tells a driving link from a group by ``code < DYAD`` (its slack and determinant are 1)."""
    codes = {name: kind.code for name, kind in groups.KINDS.items() if kind.code is not None}
    driving = [codes[name] for name in groups.DRIVING]
    assert max(driving) < groups.DYAD == min(c for name, c in codes.items() if name not in groups.DRIVING)


@pytest.mark.parametrize("kind", groups.CLOSED_FORM)
def test_every_closed_form_kind_has_a_numpy_kernel(kind, by_kind, monkeypatch):
    """The NumPy path solves each closed-form kind by its own kernel: Newton's method is never asked to."""

    def no_newton(*args, **kw):
        raise AssertionError(f"the {kind} step went to Newton's method")

    mech = by_kind[kind]
    if any(step.kind == "newton" for step in mech.program):
        pytest.skip("the mechanism has a Newton group too")
    monkeypatch.setattr(newton, "newton", no_newton)
    monkeypatch.setattr(newton, "newton_from", no_newton)
    values, rates, accels = _random_case(mech, 1)
    state = solve.run_numpy(mech, mech.program, apply(mech)[0], values, rates, accels)
    assert state.valid.all()


@numba
@pytest.mark.parametrize("kind", groups.CLOSED_FORM)
def test_the_twins_of_each_kind_agree_on_a_random_case(kind, by_kind):
    mech = by_kind[kind]
    geom = apply(mech)[0]
    values, rates, accels = _random_case(mech, 2)
    twin = kernels_numba.run(mech, geom, values, rates, accels)
    ref = solve.run_numpy(mech, mech.program, geom, values, rates, accels)
    assert twin.valid.all() and ref.valid.all() and not (twin.some_near or twin.some_limit)
    for name in ("q", "v", "a"):
        got, want = getattr(twin, name), getattr(ref, name)
        size = np.abs(want).max() + 1.0
        np.testing.assert_allclose(got / size, want / size, rtol=0, atol=1e-12, err_msg=name)


@numba
@pytest.mark.parametrize("quantity", [kernels.POSITION, kernels.VELOCITY, kernels.ACCELERATION])
def test_the_twins_of_a_point_motion_agree(quantity):
    rng = np.random.default_rng(3)
    q, v, a = (rng.normal(size=(3, 4, 9)) for _ in range(3))
    cos, sin = np.cos(q[2]), np.sin(q[2])
    lx, ly = rng.normal(size=4), rng.normal(size=4)
    got, want = np.empty((4, 9, 2)), np.empty((4, 9, 2))
    kernels_numba.point_motion_into(quantity, q, v, a, cos, sin, lx, ly, got)
    kernels.point_motion_into(quantity, q, v, a, cos, sin, lx, ly, want)
    np.testing.assert_allclose(got, want, rtol=1e-14, atol=1e-14)
    # an independent reading: the position is the link's origin plus its turned local vector
    if quantity == kernels.POSITION:
        x = q[0] + cos * lx[:, None] - sin * ly[:, None]
        np.testing.assert_allclose(want[..., 0], x, rtol=1e-14, atol=1e-14)


@numba
@pytest.mark.parametrize(
    "shape, name",
    [
        (reactions_numba.SINGLE, "four-bar"),
        (reactions_numba.DYAD, "four-bar"),
        (reactions_numba.GENERAL, "class3-triad"),
    ],
)
def test_the_twins_of_the_reactions_agree_on_a_random_case(shape, name):
    mech = lw.compile(lw.example(name))
    rows, groups, _ = reactions_numba.encode(mech)
    assert shape in reactions_numba.shapes(rows, groups)[:, 0]
    values, _, _ = _random_case(mech, 4)
    kin = lw.kinematics(mech, values[:, 0])
    lam, frame = reactions_numba.run(kin, None)
    loads = inertia_and_gravity(kin, None)
    ref, ref_frame = solve_reactions(kin, loads)
    size = np.abs(ref).max()
    np.testing.assert_allclose(lam, ref, rtol=0, atol=1e-11 * size)
    np.testing.assert_allclose(frame, foundation(kin, ref_frame, loads), rtol=0, atol=1e-11 * size)
