"""How closely two implementations' proximity numbers must agree, per unordered shape pair.

Pair sets (which pairs penetrate, which are candidates, HasCollisions) are
compared exactly; the numbers of a query record (``grammar.queries``) are
compared here, each against the row of its record's unordered shape pair.
With ``d`` the record's depth (penetration) or signed distance:

- ``distance``: ``|d_ref − d_other|``;
- ``witness``: ``‖p_ref − p_other‖`` of each witness point (``p_WCa``,
  ``p_WCb``, ``p_ACa``, ``p_BCb``);
- ``normal``: ``‖d_ref·n_ref − d_other·n_other‖`` of ``nhat_BA_W``: the normal
  is compared through the separation vector ``d·n``, a length;
- ``touching``: where ``|d_ref| < touching`` the witness points and the
  normal are not compared, only ``d``.

Why the separation vector: near contact the normal is ill-conditioned for
the iterative algorithms (pydrake and reimpl can give opposite normals a
hair's breadth from contact, while ``‖Δn‖·|d|`` stays small), whereas ``d·n``
stays a small, well-defined vector; far from contact it compares the normal
to ``tolerance / |d|``. Why ``touching``: below it the contact is a touch
within the solver's precision, and its witness points are not unique along
flat or straight features (a capsule lying along a cylinder a touch apart
gets witness points centimetres apart), nor is the normal (pydrake 1.51.1
reports NaN for a box exactly touching a cylinder, where reimpl, a rounding
error inside, reports one). Elsewhere a NaN agrees only with a NaN.

Poses (``x_wg``, ``x_wf``) are products of transforms, compared within
``POSE_TOLERANCE`` per entry of ``xyz`` and of the rotation matrix.

No measured number is written here: the reports below hold them, each written
by a committed command, and docs/queries.md renders this table and them.

- docs/reports/tolerances.json (``benchmarks/measure_tolerances.py``): the five
  shapes other than the half space, near-touching posed pairs (rows ``CLOSED``
  and ``ITERATIVE``; no study measures a shape against a half space, which the
  posed fuzz campaigns compare against ``CLOSED``);
- docs/reports/tolerances_hull.json (``benchmarks/measure_hull_tolerances.py``):
  a Mesh or Convex against each shape, another hull and a half space,
  near-touching (rows ``HULL`` and ``HULL_HALFSPACE``);
- docs/reports/mesh_script.json (``benchmarks/measure_mesh_script.py``): Drake's
  jaco arm's collision meshes beside a box and a cylinder, and the signed
  distance to points (rows ``HULL``, ``CLOSED`` for ``point``).

The rows were set from earlier studies; where a report finds records outside
a row, docs/queries.md states it as an open finding about the row.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

__all__ = [
    "CLOSED",
    "DEFAULT_TOLERANCE",
    "HULL",
    "HULL_HALFSPACE",
    "ITERATIVE",
    "POSE_TOLERANCE",
    "TOLERANCES",
    "Tolerance",
    "shape_pair",
    "tolerance",
]

#: Per entry of a pose's ``xyz`` and rotation matrix (composition of a few transforms).
POSE_TOLERANCE = 1e-12


@dataclass(frozen=True)
class Tolerance:
    """Absolute tolerances (m) of one shape pair's numbers (see the module doc), and why."""

    distance: float
    witness: float
    normal: float
    touching: float
    reason: str


def shape_pair(a: str, b: str) -> frozenset[str]:
    """The unordered pair ``{a, b}`` (a set of one for two shapes of one type)."""
    return frozenset((a, b))


#: Drake's closed forms (sphere against sphere, box, cylinder, capsule, half space), which
#: reimpl writes as Drake does, and FCL's analytic box-box and X-halfspace code, which
#: python-fcl shares: the two differ by rounding. Measured in docs/reports/tolerances.json.
CLOSED = Tolerance(
    1e-12,
    1e-12,
    1e-12,
    0.0,
    "closed form or FCL's analytic code in both: they differ by rounding "
    "(docs/reports/tolerances.json)",
)

#: GJK/EPA signed distance and libccd MPR penetration, whose answers end where each
#: solver's tolerance (Drake gives FCL its own) stops them, so the two implementations'
#: answers differ by up to about that tolerance. Measured in docs/reports/tolerances.json.
ITERATIVE = Tolerance(
    5e-5,
    1e-5,
    5e-5,
    1e-5,
    "GJK/EPA and MPR stop at the solver's tolerance (docs/reports/tolerances.json)",
)

#: A Mesh or Convex (its convex hull, FCL's Convex) against anything but a half space.
#: reimpl's hull has pydrake's vertices and polygons but numbers the vertices in file order:
#: Drake's are in Qhull's internal vertex list, which scipy does not expose. Where MPR's
#: support search meets (near-)ties, the order decides which vertex it takes, and MPR's
#: penetration depth (an estimate along its search, not the minimum) follows another path;
#: GJK/EPA's signed distance stops at the solver's tolerance as for ``ITERATIVE``.
#: Measured in docs/reports/tolerances_hull.json and docs/reports/mesh_script.json.
HULL = Tolerance(
    1e-2,
    2e-2,
    4e-2,
    1e-5,
    "a convex hull: the same hull, its vertices numbered otherwise, so MPR may take another "
    "path (docs/reports/tolerances_hull.json, docs/reports/mesh_script.json)",
)
#: A Mesh or Convex against a half space: FCL's closed form (the hull's deepest vertex) in
#: both, so the depth and normal are the same; the deepest vertex among exact ties (a hull
#: face parallel to the plane) is the first in each implementation's numbering, so the
#: witness point may be another vertex of that face. Measured in
#: docs/reports/tolerances_hull.json.
HULL_HALFSPACE = Tolerance(
    1e-12,
    2e-2,
    1e-12,
    0.0,
    "FCL's convex-halfspace closed form in both; the contact point of a face parallel to the "
    "plane is a vertex of that face (docs/reports/tolerances_hull.json)",
)

_ITERATIVE_PAIRS = (
    ("sphere", "ellipsoid"),
    ("box", "cylinder"),
    ("box", "capsule"),
    ("box", "ellipsoid"),
    ("capsule", "capsule"),
    ("capsule", "cylinder"),
    ("capsule", "ellipsoid"),
    ("cylinder", "cylinder"),
    ("cylinder", "ellipsoid"),
    ("ellipsoid", "ellipsoid"),
)
_SHAPES = ("sphere", "box", "cylinder", "capsule", "ellipsoid", "halfspace")

#: The unordered shape pair → its tolerances. Every pair of the six shapes has a row: the
#: iterative pairs ``ITERATIVE``, the others (sphere with anything but an ellipsoid, box-box,
#: anything with a half space) ``CLOSED``; a mesh or convex hull against anything ``HULL``,
#: against a half space ``HULL_HALFSPACE``. A shape against ``point`` (the signed distance
#: to a point): ``CLOSED``, the ellipsoid's through FCL in both, the meshes' through the
#: same surface (measured for a Mesh, a box and a cylinder in docs/reports/mesh_script.json).
TOLERANCES: Mapping[frozenset[str], Tolerance] = {
    **{
        shape_pair(a, b): ITERATIVE
        if (a, b) in _ITERATIVE_PAIRS or (b, a) in _ITERATIVE_PAIRS
        else CLOSED
        for i, a in enumerate(_SHAPES)
        for b in _SHAPES[i:]
    },
    **{
        shape_pair(hull, other): HULL_HALFSPACE if other == "halfspace" else HULL
        for hull in ("mesh", "convex")
        for other in (*_SHAPES, "mesh", "convex")
    },
    **{shape_pair(shape, "point"): CLOSED for shape in (*_SHAPES, "mesh", "convex")},
}

#: Shapes the table lacks (meshes, convex hulls): the loosest row.
DEFAULT_TOLERANCE = Tolerance(
    ITERATIVE.distance,
    ITERATIVE.witness,
    ITERATIVE.normal,
    ITERATIVE.touching,
    "a shape the table lacks",
)


def tolerance(a: str, b: str) -> Tolerance:
    """The row of the unordered shape pair ``{a, b}`` (``DEFAULT_TOLERANCE`` if none)."""
    return TOLERANCES.get(shape_pair(a, b), DEFAULT_TOLERANCE)
