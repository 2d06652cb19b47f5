"""Impact of a rocker turning about a fixed support on a tool (seed paper 004).

The rocker turns about its support O; the connecting rod is represented by a
point mass ``m_u`` at the rocker-rod joint N, moving with the rocker.  Its
striker hits the end face of a tool at rest at K; the face's normal is ``n``
and ``t`` (``n`` turned clockwise by 90 deg) lies in the face.  The impulse on
the rocker at K is ``S = S_n n + S_t t``; with friction through the impact
``S_t = phi S_n``, ``phi = +-f`` opposing the striker's sliding.  The angular
speed after the impact is ``omega_+ = -R omega_-`` (the paper's R).

Angular momentum about O of the rocker and the point mass, ``J_O = J + m_u |ON|^2``:

    J_O (omega_+ - omega_-) = (K - O) x S
    =>  S_n = -J_O omega_- (1 + R) / ((K - O) x (n + phi t))

Linear momentum, ``S_O`` the impulse of the support on the rocker:

    S_O = m_k dv_C + m_u dv_N - S,   dv_P = (omega_+ - omega_-) z x (P - O)

The support impulse vanishes when ``m_k (C - O) = -m_u (N - O) + z x (S / (omega_+ - omega_-))``,
which fixes the ideal centre of mass for a given ``J`` (the paper treats ``J`` as given).
The energy lost is ``J_O omega_-^2 (1 - R^2) / 2``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from linkwork.errors import LinkworkError


def _cross(a: np.ndarray, b: np.ndarray) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def _zcross(w: float, r: np.ndarray) -> np.ndarray:
    """``w z x r``."""
    return np.array([-w * r[1], w * r[0]])


@dataclass(frozen=True)
class RockerImpact:
    """Result of :func:`rocker_impact`; vectors in global axes, N s.

    Attributes
    ----------
    impulse : ndarray (2,)
        The impulse of the tool on the rocker at K.
    support_impulse : ndarray (2,)
        The impulse of the support O on the rocker.
    omega_before, omega_after : float
        Angular speed of the rocker, rad/s, counter-clockwise positive.
    energy_loss : float
        J.
    ideal_com : ndarray (2,)
        Centre of mass of the rocker at which the support impulse vanishes (rod mass included).
    ideal_com_without_rod : ndarray (2,)
        The same with the rod's mass left out (``m_u = 0``).
    phi : float
        ``S_t / S_n``: +-f, opposing the sliding.
    sliding : float
        Tangential velocity of the striker at K before the impact, m/s (along ``t``).
    inertia : float
        ``J_O = J + m_u |ON|^2``, kg m^2.
    """

    impulse: np.ndarray
    support_impulse: np.ndarray
    omega_before: float
    omega_after: float
    energy_loss: float
    ideal_com: np.ndarray
    ideal_com_without_rod: np.ndarray
    phi: float
    sliding: float
    inertia: float

    def as_dict(self) -> dict[str, Any]:
        def xy(v: np.ndarray) -> dict[str, float]:
            return {"x": float(v[0]), "y": float(v[1])}

        return {
            "impulse": xy(self.impulse),
            "support_impulse": {"O": xy(self.support_impulse)},
            "omega_before": self.omega_before,
            "omega_after": self.omega_after,
            "energy_loss": self.energy_loss,
            "ideal_com": xy(self.ideal_com),
            "ideal_com_without_rod": xy(self.ideal_com_without_rod),
            "phi": self.phi,
            "sliding_speed": self.sliding,
            "inertia_about_support": self.inertia,
        }


def rocker_impact(
    *,
    inertia: float,
    mass: float,
    com: npt.ArrayLike,
    impact_point: npt.ArrayLike,
    omega_before: float,
    restitution: float,
    friction: float = 0.0,
    support: npt.ArrayLike = (0.0, 0.0),
    rod_mass: float = 0.0,
    rod_joint: npt.ArrayLike = (0.0, 0.0),
    normal: npt.ArrayLike = (0.0, 1.0),
    slip: float | None = None,
) -> RockerImpact:
    """The impact of a rocker on a tool at rest, by the impulse-momentum equations.

    Parameters
    ----------
    inertia : float
        Moment of inertia of the rocker about its support, kg m^2.
    mass : float
        Mass of the rocker, kg.
    com, impact_point, support, rod_joint : (x, y)
        Centre of mass C, impact point K, support O, rocker-rod joint N, m.
    omega_before : float
        Angular speed before the impact, rad/s, counter-clockwise positive; it must carry the
        striker towards the tool (against ``normal``).
    restitution : float
        ``R = -omega_after / omega_before``.
    friction : float
        ``f``: the tangential impulse is ``f`` times the normal one, against the sliding.
    rod_mass : float
        The connecting rod's mass reduced to N, kg.
    normal : (x, y)
        Normal of the tool's end face, pointing out of the tool (towards the striker).
    slip : float, optional
        Direction (+1 or -1, along ``t``) the striker slides in, for the case where it does not
        slide before the impact (K on the line through O along the normal): there the friction
        impulse is indeterminate (it depends on the clearance in the support); default -1, which
        with the paper's axes (the tool below, ``normal = (0, 1)``, the rocker turning clockwise)
        is the choice of its equation (10), the limit of ``y_K -> 0`` from below.

    Returns
    -------
    RockerImpact
        The impulse at the tool (N s), the impulse in the support, the rocker's speed after (rad/s), the
        energy lost (J) and the centre of percussion that would free the support.

    Examples
    --------
    >>> import linkwork as lw
    >>> r = lw.rocker_impact(inertia=0.30, mass=6.0, com=(0.16, 0.01), impact_point=(0.30, -0.02),
    ...                      omega_before=-30.0, restitution=0.4, friction=0.15,
    ...                      rod_mass=1.2, rod_joint=(0.10, 0.02), normal=(0.0, 1.0))
    >>> round(float(r.omega_after), 3)  # rad/s: R = 0.4 of the 30 rad/s
    12.0
    """
    o, c, k, nj = (np.asarray(v, dtype=float) for v in (support, com, impact_point, rod_joint))
    n = _unit(normal)
    t = np.array([n[1], -n[0]])
    if not (inertia > 0 and mass > 0 and rod_mass >= 0 and friction >= 0 and 0 <= restitution <= 1):
        raise LinkworkError("expected inertia > 0, mass > 0, rod mass >= 0, friction >= 0 and 0 <= R <= 1")
    rk, rn, rc = k - o, nj - o, c - o
    vk = _zcross(omega_before, rk)
    if not float(vk @ n) < 0:
        raise LinkworkError(
            f"the striker does not move towards the tool: its velocity at K along the face normal is "
            f"{float(vk @ n):.6g} m/s (turn the other way, or give the normal out of the tool)"
        )
    sliding = float(vk @ t)
    # the normal impulse pushes the striker out (S_n > 0); friction opposes the sliding
    phi = -friction * sliding_direction(sliding, float(1e-12 * np.linalg.norm(vk)), slip)
    j_o = inertia + rod_mass * float(rn @ rn)
    dw = -(1.0 + restitution) * omega_before
    arm = _cross(rk, n + phi * t)  # of the sign of rk x n, which the approach makes non-zero
    s_n = j_o * dw / arm  # > 0: friction against the sliding only adds to the arm of the normal impulse
    impulse = s_n * (n + phi * t)
    support_impulse = mass * _zcross(dw, rc) + rod_mass * _zcross(dw, rn) - impulse

    def ideal(m_u: float) -> np.ndarray:
        # m_k (C - O) such that S_O = 0: z x (m_k rc) = S / dw - m_u z x rn
        j = inertia + m_u * float(rn @ rn)
        s = (j * dw / arm) * (n + phi * t)
        need = s / dw - m_u * _zcross(1.0, rn)  # = z x (m_k rc)
        return o + np.array([need[1], -need[0]]) / mass

    return RockerImpact(
        impulse,
        support_impulse,
        float(omega_before),
        float(-restitution * omega_before),
        0.5 * j_o * omega_before**2 * (1 - restitution**2),
        ideal(rod_mass),
        ideal(0.0),
        phi,
        sliding,
        j_o,
    )


def _unit(normal: npt.ArrayLike) -> np.ndarray:
    """The unit vector along ``normal`` ``(2,)``."""
    n = np.asarray(normal, dtype=float)
    if not np.linalg.norm(n) > 0:
        raise LinkworkError("normal: expected a non-zero vector")
    out: np.ndarray = n / np.linalg.norm(n)
    return out


def sliding_direction(sliding: float, tiny: float, slip: float | None = None) -> float:
    """The direction (+1 or -1 along the face) the striker slides in at the impact: its sliding speed's
    sign; where that is no more than ``tiny`` (it does not slide, and the friction impulse is
    indeterminate), ``slip``'s, by default -1."""
    if abs(sliding) > tiny:
        return math.copysign(1.0, sliding)
    return -1.0 if slip is None else math.copysign(1.0, slip)
