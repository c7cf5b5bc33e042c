"""Two answers of the pairwise signed distance that differ only in pairs at ``max_distance``.

``ComputeSignedDistancePairwiseClosestPoints(max_distance=m)`` reports a pair
iff its distance φ ≤ m (Drake's callback), unless FCL's broadphase skipped it
first: it prunes two subtrees whose bounding boxes are ≥ m apart, so a pair
whose boxes' gap ties φ (a separation along an axis) is reported at ``m = φ``
only where the tree meets the two geometries as siblings. Membership at the
boundary therefore rests on two things the tolerances do not cover: φ's last
bits (reimpl's φ is 1-4 ulps from pydrake's for spheres under nested rotated
frames, measured on pydrake 1.51.1) and the broadphase tree's shape (reimpl's
is built differently). The known divergences ``pairwise-prunes-ties-at-max-distance``
and ``sphere-distance-last-bits`` set such answers aside with this rule
(``boundary_pairs`` in a step pattern):

    the pairs present in one answer and not the other are non-empty, each has
    |φ − m| ≤ its shape pair's distance tolerance (``_tolerances``), and the
    pairs in both answers agree as ``compare.value_differences`` says.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from conformance._tolerances import tolerance
from conformance.compare import value_differences
from conformance.protocol import Command, Result

__all__ = ["PAIRWISE", "differs_only_at_max_distance"]

PAIRWISE = "compute_signed_distance_pairwise_closest_points"


def _records(result: Result | None) -> dict[tuple[str, ...], Mapping[str, Any]] | None:
    """The answer's records by pair, or None if it is not a list of records."""
    if result is None or result.error is not None or not isinstance(result.value, list):
        return None
    records = {}
    for record in result.value:
        if not isinstance(record, Mapping) or not isinstance(record.get("pair"), list):
            return None
        records[tuple(map(str, record["pair"]))] = record
    return records


def _at_boundary(record: Mapping[str, Any], max_distance: float) -> bool:
    """φ lies within its shape pair's distance tolerance of ``max_distance``."""
    shapes, phi = record.get("shapes"), record.get("distance")
    if not isinstance(shapes, list) or len(shapes) != 2 or not isinstance(phi, float):
        return False
    return abs(phi - max_distance) <= tolerance(*map(str, shapes)).distance


def differs_only_at_max_distance(
    command: Command, reference: Result | None, backend: Result | None
) -> bool:
    """The rule of the module doc, for a pairwise query with a finite ``max_distance``."""
    max_distance = command.args.get("max_distance")
    if command.op != PAIRWISE or not isinstance(max_distance, int | float):
        return False
    if not math.isfinite(max_distance):
        return False
    ours, theirs = _records(reference), _records(backend)
    if ours is None or theirs is None:
        return False
    alone = [ours[p] for p in ours.keys() - theirs.keys()]
    alone += [theirs[p] for p in theirs.keys() - ours.keys()]
    if not alone or not all(_at_boundary(r, float(max_distance)) for r in alone):
        return False
    common = sorted(ours.keys() & theirs.keys())
    return not value_differences(PAIRWISE, [ours[p] for p in common], [theirs[p] for p in common])
