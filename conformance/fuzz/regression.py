"""A shrunk divergence, written as a scenario file that ``run`` replays.

The file has one case: the divergence's command sequence, with the
*reference* backend's answers as expectations. Every step where the reference
raised gets an ``error`` expectation (kind and message). Every step that
returned a value gets ``returns``. The last step also records the reference's
whole state: C, history and IsActive, at every location.

So ``python -m conformance run FILE --backend A --backend B`` reproduces the
disagreement pair by pair. The same file run on A alone fails on A's wrong
answer. Once A is fixed, the file passes and stays as a regression case.

The file name is a hash of the steps, so writing the same finding twice
gives the same file.
"""

from __future__ import annotations

import hashlib
import json
import re
from pathlib import Path
from typing import Any

from conformance.corpus.loader import ScenarioError, load_file
from conformance.fuzz.lockstep import Divergence, HarnessError
from conformance.grammar import GRAMMAR
from conformance.protocol import Command, Observation, Result

__all__ = [
    "DEFAULT_REGRESSIONS",
    "regression_scenario",
    "reproducer_scenario",
    "write_regression",
    "write_reproducer",
]

#: Where ``fuzz`` writes findings by default (relative to the working directory).
DEFAULT_REGRESSIONS = Path("scenarios/regressions")


def _result_expectation(result: Result) -> dict[str, Any]:
    if result.error is not None:
        return {"error": result.error.to_json()}
    if isinstance(result.value, bool | int):
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


def _slug(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9]+", "-", text).strip("-").lower()


def regression_scenario(
    divergence: Divergence,
    *,
    backend: str,
    reference: str,
    reference_version: str,
    seed: int | None = None,
) -> dict[str, Any]:
    """The scenario file (a JSON-able dict) for ``divergence``."""
    steps: list[dict[str, Any]] = []
    for index, item in enumerate(divergence.trace, 1):
        step = item.command.to_json()
        expectations = [_result_expectation(item.reference)]
        if index == len(divergence.trace):
            state = _state_expectations(divergence.reference_state)
            expectations = [{**expectations[0], **state[0]}, *state[1:]]
        expectations = [e for e in expectations if e]
        if expectations:
            step["expect"] = expectations[0] if len(expectations) == 1 else expectations
        steps.append(step)
    features = _features([item.command for item in divergence.trace])
    if any(item.reference.error is not None for item in divergence.trace):
        features.append("errors")
    seeded = f" --seed {seed}" if seed is not None else ""
    description = f"{backend} diverges from {reference}: {divergence.what} after step {len(steps)}"
    return {
        "description": f"Fuzz finding: {backend} vs {reference}"[:150],
        "comment": (
            f"Found by `python -m conformance fuzz --backend {backend} --against {reference}"
            f"{seeded}` and shrunk by Hypothesis. Expectations are what {reference} "
            f"{reference_version} did. The disagreement: {divergence.detail}"
        ),
        "features": sorted(set(features)),
        "cases": [{"description": description[:150], "steps": steps}],
    }


def _features(commands: list[Command]) -> list[str]:
    return sorted({"core"} | {GRAMMAR[c.op].feature for c in commands})


def _write_checked(scenario: dict[str, Any], out_dir: Path, stem: str) -> Path:
    """Writes ``scenario`` as ``out_dir/<stem>-<hash of its steps>.json`` and validates it.

    A file that fails validation is removed and ScenarioError raised, so a
    bad file never lands.
    """
    body = json.dumps(scenario["cases"][0]["steps"], sort_keys=True)
    digest = hashlib.sha256(body.encode()).hexdigest()[:10]
    out_dir.mkdir(parents=True, exist_ok=True)
    path = out_dir / f"{stem}-{digest}.json"
    path.write_text(json.dumps(scenario, indent=2) + "\n")
    try:
        load_file(path, root=out_dir)
    except ScenarioError:
        path.unlink()
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
) -> Path:
    """Writes the scenario for ``divergence`` into ``out_dir``; returns its path."""
    scenario = regression_scenario(
        divergence,
        backend=backend,
        reference=reference,
        reference_version=reference_version,
        seed=seed,
    )
    return _write_checked(scenario, out_dir, f"{_slug(backend)}-vs-{_slug(reference)}")


def reproducer_scenario(
    error: HarnessError, *, backend: str, reference: str, seed: int | None = None
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
            f"Written by `python -m conformance fuzz --backend {backend} --against {reference}"
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
    error: HarnessError, out_dir: Path, *, backend: str, reference: str, seed: int | None = None
) -> Path | None:
    """Writes ``reproducer_scenario`` into ``out_dir`` (None if there are no commands)."""
    if not error.commands:
        return None
    scenario = reproducer_scenario(error, backend=backend, reference=reference, seed=seed)
    return _write_checked(scenario, out_dir, f"broken-{_slug(backend)}-vs-{_slug(reference)}")
