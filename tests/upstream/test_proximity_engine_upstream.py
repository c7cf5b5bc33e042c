# Ported from Drake: geometry/test/proximity_engine_test.cc
# (https://github.com/RobotLocomotion/drake, at v1.51.1), the parts about collision filters and
# candidates, re-expressed through SceneGraph and QueryObject as pytest functions that run
# unchanged on pydrake and on reimpl. Expected values are upstream's.
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
"""Upstream ProximityEngine tests, the parts about filters that the public API shows.

ProximityEngine is not bound. A SceneGraph context reaches it: each sphere sits on a
dynamic frame of its own, the pose input port gives the frame poses upstream writes
into ``X_WGs``, and the context's CollisionFilterManager applies what upstream applies
to ``engine.collision_filter()``. The queries are QueryObject's.

Left out: the AutoDiffXd and Expression engines (reimpl is double only), the
hydroelastic margin tests, and every test without a filter or candidate in it.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from types import ModuleType
from typing import Any

import pytest

from tests.upstream.geometry_support import Scene

RADIUS = 0.5
#: SimplePenetrationTest's x of the moving sphere: free and colliding.
FREE_X = 2.5 * RADIUS
COLLIDING_X = 1.5 * RADIUS


@dataclass
class Posed:
    """Spheres of RADIUS on frames of their own; a context whose poses ``move`` sets."""

    scene: Scene
    ids: list[Any]
    context: Any
    positions: dict[Any, list[float]]

    def move(self, geometry_id: Any, position: list[float]) -> None:
        self.positions[geometry_id] = position
        g = self.scene.g
        poses = g.FramePoseVector_[float]()
        for the_id, p in self.positions.items():
            frame_id = self.scene.model_inspector.GetFrameId(geometry_id=the_id)
            poses.set_value(id=frame_id, value=self.scene.drake.math.RigidTransform_[float](p=p))
        self.scene.scene_graph.get_source_pose_port(self.scene.source).FixValue(
            context=self.context, value=poses
        )

    def query(self, context: Any = None) -> Any:
        return self.scene.query_object(context if context is not None else self.context)

    def exclude_within(self, ids: list[Any]) -> None:
        g = self.scene.g
        manager = self.scene.scene_graph.collision_filter_manager(self.context)
        manager.Apply(g.CollisionFilterDeclaration().ExcludeWithin(g.GeometrySet(geometry_ids=ids)))


def posed_spheres(drake: ModuleType, positions: list[list[float]]) -> Posed:
    scene = Scene(drake)
    ids = []
    for i in range(len(positions)):
        frame_id = scene.frame()
        ids.append(
            scene.scene_graph.RegisterGeometry(
                source_id=scene.source,
                frame_id=frame_id,
                geometry=drake.geometry.GeometryInstance(
                    X_PG=drake.math.RigidTransform_[float](),
                    shape=drake.geometry.Sphere(RADIUS),
                    name=f"sphere_{i}",
                ),
            )
        )
        scene.proximity(ids[-1])
    posed = Posed(scene, ids, scene.context(), {})
    for the_id, position in zip(ids, positions, strict=True):
        posed.move(the_id, position)
    return posed


def expect_ignored_penetration(query: Any) -> None:
    """ExpectIgnoredPenetration: no penetration and no pairwise distance at all."""
    assert len(query.ComputePointPairPenetration()) == 0
    assert len(query.ComputeSignedDistancePairwiseClosestPoints(max_distance=math.inf)) == 0


def test_dynamic_spheres_collide_until_filtered(drake: ModuleType) -> None:
    """HasCollisionsDynamicAndDynamicSingleSource, then SimplePenetrationTest.
    WithCollisionFilters: once (origin, collide) is filtered, neither placement reports a
    penetration or a distance, nor does a clone of the context (upstream: a copy of the
    engine). Not upstream: HasCollisions is False once filtered (measured on pydrake
    1.51.1 and 1.58.0)."""
    posed = posed_spheres(drake, [[0, 0, 0], [0, 0, 0]])
    origin_id, collide_id = posed.ids

    posed.move(collide_id, [FREE_X, 0, 0])
    assert not posed.query().HasCollisions()
    posed.move(collide_id, [COLLIDING_X, 0, 0])
    assert posed.query().HasCollisions()
    assert (
        not posed.query()
        .inspector()
        .CollisionFiltered(geometry_id1=origin_id, geometry_id2=collide_id)
    )
    assert posed.query(posed.context.Clone()).HasCollisions()

    posed.exclude_within([origin_id, collide_id])
    assert (
        posed.query().inspector().CollisionFiltered(geometry_id1=origin_id, geometry_id2=collide_id)
    )
    posed.move(collide_id, [FREE_X, 0, 0])
    expect_ignored_penetration(posed.query())
    posed.move(collide_id, [COLLIDING_X, 0, 0])
    expect_ignored_penetration(posed.query())
    expect_ignored_penetration(posed.query(posed.context.Clone()))
    assert not posed.query().HasCollisions()


def test_unfiltered_penetration_reports_the_pair_in_id_order(drake: ModuleType) -> None:
    """ExpectPenetration (the reference the filtered case is measured against): one
    penetration, id_A < id_B, depth 2r - x."""
    posed = posed_spheres(drake, [[0, 0, 0], [COLLIDING_X, 0, 0]])
    origin_id, collide_id = posed.ids
    (penetration,) = posed.query().ComputePointPairPenetration()
    assert (penetration.id_A, penetration.id_B) == (origin_id, collide_id)
    assert penetration.depth == 2 * RADIUS - COLLIDING_X
    (distance,) = posed.query().ComputeSignedDistancePairwiseClosestPoints(max_distance=math.inf)
    assert {distance.id_A, distance.id_B} == {origin_id, collide_id}
    assert distance.id_A < distance.id_B


def test_pair_closest_points_ignore_filters(drake: ModuleType) -> None:
    """SignedDistancePairClosestPoint: the good case, the bad-id messages, and "the
    distance is evaluated even though the pair is filtered"."""
    k_distance = 1.0
    center_distance = k_distance + 2 * RADIUS
    direction = [2 / math.sqrt(29), 3 / math.sqrt(29), 4 / math.sqrt(29)]
    posed = posed_spheres(drake, [[0, 0, 0], [c * center_distance for c in direction]])
    id_A, id_B = posed.ids

    result = posed.query().ComputeSignedDistancePairClosestPoints(
        geometry_id_A=id_A, geometry_id_B=id_B
    )
    assert result.id_A == id_A
    assert result.id_B == id_B
    assert result.distance == pytest.approx(k_distance, abs=sys.float_info.epsilon)

    bad_id = drake.geometry.GeometryId.get_new_id()
    for ids in ((bad_id, id_B), (id_A, bad_id)):
        with pytest.raises(
            RuntimeError,
            match=rf"^Referenced geometry {bad_id.get_value()} has not been registered.$",
        ):
            posed.query().ComputeSignedDistancePairClosestPoints(
                geometry_id_A=ids[0], geometry_id_B=ids[1]
            )

    posed.exclude_within([id_A, id_B])
    filtered = posed.query().ComputeSignedDistancePairClosestPoints(
        geometry_id_A=id_A, geometry_id_B=id_B
    )
    assert filtered.distance == pytest.approx(k_distance, abs=sys.float_info.epsilon)


def test_collision_candidates_come_in_the_same_order_twice(drake: ModuleType) -> None:
    """FindCollisionCandidatesResultOrdering: four spheres in a ring, each touching its
    two neighbours (MakeCollidingRing(r, 4)); the candidates, asked twice with the same
    poses, come back in the same order."""
    n = 4
    span = 2 * math.pi / n
    d = 1.9 * RADIUS / math.sin(span) * math.sin((math.pi - span) / 2)
    positions = [[math.cos(i * span) * d, math.sin(i * span) * d, 0.0] for i in range(n)]
    posed = posed_spheres(drake, positions)
    results1 = posed.query().FindCollisionCandidates()
    assert len(results1) == n
    for the_id, position in zip(posed.ids, positions, strict=True):
        posed.move(the_id, position)
    results2 = posed.query().FindCollisionCandidates()
    assert len(results2) == n
    assert list(results1) == list(results2)
    ring = {frozenset((posed.ids[i], posed.ids[(i + 1) % n])) for i in range(n)}
    assert {frozenset(p) for p in results1} == ring

    # Not upstream: a filtered ring pair leaves the candidates (measured on 1.51.1, 1.58.0).
    posed.exclude_within(posed.ids[:2])
    assert {frozenset(p) for p in posed.query().FindCollisionCandidates()} == ring - {
        frozenset(posed.ids[:2])
    }


# The tests below are upstream's at Drake v1.56.0+ (geometry activation, bound since 1.55).


def _needs_activation(drake: ModuleType) -> None:
    if not hasattr(drake.geometry.CollisionFilterManager, "Deactivate"):
        pytest.skip("CollisionFilterManager.Deactivate is bound since 1.55 (activation-since-1.55)")


def _manager(posed: Posed) -> Any:
    return posed.scene.scene_graph.collision_filter_manager(posed.context)


def test_inactive_geometry_is_in_distance_to_point(drake: ModuleType) -> None:
    """InactiveGeometryInDistanceToPoint: (de)activation is about pairs; a point query
    still finds the inactive geometry."""
    _needs_activation(drake)
    posed = posed_spheres(drake, [[0, 0, 0]])
    (id_A,) = posed.ids
    for deactivate in (False, True):
        if deactivate:
            _manager(posed).Deactivate(drake.geometry.GeometrySet(id_A))
        results = posed.query().ComputeSignedDistanceToPoint(p_WQ=[0, 0, 1])
        assert [r.id_G for r in results] == [id_A]


def test_active_status_changes_reach_the_queries(drake: ModuleType) -> None:
    """ApplyActiveStatusChange (1)-(4), seen through FindCollisionCandidates: A and B
    touch; deactivating A (twice) removes the pair, activating it (twice) restores it."""
    _needs_activation(drake)
    GeometrySet = drake.geometry.GeometrySet
    posed = posed_spheres(drake, [[0, 0, 0], [1, 0, 0]])
    id_A, id_B = posed.ids
    touching = [frozenset((id_A, id_B))]

    def candidates() -> list[frozenset[Any]]:
        return [frozenset(p) for p in posed.query().FindCollisionCandidates()]

    assert candidates() == touching
    for _ in range(2):
        _manager(posed).Deactivate(GeometrySet(id_A))
        assert candidates() == []
    for _ in range(2):
        _manager(posed).Activate(GeometrySet(id_A))
        assert candidates() == touching


def test_a_geometry_moved_while_inactive_is_found_where_it_is(drake: ModuleType) -> None:
    """InactiveGeometryStaleSemantics' public face: the engine keeps an inactive
    geometry's bounding box stale while it moves, and refreshes it on Activate. So A,
    deactivated far from B, moved onto B while inactive (with queries in between) and
    then activated, collides with B; moved away again while inactive, it does not."""
    _needs_activation(drake)
    GeometrySet = drake.geometry.GeometrySet
    posed = posed_spheres(drake, [[5, 0, 0], [0, 0, 0]])
    id_A, id_B = posed.ids
    manager = _manager(posed)
    assert posed.query().FindCollisionCandidates() == []

    manager.Deactivate(GeometrySet(id_A))
    posed.move(id_A, [COLLIDING_X, 0, 0])
    assert posed.query().FindCollisionCandidates() == []
    assert len(posed.query().ComputeSignedDistanceToPoint(p_WQ=[0, 0, 3])) == 2
    manager.Activate(GeometrySet(id_A))
    (penetration,) = posed.query().ComputePointPairPenetration()
    assert {penetration.id_A, penetration.id_B} == {id_A, id_B}
    assert penetration.depth == pytest.approx(2 * RADIUS - COLLIDING_X, abs=1e-15)

    manager.Deactivate(GeometrySet(id_A))
    posed.move(id_A, [-5, 0, 0])
    assert posed.query().FindCollisionCandidates() == []
    manager.Activate(GeometrySet(id_A))
    assert posed.query().FindCollisionCandidates() == []
    assert not posed.query().HasCollisions()
