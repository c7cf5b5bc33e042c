"""SDFormat's two frame graphs, their errors, and the queries Drake makes of them.

libsdformat (as Drake 1.51.1 uses it) builds, for the document's model or
world, an *attached-to* graph (which frame is rigidly attached to which) and a
*pose* graph (which frame each pose is expressed in). Names are scoped:
inside model ``m`` a name ``x`` is the vertex ``m::x``, ``inner::x`` reaches
into a nested model, ``__model__`` is the model's own frame and only a world
knows ``world``. A nested model ``n`` is two vertices, ``m::n`` and its frame
``m::n::__model__``, joined by an alias edge.

============  ================================  ===============================
 element       attached to (edge from it)        pose relative to (default)
============  ================================  ===============================
 link          (nothing: links end the chains)   ``__model__``
 joint         its ``<child>``                   its ``<child>``
 frame         ``attached_to`` (``__model__``)   ``attached_to``
 model         its canonical link (the first     the parent's ``__model__``
               link, else the first nested       (a world's models: ``world``)
               model's, ...)
============  ================================  ===============================

A model is built as: its vertices (links, joints, frames), its nested models
(each built whole), then its edges (joints, frames, canonical link); the pose
graph likewise. The first unknown name raises libsdformat's message, e.g.
``attached_to name[world] specified by frame with name[Wd] does not match a
nested model, link, joint, or frame name in model with name[m].``; then a
cycle raises ``FrameAttachedToGraph cycle detected, already visited vertex
[m::f].`` (or ``PoseRelativeToGraph ...``). Poses compose in gz-math's
arithmetic (_sdf_poses), from the scope's own frame, as libsdformat does.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

from reimpl.multibody.parsing._diagnostics import Diagnostics, ModelParseError
from reimpl.multibody.parsing._sdf_poses import IDENTITY, GzPose

__all__ = ["GFrame", "GJoint", "GLink", "GModel", "Graphs", "join"]

_ROOT = "__root__"
_MODEL_FRAME = "__model__"
_WORLD = "world"


def join(prefix: str, name: str) -> str:
    return f"{prefix}::{name}" if prefix else name


def _error(message: str) -> ModelParseError:
    return Diagnostics(None).error(message)


@dataclass(frozen=True)
class GLink:
    name: str
    pose: GzPose = IDENTITY
    relative_to: str = ""
    kind: str = "Link"


@dataclass(frozen=True)
class GFrame:
    name: str
    pose: GzPose = IDENTITY
    raw_relative_to: str = ""
    attached_to: str = ""
    kind: str = "Frame"

    @property
    def relative_to(self) -> str:
        return self.raw_relative_to or self.attached_to


@dataclass(frozen=True)
class GJoint:
    name: str
    child: str
    pose: GzPose = IDENTITY
    raw_relative_to: str = ""
    kind: str = "Joint"

    @property
    def relative_to(self) -> str:
        return self.raw_relative_to or self.child


@dataclass
class GModel:
    """A model as both graphs see it (its interface parts included)."""

    name: str
    static: bool = False
    pose: GzPose = IDENTITY
    relative_to: str = ""
    canonical_link: str = ""
    placement_frame: str = ""
    kind: str = "Model"
    links: list[GLink] = field(default_factory=list)
    frames: list[GFrame] = field(default_factory=list)
    joints: list[GJoint] = field(default_factory=list)
    models: list[GModel] = field(default_factory=list)
    #: (proxy frame, placement frame) of merged interface models
    merged_placements: list[tuple[str, str]] = field(default_factory=list)


@dataclass
class GWorld:
    name: str
    frames: list[GFrame] = field(default_factory=list)
    joints: list[GJoint] = field(default_factory=list)
    models: list[GModel] = field(default_factory=list)


@dataclass
class _Graph:
    types: dict[str, str] = field(default_factory=dict)

    def count(self, prefix: str, name: str) -> bool:
        return join(prefix, name) in self.types


@dataclass
class _FrameGraph(_Graph):
    #: vertex -> the vertex it is attached to (alias edges too)
    out: dict[str, list[str]] = field(default_factory=dict)

    def add_edge(self, source: str, target: str) -> None:
        self.out.setdefault(source, []).append(target)


@dataclass
class _PoseGraph(_Graph):
    #: vertex -> [(source, X_source_vertex)]
    into: dict[str, list[tuple[str, GzPose]]] = field(default_factory=dict)

    def add_edge(self, source: str, target: str, X: GzPose) -> None:
        self.into.setdefault(target, []).append((source, X))

    def set_edge(self, source: str, target: str, X: GzPose) -> None:
        self.into[target] = [(s, X if s == source else x) for s, x in self.into[target]]


def _lower(kind: str) -> str:
    return kind.lower()


class Graphs:
    """The frame and pose graphs of one model or world, built with libsdformat's checks."""

    def __init__(self) -> None:
        self.frame = _FrameGraph()
        self.pose = _PoseGraph()

    # ------------------------------------------------------------ building
    @staticmethod
    def of_model(model: GModel) -> Graphs:
        """Both graphs of a document's model (scope ``__root__``); raises the first error."""
        graphs = Graphs()
        graphs._build_frames(model, "", root=True)
        graphs._validate_frames()
        graphs._build_poses(model, "", root=True)
        graphs._validate_poses()
        return graphs

    @staticmethod
    def of_world(world: GWorld) -> Graphs:
        graphs = Graphs()
        graphs._build_world_frames(world)
        graphs._validate_frames()
        graphs._build_world_poses(world)
        graphs._validate_poses()
        return graphs

    def _add_vertices(
        self, graph: _Graph, items: Sequence[GLink | GFrame | GJoint], owner: _Owner, type_: str
    ) -> None:
        for item in items:
            name = join(owner.prefix, item.name)
            if name in graph.types:
                raise _error(
                    f"{item.kind} with non-unique name [{item.name}] detected in {owner.spaced}."
                )
            graph.types[name] = type_

    def _add_models(self, models: Sequence[GModel], owner: _Owner, graph: _Graph) -> None:
        for nested in models:
            if graph.count(owner.prefix, nested.name):
                raise _error(
                    f"{nested.kind} with non-unique name [{nested.name}] detected in "
                    f"{owner.spaced}."
                )
            if graph is self.frame:
                self._build_frames(nested, owner.prefix)
            else:
                self._build_poses(nested, owner.prefix)

    def _build_frames(self, model: GModel, prefix: str, root: bool = False) -> None:
        graph = self.frame
        if not model.links and not model.models and not model.static:
            raise _error("A model must have at least one link.")
        type_ = "STATIC_MODEL" if model.static else "MODEL"
        if root:
            graph.types[_ROOT] = "STATIC_MODEL"
        owner = _Owner.of(model, prefix)
        graph.types[owner.prefix] = type_
        graph.types[owner.scope] = type_
        graph.add_edge(owner.prefix, owner.scope)
        self._add_vertices(graph, model.links, owner, "LINK")
        self._add_vertices(graph, model.joints, owner, "JOINT")
        self._add_vertices(graph, model.frames, owner, "FRAME")
        self._add_models(model.models, owner, graph)
        self._joint_edges(model.joints, owner)
        self._frame_edges(model.frames, owner)
        if model.static:
            return
        canonical = model.canonical_link
        if not graph.count(owner.prefix, canonical):
            if canonical:
                raise _error(
                    f"canonical_link with name[{canonical}] not found in model with "
                    f"name[{model.name}]."
                )
            if not model.models:
                raise _error("A model must have at least one link.")
            graph.add_edge(owner.scope, join(owner.prefix, model.models[0].name))
            return
        graph.add_edge(owner.scope, join(owner.prefix, canonical))

    def _joint_edges(self, joints: Sequence[GJoint], owner: _Owner) -> None:
        for joint in joints:
            if not self.frame.count(owner.prefix, joint.child):
                raise _error(
                    f"Child frame with name[{joint.child}] specified by {_lower(joint.kind)} with "
                    f"name[{joint.name}] not found in {owner.described}."
                )
            self.frame.add_edge(join(owner.prefix, joint.name), join(owner.prefix, joint.child))

    def _frame_edges(self, frames: Sequence[GFrame], owner: _Owner) -> None:
        for frame in frames:
            attached_to = frame.attached_to or (_WORLD if owner.world else _MODEL_FRAME)
            if not self.frame.count(owner.prefix, attached_to):
                raise _error(
                    f"attached_to name[{attached_to}] specified by {_lower(frame.kind)} with "
                    f"name[{frame.name}] does not match a{owner.what}in {owner.described}."
                )
            if frame.name == frame.attached_to:
                raise _error(
                    f"attached_to name[{attached_to}] is identical to frame name"
                    f"[{frame.attached_to}], causing a graph cycle in {owner.described}."
                )
            self.frame.add_edge(join(owner.prefix, frame.name), join(owner.prefix, attached_to))

    def _build_world_frames(self, world: GWorld) -> None:
        graph = self.frame
        graph.types[_WORLD] = "WORLD"
        owner = _Owner.of_world(world)
        self._add_models(world.models, owner, graph)
        self._add_vertices(graph, world.joints, owner, "JOINT")
        self._add_vertices(graph, world.frames, owner, "FRAME")
        self._joint_edges(world.joints, owner)
        self._frame_edges(world.frames, owner)

    def _build_poses(self, model: GModel, prefix: str, root: bool = False) -> None:
        graph = self.pose
        if root:
            graph.types[_ROOT] = "MODEL"
        owner = _Owner.of(model, prefix)
        vertex, scope = owner.prefix, owner.scope
        graph.types[vertex] = "MODEL"
        graph.types[scope] = "MODEL"
        graph.add_edge(vertex, scope, IDENTITY)
        self._add_vertices(graph, model.links, owner, "LINK")
        self._add_vertices(graph, model.joints, owner, "JOINT")
        self._add_vertices(graph, model.frames, owner, "FRAME")
        self._add_models(model.models, owner, graph)
        items: list[GLink | GFrame | GJoint] = [*model.links, *model.joints, *model.frames]
        for item in items:
            self._pose_edge(item, owner)
        for nested in model.models:
            self._model_pose_edge(nested, owner)
        if root:
            graph.add_edge(_ROOT, vertex, IDENTITY)
            graph.set_edge(_ROOT, vertex, self._placed(model, vertex))
        for proxy, placement in model.merged_placements:
            raw = next((x for s, x in graph.into[join(vertex, proxy)] if s == scope), None)
            if raw is None:  # the proxy frame is posed in another frame: no edge to update
                continue
            graph.set_edge(scope, join(vertex, proxy), IDENTITY)
            X_MPf = self.X_scope(scope, join(vertex, placement))
            graph.set_edge(scope, join(vertex, proxy), raw * X_MPf.inverse())

    def _build_world_poses(self, world: GWorld) -> None:
        graph = self.pose
        graph.types[_ROOT] = "WORLD"
        graph.types[_WORLD] = "WORLD"
        graph.add_edge(_ROOT, _WORLD, IDENTITY)
        owner = _Owner.of_world(world)
        self._add_models(world.models, owner, graph)
        self._add_vertices(graph, world.joints, owner, "JOINT")
        self._add_vertices(graph, world.frames, owner, "FRAME")
        for nested in world.models:
            self._model_pose_edge(nested, owner)
        items: list[GFrame | GJoint] = [*world.joints, *world.frames]
        for item in items:
            self._pose_edge(item, owner)

    def _relative_vertex(self, item: GLink | GFrame | GJoint | GModel, owner: _Owner) -> str:
        """The vertex ``item``'s pose is relative to (by default the owner's own frame)."""
        relative_to = item.relative_to
        if not relative_to:
            return owner.scope
        if not self.pose.count(owner.prefix, relative_to):
            word = "relative_to"
            if isinstance(item, GFrame) and not item.raw_relative_to:
                word = "attached_to"
            raise _error(
                f"{word} name[{relative_to}] specified by {_lower(item.kind)} with "
                f"name[{item.name}] does not match a{owner.what}in {owner.described}."
            )
        if item.name == relative_to:
            raise _error(
                f"relative_to name[{relative_to}] is identical to {_lower(item.kind)} name"
                f"[{item.name}], causing a graph cycle in {owner.described}."
            )
        return join(owner.prefix, relative_to)

    def _pose_edge(self, item: GLink | GFrame | GJoint, owner: _Owner) -> None:
        source = self._relative_vertex(item, owner)
        self.pose.add_edge(source, join(owner.prefix, item.name), item.pose)

    def _model_pose_edge(self, model: GModel, owner: _Owner) -> None:
        source = self._relative_vertex(model, owner)
        vertex = join(owner.prefix, model.name)
        self.pose.add_edge(source, vertex, self._placed(model, vertex))

    def _placed(self, model: GModel, vertex: str) -> GzPose:
        """X_RM of a model whose ``<pose>`` places its ``placement_frame`` Pf: X_RPf · X_MPf⁻¹."""
        if not model.placement_frame:
            return model.pose
        scope = join(vertex, _MODEL_FRAME)
        target = join(vertex, model.placement_frame)
        if target not in self.pose.types:
            raise _error(
                "PoseRelativeToGraph unable to find unique frame with name "
                f"[{model.placement_frame}] in graph."
            )
        return model.pose * self.X_scope(scope, target).inverse()

    # ---------------------------------------------------------- validation
    def _validate_frames(self) -> None:
        for vertex in self.frame.types:
            seen = {vertex}
            current = vertex
            while self.frame.out.get(current):
                current = self.frame.out[current][0]
                if current in seen:
                    raise _error(
                        f"FrameAttachedToGraph cycle detected, already visited vertex [{current}]."
                    )
                seen.add(current)

    def _validate_poses(self) -> None:
        for vertex in self.pose.types:
            seen = {vertex}
            current = vertex
            while self.pose.into.get(current):
                current = self.pose.into[current][0][0]
                if current in seen:
                    raise _error(
                        f"PoseRelativeToGraph cycle detected, already visited vertex [{current}]."
                    )
                seen.add(current)

    # -------------------------------------------------------------- queries
    def X_scope(self, scope: str, vertex: str) -> GzPose:
        """The pose of ``vertex`` in the ``scope`` frame, composed edge by edge from the scope."""
        pose = IDENTITY
        while vertex != scope:
            source, X = self.pose.into[vertex][0]
            pose = X * pose
            vertex = source
        return pose

    def resolve(self, scope: str, vertex: str, resolve_to: str) -> GzPose:
        """X_RV (libsdformat's resolvePose): X_scope(R)⁻¹ · X_scope(V)."""
        for name in (vertex, resolve_to):
            if name not in self.pose.types:
                local = name.removeprefix(scope.removesuffix(_MODEL_FRAME))
                raise _error(
                    f"PoseRelativeToGraph unable to find unique frame with name [{local}] in graph."
                )
        return self.X_scope(scope, resolve_to).inverse() * self.X_scope(scope, vertex)

    def attached_body(self, vertex: str, name: str) -> str:
        """The vertex at the end of ``vertex``'s attached-to chain (a link, or world).

        ``name`` is how the caller named it (for libsdformat's message if it is unknown).
        """
        if vertex not in self.frame.types:
            raise _error(
                f"FrameAttachedToGraph unable to find unique frame with name [{name}] in graph."
            )
        while self.frame.out.get(vertex):
            vertex = self.frame.out[vertex][0]
        return vertex

    def has(self, vertex: str) -> bool:
        return vertex in self.frame.types


@dataclass(frozen=True)
class _Owner:
    """The model (or world) whose children are being added to a graph."""

    #: the prefix of its children's vertices (its own vertex; "" for a world)
    prefix: str
    #: the vertex of its own frame (``<prefix>::__model__``, or ``world``)
    scope: str
    name: str
    kind: str
    world: bool = False

    @staticmethod
    def of(model: GModel, parent_prefix: str) -> _Owner:
        vertex = join(parent_prefix, model.name)
        return _Owner(vertex, join(vertex, _MODEL_FRAME), model.name, model.kind)

    @staticmethod
    def of_world(world: GWorld) -> _Owner:
        return _Owner("", _WORLD, world.name, "World", world=True)

    @property
    def described(self) -> str:
        return f"{_lower(self.kind)} with name[{self.name}]"

    @property
    def spaced(self) -> str:
        """As the duplicate-name message writes it: ``model with name [m]``."""
        return f"{_lower(self.kind)} with name [{self.name}]"

    @property
    def what(self) -> str:
        """What a name in this owner may name."""
        if self.world:
            return " model or frame name "
        return " nested model, link, joint, or frame name "
