"""The viewer's edits: an edit's round trip against ``lw.forces`` of the same cycle, and updates a second while
a handle is dragged in Chromium.

Run with ``python benchmarks/bench_viewer.py [--name double-cut-shears] [--edits 200] [--drag 6]`` (the
browser part needs Playwright and Debian's ``chromium``; ``--drag 0`` leaves it out).

* The server is ``linkwork view NAME --port 0 --no-browser`` in its own process, as a user starts it.
* An edit's round trip: ``POST /api/edit`` with a crank length not asked before (no answer from the
  cache), over one kept-alive connection on 127.0.0.1, until its answer is read and parsed (its JSON, its
  arrays as NumPy arrays over its bytes, as the page reads them); the median and the best of ``--edits``
  of them.
* The core: ``lw.forces`` of the same mechanism at 360 angles of a turn (kinematics, loads, reactions,
  foundation) in this process, the best of several runs and the median; the same of the viewer's own
  cycle (360 angles from position 0, the edit as a design variant: what the server solves), the median;
  and ``lw.compile`` of its file (what opening another file costs before the cycle is solved).
* Opening: the whole cycle's payload (:func:`linkwork.web.cycle_payload`) with its labels placed at the
  first sample (the page's first answer), at the live page's
  :data:`~linkwork.web.payload.LIVE_PLACED` samples (the answer that follows), and at every sample (an
  exported page), best of a few.
* A pose while others edit: ``POST /api/pose`` (one crank angle, a frame apart, as the page sends them while
  the crank turns) timed while ``--editors`` clients (0, 1, 8 by default) send edits back to back, each on
  its own connection, none answered from the cache: the median and the 90th percentile of ``--poses``.
* In Chromium: the crank's length handle dragged back and forth along the crank for ``--drag`` seconds, a mouse move due
  every 16 ms (a 60 Hz mouse: each move is sent when it is due, or at once when the browser, which takes a
  move only at its next frame, is behind); the page counts the edits' answers it shows (``data-updates`` on
  the scheme): answers a second, the moves a second it took, and the round trip the page measures for the
  answers (``data-edit-ms``, sampled).
"""

from __future__ import annotations

import argparse
import http.client
import json
import re
import statistics
import subprocess
import sys
import time

import numpy as np
from timing import best

import linkwork as lw
from linkwork.study import Study
from linkwork.web.payload import LIVE_PLACED, cycle_payload
from linkwork.web.update import decode_edit

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking"]


def start_server(name: str) -> tuple[subprocess.Popen, int]:
    code = "import sys; from linkwork.cli.main import main; sys.argv = ['linkwork'] + sys.argv[1:]; main()"
    proc = subprocess.Popen(
        [sys.executable, "-c", code, "view", name, "--port", "0", "--no-browser"], stdout=subprocess.PIPE, text=True
    )
    line = proc.stdout.readline() if proc.stdout else ""
    found = re.search(r"http://127\.0\.0\.1:(\d+)/", line)
    if not found:
        proc.kill()
        raise SystemExit(f"the viewer did not start: {line!r}")
    return proc, int(found.group(1))


def crank_length(mech: lw.Mechanism) -> str:
    """The parameter of the crank's length (the driven link's)."""
    k = int(mech.drive_pair[0])
    link = mech.link_names[max(int(i) for i in mech.pair_links[k])]
    return f"links.{link}.length"


def crank_direction(mech: lw.Mechanism) -> tuple[float, float]:
    """The crank's direction on the screen (from its pivot to its farthest point, y downwards) where the page
    opens, at position 0: a length handle moves with the pointer's travel along its link only."""
    from linkwork.motion.analysis import zero_angle

    k = int(mech.drive_pair[0])
    crank = max(int(i) for i in mech.pair_links[k])  # as crank_length
    at = lw.kinematics(mech, [zero_angle(mech)]).points()[0]  # (P, 2)
    pivot = at[int(mech.pair_points[k, 1])]
    arms = at[np.asarray(mech.point_link) == crank] - pivot
    u = arms[np.argmax(np.hypot(arms[:, 0], arms[:, 1]))]
    u = u / np.hypot(*u)
    return float(u[0]), float(-u[1])


def round_trips(port: int, name: str, start: float, count: int, warm: int = 5) -> list[float]:
    """Seconds from sending an edit to its parsed answer, each a new value, ``count`` of them after ``warm``
    not timed (they warm the server up)."""
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
    out = []
    for k in range(count + warm):
        value = start * (1 + 0.05 * ((k * 0.618) % 1 - 0.5))  # within 2.5 % of the file's, all different
        body = json.dumps({"overrides": {name: value}, "whole_turn": True}).encode()  # one send: no Nagle stall
        t = time.perf_counter()
        conn.request("POST", "/api/edit", body, {"Content-Type": "application/json", "Host": "127.0.0.1"})
        r = conn.getresponse()
        raw = r.read()
        if r.status != 200:
            raise SystemExit(f"edit {value}: {r.status} {raw[:500]!r}")
        decode_edit(raw)
        if k >= warm:
            out.append(time.perf_counter() - t)
    conn.close()
    return out


def drag(port: int, name: str, seconds: float, along: tuple[float, float]) -> tuple[float, float, list[float]]:
    """Answers a second shown while the handle of ``name`` is dragged back and forth ``along`` a direction on
    the screen, mouse moves a second, and the page's round trips (ms)."""
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=FLAGS)
        page = browser.new_page(viewport={"width": 1400, "height": 1000})
        page.goto(f"http://127.0.0.1:{port}/")
        handle = page.locator(f'[data-handle="{name}"]')
        handle.wait_for()
        box = handle.bounding_box()
        assert box is not None
        x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
        page.mouse.move(x, y)
        page.mouse.down()
        before = int(page.get_attribute("#scheme", "data-updates") or 0)
        ms: list[float] = []
        t0 = time.perf_counter()
        k = 0
        while time.perf_counter() - t0 < seconds:
            k += 1
            ahead = t0 + 0.016 * k - time.perf_counter()
            if ahead > 0:  # not due yet
                time.sleep(ahead)
            off = 25 * ((k % 40) / 20 - 1 if (k // 40) % 2 else 1 - (k % 40) / 20)  # px, 25 out to 25 in
            page.mouse.move(x + off * along[0], y + off * along[1])
            if k % 10 == 0:
                ms.append(float(page.get_attribute("#scheme", "data-edit-ms") or "nan"))
        spent = time.perf_counter() - t0
        shown = int(page.get_attribute("#scheme", "data-updates") or 0) - before
        page.mouse.up()
        browser.close()
    return shown / spent, k / spent, ms


def poses_while_editing(port: int, name: str, start: float, editors: int, count: int) -> list[float]:
    """Seconds from sending a pose (``POST /api/pose``, one crank angle of the file's mechanism) to its parsed
    answer, ``count`` of them one after another, while ``editors`` clients (threads, a kept-alive connection
    each) send edits back to back, each a value not asked before (no answer from the cache)."""
    import threading

    stop = threading.Event()

    def edit(client: int) -> None:
        conn = http.client.HTTPConnection("127.0.0.1", port, timeout=600)
        for seq in range(10**9):
            if stop.is_set():
                break
            value = start * (1 + 0.04 * ((seq * 0.618 + client * 0.37) % 1 - 0.5) + 1e-7 * client)
            body = {"overrides": {name: value}, "client": f"editor{client}", "seq": seq}
            conn.request("POST", "/api/edit", json.dumps(body).encode(), {"Content-Type": "application/json"})
            conn.getresponse().read()
        conn.close()

    warm = http.client.HTTPConnection("127.0.0.1", port, timeout=600)  # kernels compiled before any timing
    warm.request(
        "POST",
        "/api/edit",
        json.dumps({"overrides": {name: start * 1.001}}).encode(),
        {"Content-Type": "application/json"},
    )
    warm.getresponse().read()
    warm.close()
    threads = [threading.Thread(target=edit, args=(c,), daemon=True) for c in range(editors)]
    for t in threads:
        t.start()
    time.sleep(0.5 if editors else 0.0)  # the edits under way
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=600)  # the first compiles the kernels
    out = []
    try:
        for k in range(count + 5):
            body = json.dumps({"angle_deg": (7.3 * k) % 360}).encode()
            t = time.perf_counter()
            conn.request("POST", "/api/pose", body, {"Content-Type": "application/json"})
            r = conn.getresponse()
            raw = r.read()
            if r.status != 200:
                raise SystemExit(f"pose: {r.status} {raw[:500]!r}")
            json.loads(raw)
            if k >= 5:
                out.append(time.perf_counter() - t)
            time.sleep(0.016)  # a crank step a frame, as the page sends them
    finally:
        stop.set()
        for t in threads:
            t.join(timeout=60)
        conn.close()
    return out


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--name", default="double-cut-shears")
    parser.add_argument("--edits", type=int, default=200)
    parser.add_argument("--drag", type=float, default=6.0, help="seconds of dragging in Chromium (0: none)")
    parser.add_argument("--poses", type=int, default=100, help="poses timed for each number of --editors")
    parser.add_argument("--editors", default="0,1,8", help="clients editing while poses are timed, e.g. 0,1,8,32")
    parser.add_argument("--only-poses", action="store_true", help="time the poses only")
    args = parser.parse_args(argv)
    spec = lw.load(args.name)
    mech = lw.compile(spec)
    name = crank_length(mech)
    start = lw.parameters(mech)[name]
    proc, port = start_server(args.name)
    try:
        poses = {n: poses_while_editing(port, name, start, n, args.poses) for n in map(int, args.editors.split(","))}
        for n, times in poses.items():
            median, high = 1e3 * statistics.median(times), 1e3 * np.quantile(times, 0.9)
            print(
                f"  pose round trip (POST /api/pose, parsed) while {n} clients edit back to back: median "
                f"{median:.1f} ms, 90th percentile {high:.1f} ms"
            )
        if args.only_poses:
            return
        trips = round_trips(port, name, start, args.edits)
        forces = [best(lambda: lw.forces(mech, steps=360)) for _ in range(3)]
        runs = []
        for _ in range(50):
            t = time.perf_counter()
            lw.forces(mech, steps=360)
            runs.append(time.perf_counter() - t)
        own = []  # the viewer's own solve: its turn from position 0, the edit as a variant
        angles, variant = Study(mech).turn(360), {name: [1.01 * start]}
        for _ in range(50):
            t = time.perf_counter()
            lw.forces(mech, angles, variants=variant)
            own.append(time.perf_counter() - t)
        compiled = best(lambda: lw.compile(spec))
        opened = {
            n: best(lambda n=n: cycle_payload(mech, 360, placed=n), repeat=2, budget=8.0)
            for n in (1, LIVE_PLACED, None)
        }
        rate, moves, page_ms = float("nan"), float("nan"), list[float]()
        if args.drag > 0:
            rate, moves, page_ms = drag(port, name, args.drag, crank_direction(mech))
    finally:
        proc.terminate()
        proc.wait(timeout=10)
    f_best, f_median = min(forces), statistics.median(runs)
    rt_median, rt_best = statistics.median(trips), min(trips)
    print(f"{args.name}, 360 angles, {len(trips)} edits of {name}")
    print(f"  edit round trip (POST /api/edit, parsed): median {1e3 * rt_median:.1f} ms, best {1e3 * rt_best:.1f} ms")
    print(f"  lw.forces of the cycle: best {1e3 * f_best:.2f} ms, median {1e3 * f_median:.2f} ms")
    print(f"  ratio: median edit / median lw.forces {rt_median / f_median:.1f}, best / best {rt_best / f_best:.1f}")
    print(
        f"  lw.forces of the viewer's own cycle (from position 0, the edit as a variant): median "
        f"{1e3 * statistics.median(own):.2f} ms"
    )
    print(f"  lw.compile of the file: {1e3 * compiled:.1f} ms")
    print(
        f"  the cycle's payload, labels placed at the first sample {1e3 * opened[1]:.0f} ms, at "
        f"{LIVE_PLACED} samples {1e3 * opened[LIVE_PLACED]:.0f} ms, at all 360 {1e3 * opened[None]:.0f} ms"
    )
    if page_ms:
        shown = [v for v in page_ms if v == v]
        print(
            f"  dragging in Chromium: {rate:.1f} updates a second ({moves:.1f} mouse moves a second), the page's "
            f"round trip median {statistics.median(shown) if shown else float('nan'):.1f} ms"
        )


if __name__ == "__main__":
    main()
