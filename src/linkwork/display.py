"""How results show themselves in a notebook: Jupyter shows an object by its ``_repr_html_``, and the results
of linkwork (:class:`~linkwork.motion.kinematic_analysis.Kinematics`,
:class:`~linkwork.kinetostatics.reaction_forces.Forces`,
:class:`~linkwork.machine.steady_cycle.Dynamics`, :class:`~linkwork.design.sweeps.SweepTable`) give a short table
of what they hold, each number with its unit, made here.  Imports nothing of linkwork: the core may use it.

Their ``to_xarray()`` and ``to_pandas()`` are built by the core's own table modules
(:mod:`linkwork.motion.tables`, :mod:`linkwork.kinetostatics.tables`), which :mod:`linkwork.io` writes.
"""

from __future__ import annotations

import html
from collections.abc import Iterable


def table(title: str, rows: Iterable[tuple[str, object]]) -> str:
    """A two-column HTML table under a caption: each row a label and its value (as text, escaped)."""
    body = "".join(
        f'<tr><th style="text-align:left">{html.escape(label)}</th><td style="text-align:left">'
        f"{html.escape(str(value))}</td></tr>"
        for label, value in rows
    )
    return f'<table><caption style="text-align:left"><b>{html.escape(title)}</b></caption>{body}</table>'


def number(value: float, unit: str = "") -> str:
    """A value to 6 significant digits with its unit (none for a pure number, unit "1"); "none" for NaN."""
    return "none" if value != value else f"{value:.6g}{' ' + unit if unit not in ('', '1') else ''}"
