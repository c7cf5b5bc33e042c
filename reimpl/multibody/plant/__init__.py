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
from reimpl.geometry.scene_graph import SceneGraph
from reimpl.multibody.plant._coulomb_friction import CoulombFriction
from reimpl.multibody.plant._demands import demand_cc
from reimpl.multibody.plant._finalize import Finalization
from reimpl.multibody.plant._geometry_ports import GeometryPorts
from reimpl.multibody.plant._geometry_registration import GeometryRegistration
from reimpl.multibody.plant._state_names import StateNames
from reimpl.multibody.tree import (
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


class MultibodyPlant(Finalization, GeometryPorts, GeometryRegistration, StateNames):
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

    # ------------------------------------------------------------- ports

    # ---------------------------------------------------------- positions

    # -------------------------------------------------------------- poses

    # ------------------------------------------------------------ Finalize


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
