"""Force plans of the graphical method of kinetostatics: each Assur group's polygon of forces, as data.

The graphical method takes the groups from the one farthest from the drive back to the driving link
(the reverse of the order the positions are solved in).  Each group is cut free; the forces on it are

* the weights ``G2`` at the centres of mass, the inertia forces ``Phi2 = -m2 a_S2`` (``Φ2`` in Russian) there, and
  the inertia moments ``M_Phi2 = -J_S2 eps2`` (couples: they enter the moment equations, not the polygon);
* the file's external loads on its links (``F5``, named after the load);
* the reactions of the groups solved before it (``R43``: the force of link 4 on link 3), known now;
* the unknown reactions of the links placed before it (``R12``, ``R03``).

A revolute pair at the end of a dyad's link is split as the textbooks split it: its tangential component
``R12t`` (normal to the link's line from the pair to the inner joint) from the link's moments about the
inner joint, its normal component ``R12n`` along that line.  A prismatic pair at the end pushes normal
to its guide.  The two unknowns along known lines close the polygon (two equations, the plan's closing);
the inner joint's force then comes from one link's equilibrium, and a guide's couple (where the guide's
force acts) from the slider's moments.  At a dead point (:attr:`Forces.singular`) the two lines are parallel
and the reactions indeterminate: NaN there, and in the groups taken after.  The driving link closes its
polygon with the frame's reaction ``R01``, and its moment equation about the pivot gives the balancing
moment (the driving torque).

These are solved here by their own arithmetic, from the loads and the positions, not read from
:class:`~linkwork.kinetostatics.reaction_forces.Forces`: the two are independent methods and agree (the tests
compare them).  Groups the textbook method above does not cover (class III and higher, dyads with an
inner prismatic pair, groups with a slot block) are closed by the reactions of the analytic solution
(``GroupPlan.solved`` is False for them).

>>> import linkwork as lw
>>> from linkwork.kinetostatics.force_polygons import force_plans
>>> plans = force_plans(lw.forces(lw.compile(lw.load("four-bar")), steps=12))
>>> [g.label for g in plans.groups]
['II(2,3) RRR', 'I(0,1) R']
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from linkwork.kinetostatics.geometry import guide_direction
from linkwork.kinetostatics.reaction_forces import Forces
from linkwork.motion.plans import drawing_scale
from linkwork.structure.model import Mechanism, PairType, point_labels

#: How each kind of force is named in each language: symbol -> (English, Russian).
SYMBOLS = {
    "R": ("R", "R"),
    "G": ("G", "G"),
    "Phi": ("Phi", "Φ"),
    "F": ("F", "F"),
    "M": ("M", "M"),
    "MPhi": ("MPhi", "MΦ"),
    "Fb": ("Fb", "Fу"),
    "Ff": ("Ff", "Fтр"),
    "Mf": ("Mf", "Mтр"),
}

#: The kinds of force of a plan, in the order of a legend.
KINDS = ("weight", "inertia", "load", "known", "tangential", "normal", "reaction", "internal")


def pair_index(i: int, j: int) -> str:
    """The subscript of the force of link ``i`` on link ``j``: ``"12"``, ``"10,11"`` where a number has two
    digits."""
    return f"{i}{j}" if i < 10 and j < 10 else f"{i},{j}"


@dataclass(frozen=True)
class PlanForce:
    """One force of a group's plan.

    Attributes
    ----------
    symbol : str
        ``R`` (a reaction), ``G`` (a weight), ``Phi`` (an inertia force), ``F`` (an external load), ``MPhi`` or
        ``M`` (a couple: an inertia moment, an external moment), ``Fb`` (the lever's balancing force).
    index : str
        The subscript: ``"12"`` (link 1 on link 2) for a reaction, the link's number for the others.
    part : str
        ``"n"`` or ``"t"`` for the normal and tangential components of a reaction, ``""`` for a whole force.
    kind : str
        One of :data:`KINDS`, or ``"couple"``.
    link : int
        The link it acts on.
    vector : ndarray (V, A, 2)
        The force, N (a couple: zero).
    point : ndarray (V, A, 2)
        Where it acts, m (a guide's reaction: at the slider's point of the pair, with ``moment``).
    moment : ndarray (V, A)
        A couple that goes with it about ``point``, N m: the guide's couple of a prismatic pair, the moment
        of a couple (``kind == "couple"``); zero for the others.
    about : str
        The joint of a reaction, the file's name of an external load.
    pair : int
        A reaction's elementary pair (-1 for the other forces).
    """

    symbol: str
    index: str
    part: str
    kind: str
    link: int
    vector: np.ndarray
    point: np.ndarray
    moment: np.ndarray
    about: str = ""
    pair: int = -1

    def name(self, lang: str = "en") -> str:
        """The force's name in plain text: ``R12``, ``R12n``, ``R12τ``, ``G2``, ``Phi2`` (``Φ2`` in Russian)."""
        symbol = SYMBOLS[self.symbol][1 if lang == "ru" else 0]
        return f"{symbol}{self.index}{'τ' if self.part == 't' else self.part}"

    def tex(self, lang: str = "en") -> str:
        """The force's name as matplotlib's mathtext writes it: ``$R_{12}^{n}$``, ``$\\Phi_{2}$``."""
        part = {"n": "^{n}", "t": r"^{\tau}", "'": "^{\\prime}", "''": "^{\\prime\\prime}"}.get(self.part, "")
        sub = self.index
        if self.symbol == "Phi":
            return f"$\\Phi_{{{sub}}}{part}$"
        if self.symbol == "MPhi":
            return f"$M_{{\\Phi {sub}}}{part}$"
        if self.symbol == "Fb":  # the balancing force: F_b, F_у (уравновешивающая)
            return f"$F_{{{'у' if lang == 'ru' else 'b'}}}$"
        if self.symbol in ("Ff", "Mf"):  # friction solved with the reactions: F_f3, F_тр3 (сила трения)
            return f"${self.symbol[0]}_{{{'тр' if lang == 'ru' else 'f'}{self.index}}}{part}$"
        return f"${self.symbol}_{{{self.index}}}{part}$"


@dataclass(frozen=True)
class MomentEquation:
    """The moments of one link's forces about a point, which give one unknown (item of the course project's
    kinetostatic analysis).

    ``terms``: each force or couple with its moment about ``about`` (N m, (V, A)); ``unknown``: the force it
    gives (a tangential component, or a guide's couple), its moment ``-sum(terms)``.
    """

    link: int
    about: str
    terms: tuple[tuple[PlanForce, np.ndarray], ...]
    unknown: PlanForce
    arm: np.ndarray  # (V, A) m: the unknown's arm about ``about`` (its length of link), NaN for a couple


@dataclass(frozen=True)
class GroupPlan:
    """The force plan of one Assur group (or of the driving link) over the samples.

    Attributes
    ----------
    label : str
        The group's label, ``II(2,3) RRR``.
    links : tuple of int
    polygon : tuple of PlanForce
        The forces of the plan, head to tail, in the order they are drawn: the known ones link by link, then
        the unknown ones that close it.  Their sum is zero.
    reactions : tuple of PlanForce
        The reactions the plan gives, whole (``R12 = R12n + R12τ``), the inner joint's too (``R32``).
    couples : tuple of PlanForce
        The couples on the group's links (inertia moments, external moments): they enter the moment
        equations, not the polygon.
    equations : tuple of MomentEquation
        The moment equations solved before the polygon, in order.
    balancing : ndarray (V, A) or None
        For the driving link: the balancing moment, N m (the moment the drive puts on it, counter-clockwise
        positive).
    solved : bool
        False where the polygon is closed by the analytic solution's reactions (see the module's text).
    """

    label: str
    links: tuple[int, ...]
    polygon: tuple[PlanForce, ...]
    reactions: tuple[PlanForce, ...]
    couples: tuple[PlanForce, ...] = ()
    equations: tuple[MomentEquation, ...] = ()
    balancing: np.ndarray | None = None
    solved: bool = True

    def vertices(self, index: int, variant: int = 0) -> np.ndarray:
        """The polygon's vertices at sample ``index``, ``(len(polygon) + 1, 2)`` N: 0, then the running sums."""
        vectors = np.array([f.vector[variant, index] for f in self.polygon]).reshape(-1, 2)
        return np.concatenate([np.zeros((1, 2)), np.cumsum(vectors, axis=0)])

    def closure(self, index: int, variant: int = 0) -> float:
        """How far the polygon is from closing at sample ``index``, relative to its largest force."""
        vectors = np.array([f.vector[variant, index] for f in self.polygon]).reshape(-1, 2)
        big = float(np.max(np.hypot(*vectors.T), initial=0.0))
        gap = float(np.hypot(*np.sum(vectors, axis=0)))
        return gap / big if big > 0 else gap

    def scale(self, index: int, variant: int = 0) -> float:
        """The plan's scale μF at sample ``index``, N per mm: a round number that draws the polygon at most
        100 mm wide and high."""
        v = self.vertices(index, variant)
        v = v[np.isfinite(v).all(-1)]
        span = float(np.max(v.max(0) - v.min(0))) if len(v) else 0.0
        return drawing_scale(span)


@dataclass(frozen=True)
class ForcePlans:
    """The force plans of every group, in the order the graphical method solves them (the driving link last).

    Attributes
    ----------
    forces : Forces
        The kinetostatic result they were drawn for.
    groups : tuple of GroupPlan
    """

    forces: Forces
    groups: tuple[GroupPlan, ...] = field(default_factory=tuple)

    @property
    def balancing(self) -> np.ndarray:
        """The balancing moment of the driving link, N m ``(V, A)`` (NaN where there is no revolute drive)."""
        for g in self.groups:
            if g.balancing is not None:
                return g.balancing
        return np.full(self.forces.kinematics.valid_all.shape, np.nan)


def _cross(r: np.ndarray, f: np.ndarray) -> np.ndarray:
    return r[..., 0] * f[..., 1] - r[..., 1] * f[..., 0]


def _perp(v: np.ndarray) -> np.ndarray:
    return np.stack([-v[..., 1], v[..., 0]], -1)


def _unit(v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    size = np.hypot(v[..., 0], v[..., 1])
    with np.errstate(invalid="ignore", divide="ignore"):
        return v / size[..., None], size


def point_names(mech: Mechanism) -> list[str]:
    """A short name for every point of ``mech`` (its joint's name where it is a joint's)."""
    names = {p: label for label, p in point_labels(mech, with_all=True)}
    return [names.get(p, n.split(".", 1)[1]) for p, n in enumerate(mech.point_names)]


def load_names(mech: Mechanism) -> tuple[list[str], list[str]]:
    """The file's name of each elementary force and moment of :func:`~linkwork.kinetostatics.external.evaluate`,
    in its order (a process load and a friction give two of each), then of the friction in proportion to the pairs'
    forces (``friction JOINT``, two of each: :func:`~linkwork.kinetostatics.friction.with_friction`)."""
    forces: list[str] = []
    moments: list[str] = []
    for load in mech.loads:
        if load.kind == "force":
            forces.append(load.name)
        elif load.kind == "moment":
            moments.append(load.name)
        elif load.kind in ("process", "spring", "damper"):  # one force on each of two links
            forces += [load.name, load.name]
        elif load.kind == "torsion_spring":  # a moment on each of its two links
            moments += [load.name, load.name]
        elif mech.pair_type[load.pair] == PairType.REVOLUTE:
            moments += [load.name, load.name]
        else:
            forces += [load.name, load.name]
    for pair in mech.friction:  # friction in proportion to the pair's force, after the loads as it is solved
        name = f"friction {pair.joint}"
        if mech.pair_type[pair.pair] == PairType.REVOLUTE:
            moments += [name, name]
        else:
            forces += [name, name]
    return forces, moments


class _Loads:
    """The known forces and couples on every moving link: weights, inertia, external loads."""

    def __init__(self, f: Forces) -> None:
        kin, m = f.kinematics, f.mechanism
        shape = kin.valid_all.shape
        zero = np.zeros(shape)
        masses = kin.mass_properties
        mass, inertia = masses.mass[:, None], masses.inertia[:, None]  # (V, 1, N)
        com, acc = f.loads.com, f.loads.com_acceleration  # (V, A, N, 2)
        eps = kin.acc[..., 2]
        self.forces: dict[int, list[PlanForce]] = {i: [] for i in range(len(m.link_names))}
        self.couples: dict[int, list[PlanForce]] = {i: [] for i in range(len(m.link_names))}
        for i in range(1, len(m.link_names)):
            mi = np.broadcast_to(mass[..., i], shape)
            if m.gravity and np.any(mi > 0):
                weight = mi[..., None] * m.gravity_vector
                self.forces[i].append(PlanForce("G", str(i), "", "weight", i, weight, com[..., i, :], zero))
            if np.any(mi > 0):
                phi = -mi[..., None] * acc[..., i, :]
                self.forces[i].append(PlanForce("Phi", str(i), "", "inertia", i, phi, com[..., i, :], zero))
            moment = -inertia[..., i] * eps[..., i]
            if np.any(np.abs(moment) > 0):
                zeros = np.zeros(shape + (2,))
                self.couples[i].append(PlanForce("MPhi", str(i), "", "couple", i, zeros, com[..., i, :], moment))
        names_f, names_m = load_names(m)
        applied = f.external
        revolute = sum(m.pair_type[p.pair] == PairType.REVOLUTE for p in m.friction)
        rubbed = (len(names_f) - 2 * (len(m.friction) - revolute), len(names_m) - 2 * revolute)  # friction from here
        for k, (name, (link, pos, _, force)) in enumerate(zip(names_f, applied.forces, strict=True)):
            symbol = "Ff" if k >= rubbed[0] else "F"
            self.forces[link].append(PlanForce(symbol, str(link), "", "load", link, force, pos, zero, name))
        for k, (name, (link, moment)) in enumerate(zip(names_m, applied.moments, strict=True)):
            symbol = "Mf" if k >= rubbed[1] else "M"
            self.couples[link].append(
                PlanForce(symbol, str(link), "", "couple", link, np.zeros(shape + (2,)), zero, moment, name)
            )


def force_plans(f: Forces) -> ForcePlans:
    """The force plan of every group of ``f``'s mechanism over its samples (see the module's text).

    Parameters
    ----------
    f : Forces
        A kinetostatic result (:func:`linkwork.forces`).

    Returns
    -------
    ForcePlans
        Its groups in the order the graphical method takes them: the last group first, the driving link last.
    """
    m = f.mechanism
    kin = f.kinematics
    loads = _Loads(f)
    points = np.moveaxis(kin.point_positions(np.arange(len(m.point_names))), 0, -2)  # (V, A, P, 2)
    names = point_names(m)
    known: dict[tuple[int, int], PlanForce] = {}  # (pair, link): the force of the pair on that link, solved
    groups = list(m.structure.groups)
    out: list[GroupPlan] = []
    for g, group in reversed(list(enumerate(groups))):
        earlier = {0} | {i for h in groups[:g] for i in h.links}
        solver = _Group(f, group.label, tuple(group.links), earlier, loads, points, names, known)
        plan = solver.solve()
        out.append(plan)
        for r in plan.reactions:  # what the later-taken groups read: each pair's force on each of its links
            known[_key(r)] = r
            other = _other(m, r)
            if other:
                known[(_pair_of(r), other)] = _opposite(r, other)
    return ForcePlans(f, tuple(out))


def _key(r: PlanForce) -> tuple[int, int]:
    return (_pair_of(r), r.link)


def _pair_of(r: PlanForce) -> int:
    return r.pair


def _other(m: Mechanism, r: PlanForce) -> int:
    a, b = (int(x) for x in m.pair_links[_pair_of(r)])
    return a if r.link == b else b


def _opposite(r: PlanForce, on: int) -> PlanForce:
    """The force of the same pair on its other link ``on`` (Newton's third law)."""
    return PlanForce("R", pair_index(r.link, on), "", "known", on, -r.vector, r.point, -r.moment, r.about, r.pair)


class _Group:
    """One group's plan, solved (:meth:`solve`)."""

    def __init__(
        self,
        f: Forces,
        label: str,
        links: tuple[int, ...],
        earlier: set[int],
        loads: _Loads,
        points: np.ndarray,
        names: list[str],
        known: dict[tuple[int, int], PlanForce],
    ) -> None:
        m = f.mechanism
        self.f, self.m, self.label, self.links, self.points, self.names = f, m, label, links, points, names
        self.shape = f.kinematics.valid_all.shape
        members = set(links)
        self.outer: list[int] = []
        self.inner: list[int] = []
        self.on: dict[int, list[PlanForce]] = {i: list(loads.forces[i]) for i in links}
        self.couples: dict[int, list[PlanForce]] = {i: list(loads.couples[i]) for i in links}
        for k in range(m.n_pairs):
            a, b = (int(x) for x in m.pair_links[k])
            if a in members and b in members:
                self.inner.append(k)
            elif a in members or b in members:
                link, other = (a, b) if a in members else (b, a)
                if other in earlier:
                    self.outer.append(k)
                else:
                    self.on[link].append(known[(k, link)])

    def point(self, k: int) -> np.ndarray:
        return self.points[..., int(self.m.pair_points[k, 1]), :]

    def solve(self) -> GroupPlan:
        m = self.m
        virtual = any(m.link_virtual[i] for i in self.links)
        drives = [k for k in self.outer if k in set(int(d) for d in m.drive_pair)]
        if len(self.links) == 1 and len(self.outer) == 1 and drives and m.n_drives == 1 and not virtual:
            if m.pair_type[self.outer[0]] == PairType.REVOLUTE:
                return self.driving()
        if len(self.links) == 2 and len(self.outer) == 2 and len(self.inner) == 1 and not drives and not virtual:
            if m.pair_type[self.inner[0]] == PairType.REVOLUTE:
                return self.dyad()
        return self.closed_by_solution()

    # ---------------------------------------------------------------- the forces as data
    def reaction(
        self,
        k: int,
        link: int,
        vector: np.ndarray,
        part: str = "",
        kind: str = "reaction",
        moment: np.ndarray | None = None,
    ) -> PlanForce:
        a, b = (int(x) for x in self.m.pair_links[k])
        other = a if link == b else b
        couple = np.zeros(self.shape) if moment is None else moment
        return PlanForce(
            "R", pair_index(other, link), part, kind, link, vector, self.point(k), couple, str(self.m.pair_joint[k]), k
        )

    def moments_about(self, link: int, at: np.ndarray) -> tuple[np.ndarray, list[tuple[PlanForce, np.ndarray]]]:
        """The moment about ``at`` of the known forces and couples on ``link``, and each one's."""
        terms = [(p, _cross(p.point - at, p.vector) + p.moment) for p in self.on[link]]
        terms += [(c, c.moment) for c in self.couples[link]]
        total = np.zeros(self.shape)
        for _, value in terms:
            total = total + value
        return total, terms

    def total(self, link: int) -> np.ndarray:
        out = np.zeros(self.shape + (2,))
        for p in self.on[link]:
            out = out + p.vector
        return out

    # ---------------------------------------------------------------- the methods
    def driving(self) -> GroupPlan:
        """The driving link: the frame's reaction closes its polygon, its moments about the pivot give the
        balancing moment."""
        (link,), k = self.links, self.outer[0]
        pivot = self.point(k)
        moment, terms = self.moments_about(link, pivot)
        r01 = self.reaction(k, link, -self.total(link))
        couples = tuple(self.couples[link])
        return GroupPlan(self.label, self.links, (*self.on[link], r01), (r01,), couples, (), -moment)

    def dyad(self) -> GroupPlan:
        """A dyad with an inner revolute joint: the tangential components from each link's moments about the inner
        joint, then the two unknowns along known lines from the polygon's closing."""
        m, inner = self.m, self.inner[0]
        b_point = self.point(inner)
        equations: list[MomentEquation] = []
        lines, tangents = [], []
        for k in self.outer:
            link = next(i for i in self.links if i in (int(m.pair_links[k, 0]), int(m.pair_links[k, 1])))
            if m.pair_type[k] == PairType.REVOLUTE:
                u, length = _unit(b_point - self.point(k))  # along the link, from the outer joint to the inner
                moment, terms = self.moments_about(link, b_point)
                with np.errstate(invalid="ignore", divide="ignore"):
                    t = moment / length  # sum M_B = moment + cross(A - B, t perp(u)) = moment - t |AB| = 0
                tangent = self.reaction(k, link, t[..., None] * _perp(u), "t", "tangential")
                equations.append(
                    MomentEquation(link, self.names[int(m.pair_points[inner, 1])], tuple(terms), tangent, length)
                )
                tangents.append(tangent)
                lines.append((k, link, u, "n", "normal"))
            else:
                lines.append((k, link, _perp(guide_direction(self.f.kinematics, k)), "", "reaction"))
        known = sum((self.total(i) for i in self.links), np.zeros(self.shape + (2,)))
        rest = -(known + sum((t.vector for t in tangents), np.zeros(self.shape + (2,))))
        (k1, l1, d1, p1, kind1), (k2, l2, d2, p2, kind2) = lines
        with np.errstate(invalid="ignore", divide="ignore"):
            det = np.where(self.f.singular_all, np.nan, _cross(d1, d2))  # a dead point: indeterminate
            c1, c2 = _cross(rest, d2) / det, _cross(d1, rest) / det
        unknown = {
            k1: self.reaction(k1, l1, c1[..., None] * d1, p1, kind1),
            k2: self.reaction(k2, l2, c2[..., None] * d2, p2, kind2),
        }
        whole: list[PlanForce] = []
        for k, link, _, part, _ in lines:
            if part:  # R = Rn + Rt
                tangent = next(t for t in tangents if _pair_of(t) == k)
                whole.append(self.reaction(k, link, unknown[k].vector + tangent.vector))
            else:  # a guide's force, and its couple from the slider's moments about the inner joint
                moment, terms = self.moments_about(link, b_point)
                force = unknown[k].vector
                couple = -(moment + _cross(self.point(k) - b_point, force))
                guide = self.reaction(k, link, force, moment=couple)
                whole.append(guide)
                nan = np.full(self.shape, np.nan)
                equations.append(
                    MomentEquation(
                        link,
                        self.names[int(m.pair_points[inner, 1])],
                        (*terms, (unknown[k], _cross(self.point(k) - b_point, force))),
                        guide,
                        nan,
                    )
                )
        first = self.links[0]
        r_first = next(r for r in whole if r.link == first)
        inner_on_first = -(self.total(first) + r_first.vector)
        whole.append(self.reaction(inner, first, inner_on_first, kind="internal"))
        order = self._order(tangents, unknown, lines)
        couples = tuple(c for i in self.links for c in self.couples[i])
        return GroupPlan(self.label, self.links, order, tuple(whole), couples, tuple(equations))

    def _order(self, tangents: list[PlanForce], unknown: dict[int, PlanForce], lines: list) -> tuple[PlanForce, ...]:
        """The polygon as the textbook draws it: the first link's tangential component, its known forces, the
        second link's known forces and tangential component, then the second's and the first's unknown along
        their lines."""
        first, second = self.links
        t_of = {t.link: t for t in tangents}
        out: list[PlanForce] = []
        if first in t_of:
            out.append(t_of[first])
        out += self.on[first] + self.on[second]
        if second in t_of:
            out.append(t_of[second])
        by_link = {link: unknown[k] for k, link, *_ in lines}
        return (*out, by_link[second], by_link[first])

    def closed_by_solution(self) -> GroupPlan:
        """A group the method above does not cover: its polygon closed by the analytic solution's reactions."""
        m = self.m
        whole: list[PlanForce] = []
        for k in self.outer:
            a, b = (int(x) for x in m.pair_links[k])
            link = b if b in self.links else a
            force = self.f.pair_force(k)
            couple = self.f.multipliers[..., 2 * k] if m.pair_type[k] != PairType.REVOLUTE else None
            if link == a:
                force, couple = -force, None if couple is None else -couple
            whole.append(self.reaction(k, link, force, moment=couple))
        polygon = tuple(p for i in self.links for p in self.on[i]) + tuple(whole)
        for k in self.inner:
            b = int(m.pair_links[k, 1])
            whole.append(self.reaction(k, b, self.f.pair_force(k), kind="internal"))
        couples = tuple(c for i in self.links for c in self.couples[i])
        return GroupPlan(self.label, self.links, polygon, tuple(whole), couples, solved=False)
