"""QueryObject and FramePoseVector: the query port's value and the pose port's input.

A QueryObject is a live view of one context (Drake's is too): each query reads
the context's geometry state and its pose ports *now*, so fixing new poses
after ``Eval`` changes what an earlier QueryObject reports (measured on pydrake
1.51.1). The posing and the proximity queries themselves are SceneGraph's
(``_Posed``); this module gives them pydrake's names, keywords, result types
and ordering:

* ComputePointPairPenetration, ComputeSignedDistancePairwiseClosestPoints:
  sorted by (id_A, id_B) values; FindCollisionCandidates: sorted pairs
  ``(id_lo, id_hi)`` as tuples; ComputeSignedDistanceToPoint: sorted by id_G.
* Every query first validates the pose ports (Drake's FullPoseUpdate), so a
  missing pose raises before an unknown id does (measured).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np
import numpy.typing as npt

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl._release import release
from reimpl._template import scalar_template
from reimpl.common._std_unordered_map import MAP_AT_MESSAGE, identifier_set_order
from reimpl.common.value import register_value_type
from reimpl.geometry.geometry_roles import Role
from reimpl.geometry.geometry_state import WORLD_FRAME_ID
from reimpl.geometry.identifier import FrameId, GeometryId
from reimpl.geometry.proximity.transforms import Vec
from reimpl.geometry.proximity_engine import (
    PairResult,
    PoseInput,
    ProximityEngine,
    compose_poses,
)
from reimpl.geometry.query_results import (
    PenetrationAsPointPair,
    SignedDistancePair,
    SignedDistanceToPoint,
)
from reimpl.geometry.scene_graph_inspector import SceneGraphInspector
from reimpl.math import RigidTransform, RotationMatrix

if TYPE_CHECKING:
    from reimpl.geometry.geometry_state import GeometryState

__all__ = ["FramePoseVector", "FramePoseVector_", "PosedState", "QueryObject", "QueryObject_"]

_OWNER = "reimpl.geometry.QueryObject"

#: Every FramePoseVector edit draws a new stamp, so a stamp names one content.
_stamps = itertools.count(1)


class _Posed(Protocol):
    """What SceneGraph hands a QueryObject for one posed context (see scene_graph)."""

    def point_pair_penetration(self) -> list[PenetrationAsPointPair]: ...
    def has_collisions(self) -> bool: ...
    def collision_candidates(self) -> list[tuple[GeometryId, GeometryId]]: ...
    def pairwise_distances(self, max_distance: float) -> list[SignedDistancePair]: ...
    def pair_distance(self, id_A: GeometryId, id_B: GeometryId) -> SignedDistancePair: ...
    def point_distances(self, p_WQ: Vec, threshold: float) -> list[SignedDistanceToPoint]: ...
    def frame_pose_in_world(self, frame_id: FrameId) -> RigidTransform: ...
    def frame_pose_in_parent(self, frame_id: FrameId) -> RigidTransform: ...
    def geometry_pose_in_world(self, geometry_id: GeometryId) -> RigidTransform: ...


class QueryObject:
    """What SceneGraph's query output port evaluates to for one context."""

    def __init__(self) -> None:
        """A default QueryObject is not connected to any state; its queries cannot answer."""

        def invalid_query() -> Any:
            raise RuntimeError("Attempting to perform query on invalid QueryObject.")

        def unconnected_inspector() -> Any:
            # N.B. pydrake 1.51.1 aborts the process here; reimpl raises instead.
            raise RuntimeError("condition 'state_ != nullptr' failed.")

        self._state_of = unconnected_inspector
        self._posed_of = invalid_query

    _state_of: Callable[[], GeometryState]
    _posed_of: Callable[[], _Posed]

    @classmethod
    def _make(
        cls, state_of: Callable[[], GeometryState], posed_of: Callable[[], _Posed]
    ) -> QueryObject:
        query = object.__new__(cls)
        query._state_of = state_of
        query._posed_of = posed_of
        return query

    def inspector(self) -> SceneGraphInspector:
        """A live inspector of the context this object was evaluated on (needs no poses)."""
        return SceneGraphInspector._view(self._state_of)

    # ------------------------------------------------------------ queries
    def ComputePointPairPenetration(self) -> list[PenetrationAsPointPair]:
        """Every unfiltered penetrating pair, sorted by (id_A, id_B)."""
        return self._posed_of().point_pair_penetration()

    def HasCollisions(self) -> bool:
        """Whether any unfiltered pair collides; stops at the first that does."""
        return self._posed_of().has_collisions()

    def FindCollisionCandidates(self) -> list[tuple[GeometryId, GeometryId]]:
        """Unfiltered pairs whose bounding boxes overlap, as sorted (lower, higher) ids.

        Raises:
            TypeError: before Drake 1.48 when there is a pair
                (find-collision-candidates-since-1.48): pybind11 could not convert a
                SortedPair, so only an empty answer reached Python (measured on
                pydrake 1.12.0, 1.45.0, 1.47.0: [] without pairs, this TypeError with).
        """
        pairs = self._posed_of().collision_candidates()
        if pairs and not release.has("find-collision-candidates-since-1.48"):
            raise TypeError(
                "Unable to convert function return value to a Python type! The signature was"
                f"\n\t(self: {_OWNER}) -> list[drake::SortedPair<drake::geometry::GeometryId>]"
            )
        return pairs

    def ComputeSignedDistancePairwiseClosestPoints(
        self, max_distance: float = math.inf
    ) -> list[SignedDistancePair]:
        """φ for every unfiltered pair with ``φ ≤ max_distance``, sorted by (id_A, id_B)."""
        if isinstance(max_distance, bool) or not isinstance(max_distance, int | float):
            raise TypeError(
                "ComputeSignedDistancePairwiseClosestPoints(): incompatible function arguments. "
                "The following argument types are supported:\n"
                f"    1. (self: {_OWNER}, max_distance: float = inf) -> "
                "list[reimpl.geometry.SignedDistancePair]\n\n"
                f"Invoked with: <{_OWNER} object>, {max_distance!r}"
            )
        return self._posed_of().pairwise_distances(float(max_distance))

    def ComputeSignedDistancePairClosestPoints(
        self, geometry_id_A: GeometryId, geometry_id_B: GeometryId
    ) -> SignedDistancePair:
        """φ(A, B) for two proximity geometries, reported with id_A < id_B; filters are
        ignored since 1.15 (before, a filtered pair raises: ``PosedState.pair_distance``)."""
        for value in (geometry_id_A, geometry_id_B):
            if not isinstance(value, GeometryId):
                raise TypeError(
                    "ComputeSignedDistancePairClosestPoints(): incompatible function arguments. "
                    "The following argument types are supported:\n"
                    f"    1. (self: {_OWNER}, geometry_id_A: reimpl.geometry.GeometryId, "
                    "geometry_id_B: reimpl.geometry.GeometryId) -> "
                    "reimpl.geometry.SignedDistancePair\n\n"
                    f"Invoked with: <{_OWNER} object>, {geometry_id_A!r}, {geometry_id_B!r}"
                )
        return self._posed_of().pair_distance(geometry_id_A, geometry_id_B)

    def ComputeSignedDistanceToPoint(
        self, p_WQ: Any, threshold: float = math.inf
    ) -> list[SignedDistanceToPoint]:
        """φ_G(Q) for every proximity geometry G with ``φ ≤ threshold``, sorted by id_G;
        filters do not apply (a point has none)."""
        point = np.asarray(p_WQ, dtype=float) if _is_vector3(p_WQ) else None
        if (
            point is None
            or isinstance(threshold, bool)
            or not isinstance(threshold, int | float | np.floating)
        ):
            raise TypeError(
                "ComputeSignedDistanceToPoint(): incompatible function arguments. The following "
                "argument types are supported:\n"
                f"    1. (self: {_OWNER}, p_WQ: numpy.ndarray[numpy.float64[3, 1]], "
                "threshold: float = inf) -> list[reimpl.geometry.SignedDistanceToPoint]\n\n"
                f"Invoked with: <{_OWNER} object>, {p_WQ!r}, {threshold!r}"
            )
        p = point.reshape(3)
        return self._posed_of().point_distances(
            (float(p[0]), float(p[1]), float(p[2])), float(threshold)
        )

    # -------------------------------------------------------------- poses
    def GetPoseInWorld(self, *args: Any, **kwargs: Any) -> RigidTransform:
        """X_WF of a frame (``X_WF = X_WP · X_PF``) or X_WG of a geometry (``X_WF · X_FG``)."""
        return dispatch(  # type: ignore[no-any-return]
            _OWNER,
            "GetPoseInWorld",
            (
                Overload(
                    (Param("frame_id", instance_of(FrameId)),),
                    lambda frame_id: self._posed_of().frame_pose_in_world(frame_id),
                ),
                Overload(
                    (Param("geometry_id", instance_of(GeometryId)),),
                    lambda geometry_id: self._posed_of().geometry_pose_in_world(geometry_id),
                ),
            ),
            args,
            kwargs,
        )

    def GetPoseInParent(self, frame_id: FrameId) -> RigidTransform:
        """X_PF, the frame's pose in its parent, as its source's pose port gives it."""
        if not isinstance(frame_id, FrameId):
            raise TypeError(
                "GetPoseInParent(): incompatible function arguments. The following argument "
                "types are supported:\n"
                f"    1. (self: {_OWNER}, frame_id: reimpl.geometry.FrameId) -> "
                "reimpl.math.RigidTransform\n\n"
                f"Invoked with: <{_OWNER} object>, {frame_id!r}"
            )
        return self._posed_of().frame_pose_in_parent(frame_id)

    def X_WF(self, frame_id: FrameId) -> RigidTransform:
        """Drake C++'s older name for GetPoseInWorld(frame_id); pydrake 1.51.1 binds only
        GetPoseInWorld."""
        return self.GetPoseInWorld(frame_id=frame_id)

    def X_WG(self, geometry_id: GeometryId) -> RigidTransform:
        """Drake C++'s older name for GetPoseInWorld(geometry_id); pydrake 1.51.1 binds only
        GetPoseInWorld."""
        return self.GetPoseInWorld(geometry_id=geometry_id)


class FramePoseVector:
    """Poses of a source's frames, keyed by FrameId: each frame's X_PF (pose in its parent).

    Each edit draws a new process-wide stamp; SceneGraph re-poses a context only
    when a pose port's stamp changed.
    """

    def __init__(self) -> None:
        self._poses: dict[FrameId, RigidTransform] = {}
        self._matrices: dict[FrameId, npt.NDArray[np.float64]] = {}
        self._stamp = next(_stamps)
        self._stacked: tuple[int, tuple[int, ...], npt.NDArray[np.float64]] | None = None

    def set_value(self, id: FrameId, value: RigidTransform) -> None:
        pose = RigidTransform(value)
        self._poses[id] = pose
        self._matrices[id] = pose.GetAsMatrix4()
        self._stamp = next(_stamps)

    def value(self, id: FrameId) -> RigidTransform:
        return RigidTransform(self._poses[id])

    def _matrix(self, id: FrameId) -> npt.NDArray[np.float64]:
        """X_PF as a 4×4 matrix (shared, not copied)."""
        return self._matrices[id]

    def _stack(self) -> tuple[tuple[int, ...], npt.NDArray[np.float64]]:
        """The frames' id values in insertion order and their X_PF stacked (k, 4, 4),
        computed once per content."""
        if self._stacked is None or self._stacked[0] != self._stamp:
            order = tuple(f.get_value() for f in self._matrices)
            block = np.array(list(self._matrices.values()), dtype=float).reshape(-1, 4, 4)
            self._stacked = (self._stamp, order, block)
        return self._stacked[1], self._stacked[2]

    def has_id(self, id: FrameId) -> bool:
        return id in self._poses

    def ids(self) -> list[FrameId]:
        return list(self._poses)

    def size(self) -> int:
        return len(self._poses)

    def clear(self) -> None:
        self._poses.clear()
        self._matrices.clear()
        self._stamp = next(_stamps)

    def __copy__(self) -> FramePoseVector:
        """Same poses, same stamp (same content); either copy's next edit re-stamps it."""
        other = object.__new__(FramePoseVector)
        other._poses, other._matrices = dict(self._poses), dict(self._matrices)
        other._stamp, other._stacked = self._stamp, self._stacked
        return other


def _is_vector3(value: object) -> bool:
    """Whether pybind11 would take ``value`` as a float 3-vector."""
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return False
    return array.shape in {(3,), (3, 1)}


def _rigid_transform(R: npt.NDArray[np.float64], p: npt.NDArray[np.float64]) -> RigidTransform:
    return RigidTransform(RotationMatrix(np.array(R)), np.array(p))


def _role_text(state: GeometryState, geometry_id: GeometryId) -> str:
    for role, text in (
        (Role.kIllustration, "the illustration role"),
        (Role.kPerception, "the perception role"),
    ):
        if state.has_role(geometry_id, role):
            return text
    return "no role"


#: The engine's pose key for the model's default poses (PosedState.pose_model_defaults).
_MODEL_DEFAULTS = object()


class PosedState:
    """One context's GeometryState with its proximity engine, posed from its pose ports.

    SceneGraph keeps one per context and rebuilds it when the state changes
    (``GeometryState.revision``); ``pose()`` validates the ports' values with
    Drake's messages, then hands them to the engine, which re-poses only when
    some vector's stamp changed.
    """

    def __init__(self, state: GeometryState) -> None:
        self.state = state
        self.revision = state.revision
        frames = [
            (f, None if state.frame_parent(f) == WORLD_FRAME_ID else state.frame_parent(f))
            for f in state.frame_ids()
            if f != WORLD_FRAME_ID
        ]
        # N.B. In the order Drake walks its sources, which names the first source
        # without poses (GeometryState.source_ids).
        frames_of = {s: tuple(state.frames_of_source(s)) for s in state.source_ids()}
        sources = [
            PoseInput(s, state.source_name(s), own, tuple(f.get_value() for f in own))
            for s, own in frames_of.items()
            if own
        ]
        geometries = [
            (
                g,
                None if state.geometry_frame(g) == WORLD_FRAME_ID else state.geometry_frame(g),
                state.geometry_shape(g),
                state.geometry_pose(g).GetAsMatrix4(),
            )
            for g in state.geometry_ids()
            if state.has_role(g, Role.kProximity)
        ]
        self.engine = ProximityEngine(frames, sources, geometries)
        self.sources = self.engine.sources
        self._validated: list[int | None] = [None] * len(self.sources)

    def pose(self, values: Sequence[object]) -> None:
        """Validates each source's value (Drake's order and messages), then poses the engine.

        Raises:
            RuntimeError: a source with frames has no value, or its vector's size
                differs from its frame count, or lacks one of its frames.
            IndexError: a failed duplicate-name RegisterFrame left a trace.
        """
        blocks = []
        for k, (source, value) in enumerate(zip(self.sources, values, strict=True)):
            if value is None:
                raise RuntimeError(
                    f"Source '{source.name}' (id: {source.source_id.get_value()}) has registered "
                    "dynamic frames but is not connected to the appropriate input port."
                )
            if not isinstance(value, FramePoseVector):
                raise RuntimeError(
                    f"reimpl: the pose port of source '{source.name}' holds a "
                    f"{type(value).__name__}, not a FramePoseVector"
                )
            if self._validated[k] != value._stamp:
                self._validate(source, value)
                self._validated[k] = value._stamp
            blocks.append(value)
        if self.state.ghost_frames:
            # Measured: after the ports are checked, a frame index left by a failed
            # duplicate-name RegisterFrame fails the update (queries and Clone alike).
            raise IndexError(MAP_AT_MESSAGE)
        self.engine.pose(
            tuple(self._validated),
            lambda: [self._block(s, v) for s, v in zip(self.sources, blocks, strict=True)],
        )

    def pose_model_defaults(self) -> None:
        """Poses as the model is posed: X_PF = X_WF = I and X_WG = X_FG; no port is read."""
        self.engine.pose(
            (_MODEL_DEFAULTS,),
            lambda: [np.tile(np.eye(4), (len(s.frames), 1, 1)) for s in self.sources],
        )

    @staticmethod
    def _validate(source: PoseInput, value: FramePoseVector) -> None:
        if value._stack()[0] == source.values:
            return  # exactly the source's frames, in its order
        if value.size() != len(source.frames):
            raise RuntimeError(
                f"Disagreement in expected number of frames ({len(source.frames)}) and the "
                f"given number of frames ({value.size()})."
            )
        for frame in identifier_set_order(source.frames):  # Drake's walk of the source's frames
            if not value.has_id(frame):
                raise RuntimeError(
                    f"Registered frame id ({frame.get_value()}) belonging to source "
                    f"{source.source_id.get_value()} was not found in the provided "
                    "kinematics data."
                )

    @staticmethod
    def _block(source: PoseInput, value: FramePoseVector) -> npt.NDArray[np.float64]:
        """X_PF of the source's frames, in the source's order (k, 4, 4)."""
        order, block = value._stack()
        if order == source.values:
            return block
        return np.array([value._matrix(f) for f in source.frames], dtype=float)

    # ------------------------------------------------------------ queries
    @staticmethod
    def _sort(results: list[PairResult]) -> None:
        results.sort(key=lambda r: (r.id_A.get_value(), r.id_B.get_value()))

    def point_pair_penetration(self) -> list[PenetrationAsPointPair]:
        engine = self.engine
        pairs = engine.candidates(self.state.collision_filter.can_collide_with)
        found = [r for r in engine.penetrations(pairs) if r is not None]
        self._sort(found)
        return [PenetrationAsPointPair._make(r.id_A, r.id_B, r.value, r.vectors) for r in found]

    def has_collisions(self) -> bool:
        return self.engine.has_collisions(self.state.collision_filter.can_collide_with)

    def collision_candidates(self) -> list[tuple[GeometryId, GeometryId]]:
        engine = self.engine
        pairs = []
        for a, b in engine.candidates(self.state.collision_filter.can_collide_with):
            lo, hi = engine.ordered(a, b)
            pairs.append((engine.body_id(lo), engine.body_id(hi)))
        pairs.sort(key=lambda p: (p[0].get_value(), p[1].get_value()))
        return pairs

    def pairwise_distances(self, max_distance: float) -> list[SignedDistancePair]:
        engine = self.engine
        can_collide = self.state.collision_filter.can_collide_with
        pairs = [
            (a, b)
            for a, b in engine.distance_pairs(max_distance)
            if can_collide(engine.body_id(a), engine.body_id(b))
        ]
        found = [r for r in engine.signed_distances(pairs) if r.value <= max_distance]
        self._sort(found)
        return [SignedDistancePair._make(r.id_A, r.id_B, r.value, r.vectors) for r in found]

    def pair_distance(self, id_A: GeometryId, id_B: GeometryId) -> SignedDistancePair:
        """φ(A, B), filters ignored since 1.15; A then B must be registered proximity geometries."""
        slots = []
        for geometry_id in (id_A, id_B):
            self.state.geometry_frame(geometry_id)  # "Referenced geometry N has not been ..."
            slot = self.engine.slot(geometry_id)
            if slot is None:
                raise RuntimeError(
                    f"The geometry {geometry_id.get_value()} cannot be used in "
                    "ComputeSignedDistancePairClosestPoints; it does not have a proximity role. "
                    f"It has {_role_text(self.state, geometry_id)}."
                )
            slots.append(slot)
        if not release.has("signed-distance-pair-since-1.15") and (
            id_A == id_B or not self.state.collision_filter.can_collide_with(id_A, id_B)
        ):
            # Up to 1.14 the pair query asks the collision filter first, and a filtered
            # pair (a geometry with itself, two anchored ones, an excluded pair) has no
            # answer (signed-distance-pair-since-1.15: measured on pydrake 1.14.0 and 1.15.0).
            raise RuntimeError(
                f"The geometry pair ({id_A.get_value()}, {id_B.get_value()}) does not "
                "support a signed distance query"
            )
        r = self.engine.signed_distance(slots[0], slots[1])
        return SignedDistancePair._make(r.id_A, r.id_B, r.value, r.vectors)

    def point_distances(self, p_WQ: Vec, threshold: float) -> list[SignedDistanceToPoint]:
        """φ_G(Q) of every proximity geometry within ``threshold``, sorted by id (Drake's order)."""
        found = self.engine.point_distances(p_WQ, threshold)
        found.sort(key=lambda item: self.engine.body_id(item[0]).get_value())
        return [
            SignedDistanceToPoint._make(
                self.engine.body_id(slot), np.array(d.p_GN), d.distance, np.array(d.grad_W)
            )
            for slot, d in found
        ]

    # -------------------------------------------------------------- poses
    def frame_pose_in_world(self, frame_id: FrameId) -> RigidTransform:
        if frame_id == WORLD_FRAME_ID:
            return RigidTransform()
        pose = self.engine.X_WF(frame_id)
        if pose is None:
            raise RuntimeError(
                f"No world pose available for invalid frame id: {frame_id.get_value()}"
            )
        return _rigid_transform(*pose)

    def frame_pose_in_parent(self, frame_id: FrameId) -> RigidTransform:
        if frame_id == WORLD_FRAME_ID:
            return RigidTransform()
        pose = self.engine.X_PF(frame_id)
        if pose is None:
            raise RuntimeError(f"No pose available for invalid frame id: {frame_id.get_value()}")
        return _rigid_transform(*pose)

    def geometry_pose_in_world(self, geometry_id: GeometryId) -> RigidTransform:
        """X_WG = X_WF · X_FG (X_FG for anchored geometry), for a geometry of any role."""
        frame_id = self.state.geometry_frame(geometry_id)
        slot = self.engine.slot(geometry_id)
        if slot is not None:
            return _rigid_transform(*self.engine.X_WG_arrays(slot))
        X_FG = self.state.geometry_pose(geometry_id).GetAsMatrix4()
        if frame_id == WORLD_FRAME_ID:
            return _rigid_transform(X_FG[:3, :3], X_FG[:3, 3])
        R_WF, p_WF = self.engine.X_WF(frame_id)  # type: ignore[misc]
        return _rigid_transform(*compose_poses(R_WF, p_WF, X_FG[:3, :3], X_FG[:3, 3]))


FramePoseVector_ = scalar_template("reimpl.geometry", "FramePoseVector_", FramePoseVector)
QueryObject_ = scalar_template("reimpl.geometry", "QueryObject_", QueryObject)
register_value_type(
    FramePoseVector,
    "drake::geometry::KinematicsVector<drake::geometry::FrameId,drake::math::RigidTransform<double>>",
)
register_value_type(QueryObject, "drake::geometry::QueryObject<double>")
