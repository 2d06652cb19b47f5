"""Diagrams over the cycle: the kinematic diagrams of the working members, link angles, driving torque,
foundation loads, joint-force hodographs, and the machine-dynamics diagrams (reduced inertia and load
moment, Wittenbauer's diagram, the crank speed over the steady cycle); a run in time against time.

Every abscissa is the crank angle φ turned from position 0 (0 to 360°, as the 12 positions number the
cycle, :func:`linkwork.motion.analysis.from_position_0`); ``zero`` is the drive angle of position 0
(rad; default :func:`linkwork.motion.analysis.zero_angle`).  ``lang`` is ``"en"`` or ``"ru"``
(:mod:`linkwork.lang`).  Every function returns a matplotlib ``Figure`` with a constrained layout.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from linkwork.angles import unwrap
from linkwork.figures.sheet import decimal_commas, numbers
from linkwork.lang import t
from linkwork.motion.analysis import Output, coordinate, from_position_0, working, zero_angle
from linkwork.motion.kinematic_analysis import direction
from linkwork.zeros import magnitude, snap_zeros

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from linkwork.kinetostatics.reaction_forces import Forces
    from linkwork.machine.steady_cycle import Dynamics
    from linkwork.machine.timerun import Run
    from linkwork.motion.kinematic_analysis import Kinematics
    from linkwork.structure.model import Mechanism


def _figure(rows: int = 1, height: float = 2.6, width: float = 7.0) -> tuple[Figure, list[Axes]]:
    from matplotlib.figure import Figure

    fig = Figure(figsize=(width, 0.6 + height * rows), layout="constrained")
    axes = fig.subplots(rows, 1, sharex=True, squeeze=False)[:, 0]
    return fig, list(axes)


def _one(a: np.ndarray, variants: bool) -> np.ndarray:
    """The first variant of a result with variants; the array itself otherwise."""
    return a[0] if variants else a


def _abscissa(angles: np.ndarray, zero: float, sign: float, whole: bool | None = None) -> tuple[np.ndarray, np.ndarray]:
    """φ in degrees, ascending, and the order of the samples along it.  The samples of a whole turn
    (``whole``; by default: equal steps over the turn) are continued periodically by one sample beyond each
    end, so that a curve spans 0 to 360° whichever sample is nearest position 0."""
    phi = np.degrees(from_position_0(angles, zero, sign))
    order = np.argsort(phi, kind="stable")
    if whole is None:
        steps = np.diff(angles)
        whole = len(angles) > 2 and np.allclose(steps, steps[0]) and abs(abs(steps[0]) * len(angles) - 2 * np.pi) < 1e-9
    if not whole:
        return phi[order], order
    ext = np.concatenate([order[-1:], order, order[:1]])
    return np.concatenate([phi[order[-1:]] - 360.0, phi[order], phi[order[:1]] + 360.0]), ext


def _crank_axis(ax: Axes, lang: str) -> None:
    ax.set_xlim(0, 360)
    ax.set_xticks(np.arange(0, 361, 30))
    ax.set_xlabel(t("axis.crank_angle", lang))


def _grid(ax: Axes) -> None:
    ax.grid(True, lw=0.3, alpha=0.7)


def _legend(ax: Axes, **kw: Any) -> None:
    ax.legend(fontsize=8, framealpha=0.85, **kw)


def _zero_of(kin: Kinematics, zero: float | None) -> float:
    return zero_angle(kin.mechanism) if zero is None else zero


def _scale(values: np.ndarray, unit: str, kilo: str) -> tuple[float, str]:
    """Factor and unit to show forces (moments) in: kilo-units where the largest is 10,000 or more."""
    big = np.nanmax(np.abs(values)) if np.isfinite(values).any() else 0.0
    return (1e-3, kilo) if big >= 1e4 else (1.0, unit)


def member_label(mech: Mechanism, out: Output, lang: str) -> str:
    """``knife_upper (guide_E)`` for a slider: its link and its joint; ``output`` for a rocker."""
    link = str(mech.link_names[out.link])
    return t("member.slider", lang, link=link, joint=out.name) if out.kind == "slider" else link


def kinematic_diagrams(kin: Kinematics, zero: float | None = None, lang: str = "en") -> Figure:
    """Displacement, velocity and acceleration of the working members (:func:`working`) over the cycle: a
    slider's along its guide's axis from position 0 (mm, m/s, m/s²), a rocker's angle from position 0 (°),
    angular velocity and acceleration (rad/s, rad/s²).

    Parameters
    ----------
    kin : Kinematics
        A kinematics result (:func:`linkwork.kinematics`).
    zero : float, optional
        The drive angle of position 0, rad, the origin of the diagrams' angle; default position 0 as the
        report numbers it (the working member at the high end of its stroke).
    lang : str, default "en"
        The language of the texts, ``"en"`` or ``"ru"`` (:mod:`linkwork.lang`).
    """
    mech = kin.mechanism
    members = working(mech)
    fig, axes = _figure(3)
    zero = _zero_of(kin, zero)
    phi, order = _abscissa(kin.angles, zero, direction(mech))
    start = _at(mech, zero)
    for out in members:
        s, v, a = (x[0, order] for x in coordinate(kin, out))
        d = s - coordinate(start, out)[0][0, 0]  # from position 0
        if out.kind == "rocker":
            d = np.degrees(d - 2 * np.pi * np.round(np.nanmedian(d) / (2 * np.pi)))
        for ax, y in zip(axes, (d * 1000 if out.kind == "slider" else d, v, a), strict=True):
            ax.plot(phi, y, lw=1.3, label=member_label(mech, out, lang))
    kind = members[0].kind if members else "slider"
    keys = ("s", "v", "a") if kind == "slider" else ("psi", "omega", "epsilon")
    for ax, key in zip(axes, keys, strict=True):
        ax.set_ylabel(t(f"axis.member.{key}", lang), fontsize=9)
        ax.axhline(0.0, color="0.4", lw=0.6)
        _grid(ax)
    if members:
        _legend(axes[0], loc="best")
    _crank_axis(axes[-1], lang)
    fig.suptitle(t("title.kinematic_diagrams", lang, name=mech.name), fontsize=11)
    return decimal_commas(fig, lang)


def _at(mech: Mechanism, angle: float) -> Kinematics:
    from linkwork.motion.kinematic_analysis import kinematics

    return kinematics(mech, np.array([angle]))


def motion_diagram(kin: Kinematics, point: str, zero: float | None = None, lang: str = "en") -> Figure:
    """Position, velocity and acceleration (x and y components) of ``point`` over the cycle.

    Parameters
    ----------
    kin : Kinematics
        A kinematics result (:func:`linkwork.kinematics`).
    point : str
        The point, a joint's name or ``link.point``.
    zero : float, optional
        The drive angle of position 0, rad, the origin of the diagrams' angle; default position 0 as the
        report numbers it (the working member at the high end of its stroke).
    lang : str, default "en"
        The language of the texts, ``"en"`` or ``"ru"`` (:mod:`linkwork.lang`).
    """
    fig, axes = _figure(3)
    phi, order = _abscissa(kin.angles, _zero_of(kin, zero), direction(kin.mechanism))
    series = (kin.position(point) * 1000, kin.velocity(point), kin.acceleration(point))
    for ax, data, key in zip(axes, series, ("position", "velocity", "acceleration"), strict=True):
        d = _one(data, kin.variants)[order]
        ax.plot(phi, d[:, 0], label="x")
        ax.plot(phi, d[:, 1], label="y")
        ax.set_ylabel(t(f"axis.point.{key}", lang), fontsize=9)
        _grid(ax)
        _legend(ax, loc="best")
    _crank_axis(axes[-1], lang)
    fig.suptitle(t("title.point", lang, name=kin.mechanism.name, point=point), fontsize=11)
    return decimal_commas(fig, lang)


def link_angles(kin: Kinematics, zero: float | None = None, lang: str = "en") -> Figure:
    """Angle (to the x axis, °), angular velocity and angular acceleration of every moving link that turns,
    but the crank (which turns uniformly): sliders that keep their angle are left out.

    Parameters
    ----------
    kin : Kinematics
        A kinematics result (:func:`linkwork.kinematics`).
    zero : float, optional
        The drive angle of position 0, rad, the origin of the diagrams' angle; default position 0 as the
        report numbers it (the working member at the high end of its stroke).
    lang : str, default "en"
        The language of the texts, ``"en"`` or ``"ru"`` (:mod:`linkwork.lang`).
    """
    from linkwork.motion.tables import moving_links

    mech = kin.mechanism
    fig, axes = _figure(3)
    phi, order = _abscissa(kin.angles, _zero_of(kin, zero), direction(mech))
    cranks = {int(b) for k in mech.drive_pair for b in mech.pair_links[k] if b != 0 and 0 in mech.pair_links[k]}
    speed = float(np.nanmax(np.abs(kin.rates[:, 0]), initial=0.0)) or 1.0  # the crank's
    for name, i in moving_links(mech):
        rates = (_one(kin.omega(i), kin.variants)[order], _one(kin.epsilon(i), kin.variants)[order])
        if i in cranks or not np.nanmax(np.abs(rates[0]), initial=0.0) > 1e-9 * speed:
            continue
        angle = np.degrees(unwrap(_one(kin.angle(i), kin.variants)[order]))
        angle -= 360.0 * np.round(angle[np.isfinite(angle)][:1].sum() / 360.0)  # the first valid one near 0
        for ax, y in zip(axes, (angle, *rates), strict=True):
            ax.plot(phi, y, lw=1.1, label=name)
    for ax, key in zip(axes, ("angle", "omega", "epsilon"), strict=True):
        ax.set_ylabel(t(f"axis.link.{key}", lang), fontsize=9)
        _grid(ax)
    if axes[0].lines:
        fig.legend(handles=axes[0].lines, loc="outside right upper", fontsize=8)
    _crank_axis(axes[-1], lang)
    fig.suptitle(t("title.link_angles", lang, name=mech.name), fontsize=11)
    return decimal_commas(fig, lang)


def torque_diagram(forces: Forces, zero: float | None = None, lang: str = "en") -> Figure:
    """The driving torque over the cycle, its mean, and the power balance's torque beside it.

    Parameters
    ----------
    forces : Forces
        A :func:`linkwork.forces` result over a turn.
    zero : float, optional
        The drive angle of position 0, rad, the origin of the diagrams' angle; default position 0 as the
        report numbers it (the working member at the high end of its stroke).
    lang : str, default "en"
        The language of the texts, ``"en"`` or ``"ru"`` (:mod:`linkwork.lang`).
    """
    mech = forces.mechanism
    fig, (ax,) = _figure(height=3.4)
    phi, order = _abscissa(forces.angles, _zero_of(forces.kinematics, zero), direction(mech))
    torque = np.asarray(forces.driving_torque)
    factor, unit = _scale(torque, "unit.Nm", "unit.kNm")
    ax.plot(phi, torque[order] * factor, lw=1.4, label=t("legend.driving_torque", lang))
    check = forces.torque_power_all[0, :, 0] if mech.n_drives == 1 else None
    if check is not None and np.isfinite(check).any():
        ax.plot(phi, check[order] * factor, ls=":", color="black", lw=1.2, label=t("legend.power_balance", lang))
    mean = float(snap_zeros(np.nanmean(torque), magnitude(torque)))  # a mean that is a round-off of zero: 0
    ax.axhline(
        mean * factor,
        color="tab:red",
        lw=0.9,
        ls="--",
        label=t("legend.mean", lang, value=numbers(f"{mean * factor:.4g}", lang)),
    )
    ax.set_ylabel(t("axis.torque", lang, unit=t(unit, lang)))
    _grid(ax)
    _legend(ax, loc="best")
    _crank_axis(ax, lang)
    ax.set_title(t("title.driving_torque", lang, name=mech.name), fontsize=11)
    return decimal_commas(fig, lang)


def foundation_diagram(forces: Forces, zero: float | None = None, lang: str = "en") -> Figure:
    """Forces (x, y) and moment the machine puts on its foundation, and the shaking force and moment.

    Parameters
    ----------
    forces : Forces
        A :func:`linkwork.forces` result over a turn.
    zero : float, optional
        The drive angle of position 0, rad, the origin of the diagrams' angle; default position 0 as the
        report numbers it (the working member at the high end of its stroke).
    lang : str, default "en"
        The language of the texts, ``"en"`` or ``"ru"`` (:mod:`linkwork.lang`).
    """
    mech = forces.mechanism
    fig, (top, bottom) = _figure(2, height=2.8)
    phi, order = _abscissa(forces.angles, _zero_of(forces.kinematics, zero), direction(mech))
    found = np.asarray(forces.foundation)[order]
    shaking = np.hypot(*np.asarray(forces.shaking_force)[order].T)
    f, funit = _scale(np.concatenate([found[:, :2].ravel(), shaking]), "unit.N", "unit.kN")
    top.plot(phi, found[:, 0] * f, label=t("legend.Fx", lang))
    top.plot(phi, found[:, 1] * f, label=t("legend.Fy", lang))
    top.plot(phi, shaking * f, ls="--", label=t("legend.shaking_force", lang))
    top.set_ylabel(t("axis.force", lang, unit=t(funit, lang)))
    moment = np.asarray(forces.shaking_moment)[order]
    m, munit = _scale(np.concatenate([found[:, 2], moment]), "unit.Nm", "unit.kNm")
    bottom.plot(phi, found[:, 2] * m, label=t("legend.foundation_moment", lang))
    bottom.plot(phi, moment * m, ls="--", label=t("legend.shaking_moment", lang))
    bottom.set_ylabel(t("axis.moment", lang, unit=t(munit, lang)))
    for ax in (top, bottom):
        _grid(ax)
        _legend(ax, loc="best")
    _crank_axis(bottom, lang)
    fig.suptitle(t("title.foundation", lang, name=mech.name), fontsize=11)
    return decimal_commas(fig, lang)


def hodograph(
    forces: Forces, joint: str, at: Forces | None = None, zero: float | None = None, lang: str = "en"
) -> Figure:
    """Polar diagram of the force in a joint (the first-named link on the second) over the cycle, with the
    12 positions marked and numbered: ``at`` is the forces at the 12 positions (position 0 first); without
    it, the samples of ``forces`` at 0, 30, 60, ... degrees from position 0, where it has them.

    Parameters
    ----------
    forces : Forces
        A :func:`linkwork.forces` result over a turn.
    joint : str
        The joint, by its name in the file.
    at : Forces, optional
        The forces at the twelve positions, position 0 first.
    zero : float, optional
        The drive angle of position 0, rad, the origin of the diagrams' angle; default position 0 as the
        report numbers it (the working member at the high end of its stroke).
    lang : str, default "en"
        The language of the texts, ``"en"`` or ``"ru"`` (:mod:`linkwork.lang`).
    """
    mech = forces.mechanism
    fig, (ax,) = _figure(height=5.4, width=6.4)
    f = np.asarray(forces.reaction(joint))
    factor, unit = _scale(f, "unit.N", "unit.kN")
    phi, order = _abscissa(forces.angles, _zero_of(forces.kinematics, zero), direction(mech))
    ax.plot(f[order, 0] * factor, f[order, 1] * factor, lw=1.1, color="tab:blue")
    ax.plot([0], [0], "k+", ms=9)
    marks = _marks(f, phi, order) if at is None else np.asarray(at.reaction(joint))
    marks = marks * factor
    ax.plot(marks[:, 0], marks[:, 1], "o", ms=3.5, color="tab:red", zorder=3)
    ax.set_aspect("equal", adjustable="datalim")
    ax.margins(0.12)
    ax.set_xlabel(t("axis.Fx", lang, unit=t(unit, lang)))
    ax.set_ylabel(t("axis.Fy", lang, unit=t(unit, lang)))
    _grid(ax)
    ax.set_title(t("title.hodograph", lang, name=mech.name, joint=joint), fontsize=11)
    place_numbers(ax, marks, list(range(len(marks))))
    return decimal_commas(fig, lang)


def _marks(f: np.ndarray, phi: np.ndarray, order: np.ndarray) -> np.ndarray:
    """The samples of ``f`` at the 12 positions (30° apart from position 0), NaN where none is within
    0.01°."""
    out = np.full((12, 2), np.nan)
    for j in range(12):
        near = int(np.argmin(np.abs(phi - 30.0 * j)))
        if abs(phi[near] - 30.0 * j) < 0.01:
            out[j] = f[order[near]]
    return out


def place_numbers(ax: Axes, points: np.ndarray, numbers: list[int], size: float = 8.0) -> list[Any]:
    """Number the ``points`` (data coordinates, ``(N, 2)``) so that no two labels cover each other: each
    label sits beside its point, away from the points' centre; points whose labels would cover each
    other share one label (``3-5, 8``) at the first of them.  Lays the figure out (without rendering)
    to measure the labels; returns the texts."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    ok = np.isfinite(points).all(axis=1)
    if not ok.any():
        return []
    fig = cast("Figure", ax.figure)
    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    fig.draw_without_rendering()
    renderer = canvas.get_renderer()
    screen = ax.transData.transform(np.where(ok[:, None], points, 0.0))
    centre = screen[ok].mean(axis=0)
    groups: list[list[int]] = []
    texts: list[Any] = []
    for i in np.flatnonzero(ok):
        text = _number(ax, points[i], screen[i] - centre, str(numbers[i]), size)
        box = text.get_window_extent(renderer)
        hit = next((g for g, other in enumerate(texts) if box.overlaps(other.get_window_extent(renderer))), None)
        if hit is None:
            groups.append([numbers[i]])
            texts.append(text)
            continue
        text.remove()
        groups[hit].append(numbers[i])
        texts[hit].set_text(_runs(groups[hit]))
    return _separate(texts, groups, renderer)


def _separate(texts: list[Any], groups: list[list[int]], renderer: Any) -> list[Any]:
    """Merge labels that cover each other after their texts grew, until none do."""
    merged = True
    while merged:
        merged = False
        for a in range(len(texts)):
            for b in range(a + 1, len(texts)):
                if texts[a].get_window_extent(renderer).overlaps(texts[b].get_window_extent(renderer)):
                    groups[a] += groups.pop(b)
                    texts.pop(b).remove()
                    texts[a].set_text(_runs(groups[a]))
                    merged = True
                    break
            if merged:
                break
    return texts


def _number(ax: Axes, point: np.ndarray, away: np.ndarray, label: str, size: float) -> Any:
    """A label beside ``point``, offset away from the centre (``away``: screen direction)."""
    norm = math.hypot(*away)
    u = away / norm if norm > 1e-9 else np.array([0.7, 0.7])
    ha = "left" if u[0] > 0.3 else "right" if u[0] < -0.3 else "center"
    va = "bottom" if u[1] > 0.3 else "top" if u[1] < -0.3 else "center"
    at = (float(point[0]), float(point[1]))
    return ax.annotate(label, at, xytext=(5 * u[0], 5 * u[1]), textcoords="offset points", fontsize=size, ha=ha, va=va)


def _runs(numbers: list[int]) -> str:
    """``[3, 4, 5, 8]`` as ``3-5, 8``."""
    nums = sorted(set(numbers))
    out: list[str] = []
    start = prev = nums[0]
    for n in [*nums[1:], None]:
        if n is not None and n == prev + 1:
            prev = n
            continue
        out.append(str(start) if start == prev else f"{start}\u2013{prev}" if prev > start + 1 else f"{start}, {prev}")
        if n is not None:
            start = prev = n
    return ", ".join(out)


def run_diagram(run: Run, lang: str = "en") -> Figure:
    """The angle the crank has turned (deg) and its speed (rad/s) against time of a :func:`linkwork.simulate`
    run, its stops marked.

    Parameters
    ----------
    run : Run
        A :func:`linkwork.simulate` run.
    lang : str, default "en"
        The language of the texts, ``"en"`` or ``"ru"`` (:mod:`linkwork.lang`).
    """
    fig, (a1, a2) = _figure(rows=2, height=2.4)
    a1.plot(run.time, np.degrees(run.angle - run.angle[0]), lw=1.3)
    a1.set_ylabel(t("axis.turned", lang), fontsize=9)
    a2.plot(run.time, run.speed, lw=1.3, color="tab:red")
    a2.set_ylabel(t("axis.omega", lang), fontsize=9)
    a2.set_xlabel(t("axis.time", lang), fontsize=9)
    stops = [e.time for e in run.events if e.kind == "stop"]
    if stops:
        turned = np.interp(stops, run.time, np.degrees(run.angle - run.angle[0]))
        a1.plot(stops, turned, "o", color="tab:green", ms=4, label=t("legend.stop", lang))
        a2.plot(stops, np.zeros(len(stops)), "o", color="tab:green", ms=4, label=t("legend.stop", lang))
        _legend(a2, loc="best")
    for ax in (a1, a2):
        _grid(ax)
    a1.tick_params(labelbottom=False)
    fig.suptitle(t("title.simulate", lang), fontsize=11)
    return decimal_commas(fig, lang)


def dynamics_diagrams(result: Dynamics, zero: float | None = None, lang: str = "en") -> Figure:
    """Reduced moment of inertia and reduced load moment, the crank speed over the steady cycle (with its
    mean and δ) of a :func:`linkwork.dynamics` result, over the crank angle from position 0 (``zero``,
    the drive angle of position 0, rad; default the assembly angle), and Wittenbauer's diagram.

    Parameters
    ----------
    result : Dynamics
        A :func:`linkwork.dynamics` result.
    zero : float, optional
        The drive angle of position 0, rad, the origin of the diagrams' angle; default the result's first
        angle, its assembly angle.
    lang : str, default "en"
        The language of the texts, ``"en"`` or ``"ru"`` (:mod:`linkwork.lang`).
    """
    from matplotlib.figure import Figure

    from linkwork.machine import wittenbauer

    red = result.reduced
    sign = 1.0 if len(red.angle) < 2 or red.angle[1] >= red.angle[0] else -1.0
    zero = float(red.angle[0]) if zero is None else zero
    fig = Figure(figsize=(10.5, 7.6), layout="constrained")
    grid = fig.add_gridspec(3, 2, width_ratios=(1.45, 1))
    a1 = fig.add_subplot(grid[0, 0])
    a2, a3 = (fig.add_subplot(grid[i, 0], sharex=a1) for i in (1, 2))
    a4 = fig.add_subplot(grid[:, 1])
    phi, order = _abscissa(red.angle, zero, sign)
    a1.plot(phi, red.inertia[order], lw=1.3, label=t("legend.reduced_inertia", lang))
    a1.set_ylabel(t("axis.inertia", lang), fontsize=9)
    m, munit = _scale(red.load, "unit.Nm", "unit.kNm")
    a2.plot(phi, red.load[order] * m, color="tab:red", lw=1.1, label=t("legend.reduced_load", lang))
    a2.axhline(-red.mean_load * m, color="tab:green", lw=1.0, ls="--", label=t("legend.drive_moment", lang))
    a2.set_ylabel(t("axis.moment", lang, unit=t(munit, lang)), fontsize=9)
    _speed_panel(a3, result, zero, sign, lang)
    for ax in (a1, a2):
        ax.tick_params(labelbottom=False)
    for ax in (a1, a2, a3):
        _grid(ax)
        _legend(ax, loc="best")
    _crank_axis(a3, lang)
    inertia, energy = wittenbauer(red)
    e, eunit = _scale(energy, "unit.J", "unit.kJ")
    a4.plot(np.append(inertia, inertia[0]), np.append(energy, energy[0]) * e, lw=1.1, gid="wittenbauer")
    turned = np.degrees(from_position_0(red.angle, zero, sign))
    first = int(np.argmin(np.minimum(turned, 360.0 - turned)))  # the sample nearest position 0
    a4.plot(inertia[first], energy[first] * e, "o", color="tab:red", ms=4, label=t("legend.position_0", lang))
    if result.flywheel is not None:
        _tangents(a4, result, e, t(eunit, lang), lang)
        a4.legend(fontsize=8, framealpha=0.85, loc="lower center")
    a4.set_xlabel(t("axis.inertia", lang), fontsize=9)
    a4.set_ylabel(t("axis.energy", lang, unit=t(eunit, lang)), fontsize=9)
    a4.set_title(t("title.wittenbauer", lang), fontsize=10)
    _grid(a4)
    if result.flywheel is None:
        _legend(a4, loc="best")
    fig.suptitle(t("title.dynamics", lang, delta=numbers(f"{result.delta:.4g}", lang)), fontsize=11)
    return decimal_commas(fig, lang)


def _tangents(ax: Axes, result: Dynamics, e: float, eunit: str, lang: str) -> None:
    """The tangents to Wittenbauer's diagram for the flywheel's delta, from the energy axis (inertia 0) across
    the diagram, the segment ab they cut on that axis, and the constant inertia they give
    (:func:`linkwork.machine.wittenbauer_tangents`)."""
    from linkwork.machine import wittenbauer_tangents

    f = result.flywheel
    assert f is not None
    red = result.reduced
    (k_max, b_max), (k_min, b_min) = wittenbauer_tangents(red, f.delta, f.omega_mean)
    j = np.array([0.0, float(np.max(red.inertia)) * 1.05])
    for k, b, color, key in ((k_max, b_max, "tab:purple", "max"), (k_min, b_min, "tab:orange", "min")):
        ax.plot(
            j,
            (k * j + b) * e,
            color=color,
            lw=0.9,
            ls="--",
            label=t(f"legend.tangent_{key}", lang),
            gid=f"tangent:{key}",
        )
    ax.plot(
        [0.0, 0.0],
        [b_min * e, b_max * e],
        color="k",
        lw=2.2,
        solid_capstyle="butt",
        gid="tangent:ab",
        label=t(
            "legend.tangent_segment",
            lang,
            segment=f"{(b_max - b_min) * e:.4g} {eunit}",
            inertia=f"{(b_max - b_min) / (k_max - k_min):.5g}",
        ),
    )
    ax.set_xlim(left=-0.03 * j[1])
    low, high = ax.get_ylim()
    ax.set_ylim(low - 0.45 * (high - low), high)  # room under the diagram for its legend


def _speed_panel(ax: Axes, result: Dynamics, zero: float, sign: float, lang: str) -> None:
    """The crank speed (rpm) over the steady cycle against the crank angle from position 0."""
    angles, omega = result.cycle_speed(sign)
    phi, order = _abscissa(angles[:-1], zero, sign, whole=True)  # the last sample closes the turn
    rpm = 30 / np.pi
    ax.plot(phi, omega[order] * rpm, lw=1.3, label=t("legend.crank_speed", lang))
    mean = result.motion.last.omega_mean * rpm
    ax.axhline(
        mean, color="0.3", lw=0.9, ls="--", label=t("legend.mean_speed", lang, value=numbers(f"{mean:.4g}", lang))
    )
    ax.set_ylabel(t("axis.speed", lang), fontsize=9)
