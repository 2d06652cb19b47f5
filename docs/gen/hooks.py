"""mkdocs hooks of the manual.

The Python reference's navigation (``reference/api/SUMMARY.md``, written by ``docs/gen/reference.py``) is read by
literate-nav and is not a page: ``exclude_docs`` leaves out the files of ``docs/`` only, not those written at build
time, so it is excluded here, after literate-nav has read it (literate-nav's ``on_files`` runs at priority -100).
"""

from __future__ import annotations

from typing import Any

from mkdocs.plugins import event_priority
from mkdocs.structure.files import Files, InclusionLevel

NAVIGATION = "SUMMARY.md"


@event_priority(-110)
def on_files(files: Files, config: Any) -> Files:
    for file in files:
        if file.src_uri.rsplit("/", 1)[-1] == NAVIGATION:
            file.inclusion = InclusionLevel.EXCLUDED
    return files
