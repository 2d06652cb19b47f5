"""Did you mean: the closest of the names a word could have meant, for the messages of every stage.

It sits below the file format and the analyses alike (it imports only :mod:`linkwork.limits`), so that an
analysis that names a point, a link or a joint asked for (``kin.position("B2")``) says which name was meant
without importing the file format.
"""

from __future__ import annotations

import difflib
import threading
from collections.abc import Collection, Iterator
from contextlib import contextmanager

from linkwork.limits import MAX_NAME, quote

#: Candidates compared for suggestions in one pass of the file's checks (:func:`budget`): beyond, no more
#: suggestions, so that a file of many wrong names against many right ones is checked in near-linear time.
SUGGESTIONS = 200_000

_budget = threading.local()


def suggest(word: str, candidates: Collection[str]) -> str:
    """`` (did you mean "x"?)`` for the closest candidate, or an empty string (also for a word longer
    than a name, and once a pass under :func:`budget` has compared :data:`SUGGESTIONS` candidates)."""
    left = getattr(_budget, "left", None)
    if len(str(word)) > MAX_NAME or (left is not None and left < len(candidates)):
        return ""
    if left is not None:
        _budget.left = left - len(candidates)
    close = difflib.get_close_matches(str(word), [str(c) for c in candidates], n=1, cutoff=0.5)
    return f" (did you mean {quote(close[0])}?)" if close else ""


@contextmanager
def budget(candidates: int = SUGGESTIONS) -> Iterator[None]:
    """Within the block (one pass of checks, in this thread), :func:`suggest` compares at most ``candidates``
    candidates in all."""
    _budget.left = candidates
    try:
        yield
    finally:
        _budget.left = None
