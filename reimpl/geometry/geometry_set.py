"""GeometrySet: the ids a collision filter statement refers to.

A set holds GeometryIds and FrameIds as given. It does not resolve them:
frames become geometries only when a declaration is applied (see
``GeometryState.collect_ids``), so that resolution sees the scene of that
moment. Mirrors drake/geometry/geometry_set.h and its pydrake overloads.
"""

from __future__ import annotations

from typing import Any

from reimpl._overload import Overload, Param, dispatch, instance_of, list_of
from reimpl.geometry.identifier import FrameId, GeometryId

__all__ = ["GeometrySet"]

_OWNER = "reimpl.geometry.GeometrySet"


class GeometrySet:
    """An unresolved union of geometry ids and frame ids.

    >>> from reimpl.geometry import GeometryId
    >>> GeometrySet(geometry_ids=[GeometryId.get_new_id()]).num_geometries()
    1
    """

    __slots__ = ("_frame_ids", "_geometry_ids")

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self._geometry_ids: dict[GeometryId, None] = {}
        self._frame_ids: dict[FrameId, None] = {}
        dispatch(_OWNER, "__init__", self._overloads(), args, kwargs)

    def Add(self, *args: Any, **kwargs: Any) -> None:
        """Adds ids with the same overloads as the constructor (never another set)."""
        overloads = self._overloads()[1:]
        dispatch(_OWNER, "Add", overloads, args, kwargs)

    def _overloads(self) -> tuple[Overload, ...]:
        return (
            Overload((), lambda: None),
            Overload((Param("geometry_id", instance_of(GeometryId)),), self._add_geometry),
            Overload((Param("frame_id", instance_of(FrameId)),), self._add_frame),
            Overload((Param("geometry_ids", list_of(GeometryId)),), self._add_geometries),
            Overload((Param("frame_ids", list_of(FrameId)),), self._add_frames),
            Overload(
                (
                    Param("geometry_ids", list_of(GeometryId)),
                    Param("frame_ids", list_of(FrameId)),
                ),
                self._add_both,
            ),
        )

    def _add_geometry(self, geometry_id: GeometryId) -> None:
        self._geometry_ids[geometry_id] = None

    def _add_frame(self, frame_id: FrameId) -> None:
        self._frame_ids[frame_id] = None

    def _add_geometries(self, geometry_ids: list[GeometryId]) -> None:
        self._geometry_ids.update(dict.fromkeys(geometry_ids))

    def _add_frames(self, frame_ids: list[FrameId]) -> None:
        self._frame_ids.update(dict.fromkeys(frame_ids))

    def _add_both(self, geometry_ids: list[GeometryId], frame_ids: list[FrameId]) -> None:
        self._add_geometries(geometry_ids)
        self._add_frames(frame_ids)

    # reimpl-only accessors (pydrake binds none); PEP 8 names mark them as ours.
    def geometry_ids(self) -> tuple[GeometryId, ...]:
        return tuple(self._geometry_ids)

    def frame_ids(self) -> tuple[FrameId, ...]:
        return tuple(self._frame_ids)

    def num_geometries(self) -> int:
        return len(self._geometry_ids)

    def num_frames(self) -> int:
        return len(self._frame_ids)

    def __copy__(self) -> GeometrySet:
        copy = GeometrySet()
        copy._geometry_ids = dict(self._geometry_ids)
        copy._frame_ids = dict(self._frame_ids)
        return copy
