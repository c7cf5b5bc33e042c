"""Finalize adds ephemeral frames where a joint's mobilizer needs them (measured on pydrake
1.51.1 and 1.58.0, which agree): a revolute or prismatic joint whose axis, negated if the
joint is reversed, is not exactly +x, +y or +z gets ``<joint>_<frame>_F`` and ``_M``; a weld
whose X_FM is not the identity gets ``<joint>_<frame>_F``."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from conformance._backends.api import Api
from reimpl.multibody._mobilizer_frames import from_one_unit_vector

#: (name, body, is_ephemeral, X_BF as 3x4 rounded to 3 decimals), in the order Finalize adds
#: them, measured on pydrake 1.51.1 (1.58.0 gives the same).
EXPECTED = [
    ("r_world_F", "world", [[0, 1, 0, 0], [-0.8, 0, 0.6, 0], [0.6, 0, 0.8, 0]]),
    ("r_a_M", "a", [[0, 1, 0, 0], [-0.8, 0, 0.6, 0], [0.6, 0, 0.8, 0]]),
    ("s_a_F", "a", [[0, 1, 0, 0], [1, 0, 0, 0], [0, 0, -1, 0]]),
    ("s_b_M", "b", [[0, 1, 0, 0], [1, 0, 0, 0], [0, 0, -1, 0]]),
    ("w_b_F", "b", [[1, 0, 0, 1], [0, 1, 0, 0], [0, 0, 1, 0]]),
    ("rev_c_F", "c", [[0, 1, 0, 0], [1, 0, 0, 0], [0, 0, -1, 0]]),
    ("_rev_d_M", "d", [[0, 1, 0, 0], [1, 0, 0, 0], [0, 0, -1, 0]]),
]


def _plant(api: Api) -> tuple[Any, int]:
    assert api.plant is not None
    assert api.tree is not None
    tree, math = api.tree, api.math
    plant = api.plant.MultibodyPlant(time_step=0.0)
    inertia = tree.SpatialInertia(
        mass=1.0, p_PScm_E=[0.0, 0.0, 0.0], G_SP_E=tree.UnitInertia(Ixx=1.0, Iyy=1.0, Izz=1.0)
    )
    a, b, c, d = (plant.AddRigidBody(name=n, M_BBo_B=inertia) for n in "abcd")
    frame = {body.name(): body.body_frame() for body in (a, b, c, d)}
    revolute, prismatic = tree.RevoluteJoint, tree.PrismaticJoint
    plant.AddJoint(
        revolute(
            name="r",
            frame_on_parent=plant.world_frame(),
            frame_on_child=frame["a"],
            axis=[0.0, 0.6, 0.8],
            damping=0.0,
        )
    )
    plant.AddJoint(
        prismatic(
            name="s", frame_on_parent=frame["a"], frame_on_child=frame["b"], axis=[0.0, 0.0, -1.0]
        )
    )
    plant.AddJoint(
        tree.WeldJoint(
            name="w",
            frame_on_parent_F=frame["b"],
            frame_on_child_M=frame["c"],
            X_FM=math.RigidTransform(p=[1.0, 0.0, 0.0]),
        )
    )
    # d → c with c reached from the world first: the tree models it reversed, about -z.
    plant.AddJoint(
        revolute(
            name="rev",
            frame_on_parent=frame["d"],
            frame_on_child=frame["c"],
            axis=[0.0, 0.0, 1.0],
            damping=0.0,
        )
    )
    # A user frame with the name Finalize would give: its frame gets a leading '_'.
    plant.AddFrame(
        frame=tree.FixedOffsetFrame(name="rev_d_M", P=frame["a"], X_PF=math.RigidTransform())
    )
    return plant, plant.num_frames()


def test_finalize_adds_the_mobilizer_frames_drake_adds(api: Api) -> None:
    assert api.tree is not None
    plant, before = _plant(api)
    plant.Finalize()
    added = [
        plant.get_frame(frame_index=api.tree.FrameIndex(i))
        for i in range(before, plant.num_frames())
    ]
    seen = [
        (
            f.name(),
            f.body().name(),
            np.round(f.GetFixedPoseInBodyFrame().GetAsMatrix34(), 3).tolist(),
        )
        for f in added
    ]
    assert seen == EXPECTED
    assert all(f.is_ephemeral() for f in added)
    assert not plant.GetFrameByName(name="rev_d_M").is_ephemeral()


@pytest.mark.parametrize(
    ("u", "axis_index"),
    [([0.0, 0.6, 0.8], 2), ([0.0, 0.0, -1.0], 2), ([0.6, -0.8, 0.0], 0), ([1 / 3**0.5] * 3, 1)],
)
def test_from_one_unit_vector_puts_u_on_its_axis_in_a_right_handed_basis(
    u: list[float], axis_index: int
) -> None:
    R = from_one_unit_vector(np.array(u), axis_index).matrix()
    np.testing.assert_allclose(R[:, axis_index], u)
    np.testing.assert_allclose(R @ R.T, np.eye(3), atol=1e-15)
    assert np.linalg.det(R) == pytest.approx(1.0)
