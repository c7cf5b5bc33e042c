"""Mutants at the edge of a query's parameters, and where a filter decides a query (issue 30).

Each one is reimpl with one deliberate bug in its QueryObject (as
``conformance._testing.mutants``, whose ``MUTANTS`` registry lists them),
written with public calls only: a wrapper of reimpl's QueryObject that the
mutant's query output port hands out. They need posed scenes and the query
ops, so ``fuzz --poses`` is their campaign (``Mutant.posed``).

- ``max_distance`` exactly: a pair at ``φ = max_distance`` left out;
- 1 ulp beyond it: a pair at ``φ = nextafter(max_distance, ∞)`` let in;
- the filter deciding: ``HasCollisions`` and the pairwise signed distances
  blind to transient declarations.

``tests/test_mutants.py`` holds each one's witness (pydrake's exact value).
"""

from __future__ import annotations

import math
from typing import Any

from conformance._testing.mutants_basic import (
    Mutant,
    MutantSceneGraph,
    Pair,
    _pair,
    _Query,
    _QueryPort,
)
from reimpl.geometry import FilterId, Role
from reimpl.systems.framework import Context, OutputPort

__all__ = ["BOUNDARY_MUTANTS"]


class _BoundaryQuery(_Query):
    """reimpl's QueryObject; a mutant overrides one query."""

    def transient_excluded(self) -> set[Pair]:
        """The pairs an active transient declaration of this location excludes (two
        proximity geometries on different frames, not both anchored)."""
        manager = self.graph.manager(self.context)
        inspector = self.graph.real_inspector(self.context)
        live = set(inspector.GetAllGeometryIds(role=Role.kProximity))
        world = self.graph.world_frame_id()
        active: list[FilterId] = manager.active_history()
        pairs: set[Pair] = set()
        for filter_id in active:
            for resolved in self.graph.transients.get(filter_id, ()):
                if resolved.filters:
                    pairs |= {p for p in resolved.pairs() if p[0] in live and p[1] in live}

        def separable(pair: Pair) -> bool:
            frames = {inspector.GetFrameId(geometry_id=g) for g in pair}
            return len(frames) == 2 and frames != {world}

        return {p for p in pairs if separable(p)}


class _QueryMutant(MutantSceneGraph):
    """A SceneGraph whose query port hands out ``query_class`` objects."""

    query_class: type[_BoundaryQuery] = _BoundaryQuery

    def get_query_output_port(self) -> OutputPort:
        graph = self

        class Port(_QueryPort):
            def Eval(self, context: Context) -> Any:
                return graph.query_class(graph, self.inner.Eval(context), context)

        return Port(self, super().get_query_output_port())  # type: ignore[return-value]


# ----------------------------------------------------------- max_distance
class _StrictQuery(_BoundaryQuery):
    def ComputeSignedDistancePairwiseClosestPoints(self, max_distance: float = math.inf) -> Any:
        found = self.inner.ComputeSignedDistancePairwiseClosestPoints(max_distance=max_distance)
        return [r for r in found if r.distance != max_distance]


class PairwiseStrictAtMaxDistance(_QueryMutant):
    """ComputeSignedDistancePairwiseClosestPoints keeps pairs with ``φ < max_distance``:
    a pair exactly at ``max_distance`` is left out (pydrake keeps ``φ ≤ max_distance``)."""

    query_class = _StrictQuery


class _WideQuery(_BoundaryQuery):
    def ComputeSignedDistancePairwiseClosestPoints(self, max_distance: float = math.inf) -> Any:
        wider = math.nextafter(max_distance, math.inf)
        return self.inner.ComputeSignedDistancePairwiseClosestPoints(max_distance=wider)


class PairwiseOneUlpWide(_QueryMutant):
    """ComputeSignedDistancePairwiseClosestPoints compares with ``max_distance`` rounded up
    by one ulp: a pair 1 ulp beyond it is let in."""

    query_class = _WideQuery


# ------------------------------------------------------ the filter deciding
def _pair_distance(query: _BoundaryQuery, pair: Pair) -> Any:
    return query.inner.ComputeSignedDistancePairClosestPoints(
        geometry_id_A=pair[0], geometry_id_B=pair[1]
    )


class _TransientBlindCollisions(_BoundaryQuery):
    def HasCollisions(self) -> bool:
        if self.inner.HasCollisions():
            return True
        return any(_pair_distance(self, p).distance < 0 for p in self.transient_excluded())


class HasCollisionsIgnoresTransientFilters(_QueryMutant):
    """HasCollisions reads the persistent filters only: a pair that only a transient
    declaration excludes counts as a collision."""

    query_class = _TransientBlindCollisions


class _TransientBlindDistances(_BoundaryQuery):
    def ComputeSignedDistancePairwiseClosestPoints(self, max_distance: float = math.inf) -> Any:
        found = list(
            self.inner.ComputeSignedDistancePairwiseClosestPoints(max_distance=max_distance)
        )
        have = {_pair(r.id_A, r.id_B) for r in found}
        for pair in self.transient_excluded() - have:
            record = _pair_distance(self, pair)
            if record.distance <= max_distance:
                found.append(record)
        return sorted(found, key=lambda r: (r.id_A.get_value(), r.id_B.get_value()))


class PairwiseDistancesIgnoreTransientFilters(_QueryMutant):
    """ComputeSignedDistancePairwiseClosestPoints reads the persistent filters only: a pair
    that only a transient declaration excludes is reported."""

    query_class = _TransientBlindDistances


# ------------------------------------------------------------------- table
BOUNDARY_MUTANTS: tuple[Mutant, ...] = (
    Mutant(
        "pairwise_strict_at_max_distance",
        "The pairwise signed distances leave out a pair exactly at max_distance.",
        PairwiseStrictAtMaxDistance,
        posed=True,
    ),
    Mutant(
        "pairwise_one_ulp_wide",
        "The pairwise signed distances let in a pair 1 ulp beyond max_distance.",
        PairwiseOneUlpWide,
        posed=True,
    ),
    Mutant(
        "has_collisions_ignores_transient_filters",
        "HasCollisions counts a pair that only a transient declaration excludes.",
        HasCollisionsIgnoresTransientFilters,
        posed=True,
    ),
    Mutant(
        "pairwise_distances_ignore_transient_filters",
        "The pairwise signed distances report a pair that only a transient declaration excludes.",
        PairwiseDistancesIgnoreTransientFilters,
        posed=True,
    ),
)
