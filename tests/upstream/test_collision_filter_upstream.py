# Ported from Drake: geometry/proximity/test/collision_filter_test.cc
# (https://github.com/RobotLocomotion/drake, at v1.51.1), re-expressed through
# SceneGraph's public API as pytest functions that run unchanged on pydrake and on reimpl.
# Expected values are upstream's.
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
"""Upstream CollisionFilter tests, on pydrake and on reimpl.

Drake's test drives the internal ``CollisionFilter`` directly: it adds bare ids, applies
declarations with an explicit ``is_invariant`` flag, compares filters with ``==`` and
calls ``Flatten()``. pydrake binds none of that. The same facts are observed here
through a SceneGraph context: geometries are proximity spheres, ``CanCollideWith(a, b)``
is ``not CollisionFiltered(a, b)`` (asked both ways, as ``ExpectCanCollide`` does), and
an invariant filter is one SceneGraph itself declares: between geometries on one frame
(``same_frame``) or between anchored geometries (``anchored``); ``own_frames`` is the
non-invariant case. ``AddGeometry``/``RemoveGeometry`` become registering or removing
proximity geometry in the context.

Left out: ``Flatten()`` (Prop. E of TransientDeclarations; GeometryState never calls it,
so no public call reaches it) and the ``Equality`` test (``operator==`` of the internal
class; its public shadow, equal filtered pairs, is what every test here compares).
"""

from __future__ import annotations

from dataclasses import dataclass
from types import ModuleType
from typing import Any

import pytest

from tests.upstream.geometry_support import Scene, all_pairs, filtered_pairs, pair, sphere

#: pydrake's message for a persistent filter change under transient history.
PERSISTENT_WITH_HISTORY = (
    "You cannot attempt to modify the persistent collision filter configuration when "
    "there are active, transient filter declarations"
)

#: How three geometries A, B, C are placed, and whether SceneGraph filters them invariantly.
PLACEMENTS = {"own_frames": False, "same_frame": True, "anchored": True}


def place_three(scene: Scene, placement: str) -> list[Any]:
    if placement == "own_frames":
        return scene.spheres_on_own_frames(3)
    if placement == "same_frame":
        frame = scene.frame("body")
        return [scene.geometry(frame, name) for name in "ABC"]
    return [scene.anchored(name) for name in "ABC"]


@dataclass
class Filters:
    """One context's filter, read as ``can_collide``."""

    scene: Scene
    context: Any

    @property
    def manager(self) -> Any:
        return self.scene.scene_graph.collision_filter_manager(self.context)

    @property
    def inspector(self) -> Any:
        return self.scene.context_inspector(self.context)

    def can_collide(self, a: Any, b: Any) -> bool:
        """ExpectCanCollide's reading: the same answer in both orders."""
        forward = self.inspector.CollisionFiltered(geometry_id1=a, geometry_id2=b)
        backward = self.inspector.CollisionFiltered(geometry_id1=b, geometry_id2=a)
        assert forward == backward, "the collision filter state changed based on ordering"
        return not forward

    def apply(self, declaration: Any) -> None:
        self.manager.Apply(declaration)


def three(drake: ModuleType, placement: str) -> tuple[Filters, list[Any]]:
    scene = Scene(drake)
    ids = place_three(scene, placement)
    return Filters(scene, scene.context()), ids


def filter_all_pairs(drake: ModuleType, filters: Filters, ids: list[Any]) -> None:
    """FilterAllPairs: ExcludeWithin(ids), then every pair reports filtered."""
    g = drake.geometry
    filters.apply(g.CollisionFilterDeclaration().ExcludeWithin(g.GeometrySet(geometry_ids=ids)))
    for a in ids:
        for b in ids:
            assert not filters.can_collide(a, b)


@pytest.mark.parametrize("placement", list(PLACEMENTS))
def test_allow_between_cannot_lift_invariant_filters(drake: ModuleType, placement: str) -> None:
    """AllowBetween: (A, B) and (A, C) collide again unless the filters were invariant."""
    g = drake.geometry
    is_invariant = PLACEMENTS[placement]
    filters, (id_A, id_B, id_C) = three(drake, placement)
    filter_all_pairs(drake, filters, [id_A, id_B, id_C])
    filters.apply(
        g.CollisionFilterDeclaration().AllowBetween(
            g.GeometrySet(geometry_id=id_A), g.GeometrySet(geometry_ids=[id_B, id_C])
        )
    )
    assert filters.can_collide(id_A, id_B) == (not is_invariant)
    assert filters.can_collide(id_A, id_C) == (not is_invariant)
    assert not filters.can_collide(id_B, id_C)


@pytest.mark.parametrize("placement", list(PLACEMENTS))
def test_allow_within_cannot_lift_invariant_filters(drake: ModuleType, placement: str) -> None:
    """AllowWithin: two chained statements; as AllowBetween."""
    g = drake.geometry
    is_invariant = PLACEMENTS[placement]
    filters, (id_A, id_B, id_C) = three(drake, placement)
    filter_all_pairs(drake, filters, [id_A, id_B, id_C])
    filters.apply(
        g.CollisionFilterDeclaration()
        .AllowWithin(g.GeometrySet(geometry_ids=[id_A, id_B]))
        .AllowWithin(g.GeometrySet(geometry_ids=[id_A, id_C]))
    )
    assert filters.can_collide(id_A, id_B) == (not is_invariant)
    assert filters.can_collide(id_A, id_C) == (not is_invariant)
    assert not filters.can_collide(id_B, id_C)


def test_exclude_between_filters_exactly_the_cross_pairs(drake: ModuleType) -> None:
    """ExcludeBetween: A against {B, C}."""
    g = drake.geometry
    filters, (id_A, id_B, id_C) = three(drake, "own_frames")
    assert filters.can_collide(id_A, id_B)
    assert filters.can_collide(id_A, id_C)
    assert filters.can_collide(id_B, id_C)
    filters.apply(
        g.CollisionFilterDeclaration().ExcludeBetween(
            g.GeometrySet(geometry_id=id_A), g.GeometrySet(geometry_ids=[id_B, id_C])
        )
    )
    assert not filters.can_collide(id_A, id_B)
    assert not filters.can_collide(id_A, id_C)
    assert filters.can_collide(id_B, id_C)


def test_exclude_within_filters_exactly_the_pairs_inside(drake: ModuleType) -> None:
    """ExcludeWithin: {A, B, D} then {A, C}; (B, C) and (C, D) still collide."""
    g = drake.geometry
    scene = Scene(drake)
    id_A, id_B, id_C, id_D = scene.spheres_on_own_frames(4)
    filters = Filters(scene, scene.context())
    ids = [id_A, id_B, id_C, id_D]
    assert filtered_pairs(filters.inspector, ids) == set()
    filters.apply(
        g.CollisionFilterDeclaration()
        .ExcludeWithin(g.GeometrySet(geometry_ids=[id_A, id_B, id_D]))
        .ExcludeWithin(g.GeometrySet(geometry_ids=[id_A, id_C]))
    )
    assert filtered_pairs(filters.inspector, ids) == all_pairs(ids) - {
        pair(id_B, id_C),
        pair(id_C, id_D),
    }


def test_a_geometry_never_collides_with_itself(drake: ModuleType) -> None:
    """NoSelfCollision: CollisionFiltered(a, a) is True; no candidate pairs a with itself."""
    filters, ids = three(drake, "own_frames")
    for the_id in ids:
        assert not filters.can_collide(the_id, the_id)
    assert all(a != b for a, b in filters.inspector.GetCollisionCandidates())


def test_transient_declarations(drake: ModuleType) -> None:
    """TransientDeclarations, Props. A-D and F-H (E, Flatten, is unreachable; see above).

    Geometries A, B, C each on a frame of their own, D and E on one frame (so P(D, E) is
    SceneGraph's invariant filter). Prop. H becomes "the filtered pairs are the
    expected ones", whatever the history.
    """
    g = drake.geometry
    Decl = g.CollisionFilterDeclaration
    GeometrySet = g.GeometrySet
    scene = Scene(drake)
    A, B, C = scene.spheres_on_own_frames(3)
    body = scene.frame("body_DE")
    D, E = scene.geometry(body, "D"), scene.geometry(body, "E")
    frame_F = scene.frame("frame_F")  # F is registered later, in the context (Prop. F)
    context = scene.context()
    filters = Filters(scene, context)
    manager = filters.manager
    ids = [A, B, C, D, E]

    def state() -> set[frozenset[Any]]:
        return filtered_pairs(filters.inspector, ids)

    def new_filter_id() -> Any:
        """An id that was never issued by this manager (issued by another context's)."""
        other = scene.context()
        other_manager = scene.scene_graph.collision_filter_manager(other)
        return other_manager.ApplyTransient(Decl())

    # Props. C.1, B.1: no history.
    assert not manager.IsActive(new_filter_id())
    assert not manager.has_transient_history()

    # Persistent base: P(D, E), (B, C), (B, D), (B, E).
    manager.Apply(Decl().ExcludeBetween(GeometrySet(B), GeometrySet([C, D, E])))
    expected = {pair(D, E), pair(B, C), pair(B, D), pair(B, E)}
    assert state() == expected

    # Prop. H: a redundant transient declaration.
    id0 = manager.ApplyTransient(Decl().ExcludeBetween(GeometrySet(B), GeometrySet([C, D, E])))
    assert state() == expected
    assert manager.has_transient_history()  # B.2
    assert manager.IsActive(id0)  # C.2
    assert not manager.IsActive(new_filter_id())  # C.3

    # Props. A.2, A.3: add (C, D), remove (B, D).
    id1 = manager.ApplyTransient(
        Decl().ExcludeWithin(GeometrySet([C, D])).AllowWithin(GeometrySet([B, D]))
    )
    assert manager.IsActive(id1)
    assert manager.IsActive(id0)
    expected = (expected | {pair(C, D)}) - {pair(B, D)}
    assert state() == expected

    as_of_id1 = state()

    def add_2_clear_2() -> Any:
        return (
            Decl()
            .ExcludeBetween(GeometrySet(A), GeometrySet([B, C]))
            .AllowBetween(GeometrySet(B), GeometrySet([C, E]))
        )

    id2 = manager.ApplyTransient(add_2_clear_2())
    assert manager.IsActive(id2)
    expected = (expected | {pair(A, B), pair(A, C)}) - {pair(B, C), pair(B, E)}
    assert state() == expected

    # Prop. D.1: removing an id this manager never issued does nothing.
    assert not manager.RemoveDeclaration(new_filter_id())
    assert state() == expected

    # Prop. D.2: removing the last declaration returns to the previous state.
    assert manager.RemoveDeclaration(id2)
    assert state() == as_of_id1

    id3 = manager.ApplyTransient(add_2_clear_2())
    assert manager.IsActive(id3)
    assert state() == expected

    # Partially redundant with id3: keeps (A, B) filtered and (B, E) allowed.
    id4 = manager.ApplyTransient(
        Decl().ExcludeWithin(GeometrySet([A, B])).AllowWithin(GeometrySet([B, E]))
    )
    assert manager.IsActive(id4)
    assert state() == expected

    # Prop. D.3: removing id3 is only half undone; id4 keeps one filter and one removal.
    assert manager.RemoveDeclaration(id3)
    expected = (expected - {pair(A, C)}) | {pair(B, C)}
    assert state() == expected

    # Prop. A.1: a transient Allow cannot remove the invariant filter.
    id5 = manager.ApplyTransient(Decl().AllowWithin(GeometrySet([D, E])))
    assert manager.IsActive(id5)
    assert state() == expected

    # Prop. F: a geometry added under history leaves the filters alone. The public way to
    # add a geometry to the filter is to give it the proximity role, and SceneGraph then
    # declares its same-frame invariant persistently, which throws under transient
    # history even on a frame with no other proximity geometry (known divergence
    # "half-registration-during-history" of Drake from the internal class's
    # contract; measured on pydrake 1.51.1 and 1.58.0). The geometry has joined the
    # filter all the same, and the filters are untouched.
    F = scene.scene_graph.RegisterGeometry(
        context=context, source_id=scene.source, frame_id=frame_F, geometry=sphere(drake, "F")
    )
    with pytest.raises(RuntimeError, match="^" + PERSISTENT_WITH_HISTORY + "$"):
        scene.proximity(F, context=context)
    assert state() == expected
    assert filtered_pairs(filters.inspector, [*ids, F]) == expected

    # Prop. G: removing A removes its filters.
    scene.scene_graph.RemoveGeometry(context=context, source_id=scene.source, geometry_id=A)
    ids.remove(A)
    expected = expected - {pair(A, B)}
    assert filtered_pairs(filters.inspector, ids) == expected

    assert manager.has_transient_history()
    for filter_id in (id0, id1, id4, id5):
        assert manager.IsActive(filter_id)


# The tests below are upstream's at Drake v1.56.0+ (this file's C++ source gained them
# with the activation feature; ApplyWithUnknownGeometryIdThrows holds on 1.51.1 too).


def test_apply_with_an_unknown_geometry_id_throws(drake: ModuleType) -> None:
    """ApplyWithUnknownGeometryIdThrows: Apply and ApplyTransient reject an id that
    was never registered, in set A or set B. Upstream's regex ".*not been registered.*"
    is the internal CollisionFilter's message; through SceneGraph the GeometrySet is
    resolved first, and pydrake (1.51.1 and 1.58.0) says what is asserted here. The
    rejected transient declaration leaves no history."""
    g = drake.geometry
    filters, (id_A, _, _) = three(drake, "own_frames")
    unknown_id = g.GeometryId.get_new_id()
    message = (
        "^Geometry set includes a geometry id that doesn't belong to the SceneGraph: "
        f"{unknown_id.get_value()}$"
    )
    with pytest.raises(RuntimeError, match=message):
        filters.manager.Apply(
            g.CollisionFilterDeclaration().ExcludeBetween(
                g.GeometrySet(unknown_id), g.GeometrySet(id_A)
            )
        )
    with pytest.raises(RuntimeError, match=message):
        filters.manager.ApplyTransient(
            g.CollisionFilterDeclaration().ExcludeBetween(
                g.GeometrySet(id_A), g.GeometrySet(unknown_id)
            )
        )
    assert not filters.manager.has_transient_history()


def _needs_activation(drake: ModuleType) -> None:
    if not hasattr(drake.geometry.CollisionFilterManager, "Deactivate"):
        pytest.skip("CollisionFilterManager.Deactivate is bound since 1.55 (activation-since-1.55)")


def test_activation(drake: ModuleType) -> None:
    """Activation, its properties (1)-(5); (6), MakeClearCopy, is internal.

    (1) an inactive geometry collides with nothing; (2) nor with geometry added
    later; (3) Allow* does not reactivate it; (4) filters declared while inactive take
    effect on reactivation; (5) (de)activating an (in)active geometry is a no-op.
    Geometry D of (2) is registered and given the proximity role in the context."""
    _needs_activation(drake)
    g = drake.geometry
    Decl = g.CollisionFilterDeclaration
    GeometrySet = g.GeometrySet
    scene = Scene(drake)
    id_A, id_B, id_C = scene.spheres_on_own_frames(3)
    frame_D = scene.frame("frame_D")
    filters = Filters(scene, scene.context())
    manager = filters.manager

    assert filters.can_collide(id_A, id_B)
    assert filters.can_collide(id_A, id_C)
    assert filters.can_collide(id_B, id_C)

    for _ in range(2):  # (1), then (5): deactivating an inactive geometry
        manager.Deactivate(GeometrySet(id_A))
        assert not filters.can_collide(id_A, id_B)
        assert not filters.can_collide(id_A, id_C)
        assert filters.can_collide(id_B, id_C)

    # (2)
    id_D = scene.scene_graph.RegisterGeometry(
        context=filters.context,
        source_id=scene.source,
        frame_id=frame_D,
        geometry=sphere(drake, "D"),
    )
    scene.proximity(id_D, context=filters.context)
    assert not filters.can_collide(id_A, id_D)
    assert filters.can_collide(id_B, id_D)

    # (3)
    manager.Apply(Decl().AllowBetween(GeometrySet(id_A), GeometrySet([id_B, id_C, id_D])))
    assert not filters.can_collide(id_A, id_B)
    assert not filters.can_collide(id_A, id_D)

    # (4)
    manager.Apply(Decl().ExcludeWithin(GeometrySet([id_A, id_B])))
    manager.Activate(GeometrySet(id_A))
    assert not filters.can_collide(id_A, id_B)
    assert filters.can_collide(id_A, id_C)
    assert filters.can_collide(id_A, id_D)

    # (5)
    manager.Activate(GeometrySet([id_A, id_C]))
    assert filters.can_collide(id_A, id_C)


def test_active_status_change_end_state(drake: ModuleType) -> None:
    """ActiveStatusChange: the change reports are internal (a callback); the end state
    is public: (*, B) blocked because B is inactive, (A, C) collidable."""
    _needs_activation(drake)
    g = drake.geometry
    GeometrySet = g.GeometrySet
    filters, (id_A, id_B, id_C) = three(drake, "own_frames")
    manager = filters.manager
    manager.Apply(g.CollisionFilterDeclaration().ExcludeWithin(GeometrySet([id_A, id_B])))
    manager.Deactivate(GeometrySet([id_A, id_B]))
    manager.Deactivate(GeometrySet(id_A))
    manager.Activate(GeometrySet([id_A, id_C]))
    assert not filters.can_collide(id_A, id_B)
    assert filters.can_collide(id_A, id_C)
    assert not filters.can_collide(id_B, id_C)


def test_manager_activation_resolves_frames(drake: ModuleType) -> None:
    """collision_filter_manager_test.cc Activation (Drake >= 1.55): the manager passes
    its id extraction on, so a set naming a frame (de)activates that frame's geometry.
    Also its Apply, whose set names g_id2 by its frame."""
    _needs_activation(drake)
    g = drake.geometry
    GeometrySet = g.GeometrySet
    filters, (id_1, id_2, id_3) = three(drake, "own_frames")
    frame_2 = filters.inspector.GetFrameId(geometry_id=id_2)
    filters.manager.Apply(
        g.CollisionFilterDeclaration().ExcludeWithin(GeometrySet([id_1], [frame_2]))
    )
    assert not filters.can_collide(id_1, id_2)
    assert filters.can_collide(id_1, id_3)
    filters.manager.Deactivate(GeometrySet(frame_2))
    assert not filters.can_collide(id_2, id_3)
    assert filters.can_collide(id_1, id_3)
    filters.manager.Activate(GeometrySet(frame_2))
    assert filters.can_collide(id_2, id_3)
    assert not filters.can_collide(id_1, id_2)
