"""`python -m conformance run`: exit codes, reports, and precise input errors."""

from __future__ import annotations

import io
import json
import shlex
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from conformance._corpus.loader import default_corpus_root
from conformance.cli.main import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, main

TABLE1 = default_corpus_root() / "transient" / "table1.json"

GOOD_CASE = {
    "description": "a tiny file",
    "cases": [
        {
            "description": "exclude_within of two geometries empties C",
            "scene": {
                "frames": [{"name": "f0"}, {"name": "f1"}],
                "geometries": [
                    {"name": "a", "frame": "f0", "roles": ["proximity"]},
                    {"name": "b", "frame": "f1", "roles": ["proximity"]},
                ],
            },
            "steps": [
                {
                    "op": "apply",
                    "declaration": {
                        "statements": [{"op": "exclude_within", "set": {"geometries": ["a", "b"]}}]
                    },
                    "expect": {"candidates": []},
                }
            ],
        }
    ],
}


def run(*argv: str) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    code = main(["run", *argv], out=out, err=err)
    return code, out.getvalue(), err.getvalue()


def write(tmp_path: Path, data: object, name: str = "case.json") -> Path:
    path = tmp_path / name
    path.write_text(json.dumps(data) if not isinstance(data, str) else data)
    return path


def test_passing_file_exits_zero_and_prints_a_summary(tmp_path: Path) -> None:
    code, out, err = run(str(write(tmp_path, GOOD_CASE)))
    assert code == EXIT_OK
    assert "1 pass, 0 fail, 0 xfail, 0 skip" in out
    assert "reimpl:pass pydrake:pass" in err


def test_broken_expectation_exits_one_with_step_values_and_rerun_command(tmp_path: Path) -> None:
    bad = json.loads(json.dumps(GOOD_CASE))
    bad["cases"][0]["steps"][0]["expect"] = {"candidates": [["a", "b"]]}
    path = write(tmp_path, bad)
    code, out, _ = run(str(path))
    assert code == EXIT_FAILURE
    name = path.resolve().with_suffix("").as_posix()  # a file outside the corpus and the cwd
    assert f"FAIL {name} > exclude_within of two geometries empties C" in out
    assert "step 1: candidates at model [reimpl failed]" in out
    assert 'expected: ["a-b"]  (case)' in out
    assert "actual:   []" in out
    assert f"rerun: python -m conformance run {path} --case" in out


def test_malformed_json_exits_two_naming_the_file_and_line(tmp_path: Path) -> None:
    path = write(tmp_path, '{"description": "x", "cases": [\n  {,]}')
    code, _, err = run(str(path))
    assert code == EXIT_USAGE
    assert err.startswith(f"error: {path}: malformed JSON at line 2")


def test_schema_violation_exits_two_naming_the_case_step_and_field(tmp_path: Path) -> None:
    bad = json.loads(json.dumps(GOOD_CASE))
    bad["cases"][0]["steps"][0]["declaration"]["statements"][0]["op"] = "exclude_all"
    code, _, err = run(str(write(tmp_path, bad)))
    assert code == EXIT_USAGE
    assert "case 'exclude_within of two geometries empties C'" in err
    assert "step 1, field .declaration.statements[0]" in err


def test_undeclared_name_exits_two_naming_the_case_step_and_field(tmp_path: Path) -> None:
    bad = json.loads(json.dumps(GOOD_CASE))
    bad["cases"][0]["steps"][0]["declaration"]["statements"][0]["set"]["geometries"] = ["a", "zz"]
    code, _, err = run(str(write(tmp_path, bad)))
    assert code == EXIT_USAGE
    assert (
        "case 'exclude_within of two geometries empties C': step 1, field "
        "declaration.statements[1].set: unknown geometry name 'zz'" in err
    )


def test_unknown_backend_exits_two() -> None:
    code, _, err = run(str(TABLE1), "--backend", "bullet")
    assert code == EXIT_USAGE
    assert "unknown backend 'bullet'" in err


def test_unimportable_backend_module_exits_two() -> None:
    code, _, err = run(str(TABLE1), "--backend", "no_such_module:Backend")
    assert code == EXIT_USAGE
    assert "cannot import 'no_such_module'" in err


def test_missing_path_exits_two(tmp_path: Path) -> None:
    code, _, err = run(str(tmp_path / "nope.json"))
    assert code == EXIT_USAGE
    assert "no such file or directory" in err


def test_unknown_case_description_exits_two() -> None:
    code, _, err = run(str(TABLE1), "--case", "no such case")
    assert code == EXIT_USAGE
    assert "no case is described or named 'no such case'" in err


def test_junit_has_one_testcase_per_case_and_backend(tmp_path: Path) -> None:
    junit = tmp_path / "out" / "junit.xml"
    code, _, _ = run(str(write(tmp_path, GOOD_CASE)), str(TABLE1), "--junit", str(junit))
    assert code == EXIT_OK
    suite = ET.parse(junit).getroot()
    names = sorted(tc.get("name") or "" for tc in suite.iter("testcase"))
    cases = {n.rsplit(" [", 1)[0] for n in names}
    assert len(names) == 2 * len(cases)
    assert suite.get("tests") == str(len(names))
    assert any(n.endswith("[pydrake]") for n in names)


def test_json_report_records_backends_and_statuses(tmp_path: Path) -> None:
    report = tmp_path / "r.json"
    run(str(write(tmp_path, GOOD_CASE)), "--json", str(report))
    data = json.loads(report.read_text())
    assert set(data["backends"]) == {"reimpl", "pydrake"}
    assert data["cases"][0]["status"] == {"reimpl": "pass", "pydrake": "pass"}


def test_third_party_backend_loads_from_module_attribute(tmp_path: Path) -> None:
    (tmp_path / "my_backend.py").write_text(
        "from conformance._backends.reimpl_api import reimpl_api\n"
        "from conformance._backends.scene_graph import SceneGraphBackend\n"
        "def Backend():\n"
        "    b = SceneGraphBackend(reimpl_api())\n"
        "    b.name = 'mine'\n"
        "    return b\n"
    )
    sys.path.insert(0, str(tmp_path))
    try:
        code, out, _ = run(str(TABLE1), "--backend", "my_backend:Backend", "--backend", "pydrake")
    finally:
        sys.path.remove(str(tmp_path))
    assert code == EXIT_OK
    assert "mine (1.51.1)" in out


@pytest.mark.parametrize("argv", [["run", "--bogus"], ["frobnicate"]])
def test_bad_arguments_exit_two(argv: list[str]) -> None:
    result = subprocess.run(
        [sys.executable, "-m", "conformance", *argv], capture_output=True, text=True, check=False
    )
    assert result.returncode == EXIT_USAGE
    assert "error:" in result.stderr


ALLOW_WITHIN = default_corpus_root() / "statements" / "allow_within.json"
MUTANT = "conformance._testing.mutants:allow_clears_invariants"


def test_a_disagreement_fails_only_the_backend_that_is_not_the_reference() -> None:
    code, out, _ = run(str(ALLOW_WITHIN), "--backend", MUTANT, "--backend", "pydrake")
    assert code == EXIT_FAILURE
    mutant_cell, pydrake_cell = _cells(out.strip().splitlines()[-1])
    assert not mutant_cell.startswith("5 pass")
    assert pydrake_cell == "5 pass, 0 fail, 0 xfail, 0 skip"
    header = next(line for line in out.splitlines() if line.startswith("scenario file"))
    assert header.rstrip().endswith("[reference]")
    assert "allow_clears_invariants (1.51.1) [reference]" not in header
    assert "allow_clears_invariants failed]" in out
    assert "[pydrake failed]" not in out
    assert "(reference pydrake)" in out


def _cells(total: str) -> tuple[str, str]:
    """The two backend cells of the summary's total row."""
    parts = [p.strip() for p in total.split("  ") if p.strip()]
    return parts[-2], parts[-1]


def test_the_rerun_hint_repeats_the_backend_specs_as_given_and_runs() -> None:
    code, out, _ = run(str(ALLOW_WITHIN), "--backend", MUTANT, "--backend", "pydrake")
    assert code == EXIT_FAILURE
    hint = next(line for line in out.splitlines() if line.strip().startswith("rerun: "))
    assert f"--backend {MUTANT} --backend pydrake" in hint
    words = shlex.split(hint.strip().removeprefix("rerun: "))
    assert words[:4] == ["python", "-m", "conformance", "run"]
    rerun = subprocess.run(
        [sys.executable, *words[1:]], capture_output=True, text=True, check=False
    )
    assert rerun.returncode == EXIT_FAILURE, rerun.stderr
    assert "No module named" not in rerun.stderr
    assert "[1/1]" in rerun.stderr


@pytest.mark.parametrize(
    "selector",
    [
        "statements/allow_within > *",
        "*allow_within*",
    ],
)
def test_case_takes_a_qualified_name_or_a_glob(selector: str) -> None:
    code, _, err = run(str(default_corpus_root()), "--case", selector, "--backend", "reimpl")
    assert code == EXIT_OK
    assert err.count("statements/allow_within > ") == 5


def test_case_takes_the_qualified_name_that_progress_lines_print() -> None:
    _, _, err = run(str(TABLE1), "--backend", "reimpl")
    name = err.splitlines()[0].split("] ", 1)[1].rsplit("  ", 1)[0]
    code, _, err = run(str(TABLE1), "--case", name, "--backend", "reimpl")
    assert code == EXIT_OK
    assert err.startswith("[1/1] transient/table1 > ")


def test_reference_must_name_a_given_backend() -> None:
    code, _, err = run(str(TABLE1), "--reference", "nosuch")
    assert code == EXIT_USAGE
    assert "no backend is named 'nosuch'" in err


def test_schema_prints_the_published_schema() -> None:
    out, err = io.StringIO(), io.StringIO()
    assert main(["schema"], out=out, err=err) == EXIT_OK
    published = json.loads((default_corpus_root() / "scenario.schema.json").read_text())
    assert json.loads(out.getvalue()) == published
