# Ported from Drake: bindings/pydrake/geometry/test/common_test.py
# (https://github.com/RobotLocomotion/drake), the parts about shapes (test_shape_constructors,
# test_shapes) for the shapes reimpl has, re-expressed as pytest functions that run unchanged
# on pydrake and on reimpl.
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
"""Upstream shape binding tests, on pydrake and on reimpl.

Left out, as in reimpl (see reimpl/geometry/mesh.py): in-memory meshes (InMemoryMesh,
MemoryFile, ``mesh_data=``) and GetConvexHull, which need a mesh file's contents. Upstream's
``filename()`` is ``source().description()`` here: pydrake 1.51.1 has no ``Mesh.filename``.
Beyond upstream, the expected values (reprs, volumes, MakePose matrices, error messages)
were measured on pydrake 1.51.1; where 1.58.0 differs the test says so.
"""

from __future__ import annotations

import copy
import math
import os
import pathlib
import pickle
import re
from collections.abc import Callable
from types import ModuleType
from typing import Any

import numpy as np
import pytest

from tests.upstream.parsing_support import fact_holds_for, follows_1_51


def _follows_1_51(drake: ModuleType) -> bool:
    """Whether the implementation is Drake 1.51: reimpl's release (REIMPL_DRAKE_RELEASE,
    which tests/conftest.py sets to the installed pydrake's), or the installed pydrake."""
    return follows_1_51(drake)


def assert_shape_api(drake: ModuleType, shape: Any) -> None:
    """Upstream's invariant of every Shape: Clone() is a new object of the same class."""
    assert isinstance(shape, drake.geometry.Shape)
    clone = shape.Clone()
    assert type(clone) is type(shape)
    assert clone is not shape


def assert_pickle(shape: Any, attributes: Callable[[Any], Any]) -> None:
    """pydrake's assert_pickle: the unpickled object has the same class and attributes."""
    restored = pickle.loads(pickle.dumps(shape))
    assert type(restored) is type(shape)
    assert attributes(restored) == attributes(shape)


def failure_tail(error: BaseException) -> str:
    """A DRAKE_THROW_UNLESS message from " in Function():" on; the line moves between releases."""
    match = re.fullmatch(
        r"Failure at external/drake\+/geometry/shape_specification\.cc:\d+ (in .*)", str(error)
    )
    assert match, str(error)
    return match.group(1)


# ---------------------------------------------------------------- test_shape_constructors


def test_every_shape_clones_deep_copies_and_round_trips_through_repr(
    drake: ModuleType, monkeypatch: pytest.MonkeyPatch, tmp_path: pathlib.Path
) -> None:
    monkeypatch.chdir(tmp_path)
    g = drake.geometry
    shapes = [
        g.Sphere(radius=1.0),
        g.Cylinder(radius=1.0, length=2.0),
        g.Box(width=1.0, depth=2.0, height=3.0),
        g.Capsule(radius=1.0, length=2.0),
        g.Ellipsoid(a=1.0, b=2.0, c=3.0),
        g.HalfSpace(),
        g.Mesh(filename="arbitrary/path", scale=1.0),
        g.Convex(filename="arbitrary/path", scale=1.0),
        g.MeshcatCone(height=1.23, a=3.45, b=6.78),
    ]
    for shape in shapes:
        assert isinstance(shape, g.Shape)
        shape_cls = type(shape)

        shape_clone = shape.Clone()
        assert isinstance(shape_clone, shape_cls)
        assert shape_clone is not shape

        shape_copy = copy.deepcopy(shape)
        assert isinstance(shape_copy, shape_cls)
        assert shape_copy is not shape

        new_shape = eval(repr(shape), {shape_cls.__name__: shape_cls})
        assert isinstance(new_shape, shape_cls)
        assert repr(new_shape) == repr(shape)


@pytest.mark.parametrize(
    ("expression", "text"),
    [
        ("Sphere(radius=1.0)", "Sphere(radius=1)"),
        ("Sphere(0.0)", "Sphere(radius=0)"),
        ("Sphere(-0.0)", "Sphere(radius=-0)"),
        ("Sphere(1e15)", "Sphere(radius=1000000000000000)"),
        ("Sphere(1e16)", "Sphere(radius=1e+16)"),
        ("Sphere(1e-5)", "Sphere(radius=1e-05)"),
        ("Box(0.1, 0.2, 0.1 + 0.2)", "Box(width=0.1, depth=0.2, height=0.30000000000000004)"),
        ("Cylinder(radius=1, length=2)", "Cylinder(radius=1, length=2)"),
        ("Capsule(measures=[0.5, 2])", "Capsule(radius=0.5, length=2)"),
        ("Ellipsoid(1, 2, 3)", "Ellipsoid(a=1, b=2, c=3)"),
        ("MeshcatCone(1.23, 3.45, 6.78)", "MeshcatCone(height=1.23, a=3.45, b=6.78)"),
        ("MeshcatCone(2)", "MeshcatCone(height=2, a=1, b=1)"),
        ("MeshcatCone(height=2, b=3)", "MeshcatCone(height=2, a=1, b=3)"),
        ("HalfSpace()", "HalfSpace()"),
    ],
)
def test_shapes_print_each_measure_in_shortest_form(
    drake: ModuleType, expression: str, text: str
) -> None:
    g = drake.geometry
    assert repr(eval(expression, dict(vars(g)))) == text
    assert str(eval(expression, dict(vars(g)))) == text


# --------------------------------------------------------------------------- test_shapes

PRIMITIVES: list[tuple[str, dict[str, float]]] = [
    ("Box", {"width": 1.0, "depth": 2.0, "height": 3.0}),
    ("Capsule", {"radius": 1.0, "length": 2.0}),
    ("Cylinder", {"radius": 1.0, "length": 2.0}),
    ("Ellipsoid", {"a": 1.0, "b": 2.0, "c": 3.0}),
    ("MeshcatCone", {"height": 1.2, "a": 3.4, "b": 5.6}),
    ("Sphere", {"radius": 1.0}),
]


@pytest.mark.parametrize(("name", "measures"), PRIMITIVES, ids=[p[0] for p in PRIMITIVES])
def test_primitive_accessors_return_the_measures_however_given(
    drake: ModuleType, name: str, measures: dict[str, float]
) -> None:
    cls = getattr(drake.geometry, name)
    shapes = [cls(**measures), cls(*measures.values())]
    if len(measures) > 1:
        shapes.append(cls(measures=tuple(measures.values())))
        shapes.append(cls(np.array(list(measures.values()))))
    for shape in shapes:
        assert_shape_api(drake, shape)
        assert {m: getattr(shape, m)() for m in measures} == measures
        assert all(type(getattr(shape, m)()) is float for m in measures)


@pytest.mark.parametrize(("name", "measures"), PRIMITIVES, ids=[p[0] for p in PRIMITIVES])
def test_primitives_pickle_their_measures(
    drake: ModuleType, name: str, measures: dict[str, float]
) -> None:
    shape = getattr(drake.geometry, name)(**measures)
    assert_pickle(shape, lambda s: [getattr(s, m)() for m in measures])
    values = tuple(measures.values())
    assert shape.__getstate__() == (values[0] if len(values) == 1 else values)


def test_box_size_is_its_measures(drake: ModuleType) -> None:
    box = drake.geometry.Box(measures=(1.0, 2.0, 3.0))
    size = box.size()
    assert isinstance(size, np.ndarray)
    assert size.dtype == np.float64
    np.testing.assert_array_equal(size, np.array([1.0, 2.0, 3.0]))
    # 1.51.1 hands out a read-only array; 1.58.0 a writeable one.
    assert size.flags.writeable is not _follows_1_51(drake)


def test_box_has_no_make_cube(drake: ModuleType) -> None:
    assert not hasattr(drake.geometry.Box, "MakeCube")


def test_halfspace_copies_but_does_not_pickle(drake: ModuleType) -> None:
    half_space = drake.geometry.HalfSpace()
    assert_shape_api(drake, half_space)
    for duplicate in (copy.copy(half_space), copy.deepcopy(half_space)):
        assert type(duplicate) is type(half_space)
        assert duplicate is not half_space
    with pytest.raises(TypeError) as info:
        pickle.dumps(half_space)
    assert str(info.value) == f"cannot pickle '{drake.__name__}.geometry.HalfSpace' object"


def test_shape_itself_has_no_constructor(drake: ModuleType) -> None:
    # pybind11's wording: 'No constructor defined!' up to 1.57, 'no constructor defined!'
    # on 1.58 (both measured).
    no = "No" if fact_holds_for(drake, "pybind-wording-until-1.57") else "no"
    with pytest.raises(TypeError, match=rf"geometry\.Shape: {no} constructor defined!$"):
        drake.geometry.Shape()


@pytest.mark.parametrize(
    ("expression", "tail"),
    [
        (
            "Sphere(-1)",
            "in Sphere(): condition 'std::isfinite(radius) && radius >= 0' failed. radius = -1.0.",
        ),
        (
            "Sphere(radius=math.nan)",
            "in Sphere(): condition 'std::isfinite(radius) && radius >= 0' failed. radius = nan.",
        ),
        (
            "Box(0, 1, 1)",
            "in Box(): condition 'std::isfinite(width) && width > 0' failed. width = 0.0.",
        ),
        (
            "Box(-1, -2, -3)",
            "in Box(): condition 'std::isfinite(width) && width > 0' failed. width = -1.0.",
        ),
        (
            "Box(measures=[1, -0.5, 3])",
            "in Box(): condition 'std::isfinite(depth) && depth > 0' failed. depth = -0.5.",
        ),
        (
            "Box(1, 1, math.inf)",
            "in Box(): condition 'std::isfinite(height) && height > 0' failed. height = inf.",
        ),
        (
            "Capsule(-0.0, 1)",
            "in Capsule(): condition 'std::isfinite(radius) && radius > 0' failed. radius = -0.0.",
        ),
        (
            "Capsule(1, -1e-300)",
            "in Capsule(): condition 'std::isfinite(length) && "
            "length > 0' failed. length = -1.e-300.",
        ),
        (
            "Cylinder(-1e-5, 1)",
            "in Cylinder(): condition 'std::isfinite(radius) && "
            "radius > 0' failed. radius = -1.e-05.",
        ),
        (
            "Cylinder(1, math.nan)",
            "in Cylinder(): condition 'std::isfinite(length) && length > 0' failed. length = nan.",
        ),
        (
            "Ellipsoid(1, -1/3, 1)",
            "in Ellipsoid(): condition 'std::isfinite(b) && b > 0' "
            "failed. b = -0.3333333333333333.",
        ),
        (
            "Ellipsoid(1, 1, -1e15)",
            "in Ellipsoid(): condition 'std::isfinite(c) && c > 0' "
            "failed. c = -1000000000000000.0.",
        ),
        (
            "MeshcatCone(-1, -2, -3)",
            "in MeshcatCone(): condition 'std::isfinite(height) && "
            "height > 0' failed. height = -1.0.",
        ),
        (
            "MeshcatCone(1, 0)",
            "in MeshcatCone(): condition 'std::isfinite(a) && a > 0' failed. a = 0.0.",
        ),
        (
            "MeshcatCone(1, 1, -1e16)",
            "in MeshcatCone(): condition 'std::isfinite(b) && b > 0' failed. b = -1.e+16.",
        ),
    ],
)
def test_invalid_measures_raise_system_exit_naming_the_failed_condition(
    drake: ModuleType, expression: str, tail: str
) -> None:
    with pytest.raises(SystemExit) as info:
        eval(expression, {**vars(drake.geometry), "math": math})
    assert type(info.value) is SystemExit
    assert failure_tail(info.value) == tail


def test_failed_checks_name_drake_1_51_lines(drake: ModuleType) -> None:
    g = drake.geometry
    where = "Failure at external/drake+/geometry/shape_specification.cc"
    expected = {
        "Sphere(-1)": f"{where}:309 in Sphere()",
        "Box(-1, 1, 1)": f"{where}:110 in Box()",
        "Box(1, -1, 1)": f"{where}:111 in Box()",
        "Box(1, 1, -1)": f"{where}:112 in Box()",
        "Capsule(-1, 1)": f"{where}:129 in Capsule()",
        "Capsule(1, -1)": f"{where}:130 in Capsule()",
        "Cylinder(-1, 1)": f"{where}:194 in Cylinder()",
        "Cylinder(1, -1)": f"{where}:195 in Cylinder()",
        "Ellipsoid(-1, 1, 1)": f"{where}:206 in Ellipsoid()",
        "Ellipsoid(1, -1, 1)": f"{where}:207 in Ellipsoid()",
        "Ellipsoid(1, 1, -1)": f"{where}:208 in Ellipsoid()",
        "HalfSpace.MakePose([0, 0, 0], [0, 0, 0])": f"{where}:225 in MakePose()",
        "MeshcatCone(-1, 1, 1)": f"{where}:296 in MeshcatCone()",
        "MeshcatCone(1, -1, 1)": f"{where}:297 in MeshcatCone()",
        "MeshcatCone(1, 1, -1)": f"{where}:298 in MeshcatCone()",
    }
    for expression, location in expected.items():
        with pytest.raises(SystemExit) as info:
            eval(expression, dict(vars(g)))
        if _follows_1_51(drake):  # 1.58.0 has the same text at other lines (Sphere: 285)
            assert str(info.value).startswith(location + ": condition ")
        else:
            assert re.match(r".*:\d+ in \w+\(\): condition ", str(info.value))


def test_zero_radius_sphere_is_valid(drake: ModuleType) -> None:
    assert drake.geometry.Sphere(radius=0.0).radius() == 0.0


@pytest.mark.parametrize(
    ("expression", "volume"),
    [
        ("Sphere(1)", 4.1887902047863905),
        ("Sphere(0.5)", 0.5235987755982988),
        ("Sphere(0)", 0.0),
        ("Box(1, 2, 3)", 6.0),
        ("Box(0.1, 0.2, 0.3)", 0.006000000000000001),
        ("Cylinder(1, 2)", 6.283185307179586),
        ("Cylinder(0.5, 3)", 2.356194490192345),
        ("Capsule(1, 2)", 10.471975511965976),
        ("Capsule(0.5, 3)", 2.8797932657906435),
        ("Ellipsoid(1, 2, 3)", 25.132741228718345),
        ("MeshcatCone(1.2, 3.4, 5.6)", 23.926369649739858),
        ("MeshcatCone(3, 1, 1)", 3.141592653589793),
        ("HalfSpace()", math.inf),
    ],
)
def test_calc_volume_is_drakes_formula_to_the_last_bit(
    drake: ModuleType, expression: str, volume: float
) -> None:
    g = drake.geometry
    shape = eval(expression, dict(vars(g)))
    assert g.CalcVolume(shape) == volume
    assert g.CalcVolume(shape=shape) == volume


def test_calc_volume_takes_only_a_shape(drake: ModuleType) -> None:
    with pytest.raises(TypeError, match=r"^CalcVolume\(\): incompatible function arguments"):
        drake.geometry.CalcVolume(1)


# ------------------------------------------------------------------- HalfSpace.MakePose

MAKE_POSE: list[tuple[list[float], list[float], list[list[float]]]] = [
    # Hz_dir_F, p_FB, the top three rows of X_FH.GetAsMatrix4() on pydrake 1.51.1
    ([0, 1, 0], [1, 1, 1], [[0.0, -1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 1.0], [-1.0, 0.0, 0.0, 0.0]]),
    ([1, 0, 0], [0, 0, 0], [[0.0, 0.0, 1.0, 0.0], [0.0, -1.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]]),
    ([0, 0, 5], [0, 0, 0], [[0.0, -1.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]]),
    ([0, -3, 0], [4, 5, 6], [[0.0, -1.0, 0.0, 0.0], [0.0, 0.0, -1.0, 5.0], [1.0, 0.0, 0.0, 0.0]]),
    ([1e-10, 0, 0], [0, 0, 0], [[0.0, 0.0, 1.0, 0.0], [0.0, -1.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]]),
    (
        [1, 1, 1],
        [1, 2, 3],
        [
            [0.0, -0.8164965809277261, 0.5773502691896258, 2.0000000000000004],
            [0.7071067811865476, 0.4082482904638631, 0.5773502691896258, 2.0000000000000004],
            [-0.7071067811865476, 0.4082482904638631, 0.5773502691896258, 2.0000000000000004],
        ],
    ),
    (
        [1, 2, 3],
        [0, 0, 1],
        [
            [0.0, -0.9636241116594317, 0.2672612419124244, 0.2142857142857143],
            [0.8320502943378437, 0.14824986333222026, 0.5345224838248488, 0.4285714285714286],
            [-0.5547001962252291, 0.22237479499833038, 0.8017837257372732, 0.6428571428571429],
        ],
    ),
    (
        [-2, 1, 0.5],
        [1, -1, 2],
        [
            [0.4472135954999579, -0.19518001458970663, -0.8728715609439696, 0.7619047619047621],
            [0.8944271909999159, 0.09759000729485331, 0.4364357804719848, -0.38095238095238104],
            [0.0, -0.9759000729485332, 0.2182178902359924, -0.19047619047619052],
        ],
    ),
]


@pytest.mark.parametrize(("Hz_dir_F", "p_FB", "rows"), MAKE_POSE)
def test_make_pose_is_drakes_basis_and_nearest_boundary_point(
    drake: ModuleType, Hz_dir_F: list[float], p_FB: list[float], rows: list[list[float]]
) -> None:
    X_FH = drake.geometry.HalfSpace.MakePose(Hz_dir_F=Hz_dir_F, p_FB=p_FB)
    assert isinstance(X_FH, drake.math.RigidTransform)
    np.testing.assert_array_equal(X_FH.GetAsMatrix4(), np.array([*rows, [0, 0, 0, 1]]))


def test_make_pose_keeps_signed_zeros(drake: ModuleType) -> None:
    X_FH = drake.geometry.HalfSpace().MakePose([0, 0, -1], [0, 0, 0])
    assert repr(X_FH) == (
        "RigidTransform(\n"
        "  R=RotationMatrix([\n"
        "    [0.0, -1.0, 0.0],\n"
        "    [-1.0, -0.0, 0.0],\n"
        "    [0.0, -0.0, -1.0],\n"
        "  ]),\n"
        "  p=[0.0, 0.0, -0.0],\n"
        ")"
    )


@pytest.mark.parametrize(
    ("Hz_dir_F", "norm"),
    [([1e-11, 0, 0], "1.e-11"), ([0, 0, 0], "0.0"), ([math.nan, 0, 0], "nan")],
)
def test_make_pose_rejects_a_normal_shorter_than_1e_10(
    drake: ModuleType, Hz_dir_F: list[float], norm: str
) -> None:
    with pytest.raises(SystemExit) as info:
        drake.geometry.HalfSpace.MakePose(Hz_dir_F=Hz_dir_F, p_FB=[0, 0, 0])
    assert failure_tail(info.value) == (
        f"in MakePose(): condition 'norm >= 1e-10' failed. norm = {norm}."
    )


def test_make_pose_takes_two_3_vectors(drake: ModuleType) -> None:
    with pytest.raises(TypeError, match=r"^MakePose\(\): incompatible function arguments"):
        drake.geometry.HalfSpace.MakePose(Hz_dir_F=[0, 1], p_FB=[0, 0, 0])


def test_make_pose_gives_a_rotation_whose_z_is_the_normal(drake: ModuleType) -> None:
    rng = np.random.default_rng(20240519)
    for _ in range(50):
        Hz_dir_F = rng.normal(size=3) * rng.choice([1e-6, 1.0, 1e6])
        p_FB = rng.normal(size=3)
        X_FH = drake.geometry.HalfSpace.MakePose(Hz_dir_F=Hz_dir_F, p_FB=p_FB)
        R, p = X_FH.rotation().matrix(), X_FH.translation()
        Hz = Hz_dir_F / np.linalg.norm(Hz_dir_F)
        np.testing.assert_allclose(R.T @ R, np.eye(3), atol=1e-12)
        assert np.linalg.det(R) == pytest.approx(1.0, abs=1e-12)
        np.testing.assert_allclose(R[:, 2], Hz, atol=1e-12)
        # Hx is perpendicular to the axis of the normal's smallest component.
        assert R[int(np.argmin(np.abs(Hz_dir_F))), 0] == 0.0
        np.testing.assert_allclose(p, (Hz @ p_FB) * Hz, atol=1e-12)


def test_reimpl_make_pose_equals_the_installed_pydrakes() -> None:
    """Not a port: reimpl against whichever pydrake is installed, on 50 random normals."""
    pydrake_geometry = pytest.importorskip("pydrake.geometry")
    reimpl_geometry = pytest.importorskip("reimpl.geometry")
    rng = np.random.default_rng(7)
    for _ in range(50):
        Hz_dir_F = rng.normal(size=3) * rng.choice([1e-6, 1.0, 1e6])
        p_FB = rng.normal(size=3) * 10
        expected = pydrake_geometry.HalfSpace.MakePose(Hz_dir_F, p_FB).GetAsMatrix4()
        actual = reimpl_geometry.HalfSpace.MakePose(Hz_dir_F, p_FB).GetAsMatrix4()
        np.testing.assert_allclose(actual, expected, rtol=0, atol=1e-12)


# --------------------------------------------------------------------------- Mesh, Convex

MESHES = ("Mesh", "Convex")


@pytest.mark.parametrize("name", MESHES)
def test_mesh_from_a_path_keeps_path_extension_and_scale(drake: ModuleType, name: str) -> None:
    g = drake.geometry
    junk_path = "arbitrary/path.ext"
    for dut_mesh in (getattr(g, name)(filename=junk_path, scale=1.5),):
        assert_shape_api(drake, dut_mesh)
        assert dut_mesh.extension() == ".ext"
        assert dut_mesh.scale() == 1.5
        source = dut_mesh.source()
        assert isinstance(source, g.MeshSource)
        assert source.is_path()
        assert not source.is_in_memory()
        assert junk_path in source.description()
        assert_pickle(dut_mesh, lambda shape: [shape.source().description(), shape.scale()])


@pytest.mark.parametrize("name", MESHES)
def test_relative_filename_is_joined_to_the_working_directory(
    drake: ModuleType, name: str, monkeypatch: pytest.MonkeyPatch, tmp_path: pathlib.Path
) -> None:
    monkeypatch.chdir(tmp_path)
    cwd = os.getcwd()
    cls = getattr(drake.geometry, name)
    mesh = cls(filename="arbitrary/path.ext", scale=1.0)
    assert mesh.source().description() == f"{cwd}/arbitrary/path.ext"
    assert repr(mesh) == f"{name}(filename='{cwd}/arbitrary/path.ext', scale3=[1.0, 1.0, 1.0])"
    # std::filesystem::absolute keeps the text; path() (and so repr) is pathlib's spelling.
    odd = cls("a//b/./c.obj")
    assert odd.source().description() == f"{cwd}/a//b/./c.obj"
    assert odd.source().path() == pathlib.Path(f"{cwd}/a/b/c.obj")
    assert cls("../up.obj").source().description() == f"{cwd}/../up.obj"
    assert cls("/tmp//x/./y.obj").source().description() == "/tmp//x/./y.obj"
    with pytest.raises(RuntimeError) as info:
        cls("")
    assert str(info.value) == "filesystem error: cannot make absolute path: Invalid argument []"


@pytest.mark.parametrize("name", MESHES)
def test_mesh_repr_names_filename_and_scale3(drake: ModuleType, name: str) -> None:
    cls = getattr(drake.geometry, name)
    cases = {
        cls("/tmp/a.obj"): f"{name}(filename='/tmp/a.obj', scale3=[1.0, 1.0, 1.0])",
        cls("/tmp/a.obj", 1.5): f"{name}(filename='/tmp/a.obj', scale3=[1.5, 1.5, 1.5])",
        cls(filename=pathlib.Path("/tmp/a.obj"), scale3=[1, 0.5, -2.25]): (
            f"{name}(filename='/tmp/a.obj', scale3=[1.0, 0.5, -2.25])"
        ),
        cls(b"/tmp/it's.obj", scale=0.1 + 0.2): (
            f'{name}(filename="/tmp/it\'s.obj", scale3=[0.30000000000000004, '
            "0.30000000000000004, 0.30000000000000004])"
        ),
    }
    for mesh, text in cases.items():
        assert repr(mesh) == text
        assert repr(eval(repr(mesh), {name: type(mesh)})) == text
    # A MeshSource keeps a relative path, so that repr evaluates to an absolute filename.
    relative = cls(source=drake.geometry.MeshSource("rel/y.obj"), scale=2)
    assert repr(relative) == f"{name}(filename='rel/y.obj', scale3=[2.0, 2.0, 2.0])"
    evaluated = eval(repr(relative), {name: cls})
    assert evaluated.source().description() == f"{os.getcwd()}/rel/y.obj"


@pytest.mark.parametrize(
    ("filename", "extension"),
    [
        ("/m/a.obj", ".obj"),
        ("/m/a.OBJ", ".obj"),
        ("/m/a.b.GlTf", ".gltf"),
        ("/m/a.tar.gz", ".gz"),
        ("/m/a", ""),
        ("/m/.hidden", ""),
        ("/m/.a.vtk", ".vtk"),
        ("/m/..a", ".a"),
        ("/m/a.", "."),
        ("/m/dir.x/file", ""),
        ("/m/a.obj/", ""),
        ("/m/é.ÉXT", ".Éxt"),
    ],
)
def test_extension_is_std_filesystem_extension_with_ascii_lowered(
    drake: ModuleType, filename: str, extension: str
) -> None:
    g = drake.geometry
    assert g.Mesh(filename).extension() == extension
    assert g.Convex(filename).extension() == extension
    assert g.MeshSource(filename).extension() == extension


@pytest.mark.parametrize("name", MESHES)
def test_scale3_may_be_non_uniform_but_then_scale_refuses(drake: ModuleType, name: str) -> None:
    cls = getattr(drake.geometry, name)
    mesh = cls("/tmp/a.obj", scale3=[1, 2, 3])
    np.testing.assert_array_equal(mesh.scale3(), [1.0, 2.0, 3.0])
    np.testing.assert_array_equal(cls("/tmp/a.obj", 2).scale3(), [2.0, 2.0, 2.0])
    assert cls("/tmp/a.obj", scale3=[2, 2, 2]).scale() == 2.0
    assert cls("/tmp/a.obj", -1).scale() == -1.0
    with pytest.raises(RuntimeError) as info:
        mesh.scale()
    vector = "[1 2 3]" if _follows_1_51(drake) else "[1, 2, 3]ᵀ"  # 1.58.0's layout
    assert str(info.value) == (
        f"{name}::scale() can only be called for uniform scaling. This mesh has scale "
        f"{vector}. Use {name}::scale3() instead."
    )
    assert_pickle(mesh, lambda shape: shape.scale3().tolist())


@pytest.mark.parametrize(
    ("scale", "given"),
    [
        ({"scale": 0}, "[0 0 0]"),
        ({"scale": 9.99e-9}, "[9.99e-09 9.99e-09 9.99e-09]"),
        ({"scale": -9.99e-9}, "[-9.99e-09 -9.99e-09 -9.99e-09]"),
        ({"scale": math.inf}, "[inf inf inf]"),
        ({"scale3": [1, -1e-9, 1]}, "[     1 -1e-09      1]"),
        ({"scale3": [1, math.nan, 1]}, "[  1 nan   1]"),
        (
            {"scale3": [1, 1, 9.9e-9]},
            "[                    1                     1 9.899999999999999e-09]",
        ),
    ],
)
def test_scale_must_be_finite_and_at_least_1e_8_in_magnitude(
    drake: ModuleType, scale: dict[str, Any], given: str
) -> None:
    for name in MESHES:
        cls = getattr(drake.geometry, name)
        with pytest.raises(RuntimeError) as info:
            cls("/tmp/a.obj", **scale)
        message = str(info.value)
        assert message.startswith(f"{name} |scale| cannot be < 1e-8 on any axis, given ")
        if _follows_1_51(drake):  # 1.58.0 writes the vector as [1, -1e-09, 1]ᵀ
            assert message == f"{name} |scale| cannot be < 1e-8 on any axis, given {given}."
        assert cls("/tmp/a.obj", 1e-8).scale() == 1e-8
        assert cls("/tmp/a.obj", -1e-8).scale() == -1e-8


def test_mesh_source_keeps_its_path_as_given(drake: ModuleType) -> None:
    g = drake.geometry
    source = g.MeshSource("rel//x/./y.OBJ")
    assert source.is_path()
    assert not source.is_in_memory()
    assert source.description() == "rel//x/./y.OBJ"
    assert source.path() == pathlib.Path("rel/x/y.OBJ")
    assert isinstance(source.path(), pathlib.PurePath)
    assert source.extension() == ".obj"
    assert repr(source) == "MeshSource(path='rel/x/y.OBJ')"
    assert g.MeshSource(path="").description() == "<empty path>"
    assert repr(g.MeshSource(other=source)) == repr(source)
    with pytest.raises(RuntimeError, match=r"^std::get: wrong index for variant$"):
        source.in_memory()


def test_copies_keep_the_path_text_and_pickles_keep_pathlibs(
    drake: ModuleType, monkeypatch: pytest.MonkeyPatch, tmp_path: pathlib.Path
) -> None:
    monkeypatch.chdir(tmp_path)
    cwd = os.getcwd()
    g = drake.geometry
    for cls in (g.Mesh, g.Convex):
        mesh = cls("a//b/./c.obj", scale3=[1, 2, 3])
        for duplicate in (mesh.Clone(), copy.copy(mesh), copy.deepcopy(mesh)):
            assert duplicate.source().description() == f"{cwd}/a//b/./c.obj"
        restored = pickle.loads(pickle.dumps(mesh))
        assert restored.source().description() == f"{cwd}/a/b/c.obj"
        np.testing.assert_array_equal(restored.scale3(), [1.0, 2.0, 3.0])
        source, scale3 = mesh.__getstate__()
        assert isinstance(source, g.MeshSource)
        np.testing.assert_array_equal(scale3, [1.0, 2.0, 3.0])
    source = g.MeshSource("a//b")
    assert source.__getstate__() == {"path": pathlib.Path("a/b")}
    assert copy.deepcopy(source).description() == "a//b"
    assert pickle.loads(pickle.dumps(source)).description() == "a/b"
