"""SceneGraph: registration, roles, contexts, and access to C's managers.

Drake counterpart: drake/geometry/scene_graph.h. SceneGraph owns the *model*
GeometryState. ``CreateDefaultContext()`` gives each context its own deep copy,
filters and transient history included; from then on the model and the context
are independent. ``collision_filter_manager()`` edits the model,
``collision_filter_manager(context)`` edits that context only.

N.B. Contexts copy a *cached* model (measured on pydrake 1.12-1.58; the
"stale manager" of pydrake-observed.md §2). The cache is refreshed by
CreateDefaultContext/SetDefaultContext only when it is marked dirty, and only
SceneGraph's own model-editing methods, and ``collision_filter_manager()``,
mark it, even when they then raise. Edits through a manager held from earlier
do not, so contexts made afterwards miss them until one of those calls.
"""

from __future__ import annotations

from typing import Any
from weakref import WeakKeyDictionary

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl._release import release
from reimpl._template import scalar_template
from reimpl.geometry.collision_filter_manager import CollisionFilterManager
from reimpl.geometry.geometry_instance import GeometryFrame, GeometryInstance
from reimpl.geometry.geometry_roles import (
    IllustrationProperties,
    PerceptionProperties,
    ProximityProperties,
    Role,
    RoleAssign,
)
from reimpl.geometry.geometry_state import WORLD_FRAME_ID, GeometryState
from reimpl.geometry.identifier import FrameId, GeometryId, SourceId
from reimpl.geometry.pose_update import (
    PoseMode,
    on_set_default_context,
    pose_mode,
    posed_from_ports,
)
from reimpl.geometry.query_object import PosedState, QueryObject
from reimpl.geometry.scene_graph_inspector import SceneGraphInspector
from reimpl.systems._context_keyword import context_argument
from reimpl.systems.framework import Context, InputPort, LeafContext, LeafSystem, OutputPort

__all__ = ["SceneGraph", "SceneGraph_"]

_OWNER = "reimpl.geometry.SceneGraph"

_properties = instance_of(ProximityProperties, PerceptionProperties, IllustrationProperties)


#: Input ports a source adds: its pose port and its configuration port.
_PORTS_PER_SOURCE = 2


class SceneGraph(LeafSystem):
    """The geometry system: owns the model, makes contexts, hands out views."""

    _cpp_type = "drake::geometry::SceneGraph<double>"

    def __init__(self) -> None:
        super().__init__()
        self._model = GeometryState()
        self._cache = self._model
        self._dirty = True
        self._pose_ports: dict[SourceId, InputPort] = {}
        self._configuration_ports: dict[SourceId, InputPort] = {}
        self._num_input_ports = 0
        self._query_port = OutputPort(self, "query", 0, self._eval_query)
        # Each context's posed proximity engine, kept while the context lives.
        self._posed_states: WeakKeyDictionary[Context, PosedState] = WeakKeyDictionary()
        self._model_inspector = SceneGraphInspector._view(lambda: self._model)

    # ------------------------------------------------------------- helpers
    def _edit_model(self) -> GeometryState:
        """The model, for one of the calls that mark the context cache dirty."""
        self._dirty = True
        return self._model

    def _default_state(self) -> GeometryState:
        """A copy of the cached model, refreshing the cache first if it is dirty.

        Raises as Drake does if the model has an unengined geometry (``GeometryState``)."""
        self._model.check_engined()
        if self._dirty:
            self._cache = self._model.clone()
            self._dirty = False
        return self._cache.clone()

    def _state_of(self, context: Context | None) -> GeometryState:
        if context is None:
            return self._edit_model()
        self.ValidateContext(context)
        return context._geometry_state

    # -------------------------------------------------------- registration
    def RegisterSource(self, name: str = "") -> SourceId:
        model = self._edit_model()
        source_id = model.register_source(name)
        name = model.source_name(source_id)
        # Drake gives every source two input ports: poses, then configurations.
        index = self.num_input_ports()
        self._pose_ports[source_id] = InputPort(self, f"{name}_pose", index)
        self._configuration_ports[source_id] = InputPort(self, f"{name}_configuration", index + 1)
        self._num_input_ports = index + _PORTS_PER_SOURCE
        return source_id

    def num_input_ports(self) -> int:
        return self._num_input_ports

    def RegisterFrame(self, *args: Any, **kwargs: Any) -> FrameId:
        return dispatch(  # type: ignore[no-any-return]
            _OWNER, "RegisterFrame", _REGISTER_FRAME, args, kwargs, receiver=self
        )

    def _register_frame(
        self, source_id: SourceId, frame: GeometryFrame, parent_id: FrameId = WORLD_FRAME_ID
    ) -> FrameId:
        return self._edit_model().register_frame(source_id, parent_id, frame)

    def RegisterGeometry(self, *args: Any, **kwargs: Any) -> GeometryId:
        return dispatch(  # type: ignore[no-any-return]
            _OWNER, "RegisterGeometry", _REGISTER_GEOMETRY, args, kwargs, receiver=self
        )

    def _register_geometry(
        self,
        source_id: SourceId,
        frame_id: FrameId,
        geometry: GeometryInstance,
        context: Context | None = None,
    ) -> GeometryId:
        return self._state_of(context).register_geometry(source_id, frame_id, geometry)

    def RegisterAnchoredGeometry(
        self, source_id: SourceId, geometry: GeometryInstance
    ) -> GeometryId:
        return self._edit_model().register_geometry(source_id, WORLD_FRAME_ID, geometry)

    # --------------------------------------------------------------- roles
    def AssignRole(self, *args: Any, **kwargs: Any) -> None:
        dispatch(_OWNER, "AssignRole", _ASSIGN_ROLE, args, kwargs, receiver=self)

    def _assign_role(
        self,
        source_id: SourceId,
        geometry_id: GeometryId,
        properties: ProximityProperties,
        assign: RoleAssign,
        context: Context | None = None,
    ) -> None:
        self._state_of(context).assign_role(source_id, geometry_id, properties, assign)

    def RemoveRole(self, *args: Any, **kwargs: Any) -> int:
        """Removes ``role`` from one geometry, or from a frame's geometries; returns a count."""
        return dispatch(  # type: ignore[no-any-return]
            _OWNER, "RemoveRole", _REMOVE_ROLE, args, kwargs, receiver=self
        )

    def _remove_frame_role(
        self, source_id: SourceId, frame_id: FrameId, role: Role, context: Context | None = None
    ) -> int:
        return self._state_of(context).remove_frame_role(source_id, frame_id, role)

    def _remove_geometry_role(
        self,
        source_id: SourceId,
        geometry_id: GeometryId,
        role: Role,
        context: Context | None = None,
    ) -> int:
        return self._state_of(context).remove_role(source_id, geometry_id, role)

    def RemoveGeometry(self, *args: Any, **kwargs: Any) -> None:
        dispatch(_OWNER, "RemoveGeometry", _REMOVE_GEOMETRY, args, kwargs, receiver=self)

    def _remove_geometry(
        self, source_id: SourceId, geometry_id: GeometryId, context: Context | None = None
    ) -> None:
        self._state_of(context).remove_geometry(source_id, geometry_id)

    # -------------------------------------------------------------- names
    def RenameFrame(self, frame_id: FrameId, name: str) -> None:
        """Renames a frame of the model; another frame of its source may not have ``name``."""
        self._edit_model().rename_frame(frame_id, name)

    def RenameGeometry(self, geometry_id: GeometryId, name: str) -> None:
        """Renames a geometry of the model; the name must stay unique per role on its frame."""
        self._edit_model().rename_geometry(geometry_id, name)

    # --------------------------------------------------------------- views
    @staticmethod
    def world_frame_id() -> FrameId:
        return WORLD_FRAME_ID

    def model_inspector(self) -> SceneGraphInspector:
        """The model's inspector: one live view, the same object on every call."""
        return self._model_inspector

    def collision_filter_manager(self, *args: Any, **kwargs: Any) -> CollisionFilterManager:
        return dispatch(  # type: ignore[no-any-return]
            _OWNER, "collision_filter_manager", _MANAGER_OVERLOADS, args, kwargs, receiver=self
        )

    # ------------------------------------------------------------ contexts
    def _model_manager(self) -> CollisionFilterManager:
        # Handing out a manager counts as a proximity change (Drake's GeometryState).
        self._edit_model().touch(Role.kProximity)
        return CollisionFilterManager._view(lambda: self._model)

    def _context_manager(self, context: Context) -> CollisionFilterManager:
        self._state_of(context).touch(Role.kProximity)
        return CollisionFilterManager._view(lambda: context._geometry_state)

    def _new_context(self) -> Context:
        context = LeafContext._for(self, self.num_input_ports())
        context._geometry_state = self._default_state()
        return context

    @context_argument
    def SetDefaultContext(self, context: Context) -> None:
        """Resets the context's geometry state to a copy of the (cached) model.

        N.B. With the model's poses: see reimpl.geometry.pose_update.
        """
        self._state_of(context)
        on_set_default_context(context)
        context._geometry_state = self._default_state()

    def get_query_output_port(self) -> OutputPort:
        return self._query_port

    def get_source_pose_port(self, source_id: SourceId, /) -> InputPort:
        if source_id not in self._pose_ports:
            raise RuntimeError(
                f"Can't acquire pose port for unknown source id: {source_id.get_value()}."
            )
        return self._pose_ports[source_id]

    def get_source_configuration_port(self, source_id: SourceId, /) -> InputPort:
        """The port for deformable configurations; reimpl only names it."""
        if source_id not in self._configuration_ports:
            raise RuntimeError(
                f"Can't acquire configuration port for unknown source id: {source_id.get_value()}."
            )
        return self._configuration_ports[source_id]

    def _eval_query(self, context: Context) -> QueryObject:
        self._state_of(context)
        context._clone_check = self._check_pose_inputs
        return QueryObject._make(lambda: context._geometry_state, lambda: self._posed(context))

    def _pose_tracked(self, context: Context) -> bool:
        """Whether reimpl sees every change to the pose ports' values (none is connected)."""
        return all(port._source(context) is None for port in self._pose_ports.values())

    def _posed(self, context: Context) -> PosedState:
        """The context's state, posed as its pose update says (reimpl.geometry.pose_update).

        The engine is rebuilt when the context's state changed, re-posed when a
        pose port's vector changed, and otherwise reused as it is.
        """
        state = context._geometry_state
        posed = self._posed_states.get(context)
        if posed is None or posed.state is not state or posed.revision != state.revision:
            posed = PosedState(state)
            self._posed_states[context] = posed
        if pose_mode(context) is PoseMode.MODEL_DEFAULTS:
            posed.pose_model_defaults()
            return posed
        posed.pose([self._pose_ports[s.source_id]._eval(context) for s in posed.sources])
        if self._pose_tracked(context):
            posed_from_ports(context)
        return posed

    def _check_pose_inputs(self, context: Context) -> None:
        """Why Clone() fails after the query port was evaluated without poses.

        N.B. Measured on pydrake: once the query port has been evaluated,
        cloning the context runs the pose update if it is out of date, with
        the checks and messages of a query's.
        """
        if pose_mode(context) is PoseMode.OUT_OF_DATE:
            self._posed(context)


# pydrake's overload sets, in pydrake's order, built once: binding is the only per-call work.
_CONTEXT = Param("context", instance_of(Context))
_SOURCE = Param("source_id", instance_of(SourceId))
_FRAME = Param("frame_id", instance_of(FrameId))
_GEOMETRY = Param("geometry_id", instance_of(GeometryId))
_ROLE = Param("role", instance_of(Role))


def _model_then_context(params: tuple[Param, ...], impl: Any) -> tuple[Overload, Overload]:
    """The model overload ``params``, then the context overload ``(context, *params)``."""
    return Overload(params, impl), Overload((_CONTEXT, *params), impl)


_REGISTER_FRAME = (
    Overload((_SOURCE, Param("frame", instance_of(GeometryFrame))), SceneGraph._register_frame),
    Overload(
        (
            _SOURCE,
            Param("parent_id", instance_of(FrameId)),
            Param("frame", instance_of(GeometryFrame)),
        ),
        SceneGraph._register_frame,
    ),
)
_REGISTER_GEOMETRY = _model_then_context(
    (_SOURCE, _FRAME, Param("geometry", instance_of(GeometryInstance))),
    SceneGraph._register_geometry,
)
_ASSIGN_ROLE = _model_then_context(
    (
        _SOURCE,
        _GEOMETRY,
        Param("properties", _properties),
        Param("assign", instance_of(RoleAssign), RoleAssign.kNew),
    ),
    SceneGraph._assign_role,
)
#: RemoveRole by frame, then by geometry, each without and with a context; up to 1.12
#: only RemoveRole(source_id, geometry_id, role) is bound (remove-role-by-frame-since-1.13:
#: measured on pydrake 1.12.0, one overload, and 1.13.0, these four).
_REMOVE_ROLE = (
    (
        *_model_then_context((_SOURCE, _FRAME, _ROLE), SceneGraph._remove_frame_role),
        *_model_then_context((_SOURCE, _GEOMETRY, _ROLE), SceneGraph._remove_geometry_role),
    )
    if release.has("remove-role-by-frame-since-1.13")
    else (Overload((_SOURCE, _GEOMETRY, _ROLE), SceneGraph._remove_geometry_role),)
)
_REMOVE_GEOMETRY = _model_then_context((_SOURCE, _GEOMETRY), SceneGraph._remove_geometry)

#: collision_filter_manager(context) and collision_filter_manager(), in pydrake's order.
_MANAGER_OVERLOADS = (
    Overload((Param("context", instance_of(Context)),), SceneGraph._context_manager),
    Overload((), SceneGraph._model_manager),
)

SceneGraph_ = scalar_template("reimpl.geometry", "SceneGraph_", SceneGraph)
