"""The optional parts of linkwork: which package each feature needs and the extra that brings it.

Every place that imports an optional package goes through :func:`require`, so a missing one
always gives the same :class:`~linkwork.errors.MissingDependencyError`, whose message names the
package and the pip command; the command line checks what a command needs before it starts any
work and prints that one line (exit code 2).

numba is not among them: it comes with linkwork where it has wheels, and without it the
NumPy kernels run (see :mod:`linkwork.jit`).
"""

from __future__ import annotations

import importlib
import os
import sys
from types import ModuleType

from linkwork.errors import MissingDependencyError

#: The top-level module of each optional package: its name on PyPI and the extra of linkwork that brings it.
PACKAGES: dict[str, tuple[str, str]] = {
    "xarray": ("xarray", "data"),
    "matplotlib": ("matplotlib", "plot"),
    "fastapi": ("fastapi", "web"),
    "uvicorn": ("uvicorn", "web"),
    "pyarrow": ("pyarrow", "design"),
    "distributed": ("distributed", "design"),
    "dask": ("dask", "design"),
    "pandas": ("pandas", "design"),
    "ezdxf": ("ezdxf", "cad"),
    "imageio_ffmpeg": ("imageio-ffmpeg", "video"),
}


def require(*modules: str, purpose: str) -> ModuleType:
    """Import ``modules`` (e.g. ``"xarray"``, ``"pyarrow.parquet"``) for ``purpose``; the first one is returned.

    Parameters
    ----------
    *modules : str
        Dotted module names whose top-level package is one of :data:`PACKAGES`.
    purpose : str
        What needs them, as the message should say it, e.g. ``"the report (linkwork analyze)"``.

    Returns
    -------
    module
        The first of ``modules``, imported.

    Raises
    ------
    MissingDependencyError
        Naming every package of ``modules`` that cannot be imported and the pip command that
        installs them all.
    """
    loaded, missing = [], []
    for name in modules:
        try:
            loaded.append(_import(name))
        except ImportError:
            top = name.split(".", 1)[0]
            missing.append(PACKAGES.get(top, (top, "")))
    if missing:
        packages = tuple(dict.fromkeys(p for p, _ in missing))
        extras = tuple(dict.fromkeys(e for _, e in missing if e))
        raise MissingDependencyError(packages, extras, purpose)
    return loaded[0]


def _import(name: str) -> ModuleType:
    """Import ``name``; matplotlib even where the environment names a backend it does not know (``MPLBACKEND=bogus``,
    which it refuses at import): linkwork draws on its own Agg canvases, whatever the environment says."""
    try:
        return importlib.import_module(name)
    except ValueError:
        if not name.startswith("matplotlib") or "MPLBACKEND" not in os.environ:
            raise
    for partial in [m for m in sys.modules if m == "matplotlib" or m.startswith("matplotlib.")]:
        del sys.modules[partial]  # what the failed import left half-made
    wrong = os.environ.pop("MPLBACKEND")
    try:
        return importlib.import_module(name)
    finally:
        os.environ["MPLBACKEND"] = wrong
