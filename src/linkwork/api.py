"""The public entry points: what a mechanism argument is, and the stages :func:`compile` composes.

Every analysis of ``linkwork`` (``linkwork.kinematics``, ``linkwork.forces``, ...) takes its
mechanism as any of

- a path to a mechanism file (``str`` or :class:`os.PathLike`, ``.yaml``/``.yml``),
- the name of a bundled example (``"four-bar"``; ``linkwork examples`` lists them),
- a :class:`~linkwork.spec.schema.Spec` (from :func:`linkwork.load` or :class:`linkwork.MechanismBuilder`),
- a compiled :class:`~linkwork.structure.model.Mechanism` (from :func:`linkwork.compile`).

Anything else is a :class:`TypeError` that says what is expected.  The algorithms themselves live in
the module named for them (:func:`linkwork.motion.kinematic_analysis.kinematics`,
:func:`linkwork.kinetostatics.reaction_forces.forces`, ...) and take a compiled mechanism; the functions here
are those algorithms with the argument resolved first (:func:`resolving`), with the same signature
and documentation.  This module sits above the analysis packages and below the design, output,
viewer and command-line packages, which call :func:`mechanism_of` themselves.
"""

from __future__ import annotations

import dataclasses
import functools
import inspect
import os
from collections.abc import Callable
from typing import Any, Concatenate, ParamSpec, TypeVar, Union, cast

from linkwork import jit
from linkwork.errors import LinkworkError
from linkwork.examples import names, resolve
from linkwork.impulse.cycle import simulate_blows as _simulate_blows
from linkwork.impulse.mechanism import impact as _impact
from linkwork.kinetostatics.balancing import balance as _balance
from linkwork.kinetostatics.bolt_lift import bolt_speed as _bolt_speed
from linkwork.kinetostatics.reaction_forces import forces as _forces
from linkwork.machine.reduction import reduced as _reduced
from linkwork.machine.steady_cycle import dynamics as _dynamics
from linkwork.machine.timerun import simulate as _simulate
from linkwork.motion import compiled_program, groups
from linkwork.motion.kinematic_analysis import Kinematics
from linkwork.motion.kinematic_analysis import kinematics as _kinematics
from linkwork.sizing.machine_sizing import size as _size
from linkwork.spec.reader import described
from linkwork.spec.schema import Spec
from linkwork.stage_records import compile_friction, compile_loads, from_spec
from linkwork.structure.compile import structural_model
from linkwork.structure.model import Mechanism
from linkwork.structure.parameters import parameter_values

#: What a mechanism argument may be.
MechanismLike = Union[str, "os.PathLike[str]", Spec, Mechanism]  # noqa: UP007 - a string forward reference

#: What a mechanism argument may be, for messages.
EXPECTED = (
    "a mechanism file path, the name of a bundled example, a Spec (linkwork.load) or a Mechanism (linkwork.compile)"
)

P = ParamSpec("P")
R = TypeVar("R")


def spec_of(mechanism: object, what: str = "mechanism") -> Spec | None:
    """The description of ``mechanism``: loaded from a file or example, given, or the one a
    compiled mechanism was compiled from (None for a mechanism assembled in code without one).

    Raises
    ------
    TypeError
        For anything but a path, an example name, a Spec or a Mechanism.
    SpecError
        For a file or example with problems, or a name that is neither.
    """
    if isinstance(mechanism, Spec):
        return mechanism
    if isinstance(mechanism, Mechanism):
        return described(mechanism.description)
    if isinstance(mechanism, str | os.PathLike):
        return resolve(os.fspath(mechanism))
    raise TypeError(f"{what}: expected {EXPECTED}, got {type(mechanism).__name__}")


def mechanism_of(mechanism: object, what: str = "mechanism") -> Mechanism:
    """The compiled :class:`~linkwork.structure.model.Mechanism` of ``mechanism`` (compiled here
    when it is a path, an example name or a Spec; returned as it is when compiled already).

    Raises
    ------
    TypeError
        For anything but a path, an example name, a Spec or a Mechanism.
    SpecError, StructureError, UnassemblableError
        From loading and compiling.
    """
    if isinstance(mechanism, Mechanism):
        return mechanism
    spec = spec_of(mechanism, what)
    assert spec is not None
    return compile(spec)


def compile(spec: MechanismLike) -> Mechanism:  # noqa: A001 - the public name of the pipeline step
    """Compile a description into a :class:`~linkwork.structure.model.Mechanism`: the one compile.

    ``spec``: a validated Spec, or a mechanism file's path or a bundled example's name (loaded
    first); a compiled Mechanism is returned as it is.  The stages, each giving data of the model
    (the records of :mod:`linkwork.structure.records`): the structural model
    (:func:`linkwork.structure.compile.structural_model`: arrays, Assur groups, assembly pose,
    redundant constraints), the solve program of its groups (:func:`linkwork.motion.groups.build`, the
    branches read off the assembly pose by :func:`linkwork.motion.groups.with_branches`, and its table
    for the compiled kernels where they cover it: :func:`linkwork.motion.compiled_program.encode`), the
    external loads (:func:`linkwork.stage_records.compile_loads`), the friction in the pairs
    (:func:`linkwork.stage_records.compile_friction`) and the machine unit's motor and gear
    (:func:`linkwork.stage_records.from_spec`).

    Parameters
    ----------
    spec : Spec, Mechanism, str or Path
        A validated description, a mechanism file's path or a bundled example's name.

    Returns
    -------
    Mechanism
        The compiled model: frozen arrays, its structure (Assur groups), assembly pose and solve program.

    Raises
    ------
    TypeError
        For anything but a path, an example name, a Spec or a Mechanism.
    SpecError
        A group lacks the hint that chooses its assembly mode, or a mass property is impossible.
    StructureError
        The mobility does not match the drives.
    UnassemblableError
        The assembly pose does not exist.

    Examples
    --------
    >>> import linkwork as lw
    >>> lw.compile("four-bar").structure.formula
    'I(0,1) -> II(2,3)'
    """
    if isinstance(spec, Mechanism):
        return spec
    if not isinstance(spec, Spec):
        described = spec_of(spec, "compile")
        assert described is not None
        spec = described
    mech = structural_model(spec)
    program = tuple(groups.with_branches(mech, groups.build(mech)))
    return dataclasses.replace(
        mech,
        program=program,
        program_table=compiled_program.encode(program, mech.point_link) if compiled_program.supports(program) else None,
        loads=compile_loads(spec, mech),
        friction=compile_friction(spec, mech),
        motor_gear=from_spec(spec.machine) if spec.machine is not None else None,
    )


def _with_compile(algorithm: Callable[..., R]) -> Callable[..., R]:
    """``algorithm`` with :func:`compile` given as its ``compile_spec`` (a stage below this module that compiles
    edited files), its name, documentation and signature kept."""

    @functools.wraps(algorithm)
    def entry(*args: Any, **kwargs: Any) -> R:
        kwargs.setdefault("compile_spec", compile)
        return algorithm(*args, **kwargs)

    return entry


def resolving(
    algorithm: Callable[Concatenate[Mechanism, P], R], what: str, passes: tuple[type, ...] = ()
) -> Callable[Concatenate[object, P], R]:
    """``algorithm`` taking any mechanism argument (:func:`mechanism_of`) in place of a compiled one,
    with its name, documentation and signature (its first parameter typed :data:`MechanismLike`);
    arguments of the types ``passes`` go to it as they are.  Anything else is a :class:`TypeError`
    when it is called."""

    @jit.deciding
    @functools.wraps(algorithm)
    def entry(mechanism: object, /, *args: P.args, **kwargs: P.kwargs) -> R:
        if isinstance(mechanism, passes):  # a type the algorithm takes as it is (forces: a Kinematics)
            return algorithm(cast(Mechanism, mechanism), *args, **kwargs)
        return algorithm(mechanism_of(mechanism, what), *args, **kwargs)

    signature = inspect.signature(algorithm)
    first, *rest = signature.parameters.values()
    entry.__signature__ = signature.replace(  # type: ignore[attr-defined]
        parameters=[first.replace(annotation="MechanismLike"), *rest]
    )
    return entry


kinematics = resolving(_kinematics, "kinematics")
forces = resolving(_forces, "forces", passes=(Kinematics,))
reduced = resolving(_reduced, "reduced")
dynamics = resolving(_dynamics, "dynamics")
simulate = resolving(_simulate, "simulate")
impact = resolving(_impact, "impact")
simulate_blows = resolving(_simulate_blows, "simulate_blows")
balance = resolving(_balance, "balance")
bolt_speed = resolving(_bolt_speed, "bolt_speed")
size = resolving(_with_compile(_size), "size")  # sizing's masses="sized" compiles each round's file
parameters = resolving(parameter_values, "parameters")


def compile_kernels() -> list[str]:
    """Compile the numba kernels into their cache now (``linkwork warm``; :mod:`linkwork.jit`), then mark
    the cache ready, so that later processes load them where they pay and none compiles in front of a user.

    Every bundled example is solved with the compiled kernels over a cycle and over a few design variants,
    its points read, its forces and its dynamics found: the calls every analysis makes, so that each kernel
    is compiled for the arrays it is called with.  Then a fresh process loads them, and what that cost is
    recorded (:func:`linkwork.jit.measured_cost`).  Returns the examples run.
    """
    jit.force()
    done = []
    for name in names():
        mech = compile(name)
        first = parameter_values(mech)
        runs = [_kinematics(mech, steps=720)]
        if first:
            path, value = next(iter(first.items()))
            runs.append(_kinematics(mech, steps=360, variants={path: [value, value]}))
        for kin in runs:
            kin.points()
            for point in mech.point_names[:1]:
                kin.velocity(point), kin.acceleration(point)
            try:
                _forces(kin)
            except LinkworkError:  # not statically determinate: no reactions to compile for
                pass
        if mech.motor_gear is not None:
            _dynamics(mech)
        done.append(name)
    jit.mark_ready()
    jit.measure_load()  # what a later process's switch will cost it, measured on this machine
    return done
