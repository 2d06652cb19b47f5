"""Synthesis benchmark: one mechanism from its requirements, verified by the analysis of the written file.

Run with ``python benchmarks/bench_synthesis.py``.  Times ``lw``'s synthesis of the slider-crank of
docs/how-to/synthesize.md (stroke 400 mm, K = 1.05, largest pressure angle at most 30 deg), of a crank-rocker
(swing 45 deg, K = 1.2, rocker 250 mm), of a slotted lever (stroke 600 mm, K = 1.4) and of a toggle press (stroke
200 mm, 100 kN at 10 mm before the bottom, 5 kN m; its torque measured by ``lw.forces``): the closed forms, the member
picked from the family, the file's text through the YAML writer, the file read back and its stroke (swing), time
ratio and extreme angle measured by ``lw.kinematics`` over a turn of 720 samples and checked to 1e-9.  Best
of several runs (see ``timing.py``).
"""

from __future__ import annotations

import math

from timing import best

from linkwork.synthesis import synthesize

CASES = {
    "slider-crank": {"stroke": 0.4, "time_ratio": 1.05, "max_pressure_angle": math.radians(30)},
    "crank-rocker": {"swing": math.radians(45), "time_ratio": 1.2, "rocker": 0.25},
    "slotted-lever": {"stroke": 0.6, "time_ratio": 1.4},
    "toggle-press": {"stroke": 0.2, "force": 1e5, "before": 0.01, "torque": 5e3},
}


def main() -> None:
    for kind, requirements in CASES.items():
        result = synthesize(kind, **requirements)
        seconds = best(lambda kind=kind, requirements=requirements: synthesize(kind, **requirements))
        worst = max(abs(result.measured[k] / v - 1) for k, v in result.predicted.items())
        print(f"{kind:14s} {seconds * 1e3:8.1f} ms   (measured against the closed forms: {worst:.1e} relative)")


if __name__ == "__main__":
    main()
