"""Files written whole: through a symbolic link to the file it names, never into a fifo or a device,
never replacing a link or a special file, and keeping a replaced file's permissions."""

from __future__ import annotations

import os
import stat

import pytest
from typer.testing import CliRunner

import linkwork.cli.view  # noqa: F401 - registers the command
from linkwork.atomic import write_atomic
from linkwork.cli.main import app

runner = CliRunner()


def _export(target) -> object:
    return runner.invoke(app, ["view", "four-bar", "--export", str(target), "--steps", "24"])


def test_view_export_to_a_symbolic_link_writes_the_file_it_names_and_keeps_the_link(tmp_path):
    pages = tmp_path / "pages"
    pages.mkdir()
    page = pages / "shears.html"
    page.write_text("old page")
    os.chmod(page, 0o640)
    link = tmp_path / "latest.html"
    link.symlink_to(os.path.relpath(page, tmp_path))
    result = _export(link)
    assert result.exit_code == 0, result.output
    assert link.is_symlink() and os.readlink(link) == "pages/shears.html"
    assert page.read_text().startswith("<!DOCTYPE html>") and stat.S_IMODE(page.stat().st_mode) == 0o640
    assert sorted(os.listdir(tmp_path)) == ["latest.html", "pages"] and os.listdir(pages) == ["shears.html"]


def _kept(path):
    """What a write must leave as it was: the entry's kind, mode, identity, size and modification (not its
    access time, which reading a link's target may touch)."""
    st = os.lstat(path)
    return (st.st_mode, st.st_ino, st.st_size, st.st_mtime_ns, st.st_ctime_ns)


@pytest.mark.parametrize("kind", ["fifo", "link to a fifo", "dangling link", "directory"])
def test_view_export_to_a_fifo_a_dangling_link_or_a_directory_is_refused_and_left_alone(tmp_path, kind):
    target = tmp_path / "page.html"
    if kind == "fifo":
        os.mkfifo(target)
    elif kind == "link to a fifo":
        os.mkfifo(tmp_path / "pipe")
        target.symlink_to("pipe")
    elif kind == "dangling link":
        target.symlink_to("nowhere.html")
    else:
        target.mkdir()
    before = {p.name: _kept(p) for p in tmp_path.iterdir()}
    result = _export(target)
    assert result.exit_code == 2, result.output
    assert result.output.startswith(f"error: --export {target}: ") and len(result.output.splitlines()) == 1
    assert "Traceback" not in result.output
    assert {p.name: _kept(p) for p in tmp_path.iterdir()} == before


def test_a_replaced_file_keeps_its_permissions(tmp_path):
    out = tmp_path / "table.csv"
    out.write_text("old\n")
    os.chmod(out, 0o600)
    write_atomic(out, lambda p: p.write_text("new\n"))
    assert out.read_text() == "new\n" and stat.S_IMODE(out.stat().st_mode) == 0o600


def test_a_sweep_into_a_fifo_is_refused_before_the_work(tmp_path):
    pytest.importorskip("pyarrow")
    import linkwork as lw
    from linkwork.errors import DesignError

    out = tmp_path / "t.parquet"
    os.mkfifo(out)
    with pytest.raises(DesignError, match="is a fifo, not a regular file"):
        lw.sweep("four-bar", ["links.crank.length=90:110:3"], ["swing"], out=out, steps=36)
    assert stat.S_ISFIFO(os.lstat(out).st_mode) and sorted(os.listdir(tmp_path)) == ["t.parquet"]
