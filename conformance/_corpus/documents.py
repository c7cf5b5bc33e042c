"""Scenario documents: a file's bytes to JSON-like data, for JSON and YAML alike.

``read_document`` picks the parser by the file's suffix (``DOCUMENT_SUFFIXES``),
decodes UTF-8 (a leading byte order mark is dropped), parses, and checks the
nesting depth. Whatever would otherwise escape as ``UnicodeDecodeError``,
``RecursionError`` or a silently dropped key is a ``DocumentError`` whose
message says what and, where the parser knows it, where. YAML is held to what
JSON can say: string keys, no duplicate keys, no aliases (an alias is a
shared subtree, which the validator would walk once per reference).
"""

from __future__ import annotations

import codecs
import json
import math
from collections import Counter
from collections.abc import Callable, Hashable
from pathlib import Path
from typing import Any

import yaml

__all__ = ["DOCUMENT_SUFFIXES", "MAX_DEPTH", "TOO_DEEP", "DocumentError", "clip", "read_document"]

#: Arrays and objects nested deeper than this are refused; a valid scenario nests about 12 deep.
MAX_DEPTH = 64
TOO_DEEP = f"nested too deeply (more than {MAX_DEPTH} levels of arrays and objects)"

#: Echoed input (a value, a key, a name) is cut to about this many characters.
ECHO_LIMIT = 200

#: Byte order marks of encodings that are not UTF-8, longest first.
_FOREIGN_BOMS = (
    (codecs.BOM_UTF32_LE, "UTF-32"),
    (codecs.BOM_UTF32_BE, "UTF-32"),
    (codecs.BOM_UTF16_LE, "UTF-16"),
    (codecs.BOM_UTF16_BE, "UTF-16"),
)


class DocumentError(ValueError):
    """The file is not a JSON or YAML document the loader can use."""


def clip(text: str, limit: int = ECHO_LIMIT) -> str:
    """``text`` if it is at most ``limit`` characters, else its head and tail around an ellipsis."""
    if len(text) <= limit:
        return text
    tail = limit // 4
    return f"{text[: limit - tail - 1]}…{text[-tail:]}"


def _one_line(text: str) -> str:
    return clip(" ".join(text.split()))


def _decode(data: bytes) -> str:
    for bom, encoding in _FOREIGN_BOMS:
        if data.startswith(bom):
            raise DocumentError(f"{encoding} text (a {encoding} byte order mark); save it as UTF-8")
    try:
        return data.decode("utf-8").removeprefix("\ufeff")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise DocumentError(
            f"not UTF-8 text (byte 0x{data[exc.start]:02x} at offset {exc.start}, line {line})"
        ) from None


def _unique_keys(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    """``object_pairs_hook``: an object, unless a key repeats (json keeps only the last)."""
    obj = dict(pairs)
    if len(obj) != len(pairs):
        key = next(k for k, n in Counter(k for k, _ in pairs).items() if n > 1)
        raise DocumentError(f"duplicate key {clip(repr(key))} in an object")
    return obj


def _non_finite(token: str, where: str = "") -> DocumentError:
    return DocumentError(
        f"the number {clip(token)}{where} is not finite; scenario numbers must be finite"
    )


def _reject_constant(token: str) -> Any:
    """``parse_constant``: Python's json reads NaN and ±Infinity, which JSON does not have."""
    raise _non_finite(token)


def _finite_float(token: str) -> float:
    """``parse_float``: a float, unless it overflows (``1e400`` is inf to Python)."""
    value = float(token)
    if not math.isfinite(value):
        raise _non_finite(token)
    return value


def _parse_json(text: str) -> Any:
    try:
        return json.loads(
            text,
            object_pairs_hook=_unique_keys,
            parse_constant=_reject_constant,
            parse_float=_finite_float,
        )
    except DocumentError:
        raise
    except json.JSONDecodeError as exc:
        raise DocumentError(
            f"malformed JSON at line {exc.lineno}, column {exc.colno}: {exc.msg}"
        ) from None
    except RecursionError:
        raise DocumentError(TOO_DEEP) from None
    except ValueError as exc:  # an integer of more than sys.get_int_max_str_digits() digits
        raise DocumentError(f"malformed JSON: {_one_line(str(exc))}") from None


def _at(mark: yaml.Mark | None) -> str:
    return "" if mark is None else f" at line {mark.line + 1}, column {mark.column + 1}"


class _JsonLikeLoader(yaml.SafeLoader):
    """PyYAML's SafeLoader held to JSON's data model: string keys, once each; no aliases."""

    def compose_node(self, parent: yaml.Node | None, index: int) -> yaml.Node | None:
        if self.check_event(yaml.AliasEvent):
            mark = self.peek_event().start_mark  # type: ignore[no-untyped-call]
            raise DocumentError(f"YAML alias{_at(mark)}: aliases are not supported; write it out")
        return super().compose_node(parent, index)

    def construct_mapping(self, node: yaml.MappingNode, deep: bool = False) -> dict[Hashable, Any]:
        self.flatten_mapping(node)
        seen: set[str] = set()
        for key_node, _ in node.value:
            key = self.construct_object(key_node, deep=True)
            where = _at(key_node.start_mark)
            if not isinstance(key, str):
                raise DocumentError(f"mapping key {clip(repr(key))}{where} is not a string")
            if key in seen:
                raise DocumentError(f"duplicate key {clip(repr(key))}{where}")
            seen.add(key)
        return super().construct_mapping(node, deep)

    def construct_yaml_float(self, node: yaml.ScalarNode) -> float:
        value = super().construct_yaml_float(node)
        if not math.isfinite(value):
            raise _non_finite(str(node.value), _at(node.start_mark))
        return value


_JsonLikeLoader.add_constructor("tag:yaml.org,2002:float", _JsonLikeLoader.construct_yaml_float)


def _yaml_error(exc: yaml.YAMLError) -> DocumentError:
    if isinstance(exc, yaml.MarkedYAMLError) and exc.problem_mark is not None:
        context = f" ({exc.context})" if exc.context else ""
        return DocumentError(
            f"malformed YAML{_at(exc.problem_mark)}: {_one_line(str(exc.problem))}{context}"
        )
    return DocumentError(f"malformed YAML: {_one_line(str(exc))}")


def _parse_yaml(text: str) -> Any:
    try:
        # A SafeLoader subclass: it builds plain data, never arbitrary objects.
        return yaml.load(text, Loader=_JsonLikeLoader)
    except DocumentError:
        raise
    except yaml.YAMLError as exc:
        raise _yaml_error(exc) from None
    except RecursionError:
        raise DocumentError(TOO_DEEP) from None
    except ValueError as exc:  # an integer of more than sys.get_int_max_str_digits() digits
        raise DocumentError(f"malformed YAML: {_one_line(str(exc))}") from None


_PARSERS: dict[str, Callable[[str], Any]] = {
    ".json": _parse_json,
    ".yaml": _parse_yaml,
    ".yml": _parse_yaml,
}
DOCUMENT_SUFFIXES = tuple(_PARSERS)


def _check_depth(document: Any) -> None:
    """Raises ``DocumentError`` if arrays and objects nest deeper than ``MAX_DEPTH``; iterative."""
    stack = [(document, 1)]
    while stack:
        value, depth = stack.pop()
        if depth > MAX_DEPTH:
            raise DocumentError(TOO_DEEP)
        children = value.values() if isinstance(value, dict) else value
        stack.extend((c, depth + 1) for c in children if isinstance(c, dict | list))


def read_document(path: Path) -> Any:
    """The data of a ``.json``, ``.yaml`` or ``.yml`` file; ``DocumentError`` says why not."""
    parse = _PARSERS.get(path.suffix.lower())
    if parse is None:
        raise DocumentError(
            f"unsupported file type {path.suffix or '(no suffix)'!r}: "
            f"scenario files end in {', '.join(DOCUMENT_SUFFIXES)}"
        )
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise DocumentError(f"cannot read the file: {exc.strerror or exc}") from None
    text = _decode(data)
    if not text.strip():
        raise DocumentError("the file is empty")
    document = parse(text)
    if isinstance(document, dict | list):
        _check_depth(document)
    return document
