"""Finalize: what it refuses, the joints and frames it adds, then the filters.

Drake counterpart: MultibodyPlant::Finalize (multibody_plant.cc) and the
topology it builds (LinkJointGraph, SpanningForest). Measured on pydrake
1.51.1, in this order:

1. A second Finalize: ``MultibodyTreeSystem::Finalize(): repeated calls not
   allowed.`` (since 1.56 ``DeclareMiscContinuousState(): calls after Finalize()
   are not allowed.``, finalize-repeat-wording-since-1.56); a loop of bodies
   and joints (welds included): Drake's loop error.
2. Every tree not joined to the world gets a QuaternionFloatingJoint
   world → its base body (see _link_joint_graph.floating_bases), named after
   the body with leading ``_`` until unique in its instance, ephemeral, with
   the body's default free pose.
3. A joint a tree meets from its child must be one the release can reverse
   (prismatic, revolute or weld on 1.41+; see _reversed_joints).
4. q and v are laid out (see plant._topology), and each mobilizer gets the
   frames Drake adds (see _mobilizer_frames).
5. The plant is finalized, then the default collision filters are applied
   (see plant._collision_filters): an Apply that raises leaves the plant
   finalized and unfiltered.
6. Up to 1.50, a continuous plant with a PD-controlled actuator is refused
   (continuous-pd-actuators-refused-until-1.50).
"""

from __future__ import annotations

from reimpl._release import release
from reimpl.multibody import _link_joint_graph as graph
from reimpl.multibody._errors import FinalizedError, MultibodyPlantError, TopologyError
from reimpl.multibody._mobilizer_frames import mobilizer_frames
from reimpl.multibody._reversed_joints import reversed_joint_refusal
from reimpl.multibody.plant._collision_filters import CollisionFilters
from reimpl.multibody.plant._element_names import ElementNames
from reimpl.multibody.plant._poses import Poses
from reimpl.multibody.tree import FixedOffsetFrame, Joint, QuaternionFloatingJoint, RigidBody

__all__ = ["Finalization"]


#: The middle of Finalize's refusal of a loop, by release (loop-topology-wording-since-1.57).
_LOOPS_UNSUPPORTED = (
    "Automatic modeling of such systems is disabled by default; you can enable it by calling "
    "MultibodyPlant::SetEnableLoopTopology(true) before Finalize() but: the feature is in "
    "development and not yet functional even when enabled. For now, loops can be modeled "
    "with some input changes."
    if release.has("loop-topology-wording-since-1.57")
    else "Drake currently does not support automatic modeling of such systems; however, they "
    "can be modeled with some input changes."
)


#: What Drake's MultibodyTree says of a body given a second mobilizer (up to 1.40, when a
#: loop closes on it); 'the same body' and 'its base link' up to 1.24
#: (rigid-body-wording-since-1.25).
_RIGID = release.has("rigid-body-wording-since-1.25")
_TWO_INBOARD = (
    "When creating a model, an attempt was made to add two inboard joints to the same "
    f"{'rigid body' if _RIGID else 'body'}; this is not allowed. One possible cause might be "
    "attempting to weld a robot to World somewhere other than its base "
    f"{'rigid body' if _RIGID else 'link'}; see Drake issue #17429 for discussion and "
    "work-arounds, e.g., reversing some joint parent/child directions. Another possible "
    "cause might be attempting to form a kinematic loop using joints; to create a loop, "
    "consider using a LinearBushingRollPitchYaw instead of a joint."
)


class Finalization(CollisionFilters, Poses, ElementNames):
    """Finalize and the steps it takes."""

    _time_step: float  # MultibodyPlant's (0: continuous)

    def __init__(self) -> None:
        super().__init__()
        #: Joint actuators with PD gains a parser added (reimpl keeps no actuator itself).
        self._pd_controlled_actuators = 0

    def Finalize(self) -> None:
        """Adds the floating joints, then the default collision filters; seals the model."""
        if self._finalized:
            raise FinalizedError(
                "DeclareMiscContinuousState(): calls after Finalize() are not allowed."
                if release.has("finalize-repeat-wording-since-1.56")
                else "MultibodyTreeSystem::Finalize(): repeated calls not allowed."
            )
        n = len(self._bodies)
        if not release.has("reversed-joint-ordering-wording-since-1.33"):
            children = [e.child for e in self._edges() if e.child != graph.WORLD]
            if len(set(children)) < len(children):
                # Up to 1.32 a body that is the child of two joints gets two mobilizers
                # (measured on 1.12.0, 1.27.0, 1.32.0, loop or not).
                raise TopologyError(_TWO_INBOARD)
        if graph.has_loop(n, self._edges()):
            if not release.has("loop-refusal-since-1.41"):
                self._refuse_loop_before_1_41(n)
            if release.has("loop-refused-after-floating-joints-1.41-1.45"):
                for base in graph.floating_bases(n, self._edges()):
                    self._add_floating_joint(self._bodies[base])
            raise TopologyError(
                "The bodies and joints of this system form one or more loops in the system "
                f"graph. {_LOOPS_UNSUPPORTED} See "
                "https://drake.mit.edu/troubleshooting.html#mbp-loops-in-graph for advice on how "
                "to model systems with loops."
            )
        bases = graph.floating_bases(n, self._edges())
        for index in graph.reversed_joints(n, self._edges(), bases):
            self._check_reversible(self._joints[index])
        for base in bases:
            self._add_floating_joint(self._bodies[base])
        self._lay_out_positions()
        self._add_mobilizer_frames()
        # N.B. Measured: the plant is finalized before its filters are applied, so
        # an Apply that raises (transient history active) leaves it finalized,
        # unfiltered, and refusing a second Finalize.
        self._finalized = True
        self._apply_default_collision_filters()
        continuous_pd = self._pd_controlled_actuators and self._time_step == 0.0
        if continuous_pd and release.has("continuous-pd-actuators-refused-until-1.50"):
            raise MultibodyPlantError(
                "Continuous model with PD controlled joint actuators. This feature is only "
                "supported for discrete models. Refer to MultibodyPlant's documentation for "
                "further details."
            )

    def _refuse_loop_before_1_41(self, n: int) -> None:
        """Up to 1.40 Drake has no loop check; a loop fails as the forest meets it.

        1.33-1.40: the floating joints are added, then the mobilizers are made in the
        forest's order (``graph.forest_mobods``): the first reversed one that cannot be
        is refused as any reversed joint, else the first body given a second mobilizer
        is ``_TWO_INBOARD``. Up to 1.32 (a body that is the child of two joints is
        ``_TWO_INBOARD`` before this, in Finalize) the bodies of a tree whose
        every body is a child get no floating joint, the others do, and the lowest such
        body 'was not assigned a mobilizer'. Measured on 1.12.0, 1.20.0, 1.27.0,
        1.32.0, 1.33.0 and 1.40.0 with eleven loops (loop-refusal-since-1.41). A loop
        through the world as a joint's child is left to the loop refusal (pydrake 1.32.0
        raises std::bad_alloc for it).
        """
        edges = self._edges()
        if release.has("reversed-joint-ordering-wording-since-1.33"):
            bases = graph.floating_bases(n, edges)
            for base in bases:
                self._add_floating_joint(self._bodies[base])
            for mobod in graph.forest_mobods(n, edges, [graph.WORLD, *bases]):
                if mobod.reversed:
                    self._check_reversible(self._joints[mobod.edge])
                if mobod.again:
                    raise TopologyError(_TWO_INBOARD)
            raise AssertionError("a loop always gives some body a second mobilizer")
        unmobilized = graph.unrooted_bodies(n, edges)
        if not unmobilized:
            return  # a loop through the world as a child: pydrake 1.32 raises std::bad_alloc
        for base in graph.floating_bases(n, edges):
            if base not in unmobilized:
                self._add_floating_joint(self._bodies[base])
        raise TopologyError(f"Body with index {min(unmobilized)} was not assigned a mobilizer")

    def _check_reversible(self, joint: Joint) -> None:
        """Raises Drake's error unless a tree may model ``joint`` from child to parent."""
        instance = self.GetModelInstanceName(joint.model_instance())
        refusal = reversed_joint_refusal(joint, instance)  # by release: _reversed_joints
        if refusal is not None:
            raise TopologyError(refusal)

    def _add_floating_joint(self, body: RigidBody) -> None:
        """A QuaternionFloatingJoint world → body, named after the body.

        The name gets leading underscores until no joint of the body's
        instance has it (measured: ``X`` taken, ``_X`` taken → ``__X``). Up to
        1.21 it is ``$world_<body>`` (floating-joint-body-name-since-1.22: measured
        on pydrake 1.21.0 and 1.22.0).
        """
        name = body.name()
        while self._named(self._joints, name, body.model_instance()):
            name = f"_{name}"
        if not release.has("floating-joint-body-name-since-1.22"):
            name = f"$world_{body.name()}"
        joint = QuaternionFloatingJoint(name, self.world_frame(), body.body_frame())
        joint._ephemeral = True
        X_WB = self._default_free_body_poses.get(int(body.index()))
        if X_WB is not None:
            joint._set_default_pose(X_WB)
        self.AddJoint(joint)

    def _add_mobilizer_frames(self) -> None:
        """The ephemeral frames of ``_mobilizer_frames``, in the order the tree is walked."""
        assert self._forest is not None
        for mobilizer in self._forest.mobilizers:
            joint = self._joints[mobilizer.joint]
            for suffix, base, X in mobilizer_frames(joint, mobilizer.reversed):
                instance = joint.model_instance()
                name = f"{joint.name()}_{base.name()}_{suffix}"
                while self._named(self._frames, name, instance):
                    name = f"_{name}"
                frame = FixedOffsetFrame(name, base, X, instance)
                frame._ephemeral = True
                self.AddFrame(frame)
