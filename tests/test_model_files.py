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

from conformance.backends.loader import load_backend
from conformance.cli.exit_codes import EXIT_OK, EXIT_USAGE
from conformance.cli.main import main
from conformance.cli.models import model_file_cases
from conformance.corpus.loader import default_corpus_root
from conformance.corpus.model_files import (
    GROUPS_SUFFIX,
    find_model_files,
    is_model_file,
    model_cases,
)
from conformance.grammar.schema import scenario_schema
from conformance.protocol import Command, ErrorKind

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


def test_models_exits_zero_when_the_backends_agree_on_every_file(tmp_path: Path) -> None:
    report = tmp_path / "report.json"
    code, out, _ = _models(
        str(DRAKE / "examples" / "acrobot"), "--backend", "pydrake", "-q", "--json", str(report)
    )
    assert code == EXIT_OK
    cases = json.loads(report.read_text())["cases"]
    assert sorted(c["qualified_name"] for c in cases) == [
        "acrobot > Acrobot.sdf",
        "acrobot > Acrobot.urdf",
        "acrobot > Acrobot_no_collision.urdf",
    ]
    assert "3      3 pass" in out


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
    report = tmp_path / "report.json"
    code, out, _ = _models(
        str(tmp_path),
        "--obj",
        "--backend",
        "reimpl",
        "--backend",
        "pydrake",
        "-q",
        "--json",
        str(report),
    )
    assert code == EXIT_OK
    (case,) = json.loads(report.read_text())["cases"]
    assert case["qualified_name"].endswith(" > tri_cube.obj")
    assert "1 pass" in out


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


def test_models_reports_a_file_that_breaks_a_backend_and_goes_on(tmp_path: Path) -> None:
    """pydrake 1.51.1 leaves the .stl geometry half-registered after its error (a proximity
    role, but no place in the collision filter): GetCollisionCandidates then raises
    IndexError('_Map_base::at') as it pairs it with the box (a Drake bug, measured)."""
    (tmp_path / "a.stl").write_text("solid a\nendsolid a\n", encoding="utf-8")
    (tmp_path / "a_stl.urdf").write_text(STL_ROBOT, encoding="utf-8")
    (tmp_path / "b_box.urdf").write_text(STL_ROBOT.replace("a.stl", "b.obj"), encoding="utf-8")
    report = tmp_path / "report.json"
    code, _, err = _models(str(tmp_path), "--backend", "pydrake", "-q", "--json", str(report))
    assert code == EXIT_USAGE
    assert "_Map_base::at" in err
    cases = {
        c["qualified_name"].split(" > ")[1]: c for c in json.loads(report.read_text())["cases"]
    }
    assert sorted(cases) == ["a_stl.urdf", "b_box.urdf"]
    assert cases["a_stl.urdf"]["status"] == {"pydrake": "error"}
    assert cases["b_box.urdf"]["status"] == {"pydrake": "pass"}
