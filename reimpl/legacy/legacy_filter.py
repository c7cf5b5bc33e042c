"""The whole RigidBodyTree element test: anchored pairs, then groups, then cliques.

``Element::CanCollideWith`` (attic multibody/collision/element.cc) excluded a
pair iff

    (a ∈ A ∧ b ∈ A) ∨ (m_a & i_b) | (m_b & i_a) ≠ 0 ∨ cliques(a) ∩ cliques(b) ≠ ∅

with ``A`` the anchored elements. The legacy candidate set over elements ``E``
is ``C = {(a, b) : a, b ∈ E, a ≠ b} − {pairs excluded above}``.
"""

from __future__ import annotations

from collections.abc import Hashable, Iterable
from dataclasses import dataclass, field
from typing import Generic, TypeVar

from reimpl.legacy.collision_cliques import CollisionCliques
from reimpl.legacy.collision_filter_groups import CollisionFilterGroups

__all__ = ["LegacyFilter"]

E = TypeVar("E", bound=Hashable)


@dataclass
class LegacyFilter(Generic[E]):
    """Groups, cliques and the anchored elements of one RigidBodyTree."""

    groups: CollisionFilterGroups[E] = field(default_factory=CollisionFilterGroups)
    cliques: CollisionCliques[E] = field(default_factory=CollisionCliques)
    anchored: frozenset[E] = frozenset()

    def is_filtered(self, a: E, b: E) -> bool:
        """The module doc's test, cheapest clause first (as RBT ordered it)."""
        return (
            (a in self.anchored and b in self.anchored)
            or self.groups.is_filtered(a, b)
            or self.cliques.is_filtered(a, b)
        )

    def filtered_pairs(self, elements: Iterable[E]) -> set[frozenset[E]]:
        """Every pair of distinct ``elements`` that ``is_filtered``."""
        listed = list(dict.fromkeys(elements))
        return {
            frozenset((a, b))
            for i, a in enumerate(listed)
            for b in listed[i + 1 :]
            if self.is_filtered(a, b)
        }

    def candidate_pairs(self, elements: Iterable[E]) -> set[frozenset[E]]:
        """C: every pair of distinct ``elements`` that is not filtered."""
        listed = list(dict.fromkeys(elements))
        return {
            frozenset((a, b))
            for i, a in enumerate(listed)
            for b in listed[i + 1 :]
            if not self.is_filtered(a, b)
        }
