"""GeometrySet: the ids a collision filter statement refers to.

A set holds GeometryIds and FrameIds as given. It does not resolve them:
frames become geometries only when a declaration is applied (see
``GeometryState.collect_ids``), so that resolution sees the scene of that
moment. Mirrors drake/geometry/geometry_set.h and its pydrake overloads.
"""

from __future__ import annotations

from typing import Any

from reimpl._overload import Overload, Param, dispatch, instance_of, list_of
from reimpl.common._pybind_text import cannot_pickle
from reimpl.geometry.identifier import FrameId, GeometryId

__all__ = ["GeometrySet"]

_OWNER = "reimpl.geometry.GeometrySet"


def _ids(
    geometry_ids: tuple[GeometryId, ...] | list[GeometryId] = (),
    frame_ids: tuple[FrameId, ...] | list[FrameId] = (),
) -> tuple[tuple[GeometryId, ...] | list[GeometryId], tuple[FrameId, ...] | list[FrameId]]:
    return geometry_ids, frame_ids


#: The constructor's overloads, in pydrake's order; each gives (geometry ids, frame ids).
_OVERLOADS = (
    Overload((), _ids),
    Overload(
        (Param("geometry_id", instance_of(GeometryId)),),
        lambda geometry_id: ((geometry_id,), ()),
    ),
    Overload((Param("frame_id", instance_of(FrameId)),), lambda frame_id: ((), (frame_id,))),
    Overload((Param("geometry_ids", list_of(GeometryId)),), _ids),
    Overload((Param("frame_ids", list_of(FrameId)),), _ids),
    Overload(
        (Param("geometry_ids", list_of(GeometryId)), Param("frame_ids", list_of(FrameId))),
        _ids,
    ),
)


class GeometrySet:
    """An unresolved union of geometry ids and frame ids.

    >>> from reimpl.geometry import GeometryId
    >>> GeometrySet(geometry_ids=[GeometryId.get_new_id()]).num_geometries()
    1
    """

    __slots__ = ("_frame_ids", "_geometry_ids")

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        geometry_ids, frame_ids = dispatch(_OWNER, "__init__", _OVERLOADS, args, kwargs)
        self._geometry_ids: dict[GeometryId, None] = dict.fromkeys(geometry_ids)
        self._frame_ids: dict[FrameId, None] = dict.fromkeys(frame_ids)

    def Add(self, *args: Any, **kwargs: Any) -> None:
        """Adds ids with the same overloads as the constructor (never another set)."""
        geometry_ids, frame_ids = dispatch(_OWNER, "Add", _OVERLOADS[1:], args, kwargs)
        self._geometry_ids.update(dict.fromkeys(geometry_ids))
        self._frame_ids.update(dict.fromkeys(frame_ids))

    # reimpl-only accessors (pydrake binds none); PEP 8 names mark them as ours.
    def geometry_ids(self) -> tuple[GeometryId, ...]:
        return tuple(self._geometry_ids)

    def frame_ids(self) -> tuple[FrameId, ...]:
        return tuple(self._frame_ids)

    def num_geometries(self) -> int:
        return len(self._geometry_ids)

    def num_frames(self) -> int:
        return len(self._frame_ids)

    def _copy(self) -> GeometrySet:
        """A copy for reimpl's own use (a declaration keeps copies of its sets)."""
        copy = object.__new__(GeometrySet)
        copy._geometry_ids = dict(self._geometry_ids)
        copy._frame_ids = dict(self._frame_ids)
        return copy

    def __reduce__(self) -> Any:
        raise cannot_pickle(_OWNER)
