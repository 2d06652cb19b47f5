import math

import pytest

from linkwork.errors import UnitParseError
from linkwork.units import parse_quantity

MM = {"length": "mm", "mass": "kg", "time": "s", "force": "N", "angle": "deg"}


@pytest.mark.parametrize(
    "value, kind, declared, si",
    [
        ("100 mm", "length", None, 0.1),
        (100, "length", MM, 0.1),
        ("2 in", "length", None, 0.0508),
        ("30 rpm", "angular_speed", None, math.pi),
        ("1 rev/s", "angular_speed", None, 2 * math.pi),
        (30, "angular_speed", {"angle": "rad"}, 30.0),  # rad/s where angles are in rad and times in s
        (30, "angular_speed", {"angular_speed": "rpm"}, math.pi),  # a declared unit of its kind
        ("12 deg", "angle", None, 12 * math.pi / 180),
        ("0.5 rad", "angle", None, 0.5),
        (90, "angle", None, math.pi / 2),
        ("250 kN", "force", None, 250e3),
        ("3 t", "mass", None, 3000.0),
        (2.0e6, "inertia", {**MM, "inertia": "kg*mm^2"}, 2.0),
        (2.0, "inertia", None, 2.0),  # kg m^2 where lengths and masses are in m and kg
        ("2 kg*m^2", "inertia", MM, 2.0),
        (0, "inertia", MM, 0.0),  # zero in any unit
        (5, "moment", {"force": "kN", "moment": "kN*m"}, 5000.0),
        (500, "force", MM, 500.0),  # declared
        (7, "power", None, 7.0),
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


MM_ONLY = {"length": "mm"}


@pytest.mark.parametrize(
    "value, kind, declared, why, would",
    [
        # the three: 2 kg mm^2 = 2e-6 kg m^2, 1000 N mm = 1 N m, 60 deg/s = pi/3 rad/s
        (2, "inertia", MM_ONLY, "where lengths are in mm", '"2 kg*mm^2" (= 2e-06 kg*m^2)'),
        (1000, "moment", MM_ONLY, "where lengths are in mm", '"1000 N*mm" (= 1 N*m)'),
        (60, "angular_speed", MM_ONLY, "where angles are in deg", f'"60 deg/s" (= {math.pi / 3:.6g} rad/s)'),
        (60, "angular_speed", None, "where angles are in deg", '"60 rpm" or "60 deg/s"'),
        (9.81, "acceleration", MM_ONLY, "where lengths are in mm", '"9.81 mm/s^2" (= 0.00981 m/s^2)'),
        (5, "moment", {"force": "kN"}, "where forces are in kN", '"5 kN*m" (= 5000 N*m)'),
        (500, "force", MM_ONLY, "where lengths are in mm", 'e.g. "500 N", or'),
        (3, "speed", {"time": "min"}, "where times are in min", '"3 m/min" (= 0.05 m/s)'),
        (2, "inertia", {"mass": "g", "length": "cm"}, "where masses are in g and lengths are in cm", "(= 2e-07"),
    ],
)
def test_a_bare_derived_quantity_needs_its_unit_where_the_file_units_are_not_si(value, kind, declared, why, would):
    """A bare number is never read in a unit built from non-SI base units: the message says what it would
    have been (the hand-converted values above) and how to write it."""
    with pytest.raises(UnitParseError) as err:
        parse_quantity(value, kind, declared)
    message = str(err.value)
    assert message.startswith(f"a bare {value} is not read as ") and why in message, message
    assert would in message and f"units: {{{kind}: " in message


@pytest.mark.parametrize(
    "kind, declared, si, shown",
    [
        ("length", MM_ONLY, 0.1234, 123.4),
        ("inertia", MM_ONLY, 0.0125, "0.0125 kg*m^2"),  # a bare one would need its unit
        ("inertia", {"length": "mm", "inertia": "kg*mm^2"}, 0.0125, 12500.0),
        ("inertia", None, 0.0125, 0.0125),
        ("angular_speed", None, math.pi, "3.141592654 rad/s"),
    ],
)
def test_a_value_is_written_as_the_file_reads_it_back(kind, declared, si, shown):
    from linkwork.units import written

    out = written(si, kind, declared or {})
    assert out == pytest.approx(shown, rel=1e-12) if isinstance(shown, float) else out == shown
    assert parse_quantity(out, kind, declared) == pytest.approx(si, rel=1e-9)


def test_the_common_units_read_without_pint_are_pints_to_the_bit():
    """The table that spares the common units pint's registry holds pint's own values, exactly."""
    from linkwork.units import COMMON_UNITS, _pint_factor

    for kind, units in COMMON_UNITS.items():
        for unit, value in units.items():
            assert value == _pint_factor(unit, kind), (unit, kind)


def test_an_angle_is_shown_in_0_to_360_after_rounding():
    """Round-off below the shown digits never reads as a whole turn: -1e-9 rad and 2 pi - 1e-9 rad show 0.0,
    not 360.0; other angles are their degrees wrapped into [0, 360)."""
    import math

    import numpy as np

    from linkwork.units import turn_deg

    assert f"{turn_deg(-1e-9):.1f}" == "0.0"
    assert f"{turn_deg(2 * math.pi - 1e-9):.1f}" == "0.0"
    assert f"{turn_deg(math.radians(359.96)):.1f}" == "0.0"
    assert f"{turn_deg(math.radians(359.94)):.1f}" == "359.9"
    assert f"{turn_deg(-1e-9, 3):.3f}" == "0.000"
    assert turn_deg(math.radians(-90.0)) == 270.0
    shown = turn_deg(np.radians([-720.25, 30.0, 405.0, -1e-7]))
    assert np.allclose(shown, [359.8, 30.0, 45.0, 0.0], rtol=0, atol=1e-9)


@pytest.mark.parametrize("text", ["1 m^9^9^9", "1 m**9**9**9", "1 mm ^ 2 ^ 9", "2 kg*m^-9^9"])
def test_a_power_of_a_power_is_refused_before_it_is_worked_out(text):
    """m^9^9^9 is m^(9^387420489): refused at once (well under a second) instead of evaluated."""
    import time

    start = time.perf_counter()
    with pytest.raises(UnitParseError, match="not a power of a power"):
        parse_quantity(text, "length" if "kg" not in text else "inertia")
    assert time.perf_counter() - start < 1.0
    assert parse_quantity("2 kg*m^2", "inertia") == 2.0 and parse_quantity("3 m^3/m^2", "length") == 3.0
