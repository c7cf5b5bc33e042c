"""Shape specifications (drake/geometry/shape_specification.h), as pydrake 1.51.1 measures them.

Filtering never looks at a shape; these exist so that scripts construct, copy,
print and pickle the same objects as with pydrake:

* Constructors take the measures positionally, by keyword, or (all but Sphere)
  as one ``measures=`` vector; MeshcatCone's ``a`` and ``b`` default to 1.
* An invalid measure raises ``SystemExit`` with Drake's DRAKE_THROW_UNLESS text
  (see ``_shape_checks``): non-finite or non-positive for all, negative for
  Sphere (radius 0 is valid).
* ``repr`` prints each measure in shortest round-trip form without a trailing
  ``.0`` (``Box(width=0.1, depth=0.2, height=0.30000000000000004)``), so
  ``eval(repr(shape))`` rebuilds it. ``Clone()``, ``copy.copy`` and
  ``copy.deepcopy`` make a new object of the same class.
* Pickling stores the measures (a float for Sphere, a tuple otherwise);
  HalfSpace cannot be pickled, as in pydrake.
* ``Box.size()`` is read-only up to 1.57 and a writeable copy since 1.58
  (release fact box-size-writeable-since-1.58; measured on 1.51.1, 1.52.0-1.58.0).
  pydrake has no ``Box.MakeCube``, so neither has reimpl.

Mesh and Convex are in ``reimpl.geometry.mesh``; CalcVolume in
``reimpl.geometry.shape_volume``.
"""

from __future__ import annotations

from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt

from reimpl._overload import REQUIRED, Overload, Param, dispatch
from reimpl._release import release
from reimpl.common._pybind_text import no_constructor
from reimpl.geometry._drake_text import shortest
from reimpl.geometry._half_space_pose import make_pose_columns
from reimpl.geometry._shape_args import is_float, is_vector
from reimpl.geometry._shape_checks import measure_names, require
from reimpl.math import RigidTransform, RotationMatrix

__all__ = [
    "Box",
    "Capsule",
    "Cylinder",
    "Ellipsoid",
    "HalfSpace",
    "MeshcatCone",
    "Shape",
    "Sphere",
]


class Shape:
    """Base of all shapes; pydrake gives it no constructor."""

    __slots__ = ()

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        raise no_constructor("reimpl.geometry.Shape")

    def Clone(self) -> Shape:
        clone = object.__new__(type(self))
        for cls in type(self).__mro__:
            for slot in cls.__dict__.get("__slots__", ()):
                object.__setattr__(clone, slot, getattr(self, slot))
        return clone

    def __copy__(self) -> Shape:
        return self.Clone()

    def __deepcopy__(self, memo: dict[int, Any]) -> Shape:
        return self.Clone()


class _Primitive(Shape):
    """A shape given by a few named measures, validated and printed alike."""

    __slots__ = ("_measures",)
    _measures: tuple[float, ...]
    #: Defaults of trailing measures (MeshcatCone's a and b).
    _defaults: ClassVar[dict[str, float]] = {}

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        names = measure_names(type(self).__name__)
        scalars = tuple(Param(n, is_float, self._defaults.get(n, REQUIRED)) for n in names)
        overloads = [Overload(scalars, lambda **values: self._set(*(values[n] for n in names)))]
        if len(names) > 1:
            vector = Param("measures", is_vector(len(names)))
            overloads.append(Overload((vector,), self._set_vector))
        dispatch(f"reimpl.geometry.{type(self).__name__}", "__init__", overloads, args, kwargs)

    def _set_vector(self, measures: Any) -> None:
        self._set(*np.asarray(measures, dtype=float).reshape(-1))

    def _set(self, *values: Any) -> None:
        measures = tuple(float(v) for v in values)
        owner = type(self).__name__
        for name, value in zip(measure_names(owner), measures, strict=True):
            require(owner, name, value)
        self._measures = measures

    def __repr__(self) -> str:
        names = measure_names(type(self).__name__)
        args = ", ".join(f"{n}={shortest(v)}" for n, v in zip(names, self._measures, strict=True))
        return f"{type(self).__name__}({args})"

    def __getstate__(self) -> float | tuple[float, ...]:
        return self._measures[0] if len(self._measures) == 1 else self._measures

    def __setstate__(self, state: float | tuple[float, ...]) -> None:
        self._set(*(state if isinstance(state, tuple) else (state,)))


class Sphere(_Primitive):
    __slots__ = ()

    def radius(self) -> float:
        return self._measures[0]


class Box(_Primitive):
    __slots__ = ()

    def width(self) -> float:
        return self._measures[0]

    def depth(self) -> float:
        return self._measures[1]

    def height(self) -> float:
        return self._measures[2]

    def size(self) -> npt.NDArray[np.float64]:
        size = np.array(self._measures)
        size.flags.writeable = release.has("box-size-writeable-since-1.58")
        return size


class Capsule(_Primitive):
    __slots__ = ()

    def radius(self) -> float:
        return self._measures[0]

    def length(self) -> float:
        return self._measures[1]


class Cylinder(_Primitive):
    __slots__ = ()

    def radius(self) -> float:
        return self._measures[0]

    def length(self) -> float:
        return self._measures[1]


class Ellipsoid(_Primitive):
    __slots__ = ()

    def a(self) -> float:
        return self._measures[0]

    def b(self) -> float:
        return self._measures[1]

    def c(self) -> float:
        return self._measures[2]


class MeshcatCone(_Primitive):
    """An elliptic cone: apex at the origin, base at z = height with semi-axes a and b."""

    __slots__ = ()
    _defaults: ClassVar[dict[str, float]] = {"a": 1.0, "b": 1.0}

    def height(self) -> float:
        return self._measures[0]

    def a(self) -> float:
        return self._measures[1]

    def b(self) -> float:
        return self._measures[2]


class HalfSpace(Shape):
    """The half space z ≤ 0 of its canonical frame."""

    __slots__ = ()

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        dispatch(
            "reimpl.geometry.HalfSpace", "__init__", (Overload((), lambda: None),), args, kwargs
        )

    def __repr__(self) -> str:
        return "HalfSpace()"

    def __reduce_ex__(self, protocol: Any) -> Any:
        raise TypeError("cannot pickle 'reimpl.geometry.HalfSpace' object")

    @staticmethod
    def MakePose(*args: Any, **kwargs: Any) -> RigidTransform:
        """X_FH of the half space whose outward normal is ``Hz_dir_F``, through ``p_FB``."""

        def make(Hz_dir_F: Any, p_FB: Any) -> RigidTransform:
            columns, p_FH = make_pose_columns(
                np.asarray(Hz_dir_F, dtype=float).reshape(3).tolist(),
                np.asarray(p_FB, dtype=float).reshape(3).tolist(),
            )
            return RigidTransform(RotationMatrix(np.array(columns).T), np.array(p_FH))

        params = (Param("Hz_dir_F", is_vector(3)), Param("p_FB", is_vector(3)))
        return dispatch(  # type: ignore[no-any-return]
            "reimpl.geometry.HalfSpace", "MakePose", (Overload(params, make),), args, kwargs
        )
