"""A MuJoCo XML document: its text read as tinyxml2 reads it, ``<include>``s expanded.

Drake 1.51.1 (measured): a file that tinyxml2 cannot read is ``Failed to parse
XML file F:\\nXML_ERROR_...`` (F as given), model text ``Failed to parse XML
string: XML_ERROR_...``, at the document's line (0 for an empty one, else 1).
The model is the first top-level ``<mujoco>`` (none: ``ERROR: XML does not
contain a mujoco tag.``).

``<include file="F">`` is expanded lexically, before anything else is read, in
the document's first top-level element (whatever its name): F is taken below
the folder of the model file as named (of the working folder, for model text),
made absolute but not normalized; it must load (``Failed to load <include> file
at path P.``), and the children of its first top-level element replace the
``<include>``, copied without line numbers (line 0), and are themselves
expanded in turn (their own includes also below the main file's folder). An
``<include>`` without ``file`` is ``<include> tag without file attribute.``.
"""

from __future__ import annotations

import os

from reimpl.multibody.parsing._diagnostics import Diagnostics
from reimpl.multibody.parsing._xml import (
    XmlDocument,
    XmlElement,
    XmlSyntaxError,
    parse_document,
)

__all__ = ["expand_includes", "first_element", "load_document"]


def load_document(text: str, path: str | None, diagnostics: Diagnostics) -> XmlDocument:
    """The document of ``text`` (a file's, when ``path`` names it), or Drake's error."""
    try:
        return parse_document(text, from_file=path is not None)
    except XmlSyntaxError as exc:
        what = f"file {path}:\n" if path is not None else "string: "
        raise diagnostics.error(f"Failed to parse XML {what}{exc.name}", exc.line) from None


def first_element(document: XmlDocument, tag: str | None = None) -> XmlElement | None:
    """The first top-level element (named ``tag``, if given)."""
    for child in document:
        if isinstance(child, XmlElement) and (tag is None or child.tag == tag):
            return child
    return None


def _without_lines(element: XmlElement) -> XmlElement:
    """tinyxml2's DeepClone: the element's copy, its text and elements, all at line 0."""
    clone = XmlElement(element.tag, dict(element.attrib))
    clone.text = element.text
    clone.extend(_without_lines(child) for child in element if isinstance(child, XmlElement))
    return clone


def _absolute(path: str) -> str:
    """``std::filesystem::absolute``: the working folder prefixed, nothing normalized."""
    return path if os.path.isabs(path) else os.path.join(os.getcwd(), path)


def _included(node: XmlElement, folder: str, diagnostics: Diagnostics) -> list[XmlElement]:
    """The copies of an ``<include>``'s elements."""
    file = node.get("file")
    if file is None:
        raise diagnostics.error("<include> tag without file attribute.", node.line)
    path = _absolute(os.path.join(folder, file) if folder else file)
    try:
        with open(path, encoding="utf-8", newline="") as stream:
            document = parse_document(stream.read(), from_file=True)
    except (OSError, UnicodeDecodeError, XmlSyntaxError):
        raise diagnostics.error(
            f"Failed to load <include> file at path {path}.", node.line
        ) from None
    root = first_element(document)
    if root is None:
        raise diagnostics.error(f"Included file {path} has no root element.", node.line)
    return [_without_lines(child) for child in root if isinstance(child, XmlElement)]


def expand_includes(node: XmlElement, folder: str, diagnostics: Diagnostics) -> None:
    """ExpandIncludeTags: each ``<include>`` below ``node`` replaced by what it includes."""
    index = 0
    while index < len(node):
        child = node[index]
        if not isinstance(child, XmlElement):
            index += 1
        elif child.tag == "include":
            node[index : index + 1] = _included(child, folder, diagnostics)
        else:
            expand_includes(child, folder, diagnostics)
            index += 1
