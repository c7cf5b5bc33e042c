"""The scenario schema, with its step rules generated from ``GRAMMAR``.

``scenarios/scenario.schema.json`` is the published, language-agnostic
schema. Its shared definitions (names, sets, declarations, expectations,
cases) are written by hand; its ``$defs.step`` is generated here from the
grammar table: the op enum, and per op an ``if``/``then`` rule listing the
op's arguments, the required ones, the one-of groups and the keys that need
others. The value kinds of ``grammar.queries`` (``$defs.shape``, ``pose``,
``poses``) are generated from its tables too. The feature tags
(``$defs.features``) are the hand-written ones
(``scope``, ``errors``, ``quirk``: what a case is about) followed by every
op's tag that is not among them. ``scenario_schema()``
is what the corpus validates against; ``python -m conformance schema --write``
writes it back to the file, and a test asserts that the file is up to date.
"""

from __future__ import annotations

import json
from functools import cache
from pathlib import Path
from typing import Any

from conformance._corpus_root import corpus_root
from conformance._grammar import GRAMMAR, CommandSpec
from conformance._grammar.queries import DEFINITIONS
from conformance.protocol import ErrorKind

__all__ = [
    "SCHEMA_FILE",
    "feature_tags",
    "scenario_schema",
    "schema_path",
    "step_schema",
    "write_schema",
]

SCHEMA_FILE = "scenario.schema.json"

#: Keys every step may have besides its arguments.
_COMMON = {"op": True, "comment": True, "expect": True}


def schema_path() -> Path:
    """The published schema file, in the embedded corpus (``_corpus_root.corpus_root``)."""
    return corpus_root() / SCHEMA_FILE


def _rule(command: CommandSpec) -> dict[str, Any]:
    then: dict[str, Any] = {}
    required = [arg.key for arg in command.args if arg.required]
    if command.harness_only:
        required.append("expect")
    if required:
        then["required"] = required
    if command.one_of:
        (group,) = command.one_of
        then["oneOf"] = [{"required": [key]} for key in group]
    if command.needs:
        then["dependentRequired"] = {key: list(keys) for key, keys in command.needs}
    then["properties"] = {**_COMMON, **{arg.key: arg.kind.schema for arg in command.args}}
    then["additionalProperties"] = False
    return {"if": {"properties": {"op": {"const": command.op}}}, "then": then}


def step_schema() -> dict[str, Any]:
    """``$defs.step``: one command of the grammar, with its expectations."""
    return {
        "description": "One command. Generated from conformance._grammar: do not edit by hand.",
        "type": "object",
        "required": ["op"],
        "properties": {
            "op": {"enum": list(GRAMMAR)},
            "comment": {"type": "string"},
            "expect": {"$ref": "#/$defs/expect"},
        },
        "allOf": [_rule(command) for command in GRAMMAR.values()],
    }


def feature_tags(written: list[str]) -> list[str]:
    """``written`` followed by the grammar's feature tags that it lacks, in grammar order."""
    tags = list(written)
    for command in GRAMMAR.values():
        if command.feature not in tags:
            tags.append(command.feature)
    return tags


@cache
def scenario_schema() -> dict[str, Any]:
    """The whole schema: the published file's definitions with the generated step rules."""
    schema: dict[str, Any] = json.loads(schema_path().read_text(encoding="utf-8"))
    schema["$defs"].update(DEFINITIONS)
    schema["$defs"]["step"] = step_schema()
    features = schema["$defs"]["features"]["items"]
    features["enum"] = feature_tags(features["enum"])
    error = schema["$defs"]["expectation"]["properties"]["error"]["properties"]
    error["kind"]["enum"] = [kind.value for kind in ErrorKind]
    return schema


def write_schema(path: Path | None = None) -> Path:
    """Writes ``scenario_schema()`` to ``path`` (default: the published file)."""
    target = path or schema_path()
    target.write_text(json.dumps(scenario_schema(), indent=2) + "\n", encoding="utf-8")
    return target
