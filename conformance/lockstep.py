"""A Hypothesis state machine that drives two backends in lockstep.

``LockstepMachine`` sends every command to the backend under test and to the
reference backend. It compares the two Results after each command, and an
``@invariant`` compares the whole canonical state (``Backend.observe()``: C
for the model and for every context, IsActive of every declaration label,
``has_transient_history()``) after every step. Any disagreement raises
``Divergence``, which carries the command sequence so far and the reference's
answers, so a shrunk failure can be written out as a scenario case
(``conformance.regression``).

Bundles hold *names*, exactly as the scenario grammar uses them:

========== ============================================================
sources    ``source`` (the implicit source) and further sources
frames     ``world`` and registered frames
geometries registered geometries; a removed one stays (its id goes stale)
filter_ids labels of transient declarations (the FilterIds behind them)
contexts   contexts made by create_context / clone_context
========== ============================================================

Subclass it to fuzz other pairs or to add rules; ``lockstep_machine()``
makes a subclass for two backend specs. Every rule issues one scenario command
(except ``register_geometries``, which issues a batch), so the machine
covers the whole command set: registration, role changes, removal, apply,
apply_transient, remove_declaration, IsActive, history, CollisionFiltered,
contexts, and Activate/Deactivate when both backends support ``activation``.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cache
from typing import Any, ClassVar

from hypothesis import note
from hypothesis import strategies as st
from hypothesis.control import current_build_context
from hypothesis.errors import InvalidArgument
from hypothesis.stateful import (
    Bundle,
    RuleBasedStateMachine,
    initialize,
    invariant,
    multiple,
    precondition,
    rule,
)

from conformance import strategies as cs
from conformance.backend import Backend, Command, ErrorKind, Observation, Result
from conformance.backends import load_backend
from conformance.runner import results_agree

__all__ = [
    "Divergence",
    "FuzzStats",
    "HarnessError",
    "LockstepMachine",
    "TraceStep",
    "lockstep_machine",
]

MAX_SOURCES = 3
DEFAULT_SOURCE = "source"
MAX_CONTEXTS = 3


def _kept(name: str, result: Result) -> Any:
    """``name`` for the target bundle if the command succeeded, else nothing."""
    return multiple(name) if result.error is None else multiple()


def _is_final_run() -> bool:
    """True while Hypothesis replays the example it reports (False outside a run)."""
    try:
        return bool(current_build_context().is_final)
    except InvalidArgument:
        return False


@dataclass(frozen=True)
class TraceStep:
    """One command and what each side returned."""

    command: Command
    reference: Result
    backend: Result


class Divergence(AssertionError):  # noqa: N818 (a finding, named as users say it)
    """The backend and the reference disagree after the last step of ``trace``."""

    def __init__(
        self,
        what: str,
        detail: str,
        trace: list[TraceStep],
        reference_state: Observation,
        backend_state: Observation,
    ) -> None:
        super().__init__(f"{what} after step {len(trace)}: {detail}")
        self.what = what
        self.detail = detail
        self.trace = list(trace)
        self.reference_state = reference_state
        self.backend_state = backend_state


class HarnessError(RuntimeError):
    """A backend broke (raised instead of returning a Result), or named something unknown."""


@dataclass
class FuzzStats:
    """Counters shared by every machine of a campaign; ``on_step`` reports progress."""

    examples: int = 0
    steps: int = 0
    backend_seconds: float = 0.0
    divergences_seen: int = 0
    #: The smallest divergence seen so far (kept if the run is interrupted).
    best: Divergence | None = None
    on_step: Callable[[FuzzStats], None] | None = field(default=None, repr=False)

    def record(self, divergence: Divergence) -> None:
        self.divergences_seen += 1
        if self.best is None or len(divergence.trace) <= len(self.best.trace):
            self.best = divergence


def _diff(a: Observation, b: Observation) -> str:
    parts = []
    for location in sorted(set(a.locations) | set(b.locations)):
        sa, sb = a.locations.get(location), b.locations.get(location)
        if sa != sb:
            left = json.dumps(sa.to_json() if sa else None, sort_keys=True)
            right = json.dumps(sb.to_json() if sb else None, sort_keys=True)
            parts.append(f"{location}: backend {left} reference {right}")
    return "; ".join(parts)


@cache
def _scenes(frames: tuple[int, int], geometries: tuple[int, int]) -> st.SearchStrategy[cs.Scene]:
    return cs.scenes(
        min_frames=frames[0],
        max_frames=frames[1],
        min_geometries=geometries[0],
        max_geometries=geometries[1],
    )


class LockstepMachine(RuleBasedStateMachine):
    """Runs the same commands on ``backend`` and ``reference``; see the module doc."""

    #: Zero-argument factories; a subclass sets them (``lockstep_machine`` does).
    backend_factory: ClassVar[Callable[[], Backend]] = staticmethod(lambda: load_backend("reimpl"))
    reference_factory: ClassVar[Callable[[], Backend]] = staticmethod(
        lambda: load_backend("pydrake")
    )
    stats: ClassVar[FuzzStats] = FuzzStats()
    #: Bounds (inclusive) on the initial scene's frames and geometries.
    scene_frames: ClassVar[tuple[int, int]] = (1, 4)
    scene_geometries: ClassVar[tuple[int, int]] = (2, 8)
    _pair: ClassVar[tuple[Backend, Backend] | None] = None

    sources = Bundle("sources")
    frames = Bundle("frames")
    geometries = Bundle("geometries")
    filter_ids = Bundle("filter_ids")
    contexts = Bundle("contexts")

    locations = st.none() | contexts
    owners = st.none() | sources
    sets = cs.geometry_sets(geometries=geometries, frames=frames)

    def __init__(self) -> None:
        super().__init__()
        self.backend, self.reference = self._backends()
        start = time.perf_counter()
        self.backend.reset()
        self.reference.reset()
        type(self).stats.backend_seconds += time.perf_counter() - start
        self.trace: list[TraceStep] = []
        self.activation = "activation" in (self.backend.features() & self.reference.features())
        self._counter = 0
        self._sources = 1
        self._contexts = 0
        self._scene_geometries: list[str] = []
        type(self).stats.examples += 1

    @classmethod
    def _backends(cls) -> tuple[Backend, Backend]:
        """One backend pair per class, reset for every example."""
        if cls.__dict__.get("_pair") is None:
            cls._pair = (cls.backend_factory(), cls.reference_factory())
        assert cls._pair is not None
        return cls._pair

    # ---------------------------------------------------------------- core
    def fresh(self, prefix: str) -> str:
        self._counter += 1
        return f"{prefix}{self._counter}"

    def _execute(self, backend: Backend, command: Command) -> Result:
        try:
            return backend.execute(command)
        except Exception as exc:  # A broken backend, not a disagreement.
            raise HarnessError(
                f"backend {backend.name!r} raised on {json.dumps(command.to_json())}: {exc!r}"
            ) from exc

    def step(self, op: str, **args: Any) -> Result:
        """Runs one command on both backends; raises Divergence if the Results differ."""
        command = Command(op, {k: v for k, v in args.items() if v is not None})
        if _is_final_run():  # Hypothesis shows only the final replay's notes.
            note(json.dumps(command.to_json()))
        stats = type(self).stats
        start = time.perf_counter()
        got = self._execute(self.backend, command)
        want = self._execute(self.reference, command)
        stats.backend_seconds += time.perf_counter() - start
        stats.steps += 1
        self.trace.append(TraceStep(command, want, got))
        if not results_agree(got, want):
            detail = f"backend {got.to_json()} reference {want.to_json()}"
            self._diverge(f"{op} result", detail, *self._observe())
        if stats.on_step is not None:
            stats.on_step(stats)
        return want

    def _observe(self) -> tuple[Observation, Observation]:
        stats = type(self).stats
        start = time.perf_counter()
        try:
            got, want = self.backend.observe(), self.reference.observe()
        except Exception as exc:
            raise HarnessError(f"observe() raised: {exc!r}") from exc
        stats.backend_seconds += time.perf_counter() - start
        return got, want

    def _diverge(self, what: str, detail: str, got: Observation, want: Observation) -> None:
        divergence = Divergence(what, detail, self.trace, want, got)
        type(self).stats.record(divergence)
        raise divergence

    @invariant()
    def same_state(self) -> None:
        """The whole canonical state agrees, for the model and every context."""
        got, want = self._observe()
        if got != want:
            self._diverge("state", _diff(got, want), got, want)

    # ------------------------------------------------------- registration
    @initialize(target=sources)
    def default_source(self) -> str:
        return DEFAULT_SOURCE

    @initialize(
        target=frames,
        scene=st.runner().flatmap(
            lambda machine: _scenes(machine.scene_frames, machine.scene_geometries)
        ),
    )
    def scene(self, scene: cs.Scene) -> Any:
        """Registers a scene (``scene_frames``/``scene_geometries`` bound its size).

        The frames go to the ``frames`` bundle here. The geometries join the
        ``geometries`` bundle through ``adopt_scene_geometries``, because an
        initialize rule feeds one bundle only.
        """
        names: dict[str, str] = {}
        for name, parent in scene.frames:
            names[name] = self.fresh("f")
            self.step("register_frame", name=names[name], parent=names.get(parent or ""))
        for geometry in scene.geometries:
            name = self.fresh("g")
            frame = names.get(geometry.frame, cs.WORLD)
            result = self.step("register_geometry", name=name, frame=frame, roles=[*geometry.roles])
            if result.error is None:
                self._scene_geometries.append(name)
        return multiple(cs.WORLD, *names.values())

    @precondition(lambda self: self._scene_geometries)
    @rule(target=geometries)
    def adopt_scene_geometries(self) -> Any:
        """Puts the scene's geometries in the bundle (no command is sent)."""
        names, self._scene_geometries = self._scene_geometries, []
        return multiple(*names)

    @precondition(lambda self: self._sources < MAX_SOURCES)
    @rule(target=sources)
    def register_source(self) -> Any:
        name = self.fresh("s")
        self._sources += 1
        return _kept(name, self.step("register_source", name=name))

    @rule(target=frames, parent=st.none() | frames, source=owners, reuse=st.none() | frames)
    def register_frame(self, parent: str | None, source: str | None, reuse: str | None) -> Any:
        """A new frame; with ``reuse``, under another frame's Drake name (a duplicate)."""
        name = self.fresh("f")
        result = self.step(
            "register_frame", name=name, drake_name=reuse, parent=parent, source=source
        )
        return _kept(name, result)

    @rule(
        target=geometries,
        placements=st.lists(
            st.tuples(frames, cs.roles(), owners, st.none() | geometries), min_size=1, max_size=4
        ),
        context=locations,
    )
    def register_geometries(
        self,
        placements: list[tuple[str, list[str], str | None, str | None]],
        context: str | None,
    ) -> Any:
        """Registers a batch; into ``context`` only on a frame (never anchored there).

        A placement may reuse another geometry's Drake name (``drake_name``).
        """
        names = []
        for frame, roles, source, reuse in placements:
            name = self.fresh("g")
            result = self.step(
                "register_geometry",
                name=name,
                drake_name=reuse,
                frame=frame,
                roles=roles,
                source=source,
                context=context if frame != cs.WORLD else None,
            )
            # A failed role assignment leaves the geometry registered (Drake does so too).
            if result.error is None or result.error.kind is ErrorKind.TRANSIENT_HISTORY:
                names.append(name)
        return multiple(*names)

    @rule(
        geometry=geometries,
        role=st.sampled_from(cs.ROLES),
        replace=st.booleans(),
        source=owners,
        context=locations,
    )
    def assign_role(
        self, geometry: str, role: str, replace: bool, source: str | None, context: str | None
    ) -> None:
        self.step(
            "assign_role",
            geometry=geometry,
            role=role,
            assign="replace" if replace else None,
            source=source,
            context=context,
        )

    @rule(
        target_=st.tuples(st.sampled_from(("geometry", "frame")), geometries, frames),
        role=st.sampled_from((*cs.ROLES, "unassigned")),
        source=owners,
        context=locations,
    )
    def remove_role(
        self, target_: tuple[str, str, str], role: str, source: str | None, context: str | None
    ) -> None:
        kind, geometry, frame = target_
        named = {"geometry": geometry} if kind == "geometry" else {"frame": frame}
        self.step("remove_role", role=role, source=source, context=context, **named)

    @rule(geometry=geometries, context=locations)
    def reassign_proximity(self, geometry: str, context: str | None) -> None:
        """Removes the proximity role and assigns it again: the geometry starts unfiltered."""
        self.step("remove_role", geometry=geometry, role="proximity", context=context)
        self.step("assign_role", geometry=geometry, role="proximity", context=context)

    @rule(geometry=geometries, source=owners, context=locations)
    def remove_geometry(self, geometry: str, source: str | None, context: str | None) -> None:
        self.step("remove_geometry", geometry=geometry, source=source, context=context)

    # ------------------------------------------------------- declarations
    @rule(declaration=cs.declarations(geometries=geometries, frames=frames), context=locations)
    def apply(self, declaration: dict[str, Any], context: str | None) -> None:
        self.step("apply", declaration=declaration, context=context)

    @rule(
        target=filter_ids,
        declaration=cs.declarations(geometries=geometries, frames=frames),
        context=locations,
    )
    def apply_transient(self, declaration: dict[str, Any], context: str | None) -> Any:
        label = self.fresh("t")
        result = self.step("apply_transient", declaration=declaration, label=label, context=context)
        return _kept(label, result)

    @rule(declaration=cs.declarations(geometries=geometries, frames=frames), context=locations)
    def transient_round_trip(self, declaration: dict[str, Any], context: str | None) -> None:
        """ApplyTransient, then RemoveDeclaration of it: C must be as if never applied.

        Removing the newest declaration also re-derives the pairs it named
        from the base and the older declarations (Table 1, lines 5-7).
        """
        label = self.fresh("t")
        result = self.step("apply_transient", declaration=declaration, label=label, context=context)
        if result.error is None:
            self.step("remove_declaration", label=label, context=context)

    @rule(
        target=filter_ids,
        first=cs.declarations(geometries=geometries, frames=frames),
        second=cs.declarations(geometries=geometries, frames=frames),
        context=locations,
    )
    def stacked_transients(
        self, first: dict[str, Any], second: dict[str, Any], context: str | None
    ) -> Any:
        """Two transient declarations, then the first removed: the second must be replayed.

        Table 1, lines 5-7: removing a declaration re-derives C from the base
        and every declaration still active, in order.
        """
        labels = [self.fresh("t"), self.fresh("t")]
        results = [
            self.step("apply_transient", declaration=d, label=label, context=context)
            for d, label in zip((first, second), labels, strict=True)
        ]
        self.step("remove_declaration", label=labels[0], context=context)
        return _kept(labels[1], results[1])

    @rule(label=filter_ids | st.just(cs.UNKNOWN), context=locations)
    def remove_declaration(self, label: str, context: str | None) -> None:
        self.step("remove_declaration", label=label, context=context)

    @rule(label=filter_ids | st.just(cs.UNKNOWN), context=locations)
    def is_active(self, label: str, context: str | None) -> None:
        self.step("is_active", label=label, context=context)

    @rule(context=locations)
    def has_transient_history(self, context: str | None) -> None:
        self.step("has_transient_history", context=context)

    @rule(
        a=geometries | st.sampled_from((cs.UNKNOWN, cs.FOREIGN)),
        b=geometries,
        context=locations,
    )
    def collision_filtered(self, a: str, b: str, context: str | None) -> None:
        self.step("collision_filtered", pair=[a, b], context=context)

    @precondition(lambda self: self.activation)
    @rule(geometry_set=sets, context=locations)
    def deactivate(self, geometry_set: dict[str, list[str]], context: str | None) -> None:
        self.step("deactivate", set=geometry_set, context=context)

    @precondition(lambda self: self.activation)
    @rule(geometry_set=sets, context=locations)
    def activate(self, geometry_set: dict[str, list[str]], context: str | None) -> None:
        self.step("activate", set=geometry_set, context=context)

    # ------------------------------------------------------------ contexts
    @precondition(lambda self: self._contexts < MAX_CONTEXTS)
    @rule(target=contexts)
    def create_context(self) -> Any:
        name = self.fresh("c")
        self._contexts += 1
        return _kept(name, self.step("create_context", name=name))

    @precondition(lambda self: self._contexts < MAX_CONTEXTS)
    @rule(target=contexts, origin=contexts)
    def clone_context(self, origin: str) -> Any:
        name = self.fresh("c")
        self._contexts += 1
        result = self.step("clone_context", name=name, **{"from": origin})
        return _kept(name, result)

    @rule(context=contexts)
    def set_default_context(self, context: str) -> None:
        self.step("set_default_context", context=context)


def lockstep_machine(
    backend: Callable[[], Backend],
    reference: Callable[[], Backend],
    *,
    stats: FuzzStats | None = None,
    base: type[LockstepMachine] = LockstepMachine,
    scene_frames: tuple[int, int] | None = None,
    scene_geometries: tuple[int, int] | None = None,
    name: str = "Lockstep",
) -> type[LockstepMachine]:
    """A subclass of ``base`` for two backend factories, with its own stats.

    ``scene_frames`` and ``scene_geometries`` bound the initial scene (default:
    ``base``'s bounds).
    """
    namespace: dict[str, Any] = {
        "backend_factory": staticmethod(backend),
        "reference_factory": staticmethod(reference),
        "stats": stats if stats is not None else FuzzStats(),
        "_pair": None,
    }
    if scene_frames is not None:
        namespace["scene_frames"] = scene_frames
    if scene_geometries is not None:
        namespace["scene_geometries"] = scene_geometries
    return type(name, (base,), namespace)
