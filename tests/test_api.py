"""Every analysis takes its mechanism the same ways: a file path, an example name, a Spec or a Mechanism."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from ruamel.yaml import YAML

import linkwork as lw
from linkwork.examples import text


def _forms(name, tmp_path):
    path = tmp_path / f"{name}.yaml"
    path.write_text(text(name))
    spec = lw.load(name)
    return {"name": name, "str path": str(path), "Path": Path(path), "Spec": spec, "Mechanism": lw.compile(spec)}


def test_compile_and_kinematics_take_every_form(tmp_path):
    ref = None
    for form, arg in _forms("four-bar", tmp_path).items():
        mech = lw.compile(arg)
        assert isinstance(mech, lw.Mechanism), form
        b = lw.kinematics(arg, steps=36).position("B")
        ref = b if ref is None else ref
        np.testing.assert_array_equal(b, ref, err_msg=form)
    mech = lw.compile("four-bar")
    assert lw.compile(mech) is mech


@pytest.mark.slow  # over the default lane's budget on the NumPy kernels (tests/conftest.py)
def test_forces_dynamics_reduced_balance_and_bolts_take_every_form(tmp_path):
    forms = _forms("double-cut-shears", tmp_path)
    torques = [lw.forces(arg, steps=72).driving_torque for arg in forms.values()]
    for t in torques[1:]:
        np.testing.assert_array_equal(t, torques[0])
    loads = [lw.reduced(arg, steps=72).load for arg in (forms["name"], forms["Spec"])]
    np.testing.assert_array_equal(loads[0], loads[1])
    assert lw.dynamics(forms["Spec"], steps=360).delta == pytest.approx(lw.dynamics(forms["name"], steps=360).delta)
    shears = _forms("shears-slider-crank", tmp_path)
    speeds = {lw.bolt_speed(arg, pull=0.0, steps=72) for arg in (shears["Spec"], shears["str path"])}
    assert len(speeds) == 1
    weights = [lw.balance(arg, ["crank"], harmonic=1).counterweights[0].mass for arg in shears.values()]
    assert len(set(weights)) == 1


def test_parameters_and_sweep_take_every_form(tmp_path):
    forms = _forms("four-bar", tmp_path)
    listed = [lw.parameters(arg) for arg in forms.values()]
    assert all(p == listed[0] for p in listed)
    t = [lw.sweep(arg, {"links.crank.length": ("90", "110", 2)}, ["swing"], steps=72) for arg in forms.values()]
    for other in t[1:]:
        np.testing.assert_array_equal(other["swing"], t[0]["swing"])


@pytest.mark.parametrize("bad", [42, None, {"links": {}}, ["four-bar"], b"four-bar"])
def test_anything_else_is_a_type_error_that_says_what_is_expected(bad):
    for call in (
        lw.compile,
        lambda m: lw.kinematics(m, steps=8),
        lambda m: lw.forces(m, steps=8),
        lw.dynamics,
        lw.reduced,
        lw.impact,
        lw.parameters,
    ):
        with pytest.raises(TypeError, match="a mechanism file path, the name of a bundled example, a Spec"):
            call(bad)


def test_forces_of_a_kinematics_result_are_those_of_the_mechanism():
    kin = lw.kinematics("double-cut-shears", steps=90, variants={"links.crank.length": [0.09, 0.11]})
    f = lw.forces(kin)
    g = lw.forces("double-cut-shears", steps=90, variants={"links.crank.length": [0.09, 0.11]})
    np.testing.assert_array_equal(f.driving_torque, g.driving_torque)
    assert lw.forces_of(kin).driving_torque.shape == (2, 90)
    with pytest.raises(TypeError, match="the kinematics result's"):
        lw.forces(kin, steps=10)


def test_impact_reads_the_files_blow():
    """lw.impact(mech) with nothing else is the blow of the file's impact: section (read here as plain YAML)."""
    blow = YAML(typ="safe").load(text("percussion-rocker"))["impact"]

    def number(v):
        return float(str(v).split()[0])

    normal = math.radians(number(blow["normal"]))
    explicit = lw.impact(
        "percussion-rocker",
        at=blow["at"],
        normal=(math.cos(normal), math.sin(normal)),
        omega_before=number(blow["omega"]),
        restitution=float(blow["restitution"]),
        friction=float(blow.get("friction", 0.0)),
        link=blow.get("link"),
    )
    from_file = lw.impact("percussion-rocker")
    np.testing.assert_allclose(from_file.impulse, explicit.impulse, rtol=1e-14)
    assert from_file.energy_loss == pytest.approx(explicit.energy_loss, rel=1e-14)
    # and one argument given overrides only itself
    plastic = lw.impact("percussion-rocker", restitution=0.0)
    assert plastic.energy_loss > from_file.energy_loss
    with pytest.raises(lw.errors.LinkworkError, match="the blow needs at, normal, restitution, omega_before"):
        lw.impact("four-bar")
