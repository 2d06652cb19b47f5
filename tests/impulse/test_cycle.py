"""The working cycle of the percussion mechanism (seed 004's machine): energy between and across the
impacts, impulse-momentum balance of every blow, the contact phase's force, blows per minute."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork as lw
from linkwork.errors import LinkworkError
from linkwork.impulse import SlidingReversal, Tool, simulate_blows, strike
from linkwork.machine import ConstantTorque, LinearMotor, MotorGear

MECH = lw.compile(lw.example("percussion-rocker"))
UP = (0.0, 1.0)
SIGN = -1.0  # the crank turns clockwise


@pytest.fixture(scope="module")
def example():
    """The bundled example's run to its steady cycle."""
    return simulate_blows(MECH)


def _pose(angles):
    """Exact kinetic-energy inertia, potential energy of gravity and the striker's transfer functions
    per sample, from the kinematics (not from the splines the simulation integrates)."""
    from linkwork.kinetostatics.reactions import inertia_and_gravity
    from linkwork.motion import kinematics

    kin = kinematics(MECH, np.asarray(angles), speed=SIGN)
    state = inertia_and_gravity(kin)
    vc, com = state.com_velocity[0], state.com[0]
    ac = state.com_acceleration[0]
    w, e = kin.vel[0, :, :, 2], kin.acc[0, :, :, 2]
    m, j = MECH.link_mass, MECH.link_inertia
    inertia = np.sum(m * np.sum(vc * vc, -1) + j * w * w, -1)
    slope = 2 * np.sum(m * np.sum(vc * ac, -1) + j * w * e, -1)
    potential = MECH.gravity * np.sum(m * com[..., 1], -1)
    gravity_moment = -MECH.gravity * np.sum(m * vc[..., 1], -1)
    _, g, h = kin.motion_of("rocker.K")
    return inertia, slope, potential, gravity_moment, g[0], h[0]


def _segments(run):
    """Index ranges of the solver's segments (an event ends each: the same time twice)."""
    cuts = np.flatnonzero(np.diff(run.t) == 0) + 1
    return np.split(np.arange(len(run.t)), cuts)


def test_energy_is_conserved_between_impacts_without_motor_and_friction():
    """No motor, no friction, no resistance of the work: between the impacts (and the tool's stops
    on its seat) the kinetic energy of mechanism, flywheel and tool, gravity's potential and the
    feed's ``F u`` add up to a constant, evaluated from the exact kinematics."""
    drive = MotorGear(ConstantTorque(0.0), flywheel=0.6)
    tool = Tool(mass=3.0, feed=250.0)
    run = simulate_blows(MECH, drive, tool=tool, friction=0.0, blows=3, tol=0.0)
    inertia, _, potential, _, _, _ = _pose(MECH.drive_start[0] + SIGN * run.psi)
    energy = 0.5 * (inertia + 0.6) * run.omega**2 + potential + 0.5 * tool.mass * run.v**2 + tool.feed * run.u
    scale = float(np.max(0.5 * (inertia + 0.6) * run.omega**2))
    checked = 0
    worst = 0.0
    for idx in _segments(run):
        if len(idx) > 1:
            worst = max(worst, float(np.max(np.abs(energy[idx] - energy[idx[0]]))) / scale)
            checked += 1
    assert checked > 10
    assert set(run.mode) == {0, 1, 2}  # flight, apart and contact all took part
    assert worst < 1e-8, worst
    # and the impacts did lose energy (R = 0.4): the crank slowed from blow to blow
    speeds = [b.crank_speed_before for b in run.blows]
    assert speeds[1] < speeds[0] - 0.1


def test_energy_balance_over_the_run_with_the_motor(example):
    """Motor work = change of kinetic energy + losses in the blows, the rebounds and on the seat +
    work on the work + friction, over the whole run and over the steady cycle; the work on the work
    is the resistance times the tool's travel into it; the cycle is steady."""
    run = example
    assert run.steady
    e = run.energy
    assert abs(run.balance) < 1e-7 * e["motor"]
    c = run.cycle_energy
    spent = c["kinetic"] + c["blows"] + c["rebounds"] + c["seat"] + c["work"] + c["friction"]
    assert c["drive"] + c["loads"] == pytest.approx(spent, rel=1e-7)  # at the crank
    assert abs(c["kinetic"]) < 1e-5 * c["motor"]  # steady: the speed comes back
    assert abs(c["loads"]) < 1e-6 * c["motor"]  # gravity gives nothing over a turn
    for b in run.blows:
        assert b.work_on_work == pytest.approx(run.tool.resistance * b.penetration, rel=1e-7)
    assert c["work"] == pytest.approx(run.last.work_on_work, rel=1e-9)
    assert min(c[k] for k in ("blows", "rebounds", "seat", "work", "friction", "gear")) > 0


def test_the_motor_works_at_its_own_shaft_and_the_gear_takes_its_share(example):
    """The motor's work over the cycle is its own moment times its shaft's speed, ratio times the
    crank's (the motor's characteristic, not the drive's moment on the crank), integrated over the
    sampled crank speed (Simpson's rule on a cubic resampling of each stretch between impacts); the
    gear takes 1 - eta of it."""
    from scipy.integrate import simpson
    from scipy.interpolate import CubicSpline

    run, drive = example, MECH.motor_gear
    motor = 0.0
    for idx in _segments(run):
        t, w = run.t[idx], run.omega[idx]
        if t[0] < run.last.time or len(t) < 2:
            continue
        fine = np.linspace(t[0], t[-1], 2001)
        shaft = drive.ratio * (CubicSpline(t, w)(fine) if len(t) > 3 else np.interp(fine, t, w))
        motor += simpson(np.asarray(drive.motor(shaft)) * shaft, x=fine)
    c = run.cycle_energy
    assert c["motor"] == pytest.approx(motor, rel=1e-4)  # agrees to 1.1e-5
    assert c["gear"] == pytest.approx((1 - drive.efficiency) * motor, rel=1e-4)
    assert drive.efficiency < 1 and c["drive"] < c["motor"]


def _check_blow_balances(b, tool_mass, drive_inertia, restitution, friction):
    """Each link's change of momentum and of angular momentum about its centre of mass equals the
    impulses on it (joints read back from the per-joint table, the blow's, the drive's); the tool's
    momentum, Newton's restitution and the friction ratio."""
    from linkwork.motion import kinematics

    kin = kinematics(MECH, np.array([b.angle]), speed=SIGN)
    gain = kin.vel[0, 0]  # per unit turning speed
    dw = b.crank_speed_after - b.crank_speed_before
    scale = np.abs(b.impulse).max()
    pos = {name: kin.position(name)[0] for name in b.joints}
    k_pos = kin.position("rocker.K")[0]
    for i, name in enumerate(MECH.link_names[1:], 1):
        q = kin.pose[0, 0, i]
        c, s = np.cos(q[2]), np.sin(q[2])
        lc = MECH.link_com[i]
        rc = np.array([c * lc[0] - s * lc[1], s * lc[0] + c * lc[1]])
        com = q[:2] + rc
        dv = gain[i] * dw
        dvc = dv[:2] + dv[2] * np.array([-rc[1], rc[0]])
        total, moment = np.zeros(2), 0.0
        for joint, impulse in b.joints.items():
            first, second = b.joint_links[joint]
            f = impulse if name == second else -impulse if name == first else None
            if f is None:
                continue
            arm = pos[joint] - com
            total += f
            moment += arm[0] * f[1] - arm[1] * f[0]
        if name == "rocker":
            arm = k_pos - com
            total += b.impulse
            moment += arm[0] * b.impulse[1] - arm[1] * b.impulse[0]
        if name == "crank":
            moment += b.drive_impulse
        np.testing.assert_allclose(total, MECH.link_mass[i] * dvc, rtol=0, atol=1e-12 * scale)
        assert moment == pytest.approx(MECH.link_inertia[i] * dv[2], abs=1e-12 * scale)
    # the drive's impulse is what the flywheel and rotor lose, -J_d dw in the turning direction
    # (clockwise here), as a counter-clockwise moment
    assert b.drive_impulse == pytest.approx(SIGN * -drive_inertia * dw, rel=1e-10, abs=1e-14)
    # the tool: its momentum takes the normal impulse; the closing speed reverses times R
    assert tool_mass * b.tool_speed == pytest.approx(b.impulse[1], rel=1e-12)
    g = kin.velocity("rocker.K")[0]  # dK/dpsi: the kinematics at unit turning speed
    before = g[1] * b.crank_speed_before
    after = g[1] * b.crank_speed_after + b.tool_speed
    assert -before == pytest.approx(b.impact_speed, rel=1e-12)
    assert after == pytest.approx(restitution * b.impact_speed, rel=1e-10, abs=1e-12)
    # friction: the tangential impulse opposes the sliding of K on the tool (which moves along n only,
    # t = (1, 0)), before and after the blow alike (the crank keeps turning), in the ratio f
    assert abs(b.impulse[0]) == pytest.approx(friction * b.impulse[1], rel=1e-12, abs=1e-12 * b.impulse[1])
    if friction > 0:
        assert b.impulse[0] * g[0] * b.crank_speed_before < 0
        assert b.impulse[0] * g[0] * b.crank_speed_after < 0


def test_each_blow_balances_impulse_and_momentum(example):
    drive = MECH.motor_gear
    for b in example.blows[:2] + example.blows[-1:]:
        _check_blow_balances(b, 3.0, drive.inertia, 0.4, 0.15)


@pytest.mark.parametrize(("restitution", "friction"), [(0.4, 0.0), (0.0, 0.15)])
def test_a_tool_that_cannot_move_and_no_drive_inertia_is_the_impact_of_the_whole_mechanism(restitution, friction):
    """``strike`` with an infinitely heavy tool and no flywheel is ``linkwork.impact`` (an independent
    implementation: the generalised impulse from the reduced inertia, the jump of every link): elastic
    without friction, and plastic with friction (the crank stopped dead, the sliding ending with the
    impact)."""
    angle = float(MECH.drive_start[0])
    ref = lw.impact(MECH, at="rocker.K", normal=UP, omega_before=-30.0, restitution=restitution, friction=friction)
    crank = ref.speed_before * SIGN  # turning speed
    s = strike(
        MECH, at="rocker.K", normal=UP, angle=angle, crank_speed=crank, restitution=restitution, friction=friction
    )
    np.testing.assert_allclose(s.impulse, ref.impulse, rtol=1e-12)
    assert s.omega_before == pytest.approx(-30.0, rel=1e-12)
    assert s.omega_after == pytest.approx(30.0 * restitution, rel=1e-12, abs=1e-12)
    assert s.energy_lost == pytest.approx(ref.energy_loss, rel=1e-12)
    for joint, impulse in ref.joints.items():
        np.testing.assert_allclose(s.joints[joint], impulse, rtol=0, atol=1e-12 * np.abs(ref.impulse).max())
    # a flywheel on the crank and a tool that gives way make the blow softer, the drive feels it
    soft = strike(
        MECH,
        at="rocker.K",
        normal=UP,
        angle=angle,
        crank_speed=crank,
        restitution=0.4,
        friction=0.15,
        tool_mass=3.0,
        drive_inertia=0.7,
    )
    assert soft.crank_speed_after > 0 and abs(soft.drive_impulse) > 0
    assert soft.tool_speed_after * 3.0 == pytest.approx(soft.impulse[1], rel=1e-12)


def test_a_blow_that_would_reverse_the_sliding_is_refused():
    """A tool that cannot move, R = 0.4 and friction: the crank is thrown back (psi'_+ = -R psi'_-), so
    the striker's sliding on the tool, ``(dK/dpsi . t) psi'`` in a chain of one degree of freedom,
    would reverse inside the impact; the map assumes one friction sign throughout and says so."""
    angle = float(MECH.drive_start[0])
    with pytest.raises(SlidingReversal, match="slides one way throughout"):
        strike(MECH, at="rocker.K", normal=UP, angle=angle, crank_speed=30.0, restitution=0.4, friction=0.15)
    # without friction the sign of the sliding does not matter: the crank turns back at -R psi'_-
    s = strike(MECH, at="rocker.K", normal=UP, angle=angle, crank_speed=30.0, restitution=0.4, friction=0.0)
    assert s.crank_speed_after == pytest.approx(-12.0, rel=1e-12)


@pytest.mark.parametrize("tool_speed", [1.5, -1.0])
def test_a_rebound_on_a_moving_tool_balances_momentum_and_restitution(tool_speed):
    """An impact on a tool already moving (into the work ahead of the striker, or coming back up at it,
    as in the rebounds): the tool's momentum takes the normal impulse, the machine's generalised
    momentum (reduced inertia from the exact kinematics, flywheel and rotor) the impulse's
    generalised part ``dK/dpsi . S``, the normal closing speed reverses times R, and the friction
    opposes the sliding in the ratio f."""
    angle = float(MECH.drive_start[0])
    jd, mt, r, f = MECH.motor_gear.inertia, 3.0, 0.4, 0.15
    s = strike(
        MECH,
        at="rocker.K",
        normal=UP,
        angle=angle,
        crank_speed=30.0,
        restitution=r,
        friction=f,
        tool_mass=mt,
        tool_speed=tool_speed,
        drive_inertia=jd,
    )
    inertia, _, _, _, g, _ = _pose([angle])
    g = g[0]  # dK/dpsi: the kinematics at unit turning speed
    jt = inertia[0] + jd
    assert jt * (s.crank_speed_after - s.crank_speed_before) == pytest.approx(g @ s.impulse, rel=1e-10)
    assert mt * (s.tool_speed_after - s.tool_speed_before) == pytest.approx(s.impulse[1], rel=1e-12)
    before = g[1] * s.crank_speed_before + tool_speed  # the gap's rate
    after = g[1] * s.crank_speed_after + s.tool_speed_after
    assert before < 0 and after == pytest.approx(-r * before, rel=1e-10)
    assert abs(s.impulse[0]) == pytest.approx(f * s.impulse[1], rel=1e-12)
    assert s.impulse[0] * g[0] * s.crank_speed_before < 0
    # the energy it loses: the machine's and the tool's kinetic energy, before less after
    lost = 0.5 * jt * (s.crank_speed_before**2 - s.crank_speed_after**2)
    lost += 0.5 * mt * (tool_speed**2 - s.tool_speed_after**2)
    assert s.energy_lost == pytest.approx(lost, rel=1e-12)
    assert lost > 0


@pytest.mark.parametrize("friction", [0.3, 0.0])
def test_a_crank_thrown_back_by_the_blow_is_reported_as_a_stall(friction):
    """No flywheel and a heavy tool: the elastic blow throws the crank back (the rocker rebounds off
    the 200 kg tool), so the crank never turns through its cycle: an error, not blows per minute."""
    drive = dataclasses.replace(MECH.motor_gear, flywheel=0.0)
    tool = Tool(200.0, 250.0, 2000.0)
    # the first blow alone: the crank's speed after it, from the impact map, is negative
    start = MECH.drive_start[0]
    first = strike(
        MECH,
        at="rocker.K",
        normal=UP,
        angle=start,
        crank_speed=30.0,
        restitution=1.0,
        friction=0.0,
        tool_mass=tool.mass,
        drive_inertia=drive.inertia,
    )
    assert first.crank_speed_after < 0
    blow_angle = f"{math.degrees(start) % 360:.1f}"  # the first blow is in the file's pose
    with pytest.raises(LinkworkError, match=f"crank stops at {blow_angle} deg"):
        simulate_blows(MECH, drive, tool=tool, restitution=1.0, friction=friction, blows=10)


@pytest.mark.parametrize(("restitution", "friction"), [(None, None), (0.0, 0.15)])
def test_a_heavy_tool_without_flywheel_stops_the_crank_with_a_clear_error(restitution, friction):
    """A 300 kg tool and no flywheel: the file's blow (R = 0.4) throws the crank back; a plastic blow
    leaves it so slow that the crank comes to rest while it presses the tool (the tool's speed, tied to
    the crank's in contact, falls to zero with it). Either way: the crank stops, said at once, not a
    run through thousands of empty contact phases to a limit."""
    drive = dataclasses.replace(MECH.motor_gear, flywheel=0.0)
    tool = Tool(300.0, 250.0, 2000.0)
    phase = "flight" if restitution is None else "contact"
    with pytest.raises(LinkworkError, match=f"crank stops at .* deg \\(in the {phase} phase") as err:
        simulate_blows(MECH, drive, tool=tool, restitution=restitution, friction=friction, blows=10)
    if restitution is None:
        return
    # where: within the first stroke after the blow. An energy bound: the kinetic energy E after the
    # plastic blow (machine and tool, from the impact map) plus the motor's largest moment over the
    # turn it makes must pay the feed and the work's resistance over the tool's travel |s'| dpsi
    start = float(MECH.drive_start[0])
    w0 = float(abs(MECH.drive_speed[0]))
    # the speeds after the blow are linear in the crank speed before it, so E grows with it: a crank speed
    # above any the machine reaches (its motor's synchronous speed over the gear is 32.7 rad/s) bounds E
    fastest = 1.2 * drive.motor.synchronous / drive.ratio
    b = strike(
        MECH,
        at="rocker.K",
        normal=UP,
        angle=start,
        crank_speed=fastest,
        restitution=0.0,
        friction=0.15,
        tool_mass=tool.mass,
        drive_inertia=drive.inertia,
    )
    energy = 0.5 * b.inertia * b.crank_speed_after**2 + 0.5 * tool.mass * b.tool_speed_after**2
    slope = abs(b.closing_speed / b.crank_speed_before)  # |s'| at the blow, m/rad
    push = float(np.max(drive.moment(np.linspace(0.0, 2 * w0, 2001))))
    turn = energy / ((tool.feed + tool.resistance) * slope - push)
    assert 0 < turn < math.radians(3.0)
    stop = float(str(err.value).split("stops at ")[1].split(" deg")[0])
    blow = math.degrees(start) % 360  # the crank turns clockwise: the angle falls
    assert blow - 2 * math.degrees(turn) < stop <= blow + 0.05, (blow, math.degrees(turn), stop)


@pytest.mark.parametrize("tool_mass", [3.0, math.inf])
def test_elastic_blow_without_friction_loses_no_energy(tool_mass):
    angle = float(MECH.drive_start[0])
    s = strike(
        MECH,
        at="rocker.K",
        normal=UP,
        angle=angle,
        crank_speed=30.0,
        restitution=1.0,
        friction=0.0,
        tool_mass=tool_mass,
        drive_inertia=0.7,
    )
    kinetic = 0.5 * s.inertia * s.crank_speed_before**2
    assert abs(s.energy_lost) < 1e-13 * kinetic
    after = 0.5 * s.inertia * s.crank_speed_after**2
    if math.isfinite(tool_mass):
        after += 0.5 * tool_mass * s.tool_speed_after**2
    assert after == pytest.approx(kinetic, rel=1e-13)


def test_elastic_blows_in_the_cycle_lose_no_energy():
    """R = 1, f = 0: neither the blows nor the rebounds lose energy; the ledger still balances."""
    run = simulate_blows(MECH, restitution=1.0, friction=0.0, blows=3, tol=0.0)
    for b in run.blows:
        assert abs(b.energy_lost) < 1e-9 * b.energy_before
        assert abs(b.rebound_loss) < 1e-9 * b.energy_before
        _check_blow_balances(b, 3.0, MECH.motor_gear.inertia, 1.0, 0.0)
    assert abs(run.energy["blows"]) < 1e-9 * run.energy["motor"]
    assert abs(run.balance) < 1e-7 * run.energy["motor"]


@pytest.mark.slow  # over the default lane's budget on the NumPy kernels (tests/conftest.py)
def test_blows_per_minute_against_the_motor_balance_with_a_large_flywheel():
    """With a flywheel so large that the crank's speed hardly changes, the steady speed is where the
    motor's moment times 2 pi covers the energy the cycle consumes: one blow per turn at that speed."""
    stall, no_load, ratio = 600.0, 160.0, 5.0
    drive = MotorGear(LinearMotor(stall=stall, no_load=no_load), ratio=ratio, flywheel=40.0)

    def balanced(consumed):
        """The crank speed at which ratio * stall * (1 - ratio w / no_load) * 2 pi = consumed."""
        return no_load / ratio * (1.0 - consumed / (2 * math.pi * ratio * stall))

    def consumed(run):
        """What the cycle spends: the impacts, the seat, the work, friction (not the motor's entry)."""
        c = run.cycle_energy
        return c["blows"] + c["rebounds"] + c["seat"] + c["work"] + c["friction"] + c["kinetic"] - c["loads"]

    first = simulate_blows(MECH, drive, blows=3, tol=0.0, omega0=30.0)  # what a cycle needs near there
    run = simulate_blows(MECH, drive, blows=60, omega0=balanced(consumed(first)), tol=1e-7)
    assert run.steady
    speed = balanced(consumed(run))
    # a linear characteristic: its mean over the turn is its value at the mean speed over the turn,
    # which differs from 2 pi / period by the square of the (small) fluctuation
    assert run.blows_per_minute == pytest.approx(60.0 * speed / (2 * math.pi), rel=1e-4)
    # the crank's speed through the cycle stays within a small band around it
    tail = run.t >= run.last.time
    assert np.ptp(run.omega[tail]) < 0.02 * speed


def test_the_period_is_the_time_the_crank_takes_for_its_turn(example):
    """The blow-to-blow period, from the events' times, against the turn's time integrated from the
    sampled crank speed, dt = dpsi / psi' (Simpson's rule on a cubic resampling of each stretch
    between impacts, over the turning angle): one blow per turn of the crank."""
    from scipy.integrate import simpson
    from scipy.interpolate import CubicSpline

    run = example
    period, turn = 0.0, 0.0
    for idx in _segments(run):
        psi, w = run.psi[idx], run.omega[idx]
        if run.t[idx[0]] < run.last.time or len(psi) < 2:
            continue
        assert np.all(np.diff(psi) > 0) and np.all(w > 0)
        fine = np.linspace(psi[0], psi[-1], 2001)
        speed = CubicSpline(psi, w)(fine) if len(psi) > 3 else np.interp(fine, psi, w)
        period += simpson(1.0 / speed, x=fine)
        turn += psi[-1] - psi[0]
    assert turn == pytest.approx(2 * math.pi, rel=1e-9)
    assert run.period == pytest.approx(period, rel=1e-6)
    assert run.blows_per_minute == pytest.approx(60.0 / period, rel=1e-6)


def _free_gap_acceleration(run, k, into):
    """The gap's acceleration were striker and tool free at sample ``k``: the striker's along the
    normal from the mechanism's own equation (exact kinematics), the tool's from the feed and the
    resistance."""
    angle = MECH.drive_start[0] + SIGN * run.psi[k]
    inertia, slope, _, gravity_moment, g, h = _pose([angle])
    w = run.omega[k]
    jt = inertia[0] + MECH.motor_gear.inertia
    acc = (gravity_moment[0] + float(MECH.motor_gear.moment(w)) - 0.5 * slope[0] * w * w) / jt
    striker = g[0, 1] * acc + h[0, 1] * w * w  # g, h: dK/dpsi, d2K/dpsi2
    tool = -(run.tool.feed + (run.tool.resistance if into else 0.0)) / run.tool.mass
    return striker + tool


def test_the_contact_force_stays_compressive_and_the_phase_ends_where_it_would_pull(example):
    """While striker and tool move together the contact force is positive; the phase ends where the
    force the contact needs would pull: there, striker and tool left free would part (the gap's free
    acceleration, from the exact kinematics, turns from closing to opening)."""
    run = example
    contact = run.mode == 2
    assert contact.any()
    force = run.force[contact]
    assert np.all(force > 0)
    phases = list(run.phases)
    ends = 0
    for p, nxt in zip(phases, phases[1:], strict=False):
        if p.kind != "contact" or nxt.kind != "apart":
            continue
        idx = np.flatnonzero(contact & (run.t >= p.start) & (run.t <= p.end))
        inside, end = idx[len(idx) // 2], idx[-1]
        assert _free_gap_acceleration(run, inside, into=run.v[inside] > 0) < 0  # left free they would close
        # at the end the tool stops in the work: its resistance lets go and the two part
        assert abs(run.v[end]) < 1e-6 * np.max(np.abs(run.v))
        assert _free_gap_acceleration(run, end, into=False) > 0
        assert _free_gap_acceleration(run, end - 1, into=True) < 0
        ends += 1
    assert ends >= 2


def test_a_contact_phase_ending_in_a_smooth_separation():
    """A plastic blow (R = 0) and no resistance of the work: the striker carries the tool down; near
    the bottom of its stroke it slows faster than the feed can slow the tool, the contact force falls
    continuously to zero where the phase ends, and the free gap acceleration there is zero."""
    tool = Tool(mass=3.0, feed=200.0)
    run = simulate_blows(MECH, tool=tool, restitution=0.0, blows=3, tol=0.0)
    contact = run.mode == 2
    phases = list(run.phases)
    ends = 0
    for p, nxt in zip(phases, phases[1:], strict=False):
        if p.kind != "contact" or nxt.kind != "apart":
            continue
        idx = np.flatnonzero(contact & (run.t >= p.start) & (run.t <= p.end))
        peak = np.max(run.force[idx])
        assert np.all(run.force[idx] >= -1e-9 * peak)
        assert abs(run.force[idx[-1]]) < 1e-6 * peak
        assert abs(_free_gap_acceleration(run, idx[-1], into=run.v[idx[-1]] > 0)) < 1e-5 * tool.feed / tool.mass
        ends += 1
    assert ends >= 1


def test_the_loads_in_the_contact_phase_balance_every_links_acceleration(example):
    """While the striker presses the tool: the forces on each moving link (the joints' forces read back
    from the per-joint table, the tool's at K on the rocker, gravity) equal its mass times the
    acceleration of its centre of mass, and their moments about it its inertia times its angular
    acceleration, from the exact kinematics and the crank's acceleration (central differences of the
    sampled crank speed); on the crank also the drive's moment, the motor's through the gear less what
    the flywheel and rotor take, M_d(psi') - J_d psi''."""
    from linkwork.motion import kinematics

    run, loads, drive = example, example.contact, MECH.motor_gear
    assert len(loads.t) > 10
    t = run.t - run.last.time
    checked = 0
    for k in range(1, len(loads.t) - 1):
        i = int(np.flatnonzero(np.isclose(t, loads.t[k], rtol=0, atol=1e-12) & (run.mode == 2))[0])
        if not (run.mode[i - 1] == run.mode[i + 1] == 2):
            continue
        acc = (run.omega[i + 1] - run.omega[i - 1]) / (run.t[i + 1] - run.t[i - 1])
        w = run.omega[i]
        kin = kinematics(MECH, np.array([MECH.drive_start[0] + SIGN * run.psi[i]]), speed=SIGN)
        pos = {name: kin.position(name)[0] for name in loads.joints}
        k_pos = kin.position("rocker.K")[0]
        scale = loads.force.max()
        for li, name in enumerate(MECH.link_names[1:], 1):
            q = kin.pose[0, 0, li]
            c, s_ = np.cos(q[2]), np.sin(q[2])
            lc = MECH.link_com[li]
            rc = np.array([c * lc[0] - s_ * lc[1], s_ * lc[0] + c * lc[1]])
            v, a = kin.vel[0, 0, li], kin.acc[0, 0, li]  # transfer functions of the link's origin

            def com(x, rc=rc):
                return x[:2] + x[2] * np.array([-rc[1], rc[0]])

            a_c = com(v) * acc + com(a) * w * w - (v[2] * w) ** 2 * rc
            alpha = v[2] * acc + a[2] * w * w
            centre = q[:2] + rc
            total = np.array([0.0, -MECH.gravity * MECH.link_mass[li]])
            moment = 0.0
            for joint, f_all in loads.joints.items():
                first, second = loads.joint_links[joint]
                f = f_all[k] if name == second else -f_all[k] if name == first else None
                if f is None:
                    continue
                arm = pos[joint] - centre
                total, moment = total + f, moment + arm[0] * f[1] - arm[1] * f[0]
            if name == "rocker":
                push = loads.force[k] * np.array([loads.phi[k], 1.0])  # n = (0, 1), t = (1, 0)
                arm = k_pos - centre
                total, moment = total + push, moment + arm[0] * push[1] - arm[1] * push[0]
            if name == "crank":  # counter-clockwise; the crank turns clockwise
                moment += SIGN * (float(drive.moment(w)) - drive.inertia * acc)
            np.testing.assert_allclose(total, MECH.link_mass[li] * a_c, rtol=0, atol=1e-3 * scale)
            assert moment == pytest.approx(MECH.link_inertia[li] * alpha, abs=1e-4 * scale), name  # N m
        checked += 1
    assert checked > 5
    # the support O carries more than the blow's force on the striker: the rod presses the rocker down
    peak_o = np.hypot(*loads.peak("O")[1])
    assert peak_o > 1.5 * loads.force.max()


def test_the_striker_never_enters_the_tool_and_the_tool_never_rises_above_its_seat(example):
    """The gap from the exact kinematics (the striker's height above the seated face, plus the tool's
    travel) stays closed or open over every sample of the run: no event was missed."""
    from linkwork.motion import kinematics

    run = example
    kin = kinematics(MECH, MECH.drive_start[0] + SIGN * run.psi, speed=SIGN)
    height = kin.position("rocker.K")[..., 1].ravel() - (-0.02)
    gap = height + run.u
    assert gap.min() > -1e-11
    assert run.u.min() > -1e-12
    assert np.all(np.abs(gap[run.mode == 2]) < 1e-9)  # in contact they stay together
    assert np.all(run.u[run.mode == 0] == 0.0)  # in flight the tool is on its seat


def test_phases_tile_the_cycle(example):
    run = example
    cycle = run.cycle_phases()
    assert cycle[0].start == pytest.approx(run.last.time)
    assert sum(p.duration for p in cycle) == pytest.approx(run.period, rel=1e-12)
    assert math.degrees(sum(p.psi_end - p.psi_start for p in cycle)) == pytest.approx(360.0, rel=1e-9)
    assert [p.kind for p in cycle][0] == "apart" and cycle[-1].kind == "flight"
    assert {p.freedom for p in cycle} == {1, 2}


def test_bad_input_is_refused():
    with pytest.raises(LinkworkError, match="feed"):
        Tool(mass=3.0, feed=0.0)
    with pytest.raises(LinkworkError, match="drive"):
        simulate_blows(dataclasses.replace(MECH, motor_gear=None))
    with pytest.raises(LinkworkError, match="tool"):
        simulate_blows(dataclasses.replace(MECH, blow=dataclasses.replace(MECH.blow, tool=None)))
    with pytest.raises(LinkworkError, match="stops"):  # a motor far too weak for the work
        simulate_blows(MECH, MotorGear(ConstantTorque(1.0), flywheel=0.01), blows=5)


def test_a_bad_tool_section_names_each_problem_with_its_line():
    from importlib.resources import files

    text = (files("linkwork") / "examples" / "percussion-rocker.yaml").read_text(encoding="utf-8")
    bad = text.replace("feed: 250 N ", "feed: -5 N ").replace("mass: 3.0\n", "mass: 3.0\n    stiffness: 5\n")
    with pytest.raises(ValueError) as err:
        lw.loads(bad)
    message = str(err.value)
    assert 'impact.tool.stiffness: unknown key "stiffness"' in message
    assert "impact.tool.feed: expected a positive force" in message
    lines = [int(line.split(":")[1]) for line in message.splitlines() if "impact.tool" in line]
    assert len(lines) == 2 and lines[0] != lines[1]


runner = CliRunner()


def test_impact_cycle_command():
    import linkwork.cli.impact  # noqa: F401 - registers the command
    from linkwork.cli.main import app

    result = runner.invoke(app, ["impact", "percussion-rocker", "--cycle"])
    assert result.exit_code == 0, result.output
    assert "blows per minute" in result.output and "contact" in result.output
    result = runner.invoke(app, ["impact", "percussion-rocker", "--cycle", "--json", "--blows", "40"])
    assert result.exit_code == 0, result.output
    out = json.loads(result.stdout)
    assert out["steady"] and len(out["blows"]) <= 40
    assert out["blows_per_minute"] == pytest.approx(60.0 / out["period"])
    assert {"motor", "gear", "drive"} <= set(out["cycle_energy"]) and {"mean_power", "drive_power"} <= set(out)
    blow = out["blows"][-1]
    assert {"O", "O1", "A", "N"} <= set(blow["support_impulse"])
    assert blow["support_impulse"]["O"]["on"] == "rocker"
    assert {p["kind"] for p in out["phases"]} == {"apart", "contact", "flight"}
    assert sum(p["duration"] for p in out["phases"]) == pytest.approx(out["period"], rel=1e-9)
    for args, words in (
        (["--cycle", "--blows", "1"], "at least 3"),
        (["--blows", "5"], "only with --cycle"),
        (["--cycle", "--blows", "many"], "blows"),
    ):
        result = runner.invoke(app, ["impact", "percussion-rocker", *args])
        assert result.exit_code == 2, (args, result.output)
        assert words in result.output
    result = runner.invoke(app, ["impact", "four-bar", "--cycle"])
    assert result.exit_code == 2 and "no blow" in result.output
