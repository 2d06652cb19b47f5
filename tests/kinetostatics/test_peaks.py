"""Peaks of forces refined between the samples: the same number whatever the grid and whatever the route."""

from __future__ import annotations

import json

import numpy as np
import pytest

import linkwork as lw
from commandline import linkwork
from linkwork.kinetostatics.peaks import foundation_peak, refine, torque_peak


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
    from linkwork.machine.simulate import simulate

    run = lw.dynamics(shears, delta=0.03)
    start, omega0 = float(run.motion.psi[0]), float(run.motion.omega[0])
    coarse, fine = (simulate(run.reduced, run.drive, omega0=omega0, start=start, points=n) for n in (720, 200000))
    last = fine.last
    sel = (fine.t >= last.start) & (fine.t <= last.end)
    for refined, dense in (
        (coarse.last.omega_max, fine.omega[sel].max()),
        (coarse.last.omega_min, fine.omega[sel].min()),
    ):
        assert refined == pytest.approx(dense, rel=1e-9)
    assert coarse.last.delta == pytest.approx(fine.last.delta, rel=1e-7)


def test_the_report_gives_the_refined_peak_torque(shears, tmp_path):
    """The report's forces.json and its text carry the peak every route gives (the text to its 4 digits)."""
    reference = torque_peak(lw.forces(shears, steps=360)).value[0]
    run = linkwork("analyze", "double-cut-shears", "--no-animation", "--steps", "720", "--out", str(tmp_path / "r"))
    assert run.returncode == 0, run.stderr
    data = json.loads((tmp_path / "r" / "forces.json").read_text(encoding="utf-8"))
    assert data["driving_torque_peak"]["value"] == pytest.approx(reference, rel=1e-9)
    html = (tmp_path / "r" / "report.html").read_text(encoding="utf-8")
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
