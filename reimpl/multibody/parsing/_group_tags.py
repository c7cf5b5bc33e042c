"""Reading one ``<drake:collision_filter_group>`` element, in Drake's order.

URDF and SDFormat spell a group's parts differently (attributes against text;
see ``GroupSyntax``) but read them in the same order, Drake's
``CollectCollisionFilterGroup`` (detail_common.cc). With Drake's throwing
parser policy the first error ends the parse, so this order is the order of
the errors (measured on pydrake 1.51.1):

1. ``ignore``: an ignored group is skipped before anything else is read, so a
   group with ``ignore="true"`` and no name is no error;
2. the group's ``name``: missing is an error, empty skips the group;
3. each ``<drake:member>`` in document order, then each
   ``<drake:member_group>``: a missing value is an error, an empty one is
   skipped;
4. the group is declared (``group 'r::g' has no members``, ``body with name
   'r::zz' not found``, ...: the resolver's checks);
5. each ``<drake:ignored_collision_filter_group>``: a missing value is an
   error (so it comes after "no members"), an empty one is skipped; each
   other name is one excluded pair.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from reimpl.multibody.parsing._collision_filter_group_resolver import (
    CollisionFilterGroupResolver,
)
from reimpl.multibody.parsing._diagnostics import Diagnostics
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = ["GroupSyntax", "read_group"]


@dataclass(frozen=True)
class GroupSyntax:
    """How a format spells a group: each reader raises the format's error."""

    #: whether the group element says it is ignored
    is_ignored: Callable[[XmlElement], bool]
    #: the group element's name ("" skips the group)
    name: Callable[[XmlElement], str]
    #: a child element's value; the second argument is the URDF attribute that holds it
    value: Callable[[XmlElement, str], str]


def _values(group: XmlElement, tag: str, attribute: str, syntax: GroupSyntax) -> list[str]:
    """The non-empty values of ``group``'s ``tag`` children, in document order."""
    values = (syntax.value(child, attribute) for child in children(group, tag))
    return [value for value in values if value]


def read_group(
    group: XmlElement,
    syntax: GroupSyntax,
    resolver: CollisionFilterGroupResolver,
    diagnostics: Diagnostics,
    *,
    line: int | None,
    scope: str,
) -> None:
    """Declares ``group`` (read in ``scope``) and its excluded pairs to ``resolver``;
    the resolver's errors carry ``line``."""
    if syntax.is_ignored(group):
        return
    name = syntax.name(group)
    if not name:
        return
    members = _values(group, "drake:member", "link", syntax)
    member_groups = _values(group, "drake:member_group", "name", syntax)
    resolver.add_group(
        diagnostics,
        line,
        group_name=name,
        body_names=set(members),
        member_group_names=set(member_groups),
        scope=scope,
    )
    for other in _values(group, "drake:ignored_collision_filter_group", "name", syntax):
        resolver.add_pair(diagnostics, line, name, other, scope)
