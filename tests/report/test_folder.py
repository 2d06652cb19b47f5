"""Where ``linkwork analyze --out`` writes: only a new name, an empty folder or an earlier report is replaced;
a kill at any moment leaves the old or the new report whole, and the next run leaves no stray folder."""

from __future__ import annotations

import json
import os
import signal
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

pytest.importorskip("matplotlib")
fcntl = pytest.importorskip("fcntl")  # POSIX: locks, fork, fifos

import linkwork.cli.analyze  # noqa: E402,F401 - registers the command
from linkwork.cli.main import app  # noqa: E402

runner = CliRunner()
MARKER = ".linkwork-report"

# what the folder holds and how it is replaced is tested here; the figures are drawn and read elsewhere
pytestmark = pytest.mark.usefixtures("sketched_figures")


def _snapshot(root: Path) -> dict[str, tuple]:
    """Everything under ``root`` (links not followed): kind, inode, mode, size, mtime and a file's bytes."""
    out = {}
    for dirpath, dirs, files in os.walk(root):
        for name in dirs + files:
            p = Path(dirpath) / name
            st = os.lstat(p)
            data = p.read_bytes() if stat.S_ISREG(st.st_mode) else os.readlink(p) if p.is_symlink() else None
            out[str(p.relative_to(root))] = (stat.S_IFMT(st.st_mode), st.st_ino, st.st_mode, st.st_mtime_ns, data)
    return out


def _fake_report(folder: Path, version: str, extra: dict[str, str] | None = None) -> None:
    """A report folder as linkwork marks one, written by hand: its marker lists the files it holds."""
    files = {"report.html": version, "figures/a.svg": version, **(extra or {})}
    for name, text in files.items():
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text(text)
    listed = sorted({*files, "figures"})
    (folder / MARKER).write_text(json.dumps({"linkwork_report": 1, "complete": True, "files": listed}))


def _setup_target(tmp_path: Path, case: str) -> Path:
    report = tmp_path / "old-report"
    report.mkdir()
    _fake_report(report, "old")
    (tmp_path / "notes.txt").write_text("my notes")
    out = tmp_path / "target"
    if case == "folder of other files":
        out.mkdir()
        (out / "thesis.txt").write_text("three years of work")
    elif case == "report with a file of the user's":
        out.mkdir()
        _fake_report(out, "old")
        (out / "figures" / "my-sketch.svg").write_text("<svg/>")
    elif case == "folder with a marker of another program":
        out.mkdir()
        (out / MARKER).write_text("not ours")
        (out / "data.bin").write_bytes(b"\0\1")
    elif case == "file":
        out.write_text("a file")
    elif case == "symbolic link to a report":
        out.symlink_to(report)
    elif case == "symbolic link to a file":
        out.symlink_to(tmp_path / "notes.txt")
    elif case == "dangling symbolic link":
        out.symlink_to(tmp_path / "nowhere")
    elif case == "fifo":
        os.mkfifo(out)
    elif case == "inside a file":
        out = tmp_path / "notes.txt" / "target"
    return out


CASES = [
    "folder of other files",
    "report with a file of the user's",
    "folder with a marker of another program",
    "file",
    "symbolic link to a report",
    "symbolic link to a file",
    "dangling symbolic link",
    "fifo",
    "inside a file",
]


@pytest.mark.parametrize("case", CASES)
def test_an_out_that_is_not_a_report_is_refused_before_any_work_and_left_as_it_was(tmp_path, case):
    out = _setup_target(tmp_path, case)
    before = _snapshot(tmp_path)
    r = runner.invoke(app, ["analyze", "four-bar", "--out", str(out), "--steps", "36", "--no-animation"])
    assert r.exit_code == 2, r.output
    assert r.stderr.startswith(f"error: --out {out}: ") and r.stderr.count("\n") == 1, r.stderr
    assert "Traceback" not in r.output
    assert _snapshot(tmp_path) == before


def test_the_library_refuses_a_folder_of_other_files_too(tmp_path):
    import linkwork as lw
    from linkwork import report
    from linkwork.errors import LinkworkError

    out = _setup_target(tmp_path, "folder of other files")
    before = _snapshot(tmp_path)
    with pytest.raises(LinkworkError, match="linkwork did not write"):
        report.analyze(lw.compile(lw.example("four-bar")), out, steps=36, animation=False)
    assert _snapshot(tmp_path) == before


def test_the_current_folder_is_refused_even_when_empty(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    for out in (".", str(tmp_path), ".."):
        r = runner.invoke(app, ["analyze", "four-bar", "--out", out, "--steps", "36", "--no-animation"])
        assert r.exit_code == 2 and "current folder" in r.stderr, r.output
    assert list(tmp_path.iterdir()) == []


def test_a_report_folder_and_its_files_get_the_modes_of_the_umask_and_a_marker_listing_them(tmp_path):
    import linkwork as lw
    from linkwork import report

    mech = lw.compile(lw.example("four-bar"))
    old = os.umask(0o027)
    try:
        path = report.analyze(mech, tmp_path / "new" / "sub", steps=36, animation=False)
    finally:
        os.umask(old)
    folder = path.parent
    assert stat.S_IMODE(folder.stat().st_mode) == 0o750
    assert stat.S_IMODE(path.stat().st_mode) == 0o640
    assert stat.S_IMODE((folder / "figures").stat().st_mode) == 0o750
    listed = json.loads((folder / MARKER).read_text())["files"]
    held = {str(p.relative_to(folder)) for p in folder.rglob("*")} - {MARKER}
    assert set(listed) == held and "report.html" in held and "figures/scheme.svg" in held
    assert [p.name for p in tmp_path.iterdir()] == ["new"] and [p.name for p in folder.parent.iterdir()] == ["sub"]


# ---------------------------------------------------------------- kills and the next run


def _run_killed(out: Path, at: int, exchange: bool) -> bool:
    """Replace ``out`` by a report "new" in a forked child killed by SIGKILL just before (odd ``at``) or just
    after (even ``at``) step ``(at + 1) // 2`` of the swap; False where the run had fewer steps and finished."""
    pid = os.fork()
    if pid == 0:  # the child: never returns into the test
        try:
            from linkwork.report import folder

            count = [0]

            def step(fn):
                def wrapped(*args, **kwargs):
                    count[0] += 1
                    if count[0] == at:
                        os.kill(os.getpid(), signal.SIGKILL)
                    result = fn(*args, **kwargs)
                    count[0] += 1
                    if count[0] == at:
                        os.kill(os.getpid(), signal.SIGKILL)
                    return result

                return wrapped

            if not exchange:
                folder._exchange = lambda a, b: False
            for name in ("_mark", "_rename", "_remove", "_exchange"):
                setattr(folder, name, step(getattr(folder, name)))
            with folder.replacing(out) as work:
                _fake_report_body(work, "new")
            os._exit(0)
        except BaseException:
            os._exit(1)
    _, status = os.waitpid(pid, 0)
    if os.WIFEXITED(status):
        assert os.WEXITSTATUS(status) == 0
        return False
    assert os.WTERMSIG(status) == signal.SIGKILL
    return True


def _fake_report_body(work: Path, version: str) -> None:
    (work / "report.html").write_text(version)
    (work / "figures").mkdir()
    (work / "figures" / "a.svg").write_text(version)


def _complete_report(out: Path) -> str:
    """The version of the complete report at ``out``: its marker lists exactly what it holds."""
    marker = json.loads((out / MARKER).read_text())
    assert marker["complete"]
    held = {str(p.relative_to(out)) for p in out.rglob("*")} - {MARKER}
    assert set(marker["files"]) == held
    version = (out / "report.html").read_text()
    assert (out / "figures" / "a.svg").read_text() == version
    return version


@pytest.mark.parametrize("exchange", [True, False], ids=["exchange", "two renames"])
@pytest.mark.parametrize("start", ["report", "missing", "empty"])
def test_a_kill_at_any_step_leaves_the_old_or_the_new_report_and_the_next_run_no_stray_folder(
    tmp_path, exchange, start
):
    from linkwork.report import folder

    if exchange and not folder._exchange(*_pair(tmp_path)):
        pytest.skip("this file system cannot exchange two folders")
    tmp_path = tmp_path / "w"
    tmp_path.mkdir()
    out = tmp_path / "r"
    seen = set()
    for at in range(1, 40):
        if out.exists():
            folder._remove(out)
        if start == "report":
            out.mkdir()
            _fake_report(out, "old")
        elif start == "empty":
            out.mkdir()
        if not _run_killed(out, at, exchange):
            assert _complete_report(out) == "new" and sorted(os.listdir(tmp_path)) == ["r"]
            break
        if not exchange and not out.exists():  # killed between the two renames: the next run puts one back
            folder._recover(out)
        if out.exists() and (start == "report" or os.listdir(out)):
            seen.add(_complete_report(out))
        else:
            assert start != "report", f"killed at {at}: no report"
            seen.add(None)
        with folder.replacing(out) as work:
            _fake_report_body(work, "next")
        assert _complete_report(out) == "next"
        assert sorted(os.listdir(tmp_path)) == ["r"], f"killed at {at}"
    else:
        pytest.fail("the run never finished")
    assert at > 6  # the kills covered every step
    assert seen == ({"old", "new"} if start == "report" else {None, "new"})


def _pair(tmp_path: Path) -> tuple[Path, Path]:
    a, b = tmp_path / "probe-a", tmp_path / "probe-b"
    a.mkdir()
    b.mkdir()
    return a, b


def test_a_failure_between_the_two_renames_puts_the_old_report_back(tmp_path, monkeypatch):
    from linkwork.report import folder

    out = tmp_path / "r"
    out.mkdir()
    _fake_report(out, "old")
    monkeypatch.setattr(folder, "_exchange", lambda a, b: False)
    real = folder._rename

    def rename(src, dst):
        if dst == out and src.suffix == ".part":
            raise OSError(28, "No space left on device")
        real(src, dst)

    monkeypatch.setattr(folder, "_rename", rename)
    with pytest.raises(OSError, match="No space"):
        with folder.replacing(out) as work:
            _fake_report_body(work, "new")
    assert _complete_report(out) == "old" and sorted(os.listdir(tmp_path)) == ["r"]


def test_the_next_run_leaves_folders_in_use_and_folders_not_its_own(tmp_path):
    from linkwork.report import folder

    out = tmp_path / "r"
    live = tmp_path / ".r.0123456789ab.part"  # another run, still building
    live.mkdir()
    _fake_report(live, "live")
    lock = os.open(live, os.O_RDONLY)
    fcntl.flock(lock, fcntl.LOCK_EX)
    stranger = tmp_path / ".r.ba9876543210.old"  # named like ours, but holds no marker
    stranger.mkdir()
    (stranger / "keep.txt").write_text("not linkwork's")
    half = tmp_path / ".r.00000000abcd.part"  # a removal cut short: the marker goes last
    half.mkdir()
    (half / MARKER).write_text(json.dumps({"linkwork_report": 1, "complete": False, "files": []}))
    (half / "figures").mkdir()
    try:
        with folder.replacing(out) as work:
            _fake_report_body(work, "new")
        assert _complete_report(out) == "new"
        assert sorted(os.listdir(tmp_path)) == sorted(["r", live.name, stranger.name])
        assert (live / "report.html").read_text() == "live" and (stranger / "keep.txt").exists()
    finally:
        os.close(lock)


@pytest.mark.slow  # over the default lane's budget on the NumPy kernels (tests/conftest.py)
def test_a_killed_analyze_leaves_the_old_report_and_the_next_run_no_stray_folder(tmp_path):
    """The command itself, killed while it builds; its hidden folder is cleared by the next run."""
    import linkwork as lw
    from linkwork import report

    out = tmp_path / "r"
    out.mkdir()
    _fake_report(out, "old")
    cmd = [
        sys.executable,
        "-m",
        "linkwork.cli",
        "analyze",
        "four-bar",
        "--out",
        str(out),
        "--steps",
        "36",
        "--no-animation",
    ]
    # in a process group of its own, killed whole as a shell kills a job (the report's second process with it)
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and proc.poll() is None:
        if any(len(list(p.glob("figures/*"))) >= 2 for p in tmp_path.glob(".r.*")):
            break
        time.sleep(0.02)
    assert proc.poll() is None, "the run ended before it could be killed"
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    assert _complete_report(out) == "old"
    assert list(tmp_path.glob(".r.*"))  # what the killed run left
    report.analyze(lw.compile(lw.example("four-bar")), out, steps=36, animation=False)
    assert sorted(os.listdir(tmp_path)) == ["r"]
    assert json.loads((out / MARKER).read_text())["complete"] and (out / "figures" / "scheme.svg").exists()
