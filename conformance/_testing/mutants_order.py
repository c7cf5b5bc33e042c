"""Mutants whose bug needs an order of events *across* locations (issue 30).

Each one is reimpl with one deliberate bug (as ``conformance._testing.mutants``,
whose ``MUTANTS`` registry lists them), written with public calls only. Each
answers exactly as reimpl does until its combination happens: a context made
right after a model edit, a context copied under the model's history, a
clone of a context that holds a failed Apply's leftover, a clone's inherited
declaration removed there, geometry registered into a clone then named by
frame, roles removed by frame and assigned again in a context, five
disagreeing transient declarations with the oldest removed.

``tests/test_mutants.py`` holds each one's witness (pydrake's exact value).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any, cast

from conformance._testing.mutants_basic import (
    Manager,
    Mutant,
    MutantSceneGraph,
    Pair,
    Statement,
    _context_of,
    _declaration,
    _pair,
    _statements,
)
from conformance._testing.mutants_state import (
    Replay,
    _as_declaration,
    _live,
    _ReplayManager,
    _RewritingManager,
    _TrackingSceneGraph,
)
from reimpl.geometry import (
    CollisionFilterDeclaration,
    FilterId,
    GeometryId,
    GeometrySet,
    ProximityProperties,
    Role,
    RoleAssign,
    SceneGraphInspector,
)
from reimpl.systems.framework import Context

__all__ = ["ORDER_MUTANTS"]

#: Raised by reimpl for a call it rejects.
_REJECTED = (RuntimeError, ValueError, IndexError, KeyError)
#: The SceneGraph calls that edit geometry (a registration, a removal, a role).
_GEOMETRY_EDITS = (
    "RegisterGeometry",
    "RegisterAnchoredGeometry",
    "RemoveGeometry",
    "AssignRole",
    "RemoveRole",
)


# ----------------------------------------------------------------- helpers
def _statuses(
    inspector: SceneGraphInspector, ids: Iterable[GeometryId] | None = None
) -> dict[Pair, bool]:
    """CollisionFiltered of every pair of proximity geometries (of ``ids``, if given)."""
    live = sorted(inspector.GetAllGeometryIds(role=Role.kProximity), key=GeometryId.get_value)
    if ids is not None:
        wanted = set(ids)
        live = [g for g in live if g in wanted]
    return {
        _pair(a, b): inspector.CollisionFiltered(geometry_id1=a, geometry_id2=b)
        for i, a in enumerate(live)
        for b in live[i + 1 :]
    }


def _set_statuses(manager: Any, statuses: dict[Pair, bool]) -> None:
    """Applies, persistently, a declaration that gives each pair its status."""
    declaration = CollisionFilterDeclaration()
    for (a, b), filtered in statuses.items():
        one, other = GeometrySet(geometry_id=a), GeometrySet(geometry_id=b)
        if filtered:
            declaration.ExcludeBetween(set_A=one, set_B=other)
        else:
            declaration.AllowBetween(set_A=one, set_B=other)
    manager.Apply(declaration=declaration)


class _EditNotingSceneGraph(MutantSceneGraph):
    """Calls ``geometry_edited(context)`` after every geometry edit (``_GEOMETRY_EDITS``)."""

    def geometry_edited(self, context: Context | None) -> None:
        pass

    def RegisterGeometry(self, *args: Any, **kwargs: Any) -> Any:
        result = super().RegisterGeometry(*args, **kwargs)
        self.geometry_edited(_context_of(args, kwargs))
        return result

    def RegisterAnchoredGeometry(self, *args: Any, **kwargs: Any) -> Any:
        result = super().RegisterAnchoredGeometry(*args, **kwargs)
        self.geometry_edited(None)
        return result

    def RemoveGeometry(self, *args: Any, **kwargs: Any) -> Any:
        result = super().RemoveGeometry(*args, **kwargs)
        self.geometry_edited(_context_of(args, kwargs))
        return result

    def AssignRole(self, *args: Any, **kwargs: Any) -> Any:
        result = super().AssignRole(*args, **kwargs)
        self.geometry_edited(_context_of(args, kwargs))
        return result

    def RemoveRole(self, *args: Any, **kwargs: Any) -> Any:
        result = super().RemoveRole(*args, **kwargs)
        self.geometry_edited(_context_of(args, kwargs))
        return result


# ---------------------------------------- a context made after a model edit
@dataclass
class _Snapshot:
    """The model's filters before its first Apply since the last geometry edit."""

    statuses: dict[Pair, bool] | None = None


class _SnapshotManager(Manager):
    def Apply(self, declaration: CollisionFilterDeclaration) -> None:
        memory: _Snapshot = self.graph.memory_of(None)
        fresh = self.context is None and memory.statuses is None
        if fresh and not self.inner.has_transient_history():
            memory.statuses = _statuses(self.inspector())
        super().Apply(declaration)


class ContextAfterApplyStale(_EditNotingSceneGraph):
    """CreateDefaultContext copies a model state cached at the last geometry edit.

    A context made after a model Apply with no geometry edit in between has
    the filters from before that Apply (the cache is refreshed by geometry
    edits only). Reached by ``apply@model`` then ``create_context``.
    """

    manager_class = _SnapshotManager

    def new_memory(self) -> _Snapshot:
        return _Snapshot()

    def geometry_edited(self, context: Context | None) -> None:
        if context is None:
            self.memory_of(None).statuses = None

    def CreateDefaultContext(self) -> Context:
        context = super().CreateDefaultContext()
        cached: dict[Pair, bool] | None = self.memory_of(None).statuses
        manager = self.real_manager(context)
        if cached is not None and not manager.has_transient_history():
            now = _statuses(self.real_inspector(context))
            _set_statuses(manager, {p: s for p, s in cached.items() if now.get(p) != s})
        return context


@dataclass
class _Removed:
    """The model's last removed transient declaration, until the next edit there."""

    filter_id: FilterId | None = None


class _RemovalNotingManager(Manager):
    def RemoveDeclaration(self, filter_id: FilterId) -> bool:
        current = self.current(filter_id)
        removed = super().RemoveDeclaration(filter_id)
        if self.context is None:
            memory: _Removed = self.graph.memory_of(None)
            memory.filter_id = current if removed and current in self.graph.transients else None
        return removed

    def Apply(self, declaration: CollisionFilterDeclaration) -> None:
        self.forget()
        super().Apply(declaration)

    def ApplyTransient(self, declaration: CollisionFilterDeclaration) -> FilterId:
        self.forget()
        return super().ApplyTransient(declaration)

    def forget(self) -> None:
        if self.context is None:
            self.graph.memory_of(None).filter_id = None


class ContextAfterRemovalStale(_EditNotingSceneGraph):
    """CreateDefaultContext right after a model RemoveDeclaration copies the model as it
    was before the removal: the removed declaration is active in the new context.

    Reached by ``remove_declaration@model`` then ``create_context``.
    """

    manager_class = _RemovalNotingManager

    def new_memory(self) -> _Removed:
        return _Removed()

    def geometry_edited(self, context: Context | None) -> None:
        if context is None:
            self.memory_of(None).filter_id = None

    def CreateDefaultContext(self) -> Context:
        context = super().CreateDefaultContext()
        old: FilterId | None = self.memory_of(None).filter_id
        if old is not None:
            manager = Manager(self, self.real_manager(context), context)
            live = _live(manager)
            resolved = tuple(r.kept(live.__contains__) for r in self.transients[old])
            new = manager.inner.ApplyTransient(declaration=_as_declaration(resolved))
            self.transients[new] = resolved
            self.successors.setdefault(old, []).append(new)
        return context


# ------------------------------------------- contexts copied under history
class _OwnHistoryManager(Manager):
    def RemoveDeclaration(self, filter_id: FilterId) -> bool:
        graph = cast(CopyUnderHistoryDropsOwn, self.graph)
        inherited = graph.inherited.get(self.context) if self.context is not None else None
        current = self.current(filter_id)
        removed = super().RemoveDeclaration(filter_id)
        if removed and inherited is not None and current in inherited:
            for own in reversed(self.active_history()):
                if own not in inherited:
                    self.inner.RemoveDeclaration(filter_id=own)
        return removed


class CopyUnderHistoryDropsOwn(MutantSceneGraph):
    """In a context made while the model had transient history, removing an inherited
    declaration also removes the context's own transient declarations.

    Reached by ``create_context`` under model history, ``apply_transient`` in the
    context, then ``remove_declaration`` of an inherited one there.
    """

    manager_class = _OwnHistoryManager

    def __init__(self) -> None:
        super().__init__()
        self.inherited: dict[Context, frozenset[FilterId]] = {}

    def CreateDefaultContext(self) -> Context:
        context = super().CreateDefaultContext()
        history = Manager(self, self.real_manager(context), context).active_history()
        if history:
            self.inherited[context] = frozenset(history)
        return context


# ------------------------------------------------------------------ clones
@dataclass(frozen=True)
class _Leftover:
    """What a failed Apply left: the pairs it changed, each with its status before."""

    context: Context | None
    before: dict[Pair, bool]


class _LeftoverManager(Manager):
    def Apply(self, declaration: CollisionFilterDeclaration) -> None:
        inspector = self.inspector()
        mentioned: set[GeometryId] = set()
        for statement in _statements(declaration):
            try:
                for resolved in self.resolve([statement]):
                    mentioned |= resolved.mentioned()
            except _REJECTED:
                break
        before = _statuses(inspector, mentioned)
        try:
            super().Apply(declaration)
        except _REJECTED:
            after = _statuses(self.inspector(), mentioned)
            changed = {p: s for p, s in before.items() if after.get(p) != s}
            if changed:
                graph = cast(CloneDropsPartialApply, self.graph)
                graph.leftovers.append(_Leftover(self.context, changed))
            raise


class CloneDropsPartialApply(_TrackingSceneGraph):
    """A clone is rebuilt from the declarations that completed: what a failed Apply wrote
    before it raised (its leftover) is not in the clone.

    Reached by a failed ``apply`` in a context (a later statement names an unknown
    geometry), then ``clone_context`` of it.
    """

    manager_class = _LeftoverManager

    def __init__(self) -> None:
        super().__init__()
        self.leftovers: list[_Leftover] = []

    def on_clone(self, context: Context) -> None:
        manager = self.real_manager(context)
        if manager.has_transient_history():
            return
        clone = self.real_inspector(context)
        for leftover in self.leftovers:
            if leftover.context is None:
                continue
            origin = self.real_inspector(leftover.context)
            pairs = list(leftover.before)
            try:
                same = all(
                    clone.CollisionFiltered(geometry_id1=a, geometry_id2=b)
                    == origin.CollisionFiltered(geometry_id1=a, geometry_id2=b)
                    for a, b in pairs
                )
            except _REJECTED:
                continue
            if same:
                _set_statuses(manager, leftover.before)


class _CloneRemovalManager(Manager):
    def RemoveDeclaration(self, filter_id: FilterId) -> bool:
        graph = cast(CloneKeepsRemovedInherited, self.graph)
        inherited = graph.inherited.get(self.context) if self.context is not None else None
        current = self.current(filter_id)
        if (
            inherited is not None
            and current in inherited
            and self.inner.IsActive(filter_id=current)
        ):
            return True
        return super().RemoveDeclaration(filter_id)


class CloneKeepsRemovedInherited(_TrackingSceneGraph):
    """RemoveDeclaration in a clone of a declaration the clone inherited returns true and
    changes nothing: it stays active, its filters stay.

    Reached by ``clone_context`` of a context with history, then ``remove_declaration``
    of an inherited declaration in the clone.
    """

    manager_class = _CloneRemovalManager

    def __init__(self) -> None:
        super().__init__()
        self.inherited: dict[Context, frozenset[FilterId]] = {}

    def on_clone(self, context: Context) -> None:
        history = Manager(self, self.real_manager(context), context).active_history()
        self.inherited[context] = frozenset(history)


class _CloneFrameManager(_RewritingManager):
    def rewrite(self, declaration: CollisionFilterDeclaration) -> CollisionFilterDeclaration:
        graph = cast(CloneFramesResolveAtCloneTime, self.graph)
        known = graph.known.get(self.context) if self.context is not None else None
        statements = _statements(declaration)
        if known is None or not any(s.num_frames() for st in statements for s in st.sets()):
            return declaration
        try:
            self.resolve(statements)
        except _REJECTED:
            return declaration
        inspector = self.inspector()

        def at_clone_time(geometry_set: GeometrySet) -> GeometrySet:
            ids = set(geometry_set.geometry_ids())
            for frame_id in geometry_set.frame_ids():
                on_frame = inspector.GetGeometryIds(
                    geometry_set=GeometrySet(frame_id=frame_id), role=Role.kProximity
                )
                ids |= set(on_frame) & known
            return GeometrySet(geometry_ids=sorted(ids, key=GeometryId.get_value))

        mapped: list[Statement] = [s.mapped(at_clone_time) for s in statements]
        return cast(CollisionFilterDeclaration, _declaration(declaration, mapped))


class CloneFramesResolveAtCloneTime(_TrackingSceneGraph):
    """In a clone, a frame in a GeometrySet resolves to the geometries it had when the clone
    was made: geometry registered into the clone afterwards is missed.

    Reached by ``clone_context``, ``register_geometries`` into the clone on a frame,
    then a declaration naming that frame there.
    """

    manager_class = _CloneFrameManager

    def __init__(self) -> None:
        super().__init__()
        self.known: dict[Context, frozenset[GeometryId]] = {}

    def on_clone(self, context: Context) -> None:
        self.known[context] = frozenset(self.real_inspector(context).GetAllGeometryIds())

    def RegisterGeometry(self, *args: Any, **kwargs: Any) -> Any:
        self.see(_context_of(args, kwargs))  # a clone is known before it changes
        return super().RegisterGeometry(*args, **kwargs)


# -------------------------------------------- roles by frame, in a context
@dataclass
class _Dropped:
    """Per context: geometries whose proximity role RemoveRole by frame took there."""

    ids: set[GeometryId] = field(default_factory=set)


class ContextReassignTakesModelFilters(MutantSceneGraph):
    """AssignRole of proximity in a context, to a geometry whose role was removed there by
    frame, gives it back the filtered pairs it has in the model.

    pydrake: the geometry starts unfiltered there (but for the invariants). Reached by
    ``remove_role`` by frame in a context, a filter at the model, then ``assign_role``
    in the context.
    """

    def new_memory(self) -> _Dropped:
        return _Dropped()

    def RemoveRole(self, *args: Any, **kwargs: Any) -> int:
        context = _context_of(args, kwargs)
        if context is None or "frame_id" not in kwargs:
            return super().RemoveRole(*args, **kwargs)
        return self.remove_role_noting_unroled(context, *args, **kwargs)

    def AssignRole(self, *args: Any, **kwargs: Any) -> None:
        context = _context_of(args, kwargs)
        super().AssignRole(*args, **kwargs)
        g = kwargs.get("geometry_id")
        if (
            context is None
            or not isinstance(kwargs.get("properties"), ProximityProperties)
            or kwargs.get("assign") is RoleAssign.kReplace
            or g not in self.memory_of(context).ids
        ):
            return
        self.memory_of(context).ids.discard(g)
        manager = self.real_manager(context)
        if manager.has_transient_history():
            return
        here, model = self.real_inspector(context), self.real_inspector(None)
        model_proximity = set(model.GetAllGeometryIds(role=Role.kProximity))
        if g not in model_proximity:
            return
        partners = [
            h
            for h in here.GetAllGeometryIds(role=Role.kProximity)
            if h != g
            and h in model_proximity
            and model.CollisionFiltered(geometry_id1=g, geometry_id2=h)
            and not here.CollisionFiltered(geometry_id1=g, geometry_id2=h)
        ]
        if partners:
            _set_statuses(manager, {_pair(g, h): True for h in partners})


# ------------------------------------------- five disagreeing declarations
#: The history ring's slots: a fifth declaration wraps into slot 0.
_SLOTS = 4


class _RingReplayManager(_ReplayManager):
    def replays(self, remaining: list[FilterId], removed_at: int) -> list[Replay]:
        out = super().replays(remaining, removed_at)
        if removed_at == 0 and len(out) >= _SLOTS:
            return [out[-1], *out[:-1]]
        return out


class RingReplayAfterOldestRemoved(MutantSceneGraph):
    """With five or more active transient declarations, removing the oldest replays the
    rest from the ring's slot 0, where the newest wrapped: the newest first.

    Differs once the newest and an older one disagree on a pair. Reached by five
    declarations on the same pairs, then ``remove_declaration`` of the oldest.
    """

    manager_class = _RingReplayManager


# ------------------------------------------------------------------- table
ORDER_MUTANTS: tuple[Mutant, ...] = (
    Mutant(
        "context_after_apply_stale",
        "A context made after a model Apply, with no geometry edit in between, has the "
        "filters from before that Apply.",
        ContextAfterApplyStale,
    ),
    Mutant(
        "context_after_removal_stale",
        "A context made right after a model RemoveDeclaration has the removed declaration active.",
        ContextAfterRemovalStale,
    ),
    Mutant(
        "copy_under_history_drops_own",
        "In a context made under the model's transient history, removing an inherited "
        "declaration also removes the context's own.",
        CopyUnderHistoryDropsOwn,
    ),
    Mutant(
        "clone_drops_partial_apply",
        "A clone of a context lacks what a failed Apply wrote there before it raised.",
        CloneDropsPartialApply,
    ),
    Mutant(
        "clone_keeps_removed_inherited",
        "Removing an inherited transient declaration in a clone returns true and changes nothing.",
        CloneKeepsRemovedInherited,
    ),
    Mutant(
        "clone_frames_resolve_at_clone_time",
        "In a clone, a frame resolves to the geometries it had when the clone was made.",
        CloneFramesResolveAtCloneTime,
    ),
    Mutant(
        "context_reassign_takes_model_filters",
        "A geometry given the proximity role again in a context, after RemoveRole by frame "
        "there, gets the model's filtered pairs.",
        ContextReassignTakesModelFilters,
    ),
    Mutant(
        "ring_replay_after_oldest_removed",
        "With five or more transient declarations, removing the oldest replays the newest first.",
        RingReplayAfterOldestRemoved,
    ),
)
