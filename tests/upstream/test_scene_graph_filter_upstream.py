# Ported from Drake: geometry/test/scene_graph_test.cc
# (https://github.com/RobotLocomotion/drake, at v1.51.1), the parts about collision filters,
# roles and context edits, re-expressed as pytest functions that run unchanged on pydrake
# and on reimpl. Expected values are upstream's.
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
"""Upstream SceneGraph C++ tests, the parts about filters, roles and context edits.

``bindings/pydrake/geometry/test/scene_graph_test.py`` is ported in
test_scene_graph_upstream.py; this file ports the C++ ``geometry/test/scene_graph_test.cc``
where it touches collision filtering: the manager's context check, role management and
registering geometry in a context. Upstream's test-only ``GeometrySourceSystem`` is
replaced by a MultibodyPlant (another system in the same diagram); the renderer, config,
deformable, AutoDiff and Expression tests are left out.
"""

from __future__ import annotations

import re
from types import ModuleType

import pytest

from tests.upstream.geometry_support import sphere

MISMATCH_HELP = (
    "\nFor more information about Context-System mismatches, see "
    "https://drake.mit.edu/troubleshooting.html#framework-context-system-mismatch"
)


def test_collision_filter_manager_rejects_a_context_of_another_system(drake: ModuleType) -> None:
    """SceneGraphConnectionTest.FullPositionUpdateConnected, its last part: the manager
    validates the context (upstream's regex ".*\\n.*context-system-mismatch.*"; pydrake's
    full message, measured on 1.51.1 and 1.58.0)."""
    builder = drake.systems.framework.DiagramBuilder_[float]()
    plant, scene_graph = drake.multibody.plant.AddMultibodyPlantSceneGraph(builder, 0.0)
    plant.Finalize()
    diagram = builder.Build()
    diagram_context = diagram.CreateDefaultContext()
    plant_context = diagram.GetMutableSubsystemContext(plant, diagram_context)
    prefix = (
        "A function call on a drake::geometry::SceneGraph<double> system named "
        "'::_::scene_graph' was passed "
    )
    root = (
        "the root Diagram's Context instead of the appropriate subsystem Context. Use "
        "GetMyContextFromRoot() or similar to acquire the appropriate subsystem Context."
    )
    other = (
        "the Context of a system named '::_::plant' instead of the appropriate subsystem Context."
    )
    for context, middle in ((diagram_context, root), (plant_context, other)):
        with pytest.raises(
            RuntimeError, match="^" + re.escape(prefix + middle + MISMATCH_HELP) + "$"
        ):
            scene_graph.collision_filter_manager(context)
    sg_context = diagram.GetMutableSubsystemContext(scene_graph, diagram_context)
    assert not scene_graph.collision_filter_manager(sg_context).has_transient_history()


def test_role_management_smoke_test(drake: ModuleType) -> None:
    """RoleManagementSmokeTest: roles given on the instance; RemoveRole removes each."""
    g = drake.geometry
    scene_graph = g.SceneGraph_[float]()
    s_id = scene_graph.RegisterSource("test")
    f_id = scene_graph.RegisterFrame(source_id=s_id, frame=g.GeometryFrame("frame"))
    instance = sphere(drake, "sphere")
    instance.set_illustration_properties(g.IllustrationProperties())
    instance.set_proximity_properties(g.ProximityProperties())
    instance.set_perception_properties(g.PerceptionProperties())
    g_id = scene_graph.RegisterGeometry(source_id=s_id, frame_id=f_id, geometry=instance)

    inspector = scene_graph.model_inspector()
    assert inspector.GetProximityProperties(geometry_id=g_id) is not None
    assert inspector.GetIllustrationProperties(geometry_id=g_id) is not None
    assert inspector.GetPerceptionProperties(geometry_id=g_id) is not None
    for role in (g.Role.kPerception, g.Role.kProximity, g.Role.kIllustration):
        assert scene_graph.RemoveRole(source_id=s_id, geometry_id=g_id, role=role) == 1


def test_register_and_remove_geometry_in_a_context(drake: ModuleType) -> None:
    """SceneGraphContextModifier.RegisterGeometry: the context's inspector is live."""
    g = drake.geometry
    scene_graph = g.SceneGraph_[float]()
    source_id = scene_graph.RegisterSource("source")
    frame_id = scene_graph.RegisterFrame(source_id=source_id, frame=g.GeometryFrame("frame"))
    context = scene_graph.CreateDefaultContext()
    inspector = scene_graph.get_query_output_port().Eval(context).inspector()
    assert inspector.NumFramesForSource(source_id=source_id) == 1
    assert inspector.NumGeometriesForFrame(frame_id=frame_id) == 0

    sphere_id_1 = scene_graph.RegisterGeometry(
        context=context, source_id=source_id, frame_id=frame_id, geometry=sphere(drake, "sphere")
    )
    assert inspector.NumGeometriesForFrame(frame_id=frame_id) == 1
    assert inspector.GetFrameId(geometry_id=sphere_id_1) == frame_id

    scene_graph.RemoveGeometry(context=context, source_id=source_id, geometry_id=sphere_id_1)
    assert inspector.NumGeometriesForFrame(frame_id=frame_id) == 0
    with pytest.raises(RuntimeError, match=r"^Referenced geometry \d+ has not been registered.$"):
        inspector.GetFrameId(geometry_id=sphere_id_1)
    # The model never saw the geometry.
    assert scene_graph.model_inspector().NumGeometriesForFrame(frame_id=frame_id) == 0
