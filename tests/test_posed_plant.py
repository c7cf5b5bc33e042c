"""A MultibodyPlant's positions, its bodies' poses, and the diagram that feeds SceneGraph.

Every test runs on reimpl and on real pydrake 1.51.1 and asserts what pydrake
does: values measured on 1.51.1 (written here), or, for poses at random
positions, the numbers the real pydrake computes in the same test (within
1e-12). Calls use pydrake's keyword names.

The model ``ALL_JOINTS`` has every joint type Drake parses from URDF, each
with an ``<origin>`` (and axes off the coordinate axes), plus, through the
API, a weld with X_FM, an RpyFloatingJoint between offset frames, a reversed
revolute joint, a ScrewJoint about a tilted axis, and a free body that
Finalize floats. Every body has a collision sphere off its origin.
"""

from __future__ import annotations

import importlib
import math
from dataclasses import dataclass
from types import ModuleType
from typing import Any

import numpy as np
import pytest

from tests.conftest import IMPLEMENTATIONS

TOLERANCE = 1e-12


@dataclass(frozen=True)
class Modules:
    framework: ModuleType
    plant: ModuleType
    tree: ModuleType
    parsing: ModuleType
    geometry: ModuleType
    math: ModuleType


def modules(implementation: str) -> Modules:
    root = "pydrake" if implementation == "pydrake" else "reimpl"
    names = ("systems.framework", "multibody.plant", "multibody.tree", "multibody.parsing")
    names += ("geometry", "math")
    return Modules(*(importlib.import_module(f"{root}.{name}") for name in names))


@pytest.fixture(params=IMPLEMENTATIONS)
def mb(request: pytest.FixtureRequest) -> Modules:
    return modules(str(request.param))


ALL_JOINTS = """<robot name="r">
 <link name="base"><collision><origin xyz="0.1 0 0"/><geometry><box size="1 1 1"/></geometry>
  </collision></link>
 <link name="a"><collision><origin xyz="0 0.2 0" rpy="0.1 0.2 0.3"/><geometry>
  <sphere radius="0.1"/></geometry></collision></link>
 <link name="b"><collision><origin xyz="0.3 0 0"/><geometry><sphere radius="0.1"/></geometry>
  </collision></link>
 <link name="c"/>
 <link name="d"><collision><geometry><cylinder radius="0.1" length="0.3"/></geometry>
  </collision></link>
 <link name="e"><collision><origin xyz="0 0 0.2"/><geometry><sphere radius="0.1"/></geometry>
  </collision></link>
 <link name="f"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
 <link name="g"><collision><origin rpy="0.5 0 0"/><geometry><capsule radius="0.1" length="0.2"/>
  </geometry></collision></link>
 <link name="h"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
 <link name="free"><collision><origin xyz="0 0 0.1"/><geometry><sphere radius="0.1"/></geometry>
  </collision></link>
 <joint name="jw" type="fixed"><parent link="world"/><child link="base"/>
  <origin xyz="0 0 1" rpy="0 0 0.5"/></joint>
 <joint name="jr" type="revolute"><parent link="base"/><child link="a"/>
  <origin xyz="1 0 0" rpy="0.3 0 0"/><axis xyz="0 1 1"/><limit lower="-1" upper="2"/></joint>
 <joint name="jp" type="prismatic"><parent link="a"/><child link="b"/>
  <origin xyz="0 1 0" rpy="0 0.4 0"/><axis xyz="1 0 1"/><limit lower="-1" upper="2"/></joint>
 <joint name="jc" type="continuous"><parent link="b"/><child link="c"/><origin xyz="0 0 1"/>
  </joint>
 <drake:joint name="jb" type="ball"><parent link="c"/><child link="d"/>
  <origin xyz="0.5 0 0" rpy="0 0 1"/></drake:joint>
 <drake:joint name="ju" type="universal"><parent link="d"/><child link="e"/>
  <origin xyz="0 0.5 0" rpy="1 0 0"/></drake:joint>
 <joint name="jpl" type="planar"><parent link="e"/><child link="f"/><origin xyz="0 0 0.5"/>
  <axis xyz="1 0 0"/></joint>
 <drake:joint name="js" type="screw"><parent link="f"/><child link="g"/>
  <origin xyz="0.2 0 0" rpy="0 0.3 0"/><axis xyz="0 0 1"/>
  <drake:screw_thread_pitch value="0.1"/></drake:joint>
 <joint name="jpl2" type="planar"><parent link="base"/><child link="h"/>
  <origin xyz="0 0 0.5" rpy="0.2 0 0"/><axis xyz="0.3 -0.2 0.9"/></joint>
</robot>"""

#: pydrake 1.51.1's GetPositionNames() for ALL_JOINTS plus the API joints (measured).
POSITION_NAMES = [
    *("r_jr_q", "r_jp_x", "r_jc_q", "r_jb_qx", "r_jb_qy", "r_jb_qz", "r_ju_qx", "r_ju_qy"),
    *("r_jpl_x", "r_jpl_y", "r_jpl_qz", "r_js_q", "r_jpl2_x", "r_jpl2_y", "r_jpl2_qz"),
    *("api_jrpy_qx", "api_jrpy_qy", "api_jrpy_qz", "api_jrpy_x", "api_jrpy_y", "api_jrpy_z"),
    *("api_jrev_q", "api_jscrew_q"),
    *("r_free_qw", "r_free_qx", "r_free_qy", "r_free_qz", "r_free_x", "r_free_y", "r_free_z"),
    *("api_K_qw", "api_K_qx", "api_K_qy", "api_K_qz", "api_K_x", "api_K_y", "api_K_z"),
]


class Posed:
    """ALL_JOINTS and the API joints in a diagram, as a MultibodyPlant user builds it."""

    def __init__(self, mb: Modules) -> None:
        self.mb = mb
        m, t = mb.math, mb.tree
        self.builder = mb.framework.DiagramBuilder()
        self.plant, self.scene_graph = mb.plant.AddMultibodyPlantSceneGraph(
            self.builder, time_step=0.0
        )
        plant = self.plant
        mb.parsing.Parser(plant).AddModelsFromString(ALL_JOINTS, "urdf")
        api = plant.AddModelInstance("api")
        inertia = t.SpatialInertia.SolidSphereWithMass(mass=1.0, radius=0.1)
        bodies = {n: plant.AddRigidBody(n, api, inertia) for n in ("P", "Q", "R", "S", "K")}
        for name, body in bodies.items():
            plant.RegisterCollisionGeometry(
                body=body,
                X_BG=m.RigidTransform(p=[0.0, 0.05, 0.0]),
                shape=mb.geometry.Sphere(radius=0.05),
                name=name.lower(),
                properties=mb.geometry.ProximityProperties(),
            )
        base = plant.GetBodyByName("base")
        X = m.RigidTransform(m.RollPitchYaw(0.1, -0.2, 0.3), [0.3, 0.2, 0.1])
        plant.AddJoint(
            t.WeldJoint(
                name="jweld",
                frame_on_parent_F=plant.GetBodyByName("b").body_frame(),
                frame_on_child_M=bodies["P"].body_frame(),
                X_FM=X,
            )
        )
        on_base = plant.AddFrame(
            t.FixedOffsetFrame(
                name="on_base",
                P=base.body_frame(),
                X_PF=m.RigidTransform(m.RollPitchYaw(0.3, 0.0, 0.0), [0.0, 1.0, 0.0]),
            )
        )
        on_q = plant.AddFrame(
            t.FixedOffsetFrame(
                name="on_q",
                P=bodies["Q"].body_frame(),
                X_PF=m.RigidTransform(m.RollPitchYaw(0.0, 0.2, 0.0), [0.0, 0.0, 1.0]),
            )
        )
        on_on_q = plant.AddFrame(
            t.FixedOffsetFrame(
                name="on_on_q",
                P=on_q,
                X_PF=m.RigidTransform(m.RollPitchYaw(0.0, 0.0, 0.7), [1.0, 0.0, 0.0]),
            )
        )
        self.jrpy = plant.AddJoint(
            t.RpyFloatingJoint(name="jrpy", frame_on_parent=on_base, frame_on_child=on_on_q)
        )
        # Reversed: R is the parent, Q (already placed through jrpy) the child.
        self.jrev = plant.AddJoint(
            t.RevoluteJoint(
                name="jrev",
                frame_on_parent=bodies["R"].body_frame(),
                frame_on_child=bodies["Q"].body_frame(),
                axis=[1.0, 0.0, 0.0],
            )
        )
        self.jscrew = plant.AddJoint(
            t.ScrewJoint(
                name="jscrew",
                frame_on_parent=bodies["R"].body_frame(),
                frame_on_child=bodies["S"].body_frame(),
                axis=[0.0, 0.6, 0.8],
                screw_pitch=0.3,
                damping=0.0,
            )
        )
        plant.Finalize()
        self.diagram = self.builder.Build()
        self.context = self.diagram.CreateDefaultContext()
        self.plant_context = plant.GetMyMutableContextFromRoot(self.context)
        self.sg_context = self.scene_graph.GetMyContextFromRoot(self.context)

    def bodies(self) -> list[Any]:
        return [
            self.plant.get_body(self.mb.tree.BodyIndex(i)) for i in range(self.plant.num_bodies())
        ]

    def X_WB(self) -> dict[str, Any]:
        return {
            body.name(): self.plant.EvalBodyPoseInWorld(self.plant_context, body).GetAsMatrix4()
            for body in self.bodies()
        }


def random_q(rng: np.random.Generator, n: int) -> Any:
    return rng.uniform(-2.0, 2.0, n)


# ------------------------------------------------------------ the layout


@pytest.mark.parametrize(
    ("bodies", "joints", "order"),
    [
        # Measured on pydrake 1.51.1: (parent, child, kind) joints j0, j1, ... on bodies B1..Bn;
        # the order of their positions (a free tree by its base body's floating joint).
        (4, [(1, 2, "r"), (0, 3, "r")], ["j1", "B1", "j0"]),
        (3, [(0, 2, "r"), (0, 1, "r")], ["j0", "j1"]),
        (5, [(0, 1, "r"), (1, 2, "r"), (0, 3, "r"), (1, 4, "r")], ["j0", "j1", "j3", "j2"]),
        (3, [(0, 1, "r"), (2, 1, "r")], ["j0", "j1"]),
        (4, [(0, 1, "w"), (0, 2, "r"), (1, 3, "r")], ["j2", "j1"]),
        (4, [(0, 2, "r"), (0, 1, "w"), (1, 3, "r")], ["j0", "j2"]),
        (5, [(1, 2, "r"), (3, 4, "r")], ["B1", "j0", "B3", "j1"]),
        (5, [(3, 4, "r"), (1, 2, "r")], ["B1", "j1", "B3", "j0"]),
        (5, [(0, 4, "r"), (4, 3, "r"), (3, 1, "r"), (0, 2, "r")], ["j0", "j1", "j2", "j3"]),
        (6, [(2, 1, "r"), (2, 3, "r"), (0, 4, "r"), (4, 5, "w")], ["j2", "B2", "j0", "j1"]),
        (
            6,
            [(0, 1, "r"), (1, 2, "w"), (2, 3, "r"), (1, 4, "r"), (2, 5, "r")],
            ["j0", "j2", "j4", "j3"],
        ),
        (5, [(1, 2, "w"), (2, 3, "r"), (0, 4, "r")], ["j2", "B1", "j1"]),
    ],
)
def test_positions_are_laid_out_depth_first_from_the_world_in_joint_order(
    mb: Modules, bodies: int, joints: list[tuple[int, int, str]], order: list[str]
) -> None:
    plant = mb.plant.MultibodyPlant(time_step=0.0)
    inertia = mb.tree.SpatialInertia.SolidSphereWithMass(mass=1.0, radius=0.1)
    body = [plant.world_body()] + [plant.AddRigidBody(f"B{i}", inertia) for i in range(1, bodies)]
    for k, (parent, child, kind) in enumerate(joints):
        P, C = body[parent].body_frame(), body[child].body_frame()
        if kind == "w":
            plant.AddJoint(mb.tree.WeldJoint(f"j{k}", P, C, mb.math.RigidTransform()))
        else:
            plant.AddJoint(mb.tree.RevoluteJoint(f"j{k}", P, C, [0.0, 0.0, 1.0]))
    plant.Finalize()
    moving = [
        plant.get_joint(mb.tree.JointIndex(i))
        for i in range(plant.num_joints())
        if plant.get_joint(mb.tree.JointIndex(i)).num_positions()
    ]
    assert [j.name() for j in sorted(moving, key=lambda j: j.position_start())] == order


def test_every_joint_type_has_drakes_position_names_and_defaults(mb: Modules) -> None:
    posed = Posed(mb)
    plant = posed.plant
    assert plant.GetPositionNames() == POSITION_NAMES
    assert plant.num_positions() == 37
    assert plant.num_velocities() == 35
    q0 = plant.GetPositions(posed.plant_context)
    assert q0.shape == (37,)
    expected = np.zeros(37)
    expected[[23, 30]] = 1.0  # the two quaternions' w (the free trees come last)
    np.testing.assert_array_equal(q0, expected)
    np.testing.assert_array_equal(plant.GetDefaultPositions(), expected)
    api = plant.GetModelInstanceByName("api")
    # The api instance's positions are not contiguous (r's free body comes between).
    with pytest.raises(SystemExit, match=r"multibody_plant\.cc:1955 in GetPositionNames\(\)"):
        plant.GetPositionNames(api)
    np.testing.assert_array_equal(plant.GetPositions(posed.plant_context, api)[-7:], q0[30:])
    assert plant.GetPositionNames(add_model_instance_prefix=False, always_add_suffix=False)[:3] == [
        "jr",
        "jp",
        "jc",
    ]
    jr = plant.GetJointByName("jr")
    assert (jr.position_start(), jr.velocity_start()) == (0, 0)
    K = plant.GetJointByName("K", api)
    assert (K.type_name(), K.position_start(), K.velocity_start()) == (
        "quaternion_floating",
        30,
        29,
    )
    np.testing.assert_allclose(jr.revolute_axis(), [0.0, math.sqrt(0.5), math.sqrt(0.5)])


# ------------------------------------------------------------ the poses


def test_body_poses_equal_pydrakes_at_random_positions() -> None:
    """20 random q (non-unit quaternions included) on both; X_WB within 1e-12 of pydrake's."""
    reimpl, pydrake = Posed(modules("reimpl")), Posed(modules("pydrake"))
    rng = np.random.default_rng(14)
    worst = 0.0
    for _ in range(20):
        q = random_q(rng, 37)
        for posed in (reimpl, pydrake):
            posed.plant.SetPositions(posed.plant_context, q)
        ours, theirs = reimpl.X_WB(), pydrake.X_WB()
        assert ours.keys() == theirs.keys()
        for name in ours:
            worst = max(worst, float(np.abs(ours[name] - theirs[name]).max()))
    assert worst < TOLERANCE


def test_the_geometry_pose_output_holds_X_WB_for_every_body_frame_but_the_worlds() -> None:
    reimpl, pydrake = Posed(modules("reimpl")), Posed(modules("pydrake"))
    q = random_q(np.random.default_rng(3), 37)
    values = {}
    for key, posed in (("reimpl", reimpl), ("pydrake", pydrake)):
        posed.plant.SetPositions(posed.plant_context, q)
        plant = posed.plant
        poses = plant.get_geometry_pose_output_port().Eval(posed.plant_context)
        by_body = {plant.GetBodyFromFrameId(i).name(): poses.value(i) for i in poses.ids()}
        assert poses.size() == plant.num_bodies() - 1
        for body in posed.bodies()[1:]:
            np.testing.assert_array_equal(
                by_body[body.name()].GetAsMatrix4(),
                plant.EvalBodyPoseInWorld(posed.plant_context, body).GetAsMatrix4(),
            )
        # What the SceneGraph reads from its connected source pose port.
        port = posed.scene_graph.get_source_pose_port(plant.get_source_id())
        read = port.Eval(posed.sg_context)
        values[key] = {
            plant.GetBodyFromFrameId(i).name(): read.value(i).GetAsMatrix4() for i in read.ids()
        }
    assert values["reimpl"].keys() == values["pydrake"].keys()
    for name, X in values["reimpl"].items():
        np.testing.assert_allclose(X, values["pydrake"][name], rtol=0, atol=TOLERANCE)


def test_frames_and_relative_transforms_equal_pydrakes() -> None:
    reimpl, pydrake = Posed(modules("reimpl")), Posed(modules("pydrake"))
    q = random_q(np.random.default_rng(5), 37)
    results: dict[str, list[Any]] = {}
    for key, posed in (("reimpl", reimpl), ("pydrake", pydrake)):
        plant, context = posed.plant, posed.plant_context
        plant.SetPositions(context, q)
        api = plant.GetModelInstanceByName("api")
        on_on_q = plant.GetFrameByName("on_on_q", api)
        jpl_child = plant.GetFrameByName("jpl_child")
        results[key] = [
            on_on_q.GetFixedPoseInBodyFrame(),
            on_on_q.CalcPoseInWorld(context),
            on_on_q.CalcPose(context, jpl_child),
            plant.CalcRelativeTransform(context, frame_A=jpl_child, frame_B=on_on_q),
            plant.GetBodyByName("g").EvalPoseInWorld(context),
            plant.GetFrameByName("jpl2_parent").GetFixedPoseInBodyFrame(),
        ]
    for ours, theirs in zip(results["reimpl"], results["pydrake"], strict=True):
        np.testing.assert_allclose(
            ours.GetAsMatrix4(), theirs.GetAsMatrix4(), rtol=0, atol=TOLERANCE
        )


@pytest.mark.parametrize(
    "axis",
    [
        *("1 0 0", "0 1 0", "0 0 1", "0 0 -1", "1 1 0", "0.3 -0.2 0.9", "-1 0 0", "0 0 2"),
        *("0 -1 0", "0 1e-3 1", "0.1 0.2 -0.97", "-0.5 0.5 -0.1"),
    ],
)
def test_a_urdf_planar_joint_turns_both_frames_z_onto_its_axis(axis: str) -> None:
    """Measured: R(z → n) about z × n; X_PF = X_origin · R and X_CM = R (pydrake within 6e-16)."""
    urdf = f"""<robot name="r"><link name="a"/><link name="b"/>
    <joint name="j" type="planar"><parent link="a"/><child link="b"/>
    <origin xyz="0 0 0.5" rpy="0.1 0.2 0.3"/><axis xyz="{axis}"/></joint></robot>"""
    frames = {}
    for implementation in IMPLEMENTATIONS:
        mb = modules(implementation)
        plant = mb.plant.MultibodyPlant(time_step=0.0)
        mb.parsing.Parser(plant).AddModelsFromString(urdf, "urdf")
        plant.Finalize()
        frames[implementation] = [
            plant.GetFrameByName(n).GetFixedPoseInBodyFrame().GetAsMatrix4()
            for n in ("j_parent", "j_child")
        ]
        n = np.array([float(v) for v in axis.split()])
        R = frames[implementation][1][:3, :3]
        np.testing.assert_allclose(R @ [0, 0, 1], n / np.linalg.norm(n), atol=1e-15)
    for ours, theirs in zip(frames["reimpl"], frames["pydrake"], strict=True):
        np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-15)


# ----------------------------------------------------- setting positions


def test_set_free_body_pose_writes_drakes_canonical_quaternion(mb: Modules) -> None:
    posed = Posed(mb)
    plant, context, m = posed.plant, posed.plant_context, mb.math
    free = plant.GetBodyByName("free")
    # Measured on pydrake 1.51.1 (w >= 0; R_x(pi) keeps the tiny w Drake computes).
    for angle, quaternion in [
        (-3.0, [0.0707372016677029, -0.9974949866040544, 0.0, 0.0]),
        (3.0, [0.0707372016677029, 0.9974949866040544, 0.0, 0.0]),
        (math.pi, [6.123233995736766e-17, 1.0, 0.0, 0.0]),
    ]:
        X = m.RigidTransform(m.RotationMatrix.MakeXRotation(angle), [1.0, 2.0, 3.0])
        plant.SetFreeBodyPose(context=context, body=free, X_JpJc=X)
        q = plant.GetPositions(context)
        np.testing.assert_allclose(q[23:27], quaternion, rtol=0, atol=1e-15)
        np.testing.assert_array_equal(q[27:30], [1.0, 2.0, 3.0])
    X = m.RigidTransform(m.RollPitchYaw(2.0, -1.0, 3.0), [0.0, 0.0, 0.0])
    plant.SetFreeBodyPose(context, free, X)
    np.testing.assert_allclose(
        plant.GetPositions(context)[23:27],
        [0.36887136, -0.31062245, -0.71828702, -0.5015091],
        atol=1e-8,
    )
    np.testing.assert_allclose(
        plant.GetFreeBodyPose(context, free).GetAsMatrix4(), X.GetAsMatrix4(), atol=1e-15
    )
    assert free.is_floating_base_body()
    assert free.has_quaternion_dofs()


def test_a_non_unit_quaternion_poses_its_body_as_the_normalized_one(mb: Modules) -> None:
    posed = Posed(mb)
    q = np.zeros(37)
    q[23:30] = [0.0, 1.5, 1.6, 1.7, 1.8, 1.9, 2.0]
    q[30] = 1.0
    posed.plant.SetPositions(posed.plant_context, q)
    X = posed.plant.EvalBodyPoseInWorld(posed.plant_context, posed.plant.GetBodyByName("free"))
    # Measured: R = R(q/|q|) with |q|^2 = 7.7.
    np.testing.assert_allclose(
        X.rotation().matrix()[0], [-0.4155844155844156, 0.6233766233766234, 0.6623376623376623]
    )
    q[23:27] = 0.0
    posed.plant.SetPositions(posed.plant_context, q)
    with pytest.raises(
        RuntimeError,
        match=r"^QuaternionToRotationMatrix\(\): All the elements in a quaternion are zero\.$",
    ):
        posed.plant.EvalBodyPoseInWorld(posed.plant_context, posed.plant.GetBodyByName("free"))


def test_an_rpy_floating_joint_takes_drakes_roll_pitch_yaw_of_a_rotation() -> None:
    reimpl, pydrake = Posed(modules("reimpl")), Posed(modules("pydrake"))
    rng = np.random.default_rng(9)
    rotations = [rng.uniform(-math.pi, math.pi, 3) for _ in range(30)]
    rotations += [np.array([0.1, math.pi / 2, 0.3]), np.array([0.4, -math.pi / 2, -2.0])]
    for rpy in rotations:
        angles = []
        for posed in (reimpl, pydrake):
            m = posed.mb.math
            R = m.RotationMatrix(m.RollPitchYaw(rpy))
            posed.jrpy.SetPose(
                context=posed.plant_context, X_FM=m.RigidTransform(R=R, p=[1.0, 2.0, 3.0])
            )
            angles.append(posed.jrpy.get_angles(posed.plant_context))
            np.testing.assert_array_equal(
                posed.jrpy.get_translation(posed.plant_context), [1.0, 2.0, 3.0]
            )
        np.testing.assert_allclose(angles[0], angles[1], rtol=0, atol=TOLERANCE)
    # Measured at the gimbal lock: R_rpy(0.1, pi/2, 0.3) reads back as (-0.1, pi/2, 0.1).
    for posed in (reimpl, pydrake):
        m = posed.mb.math
        posed.jrpy.SetOrientation(
            posed.plant_context, m.RotationMatrix(m.RollPitchYaw(0.1, math.pi / 2, 0.3))
        )
        np.testing.assert_allclose(
            posed.jrpy.get_angles(posed.plant_context), [-0.1, math.pi / 2, 0.1], atol=1e-12
        )


def test_joint_accessors_read_and_write_their_slice_of_q(mb: Modules) -> None:
    posed = Posed(mb)
    plant, c = posed.plant, posed.plant_context
    get = plant.GetJointByName
    assert get("jr").set_angle(context=c, angle=0.25) is not None
    get("jp").set_translation(context=c, translation=-0.5)
    get("jb").set_angles(context=c, angles=[0.1, 0.2, 0.3])
    get("ju").set_angles(c, np.array([0.4, 0.5]))
    get("jpl").set_pose(context=c, p_FoMo_F=[0.6, 0.7], theta=0.8)
    get("jpl2").set_translation(c, [1.0, 1.1])
    get("jpl2").set_rotation(c, 1.2)
    get("js").set_translation(context=c, translation=0.05)
    posed.jrev.set_angle(c, -0.3)
    posed.jscrew.set_translation(c, 0.6)
    q = plant.GetPositions(c)
    np.testing.assert_allclose(q[:15], [0.25, -0.5, 0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8,
                                        0.05 * 2 * math.pi / 0.1, 1.0, 1.1, 1.2])  # fmt: skip
    np.testing.assert_allclose(q[21:23], [-0.3, 4 * math.pi])
    assert get("jr").get_angle(c) == 0.25
    assert get("jp").get_translation(c) == -0.5
    np.testing.assert_array_equal(get("jpl").get_translation(c), [0.6, 0.7])
    assert get("jpl").get_rotation(c) == 0.8
    assert math.isclose(get("js").get_translation(c), 0.05)
    assert math.isclose(posed.jscrew.get_rotation(c), 4 * math.pi)
    assert posed.jscrew.screw_pitch() == 0.3
    api = plant.GetModelInstanceByName("api")
    np.testing.assert_allclose(plant.GetPositions(c, api)[6:8], [-0.3, 4 * math.pi])
    plant.SetPositions(c, api, np.arange(15.0))
    assert posed.jrev.get_angle(c) == 6.0
    assert plant.GetPositions(c)[23] == 1.0  # the free body is in instance r


def test_default_positions_feed_new_contexts(mb: Modules) -> None:
    posed = Posed(mb)
    plant, m = posed.plant, mb.math
    plant.GetJointByName("jr").set_default_angle(0.4)
    plant.GetJointByName("jpl").set_default_pose([0.1, 0.2], 0.3)
    free = plant.GetBodyByName("free")
    plant.SetDefaultFloatingBaseBodyPose(
        body=free, X_WB=m.RigidTransform(m.RollPitchYaw(0.1, 0.2, 0.3), [1, 2, 3])
    )
    q = plant.GetPositions(plant.GetMyContextFromRoot(posed.diagram.CreateDefaultContext()))
    # Measured: the quaternion of R_rpy(0.1, 0.2, 0.3).
    np.testing.assert_allclose(
        q[[0, 8, 9, 10, 23, 24, 25, 26, 27, 28, 29]],
        [0.4, 0.1, 0.2, 0.3, 0.98334744, 0.0342708, 0.10602051, 0.14357218, 1, 2, 3],
        atol=1e-8,
    )
    assert plant.GetPositions(posed.plant_context)[0] == 0.0
    api = plant.GetModelInstanceByName("api")
    plant.SetDefaultPositions(api, np.full(15, 0.5))
    assert plant.GetDefaultPositions(api)[6] == 0.5


# -------------------------------------------------------------- errors


def test_positions_of_the_wrong_size_or_not_finite_end_the_program_as_drake_does(
    mb: Modules,
) -> None:
    posed = Posed(mb)
    plant, c = posed.plant, posed.plant_context
    h = (
        "bazel-out/k8-opt/bin/external/drake+/tools/install/libdrake/_virtual_includes/"
        "drake_shared_library/drake/multibody/plant/multibody_plant.h"
    )
    cases = [
        (lambda: plant.SetPositions(c, np.zeros(3)), f"{h}:2896", "q.size() == num_positions()"),
        (lambda: plant.SetPositions(c, np.full(37, np.nan)), f"{h}:2897", "AllFinite(q)"),
        (
            lambda: plant.SetPositions(c, plant.GetModelInstanceByName("api"), [1.0]),
            f"{h}:2912",
            "q_instance.size() == num_positions(model_instance)",
        ),
        (
            lambda: plant.SetDefaultPositions([1.0]),
            "external/drake+/multibody/plant/multibody_plant.cc:1881",
            "q.size() == num_positions()",
        ),
    ]
    for call, where, condition in cases:
        with pytest.raises(SystemExit) as raised:
            call()
        method = "SetDefaultPositions" if "1881" in where else "SetPositions"
        assert str(raised.value) == (
            f"Failure at {where} in {method}(): condition '{condition}' failed."
        )
    np.testing.assert_array_equal(plant.GetPositions(c)[:15], np.zeros(15))


def test_only_a_floating_joints_body_has_a_free_body_pose(mb: Modules) -> None:
    posed = Posed(mb)
    plant, c = posed.plant, posed.plant_context
    a = plant.GetBodyByName("a")
    for call in (
        lambda: plant.SetFreeBodyPose(c, a, mb.math.RigidTransform()),
        lambda: plant.GetFreeBodyPose(c, a),
    ):
        with pytest.raises(RuntimeError, match=r"^Body 'a' is not a free body\.$"):
            call()
    # An RpyFloatingJoint places its child too (X_JpJc), though Finalize did not float it.
    Q = plant.GetBodyByName("Q", plant.GetModelInstanceByName("api"))
    X = mb.math.RigidTransform([1.0, 2.0, 3.0])
    plant.SetFreeBodyPose(c, Q, X)
    np.testing.assert_array_equal(posed.jrpy.get_translation(c), [1.0, 2.0, 3.0])
    assert not Q.is_floating_base_body()


def test_plant_calls_check_their_context(mb: Modules) -> None:
    posed = Posed(mb)
    plant, jr = posed.plant, posed.plant.GetJointByName("jr")
    help_link = (
        "\nFor more information about Context-System mismatches, see "
        "https://drake.mit.edu/troubleshooting.html#framework-context-system-mismatch"
    )
    root = (
        "A function call on a drake::multibody::MultibodyPlant<double> system named '::_::plant' "
        "was passed the root Diagram's Context instead of the appropriate subsystem Context. Use "
        "GetMyContextFromRoot() or similar to acquire the appropriate subsystem Context."
    )
    sibling = (
        "A function call on a drake::multibody::MultibodyPlant<double> system named '::_::plant' "
        "was passed the Context of a system named '::_::scene_graph' instead of the appropriate "
        "subsystem Context."
    )
    for call, message in [
        (lambda: plant.SetPositions(posed.context, np.zeros(37)), root),
        (lambda: jr.set_angle(posed.context, 0.1), root),
        (lambda: jr.get_angle(posed.sg_context), sibling),
        (lambda: plant.EvalBodyPoseInWorld(posed.sg_context, plant.world_body()), sibling),
    ]:
        with pytest.raises(RuntimeError) as raised:
            call()
        assert str(raised.value) == message + help_link


def test_a_joints_positions_exist_only_after_finalize(mb: Modules) -> None:
    plant = mb.plant.MultibodyPlant(time_step=0.0)
    body = plant.AddRigidBody("A", mb.tree.SpatialInertia.SolidSphereWithMass(1.0, 0.1))
    joint = plant.AddJoint(
        mb.tree.RevoluteJoint("j", plant.world_frame(), body.body_frame(), [0.0, 0.0, 1.0])
    )
    with pytest.raises(SystemExit, match=r"get_mobilizer_downcast\(\): condition 'has_mobilizer"):
        joint.position_start()
    with pytest.raises(
        RuntimeError,
        match=r"^Pre-finalize calls to 'GetDefaultPositions\(\)' are not allowed; you must call "
        r"Finalize\(\) first\.$",
    ):
        plant.GetDefaultPositions()
    joint.set_default_angle(0.25)
    plant.Finalize()
    np.testing.assert_array_equal(plant.GetPositions(plant.CreateDefaultContext()), [0.25])


# -------------------------------------------------------------- diagram


def test_the_plant_and_scene_graph_are_wired_both_ways(mb: Modules) -> None:
    posed = Posed(mb)
    plant, sg = posed.plant, posed.scene_graph
    assert plant.get_geometry_pose_output_port().get_name() == "geometry_pose"
    assert plant.get_geometry_query_input_port().get_name() == "geometry_query"
    assert plant.get_geometry_query_input_port().HasValue(posed.plant_context)
    assert sg.get_source_pose_port(plant.get_source_id()).HasValue(posed.sg_context)
    query = plant.get_geometry_query_input_port().Eval(posed.plant_context)
    assert type(query).__name__ == "QueryObject"
    inspector = query.inspector()
    assert inspector.num_geometries() == 14
    # A fixed value overrides the connection (measured).
    free = plant.GetBodyByName("free")
    frame_id = plant.GetBodyFrameIdOrThrow(free.index())
    poses = mb.geometry.FramePoseVector()
    poses.set_value(frame_id, mb.math.RigidTransform([9.0, 9.0, 9.0]))
    port = sg.get_source_pose_port(plant.get_source_id())
    port.FixValue(posed.sg_context, poses)
    np.testing.assert_array_equal(
        port.Eval(posed.sg_context).value(frame_id).translation(), [9, 9, 9]
    )


def test_contexts_outside_the_diagram_have_no_connected_value(mb: Modules) -> None:
    posed = Posed(mb)
    plant, sg = posed.plant, posed.scene_graph
    lone_plant, lone_sg = plant.CreateDefaultContext(), sg.CreateDefaultContext()
    port = plant.get_geometry_query_input_port()
    assert not port.HasValue(lone_plant)
    with pytest.raises(
        RuntimeError,
        match=r"^InputPort::Eval\(\): required InputPort\[0\] \(geometry_query\) of System "
        r"::_::plant \(MultibodyPlant<double>\) is not connected$",
    ):
        port.Eval(lone_plant)
    pose_port = sg.get_source_pose_port(plant.get_source_id())
    with pytest.raises(
        RuntimeError,
        match=r"^InputPort::Eval\(\): required InputPort\[0\] \(plant_pose\) of System "
        r"::_::scene_graph \(SceneGraph<double>\) is not connected$",
    ):
        pose_port.Eval(lone_sg)
    with pytest.raises(
        RuntimeError,
        match=r"^InputPort: The Context given as an argument was not created for this "
        r"InputPort\[0\] \(geometry_query\) of System ::_::plant \(MultibodyPlant<double>\)$",
    ):
        port.Eval(posed.sg_context)


def test_a_cloned_diagram_context_keeps_its_own_positions(mb: Modules) -> None:
    posed = Posed(mb)
    plant = posed.plant
    free = plant.GetBodyByName("free")
    plant.SetFreeBodyPose(posed.plant_context, free, mb.math.RigidTransform([1.0, 2.0, 3.0]))
    clone = posed.context.Clone()
    clone_plant = plant.GetMyContextFromRoot(clone)
    plant.SetFreeBodyPose(clone_plant, free, mb.math.RigidTransform([5.0, 5.0, 5.0]))
    np.testing.assert_array_equal(
        plant.EvalBodyPoseInWorld(posed.plant_context, free).translation(), [1, 2, 3]
    )
    np.testing.assert_array_equal(
        plant.EvalBodyPoseInWorld(clone_plant, free).translation(), [5, 5, 5]
    )
    poses = plant.get_geometry_query_input_port()
    assert type(poses.Eval(clone_plant)).__name__ == "QueryObject"


def test_connect_wires_an_input_once_between_systems_of_its_builder(mb: Modules) -> None:
    builder = mb.framework.DiagramBuilder()
    plant, sg = mb.plant.AddMultibodyPlantSceneGraph(builder, time_step=0.0)
    pose = plant.get_geometry_pose_output_port()
    source_port = sg.get_source_pose_port(plant.get_source_id())
    assert builder.IsConnectedOrExported(plant.get_geometry_query_input_port())
    with pytest.raises(SystemExit) as raised:
        builder.Connect(pose, source_port)
    assert str(raised.value) == (
        "Failure at external/drake+/systems/framework/diagram_builder.cc:490 in "
        "ThrowIfInputAlreadyWired(): condition 'iter != input_port_ids_.end()' failed."
    )
    other = mb.framework.DiagramBuilder()
    with pytest.raises(RuntimeError) as error:
        other.Connect(pose, source_port)
    assert str(error.value) == (
        "DiagramBuilder: System 'plant' has not been registered to this DiagramBuilder using "
        "AddSystem nor AddNamedSystem.\n\nThe systems currently registered to this builder are: "
        "NONE.\n\nIf 'plant' was registered as a subsystem to one of these, you must export the "
        "input or output port using ExportInput/ExportOutput and then connect to the exported "
        "port."
    )
    with pytest.raises(TypeError):
        builder.Connect(src=pose, dest=source_port)
    plant.Finalize()
    builder.Build()
    with pytest.raises(
        RuntimeError, match="Build\\(\\) or BuildInto\\(\\) has already been called"
    ):
        builder.Connect(pose, source_port)


# ------------------------------------------------------------- SDFormat

POSED_SDF = """<sdf version="1.9"><world name="w">
<model name="m">
 <pose>1 0 0 0 0 0.3</pose>
 <link name="A"><pose>0 0 1 0 0.2 0</pose>
  <collision name="c"><pose>0.1 0 0 0.3 0 0</pose>
   <geometry><sphere><radius>0.1</radius></sphere></geometry></collision></link>
 <link name="B"><pose relative_to="A">0 1 0 0.1 0 0</pose>
  <collision name="c"><pose relative_to="F1">0 0 0.1 0 0 0</pose>
   <geometry><box><size>1 1 1</size></box></geometry></collision></link>
 <link name="C"><pose>0 1 2 0 0 0</pose></link>
 <link name="D"><pose>1 1 2 0 0 0.5</pose></link>
 <link name="E"><pose>0 0 3 0 0 0</pose></link>
 <link name="free"><pose>2 2 2 0.1 0.2 0.3</pose>
  <collision name="c"><geometry><sphere><radius>0.1</radius></sphere></geometry></collision></link>
 <joint name="j0" type="fixed"><parent>world</parent><child>A</child></joint>
 <joint name="j1" type="revolute"><pose>0 0 0.5 0 0 0</pose><parent>A</parent><child>B</child>
  <axis><xyz>0 0 1</xyz></axis></joint>
 <joint name="j2" type="prismatic"><pose relative_to="A">0 0.3 0 0 0 0.4</pose>
  <parent>B</parent><child>E</child><axis><xyz expressed_in="__model__">1 0 0</xyz></axis></joint>
 <joint name="ju" type="universal"><pose>0 0 0.1 0 0 0</pose><parent>B</parent><child>C</child>
  <axis><xyz>0 1 0</xyz></axis><axis2><xyz>0 0 1</xyz></axis2></joint>
 <joint name="js" type="screw"><parent>C</parent><child>D</child><axis><xyz>0 1 1</xyz></axis>
  <screw_thread_pitch>0.2</screw_thread_pitch></joint>
 <frame name="F1" attached_to="B"><pose>0 0 0.2 0 0 0</pose></frame>
 <frame name="F2"><pose relative_to="F1">0.5 0 0 0 0 0</pose></frame>
 <model name="inner"><pose>0 0 5 0.1 0 0</pose>
  <link name="N"><pose>1 0 0 0 0 0</pose>
   <collision name="c"><pose degrees="true">0 0 0 90 0 0</pose>
    <geometry><sphere><radius>0.1</radius></sphere></geometry></collision></link>
  <frame name="NF" attached_to="N">
   <pose rotation_format="quat_xyzw">0 0 1 0 0 0.7071067811865476 0.7071067811865476</pose></frame>
 </model>
 <joint name="jn" type="ball"><parent>D</parent><child>inner::N</child></joint>
</model>
<model name="s"><static>true</static><pose>0 0 -1 0 0 0.1</pose>
 <link name="S"><pose>0.5 0 0 0 0 0</pose>
  <collision name="c"><geometry><box><size>1 1 1</size></box></geometry></collision></link></model>
</world></sdf>"""


def _sdf_snapshot(implementation: str, seed: int) -> dict[str, Any]:
    """Everything SDFormat poses reach, by name: frames, geometries, axes, X_WB at q."""
    mb = modules(implementation)
    builder = mb.framework.DiagramBuilder()
    plant, scene_graph = mb.plant.AddMultibodyPlantSceneGraph(builder, time_step=0.0)
    mb.parsing.Parser(plant).AddModelsFromString(POSED_SDF, "sdf")
    plant.Finalize()
    context = plant.CreateDefaultContext()
    values: dict[str, Any] = {"default q": plant.GetPositions(context)}
    for i in range(plant.num_frames()):
        frame = plant.get_frame(mb.tree.FrameIndex(i))
        # N.B. pydrake 1.51.1 adds frames of its own at Finalize (j2_j2_parent_F, ...).
        if not frame.name().endswith(("_F", "_M")):
            key = f"frame {frame.scoped_name()} on {frame.body().name()}"
            values[key] = frame.GetFixedPoseInBodyFrame().GetAsMatrix4()
    inspector = scene_graph.model_inspector()
    for geometry_id in inspector.GetAllGeometryIds():
        values[f"geometry {inspector.GetName(geometry_id)}"] = inspector.GetPoseInFrame(
            geometry_id
        ).GetAsMatrix4()
    for i in range(plant.num_joints()):
        joint = plant.get_joint(mb.tree.JointIndex(i))
        for axis in ("revolute_axis", "translation_axis"):
            if hasattr(joint, axis):
                values[f"{joint.name()} {axis}"] = getattr(joint, axis)()
        if joint.type_name() == "weld":
            values[f"{joint.name()} X_FM"] = joint.X_FM().GetAsMatrix4()
    plant.SetPositions(context, random_q(np.random.default_rng(seed), plant.num_positions()))
    for i in range(plant.num_bodies()):
        body = plant.get_body(mb.tree.BodyIndex(i))
        values[f"X_WB {body.name()}"] = plant.EvalBodyPoseInWorld(context, body).GetAsMatrix4()
    return values


@pytest.mark.filterwarnings("ignore:Actuation")
def test_sdformat_poses_reach_frames_geometries_joints_and_free_bodies() -> None:
    """Link, joint, frame, geometry and model poses, relative_to, expressed_in, degrees,
    quat_xyzw, nested and static models: every value equals pydrake's within 1e-12."""
    for seed in (1, 2, 3):
        ours, theirs = _sdf_snapshot("reimpl", seed), _sdf_snapshot("pydrake", seed)
        assert ours.keys() == theirs.keys()
        for key, value in theirs.items():
            np.testing.assert_allclose(ours[key], value, rtol=0, atol=TOLERANCE, err_msg=key)
    # Measured: the free link floats at its SDFormat pose, X_WM * X_ML (after the 8
    # positions of j1, j2, ju, js and jn).
    np.testing.assert_allclose(
        theirs["default q"][8:],
        [0.95085035, 0.01804247, 0.10995138, 0.28890962, 2.31963256, 2.50171339, 2.0],
        atol=1e-8,
    )


@pytest.mark.parametrize(
    ("body", "message"),
    [
        (
            '<link name="L"><pose relative_to="nope">0 0 1 0 0 0</pose></link>',
            "error: relative_to name[nope] specified by link with name[L] does not match a "
            "nested model, link, joint, or frame name in model with name[m].",
        ),
        (
            '<link name="L"/><link name="M"/><joint name="j" type="revolute"><parent>L</parent>'
            '<child>M</child><axis><xyz expressed_in="nope">1 0 0</xyz></axis></joint>',
            "error: axis xyz expressed-in frame with name[nope] specified by joint with name[j] "
            "not found in model with name[m].",
        ),
        (
            '<link name="L"/><link name="M"/><joint name="j" type="universal"><parent>L</parent>'
            "<child>M</child><axis><xyz>1 0 0</xyz></axis><axis2><xyz>1 1 0</xyz></axis2></joint>",
            "<literal-string>.sdf:1: error: axis and axis2 must be orthogonal for joint 'j'",
        ),
    ],
)
@pytest.mark.filterwarnings("ignore:Actuation")
def test_sdformat_pose_errors_are_drakes(mb: Modules, body: str, message: str) -> None:
    plant = mb.plant.MultibodyPlant(time_step=0.0)
    text = f'<sdf version="1.9"><model name="m">{body}</model></sdf>'
    with pytest.raises(RuntimeError) as raised:
        mb.parsing.Parser(plant).AddModelsFromString(text, "sdf")
    assert str(raised.value) == message


# -------------------------------------------------------------- queries


def _query_snapshot(posed: Posed, q: Any) -> dict[str, Any]:
    """X_WG of every geometry and the colliding pairs, by name, at q (through the diagram)."""
    posed.plant.SetPositions(posed.plant_context, q)
    query = posed.scene_graph.get_query_output_port().Eval(posed.sg_context)
    inspector = query.inspector()

    def name(g: Any) -> str:
        """``frame/geometry``: URDF geometries without a name share their shape's name."""
        return f"{inspector.GetName(inspector.GetFrameId(g))}/{inspector.GetName(g)}"

    values: dict[str, Any] = {
        f"X_WG {name(g)}": query.GetPoseInWorld(geometry_id=g).GetAsMatrix4()
        for g in inspector.GetAllGeometryIds()
    }
    values["collisions"] = query.HasCollisions()
    pairs = query.ComputePointPairPenetration()
    values["pairs"] = sorted(tuple(sorted((name(p.id_A), name(p.id_B)))) for p in pairs)
    for pair in pairs:
        values[f"depth {sorted((name(pair.id_A), name(pair.id_B)))}"] = pair.depth
    # The plant's own input port sees the same poses.
    plant_query = posed.plant.get_geometry_query_input_port().Eval(posed.plant_context)
    for g in inspector.GetAllGeometryIds():
        np.testing.assert_array_equal(
            plant_query.GetPoseInWorld(geometry_id=g).GetAsMatrix4(), values[f"X_WG {name(g)}"]
        )
    return values


def test_queries_through_the_diagram_see_the_plants_poses() -> None:
    """At 10 random q, X_WG of the 14 geometries equals pydrake's within 1e-12 and the
    colliding pairs are pydrake's (depths within 1e-9)."""
    reimpl, pydrake = Posed(modules("reimpl")), Posed(modules("pydrake"))
    rng = np.random.default_rng(21)
    colliding = 0
    for _ in range(10):
        q = random_q(rng, 37)
        ours, theirs = _query_snapshot(reimpl, q), _query_snapshot(pydrake, q)
        assert ours.keys() == theirs.keys()
        assert ours["pairs"] == theirs["pairs"]
        assert ours["collisions"] == theirs["collisions"]
        colliding += len(theirs["pairs"])
        for key, value in theirs.items():
            if key.startswith("X_WG"):
                np.testing.assert_allclose(ours[key], value, rtol=0, atol=TOLERANCE, err_msg=key)
            elif key.startswith("depth"):
                assert abs(ours[key] - value) < 1e-9, key
    assert colliding == 9  # measured: 9 colliding pairs over the 10 configurations


@pytest.mark.parametrize("implementation", ["reimpl", "pydrake"])
def test_a_diagram_context_clones_after_a_query(implementation: str) -> None:
    posed = Posed(modules(implementation))
    posed.scene_graph.get_query_output_port().Eval(posed.sg_context)
    clone = posed.context.Clone()
    query = posed.plant.get_geometry_query_input_port().Eval(
        posed.plant.GetMyContextFromRoot(clone)
    )
    assert query.HasCollisions() is True


def test_set_default_context_restores_the_default_positions(mb: Modules) -> None:
    posed = Posed(mb)
    plant, c = posed.plant, posed.plant_context
    plant.GetJointByName("jr").set_default_angle(0.5)
    plant.SetPositions(c, np.full(37, 0.25))
    posed.diagram.SetDefaultContext(posed.context)
    assert plant.GetPositions(c)[0] == 0.5
    plant.SetPositions(c, np.full(37, 0.25))
    plant.SetDefaultContext(c)
    np.testing.assert_array_equal(plant.GetPositions(c), plant.GetDefaultPositions())
