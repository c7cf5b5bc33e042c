"""What the readers of one MuJoCo document share: plant, model instance, settings, messages.

Drake's MuJoCo parser names its source in messages as ``TinyXml2Diagnostic``
does with its default extension: a file by ``std::filesystem::absolute`` of its
name, model text as ``<literal-string>.urdf`` (sic, measured on pydrake 1.51.1
and 1.58.0). The line is the element's; an element copied in by ``<include>``
has line 0 (tinyxml2's DeepClone keeps no line numbers).

Two messages name documented MuJoCo content that Drake ignores::

    The tag 'T' found as a child of 'E' is currently unsupported and will be ignored.
    The attribute 'A' found in a 'E' tag is currently unsupported and will be ignored.

the first at the (first) child's line, the second at the element's.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from enum import Enum
from typing import Any

from reimpl._release import release
from reimpl.multibody.parsing._diagnostics import Diagnostics, ModelParseError
from reimpl.multibody.parsing._parse_context import ParseContext
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = ["Compiler", "InertiaFromGeom", "MjcfContext", "MjcfDiagnostics", "unsupported"]

#: The axes of ``euler=`` angles when no ``<compiler eulerseq>`` sets them: MuJoCo's
#: intrinsic ``xyz`` since 1.25; up to 1.24 Drake reads euler as roll-pitch-yaw, which is
#: extrinsic ``XYZ`` (mjcf-eulerseq-since-1.25: measured on pydrake 1.12.0, 1.22.0-1.24.0
#: vs 1.25.0, 1.26.0 with euler="5.73 11.46 17.19").
_DEFAULT_EULERSEQ = "xyz" if release.has("mjcf-eulerseq-since-1.25") else "XYZ"


@dataclass(frozen=True)
class MjcfDiagnostics:
    """Errors and warnings about one MuJoCo document, at an element's line."""

    diagnostics: Diagnostics

    def error(self, element: XmlElement, message: str) -> ModelParseError:
        """The exception to raise: ``raise d.error(element, ...)``."""
        return self.diagnostics.error(message, element.line)

    def warning(self, element: XmlElement, message: str) -> None:
        self.diagnostics.warning(message, element.line)

    def warn_unsupported_elements(self, element: XmlElement, tags: Iterable[str]) -> None:
        """TinyXml2Diagnostic::WarnUnsupportedElement for each of ``tags``, in order."""
        for tag in tags:
            found = children(element, tag)
            if found:
                self.warning(
                    found[0],
                    f"The tag '{tag}' found as a child of '{element.tag}' is currently "
                    "unsupported and will be ignored.",
                )

    def warn_unsupported_attributes(self, element: XmlElement, attributes: Iterable[str]) -> None:
        """TinyXml2Diagnostic::WarnUnsupportedAttribute for each of ``attributes``, in order."""
        for attribute in attributes:
            if element.get(attribute) is not None:
                self.warning(
                    element,
                    f"The attribute '{attribute}' found in a '{element.tag}' tag is currently "
                    "unsupported and will be ignored.",
                )


def unsupported(element: XmlElement, what: str) -> ModelParseError:
    """reimpl's own refusal of content Drake reads but reimpl leaves out of its subset."""
    return ModelParseError(
        f"reimpl does not read {what} (MuJoCo <{element.tag}> at line {element.line})"
    )


class InertiaFromGeom(Enum):
    """The compiler's ``inertiafromgeom``: false, true, or auto (the default)."""

    FALSE = "false"
    TRUE = "true"
    AUTO = "auto"


@dataclass
class Compiler:
    """The ``<compiler>`` settings Drake reads (defaults: MuJoCo's, as Drake keeps them)."""

    autolimits: bool = True
    degrees: bool = True
    meshdir: str | None = None
    eulerseq: str = _DEFAULT_EULERSEQ
    inertia_from_geom: InertiaFromGeom = InertiaFromGeom.AUTO


@dataclass
class MjcfContext:
    """One MuJoCo document being read into ``instance`` of the parse's plant."""

    parse: ParseContext
    d: MjcfDiagnostics
    #: where relative mesh files and includes start: the file's folder, else the working folder
    main_dir: str
    instance: Any = None
    compiler: Compiler = field(default_factory=Compiler)
    #: (element name, class) -> the ``<default>`` child holding that class's attributes
    defaults: dict[tuple[str, str], XmlElement] = field(default_factory=dict)
    materials: dict[str, XmlElement] = field(default_factory=dict)
    #: mesh asset name -> (absolute file, scale)
    meshes: dict[str, tuple[str, tuple[float, float, float]]] = field(default_factory=dict)
    #: mesh asset name -> (volume, centroid) of unit density, once computed
    mesh_inertia: dict[str, tuple[float, tuple[float, float, float]]] = field(default_factory=dict)
    #: joint index -> its ``armature`` (read for the actuators)
    armature: dict[int, float] = field(default_factory=dict)
    num_cameras: int = 0

    @property
    def plant(self) -> Any:
        return self.parse.plant
