"""The exception tree of linkwork.

Every error says *where*: the file and line, the element of the mechanism, the
crank angle or the design variant, and what was expected.  The command line
prints :class:`LinkworkError` messages as they are and exits with code 2.
"""

from __future__ import annotations

from dataclasses import dataclass

from linkwork.limits import MAX_PROBLEMS


@dataclass(frozen=True)
class Problem:
    """One problem found in a mechanism description.

    Attributes
    ----------
    path : str
        Dotted path of the element in the file, e.g. ``links.rod.length``;
        empty for problems of the file as a whole.
    message : str
        What is wrong and what was expected.
    file : str or None
        The file name as the user gave it, or None for a spec built in Python.
    line : int or None
        One-based line number in the file, when known.
    """

    path: str
    message: str
    file: str | None = None
    line: int | None = None

    def __str__(self) -> str:
        where = self.file or ""
        if self.line is not None:
            where = f"{where}:{self.line}"
        parts = [part for part in (where, self.path, self.message) if part]
        return ": ".join(parts)


class LinkworkError(Exception):
    """Base class of all errors raised by linkwork."""


class SpecError(LinkworkError, ValueError):
    """A mechanism description has one or more problems.

    Attributes
    ----------
    problems : tuple of Problem
        Every problem found, in file order (the message lists the first
        :data:`~linkwork.limits.MAX_PROBLEMS`).
    """

    def __init__(self, problems: list[Problem] | tuple[Problem, ...]):
        self.problems = tuple(problems)
        lines = [str(p) for p in self.problems[:MAX_PROBLEMS]]
        if len(self.problems) > MAX_PROBLEMS:
            lines.append(f"... and {len(self.problems) - MAX_PROBLEMS:,} more problems (SpecError.problems lists all)")
        super().__init__("\n".join(lines))


class ParameterError(LinkworkError, ValueError):
    """An override names no parameter of the mechanism, its value is out of range, or its arrays
    have unequal lengths (see :mod:`linkwork.structure.parameters`)."""


class StructureError(LinkworkError, ValueError):
    """The mechanism's structure does not match its drives (wrong mobility)."""


class UnassemblableError(LinkworkError):
    """The mechanism cannot be assembled in the requested position.

    Attributes
    ----------
    group : str
        The Assur group that fails, e.g. ``II(2,3) RRR``.
    angle : float or None
        Drive coordinate (rad or m) at which it fails, when known.
    """

    def __init__(self, message: str, group: str = "", angle: float | None = None):
        self.group = group
        self.angle = angle
        super().__init__(message)


class UnitParseError(LinkworkError, ValueError):
    """A value could not be read as the expected kind of quantity.

    ``reason`` says why a unit was refused, when there is more to say than its kind.
    """

    def __init__(self, message: str, reason: str = ""):
        super().__init__(message)
        self.reason = reason


class DesignError(LinkworkError, ValueError):
    """Bad design options (sweeps, optimisation): one line per problem in the message, the problems
    in ``problems``."""

    def __init__(self, problems: list[str] | tuple[str, ...]):
        self.problems = tuple(problems)
        super().__init__("\n".join(self.problems))


class SynthesisError(LinkworkError, ValueError):
    """Requirements of a synthesis that cannot be met together, or that are missing: the message names the
    requirements in conflict and the nearest value that can be met (:mod:`linkwork.synthesis`)."""


class SlidingReversal(LinkworkError):
    """The striker's sliding on the tool would reverse within an impact (the crank thrown back)."""


class BusyError(LinkworkError):
    """The viewer is solving as many edits as it may at once: try again."""


class LinkworkWarning(UserWarning):
    """Base class of linkwork's warnings."""


class FrictionWarning(LinkworkWarning):
    """Friction in proportion to the pairs' forces that has no solution at some positions: the pair locks
    (self-locking: the friction grows without bound, or multiplies the pairs' largest force by
    :data:`linkwork.kinetostatics.friction.LOCKING` or more; no drive moves the mechanism there), the iteration
    does not converge, or the reactions are indeterminate there (a dead point: the friction is taken as zero).

    Attributes
    ----------
    joint : str
        The joint of the pair.
    kind : str
        ``locks``, ``does not converge`` or ``indeterminate``.
    angles : tuple of float
        Where: the crank angle phi in degrees (turned from position 0) with one crank, else the first drive's
        coordinate (rad or m).
    variant : int
        The variant index (0 for a single mechanism).
    """

    def __init__(self, joint: str, kind: str, angles: tuple[float, ...], variant: int, where: str):
        self.joint, self.kind, self.angles, self.variant = joint, kind, angles, variant
        super().__init__(where)


class DesignWarning(LinkworkWarning):
    """A design option that is valid but probably not what was meant (e.g. a range in the wrong units)."""


class MissingDependencyError(LinkworkError, ImportError):
    """An optional package that a feature needs is not installed.

    Attributes
    ----------
    packages : tuple of str
        The missing packages, as pip names them.
    extras : tuple of str
        The extras of linkwork that bring them (``pip install "linkwork[EXTRA]"``).
    purpose : str
        What needs them, e.g. ``NetCDF output (kinematics.nc)``.
    """

    def __init__(self, packages: tuple[str, ...], extras: tuple[str, ...], purpose: str):
        self.packages = packages
        self.extras = extras
        self.purpose = purpose
        names = " and ".join(packages)
        command = f'pip install "linkwork[{",".join(extras)}]"' if extras else f"pip install {' '.join(packages)}"
        super().__init__(f"{purpose} needs {names}: {command}")
