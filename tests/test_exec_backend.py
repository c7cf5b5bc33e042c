"""``exec:CMD``: a backend in any language, over the worker protocol (docs/protocol.md).

Three programs speak it here: the Python worker that ``drake==X`` runs
(``python -m conformance._backends.worker``, on pydrake 1.51.1), the JavaScript
backend of ``examples/node_backend`` (skipped where ``node`` is absent), and
``tests/fake_exec_backend.py``, reimpl with one fault on demand. Faults are
driven through the real CLI in a subprocess, as a user meets them.
"""

from __future__ import annotations

import json
import os
import shlex
import shutil
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import jsonschema
import pytest

from conformance._backends import exec_backend
from conformance._backends.calls import StepTimeoutError
from conformance._backends.exec_backend import (
    CORPUS_PLACEHOLDER,
    ExecBackend,
    ExecSpecError,
    exec_spec_command,
    portable,
)
from conformance._backends.loader import BackendLoadError, load_backend
from conformance._backends.wire import CALLS, PROTOCOL_VERSION
from conformance._corpus.loader import default_corpus_root, load_corpus, load_file
from conformance._corpus_root import corpus_root
from conformance._engine import Outcome
from conformance._fuzz import operations
from conformance._fuzz.lockstep import _supported
from conformance._grammar import GRAMMAR, features_of
from conformance._run.runner import run_case
from conformance.cli.exit_codes import EXIT_FAILURE, EXIT_OK, EXIT_USAGE
from conformance.protocol import Command, ErrorKind
from conformance.protocol_schemas import (
    command_schema,
    message_names,
    problem,
    schema,
    schema_folder,
)

REPO = Path(__file__).resolve().parents[1]
ROOT = default_corpus_root()
ALLOW_WITHIN = ROOT / "statements" / "allow_within.json"
FAKE = REPO / "tests" / "fake_exec_backend.py"
NODE_BACKEND = Path("examples") / "node_backend" / "backend.js"
#: The node backend, named as a user names it from the repository's root.
NODE_SPEC = f"exec:node {NODE_BACKEND}"
#: What the node backend declares.
NODE_FEATURES = frozenset({"core", "transient"})
#: The Python worker that drake==X runs, on this interpreter's pydrake (1.51.1).
WORKER_SPEC = "exec:" + shlex.join([sys.executable, "-m", "conformance._backends.worker"])

needs_node = pytest.mark.skipif(
    shutil.which("node") is None,
    reason="node is not on PATH: examples/node_backend needs Node.js (v18 or later)",
)


def fake_spec(*args: str) -> str:
    return "exec:" + shlex.join([sys.executable, str(FAKE), *args])


def cli(*argv: str, cwd: Path = REPO) -> subprocess.CompletedProcess[str]:
    """``python -m conformance ARGV`` with this checkout's package, in ``cwd``."""
    return subprocess.run(
        [sys.executable, "-m", "conformance", *argv],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=600,
        env={**os.environ, "PYTHONPATH": str(REPO)},
        check=False,
    )


def assert_clean_exit(process: subprocess.CompletedProcess[str], code: int) -> None:
    assert process.returncode == code, process.stdout[-3000:] + process.stderr[-3000:]
    assert "Traceback" not in process.stderr
    assert "Traceback" not in process.stdout


@pytest.fixture
def at_repo(monkeypatch: pytest.MonkeyPatch) -> None:
    """Runs in the repository's root: exec commands start in the caller's folder."""
    monkeypatch.chdir(REPO)


@pytest.fixture
def node(at_repo: None) -> Iterator[ExecBackend]:
    backend = load_backend(NODE_SPEC)
    assert isinstance(backend, ExecBackend)
    yield backend
    backend.close()


# ------------------------------------------------------------------ the spec
def test_an_exec_spec_is_split_as_a_shell_splits_it() -> None:
    assert exec_spec_command("exec:node 'my dir/backend.js' --fast") == [
        "node",
        "my dir/backend.js",
        "--fast",
    ]
    assert exec_spec_command("drake==1.51.1") is None
    with pytest.raises(ExecSpecError, match="No closing quotation"):
        exec_spec_command("exec:node 'backend.js")
    with pytest.raises(ExecSpecError, match="no command after 'exec:'"):
        exec_spec_command("exec:  ")


# ------------------------------------------------------------- the handshake
@needs_node
def test_the_handshake_gives_the_node_backends_name_release_and_features(
    node: ExecBackend,
) -> None:
    assert node.name == "node-filter"
    assert node.version() == "1.51.1"
    assert node.features() == NODE_FEATURES
    assert node.isolated


def test_the_python_worker_is_the_exec_backend_named_after_the_release_it_runs(
    at_repo: None,
) -> None:
    pydrake = load_backend("pydrake")
    worker = load_backend(WORKER_SPEC)
    assert isinstance(worker, ExecBackend)
    try:
        assert worker.name == f"drake=={pydrake.version()}"
        assert worker.version() == pydrake.version()
        assert worker.features() == pydrake.features()
    finally:
        worker.close()


def test_a_backend_of_another_protocol_version_is_refused_in_one_line_with_exit_two() -> None:
    spec = fake_spec("--fault", "protocol-2")
    process = cli("run", str(ALLOW_WITHIN), "--backend", spec, "--backend", "pydrake")
    assert_clean_exit(process, EXIT_USAGE)
    assert process.stderr == (
        f"error: backend {spec!r} at hello: it speaks protocol 2; this harness speaks "
        f"protocol {PROTOCOL_VERSION} (docs/protocol.md)\n"
    )


@pytest.mark.parametrize(
    ("spec", "message"),
    [
        (fake_spec("--fault", "garbage"), " at hello: it answered a line that is not JSON: "
         "'hello, harness' (stdout carries protocol lines only; write anything else to stderr)"),
        ("exec:no-such-program-anywhere --x", " at start: cannot run 'no-such-program-anywhere': "
         "No such file or directory"),
        ("exec:", ": no command after 'exec:' (e.g. exec:'node backend.js')"),
        ("exec:node 'backend.js", ": cannot split the command: No closing quotation"),
    ],
    ids=["handshake garbage", "command not found", "no command", "broken quoting"],
)  # fmt: skip
def test_a_command_that_cannot_be_a_backend_is_one_error_line_and_exit_two(
    spec: str, message: str
) -> None:
    process = cli("run", str(ALLOW_WITHIN), "--backend", spec, "--backend", "pydrake")
    assert_clean_exit(process, EXIT_USAGE)
    assert process.stderr == f"error: backend {spec!r}{message}\n"


def test_a_handshake_that_fails_its_schema_names_the_member_and_the_rule(
    tmp_path: Path, at_repo: None
) -> None:
    script = tmp_path / "half_hello.py"
    script.write_text(
        "import sys\nsys.stdin.readline()\n"
        'print(\'{"value": {"protocol": 1, "name": "half", "version": "1.51.1"}}\', flush=True)\n'
    )
    with pytest.raises(BackendLoadError) as raised:
        load_backend("exec:" + shlex.join([sys.executable, str(script)]))
    assert str(raised.value).endswith(
        "at hello: its hello response fails hello.response.json at .value: "
        "'features' is a required property"
    )


# ------------------------------------------------------- isolation, mid-run
def _second_step(case_index: int) -> str:
    """The label the runner gives the second step of ALLOW_WITHIN's case ``case_index``."""
    step = load_file(ALLOW_WITHIN, root=ROOT).cases[case_index].steps[1]
    return f"{step.label} ({step.op})"


def test_a_process_that_dies_mid_case_is_a_crash_at_that_step_and_a_new_one_takes_over(
    tmp_path: Path,
) -> None:
    spec = fake_spec("--fault", "crash", "--case", "2", "--once", str(tmp_path / "crashed"))
    process = cli("run", str(ALLOW_WITHIN), "--backend", spec, "--backend", "pydrake",
                  "--json", str(tmp_path / "report.json"))  # fmt: skip
    assert_clean_exit(process, EXIT_FAILURE)
    report = json.loads((tmp_path / "report.json").read_text())
    statuses = [case["status"]["fake-reimpl"] for case in report["cases"]]
    assert statuses == ["pass", "crash"] + ["pass"] * (len(statuses) - 2)
    assert report["cases"][1]["aborted"] == (
        f"backend 'fake-reimpl' at {_second_step(1)}: the worker exited with status 3"
    )
    assert report["aborted"] is None  # the run went on
    assert process.stderr.count("(a new worker takes over)") == 1


def test_a_process_that_dies_arming_guards_is_a_crash_of_the_first_case_not_a_traceback(
    tmp_path: Path,
) -> None:
    """arm_guards travels just before the case's batch, so a death there is that step's."""
    spec = fake_spec("--fault", "arm-crash", "--once", str(tmp_path / "crashed"))
    process = cli("run", str(ALLOW_WITHIN), "--backend", spec, "--backend", "pydrake",
                  "--json", str(tmp_path / "report.json"))  # fmt: skip
    assert_clean_exit(process, EXIT_FAILURE)
    report = json.loads((tmp_path / "report.json").read_text())
    statuses = [case["status"]["fake-reimpl"] for case in report["cases"]]
    assert statuses == ["crash"] + ["pass"] * (len(statuses) - 1)
    step = load_file(ALLOW_WITHIN, root=ROOT).cases[0].steps[0]
    assert report["cases"][0]["aborted"] == (
        f"backend 'fake-reimpl' at {step.label} ({step.op}): the worker exited with status 3"
    )


def test_a_process_that_hangs_mid_case_is_a_timeout_at_that_step_and_is_replaced(
    tmp_path: Path,
) -> None:
    spec = fake_spec("--fault", "hang", "--case", "2", "--once", str(tmp_path / "hung"))
    process = cli("run", str(ALLOW_WITHIN), "--backend", spec, "--backend", "pydrake",
                  "--step-timeout", "2", "--json", str(tmp_path / "report.json"))  # fmt: skip
    assert_clean_exit(process, EXIT_FAILURE)
    report = json.loads((tmp_path / "report.json").read_text())
    statuses = [case["status"]["fake-reimpl"] for case in report["cases"]]
    assert statuses == ["pass", "timeout"] + ["pass"] * (len(statuses) - 2)
    assert report["cases"][1]["aborted"] == (
        f"backend 'fake-reimpl' at {_second_step(1)}: no answer within 2 s (--step-timeout)"
    )
    assert report["aborted"] is None


def test_a_malformed_response_names_the_backend_the_step_and_the_rule_and_exits_two(
    tmp_path: Path,
) -> None:
    spec = fake_spec("--fault", "malformed", "--case", "2")
    process = cli("run", str(ALLOW_WITHIN), "--backend", spec, "--backend", "pydrake",
                  "--json", str(tmp_path / "report.json"))  # fmt: skip
    assert_clean_exit(process, EXIT_USAGE)
    case = load_file(ALLOW_WITHIN, root=ROOT).cases[1]
    error = (
        f"error: {ALLOW_WITHIN}: case {case.description!r}: backend 'fake-reimpl' at "
        f"{_second_step(1)}: its steps response fails steps.response.json at .value.result: "
        "Additional properties are not allowed ('valu' was unexpected)\n"
    )
    assert error in process.stderr
    assert "stopped after 2 of " in process.stderr
    report = json.loads((tmp_path / "report.json").read_text())
    assert [c["status"].get("fake-reimpl") for c in report["cases"]] == ["pass", "error"]


# ----------------------------------------------------------------- schemas
def test_every_schema_file_is_a_valid_draft_2020_12_schema_with_its_own_id() -> None:
    for name in message_names():
        jsonschema.Draft202012Validator.check_schema(schema(name))
        assert schema(name)["$id"].endswith(f"/protocol/1/{name}")
    for call in CALLS:
        assert f"{call}.request.json" in message_names()
        assert f"{call}.response.json" in message_names()


def test_the_command_schema_is_the_one_generated_from_the_grammar() -> None:
    """``python -m conformance schema --write`` rewrites it after a grammar change."""
    shipped = json.loads((schema_folder() / "command.json").read_text(encoding="utf-8"))
    assert shipped == command_schema()


def test_the_error_kinds_of_the_schema_are_the_protocols() -> None:
    kinds = schema("values.json")["$defs"]["error"]["properties"]["kind"]["enum"]
    assert kinds == [kind.value for kind in ErrorKind]


def _validate_transcript(transcript: list[tuple[str, Any]]) -> set[str]:
    """Checks every request and response against its schema; the schemas used."""
    used: set[str] = set()
    call = None
    for direction, message in transcript:
        if direction == "request":
            call = message["call"]
            name = f"{call}.request.json"
            assert problem("request.json", message) is None, message
        else:
            name = "raised.json" if "raised" in message else f"{call}.response.json"
        wrong = problem(name, message)
        assert wrong is None, f"{name}: {wrong}: {json.dumps(message)[:300]}"
        used.add(name)
    return used


def test_every_message_of_the_python_worker_on_the_whole_corpus_meets_its_schema(
    at_repo: None,
) -> None:
    """The worker speaks the protocol the schemas describe: its every answer to the
    corpus (Results of every op, errors, query records, poses, observations with
    contexts), to execute and observe, and an error answer for an unknown name."""
    transcript: list[tuple[str, Any]] = []
    worker = ExecBackend(
        [sys.executable, "-m", "conformance._backends.worker"], transcript=transcript
    )
    try:
        cases = [case for scenario in load_corpus() for case in scenario.cases]
        outcomes = [run_case(case, [worker]) for case in cases]
        worker.reset()
        worker.execute(Command("register_frame", {"name": "f"}))
        worker.observe()
        with pytest.raises(KeyError, match="unknown geometry name 'nowhere'"):
            worker.execute(Command("collision_filtered", {"pair": ["nowhere", "f"]}))
    finally:
        worker.close()
    assert all(outcome.aborted is None for outcome in outcomes)
    used = _validate_transcript(transcript)
    assert used == {
        *(f"{call}.request.json" for call in ("hello", "arm_guards", "steps", "execute")),
        "observe.request.json",
        *(f"{c}.response.json" for c in ("hello", "arm_guards", "steps", "execute", "observe")),
        "raised.json",
    }
    responses = sum(1 for direction, _ in transcript if direction == "response")
    assert responses > 2 * len(cases)


# ----------------------------------------------------------------- features
def test_fuzz_operations_need_only_the_features_both_backends_declare() -> None:
    supported = _supported(operations.OPERATIONS, NODE_FEATURES)
    assert {"apply", "apply_transient", "remove_declaration", "collision_filtered"} <= supported
    assert "register_geometries" in supported  # issues register_geometry (core)
    assert not {"create_context", "assign_role", "activate", "clone_with_history"} & supported
    # reimpl following 1.58.0 declares every feature (plain reimpl follows 1.51.1: no activation)
    newest = load_backend("reimpl==1.58.0")
    try:
        everything = frozenset(newest.features())
    finally:
        newest.close()  # type: ignore[attr-defined]
    assert _supported(operations.OPERATIONS, everything) == frozenset(operations.OPERATIONS)


def test_fuzz_sends_a_backend_with_fewer_features_only_what_it_declared(tmp_path: Path) -> None:
    """The fake answers an op outside its features as an unknown command (exit 2)."""
    spec = fake_spec("--features", "core,transient")
    process = cli("fuzz", "--backend", spec, "--against", "reimpl", "--seed", "1",
                  "--max-examples", "20", "--out", str(tmp_path))  # fmt: skip
    assert_clean_exit(process, EXIT_OK)
    assert "fake-reimpl 1.51.1 against reimpl 1.51.1" in process.stdout + process.stderr


# ----------------------------------------------------- the node backend
@needs_node
def test_the_node_backend_passes_every_case_its_features_cover_and_sits_out_the_rest(
    node: ExecBackend,
) -> None:
    pydrake = load_backend("pydrake")
    cases = [case for scenario in load_corpus() for case in scenario.cases]
    covered = [case for case in cases if case.features <= NODE_FEATURES]
    assert len([case for case in covered if case.features == {"core"}]) >= 45
    for case in covered:
        report = run_case(case, [node, pydrake])
        assert report.status == {"node-filter": Outcome.PASS, "pydrake": Outcome.PASS}, (
            case.qualified_name,
            report.failures,
            report.aborted,
        )
    for case in cases:
        if case in covered:
            continue
        report = run_case(case, [node])
        missing = ", ".join(sorted(case.features - NODE_FEATURES))
        assert report.status == {"node-filter": Outcome.SKIP}
        assert report.skip_reasons == {"node-filter": f"needs feature(s) {missing}"}


@needs_node
def test_run_with_the_node_backend_against_pydrake_exits_zero_from_the_callers_folder() -> None:
    """The command's path is relative: the process starts in the caller's folder."""
    process = cli("run", "scenarios/statements", "scenarios/transient", "-q",
                  "--backend", f"exec:node {NODE_BACKEND}", "--backend", "pydrake")  # fmt: skip
    assert_clean_exit(process, EXIT_OK)
    assert "node-filter (1.51.1)" in process.stdout
    total = next(line for line in process.stdout.splitlines() if line.startswith("total"))
    assert total.split()[1:6] == ["46", "46", "pass,", "0", "fail,"]


@needs_node
def test_the_pytest_plugin_takes_an_exec_backend() -> None:
    process = subprocess.run(
        [sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-q",
         "scenarios/transient/table1.json", "--conformance-backend", NODE_SPEC,
         "--conformance-backend", "pydrake"],
        cwd=REPO, capture_output=True, text=True, timeout=600,
        env={**os.environ, "PYTHONPATH": str(REPO)}, check=False,
    )  # fmt: skip
    assert process.returncode == 0, process.stdout + process.stderr
    assert "2 passed" in process.stdout


# ------------------------------------------------------- docs/protocol.md
PROTOCOL_DOC = REPO / "docs" / "protocol.md"


def _doc_section(title: str) -> str:
    text = PROTOCOL_DOC.read_text(encoding="utf-8")
    return text.split(f"\n## {title}\n", 1)[1].split("\n## ", 1)[0]


def test_the_feature_table_of_the_protocol_doc_is_the_grammars() -> None:
    rows = [
        line.split(" | ")
        for line in _doc_section("Features").splitlines()
        if line.startswith("| `")
    ]
    documented = {
        feature.strip("| `"): [op.strip("` |") for op in ops.split(", ")] for feature, ops in rows
    }
    grammar: dict[str, list[str]] = {}
    for op in GRAMMAR:
        (feature,) = features_of([op])
        grammar.setdefault(feature, []).append(op)
    assert documented == grammar


@needs_node
def test_the_example_session_of_the_protocol_doc_is_what_the_node_backend_says(
    at_repo: None,
) -> None:
    """The first block of "An example session", line for line, is a fresh run of its case."""
    block = _doc_section("An example session").split("```\n", 2)[1]
    documented = [line for line in block.splitlines() if line[:2] in ("> ", "< ")]
    scenario = load_file(ROOT / "transient" / "history.json", root=ROOT)
    (case,) = [c for c in scenario.cases if c.description.startswith("an id that was never")]
    transcript: list[tuple[str, Any]] = []
    node = ExecBackend(["node", str(NODE_BACKEND)], transcript=transcript)
    try:
        report = run_case(case, [node, load_backend("pydrake")], reference="pydrake")
    finally:
        node.close()
    assert report.status == {"node-filter": Outcome.PASS, "pydrake": Outcome.PASS}
    said = [("> " if way == "request" else "< ") + json.dumps(m) for way, m in transcript]
    assert said == documented


def test_a_process_that_never_answers_hello_times_out_saying_how_long_it_waited(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A new process's hello may take STARTUP_SECONDS (longer than --step-timeout)."""
    monkeypatch.setattr(exec_backend, "STARTUP_SECONDS", 1.0)
    with pytest.raises(StepTimeoutError) as raised:
        ExecBackend(["sleep", "60"], step_timeout=0.2)
    assert str(raised.value) == (
        "backend 'exec:sleep 60' at hello: no answer within 1 s (a new process's hello)"
    )


def test_a_quoted_stderr_writes_the_corpus_folder_as_a_placeholder() -> None:
    """A worker's stderr names model files by absolute path; a report quotes it the same
    from any checkout (measured: Drake 1.41.0's PackageMap warning named the matrix's checkout)."""
    root = corpus_root()
    said = f"WARNING:drake:ignoring '{root}/real_models/a/' vs '{root}/real_models/b/'"
    assert portable(said) == (
        f"WARNING:drake:ignoring '{CORPUS_PLACEHOLDER}/real_models/a/' vs "
        f"'{CORPUS_PLACEHOLDER}/real_models/b/'"
    )
    assert portable("/elsewhere/model.sdf") == "/elsewhere/model.sdf"
