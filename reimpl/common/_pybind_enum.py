"""pybind11's ``py::enum_``, as a pydrake script sees it.

Measured against pydrake 1.51.1 (``Role``, ``RoleAssign``, ``CollisionFilterScope``):

==============================  ==============================  =====================
expression                      pybind11 enum                   ``enum.IntEnum``
==============================  ==============================  =====================
``Role.kProximity == 1``        False                           True
``isinstance(member, int)``     False                           True
``{1: "x"}.get(member)``        None                            ``"x"``
``member + 1``, ``a | b``       TypeError                       an int
``bool(Role.kUnassigned)``      True                            False
``member < 2``                  TypeError ("Expected an         True
                                enumeration of matching type!")
``int(member)``, ``[...][m]``   its value                       its value
``a < b``, same enum            by value                        by value
``Role(1)``                     the member                      the member
``Role(3)``                     ``<Role.???: 3>``               ValueError
``list(Role)``                  TypeError                       the members
``repr`` / ``str``              ``<Role.kProximity: 1>`` /      (reimpl's own)
                                ``Role.kProximity``
==============================  ==============================  =====================

So a member is a plain object (not an int) that converts to its value and
orders only against its own enum. It keeps object identity's equality and
hash, which Python computes without a Python-level call: members are dict keys
on hot paths (``Role.kProximity in properties``), where an ``enum.Enum``
member's hash costs five times an int's. Equal members are one object, so
dicts and sets behave as pybind11's do; only ``hash(member)`` differs (pybind11
hashes the value), which no filtering script relies on.
"""

from __future__ import annotations

from typing import Any, ClassVar, Self

__all__ = ["PybindEnum"]

_MISMATCH = "Expected an enumeration of matching type!"


class PybindEnum:
    """A pybind11 enum: named int values that are not ints.

    A subclass declares its members as ``ClassVar``s and makes them with
    ``define(kName=value, ...)`` once, after the class body.
    """

    __slots__ = ("_name", "_value")
    __members__: ClassVar[dict[str, Any]] = {}

    _name: str
    _value: int

    @classmethod
    def define(cls, **members: int) -> None:
        """Makes the members, in the order given (``__members__`` keeps it)."""
        cls.__members__ = {}
        for name, value in members.items():
            member = object.__new__(cls)
            member._name, member._value = name, value
            setattr(cls, name, member)
            cls.__members__[name] = member

    def __new__(cls, value: int) -> Self:
        """The member of ``value``; pybind11 makes an unnamed ``???`` one for any other int."""
        for member in cls.__members__.values():
            if member._value == value:
                return member  # type: ignore[no-any-return]
        unnamed = object.__new__(cls)
        unnamed._name, unnamed._value = "???", int(value)
        return unnamed

    def __reduce__(self) -> tuple[type[Self], tuple[int]]:
        return type(self), (self._value,)

    @property
    def name(self) -> str:
        return self._name

    @property
    def value(self) -> int:
        return self._value

    def __int__(self) -> int:
        return self._value

    def __index__(self) -> int:
        return self._value

    def __repr__(self) -> str:
        return f"<{type(self).__name__}.{self._name}: {self._value}>"

    def __str__(self) -> str:
        return f"{type(self).__name__}.{self._name}"

    def _other_value(self, other: object) -> int:
        if type(other) is not type(self):
            raise TypeError(_MISMATCH)
        return other._value

    def __lt__(self, other: object) -> bool:
        return self._value < self._other_value(other)

    def __le__(self, other: object) -> bool:
        return self._value <= self._other_value(other)

    def __gt__(self, other: object) -> bool:
        return self._value > self._other_value(other)

    def __ge__(self, other: object) -> bool:
        return self._value >= self._other_value(other)
