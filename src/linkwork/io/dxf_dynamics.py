"""The dynamics sheet of a course project: the diagrams of the machine's steady cycle (:func:`linkwork.dynamics`,
as the report's dynamics section gives them) as drawings of a sheet (:class:`~linkwork.io.dxf_sheet.SheetDrawing`).

Wittenbauer's diagram (the energy-mass diagram: the energy ``ΔT`` given to the machine from position 0 against the
reduced moment of inertia ``J``) with the two tangents for the flywheel's δ and the segment they cut on the energy
axis; the reduced moment of inertia ``J(φ)``; the reduced moments of the loads ``M(φ)`` and the constant drive
moment that balances them; the energy ``ΔT(φ)``; the crank speed ``ω(φ)`` over the steady cycle with its mean; the
flywheel's figures.  Each diagram is drawn at scales of the 1-2-2.5-5 series, the largest that fit its cell
(``μφ = 2 °/мм;  μJ = 0,5 кг·м²/мм``, stated above it), its axes thin with arrows and ticks, its curves in the main
line (ГОСТ 2.303), the second curve and the tangents dashed, its numbers and names 2.5 and 3.5 mm (ГОСТ 2.304).
Nothing is computed here that the dynamics do not give: the data are those of the report's figure
(:func:`linkwork.figures.dynamics_diagrams`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.io.dxf import CAP
from linkwork.io.dxf_sheet import (
    AXES,
    CURVES,
    LABEL,
    SMALLEST,
    TANGENTS,
    THIN,
    SheetDrawing,
    add_text,
    nice_up,
    number,
)
from linkwork.lang import t
from linkwork.scene.geometry import text_size

if TYPE_CHECKING:
    from linkwork.machine.steady_cycle import Dynamics

#: The least distance between two ticks of an axis, mm.
TICK_GAP = 15.0
#: The most points of a curve drawn (a turn in half-degree steps): more samples are thinned, their extremes kept.
POINTS = 721
#: Steps of the φ axis, degrees.
DEGREES = (15.0, 30.0, 45.0, 60.0, 90.0, 180.0)


@dataclass(frozen=True)
class DiagramCurve:
    """A curve of a diagram: ``y`` over the diagram's ``x`` ``(N,)``; ``name`` in the legend; ``dashed``."""

    y: np.ndarray
    name: str = ""
    dashed: bool = False


@dataclass(frozen=True)
class Axis:
    """An axis: its symbol (``φ``, ``M``) and unit as written (``°``, ``Н·м``); ``steps`` for its ticks, values
    (None: the 1-2-5 series); ``span`` it must show beyond the curves' (the tangents' ends); ``zero``: whether it
    starts at 0 (else the other axis crosses it at the least value: a speed that varies by a few per cent)."""

    symbol: str
    unit: str
    steps: Sequence[float] | None = None
    span: tuple[float, float] | None = None
    zero: bool = True

    @property
    def name(self) -> str:
        return f"{self.symbol}, {self.unit}"


def _span(values: np.ndarray, axis: Axis) -> tuple[float, float]:
    """The range an axis shows: the finite ``values``, ``axis.span``, and 0 where it starts at 0 (else a tenth
    more below and above)."""
    v = values[np.isfinite(values)]
    low, high = float(v.min()), float(v.max())
    if axis.span is not None:
        low, high = min(low, axis.span[0]), max(high, axis.span[1])
    if axis.zero:
        low, high = min(low, 0.0), max(high, 0.0)
    else:
        pad = 0.1 * (high - low) or 0.05 * abs(high) or 1.0
        low, high = low - pad, high + pad
    return low, high if high > low else low + 1.0


def _ticks(low: float, high: float, mu: float, steps: Sequence[float] | None) -> np.ndarray:
    """The ticks' values within ``[low, high]``, at least :data:`TICK_GAP` mm apart at the scale ``mu``."""
    least = TICK_GAP * mu
    step = next((s for s in steps if s >= least), steps[-1]) if steps else nice_up(least, (1.0, 2.0, 5.0))
    return step * np.arange(math.ceil(low / step - 1e-9), math.floor(high / step + 1e-9) + 1)


def _width(text: str, height: float = SMALLEST) -> float:
    return float(text_size(text, height / CAP)[0])


def diagram_drawing(
    title: str,
    x: np.ndarray,
    curves: Sequence[DiagramCurve],
    axes: tuple[Axis, Axis],
    lang: str,
    lines: Sequence[tuple[np.ndarray, np.ndarray, str]] = (),
    big: bool = False,
    segment: tuple[float, float] | None = None,
) -> SheetDrawing:
    """A diagram of ``curves`` over ``x`` with its ``axes`` (x, y), ticks and scales, fitting its cell; ``lines``:
    straight lines ``(xs, ys, text)`` drawn dashed on :data:`TANGENTS`, the text right of their first point;
    ``segment``: the values between which the y axis is drawn in the main line (Wittenbauer's ab)."""
    xaxis, yaxis = axes
    xlow, xhigh = _span(np.asarray(x, dtype=float), xaxis)
    ylow, yhigh = _span(np.concatenate([np.ravel(c.y) for c in curves]), yaxis)
    base = 0.0 if yaxis.zero else ylow  # where the x axis crosses the y axis
    named = [c for c in curves if c.name]

    def fit(layout: Any, w: float, h: float) -> tuple[np.ndarray, str]:
        widest = max(_width(number(v, lang)) for v in (ylow, yhigh, 0.5 * (ylow + yhigh)))
        left, right = widest + 4.0, _width(xaxis.name, LABEL) + 10.0
        below = 2 * SMALLEST + 4.0 + (2.2 * LABEL * len(named) if len(named) > 1 else 0.0)
        above = 2 * LABEL + 6.0
        mx = nice_up((xhigh - xlow) / max(w - left - right, 10.0))
        my = nice_up((yhigh - ylow) / max(h - below - above, 10.0))
        _axes(layout, (xlow, xhigh, mx), (ylow, yhigh, my, base), xaxis, yaxis, lang)
        for c in curves:
            _curve(layout, (np.asarray(x) - xlow) / mx, (np.asarray(c.y) - base) / my, CURVES, c.dashed)
        for xs, ys, text in lines:
            _curve(layout, (np.asarray(xs) - xlow) / mx, (np.asarray(ys) - base) / my, TANGENTS, True)
            add_text(layout, text, ((xs[0] - xlow) / mx + 2.0, (ys[0] - base) / my), LABEL, "LABELS", left=True)
        if segment is not None:
            u, ends = -xlow / mx, [(v - base) / my for v in segment]
            layout.add_line((u, ends[0]), (u, ends[1]), dxfattribs={"layer": CURVES})
        bottom = (ylow - base) / my - 2 * SMALLEST - 4.0
        if len(named) > 1:
            _legend(layout, named, bottom)
        top = (yhigh - base) / my + 6.0 + 2 * LABEL  # the y axis's arrow and its name
        box = np.array([-left, bottom - 2.2 * LABEL * len(named), (xhigh - xlow) / mx + right, top])
        scales = f"μ{xaxis.symbol} = {number(mx, lang)} {xaxis.unit}/{t('unit.mm', lang)};  "
        return box, scales + f"μ{yaxis.symbol} = {number(my, lang)} {yaxis.unit}/{t('unit.mm', lang)}"

    return SheetDrawing(title, fit, big=big)


def _axes(
    layout: Any,
    xs: tuple[float, float, float],
    ys: tuple[float, float, float, float],
    xaxis: Axis,
    yaxis: Axis,
    lang: str,
) -> None:
    """The axes with arrows, the x axis at the y value ``ys[3]``, their ticks and numbers (x's under the diagram,
    y's left of its axis) and their names at the arrows; ``xs`` ``(low, high, μ)``, ``ys`` ``(low, high, μ,
    base)``."""
    from linkwork.io.dxf import _head

    (xlow, xhigh, mx), (ylow, yhigh, my, base) = xs, ys
    x1, y0, y1 = (xhigh - xlow) / mx + 6.0, (ylow - base) / my, (yhigh - base) / my + 6.0
    for a, b in (((0.0, 0.0), (x1, 0.0)), ((0.0, min(y0, 0.0)), (0.0, y1))):
        layout.add_line(a, b, dxfattribs={"layer": AXES})
        _head(layout, np.array(a), np.array(b), 3.0, AXES)
    for v in _ticks(xlow, xhigh, mx, xaxis.steps):
        u = (v - xlow) / mx
        layout.add_line((u, -1.0), (u, 1.0), dxfattribs={"layer": AXES})
        add_text(layout, number(float(v), lang), (u, y0 - SMALLEST - 1.5), SMALLEST, "LABELS")
    for v in _ticks(ylow, yhigh, my, yaxis.steps):
        text = number(float(v), lang)
        y = (v - base) / my
        layout.add_line((-1.0, y), (1.0, y), dxfattribs={"layer": AXES})
        add_text(layout, text, (-2.0 - _width(text), y), SMALLEST, "LABELS", left=True)
    add_text(layout, xaxis.name, (x1 + 2.0, 0.0), LABEL, "LABELS", left=True)
    add_text(layout, yaxis.name, (2.0, y1 + LABEL), LABEL, "LABELS", left=True)


def _curve(layout: Any, u: np.ndarray, v: np.ndarray, layer: str, dashed: bool) -> None:
    """A polyline through the finite points ``(u, v)`` (mm), broken where they are not; of more than
    :data:`POINTS`, every k-th, the first, the last and the largest and least ``v`` drawn."""
    if len(u) > POINTS:
        keep = np.arange(0, len(u), -(-len(u) // POINTS))
        if np.isfinite(v).any():
            keep = np.append(keep, [np.nanargmax(v), np.nanargmin(v)])
        keep = np.unique(np.append(keep, len(u) - 1))
        u, v = u[keep], v[keep]
    ok = np.isfinite(u) & np.isfinite(v)
    runs = np.split(np.arange(len(u)), np.flatnonzero(np.diff(ok.astype(int))) + 1)
    attrs = {"layer": layer, **({"linetype": "DASHED", "lineweight": THIN} if dashed else {})}  # a thin line
    for run in runs:
        if ok[run[0]] and len(run) > 1:
            layout.add_lwpolyline(list(zip(u[run].tolist(), v[run].tolist(), strict=True)), dxfattribs=attrs)


def _legend(layout: Any, curves: Sequence[DiagramCurve], top: float) -> None:
    """Under the diagram, a stroke of each curve (dashed as drawn) and its name."""
    for row, c in enumerate(curves):
        y = top - (row + 0.5) * 2.2 * LABEL
        _curve(layout, np.array([0.0, 15.0]), np.array([y, y]), CURVES, c.dashed)
        add_text(layout, c.name, (20.0, y), LABEL, "NOTES", left=True)


def _phi(result: Dynamics, angles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """φ (deg, from position 0, ascending) of drive ``angles`` and the order of the samples along it."""
    from linkwork.motion.analysis import from_position_0

    crank, red = result.crank, result.reduced
    zero = float(red.angle[0]) if crank is None else crank.zero
    sign = _sign(result)
    phi = np.degrees(from_position_0(angles, zero, sign))
    order = np.argsort(phi, kind="stable")
    return phi[order], order


def _sign(result: Dynamics) -> float:
    if result.crank is not None:
        return float(result.crank.direction)
    angle = result.reduced.angle
    return 1.0 if len(angle) < 2 or angle[1] >= angle[0] else -1.0


def _closed(phi: np.ndarray, *ys: np.ndarray) -> tuple[np.ndarray, ...]:
    """A turn's samples closed at 360° by the first one's values (a periodic quantity)."""
    return (np.append(phi, phi[0] + 360.0), *(np.append(y, y[0]) for y in ys))


def dynamics_drawings(result: Dynamics, lang: str) -> list[SheetDrawing]:
    """The drawings of the dynamics sheet of ``result``: Wittenbauer's diagram, ``J(φ)``, ``M(φ)``, ``ΔT(φ)``,
    ``ω(φ)`` and the flywheel's figures (where it has a flywheel)."""
    from linkwork.machine import wittenbauer

    red = result.reduced
    inertia, energy = wittenbauer(red)
    phi, order = _phi(result, red.angle)
    start = float(np.interp(0.0, phi, energy[order], period=360.0))  # ΔT from position 0 on both diagrams
    energy = energy - start
    phi, j, m, e = _closed(phi, red.inertia[order], red.load[order], energy[order])
    deg = Axis("φ", t("unit.deg", lang), DEGREES)
    kgm2, nm, joule = t("sheet.unit.inertia", lang), t("unit.Nm", lang), t("unit.J", lang)
    drive = np.full_like(m, -red.mean_load)
    moments = [DiagramCurve(m, t("sheet.dyn.load", lang)), DiagramCurve(drive, t("sheet.dyn.drive", lang), dashed=True)]
    angles, omega = result.cycle_speed(_sign(result))
    at, along = _phi(result, angles[:-1])
    at, w = _closed(at, omega[:-1][along])
    mean = np.full_like(w, result.motion.last.omega_mean)
    speeds = [
        DiagramCurve(w, t("sheet.dyn.omega", lang)),
        DiagramCurve(mean, t("sheet.dyn.omega_mean", lang), dashed=True),
    ]
    drawings = [
        wittenbauer_drawing(result, inertia, energy, start, lang),
        diagram_drawing(t("sheet.dyn.inertia_title", lang), phi, [DiagramCurve(j)], (deg, Axis("J", kgm2)), lang),
        diagram_drawing(t("sheet.dyn.moments_title", lang), phi, moments, (deg, Axis("M", nm)), lang),
        diagram_drawing(t("sheet.dyn.energy_title", lang), phi, [DiagramCurve(e)], (deg, Axis("ΔT", joule)), lang),
        diagram_drawing(
            t("sheet.dyn.omega_title", lang),
            at,
            speeds,
            (deg, Axis("ω", t("sheet.unit.rad_s", lang), zero=False)),
            lang,
        ),
    ]
    return [*drawings, figures_drawing(result, lang)]


def wittenbauer_drawing(
    result: Dynamics, inertia: np.ndarray, energy: np.ndarray, start: float, lang: str
) -> SheetDrawing:
    """Wittenbauer's diagram ``ΔT(J)`` closed over the turn (``energy`` less ``start``, the energy of
    :func:`linkwork.machine.wittenbauer` at position 0); with a flywheel, its two tangents from the energy axis
    (:func:`linkwork.machine.wittenbauer_tangents`, less ``start``) and the segment ab they cut on it."""
    from linkwork.machine import wittenbauer_tangents

    curve = DiagramCurve(np.append(energy, energy[0]))
    x = np.append(inertia, inertia[0])
    lines: list[tuple[np.ndarray, np.ndarray, str]] = []
    span = segment = None
    fly = result.flywheel
    if fly is not None:
        (k_max, b_max), (k_min, b_min) = wittenbauer_tangents(result.reduced, fly.delta, fly.omega_mean)
        b_max, b_min = b_max - start, b_min - start
        ends = np.array([0.0, 1.05 * float(np.max(inertia))])
        lines = [(ends, k_max * ends + b_max, "a"), (ends, k_min * ends + b_min, "b")]
        span = (min(b_min, k_min * ends[1] + b_min), max(b_max, k_max * ends[1] + b_max))
        segment = (b_min, b_max)
    axis = Axis("ΔT", t("unit.J", lang), span=span)
    jaxis = Axis("J", t("sheet.unit.inertia", lang), span=(0.0, 1.05 * float(np.max(inertia))))
    title = t("title.wittenbauer", lang)
    return diagram_drawing(title, x, [curve], (jaxis, axis), lang, lines, big=True, segment=segment)


def figures_drawing(result: Dynamics, lang: str) -> SheetDrawing:
    """The figures of the steady cycle and the flywheel, one a line: ω mean, δ (asked and run), the energy swing
    (the segment ab), the inertia needed on the crank shaft and the flywheel's on its shaft."""
    fly, last = result.flywheel, result.motion.last
    rows = [
        t("sheet.fig.omega", lang, value=number(last.omega_mean, lang)),
        t("sheet.fig.delta", lang, value=number(last.delta, lang)),
    ]
    if fly is not None:
        rows += [
            t("sheet.fig.delta_asked", lang, value=number(fly.delta, lang)),
            t("sheet.fig.swing", lang, value=number(fly.energy_swing, lang)),
            t("sheet.fig.needed", lang, value=number(fly.inertia, lang)),
        ]
    shaft = t(f"shaft.{result.drive.flywheel_on}", lang)
    rows.append(t("sheet.fig.flywheel", lang, shaft=shaft, value=number(result.drive.flywheel, lang)))

    def fit(layout: Any, w: float, h: float) -> tuple[np.ndarray, str]:
        for k, row in enumerate(rows):
            add_text(layout, row, (0.0, -k * 2.0 * LABEL), LABEL, "NOTES", left=True)
        wide = max(_width(row, LABEL) for row in rows)
        return np.array([0.0, -(len(rows) - 1) * 2.0 * LABEL - LABEL, wide, LABEL]), ""

    return SheetDrawing(t("sheet.fig.title", lang), fit)
