"""Machine dynamics: reduced quantities against finite differences, energy and power balances,
the flywheel by the energy method against simulation, closed forms of start-up and of the motor."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

import linkwork as lw
from linkwork.machine import (
    ConstantTorque,
    InductionMotor,
    LinearMotor,
    MotorGear,
    constant_moment_cycle,
    run_turns,
    size_flywheel,
)
from linkwork.machine.simulation import Model
from mechanisms import kinetic_and_potential_by_differences, rotor


@pytest.mark.parametrize("name", ["four-bar", "double-cut-shears", "watt-six-bar"])
def test_reduced_inertia_and_gravity_moment_against_finite_differences(name):
    mech = lw.compile(lw.example(name))
    red = lw.reduced(mech, steps=720)
    inertia, dvdphi = kinetic_and_potential_by_differences(mech, red.angle)
    np.testing.assert_allclose(red.inertia, inertia, rtol=1e-6)
    slope = (np.roll(red.inertia, -1) - np.roll(red.inertia, 1)) / (2 * (red.psi[1] - red.psi[0]))
    np.testing.assert_allclose(red.inertia_slope, slope, rtol=0, atol=1e-3 * np.abs(red.inertia_slope).max())
    if not mech.loads:
        sign = -1.0 if mech.drive_speed[0] < 0 else 1.0
        np.testing.assert_allclose(red.load, -sign * dvdphi, rtol=0, atol=1e-6 * np.abs(red.load).max())


def test_reduced_load_of_the_shears_does_the_cutting_work():
    red = lw.reduced(lw.compile(lw.example("double-cut-shears")), steps=7200)
    assert red.work()[-1] == pytest.approx(-0.10 * 250e3 * 0.30, rel=2e-4)  # gravity gives nothing back


def test_periodic_splines_name_each_columns_value_slope_and_curvature():
    """``PeriodicSplines.at`` gives each column, in the order given, as its value and its first and
    second derivatives in the turning angle: against the closed forms of sin(psi) and cos(2 psi)."""
    from linkwork.machine.simulation import PeriodicSplines

    psi = 2 * np.pi * np.arange(720) / 720
    splines = PeriodicSplines(psi, [np.sin(psi), np.cos(2 * psi)])
    for x in (0.1234, 2.5, 6.2):
        first, second = splines.at(x)
        assert (first.value, first.slope, first.curvature) == pytest.approx(
            (math.sin(x), math.cos(x), -math.sin(x)), abs=1e-5
        )
        assert (second.value, second.slope, second.curvature) == pytest.approx(
            (math.cos(2 * x), -2 * math.sin(2 * x), -4 * math.cos(2 * x)), abs=1e-4
        )


@pytest.mark.parametrize("k", [3, 5, 360, 3600, 36000])
def test_periodic_cubic_is_the_periodic_spline_through_the_points(k):
    """The spline's defining conditions round the period, the wrap included: each cubic passes through its
    two points and meets the next with the same slope and curvature (to rounding of the largest); and it is
    SciPy's periodic ``CubicSpline`` (another solve of the same system) where evaluated, within the
    conditioning of that system (the curvatures of noisy data at 36,000 points are 1e8 times the data)."""
    from scipy.interpolate import CubicSpline

    from linkwork.machine.simulation import periodic_cubic

    h = 2 * np.pi / k
    psi = h * np.arange(k)
    y = np.random.default_rng(k).normal(size=k) + 3 * np.sin(psi)
    c3, c2, c1, c0 = periodic_cubic(y, h).T
    end, slope, curvature = ((c3 * h + c2) * h + c1) * h + c0, (3 * c3 * h + 2 * c2) * h + c1, 6 * c3 * h + 2 * c2
    np.testing.assert_array_equal(c0, y)
    np.testing.assert_allclose(end, np.roll(y, -1), rtol=0, atol=1e-14 * np.abs(y).max())
    np.testing.assert_allclose(slope, np.roll(c1, -1), rtol=0, atol=1e-14 * np.abs(c1).max())
    np.testing.assert_allclose(curvature, np.roll(2 * c2, -1), rtol=0, atol=1e-14 * np.abs(c2).max())
    x = np.random.default_rng(0).uniform(0, 2 * np.pi, 1000)
    i = np.minimum((x / h).astype(int), k - 1)
    u = x - i * h
    ours = ((c3[i] * u + c2[i]) * u + c1[i]) * u + c0[i]
    scipy = CubicSpline(np.append(psi, 2 * np.pi), np.append(y, y[0]), bc_type="periodic")(x)
    np.testing.assert_allclose(ours, scipy, rtol=0, atol=1e-15 * k * np.abs(y).max())


def test_energy_of_the_free_mechanism_is_conserved():
    """No drive, no loads, no friction: J(psi) omega^2 / 2 stays put (to 1e-8 per turn)."""
    red = lw.reduced(lw.compile(lw.example("four-bar")), steps=720)
    red = dataclasses.replace(red, load=np.zeros_like(red.load))
    run = run_turns(red, MotorGear(ConstantTorque(0.0)), omega0=5.0, turns=4, tol=0.0, rtol=1e-12)
    model = Model(red)
    energy = np.array([0.5 * model.at(p)[0] * w * w for p, w in zip(run.psi, run.omega, strict=True)])
    assert len(run.turns) == 4
    ends = np.array([0.5 * model.at(0.0)[0] * turn.omega_end**2 for turn in run.turns])  # psi back at 0
    assert np.max(np.abs(ends - energy[0]) / energy[0] / np.arange(1, 5)) < 1e-8
    assert np.ptp(energy) / energy[0] < 1e-7  # and within the turns
    assert np.ptp(run.omega) > 0.01  # the speed does vary
    # the time of a turn, integral of sqrt(J / 2E) dpsi: the periodic trapezoid rule on the exact J
    period = np.mean(np.sqrt(red.inertia / (2 * energy[0]))) * 2 * np.pi
    for turn in run.turns:
        assert turn.end - turn.start == pytest.approx(period, rel=1e-9)


def test_steady_cycle_mean_drive_power_equals_mean_load_power():
    mech = lw.compile(lw.example("double-cut-shears"))
    motor = InductionMotor(5500.0, 1450 * math.pi / 30, 1500 * math.pi / 30, 2.2)
    result = lw.dynamics(mech, MotorGear(motor, ratio=1450 / 30, rotor=0.03, flywheel_on="motor"), delta=0.05)
    assert result.motion.steady
    t, psi, omega = result.motion.cycle()
    drive_work = np.trapezoid(result.drive.moment(omega) * omega, t)  # the motor's torque is smooth in time
    load_work = result.reduced.work()[-1]  # exact for the model's piecewise linear load moment
    model = Model(result.reduced, result.drive.inertia)
    j = model.at(result.motion.psi[-1])[0]
    change = 0.5 * j * (omega[-1] ** 2 - omega[0] ** 2)  # zero but for the last bit of the approach
    assert drive_work + load_work - change == pytest.approx(0.0, abs=1e-5 * drive_work)
    assert drive_work / t[-1] == pytest.approx(result.drive_power, rel=1e-3)
    # the flywheel sized by the energy method holds delta within 5 % in the simulated cycle
    assert result.delta == pytest.approx(0.05, rel=0.05)
    assert result.startup_time > 0


def test_flywheel_energy_method_against_the_exact_cycle_and_the_simulation():
    """Under the constant drive moment that balances the loads, the energy integral gives the exact
    cycle; the simulation must follow it, and its delta must be the energy method's within 5 %."""
    red = lw.reduced(lw.compile(lw.example("double-cut-shears")), steps=3600)
    omega_m = math.pi
    fly = size_flywheel(red, 0.05, omega_m)
    omega, delta = constant_moment_cycle(red, fly.inertia, omega_m)
    assert delta == pytest.approx(0.05, rel=0.05)
    drive = MotorGear(ConstantTorque(fly.drive_moment), flywheel=fly.inertia)
    run = run_turns(red, drive, omega0=float(omega[0]), turns=1, rtol=1e-12)
    exact = np.interp(run.psi, np.append(red.psi, 2 * np.pi), np.append(omega, omega[0]))
    np.testing.assert_allclose(run.omega, exact, rtol=2e-5)
    assert fly.drive_power == pytest.approx(-red.mean_load * omega_m)


def test_constant_torque_start_up_with_constant_inertia():
    """A crank balanced about its pivot: J constant, no load; under a torque M it turns through
    2 pi k at t_k = sqrt(4 pi k J / M), with omega = M t / J."""
    b = lw.MechanismBuilder("flywheel", units={"angle": "deg"})
    b.frame(points={"O": (0, 0)}).link("crank", ends=("O", "A"), length=0.2, mass=5.0, com="O", inertia=0.7)
    b.revolute("O", "frame", "crank").drive("O", speed="60 rpm")
    red = lw.reduced(lw.compile(b.build()), steps=64)
    np.testing.assert_allclose(red.inertia, 0.7, rtol=1e-12)
    run = run_turns(red, MotorGear(ConstantTorque(10.0)), turns=3, tol=0.0)
    for k, turn in enumerate(run.turns, 1):
        t = math.sqrt(4 * math.pi * k * 0.7 / 10.0)
        assert turn.end == pytest.approx(t, rel=1e-9)
        assert turn.omega_max == pytest.approx(10.0 * t / 0.7, rel=1e-9)


def test_induction_motor_by_the_kloss_formula():
    motor = InductionMotor(5500.0, 1450 * math.pi / 30, 1500 * math.pi / 30, 2.2)
    rated = 5500.0 / (1450 * math.pi / 30)
    assert motor(1450 * math.pi / 30) == pytest.approx(rated, rel=1e-12)
    assert motor(1500 * math.pi / 30) == 0.0
    slip = (1 / 30) * (2.2 + math.sqrt(2.2**2 - 1))  # s_k = s_n (lambda + sqrt(lambda^2 - 1))
    assert motor((1 - slip) * 1500 * math.pi / 30) == pytest.approx(2.2 * rated, rel=1e-12)
    grid = np.linspace(0, 1500 * math.pi / 30, 2001)
    assert motor(grid).max() == pytest.approx(2.2 * rated, rel=1e-5)  # the breakdown torque is the peak
    with pytest.raises(lw.errors.LinkworkError, match="synchronous"):
        InductionMotor(5500.0, 1600 * math.pi / 30, 1500 * math.pi / 30)


@pytest.mark.parametrize(
    "motor",
    [
        InductionMotor(5500.0, 1450 * math.pi / 30, 1500 * math.pi / 30, 2.2),
        ConstantTorque(12.5),
        LinearMotor(40.0, 150.0),
    ],
)
def test_a_drive_gives_one_speed_the_moment_it_gives_an_array_of_speeds(motor):
    """The simulation asks the drive for the moment at one speed (a Python float) at every step: the same
    numbers, to the last bit, as at that speed among an array's, on either side of the rated speed."""
    drive = MotorGear(motor, ratio=48.33, efficiency=0.9)
    speeds = np.linspace(0.0, 1500 * math.pi / 30 / 48.33 * 1.01, 97)
    at_once = drive.moment(speeds)
    one_by_one = [drive.moment(float(w)) for w in speeds]
    assert all(type(m) is float for m in one_by_one)
    np.testing.assert_array_equal(one_by_one, at_once)


def test_dynamics_command_on_the_double_cut_shears(tmp_path):
    """30 cuts a minute through a 48.33 gear from a 5.5 kW induction motor, flywheel sized for
    delta = 0.05: the run holds it, and the motor's mean power times the gear's efficiency is the
    cutting work per second (7500 J a cut)."""
    from typer.testing import CliRunner

    import linkwork.cli.dynamics  # noqa: F401 - registers the command
    from linkwork.cli.main import app

    result = CliRunner().invoke(app, ["dynamics", "double-cut-shears", "--json", "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    out = json.loads(result.stdout)
    for key in ("reduced_inertia", "omega", "delta", "flywheel_inertia", "mean_power", "drive_power", "startup_time"):
        assert key in out
    assert out["delta"] == pytest.approx(0.05, rel=0.05)
    # the motor's mean power at its shaft, integrated from its torque and speed over the cycle
    cycle = out["cycle"]
    motor_work = np.trapezoid(cycle["motor_power"], cycle["t"])
    assert out["mean_power"] == pytest.approx(motor_work / cycle["t"][-1], rel=1e-3)
    assert out["drive_power"] == pytest.approx(0.95 * out["mean_power"], rel=1e-9)
    cuts_per_second = out["omega_mean"] / (2 * math.pi)
    assert out["drive_power"] == pytest.approx(7500.0 * cuts_per_second, rel=1e-3)
    assert 29.0 < out["omega_mean"] * 30 / math.pi < 31.0
    assert (tmp_path / "dynamics.csv").read_text().startswith("psi [deg],t [s],omega [rad/s]")
    bare = CliRunner().invoke(app, ["dynamics", "four-bar"])
    assert bare.exit_code == 2 and 'give a "machine:" section' in bare.stderr
    assert "MotorGear" not in bare.stderr  # nothing the command line cannot give
    bad = CliRunner().invoke(app, ["dynamics", "double-cut-shears", "--delta", "2"])
    assert bad.exit_code == 2 and "--delta" in bad.stderr


@pytest.mark.parametrize(("name", "speed"), [("double-cut-shears", math.pi), ("four-bar", 2 * math.pi)])
def test_wittenbauer_tangents_are_exact_under_a_constant_drive_moment(name, speed):
    """The flywheel from the tangents to Wittenbauer's diagram gives, in the exact cycle of the
    energy integral, the delta asked for; Merkalov's approximation comes within 5 %."""
    from linkwork.machine import size_flywheel_wittenbauer

    red = lw.reduced(lw.compile(lw.example(name)), steps=3600)
    for delta in (0.02, 0.05, 0.2):
        exact = size_flywheel_wittenbauer(red, delta, speed)
        assert constant_moment_cycle(red, exact.inertia, speed)[1] == pytest.approx(delta, rel=1e-9)
        approx = size_flywheel(red, delta, speed)
        assert approx.inertia == pytest.approx(exact.inertia, rel=0.05)


@pytest.mark.slow  # over the default lane's budget on the NumPy kernels (tests/conftest.py)
def test_the_flywheel_is_given_on_its_shaft_and_reduced_to_the_crank():
    """The double-cut shears size a flywheel for the motor shaft (gear 48.33): ``run.flywheel.flywheel`` is
    the inertia on that shaft, the one the run turned; reduced to the crank it is u^2 times as much, and
    with the rotor's u^2 J_r it makes up the constant inertia the energy method asked for on the crank."""
    mech = lw.compile(lw.example("double-cut-shears"))
    run = lw.dynamics(mech, steps=720)
    fly, u = run.flywheel, 48.33
    assert fly.shaft == "motor" and fly.ratio == u
    assert fly.flywheel == run.drive.flywheel
    assert fly.on_crank == pytest.approx(fly.flywheel * u**2, rel=1e-12)
    assert fly.inertia == pytest.approx(fly.on_crank + 0.03 * u**2, rel=1e-12)
    assert run.drive.inertia == pytest.approx(fly.inertia, rel=1e-12)
    on_crank = lw.dynamics(mech, MotorGear(run.drive.motor, u, 0.95, 0.03, flywheel_on="crank"), steps=720)
    assert on_crank.flywheel.flywheel == pytest.approx(fly.on_crank, rel=1e-12)
    assert on_crank.flywheel.flywheel == on_crank.drive.flywheel
    assert on_crank.delta == pytest.approx(run.delta, rel=1e-6)  # the same constant inertia on the crank


def test_mean_power_is_the_motors_at_its_shaft_and_drive_power_the_cranks():
    """Over the steady cycle: ``mean_power`` is the motor's torque times its speed, integrated in time
    from the simulated run; ``drive_power`` is what reaches the crank after the gear's loss (eta = 0.95);
    the same names mean the same in the working cycle of ``simulate_blows``."""
    mech = lw.compile(lw.example("double-cut-shears"))
    run = lw.dynamics(mech, steps=720)
    t, psi, omega = run.motion.cycle()
    u = run.drive.ratio
    motor = np.trapezoid(run.drive.motor(u * omega) * u * omega, t) / t[-1]
    assert run.mean_power == pytest.approx(motor, rel=1e-3)
    assert run.drive_power == pytest.approx(0.95 * motor, rel=1e-3)
    work = -run.reduced.work()[-1]  # the loads' work a turn, from the reduced load moment
    assert run.drive_power == pytest.approx(work / t[-1], rel=1e-3)


def test_delta_holds_to_the_integrations_tolerance_whatever_the_last_bits_of_the_kinematics(monkeypatch):
    """The compiled and the NumPy kernels give the reduced quantities to 1e-15 but not bit for bit, and the
    simulated delta of the double-cut shears then differs by 6.9e-8 (relative): the run's adaptive steps
    move with the last bits.  So it does here with the reduced inertia scaled by 1 + 4e-16, a change below
    the kernels' difference; the simulated delta stays within 1e-6 (the run's tolerance) of itself."""
    import importlib

    module = importlib.import_module("linkwork.machine.steady_cycle")
    mech = lw.compile("double-cut-shears")
    plain = lw.dynamics(mech).delta
    exact = module.reduced

    def nudged(m, *, steps):
        red = exact(m, steps=steps)
        return dataclasses.replace(red, inertia=red.inertia * (1 + 4e-16))

    monkeypatch.setattr(module, "reduced", nudged)
    moved = lw.dynamics(mech).delta
    assert moved != plain  # the last bits do move the run
    assert abs(moved - plain) < 1e-6 * plain


#: A crank of 2 kg with its centre of mass at (80, 30) mm in its own axes, a distance r_c from its pivot, and its own
#: inertia 0.01 kg m^2; the coupler and the rocker have no mass.  Its reduced inertia is constant, J = m r_c^2 + J_C,
#: and its weight's work over the turn is zero: the energy swings between +-m g r_c about its mean, dE = 2 m g r_c,
#: and the energy method's flywheel for delta at omega is J_c = 2 m g r_c / (delta omega^2) (the tangents' one is that
#: less J, the mechanism's own).
ROTOR = rotor(63)


@pytest.mark.parametrize("steps", [360, 720])
def test_the_flywheel_is_the_closed_form_whatever_the_grid(steps, tmp_path):
    """The rotor's energy peaks and bottoms out between the points of 360 and 720 steps (its weight's work read off
    the grid missed the swing by 5.5e-5 and 6.8e-6); with the work integrated between the points and its extremes
    refined by the rule of every peak, the energy method and Wittenbauer's tangents give the closed form to 1e-9."""
    from linkwork.machine import size_flywheel_wittenbauer

    path = tmp_path / "rotor.yaml"
    path.write_text(ROTOR, encoding="utf-8")
    red = lw.reduced(lw.compile(lw.load(path)), steps=steps)
    mass, g, r_c, delta, omega = 2.0, 9.81, math.hypot(0.08, 0.03), 0.05, 10.0
    expected = 2 * mass * g * r_c / (delta * omega**2)
    assert size_flywheel(red, delta, omega).energy_swing == pytest.approx(2 * mass * g * r_c, rel=1e-9)
    assert size_flywheel(red, delta, omega).inertia == pytest.approx(expected, rel=1e-9)
    own = mass * r_c**2 + 0.01
    assert size_flywheel_wittenbauer(red, delta, omega).inertia == pytest.approx(expected - own, rel=1e-9)


@pytest.mark.slow  # over the default lane's budget on the NumPy kernels (tests/conftest.py)
def test_the_flywheel_of_the_shears_does_not_depend_on_the_grid():
    """The double-cut shears' knives meet the billet between the points of any grid (a kink of the load): the flywheel
    for delta 0.05 at pi rad/s from 360 and 720 steps differed by 1.9e-3 (14302.2 and 14329.3 kg m^2); integrated
    between the points and refined, they agree to 1e-9, and the exact cycle under the constant drive moment gives the
    delta asked for at either grid."""
    from linkwork.machine import size_flywheel_wittenbauer

    mech = lw.compile("double-cut-shears")
    found = {}
    for steps in (360, 720):
        red = lw.reduced(mech, steps=steps)
        found[steps] = size_flywheel_wittenbauer(red, 0.05, math.pi).inertia
        assert constant_moment_cycle(red, found[steps], math.pi)[1] == pytest.approx(0.05, rel=1e-9)
    assert found[360] == pytest.approx(found[720], rel=1e-9)


def _shears_with_springs(tmp_path, n):
    """The double-cut shears with ``n`` springs from the crank pin to the rocker's pivot (stiffness 1000 + i N/m,
    free length 0.3 m)."""
    from importlib.resources import files

    text = (files("linkwork") / "examples" / "double-cut-shears.yaml").read_text(encoding="utf-8")
    springs = "".join(
        f"  s{i}: {{type: spring, between: [crank.A, O3], stiffness: {1000 + i} N/m, free_length: 0.3}}\n"
        for i in range(n)
    )
    path = tmp_path / f"shears-{n}.yaml"
    path.write_text(text.replace("loads:\n", "loads:\n" + springs, 1), encoding="utf-8")
    return lw.compile(str(path))


def test_memory_of_the_reduction_does_not_grow_with_the_springs(tmp_path):
    """Each spring's forces are evaluated over the turn and their power added before the next spring is evaluated:
    the peak memory of the reduction (3,600 angles) grows by less than one float a sample for each spring added
    (28.8 kB; it held 13 floats a sample, 375 kB, for each before), and the springs' reduced moment is minus the
    slope of their potential energy (central differences of k (L - L0)^2 / 2 over the crank angle)."""
    import tracemalloc

    from linkwork.kinetostatics.elements import potential
    from linkwork.machine.reduction import reduced

    plain, sprung = _shears_with_springs(tmp_path, 0), _shears_with_springs(tmp_path, 20)
    peaks = []
    for mech in (plain, sprung):
        reduced(mech, steps=64)  # imports and caches out of the count
        tracemalloc.start()
        red = reduced(mech)
        peaks.append(tracemalloc.get_traced_memory()[1])
        tracemalloc.stop()
    assert (peaks[1] - peaks[0]) / 20 < 3600 * 8
    springs = reduced(sprung).load - reduced(plain).load
    h = 1e-6
    sign = -1.0 if sprung.drive_speed[0] < 0 else 1.0
    energy = [potential(lw.kinematics(sprung, red.angle + sign * d)).ravel() for d in (h, -h)]
    slope = (energy[0] - energy[1]) / (2 * h)
    np.testing.assert_allclose(springs, -slope, rtol=1e-6, atol=1e-6 * np.abs(springs).max())
