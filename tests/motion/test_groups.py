"""The kinds of group are one registry (:data:`linkwork.motion.groups.KINDS`): a kind added there is solved, drawn and
analysed with nothing else edited."""

from __future__ import annotations

import contextlib

import numpy as np

import linkwork as lw
from linkwork.motion import groups, newton, plans
from linkwork.motion.groups import GroupKind
from linkwork.structure.records import Step


@contextlib.contextmanager
def registered(kind: GroupKind):
    """``kind`` in the registry, before ``newton`` (which takes every group the others leave)."""
    last = groups.KINDS.pop("newton")
    groups.KINDS[kind.name] = kind
    groups.KINDS["newton"] = last
    try:
        yield
    finally:
        del groups.KINDS[kind.name]
        groups.KINDS["newton"] = groups.KINDS.pop("newton")


def _triads(mech, g, driven):
    return Step("triad", g, g.links) if g.klass == 3 and not g.driven else None


def test_a_kind_added_to_the_registry_is_built_solved_and_drawn_with_nothing_else_edited():
    """A class III triad taken by a kind of its own (Newton's kernel under another name): the program has its step,
    and the kinematics and the forces are those of the triad solved as a ``newton`` group, to the bit."""
    triad = GroupKind("triad", build=_triads, solve=newton.solve, iterative=True)
    reference = lw.compile(lw.example("class3-triad"))
    assert [s.kind for s in reference.program] == ["crank", "newton"]
    angles = reference.drive_start[0] + np.linspace(0, 2 * np.pi, 36, endpoint=False)
    with registered(triad):
        mech = lw.compile(lw.example("class3-triad"))
        assert [s.kind for s in mech.program] == ["crank", "triad"] and mech.program_table is None
        kin, want = lw.kinematics(mech, angles), lw.kinematics(reference, angles)
        for name in ("q", "v", "a"):
            np.testing.assert_array_equal(getattr(kin, name), getattr(want, name))
        np.testing.assert_array_equal(
            lw.forces(mech, angles).driving_torque, lw.forces(reference, angles).driving_torque
        )
        velocity, _ = plans.plan_series(kin)  # its points by their absolute vectors: it has no construction
        assert {e.group for e in velocity.edges} == {mech.program[0].label}
    assert list(groups.KINDS)[-1] == "newton" and "triad" not in groups.KINDS


def test_the_kinds_are_tried_in_order_and_newton_takes_the_rest():
    assert list(groups.KINDS)[-1] == "newton"
    assert groups.CLOSED_FORM == ("crank", "slide", "RRR", "RRP", "PRP", "RPR", "RPP")
    assert groups.CHANGES_MODE == ("RRR", "RRP", "PRP") and groups.DRIVING == ("crank", "slide")
    assert groups.TRANSMISSION == ("RRR", "RRP", "PRP", "RPR")
