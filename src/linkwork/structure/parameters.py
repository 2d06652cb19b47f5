"""Named parameters of a mechanism: what an override means, in one place.

A parameter is named by its path in the mechanism file, and an override
means exactly what the same edit of the file means:

=================================  ===============================================  ========
path                               what it is                                       SI unit
=================================  ===============================================  ========
``links.crank.length``             length of a link given by ``ends``               m
``links.rocker.points.B.x``        a point of a link, in the link's coordinates     m
``frame.points.O1.y``              a frame point                                    m
``joints.guide_E.axis``            direction of a guide, in the guide's coordinates rad
``joints.guide_E.through.x``       a point of a guide line given by coordinates     m
``links.rod.mass``                 mass of a link                                   kg
``links.rod.inertia``              the file's moment of inertia of a link (about    kg m^2
                                   the centre of mass, or about ``inertia_about``)
=================================  ===============================================  ========

**The mass rule.**  A mass property the file gives stays as it is; one it
leaves to its default follows the new geometry and mass:

- the centre of mass: given as local ``[x, y]``, it stays; named by a point
  (``com: E``), it stays at that point wherever the point goes; not given, it
  is the middle of the ends for a link given by ``ends`` (a uniform rod:
  further points are markers or joints, not material), otherwise the
  centroid of the link's points, of the variant;
- the moment of inertia: given about the centre of mass, it stays; given
  about a point (``inertia_about``), the inertia about that point stays, so
  the one about the centre of mass is ``J_P - m |P - C|^2`` of the variant;
  not given, a link given by ``ends`` is a uniform rod, ``m L^2 / 12`` of the
  variant's length and mass (zero for other links).

:func:`apply` gives the arrays of the variants (:class:`Geometry` and
:class:`Masses`) for the kinematics and the forces; :func:`file_text` and
:func:`edited_spec` check values against their parameters and have
:mod:`linkwork.spec.edit` write them into the file, keeping its comments, its
layout and the units it writes each value in.  :func:`compile <linkwork.structure.compile.compile>`
uses :func:`mass_properties` for the file's own values, so the rule has one
home.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

import numpy as np
import numpy.typing as npt

from linkwork.did_you_mean import suggest
from linkwork.errors import ParameterError
from linkwork.spec import edit
from linkwork.spec.reader import described
from linkwork.spec.schema import Spec
from linkwork.structure.model import Mechanism, PairType, per_mechanism
from linkwork.units import DEFAULT_UNITS, KINDS, SI_UNITS

#: The centre of mass given in the file's link coordinates: it stays.
COM_GIVEN = -2
#: No centre of mass in the file: the middle of the ends of a link given by ends, else the centroid of its points.
COM_CENTROID = -1

#: A moment of inertia given about the centre of mass: it stays.
INERTIA_GIVEN = -3
#: No moment of inertia in the file, a link given by ends: a uniform rod, m L^2 / 12.
INERTIA_ROD = -2
#: No moment of inertia in the file and no ends: zero.
INERTIA_NONE = -1


@dataclass(frozen=True)
class Geometry:
    """Local dimensions of every variant.

    Attributes
    ----------
    point_local : ndarray, shape (V, 1, P, 2)
    pair_origin : ndarray, shape (V, 1, M, 2)
    pair_axis : ndarray, shape (V, 1, M, 2)
        The singleton axis broadcasts over crank angles.
    """

    point_local: np.ndarray
    pair_origin: np.ndarray
    pair_axis: np.ndarray

    @property
    def n_variants(self) -> int:
        return self.point_local.shape[0]

    @functools.cached_property
    def link_major(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``point_local``, ``pair_origin`` and ``pair_axis`` in the layout of the kinematic state
        (:func:`soa`), made once per geometry (once per mechanism for its file's); read-only."""
        arrays = tuple(soa(a) for a in (self.point_local, self.pair_origin, self.pair_axis))
        for array in arrays:
            array.flags.writeable = False
        return arrays  # type: ignore[return-value]


def soa(a: np.ndarray) -> np.ndarray:
    """(V, 1, K, 2) geometry arrays -> (K, 2, V, 1)."""
    return np.ascontiguousarray(np.asarray(a, dtype=float).transpose(2, 3, 0, 1))


@dataclass(frozen=True)
class Masses:
    """Mass properties of every link of every variant.

    Attributes
    ----------
    mass : ndarray, shape (V, N)
        kg.
    com : ndarray, shape (V, N, 2)
        Centre of mass in the link's coordinates, m.
    inertia : ndarray, shape (V, N)
        Moment of inertia about the centre of mass, kg m^2.
    """

    mass: np.ndarray
    com: np.ndarray
    inertia: np.ndarray


@dataclass(frozen=True)
class Parameter:
    """One named parameter.

    Attributes
    ----------
    name : str
        Its path in the file, e.g. ``links.crank.length``.
    kind : str
        The kind of quantity (:data:`linkwork.units.KINDS`): ``length``, ``angle``, ``mass`` or ``inertia``.
    value : float
        The file's value, SI.
    group : str
        ``dimensions`` or ``masses``.
    positive : bool
        Only values above zero are valid (lengths of links, masses); inertias must not be negative.
    note : str
        What it means where the name does not say (``about O3`` for an inertia).
    """

    name: str
    kind: str
    value: float
    group: str
    positive: bool = False
    note: str = ""

    @property
    def unit(self) -> str:
        """Its SI unit."""
        return KINDS[self.kind][1]

    def as_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "kind": self.kind,
            "unit": self.unit,
            "value": self.value,
            "group": self.group,
            "note": self.note,
        }

    def check(self, value: float) -> str | None:
        """What is wrong with ``value`` (SI) for this parameter, or None."""
        if not math.isfinite(value):
            return f"{self.name}: expected a finite number, got {value!r}"
        if self.positive and value <= 0:
            return f"{self.name}: expected a positive {self.kind}, got {value:g} {self.unit}"
        if self.kind == "inertia" and value < 0:
            return f"{self.name}: expected a moment of inertia of 0 or more, got {value:g} {self.unit}"
        return None


@per_mechanism
def parameters_by_name(mech: Mechanism) -> Mapping[str, Parameter]:
    """The named parameters of ``mech`` by name, in the order of :func:`parameter_list`; found once a
    mechanism (read-only)."""
    return MappingProxyType({p.name: p for p in (*_dimensions(mech), *_masses(mech))})


def parameter_list(mech: Mechanism) -> list[Parameter]:
    """Every named parameter of ``mech``, with the file's values (SI): the dimensions, then the
    mass and moment of inertia of every moving link."""
    return list(parameters_by_name(mech).values())


def parameter_values(mech: Mechanism) -> dict[str, float]:
    """The named parameters an override may set, with their values (``linkwork.parameters``).

    Parameters
    ----------
    mech : Mechanism
        A compiled mechanism (``linkwork.parameters`` also takes a path, an example name or a Spec).

    Returns
    -------
    dict of str to float
        Each parameter's name (``links.crank.length``, ``frame.points.O4.x``, a link's mass and moment of
        inertia) and its value in SI units (m, kg, kg m^2).

    Examples
    --------
    >>> import linkwork as lw
    >>> lw.parameters("four-bar")["frame.points.O4.x"]  # m
    0.3
    """
    return {p.name: p.value for p in parameter_list(mech)}


def parameter(mech: Mechanism, path: str) -> Parameter:
    """The parameter named ``path``; :class:`ParameterError` with the closest name for an unknown one."""
    known = parameters_by_name(mech)
    if path in known:
        return known[path]
    raise ParameterError(f'no parameter "{path}"{suggest(path, list(known))}; linkwork.parameters(mech) lists them')


def _dimensions(mech: Mechanism) -> list[Parameter]:
    out: list[Parameter] = []
    for p, (name, link) in enumerate(zip(mech.point_names, mech.point_link, strict=True)):
        lname, pname = name.split(".", 1)
        if mech.link_virtual[link]:
            continue
        base = f"frame.points.{pname}" if link == 0 else f"links.{lname}.points.{pname}"
        ends = mech.link_ends[link]
        if link != 0 and ends[1] == p:
            out.append(Parameter(f"links.{lname}.length", "length", float(mech.point_local[p, 0]), "dimensions", True))
            continue
        if link != 0 and ends[0] == p:
            continue
        out.append(Parameter(f"{base}.x", "length", float(mech.point_local[p, 0]), "dimensions"))
        out.append(Parameter(f"{base}.y", "length", float(mech.point_local[p, 1]), "dimensions"))
    seen: set[str] = set()
    for k, joint in enumerate(mech.pair_joint):
        if mech.pair_type[k] != PairType.PRISMATIC or joint in seen:
            continue
        seen.add(joint)
        angle = float(np.arctan2(mech.pair_axis[k, 1], mech.pair_axis[k, 0]))
        out.append(Parameter(f"joints.{joint}.axis", "angle", angle, "dimensions"))
        if mech.pair_origin_point[k] < 0:
            for c, axis in enumerate("xy"):
                value = float(mech.pair_origin[k, c])
                out.append(Parameter(f"joints.{joint}.through.{axis}", "length", value, "dimensions"))
    return out


def _masses(mech: Mechanism) -> list[Parameter]:
    out: list[Parameter] = []
    for i, lname in enumerate(mech.link_names):
        if i == 0 or mech.link_virtual[i]:
            continue
        out.append(Parameter(f"links.{lname}.mass", "mass", float(mech.link_mass[i]), "masses", True))
        rule = int(mech.link_inertia_rule[i])
        if rule >= 0:
            about = mech.point_names[rule].split(".", 1)[1]
            value, note = float(mech.link_inertia_given[i]), f"about {about}"
        else:
            value, note = float(mech.link_inertia[i]), "about the centre of mass"
        out.append(Parameter(f"links.{lname}.inertia", "inertia", value, "masses", note=note))
    return out


# --- the arrays of the variants --------------------------------------------------------------------


def file_units(spec: Spec | None) -> dict[str, str]:
    """The units bare numbers of the description ``spec`` are read in, by kind (SI without a description)."""
    if spec is None:
        return dict(SI_UNITS)
    return {**DEFAULT_UNITS, **spec.units.model_dump(exclude_none=True)}


def override_values(mech: Mechanism, path: str, value: Any) -> np.ndarray:
    """The values of the override ``path`` of ``mech`` in SI, ``(V,)``: numbers are SI; a string is read
    as ``linkwork sweep`` reads a value (``"90 mm"``; a bare number in the file's unit of the parameter's
    kind, :func:`file_units`).

    Raises
    ------
    ParameterError
        For an unknown path, or a value that is neither a number nor such a string (one message that
        names the path, the value and what is expected).
    """
    from linkwork.errors import UnitParseError
    from linkwork.units import parse_quantity

    param = parameter(mech, path)
    items = np.asarray(value, dtype=object).ravel()
    if not any(isinstance(x, str) for x in items):
        try:
            return np.asarray(value, dtype=float).ravel()
        except (TypeError, ValueError):
            pass
    declared = file_units(described(mech.description))
    out = np.empty(len(items))
    for i, x in enumerate(items):
        try:
            out[i] = parse_quantity(x, param.kind, declared) if isinstance(x, str) else float(x)
        except (UnitParseError, TypeError, ValueError) as exc:
            unit = KINDS[param.kind][1]
            raise ParameterError(
                f'variants["{path}"]: expected numbers in {unit} or {param.kind}s with a unit such as '
                f'"{_example(param.kind)}", got {x!r}' + (f" ({exc})" if isinstance(exc, UnitParseError) else "")
            ) from None
    return out


def _example(kind: str) -> str:
    return {"length": "90 mm", "angle": "30 deg", "mass": "2 kg", "inertia": "0.1 kg*m^2"}.get(kind, "1")


def apply(mech: Mechanism, overrides: Mapping[str, npt.ArrayLike] | None = None) -> tuple[Geometry, Masses]:
    """The geometry and mass properties of the variants that ``overrides`` (path -> SI value or
    ``(V,)`` array of values) describe; one variant, the file's, when there are none.

    Raises
    ------
    ParameterError
        For an unknown path (with the closest known one) or arrays of unequal length.
    """
    overrides = overrides or {}
    sizes = {np.size(v) for v in overrides.values()} - {1}
    if len(sizes) > 1:
        raise ParameterError(f"override arrays must have one length, got lengths {sorted(sizes)}")
    n = sizes.pop() if sizes else 1
    pts = np.repeat(np.asarray(mech.point_local, dtype=float)[None], n, axis=0)
    origin = np.repeat(np.asarray(mech.pair_origin, dtype=float)[None], n, axis=0)
    axis = np.repeat(np.asarray(mech.pair_axis, dtype=float)[None], n, axis=0)
    mass = np.repeat(np.asarray(mech.link_mass, dtype=float)[None], n, axis=0)
    given = np.repeat(np.asarray(mech.link_inertia_given, dtype=float)[None], n, axis=0)
    inertia_rule = np.asarray(mech.link_inertia_rule).copy()
    for path, value in overrides.items():
        v = np.broadcast_to(override_values(mech, path, value), (n,))
        _set(mech, path.split("."), v, (pts, origin, axis), (mass, given, inertia_rule))
    follow = np.flatnonzero(mech.pair_origin_point >= 0)
    origin[:, follow] = pts[:, mech.pair_origin_point[follow]]
    if not overrides:
        masses = Masses(mass, np.asarray(mech.link_com, dtype=float)[None], np.asarray(mech.link_inertia)[None])
    else:
        com, inertia = mass_properties(mech, pts, mass, given, inertia_rule)
        masses = Masses(mass, com, inertia)
    return Geometry(pts[:, None], origin[:, None], axis[:, None]), masses


def _set(
    mech: Mechanism,
    parts: list[str],
    v: np.ndarray,
    shape: tuple[np.ndarray, np.ndarray, np.ndarray],
    masses: tuple[np.ndarray, np.ndarray, np.ndarray],
) -> None:
    """Write the values ``v`` (V,) of the parameter at ``parts`` into the variants' arrays: ``shape``, the points,
    the guides' origins and axes; ``masses``, the masses, the inertias given and each link's inertia rule."""
    pts, origin, axis = shape
    mass, given, inertia_rule = masses
    if parts[0] == "links" and parts[2] in ("length", "mass", "inertia"):
        link = mech.link_names.index(parts[1])
        if parts[2] == "length":
            pts[:, mech.link_ends[link][1], 0] = v
        elif parts[2] == "mass":
            mass[:, link] = v
        else:
            given[:, link] = v
            if inertia_rule[link] < 0:  # the file gives none, or gives it about the centre of mass
                inertia_rule[link] = INERTIA_GIVEN
    elif parts[-3] == "points":
        lname = "frame" if parts[0] == "frame" else parts[1]
        p = mech.point_names.index(f"{lname}.{parts[-2]}")
        pts[:, p, 0 if parts[-1] == "x" else 1] = v
    else:
        guides = [k for k, j in enumerate(mech.pair_joint) if j == parts[1] and mech.pair_type[k] == PairType.PRISMATIC]
        for k in guides:
            if parts[2] == "axis":
                axis[:, k] = np.stack([np.cos(v), np.sin(v)], axis=-1)
            else:
                origin[:, k, 0 if parts[-1] == "x" else 1] = v


def mass_properties(
    mech: Mechanism,
    point_local: np.ndarray,
    mass: np.ndarray,
    given: np.ndarray,
    inertia_rule: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Centres of mass ``(V, N, 2)`` and moments of inertia about them ``(V, N)`` by the mass rule.

    Parameters
    ----------
    mech : Mechanism
        For its rules (``link_com_rule``, ``link_inertia_rule``), the file's given centres of
        mass (``link_com`` where the rule is :data:`COM_GIVEN`) and the links' points and ends.
    point_local : ndarray (V, P, 2)
        The variants' points.
    mass : ndarray (V, N)
    given : ndarray (V, N)
        The moments of inertia the file gives (about the centre of mass or about the rule's point).
    inertia_rule : ndarray (N,), optional
        Instead of the mechanism's.

    A moment of inertia given about a point that comes out below zero about the centre of mass
    (the point too far from it for the mass) is NaN.
    """
    rule = np.asarray(mech.link_inertia_rule if inertia_rule is None else inertia_rule)
    com = _centres(mech, point_local)
    inertia = np.where(rule == INERTIA_GIVEN, given, 0.0)
    ends = np.asarray(mech.link_ends)
    rods = np.flatnonzero(rule == INERTIA_ROD)
    if len(rods):
        span = point_local[:, ends[rods, 1]] - point_local[:, ends[rods, 0]]
        inertia[:, rods] = mass[:, rods] * np.sum(span * span, -1) / 12.0
    about = np.flatnonzero(rule >= 0)
    if len(about):
        d = point_local[:, rule[about]] - com[:, about]
        j = given[:, about] - mass[:, about] * np.sum(d * d, -1)
        scale = np.maximum(np.abs(given[:, about]), 1e-300)
        inertia[:, about] = np.where(j >= -1e-12 * scale, np.maximum(j, 0.0), np.nan)
    return com, inertia


def _centres(mech: Mechanism, point_local: np.ndarray) -> np.ndarray:
    """Centres of mass ``(V, N, 2)`` of the variants by the rule of each link (a default one: the middle
    of the ends of a link given by ``ends``, whatever markers it carries; else the centroid of its points)."""
    n_var, n_links = point_local.shape[0], len(mech.link_names)
    rule = np.asarray(mech.link_com_rule)
    com = np.broadcast_to(np.asarray(mech.link_com, dtype=float), (n_var, n_links, 2)).copy()
    at = np.flatnonzero(rule >= 0)
    com[:, at] = point_local[:, rule[at]]
    centroid = np.flatnonzero(rule == COM_CENTROID)
    if len(centroid):
        owner = np.asarray(mech.point_link)
        member = owner[None, :] == centroid[:, None]  # (C, P)
        count = np.maximum(member.sum(axis=1), 1)
        com[:, centroid] = np.einsum("cp,vpk->vck", member.astype(float), point_local) / count[None, :, None]
        ends = np.asarray(mech.link_ends)[centroid]
        rods = ends[:, 0] >= 0
        com[:, centroid[rods]] = 0.5 * (point_local[:, ends[rods, 0]] + point_local[:, ends[rods, 1]])
    return com


# --- an edited description: the values checked here, the file edited by linkwork.spec.edit -------------------


def edited_spec(mechanism: Mechanism, overrides: dict[str, float]) -> Spec:
    """The description of the compiled ``mechanism`` with ``overrides`` (path -> SI) written in, validated again:
    what a user gets who edits the file by hand (:func:`linkwork.spec.edit.with_values`).

    Raises
    ------
    ParameterError
        An unknown name (with the closest known one), or a value out of its range.
    SpecError
        The edited description fails validation (the file's message, with its line).
    """
    spec, kinds = _described(mechanism, overrides)
    return edit.with_values(spec, overrides, kinds)


def file_text(mechanism: Mechanism, values: dict[str, float]) -> str:
    """The text of the file of the compiled ``mechanism`` with ``values`` (path -> SI) written in, its comments and
    layout kept, each value in the unit the file writes it in (:func:`linkwork.spec.edit.text_with_values`).

    Raises
    ------
    ParameterError
        An unknown name, a value out of its range, or a mechanism without its description.
    """
    spec, kinds = _described(mechanism, values)
    return edit.text_with_values(spec, values, kinds)


def _described(mech: Mechanism, values: dict[str, float]) -> tuple[Spec, dict[str, str]]:
    """(spec, kinds of the paths of ``values``), each value checked against its parameter."""
    spec = described(mech.description)
    if spec is None:
        raise ParameterError(edit.NO_FILE)
    known = parameters_by_name(mech)
    for path, value in values.items():
        wrong = parameter(mech, path).check(float(value))
        if wrong is not None:
            raise ParameterError(wrong)
    return spec, {path: known[path].kind for path in values}
