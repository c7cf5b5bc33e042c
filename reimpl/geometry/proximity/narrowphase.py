"""The narrowphase: which computation answers a pair of geometries, in Drake's labelling.

Drake counterpart: drake/geometry/proximity/penetration_as_point_pair_callback.cc,
distance_to_shape_callback.cc and collisions_exist_callback.cc. Per pair (A, B)
with ``id_A < id_B`` (Drake orders the pair before computing it):

* Sphere–{Sphere, Box, Cylinder, Capsule, HalfSpace}: closed forms through the
  signed distance φ_B(Ao) from the sphere's centre Ao to B, its gradient ∇φ_B
  and nearest point N (``distance_to_point``). Penetration ``depth = r_A − φ_B(Ao)``
  (reported when ``depth ≥ 0``), ``p_WCb = X_WB · p_BN``, ``nhat_BA_W = ∇φ_B``,
  ``p_WCa = p_WA + r_A·(−nhat_BA_W)``; signed distance ``φ = φ_B(Ao) − r_A``,
  ``p_ACa = −r_A · R_AW · ∇φ_B``, ``p_BCb = p_BN``.
* Every other penetration: FCL's single contact (position c, normal n from A to
  B, depth d > ε): ``nhat_BA_W = −n``, ``p_WCa = c − d/2 · nhat_BA_W``,
  ``p_WCb = c + d/2 · nhat_BA_W``. FCL answers Box–Box and X–HalfSpace in closed
  form (python-fcl's own; a convex hull against a half space: its first deepest
  vertex); the rest is libccd's MPR, which Drake runs at
  ``gjk_tolerance = 2e-12`` while python-fcl cannot set it (1e-6), so MPR is
  reimplemented (``mpr``) on FCL's support functions.
  N.B. For Sphere–Ellipsoid and Sphere–Convex with the other's id lower, Drake
  re-labels the result after FCL's, so ``id_A`` is the sphere's, the larger
  (measured). A Mesh or Convex is FCL's ``Convex``, its convex hull.
* HasCollisions: FCL's boolean test for its closed-form pairs (and any HalfSpace
  pair), MPR's intersection test at ``gjk_tolerance`` for the rest.
* Every other signed distance: python-fcl's GJK/EPA signed distance (bit-equal
  to pydrake 1.51.1's, measured), ``nhat_BA_W = (p_WCa − p_WCb) / φ``; when
  ``|φ| < 1e-14``, Drake's touching rules (``distance_to_shape_touching``) or NaN.
* HalfSpace–HalfSpace penetration, and signed distance between a HalfSpace and
  anything but a Sphere, raise Drake's messages.
* A query point Q (ComputeSignedDistanceToPoint, ``point_signed_distance``):
  Drake's closed forms for a sphere, box, cylinder, capsule and half space; an
  ellipsoid through FCL (GJK/EPA against a sphere of radius 0 at Q, tolerance
  1e-6), its gradient the ellipsoid's normal at N, ``normalized(N ⊘ (a², b², c²))``;
  a Mesh or Convex through its distance surface (``distance_to_mesh``); a Mesh
  with none (a ``.gltf``) is not reported.

FCL itself stays with the engine: a geometry here (``PosedGeometry``) hands over
FCL's answers for itself and another.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol, Self

import numpy as np

from reimpl._release import release
from reimpl.geometry.identifier import GeometryId
from reimpl.geometry.proximity.distance_to_mesh import MeshBoundary
from reimpl.geometry.proximity.distance_to_point import PointDistance, distance_to_point
from reimpl.geometry.proximity.distance_to_shape_touching import PosedShape, touching_gradient
from reimpl.geometry.proximity.mpr import Convex, Mpr
from reimpl.geometry.proximity.transforms import (
    EPS,
    Array,
    Vec,
    add,
    rot,
    rot_t,
    scale,
    sub,
    unit,
)

if TYPE_CHECKING:
    from reimpl.geometry._convex_hull import Hull

__all__ = [
    "DISTANCE_UNSUPPORTED",
    "PairResult",
    "PosedGeometry",
    "distance_supported",
    "pair_collides",
    "pair_penetration",
    "pair_signed_distance",
    "point_signed_distance",
]


class PosedGeometry(PosedShape, Protocol):
    """A posed proximity geometry as the narrowphase reads it: its kind, measures and
    X_WG, its id, and FCL's answers for it and another geometry."""

    @property
    def id(self) -> GeometryId: ...

    @property
    def hull(self) -> Hull | None:
        """A Convex's hull (None for the other shapes)."""

    def fcl_contact(self, other: Self) -> tuple[float, Vec, Vec] | None:
        """FCL's single contact (depth, normal from self to other, position), or None."""

    def fcl_collides(self, other: Self) -> bool:
        """FCL's boolean collision test."""

    def fcl_signed_distance(self, other: Self) -> tuple[float, Vec, Vec]:
        """FCL's signed distance φ and its witnesses p_WCa (on self), p_WCb (on other)."""

    def fcl_point_distance(self, p_WQ: Vec) -> tuple[float, Vec]:
        """FCL's signed distance to a sphere of radius 0 at Q, and the witness p_WN on self."""

    def boundary(self) -> MeshBoundary | None:
        """A Mesh's or Convex's distance surface (None: not reported)."""


class PairResult:
    """A narrowphase answer in Drake's labelling: A and B, a value, two points and a normal.

    For a penetration ``value`` is the depth and the rows of ``vectors`` are
    p_WCa, p_WCb, nhat_BA_W; for a signed distance, φ and p_ACa, p_BCb, nhat_BA_W.
    """

    __slots__ = ("id_A", "id_B", "value", "vectors")

    def __init__(self, id_A: GeometryId, id_B: GeometryId, value: float, vectors: Array):
        self.id_A, self.id_B, self.value, self.vectors = id_A, id_B, value, vectors

    @classmethod
    def of(
        cls, ids: tuple[GeometryId, GeometryId], value: float, points: tuple[Vec, Vec], nhat: Vec
    ) -> PairResult:
        return cls(ids[0], ids[1], value, np.array((points[0], points[1], nhat), dtype=float))

    def swapped(self) -> PairResult:
        """(A, B) → (B, A): the points trade places and ``nhat_AB_W = −nhat_BA_W``."""
        vectors = self.vectors[[1, 0, 2]]
        vectors[2] = -vectors[2]
        return PairResult(self.id_B, self.id_A, self.value, vectors)


#: An unsupported pair's error; up to 1.15 it ends at "double" (unsupported-pair-wording-
#: since-1.16: measured on pydrake 1.15.0 and 1.16.0, both queries).
_SEE_DOCS = (
    ". See the documentation for QueryObject::{}() for the full status of supported geometries."
    if release.has("unsupported-pair-wording-since-1.16")
    else ""
)
_PENETRATION_UNSUPPORTED = (
    "Penetration queries between shapes '{}' and '{}' are not supported for scalar type double"
    + _SEE_DOCS.replace("{}", "ComputePointPairPenetration")
)
DISTANCE_UNSUPPORTED = (
    "Signed distance queries between shapes '{}' and '{}' are not supported for scalar type "
    "double" + _SEE_DOCS.replace("{}", "ComputeSignedDistancePairwiseClosestPoints")
)

#: Sphere–X pairs Drake answers in closed form (X the other shape).
_CLOSED_FORM = frozenset({"Sphere", "Box", "Cylinder", "Capsule", "Halfspace"})
#: Penetration pairs FCL answers in closed form (no MPR, no tolerance), and polytope pairs,
#: where libccd's MPR ends on repeated support vertices, not at its tolerance: python-fcl's
#: answer is bit-equal to pydrake 1.51.1's for box-convex and convex-convex (measured on 153
#: penetrating random poses of a generated 8-vertex hull, given Drake's vertex order).
_FCL_CLOSED = frozenset(
    {
        ("Box", "Box"),
        ("Box", "Convex"),
        ("Convex", "Box"),
        ("Convex", "Convex"),
        *((k, "Halfspace") for k in ("Box", "Capsule", "Cylinder", "Ellipsoid", "Convex")),
        *(("Halfspace", k) for k in ("Box", "Capsule", "Cylinder", "Ellipsoid", "Convex")),
    }
)
#: Boolean collision pairs FCL answers in closed form (with any HalfSpace pair).
_FCL_BOOLEAN = frozenset(
    frozenset(pair)
    for pair in (
        ("Sphere", "Sphere"),
        ("Sphere", "Box"),
        ("Sphere", "Capsule"),
        ("Sphere", "Cylinder"),
        ("Box", "Box"),
    )
)
#: Drake's gjk_tolerance for penetration and HasCollisions.
_GJK_TOLERANCE = 2e-12


def distance_supported(kind_A: str, kind_B: str) -> bool:
    """Signed distance: anything but a HalfSpace with a shape other than a Sphere."""
    return (kind_A != "Halfspace" or kind_B == "Sphere") and (
        kind_B != "Halfspace" or kind_A == "Sphere"
    )


def pair_penetration(a: PosedGeometry, b: PosedGeometry) -> PairResult | None:
    """A's and B's penetration (A's id lower), as Drake computes it; None if separated."""
    if a.kind == "Halfspace" and b.kind == "Halfspace":
        raise RuntimeError(_PENETRATION_UNSUPPORTED.format("Halfspace", "Halfspace"))
    a_sphere = a.kind == "Sphere"
    if (a_sphere or b.kind == "Sphere") and (b.kind if a_sphere else a.kind) in _CLOSED_FORM:
        s, o = (a, b) if a_sphere else (b, a)
        r = s.m[0]
        near = distance_to_point(o.kind, o.m, o.pose, s.pose.p)
        depth = r - near.distance
        if depth < 0:
            return None
        result = PairResult.of(
            (s.id, o.id),
            depth,
            (sub(s.pose.p, scale(near.grad_W, r)), o.pose.apply(near.p_GN)),
            near.grad_W,
        )
        return result if a_sphere else result.swapped()
    contact = _contact(a, b)
    if contact is None or contact[0] <= EPS:
        return None
    depth, normal, pos = contact
    nhat = scale(normal, -1.0)
    result = PairResult.of(
        (a.id, b.id),
        depth,
        (sub(pos, scale(nhat, 0.5 * depth)), add(pos, scale(nhat, 0.5 * depth))),
        nhat,
    )
    # N.B. Drake's sphere–ellipsoid path re-labels FCL's (A, B) answer when A is
    # not the sphere, so the larger id ends up as id_A (measured on 1.51.1).
    return result.swapped() if b.kind == "Sphere" and not a_sphere else result


def _contact(a: PosedGeometry, b: PosedGeometry) -> tuple[float, Vec, Vec] | None:
    """FCL's single contact (depth, normal from A to B, position) for a non-closed-form pair."""
    if (a.kind, b.kind) in _FCL_CLOSED:
        return a.fcl_contact(b)
    return _mpr(a, b).penetration()


def pair_collides(a: PosedGeometry, b: PosedGeometry) -> bool:
    """FCL's boolean test at Drake's tolerance (HasCollisions): FCL's closed forms, and
    MPR at ``gjk_tolerance = 2e-12`` for the rest."""
    if frozenset((a.kind, b.kind)) in _FCL_BOOLEAN or "Halfspace" in (a.kind, b.kind):
        return a.fcl_collides(b)
    return _mpr(a, b).intersect()


def _mpr(a: PosedGeometry, b: PosedGeometry) -> Mpr:
    """libccd's MPR on A and B at Drake's ``gjk_tolerance``."""
    return Mpr(
        Convex(a.kind, a.m, a.pose, a.hull), Convex(b.kind, b.m, b.pose, b.hull), _GJK_TOLERANCE
    )


def pair_signed_distance(a: PosedGeometry, b: PosedGeometry) -> PairResult:
    """φ(A, B) with witnesses (A's id lower), as Drake computes it."""
    a_sphere = a.kind == "Sphere"
    if (a_sphere or b.kind == "Sphere") and (b.kind if a_sphere else a.kind) in _CLOSED_FORM:
        s, o = (a, b) if a_sphere else (b, a)
        r = s.m[0]
        near = distance_to_point(o.kind, o.m, o.pose, s.pose.p)
        result = PairResult.of(
            (s.id, o.id),
            near.distance - r,
            (scale(rot_t(s.pose.R, near.grad_W), -r), near.p_GN),
            near.grad_W,
        )
        return result if a_sphere else result.swapped()
    distance, p_WCa, p_WCb = a.fcl_signed_distance(b)
    p_ACa = a.pose.apply_inverse(p_WCa)
    p_BCb = b.pose.apply_inverse(p_WCb)
    if abs(distance) < 1e-14:
        nhat = touching_gradient(a, b, p_ACa, p_BCb)
    else:
        diff = sub(p_WCa, p_WCb)
        nhat = (diff[0] / distance, diff[1] / distance, diff[2] / distance)
    return PairResult.of((a.id, b.id), distance, (p_ACa, p_BCb), nhat)


#: Shapes whose distance to a point is Drake's closed form (``distance_to_point``).
_POINT_CLOSED_FORM = frozenset({"Sphere", "Box", "Cylinder", "Capsule", "Halfspace"})


def point_signed_distance(g: PosedGeometry, p_WQ: Vec) -> PointDistance | None:
    """φ_G(Q), p_GN and ∇φ in W, as Drake computes them; None for a Mesh Drake skips (and,
    before release fact mesh-point-distance-since-1.36, for every Mesh and Convex)."""
    if g.kind in _POINT_CLOSED_FORM:
        return distance_to_point(g.kind, g.m, g.pose, p_WQ)
    if g.kind == "Ellipsoid":
        distance, p_WN = g.fcl_point_distance(p_WQ)
        p_GN = g.pose.apply_inverse(p_WN)
        a, b, c = g.m
        grad_G = unit((p_GN[0] / (a * a), p_GN[1] / (b * b), p_GN[2] / (c * c)))
        return PointDistance(p_GN, distance, rot(g.pose.R, grad_G))
    boundary = g.boundary() if release.has("mesh-point-distance-since-1.36") else None
    if boundary is None:  # up to 1.35, Drake leaves every Mesh and Convex out
        return None
    found = boundary.signed_distance(np.array(g.pose.apply_inverse(p_WQ)))
    p_GN = (float(found.p_MN[0]), float(found.p_MN[1]), float(found.p_MN[2]))
    gradient = (float(found.gradient[0]), float(found.gradient[1]), float(found.gradient[2]))
    return PointDistance(p_GN, found.distance, rot(g.pose.R, gradient))
