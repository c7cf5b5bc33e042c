"""Shared setup for the ported geometry filter tests: a SceneGraph and what it filters.

Drake's geometry tests observe collision filters through internals (GeometryState,
CollisionFilter, ProximityEngine, the statements of a CollisionFilterDeclaration);
pydrake binds none of them. The ported tests observe the same facts through the public
API instead: ``SceneGraphInspector.CollisionFiltered`` and ``GetCollisionCandidates``.
``Scene`` holds a SceneGraph, its source and the ids the tests register.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from itertools import combinations
from types import ModuleType
from typing import Any

__all__ = ["Scene", "all_pairs", "filtered_pairs", "pair", "sphere"]


def sphere(drake: ModuleType, name: str, radius: float = 1.0) -> Any:
    """A GeometryInstance of a sphere at the identity pose."""
    g = drake.geometry
    return g.GeometryInstance(
        X_PG=drake.math.RigidTransform_[float](), shape=g.Sphere(radius), name=name
    )


def pair(a: Any, b: Any) -> frozenset[Any]:
    """An unordered pair of ids."""
    return frozenset((a, b))


def filtered_pairs(inspector: Any, ids: Sequence[Any]) -> set[frozenset[Any]]:
    """{(a, b) : a, b ∈ ids, a ≠ b, CollisionFiltered(a, b)}, each pair asked both ways.

    Drake's tests ask both orders (``ExpectCanCollide``); a pair whose answer depends on
    the order raises AssertionError.
    """
    found = set()
    for a, b in combinations(ids, 2):
        forward = inspector.CollisionFiltered(geometry_id1=a, geometry_id2=b)
        backward = inspector.CollisionFiltered(geometry_id1=b, geometry_id2=a)
        assert forward == backward, f"the filter state of ({a}, {b}) depends on the order"
        if forward:
            found.add(pair(a, b))
    return found


@dataclass
class Scene:
    """A SceneGraph with one source, and helpers to register proximity geometry."""

    drake: ModuleType
    scene_graph: Any = None
    source: Any = None
    frames: list[Any] = field(default_factory=list)
    source_name: str = "source"

    def __post_init__(self) -> None:
        if self.scene_graph is None:
            self.scene_graph = self.drake.geometry.SceneGraph_[float]()
        if self.source is None:
            self.source = self.scene_graph.RegisterSource(self.source_name)

    @property
    def g(self) -> ModuleType:
        return self.drake.geometry

    def frame(self, name: str | None = None, parent: Any = None) -> Any:
        """Registers a dynamic frame (on the world frame unless ``parent``)."""
        name = name or f"frame_{len(self.frames)}"
        frame = self.g.GeometryFrame(name)
        if parent is None:
            frame_id = self.scene_graph.RegisterFrame(source_id=self.source, frame=frame)
        else:
            frame_id = self.scene_graph.RegisterFrame(
                source_id=self.source, parent_id=parent, frame=frame
            )
        self.frames.append(frame_id)
        return frame_id

    def geometry(self, frame_id: Any, name: str, proximity: bool = True) -> Any:
        """Registers a unit sphere on ``frame_id``; with the proximity role unless told."""
        geometry_id = self.scene_graph.RegisterGeometry(
            source_id=self.source, frame_id=frame_id, geometry=sphere(self.drake, name)
        )
        if proximity:
            self.proximity(geometry_id)
        return geometry_id

    def anchored(self, name: str, proximity: bool = True) -> Any:
        """Registers an anchored unit sphere; with the proximity role unless told."""
        geometry_id = self.scene_graph.RegisterAnchoredGeometry(
            source_id=self.source, geometry=sphere(self.drake, name)
        )
        if proximity:
            self.proximity(geometry_id)
        return geometry_id

    def proximity(self, geometry_id: Any, context: Any = None) -> None:
        """Assigns the proximity role (in ``context`` if given, else in the model)."""
        kwargs: dict[str, Any] = dict(
            source_id=self.source, geometry_id=geometry_id, properties=self.g.ProximityProperties()
        )
        if context is not None:
            kwargs["context"] = context
        self.scene_graph.AssignRole(**kwargs)

    def spheres_on_own_frames(self, count: int, prefix: str = "sphere") -> list[Any]:
        """``count`` proximity spheres, each on a dynamic frame of its own."""
        return [self.geometry(self.frame(), f"{prefix}_{i}") for i in range(count)]

    def context(self) -> Any:
        return self.scene_graph.CreateDefaultContext()

    def query_object(self, context: Any) -> Any:
        return self.scene_graph.get_query_output_port().Eval(context)

    def context_inspector(self, context: Any) -> Any:
        """The inspector of ``context``'s geometry data (a live view)."""
        return self.query_object(context).inspector()

    @property
    def model_inspector(self) -> Any:
        return self.scene_graph.model_inspector()

    def candidates(self, inspector: Any) -> set[frozenset[Any]]:
        """GetCollisionCandidates() as a set of unordered pairs."""
        return {pair(a, b) for a, b in inspector.GetCollisionCandidates()}


def all_pairs(ids: Iterable[Any]) -> set[frozenset[Any]]:
    """Every unordered pair of distinct ids."""
    return {pair(a, b) for a, b in combinations(list(ids), 2)}
