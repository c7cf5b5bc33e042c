"""SDFormat checks made before Drake sees a model (libsdformat's, as Drake 1.51.1 reports them).

libsdformat reads the whole document first; its errors name the text
``<data-string>`` (a file by its path) and an XML path, e.g.::

    <data-string>:4: error: At XML path /sdf/model[@name="m"]/link: Required
    attribute[name] in element[link] is not specified in SDF.

(one line). Checked here, per element, in document order:

* the root is ``<sdf version=...>``, holding exactly one ``<model>`` or ``<world>``;
* ``name`` on model, link, joint, collision, visual, frame; ``type`` on joint;
  ``<parent>`` and ``<child>`` in a joint; ``<uri>`` in an include;
* an unprefixed child that SDFormat does not define (under sdf, world, model,
  link) is an error, ending in a newline (Drake turns the warning into one);
* the names of a model's children (links, joints, frames, models, groups) are
  unique, and so are a link's collision names and its visual names;
* no model, link, joint or frame name holds ``::``; the message then shows the
  element as libsdformat prints it (``element_text``).
"""

from __future__ import annotations

from collections import Counter

from reimpl.multibody.parsing._diagnostics import Diagnostics, ModelParseError
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = ["check_document", "element_text", "scoped_name_error", "xml_path"]

#: element -> the unprefixed children SDFormat 1.9+ defines
_DEFINED: dict[str, frozenset[str]] = {
    "sdf": frozenset(("model", "world", "light", "actor")),
    "world": frozenset((
        "audio", "wind", "include", "gravity", "magnetic_field", "atmosphere", "gui", "physics",
        "scene", "light", "frame", "model", "actor", "plugin", "road", "spherical_coordinates",
        "state", "population", "joint",
    )),
    "model": frozenset((
        "static", "self_collide", "allow_auto_disable", "include", "model", "enable_wind",
        "frame", "pose", "link", "joint", "plugin", "gripper",
    )),
    "link": frozenset((
        "gravity", "enable_wind", "self_collide", "kinematic", "must_be_base_link",
        "velocity_decay", "pose", "inertial", "collision", "visual", "sensor", "projector",
        "audio_sink", "audio_source", "battery", "light", "particle_emitter",
    )),
}  # fmt: skip
_NAMED = frozenset({"model", "link", "joint", "collision", "visual", "frame"})
_UNSCOPED = frozenset({"model", "link", "joint", "frame"})


def element_text(element: XmlElement, indent: str = "") -> str:
    """libsdformat's printout: 2-space indents, single-quoted attributes, a final newline."""
    attributes = "".join(f" {k}='{v}'" for k, v in element.attrib.items())
    head = f"{indent}<{element.tag}{attributes}"
    if len(element):
        body = "".join(element_text(child, indent + "  ") for child in element)  # type: ignore[arg-type]
        return f"{head}>\n{body}{indent}</{element.tag}>\n"
    text = (element.text or "").strip()
    return f"{head}>{text}</{element.tag}>\n" if text else f"{head}/>\n"


def scoped_name_error(element: XmlElement) -> ModelParseError:
    return Diagnostics(None).error(
        f"Error: Detected delimiter '::' in element name in{element_text(element)}"
    )


def xml_path(element: XmlElement, parents: list[XmlElement]) -> str:
    """libsdformat's path of ``element``: ``/sdf/model[@name="m"]/link``."""
    parts = []
    for e in [*parents, element]:
        name = e.get("name")
        parts.append(e.tag if name is None else f'{e.tag}[@name="{name}"]')
    return "/" + "/".join(parts)


class _Checker:
    def __init__(self, label: str) -> None:
        self.label = label

    def error(
        self, element: XmlElement, parents: list[XmlElement], message: str
    ) -> ModelParseError:
        path = xml_path(element, parents)
        return ModelParseError(f"{self.label}:{element.line}: error: At XML path {path}: {message}")

    def check(self, element: XmlElement, parents: list[XmlElement]) -> None:
        tag = element.tag
        if tag in _NAMED and element.get("name") is None:
            raise self.error(
                element,
                parents,
                f"Required attribute[name] in element[{tag}] is not specified in SDF.",
            )
        if tag in _UNSCOPED and "::" in element.get("name", ""):
            raise scoped_name_error(element)
        if tag == "joint":
            self._check_joint(element, parents)
        if tag == "include":
            self._check_include(element, parents)
        for child in element:
            assert isinstance(child, XmlElement)
            defined = _DEFINED.get(tag)
            if defined is not None and ":" not in child.tag and child.tag not in defined:
                raise self.error(
                    child,
                    [*parents, element],
                    f"XML Element[{child.tag}], child of element[{tag}], not defined in SDF. "
                    f"Copying[{child.tag}] as children of [{tag}].\n",
                )
            self.check(child, [*parents, element])
        if tag in ("model", "world"):
            self._check_unique_names(element)
        if tag == "link":
            self._check_unique_geometry(element)

    def _check_joint(self, joint: XmlElement, parents: list[XmlElement]) -> None:
        if joint.get("type") is None:
            raise self.error(
                joint,
                parents,
                "Required attribute[type] in element[joint] is not specified in SDF.",
            )
        for end in ("parent", "child"):
            if not children(joint, end):
                raise ModelParseError(
                    f"{self.label}:{joint.line}: error: At XML path "
                    f"{xml_path(joint, parents)}/{end}: XML Missing required element[{end}], "
                    "child of element[joint]"
                )

    def _check_include(self, include: XmlElement, parents: list[XmlElement]) -> None:
        if not children(include, "uri"):
            index = [e for e in parents[-1] if e.tag == "include"].index(include)
            path = xml_path(parents[-1], parents[:-1])
            raise ModelParseError(
                f"{self.label}:{include.line}: error: At XML path {path}/include[{index}]: "
                "<include> element missing 'uri' attribute"
            )

    def _check_unique_names(self, element: XmlElement) -> None:
        names = Counter(
            c.get("name") for c in element if c.get("name") is not None and c.tag != "include"
        )
        for name, count in names.items():
            if count > 1:
                raise Diagnostics(None).error(
                    f"Non-unique name[{name}] detected {count} times in XML children of "
                    f"{element.tag} with name[{element.get('name')}]."
                )

    def _check_unique_geometry(self, link: XmlElement) -> None:
        for role in ("collision", "visual"):
            seen: set[str] = set()
            for geometry in children(link, role):
                name = geometry.get("name", "")
                if name in seen:
                    raise Diagnostics(None).error(f"{role} with name[{name}] already exists.")
                seen.add(name)


def check_document(root: XmlElement, label: str) -> None:
    """Raises libsdformat's first error about the document under ``root`` (an ``<sdf>``)."""
    _Checker(label).check(root, [])
