"""Argument checks for the shape constructors, named as pybind11 names the C++ types."""

from __future__ import annotations

import os
from collections.abc import Callable

import numpy as np

__all__ = ["is_float", "is_path_like", "is_vector", "path_text"]


def is_float(value: object) -> bool:
    """pybind11's ``float`` caster: anything with ``__float__`` or ``__index__`` (bool too)."""
    if isinstance(value, str | bytes) or (isinstance(value, np.ndarray) and value.ndim > 0):
        return False
    return hasattr(type(value), "__float__") or hasattr(type(value), "__index__")


is_float.__name__ = "float"


def is_vector(size: int) -> Callable[[object], bool]:
    """An Eigen ``Vector<size>``: a sequence or array of ``size`` numbers, flat or a column."""

    def check(value: object) -> bool:
        if isinstance(value, str | bytes):
            return False
        try:
            return np.asarray(value, dtype=float).shape in {(size,), (size, 1)}
        except (TypeError, ValueError):
            return False

    check.__name__ = f"numpy.ndarray[numpy.float64[{size}, 1]]"
    return check


def is_path_like(value: object) -> bool:
    """pybind11's ``std::filesystem::path`` caster: str, bytes or ``os.PathLike``."""
    return isinstance(value, str | bytes | os.PathLike)


is_path_like.__name__ = "os.PathLike"


def path_text(value: str | bytes | os.PathLike[str] | os.PathLike[bytes]) -> str:
    """The path's text, as the caster hands it to C++ (no normalisation)."""
    return os.fsdecode(os.fspath(value))
