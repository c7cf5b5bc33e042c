"""MultibodyPlant: model instances, bodies, joints, their geometry, and Finalize.

Drake counterpart: drake/multibody/plant/multibody_plant.h, as bound in
``pydrake.multibody.plant``. reimpl keeps what collision filtering and naming
need:

- Model instances 0 (``WorldModelInstance``) and 1 (``DefaultModelInstance``)
  always exist; the world body is body 0 and its frame is frame 0.
- Registered as a SceneGraph source (``RegisterAsSourceForSceneGraph``, or
  ``AddMultibodyPlantSceneGraph``), the plant gives every body but the world a
  SceneGraph frame named ``scoped(B)`` with frame group = B's instance index;
  the world body's frame is the world frame. A body's geometry goes on its
  frame (the world body's is anchored), named ``scoped(name)``.
- ``scoped(x)`` is ``instance::x`` for instances ≥ 2 and plain ``x`` in the
  world and default instances.
- ``Finalize()`` gives every tree not connected to the world a
  QuaternionFloatingJoint named after its base body (see _link_joint_graph),
  then declares the default collision filters (see _default_filters), and
  lays out the positions q (see kinematics: depth first from the world).
- A plant context holds q (initially the joints' default positions). The
  ``geometry_pose`` output port gives, for every body with a SceneGraph frame
  but the world, X_WB at the context's q (the FramePoseVector SceneGraph reads
  from its source pose port); the ``geometry_query`` input port reads the
  SceneGraph's QueryObject. ``AddMultibodyPlantSceneGraph`` connects both.
"""

from __future__ import annotations

import copy
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl._template import scalar_template
from reimpl.geometry.collision_filter_declaration import (
    CollisionFilterDeclaration,
    CollisionFilterScope,
)
from reimpl.geometry.geometry_instance import GeometryFrame, GeometryInstance
from reimpl.geometry.geometry_roles import (
    IllustrationProperties,
    PerceptionProperties,
    ProximityProperties,
)
from reimpl.geometry.geometry_set import GeometrySet
from reimpl.geometry.identifier import FrameId, GeometryId, SourceId
from reimpl.geometry.query_object import FramePoseVector
from reimpl.geometry.rgba import Rgba
from reimpl.geometry.scene_graph import SceneGraph
from reimpl.geometry.shape import Shape
from reimpl.math import RigidTransform
from reimpl.multibody import _link_joint_graph as graph
from reimpl.multibody._default_filters import default_collision_filters
from reimpl.multibody._errors import (
    FinalizedError,
    MultibodyPlantError,
    NotFoundError,
    TopologyError,
)
from reimpl.multibody._mobilizer_frames import mobilizer_frames
from reimpl.multibody.plant._coulomb_friction import CoulombFriction
from reimpl.multibody.plant._demands import demand_cc, demand_failed
from reimpl.multibody.plant._element_names import ElementNames
from reimpl.multibody.plant._poses import Poses, as_rigid_transform
from reimpl.multibody.plant._state_names import StateNames
from reimpl.multibody.tree import (
    BodyIndex,
    FixedOffsetFrame,
    Joint,
    QuaternionFloatingJoint,
    RigidBody,
    world_model_instance,
)
from reimpl.systems.framework import (
    Context,
    DiagramBuilder,
    InputPort,
    OutputPort,
)

__all__ = [
    "AddMultibodyPlant",
    "AddMultibodyPlantSceneGraph",
    "ApplyMultibodyPlantConfig",
    "CoulombFriction",
    "CoulombFriction_",
    "MultibodyPlant",
    "MultibodyPlantConfig",
    "MultibodyPlant_",
]

_OWNER = "reimpl.multibody.plant.MultibodyPlant"

_WORLD_BODY_NAME = "world"

#: Joint types a tree may model from child to parent (measured, from Finalize's message).
_REVERSIBLE_JOINT_TYPES = frozenset({"prismatic", "revolute", "weld"})

#: Where a plant context caches its frame poses (Context._values).
_FRAME_POSES = "geometry_pose"


class MultibodyPlant(Poses, StateNames, ElementNames):
    """Bodies joined by joints, grouped in model instances, with geometry in a SceneGraph.

    Finalize filters collisions, when the plant is a SceneGraph source, by
    ``C ← C − {(g,h) : frame(g)=F(child), frame(h)=F(parent)}`` for adjacent
    bodies and ``C ← C − {(g,h) : frame(g), frame(h) ∈ F(S)}`` for each welded
    set S (see reimpl.multibody._default_filters).
    """

    _cpp_type = "drake::multibody::MultibodyPlant<double>"

    def __init__(self, time_step: float) -> None:
        super().__init__()
        demand_cc(
            time_step >= 0, _DEMAND_LINES["MultibodyPlant"], "MultibodyPlant", "time_step >= 0"
        )
        self._time_step = float(time_step)
        self._scene_graph: SceneGraph | None = None
        self._source_id: SourceId | None = None
        self._body_frame_ids: dict[int, FrameId] = {}
        self._collision_geometries: dict[int, list[GeometryId]] = {}
        self._visual_geometries: dict[int, list[GeometryId]] = {}
        self._adjacent_bodies_collision_filters = True
        self._geometry_query_port = InputPort(self, "geometry_query", 0)
        self._geometry_pose_port = OutputPort(self, "geometry_pose", 0, self._calc_frame_poses)
        world = RigidBody(_WORLD_BODY_NAME, world_model_instance())
        self._add_body(world)

    # ---------------------------------------------------------------- state
    def time_step(self) -> float:
        return self._time_step

    # --------------------------------------------------------- SceneGraph
    def RegisterAsSourceForSceneGraph(self, scene_graph: SceneGraph) -> SourceId:
        """Registers this plant (by its name) as a source; every body so far gets a frame.

        Measured on pydrake 1.51.1: a second registration fails its demand before
        Finalize is checked.
        """
        method = "RegisterAsSourceForSceneGraph"
        demand_cc(
            self._source_id is None,
            _DEMAND_LINES[method],
            method,
            "!geometry_source_is_registered()",
        )
        if self._finalized:
            raise FinalizedError(
                "This MultibodyPlant is finalized already; RegisterAsSourceForSceneGraph() "
                "must be called before Finalize()."
            )
        self._source_id = scene_graph.RegisterSource(name=self.get_name())
        self._scene_graph = scene_graph
        for body in self._bodies:
            self._register_body_frame(body)
        return self._source_id

    def geometry_source_is_registered(self) -> bool:
        return self._source_id is not None

    def get_source_id(self) -> SourceId | None:
        return self._source_id

    def _registered_scene_graph(self, method: str) -> tuple[SceneGraph, SourceId]:
        """The SceneGraph and source id; pydrake's SystemExit (measured) for a public
        ``method`` of a plant that is no source, DemandFailedError for an internal one."""
        if self._scene_graph is None or self._source_id is None:
            condition = "geometry_source_is_registered()"
            if method in _DEMAND_LINES:
                demand_cc(False, _DEMAND_LINES[method], method, condition)
            raise demand_failed(method, condition)
        return self._scene_graph, self._source_id

    def _register_body_frame(self, body: RigidBody) -> None:
        index = int(body.index())
        if self._scene_graph is None or self._source_id is None:
            return
        if index == graph.WORLD:
            self._body_frame_ids[index] = self._scene_graph.world_frame_id()
            return
        frame = GeometryFrame(
            frame_name=self._scoped(body.model_instance(), body.name()),
            frame_group_id=int(body.model_instance()),
        )
        self._body_frame_ids[index] = self._scene_graph.RegisterFrame(
            source_id=self._source_id, frame=frame
        )

    # ----------------------------------------------------- model instances
    def _add_body(self, body: RigidBody) -> RigidBody:
        super()._add_body(body)
        index = int(body.index())
        self._collision_geometries[index] = []
        self._visual_geometries[index] = []
        self._register_body_frame(body)
        return body

    def _rename_instance(self, index: int, old: str, name: str) -> None:
        super()._rename_instance(index, old, name)
        if self._scene_graph is None or self._source_id is None:
            return
        scene_graph = self._scene_graph
        inspector = scene_graph.model_inspector()
        old_prefix = f"{old}::"

        def renamed(current: str) -> str | None:
            return (
                f"{name}::{current[len(old_prefix) :]}" if current.startswith(old_prefix) else None
            )

        for frame_id in inspector.FramesForSource(source_id=self._source_id):
            if inspector.GetFrameGroup(frame_id=frame_id) != index:
                continue
            new_name = renamed(inspector.GetName(frame_id=frame_id))
            if new_name is not None:
                scene_graph.RenameFrame(frame_id=frame_id, name=new_name)
            for geometry_id in inspector.GetGeometryIds(GeometrySet(frame_id=frame_id)):
                new_name = renamed(inspector.GetName(geometry_id=geometry_id))
                if new_name is not None:
                    scene_graph.RenameGeometry(geometry_id=geometry_id, name=new_name)

    # ---------------------------------------------------------------- bodies

    # ---------------------------------------------------------------- frames

    # ---------------------------------------------------------------- joints

    # ------------------------------------------------------- lookup by name

    # -------------------------------------------------------------- geometry
    def RegisterCollisionGeometry(self, *args: Any, **kwargs: Any) -> GeometryId:
        """Registers ``shape`` on ``body``'s frame with the proximity role.

        N.B. As in Drake, a duplicate name fails at the role assignment, after
        the geometry was registered: it stays in SceneGraph with no role, and
        is not listed by GetCollisionGeometriesForBody.
        """

        def with_properties(
            body: RigidBody,
            X_BG: RigidTransform,
            shape: Shape,
            name: str,
            properties: ProximityProperties,
        ) -> GeometryId:
            return self._register_collision(
                body, X_BG, shape, name, ProximityProperties(properties)
            )

        def with_friction(
            body: RigidBody,
            X_BG: RigidTransform,
            shape: Shape,
            name: str,
            coulomb_friction: CoulombFriction,
        ) -> GeometryId:
            properties = ProximityProperties()
            properties.AddProperty("material", "coulomb_friction", coulomb_friction)
            return self._register_collision(body, X_BG, shape, name, properties)

        placement = (
            Param("body", instance_of(RigidBody)),
            Param("X_BG", instance_of(RigidTransform)),
            Param("shape", instance_of(Shape)),
            Param("name", instance_of(str)),
        )
        return dispatch(  # type: ignore[no-any-return]
            _OWNER,
            "RegisterCollisionGeometry",
            (
                Overload(
                    (*placement, Param("properties", instance_of(ProximityProperties))),
                    with_properties,
                ),
                Overload(
                    (*placement, Param("coulomb_friction", instance_of(CoulombFriction))),
                    with_friction,
                ),
            ),
            args,
            kwargs,
        )

    def _register_collision(
        self,
        body: RigidBody,
        X_BG: RigidTransform,
        shape: Shape,
        name: str,
        properties: ProximityProperties,
    ) -> GeometryId:
        self._check_not_finalized("RegisterCollisionGeometry")
        scene_graph, source_id = self._registered_scene_graph("RegisterCollisionGeometry")
        instance = GeometryInstance(X_PG=X_BG, shape=shape, name=name)
        geometry_id = self._register_geometry(body, instance)
        scene_graph.AssignRole(source_id=source_id, geometry_id=geometry_id, properties=properties)
        self._collision_geometries[int(body.index())].append(geometry_id)
        return geometry_id

    def RegisterVisualGeometry(self, *args: Any, **kwargs: Any) -> GeometryId:
        """Registers geometry on ``body``'s frame with the illustration and perception roles."""

        def with_color(
            body: RigidBody, X_BG: RigidTransform, shape: Shape, name: str, diffuse_color: Any
        ) -> GeometryId:
            # N.B. Measured: an out-of-range color raises before anything registers.
            r, g, b, a = (float(v) for v in np.asarray(diffuse_color, dtype=float).reshape(4))
            diffuse = Rgba(r, g, b, a)
            illustration, perception = IllustrationProperties(), PerceptionProperties()
            for properties in (illustration, perception):
                properties.AddProperty("phong", "diffuse", diffuse)
            instance = GeometryInstance(X_PG=X_BG, shape=shape, name=name)
            return self._register_visual(body, instance, illustration, perception)

        def with_instance(body: RigidBody, geometry_instance: GeometryInstance) -> GeometryId:
            """Registers a copy of the instance (same id) with the roles it carries.

            Without any visual role it gets both, with default properties. As in
            pydrake (which copies the instance), the caller's instance is unchanged.
            """
            instance = copy.copy(geometry_instance)
            if instance.illustration_properties() is None and (
                instance.perception_properties() is None
            ):
                instance.set_illustration_properties(IllustrationProperties())
                instance.set_perception_properties(PerceptionProperties())
            return self._register_visual(body, instance, None, None)

        body = Param("body", instance_of(RigidBody))
        return dispatch(  # type: ignore[no-any-return]
            _OWNER,
            "RegisterVisualGeometry",
            (
                Overload(
                    (
                        body,
                        Param("X_BG", instance_of(RigidTransform)),
                        Param("shape", instance_of(Shape)),
                        Param("name", instance_of(str)),
                        Param("diffuse_color", _is_rgba),
                    ),
                    with_color,
                ),
                Overload(
                    (body, Param("geometry_instance", instance_of(GeometryInstance))),
                    with_instance,
                ),
            ),
            args,
            kwargs,
        )

    def _register_visual(
        self,
        body: RigidBody,
        instance: GeometryInstance,
        illustration: IllustrationProperties | None,
        perception: PerceptionProperties | None,
    ) -> GeometryId:
        """Registers ``instance`` with its roles, then ``illustration``, then ``perception``.

        N.B. Measured: a duplicate name fails on the illustration role and leaves
        the geometry registered with no role.
        """
        self._check_not_finalized("RegisterVisualGeometry")
        scene_graph, source_id = self._registered_scene_graph("RegisterVisualGeometry")
        geometry_id = self._register_geometry(body, instance)
        for properties in (illustration, perception):
            if properties is not None:
                scene_graph.AssignRole(
                    source_id=source_id, geometry_id=geometry_id, properties=properties
                )
        self._visual_geometries[int(body.index())].append(geometry_id)
        return geometry_id

    def _register_geometry(self, body: RigidBody, instance: GeometryInstance) -> GeometryId:
        """Registers ``instance`` (renamed to its scoped name) on F(body); no role yet."""
        scene_graph, source_id = self._registered_scene_graph("RegisterGeometry")
        if body._plant is not self:
            raise NotFoundError(f"Body '{body.name()}' does not belong to this MultibodyPlant.")
        instance.set_name(self._scoped(body.model_instance(), instance.name()))
        index = int(body.index())
        if index == graph.WORLD:
            return scene_graph.RegisterAnchoredGeometry(source_id=source_id, geometry=instance)
        return scene_graph.RegisterGeometry(
            source_id=source_id, frame_id=self._body_frame_ids[index], geometry=instance
        )

    def num_collision_geometries(self) -> int:
        """How many collision geometries the plant registered, on all its bodies."""
        return sum(len(ids) for ids in self._collision_geometries.values())

    def GetCollisionGeometriesForBody(self, body: RigidBody) -> list[GeometryId]:
        return list(self._collision_geometries[int(body.index())])

    def GetVisualGeometriesForBody(self, body: RigidBody) -> list[GeometryId]:
        return list(self._visual_geometries[int(body.index())])

    def GetBodyFromFrameId(self, frame_id: FrameId, /) -> RigidBody | None:
        """The body whose SceneGraph frame is ``frame_id``, else None.

        N.B. pydrake binds the parameter without a name: it is positional only.
        """
        for index, body_frame_id in self._body_frame_ids.items():
            if body_frame_id == frame_id:
                return self._bodies[index]
        return None

    def GetBodyFrameIdIfExists(self, body_index: BodyIndex) -> FrameId | None:
        return self._body_frame_ids.get(int(body_index))

    def GetBodyFrameIdOrThrow(self, body_index: BodyIndex) -> FrameId:
        body = self.get_body(body_index)
        frame_id = self._body_frame_ids.get(int(body_index))
        if frame_id is None:
            raise NotFoundError(f"Body '{body.name()}' does not have geometry registered with it.")
        return frame_id

    def CollectRegisteredGeometries(self, bodies: Sequence[RigidBody]) -> GeometrySet:
        """GeometrySet({F(B) : B ∈ bodies}); F(world) is the world frame.

        It holds frames, not geometries, so it resolves when a declaration is
        applied: F(world) then means every anchored proximity geometry.
        """
        self._registered_scene_graph("CollectRegisteredGeometries")
        return self._collect([int(body.index()) for body in bodies])

    def _collect(self, bodies: Sequence[int]) -> GeometrySet:
        return GeometrySet(frame_ids=[self._body_frame_ids[b] for b in bodies])

    # --------------------------------------------------------------- welds

    def EvalSceneGraphInspector(self, context: Context) -> Any:
        """The inspector of the QueryObject on the ``geometry_query`` port."""
        port = self.get_geometry_query_input_port()
        if not port.HasValue(context):
            raise MultibodyPlantError(
                "EvalSceneGraphInspector\n\nThe provided context doesn't show a connection for "
                "the plant's query input port (see "
                "MultibodyPlant::get_geometry_query_input_port()). See "
                "https://drake.mit.edu/troubleshooting.html#mbp-unconnected-query-object-port "
                "for help."
            )
        return port.Eval(context).inspector()

    # -------------------------------------------------------------- filters
    def set_adjacent_bodies_collision_filters(self, value: bool) -> None:
        """Whether Finalize filters adjacent bodies (rule (a)); welds are filtered anyway."""
        self._check_not_finalized("set_adjacent_bodies_collision_filters")
        self._adjacent_bodies_collision_filters = bool(value)

    def get_adjacent_bodies_collision_filters(self) -> bool:
        return self._adjacent_bodies_collision_filters

    def _exclude_collision_geometries_with_collision_filter_group_pair(
        self, group_a: tuple[str, GeometrySet], group_b: tuple[str, GeometrySet]
    ) -> None:
        """A collision filter group pair, for the parser (C++ only; pydrake binds none).

        Same name: C ← C − {(g, h) : g, h ∈ set_A, g ≠ h} (ExcludeWithin);
        else C ← C − {(g, h) : g ∈ set_A, h ∈ set_B} (ExcludeBetween). Scope
        kAll, applied to the SceneGraph model; allowed only before Finalize
        and with a registered SceneGraph (Drake demands both).
        """
        method = "ExcludeCollisionGeometriesWithCollisionFilterGroupPair"
        if self._finalized:
            raise demand_failed(method, "!is_finalized()")
        scene_graph, _ = self._registered_scene_graph(method)
        (name_a, set_A), (name_b, set_B) = group_a, group_b
        declaration = CollisionFilterDeclaration(CollisionFilterScope.kAll)
        if name_a == name_b:
            declaration.ExcludeWithin(set_A)
        else:
            declaration.ExcludeBetween(set_A, set_B)
        scene_graph.collision_filter_manager().Apply(declaration=declaration)

    # ------------------------------------------------------------- ports
    def get_geometry_query_input_port(self) -> InputPort:
        return self._geometry_query_port

    def get_geometry_pose_output_port(self) -> OutputPort:
        return self._geometry_pose_port

    def _calc_frame_poses(self, context: Context) -> FramePoseVector:
        """{F(B): X_WB} for every body B but the world that has a SceneGraph frame.

        Like Drake's cached output, the same vector is returned while q is
        unchanged (so SceneGraph need not re-pose).
        """
        key = self._context_positions(context).tobytes()
        cached = context._values.get(_FRAME_POSES)
        if cached is not None and cached[0] == key:
            return cached[1]  # type: ignore[no-any-return]
        poses = FramePoseVector()
        world_poses = self._body_poses(context)
        for index, frame_id in self._body_frame_ids.items():
            if index != graph.WORLD:
                poses.set_value(frame_id, as_rigid_transform(world_poses[index]))
        context._values[_FRAME_POSES] = (key, poses)
        return poses

    # ---------------------------------------------------------- positions

    # -------------------------------------------------------------- poses

    # ------------------------------------------------------------ Finalize
    def Finalize(self) -> None:
        """Adds the floating joints, then the default collision filters; seals the model."""
        if self._finalized:
            raise FinalizedError("MultibodyTreeSystem::Finalize(): repeated calls not allowed.")
        n = len(self._bodies)
        if graph.has_loop(n, self._edges()):
            raise TopologyError(
                "The bodies and joints of this system form one or more loops in the system "
                "graph. Drake currently does not support automatic modeling of such systems; "
                "however, they can be modeled with some input changes. See "
                "https://drake.mit.edu/troubleshooting.html#mbp-loops-in-graph for advice on how "
                "to model systems with loops."
            )
        bases = graph.floating_bases(n, self._edges())
        for index in graph.reversed_joints(n, self._edges(), bases):
            self._check_reversible(self._joints[index])
        for base in bases:
            self._add_floating_joint(self._bodies[base])
        self._lay_out_positions()
        self._add_mobilizer_frames()
        # N.B. Measured: the plant is finalized before its filters are applied, so
        # an Apply that raises (transient history active) leaves it finalized,
        # unfiltered, and refusing a second Finalize.
        self._finalized = True
        if self._scene_graph is not None:
            declaration = default_collision_filters(
                self._joints,
                graph.welded_subgraphs(n, self._edges()),
                self._collect,
                adjacent=self._adjacent_bodies_collision_filters,
            )
            self._scene_graph.collision_filter_manager().Apply(declaration=declaration)

    def _add_mobilizer_frames(self) -> None:
        """The ephemeral frames of ``_mobilizer_frames``, in the order the tree is walked."""
        assert self._forest is not None
        for mobilizer in self._forest.mobilizers:
            joint = self._joints[mobilizer.joint]
            for suffix, base, X in mobilizer_frames(joint, mobilizer.reversed):
                instance = joint.model_instance()
                name = f"{joint.name()}_{base.name()}_{suffix}"
                while self._named(self._frames, name, instance):
                    name = f"_{name}"
                frame = FixedOffsetFrame(name, base, X, instance)
                frame._ephemeral = True
                self.AddFrame(frame)

    def _check_reversible(self, joint: Joint) -> None:
        """Raises Drake's error unless a tree may model ``joint`` from child to parent."""
        if joint.type_name() in _REVERSIBLE_JOINT_TYPES:
            return
        kind = joint.type_name()
        raise TopologyError(
            f"MultibodyPlant::Finalize(): parent/child ordering for {kind} joint "
            f"{joint.name()} in model instance {self.GetModelInstanceName(joint.model_instance())} "
            "would have to be reversed to make a tree-structured model for this system. "
            f"Currently Drake does not support reversed {kind} joints. The joints that can be "
            f"reversed are: {', '.join(sorted(_REVERSIBLE_JOINT_TYPES))}. Reverse the ordering in "
            "your joint definition so that its parent body is closer to World in the tree."
        )

    def _add_floating_joint(self, body: RigidBody) -> None:
        """A QuaternionFloatingJoint world → body, named after the body.

        The name gets leading underscores until no joint of the body's
        instance has it (measured: ``X`` taken, ``_X`` taken → ``__X``).
        """
        name = body.name()
        while self._named(self._joints, name, body.model_instance()):
            name = f"_{name}"
        joint = QuaternionFloatingJoint(name, self.world_frame(), body.body_frame())
        joint._ephemeral = True
        X_WB = self._default_free_body_poses.get(int(body.index()))
        if X_WB is not None:
            joint._set_default_pose(X_WB)
        self.AddJoint(joint)


#: Where multibody_plant.cc (pydrake 1.51.1) demands what the public methods check
#: with DRAKE_DEMAND / DRAKE_THROW_UNLESS: a plant that is (not) a SceneGraph source, a
#: nonnegative time step. pydrake raises SystemExit (measured; 1.58.0 reports other lines).
_DEMAND_LINES = {
    "MultibodyPlant": 323,
    "RegisterAsSourceForSceneGraph": 1036,
    "RegisterVisualGeometry": 1074,
    "RegisterCollisionGeometry": 1139,
    "CollectRegisteredGeometries": 1178,
}


def _is_rgba(value: object) -> bool:
    try:
        return np.asarray(value, dtype=float).shape in {(4,), (4, 1)}
    except (TypeError, ValueError):
        return False


_is_rgba.__name__ = "numpy.ndarray[numpy.float64[4, 1]]"


def AddMultibodyPlantSceneGraph(*args: Any, **kwargs: Any) -> tuple[MultibodyPlant, SceneGraph]:
    """Adds a plant (given, or made with ``time_step``) and a SceneGraph to ``builder``.

    The plant is named ``plant``, the SceneGraph ``scene_graph``, and the
    plant is registered as its source; the plant's ``geometry_pose`` output
    feeds the source's pose port and the SceneGraph's ``query`` output feeds
    the plant's ``geometry_query`` input. Returns ``(plant, scene_graph)``.

    N.B. pydrake also connects the deformable configuration ports; reimpl has
    no deformable bodies and does not.
    """

    def add(
        builder: DiagramBuilder, plant: MultibodyPlant, scene_graph: SceneGraph | None
    ) -> tuple[MultibodyPlant, SceneGraph]:
        if scene_graph is None:
            scene_graph = SceneGraph()
            scene_graph.set_name("scene_graph")
        # N.B. Measured: a given plant is renamed; a given SceneGraph keeps its name.
        plant.set_name("plant")
        builder.AddSystem(plant)
        builder.AddSystem(scene_graph)
        source_id = plant.RegisterAsSourceForSceneGraph(scene_graph)
        builder.Connect(
            plant.get_geometry_pose_output_port(), scene_graph.get_source_pose_port(source_id)
        )
        builder.Connect(scene_graph.get_query_output_port(), plant.get_geometry_query_input_port())
        return plant, scene_graph

    def with_time_step(
        builder: DiagramBuilder, time_step: float, scene_graph: SceneGraph | None
    ) -> tuple[MultibodyPlant, SceneGraph]:
        return add(builder, MultibodyPlant(time_step), scene_graph)

    builder = Param("builder", instance_of(DiagramBuilder))
    scene_graph = Param("scene_graph", instance_of(SceneGraph), None)
    return dispatch(  # type: ignore[no-any-return]
        "reimpl.multibody.plant",
        "AddMultibodyPlantSceneGraph",
        (
            Overload((builder, Param("plant", instance_of(MultibodyPlant)), scene_graph), add),
            Overload(
                (builder, Param("time_step", instance_of(int, float)), scene_graph), with_time_step
            ),
        ),
        args,
        kwargs,
    )


@dataclass(kw_only=True)
class MultibodyPlantConfig:
    """Plant settings with pydrake's defaults; reimpl reads ``time_step`` and the flag only."""

    time_step: float = 0.001
    use_sampled_output_ports: bool = True
    penetration_allowance: float = 0.001
    stiction_tolerance: float = 0.0001
    contact_model: str = "hydroelastic_with_fallback"
    discrete_contact_approximation: str = "lagged"
    sap_near_rigid_threshold: float = 1.0
    contact_surface_representation: str = "polygon"
    adjacent_bodies_collision_filters: bool = True


def ApplyMultibodyPlantConfig(config: MultibodyPlantConfig, plant: MultibodyPlant) -> None:
    """Applies every setting but ``time_step`` (which only construction sets)."""
    plant.set_adjacent_bodies_collision_filters(config.adjacent_bodies_collision_filters)


def AddMultibodyPlant(
    config: MultibodyPlantConfig, builder: DiagramBuilder
) -> tuple[MultibodyPlant, SceneGraph]:
    """AddMultibodyPlantSceneGraph with ``config.time_step``, then the rest of ``config``."""
    plant, scene_graph = AddMultibodyPlantSceneGraph(builder=builder, time_step=config.time_step)
    ApplyMultibodyPlantConfig(config, plant)
    return plant, scene_graph


MultibodyPlant_ = scalar_template("reimpl.multibody.plant", "MultibodyPlant_", MultibodyPlant)
CoulombFriction_ = scalar_template("reimpl.multibody.plant", "CoulombFriction_", CoulombFriction)

# Public names report this module, as pydrake's report theirs (reprs, pickles, help).
CoulombFriction.__module__ = __name__
