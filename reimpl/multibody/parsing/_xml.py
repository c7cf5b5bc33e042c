"""Model text to an element tree with line numbers, read as Drake reads it.

Drake reads URDF and SDFormat with tinyxml2, which does no namespace
processing: ``<drake:member>`` is an element whose name is ``drake:member``,
whether or not the file declares ``xmlns:drake``. The standard library's expat
parser, with namespace processing off (``ParserCreate()`` without a
separator), reads the same names; its events build ``xml.etree.ElementTree``
elements that also remember the line they start on.

tinyxml2 names its syntax errors differently from expat; ``_TINYXML2_ERRORS``
maps the ones Drake users meet (measured on 1.51.1) and falls back to
``XML_ERROR_PARSING``. Drake prints line 1 for any syntax error, or line 0 for
an empty text.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass
from xml.parsers import expat

__all__ = ["XmlElement", "XmlSyntaxError", "children", "parse_xml"]

_codes = expat.errors.codes
#: expat error code -> (tinyxml2 error name, tinyxml2 ErrorID)
_TINYXML2_ERRORS: dict[int, tuple[str, int]] = {
    _codes[expat.errors.XML_ERROR_TAG_MISMATCH]: ("XML_ERROR_MISMATCHED_ELEMENT", 14),
    _codes[expat.errors.XML_ERROR_UNCLOSED_TOKEN]: ("XML_ERROR_PARSING_ATTRIBUTE", 7),
    _codes[expat.errors.XML_ERROR_DUPLICATE_ATTRIBUTE]: ("XML_ERROR_PARSING_ATTRIBUTE", 7),
    _codes[expat.errors.XML_ERROR_INVALID_TOKEN]: ("XML_ERROR_PARSING_ATTRIBUTE", 7),
    # Text where an element should start ("bad", "<!-- c -->bad"): tinyxml2 reads it as
    # a text node and fails on it (measured on pydrake 1.51.1).
    _codes[expat.errors.XML_ERROR_SYNTAX]: ("XML_ERROR_PARSING_TEXT", 8),
}
_PARSING = ("XML_ERROR_PARSING", 15)
_EMPTY_DOCUMENT = ("XML_ERROR_EMPTY_DOCUMENT", 13)


class XmlElement(ET.Element):
    """An element that knows the line it starts on (1-based)."""

    line: int = 0


@dataclass(frozen=True)
class XmlSyntaxError(Exception):
    """Text that is not well-formed XML, described as tinyxml2 would."""

    name: str
    error_id: int
    line: int


def parse_xml(text: str) -> XmlElement:
    """The first top-level element of ``text``; raises XmlSyntaxError.

    tinyxml2 accepts several top-level elements; so does this, keeping the first.
    """
    builder = ET.TreeBuilder(element_factory=XmlElement)
    parser = expat.ParserCreate()
    parser.buffer_text = True

    def start(tag: str, attributes: dict[str, str]) -> None:
        element = builder.start(tag, attributes)
        element.line = parser.CurrentLineNumber  # type: ignore[attr-defined]

    parser.StartElementHandler = start
    parser.EndElementHandler = builder.end
    parser.CharacterDataHandler = builder.data
    try:
        parser.Parse(text, True)
    except expat.ExpatError as exc:
        if exc.code != _codes[expat.errors.XML_ERROR_JUNK_AFTER_DOC_ELEMENT]:
            raise _syntax_error(text, exc.code) from None
    root = builder.close()
    assert isinstance(root, XmlElement)
    return root


def _syntax_error(text: str, code: int | None) -> XmlSyntaxError:
    if not text.strip():
        name, error_id = _EMPTY_DOCUMENT
    else:
        name, error_id = _TINYXML2_ERRORS.get(code or 0, _PARSING)
    return XmlSyntaxError(name, error_id, 1 if text else 0)


def children(element: ET.Element, tag: str) -> list[XmlElement]:
    """The child elements named ``tag``, in document order."""
    return [child for child in element if child.tag == tag and isinstance(child, XmlElement)]
