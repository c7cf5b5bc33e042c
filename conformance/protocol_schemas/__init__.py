"""The worker protocol's JSON Schemas: one file per message, shipped with the package.

``<call>.request.json`` and ``<call>.response.json`` for every call of
``backends.wire.CALLS``; ``raised.json``, the error answer any call may get;
``request.json``, any request; ``values.json``, the values that cross
(Result, Observation, the batch's steps and answers, as
``conformance.protocol``'s ``to_json`` writes them); ``command.json``, a
Command, generated from the grammar (``command_schema``: the scenario
schema's step rules without ``check``, ``comment`` and ``expect``;
``python -m conformance schema --write`` rewrites it with the scenario
schema, and a test keeps both equal to what they are generated from).

``problem(message, data)`` is what the host asks of every response of an
``exec:`` backend: None if ``data`` is valid, else one line saying where and
why it is not.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Iterator
from functools import cache
from importlib import resources
from pathlib import Path
from typing import Any

import jsonschema
import referencing
import referencing.jsonschema

from conformance._grammar.schema import scenario_schema

__all__ = [
    "COMMAND_SCHEMA",
    "command_schema",
    "message_names",
    "problem",
    "schema",
    "schema_folder",
    "validator",
    "write_command_schema",
]

COMMAND_SCHEMA = "command.json"
#: Where the schemas' ``$id`` s live (a name, not a place to fetch from).
_BASE = "https://example.invalid/drake-filter-conformance/protocol/1/"
#: Step members that are the harness's own, never sent to a backend.
_HARNESS_MEMBERS = ("comment", "expect")


def schema_folder() -> Path:
    """The folder that holds the schema files (inside the installed package)."""
    return Path(str(resources.files(__name__)))


def message_names() -> list[str]:
    """The file names of every schema, sorted."""
    return sorted(p.name for p in schema_folder().glob("*.json"))


@cache
def schema(name: str) -> dict[str, Any]:
    """The schema in file ``name`` (``execute.response.json``)."""
    data: dict[str, Any] = json.loads((schema_folder() / name).read_text(encoding="utf-8"))
    return data


@cache
def _registry() -> referencing.Registry[Any]:
    resources_ = [
        (_BASE + name, referencing.jsonschema.DRAFT202012.create_resource(schema(name)))
        for name in message_names()
    ]
    return referencing.Registry().with_resources(resources_)


@cache
def validator(name: str) -> jsonschema.protocols.Validator:
    """A validator of schema ``name`` that resolves the other files by their ``$id``."""
    return jsonschema.Draft202012Validator(schema(name), registry=_registry())


#: Validators that say least about what is wrong: a leaf error of another kind is preferred.
_WEAK = frozenset({"type", "oneOf", "anyOf", "const", "required"})


def _leaves(errors: Iterable[jsonschema.ValidationError]) -> Iterator[jsonschema.ValidationError]:
    for error in errors:
        if error.context:
            yield from _leaves(error.context)
        else:
            yield error


def problem(name: str, data: Any) -> str | None:
    """None if ``data`` is valid under schema ``name``, else one line: where and why not
    (of the errors inside every branch, the deepest, and there one that is not just a
    wrong type or a missing member).

    The candidate pairs of an observation (thousands, in a real model's scene) are checked
    by ``_pair_problem``, as ``values.json``'s ``location.candidates`` says, and the rest by
    the schema: jsonschema takes about 40 µs a pair.
    """
    slim, bulk = _set_aside_candidates(name, data)
    for where, candidates in bulk:
        wrong = _pair_problem(candidates)
        if wrong is not None:
            return f"{where}{wrong}"
    errors = list(_leaves(validator(name).iter_errors(slim)))
    if not errors:
        return None
    error = max(errors, key=lambda e: (len(e.absolute_path), e.validator not in _WEAK))
    where = "".join(f"[{p!r}]" if isinstance(p, int) else f".{p}" for p in error.absolute_path)
    text = error.message if len(error.message) <= 200 else error.message[:200] + "…"
    return f"{where or '(top level)'}: {text}"


#: Where a message holds an Observation: the path to it, per schema.
_OBSERVATION_AT: dict[str, tuple[str, ...]] = {
    "observe.response.json": ("value",),
    "steps.response.json": ("value", "observation"),
}


def _set_aside_candidates(name: str, data: Any) -> tuple[Any, list[tuple[str, list[Any]]]]:
    """``data`` with every location's candidate list emptied (copies along the way), and the
    lists set aside with where each was; ``data`` itself if it holds no such list."""
    path = _OBSERVATION_AT.get(name)
    if path is None:
        return data, []
    parents = [data]
    for key in path:
        parent = parents[-1]
        if not isinstance(parent, dict) or not isinstance(parent.get(key), dict):
            return data, []
        parents.append(parent[key])
    observation = parents[-1]
    bulk = [
        (f".{'.'.join(path)}.{location}.candidates", state["candidates"])
        for location, state in observation.items()
        if isinstance(state, dict) and isinstance(state.get("candidates"), list)
    ]
    if not bulk:
        return data, []
    slim: Any = {
        location: {**state, "candidates": []} if isinstance(state, dict) else state
        for location, state in observation.items()
    }
    for parent, key in zip(reversed(parents[:-1]), reversed(path), strict=True):
        slim = {**parent, key: slim}
    return slim, bulk


def _pair_problem(candidates: list[Any]) -> str | None:
    """``values.json``'s ``location.candidates``: unique pairs of two names."""
    seen: set[tuple[str, str]] = set()
    for index, pair in enumerate(candidates):
        if not (isinstance(pair, list) and len(pair) == 2 and all(type(n) is str for n in pair)):
            return f"[{index}]: {pair!r} is not a pair of two names"
        if (key := (pair[0], pair[1])) in seen:
            return f": {pair!r} is there twice"
        seen.add(key)
    return None


def _references(value: Any) -> set[str]:
    """The ``#/$defs/<name>`` names that ``value`` refers to."""
    if isinstance(value, dict):
        found = {
            ref.removeprefix("#/$defs/")
            for key, ref in value.items()
            if key == "$ref" and isinstance(ref, str) and ref.startswith("#/$defs/")
        }
        return found.union(*(_references(v) for v in value.values()))
    if isinstance(value, list):
        return set().union(*(_references(v) for v in value))
    return set()


def _wire_rule(rule: dict[str, Any]) -> dict[str, Any]:
    """A step rule of the scenario schema as a Command's: without the harness's members."""
    then = dict(rule["then"])
    then["properties"] = {k: v for k, v in then["properties"].items() if k not in _HARNESS_MEMBERS}
    return {**rule, "then": then}


def command_schema() -> dict[str, Any]:
    """``command.json``: a Command as the host sends it (see the module doc)."""
    scenario = scenario_schema()
    step = scenario["$defs"]["step"]
    ops = [op for op in step["properties"]["op"]["enum"] if op != "check"]
    rules = [
        _wire_rule(rule)
        for rule in step["allOf"]
        if rule["if"]["properties"]["op"]["const"] != "check"
    ]
    body = {
        "type": "object",
        "required": ["op"],
        "properties": {"op": {"enum": ops}},
        "allOf": rules,
    }
    names, todo = set(), _references(body)
    while todo:
        name = todo.pop()
        names.add(name)
        todo |= _references(scenario["$defs"][name]) - names
    return {
        "$schema": scenario["$schema"],
        "$id": _BASE + COMMAND_SCHEMA,
        "title": "Command",
        "description": "Command.to_json(): one op of the scenario grammar and its arguments, "
        "by name. Generated from conformance._grammar (python -m conformance schema --write): "
        "do not edit by hand.",
        **body,
        "$defs": {name: scenario["$defs"][name] for name in sorted(names)},
    }


def write_command_schema(path: Path | None = None) -> Path:
    """Writes ``command_schema()`` to ``path`` (default: the shipped file)."""
    target = path or schema_folder() / COMMAND_SCHEMA
    target.write_text(json.dumps(command_schema(), indent=2) + "\n", encoding="utf-8")
    return target
