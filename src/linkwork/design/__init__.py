"""Design: sweeps over many variants of a mechanism, and optimisation, in one process or on Dask.

:func:`sweep` evaluates metrics (:data:`METRICS`) over a grid or a random or
Latin-hypercube sample of the file's named parameters (:func:`linkwork.parameters`), in chunks, with
results written chunk by chunk so that a stopped sweep resumes; :func:`optimize`
searches the ranges by differential evolution for the best design under
constraints and writes it as a mechanism file.
"""

from __future__ import annotations

from linkwork.design.metrics import METRICS, Metric
from linkwork.design.optimizer import Optimum, optimize
from linkwork.design.plan import SweepPlan, Vary
from linkwork.design.sweeps import SweepTable, sweep
from linkwork.errors import DesignError

__all__ = [
    "METRICS",
    "DesignError",
    "Metric",
    "Optimum",
    "SweepPlan",
    "SweepTable",
    "Vary",
    "optimize",
    "sweep",
]
