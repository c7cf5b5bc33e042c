# Ported from Drake: multibody/plant/test/multibody_plant_test.cc at v1.51.1
# (https://github.com/RobotLocomotion/drake), the cases whose outcome is which geometry
# pairs are filtered or candidates, how geometry registers, or an error, re-expressed
# as pytest functions that run unchanged on pydrake and on reimpl. Expected values are
# upstream's; where Python observes less or otherwise than C++ (no GeometrySetTester,
# DRAKE_DEMAND as SystemExit), the value asserted was measured on pydrake 1.51.1 and
# 1.58.0, and the comment says so.
#
# Drake's license (BSD 3-Clause), which covers the upstream test this file is ported from:
#
#   Copyright 2012-2022, Robot Locomotion Group @ CSAIL, Massachusetts Institute of Technology
#   All rights reserved.
#
#   Redistribution and use in source and binary forms, with or without modification, are
#   permitted provided that the following conditions are met:
#
#   1. Redistributions of source code must retain the above copyright notice, this list of
#      conditions and the following disclaimer.
#   2. Redistributions in binary form must reproduce the above copyright notice, this list of
#      conditions and the following disclaimer in the documentation and/or other materials
#      provided with the distribution.
#   3. Neither the name of the copyright holder nor the names of its contributors may be used
#      to endorse or promote products derived from this software without specific prior
#      written permission.
#
#   THIS SOFTWARE IS PROVIDED BY THE COPYRIGHT HOLDERS AND CONTRIBUTORS "AS IS" AND ANY
#   EXPRESS OR IMPLIED WARRANTIES, INCLUDING, BUT NOT LIMITED TO, THE IMPLIED WARRANTIES OF
#   MERCHANTABILITY AND FITNESS FOR A PARTICULAR PURPOSE ARE DISCLAIMED. IN NO EVENT SHALL THE
#   COPYRIGHT HOLDER OR CONTRIBUTORS BE LIABLE FOR ANY DIRECT, INDIRECT, INCIDENTAL, SPECIAL,
#   EXEMPLARY, OR CONSEQUENTIAL DAMAGES (INCLUDING, BUT NOT LIMITED TO, PROCUREMENT OF
#   SUBSTITUTE GOODS OR SERVICES; LOSS OF USE, DATA, OR PROFITS; OR BUSINESS INTERRUPTION)
#   HOWEVER CAUSED AND ON ANY THEORY OF LIABILITY, WHETHER IN CONTRACT, STRICT LIABILITY, OR
#   TORT (INCLUDING NEGLIGENCE OR OTHERWISE) ARISING IN ANY WAY OUT OF THE USE OF THIS
#   SOFTWARE, EVEN IF ADVISED OF THE POSSIBILITY OF SUCH DAMAGE.
"""Upstream MultibodyPlant C++ tests, collision-filter subset, on pydrake and on reimpl."""

from __future__ import annotations

import re
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest

from conformance._backends.api import Api


def _demand_line(api: Api, lines: tuple[int, int]) -> int:
    """multibody_plant.cc's line of a DRAKE_DEMAND: (1.51.1's, 1.58.0's), both measured."""
    return lines[0] if api.version == "1.51.1" else lines[1]


def _spatial_inertia(drake: ModuleType) -> Any:
    """A non-zero spatial inertia (upstream's MakeUnitary has no binding)."""
    return drake.multibody.tree.SpatialInertia.SolidSphereWithMass(mass=1.0, radius=0.5)


class SphereChainScenario:
    """Upstream's SphereChainScenario: a ground half-space and a chain of spheres
    S0 → S1 → … joined by revolute hinges about y, or welds where ``weld_to_next[k]``;
    then a body with no geometry. All overlap in the zero configuration.
    """

    def __init__(self, drake: ModuleType, sphere_count: int, weld_to_next: tuple[int, ...] = ()):
        self.drake = drake
        g, mp, math = drake.geometry, drake.multibody.plant, drake.math
        self.sphere_count = sphere_count
        self.builder = drake.systems.framework.DiagramBuilder()
        self.plant, self.scene_graph = mp.AddMultibodyPlantSceneGraph(self.builder, 0.0)
        plant = self.plant
        self.ground_id = plant.RegisterCollisionGeometry(
            plant.world_body(),
            g.HalfSpace.MakePose(np.array([0.0, 1.0, 0.0]), np.zeros(3)),
            g.HalfSpace(),
            "ground",
            mp.CoulombFriction(),
        )
        self.spheres = []
        self.sphere_ids = []
        for i in range(sphere_count):
            sphere = plant.AddRigidBody(f"Sphere{i}", _spatial_inertia(drake))
            self.sphere_ids.append(
                plant.RegisterCollisionGeometry(
                    sphere, math.RigidTransform(), g.Sphere(0.5), "collision", mp.CoulombFriction()
                )
            )
            # Visual geometry, to test that it is *not* in the collision results.
            plant.RegisterVisualGeometry(
                sphere, math.RigidTransform(), g.Sphere(0.5), "visual", [0.5, 0.5, 0.5, 1.0]
            )
            self.spheres.append(sphere)
        welds = list(weld_to_next) + [0] * (sphere_count - 1 - len(weld_to_next))
        for i in range(sphere_count - 1):
            if welds[i]:
                plant.WeldFrames(self.spheres[i].body_frame(), self.spheres[i + 1].body_frame())
            else:
                plant.AddJoint(
                    drake.multibody.tree.RevoluteJoint(
                        f"hinge{i}_{i + 1}",
                        self.spheres[i].body_frame(),
                        self.spheres[i + 1].body_frame(),
                        [0.0, 1.0, 0.0],
                    )
                )
        self.no_geometry_body = plant.AddRigidBody("NothingRegistered", _spatial_inertia(drake))

    def Finalize(self) -> None:
        self.plant.Finalize()
        self.diagram = self.builder.Build()
        self.context = self.diagram.CreateDefaultContext()
        self.plant_context = self.plant.GetMyContextFromRoot(self.context)

    def unfiltered_collisions(self) -> set[frozenset[int]]:
        """The pairs expected with only the automatic filters (adjacent, same body)."""
        pairs = set()
        for i in range(self.sphere_count):
            pairs.add(frozenset((self.ground_id.get_value(), self.sphere_ids[i].get_value())))
            for j in range(i + 2, self.sphere_count):
                pairs.add(
                    frozenset((self.sphere_ids[i].get_value(), self.sphere_ids[j].get_value()))
                )
        return pairs

    def ComputePointPairPenetration(self) -> list[Any]:
        query_object = self.plant.get_geometry_query_input_port().Eval(self.plant_context)
        return list(query_object.ComputePointPairPenetration())

    def get_all_bodies(self) -> list[Any]:
        return [self.no_geometry_body, *self.spheres, self.plant.world_body()]


def _pairs(contacts: list[Any]) -> set[frozenset[int]]:
    return {frozenset((c.id_A.get_value(), c.id_B.get_value())) for c in contacts}


def test_filter_adjacent_bodies_source_errors(drake: ModuleType) -> None:
    """FilterAdjacentBodiesSourceErrors: Finalize needs no SceneGraph, and works with one."""
    mp, g = drake.multibody.plant, drake.geometry
    scene_graph = g.SceneGraph()
    mp.MultibodyPlant(0.0).Finalize()
    plant = mp.MultibodyPlant(0.0)
    plant.RegisterAsSourceForSceneGraph(scene_graph)
    plant.Finalize()


def test_auto_body_scene_graph_registration(drake: ModuleType) -> None:
    """AutoBodySceneGraphRegistration: every body has a FrameId once the plant is a source."""
    mp, g = drake.multibody.plant, drake.geometry
    plant = mp.MultibodyPlant(0.0)
    body1 = plant.AddRigidBody("body1", _spatial_inertia(drake))
    with pytest.raises(RuntimeError, match=r"^Body 'body1' does not have geometry registered"):
        plant.GetBodyFrameIdOrThrow(body1.index())
    scene_graph = g.SceneGraph()
    plant.RegisterAsSourceForSceneGraph(scene_graph)
    assert plant.geometry_source_is_registered()
    plant.GetBodyFrameIdOrThrow(body1.index())
    body2 = plant.AddRigidBody("body2", _spatial_inertia(drake))
    plant.GetBodyFrameIdOrThrow(body2.index())


@pytest.mark.parametrize("do_filters", [False, True])
def test_filter_adjacent_bodies(drake: ModuleType, do_filters: bool) -> None:
    """FilterAdjacentBodies: G–S0, G–S1, G–S2 and S0–S2 collide; adjacent spheres don't.

    Implicitly, visual geometries are not in the collision results.
    """
    scenario = SphereChainScenario(drake, 3)
    scenario.plant.set_adjacent_bodies_collision_filters(do_filters)
    scenario.Finalize()
    contacts = scenario.ComputePointPairPenetration()
    expected = scenario.unfiltered_collisions()
    if do_filters:
        assert len(contacts) == len(expected)
        assert _pairs(contacts) == expected
    else:
        assert len(contacts) > len(expected)


def test_filter_world_welds(drake: ModuleType) -> None:
    """FilterWorldWelds: everything welded to the world collides with nothing (#11116)."""
    scenario = SphereChainScenario(drake, 3, (1, 1, 1))
    scenario.plant.WeldFrames(
        scenario.plant.world_body().body_frame(), scenario.spheres[0].body_frame()
    )
    scenario.Finalize()
    assert scenario.ComputePointPairPenetration() == []


def test_filter_welded_subgraphs(drake: ModuleType) -> None:
    """FilterWeldedSubgraphs: a welded chain of 3 and one of 4 lose C(3,2) + C(4,2) pairs."""
    scenario = SphereChainScenario(drake, 12, (0, 0, 1, 1, 1, 0, 0, 1, 1, 1, 1))
    scenario.Finalize()
    contacts = scenario.ComputePointPairPenetration()
    assert len(contacts) == len(scenario.unfiltered_collisions()) - (3 + 6)


def test_collect_registered_geometries_errors(drake: ModuleType, api: Api) -> None:
    """CollectRegisteredGeometriesErrors: it needs a SceneGraph.

    Upstream matches ``.*geometry_source_is_registered.*failed.*``; pydrake
    raises SystemExit (a DRAKE_DEMAND, measured: multibody_plant.cc:1178 on
    1.51.1, :1126 on 1.58.0).
    """
    mp = drake.multibody.plant
    plant = mp.MultibodyPlant(0.0)
    body = plant.AddRigidBody("body", _spatial_inertia(drake))
    with pytest.raises(SystemExit) as info:
        plant.CollectRegisteredGeometries([body])
    line = _demand_line(api, (1178, 1126))
    assert str(info.value) == (
        f"Failure at external/drake+/multibody/plant/multibody_plant.cc:{line} in "
        "CollectRegisteredGeometries(): condition 'geometry_source_is_registered()' failed."
    )
    plant.RegisterAsSourceForSceneGraph(drake.geometry.SceneGraph())
    plant.CollectRegisteredGeometries([body])


@pytest.mark.parametrize("finalized", [False, True])
def test_collect_registered_geometries(drake: ModuleType, finalized: bool) -> None:
    """CollectRegisteredGeometries: the set holds the bodies' frames.

    Upstream inspects the set with GeometrySetTester (C++ only); here the set is
    resolved by the inspector, which expands each frame to its geometries: the
    world body's frame gives the anchored ground (a frame, not the ground's id,
    is in the set), a body without geometry gives nothing.
    """
    scenario = SphereChainScenario(drake, 5)
    plant = scenario.plant
    if finalized:
        scenario.Finalize()
    assert plant.is_finalized() == finalized
    inspector = scenario.scene_graph.model_inspector()
    proximity = drake.geometry.Role.kProximity

    def resolved(bodies: list[Any]) -> set[Any]:
        return inspector.GetGeometryIds(plant.CollectRegisteredGeometries(bodies), proximity)

    assert resolved([]) == set()
    assert resolved([scenario.spheres[0]]) == {scenario.sphere_ids[0]}
    frame_0 = plant.GetBodyFrameIdOrThrow(scenario.spheres[0].index())
    assert inspector.GetGeometries(frame_0, proximity) == [scenario.sphere_ids[0]]
    assert resolved([scenario.no_geometry_body]) == set()
    assert resolved([plant.world_body()]) == {scenario.ground_id}
    assert resolved(scenario.get_all_bodies()) == {scenario.ground_id, *scenario.sphere_ids}


def _split_pendulum(drake: ModuleType, drake_models: Path) -> Any:
    plant = drake.multibody.plant.MultibodyPlant(0.0)
    drake.multibody.parsing.Parser(plant).AddModels(
        str(drake_models / "multibody/plant/test/split_pendulum.sdf")
    )
    return plant


def test_get_bodies_welded_to(drake: ModuleType, drake_models: Path) -> None:
    """GetBodiesWeldedTo, before and after Finalize (the AutoDiff half is left out)."""
    plant = _split_pendulum(drake, drake_models)
    upper = plant.GetBodyByName("upper_section")
    lower = plant.GetBodyByName("lower_section")
    extra = plant.AddRigidBody(
        "extra", drake.multibody.tree.default_model_instance(), _spatial_inertia(drake)
    )
    plant.WeldFrames(plant.world_frame(), extra.body_frame())

    def names(bodies: list[Any]) -> set[str]:
        return {b.name() for b in bodies}

    for _ in ("pre-finalize", "post-finalize"):
        assert names(plant.GetBodiesWeldedTo(plant.world_body())) == {"world", "extra"}
        assert names(plant.GetBodiesWeldedTo(lower)) == {upper.name(), lower.name()}
        if not plant.is_finalized():
            plant.Finalize()


def test_get_bodies_kinematically_affected_by(drake: ModuleType, drake_models: Path) -> None:
    """GetBodiesKinematicallyAffectedBy: the bodies outboard of each moving joint."""
    plant = _split_pendulum(drake, drake_models)
    upper = plant.GetBodyByName("upper_section")
    lower = plant.GetBodyByName("lower_section")
    shoulder = plant.GetJointByName("pin").index()
    elbow = plant.GetJointByName("weld").index()
    extra = plant.AddRigidBody(
        "extra", drake.multibody.tree.default_model_instance(), _spatial_inertia(drake)
    )
    plant.WeldFrames(plant.world_frame(), extra.body_frame())
    expected = sorted([lower.index(), upper.index()])
    with pytest.raises(
        RuntimeError, match=r"Pre-finalize calls to .*GetBodiesKinematicallyAffectedBy"
    ):
        plant.GetBodiesKinematicallyAffectedBy([shoulder])
    plant.Finalize()
    assert plant.GetBodiesKinematicallyAffectedBy([shoulder]) == expected
    assert plant.GetBodiesKinematicallyAffectedBy([shoulder, elbow]) == expected
    assert plant.GetBodiesKinematicallyAffectedBy([elbow]) == []
    joint100 = drake.multibody.tree.JointIndex(100)
    with pytest.raises(RuntimeError, match=r"No joint with index.*registered.*removed\."):
        plant.GetBodiesKinematicallyAffectedBy([joint100])


def test_unsupported_reversed_joint(drake: ModuleType) -> None:
    """UnsupportedReversedJoint: a universal joint from a body to the world."""
    plant = drake.multibody.plant.MultibodyPlant(0.0)
    reverse_body = plant.AddRigidBody(
        "reverse_body", drake.multibody.tree.default_model_instance(), _spatial_inertia(drake)
    )
    plant.AddJoint(
        drake.multibody.tree.UniversalJoint(
            "reverse_universal", reverse_body.body_frame(), plant.world_frame()
        )
    )
    with pytest.raises(
        RuntimeError,
        match=(
            r"Finalize.*parent/child ordering.*universal joint reverse_universal"
            r".*reversed.*does not support.*universal.*can be reversed.*"
            r".*prismatic.*revolute.*weld.*Reverse.*ordering.*"
        ),
    ):
        plant.Finalize()


def test_weld_of_non_base_body(drake: ModuleType) -> None:
    """WeldOfNonBaseBody: #17429 (weld any body to the world) and #9939 (a double weld)."""
    tree, mp = drake.multibody.tree, drake.multibody.plant

    def fill_plant(plant: Any) -> None:
        bodies = {
            n: plant.AddRigidBody(n) for n in ("base", "waist", "waist1", "waist2", "torso", "arm")
        }
        frame = {n: b.body_frame() for n, b in bodies.items()}
        plant.AddJoint(tree.PrismaticJoint("prismatic_z", frame["base"], frame["waist"], [0, 0, 1]))
        plant.AddJoint(
            tree.RevoluteJoint("torso_joint1", frame["waist"], frame["waist1"], [1, 0, 0])
        )
        plant.AddJoint(
            tree.RevoluteJoint("torso_joint2", frame["waist1"], frame["waist2"], [0, 1, 0])
        )
        plant.AddJoint(
            tree.RevoluteJoint("torso_joint3", frame["waist2"], frame["torso"], [0, 1, 0])
        )
        plant.AddJoint(tree.RevoluteJoint("shoulder", frame["torso"], frame["arm"], [1, 1, 1]))

    floating = mp.MultibodyPlant(0.0)
    fill_plant(floating)
    floating.Finalize()
    for body in ("base", "waist", "torso"):
        plant = mp.MultibodyPlant(0.0)
        fill_plant(plant)
        plant.AddJoint(
            tree.WeldJoint(
                "body_to_world",
                plant.world_frame(),
                plant.GetRigidBodyByName(body).body_frame(),
                drake.math.RigidTransform(),
            )
        )
        plant.Finalize()
    bad_double_weld = mp.MultibodyPlant(0.0)
    fill_plant(bad_double_weld)
    base = bad_double_weld.GetRigidBodyByName("base").body_frame()
    bad_double_weld.AddJoint(
        tree.WeldJoint(
            "base_to_world1", bad_double_weld.world_frame(), base, drake.math.RigidTransform()
        )
    )
    with pytest.raises(
        RuntimeError,
        match=r"AddJoint.*already.*base_to_world1.*world.*base.*base_to_world2.*not allowed.*",
    ):
        bad_double_weld.AddJoint(
            tree.WeldJoint(
                "base_to_world2", bad_double_weld.world_frame(), base, drake.math.RigidTransform()
            )
        )
    # The redundant joint was not added.
    bad_double_weld.Finalize()


def test_unsupported_topological_loop(drake: ModuleType) -> None:
    """UnsupportedTopologicalLoop: World → body1 → body2 ← World."""
    tree = drake.multibody.tree
    plant = drake.multibody.plant.MultibodyPlant(0.0)
    body1 = plant.AddRigidBody("body1", tree.default_model_instance(), _spatial_inertia(drake))
    body2 = plant.AddRigidBody("body2", tree.default_model_instance(), _spatial_inertia(drake))
    world = plant.world_frame()
    plant.AddJoint(tree.RevoluteJoint("joint1", world, body1.body_frame(), [0, 0, 1]))
    plant.AddJoint(tree.RevoluteJoint("joint2", body1.body_frame(), body2.body_frame(), [0, 0, 1]))
    plant.AddJoint(tree.RevoluteJoint("joint3", world, body2.body_frame(), [0, 0, 1]))
    with pytest.raises(
        RuntimeError, match=r"^The bodies and joints of this system form one or more loops"
    ):
        plant.Finalize()


def test_collision_geometry_registration(drake: ModuleType) -> None:
    """CollisionGeometryRegistration: properties reach SceneGraph; only moving frames are posed.

    The dynamics parts (feedthrough) are left out; friction is compared by its
    coefficients (CoulombFriction has no ``==`` binding).
    """
    g, mp, math = drake.geometry, drake.multibody.plant, drake.math
    radius, x_offset = 0.5, 0.6
    builder = drake.systems.framework.DiagramBuilder()
    plant, scene_graph = mp.AddMultibodyPlantSceneGraph(builder, 0.0)
    ground_friction = mp.CoulombFriction(0.5, 0.3)
    ground_id = plant.RegisterCollisionGeometry(
        plant.world_body(),
        g.HalfSpace.MakePose(np.array([0.0, 1.0, 0.0]), np.zeros(3)),
        g.HalfSpace(),
        "ground",
        ground_friction,
    )
    sphere1 = plant.AddRigidBody("Sphere1", _spatial_inertia(drake))
    sphere1_friction = mp.CoulombFriction(0.8, 0.5)
    sphere1_properties = g.ProximityProperties()
    sphere1_properties.AddProperty("material", "coulomb_friction", sphere1_friction)
    sphere1_properties.AddProperty("material", "point_contact_stiffness", 980.0)
    sphere1_properties.AddProperty("material", "hunt_crossley_dissipation", 3.2)
    sphere1_id = plant.RegisterCollisionGeometry(
        sphere1, math.RigidTransform(), g.Sphere(radius), "collision", sphere1_properties
    )
    sphere2_properties = g.ProximityProperties()
    sphere2_properties.AddProperty("test", "dummy", 7)
    sphere2_friction = mp.CoulombFriction(0.7, 0.6)
    sphere2_properties.AddProperty("material", "coulomb_friction", sphere2_friction)
    sphere2_properties.AddProperty("material", "point_contact_stiffness", 196.0)
    sphere2_properties.AddProperty("material", "hunt_crossley_dissipation", 1.4)
    sphere2 = plant.AddRigidBody("Sphere2", _spatial_inertia(drake))
    sphere2_id = plant.RegisterCollisionGeometry(
        sphere2, math.RigidTransform(), g.Sphere(radius), "collision", sphere2_properties
    )
    inspector = scene_graph.model_inspector()
    props = inspector.GetProximityProperties(sphere2_id)
    assert props is not None
    assert props.HasProperty("test", "dummy")
    assert props.GetProperty("test", "dummy") == 7

    plant.Finalize()
    assert plant.num_collision_geometries() == 3
    assert plant.geometry_source_is_registered()
    assert plant.get_source_id() is not None

    diagram = builder.Build()
    diagram_context = diagram.CreateDefaultContext()
    plant_context = plant.GetMyMutableContextFromRoot(diagram_context)
    X_WS1 = math.RigidTransform([-x_offset, radius, 0.0])
    plant.SetFreeBodyPose(plant_context, sphere1, X_WS1)
    plant.SetFreeBodyPose(plant_context, sphere2, math.RigidTransform([x_offset, radius, 0.0]))
    pose_data = plant.get_geometry_pose_output_port().Eval(plant_context)
    assert pose_data.size() == 2  # Only two frames move.
    for index in range(1, plant.num_bodies()):
        body_index = drake.multibody.tree.BodyIndex(index)
        X_WB = pose_data.value(plant.GetBodyFrameIdOrThrow(body_index))
        X_WB_expected = plant.EvalBodyPoseInWorld(plant_context, plant.get_body(body_index))
        np.testing.assert_allclose(
            X_WB.GetAsMatrix34(), X_WB_expected.GetAsMatrix34(), rtol=5 * np.finfo(float).eps
        )

    def friction(geometry_id: Any, model: Any = inspector) -> tuple[float, float]:
        value = model.GetProximityProperties(geometry_id).GetProperty(
            "material", "coulomb_friction"
        )
        return value.static_friction(), value.dynamic_friction()

    assert friction(ground_id) == (0.5, 0.3)
    assert friction(sphere1_id) == (0.8, 0.5)
    assert friction(sphere2_id) == (0.7, 0.6)
    stiffness = [
        inspector.GetProximityProperties(i).GetProperty("material", "point_contact_stiffness")
        for i in (sphere1_id, sphere2_id)
    ]
    assert stiffness == [980.0, 196.0]
    dissipation = [
        inspector.GetProximityProperties(i).GetProperty("material", "hunt_crossley_dissipation")
        for i in (sphere1_id, sphere2_id)
    ]
    assert dissipation == [3.2, 1.4]
    # EvalSceneGraphInspector, cross-checked against the model inspector.
    context_inspector = plant.EvalSceneGraphInspector(plant_context)
    assert friction(ground_id, context_inspector) == (0.5, 0.3)


def test_acrobot_visual_geometry_registration_poses(drake: ModuleType, drake_models: Path) -> None:
    """AcrobotPlantTests.VisualGeometryRegistration: each moving body's frame is posed,
    its id maps back to the body, and the world body has the world frame."""
    builder = drake.systems.framework.DiagramBuilder()
    plant, _ = drake.multibody.plant.AddMultibodyPlantSceneGraph(builder, 0.0)
    drake.multibody.parsing.Parser(plant).AddModels(
        str(drake_models / "multibody/benchmarks/acrobot/acrobot.sdf")
    )
    plant.Finalize()
    assert plant.geometry_source_is_registered()
    assert plant.get_source_id() is not None
    # Upstream's num_visual_geometries() (not bound in pydrake): the visuals of all bodies.
    bodies = [plant.get_body(drake.multibody.tree.BodyIndex(i)) for i in range(plant.num_bodies())]
    assert sum(len(plant.GetVisualGeometriesForBody(b)) for b in bodies) == 3
    context = plant.CreateDefaultContext()
    poses = plant.get_geometry_pose_output_port().Eval(context)
    assert poses.size() == 2  # Only two frames move.
    world_frame_id = plant.GetBodyFrameIdOrThrow(plant.world_body().index())
    assert plant.GetBodyFromFrameId(world_frame_id).index() == plant.world_body().index()
    for index in range(1, plant.num_bodies()):
        body_index = drake.multibody.tree.BodyIndex(index)
        frame_id = plant.GetBodyFrameIdOrThrow(body_index)
        assert plant.GetBodyFrameIdIfExists(body_index) == frame_id
        assert plant.GetBodyFromFrameId(frame_id).index() == body_index
        X_WB = poses.value(frame_id)
        X_WB_expected = plant.EvalBodyPoseInWorld(context, plant.get_body(body_index))
        np.testing.assert_allclose(
            X_WB.GetAsMatrix34(), X_WB_expected.GetAsMatrix34(), rtol=5 * np.finfo(float).eps
        )


def test_visual_geometry_registration_roles_and_names(drake: ModuleType) -> None:
    """VisualGeometryRegistration without a renderer or render labels (left out):
    which roles each registration gives, the diffuse colors, the scoped names."""
    g, math = drake.geometry, drake.math
    scene_graph = g.SceneGraph()
    plant = drake.multibody.plant.MultibodyPlant(0.0)
    plant.RegisterAsSourceForSceneGraph(scene_graph)
    model_instance = plant.AddModelInstance("test_model")
    sphere = g.Sphere(0.5)

    def instance(name: str, shape: Any = sphere, X: Any = None) -> Any:
        return g.GeometryInstance(X if X is not None else math.RigidTransform(), shape, name)

    # The ground has no visual properties: both roles, no diffuse color.
    ground_id = plant.RegisterVisualGeometry(
        plant.world_body(),
        instance(
            "ground", g.HalfSpace(), g.HalfSpace.MakePose(np.array([0.0, 1.0, 0.0]), np.zeros(3))
        ),
    )
    sphere1 = plant.AddRigidBody("Sphere1", model_instance, _spatial_inertia(drake))
    sphere1_diffuse = [0.9, 0.1, 0.1, 0.5]
    sphere1_id = plant.RegisterVisualGeometry(
        sphere1, math.RigidTransform(), sphere, "visual1", sphere1_diffuse
    )
    sphere3 = plant.AddRigidBody("Sphere3", model_instance, _spatial_inertia(drake))
    sphere3_instance = instance("visual3")
    sphere3_instance.set_perception_properties(g.PerceptionProperties())
    sphere3_id = plant.RegisterVisualGeometry(sphere3, sphere3_instance)
    sphere5_id = plant.RegisterVisualGeometry(sphere3, instance("visual5"))
    plant.Finalize()
    assert plant.num_collision_geometries() == 0
    context = scene_graph.CreateDefaultContext()
    inspector = scene_graph.get_query_output_port().Eval(context).inspector()

    ground = inspector.GetIllustrationProperties(ground_id)
    assert ground is not None
    assert not ground.HasProperty("phong", "diffuse")
    assert inspector.GetName(ground_id) == "ground"  # the world body's: no scope
    # The property holds an Rgba (measured: its C++ type prints as drake::geometry::Rgba).
    diffuse = inspector.GetIllustrationProperties(sphere1_id).GetProperty("phong", "diffuse")
    assert diffuse == drake.geometry.Rgba(*sphere1_diffuse)
    assert diffuse.rgba.tolist() == sphere1_diffuse
    assert inspector.GetPerceptionProperties(sphere1_id).HasProperty("phong", "diffuse")
    assert inspector.GetName(sphere1_id) == "test_model::visual1"
    assert inspector.GetIllustrationProperties(sphere3_id) is None
    assert inspector.GetPerceptionProperties(sphere3_id) is not None
    assert inspector.GetName(sphere3_id) == "test_model::visual3"
    assert inspector.GetIllustrationProperties(sphere5_id) is not None
    assert inspector.GetPerceptionProperties(sphere5_id) is not None
    assert inspector.GetName(sphere5_id) == "test_model::visual5"


def test_scene_graph_ports(drake: ModuleType) -> None:
    """SceneGraphPorts: the ports exist before and after Finalize, without a SceneGraph."""
    mp = drake.multibody.plant
    plant = mp.MultibodyPlant(0.0)
    plant_finalized = mp.MultibodyPlant(0.0)
    plant_finalized.Finalize()
    for p in (plant, plant_finalized):
        p.get_geometry_query_input_port()
        p.get_geometry_pose_output_port()


ROBOT = """
<robot name="a">
  <link name="b">
    <collision>
      <geometry>
        <sphere radius="0.25"/>
      </geometry>
    </collision>
  </link>
</robot>
"""


def test_rename_model_instance(drake: ModuleType, api: Api) -> None:
    """RenameModelInstance: scoped frame and geometry names follow; odd names stay."""
    tree, g = drake.multibody.tree, drake.geometry
    plant = drake.multibody.plant.MultibodyPlant(0.0)
    scene_graph = g.SceneGraph()
    plant.RegisterAsSourceForSceneGraph(scene_graph)
    with pytest.raises(RuntimeError, match=r"no model instance id 99"):
        plant.RenameModelInstance(tree.ModelInstanceIndex(99), "invalid")
    # Allowed; it is up to applications to decide if they are a good idea.
    plant.RenameModelInstance(tree.world_model_instance(), "Mars")
    plant.RenameModelInstance(tree.default_model_instance(), "hmm")

    parser = drake.multibody.parsing.Parser(plant)
    models = parser.AddModelsFromString(ROBOT, "urdf")
    assert len(models) == 1
    body = plant.GetBodyByName("b")
    frame_id = plant.GetBodyFrameIdOrThrow(body.index())
    inspector = scene_graph.model_inspector()
    assert inspector.GetName(frame_id) == "a::b"
    geoms = inspector.GetGeometries(frame_id)
    assert len(geoms) == 1
    assert inspector.GetName(geoms[0]) == "a::Sphere"

    plant.RenameModelInstance(models[0], "zzz")
    assert inspector.GetName(frame_id) == "zzz::b"
    assert inspector.GetName(geoms[0]) == "zzz::Sphere"
    parser.AddModelsFromString(ROBOT, "urdf")  # renaming allows reload
    with pytest.raises(RuntimeError, match=r"must be unique"):
        plant.RenameModelInstance(models[0], "a")

    # Oddly renamed frames evade renaming.
    scene_graph.RenameFrame(frame_id, "something_random")
    plant.RenameModelInstance(models[0], "xoxo")
    assert inspector.GetName(frame_id) == "something_random"
    assert inspector.GetName(geoms[0]) == "xoxo::Sphere"
    # As do peculiarly renamed geometries.
    scene_graph.RenameGeometry(geoms[0], "anything_else")
    plant.RenameModelInstance(models[0], "bbbb")
    assert inspector.GetName(frame_id) == "something_random"
    assert inspector.GetName(geoms[0]) == "anything_else"

    plant.Finalize()
    # Upstream matches ".*finalized.*"; pydrake raises SystemExit (a
    # DRAKE_THROW_UNLESS in multibody_plant.cc, measured: line 1372 on 1.51.1,
    # 1320 on 1.58.0).
    with pytest.raises(SystemExit) as info:
        plant.RenameModelInstance(models[0], "too_late")
    line = _demand_line(api, (1372, 1320))
    assert re.fullmatch(
        rf"Failure at .*multibody_plant\.cc:{line} in RenameModelInstance\(\): "
        r"condition '!is_finalized\(\)' failed\.",
        str(info.value),
    )
