"""The loads' reduced moment, one formula for the steady cycle and the runs in time, against independent numbers:
a slider-crank's closed form, the work of constant loads over a small crank rotation, a damper's closed form, and
the run's moment at the file's speed where the two situations are the same."""

from __future__ import annotations

import copy
import math

import numpy as np

import linkwork as lw
from linkwork import MechanismBuilder
from linkwork.machine.reduction import reduced, reduced_terms
from mechanisms import kinetic_and_potential_by_differences

#: The slider-crank's crank, rod and guide's offset (m); the force on the slider (N) and the moment on the rod (N m).
R, L, E = 0.1, 0.35, 0.04
F, M = -1500.0, 40.0


def _slider_crank(damping: float = 0.0, heavy: bool = False) -> lw.Mechanism:
    """An offset slider-crank with a constant force ``F`` along x on the slider and ``M`` on the rod; with ``damping``
    (N s/m) a damper from the slider's B to the frame's D on the guide's line (its length changes as ``-s``);
    ``heavy``: with masses and friction in every pair (f 0.1, pins of 20 mm)."""
    b = MechanismBuilder("offset slider-crank", units={"angle": "rad"})
    b.frame(points={"O": (0, 0), "G": (0, E), "D": (0.9, E)})
    mass = {"crank": 2.0, "rod": 3.0, "slider": 5.0} if heavy else {}
    b.link("crank", ends=("O", "A"), length=R, mass=mass.get("crank"))
    b.link("rod", ends=("A", "B"), length=L, mass=mass.get("rod"))
    b.link("slider", points={"B": (0, 0)}, mass=mass.get("slider"))
    b.revolute("O", "frame", "crank").revolute("A", "crank", "rod").revolute("B", "rod", "slider")
    b.prismatic("guide", "frame", "slider", point="B", through="G", axis=0)
    b.drive("O", angle=0.3, speed="10 rad/s").hint("B", 0.1 * math.cos(0.3) + math.sqrt(L**2 - 0.0001), E)
    b.force("push", "slider.B", force=(f"{F} N", "0 N")).moment("twist", "rod", f"{M} N*m")
    if damping:
        b.damper("damper", ("slider.B", "D"), f"{damping} N*s/m")
    data = b.to_dict()
    if heavy:
        for joint in data["joints"].values():
            joint["friction"] = {"f": 0.1} if joint["type"] == "prismatic" else {"f": 0.1, "radius": "0.02 m"}
    return lw.compile(lw.from_dict(data))


def _closed_form(phi: np.ndarray) -> np.ndarray:
    """``F ds/dphi + M dtheta/dphi``: the rod at ``theta`` with ``L sin(theta) = E - R sin(phi)``, the slider at
    ``s = R cos(phi) + L cos(theta)``, so ``dtheta/dphi = -R cos(phi) / (L cos(theta))`` and
    ``ds/dphi = -R sin(phi) - L sin(theta) dtheta/dphi``; and ``ds/dphi``."""
    theta = np.arcsin((E - R * np.sin(phi)) / L)
    dtheta = -R * np.cos(phi) / (L * np.cos(theta))
    ds = -R * np.sin(phi) - L * np.sin(theta) * dtheta
    return F * ds + M * dtheta, ds


def test_the_slider_cranks_reduced_moment_is_its_closed_form_in_the_cycle_and_in_a_run():
    """A constant force on the slider and a moment on the rod: ``M = F ds/dphi + M_rod dtheta/dphi`` over the
    turn, the steady cycle's (the crank turning counter-clockwise: psi and phi alike) and the run's at any speed
    either way (these loads do not depend on it) to 1e-12 of the largest."""
    mech = _slider_crank()
    red = reduced(mech, steps=360)
    expected = _closed_form(red.angle)[0]
    scale = np.abs(expected).max()
    np.testing.assert_allclose(red.load, expected, rtol=0, atol=1e-12 * scale)
    speeds = np.random.default_rng(7).uniform(-30.0, 30.0, len(red.angle))
    run = reduced_terms(mech, red.angle, speeds).load
    np.testing.assert_allclose(run, expected, rtol=0, atol=1e-12 * scale)


def _loaded_four_bar() -> lw.Mechanism:
    """The bundled four-bar (masses, gravity) with a constant force at its coupler point, a moment on its rocker and
    a spring from the rocker's end to the frame."""
    data = copy.deepcopy(lw.example("four-bar").model_dump(exclude_none=True))
    data["units"] = {"angle": "rad"}  # the dump is in SI
    data["frame"]["points"]["S"] = [0.5, -0.1]
    data["loads"] = {
        "pull": {"type": "force", "at": "coupler.M", "force": ["120 N", "-80 N"]},
        "brake": {"type": "moment", "on": "rocker", "moment": "-15 N*m"},
        "spring": {"type": "spring", "between": ["rocker.B", "S"], "stiffness": "2000 N/m", "free_length": "0.2 m"},
    }
    return lw.compile(lw.from_dict(data))


def _work_by_differences(mech: lw.Mechanism, angle: np.ndarray, h: float) -> np.ndarray:
    """``dW/dphi`` of the four-bar's gravity, force, moment and spring by central differences of positions alone
    between the poses at ``angle +- h``: ``(F . dr_M + M dtheta - dV_spring) / 2h`` and minus the slope of the
    weights' potential energy."""
    plus, minus = (lw.kinematics(mech, angle + d) for d in (h, -h))
    force = np.sum((plus.position("coupler.M") - minus.position("coupler.M")) * [120.0, -80.0], -1)
    moment = -15.0 * (plus.angle("rocker") - minus.angle("rocker"))
    length = [np.linalg.norm(k.position("rocker.B") - [0.5, -0.1], axis=-1) for k in (plus, minus)]
    spring = -1000.0 * ((length[0] - 0.2) ** 2 - (length[1] - 0.2) ** 2)
    gravity = -kinetic_and_potential_by_differences(mech, angle, h)[1]
    out: np.ndarray = (force + moment + spring) / (2 * h) + gravity
    return out


def test_the_reduced_moment_is_the_work_of_the_loads_a_radian_of_the_crank():
    """Gravity, a constant force, a constant moment and a spring on the four-bar: the reduced moment (the loads'
    power at unit crank speed) is the rate of their work in the crank angle, ``dW/dphi``, found from the poses alone
    (central differences of 1e-5 rad: their error is ~1e-10 of the moment), in the steady cycle and in a run at any
    speed (none of these loads depends on it)."""
    mech = _loaded_four_bar()
    red = reduced(mech, steps=360)
    expected = _work_by_differences(mech, red.angle, 1e-5)
    scale = np.abs(expected).max()
    np.testing.assert_allclose(red.load, expected, rtol=0, atol=1e-8 * scale)
    speeds = np.random.default_rng(3).uniform(-20.0, 20.0, len(red.angle))
    np.testing.assert_allclose(reduced_terms(mech, red.angle, speeds).load, expected, rtol=0, atol=1e-8 * scale)


def test_a_dampers_reduced_moment_takes_its_force_at_the_true_speed():
    """A damper ``c`` along the guide: its force at the crank speed ``omega`` is ``c omega ds/dphi`` against the
    slider's motion, so the run's moment is ``F ds/dphi + M dtheta/dphi - c omega (ds/dphi)^2`` (the damper's force
    at the true speed, its point's velocity at unit speed), and the steady cycle keeps it apart as ``B = c
    (ds/dphi)^2``, its moment ``-B omega``."""
    c = 800.0
    mech = _slider_crank(damping=c)
    red = reduced(mech, steps=360)
    loads, ds = _closed_form(red.angle)
    scale = np.abs(loads).max()
    assert red.damping is not None
    np.testing.assert_allclose(red.load, loads, rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(red.damping, c * ds**2, rtol=0, atol=1e-12 * np.abs(c * ds**2).max())
    speeds = np.random.default_rng(5).uniform(-30.0, 30.0, len(red.angle))
    run = reduced_terms(mech, red.angle, speeds).load
    expected = loads - c * speeds * ds**2
    np.testing.assert_allclose(run, expected, rtol=0, atol=1e-12 * np.abs(expected).max())


def test_the_steady_cycles_moment_is_the_runs_at_the_files_speed():
    """With masses, a damper and friction in every pair (loaded by the inertia forces: the friction depends on the
    speed), the steady cycle's moment at the file's speed, ``M - B omega_n``, is the run's at the states
    ``(phi, omega_n)`` to rounding, the two taking the friction of the same pairs' forces; at twice the speed the
    run's friction differs (the test tells the two apart)."""
    mech = _slider_crank(damping=800.0, heavy=True)
    red = reduced(mech, steps=180)
    assert red.friction is not None and red.friction.max() > 0 and red.damping is not None
    rate = float(mech.drive_speed[0])
    cycle = red.load - red.damping * rate
    scale = np.abs(cycle).max()
    at = [reduced_terms(mech, red.angle, np.full(len(red.angle), k * rate)).load for k in (1.0, 2.0)]
    np.testing.assert_allclose(at[0], cycle, rtol=0, atol=1e-12 * scale)
    faster = cycle - red.damping * rate  # the damper at twice the speed; the friction still the cycle's
    assert np.abs(at[1] - faster).max() > 1e-3 * scale
