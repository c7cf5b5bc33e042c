"""Roles and role properties (drake/geometry/geometry_roles.h).

Only the proximity role matters to collision filtering: a geometry is in G,
and so can be in C, exactly while it has ProximityProperties assigned.
"""

from __future__ import annotations

from typing import Any, ClassVar

from reimpl.common._pybind_enum import PybindEnum
from reimpl.common._std_unordered_map import StdUnorderedMap
from reimpl.common.value import AbstractValue, cpp_type_name

__all__ = [
    "ASSIGNED_ROLES",
    "GeometryProperties",
    "IllustrationProperties",
    "PerceptionProperties",
    "ProximityProperties",
    "Role",
    "RoleAssign",
    "role_name",
]


class Role(PybindEnum):
    __slots__ = ()
    kUnassigned: ClassVar[Role]
    kProximity: ClassVar[Role]
    kIllustration: ClassVar[Role]
    kPerception: ClassVar[Role]


Role.define(kUnassigned=0, kProximity=1, kIllustration=2, kPerception=4)


class RoleAssign(PybindEnum):
    __slots__ = ()
    kNew: ClassVar[RoleAssign]
    kReplace: ClassVar[RoleAssign]


RoleAssign.define(kNew=0, kReplace=1)

#: The roles a geometry can be assigned (kUnassigned is having none of them).
ASSIGNED_ROLES = (Role.kProximity, Role.kIllustration, Role.kPerception)

_ROLE_NAMES = {
    Role.kUnassigned: "unassigned",
    Role.kProximity: "proximity",
    Role.kIllustration: "illustration",
    Role.kPerception: "perception",
}


def role_name(role: Role) -> str:
    """How Drake prints a role in messages (``operator<<`` of geometry_roles.h)."""
    return _ROLE_NAMES[role]


_DEFAULT_GROUP = "__default__"


class GeometryProperties:
    """Grouped, named property values, each held as an ``AbstractValue``.

    Groups, and the properties within a group, are listed (``str``,
    ``GetPropertiesInGroup``) in the order of Drake's ``std::unordered_map``.
    """

    role: Role = Role.kUnassigned

    def __init__(self, other: GeometryProperties | None = None) -> None:
        self._groups: StdUnorderedMap[StdUnorderedMap[AbstractValue]] = StdUnorderedMap()
        if other is None:
            self._groups[_DEFAULT_GROUP] = StdUnorderedMap()
            return
        # N.B. A copy keeps the maps' layouts, hence the listing order.
        self._groups = other._groups.copy()
        for name in self._groups:
            group = self._groups[name].copy()
            for key in group:
                group[key] = group[key].Clone()
            self._groups[name] = group

    def _group(self, group_name: str) -> StdUnorderedMap[AbstractValue]:
        if group_name not in self._groups:
            self._groups[group_name] = StdUnorderedMap()
        return self._groups[group_name]

    def AddProperty(self, group_name: str, name: str, value: object) -> None:
        if self.HasProperty(group_name, name):
            raise RuntimeError(
                f"AddProperty(): Trying to add property ('{group_name}', '{name}'); "
                "a property with that name already exists"
            )
        self._group(group_name)[name] = AbstractValue.Make(value)

    def UpdateProperty(self, group_name: str, name: str, value: object) -> None:
        new = AbstractValue.Make(value)
        group = self._group(group_name)
        if name in group and type(group[name]) is not type(new):
            raise RuntimeError(
                f"UpdateProperty(): Trying to update property ('{group_name}', '{name}'); "
                "The property already exists and is of different type. New type "
                f"{cpp_type_name(new)}, existing type {cpp_type_name(group[name])}"
            )
        group[name] = new

    def HasGroup(self, group_name: str) -> bool:
        return group_name in self._groups

    def num_groups(self) -> int:
        return len(self._groups)

    def HasProperty(self, group_name: str, name: str) -> bool:
        return group_name in self._groups and name in self._groups[group_name]

    def GetGroupNames(self) -> set[str]:
        return set(self._groups)

    def GetPropertiesInGroup(self, group_name: str) -> dict[str, AbstractValue]:
        if group_name not in self._groups:
            raise RuntimeError(
                "GetPropertiesInGroup(): Can't retrieve properties for a group that doesn't "
                f"exist: '{group_name}'"
            )
        group = self._groups[group_name]
        return {name: group[name] for name in group}

    def GetProperty(self, group_name: str, name: str) -> Any:
        if group_name not in self._groups:
            raise RuntimeError(
                f"GetProperty(): Trying to read property ('{group_name}', '{name}'), but the "
                "group does not exist."
            )
        if name not in self._groups[group_name]:
            raise RuntimeError(f"GetProperty(): There is no property ('{group_name}', '{name}')")
        return self._groups[group_name][name].get_value()

    def GetPropertyOrDefault(self, group_name: str, name: str, default_value: object) -> Any:
        if self.HasProperty(group_name, name):
            return self._groups[group_name][name].get_value()
        return default_value

    def RemoveProperty(self, group_name: str, name: str) -> bool:
        if not self.HasProperty(group_name, name):
            return False
        del self._groups[group_name][name]
        return True

    @staticmethod
    def default_group_name() -> str:
        return _DEFAULT_GROUP

    def __str__(self) -> str:
        lines = []
        for group_name in self._groups:
            lines.append(f"[{group_name}]")
            group = self._groups[group_name]
            lines.extend(f"  {name}: {cpp_type_name(group[name])}" for name in group)
        return "\n".join(lines)

    def __copy__(self) -> GeometryProperties:
        return type(self)(self)

    def __deepcopy__(self, memo: dict[int, object]) -> GeometryProperties:
        return type(self)(self)


class ProximityProperties(GeometryProperties):
    role = Role.kProximity


class IllustrationProperties(GeometryProperties):
    role = Role.kIllustration


class PerceptionProperties(GeometryProperties):
    role = Role.kPerception
