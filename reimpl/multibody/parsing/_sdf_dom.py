"""libsdformat's objects for a read document: models, links, joints, frames (Drake 1.51.1).

After reading (_sdf_document), libsdformat loads the ``<model>`` or
``<world>`` element by element. Per model, in this order (measured on pydrake
1.51.1 where files have several errors):

1. its name is not reserved (``world``, or ``__x__``);
2. no two children share a name (``Non-unique name[x] detected 2 times in XML
   children of model with name[m].``, the names in sorted order);
3. its ``<include>``s of custom files (URDF) are parsed into the plant
   (_sdf_interface);
4. its children in document order: nested models (loaded whole; a merged one,
   see below), links (``The supplied link name [world] is reserved.``), joints,
   frames; an implicit name taken twice is ``Link with name [x] in model with
   name [m] has a name collision. Please rename this link.``;
5. a model with no link, nested model or interface model (and not static) is
   ``A model must have at least one link.``.

A model included with ``merge="true"`` is checked as a model of its own (its
graphs), then dissolved into its parent: a frame ``_merged__<name>__model__``
(attached to its canonical link, at its pose) stands for its model frame, its
links, joints, frames and nested models become the parent's, and whatever
named its ``__model__`` (or nothing) names that frame instead. Into a world,
its links are dropped.

The canonical link of a model is its ``canonical_link``, else its first link,
else its first merged interface link, else (scoped) the first nested model's,
else the first interface model's.
"""

from __future__ import annotations

import contextlib
import math
from collections import Counter
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

from reimpl._release import release
from reimpl.multibody.parsing import _scoped_name as scoped
from reimpl.multibody.parsing._diagnostics import Diagnostics, ModelParseError
from reimpl.multibody.parsing._parse_context import ParseContext
from reimpl.multibody.parsing._sdf_document import sdformat_bool
from reimpl.multibody.parsing._sdf_graph import GFrame, GJoint, GLink, GModel, Graphs, GWorld
from reimpl.multibody.parsing._sdf_include import Loaded, find_file, text_of
from reimpl.multibody.parsing._sdf_interface import (
    InterfaceModel,
    is_custom_file,
    load_interface_model,
    merged_frame_name,
)
from reimpl.multibody.parsing._sdf_poses import GzPose, read_pose
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = ["Frame", "Joint", "Link", "Model", "World", "load_model", "load_world"]

_MODEL_FRAME = "__model__"
#: versions before 1.7 rename a clashing link, joint or frame (a warning that Drake raises)
_RENAMES_BEFORE = (1, 7)


def is_reserved(name: str) -> bool:
    """libsdformat's isReservedName: ``world``, or ``__x__``."""
    return name == "world" or (len(name) >= 4 and name.startswith("__") and name.endswith("__"))


def _error(message: str) -> ModelParseError:
    return Diagnostics(None).error(message)


class _ModelWithoutLinkError(ModelParseError):
    """``A model must have at least one link.``: libsdformat records it and goes on."""

    def __init__(self) -> None:
        super().__init__(*_error("A model must have at least one link.").args)


@dataclass
class Link:
    name: str
    element: XmlElement
    pose: GzPose
    relative_to: str


@dataclass
class Joint:
    name: str
    element: XmlElement
    pose: GzPose
    relative_to: str
    parent: str
    child: str
    type: str
    #: each ``<axis>``/``<axis2>``'s ``<xyz expressed_in>``
    expressed_in: list[str] = field(default_factory=list)


@dataclass
class Frame:
    name: str
    element: XmlElement | None
    pose: GzPose
    relative_to: str
    attached_to: str


@dataclass
class Model:
    name: str
    element: XmlElement
    pose: GzPose
    relative_to: str
    placement_frame: str
    static: bool
    canonical_attribute: str
    links: list[Link] = field(default_factory=list)
    joints: list[Joint] = field(default_factory=list)
    frames: list[Frame] = field(default_factory=list)
    models: list[Model] = field(default_factory=list)
    interfaces: list[InterfaceModel] = field(default_factory=list)
    merged_interfaces: list[InterfaceModel] = field(default_factory=list)
    merged: bool = False

    def link_by_name(self, name: str) -> Link | None:
        namespace, local = scoped.split(name)
        owner: Model | None = self
        for part in namespace.split(scoped.DELIMITER) if namespace else []:
            owner = next((m for m in owner.models if m.name == part), None) if owner else None
        if owner is None:
            owner = self
            local = name
        return next((link for link in owner.links if link.name == local), None)

    def canonical(self) -> tuple[Link | None, str]:
        """libsdformat's CanonicalLinkAndRelativeName."""
        if self.canonical_attribute:
            return self.link_by_name(self.canonical_attribute), self.canonical_attribute
        if self.links:
            return self.links[0], self.links[0].name
        interface_links = [link.name for m in self.merged_interfaces for link in m.links]
        if interface_links:
            return None, interface_links[0]
        if self.models:
            link, name = self.models[0].canonical()
            return link, scoped.join(self.models[0].name, name) if name else ""
        if self.interfaces:
            name = self.interfaces[0].canonical_link
            return None, scoped.join(self.interfaces[0].name, name) if name else ""
        return None, ""

    def graph_model(self) -> GModel:
        """The model as libsdformat's graphs see it (ModelWrapper)."""
        model = GModel(
            name=self.name,
            static=self.static,
            pose=self.pose,
            relative_to=self.relative_to,
            canonical_link=self.canonical()[1],
            placement_frame=self.placement_frame,
            links=[GLink(link.name, link.pose, link.relative_to) for link in self.links],
            frames=[GFrame(f.name, f.pose, f.relative_to, f.attached_to) for f in self.frames],
            joints=[GJoint(j.name, j.child, j.pose, j.relative_to) for j in self.joints],
            models=[
                *(m.graph_model() for m in self.models),
                *(i.graph_model() for i in self.interfaces),
            ],
        )
        for interface in self.merged_interfaces:
            _add_merged_interface(model, interface)
        return model


def _add_merged_interface(model: GModel, interface: InterfaceModel) -> None:
    proxy = merged_frame_name(interface.name)
    relative_to, X = interface.include_pose if interface.include_pose else ("", interface.X_PM)
    model.frames.append(GFrame(proxy, X, relative_to or _MODEL_FRAME, interface.canonical_link))
    for link in interface.links:
        model.links.append(GLink(link.name, link.pose, proxy))
    for frame in interface.frames:
        attached_to = proxy if frame.attached_to == _MODEL_FRAME else frame.attached_to
        model.frames.append(GFrame(frame.name, frame.pose, attached_to, attached_to))
    for joint in interface.joints:
        child = proxy if joint.child == _MODEL_FRAME else joint.child
        model.joints.append(GJoint(joint.name, child, joint.pose, child, "Interface Joint"))
    if interface.placement_frame:
        model.merged_placements.append((proxy, interface.placement_frame))


@dataclass
class World:
    name: str
    element: XmlElement
    models: list[Model] = field(default_factory=list)
    interfaces: list[InterfaceModel] = field(default_factory=list)
    joints: list[Joint] = field(default_factory=list)
    frames: list[Frame] = field(default_factory=list)

    def graph_world(self) -> GWorld:
        return GWorld(
            name=self.name,
            frames=[GFrame(f.name, f.pose, f.relative_to, f.attached_to) for f in self.frames],
            joints=[GJoint(j.name, j.child, j.pose, j.relative_to) for j in self.joints],
            models=[
                *(m.graph_model() for m in self.models),
                *(i.graph_model() for i in self.interfaces),
            ],
        )


class _Loader:
    def __init__(self, context: ParseContext, loaded: Loaded, version: tuple[int, ...]) -> None:
        self.context = context
        self.loaded = loaded
        self.version = version
        #: A custom merge-include refused up to 1.22, raised once the document is loaded.
        self.refused: ModelParseError | None = None
        #: The first nested model without a link, raised once the document is loaded.
        self.linkless: ModelParseError | None = None

    @contextlib.contextmanager
    def refusal_first(self) -> Iterator[None]:
        """Raises the refused merge-include, if any, once loading ends: before a later
        error of the document (measured on pydrake 1.16.0: it is the error reported);
        else the first nested model without a link, before a later error."""
        try:
            yield
        except ModelParseError:
            recorded = self.refused or self.linkless
            if recorded is not None:
                raise recorded from None
            raise
        recorded = self.refused or self.linkless
        if recorded is not None:
            raise recorded

    # ----------------------------------------------------------- elements
    def link(self, element: XmlElement) -> Link:
        name = element.get("name", "")
        if is_reserved(name):
            raise _error(f"The supplied link name [{name}] is reserved.")
        for role in ("visual", "collision"):
            seen: set[str] = set()
            for geometry in children(element, role):
                geometry_name = geometry.get("name", "")
                if geometry_name in seen:
                    raise _error(f"{role} with name[{geometry_name}] already exists.")
                seen.add(geometry_name)
        relative_to, X = read_pose(element)
        return Link(name, element, X, relative_to)

    def joint(self, element: XmlElement) -> Joint:
        name = element.get("name", "")
        if is_reserved(name):
            raise _error(f"The supplied joint name [{name}] is reserved.")
        relative_to, X = read_pose(element)
        parent = _first_text(element, "parent")
        child = _first_text(element, "child")
        if child == "world":
            raise _error(f"Joint with name[{name}] specified invalid child link [world].")
        if child == parent:
            raise _error(
                f"Joint with name[{name}] must specify different frame names for parent and "
                f"child, while [{child}] was specified for both."
            )
        joint_type = element.get("type", "").lower()
        if joint_type not in _JOINT_TYPES:
            raise _error(
                f"Joint type of {joint_type} is invalid. Refer to the SDF documentation for a "
                "list of valid joint types"
            )
        expressed_in = []
        for axis in (*children(element, "axis"), *children(element, "axis2")):
            xyz = children(axis, "xyz")[:1]
            values = [float(v) for v in (xyz[0].text or "").split()] if xyz else [0.0, 0.0, 1.0]
            if abs(math.sqrt(sum(v * v for v in values))) <= 1e-6:
                raise _error("The norm of the xyz vector cannot be zero")
            expressed_in.append(xyz[0].get("expressed_in", "") if xyz else "")
        return Joint(name, element, X, relative_to, parent, child, joint_type, expressed_in)

    def frame(self, element: XmlElement) -> Frame:
        name = element.get("name", "")
        if is_reserved(name):
            raise _error(f"The supplied frame name [{name}] is reserved.")
        relative_to, X = read_pose(element)
        return Frame(name, element, X, relative_to, element.get("attached_to", ""))

    # -------------------------------------------------------------- model
    def model(self, element: XmlElement, parents: list[str]) -> Model:
        """Model::Load; ``parents`` are the enclosing models' names (merged ones left out)."""
        version = self.loaded.versions.get(element, self.version)
        saved, self.version = self.version, version
        try:
            return self._model(element, parents)
        finally:
            self.version = saved

    def _model_or_none(self, element: XmlElement, parents: list[str]) -> Model | None:
        """``model()``, or None once a merge-include was refused (up to 1.22): libsdformat
        records a later model's error and goes on loading the document, so the custom
        models after it are parsed too, and the refusal is the error reported (measured
        with top_merge_include_world.sdf on pydrake 1.16.0: both tops' URDFs parsed).
        A nested model without a link is recorded the same way and left out (measured with
        top_merge_include_world.sdf and top_merge_include_in_nested_model.sdf on pydrake
        1.23.0 and 1.24.0, whose first arm_mjcf has none: the later includes are parsed)."""
        try:
            return self.model(element, parents)
        except _ModelWithoutLinkError as error:
            if self.linkless is None:
                self.linkless = error
            return None
        except ModelParseError:
            if self.refused is None and self.linkless is None:
                raise
            return None

    def _model(self, element: XmlElement, parents: list[str]) -> Model:
        name = element.get("name", "")
        if is_reserved(name):
            raise _error(f"The supplied model name [{name}] is reserved.")
        relative_to, X = read_pose(element)
        static_elements = children(element, "static")
        model = Model(
            name=name,
            element=element,
            pose=X,
            relative_to=relative_to,
            placement_frame=element.get("placement_frame", ""),
            static=bool(sdformat_bool(static_elements[0].text or "")) if static_elements else False,
            canonical_attribute=element.get("canonical_link", ""),
            merged=element in self.loaded.merged,
        )
        _check_unique_children(element, "model")
        own = parents if model.merged else [*parents, name]
        self._interfaces(element, own, model.interfaces, model.merged_interfaces)
        implicit = {i.name for i in model.interfaces}
        names: dict[str, set[str]] = {"model": set(), "link": set(), "joint": set(), "frame": set()}
        for child in element:
            assert isinstance(child, XmlElement)
            if child.tag == "model":
                nested = self._model_or_none(child, own)
                if nested is None:
                    continue
                _record(names["model"], "model", nested.name)
                if nested.merged:
                    self._merge(model, nested, implicit)
                else:
                    implicit.add(nested.name)
                    model.models.append(nested)
            elif child.tag in ("link", "joint", "frame"):
                item = getattr(self, child.tag)(child)
                _record(names[child.tag], child.tag, item.name)
                self._check_collision(item, child.tag, model.name, implicit)
                getattr(model, f"{child.tag}s").append(item)
        if not (
            model.static
            or model.links
            or model.merged_interfaces
            or model.models
            or model.interfaces
        ):
            raise _ModelWithoutLinkError()
        return model

    def _check_collision(self, item: Any, tag: str, model: str, implicit: set[str]) -> None:
        if item.name in implicit:
            kind = tag.capitalize()
            if self.version < _RENAMES_BEFORE:
                suffix = f"{item.name}_{tag}"
                counter = 0
                while suffix in implicit:
                    suffix = f"{item.name}_{tag}{counter}"
                    counter += 1
                raise _error(
                    f"{kind} with name [{item.name}] in model with name [{model}] has a name "
                    f"collision, changing {tag} name to [{suffix}]."
                )
            raise _error(
                f"{kind} with name [{item.name}] in model with name [{model}] has a name "
                f"collision. Please rename this {tag}."
            )
        implicit.add(item.name)

    def _interfaces(
        self,
        element: XmlElement,
        parents: list[str],
        interfaces: list[InterfaceModel],
        merged: list[InterfaceModel] | None,
    ) -> None:
        """loadIncludedInterfaceModels: each custom ``<include>`` parsed into the plant."""
        for include in children(element, "include"):
            uri = " ".join(text_of(u) for u in children(include, "uri")[:1])
            path = find_file(uri, self.context.package_map)
            if path is None or not is_custom_file(path):
                continue
            names = children(include, "name")
            statics = children(include, "static")
            merge = bool(sdformat_bool(include.get("merge", "false")))
            # Up to 1.22 the custom parser ignores merge (the model is parsed nested), and
            # libsdformat refuses it once every include is loaded
            # (sdf-merge-include-custom-parser-since-1.23: measured on pydrake 1.16.0 and
            # 1.22.0: the URDFs' bodies, the later includes' too, stay in the plant).
            unmergeable = merge and not release.has("sdf-merge-include-custom-parser-since-1.23")
            interface = load_interface_model(
                self.context,
                path,
                local_name=text_of(names[0]) if names else None,
                parent_name=scoped.join(*parents) if parents else None,
                merge=merge and not unmergeable,
                static=bool(sdformat_bool(statics[0].text or "")) if statics else False,
            )
            if interface.warned:
                continue  # left out by libsdformat; its bodies stay in the plant
            if unmergeable and self.refused is None:
                self.refused = Diagnostics(None).error(
                    "Custom parser does not support merge-include, but merge-include was "
                    f"requested for model with uri [{uri}]"
                )
            poses = children(include, "pose")
            if poses:
                interface.include_pose = read_pose(include)
            placements = children(include, "placement_frame")
            if placements:
                interface.placement_frame = text_of(placements[0])
            if merge and merged is not None:
                merged.append(interface)
            else:
                interfaces.append(interface)

    def _merge(self, parent: Model, child: Model, implicit: set[str]) -> None:
        """Model::PrepareForMerge, then the child's elements become the parent's."""
        graphs = Graphs.of_model(child.graph_model())
        proxy = merged_frame_name(child.name)
        X = child.pose
        if child.placement_frame:
            X = graphs.X_scope("__root__", child.name)
        parent.frames.append(
            Frame(proxy, None, X, child.relative_to or _MODEL_FRAME, child.canonical()[1])
        )
        _rename_model_frame(child, proxy)
        parent.links += child.links
        parent.frames += child.frames
        parent.joints += child.joints
        implicit.update(m.name for m in child.models)
        implicit.update(i.name for i in child.interfaces)
        parent.models += child.models
        parent.interfaces += child.interfaces
        parent.merged_interfaces += child.merged_interfaces

    # -------------------------------------------------------------- world
    def world(self, element: XmlElement) -> World:
        name = element.get("name", "")
        if is_reserved(name):
            raise _error(f"The supplied world name [{name}] is reserved.")
        _check_unique_children(element, "world")
        world = World(name, element)
        self._interfaces(element, [], world.interfaces, None)
        implicit = {i.name for i in world.interfaces}
        names: dict[str, set[str]] = {"model": set(), "joint": set(), "frame": set()}
        for child in element:
            assert isinstance(child, XmlElement)
            if child.tag == "model":
                loaded = self._model_or_none(child, [])
                if loaded is None:
                    continue
                model = loaded
                _record(names["model"], "model", model.name)
                implicit.add(model.name)
                if model.merged:
                    self._merge_into_world(world, model)
                else:
                    world.models.append(model)
            elif child.tag in ("joint", "frame"):
                item = getattr(self, child.tag)(child)
                _record(names[child.tag], child.tag, item.name)
                getattr(world, f"{child.tag}s").append(item)
        for frame in world.frames:
            if frame.name in implicit:
                raise _error(
                    f"Frame with name [{frame.name}] in world with name [{name}] has a name "
                    "collision. Please rename this frame."
                )
            implicit.add(frame.name)
        return world

    def _merge_into_world(self, world: World, model: Model) -> None:
        Graphs.of_model(model.graph_model())
        proxy = merged_frame_name(model.name)
        X = model.pose
        world.frames.append(
            Frame(proxy, None, X, model.relative_to or "world", model.canonical()[1])
        )
        _rename_model_frame(model, proxy)
        world.frames += model.frames
        world.joints += model.joints
        world.models += model.models
        world.interfaces += model.interfaces


_JOINT_TYPES = frozenset(
    {"ball", "continuous", "fixed", "gearbox", "prismatic", "revolute", "revolute2", "screw",
     "universal"}
)  # fmt: skip


def _first_text(element: XmlElement, tag: str) -> str:
    found = children(element, tag)
    return text_of(found[0]) if found else ""


def _record(names: set[str], tag: str, name: str) -> None:
    if name in names:
        raise _error(f"{tag} with name[{name}] already exists.")
    names.add(name)


def _check_unique_children(element: XmlElement, kind: str) -> None:
    counts = Counter(
        child.get("name") for child in element if child.tag != "plugin" and "name" in child.attrib
    )
    for name, count in sorted((n, c) for n, c in counts.items() if n is not None):
        if count > 1:
            raise _error(
                f"Non-unique name[{name}] detected {count} times in XML children of {kind} "
                f"with name[{element.get('name')}]."
            )


def _is_model_frame(name: str) -> bool:
    return not name or name == _MODEL_FRAME


def _rename_model_frame(model: Model, proxy: str) -> None:
    """What named the merged model's frame (``__model__``, or nothing) names the proxy frame."""
    for link in model.links:
        if _is_model_frame(link.relative_to):
            link.relative_to = proxy
    for frame in model.frames:
        if _is_model_frame(frame.attached_to):
            frame.attached_to = proxy
        if frame.relative_to == _MODEL_FRAME:
            frame.relative_to = proxy
    for joint in model.joints:
        if joint.relative_to == _MODEL_FRAME:
            joint.relative_to = proxy
        joint.parent = proxy if joint.parent == _MODEL_FRAME else joint.parent
        joint.child = proxy if joint.child == _MODEL_FRAME else joint.child
        joint.expressed_in = [proxy if e == _MODEL_FRAME else e for e in joint.expressed_in]
    for nested in model.models:
        if _is_model_frame(nested.relative_to):
            nested.relative_to = proxy
    for interface in [*model.interfaces, *model.merged_interfaces]:
        relative_to, X = interface.include_pose if interface.include_pose else ("", None)
        if _is_model_frame(relative_to):
            interface.include_pose = (proxy, X if X is not None else interface.X_PM)


def load_model(
    context: ParseContext, loaded: Loaded, element: XmlElement, version: tuple[int, ...]
) -> Model:
    """The document's ``<model>`` (Model::Load); raises libsdformat's first error."""
    loader = _Loader(context, loaded, version)
    with loader.refusal_first():
        return loader.model(element, [])


def load_world(
    context: ParseContext, loaded: Loaded, element: XmlElement, version: tuple[int, ...]
) -> World:
    loader = _Loader(context, loaded, version)
    with loader.refusal_first():
        return loader.world(element)
