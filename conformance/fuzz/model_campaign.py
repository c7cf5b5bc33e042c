"""``fuzz --models``: random models as scenario cases, run on two backends by the corpus runner.

Each example is one case (``model_cases``), in the scenario grammar:

1. now and then anchored proximity geometry from the case's own source
   (``register_geometry`` on ``world``: bodies welded to the world are
   filtered against it, whichever source it comes from);
2. now and then ``set_adjacent_filters`` (when both backends have the op);
3. ``add_models``: a tree from ``conformance.fuzz.models``, rendered as URDF
   or SDFormat (with up to two nested models), sometimes with a model name
   prefix; one in eight examples is a model with a broken group
   (``kinematic_trees(invalid=True)``), for the parse errors. Now and then
   the same text is parsed again (under the prefix ``q``, with
   ``auto_renaming``, or as it is: a name clash), and the last Parser's
   ``collision_filter_groups`` report is compared (both backends having the
   op);
4. for a valid model, up to two bodies the case adds (``add_rigid_body``,
   ``register_collision_geometry``: ``B0`` with ``b0``, ``B1`` with ``b1``),
   each on a joint of any ``add_joint`` type from the world, a parsed body
   or the other added body; and up to two ``apply`` steps, before or after
   Finalize, whose declarations name the parsed bodies' frames (``m::l1``),
   their collision geometry (``m::l1/c0``), the added bodies, the world and
   the anchored geometry;
5. ``finalize``, then ``check``.

The case runs through ``conformance.run.runner.run_case``, the corpus
runner: each backend runs it from a reset, and the runner's step-by-step
comparison of the two traces (every step's Result and the whole state after
it) is the verdict. A disagreement at step k becomes a ``Divergence`` of the
first k steps with both sides' answers, the same object the lockstep machine
raises, so Hypothesis shrinks it and ``fuzz.regression.write_regression``
writes it as a scenario file whose expectations are the reference's answers.

A backend that breaks (raises, times out) ends the campaign with a
``HarnessError`` holding the case's commands, as for the lockstep machine.
A step naming a model body or geometry that the backend's parse did not
make ends that backend's run (``UnknownNameError``); the case is then run
again up to its ``add_models`` step, whose disagreement is the finding.

``ModelCampaign`` is ``Campaign`` with this example in place of the lockstep
machine: the same seeds, batches, budgets, Hypothesis settings and results.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hypothesis import given, reject
from hypothesis import seed as hypothesis_seed
from hypothesis import strategies as st

from conformance.corpus.loader import Case, ScenarioFile, Step
from conformance.fuzz import strategies as cs
from conformance.fuzz.campaign import BatchResult, Campaign, CampaignResult, fuzz_settings
from conformance.fuzz.lockstep import (
    Divergence,
    FuzzStats,
    HarnessAbort,
    HarnessError,
    ShrinkTimeUp,
    TraceStep,
    stop_point,
)
from conformance.fuzz.models import (
    FORMATS,
    WORLD,
    geometry_names,
    kinematic_trees,
    render,
)
from conformance.grammar import GRAMMAR, features_of
from conformance.grammar.multibody import JOINT_TYPES
from conformance.policy.divergences import match_step
from conformance.protocol import Backend, Command, backend_id
from conformance.run.runner import CaseReport, Failure, Status, run_case

__all__ = [
    "ADDED_BODY",
    "MODEL_FEATURES",
    "ModelCampaign",
    "model_case",
    "model_cases",
    "run_model_case",
]

#: What a backend needs for ``fuzz --models`` at all.
MODEL_FEATURES = frozenset({"multibody", "parsing"})
#: The names of the bodies a case adds, their collision geometries and joints, before the
#: index: B0, b0, J0.
ADDED_BODY, _ADDED_GEOMETRY, _ADDED_JOINT = "B", "b", "J"
#: Up to two bodies a case adds to a parsed model: each in the default model instance or in
#: ``extra``, on a joint of any ``add_joint`` type (None: Finalize floats it), whose parent
#: is picked among the parsed bodies, the world and the bodies added before it.
_ADDED_BODIES = st.lists(
    st.tuples(
        st.sampled_from(({}, {"model": "extra"})),
        st.sampled_from((None, *JOINT_TYPES)),
        st.integers(0, 255),
    ),
    max_size=2,
)
_PREFIX = "p"
#: Nested models in an SDFormat model (each ``<model name="n<i>">`` a model instance
#: ``m::n<i>`` whose bodies and groups the outer model names as ``n<i>::...``).
_MAX_NESTED = 2
#: How the model is parsed a second time, if at all: under another prefix, with
#: SetAutoRenaming (Drake names the instance ``m_1``), or as it is (the names clash).
_AGAIN: tuple[dict[str, Any] | None, ...] = (
    None,
    {"prefix": "q"},
    {"auto_renaming": True},
    {},
)
_ANCHORED = "w"
_FILE = ScenarioFile(Path("fuzz-models"), "fuzz --models", "random models")


# ------------------------------------------------------------------ cases
def _scope(model_name: str, prefix: str | None) -> str:
    return model_name if prefix is None else f"{prefix}::{model_name}"


@st.composite
def model_cases(
    draw: st.DrawFn,
    *,
    formats: tuple[str, ...] = FORMATS,
    features: frozenset[str] | None = None,
    invalid_share: int = 8,
    max_anchored: int = 2,
    max_applies: int = 2,
) -> list[Command]:
    """The commands of one example (see the module doc).

    ``features``: what both backends support (default: everything), so an op
    neither has is never drawn. One example in ``invalid_share`` has a broken
    model (0: none).
    """
    have = (lambda tag: True) if features is None else features.__contains__
    # Everything but the model first: a draw after the model that depends on its
    # bodies keeps the shrinker from deleting bodies (measured: half the shrunk
    # models kept unneeded bodies). Declarations are drawn as templates, resolved
    # against the model's names once it exists.
    fmt = draw(st.sampled_from(formats))
    invalid = invalid_share > 0 and draw(st.integers(0, invalid_share - 1)) == invalid_share - 1
    anchored = [f"{_ANCHORED}{i}" for i in range(draw(st.integers(0, max_anchored)))]
    adjacent = draw(st.sampled_from((None, False, True)))
    prefix = draw(st.sampled_from((None, _PREFIX)))
    again = draw(st.sampled_from(_AGAIN))
    report = draw(st.booleans()) and have(GRAMMAR["collision_filter_groups"].feature)
    added = draw(_ADDED_BODIES)
    applies = draw(
        st.lists(st.tuples(cs.declaration_templates(), st.booleans()), max_size=max_applies)
    )
    nesting = _MAX_NESTED if fmt == "sdf" else 0
    model = draw(kinematic_trees(formats=(fmt,), invalid=invalid, max_nested=nesting))

    commands = [
        Command("register_geometry", {"name": name, "frame": WORLD, "roles": ["proximity"]})
        for name in anchored
    ]
    if adjacent is not None and have(GRAMMAR["set_adjacent_filters"].feature):
        commands.append(Command("set_adjacent_filters", {"value": adjacent}))
    add: dict[str, Any] = {"text": render(model, fmt), "format": fmt}
    if prefix is not None:
        add["prefix"] = prefix
    commands.append(Command("add_models", add))
    if again is not None:  # the same text once more: a second instance, renamed, or a clash
        commands.append(Command("add_models", {"text": add["text"], "format": fmt, **again}))
    if report:
        commands.append(Command("collision_filter_groups", {}))
    finalize = [Command("finalize", {}), Command("check", {})]
    if invalid:
        return commands + finalize
    scope = _scope(model.name, prefix)
    bodies = model.scoped_bodies()
    frames = [f"{scope}::{name}" for name, _ in bodies]
    geometries = [f"{scope}{name.removeprefix(model.name)}" for name in geometry_names(model, fmt)]
    # Parents with collision geometry first: there a joint type shows in C.
    solid = [f"{scope}::{n}" for n, b in bodies if any(g.collision for g in b.geometries)]
    parents = [*solid, WORLD, *(f for f in frames if f not in solid)]
    for i, (instance, joint_type, pick) in enumerate(added):
        body, geometry = f"{ADDED_BODY}{i}", f"{_ADDED_GEOMETRY}{i}"
        commands.append(Command("add_rigid_body", {"name": body, **instance}))
        commands.append(Command("register_collision_geometry", {"name": geometry, "body": body}))
        if joint_type is not None:
            joint = {"name": f"{_ADDED_JOINT}{i}", "type": joint_type}
            joint |= {"parent": parents[pick % len(parents)], "child": body}
            commands.append(Command("add_joint", joint))
        parents.insert(len(solid), body)
        frames.append(body)
        geometries.append(geometry)
    geometries += anchored
    frames.append(WORLD)
    for template, after in applies:
        declaration = template.resolve(
            lambda pick: cs.pick(geometries, pick), lambda pick: cs.pick(frames, pick)
        )
        apply = Command("apply", {"declaration": declaration})
        if after:
            finalize.insert(1, apply)
        else:
            commands.append(apply)
    return commands + finalize


def model_case(commands: list[Command], description: str = "a random model") -> Case:
    """The scenario case of ``commands`` (no expectations: the two backends are compared)."""
    steps = tuple(Step(i, c.op, dict(c.args), ()) for i, c in enumerate(commands, 1))
    features = frozenset({"core"}) | features_of(c.op for c in commands)
    return Case(_FILE, description, features, steps)


# ------------------------------------------------------------------ running
def _step_index(failure: Failure) -> int:
    """The 0-based step of a runner Failure (its label is ``step N``)."""
    return int(failure.step.split()[-1]) - 1 if failure.step.startswith("step ") else 0


def _broken(report: CaseReport, commands: list[Command]) -> HarnessError | None:
    """A HarnessError if a backend broke, skipped the case, or the case was cut short."""
    skipped = [
        f"{n} ({report.skip_reasons[n]})" for n, s in report.status.items() if s is Status.SKIP
    ]
    if skipped:
        return HarnessError(f"a backend cannot run model cases: {', '.join(skipped)}", commands)
    if report.broken or report.aborted:
        return HarnessError(report.aborted or "a backend broke", commands)
    return None


def _divergence(
    report: CaseReport, commands: list[Command], backend: str, reference: str
) -> Divergence:
    """The Divergence of the case's first disagreement (the steps up to it, both answers)."""
    failures = report.failures_of(backend)
    cut = min(_step_index(f) for f in failures) + 1
    ours, theirs = report.traces[reference], report.traces[backend]
    trace = [
        TraceStep(command, ours.results[i], theirs.results[i])
        for i, command in enumerate(commands[:cut])
    ]
    first = [f for f in failures if _step_index(f) == cut - 1]
    detail = "; ".join(
        f"{f.step}: {f.what}: {reference} {f.expected!r}, {backend} {f.actual!r}" for f in first
    )
    reference_state, backend_state = ours.observations[cut - 1], theirs.observations[cut - 1]
    # Every step of a case without a scene is observed.
    assert reference_state is not None
    assert backend_state is not None
    return Divergence(first[0].what, detail, trace, reference_state, backend_state)


def _known(divergence: Divergence, backend: Backend, reference: Backend, stats: FuzzStats) -> bool:
    """Counts and returns True if a known divergence describes a step of ``divergence``."""
    for item in divergence.trace:
        known = match_step(
            item.command,
            item.reference,
            item.backend,
            blamed=backend_id(backend),
            release=reference.version(),
        )
        if known is not None:
            stats.known[known.id] = stats.known.get(known.id, 0) + 1
            return True
    return False


def run_model_case(
    commands: list[Command],
    backend: Backend,
    reference: Backend,
    *,
    step_timeout: float | None = None,
) -> Divergence | None:
    """Runs the case on both backends; the Divergence of their first disagreement, or None.

    Raises HarnessError for a backend that broke (see the module doc).
    """
    report = run_case(
        model_case(commands),
        [backend, reference],
        reference=reference.name,
        strict_divergences=True,
        step_timeout=step_timeout,
    )
    if report.aborted and not report.broken and "add_models" in [c.op for c in commands]:
        # A name the backend's parse did not make: compare the case up to add_models.
        last = max(i for i, c in enumerate(commands) if c.op == "add_models") + 1
        shorter = run_model_case(commands[:last], backend, reference, step_timeout=step_timeout)
        if shorter is not None:
            return shorter
    broken = _broken(report, commands)
    if broken is not None:
        raise broken
    if not report.failures_of(backend.name):
        return None
    return _divergence(report, commands, backend.name, reference.name)


@contextmanager
def _quiet_drake() -> Iterator[None]:
    """Drake's parser warnings (a URDF floating joint, a renamed geometry) are not answers:
    the ``drake`` logger shows errors only while a campaign runs in this process."""
    logger = logging.getLogger("drake")
    level = logger.level
    logger.setLevel(max(level, logging.ERROR))
    try:
        yield
    finally:
        logger.setLevel(level)


@dataclass
class ModelCampaign(Campaign):
    """A ``Campaign`` whose examples are random models (``model_cases``), not lockstep runs."""

    #: Formats drawn (default: URDF and SDFormat).
    formats: tuple[str, ...] = FORMATS
    #: One example in this many has a broken model (0: none).
    invalid_share: int = 8

    def run(self) -> CampaignResult:
        with _quiet_drake():
            return super().run()

    def _batch(
        self, backend: Backend, reference: Backend, stats: FuzzStats, seed: int, size: int | None
    ) -> BatchResult:
        features = backend.features() & reference.features()
        missing = MODEL_FEATURES - features
        if missing:
            raise HarnessError(
                f"fuzz --models needs the feature(s) {', '.join(sorted(missing))} of both "
                f"{backend.name} and {reference.name}"
            )
        strategy = model_cases(
            formats=self.formats, features=features, invalid_share=self.invalid_share
        )

        @hypothesis_seed(seed)
        @fuzz_settings(max_examples=size or 100, database=self.database)
        @given(strategy)
        def example(commands: list[Command]) -> None:
            stop_point(stats)
            start = time.perf_counter()
            try:
                divergence = run_model_case(
                    commands, backend, reference, step_timeout=self.step_timeout
                )
            except HarnessError as exc:
                raise HarnessAbort(exc) from None
            finally:
                stats.backend_seconds += time.perf_counter() - start
                stats.examples += 1
                stats.steps += len(commands)
                if stats.on_step is not None:
                    stats.on_step(stats)
            if divergence is None:
                return
            if not self.strict_divergences and _known(divergence, backend, reference, stats):
                reject()
            stats.record(divergence)
            raise divergence

        stats.new_batch()
        try:
            example()
        except Divergence as divergence:
            return BatchResult(seed, divergence)
        except ShrinkTimeUp:
            return BatchResult(seed, stats.best, shrink_stopped=True)
        except HarnessAbort as abort:
            raise abort.error from None
        return BatchResult(seed, None)
