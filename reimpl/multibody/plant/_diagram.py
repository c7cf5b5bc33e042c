"""Adding a plant and its SceneGraph to a diagram: the functions and their config.

Drake counterpart: ``AddMultibodyPlantSceneGraph`` (multibody_plant.h),
``MultibodyPlantConfig`` and ``AddMultibodyPlant``/``ApplyMultibodyPlantConfig``
(multibody_plant_config_functions.h). The plant is named ``plant``, registered
as the SceneGraph's source, and wired both ways: its ``geometry_pose`` output
to the source's pose port, the SceneGraph's ``query`` output to its
``geometry_query`` input. Of a config reimpl reads ``time_step`` and
``adjacent_bodies_collision_filters`` only.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl._release import release
from reimpl.geometry.scene_graph import SceneGraph
from reimpl.multibody.plant._multibody_plant import MultibodyPlant
from reimpl.systems.framework import DiagramBuilder

__all__ = [
    "AddMultibodyPlant",
    "AddMultibodyPlantSceneGraph",
    "ApplyMultibodyPlantConfig",
    "MultibodyPlantConfig",
]


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
    if release.has("adjacent-filters-opt-out-since-1.13"):
        plant.set_adjacent_bodies_collision_filters(config.adjacent_bodies_collision_filters)


def AddMultibodyPlant(
    config: MultibodyPlantConfig, builder: DiagramBuilder
) -> tuple[MultibodyPlant, SceneGraph]:
    """AddMultibodyPlantSceneGraph with ``config.time_step``, then the rest of ``config``."""
    plant, scene_graph = AddMultibodyPlantSceneGraph(builder=builder, time_step=config.time_step)
    ApplyMultibodyPlantConfig(config, plant)
    return plant, scene_graph
