"""The cliques RigidBodyTree made by itself (seed 002), and which bodies it anchored.

Seed 002's two rules, as ``RigidBodyTree::CreateCollisionCliques`` applied them:

1. adjacent bodies — one the parent of the other through a joint that is not
   floating — share a clique holding every element of both: for each such
   joint J, a clique ``E(parent(J)) ∪ E(child(J))``;
2. the elements of one body share a clique, ``E(B)`` for each body with two or
   more elements (skipped when rule 1 already put them in a clique: same pairs).

N.B. The world is *not* exempt from rule 1 (``RigidBody::adjacentTo`` asks
only whether the joint is floating); today's MultibodyPlant skips every joint
whose parent is the world. Floating means ``quaternion_floating`` or
``rpy_floating`` (RBT's ``QuaternionFloatingJoint`` and
``RollPitchYawFloatingJoint``); MultibodyPlant skips only the former.

RBT also excluded every pair of *anchored* elements, those on bodies rigidly
fixed to the world (``IsRigidlyFixedToWorld``: the world and bodies welded to
it, weld after weld); ``anchored_bodies`` finds them. That rule lives with the
element test (``legacy_filter.LegacyFilter``), not in cliques.

A plant (``reimpl.multibody.plant.MultibodyPlant``, built in code or parsed)
is read into a ``BodyGraph``: bodies named ``<model instance>::<body>``,
elements its collision GeometryIds, joints by type name.
"""

from __future__ import annotations

from collections.abc import Hashable, Mapping
from dataclasses import dataclass
from typing import Any, Generic, TypeVar

from reimpl.legacy.collision_cliques import CollisionCliques

__all__ = [
    "FLOATING_JOINT_TYPES",
    "WELD_JOINT_TYPES",
    "BodyGraph",
    "JointEdge",
    "anchored_bodies",
    "auto_cliques",
    "body_graph",
]

B = TypeVar("B", bound=Hashable)
E = TypeVar("E", bound=Hashable)

#: Joint type names (MultibodyPlant's ``type_name()``) that RBT called floating.
FLOATING_JOINT_TYPES = frozenset({"quaternion_floating", "rpy_floating"})
#: Joint type names that fix a child to its parent (RBT's ``FixedJoint``).
WELD_JOINT_TYPES = frozenset({"weld"})


@dataclass(frozen=True)
class JointEdge(Generic[B]):
    """One joint: its name, the bodies it joins and its type name (``revolute``, ``weld``, ...)."""

    name: str
    parent: B
    child: B
    type_name: str

    @property
    def is_floating(self) -> bool:
        return self.type_name in FLOATING_JOINT_TYPES

    @property
    def is_weld(self) -> bool:
        return self.type_name in WELD_JOINT_TYPES


@dataclass(frozen=True)
class BodyGraph(Generic[B, E]):
    """Bodies (the world first), each body's collision elements in order, and the joints."""

    world: B
    bodies: tuple[B, ...]
    elements: Mapping[B, tuple[E, ...]]
    joints: tuple[JointEdge[B], ...]

    def elements_of(self, body: B) -> tuple[E, ...]:
        return tuple(self.elements.get(body, ()))

    def all_elements(self) -> list[E]:
        """Every element, body by body."""
        return [e for body in self.bodies for e in self.elements_of(body)]


def body_graph(plant: Any) -> BodyGraph[str, Any]:
    """The BodyGraph of a reimpl MultibodyPlant: bodies as ``model::body``, elements as
    collision GeometryIds (none for a plant without a SceneGraph)."""
    from reimpl.multibody.tree import BodyIndex, JointIndex  # noqa: PLC0415 (optional package)

    def scoped(body: Any) -> str:
        return f"{plant.GetModelInstanceName(body.model_instance())}::{body.name()}"

    bodies = [plant.get_body(BodyIndex(i)) for i in range(plant.num_bodies())]
    registered = plant.geometry_source_is_registered()
    elements = {
        scoped(body): tuple(plant.GetCollisionGeometriesForBody(body) if registered else ())
        for body in bodies
    }
    joints = []
    for i in range(plant.num_joints()):
        joint = plant.get_joint(JointIndex(i))
        joints.append(
            JointEdge(
                joint.name(),
                scoped(joint.parent_body()),
                scoped(joint.child_body()),
                joint.type_name(),
            )
        )
    return BodyGraph(
        scoped(plant.world_body()), tuple(scoped(b) for b in bodies), elements, tuple(joints)
    )


def auto_cliques(source: Any) -> CollisionCliques[Any]:
    """The cliques of seed 002's rules (module doc) for a plant or a ``BodyGraph``.

    >>> joint = JointEdge("j", "w", "b", "revolute")
    >>> graph = BodyGraph("w", ("w", "b"), {"w": ("floor",), "b": ("s",)}, (joint,))
    >>> auto_cliques(graph).is_filtered("floor", "s")
    True
    """
    graph: BodyGraph[Any, Any] = source if isinstance(source, BodyGraph) else body_graph(source)
    cliques: CollisionCliques[Any] = CollisionCliques()
    done: set[frozenset[Any]] = set()
    for joint in graph.joints:  # Rule 1: adjacency, once per pair of bodies.
        key = frozenset((joint.parent, joint.child))
        if joint.is_floating or len(key) < 2 or key in done:
            continue
        parent, child = graph.elements_of(joint.parent), graph.elements_of(joint.child)
        if not parent or not child:
            continue  # Nothing to filter (RBT made no clique either).
        done.add(key)
        clique = cliques.new_clique()
        for element in (*parent, *child):
            cliques.add_to_clique(element, clique)
    for body in graph.bodies:  # Rule 2: one body's elements, unless rule 1 covered them.
        elements = graph.elements_of(body)
        if len(elements) > 1 and not cliques.cliques_of(elements[0]):
            clique = cliques.new_clique()
            for element in elements:
                cliques.add_to_clique(element, clique)
    return cliques


def anchored_bodies(graph: BodyGraph[B, Any]) -> frozenset[B]:
    """The world and every body joined to it by welds alone (RBT's ``IsRigidlyFixedToWorld``)."""
    anchored = {graph.world}
    changed = True
    while changed:
        changed = False
        for joint in graph.joints:
            if joint.is_weld and (joint.parent in anchored) != (joint.child in anchored):
                anchored |= {joint.parent, joint.child}
                changed = True
    return frozenset(anchored)
