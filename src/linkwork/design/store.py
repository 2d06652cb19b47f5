"""Sweep results on disk: one Parquet file per chunk, a manifest of the plan, the final table.

``OUT.parts/`` (beside the output file ``OUT``) holds ``manifest.json`` and
``chunk-00012.parquet`` files, each written to a temporary name and renamed
into place, so a file that exists is complete.  A resumed sweep checks that
its plan matches the manifest and computes only the chunks that are missing;
the final table is the chunks concatenated in variant order.  Once it is
written, the parts folder is removed (unless asked to keep it); a folder
with a manifest and no chunk (a sweep stopped before its first chunk) counts
as empty.
"""

from __future__ import annotations

import hashlib
import json
import re
from pathlib import Path
from typing import Any

import numpy as np

from linkwork.design.plan import DesignError

#: Version of the manifest's layout.
FORMAT = 1

_CHUNK = re.compile(r"^chunk-(\d{5,})\.parquet$")


def mechanism_hash(mech: Any) -> str:
    """SHA-256 of what a compiled mechanism computes with: its arrays, names, drives and loads."""
    h = hashlib.sha256()
    for name in (
        "link_names", "link_mass", "link_com", "link_inertia", "point_names", "point_link", "point_local",
        "pair_type", "pair_links", "pair_points", "pair_origin", "pair_axis", "pair_joint", "drive_pair",
        "drive_speed", "drive_start", "gravity", "pose0", "link_ends", "pair_origin_point",
    ):  # fmt: skip
        value = getattr(mech, name)
        if isinstance(value, np.ndarray):
            h.update(np.ascontiguousarray(value).tobytes())
            h.update(str(value.dtype).encode())
        else:
            h.update(repr(value).encode())
    for load in mech.loads:
        h.update(repr((load.name, load.kind, load.link, load.points, load.vector, load.value, load.workpiece)).encode())
        if load.table is not None:
            h.update(np.asarray(load.table[0]).tobytes() + np.asarray(load.table[1]).tobytes())
    return h.hexdigest()


def parts_dir(out: str | Path) -> Path:
    """The directory of the chunk files of an output file: ``OUT.parts``."""
    out = Path(out)
    return out.with_name(out.name + ".parts")


def chunk_path(parts: Path, chunk: int) -> Path:
    return parts / f"chunk-{chunk:05d}.parquet"


def done_chunks(parts: Path) -> set[int]:
    """Chunks whose file is on disk."""
    if not parts.is_dir():
        return set()
    return {int(m.group(1)) for p in parts.iterdir() if (m := _CHUNK.match(p.name))}


def _differences(old: dict[str, Any], new: dict[str, Any]) -> list[str]:
    out = []
    for key in sorted(set(old) | set(new)):
        if old.get(key) != new.get(key):
            out.append(f"{key}: on disk {json.dumps(old.get(key))}, now {json.dumps(new.get(key))}")
    return out


def prepare(out: str | Path, manifest: dict[str, Any], resume: bool) -> set[int]:
    """Make the parts directory of ``out`` ready; returns the chunks already done (resume only).

    Raises
    ------
    DesignError
        Results are there and ``resume`` is not set; or the manifest on disk is of another plan.
    """
    from linkwork.io.atomic import write_atomic

    parts = parts_dir(out)
    path = parts / "manifest.json"
    if path.exists() and not done_chunks(parts):  # a sweep that stopped before its first chunk: nothing to keep
        path.unlink()
    if path.exists():
        if not resume:
            raise DesignError(
                [f"{parts} holds the chunks of a sweep already: add --resume to finish it, or choose another --out"]
            )
        try:
            old = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, ValueError) as exc:
            raise DesignError([f"{path}: cannot read the manifest ({exc})"]) from None
        diff = _differences(old, manifest)
        if diff:
            raise DesignError(
                [f"{path}: --resume with another plan than the one on disk; start afresh with another --out, "
                 "or give the same options:", *(f"  {d}" for d in diff)]
            )  # fmt: skip
        for tmp in parts.glob(".chunk-*.part"):  # a chunk being written when the sweep was killed
            tmp.unlink(missing_ok=True)
        return done_chunks(parts)
    if resume and parts.is_dir() and done_chunks(parts):
        raise DesignError([f"{parts}: chunks without a manifest; remove the directory and start afresh"])
    parts.mkdir(parents=True, exist_ok=True)

    def write(tmp: Path) -> None:
        tmp.write_text(json.dumps(manifest, indent=2) + "\n", encoding="utf-8")

    write_atomic(path, write)
    return set()


def cannot_write(out: str | Path) -> str | None:
    """Why ``out`` (and ``OUT.parts`` beside it) cannot be written, or None: a file is created and removed
    in its folder, so that a sweep or an optimisation does not find out only at its end."""
    import os
    import secrets

    from linkwork.io.atomic import target_problem

    why = target_problem(out)
    if why is not None:
        return why
    folder = Path(out).parent
    if not folder.is_dir():
        return f"no folder {folder}"
    probe = folder / f".{Path(out).name}.{secrets.token_hex(6)}.probe"
    try:
        os.close(os.open(probe, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o666))
        probe.unlink()
    except OSError as exc:
        return f"cannot write in {folder} ({exc.strerror or exc})"
    return None


def remove_parts(parts: Path) -> None:
    """Remove the chunk files, the manifest and the folder of a finished sweep."""
    for p in parts.iterdir():
        if p.is_file() and (p.name == "manifest.json" or _CHUNK.match(p.name) or p.name.endswith(".part")):
            p.unlink()
    try:
        parts.rmdir()
    except OSError:  # something else was put there: leave it
        pass


def to_arrow(columns: dict[str, np.ndarray], units: dict[str, str], meta: dict[str, Any] | None = None) -> Any:
    """A pyarrow Table of the columns; each field's unit in its metadata (``unit``)."""
    import pyarrow as pa

    fields, arrays = [], []
    for name, values in columns.items():
        arr = pa.array(values)
        fields.append(pa.field(name, arr.type, metadata={"unit": units.get(name, "")}))
        arrays.append(arr)
    schema = pa.schema(fields, metadata={"linkwork": json.dumps(meta)} if meta else None)
    return pa.Table.from_arrays(arrays, schema=schema)


def write_chunk(parts: Path, chunk: int, columns: dict[str, np.ndarray], units: dict[str, str]) -> Path:
    """Write one chunk's rows atomically."""
    import pyarrow.parquet as pq

    from linkwork.io.atomic import write_atomic

    table = to_arrow(columns, units)
    return write_atomic(chunk_path(parts, chunk), lambda tmp: pq.write_table(table, tmp))


def read_chunks(parts: Path, n_chunks: int) -> dict[str, np.ndarray]:
    """All chunks, concatenated in variant order."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    missing = [c for c in range(n_chunks) if not chunk_path(parts, c).exists()]
    if missing:
        raise DesignError([f"{parts}: {len(missing)} chunk(s) missing, the first chunk-{missing[0]:05d}"])
    table = pa.concat_tables([pq.read_table(chunk_path(parts, c)) for c in range(n_chunks)])
    return {name: table.column(name).to_numpy() for name in table.column_names}


def write_table(out: str | Path, columns: dict[str, np.ndarray], units: dict[str, str], meta: dict[str, Any]) -> Path:
    """The final table, atomically: Parquet (``.parquet``) or NetCDF (``.nc``, needs xarray), a row per variant."""
    from linkwork.io.atomic import write_atomic

    out = Path(out)
    if out.suffix == ".nc":
        import xarray as xr

        data = {
            name: ("variant", values, {"units": units.get(name, "")})
            for name, values in columns.items()
            if name != "variant"
        }
        ds = xr.Dataset(data, coords={"variant": columns["variant"]}, attrs={"linkwork": json.dumps(meta)})
        return write_atomic(out, lambda tmp: ds.to_netcdf(tmp))
    import pyarrow.parquet as pq

    table = to_arrow(columns, units, meta)
    return write_atomic(out, lambda tmp: pq.write_table(table, tmp))
