"""At a dead or change point the reactions are indeterminate, but the driving torque and the foundation
loads are not: lw.forces gives them there from the power balance and the momentum theorem.

Seed 000's shears (OA = AB = l, uniform rods of mass m1, knife m2 on the vertical through O, housing m)
pass through a change point at phi = 0 and 180 deg, both among 360 samples of the turn.  By hand, with the
crank turning uniformly at omega: the centres of mass are r1 = l/2 (c, s), r2 = (l/2 c, 3 l/2 s),
r3 = (0, 2 l s); the rod's angle is pi - phi.  The reduced inertia
I = m1 l^2/4 + m1 l^2/12 + m1 (l^2/4 s^2 + 9 l^2/4 c^2) + m1 l^2/12 + 4 m2 l^2 c^2, so the driving torque
M = omega^2/2 dI/dphi + dV/dphi (written out below), and the foundation force is the weight
of everything less the rate of change of momentum.
"""

from __future__ import annotations

import numpy as np
import pytest

import linkwork as lw

L, M1, M2, HOUSING, OMEGA, G = 0.15, 10.0, 20.0, 500.0, 10.0, 9.81


def test_torque_and_foundation_are_finite_at_the_change_points_and_equal_the_closed_form():
    f = lw.forces("shears-slider-crank", steps=360)
    phi = f.angles
    assert f.kinematics.valid.all()
    assert f.singular.sum() == 2  # the change points, where the reactions are indeterminate
    np.testing.assert_allclose(np.degrees(phi[f.singular]) % 360, [180.0, 0.0], atol=1e-9)
    s, c = np.sin(phi), np.cos(phi)
    # dI/dphi = m1 (l^2/2 - 9 l^2/2) s c - 8 m2 l^2 s c; dV/dphi = g l c (m1/2 + 3 m1/2 + 2 m2)
    di = (M1 * (L**2 / 2 - 9 * L**2 / 2) - 8 * M2 * L**2) * s * c
    torque = 0.5 * OMEGA**2 * di + G * L * c * (M1 / 2 + 3 * M1 / 2 + 2 * M2)
    np.testing.assert_allclose(f.driving_torque, torque, rtol=0, atol=1e-9 * np.abs(torque).max())
    # momentum: sum m a = -omega^2 (m1 l/2 c + m1 l/2 c, m1 l/2 s + m1 3l/2 s + m2 2 l s)
    ma_x = -(OMEGA**2) * (M1 * L / 2 + M1 * L / 2) * c
    ma_y = -(OMEGA**2) * (M1 * L / 2 + 3 * M1 * L / 2 + 2 * M2 * L) * s
    weight = -(HOUSING + 2 * M1 + M2) * G
    np.testing.assert_allclose(f.foundation[:, 0], -ma_x, rtol=0, atol=1e-9 * abs(weight))
    np.testing.assert_allclose(f.foundation[:, 1], weight - ma_y, rtol=0, atol=1e-9 * abs(weight))
    # the reactions stay NaN there: they are indeterminate, and saying a number would be a guess
    assert np.isnan(f.reaction("B")[f.singular]).all()
    # the sweep's metrics are those of Forces (one policy), refined between the samples: the largest torque and
    # foundation force of the closed forms (past the change point, in the mode the samples there were solved in)
    from linkwork.kinetostatics.peaks import foundation_peak, torque_peak

    t = lw.sweep(
        "shears-slider-crank",
        {"links.knife.mass": ("20", "20", 1)},
        ["peak_driving_torque", "peak_foundation_force"],
        steps=360,
    )
    assert t["peak_driving_torque"][0] == pytest.approx(abs(torque_peak(f).value[0]), rel=1e-12)
    assert t["peak_foundation_force"][0] == pytest.approx(foundation_peak(f).value[0], rel=1e-12)

    def exact(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        s, c = np.sin(x), np.cos(x)
        size = np.abs(
            0.5 * OMEGA**2 * (M1 * (L**2 / 2 - 9 * L**2 / 2) - 8 * M2 * L**2) * s * c
            + G * L * c * (M1 / 2 + 3 * M1 / 2 + 2 * M2)
        )
        fx = OMEGA**2 * (M1 * L / 2 + M1 * L / 2) * c
        fy = weight + OMEGA**2 * (M1 * L / 2 + 3 * M1 * L / 2 + 2 * M2 * L) * s
        return size, np.hypot(fx, fy)

    for k, metric in enumerate(("peak_driving_torque", "peak_foundation_force")):
        top = _largest(lambda x, k=k: exact(x)[k])
        assert t[metric][0] == pytest.approx(top, rel=1e-9)
    assert np.nanmax(exact(phi)[0]) < _largest(lambda x: exact(x)[0]) * (1 - 1e-9)  # the samples miss the torque's


def _largest(fn) -> float:
    """The largest value of a closed form over a turn: a dense grid, then scipy's bounded search beside its best."""
    from scipy.optimize import minimize_scalar

    x = np.linspace(0, 2 * np.pi, 100001)
    i = int(np.argmax(fn(x)))
    found = minimize_scalar(
        lambda y: -float(fn(np.array([y]))[0]),
        bounds=(x[i] - 1e-4, x[i] + 1e-4),
        method="bounded",
        options={"xatol": 1e-12},
    )
    return max(-float(found.fun), float(fn(x)[i]))


def test_a_group_is_solvable_by_its_norms_exactly_where_its_singular_values_say_so():
    """:func:`solvable` with the inverse decides by the Frobenius norms and falls back on the singular values
    only in between: on matrices built as U diag(s) V with condition numbers on both sides of 1 / RATIO (within
    0.1 %, where the norms leave it open, and far off) it gives what the singular values of each say."""
    from linkwork.kinetostatics.reactions import RATIO, solvable

    rng = np.random.default_rng(7)
    kappas = np.concatenate([[1.0, 1e3, 1e7, 1e11, 1e14], np.array([0.999, 1.001, 2.0, 5.0, 0.5]) / RATIO])
    for n in (3, 6, 12):
        mats = []
        for kappa in kappas:
            u, _ = np.linalg.qr(rng.normal(size=(n, n)))
            v, _ = np.linalg.qr(rng.normal(size=(n, n)))
            s = np.geomspace(1.0, 1.0 / kappa, n) * 10.0 ** rng.uniform(-3, 3)
            mats.append(u @ np.diag(s) @ v)
        a = np.array(mats)
        expected = 1.0 / kappas > RATIO * (1 + 1e-6)
        np.testing.assert_array_equal(solvable(a), expected)
        np.testing.assert_array_equal(solvable(a, np.linalg.inv(a)), expected)
