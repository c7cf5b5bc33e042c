"""The graph of bodies and joints, and the forest of mobilizers Finalize builds from it.

Drake counterpart: LinkJointGraph and SpanningForest (drake/multibody/topology),
as MultibodyPlant's topology queries read them. Bodies are nodes and joints
edges (see reimpl.multibody._link_joint_graph); at Finalize the forest
(reimpl.multibody.kinematics.Forest) gives each joint a mobilizer, inboard to
outboard, and lays out q and v. Measured on pydrake 1.51.1:

- ``GetBodiesWeldedTo(B)``: the connected component of B in the weld edges
  (B itself included), by index; ``IsAnchored(B)``: B is in the world's.
- ``GetFloatingBaseBodies()``: the bodies Finalize gave a floating joint.
- The unique base body of a model instance: its one body the forest joins
  directly to the world (welded or free); ``HasUniqueFloatingBaseBody`` asks
  that it be floating too.
- ``GetBodiesKinematicallyAffectedBy(J...)``: the bodies outboard of each
  joint that moves (welds skipped), sorted, each once.

All but the welded sets need Finalize.
"""

from __future__ import annotations

from collections.abc import Sequence

from reimpl.multibody import _link_joint_graph as graph
from reimpl.multibody import kinematics
from reimpl.multibody._errors import MultibodyPlantError, NotFoundError
from reimpl.multibody.plant._demands import fail_demand
from reimpl.multibody.plant._elements import Elements
from reimpl.multibody.tree import (
    BodyIndex,
    JointIndex,
    ModelInstanceIndex,
    RigidBody,
    WeldJoint,
    world_model_instance,
)

__all__ = ["Topology"]


class Topology(Elements):
    """The graph's queries, and the forest (None until Finalize)."""

    def __init__(self) -> None:
        super().__init__()
        self._forest: kinematics.Forest | None = None

    def _edges(self) -> list[graph.Edge]:
        return [
            graph.Edge(
                int(j.parent_body().index()),
                int(j.child_body().index()),
                is_weld=j.type_name() == WeldJoint.kTypeName,
            )
            for j in self._joints
        ]

    def _lay_out_positions(self) -> None:
        """Builds the forest Finalize walks: each joint's position and velocity start."""
        edges = [
            (
                int(j.parent_body().index()),
                int(j.child_body().index()),
                j.num_positions(),
                j.num_velocities(),
            )
            for j in self._joints
        ]
        self._forest = kinematics.build_forest(len(self._bodies), edges)
        for index, joint in enumerate(self._joints):
            joint._starts = (
                self._forest.position_start[index],
                self._forest.velocity_start[index],
            )

    def GetBodiesWeldedTo(self, body: RigidBody) -> list[RigidBody]:
        """The bodies of ``body``'s welded subgraph (itself included), by index."""
        index = int(body.index())
        for bodies in graph.welded_subgraphs(len(self._bodies), self._edges()):
            if index in bodies:
                return [self._bodies[b] for b in bodies]
        raise NotFoundError(f"Body '{body.name()}' does not belong to this MultibodyPlant.")

    def IsAnchored(self, body: RigidBody) -> bool:
        """Whether only welds join ``body`` to the world (its welded set is the world's)."""
        self._check_finalized("IsAnchored")
        return any(b.index() == body.index() for b in self.GetBodiesWeldedTo(self.world_body()))

    def GetFloatingBaseBodies(self) -> set[BodyIndex]:
        """The bodies Finalize gave a floating joint (a set, as pydrake returns it)."""
        self._check_finalized("GetFloatingBaseBodies")
        return {b.index() for b in self._bodies if b.is_floating_base_body()}

    def _unique_base_body(self, model_instance: ModelInstanceIndex) -> RigidBody | None:
        """The one body of ``model_instance`` the forest joins directly to the world, if one.

        A body welded to the world counts (measured: with one welded and two free
        bodies in an instance, it has no unique base body); the world instance has none.
        """
        if not 0 <= int(model_instance) < len(self._instance_names):
            fail_demand("MaybeGetUniqueBaseBodyIndex.instance")
        if int(model_instance) == int(world_model_instance()):
            return None
        assert self._forest is not None
        bases = [
            self._bodies[m.outboard]
            for m in self._forest.mobilizers
            if m.inboard == graph.WORLD
            and int(self._bodies[m.outboard].model_instance()) == int(model_instance)
        ]
        return bases[0] if len(bases) == 1 else None

    def HasUniqueFloatingBaseBody(self, model_instance: ModelInstanceIndex) -> bool:
        self._check_finalized("HasUniqueFloatingBaseBody")
        base = self._unique_base_body(model_instance)
        return base is not None and base.is_floating_base_body()

    def GetUniqueFloatingBaseBodyOrThrow(self, model_instance: ModelInstanceIndex) -> RigidBody:
        self._check_finalized("GetUniqueFloatingBaseBodyOrThrow")
        base = self._unique_base_body(model_instance)
        name = self.GetModelInstanceName(model_instance)
        if base is None:
            raise MultibodyPlantError(f"Model {name} does not have a unique base body.")
        if not base.is_floating_base_body():
            raise MultibodyPlantError(
                f"Model {name} has a unique base body, but it is not a floating base body."
            )
        return base

    def GetBodiesKinematicallyAffectedBy(
        self, joint_indexes: Sequence[JointIndex]
    ) -> list[BodyIndex]:
        """The bodies outboard of each joint that moves (welds skipped), sorted, unique."""
        self._check_finalized("GetBodiesKinematicallyAffectedBy")
        for joint_index in joint_indexes:
            if not self.has_joint(joint_index):
                raise NotFoundError(
                    f"GetBodiesKinematicallyAffectedBy: No joint with index {int(joint_index)} "
                    "has been registered or it has been removed."
                )
        assert self._forest is not None
        outboard: dict[int, list[int]] = {}
        placed_by: dict[int, int] = {}
        for mobilizer in self._forest.mobilizers:
            outboard.setdefault(mobilizer.inboard, []).append(mobilizer.outboard)
            placed_by[mobilizer.joint] = mobilizer.outboard
        affected: set[int] = set()
        for joint_index in joint_indexes:
            if self._joints[int(joint_index)].num_velocities() == 0:
                continue
            stack = [placed_by[int(joint_index)]]
            while stack:
                body = stack.pop()
                affected.add(body)
                stack.extend(outboard.get(body, ()))
        return [BodyIndex(b) for b in sorted(affected)]
