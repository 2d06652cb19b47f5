"""Peaks of forces refined between the samples: the same number whatever the grid and whatever the route."""

from __future__ import annotations

import json

import numpy as np
import pytest

import linkwork as lw
from commandline import linkwork
from linkwork.kinetostatics.peaks import foundation_peak, refine, torque_peak
from mechanisms import rotor


@pytest.fixture(scope="module")
def shears() -> lw.Mechanism:
    return lw.compile(lw.load("double-cut-shears"))


def _bounded_peak(mech: lw.Mechanism) -> float:
    """The peak driving torque by an independent route: a dense grid, then scipy's bounded scalar minimisation of
    minus the size of the torque solved at single angles, between the dense grid's neighbours of its best sample."""
    from scipy.optimize import minimize_scalar

    f = lw.forces(mech, steps=7200)
    size = np.abs(f.driving_torque)
    i = int(np.nanargmax(size))
    found = minimize_scalar(
        lambda x: -abs(float(lw.forces(mech, angles=np.array([x])).driving_torque[0])),
        bounds=(f.angles[i - 1], f.angles[i + 1]),
        method="bounded",
        options={"xatol": 1e-12},
    )
    return max(-float(found.fun), float(size[i]))


def test_the_peak_torque_of_the_double_cut_shears_does_not_depend_on_the_grid(shears):
    """The torque peaks where the knives' force stops rising (a kink between samples): 360 and 720 steps missed
    it by 4.6e-3 and 5.3e-4; refined, they agree to 1e-9 and with an independent bounded search to 1e-6."""
    coarse, fine = (torque_peak(lw.forces(shears, steps=n)) for n in (360, 720))
    assert coarse.value[0] == pytest.approx(fine.value[0], rel=1e-9)
    assert coarse.at[0] == pytest.approx(fine.at[0], abs=1e-6)
    assert np.max(np.abs(lw.forces(shears, steps=360).driving_torque)) < coarse.value[0] * (1 - 1e-3)
    assert coarse.value[0] == pytest.approx(_bounded_peak(shears), rel=1e-6)
    assert coarse.value[0] == pytest.approx(30215.5, rel=1e-6)


def test_every_route_gives_the_same_peak_torque(shears):
    """forces --json, the viewer's payload and the sweep metric: one number, at 360 and 720 steps."""
    from linkwork.web import cycle_payload

    reference = torque_peak(lw.forces(shears, steps=360)).value[0]
    for steps in ("360", "720"):
        run = linkwork("forces", "double-cut-shears", "--steps", steps, "--json")
        assert run.returncode == 0, run.stderr
        assert json.loads(run.stdout)["driving_torque_peak"]["value"] == pytest.approx(reference, rel=1e-9)
    text = linkwork("forces", "double-cut-shears").stdout
    assert f"peak {reference:.6g} N m" in text
    payload = cycle_payload(shears, steps=720)
    assert payload["peaks"]["driving_torque"]["value"] == pytest.approx(reference, rel=1e-9)
    t = lw.sweep(shears, {"links.crank.length": ("100 mm", "100 mm", 1)}, ["peak_driving_torque"], steps=720)
    assert t["peak_driving_torque"][0] == pytest.approx(reference, rel=1e-9)


def test_variants_are_refined_together_each_at_its_own_angles(shears):
    """Each variant of a batch refined at once equals the same variant solved alone and refined."""
    lengths = np.array([0.095, 0.1, 0.104])
    batch = lw.forces(shears, steps=360, variants={"links.crank.length": lengths})
    together = torque_peak(batch)
    for k, length in enumerate(lengths):
        alone = lw.forces(shears, steps=720, variants={"links.crank.length": [length]})
        assert together.value[k] == pytest.approx(torque_peak(alone).value[0], rel=1e-9)
    found = foundation_peak(batch)
    dense = lw.forces(shears, steps=7200, variants={"links.crank.length": lengths}).foundation
    sampled = np.hypot(dense[..., 0], dense[..., 1]).max(axis=1)
    assert np.all(found.value >= sampled * (1 - 1e-12))
    assert found.value == pytest.approx(sampled, rel=1e-5)


def test_refine_finds_a_smooth_maximum_a_kink_and_the_high_side_of_a_jump():
    """Closed forms: cos(x - 0.3) peaks at 0.3 (1); 1 - |x - 0.31| at 0.31 (1); a step from 0 to 2 - x at 0.2:
    the supremum 1.8, the limit from the high side.  The angle of a smooth maximum is known from values to the
    square root of their precision (1e-6 here); that of a kink or a jump to 1e-9."""
    angles = np.linspace(0, 2 * np.pi, 36, endpoint=False)
    cases = [
        (lambda x: np.cos(x - 0.3), 1.0, 0.3, 1e-6),
        (lambda x: 1 - np.abs(x - 0.31), 1.0, 0.31, 1e-9),
        (lambda x: np.where(x >= 0.2, 2 - x, 0.0), 1.8, 0.2, 1e-9),
    ]
    for fn, top, where, tol in cases:
        peak = refine(fn(angles)[None], angles, fn, "max")
        assert peak.value[0] == pytest.approx(top, abs=1e-12)
        assert peak.at[0] == pytest.approx(where, abs=tol)
    low = refine(np.cos(angles - 2.0)[None], angles, lambda x: np.cos(x - 2.0), "min")
    assert low.value[0] == pytest.approx(-1.0, abs=1e-12)


def test_the_simulated_speeds_extremes_do_not_depend_on_the_points_kept(shears):
    """The steady turn of the double-cut shears with a flywheel for delta 0.03: its least and largest speed from 720
    points a turn, refined on the solver's dense output, equal those read off 200 000 points of the same run."""
    from linkwork.machine.simulation import run_turns

    run = lw.dynamics(shears, delta=0.03)
    start, omega0 = float(run.motion.psi[0]), float(run.motion.omega[0])
    coarse, fine = (run_turns(run.reduced, run.drive, omega0=omega0, start=start, points=n) for n in (720, 200000))
    last = fine.last
    sel = (fine.t >= last.start) & (fine.t <= last.end)
    for refined, dense in (
        (coarse.last.omega_max, fine.omega[sel].max()),
        (coarse.last.omega_min, fine.omega[sel].min()),
    ):
        assert refined == pytest.approx(dense, rel=1e-9)
    assert coarse.last.delta == pytest.approx(fine.last.delta, rel=1e-7)


def test_the_report_gives_the_refined_peak_torque(shears, main_job):
    """The report's forces.json and its text carry the peak every route gives (the text to its 4 digits), and the
    bolt loads forces gives: the README's main job's report (360 steps) against forces on another grid."""
    assert main_job.returncode == 0, main_job.stderr
    forces = lw.forces(shears, steps=720)
    reference = torque_peak(forces).value[0]
    data = json.loads((main_job.folder / "forces.json").read_text(encoding="utf-8"))
    assert data["driving_torque_peak"]["value"] == pytest.approx(reference, rel=1e-9)
    bolts = forces.bolts()  # the bolt loads too, refined: 720 steps here, 360 there
    for name in ("shear", "push", "moment"):
        assert data["bolts"][name] == pytest.approx(getattr(bolts, name), rel=1e-9)
    html = (main_job.folder / "report.html").read_text(encoding="utf-8")
    assert f"largest {reference / 1000:.4g} kN" in html


def test_the_largest_pair_forces_do_not_depend_on_the_grid_and_the_command_prints_them(shears):
    """Every pair's largest force, refined: 360 and 720 steps agree to 1e-9, never below 7200 samples' largest and
    within 2e-4 of it (the peaks are kinks where the knives' force stops rising: 7200 samples still miss them by
    8e-5); forces prints them."""
    from linkwork.kinetostatics.peaks import pair_force_peaks

    pairs = list(range(shears.n_pairs))
    coarse, fine = (pair_force_peaks(lw.forces(shears, steps=n), pairs) for n in (360, 720))
    np.testing.assert_allclose(coarse.value, fine.value, rtol=1e-9)
    dense = lw.forces(shears, steps=7200)
    sampled = np.array([np.nanmax(np.hypot(*dense.pair_force(k)[0].T)) for k in pairs])
    assert np.all(coarse.value >= sampled * (1 - 1e-12))
    np.testing.assert_allclose(coarse.value, sampled, rtol=2e-4)
    text = linkwork("forces", "double-cut-shears").stdout
    assert f"{coarse.value[0]:.6g}" in text and f"{coarse.value[4]:.6g}" in text


#: A crank of 2 kg with its centre of mass at (80, 30) mm in its own axes, on a pivot at (40, 30) mm, turning at
#: 300 rpm; the coupler and the rocker have no mass.  What it puts on its foundation is by hand: with K = m w^2 r_c
#: and theta the angle of its centre of mass, Fx = K cos(theta), Fy = -m g + K sin(theta), and the moment about the
#: origin is that of Fy and Fx at the pivot and of the weight's arm r_c cos(theta) (the inertia force passes
#: through the pivot).
ROTOR = rotor(60)


def _rotor_bolts() -> dict[str, tuple[float, float]]:
    """The rotor's largest bolt loads by hand and the crank angle (to x, rad, in 0..2 pi) of each."""
    mass, g, omega, ox, oy = 2.0, 9.81, 300 * np.pi / 30, 0.04, 0.03
    r_c, delta = np.hypot(0.08, 0.03), np.arctan2(0.03, 0.08)
    k = mass * omega**2 * r_c
    # M(theta) = -ox m g + ox K sin(theta) - (oy K + m g r_c) cos(theta): its least is -ox m g - R
    a, b = ox * k, -(oy * k + mass * g * r_c)
    theta_m = np.arctan2(-a, -b)  # where a sin + b cos = -R
    angle = lambda theta: float(np.mod(theta - delta, 2 * np.pi))  # noqa: E731
    return {
        "shear": (k, angle(np.pi)),  # or 0: the grid's best sample picks one of the two equal maxima
        "pull": (k - mass * g, angle(np.pi / 2)),
        "push": (k + mass * g, angle(3 * np.pi / 2)),
        "moment": (ox * mass * g + np.hypot(a, b), angle(theta_m)),
    }


@pytest.mark.parametrize("steps", [7, 360])
def test_the_bolt_loads_are_the_closed_form_whatever_the_grid(steps, tmp_path):
    """A rotating mass's shear, pull, push and moment peak between the samples of 7 or 360 steps; refined, Forces.bolts
    (one mechanism and a variant of it) and forces --json give the closed form to 1e-9, and where, to 1e-6 rad."""
    path = tmp_path / "rotor.yaml"
    path.write_text(ROTOR, encoding="utf-8")
    mech = lw.compile(lw.load(path))
    expected = _rotor_bolts()
    one = lw.forces(mech, steps=steps)
    variant = lw.forces(mech, steps=steps, variants={"links.crank.mass": [2.0]})
    sampled = np.abs(one.foundation[:, 2]).max()
    assert sampled < expected["moment"][0] * (1 - 1e-6)  # the grid misses it
    for bolts in (one.bolts(), variant.bolts()):
        for name, (value, where) in expected.items():
            assert getattr(bolts, name) == pytest.approx(value, rel=1e-9), name
            at = np.mod(getattr(bolts, f"{name}_angle"), 2 * np.pi)
            if name == "shear":
                assert min(abs(at - where), abs(abs(at - where) - np.pi)) == pytest.approx(0, abs=1e-6)
            else:
                assert min(abs(at - where), 2 * np.pi - abs(at - where)) == pytest.approx(0, abs=1e-6), name
    run = linkwork("forces", str(path), "--steps", str(steps), "--json")
    assert run.returncode == 0, run.stderr
    written = json.loads(run.stdout)["bolts"]
    for name, (value, _) in expected.items():
        assert written[name] == pytest.approx(value, rel=1e-9)


def _bounded(mech: lw.Mechanism, quantity, steps: int = 7200) -> float:
    """The largest ``quantity(forces) -> (A,)`` by an independent route: a dense grid, then scipy's bounded scalar
    search between the neighbours of its best sample, solving single angles."""
    from scipy.optimize import minimize_scalar

    dense = lw.forces(mech, steps=steps)
    values, angles = quantity(dense), dense.angles
    i, step = int(np.nanargmax(values)), angles[1] - angles[0]
    found = minimize_scalar(
        lambda x: -float(quantity(lw.forces(mech, angles=np.array([x])))[0]),
        bounds=(angles[i] - step, angles[i] + step),
        method="bounded",
        options={"xatol": 1e-12},
    )
    return max(-float(found.fun), float(values[i]))


def test_bolts_and_shaking_do_not_depend_on_the_grid_and_every_route_prints_them(shears):
    """The double-cut shears' bolt loads and shaking force and moment: 360 and 720 steps agree to 1e-9; the push and
    the shaking force agree with a dense grid and a bounded search to 1e-6; forces --json and the printed lines carry
    them."""
    from linkwork.kinetostatics.peaks import shaking_peaks

    found = {}
    for steps in (360, 720):
        f = lw.forces(shears, steps=steps)
        b = f.bolts()
        found[steps] = np.concatenate([[b.shear, b.push, b.moment], shaking_peaks(f).value])
    np.testing.assert_allclose(found[360], found[720], rtol=1e-9)
    push, shake, moment = found[360][1], found[360][3], found[360][4]
    assert push == pytest.approx(_bounded(shears, lambda g: -g.foundation[:, 1]), rel=1e-6)
    assert shake == pytest.approx(_bounded(shears, lambda g: np.hypot(*g.shaking_force.T)), rel=1e-6)
    assert abs(moment) == pytest.approx(_bounded(shears, lambda g: np.abs(g.shaking_moment)), rel=1e-6)
    run = linkwork("forces", "double-cut-shears", "--steps", "720", "--json")
    assert run.returncode == 0, run.stderr
    bolts = json.loads(run.stdout)["bolts"]
    assert [bolts["shear"], bolts["push"], bolts["moment"]] == pytest.approx(list(found[360][:3]), rel=1e-9)
    text = linkwork("forces", "double-cut-shears").stdout
    assert f"shaking force max {shake:.6g} N" in text and f"shaking moment max {abs(moment):.6g} N m" in text
    assert f"push on the foundation max {push:.6g} N" in text


def test_a_guides_largest_moment_is_the_closed_form(tmp_path):
    """The slider-crank shears with the knife's centre of mass 50 mm beside its guide: the guide holds the moment of
    its weight and inertia force, m d (g - 2 l w^2 sin(phi)) (y_B = 2 l sin(phi)), largest m d (g + 2 l w^2) at
    phi = 270 deg, between the samples of 7 steps; refined, and the largest moment forces prints."""
    from linkwork.examples import text
    from linkwork.kinetostatics.peaks import pair_moment_peaks

    path = tmp_path / "offset-knife.yaml"
    path.write_text(text("shears-slider-crank").replace("    mass: 20\n", "    mass: 20\n    com: [0.05, 0]\n"))
    mech = lw.compile(lw.load(path))
    guide = [mech.pair_joint.index("guide")]
    expected = 20 * 0.05 * (9.81 + 2 * 0.15 * 10.0**2)
    f = lw.forces(mech, steps=7)
    assert np.nanmax(np.abs(f.multipliers[0, :, 2 * guide[0]])) < expected * 0.95
    found = pair_moment_peaks(f, guide)
    assert abs(found.value[0]) == pytest.approx(expected, rel=1e-9)
    assert found.at[0] == pytest.approx(np.radians(270), abs=1e-6)
    printed = linkwork("forces", str(path), "--steps", "7").stdout
    assert f"{found.value[0]:.6g}" in printed


def test_a_sweep_of_a_mechanism_with_a_group_solved_by_newton_is_refined():
    """The class III triad (a group solved by Newton's method): the sweep's peak torque and foundation force are those
    of forces, at 360 and 720 steps, to 1e-9 (its samples miss the torque's peak by 1.3e-6)."""
    mech = lw.compile("class3-triad")
    reference = lw.forces(mech, steps=360)
    torque, force = abs(torque_peak(reference).value[0]), foundation_peak(reference).value[0]
    assert np.nanmax(np.abs(reference.driving_torque)) < torque * (1 - 1e-7)
    for steps in (360, 720):
        t = lw.sweep(
            mech,
            {"links.crank.length": ("30 mm", "30 mm", 1)},
            ["peak_driving_torque", "peak_foundation_force"],
            steps=steps,
        )
        assert t["peak_driving_torque"][0] == pytest.approx(torque, rel=1e-9)
        assert t["peak_foundation_force"][0] == pytest.approx(force, rel=1e-9)


@pytest.mark.parametrize("steps", [7, 360])
def test_the_speed_at_which_the_bolts_are_pulled_is_the_closed_form_whatever_the_grid(steps, tmp_path):
    """The rotor's bolts carry a pull P first where its centre of mass is straight up, at m w^2 r_c - m g = P:
    w = sqrt((P + m g) / (m r_c)), between the samples of 7 or 360 steps (missed by 7e-3 and 1.5e-5); refined,
    lw.bolt_speed and forces --pull give it to 1e-9."""
    path = tmp_path / "rotor.yaml"
    path.write_text(ROTOR, encoding="utf-8")
    mech = lw.compile(lw.load(path))
    r_c = np.hypot(0.08, 0.03)
    for pull in (0.0, 100.0):
        expected = np.sqrt((pull + 2.0 * 9.81) / (2.0 * r_c))
        assert lw.bolt_speed(mech, pull=pull, steps=steps) == pytest.approx(expected, rel=1e-9)
    run = linkwork("forces", str(path), "--steps", str(steps), "--pull", "100 N", "--json")
    assert run.returncode == 0, run.stderr
    assert json.loads(run.stdout)["bolts"]["speed_for_pull_rad_s"] == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize("steps", [8, 12, 36])
def test_a_variant_is_refined_through_a_sample_on_a_change_point(steps):
    """The slider-crank shears pass change points at phi = 0 and 180 deg, samples of these grids; a sample there has
    the modes of both sides, so a variant is refined on both (at 8 steps its peak torque lies beside one): the
    variant's peak torque, foundation force and bolt shear and push are those of the mechanism alone (solved along
    its path through the change points) to 1e-9, and the peak torque that of the closed form."""
    mech = lw.compile("shears-slider-crank")
    one = lw.forces(mech, steps=steps)
    variant = lw.forces(mech, steps=steps, variants={"links.knife.mass": [20.0]})
    figures = []
    for f in (one, variant):
        b = f.bolts()
        figures.append([abs(torque_peak(f).value[0]), foundation_peak(f).value[0], b.shear, b.push])
    np.testing.assert_allclose(figures[1], figures[0], rtol=1e-9)
    # the torque by hand (tests/kinetostatics/test_singular_positions.py): a s c + b c, its largest size by a dense
    # grid and a bounded search
    from scipy.optimize import minimize_scalar

    length, m1, m2, omega, g = 0.15, 10.0, 20.0, 10.0, 9.81
    a = 0.5 * omega**2 * (m1 * (length**2 / 2 - 9 * length**2 / 2) - 8 * m2 * length**2)
    size = lambda x: np.abs(a * np.sin(x) * np.cos(x) + g * length * np.cos(x) * (2 * m1 + 2 * m2))  # noqa: E731
    x = np.linspace(0, 2 * np.pi, 100001)
    i = int(np.argmax(size(x)))
    found = minimize_scalar(
        lambda y: -size(y), bounds=(x[i] - 1e-4, x[i] + 1e-4), method="bounded", options={"xatol": 1e-12}
    )
    assert figures[1][0] == pytest.approx(-found.fun, rel=1e-9)


@pytest.mark.parametrize("steps", [36, 50, 72])
def test_a_peak_beside_a_change_point_strictly_between_samples_is_refined(steps, tmp_path):
    """The slider-crank shears started at 87 deg: their change points (crank at 0 and 180 deg to x) fall strictly
    between the samples of 36, 50 and 72 steps, and the two samples around each are in different assembly modes.  The
    bolts' shear is the horizontal inertia force of the two uniform rods, 2 m1 (l / 2) w^2 cos(theta), largest
    (150 N) exactly on the change points: each side is solved in its own mode up to the change point located between
    the samples, so the refined shear is 150 N at every grid, at 0 or 180 deg, and a variant gives the same."""
    from linkwork.examples import text

    path = tmp_path / "shifted.yaml"
    path.write_text(text("shears-slider-crank").replace("angle: 90 deg", "angle: 87 deg"), encoding="utf-8")
    mech = lw.compile(lw.load(path))
    f = lw.forces(mech, steps=steps)
    branch = f.kinematics.step_branch[-1][0]
    assert np.count_nonzero(branch != np.roll(branch, 1)) == 2  # two intervals with a change point inside
    assert np.abs(f.foundation[:, 0]).max() < 150 * (1 - 1e-5)  # the samples miss it
    expected = 2 * 10.0 * (0.15 / 2) * 10.0**2
    for g in (f, lw.forces(mech, steps=steps, variants={"links.knife.mass": [20.0]})):
        b = g.bolts()
        assert b.shear == pytest.approx(expected, rel=1e-9)
        assert np.sin(b.shear_angle) == pytest.approx(0.0, abs=1e-4)


@pytest.mark.parametrize("steps", [36, 50, 360])
def test_a_force_that_grows_without_bound_at_a_change_point_is_unbounded_not_a_peak(steps):
    """The slider-crank shears at the crank angle theta = 0 to x (A = (l, 0), B = O): the rod lies across the guide.
    The knife's weight m2 g reaches the rod at B across it, and the moment about A of the rod's own weight adds
    m1 g / 2: by the rod's balance of moments |F_B| = (m2 + m1 / 2) g / |theta| to first order, 245.25 N rad, without
    bound (an independent route: forces solved at single angles).  Whatever the grid (36 steps: a sample on the
    change point; 50: between two), the pairs' largest force is unbounded there, at theta = 0 (phi = 270 deg), as
    forces prints and writes (null, with the reason and the angle), not the number of the sample that fell nearest."""
    from linkwork.kinetostatics.peaks import pair_force_peaks

    mech = lw.compile("shears-slider-crank")
    joint_b = mech.pair_joint.index("B")
    for delta in (1e-3, 1e-4, 1e-5):
        near = lw.forces(mech, angles=np.array([delta, 2 * np.pi - delta]))
        size = np.hypot(*near.pair_force(joint_b).T)
        np.testing.assert_allclose(size * delta, (20.0 + 10.0 / 2) * 9.81, rtol=5 * delta)
    found = pair_force_peaks(lw.forces(mech, steps=steps), list(range(mech.n_pairs)))
    assert found.unbounded.all() and np.all(np.isinf(found.value))
    np.testing.assert_allclose(np.abs(np.cos(found.at)), 1.0, atol=1e-12)  # theta = 0, or 180 deg: the other one
    run = linkwork("forces", "shears-slider-crank", "--steps", str(steps), "--json")
    assert run.returncode == 0, run.stderr
    largest = json.loads(run.stdout)["joints"]["B"]["largest"]
    assert largest["value"] is None and largest["unbounded"] is True and "singular position" in largest["reason"]
    assert abs(np.cos(np.radians(largest["at_to_x_deg"]))) == pytest.approx(1.0, abs=1e-12)
    text = linkwork("forces", "shears-slider-crank", "--steps", str(steps)).stdout
    assert "unbounded" in text and "grows without bound" in text and "e+" not in text.split("largest pair")[1][:400]


def test_refine_calls_a_peak_unbounded_only_where_it_grows_without_bound_at_a_singular_position():
    """Closed forms on a grid of 36 steps: 1 / sqrt|x - 0.3| with a singular position at 0.3 grows without bound
    (as the inverse square root of the distance): unbounded, infinite, at 0.3; the same growth with no singular
    position, and cos(x - 0.3), bounded, at a singular position, keep their peaks (1 for the cosine)."""
    angles = np.linspace(0, 2 * np.pi, 36, endpoint=False)

    def spike(x):
        with np.errstate(divide="ignore"):
            return 1 / np.sqrt(np.abs(x - 0.3))

    def at_point(x):
        return np.abs(x - 0.3) <= 1e-9

    found = refine(spike(angles)[None], angles, spike, "max", singular=at_point)
    assert found.unbounded[0] and found.value[0] == np.inf
    assert found.at[0] == pytest.approx(0.3, abs=1e-12)
    nowhere = refine(spike(angles)[None], angles, spike, "max", singular=lambda x: np.zeros(x.shape, bool))
    assert not nowhere.unbounded[0]
    smooth = refine(np.cos(angles - 0.3)[None], angles, lambda x: np.cos(x - 0.3), "abs", singular=at_point)
    assert not smooth.unbounded[0] and smooth.value[0] == pytest.approx(1.0, abs=1e-12)


def test_a_peak_at_the_edge_of_a_lock_is_unbounded():
    """A force that grows as 1 / (0.31 - x) towards a lock at x = 0.31 (a locked position has no value, as the
    friction's rule leaves it, from x = 0.3): the zoom ends at the lock's edge, 0.3, where the value is only where
    the rule draws the line (100); with the lock told it is unbounded there, without it the edge's value is kept.
    A bounded peak (cos(x - 4.5)) far from the lock keeps its value."""
    angles = np.linspace(0, 2 * np.pi, 36, endpoint=False)

    def rising(x):
        x = np.asarray(x, dtype=float)
        with np.errstate(divide="ignore"):
            return np.where((x > 0.3) & (x < 3.0), np.nan, 1 / (0.31 - np.where(x >= 3.0, x - 2 * np.pi, x)))

    def lock(x):
        x = np.asarray(x, dtype=float)
        return (x > 0.3) & (x < 3.0)

    found = refine(rising(angles)[None], angles, rising, "max", locked=lock)
    assert found.unbounded[0] and found.value[0] == np.inf and found.at[0] == pytest.approx(0.3, abs=1e-9)
    kept = refine(rising(angles)[None], angles, rising, "max")
    assert not kept.unbounded[0] and kept.value[0] == pytest.approx(100.0, rel=1e-6)
    smooth = refine(np.cos(angles - 4.5)[None], angles, lambda x: np.cos(x - 4.5), "max", locked=lock)
    assert not smooth.unbounded[0] and smooth.value[0] == pytest.approx(1.0, abs=1e-12)


@pytest.mark.filterwarnings("ignore::linkwork.errors.FrictionWarning")
def test_the_shears_torque_next_to_their_lock_is_unbounded():
    """The slider-crank shears with f = 0.1 lock within about 7 deg of their dead points phi = 90 and 270 deg
    (tests/kinetostatics/test_friction_locking.py finds the first edge at 82.8 deg): the driving torque and every
    pair force grow without bound towards a lock, so their peaks are unbounded, at an edge of a locked span
    (no largest value: before, the peak was the value where the rule draws the line, 1,000 times the forces
    without friction)."""
    from kinetostatics.test_friction import _shears
    from linkwork.kinetostatics.peaks import pair_force_peaks, torque_peak

    f = lw.forces(_shears(0.1, 0.020), steps=360)
    torque = torque_peak(f)
    assert torque.unbounded[0]
    phi = (np.degrees(torque.at[0]) - 90.0) % 360
    assert min(abs(phi - edge) for edge in (82.8, 97.2, 262.8, 277.2)) < 0.3
    assert pair_force_peaks(f, list(range(f.mechanism.n_pairs))).unbounded.all()


def test_balance_says_the_largest_pin_force_is_unbounded():
    """The slider-crank shears' pin forces grow without bound at their change points, with counterweights or without:
    balance prints "unbounded" and its JSON a null with the reason, not inf or the nearest sample's force."""
    text = linkwork("balance", "shears-slider-crank", "--links", "crank")
    assert text.returncode == 0, text.stderr
    assert "largest pin force, N" in text.stdout and "inf" not in text.stdout.split("largest pin force")[1]
    assert text.stdout.split("largest pin force, N")[1].split() == ["unbounded", "unbounded"]
    run = linkwork("balance", "shears-slider-crank", "--links", "crank", "--json")
    data = json.loads(run.stdout)
    assert data["before"]["pair_force_peak"] is None
    assert "grows without bound" in data["nulls"]["before.pair_force_peak"]
