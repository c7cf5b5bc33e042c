# Ported from Drake: geometry/test/scene_graph_inspector_test.cc
# (https://github.com/RobotLocomotion/drake, at v1.51.1), the collision filter calls,
# re-expressed as pytest functions that run unchanged on pydrake and on reimpl.
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
"""Upstream SceneGraphInspector tests, the filter calls of ExerciseEverything.

Upstream only exercises each call (no assertions) on a tester-owned GeometryState; the
filter-related calls are given the values they return there, measured on pydrake
1.51.1 and 1.58.0: no candidates and an empty resolution before anything is
registered, and two proximity spheres on one frame are filtered. CloneGeometryInstance
and AllFrameIds have no filter in them and are not ported here.
"""

from __future__ import annotations

from types import ModuleType

from tests.upstream.geometry_support import sphere


def test_exercise_the_filter_calls(drake: ModuleType) -> None:
    g = drake.geometry
    scene_graph = g.SceneGraph_[float]()
    inspector = scene_graph.model_inspector()

    assert inspector.GetGeometryIds(geometry_set=g.GeometrySet()) == set()
    assert inspector.GetCollisionCandidates() == set()

    source_id = scene_graph.RegisterSource("name")
    frame_id = scene_graph.RegisterFrame(source_id=source_id, frame=g.GeometryFrame("frame"))
    ids = [
        scene_graph.RegisterGeometry(
            source_id=source_id, frame_id=frame_id, geometry=sphere(drake, name)
        )
        for name in ("sphere", "sphere2")
    ]
    assert inspector.GetGeometryIds(geometry_set=g.GeometrySet(frame_id=frame_id)) == set(ids)
    for geometry_id in ids:
        scene_graph.AssignRole(
            source_id=source_id, geometry_id=geometry_id, properties=g.ProximityProperties()
        )
    assert inspector.CollisionFiltered(geometry_id1=ids[0], geometry_id2=ids[1])
    assert inspector.GetCollisionCandidates() == set()
