"""Velocity and acceleration plans as scenes: vectors of named kinds, drawn to a stated scale, and labels.

A :class:`PlanScene` holds the plans of some positions (one for a figure, twelve for a sheet, every
sample for the viewer) in millimetres of the sheet: a vector ``u`` (m/s or m/s^2) is drawn ``u / scale``
mm long, ``scale`` in units per mm (written on the sheet as mu_v or mu_a).  The pole ``p`` is at the
origin.  Every point's absolute vector runs from the pole to its lower-case letter; the construction's
vectors (:mod:`linkwork.motion.plans`) run between plan points.  Plan points that coincide on the sheet
share one label ("e, knife_upper.edge"; the pole with every point at rest, "p, o"); the construction's
intermediate points (``n_ba``, ``k'_e``, ``e'``) are labelled, smaller, only where no point of the
mechanism is.  Labels are placed clear of each other and of the vectors (:mod:`linkwork.scene.labels`).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from linkwork.lang import russian_numbers, t
from linkwork.motion.plans import PlanSeries, drawing_scale, longest_length
from linkwork.scene.geometry import text_size
from linkwork.scene.labels import Obstacles, place_labels

#: The kinds of vector of each plan, in the order of a legend.
PLAN_KINDS = {
    "velocity": ("absolute", "rotation", "transport", "sliding"),
    "acceleration": ("absolute", "normal", "tangential", "transport", "coriolis", "sliding"),
}


def kind_name(kind: str, plan: str | None = None, lang: str = "en") -> str:
    """The name of a kind of vector in the legend of a ``plan`` (``"velocity"`` or ``"acceleration"``; default
    the first plan that has it), in ``lang`` (:mod:`linkwork.lang`: ``vector.PLAN.KIND``)."""
    if plan is None or kind not in PLAN_KINDS.get(plan, ()):
        plan = "velocity" if kind in PLAN_KINDS["velocity"] else "acceleration"
    return t(f"vector.{plan}.{kind}", lang)


#: Every kind of vector, in the order of a legend, with its name in English.
KINDS = {k: kind_name(k) for k in ("absolute", "rotation", "normal", "tangential", "transport", "coriolis", "sliding")}

#: Height of the labels on the sheet (mm): the drafting standard's 3.5 mm lettering.
LETTERING = 3.5

#: The textbook's name of a plan point: a letter, with a number or primes (``a``, ``o1``, ``e'``); a point named
#: otherwise (``knife_upper.edge``) is named only where no such point shares its place.
_LETTER = re.compile(r"[a-zπ][0-9]*'*")

#: The pole of each plan in each language: the Russian school writes π for the acceleration plan's.
POLES = {("acceleration", "ru"): "π"}

#: Plan points closer than this (in ems of the labels) share one label.
TOGETHER = 0.35


@dataclass(frozen=True)
class Arrow:
    """One vector of a plan: from plan point ``start`` to plan point ``end`` (indices of the labels)."""

    start: int
    end: int
    kind: str


@dataclass(frozen=True)
class PlanScene:
    """Velocity or acceleration plans of some positions, drawn to one scale.

    Attributes
    ----------
    kind : str
        ``"velocity"`` or ``"acceleration"``.
    unit : str
        Of the vectors: ``"m/s"`` or ``"m/s^2"``.
    scale : float
        Units per mm of the sheet.
    em : float
        Height of the labels' text, mm.
    angles : ndarray, shape (A,)
        Drive angle of each position, rad.
    names : tuple of str
        The plan points, ``p`` (the pole) first.
    main : ndarray, shape (L,) of bool
        Which plan points are points of the mechanism (the others are the construction's).
    points : ndarray, shape (A, L, 2)
        Plan points on the sheet, mm; NaN where the mechanism does not assemble.
    arrows : tuple of Arrow
        The absolute vectors, then the construction's.
    ends : ndarray, shape (A, E, 2, 2)
        Start and end of each arrow on the sheet, mm (the end of a construction vector is its start plus
        the vector: it meets its end point up to rounding).
    values : ndarray, shape (A, E, 2)
        Each arrow's vector, m/s or m/s^2.
    text : tuple of tuple of str
        ``(A, L)``: the label at each plan point, empty where another point's label names it.
    centres : ndarray, shape (A, L, 2)
        Centre of each label's text, mm; NaN where there is none.
    pole : str
        The pole's letter on the sheet (:data:`POLES`): ``p``, or ``π`` in a Russian acceleration plan.
    """

    kind: str
    unit: str
    scale: float
    em: float
    angles: np.ndarray
    names: tuple[str, ...]
    main: np.ndarray
    points: np.ndarray
    arrows: tuple[Arrow, ...]
    ends: np.ndarray
    values: np.ndarray
    text: tuple[tuple[str, ...], ...]
    centres: np.ndarray
    pole: str = "p"

    @property
    def symbol(self) -> str:
        """The scale's name on the sheet: ``μv`` or ``μa``."""
        return "μv" if self.kind == "velocity" else "μa"

    def scale_note(self, lang: str = "en") -> str:
        """The pole and the scale, as written under the plan: ``pole p,  μv = 0.05 (m/s)/mm`` (a decimal
        comma in Russian)."""
        unit = t(f"plan.unit.{self.kind}", lang)
        scale = russian_numbers(f"{self.scale:g}") if lang == "ru" else f"{self.scale:g}"  # 0,05 in Russian
        return t("plan.scale", lang, pole=self.pole, symbol=self.symbol, scale=scale, unit=unit)

    def drawn(self, index: int) -> list[int]:
        """The arrows drawn at position ``index``: those of finite, non-zero length."""
        ends = self.ends[index]
        size = np.hypot(*(ends[:, 1] - ends[:, 0]).T)
        return [e for e in range(len(self.arrows)) if np.isfinite(size[e]) and size[e] > 1e-9]

    def kinds(self, index: int) -> list[str]:
        """The kinds of the arrows drawn at position ``index``, in the order of :data:`KINDS` (a legend's)."""
        present = {self.arrows[e].kind for e in self.drawn(index)}
        return [k for k in KINDS if k in present]

    def extent(self, index: int) -> np.ndarray:
        """``[x0, y0, x1, y1]`` of the plan of position ``index`` on the sheet, its labels included, mm."""
        parts = [np.zeros((1, 2)), self.points[index], self.ends[index].reshape(-1, 2)]
        for j, text in enumerate(self.text[index]):
            if text:
                w, h = text_size(text, self.em * (1.0 if self.main[j] else 0.8))
                parts += [self.centres[index, j] - [w / 2, h / 2], self.centres[index, j] + [w / 2, h / 2]]
        pts = np.concatenate([np.asarray(p, dtype=float).reshape(-1, 2) for p in parts])
        pts = pts[np.isfinite(pts).all(-1)]
        return np.concatenate([pts.min(0), pts.max(0)])


def plan_scale(series: PlanSeries, indices: list[int] | np.ndarray, variant: int = 0) -> float:
    """The round scale (units per mm) that draws the longest absolute vector of the positions ``indices``
    at most 100 mm long (:func:`linkwork.motion.plans.drawing_scale`)."""
    values = series.values[variant, np.asarray(indices, dtype=int), : len(series.points)]
    longest = longest_length(values)
    return drawing_scale(float(np.max(longest, initial=0.0)))


def plan_scene(
    series: PlanSeries,
    indices: list[int] | np.ndarray,
    *,
    scale: float | None = None,
    em: float = LETTERING,
    valid: np.ndarray | None = None,
    variant: int = 0,
    lang: str = "en",
) -> PlanScene:
    """The plans of the positions ``indices`` of ``series``, drawn to one scale.

    Parameters
    ----------
    series : PlanSeries
        From :func:`linkwork.motion.plans.plan_series`.
    indices : sequence of int
        The positions (samples of the series).
    scale : float, optional
        Units per mm; default :func:`plan_scale` of these positions.
    em : float
        Height of the labels' text, mm.
    valid : ndarray of bool, shape (A,), optional
        Where the mechanism assembles (elsewhere nothing is drawn); default where the plan is finite.
    variant : int
        Which design variant.
    lang : str
        The language of the drawing: it decides the pole's letter (:data:`POLES`).

    Returns
    -------
    PlanScene
    """
    idx = np.asarray(indices, dtype=int)
    scale = plan_scale(series, idx, variant) if scale is None else float(scale)
    values = np.array(series.values[variant, idx], dtype=float)
    vectors = np.array(series.vectors[variant, idx], dtype=float)
    if valid is not None:
        values[~np.asarray(valid, dtype=bool)[idx]] = np.nan
        vectors[~np.asarray(valid, dtype=bool)[idx]] = np.nan
    names = tuple(series.labels)
    index = {lab: j for j, lab in enumerate(names)}
    main = np.array([j < len(series.points) for j in range(len(names))])
    arrows = tuple(Arrow(0, index[lab], "absolute") for lab in series.points if lab != "p")
    arrows += tuple(Arrow(index[e.start], index[e.end], e.kind) for e in series.edges)
    points = values / scale
    absolute = values[:, [a.end for a in arrows if a.kind == "absolute"]]
    value = np.concatenate([absolute, vectors], 1)  # (A, E, 2)
    starts = np.zeros_like(value)
    for e, a in enumerate(arrows):
        if a.kind != "absolute":
            starts[:, e] = points[:, a.start]
    ends = np.stack([starts, starts + value / scale], 2)
    pole = POLES.get((series.kind, lang), "p")
    text = _grouped(names, main, points, em, pole)
    centres = _placed(text, main, points, ends, em)
    unit = "m/s" if series.kind == "velocity" else "m/s^2"
    angles = np.asarray(series.angles)[idx]
    return PlanScene(
        series.kind, unit, scale, em, angles, names, main, points, arrows, ends, value, text, centres, pole
    )


def _grouped(
    names: tuple[str, ...], main: np.ndarray, points: np.ndarray, em: float, pole: str = "p"
) -> tuple[tuple[str, ...], ...]:
    """The label of each plan point at each position ``(A, L)``: the names of the points that coincide
    with it on the sheet (the textbook's letters among them, :data:`_LETTER`; the pole ``p`` written
    ``pole``), given to the first of them; empty for the others and where it is not drawn."""
    names = tuple(pole if name == "p" else name for name in names)
    out = []
    for row in points:
        finite = np.isfinite(row).all(-1)
        taken = np.zeros(len(names), dtype=bool)
        texts = [""] * len(names)
        for j in range(len(names)):
            if taken[j] or not finite[j]:
                continue
            close = finite & ~taken & (np.hypot(*(row - row[j]).T) < TOGETHER * em)
            taken |= close
            members = [names[i] for i in np.flatnonzero(close)]
            majors = [names[i] for i in np.flatnonzero(close & main)]
            letters = [name for name in majors if _LETTER.fullmatch(name)]
            texts[j] = ", ".join(letters or majors or members)
        out.append(tuple(texts))
    return tuple(out)


def _placed(
    text: tuple[tuple[str, ...], ...], main: np.ndarray, points: np.ndarray, ends: np.ndarray, em: float
) -> np.ndarray:
    """Centres ``(A, L, 2)`` of the labels, clear of each other, of the arrows and of the dots."""
    n, count = points.shape[:2]
    shown = np.array([[bool(t) for t in row] for row in text]).reshape(n, count)
    anchors = np.where(shown[..., None], points, np.nan)
    size = np.array([[text_size(t, em * (1.0 if main[j] else 0.8)) for j, t in enumerate(row)] for row in text])
    dots = np.concatenate([points, np.full((n, count, 1), 0.25 * em)], -1)
    prefer = _away(points, ends)
    order = list(np.flatnonzero(main)) + list(np.flatnonzero(~main))
    centres = place_labels(
        anchors[:, order],
        size.reshape(n, count, 2)[:, order],
        np.full(count, 0.3 * em),
        Obstacles(ends, dots),
        prefer[:, order],
        pad=0.1 * em,
    )
    out = np.full_like(centres, np.nan)
    out[:, order] = centres
    return out


def _away(points: np.ndarray, ends: np.ndarray) -> np.ndarray:
    """Unit directions ``(A, L, 2)`` away from the arrows that start or end at each plan point."""
    rel_start = ends[:, None, :, 1] - points[:, :, None]  # from the point to each arrow's far end
    rel_end = ends[:, None, :, 0] - points[:, :, None]
    at_start = np.hypot(*np.moveaxis(ends[:, None, :, 0] - points[:, :, None], -1, 0)) < 1e-6
    at_end = np.hypot(*np.moveaxis(ends[:, None, :, 1] - points[:, :, None], -1, 0)) < 1e-6
    towards = np.where(at_start[..., None], rel_start, 0.0) + np.where(at_end[..., None], rel_end, 0.0)
    size = np.hypot(*np.moveaxis(towards, -1, 0))[..., None]
    unit = np.where(size > 1e-12, towards / np.where(size > 0, size, 1), 0.0)
    away = -np.nansum(unit, 2)
    size = np.hypot(*np.moveaxis(away, -1, 0))[..., None]
    return np.where(size > 1e-9, away / np.where(size > 0, size, 1), np.sqrt(0.5))
