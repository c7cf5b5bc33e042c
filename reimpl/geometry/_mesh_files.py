"""The points and triangles of a mesh file, as Drake reads them for the proximity role.

Drake counterpart: geometry/proximity/make_convex_hull_mesh_impl.cc (ReadVertices),
obj_to_surface_mesh.cc and vtk_to_volume_mesh.cc. reimpl reads the files with
trimesh (``.obj``, ``.gltf``) and meshio (``.vtk``), each loaded as it is, and
applies Drake's arithmetic on top (measured on pydrake 1.51.1 against
``Convex(...).GetConvexHull()`` for every mesh file vendored in
``scenarios/real_models``):

* ``.obj``: every ``v`` line, in the file's order, each coordinate times the
  scale (``scale3 ⊙ v``); ``trimesh.load(process=False, maintain_order=True)``
  gives exactly the file's ``v`` lines for 72 of the 73 vendored OBJ files and
  the same set, some repeated, for the 73rd (one object per material). A file
  of vertices alone is a point cloud to trimesh, and still a hull to Drake.
* ``.gltf``: every vertex of every primitive of every node of the default
  scene, moved by the node's global transform, then turned from glTF's y-up
  frame F into Drake's z-up frame G, ``p_G = R_x(π/2)·p_F``, written out as
  Drake rounds it (``(x, c·y − z, y + c·z)`` with ``c = cos(π/2) ≈ 6e-17``), then
  scaled: bit-equal to Drake's on 8,874 of the 8,875 hull vertices of the
  vendored glTF files (the last one 1 ulp off, a node rotation given as a
  quaternion).
* ``.vtk``: the POINTS of the tetrahedral mesh, scaled.

For a Mesh's signed distance to a point Drake also reads triangles: an
``.obj``'s faces, triangulated (``obj_triangles``), and a ``.vtk``'s boundary
faces, the faces of exactly one tetrahedron (``vtk_boundary``).
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Sequence
from typing import Any

import numpy as np
import numpy.typing as npt

__all__ = ["Points", "Triangles", "mesh_vertices", "obj_triangles", "vtk_boundary"]

Points = npt.NDArray[np.float64]
Triangles = npt.NDArray[np.intp]

#: cos(π/2) as Drake's RotationMatrix::MakeXRotation(M_PI / 2) holds it.
_COS_HALF_PI = math.cos(math.pi / 2)


def _load_obj(path: str) -> Any:
    import trimesh  # noqa: PLC0415 (heavy; read only when a mesh is made)

    return trimesh.load(path, file_type="obj", process=False, maintain_order=True)


def _obj_vertices(path: str) -> Points:
    """Every ``v`` of the file (trimesh: a Trimesh, a point cloud, or a scene of them)."""
    loaded = _load_obj(path)
    geometries = getattr(loaded, "geometry", None)
    if geometries is not None:
        return np.concatenate([np.asarray(g.vertices, dtype=float) for g in geometries.values()])
    return np.asarray(loaded.vertices, dtype=float).reshape(-1, 3)


def _gltf_vertices(path: str) -> Points:
    """Every node's vertices in the file frame F, then ``R_x(π/2)`` into G (see module)."""
    import trimesh  # noqa: PLC0415

    scene = trimesh.load(path, file_type="gltf", process=False, force="scene")
    blocks = []
    for node in scene.graph.nodes_geometry:
        T, name = scene.graph[node]
        v = np.asarray(scene.geometry[name].vertices, dtype=float)
        x, y, z = v[:, 0], v[:, 1], v[:, 2]
        # vtkMatrix4x4::MultiplyPoint: each row's products summed left to right.
        blocks.append(
            np.stack([((T[i, 0] * x + T[i, 1] * y) + T[i, 2] * z) + T[i, 3] for i in range(3)], 1)
        )
    F = np.concatenate(blocks) if blocks else np.zeros((0, 3))
    x, y, z = F[:, 0], F[:, 1], F[:, 2]
    return np.stack([x, _COS_HALF_PI * y - z, y + _COS_HALF_PI * z], axis=1)


def _read_vtk(path: str) -> Any:
    import meshio  # noqa: PLC0415

    try:
        return meshio.read(path, file_format="vtk")
    except SystemExit as exc:  # meshio ends the process on some read errors
        raise RuntimeError(f"reimpl: meshio cannot read '{path}'") from exc


def _vtk_vertices(path: str) -> Points:
    return np.asarray(_read_vtk(path).points, dtype=float).reshape(-1, 3)


_READERS = {".obj": _obj_vertices, ".gltf": _gltf_vertices, ".vtk": _vtk_vertices}


def mesh_vertices(path: str, extension: str, scale3: Sequence[float]) -> Points:
    """The scaled vertices Drake's MakeConvexHull reads, in Drake's order (see module)."""
    vertices: Points = _READERS[extension](path) * np.asarray(scale3, dtype=float)
    return vertices


def obj_triangles(path: str, scale3: Sequence[float]) -> tuple[Points, Triangles]:
    """An ``.obj`` as a triangle surface (Drake's ReadObjToTriangleSurfaceMesh): the scaled
    vertices and the faces, each polygon cut into triangles."""
    loaded = _load_obj(path)
    geometries = getattr(loaded, "geometry", None)
    parts = list(geometries.values()) if geometries is not None else [loaded]
    vertices, faces, offset = [], [], 0
    for part in parts:
        v = np.asarray(part.vertices, dtype=float).reshape(-1, 3)
        f = np.asarray(getattr(part, "faces", np.zeros((0, 3))), dtype=np.intp).reshape(-1, 3)
        vertices.append(v)
        faces.append(f + offset)
        offset += len(v)
    return (
        np.concatenate(vertices) * np.asarray(scale3, dtype=float),
        np.concatenate(faces),
    )


def vtk_boundary(path: str, scale3: Sequence[float]) -> tuple[Points, Triangles]:
    """A tetrahedral ``.vtk`` mesh's boundary (Drake's ConvertVolumeToSurfaceMesh): each face
    of exactly one tetrahedron, wound outwards, on the scaled points."""
    mesh = _read_vtk(path)
    points = np.asarray(mesh.points, dtype=float).reshape(-1, 3) * np.asarray(scale3, dtype=float)
    tets = np.concatenate([np.asarray(c.data) for c in mesh.cells if c.type == "tetra"])
    # Drake's faces of tetrahedron (v0, v1, v2, v3), each wound outwards (IdentifyBoundaryFaces);
    # a face met twice is inside. Drake keeps them in the order of their sorted vertex triple.
    local = ((1, 2, 3), (3, 2, 0), (1, 3, 0), (2, 1, 0))
    faces = [tuple(int(t[i]) for i in face) for t in tets for face in local]
    count = Counter(tuple(sorted(f)) for f in faces)
    boundary = sorted((f for f in faces if count[tuple(sorted(f))] == 1), key=sorted)
    return points, np.asarray(boundary, dtype=np.intp).reshape(-1, 3)
