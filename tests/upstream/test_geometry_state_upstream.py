# Ported from Drake: geometry/test/geometry_state_test.cc
# (https://github.com/RobotLocomotion/drake, at v1.51.1), the tests about collision filters,
# candidates and roles, re-expressed through SceneGraph's public API as pytest functions
# that run unchanged on pydrake and on reimpl. Expected values are upstream's.
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
"""Upstream GeometryState tests about collision filters and roles, on pydrake and reimpl.

GeometryState is not bound; SceneGraph's public calls reach the same code (SceneGraph
forwards each to its model GeometryState, or to a context's copy), so each test runs
on SceneGraph's model (``model_inspector``, ``collision_filter_manager()``) or, where a
query needs poses, on a context whose source pose port is fixed. Where upstream looks
at an ``InternalGeometry`` (``gs_tester_.GetGeometry(id)``), the inspector's
``Get*Properties`` and ``GetAllGeometryIds`` give the same facts.

``SetUpSingleSourceTree``: source "default_source"; frames f0, f1 (on the world) and
f2 (on f1); two unit spheres on each frame, g0..g5, where gi sits at <i + 1, 0, 0>
rotated iπ/2 about x in its frame; an anchored 100 x 100 x 2 box at <0, 0, -1>.
f0 is at <1, 2, 3> turned 90° about x, f1 at <10, 20, 30> turned 90° about y, f2 at
the inverse of f1's pose in f1. Posed, only (a, g4) and (a, g5) collide.

Ported: RemoveAnchoredGeometry, RemoveGeometry, RemoveGeometryWithCollisionFilters,
TestCollisionCandidates, NonProximityRoleInCollisionFilter, CollisionFilteredExceptions,
GetGeometryIds (the GeometrySet resolution under every declaration),
AssignRolesToGeometry, InstanceRoleAssignment, ModifyProximityProperties (without the
hydroelastic representation), RoleAssignExceptions, ChildGeometryRoleCount,
RemoveUnassignedRole, RemoveRoleTests, PerceptionRoleWithoutRenderer,
GeometryVersionCopies and GeometryVersionUpdate (without renderers), and from Drake
v1.56.0+ DeactivateReachesProximityEngine (skipped before 1.55).

Left out: CollisionFilterRespectsScope (it needs deformable geometry and
ComputeDeformableContact, which reimpl does not model), the renderer tests, and all
tests with no collision filter, candidate or role in them.
"""

from __future__ import annotations

import copy
import math
import pickle
import re
from dataclasses import dataclass, field
from types import ModuleType
from typing import Any

import pytest

from tests.upstream.geometry_support import Scene, pair, sphere

NUM_FRAMES = 3
GEOMETRIES_PER_FRAME = 2


@dataclass
class Tree:
    """SetUpSingleSourceTree's scene and ids."""

    scene: Scene
    frames: list[Any] = field(default_factory=list)
    geometries: list[Any] = field(default_factory=list)
    X_PFs: list[Any] = field(default_factory=list)
    anchored: Any = None

    @property
    def g(self) -> ModuleType:
        return self.scene.g

    @property
    def sg(self) -> Any:
        return self.scene.scene_graph

    @property
    def source(self) -> Any:
        return self.scene.source

    @property
    def inspector(self) -> Any:
        return self.scene.model_inspector

    @property
    def manager(self) -> Any:
        return self.sg.collision_filter_manager()

    def all_geometry_ids(self) -> list[Any]:
        return [*self.geometries, self.anchored]

    def assign(self, properties: Any, geometry_id: Any) -> None:
        self.sg.AssignRole(source_id=self.source, geometry_id=geometry_id, properties=properties)

    def assign_to_all(self, properties: Any) -> None:
        for geometry_id in self.all_geometry_ids():
            self.assign(properties, geometry_id)

    def posed_query(self) -> Any:
        """A context with every frame at its default pose; its QueryObject."""
        context = self.sg.CreateDefaultContext()
        poses = self.g.FramePoseVector_[float]()
        for frame_id, X_PF in zip(self.frames, self.X_PFs, strict=True):
            poses.set_value(id=frame_id, value=X_PF)
        self.sg.get_source_pose_port(self.source).FixValue(context=context, value=poses)
        return self.scene.query_object(context)


def single_source_tree(drake: ModuleType, *roles: str) -> Tree:
    """SetUpSingleSourceTree(roles), roles among "proximity", "perception", "illustration"."""
    g = drake.geometry
    m = drake.math
    RigidTransform = m.RigidTransform_[float]
    scene = Scene(drake, source_name="default_source")
    tree = Tree(scene)
    sg = scene.scene_graph
    source = scene.source

    RotationMatrix = m.RotationMatrix_[float]

    X_WF0 = RigidTransform(R=RotationMatrix.MakeXRotation(theta=math.pi / 2), p=[1, 2, 3])
    X_WF1 = RigidTransform(R=RotationMatrix.MakeYRotation(theta=math.pi / 2), p=[10, 20, 30])
    X_F1F2 = X_WF1.inverse()
    f0 = sg.RegisterFrame(source_id=source, frame=g.GeometryFrame("f0"))
    f1 = sg.RegisterFrame(source_id=source, frame=g.GeometryFrame("f1"))
    f2 = sg.RegisterFrame(source_id=source, parent_id=f1, frame=g.GeometryFrame("f2"))
    tree.frames = [f0, f1, f2]
    tree.X_PFs = [X_WF0, X_WF1, X_F1F2]
    for frame_id in tree.frames:
        for i in range(GEOMETRIES_PER_FRAME):
            count = len(tree.geometries)
            X_FG = RigidTransform(
                R=RotationMatrix.MakeXRotation(theta=count * math.pi / 2), p=[count + 1.0, 0, 0]
            )
            name = f"{frame_id.get_value()}_g{i}"
            instance = g.GeometryInstance(X_PG=X_FG, shape=g.Sphere(1), name=name)
            tree.geometries.append(
                sg.RegisterGeometry(source_id=source, frame_id=frame_id, geometry=instance)
            )
    X_WA = RigidTransform(p=[0, 0, -1])
    tree.anchored = sg.RegisterAnchoredGeometry(
        source_id=source,
        geometry=g.GeometryInstance(X_PG=X_WA, shape=g.Box(100, 100, 2), name="anchored"),
    )
    if "proximity" in roles:
        properties = g.ProximityProperties()
        properties.AddProperty("test", "value", 17)
        tree.assign_to_all(properties)
    if "perception" in roles:
        properties = g.PerceptionProperties()
        properties.AddProperty("test", "value", 17)
        tree.assign_to_all(properties)
    if "illustration" in roles:
        properties = g.IllustrationProperties()
        properties.AddProperty("test", "value", 17)
        tree.assign_to_all(properties)
    return tree


def test_removing_anchored_geometry(drake: ModuleType) -> None:
    """RemoveAnchoredGeometry: with a second anchored (half space) proximity geometry."""
    g = drake.geometry
    tree = single_source_tree(drake, "proximity")
    X_WB = g.HalfSpace.MakePose(Hz_dir_F=[0, 1, 0], p_FB=[1, 1, 1])
    anchored_id_1 = tree.sg.RegisterAnchoredGeometry(
        source_id=tree.source,
        geometry=g.GeometryInstance(X_PG=X_WB, shape=g.HalfSpace(), name="anchored1"),
    )
    tree.assign(g.ProximityProperties(), anchored_id_1)
    assert tree.inspector.BelongsToSource(geometry_id=anchored_id_1, source_id=tree.source)
    tree.sg.RemoveGeometry(source_id=tree.source, geometry_id=tree.anchored)
    assert tree.anchored not in tree.inspector.GetAllGeometryIds()
    assert anchored_id_1 in tree.inspector.GetAllGeometryIds()


def test_removing_geometry_keeps_the_other_filters(drake: ModuleType) -> None:
    """RemoveGeometryWithCollisionFilters: siblings stay filtered, the rest do not."""
    tree = single_source_tree(drake, "proximity")
    gs = tree.geometries

    def is_filtered(i: int, j: int) -> bool:
        return bool(tree.inspector.CollisionFiltered(geometry_id1=gs[i], geometry_id2=gs[j]))

    siblings = {(0, 1), (2, 3), (4, 5)}
    for i in range(6):
        for j in range(i + 1, 6):
            assert is_filtered(i, j) == ((i, j) in siblings), (i, j)

    tree.sg.RemoveGeometry(source_id=tree.source, geometry_id=tree.anchored)
    tree.sg.RemoveGeometry(source_id=tree.source, geometry_id=gs[1])
    for i in (0, 2, 3, 4, 5):
        for j in (0, 2, 3, 4, 5):
            if i < j:
                assert is_filtered(i, j) == ((i, j) in siblings), (i, j)


def test_collision_candidates_shrink_one_filtered_pair_at_a_time(drake: ModuleType) -> None:
    """TestCollisionCandidates: every pair but the siblings, then ExcludeBetween each.

    Upstream compares ``set<pair<GeometryId, GeometryId>>``, so the order within a pair
    counts: the lower id first (here the ids grow in registration order).
    """
    g = drake.geometry
    tree = single_source_tree(drake, "proximity")
    gs, a = tree.geometries, tree.anchored
    expected = {
        (gs[i], gs[j]) for i in range(6) for j in range(i + 1, 6) if (i // 2) != (j // 2)
    } | {(x, a) for x in gs}
    assert len(expected) == 18
    assert set(tree.inspector.GetCollisionCandidates()) == expected

    for first, second in sorted(expected, key=lambda p: (p[0].get_value(), p[1].get_value())):
        tree.manager.Apply(
            g.CollisionFilterDeclaration().ExcludeBetween(
                g.GeometrySet(geometry_id=first), g.GeometrySet(geometry_id=second)
            )
        )
        expected.discard((first, second))
        assert set(tree.inspector.GetCollisionCandidates()) == expected
    # pydrake returns GetCollisionCandidates() as a Python set (of id tuples).
    assert tree.inspector.GetCollisionCandidates() == set()


def test_filtering_a_geometry_without_proximity_role_does_nothing(drake: ModuleType) -> None:
    """NonProximityRoleInCollisionFilter: a declaration naming a geometry that has no
    proximity role leaves it out; once it has the role, it collides until filtered."""
    g = drake.geometry
    RigidTransform = drake.math.RigidTransform_[float]
    tree = single_source_tree(drake, "proximity")

    def collisions() -> int:
        return len(tree.posed_query().ComputePointPairPenetration())

    expected_collisions = 2  # (a, g4), (a, g5)
    assert collisions() == expected_collisions
    added_id = tree.sg.RegisterGeometry(
        source_id=tree.source,
        frame_id=tree.frames[2],
        geometry=g.GeometryInstance(
            X_PG=RigidTransform(p=[5.5, 0, 0]), shape=g.Sphere(1), name="added_sphere"
        ),
    )
    assert collisions() == expected_collisions

    def exclude_added_and_anchored() -> None:
        tree.manager.Apply(
            g.CollisionFilterDeclaration().ExcludeBetween(
                g.GeometrySet(geometry_id=added_id), g.GeometrySet(geometry_id=tree.anchored)
            )
        )

    exclude_added_and_anchored()
    assert collisions() == expected_collisions
    tree.assign(g.ProximityProperties(), added_id)
    assert collisions() == expected_collisions + 1
    exclude_added_and_anchored()
    assert collisions() == expected_collisions


def test_collision_filtered_error_messages(drake: ModuleType) -> None:
    """CollisionFilteredExceptions. pydrake's messages in full (upstream matches them with
    regexes); note the two spaces before "neither id has a proximity role"."""
    g = drake.geometry
    tree = single_source_tree(drake)
    gs = tree.geometries
    tree.assign(g.ProximityProperties(), gs[0])

    def message(a: Any, b: Any, tail: str) -> str:
        text = (
            f"Can't report collision filter status between geometries "
            f"{a.get_value()} and {b.get_value()}; {tail}"
        )
        return "^" + re.escape(text) + "$"

    def collision_filtered(a: Any, b: Any) -> bool:
        return bool(tree.inspector.CollisionFiltered(geometry_id1=a, geometry_id2=b))

    no_role = f"{gs[1].get_value()} does not have a proximity role"
    with pytest.raises(RuntimeError, match=message(gs[1], gs[0], no_role)):
        collision_filtered(gs[1], gs[0])
    with pytest.raises(RuntimeError, match=message(gs[0], gs[1], no_role)):
        collision_filtered(gs[0], gs[1])
    with pytest.raises(
        RuntimeError, match=message(gs[1], gs[2], " neither id has a proximity role")
    ):
        collision_filtered(gs[1], gs[2])

    tree.assign(g.ProximityProperties(), gs[1])
    assert collision_filtered(gs[0], gs[1])

    bad_id = g.GeometryId.get_new_id()
    invalid = f"{bad_id.get_value()} is not a valid geometry"
    with pytest.raises(RuntimeError, match=message(bad_id, gs[0], invalid)):
        collision_filtered(bad_id, gs[0])
    with pytest.raises(RuntimeError, match=message(gs[0], bad_id, invalid)):
        collision_filtered(gs[0], bad_id)
    with pytest.raises(
        RuntimeError, match=message(bad_id, bad_id, "neither id is a valid geometry")
    ):
        collision_filtered(bad_id, bad_id)


def _roles(tree: Tree, geometry_id: Any) -> tuple[bool, bool, bool]:
    """(proximity, perception, illustration): which roles the geometry has."""
    inspector = tree.inspector
    return (
        inspector.GetProximityProperties(geometry_id=geometry_id) is not None,
        inspector.GetPerceptionProperties(geometry_id=geometry_id) is not None,
        inspector.GetIllustrationProperties(geometry_id=geometry_id) is not None,
    )


def test_each_combination_of_roles_is_assigned(drake: ModuleType) -> None:
    """AssignRolesToGeometry: eight geometries get the eight combinations of roles.

    Upstream's perception properties come from its dummy renderer; with no renderer,
    plain PerceptionProperties with a label (as GeometryStateNoRendererTest does)."""
    g = drake.geometry
    tree = single_source_tree(drake)
    for i in range(8 - len(tree.geometries)):
        tree.geometries.append(
            tree.sg.RegisterGeometry(
                source_id=tree.source,
                frame_id=tree.frames[0],
                geometry=g.GeometryInstance(
                    X_PG=drake.math.RigidTransform_[float](), shape=g.Sphere(1), name=f"new_geom{i}"
                ),
            )
        )

    def set_roles(geometry_id: Any, proximity: bool, perception: bool, illustration: bool) -> None:
        if proximity:
            tree.assign(g.ProximityProperties(), geometry_id)
        if perception:
            tree.assign(g.PerceptionProperties(), geometry_id)
        if illustration:
            tree.assign(g.IllustrationProperties(), geometry_id)

    for i in range(8):
        proximity, illustration, perception = bool(i & 1), bool(i & 2), bool(i & 4)
        geometry_id = tree.geometries[i]
        assert _roles(tree, geometry_id) == (False, False, False), i
        set_roles(geometry_id, proximity, perception, illustration)
        assert _roles(tree, geometry_id) == (proximity, perception, illustration), i

    assert _roles(tree, tree.anchored) == (False, False, False)
    set_roles(tree.anchored, True, False, True)
    assert _roles(tree, tree.anchored) == (True, False, True)


def test_role_counts_per_frame(drake: ModuleType) -> None:
    """ChildGeometryRoleCount: NumGeometriesForFrameWithRole after each assignment."""
    g = drake.geometry
    tree = single_source_tree(drake)
    Role = g.Role

    def counts(frame_id: Any) -> tuple[int, int, int]:
        return tuple(  # type: ignore[return-value]
            tree.inspector.NumGeometriesForFrameWithRole(frame_id=frame_id, role=role)
            for role in (Role.kProximity, Role.kPerception, Role.kIllustration)
        )

    f_id = tree.frames[0]
    g_id1, g_id2 = tree.geometries[0], tree.geometries[1]
    assert tree.inspector.GetFrameId(geometry_id=g_id1) == f_id
    assert tree.inspector.GetFrameId(geometry_id=g_id2) == f_id
    perception = g.PerceptionProperties()
    steps = [
        (g_id1, g.ProximityProperties(), (1, 0, 0)),
        (g_id2, g.IllustrationProperties(), (1, 0, 1)),
        (g_id1, g.IllustrationProperties(), (1, 0, 2)),
        (g_id1, perception, (1, 1, 2)),
        (g_id2, perception, (1, 2, 2)),
        (g_id2, g.ProximityProperties(), (2, 2, 2)),
    ]
    assert counts(f_id) == (0, 0, 0)
    for geometry_id, properties, expected in steps:
        tree.assign(properties, geometry_id)
        assert counts(f_id) == expected

    world_id = tree.sg.world_frame_id()
    assert counts(world_id) == (0, 0, 0)
    for properties, expected in (
        (g.ProximityProperties(), (1, 0, 0)),
        (perception, (1, 1, 0)),
        (g.IllustrationProperties(), (1, 1, 1)),
    ):
        tree.assign(properties, tree.anchored)
        assert counts(world_id) == expected


ALL_ROLES = ("proximity", "perception", "illustration")


def test_removing_the_unassigned_role_does_nothing(drake: ModuleType) -> None:
    """RemoveUnassignedRole."""
    Role = drake.geometry.Role
    tree = single_source_tree(drake, *ALL_ROLES)
    assert (
        tree.sg.RemoveRole(
            source_id=tree.source, geometry_id=tree.geometries[0], role=Role.kUnassigned
        )
        == 0
    )
    assert (
        tree.sg.RemoveRole(source_id=tree.source, frame_id=tree.frames[0], role=Role.kUnassigned)
        == 0
    )
    for geometry_id in tree.geometries:
        assert _roles(tree, geometry_id) == (True, True, True)


ROLE_INDEX = {"kProximity": 0, "kPerception": 1, "kIllustration": 2}


def _expect_all_roles_except(tree: Tree, without: set[Any], role_name: str) -> None:
    for geometry_id in tree.geometries:
        expected = [True, True, True]
        expected[ROLE_INDEX[role_name]] = geometry_id not in without
        assert _roles(tree, geometry_id) == tuple(expected), geometry_id


@pytest.mark.parametrize("role_name", list(ROLE_INDEX))
def test_remove_role_from_geometry(drake: ModuleType, role_name: str) -> None:
    """RemoveRoleTests.RemoveRoleFromGeometry (no renderer; upstream adds two)."""
    role = getattr(drake.geometry.Role, role_name)
    tree = single_source_tree(drake, *ALL_ROLES)
    g0 = tree.geometries[0]
    _expect_all_roles_except(tree, set(), role_name)
    assert tree.sg.RemoveRole(source_id=tree.source, geometry_id=g0, role=role) == 1
    _expect_all_roles_except(tree, {g0}, role_name)
    assert tree.sg.RemoveRole(source_id=tree.source, geometry_id=g0, role=role) == 0
    _expect_all_roles_except(tree, {g0}, role_name)


@pytest.mark.parametrize("role_name", list(ROLE_INDEX))
def test_remove_role_from_frame(drake: ModuleType, role_name: str) -> None:
    """RemoveRoleTests.RemoveRoleFromFrame."""
    role = getattr(drake.geometry.Role, role_name)
    tree = single_source_tree(drake, *ALL_ROLES)
    gs, fs, sg, source = tree.geometries, tree.frames, tree.sg, tree.source
    without: set[Any] = set()
    _expect_all_roles_except(tree, without, role_name)

    without |= {gs[0], gs[1]}
    assert sg.RemoveRole(source_id=source, frame_id=fs[0], role=role) == 2
    _expect_all_roles_except(tree, without, role_name)
    assert sg.RemoveRole(source_id=source, frame_id=fs[0], role=role) == 0
    _expect_all_roles_except(tree, without, role_name)

    sg.RemoveRole(source_id=source, geometry_id=gs[2], role=role)
    without.add(gs[2])
    _expect_all_roles_except(tree, without, role_name)
    assert sg.RemoveRole(source_id=source, frame_id=fs[1], role=role) == 1
    without.add(gs[3])
    _expect_all_roles_except(tree, without, role_name)

    source_id_2 = sg.RegisterSource("source2")
    assert sg.RemoveRole(source_id=source_id_2, frame_id=sg.world_frame_id(), role=role) == 0
    _expect_all_roles_except(tree, without, role_name)
    assert sg.RemoveRole(source_id=source, frame_id=sg.world_frame_id(), role=role) == 1
    anchored_roles = [True, True, True]
    anchored_roles[ROLE_INDEX[role_name]] = False
    assert _roles(tree, tree.anchored) == tuple(anchored_roles)


def test_remove_role_error_messages(drake: ModuleType) -> None:
    """RemoveRoleTests.RemoveRoleExceptions (upstream's regexes, pydrake's full text)."""
    g = drake.geometry
    tree = single_source_tree(drake, *ALL_ROLES)
    sg, source, unassigned = tree.sg, tree.source, g.Role.kUnassigned
    invalid_source_id = g.SourceId.get_new_id()
    invalid_frame_id = g.FrameId.get_new_id()
    invalid_geometry_id = g.GeometryId.get_new_id()

    def raises(pattern: str) -> Any:
        return pytest.raises(RuntimeError, match=pattern)

    source_unknown = (
        rf"^Referenced geometry source {invalid_source_id.get_value()} is not registered.$"
    )
    with raises(source_unknown):
        sg.RemoveRole(source_id=invalid_source_id, frame_id=invalid_frame_id, role=unassigned)
    with raises(source_unknown):
        sg.RemoveRole(source_id=invalid_source_id, geometry_id=invalid_geometry_id, role=unassigned)
    with raises("^Referenced .* frame doesn't belong to the source.$"):
        sg.RemoveRole(source_id=source, frame_id=invalid_frame_id, role=unassigned)
    with raises(
        rf"^Referenced geometry {invalid_geometry_id.get_value()} has not been registered.$"
    ):
        sg.RemoveRole(source_id=source, geometry_id=invalid_geometry_id, role=unassigned)

    source_id_2 = sg.RegisterSource("second_source")
    with raises("^Referenced .* frame doesn't belong to the source.$"):
        sg.RemoveRole(source_id=source_id_2, frame_id=tree.frames[0], role=unassigned)
    with raises("^.*the geometry doesn't belong to that source.$"):
        sg.RemoveRole(source_id=source_id_2, geometry_id=tree.geometries[0], role=unassigned)


def test_perception_role_without_renderer(drake: ModuleType) -> None:
    """GeometryStateNoRendererTest.PerceptionRoleWithoutRenderer."""
    Role = drake.geometry.Role
    tree = single_source_tree(drake, "perception")
    g0 = tree.geometries[0]
    # Upstream asserts RendererCount() == 0; SceneGraph here never gets a renderer (and
    # reimpl binds no renderer API).
    assert _roles(tree, g0)[1]
    assert tree.sg.RemoveRole(source_id=tree.source, geometry_id=g0, role=Role.kPerception) == 1
    assert not _roles(tree, g0)[1]
    assert tree.sg.RemoveRole(source_id=tree.source, geometry_id=g0, role=Role.kPerception) == 0


def test_sibling_pairs_are_filtered_in_the_tree(drake: ModuleType) -> None:
    """The tree's comment: (g0, g1), (g2, g3), (g4, g5) are filtered as siblings; the
    anchored box collides with nothing else anchored (it is alone)."""
    tree = single_source_tree(drake, "proximity")
    gs = tree.geometries
    candidates = {pair(a, b) for a, b in tree.inspector.GetCollisionCandidates()}
    for i in (0, 2, 4):
        assert pair(gs[i], gs[i + 1]) not in candidates


def test_geometry_set_resolution_by_role(drake: ModuleType) -> None:
    """GetGeometryIds: a GeometrySet resolves to geometries (frames expand to their
    geometries, redundant ids appear once), optionally only those with a role. This is
    the resolution every collision filter declaration goes through."""
    g = drake.geometry
    Role = g.Role
    tree = single_source_tree(drake, "proximity")
    gs, fs = tree.geometries, tree.frames
    perception = g.PerceptionProperties()
    perception.AddProperty("phong", "diffuse", g.Rgba(0.8, 0.8, 0.8, 1.0))
    for geometry_id in (gs[2], gs[3]):
        tree.assign(perception, geometry_id)
    illustration = g.IllustrationProperties()
    illustration.AddProperty("phong", "diffuse", g.Rgba(0.8, 0.8, 0.8, 1.0))
    tree.assign(illustration, gs[4])
    tree.assign(illustration, gs[5])
    tree.assign(perception, gs[5])

    all_geometries = {*gs, tree.anchored}
    perception_geometries = {gs[2], gs[3], gs[5]}
    illustration_geometries = {gs[4], gs[5]}

    def ids(geometry_set: Any, role: Any = None) -> Any:
        return tree.inspector.GetGeometryIds(geometry_set=geometry_set, role=role)

    all_frames = [*fs, tree.sg.world_frame_id()]
    for geometry_set in (
        g.GeometrySet(frame_ids=all_frames),
        g.GeometrySet(geometry_ids=list(all_geometries)),
    ):
        assert ids(geometry_set) == all_geometries
        assert ids(geometry_set, Role.kProximity) == all_geometries
        assert ids(geometry_set, Role.kPerception) == perception_geometries
        assert ids(geometry_set, Role.kIllustration) == illustration_geometries

    assert tree.inspector.GetFrameId(geometry_id=gs[2]) == fs[1]
    assert tree.inspector.GetFrameId(geometry_id=gs[3]) == fs[1]
    redundant_set = g.GeometrySet(geometry_ids=[gs[2]], frame_ids=[fs[1]])
    assert ids(redundant_set) == {gs[2], gs[3]}
    assert ids(redundant_set, Role.kProximity) == {gs[2], gs[3]}
    assert ids(redundant_set, Role.kPerception) == {gs[2], gs[3]}
    assert ids(redundant_set, Role.kIllustration) == set()


ROLES = ("kProximity", "kPerception", "kIllustration")


def _changed(drake: ModuleType, before: Any, after: Any) -> set[str]:
    """The roles whose versions differ between two GeometryVersions."""
    Role = drake.geometry.Role
    return {r for r in ROLES if not before.IsSameAs(other=after, role=getattr(Role, r))}


def _fixed_context(tree: Tree) -> Any:
    """A context with the pose port fixed: a context is cloned only then (both
    implementations raise "has registered dynamic frames but is not connected")."""
    context = tree.sg.CreateDefaultContext()
    poses = tree.g.FramePoseVector_[float]()
    for frame_id, X_PF in zip(tree.frames, tree.X_PFs, strict=True):
        poses.set_value(id=frame_id, value=X_PF)
    tree.sg.get_source_pose_port(tree.source).FixValue(context=context, value=poses)
    return context


def test_copied_states_share_the_version(drake: ModuleType) -> None:
    """GeometryVersionCopies: model -> gs1, gs2; gs1 -> gs3 share every role's version.
    Here gs1 and gs2 are two contexts of the model, gs3 a clone of gs1.

    Upstream's tree has proximity on every geometry; here the copies are compared with
    and without it. With proximity, a context's state is the model's with the
    SceneGraphConfig proximity defaults backfilled (``ApplyProximityDefaults``, a
    kReplace of the properties), so the contexts agree with each other but not with the
    model on proximity: see the next test."""
    for roles in ((), ("illustration",), ("proximity",)):
        tree = single_source_tree(drake, *roles)
        context_1 = _fixed_context(tree)
        context_2 = tree.sg.CreateDefaultContext()
        context_3 = context_1.Clone()
        copies = [
            tree.scene.context_inspector(c).geometry_version()
            for c in (context_1, context_2, context_3)
        ]
        for a in copies:
            for b in copies:
                assert _changed(drake, a, b) == set(), roles
        if "proximity" not in roles:
            for a in copies:
                assert _changed(drake, tree.inspector.geometry_version(), a) == set(), roles


def test_a_context_backfills_the_proximity_defaults(
    drake: ModuleType, request: pytest.FixtureRequest
) -> None:
    """Not upstream (the C++ test copies GeometryStates, not contexts): a context of a
    model whose proximity geometries lack SceneGraphConfig's default proximity
    properties gets them (SceneGraph's augmented model: ``ApplyProximityDefaults``),
    which changes the context's proximity version. Measured on pydrake 1.51.1 and
    1.58.0: a ProximityProperties with only ("test", "value") gains hydroelastic
    resolution_hint 0.02 and hydroelastic_modulus 1e7 among others.

    Drake's docs (scene_graph.h, "Detecting changes") say the model's version "is the
    same as the version in the Context provided by SceneGraph::CreateDefaultContext()";
    with proximity geometry that lacks the defaults it is not (the proximity versions
    differ), as asserted here.

    reimpl has no SceneGraphConfig and does not backfill: a known gap, not a filter
    rule (the filter and candidates are the same either way)."""
    if drake.__name__ == "reimpl":
        request.applymarker(
            pytest.mark.xfail(strict=True, reason="reimpl has no SceneGraphConfig defaults")
        )
    tree = single_source_tree(drake, "proximity")
    context = tree.sg.CreateDefaultContext()
    context_inspector = tree.scene.context_inspector(context)
    g0 = tree.geometries[0]
    model_props = tree.inspector.GetProximityProperties(geometry_id=g0)
    context_props = context_inspector.GetProximityProperties(geometry_id=g0)
    assert not model_props.HasProperty("hydroelastic", "resolution_hint")
    assert context_props.GetProperty("hydroelastic", "resolution_hint") == 0.02
    assert context_props.GetProperty("hydroelastic", "hydroelastic_modulus") == 1e7
    assert _changed(
        drake, tree.inspector.geometry_version(), context_inspector.geometry_version()
    ) == {"kProximity"}


def test_each_call_changes_the_versions_of_its_role(drake: ModuleType) -> None:
    """GeometryVersionUpdate, without renderers: the perception cases become upstream's
    "not accepted by any renderer" case (no version changes). The filter line:
    handing out a collision_filter_manager changes the proximity version.

    Not upstream: the inspector's ``geometry_version()`` is a live object in pydrake
    (the same object each call; it follows later changes), so each step keeps a copy
    ``GeometryVersion(other=...)`` (measured on pydrake 1.51.1 and 1.58.0)."""
    g = drake.geometry
    Role = g.Role
    tree = single_source_tree(drake)
    sg, source, gs = tree.sg, tree.source, tree.geometries
    inspector = tree.inspector
    assert inspector.geometry_version() is inspector.geometry_version()

    def changes(call: Any) -> set[str]:
        before = g.GeometryVersion(other=inspector.geometry_version())
        call()
        return _changed(drake, before, inspector.geometry_version())

    new_source: list[Any] = []
    assert changes(lambda: new_source.append(sg.RegisterSource("my_new_source"))) == set()
    new_frames: list[Any] = []
    assert (
        changes(
            lambda: new_frames.append(
                sg.RegisterFrame(source_id=new_source[0], frame=g.GeometryFrame("new_f0"))
            )
        )
        == set()
    )
    assert (
        changes(
            lambda: sg.RegisterFrame(
                source_id=new_source[0], parent_id=new_frames[0], frame=g.GeometryFrame("new_f1")
            )
        )
        == set()
    )
    assert (
        changes(
            lambda: sg.RegisterGeometry(
                source_id=new_source[0],
                frame_id=new_frames[0],
                geometry=sphere(drake, "new_geometry_0"),
            )
        )
        == set()
    )
    assert (
        changes(
            lambda: sg.RegisterAnchoredGeometry(
                source_id=new_source[0], geometry=sphere(drake, "new_geometry_2")
            )
        )
        == set()
    )

    def assign(geometry_id: Any, properties: Any, assign: Any = g.RoleAssign.kNew) -> Any:
        return lambda: sg.AssignRole(
            source_id=source, geometry_id=geometry_id, properties=properties, assign=assign
        )

    def remove(geometry_id: Any, role: Any) -> Any:
        return lambda: sg.RemoveRole(source_id=source, geometry_id=geometry_id, role=role)

    assert changes(assign(gs[0], g.ProximityProperties())) == {"kProximity"}
    assert changes(assign(gs[0], g.ProximityProperties(), g.RoleAssign.kReplace)) == {"kProximity"}
    assert changes(assign(gs[2], g.PerceptionProperties())) == set()
    illustration = g.IllustrationProperties()
    illustration.AddProperty("phong", "diffuse", g.Rgba(0.8, 0.8, 0.8, 1.0))
    assert changes(assign(gs[3], illustration)) == {"kIllustration"}
    assert changes(remove(gs[0], Role.kProximity)) == {"kProximity"}
    assert changes(remove(gs[2], Role.kPerception)) == set()
    assert changes(remove(gs[3], Role.kIllustration)) == {"kIllustration"}
    assert changes(remove(gs[3], Role.kIllustration)) == set()  # a role it no longer has

    for i in range(3):
        sg.AssignRole(source_id=source, geometry_id=gs[i], properties=g.ProximityProperties())
    assert changes(lambda: sg.collision_filter_manager()) == {"kProximity"}
    manager = sg.collision_filter_manager()
    declaration = g.CollisionFilterDeclaration().ExcludeWithin(g.GeometrySet(geometry_ids=gs[:3]))
    assert changes(lambda: manager.Apply(declaration)) == set()


def test_a_context_manager_changes_only_that_contexts_version(drake: ModuleType) -> None:
    """The same line on a context: the context's proximity version changes, the model's
    does not (not upstream, which has no contexts here; measured on 1.51.1 and 1.58.0).
    The tree has no proximity defaults to backfill (previous test): illustration only."""
    g = drake.geometry
    tree = single_source_tree(drake, "illustration")
    context = tree.sg.CreateDefaultContext()
    context_inspector = tree.scene.context_inspector(context)
    model_before = g.GeometryVersion(other=tree.inspector.geometry_version())
    context_before = g.GeometryVersion(other=context_inspector.geometry_version())
    assert _changed(drake, model_before, context_before) == set()
    tree.sg.collision_filter_manager(context)
    assert _changed(drake, context_before, context_inspector.geometry_version()) == {"kProximity"}
    assert _changed(drake, model_before, tree.inspector.geometry_version()) == set()


def test_geometry_versions_compare_per_role(drake: ModuleType) -> None:
    """geometry/test/geometry_version_test.cc's public half: a new version differs from
    every other in every role, a copy agrees in every role, kUnassigned cannot be
    compared (Drake's std::logic_error; pydrake raises RuntimeError)."""
    g = drake.geometry
    a, b = g.GeometryVersion(), g.GeometryVersion()
    assert _changed(drake, a, b) == set(ROLES)
    for copy_of_a in (g.GeometryVersion(other=a), copy.copy(a), copy.deepcopy(a)):
        assert _changed(drake, a, copy_of_a) == set()
    with pytest.raises(
        RuntimeError, match=r"^Trying to compare the version of unassigned roles\.$"
    ):
        a.IsSameAs(other=a, role=g.Role.kUnassigned)
    # Not upstream: a version copies but does not pickle (pydrake 1.51.1 and 1.58.0).
    with pytest.raises(
        TypeError, match=f"^cannot pickle '{drake.__name__}.geometry.GeometryVersion' object$"
    ):
        pickle.dumps(a)


def test_removing_a_proximity_geometry_and_adding_another(drake: ModuleType) -> None:
    """RemoveGeometry: counts drop by one, the posed queries still run, and a new
    proximity sphere on the same frame is filtered against its sibling (upstream asks
    only that nothing throws; the candidates are what that means here)."""
    g = drake.geometry
    tree = single_source_tree(drake, "proximity", "perception")
    gs, fs = tree.geometries, tree.frames
    inspector = tree.inspector
    assert inspector.GetFrameId(geometry_id=gs[0]) == fs[0]
    assert inspector.num_geometries() == 7
    assert inspector.NumDynamicGeometries() == 6
    tree.sg.RemoveGeometry(source_id=tree.source, geometry_id=gs[0])
    assert inspector.num_geometries() == 6
    assert inspector.NumDynamicGeometries() == 5
    assert gs[0] not in inspector.GetGeometries(frame_id=fs[0])
    assert gs[0] not in inspector.GetAllGeometryIds()
    assert len(tree.posed_query().ComputePointPairPenetration()) == 2

    added_id = tree.sg.RegisterGeometry(
        source_id=tree.source, frame_id=fs[0], geometry=sphere(drake, "newest")
    )
    tree.assign(g.ProximityProperties(), added_id)
    assert inspector.CollisionFiltered(geometry_id1=added_id, geometry_id2=gs[1])
    assert pair(added_id, gs[2]) in {pair(a, b) for a, b in inspector.GetCollisionCandidates()}
    tree.sg.RemoveGeometry(source_id=tree.source, geometry_id=added_id)
    assert len(tree.posed_query().ComputePointPairPenetration()) == 2


def test_instance_properties_become_roles(drake: ModuleType) -> None:
    """InstanceRoleAssignment: the properties an instance carries become its roles."""
    g = drake.geometry
    scene = Scene(drake)
    f_id = scene.frame("frame")
    cases = {
        "instance1": (False, False, False),
        "instance2": (True, False, False),
        "instance3": (False, False, True),
        "instance4": (False, True, False),
        "instance5": (True, True, True),
    }
    tree = Tree(scene)
    for name, (proximity, perception, illustration) in cases.items():
        instance = sphere(drake, name)
        if proximity:
            instance.set_proximity_properties(g.ProximityProperties())
        if perception:
            instance.set_perception_properties(g.PerceptionProperties())
        if illustration:
            instance.set_illustration_properties(g.IllustrationProperties())
        g_id = scene.scene_graph.RegisterGeometry(
            source_id=scene.source, frame_id=f_id, geometry=instance
        )
        assert _roles(tree, g_id) == (proximity, perception, illustration), name


def test_replacing_proximity_properties(drake: ModuleType) -> None:
    """ModifyProximityProperties, without the hydroelastic representation (internal):
    kReplace before a first assignment throws; after one, the new properties replace
    the old (no group of the old is left) and the filter keeps one entry."""
    g = drake.geometry
    tree = single_source_tree(drake)
    g0 = tree.geometries[0]
    props1 = g.ProximityProperties()
    props1.AddProperty("prop1", "value", 1)
    props2 = g.ProximityProperties()
    props2.AddProperty("prop2", "value", 2)
    with pytest.raises(
        RuntimeError,
        match=r"^Trying to replace the properties on geometry id \d+ for the 'proximity' role.*",
    ):
        tree.sg.AssignRole(
            source_id=tree.source,
            geometry_id=g0,
            properties=g.ProximityProperties(),
            assign=g.RoleAssign.kReplace,
        )
    tree.assign(props1, g0)
    assert tree.inspector.NumGeometriesWithRole(role=g.Role.kProximity) == 1
    props = tree.inspector.GetProximityProperties(geometry_id=g0)
    assert props.HasGroup("prop1")
    assert props.GetProperty("prop1", "value") == 1
    tree.sg.AssignRole(
        source_id=tree.source, geometry_id=g0, properties=props2, assign=g.RoleAssign.kReplace
    )
    assert tree.inspector.NumGeometriesWithRole(role=g.Role.kProximity) == 1
    props = tree.inspector.GetProximityProperties(geometry_id=g0)
    assert props.HasGroup("prop2")
    assert not props.HasGroup("prop1")
    assert props.GetProperty("prop2", "value") == 2


def test_role_assignment_error_messages(drake: ModuleType) -> None:
    """RoleAssignExceptions (upstream's regexes)."""
    g = drake.geometry
    tree = single_source_tree(drake)
    sg, source, g0 = tree.sg, tree.source, tree.geometries[0]

    def assign(source_id: Any, geometry_id: Any, properties: Any) -> None:
        sg.AssignRole(source_id=source_id, geometry_id=geometry_id, properties=properties)

    with pytest.raises(RuntimeError, match=r"^Referenced geometry source \d+ is not registered.$"):
        assign(g.SourceId.get_new_id(), g0, g.ProximityProperties())
    with pytest.raises(RuntimeError, match=r"^Referenced geometry \d+ has not been registered.$"):
        assign(source, g.GeometryId.get_new_id(), g.ProximityProperties())
    other_source = sg.RegisterSource("alt_source")
    with pytest.raises(
        RuntimeError, match=r"^Given geometry id \d+ does not belong to the given source .*"
    ):
        assign(other_source, g0, g.ProximityProperties())

    for role, make in (
        ("proximity", g.ProximityProperties),
        ("perception", g.PerceptionProperties),
        ("illustration", g.IllustrationProperties),
    ):
        assign(source, g0, make())
        with pytest.raises(
            RuntimeError,
            match=rf"^Trying to assign the '{role}' role to geometry id \d+ for the first time.*",
        ):
            assign(source, g0, make())

    name = tree.inspector.GetName(geometry_id=g0)
    new_id = sg.RegisterGeometry(
        source_id=source, frame_id=tree.frames[0], geometry=sphere(drake, name)
    )
    for role, make in (
        ("proximity", g.ProximityProperties),
        ("illustration", g.IllustrationProperties),
        ("perception", g.PerceptionProperties),
    ):
        with pytest.raises(
            RuntimeError,
            match=rf"^The name .* has already been used by a geometry with the '{role}' role.$",
        ):
            assign(source, new_id, make())


def test_deactivation_reaches_the_proximity_engine(drake: ModuleType) -> None:
    """DeactivateReachesProximityEngine (Drake v1.56.0+; Deactivate is bound since 1.55):
    deactivating g0 through the model's manager takes its pairs out of the candidates
    and the posed queries of a new context; activating brings them back. (Upstream
    counts the engine's inactive geometries, an internal.) Anchored geometry is left
    alone: deactivating it aborts Drake (known divergence deactivate-anchored-aborts)."""
    g = drake.geometry
    if not hasattr(g.CollisionFilterManager, "Deactivate"):
        pytest.skip("CollisionFilterManager.Deactivate is bound since 1.55 (activation-since-1.55)")
    tree = single_source_tree(drake, "proximity")
    gs = tree.geometries

    def candidates_with_g0() -> set[frozenset[Any]]:
        return {pair(a, b) for a, b in tree.inspector.GetCollisionCandidates() if gs[0] in (a, b)}

    with_g0 = candidates_with_g0()
    assert len(with_g0) == 5  # g2..g5 and the anchored box
    tree.manager.Deactivate(g.GeometrySet(gs[0]))
    assert candidates_with_g0() == set()
    assert tree.inspector.CollisionFiltered(geometry_id1=gs[0], geometry_id2=gs[2])
    assert len(tree.posed_query().ComputePointPairPenetration()) == 2
    tree.manager.Activate(g.GeometrySet(gs[0]))
    assert candidates_with_g0() == with_g0
