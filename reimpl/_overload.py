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
from dataclasses import dataclass, field
from typing import Any

from reimpl.common._pybind_text import incompatible_arguments

__all__ = ["REQUIRED", "Overload", "Param", "any_of", "dispatch", "instance_of", "list_of"]

Check = Callable[[object], bool]


class _Required:
    def __repr__(self) -> str:
        return "REQUIRED"


REQUIRED: Any = _Required()
_NO_RECEIVER: Any = object()


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
    """One signature of an overload set and the function it calls.

    Build overloads once (module or class level) and pass the same tuple to
    ``dispatch`` on every call: binding is then the only per-call work.
    """

    params: tuple[Param, ...]
    impl: Callable[..., Any]
    names: frozenset[str] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "names", frozenset(p.name for p in self.params))

    def bind(self, args: tuple[Any, ...], kwargs: dict[str, Any]) -> dict[str, Any] | None:
        """The arguments by parameter name, or None if this overload does not take them.

        A value given as the parameter's own default object is taken unchecked.
        """
        # The usual call names every argument: the keywords are the binding.
        by_name = not args and kwargs.keys() == self.names
        bound = kwargs if by_name else self._match(args, kwargs)
        if bound is None:
            return None
        for param in self.params:
            value = bound[param.name]
            if not (value is param.default or param.check(value)):
                return None
        return bound

    def _match(self, args: tuple[Any, ...], kwargs: dict[str, Any]) -> dict[str, Any] | None:
        """Names the arguments (positions, then keywords, then defaults), unchecked."""
        params = self.params
        if len(args) > len(params) or not kwargs.keys() <= self.names:
            return None
        bound: dict[str, Any] = {}
        for i, param in enumerate(params):
            if i < len(args):
                if param.name in kwargs:
                    return None
                bound[param.name] = args[i]
            elif param.name in kwargs:
                bound[param.name] = kwargs[param.name]
            elif param.default is REQUIRED:
                return None
            else:
                bound[param.name] = param.default
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
    *,
    receiver: object = _NO_RECEIVER,
) -> Any:
    """Calls the first overload that binds; raises pybind11's TypeError otherwise.

    With a ``receiver`` the overload's function is called as ``impl(receiver,
    **bound)``, so a class can keep one overload table of plain functions.
    """
    for overload in overloads:
        bound = overload.bind(args, kwargs)
        if bound is not None:
            if receiver is _NO_RECEIVER:
                return overload.impl(**bound)
            return overload.impl(receiver, **bound)
    lines = [f"{incompatible_arguments(name)}. The following argument types are supported:"]
    for i, overload in enumerate(overloads, 1):
        lines.append(f"    {i}. {overload.signature(owner)}")
    shown = [repr(a) for a in args] + [f"kwargs: {k}={v!r}" for k, v in kwargs.items()]
    lines.append("")
    lines.append(f"Invoked with: {', '.join(shown)}")
    raise TypeError("\n".join(lines))
