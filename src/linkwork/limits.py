"""Bounds on what a file or an option may ask of linkwork, and on what a message quotes back.

Each bound has one home here; the YAML reader, the unit parser, the command line and the design
options all check against these, with one message that names the bound.  A value within them may
still be refused for what it means (an angle that does not assemble); one beyond them is refused
before any work, so that no input can make linkwork run out of memory or run without end.
"""

from __future__ import annotations

import math
import os
import re
from typing import Any

#: Steps over a turn of the crank where a function of ``linkwork`` is given neither angles nor ``steps``
#: (keyword-only everywhere): for the analyses of positions over a turn (``kinematics``, ``forces``,
#: ``balance``, ``bolt_speed``, ``sweep``, ``optimize``, the report).
TURN_STEPS = 360

#: The same for machine dynamics (``reduced``, ``dynamics``, ``simulate_blows``): the integrals over the
#: turn (the work, the energy, the run of the machine unit) need the finer grid.
DYNAMICS_STEPS = 3600

#: Bytes of a mechanism file (or of YAML text given to :func:`linkwork.loads`).
MAX_FILE_BYTES = 1 << 20

#: Characters of a line of a mechanism file (a longer list is written over several lines).
MAX_LINE = 100_000

#: Values of a mechanism file (keys, list items and scalars), aliases counted each time they are used.
MAX_NODES = 100_000

#: Nesting of mappings and lists in a mechanism file.
MAX_DEPTH = 64

#: Characters of a name in a file (a key: a link, a joint, a point, a load).
MAX_NAME = 100

#: Characters of a number with its unit (``"100 mm"``) or of a unit (``"kg*m^2"``).
MAX_QUANTITY = 100

#: Characters of the text of an option (a ``--vary``, ``--metric`` or ``--constraint``).
MAX_OPTION = 1_000

#: Characters of a value a message quotes back (longer ones are cut, with an ellipsis).
QUOTE = 60

#: Characters of a path a message names (a path is shown whole up to this).
QUOTE_PATH = 300

#: Problems a message lists; those beyond are counted.
MAX_PROBLEMS = 100

#: Crank angles of one run: ``--steps``, ``--angles``, ``--count``; also the angles of a sweep's turn.
MAX_ANGLES = 100_000

#: Turns of the crank either side of its assembly angle that an asked angle may lie within.
MAX_TURNS = 100

#: Variants of one sweep (a grid's product of counts, or ``--samples``).
MAX_VARIANTS = 10_000_000

#: Samples (variants x crank angles) solved at once: a chunk of a sweep, a generation of an optimisation.
MAX_BATCH = 1 << 22

#: Generations of an optimisation.
MAX_GENERATIONS = 100_000

#: Largest seed of a random sample or of the optimiser.
MAX_SEED = 2**32 - 1

#: Worker processes of a local Dask cluster, per core of the machine.
WORKERS_PER_CORE = 4

#: Seconds to wait for a Dask scheduler.
MAX_TIMEOUT = 3600.0

#: Blows of a working cycle.
MAX_BLOWS = 10_000

#: Largest size of a value a mechanism file may give: of a quantity in SI, or of a pure number (a gear ratio, a
#: friction coefficient).  A machine's are far smaller; beyond, the products and squares of later stages
#: overflow.
MAX_MAGNITUDE = 1e9

#: Largest gear ratio (motor speed / crank speed): the simulation of the machine's start takes time in proportion
#: to it (16 s at 1000 on a 2-core machine, minutes beyond).
MAX_GEAR_RATIO = 1000.0

#: Loads of a mechanism file: each is evaluated at every crank angle of an analysis.  Machine dynamics evaluates
#: them one at a time (:func:`~linkwork.kinetostatics.external.power_of_loads`: its peak memory does not grow with
#: their number, 61 MB for the double-cut shears with 0 and with 50 springs), but its time grows by about 0.4 s a
#: spring (27 s with none, 47 s with 50, on the 2-core machine of the benchmarks page): 100 about double it.
MAX_LOADS = 100

#: Smallest dimension of a part the sizing reads (a pin, a section, a guide), m: below it the stresses overflow.
MIN_PART = 1e-6

#: Bytes of a catalogue file (a motor catalogue), and rows of it: every row is screened against the machine.
MAX_CATALOGUE_BYTES = 1 << 20
MAX_CATALOGUE_ROWS = 1_000

#: Smallest coefficient of speed fluctuation a flywheel is sized for (the inertia grows as 1/delta).
MIN_DELTA = 1e-4

#: The width / diameter of a pin or bush sized: from a thin disc to a long sleeve (common designs: 0.5 to 1.5).
WIDTH_RATIOS = (0.1, 10.0)


def quote(value: Any, limit: int = QUOTE) -> str:
    """``value`` as text in double quotes, cut to ``limit`` characters with an ellipsis, its size
    said where it was cut: ``"root:*:19000:0:..." (2,480 characters)``; see :func:`excerpt`."""
    text = value if isinstance(value, str) else str(value)
    cut = excerpt(text[:limit]).replace('"', '\\"')
    return f'"{cut}"' if len(text) <= limit else f'"{cut}..." ({len(text):,} characters)'


def excerpt(value: Any, limit: int = QUOTE) -> str:
    """``value`` as text for a message, without quotes (a path, with ``limit`` :data:`QUOTE_PATH`): cut
    to ``limit`` characters with an ellipsis, and control characters and surrogates shown escaped, so
    that it is always one short line that any terminal can print."""
    text = value if isinstance(value, str) else str(value)
    shown = "".join(c if c.isprintable() else repr(c)[1:-1] for c in text[:limit])
    return shown if len(text) <= limit else f"{shown}... ({len(text):,} characters)"


#: The control characters a terminal acts on (C0 but tab and newline, DEL, C1): an escape sequence in a name could
#: retitle the window or clear the screen.
_CONTROL = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f]")


def printable(text: str) -> str:
    """``text`` with every control character but tab and newline escaped (``\\x1b``): what may be printed to a
    terminal, whatever a file or an option held."""
    if _CONTROL.search(text) is None:
        return text
    return _CONTROL.sub(lambda m: m.group().encode("unicode_escape").decode("ascii"), text)


def digits(text: str) -> bool:
    """Whether ``text`` is a whole number written in the digits 0 to 9 alone (``str.isdigit`` also takes
    ``²``, which ``int`` refuses, and the digits of other scripts)."""
    return text.isascii() and text.isdigit()


def whole(value: Any, name: str, low: int, high: int, what: str = "number") -> str | None:
    """Why ``value`` is not a whole number from ``low`` to ``high`` (a message naming ``name`` and
    saying ``what`` it counts), or None."""
    if isinstance(value, int) and not isinstance(value, bool) and low <= value <= high:
        return None
    if low == 1:
        return f"{name}: expected a positive {what}, at most {high:,}, got {shown(value)}"
    return f"{name}: expected a whole {what}, at least {low:,} and at most {high:,}, got {shown(value)}"


def shown(value: Any) -> str:
    """A value for a message: a number or a truth value as Python writes it, other values by
    :func:`quote`; never longer than about :data:`QUOTE` characters."""
    if isinstance(value, float | bool):
        return repr(value)
    if isinstance(value, int):
        if abs(value) < 10**QUOTE:
            return str(value)
        return f"a whole number of about {len(f'{value:x}') * 1.204:,.0f} digits"
    return quote(value)


def echo(value: Any) -> str:
    """A value read from a mechanism file, for a message, spelled as the file (YAML) writes it: ``true`` and
    ``false``, ``.inf`` and ``.nan``, numbers as written, text by :func:`quote`, and what has no one spelling
    said in words (``nothing`` for an empty value, ``a mapping``, ``a list``).  The one way a message of
    :mod:`linkwork.spec` and :mod:`linkwork.units` echoes a bad value."""
    if value is None:
        return "nothing"
    if isinstance(value, dict):
        return "a mapping"
    if isinstance(value, list | tuple):
        return "a list"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float) and not math.isfinite(value):
        return ".nan" if math.isnan(value) else (".inf" if value > 0 else "-.inf")
    if isinstance(value, int | float):
        return shown(value)
    return quote(value)


def max_workers() -> int:
    """Worker processes a local Dask cluster may have on this machine."""
    return WORKERS_PER_CORE * (os.cpu_count() or 1)


def angle_problem(degrees: float, name: str) -> str | None:
    """Why a crank angle (degrees) is out of reach: not finite, or more than :data:`MAX_TURNS` turns."""
    bound = 360.0 * MAX_TURNS
    if math.isfinite(degrees) and abs(degrees) <= bound:
        return None
    return f"{name}: expected crank angles within {MAX_TURNS} turns ({bound:,.0f} deg) either way, got {degrees:g}"


def delta_problem(delta: float | None, name: str) -> str | None:
    """Why ``delta`` is not a coefficient of speed fluctuation to size a flywheel for (from
    :data:`MIN_DELTA`, below 1), or None (also for None: the file's, or none)."""
    if delta is None or (math.isfinite(delta) and MIN_DELTA <= delta < 1):
        return None
    return f"{name}: expected a coefficient of speed fluctuation from {MIN_DELTA:g} up to 1, got {shown(delta)}"


#: Longest run in time (``linkwork simulate --until``, ``simulate: until:``), s: ten minutes of a machine's
#: life, some hundreds of turns of a crank (a run's work grows with its length).
MAX_RUN_TIME = 600.0

#: Evaluations of the equation of motion in one run in time, each one exact pose of the mechanism (about
#: 5 ms each with the NumPy kernels): about four minutes of work on a 2-core machine.
MAX_RUN_EVALUATIONS = 50_000


def run_time_problem(seconds: float, name: str) -> str | None:
    """Why ``seconds`` is not the length of a run in time (positive, at most :data:`MAX_RUN_TIME`), or None."""
    if math.isfinite(seconds) and 0 < seconds <= MAX_RUN_TIME:
        return None
    return f"{name}: expected a run of more than 0 s and at most {MAX_RUN_TIME:g} s, got {seconds:g} s"
