"""Links as bars: the axial force and the bending moment along each link, its stress, and its fatigue.

A link with two or more joints is a bar along the line between the two of its joints farthest apart (unit
``e``).  It carries the forces of its joints at their points and, at its centre of mass, the resultant of its
other loads (gravity, inertia, the file's external loads) with the couple that keeps their moment: the
inertia of a bar is spread along it, so the moment between the ends is approximate (a concentrated load at the
centre of mass bends it the more).  At a section ``s`` along the bar the part before it carries the loads
``F_k`` at ``r_k``, couples ``C_k``; the internal axial force (tension positive) and the bending moment are

    N(s) = -e . sum_{s_k < s} F_k,    M(s) = sum_{s_k < s} ((r_k - r_s) x F_k + C_k).

Both are piecewise linear between the loads, so their extremes are at the loads' points, which are the sections
read.  The stress at the two edges of a section of area ``A`` and section modulus ``W`` (bending in the
mechanism's plane): ``sigma = N / A +- M / W``.  Over the cycle each edge's stress ranges between its least and
largest: the amplitude ``sigma_a`` and mean ``sigma_m`` give the fatigue safety factor by the modified Goodman
line, ``n = 1 / (sigma_a / sigma_-1 + max(sigma_m, 0) / R_m)``, with the steel's endurance limit ``sigma_-1``
(reversed bending, polished; no factors of size, surface or notch are applied: give them in the safety
factor asked) and tensile strength ``R_m``.  Without a section in the file, the least round bar for the
allowed stress ``R_e / S``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.kinetostatics.reaction_forces import Forces
from linkwork.sizing.common import Table
from linkwork.sizing.pin_shear import Steel
from linkwork.spec.part_checks import SECTION_DIMENSIONS


def section_properties(shape: str, dims: Mapping[str, float]) -> tuple[float, float]:
    """Area (m^2) and section modulus in bending (m^3) of a section: ``round`` (``d``), ``rectangle`` (``b``
    across, ``h`` in the plane), ``tube`` (``d`` outside, ``t`` wall), ``I`` (``h`` depth in the plane, ``b``
    flange width, ``tw`` web, ``tf`` flange thickness).

    Raises
    ------
    LinkworkError
        An unknown shape or a missing dimension.
    """
    need = SECTION_DIMENSIONS  # the file's sections are checked where it is read (linkwork.spec.part_checks)
    if shape not in need:
        raise LinkworkError(f'section: one of {", ".join(need)}, got "{shape}"')
    lack = [k for k in need[shape] if not dims.get(k)]
    if lack:
        raise LinkworkError(f"section {shape}: give {', '.join(lack)}")
    if shape == "round":
        d = dims["d"]
        return math.pi * d**2 / 4, math.pi * d**3 / 32
    if shape == "rectangle":
        b, h = dims["b"], dims["h"]
        return b * h, b * h**2 / 6
    if shape == "tube":
        d, t = dims["d"], dims["t"]
        di = d - 2 * t
        return math.pi * (d**2 - di**2) / 4, math.pi * (d**4 - di**4) / (32 * d)
    h, b, tw, tf = dims["h"], dims["b"], dims["tw"], dims["tf"]
    hw = h - 2 * tf
    inertia = (b * h**3 - (b - tw) * hw**3) / 12
    return 2 * b * tf + tw * hw, inertia / (h / 2)


@dataclass(frozen=True)
class Bar:
    """One link as a bar (SI): the internal forces at the worst sample and the stresses of its section."""

    link: str
    ends: tuple[str, str]
    length: float
    section: str
    area: float
    modulus: float
    given: bool
    moment_max: float
    moment_phi: float
    moment_at: float  # distance from the first end, m
    axial_at_moment: float
    axial_max: float  # the largest |N|
    axial_phi: float
    stress_max: float
    stress_phi: float
    amplitude: float
    mean: float
    fatigue: float  # Goodman safety factor


@dataclass(frozen=True)
class Bars:
    bars: tuple[Bar, ...]
    steel: Steel
    safety: float

    def table(self) -> Table:
        return Table(
            f"Links as bars ({self.steel.name}: R_e {self.steel.yield_strength / 1e6:g} MPa, R_m "
            f"{self.steel.tensile / 1e6:g} MPa, sigma_-1 {self.steel.endurance / 1e6:g} MPa; S = {self.safety:g})",
            (
                "link",
                "ends",
                "L [mm]",
                "section",
                "M max [kN m]",
                "M at phi [deg]",
                "M at s [mm]",
                "N there [kN]",
                "N max [kN]",
                "N at phi [deg]",
                "sigma max [MPa]",
                "sigma at phi [deg]",
                "sigma_a [MPa]",
                "sigma_m [MPa]",
                "Goodman n",
            ),
            tuple(
                (
                    b.link,
                    "-".join(b.ends),
                    b.length * 1e3,
                    b.section,
                    b.moment_max / 1e3,
                    b.moment_phi,
                    b.moment_at * 1e3,
                    b.axial_at_moment / 1e3,
                    b.axial_max / 1e3,
                    b.axial_phi,
                    b.stress_max / 1e6,
                    b.stress_phi,
                    b.amplitude / 1e6,
                    b.mean / 1e6,
                    b.fatigue,
                )
                for b in self.bars
            ),
            "links",
        )

    def record(self) -> dict[str, Any]:
        return {"steel": self.steel.name, "safety": self.safety, "links": self.table().record()}


def _loads_on(f: Forces, link: int) -> tuple[list[str], np.ndarray, np.ndarray, np.ndarray]:
    """The joints of ``link``, and its loads over the samples (first variant): points ``(A, K, 2)``, forces
    ``(A, K, 2)`` and couples ``(A, K)``: the joints' first (the drive's torque on the link it drives a couple at its
    joint), the rest at the centre of mass last."""
    mech, kin = f.mechanism, f.kinematics
    name = mech.link_names[link]
    joints, points = [], []
    for k in range(mech.n_pairs):
        a, b = (int(i) for i in mech.pair_links[k])
        if link not in (a, b) or mech.pair_joint[k] in joints:
            continue
        p = int(mech.pair_points[k, 0 if a == link else 1])
        if p < 0:
            p = int(mech.pair_points[k, 1])
        joints.append(mech.pair_joint[k])
        pos = kin.position(mech.point_names[p])
        points.append(pos[0] if pos.ndim == 3 else pos)
    force = f.reactions(joints, [name] * len(joints))
    force = force[0] if force.ndim == 4 else force
    loads = f.loads
    total = (loads.applied + loads.inertia)[0, :, link]  # (A, 3) about the link's origin
    com = loads.com[0, :, link]
    origin = kin.pose[0][:, link, :2]
    couple = total[:, 2] - _cross(com - origin, total[:, :2])
    pts = np.concatenate([np.stack(points, 1), com[:, None]], 1)
    forces = np.concatenate([force, total[:, None, :2]], 1)
    joint_couples = np.zeros(force.shape[:2])
    if mech.n_drives == 1:  # the drive's torque on its driven link, at its joint
        kd = int(mech.drive_pair[0])
        torque = np.asarray(f.driving_torque, dtype=float)
        torque = torque[0] if torque.ndim == 2 else torque
        sign = 1.0 if int(mech.pair_links[kd, 1]) == link else -1.0 if int(mech.pair_links[kd, 0]) == link else 0.0
        if sign and mech.pair_joint[kd] in joints:
            joint_couples[:, joints.index(mech.pair_joint[kd])] = sign * torque
    couples = np.concatenate([joint_couples, couple[:, None]], 1)
    return joints, pts, forces, couples


def _cross(r: np.ndarray, f: np.ndarray) -> np.ndarray:
    return r[..., 0] * f[..., 1] - r[..., 1] * f[..., 0]


def internal_forces(points: np.ndarray, forces: np.ndarray, couples: np.ndarray, ends: tuple[int, int]):
    """Axial force ``(A, K)`` and bending moment ``(A, K)`` just past each load (sections at the loads' points,
    taken in order along the bar from load ``ends[0]`` to load ``ends[1]``), and the sections' distances
    ``(A, K)``; see the module."""
    e = points[:, ends[1]] - points[:, ends[0]]
    e = e / np.linalg.norm(e, axis=-1, keepdims=True)
    s = np.einsum("akc,ac->ak", points - points[:, ends[0]][:, None], e)  # (A, K)
    order = np.argsort(s, axis=1, kind="stable")
    s = np.take_along_axis(s, order, 1)
    pts = np.take_along_axis(points, order[..., None], 1)
    fs = np.take_along_axis(forces, order[..., None], 1)
    cs = np.take_along_axis(couples, order, 1)
    cum_f = np.cumsum(fs, axis=1)  # the loads up to and including each
    axial = -np.einsum("akc,ac->ak", cum_f, e)
    # moment about section i of the loads 0..i: sum (r_k - r_i) x F_k + C_k
    cum_rxf = np.cumsum(_cross(pts, fs), axis=1)
    moment = cum_rxf - _cross(pts, cum_f) + np.cumsum(cs, axis=1)
    return axial, moment, s


def bars(
    f: Forces,
    phi: np.ndarray,
    steel: Steel,
    *,
    safety: float = 2.0,
    sections: Mapping[str, tuple[str, Mapping[str, float]]] | None = None,
) -> Bars:
    """Every moving link with two or more joints as a bar (see the module); ``sections``: a link's section
    (shape, dimensions in m), else the least round bar."""
    mech = f.mechanism
    sections = dict(sections or {})
    names = [n for i, n in enumerate(mech.link_names) if i and not mech.link_virtual[i]]
    wrong = [f'section of "{n}": no such link ({", ".join(names)})' for n in sections if n not in names]
    if wrong:
        raise LinkworkError("\n".join(wrong))
    out = []
    for i, name in enumerate(mech.link_names):
        if i == 0 or mech.link_virtual[i]:
            continue
        joints, pts, forces, couples = _loads_on(f, i)
        if len(joints) < 2:
            continue
        n = len(joints)
        span = np.linalg.norm(pts[0, :n, None] - pts[0, None, :n], axis=-1)
        a, b = np.unravel_index(int(np.argmax(span)), span.shape)
        if not span[a, b] > 0:  # its joints at one point (a slide's pin and guide): no bar
            continue
        out.append(
            _bar(
                name,
                (joints[a], joints[b]),
                float(span[a, b]),
                internal_forces(pts, forces, couples, (int(a), int(b))),
                phi,
                steel,
                safety,
                sections.get(name),
            )
        )
    return Bars(tuple(out), steel, safety)


def _stresses(axial: np.ndarray, moment: np.ndarray, area: float, modulus: float) -> np.ndarray:
    """The stress at the two edges, ``(2, A, K)``."""
    return np.stack([axial / area + moment / modulus, axial / area - moment / modulus])


def _least_round(axial: np.ndarray, moment: np.ndarray, allowed: float) -> float:
    lo, hi = 1e-4, 10.0
    for _ in range(100):
        d = math.sqrt(lo * hi)
        area, modulus = section_properties("round", {"d": d})
        if np.nanmax(np.abs(_stresses(axial, moment, area, modulus))) > allowed:
            lo = d
        else:
            hi = d
    return hi


def _bar(
    name: str,
    ends: tuple[str, str],
    length: float,
    internal: tuple[np.ndarray, np.ndarray, np.ndarray],
    phi: np.ndarray,
    steel: Steel,
    safety: float,
    given: tuple[str, Mapping[str, float]] | None,
) -> Bar:
    """The bar ``name`` between its ``ends`` under its ``internal`` forces (:func:`internal_forces`: axial force,
    bending moment, and where along it), sized of ``steel`` at ``safety``, or the file's section ``given``."""
    axial, moment, s = internal
    if given is not None:
        shape, dims = given
        area, modulus = section_properties(shape, dims)
        label = shape + " " + " x ".join(f"{k} {v * 1e3:g}" for k, v in dims.items() if v) + " mm"
    else:
        d = _least_round(axial, moment, steel.yield_strength / safety)
        area, modulus = section_properties("round", {"d": d})
        label = f"least round d {d * 1e3:.4g} mm"
    am = np.abs(moment)
    ia, ik = np.unravel_index(int(np.nanargmax(am)), am.shape)
    na = np.abs(axial)
    ja, _ = np.unravel_index(int(np.nanargmax(na)), na.shape)
    sigma = _stresses(axial, moment, area, modulus)  # (2, A, K)
    ea, sa, sk = np.unravel_index(int(np.nanargmax(np.abs(sigma))), sigma.shape)
    amp = (np.nanmax(sigma, axis=1) - np.nanmin(sigma, axis=1)) / 2  # (2, K)
    mean = (np.nanmax(sigma, axis=1) + np.nanmin(sigma, axis=1)) / 2
    usage = amp / steel.endurance + np.maximum(mean, 0.0) / steel.tensile
    e2, k2 = np.unravel_index(int(np.nanargmax(usage)), usage.shape)
    fatigue = 1.0 / float(usage[e2, k2]) if usage[e2, k2] > 0 else math.inf
    peak = float(abs(sigma[ea, sa, sk]))
    return Bar(
        name,
        ends,
        length,
        label,
        area,
        modulus,
        given is not None,
        float(am[ia, ik]),
        float(phi[ia]),
        float(s[ia, ik]),
        float(axial[ia, ik]),
        float(na.max()),
        float(phi[ja]),
        peak,
        float(phi[sa]),
        float(amp[e2, k2]),
        float(mean[e2, k2]),
        fatigue,
    )
