"""Faults driven through the real CLI, in a subprocess, as a user meets them.

Each faulty backend below is reimpl with one fault, written into a module in
the test's folder and loaded with ``--backend faulty:NAME`` from there (the
current folder is importable, as docs/backends.md promises). Every fault must end
with exit 2 (or 1 for a conformance failure), one message naming the backend
and the step, no traceback, and nothing already found lost.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from conformance._corpus.loader import default_corpus_root, load_file
from conformance._run.outputs import fallback_path, write_or_fall_back
from conformance.cli.exit_codes import EXIT_FAILURE, EXIT_OK, EXIT_USAGE

ROOT = default_corpus_root()
TABLE1 = ROOT / "transient" / "table1.json"
ALLOW_WITHIN = ROOT / "statements" / "allow_within.json"

#: The faulty backends, as a user's module would define them.
FAULTY = textwrap.dedent(
    '''
    import os
    import time

    from conformance._backends.loader import load_backend
    from conformance.protocol import Result

    if os.environ.get("FAULTY_IMPORT_RAISES"):
        raise RuntimeError("this module refuses to load")


    class _Faulty:
        """reimpl, with a fault from the Nth execute() call on."""

        def __init__(self, name, after=3):
            self._inner = load_backend("reimpl")
            self.name = name
            self.calls = 0
            self.after = after

        def version(self):
            return self._inner.version()

        def features(self):
            return self._inner.features()

        def reset(self):
            self._inner.reset()

        def observe(self):
            return self._inner.observe()

        def execute(self, command):
            self.calls += 1
            if self.calls >= self.after:
                return self.fault(command)
            return self._inner.execute(command)

        def fault(self, command):
            return self._inner.execute(command)


    class ReturnsNone(_Faulty):
        def fault(self, command):
            return None


    class ObservesWrongType(_Faulty):
        def observe(self):
            return {"candidates": []}


    class ExitsZero(_Faulty):
        def fault(self, command):
            raise SystemExit(0)


    class Hangs(_Faulty):
        def fault(self, command):
            time.sleep(3600)


    class Raises(_Faulty):
        def fault(self, command):
            raise RuntimeError("boom")


    class Intermittent(_Faulty):
        """Raises on one call in 97, whatever the command: Hypothesis cannot replay it."""

        def fault(self, command):
            if self.calls % 97 == 0:
                raise RuntimeError("now and then")
            return self._inner.execute(command)


    def returns_none():
        return ReturnsNone("returns-none")


    def observes_wrong_type():
        return ObservesWrongType("observes-wrong-type")


    def exits_zero():
        return ExitsZero("exits-zero")


    def hangs():
        return Hangs("hangs")


    def raises():
        return Raises("raises")


    def intermittent():
        return Intermittent("intermittent", after=1)


    class Crashes(_Faulty):
        """An isolated backend (a worker) whose process dies on its Nth call of each case."""

        isolated = True

        def reset(self):
            self.calls = 0
            self._inner.reset()

        def fault(self, command):
            from conformance._backends.calls import BackendCrashError

            raise BackendCrashError(self.name, "execute", "the worker killed by SIGABRT")


    def crashes():
        return Crashes("crashes", after=2)


    def factory_raises():
        raise ValueError("no licence for this backend")


    def version_is_a_number():
        backend = ReturnsNone("bad-version")
        backend.version = lambda: 151
        return backend
    '''
)


def cli(
    tmp_path: Path, *argv: str, env: dict[str, str] | None = None
) -> subprocess.CompletedProcess[str]:
    """``python -m conformance ARGV`` in ``tmp_path`` (where ``faulty.py`` lives)."""
    (tmp_path / "faulty.py").write_text(FAULTY)
    return subprocess.run(
        [sys.executable, "-m", "conformance", *argv],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=600,
        env={**os.environ, **(env or {})},
        check=False,
    )


def assert_clean_exit(process: subprocess.CompletedProcess[str], code: int) -> None:
    assert process.returncode == code, process.stderr
    assert "Traceback" not in process.stderr
    assert "Traceback" not in process.stdout


# ------------------------------------------------------------------- loading
@pytest.mark.parametrize(
    ("spec", "env", "message"),
    [
        (
            "faulty:returns_none",
            {"FAULTY_IMPORT_RAISES": "1"},
            "cannot import 'faulty': RuntimeError: this module refuses to load",
        ),
        (
            "faulty:factory_raises",
            None,
            "its factory raised ValueError: no licence for this backend",
        ),
        ("faulty:version_is_a_number", None, "version is a int, not str"),
    ],
    ids=["import raises", "factory raises", "version not a string"],
)
def test_a_backend_that_cannot_load_is_one_error_line_and_exit_two(
    tmp_path: Path, spec: str, env: dict[str, str] | None, message: str
) -> None:
    process = cli(tmp_path, "run", str(TABLE1), "--backend", spec, env=env)
    assert_clean_exit(process, EXIT_USAGE)
    assert process.stderr == f"error: backend {spec!r}: {message}\n"


# ------------------------------------------------------------------ run faults
@pytest.mark.parametrize(
    ("spec", "status", "message"),
    [
        ("faulty:returns_none", "error", "execute() returned NoneType, not Result"),
        ("faulty:observes_wrong_type", "error", "observe() returned dict, not Observation"),
        ("faulty:exits_zero", "error", "execute() raised SystemExit"),
        ("faulty:raises", "error", "execute() raised RuntimeError('boom')"),
        ("faulty:hangs", "timeout", "no answer within 1 s (--step-timeout)"),
    ],
    ids=["execute returns None", "observe wrong type", "SystemExit(0)", "raises", "hangs"],
)
def test_a_backend_that_breaks_mid_run_exits_two_and_keeps_every_report(
    tmp_path: Path, spec: str, status: str, message: str
) -> None:
    process = cli(
        tmp_path,
        "run",
        str(ALLOW_WITHIN),
        str(TABLE1),
        "--backend",
        spec,
        "--backend",
        "pydrake",
        "--step-timeout",
        "1",
        "--json",
        "report.json",
        "--junit",
        "report.xml",
    )
    assert_clean_exit(process, EXIT_USAGE)
    name = spec.partition(":")[2].replace("_", "-")
    assert f"error: {ALLOW_WITHIN}: case " in process.stderr
    assert f"backend {name!r} at " in process.stderr
    assert message in process.stderr
    assert "stopped after 1 of " in process.stderr
    assert "ERROR statements/allow_within > " in process.stdout  # the summary is printed
    assert "total" in process.stdout
    report = json.loads((tmp_path / "report.json").read_text())
    (case,) = report["cases"]
    assert case["status"][name] == status
    assert message in case["aborted"]
    assert report["aborted"].startswith("statements/allow_within > ")
    assert 'errors="1"' in (tmp_path / "report.xml").read_text()


def test_an_isolated_backend_that_crashes_is_recorded_per_case_and_the_run_goes_on(
    tmp_path: Path,
) -> None:
    process = cli(tmp_path, "run", str(TABLE1), "--backend", "faulty:crashes", "--backend",
                  "pydrake", "--json", "report.json")  # fmt: skip
    assert_clean_exit(process, EXIT_FAILURE)
    assert process.stderr.count("(a new worker takes over)") == 2
    report = json.loads((tmp_path / "report.json").read_text())
    assert [c["status"]["crashes"] for c in report["cases"]] == ["crash", "crash"]
    assert report["aborted"] is None
    assert "the worker killed by SIGABRT" in report["cases"][1]["aborted"]
    assert "2 crash" in process.stdout


def test_a_fault_after_some_cases_keeps_their_results(tmp_path: Path) -> None:
    """The first case of allow_within.json passes; the fault comes in a later one."""
    cases = len(load_file(ALLOW_WITHIN, root=ROOT).cases)
    first_case_calls = 1 + len(load_file(ALLOW_WITHIN, root=ROOT).cases[0].steps)
    faulty = FAULTY + textwrap.dedent(
        f"""

        def late():
            return Raises("late", after={first_case_calls + 1})
        """
    )
    (tmp_path / "faulty.py").write_text(faulty)
    process = subprocess.run(
        [sys.executable, "-m", "conformance", "run", str(ALLOW_WITHIN), "--backend",
         "faulty:late", "--backend", "pydrake", "--json", "report.json"],
        cwd=tmp_path, capture_output=True, text=True, timeout=600, check=False,
    )  # fmt: skip
    assert_clean_exit(process, EXIT_USAGE)
    report = json.loads((tmp_path / "report.json").read_text())
    assert 2 <= len(report["cases"]) <= cases
    assert report["cases"][0]["status"] == {"late": "pass", "pydrake": "pass"}
    assert report["cases"][-1]["status"]["late"] == "error"


@pytest.mark.parametrize("option", ["--json", "--junit"])
def test_an_unwritable_report_path_is_refused_before_the_run(tmp_path: Path, option: str) -> None:
    blocker = tmp_path / "a-file"
    blocker.write_text("")
    process = cli(tmp_path, "run", str(TABLE1), option, str(blocker / "report"))
    assert_clean_exit(process, EXIT_USAGE)
    assert process.stderr == f"error: {option} {blocker / 'report'}: {blocker} is not a folder\n"
    assert process.stdout == ""  # nothing ran


def test_a_report_that_cannot_be_written_after_all_goes_to_the_fallback(tmp_path: Path) -> None:
    import io  # noqa: PLC0415

    err = io.StringIO()
    target = tmp_path / "gone" / "report.json"

    def write(path: Path) -> None:
        if path == target:
            raise PermissionError(13, "Permission denied")
        path.write_text("{}")

    assert write_or_fall_back(target, write, err) == fallback_path(target)
    assert fallback_path(target).read_text() == "{}"
    assert err.getvalue().startswith(f"warning: cannot write {target} (")
    fallback_path(target).unlink()


def test_a_negative_step_timeout_is_a_usage_error(tmp_path: Path) -> None:
    process = cli(tmp_path, "run", str(TABLE1), "--step-timeout", "-1")
    assert_clean_exit(process, EXIT_USAGE)
    assert "argument --step-timeout: must be 0 (none) or positive, got -1" in process.stderr


def test_version_names_the_package_and_the_installed_drake(tmp_path: Path) -> None:
    process = cli(tmp_path, "--version")
    assert_clean_exit(process, EXIT_OK)
    assert process.stdout.startswith("drake-filter-conformance ")
    assert "drake 1." in process.stdout


# ----------------------------------------------------------------- fuzz faults
@pytest.mark.parametrize(
    ("spec", "message"),
    [
        ("faulty:hangs", "no answer within 1 s (--step-timeout)"),
        ("faulty:raises", "execute() raised RuntimeError('boom')"),
        ("faulty:intermittent", "execute() raised RuntimeError('now and then')"),
    ],
    ids=["hangs", "raises", "raises now and then"],
)
def test_a_backend_that_breaks_during_fuzz_exits_two_with_a_reproducer(
    tmp_path: Path, spec: str, message: str
) -> None:
    process = cli(
        tmp_path,
        "fuzz",
        "--backend",
        spec,
        "--seed",
        "1",
        "--max-examples",
        "50",
        "--step-timeout",
        "1",
        "--out",
        "findings",
        "-q",
    )
    assert_clean_exit(process, EXIT_USAGE)
    assert "error: a backend broke (not a divergence): backend " in process.stderr
    assert message in process.stderr
    assert "FlakyFailure" not in process.stderr
    (reproducer,) = (tmp_path / "findings").glob("broken-*.json")
    assert f"reproducer: findings/{reproducer.name}" in process.stderr
    scenario = load_file(reproducer, root=reproducer.parent)
    (case,) = scenario.cases
    assert case.steps  # the commands up to the fault


def test_an_unwritable_fuzz_out_folder_is_refused_before_the_run(tmp_path: Path) -> None:
    blocker = tmp_path / "a-file"
    blocker.write_text("")
    process = cli(tmp_path, "fuzz", "--max-examples", "5", "--out", str(blocker / "findings"))
    assert_clean_exit(process, EXIT_USAGE)
    assert process.stderr == f"error: --out {blocker / 'findings'}: {blocker} is not a folder\n"


# ------------------------------------------------------------------ big scenes
def test_a_case_with_2000_anchored_geometries_passes_on_both_backends(tmp_path: Path) -> None:
    """Observed once after the scene, not after each of its 2,000 registrations."""
    n = 2000
    scenario = {
        "description": "a big scene",
        "cases": [
            {
                "description": f"{n} anchored geometries have no candidate pairs",
                "scene": {
                    "geometries": [
                        {"name": f"g{i}", "frame": "world", "roles": ["proximity"]}
                        for i in range(n)
                    ]
                },
                "steps": [{"op": "check", "expect": {"candidates": []}}],
            }
        ],
    }
    (tmp_path / "big.json").write_text(json.dumps(scenario))
    process = cli(tmp_path, "run", "big.json", "--step-timeout", "60")
    assert_clean_exit(process, EXIT_OK)
    assert "1 pass, 0 fail" in process.stdout


# ----------------------------------------------------------- the README's skeleton
@pytest.mark.parametrize("attribute", ["MyBackend", "pydrake_like"])
def test_the_example_backend_skeleton_passes_against_pydrake(attribute: str) -> None:
    repo = Path(__file__).resolve().parent.parent
    process = subprocess.run(
        [sys.executable, "-m", "conformance", "run", str(TABLE1), str(ALLOW_WITHIN),
         "--backend", f"examples.my_backend:{attribute}", "--backend", "pydrake", "-q"],
        cwd=repo, capture_output=True, text=True, timeout=600, check=False,
    )  # fmt: skip
    assert_clean_exit(process, EXIT_OK)
    assert "mine (1.51.1)" in process.stdout


# --------------------------------------------------------------- bad input among good
def test_a_bad_file_among_good_ones_is_reported_and_the_good_ones_still_run(
    tmp_path: Path,
) -> None:
    good = json.loads(TABLE1.read_text())
    bad_name = json.loads(json.dumps(good))
    bad_name["cases"][0]["steps"][0]["expect"]["candidates"][0] = ["g0", "zz"]
    bad_schema = json.loads(json.dumps(good))
    bad_schema["cases"][0]["steps"][0]["op"] = "no_such_op"
    corpus = tmp_path / "corpus"
    corpus.mkdir()
    (corpus / "good.json").write_text(json.dumps(good))
    (corpus / "bad_name.json").write_text(json.dumps(bad_name))
    (corpus / "bad_schema.json").write_text(json.dumps(bad_schema))
    report = tmp_path / "report.json"
    process = cli(tmp_path, "run", "-q", "--backend", "reimpl", "corpus", "--json", str(report))
    assert_clean_exit(process, EXIT_USAGE)
    assert "error: corpus/bad_name.json: case " in process.stderr
    assert "unknown geometry name 'zz'" in process.stderr
    assert "error: corpus/bad_schema.json: case " in process.stderr
    # Each bad file keeps its other case: a name error and a schema error are per case.
    written = json.loads(report.read_text())
    assert len(written["input_errors"]) == 2
    assert [c["qualified_name"].split(" > ")[0] for c in written["cases"]] == [
        "corpus/bad_name",
        "corpus/bad_schema",
        "corpus/good",
        "corpus/good",
    ]
    assert {s for c in written["cases"] for s in c["status"].values()} == {"pass"}


def test_a_directory_without_scenarios_is_named_as_such(tmp_path: Path) -> None:
    (tmp_path / "empty").mkdir()
    process = cli(tmp_path, "run", "empty")
    assert_clean_exit(process, EXIT_USAGE)
    assert process.stderr == (
        "error: empty: no scenario files (*.json, *.yaml, *.yml) in this directory\n"
    )


@pytest.mark.parametrize("token", ["NaN", "Infinity", "-Infinity", "1e400"])
def test_a_non_finite_number_is_an_input_error_not_a_backend_failure(
    tmp_path: Path, token: str
) -> None:
    scenario = json.loads(TABLE1.read_text())
    scenario["cases"] = scenario["cases"][:1]
    path = tmp_path / "nonfinite.json"
    text = json.dumps(scenario).replace('"scene": {', f'"radius": {token}, "scene": {{', 1)
    path.write_text(text)
    process = cli(tmp_path, "run", "nonfinite.json")
    assert_clean_exit(process, EXIT_USAGE)
    assert process.stderr == (
        f"error: nonfinite.json: the number {token} is not finite; "
        "scenario numbers must be finite\n"
    )


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (("run", "--backend", "drake==banana"), "'banana' is not a Drake release (X.Y.Z"),
        (("run", "--backend", "drake==1.58"), "'1.58' is not a Drake release (X.Y.Z"),
        (
            ("bisect", "*", "--good", "1.51.0", "--bad", "1.51.0.0.0"),
            "--bad '1.51.0.0.0' is not a Drake release (X.Y.Z",
        ),
    ],
    ids=["not a version", "two parts", "four parts"],
)
def test_a_release_that_is_not_x_y_z_is_refused_before_anything_is_built(
    tmp_path: Path, argv: tuple[str, ...], message: str
) -> None:
    process = cli(tmp_path, *argv[:1], str(TABLE1), *argv[1:])
    assert_clean_exit(process, EXIT_USAGE)
    assert message in process.stderr


def test_an_infinite_step_timeout_means_none(tmp_path: Path) -> None:
    argv = ("run", "-q", str(TABLE1), "--backend", "reimpl", "--step-timeout", "inf")
    process = cli(tmp_path, *argv)
    assert_clean_exit(process, EXIT_OK)


def test_a_step_timeout_beyond_a_year_is_a_usage_error(tmp_path: Path) -> None:
    process = cli(tmp_path, "run", str(TABLE1), "--step-timeout", "1e10")
    assert_clean_exit(process, EXIT_USAGE)
    assert "argument --step-timeout: at most 3.1536e+07 seconds (0 or inf: none)" in process.stderr


def test_fuzz_json_naming_a_folder_is_refused_before_the_run(tmp_path: Path) -> None:
    process = cli(tmp_path, "fuzz", "--json", str(tmp_path), "--max-examples", "1")
    assert_clean_exit(process, EXIT_USAGE)
    assert process.stderr == f"error: --json {tmp_path}: {tmp_path} is a folder\n"


#: The faulty backends, faulting from their first execute() call.
EAGER = textwrap.dedent(
    """
    import faulty

    def raises():
        return faulty.Raises("raises", after=1)

    def returns_none():
        return faulty.ReturnsNone("returns-none", after=1)

    def observes_wrong_type():
        return faulty.ObservesWrongType("observes-wrong-type", after=1)

    def exits_zero():
        return faulty.ExitsZero("exits-zero", after=1)
    """
)


@pytest.mark.parametrize(
    ("spec", "message"),
    [
        ("eager:raises", "execute() raised RuntimeError('boom')"),
        ("eager:returns_none", "execute() returned NoneType, not Result"),
        ("eager:observes_wrong_type", "observe() returned dict, not Observation"),
        ("eager:exits_zero", "execute() raised SystemExit('0')"),
    ],
    ids=["raises", "returns None", "observes a dict", "exits 0"],
)
def test_a_backend_that_breaks_in_legacy_diff_is_one_error_line_and_exit_two(
    tmp_path: Path, spec: str, message: str
) -> None:
    urdf = tmp_path / "r.urdf"
    urdf.write_text(
        '<robot name="r"><link name="a"><collision><geometry><sphere radius="0.1"/>'
        "</geometry></collision></link></robot>"
    )
    (tmp_path / "eager.py").write_text(EAGER)
    process = cli(tmp_path, "legacy-diff", "r.urdf", "--backend", spec)
    assert_clean_exit(process, EXIT_USAGE)
    assert process.stderr.startswith("error: backend '")
    assert message in process.stderr
    assert process.stderr.count("\n") == 1


def test_a_named_pipe_is_refused_rather_than_read(tmp_path: Path) -> None:
    os.mkfifo(tmp_path / "pipe.json")
    process = cli(tmp_path, "run", "pipe.json")
    assert_clean_exit(process, EXIT_USAGE)
    assert process.stderr == "error: pipe.json: not a regular file or a directory\n"
