"""Diagrams against the crank angle: motion of a point, link angles, driving torque, foundation
loads, joint-force hodographs, and the machine-dynamics diagrams (reduced inertia, Wittenbauer,
speed over the cycle)."""

from __future__ import annotations

from typing import Any

import numpy as np


def _figure(rows: int = 1, height: float = 3.0) -> Any:
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7, height * rows), layout="constrained")
    return fig, [fig.add_subplot(rows, 1, i + 1) for i in range(rows)]


def _deg(kin: Any) -> np.ndarray:
    return np.degrees(kin.angles)


def motion_diagram(kin: Any, point: str) -> Any:
    """Position, velocity and acceleration (x and y components) of ``point`` over the crank angle."""
    fig, axes = _figure(3)
    phi = _deg(kin)
    for ax, (what, data, unit) in zip(
        axes,
        (("position", kin.position(point), "m"), ("velocity", kin.velocity(point), "m/s"),
         ("acceleration", kin.acceleration(point), "m/s²")),
        strict=True,
    ):  # fmt: skip
        d = data[0] if kin.variants else data
        ax.plot(phi, d[:, 0], label="x")
        ax.plot(phi, d[:, 1], label="y")
        ax.set_ylabel(f"{what}, {unit}")
        ax.grid(True, lw=0.3)
        ax.legend(loc="upper right", fontsize=8)
    axes[0].set_title(f"{kin.mechanism.name}: point {point}")
    axes[-1].set_xlabel("crank angle, °")
    return fig


def link_angles(kin: Any) -> Any:
    """Angle, angular velocity and angular acceleration of every moving link."""
    from linkwork.io.motion_tables import moving_links

    fig, axes = _figure(3)
    phi = _deg(kin)
    for name, i in moving_links(kin.mechanism):
        for ax, data in zip(axes, (np.degrees(np.unwrap(kin.angle(i))), kin.omega(i), kin.epsilon(i)), strict=True):
            ax.plot(phi, data[0] if kin.variants else data, label=name)
    for ax, label in zip(axes, ("angle, °", "ω, rad/s", "ε, rad/s²"), strict=True):
        ax.set_ylabel(label)
        ax.grid(True, lw=0.3)
    axes[0].legend(fontsize=8, ncol=3)
    axes[-1].set_xlabel("crank angle, °")
    return fig


def torque_diagram(forces: Any) -> Any:
    """The driving torque over the crank angle, with the power-balance check."""
    fig, (ax,) = _figure()
    phi = _deg(forces.kinematics)
    ax.plot(phi, forces.driving_torque, label="driving torque")
    check = forces.torque_power_all[0, :, 0] if forces.mechanism.n_drives == 1 else None
    if check is not None and np.isfinite(check).any():
        ax.plot(phi, check, ls=":", color="black", label="by the power balance")
    ax.set_xlabel("crank angle, °")
    ax.set_ylabel("N m")
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=8)
    ax.set_title(f"{forces.mechanism.name}: driving torque")
    return fig


def foundation_diagram(forces: Any) -> Any:
    """Forces (x, y) and moment the machine puts on its foundation, and the shaking force."""
    fig, (top, bottom) = _figure(2)
    phi = _deg(forces.kinematics)
    found = forces.foundation
    top.plot(phi, found[:, 0], label="Fx (bolt shear)")
    top.plot(phi, found[:, 1], label="Fy (+ pulls the bolts)")
    top.plot(phi, np.hypot(*forces.shaking_force.T), ls="--", label="|shaking force|")
    top.set_ylabel("N")
    top.legend(fontsize=8)
    bottom.plot(phi, found[:, 2], label="moment about the origin")
    bottom.plot(phi, forces.shaking_moment, ls="--", label="shaking moment")
    bottom.set_ylabel("N m")
    bottom.legend(fontsize=8)
    for ax in (top, bottom):
        ax.grid(True, lw=0.3)
    bottom.set_xlabel("crank angle, °")
    top.set_title(f"{forces.mechanism.name}: foundation")
    return fig


def hodograph(forces: Any, joint: str) -> Any:
    """Polar diagram of the force in a joint (the first-named link on the second) over the cycle."""
    fig, (ax,) = _figure(height=6)
    f = forces.reaction(joint)
    ax.plot(f[:, 0], f[:, 1], lw=1)
    ax.plot([0], [0], "k+")
    for i in np.linspace(0, len(f), 12, endpoint=False).astype(int):
        ax.annotate(f"{np.degrees(forces.angles[i]) % 360:.0f}°", f[i], fontsize=7)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("Fx, N")
    ax.set_ylabel("Fy, N")
    ax.grid(True, lw=0.3)
    ax.set_title(f"{forces.mechanism.name}: force in {joint}")
    return fig


def dynamics_diagrams(result: Any) -> Any:
    """Reduced inertia and load moment, Wittenbauer's diagram, and the crank speed over the steady
    cycle of a :func:`linkwork.dynamics` result."""
    from matplotlib.figure import Figure

    from linkwork.machine import wittenbauer

    red = result.reduced
    fig = Figure(figsize=(10, 7), layout="constrained")
    a1, a2 = fig.add_subplot(2, 2, 1), fig.add_subplot(2, 2, 2)
    a3 = fig.add_subplot(2, 1, 2)
    psi = np.degrees(red.psi)
    a1.plot(psi, red.inertia, label="J, kg m²")
    a1b = a1.twinx()
    a1b.plot(psi, red.load, color="tab:red", lw=0.8, label="M, N m")
    a1.set_xlabel("crank turning angle, °")
    a1.set_ylabel("reduced inertia, kg m²")
    a1b.set_ylabel("reduced load moment, N m")
    j, e = wittenbauer(red)
    a2.plot(j, e, lw=1)
    a2.set_xlabel("reduced inertia J, kg m²")
    a2.set_ylabel("energy A, J")
    a2.set_title("Wittenbauer's diagram")
    t, turn, omega = result.motion.cycle()
    a3.plot(np.degrees(turn), omega * 30 / np.pi)
    a3.set_xlabel("turning angle in the steady cycle, °")
    a3.set_ylabel("crank speed, rpm")
    a3.set_title(f"steady cycle: δ = {result.delta:.4g}")
    for ax in (a1, a2, a3):
        ax.grid(True, lw=0.3)
    return fig
