# Ported from Drake: multibody/parsing/test/parser_manual_test.cc at v1.51.1
# (https://github.com/RobotLocomotion/drake), together with the examples of Drake's
# parsing manual (multibody/parsing/parsing_doxygen.h: collision filter groups, scoped
# names, parses without a SceneGraph) that it exists to try by hand, re-expressed as pytest
# functions that run unchanged on pydrake and on reimpl through the public Parser API.
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
"""parser_manual_test.cc's flow, and the parsing manual's filter-group statements.

parser_manual_test.cc is no gtest: it is a command-line tool, tagged ``manual`` in
Drake's BUILD, that parses one file or URL the way a user would and prints the
collision filter groups. Its flow is ported as ``parse_like_the_tool``: a continuous
plant, a SceneGraph unless ``--scene_graph=false``, the package map populated from
``ROS_PACKAGE_PATH``, strict parsing under ``--strict``, ``AddModelsFromUrl`` when the
argument matches ``^[A-Za-z0-9+.-]+://`` (else ``AddModels``), an error caught and
reported, then ``GetCollisionFilterGroups()`` printed (``str()`` in Python is Drake's
``fmt`` form) and the exit status ``models.empty()``.

The manual's statements are checked on the documented examples' shapes. Where Drake
disagrees with the manual (names beginning with ``::``), the test expects Drake's
behaviour and says so.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

from tests.upstream.parsing_support import fact_holds_for

_IS_URL = re.compile(r"^[A-Za-z0-9+.-]+://")


@dataclass
class ToolRun:
    """What the tool prints and returns."""

    exit_status: int
    models: list[str]
    groups: str | None = None
    error: str | None = None


def parse_like_the_tool(
    drake: ModuleType, argument: str, *, scene_graph: bool = True, strict: bool = False
) -> ToolRun:
    """parser_manual_test.cc's do_main, with its log lines returned instead."""
    plant = drake.multibody.plant.MultibodyPlant(time_step=0.0)
    sg = drake.geometry.SceneGraph() if scene_graph else None
    if sg is not None:
        plant.RegisterAsSourceForSceneGraph(scene_graph=sg)
    parser = drake.multibody.parsing.Parser(plant=plant)
    parser.package_map().PopulateFromRosPackagePath()
    if strict:
        parser.SetStrictParsing()
    try:
        if _IS_URL.search(argument):
            models = parser.AddModelsFromUrl(url=argument)
        else:
            models = parser.AddModels(file_name=argument)
    except RuntimeError as error:  # the tool logs e.what() and exits with EXIT_FAILURE
        return ToolRun(exit_status=1, models=[], error=str(error))
    names = [plant.GetModelInstanceName(model_instance=m) for m in models]
    groups = str(parser.GetCollisionFilterGroups())
    return ToolRun(exit_status=int(not models), models=names, groups=groups)


_LINK = '<link name="{0}"><collision><geometry><sphere radius="1"/></geometry></collision></link>'


def _urdf(groups: str, links: tuple[str, ...] = ("a", "b", "c")) -> str:
    return '<robot name="r">' + "".join(_LINK.format(n) for n in links) + groups + "</robot>"


def _group(
    name: str,
    *,
    members: tuple[str, ...] = (),
    ignored: tuple[str, ...] = (),
    member_groups: tuple[str, ...] = (),
    attributes: str = "",
) -> str:
    body = "".join(f'<drake:member link="{m}"/>' for m in members)
    body += "".join(f'<drake:member_group name="{g}"/>' for g in member_groups)
    body += "".join(f'<drake:ignored_collision_filter_group name="{g}"/>' for g in ignored)
    tag = "drake:collision_filter_group"
    return f'<{tag} name="{name}"{attributes}>{body}</{tag}>'


#: A group of a and b that ignores itself (ExcludeWithin), as the tool prints it.
WITHIN = _group("g", members=("a", "b"), ignored=("g",))
WITHIN_PRINTED = (
    "\nCollision filter groups:\n    r::g\n        r::a\n        r::b\n"
    "Collision filter exclusion pairs:\n    r::g, r::g\n"
)
NOTHING_PRINTED = "\nCollision filter groups:\nCollision filter exclusion pairs:\n"


def _write(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


@pytest.fixture(autouse=True)
def _no_ros_package_path(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)


# --- the tool -------------------------------------------------------------------------


@pytest.mark.parametrize("as_url", [False, True], ids=["file", "url"])
def test_the_tool_prints_the_filter_groups_of_a_file_or_url(
    drake: ModuleType, tmp_path: Path, as_url: bool
) -> None:
    path = _write(tmp_path, "robot.urdf", _urdf(WITHIN))
    run = parse_like_the_tool(drake, f"file://{path}" if as_url else str(path))
    assert run == ToolRun(exit_status=0, models=["r"], groups=WITHIN_PRINTED)


def test_the_tool_finds_packages_on_the_ros_package_path(
    drake: ModuleType, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    package = tmp_path / "ros" / "my_robot"
    package.mkdir(parents=True)
    _write(package, "package.xml", '<package format="2"><name>my_robot</name></package>')
    _write(package, "robot.urdf", _urdf(WITHIN))
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path / "ros"))
    run = parse_like_the_tool(drake, "package://my_robot/robot.urdf")
    assert run == ToolRun(exit_status=0, models=["r"], groups=WITHIN_PRINTED)


def test_without_a_scene_graph_the_groups_are_ignored(drake: ModuleType, tmp_path: Path) -> None:
    """Manual: parses that do not use a SceneGraph effectively ignore geometric model
    elements; the collision filter groups are ignored with them (measured)."""
    path = _write(tmp_path, "robot.urdf", _urdf(WITHIN))
    run = parse_like_the_tool(drake, str(path), scene_graph=False)
    assert run == ToolRun(exit_status=0, models=["r"], groups=NOTHING_PRINTED)


def test_under_strict_parsing_a_warning_stops_the_tool(drake: ModuleType, tmp_path: Path) -> None:
    """A joint's ``safety_controller`` provokes a warning (manual: URDF tags that provoke a
    warning); ``--strict`` makes it the error the tool reports."""
    joint = (
        '<joint name="j" type="fixed"><parent link="a"/><child link="b"/>'
        "<safety_controller/></joint>"
    )
    path = _write(tmp_path, "robot.urdf", _urdf(joint))
    assert parse_like_the_tool(drake, str(path)).exit_status == 0
    assert parse_like_the_tool(drake, str(path), strict=True) == ToolRun(
        exit_status=1,
        models=[],
        error=(
            f"{path}:1: error: The tag 'safety_controller' found as a child of 'joint' is "
            "currently unsupported and will be ignored."
        ),
    )


def test_a_file_without_models_is_a_failing_exit_status(drake: ModuleType, tmp_path: Path) -> None:
    """The tool returns ``models.empty()``: directives that add nothing parse but fail."""
    path = _write(tmp_path, "empty.dmd.yaml", "directives: []\n")
    assert parse_like_the_tool(drake, str(path)) == ToolRun(
        exit_status=1, models=[], groups=NOTHING_PRINTED
    )


# --- the manual: drake:collision_filter_group ------------------------------------------


class Parsed:
    """A URDF or SDFormat text parsed with a SceneGraph: its groups and filtered pairs."""

    def __init__(self, drake: ModuleType, text: str, file_type: str) -> None:
        self.plant = drake.multibody.plant.MultibodyPlant(time_step=0.0)
        self.sg = drake.geometry.SceneGraph()
        self.plant.RegisterAsSourceForSceneGraph(scene_graph=self.sg)
        self.parser = drake.multibody.parsing.Parser(plant=self.plant)
        self.parser.AddModels(file_contents=text, file_type=file_type)
        report = self.parser.GetCollisionFilterGroups()
        self.groups: dict[str, set[str]] = report.groups()
        self.pairs: set[tuple[str, str]] = report.exclusion_pairs()

    def filtered(self) -> set[tuple[str, str]]:
        """The pairs of bodies whose geometries SceneGraph filters, by scoped body name."""
        inspector = self.sg.model_inspector()
        frames: dict[Any, str] = {}
        for i in range(self.plant.num_bodies()):
            body = self.plant.get_body(drake_index(self.plant, i))
            frame_id = self.plant.GetBodyFrameIdIfExists(body_index=body.index())
            if frame_id is not None:
                frames[frame_id] = body.scoped_name().to_string()
        ids = sorted(inspector.GetAllGeometryIds())
        named = {g: frames[inspector.GetFrameId(g)] for g in ids}
        return {
            tuple(sorted((named[a], named[b])))  # type: ignore[misc]
            for k, a in enumerate(ids)
            for b in ids[k + 1 :]
            if inspector.CollisionFiltered(geometry_id1=a, geometry_id2=b)
        }


def drake_index(plant: Any, i: int) -> Any:
    """BodyIndex(i) of the plant's implementation."""
    return type(plant.world_body().index())(i)


def test_an_ignored_group_element_is_skipped(drake: ModuleType) -> None:
    """Manual: if ``ignore`` is present and true-valued, the element is skipped."""
    skipped = Parsed(
        drake,
        _urdf(_group("g", members=("a", "b"), ignored=("g",), attributes=' ignore="true"')),
        "urdf",
    )
    assert (skipped.groups, skipped.pairs, skipped.filtered()) == ({}, set(), set())
    kept = Parsed(
        drake,
        _urdf(_group("g", members=("a", "b"), ignored=("g",), attributes=' ignore="false"')),
        "urdf",
    )
    assert kept.filtered() == {("r::a", "r::b")}


def test_a_group_pairing_itself_excludes_within_and_another_excludes_between(
    drake: ModuleType,
) -> None:
    """Manual: a pair naming the same group twice is ExcludeWithin; two different groups
    ExcludeBetween (members of one group stay unfiltered among themselves)."""
    within = Parsed(drake, _urdf(WITHIN), "urdf")
    assert within.pairs == {("r::g", "r::g")}
    assert within.filtered() == {("r::a", "r::b")}
    between = Parsed(
        drake,
        _urdf(_group("g", members=("a",), ignored=("h",)) + _group("h", members=("b", "c"))),
        "urdf",
    )
    assert between.pairs == {("r::g", "r::h")}
    assert between.filtered() == {("r::a", "r::b"), ("r::a", "r::c")}


def test_a_member_group_adds_its_members(drake: ModuleType) -> None:
    """Manual (drake:member_group): all members of the named group become members."""
    parsed = Parsed(
        drake,
        _urdf(
            _group("g", members=("a",))
            + _group("h", members=("b",), member_groups=("g",), ignored=("h",))
        ),
        "urdf",
    )
    assert parsed.groups == {"r::g": {"r::a"}, "r::h": {"r::a", "r::b"}}
    assert parsed.filtered() == {("r::a", "r::b")}


@pytest.mark.parametrize(
    ("group", "message"),
    [
        (_group("g", ignored=("g",)), "group 'r::g' has no members"),
        (_group("x::g", members=("a",)), "group name 'r::x::g' cannot be a scoped name"),
        # Manual (drake:member): "In SDFormat files only, the name may refer to a link
        # within a nested model"; a URDF's scoped member is read in the robot's scope.
        (_group("g", members=("r::a",)), "body with name 'r::r::a' not found"),
    ],
    ids=["no members", "scoped group name", "scoped member in URDF"],
)
def test_the_manuals_rules_for_a_group_are_errors(
    drake: ModuleType, group: str, message: str
) -> None:
    """Manual: one or more members are required; the name must not be scoped."""
    with pytest.raises(RuntimeError) as error:
        Parsed(drake, _urdf(group), "urdf")
    assert str(error.value) == f"<literal-string>.urdf:1: error: {message}"


# --- the manual: scoped names ---------------------------------------------------------

_SPHERE = "<collision name='c'><geometry><sphere><radius>1</radius></sphere></geometry></collision>"
#: The manual's example: model A contains model B, which contains model C.
NESTED_SDF = f"""<sdf version="1.9"><model name="A">
  <model name="B">
    <link name="lb">{_SPHERE}</link>
    <model name="C">
      <link name="lc">{_SPHERE}</link>
      <drake:collision_filter_group name="gc">
        <drake:member>lc</drake:member>
      </drake:collision_filter_group>
    </model>
    <drake:collision_filter_group name="gb">
      <drake:member>lb</drake:member>
      <drake:member>C::lc</drake:member>
    </drake:collision_filter_group>
  </model>
  <link name="la">{_SPHERE}</link>
  <drake:collision_filter_group name="ga">
    <drake:member>MEMBER</drake:member>
    <drake:member_group>B::C::gc</drake:member_group>
    <drake:ignored_collision_filter_group>IGNORED</drake:ignored_collision_filter_group>
  </drake:collision_filter_group>
</model></sdf>"""
NESTED_GROUPS = {
    "A::B::C::gc": {"A::B::C::lc"},
    "A::B::gb": {"A::B::C::lc", "A::B::lb"},
    "A::ga": {"A::B::C::lc", "A::la"},
}


def _nested(member: str = "la", ignored: str = "B::gb") -> str:
    return NESTED_SDF.replace("MEMBER", member).replace("IGNORED", ignored)


def test_scoped_names_reach_into_nested_models(drake: ModuleType) -> None:
    """Manual (scoped names): within A, ``B::some_frame_in_B`` and ``B::C::...``; members,
    member groups and ignored groups of an SDFormat group may use them."""
    parsed = Parsed(drake, _nested(), "sdf")
    assert parsed.groups == NESTED_GROUPS
    assert parsed.pairs == {("A::B::gb", "A::ga")}
    # ga = {la, lc} against gb = {lb, lc}: every pair across, lc with itself aside.
    assert parsed.filtered() == {
        ("A::B::lb", "A::la"),
        ("A::B::C::lc", "A::la"),
        ("A::B::C::lc", "A::B::lb"),
    }


def test_a_scoped_name_must_name_something_in_a_nested_model(drake: ModuleType) -> None:
    with pytest.raises(RuntimeError) as error:
        Parsed(drake, _nested(member="B::C::nope"), "sdf")
    assert (
        str(error.value)
        == "<literal-string>.sdf:1: error: body with name 'A::B::C::nope' not found"
    )


@pytest.mark.parametrize(
    ("member", "ignored"), [("::la", "B::gb"), ("la::", "B::gb"), ("la", "::B::gb")]
)
def test_a_filter_group_name_with_a_delimiter_at_an_end_is_its_canonical_name(
    drake: ModuleType, member: str, ignored: str
) -> None:
    """Where Drake contradicts its manual: "names must not start with ``::``; there is no
    way to denote any outer or outermost scope". Drake (since 1.14) reads a filter group's
    names as canonical ScopedNames, so ``::la``, ``la::`` and ``::B::gb`` in model A mean
    ``A::la`` and ``A::B::gb`` (measured on pydrake 1.14.0, 1.51.1 and 1.58.0); up to 1.13
    such a name is an error (release fact scoped-names-canonical-since-1.14)."""
    text = _nested(member=member, ignored=ignored)
    if not fact_holds_for(drake, "scoped-names-canonical-since-1.14"):
        bad = member if member != "la" else ignored
        what = "body name" if bad == member else "group name"
        with pytest.raises(RuntimeError, match=re.escape(f"{what} '{bad}' can neither")):
            Parsed(drake, text, "sdf")
        return
    parsed = Parsed(drake, text, "sdf")
    assert parsed.groups == NESTED_GROUPS
    assert parsed.pairs == {("A::B::gb", "A::ga")}


@pytest.mark.parametrize("name", ["::g", "g::"])
def test_a_urdf_group_named_with_a_delimiter_at_an_end_is_the_plain_group(
    drake: ModuleType, name: str
) -> None:
    """The same in URDF, for the group's own name: ``::g`` and ``g::`` declare ``r::g``
    (not a scoped name); measured on pydrake 1.14.0, 1.51.1 and 1.58.0."""
    text = _urdf(_group(name, members=("a", "b"), ignored=(name,)))
    if not fact_holds_for(drake, "scoped-names-canonical-since-1.14"):
        with pytest.raises(RuntimeError, match=re.escape(f"group name '{name}' can neither")):
            Parsed(drake, text, "urdf")
        return
    parsed = Parsed(drake, text, "urdf")
    assert parsed.groups == {"r::g": {"r::a", "r::b"}}
    assert parsed.filtered() == {("r::a", "r::b")}
