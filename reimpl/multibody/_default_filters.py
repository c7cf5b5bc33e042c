"""The collision filters MultibodyPlant declares at Finalize.

Drake counterpart: MultibodyPlant's ApplyDefaultCollisionFilters
(drake-semantics.md §5). F(B) is body B's SceneGraph frame; F(world) is the
world frame, which resolves to every anchored proximity geometry of every
source. Both rules are persistent Exclude statements on the SceneGraph model,
with scope kOmitDeformable, made only by a plant registered as a SceneGraph
source.

(a) Adjacent bodies, unless ``set_adjacent_bodies_collision_filters(False)``:
    for every joint J (those Finalize added included) with parent(J) ≠ world
    whose type ADJACENCY_RULE filters,

        C ← C − {(g, h) : frame(g) = F(child(J)), frame(h) = F(parent(J))}

    N.B. Only a world *parent* is skipped: a joint from B to a world child
    filters B against all anchored geometry.

(b) Welded subgraphs, always: for every set S of bodies joined by welds
    (the world's set included) with |S| > 1,

        C ← C − {(g, h) : frame(g), frame(h) ∈ F(S), g ≠ h}

    so bodies welded to the world are filtered against all anchored
    geometry, from every source, that has the proximity role now.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from types import MappingProxyType

from reimpl.geometry.collision_filter_declaration import (
    CollisionFilterDeclaration,
    CollisionFilterScope,
)
from reimpl.geometry.geometry_set import GeometrySet
from reimpl.multibody._link_joint_graph import WORLD
from reimpl.multibody.tree import Joint

__all__ = ["ADJACENCY_RULE", "default_collision_filters"]

#: Rule (a) by joint type: does a joint of this type filter its two bodies?
#: Measured on pydrake 1.51.1 (pydrake-observed.md §3; checklist 22). Drake
#: documents "except 6-dof joints", but tests the type, not the dofs.
ADJACENCY_RULE: Mapping[str, bool] = MappingProxyType(
    {
        "weld": True,
        "revolute": True,
        "prismatic": True,
        "screw": True,
        "universal": True,
        "ball_rpy": True,
        "curvilinear": True,
        "planar": True,
        "rpy_floating": True,  # 6 dofs, yet filtered
        "quaternion_floating": False,  # the one type skipped
    }
)


def adjacent_body_pairs(joints: Iterable[Joint]) -> list[tuple[int, int]]:
    """Rule (a) as (child, parent) body indices, in joint order."""
    return [
        (int(joint.child_body().index()), int(joint.parent_body().index()))
        for joint in joints
        if int(joint.parent_body().index()) != WORLD and ADJACENCY_RULE[joint.type_name()]
    ]


def default_collision_filters(
    joints: Sequence[Joint],
    welded: Sequence[Sequence[int]],
    collect: Callable[[Sequence[int]], GeometrySet],
    *,
    adjacent: bool,
) -> CollisionFilterDeclaration:
    """One declaration with rule (a) (when ``adjacent``) and rule (b).

    ``welded`` are the weld subgraphs (body indices); ``collect`` is the
    plant's CollectRegisteredGeometries over body indices: {F(B) : B ∈ S}.
    The statements only exclude, so their order does not matter.
    """
    declaration = CollisionFilterDeclaration._scoped(CollisionFilterScope.kOmitDeformable)
    if adjacent:
        for child, parent in adjacent_body_pairs(joints):
            declaration.ExcludeBetween(collect([child]), collect([parent]))
    for bodies in welded:
        if len(bodies) > 1:
            declaration.ExcludeWithin(collect(bodies))
    return declaration
