"""reimpl.legacy: bitmask groups, cliques, RBT's auto cliques and the old URDF syntax.

Each class holds one rule of seeds 001-003 (or of drake-semantics.md §7),
quoted in its docstring.
"""

from __future__ import annotations

import importlib
import itertools
from pathlib import Path
from typing import Any

import pytest

from reimpl.legacy import (
    UNIVERSAL,
    BodyGraph,
    CollisionCliques,
    CollisionFilterGroups,
    DuplicateGroupError,
    JointEdge,
    LegacyFilter,
    LegacyUrdfError,
    TooManyGroupsError,
    UniversalGroupError,
    UnknownCliqueError,
    UnknownGroupError,
    UnknownLinkError,
    anchored_bodies,
    auto_cliques,
    format_mask,
    groups_to_cliques,
    legacy_model,
    mask_table,
    read_legacy_urdf,
    sorted_vectors_have_intersection,
    to_groups,
)

# Seed 003's example, with the member and ignore tags closed (the seed's rendering lost the
# slashes of <member link="body1"/>).
SEED_003_URDF = """<robot name="r">
  <link name="body1"><collision><geometry><sphere radius="1"/></geometry></collision></link>
  <link name="body2"><collision><geometry><sphere radius="1"/></geometry></collision></link>
  <link name="body3"><collision><geometry><sphere radius="1"/></geometry></collision></link>
  <link name="body4"><collision><geometry><sphere radius="1"/></geometry></collision></link>
  <collision_filter_group name="groupA">
    <member link="body1"/>
    <member link="body2"/>
    <ignored_collision_filter_group collision_filter_group="groupB"/>
  </collision_filter_group>
  <collision_filter_group name="groupB">
    <member link="body3"/>
    <member link="body4"/>
    <ignored_collision_filter_group collision_filter_group="groupA"/>
  </collision_filter_group>
</robot>
"""

#: Seed 003's table, row by row.
SEED_003_TABLE = [
    ("A", "membership", "0...0011"),
    ("A", "ignore", "0...0100"),
    ("B", "membership", "0...0101"),
    ("B", "ignore", "0...0010"),
]


def pair(a: str, b: str) -> frozenset[str]:
    return frozenset((a, b))


class TestSeed003BitmaskTable:
    """Seed 003: "groupA and groupB were assigned to bits 1 and 2 ... A membership
    0...0011, A ignore 0...0100, B membership 0...0101, B ignore 0...0010"; the
    groups filter the Cartesian product (1, 3), (1, 4), (2, 3), (2, 4)."""

    def test_the_table_reproduces_from_the_api(self) -> None:
        groups: CollisionFilterGroups[str] = CollisionFilterGroups()
        assert (groups.define_group("A"), groups.define_group("B")) == (1, 2)
        for member in ("body1", "body2"):
            groups.add_member("A", member)
        for member in ("body3", "body4"):
            groups.add_member("B", member)
        groups.ignore("A", "B")
        groups.ignore("B", "A")
        assert mask_table(groups) == SEED_003_TABLE
        assert format_mask(groups.membership_mask("body1")) == "0...0011"
        assert format_mask(groups.ignore_mask("body3")) == "0...0010"

    def test_the_table_reproduces_from_the_urdf_and_filters_the_product(self) -> None:
        model = legacy_model(read_legacy_urdf(SEED_003_URDF))
        rows = [
            (name.removeprefix("group"), kind, mask)
            for name, kind, mask in mask_table(model.groups)
        ]
        assert rows == SEED_003_TABLE
        e = {i: f"r::body{i}/Sphere" for i in range(1, 5)}
        assert model.groups.filtered_pairs(model.elements()) == {
            pair(e[1], e[3]),
            pair(e[1], e[4]),
            pair(e[2], e[3]),
            pair(e[2], e[4]),
        }

    def test_to_groups_of_the_product_gives_the_same_table(self) -> None:
        product = {pair(f"body{a}", f"body{b}") for a in (1, 2) for b in (3, 4)}
        groups = to_groups(product, [f"body{i}" for i in range(1, 5)])
        rows = [({"g1": "A", "g2": "B"}[n], kind, mask) for n, kind, mask in mask_table(groups)]
        assert rows == SEED_003_TABLE

    def test_the_seeds_literal_greedy_cliques_over_filter_body3_body4(self) -> None:
        """N.B. {a} ∪ groupB per member a of groupA (the seed's N cliques) also filters
        (body3, body4); the exact greedy mapping uses |A|·|B| two-element cliques here."""
        literal: CollisionCliques[str] = CollisionCliques()
        for a in ("body1", "body2"):
            clique = literal.new_clique()
            for e in (a, "body3", "body4"):
                literal.add_to_clique(e, clique)
        assert literal.is_filtered("body3", "body4")
        groups: CollisionFilterGroups[str] = CollisionFilterGroups()
        groups.define_group("A"), groups.define_group("B")
        for a, b in (("A", "body1"), ("A", "body2"), ("B", "body3"), ("B", "body4")):
            groups.add_member(a, b)
        groups.ignore("A", "B")
        exact = groups_to_cliques(groups, [f"body{i}" for i in range(1, 5)], "greedy")
        assert not exact.is_filtered("body3", "body4")
        assert exact.num_cliques == 4
        assert exact.max_cliques_per_element() == 2


class TestGroupsAreBitsOfA128BitMask:
    """Seed 001: "a pair of fixed-width bitmasks ... Each collision filter group
    corresponds to a single bit"; §7: 128 bits, bit 0 universal, ids from 1."""

    def test_127_user_groups_fit_and_the_129th_group_raises(self) -> None:
        groups: CollisionFilterGroups[str] = CollisionFilterGroups()
        assert groups.MAX_GROUPS == 128
        bits = [groups.define_group(f"g{i}") for i in range(127)]
        assert bits == list(range(1, 128))
        with pytest.raises(TooManyGroupsError, match=r"only 127 groups .* group 129"):
            groups.define_group("one_too_many")

    def test_a_name_is_defined_once_per_session_and_bits_survive_sessions(self) -> None:
        groups: CollisionFilterGroups[str] = CollisionFilterGroups()
        groups.define_group("g")
        with pytest.raises(DuplicateGroupError, match="duplicate collision filter group: g"):
            groups.define_group("g")
        groups.add_member("g", "a")
        groups.ignore("g", "g")
        groups.end_session()
        with pytest.raises(UnknownGroupError, match="not defined in this session"):
            groups.add_member("g", "b")
        assert groups.define_group("g") == 2
        groups.add_member(1, "b")  # A bit still works.
        assert groups.is_filtered("a", "b")

    def test_an_undefined_ignore_target_is_not_an_error_and_resolves_when_defined(self) -> None:
        groups: CollisionFilterGroups[str] = CollisionFilterGroups()
        groups.define_group("a")
        groups.add_member("a", "x")
        groups.ignore("a", "later")
        groups.ignore("a", "never")
        groups.define_group("later")
        groups.add_member("later", "y")
        assert groups.is_filtered("x", "y")
        groups.end_session()
        assert groups.undefined_ignores == (("a", "never"),)
        assert groups.is_filtered("x", "y")

    def test_bit_0_takes_no_members_or_ignores_and_unknown_bits_raise(self) -> None:
        groups: CollisionFilterGroups[str] = CollisionFilterGroups()
        with pytest.raises(UniversalGroupError):
            groups.add_member(UNIVERSAL, "a")
        with pytest.raises(UniversalGroupError):
            groups.ignore(0, 0)
        with pytest.raises(UnknownGroupError, match=r"bits 0\.\.0"):
            groups.add_member(1, "a")


class TestThePairRuleIsTheMaskFormula:
    """Seed 001: "the membership mask of each is ANDed with the ignore mask of the
    other. If either operation produces a non-zero result, the pair is filtered."""

    def test_masks_and_the_formula(self) -> None:
        groups: CollisionFilterGroups[str] = CollisionFilterGroups()
        a, b = groups.define_group("A"), groups.define_group("B")
        groups.add_member("A", "x")
        groups.add_member("B", "y")
        groups.add_member("B", "x")
        groups.ignore("B", "A")
        assert groups.membership_mask("x") == 1 | 1 << a | 1 << b
        assert groups.ignore_mask("y") == 1 << a
        assert groups.membership_mask("stranger") == 1
        assert groups.ignore_mask("stranger") == 0
        for p, q in itertools.permutations(["x", "y", "stranger"], 2):
            m_p, i_p = groups.membership_mask(p), groups.ignore_mask(p)
            m_q, i_q = groups.membership_mask(q), groups.ignore_mask(q)
            assert groups.is_filtered(p, q) == bool((m_p & i_q) | (m_q & i_p))
        assert groups.filtered_pairs(["x", "y", "stranger"]) == {pair("x", "y")}

    def test_membership_alone_filters_nothing(self) -> None:
        """Seed 001: "membership in a group does not guarantee inclusion in any filtered pair"."""
        groups: CollisionFilterGroups[str] = CollisionFilterGroups()
        groups.define_group("A")
        groups.add_member("A", "x")
        groups.add_member("A", "y")
        assert not groups.filtered_pairs(["x", "y"])
        groups.ignore("A", "A")  # "inclusion in its own ignore list would be sufficient"
        assert groups.filtered_pairs(["x", "y"]) == {pair("x", "y")}

    def test_ignoring_the_universal_group_makes_an_element_invisible(self) -> None:
        groups: CollisionFilterGroups[str] = CollisionFilterGroups()
        groups.define_group("hidden")
        groups.add_member("hidden", "ghost")
        groups.ignore("hidden", UNIVERSAL)
        others = ["a", "b", "c"]
        assert groups.filtered_pairs(["ghost", *others]) == {pair("ghost", o) for o in others}


class TestCliquesIntersectSortedIdLists:
    """Seed 002: "their two sets of cliques are intersected; a non-empty resultant set
    means that this pair is filtered ... O(n + m) ... short-circuit"."""

    def test_ids_are_kept_sorted_and_unknown_ids_raise(self) -> None:
        cliques: CollisionCliques[str] = CollisionCliques()
        ids = [cliques.new_clique() for _ in range(4)]
        assert ids == [0, 1, 2, 3]
        for clique in (3, 0, 2, 0):
            cliques.add_to_clique("a", clique)
        assert cliques.cliques_of("a") == (0, 2, 3)
        assert cliques.cliques_of("nobody") == ()
        assert cliques.members(0) == ("a",)
        with pytest.raises(UnknownCliqueError):
            cliques.add_to_clique("a", 4)

    def test_sharing_a_clique_filters_every_pair_of_it(self) -> None:
        cliques: CollisionCliques[str] = CollisionCliques()
        q, r = cliques.new_clique(), cliques.new_clique()
        for e in "abc":
            cliques.add_to_clique(e, q)
        cliques.add_to_clique("c", r)
        cliques.add_to_clique("d", r)
        assert cliques.filtered_pairs("abcde") == {
            pair("a", "b"),
            pair("a", "c"),
            pair("b", "c"),
            pair("c", "d"),
        }
        assert cliques.max_cliques_per_element() == 2

    @pytest.mark.parametrize(
        ("a", "b", "expected"),
        [
            ([], [1], False),  # empty: short-circuit
            ([1, 2], [3, 4], False),  # ranges apart: short-circuit
            ([10, 20, 30], [15, 25, 35], False),  # the seed's worst case: a full walk
            ([10, 20, 30], [15, 20, 35], True),
            ([5], [5], True),
        ],
    )
    def test_the_intersection_test(self, a: list[int], b: list[int], expected: bool) -> None:
        assert sorted_vectors_have_intersection(a, b) is expected
        assert sorted_vectors_have_intersection(b, a) is expected
        assert expected == bool(set(a) & set(b))


def _chain(*joints: tuple[str, str, str]) -> BodyGraph[str, str]:
    bodies = ["world", *dict.fromkeys(c for _, c, _ in joints)]
    elements = {b: (f"{b}/g",) for b in bodies}
    edges = tuple(JointEdge(f"{p}_{c}", p, c, t) for p, c, t in joints)
    return BodyGraph("world", tuple(bodies), elements, edges)


class TestAutoCliques:
    """Seed 002: "If a body has multiple collision elements, all of those elements are put
    into the same clique ... The collision elements of two bodies are all put into the
    same clique if the bodies are adjacent ... and the joint connecting them is not a
    floating joint"; §7: "The world was not exempt from adjacency"."""

    def test_adjacent_bodies_share_a_clique_and_the_world_is_not_exempt(self) -> None:
        graph = _chain(("world", "a", "revolute"), ("a", "b", "prismatic"), ("b", "c", "weld"))
        cliques = auto_cliques(graph)
        assert cliques.filtered_pairs(graph.all_elements()) == {
            pair("world/g", "a/g"),
            pair("a/g", "b/g"),
            pair("b/g", "c/g"),
        }

    @pytest.mark.parametrize("floating", ["quaternion_floating", "rpy_floating"])
    def test_a_floating_joint_makes_no_clique(self, floating: str) -> None:
        graph = _chain(("world", "a", floating), ("a", "b", floating))
        assert auto_cliques(graph).num_cliques == 0

    def test_one_bodys_elements_share_a_clique_unless_adjacency_covers_them(self) -> None:
        alone = BodyGraph("w", ("w", "b"), {"b": ("b1", "b2", "b3")}, ())
        cliques = auto_cliques(alone)
        assert cliques.num_cliques == 1
        assert cliques.filtered_pairs(["b1", "b2", "b3"]) == {
            pair("b1", "b2"),
            pair("b1", "b3"),
            pair("b2", "b3"),
        }
        joined = BodyGraph(
            "w",
            ("w", "b"),
            {"w": ("w1",), "b": ("b1", "b2")},
            (JointEdge("j", "w", "b", "revolute"),),
        )
        assert auto_cliques(joined).num_cliques == 1  # The adjacency clique holds b1 and b2.

    def test_a_body_without_elements_makes_no_clique(self) -> None:
        graph = BodyGraph(
            "w", ("w", "a", "b"), {"b": ("b1",)}, (JointEdge("j", "a", "b", "revolute"),)
        )
        assert auto_cliques(graph).num_cliques == 0

    def test_anchored_bodies_are_those_welded_to_the_world(self) -> None:
        graph = _chain(
            ("world", "a", "weld"), ("a", "b", "weld"), ("b", "c", "revolute"), ("c", "d", "weld")
        )
        assert anchored_bodies(graph) == {"world", "a", "b"}
        legacy = LegacyFilter(
            anchored=frozenset({"world/g", "a/g", "b/g"}), cliques=auto_cliques(graph)
        )
        assert legacy.is_filtered("world/g", "b/g")  # anchored, though not adjacent
        assert not legacy.is_filtered("b/g", "d/g")
        assert pair("b/g", "d/g") in legacy.candidate_pairs(graph.all_elements())


def _reimpl_plant() -> tuple[Any, dict[str, Any]]:
    """world -revolute- a -weld- b (two spheres) -quaternion floating- c; a world sphere."""
    geometry = importlib.import_module("reimpl.geometry")
    math = importlib.import_module("reimpl.math")
    plant_module = importlib.import_module("reimpl.multibody.plant")
    tree = importlib.import_module("reimpl.multibody.tree")
    plant = plant_module.MultibodyPlant(time_step=0.0)
    plant.RegisterAsSourceForSceneGraph(scene_graph=geometry.SceneGraph())
    bodies = {"world": plant.world_body()}
    for name in "abc":
        bodies[name] = plant.AddRigidBody(name=name)
    ids: dict[str, Any] = {}
    for body, names in (("world", ["floor"]), ("a", ["a"]), ("b", ["b1", "b2"]), ("c", ["c"])):
        for name in names:
            ids[name] = plant.RegisterCollisionGeometry(
                body=bodies[body],
                X_BG=math.RigidTransform(),
                shape=geometry.Sphere(radius=0.1),
                name=name,
                coulomb_friction=plant_module.CoulombFriction(
                    static_friction=1.0, dynamic_friction=1.0
                ),
            )
    frame = {n: b.body_frame() for n, b in bodies.items()}
    plant.AddJoint(
        tree.RevoluteJoint(
            name="ja",
            frame_on_parent=frame["world"],
            frame_on_child=frame["a"],
            axis=[0.0, 0.0, 1.0],
        )
    )
    plant.AddJoint(
        tree.WeldJoint(
            name="jb",
            frame_on_parent_F=frame["a"],
            frame_on_child_M=frame["b"],
            X_FM=math.RigidTransform(),
        )
    )
    plant.AddJoint(
        tree.QuaternionFloatingJoint(
            name="jc", frame_on_parent=frame["b"], frame_on_child=frame["c"]
        )
    )
    return plant, ids


class TestAutoCliquesOnAReimplPlant:
    """auto_cliques reads a reimpl MultibodyPlant (built in code or parsed from URDF)."""

    def test_a_plant_built_in_code(self) -> None:
        plant, ids = _reimpl_plant()
        names = {v.get_value(): k for k, v in ids.items()}
        cliques = auto_cliques(plant)
        filtered = {
            frozenset(names[g.get_value()] for g in p) for p in cliques.filtered_pairs(ids.values())
        }
        assert filtered == {
            pair("floor", "a"),  # world adjacency
            pair("a", "b1"),
            pair("a", "b2"),
            pair("b1", "b2"),
        }

    def test_a_plant_parsed_from_urdf(self) -> None:
        parsing = pytest.importorskip("reimpl.multibody.parsing")
        geometry = importlib.import_module("reimpl.geometry")
        plant_module = importlib.import_module("reimpl.multibody.plant")
        plant = plant_module.MultibodyPlant(time_step=0.0)
        plant.RegisterAsSourceForSceneGraph(scene_graph=geometry.SceneGraph())
        parsing.Parser(plant=plant).AddModelsFromString(
            file_contents=SEED_003_URDF, file_type="urdf"
        )
        plant.Finalize()  # Free bodies get quaternion floating joints: no cliques.
        assert auto_cliques(plant).num_cliques == 0
        text = SEED_003_URDF.replace(
            "<collision_filter_group",
            '<joint name="j" type="revolute"><parent link="body1"/><child link="body2"/></joint>'
            "<collision_filter_group",
            1,
        )
        plant = plant_module.MultibodyPlant(time_step=0.0)
        plant.RegisterAsSourceForSceneGraph(scene_graph=geometry.SceneGraph())
        parsing.Parser(plant=plant).AddModelsFromString(file_contents=text, file_type="urdf")
        assert auto_cliques(plant).num_cliques == 1


class TestTheUnprefixedUrdfSyntax:
    """Seed 001: "It is not considered an error to ignore a non-existing group, but it is
    considered an error to reference a link that hasn't been defined"; §7: groups are
    scoped per parse; drake_ignore="true" skips."""

    def robot(self, body: str) -> str:
        links = "".join(
            f'<link name="{n}"><collision><geometry><box size="1 1 1"/></geometry>'
            "</collision></link>"
            for n in ("a", "b")
        )
        return f'<robot name="r">{links}\n{body}\n</robot>'

    def test_an_unknown_link_is_an_error_naming_file_line_and_element(self) -> None:
        text = self.robot(
            '<collision_filter_group name="g">\n<member link="zz"/>\n</collision_filter_group>'
        )
        with pytest.raises(
            UnknownLinkError,
            match=r'^m\.urdf:3: <member link="zz"> of <collision_filter_group name="g">: '
            r"robot 'r' has no link named 'zz'",
        ):
            read_legacy_urdf(text, "m.urdf")

    @pytest.mark.parametrize(
        ("body", "message"),
        [
            (
                "<collision_filter_group/>",
                'the collision filter group does not specify the required attribute "name"',
            ),
            (
                '<collision_filter_group name="g"><member/></collision_filter_group>',
                'required attribute "link"',
            ),
            (
                '<collision_filter_group name="g"><ignored_collision_filter_group/>'
                "</collision_filter_group>",
                'required attribute "collision_filter_group"',
            ),
            (
                '<collision_filter_group name="g"/><collision_filter_group name="g"/>',
                "already defined at line 2",
            ),
            ("<link>", "malformed XML"),
        ],
    )
    def test_malformed_groups_are_errors(self, body: str, message: str) -> None:
        with pytest.raises(LegacyUrdfError, match=message):
            read_legacy_urdf(self.robot(body), "m.urdf")

    def test_ignoring_an_undefined_group_is_fine_and_drake_ignore_skips_a_group(self) -> None:
        text = self.robot(
            '<collision_filter_group name="g"><member link="a"/><member link="b"/>'
            '<ignored_collision_filter_group collision_filter_group="g"/>'
            '<ignored_collision_filter_group collision_filter_group="nope"/>'
            "</collision_filter_group>"
            '<collision_filter_group name="skip" drake_ignore="true"><member link="zz"/>'
            "</collision_filter_group>"
        )
        model = legacy_model(read_legacy_urdf(text))
        assert model.groups.num_groups == 1
        assert model.groups.undefined_ignores == (("g", "nope"),)
        assert model.groups.filtered_pairs(model.elements()) == {pair("r::a/Box", "r::b/Box")}

    def test_groups_are_scoped_to_one_parse(self) -> None:
        text = self.robot(
            '<collision_filter_group name="g"><member link="a"/></collision_filter_group>'
        )
        shared: CollisionFilterGroups[str] = CollisionFilterGroups()
        legacy_model(read_legacy_urdf(text), "first", shared)
        legacy_model(read_legacy_urdf(text), "second", shared)  # No duplicate: a new session.
        assert [shared.name_of(b) for b in shared.bits()] == ["g", "g"]

    def test_drake_tags_need_no_namespace_and_geometry_names_follow_drake(self) -> None:
        text = """<robot name="r">
          <link name="a"><collision><geometry><sphere radius="1"/></geometry></collision>
            <collision><geometry><sphere radius="1"/></geometry></collision>
            <collision name="x"><geometry><drake:capsule radius="1" length="1"/></geometry>
            </collision>
          </link>
          <drake:collision_filter_group name="d"><drake:member link="a"/>
          </drake:collision_filter_group>
        </robot>"""
        urdf = read_legacy_urdf(text)
        assert urdf.links[0].collisions == ("Sphere", "Sphere_1", "x")
        assert [g.name for g in urdf.drake_groups] == ["d"]
        assert urdf.groups == ()

    def test_the_world_link_holds_anchored_elements(self) -> None:
        text = """<robot name="r">
          <link name="world"><collision><geometry><box size="1 1 1"/></geometry></collision></link>
          <link name="a"><collision><geometry><box size="1 1 1"/></geometry></collision></link>
          <link name="b"><collision><geometry><box size="1 1 1"/></geometry></collision></link>
          <joint name="ja" type="fixed"><parent link="world"/><child link="a"/></joint>
        </robot>"""
        model = legacy_model(read_legacy_urdf(text))
        assert model.anchored == {"WorldModelInstance::world", "r::a"}
        assert model.candidate_pairs() == {
            pair("WorldModelInstance::world/Box", "r::b/Box"),
            pair("r::a/Box", "r::b/Box"),
        }

    def test_a_missing_file_names_the_file(self, tmp_path: Path) -> None:
        from reimpl.legacy import load_legacy_urdf  # noqa: PLC0415

        with pytest.raises(LegacyUrdfError, match=r"nope\.urdf: cannot read the file"):
            load_legacy_urdf(tmp_path / "nope.urdf")
