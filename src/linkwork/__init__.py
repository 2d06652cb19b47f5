"""linkwork: analysis of planar lever mechanisms of machines.

Describe a mechanism once (a YAML file or :class:`MechanismBuilder`),
:func:`compile` it, and run the analyses on the compiled model.
"""

from __future__ import annotations

from typing import Any

__version__ = "0.1.0"

_LAZY = {
    "load": ("linkwork.examples", "resolve"),
    "loads": ("linkwork.spec.reader", "loads"),
    "from_dict": ("linkwork.spec.reader", "from_dict"),
    "Spec": ("linkwork.spec.schema", "Spec"),
    "MechanismBuilder": ("linkwork.spec.builder", "MechanismBuilder"),
    "compile": ("linkwork.api", "compile"),
    "Mechanism": ("linkwork.structure.model", "Mechanism"),
    "Structure": ("linkwork.structure.model", "Structure"),
    "AssurGroup": ("linkwork.structure.model", "AssurGroup"),
    "example": ("linkwork.examples", "load_example"),
    "kinematics": ("linkwork.api", "kinematics"),
    "Kinematics": ("linkwork.motion.kinematic_analysis", "Kinematics"),
    "parameters": ("linkwork.api", "parameters"),
    "forces": ("linkwork.api", "forces"),
    "forces_of": ("linkwork.kinetostatics.reaction_forces", "forces_of"),
    "Forces": ("linkwork.kinetostatics.reaction_forces", "Forces"),
    "bolt_speed": ("linkwork.api", "bolt_speed"),
    "balance": ("linkwork.api", "balance"),
    "size": ("linkwork.api", "size"),
    "reduced": ("linkwork.api", "reduced"),
    "dynamics": ("linkwork.api", "dynamics"),
    "simulate": ("linkwork.api", "simulate"),
    "rocker_impact": ("linkwork.impulse", "rocker_impact"),
    "impact": ("linkwork.api", "impact"),
    "simulate_blows": ("linkwork.api", "simulate_blows"),
    "sweep": ("linkwork.design", "sweep"),
    "optimize": ("linkwork.design", "optimize"),
    "synthesize": ("linkwork.synthesis", "synthesize"),
}

__all__ = ["__version__", *_LAZY]


def __dir__() -> list[str]:
    """The package's public names (:data:`__all__`), for ``dir(linkwork)`` and completion; their types are in
    ``__init__.pyi``, which type checkers read in place of this module."""
    return sorted(__all__)


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        import importlib

        module, attr = _LAZY[name]
        return getattr(importlib.import_module(module), attr)
    raise AttributeError(f"module 'linkwork' has no attribute {name!r}")
