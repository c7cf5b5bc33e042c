"""Ways to bend an XML model file: quirks Drake's XML reader (tinyxml2) accepts, and errors.

Each ``XmlQuirk`` rewrites a rendered URDF or SDFormat text (``apply``) and
recognises its own mark in any text (``detect``), so the coverage of
``fuzz --models`` counts what the files hold, not what the generator meant.
``accepted`` says whether pydrake 1.51.1 parses the result as it parses the
text before (measured for URDF and SDFormat, from a string and from a file):

======================== ======== ==================================================
quirk                    accepted what it does
======================== ======== ==================================================
cdata                    yes      a CDATA section inside the root element
doctype                  yes      a ``<!DOCTYPE>`` before the root element
dashdash-comment         yes      a comment holding ``--`` before the root element
blank-before-declaration yes      a blank line, then ``<?xml version="1.0"?>``
bom                      yes      a UTF-8 byte order mark first
trailing-nul             yes      a NUL character after the document
unclosed-root            no       the root element's end tag cut off
mismatched-end-tag       no       the root element's end tag misspelt
trailing-text            no       text after the root element
processing-instruction   no       ``<?pi?>`` inside the root element
duplicate-attribute      no       the ``<robot>``'s or first ``<model>``'s ``name`` twice
======================== ======== ==================================================

The accepted quirks combine (every subset, applied in ``XML_QUIRKS``'s order
of the accepted ones, parses as the text before: measured). An error's
message names tinyxml2's error (``XML_ERROR_PARSING_TEXT``) and,
for SDFormat, the line; in a URDF file read from disk it says ``XML file``,
from a string ``XML string``.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass

__all__ = ["XML_QUIRKS", "XmlQuirk", "detect_quirks"]

_ROOT_END = re.compile(r"</(robot|sdf)>(\s*)$")
_ROOT_START = re.compile(r"<(robot|sdf)\b[^>]*>")


@dataclass(frozen=True)
class XmlQuirk:
    """One way to bend a document (see the module doc)."""

    name: str
    accepted: bool
    apply: Callable[[str], str]
    detect: Callable[[str], bool]


def _after_root_start(text: str, insert: str) -> str:
    match = _ROOT_START.search(text)
    if match is None:
        return text
    return text[: match.end()] + insert + text[match.end() :]


def _cut_root_end(text: str) -> str:
    return _ROOT_END.sub(r"\2", text)


def _misspell_root_end(text: str) -> str:
    return _ROOT_END.sub(r"</\1x>\2", text)


def _duplicate_name(text: str) -> str:
    return re.sub(r'(<(?:robot|model)\b[^>]*?\bname="[^"]*")', r'\1 name="x"', text, count=1)


def _searcher(pattern: str, flags: int = 0) -> Callable[[str], bool]:
    compiled = re.compile(pattern, flags)
    return lambda text: compiled.search(text) is not None


def _unclosed(text: str) -> bool:
    root = _ROOT_START.search(text)
    return root is not None and f"</{root.group(1)}" not in text


def _misspelt(text: str) -> bool:
    root = _ROOT_START.search(text)
    end = re.search(r"</([\w:]+)>\s*\Z", text.rstrip("\0"))
    return root is not None and end is not None and end.group(1) == root.group(1) + "x"


XML_QUIRKS: dict[str, XmlQuirk] = {
    quirk.name: quirk
    for quirk in (
        # The accepted ones, in the order a document takes several (inside out).
        XmlQuirk(
            "cdata",
            True,
            lambda t: _after_root_start(t, "<![CDATA[ a < b ]]>"),
            _searcher(r"<!\[CDATA\["),
        ),
        XmlQuirk("doctype", True, lambda t: "<!DOCTYPE x>\n" + t, _searcher(r"<!DOCTYPE")),
        XmlQuirk(
            "dashdash-comment",
            True,
            lambda t: "<!-- a -- b -->\n" + t,
            _searcher(r"<!--(?:(?!-->).)*?--(?!>)", re.DOTALL),
        ),
        XmlQuirk(
            "blank-before-declaration",
            True,
            lambda t: '\n<?xml version="1.0"?>\n' + t,
            _searcher(r"\A\ufeff?\s+<\?xml\b"),
        ),
        XmlQuirk("bom", True, lambda t: "\ufeff" + t, _searcher(r"\A\ufeff")),
        XmlQuirk("trailing-nul", True, lambda t: t + "\0", _searcher(r"\x00\s*\Z")),
        XmlQuirk("unclosed-root", False, _cut_root_end, _unclosed),
        XmlQuirk("mismatched-end-tag", False, _misspell_root_end, _misspelt),
        XmlQuirk(
            "trailing-text",
            False,
            lambda t: t + "junk\n",
            _searcher(r"</(?:robot|sdf)>\s*[^\s<\x00]"),
        ),
        XmlQuirk(
            "processing-instruction",
            False,
            lambda t: _after_root_start(t, "<?pi x?>"),
            _searcher(r"<\?(?!xml\b)"),
        ),
        XmlQuirk(
            "duplicate-attribute",
            False,
            _duplicate_name,
            _searcher(r"<(?:robot|sdf|model)\b[^>]*\bname=\"[^\"]*\"[^>]*\bname=\""),
        ),
    )
}


def detect_quirks(text: str) -> list[str]:
    """The names of the quirks whose mark ``text`` holds."""
    return [name for name, quirk in XML_QUIRKS.items() if quirk.detect(text)]
