"""Each backend's outcome in a case: pass, fail, xfail (a known divergence), skip or broken.

``judge`` gives every backend of a finished case its ``Outcome``:

| the backend's track                         | outcome                          |
|---------------------------------------------|----------------------------------|
| broke (raised, timed out, its worker died)  | ERROR / TIMEOUT / CRASH          |
|   ... an isolated crash its release's crash row records | PASS (``recorded``)   |
|   ... an isolated crash a divergence expects| XFAIL                            |
| no failures                                 | PASS                             |
| a Drake release lacking a binding the case uses | SKIP                         |
| its first failure matches a known divergence| XFAIL (with the divergence's id) |
| otherwise                                   | FAIL                             |

A failure at step *i* is matched against the steps since the last observed
one before *i* (their states were not compared, so each may be the cause):
a known divergence's step pattern must match one of them, and its ``cases``,
if any, narrow it to those cases.
"""

from __future__ import annotations

from collections.abc import Sequence

from conformance._backends.calls import BackendError
from conformance._engine import Engine, Outcome, outcome_of_break
from conformance._policy.divergences import KnownDivergence, match_step
from conformance._policy.release_facts import recorded_crash
from conformance._run.case_report import CaseReport
from conformance.protocol import Backend, BackendId, ErrorKind, backend_id

__all__ = ["DRAKE_NAMES", "binding_gap", "judge"]

#: Backend names that are real Drake: preferred as the reference.
DRAKE_NAMES = ("pydrake", "drake")
#: Backend names that claim one Drake release's bindings: real Drake, and reimpl following a
#: release in a worker (``reimpl==X``), whose missing bindings are that release's.
_RELEASE_NAMES = (*DRAKE_NAMES, "reimpl==")


def judge(
    report: CaseReport,
    engine: Engine,
    strict: bool,
    divergences: Sequence[KnownDivergence] | None,
) -> None:
    """Each backend's outcome: broken, or by its failures (``_status``)."""
    release = engine.reference.version()
    for backend in engine.backends:
        broken = engine.tracks[backend.name].broken
        if broken is not None:
            _broke(report, backend, broken, strict, divergences)
        else:
            report.status[backend.name] = _status(
                report, backend_id(backend), release, strict, divergences
            )


def _known(
    report: CaseReport,
    backend: BackendId,
    *,
    release: str,
    divergences: Sequence[KnownDivergence] | None,
    at: int,
    broke: bool = False,
) -> KnownDivergence | None:
    """The known divergence that ``backend``'s first failure, at step ``at``, is, if any.

    The steps since the last observed one before ``at`` may each be the cause
    (their states were not compared); a known divergence's step pattern must
    match one of them (the reference's answer there, the backend's, or that it
    broke at ``at``), and, if it lists cases, this case must be one.
    """
    trace = report.trace
    if trace is None:
        return None
    start = at
    while start > 0 and all(v is None for v in trace.records[start - 1].observations.values()):
        start -= 1
    for record in trace.records[start : at + 1]:
        if record.command is None:
            continue
        mine = record.results.get(backend.name)
        if mine is None and not (broke and record.index == at):
            continue
        known = match_step(
            record.command,
            record.results.get(trace.reference),
            mine,
            blamed=backend,
            release=release,
            case=report.case.qualified_name,
            entries=divergences,
        )
        if known is not None:
            return known
    return None


def _broke(
    report: CaseReport,
    backend: Backend,
    broken: BackendError,
    strict: bool,
    divergences: Sequence[KnownDivergence] | None,
) -> None:
    """Records a backend that broke: its outcome, and why the case stopped early.

    A crash or a timeout of an isolated backend is recoverable (a new worker
    takes over). A crash that a crash row of the release table records for
    that backend's own release, in that case, is the release's answer: it
    passes. Any other that a known divergence expects of that release is
    ``xfail``, unless ``strict``.
    """
    status = outcome_of_break(broken)
    report.broken[backend.name] = status
    isolated = bool(getattr(backend, "isolated", False))
    recoverable = isolated and status is not Outcome.ERROR
    report.recoverable = (report.aborted is None or report.recoverable) and recoverable
    report.aborted = "; ".join(filter(None, (report.aborted, str(broken))))
    me = backend_id(backend)
    recorded = recorded_crash(report.case.qualified_name, me.version)
    if recorded is not None and status is Outcome.CRASH and recoverable:
        report.recorded[backend.name] = recorded
        report.status[backend.name] = Outcome.PASS
        return
    at = len(report.traces[backend.name].results)
    known = (
        None
        if strict
        else _known(report, me, release=me.version, divergences=divergences, at=at, broke=True)
    )
    if known is not None and recoverable:
        report.xfails[backend.name] = known.id
        status = Outcome.XFAIL
    report.status[backend.name] = status


def binding_gap(report: CaseReport, backend: str) -> str | None:
    """The first step ``backend`` answered with an error of kind ``binding`` (its Python
    bindings lack the call, or the keywords, the step uses), if any."""
    track = report.traces.get(backend)
    if track is None:
        return None
    for step, result in zip(report.case.steps, track.results, strict=False):
        if result.error is not None and result.error.kind is ErrorKind.BINDING:
            return f"{step.label} ({step.op}): {result.error.message}"
    return None


def _status(
    report: CaseReport,
    backend: BackendId,
    release: str,
    strict: bool,
    divergences: Sequence[KnownDivergence] | None,
) -> Outcome:
    """PASS, or, for a backend with failures: SKIP if it is a Drake release whose bindings
    lack a call the case makes (it cannot run the case; an implementation's missing
    binding is a failure), XFAIL if a known divergence expects them, else FAIL."""
    failures = report.failures_of(backend.name)
    if not failures:
        return Outcome.PASS
    gap = binding_gap(report, backend.name)
    if gap is not None and backend.name.startswith(_RELEASE_NAMES):
        report.skip_reasons[backend.name] = f"no binding: {gap}"
        return Outcome.SKIP
    if strict:
        return Outcome.FAIL
    at = min(f.index for f in failures)
    known = _known(report, backend, release=release, divergences=divergences, at=at)
    if known is None:
        return Outcome.FAIL
    report.xfails[backend.name] = known.id
    return Outcome.XFAIL
