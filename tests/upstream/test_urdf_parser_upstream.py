# Ported from Drake: multibody/parsing/test/detail_urdf_parser_test.cc (v1.51.1)
# (https://github.com/RobotLocomotion/drake), the cases about naming, model structure,
# collision filter groups and the parse errors, re-expressed as pytest functions that run
# unchanged on pydrake and on reimpl through the public Parser API.
#
# Upstream drives the internal AddModelFromUrdf with a diagnostic policy that records every
# error and goes on; through the public Parser the first error is raised (RuntimeError with
# Drake's whole message, measured on pydrake 1.51.1 and 1.58.0), and warnings are read from
# the "drake" logger, or raised as errors after SetStrictParsing(). Upstream passes a model
# name beside the text; the public API cannot, so a robot is named in its text or through a
# model-name prefix. Left out: dynamics-only checks (inertias, actuators' effort limits,
# rotor inertias, gear ratios, gains, joint limit and damping values, coupler-constraint
# gear ratios, force elements), the TAMSI mimic warning (reimpl has no contact solver
# setting), and the Atlas model of the drake_models package.
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
"""Upstream URDF parser tests (naming, structure, filter groups, errors), on pydrake and reimpl."""

from __future__ import annotations

import logging
from collections.abc import Iterator
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest

from tests.upstream.parsing_support import fact_holds_for

TEST_DIR = "multibody/parsing/test/urdf_parser_test"


def _elides_identity_frames(drake: ModuleType) -> bool:
    """Since Drake 1.55 a joint whose <origin> is the identity gets no ``<name>_parent``
    frame (detail_urdf_parser.cc's elide_identity_frame); 1.51.1 always adds one. For
    reimpl, its release's (release fact urdf-identity-joint-frame-elided-since-1.55)."""
    return fact_holds_for(drake, "urdf-identity-joint-frame-elided-since-1.55")


class Urdf:
    """A plant (discrete, 0.1 s, as upstream's fixture) with a SceneGraph, and a Parser."""

    def __init__(self, drake: ModuleType, time_step: float = 0.1, prefix: str = "") -> None:
        self.drake = drake
        self.plant = drake.multibody.plant.MultibodyPlant(time_step=time_step)
        self.scene_graph = drake.geometry.SceneGraph()
        self.plant.RegisterAsSourceForSceneGraph(scene_graph=self.scene_graph)
        parsing = drake.multibody.parsing
        if prefix:
            self.parser = parsing.Parser(plant=self.plant, model_name_prefix=prefix)
        else:
            self.parser = parsing.Parser(plant=self.plant)

    def strict(self) -> Urdf:
        self.parser.SetStrictParsing()
        return self

    def string(self, text: str) -> list[Any]:
        return list(self.parser.AddModelsFromString(file_contents=text, file_type="urdf"))

    def file(self, path: Path) -> list[Any]:
        return list(self.parser.AddModels(file_name=str(path)))

    def error(self, text: str) -> str:
        """The message of the RuntimeError parsing ``text`` raises."""
        with pytest.raises(RuntimeError) as info:
            self.string(text)
        return str(info.value)

    def file_error(self, path: Path) -> str:
        with pytest.raises(RuntimeError) as info:
            self.file(path)
        return str(info.value)

    # ------------------------------------------------------------ structure
    def names(self, instances: list[Any]) -> list[str]:
        return [self.plant.GetModelInstanceName(model_instance=i) for i in instances]

    def joints(self, instance: Any) -> list[tuple[str, str]]:
        """(name, type_name) of the instance's joints, in index order."""
        plant = self.plant
        return [
            (plant.get_joint(joint_index=j).name(), plant.get_joint(joint_index=j).type_name())
            for j in plant.GetJointIndices(model_instance=instance)
        ]

    def frames(self, instance: Any) -> list[str]:
        plant = self.plant
        return [
            plant.get_frame(frame_index=f).name()
            for f in plant.GetFrameIndices(model_instance=instance)
        ]

    def bodies(self, instance: Any) -> list[str]:
        plant = self.plant
        return [plant.get_body(body_index=b).name() for b in plant.GetBodyIndices(instance)]

    def geometry(self, link: str, role: Any, name: str) -> Any:
        inspector = self.scene_graph.model_inspector()
        body = self.plant.GetBodyByName(name=link)
        frame_id = self.plant.GetBodyFrameIdOrThrow(body_index=body.index())
        return inspector.GetGeometryIdByName(frame_id=frame_id, role=role, name=name)


def use_vendored_drake_package(parser: Any, drake_models: Path) -> None:
    """``package://drake`` names the vendored copy (the wheel ships no test files)."""
    package_map = parser.package_map()
    if package_map.Contains(package_name="drake"):
        package_map.Remove(package_name="drake")
    package_map.Add(package_name="drake", package_path=str(drake_models))


@pytest.fixture
def test_dir(drake_models: Path) -> Path:
    return drake_models / TEST_DIR


def warnings(caplog: pytest.LogCaptureFixture) -> list[str]:
    """The messages logged to the "drake" logger (pydrake's and reimpl's warnings)."""
    return [r.getMessage() for r in caplog.records if r.name == "drake"]


@pytest.fixture
def drake_log(caplog: pytest.LogCaptureFixture) -> Iterator[pytest.LogCaptureFixture]:
    with caplog.at_level(logging.WARNING, logger="drake"):
        yield caplog


# ----------------------------------------------------------------- the document


def test_a_missing_file_is_tinyxml2s_file_not_found_at_line_0(
    drake: ModuleType, tmp_path: Path
) -> None:
    """Upstream BadFilename."""
    path = tmp_path / "nonexistent.urdf"
    assert Urdf(drake).file_error(path) == (
        f"{path}:0: error: Failed to parse XML file: XML_ERROR_FILE_NOT_FOUND"
    )


def test_text_that_is_no_xml_is_tinyxml2s_parsing_text_error(drake: ModuleType) -> None:
    """Upstream BadXmlString."""
    assert Urdf(drake).error("not proper xml content") == (
        "<literal-string>.urdf:1: error: Failed to parse XML string: XML_ERROR_PARSING_TEXT"
    )


def test_a_document_without_robot_is_an_error(drake: ModuleType) -> None:
    """Upstream NoRobot."""
    assert Urdf(drake).error("<empty/>") == (
        "<literal-string>.urdf:1: error: URDF does not contain a robot tag."
    )


def test_a_robot_needs_a_name(drake: ModuleType) -> None:
    """Upstream NoName."""
    assert Urdf(drake).error("<robot/>") == (
        "<literal-string>.urdf:1: error: Your robot must have a name attribute or a model "
        "name must be specified."
    )


def test_a_model_name_prefix_scopes_the_robot_name(drake: ModuleType) -> None:
    """Upstream ModelRenameWithColons (there the caller's name 'left::robot' replaces the
    robot's; through the public API a prefix 'left' scopes the robot's name)."""
    urdf = Urdf(drake, prefix="left")
    instances = urdf.string("""
    <robot name='robot'>
    </robot>""")
    assert urdf.names(instances) == ["left::robot"]


def test_a_loop_joint_is_an_error_after_the_model_instance_is_made(drake: ModuleType) -> None:
    """Upstream ObsoleteLoopJoint."""
    urdf = Urdf(drake)
    assert urdf.error("<robot name='a'><loop_joint/></robot>") == (
        "<literal-string>.urdf:1: error: loop joints are not supported in MultibodyPlant"
    )
    assert urdf.plant.HasModelInstanceNamed(name="a")


# ------------------------------------------------------------------------ links


def test_a_link_with_drake_ignore_true_is_not_read(drake: ModuleType) -> None:
    """Upstream LegacyDrakeIgnoreBody."""
    urdf = Urdf(drake)
    (instance,) = urdf.string("""
    <robot name='a'>
      <link name='ignore-me' drake_ignore='true'>
        <!-- Empty visual will trigger errors if ignore fails. -->
        <visual/>
      </link>
    </robot>""")
    assert urdf.bodies(instance) == []


def test_a_link_needs_a_name(drake: ModuleType) -> None:
    """Upstream BodyNameBroken."""
    assert (
        Urdf(drake).error("""
    <robot name='a'>
      <link naQQQme='broken'/>
    </robot>""")
        == "<literal-string>.urdf:3: error: link tag is missing name attribute."
    )


# ----------------------------------------------------------------------- joints


def test_a_joint_with_drake_ignore_true_is_not_read(drake: ModuleType) -> None:
    """Upstream LegacyDrakeIgnoreJoint."""
    urdf = Urdf(drake)
    (instance,) = urdf.string("""
    <robot name='a'>
      <!-- Empty joint will trigger errors if ignore fails. -->
      <joint name='ignore-me' drake_ignore='true'/>
    </robot>""")
    assert urdf.joints(instance) == []


JOINT_KEY_ERRORS = {
    "JointNameBroken": (
        """
    <robot name='a'>
      <joint naQQQme='broken'/>
    </robot>""",
        "<literal-string>.urdf:3: error: joint tag is missing name attribute",
    ),
    "JointTypeBroken": (
        """
    <robot name='a'>
      <joint name='a' tyQQQpe='broken'/>
    </robot>""",
        "<literal-string>.urdf:3: error: joint 'a' is missing type attribute",
    ),
    "JointNoParent": (
        """
    <robot name='a'>
      <joint name='a' type='revolute'>
        <parQQQent link='parent'/>
        <child link='child'/>
      </joint>
    </robot>""",
        "<literal-string>.urdf:3: error: joint 'a' doesn't have a parent node!",
    ),
    "JointParentLinkBroken": (
        """
    <robot name='a'>
      <link name='parent'/>
      <link name='child'/>
      <joint name='a' type='revolute'>
        <parent liQQQnk='broken'/>
        <child link='child'/>
      </joint>
    </robot>""",
        "<literal-string>.urdf:6: error: joint a's parent does not have a link attribute!",
    ),
    "JointNoChild": (
        """
    <robot name='a'>
      <joint name='a' type='revolute'>
        <parent link='parent'/>
        <chiQQQld link='child'/>
      </joint>
    </robot>""",
        "<literal-string>.urdf:3: error: joint 'a' doesn't have a child node!",
    ),
    "JointChildLinkBroken": (
        """
    <robot name='a'>
      <link name='parent'/>
      <link name='child'/>
      <joint name='a' type='revolute'>
        <parent link='parent'/>
        <child liQQQnk='broken'/>
      </joint>
    </robot>""",
        "<literal-string>.urdf:7: error: joint a's child does not have a link attribute!",
    ),
    "JointLinkMissing": (
        """
    <robot name='a'>
      <!-- Parent link is missing. -->
      <link name='child'/>
      <joint name='joint' type='revolute'>
        <parent link='parent'/>
        <child link='child'/>
      </joint>
    </robot>""",
        "<literal-string>.urdf:1: error: Could not find link named 'parent' with model "
        "instance ID 2 for element 'joint'.",
    ),
    "JointZeroAxis": (
        """
    <robot name='a'>
      <link name='parent'/>
      <link name='child'/>
      <joint name='joint' type='revolute'>
        <parent link='parent'/>
        <child link='child'/>
        <axis xyz="0 0 0"/>
      </joint>
    </robot>""",
        "<literal-string>.urdf:8: error: Joint 'joint' axis is zero.  Don't do that.",
    ),
    "JointTypeUnknown": (
        """
    <robot name='a'>
      <link name='parent'/>
      <link name='child'/>
      <joint name='joint' type='who'>
        <parent link='parent'/>
        <child link='child'/>
      </joint>
    </robot>""",
        "<literal-string>.urdf:5: error: Joint 'joint' has unrecognized type: 'who'",
    ),
}


@pytest.mark.parametrize("case", JOINT_KEY_ERRORS)
def test_a_joint_error_names_the_joint_at_its_line(drake: ModuleType, case: str) -> None:
    """Upstream JointNameBroken .. JointTypeUnknown: the first error is raised."""
    text, message = JOINT_KEY_ERRORS[case]
    assert Urdf(drake).error(text) == message


DYNAMICS = """
    <robot name='a'>
      <link name='parent'/>
      <link name='child'/>
      <joint name='a' type='revolute'>
        <parent link='parent'/>
        <child link='child'/>
        <dynamics {}/>
      </joint>
    </robot>"""


@pytest.mark.parametrize("attribute", ["damping", "friction", "coulomb_window"])
def test_a_dynamics_attribute_takes_a_single_number(drake: ModuleType, attribute: str) -> None:
    """Upstream JointBadDynamicsAttributes."""
    assert Urdf(drake).error(DYNAMICS.format(f"{attribute}='1 2'")) == (
        f"<literal-string>.urdf:8: error: Expected single value for attribute '{attribute}' "
        "got '1 2'"
    )


@pytest.mark.parametrize(
    ("attribute", "warning"),
    [
        (
            "friction='10'",
            "A joint has specified a non-zero value for the 'friction' attribute of a "
            "joint/dynamics tag. MultibodyPlant does not currently support non-zero joint "
            "friction.",
        ),
        (
            "coulomb_window='10'",
            "A joint has specified a value for the 'coulomb_window' attribute of a <joint> "
            "tag. Drake no longer makes use of that attribute; all instances will be ignored.",
        ),
    ],
)
def test_joint_friction_and_coulomb_window_are_warned_about(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture, attribute: str, warning: str
) -> None:
    """Upstream DrakeFrictionWarning, DrakeCoulombWarning; strict parsing raises them."""
    text = DYNAMICS.format(attribute)
    urdf = Urdf(drake)
    (instance,) = urdf.string(text)
    assert urdf.joints(instance) == [("a", "revolute")]
    assert warnings(drake_log) == [f"<literal-string>.urdf:8: warning: {warning}"]
    assert Urdf(drake).strict().error(text) == f"<literal-string>.urdf:8: error: {warning}"


def test_a_floating_joint_leaves_the_child_free_with_a_warning(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture
) -> None:
    """Upstream JointFloatingWarning."""
    urdf = Urdf(drake)
    (instance,) = urdf.string("""
    <robot name='a'>
      <link name='parent'/>
      <link name='child'/>
      <joint name='joint' type='floating'>
        <parent link='parent'/>
        <child link='child'/>
      </joint>
    </robot>""")
    assert urdf.joints(instance) == []
    assert warnings(drake_log) == [
        "<literal-string>.urdf:5: warning: Joint 'joint' specified as type floating which is "
        "not supported by MultibodyPlant.  Leaving 'child' as a free body."
    ]


# ------------------------------------------------------------------------ mimic

MIMIC_MODEL = """
    <robot name='a'>
      <link name='parent'/>
      <link name='child0'/>
      <link name='child1'/>
      <joint name='joint0' type='revolute'>
        <parent link='parent'/>
        <child link='child0'/>
      </joint>
      <joint name='joint1' type='revolute'>
        <parent link='parent'/>
        <child link='child1'/>
        <mimic joint='joint0'/>
      </joint>
    </robot>"""


@pytest.mark.parametrize("time_step", [0.0, 0.1])
def test_a_mimic_element_parses_on_continuous_and_default_discrete_plants(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture, time_step: float
) -> None:
    """Upstream MimicContinuous (and MimicNoSap's model on a plant left at its default
    discrete approximation, which is not TAMSI: no warning, measured)."""
    urdf = Urdf(drake, time_step=time_step)
    (instance,) = urdf.string(MIMIC_MODEL)
    assert urdf.joints(instance) == [("joint0", "revolute"), ("joint1", "revolute")]
    assert warnings(drake_log) == []


MIMIC_ERRORS = {
    "MimicNoJoint": (
        "<mimic/>",
        "<literal-string>.urdf:8: error: Joint 'joint' mimic element is missing the required "
        "'joint' attribute.",
    ),
    "MimicBadJoint": (
        "<mimic joint='nonexistent'/>",
        "<literal-string>.urdf:8: error: Joint 'joint' mimic element specifies joint "
        "'nonexistent' which does not exist.",
    ),
    "MimicSameJoint": (
        "<mimic joint='joint'/>",
        "<literal-string>.urdf:8: error: Joint 'joint' mimic element specifies joint 'joint'. "
        "Joints cannot mimic themselves.",
    ),
}


@pytest.mark.parametrize("case", MIMIC_ERRORS)
def test_a_mimic_element_must_name_another_joint(drake: ModuleType, case: str) -> None:
    """Upstream MimicNoJoint, MimicBadJoint, MimicSameJoint."""
    mimic, message = MIMIC_ERRORS[case]
    text = f"""
    <robot name='a'>
      <link name='parent'/>
      <link name='child'/>
      <joint name='joint' type='revolute'>
        <parent link='parent'/>
        <child link='child'/>
        {mimic}
      </joint>
    </robot>"""
    assert Urdf(drake).error(text) == message


def _two_joints(joint0: str, joint1: str, mimic: str = "<mimic joint='joint0'/>") -> str:
    return f"""
    <robot name='a'>
      <link name='parent'/>
      <link name='child0'/>
      <link name='child1'/>
      <joint name='joint0' type='{joint0}'>
        <parent link='parent'/>
        <child link='child0'/>
      </joint>
      <joint name='joint1' type='{joint1}'>
        <parent link='parent'/>
        <child link='child1'/>
        {mimic}
      </joint>
    </robot>"""


def test_a_joint_cannot_mimic_one_of_other_dofs(drake: ModuleType) -> None:
    """Upstream MimicMismatchedJoint."""
    assert Urdf(drake).error(_two_joints("fixed", "revolute")) == (
        "<literal-string>.urdf:13: error: Joint 'joint1' which has 1 DOF cannot mimic joint "
        "'joint0' which has 0 DOF."
    )


def test_a_mimic_between_joints_without_one_dof_is_ignored_with_a_warning(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture
) -> None:
    """Upstream MimicOnlyOneDOFJoint."""
    urdf = Urdf(drake)
    (instance,) = urdf.string(_two_joints("fixed", "fixed"))
    assert urdf.joints(instance) == [("joint0", "weld"), ("joint1", "weld")]
    assert warnings(drake_log) == [
        "<literal-string>.urdf:13: warning: Drake only supports the mimic element for "
        "single-dof joints. The joint 'joint1' (with 0 dofs) is attempting to mimic joint "
        "'joint0' (with 0 dofs). The mimic element will be ignored."
    ]


def test_a_mimic_on_a_floating_joint_is_ignored_with_a_warning(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture
) -> None:
    """Upstream MimicFloatingJoint: first the floating joint's warning, then the mimic's."""
    urdf = Urdf(drake)
    (instance,) = urdf.string(_two_joints("fixed", "floating"))
    assert urdf.joints(instance) == [("joint0", "weld")]
    assert warnings(drake_log) == [
        "<literal-string>.urdf:10: warning: Joint 'joint1' specified as type floating which "
        "is not supported by MultibodyPlant.  Leaving 'child1' as a free body.",
        "<literal-string>.urdf:13: warning: Drake only supports the mimic element for "
        "single-dof joints. The mimic element in joint 'joint1' will be ignored.",
    ]


def test_mimic_elements_look_up_joints_in_their_own_model_instance(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture
) -> None:
    """Upstream MimicDifferentModelInstances: no error, no warning."""
    urdf = Urdf(drake)
    mimic = "<mimic joint='joint0' multiplier='1' offset='0' />"
    a = urdf.string(_two_joints("revolute", "revolute", mimic))
    b = urdf.string(_two_joints("revolute", "revolute", mimic).replace("name='a'", "name='b'"))
    assert urdf.names(a + b) == ["a", "b"]
    assert warnings(drake_log) == []


# ------------------------------------------------------ materials, frames, ...


def test_a_visual_may_use_a_robot_material_by_name(drake: ModuleType) -> None:
    """Upstream Material (proof of life)."""
    urdf = Urdf(drake)
    urdf.string("""
    <robot name='a'>
     <material name='black'>
      <color rgba='0 0 0 0'/>
     </material>
     <link name="base_link">
      <visual>
       <geometry>
        <cylinder length="0.6" radius="0.2"/>
       </geometry>
       <!-- use the named material! -->
       <material name='black'/>
      </visual>
     </link>
    </robot>""")
    role = drake.geometry.Role.kIllustration
    assert urdf.geometry("base_link", role, "a::Cylinder") is not None


@pytest.mark.parametrize(
    ("frame", "message"),
    [
        (
            '<frame naQQQme="broken" link="A" rpy="0 0 0" xyz="0 0 0"/>',
            "<literal-string>.urdf:3: error: parsing frame name.",
        ),
        (
            '<frame name="frameA" liQQQnk="broken" rpy="0 0 0" xyz="0 0 0"/>',
            "<literal-string>.urdf:3: error: missing link name for frame frameA.",
        ),
    ],
    ids=["FrameNameBroken", "FrameLinkBroken"],
)
def test_a_frame_needs_a_name_and_a_link(drake: ModuleType, frame: str, message: str) -> None:
    """Upstream FrameNameBroken, FrameLinkBroken."""
    text = f"""
    <robot name="a">
      {frame}
    </robot>"""
    assert Urdf(drake).error(text) == message


TRANSMISSION_ERRORS = {
    "TransmissionTypeBroken": (
        "<transmission tyQQQpe='broken'/>",
        "Transmission element is missing a type.",
    ),
    "TransmissionActuatorMissing": (
        "<transmission type='SimpleTransmission'/>",
        "Transmission is missing an actuator element.",
    ),
    "TransmissionActuatorNameBroken": (
        "<transmission type='SimpleTransmission'>\n        <actuator naQQQme='broken'/>\n"
        "      </transmission>",
        "Transmission is missing an actuator name.",
    ),
    "TransmissionJointMissing": (
        "<transmission type='SimpleTransmission'>\n        <actuator name='a'/>\n"
        "      </transmission>",
        "Transmission is missing a joint element.",
    ),
    "TransmissionJointNameBroken": (
        "<transmission type='SimpleTransmission'>\n        <actuator name='a'/>\n"
        "        <joint naQQQme='broken'/>\n      </transmission>",
        "Transmission is missing a joint name.",
    ),
    "TransmissionJointNotExist": (
        "<transmission type='SimpleTransmission'>\n        <actuator name='a'/>\n"
        "        <joint name='nowhere'/>\n      </transmission>",
        "Transmission specifies joint 'nowhere' which does not exist.",
    ),
}
#: Upstream case -> the line of its error.
TRANSMISSION_LINES = {
    "TransmissionTypeBroken": 3,
    "TransmissionActuatorMissing": 3,
    "TransmissionActuatorNameBroken": 4,
    "TransmissionJointMissing": 3,
    "TransmissionJointNameBroken": 5,
    "TransmissionJointNotExist": 5,
}


@pytest.mark.parametrize("case", TRANSMISSION_ERRORS)
def test_a_transmission_needs_a_type_an_actuator_and_an_existing_joint(
    drake: ModuleType, case: str
) -> None:
    """Upstream TransmissionTypeBroken .. TransmissionJointNotExist."""
    transmission, message = TRANSMISSION_ERRORS[case]
    text = f"""
    <robot name="a">
      {transmission}
    </robot>"""
    line = TRANSMISSION_LINES[case]
    assert Urdf(drake).error(text) == f"<literal-string>.urdf:{line}: error: {message}"


@pytest.mark.parametrize(
    "transmission",
    [
        "<transmission type='who'/>",
        "<transmission>\n        <type>who</type>\n      </transmission>",
    ],
    ids=["attribute", "element"],
)
def test_a_transmission_that_is_not_simple_is_skipped_with_a_warning(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture, transmission: str
) -> None:
    """Upstream TransmissionTypeUnknown."""
    Urdf(drake).string(f"""
    <robot name="a">
      {transmission}
    </robot>""")
    assert warnings(drake_log) == [
        "<literal-string>.urdf:3: warning: A <transmission> has a type that isn't "
        "'SimpleTransmission'. Drake only supports 'SimpleTransmission'; all other "
        "transmission types will be ignored."
    ]


LIMITED_JOINT = """
    <robot name='a'>
      <link name='parent'/>
      <link name='child'/>
      <joint name='a' type='revolute'>
        <parent link='parent'/>
        <child link='child'/>
        <limit {}/>
      </joint>
      <transmission type='SimpleTransmission'>
        <actuator name='a'/>
        <joint name='a'/>
      </transmission>
    </robot>"""


def test_a_transmission_skips_a_zero_effort_joint_and_rejects_a_negative_one(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture
) -> None:
    """Upstream TransmissionJointBadLimits (the effort's sign decides parse or error)."""
    Urdf(drake).string(LIMITED_JOINT.format("effort='0'"))
    assert warnings(drake_log) == [
        "<literal-string>.urdf:12: warning: Skipping transmission since it's attached to joint "
        '"a" which has a zero effort limit 0.'
    ]
    assert Urdf(drake).error(LIMITED_JOINT.format("effort='-3'")) == (
        "<literal-string>.urdf:12: error: Transmission specifies joint 'a' which has a "
        "negative effort limit."
    )


@pytest.mark.parametrize(
    "attribute", ["lower", "upper", "velocity", "drake:acceleration", "effort"]
)
def test_a_limit_attribute_takes_a_single_number(drake: ModuleType, attribute: str) -> None:
    """Upstream TransmissionJointBadLimits, second part."""
    assert Urdf(drake).error(LIMITED_JOINT.format(f"{attribute}='1 2'")) == (
        f"<literal-string>.urdf:8: error: Expected single value for attribute '{attribute}' "
        "got '1 2'"
    )


# ------------------------------------------------------------------ model files


def test_a_package_map_resolves_the_package_uris_of_a_urdf(
    drake: ModuleType, drake_models: Path
) -> None:
    """Upstream PackageMapSpecified (which fills the map with PopulateFromFolder; here
    the one package is added by name)."""
    urdf = Urdf(drake)
    package = drake_models / "multibody/parsing/test/box_package"
    urdf.parser.package_map().Add(package_name="box_model", package_path=str(package))
    assert urdf.plant.num_model_instances() == 2
    urdf.file(package / "urdfs/box.urdf")
    urdf.plant.Finalize()
    assert urdf.plant.num_model_instances() == 3


def test_double_pendulum_has_its_links_and_frames(drake: ModuleType, drake_models: Path) -> None:
    """Upstream DoublePendulum."""
    urdf = Urdf(drake)
    (instance,) = urdf.file(drake_models / "multibody/benchmarks/acrobot/double_pendulum.urdf")
    plant = urdf.plant
    plant.Finalize()
    assert plant.num_bodies() == 4
    # N.B. 1.51.1 adds a frame <joint>_parent for each of the two joints; since 1.55 the
    # joint at the identity origin gets none (measured on 1.58.0: 9 frames).
    assert plant.num_frames() == (9 if _elides_identity_frames(drake) else 10)
    for name in ("frame_on_link1", "frame_on_link2", "link1_com", "link2_com"):
        assert plant.HasFrameNamed(name=name)
    frame_on_link1 = plant.GetFrameByName(name="frame_on_link1")
    assert frame_on_link1.body().index() == plant.GetBodyByName(name="link1").index()
    math_ = drake.math
    expected = math_.RigidTransform(
        rpy=math_.RollPitchYaw(roll=-1, pitch=0.1, yaw=0.2), p=[0.8, -0.2, 0.3]
    )
    np.testing.assert_allclose(
        frame_on_link1.GetFixedPoseInBodyFrame().GetAsMatrix4(),
        expected.GetAsMatrix4(),
        atol=1e-10,
    )
    link2_com = plant.GetFrameByName(name="link2_com")
    assert link2_com.body().index() == plant.GetBodyByName(name="link2").index()
    assert urdf.bodies(instance) == ["base", "link1", "link2"]


def test_a_robot_without_joints_gets_a_floating_base(drake: ModuleType, test_dir: Path) -> None:
    """Upstream TestAddWithQuaternionFloatingDof."""
    urdf = Urdf(drake)
    urdf.file(test_dir / "zero_dof_robot.urdf")
    urdf.plant.Finalize()
    assert urdf.plant.num_positions() == 7
    assert urdf.plant.num_velocities() == 6


#: joint_parsing_test.urdf's joints: (name, type_name, parent link, child link), in order.
PARSED_JOINTS = [
    ("fixed_joint", "weld", "world", "link1"),
    ("revolute_joint", "revolute", "link1", "link2"),
    ("prismatic_joint", "prismatic", "link2", "link3"),
    ("ball_joint", "ball_rpy", "link3", "link4"),
    ("revolute_joint_no_limits", "revolute", "link4", "link5"),
    ("universal_joint", "universal", "link5", "link6"),
    ("planar_joint", "planar", "link6", "link7"),
    ("continuous_joint", "revolute", "link7", "link8"),
    ("screw_joint", "screw", "link8", "link9"),
    ("revolute_joint_with_mimic_forward_reference", "revolute", "link9", "link10"),
    ("revolute_joint_to_mimic", "revolute", "link10", "link11"),
    ("revolute_joint_with_mimic_backward_reference", "revolute", "link11", "link12"),
    ("curvilinear_periodic", "curvilinear", "link12", "link13"),
    ("curvilinear_aperiodic", "curvilinear", "link13", "link14"),
]


def test_every_joint_type_parses_with_its_names_links_and_order(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture, test_dir: Path
) -> None:
    """Upstream JointParsingTest, its names, types, links, axes and joint order (pydrake
    binds no CurvilinearJoint: both read its type_name())."""
    urdf = Urdf(drake)
    path = test_dir / "joint_parsing_test.urdf"
    (instance,) = urdf.file(path)
    assert warnings(drake_log) == [
        f"{path}:209: warning: Skipping transmission since it's attached to joint "
        '"prismatic_joint" which has a zero effort limit 0.'
    ]
    plant = urdf.plant
    plant.Finalize()
    parsed = [
        (j.name(), j.type_name(), j.parent_body().name(), j.child_body().name())
        for j in (plant.get_joint(joint_index=i) for i in plant.GetJointIndices(instance))
    ]
    assert parsed == PARSED_JOINTS
    np.testing.assert_array_equal(
        plant.GetJointByName(name="revolute_joint").revolute_axis(), [0, 0, 1]
    )
    np.testing.assert_array_equal(
        plant.GetJointByName(name="prismatic_joint").translation_axis(), [0, 0, 1]
    )
    np.testing.assert_array_equal(
        plant.GetJointByName(name="continuous_joint").revolute_axis(), [0, 0, 1]
    )
    assert plant.GetJointByName(name="screw_joint").screw_pitch() == 0.04
    assert plant.GetJointByName(name="curvilinear_periodic").num_positions() == 1


def test_a_custom_planar_joint_is_accepted(drake: ModuleType) -> None:
    """Upstream LegacyPlanarJointAsCustomTest."""
    urdf = Urdf(drake)
    (instance,) = urdf.string("""
    <robot name='a'>
      <link name="link1"/>
      <link name="link2"/>
      <drake:joint name="planar_joint" type="planar">
        <parent link="link1"/>
        <child link="link2"/>
      </drake:joint>
    </robot>""")
    assert urdf.joints(instance) == [("planar_joint", "planar")]


@pytest.mark.parametrize(
    ("file", "line", "message"),
    [
        (
            "joint_parsing_test_tag_mismatch_1.urdf",
            5,
            "Joint fixed_joint of type fixed is a standard joint type, and should be a <joint>",
        ),
        (
            "joint_parsing_test_tag_mismatch_2.urdf",
            5,
            "Joint ball_joint of type ball is a custom joint type, and should be a <drake:joint>",
        ),
        (
            "joint_parsing_test_missing_screw_thread_pitch.urdf",
            5,
            "A screw joint is missing the <drake:screw_thread_pitch> tag.",
        ),
        (
            "joint_parsing_test_missing_screw_thread_pitch_attribute.urdf",
            9,
            "A screw joint has a <drake:screw_thread_pitch> tag that is missing the 'value' "
            "attribute.",
        ),
    ],
)
def test_a_joint_element_must_suit_its_type(
    drake: ModuleType, test_dir: Path, file: str, line: int, message: str
) -> None:
    """Upstream JointParsingTagMismatchTest, JointParsingTagMissingScrewParametersTest."""
    path = test_dir / file
    assert Urdf(drake).file_error(path) == f"{path}:{line}: error: {message}"


def test_the_world_link_takes_geometry_but_not_mass(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture
) -> None:
    """Upstream AddingGeometriesToWorldLink (its text starts with a blank line before
    <?xml, which tinyxml2 accepts)."""
    urdf = Urdf(drake)
    urdf.string("""
<?xml version="1.0"?>
<robot xmlns:xacro="http://ros.org/wiki/xacro" name="joint_parsing_test">
  <link name="world">
    <!-- Declaring mass properties on the "world" link is bad. But it won't
     cause the parser to throw. -->
    <inertial>
      <mass value="1.0"/>
      <origin xyz="0 0 0"/>
      <inertia ixx="0.001" ixy="0.0" ixz="0.0" iyy="0.001" iyz="0.0" izz="0.001"/>
    </inertial>
    <visual>
      <geometry>
        <box size="0.1 0.2 0.3"/>
        <material>
          <color rgba="0.8 0.7 0.6 0.5"/>
        </material>
      </geometry>
    </visual>
    <collision>
      <geometry>
        <sphere radius="0.25"/>
      </geometry>
    </collision>
  </link>
</robot>
""")
    assert warnings(drake_log) == [
        '<literal-string>.urdf:4: warning: A URDF file declared the "world" link and then '
        "attempted to assign mass properties (via the <inertial> tag). Only geometries, "
        "<collision> and <visual>, can be assigned to the world link. The <inertial> tag is "
        "being ignored."
    ]
    inspector = urdf.scene_graph.model_inspector()
    world = urdf.scene_graph.world_frame_id()
    Role = drake.geometry.Role
    assert inspector.num_geometries() == 2
    assert inspector.NumGeometriesForFrame(frame_id=world) == 2
    for role in (Role.kProximity, Role.kIllustration, Role.kPerception):
        assert inspector.NumGeometriesForFrameWithRole(frame_id=world, role=role) == 1


CURVES = {
    "CurvilinearJointErrors0": (
        "",
        6,
        "A curvilinear joint is missing the <drake:curves> list.",
    ),
    "CurvilinearJointErrors1": (
        "<drake:line_segment/>",
        15,
        "A curvilinear joint contains a <drake:line_segment> that is missing the 'length' "
        "attribute.",
    ),
    "CurvilinearJointErrors2": (
        '<drake:line_segment length="-22"/>',
        15,
        "A curvilinear joint contains a <drake:line_segment> with a zero or negative "
        "'length' attribute.",
    ),
    "CurvilinearJointErrors3": (
        '<drake:circular_arc radQQQius="2.0" angle="1.57079632679489661923"/>',
        15,
        "A curvilinear joint contains a <drake:circular_arc> that is missing the 'radius' "
        "attribute.",
    ),
    "CurvilinearJointErrors4": (
        '<drake:circular_arc radius="-2.0" angle="1.57079632679489661923"/>',
        15,
        "A curvilinear joint contains a <drake:circular_arc> with a zero or negative "
        "'radius' attribute.",
    ),
    "CurvilinearJointErrors5": (
        '<drake:circular_arc radius="2.0" anQQQgle="1.57079632679489661923"/>',
        15,
        "A curvilinear joint contains a <drake:circular_arc> that is missing the 'angle' "
        "attribute.",
    ),
    "CurvilinearJointErrors6": (
        '<drake:circQQQular_arc radius="2.0" angle="1.57079632679489661923"/>',
        14,
        "A curvilinear joint contains an invalid curve node <drake:circQQQular_arc>.",
    ),
    "CurvilinearJointErrors7": (
        "\n    ",
        14,
        "A curvilinear joint contains an empty curves list.",
    ),
}


@pytest.mark.parametrize("case", CURVES)
def test_a_curvilinear_joint_needs_well_formed_curves(drake: ModuleType, case: str) -> None:
    """Upstream CurvilinearJointErrors0 .. 7 (errors at the curve, at <drake:curves> for an
    unknown curve and an empty list, at <drake:joint> for no list)."""
    curve, line, message = CURVES[case]
    curves = (
        ""
        if case == "CurvilinearJointErrors0"
        else f"\n    <drake:curves>\n      {curve}\n    </drake:curves>"
    )
    text = f"""
<?xml version="1.0"?>
<robot xmlns:xacro="http://ros.org/wiki/xacro" name="joint_parsing_test">
  <link name="a"/>
  <link name="b"/>
  <drake:joint name="curvilinear_periodic" type="curvilinear">
    <origin xyz="3 2 1" rpy="0 0 0"/>
    <parent link="a"/>
    <child link="b"/>
    <drake:initial_tangent xyz="0 0 1"/>
    <drake:plane_normal xyz="1 0 0"/>
    <drake:is_periodic value="true"/>
    <dynamics damping="0.1"/>{curves}
  </drake:joint>
</robot>
"""
    assert Urdf(drake).error(text) == f"<literal-string>.urdf:{line}: error: {message}"


#: Each shape of all_geometries_as_*.urdf, by its type name (its geometry's name).
SHAPES = ["Box", "Capsule", "Convex", "Cylinder", "Ellipsoid", "Mesh", "Sphere"]


@pytest.mark.parametrize(
    ("file", "role"),
    [
        ("all_geometries_as_collision.urdf", "kProximity"),
        ("all_geometries_as_visual.urdf", "kPerception"),
    ],
)
def test_every_shape_is_registered_named_after_its_type(
    drake: ModuleType, test_dir: Path, file: str, role: str
) -> None:
    """Upstream CollisionGeometryParsing, VisualGeometryParsing (a mesh with
    <drake:declare_convex/> is a Convex named Convex)."""
    urdf = Urdf(drake)
    use_vendored_drake_package(urdf.parser, test_dir.parents[3])
    urdf.file(test_dir / file)
    urdf.plant.Finalize()
    inspector = urdf.scene_graph.model_inspector()
    for shape in SHAPES:
        geometry_id = urdf.geometry(
            "link1", getattr(drake.geometry.Role, role), f"test_robot::{shape}"
        )
        assert type(inspector.GetShape(geometry_id=geometry_id)).__name__ == shape


def test_visual_and_collision_names_are_separate(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture
) -> None:
    """Upstream TestVisualAndCollisionNameOverlap: no renaming, no warning."""
    urdf = Urdf(drake)
    urdf.string("""
    <robot name='a'>
      <link name='b'>
        <visual name='hello'>
          <geometry><box size='1 2 3'/></geometry>
        </visual>
        <collision name='hello'>
          <geometry><box size='1 2 3'/></geometry>
        </collision>
      </link>
    </robot>""")
    assert warnings(drake_log) == []
    Role = drake.geometry.Role
    for role in (Role.kIllustration, Role.kProximity):
        assert urdf.geometry("b", role, "a::hello") is not None


BAD_INERTIA = {
    "value": ("value='1 2 3'", "ixx='0' ixy='0' ixz='0' iyy='0' iyz='0' izz='0'", 5),
    "ixx": ("value='1'", "ixx='0 2 3' ixy='0' ixz='0' iyy='0' iyz='0' izz='0'", 6),
    "ixy": ("value='1'", "ixx='0' ixy='0 2 3' ixz='0' iyy='0' iyz='0' izz='0'", 6),
    "ixz": ("value='1'", "ixx='0' ixy='0' ixz='0 2 3' iyy='0' iyz='0' izz='0'", 6),
    "iyy": ("value='1'", "ixx='0' ixy='0' ixz='0' iyy='0 2 3' iyz='0' izz='0'", 6),
    "iyz": ("value='1'", "ixx='0' ixy='0' ixz='0' iyy='0' iyz='0 2 3' izz='0'", 6),
    "izz": ("value='1'", "ixx='0' ixy='0' ixz='0' iyy='0' iyz='0' izz='0 2 3'", 6),
}


@pytest.mark.parametrize("attribute", BAD_INERTIA)
def test_mass_and_inertia_attributes_take_single_numbers(drake: ModuleType, attribute: str) -> None:
    """Upstream BadInertiaFormats."""
    mass, inertia, line = BAD_INERTIA[attribute]
    text = f"""
    <robot name='point_mass'>
      <link name='point_mass'>
        <inertial>
          <mass {mass}/>
          <inertia {inertia}/>
        </inertial>
      </link>
    </robot>"""
    assert Urdf(drake).error(text) == (
        f"<literal-string>.urdf:{line}: error: Expected single value for attribute "
        f"'{attribute}' got '{'1 2 3' if attribute == 'value' else '0 2 3'}'"
    )


# -------------------------------------------------------- collision filter groups

#: Upstream's dispositions of the pairs of links 1..10 (True: filtered).
FILTERED = {
    (1, 2): False,  # unfiltered
    (1, 3): True,  # group_link3 ignores group_link14
    (1, 4): True,  # group_link14 ignores itself
    (1, 5): False,
    (1, 6): False,
    (2, 3): True,  # group_link2 ignores group_link3
    (2, 4): False,  # declared only in the ignored group_link24
    (2, 5): True,  # group_link56 ignores group_link2
    (2, 6): True,
    (3, 4): True,  # group_link3 ignores group_link14
    (3, 5): True,  # group_link56 ignores group_link3
    (3, 6): True,
    (4, 5): False,
    (4, 6): False,
    (5, 6): True,  # group_link56 ignores itself
    # 7 .. 10 form group_of_groups, which ignores itself.
    (7, 8): True,
    (7, 9): True,
    (7, 10): True,
    (8, 9): True,
    (8, 10): True,
    (9, 10): True,
    # The two sets are separate.
    (1, 10): False,
    (6, 7): False,
}


def test_collision_filter_groups_filter_their_pairs_before_finalize(
    drake: ModuleType, test_dir: Path
) -> None:
    """Upstream CollisionFilterGroupParsingTest."""
    urdf = Urdf(drake)
    path = test_dir / "collision_filter_group_parsing_test.urdf"
    urdf.file(path)
    inspector = urdf.scene_graph.model_inspector()
    role = drake.geometry.Role.kProximity
    ids = {
        k: urdf.geometry(f"link{k}", role, f"collision_filter_group_parsing_test::link{k}_sphere")
        for k in range(1, 11)
    }
    assert not urdf.plant.is_finalized()
    filtered = {
        pair: inspector.CollisionFiltered(geometry_id1=ids[pair[0]], geometry_id2=ids[pair[1]])
        for pair in FILTERED
    }
    assert filtered == FILTERED
    groups = urdf.parser.GetCollisionFilterGroups()
    assert not groups.empty()
    # Upstream adds the model a second time under another name.
    again = drake.multibody.parsing.Parser(plant=urdf.plant, model_name_prefix="model2")
    instances = again.AddModels(file_name=str(path))
    assert urdf.names(instances) == ["model2::collision_filter_group_parsing_test"]


FILTER_GROUP_ERRORS = {
    "CollisionFilterGroupMissingName": (
        "<drake:collision_filter_group/>",
        4,
        'The tag <drake:collision_filter_group> does not specify the required attribute "name".',
    ),
    "CollisionFilterGroupMissingLink": (
        '<drake:collision_filter_group name="group_a">\n        <drake:member/>\n'
        "      </drake:collision_filter_group>",
        5,
        'The tag <drake:member> does not specify the required attribute "link".',
    ),
    "CollisionFilterGroupMissingMemberGroupName": (
        '<drake:collision_filter_group name="group_a">\n        <drake:member_group/>\n'
        "      </drake:collision_filter_group>",
        5,
        'The tag <drake:member_group> does not specify the required attribute "name".',
    ),
    # N.B. Its members are read before its ignored groups (upstream's first error too).
    "IgnoredCollisionFilterGroupMissingName": (
        '<drake:collision_filter_group name="group_a">\n'
        "        <drake:ignored_collision_filter_group/>\n"
        "      </drake:collision_filter_group>",
        2,
        "group 'robot::group_a' has no members",
    ),
}


@pytest.mark.parametrize("case", FILTER_GROUP_ERRORS)
def test_a_filter_group_tag_missing_its_attribute_is_an_error(drake: ModuleType, case: str) -> None:
    """Upstream CollisionFilterGroupMissing*: the first error (upstream's policy goes on to
    report the group having no members)."""
    group, line, message = FILTER_GROUP_ERRORS[case]
    text = f"""
    <robot name='robot'>
      <link name='a'/>
      {group}
    </robot>"""
    assert Urdf(drake).error(text) == f"<literal-string>.urdf:{line}: error: {message}"


# ------------------------------------------------------------ unsupported things


def test_unsupported_attributes_are_warned_about(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture
) -> None:
    """Upstream UnsupportedVersionIgnored, UnsupportedLinkTypeIgnored."""
    Urdf(drake).string("""
    <robot name='robot' version='0.99'>
      <link name='a' type='unknown'/>
    </robot>""")
    assert warnings(drake_log) == [
        "<literal-string>.urdf:2: warning: The attribute 'version' found in a 'robot' tag is "
        "currently unsupported and will be ignored.",
        "<literal-string>.urdf:3: warning: The attribute 'type' found in a 'link' tag is "
        "currently unsupported and will be ignored.",
    ]


@pytest.mark.parametrize("tag", ["calibration", "safety_controller"])
def test_unsupported_joint_children_are_warned_about(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture, tag: str
) -> None:
    """Upstream UnsupportedJointStuffIgnored (the robot named in its text)."""
    Urdf(drake).string(f"""
    <robot name='{tag}'>
      <link name='parent'/>
      <link name='child'/>
      <joint name='a' type='revolute'>
        <parent link='parent'/>
        <child link='child'/>
        <{tag}/>
      </joint>
    </robot>""")
    assert warnings(drake_log) == [
        f"<literal-string>.urdf:8: warning: The tag '{tag}' found as a child of 'joint' is "
        "currently unsupported and will be ignored."
    ]


@pytest.mark.parametrize(
    "tag",
    [
        "leftActuator",
        "rightActuator",
        "flexJoint",
        "rollJoint",
        "gap_joint",
        "passive_joint",
        "use_simulated_gripper_joint",
    ],
)
def test_unsupported_transmission_children_are_warned_about(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture, tag: str
) -> None:
    """Upstream UnsupportedTransmissionStuffIgnored (the robot named in its text)."""
    Urdf(drake).string(f"""
    <robot name='{tag}'>
      <link name='parent'/>
      <link name='child'/>
      <joint name='a' type='revolute'>
        <parent link='parent'/>
        <child link='child'/>
      </joint>
      <transmission type='SimpleTransmission'>
        <actuator name='a'/>
        <joint name='a'/>
        <{tag}/>
      </transmission>
    </robot>""")
    assert warnings(drake_log) == [
        f"<literal-string>.urdf:12: warning: The tag '{tag}' found as a child of "
        "'transmission' is currently unsupported and will be ignored."
    ]


@pytest.mark.parametrize(
    "text",
    [
        """
    <robot name='robot'>
      <link name='a'/>
      <gazebo/>
    </robot>""",
        """
    <robot name='a'>
      <link name='parent'/>
      <link name='child'/>
      <joint name='a' type='revolute'>
        <parent link='parent'/>
        <child link='child'/>
      </joint>
      <transmission type='SimpleTransmission'>
        <actuator name='a'>
          <hardwareInterface/>
        </actuator>
        <joint name='a'/>
      </transmission>
    </robot>""",
        """
    <robot name ='a'>
      <link name='parent'/>
      <link name='child'/>
      <joint name='a' type='revolute'>
        <parent link='parent'/>
        <child link='child'/>
      </joint>
      <transmission type='SimpleTransmission'>
        <actuator name='a'/>
        <joint name='a'>
          <hardwareInterface/>
        </joint>
      </transmission>
    </robot>""",
    ],
    ids=["gazebo", "actuator hardwareInterface", "joint hardwareInterface"],
)
def test_some_unsupported_elements_are_ignored_silently(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture, text: str
) -> None:
    """Upstream UnsupportedGazeboIgnoredSilent, UnsupportedTransmission*IgnoredSilent."""
    Urdf(drake).strict().string(text)
    assert warnings(drake_log) == []


MECHANICAL_REDUCTION = """
    <robot name='{name}'>
      <link name='parent'/>
      <link name='child'/>
      <joint name='a' type='revolute'>
        <parent link='parent'/>
        <child link='child'/>
      </joint>
      <transmission type='SimpleTransmission'>
        <actuator name='a'>
          {actuator}
        </actuator>
        <joint name='a'/>
        {transmission}
      </transmission>
    </robot>"""
#: mechanicalReduction element -> whether Drake warns of it.
REDUCTIONS = {
    "<mechanicalReduction>3500.25</mechanicalReduction>": True,
    "<mechanicalReduction>22 79 15</mechanicalReduction>": True,
    "<mechanicalReduction>QQQ</mechanicalReduction>": True,
    "<mechanicalReduction/>": False,
    "<mechanicalReduction></mechanicalReduction>": False,
    "<mechanicalReduction> </mechanicalReduction>": False,
    "<mechanicalReduction>1</mechanicalReduction>": False,
    "<mechanicalReduction>1.0</mechanicalReduction>": False,
}


@pytest.mark.parametrize("reduction", REDUCTIONS)
@pytest.mark.parametrize("where", ["actuator", "transmission"])
def test_a_mechanical_reduction_other_than_1_is_warned_about(
    drake: ModuleType, drake_log: pytest.LogCaptureFixture, reduction: str, where: str
) -> None:
    """Upstream UnsupportedMechanicalReductionIgnoredMaybe."""
    slots = {"actuator": "", "transmission": ""}
    slots[where] = reduction
    Urdf(drake).string(MECHANICAL_REDUCTION.format(name="r", **slots))
    expected = []
    if REDUCTIONS[reduction]:
        text = reduction.removeprefix("<mechanicalReduction>").removesuffix(
            "</mechanicalReduction>"
        )
        expected = [
            f"<literal-string>.urdf:{11 if where == 'actuator' else 14}: warning: A '{where}' "
            f"element contains a mechanicalReduction element with a value '{text}' other than "
            "the default of 1. MultibodyPlant does not currently support non-default "
            "mechanical reductions."
        ]
    assert warnings(drake_log) == expected


# ----------------------------------------------------------------- planar joints


@pytest.mark.parametrize(
    ("axis", "p_WB"),
    [
        ("0 1 0", [1.2, 0.0, -3.4]),  # R_WF = R_x(3π/2) takes [1.2, 3.4, 0] to this
        ("0 0 1", [1.2, 3.4, 0.0]),
    ],
    ids=["PlanarJointAxisRespected", "PlanarJointCanonicalFrame"],
)
def test_a_planar_joint_moves_in_the_plane_normal_to_its_axis(
    drake: ModuleType, axis: str, p_WB: list[float]
) -> None:
    """Upstream PlanarJointAxisRespected, PlanarJointCanonicalFrame."""
    urdf = Urdf(drake)
    urdf.string(f"""
    <robot name='a'>
      <link name="link1"/>
      <link name="link2"/>
      <drake:joint name="planar_joint" type="planar">
        <parent link="link1"/>
        <child link="link2"/>
        <axis xyz = "{axis}" />
      </drake:joint>
    </robot>""")
    plant = urdf.plant
    plant.Finalize()
    plant.GetJointByName(name="planar_joint").set_default_translation([1.2, 3.4])
    context = plant.CreateDefaultContext()
    X_WB = plant.EvalBodyPoseInWorld(context, plant.GetBodyByName(name="link2"))
    np.testing.assert_allclose(X_WB.translation(), p_WB, atol=4 * np.finfo(float).eps)
