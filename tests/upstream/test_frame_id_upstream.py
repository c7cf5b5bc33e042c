# Ported from Drake: bindings/pydrake/geometry/test/frame_id_test.py
# (https://github.com/RobotLocomotion/drake), re-expressed as a pytest function that runs
# unchanged on pydrake and on reimpl.
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
"""Upstream FrameId uniqueness test, on pydrake and on reimpl."""

from __future__ import annotations

from types import ModuleType


def test_id_uniqueness(drake: ModuleType) -> None:
    """World, new and GeometryFrame FrameIds are all distinct."""
    g = drake.geometry
    scene_graph = g.SceneGraph()
    f = g.FrameId.get_new_id().get_value()
    frame = g.GeometryFrame("geometry").id().get_value()
    world = scene_graph.world_frame_id().get_value()
    assert f != frame
    assert world != f
    assert world != frame
