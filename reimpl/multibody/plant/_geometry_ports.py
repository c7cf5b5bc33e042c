"""The plant's two SceneGraph ports: ``geometry_pose`` out, ``geometry_query`` in.

Drake counterpart: MultibodyPlant's geometry ports (multibody_plant.cc).

- ``geometry_pose`` gives the FramePoseVector {F(B): X_WB} for every body B
  but the world that has a SceneGraph frame, at the context's q; SceneGraph
  reads it on the source's pose port. Like Drake's cached output, the same
  vector is returned while q is unchanged.
- ``geometry_query`` reads the SceneGraph's QueryObject;
  ``EvalSceneGraphInspector`` is that object's inspector, or Drake's error
  for a context whose port is not connected.
- ``AddMultibodyPlantSceneGraph`` connects both.
"""

from __future__ import annotations

from typing import Any

from reimpl.geometry.query_object import FramePoseVector
from reimpl.multibody import _link_joint_graph as graph
from reimpl.multibody._errors import MultibodyPlantError
from reimpl.multibody.plant._poses import Poses, as_rigid_transform
from reimpl.multibody.plant._scene_graph_source import SceneGraphSource
from reimpl.systems.framework import Context, InputPort, OutputPort

__all__ = ["GeometryPorts"]

#: Where a plant context caches its frame poses (Context._values).
_FRAME_POSES = "geometry_pose"


class GeometryPorts(SceneGraphSource, Poses):
    """The ports and what they carry."""

    def __init__(self) -> None:
        super().__init__()
        self._geometry_query_port = InputPort(self, "geometry_query", 0)
        self._geometry_pose_port = OutputPort(self, "geometry_pose", 0, self._calc_frame_poses)

    def get_geometry_query_input_port(self) -> InputPort:
        return self._geometry_query_port

    def get_geometry_pose_output_port(self) -> OutputPort:
        return self._geometry_pose_port

    def _calc_frame_poses(self, context: Context) -> FramePoseVector:
        """{F(B): X_WB} for every body B but the world that has a SceneGraph frame.

        Like Drake's cached output, the same vector is returned while q is
        unchanged (so SceneGraph need not re-pose).
        """
        key = self._context_positions(context).tobytes()
        cached = context._values.get(_FRAME_POSES)
        if cached is not None and cached[0] == key:
            return cached[1]  # type: ignore[no-any-return]
        poses = FramePoseVector()
        world_poses = self._body_poses(context)
        for index, frame_id in self._body_frame_ids.items():
            if index != graph.WORLD:
                poses.set_value(frame_id, as_rigid_transform(world_poses[index]))
        context._values[_FRAME_POSES] = (key, poses)
        return poses

    def EvalSceneGraphInspector(self, context: Context) -> Any:
        """The inspector of the QueryObject on the ``geometry_query`` port."""
        port = self.get_geometry_query_input_port()
        if not port.HasValue(context):
            raise MultibodyPlantError(
                "EvalSceneGraphInspector\n\nThe provided context doesn't show a connection for "
                "the plant's query input port (see "
                "MultibodyPlant::get_geometry_query_input_port()). See "
                "https://drake.mit.edu/troubleshooting.html#mbp-unconnected-query-object-port "
                "for help."
            )
        return port.Eval(context).inspector()
