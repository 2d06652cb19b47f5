"""The run in time (linkwork.simulate) against closed forms, an independent Lagrange model and energy."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import solve_ivp

import linkwork as lw
from linkwork import MechanismBuilder
from linkwork.machine.timerun import simulate
from mechanisms import kinetic_and_potential_by_differences

M, L, JC, K, G = 2.0, 0.4, 0.05, 30.0, 9.81


def pendulum(k: float = K, g: float = G) -> lw.Mechanism:
    """A rod hanging from the frame's O (its centre of mass at ``L``), a torsion spring free hanging down."""
    b = MechanismBuilder("pendulum", units={"angle": "rad"}, gravity=g)
    b.frame(points={"O": (0, 0)})
    b.link("arm", points={"O": (0, 0), "P": (L, 0)}, mass=M, com=(L, 0), inertia=f"{JC} kg*m^2")
    b.revolute("O", "frame", "arm").drive("O", angle=-math.pi / 2)
    b.torsion_spring("t", "O", f"{k} N*m/rad", -math.pi / 2)
    return lw.compile(b.build())


def test_a_pendulum_with_a_torsion_spring_swings_with_the_closed_form_period():
    """Small swings: omega_n^2 = (k + m g l) / (J_C + m l^2); the crank stops every half period (the stops are
    the run's events); from 0.2 mrad the amplitude's own correction to the period is below 1e-8."""
    wn = math.sqrt((K + M * G * L) / (JC + M * L * L))
    period = 2 * math.pi / wn
    run = simulate(pendulum(), 2.2 * period, angle=-math.pi / 2 + 2e-4, speed=0.0)
    stops = np.array([e.time for e in run.events if e.kind == "stop"])
    assert len(stops) == 4
    np.testing.assert_allclose(np.diff(stops), period / 2, rtol=1e-7)
    np.testing.assert_allclose(stops[0], period / 2, rtol=1e-7)
    np.testing.assert_allclose([e.angle for e in run.events], -math.pi / 2 + np.array([-2e-4, 2e-4] * 2), atol=1e-9)


def slider_crank(k: float, c: float = 0.0) -> lw.Mechanism:
    """A slider-crank (crank 0.1 m, rod 0.35 m, slider on the x axis) with a spring (and a damper) from the
    slider to the frame's S at x = 0.7 m, free at 0.35 m."""
    b = MechanismBuilder("slider-crank", units={"angle": "rad"})
    b.frame(points={"O": (0, 0), "S": (0.7, 0)})
    b.link("crank", ends=("O", "A"), length=0.1, mass=1.5, inertia="0.004 kg*m^2")
    b.link("rod", ends=("A", "B"), length=0.35, mass=2.0)
    b.link("slider", points={"B": (0, 0)}, mass=3.0)
    b.revolute("O", "frame", "crank").revolute("A", "crank", "rod").revolute("B", "rod", "slider")
    b.prismatic("guide", "frame", "slider", point="B", through="O", axis=0)
    b.drive("O", angle=0.3).hint("B", 0.1 * math.cos(0.3) + math.sqrt(0.35**2 - (0.1 * math.sin(0.3)) ** 2), 0)
    b.spring("s", ("slider.B", "S"), f"{k} N/m", free_length=0.35)
    if c:
        b.damper("d", ("slider.B", "S"), f"{c} N*s/m")
    return lw.compile(b.build())


def lagrange_slider_crank(k: float, g: float = 9.81):
    """phi'' = f(phi, phi') of the slider-crank of :func:`slider_crank` by Lagrange's equation, in sympy."""
    phi, w = sp.symbols("phi omega")
    r, ln, x_s, free = sp.Rational(1, 10), sp.Rational(35, 100), sp.Rational(7, 10), sp.Rational(35, 100)
    a = sp.Matrix([r * sp.cos(phi), r * sp.sin(phi)])
    b = sp.Matrix([a[0] + sp.sqrt(ln**2 - a[1] ** 2), 0])
    beta = sp.atan2(b[1] - a[1], b[0] - a[0])
    rod_inertia = 2 * ln**2 / 12  # a uniform rod: the file gives no inertia
    bodies = [(1.5, a / 2, phi, sp.Rational(4, 1000)), (2, (a + b) / 2, beta, rod_inertia), (3, b, 0, 0)]
    mass_matrix = sum(m * c.diff(phi).dot(c.diff(phi)) + j * sp.diff(t, phi) ** 2 for m, c, t, j in bodies)
    potential = sum(m * g * c[1] for m, c, _, _ in bodies) + sp.Rational(1, 2) * k * (x_s - b[0] - free) ** 2
    # T = J(phi) w^2 / 2: d/dt(J w) - J' w^2 / 2 + V' = 0
    acc = -(mass_matrix.diff(phi) * w**2 / 2 + potential.diff(phi)) / mass_matrix
    return sp.lambdify((phi, w), acc, "math")


def test_a_slider_crank_with_a_spring_follows_its_lagrange_model():
    """The spring on the slider, free motion from 0.3 rad at 5 rad/s for 0.3 s: the crank angle and speed agree
    with solve_ivp on the sympy Lagrange equation (rtol 1e-12) to 1e-8."""
    k = 4000.0
    f = lagrange_slider_crank(k)
    ref = solve_ivp(
        lambda t, y: [y[1], f(y[0], y[1])],
        (0, 0.3),
        [0.3, 5.0],
        method="DOP853",
        rtol=1e-12,
        atol=1e-12,
        dense_output=True,
    )
    times = np.linspace(0, 0.3, 7)
    run = simulate(slider_crank(k), 0.3, speed=5.0, times=times)
    want = ref.sol(times)
    np.testing.assert_allclose(run.angle, want[0], rtol=1e-8, atol=1e-9)
    np.testing.assert_allclose(run.speed, want[1], rtol=1e-8, atol=1e-7)
    np.testing.assert_allclose(run.acceleration, [f(p, w) for p, w in want.T], rtol=1e-7, atol=1e-5)


def mechanical_energy(run, k: float) -> np.ndarray:
    """Kinetic energy, gravity's and the spring's potential energy of the slider-crank's run, J, from its
    positions and velocities (the spring's length from the slider's x)."""
    kin, mech = run.kinematics, run.mechanism
    kinetic = np.zeros(len(run.time))
    height = np.zeros(len(run.time))
    for link in ("crank", "rod", "slider"):
        i = mech.link_names.index(link)
        q, v = kin.pose[0, :, i], kin.vel[0, :, i]
        c, s = np.cos(q[:, 2]), np.sin(q[:, 2])
        lx, ly = mech.link_com[i]
        r = np.stack([c * lx - s * ly, s * lx + c * ly], -1)
        vc = v[:, :2] + v[:, 2:3] * np.stack([-r[:, 1], r[:, 0]], -1)
        kinetic += 0.5 * mech.link_mass[i] * np.sum(vc * vc, -1) + 0.5 * mech.link_inertia[i] * v[:, 2] ** 2
        height += mech.link_mass[i] * (q[:, 1] + r[:, 1])
    stretch = 0.7 - kin.position("B")[:, 0] - 0.35
    return kinetic + 9.81 * height + 0.5 * k * stretch**2


def test_energy_is_conserved_where_nothing_dissipates():
    k = 4000.0
    run = simulate(slider_crank(k), 0.25, speed=-8.0, times=np.linspace(0, 0.25, 51))
    e = mechanical_energy(run, k)
    assert np.ptp(e) < 1e-8 * e[0]


def test_a_dampers_dissipation_is_the_loss_of_mechanical_energy():
    """The loss of mechanical energy over the run equals the integral of c (dL/dt)^2 (Simpson's rule on the
    slider's speed); and the drive row carries nothing in a free run: the reactions balance the links with the
    run's own acceleration."""
    k, c = 4000.0, 15.0
    times = np.linspace(0, 0.4, 2001)
    run = simulate(slider_crank(k, c), 0.4, speed=10.0, times=times)
    e = mechanical_energy(run, k)
    vb = run.kinematics.velocity("B")[:, 0]
    from scipy.integrate import simpson

    dissipated = simpson(c * vb**2, x=times)
    assert e[0] - e[-1] > 0.1 * e[0]
    assert e[0] - e[-1] == pytest.approx(dissipated, rel=1e-7)
    torque = run.forces().driving_torque
    assert np.max(np.abs(torque)) < 1e-8 * np.max(np.abs(run.acceleration)) * 0.01


def test_the_end_state_is_as_accurate_as_stated():
    """The default tolerances (1e-10) against a run 100 times tighter: the end state within 1e-8 relative."""
    mech = slider_crank(4000.0, 5.0)
    loose = simulate(mech, 0.15, speed=6.0, times=[0.15])
    tight = simulate(mech, 0.15, speed=6.0, times=[0.15], rtol=1e-12, atol=1e-12)
    assert loose.angle[0] == pytest.approx(tight.angle[0], rel=1e-8)
    assert loose.speed[0] == pytest.approx(tight.speed[0], rel=1e-8)


def test_a_spring_returned_slider_stops_and_turns_back_where_the_energy_says():
    """Started towards the spring at too little speed to pass the dead point, the crank stops where its kinetic
    energy at the start has gone into the spring and gravity, and turns back."""
    k = 20000.0
    mech = slider_crank(k)
    times = np.linspace(0, 0.1, 101)
    run = simulate(mech, 0.1, angle=0.3, speed=-4.0, times=times)
    assert run.events and run.events[0].kind == "stop"
    stop = run.events[0]
    at = simulate(mech, stop.time, angle=0.3, speed=-4.0, times=[0.0, stop.time])
    e = mechanical_energy(at, k)
    assert abs(at.speed[-1]) < 1e-6
    assert e[-1] == pytest.approx(e[0], rel=1e-9)
    after = np.flatnonzero(times > stop.time)[:3]
    assert np.all(run.speed[after] > 0) and np.all(run.speed[times < stop.time] < 0)  # back the other way


def test_andrews_squeezer_reaches_the_reference_state():
    """Andrews' squeezer (seven bodies, a spring, a constant torque, from rest, no gravity; Hairer & Wanner,
    Solving ODEs II, VII.7), written as a linkwork file: the crank's angle and speed at 0.03 s against the
    reference solution of the IVP test set (beta = 15.81077119629904 rad, beta' = 1139.920302151208 rad/s),
    to 1e-6 relative (measured: 9e-10 and 1e-10 at rtol 1e-9)."""
    from pathlib import Path

    path = Path(__file__).with_name("andrews-squeezer.yaml")
    run = lw.simulate(str(path), 0.03, times=[0.03], rtol=1e-8, atol=1e-8)
    assert run.angle[0] == pytest.approx(15.81077119629904, rel=1e-6)
    assert run.speed[0] == pytest.approx(1139.920302151208, rel=1e-6)
    # the reactions with the run's own acceleration: the crank's pair carries the motor's constant torque
    assert run.forces().driving_torque[0] == pytest.approx(0.033, rel=1e-9)


def test_the_steady_cycle_with_a_damper_spends_the_motors_work_in_it():
    """``dynamics`` with a damper from the crank's A to the frame: over the steady turn the motor's work equals
    the damper's, the integral of c (dL/dpsi)^2 omega dpsi with L from the positions alone (without the damper
    in the run the balance would not close; springs and gravity give nothing over a turn)."""
    c = 2.0
    b = MechanismBuilder("damped", units={"angle": "rad"}, gravity=0)
    b.frame(points={"O": (0, 0), "S": (0.5, 0.2)})
    b.link("crank", ends=("O", "A"), length=0.1, mass=1.5, inertia="0.004 kg*m^2")
    b.revolute("O", "frame", "crank").drive("O", angle=0.0, speed="100 rpm")
    b.damper("d", ("crank.A", "S"), f"{c} N*s/m")
    b.spring("s", ("crank.A", "S"), "30 N/m", free_length=0.3)
    b.machine({"type": "linear", "stall": "2 N*m", "no_load": "150 rpm"})
    mech = lw.compile(b.build())
    result = lw.dynamics(mech)
    t, psi, omega = result.motion.cycle()
    phi = psi + result.motion.cycle_start

    def length(x):
        return np.hypot(0.1 * np.cos(x) - 0.5, 0.1 * np.sin(x) - 0.2)

    slope = (length(phi + 1e-6) - length(phi - 1e-6)) / 2e-6
    from scipy.integrate import simpson

    damper = simpson(c * slope**2 * omega, x=psi)
    motor = simpson(result.drive.moment(omega), x=psi)
    assert damper > 0.05 * motor
    assert motor == pytest.approx(damper, rel=1e-5)


def test_a_run_without_inertia_on_the_crank_is_one_clear_error():
    """A four-bar whose links have no mass: nothing to integrate, and the run says why instead of dividing by 0."""
    from mechanisms import four_bar_spec

    data, _ = four_bar_spec(0.1, 0.35, 0.25, 0.3, 1.0, False)
    with pytest.raises(lw.errors.LinkworkError, match="carries no inertia at [\\d.]+ deg to x"):
        simulate(lw.compile(lw.from_dict(data)), 0.1, speed=30.0)


def isosceles_slider_crank() -> lw.Mechanism:
    """A slider-crank whose rod is as long as its crank (0.1 m), the guide through the crank's pivot: at crank
    angles 90 and 270 deg the slider meets the pivot, the rod stands across the guide and the dyad's two
    assembly modes meet (its change points)."""
    b = MechanismBuilder("isosceles", units={"angle": "rad"}, gravity=0)
    b.frame(points={"O": (0, 0)})
    b.link("crank", ends=("O", "A"), length=0.1, mass=1.5, inertia="0.04 kg*m^2")
    b.link("rod", ends=("A", "B"), length=0.1, mass=0.2)
    b.link("slider", points={"B": (0, 0)}, mass=0.3)
    b.revolute("O", "frame", "crank").revolute("A", "crank", "rod").revolute("B", "rod", "slider")
    b.prismatic("guide", "frame", "slider", point="B", through="O", axis=0)
    b.drive("O", angle=0.3).hint("B", 0.2 * math.cos(0.3), 0)
    return lw.compile(b.build())


def test_a_run_through_the_change_points_of_an_isosceles_slider_crank_reports_them():
    """From 0.3 rad at 10 rad/s for 0.5 s the crank passes 90 and 270 deg (the rod across the guide, the
    closed form of its change points): each is a ``change-point`` event of the RRP dyad, at the run's time of
    that angle; the dense output's time of the angle agrees."""
    run = simulate(isosceles_slider_crank(), 0.5, angle=0.3, speed=10.0, motor=False)
    changes = [e for e in run.events if e.kind == "change-point"]
    assert [e.group for e in changes] == ["II(2,3) RRP"] * 2
    np.testing.assert_allclose([e.angle for e in changes], [math.pi / 2, 3 * math.pi / 2], atol=1e-7)
    times = np.interp([math.pi / 2, 3 * math.pi / 2], run.angle, run.time)  # the samples' angle rises
    np.testing.assert_allclose([e.time for e in changes], times, atol=2e-4)
    record = changes[0].as_dict()
    assert record["group"] == "II(2,3) RRP" and abs(record["angle_deg"] - 90) < 1e-5
    assert changes[1].describe().startswith("change point of group II(2,3) RRP at ")
    assert "270.0000 deg to x" in changes[1].describe()


def test_a_slider_crank_without_a_change_point_reports_none():
    """The slider-crank of :func:`slider_crank` (rod 3.5 cranks): its transmission never falls below 73 deg,
    a full turn reports no change point."""
    run = simulate(slider_crank(0.0), 0.3, angle=0.3, speed=30.0, motor=False)
    assert run.angle[-1] - run.angle[0] > 2 * math.pi
    assert not [e for e in run.events if e.kind == "change-point"]


def braked_rotor(torque: float, friction: float = 3.0, j: float = 0.05) -> lw.Mechanism:
    """A balanced rotor (its centre of mass on its pivot, own inertia ``j`` kg m^2, no gravity) with a Coulomb
    friction moment ``friction`` N m in its pivot and a motor of constant ``torque`` N m."""
    data = {
        "name": "braked-rotor",
        "gravity": 0,
        "frame": {"points": {"O": [0, 0]}},
        "links": {"rotor": {"points": {"O": [0, 0], "A": [0.1, 0]}, "mass": 1.0, "com": "O", "inertia": f"{j} kg*m^2"}},
        "joints": {"O": {"type": "revolute", "links": ["frame", "rotor"]}},
        "drives": [{"joint": "O", "angle": "0 deg", "speed": "30 rpm"}],
        "loads": {"brake": {"type": "friction", "joint": "O", "moment": f"{friction} N*m"}},
        "machine": {"motor": {"type": "constant", "torque": f"{torque} N*m"}},
    }
    return lw.compile(lw.from_dict(data))


def test_a_rotor_whose_motor_is_weaker_than_its_friction_stops_where_the_energy_says_and_stays():
    """Started at 10 rad/s with 1 N m against 3 N m of friction: it slows at (1 - 3) / J, stops at t = 10 J / 2
    having turned 100 J / 4 rad, and stays there (moving either way the friction would take more than the motor
    gives): a ``stop`` and a ``held`` event, the rest of the run at rest with the motor at its 1 N m."""
    j = 0.05
    run = simulate(braked_rotor(1.0, j=j), 1.0, speed=10.0, times=np.linspace(0, 1, 101))
    t_stop = 10.0 * j / 2.0
    assert [e.kind for e in run.events] == ["stop", "held"]
    assert run.events[0].time == pytest.approx(t_stop, rel=1e-9)
    assert run.events[0].angle == pytest.approx(100 * j / 4, rel=1e-9)
    after = run.time > t_stop
    np.testing.assert_array_equal(run.speed[after], 0.0)
    np.testing.assert_array_equal(run.acceleration[after], 0.0)
    np.testing.assert_allclose(run.angle[after], 100 * j / 4, rtol=1e-9)
    before = run.time < t_stop
    np.testing.assert_allclose(run.speed[before], 10.0 - 2.0 / j * run.time[before], rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(run.drive_moment, 1.0)
    assert "leave -2 N m to move it forward and 4 N m to move it back" in run.events[1].describe()


def test_a_rotor_held_by_its_friction_from_rest_costs_no_work_and_a_stronger_motor_starts_it():
    """From rest, 2.9 N m against 3 N m of friction: held at once (no integration); 3.5 N m: it turns with the
    constant acceleration (3.5 - 3) / J, phi = a t^2 / 2."""
    held = simulate(braked_rotor(2.9), 600.0)
    assert [e.kind for e in held.events] == ["held"] and held.evaluations == 0
    assert "-0.1 N m to move it forward" in held.events[0].describe()
    run = simulate(braked_rotor(3.5), 0.2, times=[0.0, 0.1, 0.2])
    np.testing.assert_allclose(run.angle, 0.5 * (0.5 / 0.05) * np.array([0.0, 0.1, 0.2]) ** 2, rtol=1e-9, atol=1e-12)
    assert not run.events


def test_a_motor_pushing_back_harder_than_the_friction_turns_the_rotor_back_after_its_stop():
    """-5 N m of motor against a rotor started forward at 4 rad/s with 3 N m of friction: forward it slows at
    (-5 - 3) / J, stops at 4 J / 8, then turns back at (-5 + 3) / J (the friction now against the motion back)."""
    j = 0.05
    run = simulate(braked_rotor(-5.0, j=j), 0.1, speed=4.0, times=[0.1])
    t1 = 4.0 * j / 8.0
    assert [e.kind for e in run.events] == ["stop"] and run.events[0].time == pytest.approx(t1, rel=1e-9)
    assert run.speed[0] == pytest.approx(-2.0 / j * (0.1 - t1), rel=1e-9)
    assert run.angle[0] == pytest.approx(4.0 * t1 / 2 - 1.0 / j * (0.1 - t1) ** 2, rel=1e-9)


def test_the_shears_started_in_the_cut_are_held_and_from_30_rpm_stop_in_it():
    """The double-cut shears at their assembly angle stand in the billet: from rest the motor's stall moment at the
    crank (the Kloss torque at slip 1 through the gear, far below the cut's 29 kN m) cannot start them, and from
    30 rpm the rotor's energy is spent in the cut.  Each run of 100 ms ends (the integrator used to step on at the
    stop with the time not advancing), held at rest to the end."""
    shears = lw.compile("double-cut-shears")
    drive = shears.motor_gear
    assert drive is not None
    motor = drive.motor
    s, sk = 1.0, motor.critical_slip
    stall = drive.ratio * drive.efficiency * 2 * motor.breakdown * motor.rated_torque * s * sk / (s * s + sk * sk)
    rest = simulate(shears, 0.1)
    assert [e.kind for e in rest.events] == ["held"] and rest.evaluations == 0
    np.testing.assert_allclose(rest.drive_moment, stall, rtol=1e-12)
    run = simulate(shears, 0.1, speed=math.pi)
    assert [e.kind for e in run.events] == ["stop", "held"]
    assert run.speed[-1] == 0.0 and 0 < run.events[0].time < 0.1


def test_the_fastest_rate_of_a_pendulum_is_its_closed_form_natural_frequency():
    """The pendulum with a torsion spring: small swings about hanging down at omega_n^2 = (k + m g l) / (J_C + m l^2),
    the fastest over the turn (gravity's stiffness m g l cos is greatest hanging down)."""
    from linkwork.machine.timerun import fastest_rate

    k = 1e6
    rate, at = fastest_rate(pendulum(k), -math.pi / 2)
    assert rate == pytest.approx(math.sqrt((k + M * G * L) / (JC + M * L * L)), rel=1e-6)
    assert abs(math.remainder(at + math.pi / 2, 2 * math.pi)) < 1e-12


def test_a_run_past_the_bound_on_its_work_is_refused_before_it_starts():
    """A 1e9 N/m spring (an allowed value) on the slider-crank swings the crank at some 3e4 rad/s: 200 ms of that
    is refused at once, naming the spring and the longest run within the bound."""
    import time

    began = time.monotonic()
    with pytest.raises(lw.errors.LinkworkError, match=r"past the bound on a run's work.*force elements: s\)") as info:
        simulate(slider_crank(1e9), 0.2, angle=0.3)
    assert time.monotonic() - began < 5
    longest = float(str(info.value).split("ask for at most ")[1].split(" s")[0])
    assert 0.001 < longest < 0.2


def test_a_run_longer_than_the_bound_is_refused():
    from linkwork.limits import MAX_RUN_TIME

    for until in (MAX_RUN_TIME * 1.0001, 1e9, math.inf, math.nan, 0.0, -1.0):
        with pytest.raises(lw.errors.LinkworkError, match="until: expected a run of more than 0 s and at most"):
            simulate(pendulum(), until)


def test_a_pendulum_at_rest_hanging_down_stays_there_for_the_longest_run():
    """At rest in its equilibrium the loads balance to rounding (4.8e-16 N m of gravity's cos(-pi/2)): the crank is
    held, the run of MAX_RUN_TIME costs no integration; 1 nrad off it swings (at 0.1 s, 1e-9 cos(omega_n 0.1))."""
    from linkwork.limits import MAX_RUN_TIME

    held = simulate(pendulum(), MAX_RUN_TIME, angle=-math.pi / 2)
    assert [e.kind for e in held.events] == ["held"] and held.evaluations == 0
    assert held.events[0].describe().endswith("they balance there")
    wn = math.sqrt((K + M * G * L) / (JC + M * L * L))
    off = simulate(pendulum(), 0.1, angle=-math.pi / 2 + 1e-9, times=[0.1])
    assert off.angle[0] + math.pi / 2 == pytest.approx(1e-9 * math.cos(wn * 0.1), rel=1e-6)


def test_a_run_past_a_change_point_goes_on_in_the_mode_of_the_cycle():
    """The isosceles slider-crank (OA = AB) passes change points at 0 and 180 deg, past which its cycle goes on in
    the other mode (the knife keeps moving, y_B = 2 l sin(phi)); the run in time solves each of its poses alone,
    and must take them in the cycle's modes: its reduced inertia at single angles all round the turn (a few off the
    change points) equals the one from finite differences of the cycle's positions, sum m |dr_C/dphi|^2 + J_C
    (dtheta/dphi)^2; and a run through 180 deg has the knife where the closed form puts it."""
    from linkwork.machine.timerun import cycle_of, reduced_terms

    mech = lw.compile(lw.example("shears-slider-crank"))
    cycle = cycle_of(mech)
    start = float(mech.drive_start[0])
    angles = start + np.radians(np.arange(0.0, 360.0, 7.3))
    expected = kinetic_and_potential_by_differences(mech, angles)[0]
    got = [reduced_terms(mech, np.array([a]), np.ones(1), 0.0, cycle).inertia[0] for a in angles]
    np.testing.assert_allclose(got, expected, rtol=1e-6)
    run = simulate(mech, 0.4, speed=10.0, motor=False, times=np.linspace(0.0, 0.4, 21))
    assert run.angle[-1] > math.pi + 0.5  # through 180 deg
    np.testing.assert_allclose(run.kinematics.position("B")[:, 1], 2 * 0.15 * np.sin(run.angle), atol=1e-9)


def test_friction_in_proportion_to_the_pin_force_slows_a_run_as_its_closed_form_says():
    """A balanced rotor of 10 kg (its centre of mass on its pivot, 0.05 kg m^2) under gravity, its pin of 20 mm
    with f = 0.15: the pin carries the weight alone, so its friction is the constant moment f r m g = 0.2943 N m.
    Started at 10 rad/s against a motor of 0.1 N m it slows at (0.1 - 0.2943) / J, stops at 10 J / 0.1943 s having
    turned 100 J / (2 x 0.1943) rad, and is held (the runs in time took no friction of the pairs before: the rotor
    ran on at 10 rad/s)."""
    f, r, m, g, j = 0.15, 0.020, 10.0, 9.81, 0.05
    data = {
        "name": "rotor-in-a-rough-pin",
        "frame": {"points": {"O": [0, 0]}},
        "links": {"rotor": {"points": {"O": [0, 0], "A": [0.1, 0]}, "mass": m, "com": "O", "inertia": f"{j} kg*m^2"}},
        "joints": {"O": {"type": "revolute", "links": ["frame", "rotor"], "friction": {"f": f, "radius": f"{r} m"}}},
        "drives": [{"joint": "O", "angle": "0 deg", "speed": "30 rpm"}],
        "machine": {"motor": {"type": "constant", "torque": "0.1 N*m"}},
    }
    mech = lw.compile(lw.from_dict(data))
    assert mech.gravity == pytest.approx(g)
    moment = f * r * m * g
    slows = (moment - 0.1) / j
    run = simulate(mech, 3.0, speed=10.0, times=np.linspace(0, 3, 31))
    assert [e.kind for e in run.events] == ["stop", "held"]
    assert run.events[0].time == pytest.approx(10.0 / slows, rel=1e-9)
    assert run.events[0].angle == pytest.approx(100.0 / (2 * slows), rel=1e-9)
    before = run.time < run.events[0].time
    np.testing.assert_allclose(run.speed[before], 10.0 - slows * run.time[before], rtol=1e-9, atol=1e-9)
    assert np.all(run.speed[~before] == 0.0)
