"""Decomposition of a mechanism into its driving links and Assur groups.

Starting from the frame, the smallest set of not yet placed links whose
position is fixed by its pairs with the placed links (and by the drives) is
split off, again and again.  "Fixed" is decided from the rank of the
constraint Jacobian at a random (generic) pose: a set S of k links is a
group when the rows that involve only S and placed links determine all 3k
coordinates of S.  This recognises dyads, triads (class III), four-link
groups with a closed contour (class IV) and larger groups alike, and it does
not depend on counting rules that special dimensions could fool.
"""

from __future__ import annotations

from itertools import combinations
from typing import NamedTuple

import numpy as np

from linkwork.structure.constraints import Rows
from linkwork.structure.model import AssurGroup, PairType

DYADS = ("RRR", "RRP", "RPR", "PRP", "RPP")


def rank(a: np.ndarray, rtol: float = 1e-8) -> int:
    """Numerical rank with a tolerance relative to the largest singular value."""
    if a.size == 0:
        return 0
    s = np.linalg.svd(a, compute_uv=False)
    return int(np.sum(s > rtol * max(s[0], 1e-300)))


def decompose(
    rows: Rows,
    jac: np.ndarray,
    n_total: int,
    pair_type: np.ndarray,
    pair_links: np.ndarray,
    pair_joint: tuple[str, ...],
    link_names: tuple[str, ...],
) -> tuple[list[AssurGroup], list[int]]:
    """Split the moving links into groups in solving order.

    Parameters
    ----------
    rows : Rows
        Row bookkeeping of ``jac`` (pair rows and drive rows).
    jac : ndarray, shape (m, 3 * n_total)
        Scaled constraint Jacobian at a generic pose.

    Returns
    -------
    groups : list of AssurGroup
    undetermined : list of int
        Links that no drive determines (empty when the decomposition is complete).
    """
    placed = {0}
    pairs = _Pairs(pair_type, pair_links, pair_joint, link_names)
    remaining = list(range(1, n_total))
    groups: list[AssurGroup] = []
    row_links = [set(map(int, rl)) for rl in rows.links]
    while remaining:
        found = _smallest_group(jac, row_links, placed, remaining)
        if found is None:
            return groups, remaining
        subset, sel, redundant = found
        groups.append(_classify(subset, sel, redundant, rows, pairs))
        placed |= set(subset)
        remaining = [i for i in remaining if i not in subset]
    return groups, []


def _smallest_group(
    jac: np.ndarray, row_links: list[set[int]], placed: set[int], remaining: list[int]
) -> tuple[tuple[int, ...], list[int], int] | None:
    """The smallest set of the ``remaining`` links whose coordinates the rows between them and the ``placed``
    links determine (the first found among sets of one size): the set, its rows and the number of its
    redundant constraints; None where no set is determined."""
    for k in range(1, len(remaining) + 1):
        for subset in combinations(remaining, k):
            s = set(subset)
            allowed = placed | s
            sel = [i for i, rl in enumerate(row_links) if rl <= allowed and rl & s]
            if len(sel) < 3 * k:
                continue
            cols = [3 * i + c for i in subset for c in range(3)]
            r = rank(jac[np.ix_(sel, cols)])
            if r == 3 * k:
                return subset, sel, len(sel) - r
    return None


class _Pairs(NamedTuple):
    """The kinematic pairs of a mechanism as the decomposition reads them: each pair's type, its two links and its
    joint's name, and the links' names."""

    pair_type: np.ndarray
    pair_links: np.ndarray
    pair_joint: tuple[str, ...]
    link_names: tuple[str, ...]


def _classify(subset: tuple[int, ...], sel: list[int], redundant: int, rows: Rows, of: _Pairs) -> AssurGroup:
    """The Assur group (or driven group) of the links ``subset`` closed by the constraint rows ``sel``."""
    pair_type, pair_links, pair_joint, link_names = of
    s = set(subset)
    pairs = sorted({int(rows.pair[i]) for i in sel if rows.pair[i] >= 0})
    # a pair repeated between the same links at the same points only adds redundant constraints
    distinct: dict[tuple[frozenset[int], int, str | None], int] = {}
    for k in pairs:
        key = (frozenset(map(int, pair_links[k])), int(pair_type[k]), pair_joint[k] if pair_type[k] else None)
        distinct.setdefault(key, k)
    pairs = sorted(distinct.values())
    driven = any(rows.drive[i] >= 0 for i in sel)
    internal = [k for k in pairs if set(map(int, pair_links[k])) <= s]
    external = [k for k in pairs if k not in internal]
    letter = {k: ("P" if pair_type[k] == PairType.PRISMATIC else "R") for k in pairs}
    joints = tuple(dict.fromkeys(pair_joint[k] for k in external + internal))
    inner = tuple(dict.fromkeys(pair_joint[k] for k in internal))
    names = tuple(link_names[i] for i in subset)

    def group(klass: int, order: int | None, kind: str) -> AssurGroup:
        return AssurGroup(klass, order, kind, subset, names, joints, inner, tuple(pairs), redundant, driven)

    if driven:
        return group(1, None, "".join(letter[k] for k in external + internal))
    if len(subset) == 1:
        return group(0, len(external), "".join(letter[k] for k in external))
    if len(subset) == 2 and len(internal) == 1 and len(external) == 2:
        a, b = subset
        ext_a = next(k for k in external if a in pair_links[k])
        ext_b = next(k for k in external if b in pair_links[k])
        kind = letter[ext_a] + letter[internal[0]] + letter[ext_b]
        if kind not in DYADS:
            kind = kind[::-1]
        return group(2, 2, kind)
    klass = _group_class(subset, internal, external, pair_links)
    kind = "".join(letter[k] for k in external) + "-" + "".join(letter[k] for k in internal)
    return group(klass, len(external), kind)


def _group_class(subset: tuple[int, ...], internal: list[int], external: list[int], pair_links: np.ndarray) -> int:
    """Artobolevsky's class: the largest closed contour of internal pairs, or
    the most pairs on one link of the group, whichever is larger."""
    adj: dict[int, set[int]] = {i: set() for i in subset}
    degree = dict.fromkeys(subset, 0)
    for k in internal + external:
        for i in map(int, pair_links[k]):
            if i in degree:
                degree[i] += 1
    for k in internal:
        a, b = map(int, pair_links[k])
        adj[a].add(b)
        adj[b].add(a)
    return max(_longest_cycle(adj), max(degree.values()))


def _longest_cycle(adj: dict[int, set[int]]) -> int:
    best = 0

    def walk(start: int, node: int, seen: list[int]) -> None:
        nonlocal best
        for nxt in adj[node]:
            if nxt == start and len(seen) >= 3:
                best = max(best, len(seen))
            elif nxt not in seen and nxt > start:
                walk(start, nxt, seen + [nxt])

    for start in adj:
        walk(start, start, [start])
    return best
