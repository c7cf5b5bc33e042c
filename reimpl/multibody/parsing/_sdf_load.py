"""libsdformat's Root::Load after reading: objects, graphs, then the joints' ends (Drake 1.51.1).

In this order, each raising libsdformat's first error:

1. each ``<world>``: World::Load (_sdf_dom), its graphs (_sdf_graph), then the
   interface links' default poses (the Interface API's *reposture*: X_WL from
   the pose graph);
2. the ``<model>``: Model::Load (every one; two are ``Root object can only
   contain one model. Using the first one found``), its graphs, reposture;
3. per joint of the root model, of each world model and of each world:
   ``parent frame with name[x] specified by joint with name[j] not found in
   model with name[m].``, own name as child or parent, parent and child
   attached to the same link, a child attached to the world;
4. per joint axis there: ``axis xyz expressed-in frame with name[x]
   specified by joint with name[j] not found in model with name[m].``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from reimpl.multibody.parsing import _scoped_name as scoped
from reimpl.multibody.parsing._diagnostics import Diagnostics
from reimpl.multibody.parsing._parse_context import ParseContext
from reimpl.multibody.parsing._sdf_document import version_tuple
from reimpl.multibody.parsing._sdf_dom import Joint, Model, World, load_model, load_world
from reimpl.multibody.parsing._sdf_graph import Graphs, join
from reimpl.multibody.parsing._sdf_include import Loaded
from reimpl.multibody.parsing._sdf_interface import InterfaceModel
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = ["Document", "attached_body", "load_document"]

_ROOT = "__root__"
_WORLD = "world"


@dataclass
class Document:
    """What libsdformat loaded: the worlds or the model, and their graphs."""

    worlds: list[World] = field(default_factory=list)
    model: Model | None = None
    graphs: Graphs = field(default_factory=Graphs)
    #: the plant's model instances made while loading (by the Interface API)
    interface_instances: range = range(0)


def load_document(context: ParseContext, loaded: Loaded, root: XmlElement) -> Document:
    """Root::Load of the read ``<sdf>`` element."""
    version = version_tuple(root.get("version", ""))
    first = context.plant.num_model_instances()
    document = Document()
    for element in children(root, "world"):
        world = load_world(context, loaded, element, version)
        document.graphs = Graphs.of_world(world.graph_world())
        _reposture(context, document.graphs, world.interfaces, [], "")
        for model in world.models:
            _reposture_model(context, document.graphs, model, model.name)
        document.worlds.append(world)
    models = [load_model(context, loaded, e, version) for e in children(root, "model")]
    if len(models) > 1:
        raise Diagnostics(None).error(
            "Root object can only contain one model. Using the first one found"
        )
    if models:
        document.model = models[0]
        document.graphs = Graphs.of_model(models[0].graph_model())
        _reposture_model(context, document.graphs, models[0], models[0].name)
    for check in (_check_joint_ends, _check_axes):
        if document.model is not None:
            check(document.graphs, document.model.joints, document.model.name, "model")
        for world in document.worlds:
            for model in world.models:
                check(document.graphs, model.joints, model.name, "model")
            check(document.graphs, world.joints, "", f"world with name[{world.name}]")
    document.interface_instances = range(first, context.plant.num_model_instances())
    return document


def attached_body(graphs: Graphs, vertex: str, name: str) -> str:
    """resolveFrameAttachedToBody: the link ``name`` (in scope ``vertex``) is attached to."""
    body = graphs.attached_body(join(vertex, name), name)
    if body == _WORLD or not vertex:
        return body
    return body.removeprefix(f"{vertex}::")


def _reposture(
    context: ParseContext,
    graphs: Graphs,
    interfaces: list[InterfaceModel],
    merged: list[InterfaceModel],
    scope: str,
) -> None:
    """The Interface API's reposture: each interface link's default pose, from the graph."""
    plant = context.plant
    for interface, prefix in [
        *((i, join(scope, i.name)) for i in interfaces),
        *((i, scope) for i in merged),
    ]:
        for index in plant.GetBodyIndices(interface.instance):
            body = plant.get_body(index)
            vertex = join(prefix, body.name())
            if vertex in graphs.pose.types:
                X_WL = graphs.X_scope(_ROOT, vertex).transform()
                plant.SetDefaultFloatingBaseBodyPose(body, X_WL)


def _reposture_model(context: ParseContext, graphs: Graphs, model: Model, vertex: str) -> None:
    for nested in model.models:
        _reposture_model(context, graphs, nested, join(vertex, nested.name))
    _reposture(context, graphs, model.interfaces, model.merged_interfaces, vertex)


def _where(vertex: str, kind: str) -> str:
    """``model with name[m]``, or the world's ``kind`` (which names itself)."""
    return f"{kind} with name[{vertex}]" if kind == "model" else kind


def _check_joint_ends(graphs: Graphs, joints: list[Joint], vertex: str, kind: str) -> None:
    """checkScopedJointParentChildNames."""
    where = _where(vertex, kind)
    for joint in joints:
        parent_local = scoped.split(joint.parent)[1]
        if (
            joint.parent != _WORLD
            and parent_local != "__model__"
            and not graphs.has(join(vertex, joint.parent))
        ):
            raise Diagnostics(None).error(
                f"parent frame with name[{joint.parent}] specified by joint with "
                f"name[{joint.name}] not found in {where}."
            )
        for end, name in (("child", joint.child), ("parent", joint.parent)):
            if name == joint.name:
                raise Diagnostics(None).error(
                    f"joint with name[{joint.name}] in {where} must not specify its own name as "
                    f"the {end} frame."
                )
        child = attached_body(graphs, vertex, joint.child)
        parent = _WORLD if joint.parent == _WORLD else attached_body(graphs, vertex, joint.parent)
        if child == parent:
            raise Diagnostics(None).error(
                f"joint with name[{joint.name}] in {where} specified parent frame "
                f"[{joint.parent}] and child frame [{joint.child}] that both resolve to "
                f"[{child}], but they should resolve to different values."
            )
        if child == _WORLD:
            raise Diagnostics(None).error(
                f"joint with name[{joint.name}] in {kind.split(' ', maxsplit=1)[0]} has a child "
                f"with name[{joint.child}] that resolves to world which is invalid."
            )


def _check_axes(graphs: Graphs, joints: list[Joint], vertex: str, kind: str) -> None:
    """checkScopedJointAxisExpressedInValues: each ``expressed_in`` names a frame."""
    for joint in joints:
        for expressed_in in joint.expressed_in:
            if expressed_in and not graphs.has(join(vertex, expressed_in)):
                raise Diagnostics(None).error(
                    f"axis xyz expressed-in frame with name[{expressed_in}] specified by joint "
                    f"with name[{joint.name}] not found in {_where(vertex, kind)}."
                )
