"""MuJoCo ``<contact>`` and ``<equality>``, as Drake 1.51.1 reads them (measured).

``<contact>`` is read only when the plant has a SceneGraph. Each ``<pair>``
takes the defaults of the class named by the ``<contact>`` element (sic,
Drake reads ``class`` from the parent), then needs ``geom1`` and ``geom2``
(else warned about at the ``<contact>``'s line and skipped). A name is found
among the proximity geometries of this model instance (on its bodies' frames)
as the geometry whose scoped name ends with it; none is warned about (``contact
pair specified unknown geom1 N and will be ignored.``) and skipped. Then
``condim`` and ``friction`` are warned about, a pair of geometries on bodies
joined by a joint of the instance is warned about (Finalize's adjacent-body
filter will undo it, unless that filter is off), and the pair's filter is
removed: ``AllowBetween({g1}, {g2})``. Each ``<exclude>`` needs ``body1`` and
``body2`` (else warned about); the instance's bodies of those names (a
missing one: GetBodyByName's error) get ``ExcludeBetween`` their frames.

Not modelled: a name that ends more than one geometry's scoped name; Drake
takes the first in its unordered set's order (a reimpl error).

``<equality>``: each ``<connect>`` takes the class defaults of ``equality``;
``body1`` with ``site1`` is an error (``connect node must specify either body1
and anchor OR site1 and site2, but not both.``); ``body1`` needs ``anchor``
(3) and names a body of the instance, as ``body2`` (default: the world) must;
else ``site1`` and ``site2`` are warned about and ignored, and neither is an
error (``connect must specify body1 and anchor OR site1 and site2.``). A ball
constraint needs two distinct bodies (Drake's message); reimpl's plant keeps
no constraints, so nothing is added. ``active`` is warned about; then
``<weld>``, ``<joint>``, ``<tendon>``, ``<flex>`` and ``<distance>``.
"""

from __future__ import annotations

from typing import Any

from reimpl.geometry import CollisionFilterDeclaration, GeometrySet, Role
from reimpl.multibody.parsing import _mjcf_values as values
from reimpl.multibody.parsing._diagnostics import ModelParseError
from reimpl.multibody.parsing._mjcf_context import MjcfContext
from reimpl.multibody.parsing._mjcf_defaults import apply_defaults, class_of
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = ["read_contact", "read_equality"]

_EQUALITY_UNSUPPORTED = ("weld", "joint", "tendon", "flex", "distance")


class _Pairs:
    """The instance's proximity geometries, found by the end of their names."""

    def __init__(self, context: MjcfContext) -> None:
        self.context = context
        scene_graph = context.plant._registered_scene_graph("RegisterCollisionGeometry")[0]
        self.manager = scene_graph.collision_filter_manager()
        self.inspector = scene_graph.model_inspector()
        instance = int(context.instance)
        self.ids = [
            g
            for g in self.inspector.GetAllGeometryIds(Role.kProximity)
            if self.inspector.GetFrameGroup(self.inspector.GetFrameId(g)) == instance
        ]

    def find(self, name: str) -> Any:
        found = [g for g in self.ids if self.inspector.GetName(g).endswith(name)]
        if len(found) > 1:
            raise ModelParseError(
                f"reimpl does not choose among the geometries whose names end with '{name}' "
                "(Drake takes the first in its unordered set)"
            )
        return found[0] if found else None

    def body(self, geometry: Any) -> Any:
        return self.context.plant.GetBodyFromFrameId(self.inspector.GetFrameId(geometry))


def _warn_adjacent(
    context: MjcfContext, contact: XmlElement, pairs: _Pairs, ids: tuple[Any, Any], names: Any
) -> None:
    plant = context.plant
    if not plant._adjacent_bodies_collision_filters:  # the getter is bound since 1.13
        return
    bodies = {int(pairs.body(ids[0]).index()), int(pairs.body(ids[1]).index())}
    for index in plant.GetJointIndices(context.instance):
        joint = plant.get_joint(index)
        ends = {int(joint.parent_body().index()), int(joint.child_body().index())}
        if ends == bodies and len(bodies) == 2:
            context.d.warning(
                contact,
                f"This mjcf specified a contact pair with geom1 {names[0]} and are on adjacent "
                "bodies (connected by a joint). A collision filter excluding these bodies will "
                "be added during MultibodyPlant::Finalize(), which will overwrite the collision "
                "filter specified in this file. To avoid this you must call "
                "MultibodyPlant::set_adjacent_bodies_collision_filters(), and understand the "
                "implications.",
            )


def _pair(context: MjcfContext, contact: XmlElement, node: XmlElement, pairs: _Pairs) -> None:
    d = context.d
    apply_defaults(context, "pair", class_of(contact), node)
    names = (node.get("geom1"), node.get("geom2"))
    if names[0] is None or names[1] is None:
        d.warning(
            contact,
            "contact pair node does not have required geom1 and/or geom2 attributes, so will "
            "be ignored.",
        )
        return
    ids = (pairs.find(names[0]), pairs.find(names[1]))
    for k in (0, 1):
        if ids[k] is None:
            d.warning(
                contact,
                f"contact pair specified unknown geom{k + 1} {names[k]} and will be ignored.",
            )
            return
    d.warn_unsupported_attributes(node, ("condim", "friction"))
    _warn_adjacent(context, contact, pairs, ids, names)
    pairs.manager.Apply(
        CollisionFilterDeclaration().AllowBetween(GeometrySet(ids[0]), GeometrySet(ids[1]))
    )


def _exclude(context: MjcfContext, contact: XmlElement, node: XmlElement, pairs: _Pairs) -> None:
    names = (node.get("body1"), node.get("body2"))
    if names[0] is None or names[1] is None:
        context.d.warning(
            contact,
            "contact exclude node does not have required body1 and/or body2 attributes, so "
            "will be ignored.",
        )
        return
    plant = context.plant
    frames = [
        plant.GetBodyFrameIdOrThrow(plant.GetBodyByName(name, context.instance).index())
        for name in names
    ]
    pairs.manager.Apply(
        CollisionFilterDeclaration().ExcludeBetween(GeometrySet(frames[0]), GeometrySet(frames[1]))
    )


def read_contact(context: MjcfContext, node: XmlElement) -> None:
    """ParseContact (with a SceneGraph only)."""
    if not context.parse.has_scene_graph():
        return
    pairs = _Pairs(context)
    for pair in children(node, "pair"):
        _pair(context, node, pair, pairs)
    for exclude in children(node, "exclude"):
        _exclude(context, node, exclude, pairs)


def _body(context: MjcfContext, node: XmlElement, which: str, name: str) -> Any:
    plant = context.plant
    if not plant.HasBodyNamed(name, context.instance):
        raise context.d.error(
            node,
            f"connect specified {which}: {name} but no body with that name exists in model "
            f"instance: {plant.GetModelInstanceName(context.instance)}",
        )
    return plant.GetBodyByName(name, context.instance)


def _connect(context: MjcfContext, equality: XmlElement, node: XmlElement) -> None:
    d = context.d
    apply_defaults(context, "equality", class_of(node), node)
    if node.get("body1") is not None and node.get("site1") is not None:
        raise d.error(
            node,
            "connect node must specify either body1 and anchor OR site1 and site2, but not both.",
        )
    body1 = node.get("body1")
    if body1 is None:
        if node.get("site1") is None or node.get("site2") is None:
            raise d.error(node, "connect must specify body1 and anchor OR site1 and site2.")
        d.warning(
            node,
            "connect node uses the site1 and site2 specification, which is not supported yet. "
            "This constraint will be ignored.",
        )
        return
    if values.vector(node, "anchor", 3) is None:
        raise d.error(
            equality, "connect specified body1 but does not have the required anchor attribute."
        )
    body_A = _body(context, equality, "body1", body1)
    body2 = node.get("body2")
    body_B = (
        context.plant.world_body() if body2 is None else _body(context, equality, "body2", body2)
    )
    if body_A is body_B:
        raise RuntimeError(
            f"Invalid set of parameters for constraint between bodies '{body_A.name()}' and "
            f"'{body_B.name()}'. For a ball constraint, points P and Q must be on two distinct "
            "bodies, i.e. body_A != body_B must be satisfied."
        )
    d.warn_unsupported_attributes(node, ("active",))


def read_equality(context: MjcfContext, node: XmlElement) -> None:
    """ParseEquality: connect constraints checked (reimpl's plant keeps none), warnings."""
    for connect in children(node, "connect"):
        _connect(context, node, connect)
    context.d.warn_unsupported_elements(node, _EQUALITY_UNSUPPORTED)
