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
``hash(member)``                ``hash(value)``                 ``hash(value)``
``a < b``, same enum            by value                        by value
``repr`` / ``str``              ``<Role.kProximity: 1>`` /      (reimpl's own)
                                ``Role.kProximity``
==============================  ==============================  =====================

So a member is an ``enum.Enum`` member (not an int) that converts to its
value, hashes as it, and orders only against its own enum. Iterating the class
and ``Role(3)`` are left as ``enum.Enum`` has them: pydrake refuses the first
and makes a ``???`` member for the second, so no script that runs on pydrake
depends on either.
"""

from __future__ import annotations

import enum
from typing import Any

__all__ = ["PybindEnum"]

_MISMATCH = "Expected an enumeration of matching type!"


class PybindEnum(enum.Enum):
    """A pybind11 enum: named int values that are not ints."""

    def __int__(self) -> int:
        return int(self.value)

    def __index__(self) -> int:
        return int(self.value)

    def __hash__(self) -> int:
        return hash(self.value)

    def __repr__(self) -> str:
        return f"<{type(self).__name__}.{self.name}: {self.value}>"

    def __str__(self) -> str:
        return f"{type(self).__name__}.{self.name}"

    def __format__(self, spec: str) -> str:
        return format(str(self), spec)

    def _same_type_value(self, other: Any) -> int:
        if type(other) is not type(self):
            raise TypeError(_MISMATCH)
        return int(other.value)

    def __lt__(self, other: Any) -> bool:
        return int(self.value) < self._same_type_value(other)

    def __le__(self, other: Any) -> bool:
        return int(self.value) <= self._same_type_value(other)

    def __gt__(self, other: Any) -> bool:
        return int(self.value) > self._same_type_value(other)

    def __ge__(self, other: Any) -> bool:
        return int(self.value) >= self._same_type_value(other)
