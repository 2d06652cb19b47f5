"""A mechanism, or a variant of it, solved over a whole turn of its crank: what the viewer's answers are built from.

The cycle and its forces are a :class:`linkwork.study.Study`'s, as the report's are.  An edit of dimensions or
masses does not change the structure, so it is solved as a variant of the
compiled mechanism (:func:`linkwork.kinematics` with ``variants``, the mass rule of
:mod:`linkwork.structure.parameters` included): no new description, no compile.  What a variant
means is what the same edit of the file means; where the file edited so would not compile (a group
that cannot be assembled at the drive angle of the assembly pose), the viewer says so
with the compiler's own message (:func:`check_assembly`).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np

from linkwork import jit
from linkwork.errors import LinkworkError, UnassemblableError
from linkwork.kinetostatics.reaction_forces import Forces
from linkwork.lang import group_label, numbers, t, texts
from linkwork.motion.events import Event
from linkwork.motion.kinematic_analysis import Kinematics, kinematics
from linkwork.scene.scheme import CYCLE
from linkwork.structure.model import Mechanism, one_crank
from linkwork.study import Study

#: Crank angles a dragged value's answer draws the scheme's symbols from (the sides the supports stand on,
#: the guides' lengths): fewer than :data:`linkwork.scene.scheme.CYCLE`, the whole cycle's, to answer in time;
#: the whole cycle solved once the drag ends draws them from all of those.
DRAGGED = 24


@dataclass(frozen=True)
class Cycle:
    """One mechanism (or one variant of it) over ``steps`` crank angles of a whole turn.

    Attributes
    ----------
    mech : Mechanism
        The compiled mechanism the variant is of.
    overrides : dict
        The variant: named values (SI) that differ from the file's; empty for the file's mechanism.
    kin : Kinematics
        The cycle (with one variant where there are overrides).
    symbols : Kinematics
        :data:`linkwork.scene.scheme.CYCLE` of its samples, evenly spread (:data:`DRAGGED` while a value is
        dragged), from which the scheme's fixed symbols are drawn (the sides of the supports, the guides'
        lengths), alike for every answer of the viewer.
    forces : Forces or None
        Where the mechanism has masses or loads and its reactions are statically determinate.
    reason : str
        Why there are no forces.
    notes : tuple of str
        The warnings of the solution.
    """

    mech: Mechanism
    overrides: dict[str, float]
    kin: Kinematics
    symbols: Kinematics
    forces: Forces | None
    reason: str
    notes: tuple[str, ...]

    def one(self, a: np.ndarray) -> np.ndarray:
        """``a`` without the variant axis (results of a variant have one)."""
        return a[0] if self.kin.variants else a

    @property
    def valid(self) -> np.ndarray:
        """Where the mechanism assembles, ``(A,)``."""
        return np.asarray(self.kin.valid_all[0], dtype=bool)

    @property
    def local(self) -> np.ndarray:
        """Every point in its link's axes, ``(P, 2)`` m (the variant's)."""
        return np.asarray(self.kin.local[:, :, 0, 0], dtype=float)

    def points(self) -> np.ndarray:
        """Positions ``(A, P, 2)`` m; the frame's points are given also at samples that do not assemble."""
        frame = np.asarray(self.mech.point_link) == 0
        out = np.array(self.one(self.kin.points()))
        out[:, frame] = self.local[frame]
        return out


@jit.deciding
def solve_cycle(mech: Mechanism, steps: int, overrides: dict[str, float] | None = None, symbols: int = CYCLE) -> Cycle:
    """The cycle of ``mech`` with ``overrides`` (SI, checked by the caller) at ``steps`` crank angles, the
    scheme's symbols drawn from ``symbols`` of its angles, evenly spread (:func:`symbol_samples`; the turn solved
    at ``symbols`` angles where ``steps`` are fewer) (:data:`DRAGGED` for the answers while a value is dragged).

    Raises
    ------
    LinkworkError
        For a mechanism without a single crank.
    """
    if not one_crank(mech):
        raise LinkworkError("the viewer turns one crank: the mechanism needs exactly one revolute drive")
    study = Study(mech, steps, overrides)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        kin = study.kin
        few = steps < symbols
        drawn = kinematics(mech, study.turn(symbols), variants=study.variants) if few else symbol_samples(kin, symbols)
        forces, reason = study.forces_or_reason
    notes = tuple(dict.fromkeys(str(w.message) for w in caught))
    return Cycle(mech, study.overrides, kin, drawn, forces, reason, notes)


def symbol_samples(kin: Kinematics, count: int) -> Kinematics:
    """``count`` samples of the cycle ``kin`` (of at least as many), evenly spread from its first (every fifth of
    360 for 72): what the scheme's symbols are drawn from, without solving the turn again."""
    n = len(kin.angles)
    return kin if n == count else kin.samples(np.round(np.arange(count) * (n / count)).astype(int))


class OutOfRange(UnassemblableError):
    """A variant the page may not show, with the events that say where it does not assemble.

    Attributes
    ----------
    events : list of dict
        The no-assembly ranges (:meth:`linkwork.motion.events.Event.as_dict`).
    """

    def __init__(self, message: str, events: list[dict[str, Any]]):
        super().__init__(message)
        self.events = events


def check_assembly(cycle: Cycle, whole: np.ndarray | None = None, lang: str = "en") -> None:
    """Raise :class:`OutOfRange` where the variant ``cycle`` is not a mechanism the page may show.

    A variant must assemble at the drive angle of the assembly pose (the first sample), as a file must to
    compile; the message is then the compiler's, for the file edited so.  With ``whole`` ``(A,)``, it must
    also assemble wherever ``whole`` is True (where the file's mechanism does: a drag may not take the
    mechanism out of its range): the message names the group and the crank angles where it does not, in
    ``lang`` (:func:`event_text`).
    """
    valid = cycle.valid
    if valid[0] and (whole is None or valid[np.asarray(whole, dtype=bool)].all()):
        return
    failed = [e for e in cycle.kin.events if e.kind == "no-assembly"]
    message = compile_message(cycle.mech, cycle.overrides) if not valid[0] else None
    if message is None:
        where = "; ".join(event_text(cycle, e, lang) for e in failed)
        message = t("view.out_of_range", lang, edit=_edit_text(cycle, lang), where=where)
    raise OutOfRange(message, [e.as_dict() for e in failed])


def compile_message(mech: Mechanism, overrides: dict[str, float]) -> str | None:
    """The compiler's message for the file of ``mech`` edited to ``overrides`` (SI, checked), or None where
    that file compiles."""
    from linkwork.api import compile as compile_spec
    from linkwork.structure.parameters import edited_spec

    try:
        compile_spec(edited_spec(mech, overrides))
    except UnassemblableError as exc:
        return str(exc)
    except LinkworkError:
        return None
    return None


def _edit_text(cycle: Cycle, lang: str = "en") -> str:
    """The overrides as the page shows them (``links.crank.length = 300 mm``)."""
    from linkwork.web.edits import shown

    return shown(cycle.mech, cycle.overrides, lang) or t("view.file_values", lang)


def event_text(cycle: Cycle, event: Event, lang: str = "en") -> str:
    """An event of ``cycle`` as the page says it: in English the analysis's message; in another language as the
    report says it (``event.KIND`` of :mod:`linkwork.lang`, the group in the language's letters, the crank angles φ
    from position 0, a decimal comma in Russian)."""
    from linkwork.motion.analysis import phi_deg, zero_angle
    from linkwork.motion.kinematic_analysis import direction

    key = f"event.{event.kind}"
    if lang == "en" or key not in texts():
        return event.message
    start, end = phi_deg([event.start, event.end], zero_angle(cycle.mech), direction(cycle.mech))
    text = t(key, lang, group=group_label(event.group, lang), start=f"{start:.1f}", end=f"{end:.1f}")
    return numbers(text, lang)
