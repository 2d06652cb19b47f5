"""The rule for self-locking (kinetostatics.friction.LOCKING) against maps solved by hand, and the number of
evaluations of the friction's map next to a lock."""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkwork as lw
from linkwork.errors import FrictionWarning
from linkwork.kinetostatics import friction
from linkwork.kinetostatics.friction import LOCKING, MAX_ITERATIONS


def _counted(monkeypatch) -> list[int]:
    """Count the evaluations of the friction's map ``T``."""
    count = [0]
    inner = friction._map

    def counting(*args):
        count[0] += 1
        return inner(*args)

    monkeypatch.setattr(friction, "_map", counting)
    return count


def _one_guide(products: list[float], a: float = 1000.0, f: float = 0.1):
    """One prismatic pair whose normal force is ``a + g mu`` (``a`` without friction, ``g`` the force that a unit
    of its own friction adds), one sample for each ``f g`` of ``products``: ``(revolute, lam0, gain, c)``."""
    n = len(products)
    lam0 = np.zeros((1, n, 2))
    lam0[..., 1] = a
    gain = np.zeros((1, n, 2, 1))
    gain[0, :, 1, 0] = np.asarray(products) / f
    return np.array([False]), lam0, gain, np.array([f])


def test_one_guide_locks_where_its_friction_multiplies_its_force_by_the_limit(monkeypatch):
    """``mu = f |a + g mu|``: for ``f g < 1`` the root ``mu = f a / (1 - f g)``, the force ``a / (1 - f g)``, so
    friction multiplies it by ``1 / (1 - f g)`` (and ``f g`` is the spectral radius of ``dT/dmu``); for ``f g >= 1``
    no size ``mu >= 0`` solves it (the iterates grow by ``f g`` a step).  The rule locks from ``1 / (1 - f g) =
    LOCKING``, ``f g = 0.999``; next to it, within 3e-5 of 1 either side, it is told in a few evaluations of the
    map, not after thousands of successive approximations."""
    products = [0.5, 0.998, 0.9989, 0.9991, 0.9995, 0.99997, 1.00003, 1.00024, 2.0]
    count = _counted(monkeypatch)
    mu, _, locked, unconverged = friction._iterate(*_one_guide(products))
    p = np.array(products)
    assert not unconverged.any()
    assert locked[0].tolist() == [x >= 1 - 1 / LOCKING for x in products]  # 1/(1 - fg): 2, 500, 909, 1111, 2000, ...
    solved = ~locked[0]
    np.testing.assert_allclose(mu[0, solved, 0], 0.1 * 1000.0 / (1 - p[solved]), rtol=1e-10)
    assert count[0] <= MAX_ITERATIONS + 10  # it took 2000 more, the successive approximations, before the rule


def _two_guides(products: list[float]):
    """Two prismatic pairs, each loaded by the other's friction: normal forces ``n1 = a1 + g12 mu2``, ``n2 = a2 + g21
    mu1`` with ``a1 = 1000 N``, ``a2 = 500 N``, ``f1 = 0.1``, ``f2 = 0.2``, ``g12 = 20``, ``g21`` from the product
    ``p = f1 f2 g12 g21`` of each sample: ``(revolute, lam0, gain, c)``."""
    n = len(products)
    lam0 = np.zeros((1, n, 4))
    lam0[..., 1], lam0[..., 3] = 1000.0, 500.0
    gain = np.zeros((1, n, 4, 2))
    gain[0, :, 1, 1] = 20.0
    gain[0, :, 3, 0] = np.asarray(products) / (0.1 * 0.2 * 20.0)
    return np.array([False, False]), lam0, gain, np.array([0.1, 0.2])


def test_two_guides_lock_by_the_amplification_of_the_largest_force(monkeypatch):
    """``dT/dmu = [[0, f1 g12], [f2 g21, 0]]``, eigenvalues ``±sqrt(p)``: the spectral radius ``rho = sqrt(p)``.  By
    hand, ``mu1 = f1 (a1 + f2 g12 a2) / (1 - p) = 0.1 * 3000 / (1 - p)``, ``mu2 = f2 (a2 + f1 g21 a1) / (1 - p)``; the
    largest force is ``n1 = 3000 / (1 - p)`` (``n2 = (500 + 100 g21) / (1 - p)``, ``g21`` near 2.5), 3 / (1 - p) times
    the largest without friction (1000 N): it reaches LOCKING at ``p = 0.997`` (``rho = 0.9985``), where ``1 / (1 -
    rho)`` is only 667.  ``p = 0.996``: friction multiplies the force by 750, solved; ``p = 0.998``: 1500, locked."""
    products = [0.5, 0.996, 0.998, 0.99997, 1.00003, 1.5]
    count = _counted(monkeypatch)
    mu, _, locked, unconverged = friction._iterate(*_two_guides(products))
    p = np.array(products)
    g21 = p / (0.1 * 0.2 * 20.0)
    assert not unconverged.any()
    assert locked[0].tolist() == [False, False, True, True, True, True]
    by_hand = np.stack([0.1 * 3000.0 / (1 - p), 0.2 * (500.0 + 100.0 * g21) / (1 - p)], -1)
    np.testing.assert_allclose(mu[0, :2], by_hand[:2], rtol=1e-10)
    np.testing.assert_allclose(friction._amplification(*_two_guides(products)[:3], mu)[0, :2], 3 / (1 - p[:2]))
    slope = friction._map(*_two_guides(products), mu)[1]
    np.testing.assert_allclose(friction._radius(slope[0, :2]), np.sqrt(p[:2]), rtol=1e-12)
    assert count[0] <= MAX_ITERATIONS + 10


@pytest.mark.filterwarnings("ignore::linkwork.errors.FrictionWarning")
def test_the_shears_friction_next_to_their_lock_stays_under_the_limit_and_its_peak_is_refined_quickly(monkeypatch):
    """The slider-crank shears with f = 0.1 lock about phi = 83 deg.  At 201 angles across the edge each sample
    either moves, with pair forces at most LOCKING times those of the same shears without friction (solved apart),
    or locks; none is left unsolved; the forces grow towards the lock.  Refining the peak of the driving torque next
    to it takes a few hundred evaluations of the map (24131 before the rule: each re-solve near the edge ran the
    2000 successive approximations)."""
    from kinetostatics.test_friction import _shears
    from linkwork.kinetostatics.peaks import torque_peak

    rough, smooth = _shears(0.1, 0.020), _shears(0.0, 0.020)
    drive = np.radians(np.linspace(170.0, 174.0, 201))  # phi = drive angle - 90 deg, from 80 to 84 deg
    f, f0 = lw.forces(rough, drive), lw.forces(smooth, drive)
    fr = f.friction
    assert fr is not None and not fr.unconverged.any()
    pairs = ("O", "A", "B", "guide")
    largest = np.max([np.hypot(*f.reaction(j)[:, :2].T) for j in pairs], 0)
    largest0 = np.max([np.hypot(*f0.reaction(j)[:, :2].T) for j in pairs], 0)
    moves = ~fr.locked[0]
    assert np.isfinite(largest[moves]).all() and np.isnan(largest[~moves]).all()
    ratio = largest[moves] / largest0[moves]
    assert np.all(ratio < LOCKING)
    edge = int(np.argmax(~moves))  # the first locked sample: the ratio climbs towards it
    assert 0 < edge and moves[:edge].all() and ratio[edge - 1] > 0.1 * LOCKING and ratio[edge - 1] > ratio[0] * 10
    assert math.isclose(math.degrees(drive[edge]) - 90.0, 82.8, abs_tol=0.1)
    count = _counted(monkeypatch)
    with pytest.warns(FrictionWarning):
        whole = lw.forces(rough, steps=360)
    torque_peak(whole)
    assert count[0] <= 1000
