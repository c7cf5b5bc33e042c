"""CollisionFilterGroups: what parsing declared, by fully scoped name.

``groups()`` maps each group to its member bodies (after member groups are
expanded) and ``exclusion_pairs()`` holds the pairs of groups whose members
must not collide, each pair sorted, so (a, b) and (b, a) are one pair and
(g, g) means "no collisions within g".

As in pydrake 1.51.1 (measured):

* ``AddGroup(name, members)`` takes a ``set`` or ``frozenset`` of names (no
  list) and may be empty; since Drake 1.58 any iterable of names (a list, a
  tuple, a str's characters, a dict's keys, an iterator; release fact
  add-group-members-iterable-since-1.58, measured on 1.51.1 and 1.52.0 to
  1.58.0); a name already defined ends the program (SystemExit: Drake's
  ``DRAKE_THROW_UNLESS``), with the groups added before it kept;
* ``AddExclusionPair(pair)`` takes a 2-tuple (no list);
* ``==`` is identity, since pydrake binds no comparison; ``str()`` is Drake's
  listing; the object neither copies nor pickles.

``NameGroups`` is the container itself, for any kind of name; the Parser keeps
its groups as ``NameGroups[InstancedName]`` (see _instanced_name).
"""

from __future__ import annotations

from collections.abc import Callable, Hashable, Iterable, Iterator
from typing import Any, Generic, TypeVar

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl._release import release
from reimpl.common._drake_demand import failed_demand

__all__ = ["CollisionFilterGroups", "NameGroups"]

_OWNER = "reimpl.multibody.parsing.CollisionFilterGroups"
N = TypeVar("N", bound=Hashable)
M = TypeVar("M", bound=Hashable)


class NameGroups(Generic[N]):
    """Drake's ``CollisionFilterGroupsImpl<T>``: groups of names and sorted pairs.

    ``key`` orders names as Drake's ``std::map``/``std::set`` of T do.
    """

    def __init__(self, key: Callable[[N], Any]) -> None:
        self.key = key
        self.groups: dict[N, set[N]] = {}
        self.pairs: set[tuple[N, N]] = set()

    def add_group(self, name: N, members: set[N]) -> None:
        """Adds a group; a name already defined is Drake's DRAKE_THROW_UNLESS failure."""
        if name in self.groups:
            raise failed_demand("CollisionFilterGroups.AddGroup.new")
        self.groups[name] = set(members)

    def add_pair(self, a: N, b: N) -> None:
        self.pairs.add((a, b) if self.key(a) <= self.key(b) else (b, a))

    def sorted_groups(self) -> list[tuple[N, list[N]]]:
        """The groups and their members, each level in Drake's order."""
        return [
            (name, sorted(self.groups[name], key=self.key))
            for name in sorted(self.groups, key=self.key)
        ]

    def sorted_pairs(self) -> list[tuple[N, N]]:
        return sorted(self.pairs, key=lambda pair: (self.key(pair[0]), self.key(pair[1])))

    def merge(self, source: NameGroups[N]) -> None:
        """Adds ``source``'s groups in order (stopping at a duplicate), then its pairs."""
        for name, members in source.sorted_groups():
            self.add_group(name, set(members))
        for a, b in source.sorted_pairs():
            self.add_pair(a, b)

    def convert(self, to: Callable[[N], M], key: Callable[[M], Any]) -> NameGroups[M]:
        """Drake's ``Convert``: every name through ``to``, groups added in order."""
        result: NameGroups[M] = NameGroups(key)
        for name, members in self.sorted_groups():
            result.add_group(to(name), {to(member) for member in members})
        for a, b in self.sorted_pairs():
            result.add_pair(to(a), to(b))
        return result


def _same(name: str) -> str:
    return name


#: Whether AddGroup takes any iterable of names, not only a set (Drake 1.58).
_MEMBERS_ITERABLE = release.has("add-group-members-iterable-since-1.58")


def _is_name_set(value: object) -> bool:
    kinds = Iterable if _MEMBERS_ITERABLE else set | frozenset
    return isinstance(value, kinds) and all(isinstance(v, str) for v in value)


def _replayable(args: tuple[Any, ...], kwargs: dict[str, Any]) -> tuple[Any, ...]:
    """AddGroup's arguments with an iterator of members read into a tuple, so that
    checking the names does not use them up."""
    if len(args) > 1 and isinstance(args[1], Iterator):
        args = (args[0], tuple(args[1]), *args[2:])
    if isinstance(kwargs.get("members"), Iterator):
        kwargs["members"] = tuple(kwargs["members"])
    return args


def _is_name_pair(value: object) -> bool:
    return isinstance(value, tuple) and len(value) == 2 and all(isinstance(v, str) for v in value)


_is_name_set.__name__ = "set[str]"
_is_name_pair.__name__ = "tuple[str, str]"
_ADD_GROUP = (
    Overload(
        (Param("name", instance_of(str)), Param("members", _is_name_set)),
        lambda self, name, members: self._impl.add_group(name, members),
    ),
)
_ADD_PAIR = (
    Overload((Param("pair", _is_name_pair),), lambda self, pair: self._impl.add_pair(*pair)),
)


class CollisionFilterGroups:
    """Groups of bodies and the group pairs excluded from collision."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self._impl: NameGroups[str] = NameGroups(_same)
        dispatch(_OWNER, "__init__", (Overload((), lambda: None),), args, kwargs)

    @staticmethod
    def _from(impl: NameGroups[str]) -> CollisionFilterGroups:
        groups = CollisionFilterGroups()
        groups._impl = impl
        return groups

    def AddGroup(self, *args: Any, **kwargs: Any) -> None:
        """Adds group ``name`` with body names ``members``; the name must be new."""
        if _MEMBERS_ITERABLE:
            args = _replayable(args, kwargs)
        dispatch(_OWNER, "AddGroup", _ADD_GROUP, args, kwargs, receiver=self)

    def AddExclusionPair(self, *args: Any, **kwargs: Any) -> None:
        """Adds the pair of group names, sorted; adding it again does nothing."""
        dispatch(_OWNER, "AddExclusionPair", _ADD_PAIR, args, kwargs, receiver=self)

    def empty(self) -> bool:
        return not self._impl.groups and not self._impl.pairs

    def groups(self) -> dict[str, set[str]]:
        """A new dict of new sets, in name order."""
        return {name: set(members) for name, members in self._impl.sorted_groups()}

    def exclusion_pairs(self) -> set[tuple[str, str]]:
        return set(self._impl.pairs)

    def __str__(self) -> str:
        """Drake's listing: groups and their members, then the pairs, all sorted."""
        lines = ["", "Collision filter groups:"]
        for name, members in self._impl.sorted_groups():
            lines.append(f"    {name}")
            lines.extend(f"        {member}" for member in members)
        lines.append("Collision filter exclusion pairs:")
        lines.extend(f"    {a}, {b}" for a, b in self._impl.sorted_pairs())
        return "\n".join(lines) + "\n"

    def __reduce__(self) -> Any:
        raise TypeError(f"cannot pickle '{_OWNER}' object")
