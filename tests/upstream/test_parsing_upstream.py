# Ported from Drake: bindings/pydrake/multibody/test/parsing_test.py
# (https://github.com/RobotLocomotion/drake), re-expressed as pytest functions that run
# unchanged on pydrake and on reimpl.
#
# Drake's license (BSD 3-Clause), which covers the upstream test this file is ported from:
#
#   Copyright 2012-2022, Robot Locomotion Group @ CSAIL, Massachusetts Institute of Technology
#   All rights reserved.
#
#   Redistribution and use in source and binary forms, with or without modification, are
#   permitted provided that the following conditions are met:
#
#   1. Redistributions of source code must retain the above copyright notice, this list of
#      conditions and the following disclaimer.
#   2. Redistributions in binary form must reproduce the above copyright notice, this list of
#      conditions and the following disclaimer in the documentation and/or other materials
#      provided with the distribution.
#   3. Neither the name of the copyright holder nor the names of its contributors may be used
#      to endorse or promote products derived from this software without specific prior
#      written permission.
#
#   THIS SOFTWARE IS PROVIDED BY THE COPYRIGHT HOLDERS AND CONTRIBUTORS "AS IS" AND ANY
#   EXPRESS OR IMPLIED WARRANTIES, INCLUDING, BUT NOT LIMITED TO, THE IMPLIED WARRANTIES OF
#   MERCHANTABILITY AND FITNESS FOR A PARTICULAR PURPOSE ARE DISCLAIMED. IN NO EVENT SHALL THE
#   COPYRIGHT HOLDER OR CONTRIBUTORS BE LIABLE FOR ANY DIRECT, INDIRECT, INCIDENTAL, SPECIAL,
#   EXEMPLARY, OR CONSEQUENTIAL DAMAGES (INCLUDING, BUT NOT LIMITED TO, PROCUREMENT OF
#   SUBSTITUTE GOODS OR SERVICES; LOSS OF USE, DATA, OR PROFITS; OR BUSINESS INTERRUPTION)
#   HOWEVER CAUSED AND ON ANY THEORY OF LIABILITY, WHETHER IN CONTRACT, STRICT LIABILITY, OR
#   TORT (INCLUDING NEGLIGENCE OR OTHERWISE) ARISING IN ANY WAY OUT OF THE USE OF THIS
#   SOFTWARE, EVEN IF ADVISED OF THE POSSIBILITY OF SUCH DAMAGE.
"""Upstream pydrake.multibody.parsing binding tests, on pydrake and on reimpl.

Changes, each for a stated reason: ``FindResourceOrThrow`` paths are the
vendored Drake checkout's (``drake_models``) and ``$TEST_TMPDIR`` is pytest's
``tmp_path``; ``package://drake/multibody/benchmarks/...`` is not in pydrake's
wheel (its ``drake`` package is ``share/drake``), so the URL test loads
``package://drake/examples/acrobot/Acrobot.sdf``; remote packages are fetched
into a cache under ``$TEST_TMPDIR``; the scoped-frame test runs on the
``float`` plant only (reimpl has no AutoDiffXd or Expression scalars).
Beyond upstream, the assertions check the values, measured on pydrake 1.51.1.
"""

from __future__ import annotations

import copy
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

from tests.upstream.parsing_support import names_of

ACROBOT = "multibody/benchmarks/acrobot"
TEST_DIR = "multibody/parsing/test/process_model_directives_test"


def _plant(drake: ModuleType) -> Any:
    return drake.multibody.plant.MultibodyPlant(time_step=0.01)


def test_collision_filter_groups(drake: ModuleType) -> None:
    dut = drake.multibody.parsing.CollisionFilterGroups()
    dut.AddGroup(name="a", members={"b", "c"})
    dut.AddExclusionPair(pair=("d", "e"))
    assert not dut.empty()
    assert dut.groups() == {"a": {"b", "c"}}
    assert dut.exclusion_pairs() == {("d", "e")}
    report = str(dut)
    assert report == (
        "\nCollision filter groups:\n    a\n        b\n        c\n"
        "Collision filter exclusion pairs:\n    d, e\n"
    )


def test_package_map(
    drake: ModuleType, drake_models: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    PackageMap = drake.multibody.parsing.PackageMap
    dut = PackageMap()
    assert dut.size() == 2
    PackageMap(other=dut)
    copy.copy(dut)

    dut = PackageMap.MakeEmpty()
    dut2 = PackageMap.MakeEmpty()
    tmpdir = str(tmp_path)
    monkeypatch.setenv("TEST_TMPDIR", tmpdir)

    dut.Add(package_name="root", package_path=tmpdir)
    dut2.Add(package_name="root", package_path=tmpdir)
    dut.AddMap(dut2)
    assert dut.Contains(package_name="root")
    assert dut.size() == 1
    assert dut.GetPackageNames() == ["root"]
    assert dut.GetPath(package_name="root") == tmpdir
    box_package = drake_models / "multibody/parsing/test/box_package"
    dut.AddPackageXml(filename=str(box_package / "package.xml"))
    assert dut.ResolveUrl(url="package://box_model/urdfs/box.urdf") == str(
        box_package / "urdfs" / "box.urdf"
    )
    dut2.Remove(package_name="root")
    assert dut2.size() == 0

    # Folder and environment: tmpdir holds no package.xml, so nothing is added.
    dut.PopulateFromEnvironment(environment_variable="TEST_TMPDIR")
    dut.PopulateFromFolder(path=tmpdir)
    assert sorted(dut.GetPackageNames()) == ["box_model", "root"]


def test_package_map_remote_params(drake: ModuleType) -> None:
    dut = drake.multibody.parsing.PackageMap.RemoteParams(
        urls=["file:///tmp/missing.zip"],
        sha256="0" * 64,
        archive_type="zip",
        strip_prefix="prefix",
    )
    assert "missing.zip" in dut.ToJson()
    assert dut.ToJson() == (
        f'{{"archive_type":"zip","sha256":"{"0" * 64}","strip_prefix":"prefix",'
        '"urls":["file:///tmp/missing.zip"]}'
    )
    assert repr(dut) == (
        f"RemoteParams(urls=['file:///tmp/missing.zip'], sha256='{'0' * 64}', "
        "archive_type='zip', strip_prefix='prefix')"
    )
    copy.copy(dut)
    copy.deepcopy(dut)


def test_package_map_add_remote(
    drake: ModuleType, drake_models: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A full AddRemote + GetPath lifecycle, fetching a file:// archive."""
    monkeypatch.setenv("TEST_TMPDIR", str(tmp_path))
    PackageMap = drake.multibody.parsing.PackageMap
    dut = PackageMap.MakeEmpty()
    zipfile = drake_models / "multibody/parsing/test/package_map_test_packages/compressed.zip"
    dut.AddRemote(
        package_name="compressed",
        params=PackageMap.RemoteParams(
            urls=[f"file://{zipfile}"],
            sha256="b4bdbad313293ca61fe8f4ed1b5579dadadb3a5c08f0a6d06a8e39e5f97f1bd1",
            strip_prefix="compressed_prefix",
        ),
    )
    path = dut.GetPath("compressed")
    with open(f"{path}/README", encoding="utf-8") as f:
        assert f.read() == "This package is empty.\n"


@pytest.mark.parametrize(("file_name", "as_path"), [("acrobot.sdf", True), ("acrobot.urdf", False)])
def test_parser_file(drake: ModuleType, drake_models: Path, file_name: str, as_path: bool) -> None:
    """Every combination of file-name arguments, and their return type."""
    path = drake_models / ACROBOT / file_name
    plant = _plant(drake)
    parser = drake.multibody.parsing.Parser(plant=plant)
    result = drake.multibody.parsing.Parser.AddModels(
        parser, file_name=path if as_path else str(path)
    )
    assert isinstance(result, list)
    assert isinstance(result[0], drake.multibody.tree.ModelInstanceIndex)
    assert names_of(plant, result) == ["acrobot"]


def test_parser_string(drake: ModuleType, drake_models: Path) -> None:
    sdf_contents = (drake_models / ACROBOT / "acrobot.sdf").read_text()
    plant = _plant(drake)
    parser = drake.multibody.parsing.Parser(plant=plant)
    results = parser.AddModelsFromString(file_contents=sdf_contents, file_type="sdf")
    assert isinstance(results[0], drake.multibody.tree.ModelInstanceIndex)

    # The related AddModels overload.
    plant = _plant(drake)
    parser = drake.multibody.parsing.Parser(plant=plant)
    results = parser.AddModels(file_contents=sdf_contents, file_type="sdf")
    assert isinstance(results[0], drake.multibody.tree.ModelInstanceIndex)
    assert names_of(plant, results) == ["acrobot"]


def test_parser_url(drake: ModuleType) -> None:
    """AddModelsFromUrl and its AddModels overload."""
    sdf_url = "package://drake/examples/acrobot/Acrobot.sdf"
    plant = _plant(drake)
    results = drake.multibody.parsing.Parser(plant).AddModelsFromUrl(url=sdf_url)
    assert isinstance(results[0], drake.multibody.tree.ModelInstanceIndex)
    plant = _plant(drake)
    results = drake.multibody.parsing.Parser(plant).AddModels(url=sdf_url)
    assert isinstance(results[0], drake.multibody.tree.ModelInstanceIndex)
    assert names_of(plant, results) == ["Acrobot"]


def test_parser_prefix_constructors(drake: ModuleType) -> None:
    Parser = drake.multibody.parsing.Parser
    model = "<robot name='r'><link name='a'/></robot>"
    plant = drake.multibody.plant.MultibodyPlant(time_step=0.0)
    scene_graph = drake.geometry.SceneGraph()
    Parser(plant=plant).AddModelsFromString(model, "urdf")

    # Reload the same model, via a different parser constructor: the names collide.
    with pytest.raises(RuntimeError, match=r".*names must be unique.*"):
        Parser(plant=plant, scene_graph=scene_graph).AddModelsFromString(model, "urdf")

    # Reload it with a model_name_prefix to avoid name collisions.
    Parser(plant=plant, model_name_prefix="prefix1").AddModelsFromString(model, "urdf")
    parser = Parser(plant=plant, scene_graph=scene_graph, model_name_prefix="prefix2")
    parser.AddModelsFromString(model, "urdf")
    assert parser.plant() is plant
    assert parser.scene_graph() is scene_graph


WARNS = """<robot name='robot' version='0.99'>
            <link name='a'/>
            </robot>"""


def test_strict(drake: ModuleType) -> None:
    # Lax parsing.
    plant = _plant(drake)
    parser = drake.multibody.parsing.Parser(plant=plant)
    results = parser.AddModelsFromString(file_contents=WARNS, file_type="urdf")
    assert isinstance(results[0], drake.multibody.tree.ModelInstanceIndex)
    # Strict parsing.
    plant = _plant(drake)
    parser = drake.multibody.parsing.Parser(plant=plant)
    parser.SetStrictParsing()
    with pytest.raises(RuntimeError) as info:
        parser.AddModelsFromString(file_contents=WARNS, file_type="urdf")
    assert str(info.value) == (
        "<literal-string>.urdf:1: error: The attribute 'version' found in a 'robot' tag is "
        "currently unsupported and will be ignored."
    )


def test_auto_renaming(drake: ModuleType) -> None:
    plant = _plant(drake)
    parser = drake.multibody.parsing.Parser(plant=plant)
    assert not parser.GetAutoRenaming()
    results = parser.AddModelsFromString(file_contents=WARNS, file_type="urdf")
    assert isinstance(results[0], drake.multibody.tree.ModelInstanceIndex)
    # Reload without auto-renaming: the name is taken.
    with pytest.raises(RuntimeError) as info:
        parser.AddModelsFromString(WARNS, "urdf")
    assert str(info.value) == (
        "This model already contains a model instance named 'robot'. Model instance names "
        "must be unique within a given model."
    )
    # Enable renaming and reload.
    parser.SetAutoRenaming(value=True)
    parser.AddModelsFromString(WARNS, "urdf")
    assert plant.HasModelInstanceNamed("robot_1")


def test_get_collision_filter_groups(drake: ModuleType) -> None:
    plant = _plant(drake)
    parser = drake.multibody.parsing.Parser(plant=plant)
    assert parser.GetCollisionFilterGroups().empty()


def test_parser_diagram_builder(drake: ModuleType) -> None:
    builder = drake.systems.framework.DiagramBuilder()
    plant, scene_graph = drake.multibody.plant.AddMultibodyPlantSceneGraph(builder, time_step=0.0)
    parser = drake.multibody.parsing.Parser(
        builder=builder, plant=plant, scene_graph=scene_graph, model_name_prefix="prefix"
    )
    assert parser.builder() is builder
    assert parser.plant() is plant
    assert parser.scene_graph() is scene_graph


def test_model_instance_info(drake: ModuleType) -> None:
    """The ModelInstanceInfo fields are bound (read-only properties)."""
    ModelInstanceInfo = drake.multibody.parsing.ModelInstanceInfo
    for name in (
        "model_name",
        "model_path",
        "parent_frame_name",
        "child_frame_name",
        "X_PC",
        "model_instance",
    ):
        assert hasattr(ModelInstanceInfo, name)
    # N.B. "No constructor" in 1.51.1, "no constructor" in 1.58.0 (pybind11's wording).
    with pytest.raises(TypeError, match=r"(?i)no constructor defined!$"):
        ModelInstanceInfo()


def test_scoped_frame_names(drake: ModuleType) -> None:
    plant = _plant(drake)
    parsing = drake.multibody.parsing
    world = parsing.GetScopedFrameByName(plant, "world")
    assert world.name() == "world"
    assert parsing.GetScopedFrameByNameMaybe(plant, "world").name() == "world"
    assert parsing.GetScopedFrameByNameMaybe(plant=plant, full_name="nope::frame") is None


def _make_plant_parser_directives(
    drake: ModuleType, drake_models: Path, path_type: type = Path
) -> tuple[Any, Any, Any]:
    """(plant, parser, directives) for the directive tests."""
    model_dir = drake_models / TEST_DIR
    plant = _plant(drake)
    parser = drake.multibody.parsing.Parser(plant=plant)
    parser.package_map().PopulateFromFolder(model_dir)
    directives_file = model_dir / "add_scoped_top.dmd.yaml"
    directives = drake.multibody.parsing.LoadModelDirectives(path_type(directives_file))
    return plant, parser, directives


def test_load_model_directives_from_string(drake: ModuleType) -> None:
    text = """
directives:
- add_model:
    name: new_model
    file: base.sdf
"""
    directives = drake.multibody.parsing.LoadModelDirectivesFromString(model_directives=text)
    (directive,) = directives.directives
    assert directive.add_model.name == "new_model"
    assert directive.add_model.file == "base.sdf"


def test_flatten_model_directives(drake: ModuleType, drake_models: Path) -> None:
    # N.B. pydrake's Parser does not keep its plant alive: the test holds it.
    _plant_alive, parser, directives = _make_plant_parser_directives(drake, drake_models)
    drake.multibody.parsing.ProcessModelDirectives(directives=directives, parser=parser)
    flat_directives = drake.multibody.parsing.FlattenModelDirectives(
        directives=directives, package_map=parser.package_map()
    )
    assert len(flat_directives.directives) > 0
    assert all(d.add_directives is None for d in flat_directives.directives)


def test_process_model_directives(drake: ModuleType, drake_models: Path) -> None:
    """The ProcessModelDirectives overload that takes a Parser."""
    plant, parser, directives = _make_plant_parser_directives(drake, drake_models)
    added_models = drake.multibody.parsing.ProcessModelDirectives(
        directives=directives, parser=parser
    )
    model_names = [model.model_name for model in added_models]
    assert "extra_model" in model_names
    plant.GetModelInstanceByName("extra_model")


def test_process_model_directives_dispreferred(drake: ModuleType, drake_models: Path) -> None:
    """The overload that also takes the plant, with a str path for LoadModelDirectives."""
    plant, parser, directives = _make_plant_parser_directives(drake, drake_models, path_type=str)
    added_models = drake.multibody.parsing.ProcessModelDirectives(
        directives=directives, plant=plant, parser=parser
    )
    model_names = [model.model_name for model in added_models]
    assert "extra_model" in model_names
    plant.GetModelInstanceByName("extra_model")


@pytest.mark.parametrize(
    ("name", "kwargs", "text"),
    [
        ("AddCollisionFilterGroup", {"name": "foo"}, "foo"),
        ("AddDirectives", {"file": "package://foo/bar.dmd.yaml"}, "bar.dmd.yaml"),
        ("AddFrame", {"name": "foo"}, "foo"),
        ("AddModel", {"file": "package://foo/bar.sdf"}, "bar.sdf"),
        ("AddModelInstance", {"name": "foo"}, "foo"),
        ("AddWeld", {"parent": "foo"}, "foo"),
        ("ModelDirective", {"add_model": None}, "add_model"),
    ],
)
def test_directive_structs(drake: ModuleType, name: str, kwargs: dict[str, Any], text: str) -> None:
    """The bindings of the directive helper structs: keywords, repr, copies."""
    dut = getattr(drake.multibody.parsing, name)(**kwargs)
    assert text in repr(dut)
    copy.copy(dut)
    copy.deepcopy(dut)


def test_model_directives_struct(drake: ModuleType) -> None:
    parsing = drake.multibody.parsing
    dut = parsing.ModelDirectives(directives=[parsing.ModelDirective()])
    assert "add_model" in repr(dut)
    copy.copy(dut)
    copy.deepcopy(dut)
    assert repr(dut) == (
        "ModelDirectives(directives=[ModelDirective(add_model=None, add_model_instance=None, "
        "add_frame=None, add_weld=None, add_collision_filter_group=None, add_directives=None)])"
    )


def test_directive_struct_reprs(drake: ModuleType) -> None:
    """Beyond upstream: the reprs of the default structs (measured on pydrake 1.51.1)."""
    parsing = drake.multibody.parsing
    assert repr(parsing.AddFrame(name="foo")) == (
        "AddFrame(name='foo', X_PF=Transform(base_frame=None, translation=array([0., 0., 0.]), "
        "rotation=Rotation(value=Identity())))"
    )
    assert repr(parsing.AddCollisionFilterGroup(name="foo")) == (
        "AddCollisionFilterGroup(name='foo', members=[], member_groups=[], "
        "model_namespace=None, ignored_collision_filter_groups=[])"
    )
    assert repr(parsing.AddModel(file="package://foo/bar.sdf")) == (
        "AddModel(file='package://foo/bar.sdf', name='', default_joint_positions={}, "
        "default_free_body_pose={})"
    )
    assert repr(parsing.AddWeld(parent="foo")) == "AddWeld(parent='foo', child='', X_PC=None)"
