"""Mesh, Convex and MeshSource for meshes named by a file path, as pydrake 1.51.1 measures them.

reimpl keeps the path and the scale, as Drake's shape specification does, and
reads a mesh file only where pydrake's answer depends on it: when a Mesh or
Convex gets the proximity role (SceneGraph.AssignRole, a GeometryInstance
registered with proximity properties, MultibodyPlant.RegisterCollisionGeometry,
so a parsed <collision>), Drake makes its convex hull and may fail. To decide
those errors (see reimpl.geometry._proximity_mesh for the rules and messages)
reimpl reads no more than:

* an ``.obj``: whether it can be opened, its ``v`` lines (the vertices, for
  their count and whether they are all within 1e-12 of one point or on one
  line), and, for a Mesh, which of the ``f``, ``l``, ``p`` elements it has;
* a ``.vtk`` (legacy ASCII): its DATASET kind, POINTS, cell sizes and
  CELL_TYPES (whether every cell is a tetrahedron, and that there is one);
* a ``.gltf``: whether it can be opened.

A visual (illustration or perception) mesh is never read, as on pydrake 1.51.1
(measured: an empty ``.obj`` as a visual registers fine). The shape itself:

* ``Mesh(filename, scale=1.0)``, ``Mesh(filename, scale3=[x, y, z])`` and the
  same with ``source=MeshSource(...)``. A relative filename is made absolute
  against the current directory the way ``std::filesystem::absolute`` does it
  (``'a//b/./c.obj'`` becomes ``'<cwd>/a//b/./c.obj'``); an empty one raises
  RuntimeError. A MeshSource keeps its path as given.
* Every scale factor must be finite with magnitude ≥ 1e-8 (negative is fine),
  else RuntimeError ``Mesh |scale| cannot be < 1e-8 on any axis, given [0 0 0].``
  (Eigen's 1.51.1 layout; 1.58.0 writes ``[0, 0, 0]ᵀ``).
* ``MeshSource.path()`` is a ``pathlib.Path`` of the stored text, so it (and
  ``repr``, and pickling, which goes through it) shows pathlib's spelling;
  ``description()`` is the text itself, ``'<empty path>'`` when empty.
  ``extension()`` is ``std::filesystem::path::extension()`` with ASCII letters
  lowered: ``'.obj'`` for ``a.OBJ``, ``''`` for ``.hidden``, ``'.'`` for ``a.``.
* ``repr`` is ``Mesh(filename='/tmp/a.obj', scale3=[1.5, 1.5, 1.5])``;
  ``Clone``/``copy`` keep the stored text, pickling stores
  ``(MeshSource, scale3)`` and ``{'path': Path}``.

``GetConvexHull()`` is Drake's hull of the file's vertices (``_convex_hull``), as a
PolygonSurfaceMesh, made at the first call and kept by the shape and its clones
(Drake keeps it too); a file Drake cannot hull raises Drake's message
(``_proximity_mesh``). Its vertices and faces are pydrake's; their numbering is the
file's order, not Qhull's (see ``_convex_hull``).

Out of scope: in-memory meshes (``InMemoryMesh``, ``mesh_data=``,
``MeshSource(mesh=...)``) and ``Convex(points=...)`` are absent (AttributeError /
TypeError from the overload set); ``CalcVolume`` of a Mesh or Convex raises
NotImplementedError.
``MeshSource.in_memory()`` raises pydrake's own error for a path source, the
only kind reimpl has.
"""

from __future__ import annotations

import itertools
import math
import os
import pathlib
import string
from collections.abc import Callable
from typing import Any

import numpy as np
import numpy.typing as npt

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl.geometry._convex_hull import Hull, convex_hull
from reimpl.geometry._drake_text import eigen_vector
from reimpl.geometry._mesh_files import mesh_vertices, obj_triangles, vtk_boundary
from reimpl.geometry._proximity_mesh import check_proximity_mesh
from reimpl.geometry._shape_args import is_float, is_path_like, is_vector, path_text
from reimpl.geometry.polygon_surface_mesh import PolygonSurfaceMesh
from reimpl.geometry.proximity.distance_to_mesh import MeshBoundary
from reimpl.geometry.shape import Shape

__all__ = ["Convex", "Mesh", "MeshSource"]

_ASCII_LOWER = str.maketrans(string.ascii_uppercase, string.ascii_lowercase)
_MIN_SCALE = 1e-8


def _extension(path: str) -> str:
    """``std::filesystem::path(path).extension()`` (libstdc++), ASCII-lowered as Drake does."""
    name = path.rsplit("/", 1)[-1]
    dot = name.rfind(".")
    if dot <= 0 or (len(name) <= 2 and name.startswith(".")):  # none, ".hidden", "." or ".."
        return ""
    return name[dot:].translate(_ASCII_LOWER)


def _absolute(path: str) -> str:
    """``std::filesystem::absolute(path)`` (libstdc++): cwd joined, nothing normalised."""
    if not path:
        raise RuntimeError("filesystem error: cannot make absolute path: Invalid argument []")
    if path.startswith("/"):
        return path
    cwd = os.getcwd()
    return cwd + path if cwd.endswith("/") else f"{cwd}/{path}"


class MeshSource:
    """Where a mesh's data comes from; in reimpl always a file path."""

    __slots__ = ("_path",)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        def from_path(path: Any) -> None:
            self._path = path_text(path)

        def from_other(other: MeshSource) -> None:
            self._path = other._path

        dispatch(
            "reimpl.geometry.MeshSource",
            "__init__",
            (
                Overload((Param("path", is_path_like),), from_path),
                Overload((Param("other", instance_of(MeshSource)),), from_other),
            ),
            args,
            kwargs,
        )

    def is_path(self) -> bool:
        return True

    def is_in_memory(self) -> bool:
        return False

    def path(self) -> pathlib.Path:
        return pathlib.Path(self._path)

    def in_memory(self) -> Any:
        raise RuntimeError("std::get: wrong index for variant")

    def description(self) -> str:
        return self._path or "<empty path>"

    def extension(self) -> str:
        return _extension(self._path)

    def __repr__(self) -> str:
        return f"MeshSource(path={str(self.path())!r})"

    def __copy__(self) -> MeshSource:
        return MeshSource(other=self)

    def __deepcopy__(self, memo: dict[int, Any]) -> MeshSource:
        return MeshSource(other=self)

    def __getstate__(self) -> dict[str, pathlib.Path]:
        return {"path": self.path()}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self._path = path_text(state["path"])


class _MeshShape(Shape):
    """What Mesh and Convex share: a MeshSource and a per-axis scale."""

    __slots__ = ("_boundary", "_hull", "_scale3", "_source")
    _source: MeshSource
    _scale3: tuple[float, float, float]
    _hull: Hull | None
    _boundary: MeshBoundary | None

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        def from_file(filename: Any, scale: Any = None, scale3: Any = None) -> None:
            self._set(MeshSource(_absolute(path_text(filename))), scale, scale3)

        def from_source(source: MeshSource, scale: Any = None, scale3: Any = None) -> None:
            self._set(MeshSource(other=source), scale, scale3)

        scale = Param("scale", is_float, 1.0)
        scale3 = Param("scale3", is_vector(3))
        filename = Param("filename", is_path_like)
        source = Param("source", instance_of(MeshSource))
        dispatch(
            f"reimpl.geometry.{type(self).__name__}",
            "__init__",
            (
                Overload((filename, scale), from_file),
                Overload((filename, scale3), from_file),
                Overload((source, scale), from_source),
                Overload((source, scale3), from_source),
            ),
            args,
            kwargs,
        )

    def _set(self, source: MeshSource, scale: Any, scale3: Any) -> None:
        if scale3 is None:
            scale3 = (scale,) * 3
        x, y, z = (float(s) for s in np.asarray(scale3, dtype=float).reshape(3))
        if not all(math.isfinite(s) and abs(s) >= _MIN_SCALE for s in (x, y, z)):
            raise RuntimeError(
                f"{type(self).__name__} |scale| cannot be < 1e-8 on any axis, "
                f"given {eigen_vector((x, y, z))}."
            )
        self._source, self._scale3, self._hull, self._boundary = source, (x, y, z), None, None

    def source(self) -> MeshSource:
        return MeshSource(other=self._source)

    def extension(self) -> str:
        return self._source.extension()

    def _check_proximity(self, *, hydroelastic: bool = False) -> None:
        """Raises what Drake raises making this shape's proximity representation
        (``hydroelastic``: its properties have a hydroelastic group)."""
        check_proximity_mesh(
            self._source.description(),
            self.extension(),
            self._scale3,
            is_convex=isinstance(self, Convex),
            hydroelastic=hydroelastic,
        )

    def _hull_data(self) -> Hull:
        """Drake's convex hull of the file's scaled vertices (made once, then kept)."""
        if self._hull is None:
            path = self._source.description()
            check_proximity_mesh(path, self.extension(), self._scale3, is_convex=True)
            self._hull = convex_hull(mesh_vertices(path, self.extension(), self._scale3))
        return self._hull

    def _boundary_data(self) -> MeshBoundary | None:
        """The surface ComputeSignedDistanceToPoint measures to (Drake's mesh_sdf_data_): a
        Convex's hull, fanned into triangles; a Mesh's ``.obj`` faces or ``.vtk`` boundary;
        None for a Mesh's ``.gltf`` (Drake skips it)."""
        if self._boundary is None:
            self._boundary = _BOUNDARY[type(self), self.extension()](self)
        return self._boundary

    def GetConvexHull(self) -> PolygonSurfaceMesh:
        """The convex hull as a PolygonSurfaceMesh (see the module doc)."""
        hull = self._hull_data()
        return PolygonSurfaceMesh(hull.face_data, hull.vertices)

    def scale(self) -> float:
        x, y, z = self._scale3
        if not x == y == z:
            name = type(self).__name__
            raise RuntimeError(
                f"{name}::scale() can only be called for uniform scaling. This mesh has scale "
                f"{eigen_vector(self._scale3)}. Use {name}::scale3() instead."
            )
        return x

    def scale3(self) -> npt.NDArray[np.float64]:
        return np.array(self._scale3)

    def __repr__(self) -> str:
        filename = str(self._source.path())
        return f"{type(self).__name__}(filename={filename!r}, scale3={list(self._scale3)!r})"

    def __getstate__(self) -> tuple[MeshSource, npt.NDArray[np.float64]]:
        return self.source(), self.scale3()

    def __setstate__(self, state: tuple[MeshSource, Any]) -> None:
        source, scale = state
        if is_float(scale):
            self._set(MeshSource(other=source), scale, None)
        else:
            self._set(MeshSource(other=source), None, scale)


class Mesh(_MeshShape):
    """A (possibly non-convex) mesh, by file path."""

    __slots__ = ()


class Convex(_MeshShape):
    """A mesh that Drake treats as its convex hull, by file path."""

    __slots__ = ()


def _hull_boundary(shape: _MeshShape) -> MeshBoundary:
    """Drake's MakeTriangleFromPolygonMesh: each polygon fanned from its first vertex."""
    hull = shape._hull_data()
    triangles = [
        (polygon[0], b, c) for polygon in hull.polygons for b, c in itertools.pairwise(polygon[1:])
    ]
    return MeshBoundary(hull.vertices, np.array(triangles, dtype=np.intp))


def _obj_boundary(shape: _MeshShape) -> MeshBoundary:
    """The ``.obj``'s triangles; an odd number of negative scale factors reverses them."""
    vertices, triangles = obj_triangles(shape._source.description(), shape._scale3)
    if sum(s < 0 for s in shape._scale3) % 2:
        triangles = triangles[:, ::-1]
    return MeshBoundary(vertices, triangles)


def _vtk_boundary(shape: _MeshShape) -> MeshBoundary:
    return MeshBoundary(*vtk_boundary(shape._source.description(), shape._scale3))


#: (shape class, extension) → its distance surface; a Mesh's ``.gltf`` has none.
_BOUNDARY: dict[tuple[type[_MeshShape], str], Callable[[_MeshShape], MeshBoundary | None]] = {
    **{(Convex, ext): _hull_boundary for ext in (".obj", ".vtk", ".gltf")},
    (Mesh, ".obj"): _obj_boundary,
    (Mesh, ".vtk"): _vtk_boundary,
    (Mesh, ".gltf"): lambda shape: None,
}
