"""pybind11-style overload resolution for the pydrake-compatible boundary.

pydrake methods are overload sets with named parameters. A call binds to the
first overload whose parameters accept the positional and keyword arguments;
if none does, pybind11 raises ``TypeError`` that begins
``<name>(): incompatible function arguments`` (or ``incompatible constructor
arguments`` for ``__init__``). This module reproduces that contract so that a
pydrake script, switched to reimpl, binds to the same overload with the same
keywords, or fails with the same exception type.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

__all__ = ["REQUIRED", "Overload", "Param", "any_of", "dispatch", "instance_of", "list_of"]

Check = Callable[[object], bool]


class _Required:
    def __repr__(self) -> str:
        return "REQUIRED"


REQUIRED: Any = _Required()


def instance_of(*types: type) -> Check:
    """Accepts an instance of one of ``types`` (bool is never accepted as int)."""

    def check(value: object) -> bool:
        if isinstance(value, bool) and bool not in types:
            return False
        return isinstance(value, types)

    check.__name__ = "|".join(t.__name__ for t in types)
    return check


def any_of(*checks: Check) -> Check:
    def check(value: object) -> bool:
        return any(c(value) for c in checks)

    check.__name__ = "|".join(c.__name__ for c in checks)
    return check


def list_of(item_type: type) -> Check:
    """Accepts a list or tuple whose items are all ``item_type`` (pybind11 list caster).

    N.B. pybind11 rejects ``set`` and ``str`` here; so do we.
    """

    def check(value: object) -> bool:
        if not isinstance(value, Sequence) or isinstance(value, str | bytes):
            return False
        return all(type(item) is item_type for item in value)

    check.__name__ = f"list[{item_type.__name__}]"
    return check


@dataclass(frozen=True)
class Param:
    name: str
    check: Check
    default: Any = REQUIRED


@dataclass(frozen=True)
class Overload:
    params: tuple[Param, ...]
    impl: Callable[..., Any]

    def bind(self, args: tuple[Any, ...], kwargs: dict[str, Any]) -> dict[str, Any] | None:
        if len(args) > len(self.params):
            return None
        names = [p.name for p in self.params]
        if any(k not in names for k in kwargs):
            return None
        bound: dict[str, Any] = {}
        for param, value in zip(self.params, args, strict=False):
            bound[param.name] = value
        for param in self.params[len(args) :]:
            if param.name in kwargs:
                bound[param.name] = kwargs[param.name]
            elif param.default is not REQUIRED:
                bound[param.name] = param.default
            else:
                return None
        if any(p.name in kwargs for p in self.params[: len(args)]):
            return None
        for param in self.params:
            value = bound[param.name]
            if value is param.default and param.default is not REQUIRED:
                continue
            if not param.check(value):
                return None
        return bound

    def signature(self, owner: str) -> str:
        parts = [f"self: {owner}"]
        for p in self.params:
            text = f"{p.name}: {p.check.__name__}"
            if p.default is not REQUIRED:
                text += f" = {p.default!r}"
            parts.append(text)
        return f"({', '.join(parts)})"


def dispatch(
    owner: str,
    name: str,
    overloads: Sequence[Overload],
    args: tuple[Any, ...],
    kwargs: dict[str, Any],
) -> Any:
    """Calls the first overload that binds; raises pybind11's TypeError otherwise."""
    for overload in overloads:
        bound = overload.bind(args, kwargs)
        if bound is not None:
            return overload.impl(**bound)
    what = "constructor" if name == "__init__" else "function"
    lines = [
        f"{name}(): incompatible {what} arguments. The following argument types are supported:"
    ]
    for i, overload in enumerate(overloads, 1):
        lines.append(f"    {i}. {overload.signature(owner)}")
    shown = [repr(a) for a in args] + [f"kwargs: {k}={v!r}" for k, v in kwargs.items()]
    lines.append("")
    lines.append(f"Invoked with: {', '.join(shown)}")
    raise TypeError("\n".join(lines))
