"""Design sweeps and optimisation: the metrics against closed forms and independent solutions,
sampling plans, chunk files and resuming, errors, the optimised file."""

from __future__ import annotations

import json
import math
import shlex
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from ruamel.yaml import YAML

import linkwork as lw
from commandline import linkwork
from linkwork.design.plan import Vary, make_plan
from linkwork.errors import DesignError
from linkwork.examples import text
from linkwork.kinetostatics.peaks import foundation_peak, torque_peak
from mechanisms import offset_slider_crank

pytest.importorskip("pyarrow")


def _fold(mu):
    """Transmission angle folded into [0, 90] deg."""
    mu = np.abs(np.asarray(mu)) % np.pi
    return np.minimum(mu, np.pi - mu)


# ---------------------------------------------------------------- metrics against closed forms


def test_stroke_and_time_ratio_of_an_offset_slider_crank_match_the_closed_form():
    t = lw.sweep(
        offset_slider_crank().build(),
        {"links.crank.length": ("80", "120", 5), "links.rod.length": ("380 mm", "0.42 m", 3)},
        ["stroke", "time_ratio", "forward_time_ratio", "assembles"],
        steps=720,
    )
    r, rod, e = t["links.crank.length"], t["links.rod.length"], 0.05
    stroke = np.sqrt((rod + r) ** 2 - e**2) - np.sqrt((rod - r) ** 2 - e**2)
    alpha = np.arcsin(e / (rod - r)) - np.arcsin(e / (rod + r))
    assert len(t) == 15 and np.all(t["assembles"] == 1)
    # the extremes refined by a parabola through three samples half a degree apart
    np.testing.assert_allclose(t["stroke"], stroke, rtol=1e-7)
    # counter-clockwise, the slider moves + x (away from the crank) from the folded position
    # (crank angle pi + asin(e / (l - r))) to the extended one (asin(e / (l + r))): pi - alpha of the turn
    np.testing.assert_allclose(t["forward_time_ratio"], (np.pi - alpha) / (np.pi + alpha), rtol=1e-4)
    # the coefficient K: the slower stroke over the faster one
    np.testing.assert_allclose(t["time_ratio"], (np.pi + alpha) / (np.pi - alpha), rtol=1e-4)
    # grid order: the first dimension slowest
    np.testing.assert_allclose(t["links.crank.length"][:3], 0.08)
    np.testing.assert_allclose(t["links.rod.length"][:3], [0.38, 0.40, 0.42])


def test_four_bar_swing_and_transmission_angle_match_the_law_of_cosines():
    t = lw.sweep(
        "four-bar",
        ["links.crank.length=80:110:4", "links.rocker.length=230mm:270mm:5"],
        ["swing", "min_transmission_angle", "time_ratio", "forward_time_ratio"],
    )
    a, b, c, d = t["links.crank.length"], 0.35, t["links.rocker.length"], 0.30
    # transmission angle (coupler-rocker) is extreme with the crank along the frame line: 0 and 180 deg,
    # both among the 360 samples (the turn starts at 60 deg)
    mu = [np.arccos((b * b + c * c - (d - s * a) ** 2) / (2 * b * c)) for s in (1, -1)]
    np.testing.assert_allclose(t["min_transmission_angle"], np.minimum(*(_fold(m) for m in mu)), rtol=1e-9)
    # the rocker's extremes: crank and coupler in line, O2B = b + a and b - a
    psi = [np.arccos((d * d + c * c - s**2) / (2 * d * c)) for s in (b + a, b - a)]
    np.testing.assert_allclose(t["swing"], np.abs(psi[0] - psi[1]), rtol=1e-6)
    # time ratio from the crank angles of the extremes
    phi = [np.arccos((d * d + s * s - c * c) / (2 * d * s)) for s in (b + a, b - a)]
    # B above the frame line: O2B shortening from b + a (crank angle phi0) to b - a (crank angle pi + phi1)
    # turns the rocker counter-clockwise, over the crank angle theta
    theta = np.pi + phi[1] - phi[0]
    np.testing.assert_allclose(t["forward_time_ratio"], theta / (2 * np.pi - theta), rtol=1e-4)
    k = np.maximum(theta, 2 * np.pi - theta) / np.minimum(theta, 2 * np.pi - theta)
    np.testing.assert_allclose(t["time_ratio"], k, rtol=1e-4)


@pytest.mark.parametrize("direction", ["ccw", "cw"])
def test_time_ratios_of_an_offset_slider_crank_follow_the_direction_of_rotation(direction):
    """Extreme positions: extended at crank angle asin(e / (l + r)), folded at pi + asin(e / (l - r)).
    Turning counter-clockwise the slider goes out (+ x) over pi - alpha, clockwise over pi + alpha:
    forward_time_ratio turns into its reciprocal, time_ratio (K, the slower stroke over the faster) stays.
    A process load between the slider and the crank pivot closes as the slider comes back in."""
    mech = (
        offset_slider_crank()
        .drive("O", speed="100 rpm", direction=direction, angle=30)
        .process(
            "press",
            ["slider.B", "crank.O"],
            axis="0 deg",
            workpiece=[0.3, 0.6],
            penetration=[0, 1],
            force=["0 N", "0 N"],
        )
    )
    mech._data["drives"] = mech._data["drives"][-1:]
    t = lw.sweep(
        mech.build(),
        {"links.crank.length": ("80", "120", 3)},
        ["time_ratio", "forward_time_ratio", "working_time_ratio"],
        steps=720,
    )
    r, rod, e = t["links.crank.length"], 0.4, 0.05
    alpha = np.arcsin(e / (rod - r)) - np.arcsin(e / (rod + r))
    out = np.pi - alpha if direction == "ccw" else np.pi + alpha
    np.testing.assert_allclose(t["forward_time_ratio"], out / (2 * np.pi - out), rtol=1e-4)
    np.testing.assert_allclose(t["time_ratio"], (np.pi + alpha) / (np.pi - alpha), rtol=1e-4)
    np.testing.assert_allclose(t["working_time_ratio"], (2 * np.pi - out) / out, rtol=1e-4)


def _shears_variant(crank: float, rod_mass: float | None = None, upper_mass: float | None = None) -> str:
    """The double-cut shears file edited by hand: another crank length (its centre of mass, left to its
    default, follows to mid-length; its inertia, given, stays), optionally heavier rod and knife (their
    given inertias stay)."""
    yaml = YAML()
    data = yaml.load(text("double-cut-shears"))
    data["links"]["crank"]["length"] = crank
    if rod_mass is not None:
        data["links"]["rod"]["mass"] = rod_mass
    if upper_mass is not None:
        data["links"]["knife_upper"]["mass"] = upper_mass
    import io

    buf = io.StringIO()
    yaml.dump(data, buf)
    return buf.getvalue()


def test_forces_of_geometry_and_mass_variants_equal_those_of_the_edited_file():
    """Geometry and masses through the variant overrides, against the file edited by hand to the same
    values, compiled and solved from scratch (lw.forces on one mechanism)."""
    values = [(0.1, 60.0, 300.0), (0.105, 90.0, 300.0), (0.095, 45.0, 420.0)]
    vary = {
        "links.crank.length": ("95 mm", "105 mm", 3),
        "links.rod.mass": ("45", "90", 4),
        "links.knife_upper.mass": ("300", "420", 2),
    }
    metrics = ["peak_driving_torque", "peak_foundation_force", "knife_overlap", "knife_clearance"]
    t = lw.sweep("double-cut-shears", vary, metrics, steps=360)
    assert len(t) == 24
    for crank, rod, upper in values:
        row = int(
            np.flatnonzero(
                np.isclose(t["links.crank.length"], crank)
                & np.isclose(t["links.rod.mass"], rod)
                & np.isclose(t["links.knife_upper.mass"], upper)
            )[0]
        )
        mech = lw.compile(lw.loads(_shears_variant(crank, rod, upper)))
        f = lw.forces(mech, steps=360)
        assert t["peak_driving_torque"][row] == pytest.approx(abs(torque_peak(f).value[0]), rel=1e-9)
        assert t["peak_foundation_force"][row] == pytest.approx(foundation_peak(f).value[0], rel=1e-9)
        # the knives' gap on a fine turn (no interpolation)
        k = lw.kinematics(mech, steps=36000)
        gap = k.position("knife_upper.edge")[:, 1] - k.position("knife_lower.edge")[:, 1]
        assert t["knife_overlap"][row] == pytest.approx(-gap.min(), abs=1e-7)
        assert t["knife_clearance"][row] == pytest.approx(gap.max(), abs=1e-7)


def test_peak_forces_of_the_slider_crank_shears_are_finite_where_the_knife_passes_the_crank_pivot(tmp_path):
    """Seed 000 (OA = AB = l): the knife passes O at 90 and 270 deg, where the reactions are singular (NaN);
    the peaks are taken over the finite samples, the foundation force filled there from the momentum theorem.
    Closed form: the crank (mc, centre l/2) and the rod (mr, centre at (l cos, 3 l sin)/2) move with the knife
    (m2, y = 2 l sin); the foundation carries the weights less the rate of change of momentum:
    Fx = (mc + mr) l/2 w^2 cos(phi), Fy = -M g + (mc/2 + 3 mr/2 + 2 m2) l w^2 sin(phi)."""
    t = lw.sweep(
        "shears-slider-crank",
        ["links.crank.mass=5:20:2", "links.knife.mass=10:40:2"],
        ["peak_foundation_force", "peak_driving_torque", "assembles"],
    )
    length, w, g, mr, housing = 0.15, 10.0, 9.81, 10.0, 500.0
    phi = np.linspace(0, 2 * np.pi, 720000, endpoint=False)[:, None]  # the peaks are refined between samples
    mc, m2 = t["links.crank.mass"], t["links.knife.mass"]
    fx = (mc + mr) * length / 2 * w * w * np.cos(phi)
    fy = -(housing + mc + mr + m2) * g + (mc / 2 + 3 * mr / 2 + 2 * m2) * length * w * w * np.sin(phi)
    assert np.all(t["assembles"] == 1)
    np.testing.assert_allclose(t["peak_foundation_force"], np.hypot(fx, fy).max(axis=0), rtol=1e-9)
    assert np.all(np.isfinite(t["peak_driving_torque"]))
    out = tmp_path / "x.parquet"
    r = linkwork(
        "sweep",
        "shears-slider-crank",
        "--vary",
        "links.knife.mass=10:40:4",
        "--metric",
        "peak_foundation_force",
        "--metric",
        "assembles",
        "--out",
        str(out),
        "--quiet",
    )
    assert r.returncode == 0, r.stderr
    assert "no variant assembles" not in r.stdout


def test_a_metric_with_no_value_is_explained_by_its_cause(tmp_path):
    r = linkwork(
        "sweep",
        "four-bar",
        "--vary",
        "links.crank.length=255:260:2",
        "--metric",
        "swing",
        "--metric",
        "assembles",
        "--out",
        str(tmp_path / "x.parquet"),
        "--quiet",
    )
    assert r.returncode == 0, r.stderr
    assert "no variant assembles over the whole turn" in r.stdout


def test_a_named_centre_of_mass_follows_its_point_as_in_the_edited_file():
    """percussion-rocker: the rocker's ``com: C`` and its inertia about O.  A variant moving C moves the
    centre of mass with it and keeps the inertia about O, exactly as the file edited by hand does; a file
    that pins the centre of mass at the old C (as coordinates) differs, so the test can tell them apart."""
    t = lw.sweep("percussion-rocker", ["links.rocker.points.C.x=0.2:0.2:1"], ["peak_driving_torque"])

    def peak(com):
        yaml = YAML()
        data = yaml.load(text("percussion-rocker"))
        rocker = data["links"]["rocker"]
        rocker["points"]["C"] = [0.2, 0.01]
        if com is not None:
            rocker["com"] = com
        import io

        buf = io.StringIO()
        yaml.dump(data, buf)
        return abs(torque_peak(lw.forces(lw.compile(lw.loads(buf.getvalue())), steps=360)).value[0])

    edited, pinned = peak(None), peak([0.16, 0.01])
    assert t["peak_driving_torque"][0] == pytest.approx(edited, rel=1e-9)
    assert abs(pinned - edited) > 1e-3 * edited


def test_a_link_pivoted_on_the_frame_that_turns_fully_has_no_swing():
    """O2O4 = 50 mm, the shortest link, with s + l = 0.05 + 0.28 <= 0.10 + 0.25 (Grashof): a drag link, whose
    'rocker' turns fully with the crank, so it has no swing and no time ratio; the crank-rocker beside it has."""
    t = lw.sweep(
        "four-bar",
        ["frame.points.O4.x=50:300:2", "links.coupler.length=280:280:1"],
        ["swing", "time_ratio", "assembles"],
    )
    assert list(t["assembles"]) == [1.0, 1.0]
    assert np.isnan(t["swing"][0]) and np.isnan(t["time_ratio"][0])
    a, b, c, d = 0.1, 0.28, 0.25, 0.3
    psi = [np.arccos((d * d + c * c - s**2) / (2 * d * c)) for s in (b + a, b - a)]
    assert t["swing"][1] == pytest.approx(abs(psi[0] - psi[1]), rel=1e-6)


def test_a_variant_that_does_not_assemble_has_nan_metrics():
    # a crank of 260 mm: O2B would reach 610 mm at 180 deg, beyond frame + rocker = 550 mm
    t = lw.sweep("four-bar", ["links.crank.length=100:260:2"], ["swing", "assembles", "peak_driving_torque"])
    assert list(t["assembles"]) == [1.0, 0.0]
    assert np.isfinite(t["swing"][0]) and np.isnan(t["swing"][1]) and np.isnan(t["peak_driving_torque"][1])


# ---------------------------------------------------------------- sample plans


def test_latin_hypercube_puts_one_sample_in_every_stratum_and_random_is_seeded():
    varies = [Vary("a", 1.0, 3.0, None, "length"), Vary("b", -1.0, 0.0, None, "length")]
    n = 64
    lhs = make_plan(varies, "lhs", n, seed=7)
    v = lhs.values(0, n)
    for j, (lo, hi) in enumerate([(1.0, 3.0), (-1.0, 0.0)]):
        strata = np.floor((v[:, j] - lo) / (hi - lo) * n).astype(int)
        assert sorted(strata) == list(range(n))
    np.testing.assert_array_equal(lhs.values(10, 20), v[10:20])
    rnd = make_plan(varies, "random", 1000, seed=3)
    w = rnd.values(0, 1000)
    assert np.all((w[:, 0] >= 1) & (w[:, 0] <= 3) & (w[:, 1] >= -1) & (w[:, 1] <= 0))
    np.testing.assert_array_equal(w, make_plan(varies, "random", 1000, seed=3).values(0, 1000))
    assert not np.array_equal(w, make_plan(varies, "random", 1000, seed=4).values(0, 1000))


def test_zero_and_negative_lengths_and_masses_are_refused(tmp_path):
    with pytest.raises(DesignError) as err:
        lw.sweep(
            "four-bar",
            [
                "links.crank.length=0:100:3",
                "links.rocker.length=-10mm:250mm:2",
                "links.coupler.mass=0:1:2",
                "frame.points.O4.x=-100:300:2",
            ],
            ["swing"],
        )
    problems = err.value.problems
    assert any("links.crank.length=0:100:3" in p and "a length must be positive" in p for p in problems)
    assert any("links.rocker.length=-10mm:250mm:2" in p and "a length must be positive" in p for p in problems)
    assert not any("frame.points.O4.x" in p for p in problems)  # a coordinate may be negative
    out = tmp_path / "z.parquet"
    r = linkwork("sweep", "four-bar", "--vary", "links.crank.length=0:100:3", "--metric", "swing", "--out", str(out))
    assert r.returncode == 2 and "Traceback" not in r.stderr and "a length must be positive" in r.stderr
    assert not out.exists() and not (tmp_path / "z.parquet.parts").exists()
    with pytest.raises(DesignError, match="a mass must be positive"):
        lw.sweep("four-bar", ["links.crank.mass=-1:2:2"], ["swing"])


def test_random_and_lhs_samples_need_no_count_and_refuse_one():
    t = lw.sweep("four-bar", ["links.crank.length=90:110"], ["swing"], sampling="lhs", samples=10, seed=2)
    # one sample in each tenth of the range
    strata = np.floor((t["links.crank.length"] - 0.09) / 0.02 * 10).astype(int)
    assert sorted(strata) == list(range(10))
    with pytest.raises(DesignError, match="COUNT is for a grid"):
        lw.sweep("four-bar", ["links.crank.length=90:110:3"], ["swing"], sampling="random", samples=10)
    with pytest.raises(DesignError, match="COUNT missing"):
        lw.sweep("four-bar", ["links.crank.length=90:110"], ["swing"])
    r = linkwork(
        "sweep",
        "four-bar",
        "--sample",
        "lhs",
        "--samples",
        "4",
        "--vary",
        "links.crank.length=90:110",
        "--metric",
        "swing",
        "--out",
        "/dev/null/x.parquet",
    )
    assert "COUNT" not in r.stderr


def test_a_negative_number_of_workers_is_refused(tmp_path):
    with pytest.raises(DesignError, match="workers: expected 0 or more"):
        lw.sweep("four-bar", ["links.crank.length=90:110:3"], ["swing"], workers=-1)
    out = tmp_path / "w.parquet"
    r = linkwork(
        "sweep",
        "four-bar",
        "--vary",
        "links.crank.length=90:110:3",
        "--metric",
        "swing",
        "--workers",
        "-1",
        "--out",
        str(out),
        "--quiet",
    )
    assert r.returncode == 2 and "Traceback" not in r.stderr and "workers" in r.stderr
    assert not out.exists() and not (tmp_path / "w.parquet.parts").exists()


def test_mass_paths_are_listed_with_the_geometry():
    """Against the file read as plain YAML: every moving link with a mass gets a mass path with that mass,
    every link with a length its length, and nothing else is a mass path."""
    data = YAML(typ="safe").load(text("double-cut-shears"))
    assert data["units"]["length"] == "m" and data["units"]["mass"] == "kg"
    params = lw.parameters(lw.compile(lw.load("double-cut-shears")))
    masses = {f"links.{name}.mass": float(link["mass"]) for name, link in data["links"].items() if link.get("mass")}
    assert {p: v for p, v in params.items() if p.endswith(".mass")} == pytest.approx(masses, rel=1e-12)
    for name, link in data["links"].items():
        if "length" in link:
            assert params[f"links.{name}.length"] == pytest.approx(float(link["length"]), rel=1e-12)


def test_parameters_are_listed_in_the_files_units_and_a_range_far_from_them_warns(tmp_path):
    data = YAML(typ="safe").load(text("four-bar"))
    assert data["units"]["length"] == "mm"
    r = linkwork("parameters", "four-bar")
    assert r.returncode == 0, r.stderr
    listed = {line.split()[0]: (float(line.split()[1]), line.split()[2]) for line in r.stdout.splitlines()}
    for name, link in data["links"].items():
        assert listed[f"links.{name}.length"] == (pytest.approx(float(link["length"])), "mm")
        assert listed[f"links.{name}.mass"] == (pytest.approx(float(link["mass"])), "kg")
    assert listed["frame.points.O4.x"] == (pytest.approx(float(data["frame"]["points"]["O4"][0])), "mm")
    out = tmp_path / "u.parquet"
    base = ["sweep", "four-bar", "--metric", "swing", "--out", str(out), "--quiet"]
    r = linkwork(*base, "--vary", "links.crank.length=0.09:0.11:3")  # metres meant, millimetres read
    assert r.returncode == 0, r.stderr
    warned = [line for line in r.stderr.splitlines() if line.startswith("warning:")]
    assert len(warned) == 1 and "below 1/100 of the file's value 100 mm" in warned[0]
    for vary in ("links.crank.length=90:110:3", "links.crank.length=0.09m:0.11m:3"):
        out.unlink()
        r = linkwork(*base, "--vary", vary)
        assert r.returncode == 0 and "warning" not in r.stderr, r.stderr
    from linkwork.errors import DesignWarning

    with pytest.warns(DesignWarning, match="above 100 times"):
        lw.sweep("four-bar", ["links.rocker.length=30m:40m:2"], ["assembles"])


# ---------------------------------------------------------------- chunks on disk, interruption, resume


def _log(path):
    lines = [line.split() for f in sorted(path.glob("attempts-*.txt")) for line in f.read_text().splitlines()]
    return [int(c) for c, _ in lines]


def test_an_interrupted_sweep_resumes_and_computes_every_chunk_once(tmp_path):
    out = tmp_path / "four.parquet"
    args = ("four-bar", ["links.crank.length=80:110:12", "links.rocker.length=240:260:5"], ["swing", "time_ratio"])
    whole = lw.sweep(*args, chunk_size=7)

    class Stop(Exception):
        pass

    def stop_after_three(chunk, done, total):
        if done == 3:
            raise Stop

    attempts = tmp_path / "attempts"
    attempts.mkdir()
    with pytest.raises(Stop):
        lw.sweep(*args, chunk_size=7, out=out, attempts=attempts, on_chunk=stop_after_three)
    assert not out.exists()
    parts = sorted(p.name for p in (tmp_path / "four.parquet.parts").glob("chunk-*.parquet"))
    assert parts == ["chunk-00000.parquet", "chunk-00001.parquet", "chunk-00002.parquet"]
    with pytest.raises(DesignError, match="--resume"):
        lw.sweep(*args, chunk_size=7, out=out)
    with pytest.raises(DesignError, match="another plan"):
        lw.sweep(
            "four-bar",
            ["links.crank.length=80:111:12", "links.rocker.length=240:260:5"],
            ["swing", "time_ratio"],
            chunk_size=7,
            out=out,
            resume=True,
        )
    t = lw.sweep(*args, chunk_size=7, out=out, attempts=attempts, resume=True, keep_parts=True)
    assert sorted(_log(attempts)) == list(range(9))  # 60 variants in 9 chunks, each evaluated once
    np.testing.assert_array_equal(t["variant"], np.arange(60))
    for name in whole.columns:
        np.testing.assert_array_equal(t[name], whole[name])
    import pyarrow.parquet as pq

    table = pq.read_table(out)
    assert table.num_rows == 60 and table.schema.field("swing").metadata[b"unit"] == b"rad"
    np.testing.assert_array_equal(table.column("time_ratio").to_numpy(), whole["time_ratio"])
    manifest = json.loads((tmp_path / "four.parquet.parts" / "manifest.json").read_text())
    assert manifest["chunk_size"] == 7 and manifest["plan"]["varies"][0]["count"] == 12


def test_the_parts_folder_goes_once_the_table_is_written_and_a_run_again_is_not_refused(tmp_path):
    out = tmp_path / "p.parquet"
    args = ("four-bar", ["links.crank.length=90:110:6"], ["swing"])
    first = lw.sweep(*args, chunk_size=2, out=out)
    assert out.exists() and not (tmp_path / "p.parquet.parts").exists()
    again = lw.sweep(*args, chunk_size=2, out=out)  # no --resume needed: nothing is left to resume
    np.testing.assert_array_equal(again["swing"], first["swing"])
    # a stale manifest with no chunk (a sweep that stopped before its first chunk) does not block a run
    (tmp_path / "p.parquet.parts").mkdir()
    (tmp_path / "p.parquet.parts" / "manifest.json").write_text("{}")
    lw.sweep(*args, chunk_size=2, out=out)
    assert not (tmp_path / "p.parquet.parts").exists()


def test_an_unwritable_out_is_refused_before_the_work(tmp_path):
    for args in (
        ["sweep", "four-bar", "--vary", "links.crank.length=90:110:3", "--metric", "swing", "--out", "/proc/x.parquet"],
        [
            "optimize",
            "four-bar",
            "--vary",
            "links.rocker.length=220:280",
            "--objective",
            "peak_driving_torque",
            "--out",
            "/proc/b.yaml",
        ],
        [
            "sweep",
            "four-bar",
            "--vary",
            "links.crank.length=90:110:3",
            "--metric",
            "swing",
            "--out",
            str(tmp_path / "no" / "x.parquet"),
        ],
    ):
        r = linkwork(*args)
        assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
        assert len(r.stderr.strip().splitlines()) == 1 and "--out" in r.stderr
    assert not Path("/proc/x.parquet.parts").exists() and not (tmp_path / "no").exists()


def test_a_bad_or_unreachable_scheduler_is_one_message_and_blocks_no_later_run(tmp_path):
    import socket

    out = tmp_path / "s.parquet"
    base = [
        "sweep",
        "four-bar",
        "--vary",
        "links.crank.length=90:110:3",
        "--metric",
        "swing",
        "--out",
        str(out),
        "--quiet",
    ]
    r = linkwork(*base, "--scheduler", str(tmp_path / "nonexistent.json"))
    assert r.returncode == 2 and "Traceback" not in r.stderr and "no such scheduler file" in r.stderr
    with socket.socket() as sock:  # a port nobody listens on
        sock.bind(("127.0.0.1", 0))
        port = sock.getsockname()[1]
    r = linkwork(*base, "--scheduler", f"tcp://127.0.0.1:{port}", "--connect-timeout", "1")
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert f"cannot reach a Dask scheduler at tcp://127.0.0.1:{port} within 1 s" in r.stderr
    assert not out.exists() and not (tmp_path / "s.parquet.parts").exists()
    r = linkwork(*base)  # the failed connection left nothing that would need --resume
    assert r.returncode == 0, r.stderr


@pytest.mark.parametrize("service", ["http", "silent", "chatty"])
def test_a_service_that_is_not_a_dask_scheduler_is_one_message_within_the_timeout(tmp_path, service):
    """`--scheduler` at a TCP service on 127.0.0.1 that is no Dask scheduler: an HTTP server (Dask's dashboard
    port given by mistake; Dask would read "HTTP/1.1" as a frame length of exbibytes), one that accepts and
    never answers (Dask would wait without end) and one that greets in another protocol: one line naming the
    address and the timeout, exit 2, within the timeout and a little."""
    import http.server
    import socket
    import threading
    import time

    if service == "http":
        server = http.server.HTTPServer(("127.0.0.1", 0), http.server.BaseHTTPRequestHandler)
        threading.Thread(target=server.serve_forever, daemon=True).start()
        port, stop = server.server_address[1], server.shutdown
    else:
        listener = socket.create_server(("127.0.0.1", 0))
        held = []

        def accept() -> None:
            while True:
                try:
                    conn, _ = listener.accept()
                except OSError:
                    return
                held.append(conn)
                if service == "chatty":
                    conn.sendall(b"SSH-2.0-OpenSSH_9.6\r\n")

        threading.Thread(target=accept, daemon=True).start()
        port, stop = listener.getsockname()[1], listener.close
    try:
        out = tmp_path / "s.parquet"
        start = time.monotonic()
        where = ["--scheduler", f"tcp://127.0.0.1:{port}", "--connect-timeout", "2"]
        r = linkwork(
            "sweep",
            "four-bar",
            "--vary",
            "links.crank.length=90:110:3",
            "--metric",
            "swing",
            "--out",
            str(out),
            "--quiet",
            *where,
        )
        took = time.monotonic() - start
    finally:
        stop()
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(
        f"error: cannot reach a Dask scheduler at tcp://127.0.0.1:{port} within 2 s: "
    ), r.stderr
    assert took < 2 + 3 and not out.exists() and not (tmp_path / "s.parquet.parts").exists()


def test_netcdf_without_xarray_is_refused_up_front(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "xarray", None)  # import xarray raises ImportError
    calls = []
    with pytest.raises(DesignError, match=r'pip install "linkwork\[data\]"'):
        lw.sweep(
            "four-bar",
            ["links.crank.length=90:110:3"],
            ["swing"],
            out=tmp_path / "s.nc",
            on_chunk=lambda *a: calls.append(a),
        )
    assert not calls and not list(tmp_path.iterdir())


def test_netcdf_output(tmp_path):
    xr = pytest.importorskip("xarray")
    out = tmp_path / "s.nc"
    t = lw.sweep("four-bar", ["links.crank.length=90:110:4"], ["swing"], out=out)
    with xr.open_dataset(out) as ds:
        np.testing.assert_array_equal(ds["swing"].values, t["swing"])
        assert ds["swing"].attrs["units"] == "rad"


# ---------------------------------------------------------------- errors


def test_every_problem_of_the_options_is_reported_at_once():
    with pytest.raises(DesignError) as err:
        lw.sweep(
            "four-bar",
            [
                "links.crank.lenght=90:110:3",
                "links.rocker.length=260:240:0",
                "links.coupler.length=abc:1:2",
                "links.crank.length=1 kg:2 kg:3",
                "frame.points.O4.x=1:2",
            ],
            ["knife_overlap", "bogus", "stroke"],
        )
    msg = str(err.value).splitlines()
    assert 'no parameter "links.crank.lenght" (did you mean "links.crank.length"?)' in msg[0]
    assert any("COUNT must be 1 or more, got 0" in m for m in msg)
    assert any("START 260 is greater than STOP 240" in m for m in msg)
    assert any('START: expected a length, got "abc"' in m for m in msg)
    assert any('START: expected a length, got "1 kg"' in m for m in msg)
    assert any("COUNT missing" in m for m in msg)
    assert any('"knife_overlap" does not apply to four-bar' in m for m in msg)
    assert any('"stroke" does not apply' in m and "no slider" in m for m in msg)
    assert any('metric "bogus": unknown' in m and "peak_driving_torque" in m for m in msg)
    assert any('STOP: expected a length, got "2 kg"' in m for m in msg)
    assert len(msg) == 10


def test_cli_sweep_errors_exit_2_with_no_traceback_and_no_file(tmp_path):
    out = tmp_path / "s.parquet"
    r = linkwork(
        "sweep", "four-bar", "--vary", "links.crank.length=110:90:3", "--metric", "knife_clearance", "--out", str(out)
    )
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert "START 110 is greater than STOP 90" in r.stderr and "knife_clearance" in r.stderr
    assert not out.exists() and not (tmp_path / "s.parquet.parts").exists()


def test_cli_sweep_writes_the_table(tmp_path):
    out = tmp_path / "s.parquet"
    r = linkwork(
        "sweep",
        "shears-slider-crank",
        "--vary",
        "links.crank.length=100mm:140mm:3",
        "--metric",
        "stroke",
        "--out",
        str(out),
        "--quiet",
    )
    assert r.returncode == 0, r.stderr
    import pyarrow.parquet as pq

    t = pq.read_table(out)
    # a centric slider-crank (the knife on the line through O) with the crank shorter than the rod: stroke 2 r
    r_ = t.column("links.crank.length").to_numpy()
    np.testing.assert_allclose(t.column("stroke").to_numpy(), 2 * r_, rtol=1e-7)
    assert t.num_rows == 3 and "3 variants" in r.stdout


# ---------------------------------------------------------------- optimisation


def test_optimum_transmission_angle_of_a_four_bar_is_the_closed_form_one():
    """The smallest transmission angle occurs with the crank along the frame line (0 and 180 deg); it is
    largest when the two are supplementary: b^2 + c^2 = a^2 + d^2, so for the coupler b* = sqrt(a^2 + d^2 - c^2)."""
    best = lw.optimize(
        "four-bar",
        ["links.coupler.length=150:300"],
        "min_transmission_angle",
        maximize=True,
        steps=360,
        seed=1,
        maxiter=100,
        tol=1e-12,
    )
    a, c, d = 0.1, 0.25, 0.3
    b = math.sqrt(a * a + d * d - c * c)
    assert best.feasible
    assert best.values["links.coupler.length"] == pytest.approx(b, rel=1e-6)
    mu = math.acos((b * b + c * c - (d - a) ** 2) / (2 * b * c))
    assert best.metrics["min_transmission_angle"] == pytest.approx(mu, rel=1e-6)


# about a minute of processor time on the NumPy kernels: the four-bar's optimum above stands for it in the default lane
@pytest.mark.slow
def test_double_cut_shears_optimum_is_feasible_better_than_a_sample_and_its_file_reproduces_it(tmp_path):
    vary = [
        "links.crank.length=80mm:120mm",
        "links.rocker.points.B.x=0.4:0.6",
        "links.rocker.points.C.x=0.25:0.35",
        "links.rocker.points.D.x=-0.35:-0.25",
    ]
    cons = ["knife_overlap>=5mm", "knife_clearance>=200mm"]
    out = tmp_path / "best.yaml"
    best = lw.optimize("double-cut-shears", vary, "peak_driving_torque", cons, seed=0, maxiter=40, out=out)
    assert best.feasible and best.metrics["knife_overlap"] >= 0.005 and best.metrics["knife_clearance"] >= 0.2
    assert best.metrics["peak_driving_torque"] < best.initial["peak_driving_torque"]
    # every design evaluated, with the sum of its violations: zero exactly where the constraints hold
    ev = best.evaluated
    assert len(ev) == best.evaluations
    meets = (ev["knife_overlap"] >= 0.005) & (ev["knife_clearance"] >= 0.2) & (ev["assembles"] == 1)
    np.testing.assert_array_equal(ev["violation"] == 0, meets)
    assert ev["peak_driving_torque"][meets].min() == pytest.approx(best.metrics["peak_driving_torque"], rel=1e-12)
    # no design of a random sample in the same ranges that meets the constraints does better
    sample = lw.sweep(
        "double-cut-shears",
        vary,
        ["peak_driving_torque", "knife_overlap", "knife_clearance"],
        sampling="random",
        samples=400,
        seed=5,
        steps=180,
    )
    ok = (sample["knife_overlap"] >= 0.005) & (sample["knife_clearance"] >= 0.2)
    assert ok.sum() > 10
    assert best.metrics["peak_driving_torque"] <= sample["peak_driving_torque"][ok].min() * (1 + 1e-9)
    # the written file, compiled afresh and solved by lw.forces and lw.kinematics on one mechanism
    mech = lw.compile(lw.load(out))
    for path, value in best.values.items():
        assert lw.parameters(mech)[path] == pytest.approx(value, rel=1e-9)
    f = lw.forces(mech, steps=180)
    assert abs(torque_peak(f).value[0]) == pytest.approx(best.metrics["peak_driving_torque"], rel=1e-9)
    k = lw.kinematics(mech, steps=36000)
    gap = k.position("knife_upper.edge")[:, 1] - k.position("knife_lower.edge")[:, 1]
    assert gap.max() == pytest.approx(best.metrics["knife_clearance"], abs=2e-6)
    assert -gap.min() == pytest.approx(best.metrics["knife_overlap"], abs=2e-6)
    assert "# crank pivot" in out.read_text()  # the file's comments are kept


def test_cli_optimize_reports_and_writes(tmp_path):
    out = tmp_path / "best.yaml"
    r = linkwork(
        "optimize",
        "four-bar",
        "--vary",
        "links.rocker.length=220:280",
        "--objective",
        "peak_driving_torque",
        "--constraint",
        "min_transmission_angle>=33deg",
        "--maxiter",
        "20",
        "--out",
        str(out),
        "--json",
    )
    assert r.returncode == 0, r.stderr
    res = json.loads(r.stdout)
    assert res["feasible"] and res["metrics"]["min_transmission_angle"] >= math.radians(33)
    # the written file, solved afresh: its rocker, its peak torque (lw.forces) and its smallest transmission
    # angle (law of cosines with the crank along the frame line, 0 and 180 deg, both among the samples)
    mech = lw.compile(lw.load(out))
    c = lw.parameters(mech)["links.rocker.length"]
    assert c == pytest.approx(res["values"]["links.rocker.length"], rel=1e-9)
    f = lw.forces(mech, steps=360)
    assert abs(torque_peak(f).value[0]) == pytest.approx(res["metrics"]["peak_driving_torque"], rel=1e-9)
    a, b, d = 0.1, 0.35, 0.3
    mu = [_fold(np.arccos((b * b + c * c - (d - s * a) ** 2) / (2 * b * c))) for s in (1, -1)]
    assert min(mu) == pytest.approx(res["metrics"]["min_transmission_angle"], rel=1e-9)
    assert isinstance(res["converged"], bool) and res["message"]
    bad = linkwork(
        "optimize",
        "four-bar",
        "--vary",
        "links.rocker.length=220:280",
        "--objective",
        "peak_torque",
        "--constraint",
        "swing=>3",
        "--out",
        str(tmp_path / "x.yaml"),
    )
    assert bad.returncode == 2 and "Traceback" not in bad.stderr
    assert 'metric "peak_torque": unknown' in bad.stderr and '--constraint "swing=>3"' in bad.stderr
    assert not (tmp_path / "x.yaml").exists()


def test_an_optimisation_stopped_at_its_generation_limit_says_it_did_not_converge():
    best = lw.optimize(
        "four-bar",
        ["links.coupler.length=150:300"],
        "min_transmission_angle",
        maximize=True,
        seed=1,
        maxiter=2,
        tol=1e-12,
    )
    assert best.generations == 2 and best.converged is False and "iterations" in best.message
    assert best.as_dict()["converged"] is False
    r = linkwork(
        "optimize",
        "four-bar",
        "--vary",
        "links.coupler.length=150:300",
        "--objective",
        "min_transmission_angle",
        "--maximize",
        "--maxiter",
        "2",
    )
    assert r.returncode == 0, r.stderr
    assert "not converged (Maximum number of iterations" in r.stdout


@pytest.mark.slow  # over the default lane's budget on the NumPy kernels (tests/conftest.py)
def test_the_manual_design_commands_run(tmp_path):
    from manual import page

    section = page("how-to/design.md")
    block = section.split("```", 2)[1]
    lines = block.replace("\\\n", " ").strip().splitlines()
    assert [shlex.split(line)[1] for line in lines] == ["parameters", "sweep", "optimize"]
    stdout = []
    for line in lines:
        args = shlex.split(line.split("  #")[0])
        r = linkwork(*args[1:], cwd=tmp_path)
        assert r.returncode == 0, r.stderr
        stdout.append(r.stdout)
    # the sweep's row of the file's own design (crank 100 mm, B at 500 mm) against lw.forces on the file
    import pyarrow.parquet as pq

    t = pq.read_table(tmp_path / "shears.parquet").to_pandas()
    row = t[np.isclose(t["links.crank.length"], 0.1) & np.isclose(t["links.rocker.points.B.x"], 0.5)]
    f = lw.forces(lw.compile(lw.load("double-cut-shears")), steps=360)
    assert len(row) == 1
    assert row["peak_driving_torque"].iloc[0] == pytest.approx(abs(torque_peak(f).value[0]), rel=1e-9)
    # the optimised file, solved afresh: the peak torque reported and the constraints, on a fine turn
    best = lw.compile(lw.load(tmp_path / "shears-optimised.yaml"))
    reported = next(line for line in stdout[2].splitlines() if line.split()[:1] == ["peak_driving_torque"])
    torque = abs(torque_peak(lw.forces(best, steps=360)).value[0])
    assert float(reported.split()[1]) == pytest.approx(torque, rel=1e-5)
    assert torque < 0.95 * abs(torque_peak(f).value[0])
    k = lw.kinematics(best, steps=36000)
    gap = k.position("knife_upper.edge")[:, 1] - k.position("knife_lower.edge")[:, 1]
    assert -gap.min() >= 0.005 - 2e-6 and gap.max() >= 0.2 - 2e-6


@pytest.mark.slow  # over the default lane's budget on the NumPy kernels (tests/conftest.py)
def test_a_sweep_killed_on_the_command_line_resumes_with_its_chunks_untouched(tmp_path):
    import os
    import signal
    import time

    out = tmp_path / "s.parquet"
    args = [
        "sweep",
        "double-cut-shears",
        "--vary",
        "links.crank.length=95mm:105mm:8",
        "--vary",
        "links.rod.length=390mm:410mm:3",
        "--metric",
        "peak_driving_torque",
        "--metric",
        "knife_overlap",
        "--out",
        str(out),
        "--chunk-size",
        "1",
        "--workers",
        "0",
        "--quiet",
    ]
    proc = subprocess.Popen([sys.executable, "-m", "linkwork.cli", *args], stderr=subprocess.PIPE)
    parts = tmp_path / "s.parquet.parts"
    deadline = time.monotonic() + 120
    while len(list(parts.glob("chunk-*.parquet"))) < 3 and time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.01)
    assert proc.poll() is None, "the sweep ended before it could be stopped"
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    proc.stderr.close()
    assert not out.exists()
    before = {p.name: (p.stat().st_ino, p.stat().st_mtime_ns) for p in parts.glob("chunk-*.parquet")}
    assert 3 <= len(before) < 24
    r = linkwork(*args, "--resume", "--keep-parts")
    assert r.returncode == 0, r.stderr
    after = {p.name: (p.stat().st_ino, p.stat().st_mtime_ns) for p in parts.glob("chunk-*.parquet")}
    assert len(after) == 24 and all(after[name] == stamp for name, stamp in before.items())
    assert not list(parts.glob(".*"))  # no temporary file left
    import pyarrow.parquet as pq

    t = pq.read_table(out)
    np.testing.assert_array_equal(t.column("variant").to_numpy(), np.arange(24))
    here = lw.sweep("double-cut-shears", args[3:6:2], ["peak_driving_torque", "knife_overlap"], workers=0)
    np.testing.assert_array_equal(t.column("peak_driving_torque").to_numpy(), here["peak_driving_torque"])


def test_cli_optimize_of_an_example_in_a_folder_with_a_file_of_its_name_writes_what_it_solved(tmp_path):
    """A ``four-bar.yaml`` of the user's own (coupler 360 mm) beside: the written file is the bundled example with
    the optimised crank, and solving it again gives the peak torque printed."""
    (tmp_path / "four-bar.yaml").write_text(text("four-bar").replace("length: 350", "length: 360"))
    r = linkwork(
        "optimize",
        "four-bar",
        "--vary",
        "links.crank.length=90:110",
        "--objective",
        "peak_driving_torque",
        "--maxiter",
        "3",
        "--popsize",
        "4",
        "--out",
        "best.yaml",
        "--json",
        cwd=tmp_path,
    )
    assert r.returncode == 0, r.stderr
    res = json.loads(r.stdout)
    again = lw.parameters(tmp_path / "best.yaml")
    assert again["links.coupler.length"] == pytest.approx(0.35, rel=1e-12)
    assert again["links.crank.length"] == pytest.approx(res["values"]["links.crank.length"], rel=1e-11)
    from linkwork.kinetostatics.peaks import torque_peak

    peak = abs(torque_peak(lw.forces(tmp_path / "best.yaml", steps=360)).value[0])  # refined, as the metric
    assert peak == pytest.approx(res["metrics"]["peak_driving_torque"], rel=1e-9)
