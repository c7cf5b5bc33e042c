"""A ROS ``package.xml``: the package's name and whether it is deprecated.

Drake reads ``/package/name`` and ``/package/export/deprecated`` with
tinyxml2, taking each element's *first child node* as its value (measured on
pydrake 1.51.1):

=========================================  ===================================
 first child of ``<name>``                  value
=========================================  ===================================
 text                                       the text as written (`` a `` keeps
                                            its spaces)
 an element ``<x/>``                        ``x`` (its tag)
 a comment ``<!-- c -->``                   `` c `` (its text)
 none (empty, or only whitespace)           SystemExit: DRAKE_THROW_UNLESS
=========================================  ===================================

A ``<deprecated>`` message is its first child's value with the line breaks
and the indentation around them collapsed to one space and the ends
stripped; an empty ``<deprecated/>`` reads as ``(no explanation given)``.
"""

from __future__ import annotations

import contextlib
import re
from dataclasses import dataclass, field
from xml.parsers import expat

from reimpl.common._drake_demand import failed_demand
from reimpl.multibody.parsing._xml import XmlSyntaxError, parse_xml

__all__ = ["Manifest", "read_manifest"]

_WHERE = "PackageMap::GetPackageName()"
_LINE_BREAKS = re.compile(r"\s*\n\s*")


@dataclass(frozen=True)
class Manifest:
    name: str
    #: None if the package is not deprecated; "" for an empty <deprecated/>
    deprecation: str | None


@dataclass
class _Node:
    """An element with its child nodes in order: (kind, value, node) with kind
    "text", "comment" or "element"."""

    tag: str
    children: list[tuple[str, str, _Node | None]] = field(default_factory=list)

    def element(self, tag: str) -> _Node | None:
        for kind, _, node in self.children:
            if kind == "element" and node is not None and node.tag == tag:
                return node
        return None

    def first_child(self) -> str | None:
        """tinyxml2's ``FirstChild()->Value()``; None if there is no child node."""
        return self.children[0][1] if self.children else None


def _parse(text: str) -> _Node:
    """The document node, keeping text, comments and elements in order."""
    stack = [_Node("")]
    parser = expat.ParserCreate()
    parser.buffer_text = True

    def start(tag: str, _: dict[str, str]) -> None:
        node = _Node(tag)
        stack[-1].children.append(("element", tag, node))
        stack.append(node)

    def end(_: str) -> None:
        stack.pop()

    def characters(data: str) -> None:
        # N.B. tinyxml2 drops a text node that is only whitespace.
        if data.strip():
            stack[-1].children.append(("text", data, None))

    def comment(data: str) -> None:
        stack[-1].children.append(("comment", data, None))

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = characters
    parser.CommentHandler = comment
    # N.B. parse_xml() has accepted the text: an error here is junk after the element.
    with contextlib.suppress(expat.ExpatError):
        parser.Parse(text, True)
    return stack[0]


def read_manifest(filename: str) -> Manifest:
    """The name and deprecation of the package ``filename`` describes."""
    try:
        with open(filename, encoding="utf-8") as stream:
            text = stream.read()
    except FileNotFoundError:
        raise _xml_error(filename, "XML_ERROR_FILE_NOT_FOUND") from None
    except OSError:
        raise _xml_error(filename, "XML_ERROR_FILE_READ_ERROR") from None
    try:
        parse_xml(text)
    except XmlSyntaxError as exc:
        raise _xml_error(filename, exc.name) from None
    package = _parse(text).element("package")
    if package is None:
        raise RuntimeError(
            f'{_WHERE}: ERROR: XML file "{filename}" does not contain element <package>.'
        )
    name_node = package.element("name")
    if name_node is None:
        raise RuntimeError(
            f"{_WHERE}: ERROR: <package> element does not contain element <name> "
            f'(XML file "{filename}").'
        )
    name = name_node.first_child()
    if name is None:
        raise failed_demand("ParsePackageManifest.name_children")
    if name == "":
        raise failed_demand("ParsePackageManifest.name")
    return Manifest(name, _deprecation(package))


def _deprecation(package: _Node) -> str | None:
    export = package.element("export")
    deprecated = export.element("deprecated") if export is not None else None
    if deprecated is None:
        return None
    message = deprecated.first_child()
    if message is None:
        return ""
    return _LINE_BREAKS.sub(" ", message.strip(" \r\n\t"))


def _xml_error(filename: str, name: str) -> RuntimeError:
    return RuntimeError(f'{_WHERE}: Failed to parse XML in file "{filename}".\n{name}')
