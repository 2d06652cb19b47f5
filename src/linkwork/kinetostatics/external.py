"""External loads of a mechanism file: forces at points, moments on links, process loads.

:func:`compile_loads` turns the ``loads:`` of a spec into :class:`ExternalLoad`
records (SI, indices); :func:`evaluate` gives, over a kinematics result, every
elementary force (its link, point of application, the point's velocity) and
moment, from which the reactions, the power balance and the momentum check
are all built.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.structure.model import PairType


@dataclass(frozen=True)
class ExternalLoad:
    """One external load, compiled.

    Attributes
    ----------
    name : str
    kind : str
        ``force``, ``moment``, ``process`` or ``friction`` (in the pair ``pair``: a moment for a
        revolute pair, a force for a prismatic one, of size ``value``).
    link : int
        The link a force or moment acts on (for a process load: the first tool's link).
    points : tuple of int
        Point indices: the point of a force, the tools of a process load.
    vector : tuple of float
        Force: its components (N) when ``value`` is 1, else the unit direction of the magnitude;
        process: the unit axis.
    value : float
        Constant magnitude (N, N m); NaN where a table gives it.
    table : tuple of ndarray or None
        ``(x, y)``: drive angles (rad) or relative penetrations, and magnitudes (N or N m).
    workpiece : tuple of float
        Process: extent along the axis (m).
    """

    name: str
    kind: str
    link: int
    points: tuple[int, ...] = ()
    vector: tuple[float, float] = (0.0, 0.0)
    value: float = math.nan
    table: tuple[np.ndarray, np.ndarray] | None = None
    workpiece: tuple[float, float] = (0.0, 0.0)
    pair: int = -1  # friction: the elementary pair it acts in


def compile_loads(spec: Any, mech: Any) -> tuple:
    """The :class:`ExternalLoad` records of a validated spec, for its structural model ``mech``
    (:func:`linkwork.structure.compile.structural_model`: its links, points and elementary pairs)."""
    link_index = {name: i for i, name in enumerate(mech.link_names)}
    pindex = {(int(mech.point_link[p]), name.split(".", 1)[1]): p for p, name in enumerate(mech.point_names)}
    pairs = [(j, t, a, b) for j, t, (a, b) in zip(mech.pair_joint, mech.pair_type, mech.pair_links, strict=True)]

    def point(ref: str) -> int:
        ln, p = ref.split(".", 1)
        return pindex[(link_index[ln], p)]

    def table(x: list[float], y: Any) -> tuple[np.ndarray, np.ndarray]:
        return np.array(x, dtype=float), np.array(y, dtype=float)

    out = []
    for name, load in spec.loads.items():
        if load.type == "force":
            p = point(load.at)
            link = link_index[load.at.split(".", 1)[0]]
            if load.force is not None:
                out.append(ExternalLoad(name, "force", link, (p,), (load.force[0], load.force[1]), 1.0))
                continue
            u = (math.cos(load.direction), math.sin(load.direction))
            if load.angle is None:
                out.append(ExternalLoad(name, "force", link, (p,), u, float(load.magnitude)))
            else:
                out.append(ExternalLoad(name, "force", link, (p,), u, table=table(load.angle, load.magnitude)))
        elif load.type == "friction":
            for k, (joint, kind, _, b) in enumerate(pairs):
                if joint != load.joint:
                    continue
                if kind == PairType.REVOLUTE and load.moment is not None:
                    out.append(ExternalLoad(name, "friction", int(b), value=float(load.moment), pair=k))
                elif kind == PairType.PRISMATIC and load.magnitude is not None:
                    out.append(ExternalLoad(name, "friction", int(b), value=float(load.magnitude), pair=k))
        elif load.type == "moment":
            link = link_index[load.on]
            if load.angle is None:
                out.append(ExternalLoad(name, "moment", link, value=float(load.moment)))
            else:
                out.append(ExternalLoad(name, "moment", link, table=table(load.angle, load.moment)))
        else:
            pts = tuple(point(t) for t in load.tools)
            link = link_index[load.tools[0].split(".", 1)[0]]
            u = (math.cos(load.axis), math.sin(load.axis))
            lo, hi = load.workpiece
            out.append(
                ExternalLoad(
                    name, "process", link, pts, u, table=table(load.penetration, load.force), workpiece=(lo, hi)
                )
            )
    return tuple(out)


@dataclass(frozen=True)
class Applied:
    """The elementary external loads over (V, A).

    Attributes
    ----------
    forces : list of (link, position, velocity, force)
        A force (V, A, 2) at a point of ``link`` whose position and velocity are (V, A, 2).
    moments : list of (link, moment)
        A moment (V, A) on ``link``.
    magnitude : dict
        Each load's magnitude (V, A): N for forces and process loads, N m for moments.
    penetration : dict
        Relative penetration (V, A) of each process load.
    """

    forces: list[tuple[int, np.ndarray, np.ndarray, np.ndarray]]
    moments: list[tuple[int, np.ndarray]]
    magnitude: dict[str, np.ndarray]
    penetration: dict[str, np.ndarray]


def _interp(x: np.ndarray, table: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """Linear in the table, zero outside it; NaN stays NaN."""
    xp, fp = table
    y = np.interp(x, xp, fp, left=0.0, right=0.0)
    return np.where(np.isnan(x), np.nan, y)


def _along(x: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Component of vectors (..., 2) along ``u`` (written out: ``@`` would wake BLAS threads that spin)."""
    return x[..., 0] * u[0] + x[..., 1] * u[1]


def evaluate(kin: Any) -> Applied:
    """The external loads of ``kin.mechanism`` over a kinematics result."""
    mech = kin.mechanism
    forces: list[tuple[int, np.ndarray, np.ndarray, np.ndarray]] = []
    moments: list[tuple[int, np.ndarray]] = []
    magnitude: dict[str, np.ndarray] = {}
    penetration: dict[str, np.ndarray] = {}
    shape = kin.valid_all.shape
    drive = np.broadcast_to(kin.angles, shape)

    def state(p: int) -> tuple[np.ndarray, np.ndarray]:
        pos, vel, _ = kin._point(mech.point_names[p])
        return pos, vel

    for load in getattr(mech, "loads", ()):
        if load.kind == "friction":
            _friction(kin, load, forces, moments, magnitude)
            continue
        if load.kind in ("force", "moment"):
            if load.table is None:
                size = np.full(shape, load.value)
            else:
                x0 = load.table[0][0]
                size = _interp(x0 + np.mod(drive - x0, 2 * np.pi), load.table)
            magnitude[load.name] = size
            if load.kind == "moment":
                moments.append((load.link, size))
                continue
            pos, vel = state(load.points[0])
            f = size[..., None] * np.asarray(load.vector)
            forces.append((load.link, pos, vel, f))
            continue
        u = np.asarray(load.vector)
        lo, hi = load.workpiece
        tools = [state(p) for p in load.points]
        (p1, v1) = tools[0]
        depth = np.maximum(hi - _along(p1, u), 0.0)
        closing = -_along(v1, u)
        if len(tools) == 2:
            p2, v2 = tools[1]
            depth = depth + np.maximum(_along(p2, u) - lo, 0.0)
            closing = closing + _along(v2, u)
        eps = depth / (hi - lo)
        # the table's value at zero penetration (a constant cutting force) acts from the touch on, not before
        size = np.where((closing > 0) & (eps > 0), _interp(eps, load.table), 0.0)
        size = np.where(np.isnan(closing) | np.isnan(eps), np.nan, size)
        magnitude[load.name] = size
        penetration[load.name] = eps
        f = size[..., None] * u
        forces.append((load.link, p1, v1, f))
        if len(tools) == 2:
            link2 = int(mech.point_link[load.points[1]])
            forces.append((link2, tools[1][0], tools[1][1], -f))
        else:  # the workpiece rests on the frame
            forces.append((0, p1, np.zeros_like(v1), -f))
    return Applied(forces, moments, magnitude, penetration)


def _friction(kin: Any, load: ExternalLoad, forces: list, moments: list, magnitude: dict) -> None:
    """Coulomb friction of constant size in one pair, against the relative motion (none at rest)."""
    mech = kin.mechanism
    k = load.pair
    a, b = (int(x) for x in mech.pair_links[k])
    w = kin.vel[..., 2]
    if mech.pair_type[k] == PairType.REVOLUTE:
        turn = np.sign(w[..., b] - w[..., a])
        moments.append((b, -load.value * turn))
        moments.append((a, load.value * turn))
    else:
        pos, vb, _ = kin._point(mech.point_names[int(mech.pair_points[k, 1])])
        q, v = kin.pose[..., a, :], kin.vel[..., a, :]
        r = pos - q[..., :2]
        va = v[..., :2] + w[..., a, None] * np.stack([-r[..., 1], r[..., 0]], -1)  # a's material point at P
        c, s = np.cos(q[..., 2]), np.sin(q[..., 2])
        ux, uy = kin.axis[k, 0], kin.axis[k, 1]  # (V, 1)
        u = np.stack([c * ux - s * uy, s * ux + c * uy], -1)
        slide = np.sign(np.sum((vb - va) * u, -1))
        f = (-load.value * slide)[..., None] * u
        forces.append((b, pos, vb, f))
        forces.append((a, pos, va, -f))
    magnitude[load.name] = np.full(kin.valid_all.shape, load.value)


def generalised(kin: Any, applied: Applied) -> np.ndarray:
    """Generalised loads (V, A, N, 3): force and moment about each link's origin."""
    q = kin.pose
    out = np.zeros(q.shape)
    for link, pos, _, f in applied.forces:
        r = pos - q[..., link, :2]
        out[..., link, :2] += f
        out[..., link, 2] += r[..., 0] * f[..., 1] - r[..., 1] * f[..., 0]
    for link, m in applied.moments:
        out[..., link, 2] += m
    return out


def power(kin: Any, applied: Applied) -> np.ndarray:
    """Power (W) of the external loads, (V, A)."""
    w = kin.vel[..., 2]
    total = np.zeros(kin.valid_all.shape)
    for _, _, vel, f in applied.forces:
        total = total + np.sum(f * vel, -1)
    for link, m in applied.moments:
        total = total + m * w[..., link]
    return total


def resultant(applied: Applied, shape: tuple[int, ...]) -> np.ndarray:
    """Total external force and moment about the global origin, (V, A, 3)."""
    out = np.zeros(shape + (3,))
    for _, pos, _, f in applied.forces:
        out[..., :2] += f
        out[..., 2] += pos[..., 0] * f[..., 1] - pos[..., 1] * f[..., 0]
    for _, m in applied.moments:
        out[..., 2] += m
    return out
