"""Model text to an element tree with line numbers, read as Drake's tinyxml2 reads it.

Drake reads URDF (and libsdformat reads SDFormat) with tinyxml2 11.0.0, a
lenient parser with no namespace processing: ``<drake:member>`` is an element
whose name is ``drake:member``, whether or not the file declares
``xmlns:drake``. This module follows tinyxml2's own grammar rather than an XML
standard parser's, because the two disagree on real files. tinyxml2 (measured
on pydrake 1.51.1, and read in tinyxml2.cpp) accepts:

* ``--`` inside a comment, ``<`` and unknown ``&name;`` inside an attribute
  value (kept as written), whitespace or text before ``<?xml ...?>``,
  ``<!DOCTYPE ...>`` (skipped up to the first ``>``), several top-level
  elements, whitespace after ``<`` (``< robot>``), attributes with no space
  between them;
* a NUL character: the text ends there (Drake passes a C string).

and rejects, with these tinyxml2 error names (``XML_ERROR_*``):

==========================  ===================================================
 name                        when
==========================  ===================================================
 ``EMPTY_DOCUMENT``          nothing but whitespace (and a byte-order mark)
 ``PARSING_TEXT``            text after which no ``<`` follows
 ``PARSING_COMMENT``         ``<!--`` without ``-->`` (``CDATA``, ``DECLARATION``
                             and ``UNKNOWN`` alike for ``<![CDATA[``, ``<?``, ``<!``)
 ``PARSING_DECLARATION``     ``<?...?>`` anywhere but first in the document
 ``PARSING_ELEMENT``         a tag cut short, or a stray character in it
 ``PARSING_ATTRIBUTE``       an attribute without ``="..."``, or given twice
 ``MISMATCHED_ELEMENT``      an end tag of another name, or none at all
 ``PARSING``                 an element name that does not start with a letter,
                             ``_`` or ``:``; an element its parent never closes
 ``ELEMENT_DEPTH_EXCEEDED``  elements nested 500 deep
==========================  ===================================================

An end tag at the top level (``</robot>``) ends the document quietly: what
follows is not read. Values are read as tinyxml2 returns them: line ends
normalized to LF, the five predefined entities and ``&#...;``/``&#x...;``
character references replaced, any other ``&`` kept. An element's ``text`` is
tinyxml2's ``GetText()``: its first child node when that is text (or CDATA);
whitespace between tags is no node at all. Comments, declarations and
``<!...>`` nodes are read and dropped.

``XmlSyntaxError.line`` is the line Drake's URDF parser prints (the
document's: 0 for an empty text or a file of no bytes, else 1); ``error_line``
and ``detail`` are tinyxml2's own (``ErrorStr()`` is ``message``).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass
from enum import IntEnum

__all__ = [
    "XmlDocument",
    "XmlElement",
    "XmlError",
    "XmlSyntaxError",
    "children",
    "parse_document",
    "parse_xml",
]


class XmlError(IntEnum):
    """tinyxml2's ``XMLError`` values (those a parse can give)."""

    XML_ERROR_PARSING_ELEMENT = 6
    XML_ERROR_PARSING_ATTRIBUTE = 7
    XML_ERROR_PARSING_TEXT = 8
    XML_ERROR_PARSING_CDATA = 9
    XML_ERROR_PARSING_COMMENT = 10
    XML_ERROR_PARSING_DECLARATION = 11
    XML_ERROR_PARSING_UNKNOWN = 12
    XML_ERROR_EMPTY_DOCUMENT = 13
    XML_ERROR_MISMATCHED_ELEMENT = 14
    XML_ERROR_PARSING = 15
    XML_ELEMENT_DEPTH_EXCEEDED = 18


#: tinyxml2's TINYXML2_MAX_ELEMENT_DEPTH.
_MAX_DEPTH = 500
_WHITESPACE = frozenset(" \t\n\v\f\r")
_ENTITIES = {"quot": '"', "amp": "&", "apos": "'", "lt": "<", "gt": ">"}
_MAX_CODE_POINT = 0x10FFFF


class XmlElement(ET.Element):
    """An element that knows the line it starts on (1-based)."""

    line: int = 0


class XmlDocument(XmlElement):
    """The document node: its children are the top-level elements (tag ``""``)."""


@dataclass(frozen=True)
class XmlSyntaxError(Exception):
    """Text that tinyxml2 rejects, described as tinyxml2 describes it."""

    name: str
    error_id: int
    line: int
    error_line: int = 0
    detail: str = ""

    @property
    def message(self) -> str:
        """tinyxml2's ``ErrorStr()``."""
        text = (
            f"Error={self.name} ErrorID={self.error_id} (0x{self.error_id:x}) "
            f"Line number={self.error_line}"
        )
        return f"{text}: {self.detail}" if self.detail else text


def parse_document(text: str, *, from_file: bool = False) -> XmlDocument:
    """The document node of ``text``; raises XmlSyntaxError where tinyxml2 fails.

    ``from_file``: the text is a file's (tinyxml2's LoadFile), where only a
    file of no bytes at all has line 0.
    """
    parser = _Parser(text.split("\x00", 1)[0])
    parser.empty_line = 0 if not text or not from_file else 1
    return parser.parse()


def parse_xml(text: str) -> XmlElement:
    """The first top-level element of ``text`` (the document node if it has none)."""
    document = parse_document(text)
    for child in document:
        assert isinstance(child, XmlElement)
        return child
    return document


def children(element: ET.Element, tag: str) -> list[XmlElement]:
    """The child elements named ``tag``, in document order."""
    return [child for child in element if child.tag == tag and isinstance(child, XmlElement)]


# ------------------------------------------------------------------ the parser


def _is_name_start(ch: str) -> bool:
    """tinyxml2's IsNameStartChar: an ASCII letter, ``:``, ``_``, or any non-ASCII
    (``ch`` is one character, or "" at the end of the text)."""
    return ch != "" and (ord(ch) >= 128 or ("a" <= ch.lower() <= "z") or ch in ":_")


def _is_name_char(ch: str) -> bool:
    return _is_name_start(ch) or "0" <= ch <= "9" or ch in ".-"


def _normalize(value: str, entities: bool) -> str:
    """tinyxml2's StrPair::GetStr: CR LF, LF CR and CR become LF; entities replaced.

    The value ends at a NUL (``&#0;``), as the C string Drake reads does.
    """
    out: list[str] = []
    i, n = 0, len(value)
    while i < n:
        ch = value[i]
        if ch in "\r\n":
            pair = "\n" if ch == "\r" else "\r"
            i += 2 if i + 1 < n and value[i + 1] == pair else 1
            out.append("\n")
        elif ch == "&" and entities:
            replaced, i = _entity(value, i)
            out.append(replaced)
        else:
            out.append(ch)
            i += 1
    return "".join(out).split("\x00", 1)[0]


def _entity(value: str, i: int) -> tuple[str, int]:
    """The text ``&...`` at ``i`` stands for, and where reading goes on."""
    if value.startswith("&#", i):
        return _character_reference(value, i)
    for name, replacement in _ENTITIES.items():
        if value.startswith(f"&{name};", i):
            return replacement, i + len(name) + 2
    return "&", i + 1


def _character_reference(value: str, i: int) -> tuple[str, int]:
    """tinyxml2's GetCharacterRef; the ``&`` stays as written where it fails.

    tinyxml2 reads the digits backwards from the first ``;`` to the last ``#``
    (``x`` for hexadecimal) before it, in uint32 arithmetic; ``&#`` at the very
    end of a value loses its ``&``.
    """
    if i + 2 >= len(value):
        return "", i + 1
    hexadecimal = value[i + 2] == "x"
    start = i + 3 if hexadecimal else i + 2
    end = value.find(";", start) if start < len(value) else -1
    if end < 0:
        return "&", i + 1
    digits = value[value.rfind("x" if hexadecimal else "#", i + 1, end) + 1 : end]
    code, weight = 0, 1
    for digit_char in reversed(digits):
        digit = _digit(digit_char, hexadecimal)
        if digit is None:
            return "&", i + 1
        code = (code + weight * digit) & 0xFFFFFFFF
        weight = min(weight * (16 if hexadecimal else 10) & 0xFFFFFFFF, _MAX_CODE_POINT)
    if code > _MAX_CODE_POINT:
        return "&", i + 1
    return chr(code), end + 1


def _digit(ch: str, hexadecimal: bool) -> int | None:
    if "0" <= ch <= "9":
        return ord(ch) - ord("0")
    if hexadecimal and ("a" <= ch <= "f" or "A" <= ch <= "F"):
        return int(ch, 16)
    return None


class _ParseError(Exception):
    """A tinyxml2 parse error, raised where tinyxml2 sets it."""

    def __init__(self, error: XmlError, line: int, detail: str = "") -> None:
        super().__init__(error.name)
        self.error, self.line, self.detail = error, line, detail


@dataclass
class _Open:
    """An element whose children are being read; ``nodes`` counts them so far."""

    element: XmlElement
    nodes: int = 0
    declarations: int = 0

    def add_node(self, text: str | None = None) -> None:
        """A child node; the first, when text, is the element's GetText()."""
        if self.nodes == 0 and text is not None:
            self.element.text = text
        self.nodes += 1


class _Parser:
    """tinyxml2's XMLDocument::Parse, as a loop over a stack of open elements."""

    def __init__(self, text: str) -> None:
        self.text = text
        self.pos = 0
        self.line = 1
        #: The document's line when the text is empty (the C string Drake passes, or the file).
        self.empty_line = 0

    # ------------------------------------------------------------- scanning
    def _peek(self, offset: int = 0) -> str:
        i = self.pos + offset
        return self.text[i] if i < len(self.text) else ""

    def _skip_whitespace(self) -> None:
        text, pos = self.text, self.pos
        while pos < len(text) and text[pos] in _WHITESPACE:
            if text[pos] == "\n":
                self.line += 1
            pos += 1
        self.pos = pos

    def _read_until(self, end: str) -> str | None:
        """The raw text up to ``end`` (consumed), counting lines; None at end of text."""
        found = self.text.find(end, self.pos)
        if found < 0:
            self.line += self.text.count("\n", self.pos)
            self.pos = len(self.text)
            return None
        raw = self.text[self.pos : found]
        self.line += raw.count("\n")
        self.pos = found + len(end)
        return raw

    def _read_name(self) -> str:
        start = self.pos
        if not _is_name_start(self._peek()):
            return ""
        self.pos += 1
        while self._peek() and _is_name_char(self._peek()):
            self.pos += 1
        return self.text[start : self.pos]

    # ------------------------------------------------------------- document
    def parse(self) -> XmlDocument:
        document = XmlDocument("")
        if not self.text:
            raise XmlSyntaxError("XML_ERROR_EMPTY_DOCUMENT", 13, self.empty_line)
        document.line = 1
        self._skip_whitespace()
        if self._peek() == "\ufeff":
            self.pos += 1
        if not self._peek():
            raise XmlSyntaxError("XML_ERROR_EMPTY_DOCUMENT", 13, 1)
        try:
            self._parse_nodes(document)
        except _ParseError as failed:
            raise XmlSyntaxError(
                failed.error.name, int(failed.error), 1, failed.line, failed.detail
            ) from None
        return document

    def _parse_nodes(self, document: XmlDocument) -> None:
        """XMLNode::ParseDeep at every level: read nodes, open and close elements."""
        stack = [_Open(document)]
        while True:
            if len(stack) >= _MAX_DEPTH:
                raise _ParseError(
                    XmlError.XML_ELEMENT_DEPTH_EXCEEDED, self.line, "Element nesting is too deep."
                )
            top = stack[-1]
            start, start_line = self.pos, self.line
            self._skip_whitespace()
            if not self._peek():
                if len(stack) == 1:
                    return
                raise _ParseError(XmlError.XML_ERROR_PARSING, top.element.line)
            line = self.line
            kind = self._identify()
            if kind == "text":  # N.B. Text keeps its leading whitespace.
                self.pos, self.line = start, start_line
                top.add_node(self._text(line))
            elif kind == "cdata":
                top.add_node(self._raw(kind, line))
            elif kind == "declaration":
                value = self._raw(kind, line)
                if len(stack) > 1 or top.nodes > top.declarations:
                    raise _ParseError(
                        XmlError.XML_ERROR_PARSING_DECLARATION,
                        line,
                        f"XMLDeclaration value={value}",
                    )
                top.add_node()
                top.declarations += 1
            elif kind != "element":
                self._raw(kind, line)
                top.add_node()
            elif self._element(line, stack):
                return  # N.B. An end tag at the top level ends the document.

    def _element(self, line: int, stack: list[_Open]) -> bool:
        """Reads a tag: opens, closes or adds an element; True for a top-level end tag."""
        top = stack[-1]
        element, closing = self._tag(line)
        if closing == "closing":
            if len(stack) == 1:
                return True
            stack.pop()
            if element.tag != top.element.tag:
                raise _ParseError(
                    XmlError.XML_ERROR_MISMATCHED_ELEMENT,
                    top.element.line,
                    f"XMLElement name={top.element.tag}",
                )
            stack[-1].add_node()
            stack[-1].element.append(top.element)
        elif closing == "open" and self._peek():
            stack.append(_Open(element))
        elif closing == "open":
            raise _ParseError(
                XmlError.XML_ERROR_MISMATCHED_ELEMENT, line, f"XMLElement name={element.tag}"
            )
        else:
            top.add_node()
            top.element.append(element)
        return False

    def _identify(self) -> str:
        """XMLDocument::Identify: the kind of node at the cursor (moved past its opener)."""
        for opener, kind in _OPENERS:
            if self.text.startswith(opener, self.pos):
                self.pos += len(opener)
                return kind
        return "text"

    def _raw(self, kind: str, line: int) -> str:
        """A comment's, CDATA's, declaration's or ``<!...>``'s value, line ends normalized."""
        end, error = _NODE_ENDS[kind]
        raw = self._read_until(end)
        if raw is None:
            raise _ParseError(error, line)
        return _normalize(raw, entities=False)

    def _text(self, line: int) -> str:
        """Text up to the next ``<``, which starts the next node."""
        raw = self._read_until("<")
        if raw is None:
            raise _ParseError(XmlError.XML_ERROR_PARSING_TEXT, line)
        if not self._peek():
            raise _ParseError(XmlError.XML_ERROR_PARSING, line)
        self.pos -= 1
        return _normalize(raw, entities=True)

    def _tag(self, line: int) -> tuple[XmlElement, str]:
        """XMLElement::ParseDeep up to its children: (element, open|closed|closing)."""
        self._skip_whitespace()
        closing = "open"
        if self._peek() == "/":
            closing = "closing"
            self.pos += 1
        name = self._read_name()
        if not name:
            raise _ParseError(XmlError.XML_ERROR_PARSING, line)
        element = XmlElement(name)
        element.line = line
        return element, self._attributes(element, closing)

    def _attributes(self, element: XmlElement, closing: str) -> str:
        """XMLElement::ParseAttributes; returns the element's closing type."""
        while True:
            self._skip_whitespace()
            ch = self._peek()
            if not ch:
                raise _ParseError(
                    XmlError.XML_ERROR_PARSING_ELEMENT,
                    element.line,
                    f"XMLElement name={element.tag}",
                )
            if _is_name_start(ch):
                line = self.line
                parsed = self._attribute()
                if parsed is None or parsed[0] in element.attrib:
                    raise _ParseError(
                        XmlError.XML_ERROR_PARSING_ATTRIBUTE,
                        line,
                        f"XMLElement name={element.tag}",
                    )
                element.set(*parsed)
            elif ch == ">":
                self.pos += 1
                return closing
            elif ch == "/" and self._peek(1) == ">":
                self.pos += 2
                return "closed"
            else:
                raise _ParseError(XmlError.XML_ERROR_PARSING_ELEMENT, element.line)

    def _attribute(self) -> tuple[str, str] | None:
        """XMLAttribute::ParseDeep: ``name = "value"`` (or ``'value'``); None if malformed."""
        name = self._read_name()
        if not self._peek():
            return None
        self._skip_whitespace()
        if self._peek() != "=":
            return None
        self.pos += 1
        self._skip_whitespace()
        quote = self._peek()
        if quote not in ('"', "'"):
            return None
        self.pos += 1
        raw = self._read_until(quote)
        if raw is None:
            return None
        return name, _normalize(raw, entities=True)


#: node opener -> kind, in the order tinyxml2's Identify tries them
_OPENERS = (
    ("<?", "declaration"),
    ("<!--", "comment"),
    ("<![CDATA[", "cdata"),
    ("<!", "unknown"),
    ("<", "element"),
)
#: kind -> (what ends it, the error if nothing does)
_NODE_ENDS = {
    "declaration": ("?>", XmlError.XML_ERROR_PARSING_DECLARATION),
    "comment": ("-->", XmlError.XML_ERROR_PARSING_COMMENT),
    "cdata": ("]]>", XmlError.XML_ERROR_PARSING_CDATA),
    "unknown": (">", XmlError.XML_ERROR_PARSING_UNKNOWN),
}
