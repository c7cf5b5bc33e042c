"""Proximity queries on a real robot whose links collide through meshes: Kinova's Jaco arm.

An ordinary Drake script: the Jaco arm of Drake's ``drake_models`` package
(``jaco_description/urdf/j2s7s300_arm.urdf``: seven links whose ``<collision>``
is an ``.obj`` mesh, which Drake replaces by its convex hull) welded to the
world, a static SDFormat table top and post, then ``ComputePointPairPenetration``,
``HasCollisions``, the pairwise signed distances and the signed distance to a
point, with the arm in a few configurations (``SetPositions``). The package is
read from the vendored copy (``scenarios/real_models/drake_models``). It runs
unchanged on Drake's bindings and, with its imports switched, on reimpl
(tests/test_dropin_mesh_script.py); each line names a pair by geometry names and
shapes, so the numbers compare within the tolerances of their shape pair.

    python examples/mesh_robot_queries.py
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
from pydrake.systems.framework import DiagramBuilder

#: The repository: this file's parent's parent, or the current folder when run as ``-c``.
ROOT = Path(__file__).resolve().parents[1] if "__file__" in globals() else Path.cwd()
MODELS = ROOT / "scenarios" / "real_models" / "drake_models"
ARM = MODELS / "jaco_description" / "urdf" / "j2s7s300_arm.urdf"

TABLE = """<sdf version="1.9"><model name="table"><static>true</static>
  <link name="top"><pose>0 0 -0.03 0 0 0</pose><collision name="top">
    <geometry><box><size>1.2 1.2 0.06</size></box></geometry></collision></link>
  <link name="post"><pose>0.35 0.1 0.25 0 0 0.4</pose><collision name="post">
    <geometry><cylinder><radius>0.04</radius><length>0.5</length></cylinder></geometry>
  </collision></link>
</model></sdf>"""

#: Joint positions (the 7 arm joints, radians): clear of everything, links through each other
#: and the table, through the post, down on the table, folded over.
CONFIGURATIONS = {
    "reach": [0.0, 2.9, 0.0, 1.3, 0.0, 3.2, 0.0],
    "tangled": [1.15, 0.22, 2.18, 1.58, -2.49, 1.79, -2.33],
    "post": [1.94, -1.37, -1.88, -1.06, 0.43, 0.27, 1.55],
    "table": [0.26, 0.47, 1.74, -1.77, -0.47, 2.05, -2.28],
    "folded": [-0.95, -0.07, 1.95, 2.17, -0.71, 0.36, -0.89],
}


def fmt(x: float) -> str:
    return f"{x + 0.0:.6f}"


def main() -> None:
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlantSceneGraph(builder, time_step=0.0)
    parser = Parser(plant)
    packages = parser.package_map()
    if packages.Contains("drake_models"):
        packages.Remove("drake_models")
    packages.Add("drake_models", MODELS)
    parser.AddModels(file_name=ARM)
    parser.AddModelsFromString(TABLE, "sdf")
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("j2s7s300_link_base"))
    plant.Finalize()
    diagram = builder.Build()
    context = diagram.CreateDefaultContext()
    plant_context = plant.GetMyMutableContextFromRoot(context)
    sg_context = scene_graph.GetMyContextFromRoot(context)
    inspector = scene_graph.model_inspector()

    def name(geometry_id: Any) -> str:
        """The geometry's body (the arm's collision geometries are all named Mesh)."""
        return str(plant.GetBodyFromFrameId(inspector.GetFrameId(geometry_id)).name())

    def shape(geometry_id: Any) -> str:
        return type(inspector.GetShape(geometry_id)).__name__

    def pair(a: Any, b: Any) -> str:
        (na, sa), (nb, sb) = sorted(((name(a), shape(a)), (name(b), shape(b))))
        return f"{na} x {nb} ({sa}-{sb})"

    print("positions:", plant.num_positions())
    for label, q in CONFIGURATIONS.items():
        plant.SetPositions(plant_context, np.array(q))
        query = scene_graph.get_query_output_port().Eval(sg_context)
        print(f"-- {label}: collisions {query.HasCollisions()}")
        for p in sorted(query.ComputePointPairPenetration(), key=lambda p: pair(p.id_A, p.id_B)):
            print(f"  {pair(p.id_A, p.id_B)}: depth {fmt(p.depth)}")
        distances = query.ComputeSignedDistancePairwiseClosestPoints(max_distance=0.02)
        for d in sorted(distances, key=lambda d: pair(d.id_A, d.id_B)):
            print(f"  {pair(d.id_A, d.id_B)}: distance {fmt(d.distance)}")
        hand = plant.EvalBodyPoseInWorld(plant_context, plant.GetBodyByName("j2s7s300_link_7"))
        p_WQ = hand.translation()
        near = query.ComputeSignedDistanceToPoint(p_WQ=p_WQ, threshold=0.1)
        for r in sorted(near, key=lambda r: name(r.id_G)):
            print(
                f"  {name(r.id_G)} ({shape(r.id_G)}) to the wrist: point distance {fmt(r.distance)}"
            )


if __name__ == "__main__":
    main()
