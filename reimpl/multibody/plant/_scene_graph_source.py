"""The plant as a SceneGraph source: a frame per body, named by scoped names.

Drake counterpart: MultibodyPlant's SceneGraph registration
(multibody_plant.cc). Measured on pydrake 1.51.1:

- ``RegisterAsSourceForSceneGraph`` (once, before Finalize) registers the
  plant's name as a source; from then on every body B but the world gets a
  frame F(B) named ``scoped(B)`` with frame group = B's model instance, and
  F(world) is the world frame (a world geometry is anchored).
- ``RenameModelInstance`` renames the instance's frames (frame group = the
  instance) and their geometries named ``old::x`` to ``new::x``.
- ``CollectRegisteredGeometries(bodies)`` is GeometrySet({F(B) : B ∈
  bodies}): frames, resolved when a declaration is applied (F(world) then
  means every anchored geometry).
- A call that needs a source on a plant that is none ends the program
  (SystemExit, the demand ``_DEMANDS`` names); a C++-only one raises
  DemandFailedError.
"""

from __future__ import annotations

from collections.abc import Sequence

from reimpl.geometry.geometry_instance import GeometryFrame
from reimpl.geometry.geometry_set import GeometrySet
from reimpl.geometry.identifier import FrameId, GeometryId, SourceId
from reimpl.geometry.scene_graph import SceneGraph
from reimpl.multibody import _link_joint_graph as graph
from reimpl.multibody._errors import FinalizedError, NotFoundError
from reimpl.multibody.plant._demands import demand, demand_failed
from reimpl.multibody.plant._elements import Elements
from reimpl.multibody.tree import BodyIndex, RigidBody

__all__ = ["SceneGraphSource"]

#: The demands (ids of reimpl/common/demand_lines.json) that the plant is (not) a
#: SceneGraph source, by public method. pydrake raises SystemExit (measured).
_DEMANDS = {
    "RegisterAsSourceForSceneGraph": "RegisterAsSourceForSceneGraph.registered",
    "RegisterVisualGeometry": "RegisterVisualGeometry.no_source",
    "RegisterCollisionGeometry": "RegisterCollisionGeometry.no_source",
    "CollectRegisteredGeometries": "CollectRegisteredGeometries.no_source",
}


class SceneGraphSource(Elements):
    """The SceneGraph, the source id, and each body's frame id and geometry ids."""

    def __init__(self) -> None:
        super().__init__()
        self._scene_graph: SceneGraph | None = None
        self._source_id: SourceId | None = None
        self._body_frame_ids: dict[int, FrameId] = {}
        self._collision_geometries: dict[int, list[GeometryId]] = {}
        self._visual_geometries: dict[int, list[GeometryId]] = {}

    def RegisterAsSourceForSceneGraph(self, scene_graph: SceneGraph) -> SourceId:
        """Registers this plant (by its name) as a source; every body so far gets a frame.

        Measured on pydrake 1.51.1: a second registration fails its demand before
        Finalize is checked.
        """
        method = "RegisterAsSourceForSceneGraph"
        demand(self._source_id is None, _DEMANDS[method])
        if self._finalized:
            raise FinalizedError(
                "This MultibodyPlant is finalized already; RegisterAsSourceForSceneGraph() "
                "must be called before Finalize()."
            )
        self._source_id = scene_graph.RegisterSource(name=self.get_name())
        self._scene_graph = scene_graph
        for body in self._bodies:
            self._register_body_frame(body)
        return self._source_id

    def geometry_source_is_registered(self) -> bool:
        return self._source_id is not None

    def get_source_id(self) -> SourceId | None:
        return self._source_id

    def _registered_scene_graph(self, method: str) -> tuple[SceneGraph, SourceId]:
        """The SceneGraph and source id; pydrake's SystemExit (measured) for a public
        ``method`` of a plant that is no source, DemandFailedError for an internal one."""
        if self._scene_graph is None or self._source_id is None:
            condition = "geometry_source_is_registered()"
            if method in _DEMANDS:
                demand(False, _DEMANDS[method])
            raise demand_failed(method, condition)
        return self._scene_graph, self._source_id

    def _add_body(self, body: RigidBody) -> RigidBody:
        """And the body's (empty) geometry lists, and its SceneGraph frame if a source."""
        super()._add_body(body)
        index = int(body.index())
        self._collision_geometries[index] = []
        self._visual_geometries[index] = []
        self._register_body_frame(body)
        return body

    def _register_body_frame(self, body: RigidBody) -> None:
        index = int(body.index())
        if self._scene_graph is None or self._source_id is None:
            return
        if index == graph.WORLD:
            self._body_frame_ids[index] = self._scene_graph.world_frame_id()
            return
        frame = GeometryFrame(
            frame_name=self._scoped(body.model_instance(), body.name()),
            frame_group_id=int(body.model_instance()),
        )
        self._body_frame_ids[index] = self._scene_graph.RegisterFrame(
            source_id=self._source_id, frame=frame
        )

    def _rename_instance(self, index: int, old: str, name: str) -> None:
        """And ``old::x`` → ``name::x`` for the instance's frames and their geometries."""
        super()._rename_instance(index, old, name)
        if self._scene_graph is None or self._source_id is None:
            return
        scene_graph = self._scene_graph
        inspector = scene_graph.model_inspector()
        old_prefix = f"{old}::"

        def renamed(current: str) -> str | None:
            return (
                f"{name}::{current[len(old_prefix) :]}" if current.startswith(old_prefix) else None
            )

        for frame_id in inspector.FramesForSource(source_id=self._source_id):
            if inspector.GetFrameGroup(frame_id=frame_id) != index:
                continue
            new_name = renamed(inspector.GetName(frame_id=frame_id))
            if new_name is not None:
                scene_graph.RenameFrame(frame_id=frame_id, name=new_name)
            for geometry_id in inspector.GetGeometryIds(GeometrySet(frame_id=frame_id)):
                new_name = renamed(inspector.GetName(geometry_id=geometry_id))
                if new_name is not None:
                    scene_graph.RenameGeometry(geometry_id=geometry_id, name=new_name)

    def GetBodyFromFrameId(self, frame_id: FrameId, /) -> RigidBody | None:
        """The body whose SceneGraph frame is ``frame_id``, else None.

        N.B. pydrake binds the parameter without a name: it is positional only.
        """
        for index, body_frame_id in self._body_frame_ids.items():
            if body_frame_id == frame_id:
                return self._bodies[index]
        return None

    def GetBodyFrameIdIfExists(self, body_index: BodyIndex) -> FrameId | None:
        return self._body_frame_ids.get(int(body_index))

    def GetBodyFrameIdOrThrow(self, body_index: BodyIndex) -> FrameId:
        body = self.get_body(body_index)
        frame_id = self._body_frame_ids.get(int(body_index))
        if frame_id is None:
            raise NotFoundError(f"Body '{body.name()}' does not have geometry registered with it.")
        return frame_id

    def CollectRegisteredGeometries(self, bodies: Sequence[RigidBody]) -> GeometrySet:
        """GeometrySet({F(B) : B ∈ bodies}); F(world) is the world frame.

        It holds frames, not geometries, so it resolves when a declaration is
        applied: F(world) then means every anchored proximity geometry.
        """
        self._registered_scene_graph("CollectRegisteredGeometries")
        return self._collect([int(body.index()) for body in bodies])

    def _collect(self, bodies: Sequence[int]) -> GeometrySet:
        return GeometrySet(frame_ids=[self._body_frame_ids[b] for b in bodies])
