# Ported from Drake: multibody/parsing/test/collision_filter_groups_test.cc and
# multibody/parsing/test/detail_collision_filter_group_resolver_test.cc
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
"""Upstream CollisionFilterGroups and group-resolver tests, on pydrake and on reimpl.

``collision_filter_groups_test.cc`` tests the C++ class; its cases are kept where
the Python binding reaches: pydrake binds no copy, move nor ``==``
(``==`` is identity, measured on 1.51.1 and 1.58.0), so equality is checked on
``groups()`` and ``exclusion_pairs()``; ``Convert`` and ``Merge`` are internal,
and are what ``Parser.GetCollisionFilterGroups()`` does across parses, so they
are checked through it.

``detail_collision_filter_group_resolver_test.cc`` drives the internal resolver
with a diagnostic policy that collects every error. Through the public API,
Drake's Parser raises the first error, so each case is a URDF, SDFormat or
model-directives text that breaks the same rule, and the test checks the
message of that first error (full text, measured on pydrake 1.51.1). Groups
declared at global scope exist only in model directives. Left out: the
ambiguous rigid/deformable body name (reimpl has no deformable bodies).
"""

from __future__ import annotations

import copy
from pathlib import Path
from types import ModuleType

import pytest

from tests.upstream.parsing_support import Parsing, fact_holds_for, invalid_directive, write


def _sphere_link(name: str) -> str:
    return (
        f"<link name='{name}'><collision name='{name}'><geometry><sphere radius='1'/>"
        "</geometry></collision></link>"
    )


def _sdf_link(name: str) -> str:
    return (
        f"<link name='{name}'><collision name='{name}'><geometry><sphere><radius>1</radius>"
        "</sphere></geometry></collision></link>"
    )


def _urdf(name: str, body: str) -> str:
    return f"<robot name='{name}'>\n{body}</robot>\n"


def _sdf(body: str) -> str:
    return f"<?xml version='1.0'?>\n<sdf version='1.9'>\n{body}</sdf>\n"


def _raises(parsing: Parsing, text: str, file_type: str) -> str:
    with pytest.raises(RuntimeError) as info:
        parsing.add(text, file_type)
    return str(info.value)


# ------------------------------------------------------ collision_filter_groups_test.cc
class TestCollisionFilterGroups:
    def test_a_new_value_is_empty_and_adding_a_group_makes_it_non_empty(
        self, drake: ModuleType
    ) -> None:
        """Lifecycle: pydrake binds no copy or move, only the constructor."""
        original = drake.multibody.parsing.CollisionFilterGroups()
        assert original.empty()
        donor = drake.multibody.parsing.CollisionFilterGroups()
        donor.AddGroup(name="a", members={"b"})
        assert not donor.empty()

    def test_the_value_is_not_copyable(self, drake: ModuleType) -> None:
        groups = drake.multibody.parsing.CollisionFilterGroups()
        with pytest.raises(TypeError, match="cannot pickle"):
            copy.copy(groups)

    def test_contents_compare_equal_whatever_the_order_they_were_added_in(
        self, drake: ModuleType
    ) -> None:
        """ContentsAndComparison, on the contents (``==`` is identity in pydrake)."""
        parsing = drake.multibody.parsing
        nothing = parsing.CollisionFilterGroups()
        assert nothing.empty()
        a_group = parsing.CollisionFilterGroups()
        a_group.AddGroup(name="a", members={"b"})
        assert not a_group.empty()
        assert a_group.groups() != nothing.groups()
        a_pair = parsing.CollisionFilterGroups()
        a_pair.AddExclusionPair(pair=("c", "d"))
        assert not a_pair.empty()
        assert a_pair.exclusion_pairs() != nothing.exclusion_pairs()
        assert a_pair.groups() == {}

        forward = parsing.CollisionFilterGroups()
        backward = parsing.CollisionFilterGroups()
        forward.AddGroup(name="m", members={"n", "o", "p"})
        forward.AddGroup(name="k", members={"l"})
        backward.AddGroup(name="k", members={"l"})
        backward.AddGroup(name="m", members={"p", "o", "n"})
        forward.AddExclusionPair(pair=("e", "f"))
        forward.AddExclusionPair(pair=("g", "h"))
        backward.AddExclusionPair(pair=("g", "h"))
        backward.AddExclusionPair(pair=("e", "f"))
        assert forward.groups() == backward.groups() == {"k": {"l"}, "m": {"n", "o", "p"}}
        assert forward.exclusion_pairs() == backward.exclusion_pairs() == {("e", "f"), ("g", "h")}
        assert str(forward) == str(backward)
        # N.B. pydrake binds no comparison: two values are equal only if they are one.
        assert forward != backward

    def test_a_pair_is_stored_sorted(self, drake: ModuleType) -> None:
        groups = drake.multibody.parsing.CollisionFilterGroups()
        groups.AddExclusionPair(pair=("z", "a"))
        groups.AddExclusionPair(pair=("a", "z"))
        assert groups.exclusion_pairs() == {("a", "z")}

    def test_dump_lists_groups_members_and_pairs(self, drake: ModuleType) -> None:
        stuff = drake.multibody.parsing.CollisionFilterGroups()
        stuff.AddGroup(name="q", members={"r", "s"})
        stuff.AddGroup(name="v", members={"w", "x", "y"})
        stuff.AddExclusionPair(pair=("q", "v"))
        assert str(stuff) == (
            "\nCollision filter groups:\n"
            "    q\n        r\n        s\n"
            "    v\n        w\n        x\n        y\n"
            "Collision filter exclusion pairs:\n"
            "    q, v\n"
        )

    def test_adding_a_group_name_twice_ends_the_program(self, drake: ModuleType) -> None:
        """Drake's DRAKE_THROW_UNLESS, which pydrake raises as SystemExit."""
        groups = drake.multibody.parsing.CollisionFilterGroups()
        groups.AddGroup(name="a", members={"b"})
        with pytest.raises(SystemExit) as info:
            groups.AddGroup(name="a", members={"c"})
        assert str(info.value) == (
            "Failure at external/drake+/multibody/parsing/"
            "detail_collision_filter_groups_impl.cc:24 in AddGroup(): "
            "condition '!groups_.contains(name)' failed."
        )
        assert groups.groups() == {"a": {"b"}}

    def test_a_group_may_be_empty(self, drake: ModuleType) -> None:
        groups = drake.multibody.parsing.CollisionFilterGroups()
        groups.AddGroup(name="a", members=set())
        assert not groups.empty()
        assert groups.groups() == {"a": set()}

    def test_members_are_a_set(self, drake: ModuleType) -> None:
        """pydrake 1.51.1 takes a set only; 1.58.0 also takes a list (measured; release
        fact add-group-members-iterable-since-1.58)."""
        groups = drake.multibody.parsing.CollisionFilterGroups()
        if not fact_holds_for(drake, "add-group-members-iterable-since-1.58"):
            with pytest.raises(TypeError, match=r"^AddGroup\(\): incompatible function"):
                groups.AddGroup(name="a", members=["b"])
        else:
            groups.AddGroup(name="a", members=["b"])
            assert groups.groups() == {"a": {"b"}}

    def test_merging_parses_keeps_every_group_and_pair(self, drake: ModuleType) -> None:
        """Merge and Convert: the Parser merges each parse's groups into its own."""
        parsing = Parsing(drake)
        group = (
            "<drake:collision_filter_group name='g'><drake:member link='a'/>"
            "<drake:ignored_collision_filter_group name='g'/></drake:collision_filter_group>"
        )
        parsing.add(_urdf("r1", _sphere_link("a") + group), "urdf")
        parsing.add(_urdf("r2", _sphere_link("a") + group), "urdf")
        assert parsing.groups() == (
            {"r1::g": {"r1::a"}, "r2::g": {"r2::a"}},
            {("r1::g", "r1::g"), ("r2::g", "r2::g")},
        )


# ------------------------------------------- detail_collision_filter_group_resolver_test.cc
_OPEN = "<drake:collision_filter_group name='{name}'>"
_CLOSE = "</drake:collision_filter_group>\n"


def _group(
    name: str,
    members: tuple[str, ...] = (),
    *,
    member_groups: tuple[str, ...] = (),
    ignored: tuple[str, ...] = (),
) -> str:
    parts = [f"<drake:member link='{m}'/>" for m in members]
    parts += [f"<drake:member_group name='{g}'/>" for g in member_groups]
    parts += [f"<drake:ignored_collision_filter_group name='{g}'/>" for g in ignored]
    return f"{_OPEN.format(name=name)}{''.join(parts)}{_CLOSE}"


def _sdf_group(
    name: str,
    members: tuple[str, ...] = (),
    *,
    member_groups: tuple[str, ...] = (),
    ignored: tuple[str, ...] = (),
) -> str:
    parts = [f"<drake:member>{m}</drake:member>" for m in members]
    parts += [f"<drake:member_group>{g}</drake:member_group>" for g in member_groups]
    parts += [
        f"<drake:ignored_collision_filter_group>{g}</drake:ignored_collision_filter_group>"
        for g in ignored
    ]
    return f"{_OPEN.format(name=name)}{''.join(parts)}{_CLOSE}"


def _box_models(tmp_path: Path, parsing: Parsing, *names: str) -> str:
    """Directives text adding one URDF robot per name, each with body ``body``."""
    write(tmp_path, "box.urdf", _urdf("box", _sphere_link("body")))
    parsing.parser.package_map().Add(package_name="boxes", package_path=str(tmp_path))
    return "directives:\n" + "".join(
        f"- add_model: {{name: {name}, file: package://boxes/box.urdf}}\n" for name in names
    )


class TestResolver:
    def test_a_pair_naming_an_unknown_scoped_group_is_reported_with_its_full_name(
        self, drake: ModuleType
    ) -> None:
        """BogusPairScoped: names in a model are read in that model."""
        parsing = Parsing(drake)
        text = _sdf(
            "<model name='r1'>\n"
            + _sdf_link("x")
            + _sdf_group("a", ("x",), ignored=("sub::b",))
            + "</model>\n"
        )
        assert _raises(parsing, text, "sdf") == (
            "error: collision filter group with name 'r1::sub::b' not found"
        )

    def test_a_pair_naming_an_unknown_global_group_is_reported_with_its_name(
        self, drake: ModuleType, tmp_path: Path
    ) -> None:
        """BogusPairGlobal."""
        parsing = Parsing(drake)
        text = _box_models(tmp_path, parsing, "m") + (
            "- add_collision_filter_group:\n"
            "    {name: a, members: [m::body], ignored_collision_filter_groups: [b]}\n"
        )
        assert _raises(parsing, text, "dmd.yaml") == (
            "error: collision filter group with name 'b' not found"
        )

    @pytest.mark.parametrize("file_type", ["urdf", "sdf"])
    def test_a_group_name_must_not_be_scoped(self, drake: ModuleType, file_type: str) -> None:
        """BogusGroupName."""
        parsing = Parsing(drake)
        if file_type == "urdf":
            text = _urdf("r1", _sphere_link("x") + _group("haha::a", ("x",)))
            where = "<literal-string>.urdf:1"
        else:
            text = _sdf(
                "<model name='r1'>\n"
                + _sdf_link("x")
                + _sdf_group("haha::a", ("x",))
                + "</model>\n"
            )
            where = "<literal-string>.sdf:3"
        assert _raises(parsing, text, file_type) == (
            f"{where}: error: group name 'r1::haha::a' cannot be a scoped name"
        )

    def test_a_global_group_without_members_is_an_invalid_directive(
        self, drake: ModuleType
    ) -> None:
        """EmptyGroupGlobal: model directives refuse it before any group is declared."""
        parsing = Parsing(drake)
        problem = (
            "add_collision_filter_group: at least one of `members` or `member_groups` must be "
            "non-empty"
        )
        with invalid_directive(drake, problem):
            parsing.add("directives:\n- add_collision_filter_group: {name: a}\n", "dmd.yaml")

    @pytest.mark.parametrize("model", ["r1", "r2"])
    def test_a_group_without_members_is_reported_with_its_scoped_name(
        self, drake: ModuleType, model: str
    ) -> None:
        """EmptyGroupsScoped."""
        parsing = Parsing(drake)
        text = _urdf(model, _sphere_link("x") + _group("a"))
        assert _raises(parsing, text, "urdf") == (
            f"<literal-string>.urdf:1: error: group '{model}::a' has no members"
        )

    @pytest.mark.parametrize(
        ("member", "message"),
        [
            ("abody", "body with name 'abody' not found"),
            ("r1::abody", "body with name 'r1::abody' not found"),
            # AddGroup() does not choke on an instance name that does not exist.
            ("zzz::abody", "body with name 'zzz::abody' not found"),
        ],
    )
    def test_a_missing_body_of_a_global_group_is_reported_as_written(
        self, drake: ModuleType, member: str, message: str
    ) -> None:
        """MissingBodyGlobal, one member at a time (Drake raises the first error)."""
        parsing = Parsing(drake)
        text = (
            "directives:\n- add_model_instance: {name: r1}\n"
            f"- add_collision_filter_group: {{name: a, members: ['{member}']}}\n"
        )
        assert _raises(parsing, text, "dmd.yaml") == f"error: {message}"

    def test_the_members_of_a_group_are_checked_in_name_order(self, drake: ModuleType) -> None:
        """MissingBodyGlobal with all three: Drake checks a std::set, so 'abody' first."""
        parsing = Parsing(drake)
        text = (
            "directives:\n- add_model_instance: {name: r1}\n"
            "- add_collision_filter_group:\n"
            "    {name: a, members: [zzz::abody, r1::abody, abody]}\n"
        )
        assert _raises(parsing, text, "dmd.yaml") == "error: body with name 'abody' not found"

    @pytest.mark.parametrize("member_group", ["agroup", "r1::agroup", "zzz::agroup"])
    def test_a_missing_member_group_is_reported_when_the_parse_ends(
        self, drake: ModuleType, member_group: str
    ) -> None:
        """MissingMemberGroupGlobal: member groups are checked at resolution time."""
        parsing = Parsing(drake)
        text = (
            "directives:\n- add_model_instance: {name: r1}\n"
            f"- add_collision_filter_group: {{name: a, member_groups: ['{member_group}']}}\n"
        )
        assert _raises(parsing, text, "dmd.yaml") == (
            f"error: collision filter group with name '{member_group}' not found"
        )

    def test_a_group_defined_twice_is_reported_at_once(self, drake: ModuleType) -> None:
        """DuplicateGroupDefinitions: the redefinition fails before its members are resolved."""
        parsing = Parsing(drake)
        group = "- add_collision_filter_group: {name: a, member_groups: [agroup]}\n"
        text = "directives:\n- add_model_instance: {name: r1}\n" + group * 2
        assert _raises(parsing, text, "dmd.yaml") == "error: group 'a' has already been defined"

    @pytest.mark.parametrize(
        ("member", "message"),
        [
            (
                "DefaultModelInstance::stuff",
                "body name 'DefaultModelInstance::stuff' refers to a model outside the current "
                "parse",
            ),
            (
                "WorldModelInstance::world",
                "body name 'WorldModelInstance::world' refers to a model outside the current parse",
            ),
            # Unqualified body names at global scope are not looked up in the default model.
            ("stuff", "body with name 'stuff' not found"),
        ],
    )
    def test_bodies_outside_the_parse_are_refused(
        self, drake: ModuleType, member: str, message: str
    ) -> None:
        """OutOfParseBodyGlobal."""
        parsing = Parsing(drake)
        parsing.plant.AddRigidBody(name="stuff")
        text = f"directives:\n- add_collision_filter_group: {{name: a, members: ['{member}']}}\n"
        assert _raises(parsing, text, "dmd.yaml") == f"error: {message}"

    @pytest.mark.parametrize(
        ("member", "message"),
        [
            ("abody", "body with name 'r1::abody' not found"),
            ("sub::abody", "body with name 'r1::sub::abody' not found"),
            ("zzz::abody", "body with name 'r1::zzz::abody' not found"),
        ],
    )
    def test_a_missing_body_of_a_model_group_is_reported_with_its_scoped_name(
        self, drake: ModuleType, member: str, message: str
    ) -> None:
        """MissingBodyScoped, with the nested model ``r1::sub`` of SDFormat."""
        parsing = Parsing(drake)
        text = _sdf(
            "<model name='r1'>\n"
            + _sdf_link("x")
            + "<model name='sub'>"
            + _sdf_link("y")
            + "</model>\n"
            + _sdf_group("a", (member,))
            + "</model>\n"
        )
        assert _raises(parsing, text, "sdf") == f"<literal-string>.sdf:3: error: {message}"

    @pytest.mark.parametrize("member_group", ["agroup", "sub::agroup", "zzz::agroup"])
    def test_a_missing_member_group_of_a_model_group_is_reported_with_its_scoped_name(
        self, drake: ModuleType, member_group: str
    ) -> None:
        """MissingMemberGroupScoped."""
        parsing = Parsing(drake)
        text = _sdf(
            "<model name='r1'>\n"
            + _sdf_link("x")
            + "<model name='sub'>"
            + _sdf_link("y")
            + "</model>\n"
            + _sdf_group("a", member_groups=(member_group,))
            + "</model>\n"
        )
        assert _raises(parsing, text, "sdf") == (
            f"error: collision filter group with name 'r1::{member_group}' not found"
        )

    def test_a_global_group_names_bodies_by_their_scoped_names(
        self, drake: ModuleType, tmp_path: Path
    ) -> None:
        """GroupGlobalBodies."""
        parsing = Parsing(drake)
        text = _box_models(tmp_path, parsing, "r1", "r2") + (
            "- add_collision_filter_group: {name: a, members: [r1::body]}\n"
            "- add_collision_filter_group:\n"
            "    {name: b, members: [r2::body], ignored_collision_filter_groups: [a]}\n"
        )
        parsing.add(text, "dmd.yaml")
        assert parsing.groups() == ({"a": {"r1::body"}, "b": {"r2::body"}}, {("a", "b")})
        assert parsing.filtered("r1::body", "r2::body")

    def test_a_global_group_takes_member_groups_of_models(
        self, drake: ModuleType, tmp_path: Path
    ) -> None:
        """GroupGlobalMemberGroups: ``r1::ra`` is the group ``ra`` of model r1."""
        parsing = Parsing(drake)
        write(tmp_path, "ra.urdf", _urdf("ra", _sphere_link("body") + _group("ra", ("body",))))
        write(tmp_path, "rb.urdf", _urdf("rb", _sphere_link("body") + _group("rb", ("body",))))
        parsing.parser.package_map().Add(package_name="rs", package_path=str(tmp_path))
        text = (
            "directives:\n"
            "- add_model: {name: r1, file: package://rs/ra.urdf}\n"
            "- add_model: {name: r2, file: package://rs/rb.urdf}\n"
            "- add_collision_filter_group: {name: a, member_groups: [r1::ra]}\n"
            "- add_collision_filter_group:\n"
            "    {name: b, member_groups: [r2::rb], ignored_collision_filter_groups: [a]}\n"
        )
        parsing.add(text, "dmd.yaml")
        assert parsing.groups() == (
            {
                "a": {"r1::body"},
                "b": {"r2::body"},
                "r1::ra": {"r1::body"},
                "r2::rb": {"r2::body"},
            },
            {("a", "b")},
        )
        assert parsing.filtered("r1::body", "r2::body")

    def test_a_model_group_names_bodies_of_nested_models(self, drake: ModuleType) -> None:
        """LinkScoped: ``sub::abody`` inside r1 is body abody of model r1::sub."""
        parsing = Parsing(drake)
        text = _sdf(
            "<model name='r1'>\n"
            + _sdf_link("abody")
            + "<model name='sub'>"
            + _sdf_link("abody")
            + "</model>\n"
            + _sdf_group("a", ("abody", "sub::abody"), ignored=("a",))
            + "</model>\n"
        )
        parsing.add(text, "sdf")
        assert parsing.groups() == (
            {"r1::a": {"r1::abody", "r1::sub::abody"}},
            {("r1::a", "r1::a")},
        )
        assert parsing.filtered("r1::abody", "r1::sub::abody")

    def test_every_group_of_a_member_group_cycle_gets_every_member(self, drake: ModuleType) -> None:
        """MemberGroupCycle: group body{k} holds body{k} and member group body{k+1 mod 100}."""
        length = 100
        parsing = Parsing(drake)
        links = "".join(_sphere_link(f"body{k}") for k in range(length))
        groups = "".join(
            _group(f"body{k}", (f"body{k}",), member_groups=(f"body{(k + 1) % length}",))
            for k in range(length)
        )
        groups += _group("pair", ("body0",), ignored=(f"body{length - 1}",))
        parsing.add(_urdf("r1", links + groups), "urdf")
        every = {f"r1::body{k}" for k in range(length)}
        found, pairs = parsing.groups()
        assert {name: found[name] for name in found if name != "r1::pair"} == {
            f"r1::body{k}": every for k in range(length)
        }
        assert pairs == {("r1::body99", "r1::pair")}
        assert parsing.filtered("r1::body0", "r1::body99")

    def test_a_self_excluded_group_of_a_cycle_filters_all_its_bodies(
        self, drake: ModuleType
    ) -> None:
        """MemberGroupCycle's own pair: body99 ignores itself."""
        length = 100
        parsing = Parsing(drake)
        links = "".join(_sphere_link(f"body{k}") for k in range(length))
        groups = "".join(
            _group(
                f"body{k}",
                (f"body{k}",),
                member_groups=(f"body{(k + 1) % length}",),
                ignored=(f"body{k}",) if k == length - 1 else (),
            )
            for k in range(length)
        )
        parsing.add(_urdf("r1", links + groups), "urdf")
        assert parsing.groups()[1] == {("r1::body99", "r1::body99")}
        assert parsing.filtered("r1::body0", "r1::body99")
        assert parsing.filtered("r1::body0", "r1::body50")

    def test_deeply_nested_member_groups_hold_every_body_below_them(
        self, drake: ModuleType
    ) -> None:
        """MemberGroupDeepNest: group body{k} holds body{k} and member group body{k+1}."""
        depth = 100
        parsing = Parsing(drake)
        links = "".join(_sphere_link(f"body{k}") for k in range(depth))
        groups = "".join(
            _group(
                f"body{k}",
                (f"body{k}",),
                member_groups=(f"body{k + 1}",) if k + 1 < depth else (),
                ignored=("body0",) if k == 0 else (),
            )
            for k in range(depth)
        )
        parsing.add(_urdf("r1", links + groups), "urdf")
        found, pairs = parsing.groups()
        assert found == {
            f"r1::body{k}": {f"r1::body{m}" for m in range(k, depth)} for k in range(depth)
        }
        assert pairs == {("r1::body0", "r1::body0")}
        assert parsing.filtered("r1::body0", "r1::body99")
