"""The cross-checks' one home (linkwork.kinetostatics.crosschecks): each result found again by an independent method
agrees to rounding on every bundled example, a planted difference is measured as planted, and every output (the JSON,
the report, the viewer) shows the same checks."""

from __future__ import annotations

import json

import numpy as np
import pytest

import linkwork as lw
from commandline import linkwork
from linkwork.examples import names
from linkwork.kinetostatics import crosschecks, zhukovsky
from linkwork.kinetostatics.crosschecks import GRAPHICAL, cross_checks, free_body_residuals, lever_gaps
from linkwork.structure.model import one_crank

BALANCES = ("driving_torque_vs_power_balance", "foundation_force_vs_momentum", "foundation_moment_vs_momentum")


@pytest.mark.parametrize("name", names())
def test_every_independent_method_agrees_to_rounding(name: str) -> None:
    """Power and momentum balances, the lever and the force plans (one crank), and each group's free body: within
    1e-9 of the largest value compared, on 72 samples of each bundled example."""
    mech = lw.compile(name)
    if mech.structure.redundant:
        pytest.skip("statically indeterminate")
    f = lw.forces(mech, steps=72)
    found = cross_checks(f)
    assert set(found) == set(BALANCES) | (set(GRAPHICAL) if one_crank(mech) else set())
    assert all(not value > 1e-9 for value in found.values()), found  # NaN: nothing to compare (at rest)
    assert all(value <= 1e-9 for value in free_body_residuals(f).values())
    assert len(free_body_residuals(f)) == len(mech.structure.groups)


def test_a_lever_one_percent_off_is_measured_as_one_percent(monkeypatch) -> None:
    """The lever's balancing moment made 1 % larger than the driving torque: the check reads 0.01 of the largest
    torque at its largest sample (the relative difference is |0.01 Md| / max |Md|), and at each sample 0.01 |Md| over
    that largest."""
    f = lw.forces(lw.compile("double-cut-shears"), steps=36)
    real = zhukovsky.lever

    def off(forces):
        lever = real(forces)
        return type(lever)(**{**vars(lever), "balancing": lever.balancing * 1.01})

    monkeypatch.setattr(zhukovsky, "lever", off)
    torque = np.asarray(f.driving_torque)
    assert cross_checks(f)["driving_torque_vs_lever"] == pytest.approx(0.01, rel=1e-9)
    np.testing.assert_allclose(lever_gaps(f), 0.01 * np.abs(torque) / np.max(np.abs(torque)), rtol=1e-9)
    monkeypatch.setattr(crosschecks, "_moving", lambda forces: np.zeros(len(torque), bool))
    assert np.isnan(crosschecks.graphical_checks(f)["driving_torque_vs_lever"])


def test_the_json_and_the_viewer_show_the_checks_of_the_one_home() -> None:
    """``linkwork forces --json``'s ``checks`` are the five of :func:`cross_checks` with their values; the viewer's
    payload carries the same names."""
    from linkwork.web.cycle import solve_cycle
    from linkwork.web.payload import full_payload

    out = linkwork("forces", "shears-slider-crank", "--json")
    data = json.loads(out.stdout)
    mine = cross_checks(lw.forces(lw.compile("shears-slider-crank")))
    assert set(data["checks"]) == set(mine) == set(BALANCES) | set(GRAPHICAL)
    for key, value in mine.items():
        assert data["checks"][key] == pytest.approx(value, rel=1e-6, abs=1e-18)
    shown = full_payload(solve_cycle(lw.compile("shears-slider-crank"), 90))["forces"]["checks"]
    assert set(shown) == set(mine)
