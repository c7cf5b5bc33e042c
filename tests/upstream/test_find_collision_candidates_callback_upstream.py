# Ported from Drake: geometry/proximity/test/find_collision_candidates_callback_test.cc at
# v1.51.1 (https://github.com/RobotLocomotion/drake), re-expressed as pytest functions that
# run unchanged on pydrake and on reimpl through QueryObject.FindCollisionCandidates on a
# posed SceneGraph context (the internal FCL callback is not bound).
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
"""Upstream find_collision_candidates Callback tests, through FindCollisionCandidates.

Upstream hands the callback two FCL boxes (0.25 × 0.3 × 0.4 and 0.4 × 0.3 × 0.2, both at
the identity, so they overlap) in both orders; here the boxes are posed in a SceneGraph
and the argument order is varied by anchoring either box (``posed_scene.Layout``).
"""

from __future__ import annotations

from types import ModuleType

import pytest

from tests.upstream.posed_scene import Layout, PosedScene


def _two_boxes(drake: ModuleType, layout: Layout) -> PosedScene:
    g, identity = drake.geometry, drake.math.RigidTransform_[float]()
    scene = PosedScene(drake, layout)
    scene.add("box_A", g.Box(0.25, 0.3, 0.4), identity)
    scene.add("box_B", g.Box(0.4, 0.3, 0.2), identity)
    return scene


@pytest.mark.parametrize("layout", list(Layout), ids=lambda x: x.value)
def test_a_candidate_pair_is_the_sorted_pair_of_ids(drake: ModuleType, layout: Layout) -> None:
    """PairsProperlyFormed: one pair, (id_A, id_B) with id_A < id_B, whichever order the
    broadphase meets the boxes in."""
    scene = _two_boxes(drake, layout)
    (found,) = scene.query_object().FindCollisionCandidates()
    id_A, id_B = scene.ids["box_A"], scene.ids["box_B"]
    assert id_A < id_B
    assert (found[0], found[1]) == (id_A, id_B)


@pytest.mark.parametrize("layout", list(Layout), ids=lambda x: x.value)
def test_a_filtered_pair_is_no_candidate(drake: ModuleType, layout: Layout) -> None:
    """RespectsCollisionFilter: ExcludeWithin({A, B}) removes the overlapping pair."""
    scene = _two_boxes(drake, layout)
    scene.exclude_within("box_A", "box_B")
    assert list(scene.query_object().FindCollisionCandidates()) == []
