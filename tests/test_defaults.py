"""One rule for the public functions' ``steps`` and for the values of ``variants``."""

from __future__ import annotations

import inspect
import math

import numpy as np
import pytest

import linkwork as lw
from linkwork.errors import ParameterError
from linkwork.limits import DYNAMICS_STEPS, TURN_STEPS

#: The public analyses over a turn of the crank, and those of machine dynamics.
TURN = ("kinematics", "forces", "balance", "bolt_speed", "sweep", "optimize")
DYNAMICS = ("reduced", "dynamics", "simulate_blows")


@pytest.mark.parametrize("name", TURN + DYNAMICS)
def test_steps_is_keyword_only_with_the_default_of_its_kind(name):
    steps = inspect.signature(getattr(lw, name)).parameters["steps"]
    assert steps.kind == inspect.Parameter.KEYWORD_ONLY
    expected = DYNAMICS_STEPS if name in DYNAMICS else TURN_STEPS
    assert steps.default in (expected, None)  # None: either angles or steps, by default these steps


def test_the_defaults_of_the_kinds():
    assert (TURN_STEPS, DYNAMICS_STEPS) == (360, 3600)
    kin = lw.kinematics("four-bar")
    assert len(kin.angles) == 360
    np.testing.assert_allclose(np.diff(np.unwrap(kin.angles)), 2 * math.pi / 360, rtol=1e-12)
    assert len(lw.forces("shears-slider-crank").driving_torque) == 360
    assert len(lw.reduced("double-cut-shears").inertia) == 3600
    with pytest.raises(TypeError):
        lw.reduced("double-cut-shears", 720)  # type: ignore[misc]
    with pytest.raises(TypeError):
        lw.bolt_speed("shears-slider-crank", 0.0, 72)  # type: ignore[misc]


def test_variants_take_values_with_units_as_sweep_does():
    """``"90 mm"``, a bare ``"110"`` in the file's unit (mm) and 0.1 (SI): the crank pin A of the four-bar at
    the assembly angle, 60 deg, lies at l (cos 60, sin 60)."""
    kin = lw.kinematics("four-bar", steps=4, variants={"links.crank.length": ["90 mm", 0.1, "110"]})
    lengths = np.array([0.09, 0.1, 0.11])
    np.testing.assert_allclose(kin.position("A")[:, 0], lengths[:, None] * [0.5, math.sqrt(3) / 2], rtol=1e-12)
    with pytest.raises(
        ParameterError,
        match=r'variants\["links.crank.length"\]: expected numbers in m or lengths '
        r'with a unit such as "90 mm", got \'90 kg\'',
    ):
        lw.kinematics("four-bar", steps=4, variants={"links.crank.length": ["90 kg"]})
    with pytest.raises(ParameterError, match="did you mean"):
        lw.forces("four-bar", steps=4, variants={"links.crank.lenght": ["90 mm"]})


def test_bolts_print_their_angles_in_degrees():
    """The shears' crank (m1 = 1 kg... the housing shear m1 omega^2 l = 150 N) at 180 deg: printed in degrees, as
    the command line prints it; the attributes stay SI."""
    bolts = lw.forces("shears-slider-crank", steps=360).bolts()
    # refined between the samples; 180 deg is a change point, where the reactions solved beside it are
    # ill-conditioned: the flat maximum's angle is found to 1e-5 rad (its value to 1e-11)
    assert bolts.shear_angle == pytest.approx(math.pi, abs=1e-5)
    assert bolts.shear == pytest.approx(150.0, rel=1e-11)
    assert "shear 150 N at 180.0 deg" in str(bolts)
    assert str(bolts).endswith("; crank angles to the x axis)")
