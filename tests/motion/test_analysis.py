"""Strokes, time ratio, transmission angles, instantaneous centres, plans, and the CLI commands."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork as lw
import linkwork.cli.motion  # noqa: F401,E402 - registers the commands
from linkwork.cli.main import app
from linkwork.motion.analysis import extremes, instant_centre, transmission_angles
from linkwork.motion.plans import plans
from mechanisms import TEXTBOOK

runner = CliRunner()


def cross2(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def test_offset_slider_crank_stroke_and_time_ratio_closed_form():
    r, rod, e = 0.1, 0.4, 0.05
    mech = lw.compile(TEXTBOOK["offset slider-crank"][0]().build())
    kin = lw.kinematics(mech, steps=3600)
    (ext,) = [x for x in extremes(kin) if x.kind == "slider"]
    stroke = math.sqrt((rod + r) ** 2 - e**2) - math.sqrt((rod - r) ** 2 - e**2)
    assert ext.stroke == pytest.approx(stroke, abs=1e-9)
    theta = math.asin(e / (rod - r)) - math.asin(e / (rod + r))
    assert ext.time_ratio == pytest.approx((math.pi + theta) / (math.pi - theta), rel=1e-6)
    # the outer dead point: crank and rod in line, phi = asin(e / (l + r))
    assert math.degrees(ext.at_high) % 360 == pytest.approx(math.degrees(math.asin(e / (rod + r))), abs=1e-3)


def test_four_bar_rocker_swing_and_transmission_angle_closed_form():
    a, b, c, d = 0.1, 0.35, 0.25, 0.3
    mech = lw.compile(lw.example("four-bar"))
    kin = lw.kinematics(mech, steps=7200)
    (rocker,) = [x for x in extremes(kin) if x.kind == "rocker"]

    def rocker_angle(o2b):  # angle of O4B from +x, B above the frame line
        return math.pi - math.acos((d * d + c * c - o2b * o2b) / (2 * d * c))

    swing = rocker_angle(a + b) - rocker_angle(b - a)
    assert rocker.stroke == pytest.approx(abs(swing), abs=1e-7)
    # time ratio from the crank angles of the two dead points: crank and coupler stretched, then folded
    b_ext = (d + c * math.cos(rocker_angle(a + b)), c * math.sin(rocker_angle(a + b)))
    b_fold = (d + c * math.cos(rocker_angle(b - a)), c * math.sin(rocker_angle(b - a)))
    forward = (math.atan2(b_fold[1], b_fold[0]) + math.pi - math.atan2(b_ext[1], b_ext[0])) % (2 * math.pi)
    ratio = max(forward, 2 * math.pi - forward) / min(forward, 2 * math.pi - forward)
    assert rocker.time_ratio == pytest.approx(ratio, rel=1e-6)
    mu = transmission_angles(kin)["II(2,3) RRR"]
    o4a = np.hypot(*(kin.position("A") - (d, 0)).T)
    cos_mu = (b * b + c * c - o4a**2) / (2 * b * c)
    expect = np.arcsin(np.sqrt(1 - cos_mu**2))  # folded into [0, 90] deg
    np.testing.assert_allclose(mu, expect, atol=1e-9)
    # extreme transmission angles at crank angles 0 and 180 deg (Freudenstein)
    mu_min = math.acos((b * b + c * c - (d - a) ** 2) / (2 * b * c))
    mu_max = math.acos((b * b + c * c - (d + a) ** 2) / (2 * b * c))
    assert mu.min() == pytest.approx(min(mu_min, math.pi - mu_max, math.pi / 2), abs=1e-5)


def test_instant_centres_by_kennedy():
    mech = lw.compile(lw.example("four-bar"))
    kin = lw.kinematics(mech, steps=36)
    a, b = kin.position("A"), kin.position("B")
    ic = instant_centre(kin, "coupler")
    # on O2A and on O4B
    np.testing.assert_allclose(cross2(a, ic), 0, atol=1e-12)
    np.testing.assert_allclose(cross2(b - (0.3, 0), ic - (0.3, 0)), 0, atol=1e-12)
    # relative centres of links joined by a pin are the pin
    rel = instant_centre(kin, "coupler", "rocker")
    finite = np.isfinite(rel[:, 0])
    assert finite.sum() >= 34
    np.testing.assert_allclose(rel[finite], b[finite], atol=1e-9)
    np.testing.assert_allclose(instant_centre(kin, "crank"), 0, atol=1e-12)
    # three-centre theorem: the centre of crank relative to rocker lies on the frame line O2 O4
    # and on the coupler line A B
    p24 = instant_centre(kin, "crank", "rocker")
    np.testing.assert_allclose(p24[:, 1], 0, atol=1e-9)
    np.testing.assert_allclose(cross2(b - a, p24 - a), 0, atol=1e-9)


def test_velocity_plan_of_the_double_cut_shears_follows_the_paper():
    mech = lw.compile(lw.example("double-cut-shears"))
    kin = lw.kinematics(mech, steps=12)
    vp, ap = plans(kin, 9)
    pts = {k: np.array(v) for k, v in vp.points.items()}
    vec = {(v.start, v.end): np.array(v.vector) for v in vp.vectors}
    pos = {n: kin.position(n)[9] for n in ("A", "B", "C", "D", "E", "F")}
    # (2): pa = omega l, normal to O1A
    assert np.hypot(*pts["a"]) == pytest.approx(math.pi * 0.1)
    # (3): b from a along the normal to AB, and from p along the normal to O3B
    assert vec[("a", "b")] @ (pos["B"] - pos["A"]) == pytest.approx(0, abs=1e-12)
    np.testing.assert_allclose(pts["a"] + vec[("a", "b")], pts["b"], atol=1e-12)
    np.testing.assert_allclose(vec[("p", "b")], pts["b"], atol=1e-12)
    assert pts["b"] @ pos["B"] == pytest.approx(0, abs=1e-12)
    # c and d by similarity: on the line p b, |pc| / |pb| = 0.3 / 0.5
    for name in ("c", "d"):
        assert cross2(pts[name], pts["b"]) == pytest.approx(0, abs=1e-12)
        assert np.hypot(*pts[name]) / np.hypot(*pts["b"]) == pytest.approx(0.6)
    # (4): e from d along the normal to DE, and from p vertically (the fixed guide)
    assert vec[("d", "e")] @ (pos["E"] - pos["D"]) == pytest.approx(0, abs=1e-12)
    np.testing.assert_allclose(pts["d"] + vec[("d", "e")], pts["e"], atol=1e-12)
    assert vec[("p", "e")][0] == pytest.approx(0, abs=1e-12)
    # (5): the same for f from c
    np.testing.assert_allclose(pts["c"] + vec[("c", "f")], pts["f"], atol=1e-12)
    assert vp.scale in (0.001, 0.002, 0.0025, 0.005) and max(np.hypot(*p) for p in pts.values()) / vp.scale <= 100


def test_acceleration_plan_components():
    mech = lw.compile(lw.example("double-cut-shears"))
    kin = lw.kinematics(mech, steps=12)
    _, ap = plans(kin, 9)
    pts = {k: np.array(v) for k, v in ap.points.items()}
    by = {(v.start, v.end, v.kind): np.array(v.vector) for v in ap.vectors}
    a, b = kin.position("A")[9], kin.position("B")[9]
    w2 = kin.omega("rod")[9]
    n = by[("a", "n_ba", "normal")]
    np.testing.assert_allclose(n, -(w2**2) * (b - a), atol=1e-12)  # towards A, omega^2 |AB|
    t = by[("n_ba", "b", "tangential")]
    assert t @ (b - a) == pytest.approx(0, abs=1e-12)
    np.testing.assert_allclose(pts["a"] + n + t, pts["b"], atol=1e-10)
    # the fixed guides: no Coriolis component
    np.testing.assert_allclose(by[("p", "k'_e", "coriolis")], 0, atol=1e-15)


def test_kinematics_command_json_and_files(tmp_path):
    result = runner.invoke(app, ["kinematics", "double-cut-shears", "--steps", "36", "--json", "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    out = json.loads(result.stdout)
    assert set(out) >= {"phi_deg", "crank_angle_to_x_deg", "points", "links", "valid", "events"}
    assert set(out["points"]["E"]) == {"x", "y", "vx", "vy", "ax", "ay"}
    assert set(out["links"]["rocker"]) == {"angle", "omega", "epsilon"}
    kin = lw.kinematics(lw.compile(lw.example("double-cut-shears")), steps=36)
    np.testing.assert_allclose(out["points"]["E"]["vy"], kin.velocity("E")[:, 1])
    strokes = [e for e in out["events"] if e["kind"] == "stroke"]
    assert {s["name"] for s in strokes} >= {"guide_E", "guide_F"}
    header = (tmp_path / "kinematics.csv").read_text().splitlines()[0].split(",")
    assert "E.vy [m/s]" in header and "rocker.omega [rad/s]" in header
    xr = pytest.importorskip("xarray")
    ds = xr.open_dataset(tmp_path / "kinematics.nc", engine="scipy")
    assert dict(ds.sizes) == {"variant": 1, "angle": 36, "point": len(ds.point), "link": 7}
    np.testing.assert_allclose(ds["ay"].sel(point="F").values[0], kin.acceleration("F")[:, 1])
    assert ds["vx"].attrs["units"] == "m/s"


@pytest.mark.parametrize("variants", [None, {"links.crank.length": [0.2, 0.22]}])
def test_netcdf_is_written_as_xarray_writes_it_without_importing_xarray(tmp_path, variants):
    """kinematics.nc is written by SciPy's NetCDF 3 writer: byte for byte the file xarray writes of
    to_dataset (with or without variants, a string coordinate, NaN fill values), and neither xarray, pandas
    nor Dask is imported to write it (checked in a fresh interpreter)."""
    import subprocess
    import sys

    xr = pytest.importorskip("xarray")
    from linkwork.io.motion_tables import write_netcdf
    from linkwork.motion.tables import to_dataset

    kin = lw.kinematics(lw.compile(lw.example("four-bar")), steps=36, variants=variants)
    write_netcdf(kin, tmp_path / "ours.nc")
    to_dataset(kin).to_netcdf(tmp_path / "xarray.nc", engine="scipy")
    assert (tmp_path / "ours.nc").read_bytes() == (tmp_path / "xarray.nc").read_bytes()
    with xr.open_dataset(tmp_path / "ours.nc") as ds:
        vy = kin.velocity("B")[..., 1].reshape(-1, 36)
        np.testing.assert_allclose(ds["vy"].sel(point="B").values, vy, rtol=1e-12)
    fresh = str(tmp_path / "fresh.nc")
    code = (
        "import sys, linkwork as lw; from linkwork.io.motion_tables import write_netcdf; "
        f"write_netcdf(lw.kinematics(lw.compile(lw.example('four-bar')), steps=36), {fresh!r}); "
        "print(sorted(m for m in ('xarray', 'pandas', 'dask') if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_positions_start_with_the_knives_open():
    result = runner.invoke(app, ["positions", "double-cut-shears", "--json"])
    assert result.exit_code == 0, result.output
    rows = json.loads(result.stdout)["positions"]
    assert len(rows) == 12
    e = [r["E"][1] for r in rows]
    assert e[0] == max(e) and rows[0]["F"][1] == min(r["F"][1] for r in rows)
    kin = lw.kinematics(lw.compile(lw.example("double-cut-shears")), steps=36000)
    assert e[0] == pytest.approx(kin.position("E")[:, 1].max() * 1000, abs=1e-3)
    step = (rows[1]["crank_angle_to_x_deg"] - rows[0]["crank_angle_to_x_deg"]) % 360
    assert step == pytest.approx(30)
    assert [r["phi_deg"] for r in rows] == [30.0 * k for k in range(12)]  # exact: 1e-9 deg rounding


@pytest.mark.parametrize(
    "args, message",
    [
        (["kinematics", "four-bar", "--angles", "ten"], "--angles: expected numbers in degrees"),
        (["kinematics", "four-bar", "--angles", "10", "--steps", "5"], "give either --steps or --angles"),
        (["kinematics", "four-bar", "--steps", "0"], "--steps: expected a positive number"),
        (["positions", "four-bar", "--count", "0"], "--count: expected a positive number"),
    ],
)
def test_bad_options_exit_2_with_a_message(args, message):
    result = runner.invoke(app, args)
    assert result.exit_code == 2
    assert message in result.stderr
    assert "Traceback" not in result.output


def test_the_scales_percentile_is_numpys_linear_percentile_exactly():
    """The percentile the plans' and the force arrows' scales are set by (a partition, no sort): the value of
    :func:`numpy.percentile` bit for bit, over random arrays of 1 to 400 values with ties, at the quantiles used
    and at random ones."""
    from linkwork.motion.plans import percentile

    rng = np.random.default_rng(7)
    for _ in range(3000):
        x = rng.normal(size=int(rng.integers(1, 400))) * 10 ** rng.uniform(-5, 5)
        if rng.random() < 0.3:
            x = np.round(x, 1)  # ties
        for q in (95.0, 2.5, 50.0, 100.0, 0.0, float(rng.uniform(0, 100))):
            assert percentile(x, q) == float(np.percentile(x, q)), (x, q)


def test_plans_follow_the_variants_guides_and_keep_names_apart(tmp_path):
    kin = lw.kinematics(lw.compile(lw.example("double-cut-shears")), [0.3], variants={"joints.guide_E.axis": [1.4]})
    vp, _ = plans(kin, 0)
    vec = {(v.start, v.end): np.array(v.vector) for v in vp.vectors}
    np.testing.assert_allclose(vec[("p", "e")], vp.points["e"], atol=1e-12)  # transport 0 + sliding = v_E
    from linkwork.examples import text

    path = tmp_path / "marker.yaml"
    path.write_text(
        text("four-bar").replace(
            "    ends: [O2, A]\n    length: 100\n", "    ends: [O2, A]\n    length: 100\n    points: {B: [50, 10]}\n"
        ),
        encoding="utf-8",
    )
    mech = lw.compile(lw.load(path))
    kin = lw.kinematics(mech, [math.radians(60)])
    vp, _ = plans(kin, 0)
    np.testing.assert_allclose(vp.points["b"], kin.velocity("rocker.B")[0], atol=1e-12)
    np.testing.assert_allclose(vp.points["crank.b"], kin.velocity("crank.B")[0], atol=1e-12)
    out = json.loads(runner.invoke(app, ["kinematics", str(path), "--angles", "60", "--json"]).stdout)
    np.testing.assert_allclose(out["points"]["B"]["x"], kin.position("rocker.B")[:, 0])


def test_extremes_over_a_turn_that_does_not_all_assemble():
    kin = lw.kinematics(lw.compile(lw.example("four-bar")), steps=360, variants={"links.crank.length": [0.22]})
    (rocker,) = [e for e in extremes(kin, 0) if e.kind == "rocker"]
    assert np.isfinite(rocker.stroke) and math.isnan(rocker.time_ratio)


def test_linear_drive_and_two_drives_on_the_command_line(tmp_path):
    from ruamel.yaml import YAML

    from mechanisms import five_bar, hydraulic_boom

    boom = tmp_path / "boom.yaml"
    with open(boom, "w") as fh:
        YAML().dump(hydraulic_boom().to_dict(), fh)
    result = runner.invoke(app, ["kinematics", str(boom), "--angles", "500,520", "--json"])
    assert result.exit_code == 0, result.output
    kin = lw.kinematics(lw.compile(lw.load(boom)), [0.5, 0.52])
    np.testing.assert_allclose(json.loads(result.stdout)["points"]["B"]["x"], kin.position("B")[:, 0])
    assert runner.invoke(app, ["kinematics", str(boom)]).exit_code == 2
    five = tmp_path / "five.yaml"
    with open(five, "w") as fh:
        YAML().dump(five_bar().to_dict(), fh)
    result = runner.invoke(app, ["kinematics", str(five), "--angles", "90"])
    assert result.exit_code == 2 and "this mechanism has 2 drives" in result.stderr
    result = runner.invoke(app, ["kinematics", "four-bar", "--angles", "nan"])
    assert result.exit_code == 2 and "finite" in result.stderr


def test_coriolis_in_the_acceleration_plan_of_a_slotted_rocker():
    """Crank-shaper (RPR): the block at the crank pin A slides in the rocker's slot.  The rocker's
    point A' under A has a_A' = a^n + a^t about O2; a_A = a_A' + 2 omega_3 x v_rel + a_rel."""
    mech = lw.compile(TEXTBOOK["crank-shaper"][0]().build())
    kin = lw.kinematics(mech, np.radians([30.0]), speed=10.0)
    vp, ap = plans(kin, 0)
    vec = {(v.start, v.end, v.kind): np.array(v.vector) for v in ap.vectors}
    vvec = {(v.start, v.end, v.kind): np.array(v.vector) for v in vp.vectors}
    w3 = kin.omega("rocker")[0]
    a_pos = kin.position("A")[0]
    u = a_pos / np.hypot(*a_pos)  # the slot runs through O2 = (0, 0)
    v_rel = vvec[("a'", "a", "sliding")]
    np.testing.assert_allclose(v_rel, (kin.velocity("A")[0] - w3 * np.array([-a_pos[1], a_pos[0]])), atol=1e-12)
    cor = vec[("a'", "k'_a", "coriolis")]
    np.testing.assert_allclose(cor, 2 * w3 * np.array([-v_rel[1], v_rel[0]]), atol=1e-12)
    assert abs(cor @ u) < 1e-12 and np.hypot(*cor) > 0
    # the rocker's point A' as the construction draws it: normal (towards O2, w3^2 |O2A|) and tangential
    # (normal to O2A, e3 |O2A|) components about O2 (at the pole)
    normal, tangential = vec[("p", "n_a'o2", "normal")], vec[("n_a'o2", "a'", "tangential")]
    e3 = kin.epsilon("rocker")[0]
    np.testing.assert_allclose(normal, -(w3**2) * a_pos, atol=1e-10)
    np.testing.assert_allclose(tangential, e3 * np.array([-a_pos[1], a_pos[0]]), atol=1e-10)
    assert not [v for v in ap.vectors if v.kind == "transport"]
    np.testing.assert_allclose(vvec[("p", "a'", "rotation")], w3 * np.array([-a_pos[1], a_pos[0]]), atol=1e-12)
    # closure: a_A' (normal + tangential) + Coriolis + relative = a_A
    chain = normal + tangential + cor + vec[("k'_a", "a", "sliding")]
    np.testing.assert_allclose(chain, kin.acceleration("A")[0], atol=1e-10)


def test_the_stroke_of_the_seed_000_shears_is_measured_along_the_variants_guide():
    """Seed 000: OA = AB = l and the knife's guide through O.  With the guide at psi, B lies on it at
    s = 2 l cos(phi - psi) (the isosceles triangle OAB), so the stroke is 4 l = 0.6 m whatever psi, with the
    knife at the top of it when the crank points along the guide (phi = psi) and at the bottom at psi + 180."""
    rod = 0.15
    psi = np.radians([90.0, 100.0])
    mech = lw.compile(lw.example("shears-slider-crank"))
    kin = lw.kinematics(mech, steps=360, variants={"joints.guide.axis": psi})
    for v, angle in enumerate(psi):
        (knife,) = extremes(kin, v)
        assert knife.name == "guide" and knife.stroke == pytest.approx(4 * rod, abs=1e-12)
        assert knife.high == pytest.approx(2 * rod, abs=1e-12) and knife.low == pytest.approx(-2 * rod, abs=1e-12)
        assert knife.at_high % (2 * np.pi) == pytest.approx(angle, abs=1e-9)
        assert knife.at_low % (2 * np.pi) == pytest.approx(angle + np.pi, abs=1e-9)
        # the knife's strokes each take half a turn
        assert knife.time_ratio == pytest.approx(1.0, abs=1e-9)


def test_a_link_pivoted_on_the_frame_that_turns_fully_is_no_rocker():
    """A drag link (O2O4 = 50 mm the shortest, 0.05 + 0.28 <= 0.10 + 0.25): its 'rocker' turns fully with the
    crank, so it has no swing to list; the crank-rocker beside it (O2O4 = 300 mm) has."""
    kin = lw.kinematics(
        lw.compile(lw.example("four-bar")),
        steps=360,
        variants={"frame.points.O4.x": [0.05, 0.3], "links.coupler.length": [0.28, 0.28]},
    )
    assert kin.valid_all.all()
    closed = np.unwrap(np.append(kin.angle("rocker")[0], kin.angle("rocker")[0, 0]))
    assert abs(closed[-1] - closed[0]) == pytest.approx(2 * np.pi)  # it does turn fully
    assert extremes(kin, 0) == []
    (rocker,) = extremes(kin, 1)
    a, b, c, d = 0.1, 0.28, 0.25, 0.3
    psi = [math.acos((d * d + c * c - s**2) / (2 * d * c)) for s in (b + a, b - a)]
    assert rocker.stroke == pytest.approx(abs(psi[0] - psi[1]), rel=1e-6)


def test_transmission_angles_of_four_bars_follow_the_law_of_cosines_at_every_angle_and_variant():
    """The coupler-rocker angle mu from the triangle A B O4: cos mu = (b^2 + c^2 - |O4A|^2) / (2 b c), folded
    into [0, 90] deg, for every sample of every variant; the sweep metric is the least of them."""
    from linkwork.motion.analysis import transmission

    b = np.array([0.33, 0.35, 0.37, 0.36])
    c = np.array([0.25, 0.24, 0.27, 0.23])
    d = np.array([0.30, 0.31, 0.29, 0.30])
    variants = {"links.coupler.length": b, "links.rocker.length": c, "frame.points.O4.x": d}
    kin = lw.kinematics(lw.compile(lw.example("four-bar")), steps=360, variants=variants)
    assert kin.valid_all.all()
    (mu,) = transmission(kin).values()
    assert mu.shape == (4, 360)
    o4a = np.hypot(kin.position("A")[..., 0] - d[:, None], kin.position("A")[..., 1])
    cos_mu = (b[:, None] ** 2 + c[:, None] ** 2 - o4a**2) / (2 * b[:, None] * c[:, None])
    np.testing.assert_allclose(mu, np.arcsin(np.sqrt(1 - cos_mu**2)), atol=1e-9)
    from linkwork.design.evaluate import Evaluation
    from linkwork.design.metrics import METRICS

    least = METRICS["min_transmission_angle"].compute(Evaluation(kin), None)
    np.testing.assert_allclose(least, np.arcsin(np.sqrt(1 - cos_mu**2)).min(axis=1), atol=1e-9)


def _d1(f, h):
    """First derivative along axis 1 of periodic samples, fourth-order central differences."""
    return (-np.roll(f, -2, 1) + 8 * np.roll(f, -1, 1) - 8 * np.roll(f, 1, 1) + np.roll(f, 2, 1)) / (12 * h)


def test_the_plans_of_every_position_are_the_derivatives_of_the_motion():
    """One construction for every position of two variants of the double-cut shears (one with its knives'
    guides turned): each point's plan vector is its velocity (acceleration), and also the fourth-order
    central difference of the positions (velocities) over the turn; the relative vectors of the construction
    close on the absolute ones (v_B = v_A + v_BA; a_E = a_E' + a_cor + a_rel)."""
    from linkwork.motion.plans import plan_series

    mech = lw.compile(lw.example("double-cut-shears"))
    variants = {"links.crank.length": [0.10, 0.11], "joints.guide_E.axis": [math.pi / 2, math.radians(95)]}
    kin = lw.kinematics(mech, steps=720, variants=variants)
    assert kin.valid_all.all()
    vel, acc = plan_series(kin)
    assert vel.values.shape[:2] == acc.values.shape[:2] == (2, 720)
    h = math.radians(0.5) / abs(kin.rates[0, 0])
    for name in ("A", "B", "C", "D", "E", "F"):
        x, v, a = kin.position(name), kin.velocity(name), kin.acceleration(name)
        pv, pa = vel.values[:, :, vel.labels.index(name.lower())], acc.values[:, :, acc.labels.index(name.lower())]
        np.testing.assert_allclose(pv, v, rtol=0, atol=1e-12 * np.abs(v).max())
        np.testing.assert_allclose(pa, a, rtol=0, atol=1e-12 * np.abs(a).max())
        assert np.abs(pv - _d1(x, h)).max() < 1e-6 * np.abs(v).max()
        assert np.abs(pa - _d1(v, h)).max() < 1e-5 * np.abs(a).max()
    for series in (vel, acc):
        at = {lab: series.values[:, :, j] for j, lab in enumerate(series.labels)}
        for j, edge in enumerate(series.edges):
            gap = at[edge.end] - at[edge.start] - series.vectors[:, :, j]
            assert np.abs(gap).max() < 1e-9 * np.abs(series.values).max(), (series.kind, edge)
    # the sliding of E is along the variant's guide: 95 deg from +x in variant 1
    j = next(j for j, e in enumerate(vel.edges) if e.kind == "sliding" and e.end == "e")
    u = np.array([math.cos(math.radians(95)), math.sin(math.radians(95))])
    np.testing.assert_allclose(cross2(vel.vectors[1, :, j], u), 0, atol=1e-12)


def test_the_plans_of_every_position_equal_those_of_each_position_solved_alone():
    """The plans of a whole turn (one vectorised construction) against :func:`plans` of each angle solved on
    its own, for every position of the crank-shaper (RPR, with its Coriolis component) and the shears."""
    from linkwork.motion.plans import plan_series

    for mech in (lw.compile(TEXTBOOK["crank-shaper"][0]().build()), lw.compile(lw.example("double-cut-shears"))):
        kin = lw.kinematics(mech, steps=24)
        series = plan_series(kin)
        for i, angle in enumerate(kin.angles):
            alone = plans(lw.kinematics(mech, [angle]), 0)
            for s, plan in zip(series, alone, strict=True):
                assert list(plan.points) == list(s.points) and s.at(i).scale == plan.scale
                np.testing.assert_allclose(
                    [s.at(i).points[k] for k in s.points], list(plan.points.values()), rtol=1e-9, atol=1e-12
                )
                assert [(v.start, v.end, v.kind) for v in plan.vectors] == [(e.start, e.end, e.kind) for e in s.edges]
                np.testing.assert_allclose(s.vectors[0, i], [v.vector for v in plan.vectors], rtol=1e-9, atol=1e-12)
