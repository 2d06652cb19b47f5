"""``to_xarray()`` and ``to_pandas()`` of the results: the numbers of the result's own arrays under named
dimensions, the units in the attributes, the crank angle φ from position 0, and the same table as the file
``linkwork kinematics --out F.nc`` writes."""

from __future__ import annotations

import sys

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork as lw
import linkwork.cli.motion  # noqa: F401 - registers the commands
from linkwork.cli.main import app
from linkwork.errors import LinkworkError, MissingDependencyError

xr = pytest.importorskip("xarray")
pd = pytest.importorskip("pandas")


@pytest.fixture(scope="module")
def kin():
    return lw.kinematics("four-bar", steps=36, variants={"links.crank.length": [0.1, 0.11]})


def test_kinematics_dataset_holds_the_positions_under_named_dimensions(kin):
    ds = kin.to_xarray()
    assert ds["x"].dims == ("variant", "angle", "point") and ds["omega"].dims == ("variant", "angle", "link")
    assert ds.sizes["variant"] == 2 and ds.sizes["angle"] == 36
    assert (ds["x"].attrs["units"], ds["vy"].attrs["units"], ds["epsilon"].attrs["units"]) == ("m", "m/s", "rad/s^2")
    for v, i in [(0, 0), (1, 7), (1, 35)]:
        here = ds.isel(variant=v, angle=i)
        assert here["x"].sel(point="B") == pytest.approx(kin.position("B")[v, i, 0], rel=1e-12)
        assert here["ay"].sel(point="M") == pytest.approx(kin.acceleration("coupler.M")[v, i, 1], rel=1e-12)
        assert here["omega"].sel(link="rocker") == pytest.approx(kin.omega("rocker")[v, i], rel=1e-12)


def test_the_angle_is_phi_from_the_rocker_s_high_end(kin):
    """The four-bar's position 0 is its rocker at the high end of its swing: found here on a grid of 0.1 deg,
    φ of each sample is the crank's turn from there (counter-clockwise), within that grid."""
    ds = kin.to_xarray()
    fine = lw.kinematics("four-bar", steps=3600)
    rocker = np.unwrap(fine.angle("rocker"))
    high = np.degrees(fine.angles[np.argmax(rocker)])
    to_x = np.degrees(kin.angles)
    np.testing.assert_allclose(ds["crank_angle_to_x"], np.round(np.mod(to_x, 360.0), 6) % 360.0, atol=1e-9)
    turned = np.mod(to_x - high, 360.0)
    gap = np.abs((ds["angle"].values - turned + 180.0) % 360.0 - 180.0)
    assert gap.max() < 0.1
    assert ds["angle"].attrs["units"] == "deg" and "position 0" in ds["angle"].attrs["long_name"]


def test_kinematics_frame_is_indexed_by_variant_angle_and_point(kin):
    df = kin.to_pandas()
    assert list(df.index.names) == ["variant", "angle", "point"]
    assert df.attrs["units"]["vx"] == "m/s" and df.attrs["angle_units"] == "deg"
    phi = kin.to_xarray()["angle"].values
    assert df.loc[(1, phi[5], "B"), "vx"] == pytest.approx(kin.velocity("B")[1, 5, 0], rel=1e-12)
    links = kin.to_pandas(by="link")
    assert list(links.index.names) == ["variant", "angle", "link"] and links.attrs["units"]["theta"] == "rad"
    assert links.loc[(0, phi[9], "coupler"), "theta"] == pytest.approx(kin.angle("coupler")[0, 9], rel=1e-12)


def test_the_netcdf_file_of_the_command_is_the_dataset_of_the_run(tmp_path):
    out = tmp_path / "x.nc"
    result = CliRunner().invoke(app, ["kinematics", "four-bar", "--steps", "36", "--out", str(out)])
    assert result.exit_code == 0, result.output
    with xr.open_dataset(out) as written:
        xr.testing.assert_identical(written.load(), lw.kinematics("four-bar", steps=36).to_xarray())


def test_forces_dataset_holds_the_reactions_as_the_result_gives_them():
    """Each joint's force is the first-named link's on the second (``reaction``); the frame's joints carry the
    foundation force: minus the sum of the frame's forces on the moving links, plus the frame's weight (none)."""
    f = lw.forces("double-cut-shears", steps=24)
    ds = f.to_xarray()
    assert ds["force"].dims == ("variant", "angle", "joint", "component")
    assert ds["force"].attrs["units"] == "N" and ds["moment"].attrs["units"] == "N m"
    assert ds["driving_torque"].attrs["units"] == "N m"
    for i in (0, 5, 17):
        for joint in ("A", "O1", "guide_E"):
            np.testing.assert_array_equal(ds["force"].isel(variant=0, angle=i).sel(joint=joint), f.reaction(joint)[i])
    np.testing.assert_allclose(ds["moment"].sel(joint="guide_E")[0], f.pair_moment("guide_E"), atol=1e-6)
    assert np.isnan(ds["moment"].sel(joint="A")).all()
    on_frame = ds["force"].where(ds["first"] == "frame", 0.0).sum("joint") - ds["force"].where(
        ds["second"] == "frame", 0.0
    ).sum("joint")
    scale = float(np.abs(ds["force"]).max())
    np.testing.assert_allclose(-on_frame[0], ds["foundation_force"][0], atol=1e-9 * scale)


def test_forces_frame_by_joint_and_by_angle():
    f = lw.forces("double-cut-shears", steps=24)
    phi = f.to_xarray()["angle"].values
    df = f.to_pandas()
    assert list(df.index.names) == ["variant", "angle", "joint"] and df.attrs["units"]["x"] == "N"
    assert df.loc[(0, phi[3], "B"), "y"] == f.reaction("B")[3, 1]
    per_angle = f.to_pandas(by="angle")
    assert list(per_angle.index.names) == ["variant", "angle"]
    assert per_angle.attrs["units"]["driving_torque"] == "N m"
    assert per_angle.loc[(0, phi[11]), "driving_torque"] == f.driving_torque[11]
    assert per_angle.loc[(0, phi[11]), "foundation_y"] == f.foundation[11, 1]


def test_without_xarray_or_pandas_the_message_names_the_extra(kin, monkeypatch):
    monkeypatch.setitem(sys.modules, "xarray", None)
    monkeypatch.setitem(sys.modules, "pandas", None)
    with pytest.raises(MissingDependencyError, match=r'needs xarray: pip install "linkwork\[data\]"$'):
        kin.to_xarray()
    with pytest.raises(MissingDependencyError, match=r'needs pandas: pip install "linkwork\[design\]"$'):
        lw.forces("four-bar", steps=12).to_pandas()


def test_each_drive_has_its_own_torque():
    """Two drives: the driving torque over a dimension ``drive`` named by the drives' joints, each the
    result's own column (not the first drive's alone)."""
    from mechanisms import five_bar

    mech = lw.compile(five_bar().build())
    angles = np.radians(np.stack([np.linspace(80, 100, 5), np.linspace(90, 70, 5)], axis=1))
    f = lw.forces(mech, angles)
    torque = f.to_xarray()["driving_torque"]
    assert torque.dims == ("variant", "angle", "drive") and list(torque["drive"].values) == ["O1", "O5"]
    np.testing.assert_array_equal(torque[0], f.driving_torque)


@pytest.fixture(scope="module")
def run():
    return lw.dynamics("double-cut-shears")


def test_dynamics_dataset_holds_the_result_s_arrays(run):
    ds = run.to_xarray()
    assert ds["inertia"].dims == ("angle",) and ds["omega"].dims == ("time",)
    np.testing.assert_array_equal(ds["inertia"], run.reduced.inertia)
    np.testing.assert_array_equal(ds["load"], run.reduced.load)
    t, psi, omega = run.motion.cycle()
    np.testing.assert_array_equal(ds["omega"], omega)
    np.testing.assert_array_equal(ds["time"], t)
    # the work of the loads up to each sample: the reduced result's own (integrated between the samples), and
    # within the trapezoid sum's error on this grid (the cut's load has kinks: 1e-5 of the turn's work) of it
    np.testing.assert_array_equal(ds["work"], run.reduced.work()[:-1])
    step = 2 * np.pi / len(run.reduced.load)
    work = np.concatenate([[0.0], np.cumsum((run.reduced.load[1:] + run.reduced.load[:-1]) * step / 2)])
    np.testing.assert_allclose(ds["work"], work, rtol=0, atol=2e-5 * np.max(np.abs(work)))
    assert (ds["load"].attrs["units"], ds["omega"].attrs["units"], ds["time"].attrs["units"]) == ("N m", "rad/s", "s")
    assert ds.attrs["delta"] == run.delta and ds.attrs["mechanism"] == "double-cut-shears"
    frame = run.to_pandas("time")
    assert list(frame.index.names) == ["time"] and frame.attrs["units"]["motor_torque"] == "N m"
    np.testing.assert_array_equal(frame["omega"], omega)
    with pytest.raises(LinkworkError, match='by="angle" or by="time"'):
        run.to_pandas("joint")


def test_dynamics_phi_counts_from_the_knives_open_as_the_command_prints_it(run):
    """Position 0 of the double-cut shears is the upper knife at the top of its stroke (found here on a grid
    of 0.1 deg of the crank); φ of the reduced grid and of the steady cycle is the crank's turn from there
    (counter-clockwise), and φ at the cycle's lowest speed is the one ``linkwork dynamics`` prints."""
    import re

    ds = run.to_xarray()
    fine = lw.kinematics("double-cut-shears", steps=3600)
    top = np.degrees(fine.angles[np.argmax(fine.position("knife_upper.E")[..., 1])])
    turned = np.mod(ds["crank_angle_to_x"].values - top, 360.0)
    assert np.abs((ds["angle"].values - turned + 180.0) % 360.0 - 180.0).max() < 0.1
    assert ds.attrs["position_0_deg"] == pytest.approx(top, abs=0.1)
    out = CliRunner().invoke(app, ["dynamics", "double-cut-shears"]).output
    printed = float(re.search(r"lowest speed at ([\d.]+) deg from position 0", out).group(1))
    assert float(ds["phi"][int(np.argmin(ds["omega"].values))]) == pytest.approx(printed, abs=0.05)
