"""Writes the real-model corpus: a case per vendored model file, with Drake's errors.

Usage::

    python scenarios/real_models/make_cases.py [--drake 1.58.0 ...]

Each model file below ``drake/`` and ``drake_models/`` is a case
(``conformance.corpus.model_files``): parse, Finalize, the plant's inventory,
the candidate pairs after each step, and for files that may declare
collision filter groups, the parser's group report. Every backend is
compared with the reference step by step; this script only adds what the
reference cannot say by itself: the steps where Drake raises. It runs every
case on pydrake (this environment's release) and on each ``--drake`` release
(in its own environment) and writes each failing step's error as an
expectation for the releases that gave it (``until`` the older one, ``since``
the newer one, or for all releases where they agree), so ``run`` knows that
the file is rejected on purpose, not a broken input.

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

from conformance.backends.loader import load_backend
from conformance.corpus.loader import scenario_from_data
from conformance.corpus.model_files import find_model_files, model_cases
from conformance.protocol import Backend
from conformance.run.runner import run_case

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
#: Errors on a release: case description → {step number: {"kind", "message"}}.
Errors = dict[str, dict[int, dict[str, str]]]


def _errors(data: dict[str, Any], at: Path, backend: Backend) -> Errors:
    """The steps where ``backend`` raises, per case of ``data``."""
    found: Errors = {}
    scenario = scenario_from_data(data, at)
    for count, case in enumerate(scenario.cases, 1):
        report = run_case(case, [backend])
        trace = report.traces.get(backend.name)
        if trace is None or trace.broken is not None:
            raise RuntimeError(f"{case.qualified_name}: {backend.name} broke: {report.aborted}")
        for number, result in enumerate(trace.results, 1):
            if result.error is not None:
                error = {"kind": result.error.kind.value, "message": result.error.message}
                found.setdefault(case.description, {})[number] = error
        if count % 25 == 0:
            print(f"  {backend.name}: {count}/{len(scenario.cases)}", file=sys.stderr)
    return found


def _expectations(per_release: Sequence[tuple[str, Errors]]) -> dict[str, Any]:
    """{description: {step: expect}}: one expectation where all releases agree, else one
    per release (``until`` the oldest, ``since`` the others; releases are given oldest
    first)."""
    merged: dict[str, dict[int, Any]] = {}
    keys = {(d, n) for _, errors in per_release for d, steps in errors.items() for n in steps}
    for description, number in sorted(keys):
        seen = [
            (release, errors.get(description, {}).get(number)) for release, errors in per_release
        ]
        if all(error == seen[0][1] for _, error in seen):
            merged.setdefault(description, {})[number] = {"error": seen[0][1]}
            continue
        expects = []
        for index, (release, error) in enumerate(seen):
            if error is None:
                continue
            bound = "until" if index == 0 else "since"
            expects.append({bound: release, "error": error})
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
        per_release.append((backend.version(), _errors(data, HERE / name, backend)))
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
