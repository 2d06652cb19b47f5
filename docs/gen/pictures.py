"""The pictures of the guides, how-tos, tutorials and concepts, drawn when the site is built by the same
functions the report draws with (``linkwork.figures``), so that no picture can drift from the code.  Each is
written to ``pictures/NAME.svg``; a page shows it with ``![what](../pictures/NAME.svg)``.

``COMMANDS`` gives, for each picture, the command line that draws the same figure in a report; the gallery of
pictures (``pictures/index.md``) lists them.  Short batches and the NumPy kernels keep the build quick.
"""

from __future__ import annotations

import functools
import io
import json
import os
import shutil
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

import mkdocs_gen_files

os.environ.setdefault("LINKWORK_NUMBA", "0")
os.environ["MPLBACKEND"] = "agg"

SHEARS = "double-cut-shears"


def _svg(fig: Any) -> str:
    buf = io.StringIO()
    fig.savefig(buf, format="svg", bbox_inches="tight")
    return buf.getvalue()


@functools.cache
def _cycle(name: str, steps: int = 120) -> tuple[Any, Any, Any, int, float]:
    """(kinematics over a turn, at the twelve positions, the forces at the twelve, the position drawn, zero)."""
    import linkwork as lw
    from linkwork.motion.analysis import position_angles, zero_angle
    from linkwork.scene.positions import plan_positions

    mech = lw.compile(name)
    zero = zero_angle(mech)
    kin = lw.kinematics(mech, position_angles(mech, steps, zero))
    twelve = lw.kinematics(mech, position_angles(mech, 12, zero))
    first = plan_positions(mech, twelve)[0]
    forces = None if mech.structure.redundant else lw.forces(twelve)
    return kin, twelve, forces, first, zero


def _scheme(name: str, lang: str = "en") -> Any:
    from linkwork import figures

    kin, twelve, _, first, _ = _cycle(name)
    return figures.draw_scheme(twelve, first, position=first, cycle=kin, lang=lang)


def _plan(kind: str, lang: str = "en") -> Any:
    from linkwork import figures

    _, twelve, _, first, _ = _cycle(SHEARS)
    draw = figures.velocity_plan if kind == "velocity" else figures.acceleration_plan
    return draw(twelve, first, position=first, lang=lang)


def _force(which: int) -> Any:
    from linkwork.figures.force_plans import force_figures

    _, _, forces, first, _ = _cycle(SHEARS)
    return force_figures(forces, first, position=first)[which]


def _turn_forces(name: str) -> Any:
    import linkwork as lw

    kin, *_ = _cycle(name)
    return lw.forces(kin)


def _torque(name: str) -> Any:
    from linkwork import figures

    return figures.torque_diagram(_turn_forces(name), _cycle(name)[4])


def _foundation() -> Any:
    from linkwork import figures

    return figures.foundation_diagram(_turn_forces(SHEARS), _cycle(SHEARS)[4])


def _diagrams() -> Any:
    from linkwork import figures

    kin, *_, zero = _cycle(SHEARS)
    return figures.kinematic_diagrams(kin, zero)


def _positions(name: str) -> Any:
    from linkwork import figures

    return figures.draw_positions(_cycle(name)[0])


def _dynamics() -> Any:
    import linkwork as lw
    from linkwork import figures

    return figures.dynamics_diagrams(lw.dynamics(SHEARS, steps=360, turns=20), _cycle(SHEARS)[4])


def _limits(kind: str, **requirements: Any) -> Any:
    import linkwork as lw
    from linkwork import figures
    from linkwork.motion.analysis import position_angles, zero_angle

    mech = lw.compile(lw.synthesize(kind, **requirements).spec)
    return figures.draw_limits(lw.kinematics(mech, position_angles(mech, 120, zero_angle(mech))))


def _sweep() -> Any:
    import matplotlib.pyplot as plt

    import linkwork as lw

    table = lw.sweep(SHEARS, {"links.crank.length": ("90 mm", "110 mm", 11)}, ["peak_driving_torque"], steps=72)
    frame = table.to_pandas() if hasattr(table, "to_pandas") else table
    x = [c for c in frame.columns if "crank" in c][0]
    fig, ax = plt.subplots(figsize=(5.5, 3.2), layout="constrained")
    ax.plot(frame[x] * 1000, frame["peak_driving_torque"], "o-", ms=4)
    ax.set_xlabel("crank length, mm")
    ax.set_ylabel("peak driving torque, N m")
    ax.set_title("A sweep of the double-cut shears' crank length")
    ax.grid(alpha=0.3)
    return fig


#: The viewer's picture: the double-cut shears' exported page at 120 crank angles, the slider at position 9 of the
#: twelve (sample 90), in a window of 1200 x 760 px.
VIEWER_STEPS, VIEWER_SAMPLE, VIEWER_WINDOW = 120, 90, (1200, 760)


def _viewer_page(folder: Path) -> Path:
    from linkwork.web import export_page

    return export_page(SHEARS, folder / "viewer.html", steps=VIEWER_STEPS)


def _screenshot(page: Path) -> bytes | None:
    """The page in headless Chromium (Debian's, driven by Playwright) at :data:`VIEWER_SAMPLE`; None where either
    is missing."""
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        return None
    if chromium is None:
        return None
    width, height = VIEWER_WINDOW
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=chromium, args=["--headless", "--no-sandbox", "--disable-gpu"])
        try:
            tab = browser.new_page(viewport={"width": width, "height": height})
            tab.goto(page.as_uri())
            tab.wait_for_selector('#scheme circle.joint[data-point="E"]')
            tab.locator("#angle").fill(str(VIEWER_SAMPLE))
            tab.wait_for_timeout(500)
            return tab.screenshot()
        finally:
            browser.close()


def _payload(page: Path) -> dict[str, Any]:
    """The data the exported page reads (its ``linkwork-data`` script)."""
    text = page.read_text(encoding="utf-8")
    start = text.index('id="linkwork-data">') + len('id="linkwork-data">')
    return json.loads(text[start : text.index("</script>", start)])


def _placed(xy: Any, pose: Any) -> Any:
    import numpy as np

    c, s = np.cos(pose[2]), np.sin(pose[2])
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    return np.column_stack([pose[0] + c * xy[:, 0] - s * xy[:, 1], pose[1] + s * xy[:, 0] + c * xy[:, 1]])


def _payload_figure(data: dict[str, Any], k: int) -> Any:
    """Without a browser: what the page shows at sample ``k``, drawn with matplotlib from the same data: the
    scheme's items placed by the links' poses, its labels, and the two plans' vectors from the pole."""
    import matplotlib.pyplot as plt
    import numpy as np

    scene = data["scene"]
    poses = np.asarray(scene["poses"][k], dtype=float)
    fig, axes = plt.subplots(1, 3, figsize=(12, 4.6), width_ratios=[2, 1, 1], layout="constrained")
    for item in scene["items"]:
        xy = _placed(item["xy"], poses[item["link"]])
        if item.get("radius"):
            axes[0].add_patch(plt.Circle(xy[0], item["radius"], fill=False, lw=0.8))
        else:
            xy = np.vstack([xy, xy[:1]]) if item.get("closed") else xy
            axes[0].plot(xy[:, 0], xy[:, 1], color="#1f4e8c" if item["link"] else "0.3", lw=1.2)
    for label in scene["labels"]:
        if label["centre"][k] is not None:
            axes[0].text(*label["centre"][k], label["text"], ha="center", va="center", fontsize=8)
    axes[0].set_title(f"{data['name']}: turned {data['turn_deg'][k]:.0f} deg from position 0", fontsize=9)
    for ax, kind in zip(axes[1:], ("velocity", "acceleration"), strict=True):
        plan = data["plans"][kind]
        values = np.asarray([v if v is not None else [np.nan, np.nan] for v in plan["values"][k]], dtype=float)
        for vector in plan["vectors"]:
            a, b = values[vector["from"]], values[vector["to"]]
            ax.annotate("", b, a, arrowprops={"arrowstyle": "->", "lw": 0.8})
        ax.plot(values[:, 0], values[:, 1], ".", color="0.2", ms=3)
        for name, xy in zip(plan["labels"], values, strict=True):
            ax.text(*xy, name.split(".")[0], fontsize=7)
        ax.set_title(f"{kind} plan, pole p ({plan['unit']})", fontsize=9)
    for ax in axes:
        ax.set_aspect("equal", adjustable="datalim")
        ax.autoscale()
        ax.axis("off")
    return fig


def viewer() -> None:
    """``pictures/viewer.png`` (the page in Chromium, or drawn from its data without a browser) and the page
    itself, ``pictures/viewer-double-cut-shears.html``, which the how-to links to."""
    import matplotlib.pyplot as plt

    with tempfile.TemporaryDirectory() as tmp:
        page = _viewer_page(Path(tmp))
        png = _screenshot(page)
        if png is None:
            print(
                "pictures.py: no chromium or Playwright; the viewer's picture is drawn from its data", file=sys.stderr
            )
            fig = _payload_figure(_payload(page), VIEWER_SAMPLE)
            buf = io.BytesIO()
            fig.savefig(buf, format="png", dpi=100)
            plt.close(fig)
            png = buf.getvalue()
        with mkdocs_gen_files.open("pictures/viewer.png", "wb") as f:
            f.write(png)
        with mkdocs_gen_files.open(f"pictures/viewer-{SHEARS}.html", "w") as f:
            f.write(page.read_text(encoding="utf-8"))


#: name -> (caption, drawing, the command whose report draws the same figure)
PICTURES: dict[str, tuple[str, Callable[[], Any], str]] = {
    "scheme-shears": (
        "Kinematic scheme of the double-cut shears",
        lambda: _scheme(SHEARS),
        f"linkwork analyze {SHEARS} --out report",
    ),
    "scheme-shears-ru": (
        "Кинематическая схема ножниц (--lang ru)",
        lambda: _scheme(SHEARS, "ru"),
        f"linkwork analyze {SHEARS} --out report --lang ru",
    ),
    "scheme-four-bar": (
        "Kinematic scheme of the four-bar",
        lambda: _scheme("four-bar"),
        "linkwork analyze four-bar --out report",
    ),
    "scheme-slider-crank": (
        "Kinematic scheme of the slider-crank shears",
        lambda: _scheme("shears-slider-crank"),
        "linkwork analyze shears-slider-crank --out report",
    ),
    "scheme-rocker": (
        "Kinematic scheme of the percussion rocker",
        lambda: _scheme("percussion-rocker"),
        "linkwork analyze percussion-rocker --out report",
    ),
    "scheme-six-bar": (
        "Kinematic scheme of the Stephenson six-bar",
        lambda: _scheme("stephenson-six-bar"),
        "linkwork analyze stephenson-six-bar --out report",
    ),
    "positions-shears": (
        "The twelve positions of the double-cut shears",
        lambda: _positions(SHEARS),
        f"linkwork analyze {SHEARS} --out report",
    ),
    "velocity-plan": ("Velocity plan", lambda: _plan("velocity"), f"linkwork analyze {SHEARS} --out report"),
    "velocity-plan-ru": (
        "План скоростей (--lang ru)",
        lambda: _plan("velocity", "ru"),
        f"linkwork analyze {SHEARS} --out report --lang ru",
    ),
    "acceleration-plan": (
        "Acceleration plan",
        lambda: _plan("acceleration"),
        f"linkwork analyze {SHEARS} --out report",
    ),
    "kinematic-diagrams": (
        "Kinematic diagrams of the knives",
        _diagrams,
        f"linkwork analyze {SHEARS} --out report",
    ),
    "force-plans": ("Force plans of the groups", lambda: _force(0), f"linkwork analyze {SHEARS} --out report"),
    "lever": ("Zhukovsky's lever", lambda: _force(1), f"linkwork analyze {SHEARS} --out report"),
    "torque-shears": (
        "Driving torque of the double-cut shears",
        lambda: _torque(SHEARS),
        f"linkwork analyze {SHEARS} --out report",
    ),
    "torque-slider-crank": (
        "Driving torque of the slider-crank shears",
        lambda: _torque("shears-slider-crank"),
        "linkwork analyze shears-slider-crank --out report",
    ),
    "foundation": ("Foundation loads", _foundation, f"linkwork analyze {SHEARS} --out report"),
    "dynamics": ("Machine dynamics", _dynamics, f"linkwork analyze {SHEARS} --out report"),
    "limits-crank-rocker": (
        "Limit positions of a synthesised crank-rocker",
        lambda: _limits("crank-rocker", swing="45 deg", time_ratio=1.2, rocker="300 mm"),
        'linkwork synthesize crank-rocker --swing "45 deg" --time-ratio 1.2 --rocker "300 mm" --out cr.yaml'
        " && linkwork analyze cr.yaml --out report",
    ),
    "limits-slider-crank": (
        "Limit positions of a synthesised slider-crank",
        lambda: _limits("slider-crank", stroke="400 mm", time_ratio=1.2, rod_ratio=0.25),
        'linkwork synthesize slider-crank --stroke "400 mm" --time-ratio 1.2 --rod-ratio 0.25 --out sc.yaml'
        " && linkwork analyze sc.yaml --out report",
    ),
    "sweep": (
        "Peak driving torque against the crank's length",
        _sweep,
        f'linkwork sweep {SHEARS} --vary "links.crank.length=90mm:110mm:11" --metric peak_driving_torque '
        "--steps 72 --out sweep.parquet",
    ),
}


def main() -> None:
    import matplotlib.pyplot as plt

    rows = [
        "# Pictures of the manual",
        "",
        "Every picture of the guides, drawn when this manual was built by the functions the report draws",
        "with, and the command whose report (or table) holds the same figure.",
        "",
    ]
    for name, (caption, draw, command) in PICTURES.items():
        fig = draw()
        with mkdocs_gen_files.open(f"pictures/{name}.svg", "w") as f:
            f.write(_svg(fig))
        plt.close(fig)
        image = f'[![{caption}]({name}.svg){{ width="520" }}]({name}.svg)'
        rows += [f"## {caption}", "", f"`{command}`", "", image, ""]
    viewer()
    caption = "The viewer of the double-cut shears at position 9"
    command = f"linkwork view {SHEARS} --export shears.html --steps {VIEWER_STEPS}"
    image = f'[![{caption}](viewer.png){{ width="520" }}](viewer-{SHEARS}.html)'
    rows += [f"## {caption}", "", f"`{command}` (click the picture: the page itself)", "", image, ""]
    with mkdocs_gen_files.open("pictures/index.md", "w") as f:
        f.write("\n".join(rows) + "\n")


main()
