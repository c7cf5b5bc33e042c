# Ported from Drake: geometry/test/collision_filter_manager_test.cc
# (https://github.com/RobotLocomotion/drake, at v1.51.1), re-expressed as pytest
# functions that run unchanged on pydrake and on reimpl. Expected values are upstream's.
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
"""Upstream CollisionFilterManager tests, on pydrake and on reimpl.

``PopulateSceneGraph``: three proximity spheres, each on a dynamic frame of its own, no
filters. C++'s copy and move construction/assignment of a manager become Python name
binding (a manager cannot be copied in Python: ``copy.copy`` raises TypeError, measured
on pydrake 1.51.1 and 1.58.0); what upstream checks, that a manager held elsewhere keeps
its live access to the model or to the context it came from, is checked the same way.
"""

from __future__ import annotations

import copy
import pickle
from types import ModuleType
from typing import Any

import pytest

from tests.upstream.geometry_support import Scene


def populate_scene_graph(drake: ModuleType) -> tuple[Scene, list[Any]]:
    """Three proximity spheres on frames frame_0..frame_2; the model filters no pair."""
    scene = Scene(drake)
    ids = scene.spheres_on_own_frames(3)
    inspector = scene.model_inspector
    g1, g2, g3 = ids
    for a, b in ((g1, g2), (g1, g3), (g2, g3)):
        if inspector.CollisionFiltered(geometry_id1=a, geometry_id2=b):
            raise RuntimeError("Initial conditions erroneously has filtered pairs")
    return scene, ids


def test_apply_and_apply_transient_edit_the_context_not_the_model(drake: ModuleType) -> None:
    """Apply: one persistent and one transient declaration, then its removal."""
    g = drake.geometry
    scene, (g_id1, g_id2, g_id3) = populate_scene_graph(drake)
    context = scene.context()
    inspector = scene.context_inspector(context)

    def filtered(a: Any, b: Any) -> bool:
        return bool(inspector.CollisionFiltered(geometry_id1=a, geometry_id2=b))

    # The unfiltered state was copied into the context.
    assert not filtered(g_id1, g_id2)
    assert not filtered(g_id1, g_id3)
    assert not filtered(g_id2, g_id3)

    filter_manager = scene.scene_graph.collision_filter_manager(context)
    filter_manager.Apply(
        g.CollisionFilterDeclaration().ExcludeWithin(g.GeometrySet(geometry_ids=[g_id1, g_id2]))
    )
    assert filtered(g_id1, g_id2)
    assert not filtered(g_id1, g_id3)
    assert not filtered(g_id2, g_id3)

    assert not filter_manager.has_transient_history()

    filter_id = filter_manager.ApplyTransient(
        g.CollisionFilterDeclaration().ExcludeBetween(
            g.GeometrySet(geometry_ids=[g_id1, g_id2]), g.GeometrySet(geometry_ids=[g_id3])
        )
    )
    assert filtered(g_id1, g_id2)
    assert filtered(g_id1, g_id3)
    assert filtered(g_id2, g_id3)

    assert filter_manager.has_transient_history()
    assert filter_manager.IsActive(filter_id)
    assert filter_manager.RemoveDeclaration(filter_id)
    assert filtered(g_id1, g_id2)
    assert not filtered(g_id1, g_id3)
    assert not filtered(g_id2, g_id3)

    # The underlying model did not change.
    model_inspector = scene.model_inspector
    for a, b in ((g_id1, g_id2), (g_id1, g_id3), (g_id2, g_id3)):
        assert not model_inspector.CollisionFiltered(geometry_id1=a, geometry_id2=b)


@pytest.mark.parametrize("how", ["CopySemantics", "MoveSemantics"])
def test_a_manager_held_elsewhere_keeps_live_access(drake: ModuleType, how: str) -> None:
    """CopySemantics / MoveSemantics: a manager bound to another name (C++: copied or
    moved) edits what its source edits, the model's data or the context's."""
    g = drake.geometry
    scene, (g_id1, g_id2, g_id3) = populate_scene_graph(drake)
    context = scene.context()
    model_inspector = scene.model_inspector
    context_inspector = scene.context_inspector(context)

    model_filter = scene.scene_graph.collision_filter_manager()
    copy_filter = model_filter
    if how == "MoveSemantics":
        del model_filter
    copy_filter.Apply(
        g.CollisionFilterDeclaration().ExcludeWithin(g.GeometrySet(geometry_ids=[g_id1, g_id2]))
    )
    assert model_inspector.CollisionFiltered(geometry_id1=g_id1, geometry_id2=g_id2)
    assert not context_inspector.CollisionFiltered(geometry_id1=g_id1, geometry_id2=g_id2)

    context_filter = scene.scene_graph.collision_filter_manager(context=context)
    copy_filter = context_filter
    if how == "MoveSemantics":
        del context_filter
    copy_filter.Apply(
        g.CollisionFilterDeclaration().ExcludeWithin(g.GeometrySet(geometry_ids=[g_id1, g_id3]))
    )
    assert not model_inspector.CollisionFiltered(geometry_id1=g_id1, geometry_id2=g_id3)
    assert context_inspector.CollisionFiltered(geometry_id1=g_id1, geometry_id2=g_id3)


def test_a_manager_cannot_be_copied(drake: ModuleType) -> None:
    """Not upstream: pydrake binds no copy of a manager (measured on 1.51.1 and 1.58.0)."""
    manager = drake.geometry.SceneGraph_[float]().collision_filter_manager()
    message = f"cannot pickle '{drake.__name__}.geometry.CollisionFilterManager' object"
    for duplicate in (copy.copy, copy.deepcopy, pickle.dumps):
        with pytest.raises(TypeError, match=f"^{message}$"):
            duplicate(manager)
