"""URDF ``<material>``: the robot's named materials and what a visual uses (Drake 1.51.1).

Drake reads every ``<material>`` child of ``<robot>`` first (their names are
required), then each visual's ``<material>`` (name optional), all into one map
from name to (rgba, diffuse map). A material reads, in this order (errors at
the material's line unless said otherwise):

1. a robot material without a name (or ``name=""``): ``Material tag is missing
   a required name``;
2. a ``<drake:diffuse_map>`` child: an error (it is SDFormat's tag);
3. ``<texture filename>``: resolved like any URI (its errors at the texture's
   line); ``<color rgba>``: four numbers (``<color>`` without ``rgba`` is the
   error ``Failed to parse 'rgba' attribute of <color>}``, brace included);
4. a named material with neither, whose name is not in the map yet:
   ``Material 'x' not previously defined, but has no color or texture
   information.`` -- a visual may use a robot material before its line, but
   not one that only a later visual defines;
5. a named material whose name is in the map: on ``<robot>`` always an error;
   in a visual an error when its diffuse map differs from the one stored
   (giving none is no difference) or when it gives a colour that the stored
   one lacks or that is farther than 1e-10 from it. The message is Drake's,
   three lines::

       Material 'brown' was previously defined.
         - existing definition: RGBA: 0.93333333333 ... 1, Diffuse map: None
         - new definition:      RGBA: ..., Diffuse map: None

   Up to 1.51 an RGBA prints as Eigen prints a row vector with 16 significant
   digits, each number right-aligned to the widest, without brackets; since
   1.52 as fmt writes a column vector, ``[0.93333333333, 0.2, 0.2, 1]ᵀ``
   (release fact eigen-vector-wording-since-1.52; measured with Drake's
   duplicate_materials.urdf and conflicting_materials.urdf on 1.51.1, 1.52.0
   and 1.58.0). A new name is stored, a missing colour as transparent black
   (0 0 0 0).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from reimpl._release import release
from reimpl.geometry._drake_text import eigen_row, eigen_vector
from reimpl.multibody.parsing._diagnostics import Diagnostics
from reimpl.multibody.parsing._urdf_values import vector
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = ["Material", "MaterialMap"]

_DIFFUSE_MAP_URL = (
    "https://drake.mit.edu/doxygen_cxx/group__multibody__parsing.html#tag_drake_diffuse_map"
)
#: Colours this close (Euclidean norm of the difference) are the same colour.
_SAME_COLOUR = 1e-10


@dataclass(frozen=True)
class Material:
    """A colour and a diffuse map (texture path), either possibly absent."""

    rgba: tuple[float, ...] | None = None
    diffuse_map: str | None = None

    def describe(self) -> str:
        rgba = "RGBA: None" if self.rgba is None else f"RGBA: {_rgba_text(self.rgba)}"
        diffuse = "None" if self.diffuse_map is None else self.diffuse_map
        return f"{rgba}, Diffuse map: {diffuse}"

    def conflicts_with(self, stored: Material) -> bool:
        """Whether redefining ``stored`` as this, in a visual, is an error (rule 5)."""
        if self.diffuse_map is not None and self.diffuse_map != stored.diffuse_map:
            return True
        if self.rgba is None:
            return False
        if stored.rgba is None:
            return True
        return math.dist(self.rgba, stored.rgba) > _SAME_COLOUR


def _rgba_text(values: tuple[float, ...]) -> str:
    """Since 1.52 fmt's column vector (``eigen_vector``); up to 1.51 Eigen's
    ``operator<<`` of a row, without eigen_row's brackets; up to 1.13 that row at a C++
    stream's default 6 significant digits (urdf-material-rgba-digits-since-1.14:
    ``0.933333 0.796078 0.678431        1``, measured on 1.12.0, 1.13.0 and 1.14.0)."""
    if release.has("eigen-vector-wording-since-1.52"):
        return eigen_vector(values)
    if not release.has("urdf-material-rgba-digits-since-1.14"):
        cells = [f"{v:.6g}" for v in values]
        width = max(len(c) for c in cells)
        return " ".join(c.rjust(width) for c in cells)
    return eigen_row(values)[1:-1]


class MaterialMap:
    """The named materials of one robot."""

    def __init__(self, diagnostics: Diagnostics, resolve: Callable[[str, int], str]) -> None:
        self.diagnostics = diagnostics
        self.resolve = resolve
        self.materials: dict[str, Material] = {}

    def read(self, element: XmlElement, name_required: bool) -> Material:
        """Reads a ``<material>`` (of the robot when ``name_required``); returns what it gives."""
        d = self.diagnostics
        name = element.get("name", "")
        if not name and name_required:
            raise d.error("Material tag is missing a required name", element.line)
        if children(element, "drake:diffuse_map"):
            raise d.error(
                f"<drake:diffuse_map> is not supported in URDF. See {_DIFFUSE_MAP_URL} for more "
                "details.",
                element.line,
            )
        texture = self._texture(element)
        material = Material(self._rgba(element), texture)
        if material == Material() and name and name not in self.materials:
            raise d.error(
                f"Material '{name}' not previously defined, but has no color or texture "
                "information.",
                element.line,
            )
        if not name:
            return material
        return self._add(name, material, name_required, element.line)

    def _texture(self, element: XmlElement) -> str | None:
        textures = children(element, "texture")
        if not textures:
            return None
        filename = textures[0].get("filename", "")
        return self.resolve(filename, textures[0].line) if filename else None

    def _rgba(self, element: XmlElement) -> tuple[float, ...] | None:
        colors = children(element, "color")
        if not colors:
            return None
        rgba = vector(colors[0], "rgba", 4)
        if rgba is None:
            raise self.diagnostics.error(
                "Failed to parse 'rgba' attribute of <color>}", colors[0].line
            )
        return tuple(rgba)

    def _add(self, name: str, material: Material, always_clash: bool, line: int) -> Material:
        stored = self.materials.get(name)
        if stored is None:
            rgba = material.rgba if material.rgba is not None else (0.0, 0.0, 0.0, 0.0)
            self.materials[name] = Material(rgba, material.diffuse_map)
            return self.materials[name]
        if always_clash or material.conflicts_with(stored):
            raise self.diagnostics.error(
                f"Material '{name}' was previously defined.\n"
                f"  - existing definition: {stored.describe()}\n"
                f"  - new definition:      {material.describe()}",
                line,
            )
        return stored
