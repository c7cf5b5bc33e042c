"""Hypothesis strategies for collision-filter scenarios (public API).

Every value is in the scenario grammar (``scenarios/README.md``): names, not
ids. Geometry sets are ``{"geometries": [...], "frames": [...]}``,
declarations ``{"statements": [...]}``, commands ``conformance.protocol.Command``.
So anything drawn here can be sent to any backend, or written to a scenario
file as it is.

Each strategy takes keyword-only options. Wherever a strategy needs names it
accepts either a sequence of names or a strategy of names, such as a stateful
``Bundle``:

>>> from hypothesis import strategies as st
>>> sets = geometry_sets(geometries=["a", "b"], frames=["f"])
>>> decls = declarations(geometries=st.sampled_from(["a", "b"]), frames=["world"])

Special references are drawn rarely and shrink away. They are ``@unknown`` (an
id never issued), ``@foreign`` (an id from another SceneGraph), and ``world``
(the world frame: every anchored proximity geometry). A removed geometry's name
is an ordinary name whose id has gone stale.

Names are cheap to draw. A name is a *pick*, one byte read against a list
of names by ``pick``, and the picks a value needs are drawn together as one
fixed-size ``bytes`` choice (``picks(n)``): Hypothesis draws the bytes
uniformly and shrinks each towards 0. ``set_templates`` and
``declaration_templates`` draw whole sets and declarations as one such choice
each, to be resolved later against lists that may have grown since (a state
machine's bundles do; ``conformance._fuzz.lockstep`` uses them so).
``geometry_sets`` and ``declarations`` are those templates resolved at once.

Posed scenes (``fuzz --poses``) add shapes, poses and near-touching offsets,
drawn the same way: ``shape_of``, ``pose_of`` and ``Touch.decode`` read a
few bytes each, and ``shapes``, ``poses`` and ``touches`` are those bytes
as strategies. A ``SHAPE`` and a ``POSE`` are the grammar's JSON values
(``{"type": "box", "width": w, "depth": d, "height": h}``,
``{"xyz": [x, y, z], "rpy": [r, p, y]}``). ``touching_position`` places one
shape at a signed gap from another along a direction, from the shapes'
support points; see its doc for why the gap is then the signed distance.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field, replace
from functools import cache, partial
from typing import Any

from hypothesis import strategies as st

from conformance._corpus_root import corpus_root
from conformance.protocol import Command

__all__ = [
    "FOREIGN",
    "GAP_SCALES",
    "HALFSPACE_SHARE",
    "MESH_FILES",
    "PICK_RANGE",
    "POSED_HALFSPACE_SHARE",
    "POSE_BYTES",
    "ROLES",
    "SHAPE_BYTES",
    "SHAPE_TYPES",
    "STATEMENT_OPS",
    "TOUCH_BYTES",
    "UNKNOWN",
    "WORLD",
    "DeclarationTemplate",
    "GeometrySpec",
    "Matrix",
    "Names",
    "Picker",
    "Scene",
    "SetTemplate",
    "Touch",
    "Transform",
    "Vector",
    "declaration_templates",
    "declarations",
    "geometry_sets",
    "pick",
    "picks",
    "point_of",
    "points",
    "pose_of",
    "poses",
    "role_list",
    "roles",
    "rotation",
    "scenes",
    "set_spec",
    "set_templates",
    "shape_of",
    "shapes",
    "statements",
    "support",
    "touches",
    "touching_position",
]

WORLD = "world"
UNKNOWN = "@unknown"
FOREIGN = "@foreign"
#: The roles a geometry can be registered with (``proximity`` decides C).
ROLES = ("proximity", "illustration", "perception")
STATEMENT_OPS = ("exclude_within", "allow_within", "exclude_between", "allow_between")

#: Names to draw from: a sequence, or a strategy (e.g. a stateful Bundle).
Names = Sequence[str] | st.SearchStrategy[str]


#: Resolves a pick (0-255) to a name, or None for "left out".
Picker = Callable[[int], str | None]

#: A pick is one byte.
PICK_RANGE = 256
#: Picks from here up stand for a rare name when there are any (1 in 8).
_RARE_FROM = PICK_RANGE - PICK_RANGE // 8


@cache
def picks(count: int = 1) -> st.SearchStrategy[bytes]:
    """``count`` picks as one choice: ``bytes`` of that length (each shrinks towards 0)."""
    return st.binary(min_size=count, max_size=count)


def pick(
    names: Sequence[str], index: int, *, rare: Sequence[str] = (), none_below: int = 0
) -> str | None:
    """The name that a pick (``index``, 0-255) stands for in ``names``.

    ==========================================  =============================
    ``index < none_below``                      None (an optional name left
                                                out; shrinks to this)
    ``index ≥ 224`` and ``rare``, or no names   ``rare[index % len(rare)]``
                                                (None if no ``rare`` either)
    otherwise                                   ``names[index % len(names)]``
    ==========================================  =============================
    """
    if index < none_below:
        return None
    if rare and (index >= _RARE_FROM or not names):
        return rare[index % len(rare)]
    return names[index % len(names)] if names else None


def _picker(draw: st.DrawFn, names: Names, rare: Sequence[str]) -> Picker:
    """A sequence is read by index; a strategy is drawn from (the index is ignored)."""
    if isinstance(names, st.SearchStrategy):
        strategy = _rarely(names, tuple(rare))
        return lambda index: draw(strategy)
    listed = list(names)
    return lambda index: pick(listed, index, rare=rare)


@cache
def _rarely(common: st.SearchStrategy[str], rare: tuple[str, ...]) -> st.SearchStrategy[str]:
    """``common``, or now and then one of ``rare`` (shrinks to ``common``)."""
    if not rare:
        return common
    return st.tuples(st.integers(min_value=0, max_value=7), common, st.sampled_from(rare)).map(
        lambda t: t[2] if t[0] == 7 else t[1]
    )


def _unique(names: Iterable[str | None]) -> list[str]:
    return list(dict.fromkeys(name for name in names if name is not None))


#: Role codes (0-15) by ``roles(proximity=...)``: proximity below 12, 3 codes in 4.
_ROLE_CODES = {None: (0, 15), True: (0, 11), False: (12, 15)}


def role_list(code: int) -> list[str]:
    """The roles of a role code, taken mod 16: 0 is proximity alone, 12 no role at all.

    Proximity is ``code % 16 < 12``; bit 0 adds illustration, bit 1 perception.
    Codes shrink towards 0, so towards the role that decides C.
    """
    code %= 16
    chosen = (code < 12, bool(code & 1), bool(code & 2))
    return [role for role, on in zip(ROLES, chosen, strict=True) if on]


@cache
def _role_codes(proximity: bool | None) -> st.SearchStrategy[int]:
    low, high = _ROLE_CODES[proximity]
    return st.integers(min_value=low, max_value=high)


def roles(*, proximity: bool | None = None) -> st.SearchStrategy[list[str]]:
    """A list of distinct roles; ``proximity`` forces the role in (True) or out (False).

    One choice (a role code, ``role_list``); proximity comes three times in four.
    """
    return _role_codes(proximity).map(role_list)


# ------------------------------------------------------- shapes, poses, touches
#: The shapes of the grammar's SHAPE, in Drake's order of ``shape_specification.h``, then the
#: mesh files (``MESH_FILES``) as a Mesh and as a Convex.
SHAPE_TYPES = ("sphere", "box", "cylinder", "capsule", "ellipsoid", "halfspace", "mesh", "convex")
#: The bounded shapes a drawn byte picks among (the half space is drawn apart).
_DRAWN_TYPES = ("sphere", "box", "cylinder", "capsule", "ellipsoid", "mesh", "convex")
#: The mesh files a drawn mesh or convex shape names (below the corpus folder): small
#: irregular hulls, generated so that no face is parallel to a coordinate plane or to another
#: face (a support point is then unique for the directions the queries meet), an .obj of 8
#: and one of 12 vertices and a .vtk of two tetrahedra; and a real robot's collision mesh,
#: Drake's iiwa link 7 polytope (drake_models, 64 vertices, 16 on each of its two faces
#: parallel to the xy plane: support ties, where the HULL tolerance row applies in full).
MESH_FILES = (
    "queries/meshes/poly8.obj",
    "queries/meshes/poly12.obj",
    "queries/meshes/two_tets.vtk",
    "real_models/drake_models/iiwa_description/meshes/iiwa14/collision/link_7_polytope.obj",
)
#: A drawn mesh's scale: 0.8 + byte % 5 / 10 (0.8 to 1.2).
_MESH_SCALES = 5

#: Bytes of a drawn shape: the type, then one per dimension.
SHAPE_BYTES = 4
#: Bytes of a drawn pose: x, y, z, then roll, pitch, yaw.
POSE_BYTES = 6
#: How often a drawn shape is a HalfSpace by default: one time in this many.
HALFSPACE_SHARE = 32
#: ... and in the posed fuzz campaign (``scenes(posed=True)``, ``operations``): never.
#:
#: N.B. pydrake crashes (SIGSEGV in FCL's AABB tree, seen under
#: ``ProximityEngine::AddDynamicGeometry`` and ``FinalizePoseUpdate``) once a few
#: HalfSpaces share its proximity engine with a few dozen other shapes, anchored
#: or on frames alike. Measured on pydrake 1.51.1, registration alone, random
#: spheres: 2 HalfSpaces among 16 proximity geometries crash 0 scenes of 12,
#: among 20 1 of 12, among 24 2 of 12, among 30 3 of 8; 3 HalfSpaces among 30
#: crash 7 of 8 (1.58.0: 7 of 8 too). A fuzz example grows to that size and a
#: crash ends the campaign, so HalfSpaces are left to the corpus's small cases
#: (``scenarios/queries``); set a share here to draw them anyway.
POSED_HALFSPACE_SHARE = 0


#: Dimensions in centimetres, inclusive: a radius (or semi-axis), a length.
_RADIUS = (5, 30)
_LENGTH = (10, 60)
#: Each shape's dimensions, as pydrake's constructors name them.
_DIMENSIONS: dict[str, tuple[tuple[str, tuple[int, int]], ...]] = {
    "sphere": (("radius", _RADIUS),),
    "box": (("width", _LENGTH), ("depth", _LENGTH), ("height", _LENGTH)),
    "cylinder": (("radius", _RADIUS), ("length", _LENGTH)),
    "capsule": (("radius", _RADIUS), ("length", _LENGTH)),
    "ellipsoid": (("a", _RADIUS), ("b", _RADIUS), ("c", _RADIUS)),
    "halfspace": (),
    "mesh": (),
    "convex": (),
}
#: A pose's steps: 5 mm (±0.64 m) and 0.025 rad (±3.2 rad). Dividing by a whole
#: number of steps keeps the values short in a written case (0.575, not 0.5750000000000001).
_STEPS_PER_METRE = 200
_STEPS_PER_RADIAN = 40


def _centimetres(byte: int, bounds: tuple[int, int]) -> float:
    low, high = bounds
    return (low + byte % (high - low + 1)) / 100


def _signed(byte: int) -> int:
    """0, 1, -1, 2, -2, ... for bytes 0, 1, 2, 3, 4, ...: shrinks towards 0."""
    return (byte + 1) // 2 * (1 if byte & 1 else -1)


def shape_of(data: bytes, *, halfspace: int = HALFSPACE_SHARE) -> dict[str, Any]:
    """The SHAPE that ``SHAPE_BYTES`` bytes stand for.

    Byte 0 is the type: one of the five primitives, a mesh or a convex
    (``byte % 7``; 0, the sphere, is where it shrinks), or a HalfSpace one time
    in ``halfspace`` (its top bytes: from 248 up for 32; 0 for never). The
    next bytes are the dimensions in whole centimetres, smallest at 0: radii
    and semi-axes 0.05-0.30 m, lengths and box sides 0.10-0.60 m. Whole
    centimetres keep a written case readable (``"radius": 0.23``). A mesh or
    convex reads a file of ``MESH_FILES`` and a scale 0.8-1.2 instead.
    """
    head = data[0] if data else 0
    from_ = PICK_RANGE - PICK_RANGE // halfspace if halfspace else PICK_RANGE
    kind = "halfspace" if head >= from_ else _DRAWN_TYPES[head % len(_DRAWN_TYPES)]
    if kind in ("mesh", "convex"):
        file, scale = (data[1:3] + b"\0\0")[:2]
        return {
            "type": kind,
            "path": MESH_FILES[file % len(MESH_FILES)],
            "scale": 0.8 + (scale % _MESH_SCALES) / 10,
        }
    sizes = iter(data[1:])
    return {"type": kind} | {
        key: _centimetres(next(sizes, 0), bounds) for key, bounds in _DIMENSIONS[kind]
    }


def pose_of(data: bytes) -> dict[str, list[float]]:
    """The POSE that ``POSE_BYTES`` bytes stand for (all zero bytes: the identity, ``{}``).

    Each byte is a signed step (``0, 1, -1, 2, ...``): xyz in steps of
    5 mm (±0.64 m), rpy in steps of 0.025 rad (±3.2 rad, a whole turn). A
    part that is all zero is left out, as the grammar allows.
    """
    steps = [_signed(byte) for byte in data[:POSE_BYTES].ljust(POSE_BYTES, b"\0")]
    xyz = [step / _STEPS_PER_METRE for step in steps[:3]]
    rpy = [step / _STEPS_PER_RADIAN for step in steps[3:]]
    return {key: part for key, part in (("xyz", xyz), ("rpy", rpy)) if any(part)}


@cache
def shapes(*, halfspace: int = HALFSPACE_SHARE) -> st.SearchStrategy[dict[str, Any]]:
    """A SHAPE of the six types (a HalfSpace one time in ``halfspace``, 32; 0: never).

    One choice of ``SHAPE_BYTES`` bytes, read by ``shape_of``.
    """
    return picks(SHAPE_BYTES).map(partial(shape_of, halfspace=halfspace))


def point_of(data: bytes) -> list[float]:
    """The point ``[x, y, z]`` that 3 bytes stand for: signed steps of 5 mm (±0.64 m)."""
    steps = [_signed(byte) for byte in data[:3].ljust(3, b"\0")]
    return [step / _STEPS_PER_METRE for step in steps]


@cache
def points() -> st.SearchStrategy[list[float]]:
    """A point in the world (``point_of``); one choice of 3 bytes."""
    return picks(3).map(point_of)


@cache
def poses() -> st.SearchStrategy[dict[str, list[float]]]:
    """A POSE (rpy and xyz); one choice of ``POSE_BYTES`` bytes, read by ``pose_of``."""
    return picks(POSE_BYTES).map(pose_of)


Vector = tuple[float, float, float]
#: A rotation matrix, by rows.
Matrix = tuple[Vector, Vector, Vector]


def rotation(rpy: Sequence[float]) -> Matrix:
    """``R = Rz(yaw) · Ry(pitch) · Rx(roll)``, as ``RollPitchYaw.ToRotationMatrix()``."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = (
        math.cos(r),
        math.sin(r),
        math.cos(p),
        math.sin(p),
        math.cos(y),
        math.sin(y),
    )
    return (
        (cp * cy, sr * sp * cy - cr * sy, cr * sp * cy + sr * sy),
        (cp * sy, sr * sp * sy + cr * cy, cr * sp * sy - sr * cy),
        (-sp, sr * cp, cr * cp),
    )


def _norm(v: Sequence[float]) -> float:
    return math.sqrt(sum(x * x for x in v))


def _scaled(v: Sequence[float], k: float) -> Vector:
    return (v[0] * k, v[1] * k, v[2] * k)


def _sign(x: float) -> float:
    return -1.0 if x < 0 else 1.0


def _support_ellipsoid(shape: dict[str, Any], d: Vector) -> Vector:
    """``x = D² d / |D d|`` with ``D = diag(a, b, c)``: the maximiser of ``d · x``."""
    axes = (shape["a"], shape["b"], shape["c"])
    scaled = [a * x for a, x in zip(axes, d, strict=True)]
    length = _norm(scaled)
    return (
        axes[0] * scaled[0] / length,
        axes[1] * scaled[1] / length,
        axes[2] * scaled[2] / length,
    )


def _support_round(radius: float, d: Vector) -> Vector:
    return _scaled(d, radius / _norm(d))


def _support_cylinder(shape: dict[str, Any], d: Vector) -> Vector:
    """The rim point: ``r (dx, dy) / |(dx, dy)|`` and the cap ``±L/2`` on z by the sign of dz."""
    radial = math.hypot(d[0], d[1])
    k = shape["radius"] / radial if radial else 0.0
    return (d[0] * k, d[1] * k, _sign(d[2]) * shape["length"] / 2)


def _support_capsule(shape: dict[str, Any], d: Vector) -> Vector:
    """The end of the segment on the side of d, plus the radius along d."""
    x, y, z = _support_round(shape["radius"], d)
    return (x, y, z + _sign(d[2]) * shape["length"] / 2)


#: The support point of each bounded shape in its own frame, for a direction d ≠ 0.
_SUPPORT: dict[str, Callable[[dict[str, Any], Vector], Vector]] = {
    "sphere": lambda shape, d: _support_round(shape["radius"], d),
    "box": lambda shape, d: (
        _sign(d[0]) * shape["width"] / 2,
        _sign(d[1]) * shape["depth"] / 2,
        _sign(d[2]) * shape["height"] / 2,
    ),
    "cylinder": _support_cylinder,
    "capsule": _support_capsule,
    "ellipsoid": _support_ellipsoid,
}


@cache
def _mesh_points(path: str) -> tuple[Vector, ...]:
    """The vertices of a corpus mesh file (``v`` lines of an .obj, POINTS of a legacy .vtk)."""
    lines = (corpus_root() / path).read_text().splitlines()
    if path.endswith(".obj"):
        rows = [line.split()[1:4] for line in lines if line.startswith("v ")]
    else:
        start = next(i for i, line in enumerate(lines) if line.startswith("POINTS"))
        count = int(lines[start].split()[1])
        rows = [line.split() for line in lines[start + 1 : start + 1 + count]]
    return tuple((float(x), float(y), float(z)) for x, y, z in rows)


def _support_mesh(shape: dict[str, Any], d: Vector) -> Vector:
    """The scaled vertex farthest along d (a mesh collides as its convex hull)."""
    k = shape.get("scale", 1.0)
    points = [(x * k, y * k, z * k) for x, y, z in _mesh_points(shape["path"])]
    return max(points, key=lambda p: p[0] * d[0] + p[1] * d[1] + p[2] * d[2])


_SUPPORT["mesh"] = _support_mesh
_SUPPORT["convex"] = _support_mesh


def support(shape: dict[str, Any], direction: Vector) -> Vector:
    """A point of ``shape`` (in its frame) that maximises ``direction · x``.

    A HalfSpace (``z ≤ 0``) is bounded only along +z: its support in any
    direction is taken as its origin, which is right only for ``+z``
    (``touching_position`` turns the direction so).
    """
    if shape["type"] == "halfspace":
        return (0.0, 0.0, 0.0)
    return _SUPPORT[shape["type"]](shape, direction)


def _apply(rotation_: Matrix, v: Sequence[float]) -> Vector:
    return (
        rotation_[0][0] * v[0] + rotation_[0][1] * v[1] + rotation_[0][2] * v[2],
        rotation_[1][0] * v[0] + rotation_[1][1] * v[1] + rotation_[1][2] * v[2],
        rotation_[2][0] * v[0] + rotation_[2][1] * v[1] + rotation_[2][2] * v[2],
    )


def _apply_transposed(rotation_: Matrix, v: Sequence[float]) -> Vector:
    return (
        rotation_[0][0] * v[0] + rotation_[1][0] * v[1] + rotation_[2][0] * v[2],
        rotation_[0][1] * v[0] + rotation_[1][1] * v[1] + rotation_[2][1] * v[2],
        rotation_[0][2] * v[0] + rotation_[1][2] * v[1] + rotation_[2][2] * v[2],
    )


def _product(a: Matrix, b: Matrix) -> Matrix:
    columns = [(b[0][j], b[1][j], b[2][j]) for j in range(3)]
    rows = [tuple(sum(x * y for x, y in zip(row, c, strict=True)) for c in columns) for row in a]
    return (
        (rows[0][0], rows[0][1], rows[0][2]),
        (rows[1][0], rows[1][1], rows[1][2]),
        (rows[2][0], rows[2][1], rows[2][2]),
    )


def _plus(a: Vector, b: Vector) -> Vector:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def _minus(a: Vector, b: Vector) -> Vector:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


_IDENTITY_ROTATION: Matrix = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))


@dataclass(frozen=True)
class Transform:
    """A rigid transform ``X_AB``: B's rotation and origin in A (what a POSE stands for)."""

    rotation: Matrix = _IDENTITY_ROTATION
    translation: Vector = (0.0, 0.0, 0.0)

    @classmethod
    def of(cls, pose: dict[str, Any] | None) -> Transform:
        """The transform of a POSE: ``RigidTransform(rpy=RollPitchYaw(rpy), p=xyz)``."""
        pose = pose or {}
        rpy, xyz = pose.get("rpy", (0.0, 0.0, 0.0)), pose.get("xyz", (0.0, 0.0, 0.0))
        return cls(rotation(rpy), (float(xyz[0]), float(xyz[1]), float(xyz[2])))

    def __mul__(self, other: Transform) -> Transform:
        """``X_AC = X_AB · X_BC``: ``R_AC = R_AB R_BC``, ``p_AC = p_AB + R_AB p_BC``."""
        return Transform(
            _product(self.rotation, other.rotation),
            _plus(self.translation, _apply(self.rotation, other.translation)),
        )

    def point(self, p_B: Vector) -> Vector:
        """``p_A = X_AB · p_B``."""
        return _plus(self.translation, _apply(self.rotation, p_B))

    def local(self, p_A: Vector) -> Vector:
        """``p_B = X_AB⁻¹ · p_A = R_ABᵀ (p_A − p_AB)``."""
        return _apply_transposed(self.rotation, _minus(p_A, self.translation))


def touching_position(
    shape_a: dict[str, Any],
    pose_a: Transform,
    shape_b: dict[str, Any],
    rotation_b: Matrix,
    *,
    direction: Vector,
    gap: float,
) -> Vector | None:
    """Where B's origin goes (in the world) for B to sit at ``gap`` from A along ``direction``.

    ``pose_a`` is A's world pose X_WA, ``rotation_b`` B's world
    rotation R_WB, ``direction`` a unit vector u. With ``s_A`` A's support
    point along u and ``s_B`` B's along −u (both in the world), B goes to
    ``p_WB = s_A + gap·u − R_WB·s_B(B frame)``. For ``gap ≥ 0`` the two planes
    normal to u through the support points bound a slab of width ``gap``
    between the shapes, and the support points are ``gap`` apart, so the
    signed distance is exactly ``gap``; for ``gap < 0`` the shapes overlap by
    ``|gap|`` along u, and the penetration depth is at most ``|gap|``. Either
    way the pair goes from colliding to not colliding at ``gap = 0``.

    A HalfSpace is bounded only along its normal, so u becomes A's outward
    normal ``R_WA·z`` if A is one, or ``−R_WB·z`` if B is one (B's normal then
    faces A). Two HalfSpaces have no such position: None.
    """
    rotation_a, origin_a = pose_a.rotation, pose_a.translation
    if shape_a["type"] == "halfspace" and shape_b["type"] == "halfspace":
        return None
    if shape_a["type"] == "halfspace":
        direction = _apply(rotation_a, (0.0, 0.0, 1.0))
    elif shape_b["type"] == "halfspace":
        direction = _scaled(_apply(rotation_b, (0.0, 0.0, 1.0)), -1.0)
    local_a = support(shape_a, _apply_transposed(rotation_a, direction))
    s_a = _apply(rotation_a, local_a)
    local_b = support(shape_b, _apply_transposed(rotation_b, _scaled(direction, -1.0)))
    s_b = _apply(rotation_b, local_b)
    return (
        origin_a[0] + s_a[0] + gap * direction[0] - s_b[0],
        origin_a[1] + s_a[1] + gap * direction[1] - s_b[1],
        origin_a[2] + s_a[2] + gap * direction[2] - s_b[2],
    )


#: Scales of a drawn gap (metres): ``|gap| = scale·(1 + m/256)``, so 1e-9 ≤ |gap| < 1e-3.
#:
#: N.B. Not below 1e-9. Nearer contact the two sides may rightly disagree, and
#: pydrake may end the process, so a finding there says nothing about the filters
#: or the queries (measured against pydrake 1.51.1): at an exact touch, rounding
#: of the poses decides the pair set even for closed forms (a sphere–box touch:
#: pydrake a penetration of depth 1.4e-17, reimpl none; ``fuzz --poses --seed 1``
#: with exact gaps drawn); ``HasCollisions`` of GJK/MPR pairs differs 2e-12 to
#: 6e-12 from contact; and pydrake 1.51.1 aborts (``std::logic_error`` in FCL's
#: EPA, then ``terminate``) on box–cylinder, capsule–capsule, box–capsule and
#: cylinder–capsule pairs within about 1e-12 of touching (docs/queries.md). At
#: 1e-9 the pair set is decided with a margin of 100 over the last two.
GAP_SCALES = (5e-4, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9)
#: Bytes of a drawn touch: the pair (2), the direction (3), B's frame rotation (3), the gap (2).
TOUCH_BYTES = 10


@dataclass(frozen=True)
class Touch:
    """A near-touching offset: put geometry B at ``gap`` from geometry A along ``direction``.

    ``a`` and ``b`` are picks (names are read later, as for any template);
    ``rpy`` is the rotation of B's frame in its parent, drawn with the offset.
    """

    a: int
    b: int
    direction: Vector
    rpy: Vector
    gap: float

    @classmethod
    def decode(cls, data: bytes) -> Touch:
        """``TOUCH_BYTES`` bytes: picks a, b; direction; rpy; sign-and-scale, mantissa.

        The direction is three signed steps, normalised (all zero: +z). The
        gap's byte 8 holds the sign (bit 0) and the scale (the rest, mod
        ``len(GAP_SCALES)``), byte 9 the mantissa: ``±scale·(1 + m/256)``,
        so ``1e-9 ≤ |gap| < 1e-3``. All bytes zero: ``+5e-4`` along +z,
        unrotated.
        """
        data = data[:TOUCH_BYTES].ljust(TOUCH_BYTES, b"\0")
        steps = [float(_signed(byte)) for byte in data[2:5]]
        length = _norm(steps)
        direction = (0.0, 0.0, 1.0) if not length else _scaled(steps, 1 / length)
        rpy = (
            _signed(data[5]) / _STEPS_PER_RADIAN,
            _signed(data[6]) / _STEPS_PER_RADIAN,
            _signed(data[7]) / _STEPS_PER_RADIAN,
        )
        scale = GAP_SCALES[(data[8] >> 1) % len(GAP_SCALES)]
        gap = (-1 if data[8] & 1 else 1) * scale * (1 + data[9] / 256)
        return cls(data[0], data[1], direction, rpy, gap)


@cache
def touches() -> st.SearchStrategy[Touch]:
    """A ``Touch``: one choice of ``TOUCH_BYTES`` bytes, read by ``Touch.decode``."""
    return picks(TOUCH_BYTES).map(Touch.decode)


# ------------------------------------------------------------------ scenes
@dataclass(frozen=True)
class GeometrySpec:
    name: str
    frame: str  # WORLD for anchored geometry
    roles: tuple[str, ...]
    #: The grammar's SHAPE (None: the default sphere) and POSE in the frame (None: identity).
    shape: dict[str, Any] | None = field(default=None, hash=False, compare=True)
    pose: dict[str, list[float]] | None = field(default=None, hash=False, compare=True)

    def arguments(self) -> dict[str, Any]:
        """The register_geometry arguments besides the frame: name, roles, shape, pose."""
        args: dict[str, Any] = {"name": self.name, "roles": [*self.roles]}
        if self.shape is not None:
            args["shape"] = self.shape
        if self.pose:
            args["pose"] = self.pose
        return args


@dataclass(frozen=True)
class Scene:
    """Frames (name → parent, None for the world) and geometries, in registration order.

    ``poses`` (a posed scene) holds each frame's pose in its parent (the
    grammar's POSES, for ``set_poses``); a frame left out is at the identity.
    """

    frames: tuple[tuple[str, str | None], ...]
    geometries: tuple[GeometrySpec, ...]
    poses: tuple[tuple[str, dict[str, list[float]]], ...] = field(default=(), hash=False)
    frame_names: tuple[str, ...] = field(init=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "frame_names", tuple(name for name, _ in self.frames))

    def commands(self) -> list[Command]:
        """register_frame, register_geometry, then (posed) set_poses, on the implicit source."""
        out: list[Command] = []
        for name, parent in self.frames:
            args: dict[str, Any] = {"name": name}
            if parent is not None:
                args["parent"] = parent
            out.append(Command("register_frame", args))
        for g in self.geometries:
            out.append(Command("register_geometry", {**g.arguments(), "frame": g.frame}))
        if self.poses:
            out.append(Command("set_poses", {"poses": dict(self.poses)}))
        return out

    def to_json(self) -> dict[str, Any]:
        """The scenario file's ``scene`` object (a posed scene's frame poses are not in it)."""
        return {
            "frames": [
                {"name": n} if p is None else {"name": n, "parent": p} for n, p in self.frames
            ],
            "geometries": [{**g.arguments(), "frame": g.frame} for g in self.geometries],
        }


@st.composite
def scenes(
    draw: st.DrawFn,
    *,
    min_frames: int = 0,
    max_frames: int = 4,
    min_geometries: int = 1,
    max_geometries: int = 8,
    anchored: bool = True,
    nested: bool = True,
    non_proximity: bool = True,
    posed: bool = False,
    halfspace: int = POSED_HALFSPACE_SHARE,
) -> Scene:
    """A scene: a frame tree and geometry on it.

    Frames are ``f1, f2, ...``; with ``nested`` a frame's parent may be an
    earlier frame. Geometries are ``g1, g2, ...`` on a frame or, with
    ``anchored``, on the world. With ``non_proximity`` some geometries lack
    the proximity role (only illustration/perception, or no role at all).
    ``posed`` draws a shape and a pose for every geometry (``shape_of``,
    with a HalfSpace one time in ``halfspace``, by default never:
    ``POSED_HALFSPACE_SHARE``; ``pose_of``) and a pose for every frame, after
    everything else, so an unposed scene is drawn as before.
    """
    n_frames = draw(st.integers(min_value=min_frames, max_value=max_frames))
    frames: list[tuple[str, str | None]] = []
    for index, byte in enumerate(draw(picks(n_frames)), start=1):
        # Pick 0 is "no parent" (the world), so parents shrink away.
        parent = byte % index if nested else 0
        frames.append((f"f{index}", frames[parent - 1][0] if parent else None))
    places = ([WORLD] if anchored or not frames else []) + [name for name, _ in frames]
    n_geometries = draw(st.integers(min_value=min_geometries, max_value=max_geometries))
    layout = draw(picks(2 * n_geometries))  # (place, role code) per geometry
    geometries = [
        GeometrySpec(
            f"g{index}",
            places[layout[2 * index - 2] % len(places)],
            tuple(role_list(code if non_proximity else code % 12)),
        )
        for index, code in enumerate(layout[1::2], start=1)
    ]
    if not posed:
        return Scene(tuple(frames), tuple(geometries))
    solid = SHAPE_BYTES + POSE_BYTES
    drawn = draw(picks(solid * n_geometries + POSE_BYTES * n_frames))
    geometries = [
        replace(
            g,
            shape=shape_of(drawn[i * solid : i * solid + SHAPE_BYTES], halfspace=halfspace),
            pose=pose_of(drawn[i * solid + SHAPE_BYTES : (i + 1) * solid]),
        )
        for i, g in enumerate(geometries)
    ]
    at = solid * n_geometries
    frame_poses = [
        (name, pose_of(drawn[at + i * POSE_BYTES : at + (i + 1) * POSE_BYTES]))
        for i, (name, _) in enumerate(frames)
    ]
    return Scene(
        tuple(frames), tuple(geometries), tuple((name, pose) for name, pose in frame_poses if pose)
    )


# ---------------------------------------------------------- sets, declarations
def set_spec(geometries: Sequence[str], frames: Sequence[str]) -> dict[str, list[str]]:
    """The scenario grammar's geometry set; an empty list is left out."""
    out: dict[str, list[str]] = {}
    if geometries:
        out["geometries"] = list(geometries)
    if frames:
        out["frames"] = list(frames)
    return out


@dataclass(frozen=True)
class SetTemplate:
    """A geometry set drawn as picks; ``resolve`` reads them against names."""

    geometries: tuple[int, ...]
    frames: tuple[int, ...]

    @classmethod
    def decode(cls, data: bytes, *, max_geometries: int = 3, max_frames: int = 2) -> SetTemplate:
        """Byte 0 gives the counts (bits 0-1 geometries, bits 2-3 frames), then the picks."""
        head = data[0] if data else 0
        n_geometries = min(head & 3, max_geometries)
        n_frames = min(head >> 2 & 3, max_frames)
        body = data[1:]
        return cls(tuple(body[:n_geometries]), tuple(body[n_geometries : n_geometries + n_frames]))

    def resolve(self, geometry: Picker, frame: Picker) -> dict[str, list[str]]:
        """``set_spec`` of the picked names (duplicates and Nones dropped)."""
        return set_spec(_unique(map(geometry, self.geometries)), _unique(map(frame, self.frames)))


@cache
def set_templates(
    *, max_geometries: int = 3, max_frames: int = 2
) -> st.SearchStrategy[SetTemplate]:
    """Up to ``max_geometries`` (≤ 3) geometry picks and ``max_frames`` (≤ 3) frame picks.

    One choice: ``bytes`` decoded by ``SetTemplate.decode``.
    """
    if not (0 <= max_geometries <= 3 and 0 <= max_frames <= 3):
        raise ValueError("set_templates: at most 3 geometry picks and 3 frame picks")
    return st.binary(min_size=1, max_size=1 + max_geometries + max_frames).map(
        lambda data: SetTemplate.decode(data, max_geometries=max_geometries, max_frames=max_frames)
    )


#: Bits of a mask: a declaration's pool has at most this many picks.
_MASK_BITS = 6


@dataclass(frozen=True)
class DeclarationTemplate:
    """A declaration drawn as picks: statements whose sets are bitmasks over one pool.

    The pool is the ``geometries`` picks, then the ``frames`` picks; bit i of
    a mask puts pool item i in the set. Drawing sets from one small pool
    makes statements overlap, as in real declarations where a later
    statement refines an earlier one.
    """

    geometries: tuple[int, ...]
    frames: tuple[int, ...]
    #: (op, masks): one mask for ``*_within``, two (a, b) for ``*_between``.
    statements: tuple[tuple[str, tuple[int, ...]], ...]

    @classmethod
    def decode(
        cls, data: bytes, *, pool_size: int = 4, frame_pool_size: int = 2, max_statements: int = 4
    ) -> DeclarationTemplate:
        """The pool's picks, then the statements: one byte each, plus one for ``b``.

        A statement byte holds the op (bits 0-1, ``STATEMENT_OPS``) and the
        first set's mask (bits 2-7); ``*_between`` takes the next byte's low
        six bits as the second set's mask (0, the empty set, if none is left).
        """
        pool = pool_size + frame_pool_size
        stream = iter(data[pool:])
        statements: list[tuple[str, tuple[int, ...]]] = []
        for byte in stream:
            if len(statements) == max_statements:
                break
            op = STATEMENT_OPS[byte & 3]
            masks = (byte >> 2,) if op.endswith("_within") else (byte >> 2, next(stream, 0) & 63)
            statements.append((op, masks))
        return cls(tuple(data[:pool_size]), tuple(data[pool_size:pool]), tuple(statements))

    def resolve(self, geometry: Picker, frame: Picker) -> dict[str, Any]:
        """``{"statements": [...]}`` in the scenario grammar."""
        pool = [geometry(index) for index in self.geometries]
        pool_frames = [frame(index) for index in self.frames]

        def members(mask: int) -> dict[str, list[str]]:
            chosen = [mask >> bit & 1 for bit in range(len(pool) + len(pool_frames))]
            return set_spec(
                _unique(n for n, on in zip(pool, chosen, strict=False) if on),
                _unique(n for n, on in zip(pool_frames, chosen[len(pool) :], strict=False) if on),
            )

        items: list[dict[str, Any]] = []
        for op, masks in self.statements:
            if op.endswith("_within"):
                items.append({"op": op, "set": members(masks[0])})
            else:
                items.append({"op": op, "a": members(masks[0]), "b": members(masks[1])})
        return {"statements": items}


@cache
def declaration_templates(
    *,
    min_statements: int = 1,
    max_statements: int = 4,
    pool_size: int = 4,
    frame_pool_size: int = 2,
) -> st.SearchStrategy[DeclarationTemplate]:
    """``DeclarationTemplate``: 1-4 statements by default, in any order.

    A pool of ``pool_size`` geometry picks and ``frame_pool_size`` frame picks
    (at most 6 in all; repeated picks name one item); each set is a bitmask
    over the pool that shrinks towards the empty set. One choice: ``bytes``
    decoded by ``DeclarationTemplate.decode``.
    """
    pool = pool_size + frame_pool_size
    if pool > _MASK_BITS or not 1 <= min_statements <= max_statements:
        raise ValueError(
            "declaration_templates: at most 6 pool picks and 1 ≤ min_statements ≤ max_statements"
        )
    return st.binary(min_size=pool + min_statements, max_size=pool + 2 * max_statements).map(
        lambda data: DeclarationTemplate.decode(
            data,
            pool_size=pool_size,
            frame_pool_size=frame_pool_size,
            max_statements=max_statements,
        )
    )


def geometry_sets(
    *,
    geometries: Names,
    frames: Names = (WORLD,),
    max_size: int = 3,
    special: bool = True,
) -> st.SearchStrategy[dict[str, list[str]]]:
    """``{"geometries": [...], "frames": [...]}``, either list possibly empty or absent.

    With ``special``, an element is now and then ``@unknown`` or ``@foreign``.
    Removed or non-proximity geometry comes from ``geometries`` itself.
    """
    rare = (UNKNOWN, FOREIGN) if special else ()
    templates = set_templates(
        max_geometries=min(max_size, 3), max_frames=min(max(1, max_size - 1), 3)
    )

    @st.composite
    def resolved(draw: st.DrawFn) -> dict[str, list[str]]:
        return draw(templates).resolve(_picker(draw, geometries, rare), _picker(draw, frames, rare))

    return resolved()


def statements(
    *, geometries: Names, frames: Names = (WORLD,), special: bool = True, max_size: int = 3
) -> st.SearchStrategy[dict[str, Any]]:
    """One statement: ``exclude_within``/``allow_within`` on a set, or ``*_between`` on two."""
    sets = geometry_sets(geometries=geometries, frames=frames, special=special, max_size=max_size)
    within = st.builds(lambda op, s: {"op": op, "set": s}, st.sampled_from(STATEMENT_OPS[:2]), sets)
    between = st.builds(
        lambda op, a, b: {"op": op, "a": a, "b": b}, st.sampled_from(STATEMENT_OPS[2:]), sets, sets
    )
    return within | between


@st.composite
def declarations(
    draw: st.DrawFn,
    *,
    geometries: Names,
    frames: Names = (WORLD,),
    min_statements: int = 1,
    max_statements: int = 4,
    special: bool = True,
    pool_size: int = 4,
) -> dict[str, Any]:
    """``{"statements": [...]}``: a ``DeclarationTemplate`` resolved against the names.

    1-4 statements by default, in any order, over one pool of up to
    ``pool_size`` geometries and 2 frames (see ``DeclarationTemplate``).
    """
    rare = (UNKNOWN, FOREIGN) if special else ()
    template = draw(
        declaration_templates(
            min_statements=min_statements, max_statements=max_statements, pool_size=pool_size
        )
    )
    return template.resolve(_picker(draw, geometries, rare), _picker(draw, frames, rare))
