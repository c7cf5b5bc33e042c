# Ported from Drake: bindings/pydrake/geometry/test/common_test.py
# (https://github.com/RobotLocomotion/drake), the parts about the collision-filtering
# subset (collision filtering, frames, instances, properties, identifiers), re-expressed
# as pytest functions that run unchanged on pydrake and on reimpl.
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
"""Upstream geometry common binding tests, filter subset, on pydrake and on reimpl."""

from __future__ import annotations

import copy
from types import ModuleType

import pytest


def test_collision_filtering(drake: ModuleType) -> None:
    g = drake.geometry
    sg = g.SceneGraph()
    sg_context = sg.CreateDefaultContext()
    geometries = g.GeometrySet()

    for manager in (sg.collision_filter_manager(), sg.collision_filter_manager(sg_context)):
        assert isinstance(manager, g.CollisionFilterManager)

    dut = sg.collision_filter_manager(sg_context)
    dut.Apply(declaration=g.CollisionFilterDeclaration().ExcludeBetween(geometries, geometries))
    dut.Apply(declaration=g.CollisionFilterDeclaration().ExcludeWithin(geometries))
    dut.Apply(
        declaration=g.CollisionFilterDeclaration().AllowBetween(set_A=geometries, set_B=geometries)
    )
    dut.Apply(declaration=g.CollisionFilterDeclaration().AllowWithin(geometry_set=geometries))

    filter_id = dut.ApplyTransient(
        declaration=g.CollisionFilterDeclaration().ExcludeWithin(geometries)
    )
    assert dut.has_transient_history()
    assert dut.IsActive(filter_id=filter_id)
    assert dut.RemoveDeclaration(filter_id=filter_id)


def test_geometry_frame_api(drake: ModuleType) -> None:
    g = drake.geometry
    frame = g.GeometryFrame(frame_name="test_frame")
    assert isinstance(frame.id(), g.FrameId)
    assert frame.name() == "test_frame"
    frame = g.GeometryFrame(frame_name="test_frame", frame_group_id=1)
    assert frame.frame_group() == 1


def test_geometry_instance_api(drake: ModuleType) -> None:
    g = drake.geometry
    RigidTransform = drake.math.RigidTransform
    geometry = g.GeometryInstance(X_PG=RigidTransform(), shape=g.Sphere(1.0), name="sphere")
    assert isinstance(geometry.id(), g.GeometryId)
    geometry.set_pose(RigidTransform([1, 0, 0]))
    assert isinstance(geometry.pose(), RigidTransform)
    assert isinstance(geometry.shape(), g.Shape)
    assert geometry.name() == "sphere"
    geometry.set_name("funky")
    assert geometry.name() == "funky"
    geometry.set_proximity_properties(g.ProximityProperties())
    geometry.set_illustration_properties(g.IllustrationProperties())
    geometry.set_perception_properties(g.PerceptionProperties())
    assert isinstance(geometry.mutable_proximity_properties(), g.ProximityProperties)
    assert isinstance(geometry.proximity_properties(), g.ProximityProperties)
    assert isinstance(geometry.mutable_illustration_properties(), g.IllustrationProperties)
    assert isinstance(geometry.illustration_properties(), g.IllustrationProperties)
    assert isinstance(geometry.mutable_perception_properties(), g.PerceptionProperties)
    assert isinstance(geometry.perception_properties(), g.PerceptionProperties)


def test_proximity_properties_api(drake: ModuleType) -> None:
    """Upstream ``test_geometry_properties_api`` without the Rgba/Phong illustration part."""
    AbstractValue = drake.common.value.AbstractValue
    prop = drake.geometry.ProximityProperties()
    assert str(prop) == "[__default__]"
    default_group = prop.default_group_name()
    assert prop.HasGroup(group_name=default_group)
    assert prop.num_groups() == 1
    assert default_group in prop.GetGroupNames()
    prop.AddProperty(group_name=default_group, name="test", value=3)
    assert prop.HasProperty(group_name=default_group, name="test")
    assert prop.GetProperty(group_name=default_group, name="test") == 3
    assert prop.GetPropertyOrDefault(group_name=default_group, name="empty", default_value=5) == 5
    group_values = prop.GetPropertiesInGroup(group_name=default_group)
    assert list(group_values) == ["test"]
    for name, value in group_values.items():
        assert isinstance(name, str)
        assert isinstance(value, AbstractValue)
    assert prop.RemoveProperty(group_name=default_group, name="test")
    assert not prop.HasProperty(group_name=default_group, name="test")

    prop.AddProperty(group_name=default_group, name="to_update", value=17)
    assert prop.HasProperty(group_name=default_group, name="to_update")
    assert prop.GetProperty(group_name=default_group, name="to_update") == 17
    prop.UpdateProperty(group_name=default_group, name="to_update", value=20)
    assert prop.HasProperty(group_name=default_group, name="to_update")
    assert prop.GetProperty(group_name=default_group, name="to_update") == 20


@pytest.mark.parametrize(
    "class_name", ["ProximityProperties", "IllustrationProperties", "PerceptionProperties"]
)
def test_property_copying(drake: ModuleType, class_name: str) -> None:
    property_cls = getattr(drake.geometry, class_name)
    props = property_cls()
    props.AddProperty("g", "p", 10)
    assert props.HasProperty("g", "p")
    assert property_cls(other=props).HasProperty("g", "p")
    assert copy.copy(props).HasProperty("g", "p")
    assert copy.deepcopy(props).HasProperty("g", "p")


@pytest.mark.parametrize(
    "class_name", ["ProximityProperties", "IllustrationProperties", "PerceptionProperties"]
)
@pytest.mark.parametrize("T", [str, bool, float])
def test_property_values_keep_their_python_type(
    drake: ModuleType, class_name: str, T: type
) -> None:
    """Upstream ``test_geometry_properties_cpp_types``, read back through Python.

    Upstream reads the value through the private ``_testing`` module in C++;
    here the round trip and the C++ type pydrake prints stand in for it.
    """
    props = getattr(drake.geometry, class_name)()
    value = T()
    props.AddProperty("g", "p", value)
    read = props.GetProperty("g", "p")
    assert isinstance(read, T)
    assert read == value
    cpp = {str: "std::string", bool: "bool", float: "double"}[T]
    assert str(props) == f"[g]\n  p: {cpp}\n[__default__]"


def test_identifier_api(drake: ModuleType) -> None:
    """Upstream ``test_identifier_api`` without ``_testing.get_constant_id``."""
    g = drake.geometry
    for cls in (g.FilterId, g.SourceId, g.FrameId, g.GeometryId):
        a = cls.get_new_id()
        assert a.is_valid()
        b = cls.get_new_id()
        assert a == a  # noqa: PLR0124 (upstream checks reflexive equality)
        assert not a == b  # noqa: SIM201 (upstream checks __eq__ itself)
        assert a < b or b > a
        assert f"value={a.get_value()}" in repr(a)
