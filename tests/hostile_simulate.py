"""Hostile cases of the run in time and of a file's requirements, for :mod:`hostile`'s option cases.

Three generators, each a class of input:

- :func:`simulate_options`: ``linkwork simulate`` with ``--until``, ``--angle``, ``--speed`` and ``--samples`` at and
  past every bound (``limits.MAX_RUN_TIME``, ``MAX_TURNS``, ``MAX_MAGNITUDE``), without units or of the wrong kind,
  and force elements stiff enough to pass the bound on a run's work (refused before the work);
- :func:`requirements_of_another_kind`: a bundled example carrying the requirements of each kind, under its own
  kind's name and under another's (the shears' on a slider-crank, a crank-rocker's on the shears...);
- :func:`non_finite_requirements`: every requirement of every kind as ``.inf``, ``-.inf``, ``.nan``, a
  quantity's ``inf mm`` and a number past a double's range, drawn from a seeded generator.

Each case must end in exit code 0, or 2 with one message and no traceback, within the suite's time bound.
"""

from __future__ import annotations

import functools
import random

from hostile import Case
from linkwork.examples import text
from linkwork.limits import MAX_RUN_TIME, MAX_TURNS
from linkwork.spec.requirements import KINDS

#: A valid set of requirements of each kind, in a file's spelling.
REQUIREMENTS: dict[str, dict[str, str]] = {
    "slider-crank": {"stroke": "400 mm", "time_ratio": "1.3", "max_pressure_angle": "60 deg"},
    "crank-rocker": {"swing": "45 deg", "time_ratio": "1.2", "rocker": "300 mm"},
    "slotted-lever": {"stroke": "400 mm", "time_ratio": "1.5"},
    "toggle-press": {"stroke": "20 mm", "force": "100 kN", "before": "5 mm", "torque": "5000 N*m"},
    "double-cut-shears": {"upper_stroke": "200 mm", "lower_stroke": "200 mm", "time_ratio": "1.1", "overlap": "30 mm"},
}

#: A bundled example of each structure the requirements are measured on.
BASES = {"slider-crank": "shears-slider-crank", "crank-rocker": "four-bar", "double-cut-shears": "double-cut-shears"}

#: A slider-crank with a spring (and a damper) too stiff to follow for long, as a file.
STIFF = """\
name: stiff
units: {length: m, angle: rad}
gravity: 0
frame: {points: {O: [0, 0], S: [0.7, 0]}}
links:
  crank: {ends: [O, A], length: 0.1, mass: 1.5, inertia: 0.004 kg*m^2}
  rod: {ends: [A, B], length: 0.35, mass: 2.0}
  slider: {points: {B: [0, 0]}, mass: 3.0}
joints:
  O: {type: revolute, links: [frame, crank]}
  A: {type: revolute, links: [crank, rod]}
  B: {type: revolute, links: [rod, slider]}
  guide: {type: prismatic, links: [frame, slider], point: B, through: O, axis: 0}
drives: [{joint: O, angle: 0.3}]
hints: {B: [0.4356, 0]}
loads:
  s: {type: spring, between: [slider.B, S], stiffness: STIFFNESS N/m, free_length: 0.35}
  d: {type: damper, between: [slider.B, S], damping: DAMPING N*s/m}
"""


def cases() -> list[Case]:
    """Every case of the three generators, named by its class and number."""
    out = []
    for what, made in (
        ("simulate", simulate_options()),
        ("requirements-kind", requirements_of_another_kind()),
        ("requirements-finite", non_finite_requirements()),
    ):
        out += [Case(f"{what} {i}", argv, files) for i, (argv, files) in enumerate(made)]
    return out


Made = list[tuple[tuple[str, ...], dict[str, str | bytes]]]


@functools.cache
def simulate_options() -> Made:
    """``simulate`` with its options at and past each bound; the flagship example (held in the cut from its
    assembly angle, so a run of the longest length ends at once) and a file of stiff force elements."""
    run = ("simulate", "double-cut-shears")
    longest = f"{MAX_RUN_TIME:g} s"
    past = f"{MAX_RUN_TIME * 1.000001:.9g} s"
    untils = [longest, past, "1e9 s", "1 h", "100 years", "0 s", "-1 s", "nan s", "inf s", "1e-300 s", "1e400 s"]
    untils += ["30", "30 kg", "", "x" * 5000, "30 ms" + " " * 200]
    out: Made = [((*run, "--until", u), {}) for u in untils]
    turns = 360 * MAX_TURNS
    for angle in (f"{turns} deg", f"{turns + 1} deg", f"-{turns + 1} deg", "1e308 deg", "nan deg", "30 mm", "30"):
        out.append(((*run, "--until", "1 ms", "--angle", angle), {}))
    for speed in ("1e9 rad/s", "1.0001e9 rad/s", "-1e9 rad/s", "nan rpm", "inf rpm", "30 kg", "30", "-30 rpm"):
        out.append(((*run, "--until", "1 ms", "--speed", speed), {}))
    for samples in ("0", "1", "2", "100000", "100001", "1" + "0" * 30, "x"):
        out.append(((*run, "--until", "1 ms", "--samples", samples), {}))
    for stiffness, damping, until in (("1e9", "0", "200 ms"), ("1e9", "0", "1 ms"), ("1", "1e9", "200 ms")):
        body = STIFF.replace("STIFFNESS", stiffness).replace("DAMPING", damping)
        out.append((("simulate", "{dir}/stiff.yaml", "--until", until, "--speed", "5 rad/s"), {"stiff.yaml": body}))
    out.append((("simulate", "four-bar", "--until", "10 ms", "--speed", "30 rpm"), {}))  # no masses: refused
    return out


def _with(base: str, kind: str, given: dict[str, str]) -> str:
    """The bundled example ``base`` carrying ``requirements:`` of ``kind`` with ``given``."""
    lines = [f"  kind: {kind}"] + [f"  {name}: {value}" for name, value in given.items()]
    return text(base).rstrip("\n") + "\nrequirements:\n" + "\n".join(lines) + "\n"


@functools.cache
def requirements_of_another_kind() -> Made:
    """Each structure's example with each kind's requirements, named as that kind and as its own; ``check`` on
    each, and ``analyze`` on each but the example with its own kind's requirements (which ``check`` accepts)."""
    out: Made = []
    for own, base in BASES.items():
        for kind, given in REQUIREMENTS.items():
            for label in dict.fromkeys((kind, own)):
                body = _with(base, label, given)
                out.append((("check", "{dir}/req.yaml"), {"req.yaml": body}))
                if label != own or kind != own:  # refused: analyze as check (an accepted one: a report, no animation)
                    command = ("analyze", "{dir}/req.yaml", "--out", "{dir}/r", "--steps", "36", "--no-animation")
                    out.append((command, {"req.yaml": body}))
    return out


@functools.cache
def non_finite_requirements(seed: int = 39, count: int = 40) -> Made:
    """``count`` cases drawn with ``seed``: a requirement of a kind, on that kind's example (or the slider-crank's),
    given a non-finite or overflowing value; ``check`` or ``analyze`` reads it."""
    rng = random.Random(seed)
    values = [".inf", "-.inf", ".nan", "1e400", '"inf mm"', '"nan deg"', '"-inf N"', '"1e400 mm"', "1e308"]
    out: Made = []
    for _ in range(count):
        kind = rng.choice(list(KINDS))
        given = dict(REQUIREMENTS[kind])
        given[rng.choice(KINDS[kind])] = rng.choice(values)
        body = _with(BASES.get(kind, "shears-slider-crank"), kind, given)
        analyze = ("analyze", "{dir}/req.yaml", "--out", "{dir}/r", "--no-animation")
        command = rng.choice((("check", "{dir}/req.yaml"), analyze))
        out.append((command, {"req.yaml": body}))
    return out
