import math

import pytest

from linkwork.units import UnitParseError, parse_quantity

MM = {"length": "mm", "mass": "kg", "time": "s", "force": "N", "angle": "deg"}


@pytest.mark.parametrize(
    "value, kind, declared, si",
    [
        ("100 mm", "length", None, 0.1),
        (100, "length", MM, 0.1),
        ("2 in", "length", None, 0.0508),
        ("30 rpm", "angular_speed", None, math.pi),
        ("1 rev/s", "angular_speed", None, 2 * math.pi),
        (30, "angular_speed", None, math.radians(30)),  # deg/s by default
        ("12 deg", "angle", None, 12 * math.pi / 180),
        ("0.5 rad", "angle", None, 0.5),
        (90, "angle", None, math.pi / 2),
        ("250 kN", "force", None, 250e3),
        ("3 t", "mass", None, 3000.0),
        (2.0e6, "inertia", MM, 2.0),  # kg mm^2
        ("9.81 m/s^2", "acceleration", None, 9.81),
        ("1.5", "length", MM, 1.5e-3),
    ],
)
def test_quantities_convert_to_si(value, kind, declared, si):
    assert parse_quantity(value, kind, declared) == pytest.approx(si, rel=1e-12)


@pytest.mark.parametrize(
    "value, kind, message",
    [
        ("12 kg", "length", 'expected a length, got "12 kg"'),
        ("5 m", "mass", 'expected a mass, got "5 m"'),
        ("3 furlongz", "length", 'expected a length, got "3 furlongz" (unknown unit "furlongz")'),
        ("mm", "length", 'expected a length, got "mm" (write a number and a unit, e.g. "100 mm")'),
        ("10**10**9 mm", "length", 'expected a length, got "10**10**9 mm" (write a number and a unit, e.g. "100 mm")'),
        ("3 mm*deg", "length", 'expected a length, got "3 mm*deg" (an angle unit in it)'),
        ("90 percent", "angle", 'expected an angle, got "90 percent" (use deg, rad or rev)'),
        (10**400, "length", "expected a length, got a number too large to use"),
        ("1e400 mm", "length", 'expected a length, got "1e400 mm"'),
        ("0.5 Hz", "angular_speed", 'expected an angular speed, got "0.5 Hz" (write rpm, rev/s or rad/s, not Hz)'),
        (True, "length", "expected a length, got true"),
        ([1, 2], "length", "expected a length, got a list"),
        (None, "mass", "expected a mass, got nothing"),
    ],
)
def test_bad_quantities_say_what_was_expected(value, kind, message):
    with pytest.raises(UnitParseError) as err:
        parse_quantity(value, kind)
    assert str(err.value) == message
