"""pytest plugin (entry point ``pytest11``): scenario cases as test items.

``pytest scenarios/`` collects every case of every scenario file (a ``*.json``
file below a directory holding ``scenario.schema.json``) as one item named by
the case's qualified name. Each item runs the case on the chosen backends
(``--conformance-backend``, repeatable; default reimpl and pydrake) and fails
with the same Result/Expect text as ``python -m conformance run``. It works
with pytest-xdist (``-n``) and ``--junitxml``.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from conformance.backends.loader import BackendLoadError, load_backend
from conformance.corpus.loader import SCENARIO_SCHEMA, Case, ScenarioError, load_file
from conformance.protocol import Backend
from conformance.run.report import failure_lines
from conformance.run.runner import CaseReport, Status, run_case

__all__ = ["ScenarioCaseItem", "ScenarioFileCollector"]


def pytest_addoption(parser: pytest.Parser) -> None:
    group = parser.getgroup("conformance", "collision filter conformance scenarios")
    group.addoption(
        "--conformance-backend",
        action="append",
        dest="conformance_backends",
        metavar="NAME",
        help="backend for scenario items: reimpl, pydrake or module:attribute (repeatable)",
    )


def _corpus_root(path: Path) -> Path | None:
    for parent in path.parents:
        if (parent / SCENARIO_SCHEMA).exists():
            return parent
    return None


def pytest_collect_file(parent: pytest.Collector, file_path: Path) -> pytest.Collector | None:
    if file_path.suffix != ".json" or file_path.name == SCENARIO_SCHEMA:
        return None
    if _corpus_root(file_path) is None:
        return None
    return ScenarioFileCollector.from_parent(parent, path=file_path)


class ScenarioFileCollector(pytest.File):
    """One scenario file; yields one item per case."""

    def collect(self) -> Iterator[pytest.Item]:
        try:
            scenario = load_file(self.path, root=_corpus_root(self.path))
        except ScenarioError as exc:
            raise self.CollectError(str(exc)) from None
        for case in scenario.cases:
            yield ScenarioCaseItem.from_parent(self, name=case.qualified_name, case=case)


class _ConformanceError(Exception):
    def __init__(self, report: CaseReport) -> None:
        super().__init__(report.case.qualified_name)
        self.report = report


def _backends(config: pytest.Config) -> list[Backend]:
    cached: list[Backend] | None = getattr(config, "_conformance_backends", None)
    if cached is None:
        specs = config.getoption("conformance_backends") or ["reimpl", "pydrake"]
        try:
            cached = [load_backend(spec) for spec in specs]
        except BackendLoadError as exc:
            raise pytest.UsageError(str(exc)) from None
        config._conformance_backends = cached  # type: ignore[attr-defined]
    return cached


class ScenarioCaseItem(pytest.Item):
    """One case, run on every backend in lockstep."""

    def __init__(self, *, case: Case, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.case = case
        for feature in sorted(case.features):
            self.add_marker(feature)

    def runtest(self) -> None:
        backends = _backends(self.config)
        report = run_case(self.case, backends)
        for backend in backends:
            self.user_properties.append((f"{backend.name}_version", backend.version()))
            self.user_properties.append(
                (f"{backend.name}_status", report.status[backend.name].value)
            )
        if not report.passed:
            raise _ConformanceError(report)
        if report.xfails:
            pytest.xfail("; ".join(f"{b}: known divergence {d}" for b, d in report.xfails.items()))
        if all(s is Status.SKIP for s in report.status.values()):
            pytest.skip("; ".join(f"{b}: {r}" for b, r in report.skip_reasons.items()))

    def repr_failure(self, excinfo: pytest.ExceptionInfo[BaseException], style: Any = None) -> str:
        if isinstance(excinfo.value, _ConformanceError):
            header = f"{self.case.qualified_name} ({self.case.file.path})"
            return "\n".join([header, *failure_lines(excinfo.value.report)])
        return str(super().repr_failure(excinfo))

    def reportinfo(self) -> tuple[Path, int, str]:
        return self.path, 0, self.case.qualified_name
