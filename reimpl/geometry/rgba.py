"""Rgba: a color, the value type of a visual geometry's ``("phong", "diffuse")`` property.

Drake counterpart: drake/geometry/rgba.h, as bound in ``pydrake.geometry``.
reimpl keeps it because MultibodyPlant.RegisterVisualGeometry stores its
``diffuse_color`` as an Rgba (measured on pydrake 1.51.1: the property's C++
type prints as ``drake::geometry::Rgba``, and an out-of-range color raises
before anything registers). Every channel must lie in [0, 1] (NaN fails):
``Rgba values must be within the range [0, 1]. Values provided: (r=2, g=0, b=0,
a=1)``, the values in fmt's shortest spelling.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import numpy.typing as npt

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl.common.value import register_value_type
from reimpl.geometry._drake_text import shortest

__all__ = ["Rgba"]

_OWNER = "reimpl.geometry.Rgba"
_number = instance_of(int, float)


def _checked(r: float, g: float, b: float, a: float) -> tuple[float, float, float, float]:
    values = (float(r), float(g), float(b), float(a))
    if not all(0.0 <= v <= 1.0 for v in values):
        listed = ", ".join(f"{c}={shortest(v)}" for c, v in zip("rgba", values, strict=True))
        raise RuntimeError(
            f"Rgba values must be within the range [0, 1]. Values provided: ({listed})"
        )
    return values


def _is_vector(value: object) -> bool:
    try:
        return np.asarray(value, dtype=float).ndim == 1
    except (TypeError, ValueError):
        return False


_is_vector.__name__ = "numpy.ndarray[numpy.float64[m, 1]]"


class Rgba:
    """Red, green, blue, alpha, each in [0, 1]; opaque white by default."""

    __slots__ = ("_rgba",)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self._rgba = (1.0, 1.0, 1.0, 1.0)

        def from_values(r: float, g: float, b: float, a: float = 1.0) -> None:
            self._rgba = _checked(r, g, b, a)

        dispatch(
            _OWNER,
            "__init__",
            (
                Overload((), lambda: None),
                Overload(
                    (
                        Param("r", _number),
                        Param("g", _number),
                        Param("b", _number),
                        Param("a", _number, 1.0),
                    ),
                    from_values,
                ),
            ),
            args,
            kwargs,
        )

    def r(self) -> float:
        return self._rgba[0]

    def g(self) -> float:
        return self._rgba[1]

    def b(self) -> float:
        return self._rgba[2]

    def a(self) -> float:
        return self._rgba[3]

    @property
    def rgba(self) -> npt.NDArray[np.float64]:
        """The four values as a vector (a property, as pydrake binds it)."""
        return np.array(self._rgba)

    def set(self, *args: Any, **kwargs: Any) -> None:
        """(r, g, b, a=1), or a vector of 3 or 4 values."""

        def from_values(r: float, g: float, b: float, a: float = 1.0) -> None:
            self._rgba = _checked(r, g, b, a)

        def from_vector(rgba: Any) -> None:
            values = [float(v) for v in np.asarray(rgba, dtype=float).reshape(-1)]
            if len(values) not in (3, 4):
                raise RuntimeError(
                    f"Rgba must contain either 3 or 4 elements (given [{len(values)}])"
                )
            self._rgba = _checked(*values, *([1.0] if len(values) == 3 else []))

        dispatch(
            _OWNER,
            "set",
            (
                Overload(
                    (
                        Param("r", _number),
                        Param("g", _number),
                        Param("b", _number),
                        Param("a", _number, 1.0),
                    ),
                    from_values,
                ),
                Overload((Param("rgba", _is_vector),), from_vector),
            ),
            args,
            kwargs,
        )

    def update(
        self,
        r: float | None = None,
        g: float | None = None,
        b: float | None = None,
        a: float | None = None,
    ) -> None:
        """Replaces the values given; the others stay."""
        given = (r, g, b, a)
        self._rgba = _checked(
            *(old if new is None else new for old, new in zip(self._rgba, given, strict=True))
        )

    def scale_rgb(self, scale: float) -> Rgba:
        """r, g, b times ``scale`` (each clamped to [0, 1]); a unchanged."""
        r, g, b, a = self._rgba
        return Rgba(*(min(max(v * scale, 0.0), 1.0) for v in (r, g, b)), a)

    def __mul__(self, other: Rgba) -> Rgba:
        return Rgba(*(x * y for x, y in zip(self._rgba, other._rgba, strict=True)))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Rgba):
            return NotImplemented
        return self._rgba == other._rgba

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        r, g, b, a = self._rgba
        return f"Rgba(r={r!r}, g={g!r}, b={b!r}, a={a!r})"


register_value_type(Rgba, "drake::geometry::Rgba")
