"""URDF as RigidBodyTree read it: the unprefixed collision filter groups, and its model.

The old syntax (attic ``multibody/parsers/parser_common.cc``,
``ParseCollisionFilterGroup``), one group per element, children of ``<robot>``::

    <collision_filter_group name="G" [drake_ignore="true"]>
      <member link="L"/>                                         (0..n)
      <ignored_collision_filter_group collision_filter_group="K"/>  (0..n; K may be G)
    </collision_filter_group>

- ``drake_ignore="true"`` skips the group (as it skips a ``<link>``);
- a missing ``name``, ``link`` or ``collision_filter_group`` attribute, a
  second group of the same name, and a ``link`` that names no link of the
  robot are errors;
- ignoring a group that is never defined is not (a warning; see
  ``CollisionFilterGroups.undefined_ignores``);
- groups are scoped to one parse: ``legacy_model`` ends the session.

Today's parser silently ignores these tags and reads ``drake:``-prefixed
groups instead; this module reads those too (``LegacyUrdf.drake_groups``),
only so that a comparison can say which pairs they explain.

The model: a link named ``world`` is the world body; every other link is
``<robot>::<link>``; each ``<collision>`` with a shape is one element named
as Drake names the geometry, ``<body>/<name>`` (its ``name``, else its shape
class, ``Box``, ``Sphere`` ..., with ``_1``, ``_2`` ... for repeats on one
link). Joints: ``fixed`` is a weld; ``floating`` is RBT's floating joint;
``<drake:joint>`` did not exist for RBT, so its child, like every link
without a parent, hangs from the world by a floating base (RBT's
``kRollPitchYaw``).

N.B. The XML is read with expat without namespace processing, so that
``drake:`` tags need no ``xmlns:drake`` declaration, as in Drake's parser
(``xml.etree`` refuses an unbound prefix).
"""

from __future__ import annotations

import xml.parsers.expat
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

from reimpl.legacy._errors import LegacyError, LegacyUrdfError, UnknownLinkError
from reimpl.legacy.auto_cliques import BodyGraph, JointEdge, anchored_bodies, auto_cliques
from reimpl.legacy.collision_cliques import CollisionCliques
from reimpl.legacy.collision_filter_groups import CollisionFilterGroups
from reimpl.legacy.legacy_filter import LegacyFilter

__all__ = [
    "WORLD",
    "WORLD_BODY",
    "LegacyModel",
    "LegacyUrdf",
    "UrdfGroup",
    "UrdfJoint",
    "UrdfLink",
    "legacy_model",
    "load_legacy_urdf",
    "read_legacy_urdf",
]

#: The reserved link name of the world body, and its scoped name in a plant.
WORLD = "world"
WORLD_BODY = "WorldModelInstance::world"

#: ``<geometry>`` shape tags in the order Drake looks for them, and Drake's shape class.
_SHAPES = (
    ("box", "Box"),
    ("sphere", "Sphere"),
    ("cylinder", "Cylinder"),
    ("capsule", "Capsule"),
    ("drake:capsule", "Capsule"),
    ("drake:ellipsoid", "Ellipsoid"),
    ("mesh", "Mesh"),
)
#: ``<joint type>`` → the joint type name of the legacy model (RBT's joint classes).
_LEGACY_JOINT_TYPES = {
    "fixed": "weld",
    "revolute": "revolute",
    "continuous": "revolute",
    "prismatic": "prismatic",
    "planar": "planar",
    "floating": "quaternion_floating",
}
#: The joint type of RBT's default floating base.
FLOATING_BASE = "rpy_floating"


# ------------------------------------------------------------------ the XML
@dataclass
class _Node:
    tag: str
    attrib: dict[str, str]
    line: int
    children: list[_Node] = field(default_factory=list)

    def each(self, tag: str) -> Iterator[_Node]:
        return (c for c in self.children if c.tag == tag)

    def first(self, tag: str) -> _Node | None:
        return next(self.each(tag), None)

    def describe(self) -> str:
        attributes = "".join(f' {k}="{v}"' for k, v in self.attrib.items())
        return f"<{self.tag}{attributes}>"


def _parse_xml(text: str, source: str) -> _Node:
    parser = xml.parsers.expat.ParserCreate()
    stack: list[_Node] = []
    root: list[_Node] = []

    def start(tag: str, attrib: dict[str, str]) -> None:
        node = _Node(tag, dict(attrib), parser.CurrentLineNumber)
        (stack[-1].children if stack else root).append(node)
        stack.append(node)

    def end(_: str) -> None:
        stack.pop()

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    try:
        parser.Parse(text, True)
    except xml.parsers.expat.ExpatError as exc:
        raise LegacyUrdfError(
            f"{source}:{exc.lineno}: malformed XML: {xml.parsers.expat.ErrorString(exc.code)}"
        ) from None
    return root[0]


# ----------------------------------------------------------------- the file
@dataclass(frozen=True)
class UrdfLink:
    """A link, with Drake's names of its collision geometries (the legacy elements)."""

    name: str
    line: int
    collisions: tuple[str, ...]


@dataclass(frozen=True)
class UrdfJoint:
    """A ``<joint>`` (or a ``<drake:joint>``, which RBT did not read)."""

    name: str
    type: str
    parent: str
    child: str
    line: int
    drake_joint: bool = False


@dataclass(frozen=True)
class UrdfGroup:
    """An unprefixed (legacy) or ``drake:`` (modern) collision filter group."""

    name: str
    line: int
    members: tuple[str, ...]
    ignored: tuple[str, ...]
    member_groups: tuple[str, ...] = ()
    prefixed: bool = False


@dataclass(frozen=True)
class LegacyUrdf:
    """What a URDF says about filtering, read by the RBT-era rules (module doc)."""

    source: str
    robot: str | None
    links: tuple[UrdfLink, ...]
    joints: tuple[UrdfJoint, ...]
    groups: tuple[UrdfGroup, ...]
    drake_groups: tuple[UrdfGroup, ...]

    def link_names(self) -> set[str]:
        return {link.name for link in self.links} | {WORLD}


class _Reader:
    def __init__(self, source: str) -> None:
        self.source = source

    def error(self, node: _Node, message: str) -> LegacyUrdfError:
        return LegacyUrdfError(f"{self.source}:{node.line}: {node.describe()}: {message}")

    def required(self, node: _Node, attribute: str, what: str) -> str:
        value = node.attrib.get(attribute)
        if value is None:
            raise self.error(node, f'{what} does not specify the required attribute "{attribute}"')
        return value

    def link(self, node: _Node) -> UrdfLink:
        name = self.required(node, "name", "the link")
        names: list[str] = []
        for collision in node.each("collision"):
            geometry = collision.first("geometry")
            if geometry is None:
                raise self.error(
                    collision, f"link '{name}' has a collision element without geometry"
                )
            shape = next((cls for tag, cls in _SHAPES if geometry.first(tag) is not None), None)
            if shape is None:
                continue  # No element (today's parser refuses the file).
            base = collision.attrib.get("name", shape)
            unique, suffix = base, 0
            while unique in names:
                suffix += 1
                unique = f"{base}_{suffix}"
            names.append(unique)
        return UrdfLink(name, node.line, tuple(n.strip() for n in names))

    def joint(self, node: _Node, links: set[str]) -> UrdfJoint:
        name = self.required(node, "name", "the joint")
        kind = self.required(node, "type", f"joint '{name}'")
        ends = []
        for end in ("parent", "child"):
            element = node.first(end)
            if element is None:
                raise self.error(node, f"joint '{name}' has no <{end}> element")
            link = self.required(element, "link", f"the <{end}> of joint '{name}'")
            if link not in links:
                raise self.error(
                    element, f"joint '{name}' names {end} link '{link}', which is not a link"
                )
            ends.append(link)
        return UrdfJoint(name, kind, ends[0], ends[1], node.line, node.tag == "drake:joint")

    def legacy_group(self, node: _Node, robot: str | None, links: set[str]) -> UrdfGroup:
        name = self.required(node, "name", "the collision filter group")
        members = []
        for member in node.each("member"):
            link = self.required(member, "link", f"a member of collision filter group '{name}'")
            if link not in links:
                raise UnknownLinkError(
                    f"{self.source}:{member.line}: {member.describe()} of <collision_filter_group "
                    f"name=\"{name}\">: robot '{robot}' has no link named '{link}'"
                )
            members.append(link)
        ignored = [
            self.required(
                target,
                "collision_filter_group",
                f"an ignored group of collision filter group '{name}'",
            )
            for target in node.each("ignored_collision_filter_group")
        ]
        return UrdfGroup(name, node.line, tuple(members), tuple(ignored))

    @staticmethod
    def drake_group(node: _Node) -> UrdfGroup | None:
        """A ``drake:`` group, leniently (today's parser reports its errors)."""
        name = node.attrib.get("name")
        if name is None or node.attrib.get("ignore") == "true":
            return None

        def values(tag: str, attribute: str) -> tuple[str, ...]:
            return tuple(c.attrib[attribute] for c in node.each(tag) if attribute in c.attrib)

        return UrdfGroup(
            name,
            node.line,
            values("drake:member", "link"),
            values("drake:ignored_collision_filter_group", "name"),
            values("drake:member_group", "name"),
            prefixed=True,
        )


def read_legacy_urdf(text: str, source: str = "<string>") -> LegacyUrdf:
    """Reads URDF ``text``; ``source`` (a file name) starts every error message.

    Raises:
        LegacyUrdfError: malformed XML, a missing required attribute, no ``<robot>``.
        UnknownLinkError: a legacy group's ``<member link>`` names no link.
    """
    reader = _Reader(source)
    root = _parse_xml(text, source)
    if root.tag != "robot":
        raise reader.error(root, "the root element is not <robot>")
    robot = root.attrib.get("name")
    links = [reader.link(n) for n in root.each("link") if n.attrib.get("drake_ignore") != "true"]
    names = {link.name for link in links} | {WORLD}
    joints = [
        reader.joint(node, names)
        for node in root.children
        if node.tag in {"joint", "drake:joint"} and node.attrib.get("drake_ignore") != "true"
    ]
    groups = [
        reader.legacy_group(node, robot, names)
        for node in root.each("collision_filter_group")
        if node.attrib.get("drake_ignore") != "true"
    ]
    seen: dict[str, UrdfGroup] = {}
    for group in groups:
        if group.name in seen:
            raise LegacyUrdfError(
                f'{source}:{group.line}: <collision_filter_group name="{group.name}">: '
                f"a group of that name is already defined at line {seen[group.name].line}"
            )
        seen[group.name] = group
    drake_groups = [
        g for n in root.each("drake:collision_filter_group") if (g := reader.drake_group(n))
    ]
    return LegacyUrdf(
        source, robot, tuple(links), tuple(joints), tuple(groups), tuple(drake_groups)
    )


def load_legacy_urdf(path: str | Path) -> LegacyUrdf:
    """Reads the URDF file at ``path`` (its name starts error messages).

    Raises:
        LegacyUrdfError: the file cannot be read, or ``read_legacy_urdf`` refuses it.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise LegacyUrdfError(f"{path}: cannot read the file: {exc}") from None
    return read_legacy_urdf(text, str(path))


# ---------------------------------------------------------------- the model
@dataclass(frozen=True)
class LegacyModel:
    """One URDF as a RigidBodyTree filtered it: elements, groups, cliques, anchoring."""

    name: str
    urdf: LegacyUrdf
    graph: BodyGraph[str, str]
    groups: CollisionFilterGroups[str]
    cliques: CollisionCliques[str]
    anchored: frozenset[str]  # bodies
    filter: LegacyFilter[str]

    def elements(self) -> list[str]:
        return self.graph.all_elements()

    def body_of(self, element: str) -> str:
        """The body ``element`` is on."""
        for body in self.graph.bodies:
            if element in self.graph.elements_of(body):
                return body
        raise KeyError(element)

    def scoped(self, link: str) -> str:
        """The body name of ``link``: ``<model>::<link>``, or the world's."""
        return WORLD_BODY if link == WORLD else f"{self.name}::{link}"

    def candidate_pairs(self) -> set[frozenset[str]]:
        """C over this model's elements (legacy_filter's formula)."""
        return self.filter.candidate_pairs(self.elements())


def legacy_model(
    urdf: LegacyUrdf,
    model_name: str | None = None,
    groups: CollisionFilterGroups[str] | None = None,
) -> LegacyModel:
    """The RigidBodyTree of ``urdf``: its body graph, its groups (one parse session, ended
    here; pass ``groups`` to share bits with earlier parses), auto cliques and anchoring.

    Raises:
        LegacyUrdfError: the robot has no name and none is given, or more than 127
            groups would be defined (the message names the group).
    """
    name = model_name or urdf.robot
    if not name:
        raise LegacyUrdfError(f"{urdf.source}: <robot> has no name attribute")
    model_groups: CollisionFilterGroups[str] = (
        groups if groups is not None else CollisionFilterGroups()
    )

    def scoped(link: str) -> str:
        return WORLD_BODY if link == WORLD else f"{name}::{link}"

    links = {link.name: link for link in urdf.links}
    bodies = [WORLD_BODY] + [scoped(n) for n in links if n != WORLD]
    elements = {
        scoped(link.name): tuple(f"{scoped(link.name)}/{g}" for g in link.collisions)
        for link in urdf.links
    }
    joints = [
        JointEdge(
            j.name, scoped(j.parent), scoped(j.child), _LEGACY_JOINT_TYPES.get(j.type, j.type)
        )
        for j in urdf.joints
        if not j.drake_joint
    ]
    children = {j.child for j in joints}
    joints += [
        JointEdge(f"(floating base of {body})", WORLD_BODY, body, FLOATING_BASE)
        for body in bodies[1:]
        if body not in children
    ]
    graph = BodyGraph(WORLD_BODY, tuple(bodies), elements, tuple(joints))
    for group in urdf.groups:
        try:
            model_groups.define_group(group.name)
        except LegacyError as exc:
            raise LegacyUrdfError(f"{urdf.source}:{group.line}: {exc}") from None
        for link in group.members:
            for element in graph.elements_of(scoped(link)):
                model_groups.add_member(group.name, element)
        for target in group.ignored:
            model_groups.ignore(group.name, target)
    model_groups.end_session()
    anchored = anchored_bodies(graph)
    cliques = auto_cliques(graph)
    anchored_elements = frozenset(e for body in anchored for e in graph.elements_of(body))
    return LegacyModel(
        name,
        urdf,
        graph,
        model_groups,
        cliques,
        anchored,
        LegacyFilter(model_groups, cliques, anchored_elements),
    )
