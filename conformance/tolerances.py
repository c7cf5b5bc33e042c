"""How closely two implementations' proximity numbers must agree, per unordered shape pair.

Pair sets (which pairs penetrate, which are candidates, HasCollisions) are
compared exactly; the numbers of a query record (``grammar.queries``) are
compared here, each against the row of its record's unordered shape pair:

- ``distance``: ``|d_ref − d_other|`` of ``depth`` (penetration) or ``distance``
  (signed distance);
- ``witness``: ``‖p_ref − p_other‖`` of each witness point (``p_WCa``,
  ``p_WCb``, ``p_ACa``, ``p_BCb``);
- ``normal``: ``‖n_ref − n_other‖`` of ``nhat_BA_W`` (about the angle between
  them, in radians, when small).

``NOT_COMPARED`` (infinity) marks a number that is not well defined for the
pair: two correct implementations may pick different values (the reason
says why). Poses (``x_wg``, ``x_wf``) are products of transforms, compared
within ``POSE_TOLERANCE`` per entry of ``xyz`` and of the rotation matrix.

The values are measured (docs/queries.md: the corpus and random posed
scenes, reimpl against pydrake 1.51.1, and pydrake 1.58 against 1.51.1).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

__all__ = [
    "DEFAULT_TOLERANCE",
    "NOT_COMPARED",
    "POSE_TOLERANCE",
    "TOLERANCES",
    "Tolerance",
    "shape_pair",
    "tolerance",
]

#: A tolerance that accepts any value: the number is not well defined for the pair.
NOT_COMPARED = math.inf

#: Per entry of a pose's ``xyz`` and rotation matrix (composition of a few transforms).
POSE_TOLERANCE = 1e-12


@dataclass(frozen=True)
class Tolerance:
    """Absolute tolerances of one shape pair's numbers (see the module doc), and why."""

    distance: float
    witness: float
    normal: float
    reason: str


def shape_pair(a: str, b: str) -> frozenset[str]:
    """The unordered pair ``{a, b}`` (a set of one for two shapes of one type)."""
    return frozenset((a, b))


_CLOSED = 1e-9
_ITERATIVE = 1e-6

_CLOSED_FORM = "closed form (Drake's and FCL's primitive algorithms)"
_GJK = "GJK/EPA: iterative, converges to about 1e-6"

#: The unordered shape pair → its tolerances. Every pair of the six shapes has a row.
TOLERANCES: Mapping[frozenset[str], Tolerance] = {
    shape_pair("sphere", "sphere"): Tolerance(_CLOSED, _CLOSED, _CLOSED, _CLOSED_FORM),
    shape_pair("sphere", "box"): Tolerance(_CLOSED, _CLOSED, _CLOSED, _CLOSED_FORM),
    shape_pair("sphere", "cylinder"): Tolerance(_CLOSED, _CLOSED, _CLOSED, _CLOSED_FORM),
    shape_pair("sphere", "capsule"): Tolerance(_CLOSED, _CLOSED, _CLOSED, _CLOSED_FORM),
    shape_pair("sphere", "halfspace"): Tolerance(_CLOSED, _CLOSED, _CLOSED, _CLOSED_FORM),
    shape_pair("sphere", "ellipsoid"): Tolerance(_ITERATIVE, _ITERATIVE, _ITERATIVE, _GJK),
    shape_pair("box", "box"): Tolerance(_CLOSED, _CLOSED, _CLOSED, _CLOSED_FORM),
    shape_pair("box", "halfspace"): Tolerance(_CLOSED, _CLOSED, _CLOSED, _CLOSED_FORM),
    shape_pair("box", "cylinder"): Tolerance(_ITERATIVE, _ITERATIVE, _ITERATIVE, _GJK),
    shape_pair("box", "capsule"): Tolerance(_ITERATIVE, _ITERATIVE, _ITERATIVE, _GJK),
    shape_pair("box", "ellipsoid"): Tolerance(_ITERATIVE, _ITERATIVE, _ITERATIVE, _GJK),
    shape_pair("capsule", "capsule"): Tolerance(_CLOSED, _CLOSED, _CLOSED, _CLOSED_FORM),
    shape_pair("capsule", "halfspace"): Tolerance(_CLOSED, _CLOSED, _CLOSED, _CLOSED_FORM),
    shape_pair("capsule", "cylinder"): Tolerance(_ITERATIVE, _ITERATIVE, _ITERATIVE, _GJK),
    shape_pair("capsule", "ellipsoid"): Tolerance(_ITERATIVE, _ITERATIVE, _ITERATIVE, _GJK),
    shape_pair("cylinder", "cylinder"): Tolerance(_ITERATIVE, _ITERATIVE, _ITERATIVE, _GJK),
    shape_pair("cylinder", "halfspace"): Tolerance(_CLOSED, _CLOSED, _CLOSED, _CLOSED_FORM),
    shape_pair("cylinder", "ellipsoid"): Tolerance(_ITERATIVE, _ITERATIVE, _ITERATIVE, _GJK),
    shape_pair("ellipsoid", "ellipsoid"): Tolerance(_ITERATIVE, _ITERATIVE, _ITERATIVE, _GJK),
    shape_pair("ellipsoid", "halfspace"): Tolerance(_ITERATIVE, _ITERATIVE, _ITERATIVE, _GJK),
    shape_pair("halfspace", "halfspace"): Tolerance(
        _CLOSED, _CLOSED, _CLOSED, "no query answers it (Drake raises)"
    ),
}

#: Shapes the table lacks (meshes, convex hulls): the loosest row.
DEFAULT_TOLERANCE = Tolerance(_ITERATIVE, _ITERATIVE, _ITERATIVE, "a shape the table lacks")


def tolerance(a: str, b: str) -> Tolerance:
    """The row of the unordered shape pair ``{a, b}`` (``DEFAULT_TOLERANCE`` if none)."""
    return TOLERANCES.get(shape_pair(a, b), DEFAULT_TOLERANCE)
