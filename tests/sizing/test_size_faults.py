"""``linkwork size`` on impossible parts, bad catalogues and bad destinations: exit code 2 with the reason, before
any computing, no traceback, nothing written; parts that cannot be made refused where the file is read."""

from __future__ import annotations

import os
import stat
import time

import pytest

import linkwork as lw
from commandline import linkwork
from linkwork.errors import LinkworkError, SpecError
from linkwork.examples import text
from linkwork.limits import MAX_CATALOGUE_ROWS, MAX_LOADS, MAX_PROBLEMS

SHEARS = text("double-cut-shears")
HEADING = "name,power [kW],synchronous [rpm],speed [rpm],starting [1],breakdown [1],inertia [kg m^2],mass [kg]\n"


def _refused(result, *texts: str) -> None:
    assert result.returncode == 2, (result.returncode, result.stderr[-2000:])
    assert "Traceback" not in result.stderr
    for t in texts:
        assert t in result.stderr, (t, result.stderr[-2000:])


def _with_sizing(extra: str) -> str:
    return SHEARS.replace("    guide_F: 0.40\n", "    guide_F: 0.40\n" + extra, 1)


# ---------------------------------------------------------------------------------------------- parts


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (
            "  sections: {crank: {shape: tube, d: 0.05, t: 0.025}}\n",
            "the wall t = 25 mm must be thinner than the radius",
        ),
        ("  sections: {crank: {shape: I, h: 0.05, b: 0.04, tw: 0.01, tf: 0.025}}\n", "fill the depth h = 50 mm"),
        ("  sections: {crank: {shape: I, h: 0.05, b: 0.04, tw: 0.041, tf: 0.01}}\n", "is wider than the flanges"),
        ("  sections: {crank: {shape: round, d: 1e-300}}\n", "a section's d of 1e-300 m is below 0.001 mm"),
        ("  sections: {crank: {shape: tube, d: 0.05}}\n", "a tube section needs d, t: give t"),
    ],
)
def test_a_section_that_cannot_be_made_is_refused_where_the_file_is_read(extra, message, tmp_path):
    path = tmp_path / "m.yaml"
    path.write_text(_with_sizing(extra))
    with pytest.raises(SpecError, match="sizing.sections.crank"):
        lw.load(path)
    _refused(linkwork("size", str(path), "--no-motor"), message, "m.yaml:")


def test_a_tube_just_thinner_than_its_radius_is_sized(tmp_path):
    path = tmp_path / "m.yaml"
    path.write_text(_with_sizing("  sections: {crank: {shape: tube, d: 0.2, t: 0.0999}}\n"))
    assert lw.load(path).sizing.sections["crank"].t == pytest.approx(0.0999)


def test_a_pin_of_1e_300_m_is_refused_not_a_traceback(tmp_path):
    path = tmp_path / "m.yaml"
    path.write_text(SHEARS.replace("O1: {diameter: 0.16, width: 0.16}", "O1: {diameter: 1e-300, width: 0.16}"))
    _refused(linkwork("size", str(path), "--no-motor"), "sizing.pins.O1.diameter: a pin's diameter of 1e-300 m")


@pytest.mark.parametrize("ratio", ["1e300", "1e-300", "0.05", "11", "nan", "-1"])
def test_a_width_ratio_past_its_bounds_is_refused(ratio):
    _refused(linkwork("size", "four-bar", "--no-motor", "--width-ratio", ratio), "--width-ratio", "from 0.1 to 10")


# ---------------------------------------------------------------------------------------------- springs


def _springs(loads: str) -> str:
    return text("four-bar") + "\nloads:\n" + loads


def test_a_spring_of_negative_free_length_is_refused(tmp_path):
    path = tmp_path / "m.yaml"
    path.write_text(_springs("  s: {type: spring, between: [O4, coupler.M], stiffness: 100 N/m, free_length: -20}\n"))
    _refused(linkwork("check", str(path)), "loads.s.free_length", "from 0 up, got -0.02 m")


def test_a_preload_that_needs_a_negative_free_length_is_refused_with_the_most_it_may_be(tmp_path):
    """O4 = (300, 0) mm and M on the coupler: the spring's length in the assembly pose L; a preload P at
    k = 100 N/m needs the free length L - P / k, negative past P = k L."""
    path = tmp_path / "m.yaml"
    path.write_text(_springs("  s: {type: spring, between: [O4, coupler.M], stiffness: 100 N/m, preload: 1e6 N}\n"))
    mech = lw.compile("four-bar")
    p = mech.points0()
    names = list(mech.point_names)
    length = float(((p[names.index("coupler.M")] - p[names.index("frame.O4")]) ** 2).sum() ** 0.5)
    _refused(linkwork("forces", str(path)), "loads.s.preload", f"at most {100 * length:g} N")


def test_more_loads_than_the_bound_are_refused_before_any_work(tmp_path):
    path = tmp_path / "m.yaml"
    one = "  s{}: {{type: spring, between: [O4, coupler.M], stiffness: 100 N/m, free_length: 200}}\n"
    path.write_text(_springs("".join(one.format(i) for i in range(MAX_LOADS + 1))))
    start = time.perf_counter()
    _refused(linkwork("dynamics", str(path)), f"{MAX_LOADS + 1:,} loads; at most {MAX_LOADS:,}")
    assert time.perf_counter() - start < 10


# ---------------------------------------------------------------------------------------------- catalogues


def test_catalogues_that_are_no_regular_file_are_refused_before_they_are_opened(tmp_path):
    fifo = tmp_path / "motors.csv"
    os.mkfifo(fifo)  # no writer: opening it would block for ever
    start = time.perf_counter()
    _refused(linkwork("size", "four-bar", "--catalogue", str(fifo)), "it is a fifo, not a regular file")
    _refused(linkwork("size", "four-bar", "--catalogue", "/dev/zero"), "it is a character device")
    _refused(linkwork("size", "four-bar", "--catalogue", str(tmp_path)), "it is a directory")
    assert time.perf_counter() - start < 20


def test_a_catalogue_of_bad_rows_lists_a_screenful_and_counts_the_rest(tmp_path):
    path = tmp_path / "motors.csv"
    path.write_text(HEADING + "x,a,b,c,d,e,f,g\n" * 500)  # 7 bad numbers a row: 3,500 problems
    result = linkwork("size", "four-bar", "--catalogue", str(path))
    _refused(result, f"... and {3500 - MAX_PROBLEMS:,} more problems")
    assert len(result.stderr.splitlines()) == MAX_PROBLEMS + 2  # "error:", the problems, the count


def test_a_catalogue_past_its_rows_is_refused_before_any_work(tmp_path):
    path = tmp_path / "motors.csv"
    path.write_text(HEADING + "m,0.1,1500,1400,2,2.2,0.001,5\n" * (MAX_CATALOGUE_ROWS + 1))
    _refused(linkwork("size", "double-cut-shears", "--catalogue", str(path)), f"{MAX_CATALOGUE_ROWS + 1:,} rows")


def test_a_catalogue_larger_than_its_bound_is_not_read(tmp_path):
    path = tmp_path / "motors.csv"
    with open(path, "wb") as f:
        f.truncate(1 << 30)  # a sparse gigabyte
    _refused(linkwork("size", "four-bar", "--catalogue", str(path)), "1,073,741,824 bytes; a catalogue is at most")


def test_a_synchronous_speed_no_motor_has_is_said_with_the_speeds_there_are():
    start = time.perf_counter()
    result = linkwork("size", "double-cut-shears", "--synchronous", "1234 rpm")
    _refused(result, "no motor of the catalogue motors.csv has a synchronous speed of 1234 rpm", "1500")
    assert time.perf_counter() - start < 10  # before the loads are computed


def test_a_unit_that_is_not_one_is_said_so():
    _refused(linkwork("size", "four-bar", "--no-motor", "--life", "20000 ч"), '--life: "ч" is not a unit')
    _refused(linkwork("size", "four-bar", "--no-motor", "--life", "20000 rpm"), '"rpm" is a unit of another kind')


# ---------------------------------------------------------------------------------------------- --write


def test_a_read_only_file_is_not_replaced(tmp_path):
    out = tmp_path / "m.yaml"
    out.write_text("kept\n")
    out.chmod(0o444)
    start = time.perf_counter()
    _refused(linkwork("size", "double-cut-shears", "--write", str(out)), "is read-only (mode 0444)")
    assert time.perf_counter() - start < 10  # before any computing
    assert out.read_text() == "kept\n" and stat.S_IMODE(out.stat().st_mode) == 0o444


def test_a_destination_under_a_file_is_said_plainly_before_any_work(tmp_path):
    (tmp_path / "f").write_text("a file\n")
    start = time.perf_counter()
    result = linkwork("size", "double-cut-shears", "--write", str(tmp_path / "f" / "m.yaml"))
    _refused(result, f"cannot be made: {tmp_path / 'f'} is a file, not a folder")
    assert "Errno" not in result.stderr and time.perf_counter() - start < 10
    assert (tmp_path / "f").read_text() == "a file\n"


# ---------------------------------------------------------------------------------------------- --no-motor


def test_no_motor_says_what_was_not_sized_and_states_no_motor_inputs():
    result = linkwork("size", "four-bar", "--no-motor")
    assert result.returncode == 0, result.stderr
    assert "not sized: motor: not asked" in result.stdout
    assert "reserve" not in result.stdout and "catalogue" not in result.stdout


def test_a_bush_whose_load_is_not_finite_is_not_said_to_be_within_its_limits():
    from linkwork.sizing.bearings import Bearings, Bush, JointBearing

    nan = float("nan")
    j = JointBearing("O", ("frame", "crank"), "turns", 6.3, nan, 0, nan, 1, nan, nan, nan, nan, False, *[nan] * 5)
    b = Bearings((j,), (), 20000, "ball", 30, Bush("bronze", 15e6, 1, 2.5e6), 1.0)
    assert b.over(j).startswith("not known")


# ---------------------------------------------------------------------------------------------- --write text


def _outside(text: str, key: str) -> list[str]:
    """The lines of ``text`` outside its top-level section ``key`` (to the next top-level key)."""
    out, inside = [], False
    for line in text.splitlines():
        if line and not line[0].isspace() and not line.startswith("#"):
            inside = line.startswith(f"{key}:")
        if not inside:
            out.append(line)
    return out


@pytest.mark.parametrize("example", ["double-cut-shears", "four-bar"])
def test_the_machine_section_written_keeps_every_other_byte_comments_after_anchors_and_aliases_too(example, tmp_path):
    from linkwork.spec.edit import text_with_section

    original = text(example).replace("length: 0.10", "length: &L 0.10   # the crank's length", 1)
    original = original.replace("length: 100\n", "length: &L 100   # the crank's length\n", 1)
    original = original.replace("length: 250\n", "length: *L  # as the crank\n", 1)
    original = original.replace("    guide_F: 0.40", "    guide_F: *L  # as the crank", 1)
    assert "*L  # as the crank" in original
    path = tmp_path / "m.yaml"
    path.write_text(original)
    section = {"delta": 0.05, "flywheel": {"inertia": "1 kg*m^2", "on": "motor"}}
    motor = {"type": "induction", "power": "7.5 kW", "speed": "1450 rpm", "synchronous": "1500 rpm", "breakdown": 2.2}
    section["motor"] = {**motor, "inertia": "0.05 kg*m^2", "torque": None, "stall": None, "no_load": None}
    written = text_with_section(lw.load(path), "machine", section)
    assert _outside(written, "machine") == _outside(original, "machine")
    assert lw.loads(written).machine.flywheel.inertia == pytest.approx(1.0)


def test_a_terminal_is_shown_the_motors_looked_at_and_the_line_is_cleared(monkeypatch):
    import io
    import sys

    from linkwork.cli.size import _cleared, _progress

    class Terminal(io.StringIO):
        def isatty(self) -> bool:
            return True

    screen = Terminal()
    monkeypatch.setattr(sys, "stderr", screen)
    show = _progress()
    assert show is not None
    show(41, 1000)
    _cleared(show)
    assert screen.getvalue() == "\r\033[K  motor 42 of 1,000 looked at\r\033[K"
    monkeypatch.setattr(sys, "stderr", io.StringIO())  # a file or a pipe: nothing
    assert _progress() is None


@pytest.mark.slow
def test_a_catalogue_of_motors_that_fail_the_run_is_bounded_and_says_what_it_did_not_try(tmp_path):
    """60 motors of 10 kW whose breakdown ratio 1.05 fails every run: 12 runs, then the other 48 named."""
    path = tmp_path / "motors.csv"
    path.write_text(HEADING + "".join(f"m{i},{10 + i * 0.001},1500,1400,2,1.05,0.001,5\n" for i in range(60)))
    start = time.perf_counter()
    result = linkwork("size", "double-cut-shears", "--catalogue", str(path))
    _refused(result, "48 larger motors of the catalogue not tried: 12 runs of the machine is the most")
    assert time.perf_counter() - start < 180


def _rough_shears(f: float, radius: float) -> str:
    """The slider-crank shears of seed 000 with friction ``f`` in every pair (pins of ``radius``), as a file."""
    out = text("shears-slider-crank")
    for kind in ("type: revolute", "type: prismatic"):
        pin = f", radius: {radius * 1e3:g} mm" if kind.endswith("revolute") else ""
        out = out.replace(kind, f"{kind}, friction: {{f: {f}{pin}}}")
    return out


@pytest.mark.filterwarnings("ignore::linkwork.errors.FrictionWarning")
def test_a_machine_that_friction_locks_is_not_sized_and_the_locked_angles_are_named(tmp_path):
    """f = 0.1 with pins of 20 mm: within about the friction angle (atan 0.1 = 5.7 deg, more with the pins' friction
    circles) of the dead points phi = 90 and 270 deg, where the rod lies across the knife's guide, no drive moves the
    shears; sizing refuses them, naming those angles (the friction is taken as zero at the dead points themselves),
    on the command line too: exit 2, one message, nothing written.  With f = 0.01 and pins of 10 mm nothing locks,
    and the parts are sized."""
    path = tmp_path / "rough.yaml"
    path.write_text(_rough_shears(0.1, 0.020), encoding="utf-8")
    assert path.read_text().count("friction:") >= 4
    with pytest.raises(LinkworkError, match="friction locks the machine at phi = ") as caught:
        lw.size(str(path), motor=False, steps=360)
    spans = caught.value.args[0].split("phi = ")[1].split(" deg")[0].split(", ")
    bounds = [tuple(float(x) for x in span.split(" to ")) for span in spans]
    assert bounds[0][0] > 80 and bounds[-1][-1] < 280  # none far from the dead points
    for dead in (90.0, 270.0):
        near = [b for b in bounds if abs(b[0] - dead) < 10]
        assert [b[0] for b in near] == [pytest.approx(dead - 7, abs=1.5), dead + 1]
        assert [b[-1] for b in near] == [dead - 1, pytest.approx(dead + 7, abs=1.5)]
    result = linkwork("size", str(path), "--write", str(tmp_path / "out.yaml"))
    _refused(result, "friction locks the machine at phi = 83 to 89")
    assert not (tmp_path / "out.yaml").exists() and result.stderr.count("\n") == 1
    smooth = tmp_path / "smooth.yaml"
    smooth.write_text(_rough_shears(0.01, 0.010), encoding="utf-8")
    sized = lw.size(str(smooth), motor=False, steps=90)
    assert sized.pins and sized.bearings
