# Ported from Drake: geometry/proximity/test/penetration_as_point_pair_callback_test.cc at
# v1.51.1 (https://github.com/RobotLocomotion/drake), the double-scalar cases, re-expressed
# as pytest functions that run unchanged on pydrake and on reimpl through
# QueryObject.ComputePointPairPenetration on a posed SceneGraph context (the internal FCL
# callback is not bound).
#
# Drake's license (BSD 3-Clause), which covers the upstream test this file is ported from:
#
#   Copyright 2012-2022, Robot Locomotion Group @ CSAIL, Massachusetts Institute of Technology
#   All rights reserved.
#
#   Redistribution and use in source and binary forms, with or without modification, are
#   permitted provided that the following conditions are met:
#
#   1. Redistributions of source code must retain the above copyright notice, this list of
#      conditions and the following disclaimer.
#   2. Redistributions in binary form must reproduce the above copyright notice, this list of
#      conditions and the following disclaimer in the documentation and/or other materials
#      provided with the distribution.
#   3. Neither the name of the copyright holder nor the names of its contributors may be used
#      to endorse or promote products derived from this software without specific prior
#      written permission.
#
#   THIS SOFTWARE IS PROVIDED BY THE COPYRIGHT HOLDERS AND CONTRIBUTORS "AS IS" AND ANY
#   EXPRESS OR IMPLIED WARRANTIES, INCLUDING, BUT NOT LIMITED TO, THE IMPLIED WARRANTIES OF
#   MERCHANTABILITY AND FITNESS FOR A PARTICULAR PURPOSE ARE DISCLAIMED. IN NO EVENT SHALL THE
#   COPYRIGHT HOLDER OR CONTRIBUTORS BE LIABLE FOR ANY DIRECT, INDIRECT, INCIDENTAL, SPECIAL,
#   EXEMPLARY, OR CONSEQUENTIAL DAMAGES (INCLUDING, BUT NOT LIMITED TO, PROCUREMENT OF
#   SUBSTITUTE GOODS OR SERVICES; LOSS OF USE, DATA, OR PROFITS; OR BUSINESS INTERRUPTION)
#   HOWEVER CAUSED AND ON ANY THEORY OF LIABILITY, WHETHER IN CONTRACT, STRICT LIABILITY, OR
#   TORT (INCLUDING NEGLIGENCE OR OTHERWISE) ARISING IN ANY WAY OUT OF THE USE OF THIS
#   SOFTWARE, EVEN IF ADVISED OF THE POSSIBILITY OF SUCH DAMAGE.
"""Upstream PenetrationAsPointPairCallbackTest, through ComputePointPairPenetration.

Upstream hands the callback a sphere of radius 0.5 at the origin and a second shape, in
both orders, and checks: no result when apart; one result whose depth is the target
within machine epsilon, consistent with its witness points and normal, bit identical in
both orders; none once the pair is filtered; and the error for two half spaces. Here the
shapes are posed in a SceneGraph and the order is varied by anchoring either one
(``posed_scene.Layout``); the results of the three layouts must be bit identical.

Left out: the AutoDiffXd cases (TestGradient, the *AutoDiffXd variants,
UnsupportedAutoDiffXd) and UnsupportedExpression: reimpl implements the double scalar only.
"""

from __future__ import annotations

import math
import sys
from types import ModuleType
from typing import Any

import numpy as np
import pytest

from tests.upstream.posed_scene import Layout, PosedScene

K_EPS = sys.float_info.epsilon
K_RADIUS = 0.5
BOX_SIZE = (0.1, 0.2, 0.3)
CYLINDER_SIZE = (1.2, 2.1)  # radius, length
CAPSULE_SIZE = (1.3, 2.3)  # radius, length
TARGET_DEPTH = 0.1

LAYOUTS = list(Layout)


def _result(record: Any) -> tuple[Any, ...]:
    """A PenetrationAsPointPair's fields, comparable bit for bit."""
    return (
        record.id_A,
        record.id_B,
        record.depth,
        tuple(record.p_WCa),
        tuple(record.p_WCb),
        tuple(record.nhat_BA_W),
    )


def _sphere_pose_B(drake: ModuleType) -> Any:
    """TestCollisionFilterRespected's X_WB: B penetrates A to 0.1, turned arbitrarily."""
    RotationMatrix = drake.math.RotationMatrix_[float]
    center_distance = K_RADIUS * 2 - TARGET_DEPTH
    direction = np.array([1.0, -2.0, 3.0])
    p_WBo = direction / np.linalg.norm(direction) * center_distance
    R_WB = RotationMatrix.MakeYRotation(math.pi / 3) @ RotationMatrix.MakeZRotation(-math.pi / 7)
    return drake.math.RigidTransform_[float](R=R_WB, p=p_WBo)


def _two_spheres(drake: ModuleType, layout: Layout, X_WB: Any) -> PosedScene:
    g = drake.geometry
    scene = PosedScene(drake, layout)
    scene.add("A", g.Sphere(K_RADIUS), drake.math.RigidTransform_[float]())
    scene.add("B", g.Sphere(K_RADIUS), X_WB)
    return scene


@pytest.mark.parametrize("layout", LAYOUTS, ids=lambda x: x.value)
def test_spheres_apart_give_no_penetration(drake: ModuleType, layout: Layout) -> None:
    """NonCollisionDouble: B moved 3 radii along x."""
    X_WB = drake.math.RigidTransform_[float](p=[K_RADIUS * 3, 0.0, 0.0])
    scene = _two_spheres(drake, layout, X_WB)
    assert list(scene.query_object().ComputePointPairPenetration()) == []


def test_a_penetration_is_the_same_in_every_order_and_gone_once_filtered(
    drake: ModuleType,
) -> None:
    """CollisionFilterRespectedDouble."""
    results = []
    for layout in LAYOUTS:
        scene = _two_spheres(drake, layout, _sphere_pose_B(drake))
        (record,) = scene.query_object().ComputePointPairPenetration()
        p_WCa, p_WCb, nhat = record.p_WCa, record.p_WCb, record.nhat_BA_W
        assert abs(np.linalg.norm(p_WCa - p_WCb) - record.depth) <= K_EPS
        np.testing.assert_allclose(p_WCb - p_WCa, record.depth * nhat, rtol=0, atol=K_EPS)
        assert (record.id_A, record.id_B) == (scene.ids["A"], scene.ids["B"])
        assert abs(record.depth - TARGET_DEPTH) <= K_EPS
        # Ids differ between scenes; the values must not, to the bit.
        results.append(_result(record)[2:])

        scene.exclude_within("A", "B")
        assert list(scene.query_object().ComputePointPairPenetration()) == []
    assert results[1:] == results[:1] * (len(results) - 1)


def _along_x_turned(drake: ModuleType, center_distance: float) -> Any:
    """CalcBoxPoseInSphereBox and its cylinder and capsule twins: turned 0.2 about z, its
    origin ``center_distance`` along the turned x axis."""
    R_WB = drake.math.RotationMatrix_[float].MakeZRotation(0.2)
    p_WBo = R_WB.multiply(np.array([center_distance, 0.0, 0.0]))
    return drake.math.RigidTransform_[float](R=R_WB, p=p_WBo)


def _half_space_pose(drake: ModuleType) -> tuple[Any, float]:
    """CalcHalfspacePoseInSphereHalfspace: the pose and the depth it gives (normal +z,
    offset 0, in the half space's frame)."""
    RotationMatrix = drake.math.RotationMatrix_[float]
    R_WB = RotationMatrix.MakeZRotation(0.1) @ RotationMatrix.MakeXRotation(0.5)
    p_WBo = np.array([0.5, -0.2, 0.9])
    target_depth = 0.0 + float(R_WB.inverse().multiply(p_WBo)[2]) + K_RADIUS
    return drake.math.RigidTransform_[float](R=R_WB, p=p_WBo), target_depth


def _shape_case(drake: ModuleType, name: str) -> tuple[Any, Any, float]:
    """(shape, X_WB, target depth) of upstream's Sphere<Shape>Double test."""
    g = drake.geometry
    if name == "halfspace":
        X_WB, target = _half_space_pose(drake)
        return g.HalfSpace(), X_WB, target
    shape, reach = {
        "box": (g.Box(*BOX_SIZE), BOX_SIZE[0] / 2),
        "cylinder": (g.Cylinder(*CYLINDER_SIZE), CYLINDER_SIZE[0]),
        "capsule": (g.Capsule(*CAPSULE_SIZE), CAPSULE_SIZE[0]),
    }[name]
    return shape, _along_x_turned(drake, K_RADIUS + reach - TARGET_DEPTH), TARGET_DEPTH


@pytest.mark.parametrize("name", ["box", "cylinder", "halfspace", "capsule"])
def test_a_sphere_penetrates_each_shape_alike_in_every_order(drake: ModuleType, name: str) -> None:
    """SphereBoxDouble, SphereCylinderDouble, SphereHalfspaceDouble, SphereCapsuleDouble
    (TestSphereShape): the depth is the target within epsilon, also measured along the
    normal, and bit identical whichever order the pair is met in."""
    results = []
    for layout in LAYOUTS:
        shape, X_WB, target = _shape_case(drake, name)
        scene = PosedScene(drake, layout)
        scene.add("sphere", drake.geometry.Sphere(K_RADIUS), drake.math.RigidTransform_[float]())
        scene.add(name, shape, X_WB)
        (record,) = scene.query_object().ComputePointPairPenetration()
        assert abs(record.depth - target) <= K_EPS
        along_normal = float((record.p_WCb - record.p_WCa) @ record.nhat_BA_W)
        assert abs(along_normal - target) <= K_EPS
        results.append(_result(record)[2:])
    assert results[1:] == results[:1] * (len(results) - 1)


@pytest.mark.parametrize("layout", [Layout.BOTH_DYNAMIC, Layout.FIRST_ANCHORED])
def test_two_half_spaces_are_refused(drake: ModuleType, layout: Layout) -> None:
    """UnsupportedHalfSpaceHalfSpace (double): the second half space's normal is +x (its
    frame turned 90 degrees about y), upstream's fcl::Halfspaced(Vector3d{1, 0, 0}, 0)."""
    g, RigidTransform = drake.geometry, drake.math.RigidTransform_[float]
    scene = PosedScene(drake, layout)
    scene.add("half_space", g.HalfSpace(), RigidTransform())
    turned = RigidTransform(R=drake.math.RotationMatrix_[float].MakeYRotation(math.pi / 2))
    scene.add("half_space_2", g.HalfSpace(), turned)
    with pytest.raises(RuntimeError) as error:
        scene.query_object().ComputePointPairPenetration()
    assert str(error.value) == (
        "Penetration queries between shapes 'Halfspace' and 'Halfspace' are not supported "
        "for scalar type double. See the documentation for "
        "QueryObject::ComputePointPairPenetration() for the full status of supported "
        "geometries."
    )
