"""Shape specifications (drake/geometry/shape_specification.h).

Filtering never looks at a shape; these exist so that scripts construct the
same objects and print them as pydrake does.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["Box", "Capsule", "Cylinder", "Ellipsoid", "HalfSpace", "Shape", "Sphere"]


def _require_positive(owner: str, **measures: float) -> None:
    for name, value in measures.items():
        if not (math.isfinite(value) and value > 0):
            raise RuntimeError(f"{owner}(): {name} = {value} is not finite positive")


def _fmt(value: float) -> str:
    """As pydrake prints a measure: integral values without a point, others round-trip."""
    return str(int(value)) if value.is_integer() else repr(value)


class Shape:
    """Base of all shapes."""

    _fields: tuple[str, ...] = ()

    def __repr__(self) -> str:
        args = ", ".join(f"{f}={_fmt(getattr(self, '_' + f))}" for f in self._fields)
        return f"{type(self).__name__}({args})"

    def Clone(self) -> Shape:
        clone = object.__new__(type(self))
        clone.__dict__.update(self.__dict__)
        return clone


class Sphere(Shape):
    _fields = ("radius",)

    def __init__(self, radius: float) -> None:
        if not (math.isfinite(radius) and radius >= 0):
            raise RuntimeError(f"Sphere(): radius = {radius} is not finite non-negative")
        self._radius = float(radius)

    def radius(self) -> float:
        return self._radius


class Box(Shape):
    _fields = ("width", "depth", "height")

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        if len(args) + len(kwargs) == 1:
            measures = np.asarray(next(iter([*args, *kwargs.values()])), dtype=float)
            width, depth, height = (float(x) for x in measures.reshape(3))
        else:
            values = dict(zip(("width", "depth", "height"), args, strict=False)) | kwargs
            width, depth, height = (float(values[k]) for k in ("width", "depth", "height"))
        _require_positive("Box", width=width, depth=depth, height=height)
        self._width, self._depth, self._height = width, depth, height

    @staticmethod
    def MakeCube(edge_size: float) -> Box:
        return Box(edge_size, edge_size, edge_size)

    def width(self) -> float:
        return self._width

    def depth(self) -> float:
        return self._depth

    def height(self) -> float:
        return self._height

    def size(self) -> np.ndarray[Any, np.dtype[np.float64]]:
        return np.array([self._width, self._depth, self._height])


class _RadiusLength(Shape):
    _fields = ("radius", "length")

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        if len(args) + len(kwargs) == 1:
            measures = np.asarray(next(iter([*args, *kwargs.values()])), dtype=float)
            radius, length = (float(x) for x in measures.reshape(2))
        else:
            values = dict(zip(("radius", "length"), args, strict=False)) | kwargs
            radius, length = float(values["radius"]), float(values["length"])
        _require_positive(type(self).__name__, radius=radius, length=length)
        self._radius, self._length = radius, length

    def radius(self) -> float:
        return self._radius

    def length(self) -> float:
        return self._length


class Cylinder(_RadiusLength):
    pass


class Capsule(_RadiusLength):
    pass


class Ellipsoid(Shape):
    _fields = ("a", "b", "c")

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        if len(args) + len(kwargs) == 1:
            measures = np.asarray(next(iter([*args, *kwargs.values()])), dtype=float)
            a, b, c = (float(x) for x in measures.reshape(3))
        else:
            values = dict(zip(("a", "b", "c"), args, strict=False)) | kwargs
            a, b, c = (float(values[k]) for k in ("a", "b", "c"))
        _require_positive("Ellipsoid", a=a, b=b, c=c)
        self._a, self._b, self._c = a, b, c

    def a(self) -> float:
        return self._a

    def b(self) -> float:
        return self._b

    def c(self) -> float:
        return self._c


class HalfSpace(Shape):
    pass
