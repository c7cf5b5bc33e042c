"""An OBJ file as a triangle mesh, read as Drake 1.51.1 reads it with tinyobjloader.

Drake's ReadObjToTriangleSurfaceMesh (and the mesh model parser) read, line by
line after leading spaces and tabs:

* ``v x y z``: a vertex, each coordinate scaled by the scale's axis (a
  coordinate that is missing or no number reads as 0, as tinyobjloader's does);
* ``f i j k ...``: a face of the vertices ``i`` (``i/t``, ``i//n``, ``i/t/n``):
  a positive index counts from 1, a negative one back from the vertices read so
  far. A triangle is kept as is; a quad is split along its shorter diagonal
  ([0, 1, 2] + [0, 2, 3] when ‖v₂ − v₀‖ < ‖v₃ − v₁‖, else [0, 1, 3] + [1, 2, 3]),
  as tinyobjloader triangulates it; a larger polygon is split as a fan from its
  first vertex (tinyobjloader clips ears: the same triangles' union for a convex
  face, whose volume terms agree up to rounding);
* ``l`` and ``p``: elements without faces;
* ``o name``: the object's name, the text after ``o`` and one space or tab
  (the last one read names the mesh).

With an odd number of negative scale factors each triangle's winding is
reversed. No element at all is ``error: The OBJ data parsed contains no
objects; the data could be corrupt, empty, or not an OBJ file. Name: 'P'``;
elements but no triangle is ``A mesh must contain at least one triangle``.

Not modelled (a reimpl error): a face with fewer than three vertices, an index
of 0 or one that names no vertex (tinyobjloader warns, skips or fails; Drake
then fails in ways reimpl does not reproduce).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from reimpl.multibody.parsing._diagnostics import ModelParseError

__all__ = ["ObjMesh", "read_obj_mesh", "tinyobj_real"]

_LEADING_INTEGER = re.compile(r"[ \t\n\v\f\r]*([+-]?[0-9]+)")

Vertex = tuple[float, float, float]
Triangle = tuple[int, int, int]


@dataclass(frozen=True)
class ObjMesh:
    """The scaled vertices and the triangles of an OBJ file, and its object name."""

    vertices: list[Vertex]
    triangles: list[Triangle]
    name: str


def tinyobj_real(text: str) -> float:
    """tinyobjloader's parseReal: a number, or 0 where the text is not one."""
    try:
        return float(text)
    except ValueError:
        return 0.0


def _refuse(path: str, line_number: int, problem: str) -> ModelParseError:
    return ModelParseError(
        f"reimpl does not read OBJ faces with {problem} ('{path}', line {line_number})"
    )


def _atoi(token: str) -> int:
    """C's atoi: the leading integer (after blanks), 0 where there is none."""
    match = _LEADING_INTEGER.match(token)
    return int(match.group(1)) if match else 0


def _vertex_index(token: str, count: int, path: str, line_number: int) -> int:
    """tinyobjloader's fixIndex of ``atoi(token)``, 0-based (a bad index is refused).

    A negative index counts back from the ``count`` vertices read so far; a
    positive one is checked against all the file's vertices once they are read.
    """
    number = _atoi(token)
    if number == 0 or count + number < 0:
        raise _refuse(path, line_number, "a vertex index that names no vertex")
    return number - 1 if number > 0 else count + number


def _split_quad(vertices: list[Vertex], face: list[int]) -> list[Triangle]:
    """tinyobjloader's quad: along the shorter diagonal."""
    v0, v1, v2, v3 = (vertices[i] for i in face)
    e02 = [v2[k] - v0[k] for k in range(3)]
    e13 = [v3[k] - v1[k] for k in range(3)]
    sqr02 = e02[0] * e02[0] + e02[1] * e02[1] + e02[2] * e02[2]
    sqr13 = e13[0] * e13[0] + e13[1] * e13[1] + e13[2] * e13[2]
    a, b, c, d = face
    if sqr02 < sqr13:
        return [(a, b, c), (a, c, d)]
    return [(a, b, d), (b, c, d)]


def _triangles(vertices: list[Vertex], face: list[int]) -> list[Triangle]:
    if len(face) == 3:
        return [(face[0], face[1], face[2])]
    if len(face) == 4:
        return _split_quad(vertices, face)
    return [(face[0], face[i], face[i + 1]) for i in range(1, len(face) - 1)]


def read_obj_mesh(path: str, scale: tuple[float, float, float], hint: str) -> ObjMesh:
    """The triangle mesh of the OBJ file at ``path`` (``hint`` names it in messages)."""
    try:
        with open(path, encoding="utf-8", errors="replace", newline="") as stream:
            text = stream.read()
    except OSError:
        raise RuntimeError(f"MemoryFile::Make() cannot read the file '{hint}'.") from None
    raw: list[Vertex] = []
    faces: list[list[int]] = []
    has_elements = False
    name = ""
    for number, line in enumerate(text.split("\n"), 1):
        token = line.rstrip("\r").lstrip(" \t")
        kind, rest = token[:1], token[2:]
        if len(token) < 2 or token[1] not in " \t":
            continue
        if kind == "v":
            xyz = [*rest.split()[:3], "", "", ""][:3]
            raw.append((tinyobj_real(xyz[0]), tinyobj_real(xyz[1]), tinyobj_real(xyz[2])))
        elif kind == "f":
            tokens = rest.split()
            if len(tokens) < 3:
                raise _refuse(path, number, "fewer than three vertices")
            faces.append([_vertex_index(t, len(raw), path, number) for t in tokens])
            has_elements = True
        elif kind in ("l", "p"):
            has_elements = True
        elif kind == "o":
            name = rest
    if any(index >= len(raw) for face in faces for index in face):
        raise ModelParseError(
            f"reimpl does not read OBJ faces with a vertex index that names no vertex ('{path}')"
        )
    if not has_elements:
        raise ModelParseError(
            "error: The OBJ data parsed contains no objects; the data could be corrupt, empty, "
            f"or not an OBJ file. Name: '{hint}'"
        )
    sx, sy, sz = scale
    vertices = [(x * sx, y * sy, z * sz) for x, y, z in raw]
    triangles = [t for face in faces for t in _triangles(raw, face)]
    if sum(s < 0 for s in scale) % 2 == 1:
        triangles = [(c, b, a) for a, b, c in triangles]
    if not triangles:
        raise RuntimeError("A mesh must contain at least one triangle")
    return ObjMesh(vertices, triangles, name)
