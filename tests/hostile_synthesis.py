"""Hostile requests to ``linkwork synthesize``: every option of every kind at and past its bounds.

Each kind starts from a request it meets (:data:`FEASIBLE`); one option at a time is replaced by each value of
its class (:data:`VALUES`: zero, negative, tiny and huge magnitudes, non-finite ones, a bare number where a unit is
due, a unit of another kind, angles at 0 and 90 deg and just inside them, time ratios at 1, just over it and far
above).  Each case must end as every hostile case does (:func:`hostile.problems`: exit 0, or 2 with one short
message, no traceback), and a refusal leaves no file.  The cases are command lines of :class:`hostile.Case`,
listed by :func:`synthesis_argvs` for :func:`hostile.option_cases`.
"""

from __future__ import annotations

#: A request each kind meets, option -> value (the option replaced in a case is left out of it).
FEASIBLE: dict[str, dict[str, str]] = {
    "slider-crank": {"--stroke": "400mm", "--time-ratio": "1.2"},
    "crank-rocker": {"--swing": "45deg", "--time-ratio": "1.2", "--rocker": "250mm"},
    "slotted-lever": {"--stroke": "400mm", "--time-ratio": "1.5"},
    "toggle-press": {"--stroke": "40mm", "--force": "100kN", "--before": "2mm", "--torque": "8kN*m"},
    "double-cut-shears": {
        "--upper-stroke": "150mm",
        "--lower-stroke": "110mm",
        "--time-ratio": "1.05",
        "--overlap": "15mm",
    },
}

#: The options each kind takes beside its feasible request's, and their class.
OPTIONS: dict[str, dict[str, str]] = {
    "slider-crank": {
        "--stroke": "length",
        "--time-ratio": "ratio",
        "--rod-ratio": "ratio",
        "--offset": "length",
        "--max-pressure-angle": "angle",
        "--min-transmission-angle": "angle",
        "--force": "force",
        "--working": "length",
        "--speed": "speed",
        "--section": "section",
    },
    "crank-rocker": {
        "--swing": "angle",
        "--time-ratio": "ratio",
        "--rocker": "length",
        "--min-transmission-angle": "angle",
        "--speed": "speed",
    },
    "slotted-lever": {
        "--stroke": "length",
        "--time-ratio": "ratio",
        "--frame": "length",
        "--crank": "length",
        "--rod": "length",
        "--max-pressure-angle": "angle",
        "--min-transmission-angle": "angle",
        "--speed": "speed",
    },
    "toggle-press": {
        "--stroke": "length",
        "--force": "force",
        "--before": "length",
        "--torque": "moment",
        "--swing": "angle",
        "--time-ratio": "ratio",
        "--min-transmission-angle": "angle",
        "--speed": "speed",
    },
    "double-cut-shears": {
        "--upper-stroke": "length",
        "--lower-stroke": "length",
        "--time-ratio": "ratio",
        "--overlap": "length",
        "--opening": "length",
        "--crank": "length",
        "--min-transmission-angle": "angle",
        "--speed": "speed",
    },
}

#: The values of each class: at and past its bounds.
VALUES: dict[str, tuple[str, ...]] = {
    "length": ("0 mm", "-1 mm", "1e-300 mm", "1e300 mm", "nan mm", "inf mm", "160", "1 kg", "x"),
    "ratio": ("1", "1.0000000001", "1.001", "0", "-1", "1e300", "nan", "inf", "x"),
    "angle": ("0 deg", "1e-300 deg", "1e-12 deg", "89.999999999deg", "90deg", "-5deg", "1e300 deg", "45", "nan deg"),
    "force": ("0 N", "-1 kN", "1e-300 N", "1e300 N", "inf N", "100"),
    "moment": ("0 N*m", "-1 N*m", "1e-300 N*m", "1e300 N*m", "inf N*m", "8000"),
    "speed": ("-30 rpm", "0 rpm", "1e300 rpm", "nan rpm", "30", "30 kg"),
    "section": ("0mm x 20mm", "-40mm x 20mm", "1e300mm x 20mm", "1000m x 1000m", "40mm", "nan mm x 20 mm"),
}

#: Values whose cases the shears would solve in full (their continuation takes tens of seconds): left to the
#: requests the shears' own tests make.
SHEARS_SOLVED = {"1.0000000001", "1.001", "1", "1e-300 deg", "1e-12 deg", "89.999999999deg"}


def synthesis_argvs() -> list[tuple[str, ...]]:
    """Every kind's every option at and past its bounds, one option replaced at a time (the rest of the kind's
    feasible request kept), each writing ``{dir}/synthesised.yaml``."""
    out: list[tuple[str, ...]] = []
    for kind, options in OPTIONS.items():
        for option, cls in options.items():
            for value in VALUES[cls]:
                if kind == "double-cut-shears" and value in SHEARS_SOLVED:
                    continue
                rest = [x for name, v in FEASIBLE[kind].items() if name != option for x in (name, v)]
                out.append(("synthesize", kind, *rest, option, value, "--out", "{dir}/synthesised.yaml"))
    return out
