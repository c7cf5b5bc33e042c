"""The model grammar ``fuzz --models`` draws: every valid scene parses on pydrake as drawn, every
invalid one is refused, the XML quirks are what tinyxml2 makes of them, and the coverage
reads the grammar back from the files."""

from __future__ import annotations

import dataclasses
import logging
from collections.abc import Iterator
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import seed as hypothesis_seed

from conformance._backends.loader import load_backend
from conformance._backends.pydrake_api import pydrake_api
from conformance._backends.scene_graph import CANDIDATES_ERROR, Api, SceneGraphBackend
from conformance._fuzz import models as fm
from conformance._fuzz.model_campaign import model_cases
from conformance._fuzz.model_coverage import (
    MODEL_FEATURES,
    case_features,
    error_category,
    expected_model_features,
)
from conformance._fuzz.model_scenes import (
    MESH_OBJ,
    SCENE_FORMATS,
    Scene,
    model_scenes,
    package_xml,
    scene_faults,
)
from conformance._fuzz.xml_quirks import XML_QUIRKS, detect_quirks
from conformance.protocol import Command, ErrorInfo, ErrorKind, Result, UnknownNameError

PYDRAKE = load_backend("pydrake")
SETTINGS = settings(
    max_examples=25, deadline=None, database=None, suppress_health_check=list(HealthCheck)
)


@pytest.fixture(autouse=True)
def _quiet_drake() -> Iterator[None]:
    logger = logging.getLogger("drake")
    level = logger.level
    logger.setLevel(logging.CRITICAL)
    yield
    logger.setLevel(level)


def parse(scene: Scene, backend: Any = PYDRAKE) -> Result:
    """The scene's add_models step on ``backend`` from a reset."""
    backend.reset()
    args: dict[str, Any] = {"files": dict(scene.files)}
    args |= {"path": scene.path} if scene.path else {"text": scene.text, "format": scene.format}
    return backend.execute(Command("add_models", args))  # type: ignore[no-any-return]


# ------------------------------------------------------------------ scenes
@pytest.mark.parametrize("fmt", SCENE_FORMATS)
def test_every_drawn_valid_scene_parses_and_finalizes_on_pydrake(fmt: str) -> None:
    @hypothesis_seed(1)
    @SETTINGS
    @given(model_scenes(formats=(fmt,)))
    def parses(scene: Scene) -> None:
        assert scene.valid
        assert parse(scene).error is None
        assert PYDRAKE.execute(Command("finalize", {})).error is None

    parses()


@pytest.mark.parametrize("fmt", SCENE_FORMATS)
def test_every_drawn_invalid_scene_is_refused_by_pydrake(fmt: str) -> None:
    @hypothesis_seed(1)
    @SETTINGS
    @given(model_scenes(formats=(fmt,), invalid=True))
    def refused(scene: Scene) -> None:
        assert scene.fault in scene_faults(fmt)
        assert parse(scene).error is not None

    refused()


@pytest.mark.parametrize(
    ("fmt", "fault"), [(f, fault) for f in SCENE_FORMATS for fault in scene_faults(f)]
)
def test_each_fault_of_a_format_is_refused_with_its_error_category(fmt: str, fault: str) -> None:
    """Each fault gives the error its coverage category names (measured on pydrake 1.51.1)."""
    expected = {
        "group": "group",
        "joint_to_unknown_link": "unknown-name",
        "frame_on_unknown_link": "unknown-name",
        "world_link": "reserved-name",
        "world_frame": "reserved-name",
        "negative_damping": "damping",
        "inverted_limits": "limits",
        "two_value_scale": "mesh-scale",
        "frame_cycle": "frame-cycle",
        "include-missing": "missing-file",
        "missing-namespace": "namespace",
        "unknown-weld-frame": "unknown-model-instance",
        "model-twice": "model-name-clash",
        "unknown-member": "unknown-name",
    }
    name = fault.split(":", 1)[-1]
    index = scene_faults(fmt).index(fault)

    @hypothesis_seed(2)
    @settings(SETTINGS, max_examples=5)
    @given(model_scenes(formats=(fmt,), invalid=True, fault_index=index))
    def refused(scene: Scene) -> None:
        result = parse(scene)
        assert result.error is not None
        category = error_category(result.error.message)
        if fault.startswith("xml:"):
            assert category == "xml"
        elif name == "group":
            # A member no model has is an unknown name. A group defined twice in SDFormat
            # is a group error on 1.51.1 ("group 'm::g0' has already been defined") and
            # SDFormat's "Non-unique name[g0] detected 2 times" on 1.58.0 (both measured).
            assert category in ("group", "unknown-name", "element-name-clash"), result.error
        elif name in expected:
            assert category == expected[name], result.error.message
        else:  # model:any, a directives file whose first model has some fault
            assert category != "other", result.error.message

    refused()


def test_a_merged_include_drops_the_included_models_groups() -> None:
    """pydrake 1.51.1 drops the groups of a merge-included model without a word: they are
    not reported, and the including model cannot name them."""
    inner = fm.Model(
        "i0",
        (fm.Body("i0l0", (fm.Geometry("sphere", "c"),)), fm.Body("i0l1")),
        groups=(fm.Group("i0g0", ("i0l0", "i0l1"), ignored=("i0g0",)),),
    )
    include = fm.Include(inner, "package://pkg/i0.sdf", merge=True)
    top = fm.Model("m", (fm.Body("l0"),), includes=(include,))
    files = {"i0.sdf": fm.to_sdf(inner)}
    assert parse(Scene("sdf", fm.to_sdf(top), None, files)).value == ["m"]
    assert PYDRAKE.execute(Command("collision_filter_groups", {})).value == {
        "groups": {},
        "pairs": [],
    }
    referring = dataclasses.replace(top, groups=(fm.Group("g", ("l0",), ("i0g0",)),))
    result = parse(Scene("sdf", fm.to_sdf(referring), None, files))
    assert result.error is not None
    assert result.error.message.endswith("collision filter group with name 'm::i0g0' not found")


def test_a_directory_include_reads_its_model_config_by_package_and_model_uris() -> None:
    inner = fm.Model("i0", (fm.Body("i0l0"),))
    files = {
        "pb/package.xml": package_xml("pb"),
        "pb/i0/model.sdf": fm.to_sdf(inner),
        "pb/i0/model.config": (
            '<?xml version="1.0"?>\n<model><name>i0</name><sdf version="1.9">model.sdf</sdf>'
            "</model>\n"
        ),
    }
    for uri in ("package://pb/i0", "model://pb/i0"):
        top = fm.Model("m", (fm.Body("l0"),), includes=(fm.Include(inner, uri, name="r0"),))
        assert parse(Scene("sdf", fm.to_sdf(top), None, files)).value == ["m", "m::r0"]


def test_a_stl_collision_mesh_leaves_pydrake_unable_to_list_the_candidates_until_1_52() -> None:
    """Why the scenes draw no .stl collision mesh (model_scenes.UNOBSERVED_FAULTS): the
    parse fails in MakeConvexHull, after the geometry got its proximity properties; on
    1.51.1 GetCollisionCandidates then raises IndexError('_Map_base::at'), on 1.58.0 it
    lists the geometry's pair (both measured)."""
    urdf = (
        '<robot name="m"><link name="l0"><collision><geometry><sphere radius="0.1"/>'
        '</geometry></collision></link><link name="lx"><collision name="c0"><geometry>'
        '<mesh filename="package://pkg/meshes/mesh.stl"/></geometry></collision></link></robot>'
    )
    files = {"meshes/mesh.stl": "solid t\nendsolid t\n"}
    result = parse(Scene("urdf", urdf, None, files))
    assert result.error is not None
    assert result.error.message.startswith("MakeConvexHull only applies to .obj, .vtk")
    if PYDRAKE.version() == "1.51.1":
        # The observation records the IndexError as the candidates' answer.
        model = PYDRAKE.observe().locations["model"]
        assert model.counts[CANDIDATES_ERROR] == "error: _Map_base::at"
        assert not model.candidates
    else:
        assert PYDRAKE.observe().locations["model"].candidates


def test_files_in_a_folder_with_a_package_xml_are_a_package_for_every_parser_of_the_case() -> None:
    PYDRAKE.reset()
    urdf = '<robot name="r"><link name="a"/></robot>'
    files = {"pa/package.xml": package_xml("pa"), "pa/r.urdf": urdf}
    first = PYDRAKE.execute(Command("add_models", {"files": files, "path": "pa/r.urdf"}))
    assert first.value == ["r"]
    directives = "directives:\n- add_model:\n    name: r2\n    file: package://pa/r.urdf\n"
    later = PYDRAKE.execute(Command("add_models", {"text": directives, "format": "dmd.yaml"}))
    assert later.value == ["r2"]


def _without_populate(api: Api) -> Api:
    """``api`` whose Parser's package map has no PopulateFromFolder (as reimpl until the
    directives rewrite)."""
    parsing = api.parsing
    assert parsing is not None

    class Narrow:
        def __init__(self, real: Any) -> None:
            self.real = real

        def __getattr__(self, name: str) -> Any:
            if name == "PopulateFromFolder":
                raise AttributeError(name)
            return getattr(self.real, name)

    class Parser(parsing.Parser):  # type: ignore[name-defined,misc]
        def package_map(self) -> Any:
            return Narrow(super().package_map())

    module = type(parsing)("narrow_parsing")
    module.Parser = Parser  # type: ignore[attr-defined]
    return dataclasses.replace(api, name="narrow", parsing=module)


def test_an_implementation_without_populate_from_folder_answers_a_binding_error() -> None:
    narrow = SceneGraphBackend(_without_populate(pydrake_api()))
    narrow.reset()
    files = {"pa/package.xml": package_xml("pa"), "pa/r.urdf": '<robot name="r"/>'}
    result = narrow.execute(Command("add_models", {"files": files, "path": "pa/r.urdf"}))
    assert result.error is not None
    assert result.error.kind is ErrorKind.BINDING
    assert result.error.message.endswith("has no PackageMap.PopulateFromFolder")


# ------------------------------------------------------------------ renaming
GROUPED = (
    '<robot name="r" xmlns:drake="http://drake.mit.edu"><link name="a"><collision>'
    '<geometry><sphere radius="0.1"/></geometry></collision></link><link name="b"><collision>'
    '<geometry><sphere radius="0.1"/></geometry></collision></link>'
    '<drake:collision_filter_group name="g"><drake:member link="a"/><drake:member link="b"/>'
    '<drake:ignored_collision_filter_group name="g"/></drake:collision_filter_group></robot>'
)


def test_a_parser_reused_after_a_rename_reports_both_models_by_their_current_names() -> None:
    """Drake issue #21316 (fixed by 1.51.1): parse, RenameModelInstance, parse again with
    the same Parser; the report names the renamed model anew (measured on pydrake 1.51.1)."""
    PYDRAKE.reset()
    text = {"text": GROUPED, "format": "urdf"}
    assert PYDRAKE.execute(Command("add_models", text)).value == ["r"]
    rename = Command("rename_model_instance", {"model": "r", "name": "r_first"})
    assert PYDRAKE.execute(rename).error is None
    report = PYDRAKE.execute(Command("collision_filter_groups", {})).value
    assert report == {
        "groups": {"r_first::g": ["r_first::a", "r_first::b"]},
        "pairs": [["r_first::g", "r_first::g"]],
    }
    again = PYDRAKE.execute(Command("add_models", {**text, "reuse_parser": True}))
    assert again.value == ["r"]
    assert PYDRAKE.execute(Command("collision_filter_groups", {})).value == {
        "groups": {"r::g": ["r::a", "r::b"], "r_first::g": ["r_first::a", "r_first::b"]},
        "pairs": [["r::g", "r::g"], ["r_first::g", "r_first::g"]],
    }
    # The renamed model's geometries are named anew: Drake renamed them 'r_first::Sphere'.
    assert PYDRAKE.execute(Command("finalize", {})).error is None
    candidates = PYDRAKE.observe().locations["model"].candidates
    assert ("r::a/Sphere", "r_first::a/Sphere") in candidates
    assert ("r::a/Sphere", "r::b/Sphere") not in candidates


def test_reuse_parser_takes_no_prefix_and_needs_an_earlier_parser() -> None:
    PYDRAKE.reset()
    args = {"text": GROUPED, "format": "urdf", "reuse_parser": True}
    with pytest.raises(UnknownNameError):
        PYDRAKE.execute(Command("add_models", args))
    PYDRAKE.execute(Command("add_models", {"text": GROUPED, "format": "urdf"}))
    result = PYDRAKE.execute(Command("add_models", {**args, "prefix": "p"}))
    assert result.error is not None
    assert "reuse_parser takes no prefix" in result.error.message


# ------------------------------------------------------------------ XML quirks
ROBOT = fm.Model(
    "m",
    (fm.Body("l0", (fm.Geometry("sphere", "c"),)), fm.Body("l1")),
    (fm.Joint("j", "revolute", "l0", "l1"),),
)


@pytest.mark.parametrize("fmt", fm.FORMATS)
@pytest.mark.parametrize("name", sorted(XML_QUIRKS))
def test_a_quirk_tinyxml2_accepts_parses_as_the_plain_text_and_another_is_refused(
    fmt: str, name: str
) -> None:
    plain = fm.render(ROBOT, fmt)
    assert detect_quirks(plain) == []
    quirk = XML_QUIRKS[name]
    bent = quirk.apply(plain)
    assert detect_quirks(bent) == [name]
    for path in (None, f"m.{fmt}"):
        files = {path: bent} if path else {}
        result = parse(Scene(fmt, bent, path, files))
        if quirk.accepted:
            assert result.value == ["m"], result
            assert PYDRAKE.execute(Command("model_inventory", {})).value["frames"][-1] == "m::l1"
        else:
            assert result.error is not None
            assert "XML_ERROR" in result.error.message


def test_the_accepted_quirks_combine() -> None:
    for fmt in fm.FORMATS:
        text = fm.render(ROBOT, fmt)
        accepted = [q for q in XML_QUIRKS.values() if q.accepted]
        for quirk in accepted:
            text = quirk.apply(text)
        assert sorted(detect_quirks(text)) == sorted(q.name for q in accepted)
        assert parse(Scene(fmt, text, None)).value == ["m"]


# ------------------------------------------------------------------ coverage
def test_error_categories_name_pydrakes_messages() -> None:
    measured = {
        "<literal-string>.urdf:1: error: Failed to parse XML string: XML_ERROR_PARSING": "xml",
        "error: The supplied link name [world] is reserved.": "reserved-name",
        "Revolute joint damping must be nonnegative.": "damping",
        "Failure at bazel-out/k8-opt/bin/external/drake+/multibody/tree/_virtual_includes/"
        "multibody_tree_core/drake/multibody/tree/joint.h:# in Joint(): condition "
        "'(pos_lower_limits.array() <= pos_upper_limits.array()).all()' failed.": "limits",
        "Expected # values for attribute scale got # #": "mesh-scale",
        "error: FrameAttachedToGraph cycle detected, already visited vertex [m::fx].": (
            "frame-cycle"
        ),
        "Namespace 'nope' does not exist as model instance": "namespace",
        "This model already contains a model instance named 'r1'. Model instance names must "
        "be unique within a given model.": "model-name-clash",
        "GetModelInstanceByName(): There is no model instance named 'zz'.": (
            "unknown-model-instance"
        ),
        "error: collision filter group with name 'nope' not found": "group",
        "error: body with name 'd0::zz' not found": "unknown-name",
        '/m.sdf:5: error: At XML path /sdf/model[@name="m"]/include[#]/uri: Unable to find '
        "uri[package://pkg/i0.sdf_gone]": "missing-file",
    }
    for message, category in measured.items():
        assert error_category(message) == category, message


def test_case_features_are_read_from_the_files_and_the_references_answers() -> None:
    inner = fm.Model("i0", (fm.Body("i0l0", (fm.Geometry("drake:capsule", "c"),)),))
    top = fm.Model(
        "m",
        (fm.Body("l0"), fm.Body("l1")),
        (fm.Joint("j0", "revolute", "l0", "f0"),),
        includes=(fm.Include(inner, "model://pa/i0.sdf", name="r0", merge=True),),
        frames=(fm.Frame("f0", "l1", relative_to="l0"),),
    )
    sdf = {
        "files": {
            "pa/package.xml": package_xml("pa"),
            "pb/package.xml": package_xml("pb"),
            "pa/i0.sdf": fm.to_sdf(inner),
            "meshes/mesh.obj": MESH_OBJ,
        },
        "text": XML_QUIRKS["bom"].apply(fm.to_sdf(top)),
        "format": "sdf",
    }
    directives = (
        "directives:\n- add_model:\n    name: d0\n    file: package://pb/r.urdf\n"
        "- add_weld:\n    parent: world\n    child: d0::a\n"
        "- add_collision_filter_group:\n    name: G\n    model_namespace: d0\n"
        "    members: [a]\n    member_groups: [g]\n"
    )
    commands = [
        Command("add_models", sdf),
        Command("collision_filter_groups", {}),
        Command("rename_model_instance", {"model": "m", "name": "m_old"}),
        Command("add_models", {"text": directives, "format": "dmd.yaml", "reuse_parser": True}),
        Command("finalize", {}),
        Command("model_inventory", {}),
    ]
    results = [
        Result(value=["m"]),
        Result(value={"groups": {"m::g": ["m::l0"]}, "pairs": []}),
        Result(),
        Result(error=ErrorInfo(ErrorKind.OTHER, "Namespace 'x' does not exist as model instance")),
        Result(),
        Result(value={}),
    ]
    reached = case_features(commands, results)
    assert {
        "format:sdf",
        "format:dmd",
        "parse:text",
        "parse:again",
        "parse:reuse_parser",
        "packages>=2",
        "package-across",
        "sdf:include-file",
        "sdf:include-model-uri",
        "sdf:include-name",
        "sdf:merge-include",
        "sdf:frame",
        "sdf:frame-attached_to",
        "sdf:frame-relative_to",
        "sdf:joint-via-frame",
        "sdf:drake:capsule",
        "xml:bom",
        "dmd:add_model",
        "dmd:add_weld",
        "dmd:add_collision_filter_group",
        "dmd:member_groups",
        "dmd:group-model_namespace",
        "rename",
        "rename-then-parse",
        "rename-reuse-parser",
        "report:groups",
        "report:inventory-finalized",
        "error:other",
        "parse-error:namespace",
    } <= reached
    assert not {"xml:malformed", "sdf:include-dir", "dmd:model_namespace"} & reached


def test_expected_features_leave_out_what_without_leaves_out() -> None:
    everything = expected_model_features()
    assert everything == list(MODEL_FEATURES)
    fewer = expected_model_features(["packages", "sdf:frame", "rename-then-parse"])
    assert set(everything) - set(fewer) == {
        "packages>=2",
        "package-across",
        "sdf:frame",
        "sdf:frame-attached_to",
        "sdf:frame-attached_to-nested",
        "sdf:frame-relative_to",
        "sdf:joint-via-frame",
        "rename",
        "rename-then-parse",
        "rename-reuse-parser",
    }
    assert "report:groups" not in expected_model_features(groups_report=False)


def test_cases_drawn_without_elements_hold_none_of_them() -> None:
    without = frozenset({"packages", "sdf:merge-include", "urdf:frame", "rename-then-parse"})
    reached: set[str] = set()

    @hypothesis_seed(1)
    @settings(SETTINGS, max_examples=80)
    @given(model_cases(without=without))
    def draw(commands: list[Command]) -> None:
        reached.update(case_features(commands, [Result()] * len(commands)))

    draw()
    left_out = {"packages>=2", "sdf:merge-include", "urdf:frame", "rename"}
    assert not left_out & reached, left_out & reached
    assert {"format:urdf", "format:sdf", "format:dmd", "sdf:include-file"} <= reached
