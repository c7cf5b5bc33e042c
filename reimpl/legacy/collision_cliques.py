"""Collision cliques, as RigidBodyTree had them (seed 002, Drake ≤ v0.22).

A clique is an integer id; each element keeps the sorted ids of its cliques.
A pair is filtered iff the two sorted sets intersect: every pair inside one
clique is filtered, ``{(a, b) : a, b ∈ Q, a ≠ b}`` for each clique ``Q``.

The test is ``SortedVectorsHaveIntersection`` (drake/common/sorted_vectors_have_intersection.h):
O(n + m) for elements in n and m cliques in the worst case (interleaved ids,
no common one), with two short-circuits that make the common cases constant:
an empty set, and ranges that do not overlap (``a[0] > b[-1]`` or
``b[0] > a[-1]``).

>>> cliques = CollisionCliques()
>>> q = cliques.new_clique()
>>> cliques.add_to_clique("a", q); cliques.add_to_clique("b", q)
>>> cliques.is_filtered("a", "b"), cliques.is_filtered("a", "c")
(True, False)
"""

from __future__ import annotations

import bisect
from collections.abc import Hashable, Iterable, Sequence
from typing import Generic, TypeVar

from reimpl.legacy._errors import UnknownCliqueError

__all__ = ["CollisionCliques", "sorted_vectors_have_intersection"]

E = TypeVar("E", bound=Hashable)


def sorted_vectors_have_intersection(a: Sequence[int], b: Sequence[int]) -> bool:
    """True iff the sorted sequences share an entry; constant time when one is empty or
    their ranges do not overlap, else a merge walk of at most ``len(a) + len(b)`` steps.

    >>> sorted_vectors_have_intersection([10, 20, 30], [15, 25, 35])
    False
    """
    if not a or not b:
        return False
    if a[0] > b[-1] or b[0] > a[-1]:
        return False
    i = j = 0
    while True:
        if a[i] < b[j]:
            i += 1
            if i == len(a):
                return False
        elif b[j] < a[i]:
            j += 1
            if j == len(b):
                return False
        else:
            return True


class CollisionCliques(Generic[E]):
    """Clique ids and, per element, the sorted list of the cliques it is in."""

    def __init__(self) -> None:
        self._next_id = 0
        self._cliques: dict[E, list[int]] = {}
        self._members: dict[int, dict[E, None]] = {}  # an ordered set per clique

    def new_clique(self) -> int:
        """A fresh clique id (0, 1, ... in order)."""
        clique = self._next_id
        self._next_id += 1
        self._members[clique] = {}
        return clique

    def add_to_clique(self, element: E, clique: int) -> None:
        """Puts ``element`` in ``clique`` (sorted insertion, O(n); adding twice is a no-op).

        Raises:
            UnknownCliqueError: ``new_clique`` never returned ``clique``.
        """
        if clique not in self._members:
            raise UnknownCliqueError(
                f"Cannot add an element to clique {clique}: ids 0..{self._next_id - 1} were issued."
            )
        ids = self._cliques.setdefault(element, [])
        at = bisect.bisect_left(ids, clique)
        if at == len(ids) or ids[at] != clique:
            ids.insert(at, clique)
            self._members[clique][element] = None

    def cliques_of(self, element: E) -> tuple[int, ...]:
        """The ids of ``element``'s cliques, sorted (empty for an element in none)."""
        return tuple(self._cliques.get(element, ()))

    def members(self, clique: int) -> tuple[E, ...]:
        """The elements of ``clique``, in the order they were added."""
        if clique not in self._members:
            raise UnknownCliqueError(f"Clique {clique} was never issued.")
        return tuple(self._members[clique])

    @property
    def num_cliques(self) -> int:
        """The ids issued so far."""
        return self._next_id

    def max_cliques_per_element(self) -> int:
        """The largest clique set of any element: the n of the O(n + m) test."""
        return max((len(ids) for ids in self._cliques.values()), default=0)

    def is_filtered(self, a: E, b: E) -> bool:
        """True iff ``a`` and ``b`` share a clique (see ``sorted_vectors_have_intersection``)."""
        return sorted_vectors_have_intersection(self._cliques.get(a, ()), self._cliques.get(b, ()))

    def filtered_pairs(self, elements: Iterable[E]) -> set[frozenset[E]]:
        """Every pair {a, b} of distinct ``elements`` that ``is_filtered``."""
        listed = list(dict.fromkeys(elements))
        ids = [self._cliques.get(e, []) for e in listed]
        pairs: set[frozenset[E]] = set()
        for i, a in enumerate(listed):
            for j in range(i + 1, len(listed)):
                if sorted_vectors_have_intersection(ids[i], ids[j]):
                    pairs.add(frozenset((a, listed[j])))
        return pairs
