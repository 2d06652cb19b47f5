"""Force plans and Zhukovsky's lever as scenes: named force vectors drawn to a stated scale, and labels.

A :class:`ForceScene` is one drawing of one position in millimetres of the sheet:

* a group's **force plan** (:func:`force_plan_scene`): the polygon of its forces head to tail from the
  origin, a force ``F`` (N) drawn ``F / scale`` mm long (``scale``: μF in N/mm), each named beside its
  middle (``G2``, ``Φ2``, ``R12τ``...), then the reactions it gives (``R12 = R12n + R12τ``, the inner
  joint's ``R32``) dashed between the polygon's vertices they join;
* **Zhukovsky's lever** (:func:`lever_scene`): the velocity plan turned by 90 degrees (its lines thin, its
  points lettered), at the velocity plan's scale μv, and every force at its point's image, drawn to a
  force scale of its own, the balancing force at the crank pin's image.

Labels are placed clear of each other and of the lines (:mod:`linkwork.scene.labels`).  The renderers are
:mod:`linkwork.figures.force_plans` (matplotlib) and :mod:`linkwork.io.dxf_forces` (DXF).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from linkwork.kinetostatics.force_polygons import GroupPlan, PlanForce
from linkwork.kinetostatics.zhukovsky import Lever
from linkwork.motion.plans import PlanSeries, drawing_scale
from linkwork.scene.geometry import text_size
from linkwork.scene.labels import DIRECTIONS, Obstacles, place_labels
from linkwork.scene.plans import LETTERING, _grouped
from linkwork.scene.positions import FINE

#: An arrow before its name is placed: start, end (mm), the force, whether it is a reaction read off the plan.
_Draft = tuple[np.ndarray, np.ndarray, PlanForce, bool]

#: A force whose arrow on a force plan is shorter than this many ems (the height of its name) is not named beside
#: it, where the names of several such arrows would pile up at one vertex: its name and value are listed under
#: the plan (:func:`short_note`), and the report's table gives its length on the plan.
SHORT = 1.0

#: The kinds of arrow of the force drawings, in the order of a legend.
FORCE_KINDS = ("weight", "inertia", "load", "known", "tangential", "normal", "reaction", "internal", "balancing")


@dataclass(frozen=True)
class ForceArrow:
    """One arrow: from ``start`` to ``end`` (mm of the sheet), of ``kind``, named ``text`` (``tex``: as
    mathtext), its name's centre ``centre`` (NaN: unlabelled); ``resultant``: a reaction read off the plan
    (drawn dashed)."""

    start: np.ndarray
    end: np.ndarray
    kind: str
    text: str
    tex: str
    centre: np.ndarray
    value: float
    resultant: bool = False
    second: bool = False  # drawn to the lever's scale of its kind (:attr:`ForceScene.second_scales`)


@dataclass(frozen=True)
class ForceScene:
    """A force plan or a lever at one position, in mm of the sheet.

    Attributes
    ----------
    kind : str
        ``"force_plan"`` or ``"lever"``.
    label : str
        The group's label (a force plan) or ``""``.
    angle : float
        Drive angle of the position, rad.
    scale : float
        μF, N per mm of the arrows.
    plan_scale : float
        The lever's μv, (m/s) per mm (NaN for a force plan).
    em : float
        Height of the labels' text, mm.
    arrows : tuple of ForceArrow
    lines : ndarray (S, 2, 2)
        The lever's turned velocity plan, end to end (empty for a force plan).
    dots : ndarray (D, 2)
        Points marked: the polygon's vertices, the lever's pole and image points.
    dot_text : tuple of str
        Each dot's letter (empty for none).
    dot_centres : ndarray (D, 2)
    """

    kind: str
    label: str
    angle: float
    scale: float
    plan_scale: float
    em: float
    arrows: tuple[ForceArrow, ...]
    lines: np.ndarray
    dots: np.ndarray
    dot_text: tuple[str, ...]
    dot_centres: np.ndarray
    left_out: tuple[tuple[str, float], ...] = ()  # a lever's forces too short to draw: (name, value N)
    second_scales: tuple[tuple[str, float], ...] = ()  # a lever's kinds too short at μF: (kind, its scale N/mm)

    def kind_scales(self, lang: str = "en") -> dict[str, str]:
        """The lever's scales of the kinds too short at μF, each as written: ``{"inertia": "μΦ = 5 N/mm"}``."""
        from linkwork.lang import t

        unit = t("unit.N", lang) + "/" + t("unit.mm", lang)
        return {k: f"μ{KIND_SYMBOL.get(k, 'F')} = {v:g} {unit}" for k, v in self.second_scales}

    def second_note(self, lang: str = "en") -> str:
        """The lever's scales of the kinds too short at μF: ``μG = 200 N/mm, μΦ = 5 N/mm``; empty where none is."""
        return ", ".join(self.kind_scales(lang).values())

    def short(self) -> list[ForceArrow]:
        """The named arrows whose names are not drawn beside them (shorter than :data:`SHORT` ems on a plan)."""
        return [a for a in self.arrows if a.text and not np.isfinite(a.centre).all()]

    def kinds(self) -> list[str]:
        """The kinds of the arrows drawn, in the order of :data:`FORCE_KINDS`."""
        present = {a.kind for a in self.arrows}
        return [k for k in FORCE_KINDS if k in present]

    def extent(self) -> np.ndarray:
        """``[x0, y0, x1, y1]`` of the drawing, its labels included, mm."""
        parts = [np.zeros((1, 2)), self.dots.reshape(-1, 2), self.lines.reshape(-1, 2)]
        for a in self.arrows:
            parts += [a.start[None], a.end[None]]
            if a.text and np.isfinite(a.centre).all():
                w, h = text_size(a.text, self.em)
                parts += [a.centre[None] - [w / 2, h / 2], a.centre[None] + [w / 2, h / 2]]
        for text, c in zip(self.dot_text, self.dot_centres, strict=True):
            if text and np.isfinite(c).all():
                w, h = text_size(text, self.em)
                parts += [c[None] - [w / 2, h / 2], c[None] + [w / 2, h / 2]]
        pts = np.concatenate(parts)
        pts = pts[np.isfinite(pts).all(-1)]
        return np.concatenate([pts.min(0), pts.max(0)])


def _drawn(vector: np.ndarray, largest: float) -> bool:
    """Whether a force is drawn: finite and longer than a millionth of the largest."""
    return bool(np.isfinite(vector).all() and np.hypot(*vector) > 1e-6 * largest)


def force_plan_scene(
    group: GroupPlan,
    index: int,
    *,
    lang: str = "en",
    scale: float | None = None,
    em: float = LETTERING,
    variant: int = 0,
    angle: float = float("nan"),
) -> ForceScene:
    """The force plan of ``group`` at sample ``index`` (drive ``angle``, rad, for its title), drawn to ``scale``
    (N/mm; default :meth:`GroupPlan.scale`), its names in ``lang``; without arrows at a dead point (where the
    plan's reactions are NaN)."""
    scale = group.scale(index, variant) if scale is None else float(scale)
    vertices = group.vertices(index, variant) / scale
    values = [f.vector[variant, index] for f in group.polygon]
    largest = max((float(np.hypot(*v)) for v in values if np.isfinite(v).all()), default=0.0)
    drafts: list[_Draft] = []
    if not np.isfinite(vertices).all():  # a dead point: no plan (a part of one would mislead)
        nothing = (drafts, np.zeros((0, 2, 2)))
        return _scene("force_plan", group.label, (scale, np.nan), em, lang, nothing, (np.zeros((0, 2)), ()), angle)
    for j, f in enumerate(group.polygon):
        if _drawn(values[j], largest):
            drafts.append((vertices[j], vertices[j + 1], f, False))
    drafts, links = _apart(drafts, em)
    for r in group.reactions:
        v = r.vector[variant, index]
        if r.part or not _drawn(v, largest):
            continue
        ends = _between(vertices, v / scale, largest / scale)
        if ends is not None and not any(
            f.pair == r.pair and f.link == r.link and not f.part and f.kind != "known" for f in group.polygon
        ):
            drafts.append((ends[0], ends[1], r, True))
    corners = vertices[np.isfinite(vertices).all(-1)]
    return _scene(
        "force_plan", group.label, (scale, np.nan), em, lang, (drafts, links), (corners, ("",) * len(corners)), angle
    )


#: Two arrows of a force plan one after the other along one line, the second back over the first (within
#: :data:`COLLINEAR` rad), would cover each other: the second is drawn :data:`APART` ems beside its place, joined
#: to the polygon's vertices by thin lines (``G3`` down and ``Φ3`` up at a slider on a vertical guide).
COLLINEAR, APART = np.radians(3.0), 0.8


def _apart(drafts: list[_Draft], em: float) -> tuple[list[_Draft], np.ndarray]:
    """``drafts`` of a polygon with each arrow that runs back over the one before it (:data:`COLLINEAR`) moved
    :data:`APART` ems to the right of that one (their names, each to its left, fall outside), and the thin lines
    ``(K, 2, 2)`` that join it to its vertices."""
    out: list[_Draft] = []
    links: list[np.ndarray] = []
    for s, e, f, resultant in drafts:
        if out and not resultant and not out[-1][3] and np.allclose(out[-1][1], s):
            a, b = out[-1][1] - out[-1][0], e - s
            la, lb = float(np.hypot(*a)), float(np.hypot(*b))
            if la > 0 and lb > 0 and a @ b < 0 and abs(a[0] * b[1] - a[1] * b[0]) < np.sin(COLLINEAR) * la * lb:
                shift = APART * em * np.array([a[1], -a[0]]) / la  # to the right of the first: each name outside
                links += [np.array([s, s + shift]), np.array([e + shift, e])]
                out.append((s + shift, e + shift, f, resultant))
                continue
        out.append((s, e, f, resultant))
    return out, np.array(links).reshape(-1, 2, 2)


def _between(vertices: np.ndarray, vector: np.ndarray, size: float) -> tuple[np.ndarray, np.ndarray] | None:
    """Two vertices of the polygon the ``vector`` joins (from the first to the second), if any."""
    gap = vertices[None, :] - vertices[:, None] - vector  # (i, j): from i to j
    miss = np.hypot(gap[..., 0], gap[..., 1])
    miss = np.where(np.isfinite(miss), miss, np.inf)
    i, j = np.unravel_index(int(np.argmin(miss)), miss.shape)
    if miss[i, j] > 1e-6 * max(size, 1e-300):
        return None
    return vertices[i], vertices[j]


def lever_scene(
    lv: Lever,
    velocity: PlanSeries,
    index: int,
    *,
    lang: str = "en",
    em: float = LETTERING,
    variant: int = 0,
    plan_scale: float | None = None,
    scale: float | None = None,
) -> ForceScene:
    """Zhukovsky's lever at sample ``index``: the velocity plan ``velocity`` (of the same samples) turned by 90
    degrees at its scale μv (``plan_scale``, (m/s)/mm; default its own), every force of ``lv`` at its point's image
    to a force scale μF (``scale``, N/mm; default one that draws the largest 40 mm long; those shorter than half
    the lettering left out), the balancing force at the crank pin's image; names in ``lang``."""
    values = velocity.values[variant, index]  # (L, 2) m/s
    if plan_scale is None:
        plan_scale = drawing_scale(float(np.nanmax(np.hypot(*values[: len(velocity.points)].T), initial=0.0)))
    turn = np.array([[0.0, -1.0], [1.0, 0.0]])  # +90 degrees
    places = (values @ turn.T) / plan_scale
    lines = [np.stack([np.zeros(2), places[j]]) for j in range(1, len(velocity.points))]
    where = {lab: j for j, lab in enumerate(velocity.labels)}
    lines += [np.stack([places[where[e.start]], places[where[e.end]]]) for e in velocity.edges]
    segs = np.array([s for s in lines if np.isfinite(s).all()]).reshape(-1, 2, 2)
    forces = [(lf.image[variant, index] / plan_scale, lf.force) for lf in lv.forces]
    vectors = [f.vector[variant, index] for _, f in forces] + [lv.balancing_force[variant, index]]
    largest = max((float(np.hypot(*v)) for v in vectors if np.isfinite(v).all()), default=0.0)
    scale = drawing_scale(largest * 100.0 / 40.0) if scale is None else float(scale)
    seconds = _second_scales([f.kind for _, f in forces], vectors[:-1], scale, em)
    drafts: list[_Draft] = []
    scales: list[float] = []
    left_out: list[tuple[str, float]] = []
    for (at, f), v in zip(forces, vectors, strict=False):  # those too short to see left out (they need not close)
        size = float(np.hypot(*v)) if np.isfinite(v).all() else 0.0
        each = scale if size / scale >= SMALL * em else seconds.get(f.kind, scale)
        if _drawn(v, largest) and np.isfinite(at).all() and size / each > 0.5 * em:
            drafts.append((at, at + v / each, f, False))
            scales.append(each)
        elif size > 0:
            left_out.append((_name(f, lang), size))
    pin = lv.pin_image[variant, index] / plan_scale
    balancing = PlanForce("Fb", "", "", "balancing", 1, lv.balancing_force, lv.pin_image, np.zeros(1))
    if _drawn(vectors[-1], largest) and np.isfinite(pin).all():
        drafts.append((pin, pin + vectors[-1] / scale, balancing, False))
        scales.append(scale)
    # the pole and the letters of the plan's points where a force acts (and the pin)
    shown = dict.fromkeys(["p", lv.pin] + [lf.label for lf in lv.forces])
    dots, texts = [np.zeros(2)], ["p"]
    seen = {(0.0, 0.0)}
    for lf in lv.forces:
        at = lf.image[variant, index] / plan_scale
        key = (round(float(at[0]), 6), round(float(at[1]), 6))
        if lf.label in shown and np.isfinite(at).all() and key not in seen:
            seen.add(key)
            dots.append(at)
            texts.append(lf.label)
    if np.isfinite(pin).all() and (round(float(pin[0]), 6), round(float(pin[1]), 6)) not in seen:
        dots.append(pin)
        texts.append(lv.pin)
    # points whose images nearly coincide share one label, as on the velocity plan: the pole, the joints' letters,
    # then the centres of mass ("p, b, c, s3" at rest)
    order = [0, *sorted(range(1, len(texts)), key=lambda j: (texts[j].startswith("s"), texts[j]))]
    dots, texts = [dots[j] for j in order], [texts[j] for j in order]
    texts = list(_grouped(tuple(texts), np.ones(len(texts), dtype=bool), np.array(dots)[None], em)[0])
    scene = _scene(
        "lever",
        "",
        (scale, plan_scale),
        em,
        lang,
        (drafts, segs),
        (np.array(dots), tuple(texts)),
        float(velocity.angles[index]),
    )
    arrows = tuple(
        dataclasses.replace(a, value=a.value / scale * each, second=True) if each != scale else a
        for a, each in zip(scene.arrows, scales, strict=True)
    )
    used = tuple((k, v) for k, v in seconds.items() if any(a.second and a.kind == k for a in arrows))
    return dataclasses.replace(scene, arrows=arrows, left_out=tuple(left_out), second_scales=used)


#: On a lever, a force shorter than this many ems at its scale μF is drawn to a scale of its kind (where that is at
#: least :data:`FINER` times finer), which draws the largest of the kind's short ones :data:`SECOND_LENGTH` mm long:
#: the weights and the inertia forces beside a cutting force a thousand times larger.  Only the moments of the
#: forces about the pole balance on a lever, so each force may be drawn to any scale that is stated.
SMALL, FINER, SECOND_LENGTH = 2.0, 4.0, 12.0

#: The letter of a scale of a kind of force on a lever: μG of the weights, μΦ of the inertia forces.
KIND_SYMBOL = {"weight": "G", "inertia": "Φ"}


#: How much wider than :func:`~linkwork.scene.geometry.text_size` (DejaVu's advances) a lever's names are placed:
#: Agg draws text up to a tenth wider at the small sizes of a sheet of twelve levers (6.4 pt at 100 dpi: the
#: glyphs' hinting; the letters of the points at rest about the pole, "p, b, c, d, e, f, s3, s4, s6", 6% wider),
#: and a lever's names crowd about its pole, where a box too narrow puts a name on its neighbour.
HINTED = 0.1


def _second_scales(kinds: list[str], vectors: list[np.ndarray], scale: float, em: float) -> dict[str, float]:
    """The lever's scale (N/mm) of each kind of force of ``kinds`` whose ``vectors`` include some shorter than
    :data:`SMALL` ems at ``scale``, where it is :data:`FINER` times finer, in the order of :data:`FORCE_KINDS`."""
    out: dict[str, float] = {}
    for kind in FORCE_KINDS:
        sizes = np.array([float(np.hypot(*v)) for k, v in zip(kinds, vectors, strict=True) if k == kind])
        small = sizes[np.isfinite(sizes) & (sizes > 0) & (sizes / scale < SMALL * em)]
        if len(small):
            second = drawing_scale(float(small.max()) * 100.0 / SECOND_LENGTH)
            if second * FINER <= scale:
                out[kind] = second
    return out


def _scene(
    kind: str,
    label: str,
    scales: tuple[float, float],
    em: float,
    lang: str,
    drawn: tuple[list[_Draft], np.ndarray],
    points: tuple[np.ndarray, tuple[str, ...]],
    angle: float,
) -> ForceScene:
    """The scene of the ``drawn`` arrows (each start, end, force, resultant) and thin lines, and the ``points``
    (their places and letters), at the ``scales`` of the forces and of the plan (N/mm, m/s per mm), with every name
    placed."""
    (scale, plan_scale), (drafts, lines), (dots, dot_text) = scales, drawn, points
    texts = [_name(f, lang) for _, _, f, _ in drafts]
    segments = np.array([[s, e] for s, e, _, _ in drafts] + [list(x) for x in lines]).reshape(1, -1, 2, 2)
    circles = np.concatenate([dots.reshape(-1, 2), np.full((len(dots), 1), 0.25 * em)], -1)[None]
    mids = np.array([(s + e) / 2 for s, e, _, _ in drafts]).reshape(1, -1, 2)
    along = np.array([e - s for s, e, _, _ in drafts]).reshape(-1, 2)
    size = np.hypot(*along.T)[:, None] if len(along) else np.zeros((0, 1))
    if kind == "force_plan":  # a short arrow's name goes under the plan (short_note)
        mids[0, size[:, 0] < SHORT * em] = np.nan
    with np.errstate(invalid="ignore", divide="ignore"):
        left = np.where(size > 0, np.stack([-along[:, 1], along[:, 0]], -1) / size, np.sqrt(0.5))
    wider = np.array([1.0 + HINTED, 1.0]) if kind == "lever" else np.ones(2)  # a lever's names crowd about its pole
    sizes = np.array([text_size(_as_drawn(t), em) * wider for t in texts]).reshape(1, -1, 2)
    obstacles = Obstacles(segments, circles)
    fine = FINE if kind == "lever" else DIRECTIONS
    gaps = np.full(len(texts), 0.3 * em)
    centres = place_labels(mids, sizes, gaps, obstacles, left[None], pad=0.1 * em, directions=fine)[0]
    boxes = np.concatenate([centres - sizes[0] / 2, centres + sizes[0] / 2], -1)[None]
    dot_sizes = np.array([text_size(t, em) * wider for t in dot_text]).reshape(1, -1, 2)
    anchors = np.where(np.array([bool(t) for t in dot_text], dtype=bool)[:, None], dots.reshape(-1, 2), np.nan)
    dot_centres = place_labels(
        anchors[None],
        dot_sizes,
        np.full(len(dot_text), 0.3 * em),
        obstacles,
        pad=0.1 * em,
        taken=boxes,
        directions=fine,
    )[0]
    arrows = tuple(
        ForceArrow(s, e, f.kind, texts[j], f.tex(lang), centres[j], float(np.hypot(*(e - s))) * scale, resultant)
        for j, (s, e, f, resultant) in enumerate(drafts)
    )
    return ForceScene(
        kind,
        label,
        angle,
        scale,
        plan_scale,
        em,
        arrows,
        lines.reshape(-1, 2, 2),
        dots.reshape(-1, 2),
        dot_text,
        dot_centres.reshape(-1, 2),
    )


def short_note(scene: ForceScene, lang: str = "en") -> str:
    """The line under a force plan naming its short arrows (:data:`SHORT`) with their values:
    ``shorter than 3.5 mm: G6 = 294.3 N, Φ6 = 5.53 N`` (decimal commas in Russian; the inertia forces' Φ as their
    labels draw it in either language); empty where none is."""
    from linkwork.lang import numbers, t

    def listed(pairs: list[tuple[str, float]]) -> str:
        return ", ".join(f"{_as_drawn(name)}\u00a0=\u00a0{value:.4g}\u00a0{t('unit.N', lang)}" for name, value in pairs)

    found = [(a.text, a.value) for a in scene.short()]
    parts = [t("forceplans.short", lang, size=f"{SHORT * scene.em:.1f}", forces=listed(found))] if found else []
    if scene.left_out:
        size = f"{0.5 * scene.em:.1f}"
        parts.append(t("forceplans.left_out", lang, size=size, forces=listed(list(scene.left_out))))
    text = "; ".join(parts)
    return numbers(text, lang)


def _as_drawn(name: str) -> str:
    """A force's ``name`` as its label is measured: the letters ``Phi`` as the one Greek capital drawn (``Φ5``), so
    that the box of an inertia force's name is as wide as the name drawn, not as the three letters."""
    return name.replace("Phi", "Φ")


def _name(f: PlanForce, lang: str) -> str:
    """The name written beside a force: ``Fb`` for the balancing force, the force's own name otherwise."""
    return f.name(lang)
