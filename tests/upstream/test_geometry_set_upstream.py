# Ported from Drake: geometry/test/geometry_set_test.cc
# (https://github.com/RobotLocomotion/drake, at v1.51.1), re-expressed through the public API
# (a set observed by the geometries it resolves to) as pytest functions that run unchanged
# on pydrake and on reimpl. Expected values are upstream's.
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
"""Upstream GeometrySet tests, on pydrake and on reimpl.

Drake's test counts a set's frames and geometries through a friend class
(``GeometrySetTester``); pydrake binds no view of a set. Here a set is observed by what
it resolves to: in a scene whose pool geometries and pool frames each carry one
proximity sphere on a frame of their own, ``ExcludeBetween(set, {probe})`` filters
(g, probe) exactly for the geometries g the set names, directly or through their frame.
So "the set contains geometry g" is "(g, probe) is filtered", "the set contains frame f"
is "(the sphere on f, probe) is filtered", and the counts are the numbers of those.

Upstream draws fresh ids with ``get_new_id()``; an id SceneGraph never registered makes
the declaration throw, so the ids here are registered ones.

pydrake binds ``list[GeometryId]`` and ``list[FrameId]`` where C++ takes any iterable:
a ``list`` and a ``tuple`` are accepted, a Python ``set`` is a TypeError (measured on
pydrake 1.51.1 and 1.58.0). C++'s ``std::set`` and ``std::unordered_set`` sources become
lists here, its initializer lists tuples.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import ModuleType
from typing import Any

import pytest

from tests.upstream.geometry_support import Scene

POOL = 10


@dataclass
class Pools:
    """``geometries``: POOL spheres, each on a frame of its own; ``frames``: POOL other
    frames with a sphere each (``sphere_on``); ``probe``: one more sphere on its own frame."""

    scene: Scene
    geometries: list[Any]
    frames: list[Any]
    sphere_on: dict[Any, Any]
    probe: Any

    def resolved(self, geometry_set: Any) -> tuple[set[Any], set[Any]]:
        """The pool geometries and pool frames ``geometry_set`` contains."""
        g = self.scene.g
        context = self.scene.context()
        manager = self.scene.scene_graph.collision_filter_manager(context)
        manager.Apply(
            g.CollisionFilterDeclaration().ExcludeBetween(
                set_A=geometry_set, set_B=g.GeometrySet(geometry_id=self.probe)
            )
        )
        inspector = self.scene.context_inspector(context)

        def hit(geometry_id: Any) -> bool:
            return bool(
                inspector.CollisionFiltered(geometry_id1=geometry_id, geometry_id2=self.probe)
            )

        return (
            {x for x in self.geometries if hit(x)},
            {f for f in self.frames if hit(self.sphere_on[f])},
        )

    def num_geometries(self, geometry_set: Any) -> int:
        return len(self.resolved(geometry_set)[0])

    def num_frames(self, geometry_set: Any) -> int:
        return len(self.resolved(geometry_set)[1])

    def contains(self, geometry_set: Any, the_id: Any) -> bool:
        geometries, frames = self.resolved(geometry_set)
        return the_id in geometries or the_id in frames

    def expect(
        self,
        geometry_set: Any,
        frames: list[Any] | tuple[Any, ...],
        geometries: list[Any] | tuple[Any, ...],
    ) -> None:
        """The set contains exactly these pool frames and pool geometries."""
        assert self.resolved(geometry_set) == (set(geometries), set(frames))


@pytest.fixture
def pools(drake: ModuleType) -> Pools:
    scene = Scene(drake)
    geometries = scene.spheres_on_own_frames(POOL, prefix="pool_geometry")
    frames = [scene.frame(f"pool_frame_{i}") for i in range(POOL)]
    sphere_on = {f: scene.geometry(f, f"on_pool_frame_{i}") for i, f in enumerate(frames)}
    probe = scene.geometry(scene.frame("probe_frame"), "probe")
    return Pools(scene, geometries, frames, sphere_on, probe)


def test_a_default_set_is_empty(drake: ModuleType, pools: Pools) -> None:
    """DefaultConstructor: no frames, no geometries; nothing is reported as in it."""
    geometry_set = drake.geometry.GeometrySet()
    assert pools.num_frames(geometry_set) == 0
    assert pools.num_geometries(geometry_set) == 0
    assert not pools.contains(geometry_set, pools.geometries[0])
    assert not pools.contains(geometry_set, pools.frames[0])


def test_each_constructor_holds_exactly_its_ids(drake: ModuleType, pools: Pools) -> None:
    """ConversionConstructor: sets 1..12 of upstream, one per constructor spelling."""
    GeometrySet = drake.geometry.GeometrySet
    gs, fs = pools.geometries, pools.frames
    g_id, f_id = gs[0], fs[0]
    geometry_list = (gs[1], gs[2])  # C++ initializer list
    geometry_vector = list(geometry_list)
    geometry_set = [gs[3], gs[4], gs[5]]  # C++ std::set
    geometry_hash = [gs[6], gs[7], gs[8], gs[9]]  # C++ std::unordered_set
    frame_list = (fs[1], fs[2])
    frame_vector = list(frame_list)

    pools.expect(GeometrySet(geometry_id=g_id), [], [g_id])  # set1
    pools.expect(GeometrySet(frame_id=f_id), [f_id], [])  # set2
    pools.expect(GeometrySet(geometry_ids=geometry_vector), [], geometry_vector)  # set3
    pools.expect(GeometrySet(geometry_ids=geometry_set), [], geometry_set)  # set4
    pools.expect(GeometrySet(geometry_ids=geometry_hash), [], geometry_hash)  # set5
    pools.expect(GeometrySet(geometry_list), [], geometry_list)  # set6
    pools.expect(GeometrySet((geometry_vector[0], geometry_vector[1])), [], geometry_vector)
    pools.expect(GeometrySet(frame_list), frame_vector, [])  # set8
    pools.expect(GeometrySet((frame_vector[0], frame_vector[1])), frame_vector, [])  # set9
    pools.expect(GeometrySet(geometry_list, frame_vector), frame_vector, geometry_vector)
    pools.expect(
        GeometrySet(geometry_ids=geometry_vector, frame_ids=(frame_vector[0], frame_vector[1])),
        frame_vector,
        geometry_vector,
    )  # set11
    pools.expect(GeometrySet(geometry_list, frame_list), frame_vector, geometry_vector)  # set12


def test_a_python_set_of_ids_is_not_accepted(drake: ModuleType, pools: Pools) -> None:
    """Not upstream: pydrake's list caster takes a list or a tuple, not a ``set``
    (TypeError, measured on pydrake 1.51.1 and 1.58.0)."""
    GeometrySet = drake.geometry.GeometrySet
    with pytest.raises(TypeError, match=r"^__init__\(\): incompatible"):
        GeometrySet(set(pools.geometries[:2]))
    with pytest.raises(TypeError, match=r"^Add\(\): incompatible function arguments"):
        GeometrySet().Add(set(pools.frames[:2]))


@pytest.mark.parametrize("kind", ["frame", "geometry"])
def test_adding_one_id_twice_keeps_one_member(drake: ModuleType, pools: Pools, kind: str) -> None:
    """SingleFrameAdd / SingleGeometryAdd: a redundant Add neither throws nor changes
    the membership."""
    geometry_set = drake.geometry.GeometrySet()
    the_id = pools.frames[0] if kind == "frame" else pools.geometries[0]
    count = pools.num_frames if kind == "frame" else pools.num_geometries
    keyword = "frame_id" if kind == "frame" else "geometry_id"
    assert not pools.contains(geometry_set, the_id)
    geometry_set.Add(**{keyword: the_id})
    assert count(geometry_set) == 1
    assert pools.contains(geometry_set, the_id)
    geometry_set.Add(**{keyword: the_id})
    assert count(geometry_set) == 1
    assert pools.contains(geometry_set, the_id)


@pytest.mark.parametrize("kind", ["frame", "geometry"])
def test_adding_iterables_accumulates(drake: ModuleType, pools: Pools, kind: str) -> None:
    """IterableFrameAdd / IterableGeometryAdd: containers of 2, 3 and 4 ids add up."""
    GeometrySet = drake.geometry.GeometrySet
    pool = pools.frames if kind == "frame" else pools.geometries
    keyword = "frame_ids" if kind == "frame" else "geometry_ids"

    def members(geometry_set: Any) -> set[Any]:
        geometries, frames = pools.resolved(geometry_set)
        assert not (geometries if kind == "frame" else frames)
        return frames if kind == "frame" else geometries

    as_vector, as_set, as_hash = pool[0:2], pool[2:5], tuple(pool[5:9])
    geometry_set = GeometrySet()
    assert members(geometry_set) == set()
    expected: set[Any] = set()
    for container in (as_vector, as_set, as_hash):
        geometry_set.Add(**{keyword: container})
        expected |= set(container)
        assert members(geometry_set) == expected

    geometry_set2 = GeometrySet()
    geometry_set2.Add((as_vector[0], as_vector[1]))  # the initializer list
    assert members(geometry_set2) == set(as_vector)


def test_adding_geometries_and_frames_together(drake: ModuleType, pools: Pools) -> None:
    """IterableGeometryAndFrames: Add(geometry_ids, frame_ids), three spellings."""
    GeometrySet = drake.geometry.GeometrySet
    geometry_id_vector = pools.geometries[:2]
    frame_id_set = pools.frames[:2]

    geometry_set = GeometrySet()
    geometry_set.Add(geometry_ids=geometry_id_vector, frame_ids=frame_id_set)
    pools.expect(geometry_set, frame_id_set, geometry_id_vector)

    geometry_set2 = GeometrySet()
    geometry_set2.Add((geometry_id_vector[0], geometry_id_vector[1]), frame_id_set)
    pools.expect(geometry_set2, frame_id_set, geometry_id_vector)

    geometry_set3 = GeometrySet()
    geometry_set3.Add(geometry_id_vector, (frame_id_set[0], frame_id_set[1]))
    pools.expect(geometry_set3, frame_id_set, geometry_id_vector)


def test_adding_a_set_to_a_set_is_not_bound(drake: ModuleType, pools: Pools) -> None:
    """GeometrySetAdd: C++ ``GeometrySet::Add(const GeometrySet&)`` has no pydrake binding
    (TypeError on 1.51.1 and 1.58.0), so upstream's union check cannot run; the union of
    the ids, added as lists, is checked instead."""
    GeometrySet = drake.geometry.GeometrySet
    frame_ids, geometry_ids = pools.frames[:2], pools.geometries[:2]
    frame_ids_2, geometry_ids_2 = (
        [frame_ids[0], pools.frames[2]],
        [geometry_ids[0], pools.geometries[2]],
    )
    set1 = GeometrySet(geometry_ids=geometry_ids, frame_ids=frame_ids)
    set2 = GeometrySet(geometry_ids=geometry_ids_2, frame_ids=frame_ids_2)
    pools.expect(set1, frame_ids, geometry_ids)
    pools.expect(set2, frame_ids_2, geometry_ids_2)
    with pytest.raises(TypeError, match=r"^Add\(\): incompatible function arguments"):
        set1.Add(set2)
    set1.Add(geometry_ids=geometry_ids_2, frame_ids=frame_ids_2)
    pools.expect(set1, [*frame_ids, frame_ids_2[1]], [*geometry_ids, geometry_ids_2[1]])
