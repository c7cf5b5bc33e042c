"""The pytest plugin (conformance._run.pytest_plugin), run as a user runs it.

Every run is ``python -m pytest`` in a fresh directory of pytester's, with no
pyproject of ours: the plugin comes in through its ``pytest11`` entry point,
and the repository is on PYTHONPATH so that its working tree is what runs.
The backends are real: reimpl, the installed pydrake, and ``partial``
backends of the temporary directory, which are reimpl reporting fewer
features, so that which backends can run a case does not hang on the Drake
release.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

import pytest

from conformance._backends.loader import load_backend
from conformance._run.pytest_plugin import FEATURE_TAGS

pytest_plugins = ["pytester"]

REPO = Path(__file__).resolve().parents[1]
CORPUS = REPO / "scenarios"
#: Loaded here, before any test: pytester restores sys.modules after each test, and
#: pydrake's modules first imported inside one come back without their bindings
#: (measured: a later test found pydrake.math without RigidTransform).
PYDRAKE = load_backend("pydrake")

#: Backends of the temporary directory: reimpl without one feature, under another name.
PARTIAL_BACKENDS = """
from conformance._backends.loader import load_backend


class Partial:
    def __init__(self, name, lacks):
        self._inner = load_backend("reimpl")
        self.name = name
        self._lacks = frozenset(lacks)

    def features(self):
        return self._inner.features() - self._lacks

    def __getattr__(self, attribute):
        return getattr(self._inner, attribute)


def full():
    return Partial("full", ())


def no_roles():
    return Partial("no_roles", ("roles",))


def no_roles_either():
    return Partial("no_roles_either", ("roles",))
"""


def scenario(*, features: tuple[str, ...] = ("core",), expect: list[Any] | None = None) -> str:
    """A scenario file of two cases: exclude_within g0, g1 leaves no candidate pair."""
    scene = {
        "frames": [{"name": "f0"}, {"name": "f1"}],
        "geometries": [
            {"name": "g0", "frame": "f0", "roles": ["proximity"]},
            {"name": "g1", "frame": "f1", "roles": ["proximity"]},
        ],
    }
    step = {
        "op": "apply",
        "declaration": {
            "statements": [{"op": "exclude_within", "set": {"geometries": ["g0", "g1"]}}]
        },
        "expect": {"candidates": [] if expect is None else expect},
    }
    cases = [
        {"description": description, "scene": scene, "steps": [step]}
        for description in ("first", "second")
    ]
    data = {"description": "a user's scenario", "features": list(features), "cases": cases}
    return json.dumps(data, indent=2)


@pytest.fixture
def user_dir(pytester: pytest.Pytester, monkeypatch: pytest.MonkeyPatch) -> pytest.Pytester:
    """A directory of the user's: no ini file, the repository and the directory importable."""
    path = os.pathsep.join([str(REPO), str(pytester.path), os.environ.get("PYTHONPATH", "")])
    monkeypatch.setenv("PYTHONPATH", path)
    pytester.makepyfile(partial=PARTIAL_BACKENDS)
    return pytester


def run(pytester: pytest.Pytester, *args: str) -> pytest.RunResult:
    return pytester.runpytest_subprocess("-p", "no:cacheprovider", "-p", "no:benchmark", *args)


def backends(*specs: str) -> list[str]:
    """``--conformance-backend`` for each spec."""
    return [arg for spec in specs for arg in ("--conformance-backend", spec)]


def collected(result: pytest.RunResult) -> list[str]:
    """The node ids ``--collect-only -q`` printed."""
    return [line for line in result.outlines if "::" in line]


# Collection


def test_a_scenario_file_named_on_the_command_line_is_collected_anywhere(
    user_dir: pytest.Pytester,
) -> None:
    (user_dir.path / "my").mkdir()
    (user_dir.path / "my" / "case.json").write_text(scenario())
    result = run(user_dir, "my/case.json", "-v")  # docs/user-guide.md's command
    result.assert_outcomes(passed=2)
    assert result.ret == pytest.ExitCode.OK
    result.stdout.fnmatch_lines(["my/case.json::*case > first PASSED*"])


def test_without_conformance_paths_a_users_folder_is_not_a_scenario_folder(
    user_dir: pytest.Pytester,
) -> None:
    (user_dir.path / "mine").mkdir()
    (user_dir.path / "mine" / "case.json").write_text(scenario())
    result = run(user_dir, "mine")
    assert result.ret == pytest.ExitCode.NO_TESTS_COLLECTED


def test_conformance_paths_makes_its_scenario_files_items_and_ignores_other_json(
    user_dir: pytest.Pytester,
) -> None:
    user_dir.makeini("[pytest]\nconformance_paths = mine\n")
    mine = user_dir.path / "mine"
    (mine / "deeper").mkdir(parents=True)
    (mine / "a.json").write_text(scenario())
    (mine / "deeper" / "b.json").write_text(scenario())
    (mine / "package.json").write_text(json.dumps({"name": "not a scenario"}))
    (mine / "list.json").write_text("[1, 2]")
    (user_dir.path / "elsewhere.json").write_text(scenario())
    result = run(user_dir, "--collect-only", "-q")
    assert sorted(collected(result)) == [
        "mine/a.json::a > first",
        "mine/a.json::a > second",
        "mine/deeper/b.json::deeper/b > first",
        "mine/deeper/b.json::deeper/b > second",
    ]
    run(user_dir).assert_outcomes(passed=4)


def test_conformance_paths_collects_yaml_scenario_files(user_dir: pytest.Pytester) -> None:
    user_dir.makeini("[pytest]\nconformance_paths = mine\n")
    (user_dir.path / "mine").mkdir()
    # JSON is YAML: the same scenario, under both YAML suffixes.
    (user_dir.path / "mine" / "a.yaml").write_text(scenario())
    (user_dir.path / "mine" / "b.yml").write_text(scenario())
    (user_dir.path / "mine" / "config.yaml").write_text("name: not a scenario\n")
    result = run(user_dir, "-v")
    result.assert_outcomes(passed=4)
    result.stdout.fnmatch_lines(["mine/a.yaml::a > first PASSED*", "mine/b.yml::b > first PASSED*"])


def test_a_malformed_file_under_conformance_paths_is_a_collection_error(
    user_dir: pytest.Pytester,
) -> None:
    user_dir.makeini("[pytest]\nconformance_paths = mine\n")
    (user_dir.path / "mine").mkdir()
    (user_dir.path / "mine" / "typo.json").write_text('{"cases": [')
    result = run(user_dir)
    assert result.ret == pytest.ExitCode.INTERRUPTED
    result.stdout.fnmatch_lines(["*ERROR collecting mine/typo.json*"])


def test_a_non_scenario_json_named_on_the_command_line_is_a_collection_error(
    user_dir: pytest.Pytester,
) -> None:
    (user_dir.path / "package.json").write_text(json.dumps({"name": "not a scenario"}))
    result = run(user_dir, "package.json")
    assert result.ret == pytest.ExitCode.INTERRUPTED
    result.stdout.fnmatch_lines(
        ["*package.json: not a scenario file (its data has no top-level 'cases' key)"]
    )
    (user_dir.path / "broken.json").write_text(json.dumps({"cases": []}))
    broken = run(user_dir, "broken.json")
    assert broken.ret == pytest.ExitCode.INTERRUPTED
    broken.stdout.fnmatch_lines(["*not a valid scenario file: *broken.json: schema violation*"])


def test_a_folder_holding_the_schema_is_a_corpus_and_the_schema_is_never_an_item(
    user_dir: pytest.Pytester,
) -> None:
    corpus = user_dir.path / "corpus"
    (corpus / "group").mkdir(parents=True)
    (corpus / "scenario.schema.json").write_text((CORPUS / "scenario.schema.json").read_text())
    (corpus / "group" / "a.json").write_text(scenario())
    (corpus / "notes.json").write_text(json.dumps({"not": "a scenario"}))
    result = run(user_dir, "corpus", "--collect-only", "-q")
    assert sorted(collected(result)) == [
        "corpus/group/a.json::group/a > first",
        "corpus/group/a.json::group/a > second",
    ]
    named = run(user_dir, "corpus/scenario.schema.json", "--collect-only", "-q")
    assert collected(named) == []
    assert named.ret == pytest.ExitCode.USAGE_ERROR  # pytest: no collector for the file


# Markers


def test_every_feature_tag_is_a_registered_marker(user_dir: pytest.Pytester) -> None:
    result = run(user_dir, "--markers")
    for tag in FEATURE_TAGS:
        result.stdout.fnmatch_lines([f"@pytest.mark.{tag}: scenario feature tag*"])
    assert {"core", "activation", "quirk"} <= set(FEATURE_TAGS)


def test_feature_markers_pass_strict_markers_and_warnings_as_errors(
    user_dir: pytest.Pytester,
) -> None:
    (user_dir.path / "case.json").write_text(scenario(features=tuple(FEATURE_TAGS)))
    # reimpl following 1.58.0 (a worker) has every feature; plain reimpl (1.51.1) lacks activation.
    args = ("case.json", "--strict-markers", "-W", "error", *backends("reimpl==1.58.0"))
    run(user_dir, *args).assert_outcomes(passed=2)
    run(user_dir, *args, "-m", "quirk and roles").assert_outcomes(passed=2)


# Backends


@pytest.mark.parametrize("xdist", [(), ("-n", "2")], ids=["serial", "xdist"])
@pytest.mark.parametrize("spec", ["nosuch", "partial:missing"])
def test_a_backend_that_cannot_load_is_one_usage_error(
    user_dir: pytest.Pytester, spec: str, xdist: tuple[str, ...]
) -> None:
    (user_dir.path / "case.json").write_text(scenario())
    result = run(user_dir, "case.json", *xdist, *backends(spec))
    assert result.ret == pytest.ExitCode.USAGE_ERROR
    assert "\n".join(result.errlines).count(f"backend {spec!r}") == 1
    assert len(str(result.stdout) + str(result.stderr)) < 2000


def test_a_default_backend_that_cannot_load_is_one_usage_error(user_dir: pytest.Pytester) -> None:
    (user_dir.path / "case.json").write_text(scenario())
    # The defaults are reimpl and pydrake; this conftest makes one of them unloadable.
    user_dir.makeconftest(
        "import conformance._run.pytest_plugin as plugin\n"
        "plugin._DEFAULT_BACKENDS = ('reimpl', 'nosuch')\n"
    )
    result = run(user_dir, "case.json")
    assert result.ret == pytest.ExitCode.USAGE_ERROR
    assert "\n".join(result.errlines).count("backend 'nosuch'") == 1
    assert len(str(result.stdout) + str(result.stderr)) < 2000


# Skips


def test_a_case_only_one_of_two_backends_can_run_is_skipped_with_the_reason(
    user_dir: pytest.Pytester,
) -> None:
    (user_dir.path / "case.json").write_text(scenario(features=("core", "roles")))
    result = run(user_dir, "case.json", "-rs", *backends("partial:full", "partial:no_roles"))
    result.assert_outcomes(skipped=2)
    version = load_backend("reimpl").version()
    result.stdout.fnmatch_lines(
        [
            f"SKIPPED [[]2[]] case.json:1: no_roles {version} needs feature(s) roles"
            " (not compared; full met the case's expectations alone)"
        ]
    )


def test_a_case_no_backend_can_run_is_skipped_naming_every_backend(
    user_dir: pytest.Pytester,
) -> None:
    (user_dir.path / "case.json").write_text(scenario(features=("core", "roles")))
    specs = backends("partial:no_roles", "partial:no_roles_either")
    result = run(user_dir, "case.json", "-rs", *specs)
    result.assert_outcomes(skipped=2)
    result.stdout.fnmatch_lines(
        ["SKIPPED [[]2[]] case.json:1: no_roles * roles; no_roles_either * roles"]
    )


def test_a_backend_that_runs_a_case_alone_must_still_meet_its_expectations(
    user_dir: pytest.Pytester,
) -> None:
    wrong = [["g0", "g1"]]  # exclude_within leaves no pair: this expectation is false
    (user_dir.path / "case.json").write_text(scenario(features=("core", "roles"), expect=wrong))
    result = run(user_dir, "case.json", *backends("partial:full", "partial:no_roles"))
    result.assert_outcomes(failed=2)
    result.stdout.fnmatch_lines(["*step 1: candidates* [[]full failed[]]*"])


def test_a_case_two_of_three_backends_run_is_compared_and_passes(
    user_dir: pytest.Pytester,
) -> None:
    (user_dir.path / "case.json").write_text(scenario(features=("core", "roles")))
    specs = backends("reimpl", "partial:full", "partial:no_roles")
    result = run(user_dir, "case.json", "--junitxml=report.xml", *specs)
    result.assert_outcomes(passed=2)
    junit = (user_dir.path / "report.xml").read_text()
    assert junit.count('name="no_roles_skip_reason" value="needs feature(s) roles"') == 2


def test_a_users_backend_module_runs_a_scenario_folder_beside_reimpl(
    user_dir: pytest.Pytester,
) -> None:
    """docs/user-guide.md's command: a folder holding the schema, and a backend of the
    user's package named ``module:attribute`` (here reimpl reporting every feature)."""
    (user_dir.path / "mypkg").mkdir()
    (user_dir.path / "mypkg" / "__init__.py").write_text("")
    (user_dir.path / "mypkg" / "backend.py").write_text("from partial import full as Backend\n")
    (user_dir.path / "scenarios").mkdir()
    (user_dir.path / "scenarios" / "scenario.schema.json").write_text("{}")
    (user_dir.path / "scenarios" / "case.json").write_text(scenario())
    args = ("scenarios/", "--conformance-backend", "reimpl")
    result = run(user_dir, *args, "--conformance-backend", "mypkg.backend:Backend", "-v")
    result.assert_outcomes(passed=2)
    assert result.ret == pytest.ExitCode.OK
    result.stdout.fnmatch_lines(["scenarios/case.json::*case > first PASSED*"])


def test_a_single_backend_that_runs_the_case_passes_it(user_dir: pytest.Pytester) -> None:
    (user_dir.path / "case.json").write_text(scenario(features=("core", "roles")))
    run(user_dir, "case.json", *backends("reimpl")).assert_outcomes(passed=2)


def test_corpus_cases_the_installed_pydrake_lacks_features_for_are_skipped(
    user_dir: pytest.Pytester,
) -> None:
    activation = CORPUS / "activation" / "activation.json"
    (user_dir.path / "activation.json").write_text(activation.read_text())
    cases = len(json.loads(activation.read_text())["cases"])
    pydrake = PYDRAKE
    result = run(user_dir, "activation.json", "-rs")
    if "activation" in pydrake.features():
        result.assert_outcomes(passed=cases)
    else:
        result.assert_outcomes(skipped=cases)
        reason = f"pydrake {pydrake.version()} needs feature(s) activation"
        # plain reimpl follows 1.51.1 too (activation-since-1.55), so it is named first
        result.stdout.fnmatch_lines([f"SKIPPED [[]{cases}[]] activation.json:1: *{reason}*"])
