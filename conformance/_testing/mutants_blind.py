"""Mutants from a blind audit (issue 31): bugs written from reading reimpl, not the fuzzer.

Each one is reimpl with one deliberate bug of the kind an implementer of
``reimpl.geometry`` could make (an index, a mask, a wrong location, a state
kept or dropped), written as the other mutants are (``mutants_basic``), with
public calls only. They were written before the existing mutants' table was
read; those that duplicated one were dropped. ``conformance._testing.mutants``
lists them with the rest.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, cast

from conformance._testing.mutants_basic import (
    Manager,
    Mutant,
    MutantSceneGraph,
    Pair,
    Resolved,
    _context_of,
    _declaration,
    _pair,
    _SameFrameLedger,
    _SameFrameMutant,
    _statements,
    apply_persistent,
)
from conformance._testing.mutants_state import (
    _LOOKUP_ERRORS,
    Replay,
    _lift,
    _reapply,
    _RewritingManager,
    _TrackingSceneGraph,
)
from reimpl.geometry import (
    CollisionFilterDeclaration,
    CollisionFilterManager,
    FilterId,
    GeometryId,
    GeometrySet,
    ProximityProperties,
    Role,
    RoleAssign,
    SourceId,
)
from reimpl.systems.framework import Context

__all__ = ["BLIND_MUTANTS"]


# ------------------------------------------------------------ statements
class _AllowWithinRowsManager(_RewritingManager):
    def rewrite(self, declaration: CollisionFilterDeclaration) -> CollisionFilterDeclaration:
        statements = _statements(declaration)
        if not any(s.method == "AllowWithin" for s in statements):
            return declaration
        every = GeometrySet(geometry_ids=sorted(_live_ids(self), key=GeometryId.get_value))
        out = [
            type(s)("AllowBetween", s.set_A, every) if s.method == "AllowWithin" else s
            for s in statements
        ]
        return cast(CollisionFilterDeclaration, _declaration(declaration, out))


def _live_ids(manager: Manager) -> set[GeometryId]:
    return set(manager.inspector().GetAllGeometryIds(role=Role.kProximity))


class AllowWithinClearsRows(MutantSceneGraph):
    """AllowWithin(S) clears the whole rows of S (S × every geometry), not S × S.

    An implementer who writes ``row[a] = 0`` for "allow a with the set" where
    ``row[a] &= ~mask(S)`` was meant. Invariant pairs stay (Allow never clears them).
    """

    manager_class = _AllowWithinRowsManager


class _OverlapManager(_RewritingManager):
    def rewrite(self, declaration: CollisionFilterDeclaration) -> CollisionFilterDeclaration:
        statements = _statements(declaration)
        if not any(s.method == "ExcludeBetween" for s in statements):
            return declaration
        try:
            resolved = self.resolve(statements)
        except _LOOKUP_ERRORS:
            return declaration  # reimpl reports the bad set
        out = [
            Resolved(r.filters, r.ids_A, r.ids_B - r.ids_A, r.within)
            if r.filters and not r.within
            else r
            for r in resolved
        ]
        return cast(
            CollisionFilterDeclaration, _declaration(declaration, (r.statement() for r in out))
        )


class BetweenSkipsOverlap(MutantSceneGraph):
    """ExcludeBetween(A, B) writes A × (B − A): a pair with its B side also in A is missed.

    An implementer who skips "b in A" to avoid self pairs, where ``a != b`` was meant.
    """

    manager_class = _OverlapManager


# ------------------------------------------------------------ invariants
def _sources(
    graph: MutantSceneGraph, context: Context | None, live: set[GeometryId]
) -> dict[GeometryId, str]:
    inspector = graph.real_inspector(context)
    return {g: inspector.GetOwningSourceName(geometry_id=g) for g in live}


class AnchoredInvariantPerSource(_SameFrameMutant):
    """An anchored geometry is invariantly excluded only from the anchored geometry of its
    own source (the world frame looked up in the source's anchored list), not from every
    source's."""

    def invariant_pairs(
        self, context: Context | None, ledger: _SameFrameLedger, live: set[GeometryId]
    ) -> set[Pair]:
        inspector = self.real_inspector(context)
        world = self.world_frame_id()
        anchored = [g for g in live if inspector.GetFrameId(geometry_id=g) == world]
        source = _sources(self, context, set(anchored))
        return {
            _pair(a, b) for a in anchored for b in anchored if a != b and source[a] != source[b]
        }


class ContextRegistrationMissesInvariant(_SameFrameMutant):
    """A geometry registered into a context is not invariantly excluded from the other
    proximity geometry on its frame (the invariant is written to the model's filter)."""

    def invariant_pairs(
        self, context: Context | None, ledger: _SameFrameLedger, live: set[GeometryId]
    ) -> set[Pair]:
        if context is None:
            return set()
        model = set(self.real_inspector(None).GetAllGeometryIds())
        inspector = self.real_inspector(context)
        frame = {g: inspector.GetFrameId(geometry_id=g) for g in live}
        return {
            _pair(a, b)
            for a in live
            if a not in model
            for b in live
            if b != a and frame[b] == frame[a]
        }


# ----------------------------------------------------------------- roles
@dataclass
class _Freed:
    """Per location: the filtered partners of each geometry that lost its proximity role,
    newest last (a free list of slots, reused last-in first-out)."""

    partners: list[list[GeometryId]] = field(default_factory=list)


class SlotReuseInheritsFilters(MutantSceneGraph):
    """A geometry given the proximity role takes the freed slot of the last geometry that
    lost it, and that slot's rows still hold the old geometry's filtered pairs (other frames).

    N.B. The filtered pairs are read through CollisionFiltered when the role goes; they
    come back as persistent pairs.
    """

    def new_memory(self) -> _Freed:
        return _Freed()

    def proximity(self, context: Context | None) -> set[GeometryId]:
        return set(self.real_inspector(context).GetAllGeometryIds(role=Role.kProximity))

    def losing(
        self, context: Context | None, before: set[GeometryId]
    ) -> dict[GeometryId, list[GeometryId]]:
        inspector = self.real_inspector(context)
        out = {}
        for g in before:
            frame = inspector.GetFrameId(geometry_id=g)
            out[g] = [
                h
                for h in before
                if h != g
                and inspector.GetFrameId(geometry_id=h) != frame
                and inspector.CollisionFiltered(geometry_id1=g, geometry_id2=h)
            ]
        return out

    def unrole(self, context: Context | None, action: Callable[[], Any]) -> Any:
        before = self.proximity(context)
        partners = self.losing(context, before)
        result = action()
        memory: _Freed = self.memory_of(context)
        for g in sorted(before - self.proximity(context), key=GeometryId.get_value):
            memory.partners.append(partners[g])
        return result

    def RemoveRole(self, *args: Any, **kwargs: Any) -> int:
        if kwargs.get("role") is not Role.kProximity:
            return super().RemoveRole(*args, **kwargs)
        return cast(
            int,
            self.unrole(
                _context_of(args, kwargs),
                lambda: super(SlotReuseInheritsFilters, self).RemoveRole(*args, **kwargs),
            ),
        )

    def RemoveGeometry(self, *args: Any, **kwargs: Any) -> None:
        self.unrole(
            _context_of(args, kwargs),
            lambda: super(SlotReuseInheritsFilters, self).RemoveGeometry(*args, **kwargs),
        )

    def AssignRole(self, *args: Any, **kwargs: Any) -> None:
        context = _context_of(args, kwargs)
        before = self.proximity(context)
        try:
            super().AssignRole(*args, **kwargs)
        finally:
            memory: _Freed = self.memory_of(context)
            live = self.proximity(context)
            for g in live - before:
                if not memory.partners:
                    break
                again = [h for h in memory.partners.pop() if h in live and h != g]
                if again:
                    declaration = CollisionFilterDeclaration().ExcludeBetween(
                        set_A=GeometrySet(geometry_id=g), set_B=GeometrySet(geometry_ids=again)
                    )
                    apply_persistent(self.manager(context), declaration)


class WorldRoleRemovalCrossesSources(MutantSceneGraph):
    """RemoveRole by the world frame removes the role from every source's anchored geometry,
    not only the calling source's (the world frame's geometry list is shared), and counts them.
    """

    def __init__(self) -> None:
        super().__init__()
        self.source_ids: list[SourceId] = []

    def RegisterSource(self, *args: Any, **kwargs: Any) -> SourceId:
        source_id = super().RegisterSource(*args, **kwargs)
        self.source_ids.append(source_id)
        return source_id

    def RemoveRole(self, *args: Any, **kwargs: Any) -> int:
        count = super().RemoveRole(*args, **kwargs)
        if kwargs.get("frame_id") != self.world_frame_id():
            return count
        context = _context_of(args, kwargs)
        inspector = self.real_inspector(context)
        role = kwargs["role"]
        where = {} if context is None else {"context": context}
        for g in inspector.GetGeometries(frame_id=self.world_frame_id(), role=role):
            for s in self.source_ids:
                if s == kwargs["source_id"]:
                    continue
                try:
                    count += super().RemoveRole(source_id=s, geometry_id=g, role=role, **where)
                except _LOOKUP_ERRORS:
                    continue
        return count


class RemoveRoleCountsAll(MutantSceneGraph):
    """RemoveRole by a frame (not the world) answers the number of geometries on the frame,
    not the number that had the role."""

    def RemoveRole(self, *args: Any, **kwargs: Any) -> int:
        count = super().RemoveRole(*args, **kwargs)
        frame = kwargs.get("frame_id")
        if frame is None or frame == self.world_frame_id():
            return count
        inspector = self.real_inspector(_context_of(args, kwargs))
        return len(inspector.GetGeometries(frame_id=frame))


class ReplaceProximityResetsFilters(MutantSceneGraph):
    """AssignRole(kReplace) of proximity properties, with no transient history there, is a
    removal of the role and a new assignment: the geometry leaves the filter and comes back
    unfiltered (its same-frame invariant pairs come back too)."""

    def AssignRole(self, *args: Any, **kwargs: Any) -> None:
        properties = kwargs.get("properties")
        context = _context_of(args, kwargs)
        where = {} if context is None else {"context": context}
        if (
            kwargs.get("assign") is not RoleAssign.kReplace
            or not isinstance(properties, ProximityProperties)
            or self.real_manager(context).has_transient_history()
        ):
            super().AssignRole(*args, **kwargs)
            return
        try:
            had = self.real_inspector(context).GetProximityProperties(
                geometry_id=kwargs["geometry_id"]
            )
        except _LOOKUP_ERRORS:
            had = None
        if had is None:
            super().AssignRole(*args, **kwargs)
            return
        try:
            super().RemoveRole(
                source_id=kwargs["source_id"],
                geometry_id=kwargs["geometry_id"],
                role=Role.kProximity,
                **where,
            )
        except _LOOKUP_ERRORS:
            super().AssignRole(*args, **kwargs)  # reimpl reports the bad source
            return
        super().AssignRole(**{**kwargs, "assign": RoleAssign.kNew})


# -------------------------------------------------------------- contexts
class SetDefaultContextKeepsFilters(MutantSceneGraph):
    """SetDefaultContext resets a context's scene to the model's but keeps the context's
    collision filter state for the pairs of geometries that are in both."""

    def SetDefaultContext(self, context: Context) -> None:
        inspector = self.real_inspector(context)
        live = sorted(inspector.GetAllGeometryIds(role=Role.kProximity), key=GeometryId.get_value)
        before = {
            (a, b): inspector.CollisionFiltered(geometry_id1=a, geometry_id2=b)
            for i, a in enumerate(live)
            for b in live[i + 1 :]
        }
        super().SetDefaultContext(context)
        inspector = self.real_inspector(context)
        now = set(inspector.GetAllGeometryIds(role=Role.kProximity))
        declaration = CollisionFilterDeclaration()
        changed = False
        for (a, b), filtered in before.items():
            if a not in now or b not in now:
                continue
            if filtered == inspector.CollisionFiltered(geometry_id1=a, geometry_id2=b):
                continue
            changed = True
            one, two = GeometrySet(geometry_id=a), GeometrySet(geometry_id=b)
            if filtered:
                declaration.ExcludeBetween(set_A=one, set_B=two)
            else:
                declaration.AllowBetween(set_A=one, set_B=two)
        if changed:
            apply_persistent(self.manager(context), declaration)


class _FirstContextGraph(MutantSceneGraph):
    def __init__(self) -> None:
        super().__init__()
        self.first_context: Context | None = None

    def collision_filter_manager(self, *args: Any, **kwargs: Any) -> CollisionFilterManager:
        context = _context_of(args, kwargs)
        if context is None:
            return super().collision_filter_manager(*args, **kwargs)
        if self.first_context is None:
            self.first_context = context
        return super().collision_filter_manager(context=self.first_context)


class ContextManagersShareFirst(_FirstContextGraph):
    """collision_filter_manager(context=c) edits the first context a manager was asked for,
    whatever c is (a manager cached on the SceneGraph)."""


class CloneDropsHistory(_TrackingSceneGraph):
    """Context.Clone copies the persistent filters but not the transient history: the
    clone has none, and C there is the persistent base."""

    def on_clone(self, context: Context) -> None:
        _lift(Manager(self, self.real_manager(context), context))


# ----------------------------------------------------------- declarations
class _RemovedMemory:
    def __init__(self) -> None:
        self.removed: set[FilterId] = set()


class _TwiceTrueManager(Manager):
    def RemoveDeclaration(self, filter_id: FilterId) -> bool:
        memory: _RemovedMemory = self.memory
        removed = super().RemoveDeclaration(filter_id)
        if removed:
            memory.removed.add(filter_id)
        return removed or filter_id in memory.removed


class RemoveDeclarationTwiceTrue(MutantSceneGraph):
    """RemoveDeclaration answers True for a FilterId this location already removed (it asks
    "was it ever issued here", not "is it active")."""

    manager_class = _TwiceTrueManager

    def new_memory(self) -> _RemovedMemory:
        return _RemovedMemory()


class _OffByOneManager(Manager):
    def RemoveDeclaration(self, filter_id: FilterId) -> bool:
        current = self.current(filter_id)
        history = self.active_history()
        if current not in history or current == history[-1]:
            return super().RemoveDeclaration(filter_id)
        younger = history[history.index(current) + 1]
        _lift(self)
        replays: list[Replay] = []
        for old in history:
            if old == current:
                continue
            kept = self.graph.transients[current if old == younger else old]
            replays.append((old, kept, kept))
        _reapply(self, replays)
        return True


class RemoveDeclarationOffByOne(MutantSceneGraph):
    """RemoveDeclaration of a declaration with a younger one erases the younger one's
    statements (history index + 1); the FilterIds' IsActive answers are right."""

    manager_class = _OffByOneManager


# ------------------------------------------------------------------- table
BLIND_MUTANTS: tuple[Mutant, ...] = (
    Mutant(
        "allow_within_clears_rows",
        "AllowWithin(S) allows S with every geometry, not only within S.",
        AllowWithinClearsRows,
    ),
    Mutant(
        "between_skips_overlap",
        "ExcludeBetween(A, B) leaves out the pairs whose B geometry is also in A.",
        BetweenSkipsOverlap,
    ),
    Mutant(
        "anchored_invariant_per_source",
        "Anchored geometries of different sources are not invariantly excluded from each other.",
        AnchoredInvariantPerSource,
    ),
    Mutant(
        "context_registration_misses_invariant",
        "A geometry registered into a context is not invariantly excluded from its frame's "
        "other proximity geometries there.",
        ContextRegistrationMissesInvariant,
    ),
    Mutant(
        "slot_reuse_inherits_filters",
        "A geometry getting the proximity role inherits the filtered pairs of the last geometry "
        "that lost it (a reused slot's stale rows).",
        SlotReuseInheritsFilters,
    ),
    Mutant(
        "world_role_removal_crosses_sources",
        "RemoveRole by the world frame also removes the role from other sources' anchored "
        "geometry.",
        WorldRoleRemovalCrossesSources,
    ),
    Mutant(
        "remove_role_counts_all",
        "RemoveRole by a frame answers the number of geometries on the frame, not how many had "
        "the role.",
        RemoveRoleCountsAll,
    ),
    Mutant(
        "replace_proximity_resets_filters",
        "AssignRole(kReplace) of proximity properties drops the geometry's filtered pairs.",
        ReplaceProximityResetsFilters,
    ),
    Mutant(
        "set_default_context_keeps_filters",
        "SetDefaultContext resets the scene but keeps the context's collision filters.",
        SetDefaultContextKeepsFilters,
    ),
    Mutant(
        "context_managers_share_first",
        "Every context's collision_filter_manager edits the first context one was made for.",
        ContextManagersShareFirst,
    ),
    Mutant(
        "clone_drops_history",
        "Context.Clone leaves out the transient history: the clone has only the persistent "
        "filters.",
        CloneDropsHistory,
    ),
    Mutant(
        "remove_declaration_twice_true",
        "RemoveDeclaration answers True again for a declaration already removed.",
        RemoveDeclarationTwiceTrue,
    ),
    Mutant(
        "remove_declaration_off_by_one",
        "RemoveDeclaration of a declaration with a younger one erases the younger one's "
        "statements instead.",
        RemoveDeclarationOffByOne,
    ),
)
