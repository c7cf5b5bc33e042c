"""Proximity queries on a MultibodyPlant's SceneGraph, posed by the plant's positions.

An ordinary Drake script: a DiagramBuilder with ``AddMultibodyPlantSceneGraph``,
a URDF arm (a shoulder and an elbow with joint origins, its base welded over a
floor) and an SDFormat ball (a free body at its link pose), ``Finalize``, then
queries from the SceneGraph's query port and from the plant's geometry query
input, as the arm moves (``set_angle``, ``SetPositions``) and the ball is
placed (``SetFreeBodyPose``). It runs unchanged on Drake's bindings and, with
its imports switched, on reimpl (tests/test_dropin_posed_script.py), and
prints numbers to 6 decimals.

    python examples/posed_plant_queries.py
"""

from __future__ import annotations

import math
from typing import Any

from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
from pydrake.systems.framework import DiagramBuilder

ARM = """<robot name="arm">
  <link name="base"><collision name="floor"><origin xyz="0 0 -0.05"/>
    <geometry><box size="2 2 0.1"/></geometry></collision></link>
  <link name="upper"><collision name="upper"><origin xyz="0 0 0.25"/>
    <geometry><capsule radius="0.05" length="0.4"/></geometry></collision></link>
  <link name="fore"><collision name="fore"><origin xyz="0 0 0.2"/>
    <geometry><capsule radius="0.04" length="0.3"/></geometry></collision></link>
  <link name="hand"><collision name="palm"><geometry><sphere radius="0.06"/></geometry>
    </collision></link>
  <joint name="weld" type="fixed"><parent link="world"/><child link="base"/></joint>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 1 0"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/>
    <origin xyz="0 0 0.5" rpy="0 0.3 0"/><axis xyz="0 1 0"/></joint>
  <joint name="wrist" type="fixed"><parent link="fore"/><child link="hand"/>
    <origin xyz="0 0 0.4"/></joint>
</robot>"""

BALL = """<sdf version="1.9"><model name="ball"><pose>0.4 0 0.8 0 0 0</pose>
  <link name="ball"><collision name="ball">
    <geometry><sphere><radius>0.1</radius></sphere></geometry></collision></link>
</model></sdf>"""


def fmt(x: float) -> str:
    return f"{x + 0.0:.6f}"


def vec(v: Any) -> str:
    return "[" + ", ".join(fmt(float(x)) for x in v) + "]"


def report(label: str, query: Any, name: Any) -> None:
    """Penetrations and distances by geometry name (sorted), as this query object sees them."""
    print(f"-- {label}: collisions {query.HasCollisions()}")
    for pair in sorted(
        query.ComputePointPairPenetration(), key=lambda p: (name(p.id_A), name(p.id_B))
    ):
        print(f"  {name(pair.id_A)} x {name(pair.id_B)}: depth {fmt(pair.depth)}")
    distances = query.ComputeSignedDistancePairwiseClosestPoints(max_distance=0.3)
    for pair in sorted(distances, key=lambda p: tuple(sorted((name(p.id_A), name(p.id_B))))):
        a, b = sorted((name(pair.id_A), name(pair.id_B)))
        print(f"  {a} ~ {b}: distance {fmt(pair.distance)}")


def main() -> None:
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlantSceneGraph(builder, time_step=0.0)
    parser = Parser(plant)
    parser.AddModelsFromString(ARM, "urdf")
    parser.AddModelsFromString(BALL, "sdf")
    plant.Finalize()
    diagram = builder.Build()
    context = diagram.CreateDefaultContext()
    plant_context = plant.GetMyMutableContextFromRoot(context)
    sg_context = scene_graph.GetMyContextFromRoot(context)
    inspector = scene_graph.model_inspector()

    def name(geometry_id: Any) -> str:
        return str(inspector.GetName(geometry_id))

    print("positions:", plant.GetPositionNames(add_model_instance_prefix=False))
    print("default q:", vec(plant.GetPositions(plant_context)))
    hand, ball = plant.GetBodyByName("hand"), plant.GetBodyByName("ball")
    print("hand at q=0:", vec(plant.EvalBodyPoseInWorld(plant_context, hand).translation()))
    report("arm up", scene_graph.get_query_output_port().Eval(sg_context), name)

    # Bend the elbow onto the ball, through the joint.
    plant.GetJointByName("elbow").set_angle(plant_context, 0.9)
    query = plant.get_geometry_query_input_port().Eval(plant_context)
    palm = plant.GetCollisionGeometriesForBody(hand)[0]
    print("palm X_WG:", vec(query.GetPoseInWorld(geometry_id=palm).translation()))
    report("elbow 0.9", query, name)

    # Lay the arm down and drop the ball beside it, through q and a free-body pose.
    q = plant.GetPositions(plant_context)
    q[0], q[1] = math.pi / 2 - 0.3, 0.0
    plant.SetPositions(plant_context, q)
    p_WB: Any = [0.5, 0.12, 0.09]
    plant.SetFreeBodyPose(plant_context, ball, RigidTransform(RollPitchYaw(0.0, 0.0, 0.5), p_WB))
    print("q:", vec(plant.GetPositions(plant_context)))
    print("ball:", vec(plant.EvalBodyPoseInWorld(plant_context, ball).translation()))
    report("arm down", scene_graph.get_query_output_port().Eval(sg_context), name)
    pair = query.ComputeSignedDistancePairClosestPoints(
        geometry_id_A=palm, geometry_id_B=plant.GetCollisionGeometriesForBody(ball)[0]
    )
    print("palm to ball:", fmt(pair.distance))


if __name__ == "__main__":
    main()
