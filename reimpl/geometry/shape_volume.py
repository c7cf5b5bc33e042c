"""CalcVolume(shape) (drake/geometry/shape_specification.cc), one formula per shape.

Each formula is Drake's, in Drake's operation order, so the volumes equal
pydrake's bit for bit (measured on 1.51.1): a HalfSpace is infinite. The
volume of a Mesh or Convex needs the mesh file's contents, which reimpl does
not read: CalcVolume raises NotImplementedError for them rather than guess.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl.geometry.mesh import Convex, Mesh
from reimpl.geometry.shape import (
    Box,
    Capsule,
    Cylinder,
    Ellipsoid,
    HalfSpace,
    MeshcatCone,
    Shape,
    Sphere,
)

__all__ = ["CalcVolume"]


def _mesh_volume(shape: Mesh | Convex) -> float:
    raise NotImplementedError(
        f"CalcVolume({type(shape).__name__}) needs the contents of "
        f"{shape.source().description()!r}; reimpl does not read mesh files"
    )


_VOLUME: dict[type[Shape], Callable[[Any], float]] = {
    Box: lambda s: s.width() * s.depth() * s.height(),
    Capsule: lambda s: (
        math.pi * s.radius() ** 2 * s.length() + 4.0 / 3.0 * math.pi * s.radius() ** 3
    ),
    Convex: _mesh_volume,
    Cylinder: lambda s: math.pi * s.radius() ** 2 * s.length(),
    Ellipsoid: lambda s: 4.0 / 3.0 * math.pi * s.a() * s.b() * s.c(),
    HalfSpace: lambda s: math.inf,
    Mesh: _mesh_volume,
    MeshcatCone: lambda s: 1.0 / 3.0 * math.pi * s.a() * s.b() * s.height(),
    Sphere: lambda s: 4.0 / 3.0 * math.pi * s.radius() ** 3,
}


def CalcVolume(*args: Any, **kwargs: Any) -> float:
    """The volume of ``shape`` in m³."""

    def volume(shape: Shape) -> float:
        kind = next(cls for cls in type(shape).__mro__ if cls in _VOLUME)
        return _VOLUME[kind](shape)

    overload = Overload((Param("shape", instance_of(Shape)),), volume)
    return dispatch("reimpl.geometry", "CalcVolume", (overload,), args, kwargs)  # type: ignore[no-any-return]
