# Ported from Drake: multibody/parsing/test/detail_dmd_parser_test.cc at v1.51.1
# (https://github.com/RobotLocomotion/drake), re-expressed as pytest functions that run
# unchanged on pydrake and on reimpl through the public Parser API (the internal
# ParseModelDirectives is not bound).
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
"""Upstream DmdParserTest cases, through ``Parser.AddModels(file_contents=..., "dmd.yaml")``.

Upstream calls the internal ``ParseModelDirectives`` with a diagnostic policy that records
errors; through the public Parser a recorded error is the RuntimeError the Parser raises.
The sphere SDFormat file is written to pytest's tmp_path as upstream writes it to a temp
directory, and ``package://drake`` points at the vendored checkout.
"""

from __future__ import annotations

import re
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest

P_PC = np.array([1.0, 2.0, 3.0])
OFFSET = "[1.0, 2.0, 3.0]"

_SPHERE_SDF = """
<?xml version="1.0"?>
<sdf version="1.7">
  <model name="sphere">
    <link name="ball">
      <inertial>
        <mass>0.03</mass>
        <inertia>
          <ixx>1.0e-5</ixx>
          <ixy>0</ixy>
          <ixz>0</ixz>
          <iyy>1.0e-5</iyy>
          <iyz>0</iyz>
          <izz>1.0e-5</izz>
        </inertia>
      </inertial>
    </link>
    <frame name="base_offset" attached_to="ball">
      <pose>{x} {y} {z} 0 0 0</pose>
    </frame>
    <link name="dummy"/>
    <frame name="dummy_offset" attached_to="dummy">
      <pose>{x} {y} {z} 0 0 0</pose>
    </frame>
  </model>
</sdf>
  """

_DEFORMABLE_SDF = """
<?xml version="1.0"?>
<sdf version="1.7">
  <model name='deformable'>
    <link name='body'>
      <collision name='collision'>
        <geometry>
          <mesh><uri>package://drake/multibody/parsing/test/single_tet.vtk</uri></mesh>
        </geometry>
      </collision>
      <drake:deformable_properties></drake:deformable_properties>
    </link>
  </model>
</sdf>
  """

#: reimpl refuses deformable bodies (outside its collision-filtering subset; see
#: reimpl/multibody/parsing/_sdf_deformable.py), so the deformable cases run on pydrake only.
_NO_DEFORMABLES = "reimpl does not model deformable bodies (outside its subset)"


def _sphere_sdf(tmp_path: Path, p_BF: np.ndarray) -> str:
    """MakeSphereSdf: a file:// URL of a 'ball' and a 'dummy' body, each with an offset frame.

    Upstream formats the offset with fmt's ``{}`` (shortest round trip: ``1``, ``2``,
    ``3``, ``0``); Python's ``repr`` of a float (``1.0``) parses to the same value."""
    path = tmp_path / "sphere.sdf"
    x, y, z = (repr(float(v)) for v in p_BF)
    path.write_text(_SPHERE_SDF.format(x=x, y=y, z=z))
    return "file://" + str(path)


def _deformable_sdf(tmp_path: Path) -> str:
    path = tmp_path / "deformable.sdf"
    path.write_text(_DEFORMABLE_SDF)
    return "file://" + str(path)


class Setup:
    """DmdParserTest's fixture: a discrete plant (time step 0.01), maybe a SceneGraph."""

    def __init__(self, drake: ModuleType, drake_models: Path, *, scene_graph: bool) -> None:
        self.drake = drake
        self.plant = drake.multibody.plant.MultibodyPlant(time_step=0.01)
        self.sg = drake.geometry.SceneGraph() if scene_graph else None
        if self.sg is not None:
            self.plant.RegisterAsSourceForSceneGraph(scene_graph=self.sg)
        self.parser = drake.multibody.parsing.Parser(plant=self.plant)
        self.parser.package_map().Remove(package_name="drake")
        self.parser.package_map().Add(package_name="drake", package_path=str(drake_models))

    def parse(self, directives: str) -> list[Any]:
        return list(self.parser.AddModels(file_contents=directives, file_type="dmd.yaml"))


def test_default_free_body_pose_poses_bodies_and_frames_against_any_base_frame(
    drake: ModuleType, drake_models: Path, tmp_path: Path
) -> None:
    """DefaultFreeBodyPose: which frames each joint connects, and each frame's world pose."""
    sphere = _sphere_sdf(tmp_path, P_PC)
    setup = Setup(drake, drake_models, scene_graph=False)
    setup.parse(f"""
directives:
- add_model:
    name: pose_body_to_world_implicitly_2
    file: {sphere}
    default_free_body_pose:
        ball:
            translation: {OFFSET}
- add_model:
    name: pose_body_to_world_explicitly_3
    file: {sphere}
    default_free_body_pose:
        ball:
            base_frame: world
            translation: {OFFSET}
- add_model:
    name: pose_body_to_body_4
    file: {sphere}
    default_free_body_pose:
        ball:
            base_frame: pose_body_to_world_explicitly_3::ball
            translation: {OFFSET}
- add_model:
    name: pose_body_to_frame_5
    file: {sphere}
    default_free_body_pose:
        ball:
            base_frame: pose_body_to_world_implicitly_2::base_offset
            translation: {OFFSET}
- add_model:
    name: pose_frame_to_body_6
    file: {sphere}
    default_free_body_pose:
        base_offset:
            base_frame: pose_body_to_world_implicitly_2::ball
            translation: {OFFSET}
- add_model:
    name: pose_frame_to_frame_7
    file: {sphere}
    default_free_body_pose:
        base_offset:
            base_frame: pose_body_to_world_implicitly_2::base_offset
            translation: {OFFSET}
- add_model:
    name: pose_body_to_in_scope_frame_8
    file: {sphere}
    default_free_body_pose:
        ball:
            base_frame: pose_body_to_in_scope_frame_8::dummy_offset
            translation: {OFFSET}
- add_model:
    name: pose_frame_to_world_9
    file: {sphere}
    default_free_body_pose:
        base_offset:
            translation: {OFFSET}
- add_model:
    name: pose_canonical_body_to_world_10
    file: package://drake/multibody/parsing/test/process_model_directives_test/simple_model.sdf
    default_free_body_pose:
        "":
            translation: {OFFSET}
""")
    plant = setup.plant
    plant.Finalize()
    context = plant.CreateDefaultContext()

    joints_actual = []
    for index in plant.GetJointIndices():
        joint = plant.get_joint(joint_index=index)
        instance = plant.GetModelInstanceName(model_instance=joint.model_instance())
        joints_actual.append((
            f"{instance}::{joint.name()}",
            joint.frame_on_parent().scoped_name().to_string(),
            joint.frame_on_child().scoped_name().to_string(),
        ))  # fmt: skip
    world = "WorldModelInstance::world"
    joints_expected = [
        # The default_free_body_pose for #4 .. #9 added a joint.
        ("pose_body_to_body_4::ball", "pose_body_to_world_explicitly_3::ball",
         "pose_body_to_body_4::ball"),
        ("pose_body_to_frame_5::ball", "pose_body_to_world_implicitly_2::base_offset",
         "pose_body_to_frame_5::ball"),
        ("pose_frame_to_body_6::ball", "pose_body_to_world_implicitly_2::ball",
         "pose_frame_to_body_6::base_offset"),
        ("pose_frame_to_frame_7::ball", "pose_body_to_world_implicitly_2::base_offset",
         "pose_frame_to_frame_7::base_offset"),
        ("pose_body_to_in_scope_frame_8::ball", "pose_body_to_in_scope_frame_8::dummy_offset",
         "pose_body_to_in_scope_frame_8::ball"),
        ("pose_frame_to_world_9::ball", world, "pose_frame_to_world_9::base_offset"),
        # All other joints were added during Finalize, in Drake's order.
        *[
            (f"{name}", world, f"{name}")
            for name in (
                "pose_body_to_world_implicitly_2::ball",
                "pose_body_to_world_explicitly_3::ball",
                "pose_body_to_in_scope_frame_8::dummy",
                "pose_body_to_world_implicitly_2::dummy",
                "pose_body_to_world_explicitly_3::dummy",
                "pose_body_to_body_4::dummy",
                "pose_body_to_frame_5::dummy",
                "pose_frame_to_body_6::dummy",
                "pose_frame_to_frame_7::dummy",
                "pose_frame_to_world_9::dummy",
                "pose_canonical_body_to_world_10::base",
            )
        ],
    ]  # fmt: skip
    assert joints_actual == joints_expected

    poses_actual = []
    for i in range(plant.num_frames()):
        frame = plant.get_frame(frame_index=drake.multibody.tree.FrameIndex(i))
        poses_actual.append(
            (frame.scoped_name().to_string(), frame.CalcPoseInWorld(context).translation())
        )
    sphere_frames = ("ball", "dummy", "__model__", "base_offset", "dummy_offset")
    # (model, offsets from the world to ball, dummy, __model__, base_offset, dummy_offset)
    sphere_counts = [
        ("pose_body_to_world_implicitly_2", (1, 0, 1, 2, 1)),
        ("pose_body_to_world_explicitly_3", (1, 0, 1, 2, 1)),
        ("pose_body_to_body_4", (2, 0, 2, 3, 1)),
        ("pose_body_to_frame_5", (3, 0, 3, 4, 1)),
        ("pose_frame_to_body_6", (1, 0, 1, 2, 1)),
        ("pose_frame_to_frame_7", (2, 0, 2, 3, 1)),
        ("pose_body_to_in_scope_frame_8", (2, 0, 2, 3, 1)),
        ("pose_frame_to_world_9", (0, 0, 0, 1, 1)),
    ]
    poses_expected = [("WorldModelInstance::world", 0)]
    for model, counts in sphere_counts:
        poses_expected += [(f"{model}::{f}", n) for f, n in zip(sphere_frames, counts, strict=True)]
    poses_expected += [
        ("pose_canonical_body_to_world_10::base", 1),
        ("pose_canonical_body_to_world_10::__model__", 1),
        ("pose_canonical_body_to_world_10::frame", 2),
    ]
    assert [name for name, _ in poses_actual] == [name for name, _ in poses_expected]
    for (name, p_WF), (_, count) in zip(poses_actual, poses_expected, strict=True):
        np.testing.assert_array_equal(p_WF, P_PC * count, err_msg=name)


def test_a_free_body_pose_may_not_add_a_second_joint_between_two_bodies(
    drake: ModuleType, drake_models: Path, tmp_path: Path
) -> None:
    """DefaultFreeBodyPoseAddsDuplicateJoints."""
    sphere = _sphere_sdf(tmp_path, P_PC)
    setup = Setup(drake, drake_models, scene_graph=False)
    with pytest.raises(RuntimeError, match=r"(?s).*already has.*joint.*connecting.*dummy.*ball.*"):
        setup.parse(f"""
directives:
- add_model:
    name: dummy
    file: {sphere}
    default_free_body_pose:
        ball:
            base_frame: dummy::dummy
            translation: {OFFSET}
        dummy:
            base_frame: dummy::ball
            translation: {OFFSET}
""")


def test_an_empty_body_name_is_an_error_for_a_model_of_two_bodies(
    drake: ModuleType, drake_models: Path, tmp_path: Path
) -> None:
    """DefaultFreeBodyPoseMultipleBodies."""
    sphere = _sphere_sdf(tmp_path, np.zeros(3))
    setup = Setup(drake, drake_models, scene_graph=False)
    with pytest.raises(RuntimeError) as error:
        setup.parse(f"""
directives:
- add_model:
    name: two_bodies
    file: {sphere}
    default_free_body_pose:
      "":
        translation: [1, 2, 3]
""")
    assert re.fullmatch(r"(?s).*two_bodies.*default_free_body_pose.*2.*bodies.*", str(error.value))


def _skip_deformables_on_reimpl(drake: ModuleType) -> None:
    if drake.__name__ == "reimpl":
        pytest.skip(_NO_DEFORMABLES)


def test_a_rigid_and_a_deformable_model_share_one_scene(
    drake: ModuleType, drake_models: Path, tmp_path: Path
) -> None:
    """AddDeformableModel."""
    _skip_deformables_on_reimpl(drake)
    setup = Setup(drake, drake_models, scene_graph=True)
    setup.parse(f"""
directives:
- add_model:
    name: rigid
    file: {_sphere_sdf(tmp_path, np.zeros(3))}
- add_model:
    name: deformable
    file: {_deformable_sdf(tmp_path)}
""")
    setup.plant.Finalize()
    # Two added rigid bodies plus the world body.
    assert setup.plant.num_bodies() == 3
    assert setup.plant.deformable_model().num_bodies() == 1


def test_a_free_body_pose_poses_a_deformable_body_in_the_world(
    drake: ModuleType, drake_models: Path, tmp_path: Path
) -> None:
    """FreeBodyPoseDeformableWorldFrame."""
    _skip_deformables_on_reimpl(drake)
    setup = Setup(drake, drake_models, scene_graph=True)
    setup.parse(f"""
directives:
- add_model:
    name: deformable
    file: {_deformable_sdf(tmp_path)}
    default_free_body_pose:
        body:
            translation: [1, 2, 3]
""")
    setup.plant.Finalize()
    deformables = setup.plant.deformable_model()
    assert deformables.num_bodies() == 1
    expected = drake.math.RigidTransform_[float](p=[1.0, 2.0, 3.0])
    assert (
        deformables.GetBodyByName(name="body").get_default_pose().IsExactlyEqualTo(other=expected)
    )


def test_a_deformable_body_is_posed_only_relative_to_the_world(
    drake: ModuleType, drake_models: Path, tmp_path: Path
) -> None:
    """FreeBodyPoseDeformableNonWorldFrame."""
    _skip_deformables_on_reimpl(drake)
    setup = Setup(drake, drake_models, scene_graph=True)
    with pytest.raises(RuntimeError) as error:
        setup.parse(f"""
directives:
- add_model:
       name: rigid
       file: {_sphere_sdf(tmp_path, np.zeros(3))}
- add_model:
    name: deformable
    file: {_deformable_sdf(tmp_path)}
    default_free_body_pose:
        body:
            base_frame: rigid::ball
            translation: [1, 2, 3]
""")
    assert re.fullmatch(
        r"(?s).*Default pose for deformable body 'body' can only be specified "
        r"relative to the world frame.*",
        str(error.value),
    )


def test_default_joint_positions_cannot_pose_a_deformable_body(
    drake: ModuleType, drake_models: Path, tmp_path: Path
) -> None:
    """DefaultJointPositions: deformables aren't associated with any joint."""
    _skip_deformables_on_reimpl(drake)
    setup = Setup(drake, drake_models, scene_graph=True)
    with pytest.raises(RuntimeError, match=r"(?s).*no Joint.*"):
        setup.parse(f"""
directives:
- add_model:
    name: deformable
    file: {_deformable_sdf(tmp_path)}
    default_joint_positions:
      wrong: [0.0]
""")
