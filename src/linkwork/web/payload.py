"""The whole cycle of a mechanism as plain JSON-able data, for the viewer and its exported page.

One call solves the cycle at ``steps`` crank angles (kinematics, the velocity
and acceleration plans of every position, and the forces where the
mechanism has masses or loads; :mod:`linkwork.web.cycle`), so the page only
indexes arrays when the crank turns.  Lengths in m, the plans' vectors in m/s
and m/s^2, angles of the cycle in degrees, forces in N, the series in the
units they name; missing values (samples that do not assemble) are ``null``,
except the frame's points, which are always given.  An edit's answer carries
what an edit changes, in a compact form (:mod:`linkwork.web.update`).

Layout (``format: linkwork-view/1``):

* ``angles_deg`` (A,): the drive angle of every sample, counter-clockwise
  from +x, from position 0 in the direction of rotation (the first working
  member at the high end of its stroke, as the report numbers the cycle);
  ``turn_deg`` (A,): the angle φ turned from position 0;
* ``points`` (P,): ``name`` (``link.point``), ``label``, ``link``,
  ``joint`` (a point of a pair); ``local`` (P, 2), each point in its link's
  axes, m; ``positions`` (A, P, 2), m;
* ``links``: the points each moving link is drawn through, and its ``ends``
  (the points of a link given by its ends and length); ``pairs``: the
  joints (``revolute`` / ``prismatic``, links, points, the guide's global
  direction ``axis`` (A, 2) for prismatic pairs, the guide's point
  ``through_point`` where the file names one, and ``frame_point``, the
  frame's point of a pair on the frame whichever side it is named on);
* ``plans``: for ``velocity`` and ``acceleration``, the labels of the plan
  points (``p``, ``a``, ``b``..., and the construction's intermediate
  points), their vectors from the pole ``values`` (A, L, 2), the
  construction's ``vectors`` (from, to, kind, group) and one drawing
  ``scale_per_mm`` for the whole cycle (units per mm of the plan drawn
  full size, before the page scales the drawing to fit its panel; from
  the 1-2-5 series, that draws the longest vector of 95 % of the positions
  at most 100 mm long);
* ``labels_placed``: how many samples, evenly spread, the labels were placed at (``steps``: every one;
  in between, each label keeps its offset from what it names, :func:`carried`);
* ``scene``: the drawing (:mod:`linkwork.scene`), the same the figures and DXF draw: ``items``
  (``kind``, ``link``, vertices ``xy`` in the link's axes, m, ``closed``, ``radius``, ``name``), the
  links' ``poses`` (A, N, 3) that place them, ``labels`` (``text``, ``kind``, ``link``, the labelled
  point ``at`` in its link's axes, the text's ``centre`` (A, 2), m), ``em`` (the text's height, m),
  ``extent`` and the ``paths`` drawn (point indices); for each plan, the ``frame`` the page shows it
  in (mm of the sheet, y up, holding 95 % of the positions), the labels' ``text`` (A, L) (one label
  for plan points that coincide) and ``centre`` (A, L, 2, mm), their ``em`` and the ``kinds`` of
  vector with their names, for a legend;
* ``series``: quantities over the cycle (slider positions, rocker angles,
  driving torque, foundation force...), each with ``label``, ``unit`` and
  ``values`` (A,), written as the command line's JSON writes numbers
  (:mod:`linkwork.io.jsonout`: 12 significant digits, round-off zeros as 0);
  torques and moments counter-clockwise positive (a clockwise drive's
  driving torque is mostly negative), forces x right and y up, as the
  labels say;
* ``forces``: ``available`` (and the ``reason`` where not), the ``checks``
  of the reactions, and the arrows the scheme draws (:mod:`linkwork.web.arrows`):
  ``arrows`` (``kind``, ``name``, ``label``, ``on``, ``by``, the ``point`` it
  acts at), their forces ``values`` (A, K, 2), N, their ``scale_per_mm`` (N
  per mm of the mechanism drawn full size) and ``torque_point``, the crank's
  pivot, where the driving torque is drawn;
* ``force_plans`` (added by the viewer's session, :meth:`linkwork.web.session.Viewer.cycle`): the force plans
  of the groups and Zhukovsky's lever (:mod:`linkwork.web.force_plans`): which there are, and the drawings of
  the samples it carries (none: the live page asks for the sample shown; an exported page carries some);
* ``peaks``: ``driving_torque`` (``value``, ``turn_deg``), the peak refined between the samples as
  every route gives it (:func:`peaks`);
* ``extremes``: every slider on a frame guide and rocker, as
  :func:`linkwork.motion.analysis.extremes` gives them (stroke, extreme
  positions, ``time_ratio`` K and ``forward_time_ratio``);
* ``units``: the unit the page shows each kind of value in (in the page's language) and its factor from SI;
* ``lang`` and ``texts``: the page's language and every text it writes in it, key: text with its fields in braces
  (:func:`~linkwork.web.texts.page_texts`, from the catalogues of :mod:`linkwork.lang`); the series' labels and
  units, the plans' ``kinds`` and ``pole`` (π on a Russian acceleration plan), the groups' ``kind_shown`` (ВВП)
  and the events' ``text`` (in a language other than English) are written in it too;
* ``structure``, ``drives``, ``events``, ``warnings``.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.errors import UnassemblableError
from linkwork.io import jsonout
from linkwork.lang import friction_problem, group_kind, numbers, t
from linkwork.motion.analysis import Output, coordinate, extremes, guide, outputs, slider_coordinates
from linkwork.motion.kinematic_analysis import kinematics
from linkwork.motion.plans import PlanSeries, drawing_scale, longest_length, percentile, plan_series
from linkwork.scene.geometry import SUBSCRIPTED
from linkwork.scene.plans import KINDS, kind_name, plan_scene
from linkwork.scene.scheme import SchemeScene, scheme_scene
from linkwork.structure.model import Mechanism, PairType, per_mechanism
from linkwork.web.arrows import force_arrows
from linkwork.web.cycle import Cycle, compile_message, event_text, solve_cycle
from linkwork.web.texts import display_units, page_texts

if TYPE_CHECKING:
    from linkwork.motion.kinematic_analysis import Kinematics

FORMAT = "linkwork-view/1"

#: Percentile of the positions' longest plan vectors that sets the plans' one scale for the cycle.
PLAN_PERCENTILE = 95.0

#: Height of the plans' labels on the page, as a fraction of the larger side of the plan's frame.
PLAN_FONT = 0.045

#: Samples of a turn the live viewer places its labels at (about every 8 degrees; placing them costs
#: some milliseconds a sample): in between, each label keeps its offset from what it names
#: (:func:`carried`).  The exported page places them at every sample.
LIVE_PLACED = 45


def _json(a: Any, decimals: int | None = None) -> Any:
    """A nested list of Python floats, NaN and infinities as None, optionally rounded."""
    a = np.asarray(a, dtype=float)
    if decimals is not None:
        a = np.round(a, decimals)
    out = a.astype(object)
    out[~np.isfinite(a)] = None
    return out.tolist()


def _significant(a: np.ndarray, digits: int = 9) -> int:
    """Decimals that keep ``digits`` significant digits of the largest finite value of ``a``."""
    finite = np.abs(a[np.isfinite(a)])
    top = float(finite.max()) if finite.size else 0.0
    return digits - (math.ceil(math.log10(top)) if top > 0 else 0)


def cycle_payload(
    mech: Mechanism,
    steps: int = 360,
    overrides: dict[str, float] | None = None,
    placed: int | None = None,
    lang: str = "en",
) -> dict[str, Any]:
    """Everything the viewer shows, over a whole turn of the crank at ``steps`` angles.

    Parameters
    ----------
    mech : Mechanism
        From :func:`linkwork.compile`, with one revolute drive.
    steps : int
        Samples of the turn.
    overrides : dict, optional
        A variant: named values (SI, checked: :func:`linkwork.web.edits.validated`).
    placed : int, optional
        Place the labels at about this many samples, evenly spread (:func:`placed_samples`), and carry
        them along in between; default at every sample.
    lang : str
        The language of the page's texts (:data:`linkwork.lang.LANGUAGES`).

    Returns
    -------
    dict
        JSON-able data, see the module's description.

    Raises
    ------
    LinkworkError
        For a mechanism without a single crank.
    """
    return full_payload(solve_cycle(mech, steps, overrides), placed, lang)


def full_payload(cycle: Cycle, placed: int | None = None, lang: str = "en") -> dict[str, Any]:
    """The payload of a solved cycle (:func:`cycle_payload`), its labels placed at about ``placed`` samples
    (default every one), its texts in ``lang``."""
    mech, kin = cycle.mech, cycle.kin
    series = plan_series(kin)
    angles = kin.angles
    speed = float(kin.rates[0, 0])
    at = placed_samples(len(angles), placed)
    scene = _scene(cycle, series, at, lang)
    out: dict[str, Any] = {
        "format": FORMAT,
        "name": mech.name,
        "source": mech.source,
        "steps": len(angles),
        "labels_placed": len(at),
        "angles_deg": _json(np.degrees(angles), 9),
        "turn_deg": _json(np.abs(np.degrees(angles - angles[0])), 9),
        "speed": speed,
        "period_s": 2 * math.pi / abs(speed) if speed else None,
        "valid": [bool(x) for x in cycle.valid],
        "points": _points(mech),
        "local": _json(cycle.local, 12),
        "positions": _json(cycle.points(), 9),
        "links": _links(mech),
        "pairs": _pairs(mech, kin),
        "plans": _plans(cycle, series),
        "scene": scene,
        "series": _series(cycle, lang),
        "structure": _structure(mech, lang),
        "drives": [_drive(mech, speed)],
        "units": display_units(lang),
        "lang": lang,
        "texts": page_texts(lang),
        "forces": forces_part(cycle, scene["size"]),
    }
    if cycle.forces is not None:  # the independent checks of the reactions (kinetostatics.crosschecks)
        from linkwork.kinetostatics.crosschecks import cross_checks

        out["forces"]["checks"] = _finite(cross_checks(cycle.forces))
    out.update(_outcome(cycle, lang))
    return out


def _outcome(cycle: Cycle, lang: str = "en") -> dict[str, Any]:
    """The extremes, events and warnings of a cycle."""
    return {
        "extremes": [_finite(e.as_dict()) for e in extremes(cycle.kin)],
        "peaks": peaks(cycle),
        "events": events_part(cycle, lang),
        "warnings": _notes(cycle, lang),
    }


def _notes(cycle: Cycle, lang: str) -> list[str]:
    """The warnings of a cycle, those of the friction as the report says them in ``lang``
    (:func:`linkwork.lang.friction_problem`; the others as the analysis words them)."""
    friction = cycle.forces.friction if cycle.forces is not None else None
    said = {str(p): friction_problem(p, lang) for p in (friction.problems if friction is not None else ())}
    return [numbers(said.get(note, note), lang) if lang != "en" else note for note in cycle.notes]


def events_part(cycle: Cycle, lang: str = "en") -> list[dict[str, Any]]:
    """The events of a cycle (:meth:`linkwork.motion.events.Event.as_dict`, its ``message`` in English); in another
    language each with its ``text`` as the report says it (``event.KIND`` of :mod:`linkwork.lang`, the group in the
    language's letters, the crank angles φ from position 0, a decimal comma in Russian)."""
    out = [_finite(e.as_dict()) for e in cycle.kin.events]
    if lang != "en":
        for item, e in zip(out, cycle.kin.events, strict=True):
            item["text"] = event_text(cycle, e, lang)
    return out


def peaks(cycle: Cycle) -> dict[str, Any]:
    """The peak driving torque of the cycle (largest size, with its sign), refined between the samples as every
    route gives it (:func:`linkwork.kinetostatics.torque_peak`): ``value`` (N m) and ``turn_deg``, the angle
    turned from position 0; empty without forces or with several drives."""
    from linkwork.kinetostatics.peaks import torque_peak

    f = cycle.forces
    if f is None or cycle.mech.n_drives != 1:
        return {}
    peak = torque_peak(f)
    value, at = float(peak.value[0]), float(peak.at[0])
    if not math.isfinite(value):
        return {}
    angles = f.angles
    sign = 1.0 if len(angles) < 2 or angles[1] >= angles[0] else -1.0
    turn = math.degrees((sign * (at - float(angles[0]))) % (2 * math.pi))
    return {"driving_torque": {"value": value, "turn_deg": turn}}


def _drive(mech: Mechanism, speed: float) -> dict[str, Any]:
    return {
        "joint": mech.pair_joint[int(mech.drive_pair[0])],
        "speed_rad_s": speed,
        "rpm": abs(speed) * 30 / math.pi,
        "direction": "ccw" if speed >= 0 else "cw",
        "start_deg": math.degrees(float(mech.drive_start[0])),
    }


def forces_part(cycle: Cycle, size: float, encode: Callable[[np.ndarray], Any] | None = None) -> dict[str, Any]:
    """Whether there are forces (and why not), and the arrows of a scheme of ``size`` m
    (:mod:`linkwork.web.arrows`): what each is, and its force (A, K, 2) in N, as ``encode`` writes an
    array (default: nested lists of 9 significant digits)."""
    out: dict[str, Any] = {"available": cycle.forces is not None, "reason": cycle.reason}
    found = force_arrows(cycle, size)
    if cycle.forces is None or found is None:
        return out
    out["arrows"] = [a.as_dict() for a in found.arrows]
    out["scale_per_mm"] = found.scale
    out["torque_point"] = found.torque_point
    out["values"] = encode(found.values) if encode is not None else _json(found.values, _significant(found.values))
    return out


def _finite(d: dict[str, Any]) -> dict[str, Any]:
    return {k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in d.items()}


def _points(mech: Mechanism) -> list[dict[str, Any]]:
    from linkwork.structure.model import point_labels

    labels = dict((p, label) for label, p in point_labels(mech, with_all=True))
    joint = {int(p) for pair in mech.pair_points for p in pair if p >= 0}
    return [
        {
            "name": name,
            "label": labels.get(p, name),
            "link": int(mech.point_link[p]),
            "joint": p in joint,
            "virtual": bool(mech.link_virtual[mech.point_link[p]]),
        }
        for p, name in enumerate(mech.point_names)
    ]


def _links(mech: Mechanism) -> list[dict[str, Any]]:
    """Each link with the points it is drawn through: its joint points, then its markers."""
    joint = {int(p) for pair in mech.pair_points for p in pair if p >= 0}
    out = []
    for i, name in enumerate(mech.link_names):
        own = [p for p in range(len(mech.point_names)) if mech.point_link[p] == i]
        draw = [p for p in own if p in joint] + [p for p in own if p not in joint]
        ends = [int(p) for p in mech.link_ends[i]] if i and mech.link_ends[i][0] >= 0 else None
        out.append({"index": i, "name": name, "virtual": bool(mech.link_virtual[i]), "draw": draw, "ends": ends})
    return out


def _pairs(mech: Mechanism, kin: Kinematics) -> list[dict[str, Any]]:
    driven = {int(k) for k in mech.drive_pair}
    out = []
    for k in range(mech.n_pairs):
        a, b = (int(x) for x in mech.pair_links[k])
        item: dict[str, Any] = {
            "joint": mech.pair_joint[k],
            "type": "revolute" if mech.pair_type[k] == PairType.REVOLUTE else "prismatic",
            "links": [a, b],
            "points": [int(x) for x in mech.pair_points[k]],
            "driven": k in driven,
            "axis": None,
            # the frame's point of the pair (a support is drawn there), whichever side the frame is named on
            "frame_point": int(mech.pair_points[k, 0 if a == 0 else 1]) if 0 in (a, b) else None,
            # the point of the guide its line passes through, where the file names one
            "through_point": int(mech.pair_origin_point[k]) if mech.pair_origin_point[k] >= 0 else None,
        }
        if mech.pair_type[k] == PairType.PRISMATIC:
            item["axis"] = _json(guide(kin, k)[1][0], 9)
        out.append(item)
    return out


def _plans(cycle: Cycle, series: tuple[PlanSeries, PlanSeries]) -> dict[str, Any]:
    """The plans of every sample: plan points (pole-relative vectors) and the construction's vectors."""
    out = {}
    for one in series:
        index = {lab: j for j, lab in enumerate(one.labels)}
        out[one.kind] = {
            "kind": one.kind,
            "unit": "m/s" if one.kind == "velocity" else "m/s^2",
            "labels": list(one.labels),
            "absolute": [index[lab] for lab in one.points if lab != "p"],
            "vectors": [
                {"from": index[e.start], "to": index[e.end], "kind": e.kind, "group": e.group, "about": e.about}
                for e in one.edges
            ],
            "scale_per_mm": cycle_scale(one, cycle.valid),
            "values": _json(plan_values(one, cycle.valid), _significant(plan_values(one, cycle.valid))),
        }
    return out


def plan_values(series: PlanSeries, valid: np.ndarray) -> np.ndarray:
    """The plan points' vectors ``(A, L, 2)`` of the first variant, NaN where the mechanism does not assemble."""
    return np.where(valid[:, None, None], series.values[0], np.nan)


def cycle_scale(series: PlanSeries, valid: np.ndarray) -> float:
    """One scale (units per mm) for the plans of the whole cycle: the longest vector of nearly every position
    at most 100 mm (the rare positions near a dead point, where accelerations grow without bound, would
    shrink all the others): the :data:`PLAN_PERCENTILE` of the positions' longest vectors."""
    values = np.where(valid[:, None, None], series.values[0], np.nan)
    longest = longest_length(values[:, : len(series.points)])
    return drawing_scale(percentile(longest, PLAN_PERCENTILE) if len(longest) else 0.0)


def placed_samples(n: int, most: int | None) -> np.ndarray:
    """Indices of the samples (of ``n``) labels are placed at: every one, or one in ``ceil(n / most)``."""
    return np.arange(0, n, 1 if most is None else max(1, math.ceil(n / most)))


def carried(centres: np.ndarray, anchors: np.ndarray, at: np.ndarray) -> np.ndarray:
    """Labels' centres at every sample from those placed at the samples ``at``: each keeps its offset from
    its anchor at the nearest sample it was placed at along the turn.

    Parameters
    ----------
    centres : ndarray, shape (A, L, 2)
        NaN but at the samples ``at`` (and where a label is not drawn).
    anchors : ndarray, shape (A, L, 2)
        What each label names, at every sample; NaN where it is not drawn.
    at : ndarray of int, shape (K,)
        The samples placed, ascending.

    Returns
    -------
    ndarray, shape (A, L, 2)
    """
    if len(at) == len(centres):
        return centres
    nearest = nearest_placed(len(centres), at)
    out = anchors + (centres[nearest] - anchors[nearest])
    out[at] = centres[at]
    return out


def nearest_placed(n: int, at: np.ndarray) -> np.ndarray:
    """For each of ``n`` samples of a turn, the nearest of the samples ``at`` (ascending) along the turn, which
    closes on itself (the last samples are near the first), ``(n,)``."""
    ring = np.concatenate([at - n, at, at + n])
    i = np.arange(n)
    k = np.clip(np.searchsorted(ring, i), 1, len(ring) - 1)
    return np.where(i - ring[k - 1] <= ring[k] - i, ring[k - 1], ring[k]) % n


def _scene(cycle: Cycle, series: tuple[PlanSeries, PlanSeries], at: np.ndarray, lang: str = "en") -> dict[str, Any]:
    """The drawing of the cycle (:mod:`linkwork.scene`): the scheme's items in their links' axes, the links'
    poses and the labels, placed at the samples ``at`` (:func:`carried` between); for each plan, the frame the
    page shows and the labels."""
    scheme = scheme_scene(cycle.kin, at=[int(i) for i in at], cycle=cycle.symbols)
    centres = np.stack([lab.centre for lab in scheme.labels], 1) if scheme.labels else np.zeros((len(at), 0, 2))
    centres = carried(centres, _label_anchors(scheme), at)
    labels = [
        {
            "text": lab.text,
            "kind": lab.kind,
            "link": lab.link,
            "at": _json(lab.at, 12),
            "centre": _json(centres[:, j], 5),
        }
        for j, lab in enumerate(scheme.labels)
    ]
    out = scheme_shape(scheme)
    out.update(
        {
            "extent": _json(scheme.extent(), 9),
            "poses": _json(scheme.poses, 9),
            "labels": labels,
            "paths": [cycle.mech.point_names.index(name) for name in scheme.path_names],
            "plans": {one.kind: _plan_scene(cycle, one, at, lang) for one in series},
            "subscripts": SUBSCRIPTED,
        }
    )
    return out


def _label_anchors(scheme: SchemeScene) -> np.ndarray:
    """Where each of the scheme's labels points at every sample, ``(A, L, 2)``, m: its ``at`` placed by its
    link's pose (NaN where the mechanism does not assemble)."""
    at = np.array([lab.at for lab in scheme.labels], dtype=float).reshape(-1, 2)  # (L, 2)
    pose = scheme.poses[:, [lab.link for lab in scheme.labels]]  # (A, L, 3)
    c, s = np.cos(pose[..., 2]), np.sin(pose[..., 2])
    x = pose[..., 0] + c * at[:, 0] - s * at[:, 1]
    y = pose[..., 1] + s * at[:, 0] + c * at[:, 1]
    return np.stack([x, y], -1)


def scheme_shape(scheme: SchemeScene) -> dict[str, Any]:
    """The scheme's sizes and items (what a dimension changes, but for the poses, the labels and the extent)."""
    # every item's vertices rounded at once, then cut back into items (a drawing's vertices are finite)
    xy = [np.asarray(it.xy, dtype=float).reshape(-1, 2) for it in scheme.items]
    rows = np.round(np.concatenate(xy), 9).tolist() if xy else []
    ends = np.cumsum([len(a) for a in xy]).tolist()
    items = [
        {
            "kind": it.kind,
            "link": it.link,
            "xy": rows[end - len(a) : end],
            "closed": it.closed,
            "radius": it.radius,
            "name": it.name,
        }
        for it, a, end in zip(scheme.items, xy, ends, strict=True)
    ]
    return {"size": scheme.size, "r": scheme.r, "em": scheme.em, "items": items, "elements": element_list(scheme)}


def element_list(scheme: SchemeScene) -> list[dict[str, Any]]:
    """The scheme's springs and dampers (:class:`~linkwork.scene.Element`) as the page draws them: ``kind``,
    ``name``, the ``links`` of its two points, the points ``at`` in their links' axes and the symbol's
    ``strokes``, rows ``(f, s, c)``: the vertex ``a + f (b - a) + s u + c n`` between its points ``a`` and ``b``."""
    return [
        {
            "kind": e.kind,
            "name": e.name,
            "links": list(e.links),
            "at": _json(e.at, 12),
            "strokes": [_json(stroke, 9) for stroke in e.strokes],
        }
        for e in scheme.elements
    ]


def _plan_scene(cycle: Cycle, series: PlanSeries, at: np.ndarray, lang: str = "en") -> dict[str, Any]:
    """The labels of a plan at every sample, placed in the frame the page shows it in (:func:`plan_frame`) at
    the samples ``at``, and between them carried with their points and their texts kept; its pole's letter
    (``pole``: π on a Russian acceleration plan) and the names of its kinds of vector in ``lang``."""
    out, scale = plan_shape(cycle, series)
    n = len(cycle.valid)
    scene = plan_scene(series, at, scale=scale, em=out["em"], valid=cycle.valid, lang=lang)
    drawn = {kind for i in range(len(at)) for kind in scene.kinds(i)}
    out["kinds"] = {k: kind_name(k, series.kind, lang) for k in KINDS if k in drawn}
    out["pole"] = scene.pole
    points = plan_values(series, cycle.valid) / scale  # (A, L, 2), mm of the sheet
    centres = np.full(points.shape, np.nan)
    centres[at] = scene.centres
    centres = carried(centres, points, at)
    text = np.full((n, len(series.labels)), "", dtype=object)
    text[at] = np.array(scene.text, dtype=object).reshape(len(at), -1)
    text = text[nearest_placed(n, at)]  # each sample's texts: those of the sample its labels are carried from
    shown = (text != "") & np.isfinite(centres).all(-1)
    out["text"] = np.where(shown, text, "").tolist()
    out["centres"] = _json(np.where(shown[..., None], centres, np.nan), 3)
    return out


def plan_shape(cycle: Cycle, series: PlanSeries) -> tuple[dict[str, Any], float]:
    """The frame a plan is shown in for the cycle and its labels' size (``frame``, ``em``), and its scale."""
    scale = cycle_scale(series, cycle.valid)
    frame = plan_frame(series, cycle.valid, scale)
    em = PLAN_FONT * float(max(frame[2] - frame[0], frame[3] - frame[1]))
    return {"frame": _json(frame, 6), "em": em}, scale


def plan_frame(series: PlanSeries, valid: np.ndarray, scale: float) -> np.ndarray:
    """``[x0, y0, x1, y1]`` (mm of the sheet, y up) that holds the plans of 95 % of the positions, the pole
    among them: one frame for the cycle, so that the plan does not jump while the crank turns."""
    ok = np.asarray(valid, dtype=bool)
    if not ok.any():
        return np.array([-1.0, -1.0, 1.0, 1.0])
    pts = np.ascontiguousarray(np.moveaxis(series.values[0][ok], 1, -1)) / scale  # (a, 2, L): the points last
    finite = np.isfinite(pts)
    lo = np.minimum(np.where(finite, pts, np.inf).min(-1), 0.0)  # (a, 2)
    hi = np.maximum(np.where(finite, pts, -np.inf).max(-1), 0.0)
    q = np.quantile(np.concatenate([lo, hi], 1), [0.025, 0.975], axis=0)
    return np.concatenate([q[0, :2], q[1, 2:]])


def _series(cycle: Cycle, lang: str = "en") -> list[dict[str, Any]]:
    """Quantities over the cycle the page can chart, their labels and units in ``lang``."""
    return [
        {"key": key, "label": label, "unit": unit, "group": group, "values": _written(values)}
        for key, label, unit, group, values in series_values(cycle, lang)
    ]


def _written(values: np.ndarray) -> list[float | None]:
    """The numbers of ``values`` (A,) as the one JSON writer writes them (:func:`linkwork.io.jsonout.dumps`),
    so that a series the page shows or saves is the one ``--json`` gives."""
    out: list[float | None] = json.loads(jsonout.dumps(np.asarray(values, dtype=float)))
    return out


def series_values(cycle: Cycle, lang: str = "en") -> list[tuple[str, str, str, str, np.ndarray]]:
    """(key, label, unit, group, values (A,)) of every quantity over the cycle the page can chart, the labels and
    units in ``lang``."""
    motion, forces = _series_names(cycle.mech)
    named = list(zip(motion, _motion_values(cycle), strict=True))
    if cycle.forces is not None:
        named += zip(forces, _force_values(cycle), strict=True)
    return [
        (key, t(f"view.series.{text}", lang, **fields), t(f"view.unit.{unit}", lang), group, np.asarray(v, float))
        for (key, text, fields, unit, group), v in named
    ]


#: The key of a series, the key of its label's text (``view.series.*`` of :mod:`linkwork.lang`) and its fields,
#: the key of its unit's (``view.unit.*``) and its group.
_Name = tuple[str, str, dict[str, str], str, str]


@per_mechanism
def _series_names(mech: Mechanism) -> tuple[tuple[_Name, ...], tuple[_Name, ...]]:
    """The names of the series of ``mech`` the page can chart: of the motion's (:func:`_motion_values`), of the
    forces' (:func:`_force_values`)."""
    motion: list[_Name] = []
    for output in _outputs(mech):
        if output.kind == "slider":
            at = {"point": mech.point_names[output.point].split(".", 1)[1], "joint": output.name}
            motion.append((f"slider:{output.name}:s", "slider_s", at, "mm", "sliders"))
            motion.append((f"slider:{output.name}:v", "slider_v", at, "m_s", "sliders"))
            motion.append((f"slider:{output.name}:a", "slider_a", at, "m_s2", "sliders"))
        else:
            link = {"link": output.name}
            motion.append((f"link:{output.name}:angle", "angle", link, "deg", "links"))
            motion.append((f"link:{output.name}:omega", "omega", link, "rad_s", "links"))
    # signs as in linkwork.forces: torques and moments counter-clockwise positive, whatever the direction of
    # rotation (a clockwise crank driven against the load has a negative driving torque); x right, y up
    forces: list[_Name] = [
        ("torque", "torque", {}, "Nm", "forces"),
        ("foundation:fx", "fx", {}, "N", "forces"),
        ("foundation:fy", "fy", {}, "N", "forces"),
        ("foundation:m", "m", {}, "Nm", "forces"),
    ]
    forces += [(f"reaction:{joint}", "reaction", {"joint": joint}, "N", "forces") for joint in _supports(mech)]
    return tuple(motion), tuple(forces)


def _motion_values(cycle: Cycle) -> list[np.ndarray]:
    """Each slider's position (mm), velocity and acceleration along its guide, each rocker's angle (deg) and angular
    velocity, in the order of their pairs."""
    kin, outs = cycle.kin, _outputs(cycle.mech)
    sliders = iter(slider_coordinates(kin, [o for o in outs if o.kind == "slider"])[..., 0, :])  # (S, 3, A)
    out: list[np.ndarray] = []
    for output in outs:
        if output.kind == "slider":
            s, v, a = next(sliders)
            out += [1000 * s, v, a]
        else:
            s, v, _ = coordinate(kin, output)
            out += [np.degrees(s[0]), v[0]]
    return out


def _force_values(cycle: Cycle) -> list[np.ndarray]:
    """The driving torque, the foundation's forces and moment, and the size of the force each support takes (of all
    the links it holds in the joint)."""
    mech, forces = cycle.mech, cycle.forces
    assert forces is not None
    found = cycle.one(forces.foundation)
    supports = _supports(mech)
    f = cycle.one(forces.reactions(supports, (mech.link_names[0],) * len(supports)))  # (A, S, 2)
    size = np.hypot(f[..., 0], f[..., 1])
    return [cycle.one(forces.driving_torque), found[:, 0], found[:, 1], found[:, 2], *size.T]


@per_mechanism
def _outputs(mech: Mechanism) -> tuple[Output, ...]:
    """The sliders and rockers of ``mech`` (:func:`~linkwork.motion.analysis.outputs`), found once."""
    return outputs(mech)


@per_mechanism
def _supports(mech: Mechanism) -> tuple[str, ...]:
    """The joints of ``mech``'s revolute pairs with the frame, each once, in the order of their pairs."""
    on_frame = (k for k in range(mech.n_pairs) if 0 in mech.pair_links[k] and mech.pair_type[k] == PairType.REVOLUTE)
    return tuple(dict.fromkeys(mech.pair_joint[k] for k in on_frame))


def _structure(mech: Mechanism, lang: str = "en") -> dict[str, Any]:
    """The structure of ``mech``; each group's kind also as ``lang`` writes it (``kind_shown``: ВВП in Russian)."""
    s = mech.structure
    out = s.as_dict()
    out["groups"] = [
        {**g.as_dict(), "label": g.label, "formula_part": g.label.split(" ")[0], "kind_shown": group_kind(g.kind, lang)}
        for g in s.groups
    ]
    out["link_names"] = list(mech.link_names)
    out["warnings"] = [numbers(t(key, lang, **dict(fields)), lang) for key, fields in s.said]  # as the report says them
    return out


#: Largest crank step (rad) of :func:`way`.
WAY_STEP = math.radians(1.0)


def way(mech: Mechanism, angle: float) -> np.ndarray:
    """The crank angles (rad) from the assembly pose to ``angle`` as the viewer's cycle (a turn from position 0 in
    the drive's direction, :meth:`linkwork.study.Study.turn`) reaches it from there: forward where it lies later in
    that turn, back where earlier, in steps of at most :data:`WAY_STEP`; the last is ``angle`` (to whole turns)."""
    from linkwork.motion.analysis import zero_angle
    from linkwork.motion.kinematic_analysis import direction

    sense, zero, start = direction(mech), zero_angle(mech), float(mech.drive_start[0])
    u0, u = (((a - zero) * sense) % (2 * math.pi) for a in (start, angle))
    return start + sense * np.linspace(0.0, u - u0, max(3, math.ceil(abs(u - u0) / WAY_STEP) + 1))


def pose_payload(mech: Mechanism, angle_deg: float, overrides: dict[str, float] | None = None) -> dict[str, Any]:
    """Positions of every point at one crank angle: ``{name: [x, y]}`` in m, in the assembly mode the cycle has
    there (solved along :func:`way`: past a change point, where the motion goes on in the other mode, as the cycle
    and ``linkwork kinematics`` show it, not in the file's mode as a pose solved on its own would be).

    ``overrides`` (SI, checked) make it a variant, as for the cycle.  ``angle_deg`` (degrees) is echoed as
    given; the frame's points are given where the mechanism does not assemble, as in the cycle.

    Raises
    ------
    UnassemblableError
        For a variant that does not assemble at the drive angle of the assembly pose (the file edited so
        would not compile): the compiler's message.
    """
    variants = {name: [value] for name, value in (overrides or {}).items()} or None
    kin = kinematics(mech, way(mech, math.radians(angle_deg)), variants=variants)
    if variants and not kin.valid_all[0, 0]:
        message = compile_message(mech, dict(overrides or {}))
        raise UnassemblableError(message or "the mechanism does not assemble at the drive angle of its assembly pose")
    pts = kin.points()
    pts = np.array(pts[0] if kin.variants else pts)[-1]
    frame = np.asarray(mech.point_link) == 0
    pts[frame] = kin.local[frame, :, 0, 0]
    return {
        "angle_deg": angle_deg,
        "valid": bool(kin.valid_all[0, -1]),
        "points": {name: _json(pts[p]) for p, name in enumerate(mech.point_names)},
    }
