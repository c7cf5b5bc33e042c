"""Collision filter groups: from declared names to excluded geometry pairs.

One resolver serves one parse (``Parser.AddModels*`` and everything it
includes). Parsers declare groups and pairs as they read; ``resolve()`` runs
at the end of the parse, before Finalize. In formulas, with direct(G) the
bodies a group names itself and G → H meaning "G lists H as a member_group":

    members(G) = ⋃ { direct(H) : H = G or H reachable from G by → }

    (a, b) is excluded  iff  ∃ (G, H) ∈ pairs : (a ∈ G ∧ b ∈ H) ∨ (a ∈ H ∧ b ∈ G)

where a and b stand for every geometry of the member bodies. → may have
cycles: every group of a cycle gets the union of the cycle's members.

Names are fully scoped: a name read inside model instance ``top::inner``
means ``top::inner::<name>``, in Drake's canonical form since 1.14
(``_scoped_name.qualify``: ``::a`` and ``a::`` mean ``top::inner::a``); a name
read in the global scope (model directives without a namespace) is itself.
Up to 1.13 a group, body or ignored group name that begins or ends with ``:``
is an error, ``group name '::g' can neither begin nor end with '::'`` (or
``body name``), checked before anything else about it
(scoped-names-canonical-since-1.14; measured on pydrake 1.13.0, 1.14.0 and
1.51.1). A group's own name must not be scoped. Bodies
must come from model instances this parse created (the parse-scope rule);
groups must be declared in this parse, but a pair or member_group may name a
group declared later. The checks and messages are Drake 1.51.1's (measured):

* at declaration, in this order: ``group name 'M::x::g' cannot be a scoped
  name``, ``group 'M::g' has already been defined``, ``group 'M::g' has no
  members``, then per body in sorted order ``body name 'N' refers to a model
  outside the current parse`` or ``body with name 'N' not found``;
* at resolve, without a source: ``collision filter group with name 'N' not
  found``, first for member groups (sorted), then for pairs (sorted), each
  pair applied once both its groups are found. Up to 1.30 the pairs' error
  is not caught and the process aborts (undefined-ignored-group-aborts).

Member groups add their members since 1.27; up to 1.26 they add nothing
(member-groups-since-1.27, measured by the release matrix on 1.26.0). A group
defined twice is an error since 1.27; up to 1.26 the second definition's bodies
are looked up (an unknown one is an error) and then it is dropped: the first
definition stays (group-redefinition-error-since-1.27; measured on pydrake
1.12.0-1.26.0 with g1 = {a, b} then g1 = {c, d}: (a, b) filtered, (c, d) not).

Each pair is applied with ``plant._exclude_collision_geometries_with_collision_
filter_group_pair``, whose equal names mean ExcludeWithin, else ExcludeBetween.
"""

from __future__ import annotations

from typing import Any

from reimpl._release import release
from reimpl.common._drake_demand import abort_uncaught, failed_demand
from reimpl.geometry import GeometrySet
from reimpl.multibody.parsing import _scoped_name as scoped
from reimpl.multibody.parsing._collision_filter_groups import NameGroups
from reimpl.multibody.parsing._diagnostics import Diagnostics, ModelParseError
from reimpl.multibody.parsing._instanced_name import InstancedName, instanced, order

__all__ = ["CollisionFilterGroupResolver"]

#: Since 1.14 names are canonical ScopedNames; up to 1.13 a name with a delimiter
#: at either end is refused (scoped-names-canonical-since-1.14).
_CANONICAL_NAMES = release.has("scoped-names-canonical-since-1.14")


def _canonical(name: str) -> str:
    """``name`` as Drake's ScopedName::Parse leaves it (since 1.14), else unchanged."""
    return scoped.parse(name) if _CANONICAL_NAMES else name


def _qualify(scope: str, name: str) -> str:
    """``name`` read in model instance ``scope``: Drake's FullyQualify (since 1.14 a
    canonical ScopedName), else ``scope::name``."""
    return scoped.qualify(scope, name) if _CANONICAL_NAMES else scoped.join(scope, name)


def _check_legal(diagnostics: Diagnostics, line: int | None, name: str, what: str) -> None:
    """Up to 1.13 (CheckLegalName): a name may neither begin nor end with ``:``."""
    if not _CANONICAL_NAMES and (name.startswith(":") or name.endswith(":")):
        raise diagnostics.error(f"{what} '{name}' can neither begin nor end with '::'", line)


class CollisionFilterGroupResolver:
    """Collects one parse's groups and pairs, then applies them to the plant."""

    def __init__(self, plant: Any) -> None:
        self._plant = plant
        #: Model instances with a smaller index existed before this parse.
        self._first_new_instance = plant.num_model_instances()
        #: group name -> {body name: body}, both fully scoped
        self._bodies: dict[str, dict[str, Any]] = {}
        #: group name -> the groups it names as member_group
        self._member_groups: dict[str, set[str]] = {}
        self._pairs: set[tuple[str, str]] = set()

    def add_group(
        self,
        diagnostics: Diagnostics,
        line: int | None,
        *,
        group_name: str,
        body_names: set[str],
        member_group_names: set[str],
        scope: str,
    ) -> None:
        """Declares group ``scope::group_name``; names are relative to ``scope``."""
        self._check_scope(scope)
        _check_legal(diagnostics, line, group_name, "group name")
        name = _qualify(scope, group_name)
        if scoped.is_scoped(_canonical(group_name)):
            raise diagnostics.error(f"group name '{name}' cannot be a scoped name", line)
        redefined = name in self._bodies
        if redefined and release.has("group-redefinition-error-since-1.27"):
            raise diagnostics.error(f"group '{name}' has already been defined", line)
        if not release.has("member-groups-since-1.27"):
            member_group_names = set()  # up to 1.26 a group's member groups add nothing
        if not body_names and not member_group_names:  # so up to 1.26 they are no members
            raise diagnostics.error(f"group '{name}' has no members", line)
        for body_name in sorted(body_names):
            _check_legal(diagnostics, line, body_name, "body name")
        bodies = {}
        for body_name in sorted(_canonical(_qualify(scope, b)) for b in body_names):
            bodies[body_name] = self._find_body(diagnostics, line, body_name)
        if redefined:  # up to 1.26 the first definition stays (its bodies were checked)
            return
        self._bodies[name] = bodies
        self._member_groups[name] = {_qualify(scope, g) for g in member_group_names}

    def _check_scope(self, scope: str) -> None:
        """A group's model instance must be one this parse made (Drake's DRAKE_DEMAND;
        only model directives can name another, by ``model_namespace``)."""
        plant = self._plant
        outside = scope and plant.HasModelInstanceNamed(scope)
        if outside and int(plant.GetModelInstanceByName(scope)) < self._first_new_instance:
            raise failed_demand("CollisionFilterGroupResolver.AddGroup.instance")

    def add_pair(
        self, diagnostics: Diagnostics, line: int | None, group_a: str, group_b: str, scope: str
    ) -> None:
        """Declares that the two groups (relative to ``scope``) do not collide; the
        errors carry ``line``."""
        _check_legal(diagnostics, line, group_a, "group name")
        _check_legal(diagnostics, line, group_b, "group name")
        a, b = sorted((_qualify(scope, group_a), _qualify(scope, group_b)))
        self._pairs.add((a, b))

    def _find_body(self, diagnostics: Diagnostics, line: int | None, name: str) -> Any:
        plant = self._plant
        instance_name, body_name = scoped.split(name)
        if instance_name and plant.HasModelInstanceNamed(instance_name):
            instance = plant.GetModelInstanceByName(instance_name)
            if int(instance) < self._first_new_instance:
                raise diagnostics.error(
                    f"body name '{name}' refers to a model outside the current parse", line
                )
            if plant.HasBodyNamed(body_name, instance):
                return plant.GetBodyByName(body_name, instance)
        raise diagnostics.error(f"body with name '{name}' not found", line)

    def resolve_unwinding(self) -> None:
        """``resolve()`` for a parse that failed, on the releases that do it.

        Up to 1.30 Drake resolves in CompositeParse's destructor, so a parse that
        fails still applies the pairs of the groups declared before the failure;
        since 1.31 it resolves only a parse that finishes
        (failed-parse-resolves-groups-until-1.30: measured on pydrake 1.12.0-1.30.0
        and 1.31.0-1.58.0). An error while resolving then is thrown from a
        destructor during unwinding: the process aborts.
        """
        if not release.has("failed-parse-resolves-groups-until-1.30"):
            return
        try:
            self.resolve()
        except ModelParseError as error:
            abort_uncaught("std::runtime_error", str(error))

    def _members(self, group: str) -> dict[str, Any]:
        """members(G): the bodies of G and of every group reachable from G."""
        seen, stack, bodies = {group}, [group], {}
        while stack:
            current = stack.pop()
            bodies.update(self._bodies[current])
            for member_group in self._member_groups[current] - seen:
                seen.add(member_group)
                stack.append(member_group)
        return dict(sorted(bodies.items()))

    def resolve(self) -> NameGroups[InstancedName]:
        """Checks every group name, applies the pairs, and reports what was declared,
        held by model instance index (see _instanced_name).

        N.B. Pairs are applied one by one in sorted order, so the pairs sorted
        before one naming an unknown group are applied when it raises (measured).
        """
        unlocated = Diagnostics(None)
        for name in sorted(set().union(*self._member_groups.values())):
            self._check_group(unlocated, name)
        members = {group: self._members(group) for group in sorted(self._bodies)}
        for a, b in sorted(self._pairs):
            self._check_ignored_group(unlocated, a)
            self._check_ignored_group(unlocated, b)
            self._plant._exclude_collision_geometries_with_collision_filter_group_pair(
                (a, self._geometry_set(members[a].values())),
                (b, self._geometry_set(members[b].values())),
            )
        report: NameGroups[str] = NameGroups(str)
        for group, bodies in members.items():
            report.add_group(group, set(bodies))
        for pair in self._pairs:
            report.add_pair(*pair)
        return report.convert(lambda name: instanced(self._plant, name), order)

    def _check_group(self, diagnostics: Diagnostics, name: str) -> None:
        if name not in self._bodies:
            raise diagnostics.error(f"collision filter group with name '{name}' not found")

    def _check_ignored_group(self, diagnostics: Diagnostics, name: str) -> None:
        """``_check_group`` for a group a pair ignores; up to 1.30 Drake throws it where
        nothing catches it, and the process aborts (undefined-ignored-group-aborts)."""
        try:
            self._check_group(diagnostics, name)
        except ModelParseError as error:
            if release.has("undefined-ignored-group-aborts"):
                abort_uncaught("std::runtime_error", str(error))
            raise

    def _geometry_set(self, bodies: Any) -> GeometrySet:
        frame_ids = [self._plant.GetBodyFrameIdOrThrow(body.index()) for body in bodies]
        return GeometrySet(frame_ids=list(dict.fromkeys(frame_ids)))
