"""A shrunk divergence, written as a scenario file that ``run`` replays.

The file has one case: the divergence's command sequence, with the
*reference* backend's answers as expectations. Every step where the reference
raised gets an ``error`` expectation (kind and message). Every step that
returned a value gets ``returns``. The last step also records the reference's
whole state: C, history and IsActive, at every location.

So ``python -m conformance run FILE --backend A --backend B`` reproduces the
disagreement pair by pair. The same file run on A alone fails on A's wrong
answer. Once A is fixed, the file passes and stays as a regression case.

**Two Drake releases** (``fuzz --backend drake==1.51.1 --against
drake==1.58.0``): neither answer is wrong, the releases differ. When the
caller passes ``backend_version`` (the backend is itself a Drake release,
``drake_release``) and it differs from ``reference_version``, every step
where the two answered differently gets both answers: the earlier release's
bounded by ``until: <earlier>``, the later one's by ``since: <later>``
(a step where they agree keeps one unbounded expectation). The file then
passes on each release alone, and the pair still disagrees under ``run``.
Releases strictly between the two are left unclaimed: run the file on them
to narrow the range.

The file name is a hash of the steps, so writing the same finding twice
gives the same file. Files land whole (a temporary file moved over the
name), so ``fuzz`` can write a finding as soon as it is seen and replace it
as it shrinks.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import secrets
import tempfile
from pathlib import Path
from typing import Any

from conformance._backends.subprocess_backend import SPEC_PREFIX
from conformance._corpus.loader import load_file
from conformance._engine import Divergence, HarnessError
from conformance._grammar import GRAMMAR
from conformance._policy.versions import parse_version
from conformance.protocol import BackendId, Command

__all__ = [
    "DEFAULT_REGRESSIONS",
    "drake_release",
    "prepare_writing",
    "regression_scenario",
    "reproducer_scenario",
    "write_regression",
    "write_reproducer",
]

#: Where ``fuzz`` writes findings by default (relative to the working directory).
DEFAULT_REGRESSIONS = Path("scenarios/regressions")


def _slug(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9]+", "-", text).strip("-").lower()


def drake_release(backend: BackendId) -> str | None:
    """The Drake release ``backend`` *is*, or None for an implementation that only claims one.

    Real Drake is the in-process ``pydrake`` and a ``drake==X`` worker. reimpl,
    the mutants and third-party backends claim a release (their ``version()``
    selects expectations) but their answers are not that release's: a finding
    against them keeps the single-reference format.
    """
    real = backend.name == "pydrake" or backend.name.startswith(SPEC_PREFIX)
    return backend.version if real and parse_version(backend.version) else None


def regression_scenario(
    divergence: Divergence,
    *,
    backend: str,
    reference: str,
    reference_version: str,
    seed: int | None = None,
    backend_version: str | None = None,
    models: bool = False,
    poses: bool = False,
) -> dict[str, Any]:
    """The scenario file (a JSON-able dict) for ``divergence``.

    ``models``/``poses``: found by ``fuzz --models``/``fuzz --poses``; the
    description and the command in the comment say so.

    ``backend_version``: the Drake release the backend *is* (``drake_release``;
    None for reimpl and other implementations). When it differs from
    ``reference_version``, each release's answers carry ``since``/``until``
    (see the module doc).
    """
    releases = (
        (reference_version, backend_version)
        if backend_version is not None
        and parse_version(backend_version)
        and parse_version(reference_version)
        and parse_version(backend_version) != parse_version(reference_version)
        else None
    )
    trace = divergence.trace
    case = trace.to_case(
        "",
        other=divergence.backend,
        states={
            name: state
            for name, state in (
                (trace.reference, divergence.reference_state),
                (divergence.backend, divergence.backend_state),
            )
            if state is not None
        },
        releases=releases,
    )
    steps = case["steps"]
    commands = trace.commands()
    features = _features(commands)
    sides = [r.results[trace.reference] for r in trace.records if r.command is not None]
    if releases is not None:
        sides += [r.results[divergence.backend] for r in trace.records if r.command is not None]
    if any(result.error is not None for result in sides):
        features.append("errors")
    seeded = f" --seed {seed}" if seed is not None else ""
    mode = _mode(models=models, poses=poses)
    found = (
        f"Found by `python -m conformance fuzz{mode} "
        f"--backend {backend} --against {reference}"
        f"{seeded}` and shrunk by Hypothesis."
    )
    if releases is None:
        description = (
            f"{backend} diverges from {reference}: {divergence.what} after step {len(steps)}"
        )
        comment = (
            f"{found} Expectations are what {reference} {reference_version} did. "
            f"The disagreement: {divergence.detail}"
        )
    else:
        early, late = sorted(releases, key=parse_version)
        description = f"Drake {early} and {late} differ: {divergence.what} after step {len(steps)}"
        comment = (
            f"{found} Where the two releases answered differently, the expectations bounded "
            f"`until: {early}` are what Drake {early} did and those bounded `since: {late}` "
            f"what Drake {late} did, so the file passes on each release alone; releases in "
            f"between are not claimed (run the file on them to narrow the range). The "
            f"disagreement ({reference} {reference_version} as reference): {divergence.detail}"
        )
    return {
        "description": f"Fuzz{mode} finding: {backend} vs {reference}"[:150],
        "comment": comment,
        "features": sorted(set(features)),
        "cases": [{"description": description[:150], "steps": steps}],
    }


def _mode(*, models: bool, poses: bool) -> str:
    """The campaign's option on the command line: `` --models``, `` --poses`` or none."""
    return " --models" if models else " --poses" if poses else ""


def _features(commands: list[Command]) -> list[str]:
    return sorted({"core"} | {GRAMMAR[c.op].feature for c in commands})


def prepare_writing() -> None:
    """Builds what checking a scenario file needs, now (about 0.5 s, once per process).

    ``fuzz`` calls it before its run, so that the first finding lands within
    milliseconds of being seen: the first ``load_file`` of a process checks
    the scenario schema itself, which takes most of a second.
    """
    warm_up = {
        "description": "warm-up",
        "cases": [{"description": "a frame", "steps": [{"op": "register_frame", "name": "f1"}]}],
    }
    with tempfile.TemporaryDirectory(prefix="finding-") as private:
        path = Path(private) / "warm-up.json"
        path.write_text(json.dumps(warm_up))
        load_file(path, root=Path(private))


def _write_checked(scenario: dict[str, Any], out_dir: Path, stem: str) -> Path:
    """Writes ``scenario`` as ``out_dir/<stem>-<hash of its steps>.json``, valid and whole.

    The text is validated first (``load_file`` on a copy in a private
    temporary folder: a ScenarioError leaves nothing in ``out_dir``), then
    written to a hidden ``.tmp`` file in ``out_dir`` and moved over the final
    name with ``os.replace``. So a reader of ``out_dir`` never sees a
    half-written or invalid scenario, even if the process dies mid-write. A
    run killed between the two may leave the ``.tmp`` file (not a scenario).
    """
    text = json.dumps(scenario, indent=2) + "\n"
    body = json.dumps(scenario["cases"][0]["steps"], sort_keys=True)
    digest = hashlib.sha256(body.encode()).hexdigest()[:10]
    name = f"{stem}-{digest}.json"
    with tempfile.TemporaryDirectory(prefix="finding-") as private:
        draft = Path(private) / name
        draft.write_text(text)
        load_file(draft, root=Path(private))
    out_dir.mkdir(parents=True, exist_ok=True)
    path = out_dir / name
    # Not mkstemp: its 0600 mode would stay on the finding; "x" keeps the umask's.
    temporary = out_dir / f".{name}.{os.getpid()}-{secrets.token_hex(4)}.tmp"
    try:
        with temporary.open("x") as file:
            file.write(text)
        os.replace(temporary, path)
    except BaseException:  # an interrupt or a failed write: no stray temporary file
        temporary.unlink(missing_ok=True)
        raise
    return path


def write_regression(
    divergence: Divergence,
    out_dir: Path,
    *,
    backend: str,
    reference: str,
    reference_version: str,
    seed: int | None = None,
    backend_version: str | None = None,
    models: bool = False,
    poses: bool = False,
) -> Path:
    """Writes the scenario for ``divergence`` into ``out_dir``; returns its path.

    A ``models`` finding's file name starts with ``models-``, a ``poses`` one's with
    ``poses-``."""
    scenario = regression_scenario(
        divergence,
        backend=backend,
        reference=reference,
        reference_version=reference_version,
        seed=seed,
        backend_version=backend_version,
        models=models,
        poses=poses,
    )
    prefix = _mode(models=models, poses=poses).strip(" -")
    stem = f"{prefix + '-' if prefix else ''}{_slug(backend)}-vs-{_slug(reference)}"
    return _write_checked(scenario, out_dir, stem)


def reproducer_scenario(
    error: HarnessError,
    *,
    backend: str,
    reference: str,
    seed: int | None = None,
    poses: bool = False,
) -> dict[str, Any]:
    """A scenario replaying the commands that broke a backend (no expectations).

    ``run`` on it with the same backends meets the same fault, if the fault
    is deterministic.
    """
    seeded = f" --seed {seed}" if seed is not None else ""
    message = str(error)
    return {
        "description": f"Fuzz reproducer: a backend broke ({backend} vs {reference})"[:150],
        "comment": (
            f"Written by `python -m conformance fuzz{_mode(models=False, poses=poses)} "
            f"--backend {backend} --against {reference}"
            f"{seeded}` when a backend broke (not a divergence): {message[:500]}"
        ),
        "features": _features(error.commands),
        "cases": [
            {
                "description": f"the commands up to the fault ({len(error.commands)})",
                "steps": [c.to_json() for c in error.commands],
            }
        ],
    }


def write_reproducer(
    error: HarnessError,
    out_dir: Path,
    *,
    backend: str,
    reference: str,
    seed: int | None = None,
    poses: bool = False,
) -> Path | None:
    """Writes ``reproducer_scenario`` into ``out_dir`` (None if there are no commands)."""
    if not error.commands:
        return None
    scenario = reproducer_scenario(
        error, backend=backend, reference=reference, seed=seed, poses=poses
    )
    return _write_checked(scenario, out_dir, f"broken-{_slug(backend)}-vs-{_slug(reference)}")
