"""A resumed sweep trusts no chunk file on its word: a part that is truncated, garbled, swapped with another,
bit-flipped or forged is computed again, and the final table equals an uninterrupted run's."""

from __future__ import annotations

import json
import os
import shutil
import warnings

import numpy as np
import pytest

import linkwork as lw
from commandline import linkwork
from linkwork.errors import DesignError, DesignWarning

pq = pytest.importorskip("pyarrow.parquet")

VARY = ["links.crank.length=80:110:6", "links.rocker.length=240:260:3"]  # 18 variants
METRICS = ["swing", "time_ratio", "min_transmission_angle"]
OPTIONS = {"chunk_size": 4, "steps": 36}  # chunks of variants 0-3, 4-7, 8-11, 12-15, 16-17


@pytest.fixture(scope="module")
def whole(tmp_path_factory):
    """The table of an uninterrupted sweep, as written."""
    out = tmp_path_factory.mktemp("whole") / "w.parquet"
    lw.sweep("four-bar", VARY, METRICS, out=out, **OPTIONS)
    return pq.read_table(out)


def _parts(tmp_path):
    """A sweep's five chunks on disk and no table: a sweep to be resumed."""
    out = tmp_path / "s.parquet"
    lw.sweep("four-bar", VARY, METRICS, out=out, keep_parts=True, **OPTIONS)
    out.unlink()
    return out, tmp_path / "s.parquet.parts"


def _resume(out, tmp_path):
    """Resume; returns the chunks computed again and the warnings' messages."""
    attempts = tmp_path / "attempts"
    attempts.mkdir(exist_ok=True)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", DesignWarning)
        lw.sweep("four-bar", VARY, METRICS, out=out, resume=True, attempts=attempts, **OPTIONS)
    lines = [line for f in attempts.glob("attempts-*.txt") for line in f.read_text().splitlines()]
    computed = sorted(int(line.split()[0]) for line in lines)
    return computed, [str(w.message) for w in caught if issubclass(w.category, DesignWarning)]


def _flip_a_value_parquet_does_not_notice(path, value):
    """Flip the lowest bit of ``value``'s bytes in the file; the file still reads, with another value."""
    data = bytearray(path.read_bytes())
    at = bytes(data).find(np.float64(value).tobytes())
    assert at > 0, "the value is not stored as plain bytes"
    data[at] ^= 1
    path.write_bytes(bytes(data))
    flipped = pq.read_table(path)  # parquet itself sees nothing wrong
    return flipped


@pytest.mark.parametrize("damage", ["truncate", "garble", "swap", "copy", "flip", "remove", "fifo", "dev-zero"])
def test_a_damaged_or_swapped_part_is_computed_again_and_the_table_equals_an_uninterrupted_run(tmp_path, whole, damage):
    out, parts = _parts(tmp_path)
    one, two = parts / "chunk-00001.parquet", parts / "chunk-00002.parquet"
    if damage == "truncate":
        one.write_bytes(one.read_bytes()[: one.stat().st_size // 2])
    elif damage == "garble":
        one.write_bytes(bytes(range(256)) * 4)
    elif damage == "swap":  # two files of the same size exchanged
        a, b = one.read_bytes(), two.read_bytes()
        one.write_bytes(b)
        two.write_bytes(a)
    elif damage == "copy":  # another chunk's file in its place: variants 8-11 twice, 4-7 missing
        shutil.copy(two, one)
    elif damage == "flip":
        before = pq.read_table(one).column("swing").to_numpy()
        after = _flip_a_value_parquet_does_not_notice(one, before[1]).column("swing").to_numpy()
        assert np.sum(after != before) == 1
    elif damage == "remove":
        one.unlink()
    elif damage == "fifo":  # no program writes to it: reading it would wait for ever
        one.unlink()
        os.mkfifo(one)
    elif damage == "dev-zero":  # reading it would never end
        one.unlink()
        one.symlink_to("/dev/zero")
    computed, said = _resume(out, tmp_path)
    again = [1, 2] if damage == "swap" else [1]
    assert computed == again
    assert len(said) == len(again)
    assert all(f"computing chunk {c} (variants" in m for c, m in zip(again, said, strict=True))
    assert pq.read_table(out).equals(whole, check_metadata=True)


class Killed(BaseException):
    """Stands for a kill: nothing catches it on its way out."""


@pytest.mark.parametrize("before", [True, False], ids=["before", "after"])
def test_a_sweep_stopped_at_any_write_keeps_every_file_it_left_and_resumes_to_the_same_table(
    tmp_path, monkeypatch, whole, before
):
    """Stopped just before or after each rename of a chunk file, the manifest or the table: every chunk file
    left on disk is recorded and kept as it is; only the others are computed on resume."""
    real = os.replace
    for at in range(1, 30):
        here = tmp_path / str(at)
        here.mkdir()
        out, count = here / "s.parquet", [0]

        def replace(src, dst, at=at, count=count):
            count[0] += 1
            if before and count[0] == at:
                raise Killed
            real(src, dst)
            if not before and count[0] == at:
                raise Killed

        monkeypatch.setattr(os, "replace", replace)
        try:
            lw.sweep("four-bar", VARY, METRICS, out=out, **OPTIONS)
            stopped = False
        except Killed:
            stopped = True
        finally:
            monkeypatch.setattr(os, "replace", real)
        if not stopped:
            break
        parts = here / "s.parquet.parts"
        left = {p.name: p.stat().st_ino for p in parts.glob("chunk-*.parquet")}
        if out.exists():
            assert pq.read_table(out).equals(whole, check_metadata=True)
            continue
        if not left:
            continue
        computed, _ = _resume(out, here)
        assert computed == [c for c in range(5) if f"chunk-{c:05d}.parquet" not in left], f"stopped at {at}"
        assert pq.read_table(out).equals(whole, check_metadata=True)
    else:
        pytest.fail("the sweep never finished")
    assert at > 10


def test_a_part_with_a_forged_record_in_the_manifest_is_caught_by_its_own_metadata(tmp_path, whole):
    """Chunk 2's file and its checksum copied to chunk 1's place: the file says which variants it holds."""
    out, parts = _parts(tmp_path)
    shutil.copy(parts / "chunk-00002.parquet", parts / "chunk-00001.parquet")
    manifest = json.loads((parts / "manifest.json").read_text())
    manifest["chunks"]["1"]["sha256"] = manifest["chunks"]["2"]["sha256"]
    (parts / "manifest.json").write_text(json.dumps(manifest))
    computed, said = _resume(out, tmp_path)
    assert computed == [1] and "is not" in said[0] and '"first": 8' in said[0]
    assert pq.read_table(out).equals(whole, check_metadata=True)


def test_a_part_changed_during_the_run_stops_the_table_and_a_resume_mends_it(tmp_path, whole):
    out = tmp_path / "s.parquet"
    parts = tmp_path / "s.parquet.parts"

    def damage_the_first(chunk, done, total):
        if done == total:
            path = parts / "chunk-00000.parquet"
            path.write_bytes(path.read_bytes()[:-10])

    with pytest.raises(DesignError, match=r"chunk-00000.parquet: its checksum .*\n.*--resume"):
        lw.sweep("four-bar", VARY, METRICS, out=out, on_chunk=damage_the_first, **OPTIONS)
    assert not out.exists()
    computed, _ = _resume(out, tmp_path)
    assert computed == [0] and pq.read_table(out).equals(whole, check_metadata=True)


def test_the_table_is_checked_to_hold_every_variant_once_before_it_is_written():
    from linkwork.design.store import check_table

    meta = {"plan": {"n_variants": 4, "varies": [{"path": "links.crank.length"}]}, "metrics": ["swing"]}
    good = {"variant": np.arange(4), "links.crank.length": np.ones(4), "swing": np.ones(4)}
    check_table(good, meta)
    with pytest.raises(DesignError, match=r"1 missing, 1 repeated"):
        check_table({**good, "variant": np.array([0, 1, 1, 3])}, meta)
    with pytest.raises(DesignError, match="do not have the plan's 4 rows"):
        check_table({**good, "swing": np.ones(3)}, meta)
    with pytest.raises(DesignError, match="not the plan's"):
        check_table({"variant": np.arange(4), "swing": np.ones(4)}, meta)


@pytest.mark.parametrize("manifest", ['{"format": 2, "plan"', "[]", "format 1", "fifo", "dev-zero"])
def test_an_unreadable_or_older_manifest_is_refused_with_a_message(tmp_path, manifest):
    out, parts = _parts(tmp_path)
    if manifest == "format 1":
        old = json.loads((parts / "manifest.json").read_text())
        del old["chunks"], old["plan_sha256"]
        manifest = json.dumps({**old, "format": 1})
    (parts / "manifest.json").unlink()
    if manifest == "fifo":
        os.mkfifo(parts / "manifest.json")
    elif manifest == "dev-zero":
        (parts / "manifest.json").symlink_to("/dev/zero")
    else:
        (parts / "manifest.json").write_text(manifest)
    r = linkwork(
        "sweep",
        "four-bar",
        *sum((["--vary", v] for v in VARY), []),
        *sum((["--metric", m] for m in METRICS), []),
        "--chunk-size",
        "4",
        "--steps",
        "36",
        "--out",
        str(out),
        "--resume",
        "--quiet",
    )
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    assert r.stderr.startswith("error: ") and "start afresh" in r.stderr and not out.exists()


def test_the_command_says_which_parts_it_computes_again_one_line_each(tmp_path, whole):
    out, parts = _parts(tmp_path)
    for name in ("chunk-00000.parquet", "chunk-00004.parquet"):
        (parts / name).write_bytes(b"PAR1 damaged PAR1")
    r = linkwork(
        "sweep",
        "four-bar",
        *sum((["--vary", v] for v in VARY), []),
        *sum((["--metric", m] for m in METRICS), []),
        "--chunk-size",
        "4",
        "--steps",
        "36",
        "--out",
        str(out),
        "--resume",
        "--quiet",
    )
    assert r.returncode == 0, r.stderr
    lines = [line for line in r.stderr.splitlines() if line.startswith("warning:")]
    assert len(lines) == 2
    assert "chunk-00000.parquet" in lines[0] and "variants 0 to 3" in lines[0]
    assert "chunk-00004.parquet" in lines[1] and "variants 16 to 17" in lines[1]
    assert pq.read_table(out).equals(whole, check_metadata=True)


def test_a_manifest_record_under_a_name_of_unicode_digits_is_no_chunk(tmp_path, whole):
    """``"²"`` passes ``str.isdigit`` and fails ``int``: such a record is no chunk of the plan, and the resume
    computes the chunk it stands beside again, to the same table."""
    out, parts = _parts(tmp_path)
    manifest = json.loads((parts / "manifest.json").read_text())
    manifest["chunks"]["\u00b2"] = manifest["chunks"].pop("2")
    (parts / "manifest.json").write_text(json.dumps(manifest))
    computed, _ = _resume(out, tmp_path)
    assert computed == [2]
    assert pq.read_table(out).equals(whole, check_metadata=True)


def _changed(value):
    """``value`` with one entry changed (the first that can be), of the same kind; None if none can."""
    import dataclasses
    import enum

    if isinstance(value, np.ndarray):
        if value.size == 0:
            return np.zeros((1, *value.shape[1:]), dtype=value.dtype) if value.dtype != object else None
        out = value.copy()
        flat = out.reshape(-1)
        flat[0] = (not flat[0]) if value.dtype == bool else (flat[0] + 1 if np.isfinite(flat[0]) else 0)
        return out
    if dataclasses.is_dataclass(value):
        for f in dataclasses.fields(value):
            new = _changed(getattr(value, f.name))
            if new is not None:
                return dataclasses.replace(value, **{f.name: new})
        return None
    if hasattr(value, "model_copy"):
        for name in type(value).model_fields:
            new = _changed(getattr(value, name))
            if new is not None:
                return value.model_copy(update={name: new})
        return None
    if isinstance(value, tuple | list):
        for i, item in enumerate(value):
            new = _changed(item)
            if new is not None:
                items = [*value[:i], new, *value[i + 1 :]]
                return value._make(items) if hasattr(value, "_make") else type(value)(items)
        return None
    if isinstance(value, enum.Enum):
        others = [m for m in type(value) if m != value]
        return others[0] if others else None
    if isinstance(value, bool):
        return not value
    if isinstance(value, int | float):
        return value + 1
    if isinstance(value, str):
        return value + "'"
    return None


def test_the_mechanism_hash_covers_every_field_of_the_compiled_model():
    """Each field of a compiled mechanism (but where its file lies and the description it came from), changed
    once in one bundled example that gives it, changes the hash a resumed sweep compares: no result can be
    read back from parts computed with another mass rule, load, drive, program or blow."""
    import dataclasses

    from linkwork.design.store import UNHASHED, mechanism_hash
    from linkwork.examples import names

    mechs = [lw.compile(lw.example(n)) for n in names()]
    rubbing = lw.examples.text("four-bar").replace(  # no bundled example has friction in proportion to the forces
        "links: [coupler, rocker]}", "links: [coupler, rocker], friction: {f: 0.1, radius: 10 mm}}"
    )
    mechs.append(lw.compile(lw.loads(rubbing)))
    untested = []
    for f in dataclasses.fields(mechs[0]):
        if f.name in UNHASHED:
            continue
        for mech in mechs:
            new = _changed(getattr(mech, f.name))
            if new is not None:
                changed = dataclasses.replace(mech, **{f.name: new})
                assert mechanism_hash(changed) != mechanism_hash(mech), f.name
                break
        else:
            untested.append(f.name)
    assert untested == []
    assert mechanism_hash(lw.compile(lw.example("four-bar"))) == mechanism_hash(lw.compile(lw.example("four-bar")))


def test_a_resume_over_another_mass_rule_is_refused(tmp_path):
    """The four-bar with its rocker's default inertia (m L^2 / 12 = 0.009375 kg m^2, following its length)
    written out as that number (held as the length varies): the same numbers at the nominal mechanism, another
    mass rule; a sweep over the rocker's length resumed over the other's parts is refused, and nothing written."""
    text = lw.examples.text("four-bar")
    given = tmp_path / "given.yaml"
    given.write_text(text.replace("    mass: 1.8\n", '    mass: 1.8\n    inertia: "0.009375 kg*m^2"\n'))
    default, held = lw.compile(lw.example("four-bar")), lw.compile(lw.load(given))
    np.testing.assert_array_equal(default.link_inertia, held.link_inertia)
    out = tmp_path / "s.parquet"
    vary = ["links.rocker.length=240:260:3"]
    lw.sweep("four-bar", vary, ["peak_driving_torque"], out=out, keep_parts=True, chunk_size=1, steps=36)
    out.unlink()
    with pytest.raises(DesignError, match="another plan than the one on disk") as caught:
        lw.sweep(held, vary, ["peak_driving_torque"], out=out, resume=True, chunk_size=1, steps=36)
    assert "mechanism_sha256" in str(caught.value) and not out.exists()
