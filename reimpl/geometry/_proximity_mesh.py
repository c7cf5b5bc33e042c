"""Whether Drake can give a Mesh or Convex the proximity role, and its error if not.

Drake counterpart: geometry/proximity/make_convex_hull_mesh_impl.cc (the hull
every proximity Mesh and Convex gets), vtk_to_volume_mesh.cc, read_obj.cc and
the non-convex Mesh's distance data in proximity_engine.cc. The checks run in
this order, each with Drake's message (measured on pydrake 1.51.1, ``D`` the
mesh's path as given, ``ext`` its lowered extension):

1. ``ext`` not ``.obj``, ``.vtk`` or ``.gltf``: ``MakeConvexHull only applies to
   .obj, .vtk, and .gltf meshes; unsupported extension 'ext' for geometry data: D.``
2. Reading the vertices (scaled by ``scale3``):

   - ``.obj``: an unreadable file is ``MemoryFile::Make() cannot read the file
     'D'.``; the vertices are the ``v`` lines (a coordinate that does not
     parse, or is missing, reads as 0, as tinyobjloader reads it).
   - ``.vtk`` (legacy ASCII): a missing file, or a data set that is not an
     UNSTRUCTURED_GRID, has no cells. The first cell that is not a tetrahedron
     raises ``ReadVtkToVolumeMesh(): mesh data should only contain tetrahedra
     (type id=10). Read cell with type id=T, dimension K, and number of points
     N in 'D'.``; no cell at all raises ``A mesh must contain at least one
     tetrahedron``. The vertices are the POINTS.
   - ``.gltf``: a missing file raises ``glTF 'D', named an inaccessible file:
     '<the .gltf file itself>'.``; an existing one is taken as valid.

3. Fewer than three vertices: ``MakeConvexHull() cannot be used on a mesh with
   fewer than three vertices; found N vertices in geometry data: D.``
4. Drake's search for a plane through v₀: the first vᵢ with ‖vᵢ − v₀‖² ≥ 1e-24
   gives a; none raises ``MakeConvexHull failed because all vertices in the
   mesh were within a sphere with radius 1e-12 for geometry: D.``; from there
   on, the first vⱼ with ‖vⱼ − v₀‖² ≥ 1e-24 and ‖â × (vⱼ − v₀)‖² ≥ 1e-24 gives
   the normal; none raises ``MakeConvexHull failed because all vertices in the
   mesh appear to be co-linear for file: D.`` (Coplanar vertices are fine.)
5. A Mesh (not a Convex) from an ``.obj`` is also read as a triangle mesh: no
   ``f``, ``l`` or ``p`` element raises ``error: The OBJ data parsed contains no
   objects; the data could be corrupt, empty, or not an OBJ file. Name: 'D'``;
   no face of three or more vertices raises ``A mesh must contain at least one
   triangle``.

Earlier releases, each by its release fact (measured on 1.12.0-1.35.0 with a Mesh and
a Convex of an ``.stl``, a ``.gltf`` and an ``.obj`` of two objects):

- 1.27-1.33 word check 1 ``MakeConvexHull only applies to obj, vtk, and gltf meshes;
  given file: D.`` (hull-extension-wording-since-1.34); 1.27 then refuses a ``.gltf``
  as 1.23-1.26 do (gltf-mesh-proximity-since-1.28).
- Up to 1.26 there is no hull step 1: the proximity engine refuses any file but an
  ``.obj`` (and, since 1.23, a ``.vtk``: proximity-vtk-meshes-since-1.23) in
  ``_engine_refusal``'s words (convex-hull-meshes-since-1.27,
  engine-extension-wording-since-1.19).
- Up to 1.31 an ``.obj`` whose faces fall into more than one object (``o`` or ``g``
  sections) is ``The OBJ file contains multiple objects; only OBJs with a single object
  are supported: File name: 'D'`` (obj-multiple-objects-refused-until-1.31), after
  check 1.

Not modelled (reimpl reads no more of the file): qhull's own failures on
nearly degenerate clouds, a face index out of range (pydrake 1.51.1 ends with
SystemExit), a binary or XML VTK file (taken as valid), a Mesh's ``.vtk`` whose
tetrahedra have non-positive volume, and a malformed glTF.
"""

from __future__ import annotations

import itertools
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from reimpl._release import release

__all__ = ["HullError", "check_proximity_mesh"]

#: ‖·‖² below which Drake takes two vertices, or a cross product, as zero.
_ZERO_SQUARED = 1e-24
_VTK_TETRA = 10
#: VTK's linear cell types: type id → dimension (vtkCellType.h).
_VTK_CELL_DIMENSION = {
    1: 0,  # vertex
    2: 0,  # poly vertex
    3: 1,  # line
    4: 1,  # poly line
    5: 2,  # triangle
    6: 2,  # triangle strip
    7: 2,  # polygon
    8: 2,  # pixel
    9: 2,  # quad
    10: 3,  # tetrahedron
    11: 3,  # voxel
    12: 3,  # hexahedron
    13: 3,  # wedge
    14: 3,  # pyramid
}

#: The section keywords of a legacy VTK file (a section's numbers run to the next one).
_VTK_KEYWORDS = frozenset(
    {"POINTS", "CELLS", "CELL_TYPES", "OFFSETS", "CONNECTIVITY", "POINT_DATA", "CELL_DATA"}
)

_Vertices = npt.NDArray[np.float64]


def _tinyobj_real(text: str) -> float:
    """tinyobjloader's parseReal: a number, or 0 where the text is not one."""
    try:
        return float(text)
    except ValueError:
        return 0.0


@dataclass(frozen=True)
class _Obj:
    """What reimpl reads of an OBJ file: its vertices and its element kinds."""

    vertices: list[tuple[float, float, float]]
    has_elements: bool
    has_polygon: bool


def _read_obj(path: str, description: str) -> _Obj:
    try:
        with open(path, encoding="utf-8", errors="replace") as file:
            lines = file.read().splitlines()
    except OSError:
        raise RuntimeError(f"MemoryFile::Make() cannot read the file '{description}'.") from None
    vertices = []
    has_elements = has_polygon = False
    for line in lines:
        tokens = line.split()
        if not tokens:
            continue
        if tokens[0] == "v":
            xyz = [*tokens[1:4], "0", "0", "0"][:3]
            vertices.append((_tinyobj_real(xyz[0]), _tinyobj_real(xyz[1]), _tinyobj_real(xyz[2])))
        elif tokens[0] in {"f", "l", "p"}:
            has_elements = True
            has_polygon = has_polygon or (tokens[0] == "f" and len(tokens) > 3)
    return _Obj(vertices, has_elements, has_polygon)


def _obj_vertices(path: str, description: str) -> Sequence[tuple[float, float, float]]:
    return _read_obj(path, description).vertices


def _vtk_vertices(path: str, description: str) -> Sequence[tuple[float, float, float]]:
    """The POINTS of a legacy ASCII UNSTRUCTURED_GRID, after its cells are checked."""
    try:
        with open(path, encoding="utf-8", errors="replace") as file:
            lines = file.read().splitlines()
    except OSError:
        lines = []
    if len(lines) > 2 and lines[2].strip().upper() != "ASCII":
        return [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]  # not read
    tokens = " ".join(lines[3:]).split()
    if tokens[:2] != ["DATASET", "UNSTRUCTURED_GRID"]:
        tokens = []
    starts = [i for i, token in enumerate(tokens) if token in _VTK_KEYWORDS]

    def numbers(keyword: str) -> list[str]:
        """The tokens after ``keyword`` up to the next keyword."""
        start = next((i for i in starts if tokens[i] == keyword), None)
        if start is None:
            return []
        end = next((i for i in starts if i > start), len(tokens))
        return tokens[start + 1 : end]

    points = [float(x) for x in numbers("POINTS")[2:]]
    cells = [int(x) for x in numbers("CELLS")[2:]]
    types = [int(x) for x in numbers("CELL_TYPES")[1:]]
    # Each cell's number of points: from OFFSETS (VTK 5.1), else the classic
    # layout's "n i₀ … iₙ₋₁" per cell.
    offsets = [int(x) for x in numbers("OFFSETS")[1:]]
    sizes = [b - a for a, b in itertools.pairwise(offsets)]
    while cells and not offsets:
        sizes.append(cells[0])
        cells = cells[cells[0] + 1 :]
    for cell_type, size in zip(types, sizes, strict=False):
        if cell_type != _VTK_TETRA:
            raise RuntimeError(
                "ReadVtkToVolumeMesh(): mesh data should only contain tetrahedra (type "
                f"id={_VTK_TETRA}). Read cell with type id={cell_type}, dimension "
                f"{_VTK_CELL_DIMENSION.get(cell_type, -1)}, and number of points {size} in "
                f"'{description}'."
            )
    if not types:
        raise RuntimeError("A mesh must contain at least one tetrahedron")
    return [(points[i], points[i + 1], points[i + 2]) for i in range(0, len(points) - 2, 3)]


def _gltf_vertices(path: str, description: str) -> Sequence[tuple[float, float, float]]:
    if not (os.path.isfile(path) and os.access(path, os.R_OK)):
        raise RuntimeError(
            f"glTF '{description}', named an inaccessible file: '<the .gltf file itself>'."
        )
    return [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]  # not read


_VERTEX_READERS: dict[str, Callable[[str, str], Sequence[tuple[float, float, float]]]] = {
    ".obj": _obj_vertices,
    ".vtk": _vtk_vertices,
    ".gltf": _gltf_vertices,
}


def _check_plane(vertices: _Vertices, description: str) -> None:
    """Drake's FindNormal: raises unless some three vertices span a plane."""
    offsets = vertices - vertices[0]
    squared = (offsets**2).sum(axis=1)
    far = np.flatnonzero(squared >= _ZERO_SQUARED)
    if far.size == 0:
        raise RuntimeError(
            "MakeConvexHull failed because all vertices in the mesh were within a sphere with "
            f"radius 1e-12 for geometry: {description}."
        )
    first = int(far[0])
    a = offsets[first] / np.sqrt(squared[first])
    rest = offsets[first:]
    normals = np.cross(a, rest)
    spans = (squared[first:] >= _ZERO_SQUARED) & ((normals**2).sum(axis=1) >= _ZERO_SQUARED)
    if not spans.any():
        raise RuntimeError(
            "MakeConvexHull failed because all vertices in the mesh appear to be co-linear for "
            f"file: {description}."
        )


def _engine_refusal(extension: str, path: str, *, is_convex: bool) -> str:
    """What the proximity engine of a release up to 1.27 says of a file type it refuses."""
    shape = "Convex" if is_convex else "Mesh"
    if release.has("proximity-vtk-meshes-since-1.23"):
        if is_convex:
            return (
                "ProximityEngine: Convex shapes only support .obj or .vtk files; got "
                f"({path}) instead."
            )
        return (
            "ProximityEngine: Mesh shapes for non-hydroelastic contact only support .obj or "
            f".vtk files; got ({path}) instead."
        )
    if release.has("engine-extension-wording-since-1.19"):
        return (
            f"ProximityEngine: {shape} shapes for non-hydroelastic contact only support .obj "
            f"files; got ({path}) instead."
        )
    if is_convex:  # up to 1.18 a Convex's file is read as an OBJ, whatever its name
        return (
            "The file parsed contains no objects; only OBJs with a single object are "
            "supported. The file could be corrupt, empty, or not an OBJ file. File name: "
            f"'{path}'"
        )
    return (
        f"ProximityEngine: expect an Obj file for non-hydroelastics but get {extension} file "
        f"({path}) instead."
    )


def _extension_refusal(extension: str, path: str, *, is_convex: bool) -> str | None:
    """Check 1, by release (see the module): the error for a file type refused, or None."""
    if not release.has("convex-hull-meshes-since-1.27"):
        # N.B. Up to 1.22 a .vtk is refused only without a hydroelastic compliance type,
        # which reimpl's SDFormat parser does not record: reimpl takes every .vtk then.
        accepted = {".obj", ".vtk"}
        return (
            None if extension in accepted else _engine_refusal(extension, path, is_convex=is_convex)
        )
    if extension not in _VERTEX_READERS:
        if not release.has("hull-extension-wording-since-1.34"):
            return f"MakeConvexHull only applies to obj, vtk, and gltf meshes; given file: {path}."
        return (
            "MakeConvexHull only applies to .obj, .vtk, and .gltf meshes; unsupported "
            f"extension '{extension}' for geometry data: {path}."
        )
    return None


def _obj_objects(path: str) -> int:
    """How many objects tinyobjloader makes of an OBJ file: its ``o``/``g`` sections that
    hold a face (the faces before any such line are one more)."""
    try:
        with open(path, encoding="utf-8", errors="replace") as file:
            lines = file.read().splitlines()
    except OSError:
        return 0
    objects, faces = 0, False
    for line in lines:
        keyword = line.split()[:1]
        if keyword in (["o"], ["g"]):
            objects, faces = objects + faces, False
        elif keyword == ["f"]:
            faces = True
    return objects + faces


class HullError(RuntimeError):
    """An error of the convex hull step (Drake >= 1.27), not of the proximity engine: in
    1.27 GeometryState makes the hull before it stores the role, so the geometry is left
    without it (hull-before-role-1.27)."""


def check_proximity_mesh(
    path: str,
    extension: str,
    scale3: Sequence[float],
    *,
    is_convex: bool,
    hydroelastic: bool = False,
) -> None:
    """Raises Drake's error where it cannot make the proximity representation (see module).

    Up to 1.26 the engine checks the file type only of a geometry with no hydroelastic
    compliance type (a hydroelastic one gets its own representation, not modelled);
    reimpl's parsers record no compliance type, so ``hydroelastic`` (any property in the
    hydroelastic group) stands for it (measured: drake_models' evo_bowl_compliant.urdf, a
    compliant .vtk Mesh, parses on 1.12.0-1.22.0). Not modelled: up to 1.22 a .vtk of a
    geometry with no compliance type is refused (reimpl takes it)."""
    hull = release.has("convex-hull-meshes-since-1.27")
    if hydroelastic and not hull:
        return
    try:
        _check_hull(path, extension, scale3, is_convex=is_convex)
    except RuntimeError as error:
        if not hull:
            raise
        raise HullError(*error.args) from None
    if hull and extension == ".gltf" and not release.has("gltf-mesh-proximity-since-1.28"):
        raise RuntimeError(_engine_refusal(extension, path, is_convex=is_convex))
    if is_convex or extension != ".obj":
        return
    obj = _read_obj(path, path)
    if not obj.has_elements:
        raise RuntimeError(
            "error: The OBJ data parsed contains no objects; the data could be corrupt, empty, "
            f"or not an OBJ file. Name: '{path}'"
        )
    if not obj.has_polygon:
        raise RuntimeError("A mesh must contain at least one triangle")


def _check_hull(path: str, extension: str, scale3: Sequence[float], *, is_convex: bool) -> None:
    """Checks 1-4 (and the multiple objects of an old release)."""
    refusal = _extension_refusal(extension, path, is_convex=is_convex)
    if refusal is not None:
        raise RuntimeError(refusal)
    if (
        extension == ".obj"
        and release.has("obj-multiple-objects-refused-until-1.31")
        and _obj_objects(path) > 1
    ):
        raise RuntimeError(
            "The OBJ file contains multiple objects; only OBJs with a single object are "
            f"supported: File name: '{path}'"
        )
    read = _VERTEX_READERS[extension](path, path)
    if not release.has("convex-hull-meshes-since-1.27"):
        return  # no hull: checks 3 and 4 are the hull's (measured: a two-vertex .obj on 1.26)
    if len(read) < 3:
        raise RuntimeError(
            "MakeConvexHull() cannot be used on a mesh with fewer than three vertices; found "
            f"{len(read)} vertices in geometry data: {path}."
        )
    _check_plane(np.asarray(read, dtype=float) * np.asarray(scale3, dtype=float), path)
