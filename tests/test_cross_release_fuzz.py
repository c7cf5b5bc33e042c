"""Cross-release differential fuzzing: two Drake releases in worker processes, one oracle each.

``fuzz --backend drake==1.51.1 --against drake==1.58.0`` drives both releases
in lockstep. Known release changes are set aside by the *release pair*
(``known_divergences.json``), and a finding is written with both releases'
answers, bounded by ``until``/``since``, so the file passes on each release
alone. Nothing here mocks pydrake: the workers run the real releases (their
environments are built on first use and cached, as ``--backend drake==X``
does).
"""

from __future__ import annotations

import json
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from conformance._backends.environments import DrakeEnvironmentError, find_python
from conformance._backends.loader import load_backend
from conformance._corpus.loader import default_corpus_root, load_file
from conformance._engine import Divergence, Engine, Outcome
from conformance._fuzz.campaign import Campaign
from conformance._fuzz.findings import cross_release
from conformance._fuzz.regression import drake_release, regression_scenario, write_regression
from conformance._policy.divergences import match_step
from conformance._policy.guards import arm_guards
from conformance._run.runner import run_case
from conformance.compare import Difference
from conformance.protocol import Backend, BackendId, Command, backend_id

EARLY, LATE = "1.51.1", "1.58.0"
#: The 1.51 → 1.52 change: a failing apply_transient's earlier statement reaches C up to 1.51.1.
FAILING_TRANSIENT = [
    Command("register_frame", {"name": "f1"}),
    Command("register_geometry", {"name": "g2", "frame": "world", "roles": ["proximity"]}),
    Command("register_geometry", {"name": "g3", "frame": "f1", "roles": ["proximity"]}),
    Command("create_context", {"name": "c"}),
    Command(
        "apply_transient",
        {
            "label": "t4",
            "declaration": {
                "statements": [
                    {"op": "exclude_within", "set": {"geometries": ["g2"], "frames": ["f1"]}},
                    {"op": "exclude_within", "set": {"geometries": ["@unknown"]}},
                ]
            },
        },
    ),
]


def _have_python(release: str) -> bool:
    try:
        find_python(release)
    except DrakeEnvironmentError:
        return False
    return True


needs_releases = pytest.mark.skipif(
    not (_have_python(EARLY) and _have_python(LATE)),
    reason=f"no Python for Drake {EARLY} (3.11/3.12) and {LATE} (3.12+)",
)


@pytest.fixture(scope="module")
def releases() -> Iterator[tuple[Backend, Backend]]:
    """drake==1.51.1 and drake==1.58.0 in workers, guards armed as the fuzzer arms them."""
    early, late = load_backend(f"drake=={EARLY}"), load_backend(f"drake=={LATE}")
    arm_guards((early, late))
    yield early, late
    for backend in (early, late):
        backend.close()  # type: ignore[attr-defined]


def _divergence(backend: Backend, reference: Backend, commands: list[Command]) -> Divergence:
    """The commands run on both backends, as the lockstep machine records them."""
    engine = Engine([backend, reference], reference.name)
    engine.reset()
    for command in commands:
        engine.step(command)
    differences = [Difference("state", "the last step", "the last step")]
    return Divergence(backend.name, engine.trace, differences, states=engine.observe())


# ---------------------------------------------------------------- no workers needed


def test_only_real_drake_releases_count_as_releases() -> None:
    assert drake_release(BackendId("drake==1.51.1", "1.51.1")) == "1.51.1"
    assert drake_release(BackendId("pydrake", "1.58.0")) == "1.58.0"
    # reimpl and the mutants claim a release, but their answers are not that release's.
    assert drake_release(BackendId("reimpl", "1.51.1")) is None
    assert drake_release(BackendId("mutant:allow_clears_invariants", "1.51.1")) is None


def test_a_finding_against_one_release_keeps_the_reference_answers_in_every_location(
    tmp_path: Path,
) -> None:
    """reimpl vs pydrake: one unbounded expectation per location, each with the step's error."""
    reimpl, pydrake = load_backend("reimpl"), load_backend("pydrake")
    divergence = _divergence(reimpl, pydrake, FAILING_TRANSIENT)
    path = write_regression(
        divergence,
        tmp_path,
        backend="reimpl",
        reference="pydrake",
        reference_version=pydrake.version(),
        backend_version=drake_release(backend_id(reimpl)),
    )
    expect = json.loads(path.read_text())["cases"][0]["steps"][-1]["expect"]
    assert [e["at"] for e in expect] == ["c", "model"]
    assert all("since" not in e and "until" not in e for e in expect)
    # An expectation without `error` would say the step succeeded at that location.
    assert all(e["error"]["kind"] == "unknown_geometry" for e in expect)
    (case,) = load_file(path, root=tmp_path).cases
    assert run_case(case, [pydrake]).status == {"pydrake": Outcome.PASS}


def test_the_release_pair_picks_the_known_divergence_in_both_directions() -> None:
    apply = FAILING_TRANSIENT[-1]
    reimpl = load_backend("reimpl")
    reimpl.reset()
    for command in FAILING_TRANSIENT[:-1]:
        reimpl.execute(command)
    raised = reimpl.execute(apply)  # both releases raise the same unknown_geometry error
    assert raised.error is not None

    def known(blamed: BackendId, release: str) -> str | None:
        entry = match_step(apply, raised, raised, blamed=blamed, release=release)
        return entry.id if entry is not None else None

    early, late = BackendId(f"drake=={EARLY}", EARLY), BackendId(f"drake=={LATE}", LATE)
    assert known(early, LATE) == "failed-apply-leaves-c-unchanged-since-1.52"
    assert known(BackendId("pydrake", EARLY), LATE) == "failed-apply-leaves-c-unchanged-since-1.52"
    assert known(late, EARLY) == "partial-apply-until-1.51"
    # reimpl and the mutants built on it follow the release they claim: one entry for all.
    assert known(BackendId("reimpl", EARLY), LATE) == "failed-apply-leaves-c-unchanged-since-1.52"
    assert known(BackendId("mutant:x", EARLY), LATE) == "failed-apply-leaves-c-unchanged-since-1.52"
    assert known(BackendId("drake==1.52.0", "1.52.0"), LATE) is None  # same side of the change
    assert known(BackendId(f"reimpl=={LATE}", LATE), LATE) is None


def test_the_release_scenarios_pass_on_reimpl_and_the_installed_pydrake() -> None:
    releases = load_file(default_corpus_root() / "releases" / "failed_apply.json")
    wording = load_file(default_corpus_root() / "releases" / "error_wording.json")
    backends = [load_backend("reimpl"), load_backend("pydrake")]
    for case in [*releases.cases, *wording.cases]:
        report = run_case(case, backends)
        assert set(report.status.values()) <= {Outcome.PASS, Outcome.XFAIL}, report.failures


# ---------------------------------------------------------------- two releases in workers


@needs_releases
def test_a_two_release_finding_passes_on_each_release_alone(
    releases: tuple[Backend, Backend], tmp_path: Path
) -> None:
    early, late = releases
    assert cross_release(early, late) == EARLY
    divergence = _divergence(early, late, FAILING_TRANSIENT)
    scenario = regression_scenario(
        divergence,
        backend=early.name,
        reference=late.name,
        reference_version=LATE,
        backend_version=EARLY,
    )
    expect = scenario["cases"][0]["steps"][-1]["expect"]
    shared = [e for e in expect if "since" not in e and "until" not in e]
    assert {e["at"] for e in shared} == {"c", "model"}  # the error, history, IsActive agree
    assert [(e.get("until"), e.get("since"), e["at"], e["candidates"]) for e in expect[2:]] == [
        (EARLY, None, "model", []),
        (None, LATE, "model", [["g2", "g3"]]),
    ]
    assert all(e["error"]["kind"] == "unknown_geometry" for e in expect)
    assert "Drake 1.51.1 and 1.58.0 differ" in scenario["cases"][0]["description"]

    path = write_regression(
        divergence,
        tmp_path,
        backend=early.name,
        reference=late.name,
        reference_version=LATE,
        backend_version=EARLY,
    )
    (case,) = load_file(path, root=tmp_path).cases
    for backend in (early, late, load_backend("reimpl")):
        assert run_case(case, [backend]).status == {backend.name: Outcome.PASS}
    both = run_case(case, [early, late], reference=late.name)
    assert both.status[early.name] is Outcome.FAIL  # the releases still disagree pair by pair


@needs_releases
def test_a_cross_release_campaign_sets_the_change_aside_under_its_release_id(
    releases: tuple[Backend, Backend],
) -> None:
    early, late = releases
    for backend, reference, expected in (
        (early, late, "failed-apply-leaves-c-unchanged-since-1.52"),
        (late, early, "partial-apply-until-1.51"),
    ):
        result = Campaign(
            backend=lambda b=backend: b,
            reference=lambda r=reference: r,
            seed=1,
            max_examples=20,
            steps=30,
        ).run()
        assert result.divergences == []
        assert expected in result.stats.known


@needs_releases
def test_strict_cross_release_fuzz_finds_the_1_52_change_and_writes_both_releases(
    tmp_path: Path,
) -> None:
    """In a fresh process, as a user runs it: the seed's run does not depend on pytest's imports."""
    process = subprocess.run(
        [sys.executable, "-m", "conformance", "fuzz", "--backend", f"drake=={EARLY}",
         "--against", f"drake=={LATE}", "--seed", "9", "--max-examples", "60", "--steps", "3",
         "--strict-divergences", "--out", str(tmp_path), "-q"],
        capture_output=True, text=True, timeout=300, check=False,
    )  # fmt: skip
    assert process.returncode == 1, process.stdout + process.stderr
    assert "(reproduces)" in process.stdout
    assert "each release alone meets its own (since/until) expectations" in process.stdout
    (path,) = tmp_path.glob("drake-1-51-1-vs-drake-1-58-0-*.json")
    steps = json.loads(path.read_text())["cases"][0]["steps"]
    expects = [
        s["expect"] for s in steps if s["op"] in {"apply", "apply_transient"} and "expect" in s
    ]
    bounds = {
        (e.get("until"), e.get("since"))
        for expect in expects
        for e in (expect if isinstance(expect, list) else [expect])
    }
    assert {(EARLY, None), (None, LATE)} <= bounds
