"""Roles and role properties (drake/geometry/geometry_roles.h).

Only the proximity role matters to collision filtering: a geometry is in G,
and so can be in C, exactly while it has ProximityProperties assigned.
"""

from __future__ import annotations

import copy
import enum
from typing import Any

__all__ = [
    "GeometryProperties",
    "IllustrationProperties",
    "PerceptionProperties",
    "ProximityProperties",
    "Role",
    "RoleAssign",
]


class _PybindEnum(enum.IntEnum):
    def __repr__(self) -> str:
        return f"<{type(self).__name__}.{self.name}: {self.value}>"

    def __str__(self) -> str:
        return f"{type(self).__name__}.{self.name}"


class Role(_PybindEnum):
    kUnassigned = 0
    kProximity = 1
    kIllustration = 2
    kPerception = 4


class RoleAssign(_PybindEnum):
    kNew = 0
    kReplace = 1


_DEFAULT_GROUP = "__default__"


class GeometryProperties:
    """Grouped, named property values."""

    role: Role = Role.kUnassigned

    def __init__(self, other: GeometryProperties | None = None) -> None:
        self._groups: dict[str, dict[str, Any]] = {_DEFAULT_GROUP: {}}
        if other is not None:
            self._groups = copy.deepcopy(other._groups)

    def AddProperty(self, group_name: str, name: str, value: object) -> None:
        group = self._groups.setdefault(group_name, {})
        if name in group:
            raise RuntimeError(
                f"AddProperty(): Trying to add property ('{group_name}', '{name}'); "
                "a property with that name already exists"
            )
        group[name] = value

    def UpdateProperty(self, group_name: str, name: str, value: object) -> None:
        self._groups.setdefault(group_name, {})[name] = value

    def HasGroup(self, group_name: str) -> bool:
        return group_name in self._groups

    def HasProperty(self, group_name: str, name: str) -> bool:
        return name in self._groups.get(group_name, {})

    def GetGroupNames(self) -> set[str]:
        return set(self._groups)

    def GetPropertiesInGroup(self, group_name: str) -> dict[str, Any]:
        return dict(self._groups.get(group_name, {}))

    def GetProperty(self, group_name: str, name: str) -> Any:
        if not self.HasProperty(group_name, name):
            raise RuntimeError(f"GetProperty(): There is no property ('{group_name}', '{name}')")
        return self._groups[group_name][name]

    def GetPropertyOrDefault(self, group_name: str, name: str, default_value: object) -> Any:
        return self._groups.get(group_name, {}).get(name, default_value)

    def RemoveProperty(self, group_name: str, name: str) -> bool:
        return self._groups.get(group_name, {}).pop(name, _MISSING) is not _MISSING

    @staticmethod
    def default_group_name() -> str:
        return _DEFAULT_GROUP

    def __copy__(self) -> GeometryProperties:
        return type(self)(self)

    def __deepcopy__(self, memo: dict[int, object]) -> GeometryProperties:
        return type(self)(self)


_MISSING = object()


class ProximityProperties(GeometryProperties):
    role = Role.kProximity


class IllustrationProperties(GeometryProperties):
    role = Role.kIllustration


class PerceptionProperties(GeometryProperties):
    role = Role.kPerception
