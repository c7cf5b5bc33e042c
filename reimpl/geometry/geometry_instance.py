"""GeometryFrame and GeometryInstance: what a source hands SceneGraph to register.

As in pydrake, each object draws its id when constructed; registering it
returns that id.
"""

from __future__ import annotations

from reimpl.geometry.geometry_roles import (
    IllustrationProperties,
    PerceptionProperties,
    ProximityProperties,
)
from reimpl.geometry.identifier import FrameId, GeometryId
from reimpl.geometry.shape import Shape
from reimpl.math import RigidTransform

__all__ = ["GeometryFrame", "GeometryInstance", "canonicalize_string_name"]

#: What Drake's CanonicalizeStringName trims from both ends of a geometry name:
#: spaces and tabs only; a newline, vertical tab or form feed stays
#: (drake/geometry/test/utilities_test.cc).
_TRIMMED = " \t"


def canonicalize_string_name(name: str) -> str:
    """A geometry name in canonical form: without leading or trailing spaces and tabs."""
    return name.strip(_TRIMMED)


class GeometryFrame:
    """A frame to register: a name and a frame group."""

    def __init__(self, frame_name: str, frame_group_id: int = 0) -> None:
        if frame_group_id < 0:
            raise RuntimeError("GeometryFrame(): frame_group_id must be non-negative")
        self._id = FrameId.get_new_id()
        self._name = str(frame_name)
        self._frame_group = int(frame_group_id)

    def id(self) -> FrameId:
        return self._id

    def name(self) -> str:
        return self._name

    def frame_group(self) -> int:
        return self._frame_group


class GeometryInstance:
    """A geometry to register: pose in its parent frame, shape, name, role properties."""

    def __init__(self, X_PG: RigidTransform, shape: Shape, name: str) -> None:
        self._id = GeometryId.get_new_id()
        self._pose = RigidTransform(X_PG)
        self._shape = shape
        self.set_name(name)
        self._proximity: ProximityProperties | None = None
        self._illustration: IllustrationProperties | None = None
        self._perception: PerceptionProperties | None = None

    def id(self) -> GeometryId:
        return self._id

    def name(self) -> str:
        return self._name

    def set_name(self, name: str, /) -> None:
        """Keeps the canonical name; one that is empty raises (Drake's message).

        N.B. pydrake binds the parameter without a name (arg0): it is positional only.
        """
        self._name = canonicalize_string_name(str(name))
        if not self._name:
            raise RuntimeError(
                f"GeometryInstance given the name '{name}' which is an empty canonical string"
            )

    def pose(self) -> RigidTransform:
        return RigidTransform(self._pose)

    def set_pose(self, X_PG: RigidTransform) -> None:
        self._pose = RigidTransform(X_PG)

    def shape(self) -> Shape:
        return self._shape

    def proximity_properties(self) -> ProximityProperties | None:
        return self._proximity

    def illustration_properties(self) -> IllustrationProperties | None:
        return self._illustration

    def perception_properties(self) -> PerceptionProperties | None:
        return self._perception

    def mutable_proximity_properties(self) -> ProximityProperties | None:
        return self._proximity

    def mutable_illustration_properties(self) -> IllustrationProperties | None:
        return self._illustration

    def mutable_perception_properties(self) -> PerceptionProperties | None:
        return self._perception

    def set_proximity_properties(self, properties: ProximityProperties) -> None:
        self._proximity = ProximityProperties(properties)

    def set_illustration_properties(self, properties: IllustrationProperties) -> None:
        self._illustration = IllustrationProperties(properties)

    def set_perception_properties(self, properties: PerceptionProperties) -> None:
        self._perception = PerceptionProperties(properties)
