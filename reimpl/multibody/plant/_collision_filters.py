"""The collision filters a plant declares on its SceneGraph.

Drake counterpart: MultibodyPlant's default collision filters
(ApplyDefaultCollisionFilters, drake-semantics.md §5) and the parser's
ExcludeCollisionGeometriesWithCollisionFilterGroupPair. C is the set of
candidate pairs (g, h); F(B) is body B's SceneGraph frame, F(world) the
world frame, which resolves to every anchored proximity geometry.

At Finalize (see reimpl.multibody._default_filters), when the plant is a
SceneGraph source, with scope kOmitDeformable:

(a) adjacent bodies, unless ``set_adjacent_bodies_collision_filters(False)``
    (before Finalize): for every joint J whose parent is not the world and
    whose type is not quaternion_floating,

        C ← C − {(g, h) : frame(g) = F(child(J)), frame(h) = F(parent(J))}

(b) welded subgraphs, always: for every set S of bodies joined by welds
    (the world's set included, so bodies welded to the world are filtered
    against all anchored geometry) with |S| > 1,

        C ← C − {(g, h) : frame(g), frame(h) ∈ F(S), g ≠ h}

A collision filter group pair of the parser (before Finalize, on a source;
scope kAll): the same group twice,

        C ← C − {(g, h) : g, h ∈ set_A, g ≠ h}

else C ← C − {(g, h) : g ∈ set_A, h ∈ set_B}.
"""

from __future__ import annotations

from reimpl._release import release
from reimpl.geometry.collision_filter_declaration import (
    CollisionFilterDeclaration,
    CollisionFilterScope,
)
from reimpl.geometry.geometry_set import GeometrySet
from reimpl.multibody import _link_joint_graph as graph
from reimpl.multibody._default_filters import default_collision_filters
from reimpl.multibody.plant._demands import demand_failed
from reimpl.multibody.plant._scene_graph_source import SceneGraphSource
from reimpl.multibody.plant._topology import Topology

__all__ = ["CollisionFilters"]


class CollisionFilters(SceneGraphSource, Topology):
    """Finalize's default filters (and their one setting), and group pairs."""

    def __init__(self) -> None:
        super().__init__()
        self._adjacent_bodies_collision_filters = True

    @release.binding("adjacent-filters-opt-out-since-1.13")
    def set_adjacent_bodies_collision_filters(self, value: bool) -> None:
        """Whether Finalize filters adjacent bodies (rule (a)); welds are filtered anyway."""
        self._check_not_finalized("set_adjacent_bodies_collision_filters")
        self._adjacent_bodies_collision_filters = bool(value)

    @release.binding("adjacent-filters-opt-out-since-1.13")
    def get_adjacent_bodies_collision_filters(self) -> bool:
        return self._adjacent_bodies_collision_filters

    def _apply_default_collision_filters(self) -> None:
        """Rules (a) and (b), in one declaration, when the plant is a SceneGraph source.

        Drake asks SceneGraph for a manager once per statement, and handing out a
        manager changes the model's proximity version (geometry_version.py), so a
        plant with no statement to make (no joint between two non-world bodies, no
        welded subgraph of two bodies or more) asks for none: measured on pydrake
        1.51.1 and 1.58.0, Finalize of an empty plant or of one free body leaves
        the proximity version alone, and of two jointed bodies changes it.
        """
        if self._scene_graph is not None:
            declaration = default_collision_filters(
                self._joints,
                graph.welded_subgraphs(len(self._bodies), self._edges()),
                self._collect,
                adjacent=self._adjacent_bodies_collision_filters,
            )
            if declaration.statements():
                self._scene_graph.collision_filter_manager().Apply(declaration=declaration)

    def _exclude_collision_geometries_with_collision_filter_group_pair(
        self, group_a: tuple[str, GeometrySet], group_b: tuple[str, GeometrySet]
    ) -> None:
        """A collision filter group pair, for the parser (C++ only; pydrake binds none).

        Same name: C ← C − {(g, h) : g, h ∈ set_A, g ≠ h} (ExcludeWithin);
        else C ← C − {(g, h) : g ∈ set_A, h ∈ set_B} (ExcludeBetween). Scope
        kAll, applied to the SceneGraph model; allowed only before Finalize
        and with a registered SceneGraph (Drake demands both).
        """
        method = "ExcludeCollisionGeometriesWithCollisionFilterGroupPair"
        if self._finalized:
            raise demand_failed(method, "!is_finalized()")
        scene_graph, _ = self._registered_scene_graph(method)
        (name_a, set_A), (name_b, set_B) = group_a, group_b
        declaration = CollisionFilterDeclaration._scoped(CollisionFilterScope.kAll)
        if name_a == name_b:
            declaration.ExcludeWithin(set_A)
        else:
            declaration.ExcludeBetween(set_A, set_B)
        scene_graph.collision_filter_manager().Apply(declaration=declaration)
