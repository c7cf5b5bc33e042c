"""An OBJ file as a triangle mesh, read as Drake 1.51.1 reads it with tinyobjloader.

Drake's ReadObjToTriangleSurfaceMesh (and the mesh model parser) read, line by
line after leading spaces and tabs:

* ``v x y z``: a vertex, each coordinate scaled by the scale's axis (a
  coordinate that is missing or no number reads as 0, as tinyobjloader's does);
* ``f i j k ...``: a face of the vertices ``i`` (``i/t``, ``i//n``, ``i/t/n``):
  a positive index counts from 1, a negative one back from the vertices read so
  far. A triangle is kept as is; a quad is split along its shorter diagonal
  ([0, 1, 2] + [0, 2, 3] when ‖v₂ − v₀‖ < ‖v₃ − v₁‖, else [0, 1, 3] + [1, 2, 3]),
  as tinyobjloader triangulates it; a larger polygon is cut into ears by
  tinyobjloader's own clipper (in the two coordinates its first turning corner
  spans most, an ear kept when it turns the polygon's way and holds no other
  vertex; a polygon it cannot finish keeps the ears it cut);
* ``l`` and ``p``: elements without faces;
* ``o name``: the object's name, the text after ``o`` and one space or tab
  (the last one read names the mesh).

With an odd number of negative scale factors each triangle's winding is
reversed. No element at all is ``error: The OBJ data parsed contains no
objects; the data could be corrupt, empty, or not an OBJ file. Name: 'P'``;
elements but no triangle is ``A mesh must contain at least one triangle``.

tinyobjloader's warnings are kept, in its order, as one text ``Warning while
parsing OBJ 'P' : ...``: ``Degenerated face found\\n.`` for each face of fewer
than three vertices (skipped), given when its group ends (at a ``g`` or ``o``
line, or after the end's), and at the end ``Vertex normal indices out of
bounds (line N.)\\n\\n`` and the same for ``texcoord`` when a face names a
``vn`` or ``vt`` that is not there (N the file's number of lines).

Not modelled (a reimpl error): an index of 0, or a vertex index that names no
vertex (tinyobjloader warns, and Drake then fails in ways reimpl does not
reproduce).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, field

from reimpl.multibody.parsing._diagnostics import ModelParseError

__all__ = ["ObjMesh", "read_obj_mesh", "tinyobj_real"]

#: A line: leading blanks, its keyword, one space or tab, the rest.
_KEYWORD = re.compile(r"[ \t]*([^ \t]*)[ \t](.*)", re.DOTALL)
#: tinyobjloader's epsilon (double precision).
_EPSILON = 2.220446049250313e-16
_LEADING_INTEGER = re.compile(r"[ \t\n\v\f\r]*([+-]?[0-9]+)")

Vertex = tuple[float, float, float]
Triangle = tuple[int, int, int]


@dataclass(frozen=True)
class ObjMesh:
    """The scaled vertices and the triangles of an OBJ file, and its object name."""

    vertices: list[Vertex]
    triangles: list[Triangle]
    name: str
    #: tinyobjloader's warning (``Warning while parsing OBJ 'P' : ...``), or ""
    warning: str = ""


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


def _fix_index(number: int, count: int) -> int:
    """tinyobjloader's fixIndex: 0-based from 1-based, or back from ``count`` if negative."""
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


def _point_in_triangle(vx: list[float], vy: list[float], tx: float, ty: float) -> bool:
    """tinyobjloader's pnpoly for a triangle (an even-odd crossing test)."""
    inside = False
    j = 2
    for i in range(3):
        if (vy[i] > ty) != (vy[j] > ty) and tx < (vx[j] - vx[i]) * (ty - vy[i]) / (
            vy[j] - vy[i]
        ) + vx[i]:
            inside = not inside
        j = i
    return inside


def _axes(vertices: list[Vertex], face: list[int]) -> tuple[int, int]:
    """The two coordinates the ear clipper works in: from the first corner that turns."""
    n = len(face)
    for k in range(n):
        v0, v1, v2 = (vertices[face[(k + m) % n]] for m in range(3))
        e0 = [v1[a] - v0[a] for a in range(3)]
        e1 = [v2[a] - v1[a] for a in range(3)]
        cx = abs(e0[1] * e1[2] - e0[2] * e1[1])
        cy = abs(e0[2] * e1[0] - e0[0] * e1[2])
        cz = abs(e0[0] * e1[1] - e0[1] * e1[0])
        if cx > _EPSILON or cy > _EPSILON or cz > _EPSILON:
            if cx > cy and cx > cz:
                return 1, 2
            return (0, 1) if cz > cx and cz > cy else (0, 2)
    return 1, 2


def _clip_ears(vertices: list[Vertex], face: list[int]) -> list[Triangle]:
    """tinyobjloader's built-in ear clipping of a polygon of more than four vertices."""
    first, second = _axes(vertices, face)
    remaining = list(face)
    triangles: list[Triangle] = []
    guess = 0
    iterations = previous = len(remaining)
    while len(remaining) > 3 and iterations > 0:
        n = len(remaining)
        if guess >= n:
            guess -= n
        if previous != n:
            previous, iterations = n, n
        else:
            iterations -= 1
        ear = [remaining[(guess + k) % n] for k in range(3)]
        vx = [vertices[i][first] for i in ear]
        vy = [vertices[i][second] for i in ear]
        cross = (vx[1] - vx[0]) * (vy[2] - vy[1]) - (vy[1] - vy[0]) * (vx[2] - vx[1])
        area = (vx[0] * vy[1] - vy[0] * vx[1]) * 0.5
        if cross * area < 0.0 or any(
            _point_in_triangle(vx, vy, vertices[i][first], vertices[i][second])
            for i in (remaining[(guess + k) % n] for k in range(3, n))
        ):
            guess += 1
            continue
        triangles.append((ear[0], ear[1], ear[2]))
        del remaining[(guess + 1) % n]
    if len(remaining) == 3:
        triangles.append((remaining[0], remaining[1], remaining[2]))
    return triangles


def _triangles(vertices: list[Vertex], face: list[int]) -> list[Triangle]:
    if len(face) == 3:
        return [(face[0], face[1], face[2])]
    if len(face) == 4:
        return _split_quad(vertices, face)
    return _clip_ears(vertices, face)


@dataclass
class _Reader:
    """tinyobjloader's LoadObj over the lines of one file (the parts Drake's mesh needs)."""

    path: str
    raw: list[Vertex] = field(default_factory=list)
    faces: list[list[int]] = field(default_factory=list)
    counts: dict[str, int] = field(default_factory=lambda: {"vt": 0, "vn": 0})
    #: the largest texture-coordinate and normal index used (0-based), as tinyobjloader's
    greatest: dict[str, int] = field(default_factory=lambda: {"vt": -1, "vn": -1})
    has_elements: bool = False
    name: str = ""
    #: tinyobjloader's warnings, and the degenerate faces of the group being read
    warnings: str = ""
    degenerate: int = 0

    def vertex(self, rest: str, number: int) -> None:
        xyz = [*rest.split()[:3], "", "", ""][:3]
        self.raw.append((tinyobj_real(xyz[0]), tinyobj_real(xyz[1]), tinyobj_real(xyz[2])))

    def _corner(self, token: str, number: int) -> int:
        """One ``v[/vt][/vn]`` of a face: its vertex index (its others only tracked)."""
        parts = token.split("/")
        first = _atoi(parts[0])
        index = _fix_index(first, len(self.raw))
        if first == 0 or index < 0:
            raise _refuse(self.path, number, "a vertex index that names no vertex")
        for kind, part in zip(("vt", "vn"), parts[1:3], strict=False):
            if part:
                value = _atoi(part)
                if value == 0:
                    raise _refuse(self.path, number, f"a {kind} index of 0")
                fixed = _fix_index(value, self.counts[kind])
                self.greatest[kind] = max(self.greatest[kind], fixed)
        return index

    def face(self, rest: str, number: int) -> None:
        tokens = rest.split()
        corners = [self._corner(t, number) for t in tokens]
        if len(corners) < 3:
            self.degenerate += 1
            return
        self.faces.append(corners)
        self.has_elements = True

    def element(self, rest: str, number: int) -> None:
        self.has_elements = True

    def _flush(self) -> None:
        """exportGroupsToShape: the warnings about the group's degenerate faces."""
        self.warnings += "Degenerated face found\n." * self.degenerate
        self.degenerate = 0

    def group(self, rest: str, number: int) -> None:
        self._flush()

    def object(self, rest: str, number: int) -> None:
        self._flush()
        self.name = rest

    def texcoord(self, rest: str, number: int) -> None:
        self.counts["vt"] += 1

    def normal(self, rest: str, number: int) -> None:
        self.counts["vn"] += 1

    def finish(self, lines: int) -> None:
        """The end of the file: the index warnings, then the last group's."""
        for kind, what in (("vn", "Vertex normal"), ("vt", "Vertex texcoord")):
            if self.greatest[kind] >= self.counts[kind]:
                self.warnings += f"{what} indices out of bounds (line {lines}.)\n\n"
        self._flush()
        if any(index >= len(self.raw) for face in self.faces for index in face):
            raise ModelParseError(
                "reimpl does not read OBJ faces with a vertex index that names no vertex "
                f"('{self.path}')"
            )


#: A line's keyword (followed by a space or tab) -> what reads it.
_LINE_READERS: dict[str, Callable[[_Reader, str, int], None]] = {
    "v": _Reader.vertex,
    "vt": _Reader.texcoord,
    "vn": _Reader.normal,
    "f": _Reader.face,
    "l": _Reader.element,
    "p": _Reader.element,
    "g": _Reader.group,
    "o": _Reader.object,
}


def read_obj_mesh(path: str, scale: tuple[float, float, float], hint: str) -> ObjMesh:
    """The triangle mesh of the OBJ file at ``path`` (``hint`` names it in messages)."""
    try:
        with open(path, encoding="utf-8", errors="replace", newline="") as stream:
            lines = stream.read().split("\n")
    except OSError:
        raise RuntimeError(f"MemoryFile::Make() cannot read the file '{hint}'.") from None
    reader = _Reader(path)
    for number, line in enumerate(lines, 1):
        match = _KEYWORD.match(line.rstrip("\r"))
        read = _LINE_READERS.get(match.group(1)) if match else None
        if match is not None and read is not None:
            read(reader, match.group(2), number)
    reader.finish(len(lines) - (1 if lines and lines[-1] == "" else 0))
    if not reader.has_elements:
        raise ModelParseError(
            "error: The OBJ data parsed contains no objects; the data could be corrupt, empty, "
            f"or not an OBJ file. Name: '{hint}'"
        )
    sx, sy, sz = scale
    vertices = [(x * sx, y * sy, z * sz) for x, y, z in reader.raw]
    triangles = [t for face in reader.faces for t in _triangles(reader.raw, face)]
    if sum(s < 0 for s in scale) % 2 == 1:
        triangles = [(c, b, a) for a, b, c in triangles]
    if not triangles:
        raise RuntimeError("A mesh must contain at least one triangle")
    warning = f"Warning while parsing OBJ '{hint}' : {reader.warnings}" if reader.warnings else ""
    return ObjMesh(vertices, triangles, reader.name, warning)
