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

from dataclasses import dataclass
from typing import Any

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl._template import scalar_template
from reimpl.geometry.collision_filter_declaration import (
    CollisionFilterDeclaration,
    CollisionFilterScope,
)
from reimpl.geometry.geometry_set import GeometrySet
from reimpl.geometry.scene_graph import SceneGraph
from reimpl.multibody import _link_joint_graph as graph
from reimpl.multibody._default_filters import default_collision_filters
from reimpl.multibody._errors import (
    FinalizedError,
    TopologyError,
)
from reimpl.multibody._mobilizer_frames import mobilizer_frames
from reimpl.multibody.plant._coulomb_friction import CoulombFriction
from reimpl.multibody.plant._demands import demand_cc, demand_failed
from reimpl.multibody.plant._element_names import ElementNames
from reimpl.multibody.plant._geometry_ports import GeometryPorts
from reimpl.multibody.plant._geometry_registration import GeometryRegistration
from reimpl.multibody.plant._state_names import StateNames
from reimpl.multibody.tree import (
    FixedOffsetFrame,
    Joint,
    QuaternionFloatingJoint,
    RigidBody,
    world_model_instance,
)
from reimpl.systems.framework import (
    DiagramBuilder,
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


class MultibodyPlant(GeometryPorts, GeometryRegistration, StateNames, ElementNames):
    """Bodies joined by joints, grouped in model instances, with geometry in a SceneGraph.

    Finalize filters collisions, when the plant is a SceneGraph source, by
    ``C ← C − {(g,h) : frame(g)=F(child), frame(h)=F(parent)}`` for adjacent
    bodies and ``C ← C − {(g,h) : frame(g), frame(h) ∈ F(S)}`` for each welded
    set S (see reimpl.multibody._default_filters).
    """

    _cpp_type = "drake::multibody::MultibodyPlant<double>"

    def __init__(self, time_step: float) -> None:
        super().__init__()
        # N.B. pydrake 1.51.1 demands this at multibody_plant.cc:323 (SystemExit, measured).
        demand_cc(time_step >= 0, 323, "MultibodyPlant", "time_step >= 0")
        self._time_step = float(time_step)
        self._adjacent_bodies_collision_filters = True
        world = RigidBody(_WORLD_BODY_NAME, world_model_instance())
        self._add_body(world)

    # ---------------------------------------------------------------- state
    def time_step(self) -> float:
        return self._time_step

    # --------------------------------------------------------- SceneGraph

    # ----------------------------------------------------- model instances

    # ---------------------------------------------------------------- bodies

    # ---------------------------------------------------------------- frames

    # ---------------------------------------------------------------- joints

    # ------------------------------------------------------- lookup by name

    # -------------------------------------------------------------- geometry

    # --------------------------------------------------------------- welds

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
