"""A SceneGraph of named proximity shapes at fixed world poses, and its QueryObject.

Drake's callback tests call the FCL callback on two collision objects with a pose map;
pydrake binds neither, so these ports pose the same shapes in a SceneGraph and ask its
QueryObject. Which argument order FCL hands the callback is the broadphase's choice;
``Layout`` varies it through public means: both shapes on frames of their own (the
dynamic tree), or one of them anchored (then FCL pairs the dynamic one with the
anchored one, in that order).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum
from types import ModuleType
from typing import Any

__all__ = ["Layout", "PosedScene"]


class Layout(Enum):
    """Which of two shapes, if any, is anchored."""

    BOTH_DYNAMIC = "both dynamic"
    FIRST_ANCHORED = "first anchored"
    SECOND_ANCHORED = "second anchored"

    def anchors(self, index: int) -> bool:
        return (self, index) in {(Layout.FIRST_ANCHORED, 0), (Layout.SECOND_ANCHORED, 1)}


@dataclass
class PosedScene:
    """Shapes registered in order (so their ids increase), each at its world pose."""

    drake: ModuleType
    layout: Layout = Layout.BOTH_DYNAMIC
    scene_graph: Any = field(init=False)
    source: Any = field(init=False)
    ids: dict[str, Any] = field(init=False, default_factory=dict)
    _poses: dict[Any, Any] = field(init=False, default_factory=dict)
    _context: Any = field(init=False, default=None)

    def __post_init__(self) -> None:
        self.scene_graph = self.drake.geometry.SceneGraph_[float]()
        self.source = self.scene_graph.RegisterSource("callback_test")

    def add(self, name: str, shape: Any, X_WG: Any) -> Any:
        """Registers ``shape`` (proximity role) at ``X_WG``; returns its id."""
        g, sg = self.drake.geometry, self.scene_graph
        identity = self.drake.math.RigidTransform_[float]()
        if self.layout.anchors(len(self.ids)):
            instance = g.GeometryInstance(X_PG=X_WG, shape=shape, name=name)
            geometry_id = sg.RegisterAnchoredGeometry(source_id=self.source, geometry=instance)
        else:
            frame_id = sg.RegisterFrame(source_id=self.source, frame=g.GeometryFrame(name))
            instance = g.GeometryInstance(X_PG=identity, shape=shape, name=name)
            geometry_id = sg.RegisterGeometry(
                source_id=self.source, frame_id=frame_id, geometry=instance
            )
            self._poses[frame_id] = X_WG
        sg.AssignRole(
            source_id=self.source, geometry_id=geometry_id, properties=g.ProximityProperties()
        )
        self.ids[name] = geometry_id
        return geometry_id

    def exclude_within(self, *names: str) -> None:
        """Filters every pair among ``names`` (CollisionFilterDeclaration.ExcludeWithin)."""
        g = self.drake.geometry
        members = g.GeometrySet(geometry_ids=[self.ids[n] for n in names])
        self.scene_graph.collision_filter_manager().Apply(
            declaration=g.CollisionFilterDeclaration().ExcludeWithin(geometry_set=members)
        )

    def query_object(self) -> Any:
        """The QueryObject of a context whose frames sit at their poses (the scene keeps the
        context alive: a QueryObject refers to it)."""
        self._context = context = self.scene_graph.CreateDefaultContext()
        poses = self.drake.geometry.FramePoseVector()
        for frame_id, X_WF in self._poses.items():
            poses.set_value(id=frame_id, value=X_WF)
        self.scene_graph.get_source_pose_port(self.source).FixValue(context, poses)
        return self.scene_graph.get_query_output_port().Eval(context)
