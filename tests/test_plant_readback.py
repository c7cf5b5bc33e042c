"""What a parsed plant reads back: names, counts, topology, and the errors for unknown names.

Each test parses the same URDF twice (the second copy auto-renamed ``r_1``)
on reimpl and on real pydrake and asserts the values measured on pydrake
1.51.1; where 1.58.0 differs, the expectation depends on ``api.version``.
"""

from __future__ import annotations

import importlib
from typing import Any

import numpy as np
import pytest

from conformance._backends.api import Api

URDF = """<robot name="r">
<link name="base"><collision><geometry><box size="1 1 1"/></geometry></collision>
  <visual><geometry><sphere radius="1"/></geometry></visual></link>
<link name="l1"><collision><geometry><sphere radius="1"/></geometry></collision></link>
<link name="l2"><collision name="c2"><geometry><sphere radius="1"/></geometry></collision>
  <collision name="c3"><geometry><sphere radius="1"/></geometry></collision></link>
<link name="l3"/>
<joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/></joint>
<joint name="j2" type="fixed"><parent link="l1"/><child link="l2"/></joint>
<joint name="j3" type="prismatic"><parent link="l2"/><child link="l3"/><axis xyz="0 0 1"/></joint>
</robot>"""


class Parsed:
    """Two copies of URDF, in model instances ``r`` (2) and ``r_1`` (3)."""

    def __init__(self, api: Api) -> None:
        assert api.plant is not None
        assert api.parsing is not None
        assert api.tree is not None
        self.tree = api.tree
        framework = importlib.import_module(f"{api.name}.systems.framework")
        self.plant, self.scene_graph = api.plant.AddMultibodyPlantSceneGraph(
            builder=framework.DiagramBuilder(), time_step=0.0
        )
        parser = api.parsing.Parser(plant=self.plant)
        (self.r,) = parser.AddModelsFromString(file_contents=URDF, file_type="urdf")
        parser.SetAutoRenaming(value=True)
        (self.r_1,) = parser.AddModelsFromString(file_contents=URDF, file_type="urdf")

    def body(self, name: str, instance: Any) -> Any:
        return self.plant.GetBodyByName(name=name, model_instance=instance)

    def names(self, geometry_ids: list[Any]) -> list[str]:
        inspector = self.scene_graph.model_inspector()
        return [inspector.GetName(geometry_id=g) for g in geometry_ids]


@pytest.fixture
def m(api: Api) -> Parsed:
    return Parsed(api)


def valid_names(kind: str, per_instance: dict[str, str]) -> str:
    listed = "; ".join(
        f"valid names in model instance '{i}' are: {n}" for i, n in per_instance.items()
    )
    return f"There is no {kind} named 'zz' anywhere in the model ({listed})"


class TestNames:
    def test_model_instances_are_named_in_order(self, m: Parsed) -> None:
        instance = m.tree.ModelInstanceIndex
        names = [m.plant.GetModelInstanceName(model_instance=instance(i)) for i in range(4)]
        assert names == ["WorldModelInstance", "DefaultModelInstance", "r", "r_1"]
        assert m.plant.HasModelInstanceNamed(name="r_1")
        assert not m.plant.HasModelInstanceNamed(name="r_2")

    def test_an_unknown_model_instance_index_is_named_in_the_error(self, m: Parsed) -> None:
        with pytest.raises(RuntimeError, match=r"^There is no model instance id 9 in the model\.$"):
            m.plant.GetModelInstanceName(model_instance=m.tree.ModelInstanceIndex(9))
        with pytest.raises(
            RuntimeError, match=r"^There is no model instance id -1234567 in the model\.$"
        ):
            m.plant.GetModelInstanceName(model_instance=m.tree.ModelInstanceIndex())

    def test_an_unknown_model_instance_name_lists_the_names_sorted(self, m: Parsed) -> None:
        with pytest.raises(RuntimeError) as info:
            m.plant.GetModelInstanceByName(name="nope")
        assert str(info.value) == (
            "GetModelInstanceByName(): There is no model instance named 'nope'. The current "
            "model instances are 'DefaultModelInstance', 'WorldModelInstance', 'r', 'r_1'."
        )

    def test_an_unknown_body_lists_every_instances_bodies(self, m: Parsed) -> None:
        expected = valid_names(
            "RigidBody",
            {
                "WorldModelInstance": "world",
                "r": "base, l1, l2, l3",
                "r_1": "base, l1, l2, l3",
            },
        )
        with pytest.raises(RuntimeError) as info:
            m.plant.GetBodyByName(name="zz")
        assert str(info.value) == f"GetRigidBodyByName(): {expected}"
        # With a model instance, the message is the same.
        with pytest.raises(RuntimeError) as info:
            m.plant.GetRigidBodyByName(name="zz", model_instance=m.r)
        assert str(info.value) == f"GetRigidBodyByName(): {expected}"

    def test_an_unknown_joint_lists_every_instances_joints(self, m: Parsed) -> None:
        with pytest.raises(RuntimeError) as info:
            m.plant.GetJointByName(name="zz", model_instance=m.r_1)
        assert str(info.value) == "GetJointByName(): " + valid_names(
            "Joint", {"r": "j1, j2, j3", "r_1": "j1, j2, j3"}
        )

    def test_a_name_in_two_instances_needs_an_instance(self, m: Parsed) -> None:
        suffix = "appears in multiple model instances (r, r_1); you must provide a model_instance"
        with pytest.raises(RuntimeError) as info:
            m.plant.GetBodyByName(name="l1")
        assert str(info.value) == (
            f"GetRigidBodyByName(): A RigidBody named 'l1' {suffix} argument to disambiguate."
        )
        with pytest.raises(RuntimeError) as info:
            m.plant.HasBodyNamed(name="l1")
        assert str(info.value) == (
            f"HasRigidBodyNamed(): A RigidBody named 'l1' {suffix} argument to disambiguate."
        )
        with pytest.raises(RuntimeError) as info:
            m.plant.HasJointNamed(name="j1")
        assert str(info.value) == (
            f"HasJointNamed(): A Joint named 'j1' {suffix} argument to disambiguate."
        )
        assert m.plant.HasBodyNamed(name="l1", model_instance=m.r_1)
        assert not m.plant.HasBodyNamed(name="zz", model_instance=m.r_1)
        assert m.plant.NumBodiesWithName(name="l1") == 2
        assert m.plant.NumBodiesWithName(name="zz") == 0

    def test_a_joint_in_another_instance_is_named_in_the_error(self, m: Parsed) -> None:
        with pytest.raises(RuntimeError) as info:
            m.plant.GetJointByName(name="j1", model_instance=m.tree.default_model_instance())
        assert str(info.value) == (
            "GetJointByName(): There is no Joint named 'j1' in the model instance named "
            "'DefaultModelInstance', but one does exist in other model instances (r, r_1)."
        )

    def test_indices_out_of_range_give_the_count(self, m: Parsed) -> None:
        with pytest.raises(RuntimeError) as info:
            m.plant.get_body(body_index=m.tree.BodyIndex(99))
        assert (
            str(info.value) == "The given RigidBodyIndex(99) is out of bounds (must be less than 9)"
        )
        with pytest.raises(RuntimeError) as info:
            m.plant.get_joint(joint_index=m.tree.JointIndex(99))
        assert str(info.value) == "The given JointIndex(99) is out of bounds (must be less than 6)"
        assert m.plant.has_joint(joint_index=m.tree.JointIndex(5))
        assert not m.plant.has_joint(joint_index=m.tree.JointIndex(6))


class TestInvalidModelInstances:
    """An index no instance has: each family of calls has its own error (1.51.1 and 1.58.0)."""

    def test_counts_and_names_use_the_index_tables_message(self, m: Parsed) -> None:
        m.plant.Finalize()
        index = m.tree.ModelInstanceIndex
        for call in (
            lambda mi: m.plant.num_positions(model_instance=mi),
            lambda mi: m.plant.num_velocities(model_instance=mi),
            lambda mi: m.plant.GetPositionNames(model_instance=mi),
            lambda mi: m.plant.GetStateNames(model_instance=mi),
            lambda mi: m.plant.GetDefaultPositions(model_instance=mi),
        ):
            with pytest.raises(RuntimeError) as info:
                call(index(9))
            assert str(info.value) == (
                "The given ModelInstanceIndex(9) is out of bounds (must be less than 4)"
            )
            with pytest.raises(RuntimeError) as info:
                call(index())
            assert str(info.value) == (
                "The given default-constructed ModelInstanceIndex() cannot be used. You must "
                "pass a valid integer as the index."
            )

    def test_listings_end_in_system_exit(self, api: Api, m: Parsed) -> None:
        # multibody_tree.cc's demand, measured: 1.51.1 at 481/494/521 (GetBodyIndices);
        # 1.58.0 at 486 (named GetLinkIndices)/499/526.
        lines = {"GetBodyIndices": 481, "GetJointIndices": 494, "GetFrameIndices": 521}
        renamed = {"GetBodyIndices": "GetLinkIndices"}
        for method, line_1_51 in lines.items():
            with pytest.raises(SystemExit) as info:
                getattr(m.plant, method)(m.tree.ModelInstanceIndex(9))
            line, where = line_1_51, method
            if api.version != "1.51.1":
                line, where = line_1_51 + 5, renamed.get(method, method)
            assert str(info.value) == (
                f"Failure at external/drake+/multibody/tree/multibody_tree.cc:{line} in "
                f"{where}(): condition 'model_instances_.has_element(model_instance)' failed."
            )
        # Name lookups give the name lookup's message.
        with pytest.raises(RuntimeError, match=r"^There is no model instance id 9 in the model\.$"):
            m.plant.HasBodyNamed("l1", m.tree.ModelInstanceIndex(9))


class TestStructure:
    def test_counts_and_joint_types(self, m: Parsed) -> None:
        assert (m.plant.num_bodies(), m.plant.num_joints(), m.plant.num_model_instances()) == (
            9,
            6,
            4,
        )
        assert m.plant.num_collision_geometries() == 8
        types = [m.plant.get_joint(joint_index=j).type_name() for j in m.plant.GetJointIndices()]
        assert types == ["revolute", "weld", "prismatic"] * 2
        assert [int(b) for b in m.plant.GetBodyIndices(model_instance=m.r_1)] == [5, 6, 7, 8]
        assert [int(j) for j in m.plant.GetJointIndices(model_instance=m.r_1)] == [3, 4, 5]

    def test_geometries_are_listed_per_body_with_scoped_names(self, m: Parsed) -> None:
        counts = [
            len(m.plant.GetCollisionGeometriesForBody(body=m.body(n, m.r)))
            for n in ("base", "l1", "l2", "l3")
        ]
        assert counts == [1, 1, 2, 0]
        visuals = [
            len(m.plant.GetVisualGeometriesForBody(body=m.body(n, m.r)))
            for n in ("base", "l1", "l2", "l3")
        ]
        assert visuals == [1, 0, 0, 0]
        l2 = m.body("l2", m.r_1)
        assert m.names(m.plant.GetCollisionGeometriesForBody(body=l2)) == ["r_1::c2", "r_1::c3"]

    def test_welded_bodies_are_read_back_in_index_order(self, m: Parsed) -> None:
        welded = m.plant.GetBodiesWeldedTo(body=m.body("l2", m.r))
        assert [b.name() for b in welded] == ["l1", "l2"]
        assert [b.name() for b in m.plant.GetBodiesWeldedTo(body=m.plant.world_body())] == ["world"]

    def test_topology_read_backs_need_finalize(self, m: Parsed) -> None:
        for call, name in (
            (lambda: m.plant.GetFloatingBaseBodies(), "GetFloatingBaseBodies"),
            (lambda: m.plant.IsAnchored(body=m.body("l1", m.r)), "IsAnchored"),
            (
                lambda: m.plant.HasUniqueFloatingBaseBody(model_instance=m.r),
                "HasUniqueFloatingBaseBody",
            ),
            (
                lambda: m.plant.GetBodiesKinematicallyAffectedBy(joint_indexes=[]),
                "GetBodiesKinematicallyAffectedBy",
            ),
        ):
            with pytest.raises(RuntimeError) as info:
                call()
            assert str(info.value) == (
                f"Pre-finalize calls to '{name}()' are not allowed; you must call Finalize() first."
            )

    def test_topology_after_finalize(self, m: Parsed) -> None:
        m.plant.Finalize()
        assert {int(b) for b in m.plant.GetFloatingBaseBodies()} == {1, 5}
        assert isinstance(m.plant.GetFloatingBaseBodies(), set)
        assert not m.plant.IsAnchored(body=m.body("l1", m.r))
        assert m.plant.IsAnchored(body=m.plant.world_body())
        assert m.plant.HasUniqueFloatingBaseBody(model_instance=m.r)
        assert m.plant.GetUniqueFloatingBaseBodyOrThrow(model_instance=m.r_1).name() == "base"
        world = m.tree.world_model_instance()
        assert not m.plant.HasUniqueFloatingBaseBody(model_instance=world)
        with pytest.raises(RuntimeError) as info:
            m.plant.GetUniqueFloatingBaseBodyOrThrow(model_instance=world)
        assert str(info.value) == "Model WorldModelInstance does not have a unique base body."
        j1 = m.plant.GetJointByName(name="j1", model_instance=m.r).index()
        affected = m.plant.GetBodiesKinematicallyAffectedBy(joint_indexes=[j1])
        assert [int(b) for b in affected] == [2, 3, 4]
        with pytest.raises(RuntimeError) as info:
            m.plant.GetBodiesKinematicallyAffectedBy(joint_indexes=[m.tree.JointIndex(99)])
        assert str(info.value) == (
            "GetBodiesKinematicallyAffectedBy: No joint with index 99 has been registered or it "
            "has been removed."
        )
        types = [m.plant.get_joint(joint_index=j).type_name() for j in m.plant.GetJointIndices()]
        assert types[6:] == ["quaternion_floating"] * 2
        base = m.body("base", m.r_1)
        assert (base.floating_positions_start(), base.floating_velocities_start_in_v()) == (9, 8)
        assert base.floating_position_suffix(0) == "qw"


class TestCoordinateNames:
    def test_velocity_and_state_names_follow_v_and_q(self, m: Parsed) -> None:
        m.plant.Finalize()
        free = [f"base_{s}" for s in ("wx", "wy", "wz", "vx", "vy", "vz")]
        assert m.plant.GetVelocityNames() == [
            *(f"r_{n}" for n in free),
            "r_j1_w",
            "r_j3_v",
            *(f"r_1_{n}" for n in free),
            "r_1_j1_w",
            "r_1_j3_v",
        ]
        short = m.plant.GetVelocityNames(add_model_instance_prefix=False, always_add_suffix=False)
        assert short == [*free, "j1", "j3"] * 2
        q_names = [f"base_{s}" for s in ("qw", "qx", "qy", "qz", "x", "y", "z")]
        assert m.plant.GetStateNames(model_instance=m.r) == [
            *q_names,
            "j1_q",
            "j3_x",
            *free,
            "j1_w",
            "j3_v",
        ]
        assert m.plant.GetStateNames(add_model_instance_prefix=False)[:3] == q_names[:3]

    def test_velocity_names_need_finalize(self, m: Parsed) -> None:
        with pytest.raises(RuntimeError) as info:
            m.plant.GetVelocityNames()
        assert str(info.value) == (
            "Pre-finalize calls to 'GetVelocityNames()' are not allowed; you must call "
            "Finalize() first."
        )


class TestRename:
    def test_renaming_renames_the_scoped_frame_and_geometry_names(self, m: Parsed) -> None:
        m.plant.RenameModelInstance(model_instance=m.r_1, name="renamed")
        assert m.plant.GetModelInstanceName(model_instance=m.r_1) == "renamed"
        l2 = m.body("l2", m.r_1)
        assert m.names(m.plant.GetCollisionGeometriesForBody(body=l2)) == [
            "renamed::c2",
            "renamed::c3",
        ]
        frame_id = m.plant.GetBodyFrameIdOrThrow(body_index=l2.index())
        assert m.scene_graph.model_inspector().GetName(frame_id=frame_id) == "renamed::l2"
        assert l2.scoped_name().get_full() == "renamed::l2"

    def test_renaming_to_a_taken_name_raises(self, m: Parsed) -> None:
        with pytest.raises(RuntimeError) as info:
            m.plant.RenameModelInstance(model_instance=m.r_1, name="r")
        assert str(info.value) == (
            "This model already contains a model instance named 'r'. Model instance names must "
            "be unique within a given model."
        )
        m.plant.RenameModelInstance(model_instance=m.r_1, name="r_1")  # its own name: no-op
        with pytest.raises(RuntimeError, match=r"^There is no model instance id 9 in the model\.$"):
            m.plant.RenameModelInstance(model_instance=m.tree.ModelInstanceIndex(9), name="x")

    def test_renaming_after_finalize_ends_in_system_exit(self, api: Api, m: Parsed) -> None:
        m.plant.Finalize()
        with pytest.raises(SystemExit) as info:
            m.plant.RenameModelInstance(model_instance=m.r_1, name="x")
        # The DRAKE_DEMAND is at multibody_plant.cc:1372 in 1.51.1, :1320 in 1.58.0.
        line = 1372 if api.version == "1.51.1" else 1320
        assert str(info.value) == (
            f"Failure at external/drake+/multibody/plant/multibody_plant.cc:{line} in "
            "RenameModelInstance(): condition '!is_finalized()' failed."
        )


class TestPoseReadBacks:
    """Rotations of frames and the small pose helpers of pydrake.math (values from 1.51.1)."""

    def test_a_frames_rotations_are_the_rotation_parts_of_its_poses(self, api: Api) -> None:
        assert api.plant is not None
        assert api.tree is not None
        M, tree = api.math, api.tree
        plant = api.plant.MultibodyPlant(time_step=0.0)
        a, b = plant.AddRigidBody(name="a"), plant.AddRigidBody(name="b")
        plant.AddJoint(tree.RevoluteJoint("j", a.body_frame(), b.body_frame(), [0, 0, 1], 0.0))
        X_BF = M.RigidTransform(M.RotationMatrix.MakeXRotation(0.4), [1, 2, 3])
        f = plant.AddFrame(frame=tree.FixedOffsetFrame("f", b.body_frame(), X_BF))
        plant.Finalize()
        context = plant.CreateDefaultContext()
        plant.SetPositions(context, [1, 0, 0, 0, 0.1, 0.2, 0.3, 0.7])
        R_FQ = M.RotationMatrix.MakeYRotation(0.2)
        R_BF = M.RotationMatrix.MakeXRotation(0.4)
        R_AF = M.RotationMatrix.MakeZRotation(0.7) @ R_BF

        def near(R: Any, expected: Any) -> bool:
            return bool(np.allclose(R.matrix(), expected.matrix(), rtol=0, atol=1e-15))

        assert near(f.GetFixedRotationMatrixInBodyFrame(), R_BF)
        assert near(f.GetFixedRotationMatrixInBody(R_FQ=R_FQ), R_BF @ R_FQ)
        assert near(f.CalcOffsetRotationMatrixInBody(context=context, R_FQ=R_FQ), R_BF @ R_FQ)
        assert near(f.CalcRotationMatrix(context=context, frame_M=a.body_frame()), R_AF)
        assert near(
            plant.CalcRelativeRotationMatrix(context=context, frame_A=a.body_frame(), frame_B=f),
            R_AF,
        )
        assert near(f.CalcRotationMatrixInWorld(context=context), R_AF)

    def test_rigid_transform_comparisons(self, api: Api) -> None:
        M = api.math
        X = M.RigidTransform(M.RotationMatrix.MakeZRotation(0.3), [1, 2, 3])
        Y = M.RigidTransform(M.RotationMatrix.MakeXRotation(0.2), [1, 2, 3.5])
        assert X.GetAsMatrix34().shape == (3, 4)
        assert X.IsExactlyEqualTo(other=M.RigidTransform(X))
        assert X.GetMaximumAbsoluteTranslationDifference(other=Y) == 0.5
        assert X.GetMaximumAbsoluteDifference(other=Y) == 0.5  # the translation dominates
        assert X.IsNearlyEqualTo(other=Y, tolerance=0.5)  # ≤ tolerance
        assert not X.IsNearlyEqualTo(other=Y, tolerance=0.4999)
        assert X.InvertAndCompose(other=X).IsNearlyIdentity(translation_tolerance=1e-15)
        assert M.RigidTransform([1e-9, 0, 0]).IsNearlyIdentity(translation_tolerance=1e-9)
        assert not M.RigidTransform([1e-9, 0, 0]).IsNearlyIdentity(translation_tolerance=1e-10)
        Z = M.RigidTransform(X)
        Z.set(R=M.RotationMatrix(), p=[4, 5, 6])
        assert Z.translation().tolist() == [4.0, 5.0, 6.0]
        returned = Z.SetIdentity()
        # pybind11 (1.51.1) returns the transform itself; nanobind (1.58.0) an equal copy.
        assert (returned is Z) == (api.version == "1.51.1")
        assert returned.IsExactlyIdentity()
        assert Z.IsExactlyIdentity()

    def test_rotation_rows_columns_and_identity_tolerance(self, api: Api) -> None:
        M = api.math
        R = M.RotationMatrix.MakeZRotation(0.3)
        assert R.row(index=2).tolist() == [0.0, 0.0, 1.0]
        assert R.col(index=2).tolist() == [0.0, 0.0, 1.0]
        assert R.transpose().matrix().tolist() == R.matrix().T.tolist()
        assert R.InvertAndCompose(other=R).IsNearlyIdentity()
        assert M.RotationMatrix.MakeZRotation(1e-15).IsNearlyIdentity()
        # The default tolerance is 128 ε ≈ 2.84e-14.
        assert not M.RotationMatrix.MakeZRotation(1e-13).IsNearlyIdentity()
        assert M.RotationMatrix.MakeZRotation(1e-13).IsNearlyIdentity(tolerance=1e-12)
        rpy = M.RollPitchYaw(0.1, 0.2, 0.3)
        assert (rpy.roll_angle(), rpy.pitch_angle(), rpy.yaw_angle()) == (0.1, 0.2, 0.3)
