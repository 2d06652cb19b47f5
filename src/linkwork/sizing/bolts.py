"""Foundation bolts: the preload that keeps the joint between the machine's bed and its foundation closed and
from sliding over the whole cycle, and the bolt size from the thread's stress.

The bed is taken as rigid on a rigid foundation, the bolts at ``(x_i, y_i)`` in the plane of the mechanism (the
bed's plane through their centre ``c``).  The machine puts on the foundation the force ``(F_x, F_y)`` (``F_y``
up: it lifts the bed) and the moment ``M`` about the origin (:attr:`linkwork.kinetostatics.Forces.foundation`);
about ``c`` the moment is ``M_c = M - (x_c F_y - y_c F_x)``.  The force that would open the joint at bolt ``i``
(the lift the bolt must hold down, linear across the bed):

    F_i = F_y / n + M_c (x_i - x_c) / sum_j (x_j - x_c)^2.

With the safety factor ``S``: the joint stays closed while the preload ``F_V >= S max F_i``; it does not slide
while friction ``mu`` over the clamping force left, ``mu (n F_V - F_y)``, holds ``S |F_x|``:
``F_V >= (S |F_x| / mu + F_y) / n``.  The preload is the larger over the cycle.  The bolt carries the preload
and the share ``Phi`` (the load factor of the joint's stiffnesses) of its working force: ``F_b = F_V + Phi max
F_i``; tightened by a torque, its equivalent stress is ``1.3 F_b / A_s`` (the torsion of tightening), so the
thread needs the stress area ``A_s >= 1.3 F_b S_b / R_e`` of the bolt's property class (yield ``R_e``, safety
``S_b``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.errors import LinkworkError
from linkwork.sizing.common import Table, bundled


@dataclass(frozen=True)
class BoltResult:
    """The bolts of the pattern (SI): each one's largest opening force and where, the preload, the bolt."""

    points: np.ndarray  # (n, 2)
    opening: np.ndarray  # (n,) largest F_i over the cycle, N
    opening_phi: np.ndarray  # (n,) deg
    preload: float  # N per bolt
    decided_by: str  # "opening", "sliding", or why there is no preload
    decided_phi: float
    bolt_force: float
    area_needed: float  # m^2
    thread: str
    thread_area: float
    bolt_class: str
    safety: float
    friction: float
    load_factor: float
    bolt_safety: float

    def tables(self) -> list[Table]:
        each = zip(self.points, self.opening, self.opening_phi, strict=True)
        rows = tuple(
            (f"{i + 1}", float(x * 1e3), float(y * 1e3), float(f / 1e3), float(a))
            for i, ((x, y), f, a) in enumerate(each)
        )
        per = Table(
            "Foundation bolts: the largest force opening the joint at each",
            ("bolt", "x [mm]", "y [mm]", "F open max [kN]", "at phi [deg]"),
            rows,
            "bolts",
        )
        summary = Table(
            f"Foundation bolts: preload (S = {self.safety:g}, friction {self.friction:g}) and size (class "
            f"{self.bolt_class}, S_b = {self.bolt_safety:g}, load factor {self.load_factor:g})",
            ("quantity", "value", "unit"),
            (
                ("preload per bolt", self.preload / 1e3, "kN"),
                ("decided by", self.decided_by, ""),
                ("  at phi", self.decided_phi, "deg"),
                ("largest bolt force", self.bolt_force / 1e3, "kN"),
                ("stress area needed", self.area_needed * 1e6, "mm^2"),
                ("thread", self.thread, ""),
                ("its stress area", self.thread_area * 1e6, "mm^2"),
            ),
            "preload",
        )
        return [per, summary]

    def record(self) -> dict[str, Any]:
        per, _ = self.tables()
        return {
            "bolts": per.record(),
            "preload_kN": self.preload / 1e3,
            "decided_by": self.decided_by,
            "decided_phi_deg": self.decided_phi,
            "bolt_force_kN": self.bolt_force / 1e3,
            "area_needed_mm2": self.area_needed * 1e6,
            "thread": self.thread,
            "thread_area_mm2": self.thread_area * 1e6,
            "bolt_class": self.bolt_class,
            "safety": self.safety,
            "friction": self.friction,
            "load_factor": self.load_factor,
            "bolt_safety": self.bolt_safety,
        }


def opening_forces(foundation: np.ndarray, points: np.ndarray) -> np.ndarray:
    """The force opening the joint at each bolt, ``(A, n)`` N, of the foundation loads ``(A, 3)`` (see the module)."""
    pts = np.asarray(points, dtype=float)
    n = len(pts)
    c = pts.mean(axis=0)
    dx = pts[:, 0] - c[0]
    fx, fy, m = foundation[:, 0], foundation[:, 1], foundation[:, 2]
    mc = m - (c[0] * fy - c[1] * fx)
    arm = float(np.sum(dx**2))
    share = dx / arm if arm > 0 else np.zeros(n)
    return fy[:, None] / n + mc[:, None] * share[None, :]


def size_bolts(
    foundation: np.ndarray,
    phi: np.ndarray,
    points: np.ndarray,
    *,
    bolt_class: str = "5.6",
    safety: float = 1.5,
    friction: float = 0.2,
    load_factor: float = 0.25,
    bolt_safety: float = 1.5,
) -> BoltResult:
    """Preload and size of the foundation bolts at ``points`` ``(n, 2)`` m for the foundation loads ``(A, 3)``
    at the crank angles ``phi`` (deg), of the bundled threads and bolt classes; see the module.

    Raises
    ------
    LinkworkError
        Fewer than two bolts, bolts all at one x (no lever against the moment), an unknown class, no thread
        of the catalogue strong enough, or a factor out of range.
    """
    threads, classes = bundled("threads.csv"), bundled("bolt_classes.csv")
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    problems = []
    if len(pts) < 2 or np.ptp(pts[:, 0]) <= 0:
        problems.append("bolts: give at least two bolts at different x (the bed must hold the moment)")
    if bolt_class not in classes.names:
        problems.append(f'bolt class "{bolt_class}": one of {", ".join(classes.names)}')
    for name, value in (("safety", safety), ("friction", friction), ("bolt safety", bolt_safety)):
        if not value > 0:
            problems.append(f"bolts: {name} must be positive, got {value}")
    if not 0 <= load_factor < 1:
        problems.append(f"bolts: the load factor is in [0, 1), got {load_factor}")
    if problems:
        raise LinkworkError("\n".join(problems))
    f = opening_forces(foundation, pts)
    k = np.nanargmax(f, axis=0)
    opening = f[k, np.arange(len(pts))]
    n = len(pts)
    keep_closed = safety * np.nanmax(f, axis=1)
    no_slip = (safety * np.abs(foundation[:, 0]) / friction + foundation[:, 1]) / n
    need = np.fmax(keep_closed, no_slip)
    i = int(np.nanargmax(need))
    preload = max(float(need[i]), 0.0)
    decided = "opening" if keep_closed[i] >= no_slip[i] else "sliding"
    if not need[i] > 0:
        decided = "nothing: the loads never lift the bed nor push it sideways beyond its friction"
    bolt_force = preload + load_factor * max(float(np.nanmax(opening)), 0.0)
    r_e = classes.columns["yield"][classes.names.index(bolt_class)]
    area = 1.3 * bolt_force * bolt_safety / r_e
    areas = threads.columns["stress area"]
    fits = np.flatnonzero(areas >= area)
    if not len(fits):
        raise LinkworkError(
            f"bolts: a stress area of {area * 1e6:.4g} mm^2 is needed, more than the largest thread of "
            f"{threads.source} ({areas.max() * 1e6:.4g} mm^2): more bolts, or a stronger class"
        )
    j = int(fits[np.argmin(areas[fits])])
    return BoltResult(
        pts,
        opening,
        phi[k],
        preload,
        decided,
        float(phi[i]),
        bolt_force,
        area,
        threads.names[j],
        float(areas[j]),
        bolt_class,
        safety,
        friction,
        load_factor,
        bolt_safety,
    )
