"""Hostile input for ``linkwork size`` and the parts it reads, one generator per class (registered in
:func:`hostile.option_cases`): options at and past their bounds, sections and pins that cannot be made,
force elements of impossible lengths or in numbers past the bound, catalogues that are devices, folders, huge or
all invalid, and ``--write`` destinations that cannot be written.  Each case must end in exit code 0, or 2 with
a short message, within the suite's time and memory bounds; those that compute are kept to ``--no-motor`` or to
refusals made before any computing, so that each takes seconds.
"""

from __future__ import annotations

from hostile import Case
from linkwork.examples import text
from linkwork.limits import MAX_CATALOGUE_BYTES, MAX_CATALOGUE_ROWS, MAX_LOADS

SHEARS = text("double-cut-shears")
HEADING = "name,power [kW],synchronous [rpm],speed [rpm],starting [1],breakdown [1],inertia [kg m^2],mass [kg]\n"
MAGNITUDES = ("1e300", "1e-300", "0", "-1", "nan", "inf", "1e-7", "1e9")


def option_cases() -> list[Case]:
    """``size`` options at and past their bounds: the width ratio, the life, the synchronous speed, the reserve."""
    out = [("size", "four-bar", "--no-motor", "--width-ratio", r) for r in (*MAGNITUDES, "0.1", "10", "10.0001")]
    lives = ("1e300 h", "1e-300 h", "20000 ч", "20000", "20000 rpm", "x h", "nan h", "-5 h", "1e400 h", "")
    out += [("size", "four-bar", "--no-motor", "--life", life) for life in lives]
    speeds = ("1234 rpm", "1e300 rpm", "0 rpm", "1500 kg", "1500", "nan rpm", "1500 об/мин")
    out += [("size", "double-cut-shears", "--synchronous", s) for s in speeds]
    out += [("size", "double-cut-shears", "--reserve", r) for r in ("0", "1.0001", "nan", "-1", "1e300")]
    out += [("size", "four-bar", "--no-motor", "--masses", m) for m in ("sized", "guess", "", "SIZED")]
    return [Case(f"size option {i}", argv) for i, argv in enumerate(out)]


def part_cases() -> list[Case]:
    """Pins, guides, sections and the main shaft of every magnitude and of parts that do not fit, checked and
    sized."""
    sections = [f"{{shape: round, d: {m}}}" for m in MAGNITUDES]
    sections += [
        "{shape: tube, d: 0.05, t: 0.025}",
        "{shape: tube, d: 0.05, t: 0.04}",
        "{shape: tube, d: 0.05}",
        "{shape: I, h: 0.05, b: 0.04, tw: 0.01, tf: 0.025}",
        "{shape: I, h: 0.05, b: 0.04, tw: 0.05, tf: 0.01}",
        "{shape: rectangle, b: 1e-300, h: 1e300}",
        "{shape: round, d: 0.05, t: 0.01}",
    ]
    files = [
        SHEARS.replace("    guide_F: 0.40\n", f"    guide_F: 0.40\n  sections: {{crank: {s}}}\n") for s in sections
    ]
    pin = "O1: {diameter: 0.16, width: 0.16}"
    files += [SHEARS.replace(pin, f"O1: {{diameter: {m}, width: {m}}}") for m in MAGNITUDES]
    files += [SHEARS.replace("guide_E: 0.40", f"guide_E: {m}") for m in MAGNITUDES]
    shafts = [f"{{spacing: {m}}}" for m in MAGNITUDES] + [f"{{spacing: 0.5, overhang: {m}}}" for m in MAGNITUDES]
    files += [SHEARS.replace("    guide_F: 0.40\n", f"    guide_F: 0.40\n  shaft: {sh}\n") for sh in shafts]
    out = []
    for i, body in enumerate(files):
        command = ("check", "{dir}/m.yaml") if i % 2 else ("size", "{dir}/m.yaml", "--no-motor", "--json")
        out.append(Case(f"size part {i}", command, {"m.yaml": body}))
    return out


def element_cases() -> list[Case]:
    """Springs of negative, zero and huge free lengths and preloads, and more force elements than the bound."""
    base = text("four-bar") + "\nloads:\n"
    spring = "  s{}: {{type: spring, between: [O4, coupler.M], stiffness: 100 N/m, {}}}\n"
    fields = [f"free_length: {m}" for m in ("-20", "0", "-1e300", "1e300")]
    fields += [f"preload: {m} N" for m in ("1e6", "-1e6", "43", "0")]
    out = [
        Case(f"size spring {i}", ("forces", "{dir}/m.yaml", "--steps", "12"), {"m.yaml": base + spring.format(0, f)})
        for i, f in enumerate(fields)
    ]
    many = base + "".join(spring.format(i, "free_length: 200") for i in range(2000))
    machine = "\nmachine:\n  motor: {type: constant, torque: 10 N*m}\n"
    for n, body in (
        ("2000", many + machine),
        ("bound", base + "".join(spring.format(i, "free_length: 200") for i in range(MAX_LOADS + 1)) + machine),
    ):
        out.append(Case(f"size springs {n}", ("dynamics", "{dir}/m.yaml"), {"m.yaml": body}))
    return out


def catalogue_cases() -> list[Case]:
    """Catalogues that are devices or folders, empty, huge, past their rows, or all invalid."""
    row = "m{},0.1,1500,1400,2,2.2,0.001,5\n"
    files: dict[str, str | bytes] = {
        "empty.csv": "",
        "heading.csv": HEADING,
        "bad.csv": HEADING + "x,a,b,c,d,e,f,g\n" * 60_000,
        "rows.csv": HEADING + "".join(row.format(i) for i in range(MAX_CATALOGUE_ROWS + 1)),
        "huge.csv": b"#" * (MAX_CATALOGUE_BYTES + 1),
        "binary.csv": b"\xff\xfe\x00" * 100,
        "units.csv": HEADING.replace("[kW]", "[kg]") + row.format(0),
    }
    paths = ["/dev/zero", "/dev/null", "/dev/urandom", "{dir}", "{dir}/none.csv", *(f"{{dir}}/{n}" for n in files)]
    return [Case(f"size catalogue {i}", ("size", "four-bar", "--catalogue", p), files) for i, p in enumerate(paths)]


def destination_cases() -> list[Case]:
    """``--write`` destinations that cannot be written: under a file, a folder, a device, not a .yaml."""
    files: dict[str, str | bytes] = {"f": "a file\n"}
    outs = ("{dir}/f/m.yaml", "{dir}", "{dir}/", "/dev/null", "{dir}/m.txt", "{dir}/f/g/h.yaml")
    return [Case(f"size write {i}", ("size", "double-cut-shears", "--write", o), files) for i, o in enumerate(outs)]


def cases() -> list[Case]:
    """Every hostile case of sizing."""
    return option_cases() + part_cases() + element_cases() + catalogue_cases() + destination_cases()
