# A two-arm cell from model files: which pairs does the collision engine consider?

from collections.abc import Callable, Iterable

from pydrake.geometry import Box, CollisionFilterDeclaration, Sphere
from pydrake.math import RigidTransform
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph, CoulombFriction
from pydrake.multibody.tree import RpyFloatingJoint
from pydrake.systems.framework import DiagramBuilder

ARM = """<?xml version="1.0"?>
<robot name="arm" xmlns:drake="http://drake.mit.edu">
  <link name="base">
    <collision name="base_box"><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
  </link>
  <link name="upper">
    <collision><geometry><cylinder radius="0.05" length="0.4"/></geometry></collision>
    <visual><geometry><cylinder radius="0.05" length="0.4"/></geometry></visual>
  </link>
  <link name="fore">
    <collision><geometry><cylinder radius="0.04" length="0.3"/></geometry></collision>
  </link>
  <link name="hand">
    <collision name="palm"><geometry><box size="0.08 0.08 0.02"/></geometry></collision>
    <collision name="finger"><geometry><box size="0.01 0.01 0.05"/></geometry></collision>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="elbow" type="continuous">
    <parent link="upper"/><child link="fore"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="wrist" type="fixed"><parent link="fore"/><child link="hand"/></joint>
  <drake:collision_filter_group name="reach">
    <drake:member link="upper"/>
    <drake:member link="hand"/>
    <drake:ignored_collision_filter_group name="reach"/>
  </drake:collision_filter_group>
</robot>
"""

BIN = """<?xml version="1.0"?>
<sdf version="1.9">
  <model name="bin">
    <link name="tray">
      <collision name="bottom"><geometry><box><size>0.5 0.5 0.02</size></box></geometry></collision>
    </link>
    <model name="lid">
      <link name="panel">
        <collision name="panel">
          <geometry><box><size>0.5 0.5 0.01</size></box></geometry>
        </collision>
      </link>
    </model>
    <joint name="hinge" type="revolute">
      <parent>tray</parent><child>lid::panel</child><axis><xyz>1 0 0</xyz></axis>
    </joint>
    <drake:collision_filter_group name="all">
      <drake:member>tray</drake:member>
      <drake:member>lid::panel</drake:member>
      <drake:ignored_collision_filter_group>all</drake:ignored_collision_filter_group>
    </drake:collision_filter_group>
  </model>
</sdf>
"""

builder = DiagramBuilder()
plant, scene_graph = AddMultibodyPlantSceneGraph(builder, 0.0)
left = Parser(plant, "left").AddModelsFromString(ARM, "urdf")
right = Parser(plant, "right").AddModelsFromString(ARM, "urdf")
bin_parser = Parser(plant)
bins = bin_parser.AddModelsFromString(BIN, "sdf")
print("models:", [plant.GetModelInstanceName(m) for m in left + right + bins])
groups = bin_parser.GetCollisionFilterGroups()
print("bin groups:", {k: sorted(v) for k, v in groups.groups().items()})
print("bin exclusions:", sorted(groups.exclusion_pairs()))

# The floor, and a free-flying tool tied to the right hand by a 6-dof joint.
plant.RegisterCollisionGeometry(
    plant.world_body(), RigidTransform(), Box(4.0, 4.0, 0.1), "floor", CoulombFriction(1.0, 1.0)
)
tool = plant.AddRigidBody("tool", plant.GetModelInstanceByName("right::arm"))
plant.RegisterCollisionGeometry(
    tool, RigidTransform(), Sphere(0.03), "tip", CoulombFriction(1.0, 1.0)
)
plant.AddJoint(
    RpyFloatingJoint(
        "tool_float", plant.GetBodyByName("hand", right[0]).body_frame(), tool.body_frame()
    )
)
plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base", left[0]))
plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base", right[0]))
plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("tray", bins[0]))
plant.Finalize()
diagram = builder.Build()

inspector = scene_graph.model_inspector()


def name(geometry_id: object) -> str:
    body = plant.GetBodyFromFrameId(inspector.GetFrameId(geometry_id))
    model = plant.GetModelInstanceName(body.model_instance())
    return f"{model}::{body.name()}/{inspector.GetName(geometry_id)}"


def show(label: str, candidates: Iterable[tuple[object, object]]) -> None:
    pairs = sorted(" - ".join(sorted((name(a), name(b)))) for a, b in candidates)
    print(f"{label}: {len(pairs)} pairs")
    for pair in pairs:
        print(f"  {pair}")


print("bodies:", plant.num_bodies(), "models:", plant.num_model_instances())
print("joints:", sorted(plant.get_joint(j).name() for j in plant.GetJointIndices()))
hand = plant.GetBodyByName("hand", left[0])
print("welded to left hand:", sorted(b.name() for b in plant.GetBodiesWeldedTo(hand)))
print(
    "left hand geometries:",
    sorted(inspector.GetName(g) for g in plant.GetCollisionGeometriesForBody(hand)),
)
print(
    "world frame:",
    plant.GetBodyFrameIdOrThrow(plant.world_body().index()) == scene_graph.world_frame_id(),
)
show("after Finalize", inspector.GetCollisionCandidates())

# On top of the parsed models: the two hands may never touch, for the whole run.
context = diagram.CreateDefaultContext()
sg_context = scene_graph.GetMyMutableContextFromRoot(context)
scene_graph.collision_filter_manager(sg_context).Apply(
    CollisionFilterDeclaration().ExcludeBetween(
        plant.CollectRegisteredGeometries([hand]),
        plant.CollectRegisteredGeometries([plant.GetBodyByName("hand", right[0])]),
    )
)
show(
    "context",
    scene_graph.get_query_output_port().Eval(sg_context).inspector().GetCollisionCandidates(),
)
checks: list[tuple[str, Callable[[], object]]] = [
    ("unknown body", lambda: plant.GetBodyByName("elbow")),
    ("late adjacency flag", lambda: plant.set_adjacent_bodies_collision_filters(False)),
    (
        "unknown link",
        lambda: Parser(AddMultibodyPlantSceneGraph(DiagramBuilder(), 0.0)[0]).AddModelsFromString(
            ARM.replace('<drake:member link="hand"/>', '<drake:member link="claw"/>'), "urdf"
        ),
    ),
]
for label, call in checks:
    try:
        call()
    except RuntimeError as e:
        print(f"{label}: {e}")
