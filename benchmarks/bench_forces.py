"""Kinetostatics benchmark: reactions and driving torque of the 7-link double-cut shears (seed 002).

Run with ``python benchmarks/bench_forces.py``.  No free tool computes joint
reactions of a planar mechanism over a cycle, so the peers are the two
ways of solving the same equations in NumPy: the batched group-by-group
solves of :func:`linkwork.kinetostatics.reactions.solve_reactions` (linkwork's
reference path, used without numba), and one global dense solve per sample,
``J^T lam = -Q`` with all 23 constraint rows at once (the textbook
formulation).  linkwork runs through its public API (kinematics, loads with
the cutting force of example-data.md, reactions, foundation), with its
compiled kernels, on all cores and on one thread.  Each peer's driving
torque is checked against linkwork's before its time is reported.  Best of
several runs, one process.
"""

from __future__ import annotations

import sys

import numpy as np
from timing import best

import linkwork as lw
from linkwork import threads as threads_
from linkwork.kinetostatics import reactions_numba
from linkwork.kinetostatics.reactions import inertia_and_gravity, solve_reactions
from linkwork.structure.constraints import residuals_and_jacobian
from linkwork.structure.parameters import Geometry


def numpy_groups(mech, phi):
    kin = lw.kinematics(mech, phi)
    loads = inertia_and_gravity(kin)
    return solve_reactions(kin, loads)[0][0, :, -1]


def numpy_global(mech, phi):
    kin = lw.kinematics(mech, phi)
    loads = inertia_and_gravity(kin)
    geom = Geometry(*(np.moveaxis(g, (0, 1), (2, 3)) for g in (kin.local, kin.origin, kin.axis)))
    _, jac = residuals_and_jacobian(kin.pose, mech, geom=geom)
    moving = np.swapaxes(jac[..., 3:], -1, -2)  # (V, A, 3n, m): the frame's columns left out
    rhs = -loads.total[..., 1:, :].reshape(loads.total.shape[:2] + (-1,))
    return np.linalg.solve(moving, rhs[..., None])[0, :, -1, 0]


def main() -> None:
    mech = lw.compile(lw.example("double-cut-shears"))
    n = 36_000
    phi = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    reference = lw.forces(mech, phi).driving_torque
    scale = np.nanmax(np.abs(reference))
    rows = []

    def run(label, fn, threads=None):
        saved = threads_.THREADS
        if threads is not None:
            threads_.set_threads(threads)
        try:
            torque = fn()
            ok = np.isfinite(reference) & np.isfinite(torque)
            err = float(np.max(np.abs(torque[ok] - reference[ok])) / scale)
            if err > 1e-9:
                sys.exit(f"{label}: driving torque differs from linkwork's by {err:.1e} (relative)")
            t = best(fn, budget=5.0)
        finally:
            threads_.set_threads(saved)
        rows.append((label, t, err))

    if reactions_numba.available():
        run(f"linkwork ({threads_.THREADS} threads)", lambda: lw.forces(mech, phi).driving_torque)
        run("linkwork-1 (one thread)", lambda: lw.forces(mech, phi).driving_torque, threads=1)
    else:
        print("numba is not installed: linkwork runs its NumPy path (pip install '.[bench]')")
        run("linkwork (NumPy)", lambda: lw.forces(mech, phi).driving_torque)
    run("numpy, group by group", lambda: numpy_groups(mech, phi))
    run("numpy, global dense solve", lambda: numpy_global(mech, phi))
    print(f"reactions and driving torque of the double-cut shears (7 links, 23 rows), {n} crank angles")
    print(f"{'':32s} {'time, ms':>10s} {'M positions/s':>14s} {'max rel. diff':>14s}")
    for label, t, err in rows:
        print(f"{label:32s} {t * 1e3:10.2f} {n / t / 1e6:14.3f} {err:14.1e}")


if __name__ == "__main__":
    main()
