"""``linkwork synthesize``: the file it writes is taken as it is by check, kinematics, analyze and view;
requirements that cannot be met exit 2 with one line and no file."""

from __future__ import annotations

import json
import math
import re
import shlex

import pytest

import linkwork as lw
from commandline import linkwork
from linkwork.motion.analysis import extremes
from linkwork.units import parse_quantity


def stated(path, name):
    """The tolerance (SI) the written file states for its requirement ``name``: what its lengths, written to 0.1 mm,
    allow the measure (``<name>_tolerance`` under ``requirements:``)."""
    tol = lw.load(str(path)).requirements[f"{name}_tolerance"]
    if not isinstance(tol, str):
        return float(tol)
    return parse_quantity(tol, "angle" if "deg" in tol else "length")


def printed(stdout, name):
    """The measure and its tolerance ``synthesize`` prints for ``name`` (``upper stroke  129.98 mm  +- 0.08 mm``)."""
    found = re.search(rf"{name}\s+(\S+)(?: mm)?\s+\+- (\S+)", stdout)
    assert found, stdout
    return float(found.group(1)), float(found.group(2))


def test_the_written_slider_crank_meets_the_request_and_every_command_takes_it(tmp_path):
    out = tmp_path / "s.yaml"
    run = linkwork(
        "synthesize",
        "slider-crank",
        "--stroke",
        "400mm",
        "--time-ratio",
        "1.05",
        "--max-pressure-angle",
        "30deg",
        "--out",
        str(out),
    )
    assert run.returncode == 0, run.stderr
    (ext,) = extremes(lw.kinematics(str(out), steps=3600))
    assert abs(ext.stroke - 0.4) <= stated(out, "stroke") and abs(ext.time_ratio - 1.05) <= stated(out, "time_ratio")
    assert linkwork("check", str(out)).returncode == 0
    kin = linkwork("kinematics", str(out))
    assert kin.returncode == 0 and "time ratio K 1.0500" in kin.stdout
    shown = float(re.search(r"stroke (\S+) mm", kin.stdout).group(1))  # to 0.01 mm
    assert abs(shown - 400) <= stated(out, "stroke") * 1e3 + 0.005
    view = linkwork("view", str(out), "--export", str(tmp_path / "v.html"), "--steps", "36")
    assert view.returncode == 0, view.stderr
    report = linkwork("analyze", str(out), "--out", str(tmp_path / "r"), "--steps", "36", "--no-animation")
    assert report.returncode == 0, report.stderr


def test_the_written_crank_rocker_meets_the_swing(tmp_path):
    out = tmp_path / "c.yaml"
    run = linkwork(
        "synthesize",
        "crank-rocker",
        "--swing",
        "45deg",
        "--time-ratio",
        "1.2",
        "--frame",
        "300mm",
        "--out",
        str(out),
        "--json",
    )
    assert run.returncode == 0, run.stderr
    (ext,) = extremes(lw.kinematics(str(out), steps=3600))
    tol = json.loads(run.stdout)["tolerances"]  # the lengths written to 0.1 mm; the file states them too
    assert ext.stroke == pytest.approx(math.radians(45), abs=tol["swing"])
    assert ext.time_ratio == pytest.approx(1.2, abs=tol["time_ratio"])
    assert "swing_tolerance:" in out.read_text() and "time_ratio_tolerance:" in out.read_text()
    assert '"frame": 0.3' in run.stdout
    assert linkwork("check", str(out)).returncode == 0


def test_the_written_slotted_lever_meets_the_stroke_and_time_ratio_and_check_and_view_take_it(tmp_path):
    out = tmp_path / "shaper.yaml"
    run = linkwork(
        "synthesize",
        "slotted-lever",
        "--stroke",
        "600mm",
        "--time-ratio",
        "1.4",
        "--rod",
        "300mm",
        "--out",
        str(out),
        "--json",
    )
    assert run.returncode == 0, run.stderr
    (ram,) = [e for e in extremes(lw.kinematics(str(out), steps=3600)) if e.kind == "slider"]
    assert abs(ram.stroke - 0.6) <= stated(out, "stroke") and abs(ram.time_ratio - 1.4) <= stated(out, "time_ratio")
    assert '"rod": 0.3' in run.stdout
    assert linkwork("check", str(out)).returncode == 0
    view = linkwork("view", str(out), "--export", str(tmp_path / "v.html"), "--steps", "36")
    assert view.returncode == 0, view.stderr


def test_the_written_toggle_press_meets_the_stroke_and_its_forces_give_the_nominal_torque(tmp_path):
    out = tmp_path / "press.yaml"
    run = linkwork(
        "synthesize",
        "toggle-press",
        "--stroke",
        "200mm",
        "--force",
        "100kN",
        "--before",
        "10mm",
        "--torque",
        "5kN*m",
        "--out",
        str(out),
        "--json",
    )
    assert run.returncode == 0, run.stderr
    (ram,) = [e for e in extremes(lw.kinematics(str(out), steps=3600)) if e.kind == "slider"]
    assert abs(ram.stroke - 0.2) <= stated(out, "stroke")
    assert linkwork("check", str(out)).returncode == 0
    assert linkwork("forces", str(out)).returncode == 0


@pytest.mark.parametrize(
    "args",
    [
        ["slider-crank", "--stroke", "400mm", "--time-ratio", "1.3", "--max-pressure-angle", "30deg"],
        ["slider-crank", "--stroke", "400mm", "--time-ratio", "3.2"],
        ["slider-crank", "--stroke", "400 kg", "--time-ratio", "1.2"],
        ["slider-crank", "--time-ratio", "1.2"],
        ["crank-rocker", "--swing", "60deg", "--time-ratio", "1.5", "--rocker", "1m", "--min-transmission-angle", "45"],
        ["crank-rocker", "--swing", "60deg", "--time-ratio", "1.5", "--stroke", "1m"],
        ["four-bar", "--stroke", "1m", "--time-ratio", "1"],
        ["slider-crank", "--stroke", "nan", "--time-ratio", "1.1"],
        ["slider-crank", "--stroke", "1m", "--time-ratio", "abc"],
        ["crank-rocker", "--swing", "45deg", "--time-ratio", "inf", "--rocker", "1m"],
        ["crank-rocker", "--swing", "45deg", "--time-ratio", "1.1", "--rocker", "-1m"],
        ["slotted-lever", "--stroke", "600mm", "--time-ratio", "1"],
        ["slotted-lever", "--stroke", "600mm", "--time-ratio", "1.4", "--frame", "2m"],
        ["slotted-lever", "--stroke", "600mm", "--time-ratio", "1.4", "--offset", "10mm"],
        ["slotted-lever", "--time-ratio", "1.4"],
        ["toggle-press", "--stroke", "200mm", "--force", "100kN", "--before", "10mm", "--torque", "3kN*m"],
        ["toggle-press", "--stroke", "200mm", "--force", "100kN"],
        ["toggle-press", "--stroke", "200mm", "--force", "100kN", "--before", "300mm", "--torque", "5kN*m"],
    ],
)
def test_requirements_that_cannot_be_met_exit_2_with_one_line_and_no_file(tmp_path, args):
    out = tmp_path / "x.yaml"
    run = linkwork("synthesize", *args, "--out", str(out))
    assert run.returncode == 2
    assert run.stderr.startswith("error: ") and len(run.stderr.strip().splitlines()) == 1, run.stderr
    assert "Traceback" not in run.stderr
    assert not out.exists()


def test_the_message_of_an_impossible_bound_names_both_requirements_and_the_nearest_values(tmp_path):
    run = linkwork(
        "synthesize",
        "slider-crank",
        "--stroke",
        "400mm",
        "--time-ratio",
        "1.3",
        "--max-pressure-angle",
        "30deg",
        "--out",
        str(tmp_path / "s.yaml"),
    )
    assert run.stderr.strip() == (
        "error: time ratio K = 1.3 needs a largest pressure angle of at least 51.01 deg; at most 30 deg gives "
        "K <= 1.092"
    )


def test_the_manual_synthesis_commands_and_python_run(tmp_path, monkeypatch):
    from manual import page

    section = page("how-to/synthesize.md")
    commands, python = section.split("```")[1], section.split("```")[3]
    for line in commands.strip().splitlines():
        run = linkwork(*shlex.split(line)[1:], cwd=tmp_path)
        assert run.returncode == 0, run.stderr
    (ext,) = extremes(lw.kinematics(str(tmp_path / "press.yaml"), steps=3600))
    assert abs(ext.stroke - 0.4) <= stated(tmp_path / "press.yaml", "stroke")
    monkeypatch.chdir(tmp_path)
    exec(python.removeprefix("python\n"), {})  # noqa: S102 - the manual's own example
    (ext,) = extremes(lw.kinematics(str(tmp_path / "press.yaml"), steps=3600))
    assert abs(ext.time_ratio - 1.3) <= stated(tmp_path / "press.yaml", "time_ratio")
    assert "1.092" in section  # the message quoted is the one the command prints (tested above)


def test_the_written_double_cut_shears_meet_the_knives_requirements_and_check_takes_them(tmp_path):
    out = tmp_path / "shears.yaml"
    run = linkwork(
        "synthesize",
        "double-cut-shears",
        "--upper-stroke",
        "130mm",
        "--lower-stroke",
        "110mm",
        "--time-ratio",
        "1.05",
        "--opening",
        "225mm",
        "--out",
        str(out),
    )
    assert run.returncode == 0, run.stderr
    upper, tol = printed(run.stdout, "upper stroke")
    assert abs(upper - 130) <= tol and tol == pytest.approx(stated(out, "upper_stroke") * 1e3, rel=2e-3)
    overlap, tol = printed(run.stdout, "overlap")
    assert abs(overlap - 15) <= tol
    from linkwork.design.evaluate import Evaluation
    from linkwork.design.metrics import METRICS

    ev = Evaluation(lw.kinematics(str(out), steps=3600))
    assert abs(float(METRICS["stroke"].compute(ev, "guide_F")[0]) - 0.11) <= stated(out, "lower_stroke")
    assert abs(float(METRICS["knife_clearance"].compute(ev, None)[0]) - 0.225) <= stated(out, "opening")
    assert linkwork("check", str(out)).returncode == 0


def test_shears_whose_overlap_and_opening_disagree_exit_2_with_one_line_and_no_file(tmp_path):
    out = tmp_path / "shears.yaml"
    run = linkwork(
        "synthesize",
        "double-cut-shears",
        "--upper-stroke",
        "130mm",
        "--lower-stroke",
        "110mm",
        "--time-ratio",
        "1.05",
        "--opening",
        "225mm",
        "--overlap",
        "20mm",
        "--out",
        str(out),
    )
    assert run.returncode == 2 and not out.exists()
    assert run.stderr.strip().count("\n") == 0 and "must equal the strokes together 240 mm" in run.stderr


def test_the_summary_speaks_russian_with_lang_ru(tmp_path):
    out = tmp_path / "c.yaml"
    run = linkwork(
        "synthesize",
        "crank-rocker",
        "--swing",
        "45deg",
        "--time-ratio",
        "1.2",
        "--frame",
        "300mm",
        "--out",
        str(out),
        "--lang",
        "ru",
    )
    assert run.returncode == 0, run.stderr
    swing = re.search(r"угол качания +(\S+) град  \+- (\S+) град", run.stdout)
    assert "измерено анализом" in run.stdout and swing is not None
    assert abs(float(swing.group(1)) - 45) <= float(swing.group(2))  # within its tolerance, in Russian units
    assert f"записан: {out}" in run.stdout
    wrong = linkwork(
        "synthesize",
        "crank-rocker",
        "--swing",
        "45deg",
        "--time-ratio",
        "1.2",
        "--frame",
        "300mm",
        "--out",
        str(tmp_path / "d.yaml"),
        "--lang",
        "de",
    )
    assert wrong.returncode == 2 and not (tmp_path / "d.yaml").exists()


#: The requests of the reports that ended in a traceback, a message that contradicted itself or cited a file the
#: user never sees, or a file written with a value other commands refuse.
FAULTS = [
    "slider-crank --stroke 400mm --time-ratio 1 --rod-ratio 1",
    "slider-crank --stroke 400mm --time-ratio 1 --rod-ratio 1.5",
    "slider-crank --stroke 160 --time-ratio 1.2",
    "slider-crank --stroke '1e300 mm' --time-ratio 1.2",
    "slider-crank --stroke 400mm --time-ratio 1.2 --speed '-30 rpm'",
    "slotted-lever --stroke 400mm --time-ratio 1.001",
    "slotted-lever --stroke '1e300 mm' --time-ratio 1.5",
    "slotted-lever --stroke 400mm --time-ratio 1.0000000001",
    "slotted-lever --stroke 400mm --time-ratio 1.5 --max-pressure-angle '1e-300 deg'",
    "crank-rocker --swing 45deg --rocker 250mm --time-ratio 1.0000000001",
    "crank-rocker --swing 45deg --rocker 250mm --time-ratio 1e300",
    "crank-rocker --swing 170deg --rocker 100mm --time-ratio 1.2",
    "toggle-press --stroke 40mm --force 100kN --before 2mm --torque 8kN*m --swing '1e-12 deg'",
    "toggle-press --stroke 40mm --force 100kN --before 2mm --torque 8kN*m --time-ratio -1",
    "toggle-press --stroke 40mm --force 100kN --before 2mm --torque 8kN*m --time-ratio 1e300",
    "slider-crank --stroke 400mm --time-ratio 1.2 --section '1000m x 1000m'",  # masses over the files' bound
]


@pytest.mark.parametrize("request_", FAULTS)
def test_each_reported_fault_is_refused_with_one_line_of_the_users_own_words(tmp_path, request_):
    out = tmp_path / "s.yaml"
    run = linkwork("synthesize", *shlex.split(request_), "--out", str(out))
    assert run.returncode == 2 and not out.exists(), run.stderr
    lines = run.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and "Traceback" not in run.stderr
    assert "<synthesised>" not in run.stderr and "nan" not in run.stderr.replace("nanometre", "")


def test_a_bare_length_is_refused_with_the_unit_to_give(tmp_path):
    run = linkwork(
        "synthesize", "slider-crank", "--stroke", "160", "--time-ratio", "1.2", "--out", str(tmp_path / "s.yaml")
    )
    assert run.returncode == 2 and run.stderr.strip() == 'error: --stroke "160": give the unit, e.g. "160 mm"'


def test_the_slotted_levers_refusal_near_k_1_names_a_time_ratio_that_is_met(tmp_path):
    """K = 1.001 gave a lever of 255 m and a rod of 0.23 mm (and a structural message); the refusal names the
    least K whose lengths stay within 1000:1, and that K is met."""
    run = linkwork(
        "synthesize", "slotted-lever", "--stroke", "400mm", "--time-ratio", "1.001", "--out", str(tmp_path / "a.yaml")
    )
    k = run.stderr.split("a time ratio K >= ")[1].split(" ")[0]
    ok = linkwork(
        "synthesize", "slotted-lever", "--stroke", "400mm", "--time-ratio", k, "--out", str(tmp_path / "b.yaml")
    )
    assert ok.returncode == 0, ok.stderr
    lengths = [float(v) for v in re.findall(r"length: ([0-9.e+-]+)", (tmp_path / "b.yaml").read_text())]
    assert max(lengths) <= 1000 * min(lengths)


def test_a_central_press_file_an_engineer_keeps(tmp_path):
    """Described as central, no -0.0, every length to the files' one rule (12 significant digits), a comment on
    each derived length."""
    out = tmp_path / "press.yaml"
    args = ["--stroke", "400mm", "--time-ratio", "1", "--rod-ratio", "0.25", "--force", "50kN", "--working", "40mm"]
    assert linkwork("synthesize", "slider-crank", *args, "--out", str(out)).returncode == 0
    text = out.read_text()
    assert text.count("Central slider-crank") == 1 and "Offset" not in text and "-0.0" not in text
    for number in re.findall(r"-?\d+\.\d+(?:e[+-]?\d+)?", text.split("requirements:")[0]):
        assert len(number.lstrip("-").replace(".", "").lstrip("0")) <= 12, number
    for line in text.splitlines():
        if line.strip().startswith(("length:", "workpiece:", "through:")):
            assert "#" in line, line
