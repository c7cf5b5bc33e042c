"""QueryObject and FramePoseVector: the query port's value and the pose port's input.

Only the inspector is served: reimpl answers which pairs are candidates, not
where geometry is.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from reimpl._template import scalar_template
from reimpl.common.value import register_value_type
from reimpl.geometry.identifier import FrameId
from reimpl.geometry.scene_graph_inspector import SceneGraphInspector
from reimpl.math import RigidTransform

if TYPE_CHECKING:
    from reimpl.geometry.geometry_state import GeometryState

__all__ = ["FramePoseVector", "FramePoseVector_", "QueryObject", "QueryObject_"]


class QueryObject:
    """What SceneGraph's query output port evaluates to for one context."""

    def __init__(self) -> None:
        """A default QueryObject is not connected to any state; its inspector cannot answer."""

        def unconnected() -> GeometryState:
            # N.B. pydrake 1.51.1 aborts the process here; reimpl raises instead.
            raise RuntimeError("condition 'state_ != nullptr' failed.")

        self._state_of = unconnected

    _state_of: Callable[[], GeometryState]

    @classmethod
    def _make(cls, state_of: Callable[[], GeometryState]) -> QueryObject:
        query = object.__new__(cls)
        query._state_of = state_of
        return query

    def inspector(self) -> SceneGraphInspector:
        """A live inspector of the context this object was evaluated on."""
        return SceneGraphInspector._view(self._state_of)


class FramePoseVector:
    """Poses of a source's frames, keyed by FrameId."""

    def __init__(self) -> None:
        self._poses: dict[FrameId, RigidTransform] = {}

    def set_value(self, id: FrameId, value: RigidTransform) -> None:
        self._poses[id] = RigidTransform(value)

    def value(self, id: FrameId) -> RigidTransform:
        return RigidTransform(self._poses[id])

    def has_id(self, id: FrameId) -> bool:
        return id in self._poses

    def ids(self) -> list[FrameId]:
        return list(self._poses)

    def size(self) -> int:
        return len(self._poses)

    def clear(self) -> None:
        self._poses.clear()


FramePoseVector_ = scalar_template("reimpl.geometry", "FramePoseVector_", FramePoseVector)
QueryObject_ = scalar_template("reimpl.geometry", "QueryObject_", QueryObject)
register_value_type(
    FramePoseVector,
    "drake::geometry::KinematicsVector<drake::geometry::FrameId,drake::math::RigidTransform<double>>",
)
register_value_type(QueryObject, "drake::geometry::QueryObject<double>")
