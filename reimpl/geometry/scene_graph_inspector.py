"""SceneGraphInspector: read-only, live queries on one GeometryState.

Drake counterpart: drake/geometry/scene_graph_inspector.h. The inspector is a
view, not a snapshot: it sees later changes to the state it inspects.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl._template import scalar_template
from reimpl.common._pybind_text import no_constructor
from reimpl.common._std_unordered_map import identifier_set_order
from reimpl.geometry.geometry_instance import GeometryInstance, canonicalize_string_name
from reimpl.geometry.geometry_roles import (
    ASSIGNED_ROLES,
    GeometryProperties,
    IllustrationProperties,
    PerceptionProperties,
    ProximityProperties,
    Role,
    role_name,
)
from reimpl.geometry.geometry_set import GeometrySet
from reimpl.geometry.geometry_state import WORLD_FRAME_ID
from reimpl.geometry.geometry_version import GeometryVersion
from reimpl.geometry.identifier import FrameId, GeometryId, SourceId
from reimpl.geometry.shape import Shape
from reimpl.math import RigidTransform

if TYPE_CHECKING:
    from reimpl.geometry.geometry_state import GeometryState

__all__ = ["SceneGraphInspector", "SceneGraphInspector_"]

_OWNER = "reimpl.geometry.SceneGraphInspector"


class SceneGraphInspector:
    """Queries on a model or context state; get one from SceneGraph or a QueryObject."""

    def __init__(self, *args: object, **kwargs: object) -> None:
        raise no_constructor("reimpl.geometry.SceneGraphInspector")

    _state_of: Callable[[], GeometryState]

    @classmethod
    def _view(cls, state_of: Callable[[], GeometryState]) -> SceneGraphInspector:
        """A live view of whatever state ``state_of()`` returns at each call."""
        inspector = object.__new__(cls)
        inspector._state_of = state_of
        return inspector

    @property
    def _state(self) -> GeometryState:
        return self._state_of()

    # ---------------------------------------------------------- filtering
    def GetCollisionCandidates(self) -> set[tuple[GeometryId, GeometryId]]:
        """C, each pair as (a, b) with a.get_value() < b.get_value()."""
        return self._state.collision_candidates()

    def CollisionFiltered(self, geometry_id1: GeometryId, geometry_id2: GeometryId) -> bool:
        """True iff the pair is not in C; raises unless both are proximity geometries."""
        return self._state.collision_filtered(geometry_id1, geometry_id2)

    def geometry_version(self) -> GeometryVersion:
        """The state's GeometryVersion itself, a live object as pydrake's reference is
        (later changes show in it); keep ``GeometryVersion(other=...)`` to compare."""
        return self._state.version

    # ------------------------------------------------------------- counts
    def num_sources(self) -> int:
        return len(self._state.source_ids())

    def num_frames(self) -> int:
        return len(self._state.frame_ids())

    def num_geometries(self) -> int:
        return len(self._state.geometry_ids())

    def NumGeometriesWithRole(self, role: Role) -> int:
        return len(self.GetAllGeometryIds(role))

    def NumAnchoredGeometries(self) -> int:
        return len(self._state.geometries_on(WORLD_FRAME_ID))

    def NumDynamicGeometries(self) -> int:
        return self.num_geometries() - self.NumAnchoredGeometries()

    def NumFramesForSource(self, source_id: SourceId) -> int:
        return len(self._state.frames_of_source(source_id))

    def NumGeometriesForFrame(self, frame_id: FrameId) -> int:
        return len(self._state.geometries_on(frame_id))

    def NumGeometriesForFrameWithRole(self, frame_id: FrameId, role: Role) -> int:
        return sum(1 for g in self._state.geometries_on(frame_id) if self._has(g, role))

    # ---------------------------------------------------------------- ids
    @staticmethod
    def world_frame_id() -> FrameId:
        return WORLD_FRAME_ID

    def GetAllSourceIds(self) -> list[SourceId]:
        # N.B. Measured: sorted by value, where Drake walks them in another order.
        return sorted(self._state.source_ids(), key=lambda s: s.get_value())

    def GetAllFrameIds(self) -> list[FrameId]:
        return self._state.frame_ids()

    def FramesForSource(self, source_id: SourceId) -> set[FrameId]:
        return set(self._state.frames_of_source(source_id))

    def SourceIsRegistered(self, source_id: SourceId) -> bool:
        return self._state.has_source(source_id)

    def GetAllGeometryIds(self, role: Role | None = None) -> list[GeometryId]:
        ids = sorted(self._state.geometry_ids())
        return ids if role is None else [g for g in ids if self._has(g, role)]

    def GetGeometryIds(
        self, geometry_set: GeometrySet, role: Role | None = None
    ) -> set[GeometryId]:
        """The set's geometries (frames expanded to their direct children), by role."""
        ids: set[GeometryId] = set()
        for frame_id in geometry_set.frame_ids():
            self._state.collect_ids(GeometrySet(frame_id=frame_id))  # validates
            ids.update(self._state.geometries_on(frame_id))
        for geometry_id in geometry_set.geometry_ids():
            self._state.collect_ids(GeometrySet(geometry_id=geometry_id))  # validates
            ids.add(geometry_id)
        return ids if role is None else {g for g in ids if self._has(g, role)}

    def GetGeometries(self, frame_id: FrameId, role: Role | None = None) -> list[GeometryId]:
        """Geometries registered directly on the frame, in registration order, by role."""
        ids = self._state.geometries_registered_on(frame_id)
        return ids if role is None else [g for g in ids if self._has(g, role)]

    def _has(self, geometry_id: GeometryId, role: Role) -> bool:
        if role is Role.kUnassigned:
            return not any(self._state.has_role(geometry_id, r) for r in ASSIGNED_ROLES)
        return self._state.has_role(geometry_id, role)

    def GetGeometryIdByName(self, frame_id: FrameId, role: Role, name: str) -> GeometryId:
        """The one geometry on the frame with the role and the canonical form of ``name``.

        Drake walks the frame's child geometries, an ``unordered_set``, so the
        names listed when there is none are in that set's order (an id erased
        from the set is taken as never inserted, which can differ from Drake in
        bucket count after removals).
        """
        canonical = canonicalize_string_name(name)
        children = identifier_set_order(self._state.geometries_on(frame_id))
        frame_name = self._state.frame_name(frame_id)
        with_role = [g for g in children if self._has(g, role)]
        found = [g for g in with_role if self._state.geometry_name(g) == canonical]
        where = f"The frame '{frame_name}' ({frame_id.get_value()})"
        if len(found) == 1:
            return found[0]
        if not found:
            names = ", ".join(self._state.geometry_name(g) for g in with_role)
            raise RuntimeError(
                f"{where} has no geometry with the role '{role_name(role)}' and the canonical "
                f"name '{canonical}'. The names associated with this frame/role are {{{names}}}."
            )
        # Only unassigned geometries may share a name on one frame.
        raise RuntimeError(
            f"{where} has multiple geometries with the role '{role_name(role)}' and the "
            f"canonical name '{canonical}'"
        )

    # -------------------------------------------------------------- names
    def GetName(self, *args: Any, **kwargs: Any) -> str:
        return dispatch(  # type: ignore[no-any-return]
            _OWNER,
            "GetName",
            (
                Overload((Param("source_id", instance_of(SourceId)),), self._state.source_name),
                Overload((Param("frame_id", instance_of(FrameId)),), self._state.frame_name),
                Overload(
                    (Param("geometry_id", instance_of(GeometryId)),), self._state.geometry_name
                ),
            ),
            args,
            kwargs,
        )

    def GetOwningSourceName(self, *args: Any, **kwargs: Any) -> str:
        state = self._state

        def of_frame(frame_id: FrameId) -> str:
            source = state._frame(frame_id).source_id
            return state.source_name(source if source is not None else state.internal_source())

        def of_geometry(geometry_id: GeometryId) -> str:
            return state.source_name(state.geometry_source(geometry_id))

        return dispatch(  # type: ignore[no-any-return]
            _OWNER,
            "GetOwningSourceName",
            (
                Overload((Param("frame_id", instance_of(FrameId)),), of_frame),
                Overload((Param("geometry_id", instance_of(GeometryId)),), of_geometry),
            ),
            args,
            kwargs,
        )

    def BelongsToSource(self, *args: Any, **kwargs: Any) -> bool:
        state = self._state

        def frame_in(frame_id: FrameId, source_id: SourceId) -> bool:
            return state._frame(frame_id).source_id == source_id

        def geometry_in(geometry_id: GeometryId, source_id: SourceId) -> bool:
            return state.geometry_source(geometry_id) == source_id

        source = Param("source_id", instance_of(SourceId))
        return dispatch(  # type: ignore[no-any-return]
            _OWNER,
            "BelongsToSource",
            (
                Overload((Param("frame_id", instance_of(FrameId)), source), frame_in),
                Overload((Param("geometry_id", instance_of(GeometryId)), source), geometry_in),
            ),
            args,
            kwargs,
        )

    def GetFrameId(self, geometry_id: GeometryId) -> FrameId:
        return self._state.geometry_frame(geometry_id)

    def GetParentFrame(self, *args: Any, **kwargs: Any) -> FrameId:
        """The frame ``frame_id`` was registered on; the world frame's parent is itself.

        N.B. Bound since pydrake 1.52.0 (measured on 1.58.0: an unknown id raises
        RuntimeError ``No frame name available for invalid frame id: N``);
        pydrake 1.51.1 has no such method. reimpl has it, so Drake's newer
        scene_graph_test.py runs.
        """

        def parent(frame_id: FrameId) -> FrameId:
            self._state.frame_name(frame_id)  # validates, with Drake's message
            return self._state.frame_parent(frame_id)

        return dispatch(  # type: ignore[no-any-return]
            _OWNER,
            "GetParentFrame",
            (Overload((Param("frame_id", instance_of(FrameId)),), parent),),
            args,
            kwargs,
        )

    def GetFrameGroup(self, frame_id: FrameId) -> int:
        return self._state.frame_group(frame_id)

    def GetShape(self, geometry_id: GeometryId) -> Shape:
        return self._state.geometry_shape(geometry_id)

    def GetPoseInFrame(self, geometry_id: GeometryId) -> RigidTransform:
        return self._state.geometry_pose(geometry_id)

    def CloneGeometryInstance(self, geometry_id: GeometryId) -> GeometryInstance:
        """A copy of the registered geometry, roles included, with a new id."""
        return self._state.clone_instance(geometry_id)

    # --------------------------------------------------------- properties
    def GetProperties(self, geometry_id: GeometryId, role: Role) -> GeometryProperties | None:
        return self._state.properties(geometry_id, role)

    def GetProximityProperties(self, geometry_id: GeometryId) -> ProximityProperties | None:
        return self._state.properties(geometry_id, Role.kProximity)  # type: ignore[return-value]

    def GetIllustrationProperties(self, geometry_id: GeometryId) -> IllustrationProperties | None:
        return self._state.properties(geometry_id, Role.kIllustration)  # type: ignore[return-value]

    def GetPerceptionProperties(self, geometry_id: GeometryId) -> PerceptionProperties | None:
        return self._state.properties(geometry_id, Role.kPerception)  # type: ignore[return-value]


SceneGraphInspector_ = scalar_template(
    "reimpl.geometry", "SceneGraphInspector_", SceneGraphInspector
)
