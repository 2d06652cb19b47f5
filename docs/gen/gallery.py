"""The gallery, generated when the site is built: every bundled example run through linkwork, its check, its
scheme, plan of positions, velocity and acceleration plans, kinematic diagrams, driving torque and an
animation, drawn by ``linkwork.figures`` as the report draws them (nothing is committed but this script).

Set ``LINKWORK_NUMBA=0`` for a quick build: the short batches here take the NumPy kernels milliseconds.
"""

from __future__ import annotations

import io
import os
import re
import tempfile
from pathlib import Path

import mkdocs_gen_files

os.environ.setdefault("LINKWORK_NUMBA", "0")
os.environ["MPLBACKEND"] = "agg"

STEPS = 120  # samples of the turn for the diagrams and the trajectories: enough to draw, quick to build


def _svg(fig) -> str:
    buf = io.StringIO()
    fig.savefig(buf, format="svg")
    return buf.getvalue()


def _prose(text: str) -> str:
    """A description as plain text in Markdown: one line, its ``*`` and ``_`` (``W = 3*7 - 2*10``) not emphasis."""
    return re.sub(r"([*_\\])", r"\\\1", " ".join(text.split()))


def _check(name: str) -> str:
    """What ``linkwork check NAME`` prints."""
    from typer.testing import CliRunner

    from linkwork.cli.main import app

    return CliRunner().invoke(app, ["check", name]).output


def example_page(name: str) -> str:
    import linkwork as lw
    from linkwork import examples, figures
    from linkwork.motion.analysis import position_angles, zero_angle
    from linkwork.scene.positions import plan_positions

    mech = lw.compile(lw.example(name))
    zero = zero_angle(mech)
    kin = lw.kinematics(mech, position_angles(mech, STEPS, zero))
    twelve = lw.kinematics(mech, position_angles(mech, 12, zero))
    first = plan_positions(mech, twelve)[0]
    drawings = {
        "scheme": (
            f"Kinematic scheme at position {first}",
            lambda: figures.draw_scheme(twelve, first, position=first, cycle=kin),
        ),
        "positions": ("Plan of the twelve positions", lambda: figures.draw_positions(kin)),
        "velocity_plan": (
            f"Velocity plan, position {first}",
            lambda: figures.velocity_plan(twelve, first, position=first),
        ),
        "acceleration_plan": (
            f"Acceleration plan, position {first}",
            lambda: figures.acceleration_plan(twelve, first, position=first),
        ),
        "kinematic_diagrams": (
            "Kinematic diagrams of the working members",
            lambda: figures.kinematic_diagrams(kin, zero),
        ),
    }
    if not mech.structure.redundant:
        drawings["driving_torque"] = ("Driving torque", lambda: figures.torque_diagram(lw.forces(kin), zero))
    # the same in the report's Russian (--lang ru): its notation, the plan's pole p and scale μv
    drawings["scheme_ru"] = (
        f"Кинематическая схема, положение {first} (--lang ru)",
        lambda: figures.draw_scheme(twelve, first, position=first, cycle=kin, lang="ru"),
    )
    drawings["velocity_plan_ru"] = (
        f"План скоростей, положение {first} (--lang ru)",
        lambda: figures.velocity_plan(twelve, first, position=first, lang="ru"),
    )
    spec = lw.example(name)
    out = [
        f"# {name}",
        "",
        _prose(spec.description or ""),
        "",
        f"`linkwork example {name} > {name}.yaml` writes the file to start your own from; "
        f"`linkwork analyze {name} --out report` writes its whole report.",
        "",
        "## Structure",
        "",
        "```",
        _check(name).rstrip(),
        "```",
    ]
    import matplotlib.pyplot as plt

    for key, (caption, draw) in drawings.items():
        fig = draw()
        with mkdocs_gen_files.open(f"gallery/{name}/{key}.svg", "w") as f:
            f.write(_svg(fig))
        plt.close(fig)
        out += ["", f"## {caption}", "", f"![{caption}]({name}/{key}.svg)"]
    with tempfile.TemporaryDirectory() as tmp:
        gif = Path(tmp) / "animation.gif"
        figures.animate(kin, gif, frames=24, fps=8)
        with mkdocs_gen_files.open(f"gallery/{name}/animation.gif", "wb") as f:
            f.write(gif.read_bytes())
    out += ["", "## Animation", "", f"![the cycle]({name}/animation.gif)"]
    out += ["", "## The file", "", "```yaml", examples.text(name).rstrip(), "```"]
    return "\n".join(out) + "\n"


def main() -> None:
    import linkwork as lw
    from linkwork import examples

    rows = [
        "# Gallery",
        "",
        "Every bundled example, run through linkwork when this manual was built: its structure,",
        "scheme, plan of positions, plans, diagrams and animation.  The force plans, the lever, the",
        "dynamics and the synthesised mechanisms are among [the pictures of the manual](../pictures/index.md).",
        "",
        "",
    ]
    for name in examples.names():
        text = example_page(name)
        with mkdocs_gen_files.open(f"gallery/{name}.md", "w") as f:
            f.write(text)
        first = _prose(((lw.example(name).description or "").strip().splitlines() or [""])[0])
        rows += [
            f"## [{name}]({name}.md)",
            "",
            f"{first.rstrip('.')}.  Drawn by `linkwork analyze {name} --out report`.",
            "",
            f'[![the scheme of {name}]({name}/scheme.svg){{ width="520" }}]({name}.md)',
            "",
        ]
    with mkdocs_gen_files.open("gallery/index.md", "w") as f:
        f.write("\n".join(rows) + "\n")


main()
