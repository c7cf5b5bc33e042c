"""A method with pybind11's single-signature binding: named parameters, type checks.

``@binds(owner, Param(...), ...)`` makes a method take its arguments by
position or by name as pybind11 does, and raise pybind11's ``incompatible
function arguments`` TypeError for a value its parameter does not accept
(see reimpl._overload).
"""

from __future__ import annotations

import functools
import os
from collections.abc import Callable
from typing import Any, TypeVar

from reimpl._overload import Overload, Param, dispatch

__all__ = ["binds", "is_path", "is_str"]

F = TypeVar("F", bound=Callable[..., Any])


def is_str(value: object) -> bool:
    """pybind11's ``str`` caster (which also takes bytes)."""
    return isinstance(value, str | bytes)


is_str.__name__ = "str"


def is_path(value: object) -> bool:
    """pybind11's ``std::filesystem::path`` caster: a str or an os.PathLike."""
    return isinstance(value, str | os.PathLike)


is_path.__name__ = "os.PathLike"


def _text(value: Any) -> Any:
    return value.decode() if isinstance(value, bytes) else value


def binds(owner: str, *params: Param) -> Callable[[F], F]:
    """Binds the decorated method's parameters ``params`` as pybind11 would."""

    def decorate(method: F) -> F:
        overloads = (Overload(params, method),)

        @functools.wraps(method)
        def bound(self: Any, *args: Any, **kwargs: Any) -> Any:
            args = tuple(_text(a) for a in args)
            kwargs = {k: _text(v) for k, v in kwargs.items()}
            return dispatch(owner, method.__name__, overloads, args, kwargs, receiver=self)

        return bound  # type: ignore[return-value]

    return decorate
