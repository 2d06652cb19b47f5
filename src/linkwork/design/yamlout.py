"""Writing a design back as a mechanism file: the original file with new values, comments kept.

Values are written as the file reads them back (:func:`linkwork.units.written`): bare numbers in the
file's units, or with their unit where a bare number of their kind would need one.  Design variants keep
the file's mass properties (see :mod:`linkwork.design.evaluate`), so a link
whose geometry changed gets its centre of mass and moment of inertia written
out explicitly where the file left them to their defaults (the centroid, a
uniform rod): the file then describes the very mechanism that was evaluated.
A changed mass scales an explicit moment of inertia with it.
"""

from __future__ import annotations

import io
from pathlib import Path
from typing import Any

from linkwork.design.plan import DesignError, kind_of


def _text(mechanism: Any) -> tuple[str, str]:
    """The YAML text of a file or bundled example, and its name for messages."""
    from linkwork.examples import names, text

    path = Path(str(mechanism))
    if path.exists():
        return path.read_text(encoding="utf-8"), str(path)
    if str(mechanism) in names():
        return text(str(mechanism)), f"{mechanism}.yaml"
    raise DesignError([f'"{mechanism}": the optimised design is written from a mechanism file or a bundled example'])


def write_design(mechanism: Any, spec: Any, mech: Any, values: dict[str, float], out: str | Path) -> Path:
    """Write the file of ``mechanism`` with ``values`` (path -> SI) to ``out``, atomically."""
    from ruamel.yaml import YAML
    from ruamel.yaml.comments import CommentedSeq

    from linkwork.io.atomic import write_atomic
    from linkwork.units import DEFAULT_UNITS, parse_quantity, written

    source, _ = _text(mechanism)
    yaml = YAML()  # round trip: comments, order and flow style kept
    yaml.preserve_quotes = True
    yaml.width = 4096  # no folding of long flow mappings
    yaml.indent(mapping=2, sequence=4, offset=2)
    data = yaml.load(source)
    declared = {**DEFAULT_UNITS, **spec.units.model_dump(exclude_none=True)}

    def file_units(si: float, kind: str) -> float | str:
        return written(si, kind, declared)

    changed_links: set[str] = set()
    scaled: dict[str, float] = {}
    for path, si in values.items():
        parts = path.split(".")
        kind = kind_of(path)
        if parts[0] == "links" and parts[2] == "length":
            data["links"][parts[1]]["length"] = file_units(si, kind)
            changed_links.add(parts[1])
        elif parts[0] == "links" and parts[2] == "mass":
            link = data["links"][parts[1]]
            old = mech.link_mass[mech.link_names.index(parts[1])]
            scaled[parts[1]] = si / old
            link["mass"] = file_units(si, "mass")
        elif parts[-3] == "points":
            owner = data["frame"] if parts[0] == "frame" else data["links"][parts[1]]
            point = owner["points"][parts[-2]]
            if not isinstance(point, list):
                raise DesignError([f"{path}: the point is not given as [x, y] in the file"])
            point[0 if parts[-1] == "x" else 1] = file_units(si, kind)
            if parts[0] == "links":
                changed_links.add(parts[1])
        elif parts[0] == "joints" and parts[2] == "axis":
            data["joints"][parts[1]]["axis"] = file_units(si, "angle")
        elif parts[0] == "joints" and parts[2] == "through":
            through = data["joints"][parts[1]]["through"]
            through[0 if parts[-1] == "x" else 1] = file_units(si, kind)
    for name in sorted(changed_links | set(scaled)):
        i = mech.link_names.index(name)
        link = data["links"][name]
        s = scaled.get(name, 1.0)
        if name in changed_links and (link.get("com") is None or isinstance(link.get("com"), str)):
            com = CommentedSeq([file_units(float(c), "length") for c in mech.link_com[i]])
            com.fa.set_flow_style()
            link["com"] = com
        if name in changed_links and (link.get("inertia") is None or link.get("inertia_about") is not None):
            link.pop("inertia_about", None)
            link["inertia"] = file_units(float(mech.link_inertia[i]) * s, "inertia")
        elif name in scaled and link.get("inertia") is not None:
            j = parse_quantity(link["inertia"], "inertia", declared)
            link["inertia"] = file_units(j * s, "inertia")
    buf = io.StringIO()
    yaml.dump(data, buf)
    text = buf.getvalue()

    def write(tmp: Path) -> None:
        tmp.write_text(text, encoding="utf-8")

    return write_atomic(out, write)
