"""Textbook mechanisms built with the Python builder, with what the textbooks say of them.

Each entry gives the builder and the expected structure: n, p5, p4, W,
redundant constraints, and the decomposition as (class, order, kind) in
solving order.  The expectations come from the textbooks (Artobolevsky,
Theory of Mechanisms and Machines, ch. 2), not from linkwork's output.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import strategies as st

import linkwork as lw
from linkwork import MechanismBuilder
from linkwork.structure.model import PairType


def circle_intersection(c1, r1, c2, r2, left=True):
    """Intersection of two circles; ``left`` picks the point to the left of c1 -> c2."""
    dx, dy = c2[0] - c1[0], c2[1] - c1[1]
    d = math.hypot(dx, dy)
    a = (r1 * r1 - r2 * r2 + d * d) / (2 * d)
    h = math.sqrt(r1 * r1 - a * a)
    mx, my = c1[0] + a * dx / d, c1[1] + a * dy / d
    s = 1 if left else -1
    return (mx - s * h * dy / d, my + s * h * dx / d)


def four_bar():
    a = (0.1 * math.cos(math.radians(60)), 0.1 * math.sin(math.radians(60)))
    b = circle_intersection(a, 0.35, (0.3, 0.0), 0.25, left=False)
    return (
        MechanismBuilder("four-bar")
        .frame(points={"O2": (0, 0), "O4": (0.3, 0)})
        .link("crank", ends=("O2", "A"), length=0.1)
        .link("coupler", ends=("A", "B"), length=0.35)
        .link("rocker", ends=("O4", "B"), length=0.25)
        .revolute("O2", "frame", "crank")
        .revolute("A", "crank", "coupler")
        .revolute("B", "coupler", "rocker")
        .revolute("O4", "frame", "rocker")
        .drive("O2", speed="60 rpm", angle="60 deg")
        .hint("B", *b)
    )


def offset_slider_crank():
    return (
        MechanismBuilder("offset slider-crank", units={"length": "mm"})
        .frame(points={"O": (0, 0), "G": (0, 50)})
        .link("crank", ends=("O", "A"), length=100)
        .link("rod", ends=("A", "B"), length=400)
        .link("slider", points={"B": (0, 0)})
        .revolute("O", "frame", "crank")
        .revolute("A", "crank", "rod")
        .revolute("B", "rod", "slider")
        .prismatic("guide", "frame", "slider", point="B", through="G", axis=0)
        .drive("O", speed="100 rpm", angle=30)
        .hint("B", 480, 50)
    )


def crank_shaper():
    """Whitworth-type quick return: block on the crank pin slides in the rocker (RPR)."""
    return (
        MechanismBuilder("crank-shaper")
        .frame(points={"O1": (0, 0.2), "O2": (0, 0)})
        .link("crank", ends=("O1", "A"), length=0.1)
        .link("block", points={"A": (0, 0)})
        .link("rocker", points={"O2": (0, 0), "T": (0.5, 0)})
        .revolute("O1", "frame", "crank")
        .revolute("A", "crank", "block")
        .prismatic("slot", "rocker", "block", point="A", through="O2", axis=0)
        .revolute("O2", "frame", "rocker")
        .drive("O1", angle=0)
        .hint("slot", 0.1, 0.2)
        .hint("rocker.T", 0.22, 0.45)
    )


def scotch_yoke():
    return (
        MechanismBuilder("scotch yoke")
        .frame(points={"O": (0, 0)})
        .link("crank", ends=("O", "A"), length=0.1)
        .link("block", points={"A": (0, 0)})
        .link("yoke", points={"Y": (0, 0), "P": (0, 0.1)})
        .revolute("O", "frame", "crank")
        .revolute("A", "crank", "block")
        .prismatic("slot", "yoke", "block", point="A", through="Y", axis=90)
        .prismatic("guide", "frame", "yoke", point="Y", through="O", axis=0)
        .drive("O", angle=30)
        .hint("slot", 0.0866, 0.05)
    )


def slotted_crank_prp():
    return (
        MechanismBuilder("slotted crank with a slider (PRP)")
        .frame(points={"O1": (0, 0), "G": (0, 0.1)})
        .link("crank", points={"O1": (0, 0), "T": (0.3, 0)})
        .link("block", points={"Q": (0, 0)})
        .link("slider", points={"Q": (0, 0)})
        .revolute("O1", "frame", "crank")
        .prismatic("on_crank", "crank", "block", point="Q", through="O1", axis=0)
        .revolute("Q", "block", "slider")
        .prismatic("guide", "frame", "slider", point="Q", through="G", axis=0)
        .drive("O1", angle=45)
        .hint("Q", 0.1, 0.1)
    )


def class4_group():
    """A four-link group with a closed contour B-C-D-E (class IV, order 2)."""
    pts = {"A": (30, 0), "B": (200, 150), "E": (200, -50), "C": (450, 200), "D": (450, -100), "O": (600, 50)}

    def local(*names):
        x0, y0 = pts[names[0]]
        return {n: (pts[n][0] - x0, pts[n][1] - y0) for n in names}

    def dist(p, q):
        return math.hypot(pts[p][0] - pts[q][0], pts[p][1] - pts[q][1])

    return (
        MechanismBuilder("class IV group", units={"length": "mm"})
        .frame(points={"O1": (0, 0), "O": pts["O"]})
        .link("crank", ends=("O1", "A"), length=30)
        .link("left", points=local("A", "B", "E"))
        .link("top", ends=("B", "C"), length=dist("B", "C"))
        .link("right", points=local("O", "C", "D"))
        .link("bottom", ends=("E", "D"), length=dist("E", "D"))
        .revolute("O1", "frame", "crank")
        .revolute("A", "crank", "left")
        .revolute("B", "left", "top")
        .revolute("C", "top", "right")
        .revolute("O", "frame", "right")
        .revolute("D", "right", "bottom")
        .revolute("E", "bottom", "left")
        .drive("O1", angle=0)
        .hint("B", *pts["B"])
        .hint("C", *pts["C"])
        .hint("D", *pts["D"])
        .hint("E", *pts["E"])
    )


def parallelogram_with_redundant_link():
    """Parallelogram O2ABO4 with a third crank O6C parallel to the others: W = 0, q = 1."""
    c, s = math.cos(math.radians(60)), math.sin(math.radians(60))
    return (
        MechanismBuilder("parallelogram with a redundant link")
        .frame(points={"O2": (0, 0), "O4": (0.3, 0), "O6": (0.15, 0)})
        .link("crank", ends=("O2", "A"), length=0.1)
        .link("coupler", ends=("A", "B"), length=0.3, points={"C": (0.15, 0)})
        .link("rocker", ends=("O4", "B"), length=0.1)
        .link("extra", ends=("O6", "C"), length=0.1)
        .revolute("O2", "frame", "crank")
        .revolute("A", "crank", "coupler")
        .revolute("B", "coupler", "rocker")
        .revolute("O4", "frame", "rocker")
        .revolute("O6", "frame", "extra")
        .revolute("C", "coupler", "extra")
        .drive("O2", angle=60)
        .hint("B", 0.3 + 0.1 * c, 0.1 * s)
    )


def five_bar():
    c = circle_intersection((0, 0.1), 0.25, (0.2, 0.1), 0.25, left=True)
    return (
        MechanismBuilder("five-bar, two drives")
        .frame(points={"O1": (0, 0), "O5": (0.2, 0)})
        .link("crank1", ends=("O1", "A"), length=0.1)
        .link("rod1", ends=("A", "C"), length=0.25)
        .link("rod2", ends=("D", "C"), length=0.25)
        .link("crank2", ends=("O5", "D"), length=0.1)
        .revolute("O1", "frame", "crank1")
        .revolute("A", "crank1", "rod1")
        .revolute("C", "rod1", "rod2")
        .revolute("D", "rod2", "crank2")
        .revolute("O5", "frame", "crank2")
        .drive("O1", angle=90)
        .drive("O5", angle=90)
        .hint("C", *c)
    )


def pin_in_slot():
    """Crank pin running in the slot of a rocker: a higher pair (p4 = 1)."""
    return (
        MechanismBuilder("pin in slot")
        .frame(points={"O1": (0, 0.2), "O2": (0, 0)})
        .link("crank", ends=("O1", "A"), length=0.1)
        .link("rocker", points={"O2": (0, 0), "T": (0.5, 0)})
        .revolute("O1", "frame", "crank")
        .revolute("O2", "frame", "rocker")
        .pin_in_slot("slot", "rocker", "crank", point="A", through="O2", axis=0)
        .drive("O1", angle=0)
        .hint("slot", 0.1, 0.2)
        .hint("rocker.T", 0.22, 0.45)
    )


def compound_hinge():
    """Three links share the hinge B: it counts as two pairs."""
    a = (0.1 * math.cos(math.radians(60)), 0.1 * math.sin(math.radians(60)))
    b = circle_intersection(a, 0.35, (0.3, 0.0), 0.25, left=False)
    yg = b[1] + 0.15
    return (
        MechanismBuilder("four-bar with a slider on a compound hinge")
        .frame(points={"O2": (0, 0), "O4": (0.3, 0), "G": (0, yg)})
        .link("crank", ends=("O2", "A"), length=0.1)
        .link("coupler", ends=("A", "B"), length=0.35)
        .link("rocker", ends=("O4", "B"), length=0.25)
        .link("rod", ends=("B", "C"), length=0.3)
        .link("slider", points={"C": (0, 0)})
        .revolute("O2", "frame", "crank")
        .revolute("A", "crank", "coupler")
        .revolute("B", "coupler", "rocker", "rod")
        .revolute("O4", "frame", "rocker")
        .revolute("C", "rod", "slider")
        .prismatic("guide", "frame", "slider", point="C", through="G", axis=0)
        .drive("O2", angle=60)
        .hint("B", *b)
        .hint("C", b[0] + math.sqrt(0.3**2 - 0.15**2), yg)
    )


def hydraulic_boom():
    """A boom raised by a hydraulic cylinder: the drive is the cylinder's prismatic pair."""
    return (
        MechanismBuilder("boom with a hydraulic cylinder")
        .frame(points={"O1": (0, 0), "O2": (0.5, 0)})
        .link("boom", points={"O1": (0, 0), "B": (1.0, 0), "T": (2.0, 0)})
        .link("cylinder", points={"O2": (0, 0)})
        .link("piston", points={"P": (0, 0), "B": (0.3, 0)})
        .revolute("O1", "frame", "boom")
        .revolute("O2", "frame", "cylinder")
        .prismatic("ram", "cylinder", "piston", point="P", through="O2", axis=0)
        .revolute("B", "piston", "boom")
        .drive("ram", position=0.5, speed="0.05 m/s")
        .hint("B", 0.8, 0.6)
        .hint("ram", 0.5 + 0.5 * 0.3 / 0.6708, 0.5 * 0.6 / 0.6708)
        .hint("boom.T", 1.6, 1.2)
    )


#: name -> (builder factory, n, p5, p4, W, redundant, [(class, order, kind), ...])
TEXTBOOK = {
    "four-bar": (four_bar, 3, 4, 0, 1, 0, [(1, None, "R"), (2, 2, "RRR")]),
    "offset slider-crank": (offset_slider_crank, 3, 4, 0, 1, 0, [(1, None, "R"), (2, 2, "RRP")]),
    "crank-shaper": (crank_shaper, 3, 4, 0, 1, 0, [(1, None, "R"), (2, 2, "RPR")]),
    "scotch yoke": (scotch_yoke, 3, 4, 0, 1, 0, [(1, None, "R"), (2, 2, "RPP")]),
    "PRP dyad": (slotted_crank_prp, 3, 4, 0, 1, 0, [(1, None, "R"), (2, 2, "PRP")]),
    "class IV": (class4_group, 5, 7, 0, 1, 0, [(1, None, "R"), (4, 2, None)]),
    "parallelogram": (parallelogram_with_redundant_link, 4, 6, 0, 0, 1, [(1, None, "R"), (2, 2, "RRR"), (0, 2, "RR")]),
    "five-bar": (five_bar, 4, 5, 0, 2, 0, [(1, None, "R"), (1, None, "R"), (2, 2, "RRR")]),
    "pin in slot": (pin_in_slot, 2, 2, 1, 1, 0, [(1, None, "R"), (2, 2, "RPR")]),
    "compound hinge": (compound_hinge, 5, 7, 0, 1, 0, [(1, None, "R"), (2, 2, "RRR"), (2, 2, "RRP")]),
}


# ---------------------------------------------------------------- builders shared by the tests


def four_bar_spec(a, b, c, d, phi, left, transform=(0.0, 0.0, 0.0)):
    """A four-bar as plain data, moved rigidly by ``transform`` = (dx, dy, rotation)."""
    dx, dy, rot = transform
    cr, sr = math.cos(rot), math.sin(rot)

    def move(p):
        return [cr * p[0] - sr * p[1] + dx, sr * p[0] + cr * p[1] + dy]

    pa = (a * math.cos(phi), a * math.sin(phi))
    pb = circle_intersection(pa, b, (d, 0.0), c, left=left)
    data = {
        "units": {"angle": "rad"},
        "frame": {"points": {"O2": move((0, 0)), "O4": move((d, 0))}},
        "links": {
            "crank": {"ends": ["O2", "A"], "length": a},
            "coupler": {"ends": ["A", "B"], "length": b},
            "rocker": {"ends": ["O4", "B"], "length": c},
        },
        "joints": {
            "O2": {"type": "revolute", "links": ["frame", "crank"]},
            "A": {"type": "revolute", "links": ["crank", "coupler"]},
            "B": {"type": "revolute", "links": ["coupler", "rocker"]},
            "O4": {"type": "revolute", "links": ["frame", "rocker"]},
        },
        "drives": [{"joint": "O2", "angle": phi + rot}],  # the drive angle turns with the frame
        "hints": {"B": move(pb)},
    }
    return data, move(pb)


def meeting_spring_four_bar():
    """A four-bar (:func:`four_bar_spec`, as plain data) with a spring from the crank's A to the frame's O4 on a
    crank as long as O2 O4 (the rocker pivots at Q): the spring's points meet with the crank at 0 deg to x, where
    its line has no direction."""
    data, _ = four_bar_spec(0.3, 0.35, 0.25, 0.5, 1.0, False)
    data["loads"] = {"s": {"type": "spring", "between": ["crank.A", "frame.O4"], "stiffness": 10.0, "free_length": 0}}
    data["frame"]["points"]["O4"] = [0.3, 0.0]
    data["frame"]["points"]["Q"] = [0.5, 0.0]
    data["joints"]["O4"]["links"] = ["frame", "rocker"]
    data["links"]["rocker"]["ends"] = ["Q", "B"]
    data["joints"]["Q"] = data["joints"].pop("O4")
    return data


four_bars = st.tuples(
    st.floats(0.05, 1.0),
    st.floats(0.05, 1.0),
    st.floats(0.05, 1.0),
    st.floats(0.05, 1.0),
    st.floats(-math.pi, math.pi),
    st.booleans(),
).filter(lambda t: assembles(*t[:5]))


def assembles(a, b, c, d, phi):
    e = math.hypot(a * math.cos(phi) - d, a * math.sin(phi))
    # away from the dead points, so that the branch is well defined
    return abs(b - c) + 0.02 < e < b + c - 0.02 and e > 0.02


SOLVED = [
    ("example", n)
    for n in [
        "double-cut-shears",
        "four-bar",
        "watt-six-bar",
        "stephenson-six-bar",
        "class3-triad",
        "percussion-rocker",
        "shears-slider-crank",
    ]
] + [
    ("textbook", n)
    for n in [
        "offset slider-crank",
        "crank-shaper",
        "scotch yoke",
        "PRP dyad",
        "pin in slot",
        "compound hinge",
        "class IV",
        "five-bar",
        "parallelogram",
    ]
]


def compiled(kind, name):
    return lw.compile(lw.example(name) if kind == "example" else TEXTBOOK[name][0]().build())


def angles_around(mech, n=48, span=2 * np.pi):
    """Drive values around the assembly pose (a whole turn for cranks)."""
    start = mech.drive_start
    offsets = np.linspace(-span / 2, span / 2, n, endpoint=False) + 1e-3
    if mech.pair_type[mech.drive_pair[0]] == PairType.PRISMATIC:  # linear drive: a few centimetres
        offsets = np.linspace(-0.05, 0.05, n)
    return start[None, :] + offsets[:, None]


def assert_free_bodies_balance(f):
    """Each group, cut free, is in equilibrium under the pair forces read back at their points."""
    for body in f.free_bodies():
        scale = max(np.nanmax(np.abs(c.force)) for c in body.external)
        scale = max(scale, np.nanmax(np.abs(body.loads[..., :2])))
        arm = np.nanmax(np.abs(np.concatenate([c.point for c in body.external], -1))) + 1.0
        assert np.nanmax(np.abs(body.residual[..., :2])) < 1e-9 * scale, body.label
        assert np.nanmax(np.abs(body.residual[..., 2])) < 1e-9 * scale * arm, body.label


def heavy_compound_hinge(order):
    """The four-bar with a slider rod on its compound hinge B (members nearest the frame: the rocker),
    every link heavy, B written ``links: order``."""
    data = compound_hinge().to_dict()
    for name, mass in (("crank", 2.0), ("coupler", 5.0), ("rocker", 4.0), ("rod", 3.0), ("slider", 6.0)):
        data["links"][name]["mass"] = mass
    data["joints"]["B"]["links"] = list(order)
    return lw.compile(lw.from_dict(data))


def forces_on_b(f):
    """The force B puts on each of its members, from the free body of that member alone: m a_C - W less
    the force of its other joint (reaction of a two-link joint: the first-named link on the second)."""
    mech, kin = f.mechanism, f.kinematics
    g = np.array([0.0, -mech.gravity])
    other = {"coupler": ("A", f.reaction("A")), "rocker": ("O4", f.reaction("O4")), "rod": ("C", -f.reaction("C"))}
    out = {}
    for link, (joint, force) in other.items():
        m = mech.link_mass[mech.link_names.index(link)]
        a_c = 0.5 * (kin.acceleration("B") + kin.acceleration(joint))  # mid-length of each binary link
        out[link] = m * a_c - m * g - force
    return out


#: A four-bar with all four sides equal: its parallelogram and folded modes meet at 0 and 180 deg.
RHOMBUS = """
name: rhombus
units: {length: mm, angle: deg}
frame:
  points: {O2: [0, 0], O4: [100, 0]}
links:
  crank: {ends: [O2, A], length: 100}
  coupler: {ends: [A, B], length: 100}
  rocker: {ends: [O4, B], length: 100}
joints:
  O2: {type: revolute, links: [frame, crank]}
  A: {type: revolute, links: [crank, coupler]}
  B: {type: revolute, links: [coupler, rocker]}
  O4: {type: revolute, links: [frame, rocker]}
drives:
  - {joint: O2, speed: 60 rpm, direction: ccw, angle: 60 deg}
hints:
  B: [150, 86.6]
"""


def rotor(angle_deg: float) -> str:
    """The file of a rotor: a crank of 2 kg with its centre of mass at (80, 30) mm in its own axes (off its line)
    and its own inertia 0.01 kg m^2, driving a massless coupler and rocker at 300 rpm from ``angle_deg``.  Its
    reduced inertia is constant and every load on its frame is a closed form of the crank's angle."""
    return """\
name: rotor
units: {length: mm, mass: kg, angle: deg}
frame:
  points: {O2: [40, 30], O4: [300, 0]}
links:
  crank: {ends: [O2, A], length: 100, mass: 2.0, com: [80, 30], inertia: 0.01 kg*m^2}
  coupler: {ends: [A, B], length: 350}
  rocker: {ends: [O4, B], length: 250}
joints:
  O2: {type: revolute, links: [frame, crank]}
  A: {type: revolute, links: [crank, coupler]}
  B: {type: revolute, links: [coupler, rocker]}
  O4: {type: revolute, links: [frame, rocker]}
drives:
  - {joint: O2, speed: 300 rpm, direction: ccw, angle: ANGLE deg}
hints:
  B: [330, 240]
""".replace("ANGLE", f"{angle_deg:g}")


def kinetic_and_potential_by_differences(mech, angle, h=1e-6):
    """Reduced inertia from the positions alone: velocities of the centres of mass and angular
    velocities by central differences in the crank angle; the potential energy too."""
    plus, minus = lw.kinematics(mech, angle + h), lw.kinematics(mech, angle - h)

    def com(k):
        q = k.pose[0]
        c, s = np.cos(q[..., 2]), np.sin(q[..., 2])
        lx, ly = mech.link_com[:, 0], mech.link_com[:, 1]
        return np.stack([q[..., 0] + c * lx - s * ly, q[..., 1] + s * lx + c * ly], -1), q[..., 2]

    (cp, tp), (cm, tm) = com(plus), com(minus)
    v = (cp - cm) / (2 * h)
    w = (np.unwrap(np.stack([tm, tp]), axis=0)[1] - np.unwrap(np.stack([tm, tp]), axis=0)[0]) / (2 * h)
    inertia = np.sum(mech.link_mass * np.sum(v * v, -1) + mech.link_inertia * w * w, -1)
    potential = lambda c: np.sum(mech.link_mass * mech.gravity * c[..., 1], -1)  # noqa: E731
    return inertia, (potential(cp) - potential(cm)) / (2 * h)
