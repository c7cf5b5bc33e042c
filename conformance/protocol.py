"""The protocol: what an implementation under test provides, and the values that cross it.

A backend executes scenario commands, which refer to everything by *name*
(sources, frames, geometries, contexts, declaration labels), and reports the
canonical observable state. Because nothing crosses the boundary but names,
booleans and strings, a backend can live in this process (``reimpl``,
``pydrake``), in another Python environment, or in another language.

Observable state, compared pair by pair (collision_filter.h, "two filters are
equivalent iff they report the same CanCollideWith for every pair"):

- candidate pairs, as sorted name pairs, for the model and for every context;
- for every declaration label, whether its FilterId is active, per location;
- ``has_transient_history()`` per location;
- ``CollisionFiltered`` on a sample of geometry pairs per location
  (``sample_pairs``: every registered name, removed, non-proximity and world
  geometry included), a bool or the normalised message of its error;
- the inspector's counts per location (``LocationState.counts``);
- at the model, the last Parser's collision filter group report;
- errors as (kind, message), with id values normalised out of the message.

The last three are optional: a backend that does not report them (None) is
not compared on them (``compare``).

Write a third-party backend as a class with these methods (no base class is
required) and load it with ``--backend package.module:attribute``, where the
attribute is the class or a zero-argument factory.
"""

from __future__ import annotations

import enum
import re
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

__all__ = [
    "MODEL",
    "Backend",
    "BackendId",
    "BatchingBackend",
    "Command",
    "ErrorInfo",
    "ErrorKind",
    "LocationState",
    "Observation",
    "Pair",
    "Result",
    "UnknownNameError",
    "backend_id",
    "classify_assertion",
    "classify_error",
    "normalise_message",
    "sample_pairs",
]

#: The location name of the model (contexts are named by the scenario).
MODEL = "model"

Pair = tuple[str, str]


class UnknownNameError(KeyError):
    """A command names a source, frame, geometry, context or label that no earlier command made.

    An input error in the scenario (or the fuzz sequence), not a backend
    fault: any backend may raise it from ``execute``.
    """

    def __init__(self, kind: str, name: str) -> None:
        super().__init__(f"unknown {kind} name {name!r}")
        self.kind = kind
        self.name = name
        #: The step that named it (``step 3 (apply)``), added by the runner.
        self.where: str | None = None

    def __str__(self) -> str:
        return str(self.args[0])


class ErrorKind(enum.Enum):
    """What went wrong, independent of the exact wording or the exception class."""

    UNKNOWN_GEOMETRY = "unknown_geometry"
    UNKNOWN_FRAME = "unknown_frame"
    UNKNOWN_SOURCE = "unknown_source"
    TRANSIENT_HISTORY = "transient_history"
    DUPLICATE_ROLE = "duplicate_role"
    MISSING_ROLE = "missing_role"
    NOT_OWNED = "not_owned"
    INVALID_QUERY = "invalid_query"
    BINDING = "binding"  # TypeError: no overload accepts the arguments.
    REFUSED = "refused"  # The harness would not send this call (it crashes some release).
    #: A DRAKE_DEMAND failed: pydrake raises SystemExit("Failure at <file>:<line> in <fn>():
    #: condition '...' failed."), and reimpl imitates it (``classify_assertion``).
    ASSERTION = "assertion"
    OTHER = "other"


# Message prefixes (after normalisation), checked in order; the first match names the kind.
_KIND_BY_PREFIX: tuple[tuple[str, ErrorKind], ...] = (
    ("Geometry set includes a geometry id that doesn't belong", ErrorKind.UNKNOWN_GEOMETRY),
    ("Referenced geometry #", ErrorKind.UNKNOWN_GEOMETRY),
    ("Referenced frame #", ErrorKind.UNKNOWN_FRAME),
    ("Referenced geometry source #", ErrorKind.UNKNOWN_SOURCE),
    ("You cannot attempt to modify the persistent collision filter", ErrorKind.TRANSIENT_HISTORY),
    ("Trying to assign the '", ErrorKind.DUPLICATE_ROLE),
    ("Trying to replace the properties", ErrorKind.MISSING_ROLE),
    ("Can't report collision filter status", ErrorKind.INVALID_QUERY),
    ("Given geometry id # does not belong", ErrorKind.NOT_OWNED),
    ("Frame id # does not belong", ErrorKind.NOT_OWNED),
)

#: A model file's position (``r.urdf:7:``, ``<data-string>:7:``, ``r.sdf:7:3:``), kept
#: as it is, or else an integer (an id value).
_POSITION_OR_ID = re.compile(r"((?:\.\w+|>):\d+(?::\d+)?:)|\b\d+\b")


def normalise_message(message: str) -> str:
    """Replaces id values (every integer but a model file's line) with ``#``: ids differ
    between runs; lines in a model file do not, and name the element."""
    return _POSITION_OR_ID.sub(lambda m: m.group(1) or "#", message.strip())


#: How pydrake's SystemExit for a failed DRAKE_DEMAND begins.
ASSERTION_PREFIX = "Failure at "


def classify_assertion(exception: SystemExit) -> ErrorInfo | None:
    """The ErrorInfo of a SystemExit that reports a failed DRAKE_DEMAND, else None (a real
    exit, which no backend may answer with)."""
    message = str(exception)
    if not message.startswith(ASSERTION_PREFIX):
        return None
    return ErrorInfo(ErrorKind.ASSERTION, normalise_message(message))


def classify_error(exception: BaseException) -> ErrorInfo:
    """Maps an exception from any backend to its (kind, normalised first line, normalised
    further lines)."""
    first, _, rest = str(exception).partition("\n")
    message, detail = normalise_message(first), normalise_message(rest)
    if isinstance(exception, TypeError):
        return ErrorInfo(ErrorKind.BINDING, message)
    for prefix, kind in _KIND_BY_PREFIX:
        if message.startswith(prefix):
            return ErrorInfo(kind, message, detail)
    return ErrorInfo(ErrorKind.OTHER, message, detail)


@dataclass(frozen=True)
class ErrorInfo:
    """An error: its kind, its message's first line (what reports show and what a case's
    expectation matches), and its further lines (``detail``: Drake's report of what was
    wrong, e.g. both definitions of a redefined material), each with ids written ``#``.
    Two backends' errors agree when all three do (``compare``)."""

    kind: ErrorKind
    message: str
    detail: str = ""

    def to_json(self) -> dict[str, str]:
        data = {"kind": self.kind.value, "message": self.message}
        if self.detail:
            data["detail"] = self.detail
        return data

    @classmethod
    def from_json(cls, data: Mapping[str, str]) -> ErrorInfo:
        return cls(ErrorKind(data["kind"]), data.get("message", ""), data.get("detail", ""))


@dataclass(frozen=True)
class Result:
    """What one command did: a return value, or an error."""

    value: Any = None
    error: ErrorInfo | None = None

    def to_json(self) -> dict[str, Any]:
        if self.error is not None:
            return {"error": self.error.to_json()}
        return {"value": self.value}

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> Result:
        if "error" in data:
            return cls(error=ErrorInfo.from_json(data["error"]))
        return cls(value=data.get("value"))


#: At most this many pairs in ``sample_pairs``.
SAMPLE_PAIRS = 32


def sample_pairs(names: Sequence[str], limit: int = SAMPLE_PAIRS) -> list[Pair]:
    """The geometry pairs whose ``CollisionFiltered`` a backend reports, by name.

    With ``g_0 < ... < g_{n-1}`` the sorted names (every geometry name a
    command made: removed, non-proximity, anchored and context-only ones
    too), the ring ``(g_i, g_{i+1 mod n})``, each pair once (as ``(a, b)``
    with ``a < b``), the first ``limit``. Every name is in a pair while
    ``n <= limit``. Depends on the names alone, so every backend asks the
    same pairs. (A ring, not every pair: each CollisionFiltered that raises
    costs pydrake about 10 µs, and the candidate set already decides every
    pair of proximity geometries.)
    """
    ordered = sorted(set(names))
    pairs: dict[Pair, None] = {}
    for i, a in enumerate(ordered):
        b = ordered[(i + 1) % len(ordered)]
        if a != b:
            pairs[(a, b) if a < b else (b, a)] = None
    return list(pairs)[:limit]


#: A sampled CollisionFiltered answer: the bool, or the normalised message of its error.
Filtered = bool | str


@dataclass(frozen=True)
class LocationState:
    """The observable filter state of the model or of one context.

    ``filtered``: ``CollisionFiltered`` of the ``sample_pairs`` (a bool, or
    ``"error: <normalised message>"``). ``counts``: the inspector's counts
    (``num_sources``, ``num_frames``, ``num_geometries``, anchored, dynamic,
    per role, per frame, per source; an int or ``"error: ..."``; and under
    ``"GetCollisionCandidates"`` its error, when it raises, with ``candidates``
    then empty: a failed parse can leave a geometry that Drake's engine lacks).
    ``filter_groups``: at the model, the last Parser's
    ``GetCollisionFilterGroups()`` as the ``collision_filter_groups`` op
    returns it. Each is None when the backend does not report it.
    """

    candidates: frozenset[Pair]
    has_transient_history: bool
    active: Mapping[str, bool] = field(default_factory=dict)
    filtered: Mapping[Pair, Filtered] | None = None
    counts: Mapping[str, int | str] | None = None
    filter_groups: Mapping[str, Any] | None = None

    def to_json(self) -> dict[str, Any]:
        data: dict[str, Any] = {
            "candidates": sorted(list(p) for p in self.candidates),
            "has_transient_history": self.has_transient_history,
            "active": dict(sorted(self.active.items())),
        }
        if self.filtered is not None:
            data["filtered"] = [[a, b, v] for (a, b), v in sorted(self.filtered.items())]
        if self.counts is not None:
            data["counts"] = dict(sorted(self.counts.items()))
        if self.filter_groups is not None:
            data["filter_groups"] = dict(self.filter_groups)
        return data

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> LocationState:
        filtered = data.get("filtered")
        counts = data.get("counts")
        groups = data.get("filter_groups")
        return cls(
            candidates=frozenset((a, b) if a < b else (b, a) for a, b in data["candidates"]),
            has_transient_history=bool(data["has_transient_history"]),
            active={str(k): bool(v) for k, v in data.get("active", {}).items()},
            filtered=None
            if filtered is None
            else {((a, b) if a < b else (b, a)): v for a, b, v in filtered},
            counts=None if counts is None else dict(counts),
            filter_groups=None if groups is None else dict(groups),
        )


@dataclass(frozen=True)
class Observation:
    """The canonical state of a backend: one LocationState per location."""

    locations: Mapping[str, LocationState]

    def to_json(self) -> dict[str, Any]:
        return {name: state.to_json() for name, state in sorted(self.locations.items())}

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> Observation:
        return cls({name: LocationState.from_json(state) for name, state in data.items()})


@dataclass(frozen=True)
class Command:
    """One scenario command: ``op`` plus its arguments, all by name."""

    op: str
    args: Mapping[str, Any]

    def to_json(self) -> dict[str, Any]:
        return {"op": self.op, **self.args}

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> Command:
        return cls(str(data["op"]), {k: v for k, v in data.items() if k != "op"})


@dataclass(frozen=True)
class BackendId:
    """Who answered: the backend's name and the Drake release whose behaviour it has.

    ``version`` selects since/until expectations, known divergences and
    release guards. It is ``"unknown"`` for an implementation that claims no
    Drake release.
    """

    name: str
    version: str

    def __str__(self) -> str:
        return f"{self.name} ({self.version})"

    def to_json(self) -> dict[str, str]:
        return {"name": self.name, "version": self.version}

    @classmethod
    def from_json(cls, data: Mapping[str, str]) -> BackendId:
        return cls(data["name"], data["version"])


@runtime_checkable
class Backend(Protocol):
    """An implementation under test.

    ``reset`` starts a fresh, empty SceneGraph. ``execute`` runs one command and
    never raises for a failure of the implementation: it returns the error in
    the Result. ``observe`` reports the canonical state. ``features`` names the
    scenario feature tags the backend supports (e.g. ``"activation"``), so
    cases that need more are skipped rather than failed.
    """

    name: str

    def version(self) -> str: ...

    def features(self) -> frozenset[str]: ...

    def reset(self) -> None: ...

    def execute(self, command: Command) -> Result: ...

    def observe(self) -> Observation: ...


@runtime_checkable
class BatchingBackend(Backend, Protocol):
    """A backend that answers a sequence of steps in one request (a worker in its own
    process): ``run_steps`` yields, per ``(command, observe)``, the Result (an empty one for
    a None command) and the Observation after it if ``observe`` (else None), as they come."""

    def run_steps(
        self, steps: Sequence[tuple[Command | None, bool]]
    ) -> Iterator[tuple[Result, Observation | None]]: ...


def backend_id(backend: Backend) -> BackendId:
    """The BackendId of ``backend`` (its ``name`` and ``version()``)."""
    return BackendId(backend.name, backend.version())
