"""Named parameters: an override means exactly what the same edit of the file means.

Every case edits the bundled file by hand (ruamel, in the file's own units, nothing of linkwork's
parameter code involved), compiles it afresh and solves it; the four ways linkwork applies the same
overrides must give the same driving torque and foundation loads to 1e-9: variants of one compiled
mechanism (``lw.forces(variants=)``), the viewer's edit, a sweep's metrics and the file the optimiser
writes.
"""

from __future__ import annotations

import io
import math

import numpy as np
import pytest
from ruamel.yaml import YAML

import linkwork as lw
from linkwork.errors import ParameterError
from linkwork.examples import text
from linkwork.kinetostatics.peaks import foundation_peak, torque_peak
from linkwork.motion.analysis import zero_angle
from linkwork.motion.kinematic_analysis import cycle
from linkwork.spec.edit import write_text
from linkwork.structure.parameters import file_text
from linkwork.web.session import Viewer

STEPS = 360

#: (example, overrides in SI, the same edits of the file in its own units)
CASES = [
    ("four-bar", {"links.coupler.length": 0.38}, [(("links", "coupler", "length"), 380)]),
    (
        "four-bar",
        {"frame.points.O4.x": 0.32, "links.crank.mass": 1.4, "links.rocker.inertia": 0.012},
        [
            (("frame", "points", "O4", 0), 320),
            (("links", "crank", "mass"), 1.4),
            (("links", "rocker", "inertia"), "0.012 kg*m^2"),
        ],
    ),
    (
        "double-cut-shears",
        {
            "joints.guide_E.axis": math.radians(93),
            "frame.points.O1.y": 0.42,
            "links.rod.mass": 70.0,
            "links.rocker.points.C.x": 0.28,
            "links.crank.length": 0.105,
        },
        [
            (("joints", "guide_E", "axis"), "93 deg"),
            (("frame", "points", "O1", 1), 0.42),
            (("links", "rod", "mass"), 70),
            (("links", "rocker", "points", "C", 0), 0.28),
            (("links", "crank", "length"), 0.105),
        ],
    ),
    ("shears-slider-crank", {"joints.guide.axis": math.radians(100)}, [(("joints", "guide", "axis"), "100 deg")]),
    (
        "percussion-rocker",
        {"links.rocker.points.C.x": 0.2, "links.rocker.mass": 7.0},
        [(("links", "rocker", "points", "C", 0), 0.2), (("links", "rocker", "mass"), 7.0)],
    ),
]


def _write_file(mech, values, out):
    """The file of ``mech`` with ``values`` written in, written to ``out`` (what ``linkwork design --best`` writes)."""
    return write_text(file_text(mech, values), out)


def _edited_by_hand(name, edits):
    yaml = YAML()
    data = yaml.load(text(name))
    for keys, value in edits:
        node = data
        for key in keys[:-1]:
            node = node[key]
        node[keys[-1]] = value
    buf = io.StringIO()
    yaml.dump(data, buf)
    return lw.compile(lw.loads(buf.getvalue(), file=f"{name}-edited.yaml"))


def _same(a, b, rel=1e-9):
    a, b = np.asarray(a), np.asarray(b)
    assert np.isfinite(b).all()
    scale = max(float(np.max(np.abs(b))), 1e-300)
    np.testing.assert_allclose(a, b, rtol=0, atol=rel * scale)


_IDS = [f"{c[0]}-{'+'.join(c[1])}" for c in CASES]


@pytest.mark.parametrize("name, overrides, edits", CASES, ids=_IDS)
def test_overrides_mean_what_the_edited_file_means(name, overrides, edits, tmp_path):
    ref = lw.forces(_edited_by_hand(name, edits), steps=STEPS)
    mech = lw.compile(name)
    # variants of one compiled mechanism
    var = lw.forces(mech, steps=STEPS, variants={k: [v] for k, v in overrides.items()})
    _same(var.driving_torque[0], ref.driving_torque)
    _same(var.foundation[0], ref.foundation)
    # the viewer's edit: a variant of the compiled mechanism, as the page asks for it
    # (its cycle numbered from the file's position 0, as the report numbers it)
    viewed = Viewer(mech).solve(overrides, steps=STEPS).forces
    by_hand = _edited_by_hand(name, edits)
    at = lw.forces(by_hand, cycle(by_hand, STEPS, start=zero_angle(mech)))
    _same(viewed.driving_torque[0], at.driving_torque)
    _same(viewed.foundation[0, :, :2], at.foundation[..., :2])
    # the file the optimiser writes, read back
    written = lw.forces(lw.load(_write_file(mech, overrides, tmp_path / "best.yaml")), steps=STEPS)
    _same(written.driving_torque, ref.driving_torque)
    # a sweep's metrics
    vary = {k: (f"{v!r} {_unit(k)}", f"{v!r} {_unit(k)}", 1) for k, v in overrides.items()}
    t = lw.sweep(name, vary, ["peak_driving_torque", "peak_foundation_force"], steps=STEPS)
    assert t["peak_driving_torque"][0] == pytest.approx(abs(torque_peak(ref).value[0]), rel=1e-9)
    assert t["peak_foundation_force"][0] == pytest.approx(foundation_peak(ref).value[0], rel=1e-9)


def _unit(path):
    return {"length": "m", "angle": "rad", "mass": "kg", "inertia": "kg*m^2"}[
        "angle"
        if path.endswith("axis")
        else "mass"
        if path.endswith("mass")
        else "inertia"
        if path.endswith("inertia")
        else "length"
    ]


def test_the_four_bar_with_a_longer_coupler_has_the_edited_files_peak_torque():
    """The case of the issue: coupler 0.38 m, the peak driving torque of a sweep that of the edited file (a
    sweep once kept the old coupler's centre of mass and inertia, 1.5 % off)."""
    ref = lw.forces(_edited_by_hand("four-bar", [(("links", "coupler", "length"), 380)]), steps=STEPS)
    t = lw.sweep("four-bar", {"links.coupler.length": ("380", "380", 1)}, ["peak_driving_torque"], steps=STEPS)
    assert t["peak_driving_torque"][0] == pytest.approx(abs(torque_peak(ref).value[0]), rel=1e-9)
    assert t["peak_driving_torque"][0] >= np.max(np.abs(ref.driving_torque))  # refined between the samples


def test_default_mass_properties_follow_the_geometry_and_given_ones_stay():
    """The four-bar's coupler (no com, no inertia: the middle of its ends and m L^2/12) and the double-cut
    shears' rod (inertia given: stays) against the rule worked by hand."""
    kin = lw.kinematics("four-bar", [1.0], variants={"links.coupler.length": [0.4], "links.coupler.mass": [3.0]})
    ms = kin.mass_properties
    i = kin.mechanism.link_names.index("coupler")
    np.testing.assert_allclose(ms.com[0, i], [0.4 / 2, 0.0], rtol=0, atol=1e-15)  # the middle of A B, not M
    assert ms.inertia[0, i] == pytest.approx(3.0 * 0.4**2 / 12, rel=1e-12)
    kin = lw.kinematics("double-cut-shears", [1.0], variants={"links.rod.length": [0.45], "links.rod.mass": [80.0]})
    j = kin.mechanism.link_names.index("rod")
    assert kin.mass_properties.inertia[0, j] == pytest.approx(0.80, rel=1e-12)
    np.testing.assert_allclose(kin.mass_properties.com[0, j], [0.225, 0.0], rtol=1e-12)
    # the inertia given about a point (percussion rocker, 0.30 kg m^2 about O): J_C = J_O - m |OC|^2
    kin = lw.kinematics("percussion-rocker", [1.0], variants={"links.rocker.mass": [7.0]})
    r = kin.mechanism.link_names.index("rocker")
    assert kin.mass_properties.inertia[0, r] == pytest.approx(0.30 - 7.0 * (0.16**2 + 0.01**2), rel=1e-12)


def test_the_python_listing_and_the_command_line_listing_agree():
    """`linkwork parameters` and lw.parameters name the same parameters, masses and inertias included,
    and lw.kinematics accepts every one of them as a variant."""
    from commandline import linkwork

    out = linkwork("parameters", "double-cut-shears")
    assert out.returncode == 0, out.stderr
    listed = [line.split()[0] for line in out.stdout.splitlines()]
    params = lw.parameters("double-cut-shears")
    assert listed == list(params)
    assert "links.rod.mass" in params and "links.rocker.inertia" in params
    kin = lw.kinematics("double-cut-shears", [1.0], variants={name: [value] for name, value in params.items()})
    plain = lw.kinematics("double-cut-shears", [1.0])
    np.testing.assert_allclose(kin.position("E")[0], plain.position("E"), atol=1e-12)


def test_an_unknown_parameter_or_a_bad_value_is_named():
    with pytest.raises(ParameterError, match='no parameter "links.rod.mas" .did you mean "links.rod.mass"'):
        lw.kinematics("double-cut-shears", [1.0], variants={"links.rod.mas": [1.0]})
    with pytest.raises(ParameterError, match="links.rod.length: expected a positive length"):
        _write_file(lw.compile("double-cut-shears"), {"links.rod.length": -1.0}, "/nonexistent/x.yaml")


def test_a_written_file_keeps_the_units_each_value_was_written_in(tmp_path):
    """Bare numbers stay bare in the file's units (mm), a value with a unit keeps its unit, a value the
    file leaves out is written with its SI unit; the comments stay."""
    source = tmp_path / "four-bar.yaml"
    source.write_text(text("four-bar").replace("length: 250", 'length: "0.25 m"  # rocker'))
    mech = lw.compile(source)
    out = _write_file(
        mech,
        {"links.crank.length": 0.105, "links.rocker.length": 0.26, "links.coupler.inertia": 0.03},
        tmp_path / "x.yaml",
    )
    data = YAML(typ="safe").load(out.read_text())
    assert data["links"]["crank"]["length"] == pytest.approx(105)
    assert data["links"]["rocker"]["length"] == "0.26 m"
    assert data["links"]["coupler"]["inertia"] == "0.03 kg*m^2"
    assert "# coupler point" in out.read_text() and "# rocker" in out.read_text()
    again = lw.parameters(out)
    assert again["links.rocker.length"] == pytest.approx(0.26, rel=1e-12)
    assert again["links.coupler.inertia"] == pytest.approx(0.03, rel=1e-12)


def test_what_depends_on_a_mechanism_alone_is_found_once_and_freed_with_it():
    """``per_mechanism``: one call of the maker per mechanism (told apart by identity, not equality: two
    compilations of one file are two mechanisms), its result shared and read-only where it is a mapping of
    parameters, and forgotten once the mechanism is freed."""
    import gc
    import weakref

    from linkwork.structure.model import per_mechanism
    from linkwork.structure.parameters import parameters_by_name

    calls = []

    @per_mechanism
    def links(mech):
        calls.append(1)
        return len(mech.link_names)

    a, b = lw.compile("four-bar"), lw.compile("four-bar")
    assert [links(a), links(a), links(b)] == [4, 4, 4] and len(calls) == 2
    known = parameters_by_name(a)
    assert parameters_by_name(a) is known and parameters_by_name(b) is not known
    with pytest.raises(TypeError):
        known["links.crank.length"] = None  # type: ignore[index]
    gone = weakref.ref(a)
    del a, known
    gc.collect()
    assert gone() is None
    assert links(lw.compile("four-bar")) == 4 and len(calls) == 3


def _uniform_rods_power_balance(kin, rods):
    """The driving torque of a mechanism of uniform rods ``(link, end, end, mass)`` driven at a constant
    speed with no loads, by the power balance, each rod's centre of mass the middle of its ends:
    T w = sum(m a_c . v_c + J eps w + m g v_cy)."""
    g = kin.mechanism.gravity
    power = 0.0
    for link, p, q, m in rods:
        v = (kin.velocity(p) + kin.velocity(q)) / 2
        a = (kin.acceleration(p) + kin.acceleration(q)) / 2
        length = np.linalg.norm(kin.position(q) - kin.position(p), axis=-1)
        j = m * length**2 / 12
        power = power + m * np.sum(a * v, -1) + j * kin.epsilon(link) * kin.omega(link) + m * g * v[:, 1]
    return power / kin.omega("crank")


def test_a_marker_does_not_move_a_rods_centre_of_mass():
    """The bundled four-bar's coupler carries the marker M (175, 80) mm: a marker is not material, so the
    coupler's default centre of mass is the middle of its ends, and its driving torque that of the power
    balance of three uniform rods, the same without M; a centre of mass the file gives stays."""
    src = text("four-bar")
    marker = "    points: {M: [175, 80]}  # coupler point\n"
    assert marker in src
    mech = lw.compile(lw.loads(src))
    i = mech.link_names.index("coupler")
    np.testing.assert_allclose(mech.link_com[i], [0.175, 0.0], rtol=0, atol=1e-15)
    f = lw.forces(mech, steps=90)
    rods = [("crank", "O2", "A", 1.0), ("coupler", "A", "B", 2.5), ("rocker", "O4", "B", 1.8)]
    np.testing.assert_allclose(f.driving_torque, _uniform_rods_power_balance(f.kinematics, rods), rtol=0, atol=1e-10)
    bare = lw.forces(lw.compile(lw.loads(src.replace(marker, ""))), steps=90)
    np.testing.assert_allclose(bare.driving_torque, f.driving_torque, rtol=0, atol=1e-12)
    given = lw.compile(lw.loads(src.replace(marker, marker + "    com: M\n")))
    np.testing.assert_allclose(given.link_com[i], [0.175, 0.08], rtol=0, atol=1e-15)


def test_a_file_written_from_an_example_edits_the_example_not_a_file_of_that_name_here(tmp_path, monkeypatch):
    """The bundled four-bar solved in a folder that holds a ``four-bar.yaml`` of the user's own (a coupler of
    360 mm): the written file is the example (coupler 350 mm, its comment) with the value written in."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "four-bar.yaml").write_text(text("four-bar").replace("length: 350", "length: 360"))
    out = _write_file(lw.compile("four-bar"), {"links.crank.length": 0.105}, tmp_path / "best.yaml")
    again = lw.parameters(out)
    assert again["links.coupler.length"] == pytest.approx(0.35, rel=1e-12)
    assert again["links.crank.length"] == pytest.approx(0.105, rel=1e-12)
    assert "# coupler point" in out.read_text()


def test_a_file_written_from_one_changed_on_disk_since_it_was_read_edits_what_was_read(tmp_path):
    source = tmp_path / "m.yaml"
    source.write_text(text("four-bar"))
    mech = lw.compile(source)
    source.write_text(text("four-bar").replace("length: 350", "length: 360"))
    assert lw.parameters(_write_file(mech, {"links.crank.length": 0.105}, tmp_path / "x.yaml"))[
        "links.coupler.length"
    ] == pytest.approx(0.35, rel=1e-12)


_ROCKER = "    ends: [O4, B]\n    length: 250\n"

#: The four-bar with the rocker merging the crank's mapping (its mass inherited) and a coupler point that is
#: an alias of the frame's O4.
SHARED = (
    text("four-bar")
    .replace("  crank:\n", "  crank: &crank\n")
    .replace(_ROCKER + "    mass: 1.8\n", "    <<: *crank\n" + _ROCKER)
    .replace("O4: [300, 0]", "O4: &o4 [300, 0]")
    .replace("points: {M: [175, 80]}", "points: {M: *o4}")
)


@pytest.mark.parametrize(
    "values",
    [
        {"links.crank.mass": 3.0},
        {"links.rocker.mass": 4.0},
        {"frame.points.O4.x": 0.31},
        {"links.coupler.points.M.y": 0.01, "links.crank.length": 0.09},
    ],
    ids=["anchor", "heir", "aliased-pair", "alias-and-anchor"],
)
def test_a_value_written_where_the_file_shares_a_node_changes_that_value_alone(values, tmp_path):
    """Reading the written file back and solving it gives the driving torque of the variant solved (to 1e-12);
    the masses and points the file shares through its anchors stay as they were elsewhere."""
    source = tmp_path / "m.yaml"
    source.write_text(SHARED)
    mech = lw.compile(source)
    before = lw.parameters(mech)
    assert before["links.rocker.mass"] == 1.0 and before["links.coupler.points.M.x"] == pytest.approx(0.3)
    out = _write_file(mech, values, tmp_path / "x.yaml")
    again = lw.parameters(out)
    for name, value in before.items():  # the inertias left to their default follow the masses
        if not name.endswith("inertia"):
            assert again[name] == pytest.approx(values.get(name, value), rel=1e-12, abs=1e-15), name
    variant = lw.forces(mech, steps=STEPS, variants={k: [v] for k, v in values.items()}).driving_torque[0]
    np.testing.assert_allclose(lw.forces(out, steps=STEPS).driving_torque, variant, rtol=1e-12, atol=1e-12)


def test_the_viewers_save_writes_what_it_solves_whatever_the_folder_and_the_disk_hold(tmp_path, monkeypatch):
    """The viewer of the bundled four-bar in a folder with a ``four-bar.yaml`` of the user's own, and of a file
    changed on disk after the viewer read it: Save gives the file the viewer solved, with the edit written in."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "four-bar.yaml").write_text(text("four-bar").replace("length: 350", "length: 360"))
    source = tmp_path / "mine.yaml"
    source.write_text(text("four-bar"))
    viewers = [Viewer(lw.compile("four-bar")), Viewer(lw.compile(source))]
    source.write_text(text("four-bar").replace("length: 350", "length: 370"))
    for viewer in viewers:
        saved = tmp_path / "saved.yaml"
        saved.write_text(viewer.file_text({"links.crank.length": 0.105}))
        again = lw.parameters(saved)
        assert again["links.coupler.length"] == pytest.approx(0.35, rel=1e-12)
        assert again["links.crank.length"] == pytest.approx(0.105, rel=1e-12)
