"""RotationMatrix and RigidTransform times vectors: pydrake's overloads and bits.

reimpl had only the rotation-times-rotation and transform-times-transform overloads;
``R.multiply(v_B)`` raised AttributeError where pydrake returns R·v (found porting
penetration_as_point_pair_callback_test.cc). Expected values measured on pydrake 1.51.1
and 1.58.0 (identical); the rotation is RollPitchYaw(0.75, 2.38, 1.65) and v_B
(-5.496, -3.997, 7.471), a case where numpy's ``R @ v`` differs from Drake in the last
bit of the z component (reimpl/math/_products.py says why).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

RPY = [0.75, 2.38, 1.65]
V_B = np.array([-5.496, -3.997, 7.471])
R_V = [7.527526004217423, 6.485722903020556, 1.808208140968593]
P_AB = [0.5, -1.25, 2.0]
X_V = [8.027526004217423, 5.235722903020556, 3.808208140968593]


def _rotation(api: Any) -> Any:
    return api.math.RotationMatrix(api.math.RollPitchYaw(RPY))


def test_a_rotation_times_a_vector_is_drakes_product_to_the_bit(api: Any) -> None:
    R = _rotation(api)
    for product in (R.multiply(v_B=V_B), R @ V_B, R.multiply(list(V_B))):
        assert product.shape == (3,)
        assert product.tolist() == R_V
    assert (R.matrix() @ V_B).tolist() != R_V  # numpy's order is not Drake's


def test_a_rotation_times_a_block_keeps_its_columns(api: Any) -> None:
    R = _rotation(api)
    block = np.stack([V_B, -V_B, np.zeros(3)], axis=1)
    product = R @ block
    assert product.shape == (3, 3)
    assert product[:, 0].tolist() == R_V
    assert product[:, 1].tolist() == [-x for x in R_V]
    assert R.multiply(V_B.reshape(3, 1)).shape == (3, 1)
    assert R.multiply(np.zeros((3, 0))).shape == (3, 0)


def test_a_transform_moves_a_point_and_turns_a_direction(api: Any) -> None:
    X = api.math.RigidTransform(_rotation(api), P_AB)
    assert X.multiply(p_BoQ_B=V_B).tolist() == X_V
    assert (X @ np.stack([V_B, V_B], axis=1))[:, 1].tolist() == X_V
    assert X.multiply(vec_B=np.append(V_B, 1.0)).tolist() == [*X_V, 1.0]
    assert X.multiply(np.append(V_B, 0.0)).tolist() == [*R_V, 0.0]
    assert X.multiply(np.append(V_B, 1.0).reshape(4, 1)).shape == (4, 1)


@pytest.mark.parametrize(
    ("fourth", "listed"), [(2.5, "[1, 2, 3, 2.5]"), (float("nan"), "[1, 2, 3, nan]")]
)
def test_a_four_vector_must_end_in_zero_or_one(api: Any, fourth: float, listed: str) -> None:
    X = api.math.RigidTransform(p=P_AB)
    with pytest.raises(RuntimeError) as error:
        X.multiply(np.array([1.0, 2.0, 3.0, fourth]))
    assert str(error.value) == (
        f"The 4th element in vector {listed} passed to RigidTransform::operator* is not 0 or 1."
    )


@pytest.mark.parametrize("value", ["x", np.ones(5), np.ones((4, 2))])
def test_other_arguments_are_a_type_error(api: Any, value: Any) -> None:
    with pytest.raises(TypeError, match=r"^multiply\(\): incompatible function arguments"):
        _rotation(api).multiply(value)
    with pytest.raises(TypeError, match=r"^multiply\(\): incompatible function arguments"):
        api.math.RigidTransform().multiply(value)
