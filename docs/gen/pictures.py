"""The pictures of the guides, how-tos, tutorials and concepts, drawn when the site is built by the same
functions the report draws with (``linkwork.figures``), so that no picture can drift from the code.  Each is
written to ``pictures/NAME.svg``; a page shows it with ``![what](../pictures/NAME.svg)``.

``COMMANDS`` gives, for each picture, the command line that draws the same figure in a report; the gallery of
pictures (``pictures/index.md``) lists them.  Short batches and the NumPy kernels keep the build quick.
"""

from __future__ import annotations

import functools
import io
import os
from collections.abc import Callable
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
    with mkdocs_gen_files.open("pictures/index.md", "w") as f:
        f.write("\n".join(rows) + "\n")


main()
