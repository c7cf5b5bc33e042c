"""The model corpus (scenarios/models) and the model ops of the grammar, on pydrake and reimpl.

The cases' expectations were measured on pydrake 1.51.1; the runner holds
each backend to them and reimpl to pydrake's answers step by step.
"""

from __future__ import annotations

import io
import json
from pathlib import Path
from typing import Any

import pytest

from conformance._backends.env_cache import missing_releases
from conformance._backends.loader import load_backend
from conformance._backends.multibody import JOINT_CLASSES
from conformance._backends.scene_graph import SceneGraphBackend
from conformance._corpus.loader import Case, ScenarioError, default_corpus_root, load_corpus
from conformance._engine import Outcome
from conformance._grammar import GRAMMAR, ops_of
from conformance._grammar.multibody import JOINT_TYPES, MODEL_COMMANDS
from conformance._grammar.schema import scenario_schema
from conformance._policy.versions import parse_version
from conformance._run.runner import run_case
from conformance.cli.exit_codes import EXIT_OK, EXIT_USAGE
from conformance.cli.main import main
from conformance.protocol import Command, ErrorKind, backend_id

MODELS = default_corpus_root() / "models"
CASES = [case for f in load_corpus([MODELS]) for case in f.cases]
PYDRAKE = load_backend("pydrake")
REIMPL = load_backend("reimpl")
MODEL_FEATURES = {"multibody", "parsing", "adjacency_opt_out", "filter_groups_report"}

URDF = (
    '<robot name="r" xmlns:drake="http://drake.mit.edu">\n'
    '  <link name="a"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>\n'
    '  <link name="b"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>\n'
    '  <drake:collision_filter_group name="g1"><drake:member link="a"/>'
    '<drake:member link="{member}"/><drake:ignored_collision_filter_group name="g1"/>'
    "</drake:collision_filter_group>\n"
    "</robot>\n"
)


def _id(case: Case) -> str:
    return case.qualified_name


# ------------------------------------------------------------------ the corpus
def test_the_model_corpus_has_at_least_forty_cases_in_its_topics() -> None:
    names = {case.file.name for case in CASES}
    assert len(CASES) >= 40
    assert names == {
        "models/plant_adjacency",
        "models/welds",
        "models/urdf_groups",
        "models/sdf_groups",
        "models/directives",
        "models/model_errors",
        "models/on_top",
        "models/fuzz_findings",
        "models/inventory",
        "models/urdf_inertia",
        "models/sdf_documents",
    }


@pytest.mark.parametrize("case", CASES, ids=_id)
def test_the_model_case_holds_on_pydrake(case: Case) -> None:
    report = run_case(case, [PYDRAKE])
    assert report.status["pydrake"] is Outcome.PASS, report.failures or report.aborted


@pytest.mark.parametrize("case", CASES, ids=_id)
def test_reimpl_agrees_with_pydrake_on_the_model_case(case: Case) -> None:
    missing = case.features - REIMPL.features()
    if missing:
        pytest.skip(f"reimpl lacks {sorted(missing)} (reimpl.multibody has not landed)")
    report = run_case(case, [REIMPL, PYDRAKE])
    assert report.status["reimpl"] in (Outcome.PASS, Outcome.XFAIL), report.failures


def test_every_model_case_needs_the_features_of_its_ops() -> None:
    for case in CASES:
        assert {GRAMMAR[step.op].feature for step in case.steps} <= case.features


def test_the_backend_has_a_joint_class_for_every_joint_type_of_the_grammar() -> None:
    assert tuple(JOINT_CLASSES) == JOINT_TYPES


def test_every_joint_type_and_model_op_is_exercised_by_the_corpus() -> None:
    steps = [step for case in CASES for step in case.steps]
    assert {step.op for step in steps} >= set(ops_of("model"))
    assert {step.args["type"] for step in steps if step.op == "add_joint"} == set(JOINT_TYPES)
    formats = {step.args.get("format") for step in steps if step.op == "add_models"}
    assert formats == {"urdf", "sdf", "dmd.yaml", None}  # None: a path


# ---------------------------------------------------------------- the grammar
def test_the_model_ops_are_rows_of_the_grammar_with_domain_model() -> None:
    assert [c.op for c in MODEL_COMMANDS] == list(ops_of("model"))
    assert [c.op for c in MODEL_COMMANDS] == [
        "add_models",
        "collision_filter_groups",
        "model_inventory",
        "rename_model_instance",
        "add_rigid_body",
        "add_joint",
        "weld_frames",
        "register_collision_geometry",
        "register_visual_geometry",
        "set_adjacent_filters",
        "finalize",
    ]
    assert {c.feature for c in MODEL_COMMANDS} == MODEL_FEATURES


def test_the_schema_has_a_rule_for_each_model_op_and_their_feature_tags() -> None:
    schema = scenario_schema()
    step = schema["$defs"]["step"]
    rules = {rule["if"]["properties"]["op"]["const"]: rule["then"] for rule in step["allOf"]}
    for command in MODEL_COMMANDS:
        assert command.op in step["properties"]["op"]["enum"]
        assert set(rules[command.op]["properties"]) == {
            "op",
            "comment",
            "expect",
            *(arg.key for arg in command.args),
        }
    add_models = rules["add_models"]
    assert add_models["oneOf"] == [{"required": ["text"]}, {"required": ["path"]}]
    assert add_models["dependentRequired"] == {"text": ["format"], "folder": ["path"]}
    assert rules["add_joint"]["required"] == ["name", "type", "parent", "child"]
    assert set(schema["$defs"]["features"]["items"]["enum"]) >= MODEL_FEATURES


def test_pydrake_since_1_31_has_every_model_feature() -> None:
    assert parse_version(backend_id(PYDRAKE).version) >= (1, 31)
    assert PYDRAKE.features() >= MODEL_FEATURES


# ------------------------------------------------------------ input errors
def _write(tmp_path: Path, steps: list[dict[str, Any]]) -> Path:
    path = tmp_path / "model_case.json"
    data = {"description": "a model case", "cases": [{"description": "c1", "steps": steps}]}
    path.write_text(json.dumps(data), encoding="utf-8")
    return path


def _run(path: Path) -> tuple[int, str]:
    out, err = io.StringIO(), io.StringIO()
    code = main(["run", str(path), "--backend", "pydrake"], out=out, err=err)
    return code, err.getvalue()


def test_model_text_without_its_format_is_exit_two_naming_file_case_and_step(
    tmp_path: Path,
) -> None:
    path = _write(
        tmp_path,
        [
            {"op": "finalize"},
            {"op": "add_models", "text": URDF.format(member="b"), "expect": {"candidates": []}},
        ],
    )
    code, err = _run(path)
    assert code == EXIT_USAGE
    assert f"{path}: case 'c1': schema violation at step 2" in err
    assert "'format' is a dependency of 'text'" in err


def test_a_scoped_name_before_any_add_models_is_exit_two_naming_the_step_and_field(
    tmp_path: Path,
) -> None:
    path = _write(
        tmp_path,
        [
            {"op": "collision_filtered", "pair": ["r::a/Sphere", "r::b/Sphere"]},
            {"op": "add_models", "text": URDF.format(member="b"), "format": "urdf"},
            {"op": "collision_filtered", "pair": ["r::a/Sphere", "r::b/Sphere"], "expect": {}},
        ],
    )
    with pytest.raises(ScenarioError) as raised:
        load_corpus([path])
    assert str(raised.value) == (
        f"{path}: case 'c1': step 1, field pair: unknown geometry name 'r::a/Sphere' "
        "(declare it in the scene or an earlier step)"
    )
    assert _run(path)[0] == EXIT_USAGE


def test_scoped_names_after_add_models_pass_the_name_check_and_the_case_runs(
    tmp_path: Path,
) -> None:
    path = _write(
        tmp_path,
        [
            {"op": "add_models", "text": URDF.format(member="b"), "format": "urdf"},
            {
                "op": "collision_filtered",
                "pair": ["r::a/Sphere", "r::b/Sphere"],
                "expect": {"returns": True, "candidates": []},
            },
        ],
    )
    assert _run(path)[0] == EXIT_OK


@pytest.mark.parametrize("backend", [PYDRAKE, REIMPL], ids=lambda b: b.name)
def test_a_bad_model_is_a_result_with_drakes_message_naming_the_element(
    backend: SceneGraphBackend,
) -> None:
    if "parsing" not in backend.features():
        pytest.skip(f"{backend.name} cannot parse models yet")
    backend.reset()
    command = {"text": URDF.format(member="zz"), "format": "urdf"}
    result = backend.execute(Command("add_models", command))
    assert result.error is not None
    assert result.error.kind is ErrorKind.OTHER
    assert (
        result.error.message == "<literal-string>.urdf:1: error: body with name 'r::zz' not found"
    )


@pytest.mark.parametrize("backend", [PYDRAKE, REIMPL], ids=lambda b: b.name)
def test_a_bad_model_file_names_the_file_below_the_case_folder(
    backend: SceneGraphBackend,
) -> None:
    if "parsing" not in backend.features():
        pytest.skip(f"{backend.name} cannot parse models yet")
    backend.reset()
    files = {"robots/r.urdf": URDF.format(member="zz")}
    result = backend.execute(Command("add_models", {"files": files, "path": "robots/r.urdf"}))
    assert result.error is not None
    assert result.error.message == "robots/r.urdf:1: error: body with name 'r::zz' not found"


def test_a_case_folder_holds_the_files_until_the_next_reset() -> None:
    backend = PYDRAKE
    assert isinstance(backend, SceneGraphBackend)
    backend.reset()
    files = {"r.urdf": URDF.format(member="b")}
    result = backend.execute(Command("add_models", {"files": files, "path": "r.urdf"}))
    assert result.value == ["r"]
    folder = backend._folder
    assert folder is not None
    assert (folder / "r.urdf").is_file()
    backend.reset()
    assert not folder.exists()


def test_an_unknown_scoped_body_in_a_step_is_an_input_error_of_the_case(tmp_path: Path) -> None:
    path = _write(
        tmp_path,
        [
            {"op": "add_models", "text": URDF.format(member="b"), "format": "urdf"},
            {"op": "weld_frames", "parent": "world", "child": "r::zz", "expect": {}},
        ],
    )
    code, err = _run(path)
    assert code == EXIT_USAGE
    assert f"{path.name}: case 'c1': step 2 (weld_frames): unknown body name 'r::zz'" in err


def test_a_model_every_backend_rejects_unexpectedly_is_exit_two_naming_file_case_and_line(
    tmp_path: Path,
) -> None:
    path = _write(
        tmp_path,
        [
            {"op": "add_models", "text": URDF.format(member="zz"), "format": "urdf"},
            {"op": "finalize"},
        ],
    )
    code, err = _run(path)
    assert code == EXIT_USAGE
    assert (
        f"{path.name}: case 'c1': step 1 (add_models): the model is invalid on pydrake: "
        "<literal-string>.urdf:1: error: body with name 'r::zz' not found"
    ) in err


def test_a_model_error_the_case_expects_is_a_conformance_check(tmp_path: Path) -> None:
    error = {"kind": "other", "message": "<literal-string>.urdf:1: error: body with name"}
    path = _write(
        tmp_path,
        [
            {
                "op": "add_models",
                "text": URDF.format(member="zz"),
                "format": "urdf",
                "expect": {"error": error},
            },
        ],
    )
    assert _run(path)[0] == EXIT_OK


# --------------------------------------------------------- other releases
def _cached(version: str) -> bool:
    """Whether an environment for ``version`` is built (the tests' cache, or the real one)."""
    return not missing_releases([version])


def _case(description: str) -> Case:
    return next(case for case in CASES if case.description == description)


@pytest.mark.skipif(not _cached("1.40.0"), reason="no cached environment for Drake 1.40.0")
def test_a_worker_of_another_release_runs_the_model_ops() -> None:
    worker = load_backend("drake==1.40.0")
    case = _case("the parser reports each group's scoped members and each ignored pair once")
    report = run_case(case, [worker])
    assert report.status["drake==1.40.0"] is Outcome.PASS, report.failures


@pytest.mark.skipif(not _cached("1.30.0"), reason="no cached environment for Drake 1.30.0")
def test_drake_1_30_aborts_on_an_undefined_ignored_group_as_its_crash_row_records() -> None:
    worker = load_backend("drake==1.30.0")
    report = run_case(
        _case("ignoring an undefined group is an error naming the scoped group"), [worker]
    )
    assert report.broken["drake==1.30.0"] is Outcome.CRASH
    assert report.recorded == {"drake==1.30.0": "undefined-ignored-group-aborts"}
    assert report.status["drake==1.30.0"] is Outcome.PASS  # the release's recorded answer


@pytest.mark.skipif(not _cached("1.12.0"), reason="no cached environment for Drake 1.12.0")
def test_a_release_without_a_binding_the_case_calls_skips_it_in_run() -> None:
    worker = load_backend("drake==1.12.0")
    case = next(c for c in CASES if "RpyFloatingJoint between two bodies" in c.description)
    report = run_case(case, [REIMPL, worker])
    assert report.status[worker.name] is Outcome.SKIP
    assert report.skip_reasons[worker.name].startswith(
        "no binding: step 5 (add_joint): pydrake #.#.# has no multibody.tree.RpyFloatingJoint"
    )


def test_a_model_case_that_no_backend_runs_is_no_input_error() -> None:
    case = _case("the parser reports each group's scoped members and each ignored pair once")
    from conformance._engine import Trace  # noqa: PLC0415
    from conformance._run.runner import _bad_model  # noqa: PLC0415 (the rule under test)

    assert _bad_model(case, Trace("pydrake"), [], "pydrake") is None
