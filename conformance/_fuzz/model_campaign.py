"""``fuzz --models``: random model files as scenario cases, run on two backends by the runner.

Each example is one case (``model_cases``), in the scenario grammar:

1. now and then anchored proximity geometry from the case's own source
   (``register_geometry`` on ``world``: bodies welded to the world are
   filtered against it, whichever source it comes from);
2. now and then ``set_adjacent_filters`` (when both backends have the op);
3. ``add_models`` of a scene from ``conformance._fuzz.model_scenes``: a
   URDF, SDFormat or model directives document, parsed from a string or a
   file, with the files it needs (packages, included models and model
   directories, meshes, a second directives file), sometimes with a model
   name prefix; one in ``invalid_share`` (4) examples has a fault Drake refuses
   (a broken group or joint, an XML error, a missing include, a directives
   fault), for the parse errors, and then, one time in four, a broken scene
   for each other fault of every format (with
   ``auto_renaming``, so that their models' names do not clash first).
   Now and then the same scene is parsed again
   (under the prefix ``q``, with ``auto_renaming``, with the same Parser, or
   as it is: a name clash), and now and then the first model is renamed
   (``rename_model_instance``) and the scene parsed again, with the same
   Parser or a new one, which may rename (Drake issue #21316);
4. after **every** ``add_models``: the Parser's ``collision_filter_groups``
   report (when both backends have the op) and a ``model_inventory``;
5. for a valid scene, up to two bodies the case adds (``add_rigid_body``,
   ``register_collision_geometry``: ``B0`` with ``b0``, ``B1`` with ``b1``),
   each on a joint of any ``add_joint`` type from the world, a parsed body
   or the other added body; and up to two ``apply`` steps, before or after
   Finalize, whose declarations name the parsed bodies' frames (``m::l1``),
   their collision geometry (``m::l1/c0``), the added bodies, the world and
   the anchored geometry;
6. ``finalize``, a ``model_inventory``, then ``check``.

``without`` names grammar elements (``model_scenes.SWITCHES``) to leave out,
for a backend that lacks them; ``model_coverage`` counts what the drawn
files and the reference's answers reached.

The case runs through ``conformance._run.runner.run_case``, the corpus
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
again up to its last ``add_models`` step and the reports after it, whose
disagreement is the finding.

``ModelCampaign`` is ``Campaign`` with this example in place of the lockstep
machine: the same seeds, batches, budgets, Hypothesis settings and results.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from hypothesis import given, reject
from hypothesis import seed as hypothesis_seed
from hypothesis import strategies as st

from conformance._corpus.loader import Case, ScenarioFile, Step
from conformance._engine import Divergence, HarnessError, Outcome, known_in
from conformance._fuzz import strategies as cs
from conformance._fuzz.branch_coverage import example_feedback
from conformance._fuzz.campaign import BatchResult, Campaign, CampaignResult, fuzz_settings
from conformance._fuzz.model_coverage import ModelCoverage
from conformance._fuzz.model_scenes import (
    DIRECTIVES,
    SCENE_FORMATS,
    SWITCHES,
    Scene,
    model_scenes,
    scene_faults,
)
from conformance._fuzz.models import WORLD
from conformance._fuzz.sequence_coverage import SequenceBook
from conformance._fuzz.stats import FuzzStats, HarnessAbort, ShrinkTimeUp, stop_point
from conformance._grammar import GRAMMAR, features_of
from conformance._grammar.multibody import JOINT_TYPES
from conformance._run.case_report import CaseReport
from conformance._run.runner import run_case
from conformance.compare import Difference
from conformance.protocol import Backend, Command, Result, backend_id

__all__ = [
    "ADDED_BODY",
    "MODEL_FEATURES",
    "MODEL_SWITCHES",
    "SEQUENCE_OPS_ISSUED",
    "ModelCampaign",
    "model_case",
    "model_cases",
    "run_model_case",
]

#: The grammar elements of a case, besides its scenes': the renaming flow, a directives
#: scene parsed again under a prefix, and a directives scene parsed again at all.
_CASE_SWITCHES = frozenset({"rename-then-parse", "dmd:prefix", "dmd:again"})
#: The grammar elements ``without`` may leave out: the scenes' and the case's.
MODEL_SWITCHES: tuple[str, ...] = (*SWITCHES, *sorted(_CASE_SWITCHES))
#: What a backend needs for ``fuzz --models`` at all.
MODEL_FEATURES = frozenset({"multibody", "parsing"})
#: The sequence ops (``sequence_coverage.SEQUENCE_OPS``) a model case issues: its apply steps.
SEQUENCE_OPS_ISSUED = frozenset({"apply"})
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
#: How the scene is parsed a second time, if at all: under another prefix, with
#: SetAutoRenaming (Drake names the instance ``m_1``), with the same Parser, or as it is
#: (the names clash).
_AGAIN: tuple[dict[str, Any] | None, ...] = (
    None,
    None,
    {"prefix": "q"},
    {"auto_renaming": True},
    {"reuse_parser": True},
    {},
)
#: After renaming the first model (``<name>_old``), how the scene is parsed again: with a
#: new Parser, the same one (Drake issue #21316), or a new one that renames.
_AFTER_RENAME: tuple[dict[str, Any], ...] = ({}, {"reuse_parser": True}, {"auto_renaming": True})
_RENAMED = "_old"
_ANCHORED = "w"
_FILE = ScenarioFile(Path("fuzz-models"), "fuzz --models", "random models")


# ------------------------------------------------------------------ cases
def _parse_args(scene: Scene, prefix: str | None) -> dict[str, Any]:
    """The ``add_models`` arguments of a scene: its files, and its path or text."""
    args: dict[str, Any] = {}
    if scene.files:
        args["files"] = dict(scene.files)
    if scene.path is not None:
        args["path"] = scene.path
    else:
        args |= {"text": scene.text, "format": scene.format}
    if prefix is not None:
        args["prefix"] = prefix
    return args


@dataclass(frozen=True)
class _Plan:
    """What a case does besides its scene, drawn before it (see ``model_cases``)."""

    anchored: list[str]
    adjacent: bool | None
    prefix: str | None
    again: dict[str, Any] | None
    rename: dict[str, Any] | None
    added: list[tuple[dict[str, Any], str | None, int]]
    applies: list[tuple[Any, bool]]
    reports: list[str] = field(default_factory=list)


def _directives_plan(plan: _Plan, without: frozenset[str]) -> _Plan:
    """The plan for a directives scene: no prefix (it scopes directives in ways of their
    own), and no parse again under a prefix (``dmd:prefix``) or at all (``dmd:again``)."""
    plan = replace(plan, prefix=None)
    if "dmd:prefix" in without and plan.again is not None and "prefix" in plan.again:
        plan = replace(plan, again=None)
    if "dmd:again" in without:
        plan = replace(plan, again=None, rename=None)
    return plan


def _reports(plan: _Plan) -> list[Command]:
    return [Command(op, {}) for op in plan.reports]


def _parses(scene: Scene, plan: _Plan) -> list[Command]:
    """The ``add_models`` steps, each followed by the reports."""
    first = _parse_args(scene, plan.prefix)
    commands = [Command("add_models", first), *_reports(plan)]
    if plan.again is not None:
        again = dict(first)
        if "prefix" in plan.again or "reuse_parser" in plan.again:
            again.pop("prefix", None)
        again |= plan.again
        commands += [Command("add_models", again), *_reports(plan)]
    if plan.rename is not None:
        scope = "" if plan.prefix is None else f"{plan.prefix}::"
        top = f"{scope}{scene.top}"
        commands.append(
            Command("rename_model_instance", {"model": top, "name": f"{top}{_RENAMED}"})
        )
        again = dict(first)
        if "reuse_parser" in plan.rename:
            again.pop("prefix", None)
        commands += [Command("add_models", again | plan.rename), *_reports(plan)]
    return commands


@st.composite
def model_cases(
    draw: st.DrawFn,
    *,
    formats: tuple[str, ...] = SCENE_FORMATS,
    features: frozenset[str] | None = None,
    invalid_share: int = 4,
    max_anchored: int = 2,
    max_applies: int = 2,
    without: frozenset[str] = frozenset(),
) -> list[Command]:
    """The commands of one example (see the module doc).

    ``features``: what both backends support (default: everything), so an op
    neither has is never drawn. One example in ``invalid_share`` has a broken
    scene (0: none). ``without``: grammar elements left out
    (``model_scenes.SWITCHES``, and ``rename-then-parse``).
    """
    have = (lambda tag: True) if features is None else features.__contains__
    # Everything but the scene first: a draw after the scene that depends on its
    # bodies keeps the shrinker from deleting bodies (measured: half the shrunk
    # models kept unneeded bodies). Declarations are drawn as templates, resolved
    # against the scene's names once it exists.
    invalid = invalid_share > 0 and draw(st.integers(0, invalid_share - 1)) == invalid_share - 1
    anchored = [f"{_ANCHORED}{i}" for i in range(draw(st.integers(0, max_anchored)))]
    adjacent = draw(st.sampled_from((None, False, True)))
    if not have(GRAMMAR["set_adjacent_filters"].feature):
        adjacent = None
    prefix = draw(st.sampled_from((None, _PREFIX)))
    again = draw(st.sampled_from(_AGAIN))
    rename = None
    if "rename-then-parse" not in without and draw(st.integers(0, 3)) == 3:
        rename = draw(st.sampled_from(_AFTER_RENAME))
    reports = ["model_inventory"]
    if have(GRAMMAR["collision_filter_groups"].feature):
        reports.insert(0, "collision_filter_groups")
    plan = _Plan(
        anchored,
        adjacent,
        prefix,
        again,
        rename,
        draw(_ADDED_BODIES),
        draw(st.lists(st.tuples(cs.declaration_templates(), st.booleans()), max_size=max_applies)),
        reports,
    )
    scene_without = without - _CASE_SWITCHES
    scene = draw(model_scenes(formats=formats, invalid=invalid, without=scene_without))
    if scene.format == DIRECTIVES:
        plan = _directives_plan(plan, without)
    # An invalid example parses more broken scenes, with the next faults of their table:
    # the faults are many, the invalid examples few.
    extra: list[Scene] = []
    if scene.fault is not None:
        # Other faults too, of every format, one broken scene each, one time in two each:
        # the faults are many, the invalid examples few (one fault per example left one of
        # fourteen unreached at seed 1 x 300, one in four each left one). A shrunk finding
        # keeps the scenes it needs.
        for fmt in formats:
            for index, fault in enumerate(scene_faults(fmt, scene_without)):
                if (fmt, fault) != (scene.format, scene.fault) and draw(st.booleans()):
                    broken_scenes = model_scenes(
                        formats=(fmt,), invalid=True, without=scene_without, fault_index=index
                    )
                    extra.append(draw(broken_scenes))
    commands = [
        Command("register_geometry", {"name": name, "frame": WORLD, "roles": ["proximity"]})
        for name in plan.anchored
    ]
    if plan.adjacent is not None:
        commands.append(Command("set_adjacent_filters", {"value": plan.adjacent}))
    commands += _parses(scene, plan)
    for broken in extra:  # renamed, or their models' names would clash before the fault
        args = _parse_args(broken, None) | {"auto_renaming": True}
        commands += [Command("add_models", args), *_reports(plan)]
    finalize = [Command("finalize", {}), Command("model_inventory", {}), Command("check", {})]
    if not scene.valid:
        return commands + finalize
    return commands + _on_top(scene, plan, finalize)


def _renamed(name: str, scene: Scene, plan: _Plan) -> str:
    """A body or geometry name of the first parse after the renaming, if any: the first
    model's own bodies are then ``<top>_old::...`` (its nested models keep their names;
    the scene parsed again may fail)."""
    scope = "" if plan.prefix is None else f"{plan.prefix}::"
    top = f"{scope}{scene.top}::"
    if plan.rename is None or not name.startswith(top):
        return name
    rest = name.removeprefix(top)
    if "::" in rest.split("/", 1)[0]:
        return name
    return f"{scope}{scene.top}{_RENAMED}::{rest}"


def _on_top(scene: Scene, plan: _Plan, finalize: list[Command]) -> list[Command]:
    """The bodies the case adds and the declarations it applies, with ``finalize``."""
    scope = "" if plan.prefix is None else f"{plan.prefix}::"
    frames = [_renamed(name, scene, plan) for name in scene.bodies(scope)]
    geometries = [_renamed(name, scene, plan) for name in scene.geometries(scope)]
    solid_names = {
        f"{scope}{name}::{body}"
        for name, model, _ in scene.instances
        for body, b in model.scoped_bodies()
        if any(g.collision for g in b.geometries)
    }
    solid_names = {_renamed(name, scene, plan) for name in solid_names}
    # Parents with collision geometry first: there a joint type shows in C.
    solid = [f for f in frames if f in solid_names]
    parents = [*solid, WORLD, *(f for f in frames if f not in solid_names)]
    commands = []
    for i, (instance, joint_type, pick) in enumerate(plan.added):
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
    geometries += plan.anchored
    frames.append(WORLD)
    finalize = list(finalize)
    for template, after in plan.applies:
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
def _broken(report: CaseReport, commands: list[Command]) -> HarnessError | None:
    """A HarnessError if a backend broke, skipped the case, or the case was cut short (its
    commands without ``check``, which a reproducer cannot hold without expectations)."""
    commands = [c for c in commands if c.op != "check"]
    skipped = [
        f"{n} ({report.skip_reasons[n]})" for n, s in report.status.items() if s is Outcome.SKIP
    ]
    if skipped:
        return HarnessError(f"a backend cannot run model cases: {', '.join(skipped)}", commands)
    if report.broken or report.aborted:
        return HarnessError(report.aborted or "a backend broke", commands)
    return None


def _divergence(report: CaseReport, backend: str) -> Divergence:
    """The Divergence of the case's first disagreement: the steps up to it, every answer."""
    assert report.trace is not None
    failures = report.failures_of(backend)
    at = min(f.index for f in failures)
    trace = replace(report.trace, records=report.trace.records[: at + 1])
    differences = [Difference(f.what, f.expected, f.actual) for f in failures if f.index == at]
    # Every step of a case without a scene is observed.
    states = {n: o for n, o in trace.records[-1].observations.items() if o is not None}
    return Divergence(backend, trace, differences, states=states)


def _known(divergence: Divergence, backend: Backend, reference: Backend, stats: FuzzStats) -> bool:
    """Counts and returns True if a known divergence describes a step of ``divergence``."""
    known = known_in(divergence.trace, backend_id(backend), reference.version())
    if known is not None:
        stats.known[known.id] = stats.known.get(known.id, 0) + 1
    return known is not None


#: The steps that report on a parse (``model_cases`` puts them after every add_models).
_REPORTS = frozenset({"collision_filter_groups", "model_inventory"})


def run_model_case(
    commands: list[Command],
    backend: Backend,
    reference: Backend,
    *,
    step_timeout: float | None = None,
    on_results: Callable[[list[Command], list[Result]], None] | None = None,
) -> Divergence | None:
    """Runs the case on both backends; the Divergence of their first disagreement, or None.

    ``on_results`` gets the commands and the reference's results (for
    coverage). Raises HarnessError for a backend that broke (see the module
    doc).
    """
    report = run_case(
        model_case(commands),
        [backend, reference],
        reference=reference.name,
        strict_divergences=True,
        step_timeout=step_timeout,
    )
    trace = report.traces.get(reference.name)
    if on_results is not None and trace is not None:
        on_results(commands, list(trace.results))
    if report.aborted and not report.broken and "add_models" in [c.op for c in commands]:
        # A name the backend's parse did not make: compare the case up to the last
        # add_models and its reports.
        last = max(i for i, c in enumerate(commands) if c.op == "add_models") + 1
        while last < len(commands) and commands[last].op in _REPORTS:
            last += 1
        shorter = run_model_case(commands[:last], backend, reference, step_timeout=step_timeout)
        if shorter is not None:
            return shorter
    broken = _broken(report, commands)
    if broken is not None:
        raise broken
    if not report.failures_of(backend.name):
        return None
    return _divergence(report, backend.name)


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

    #: Formats drawn (default: URDF, SDFormat and model directives).
    formats: tuple[str, ...] = SCENE_FORMATS
    #: One example in this many has a broken model (0: none).
    invalid_share: int = 4
    #: Grammar elements left out (``model_scenes.SWITCHES``, ``rename-then-parse``).
    without: frozenset[str] = frozenset()
    #: In a measuring run, ``hypothesis.target`` the new reimpl branches of each case
    #: (``branch_coverage.example_feedback``). Off by default: then ``fuzz --models
    #: --coverage`` draws what ``fuzz --models`` draws, whose grammar table is checked at
    #: seed 1 x 300 (with it on, ``rename-reuse-parser`` was left unreached there).
    branch_feedback: bool = False

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
            formats=self.formats,
            features=features,
            invalid_share=self.invalid_share,
            without=self.without,
        )
        if not isinstance(stats.coverage, ModelCoverage):
            stats.coverage = ModelCoverage()
        coverage = stats.coverage

        def follow(commands: list[Command], results: list[Result]) -> None:
            coverage.follow_case(commands, results)
            book = SequenceBook()
            for command, result in zip(commands, results, strict=False):
                book.follow(command, result)
            stats.sequences.close(book)

        @hypothesis_seed(seed)
        @fuzz_settings(max_examples=size or 100, database=self.database)
        @given(strategy)
        def example(commands: list[Command]) -> None:
            stop_point(stats)
            start = time.perf_counter()
            try:
                divergence = run_model_case(
                    commands,
                    backend,
                    reference,
                    step_timeout=self.step_timeout,
                    on_results=follow,
                )
            except HarnessError as exc:
                raise HarnessAbort(exc) from None
            finally:
                stats.backend_seconds += time.perf_counter() - start
                stats.examples += 1
                stats.steps += len(commands)
                if stats.on_step is not None:
                    stats.on_step(stats)
            if self.branch_feedback:
                example_feedback()
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
