"""Dimensions of design variants: many dimension sets for one compiled mechanism.

A variant overrides named dimensions of the file, by their path in the YAML:
``links.crank.length``, ``links.rocker.points.B.x``, ``frame.points.O1.y``,
``joints.guide_E.axis`` (radians), ``joints.guide_E.through.x``; values in SI.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork.errors import LinkworkError


class ParameterError(LinkworkError, ValueError):
    """A design-variant override names no dimension of the mechanism, or has the wrong shape."""


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


def parameters(mech: Any) -> dict[str, float]:
    """The named dimensions a variant may override, with their values (SI)."""
    out: dict[str, float] = {}
    for p, (name, link) in enumerate(zip(mech.point_names, mech.point_link, strict=True)):
        lname, pname = name.split(".", 1)
        if mech.link_virtual[link]:
            continue
        base = f"frame.points.{pname}" if link == 0 else f"links.{lname}.points.{pname}"
        if link != 0 and mech.link_ends[link][1] == p:
            out[f"links.{lname}.length"] = float(mech.point_local[p, 0])
            continue
        if link != 0 and mech.link_ends[link][0] == p:
            continue
        out[f"{base}.x"] = float(mech.point_local[p, 0])
        out[f"{base}.y"] = float(mech.point_local[p, 1])
    for k, joint in enumerate(mech.pair_joint):
        if mech.pair_type[k] == 1 and f"joints.{joint}.axis" not in out:
            out[f"joints.{joint}.axis"] = float(np.arctan2(mech.pair_axis[k, 1], mech.pair_axis[k, 0]))
            if mech.pair_origin_point[k] < 0:
                out[f"joints.{joint}.through.x"] = float(mech.pair_origin[k, 0])
                out[f"joints.{joint}.through.y"] = float(mech.pair_origin[k, 1])
    return out


def geometry(mech: Any, variants: dict[str, Any] | None = None) -> Geometry:
    """Geometry arrays for the given overrides (one variant when there are none).

    Raises
    ------
    ParameterError
        For an unknown path (with the closest known one) or arrays of unequal length.
    """
    variants = variants or {}
    known = parameters(mech) if variants else {}
    sizes = {np.size(v) for v in variants.values()} - {1}
    if len(sizes) > 1:
        raise ParameterError(f"design-variant arrays must have one length, got lengths {sorted(sizes)}")
    n = sizes.pop() if sizes else 1
    pts = np.repeat(np.asarray(mech.point_local, dtype=float)[None], n, axis=0)
    origin = np.repeat(np.asarray(mech.pair_origin, dtype=float)[None], n, axis=0)
    axis = np.repeat(np.asarray(mech.pair_axis, dtype=float)[None], n, axis=0)
    for path, value in variants.items():
        if path not in known:
            from linkwork.spec.checks import suggest

            raise ParameterError(f'no dimension "{path}"{suggest(path, known)}; linkwork.parameters(mech) lists them')
        v = np.broadcast_to(np.asarray(value, dtype=float).ravel(), (n,))
        parts = path.split(".")
        if parts[0] == "links" and parts[2] == "length":
            link = mech.link_names.index(parts[1])
            pts[:, mech.link_ends[link][1], 0] = v
        elif parts[0] in ("links", "frame") and parts[-3] == "points":
            lname = "frame" if parts[0] == "frame" else parts[1]
            p = mech.point_names.index(f"{lname}.{parts[-2]}")
            pts[:, p, 0 if parts[-1] == "x" else 1] = v
        else:
            ks = [k for k, j in enumerate(mech.pair_joint) if j == parts[1] and mech.pair_type[k] == 1]
            for k in ks:
                if parts[2] == "axis":
                    axis[:, k] = np.stack([np.cos(v), np.sin(v)], axis=-1)
                else:
                    origin[:, k, 0 if parts[-1] == "x" else 1] = v
    follow = np.flatnonzero(mech.pair_origin_point >= 0)
    origin[:, follow] = pts[:, mech.pair_origin_point[follow]]
    return Geometry(pts[:, None], origin[:, None], axis[:, None])
