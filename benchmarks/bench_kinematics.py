"""Kinematics benchmark: linkwork against pylinkage, a NumPy closed form and a plain C closed form.

Run with ``python benchmarks/bench_kinematics.py``.  All peers solve the
same four-bar (the bundled ``four-bar`` example): positions, velocities and
accelerations over a turn of the crank, in one process, one after the other,
best of several runs.  The C kernel is compiled at run time with the
system's C compiler (``cc -O3``); pylinkage (with numba) is used when
installed.  linkwork runs through its public API, with the compiled
kernels when numba is installed (``pip install ".[bench]"``), on all cores
and on one thread.  Each peer's coupler-rocker joint B is checked against
linkwork's before its time is reported.

linkwork is timed as a user runs it: ``lw.kinematics`` and then the
position, velocity and acceleration of joint B read from the result (the
closed forms give B's directly).  The solve alone is timed too, and the
fixed cost of a call: the solve less the time the compiled kernels
themselves take.
"""

from __future__ import annotations

import ctypes
import math
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from timing import best

import linkwork as lw
from linkwork import threads
from linkwork.motion import kernels_numba

A, B, C, D = 0.10, 0.35, 0.25, 0.30
W = 2 * math.pi  # 60 rpm


def numpy_closed_form(phi, sigma):
    ax, ay = A * np.cos(phi), A * np.sin(phi)
    vax, vay, aax, aay = -W * ay, W * ax, -W * W * ax, -W * W * ay
    dx, dy = D - ax, -ay
    dist2 = dx * dx + dy * dy
    inv = 1 / np.sqrt(dist2)
    t = (B * B - C * C + dist2) * 0.5 * inv
    h = sigma * np.sqrt(B * B - t * t)
    ex, ey = dx * inv, dy * inv
    bx, by = ax + t * ex - h * ey, ay + t * ey + h * ex
    r1x, r1y, r2x, r2y = bx - ax, by - ay, bx - D, by
    c1x, c1y, c2x, c2y = -r1y, r1x, r2y, -r2x
    det = c1x * c2y - c1y * c2x
    w2 = (-vax * c2y + vay * c2x) / det
    w3 = (-c1x * vay + c1y * vax) / det
    rax = -aax + w2 * w2 * r1x - w3 * w3 * r2x
    ray = -aay + w2 * w2 * r1y - w3 * w3 * r2y
    e2 = (rax * c2y - ray * c2x) / det
    e3 = (c1x * ray - c1y * rax) / det
    return bx, by, -w3 * r2y, w3 * r2x, -e3 * r2y - w3 * w3 * r2x, e3 * r2x - w3 * w3 * r2y, w2, w3, e2, e3


def c_kernel():
    cc = shutil.which("cc") or shutil.which("gcc")
    if cc is None:
        return None
    tmp = Path(tempfile.mkdtemp())
    lib = tmp / "four_bar.so"
    src = Path(__file__).with_name("four_bar_c.c")
    subprocess.run([cc, "-O3", "-march=native", "-shared", "-fPIC", str(src), "-o", str(lib), "-lm"], check=True)
    dll = ctypes.CDLL(str(lib))
    dp = ctypes.POINTER(ctypes.c_double)
    runs = []
    for name, width in (("four_bar", 10), ("four_bar_full", 27)):
        f = getattr(dll, name)
        f.argtypes = [ctypes.c_int, dp, *[ctypes.c_double] * 6, dp]

        def run(phi, sigma, f=f, width=width):
            out = np.empty((len(phi), width))
            f(len(phi), phi.ctypes.data_as(dp), A, B, C, D, W, sigma, out.ctypes.data_as(dp))
            return out

        runs.append(run)
    return runs


def pylinkage_four_bar(n):
    try:
        import pylinkage as pl
    except ImportError:
        return None
    mech = lw.compile(lw.example("four-bar"))
    b0 = mech.points0()[mech.point_names.index("rocker.B")]
    o2, o4 = pl.Ground(0.0, 0.0, name="O2"), pl.Ground(D, 0.0, name="O4")
    crank = pl.Crank(o2, radius=A, angular_velocity=2 * math.pi / n, initial_angle=math.radians(60), name="A")
    dyad = pl.RRRDyad(crank.output, o4, distance1=B, distance2=C, x=b0[0], y=b0[1], name="B")
    linkage = pl.Linkage([o2, o4, crank, dyad], name="four-bar")
    linkage.set_input_velocity(crank, W)
    idx = [c.name for c in linkage.components].index("B")

    def run():
        return linkage.step_fast_with_kinematics(iterations=n)

    return run, idx


def solve_and_read(mech, phi):
    """What a user does: solve the turn, then read joint B's position, velocity and acceleration."""
    kin = lw.kinematics(mech, phi)
    return kin.position("B"), kin.velocity("B"), kin.acceleration("B")


def kernel_only(mech, phi):
    """The compiled kernel alone on ``phi`` (no argument handling, events or result objects), or None
    without numba."""
    if not kernels_numba.available():
        return None
    from linkwork.structure.parameters import apply

    geom, values = apply(mech)[0], phi[:, None]
    rates, accels = np.full_like(values, mech.drive_speed[0]), np.zeros_like(values)
    return lambda: kernels_numba.run(mech, geom, values, rates, accels)


def main() -> None:
    mech = lw.compile(lw.example("four-bar"))
    sigma = mech.program[1].branch
    sigma_c = sigma  # the same assembly mode in the closed forms
    rows = []
    ckern = c_kernel()
    for n in (360, 36_000):
        phi = mech.drive_start[0] + 2 * np.pi * np.arange(n) / n
        kin = lw.kinematics(mech, phi)
        ref = kin.position("B")
        t_lw = best(lambda phi=phi: solve_and_read(mech, phi))
        t_solve = best(lambda phi=phi: lw.kinematics(mech, phi))
        saved = threads.THREADS
        threads.set_threads(1)
        t_lw1 = best(lambda phi=phi: solve_and_read(mech, phi))
        threads.set_threads(saved)
        kernel = kernel_only(mech, phi)
        t_kernel = best(kernel) if kernel is not None else float("nan")
        npy = numpy_closed_form(phi, sigma_c)
        err_np = float(np.max(np.abs(np.stack(npy[:2], -1) - ref)))
        t_np = best(lambda phi=phi: numpy_closed_form(phi, sigma_c))
        row = {"case": f"four-bar, {n} angles", "n": n, "linkwork": t_lw, "linkwork-1": t_lw1, "solve": t_solve}
        row["kernel"] = t_kernel
        row.update(numpy=t_np, err_numpy=err_np)
        if ckern is not None:
            c_b, c_full = ckern
            out = c_b(phi, sigma_c)
            row["err_c"] = float(np.max(np.abs(out[:, :2] - ref)))
            row["c"] = best(lambda phi=phi, f=c_b: f(phi, sigma_c))
            full = c_full(phi, sigma_c)
            # linkwork's state of every moving link in the kernel's layout: x, y, angle, their rates, accelerations
            mine = np.stack([np.stack([kin.q[k], kin.v[k], kin.a[k]], 0)[:, :, 0] for k in (1, 2, 3)])  # (3, 3, 3, A)
            mine = np.moveaxis(mine.reshape(27, -1), 0, 1)
            diff = np.abs(full - mine)
            diff[:, 2::9] = np.abs(np.angle(np.exp(1j * (full[:, 2::9] - mine[:, 2::9]))))  # angles modulo a turn
            row["err_c-full"] = float(diff.max() / np.abs(mine).max())
            row["c-full"] = best(lambda phi=phi, f=c_full: f(phi, sigma_c))
        pyl = pylinkage_four_bar(n)
        if pyl is not None:
            run, idx = pyl
            pos = run()[0]
            start = np.argmin(np.abs(pos[:, idx, 0] - ref[0, 0]) + np.abs(pos[:, idx, 1] - ref[0, 1]))
            row["err_pylinkage"] = float(np.max(np.abs(np.roll(pos[:, idx], -start, axis=0) - ref)))
            row["pylinkage"] = best(run)
        rows.append(row)
    variants = {"links.crank.length": np.linspace(0.09, 0.11, 10_000)}
    phi = mech.drive_start[0] + 2 * np.pi * np.arange(360) / 360
    t_var = best(lambda: lw.kinematics(mech, phi, variants=variants), repeat=3, budget=20)
    compiled = "NumPy kernels (no numba)"
    if kernels_numba.available():
        compiled = f"compiled kernels, up to {threads.THREADS} threads"
    print(f"python {sys.version.split()[0]}, numpy {np.__version__}; linkwork: {compiled}; linkwork-1: one thread")
    print("c: the closed form for B and the two angular rates (10 numbers a sample); c-full: the same closed")
    print("form giving what linkwork gives, every moving link's pose, velocity and acceleration (27 numbers);")
    print("its last column is the largest difference from linkwork's relative to the largest value;")
    print("linkwork: lw.kinematics and reading B's position, velocity and acceleration; solve: lw.kinematics")
    print("alone; kernel: the compiled kernels alone (kernels_numba.run)")
    print(
        f"{'case':28s} {'peer':10s} {'time, ms':>10s} {'configs/s':>12s} {'vs C':>7s} {'vs C-full':>9s} "
        f"{'max |dB|, m':>12s}"
    )
    for row in rows:
        for peer in ("linkwork", "linkwork-1", "solve", "kernel", "numpy", "c", "c-full", "pylinkage"):
            if peer not in row:
                continue
            t = row[peer]
            rate = row["n"] / t
            ratio = t / row["c"] if "c" in row else float("nan")
            ratio_full = t / row["c-full"] if "c-full" in row else float("nan")
            err = row.get(f"err_{peer}", 0.0)
            print(
                f"{row['case']:28s} {peer:10s} {t * 1e3:10.3f} {rate:12.3e} {ratio:7.2f} {ratio_full:9.2f} {err:12.1e}"
            )
    print(f"{'four-bar, 10000 x 360':28s} {'solve':10s} {t_var * 1e3:10.1f} {3.6e6 / t_var:12.3e}")
    for row in rows:
        fixed = row["solve"] - row["kernel"]
        print(
            f"{row['case']}: fixed cost of lw.kinematics (the solve less the kernel) {fixed * 1e3:.3f} ms, "
            f"{fixed / row['solve']:.0%} of the solve; reading B {(row['linkwork'] - row['solve']) * 1e3:.3f} ms"
        )


if __name__ == "__main__":
    main()
