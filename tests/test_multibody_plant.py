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


def _z(mb: Modules) -> Any:
    return [0.0, 0.0, 1.0]


#: Joint constructors, called with pydrake's keyword names.
JOINTS: dict[str, Any] = {
    "revolute": lambda mb, n, p, c: mb.tree.RevoluteJoint(
        name=n, frame_on_parent=p, frame_on_child=c, axis=_z(mb)
    ),
    "prismatic": lambda mb, n, p, c: mb.tree.PrismaticJoint(
        name=n, frame_on_parent=p, frame_on_child=c, axis=_z(mb)
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
