"""Writes the real-model corpus: a case per vendored model file, with Drake's errors.

Usage::

    python scenarios/real_models/make_cases.py [--drake 1.58.0 ...]

Each model file below ``drake/`` and ``drake_models/`` is a case
(``conformance._corpus.model_files``): parse, Finalize, the plant's inventory,
the candidate pairs after each step, and for files that may declare
collision filter groups, the parser's group report. Every backend is
compared with the reference step by step; this script adds what a case can
say by itself, small and stable: the model instances each ``add_models``
returns, and the steps where Drake raises (so ``run`` knows a file is
rejected on purpose, not a broken input). It runs every case on pydrake (this
environment's release) and on each ``--drake`` release (in its own
environment) and writes each answer as an expectation for the releases that
gave it (``until`` the older one, ``since`` the newer one, or for all
releases where they agree).

Output: ``drake_repository.json`` (Drake's own files) and ``robot_models.json``
(``drake_models``), beside this script. The same inputs give the same files.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from conformance._backends.loader import load_backend
from conformance._corpus.loader import scenario_from_data
from conformance._corpus.model_files import find_model_files, model_cases
from conformance._run.runner import run_case
from conformance.protocol import Backend

HERE = Path(__file__).resolve().parent
#: Output file → (its description, the vendored folder whose model files it holds).
CORPORA: Mapping[str, tuple[str, str]] = {
    "drake_repository.json": (
        "Drake's own model files (examples, parser and plant tests), parsed and finalized",
        "drake",
    ),
    "robot_models.json": (
        "The robots of Drake's drake_models package, parsed and finalized",
        "drake_models",
    ),
}
#: Answers on a release: case description → {step number: an expectation, ``{"error":
#: {"kind", "message"}}`` or ``{"returns": [model instances]}``}.
Answers = dict[str, dict[int, dict[str, Any]]]


def _answers(data: dict[str, Any], at: Path, backend: Backend) -> Answers:
    """The steps where ``backend`` raises, and what each add_models returns, per case."""
    found: Answers = {}
    scenario = scenario_from_data(data, at)
    for count, case in enumerate(scenario.cases, 1):
        report = run_case(case, [backend])
        trace = report.traces.get(backend.name)
        if trace is None or trace.broken is not None:
            raise RuntimeError(f"{case.qualified_name}: {backend.name} broke: {report.aborted}")
        for number, (step, result) in enumerate(zip(case.steps, trace.results, strict=True), 1):
            if result.error is not None:
                error = {"kind": result.error.kind.value, "message": result.error.message}
                found.setdefault(case.description, {})[number] = {"error": error}
            elif step.op == "add_models":
                found.setdefault(case.description, {})[number] = {"returns": result.value}
        if count % 25 == 0:
            print(f"  {backend.name}: {count}/{len(scenario.cases)}", file=sys.stderr)
    return found


def _expectations(per_release: Sequence[tuple[str, Answers]]) -> dict[str, Any]:
    """{description: {step: expect}}: one expectation where all releases agree, else one per
    run of consecutive releases (oldest first) that agree: the first run ``until`` its last
    release, the last ``since`` its first, any between both; releases between two runs are
    not checked (nothing was measured there)."""
    merged: dict[str, dict[int, Any]] = {}
    keys = {(d, n) for _, answers in per_release for d, steps in answers.items() for n in steps}
    for description, number in sorted(keys):
        seen = [
            (release, answers.get(description, {}).get(number)) for release, answers in per_release
        ]
        runs: list[tuple[list[str], Any]] = []
        for release, answer in seen:
            if runs and runs[-1][1] == answer:
                runs[-1][0].append(release)
            else:
                runs.append(([release], answer))
        if len(runs) == 1:
            merged.setdefault(description, {})[number] = runs[0][1]
            continue
        expects = []
        for index, (releases, answer) in enumerate(runs):
            if answer is None:
                continue
            bounds = {}
            if index > 0:
                bounds["since"] = releases[0]
            if index < len(runs) - 1:
                bounds["until"] = releases[-1]
            expects.append({**bounds, **answer})
        merged.setdefault(description, {})[number] = expects
    return merged


def _write(name: str, drake_specs: Sequence[str]) -> Path:
    description, folder = CORPORA[name]
    files = [Path(folder) / f for f in find_model_files(HERE / folder)]
    plain = {
        "description": description,
        "comment": "Written by make_cases.py: each file gives the same inventory, candidate "
        "pairs, filter groups or error on every backend.",
        "features": ["multibody", "parsing"],
    }
    data = {**plain, "cases": model_cases(HERE, files, folder_arg=".")}
    backends = [load_backend("pydrake"), *(load_backend(f"drake=={v}") for v in drake_specs)]
    per_release = []
    for backend in backends:
        print(f"{name}: {len(data['cases'])} cases on {backend.name}", file=sys.stderr)
        per_release.append((backend.version(), _answers(data, HERE / name, backend)))
    per_release.sort(key=lambda item: tuple(int(p) for p in item[0].split(".")))
    expected = _expectations(per_release)
    cases = model_cases(HERE, files, folder_arg=".")
    for case in cases:
        for number, step in enumerate(case["steps"], 1):
            expect = expected.get(case["description"], {}).get(number)
            if expect is not None:
                step["expect"] = expect
    path = HERE / name
    path.write_text(json.dumps({**plain, "cases": cases}, indent=1) + "\n", encoding="utf-8")
    return path


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--drake",
        action="append",
        default=[],
        metavar="X.Y.Z",
        help="another Drake release to measure, in its own environment (repeatable)",
    )
    args = parser.parse_args(argv)
    for name in CORPORA:
        print(f"wrote {_write(name, args.drake)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
