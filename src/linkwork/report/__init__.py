"""The main job: every analysis a mechanism supports, its tables, figures, animation and a report
(:func:`analyze`, built in :mod:`linkwork.report.build`; the folder it is written into is handled by
:mod:`linkwork.report.folder`)."""

from __future__ import annotations

from linkwork.report.build import analyze, require_packages

__all__ = ["analyze", "require_packages"]
