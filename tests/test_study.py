"""The study of a mechanism: each analysis solved once when first read, and its parts consistent with one
another by balances that do not use the code that computed them."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork as lw
from linkwork.study import Study


def _energy(kin: lw.Kinematics) -> tuple[np.ndarray, np.ndarray]:
    """Kinetic energy ``T`` (J) and potential energy of gravity ``V`` (J) of every sample ``(A,)``, summed link by
    link from the poses and velocities of the links (their origins and angles) and their mass properties."""
    mech = kin.mechanism
    masses = kin.mass_properties
    m, c, inertia = (np.asarray(a)[0] for a in (masses.mass, masses.com, masses.inertia))
    q, v = kin.pose[0], kin.vel[0]  # (A, N, 3): x, y, angle and their rates
    cos, sin = np.cos(q[..., 2]), np.sin(q[..., 2])
    rc = np.stack([cos * c[:, 0] - sin * c[:, 1], sin * c[:, 0] + cos * c[:, 1]], axis=-1)  # (A, N, 2)
    vc = v[..., :2] + v[..., 2:3] * np.stack([-rc[..., 1], rc[..., 0]], axis=-1)
    kinetic = 0.5 * (m * (vc**2).sum(-1) + inertia * v[..., 2] ** 2)
    g = np.asarray(mech.gravity_vector, dtype=float)
    potential = -(m * ((q[..., :2] + rc) @ g))
    return kinetic[:, 1:].sum(-1), potential[:, 1:].sum(-1)


def test_each_analysis_is_solved_once(monkeypatch):
    import linkwork.motion.kinematic_analysis as motion

    calls = []
    solve = motion.kinematics
    monkeypatch.setattr(motion, "kinematics", lambda *a, **k: calls.append(a) or solve(*a, **k))
    study = Study(lw.compile(lw.example("four-bar")), steps=36)
    assert calls == []  # nothing until read
    f = study.forces
    solved = len(calls)  # the cycle, and what the forces solve of their own (their change points)
    assert study.forces is f and f.kinematics is study.kin
    assert study.forces_or_reason == (f, "") and study.kin is f.kinematics
    assert len(calls) == solved  # read again: nothing solved again
    assert study.forces_twelve.kinematics is study.twelve
    assert study.twelve is study.forces_twelve.kinematics and len(study.twelve.angles) == 12


@pytest.mark.parametrize("name", ["four-bar", "watt-six-bar"])
def test_the_study_s_driving_torque_is_the_rate_of_change_of_the_energy(name):
    """At a uniform crank speed w and without loads, M w = dT/dt + dV/dt: the torque of the reactions' solution
    against a central difference of the energy the links' motion has (a step of 0.1 deg)."""
    study = Study(lw.compile(lw.example(name)), steps=3600)
    f = study.forces
    kinetic, potential = _energy(study.kin)
    w = float(study.kin.rates[0, 0])
    dphi = 2 * np.pi / 3600 * study.sign  # the samples turn in the drive's direction
    energy = kinetic + potential
    rate = (np.roll(energy, -1) - np.roll(energy, 1)) / (2 * dphi) * w  # dE/dt at a uniform speed
    torque = np.asarray(f.driving_torque)
    assert np.abs(torque).max() > 0.1
    assert np.abs(torque * w - rate).max() < 1e-4 * np.abs(torque * w).max()


def test_the_study_s_reduced_inertia_is_twice_its_kinetic_energy_over_the_crank_speed_squared():
    """J(phi) of the machine's dynamics = 2 T / w^2 of the links' motion at the same crank angles."""
    mech = lw.compile(lw.example("double-cut-shears"))
    study = Study(mech, steps=72)
    red = study.dynamics.reduced
    kin = lw.kinematics(mech, np.asarray(red.angle)[::25])
    kinetic, _ = _energy(kin)
    w = np.asarray(kin.rates)[:, 0]
    j = 2 * kinetic / w**2
    assert j == pytest.approx(np.asarray(red.inertia)[::25], rel=1e-9)


def test_the_study_s_cycle_turns_from_the_angle_asked_at_the_speed_asked():
    """``start``: the steps of a turn from that drive angle in the drive's direction (the commands' ``--steps``,
    from the assembly pose: 60 deg, counter-clockwise, for the four-bar); ``speed``: the cycle's and the twelve
    positions' drive speed."""
    mech = lw.compile(lw.example("four-bar"))
    study = Study(mech, 8, start=float(mech.drive_start[0]), speed=2.0)
    assert np.degrees(study.kin.angles) == pytest.approx(60 + 45 * np.arange(8), abs=1e-12)
    assert np.asarray(study.kin.rates) == pytest.approx(2.0) and np.asarray(study.twelve.rates) == pytest.approx(2.0)
    given = Study(mech, angles=np.radians([10.0, 20.0]))
    assert np.degrees(given.kin.angles) == pytest.approx([10, 20], abs=1e-12)
    assert np.asarray(given.kin.rates) == pytest.approx(2 * np.pi)  # the file's 60 rpm


def test_a_study_balances_only_over_equal_steps_of_a_whole_turn():
    """The least squares of the counterweights (and the first harmonic's orthonormal basis) hold over equal steps
    of a whole turn: a study of other angles is refused, in one sentence."""
    mech = lw.compile(lw.example("four-bar"))
    with pytest.raises(lw.errors.LinkworkError, match="equal steps of a whole turn"):
        Study(mech, angles=np.radians(np.arange(0.0, 180.0, 10.0))).balance(["crank"])
    weights = Study(mech, 36).balance(["crank", "rocker"]).counterweights
    assert [w.link for w in weights] == ["crank", "rocker"]
