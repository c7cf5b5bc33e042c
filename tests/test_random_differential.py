"""Seeded random differential test: reimpl and pydrake run the same command stream.

Each seed drives ``random.Random(seed)`` through STEPS commands over one
SceneGraph: frames (some with parents), anchored and dynamic geometry with a
random subset of roles, role changes, removals, persistent and transient
declarations over random sets (sometimes naming ``@unknown`` ids), declaration
removal, contexts and commands on them, and CollisionFiltered queries. After
every command both backends must return the same Result (same value; same
error kind and, unless the kind is BINDING, the same normalised message) and
the same Observation (candidate pairs per location, active labels, history).

The generator reads the names the backends know after each step, so it only
names what exists (or ``@unknown``); names are unique per run. Deactivate is
never used (it kills pydrake on anchored geometry), and no context is created
before the source is registered (see ``CommandGenerator.next``).

Partial applies (a valid statement before a bad id) happen often: their
leftover in C, how contexts copy it and when RemoveDeclaration re-derives it
are all compared step by step. So are the half-registered geometries Drake
leaves when a proximity role is assigned during transient history.
"""

from __future__ import annotations

import json
import random
from collections.abc import Mapping, Sequence
from typing import Any

import pytest

from conformance.backends.pydrake_api import pydrake_api
from conformance.backends.reimpl_api import reimpl_api
from conformance.backends.scene_graph import SceneGraphBackend
from conformance.fuzz.strategies import set_spec
from conformance.protocol import MODEL, Command, Observation, Result
from conformance.run.runner import results_agree

SEEDS = range(100)
STEPS = 80
MAX_CONTEXTS = 3
UNKNOWN = "@unknown"
ROLES = ("proximity", "illustration")
STATEMENT_OPS = ("exclude_within", "allow_within", "exclude_between", "allow_between")

#: The active declaration labels of each location ("model" or a context name).
Live = Mapping[str, Sequence[str]]


class CommandGenerator:
    """Draws the next command from the names the backend knows."""

    def __init__(self, seed: int) -> None:
        self.rng = random.Random(seed)
        # Odd seeds may put an unknown id in any statement (a partial apply).
        self.partial = seed % 2 == 1
        self.counter = 0
        # Geometries removed somewhere (model or a context): their stale ids are unknown.
        self.removed: set[str] = set()

    def record(self, command: Command, result: Result) -> None:
        if command.op == "remove_geometry" and result.error is None:
            self.removed.add(command.args["geometry"])

    # ------------------------------------------------------------ helpers
    def _fresh(self, prefix: str) -> str:
        self.counter += 1
        return f"{prefix}{self.counter}"

    def _pick(self, names: Sequence[str], unknown: float = 0.0) -> str:
        if not names or self.rng.random() < unknown:
            return UNKNOWN
        return self.rng.choice(list(names))

    def _geometries(self, backend: SceneGraphBackend) -> list[str]:
        """Mostly geometries not removed anywhere; sometimes any ever registered."""
        names = sorted(backend.geometries)
        if self.rng.random() < 0.9:
            names = [n for n in names if n not in self.removed]
        return names

    def _location(self, backend: SceneGraphBackend, args: dict[str, Any]) -> str:
        if backend.contexts and self.rng.random() < 0.3:
            args["context"] = self.rng.choice(sorted(backend.contexts))
        return str(args.get("context", MODEL))

    def _set(self, backend: SceneGraphBackend, unknown: bool = False) -> dict[str, list[str]]:
        rng = self.rng
        geometries = self._geometries(backend)
        frames = sorted(backend.frames)
        chosen_g = rng.sample(geometries, k=min(len(geometries), rng.randint(0, 3)))
        chosen_f = rng.sample(frames, k=min(len(frames), rng.choice((0, 0, 1, 2))))
        if unknown:
            (chosen_g if rng.random() < 0.6 else chosen_f).append(UNKNOWN)
        return set_spec(chosen_g, chosen_f)

    def _declaration(self, backend: SceneGraphBackend) -> dict[str, Any]:
        """1-4 statements; sometimes one set names an ``@unknown`` id.

        Odd seeds put it in any statement (a partial apply leaves a leftover);
        even seeds only in the first (nothing is applied). A removed geometry's
        stale id, sometimes drawn by ``_set``, fails the same way anywhere.
        """
        rng = self.rng
        count = rng.randint(1, 4)
        bad = -1
        if rng.random() < 0.15:
            bad = rng.randrange(count) if self.partial else 0
        statements = []
        for index in range(count):
            op = rng.choice(STATEMENT_OPS)
            unknown = index == bad
            if op.endswith("_within"):
                statements.append({"op": op, "set": self._set(backend, unknown)})
            else:
                in_a = rng.random() < 0.5
                statements.append(
                    {
                        "op": op,
                        "a": self._set(backend, unknown and in_a),
                        "b": self._set(backend, unknown and not in_a),
                    }
                )
        return {"statements": statements}

    # ---------------------------------------------------------------- next
    def next(self, backend: SceneGraphBackend, live: Live) -> Command:
        """The next command; ``live`` maps each location to its active labels."""
        contexts = sorted(backend.contexts)
        dynamic_frames = sorted(f for f in backend.frames if f != "world")
        weights = {
            "register_frame": 3 if len(dynamic_frames) < 6 else 1,
            "register_geometry": 6 if len(backend.geometries) < 10 else 2,
            "assign_role": 2,
            "remove_role": 2,
            "remove_geometry": 1,
            "apply": 4,
            "apply_transient": 3,
            # History blocks persistent edits: remove declarations about as often as made.
            "remove_declaration": 6 if live.get(MODEL) else 1,
            "is_active": 1,
            "has_transient_history": 1,
            "collision_filtered": 2,
            # N.B. A context allocated before the source exists lacks its pose port;
            # after SetDefaultContext, pydrake's Clone() of it fails a DRAKE_DEMAND in
            # MaybeGetFixedInputPortValue() and kills the process.
            "create_context": 1 if backend.sources and len(contexts) < MAX_CONTEXTS else 0,
            "clone_context": 0.5 if contexts and len(contexts) < MAX_CONTEXTS else 0,
            "set_default_context": 0.3 if contexts else 0,
        }
        op = self.rng.choices(list(weights), weights=list(weights.values()))[0]
        args: dict[str, Any] = {}
        getattr(self, f"_{op}")(backend, args, live)
        return Command(op, args)

    # One builder per op: each fills ``args`` for that op.
    def _register_frame(self, backend: SceneGraphBackend, args: dict[str, Any], live: Live) -> None:
        dynamic_frames = sorted(f for f in backend.frames if f != "world")
        args["name"] = self._fresh("f")
        if dynamic_frames and self.rng.random() < 0.4:
            args["parent"] = self._pick(dynamic_frames, unknown=0.05)
        elif self.rng.random() < 0.1:
            args["parent"] = "world"

    def _register_geometry(
        self, backend: SceneGraphBackend, args: dict[str, Any], live: Live
    ) -> None:
        rng = self.rng
        dynamic_frames = sorted(f for f in backend.frames if f != "world")
        args["name"] = self._fresh("g")
        roles = [r for r in ROLES if rng.random() < (0.8 if r == "proximity" else 0.3)]
        rng.shuffle(roles)
        args["roles"] = roles
        if dynamic_frames and rng.random() < 0.75:
            args["frame"] = rng.choice(dynamic_frames)
            if backend.contexts and rng.random() < 0.1:
                args["context"] = rng.choice(sorted(backend.contexts))
        else:
            args["frame"] = "world"

    def _assign_role(self, backend: SceneGraphBackend, args: dict[str, Any], live: Live) -> None:
        args["geometry"] = self._pick(self._geometries(backend), unknown=0.05)
        args["role"] = self.rng.choice(ROLES)
        if self.rng.random() < 0.2:
            args["assign"] = "replace"
        self._location(backend, args)

    def _remove_role(self, backend: SceneGraphBackend, args: dict[str, Any], live: Live) -> None:
        args["role"] = self.rng.choice(ROLES)
        if self.rng.random() < 0.3:
            args["frame"] = self._pick(sorted(backend.frames), unknown=0.05)
        else:
            args["geometry"] = self._pick(self._geometries(backend), unknown=0.05)
        self._location(backend, args)

    def _remove_geometry(
        self, backend: SceneGraphBackend, args: dict[str, Any], live: Live
    ) -> None:
        args["geometry"] = self._pick(self._geometries(backend), unknown=0.05)
        self._location(backend, args)

    def _apply(self, backend: SceneGraphBackend, args: dict[str, Any], live: Live) -> None:
        args["declaration"] = self._declaration(backend)
        self._location(backend, args)

    def _apply_transient(
        self, backend: SceneGraphBackend, args: dict[str, Any], live: Live
    ) -> None:
        self._apply(backend, args, live)
        args["label"] = self._fresh("t")

    def _remove_declaration(
        self, backend: SceneGraphBackend, args: dict[str, Any], live: Live
    ) -> None:
        """Only labels issued so far, or ``@unknown``; mostly one active where it runs."""
        here = live.get(self._location(backend, args), ())
        if here and self.rng.random() < 0.7:
            args["label"] = self.rng.choice(list(here))
        else:
            args["label"] = self._pick(sorted(backend.labels), unknown=0.2)

    _is_active = _remove_declaration

    def _has_transient_history(
        self, backend: SceneGraphBackend, args: dict[str, Any], live: Live
    ) -> None:
        self._location(backend, args)

    def _collision_filtered(
        self, backend: SceneGraphBackend, args: dict[str, Any], live: Live
    ) -> None:
        geometries = self._geometries(backend)
        args["pair"] = [self._pick(geometries, unknown=0.05) for _ in range(2)]
        self._location(backend, args)

    def _create_context(self, backend: SceneGraphBackend, args: dict[str, Any], live: Live) -> None:
        args["name"] = self._fresh("ctx")

    def _clone_context(self, backend: SceneGraphBackend, args: dict[str, Any], live: Live) -> None:
        args["from"] = self.rng.choice(sorted(backend.contexts))
        args["name"] = self._fresh("ctx")

    def _set_default_context(
        self, backend: SceneGraphBackend, args: dict[str, Any], live: Live
    ) -> None:
        args["context"] = self.rng.choice(sorted(backend.contexts))


def live_labels(observation: Observation) -> dict[str, list[str]]:
    return {
        location: sorted(label for label, active in state.active.items() if active)
        for location, state in observation.locations.items()
    }


def failure(seed: int, step: int, commands: list[Command], detail: str) -> str:
    script = "[\n" + ",\n".join(json.dumps(c.to_json()) for c in commands) + "\n]"
    return f"seed {seed}, step {step}: {detail}\ncommands so far (JSON):\n{script}"


@pytest.mark.parametrize("seed", SEEDS)
def test_reimpl_matches_pydrake_on_random_commands(seed: int) -> None:
    reimpl = SceneGraphBackend(reimpl_api())
    drake = SceneGraphBackend(pydrake_api())
    generator = CommandGenerator(seed)
    commands: list[Command] = []
    errors = 0
    live: dict[str, list[str]] = {}
    for step in range(STEPS):
        command = generator.next(reimpl, live)
        commands.append(command)
        try:
            a = reimpl.execute(command)
            b = drake.execute(command)
        except KeyError as exc:  # UnknownNameError: a generator bug, not a conformance one.
            pytest.fail(failure(seed, step, commands, f"generator named an unknown thing: {exc}"))
        if not results_agree(a, b):
            detail = f"results differ: reimpl {a.to_json()} pydrake {b.to_json()}"
            pytest.fail(failure(seed, step, commands, detail))
        errors += a.error is not None
        generator.record(command, b)
        observed_a, observed_b = reimpl.observe(), drake.observe()
        if observed_a != observed_b:
            detail = (
                f"observations differ:\nreimpl  {json.dumps(observed_a.to_json())}\n"
                f"pydrake {json.dumps(observed_b.to_json())}"
            )
            pytest.fail(failure(seed, step, commands, detail))
        live = live_labels(observed_a)
    # The stream is not trivial: it built a scene, and some commands failed, some did not.
    assert len(reimpl.geometries) >= 3
    assert 0 < errors < STEPS
