"""The first mutants, and what every mutant is built from (``conformance._testing.mutants``).

``Mutant`` (one bug: its name, its sentence, the public classes that carry it),
``MutantBackend``, and the pieces the mutants share: ``MutantSceneGraph``,
``Manager`` and ``Inspector`` (thin wrappers of reimpl's), the declarations that
record their statements, and the same-frame ledger. ``BASIC_MUTANTS`` are the
twelve mutants that need no reached state; ``conformance._testing.mutants_state``
builds on this module, and ``conformance._testing.mutants`` lists both.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from types import ModuleType
from typing import Any, ClassVar, Self, cast

import reimpl.geometry
import reimpl.math
from conformance._backends.reimpl_api import REIMPL_DRAKE_VERSION
from conformance._backends.scene_graph import Api, SceneGraphBackend
from reimpl.geometry import (
    CollisionFilterDeclaration,
    CollisionFilterManager,
    FilterId,
    GeometryId,
    GeometrySet,
    ProximityProperties,
    QueryObject,
    Role,
    RoleAssign,
    SceneGraph,
    SceneGraphInspector,
)
from reimpl.systems.framework import Context, OutputPort

__all__ = ["BASIC_MUTANTS", "Mutant", "MutantBackend"]

#: A pair of proximity geometries, the smaller id value first (as GetCollisionCandidates).
Pair = tuple[GeometryId, GeometryId]


def _pair(a: GeometryId, b: GeometryId) -> Pair:
    return (a, b) if a.get_value() < b.get_value() else (b, a)


def _context_of(args: Sequence[Any], kwargs: dict[str, Any]) -> Context | None:
    """The ``context`` argument of a SceneGraph call, or None for the model."""
    if "context" in kwargs:
        return cast(Context, kwargs["context"])
    return next((a for a in args if isinstance(a, Context)), None)


# ------------------------------------------------------------ declarations
@dataclass(frozen=True)
class Statement:
    """One statement as the caller made it: the method's name and its sets."""

    method: str  # "ExcludeWithin", "AllowBetween", ...
    set_A: GeometrySet
    set_B: GeometrySet

    @property
    def filters(self) -> bool:
        return self.method.startswith("Exclude")

    @property
    def within(self) -> bool:
        return self.method.endswith("Within")

    def sets(self) -> tuple[GeometrySet, ...]:
        return (self.set_A,) if self.within else (self.set_A, self.set_B)

    def add_to(self, declaration: CollisionFilterDeclaration) -> None:
        if self.within:
            getattr(declaration, self.method)(geometry_set=self.set_A)
        else:
            getattr(declaration, self.method)(set_A=self.set_A, set_B=self.set_B)

    def mapped(self, edit: Callable[[GeometrySet], GeometrySet]) -> Statement:
        a = edit(self.set_A)
        return Statement(self.method, a, a if self.within else edit(self.set_B))


def _copied(geometry_set: GeometrySet) -> GeometrySet:
    """A copy of ``geometry_set`` (GeometrySet, like pydrake's, refuses ``copy.copy``)."""
    return GeometrySet(
        geometry_ids=list(geometry_set.geometry_ids()), frame_ids=list(geometry_set.frame_ids())
    )


class RecordingDeclaration(CollisionFilterDeclaration):
    """reimpl's declaration, which also keeps its statements where a mutant can read them."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.arguments = (args, kwargs)
        self.recorded: list[Statement] = []

    def record(self, method: str, set_A: GeometrySet, set_B: GeometrySet) -> None:
        self.recorded.append(Statement(method, _copied(set_A), _copied(set_B)))

    def AllowBetween(self, set_A: GeometrySet, set_B: GeometrySet) -> Self:
        result = super().AllowBetween(set_A=set_A, set_B=set_B)
        self.record("AllowBetween", set_A, set_B)
        return result

    def AllowWithin(self, geometry_set: GeometrySet) -> Self:
        result = super().AllowWithin(geometry_set=geometry_set)
        self.record("AllowWithin", geometry_set, geometry_set)
        return result

    def ExcludeBetween(self, set_A: GeometrySet, set_B: GeometrySet) -> Self:
        result = super().ExcludeBetween(set_A=set_A, set_B=set_B)
        self.record("ExcludeBetween", set_A, set_B)
        return result

    def ExcludeWithin(self, geometry_set: GeometrySet) -> Self:
        result = super().ExcludeWithin(geometry_set=geometry_set)
        self.record("ExcludeWithin", geometry_set, geometry_set)
        return result


def _statements(declaration: CollisionFilterDeclaration) -> list[Statement]:
    if not isinstance(declaration, RecordingDeclaration):
        raise TypeError("a mutant needs declarations made by its own CollisionFilterDeclaration")
    return declaration.recorded


def _declaration(like: CollisionFilterDeclaration, statements: Iterable[Statement]) -> Any:
    """A new declaration with ``like``'s scope and the given statements."""
    args, kwargs = like.arguments if isinstance(like, RecordingDeclaration) else ((), {})
    out = RecordingDeclaration(*args, **kwargs)
    for statement in statements:
        statement.add_to(out)
    return out


@dataclass(frozen=True)
class Resolved:
    """A statement resolved to proximity geometry ids (as Drake resolves it, once)."""

    filters: bool
    ids_A: frozenset[GeometryId]
    ids_B: frozenset[GeometryId]
    within: bool

    def mentioned(self) -> frozenset[GeometryId]:
        return self.ids_A | self.ids_B

    def pairs(self) -> Iterator[Pair]:
        for a in self.ids_A:
            for b in self.ids_B:
                if a != b:
                    yield _pair(a, b)

    def kept(self, keep: Callable[[GeometryId], bool]) -> Resolved:
        return Resolved(
            self.filters,
            frozenset(filter(keep, self.ids_A)),
            frozenset(filter(keep, self.ids_B)),
            self.within,
        )

    def statement(self) -> Statement:
        a = GeometrySet(geometry_ids=sorted(self.ids_A, key=GeometryId.get_value))
        b = GeometrySet(geometry_ids=sorted(self.ids_B, key=GeometryId.get_value))
        if self.within:
            return Statement("ExcludeWithin" if self.filters else "AllowWithin", a, a)
        return Statement("ExcludeBetween" if self.filters else "AllowBetween", a, b)


# ---------------------------------------------------------------- wrappers
class Manager:
    """Wraps reimpl's CollisionFilterManager for one location; mutants override its methods.

    Also the bookkeeping some mutants need, all with public calls: the resolved
    statements of every transient declaration, and the FilterIds that stand
    for one another when a mutant re-applies transient declarations.
    """

    def __init__(self, graph: MutantSceneGraph, inner: CollisionFilterManager, context: Any):
        self.graph = graph
        self.inner = inner
        self.context = context

    @property
    def memory(self) -> Any:
        return self.graph.memory_of(self.context)

    def inspector(self) -> SceneGraphInspector:
        return self.graph.real_inspector(self.context)

    def resolve(self, statements: Iterable[Statement]) -> tuple[Resolved, ...]:
        inspector = self.inspector()

        def ids(geometry_set: GeometrySet) -> frozenset[GeometryId]:
            return frozenset(
                inspector.GetGeometryIds(geometry_set=geometry_set, role=Role.kProximity)
            )

        out = []
        for s in statements:
            ids_A = ids(s.set_A)
            out.append(Resolved(s.filters, ids_A, ids_A if s.within else ids(s.set_B), s.within))
        return tuple(out)

    # ------------------------------------------------ the pydrake methods
    def Apply(self, declaration: CollisionFilterDeclaration) -> None:
        self.inner.Apply(declaration=declaration)

    def ApplyTransient(self, declaration: CollisionFilterDeclaration) -> FilterId:
        filter_id = self.inner.ApplyTransient(declaration=declaration)
        self.graph.transients[filter_id] = self.resolve(_statements(declaration))
        return filter_id

    def RemoveDeclaration(self, filter_id: FilterId) -> bool:
        return self.inner.RemoveDeclaration(filter_id=self.current(filter_id))

    def IsActive(self, filter_id: FilterId) -> bool:
        return self.inner.IsActive(filter_id=self.current(filter_id))

    def has_transient_history(self) -> bool:
        return self.inner.has_transient_history()

    def Activate(self, geometry_set: GeometrySet) -> None:
        self.inner.Activate(geometry_set=geometry_set)

    def Deactivate(self, geometry_set: GeometrySet) -> None:
        self.inner.Deactivate(geometry_set=geometry_set)

    # ------------------------------------------------------- FilterIds
    def current(self, filter_id: FilterId) -> FilterId:
        """The FilterId that stands for ``filter_id`` here (itself unless re-applied)."""
        queue = [filter_id]
        while queue:
            candidate = queue.pop(0)
            if self.inner.IsActive(filter_id=candidate):
                return candidate
            queue.extend(self.graph.successors.get(candidate, ()))
        return filter_id

    def active_history(self) -> list[FilterId]:
        """The active transient declarations here, oldest first."""
        known = sorted(self.graph.transients, key=FilterId.get_value)
        return [f for f in known if self.inner.IsActive(filter_id=f)]

    def lifting_history(
        self,
        action: Callable[[], object],
        *,
        skip: FilterId | None = None,
        restrict: frozenset[GeometryId] = frozenset(),
    ) -> None:
        """Removes every transient declaration, runs ``action``, then re-applies them.

        The declaration ``skip`` is not re-applied, and re-applied ones no longer
        mention the geometries in ``restrict``. Each re-applied declaration gets
        a new FilterId, which stands in for the old one from then on.
        """
        history = self.active_history()
        for filter_id in reversed(history):
            self.inner.RemoveDeclaration(filter_id=filter_id)
        try:
            action()
        finally:
            live = set(self.inspector().GetAllGeometryIds(role=Role.kProximity)) - restrict
            for old in history:
                if old == skip:
                    continue
                resolved = tuple(r.kept(live.__contains__) for r in self.graph.transients[old])
                declaration = _declaration(
                    CollisionFilterDeclaration(), (r.statement() for r in resolved)
                )
                new = self.inner.ApplyTransient(declaration=declaration)
                self.graph.transients[new] = resolved
                self.graph.successors.setdefault(old, []).append(new)


class Inspector:
    """Wraps reimpl's SceneGraphInspector; mutants override its filtering queries."""

    def __init__(self, graph: MutantSceneGraph, inner: SceneGraphInspector, context: Any):
        self.graph = graph
        self.inner = inner
        self.context = context

    def __getattr__(self, name: str) -> Any:
        return getattr(self.inner, name)

    def GetCollisionCandidates(self) -> set[Pair]:
        return self.inner.GetCollisionCandidates()

    def CollisionFiltered(self, geometry_id1: GeometryId, geometry_id2: GeometryId) -> bool:
        return self.inner.CollisionFiltered(geometry_id1=geometry_id1, geometry_id2=geometry_id2)


class _Query:
    """A QueryObject whose inspector() is the mutant's."""

    def __init__(self, graph: MutantSceneGraph, inner: QueryObject, context: Context) -> None:
        self.graph, self.inner, self.context = graph, inner, context

    def __getattr__(self, name: str) -> Any:
        return getattr(self.inner, name)

    def inspector(self) -> Any:
        return self.graph.inspector_class(self.graph, self.inner.inspector(), self.context)


class _QueryPort:
    """The query output port, evaluating to the mutant's QueryObject."""

    def __init__(self, graph: MutantSceneGraph, inner: OutputPort) -> None:
        self.graph, self.inner = graph, inner

    def __getattr__(self, name: str) -> Any:
        return getattr(self.inner, name)

    def Eval(self, context: Context) -> Any:
        return _Query(self.graph, self.inner.Eval(context), context)


class MutantSceneGraph(SceneGraph):
    """reimpl's SceneGraph, handing out the mutant's managers and inspectors.

    ``memory_of(context)`` is what the mutant remembers about one location
    (None: the model); subclasses say what a fresh one is (``new_memory``).
    """

    manager_class: ClassVar[type[Manager]] = Manager
    inspector_class: ClassVar[type[Inspector]] = Inspector

    def __init__(self) -> None:
        super().__init__()
        self.memories: dict[Context | None, Any] = {}
        #: Every transient declaration made through a mutant manager, resolved.
        self.transients: dict[FilterId, tuple[Resolved, ...]] = {}
        #: A re-applied declaration's old FilterId → the new ones.
        self.successors: dict[FilterId, list[FilterId]] = {}

    def new_memory(self) -> Any:
        return None

    def memory_for_new_context(self) -> Any:
        """A new context's memory: by default it remembers nothing."""
        return self.new_memory()

    def memory_of(self, context: Context | None) -> Any:
        if context not in self.memories:
            self.memories[context] = self.new_memory()
        return self.memories[context]

    def real_inspector(self, context: Context | None) -> SceneGraphInspector:
        if context is None:
            return super().model_inspector()
        return cast(SceneGraphInspector, super().get_query_output_port().Eval(context).inspector())

    def remove_role_noting_unroled(self, context: Context | None, *args: Any, **kwargs: Any) -> int:
        """The real RemoveRole; the proximity ids it unroled join ``memory_of(context).ids``."""
        before = set(self.real_inspector(context).GetAllGeometryIds(role=Role.kProximity))
        count = super().RemoveRole(*args, **kwargs)
        after = set(self.real_inspector(context).GetAllGeometryIds(role=Role.kProximity))
        self.memory_of(context).ids |= before - after
        return count

    def real_manager(self, context: Context | None) -> CollisionFilterManager:
        if context is None:
            return super().collision_filter_manager()
        return super().collision_filter_manager(context=context)

    def manager(self, context: Context | None) -> Manager:
        return self.manager_class(self, self.real_manager(context), context)

    # ------------------------------------------------ the pydrake methods
    def collision_filter_manager(self, *args: Any, **kwargs: Any) -> CollisionFilterManager:
        inner = super().collision_filter_manager(*args, **kwargs)
        return cast(
            CollisionFilterManager, self.manager_class(self, inner, _context_of(args, kwargs))
        )

    def model_inspector(self) -> SceneGraphInspector:
        return cast(
            SceneGraphInspector, self.inspector_class(self, super().model_inspector(), None)
        )

    def get_query_output_port(self) -> OutputPort:
        return cast(OutputPort, _QueryPort(self, super().get_query_output_port()))

    def CreateDefaultContext(self) -> Context:
        context = super().CreateDefaultContext()
        self.memories[context] = self.memory_for_new_context()
        return context

    def SetDefaultContext(self, context: Context) -> None:
        super().SetDefaultContext(context=context)
        self.memories[context] = self.memory_for_new_context()


# ------------------------------------------------------------------ mutants
class _AllowBetweenDeclaration(RecordingDeclaration):
    def AllowBetween(self, set_A: GeometrySet, set_B: GeometrySet) -> Self:
        super().AllowBetween(set_A=set_A, set_B=set_B)
        super().AllowWithin(geometry_set=set_A)
        return super().AllowWithin(geometry_set=set_B)


class _ReversingManager(Manager):
    def Apply(self, declaration: CollisionFilterDeclaration) -> None:
        super().Apply(_declaration(declaration, reversed(_statements(declaration))))

    def ApplyTransient(self, declaration: CollisionFilterDeclaration) -> FilterId:
        return super().ApplyTransient(_declaration(declaration, reversed(_statements(declaration))))


class ReverseStatementOrder(MutantSceneGraph):
    """The manager hands reimpl a copy of the declaration with its statements reversed."""

    manager_class = _ReversingManager


class _LazyManager(Manager):
    def Apply(self, declaration: CollisionFilterDeclaration) -> None:
        super().Apply(declaration)
        self.memory.extend(
            s for s in _statements(declaration) if any(x.num_frames() for x in s.sets())
        )


class LazyFrameResolution(MutantSceneGraph):
    """Remembers persistent statements naming a frame and re-applies them on AssignRole.

    Like a GeometryState that resolves frames lazily: once a geometry gets the
    proximity role (and no transient declaration is active), every remembered
    statement is applied again, to the geometries that are still registered.
    """

    manager_class = _LazyManager

    def new_memory(self) -> list[Statement]:
        return []

    def AssignRole(self, *args: Any, **kwargs: Any) -> None:
        super().AssignRole(*args, **kwargs)
        if not isinstance(kwargs.get("properties"), ProximityProperties):
            return
        if kwargs.get("assign") is RoleAssign.kReplace:
            return
        context = _context_of(args, kwargs)
        remembered: list[Statement] = self.memory_of(context)
        manager = self.real_manager(context)
        if not remembered or manager.has_transient_history():
            return
        live = set(self.real_inspector(context).GetAllGeometryIds())

        def registered(geometry_set: GeometrySet) -> GeometrySet:
            return GeometrySet(
                geometry_ids=[g for g in geometry_set.geometry_ids() if g in live],
                frame_ids=list(geometry_set.frame_ids()),
            )

        again = [s.mapped(registered) for s in remembered]
        manager.Apply(declaration=_declaration(CollisionFilterDeclaration(), again))


class _NoReplayManager(Manager):
    def RemoveDeclaration(self, filter_id: FilterId) -> bool:
        current = self.current(filter_id)
        if not self.inner.IsActive(filter_id=current):
            return self.inner.RemoveDeclaration(filter_id=current)
        mentioned: frozenset[GeometryId] = frozenset()
        for item in self.graph.transients[current]:
            mentioned |= item.mentioned()
        self.lifting_history(lambda: None, skip=current, restrict=mentioned)
        return True


class RemoveDeclarationNoReplay(MutantSceneGraph):
    """RemoveDeclaration drops the removed declaration's geometries from the remaining ones.

    So the pairs of the geometries it mentioned fall back to the persistent
    base, as if C were re-derived there without replaying the history.
    """

    manager_class = _NoReplayManager


class ContextManagersWriteModel(MutantSceneGraph):
    """collision_filter_manager(context) checks the context, then returns the model's manager."""

    def collision_filter_manager(self, *args: Any, **kwargs: Any) -> CollisionFilterManager:
        if _context_of(args, kwargs) is not None:
            super().collision_filter_manager(*args, **kwargs)  # The same checks.
        return super().collision_filter_manager()


class _StrictManager(Manager):
    def check(self, sets: Iterable[GeometrySet]) -> None:
        """Raises at the first registered geometry without the proximity role.

        N.B. An unknown id met first is left for reimpl to report.
        """
        inspector = self.inspector()
        for geometry_set in sets:
            try:
                inspector.GetGeometryIds(geometry_set=geometry_set)
            except (RuntimeError, ValueError, IndexError):
                return
            for geometry_id in geometry_set.geometry_ids():
                if inspector.GetProximityProperties(geometry_id=geometry_id) is None:
                    raise RuntimeError(
                        f"Geometry set includes geometry {geometry_id.get_value()}, "
                        "which has no proximity role"
                    )

    def statement_sets(self, declaration: CollisionFilterDeclaration) -> Iterator[GeometrySet]:
        for statement in _statements(declaration):
            yield from statement.sets()

    def Apply(self, declaration: CollisionFilterDeclaration) -> None:
        self.check(self.statement_sets(declaration))
        super().Apply(declaration)

    def ApplyTransient(self, declaration: CollisionFilterDeclaration) -> FilterId:
        self.check(self.statement_sets(declaration))
        return super().ApplyTransient(declaration)

    def Activate(self, geometry_set: GeometrySet) -> None:
        self.check([geometry_set])
        super().Activate(geometry_set)

    def Deactivate(self, geometry_set: GeometrySet) -> None:
        self.check([geometry_set])
        super().Deactivate(geometry_set)


class NonProximityIdsRaise(MutantSceneGraph):
    """The manager checks every set for geometries without the proximity role.

    N.B. reimpl's own check runs first, so unknown ids are reported as before;
    but statements before the offending one are not applied (reimpl would have
    written them to C before it failed).
    """

    manager_class = _StrictManager


class _PermissiveManager(Manager):
    def Apply(self, declaration: CollisionFilterDeclaration) -> None:
        if not self.inner.has_transient_history():
            super().Apply(declaration)
            return
        self.lifting_history(lambda: self.inner.Apply(declaration=declaration))


class ApplyDuringHistoryAllowed(MutantSceneGraph):
    """Apply under transient history lifts the history, applies, and re-applies it."""

    manager_class = _PermissiveManager


@dataclass
class _Partners:
    """Per location: a geometry whose proximity role was removed → its filtered partners."""

    of: dict[GeometryId, list[GeometryId]] = field(default_factory=dict)


class RoleReassignKeepsFilters(MutantSceneGraph):
    """Remembers a geometry's filtered pairs when its proximity role goes; re-excludes them.

    N.B. Filtered pairs are read through CollisionFiltered, so a pair filtered
    only by a transient declaration comes back as a persistent one.
    """

    def new_memory(self) -> _Partners:
        return _Partners()

    def proximity(self, context: Context | None) -> set[GeometryId]:
        return set(self.real_inspector(context).GetAllGeometryIds(role=Role.kProximity))

    def RemoveRole(self, *args: Any, **kwargs: Any) -> int:
        context = _context_of(args, kwargs)
        memory: _Partners = self.memory_of(context)
        if kwargs.get("role") is not Role.kProximity:
            return super().RemoveRole(*args, **kwargs)
        inspector = self.real_inspector(context)
        before = self.proximity(context)
        losing: set[GeometryId] = set()
        try:
            if "frame_id" in kwargs:
                named = GeometrySet(frame_id=kwargs["frame_id"])
                losing = set(inspector.GetGeometryIds(geometry_set=named))
            else:
                losing = {kwargs["geometry_id"]}
        except (RuntimeError, ValueError, IndexError, KeyError):
            pass
        partners: dict[GeometryId, list[GeometryId]] = {}
        for g in losing & before:
            frame = inspector.GetFrameId(geometry_id=g)
            partners[g] = [
                h
                for h in before
                if h != g
                and inspector.GetFrameId(geometry_id=h) != frame
                and inspector.CollisionFiltered(geometry_id1=g, geometry_id2=h)
            ]
        count = super().RemoveRole(*args, **kwargs)
        for g in before - self.proximity(context):
            memory.of[g] = partners.get(g, [])
        return count

    def AssignRole(self, *args: Any, **kwargs: Any) -> None:
        context = _context_of(args, kwargs)
        memory: _Partners = self.memory_of(context)
        geometry_id = kwargs.get("geometry_id")
        try:
            super().AssignRole(*args, **kwargs)
        finally:
            # N.B. Under transient history reimpl raises after the role is assigned.
            if geometry_id in memory.of and geometry_id in (live := self.proximity(context)):
                again = [h for h in memory.of.pop(geometry_id) if h in live]
                if again:
                    self.restore(context, geometry_id, again)

    def restore(self, context: Context | None, g: GeometryId, partners: list[GeometryId]) -> None:
        manager = self.manager(context)
        declaration = CollisionFilterDeclaration().ExcludeBetween(
            set_A=GeometrySet(geometry_id=g), set_B=GeometrySet(geometry_ids=partners)
        )
        apply_persistent(manager, declaration)


def apply_persistent(manager: Manager, declaration: CollisionFilterDeclaration) -> None:
    """A persistent Apply at the manager's location, lifting its transient history if any."""
    if manager.has_transient_history():
        manager.lifting_history(lambda: manager.inner.Apply(declaration=declaration))
    else:
        manager.inner.Apply(declaration=declaration)


class _StaleManager(Manager):
    def ApplyTransient(self, declaration: CollisionFilterDeclaration) -> FilterId:
        filter_id = super().ApplyTransient(declaration)
        self.memory.append(True)
        return filter_id

    def has_transient_history(self) -> bool:
        return super().has_transient_history() or bool(self.memory)


class StaleHasTransientHistory(MutantSceneGraph):
    """The manager answers has_transient_history() with "was there ever one here"."""

    manager_class = _StaleManager

    def new_memory(self) -> list[bool]:
        return []


class _WorldBlindManager(Manager):
    def world_blind(self, declaration: CollisionFilterDeclaration) -> Any:
        world = self.graph.world_frame_id()

        def without_world(geometry_set: GeometrySet) -> GeometrySet:
            return GeometrySet(
                geometry_ids=list(geometry_set.geometry_ids()),
                frame_ids=[f for f in geometry_set.frame_ids() if f != world],
            )

        return _declaration(
            declaration, (s.mapped(without_world) for s in _statements(declaration))
        )

    def Apply(self, declaration: CollisionFilterDeclaration) -> None:
        super().Apply(self.world_blind(declaration))

    def ApplyTransient(self, declaration: CollisionFilterDeclaration) -> FilterId:
        return super().ApplyTransient(self.world_blind(declaration))


class WorldFrameResolvesNothing(MutantSceneGraph):
    """The manager drops the world frame from every set before reimpl resolves it.

    Only declarations applied through a manager are affected: the invariant
    pairs reimpl writes for anchored geometry still see the world.
    """

    manager_class = _WorldBlindManager


# -------------------------------- same-frame pairs: C minus the invariant
@dataclass
class _SameFrameLedger:
    """Per location: what user declarations say about pairs on one frame.

    reimpl's public API never shows whether such a pair is filtered by a
    declaration, since the invariant hides it; these mutants keep the record.
    """

    #: Pair → filtered, from persistent declarations.
    base: dict[Pair, bool] = field(default_factory=dict)
    #: FilterId → (pair → filtered), in history order.
    transient: dict[FilterId, dict[Pair, bool]] = field(default_factory=dict)
    #: Pairs that lost their invariant (allow_clears_invariants).
    cleared: set[Pair] = field(default_factory=set)

    def copy(self) -> _SameFrameLedger:
        return _SameFrameLedger(dict(self.base), dict(self.transient), set(self.cleared))

    def filtered(self, pair: Pair, manager: Manager) -> bool:
        value = self.base.get(pair, False)
        for filter_id, pairs in self.transient.items():
            if pair in pairs and manager.inner.IsActive(filter_id=filter_id):
                value = pairs[pair]
        return value

    def forget(self, live: set[GeometryId]) -> None:
        def keep(pairs: dict[Pair, bool]) -> dict[Pair, bool]:
            return {p: v for p, v in pairs.items() if p[0] in live and p[1] in live}

        self.base = keep(self.base)
        self.transient = {f: keep(pairs) for f, pairs in self.transient.items()}
        self.cleared = {p for p in self.cleared if p[0] in live and p[1] in live}


class _LedgerManager(Manager):
    def same_frame(self, resolved: Iterable[Resolved]) -> Iterator[tuple[Resolved, Pair]]:
        inspector = self.inspector()
        for item in resolved:
            for a, b in item.pairs():
                if inspector.GetFrameId(geometry_id=a) == inspector.GetFrameId(geometry_id=b):
                    yield item, (a, b)

    def note(self, target: dict[Pair, bool], resolved: Iterable[Resolved]) -> None:
        ledger: _SameFrameLedger = self.memory
        for item, pair in self.same_frame(resolved):
            target[pair] = item.filters
            if not item.filters and cast(_SameFrameMutant, self.graph).allow_clears_invariants:
                ledger.cleared.add(pair)

    def Apply(self, declaration: CollisionFilterDeclaration) -> None:
        super().Apply(declaration)
        ledger: _SameFrameLedger = self.memory
        self.note(ledger.base, self.resolve(_statements(declaration)))

    def ApplyTransient(self, declaration: CollisionFilterDeclaration) -> FilterId:
        filter_id = super().ApplyTransient(declaration)
        ledger: _SameFrameLedger = self.memory
        self.note(ledger.transient.setdefault(filter_id, {}), self.graph.transients[filter_id])
        return filter_id


class _LedgerInspector(Inspector):
    def extra(self) -> set[Pair]:
        """Invariant pairs the mutant reports as candidates: not filtered by a declaration."""
        graph = cast(_SameFrameMutant, self.graph)
        manager = graph.manager(self.context)
        ledger: _SameFrameLedger = graph.memory_of(self.context)
        live = set(self.inner.GetAllGeometryIds(role=Role.kProximity))
        ledger.forget(live)
        return {
            p
            for p in graph.invariant_pairs(self.context, ledger, live)
            if not ledger.filtered(p, manager)
        }

    def GetCollisionCandidates(self) -> set[Pair]:
        return super().GetCollisionCandidates() | self.extra()

    def CollisionFiltered(self, geometry_id1: GeometryId, geometry_id2: GeometryId) -> bool:
        filtered = super().CollisionFiltered(geometry_id1, geometry_id2)
        return filtered and _pair(geometry_id1, geometry_id2) not in self.extra()


class _SameFrameMutant(MutantSceneGraph):
    """Reports some invariant pairs (same frame) as candidates, unless a declaration filters them.

    N.B. reimpl's public API cannot remove an invariant pair, so these mutants
    answer the inspector's filtering queries (GetCollisionCandidates,
    CollisionFiltered) as if the invariant were missing; the state itself is
    reimpl's.
    """

    manager_class = _LedgerManager
    inspector_class = _LedgerInspector
    allow_clears_invariants = False

    def new_memory(self) -> _SameFrameLedger:
        return _SameFrameLedger()

    def memory_for_new_context(self) -> _SameFrameLedger:
        model: _SameFrameLedger = self.memory_of(None)
        return model.copy()

    def invariant_pairs(
        self, context: Context | None, ledger: _SameFrameLedger, live: set[GeometryId]
    ) -> set[Pair]:
        raise NotImplementedError

    def forget_removed(self, context: Context | None) -> None:
        ledger: _SameFrameLedger = self.memory_of(context)
        ledger.forget(set(self.real_inspector(context).GetAllGeometryIds(role=Role.kProximity)))

    def RemoveRole(self, *args: Any, **kwargs: Any) -> int:
        count = super().RemoveRole(*args, **kwargs)
        self.forget_removed(_context_of(args, kwargs))
        return count

    def RemoveGeometry(self, *args: Any, **kwargs: Any) -> None:
        super().RemoveGeometry(*args, **kwargs)
        self.forget_removed(_context_of(args, kwargs))


class AllowClearsInvariants(_SameFrameMutant):
    """An Allow statement covering a same-frame pair clears its invariant, for good."""

    allow_clears_invariants = True

    def invariant_pairs(
        self, context: Context | None, ledger: _SameFrameLedger, live: set[GeometryId]
    ) -> set[Pair]:
        return set(ledger.cleared)


class NoSameFrameInvariant(_SameFrameMutant):
    """No pair of proximity geometries on one frame is invariantly excluded."""

    def invariant_pairs(
        self, context: Context | None, ledger: _SameFrameLedger, live: set[GeometryId]
    ) -> set[Pair]:
        inspector = self.real_inspector(context)
        by_frame: dict[Any, list[GeometryId]] = {}
        for g in live:
            by_frame.setdefault(inspector.GetFrameId(geometry_id=g), []).append(g)
        return {_pair(a, b) for group in by_frame.values() for a in group for b in group if a != b}


# ------------------------------------------------------------------- table
@dataclass(frozen=True)
class Mutant:
    """One injected bug: its name, what is wrong, and the public classes that carry it."""

    name: str
    bug: str
    scene_graph: type[MutantSceneGraph]
    declaration: type[RecordingDeclaration] = RecordingDeclaration
    #: Its bug is in a query: its campaign is ``fuzz --poses``.
    posed: bool = False

    def api(self) -> Api:
        """reimpl's Api with this mutant's SceneGraph and CollisionFilterDeclaration."""
        geometry = ModuleType(f"{__name__}.{self.name}.geometry", "reimpl.geometry, mutated")
        for name in reimpl.geometry.__all__:
            setattr(geometry, name, getattr(reimpl.geometry, name))
        geometry.SceneGraph = self.scene_graph  # type: ignore[attr-defined]
        geometry.CollisionFilterDeclaration = self.declaration  # type: ignore[attr-defined]
        return Api(
            name=f"mutant:{self.name}",
            version=REIMPL_DRAKE_VERSION,
            geometry=geometry,
            math=reimpl.math,
        )


class MutantBackend(SceneGraphBackend):
    """The reimpl backend over ``mutant``'s Api."""

    def __init__(self, mutant: Mutant) -> None:
        self.mutant = mutant
        super().__init__(mutant.api())


class AllowBetweenClearsWithin(MutantSceneGraph):
    """Plain: the bug is in the declaration (AllowBetween adds AllowWithin of each set)."""


BASIC_MUTANTS: tuple[Mutant, ...] = (
    Mutant(
        "allow_clears_invariants",
        "AllowWithin/AllowBetween also clear invariant pairs (same frame, anchored-anchored).",
        AllowClearsInvariants,
    ),
    Mutant(
        "allow_between_clears_within",
        "AllowBetween(A, B) also allows the pairs within A and within B.",
        AllowBetweenClearsWithin,
        _AllowBetweenDeclaration,
    ),
    Mutant(
        "reverse_statement_order",
        "A declaration's statements are applied in reverse order.",
        ReverseStatementOrder,
    ),
    Mutant(
        "lazy_frame_resolution",
        "Persistent declarations naming a frame also cover geometry that gets the "
        "proximity role on that frame later.",
        LazyFrameResolution,
    ),
    Mutant(
        "remove_declaration_no_replay",
        "RemoveDeclaration re-derives C from the persistent base without replaying the "
        "remaining transient declarations.",
        RemoveDeclarationNoReplay,
    ),
    Mutant(
        "context_managers_write_model",
        "collision_filter_manager(context=...) edits the model instead of the context.",
        ContextManagersWriteModel,
    ),
    Mutant(
        "non_proximity_ids_raise",
        "A GeometrySet naming a registered geometry without the proximity role raises "
        "instead of ignoring it.",
        NonProximityIdsRaise,
    ),
    Mutant(
        "apply_during_history_allowed",
        "Persistent Apply succeeds while transient history is active.",
        ApplyDuringHistoryAllowed,
    ),
    Mutant(
        "role_reassign_keeps_filters",
        "Removing a geometry's proximity role and assigning it again restores its old "
        "filtered pairs.",
        RoleReassignKeepsFilters,
    ),
    Mutant(
        "stale_has_transient_history",
        "has_transient_history() stays True after the last transient declaration is removed.",
        StaleHasTransientHistory,
    ),
    Mutant(
        "world_frame_resolves_nothing",
        "The world frame in a GeometrySet resolves to no geometry instead of every "
        "anchored proximity geometry.",
        WorldFrameResolvesNothing,
    ),
    Mutant(
        "no_same_frame_invariant",
        "A geometry getting the proximity role is not invariantly excluded from the other "
        "proximity geometries on its frame.",
        NoSameFrameInvariant,
    ),
)
