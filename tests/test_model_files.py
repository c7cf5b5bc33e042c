"""Model files nobody wrote for this harness: ``model_inventory``, ``add_models`` with a
``folder``, failed DRAKE_DEMANDs as answers, and ``python -m conformance models``.

Expected values were measured on pydrake 1.51.1 with Drake's own model files
(vendored in ``scenarios/real_models/drake``).
"""

from __future__ import annotations

import io
import json
from pathlib import Path
from typing import Any

import pytest

from conformance._backends.environments import DrakeEnvironmentError, find_python
from conformance._backends.loader import load_backend
from conformance._corpus.loader import default_corpus_root
from conformance._corpus.model_files import (
    GROUPS_SUFFIX,
    find_model_files,
    is_model_file,
    model_cases,
)
from conformance._grammar.schema import scenario_schema
from conformance.cli.exit_codes import EXIT_FAILURE, EXIT_OK, EXIT_USAGE
from conformance.cli.main import main
from conformance.cli.models import model_file_cases
from conformance.protocol import Command, ErrorKind
from tests.test_html_report import parse, step_of

DRAKE = default_corpus_root() / "real_models" / "drake"
ACROBOT = "examples/acrobot/Acrobot.urdf"

#: pydrake 1.51.1's inventory of Drake's Acrobot.urdf after Finalize.
ACROBOT_INVENTORY = {
    "models": ["Acrobot", "DefaultModelInstance", "WorldModelInstance"],
    "bodies": [
        "Acrobot::base_link",
        "Acrobot::lower_link",
        "Acrobot::upper_link",
        "WorldModelInstance::world",
    ],
    "frames": [
        "Acrobot::base_link",
        "Acrobot::base_weld_parent",
        "Acrobot::elbow_parent",
        "Acrobot::hand",
        "Acrobot::lower_link",
        "Acrobot::shoulder_parent",
        "Acrobot::upper_link",
        "WorldModelInstance::world",
    ],
    "joints": [
        "Acrobot::base_weld (weld)",
        "Acrobot::elbow (revolute)",
        "Acrobot::shoulder (revolute)",
    ],
    "geometries": [
        "Acrobot::base_link/Acrobot::Box: Box [illustration, perception]",
        "Acrobot::base_link/Acrobot::base_link_collision: Box [proximity]",
        "Acrobot::lower_link/Acrobot::Cylinder: Cylinder [illustration, perception]",
        "Acrobot::lower_link/Acrobot::lower_link_collision: Cylinder [proximity]",
        "Acrobot::upper_link/Acrobot::Cylinder: Cylinder [illustration, perception]",
        "Acrobot::upper_link/Acrobot::upper_link_collision: Cylinder [proximity]",
    ],
}


def _execute(backend: Any, op: str, **args: Any) -> Any:
    return backend.execute(Command(op, args))


@pytest.mark.parametrize("name", ["reimpl", "pydrake"])
def test_model_inventory_lists_models_bodies_frames_joints_and_geometries(name: str) -> None:
    backend = load_backend(name)
    backend.reset()
    text = (DRAKE / ACROBOT).read_text(encoding="utf-8")
    assert _execute(backend, "add_models", text=text, format="urdf").value == ["Acrobot"]
    assert _execute(backend, "finalize").error is None
    assert _execute(backend, "model_inventory").value == ACROBOT_INVENTORY


def test_add_models_with_a_folder_finds_its_packages_and_cuts_it_from_messages() -> None:
    backend = load_backend("pydrake")
    backend.reset()
    models = _execute(backend, "add_models", folder=str(DRAKE), path=ACROBOT)
    assert models.value == ["Acrobot"]
    backend.reset()
    bad = "multibody/parsing/test/urdf_parser_test/conflicting_materials.urdf"
    error = _execute(backend, "add_models", folder=str(DRAKE), path=bad).error
    assert error is not None
    assert error.message == f"{bad}:6: error: Material 'brown' was previously defined."


def test_a_failed_drake_demand_is_an_assertion_error_result_not_a_broken_backend() -> None:
    backend = load_backend("pydrake")
    backend.reset()
    weld = "multibody/parsing/test/process_model_directives_test/deep_child_frame_weld.dmd.yaml"
    error = _execute(backend, "add_models", folder=str(DRAKE), path=weld).error
    assert error is not None
    assert error.kind is ErrorKind.ASSERTION
    assert error.message.startswith("Failure at ")
    assert error.message.endswith("in AddWeld(): condition 'found' failed.")


#: The MuJoCo models of Drake's repository (its other .xml files are package.xml files).
MUJOCO_FILES = [
    Path("multibody/benchmarks/acrobot/acrobot.xml"),
    Path("multibody/parsing/test/box_package/mjcfs/box.xml"),
    Path("multibody/parsing/test/mujoco_parser_test/nested.xml"),
    Path("multibody/parsing/test/mujoco_parser_test/pendulum.xml"),
    Path("multibody/parsing/test/mujoco_parser_test/pendulum_geom.xml"),
    Path("multibody/parsing/test/mujoco_parser_test/scene.xml"),
    Path("multibody/parsing/test/sdf_parser_test/interface_api_test/arm.xml"),
]


def test_find_model_files_lists_urdf_sdf_directives_and_mujoco_in_sorted_order() -> None:
    files = find_model_files(DRAKE)
    assert len(files) == 162
    assert files == sorted(files)
    assert {f.name.rsplit(".", 1)[-1] for f in files} == {"urdf", "sdf", "yaml", "xml"}
    assert [f for f in files if f.suffix == ".xml"] == MUJOCO_FILES
    assert Path(ACROBOT) in files


def test_find_model_files_lists_obj_meshes_only_when_asked() -> None:
    with_obj = find_model_files(DRAKE, obj=True)
    meshes = [f for f in with_obj if f.suffix == ".obj"]
    assert len(meshes) == 19
    assert Path("multibody/parsing/test/tri_cube.obj") in meshes
    assert sorted(set(with_obj) - set(meshes)) == find_model_files(DRAKE)


@pytest.mark.parametrize(
    ("text", "is_model"),
    [
        ('<mujoco model="m"/>', True),
        ('\ufeff<?xml version="1.0"?>\n<!-- a <mujoco> comment -->\n<mujoco>\n</mujoco>', True),
        ("<package format='2'><name>mujoco</name></package>", False),
        ("<mujocox/>", False),
        ("", False),
    ],
)
def test_an_xml_file_is_a_model_file_when_its_first_element_is_mujoco(
    tmp_path: Path, text: str, is_model: bool
) -> None:
    path = tmp_path / "model.xml"
    path.write_text(text, encoding="utf-8")
    assert is_model_file(path) is is_model


def test_a_file_that_may_declare_groups_also_gets_a_filter_group_case() -> None:
    groups = "multibody/parsing/test/urdf_parser_test/non_conflicting_materials_3.urdf"
    cases = model_cases(DRAKE, [Path(ACROBOT), Path(groups)])
    assert [c["description"] for c in cases] == [ACROBOT, groups]
    with_groups = "multibody/parsing/test/sdf_parser_test/collision_filter_group_parsing_test/"
    cases = model_cases(DRAKE, [Path(with_groups + "test.sdf")])
    assert [c["description"] for c in cases] == [
        with_groups + "test.sdf",
        with_groups + "test.sdf" + GROUPS_SUFFIX,
    ]
    assert [s["op"] for s in cases[1]["steps"]] == ["add_models", "collision_filter_groups"]


def test_a_model_file_given_alone_finds_the_packages_of_its_package_root() -> None:
    (case,) = model_file_cases([DRAKE / ACROBOT])
    assert case.qualified_name == f"drake > {ACROBOT}"
    assert case.steps[0].args == {"folder": str(DRAKE), "path": ACROBOT}


def _models(*argv: str) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    code = main(["models", *argv], out, err)
    return code, out.getvalue(), err.getvalue()


def _report(folder: Path) -> dict[str, Any]:
    document: dict[str, Any] = json.loads((folder / "report.json").read_text())
    return document


def test_models_exits_zero_when_the_backends_agree_on_every_file(tmp_path: Path) -> None:
    code, out, _ = _models(
        str(DRAKE / "examples" / "acrobot"), "-q", "--report", str(tmp_path / "report")
    )
    assert code == EXIT_OK
    assert out.splitlines()[0] == "reimpl against pydrake: agrees on all 3 file(s)"
    report = _report(tmp_path / "report")
    assert report["columns"] == ["reimpl", "pydrake"]
    assert report["files"] == {
        name: {"reimpl": "pass", "pydrake": "pass"}
        for name in ("Acrobot.sdf", "Acrobot.urdf", "Acrobot_no_collision.urdf")
    }
    assert report["comparisons"] == [
        {"from": "pydrake", "to": "reimpl", "files": [], "changes": []}
    ]
    assert sorted(p.name for p in (tmp_path / "report").iterdir()) == [
        "heatmap.png",
        "report.html",
        "report.json",
        "report.md",
    ]


#: A URDF whose ``<drake:capsule>`` a mutant drops (model_mutants.drake_capsule_dropped).
CAPSULES = (
    '<robot name="r" xmlns:drake="http://drake.mit.edu"><link name="a"><collision name="c">'
    '<geometry><drake:capsule radius="0.1" length="0.2"/></geometry></collision></link>'
    '<link name="b"><collision name="d"><geometry><box size="1 1 1"/></geometry></collision>'
    "</link></robot>\n"
)
MUTANT = "conformance._testing.model_mutants:drake_capsule_dropped"


def test_models_lists_each_difference_from_the_reference_by_scoped_name_and_exits_one(
    tmp_path: Path,
) -> None:
    (tmp_path / "r.urdf").write_text(CAPSULES, encoding="utf-8")
    code, out, _ = _models(str(tmp_path), "--backend", "pydrake", "--backend", MUTANT, "-q")
    assert code == EXIT_FAILURE
    assert out.splitlines() == [
        f"{'mutant:drake_capsule_dropped'} against pydrake: 1 of 1 file(s) differ",
        "  r.urdf",
        "    geometries: only pydrake: r::a/r::c: Capsule [proximity]",
        "    candidate pairs: only pydrake: r::a/c-r::b/d",
    ]


def test_models_save_writes_one_columns_answers_and_check_finds_each_change(
    tmp_path: Path,
) -> None:
    (tmp_path / "robot").mkdir()
    model = tmp_path / "robot" / "r.urdf"
    model.write_text(CAPSULES, encoding="utf-8")
    golden = tmp_path / "golden.json"
    code, out, _ = _models(str(tmp_path / "robot"), "--backend", "pydrake", "--save", str(golden))
    assert code == EXIT_OK
    assert out.splitlines()[-1] == f"wrote {golden} (pydrake's answers)"
    code, out, _ = _models(str(tmp_path / "robot"), "--backend", "reimpl", "--check", str(golden))
    assert code == EXIT_OK
    assert out.splitlines() == ["golden (pydrake) → reimpl: no change in 1 file(s)"]
    model.write_text(CAPSULES.replace('name="b"', 'name="b2"'), encoding="utf-8")
    code, out, _ = _models(str(tmp_path / "robot"), "--backend", "reimpl", "--check", str(golden))
    assert code == EXIT_FAILURE
    assert "golden (pydrake) → reimpl: 1 of 1 file(s) changed" in out
    assert "    bodies: only golden (pydrake): r::b" in out
    assert "    bodies: only reimpl: r::b2" in out
    assert "    candidate pairs: only reimpl: r::a/c-r::b2/d" in out


def test_models_save_needs_exactly_one_column(tmp_path: Path) -> None:
    (tmp_path / "r.urdf").write_text(CAPSULES, encoding="utf-8")
    code, _, err = _models(str(tmp_path), "--save", str(tmp_path / "g.json"), "-q")
    assert code == EXIT_USAGE
    assert "--save needs exactly one column that ran, got ['reimpl', 'pydrake']" in err


def test_models_check_refuses_a_file_that_is_not_a_golden_file(tmp_path: Path) -> None:
    (tmp_path / "r.urdf").write_text(CAPSULES, encoding="utf-8")
    (tmp_path / "g.json").write_text("{}", encoding="utf-8")
    code, _, err = _models(str(tmp_path / "r.urdf"), "--check", str(tmp_path / "g.json"))
    assert code == EXIT_USAGE
    assert f"error: {tmp_path / 'g.json'}: not a golden file of format 1" in err


def test_models_package_option_adds_a_package_the_folder_does_not_hold(tmp_path: Path) -> None:
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "box.obj").write_bytes(
        (DRAKE / "multibody/parsing/test/tri_cube.obj").read_bytes()
    )
    (tmp_path / "robot").mkdir()
    (tmp_path / "robot" / "r.urdf").write_text(
        '<robot name="r"><link name="a"><collision><geometry>'
        '<mesh filename="package://my_meshes/box.obj"/></geometry></collision></link></robot>\n',
        encoding="utf-8",
    )
    robot, meshes = str(tmp_path / "robot"), tmp_path / "meshes"
    answers = {}
    for name, extra in (("without", []), ("with", ["--package", f"my_meshes={meshes}"])):
        golden = tmp_path / f"{name}.json"
        code, _, _ = _models(robot, "-q", "--backend", "pydrake", "--save", str(golden), *extra)
        assert code == EXIT_OK
        (answer,) = json.loads(golden.read_text())["answers"].values()
        answers[name] = answer["results"][0]
    assert answers["without"]["error"]["message"] == (
        "r.urdf:1: error: URI 'package://my_meshes/box.obj' refers to unknown package 'my_meshes'"
    )
    assert answers["with"] == {"value": ["r"]}
    code, out, _ = _models(robot, "-q", "--package", f"my_meshes={meshes}")
    assert code == EXIT_OK
    assert out.splitlines() == ["reimpl against pydrake: agrees on all 1 file(s)"]


@pytest.mark.parametrize(
    ("given", "message"),
    [
        ("nowhere", "no such file or folder"),
        ("README.md", "not a model file (.urdf, .sdf, .dmd.yaml, MuJoCo .xml, .obj)"),
    ],
)
def test_models_refuses_what_is_not_a_model_file_with_exit_two(
    given: str, message: str, tmp_path: Path
) -> None:
    (tmp_path / "README.md").write_text("hello", encoding="utf-8")
    code, _, err = _models(str(tmp_path / given), "--backend", "pydrake")
    assert code == EXIT_USAGE
    assert err.startswith("error: ")
    assert message in err


def test_models_refuses_a_folder_without_model_files(tmp_path: Path) -> None:
    code, _, err = _models(str(tmp_path), "--backend", "pydrake")
    assert code == EXIT_USAGE
    assert "no model files (.urdf, .sdf, .dmd.yaml, MuJoCo .xml, .obj) below this folder" in err


def test_models_parses_the_obj_meshes_of_a_folder_with_obj(tmp_path: Path) -> None:
    """Without --obj a folder of meshes has no model files; with it, reimpl and pydrake each
    add tri_cube.obj as the one-body model tri_cube, and agree (pydrake 1.51.1)."""
    mesh = DRAKE / "multibody/parsing/test/tri_cube.obj"
    (tmp_path / "tri_cube.obj").write_bytes(mesh.read_bytes())
    code, _, err = _models(str(tmp_path), "--backend", "pydrake")
    assert code == EXIT_USAGE
    assert "no model files" in err
    code, _, _ = _models(str(tmp_path), "--obj", "-q", "--report", str(tmp_path / "report"))
    assert code == EXIT_OK
    assert _report(tmp_path / "report")["files"] == {
        "tri_cube.obj": {"reimpl": "pass", "pydrake": "pass"}
    }


def test_the_schema_accepts_every_error_kind_of_the_protocol() -> None:
    schema = scenario_schema()
    kinds = schema["$defs"]["expectation"]["properties"]["error"]["properties"]["kind"]["enum"]
    assert kinds == [kind.value for kind in ErrorKind]
    assert "assertion" in kinds


#: A link whose second collision is a .stl mesh (as simple_humanoid.urdf of
#: Gepetto/example-robot-data has it).
STL_ROBOT = (
    '<robot name="r"><link name="a"><collision name="c"><geometry><box size="1 1 1"/>'
    '</geometry></collision><collision name="m"><geometry><mesh filename="a.stl"/></geometry>'
    "</collision></link></robot>\n"
)


def test_models_records_a_raising_candidates_answer_as_the_files_answer(
    tmp_path: Path,
) -> None:
    """pydrake 1.51.1 leaves the .stl geometry half-registered after its error (a proximity
    role, but no place in the collision filter): GetCollisionCandidates then raises
    IndexError('_Map_base::at') as it pairs it with the box (a Drake bug, measured; since
    1.52 it lists the pair). The observation records that error as the answer, so the file
    is a case like any other and the run goes on (it broke the case before 77d8cab)."""
    (tmp_path / "a.stl").write_text("solid a\nendsolid a\n", encoding="utf-8")
    (tmp_path / "a_stl.urdf").write_text(STL_ROBOT, encoding="utf-8")
    (tmp_path / "b_box.urdf").write_text(STL_ROBOT.replace("a.stl", "b.obj"), encoding="utf-8")
    code, _, err = _models(
        str(tmp_path), "--backend", "pydrake", "-q", "--report", str(tmp_path / "report")
    )
    assert code == EXIT_OK
    assert "broke an implementation" not in err
    assert _report(tmp_path / "report")["files"] == {
        "a_stl.urdf": {"pydrake": "pass"},
        "b_box.urdf": {"pydrake": "pass"},
    }


def _have_python_312() -> bool:
    try:
        find_python("1.58.0")
    except DrakeEnvironmentError:
        return False
    return True


@pytest.mark.skipif(not _have_python_312(), reason="no Python 3.12+ for Drake 1.58")
def test_models_across_releases_lists_what_changed_from_each_release_to_the_next(
    tmp_path: Path,
) -> None:
    """Measured: Drake 1.55 stopped making a URDF joint's '<joint>_parent' frame for an
    identity origin (urdf-identity-joint-parent-frame-until-1.54)."""
    code, out, _ = _models(
        str(DRAKE / ACROBOT), "--drake", "1.51.1", "1.58.0", "-q", "--report", str(tmp_path)
    )
    assert code == EXIT_OK  # a change between releases is no failure
    assert out.splitlines()[:3] == [
        "1.51.1 → 1.58.0: 1 of 1 file(s) changed",
        f"  {ACROBOT}",
        "    frames: only 1.51.1: Acrobot::base_weld_parent",
    ]
    report = _report(tmp_path)
    assert report["columns"] == ["1.51.1", "1.58.0"]
    assert report["comparisons"][0]["changes"] == [
        {
            "file": ACROBOT,
            "what": "frames",
            "removed": ["Acrobot::base_weld_parent"],
            "added": [],
        }
    ]
    # report.html: the file's row changes; 1.58.0's cell opens the first differing step,
    # model_inventory's answer, with 1.51.1's frames holding base_weld_parent and 1.58.0's not.
    root = parse((tmp_path / "report.html").read_text())
    (row,) = root.by_id("changed-rows").all("tr", "row")
    old, new = row.all("td", "cell")
    assert not old.all("details")
    step = step_of(new)
    assert step["where"] == "step 3"
    answers = step["answers"]
    assert isinstance(answers, dict)
    assert "Acrobot::base_weld_parent" in answers["1.51.1"]
    assert "Acrobot::base_weld_parent" not in answers["1.58.0"]
