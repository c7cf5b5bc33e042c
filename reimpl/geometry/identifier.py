"""Drake's type-safe identifiers: GeometryId, FrameId, SourceId, FilterId.

Mirrors drake/common/identifier.h as bound by pydrake: ids cannot be built
directly, only obtained from registration or from ``get_new_id()``; they
compare and order by value within one type; and every id type draws from one
process-wide counter, so no two ids ever share a value.
"""

from __future__ import annotations

import itertools
from typing import ClassVar, Self

from reimpl.common._pybind_text import no_constructor

__all__ = ["FilterId", "FrameId", "GeometryId", "Identifier", "SourceId"]

# N.B. One counter for every id type, as in pydrake (see pydrake-observed.md §1).
_next_value = itertools.count(1)


class Identifier:
    """Base of the id types; not constructible from Python, like pydrake's."""

    __slots__ = ("_value",)
    _type_name: ClassVar[str] = "Identifier"

    _value: int

    def __init__(self) -> None:
        raise no_constructor(f"reimpl.geometry.{type(self).__name__}")

    @classmethod
    def _from_value(cls, value: int) -> Self:
        instance = object.__new__(cls)
        instance._value = value
        return instance

    @classmethod
    def get_new_id(cls) -> Self:
        """Returns a new, valid id with a value no other id in this process has."""
        return cls._from_value(next(_next_value))

    def get_value(self) -> int:
        return self._value

    def is_valid(self) -> bool:
        return True

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        return self._value == other._value

    def __lt__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        return self._value < other._value

    def __hash__(self) -> int:
        return hash(self._value)

    def __repr__(self) -> str:
        return f"<{type(self).__name__} value={self._value}>"

    def __copy__(self) -> Self:
        return self

    def __deepcopy__(self, memo: dict[int, object]) -> Self:
        return self

    def __reduce__(self) -> tuple[object, tuple[int]]:
        return (type(self)._from_value, (self._value,))


class GeometryId(Identifier):
    """Identifies a geometry registered with a SceneGraph."""

    __slots__ = ()


class FrameId(Identifier):
    """Identifies a frame registered with a SceneGraph."""

    __slots__ = ()


class SourceId(Identifier):
    """Identifies a geometry source registered with a SceneGraph."""

    __slots__ = ()


class FilterId(Identifier):
    """Identifies a transient collision filter declaration."""

    __slots__ = ()
