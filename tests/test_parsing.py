"""Parser on reimpl and on real pydrake: URDF, SDFormat, model directives and filter groups.

Every test runs on both implementations (the same calls, the imports switched)
and asserts the value measured on pydrake 1.51.1 (drake-semantics.md §6 and
checklist 26-32, pydrake-observed.md §3), never mere agreement. Calls use
pydrake's keyword names.

Setup unless stated: ``AddMultibodyPlantSceneGraph(builder, time_step=0.0)``,
``Parser(plant=plant)`` with package ``test_models`` = tests/models. A
geometry is named ``<model>::<body>/<geometry>``, the geometry's name without
its model prefix; a candidate pair is the two names sorted and joined by
``|``. Candidates are read before Finalize unless a test finalizes.
"""

from __future__ import annotations

import importlib
import itertools
import os
import subprocess
import sys
from dataclasses import dataclass
from importlib.metadata import version
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

from conformance._policy.release_facts import fact_holds
from reimpl._release import release as reimpl_release
from reimpl.common._demand_lines import site_in
from tests.conftest import IMPLEMENTATIONS

MODELS = Path(__file__).parent / "models"
ROOT = Path(__file__).parent.parent


@dataclass(frozen=True)
class Modules:
    """One implementation's modules, named as in pydrake."""

    framework: ModuleType
    plant: ModuleType
    parsing: ModuleType


@pytest.fixture(params=IMPLEMENTATIONS)
def mb(request: pytest.FixtureRequest) -> Modules:
    root = "pydrake" if request.param == "pydrake" else "reimpl"
    names = ("systems.framework", "multibody.plant", "multibody.parsing")
    return Modules(*(importlib.import_module(f"{root}.{name}") for name in names))


def followed_release(mb: Modules) -> str:
    """The Drake release ``mb`` behaves as: reimpl's (``REIMPL_DRAKE_RELEASE``, which
    tests/conftest.py sets to the installed pydrake's unless set), or the installed pydrake's."""
    reimpl = mb.plant.__name__.startswith("reimpl")
    return reimpl_release.version if reimpl else version("drake")


def holds(mb: Modules, fact_id: str) -> bool:
    """Whether the release fact ``fact_id`` (conformance/_policy/release_facts.json) holds
    for the release ``mb`` behaves as."""
    return fact_holds(fact_id, followed_release(mb))


def demand_message(mb: Modules, demand: str) -> str:
    """The SystemExit text of the failed DRAKE_DEMAND ``demand`` (an id of
    reimpl/common/demand_lines.json) in the release ``mb`` behaves as: its file and line as
    tools/measure_demand_lines.py measured them on that release, as the lines move between
    releases."""
    path, line, function, condition = site_in(demand, followed_release(mb))
    return f"Failure at {path}:{line} in {function}(): condition '{condition}' failed."


class Parsed:
    """A plant and SceneGraph filled by one Parser, read back by name."""

    def __init__(self, mb: Modules, *, scene_graph: bool = True) -> None:
        self.builder = mb.framework.DiagramBuilder()
        if scene_graph:
            self.plant, self.scene_graph = mb.plant.AddMultibodyPlantSceneGraph(
                builder=self.builder, time_step=0.0
            )
        else:
            self.plant, self.scene_graph = mb.plant.MultibodyPlant(time_step=0.0), None
        self.parser = mb.parsing.Parser(plant=self.plant)
        self.parser.package_map().Add(package_name="test_models", package_path=str(MODELS))

    def add(self, text: str, file_type: str) -> list[str]:
        instances = self.parser.AddModelsFromString(file_contents=text, file_type=file_type)
        return [self.plant.GetModelInstanceName(i) for i in instances]

    def name(self, geometry_id: Any) -> str:
        inspector = self.scene_graph.model_inspector()
        body = self.plant.GetBodyFromFrameId(inspector.GetFrameId(geometry_id))
        model = self.plant.GetModelInstanceName(body.model_instance())
        local = inspector.GetName(geometry_id).removeprefix(f"{model}::")
        return f"{model}::{body.name()}/{local}"

    def geometries(self) -> set[str]:
        return {self.name(g) for g in self.scene_graph.model_inspector().GetAllGeometryIds()}

    def candidates(self) -> set[str]:
        pairs = self.scene_graph.model_inspector().GetCollisionCandidates()
        return {"|".join(sorted((self.name(a), self.name(b)))) for a, b in pairs}

    def bodies(self) -> set[str]:
        """``<model>::<body>`` of every body but the world."""
        plant = self.plant
        body_index = type(plant.world_body().index())  # BodyIndex, of this implementation
        bodies = (plant.get_body(body_index(i)) for i in range(1, plant.num_bodies()))
        return {f"{plant.GetModelInstanceName(b.model_instance())}::{b.name()}" for b in bodies}

    def joints(self) -> set[str]:
        """``<joint>:<type>:<parent>-><child>`` of every joint."""
        joints = (self.plant.get_joint(j) for j in self.plant.GetJointIndices())
        return {
            f"{j.name()}:{j.type_name()}:{j.parent_body().name()}->{j.child_body().name()}"
            for j in joints
        }

    def report(self) -> tuple[dict[str, set[str]], set[tuple[str, str]]]:
        groups = self.parser.GetCollisionFilterGroups()
        return groups.groups(), groups.exclusion_pairs()


def pairs(*names: str) -> set[str]:
    """``pairs("a", "b", "c")`` is every pair among the names."""
    return {"|".join(sorted(p)) for p in itertools.combinations(names, 2)}


def pair(a: str, b: str) -> str:
    return "|".join(sorted((a, b)))


# ------------------------------------------------------------------ URDF groups

DRAKE_NS = 'xmlns:drake="http://drake.mit.edu"'


def robot(body: str, *, name: str = "r", links: str = "abcd") -> str:
    """URDF robot ``name`` with free links (one unnamed sphere each), then ``body``."""
    link_text = "".join(
        f'<link name="{link}"><collision><geometry><sphere radius="0.1"/></geometry>'
        "</collision></link>\n"
        for link in links
    )
    return f'<robot name="{name}" {DRAKE_NS}>\n{link_text}{body}</robot>\n'


def group(name: str, *children: str, attributes: str = "") -> str:
    return (
        f'<drake:collision_filter_group name="{name}"{attributes}>\n'
        + "".join(f"{child}\n" for child in children)
        + "</drake:collision_filter_group>\n"
    )


def member(link: str) -> str:
    return f'<drake:member link="{link}"/>'


def member_group(name: str) -> str:
    return f'<drake:member_group name="{name}"/>'


def ignores(name: str) -> str:
    return f'<drake:ignored_collision_filter_group name="{name}"/>'


A, B, C, D = (f"r::{x}/Sphere" for x in "abcd")
ALL_ABCD = pairs(A, B, C, D)


def test_group_ignoring_itself_and_a_second_group_filters_its_members_and_the_second(
    mb: Modules,
) -> None:
    """Checklist 26: g1={a,b} ignores g1 and g2={c}: ab, ac, bc filtered."""
    parsed = Parsed(mb)
    text = robot(
        group("g1", member("a"), member("b"), ignores("g1"), ignores("g2"))
        + group("g2", member("c"))
    )
    assert parsed.add(text, "urdf") == ["r"]
    assert parsed.candidates() == {pair(A, D), pair(B, D), pair(C, D)}
    assert parsed.report() == (
        {"r::g1": {"r::a", "r::b"}, "r::g2": {"r::c"}},
        {("r::g1", "r::g1"), ("r::g1", "r::g2")},
    )


@pytest.mark.parametrize(
    ("ignore", "applied"),
    [("true", False), ("1", True), ("True", True), ("false", True)],
)
def test_urdf_group_is_dropped_only_when_ignore_is_exactly_true(
    mb: Modules, ignore: str, applied: bool
) -> None:
    """Checklist 27: only ignore="true" drops the group (and its report entry)."""
    parsed = Parsed(mb)
    attributes = f' ignore="{ignore}"'
    parsed.add(
        robot(group("g", member("a"), member("b"), ignores("g"), attributes=attributes)), "urdf"
    )
    if applied:
        assert parsed.candidates() == ALL_ABCD - {pair(A, B)}
        assert parsed.report() == ({"r::g": {"r::a", "r::b"}}, {("r::g", "r::g")})
    else:
        assert parsed.candidates() == ALL_ABCD
        assert parsed.report() == ({}, set())


def test_unprefixed_urdf_collision_filter_group_is_silently_ignored(mb: Modules) -> None:
    """Checklist 28: the RigidBodyTree syntax: no filter, no error, no report."""
    parsed = Parsed(mb)
    old = (
        '<collision_filter_group name="g"><member link="a"/><member link="b"/>'
        '<ignored_collision_filter_group collision_filter_group="g"/>'
        "</collision_filter_group>\n"
    )
    parsed.add(robot(old), "urdf")
    assert parsed.candidates() == ALL_ABCD
    assert parsed.report() == ({}, set())


def test_member_groups_are_transitive(mb: Modules) -> None:
    """Checklist 30: g1={a}, g2={b}+g1, g3={c}+g2 ignoring g3: ab, ac, bc filtered."""
    parsed = Parsed(mb)
    text = robot(
        group("g1", member("a"))
        + group("g2", member("b"), member_group("g1"))
        + group("g3", member("c"), member_group("g2"), ignores("g3"))
    )
    parsed.add(text, "urdf")
    assert parsed.candidates() == {pair(A, D), pair(B, D), pair(C, D)}
    assert parsed.report() == (
        {"r::g1": {"r::a"}, "r::g2": {"r::a", "r::b"}, "r::g3": {"r::a", "r::b", "r::c"}},
        {("r::g3", "r::g3")},
    )


def test_a_cycle_of_member_groups_gives_each_group_the_union(mb: Modules) -> None:
    """Checklist 30: g1 → g3 → g2 → g1; g4={d}+itself ignores g1: a, b, c each vs d."""
    parsed = Parsed(mb)
    text = robot(
        group("g1", member("a"), member_group("g3"))
        + group("g2", member("b"), member_group("g1"))
        + group("g3", member("c"), member_group("g2"))
        + group("g4", member("d"), member_group("g4"), ignores("g1"))
    )
    parsed.add(text, "urdf")
    assert parsed.candidates() == pairs(A, B, C)
    abc = {"r::a", "r::b", "r::c"}
    assert parsed.report() == (
        {"r::g1": abc, "r::g2": abc, "r::g3": abc, "r::g4": {"r::d"}},
        {("r::g1", "r::g4")},
    )


# pydrake-observed.md §3: model "m" with free links l1..l4, one sphere each.
L1, L2, L3, L4 = (f"m::l{i}/Sphere" for i in range(1, 5))
SECTION_3_ROWS = {
    "no groups": ("", pairs(L1, L2, L3, L4)),
    "a group ignoring itself": (
        group("g", member("l1"), member("l2"), member("l3"), ignores("g")),
        {pair(L1, L4), pair(L2, L4), pair(L3, L4)},
    ),
    "a group alone does nothing": (
        group("g", member("l1"), member("l2"), member("l3")),
        pairs(L1, L2, L3, L4),
    ),
    "ga ignores gb": (
        group("ga", member("l1"), member("l2"), ignores("gb"))
        + group("gb", member("l3"), member("l4")),
        {pair(L1, L2), pair(L3, L4)},
    ),
    "overlapping groups": (
        group("ga", member("l1"), member("l2"), ignores("gb"))
        + group("gb", member("l2"), member("l3")),
        {pair(L1, L4), pair(L2, L4), pair(L3, L4)},
    ),
    "nested member group": (
        group("inner", member("l1"), member("l2"))
        + group("outer", member_group("inner"), member("l3"), ignores("outer")),
        {pair(L1, L4), pair(L2, L4), pair(L3, L4)},
    ),
    "ignore=true drops the group": (
        group("g", member("l1"), member("l2"), ignores("g"), attributes=' ignore="true"'),
        pairs(L1, L2, L3, L4),
    ),
    "an unknown child element is ignored": (
        group("g", member("l1"), "<drake:foo/>", member("l2"), ignores("g")),
        pairs(L1, L2, L3, L4) - {pair(L1, L2)},
    ),
}


@pytest.mark.parametrize("row", SECTION_3_ROWS)
def test_section_3_group_table(mb: Modules, row: str) -> None:
    body, expected = SECTION_3_ROWS[row]
    parsed = Parsed(mb)
    parsed.add(robot(body, name="m", links=("l1", "l2", "l3", "l4")), "urdf")  # type: ignore[arg-type]
    assert parsed.candidates() == expected


def test_groups_of_two_prefixed_instances_apply_per_instance(mb: Modules) -> None:
    """§3: Parser(plant, 'left'/'right'): names 'left::m::g'; no cross-instance filter."""
    parsed = Parsed(mb)
    text = robot(group("g", member("a"), member("b"), ignores("g")), name="m", links="ab")
    names = []
    for prefix in ("left", "right"):
        parser = mb.parsing.Parser(plant=parsed.plant, model_name_prefix=prefix)
        names += [
            parsed.plant.GetModelInstanceName(i) for i in parser.AddModelsFromString(text, "urdf")
        ]
        assert parser.GetCollisionFilterGroups().groups() == {
            f"{prefix}::m::g": {f"{prefix}::m::a", f"{prefix}::m::b"}
        }
    assert names == ["left::m", "right::m"]
    left = [f"left::m::{x}/Sphere" for x in "ab"]
    right = [f"right::m::{x}/Sphere" for x in "ab"]
    assert parsed.candidates() == {pair(x, y) for x in left for y in right}


def test_urdf_groups_are_skipped_without_a_scene_graph(mb: Modules) -> None:
    """No SceneGraph: groups are not read at all, so even an unknown link is no error."""
    parsed = Parsed(mb, scene_graph=False)
    parsed.add(robot(group("g", member("zz"), ignores("nope"))), "urdf")
    assert parsed.parser.GetCollisionFilterGroups().empty()


def test_filter_groups_report_accumulates_successful_parses(mb: Modules) -> None:
    parsed = Parsed(mb)
    for name in ("x", "y"):
        parsed.add(robot(group("g", member("a"), ignores("g")), name=name, links="a"), "urdf")
    with pytest.raises(RuntimeError):
        parsed.add(robot(group("g", member("zz")), name="z", links="a"), "urdf")
    assert parsed.report() == (
        {"x::g": {"x::a"}, "y::g": {"y::a"}},
        {("x::g", "x::g"), ("y::g", "y::g")},
    )


# ------------------------------------------------------------------ URDF errors

URDF_GROUP_ERRORS = {
    "unknown link": (
        group("g1", member("zz")),
        "<literal-string>.urdf:1: error: body with name 'r::zz' not found",
    ),
    "unknown ignored group": (
        group("g1", member("a"), ignores("nope")),
        "error: collision filter group with name 'r::nope' not found",
    ),
    "unknown member group": (
        group("g1", member("a"), member_group("zz")),
        "error: collision filter group with name 'r::zz' not found",
    ),
    "no members": (
        group("g1", ignores("g1")),
        "<literal-string>.urdf:1: error: group 'r::g1' has no members",
    ),
    "defined twice": (
        group("g1", member("a")) + group("g1", member("b")),
        "<literal-string>.urdf:1: error: group 'r::g1' has already been defined",
    ),
    "scoped group name": (
        group("x::g1", member("a")),
        "<literal-string>.urdf:1: error: group name 'r::x::g1' cannot be a scoped name",
    ),
    "a scoped link is read inside the robot": (
        group("g1", member("r::a")),
        "<literal-string>.urdf:1: error: body with name 'r::r::a' not found",
    ),
    "the world is no member": (
        group("g1", member("world")),
        "<literal-string>.urdf:1: error: body with name 'r::world' not found",
    ),
    "unknown links are reported in sorted order": (
        group("g1", member("zz"), member("yy")),
        "<literal-string>.urdf:1: error: body with name 'r::yy' not found",
    ),
    "member groups are checked before pairs": (
        group("g1", member("a"), member_group("m1"), ignores("m0")),
        "error: collision filter group with name 'r::m1' not found",
    ),
    "group without name": (
        '<drake:collision_filter_group>\n<drake:member link="a"/>\n'
        "</drake:collision_filter_group>\n",
        "<literal-string>.urdf:6: error: The tag <drake:collision_filter_group> does not "
        'specify the required attribute "name".',
    ),
    "member without link": (
        group("g1", "<drake:member/>"),
        "<literal-string>.urdf:7: error: The tag <drake:member> does not specify the required "
        'attribute "link".',
    ),
    "ignored group without name": (
        group("g1", member("a"), "<drake:ignored_collision_filter_group/>"),
        "<literal-string>.urdf:8: error: The tag <drake:ignored_collision_filter_group> does "
        'not specify the required attribute "name".',
    ),
}


@pytest.mark.parametrize("case", URDF_GROUP_ERRORS)
def test_urdf_group_error_message(mb: Modules, case: str) -> None:
    """Checklist 29: Drake's messages, byte for byte (the robot tag is on line 1)."""
    body, message = URDF_GROUP_ERRORS[case]
    with pytest.raises(RuntimeError) as info:
        Parsed(mb).add(robot(body), "urdf")
    assert str(info.value) == message


def test_pairs_sorted_before_an_unknown_group_are_applied_when_it_raises(mb: Modules) -> None:
    """(r::g1, r::g1) sorts before (r::g1, r::nope): a-b is filtered, then the error."""
    parsed = Parsed(mb)
    with pytest.raises(RuntimeError, match="'r::nope' not found"):
        parsed.add(
            robot(group("g1", member("a"), member("b"), ignores("g1"), ignores("nope"))), "urdf"
        )
    assert parsed.candidates() == ALL_ABCD - {pair(A, B)}
    assert parsed.report() == ({}, set())


def test_an_unknown_member_group_stops_before_any_pair_is_applied(mb: Modules) -> None:
    parsed = Parsed(mb)
    text = robot(
        group("g1", member("a"), member("b"), ignores("g1"))
        + group("h", member("c"), member_group("zz"))
    )
    with pytest.raises(RuntimeError, match="'r::zz' not found"):
        parsed.add(text, "urdf")
    assert parsed.candidates() == ALL_ABCD


def test_urdf_groups_are_read_before_joints_so_a_group_error_leaves_no_joint(
    mb: Modules,
) -> None:
    """Measured: the group error wins over a bad joint, and l0-l1 stays unjoined."""
    parsed = Parsed(mb)
    joint = '<joint name="j" type="weird"><parent link="a"/><child link="b"/></joint>\n'
    with pytest.raises(RuntimeError, match="body with name 'r::zz' not found"):
        parsed.add(robot(joint + group("g", member("zz"))), "urdf")
    assert parsed.plant.num_joints() == 0


def test_group_errors_carry_the_robot_line(mb: Modules) -> None:
    text = "<?xml version='1.0'?>\n<!-- model -->\n" + robot(group("g1", member("zz")))
    with pytest.raises(RuntimeError, match=r"^<literal-string>\.urdf:3: error: body with name"):
        Parsed(mb).add(text, "urdf")


def test_parse_scope_rule_rejects_bodies_of_earlier_parses(mb: Modules) -> None:
    """A group may name only bodies of model instances made by the same parse."""
    parsed = Parsed(mb)
    inner = '<sdf version="1.9"><model name="x"><link name="a"/></model></sdf>'
    mb.parsing.Parser(plant=parsed.plant, model_name_prefix="r").AddModelsFromString(inner, "sdf")
    with pytest.raises(RuntimeError) as info:
        parsed.add(robot(group("g", member("x::a")), links="b"), "urdf")
    assert str(info.value) == (
        "<literal-string>.urdf:1: error: body name 'r::x::a' refers to a model outside the "
        "current parse"
    )


URDF_MODEL_ERRORS = {
    "robot without name": (
        '<robot>\n<link name="a"/>\n</robot>',
        "<literal-string>.urdf:1: error: Your robot must have a name attribute or a model name "
        "must be specified.",
    ),
    "link without name": (
        '<robot name="m">\n<link/>\n</robot>',
        "<literal-string>.urdf:2: error: link tag is missing name attribute.",
    ),
    "duplicate link": (
        '<robot name="m">\n<link name="a"/>\n<link name="a"/>\n</robot>',
        "Model instance 'm' already contains a body named 'a'. Body names must be unique "
        "within a given model.",
    ),
    "joint without name": (
        '<robot name="m">\n<link name="a"/><link name="b"/>\n'
        '<joint type="fixed"><parent link="a"/><child link="b"/></joint>\n</robot>',
        "<literal-string>.urdf:3: error: joint tag is missing name attribute",
    ),
    "joint to an unknown link": (
        '<robot name="m">\n<link name="b"/>\n'
        '<joint name="j" type="fixed"><parent link="zz"/><child link="b"/></joint>\n</robot>',
        "<literal-string>.urdf:1: error: Could not find link named 'zz' with model instance ID "
        "2 for element 'j'.",
    ),
    "unknown joint type": (
        '<robot name="m">\n<link name="a"/><link name="b"/>\n'
        '<joint name="j" type="weird"><parent link="a"/><child link="b"/></joint>\n</robot>',
        "<literal-string>.urdf:3: error: Joint 'j' has unrecognized type: 'weird'",
    ),
    "ball is a drake:joint": (
        '<robot name="m">\n<link name="a"/><link name="b"/>\n'
        '<joint name="j" type="ball"><parent link="a"/><child link="b"/></joint>\n</robot>',
        "<literal-string>.urdf:3: error: Joint j of type ball is a custom joint type, and should "
        "be a <drake:joint>",
    ),
    "sphere without radius": (
        '<robot name="m">\n<link name="a">\n<collision><geometry>\n<sphere/>\n</geometry>'
        "</collision>\n</link>\n</robot>",
        "<literal-string>.urdf:4: error: Missing sphere attribute: radius",
    ),
    "not a robot": (
        '<model name="m"/>',
        "<literal-string>.urdf:1: error: URDF does not contain a robot tag.",
    ),
    "malformed XML": (
        '<robot name="m">\n<link name="a">\n</robot>',
        "<literal-string>.urdf:1: error: Failed to parse XML string: XML_ERROR_MISMATCHED_ELEMENT",
    ),
}


@pytest.mark.parametrize("case", URDF_MODEL_ERRORS)
def test_urdf_model_error_message(mb: Modules, case: str) -> None:
    text, message = URDF_MODEL_ERRORS[case]
    with pytest.raises(RuntimeError) as info:
        Parsed(mb).add(text, "urdf")
    assert str(info.value) == message


def test_duplicate_model_name_is_an_error_unless_auto_renaming(mb: Modules) -> None:
    parsed = Parsed(mb)
    text = robot("", name="m", links="a")
    assert parsed.add(text, "urdf") == ["m"]
    with pytest.raises(RuntimeError) as info:
        parsed.add(text, "urdf")
    assert str(info.value) == (
        "This model already contains a model instance named 'm'. Model instance names must be "
        "unique within a given model."
    )
    parsed.parser.SetAutoRenaming(True)
    assert parsed.parser.GetAutoRenaming()
    assert parsed.add(text, "urdf") == ["m_1"]
    assert parsed.add(text, "urdf") == ["m_2"]


# ------------------------------------------------------- URDF names and joints


def test_unnamed_urdf_geometry_is_named_after_its_shape_per_link_and_role(mb: Modules) -> None:
    """Measured: ``Sphere``, ``Sphere_1``, ... per link and role; visuals count apart."""
    parsed = Parsed(mb)
    sphere = '<geometry><sphere radius="0.1"/></geometry>'
    text = (
        '<robot name="m" xmlns:drake="http://drake.mit.edu">\n<link name="l1">\n'
        + f"<collision>{sphere}</collision>\n" * 2
        + '<collision name="Sphere_2">'
        + sphere
        + "</collision>\n"
        + f"<collision>{sphere}</collision>\n"
        + '<collision><geometry><box size="1 1 1"/></geometry></collision>\n'
        + '<collision><geometry><cylinder radius="1" length="2"/></geometry></collision>\n'
        + '<collision><geometry><capsule radius="1" length="2"/></geometry></collision>\n'
        + '<collision><geometry><drake:ellipsoid a="1" b="2" c="3"/></geometry></collision>\n'
        + f"<visual>{sphere}</visual>\n"
        + "</link>\n"
        + f'<link name="l2"><collision>{sphere}</collision></link>\n'
        + "</robot>"
    )
    parsed.add(text, "urdf")
    inspector = parsed.scene_graph.model_inspector()
    visuals = [
        g for g in inspector.GetAllGeometryIds() if inspector.GetProximityProperties(g) is None
    ]
    assert [parsed.name(g) for g in visuals] == ["m::l1/Sphere"]
    assert parsed.geometries() == {
        "m::l1/Sphere",
        "m::l1/Sphere_1",
        "m::l1/Sphere_2",
        "m::l1/Sphere_3",
        "m::l1/Box",
        "m::l1/Cylinder",
        "m::l1/Capsule",
        "m::l1/Ellipsoid",
        "m::l2/Sphere",
    }


def test_a_repeated_explicit_urdf_name_is_renamed(mb: Modules) -> None:
    parsed = Parsed(mb)
    sphere = '<geometry><sphere radius="0.1"/></geometry>'
    parsed.add(
        f'<robot name="m"><link name="a"><collision name="x">{sphere}</collision>'
        f'<collision name="x">{sphere}</collision></link></robot>',
        "urdf",
    )
    assert parsed.geometries() == {"m::a/x", "m::a/x_1"}


def test_urdf_joint_types_and_names(mb: Modules) -> None:
    """fixed → weld, continuous → revolute, floating → no joint (the body stays free)."""
    parsed = Parsed(mb)
    text = (
        '<robot name="m" xmlns:drake="http://drake.mit.edu">\n'
        + "".join(f'<link name="{x}"/>' for x in "abcdefghi")
        + '\n<joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>'
        '<joint name="j2" type="revolute"><parent link="a"/><child link="c"/></joint>'
        '<joint name="j3" type="continuous"><parent link="a"/><child link="d"/></joint>'
        '<joint name="j4" type="prismatic"><parent link="a"/><child link="e"/></joint>'
        '<joint name="j5" type="floating"><parent link="a"/><child link="f"/></joint>'
        '<joint name="j6" type="planar"><parent link="a"/><child link="g"/></joint>'
        '<drake:joint name="j7" type="ball"><parent link="a"/><child link="h"/></drake:joint>'
        '<drake:joint name="j8" type="universal"><parent link="a"/><child link="i"/>'
        "</drake:joint>\n</robot>"
    )
    parsed.add(text, "urdf")
    plant = parsed.plant
    joints = {
        (plant.get_joint(j).name(), plant.get_joint(j).type_name()) for j in plant.GetJointIndices()
    }
    assert joints == {
        ("j1", "weld"),
        ("j2", "revolute"),
        ("j3", "revolute"),
        ("j4", "prismatic"),
        ("j6", "planar"),
        ("j7", "ball_rpy"),
        ("j8", "universal"),
    }
    # The weld j1 has no <origin>: up to 1.54 it gets a frame j1_parent, since 1.55 it uses
    # link a's frame (measured on 1.51.1, 1.54.0: made; 1.55.0, 1.57.0, 1.58.0: not made).
    elided = holds(mb, "urdf-identity-joint-frame-elided-since-1.55")
    assert plant.HasFrameNamed("j1_parent") is not elided
    assert plant.HasFrameNamed("j6_child")


def test_urdf_joints_filter_adjacent_links_at_finalize(mb: Modules) -> None:
    """§3: revolute l1->l2 filters l1-l2; a fixed chain l1->l2->l3 filters all three."""
    parsed = Parsed(mb)
    joints = (
        '<joint name="j" type="revolute"><parent link="l1"/><child link="l2"/></joint>\n'
        '<joint name="k" type="fixed"><parent link="l3"/><child link="l4"/></joint>\n'
    )
    parsed.add(robot(joints, name="m", links=("l1", "l2", "l3", "l4")), "urdf")  # type: ignore[arg-type]
    parsed.plant.Finalize()
    assert parsed.candidates() == pairs(L1, L2, L3, L4) - {pair(L1, L2), pair(L3, L4)}


# ---------------------------------------------- URDF drake_ignore, names, axes


def sphere_link(name: str, attributes: str = "") -> str:
    return (
        f'<link name="{name}"{attributes}><collision><geometry><sphere radius="0.1"/>'
        "</geometry></collision></link>\n"
    )


def joint(name: str, parent: str, child: str, kind: str = "revolute", inner: str = "") -> str:
    tag = "drake:joint" if kind in ("ball", "universal", "screw") else "joint"
    return (
        f'<{tag} name="{name}" type="{kind}">{inner}<parent link="{parent}"/>'
        f'<child link="{child}"/></{tag}>\n'
    )


def urdf(*elements: str) -> str:
    return f'<robot name="r" {DRAKE_NS}>\n' + "".join(elements) + "</robot>\n"


# Measured on pydrake 1.51.1: only the exact value "true" counts.
DRAKE_IGNORE_VALUES = [
    ("true", True),
    ("1", False),
    ("True", False),
    ("TRUE", False),
    (" true", False),
    ("false", False),
    ("", False),
]


@pytest.mark.parametrize(("value", "ignored"), DRAKE_IGNORE_VALUES)
def test_drake_ignore_drops_a_link_only_when_exactly_true(
    mb: Modules, value: str, ignored: bool
) -> None:
    """An ignored link leaves no body and no geometry, hence no candidate pair."""
    parsed = Parsed(mb)
    parsed.add(
        urdf(sphere_link("a"), sphere_link("b", f' drake_ignore="{value}"'), sphere_link("c")),
        "urdf",
    )
    a, b, c = (f"r::{x}/Sphere" for x in "abc")
    if ignored:
        assert parsed.bodies() == {"r::a", "r::c"}
        assert parsed.candidates() == {pair(a, c)}
    else:
        assert parsed.bodies() == {"r::a", "r::b", "r::c"}
        assert parsed.candidates() == pairs(a, b, c)


@pytest.mark.parametrize(("value", "ignored"), DRAKE_IGNORE_VALUES)
def test_drake_ignore_drops_a_joint_or_drake_joint_only_when_exactly_true(
    mb: Modules, value: str, ignored: bool
) -> None:
    parsed = Parsed(mb)
    attribute = f'drake_ignore="{value}" '
    text = urdf(
        *(sphere_link(x) for x in "abc"),
        joint("j", "a", "b").replace("<joint ", f"<joint {attribute}"),
        joint("k", "a", "c", "ball").replace("<drake:joint ", f"<drake:joint {attribute}"),
    )
    parsed.add(text, "urdf")
    assert parsed.bodies() == {"r::a", "r::b", "r::c"}
    assert parsed.joints() == (set() if ignored else {"j:revolute:a->b", "k:ball_rpy:a->c"})
    # j has no <origin>: since 1.55 it makes no j_parent frame even when kept (release fact
    # urdf-identity-joint-frame-elided-since-1.55; measured on 1.51.1, 1.54.0 and 1.55.0).
    elided = holds(mb, "urdf-identity-joint-frame-elided-since-1.55")
    assert parsed.plant.HasFrameNamed("j_parent") is not (ignored or elided)


def test_ignored_links_and_joints_are_not_read(mb: Modules) -> None:
    """Measured: no name, a bad shape, a taken name, a bad type or an unknown link in an
    ignored element is no error; the rest of the robot is parsed."""
    parsed = Parsed(mb)
    ignore = ' drake_ignore="true"'
    text = urdf(
        f"<link{ignore}/>\n",
        f'<link name="x"{ignore}><collision><geometry><bogus/></geometry></collision></link>\n',
        sphere_link("a"),
        sphere_link("a", ignore),
        sphere_link("b"),
        f'<joint type="revolute"{ignore}><parent link="a"/><child link="b"/></joint>\n',
        f'<joint name="j" type="bogus"{ignore}><parent link="a"/><child link="b"/></joint>\n',
        f'<joint name="k" type="fixed"{ignore}><parent link="a"/><child link="zz"/></joint>\n',
        joint("m", "a", "b", "fixed"),
    )
    parsed.add(text, "urdf")
    assert parsed.bodies() == {"r::a", "r::b"}
    assert parsed.joints() == {"m:weld:a->b"}


def test_an_ignored_world_link_registers_no_world_geometry(mb: Modules) -> None:
    parsed = Parsed(mb)
    text = urdf(
        sphere_link("world", ' drake_ignore="true"'),
        sphere_link("a"),
        sphere_link("b"),
        joint("j", "world", "a", "fixed"),
    )
    parsed.add(text, "urdf")
    assert parsed.bodies() == {"r::a", "r::b"}
    assert parsed.joints() == {"j:weld:world->a"}
    assert parsed.geometries() == {"r::a/Sphere", "r::b/Sphere"}
    assert parsed.candidates() == {pair("r::a/Sphere", "r::b/Sphere")}


IGNORED_LINK_ERRORS = {
    # Measured: a joint (of any type, floating too) or a filter group naming an ignored
    # link fails as for a link never written; the joint is not dropped with the link.
    "revolute child": joint("j", "a", "b"),
    "revolute parent": joint("j", "b", "a"),
    "floating": joint("j", "a", "b", "floating"),
    "drake:joint": joint("j", "a", "b", "ball"),
    "group member": group("g", member("a"), member("b"), ignores("g")),
}


@pytest.mark.parametrize("case", IGNORED_LINK_ERRORS)
def test_naming_an_ignored_link_is_an_error(mb: Modules, case: str) -> None:
    parsed = Parsed(mb)
    text = urdf(
        sphere_link("a"), sphere_link("b", ' drake_ignore="true"'), IGNORED_LINK_ERRORS[case]
    )
    with pytest.raises(RuntimeError) as info:
        parsed.add(text, "urdf")
    if case == "group member":
        assert str(info.value) == "<literal-string>.urdf:1: error: body with name 'r::b' not found"
    else:
        assert str(info.value) == (
            "<literal-string>.urdf:1: error: Could not find link named 'b' with model instance "
            "ID 2 for element 'j'."
        )
    assert parsed.joints() == set()


def test_a_joint_with_an_empty_name_is_skipped_unread(mb: Modules) -> None:
    """Measured: no joint, no ``_parent`` frame, no error (even for a bad type or an
    unknown link) and no warning; a name of one space is a name."""
    parsed = Parsed(mb)
    text = urdf(
        *(sphere_link(x) for x in "abc"),
        joint("", "a", "b"),
        joint("", "a", "b", "fixed"),
        joint("", "a", "zz"),
        joint("", "a", "b", "bogus"),
        joint("", "a", "c", "ball"),
        joint(" ", "b", "c", "prismatic"),
    )
    parsed.add(text, "urdf")
    assert parsed.joints() == {" :prismatic:b->c"}
    assert not parsed.plant.HasFrameNamed("_parent")


@pytest.mark.parametrize(
    # screw: before its missing <drake:screw_thread_pitch> is noticed.
    "kind",
    ["revolute", "continuous", "prismatic", "planar", "universal", "screw"],
)
def test_a_zero_axis_is_an_error_at_the_axis_line(mb: Modules, kind: str) -> None:
    text = urdf(
        sphere_link("a"), sphere_link("b"), joint("j", "a", "b", kind, '\n<axis xyz="0 0 0"/>')
    )
    with pytest.raises(RuntimeError) as info:
        Parsed(mb).add(text, "urdf")
    assert str(info.value) == (
        "<literal-string>.urdf:5: error: Joint 'j' axis is zero.  Don't do that."
    )


def test_an_axis_is_zero_below_norm_1e_8_and_unchecked_for_weld_ball_and_floating(
    mb: Modules,
) -> None:
    parsed = Parsed(mb)
    zero, small = '<axis xyz="0 0 0"/>', '<axis xyz="0 0 1e-8"/>'
    text = urdf(
        *(sphere_link(x) for x in "abcde"),
        joint("j1", "a", "b", "fixed", zero),
        joint("j2", "a", "c", "floating", zero),
        joint("j3", "a", "d", "ball", zero),
        joint("j4", "a", "e", "revolute", small),
    )
    parsed.add(text, "urdf")
    assert parsed.joints() == {"j1:weld:a->b", "j3:ball_rpy:a->d", "j4:revolute:a->e"}
    tiny = urdf(
        sphere_link("a"),
        sphere_link("b"),
        joint("j", "a", "b", "revolute", '<axis xyz="5e-9 5e-9 5e-9"/>'),
    )
    with pytest.raises(RuntimeError, match="axis is zero"):
        Parsed(mb).add(tiny, "urdf")


def test_an_empty_model_instance_name_ends_the_program(mb: Modules) -> None:
    """pydrake 1.51.1's DRAKE_DEMAND in ModelInstance::set_name, raised (measured) as
    SystemExit by AddModelInstance, RenameModelInstance and ``<robot name="">``."""
    parsed = Parsed(mb)
    empty_name = demand_message(mb, "ModelInstance.set_name")  # model_instance.cc:23
    with pytest.raises(SystemExit) as info:
        parsed.add(robot("", name=""), "urdf")
    assert str(info.value) == empty_name
    assert parsed.bodies() == set()
    with pytest.raises(SystemExit) as info:
        parsed.plant.AddModelInstance("")
    assert str(info.value) == empty_name
    instance = parsed.plant.AddModelInstance("m")
    with pytest.raises(SystemExit) as info:
        parsed.plant.RenameModelInstance(instance, "")
    assert str(info.value) == empty_name
    assert parsed.plant.GetModelInstanceName(instance) == "m"


# ------------------------------------------------------------------ SDFormat


def sdf(body: str) -> str:
    return f'<?xml version="1.0"?>\n<sdf version="1.9">\n{body}</sdf>\n'


def link(name: str) -> str:
    return (
        f'<link name="{name}"><collision name="c"><geometry><sphere><radius>0.1</radius>'
        "</sphere></geometry></collision></link>\n"
    )


def sdf_group(name: str, members: tuple[str, ...] = (), ignored: tuple[str, ...] = ()) -> str:
    return (
        f'<drake:collision_filter_group name="{name}">'
        + "".join(f"<drake:member>{m}</drake:member>" for m in members)
        + "".join(
            f"<drake:ignored_collision_filter_group>{g}</drake:ignored_collision_filter_group>"
            for g in ignored
        )
        + "</drake:collision_filter_group>\n"
    )


def test_sdf_nested_model_groups_use_scoped_names(mb: Modules) -> None:
    """Checklist 31: inner::ig={x}; tg={a, inner::y} ignoring inner::ig and tg."""
    parsed = Parsed(mb)
    text = sdf(
        '<model name="top">\n'
        + link("a")
        + link("b")
        + '<model name="inner">\n'
        + link("x")
        + link("y")
        + sdf_group("ig", ("x",))
        + "</model>\n"
        + sdf_group("tg", ("a", "inner::y"), ("inner::ig", "tg"))
        + "</model>\n"
    )
    assert parsed.add(text, "sdf") == ["top", "top::inner"]
    a, b, x, y = "top::a/c", "top::b/c", "top::inner::x/c", "top::inner::y/c"
    assert parsed.candidates() == pairs(a, b, x, y) - {pair(a, x), pair(y, x), pair(a, y)}
    assert parsed.report() == (
        {"top::inner::ig": {"top::inner::x"}, "top::tg": {"top::a", "top::inner::y"}},
        {("top::inner::ig", "top::tg"), ("top::tg", "top::tg")},
    )


@pytest.mark.parametrize(("ignore", "applied"), [("true", False), ("1", False), ("false", True)])
def test_sdf_ignore_is_an_sdformat_bool(mb: Modules, ignore: str, applied: bool) -> None:
    parsed = Parsed(mb)
    text = sdf(
        '<model name="m">\n'
        + link("a")
        + link("b")
        + f'<drake:collision_filter_group name="g" ignore="{ignore}">'
        "<drake:member>a</drake:member><drake:member>b</drake:member>"
        "<drake:ignored_collision_filter_group>g</drake:ignored_collision_filter_group>"
        "</drake:collision_filter_group>\n</model>\n"
    )
    parsed.add(text, "sdf")
    assert parsed.candidates() == (set() if applied else {pair("m::a/c", "m::b/c")})


def test_sdf_include_through_the_package_map_with_a_name_override(mb: Modules) -> None:
    parsed = Parsed(mb)
    text = sdf(
        '<model name="top">\n'
        + link("a")
        + "<include><uri>package://test_models/simple_box.sdf</uri></include>\n"
        + "<include><uri>package://test_models/simple_box.sdf</uri><name>second</name></include>\n"
        + sdf_group("g", ("simple_box::base", "second::base"), ("g",))
        + "</model>\n"
    )
    assert parsed.add(text, "sdf") == ["top", "top::simple_box", "top::second"]
    assert parsed.candidates() == {
        pair("top::a/c", "top::simple_box::base/collision"),
        pair("top::a/c", "top::second::base/collision"),
    }


def test_sdf_world_models_are_top_level_instances(mb: Modules) -> None:
    parsed = Parsed(mb)
    text = sdf('<world name="w">\n<model name="m">\n' + link("a") + "</model>\n"
               '<model name="n">\n' + link("b") + "</model>\n</world>\n")  # fmt: skip
    assert parsed.add(text, "sdf") == ["m", "n"]
    assert parsed.candidates() == {pair("m::a/c", "n::b/c")}


SDF_ERRORS = {
    "unprefixed collision_filter_group": (
        '<model name="m">\n' + link("a") + link("b")
        + '<collision_filter_group name="g"><member>a</member></collision_filter_group>\n'
        "</model>\n",
        '<data-string>:6: error: At XML path /sdf/model[@name="m"]/collision_filter_group'
        '[@name="g"]: XML Element[collision_filter_group], child of element[model], not '
        "defined in SDF. Copying[collision_filter_group] as children of [model].\n",
    ),
    "unknown link in a group": (
        '<model name="m">\n' + link("a") + sdf_group("g", ("zz",)) + "</model>\n",
        "<literal-string>.sdf:3: error: body with name 'm::zz' not found",
    ),
    "group without name": (
        '<model name="m">\n' + link("a")
        + "<drake:collision_filter_group><drake:member>a</drake:member>"
        "</drake:collision_filter_group>\n</model>\n",
        '<literal-string>.sdf: error: The tag <drake:collision_filter_group> is missing the '
        'required attribute "name"',
    ),
    "empty member": (
        '<model name="m">\n' + link("a") + sdf_group("g", ("",)) + "</model>\n",
        "<literal-string>.sdf: error: The tag <drake:member> is missing a required string value.",
    ),
    "group in a link": (
        '<model name="m">\n<link name="a">\n' + sdf_group("g", ("a",)) + "</link>\n</model>\n",
        "<literal-string>.sdf: error: Unsupported SDFormat element in link: "
        "drake:collision_filter_group",
    ),
    "model without name": (
        "<model>\n" + link("a") + "</model>\n",
        "<data-string>:3: error: At XML path /sdf/model: Required attribute[name] in "
        "element[model] is not specified in SDF.",
    ),
    "collision without name": (
        '<model name="m">\n<link name="a"><collision><geometry><sphere><radius>1</radius>'
        "</sphere></geometry></collision></link>\n</model>\n",
        '<data-string>:4: error: At XML path /sdf/model[@name="m"]/link[@name="a"]/collision: '
        "Required attribute[name] in element[collision] is not specified in SDF.",
    ),
    "duplicate link": (
        '<model name="m">\n' + link("a") + link("a") + "</model>\n",
        "error: Non-unique name[a] detected 2 times in XML children of model with name[m].",
    ),
    "a group named like a link": (
        '<model name="m">\n' + link("g") + sdf_group("g", ("g",)) + "</model>\n",
        "error: Non-unique name[g] detected 2 times in XML children of model with name[m].",
    ),
    "two models": (
        '<model name="m">\n' + link("a") + '</model>\n<model name="n">\n' + link("b")
        + "</model>\n",
        "error: Root object can only contain one model. Using the first one found",
    ),
    "joint to an unknown child": (
        '<model name="m">\n' + link("a")
        + '<joint name="j" type="fixed"><parent>a</parent><child>zz</child></joint>\n'
        "</model>\n",
        "error: Child frame with name[zz] specified by joint with name[j] not found in model "
        "with name[m].",
    ),
    "revolute joint without axis": (
        '<model name="m">\n' + link("a") + link("b")
        + '<joint name="j" type="revolute"><parent>a</parent><child>b</child></joint>\n'
        "</model>\n",
        "<literal-string>.sdf:6: error: An axis must be specified for joint 'j'",
    ),
}  # fmt: skip


@pytest.mark.parametrize("case", SDF_ERRORS)
def test_sdf_error_message(mb: Modules, case: str) -> None:
    body, message = SDF_ERRORS[case]
    with pytest.raises(RuntimeError) as info:
        Parsed(mb).add(sdf(body), "sdf")
    assert str(info.value) == message


# ------------------------------------------------- SDFormat includes and frames

TWO_LINKS = sdf(
    '<model name="two">\n'
    + link("a")
    + '<link name="b"><pose>0 0 1 0 0 0</pose><collision name="c"><geometry><sphere>'
    "<radius>0.1</radius></sphere></geometry></collision></link>\n"
    '<joint name="j" type="revolute"><parent>a</parent><child>b</child>'
    "<axis><xyz>0 1 0</xyz></axis></joint>\n"
    '<frame name="tip" attached_to="b"><pose>0 0 0.5 0 0 0</pose></frame>\n'
    "</model>\n"
)


def included(mb: Modules, tmp_path: Path, **files: str) -> Parsed:
    """A Parsed whose package ``inc`` is ``tmp_path``, holding ``files`` (name -> text)."""
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    parsed = Parsed(mb)
    parsed.parser.package_map().Add(package_name="inc", package_path=str(tmp_path))
    return parsed


def default_position(parsed: Parsed, model: str, body: str) -> list[float]:
    plant = parsed.plant
    instance = plant.GetModelInstanceByName(model)
    X_WB = plant.GetDefaultFloatingBaseBodyPose(plant.GetBodyByName(body, instance))
    return [float(v) for v in X_WB.translation()]


def test_sdf_a_model_made_only_of_includes_is_a_model(mb: Modules, tmp_path: Path) -> None:
    """Its frame is on the first included model's canonical link (once a bare KeyError)."""
    parsed = included(mb, tmp_path, **{"two.sdf": TWO_LINKS})
    text = sdf(
        '<model name="top">\n<include><uri>package://inc/two.sdf</uri></include>\n'
        "<include><uri>package://inc/two.sdf</uri><name>second</name>"
        "<pose>1 0 0 0 0 0</pose></include>\n</model>\n"
    )
    assert parsed.add(text, "sdf") == ["top", "top::two", "top::second"]
    assert parsed.bodies() == {"top::two::a", "top::two::b", "top::second::a", "top::second::b"}
    top = parsed.plant.GetModelInstanceByName("top")
    assert parsed.plant.GetFrameByName("__model__", top).body().name() == "a"
    assert default_position(parsed, "top::second", "b") == [1.0, 0.0, 1.0]
    parsed.plant.Finalize()
    two_a, two_b = "top::two::a/c", "top::two::b/c"
    second_a, second_b = "top::second::a/c", "top::second::b/c"
    assert parsed.candidates() == pairs(two_a, two_b, second_a, second_b) - {
        pair(two_a, two_b),
        pair(second_a, second_b),
    }


def test_sdf_a_nested_model_may_be_posed_relative_to_a_later_include(
    mb: Modules, tmp_path: Path
) -> None:
    """x is at the included model's frame ``tip``: (0, 1, 0) + (0, 0, 1) + (0, 0, 0.5)."""
    parsed = included(mb, tmp_path, **{"two.sdf": TWO_LINKS})
    text = sdf(
        '<model name="top">\n<link name="base"/>\n'
        '<model name="n"><pose relative_to="later::tip"/><link name="x"/></model>\n'
        "<include><uri>package://inc/two.sdf</uri><name>later</name>"
        '<pose relative_to="base">0 1 0 0 0 0</pose></include>\n</model>\n'
    )
    assert parsed.add(text, "sdf") == ["top", "top::n", "top::later"]
    assert default_position(parsed, "top::n", "x") == [0.0, 1.0, 1.5]


def test_sdf_an_include_error_names_the_uri_line(mb: Modules, tmp_path: Path) -> None:
    """libsdformat reports an unknown URI at the ``<uri>``, not the ``<include>`` (measured)."""
    parsed = included(mb, tmp_path)
    text = sdf(
        '<model name="top">\n<link name="base"/>\n<include>\n<name>x</name>\n'
        "<uri>package://inc/nope.sdf</uri>\n</include>\n</model>\n"
    )
    with pytest.raises(RuntimeError) as info:
        parsed.add(text, "sdf")
    assert str(info.value) == (
        '<data-string>:7: error: At XML path /sdf/model[@name="top"]/include[0]/uri: Unable to '
        "find uri[package://inc/nope.sdf]"
    )


def test_sdf_an_included_model_directory_names_its_file_in_model_config(
    mb: Modules, tmp_path: Path
) -> None:
    """The highest ``<sdf version>`` wins; one newer than 1.12 is an error (libsdformat's
    warning, measured); a directory without model.config is an error."""
    for name, versions in (("robot", ("1.6", "1.9")), ("future", ("1.9", "1.99"))):
        (tmp_path / name).mkdir()
        entries = "".join(f'<sdf version="{v}">v{v}.sdf</sdf>' for v in versions)
        (tmp_path / name / "model.config").write_text(
            f'<?xml version="1.0"?>\n<model><name>{name}</name>{entries}</model>\n'
        )
        for number in versions:
            model = f'<model name="v{number.replace(".", "_")}">\n' + link("a") + "</model>\n"
            (tmp_path / name / f"v{number}.sdf").write_text(sdf(model))

    def include(uri: str) -> str:
        return sdf(
            f'<model name="top">\n<include><uri>package://inc/{uri}</uri></include>\n</model>\n'
        )

    assert included(mb, tmp_path).add(include("robot/"), "sdf") == ["top", "top::v1_9"]
    for uri, message in (
        ("future/", "error: Ignoring version 1.99 for model future because is newer than this "
         "sdf parser (version 1.12)"),
        ("", f"error: Could not find model.config or manifest.xml in [{tmp_path}/]"),
    ):  # fmt: skip
        with pytest.raises(RuntimeError) as info:
            included(mb, tmp_path).add(include(uri), "sdf")
        assert str(info.value) == message


def test_sdf_a_merge_include_dissolves_into_its_parent(mb: Modules, tmp_path: Path) -> None:
    """The links, joints and frames become the parent's; ``_merged__two__model__`` stands for
    the merged model's frame, on its canonical link. Its filter groups are dropped (measured)."""
    grouped = TWO_LINKS.replace("</model>", sdf_group("g", ("a", "b"), ("g",)) + "</model>")
    parsed = included(mb, tmp_path, **{"two.sdf": grouped})
    text = sdf(
        '<model name="top">\n<link name="base"/>\n<include merge="true">'
        "<uri>package://inc/two.sdf</uri><pose>0 0 2 0 0 0</pose></include>\n"
        '<joint name="w" type="fixed"><parent>base</parent><child>a</child></joint>\n'
        "</model>\n"
    )
    assert parsed.add(text, "sdf") == ["top"]
    assert parsed.bodies() == {"top::base", "top::a", "top::b"}
    assert parsed.joints() == {"j:revolute:a->b", "w:weld:base->a"}
    top = parsed.plant.GetModelInstanceByName("top")
    assert parsed.plant.GetFrameByName("_merged__two__model__", top).body().name() == "a"
    assert parsed.plant.GetFrameByName("tip", top).body().name() == "b"
    assert default_position(parsed, "top", "b") == [0.0, 0.0, 3.0]
    assert parsed.report() == ({}, set())


#: A URDF arm whose parse warns: ``version`` is an attribute Drake does not read.
WARNING_ARM = (
    '<?xml version="1.0"?>\n<robot name="arm" version="1.0">\n<link name="L1"/>\n'
    '<joint name="J1" type="revolute"><parent link="L1"/><child link="L2"/>'
    '<axis xyz="0 0 1"/></joint>\n<link name="L2"/>\n</robot>\n'
)


def test_sdf_a_custom_include_that_warns_is_left_out_of_the_sdformat_model(
    mb: Modules, tmp_path: Path
) -> None:
    """Drake hands a URDF's warnings to libsdformat as errors, and libsdformat then drops
    the include's interface model: its bodies stay in the plant, but no SDFormat name can
    refer to them, merged or not, and a model holding only it has no link (measured on
    pydrake 1.12.0, 1.16.0, 1.22.0-1.25.0, 1.51.1 and 1.58.0 with this arm's ``version``;
    without it each text loads)."""
    joint = '<joint name="jj" type="fixed"><parent>torso</parent><child>{}</child></joint>\n'
    texts = {
        "merged": ('<include merge="true"><uri>package://inc/arm.urdf</uri></include>\n'
                   + joint.format("L1"),
                   "error: Child frame with name[L1] specified by joint with name[jj] not found "
                   "in model with name[top]."),
        "nested": ("<include><uri>package://inc/arm.urdf</uri></include>\n"
                   + joint.format("arm::L1"),
                   "error: Child frame with name[arm::L1] specified by joint with name[jj] not "
                   "found in model with name[top]."),
        "alone": ('<model name="w"><include merge="true"><uri>package://inc/arm.urdf</uri>'
                  "</include></model>\n",
                  "error: A model must have at least one link."),
    }  # fmt: skip
    quiet_arm = WARNING_ARM.replace(' version="1.0"', "")
    for body, message in texts.values():
        text = sdf(f'<model name="top">\n<link name="torso"/>\n{body}</model>\n')
        with pytest.raises(RuntimeError) as info:
            included(mb, tmp_path, **{"arm.urdf": WARNING_ARM}).add(text, "sdf")
        assert str(info.value) == message
        assert included(mb, tmp_path, **{"arm.urdf": quiet_arm}).add(text, "sdf")[0] == "top"
    parsed = included(mb, tmp_path, **{"arm.urdf": WARNING_ARM})
    text = sdf(
        '<model name="top">\n<link name="torso"/>\n<model name="w"><link name="own"/>'
        '<include merge="true"><uri>package://inc/arm.urdf</uri></include></model>\n'
        "</model>\n"
    )
    assert parsed.add(text, "sdf") == ["top", "top::w"]
    assert parsed.bodies() == {"top::torso", "top::w::own", "top::w::L1", "top::w::L2"}


def test_sdf_errors_come_in_libsdformats_then_drakes_order(mb: Modules) -> None:
    """Reading (an undefined element) before loading (a reserved link name) before the
    frame graphs (an unknown frame) before Drake's own checks (negative damping)."""
    damped = (
        '<link name="b"/><joint name="j" type="revolute"><parent>a</parent><child>b</child>'
        "<axis><xyz>0 0 1</xyz><dynamics><damping>-1</damping></dynamics></axis></joint>\n"
    )
    bad_frame = '<frame name="f" attached_to="zz"/>\n'
    layers = [
        ("<bogus/>\n", '<data-string>:{line}: error: At XML path /sdf/model[@name="m"]/bogus: '
         "XML Element[bogus], child of element[model], not defined in SDF. Copying[bogus] as "
         "children of [model].\n"),
        ('<link name="world"/>\n', "error: The supplied link name [world] is reserved."),
        (bad_frame, "error: attached_to name[zz] specified by frame with name[f] does not match "
         "a nested model, link, joint, or frame name in model with name[m]."),
        (damped, "<literal-string>.sdf:{line}: error: Joint damping is negative for joint 'j'. "
         "Joint damping must be a non-negative number."),
    ]  # fmt: skip
    for first, (element, message) in enumerate(layers):
        # The first to fail is last in the text: the stage decides, not the order.
        body = "".join(text for text, _ in reversed(layers[first:]))
        line = 4 + body[: body.index(element)].count("\n")
        with pytest.raises(RuntimeError) as info:
            Parsed(mb).add(sdf('<model name="m">\n<link name="a"/>' + body + "</model>\n"), "sdf")
        assert str(info.value) == message.format(line=line)


def test_sdf_a_joint_gets_a_parent_frame_only_where_it_is_off_the_parent_body(
    mb: Modules,
) -> None:
    """Drake tests libsdformat's resolved X_PJ for *exact* identity (gz-math arithmetic)."""
    parsed = Parsed(mb)
    text = sdf(
        '<model name="m">\n<pose>1 2 3 0.1 0.2 0.3</pose>\n'
        '<link name="a"><pose>0.5 0 0 0 0.4 0</pose></link>\n'
        '<link name="b"><pose>0 0.5 0 0.3 0 0</pose></link>\n'
        '<link name="c"><pose>0.5 0 0 0 0.4 0</pose></link>\n'
        '<joint name="j" type="revolute"><pose>0.1 0 0 0 0 0.2</pose><parent>a</parent>'
        "<child>b</child><axis><xyz>0 1 1</xyz></axis></joint>\n"
        '<joint name="k" type="fixed"><parent>a</parent><child>c</child></joint>\n'
        "</model>\n"
    )
    parsed.add(text, "sdf")
    plant = parsed.plant
    frames = {
        j.name(): (j.frame_on_parent().name(), j.frame_on_child().name())
        for j in (plant.get_joint(i) for i in plant.GetJointIndices())
    }
    assert frames == {"j": ("j_parent", "j_child"), "k": ("a", "k_child")}


# ---------------------------------------------------------------- directives


def test_directive_filter_groups_filter_eleven_pairs_before_finalize(mb: Modules) -> None:
    """Checklist 32: the CollisionFilterGroupSmokeTest situations, before Finalize."""
    parsed = Parsed(mb)
    models = parsed.parser.AddModels(file_name=str(MODELS / "filter_groups.dmd.yaml"))
    assert len(models) == 9
    assert not parsed.plant.is_finalized()
    boxes = [f"model{i}::base/collision" for i in range(1, 8)]
    subs = [f"nested::sub_model{i}::base/collision" for i in (1, 2)]
    m1, m2, m3, m4, m5, m6, m7 = boxes
    s1, s2 = subs
    filtered = {pair(m1, m2), pair(m1, s2), pair(m3, s1), pair(m3, s2), pair(s1, s2)}
    filtered |= pairs(m4, m5, m6, m7)
    assert len(filtered) == 11
    assert parsed.candidates() == pairs(*boxes, *subs) - filtered
    groups, exclusion_pairs = parsed.report()
    assert groups == {
        "across_models": {"model1::base", "model2::base"},
        "group_45": {"model4::base", "model5::base"},
        "group_4567": {"model4::base", "model5::base", "model6::base", "model7::base"},
        "group_67": {"model6::base", "model7::base"},
        "nested::across_sub_models": {"nested::sub_model1::base", "nested::sub_model2::base"},
        "nested_group": {"model3::base"},
        "nested_members": {"model1::base", "nested::sub_model2::base"},
    }
    assert exclusion_pairs == {
        ("across_models", "across_models"),
        ("group_4567", "group_4567"),
        ("nested::across_sub_models", "nested::across_sub_models"),
        ("nested::across_sub_models", "nested_group"),
        ("nested_members", "nested_members"),
    }


def box(name: str) -> str:
    return f"- add_model: {{name: {name}, file: package://test_models/simple_box.sdf}}\n"


def test_directive_group_with_model_namespace_reads_names_in_that_instance(mb: Modules) -> None:
    parsed = Parsed(mb)
    text = (
        "directives:\n"
        + box("a")
        + box("b")
        + "- add_collision_filter_group: {name: g, model_namespace: a, members: [base]}\n"
        + "- add_collision_filter_group:\n"
        "    {name: h, members: [b::base], member_groups: [a::g], "
        "ignored_collision_filter_groups: [h]}\n"
    )
    assert parsed.add(text, "dmd.yaml") == ["a", "b"]
    assert parsed.candidates() == set()
    assert parsed.report() == (
        {"a::g": {"a::base"}, "h": {"a::base", "b::base"}},
        {("h", "h")},
    )


def test_add_weld_names_the_joint_after_its_frames(mb: Modules) -> None:
    parsed = Parsed(mb)
    text = (
        "directives:\n"
        + box("a")
        + box("b")
        + "- add_weld: {parent: world, child: a::base}\n"
        + "- add_weld: {parent: a::top, child: b::base, X_PC: {translation: [0, 0, 1]}}\n"
    )
    parsed.add(text, "dmd.yaml")
    plant = parsed.plant
    assert plant.HasJointNamed("world_welds_to_base", plant.GetModelInstanceByName("a"))
    assert plant.HasJointNamed("top_welds_to_base", plant.GetModelInstanceByName("b"))
    parsed.plant.Finalize()
    assert parsed.candidates() == set()


DIRECTIVE_ERRORS = {
    "unknown member": (
        box("a") + "- add_collision_filter_group: {name: g, members: [a::zz]}\n",
        "error: body with name 'a::zz' not found",
    ),
    "unscoped member at global scope": (
        box("a") + "- add_collision_filter_group: {name: g, members: [base]}\n",
        "error: body with name 'base' not found",
    ),
    "unknown ignored group": (
        box("a") + "- add_collision_filter_group:\n"
        "    {name: g, members: [a::base], ignored_collision_filter_groups: [nope]}\n",
        "error: collision filter group with name 'nope' not found",
    ),
    "scoped group name": (
        box("a") + "- add_collision_filter_group: {name: a::g, members: [a::base]}\n",
        "error: group name 'a::g' cannot be a scoped name",
    ),
    "group defined twice": (
        box("a") + "- add_collision_filter_group: {name: g, members: [a::base]}\n" * 2,
        "error: group 'g' has already been defined",
    ),
    "unknown package": (
        "- add_model: {name: a, file: package://nope/simple_box.sdf}\n",
        "error: URI 'package://nope/simple_box.sdf' refers to unknown package 'nope'",
    ),
    "unknown key": (
        "- add_model: {name: a, file: package://test_models/simple_box.sdf, foo: 1}\n",
        "<string>:2:14: YAML node of type Mapping (with size 3 and keys {file, foo, name}) key "
        "'foo' did not match any visited value entry for <root> while accepting YAML node of "
        "type Mapping (with size 1 and keys {add_model}) while visiting "
        "std::optional<drake::multibody::parsing::AddModel> add_model while accepting  (with "
        "size 1 and keys {directives[0]}) while visiting "
        "drake::multibody::parsing::ModelDirective directives[0] while accepting YAML node of "
        "type Mapping (with size 1 and keys {directives}) while visiting "
        "std::vector<drake::multibody::parsing::ModelDirective,std::allocator<drake::multibody::"
        "parsing::ModelDirective>> directives.",
    ),
}


@pytest.mark.parametrize("case", DIRECTIVE_ERRORS)
def test_directive_error_message(mb: Modules, case: str) -> None:
    body, message = DIRECTIVE_ERRORS[case]
    with pytest.raises(RuntimeError) as info:
        Parsed(mb).add("directives:\n" + body, "dmd.yaml")
    assert str(info.value) == message


def test_an_invalid_directive_ends_the_program_as_pydrake_does(mb: Modules) -> None:
    """Drake's IsValid is a DRAKE_DEMAND, which pydrake reports as SystemExit (measured on
    1.51.1); since 1.58 the problem is a parse error (measured on 1.58.0)."""
    text = "directives:\n- add_collision_filter_group: {name: g}\n"
    if holds(mb, "directives-invalid-error-since-1.58"):
        with pytest.raises(RuntimeError) as error:
            Parsed(mb).add(text, "dmd.yaml")
        assert str(error.value) == (
            "error: add_collision_filter_group: at least one of `members` or `member_groups` "
            "must be non-empty"
        )
        return
    with pytest.raises(SystemExit) as info:
        Parsed(mb).add(text, "dmd.yaml")
    # detail_dmd_parser.cc:332 on 1.51.1
    assert str(info.value) == demand_message(mb, "LoadModelDirectives.valid")


def test_directive_groups_are_skipped_without_a_scene_graph(mb: Modules) -> None:
    parsed = Parsed(mb, scene_graph=False)
    parsed.add(
        "directives:\n" + box("a") + "- add_collision_filter_group: {name: g, members: [a::zz]}\n",
        "dmd.yaml",
    )
    assert parsed.parser.GetCollisionFilterGroups().empty()


# ------------------------------------------------- directives: scoping and errors
#
# Each case was run on pydrake 1.51.1 (and reimpl) with the same text; the expected
# values are pydrake's.

DIRECTIVE_SCOPING_ERRORS = {
    # Drake evaluates AddWeld's arguments right to left: the child is looked up first.
    "weld with both frames missing": (
        "- add_weld: {parent: nope::a, child: nope2::b}\n",
        "GetModelInstanceByName(): There is no model instance named 'nope2'. The current "
        "model instances are 'DefaultModelInstance', 'WorldModelInstance'.",
    ),
    "frame scoped to a missing instance": (
        box("m") + "- add_frame: {name: nope::f, X_PF: {base_frame: m::base}}\n",
        "GetModelInstanceByName(): There is no model instance named 'nope'. The current model "
        "instances are 'DefaultModelInstance', 'WorldModelInstance', 'm'.",
    ),
    "nested namespace that is not an instance": (
        "- add_model_instance: {name: a}\n"
        "- add_directives: {file: package://test_models/two_boxes.dmd.yaml, "
        "model_namespace: a}\n"
        "- add_directives: {file: package://test_models/filter_groups.dmd.yaml, "
        "model_namespace: a::zz}\n",
        "Namespace 'a::zz' does not exist as model instance",
    ),
    "relative model file": (
        "- add_model: {name: m, file: simple_box.sdf}\n",
        "error: URI 'simple_box.sdf' is invalid when parsing a string instead of a filename.",
    ),
    "directives file as a model": (
        "- add_model: {name: m, file: package://test_models/two_boxes.dmd.yaml}\n",
        "error: '{models}/two_boxes.dmd.yaml' is a model directives data source; it is always "
        "an error to pass a model directives source to a single-model parser method. Use "
        "AddModels() instead.",
    ),
}


@pytest.mark.parametrize("case", DIRECTIVE_SCOPING_ERRORS)
def test_directive_scoping_error_message(mb: Modules, case: str) -> None:
    body, message = DIRECTIVE_SCOPING_ERRORS[case]
    # Measured: 'Namespace ...' on 1.51.1, 1.54.0, 1.55.0 and 1.57.0; 'error: Namespace ...'
    # on 1.58.0 (release fact directives-namespace-error-wording-since-1.58).
    parse_error = holds(mb, "directives-namespace-error-wording-since-1.58")
    if message.startswith("Namespace") and parse_error:
        message = f"error: {message}"
    with pytest.raises(RuntimeError) as info:
        Parsed(mb).add("directives:\n" + body, "dmd.yaml")
    assert str(info.value) == message.replace("{models}", str(MODELS))


def test_an_unscoped_added_frame_goes_to_its_base_frames_instance(mb: Modules) -> None:
    parsed = Parsed(mb)
    text = (
        "directives:\n"
        + box("m")
        + "- add_frame: {name: f, X_PF: {base_frame: m::base, translation: [1, 2, 3]}}\n"
        + "- add_frame: {name: m::g, X_PF: {base_frame: world}}\n"
        + "- add_frame: {name: h, X_PF: {base_frame: world}}\n"
    )
    parsed.add(text, "dmd.yaml")
    plant = parsed.plant
    m = plant.GetModelInstanceByName("m")
    assert plant.HasFrameNamed("f", m)
    assert plant.HasFrameNamed("g", m)
    assert plant.HasFrameNamed("h", plant.world_body().model_instance())


def test_a_group_namespace_of_an_earlier_parse_ends_the_program(mb: Modules) -> None:
    """Drake's resolver DRAKE_DEMANDs that a group's model instance is new in the parse."""
    parsed = Parsed(mb)
    parsed.parser.AddModels(url="package://test_models/simple_box.sdf")
    with pytest.raises(SystemExit) as info:
        parsed.add(
            "directives:\n"
            "- add_collision_filter_group: {name: g, model_namespace: simple_box, "
            "members: [base]}\n",
            "dmd.yaml",
        )
    # detail_collision_filter_group_resolver.cc:39 on 1.51.1 and 1.58.0
    assert str(info.value) == demand_message(mb, "CollisionFilterGroupResolver.AddGroup.instance")


def test_a_prefixed_parser_reads_directive_groups_in_the_prefix_instance(mb: Modules) -> None:
    """The prefix is the top namespace, so a group is read in instance ``pre``, which
    must exist."""
    parsed = Parsed(mb)
    parser = mb.parsing.Parser(plant=parsed.plant, model_name_prefix="pre")
    parser.package_map().Add(package_name="test_models", package_path=str(MODELS))
    text = (
        "directives:\n" + box("m") + "- add_collision_filter_group: {name: g, members: [m::base]}\n"
    )
    with pytest.raises(RuntimeError) as info:
        parser.AddModelsFromString(file_contents=text, file_type="dmd.yaml")
    assert str(info.value).startswith(
        "GetModelInstanceByName(): There is no model instance named 'pre'."
    )


def test_default_free_body_pose_from_a_frame_adds_a_floating_joint(mb: Modules) -> None:
    parsed = Parsed(mb)
    text = (
        "directives:\n"
        + box("m")
        + "- add_model:\n    name: n\n    file: package://test_models/simple_box.sdf\n"
        "    default_free_body_pose: {base: {base_frame: m::base, translation: [1, 2, 3]}}\n"
    )
    parsed.add(text, "dmd.yaml")
    assert "base:quaternion_floating:base->base" in parsed.joints()


def test_wrong_sized_default_joint_positions_are_drakes_error(mb: Modules, tmp_path: Path) -> None:
    (tmp_path / "arm.urdf").write_text(
        urdf(sphere_link("a"), sphere_link("b"), joint("j", "a", "b"))
    )
    parsed = Parsed(mb)
    text = (
        f"directives:\n- add_model: {{name: arm, file: 'file://{tmp_path}/arm.urdf', "
        "default_joint_positions: {j: [0.1, 0.2]}}\n"
    )
    with pytest.raises(RuntimeError) as info:
        parsed.add(text, "dmd.yaml")
    assert str(info.value) == (
        "set_default_positions: The number of positions in the input (2) does not match the "
        "number of positions of the joint 'arm::j' (1)."
    )


def test_auto_renaming_applies_to_added_model_instances(mb: Modules) -> None:
    parsed = Parsed(mb)
    parsed.parser.SetAutoRenaming(value=True)
    parsed.add(
        "directives:\n- add_model_instance: {name: a}\n- add_model_instance: {name: a}\n",
        "dmd.yaml",
    )
    assert parsed.plant.HasModelInstanceNamed("a_1")


DIRECTIVE_YAML_ERRORS = {
    "duplicate key": (
        "- add_model_instance: {name: a, name: b}\n",
        "Cannot Node::Add(key, value) using duplicate key 'name'",
    ),
    "sequence for a string": (
        "- add_model_instance:\n    name: [a]\n",
        "<string>:3:5: YAML node of type Mapping (with size 1 and keys {name}) has non-Scalar "
        "(Sequence) entry for std::string name while accepting YAML node of type Mapping "
        "(with size 1 and keys {add_model_instance}) while visiting "
        "std::optional<drake::multibody::parsing::AddModelInstance> add_model_instance while "
        "accepting  (with size 1 and keys {directives[0]}) while visiting "
        "drake::multibody::parsing::ModelDirective directives[0] while accepting YAML node of "
        "type Mapping (with size 1 and keys {directives}) while visiting "
        "std::vector<drake::multibody::parsing::ModelDirective,std::allocator<drake::"
        "multibody::parsing::ModelDirective>> directives.",
    ),
    "short translation": (
        "- add_frame: {name: f, X_PF: {base_frame: world, translation: [1, 2]}}\n",
        "<string>:2:30: YAML node of type Mapping (with size 2 and keys {base_frame, "
        "translation}) has 2-size entry (wanted 3-size) entry for Eigen::Vector3d translation "
        "while accepting YAML node of type Mapping (with size 2 and keys {X_PF, name}) while "
        "visiting drake::schema::Transform X_PF while accepting YAML node of type Mapping "
        "(with size 1 and keys {add_frame}) while visiting "
        "std::optional<drake::multibody::parsing::AddFrame> add_frame while accepting  (with "
        "size 1 and keys {directives[0]}) while visiting "
        "drake::multibody::parsing::ModelDirective directives[0] while accepting YAML node of "
        "type Mapping (with size 1 and keys {directives}) while visiting "
        "std::vector<drake::multibody::parsing::ModelDirective,std::allocator<drake::"
        "multibody::parsing::ModelDirective>> directives.",
    ),
    "unknown rotation tag": (
        "- add_frame: {name: f, X_PF: {base_frame: world, rotation: !Foo {}}}\n",
        "<string>:2:30: YAML node of type Mapping (with size 2 and keys {base_frame, "
        "rotation}) has unsupported type tag !Foo while selecting a variant<> entry for "
        "std::variant<drake::schema::Rotation::Identity,drake::schema::Rotation::Rpy,"
        "drake::schema::Rotation::AngleAxis,drake::schema::Rotation::Uniform> rotation while "
        "accepting YAML node of type Mapping (with size 2 and keys {X_PF, name}) while "
        "visiting drake::schema::Transform X_PF while accepting YAML node of type Mapping "
        "(with size 1 and keys {add_frame}) while visiting "
        "std::optional<drake::multibody::parsing::AddFrame> add_frame while accepting  (with "
        "size 1 and keys {directives[0]}) while visiting "
        "drake::multibody::parsing::ModelDirective directives[0] while accepting YAML node of "
        "type Mapping (with size 1 and keys {directives}) while visiting "
        "std::vector<drake::multibody::parsing::ModelDirective,std::allocator<drake::"
        "multibody::parsing::ModelDirective>> directives.",
    ),
}


@pytest.mark.parametrize("case", DIRECTIVE_YAML_ERRORS)
def test_directive_yaml_error_message(mb: Modules, case: str) -> None:
    body, message = DIRECTIVE_YAML_ERRORS[case]
    with pytest.raises(RuntimeError) as info:
        Parsed(mb).add("directives:\n" + body, "dmd.yaml")
    assert str(info.value) == message


def test_a_finalized_plant_with_a_scene_graph_refuses_any_parse(mb: Modules) -> None:
    parsed = Parsed(mb)
    parsed.plant.Finalize()
    with pytest.raises(SystemExit) as info:
        parsed.add("directives: []\n", "dmd.yaml")
    assert str(info.value).endswith(
        "in GetMutableSceneGraphPreFinalize(): condition '!is_finalized()' failed."
    )


def test_obj_model_text_is_refused(mb: Modules) -> None:
    with pytest.raises(RuntimeError) as info:
        Parsed(mb).add("v 0 0 0\n", "obj")
    assert str(info.value) == (
        "Parser does not yet support adding models using in-memory OBJ data. The OBJ data "
        "must be referenced as a file."
    )


PACKAGE_XML_NAMES = {
    "text, spaces kept": ("<package><name> sp </name></package>", " sp "),
    "an element": ("<package><name><x/></name></package>", "x"),
    "text before an element": ("<package><name>a<x/>b</name></package>", "a"),
}


@pytest.mark.parametrize("case", PACKAGE_XML_NAMES)
def test_a_package_name_is_the_first_child_of_name(mb: Modules, tmp_path: Path, case: str) -> None:
    text, name = PACKAGE_XML_NAMES[case]
    (tmp_path / "package.xml").write_text(text)
    package_map = mb.parsing.PackageMap.MakeEmpty()
    package_map.AddPackageXml(filename=str(tmp_path / "package.xml"))
    assert package_map.GetPackageNames() == [name]


def test_a_name_of_only_whitespace_ends_the_program(mb: Modules, tmp_path: Path) -> None:
    (tmp_path / "package.xml").write_text("<package><name>  </name></package>")
    with pytest.raises(SystemExit) as info:
        mb.parsing.PackageMap.MakeEmpty().AddPackageXml(filename=str(tmp_path / "package.xml"))
    # package_map.cc:886 on 1.51.1, :887 on 1.52.0-1.58.0 (measured with this file on 1.51.1,
    # 1.54.0, 1.55.0, 1.57.0 and 1.58.0; demand_lines.json measures it with <name/>).
    assert str(info.value) == demand_message(mb, "ParsePackageManifest.name_children")


def test_package_urls_resolve_to_lexically_normal_paths(mb: Modules, tmp_path: Path) -> None:
    (tmp_path / "a").mkdir()
    (tmp_path / "a" / "m.sdf").write_text("")
    package_map = mb.parsing.PackageMap.MakeEmpty()
    package_map.Add(package_name="p", package_path=str(tmp_path / "a" / ".." / "a"))
    assert package_map.ResolveUrl(url="package://p//m.sdf") == str(tmp_path / "a" / "m.sdf")
    assert package_map.ResolveUrl(url="package://p/") == f"{tmp_path}/a/"
    with pytest.raises(RuntimeError) as info:
        package_map.ResolveUrl(url="package://p")
    assert str(info.value) == (
        "error: URI 'package://p' is invalid when parsing a string instead of a filename."
    )


# ---------------------------------------------------- Parser, PackageMap, groups


def test_parser_from_a_builder_finds_the_plant_named_plant(mb: Modules) -> None:
    builder = mb.framework.DiagramBuilder()
    with pytest.raises(RuntimeError) as info:
        mb.parsing.Parser(builder=builder)
    assert str(info.value) == (
        "DiagramBuilder does not contain a subsystem named plant. Valid subsystems are ."
    )
    plant, scene_graph = mb.plant.AddMultibodyPlantSceneGraph(builder=builder, time_step=0.0)
    parser = mb.parsing.Parser(builder=builder, model_name_prefix="p")
    assert parser.plant() is plant
    assert parser.scene_graph() is scene_graph
    assert parser.builder() is builder
    models = parser.AddModelsFromString(file_contents=robot("", links="a"), file_type="urdf")
    assert [plant.GetModelInstanceName(m) for m in models] == ["p::r"]


def test_unknown_file_type_message(mb: Modules) -> None:
    with pytest.raises(RuntimeError) as info:
        Parsed(mb).add("<robot/>", "foo")
    assert str(info.value) == (
        "error: The file '<literal-string>.foo' is not a recognized type. Known types are: "
        ".urdf, .sdf, .xml (Mujoco), .dmd.yaml, .obj"
    )


def test_add_models_reads_a_file_and_names_it_in_errors(mb: Modules, tmp_path: Path) -> None:
    path = tmp_path / "r.urdf"
    path.write_text(robot(group("g", member("zz")), links="a"))
    parsed = Parsed(mb)
    with pytest.raises(RuntimeError) as info:
        parsed.parser.AddModels(file_name=str(path))
    assert str(info.value) == f"{path}:1: error: body with name 'r::zz' not found"


def test_package_map(mb: Modules, tmp_path: Path) -> None:
    package_map = mb.parsing.PackageMap.MakeEmpty()
    assert package_map.size() == 0
    package_map.Add(package_name="p", package_path=str(tmp_path))
    package_map.Add(package_name="p", package_path=str(tmp_path))  # the same path: no error
    assert package_map.Contains("p")
    assert not package_map.Contains("q")
    assert package_map.GetPath("p") == str(tmp_path)
    (tmp_path / "m.sdf").write_text("")
    assert package_map.ResolveUrl("package://p/m.sdf") == str(tmp_path / "m.sdf")
    with pytest.raises(RuntimeError) as info:
        package_map.ResolveUrl("package://q/m.sdf")
    assert str(info.value) == "error: URI 'package://q/m.sdf' refers to unknown package 'q'"
    with pytest.raises(RuntimeError) as info:
        package_map.Add(package_name="q", package_path=str(tmp_path / "nope"))
    assert str(info.value) == (
        f"PackageMap::Add cannot add 'q' because directory '{tmp_path / 'nope'}' does not exist"
    )
    assert sorted(mb.parsing.PackageMap().GetPackageNames()) == ["drake", "drake_models"]


def test_collision_filter_groups_value_api(mb: Modules) -> None:
    groups = mb.parsing.CollisionFilterGroups()
    assert groups.empty()
    groups.AddGroup(name="g", members={"m::a", "m::b"})
    groups.AddExclusionPair(pair=("h", "g"))
    groups.AddExclusionPair(pair=("g", "h"))
    assert not groups.empty()
    assert groups.groups() == {"g": {"m::a", "m::b"}}
    assert groups.exclusion_pairs() == {("g", "h")}


def test_collision_filter_groups_print_groups_members_and_pairs_sorted(mb: Modules) -> None:
    groups = mb.parsing.CollisionFilterGroups()
    assert str(groups) == "\nCollision filter groups:\nCollision filter exclusion pairs:\n"
    groups.AddGroup(name="m::b", members={"m::z", "m::a"})
    groups.AddGroup(name="m::a", members=set())
    groups.AddExclusionPair(pair=("m::b", "m::a"))
    groups.AddExclusionPair(pair=("m::a", "m::a"))
    assert str(groups) == (
        "\nCollision filter groups:\n"
        "    m::a\n"
        "    m::b\n"
        "        m::a\n"
        "        m::z\n"
        "Collision filter exclusion pairs:\n"
        "    m::a, m::a\n"
        "    m::a, m::b\n"
    )


def test_add_models_by_url_resolves_package_and_file_urls(mb: Modules) -> None:
    parsed = Parsed(mb)
    by_package = parsed.parser.AddModels(url="package://test_models/simple_box.sdf")
    by_file = parsed.parser.AddModelsFromUrl(url=f"file://{MODELS / 'filter_groups.dmd.yaml'}")
    names = [parsed.plant.GetModelInstanceName(i) for i in [*by_package, *by_file]]
    assert names[:2] == ["simple_box", "model1"]
    with pytest.raises(RuntimeError) as info:
        parsed.parser.AddModelsFromUrl(url="package://test_models/zz.sdf")
    assert str(info.value) == (
        f"error: URI 'package://test_models/zz.sdf' resolved to '{MODELS / 'zz.sdf'}' which does "
        "not exist."
    )


def test_sdformat_names_a_file_with_a_leading_slash(mb: Modules, tmp_path: Path) -> None:
    """Measured: libsdformat's and Drake's messages about an SDFormat file say ``//tmp/...``."""
    path = tmp_path / "m.sdf"
    path.write_text(sdf('<model name="m">\n' + link("a") + sdf_group("g", ("zz",)) + "</model>\n"))
    with pytest.raises(RuntimeError) as info:
        Parsed(mb).parser.AddModels(file_name=str(path))
    assert str(info.value) == f"/{path}:3: error: body with name 'm::zz' not found"


def test_a_static_sdf_model_welds_each_of_its_links_to_the_world(mb: Modules) -> None:
    parsed = Parsed(mb)
    parsed.add(
        sdf('<model name="m">\n<static>true</static>\n' + link("a") + link("b") + "</model>\n"),
        "sdf",
    )
    plant = parsed.plant
    welds = {plant.get_joint(j).name() for j in plant.GetJointIndices()}
    assert welds == {
        "sdformat_model_static_world_welds_to_a",
        "sdformat_model_static_world_welds_to_b",
    }
    plant.Finalize()
    assert parsed.candidates() == set()


def test_sdf_joint_types_and_the_joint_frames_drake_adds(mb: Modules) -> None:
    parsed = Parsed(mb)
    axis = "<axis><xyz>0 0 1</xyz></axis>"
    joints = {
        "j1": ("fixed", ""),
        "j2": ("prismatic", axis),
        "j3": ("ball", ""),
        "j4": ("universal", axis + "<axis2><xyz>0 1 0</xyz></axis2>"),
        "j5": ("continuous", axis),
    }
    text = '<model name="m">\n' + link("a")
    for i, (name, (kind, extra)) in enumerate(joints.items()):
        ends = f"<parent>a</parent><child>c{i}</child>"
        text += link(f"c{i}") + f'<joint name="{name}" type="{kind}">{ends}{extra}</joint>\n'
    parsed.add(sdf(text + "</model>\n"), "sdf")
    plant = parsed.plant
    assert {
        (plant.get_joint(j).name(), plant.get_joint(j).type_name()) for j in plant.GetJointIndices()
    } == {
        ("j1", "weld"),
        ("j2", "prismatic"),
        ("j3", "ball_rpy"),
        ("j4", "universal"),
        ("j5", "revolute"),
    }
    m = plant.GetModelInstanceByName("m")
    assert all(plant.HasFrameNamed(f"{name}_child", m) for name in joints)
    assert plant.HasFrameNamed("j4_parent", m)
    assert not plant.HasFrameNamed("j1_parent", m)
    assert plant.HasFrameNamed("__model__", m)


def test_parser_with_a_scene_graph_registers_the_plant(mb: Modules) -> None:
    geometry = importlib.import_module(f"{mb.plant.__name__.split('.')[0]}.geometry")
    plant = mb.plant.MultibodyPlant(time_step=0.0)
    scene_graph = geometry.SceneGraph()
    parser = mb.parsing.Parser(plant=plant, scene_graph=scene_graph)
    assert plant.geometry_source_is_registered()
    assert parser.scene_graph() is scene_graph


@pytest.mark.parametrize("mod", ["pydrake", "reimpl"])
def test_urdf_joints_and_drake_joints_are_added_in_document_order(mod: str) -> None:
    urdf = """<robot name="m" xmlns:drake="http://drake.mit.edu">
<link name="l0"/><link name="l1"/><link name="l2"/><link name="l3"/>
<joint name="a" type="revolute"><parent link="l0"/><child link="l1"/><axis xyz="0 0 1"/></joint>
<drake:joint name="b" type="ball"><parent link="l1"/><child link="l2"/></drake:joint>
<joint name="c" type="revolute"><parent link="l2"/><child link="l3"/><axis xyz="0 0 1"/></joint>
</robot>"""
    plant_module = importlib.import_module(f"{mod}.multibody.plant")
    parsing = importlib.import_module(f"{mod}.multibody.parsing")
    framework = importlib.import_module(f"{mod}.systems.framework")
    plant, _ = plant_module.AddMultibodyPlantSceneGraph(framework.DiagramBuilder(), 0.0)
    parsing.Parser(plant).AddModelsFromString(urdf, "urdf")
    assert [plant.get_joint(j).name() for j in plant.GetJointIndices()] == ["a", "b", "c"]


# ------------------------------------------ URDF reading as Drake reads it (1.51.1)
# Measured on pydrake 1.51.1 (and 1.58.0 where a test branches): tinyxml2's grammar,
# istream numbers, meshes, materials, curvilinear joints, the order of checks.

REAL_MODELS = Path(__file__).parent.parent / "scenarios" / "real_models" / "drake"
URDF_TEST_DIR = REAL_MODELS / "multibody/parsing/test/urdf_parser_test"


def urdf_error(mb: Modules, text: str, *, strict: bool = False) -> str:
    parsed = Parsed(mb)
    if strict:
        parsed.parser.SetStrictParsing()
    with pytest.raises(RuntimeError) as info:
        parsed.add(text, "urdf")
    return str(info.value)


R = '<robot name="r"><link name="a"/></robot>'

#: Text tinyxml2 accepts (an XML parser like expat rejects each) -> the models it gives.
TINYXML2_ACCEPTS = {
    "'--' inside a comment": '<robot name="r"><!-- a -- b --><link name="a"/></robot>',
    "blank lines before <?xml": '\n\n<?xml version="1.0"?>\n' + R,
    "a trailing NUL": R + "\x00",
    "text before the robot": "junk " + R,
    "a second top-level element": R + '<robot name="q"/>',
    "'<' and unknown entities in a value": '<robot name="r&foo;<"><link name="a"/></robot>',
    "a DOCTYPE": "<!DOCTYPE robot>" + R,
    "whitespace after '<'": '< robot name="r"><link name="a"/></robot >',
    "attributes without space between": '<robot name="r"><link name="a"type="x"/></robot>',
    "the robot after another element": '<foo/><robot name="r"><link name="a"/></robot>',
}


@pytest.mark.parametrize("case", TINYXML2_ACCEPTS)
def test_urdf_text_is_read_with_tinyxml2s_grammar(mb: Modules, case: str) -> None:
    expected = ["r&foo;<"] if case.startswith("'<'") else ["r"]
    assert Parsed(mb).add(TINYXML2_ACCEPTS[case], "urdf") == expected


#: Text tinyxml2 rejects -> its error name (Drake prints line 1, or 0 for no text).
TINYXML2_REJECTS = {
    "text after the robot": (R + " junk", "XML_ERROR_PARSING_TEXT", 1),
    "<?xml after an element": (R + '<?xml version="1.0"?>', "XML_ERROR_PARSING_DECLARATION", 1),
    "an unclosed comment": ('<robot name="r"/><!-- c ', "XML_ERROR_PARSING_COMMENT", 1),
    "an unclosed CDATA": ('<robot name="r"><![CDATA[x</robot>', "XML_ERROR_PARSING_CDATA", 1),
    "a duplicate attribute": ('<robot name="r" name="q"/>', "XML_ERROR_PARSING_ATTRIBUTE", 1),
    "an unquoted attribute": ("<robot name=r/>", "XML_ERROR_PARSING_ATTRIBUTE", 1),
    "a tag name starting with a digit": ('<robot name="r"><1a/></robot>', "XML_ERROR_PARSING", 1),
    "an end tag of another name": (
        '<robot name="r">\n<a>\n</b></robot>',
        "XML_ERROR_MISMATCHED_ELEMENT",
        1,
    ),
    "a cut tag": ('<robot name="r"', "XML_ERROR_PARSING_ELEMENT", 1),
    "only whitespace": (" \n ", "XML_ERROR_EMPTY_DOCUMENT", 1),
    "nothing": ("", "XML_ERROR_EMPTY_DOCUMENT", 0),
    "a NUL first": ("\x00" + R, "XML_ERROR_EMPTY_DOCUMENT", 0),
}


@pytest.mark.parametrize("case", TINYXML2_REJECTS)
def test_urdf_syntax_errors_carry_tinyxml2s_names(mb: Modules, case: str) -> None:
    text, name, line = TINYXML2_REJECTS[case]
    assert urdf_error(mb, text) == (
        f"<literal-string>.urdf:{line}: error: Failed to parse XML string: {name}"
    )


def test_a_urdf_file_with_a_syntax_error_is_named_a_file(mb: Modules, tmp_path: Path) -> None:
    """Drake's wording names a file 'XML file' (Drake's own sdf_parser_test/bad.urdf)."""
    path = REAL_MODELS / "multibody/parsing/test/sdf_parser_test/bad.urdf"
    with pytest.raises(RuntimeError) as info:
        Parsed(mb).parser.AddModels(file_name=str(path))
    assert str(info.value) == f"{path}:1: error: Failed to parse XML file: XML_ERROR_PARSING_TEXT"
    empty = tmp_path / "empty.urdf"
    empty.write_text("")
    with pytest.raises(RuntimeError) as info:
        Parsed(mb).parser.AddModels(file_name=str(empty))
    assert (
        str(info.value) == f"{empty}:0: error: Failed to parse XML file: XML_ERROR_EMPTY_DOCUMENT"
    )


def test_a_cr_only_urdf_file_counts_lines_by_lf(mb: Modules, tmp_path: Path) -> None:
    """tinyxml2 counts LFs only: a file with CR line ends is all line 1."""
    path = tmp_path / "cr.urdf"
    path.write_bytes(b'<robot name="r">\r<link/>\r</robot>')
    with pytest.raises(RuntimeError) as info:
        Parsed(mb).parser.AddModels(file_name=str(path))
    assert str(info.value) == f"{path}:1: error: link tag is missing name attribute."


def sphere_robot(radius: str) -> str:
    return (
        f'<robot name="r"><link name="a"><collision><geometry><sphere radius="{radius}"/>'
        "</geometry></collision></link></robot>"
    )


#: A number as C++'s ``istream >> double`` reads it: the prefix that is a number,
#: reading stopping at the first failure; exactly one must come out.
NUMBERS_READ = ["1", " 1 ", "1abc", ".5", "+1", "1.", "1e5x", "2 x", "0x10", "1,5", "1 2e"]
NUMBERS_REJECTED = ["1 2", "abc", "", "1e", "1e+", "inf", "nan", "1.5.5", "1e400", "-"]


@pytest.mark.parametrize("text", NUMBERS_READ)
def test_a_urdf_number_is_its_leading_numeric_text(mb: Modules, text: str) -> None:
    parsed = Parsed(mb)
    parsed.add(sphere_robot(text), "urdf")
    assert parsed.geometries() == {"r::a/Sphere"}


@pytest.mark.parametrize("text", NUMBERS_REJECTED)
def test_a_urdf_number_must_be_one_finite_number(mb: Modules, text: str) -> None:
    assert urdf_error(mb, sphere_robot(text)) == (
        f"<literal-string>.urdf:1: error: Expected single value for attribute 'radius' got '{text}'"
    )


def mesh_robot(path: Path, *meshes: str) -> str:
    collisions = "".join(
        f'<collision><geometry><mesh filename="{path}"{m}</geometry></collision>' for m in meshes
    )
    return f'<robot name="r" {DRAKE_NS}><link name="a">{collisions}</link></robot>'


@pytest.fixture
def obj_file(tmp_path: Path) -> Path:
    path = tmp_path / "tri_cube.obj"
    path.write_bytes((REAL_MODELS / "multibody/parsing/test/tri_cube.obj").read_bytes())
    return path


def test_declare_convex_makes_a_convex_named_after_its_type(
    mb: Modules, tmp_path: Path, obj_file: Path
) -> None:
    """Unnamed: Convex, Convex_1, then a plain mesh is Mesh (names per link and role)."""
    parsed = Parsed(mb)
    convex = "><drake:declare_convex/></mesh>"
    path = tmp_path / "m.urdf"
    path.write_text(mesh_robot(obj_file, convex, convex, "/>"))
    parsed.parser.AddModels(file_name=str(path))
    inspector = parsed.scene_graph.model_inspector()
    shapes = {
        inspector.GetName(g): type(inspector.GetShape(g)).__name__
        for g in inspector.GetAllGeometryIds()
    }
    assert shapes == {"r::Convex": "Convex", "r::Convex_1": "Convex", "r::Mesh": "Mesh"}


@pytest.mark.parametrize(
    ("scale", "scale3"), [("2", [2, 2, 2]), ("2abc", [2, 2, 2]), ("1 2 3", [1, 2, 3])]
)
def test_a_mesh_scale_is_one_number_for_all_axes_or_three(
    mb: Modules, tmp_path: Path, obj_file: Path, scale: str, scale3: list[float]
) -> None:
    parsed = Parsed(mb)
    path = tmp_path / "m.urdf"
    path.write_text(mesh_robot(obj_file, f' scale="{scale}"/>'))
    parsed.parser.AddModels(file_name=str(path))
    inspector = parsed.scene_graph.model_inspector()
    (geometry_id,) = inspector.GetAllGeometryIds()
    assert list(inspector.GetShape(geometry_id).scale3()) == scale3


@pytest.mark.parametrize(
    ("scale", "raised"),
    [
        ("2 3", (ValueError, "Expected 3 values for attribute scale got 2 3")),
        ("2 3 4 5", (ValueError, "Expected 3 values for attribute scale got 2 3 4 5")),
        (" 2", (ValueError, "Expected 3 values for attribute scale got  2")),
        (
            "2\t3\t4",
            (RuntimeError, "error: Expected single value for attribute 'scale' got '2\t3\t4'"),
        ),
        ("abc", (RuntimeError, "error: Expected single value for attribute 'scale' got 'abc'")),
    ],
)
def test_a_mesh_scale_with_a_space_needs_three_numbers_else_one(
    mb: Modules, tmp_path: Path, obj_file: Path, scale: str, raised: tuple[type, str]
) -> None:
    """A space makes it a vector (ValueError without a source); else one number, whose
    error names no source either."""
    error, message = raised
    path = tmp_path / "m.urdf"
    path.write_text(mesh_robot(obj_file, f' scale="{scale}"/>'))
    with pytest.raises(error) as info:
        Parsed(mb).parser.AddModels(file_name=str(path))
    assert str(info.value) == message


@pytest.mark.parametrize("file", ["conflicting_materials", "duplicate_materials"])
def test_a_robot_material_defined_twice_is_an_error_even_when_equal(mb: Modules, file: str) -> None:
    path = URDF_TEST_DIR / f"{file}.urdf"
    with pytest.raises(RuntimeError) as info:
        Parsed(mb).parser.AddModels(file_name=str(path))
    new = ("0.2", "0.2") if file == "conflicting_materials" else ("0.79607843137", "0.67843137254")
    if not holds(mb, "eigen-vector-wording-since-1.52"):  # N.B. Measured on 1.51.1.
        existing = "0.93333333333 0.79607843137 0.67843137254             1"
        given = f"0.93333333333 {new[0]:>13} {new[1]:>13}             1"
    else:  # N.B. Measured on 1.52.0 and 1.58.0: fmt_eigen prints a column vector.
        existing = "[0.93333333333, 0.79607843137, 0.67843137254, 1]ᵀ"
        given = f"[0.93333333333, {new[0]}, {new[1]}, 1]ᵀ"
    assert str(info.value) == (
        f"{path}:6: error: Material 'brown' was previously defined.\n"
        f"  - existing definition: RGBA: {existing}, Diffuse map: None\n"
        f"  - new definition:      RGBA: {given}, Diffuse map: None"
    )


def visual(material: str) -> str:
    return f'<visual><geometry><box size="1 1 1"/></geometry>{material}</visual>'


NAMED_X = '<material name="x"/>'
RED_X = '<material name="x"><color rgba="1 0 0 1"/></material>'
ALMOST_RED_X = '<material name="x"><color rgba="1 0 0 1.00000000001"/></material>'

#: Robot body -> Drake's error (None: it parses).
MATERIALS = {
    # A visual may name a robot material, wherever the robot defines it...
    "a robot material": (f'<link name="a">{visual(NAMED_X)}</link>{RED_X}', None),
    # ... but not one that only a later visual defines.
    "used before defined": (
        f'<link name="a">{visual(NAMED_X)}{visual(RED_X)}</link>',
        "Material 'x' not previously defined, but has no color or texture information.",
    ),
    # A visual redefining a material within 1e-10 of its colour is no error.
    "the same colour": (f'{RED_X}<link name="a">{visual(ALMOST_RED_X)}</link>', None),
    "no name": (
        '<material><color rgba="1 0 0 1"/></material>',
        "Material tag is missing a required name",
    ),
    "no rgba": (
        '<material name="x"><color/></material>',
        "Failed to parse 'rgba' attribute of <color>}",
    ),
}


@pytest.mark.parametrize("case", MATERIALS)
def test_urdf_materials_are_checked_as_drake_checks_them(mb: Modules, case: str) -> None:
    body, error = MATERIALS[case]
    text = f'<robot name="r">{body}</robot>'
    if error is None:
        assert Parsed(mb).add(text, "urdf") == ["r"]
    else:
        assert urdf_error(mb, text) == f"<literal-string>.urdf:1: error: {error}"


def test_a_visual_colour_must_lie_in_0_1_while_a_robot_colour_need_not(mb: Modules) -> None:
    """The visual's diffuse colour is a geometry::Rgba, which checks its range."""
    unused = '<material name="m"><color rgba="2 0 0 1"/></material>'
    assert Parsed(mb).add(f'<robot name="r">{unused}<link name="a"/></robot>', "urdf") == ["r"]
    used = visual('<material name="m"/>')
    with pytest.raises(RuntimeError) as info:
        Parsed(mb).add(f'<robot name="r">{unused}<link name="a">{used}</link></robot>', "urdf")
    assert str(info.value) == (
        "Rgba values must be within the range [0, 1]. Values provided: (r=2, g=0, b=0, a=1)"
    )


#: A robot with several errors -> the one Drake raises (its order of checks).
FIRST_ERRORS = {
    "robot materials before links": (
        '<robot name="r">\n<link/>\n<material name="m"/>\n</robot>',
        "3: error: Material 'm' not previously defined, but has no color or texture information.",
    ),
    "visuals before collisions": (
        '<robot name="r">\n<link name="a">\n<collision/>\n<visual/>\n</link>\n</robot>',
        "4: error: Link a has a visual element without geometry.",
    ),
    "groups before joints": (
        f'<robot name="r" {DRAKE_NS}>\n<link name="a"/>\n'
        '<joint name="j" type="weird"><parent link="a"/><child link="a"/></joint>\n'
        '<drake:collision_filter_group name="g"><drake:member link="zz"/>'
        "</drake:collision_filter_group>\n</robot>",
        "1: error: body with name 'r::zz' not found",
    ),
    "a zero axis before an unknown type": (
        '<robot name="r">\n<link name="a"/><link name="b"/>\n'
        '<joint name="j" type="weird"><parent link="a"/><child link="b"/>\n'
        '<axis xyz="0 0 0"/></joint>\n</robot>',
        "4: error: Joint 'j' axis is zero.  Don't do that.",
    ),
    "the element's tag before the limits": (
        '<robot name="r">\n<link name="a"/><link name="b"/>\n'
        '<drake:joint name="j" type="revolute"><parent link="a"/><child link="b"/>\n'
        '<limit lower="1 2"/></drake:joint>\n</robot>',
        "3: error: Joint j of type revolute is a standard joint type, and should be a <joint>",
    ),
    "dynamics before the screw pitch": (
        '<robot name="r">\n<link name="a"/><link name="b"/>\n'
        '<drake:joint name="j" type="screw"><parent link="a"/><child link="b"/>\n'
        '<dynamics damping="1 2"/></drake:joint>\n</robot>',
        "4: error: Expected single value for attribute 'damping' got '1 2'",
    ),
    "mimics before transmissions": (
        '<robot name="r">\n<link name="a"/><link name="b"/>\n<transmission/>\n'
        '<joint name="j" type="revolute"><parent link="a"/><child link="b"/>\n'
        "<mimic/></joint>\n</robot>",
        "5: error: Joint 'j' mimic element is missing the required 'joint' attribute.",
    ),
    "transmissions before frames": (
        '<robot name="r">\n<link name="a"/>\n<frame name="f" link="zz"/>\n<transmission/>\n'
        "</robot>",
        "4: error: Transmission element is missing a type.",
    ),
    "loop joints before frames": (
        '<robot name="r">\n<frame name="f"/>\n<loop_joint/>\n</robot>',
        "1: error: loop joints are not supported in MultibodyPlant",
    ),
    "frames before bushings": (
        f'<robot name="r" {DRAKE_NS}>\n<link name="a"/>\n<drake:linear_bushing_rpy/>\n'
        '<frame name="f"/>\n</robot>',
        "4: error: missing link name for frame f.",
    ),
    "the screw pitch's value": (
        '<robot name="r">\n<link name="a"/><link name="b"/>\n'
        '<drake:joint name="j" type="screw"><parent link="a"/><child link="b"/>\n'
        "<drake:screw_thread_pitch/></drake:joint>\n</robot>",
        "4: error: A screw joint has a <drake:screw_thread_pitch> tag that is missing the "
        "'value' attribute.",
    ),
}


@pytest.mark.parametrize("case", FIRST_ERRORS)
def test_the_first_urdf_error_in_drakes_order_is_raised(mb: Modules, case: str) -> None:
    text, message = FIRST_ERRORS[case]
    assert urdf_error(mb, text) == f"<literal-string>.urdf:{message}"


#: A URDF whose joint j2 mimics a joint the file does not have (Gepetto's
#: alex_psyonic_hands.urdf mimics 'index_q1', naming it 'Left_index_q1').
MIMIC_OF_A_MISSING_JOINT = (
    '<robot name="r"><link name="a"/><link name="b"/><link name="c"/>\n'
    '<joint name="j1" type="revolute"><parent link="a"/><child link="b"/>'
    '<axis xyz="0 0 1"/></joint>\n'
    '<joint name="j2" type="revolute"><parent link="b"/><child link="c"/><axis xyz="0 0 1"/>'
    '<mimic joint="nope" multiplier="2"/></joint></robot>'
)


@pytest.mark.parametrize("time_step", [0.0, 0.001])
def test_a_mimic_of_a_missing_joint_is_an_error_where_the_release_reads_mimics(
    mb: Modules, time_step: float
) -> None:
    """Measured: with time_step 0 the parse succeeds up to 1.50.0 and fails from 1.51.0;
    with 0.001 it succeeds up to 1.36.0 and fails from 1.37.0."""
    builder = mb.framework.DiagramBuilder()
    plant, _ = mb.plant.AddMultibodyPlantSceneGraph(builder=builder, time_step=time_step)
    parser = mb.parsing.Parser(plant=plant)
    fact = (
        "urdf-mimic-continuous-since-1.51" if time_step == 0.0 else "urdf-mimic-discrete-since-1.37"
    )
    if not holds(mb, fact):
        assert len(parser.AddModelsFromString(MIMIC_OF_A_MISSING_JOINT, "urdf")) == 1
        return
    with pytest.raises(RuntimeError) as info:
        parser.AddModelsFromString(MIMIC_OF_A_MISSING_JOINT, "urdf")
    assert str(info.value) == (
        "<literal-string>.urdf:3: error: Joint 'j2' mimic element specifies joint 'nope' "
        "which does not exist."
    )


@pytest.mark.parametrize(
    ("release", "time_step", "read"),
    [
        ("1.36.0", 0.001, False),
        ("1.37.0", 0.001, True),
        ("1.50.0", 0.0, False),
        ("1.50.0", 0.001, True),
        ("1.51.0", 0.0, True),
    ],
)
def test_reimpl_reads_a_mimic_on_the_releases_drake_does(
    release: str, time_step: float, read: bool
) -> None:
    """reimpl set to each boundary release, against what those releases of pydrake did
    (measured with MIMIC_OF_A_MISSING_JOINT)."""
    code = (
        "from reimpl.multibody.plant import AddMultibodyPlantSceneGraph\n"
        "from reimpl.multibody.parsing import Parser\n"
        "from reimpl.systems.framework import DiagramBuilder\n"
        f"plant, _ = AddMultibodyPlantSceneGraph(DiagramBuilder(), {time_step})\n"
        "try:\n"
        f"    Parser(plant).AddModelsFromString({MIMIC_OF_A_MISSING_JOINT!r}, 'urdf')\n"
        "    print('ignored')\n"
        "except RuntimeError as e:\n"
        "    print(e)\n"
    )
    env = {**os.environ, "REIMPL_DRAKE_RELEASE": release, "PYTHONPATH": str(ROOT)}
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=False
    )
    assert done.stdout.strip() == (
        "<literal-string>.urdf:3: error: Joint 'j2' mimic element specifies joint 'nope' "
        "which does not exist."
        if read
        else "ignored"
    )


def curvilinear_robot() -> str:
    sphere = '<collision><geometry><sphere radius="0.1"/></geometry></collision>'
    return (
        f'<robot name="r" {DRAKE_NS}><link name="w0">{sphere}</link><link name="a">{sphere}'
        f'</link><link name="b">{sphere}</link>'
        '<joint name="w" type="revolute"><parent link="w0"/><child link="a"/>'
        '<axis xyz="0 0 1"/></joint>'
        '<drake:joint name="j" type="curvilinear"><origin xyz="1 2 3" rpy="0.1 0.2 0.3"/>'
        '<parent link="a"/><child link="b"/><drake:initial_tangent xyz="0 0 1"/>'
        '<drake:plane_normal xyz="1 0 0"/><drake:is_periodic value="true"/><drake:curves>'
        '<drake:line_segment length="1.0"/><drake:circular_arc radius="2.0" angle="1.5"/>'
        '<drake:circular_arc radius="2.0" angle="-1.0"/></drake:curves></drake:joint></robot>'
    )


#: Arc length s -> p_FM of the curvilinear joint above (line 1, arcs of 3 and 2: length 6).
CURVE_POINTS = {
    0.0: [0.0, 0.0, 0.0],
    0.5: [0.0, 0.0, 0.5],
    2.0: [0.0, -0.244835, 1.958851],
    3.4: [0.0, -1.275284, 2.864078],
    5.0: [0.0, -2.797656, 3.307038],
    -1.0: [0.0, -2.797656, 3.307038],  # periodic: s = 5
    20.0: [0.0, -0.244835, 1.958851],  # periodic: s = 2
}


def test_a_curvilinear_joint_follows_its_curve_and_filters_its_links(mb: Modules) -> None:
    """Drake's CurvilinearJoint (not bound in pydrake: type_name() only); its links are
    adjacent for the default filters, like any joint's but a quaternion floating one's."""
    parsed = Parsed(mb)
    parsed.add(curvilinear_robot(), "urdf")
    plant = parsed.plant
    plant.Finalize()
    assert parsed.candidates() == {pair("r::b/Sphere", "r::w0/Sphere")}
    joint = plant.GetJointByName("j")
    assert (joint.type_name(), joint.num_positions()) == ("curvilinear", 1)
    context = plant.CreateDefaultContext()
    for s, p_FM in CURVE_POINTS.items():
        q = plant.GetPositions(context)
        q[joint.position_start()] = s
        plant.SetPositions(context, q)
        X_FM = plant.CalcRelativeTransform(
            context, plant.GetFrameByName("j_parent"), plant.GetFrameByName("b")
        )
        assert X_FM.translation() == pytest.approx(p_FM, abs=1e-6)


def test_an_implausible_inertia_is_a_warning_and_a_strict_error(mb: Modules) -> None:
    text = (
        '<robot name="r"><link name="a"><inertial><mass value="1"/>'
        '<inertia ixx="-1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link></robot>'
    )
    assert Parsed(mb).add(text, "urdf") == ["r"]
    assert urdf_error(mb, text, strict=True) == (
        "<literal-string>.urdf:1: error: While parsing inertia matrix: "
        "MakeFromMomentsAndProductsOfInertia(): The rotational inertia\n"
        "[-1   0   0]\n[ 0   1   0]\n[ 0   0   1]\n"
        "did not pass the test CouldBePhysicallyValid().\n"
        "The associated principal moments of inertia:\n-1  1  1\n"
        "are invalid since at least one is negative."
    )


@pytest.mark.parametrize(
    ("version", "frame", "error"),
    [
        ("1.6", 'frame=""', None),
        ("1.6", 'frame="l"', '@relative_to="l"'),
        ("1.9", 'frame=""', '@frame=""'),
    ],
)
def test_sdf_an_empty_pose_frame_before_1_7_is_dropped_where_a_named_one_is_refused(
    mb: Modules, version: str, frame: str, error: str | None
) -> None:
    """Measured on pydrake 1.51.1 (found in Gepetto/example-robot-data's cassie.sdf, SDFormat
    1.6): the conversion to 1.7 turns ``frame`` into ``relative_to``, which an ``<inertial>``
    pose does not have, but drops an empty one."""
    text = (
        f'<sdf version="{version}"><model name="m"><link name="l"><inertial>'
        f"<pose {frame}>0 0 1 0 0 0</pose><mass>1</mass></inertial></link></model></sdf>"
    )
    if error is None:
        assert Parsed(mb).add(text, "sdf") == ["m"]
        return
    with pytest.raises(RuntimeError) as info:
        Parsed(mb).add(text, "sdf")
    attribute = error.split("=")[0].removeprefix("@")
    assert str(info.value) == (
        f'<data-string>:1: error: At XML path /sdf/model[@name="m"]/link[@name="l"]/inertial/'
        f"pose[{error}]: XML Attribute[{attribute}] in element[pose] not defined in SDF.\n"
    )


def test_sdf_a_syntax_error_names_the_file_or_the_string_and_tinyxml2s_element(
    mb: Modules, tmp_path: Path
) -> None:
    """Measured on pydrake 1.51.1 (found by fuzz --models at seed 1)."""
    text = '<sdf version="1.9">\n<model name="m" name="x"><link name="l"/></model></sdf>\n'
    detail = (
        "Error=XML_ERROR_PARSING_ATTRIBUTE ErrorID=7 (0x7) Line number=2: XMLElement name=model"
    )
    with pytest.raises(RuntimeError) as info:
        Parsed(mb).add(text, "sdf")
    assert str(info.value) == f"error: Error parsing XML from string: {detail}"
    (tmp_path / "bad.sdf").write_text(text, encoding="utf-8")
    with pytest.raises(RuntimeError) as info:
        Parsed(mb).parser.AddModels(file_name=str(tmp_path / "bad.sdf"))
    assert str(info.value) == f"error: Error parsing XML in file [/{tmp_path}/bad.sdf]: {detail}"
