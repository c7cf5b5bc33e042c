"""Mutants whose bug needs a reached state: a size, a sequence, a context, a replay order.

Each one is reimpl with one deliberate bug (as ``conformance._testing.mutants``,
whose ``MUTANTS`` registry lists them), written with public calls only. Below
the state its bug needs, each answers exactly as reimpl does; its docstring
names the ``conformance._fuzz.coverage.FEATURES`` entry that reaches it.

- size-dependent: a location past 16 proximity geometries;
- sequence-dependent: a fifth active declaration, a removal out of order, a
  removal then an apply, a filter edit after a RemoveRole by frame and a
  re-assignment;
- context-dependent: clones of a context with history, default contexts of a
  model with history;
- replay-order-dependent: how RemoveDeclaration replays what remains.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any, cast

from conformance._testing.mutants_basic import (
    Inspector,
    Manager,
    Mutant,
    MutantSceneGraph,
    NoSameFrameInvariant,
    Pair,
    Resolved,
    _context_of,
    _declaration,
    _SameFrameLedger,
    _statements,
)
from reimpl.geometry import (
    CollisionFilterDeclaration,
    CollisionFilterManager,
    FilterId,
    GeometryId,
    GeometrySet,
    Role,
    SceneGraphInspector,
)
from reimpl.systems.framework import Context, OutputPort

__all__ = ["STATE_MUTANTS"]

#: Raised by reimpl for a set naming something unknown: left for reimpl to report.
_LOOKUP_ERRORS = (RuntimeError, ValueError, IndexError, KeyError)


# ----------------------------------------------------------------- helpers
def _proximity(inspector: SceneGraphInspector) -> list[GeometryId]:
    """The proximity geometries of a location, by id value (their slots in a dense table)."""
    return sorted(inspector.GetAllGeometryIds(role=Role.kProximity), key=GeometryId.get_value)


def _as_declaration(resolved: Iterable[Resolved]) -> Any:
    return _declaration(CollisionFilterDeclaration(), (r.statement() for r in resolved))


def _live(manager: Manager) -> set[GeometryId]:
    return set(manager.inspector().GetAllGeometryIds(role=Role.kProximity))


#: One declaration to replay: (its old FilterId, what is applied now, what is remembered).
Replay = tuple[FilterId, tuple[Resolved, ...], tuple[Resolved, ...]]


def _lift(manager: Manager) -> list[FilterId]:
    """Removes the active transient declarations here, newest first; returns them oldest first."""
    history = manager.active_history()
    for filter_id in reversed(history):
        manager.inner.RemoveDeclaration(filter_id=filter_id)
    return history


def _reapply(manager: Manager, replays: Iterable[Replay], *, link: bool = True) -> None:
    """Applies each replay as a new transient declaration (to the geometries still there).

    With ``link`` the new FilterId stands in for the old one from then on.
    """
    live = _live(manager)
    for old, applied, remembered in replays:
        new = manager.inner.ApplyTransient(
            declaration=_as_declaration(r.kept(live.__contains__) for r in applied)
        )
        manager.graph.transients[new] = tuple(r.kept(live.__contains__) for r in remembered)
        if link:
            manager.graph.successors.setdefault(old, []).append(new)


class _RewritingManager(Manager):
    """Hands reimpl ``rewrite(declaration)`` in Apply and ApplyTransient."""

    def rewrite(self, declaration: CollisionFilterDeclaration) -> CollisionFilterDeclaration:
        return declaration

    def Apply(self, declaration: CollisionFilterDeclaration) -> None:
        super().Apply(self.rewrite(declaration))

    def ApplyTransient(self, declaration: CollisionFilterDeclaration) -> FilterId:
        return super().ApplyTransient(self.rewrite(declaration))


# ------------------------------------------------------------------- sizes
#: The width of one word of a dense filter row.
_WORD = 16


class _CandidateScanInspector(Inspector):
    def GetCollisionCandidates(self) -> set[Pair]:
        slots = _proximity(self.inner)
        seen = set(slots[:_WORD])
        return {p for p in super().GetCollisionCandidates() if p[0] in seen and p[1] in seen}


class CandidateScanOneWord(MutantSceneGraph):
    """GetCollisionCandidates scans each row through one 16-bit column word.

    Pairs with a geometry past the 16th proximity slot (by id) are never
    reported; CollisionFiltered answers right. Reached by ``proximity>16``.
    """

    inspector_class = _CandidateScanInspector


class InvariantWordOverflow(NoSameFrameInvariant):
    """The same-frame invariant is written through a 16-bit row mask at registration.

    A geometry past the 16th proximity slot of its location (by id) is not
    invariantly excluded from the proximity geometries on its frame (nor,
    anchored, from the other anchored ones), unless a declaration filters the
    pair. Reached by ``proximity>16``.
    """

    def invariant_pairs(
        self, context: Context | None, ledger: _SameFrameLedger, live: set[GeometryId]
    ) -> set[Pair]:
        past = set(sorted(live, key=GeometryId.get_value)[_WORD:])
        pairs = super().invariant_pairs(context, ledger, live)
        return {p for p in pairs if p[0] in past or p[1] in past}


# --------------------------------------------------------------- sequences
#: The capacity of the history ring.
_RING = 4


class _RingManager(Manager):
    def ApplyTransient(self, declaration: CollisionFilterDeclaration) -> FilterId:
        filter_id = super().ApplyTransient(declaration)
        history = self.active_history()
        if len(history) > _RING:
            oldest = history[0]
            folded = _as_declaration(
                r.kept(_live(self).__contains__) for r in self.graph.transients[oldest]
            )
            self.lifting_history(lambda: self.inner.Apply(declaration=folded), skip=oldest)
        return filter_id


class HistoryRingOfFour(MutantSceneGraph):
    """The transient history is a ring of 4 deltas: a fifth folds the oldest into the base.

    The filters stay right, but the oldest declaration is no longer active and
    cannot be removed. Reached by ``transients>=5``.
    """

    manager_class = _RingManager


@dataclass
class _FreeList:
    """Per location: FilterIds of removed declarations, to hand out again."""

    free: list[FilterId] = field(default_factory=list)


class _RecyclingManager(Manager):
    def RemoveDeclaration(self, filter_id: FilterId) -> bool:
        removed = super().RemoveDeclaration(filter_id)
        if removed:
            self.memory.free.append(filter_id)
        return removed

    def ApplyTransient(self, declaration: CollisionFilterDeclaration) -> FilterId:
        filter_id = super().ApplyTransient(declaration)
        free: list[FilterId] = self.memory.free
        if not free:
            return filter_id
        recycled = free.pop()
        self.graph.successors.setdefault(recycled, []).append(filter_id)
        return recycled


class FilterIdsRecycled(MutantSceneGraph):
    """A location hands out the FilterId of its last removed declaration again.

    So after a removal and an apply there, the removed declaration's FilterId
    is active again (and names the new one). Reached by
    ``remove_declaration@model`` (or ``@context``) then ``apply_transient``.
    """

    manager_class = _RecyclingManager

    def new_memory(self) -> _FreeList:
        return _FreeList()


@dataclass
class _FrameIndex:
    """Per location: geometries dropped from the frame index by RemoveRole by frame."""

    dropped: set[GeometryId] = field(default_factory=set)


class _FrameIndexManager(_RewritingManager):
    def rewrite(self, declaration: CollisionFilterDeclaration) -> CollisionFilterDeclaration:
        dropped: set[GeometryId] = self.memory.dropped
        statements = _statements(declaration)
        if not dropped or not any(s.num_frames() for st in statements for s in st.sets()):
            return declaration
        inspector = self.inspector()

        def indexed(geometry_set: GeometrySet) -> GeometrySet:
            ids = set(geometry_set.geometry_ids())
            for frame_id in geometry_set.frame_ids():
                on_frame = inspector.GetGeometryIds(
                    geometry_set=GeometrySet(frame_id=frame_id), role=Role.kProximity
                )
                ids |= set(on_frame) - dropped
            return GeometrySet(geometry_ids=sorted(ids, key=GeometryId.get_value))

        try:
            self.resolve(statements)
        except _LOOKUP_ERRORS:
            return declaration
        return cast(
            CollisionFilterDeclaration,
            _declaration(declaration, (s.mapped(indexed) for s in statements)),
        )


class FrameIndexStaleAfterRemoveRole(MutantSceneGraph):
    """RemoveRole by frame drops the frame's geometries from a frame index; AssignRole
    does not put them back.

    A statement naming the frame then misses the geometries that got the
    proximity role back (named by id, they resolve). Reached by
    ``reassigned_by_frame_then_filter``.
    """

    manager_class = _FrameIndexManager

    def new_memory(self) -> _FrameIndex:
        return _FrameIndex()

    def RemoveRole(self, *args: Any, **kwargs: Any) -> int:
        context = _context_of(args, kwargs)
        if "frame_id" not in kwargs or kwargs.get("role") not in (
            Role.kProximity,
            Role.kUnassigned,
        ):
            return super().RemoveRole(*args, **kwargs)
        before = set(self.real_inspector(context).GetAllGeometryIds(role=Role.kProximity))
        count = super().RemoveRole(*args, **kwargs)
        after = set(self.real_inspector(context).GetAllGeometryIds(role=Role.kProximity))
        index: _FrameIndex = self.memory_of(context)
        index.dropped |= before - after
        return count


# ------------------------------------------------------------------ replay
class _ReplayManager(Manager):
    """RemoveDeclaration re-derives C: removes every declaration, replays ``replays``."""

    def replays(self, remaining: list[FilterId], removed_at: int) -> list[Replay]:
        return [(f, self.graph.transients[f], self.graph.transients[f]) for f in remaining]

    def RemoveDeclaration(self, filter_id: FilterId) -> bool:
        current = self.current(filter_id)
        if current not in self.graph.transients or not self.inner.IsActive(filter_id=current):
            return self.inner.RemoveDeclaration(filter_id=current)
        history = _lift(self)
        at = history.index(current)
        _reapply(self, self.replays(history[:at] + history[at + 1 :], at))
        return True


class _ReverseReplayManager(_ReplayManager):
    def replays(self, remaining: list[FilterId], removed_at: int) -> list[Replay]:
        return super().replays(remaining[::-1], removed_at)


class ReplayNewestFirst(MutantSceneGraph):
    """RemoveDeclaration replays the remaining declarations newest first.

    Differs once two remaining declarations disagree on a pair. Reached by
    ``transients>=5`` and ``out_of_order_removal`` (two or more remain).
    """

    manager_class = _ReverseReplayManager


class _SkipOldestManager(_ReplayManager):
    def replays(self, remaining: list[FilterId], removed_at: int) -> list[Replay]:
        out = super().replays(remaining, removed_at)
        return [
            (old, () if i == 0 else applied, kept) for i, (old, applied, kept) in enumerate(out)
        ]


class ReplaySkipsOldest(MutantSceneGraph):
    """RemoveDeclaration replays the remaining declarations from index 1 (index 0 taken
    for the base): the oldest stays active without effect.

    Reached by a removal that leaves 1 or more declarations (``stacked_transients``,
    ``out_of_order_removal``).
    """

    manager_class = _SkipOldestManager


class _SkipSuccessorManager(_ReplayManager):
    def replays(self, remaining: list[FilterId], removed_at: int) -> list[Replay]:
        out = super().replays(remaining, removed_at)
        return [
            (old, () if i == removed_at else applied, kept)
            for i, (old, applied, kept) in enumerate(out)
        ]


class EraseSkipsSuccessor(MutantSceneGraph):
    """Removing a declaration from the middle erases it, then replays from the next index:
    the declaration that moved into its slot is skipped (active, without effect until
    the next removal).

    Removing the newest replays everything. Reached by ``out_of_order_removal``.
    """

    manager_class = _SkipSuccessorManager


class _AllowFirstManager(_ReplayManager):
    def replays(self, remaining: list[FilterId], removed_at: int) -> list[Replay]:
        return [
            (old, tuple(sorted(applied, key=lambda r: r.filters)), kept)
            for old, applied, kept in super().replays(remaining, removed_at)
        ]


class ReplayAllowsBeforeExcludes(MutantSceneGraph):
    """A replayed delta writes its Allow statements before its Exclude ones.

    So on RemoveDeclaration a remaining declaration that excluded, then allowed
    a pair, comes back with the pair filtered. Reached by a removal leaving a
    declaration with both kinds (``stacked_transients``, ``out_of_order_removal``).
    """

    manager_class = _AllowFirstManager


# ---------------------------------------------------------------- contexts
class _TrackingSceneGraph(MutantSceneGraph):
    """Notes every context it is handed, in order; a context it did not make is a clone.

    ``made``: the contexts CreateDefaultContext made (or SetDefaultContext reset).
    ``on_clone`` runs the first time a clone is seen.
    """

    def __init__(self) -> None:
        super().__init__()
        self.seen: list[Context] = []
        self.made: list[Context] = []

    def see(self, context: Context | None) -> None:
        if context is None or any(c is context for c in self.seen):
            return
        self.seen.append(context)
        if not any(c is context for c in self.made):
            self.on_clone(context)

    def on_clone(self, context: Context) -> None:
        pass

    def collision_filter_manager(self, *args: Any, **kwargs: Any) -> CollisionFilterManager:
        self.see(_context_of(args, kwargs))
        return super().collision_filter_manager(*args, **kwargs)

    def get_query_output_port(self) -> OutputPort:
        return cast(OutputPort, _SeeingPort(self, super().get_query_output_port()))

    def CreateDefaultContext(self) -> Context:
        context = super().CreateDefaultContext()
        self.made.append(context)
        self.see(context)
        return context

    def SetDefaultContext(self, context: Context) -> None:
        self.see(context)
        super().SetDefaultContext(context)
        if not any(c is context for c in self.made):
            self.made.append(context)


class _SeeingPort:
    def __init__(self, graph: _TrackingSceneGraph, inner: Any) -> None:
        self.graph, self.inner = graph, inner

    def __getattr__(self, name: str) -> Any:
        return getattr(self.inner, name)

    def Eval(self, context: Context) -> Any:
        self.graph.see(context)
        return self.inner.Eval(context)


class _SharedRemovalManager(Manager):
    def RemoveDeclaration(self, filter_id: FilterId) -> bool:
        current = self.current(filter_id)
        removed = super().RemoveDeclaration(filter_id)
        graph = cast(_TrackingSceneGraph, self.graph)
        if removed:
            for other in [None, *graph.seen]:
                inner = graph.real_manager(other)
                if other is not self.context and inner.IsActive(filter_id=current):
                    inner.RemoveDeclaration(filter_id=current)
        return removed


class CopiesShareHistory(_TrackingSceneGraph):
    """A copied context (a clone, or a default context of a model with history) copies
    the filters but shares the history's deltas with where it was copied from: removing
    an inherited declaration in one removes it in both.

    Reached by ``clone_with_history_edited_both``, and by ``model_edit_after_context``
    (a removal at the model after a context was made under its history).
    """

    manager_class = _SharedRemovalManager


class CloneRenumbersHistory(_TrackingSceneGraph):
    """Context.Clone copies the history with new FilterIds: the inherited declarations'
    FilterIds are not active in the clone (the filters are right).

    Reached by ``clone_with_history``.
    """

    def on_clone(self, context: Context) -> None:
        manager = Manager(self, self.real_manager(context), context)
        history = _lift(manager)
        _reapply(
            manager, ((f, self.transients[f], self.transients[f]) for f in history), link=False
        )


class DefaultContextFlattensHistory(MutantSceneGraph):
    """CreateDefaultContext copies the model's composite filter into the new context's
    base: the model's active transient declarations are not active there, nor removable
    (the filters are right).

    Reached by ``create_context@model`` while the model has transient declarations.
    """

    def CreateDefaultContext(self) -> Context:
        context = super().CreateDefaultContext()
        manager = Manager(self, self.real_manager(context), context)
        history = _lift(manager)
        live = _live(manager)
        for filter_id in history:
            resolved = (r.kept(live.__contains__) for r in self.transients[filter_id])
            manager.inner.Apply(declaration=_as_declaration(resolved))
        return context


# ------------------------------------------------------------------- table
STATE_MUTANTS: tuple[Mutant, ...] = (
    Mutant(
        "candidate_scan_one_word",
        "GetCollisionCandidates never reports a pair with a geometry past the 16th proximity slot.",
        CandidateScanOneWord,
    ),
    Mutant(
        "invariant_word_overflow",
        "A geometry past the 16th proximity slot is not invariantly excluded from the "
        "proximity geometries on its frame.",
        InvariantWordOverflow,
    ),
    Mutant(
        "history_ring_of_four",
        "A fifth active transient declaration folds the oldest into the persistent base.",
        HistoryRingOfFour,
    ),
    Mutant(
        "filter_ids_recycled",
        "ApplyTransient hands out the FilterId of the location's last removed declaration.",
        FilterIdsRecycled,
    ),
    Mutant(
        "frame_index_stale_after_remove_role",
        "After RemoveRole by frame, a statement naming the frame misses the geometries "
        "that got the proximity role back.",
        FrameIndexStaleAfterRemoveRole,
    ),
    Mutant(
        "replay_newest_first",
        "RemoveDeclaration replays the remaining transient declarations newest first.",
        ReplayNewestFirst,
    ),
    Mutant(
        "replay_skips_oldest",
        "RemoveDeclaration does not replay the oldest remaining transient declaration.",
        ReplaySkipsOldest,
    ),
    Mutant(
        "erase_skips_successor",
        "RemoveDeclaration of a declaration that is not the newest does not replay the "
        "one after it.",
        EraseSkipsSuccessor,
    ),
    Mutant(
        "replay_allows_before_excludes",
        "A replayed transient declaration applies its Allow statements before its Exclude ones.",
        ReplayAllowsBeforeExcludes,
    ),
    Mutant(
        "copies_share_history",
        "Removing an inherited transient declaration in a context or where it was copied "
        "from removes it in both.",
        CopiesShareHistory,
    ),
    Mutant(
        "clone_renumbers_history",
        "A clone's inherited transient declarations get new FilterIds.",
        CloneRenumbersHistory,
    ),
    Mutant(
        "default_context_flattens_history",
        "CreateDefaultContext gives the model's transient declarations to the new context "
        "as persistent filters.",
        DefaultContextFlattensHistory,
    ),
)
