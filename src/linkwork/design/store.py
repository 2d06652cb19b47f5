"""Sweep results on disk: one Parquet file per chunk, a manifest of the plan and of every stored chunk, the final table.

``OUT.parts/`` (beside the output file ``OUT``) holds ``manifest.json`` and
``chunk-00012.parquet`` files, each written to a temporary name and renamed
into place.  The manifest holds the plan, its hash, and for every stored
chunk its first variant, its row count and the SHA-256 of its file; the
chunk's file carries the plan's hash, its chunk number and range in its own
metadata.  A resumed sweep checks that its plan matches the manifest and
keeps only the chunks that prove themselves (the file there, of the
manifest's checksum, of this plan, of the chunk's range and row count, with
the variants of that range): any other is computed again, with a
:class:`~linkwork.design.plan.DesignWarning`.  The final table is the chunks
concatenated in variant order, checked to hold every variant once before it
is written.  Once it is written, the parts folder is removed (unless asked to
keep it); a folder with a manifest and no chunk file (a sweep stopped before
its first chunk) counts as empty.
"""

from __future__ import annotations

import dataclasses
import enum
import hashlib
import json
import os
import re
import secrets
import stat
import warnings
from pathlib import Path
from typing import Any

import numpy as np

from linkwork.atomic import kind, target_problem, write_atomic
from linkwork.errors import DesignError, DesignWarning
from linkwork.limits import digits
from linkwork.optional import require
from linkwork.structure.model import Mechanism

#: Version of the manifest's layout.
FORMAT = 2

_CHUNK = re.compile(r"^chunk-(\d{5,})\.parquet$")
_MANIFEST = "manifest.json"


#: The fields of a compiled mechanism its results do not depend on: where its file lies (a file moved or
#: copied resumes its sweep) and the description it was compiled from (every value of it that a computation
#: reads is in the other fields).
UNHASHED = ("source", "spec")


def mechanism_hash(mech: Mechanism) -> str:
    """SHA-256 of everything a compiled mechanism computes with: every field but :data:`UNHASHED`, each
    array by its dtype, shape and bytes, each nested record (loads, the program, the drive, the blow) field
    by field, so that no field a result depends on (the mass rule, a load's table) can be left out."""
    h = hashlib.sha256()
    for f in dataclasses.fields(mech):
        if f.name not in UNHASHED:
            h.update(f.name.encode() + b"=")
            _feed(h, getattr(mech, f.name))
    return h.hexdigest()


def _feed(h: Any, value: Any) -> None:
    """Add ``value`` to the hash ``h``, its type and content written so that two values differ in the hash
    where they differ in any entry (arrays, dataclasses, validated models, mappings, sequences, numbers, text,
    enums)."""
    if isinstance(value, np.ndarray | np.generic):
        a = np.asarray(value)
        h.update(f"array:{a.dtype.str}:{a.shape}:".encode())
        h.update(np.ascontiguousarray(a).tobytes() if a.dtype != object else repr(a.tolist()).encode())
    elif dataclasses.is_dataclass(value) and not isinstance(value, type):
        h.update(f"{type(value).__qualname__}(".encode())
        for f in dataclasses.fields(value):
            h.update(f.name.encode() + b"=")
            _feed(h, getattr(value, f.name))
        h.update(b")")
    elif hasattr(value, "model_dump"):  # a validated section of the file (the blow, its tool)
        h.update(f"{type(value).__qualname__}:".encode())
        _feed(h, value.model_dump())
    elif isinstance(value, dict):
        h.update(f"dict:{len(value)}:".encode())
        for key in sorted(value, key=repr):
            _feed(h, key)
            _feed(h, value[key])
    elif isinstance(value, list | tuple | set | frozenset):
        items = sorted(value, key=repr) if isinstance(value, set | frozenset) else value
        h.update(f"{type(value).__name__}:{len(items)}:".encode())
        for item in items:
            _feed(h, item)
    elif isinstance(value, enum.Enum):
        h.update(f"{type(value).__qualname__}.{value.name};".encode())
    elif value is None or isinstance(value, bool | int | float | complex | str | bytes):
        h.update(f"{type(value).__name__}:{value.hex() if isinstance(value, float) else value!r};".encode())
    else:
        raise TypeError(f"cannot hash a {type(value).__qualname__} of a compiled mechanism")


def parts_dir(out: str | Path) -> Path:
    """The directory of the chunk files of an output file: ``OUT.parts``."""
    out = Path(out)
    return out.with_name(out.name + ".parts")


def chunk_path(parts: Path, chunk: int) -> Path:
    return parts / f"chunk-{chunk:05d}.parquet"


def chunk_files(parts: Path) -> set[int]:
    """Chunks that have a file in ``parts`` (proven or not)."""
    if not parts.is_dir():
        return set()
    return {int(m.group(1)) for p in parts.iterdir() if (m := _CHUNK.match(p.name))}


def plan_hash(meta: dict[str, Any]) -> str:
    """SHA-256 of a sweep's plan (its ``meta``), which every chunk file of the sweep carries."""
    return hashlib.sha256(json.dumps(meta, sort_keys=True, separators=(",", ":")).encode()).hexdigest()


def chunk_range(meta: dict[str, Any], chunk: int) -> tuple[int, int]:
    """The variants ``(first, stop)`` of chunk ``chunk`` of the plan ``meta``."""
    size, n = int(meta["chunk_size"]), int(meta["plan"]["n_variants"])
    return chunk * size, min((chunk + 1) * size, n)


def _columns(meta: dict[str, Any]) -> list[str]:
    """The columns of the plan's table, in order: ``variant``, the varied paths, the metrics."""
    return list(dict.fromkeys(["variant", *(v["path"] for v in meta["plan"]["varies"]), *meta["metrics"]]))


def _differences(old: dict[str, Any], new: dict[str, Any]) -> list[str]:
    out = []
    for key in sorted(set(old) | set(new)):
        if old.get(key) != new.get(key):
            out.append(f"{key}: on disk {json.dumps(old.get(key))}, now {json.dumps(new.get(key))}")
    return out


def _read_manifest(parts: Path) -> dict[str, Any]:
    """The manifest in ``parts``, of this version's layout.

    Raises
    ------
    DesignError
        It cannot be read, is not a manifest, or is of another layout.
    """
    path = parts / _MANIFEST
    again = f"remove {parts} and start afresh"
    try:
        data = json.loads(_read_regular(path).decode("utf-8"))
    except (OSError, ValueError) as exc:
        raise DesignError([f"{path}: cannot read the manifest ({exc}); {again}"]) from None
    if not isinstance(data, dict) or not isinstance(data.get("chunks"), dict):
        if isinstance(data, dict) and data.get("format") not in (None, FORMAT):
            raise DesignError(
                [
                    f"{path}: a manifest of format {data.get('format')!r}, whose chunks this version cannot check "
                    f"(format {FORMAT}); {again}"
                ]
            )
        raise DesignError([f"{path}: not a manifest of linkwork's sweeps; {again}"])
    return data


def _write_manifest(parts: Path, manifest: dict[str, Any]) -> None:
    text = json.dumps(manifest, indent=1) + "\n"
    write_atomic(parts / _MANIFEST, lambda tmp: tmp.write_text(text, encoding="utf-8"))


def prepare(out: str | Path, meta: dict[str, Any], resume: bool) -> set[int]:
    """Make the parts directory of ``out`` ready; returns the chunks already done that prove themselves
    (resume only; see :func:`read_part`), each other one named in a :class:`DesignWarning`.

    Raises
    ------
    DesignError
        Results are there and ``resume`` is not set; or the manifest on disk is of another plan, or
        cannot be read.
    """
    parts = parts_dir(out)
    path = parts / _MANIFEST
    if path.exists() and not chunk_files(parts):  # a sweep that stopped before its first chunk: nothing to keep
        path.unlink()
    plan = {**meta, "plan_sha256": plan_hash(meta)}
    manifest = {**plan, "chunks": {}}
    if path.exists():
        if not resume:
            raise DesignError(
                [f"{parts} holds the chunks of a sweep already: add --resume to finish it, or choose another --out"]
            )
        old = _read_manifest(parts)
        diff = _differences({k: v for k, v in old.items() if k != "chunks"}, plan)
        if diff:
            raise DesignError(
                [
                    f"{path}: --resume with another plan than the one on disk; start afresh with another --out, "
                    "or give the same options:",
                    *(f"  {d}" for d in diff),
                ]
            )
        for tmp in parts.glob(".*.part"):  # a chunk or the manifest being written when the sweep was killed
            tmp.unlink(missing_ok=True)
        for key, entry in old["chunks"].items():
            chunk = int(key) if isinstance(key, str) and digits(key) else -1
            why = read_part(parts, manifest, chunk, entry)[1]
            if why is None:
                manifest["chunks"][str(chunk)] = entry
            elif 0 <= chunk < int(meta["n_chunks"]):
                lo, hi = chunk_range(meta, chunk)
                _discard_odd(chunk_path(parts, chunk))
                warnings.warn(
                    f"{chunk_path(parts, chunk)}: {why}; computing chunk {chunk} (variants {lo} to {hi - 1}) again",
                    DesignWarning,
                    stacklevel=3,
                )
        _write_manifest(parts, manifest)
        return {int(c) for c in manifest["chunks"]}
    if resume and parts.is_dir() and chunk_files(parts):
        raise DesignError([f"{parts}: chunks without a manifest; remove the directory and start afresh"])
    parts.mkdir(parents=True, exist_ok=True)
    _write_manifest(parts, manifest)
    return set()


def cannot_write(out: str | Path) -> str | None:
    """Why ``out`` (and ``OUT.parts`` beside it) cannot be written, or None: a file is created and removed
    in its folder, so that a sweep or an optimisation does not find out only at its end."""
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
    pa = require("pyarrow", purpose="a sweep's table (pyarrow)")

    fields, arrays = [], []
    for name, values in columns.items():
        arr = pa.array(values)
        fields.append(pa.field(name, arr.type, metadata={"unit": units.get(name, "")}))
        arrays.append(arr)
    schema = pa.schema(fields, metadata={"linkwork": json.dumps(meta)} if meta else None)
    return pa.Table.from_arrays(arrays, schema=schema)


def write_chunk(parts: Path, chunk: int, columns: dict[str, np.ndarray], units: dict[str, str]) -> Path:
    """Write one chunk's rows atomically, with the plan's hash, the chunk and its range in the file's
    metadata, and record it in the manifest with its row count and checksum.

    The record is written before the file is renamed into place, so a sweep stopped in between finds a
    record of a missing file (computed again), never a file without its record."""
    pa = require("pyarrow", purpose="a sweep's chunk files (Parquet)")
    pq = require("pyarrow.parquet", purpose="a sweep's chunk files (Parquet)")

    manifest = _read_manifest(parts)
    first, rows = int(columns["variant"][0]), len(columns["variant"])
    own = {"plan_sha256": manifest["plan_sha256"], "chunk": chunk, "first": first, "rows": rows}
    sink = pa.BufferOutputStream()
    pq.write_table(to_arrow(columns, units, own), sink)
    data = sink.getvalue().to_pybytes()
    manifest["chunks"][str(chunk)] = {"first": first, "rows": rows, "sha256": hashlib.sha256(data).hexdigest()}

    def write(tmp: Path) -> None:  # the record goes in before the file: a file in place is always recorded
        tmp.write_bytes(data)
        _write_manifest(parts, manifest)

    return write_atomic(chunk_path(parts, chunk), write)


def read_part(parts: Path, manifest: dict[str, Any], chunk: int, entry: Any) -> tuple[Any, str | None]:
    """Chunk ``chunk``'s file as a pyarrow Table, where it proves that it holds the chunk's rows of the
    manifest's plan, intact: ``(table, None)``; else ``(None, why)``.

    The proof: the file's bytes have the checksum the manifest's record ``entry`` gives; its metadata
    names the plan's hash, the chunk's number, first variant and row count; it holds the plan's columns
    and the variants of the chunk's range, in order."""
    pa = require("pyarrow", purpose="a sweep's chunk files (Parquet)")
    pq = require("pyarrow.parquet", purpose="a sweep's chunk files (Parquet)")

    if not 0 <= chunk < int(manifest["n_chunks"]):
        return None, f"chunk {chunk} is not one of the plan's {manifest['n_chunks']}"
    first, stop = chunk_range(manifest, chunk)
    if entry is None:
        return None, "not recorded in the manifest"
    if not isinstance(entry, dict) or entry.get("first") != first or entry.get("rows") != stop - first:
        return None, f"the manifest's record of it is not of variants {first} to {stop - 1}"
    try:
        data = _read_regular(chunk_path(parts, chunk))
    except FileNotFoundError:
        return None, "missing"
    except OSError as exc:
        return None, f"cannot be read ({exc.strerror or exc})"
    if hashlib.sha256(data).hexdigest() != entry.get("sha256"):
        return None, "its checksum is not the one the manifest recorded (damaged or replaced)"
    try:
        table = pq.read_table(pa.BufferReader(data), use_threads=False)
        own = json.loads((table.schema.metadata or {}).get(b"linkwork", b"null"))
    except (pa.ArrowException, OSError, ValueError) as exc:
        return None, f"not a readable Parquet file ({exc})"
    expected = {"plan_sha256": manifest["plan_sha256"], "chunk": chunk, "first": first, "rows": stop - first}
    if own != expected:
        return None, f"its own record {json.dumps(own)} is not {json.dumps(expected)}"
    if table.column_names != _columns(manifest) or table.num_rows != stop - first:
        return None, f"its columns or rows are not the plan's ({table.column_names}, {table.num_rows} rows)"
    if not np.array_equal(table.column("variant").to_numpy(), np.arange(first, stop)):
        return None, f"its variants are not {first} to {stop - 1}"
    return table, None


def _discard_odd(path: Path) -> None:
    """Remove ``path`` where it is no regular file of its own (a link, a named pipe, an empty folder): its chunk is
    written anew in its place, not through it.  DesignError where it cannot be (a folder that holds files)."""
    try:
        mode = os.lstat(path).st_mode
    except FileNotFoundError:
        return
    if stat.S_ISREG(mode):
        return
    try:
        if stat.S_ISDIR(mode):
            path.rmdir()
        else:
            path.unlink()
    except OSError as exc:
        raise DesignError(
            [f"{path}: {kind(mode)} in place of a chunk file, which cannot be removed ({exc.strerror})"]
        ) from None


def _read_regular(path: Path) -> bytes:
    """The bytes of the regular file ``path``; OSError for anything else (a named pipe, which would wait for a
    writer, a device such as ``/dev/zero``, which never ends, a folder), found without reading it."""
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0))
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            raise OSError(0, "not a regular file")
        with os.fdopen(fd, "rb", closefd=False) as f:
            return f.read()
    finally:
        os.close(fd)


def check_table(columns: dict[str, np.ndarray], meta: dict[str, Any]) -> None:
    """Check a sweep's table before it is written: the plan's columns, every variant ``0..n-1`` exactly once
    and in order.

    Raises
    ------
    DesignError
        What is wrong.
    """
    n = int(meta["plan"]["n_variants"])
    problems = []
    if list(columns) != _columns(meta):
        problems.append(f"the table's columns {list(columns)} are not the plan's {_columns(meta)}")
    bad = [name for name, values in columns.items() if len(values) != n]
    if bad:
        problems.append(f"the table's columns {', '.join(bad)} do not have the plan's {n} rows")
    ids = np.asarray(columns.get("variant", np.arange(n)))
    if not bad and not np.array_equal(ids, np.arange(n)):
        missing = np.setdiff1d(np.arange(n), ids).size
        twice = ids.size - np.unique(ids).size
        problems.append(f"the table does not hold every variant once in order ({missing} missing, {twice} repeated)")
    if problems:
        raise DesignError(problems)


def read_chunks(parts: Path) -> dict[str, np.ndarray]:
    """All the chunks of the manifest in ``parts``, each proven (:func:`read_part`), concatenated in
    variant order and checked (:func:`check_table`).

    Raises
    ------
    DesignError
        A chunk is not recorded or does not prove itself (changed since it was written), or the table
        fails its check.
    """
    manifest = _read_manifest(parts)
    tables, problems = [], []
    for chunk in range(int(manifest["n_chunks"])):
        table, why = read_part(parts, manifest, chunk, manifest["chunks"].get(str(chunk)))
        if why is not None:
            problems.append(f"{chunk_path(parts, chunk)}: {why}")
        tables.append(table)
    if problems:
        raise DesignError([*problems, f"run again with --resume to compute {'it' if len(problems) == 1 else 'them'}"])
    names = tables[0].column_names if tables else _columns(manifest)
    columns = {name: np.concatenate([t.column(name).to_numpy() for t in tables]) for name in names}
    check_table(columns, manifest)
    return columns


def write_table(out: str | Path, columns: dict[str, np.ndarray], units: dict[str, str], meta: dict[str, Any]) -> Path:
    """The final table, atomically: Parquet (``.parquet``) or NetCDF (``.nc``, needs xarray), a row per variant."""
    out = Path(out)
    if out.suffix == ".nc":
        xr = require("xarray", purpose="a sweep's table as NetCDF (.nc)")

        data = {
            name: ("variant", values, {"units": units.get(name, "")})
            for name, values in columns.items()
            if name != "variant"
        }
        ds = xr.Dataset(data, coords={"variant": columns["variant"]}, attrs={"linkwork": json.dumps(meta)})
        return write_atomic(out, lambda tmp: ds.to_netcdf(tmp))
    pq = require("pyarrow.parquet", purpose="a sweep's table as Parquet (.parquet)")
    table = to_arrow(columns, units, meta)
    return write_atomic(out, lambda tmp: pq.write_table(table, tmp))
