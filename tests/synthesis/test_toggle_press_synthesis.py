"""Toggle-press synthesis: the written file's stroke, as the kinematic analysis measures it, is the requested
one; the crank torque of the nominal force at the nominal point, by the project's forces, is the virtual-work
closed form and agrees with a finite difference of the ram's position; an insufficient torque limit says
which force it allows."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import linkwork as lw
from linkwork.errors import SynthesisError
from linkwork.motion.analysis import extremes
from linkwork.synthesis import synthesize
from linkwork.synthesis.toggle_press import geometry, nominal

#: A bound on the least transmission angle low enough that the geometry alone decides (the design rule's 40 deg
#: refuses some of the random requests, which these tests make for the geometry).
FREE = 1e-6


def ram_stroke(spec) -> float:
    (ram,) = [e for e in extremes(lw.kinematics(spec, steps=3600)) if e.kind == "slider"]
    return ram.stroke


def torque_by_difference(spec, stroke: float, before: float, force: float, swing: float, k: float) -> float:
    """F times the ram's descent per radian of the crank (turning clockwise, the drive angle falling) at the
    nominal point, by a central difference of the ram's height that lw.kinematics gives (no velocity
    analysis): the clockwise torque, by virtual work."""
    angle, _ = nominal(geometry(stroke, swing, k), before)
    h = 1e-5
    y = lw.kinematics(spec, np.array([angle - h, angle + h])).position("R")[:, 1]
    return force * float(y[1] - y[0]) / (2 * h)


def test_the_default_swing_of_45_deg_gives_toggle_links_of_h_over_2_minus_root_2():
    """H = 2 a (1 - cos 45 deg) = a (2 - sqrt 2); the lower link at 45 deg to the guide at the top, within the
    40 deg rule."""
    s = synthesize("toggle-press", stroke=0.2, force=1e5, before=0.01, torque=5e3)
    assert s.dimensions["toggle"] == pytest.approx(0.2 / (2 - math.sqrt(2)), rel=1e-12)
    tol = s.tolerances  # the lengths written to 0.1 mm
    assert ram_stroke(s.spec) == pytest.approx(0.2, abs=tol["stroke"])
    nominal = s.predicted["torque_at_nominal"]
    assert s.measured["torque_at_nominal"] == pytest.approx(nominal, abs=tol["torque_at_nominal"])
    fd = torque_by_difference(s.spec, 0.2, 0.01, 1e5, math.radians(45), 1.2)
    assert s.measured["torque_at_nominal"] == pytest.approx(fd, rel=1e-6)
    mu = lw.motion.analysis.transmission(lw.kinematics(s.spec, steps=3600))
    least = min(float(np.min(v)) for v in mu.values())
    assert least == pytest.approx(math.radians(44.58), abs=math.radians(0.01) + tol["min_transmission_angle"])


def test_a_60_deg_swing_is_refused_by_the_rule_and_accepted_below_it():
    """The lower link at 60 deg to the ram's guide at the top: 30 deg of transmission, under the rule's 40; the
    message names the largest swing (50 deg), and a bound of 30 deg lets it through with a = H."""
    with pytest.raises(SynthesisError, match=r"least transmission angle of 30 deg.*a swing of at most 50 deg"):
        synthesize("toggle-press", stroke=0.2, force=1e5, before=0.01, torque=5e3, swing=math.radians(60))
    s = synthesize(
        "toggle-press",
        stroke=0.2,
        force=1e5,
        before=0.01,
        torque=5e3,
        swing=math.radians(60),
        min_transmission_angle=math.radians(30) * (1 - 1e-9),
    )
    assert s.dimensions["toggle"] == pytest.approx(0.2, rel=1e-12)


@settings(max_examples=8, deadline=None)
@given(
    stroke=st.floats(0.02, 1.0),
    where=st.floats(0.02, 0.9),
    force=st.floats(1e3, 1e6),
    swing=st.floats(math.radians(20), math.radians(80)),
    k=st.floats(1.05, 1.6),
)
def test_random_feasible_requirements_are_met_as_the_analysis_measures_them(stroke, where, force, swing, k):
    before = where * stroke
    _, rho = nominal(geometry(stroke, swing, k), before)
    s = synthesize(
        "toggle-press",
        stroke=stroke,
        force=force,
        before=before,
        torque=1e9,  # the geometry here; the limit's own tests are below
        swing=swing,
        time_ratio=k,
        min_transmission_angle=FREE,
    )
    tol = s.tolerances  # the lengths written to 0.1 mm
    assert ram_stroke(s.spec) == pytest.approx(stroke, abs=tol["stroke"])
    assert s.measured["torque_at_nominal"] == pytest.approx(force * rho, abs=tol["torque_at_nominal"])
    fd = torque_by_difference(s.spec, stroke, before, force, swing, k)
    assert s.measured["torque_at_nominal"] == pytest.approx(fd, rel=1e-5)


def test_the_torque_grows_slower_than_the_distance_before_the_bottom():
    """Near the bottom s ~ (phi - phi0)^4, so the torque ratio goes as s^(3/4): a tenth of the distance
    needs about 10^(-3/4) of the torque."""
    geo = geometry(0.2, math.radians(60), 1.2)
    ratio = nominal(geo, 1e-5)[1] / nominal(geo, 1e-4)[1]
    assert ratio == pytest.approx(10 ** (-0.75), rel=0.02)


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        ({"before": 0.3}, "it must lie within the stroke"),
        ({"time_ratio": 1.0}, "the time ratio K must be over 1"),
        ({"swing": math.radians(100)}, "expected between 0 and 90 deg"),
    ],
)
def test_requirements_that_cannot_be_met_say_so(extra, words):
    requirements = {"stroke": 0.2, "force": 1e5, "before": 0.01, "torque": 5e3, **extra}
    with pytest.raises(SynthesisError) as err:
        synthesize("toggle-press", **requirements)
    assert words in str(err.value)


def test_the_file_carries_the_nominal_force_as_a_process_load():
    s = synthesize("toggle-press", stroke=0.2, force=1e5, before=0.01, torque=5e3)
    (load,) = s.spec.loads.values()
    assert load.type == "process"
    assert any("stroke H = 200 mm" in line for line in s.text.splitlines())


def _turn(path, steps: int = 7200):
    """(ram heights above the bottom (m), the process load's share of the driving torque (N m), the whole
    driving torque (N m)) over a turn of the written file as lw.forces measures it: the load's share is the file's
    torque less the torque of the same file without its loads (forces are linear in the loads)."""
    spec = lw.load(path)
    whole = lw.forces(spec, steps=steps)
    idle = lw.forces(spec.model_copy(update={"loads": {}}), steps=steps).driving_torque
    y = whole.kinematics.position("R")[:, 1]
    return y - y.min(), np.ravel(whole.driving_torque) - np.ravel(idle), np.ravel(whole.driving_torque)


@pytest.mark.parametrize(
    ("stroke", "force", "before", "limit"),
    [(0.040, 1e6, 0.002, 8e3), (0.200, 1e5, 0.010, 5e3)],
)
def test_the_written_press_loads_from_the_nominal_point_and_keeps_its_torque_limit(
    tmp_path, stroke, force, before, limit
):
    """The two presses of the report: the file read back, its load acts exactly over the last ``before`` of the
    ram's descent (none above it, on every sample below it) and its peak driving torque over the whole turn, on a
    grid ten times the synthesis's, stays within the limit (the load from 2 ``before`` gave 10,359 N m against
    8 kN m)."""
    s = synthesize("toggle-press", stroke=stroke, force=force, before=before, torque=limit)
    path = s.write(tmp_path / "press.yaml")
    height, load, whole = _turn(path)
    down = np.gradient(height) < 0
    acting = np.abs(load) > 1e-6 * force * before
    assert not acting[height > before * (1 + 1e-9)].any()
    assert acting[down & (height < before * (1 - 1e-3)) & (height > before * 1e-3)].all()
    assert np.max(np.abs(whole)) <= limit
    (pressing,) = lw.load(path).loads.values()
    assert pressing.workpiece[1] - pressing.workpiece[0] == pytest.approx(before, rel=1e-9)  # 12 digits of each end


def test_a_limit_under_the_peak_is_refused_with_the_limit_needed_and_the_force_it_allows(tmp_path):
    """exit 2, no file; the torque named is at least the peak the file would have, and the force named meets the
    limit when asked for (both rounded in their safe directions)."""
    from commandline import linkwork

    out = tmp_path / "press.yaml"
    args = ["synthesize", "toggle-press", "--stroke", "200mm", "--force", "100kN", "--before", "10mm"]
    run = linkwork(*args, "--torque", "3kN*m", "--out", str(out))
    assert run.returncode == 2 and not out.exists() and len(run.stderr.splitlines()) == 1
    needed = float(run.stderr.split("needs a crank torque of ")[1].split(" N m")[0])
    allowed = float(run.stderr.split("allows at most ")[1].split(" kN")[0]) * 1e3
    fits = synthesize("toggle-press", stroke=0.2, force=allowed, before=0.01, torque=3e3)
    _, load, whole = _turn(fits.write(tmp_path / "fits.yaml"))
    assert 3e3 * 0.99 < np.max(np.abs(whole)) <= 3e3  # 4 digits rounded down, a grid a little short of the jump
    asked = np.max(np.abs(whole + (1e5 / allowed - 1) * load))  # the asked force's torque, the loads scaled
    assert asked * (1 - 1e-2) < needed and asked <= needed
