"""The proximity engine: FCL objects for one GeometryState, posed, the broadphase and queries.

Drake counterpart: drake/geometry/proximity_engine.cc and proximity/*_callback.cc
(Drake 1.51.1 builds on its vendored FCL and libccd). This is the only module
that imports ``fcl`` (python-fcl); everything else sees GeometryIds, numpy
arrays and result objects.

Posing. A pose port holds ``X_PF`` for each frame of its source, F's pose in
its parent P (measured: a frame registered under another frame). Then
``X_WF = X_WP · X_PF`` down the frame tree, ``X_WG = X_WF · X_FG`` for a
geometry on F (rounded as Drake's fused multiply-adds round it), and
``X_WG = X_FG`` for anchored geometry. Posing again moves only the FCL objects
whose ``X_WG`` changed.

Broadphase. Two ``fcl.DynamicAABBTreeCollisionManager``, as in Drake: one for
dynamic geometry (queried against itself) and one for anchored geometry
(queried against the dynamic one, dynamic object first); anchored pairs are
never met. Each met pair is kept only if ``collision_filter.can_collide_with``
(filters and activation). python-fcl hands callbacks new wrappers, so a met
object is named by its translation (see ``_identify``). Per pose the engine
keeps the met pairs, the distance traversal's visits and every narrowphase
answer; the filter is applied at each query, as it may change in between.

Narrowphase. Each pair is answered as Drake answers it by
``reimpl.geometry.proximity.narrowphase`` (closed forms, libccd's MPR ported to
Drake's tolerance, Drake's touching rules), sphere–sphere pairs stacked by
``proximity.sphere_sphere``; FCL's own answers (Box–Box and X–HalfSpace
contacts, boolean tests, GJK/EPA signed distance) come from the ``_Body``
methods here.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, NamedTuple, cast

import fcl
import numpy as np

from reimpl._release import release
from reimpl.geometry._convex_hull import Hull
from reimpl.geometry.identifier import FrameId, GeometryId, SourceId
from reimpl.geometry.mesh import Convex, Mesh
from reimpl.geometry.proximity.distance_to_mesh import MeshBoundary
from reimpl.geometry.proximity.distance_to_point import PointDistance
from reimpl.geometry.proximity.narrowphase import (
    DISTANCE_UNSUPPORTED,
    PairResult,
    distance_supported,
    pair_collides,
    pair_penetration,
    pair_signed_distance,
    point_signed_distance,
)
from reimpl.geometry.proximity.sphere_sphere import sphere_sphere
from reimpl.geometry.proximity.tight_aabb import HALF_SPACE, local_box, overlapping_pairs
from reimpl.geometry.proximity.transforms import EPS, Array, Pose, Vec, compose_poses
from reimpl.geometry.shape import Box, Capsule, Cylinder, Ellipsoid, HalfSpace, Shape, Sphere

__all__ = ["PairResult", "PoseInput", "ProximityEngine", "WorldPoses", "compose_poses"]


# ===================================================================== shapes
class _ShapeInfo(NamedTuple):
    """How Drake's engine sees a shape: FCL's name for it, its measures, an FCL geometry,
    and a Mesh's or Convex's convex hull."""

    name: str
    measures: tuple[float, ...]
    make: Callable[[], Any]
    hull: Hull | None = None
    boundary: Callable[[], MeshBoundary | None] | None = None


def _convex(hull: Hull) -> Callable[[], Any]:
    """An ``fcl.Convex`` of the hull: its vertices, and its polygons as Drake's face data."""
    return lambda: fcl.Convex(hull.vertices, len(hull.polygons), hull.face_data)


def _mesh_info(shape: Mesh | Convex) -> _ShapeInfo:
    hull = shape._hull_data()
    return _ShapeInfo("Convex", (), _convex(hull), hull, shape._boundary_data)


def _box_info(shape: Box) -> _ShapeInfo:
    w, d, h = shape.width(), shape.depth(), shape.height()
    return _ShapeInfo("Box", (w / 2.0, d / 2.0, h / 2.0), lambda: fcl.Box(w, d, h))


def _half_space_info(shape: HalfSpace) -> _ShapeInfo:
    # Drake's half space is {z ≤ 0} in its frame: fcl::Halfspace(n = +z, d = 0).
    return _ShapeInfo("Halfspace", (), lambda: fcl.Halfspace(np.array([0.0, 0.0, 1.0]), 0.0))


#: Shape class → its FCL view (Drake's ProximityEngine::ImplementGeometry): FCL's name,
#: the measures the narrowphase reads (a box's half sizes, radius and half length), the
#: FCL geometry; a Mesh or Convex is its convex hull, an FCL Convex.
_SHAPE_INFO: dict[type[Shape], Callable[[Any], _ShapeInfo]] = {
    Sphere: lambda s: _ShapeInfo("Sphere", (s.radius(),), lambda: fcl.Sphere(s.radius())),
    Box: _box_info,
    Cylinder: lambda s: _ShapeInfo(
        "Cylinder", (s.radius(), s.length() / 2), lambda: fcl.Cylinder(s.radius(), s.length())
    ),
    Capsule: lambda s: _ShapeInfo(
        "Capsule", (s.radius(), s.length() / 2), lambda: fcl.Capsule(s.radius(), s.length())
    ),
    Ellipsoid: lambda s: _ShapeInfo(
        "Ellipsoid", (s.a(), s.b(), s.c()), lambda: fcl.Ellipsoid(s.a(), s.b(), s.c())
    ),
    HalfSpace: _half_space_info,
    Mesh: _mesh_info,
    Convex: _mesh_info,
}


def _shape_info(shape: Shape) -> _ShapeInfo:
    """The FCL view of a supported shape (``_SHAPE_INFO``)."""
    info = _SHAPE_INFO.get(type(shape))
    if info is None:
        raise NotImplementedError(
            f"reimpl's proximity engine supports Sphere, Box, Cylinder, Capsule, Ellipsoid, "
            f"HalfSpace, Mesh and Convex; got {type(shape).__name__}"
        )
    return info(shape)


# ============================================================ the geometries
class _Poses:
    """The world poses of all proximity geometries for one posing: X_WG rows, and their
    float views, made when a narrowphase call first asks."""

    __slots__ = ("R", "floats", "p", "stale")

    def __init__(self, R: Array, p: Array) -> None:
        self.R, self.p = R, p
        self.floats: list[Pose | None] = [None] * len(p)
        # Slots whose FCL object still has an older rotation (see ProximityEngine.pose).
        self.stale: set[int] = set()


class _Body:
    """One proximity geometry as the engine holds it (a ``narrowphase.PosedGeometry``)."""

    __slots__ = (
        "boundary_of",
        "dynamic",
        "frame",
        "geometry",
        "hull",
        "id",
        "kind",
        "m",
        "obj",
        "poses",
        "slot",
        "value",
    )

    def __init__(
        self, slot: int, geometry_id: GeometryId, info: _ShapeInfo, dynamic: bool, poses: _Poses
    ):
        self.slot, self.id, self.dynamic = slot, geometry_id, dynamic
        self.kind, self.m, self.hull = info.name, info.measures, info.hull
        self.boundary_of = info.boundary
        self.value = geometry_id.get_value()
        self.geometry: Any = info.make()
        self.obj: Any = fcl.CollisionObject(self.geometry, fcl.Transform())
        self.poses = poses
        self.frame = -1

    def fcl_object(self) -> Any:
        """The FCL object, its rotation brought up to date for a narrowphase call."""
        if self.slot in self.poses.stale:
            self.obj.setRotation(self.poses.R[self.slot])
            self.poses.stale.discard(self.slot)
        return self.obj

    @property
    def pose(self) -> Pose:
        """X_WG as floats."""
        pose = self.poses.floats[self.slot]
        if pose is None:
            R, p = self.poses.R[self.slot].tolist(), self.poses.p[self.slot].tolist()
            pose = Pose((tuple(R[0]), tuple(R[1]), tuple(R[2])), tuple(p))
            self.poses.floats[self.slot] = pose
        return pose

    # ------------------------------------------------- FCL's narrowphase
    def fcl_contact(self, other: _Body) -> tuple[float, Vec, Vec] | None:
        """FCL's single contact (depth, normal from self to other, position), or None."""
        result = fcl.CollisionResult()
        fcl.collide(
            self.fcl_object(),
            other.fcl_object(),
            fcl.CollisionRequest(num_max_contacts=1, enable_contact=True),
            result,
        )
        if not result.is_collision or not result.contacts:
            return None
        c = result.contacts[0]
        n, pos = c.normal, c.pos
        return (
            float(c.penetration_depth),
            (float(n[0]), float(n[1]), float(n[2])),
            (float(pos[0]), float(pos[1]), float(pos[2])),
        )

    def fcl_collides(self, other: _Body) -> bool:
        """FCL's boolean collision test."""
        return bool(fcl.collide(self.fcl_object(), other.fcl_object(), fcl.CollisionRequest()) > 0)

    def fcl_signed_distance(self, other: _Body) -> tuple[float, Vec, Vec]:
        """FCL's signed distance φ and its witnesses p_WCa (on self), p_WCb (on other)."""
        request = fcl.DistanceRequest(enable_nearest_points=True, enable_signed_distance=True)
        answer = fcl.DistanceResult()
        fcl.distance(self.fcl_object(), other.fcl_object(), request, answer)
        a, b = answer.nearest_points
        return (
            float(answer.min_distance),
            (float(a[0]), float(a[1]), float(a[2])),
            (float(b[0]), float(b[1]), float(b[2])),
        )

    def fcl_point_distance(self, p_WQ: Vec) -> tuple[float, Vec]:
        """FCL's signed distance to a sphere of radius 0 at Q (libccd, tolerance 1e-6) and
        the witness p_WN on self."""
        point = fcl.CollisionObject(fcl.Sphere(0.0), fcl.Transform(np.array(p_WQ)))
        request = fcl.DistanceRequest(enable_nearest_points=True, enable_signed_distance=True)
        answer = fcl.DistanceResult()
        fcl.distance(self.fcl_object(), point, request, answer)
        a = answer.nearest_points[0]
        return float(answer.min_distance), (float(a[0]), float(a[1]), float(a[2]))

    def boundary(self) -> MeshBoundary | None:
        return None if self.boundary_of is None else self.boundary_of()


# ================================================================== the poses
class PoseInput(NamedTuple):
    """A source's frames as its pose port must cover them."""

    source_id: SourceId
    name: str
    frames: tuple[FrameId, ...]
    #: The frames' id values, to recognise a FramePoseVector filled in the same order.
    values: tuple[int, ...]


class WorldPoses(NamedTuple):
    """X_WF of every frame (row = frame index) as rotations and translations."""

    R: Array
    p: Array


# ================================================================= the engine
Slot = int
_Met = tuple[Slot, Slot]


class ProximityEngine:
    """FCL objects for the proximity geometries of one GeometryState, and the queries.

    Built from plain data (the caller reads the state): every non-world frame
    with its parent, the sources with frames, and the proximity geometries with
    their frame, shape and X_FG. ``pose()`` takes each source's FramePoseVector;
    the queries then run on those poses until the next ``pose()``.
    """

    def __init__(
        self,
        frames: Sequence[tuple[FrameId, FrameId | None]],
        sources: Sequence[PoseInput],
        geometries: Sequence[tuple[GeometryId, FrameId | None, Shape, Array]],
    ) -> None:
        """``frames``: (frame, parent or None for the world), parents first.
        ``geometries``: (id, frame or None if anchored, shape, X_FG as a 4×4 matrix)."""
        self._frame_index = {f: i for i, (f, _) in enumerate(frames)}
        self._frames = [f for f, _ in frames]
        self._parent = [-1 if p is None else self._frame_index[p] for _, p in frames]
        self._nested = [i for i, p in enumerate(self._parent) if p >= 0]
        self._sources = list(sources)
        self._source_rows = [
            np.array([self._frame_index[f] for f in s.frames], dtype=np.intp) for s in sources
        ]
        self._bodies: list[_Body] = []
        self._slot_of: dict[GeometryId, Slot] = {}
        holder = _Poses(np.zeros((0, 3, 3)), np.zeros((0, 3)))
        frame_rows, X_FG = [], []
        for geometry_id, frame_id, shape, X in geometries:
            body = _Body(
                len(self._bodies), geometry_id, _shape_info(shape), frame_id is not None, holder
            )
            body.frame = -1 if frame_id is None else self._frame_index[frame_id]
            self._slot_of[geometry_id] = body.slot
            self._bodies.append(body)
            frame_rows.append(body.frame)
            X_FG.append(X)
        self._body_frame = np.array(frame_rows, dtype=np.intp)
        self._values = [body.value for body in self._bodies]
        X_FG_all = np.array(X_FG, dtype=float).reshape(-1, 4, 4)
        self._R_FG, self._p_FG = X_FG_all[:, :3, :3], X_FG_all[:, :3, 3]
        dynamic = self._body_frame >= 0
        identity = np.all(X_FG_all == np.eye(4), axis=(1, 2))
        self._on_frame_origin = np.flatnonzero(dynamic & identity)
        self._off_frame_origin = np.flatnonzero(dynamic & ~identity)
        self._R_WG = np.full_like(self._R_FG, np.nan)
        self._p_WG = np.full_like(self._p_FG, np.nan)
        holder.R, holder.p = self._R_WG, self._p_WG
        self._poses = holder
        self._objects = [body.obj for body in self._bodies]
        self._is_sphere = np.array([body.kind == "Sphere" for body in self._bodies], dtype=bool)
        # Whether each FCL object's rotation is the identity now (FCL starts them so).
        self._fcl_unrotated = np.ones(len(self._bodies), dtype=bool)
        self._has_dynamic_half_space = any(
            body.dynamic and body.kind == "Halfspace" for body in self._bodies
        )
        self._X_PF = np.tile(np.eye(4), (len(self._frames), 1, 1))
        self.world = WorldPoses(
            np.zeros((len(self._frames), 3, 3)), np.zeros((len(self._frames), 3))
        )
        self._pose_key: tuple[object, ...] | None = None
        self._dynamic = fcl.DynamicAABBTreeCollisionManager()
        self._anchored = fcl.DynamicAABBTreeCollisionManager()
        self._registered = False
        self._balanced = False
        self._by_translation: dict[bytes, Slot | list[Slot]] = {}
        self._clear_caches()

    # ------------------------------------------------------------- caches
    def _clear_caches(self) -> None:
        self._met: list[_Met] | None = None
        self._penetrations: dict[_Met, PairResult | None] = {}
        self._distances: dict[_Met, PairResult] = {}
        self._collisions: dict[_Met, bool] = {}
        self._visits: dict[float, list[_Met]] = {}

    def slot(self, geometry_id: GeometryId) -> Slot | None:
        return self._slot_of.get(geometry_id)

    def kind(self, slot: Slot) -> str:
        return self._bodies[slot].kind

    # -------------------------------------------------------------- poses
    @property
    def sources(self) -> list[PoseInput]:
        return self._sources

    def pose(self, key: tuple[object, ...], blocks: Callable[[], Sequence[Array]]) -> None:
        """Poses every frame and geometry from the sources' X_PF.

        ``key`` identifies the pose ports' contents (unchanged: nothing to do);
        ``blocks()`` gives each source's X_PF stacked in its frames' order.
        X_WF = X_WP · X_PF, parents first; X_WG = X_WF · X_FG; only the FCL
        objects whose X_WG changed move.
        """
        if key == self._pose_key:
            return
        X_PF = self._X_PF
        for rows, block in zip(self._source_rows, blocks(), strict=True):
            X_PF[rows] = block
        R_WF, p_WF = X_PF[:, :3, :3].copy(), X_PF[:, :3, 3].copy()
        for i in self._nested:
            parent = self._parent[i]
            R_WF[i], p_WF[i] = compose_poses(R_WF[parent], p_WF[parent], R_WF[i], p_WF[i])
        self.world = WorldPoses(R_WF, p_WF)
        R_WG, p_WG = self._R_FG.copy(), self._p_FG.copy()
        # X_FG = I: X_WG = X_WF, which Drake's product gives too (adding exact zeros).
        on_origin, offset = self._on_frame_origin, self._off_frame_origin
        R_WG[on_origin], p_WG[on_origin] = (
            R_WF[self._body_frame[on_origin]],
            p_WF[self._body_frame[on_origin]],
        )
        if len(offset):
            frame = self._body_frame[offset]
            R_WG[offset], p_WG[offset] = compose_poses(
                R_WF[frame], p_WF[frame], self._R_FG[offset], self._p_FG[offset]
            )
        moved = np.flatnonzero(
            ~(np.all(R_WG == self._R_WG, axis=(1, 2)) & np.all(p_WG == self._p_WG, axis=1))
        )
        # N.B. A sphere's AABB in FCL is a cube around its centre, of half-width r when its
        # rotation is the identity (Eigen's isIdentity, within 1e-12) and r·√3 otherwise;
        # so a sphere staying rotated (or unrotated) moves by its translation alone, its
        # rotation set later, if a narrowphase call reads it.
        identity = np.all(np.abs(R_WG - np.eye(3)) <= 1e-12, axis=(1, 2))
        is_moved = np.zeros(len(R_WG), dtype=bool)
        is_moved[moved] = True
        rotate = is_moved & (~self._is_sphere | (identity != self._fcl_unrotated))
        self._fcl_unrotated[rotate] = identity[rotate]
        rotated = np.flatnonzero(rotate).tolist()
        objects = self._objects
        for slot, R in zip(rotated, R_WG[rotate], strict=True):
            objects[slot].setRotation(R)
        for slot, p in zip(moved.tolist(), p_WG[moved], strict=True):
            objects[slot].setTranslation(p)
        poses = self._poses
        poses.R, poses.p, poses.floats = R_WG, p_WG, [None] * len(R_WG)
        poses.stale.update(np.flatnonzero(is_moved & ~rotate).tolist())
        poses.stale.difference_update(rotated)
        self._R_WG, self._p_WG = R_WG, p_WG
        self._pose_key = key
        if len(moved) or not self._registered:
            self._index_translations()
            self._refit_managers()
            self._clear_caches()

    def _refit_managers(self) -> None:
        """Refits the trees to the new poses (Drake's update); the first time, registers.

        N.B. A refit keeps the tree's topology; after poses move far, that tree
        overlaps itself everywhere (measured with python-fcl on 1000 spheres moved at
        random: collide 9.9 ms after a refit, 0.6 ms on a tree built at the poses, 0.5
        ms to build). A query that visits every overlapping pair rebuilds the tree
        first (``_balanced``); HasCollisions, which stops at the first, does not.
        """
        if not self._registered:
            for body in self._bodies:
                (self._dynamic if body.dynamic else self._anchored).registerObject(body.obj)
            self._anchored.update()
            self._registered = True
        self._dynamic.update()
        self._balanced = False

    def _balance(self) -> None:
        """Rebuilds the dynamic tree at the current poses, if a refit left it unbalanced.

        FCL's bulk build is used unless a dynamic HalfSpace is present (its infinite
        box crashes it); then sequential insertion in registration order meets two
        dynamic objects newest first, as pydrake 1.51.1 does (measured with a Box and
        a HalfSpace). The order among more is the tree's and differs from Drake's; it
        shows only in which of several unsupported pairs an error names.
        """
        if self._balanced:
            return
        self._dynamic = fcl.DynamicAABBTreeCollisionManager()
        dynamic = [body.obj for body in self._bodies if body.dynamic]
        if self._has_dynamic_half_space:
            for obj in dynamic:
                self._dynamic.registerObject(obj)
            self._dynamic.update()
        elif dynamic:
            self._dynamic.registerObjects(dynamic)  # FCL's balanced bulk build
            self._dynamic.setup()
        self._balanced = True

    def _index_translations(self) -> None:
        """translation bytes → slot (or the slots sharing that translation)."""
        rows = np.ascontiguousarray(self._p_WG).view(np.dtype((np.void, 24))).ravel()
        keys = cast("list[bytes]", rows.tolist())
        index: dict[bytes, Slot | list[Slot]] = dict(zip(keys, range(len(keys)), strict=True))
        if len(index) < len(keys):
            shared: dict[bytes, list[Slot]] = {}
            for slot, key in enumerate(keys):
                shared.setdefault(key, []).append(slot)
            index.update({k: v for k, v in shared.items() if len(v) > 1})
        self._by_translation = index

    def X_WF(self, frame_id: FrameId) -> tuple[Array, Array] | None:
        """(R_WF, p_WF) of a non-world frame, or None if the engine does not know it."""
        i = self._frame_index.get(frame_id)
        return None if i is None else (self.world.R[i], self.world.p[i])

    def X_PF(self, frame_id: FrameId) -> tuple[Array, Array] | None:
        """(R_PF, p_PF) as the frame's pose port gave it, or None."""
        i = self._frame_index.get(frame_id)
        return None if i is None else (self._X_PF[i, :3, :3], self._X_PF[i, :3, 3])

    def X_WG_arrays(self, slot: Slot) -> tuple[Array, Array]:
        """(R_WG, p_WG) of a proximity geometry."""
        return self._R_WG[slot], self._p_WG[slot]

    # ---------------------------------------------------- identification
    def _identify(self, obj: Any) -> Slot | tuple[Slot, ...]:
        """Which geometry (or group of identical ones) an FCL callback object is.

        python-fcl hands callbacks new wrappers; X_WG's translation names the
        geometry. Geometries with the same translation are told apart by
        rotation and shape, then by asking FCL (``distance`` reports the
        geometry object); fully identical ones (same shape, same X_WG) are
        interchangeable and come back as a group.
        """
        hit = self._by_translation[obj.getTranslation().tobytes()]
        if not isinstance(hit, list):
            return hit
        for slot in hit:
            self._bodies[slot].fcl_object()
        R = obj.getRotation().tobytes()
        node = obj.getNodeType()
        same = [
            s
            for s in hit
            if self._R_WG[s].tobytes() == R and self._bodies[s].obj.getNodeType() == node
        ]
        if len(same) == 1:
            return same[0]
        shapes = {(self._bodies[s].kind, self._bodies[s].m, id(self._bodies[s].hull)) for s in same}
        if len(shapes) == 1:
            return tuple(same)
        return self._identify_by_geometry(obj, same)

    def _identify_by_geometry(self, obj: Any, candidates: list[Slot]) -> Slot:
        """FCL's distance result names the python geometry object behind ``obj``."""
        probe = fcl.DistanceResult()
        fcl.distance(obj, obj, fcl.DistanceRequest(), probe)
        for slot in candidates:
            if self._bodies[slot].geometry is probe.o1:
                return slot
        raise AssertionError("an FCL object the engine does not hold")

    @staticmethod
    def _expand(a: Slot | tuple[Slot, ...], b: Slot | tuple[Slot, ...]) -> list[_Met]:
        if isinstance(a, int) and isinstance(b, int):
            return [(a, b)]
        group_a = (a,) if isinstance(a, int) else a
        group_b = (b,) if isinstance(b, int) else b
        if group_a == group_b:
            return [(x, y) for i, x in enumerate(group_a) for y in group_a[i + 1 :]]
        return [(x, y) for x in group_a for y in group_b if x != y]

    def _pair_callback(
        self, visit: Callable[[Slot, Slot], bool], failure: list[BaseException]
    ) -> Callable[[Any, Any], bool]:
        """An FCL callback body: names both objects, hands each pair to ``visit``, and
        returns whether to stop. Exceptions cannot cross FCL's C++: they stop the
        traversal and wait in ``failure``."""
        index = self._by_translation
        seen: set[_Met] = set()

        def on_pair(o1: Any, o2: Any) -> bool:
            try:
                hit_a = index[o1.getTranslation().tobytes()]
                hit_b = index[o2.getTranslation().tobytes()]
                if type(hit_a) is int and type(hit_b) is int:
                    return visit(hit_a, hit_b)
                a, b = self._identify(o1), self._identify(o2)
                # N.B. A group of identical geometries may hold anchored and dynamic ones;
                # two anchored geometries are never met (fuzz --poses, seed 1: an anchored
                # sphere posed as a dynamic one was paired with the other anchored ones).
                bodies = self._bodies
                pairs = [
                    p
                    for p in self._expand(a, b)
                    if (min(p), max(p)) not in seen
                    and (bodies[p[0]].dynamic or bodies[p[1]].dynamic)
                ]
                seen.update((min(p), max(p)) for p in pairs)
                return any(visit(x, y) for x, y in pairs)
            except BaseException as error:
                failure.append(error)
                return True

        return on_pair

    def _traverse(self, visit: Callable[[Slot, Slot], bool]) -> None:
        """Every pair whose AABBs overlap, as FCL meets them (dynamic × dynamic, then
        dynamic × anchored), until ``visit`` returns True."""
        failure: list[BaseException] = []
        stopped = [False]
        on_pair = self._pair_callback(visit, failure)

        def callback(o1: Any, o2: Any, _data: Any) -> bool:
            stopped[0] = on_pair(o1, o2)
            return stopped[0]

        self._dynamic.collide(None, callback)
        if not stopped[0]:
            self._dynamic.collide(self._anchored, None, callback)
        if failure:
            raise failure[0]

    def met_pairs(self) -> list[_Met]:
        """Every pair of geometries whose AABBs overlap, in the order FCL meets them."""
        if self._met is None:
            met: list[_Met] = []

            def keep(a: Slot, b: Slot) -> bool:
                met.append((a, b))
                return False

            self._balance()
            self._traverse(keep)
            if release.has("rotated-aabb-tight-since-1.58"):
                met = self._tight_boxes(met)
            self._met = met
        return self._met

    def _tight_boxes(self, met: list[_Met]) -> list[_Met]:
        """The met pairs under Drake 1.58's boxes (``proximity.tight_aabb``)."""
        boxes = [
            local_box(body.kind, body.m, None if body.hull is None else body.hull.vertices)
            for body in self._bodies
        ]
        dynamic = [body.dynamic for body in self._bodies]
        spaces = [body.kind == HALF_SPACE for body in self._bodies]
        return overlapping_pairs(met, boxes, dynamic, self._R_WG, self._p_WG, half_spaces=spaces)

    def distance_pairs(self, max_distance: float) -> list[_Met]:
        """Pairs FCL's distance traversal visits when it prunes at ``max(max_distance, ε/10)``
        (Drake's callback keeps resetting the bound so), in the order it visits them."""
        prune = max(max_distance, EPS / 10)
        if prune not in self._visits:
            visited: list[_Met] = []
            failure: list[BaseException] = []

            def keep(a: Slot, b: Slot) -> bool:
                visited.append((a, b))
                return False

            on_pair = self._pair_callback(keep, failure)

            def callback(o1: Any, o2: Any, _data: Any) -> tuple[bool, float]:
                return on_pair(o1, o2), prune

            self._balance()
            self._dynamic.distance(None, callback)
            if not failure:
                self._dynamic.distance(self._anchored, None, callback)
            if failure:
                raise failure[0]
            self._visits[prune] = visited
        return self._visits[prune]

    # ------------------------------------------------------------ queries
    def candidates(self, can_collide: Callable[[GeometryId, GeometryId], bool]) -> list[_Met]:
        """Met pairs the filter lets through."""
        bodies = self._bodies
        return [(a, b) for a, b in self.met_pairs() if can_collide(bodies[a].id, bodies[b].id)]

    def ordered(self, a: Slot, b: Slot) -> _Met:
        """(a, b) with the lower GeometryId first, as Drake's callbacks order a pair."""
        return (a, b) if self._bodies[a].value < self._bodies[b].value else (b, a)

    def penetrations(self, pairs: Sequence[_Met]) -> list[PairResult | None]:
        """Each pair's penetration (A the lower id), in order; raises at the first
        HalfSpace–HalfSpace pair. Sphere–sphere pairs are computed together."""
        v = self._values
        ordered = [(a, b) if v[a] < v[b] else (b, a) for a, b in pairs]
        memo = self._penetrations
        bodies = self._bodies
        spheres = [
            p
            for p in ordered
            if p not in memo and bodies[p[0]].kind == "Sphere" == bodies[p[1]].kind
        ]
        if spheres:
            memo.update(
                zip(
                    spheres,
                    sphere_sphere(spheres, bodies, self._R_WG, self._p_WG, penetration=True),
                    strict=True,
                )
            )
        for pair in ordered:
            if pair not in memo:
                memo[pair] = pair_penetration(bodies[pair[0]], bodies[pair[1]])
        return [memo[p] for p in ordered]

    def collides(self, a: Slot, b: Slot) -> bool:
        pair = self.ordered(a, b)
        if pair not in self._collisions:
            self._collisions[pair] = pair_collides(self._bodies[pair[0]], self._bodies[pair[1]])
        return self._collisions[pair]

    def signed_distances(self, pairs: Sequence[_Met]) -> list[PairResult]:
        """φ of each pair (A the lower id), in order; raises Drake's message at the first
        unsupported pair, its shapes named in the order given. Sphere–sphere pairs are
        computed together."""
        bodies = self._bodies
        for a, b in pairs:
            if not distance_supported(bodies[a].kind, bodies[b].kind):
                raise RuntimeError(DISTANCE_UNSUPPORTED.format(bodies[a].kind, bodies[b].kind))
        v = self._values
        ordered = [(a, b) if v[a] < v[b] else (b, a) for a, b in pairs]
        memo = self._distances
        spheres = [
            p
            for p in ordered
            if p not in memo and bodies[p[0]].kind == "Sphere" == bodies[p[1]].kind
        ]
        if spheres:
            found = sphere_sphere(spheres, bodies, self._R_WG, self._p_WG, penetration=False)
            memo.update(zip(spheres, found, strict=True))  # type: ignore[arg-type]
        for pair in ordered:
            if pair not in memo:
                memo[pair] = pair_signed_distance(bodies[pair[0]], bodies[pair[1]])
        return [memo[p] for p in ordered]

    def signed_distance(self, a: Slot, b: Slot) -> PairResult:
        """φ(a, b) (A the lower id); raises Drake's message, shapes named a then b."""
        return self.signed_distances([(a, b)])[0]

    def has_collisions(self, can_collide: Callable[[GeometryId, GeometryId], bool]) -> bool:
        """Whether any unfiltered pair collides; stops at the first that does."""
        bodies = self._bodies
        if self._met is not None:
            return any(
                can_collide(bodies[a].id, bodies[b].id) and self.collides(a, b)
                for a, b in self._met
            )
        found = [False]

        def check(a: Slot, b: Slot) -> bool:
            if can_collide(bodies[a].id, bodies[b].id) and self.collides(a, b):
                found[0] = True
            return found[0]

        self._traverse(check)
        return found[0]

    def point_distances(self, p_WQ: Vec, threshold: float) -> list[tuple[Slot, PointDistance]]:
        """φ_G(Q) of every geometry FCL's distance traversal from a point at Q visits (it
        prunes at ``max(threshold, ε/10)``, as Drake's callback sets), dynamic then anchored,
        kept where ``φ ≤ threshold``; a Mesh Drake skips is left out."""
        point = fcl.CollisionObject(fcl.Sphere(0.0), fcl.Transform(np.array(p_WQ)))
        prune = max(threshold, EPS / 10)
        visited: list[Slot] = []
        failure: list[BaseException] = []

        def callback(o1: Any, _o2: Any, _data: Any) -> tuple[bool, float]:
            # FCL hands the tree's object first, the query point second.
            try:
                found = self._identify(o1)
                visited.extend((found,) if isinstance(found, int) else found)
            except BaseException as error:
                failure.append(error)
                return True, prune
            return False, prune

        self._balance()
        for manager in (self._dynamic, self._anchored):
            manager.distance(point, None, callback)
            if failure:
                raise failure[0]
        found = []
        for slot in dict.fromkeys(visited):
            distance = point_signed_distance(self._bodies[slot], p_WQ)
            if distance is not None and distance.distance <= threshold:
                found.append((slot, distance))
        return found

    def body_id(self, slot: Slot) -> GeometryId:
        return self._bodies[slot].id
