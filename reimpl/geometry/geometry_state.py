"""The registered world of one SceneGraph (model) or one context.

Drake counterpart: drake/geometry/geometry_state.h (internal). It owns the
sources, frames and geometries, their roles, and the CollisionFilter. Two rules
that tie the scene to C live here:

- Resolution (``collect_ids``). A GeometrySet becomes proximity geometry ids
  when a declaration is applied: a FrameId gives the frame's *direct* child
  geometries that have the proximity role at that moment (the world frame gives
  every anchored one, from every source); a GeometryId without the proximity
  role is dropped; an unknown id raises.
- Invariants (``_assign_proximity``). When g gets the proximity role it joins
  the filter and g is excluded, invariantly, from every proximity geometry on
  its frame: V ← V ∪ {(g, h) : frame(h) = frame(g)}. For anchored g that frame
  is the world frame, which yields Aₚ × Aₚ.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NoReturn

from reimpl._release import release
from reimpl.common._drake_demand import failed_demand
from reimpl.common._std_unordered_map import MAP_AT_MESSAGE, IdentifierUnorderedMap
from reimpl.geometry._proximity_mesh import HullError
from reimpl.geometry.collision_filter import CollisionFilter
from reimpl.geometry.collision_filter_declaration import Statement, StatementOp
from reimpl.geometry.errors import (
    DuplicateRoleError,
    GeometryStateError,
    UnenginedGeometryError,
    UnknownFrameError,
    UnknownGeometryError,
    UnknownSourceError,
    UnqueryableGeometryError,
)
from reimpl.geometry.geometry_instance import GeometryFrame, GeometryInstance
from reimpl.geometry.geometry_roles import (
    ASSIGNED_ROLES,
    GeometryProperties,
    Role,
    RoleAssign,
    role_name,
)
from reimpl.geometry.geometry_set import GeometrySet
from reimpl.geometry.geometry_version import GeometryVersion
from reimpl.geometry.identifier import FrameId, GeometryId, SourceId
from reimpl.geometry.mesh import _MeshShape
from reimpl.geometry.shape import Shape
from reimpl.math import RigidTransform

#: What ``unordered_map::at`` says of a missing key (pydrake: IndexError), by release.
_MAP_AT = MAP_AT_MESSAGE
#: Whether the collision filter's queries raise IndexError for an unengined geometry
#: (up to 1.51: Drake's dense filter has no entry for it); since 1.52 it is unfiltered.
_UNENGINED_RAISES = not release.has("unengined-geometry-unfiltered-since-1.52")

__all__ = ["WORLD_FRAME_ID", "GeometryState"]

#: The world frame's id: one static id shared by every SceneGraph, as in Drake.
WORLD_FRAME_ID = FrameId.get_new_id()
_WORLD_FRAME_NAME = "world"
_INTERNAL_SOURCE_NAME = "SceneGraphInternal"
#: The world frame's frame group (Drake's InternalFrame::world_frame_group()),
#: a value no registered frame can have, as they must be non-negative.
_WORLD_FRAME_GROUP = -1234567


@dataclass
class _Source:
    id: SourceId
    name: str
    frames: list[FrameId] = field(default_factory=list)
    anchored: list[GeometryId] = field(default_factory=list)


@dataclass
class _Frame:
    id: FrameId
    name: str
    source_id: SourceId | None
    parent_id: FrameId
    frame_group: int
    geometries: list[GeometryId] = field(default_factory=list)


@dataclass
class _Geometry:
    id: GeometryId
    name: str
    frame_id: FrameId
    source_id: SourceId
    shape: Shape
    pose: RigidTransform
    properties: dict[Role, GeometryProperties] = field(default_factory=dict)

    @property
    def is_anchored(self) -> bool:
        return self.frame_id == WORLD_FRAME_ID

    @property
    def has_proximity(self) -> bool:
        return Role.kProximity in self.properties


#: The roles whose changes GeometryState records in its GeometryVersion.
_VERSIONED_ROLES = frozenset({Role.kProximity, Role.kIllustration})


class GeometryState:
    """Sources, frames, geometries, roles and the collision filter of one state."""

    def __init__(self) -> None:
        internal = SourceId.get_new_id()
        self._internal_source = internal
        # N.B. In Drake's unordered_map order, which decides which of several
        # sources without poses a query names (source_ids).
        self._sources: IdentifierUnorderedMap[SourceId, _Source] = IdentifierUnorderedMap()
        self._sources[internal] = _Source(internal, _INTERNAL_SOURCE_NAME)
        self._frames: dict[FrameId, _Frame] = {
            WORLD_FRAME_ID: _Frame(
                WORLD_FRAME_ID, _WORLD_FRAME_NAME, internal, WORLD_FRAME_ID, _WORLD_FRAME_GROUP
            )
        }
        self._geometries: dict[GeometryId, _Geometry] = {}
        self.collision_filter = CollisionFilter()
        #: Per-role revisions (geometry_version.py says which calls change which role).
        self.version = GeometryVersion()
        # Frames whose registration failed on a duplicate name; see register_frame.
        self.ghost_frames = 0
        # Bumped by every change to the frames or the proximity geometries, so a
        # posed proximity engine built from this state knows when it is stale.
        self.revision = 0
        #: Proximity geometries whose proximity engine entry failed (``unengined``).
        self.unengined: set[GeometryId] = set()

    def clone(self) -> GeometryState:
        """A deep copy, as a context's copy of the model is (filters and history too)."""
        other = object.__new__(GeometryState)
        other._internal_source = self._internal_source
        other._sources = self._sources.copy()  # the same order
        for s, r in self._sources.items():
            other._sources[s] = _Source(r.id, r.name, list(r.frames), list(r.anchored))
        other._frames = {
            f: _Frame(r.id, r.name, r.source_id, r.parent_id, r.frame_group, list(r.geometries))
            for f, r in self._frames.items()
        }
        other._geometries = {
            g: _Geometry(
                r.id,
                r.name,
                r.frame_id,
                r.source_id,
                r.shape,
                r.pose,
                {role: type(p)(p) for role, p in r.properties.items()},
            )
            for g, r in self._geometries.items()
        }
        other.collision_filter = self.collision_filter.copy()
        other.version = GeometryVersion(self.version)
        other.ghost_frames = self.ghost_frames
        other.revision = self.revision
        other.unengined = set(self.unengined)
        return other

    # ------------------------------------------------------------- validation
    def _source(self, source_id: SourceId) -> _Source:
        try:
            return self._sources[source_id]
        except KeyError:
            raise UnknownSourceError(
                f"Referenced geometry source {source_id.get_value()} is not registered."
            ) from None

    def _frame(self, frame_id: FrameId) -> _Frame:
        try:
            return self._frames[frame_id]
        except KeyError:
            raise UnknownFrameError(
                f"Referenced frame {frame_id.get_value()} has not been registered."
            ) from None

    def _geometry(self, geometry_id: GeometryId, *, period: str = ".") -> _Geometry:
        try:
            return self._geometries[geometry_id]
        except KeyError:
            raise UnknownGeometryError(
                f"Referenced geometry {geometry_id.get_value()} has not been registered{period}"
            ) from None

    def _owned_geometry(
        self, source_id: SourceId, geometry_id: GeometryId, not_owned: str
    ) -> _Geometry:
        """The geometry, after checking the source, the id, then ownership (Drake's order).

        ``not_owned`` is Drake's message for the operation when another source owns it.
        """
        self._source(source_id)
        geometry = self._geometry(geometry_id)
        if geometry.source_id != source_id:
            raise GeometryStateError(not_owned)
        return geometry

    def _frame_of_source(self, source_id: SourceId, frame_id: FrameId) -> _Frame:
        """The frame, if ``source_id`` may hang geometry on it (the world frame: any source)."""
        frame = self._frames.get(frame_id)
        if frame is None or (frame_id != WORLD_FRAME_ID and frame.source_id != source_id):
            raise UnknownFrameError(
                f"Referenced frame {frame_id.get_value()} for source {source_id.get_value()}, "
                "but the frame doesn't belong to the source."
            )
        return frame

    # ----------------------------------------------------------- registration
    def register_source(self, name: str) -> SourceId:
        """A new source, named ``name`` or, if that is empty, ``Source_<id>``.

        As in Drake, the id is drawn before the name is checked, so a duplicate
        name still uses up an id.
        """
        source_id = SourceId.get_new_id()
        name = name or f"Source_{source_id.get_value()}"
        if any(s.name == name for s in self._sources.values()):
            raise GeometryStateError(f"Registering new source with duplicate name: {name}.")
        self._sources[source_id] = _Source(source_id, name)
        return source_id

    def register_frame(
        self, source_id: SourceId, parent_id: FrameId, frame: GeometryFrame
    ) -> FrameId:
        source = self._source(source_id)
        parent = self._frames.get(parent_id)
        if parent is None or (parent_id != WORLD_FRAME_ID and parent.source_id != source_id):
            raise UnknownFrameError(
                f"Indicated parent id {parent_id.get_value()} does not belong to the indicated "
                f"source id {source_id.get_value()}."
            )
        if frame.id() in self._frames:
            raise GeometryStateError(
                "Registering frame with an id that has already been registered: "
                f"{frame.id().get_value()}"
            )
        if any(self._frames[f].name == frame.name() for f in source.frames):
            # N.B. Measured (pydrake 1.51.1 and 1.58): this failure leaves a trace
            # in the state (and in contexts made from it later); cloning such a
            # context after fixing its poses and evaluating it raises IndexError.
            # Found by the lockstep fuzzer; see known_divergences.json.
            self.ghost_frames += 1
            raise GeometryStateError(
                f"Registering frame for source '{source.name}' with a duplicate name "
                f"'{frame.name()}'"
            )
        self._frames[frame.id()] = _Frame(
            frame.id(), frame.name(), source_id, parent_id, frame.frame_group()
        )
        source.frames.append(frame.id())
        self.revision += 1
        return frame.id()

    def register_geometry(
        self, source_id: SourceId, frame_id: FrameId, geometry: GeometryInstance
    ) -> GeometryId:
        """Registers the geometry, then assigns the roles its instance carries.

        N.B. As in Drake, a role assignment that fails here (a duplicate name,
        or transient history for proximity) raises with the geometry left
        registered.
        """
        self._source(source_id)
        frame = self._frame_of_source(source_id, frame_id)
        if geometry.id() in self._geometries:
            raise GeometryStateError(
                "Registering geometry with an id that has already been registered: "
                f"{geometry.id().get_value()}"
            )
        record = _Geometry(
            geometry.id(), geometry.name(), frame_id, source_id, geometry.shape(), geometry.pose()
        )
        self._geometries[record.id] = record
        frame.geometries.append(record.id)
        if frame_id == WORLD_FRAME_ID:
            self._sources[source_id].anchored.append(record.id)
        for properties in (
            geometry.proximity_properties(),
            geometry.perception_properties(),
            geometry.illustration_properties(),
        ):
            if properties is not None:
                self.assign_role(source_id, record.id, properties, RoleAssign.kNew)
        return record.id

    # ----------------------------------------------------------------- roles
    def assign_role(
        self,
        source_id: SourceId,
        geometry_id: GeometryId,
        properties: GeometryProperties,
        assign: RoleAssign,
    ) -> None:
        """Assigns or replaces a role; a new proximity role joins C (see module doc).

        N.B. Drake rejects kReplace of perception properties before it checks
        the source or the geometry (measured; found by the lockstep fuzzer).
        """
        if assign is RoleAssign.kReplace and properties.role is Role.kPerception:
            raise GeometryStateError(
                "AssignRole() with RoleAssign::kReplace does not work for perception properties"
            )
        geometry = self._owned_geometry(
            source_id,
            geometry_id,
            f"Given geometry id {geometry_id.get_value()} does not belong to the given "
            f"source id {source_id.get_value()}",
        )
        role = properties.role
        name = role_name(role)
        has_role = role in geometry.properties
        if assign is RoleAssign.kReplace:
            if not has_role:
                raise GeometryStateError(
                    f"Trying to replace the properties on geometry id "
                    f"{geometry_id.get_value()} for the '{name}' role; it has not had the "
                    "role initially assigned"
                )
            self.touch(role)
            geometry.properties[role] = type(properties)(properties)
            return
        if has_role:
            raise DuplicateRoleError(
                f"Trying to assign the '{name}' role to geometry id "
                f"{geometry_id.get_value()} for the first time; it already has the role "
                "assigned"
            )
        if any(
            self._geometries[other].name == geometry.name
            and role in self._geometries[other].properties
            for other in self._frames[geometry.frame_id].geometries
        ):
            raise GeometryStateError(
                f"The name '{geometry.name}' has already been used by a geometry with the "
                f"'{name}' role."
            )
        self.touch(role)
        if role is Role.kProximity and isinstance(geometry.shape, _MeshShape):
            try:
                geometry.shape._check_proximity(hydroelastic=properties.HasGroup("hydroelastic"))
            except HullError:
                if release.has("hull-before-role-1.27"):
                    raise  # 1.27 makes the hull before it stores the role
                self._keep_unengined(geometry, properties)
                raise
            except RuntimeError:
                self._keep_unengined(geometry, properties)
                raise
        geometry.properties[role] = type(properties)(properties)
        if role is Role.kProximity:
            self.revision += 1
            self._assign_proximity(geometry)

    def touch(self, role: Role) -> None:
        """Marks ``role``'s data changed in ``version`` if a change of it is versioned here.

        Proximity and illustration are; perception changes only when a renderer takes
        or drops a geometry, and reimpl has none (measured on pydrake 1.51.1 and 1.58.0:
        AssignRole and RemoveRole of perception leave every version alone)."""
        if role in _VERSIONED_ROLES:
            self.version._modify(role)

    def _keep_unengined(self, geometry: _Geometry, properties: GeometryProperties) -> None:
        """What a failed proximity engine entry leaves: Drake stores the properties before
        its proximity engine computes the hull, so the geometry keeps the role, unengined."""
        geometry.properties[Role.kProximity] = type(properties)(properties)
        self.unengined.add(geometry.id)
        self.revision += 1
        if not _UNENGINED_RAISES:
            # Since 1.52 the filter keeps pairs by id: unengined, the geometry is still
            # unfiltered against everything (no same-frame pairs).
            self.collision_filter.add_geometry(geometry.id, engined=False)

    def _assign_proximity(self, geometry: _Geometry) -> None:
        """V ← V ∪ {(g, h) : h ∈ Gₚ, frame(h) = frame(g)}.

        N.B. With transient history active the invariant Apply raises after g
        has joined the filter, so g keeps its role but gets no same-frame
        invariant pairs: Drake's half-registered state, reproduced on purpose.
        """
        self.collision_filter.add_geometry(geometry.id)
        statement = Statement(
            StatementOp.kExcludeBetween,
            GeometrySet(geometry_id=geometry.id),
            GeometrySet(frame_id=geometry.frame_id),
        )
        self.collision_filter.apply([statement], self.collect_ids, is_invariant=True)

    def remove_role(self, source_id: SourceId, geometry_id: GeometryId, role: Role) -> int:
        geometry = self._owned_geometry(
            source_id,
            geometry_id,
            f"Trying to remove the role {role_name(role)} from the "
            f"geometry {geometry_id.get_value()} from source {source_id.get_value()}, but "
            "the geometry doesn't belong to that source.",
        )
        return self._remove_role(geometry, role)

    def remove_frame_role(self, source_id: SourceId, frame_id: FrameId, role: Role) -> int:
        self._source(source_id)
        frame = self._frame_of_source(source_id, frame_id)
        geometries = (
            self._sources[source_id].anchored if frame_id == WORLD_FRAME_ID else frame.geometries
        )
        return sum(self._remove_role(self._geometries[g], role) for g in list(geometries))

    def _remove_role(self, geometry: _Geometry, role: Role) -> int:
        if role is Role.kProximity and geometry.id in self.unengined:
            raise UnenginedGeometryError(_MAP_AT)
        if geometry.properties.pop(role, None) is None:
            return 0
        self.touch(role)
        if role is Role.kProximity:
            self.revision += 1
            self.collision_filter.remove_geometry(geometry.id)
        return 1

    def remove_geometry(self, source_id: SourceId, geometry_id: GeometryId) -> None:
        geometry = self._owned_geometry(
            source_id,
            geometry_id,
            f"Trying to remove geometry {geometry_id.get_value()} from source "
            f"{source_id.get_value()}, but the geometry doesn't belong to that source.",
        )
        for role in list(geometry.properties):
            self._remove_role(geometry, role)
        self._frames[geometry.frame_id].geometries.remove(geometry_id)
        if geometry.is_anchored:
            self._sources[source_id].anchored.remove(geometry_id)
        del self._geometries[geometry_id]
        self.revision += 1

    # ----------------------------------------------------------------- names
    def rename_frame(self, frame_id: FrameId, name: str) -> None:
        if frame_id not in self._frames:
            raise UnknownFrameError(
                f"Cannot rename frame with invalid frame id: {frame_id.get_value()}"
            )
        frame = self._frames[frame_id]
        source = self._sources.get(frame.source_id) if frame.source_id is not None else None
        siblings = [] if source is None else source.frames
        if any(f != frame_id and self._frames[f].name == name for f in siblings):
            raise GeometryStateError(
                f"Renaming frame from '{frame.name}' to an already existing name '{name}'"
            )
        frame.name = name

    def rename_geometry(self, geometry_id: GeometryId, name: str) -> None:
        """Renames; the name must be unique among same-role geometries on the frame."""
        if geometry_id not in self._geometries:
            raise UnknownGeometryError(
                f"Cannot rename geometry with invalid geometry id: {geometry_id.get_value()}"
            )
        geometry = self._geometries[geometry_id]
        for role in ASSIGNED_ROLES:
            if role in geometry.properties and any(
                other != geometry_id
                and self._geometries[other].name == name
                and role in self._geometries[other].properties
                for other in self._frames[geometry.frame_id].geometries
            ):
                raise GeometryStateError(
                    f"The name '{name}' has already been used by a geometry with the "
                    f"'{role_name(role)}' role."
                )
        geometry.name = name

    def geometries_registered_on(self, frame_id: FrameId) -> list[GeometryId]:
        """The frame's geometries in registration order (SceneGraphInspector::GetGeometries)."""
        if frame_id not in self._frames:
            raise UnknownFrameError(
                f"Cannot report geometries associated with invalid frame id: {frame_id.get_value()}"
            )
        return list(self._frames[frame_id].geometries)

    def clone_instance(self, geometry_id: GeometryId) -> GeometryInstance:
        """A new instance (new id) with the geometry's name, pose, shape and role properties."""
        self.geometry_name(geometry_id)  # validates, with Drake's message
        record = self._geometries[geometry_id]
        instance = GeometryInstance(X_PG=record.pose, shape=record.shape.Clone(), name=record.name)
        for properties in record.properties.values():
            if properties.role is Role.kProximity:
                instance.set_proximity_properties(properties)  # type: ignore[arg-type]
            elif properties.role is Role.kIllustration:
                instance.set_illustration_properties(properties)  # type: ignore[arg-type]
            else:
                instance.set_perception_properties(properties)  # type: ignore[arg-type]
        return instance

    # ------------------------------------------------------------ resolution
    def _proximity_on(self, frame_id: FrameId) -> list[GeometryId]:
        return [
            g
            for g in self._frames[frame_id].geometries
            if Role.kProximity in self._geometries[g].properties
        ]

    def collect_ids(self, geometry_set: GeometrySet) -> list[GeometryId]:
        """Resolves a set to proximity geometry ids, now (GeometryState::CollectIds).

        Frames are checked before geometries, as in Drake.

        Raises:
            UnknownFrameError: a FrameId is not registered.
            UnknownGeometryError: a GeometryId is not registered.
        """
        ids: dict[GeometryId, None] = {}
        for frame_id in geometry_set.frame_ids():
            self._frame(frame_id)
            ids.update(dict.fromkeys(self._proximity_on(frame_id)))
        for geometry_id in geometry_set.geometry_ids():
            geometry = self._geometries.get(geometry_id)
            if geometry is None:
                raise UnknownGeometryError(
                    "Geometry set includes a geometry id that doesn't belong to the "
                    f"SceneGraph: {geometry_id.get_value()}"
                )
            if Role.kProximity in geometry.properties:
                ids[geometry_id] = None
        return list(ids)

    def set_active(self, geometry_set: GeometrySet, *, active: bool) -> None:
        """(De)activates the set's proximity geometries (Drake ≥ 1.55: Activate, Deactivate).

        The filter's inactive set changes first; then the proximity engine is told of
        each geometry whose status changed. Up to 1.58 it looks an anchored one up among
        its dynamic objects and fails a DRAKE_DEMAND (deactivate-anchored-aborts):
        pydrake's SystemExit, with the anchored pairs already out of C (measured on
        1.55.0-1.58.0; the lines are each release's, from demand_lines.json).
        """
        changed = self.collision_filter.set_active(self.collect_ids(geometry_set), active)
        anchored = any(self._geometries[g].is_anchored for g in changed)
        if anchored and release.has("deactivate-anchored-aborts"):
            change = "activate" if active else "deactivate"
            raise failed_demand(f"ApplyActiveStatusChange.{change}")

    # ---------------------------------------------------------------- queries
    def collision_filtered(self, a: GeometryId, b: GeometryId) -> bool:
        """True iff (a, b) ∉ C, for two proximity geometries (SceneGraphInspector)."""
        ga, gb = self._geometries.get(a), self._geometries.get(b)
        if ga is None or gb is None or not (ga.has_proximity and gb.has_proximity):
            self._raise_unqueryable(a, b)
        if a == b:
            return True
        if _UNENGINED_RAISES and (a in self.unengined or b in self.unengined):
            raise UnenginedGeometryError(_MAP_AT)
        return not self.collision_filter.can_collide_with(a, b)

    def collision_candidates(self) -> set[tuple[GeometryId, GeometryId]]:
        """C, each pair (a, b) with a.get_value() < b.get_value() (SceneGraphInspector).

        Drake asks the filter about every pair of proximity geometries, so up to 1.51 an
        unengined one raises as soon as there is another; since 1.52 it is unfiltered
        against the others (unengined-geometry-unfiltered-since-1.52)."""
        proximity = sum(g.has_proximity for g in self._geometries.values())
        if _UNENGINED_RAISES and self.unengined and proximity > 1:
            raise UnenginedGeometryError(_MAP_AT)
        return self.collision_filter.candidates()

    def check_engined(self) -> None:
        """Raises as Drake's context creation does for an unengined geometry (it re-applies
        the default proximity properties to every proximity geometry, by id)."""
        if self.unengined:
            first = min(self.unengined, key=lambda g: g.get_value())
            raise GeometryStateError(
                f"The proximity engine does not contain a geometry with the id "
                f"{first.get_value()}; its properties cannot be updated"
            )

    def _raise_unqueryable(self, a: GeometryId, b: GeometryId) -> NoReturn:
        """Drake's message for CollisionFiltered of a non-proximity or unknown geometry."""
        prefix = (
            f"Can't report collision filter status between geometries {a.get_value()} and "
            f"{b.get_value()}; "
        )
        valid = [g in self._geometries for g in (a, b)]
        if not all(valid):
            if not any(valid):
                raise UnqueryableGeometryError(prefix + "neither id is a valid geometry")
            bad = a if not valid[0] else b
            raise UnqueryableGeometryError(prefix + f"{bad.get_value()} is not a valid geometry")
        proximity = [Role.kProximity in self._geometries[g].properties for g in (a, b)]
        if not any(proximity):
            raise UnqueryableGeometryError(prefix + " neither id has a proximity role")
        bad = a if not proximity[0] else b
        raise UnqueryableGeometryError(prefix + f"{bad.get_value()} does not have a proximity role")

    def has_source(self, source_id: SourceId) -> bool:
        return source_id in self._sources

    def source_name(self, source_id: SourceId) -> str:
        if source_id not in self._sources:
            raise UnknownSourceError(
                f"Querying source name for an invalid source id: {source_id.get_value()}."
            )
        return self._sources[source_id].name

    def frame_name(self, frame_id: FrameId) -> str:
        if frame_id not in self._frames:
            raise UnknownFrameError(
                f"No frame name available for invalid frame id: {frame_id.get_value()}"
            )
        return self._frames[frame_id].name

    def frame_parent(self, frame_id: FrameId) -> FrameId:
        """The frame's parent frame (the world frame's parent is itself)."""
        return self._frame(frame_id).parent_id

    def frame_group(self, frame_id: FrameId) -> int:
        return self._frame(frame_id).frame_group

    def geometry_name(self, geometry_id: GeometryId) -> str:
        if geometry_id not in self._geometries:
            raise UnknownGeometryError(
                f"No geometry available for invalid geometry id: {geometry_id.get_value()}"
            )
        return self._geometries[geometry_id].name

    def geometry_frame(self, geometry_id: GeometryId) -> FrameId:
        return self._geometry(geometry_id).frame_id

    def geometry_source(self, geometry_id: GeometryId) -> SourceId:
        return self._geometry(geometry_id).source_id

    def geometry_shape(self, geometry_id: GeometryId) -> Shape:
        return self._geometry(geometry_id).shape

    def geometry_pose(self, geometry_id: GeometryId) -> RigidTransform:
        return RigidTransform(self._geometry(geometry_id).pose)

    def properties(self, geometry_id: GeometryId, role: Role) -> GeometryProperties | None:
        return self._geometry(geometry_id, period="").properties.get(role)

    def has_role(self, geometry_id: GeometryId, role: Role) -> bool:
        return role in self._geometry(geometry_id).properties

    def source_ids(self) -> list[SourceId]:
        """Every source, SceneGraph's own first among them, in the order Drake walks them.

        N.B. That is libstdc++'s unordered_map order for Drake's hash of the ids
        (reimpl.common._std_unordered_map), not registration order.
        """
        return list(self._sources)

    def internal_source(self) -> SourceId:
        return self._internal_source

    def frame_ids(self) -> list[FrameId]:
        return list(self._frames)

    def frames_of_source(self, source_id: SourceId) -> list[FrameId]:
        return list(self._source(source_id).frames)

    def geometry_ids(self) -> list[GeometryId]:
        return list(self._geometries)

    def geometries_on(self, frame_id: FrameId) -> list[GeometryId]:
        return list(self._frame(frame_id).geometries)
