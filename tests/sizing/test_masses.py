"""The links' masses from their sized sections, to a fixed point: each bar's mass is the steel of the section the
loads of those masses ask (rho A L, by hand from the table's diameter), no slenderer than L/d = 20."""

from __future__ import annotations

import math

import pytest

import linkwork as lw
from commandline import linkwork
from linkwork.sizing.masses import AGREE, SLENDER, STEEL


def test_the_sized_masses_are_the_steel_of_the_sections_their_loads_ask():
    sized = lw.size("double-cut-shears", motor=False, masses="sized")
    assert sized.masses is not None and sized.masses.converged
    for bar in sized.links.bars:
        least = math.pi * (bar.length / SLENDER) ** 2 / 4
        expected = STEEL * max(bar.area, least) * bar.length
        assert sized.masses.masses[bar.link] == pytest.approx(expected, rel=3 * AGREE), bar.link
    crank = next(b for b in sized.links.bars if b.link == "crank")  # d from the table: rho pi d^2 / 4 L by hand
    d = float(crank.section.split()[3]) / 1e3
    assert sized.masses.masses["crank"] == pytest.approx(STEEL * math.pi * d**2 / 4 * 0.1, rel=1e-2)
    # the knives slide: steel blocks carrying their pins (the file gave 300 kg each), nothing kept
    assert sized.masses.blocks == ("knife_upper", "knife_lower") and sized.masses.kept == ()
    assert "to a fixed point" in sized.inputs["masses"]


def test_a_mechanism_loaded_by_its_own_masses_stops_at_the_slenderest_bar():
    sized = lw.size("four-bar", motor=False, masses="sized")
    for bar in sized.links.bars:
        assert sized.masses.masses[bar.link] == pytest.approx(
            STEEL * math.pi * (bar.length / SLENDER) ** 2 / 4 * bar.length, rel=1e-9
        )


def test_an_unknown_masses_option_is_refused():
    result = linkwork("size", "four-bar", "--no-motor", "--masses", "guess")
    assert result.returncode == 2 and '--masses: "file" or "sized", got "guess"' in result.stderr


def test_write_puts_the_sized_masses_and_the_motor_into_the_file(tmp_path):
    out = tmp_path / "sized.yaml"
    result = linkwork("size", "four-bar", "--masses", "sized", "--write", str(out), "--json")
    assert result.returncode == 0, result.stderr
    import json

    masses = json.loads(result.stdout)["masses_kg"]
    file = lw.load(out)
    written = lw.compile(file)
    for name, mass in masses.items():
        assert float(written.link_mass[list(written.link_names).index(name)]) == pytest.approx(mass, rel=1e-9)
    assert file.machine is not None and file.machine.motor.type == "induction"
