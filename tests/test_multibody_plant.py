"""MultibodyPlant on reimpl and on real pydrake: building, reading back, Finalize's filters.

Every test runs on both implementations and asserts the value measured on
pydrake 1.51.1 (pydrake-observed.md §3, drake-semantics.md §5 and checklist
22-25), never mere agreement. Calls use pydrake's keyword names, so a
keyword reimpl lacks fails here. Candidate pairs are compared by name:
``body/geometry``, the two names of a pair sorted and joined by ``|``.

Setup unless stated: ``AddMultibodyPlantSceneGraph(builder, time_step=0.0)``;
bodies in model instance ``m``; each body has one sphere named ``c``.
"""

from __future__ import annotations

import importlib
from collections.abc import Iterable
from dataclasses import dataclass
from types import ModuleType
from typing import Any

import pytest

from reimpl._release import release
from reimpl.geometry import CollisionFilterScope, GeometrySet
from reimpl.multibody import tree
from reimpl.multibody._default_filters import ADJACENCY_RULE, default_collision_filters
from tests.conftest import IMPLEMENTATIONS


@dataclass(frozen=True)
class Modules:
    """One implementation's modules, named as in pydrake."""

    geometry: ModuleType
    math: ModuleType
    framework: ModuleType
    plant: ModuleType
    tree: ModuleType


def modules(implementation: str) -> Modules:
    root = "pydrake" if implementation == "pydrake" else "reimpl"
    return Modules(
        *(
            importlib.import_module(f"{root}.{name}")
            for name in (
                "geometry",
                "math",
                "systems.framework",
                "multibody.plant",
                "multibody.tree",
            )
        )
    )


@pytest.fixture(params=IMPLEMENTATIONS)
def implementation(request: pytest.FixtureRequest) -> str:
    return str(request.param)


@pytest.fixture
def mb(implementation: str) -> Modules:
    return modules(implementation)


class Model:
    """A plant and its SceneGraph, built through the public API with names for everything."""

    def __init__(self, mb: Modules, *, instance: str = "m") -> None:
        self.mb = mb
        self.builder = mb.framework.DiagramBuilder()
        self.plant, self.scene_graph = mb.plant.AddMultibodyPlantSceneGraph(
            builder=self.builder, time_step=0.0
        )
        self.instance = self.plant.AddModelInstance(name=instance)
        self.bodies: dict[str, Any] = {"world": self.plant.world_body()}
        self.names: dict[int, str] = {}

    def body(self, name: str, *, geometries: Iterable[str] = ("c",)) -> Any:
        body = self.plant.AddRigidBody(name=name, model_instance=self.instance)
        self.bodies[name] = body
        for geometry in geometries:
            self.geometry(name, geometry)
        return body

    def geometry(self, body: str, name: str) -> Any:
        geometry_id = self.plant.RegisterCollisionGeometry(
            body=self.bodies[body],
            X_BG=self.mb.math.RigidTransform(),
            shape=self.mb.geometry.Sphere(radius=0.1),
            name=name,
            coulomb_friction=self.mb.plant.CoulombFriction(),
        )
        self.names[geometry_id.get_value()] = f"{body}/{name}"
        return geometry_id

    def anchored_from_other_source(self, name: str) -> Any:
        """An anchored proximity sphere registered by another source, ``other``."""
        g = self.mb.geometry
        source = self.scene_graph.RegisterSource(name="other")
        instance = g.GeometryInstance(
            X_PG=self.mb.math.RigidTransform(), shape=g.Sphere(radius=0.1), name=name
        )
        geometry_id = self.scene_graph.RegisterAnchoredGeometry(source_id=source, geometry=instance)
        self.scene_graph.AssignRole(
            source_id=source, geometry_id=geometry_id, properties=g.ProximityProperties()
        )
        self.names[geometry_id.get_value()] = f"other/{name}"
        return geometry_id

    def frame(self, body: str) -> Any:
        return self.bodies[body].body_frame()

    def joint(self, kind: str, parent: str, child: str, name: str | None = None) -> Any:
        """Adds a joint of ``kind`` (a key of JOINTS) from ``parent`` to ``child``."""
        joint = JOINTS[kind](
            self.mb, name or f"{parent}_{child}", self.frame(parent), self.frame(child)
        )
        return self.plant.AddJoint(joint=joint)

    def weld(self, parent: str, child: str) -> Any:
        return self.plant.WeldFrames(
            frame_on_parent_F=self.frame(parent), frame_on_child_M=self.frame(child)
        )

    def finalize(self) -> None:
        self.plant.Finalize()

    def C(self) -> set[str]:
        """The model's candidate pairs, by name."""
        pairs = self.scene_graph.model_inspector().GetCollisionCandidates()
        return {
            "|".join(sorted((self.names[a.get_value()], self.names[b.get_value()])))
            for a, b in pairs
        }

    def joint_names(self) -> list[tuple[str, str]]:
        joints = (self.plant.get_joint(joint_index=i) for i in self.plant.GetJointIndices())
        return [(j.name(), j.type_name()) for j in joints]


Z_AXIS = [0.0, 0.0, 1.0]


#: Joint constructors, called with pydrake's keyword names.
JOINTS: dict[str, Any] = {
    "revolute": lambda mb, n, p, c: mb.tree.RevoluteJoint(
        name=n, frame_on_parent=p, frame_on_child=c, axis=Z_AXIS
    ),
    "prismatic": lambda mb, n, p, c: mb.tree.PrismaticJoint(
        name=n, frame_on_parent=p, frame_on_child=c, axis=Z_AXIS
    ),
    "weld": lambda mb, n, p, c: mb.tree.WeldJoint(
        name=n, frame_on_parent_F=p, frame_on_child_M=c, X_FM=mb.math.RigidTransform()
    ),
    "ball_rpy": lambda mb, n, p, c: mb.tree.BallRpyJoint(
        name=n, frame_on_parent=p, frame_on_child=c
    ),
    "universal": lambda mb, n, p, c: mb.tree.UniversalJoint(
        name=n, frame_on_parent=p, frame_on_child=c
    ),
    "planar": lambda mb, n, p, c: mb.tree.PlanarJoint(name=n, frame_on_parent=p, frame_on_child=c),
    "quaternion_floating": lambda mb, n, p, c: mb.tree.QuaternionFloatingJoint(
        name=n, frame_on_parent=p, frame_on_child=c
    ),
    "rpy_floating": lambda mb, n, p, c: mb.tree.RpyFloatingJoint(
        name=n, frame_on_parent=p, frame_on_child=c
    ),
}


# ------------------------------------------------------------ §3's table


@dataclass(frozen=True)
class Row:
    """One row of pydrake-observed.md §3: bodies, joints, flags, and the measured C."""

    label: str
    bodies: str
    joints: tuple[tuple[str, str, str], ...]
    C: frozenset[str]
    geometries: tuple[tuple[str, int], ...] = ()
    world_geometry: bool = False
    adjacent: bool = True


def _pairs(*pairs: str) -> frozenset[str]:
    return frozenset(pairs)


SECTION_3 = (
    Row("revolute A->B, C free", "ABC", (("revolute", "A", "B"),), _pairs("A/c|C/c", "B/c|C/c")),
    Row("weld A->B, C free", "ABC", (("weld", "A", "B"),), _pairs("A/c|C/c", "B/c|C/c")),
    Row("two free bodies", "AB", (), _pairs("A/c|B/c")),
    Row(
        "weld chain A-B-C, revolute C->D",
        "ABCD",
        (("weld", "A", "B"), ("weld", "B", "C"), ("revolute", "C", "D")),
        _pairs("A/c|D/c", "B/c|D/c"),
    ),
    Row(
        "revolute chain A->B->C",
        "ABC",
        (("revolute", "A", "B"), ("revolute", "B", "C")),
        _pairs("A/c|C/c"),
    ),
    Row(
        "world geometry; A, B welded to world; C revolute from world",
        "ABC",
        (("weld", "world", "A"), ("weld", "world", "B"), ("revolute", "world", "C")),
        _pairs("A/c|C/c", "B/c|C/c", "C/c|world/Wg"),
        world_geometry=True,
    ),
    Row(
        "world geometry; A welded to world; B revolute from A",
        "AB",
        (("weld", "world", "A"), ("revolute", "A", "B")),
        _pairs("B/c|world/Wg"),
        world_geometry=True,
    ),
    Row(
        "A with 3 geometries, B with 2, both free",
        "AB",
        (),
        _pairs(*(f"A/a{i}|B/b{j}" for i in range(3) for j in range(2))),
        geometries=(("A", 3), ("B", 2)),
    ),
    Row(
        "A with 2 geometries revolute to B with 2",
        "AB",
        (("revolute", "A", "B"),),
        _pairs(),
        geometries=(("A", 2), ("B", 2)),
    ),
    Row(
        "revolute A->B, weld B->C",
        "ABC",
        (("revolute", "A", "B"), ("weld", "B", "C")),
        _pairs("A/c|C/c"),
    ),
    Row(
        "adjacency off: revolute A->B, weld B->C",
        "ABC",
        (("revolute", "A", "B"), ("weld", "B", "C")),
        _pairs("A/c|B/c", "A/c|C/c"),
        adjacent=False,
    ),
    Row(
        "explicit QuaternionFloatingJoint A->B",
        "AB",
        (("quaternion_floating", "A", "B"),),
        _pairs("A/c|B/c"),
    ),
    Row(
        "world geometry; prismatic world->A",
        "A",
        (("prismatic", "world", "A"),),
        _pairs("A/c|world/Wg"),
        world_geometry=True,
    ),
)


def build(mb: Modules, row: Row) -> Model:
    model = Model(mb)
    counts = dict(row.geometries)
    for name in row.bodies:
        if name in counts:
            model.body(name, geometries=[f"{name.lower()}{i}" for i in range(counts[name])])
        else:
            model.body(name)
    if row.world_geometry:
        model.geometry("world", "Wg")
    for kind, parent, child in row.joints:
        model.joint(kind, parent, child)
    model.plant.set_adjacent_bodies_collision_filters(value=row.adjacent)
    model.finalize()
    return model


@pytest.mark.parametrize("row", SECTION_3, ids=lambda row: row.label)
def test_finalize_leaves_the_measured_candidates(mb: Modules, row: Row) -> None:
    assert build(mb, row).C() == row.C


# ----------------------------------------------------- checklist 22-25


def two_bodies_joined_by(mb: Modules, kind: str) -> Model:
    model = Model(mb)
    model.body("A")
    model.body("B")
    model.joint(kind, "A", "B")
    model.finalize()
    return model


@pytest.mark.parametrize(
    ("kind", "filtered"),
    [
        ("revolute", True),
        ("prismatic", True),
        ("weld", True),
        ("ball_rpy", True),
        ("universal", True),
        ("planar", True),
        ("rpy_floating", True),
        ("quaternion_floating", False),
    ],
)
def test_a_joint_between_two_bodies_filters_them_unless_it_is_quaternion_floating(
    mb: Modules, kind: str, filtered: bool
) -> None:
    assert two_bodies_joined_by(mb, kind).C() == (set() if filtered else {"A/c|B/c"})


def test_a_revolute_joint_from_the_world_filters_nothing(mb: Modules) -> None:
    model = Model(mb)
    model.body("B")
    model.geometry("world", "Wg")
    model.joint("revolute", "world", "B")
    model.finalize()
    assert model.C() == {"B/c|world/Wg"}


def test_a_joint_to_a_world_child_filters_its_parent_against_all_anchored_geometry(
    mb: Modules,
) -> None:
    model = Model(mb)
    model.body("A")
    model.body("B")
    model.geometry("world", "Wg")
    model.anchored_from_other_source("O")
    model.joint("revolute", "A", "world")
    model.finalize()
    assert model.C() == {"A/c|B/c", "B/c|other/O", "B/c|world/Wg"}


def test_bodies_welded_to_the_world_are_filtered_against_another_sources_anchored_geometry(
    mb: Modules,
) -> None:
    """Checklist 23: W-B0 weld, B0-B1 weld, B1-B2 revolute."""
    model = Model(mb)
    for name in ("B0", "B1", "B2"):
        model.body(name)
    model.geometry("world", "Wg")
    model.anchored_from_other_source("O")
    model.weld("world", "B0")
    model.weld("B0", "B1")
    model.joint("revolute", "B1", "B2")
    model.finalize()
    assert model.C() == {"B0/c|B2/c", "B2/c|other/O", "B2/c|world/Wg"}


def test_without_adjacency_filters_only_the_weld_filters(mb: Modules) -> None:
    """Checklist 24: W-B0 revolute, B0-B1 revolute, B1-B2 weld, adjacency off."""
    model = Model(mb)
    for name in ("B0", "B1", "B2"):
        model.body(name)
    model.geometry("world", "Wg")
    model.joint("revolute", "world", "B0")
    model.joint("revolute", "B0", "B1")
    model.weld("B1", "B2")
    model.plant.set_adjacent_bodies_collision_filters(value=False)
    model.finalize()
    every_pair = {
        "|".join(sorted((a, b)))
        for a in ("B0/c", "B1/c", "B2/c", "world/Wg")
        for b in ("B0/c", "B1/c", "B2/c", "world/Wg")
        if a < b
    }
    assert model.C() == every_pair - {"B1/c|B2/c"}


def test_geometries_of_one_free_body_are_filtered_and_across_bodies_are_not(
    mb: Modules,
) -> None:
    """Checklist 25, before and after Finalize."""
    model = Model(mb)
    model.body("A", geometries=("a0", "a1"))
    model.body("B")
    assert model.C() == {"A/a0|B/c", "A/a1|B/c"}
    model.finalize()
    assert model.C() == {"A/a0|B/c", "A/a1|B/c"}


def test_adjacency_filters_are_in_the_model_and_reach_new_contexts(mb: Modules) -> None:
    model = Model(mb)
    model.body("A")
    model.body("B")
    model.body("C")
    model.joint("revolute", "A", "B")
    model.finalize()
    diagram = model.builder.Build()
    context = model.scene_graph.GetMyContextFromRoot(diagram.CreateDefaultContext())
    inspector = model.scene_graph.get_query_output_port().Eval(context).inspector()
    names = {
        "|".join(sorted((model.names[a.get_value()], model.names[b.get_value()])))
        for a, b in inspector.GetCollisionCandidates()
    }
    assert names == model.C() == {"A/c|C/c", "B/c|C/c"}


def test_anchored_geometry_registered_after_finalize_is_not_filtered(mb: Modules) -> None:
    """Filters resolve F(world) when Finalize applies them; later geometry is not covered."""
    model = Model(mb)
    model.body("A")
    model.weld("world", "A")
    model.finalize()
    model.anchored_from_other_source("late")
    assert model.C() == {"A/c|other/late"}


def test_finalize_filters_a_plant_registered_on_a_standalone_scene_graph(mb: Modules) -> None:
    scene_graph = mb.geometry.SceneGraph()
    plant = mb.plant.MultibodyPlant(time_step=0.0)
    plant.RegisterAsSourceForSceneGraph(scene_graph=scene_graph)
    bodies = [plant.AddRigidBody(name=name) for name in ("A", "B")]
    for body in bodies:
        plant.RegisterCollisionGeometry(
            body=body,
            X_BG=mb.math.RigidTransform(),
            shape=mb.geometry.Sphere(radius=0.1),
            name=f"{body.name()}c",
            coulomb_friction=mb.plant.CoulombFriction(),
        )
    plant.WeldFrames(
        frame_on_parent_F=bodies[0].body_frame(), frame_on_child_M=bodies[1].body_frame()
    )
    inspector = scene_graph.model_inspector()
    assert len(inspector.GetCollisionCandidates()) == 1
    plant.Finalize()
    assert inspector.GetCollisionCandidates() == set()


# ------------------------------------------------------ the adjacency flag

POST_FINALIZE = (
    "Post-finalize calls to '{}()' are not allowed; calls to this method must happen before "
    "Finalize()."
)


def test_adjacency_flag_is_true_by_default_and_settable(mb: Modules) -> None:
    plant = Model(mb).plant
    assert plant.get_adjacent_bodies_collision_filters() is True
    plant.set_adjacent_bodies_collision_filters(value=False)
    assert plant.get_adjacent_bodies_collision_filters() is False


def test_setting_the_adjacency_flag_after_finalize_raises(mb: Modules) -> None:
    plant = Model(mb).plant
    plant.Finalize()
    with pytest.raises(RuntimeError) as raised:
        plant.set_adjacent_bodies_collision_filters(value=False)
    assert str(raised.value) == POST_FINALIZE.format("set_adjacent_bodies_collision_filters")


# ------------------------------------------------------------- Finalize


def test_finalize_gives_each_free_tree_a_floating_joint_named_after_its_base(
    mb: Modules,
) -> None:
    model = Model(mb)
    for name in "XYZL":
        model.body(name)
    model.joint("revolute", "Z", "Y", name="zy")
    model.joint("revolute", "Y", "X", name="yx")
    model.finalize()
    # The reversed chain Z→Y→X has base Z; the lone L comes after every tree with a joint.
    assert model.joint_names() == [
        ("zy", "revolute"),
        ("yx", "revolute"),
        ("Z", "quaternion_floating"),
        ("L", "quaternion_floating"),
    ]
    assert model.plant.num_joints() == 4
    floating = model.plant.GetJointByName(name="Z")
    assert floating.parent_body().name() == "world"
    assert floating.child_body().name() == "Z"
    assert floating.model_instance() == model.instance


def test_the_base_of_a_free_tree_is_the_parent_of_the_most_joints(mb: Modules) -> None:
    """Bodies P..T; P→R, Q→S, Q→T, R→S: P and Q are no joint's child, Q has more children."""
    model = Model(mb)
    for name in "PQRST":
        model.body(name)
    for parent, child in ("PR", "QS", "QT", "RS"):
        model.joint("revolute", parent, child, name=f"{parent}{child}")
    model.finalize()
    assert [name for name, kind in model.joint_names() if kind == "quaternion_floating"] == ["Q"]


def test_a_floating_joint_name_gets_underscores_until_unique_in_its_instance(
    mb: Modules,
) -> None:
    model = Model(mb)
    model.body("X")
    model.body("Y")
    model.body("Q")
    model.joint("revolute", "X", "Y", name="X")
    model.joint("revolute", "Y", "Q", name="_X")
    model.finalize()
    assert model.joint_names()[-1] == ("__X", "quaternion_floating")


def test_finalize_twice_raises(mb: Modules) -> None:
    plant = Model(mb).plant
    plant.Finalize()
    with pytest.raises(RuntimeError) as raised:
        plant.Finalize()
    # Measured: 1.55.0 the first, 1.56.0 and 1.58.0 the second (both implementations
    # follow the installed release: tests/conftest.py).
    assert str(raised.value) == (
        "DeclareMiscContinuousState(): calls after Finalize() are not allowed."
        if release.has("finalize-repeat-wording-since-1.56")
        else "MultibodyTreeSystem::Finalize(): repeated calls not allowed."
    )
    assert plant.is_finalized() is True


def test_finalize_refuses_a_loop_of_welds(mb: Modules) -> None:
    model = Model(mb)
    model.body("X")
    model.body("Y")
    model.weld("world", "X")
    model.weld("X", "Y")
    model.weld("Y", "world")
    with pytest.raises(RuntimeError) as raised:
        model.finalize()
    # Measured with a three-link loop: 1.45.0-1.56.0 the first middle, 1.57.0 and 1.58.0
    # the second (loop-topology-wording-since-1.57).
    middle = (
        "Automatic modeling of such systems is disabled by default; you can enable it by "
        "calling MultibodyPlant::SetEnableLoopTopology(true) before Finalize() but: the "
        "feature is in development and not yet functional even when enabled. For now, loops "
        "can be modeled with some input changes."
        if release.has("loop-topology-wording-since-1.57")
        else "Drake currently does not support automatic modeling of such systems; however, "
        "they can be modeled with some input changes."
    )
    assert str(raised.value) == (
        "The bodies and joints of this system form one or more loops in the system graph. "
        f"{middle} See https://drake.mit.edu/troubleshooting.html#mbp-loops-in-graph for "
        "advice on how to model systems with loops."
    )


def test_finalize_refuses_a_ball_joint_it_would_have_to_reverse(mb: Modules) -> None:
    model = Model(mb)
    model.body("A")
    model.joint("ball_rpy", "A", "world", name="j")
    with pytest.raises(RuntimeError) as raised:
        model.finalize()
    assert str(raised.value) == (
        "MultibodyPlant::Finalize(): parent/child ordering for ball_rpy joint j in model "
        "instance WorldModelInstance would have to be reversed to make a tree-structured model "
        "for this system. Currently Drake does not support reversed ball_rpy joints. The joints "
        "that can be reversed are: prismatic, revolute, weld. Reverse the ordering in your joint "
        "definition so that its parent body is closer to World in the tree."
    )


def test_finalize_with_transient_history_is_finalized_but_unfiltered(mb: Modules) -> None:
    """The plant is sealed before Finalize applies its filters, and that Apply raises."""
    model = Model(mb)
    model.body("A")
    model.body("B")
    model.weld("A", "B")
    manager = model.scene_graph.collision_filter_manager()
    manager.ApplyTransient(declaration=mb.geometry.CollisionFilterDeclaration())
    with pytest.raises(RuntimeError) as raised:
        model.finalize()
    assert str(raised.value) == (
        "You cannot attempt to modify the persistent collision filter configuration when there "
        "are active, transient filter declarations"
    )
    assert model.plant.is_finalized() is True
    assert model.C() == {"A/c|B/c"}
    repeated = (  # finalize-repeat-wording-since-1.56 (measured on 1.55.0 and 1.56.0)
        "calls after Finalize"
        if release.has("finalize-repeat-wording-since-1.56")
        else "repeated calls not allowed"
    )
    with pytest.raises(RuntimeError, match=repeated):
        model.finalize()


@pytest.mark.parametrize(
    ("method", "call"),
    [
        ("AddRigidBody", lambda m: m.plant.AddRigidBody(name="late", model_instance=m.instance)),
        ("AddJoint", lambda m: m.joint("revolute", "A", "B")),
        ("AddJoint", lambda m: m.weld("A", "B")),
        ("RegisterCollisionGeometry", lambda m: m.geometry("A", "late")),
        (
            "RegisterVisualGeometry",
            lambda m: m.plant.RegisterVisualGeometry(
                body=m.bodies["A"],
                X_BG=m.mb.math.RigidTransform(),
                shape=m.mb.geometry.Sphere(radius=0.1),
                name="v",
                diffuse_color=[1.0, 1.0, 1.0, 1.0],
            ),
        ),
    ],
)
def test_building_after_finalize_raises(mb: Modules, method: str, call: Any) -> None:
    model = Model(mb)
    model.body("A")
    model.body("B")
    model.finalize()
    with pytest.raises(RuntimeError) as raised:
        call(model)
    assert str(raised.value) == POST_FINALIZE.format(method)


def test_adding_a_model_instance_after_finalize_raises(mb: Modules) -> None:
    plant = Model(mb).plant
    plant.Finalize()
    with pytest.raises(RuntimeError) as raised:
        plant.AddModelInstance(name="late")
    assert str(raised.value) == (
        "This MultibodyTree is finalized already. Therefore adding more model instances is not "
        "allowed. See documentation for Finalize() for details."
    )


# ------------------------------------------------------------ building


def test_add_multibody_plant_scene_graph_returns_a_named_plant_and_scene_graph(
    mb: Modules,
) -> None:
    builder = mb.framework.DiagramBuilder()
    result = mb.plant.AddMultibodyPlantSceneGraph(builder=builder, time_step=0.001)
    assert type(result) is tuple
    plant, scene_graph = result
    assert isinstance(plant, mb.plant.MultibodyPlant)
    assert isinstance(scene_graph, mb.geometry.SceneGraph)
    assert (plant.get_name(), scene_graph.get_name()) == ("plant", "scene_graph")
    assert plant.time_step() == 0.001
    assert plant.geometry_source_is_registered() is True
    assert scene_graph.model_inspector().GetName(plant.get_source_id()) == "plant"


def test_add_multibody_plant_scene_graph_uses_a_given_scene_graph_and_keeps_its_name(
    mb: Modules,
) -> None:
    scene_graph = mb.geometry.SceneGraph()
    scene_graph.set_name("mine")
    given = mb.plant.MultibodyPlant(time_step=0.0)
    given.set_name("renamed")
    plant, returned = mb.plant.AddMultibodyPlantSceneGraph(
        builder=mb.framework.DiagramBuilder(), plant=given, scene_graph=scene_graph
    )
    assert plant is given
    assert returned is scene_graph
    assert (plant.get_name(), returned.get_name()) == ("plant", "mine")


def test_add_multibody_plant_applies_a_config(mb: Modules) -> None:
    config = mb.plant.MultibodyPlantConfig(time_step=0.0, adjacent_bodies_collision_filters=False)
    plant, scene_graph = mb.plant.AddMultibodyPlant(
        config=config, builder=mb.framework.DiagramBuilder()
    )
    assert (plant.time_step(), plant.get_adjacent_bodies_collision_filters()) == (0.0, False)
    assert (plant.get_name(), scene_graph.get_name()) == ("plant", "scene_graph")
    assert repr(mb.plant.MultibodyPlantConfig()) == (
        "MultibodyPlantConfig(time_step=0.001, use_sampled_output_ports=True, "
        "penetration_allowance=0.001, stiction_tolerance=0.0001, "
        "contact_model='hydroelastic_with_fallback', discrete_contact_approximation='lagged', "
        "sap_near_rigid_threshold=1.0, contact_surface_representation='polygon', "
        "adjacent_bodies_collision_filters=True)"
    )


def test_a_new_plant_has_the_world_body_and_two_model_instances(mb: Modules) -> None:
    plant = mb.plant.MultibodyPlant(time_step=0.0)
    assert (plant.num_bodies(), plant.num_model_instances()) == (1, 2)
    assert (plant.num_joints(), plant.num_frames()) == (0, 1)
    assert plant.GetModelInstanceName(model_instance=mb.tree.world_model_instance()) == (
        "WorldModelInstance"
    )
    assert plant.GetModelInstanceName(model_instance=mb.tree.default_model_instance()) == (
        "DefaultModelInstance"
    )
    world = plant.world_body()
    assert (world.name(), int(world.index()), int(world.model_instance())) == ("world", 0, 0)
    assert repr(world) == "<RigidBody name='world' index=0 model_instance=0>"
    assert repr(plant.world_frame()) == "<RigidBodyFrame name='world' index=0 model_instance=0>"
    assert plant.get_source_id() is None
    assert plant.geometry_source_is_registered() is False


def test_bodies_and_their_frames_are_numbered_and_scoped(mb: Modules) -> None:
    model = Model(mb)
    body = model.body("A", geometries=())
    assert repr(body) == "<RigidBody name='A' index=1 model_instance=2>"
    assert str(body.scoped_name()) == "m::A"
    assert (body.body_frame().name(), int(body.body_frame().index())) == ("A", 1)
    assert model.plant.GetBodyByName(name="A") is body
    assert model.plant.get_body(body_index=body.index()) is body
    assert [int(i) for i in model.plant.GetBodyIndices(model_instance=model.instance)] == [1]
    assert model.plant.HasBodyNamed("A") is True
    assert model.plant.GetModelInstanceByName(name="m") == model.instance


def test_a_body_without_a_model_instance_needs_only_the_default_ones(mb: Modules) -> None:
    plant = mb.plant.MultibodyPlant(time_step=0.0)
    body = plant.AddRigidBody(name="A")
    assert int(body.model_instance()) == 1
    assert str(body.scoped_name()) == "DefaultModelInstance::A"
    plant.AddModelInstance(name="m")
    with pytest.raises(RuntimeError) as raised:
        plant.AddRigidBody(name="B")
    assert str(raised.value) == (
        "This model has more model instances than the default.  Please call AddRigidBody with "
        "an explicit model instance."
    )
    inertia = mb.tree.SpatialInertia.Zero()
    explicit = plant.AddRigidBody(
        name="B", model_instance=mb.tree.default_model_instance(), M_BBo_B=inertia
    )
    assert int(explicit.index()) == 2


def test_after_finalize_the_instance_count_is_checked_before_finalize_is(mb: Modules) -> None:
    plant = mb.plant.MultibodyPlant(time_step=0.0)
    plant.AddModelInstance(name="m")
    plant.Finalize()
    with pytest.raises(RuntimeError) as raised:
        plant.AddRigidBody(name="B")
    assert str(raised.value).startswith("This model has more model instances than the default.")


def test_num_collision_geometries_counts_the_collision_geometries_of_all_bodies(
    mb: Modules,
) -> None:
    model = Model(mb)
    model.body("A", geometries=())
    model.body("B", geometries=())
    assert model.plant.num_collision_geometries() == 0
    model.geometry("A", "a1")
    model.geometry("A", "a2")
    model.geometry("B", "b1")
    model.plant.RegisterVisualGeometry(
        body=model.bodies["B"],
        X_BG=mb.math.RigidTransform(),
        shape=mb.geometry.Sphere(radius=0.1),
        name="v",
        diffuse_color=[1.0, 1.0, 1.0, 1.0],
    )
    assert model.plant.num_collision_geometries() == 3
    model.finalize()
    assert model.plant.num_collision_geometries() == 3


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (
            lambda m: m.plant.AddRigidBody(name="A", model_instance=m.instance),
            "Model instance 'm' already contains a body named 'A'. Body names must be unique "
            "within a given model.",
        ),
        (
            lambda m: m.plant.AddModelInstance(name="m"),
            "This model already contains a model instance named 'm'. Model instance names must "
            "be unique within a given model.",
        ),
        (
            lambda m: m.plant.AddRigidBody(
                name="W", model_instance=m.mb.tree.world_model_instance()
            ),
            "AddLink(): Model instance index 0 is reserved for the World link.  World is always "
            "predefined and is named 'world'.",
        ),
        (
            lambda m: m.joint("revolute", "A", "B", name="A_B"),
            "Model instance 'm' already contains a joint named 'A_B'. Joint names must be unique "
            "within a given model.",
        ),
        (
            lambda m: m.joint("revolute", "B", "A", name="again"),
            "AddJoint(): This LinkJointGraph already has joint 'A_B' (model instance 2) "
            "connecting link 'A' to link 'B'. Therefore adding joint 'again' (model instance 2) "
            "connecting link 'B' to link 'A' is not allowed.",
        ),
        (
            lambda m: m.weld("A", "A"),
            "AddJoint(): joint A_welds_to_A would connect body A to itself.",
        ),
        (
            lambda m: m.geometry("A", "c"),
            "The name 'm::c' has already been used by a geometry with the 'proximity' role.",
        ),
    ],
    ids=[
        "duplicate body",
        "duplicate model instance",
        "body in the world instance",
        "duplicate joint",
        "second joint between two bodies",
        "weld to itself",
        "duplicate geometry",
    ],
)
def test_building_errors_are_drakes(mb: Modules, call: Any, message: str) -> None:
    model = Model(mb)
    model.body("A")
    model.body("B")
    model.joint("revolute", "A", "B")
    with pytest.raises(RuntimeError) as raised:
        call(model)
    assert str(raised.value) == message


def test_a_joint_belongs_to_its_child_bodys_model_instance(mb: Modules) -> None:
    model = Model(mb)
    model.body("A")
    default_body = model.plant.AddRigidBody(
        name="D", model_instance=mb.tree.default_model_instance()
    )
    model.bodies["D"] = default_body
    joint = model.joint("revolute", "A", "D", name="j")
    weld = model.weld("D", "world")
    assert repr(joint) == "<RevoluteJoint name='j' index=0 model_instance=1>"
    assert (weld.name(), int(weld.model_instance()), weld.type_name()) == (
        "D_welds_to_world",
        0,
        "weld",
    )
    assert [
        int(i) for i in model.plant.GetJointIndices(model_instance=mb.tree.world_model_instance())
    ] == [1]


def test_joint_type_names_and_dofs(mb: Modules) -> None:
    model = Model(mb)
    model.body("A", geometries=())
    model.body("B", geometries=())
    joints = [JOINTS[kind](mb, kind, model.frame("A"), model.frame("B")) for kind in JOINTS]
    assert [(j.type_name(), j.num_positions(), j.num_velocities()) for j in joints] == [
        ("revolute", 1, 1),
        ("prismatic", 1, 1),
        ("weld", 0, 0),
        ("ball_rpy", 3, 3),
        ("universal", 2, 2),
        ("planar", 3, 3),
        ("quaternion_floating", 7, 6),
        ("rpy_floating", 6, 6),
    ]


def test_a_fixed_offset_frame_joins_its_bodys_name_space(mb: Modules) -> None:
    model = Model(mb)
    model.body("A", geometries=())
    model.body("B", geometries=())
    frame = model.plant.AddFrame(
        frame=mb.tree.FixedOffsetFrame(name="F", P=model.frame("A"), X_PF=mb.math.RigidTransform())
    )
    assert repr(frame) == "<FixedOffsetFrame name='F' index=3 model_instance=2>"
    assert (str(frame.scoped_name()), frame.body().name()) == ("m::F", "A")
    assert model.plant.GetFrameByName(name="F", model_instance=model.instance) is frame
    joint = model.plant.AddJoint(joint=JOINTS["revolute"](mb, "j", frame, model.frame("B")))
    assert joint.parent_body().name() == "A"
    assert model.plant.num_frames() == 4
    with pytest.raises(RuntimeError) as raised:
        model.plant.AddFrame(
            frame=mb.tree.FixedOffsetFrame(
                name="B", bodyB=model.bodies["A"], X_BF=mb.math.RigidTransform()
            )
        )
    assert str(raised.value) == (
        "Model instance 'm' already contains a frame named 'B'. Frame names must be unique "
        "within a given model."
    )


# -------------------------------------------------------------- geometry


def test_geometry_names_are_scoped_by_model_instance_from_the_third_on(mb: Modules) -> None:
    model = Model(mb)
    model.body("A")
    default_body = model.plant.AddRigidBody(
        name="D", model_instance=mb.tree.default_model_instance()
    )
    model.bodies["D"] = default_body
    inspector = model.scene_graph.model_inspector()
    named = {
        "instance m": model.geometry("A", "x::y"),
        "default": model.geometry("D", "c"),
        "world": model.geometry("world", "c"),
    }
    assert {k: inspector.GetName(g) for k, g in named.items()} == {
        "instance m": "m::x::y",
        "default": "c",
        "world": "c",
    }
    frames = {
        inspector.GetName(f): inspector.GetFrameGroup(f)
        for f in inspector.GetAllFrameIds()
        if f != inspector.world_frame_id()
    }
    assert frames == {"m::A": 2, "D": 1}
    assert inspector.NumAnchoredGeometries() == 1


def test_a_duplicate_name_leaves_the_geometry_registered_without_a_role(mb: Modules) -> None:
    model = Model(mb)
    model.body("A")
    inspector = model.scene_graph.model_inspector()
    with pytest.raises(RuntimeError):
        model.geometry("A", "c")
    assert inspector.num_geometries() == 2
    assert inspector.NumGeometriesWithRole(role=mb.geometry.Role.kProximity) == 1
    assert [
        inspector.GetName(g)
        for g in model.plant.GetCollisionGeometriesForBody(body=model.bodies["A"])
    ] == ["m::c"]


def test_visual_geometry_has_the_illustration_and_perception_roles(mb: Modules) -> None:
    model = Model(mb)
    body = model.body("A", geometries=())
    g, math = mb.geometry, mb.math
    by_color = model.plant.RegisterVisualGeometry(
        body=body,
        X_BG=math.RigidTransform(),
        shape=g.Sphere(radius=0.1),
        name="v",
        diffuse_color=[0.5, 0.5, 0.5, 1.0],
    )
    instance = g.GeometryInstance(X_PG=math.RigidTransform(), shape=g.Sphere(radius=0.1), name="gi")
    by_instance = model.plant.RegisterVisualGeometry(body=body, geometry_instance=instance)
    inspector = model.scene_graph.model_inspector()
    assert [inspector.GetName(v) for v in model.plant.GetVisualGeometriesForBody(body=body)] == [
        "m::v",
        "m::gi",
    ]
    assert (by_instance, instance.name()) == (instance.id(), "gi")
    for geometry_id in (by_color, by_instance):
        assert inspector.GetProximityProperties(geometry_id) is None
        assert inspector.GetIllustrationProperties(geometry_id) is not None
        assert inspector.GetPerceptionProperties(geometry_id) is not None
    assert model.plant.GetCollisionGeometriesForBody(body=body) == []
    with pytest.raises(RuntimeError) as raised:
        model.plant.RegisterVisualGeometry(
            body=body,
            X_BG=math.RigidTransform(),
            shape=g.Sphere(radius=0.1),
            name="v",
            diffuse_color=[0.5, 0.5, 0.5, 1.0],
        )
    assert str(raised.value) == (
        "The name 'm::v' has already been used by a geometry with the 'illustration' role."
    )


def test_collision_geometries_are_listed_in_registration_order(mb: Modules) -> None:
    model = Model(mb)
    body = model.body("A", geometries=("c", "b", "a"))
    inspector = model.scene_graph.model_inspector()
    geometry_ids = model.plant.GetCollisionGeometriesForBody(body=body)
    assert [inspector.GetName(g) for g in geometry_ids] == ["m::c", "m::b", "m::a"]
    assert {inspector.GetFrameId(g) for g in geometry_ids} == {
        model.plant.GetBodyFrameIdOrThrow(body_index=body.index())
    }


# ------------------------------------------------------------ reading back


def test_body_frame_ids_map_to_bodies_and_back(mb: Modules) -> None:
    model = Model(mb)
    body = model.body("A")
    plant = model.plant
    frame_id = plant.GetBodyFrameIdOrThrow(body_index=body.index())
    assert plant.GetBodyFrameIdIfExists(body_index=body.index()) == frame_id
    assert plant.GetBodyFromFrameId(frame_id) is body
    world_frame_id = model.scene_graph.world_frame_id()
    assert plant.GetBodyFrameIdOrThrow(body_index=plant.world_body().index()) == world_frame_id
    assert plant.GetBodyFromFrameId(world_frame_id).name() == "world"
    assert plant.GetBodyFromFrameId(mb.geometry.FrameId.get_new_id()) is None
    assert plant.GetBodyFrameIdIfExists(body_index=mb.tree.BodyIndex(99)) is None
    with pytest.raises(TypeError):
        plant.GetBodyFromFrameId(frame_id=frame_id)


def test_body_frame_ids_of_an_unregistered_plant(mb: Modules) -> None:
    plant = mb.plant.MultibodyPlant(time_step=0.0)
    body = plant.AddRigidBody(name="X")
    assert plant.GetBodyFrameIdIfExists(body_index=body.index()) is None
    assert plant.GetCollisionGeometriesForBody(body=body) == []
    with pytest.raises(RuntimeError) as raised:
        plant.GetBodyFrameIdOrThrow(body_index=body.index())
    assert str(raised.value) == "Body 'X' does not have geometry registered with it."
    with pytest.raises(RuntimeError) as raised:
        plant.GetBodyFrameIdOrThrow(body_index=mb.tree.BodyIndex(99))
    assert str(raised.value) == (
        "The given RigidBodyIndex(99) is out of bounds (must be less than 2)"
    )
    scene_graph = mb.geometry.SceneGraph()
    plant.RegisterAsSourceForSceneGraph(scene_graph=scene_graph)
    frame_id = plant.GetBodyFrameIdOrThrow(body_index=body.index())
    assert scene_graph.model_inspector().GetName(frame_id) == "X"


def test_collect_registered_geometries_holds_body_frames_resolved_when_applied(
    mb: Modules,
) -> None:
    """F(world) resolves to every anchored geometry, this plant's or not."""
    model = Model(mb)
    model.body("A")
    model.body("B")
    model.geometry("world", "Wg")
    model.anchored_from_other_source("O")
    plant = model.plant
    both = plant.CollectRegisteredGeometries(bodies=[model.bodies["A"], plant.world_body()])
    declaration = mb.geometry.CollisionFilterDeclaration().ExcludeWithin(geometry_set=both)
    model.scene_graph.collision_filter_manager().Apply(declaration=declaration)
    assert model.C() == {"A/c|B/c", "B/c|other/O", "B/c|world/Wg"}


def test_bodies_welded_to_a_body_include_itself_in_index_order(mb: Modules) -> None:
    model = Model(mb)
    for name in "ABCD":
        model.body(name, geometries=())
    model.weld("C", "A")
    model.joint("revolute", "A", "B")
    model.weld("world", "D")

    def welded(body: Any) -> list[str]:
        return [b.name() for b in model.plant.GetBodiesWeldedTo(body=body)]

    assert welded(model.bodies["A"]) == ["A", "C"]
    assert welded(model.bodies["B"]) == ["B"]
    assert welded(model.plant.world_body()) == ["world", "D"]
    model.finalize()
    assert welded(model.bodies["C"]) == ["A", "C"]


@pytest.mark.parametrize(
    ("case", "call", "message"),
    [
        (
            "no body anywhere",
            lambda p, m: p.GetBodyByName(name="nope"),
            "GetRigidBodyByName(): There is no RigidBody named 'nope' anywhere in the model "
            "(valid names in model instance 'WorldModelInstance' are: world; valid names in "
            "model instance 'DefaultModelInstance' are: B; valid names in model instance 'm' are: "
            "B, Z, a)",
        ),
        (
            "body in another instance",
            lambda p, m: p.GetBodyByName(
                name="Z", model_instance=p.GetModelInstanceByName("DefaultModelInstance")
            ),
            "GetRigidBodyByName(): There is no RigidBody named 'Z' in the model instance named "
            "'DefaultModelInstance', but one does exist in other model instances (m).",
        ),
        (
            "body in two instances",
            lambda p, m: p.GetBodyByName(name="B"),
            "GetRigidBodyByName(): A RigidBody named 'B' appears in multiple model instances "
            "(DefaultModelInstance, m); you must provide a model_instance argument to "
            "disambiguate.",
        ),
        (
            "no frame anywhere",
            lambda p, m: p.GetFrameByName(name="nope", model_instance=m),
            "GetFrameByName(): There is no Frame named 'nope' anywhere in the model (valid names "
            "in model instance 'WorldModelInstance' are: world; valid names in model instance "
            "'DefaultModelInstance' are: B; valid names in model instance 'm' are: B, Z, a)",
        ),
        (
            "no joint at all",
            lambda p, m: p.GetJointByName(name="nope"),
            "GetJointByName(): There are no Joints defined in the model",
        ),
        (
            "no such model instance",
            lambda p, m: p.GetModelInstanceByName(name="nope"),
            "GetModelInstanceByName(): There is no model instance named 'nope'. The current "
            "model instances are 'DefaultModelInstance', 'WorldModelInstance', 'm'.",
        ),
        (
            "no such model instance index",
            lambda p, m: p.GetModelInstanceName(model_instance=type(m)(7)),
            "There is no model instance id 7 in the model.",
        ),
        (
            "body index out of range",
            lambda p, m: p.get_body(body_index=type(p.world_body().index())(9)),
            "The given RigidBodyIndex(9) is out of bounds (must be less than 5)",
        ),
    ],
)
def test_lookup_errors_are_drakes(mb: Modules, case: str, call: Any, message: str) -> None:
    plant = mb.plant.MultibodyPlant(time_step=0.0)
    plant.AddRigidBody(name="B")
    m = plant.AddModelInstance(name="m")
    for name in ("Z", "a", "B"):
        plant.AddRigidBody(name=name, model_instance=m)
    with pytest.raises(RuntimeError) as raised:
        call(plant, m)
    assert str(raised.value) == message


def test_joint_lookup_lists_the_instances_that_have_joints(mb: Modules) -> None:
    model = Model(mb)
    model.body("A")
    model.body("B")
    model.joint("revolute", "A", "B", name="j")
    assert model.plant.GetJointByName(name="j", model_instance=model.instance).name() == "j"
    assert model.plant.HasJointNamed("j") is True
    with pytest.raises(RuntimeError) as raised:
        model.plant.GetJointByName(name="nope")
    assert str(raised.value) == (
        "GetJointByName(): There is no Joint named 'nope' anywhere in the model (valid names in "
        "model instance 'm' are: j)"
    )


def test_renaming_a_model_instance_renames_its_scoped_names(mb: Modules) -> None:
    model = Model(mb)
    body = model.body("A")
    visual = model.plant.RegisterVisualGeometry(
        body=body,
        X_BG=mb.math.RigidTransform(),
        shape=mb.geometry.Sphere(radius=0.1),
        name="m::v",
        diffuse_color=[1.0, 1.0, 1.0, 1.0],
    )
    model.plant.RenameModelInstance(model_instance=model.instance, name="n")
    inspector = model.scene_graph.model_inspector()
    (collision,) = model.plant.GetCollisionGeometriesForBody(body=body)
    assert str(body.scoped_name()) == "n::A"
    assert inspector.GetName(model.plant.GetBodyFrameIdOrThrow(body_index=body.index())) == "n::A"
    assert (inspector.GetName(collision), inspector.GetName(visual)) == ("n::c", "n::m::v")
    assert model.plant.HasModelInstanceNamed(name="m") is False
    model.plant.RenameModelInstance(model_instance=model.instance, name="n")
    with pytest.raises(RuntimeError) as raised:
        model.plant.RenameModelInstance(model_instance=model.instance, name="DefaultModelInstance")
    assert str(raised.value) == (
        "This model already contains a model instance named 'DefaultModelInstance'. Model "
        "instance names must be unique within a given model."
    )


def test_a_plant_makes_contexts_only_after_finalize(mb: Modules) -> None:
    plant = mb.plant.MultibodyPlant(time_step=0.0)
    with pytest.raises(RuntimeError) as raised:
        plant.CreateDefaultContext()
    assert str(raised.value) == (
        "MultibodyPlant cannot SetDefaultParameters or CreateDefaultContext until after "
        "MultibodyPlant::Finalize() has been called."
    )
    plant.Finalize()
    plant.CreateDefaultContext()


def test_indices_compare_as_integers(mb: Modules) -> None:
    tree = mb.tree
    assert tree.BodyIndex(1) == 1
    assert tree.BodyIndex(1) == tree.JointIndex(1)
    assert tree.BodyIndex(1) < tree.BodyIndex(2)
    assert repr(tree.BodyIndex()) == "BodyIndex(-1234567)"
    assert tree.BodyIndex().is_valid() is False
    assert (repr(tree.world_index()), repr(tree.world_frame_index())) == (
        "BodyIndex(0)",
        "FrameIndex(0)",
    )


# ------------------ reimpl only: the parser's group pair, the filters' scope and table


@pytest.fixture
def reimpl_model() -> Model:
    """pydrake 1.51.1 binds no ExcludeCollisionGeometriesWithCollisionFilterGroupPair."""
    return Model(modules("reimpl"))


def group(model: Model, name: str, *bodies: str) -> tuple[str, Any]:
    plant = model.plant
    return name, plant.CollectRegisteredGeometries(bodies=[model.bodies[b] for b in bodies])


def test_a_group_paired_with_itself_is_excluded_within(reimpl_model: Model) -> None:
    model = reimpl_model
    for name in "ABCD":
        model.body(name)
    g1 = group(model, "r::g1", "A", "B", "C")
    model.plant._exclude_collision_geometries_with_collision_filter_group_pair(g1, g1)
    assert model.C() == {"A/c|D/c", "B/c|D/c", "C/c|D/c"}


def test_two_groups_are_excluded_between_only(reimpl_model: Model) -> None:
    model = reimpl_model
    for name in "ABCD":
        model.body(name)
    pair = (group(model, "r::ga", "A", "B"), group(model, "r::gb", "C", "D"))
    model.plant._exclude_collision_geometries_with_collision_filter_group_pair(*pair)
    assert model.C() == {"A/c|B/c", "C/c|D/c"}


def test_a_group_pair_is_refused_after_finalize_or_without_a_scene_graph(
    reimpl_model: Model,
) -> None:
    model = reimpl_model
    model.body("A")
    g = group(model, "r::g", "A")
    model.finalize()
    with pytest.raises(RuntimeError, match="is_finalized"):
        model.plant._exclude_collision_geometries_with_collision_filter_group_pair(g, g)
    plant = modules("reimpl").plant.MultibodyPlant(time_step=0.0)
    with pytest.raises(RuntimeError, match="geometry_source_is_registered"):
        plant._exclude_collision_geometries_with_collision_filter_group_pair(g, g)


def test_the_default_filters_have_scope_omit_deformable() -> None:
    declaration = default_collision_filters([], [], lambda bodies: GeometrySet(), adjacent=True)
    assert declaration.scope() is CollisionFilterScope.kOmitDeformable


def test_the_adjacency_rule_names_every_joint_type() -> None:
    kinds = {
        cls.kTypeName
        for cls in vars(tree).values()
        if isinstance(cls, type) and issubclass(cls, tree.Joint) and cls is not tree.Joint
    }
    assert kinds == set(ADJACENCY_RULE)
