"""Working-cycle benchmark: the percussion mechanism of seed 004 run blow by blow to its steady cycle.

Run with ``python benchmarks/bench_impact_cycle.py``.  Times, best of several
runs in one process: the whole run of :func:`linkwork.simulate_blows` from the
file's speed to the steady cycle (reduced quantities and splines over the
turn, the integration with its events, every blow's and rebound's impact map
and impulsive reactions, the contact phase's loads), the same run to a fixed
number of blows, and one blow's map (:func:`linkwork.impulse.impact_map`).  The
energy ledger's closure is printed beside: the accuracy the time buys.
"""

from __future__ import annotations

from timing import best

import linkwork as lw
from linkwork.impulse import simulate_blows, strike


def main() -> None:
    mech = lw.compile(lw.example("percussion-rocker"))
    run = simulate_blows(mech)
    impacts = sum(1 + b.rebounds for b in run.blows)
    t_run = best(lambda: simulate_blows(mech), budget=10.0)
    t_20 = best(lambda: simulate_blows(mech, blows=20, tol=0.0), budget=10.0)
    blow = run.last
    kw = dict(at="rocker.K", normal=(0.0, 1.0), angle=blow.angle, crank_speed=blow.crank_speed_before)
    kw.update(restitution=0.4, friction=0.15, tool_mass=3.0, drive_inertia=mech.machine.inertia)
    t_strike = best(lambda: strike(mech, **kw))
    print("percussion-rocker: working cycle with its motor, gear and flywheel")
    steady = f"{len(run.blows)} blows, {impacts} impacts, {len(run.t)} samples"
    print(f"  to the steady cycle: {steady}: {t_run * 1e3:.0f} ms")
    print(f"  20 blows: {t_20 * 1e3:.0f} ms ({t_20 / 20 * 1e3:.1f} ms a blow with its rebounds and contact phase)")
    print(f"  one blow's map with the impulsive reactions of every pair: {t_strike * 1e3:.2f} ms")
    print(f"  energy ledger of the run closes to {abs(run.balance) / run.energy['motor']:.1e} of the motor's work")


if __name__ == "__main__":
    main()
