"""A step's expectations, checked against one backend's Result and Observation.

An expectation holds for a backend only if the backend's Drake release lies
in its ``since``/``until`` range and on the side of the release fact it names
(``release_fact``: ``"<id>"``, ``"before <id>"`` or ``"after <id>"``, a row
of ``policy/release_facts.json``): ``applies``. An expectation of a refusal that names a
crash row (``refused (<id>)``, a release guard's message) describes a run
whose guard was armed; where it was not (a worker) and the backend gave the
row's answer instead (``policy.release_facts.crash_answer``), the call was
made and the expectation does not apply. ``check`` yields ``(what, expected,
actual)`` for every part that does not hold: the error kind and message
prefix (the part an op's ``error_choice`` matches may name any choice), the
return value (compared as the op's ``CommandSpec.compare`` says:
``compare.value_differences``, within tolerances for query values), and at
the location ``at`` (default: the step's
context, else the model) the exact candidate set, pairs that must be
filtered or unfiltered, IsActive per label and ``has_transient_history``.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator, Mapping, Sequence
from typing import Any

from conformance._corpus.loader import Step
from conformance._policy.release_facts import crash_answer, fact_side
from conformance._policy.versions import version_in_range
from conformance.compare import comparable_message, format_pairs, value_differences
from conformance.protocol import (
    MODEL,
    ErrorKind,
    LocationState,
    Observation,
    Pair,
    Result,
    normalise_message,
)

__all__ = ["applies", "check"]


def applies(expectation: Mapping[str, Any], version: str) -> bool:
    """Whether ``expectation`` holds for a backend of Drake ``version`` (see the module doc)."""
    if not version_in_range(version, expectation.get("since"), expectation.get("until")):
        return False
    references = expectation.get("release_fact", ())
    if isinstance(references, str):
        references = (references,)
    return all(fact.on_side(version, side) for fact, side in map(fact_side, references))


def _pairs(raw: Iterable[Sequence[str]]) -> frozenset[Pair]:
    return frozenset((a, b) if a < b else (b, a) for a, b in raw)


#: The path prefix of the files a failed DRAKE_DEMAND names in some releases.
_DEMAND_PATH = "external/drake+/"
#: A release guard's refusal: ``refused (<crash row id>): ...``.
_REFUSAL = re.compile(r"^refused \(([a-z0-9.-]+)\)")


def _answered_unguarded(op: str, expectation: Mapping[str, Any], result: Result) -> bool:
    """Whether ``expectation`` expects a refusal naming a crash row and ``result`` is that
    row's answer instead (no guard refused the call)."""
    expected = expectation.get("error") or {}
    refusal = _REFUSAL.match(expected.get("message", ""))
    if expected.get("kind") != ErrorKind.REFUSED.value or refusal is None or result.error is None:
        return False
    answer = crash_answer(refusal.group(1))
    if answer is None or result.error.kind.value != answer["kind"]:
        return False
    # The failed DRAKE_DEMAND's path is the release's own (demand-path-external-since-...).
    got, want = (
        comparable_message(op, normalise_message(m)).replace(_DEMAND_PATH, "")
        for m in (result.error.message, answer["message"])
    )
    return got.startswith(want)


def _check_result(
    op: str, expectation: Mapping[str, Any], result: Result
) -> Iterator[tuple[str, Any, Any]]:
    error = expectation.get("error")
    if error is not None:
        actual = result.error.to_json() if result.error else "no error"
        if result.error is None or result.error.kind.value != error["kind"]:
            yield "error", error, actual
        elif not comparable_message(op, result.error.message).startswith(
            comparable_message(op, normalise_message(error.get("message", "")))
        ):
            yield "error message prefix", error, actual
    elif result.error is not None:
        yield "no error", None, result.error.to_json()
    if "returns" in expectation and result.error is None:
        details = value_differences(op, expectation["returns"], result.value)
        if details:
            shown = "" if details == ["values differ"] else f" ({'; '.join(details)})"
            yield f"return value{shown}", expectation["returns"], result.value


def _check_state(
    expectation: Mapping[str, Any], at: str, state: LocationState
) -> Iterator[tuple[str, Any, Any]]:
    if "candidates" in expectation:
        expected = _pairs(expectation["candidates"])
        if state.candidates != expected:
            yield f"candidates at {at}", format_pairs(expected), format_pairs(state.candidates)
    for key, want_in in (("filtered", False), ("unfiltered", True)):
        for pair in _pairs(expectation.get(key, ())):
            if (pair in state.candidates) != want_in:
                yield f"{'-'.join(pair)} {key} at {at}", want_in, not want_in
    for label, active in expectation.get("active", {}).items():
        if state.active.get(label) != active:
            yield f"IsActive({label}) at {at}", active, state.active.get(label)
    if "history" in expectation and state.has_transient_history != expectation["history"]:
        yield f"has_transient_history at {at}", expectation["history"], state.has_transient_history


def check(
    step: Step, expectation: Mapping[str, Any], result: Result, observation: Observation
) -> Iterator[tuple[str, Any, Any]]:
    """(what, expected, actual) for every part of ``expectation`` that does not hold."""
    if _answered_unguarded(step.op, expectation, result):
        return
    yield from _check_result(step.op, expectation, result)
    at = expectation.get("at", step.args.get("context", MODEL))
    state = observation.locations.get(at)
    if state is None:
        yield f"location {at!r} exists", at, sorted(observation.locations)
    else:
        yield from _check_state(expectation, at, state)
