"""libsdformat's reading of a document, before any DOM object is made (Drake 1.51.1).

libsdformat reads the XML element by element (``readXml``), expanding each
``<include>`` where it stands, and reports what it cannot read with the text's
name (``<data-string>`` for a string, ``/`` + the path for a file) and an XML
path, e.g. (one line)::

    <data-string>:4: error: At XML path /sdf/model[@name="m"]/link: Required
    attribute[name] in element[link] is not specified in SDF.

Per element, in this order (the elements and attributes of _sdf_schema):

1. its attributes in document order: a name with ``:`` is kept as is; an
   undefined one is an error (at ``path[@attr="value"]``); a bad boolean
   (``degrees``, ``merge``) is ``Unable to read attribute[...]``; then a
   missing required attribute;
2. its value: a ``<pose>`` text, or a boolean (``<static>``) that does not
   read is ``Error reading element <pose>`` (libsdformat also logs why);
3. its children in document order: an ``<include>`` is expanded through the
   caller's hook (_sdf_include); an unprefixed child that SDFormat does not
   define is an error (its message ends with a newline);
4. a joint (other than ``ball``) without ``<parent>`` or ``<child>``.

After the whole document (version 1.8 and later): no name holds ``::``.
Versions before 1.7 are converted first: ``<pose frame=...>`` becomes
``relative_to`` (an empty ``frame`` is dropped), and ``<use_parent_model_frame>``
(true by default before 1.5) becomes ``<xyz expressed_in="__model__">``.
"""

from __future__ import annotations

import logging
import math
import re
import sys
from collections.abc import Callable

import numpy as np

from reimpl.multibody.parsing._diagnostics import Diagnostics, ModelParseError
from reimpl.multibody.parsing._sdf_poses import PoseTextError, parse_pose
from reimpl.multibody.parsing._sdf_schema import description
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = [
    "IncludeHook",
    "check_document",
    "element_text",
    "log_sdformat_error",
    "material_color",
    "scoped_name_error",
    "sdformat_bool",
    "version_tuple",
    "xml_path",
]

#: Expands one ``<include>``: (include, its parent, its XML path, the including text's name)
#: -> the elements that stand in its place.
IncludeHook = Callable[[XmlElement, XmlElement, str, str], list[XmlElement]]

_BOOLS = {"true": True, "1": True, "false": False, "0": False}
#: (element, parent) -> the element's value is an SDFormat bool
_BOOL_VALUES = {
    ("static", "model"), ("self_collide", "model"), ("allow_auto_disable", "model"),
    ("enable_wind", "model"), ("static", "include"), ("self_collide", "link"),
    ("kinematic", "link"), ("gravity", "link"), ("must_be_base_link", "link"),
    ("enable_wind", "link"),
}  # fmt: skip
_COLORS = frozenset({"diffuse", "ambient", "specular", "emissive"})
_BOOL_ATTRIBUTES = {("pose", "degrees"), ("include", "merge"), ("inertial", "auto")}
_UNSCOPED_SINCE = (1, 8)


def sdformat_bool(text: str) -> bool | None:
    """SDFormat's bool: ``true``/``1`` or ``false``/``0``, trimmed, any case; else None."""
    return _BOOLS.get(text.strip().lower())


_STOF = re.compile(
    r"\s*[+-]?(?:(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|inf(?:inity)?|nan)", re.IGNORECASE
)
_FLOAT_MAX = float(np.finfo(np.float32).max)


def _stof(token: str) -> float:
    """std::stof: the longest leading number; ValueError (invalid) or OverflowError."""
    match = _STOF.match(token)
    if match is None:
        raise ValueError(token)
    value = float(match.group())
    if abs(value) > _FLOAT_MAX and abs(value) != float("inf"):
        raise OverflowError(token)
    return float(np.float32(value))


def parse_color(
    text: str, key: str, *, report_clamp: bool = False
) -> tuple[tuple[float, float, float, float] | None, str]:
    """ParseColorUsingStringStream: (color, "") or (None, libsdformat's errors joined as
    pydrake logs them). 3 or 4 floats each in [0, 1] (NaN allowed: gz::math::Color clamps it
    to 0, printing so to stderr where ``report_clamp``); alpha 1 by default. No text is the
    default, "0 0 0 1" (libsdformat reads no value then)."""
    value = text.strip()
    if not value:
        return (0.0, 0.0, 0.0, 1.0), ""
    if value.lower() in ("true", "false"):
        value = "1" if value.lower() == "true" else "0"
    errors = []
    colors: list[float] = []
    valid = True
    for token in value.split():
        try:
            c = _stof(token)
        except ValueError:
            errors.append(f"Invalid argument. Unable to set value [{token}] for key [{key}].")
            valid = False
            break
        except OverflowError:
            errors.append(f"Out of range. Unable to set value [{token}] for key [{key}].")
            valid = False
            break
        colors.append(c)
        if c < 0.0 or c > 1.0:
            valid = False
            break
    if valid and len(colors) == 3:
        colors.append(1.0)
    elif len(colors) != 4:
        valid = False
    if valid:
        if any(math.isnan(c) for c in colors):
            colors = [0.0 if math.isnan(c) else c for c in colors]
            if report_clamp:
                print("Color values were clamped", file=sys.stderr)
        r, g, b, alpha = colors
        return (r, g, b, alpha), ""
    errors.append(f"The value <{key}>{value}</{key}> is invalid.")
    return None, "\nError Code 34: Msg: ".join(errors)


def material_color(text: str, key: str) -> tuple[float, float, float, float]:
    """gz::math::Color of a ``<diffuse>`` (...), held as floats (so 0.1 reads back as
    0.10000000149011612). ValueError where libsdformat's reading fails."""
    color, errors = parse_color(text, key)
    if color is None:
        raise ValueError(errors)
    return color


def log_sdformat_error(message: str) -> None:
    """libsdformat's console line for a value it cannot read (pydrake logs it, measured)."""
    logging.getLogger("drake").error(
        "SDFormat Error [Param.cc:1289] Error Code 34: Msg: %s", message
    )


def version_tuple(version: str) -> tuple[int, ...]:
    try:
        return tuple(int(part) for part in version.split("."))
    except ValueError:
        return (0,)


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


def _step(element: XmlElement) -> str:
    name = element.get("name")
    return f"/{element.tag}" if name is None else f'/{element.tag}[@name="{name}"]'


class _Checker:
    def __init__(self, label: str, include: IncludeHook | None, strict: bool) -> None:
        self.label = label
        self.include = include
        self.strict = strict

    def error(self, line: int, path: str, message: str) -> ModelParseError:
        return ModelParseError(f"{self.label}:{line}: error: At XML path {path}: {message}")

    def check(self, element: XmlElement, parent_tag: str | None, path: str) -> None:
        """readXml: ``element``, whose XML path is ``path``, and what it holds."""
        defined = description(element.tag, parent_tag)
        if defined is None:
            return
        self._check_attributes(element, path, defined[0])
        self._check_value(element, parent_tag, path)
        include_index = -1
        for child in list(element):
            assert isinstance(child, XmlElement)
            if child.tag == "include" and element.tag in ("model", "world"):
                include_index += 1
                self._include(element, child, f"{path}/include[{include_index}]")
                continue
            child_path = path + _step(child)
            if child.tag in defined[1]:
                if defined[1][child.tag] == "-1":
                    Diagnostics(None, self.strict).warning(
                        f"At XML path {child_path}: SDF Element[{child.tag}] is deprecated\n"
                    )
                self.check(child, element.tag, child_path)
            elif ":" not in child.tag:
                raise self.error(
                    child.line,
                    child_path,
                    f"XML Element[{child.tag}], child of element[{element.tag}], not defined "
                    f"in SDF. Copying[{child.tag}] as children of [{element.tag}].\n",
                )
        if element.tag == "joint" and element.get("type") != "ball":
            for end in ("parent", "child"):
                if not children(element, end):
                    raise self.error(
                        element.line,
                        f"{path}/{end}",
                        f"XML Missing required element[{end}], child of element[joint]",
                    )

    def _check_attributes(
        self, element: XmlElement, path: str, attributes: dict[str, bool]
    ) -> None:
        for key, value in element.attrib.items():
            if ":" in key:
                continue
            attribute_path = f'{path}[@{key}="{value}"]'
            if key not in attributes:
                raise self.error(
                    element.line,
                    attribute_path,
                    f"XML Attribute[{key}] in element[{element.tag}] not defined in SDF.\n",
                )
            if (element.tag, key) in _BOOL_ATTRIBUTES and sdformat_bool(value) is None:
                log_sdformat_error("Invalid boolean value")
                raise self.error(element.line, attribute_path, f"Unable to read attribute[{key}]")
        for key, required in attributes.items():
            if required and key not in element.attrib:
                raise self.error(
                    element.line,
                    path,
                    f"Required attribute[{key}] in element[{element.tag}] is not specified in SDF.",
                )

    def _check_value(self, element: XmlElement, parent_tag: str | None, path: str) -> None:
        if element.tag == "pose":
            try:
                parse_pose(
                    element.text or "", element.get("rotation_format"), element.get("degrees")
                )
            except PoseTextError as exc:
                if exc.attribute is None:
                    log_sdformat_error(str(exc))
                    raise self.error(element.line, path, "Error reading element <pose>") from None
        elif element.tag in _COLORS and parent_tag == "material":
            color, errors = parse_color(element.text or "", element.tag, report_clamp=True)
            if color is None:
                log_sdformat_error(errors)
                raise self.error(element.line, path, f"Error reading element <{element.tag}>")
        elif (element.tag, parent_tag) in _BOOL_VALUES and sdformat_bool(
            element.text or ""
        ) is None:
            log_sdformat_error("Invalid boolean value")
            raise self.error(element.line, path, f"Error reading element <{element.tag}>")

    def _include(self, parent: XmlElement, include: XmlElement, path: str) -> None:
        """Checks the ``<include>`` itself (paths from the include), then expands it in place."""
        _Checker(self.label, None, self.strict).check(include, parent.tag, "")
        replacements = self.include(include, parent, path, self.label) if self.include else []
        position = list(parent).index(include)
        parent.remove(include)
        for offset, element in enumerate(replacements):
            parent.insert(position + offset, element)


def _convert(root: XmlElement, version: tuple[int, ...]) -> None:
    """libsdformat's conversions of versions before 1.7 that Drake's reading depends on."""
    if version >= (1, 7):
        return
    for pose in root.iter("pose"):
        if "frame" in pose.attrib and "relative_to" not in pose.attrib:
            frame = pose.attrib.pop("frame")
            if frame:  # N.B. Measured: an empty frame is dropped (an <inertial> pose takes it).
                pose.set("relative_to", frame)
    for joint in root.iter("joint"):
        for axis in [*children(joint, "axis"), *children(joint, "axis2")]:
            flags = children(axis, "use_parent_model_frame")
            parent_frame = sdformat_bool(flags[0].text or "") if flags else version < (1, 5)
            for flag in flags:
                axis.remove(flag)
            if parent_frame:
                for xyz in children(axis, "xyz"):
                    xyz.set("expressed_in", "__model__")


def _scoped_names(element: XmlElement) -> None:
    """recursiveSiblingNoDoubleColonInNames: no ``name`` (outside plugins and drake:) has ``::``."""
    if element.tag == "plugin" or ":" in element.tag:
        return
    if "::" in element.get("name", ""):
        raise scoped_name_error(element)
    for child in element:
        assert isinstance(child, XmlElement)
        _scoped_names(child)


def check_document(
    root: XmlElement, label: str, include: IncludeHook | None, strict: bool = False
) -> None:
    """Reads ``root`` (an ``<sdf>``) as libsdformat does; raises its first error.

    Each ``<include>`` of a model or world is replaced by what ``include`` returns. A
    deprecated element is warned about (an error with ``strict``).
    """
    version = version_tuple(root.get("version", ""))
    _convert(root, version)
    models = children(root, "model")
    # N.B. checkXmlFromRoot names a string "<<data-string>>" (it wraps its name again).
    source = f"<{label}>" if label == "<data-string>" else label
    if models:
        for pose in children(models[0], "pose"):
            relative_to = pose.get("relative_to")
            if relative_to:
                raise ModelParseError(
                    f"{source}:{pose.line}: error: Attribute //pose[@relative_to] of top level "
                    f"model must be left empty, found //pose[@relative_to='{relative_to}'].\n"
                )
    _Checker(label, include, strict).check(root, None, "/sdf")
    if version >= _UNSCOPED_SINCE:
        _scoped_names(root)
