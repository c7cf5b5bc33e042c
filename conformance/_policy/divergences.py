"""Known divergences, as data (``known_divergences.json``), and the matcher that acts on them.

Each entry records one finding: what Drake documents, what it does, the
releases it holds for, and the scenarios or tests that show it. Its kind is one of

- ``doc_vs_drake``: the documentation says one thing, Drake does another;
- ``release_change``: releases differ (the release fact it names says how);
- ``drake_crash``: the call ends the process on some releases (a crash row,
  which the release guards name);
- ``reimpl_vs_drake``: reimpl knowingly differs from every release.

An entry about a release fact names its row (``release_fact``: an id of
``release_facts.json``), whose range is the entry's; any other gives the
releases it was measured on (``drake``). An entry may
also say when a failure is *expected* (its ``xfail`` object):

- ``backends``: ``fnmatch`` patterns of the backends that may fail this way (the one
  blamed; empty: any), e.g. ``drake==*`` for every release in a worker;
- ``backend_drake``: the releases the blamed backend must claim (its
  ``version()``), e.g. ``{"until": "1.51.1"}`` for any backend that follows
  1.51.1, reimpl and the mutants built on it alike;
- ``steps``: patterns of the diverging step: ``op`` (one of),
  ``reference_error`` (whether the reference raised), ``reference_kinds``
  (the error kinds it may have raised), ``reference_message`` (a prefix of
  its error message), ``backend_error`` (whether the blamed backend raised
  too), ``backend_kinds`` (the error kinds the blamed backend may have
  raised), ``backend_broke`` (whether the blamed backend broke at the step:
  crashed, timed out), ``boundary_pairs`` (true: the two answers of a pairwise
  signed distance query differ only in pairs at its ``max_distance``, as
  ``at_max_distance`` says). A field about the reference does not match where
  no reference answered (a backend run alone); ``backend_broke`` false and
  the backend fields do not match where the backend broke;
- ``cases``: ``fnmatch`` patterns of case qualified names (``file > description``),
  a narrowing filter: where a case is run (``run``), it must be one of them;
  the fuzzer, which has no case name, matches the step patterns alone;
- ``drake``: the releases it applies to, if narrower than the entry's.

The release checked is that of the run's reference backend: the Drake
release whose behaviour the others are held to. Both ``run`` and ``fuzz``
match through ``match_step`` (the engine's steps): a case whose first failure
on a backend is at a step an entry's pattern matches is reported as
``xfail`` with the entry's id, not as a failure; ``--strict-divergences``
turns it back into one.
"""

from __future__ import annotations

import fnmatch
import json
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cache
from importlib import resources
from typing import Any

from conformance._policy.at_max_distance import differs_only_at_max_distance
from conformance._policy.release_facts import release_fact
from conformance._policy.versions import VersionRange
from conformance.protocol import BackendId, Command, Result

__all__ = [
    "KnownDivergence",
    "StepPattern",
    "XfailMatcher",
    "divergence",
    "known_divergences",
    "match_step",
]


@dataclass(frozen=True)
class StepPattern:
    """A diverging step: its op is one of ``ops``; the answers as given (see the module doc)."""

    ops: frozenset[str]
    reference_error: bool | None = None
    reference_kinds: frozenset[str] = frozenset()
    reference_message: str | None = None
    backend_error: bool | None = None
    backend_kinds: frozenset[str] = frozenset()
    backend_broke: bool | None = None
    boundary_pairs: bool | None = None

    def matches(self, command: Command, reference: Result | None, backend: Result | None) -> bool:
        """``reference``: None where no reference answered; ``backend``: None where it broke."""
        if command.op not in self.ops:
            return False
        if self.backend_broke is not None and (backend is None) != self.backend_broke:
            return False
        if self.boundary_pairs is not None and self.boundary_pairs != (
            differs_only_at_max_distance(command, reference, backend)
        ):
            return False
        return self._reference_matches(reference) and self._backend_matches(backend)

    def _reference_matches(self, reference: Result | None) -> bool:
        asks = (self.reference_error, self.reference_kinds, self.reference_message)
        if reference is None:
            return asks == (None, frozenset(), None)
        error = reference.error
        return all(
            (
                self.reference_error is None or (error is not None) == self.reference_error,
                not self.reference_kinds
                or (error is not None and error.kind.value in self.reference_kinds),
                self.reference_message is None
                or (error is not None and error.message.startswith(self.reference_message)),
            )
        )

    def _backend_matches(self, backend: Result | None) -> bool:
        if backend is None:
            return self.backend_error is None and not self.backend_kinds
        error = backend.error
        return all(
            (
                self.backend_error is None or (error is not None) == self.backend_error,
                not self.backend_kinds
                or (error is not None and error.kind.value in self.backend_kinds),
            )
        )


def _names(backend: str, pattern: str) -> bool:
    """Whether ``pattern`` names the backend: its name, or the implementation a release
    spec runs (``reimpl`` names ``reimpl==1.58.0`` too: the same reimpl, following 1.58.0)."""
    implementation = backend.split("==", 1)[0]
    return fnmatch.fnmatchcase(backend, pattern) or fnmatch.fnmatchcase(implementation, pattern)


@dataclass(frozen=True)
class XfailMatcher:
    """When a failure is this divergence (see the module doc)."""

    releases: VersionRange
    backends: frozenset[str] = frozenset()
    cases: tuple[str, ...] = ()
    steps: tuple[StepPattern, ...] = ()
    backend_releases: VersionRange = field(default_factory=VersionRange)

    def _applies(self, blamed: BackendId, release: str) -> bool:
        return (
            release in self.releases
            and blamed.version in self.backend_releases
            and (not self.backends or any(_names(blamed.name, b) for b in self.backends))
        )

    def matches_step(
        self,
        command: Command,
        reference: Result | None,
        backend: Result | None,
        *,
        blamed: BackendId,
        release: str,
        case: str | None = None,
    ) -> bool:
        return (
            self._applies(blamed, release)
            and (
                case is None
                or not self.cases
                or any(fnmatch.fnmatchcase(case, pattern) for pattern in self.cases)
            )
            and any(step.matches(command, reference, backend) for step in self.steps)
        )


@dataclass(frozen=True)
class KnownDivergence:
    """One finding: what Drake documents, what it does, and where that is shown."""

    id: str
    kind: str  # doc_vs_drake | release_change | drake_crash | reimpl_vs_drake
    releases: VersionRange
    observed: str
    reason: str
    scenarios: tuple[str, ...]
    tests: tuple[str, ...]
    xfail: XfailMatcher | None = None
    #: The release fact the entry is about (its row in ``release_facts.json``), if any.
    release_fact: str | None = None

    @property
    def since(self) -> str | None:
        return self.releases.since

    @property
    def until(self) -> str | None:
        return self.releases.until


def _range(data: Mapping[str, Any]) -> VersionRange:
    return VersionRange(data.get("since"), data.get("until"))


def _matcher(data: Mapping[str, Any] | None, releases: VersionRange) -> XfailMatcher | None:
    if data is None:
        return None
    return XfailMatcher(
        releases=_range(data["drake"]) if "drake" in data else releases,
        backends=frozenset(data.get("backends", ())),
        backend_releases=_range(data.get("backend_drake", {})),
        cases=tuple(data.get("cases", ())),
        steps=tuple(
            StepPattern(
                ops=frozenset(step["op"]),
                reference_error=step.get("reference_error"),
                reference_kinds=frozenset(step.get("reference_kinds", ())),
                reference_message=step.get("reference_message"),
                backend_error=step.get("backend_error"),
                backend_kinds=frozenset(step.get("backend_kinds", ())),
                backend_broke=step.get("backend_broke"),
                boundary_pairs=step.get("boundary_pairs"),
            )
            for step in data.get("steps", ())
        ),
    )


@cache
def known_divergences() -> tuple[KnownDivergence, ...]:
    data: dict[str, Any] = json.loads(
        resources.files("conformance._policy").joinpath("known_divergences.json").read_text()
    )
    entries = []
    for e in data["entries"]:
        fact = e.get("release_fact")
        releases = release_fact(fact).releases if fact is not None else _range(e["drake"])
        entries.append(
            KnownDivergence(
                id=e["id"],
                kind=e["kind"],
                releases=releases,
                observed=e["observed"],
                reason=e["reason"],
                scenarios=tuple(e["evidence"].get("scenarios", ())),
                tests=tuple(e["evidence"].get("tests", ())),
                xfail=_matcher(e.get("xfail"), releases),
                release_fact=fact,
            )
        )
    return tuple(entries)


@cache
def divergence(divergence_id: str) -> KnownDivergence:
    """The known divergence with this id (KeyError if there is none)."""
    for entry in known_divergences():
        if entry.id == divergence_id:
            return entry
    raise KeyError(f"no known divergence {divergence_id!r}")


def _first(
    entries: Sequence[KnownDivergence] | None, matches: Callable[[XfailMatcher], bool]
) -> KnownDivergence | None:
    for entry in known_divergences() if entries is None else entries:
        if entry.xfail is not None and matches(entry.xfail):
            return entry
    return None


def match_step(
    command: Command,
    reference: Result | None,
    backend: Result | None,
    *,
    blamed: BackendId,
    release: str,
    case: str | None = None,
    entries: Sequence[KnownDivergence] | None = None,
) -> KnownDivergence | None:
    """The known divergence that a disagreement of ``blamed`` on ``command`` is, if any.

    ``reference``/``backend``: their Results (None: no reference answered; the
    backend broke); ``case``: the case's qualified name, where a case is run.
    """
    return _first(
        entries,
        lambda x: x.matches_step(
            command, reference, backend, blamed=blamed, release=release, case=case
        ),
    )
