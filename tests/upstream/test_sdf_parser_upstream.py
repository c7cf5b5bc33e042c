# Ported from Drake: multibody/parsing/test/detail_sdf_parser_test.cc at v1.51.1
# (https://github.com/RobotLocomotion/drake), the cases about model structure and naming
# (model instances, bodies, joints and their types, frames, geometries with their shapes and
# roles), collision filter groups and parse errors, re-expressed as pytest functions that run
# unchanged on pydrake and on reimpl through the public Parser API. Dynamics-only checks
# (inertias, actuators, springs, mimic, constraints, hydroelastic values, pose values beyond
# what decides a name or a body) are left out. Expected values
# are upstream's, re-measured on pydrake 1.51.1 and 1.58.0 (both give the same answers here).
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
"""Upstream SDFormat parser tests, model structure and filter groups, on pydrake and reimpl."""

from __future__ import annotations

import re
from itertools import combinations
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest

_TEST = "multibody/parsing/test"
_SDF_TEST = f"{_TEST}/sdf_parser_test"


def _sdf(inner: str, version: str = "1.6") -> str:
    """Upstream's ParseTestString: the text inside ``<sdf version=...>``."""
    return f"<sdf version='{version}'>{inner}\n</sdf>\n"


class _Parse:
    """A plant (with a SceneGraph unless told) and a Parser, as upstream's fixture has."""

    def __init__(
        self,
        drake: ModuleType,
        *,
        scene_graph: bool = True,
        time_step: float = 0.0,
        prefix: str = "",
    ) -> None:
        self.drake = drake
        self.plant = drake.multibody.plant.MultibodyPlant(time_step=time_step)
        self.scene_graph = drake.geometry.SceneGraph()
        if scene_graph:
            self.plant.RegisterAsSourceForSceneGraph(scene_graph=self.scene_graph)
        parsing = drake.multibody.parsing
        if prefix:
            self.parser = parsing.Parser(plant=self.plant, model_name_prefix=prefix)
        else:
            self.parser = parsing.Parser(plant=self.plant)

    def package(self, name: str, path: Path) -> _Parse:
        self.parser.package_map().Add(package_name=name, package_path=str(path))
        return self

    def drake_package(self, root: Path) -> _Parse:
        """Maps ``package://drake`` to the vendored checkout (both implementations)."""
        package_map = self.parser.package_map()
        package_map.Remove(package_name="drake")
        package_map.Add(package_name="drake", package_path=str(root))
        return self

    def string(self, text: str) -> list[str]:
        models = self.parser.AddModelsFromString(file_contents=text, file_type="sdf")
        return [self.plant.GetModelInstanceName(model_instance=m) for m in models]

    def file(self, path: Path) -> list[str]:
        models = self.parser.AddModels(file_name=str(path))
        return [self.plant.GetModelInstanceName(model_instance=m) for m in models]

    # ----------------------------------------------------------- answers
    def instances(self) -> list[str]:
        index = self.drake.multibody.tree.ModelInstanceIndex
        return [
            self.plant.GetModelInstanceName(model_instance=index(i))
            for i in range(self.plant.num_model_instances())
        ]

    def bodies(self) -> list[tuple[str, str]]:
        index = self.drake.multibody.tree.BodyIndex
        found = []
        for i in range(1, self.plant.num_bodies()):
            body = self.plant.get_body(body_index=index(i))
            instance = self.plant.GetModelInstanceName(model_instance=body.model_instance())
            found.append((instance, body.name()))
        return found

    def joints(self) -> list[tuple[str, str, str, str, str]]:
        """(name, type, frame on parent, frame on child, model instance) per joint."""
        index = self.drake.multibody.tree.JointIndex
        found = []
        for i in range(self.plant.num_joints()):
            joint = self.plant.get_joint(joint_index=index(i))
            instance = self.plant.GetModelInstanceName(model_instance=joint.model_instance())
            found.append(
                (
                    joint.name(),
                    joint.type_name(),
                    joint.frame_on_parent().name(),
                    joint.frame_on_child().name(),
                    instance,
                )
            )
        return found

    def frame(self, name: str, instance: str | None = None) -> tuple[str, str]:
        """(model instance, body) of the frame ``name``."""
        if instance is None:
            frame = self.plant.GetFrameByName(name=name)
        else:
            model = self.plant.GetModelInstanceByName(name=instance)
            frame = self.plant.GetFrameByName(name=name, model_instance=model)
        owner = self.plant.GetModelInstanceName(model_instance=frame.model_instance())
        return owner, frame.body().name()

    def geometries(self) -> set[tuple[str, str, str, str]]:
        """(name, frame, shape, roles) per geometry; roles P(roximity) I(llustration) R."""
        inspector = self.scene_graph.model_inspector()
        found = set()
        for geometry in inspector.GetAllGeometryIds():
            roles = "".join(
                letter
                for letter, properties in (
                    ("P", inspector.GetProximityProperties(geometry_id=geometry)),
                    ("I", inspector.GetIllustrationProperties(geometry_id=geometry)),
                    ("R", inspector.GetPerceptionProperties(geometry_id=geometry)),
                )
                if properties is not None
            )
            frame = inspector.GetName(frame_id=inspector.GetFrameId(geometry_id=geometry))
            shape = type(inspector.GetShape(geometry_id=geometry)).__name__
            found.add((inspector.GetName(geometry_id=geometry), frame, shape, roles))
        return found

    def filtered_pairs(self) -> set[tuple[str, str]]:
        """Upstream's VerifyCollisionFilters: the filtered pairs, by geometry name."""
        inspector = self.scene_graph.model_inspector()
        ids = inspector.GetAllGeometryIds()
        filtered = set()
        for a, b in combinations(ids, 2):
            if inspector.CollisionFiltered(geometry_id1=a, geometry_id2=b):
                names = sorted((inspector.GetName(geometry_id=a), inspector.GetName(geometry_id=b)))
                filtered.add((names[0], names[1]))
        return filtered

    def groups(self) -> tuple[dict[str, list[str]], list[list[str]]]:
        report = self.parser.GetCollisionFilterGroups()
        groups = {name: sorted(members) for name, members in report.groups().items()}
        return groups, sorted(sorted(pair) for pair in report.exclusion_pairs())


def _error(drake: ModuleType, text: str, **parse: Any) -> str:
    with pytest.raises(RuntimeError) as info:
        _Parse(drake, **parse).string(text)
    return str(info.value)


# --------------------------------------------------------------- model instances
def test_a_parent_model_name_scopes_a_second_copy_of_a_model(drake: ModuleType) -> None:
    """Upstream ParentModelNameWithString."""
    model = "<model name='something'><link name='link'/></model>"
    parse = _Parse(drake)
    assert parse.string(_sdf(model)) == ["something"]
    second = drake.multibody.parsing.Parser(plant=parse.plant, model_name_prefix="2")
    second.AddModelsFromString(file_contents=_sdf(model), file_type="sdf")
    parse.plant.Finalize()
    assert parse.instances() == [
        "WorldModelInstance",
        "DefaultModelInstance",
        "something",
        "2::something",
    ]


def test_a_parent_model_name_scopes_every_model_of_a_world(drake: ModuleType) -> None:
    """Upstream ParentModelNameWithStringWorld."""
    world = (
        "<world name='here'><model name='a'><link name='link'/></model>"
        "<model name='b'><link name='link'/></model></world>"
    )
    parse = _Parse(drake)
    assert parse.string(_sdf(world)) == ["a", "b"]
    second = drake.multibody.parsing.Parser(plant=parse.plant, model_name_prefix="2")
    models = second.AddModelsFromString(file_contents=_sdf(world), file_type="sdf")
    assert [parse.plant.GetModelInstanceName(model_instance=m) for m in models] == [
        "2::a",
        "2::b",
    ]
    assert parse.plant.num_model_instances() == 6


def test_a_model_name_taken_by_an_earlier_parse_is_an_error(drake: ModuleType) -> None:
    """Upstream ModelInstanceTest: a duplicate model name is not allowed."""
    parse = _Parse(drake)
    model = _sdf("<model name='instance1'><link name='a'/></model>")
    parse.string(model)
    with pytest.raises(RuntimeError) as info:
        parse.string(model)
    assert str(info.value) == (
        "This model already contains a model instance named 'instance1'. Model instance names "
        "must be unique within a given model."
    )


def test_two_acrobots_keep_their_links_and_joints_apart(
    drake: ModuleType, drake_models: Path
) -> None:
    """Upstream ModelInstanceTest: per-model-instance links and joints of two acrobots."""
    acrobot = drake_models / "multibody/benchmarks/acrobot/acrobot.sdf"
    parse = _Parse(drake)
    assert parse.file(acrobot) == ["acrobot"]
    renamed = drake.multibody.parsing.Parser(plant=parse.plant, model_name_prefix="3")
    renamed.AddModels(file_name=str(acrobot))
    plant = parse.plant
    plant.Finalize()
    first = plant.GetModelInstanceByName(name="acrobot")
    second = plant.GetModelInstanceByName(name="3::acrobot")
    assert plant.HasBodyNamed(name="Link1", model_instance=first)
    assert plant.HasBodyNamed(name="Link1", model_instance=second)
    assert plant.HasJointNamed(name="ShoulderJoint", model_instance=first)
    assert plant.HasJointNamed(name="ShoulderJoint", model_instance=second)
    link1 = plant.GetBodyByName(name="Link1", model_instance=first)
    link2 = plant.GetBodyByName(name="Link1", model_instance=second)
    assert link1.index() != link2.index()
    assert link1.model_instance() == first
    assert link2.model_instance() == second


# ----------------------------------------------------------------- static models
def test_a_static_model_welds_each_of_its_links_to_the_world(drake: ModuleType) -> None:
    """Upstream StaticModelSupported1."""
    parse = _Parse(drake, scene_graph=False)
    parse.string(
        _sdf(
            "<model name='good'><static>true</static>"
            "<link name='a'><pose>1 2 3  0.1 0.2 0.3</pose></link>"
            "<link name='b'><pose>4 5 6  0.4 0.5 0.6</pose></link></model>"
        )
    )
    parse.plant.Finalize()
    assert parse.plant.num_positions() == 0
    assert parse.joints() == [
        ("sdformat_model_static_world_welds_to_a", "weld", "world", "a", "good"),
        ("sdformat_model_static_world_welds_to_b", "weld", "world", "b", "good"),
    ]


def test_a_static_model_needs_no_link_and_its_frame_is_on_the_world(drake: ModuleType) -> None:
    """Upstream StaticModelSupported2."""
    parse = _Parse(drake)
    parse.string(
        _sdf("<model name='a'><pose>1 2 3  0.1 0.2 0.3</pose><static>true</static></model>", "1.8")
    )
    parse.plant.Finalize()
    assert parse.frame("__model__", "a") == ("a", "world")


def test_a_model_holding_a_static_model_needs_no_link(drake: ModuleType) -> None:
    """Upstream StaticModelSupported3."""
    parse = _Parse(drake)
    parse.string(
        _sdf(
            "<model name='a'><pose>1 2 3  0.0 0.0 0.3</pose><model name='b'>"
            "<pose>0 0 0  0.1 0.2 0.0</pose><static>true</static></model></model>",
            "1.8",
        )
    )
    parse.plant.Finalize()
    assert parse.frame("__model__", "a") == ("a", "world")
    assert parse.frame("__model__", "a::b") == ("a::b", "world")


def test_a_static_model_may_hold_only_frames(drake: ModuleType) -> None:
    """Upstream StaticFrameOnlyModelsSupported: every frame is on the world body."""
    parse = _Parse(drake)
    parse.string(
        _sdf(
            "<model name='a'><static>true</static><pose>1 0 0  0 0 0</pose>"
            "<frame name='b'><pose>0 2 0 0 0 0</pose></frame>"
            "<frame name='c' attached_to='b'><pose>0 0 3 0 0 0</pose></frame>"
            "<frame name='d'><pose relative_to='c'>0 0 0 0 0 0.3</pose></frame></model>",
            "1.8",
        )
    )
    parse.plant.Finalize()
    for name in ("__model__", "b", "c", "d"):
        assert parse.frame(name) == ("a", "world")


def test_welds_a_static_model_declares_stand_in_for_its_world_welds(drake: ModuleType) -> None:
    """Upstream StaticModelWithJoints: redundant welds add no sdformat_model_static_ weld."""
    parse = _Parse(drake)
    parse.string(
        _sdf(
            "<model name='good'><static>true</static><link name='a'/>"
            "<joint name='a_weld' type='fixed'><parent>world</parent><child>a</child></joint>"
            "<link name='b'/><joint name='b_weld' type='fixed'><parent>a</parent><child>b</child>"
            "</joint></model>"
        )
    )
    assert parse.joints() == [
        ("a_weld", "weld", "world", "a_weld_child", "good"),
        ("b_weld", "weld", "a", "b_weld_child", "good"),
    ]


def test_a_static_model_with_a_revolute_joint_is_an_error(drake: ModuleType) -> None:
    """Upstream StaticModelWithJoints: Drake does not support frozen joints."""
    text = _sdf(
        "\n<model name='mixed_emotions'><static>true</static><link name='a'/><link name='b'/>"
        "<joint name='my_hinge' type='revolute'><parent>a</parent><child>b</child>"
        "<axis><xyz>0 0 1</xyz></axis></joint></model>"
    )
    assert _error(drake, text) == (
        "<literal-string>.sdf:2: error: Only fixed joints are permitted in static models."
    )


# ------------------------------------------------------------------------ joints
_TWO_LINKS = "<link name='a'/><link name='b'/>"
_JOINT_ERRORS = {
    "revolute_with_only_axis2": (
        "<model name='joint_no_axis'>" + _TWO_LINKS + "\n<joint name='no_axis' type='revolute'>"
        "<parent>a</parent><child>b</child><axis2><xyz>0 0 1</xyz></axis2></joint></model>",
        "<literal-string>.sdf:2: error: An axis must be specified for joint 'no_axis'",
    ),
    "lower_above_upper": (
        "<model name='joint_no_axis'>" + _TWO_LINKS + "\n<joint name='no_axis' type='prismatic'>"
        "<parent>a</parent><child>b</child><axis><xyz>0 0 1</xyz><limit><lower>2</lower>"
        "<upper>1</upper></limit></axis></joint></model>",
        "<literal-string>.sdf:2: error: The lower limit must be lower (or equal) than the upper "
        "limit for joint 'no_axis'.",
    ),
    "negative_acceleration": (
        "<model name='joint_no_axis'>" + _TWO_LINKS + "<joint name='no_axis' type='prismatic'>"
        "<parent>a</parent><child>b</child><axis><xyz>0 0 1</xyz>\n<limit>"
        "<drake:acceleration>-1</drake:acceleration></limit></axis></joint></model>",
        "<literal-string>.sdf:2: error: Acceleration limit is negative for joint 'no_axis'. "
        "Aceleration limit must be a non-negative number.",
    ),
    "prismatic_without_axis": (
        "<model name='joint_no_axis'>" + _TWO_LINKS + "\n<joint name='no_axis' type='prismatic'>"
        "<parent>a</parent><child>b</child></joint></model>",
        "<literal-string>.sdf:2: error: An axis must be specified for joint 'no_axis'",
    ),
    "world_joint_not_fixed": (
        "\n<world name='uno'><joint name='no_axis' type='prismatic'><parent>a</parent>"
        "<child>b</child><axis><xyz>0 0 1</xyz></axis></joint><model name='a'><link name='l'/>"
        "</model><model name='b'><link name='h'/></model></world>",
        "<literal-string>.sdf:2: error: Only fixed joints are permitted in world joints.",
    ),
    "drake_joint_without_type": (
        "<model name='good'><link name='a'/><drake:joint>\n</drake:joint></model>",
        "<literal-string>.sdf: error: <drake:joint>: Unable to find the 'type' attribute.",
    ),
    "drake_joint_without_name": (
        "<model name='good'><link name='a'/><drake:joint type='nonetype'>\n</drake:joint></model>",
        "<literal-string>.sdf: error: <drake:joint>: Unable to find the 'name' attribute.",
    ),
    "drake_joint_with_pose": (
        "<model name='good'><link name='a'/><drake:joint type='nonetype' name='joint_name'>"
        "<pose></pose></drake:joint></model>",
        "<literal-string>.sdf: error: <drake:joint> does not yet support the <pose> child tag.",
    ),
    "drake_joint_of_unknown_type": (
        "<model name='good'>" + _TWO_LINKS + "<drake:joint type='nonetype' name='joint_name'>"
        "<drake:parent>a</drake:parent><drake:child>b</drake:child></drake:joint></model>",
        "<literal-string>.sdf: error: ERROR: <drake:joint> 'joint_name' has unrecognized value "
        "for 'type' attribute: nonetype",
    ),
    "drake_joint_parent_in_an_unknown_model": (
        "<model name='good'><model name='nested'>" + _TWO_LINKS + "</model>"
        "<drake:joint type='planar' name='joint_name'><drake:parent>nesQQQted::a</drake:parent>"
        "<drake:child>nested::b</drake:child><drake:damping>0.1 0.1 0.1</drake:damping>"
        "</drake:joint></model>",
        "<literal-string>.sdf: error: <drake:joint>: Model instance name 'good::nesQQQted' "
        "(implied by frame name 'nesQQQted::a' in <drake:parent> within model instance 'good') "
        "does not exist in the model.",
    ),
    "drake_joint_child_in_an_unknown_model": (
        "<model name='good'><model name='nested'>" + _TWO_LINKS + "</model>"
        "<drake:joint type='planar' name='joint_name'><drake:parent>nested::a</drake:parent>"
        "<drake:child>nesQQQted::b</drake:child><drake:damping>0.1 0.1 0.1</drake:damping>"
        "</drake:joint></model>",
        "<literal-string>.sdf: error: <drake:joint>: Model instance name 'good::nesQQQted' "
        "(implied by frame name 'nesQQQted::b' in <drake:child> within model instance 'good') "
        "does not exist in the model.",
    ),
    "two_worlds": (
        "\n<world name='uno'>\n</world>\n<world name='dos'>\n</world>",
        "<literal-string>.sdf:1: error: File must have exactly one <model> or exactly one "
        "<world>, but instead has 0 models and 2 worlds",
    ),
}


@pytest.mark.parametrize("case", sorted(_JOINT_ERRORS))
def test_joint_and_document_errors_are_drakes(drake: ModuleType, case: str) -> None:
    """Upstream JointWithNoAxisError, JointAxisLimitsError, JointAxisDrakeAccelerationError,
    PrismaticJointWithNoAxisError, WorldJointNotFixedError, DrakeJoint*Error/Bad and
    MoreThanOneWorldOrModelError: the first error, at its element's line."""
    inner, message = _JOINT_ERRORS[case]
    assert _error(drake, _sdf(inner)) == message


def test_a_ball_joint_axis_is_only_warned_about(drake: ModuleType) -> None:
    """Upstream BallJointWithAxis2Error: warnings, an error under strict parsing."""
    inner = (
        "<model name='joint_no_axis'>" + _TWO_LINKS + "\n<joint name='should_not_have_axis' "
        "type='ball'><parent>a</parent><child>b</child><axis><xyz>0 0 1</xyz></axis><axis2>"
        "<xyz>0 0 1</xyz></axis2></joint></model>"
    )
    parse = _Parse(drake)
    parse.string(_sdf(inner))
    assert parse.joints() == [
        ("should_not_have_axis", "ball_rpy", "a", "should_not_have_axis_child", "joint_no_axis")
    ]
    strict = _Parse(drake)
    strict.parser.SetStrictParsing()
    with pytest.raises(RuntimeError) as info:
        strict.string(_sdf(inner))
    assert str(info.value) == (
        "<literal-string>.sdf:2: error: A ball joint axis will be ignored. Only the dynamic "
        "parameters and limits will be considered."
    )


def test_negative_joint_damping_is_an_error_at_the_joint(
    drake: ModuleType, drake_models: Path
) -> None:
    """Upstream ThrowsWhenJointDampingIsNegative."""
    path = drake_models / _SDF_TEST / "negative_damping_joint.sdf"
    with pytest.raises(RuntimeError) as info:
        _Parse(drake).file(path)
    assert str(info.value) == (
        f"/{path}:11: error: Joint damping is negative for joint 'joint'. Joint damping must be "
        "a non-negative number."
    )


def test_a_drake_joint_joins_frames_of_a_nested_model(drake: ModuleType) -> None:
    """Upstream DrakeJointNestedParentChild: a planar joint in the child's instance."""
    parse = _Parse(drake)
    parse.string(
        _sdf(
            "<model name='good'><model name='nested'>" + _TWO_LINKS + "</model>"
            "<drake:joint type='planar' name='joint_name'><drake:parent>nested::a</drake:parent>"
            "<drake:child>nested::b</drake:child><drake:damping>0.1 0.1 0.1</drake:damping>"
            "</drake:joint></model>"
        )
    )
    assert parse.joints() == [("joint_name", "planar", "a", "b", "good::nested")]


def test_joint_parsing_test_names_its_joints_and_their_types(
    drake: ModuleType, drake_models: Path
) -> None:
    """Upstream JointParsingTest: which joints the file makes, of which type, where."""
    parse = _Parse(drake)
    path = drake_models / _SDF_TEST / "joint_parsing_test.sdf"
    assert parse.file(path) == ["joint_parsing_test", "joint_parsing_test2"]
    first, second = "joint_parsing_test", "joint_parsing_test2"
    assert [(name, kind, instance) for name, kind, _, _, instance in parse.joints()] == [
        ("revolute_joint", "revolute", first),
        ("prismatic_joint", "prismatic", first),
        ("revolute_joint_no_limits", "revolute", first),
        ("ball_joint", "ball_rpy", first),
        ("universal_joint", "universal", first),
        ("continuous_joint", "revolute", first),
        ("screw_joint", "screw", first),
        ("planar_joint", "planar", first),
        ("curvilinear_joint_periodic", "curvilinear", first),
        ("curvilinear_joint_aperiodic", "curvilinear", first),
        ("planar_joint", "planar", second),
    ]


_CURVILINEAR = (
    "<model name='test'><link name='a'/><link name='b'/><drake:joint "
    'name="curvilinear_joint" type="curvilinear"><drake:parent>a</drake:parent>'
    "<drake:child>b</drake:child>{}</drake:joint></model>"
)
_CURVILINEAR_ERRORS = {
    "non_boolean_is_periodic": (
        "<drake:is_periodic>TRUE</drake:is_periodic><drake:curves><drake:line_segment>"
        "<drake:length>1.0</drake:length></drake:line_segment></drake:curves>",
        "<drake:is_periodic>: boolean node contains non-boolean value 'TRUE'.",
    ),
    "no_curves": ("", "<drake:joint>: Unable to find the <drake:curves> child node."),
    "segment_without_length": (
        "<drake:curves><drake:line_segment>\n</drake:line_segment></drake:curves>",
        "<drake:line_segment>: Unable to find the <drake:length> child tag.",
    ),
    "negative_damping": (
        "<drake:damping>-1</drake:damping><drake:curves><drake:line_segment><drake:length>1.0"
        "</drake:length></drake:line_segment></drake:curves>",
        "ERROR: <drake:joint> 'curvilinear_joint' has negative value for 'damping' attribute: "
        "-1.000000",
    ),
    "negative_radius": (
        "<drake:curves><drake:circular_arc><drake:radius>-2.0</drake:radius><drake:angle>1.57"
        "</drake:angle></drake:circular_arc></drake:curves>",
        "<drake:circular_arc>: A drake:circular_arc node has a 0 or negative drake:radius.",
    ),
    "unknown_curve": (
        "<drake:curves><drake:circular_arc><drake:radius>2.0</drake:radius><drake:angle>1.57"
        "</drake:angle></drake:circular_arc><drake:cirQQQcular_arc/></drake:curves>",
        "<drake:joint>: drake:curves node contains an invalid child node <drake:cirQQQcular_arc>.",
    ),
}


@pytest.mark.parametrize("case", sorted(_CURVILINEAR_ERRORS))
def test_curvilinear_joint_errors(drake: ModuleType, case: str) -> None:
    """Upstream CurvilinearJointErrors0..6 (no line: <drake:joint> is not SDFormat's)."""
    curves, message = _CURVILINEAR_ERRORS[case]
    text = _sdf(_CURVILINEAR.format(curves))
    assert _error(drake, text) == f"<literal-string>.sdf: error: {message}"


@pytest.mark.parametrize("kind", ["gearbox", "revolute2"])
def test_gearbox_and_revolute2_joints_are_not_supported(drake: ModuleType, kind: str) -> None:
    """Upstream GearboxJointParsingTest and Revolute2JointParsingTest."""
    inner = (
        "<model name='m'>" + _TWO_LINKS + f"\n<joint name='j' type='{kind}'><parent>a</parent>"
        "<child>b</child></joint></model>"
    )
    assert _error(drake, _sdf(inner)) == (
        f"<literal-string>.sdf:2: error: Joint type ({kind}) not supported for joint 'j'."
    )


def test_a_misspelled_joint_type_is_libsdformats_error(drake: ModuleType) -> None:
    """Upstream MisspelledJointParsingTest."""
    inner = (
        "<model name='m'>" + _TWO_LINKS + "<joint name='j' type='revoluteQQQ'>"
        "<parent>a</parent><child>b</child></joint></model>"
    )
    assert _error(drake, _sdf(inner)) == (
        "error: Joint type of revoluteqqq is invalid. Refer to the SDF documentation for a list "
        "of valid joint types"
    )


# ---------------------------------------------------------------------- includes
def test_included_model_directories_become_nested_instances(
    drake: ModuleType, drake_models: Path
) -> None:
    """Upstream IncludeTags: ``model://`` directories found through their model.config."""
    parse = _Parse(drake, scene_graph=False)
    test = drake_models / _SDF_TEST
    parse.package("simple_robot1", test / "simple_robot1")
    parse.package("simple_robot2", test / "simple_robot2")
    assert parse.file(test / "include_models.sdf") == [
        "robot1",
        "robot2",
        "weld_models",
        "weld_models::robot1",
        "weld_models::robot2",
    ]
    parse.plant.Finalize()
    assert parse.plant.num_model_instances() == 7
    assert parse.plant.num_bodies() == 9
    assert parse.plant.num_joints() == 8
    for instance in ("robot1", "robot2", "weld_models::robot1", "weld_models::robot2"):
        assert (instance, "base_link") in parse.bodies()
        assert (instance, "moving_link") in parse.bodies()
    joints = {(name, instance): kind for name, kind, _, _, instance in parse.joints()}
    assert joints[("slider", "weld_models::robot1")] == "prismatic"
    # By convention, the joint has the same model instance as its child frame.
    assert joints[("weld_robots", "weld_models::robot2")] == "revolute"


def test_a_merge_include_puts_the_included_links_in_the_parent(
    drake: ModuleType, drake_models: Path
) -> None:
    """Upstream MergeInclude."""
    parse = _Parse(drake, scene_graph=False)
    test = drake_models / _SDF_TEST
    parse.package("simple_robot1", test / "simple_robot1")
    parse.package("simple_robot2", test / "simple_robot2")
    assert parse.file(test / "merge_include_models.sdf") == ["robot1_with_tool"]
    parse.plant.Finalize()
    assert parse.plant.num_model_instances() == 3
    assert parse.plant.num_bodies() == 4
    assert parse.plant.num_joints() == 3
    assert parse.bodies() == [
        ("robot1_with_tool", "base_link"),
        ("robot1_with_tool", "moving_link"),
        ("robot1_with_tool", "tool"),
    ]
    # The merged model's frame stands in for it, on its canonical link.
    assert parse.frame("_merged__robot1__model__") == ("robot1_with_tool", "base_link")


def test_models_nested_in_a_world_model_are_instances(
    drake: ModuleType, drake_models: Path
) -> None:
    """Upstream LoadDirectlyNestedModelsInWorld."""
    parse = _Parse(drake, scene_graph=False)
    path = drake_models / _SDF_TEST / "world_with_directly_nested_models.sdf"
    assert parse.file(path) == ["parent_model", "parent_model::robot1", "parent_model::robot2"]
    parse.plant.Finalize()
    assert (parse.plant.num_model_instances(), parse.plant.num_bodies()) == (5, 5)
    assert parse.plant.num_joints() == 4
    assert (
        "weld_robots",
        "revolute",
        "base_link",
        "weld_robots_child",
        "parent_model::robot2",
    ) in (parse.joints())


def test_models_nested_two_deep_are_instances(drake: ModuleType, drake_models: Path) -> None:
    """Upstream LoadDirectlyNestedModelsInModel."""
    parse = _Parse(drake, scene_graph=False)
    path = drake_models / _SDF_TEST / "model_with_directly_nested_models.sdf"
    assert parse.file(path) == [
        "grand_parent_model",
        "grand_parent_model::parent_model",
        "grand_parent_model::parent_model::robot1",
        "grand_parent_model::parent_model::robot2",
    ]
    parse.plant.Finalize()
    assert (parse.plant.num_model_instances(), parse.plant.num_bodies()) == (6, 5)
    assert parse.plant.num_joints() == 4
    robot2 = "grand_parent_model::parent_model::robot2"
    assert ("weld_robots", "revolute", "base_link", "weld_robots_child", robot2) in (parse.joints())


def test_a_single_model_in_a_world_is_one_instance(drake: ModuleType, drake_models: Path) -> None:
    """Upstream TestSingleModelInWorld (regression test for #18878)."""
    parse = _Parse(drake)
    assert parse.file(drake_models / _SDF_TEST / "table_in_world.sdf") == ["table"]
    parse.plant.Finalize()
    assert parse.plant.num_model_instances() == 3


def test_a_document_may_hold_one_model_only(drake: ModuleType) -> None:
    """Upstream TestSingleModelEnforcement (and TestSdformatParserPolicies)."""
    text = (
        "\n  <sdf version='1.9'>\n  <model name='a'><link name='a'/></model>\n"
        "  <model name='b'><link name='b'/></model>\n  </sdf>\n"
    )
    assert _error(drake, text) == (
        "error: Root object can only contain one model. Using the first one found"
    )


# --------------------------------------------------------------------- frames
@pytest.mark.parametrize(
    "inner",
    [
        # //link/pose[@relative_to]
        "<model name='good'><frame name='my_frame'/><link name='my_link'>"
        "<pose relative_to='my_frame'/></link></model>",
        # //link/visual/pose[@relative_to]
        "<model name='good'><frame name='my_frame'/><link name='my_link'>"
        "<visual name='my_visual'><pose relative_to='my_frame'/></visual></link></model>",
        # //link/collision/pose[@relative_to]
        "<model name='good'><frame name='my_frame'/><link name='my_link'>"
        "<collision name='my_collision'><pose relative_to='my_frame'/></collision></link></model>",
        # //joint/pose[@relative_to]
        "<model name='good'><link name='a'/><frame name='my_frame'/><joint name='b' type='fixed'>"
        "<pose relative_to='my_frame'/><parent>world</parent><child>a</child></joint></model>",
    ],
    ids=["link", "visual", "collision", "joint"],
)
def test_poses_may_be_relative_to_a_model_frame(drake: ModuleType, inner: str) -> None:
    """Upstream TestSupportedFrames1..4."""
    parse = _Parse(drake)
    assert parse.string(_sdf(inner)) == ["good"]
    assert parse.frame("my_frame") == ("good", parse.bodies()[0][1])


_FRAME_ERRORS = {
    "attached_to_world": (
        "<model name='bad'><link name='dont_crash_plz'/><frame name='model_scope_world_frame' "
        "attached_to='world'><pose>0 0 0 0 0 0</pose></frame></model>",
        "error: attached_to name[world] specified by frame with name[model_scope_world_frame] "
        "does not match a nested model, link, joint, or frame name in model with name[bad].",
    ),
    "relative_to_world": (
        "<model name='bad'><link name='dont_crash_plz'/><frame "
        "name='model_scope_world_relative_frame'><pose relative_to='world'>0 0 0 0 0 0</pose>"
        "</frame></model>",
        "error: relative_to name[world] specified by frame with "
        "name[model_scope_world_relative_frame] does not match a nested model, link, joint, or "
        "frame name in model with name[bad].",
    ),
    "named_world": (
        "<model name='bad'><link name='dont_crash_plz'/><frame name='world'/></model>",
        "error: The supplied frame name [world] is reserved.",
    ),
    "named___model__": (
        "<model name='bad'><link name='dont_crash_plz'/><frame name='__model__'/></model>",
        "error: The supplied frame name [__model__] is reserved.",
    ),
    "named___anything__": (
        "<model name='bad'><link name='dont_crash_plz'/><frame name='__anything__'/></model>",
        "error: The supplied frame name [__anything__] is reserved.",
    ),
    "top_level_relative_to": (
        "<model name='bad'>\n<pose relative_to='invalid_usage'/><link name='dont_crash_plz'/>"
        "</model>",
        # N.B. libsdformat names the text "<data-string>" and then wraps it again here.
        "<<data-string>>:2: error: Attribute //pose[@relative_to] of top level model must be "
        "left empty, found //pose[@relative_to='invalid_usage'].\n",
    ),
    "inertial_pose_relative_to": (
        "<model name='bad'><frame name='my_frame'/><link name='a'>\n<inertial>"
        "<pose relative_to='my_frame'/></inertial></link></model>",
        '<data-string>:2: error: At XML path /sdf/model[@name="bad"]/link[@name="a"]/inertial/'
        'pose[@relative_to="my_frame"]: XML Attribute[relative_to] in element[pose] not defined '
        "in SDF.\n",
    ),
}


@pytest.mark.parametrize("case", sorted(_FRAME_ERRORS))
def test_unsupported_frames_are_libsdformats_errors(drake: ModuleType, case: str) -> None:
    """Upstream TestUnsupportedFrames: model frames cannot reach the world frame."""
    inner, message = _FRAME_ERRORS[case]
    assert _error(drake, _sdf(inner)) == message


def test_a_placement_frame_poses_a_nested_model(drake: ModuleType) -> None:
    """Upstream ModelPlacementFrame: names and bodies (poses are the upstream test's)."""
    parse = _Parse(drake)
    parse.string(
        _sdf(
            "<model name='table'><pose>0 10 0  0 0 0</pose><link name='table_top'>"
            "<pose>0 0 1  0 0 0</pose></link><model name='mug' placement_frame='base'>"
            "<pose relative_to='table_top'/><link name='handle'><pose>0.1 0 0  0 0 0</pose>"
            "</link><link name='base'><pose>0 0 -0.1  0 0 0</pose></link></model></model>",
            "1.8",
        )
    )
    assert parse.instances()[2:] == ["table", "table::mug"]
    assert parse.frame("__model__", "table::mug") == ("table::mug", "handle")
    assert parse.frame("table_top") == ("table", "table_top")


def test_frames_attach_to_links_and_models_nested_two_deep(drake: ModuleType) -> None:
    """Upstream FrameAttachedToMultiLevelNestedFrame: both frames are on link d."""
    parse = _Parse(drake)
    parse.string(
        _sdf(
            "<model name='a'><pose>0.1 0 0  0 0 0</pose><model name='b'><pose>0 0.2 0.0  0 0 0"
            "</pose><model name='c'><pose>0 0.0 0.3  0 0 0</pose><link name='d'><pose>0 0.0 0.0"
            "  0 0.5 0.6</pose></link></model></model><frame name='e' attached_to='b::c::d'>"
            "<pose>0 0 0  0.4 0 0.0</pose></frame><frame name='f' attached_to='b::c'><pose>0 0 0"
            "  0.4 0.5 0.6</pose></frame></model>",
            "1.8",
        )
    )
    # N.B. A frame is in the model instance of the frame it is attached to.
    assert parse.frame("e") == ("a::b::c", "d")
    assert parse.frame("f") == ("a::b::c", "d")


def test_frames_and_links_of_sibling_models_may_share_names(drake: ModuleType) -> None:
    """Upstream RepeatedLinkName."""
    parse = _Parse(drake)
    world = (
        "<world name='a'><model name='b1'><link name='c'/><frame name='d'/></model>"
        "<model name='b2'><link name='c'/><frame name='d'/></model></world>"
    )
    assert parse.string(_sdf(world, "1.8")) == ["b1", "b2"]
    assert parse.frame("d", "b1") == ("b1", "c")
    assert parse.frame("d", "b2") == ("b2", "c")


def test_world_frames_attach_to_models(drake: ModuleType) -> None:
    """Upstream FrameAttachedToModelFrameInWorld."""
    parse = _Parse(drake)
    parse.string(
        _sdf(
            "<world name='a'><model name='b'><pose>0.1 0.2 0.0  0 0 0</pose><model name='c'>"
            "<pose>0 0.0 0.3  0 0 0</pose><link name='d'/></model></model><frame name='e' "
            "attached_to='b'><pose>0 0 0.3  0.0 0.0 0.0</pose></frame><frame name='f' "
            "attached_to='b::c'><pose>0 0 0  0.0 0.0 0.6</pose></frame></world>",
            "1.8",
        )
    )
    assert parse.frame("e") == ("b", "d")
    assert parse.frame("f") == ("b::c", "d")


def test_frames_attach_to_joints_through_their_child_links(drake: ModuleType) -> None:
    """Upstream FrameAttachedToJointFrame: Drake makes no frame for a joint."""
    parse = _Parse(drake)
    parse.string(
        _sdf(
            "<world name='default'><model name='parent_model'><pose>0.1 0.2 0.0  0 0 0</pose>"
            "<link name='L1'/><link name='L2'/><model name='M1'><pose>0 0.0 0.3  0 0 0</pose>"
            "<link name='L3'/></model><joint name='J1' type='fixed'><parent>L1</parent>"
            "<child>L2</child></joint><joint name='J2' type='fixed'><parent>L1</parent>"
            "<child>M1::L3</child></joint><frame name='F1' attached_to='J1'/>"
            "<frame name='F2' attached_to='J2'/></model></world>",
            "1.8",
        )
    )
    assert parse.frame("F1") == ("parent_model", "L2")
    assert parse.frame("F2") == ("parent_model::M1", "L3")
    assert parse.joints() == [
        ("J1", "weld", "L1", "J1_child", "parent_model"),
        ("J2", "weld", "J2_parent", "J2_child", "parent_model::M1"),
    ]


def test_a_canonical_link_may_be_nested_or_not_first(drake: ModuleType) -> None:
    """Upstream SupportNonDefaultCanonicalLink."""
    parse = _Parse(drake)
    parse.string(
        _sdf(
            "<model name='a' canonical_link='c::e'><link name='b'/><model name='c' "
            "canonical_link='f'><link name='d'/><link name='e'/><link name='f'/></model></model>",
            "1.8",
        )
    )
    parse.plant.Finalize()
    assert parse.frame("__model__", "a") == ("a", "e")
    assert parse.frame("__model__", "a::c") == ("a::c", "f")


def test_frames_may_be_joint_parents_and_children(drake: ModuleType, drake_models: Path) -> None:
    """Upstream FramesAsJointParentOrChild."""
    parse = _Parse(drake)
    parse.file(drake_models / _SDF_TEST / "frames_as_joint_parent_or_child.sdf")
    parse.plant.Finalize()
    joints = {
        name: (parent, child, instance) for name, _, parent, child, instance in parse.joints()
    }
    assert joints["J1"] == ("J1_parent", "J1_child", "parent_model")
    assert joints["J2"] == ("J2_parent", "J2_child", "parent_model::M2")
    assert parse.frame("J1_parent") == ("parent_model", "L1")
    assert parse.frame("J1_child") == ("parent_model", "L2")
    assert parse.frame("J2_parent") == ("parent_model::M2", "base_link")
    assert parse.frame("J2_child") == ("parent_model::M2", "base_link")


def test_the_world_joint_file_joins_two_models(drake: ModuleType, drake_models: Path) -> None:
    """Upstream WorldJoint."""
    parse = _Parse(drake)
    assert parse.file(drake_models / _SDF_TEST / "world_joint_test.sdf") == [
        "parent_model",
        "child_model",
    ]
    parse.plant.Finalize()
    assert parse.plant.num_model_instances() == 4
    assert parse.joints()[:2] == [
        ("J1", "weld", "J1_parent", "J1_child", "child_model"),
        ("J2", "weld", "world", "J2_child", "parent_model"),
    ]
    assert parse.frame("J1_parent") == ("child_model", "L_P")
    assert parse.frame("J1_child") == ("child_model", "L_C")
    assert parse.frame("child_frame") == ("child_model", "L_C")


def test_poses_may_be_in_degrees_or_quaternions(drake: ModuleType) -> None:
    """Upstream PoseWithRotationInDegreesOrQuaternions: the three links are read."""
    parse = _Parse(drake)
    parse.string(
        _sdf(
            "<model name='test_model'><link name='E1'><pose degrees='true'>1 2 3   15 30 45</pose>"
            "</link><link name='E2'><pose rotation_format=\"euler_rpy\" degrees='true'>1 2 3   "
            "15 30 45</pose></link><link name='Q'><pose rotation_format='quat_xyzw'>1 2 3 "
            "0.3826834323650898 0 0 0.9238795325112867</pose></link></model>",
            "1.9",
        )
    )
    assert parse.bodies() == [("test_model", "E1"), ("test_model", "E2"), ("test_model", "Q")]


# ---------------------------------------------------------- libsdformat policies
_POLICY_ERRORS = {
    "undefined_attribute": (
        "<model name='model_with_bad_attribute' bad_attribute=\"junk\">\n<link name='a'/></model>",
        "1.6",
        '<data-string>:1: error: At XML path /sdf/model[@name="model_with_bad_attribute"]'
        '[@bad_attribute="junk"]: XML Attribute[bad_attribute] in element[model] not defined '
        "in SDF.\n",
    ),
    "undefined_element": (
        "<model name='model_with_bad_element'>\n<link name='a'/>\n<bad_element/>\n</model>",
        "1.6",
        '<data-string>:3: error: At XML path /sdf/model[@name="model_with_bad_element"]/'
        "bad_element: XML Element[bad_element], child of element[model], not defined in SDF. "
        "Copying[bad_element] as children of [model].\n",
    ),
    "undefined_axis_element": (
        "<model name='model_with_initial_position'><link name='l1'/><link name='l2'/>"
        "<joint name='b' type=\"revolute\"><child>l1</child><parent>l2</parent><axis>\n"
        "<initial_position>0</initial_position></axis></joint></model>",
        "1.9",
        '<data-string>:2: error: At XML path /sdf/model[@name="model_with_initial_position"]/'
        'joint[@name="b"]/axis/initial_position: XML Element[initial_position], child of '
        "element[axis], not defined in SDF. Copying[initial_position] as children of [axis].\n",
    ),
}


@pytest.mark.parametrize("case", sorted(_POLICY_ERRORS))
def test_libsdformat_warnings_are_errors(drake: ModuleType, case: str) -> None:
    """Upstream TestSdformatParserPolicies: Drake makes libsdformat's warnings errors."""
    inner, version, message = _POLICY_ERRORS[case]
    assert _error(drake, _sdf(inner, version)) == message


def test_a_deprecated_element_is_a_warning_and_an_error_when_strict(drake: ModuleType) -> None:
    """Upstream TestSdformatParserPolicies: Drake's own deprecated test element."""
    inner = (
        "<model name='deprecation_test'><link name='l1'/></model>\n"
        "<_drake_deprecation_unit_test_element/>"
    )
    assert _Parse(drake).string(_sdf(inner, "1.9")) == ["deprecation_test"]
    strict = _Parse(drake)
    strict.parser.SetStrictParsing()
    with pytest.raises(RuntimeError) as info:
        strict.string(_sdf(inner, "1.9"))
    assert str(info.value) == (
        "error: At XML path /sdf/_drake_deprecation_unit_test_element: SDF "
        "Element[_drake_deprecation_unit_test_element] is deprecated\n"
    )


def test_unsupported_elements_warn_and_drake_ones_are_errors(
    drake: ModuleType, drake_models: Path
) -> None:
    """Upstream UnsupportedElements: the first error is the link's <drake:proximity_properties>
    (no line: libsdformat keeps none for elements it does not define); under strict parsing
    the first warning (<self_collide>) is."""
    path = drake_models / _SDF_TEST / "unsupported_elements.sdf"
    with pytest.raises(RuntimeError) as info:
        _Parse(drake).file(path)
    assert str(info.value) == (
        f"/{path}: error: Unsupported SDFormat element in link: drake:proximity_properties"
    )
    strict = _Parse(drake)
    strict.parser.SetStrictParsing()
    with pytest.raises(RuntimeError) as info:
        strict.file(path)
    assert str(info.value) == (
        f"/{path}:7: error: Ignoring unsupported SDFormat element in link: self_collide"
    )


# -------------------------------------------------------------------- geometry
_SHAPES = ("Box", "Capsule", "Convex", "Cylinder", "Ellipsoid", "HalfSpace", "Mesh", "Sphere")


@pytest.mark.parametrize(
    ("file", "roles"),
    [("all_geometries_as_collision.sdf", "P"), ("all_geometries_as_visual.sdf", "IR")],
)
def test_every_shape_drake_reads_is_registered(
    drake: ModuleType, drake_models: Path, file: str, roles: str
) -> None:
    """Upstream GeometrySdfParserTest Collision/VisualGeometryParsing: each shape, named after
    its type (<drake:capsule>, <drake:ellipsoid> and <drake:declare_convex/> included)."""
    parse = _Parse(drake).drake_package(drake_models)
    parse.file(drake_models / _SDF_TEST / file)
    parse.plant.Finalize()
    found = {(name, shape) for name, frame, shape, r in parse.geometries() if r == roles}
    for shape in _SHAPES:
        assert (f"test_robot::{shape}", shape) in found
    assert ("test_robot::DrakeCapsule", "Capsule") in found
    assert ("test_robot::DrakeEllipsoid", "Ellipsoid") in found


@pytest.mark.parametrize("shape", ["heightmap", "polyline"])
@pytest.mark.parametrize("role", ["visual", "collision"])
def test_unsupported_geometry_registers_nothing(drake: ModuleType, role: str, shape: str) -> None:
    """Upstream TestUnsupportedVisualGeometry and TestUnsupportedCollisionGeometry."""
    inner = (
        f'<model name="{shape}_model"><link name="a">\n<{role} name="b"><geometry><{shape}/>'
        f"</geometry></{role}></link></model>"
    )
    parse = _Parse(drake)
    parse.string(_sdf(inner))
    assert parse.geometries() == set()
    strict = _Parse(drake)
    strict.parser.SetStrictParsing()
    with pytest.raises(RuntimeError) as info:
        strict.string(_sdf(inner))
    assert str(info.value) == (
        f"<literal-string>.sdf:2: error: Ignoring unsupported SDFormat element in geometry: {shape}"
    )


_VISUALS = """
  <model name="visual_model">
    <link name="unused_default_geometry">
      <visual name="general_visual">
        <pose>-1 0 0 0 0 0</pose>
        <geometry><box><size>1 1 1</size></box></geometry>
        <drake:perception_properties enabled="false"/>
        <drake:illustration_properties enabled="false"/>
      </visual>
      <drake:visual name="non-existent">
        <drake:geometry><drake:sphere><drake:radius>10</drake:radius></drake:sphere>
        </drake:geometry>
        <drake:perception_properties enabled="false"/>
        <drake:illustration_properties enabled="false"/>
      </drake:visual>
      <drake:visual name="illustration">
        <drake:pose>1 0 0 0 0 0</drake:pose>
        <drake:geometry><drake:cylinder><drake:radius>0.8</drake:radius>
          <drake:length>0.02</drake:length></drake:cylinder></drake:geometry>
        <drake:perception_properties enabled="false"/>
      </drake:visual>
      <drake:visual name="perception">
        <drake:pose>0 0 0 0 0 0</drake:pose>
        <drake:geometry><drake:sphere><drake:radius>2</drake:radius></drake:sphere>
        </drake:geometry>
        <drake:illustration_properties enabled="false"/>
      </drake:visual>
    </link>
  </model>"""


def test_visual_roles_can_be_turned_off_one_by_one(drake: ModuleType) -> None:
    """Upstream VisualRoleConfiguration: a visual gets only the roles left enabled."""
    parse = _Parse(drake)
    parse.string(_sdf(_VISUALS))
    frame = "visual_model::unused_default_geometry"
    assert parse.geometries() == {
        ("visual_model::illustration", frame, "Cylinder", "I"),
        ("visual_model::perception", frame, "Sphere", "R"),
    }


def test_a_visual_with_both_roles_off_is_warned_about(drake: ModuleType) -> None:
    """Upstream VisualRoleConfiguration: the warning for a <visual> (not a <drake:visual>)."""
    parse = _Parse(drake)
    parse.parser.SetStrictParsing()
    with pytest.raises(RuntimeError) as info:
        parse.string(_sdf(_VISUALS))
    assert str(info.value) == (
        '<literal-string>.sdf:4: error: The <visual name="general_visual"> tag had all visual '
        "roles turned off for Drake; this model may appear very different in Drake from other "
        "sdformat loaders."
    )


def test_drake_visual_children_must_be_drake_namespaced(drake: ModuleType) -> None:
    """Upstream VisualRoleConfiguration: ``bad_nesting``."""
    inner = (
        '<model name="visual_model"><link name="l"><drake:visual name="bad_nesting">'
        "<pose>0 0 0 0 0 0</pose></drake:visual></link></model>"
    )
    assert _error(drake, _sdf(inner)) == (
        "<literal-string>.sdf: error: All tags under a drake-namespaced tag must likewise be "
        "drake-namespaced."
    )


# ----------------------------------------------------------------- Interface API
def test_urdf_included_through_the_interface_api(drake: ModuleType, drake_models: Path) -> None:
    """Upstream InterfaceApi: the URDF is parsed first, then the SDFormat models; collision
    filtering across models before Finalize, and the parser's group report."""
    api_test = drake_models / _SDF_TEST / "interface_api_test"
    parse = _Parse(drake).package("interface_api_test", api_test)
    assert parse.file(api_test / "top.sdf") == [
        "top",
        "top::tactile_sensor",
        "top::gripper",
        "top::table",
        "top::mug",
    ]
    assert parse.instances()[2:4] == ["top::arm", "top"]
    assert parse.geometries() == {
        ("top::arm::L1", "top::arm::L1", "Sphere", "P"),
        ("top::arm::L2", "top::arm::L2", "Sphere", "P"),
        ("top::gripper::gripper_link", "top::gripper::gripper_link", "Sphere", "P"),
        ("top::torso", "top::torso", "Sphere", "P"),
    }
    assert parse.filtered_pairs() == {
        ("top::arm::L1", "top::gripper::gripper_link"),
        ("top::arm::L1", "top::torso"),
        ("top::gripper::gripper_link", "top::torso"),
    }
    assert parse.groups() == (
        {"top::g1": ["top::arm::L1", "top::gripper::gripper_link", "top::torso"]},
        [["top::g1", "top::g1"]],
    )
    # The URDF's joint frame and the placed mug's frames.
    assert parse.frame("__model__", "top::arm") == ("top::arm", "L1")
    assert parse.frame("top", "top::mug") == ("top::mug", "body")
    assert parse.frame("mug_top_alias") == ("top::mug", "body")
    assert parse.frame("table_top_alias") == ("top::table", "body")


def test_errors_of_an_included_urdf_reach_the_caller(drake: ModuleType, drake_models: Path) -> None:
    """Upstream ErrorsFromIncludedUrdf (the package is the vendored test folder)."""
    inner = (
        '<model name="top"><link name="torso"/><include><pose relative_to="torso">1 0 0 0 0 0'
        "</pose><uri>package://sdf_parser_test/bad.urdf</uri><name>arm</name></include></model>"
    )
    parse = _Parse(drake).package("sdf_parser_test", drake_models / _SDF_TEST)
    with pytest.raises(RuntimeError) as info:
        parse.string(_sdf(inner, "1.8"))
    assert re.fullmatch(r".*bad\.urdf.*XML_ERROR.*", str(info.value))


def test_a_urdf_and_an_sdformat_model_merge_into_one_model(
    drake: ModuleType, drake_models: Path
) -> None:
    """Upstream BasicMergeIncludeInterfaceApi."""
    api_test = drake_models / _SDF_TEST / "interface_api_test"
    parse = _Parse(drake).package("interface_api_test", api_test)
    assert parse.file(api_test / "arm_with_gripper_merge_include.sdf") == ["arm_with_gripper"]
    parse.plant.Finalize()
    assert parse.plant.num_model_instances() == 3
    assert parse.plant.num_bodies() == 4
    assert parse.plant.num_joints() == 3
    assert parse.bodies() == [
        ("arm_with_gripper", "L1"),
        ("arm_with_gripper", "L2"),
        ("arm_with_gripper", "gripper_link"),
    ]
    joints = {name: instance for name, _, _, _, instance in parse.joints()}
    assert joints["J1"] == "arm_with_gripper"
    # The URDF's model frame and the gripper's stand for the merged models.
    assert parse.frame("_merged__arm__model__") == ("arm_with_gripper", "L1")
    assert parse.frame("_merged__gripper__model__") == ("arm_with_gripper", "gripper_link")
    assert parse.frame("__model__") == ("arm_with_gripper", "gripper_link")


def test_a_merge_include_reaches_frames_of_the_merged_model(
    drake: ModuleType, drake_models: Path
) -> None:
    """Upstream MergeIncludeInterfaceApi's arm_merge_include.sdf (its SDFormat part): J3's child
    ``grasp_frame`` comes from the merge-included gripper."""
    api_test = drake_models / _SDF_TEST / "interface_api_test"
    parse = _Parse(drake).package("interface_api_test", api_test)
    assert parse.file(api_test / "arm_merge_include.sdf") == ["arm", "arm::flange"]
    assert parse.joints() == [
        ("J1", "revolute", "J1_parent", "J1_child", "arm"),
        ("J2", "weld", "J2_parent", "J2_child", "arm::flange"),
        ("J3", "weld", "J3_parent", "J3_child", "arm"),
    ]
    assert parse.frame("grasp_frame") == ("arm", "gripper_link")
    assert not parse.plant.HasModelInstanceNamed(name="arm::gripper")


def _check_merge_include_poses(drake: ModuleType, parse: _Parse, prefix: str) -> None:
    """Upstream TestMergeIncludeWithInterfaceApi: the merge-included SDFormat, URDF and MuJoCo
    arms of top_merge_include.sdf (no nested model instances for them), and their poses."""
    plant, join = parse.plant, (lambda name: f"{prefix}::{name}")
    for absent in (
        "arm::gripper",
        "arm_sdf::test_arm_sdf_name",
        "arm_urdf::test_arm_urdf_name",
        "arm_sdf_name_override::test_arm_sdf_name",
        "arm_urdf_name_override::test_arm_urdf_name",
    ):
        assert not plant.HasModelInstanceNamed(name=join(absent))
    instance = {
        name: plant.GetModelInstanceByName(name=join(name))
        for name in ("arm_urdf", "arm_urdf_name_override", "arm_sdf", "arm_mjcf")
    }
    assert plant.HasFrameNamed(name="_merged__arm__model__", model_instance=instance["arm_urdf"])
    assert plant.HasFrameNamed(
        name="_merged__test_arm_urdf_name__model__",
        model_instance=instance["arm_urdf_name_override"],
    )
    context = plant.CreateDefaultContext()
    math = drake.math

    def X_W(name: str, model: Any) -> Any:
        frame = plant.GetFrameByName(name=name, model_instance=model)
        return frame.CalcPoseInWorld(context=context)

    def pose(rpy: list[float], p: list[float]) -> Any:
        return math.RigidTransform(rpy=math.RollPitchYaw(rpy=rpy), p=p)

    X_WT = pose([0, 0, 0], [0, 0, 1])
    flange = plant.GetModelInstanceByName(name=join("arm_sdf::flange"))
    expected = [
        ("grasp_frame", instance["arm_sdf"], pose([0.1, 0.2, 0.3], [1, 2, 4])),
        ("__model__", instance["arm_sdf"], X_WT),
        ("L1", instance["arm_sdf"], pose([0, 0, 0], [1, 0, 1])),
        ("__model__", instance["arm_urdf"], X_WT),
        ("L2", instance["arm_urdf"], pose([0.1, 0.2, 0.3], [1, 4, 4])),
        ("__model__", flange, pose([0, 0, 0], [1, 2, 2])),
        ("gripper_mount", flange, pose([0.1, 0.2, 0.3], [1, 2, 4])),
        ("__model__", instance["arm_mjcf"], X_WT),
        ("L2", instance["arm_mjcf"], pose([0.1, 0.2, 0.3], [11, 4, 4])),
    ]
    for name, model, X_expected in expected:
        X = X_W(name, model)
        assert np.allclose(X.GetAsMatrix4(), X_expected.GetAsMatrix4(), rtol=0, atol=1e-13), name


def test_a_mujoco_arm_merges_into_a_model_beside_sdformat_and_urdf_arms(
    drake: ModuleType, drake_models: Path
) -> None:
    """Upstream MergeIncludeInterfaceApi1 (top_merge_include.sdf merge-includes arm.xml)."""
    api_test = drake_models / _SDF_TEST / "interface_api_test"
    parse = _Parse(drake).package("interface_api_test", api_test)
    parse.file(api_test / "top_merge_include.sdf")
    parse.plant.Finalize()
    _check_merge_include_poses(drake, parse, "top")


def test_a_world_merge_includes_the_mujoco_arm_in_each_top(
    drake: ModuleType, drake_models: Path
) -> None:
    """Upstream MergeIncludeInterfaceApi2 (top_merge_include_world.sdf, two tops)."""
    api_test = drake_models / _SDF_TEST / "interface_api_test"
    parse = _Parse(drake).package("interface_api_test", api_test)
    parse.file(api_test / "top_merge_include_world.sdf")
    parse.plant.Finalize()
    for prefix in ("top", "another_top"):
        _check_merge_include_poses(drake, parse, prefix)


def test_a_model_of_mujoco_includes_merges_into_the_world(
    drake: ModuleType, drake_models: Path
) -> None:
    """Upstream MergeIncludeIntoWorld (top_merge_include_in_nested_model.sdf)."""
    api_test = drake_models / _SDF_TEST / "interface_api_test"
    parse = _Parse(drake).package("interface_api_test", api_test)
    parse.string(
        "<sdf version='1.10'><world name='merge_into_world'><include merge=\"true\"><uri>"
        "package://interface_api_test/top_merge_include_in_nested_model.sdf"
        "</uri></include></world></sdf>"
    )
    parse.plant.Finalize()
    for prefix in ("top", "another_top"):
        _check_merge_include_poses(drake, parse, prefix)


# ------------------------------------------------------- collision filter groups
def test_collision_filter_groups_of_included_robots(drake: ModuleType, drake_models: Path) -> None:
    """Upstream CollisionFilterGroupParsingTest: filtering before Finalize, and the report."""
    folder = drake_models / _SDF_TEST / "collision_filter_group_parsing_test"
    parse = _Parse(drake).package("collision_filter_group_parsing_test", folder)
    assert parse.file(folder / "test.sdf") == ["test", "test::robot1", "test::robot2"]
    assert len(parse.geometries()) == 12
    assert all(roles == "P" for *_, roles in parse.geometries())

    def within(robot: str) -> set[tuple[str, str]]:
        pairs = [(1, 3), (1, 4), (2, 3), (2, 5), (2, 6), (3, 4), (3, 5), (3, 6), (5, 6)]
        return {
            (f"test::{robot}::link{a}_sphere", f"test::{robot}::link{b}_sphere") for a, b in pairs
        }

    assert parse.filtered_pairs() == within("robot1") | within("robot2") | {
        # Filtered across both robots.
        ("test::robot1::link3_sphere", "test::robot2::link3_sphere"),
        ("test::robot1::link6_sphere", "test::robot2::link6_sphere"),
        # Filtered by group_of_groups.
        ("test::robot1::link2_sphere", "test::robot2::link3_sphere"),
    }
    groups, pairs = parse.groups()
    expected = {
        "test::group_3s": ["test::robot1::link3"],
        "test::group_6s": ["test::robot1::link6", "test::robot2::link6"],
        "test::group_of_groups": ["test::robot1::link2", "test::robot2::link3"],
    }
    for robot in ("robot1", "robot2"):
        expected.update(
            {
                f"test::{robot}::group_link14": [f"test::{robot}::link1", f"test::{robot}::link4"],
                f"test::{robot}::group_link2": [f"test::{robot}::link2"],
                f"test::{robot}::group_link3": [f"test::{robot}::link3"],
                f"test::{robot}::group_link56": [f"test::{robot}::link5", f"test::{robot}::link6"],
            }
        )
    assert groups == expected
    expected_pairs = [
        ["test::group_3s", "test::robot2::group_link3"],
        ["test::group_6s", "test::group_6s"],
        ["test::group_of_groups", "test::group_of_groups"],
    ]
    for robot in ("robot1", "robot2"):
        group = f"test::{robot}::group_link"
        expected_pairs += [
            [f"{group}14", f"{group}14"],
            [f"{group}14", f"{group}3"],
            [f"{group}2", f"{group}3"],
            [f"{group}2", f"{group}56"],
            [f"{group}3", f"{group}56"],
            [f"{group}56", f"{group}56"],
        ]
    assert pairs == sorted(expected_pairs)


def test_the_filter_group_file_can_be_added_a_second_time(
    drake: ModuleType, drake_models: Path
) -> None:
    """Upstream CollisionFilterGroupParsingTest: 'Make sure we can add the model a second time'
    (here under a parse prefix, the public API's way to name it anew)."""
    folder = drake_models / _SDF_TEST / "collision_filter_group_parsing_test"
    parse = _Parse(drake).package("collision_filter_group_parsing_test", folder)
    parse.file(folder / "test.sdf")
    second = drake.multibody.parsing.Parser(plant=parse.plant, model_name_prefix="model2")
    second.package_map().Add(
        package_name="collision_filter_group_parsing_test", package_path=str(folder)
    )
    models = second.AddModels(file_name=str(folder / "test.sdf"))
    assert [parse.plant.GetModelInstanceName(model_instance=m) for m in models] == [
        "model2::test",
        "model2::test::robot1",
        "model2::test::robot2",
    ]


_GROUP_ERRORS = {
    "group_without_a_name": (
        "<model name='error1'><link name='a'/><drake:collision_filter_group/></model>",
        "<literal-string>.sdf: error: The tag <drake:collision_filter_group> is missing the "
        'required attribute "name"',
    ),
    "member_without_a_value": (
        "<model name='error2'><link name='a'/><drake:collision_filter_group name=\"group_a\">"
        "<drake:member></drake:member><drake:member_group></drake:member_group>"
        "</drake:collision_filter_group></model>",
        "<literal-string>.sdf: error: The tag <drake:member> is missing a required string value.",
    ),
    # N.B. The group is declared (and found empty) before its ignored groups are read.
    "group_with_only_an_empty_ignored_group": (
        "<model name='error3'><link name='a'/><drake:collision_filter_group name=\"group_a\">"
        "<drake:ignored_collision_filter_group>\n</drake:ignored_collision_filter_group>"
        "</drake:collision_filter_group></model>",
        "<literal-string>.sdf:1: error: group 'error3::group_a' has no members",
    ),
}


@pytest.mark.parametrize("case", sorted(_GROUP_ERRORS))
def test_collision_filter_group_errors(drake: ModuleType, case: str) -> None:
    """Upstream CollisionFilterGroupParsingErrorsTest: the first of its errors."""
    inner, message = _GROUP_ERRORS[case]
    assert _error(drake, _sdf(inner)) == message


# ------------------------------------------------------------------ deformables
def test_a_deformable_link_on_a_continuous_plant_is_drakes_error(
    drake: ModuleType, drake_models: Path
) -> None:
    """Upstream's deformable tests use a discrete plant; on a continuous one Drake refuses
    the body (deformables are outside reimpl's subset, this error is not)."""
    inner = (
        "<model name='deformable'><link name='body'><collision name='collision'><geometry><mesh>"
        "<uri>package://drake/multibody/parsing/test/single_tet.vtk</uri></mesh></geometry>"
        "</collision><drake:deformable_properties/></link></model>"
    )
    parse = _Parse(drake).drake_package(drake_models)
    with pytest.raises(RuntimeError) as info:
        parse.string(_sdf(inner))
    assert str(info.value) == (
        "Calls to RegisterDeformableBody() with a DeformableModel belonging to a continuous "
        "MultibodyPlant are not allowed."
    )
