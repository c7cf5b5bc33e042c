"""A plant's bodies, frames and joints: adding them, and reading them back by index.

Drake counterpart: the element tables of MultibodyPlant's MultibodyTree
(multibody_plant.cc, multibody_tree.cc). Measured on pydrake 1.51.1:

- Body 0 is the world body and frame 0 its frame; a body's frame comes with
  it (same name, same model instance). Indices are given in the order
  elements are added, and elements are added only before Finalize.
- A name is unique per kind within a model instance: ``Model instance 'm'
  already contains a body named 'x'.`` (a body may share its name with a
  frame). A joint joins two bodies of this plant, never a body to itself,
  and no two joints join the same two bodies.
- ``num_positions``/``num_velocities`` add up the joints' (of one model
  instance); the instance is checked as Drake's per-instance tables check it.
- Listings by model instance (``GetBodyIndices``, ...) end the program
  (SystemExit) for an instance that does not exist.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, TypeVar

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl._release import release
from reimpl.math import RigidTransform
from reimpl.multibody._errors import (
    DuplicateNameError,
    FinalizedError,
    MultibodyPlantError,
    NotFoundError,
    TopologyError,
)
from reimpl.multibody._link_joint_graph import WORLD
from reimpl.multibody.plant._model_instances import PREDEFINED_INSTANCES, ModelInstances
from reimpl.multibody.tree import (
    BodyIndex,
    Frame,
    FrameIndex,
    Joint,
    JointIndex,
    ModelInstanceIndex,
    RigidBody,
    SpatialInertia,
    WeldJoint,
    default_model_instance,
    world_model_instance,
)

__all__ = ["Elements"]

_OWNER = "reimpl.multibody.plant.MultibodyPlant"

_E = TypeVar("_E", RigidBody, Frame, Joint)


class Elements(ModelInstances):
    """The bodies, frames and joints, each list in index order."""

    def __init__(self) -> None:
        super().__init__()
        self._bodies: list[RigidBody] = []
        self._frames: list[Frame] = []
        self._joints: list[Joint] = []

    def AddRigidBody(self, *args: Any, **kwargs: Any) -> RigidBody:
        """Adds a body (and its frame) to a model instance; returns it."""
        inertia = Param("M_BBo_B", instance_of(SpatialInertia), SpatialInertia.Zero())
        name = Param("name", instance_of(str))
        instance = Param("model_instance", instance_of(ModelInstanceIndex))
        return dispatch(  # type: ignore[no-any-return]
            _OWNER,
            "AddRigidBody",
            (
                Overload((name, inertia), self._add_rigid_body_to_default),
                Overload((name, instance, inertia), self._add_rigid_body),
            ),
            args,
            kwargs,
        )

    def _add_rigid_body_to_default(self, name: str, M_BBo_B: SpatialInertia) -> RigidBody:
        # N.B. Measured: the instance count is checked before Finalize is.
        if len(self._instance_names) > PREDEFINED_INSTANCES:
            raise MultibodyPlantError(
                "This model has more model instances than the default.  Please call "
                "AddRigidBody with an explicit model instance."
            )
        return self._add_rigid_body(name, default_model_instance(), M_BBo_B)

    def _add_rigid_body(
        self, name: str, model_instance: ModelInstanceIndex, M_BBo_B: SpatialInertia
    ) -> RigidBody:
        self._check_not_finalized("AddRigidBody")
        index = int(model_instance)
        if index == int(world_model_instance()):
            raise MultibodyPlantError(
                "AddLink(): Model instance index 0 is reserved for the World link.  World is "
                "always predefined and is named 'world'."
            )
        if not 0 <= index < len(self._instance_names):
            raise NotFoundError("Invalid model instance specified.")
        # N.B. Measured: a body may share its name with a FixedOffsetFrame.
        self._check_unique("body", self._bodies, name, model_instance)
        return self._add_body(RigidBody(name, model_instance, M_BBo_B))

    def _add_body(self, body: RigidBody) -> RigidBody:
        """Gives ``body`` the next BodyIndex and its frame the next FrameIndex."""
        body._adopt(self, len(self._bodies))
        self._bodies.append(body)
        frame = body.body_frame()
        frame._adopt(self, len(self._frames))
        self._frames.append(frame)
        return body

    def _check_unique(
        self, kind: str, elements: Sequence[_E], name: str, model_instance: ModelInstanceIndex
    ) -> None:
        """Up to 1.18 a frame name may repeat, and a repeated joint name is
        ``AddJoint(): Duplicate joint name 'j'.`` (unique-frame-names-since-1.19:
        measured on pydrake 1.18.0 and 1.19.0)."""
        old = not release.has("unique-frame-names-since-1.19")
        if old and kind == "frame":
            return
        if any(e.name() == name and e.model_instance() == model_instance for e in elements):
            if old and kind == "joint":
                raise DuplicateNameError(f"AddJoint(): Duplicate joint name '{name}'.")
            raise DuplicateNameError(
                f"Model instance '{self.GetModelInstanceName(model_instance)}' already contains "
                f"a {kind} named '{name}'. {kind.capitalize()} names must be unique within a "
                "given model."
            )

    def _in_range(self, kind: str, index: Any, elements: Sequence[object]) -> int:
        value = int(index)
        if not 0 <= value < len(elements):
            raise NotFoundError(
                f"The given {kind}({value}) is out of bounds (must be less than {len(elements)})"
            )
        return value

    def num_bodies(self) -> int:
        return len(self._bodies)

    def world_body(self) -> RigidBody:
        return self._bodies[WORLD]

    def world_frame(self) -> Frame:
        return self._frames[0]

    def get_body(self, body_index: BodyIndex) -> RigidBody:
        return self._bodies[self._in_range("RigidBodyIndex", body_index, self._bodies)]

    def GetBodyIndices(self, model_instance: ModelInstanceIndex) -> list[BodyIndex]:
        index = self._listed_instance("GetBodyIndices", model_instance)
        return [b.index() for b in self._bodies if int(b.model_instance()) == index]

    def AddFrame(self, frame: Frame) -> Frame:
        if self._finalized:
            raise FinalizedError(
                "This MultibodyTree is finalized already. Therefore adding more frames is not "
                "allowed. See documentation for Finalize() for details."
            )
        if frame.body()._plant is not self:
            raise TopologyError(
                f"AddFrame(): frame '{frame.name()}' is attached to a body of another plant."
            )
        self._check_unique("frame", self._frames, frame.name(), frame.model_instance())
        frame._adopt(self, len(self._frames))
        self._frames.append(frame)
        return frame

    def num_frames(self) -> int:
        return len(self._frames)

    def get_frame(self, frame_index: FrameIndex) -> Frame:
        return self._frames[self._in_range("FrameIndex", frame_index, self._frames)]

    def GetFrameIndices(self, model_instance: ModelInstanceIndex) -> list[FrameIndex]:
        index = self._listed_instance("GetFrameIndices", model_instance)
        return [f.index() for f in self._frames if int(f.model_instance()) == index]

    def AddJoint(self, joint: Joint) -> Joint:
        """Adds a joint between two bodies of this plant; returns it."""
        self._check_not_finalized("AddJoint")
        parent, child = joint.parent_body(), joint.child_body()
        if parent._plant is not self or child._plant is not self:
            raise TopologyError(
                f"AddJoint(): can't add joint {joint.name()} because bodies {parent.name()} "
                f"and {child.name()} are from different MultibodyPlants."
            )
        if parent is child:
            raise TopologyError(
                f"AddJoint(): joint {joint.name()} would connect body {parent.name()} to itself."
            )
        self._check_unique("joint", self._joints, joint.name(), joint.model_instance())
        for other in self._joints:
            if {other.parent_body(), other.child_body()} == {parent, child}:
                raise TopologyError(
                    f"AddJoint(): This LinkJointGraph already has joint '{other.name()}' (model "
                    f"instance {int(other.model_instance())}) connecting link "
                    f"'{other.parent_body().name()}' to link '{other.child_body().name()}'. "
                    f"Therefore adding joint '{joint.name()}' (model instance "
                    f"{int(joint.model_instance())}) connecting link '{parent.name()}' to link "
                    f"'{child.name()}' is not allowed."
                )
        joint._adopt(self, len(self._joints))
        self._joints.append(joint)
        return joint

    def WeldFrames(
        self,
        frame_on_parent_F: Frame,
        frame_on_child_M: Frame,
        X_FM: RigidTransform | None = None,
    ) -> WeldJoint:
        """Adds the WeldJoint ``F_welds_to_M`` (F and M being the frames' names)."""
        name = f"{frame_on_parent_F.name()}_welds_to_{frame_on_child_M.name()}"
        weld = WeldJoint(name, frame_on_parent_F, frame_on_child_M, X_FM or RigidTransform())
        self.AddJoint(weld)
        return weld

    def num_joints(self) -> int:
        return len(self._joints)

    def get_joint(self, joint_index: JointIndex) -> Joint:
        return self._joints[self._in_range("JointIndex", joint_index, self._joints)]

    def has_joint(self, joint_index: JointIndex) -> bool:
        return 0 <= int(joint_index) < len(self._joints)

    def get_mutable_joint(self, joint_index: JointIndex) -> Joint:
        return self.get_joint(joint_index)

    def GetJointIndices(self, *args: Any, **kwargs: Any) -> list[JointIndex]:
        def of(model_instance: ModelInstanceIndex | None = None) -> list[JointIndex]:
            if model_instance is None:
                return [j.index() for j in self._joints]
            index = self._listed_instance("GetJointIndices", model_instance)
            return [j.index() for j in self._joints if int(j.model_instance()) == index]

        return dispatch(  # type: ignore[no-any-return]
            _OWNER,
            "GetJointIndices",
            (
                Overload((), of),
                Overload((Param("model_instance", instance_of(ModelInstanceIndex)),), of),
            ),
            args,
            kwargs,
        )

    def num_positions(self, model_instance: ModelInstanceIndex | None = None) -> int:
        return sum(j.num_positions() for j in self._joints_of(model_instance))

    def num_velocities(self, model_instance: ModelInstanceIndex | None = None) -> int:
        return sum(j.num_velocities() for j in self._joints_of(model_instance))

    def num_multibody_states(self, model_instance: ModelInstanceIndex | None = None) -> int:
        """nq + nv (of ``model_instance``)."""
        return self.num_positions(model_instance) + self.num_velocities(model_instance)

    def _joints_of(self, model_instance: ModelInstanceIndex | None) -> list[Joint]:
        if model_instance is None:
            return list(self._joints)
        index = self._indexed_instance(model_instance)
        return [j for j in self._joints if int(j.model_instance()) == index]
