"""The runner judges against a reference, and acts on known divergences and release guards."""

from __future__ import annotations

import json
from pathlib import Path

from conformance._backends.loader import load_backend
from conformance._corpus.loader import Step, load_corpus, load_file
from conformance._engine import Outcome
from conformance._policy.divergences import KnownDivergence, StepPattern, XfailMatcher
from conformance._policy.guards import armed_guards
from conformance._policy.versions import VersionRange
from conformance._run.runner import _observed_steps, choose_reference, run_case
from conformance.protocol import Command, ErrorInfo, ErrorKind, Observation, Result

MUTANT = "conformance._testing.mutants:allow_clears_invariants"
FILE = "statements/allow_within"
CASES = {c.qualified_name: c for f in load_corpus() for c in f.cases if f.name == FILE}
CASE = next(c for name, c in CASES.items() if "world frame" in name)


def divergence(
    cases: tuple[str, ...], releases: VersionRange, ops: frozenset[str] = frozenset({"apply"})
) -> KnownDivergence:
    return KnownDivergence(
        id="test-entry",
        kind="reimpl_vs_drake",
        releases=releases,
        observed="",
        reason="",
        scenarios=(),
        tests=(),
        xfail=XfailMatcher(releases=releases, cases=cases, steps=(StepPattern(ops=ops),)),
    )


def test_pydrake_is_the_reference_wherever_it_is_listed() -> None:
    mutant, pydrake = load_backend(MUTANT), load_backend("pydrake")
    assert choose_reference([mutant, pydrake]) is pydrake
    assert choose_reference([mutant, pydrake], "pydrake") is pydrake
    assert choose_reference([mutant, load_backend("reimpl")]) is mutant


def test_a_disagreement_fails_the_backend_and_not_the_reference() -> None:
    mutant, pydrake = load_backend(MUTANT), load_backend("pydrake")
    report = run_case(CASE, [mutant, pydrake])
    assert report.reference == "pydrake"
    assert report.status == {mutant.name: Outcome.FAIL, "pydrake": Outcome.PASS}
    assert {f.backend for f in report.failures} == {mutant.name}


def test_a_failure_a_known_divergence_describes_is_xfail_with_its_id() -> None:
    mutant, pydrake = load_backend(MUTANT), load_backend("pydrake")
    entries = [divergence((f"{FILE} > *world frame*",), VersionRange(since="1.12"))]
    report = run_case(CASE, [mutant, pydrake], divergences=entries)
    assert report.status[mutant.name] is Outcome.XFAIL
    assert report.xfails == {mutant.name: "test-entry"}
    assert report.passed


def test_a_known_divergence_whose_step_pattern_misses_the_diverging_step_does_not_act() -> None:
    mutant, pydrake = load_backend(MUTANT), load_backend("pydrake")
    entries = [divergence((f"{FILE} > *",), VersionRange(since="1.12"), frozenset({"finalize"}))]
    report = run_case(CASE, [mutant, pydrake], divergences=entries)
    assert report.status[mutant.name] is Outcome.FAIL


def test_the_cases_of_a_known_divergence_narrow_where_its_step_pattern_acts() -> None:
    mutant, pydrake = load_backend(MUTANT), load_backend("pydrake")
    entries = [divergence((f"{FILE} > no such case",), VersionRange(since="1.12"))]
    report = run_case(CASE, [mutant, pydrake], divergences=entries)
    assert report.status[mutant.name] is Outcome.FAIL
    entries = [divergence((), VersionRange(since="1.12"))]
    report = run_case(CASE, [mutant, pydrake], divergences=entries)
    assert report.xfails == {mutant.name: "test-entry"}


def test_strict_divergences_turn_xfail_back_into_failure() -> None:
    mutant, pydrake = load_backend(MUTANT), load_backend("pydrake")
    entries = [divergence((f"{FILE} > *",), VersionRange(since="1.12"))]
    report = run_case(CASE, [mutant, pydrake], divergences=entries, strict_divergences=True)
    assert report.status[mutant.name] is Outcome.FAIL


def test_a_known_divergence_outside_the_reference_release_does_not_act() -> None:
    mutant, pydrake = load_backend(MUTANT), load_backend("pydrake")
    entries = [divergence((f"{FILE} > *",), VersionRange(since="99.0"))]
    report = run_case(CASE, [mutant, pydrake], divergences=entries)
    assert report.status[mutant.name] is Outcome.FAIL


def test_the_anchored_deactivation_guard_is_armed_only_by_releases_1_55_to_1_58() -> None:
    assert "deactivate-anchored-aborts" not in armed_guards(["1.51.1"])
    assert "deactivate-anchored-aborts" in armed_guards(["1.51.1", "1.58.0"])
    assert "deactivate-anchored-aborts" in armed_guards(["1.55.0"])
    assert "deactivate-anchored-aborts" not in armed_guards(["1.59.0"])
    assert "older-context-pose-port-aborts" in armed_guards(["1.51.1"])


class _CountingObserver:
    """reimpl, counting observe() calls."""

    def __init__(self) -> None:
        self._inner = load_backend("reimpl")
        self.name = "counting"
        self.observed = 0

    def version(self) -> str:
        return self._inner.version()

    def features(self) -> frozenset[str]:
        return self._inner.features()

    def reset(self) -> None:
        self._inner.reset()

    def execute(self, command: Command) -> Result:
        return self._inner.execute(command)

    def observe(self) -> Observation:
        self.observed += 1
        return self._inner.observe()


def test_a_scene_is_observed_once_after_its_last_registration(tmp_path: Path) -> None:
    """40 registrations, then two steps (one without expectations): 3 observations, not 42."""
    scenario = {
        "description": "observation count",
        "cases": [
            {
                "description": "a scene of 20 frames and 20 geometries",
                "scene": {
                    "frames": [{"name": f"f{i}"} for i in range(20)],
                    "geometries": [
                        {"name": f"g{i}", "frame": f"f{i}", "roles": ["proximity"]}
                        for i in range(20)
                    ],
                },
                "steps": [
                    {"op": "collision_filtered", "pair": ["g0", "g1"]},
                    {"op": "check", "expect": {"history": False}},
                ],
            }
        ],
    }
    path = tmp_path / "count.json"
    path.write_text(json.dumps(scenario))
    (case,) = load_file(path, root=tmp_path).cases
    counting = _CountingObserver()
    report = run_case(case, [counting, load_backend("reimpl")])
    assert report.status == {"counting": Outcome.PASS, "reimpl": Outcome.PASS}
    assert counting.observed == 3


def test_state_is_observed_after_the_scene_and_after_every_later_step() -> None:
    steps = [
        Step(0, "register_frame", {"name": "f"}, ()),
        Step(0, "register_frame", {"name": "g"}, ()),
    ]
    assert _observed_steps(steps) == [False, True]
    with_expectation = [Step(0, "register_frame", {"name": "f"}, ({"history": False},)), steps[1]]
    assert _observed_steps(with_expectation) == [True, True]
    assert _observed_steps([*steps, Step(1, "check", {}, ())]) == [False, True, True]


def test_on_step_counts_every_step_of_every_backend_as_it_finishes() -> None:
    calls: list[tuple[int, int]] = []
    backends = [load_backend("reimpl"), load_backend("pydrake")]
    run_case(CASE, backends, on_step=lambda done, total: calls.append((done, total)))
    total = 2 * len(CASE.steps)
    assert calls == [(done, total) for done in range(1, total + 1)]


class _RefusesFirstGeometry(_CountingObserver):
    """reimpl, but the first register_geometry fails (as a backend might)."""

    def execute(self, command: Command) -> Result:
        if command.op == "register_geometry" and command.args["name"] == "g0":
            return Result(error=ErrorInfo(ErrorKind.REFUSED, "refused"))
        return super().execute(command)


def test_a_scene_registration_that_fails_fails_the_case_even_where_state_is_not_observed(
    tmp_path: Path,
) -> None:
    scenario = {
        "description": "scene error",
        "cases": [
            {
                "description": "two geometries",
                "scene": {
                    "frames": [{"name": "f"}],
                    "geometries": [
                        {"name": f"g{i}", "frame": "f", "roles": ["proximity"]} for i in range(2)
                    ],
                },
                "steps": [{"op": "check", "expect": {"candidates": []}}],
            }
        ],
    }
    path = tmp_path / "scene_error.json"
    path.write_text(json.dumps(scenario))
    (case,) = load_file(path, root=tmp_path).cases
    backend = _RefusesFirstGeometry()
    report = run_case(case, [backend])
    assert report.status == {"counting": Outcome.FAIL}
    assert [f.what for f in report.failures] == ["scene register_geometry g0"]
    assert backend.observed == 2  # after the scene (g1, not g0), and after the check
