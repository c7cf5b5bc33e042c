"""CollisionFilterGroups: what a parse declared, by fully scoped name.

``groups()`` maps each group to its member bodies (after member groups are
expanded) and ``exclusion_pairs()`` holds the pairs of groups whose members
must not collide, each pair sorted, so (a, b) and (b, a) are one pair and
(g, g) means "no collisions within g".

As in pydrake 1.51.1 (measured): ``AddGroup`` takes a ``set`` of names and
ends the program (SystemExit) for a name already defined; ``AddExclusionPair``
takes a 2-tuple; ``==`` is identity, since pydrake binds no comparison.
"""

from __future__ import annotations

from typing import Any

from reimpl._overload import Overload, Param, dispatch, instance_of

__all__ = ["CollisionFilterGroups"]

_OWNER = "reimpl.multibody.parsing.CollisionFilterGroups"


def _is_name_set(value: object) -> bool:
    return isinstance(value, set | frozenset) and all(isinstance(v, str) for v in value)


def _is_name_pair(value: object) -> bool:
    return isinstance(value, tuple) and len(value) == 2 and all(isinstance(v, str) for v in value)


class CollisionFilterGroups:
    """Groups of bodies and the group pairs excluded from collision."""

    def __init__(self) -> None:
        self._groups: dict[str, set[str]] = {}
        self._pairs: set[tuple[str, str]] = set()

    def AddGroup(self, *args: Any, **kwargs: Any) -> None:
        """Adds group ``name`` with body names ``members``; the name must be new."""
        params = (Param("name", instance_of(str)), Param("members", _is_name_set))
        dispatch(_OWNER, "AddGroup", (Overload(params, self._add_group),), args, kwargs)

    def _add_group(self, name: str, members: set[str]) -> None:
        if name in self._groups:
            raise SystemExit(
                "Failure at external/drake+/multibody/parsing/"
                "detail_collision_filter_groups_impl.cc:24 in AddGroup(): "
                "condition '!groups_.contains(name)' failed."
            )
        self._groups[name] = set(members)

    def AddExclusionPair(self, *args: Any, **kwargs: Any) -> None:
        """Adds the pair of group names, sorted; adding it again does nothing."""
        params = (Param("pair", _is_name_pair),)
        dispatch(_OWNER, "AddExclusionPair", (Overload(params, self._add_pair),), args, kwargs)

    def _add_pair(self, pair: tuple[str, str]) -> None:
        a, b = sorted(pair)
        self._pairs.add((a, b))

    def empty(self) -> bool:
        return not self._groups and not self._pairs

    def groups(self) -> dict[str, set[str]]:
        return {name: set(members) for name, members in self._groups.items()}

    def exclusion_pairs(self) -> set[tuple[str, str]]:
        return set(self._pairs)

    def __str__(self) -> str:
        """Drake's listing: groups and their members, then the pairs, all sorted.

        (Drake keeps them in a ``std::map`` of ``std::set``s and a ``std::set``
        of sorted pairs, so each level is in byte order.)
        """
        lines = ["", "Collision filter groups:"]
        for name in sorted(self._groups):
            lines.append(f"    {name}")
            lines.extend(f"        {member}" for member in sorted(self._groups[name]))
        lines.append("Collision filter exclusion pairs:")
        lines.extend(f"    {a}, {b}" for a, b in sorted(self._pairs))
        return "\n".join(lines) + "\n"
