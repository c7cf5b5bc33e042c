"""A scenario case from a sequence of commands and the answers a backend gave them.

``case_of`` writes each step's expectations from the *reference*'s answers:
every step where it raised gets an ``error`` expectation (kind and message),
every step that returned a value gets ``returns``, and the last step also
records the reference's whole state: C, history and IsActive, at every
location. Run on the backends that gave the answers, the case reproduces
their disagreement pair by pair.

**Two Drake releases.** When the two sides are different Drake releases
(``releases``: the reference's and the other's), neither answer is wrong,
the releases differ. Every step where they answered differently gets both
answers: the earlier release's bounded by ``until: <earlier>``, the later
one's by ``since: <later>`` (a step where they agree keeps one unbounded
expectation). The case then passes on each release alone, and the pair
still disagrees.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from conformance._grammar import GRAMMAR
from conformance._policy.versions import parse_version
from conformance.protocol import Command, Observation, Result

__all__ = ["case_of"]


def _result_expectation(op: str, result: Result) -> dict[str, Any]:
    """``error``, or ``returns`` for a bool, an int, or any value of a query op (a list of
    records, a pose) or a model op (the model instances a parse made, a group report, an
    inventory), which ``run`` compares as the op's ``CommandSpec.compare`` says."""
    if result.error is not None:
        return {"error": result.error.to_json()}
    if isinstance(result.value, bool | int) or (
        result.value is not None and GRAMMAR[op].domain in ("queries", "model")
    ):
        return {"returns": result.value}
    return {}


def _state_expectations(state: Observation) -> list[dict[str, Any]]:
    out = []
    for location, where in sorted(state.locations.items()):
        out.append(
            {
                "at": location,
                "candidates": sorted([a, b] for a, b in where.candidates),
                "history": where.has_transient_history,
                **({"active": dict(sorted(where.active.items()))} if where.active else {}),
            }
        )
    return out


def _step_expectations(op: str, result: Result, state: Observation | None) -> list[dict[str, Any]]:
    """One side's expectations for a step: its result, then (last step) its whole state.

    An expectation without ``error`` says the step succeeded, so when the
    step raised, each location's expectation repeats the error.
    """
    expectations = [_result_expectation(op, result)]
    if state is not None:
        error = {"error": result.error.to_json()} if result.error is not None else {}
        located = [{**error, **where} for where in _state_expectations(state)]
        expectations = [{**expectations[0], **located[0]}, *located[1:]]
    return [e for e in expectations if e]


def _expect(
    reference: list[dict[str, Any]],
    backend: list[dict[str, Any]],
    releases: tuple[str, str] | None,
) -> list[dict[str, Any]]:
    """The step's expectations: the reference's, or both releases' where they differ.

    ``releases`` is (reference's, backend's) release when the two are
    different Drake releases. What both answered stays unbounded; what only
    the earlier release answered gets ``until`` it, what only the later one
    answered ``since`` it (each keeps its ``at``).
    """
    if releases is None or reference == backend:
        return reference
    ordered = sorted(zip(releases, (reference, backend), strict=True), key=_release_key)
    (early, early_side), (late, late_side) = ordered
    if len(early_side) != len(late_side) or any(
        old.get("at") != new.get("at") for old, new in zip(early_side, late_side, strict=True)
    ):  # different locations (e.g. a context only one side has): each side whole
        return [{"until": early, **e} for e in early_side] + [
            {"since": late, **e} for e in late_side
        ]
    shared: list[dict[str, Any]] = []
    earlier: list[dict[str, Any]] = []
    later: list[dict[str, Any]] = []
    for old, new in zip(early_side, late_side, strict=True):
        common = {k: v for k, v in old.items() if k in new and new[k] == v}
        where = {"at": old["at"]} if "at" in old else {}
        if set(common) - {"at"}:
            shared.append(common)
        for side, bound, into in ((old, {"until": early}, earlier), (new, {"since": late}, later)):
            own = {k: v for k, v in side.items() if k not in common}
            if own:  # without its error it would say the step succeeded there
                error = {"error": side["error"]} if "error" in side else {}
                into.append({**bound, **where, **error, **own})
    return shared + earlier + later


def _release_key(side: tuple[str, list[dict[str, Any]]]) -> tuple[int, ...]:
    return parse_version(side[0])


def case_of(
    description: str,
    commands: Sequence[Command],
    results: Mapping[str, Sequence[Result]],
    states: Mapping[str, Observation | None],
    *,
    releases: tuple[str, str] | None = None,
) -> dict[str, Any]:
    """The case (a JSON-able dict) of ``commands``, with expectations from the answers.

    ``results`` and ``states`` hold, by side, each step's Result and the
    state after the last step; the first side is the reference. With
    ``releases`` (the reference's and the other side's Drake release), each
    release's own answers where they differ (see the module doc).
    """
    sides = list(results)
    steps: list[dict[str, Any]] = []
    for index, command in enumerate(commands):
        step = command.to_json()
        last = index + 1 == len(commands)
        answers = [
            _step_expectations(command.op, results[side][index], states.get(side) if last else None)
            for side in sides
        ]
        expectations = answers[0]
        if len(answers) > 1:
            expectations = _expect(answers[0], answers[1], releases)
        if expectations:
            step["expect"] = expectations[0] if len(expectations) == 1 else expectations
        steps.append(step)
    return {"description": description[:150], "steps": steps}
