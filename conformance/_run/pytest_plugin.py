"""pytest plugin (entry point ``pytest11``): scenario cases as test items.

Every case of a scenario file becomes one item named by the case's qualified
name. A ``.json``, ``.yaml`` or ``.yml`` file is a scenario file when

- it is named on the command line (``pytest my/case.json``): it must then be
  a scenario, or collection fails naming the problem;
- it lies below a directory holding ``scenario.schema.json`` (the corpus), or
  below a path of the ``conformance_paths`` ini option: there a file whose
  data has no top-level ``cases`` key is some other data file and is ignored.

``scenario.schema.json`` itself is never collected. pytest still walks only
what its arguments (or ``testpaths``) reach; ``conformance_paths`` says which
of the files it meets are scenarios.

Each item runs the case on the chosen backends (``--conformance-backend``,
repeatable; default reimpl and pydrake), loaded once before the first case
runs: a spec that cannot be loaded is one usage error (exit 4). An item fails with
the same Result/Expect text as ``python -m conformance run``; it is an xfail
when its failures are a known divergence, and a skip when no comparison was
possible: fewer than two backends (or than the one given) could run the case,
because the others lack one of its features. The skip reason names them, e.g.
``pydrake 1.51.1 needs feature(s) activation``; the backends that did run it
must still meet the case's expectations, or the item fails. Every feature tag
is registered as a marker, so ``--strict-markers`` holds anywhere. It works
with pytest-xdist (``-n``) and ``--junitxml``.
"""

from __future__ import annotations

from collections.abc import Generator, Iterator, Sequence
from pathlib import Path
from typing import Any

import pytest

from conformance._backends.loader import BackendLoadError, load_backend
from conformance._corpus.documents import DOCUMENT_SUFFIXES, DocumentError, read_document
from conformance._corpus.loader import (
    SCENARIO_SCHEMA,
    Case,
    ScenarioError,
    enclosing_corpus,
    in_model_package,
    load_file,
)
from conformance._engine import Outcome
from conformance._grammar.schema import scenario_schema
from conformance._run.case_report import CaseReport
from conformance._run.report import failure_lines
from conformance._run.runner import run_case
from conformance.protocol import Backend

__all__ = ["FEATURE_TAGS", "SCENARIO_SUFFIXES", "ScenarioCaseItem", "ScenarioFileCollector"]

#: The scenario features (the schema's enum); each is a marker on the cases that have it.
FEATURE_TAGS: tuple[str, ...] = tuple(scenario_schema()["$defs"]["features"]["items"]["enum"])

_DEFAULT_BACKENDS = ("reimpl", "pydrake")


#: The suffixes of scenario files (the corpus loader's document types).
SCENARIO_SUFFIXES = frozenset(DOCUMENT_SUFFIXES)


def pytest_addoption(parser: pytest.Parser) -> None:
    group = parser.getgroup("conformance", "collision filter conformance scenarios")
    group.addoption(
        "--conformance-backend",
        action="append",
        dest="conformance_backends",
        metavar="NAME",
        help="backend for scenario items: reimpl, pydrake, drake==X.Y.Z, exec:'CMD ARGS' or "
        "module:attribute (repeatable)",
    )
    parser.addini(
        "conformance_paths",
        "folders (or files) whose .json/.yaml/.yml files with a top-level 'cases' key "
        "are scenario files, relative to the ini file",
        type="paths",
        default=[],
    )


def pytest_configure(config: pytest.Config) -> None:
    for tag in FEATURE_TAGS:
        config.addinivalue_line("markers", f"{tag}: scenario feature tag (conformance plugin)")
    if config.getoption("conformance_backends"):
        _backends(config)  # a bad spec is one usage error, before anything runs


def pytest_collection_modifyitems(config: pytest.Config, items: Sequence[pytest.Item]) -> None:
    # The default backends load once there are cases to run. A usage error in an xdist
    # worker would crash it without the message, so there each item reports it instead.
    if not hasattr(config, "workerinput") and any(isinstance(i, ScenarioCaseItem) for i in items):
        _backends(config)


def _listed_root(config: pytest.Config, path: Path) -> Path | None:
    """The ``conformance_paths`` folder holding ``path`` (its parent if a file is listed)."""
    resolved = path.resolve()
    for listed in config.getini("conformance_paths"):
        folder = Path(listed).resolve()
        if resolved == folder:
            return folder.parent
        if folder in resolved.parents:
            return folder
    return None


def _scenario_root(config: pytest.Config, path: Path) -> Path | None:
    """The folder a scenario's name is relative to: the corpus, else a listed folder."""
    return enclosing_corpus(path) or _listed_root(config, path)


def _other_data(path: Path) -> bool:
    """True if ``path`` parses to data without a top-level ``cases`` key: not a scenario.

    A file that does not parse counts as a scenario, so that loading it reports the problem.
    """
    try:
        data = read_document(path)
    except DocumentError:
        return False
    return not (isinstance(data, dict) and "cases" in data)


def pytest_collect_file(parent: pytest.Collector, file_path: Path) -> pytest.Collector | None:
    if file_path.suffix.lower() not in SCENARIO_SUFFIXES or file_path.name == SCENARIO_SCHEMA:
        return None
    explicit = parent.session.isinitpath(file_path)
    root = _scenario_root(parent.config, file_path)
    if not explicit and (
        root is None or in_model_package(file_path, root) or _other_data(file_path)
    ):
        return None
    return ScenarioFileCollector.from_parent(parent, path=file_path)


class ScenarioFileCollector(pytest.File):
    """One scenario file; yields one item per case."""

    def collect(self) -> Iterator[pytest.Item]:
        if _other_data(self.path):  # only a file named on the command line gets here
            raise self.CollectError(
                f"{self.path}: not a scenario file (its data has no top-level 'cases' key)"
            )
        try:
            scenario = load_file(self.path, root=_scenario_root(self.config, self.path))
        except ScenarioError as exc:
            raise self.CollectError(f"not a valid scenario file: {exc}") from None
        for case in scenario.cases:
            yield ScenarioCaseItem.from_parent(self, name=case.qualified_name, case=case)


class _ConformanceError(Exception):
    def __init__(self, report: CaseReport) -> None:
        super().__init__(report.case.qualified_name)
        self.report = report


class _BackendsUnavailableError(Exception):
    """A backend failed to load in an xdist worker: each item says so in one line."""


def _backends(config: pytest.Config) -> list[Backend]:
    """The session's backends, loaded on first use; a spec that fails is a usage error."""
    cached: list[Backend] | None = getattr(config, "_conformance_backends", None)
    if cached is None:
        specs = config.getoption("conformance_backends") or list(_DEFAULT_BACKENDS)
        try:
            cached = [load_backend(spec) for spec in specs]
        except BackendLoadError as exc:
            raise pytest.UsageError(f"conformance plugin: {exc}") from None
        config._conformance_backends = cached  # type: ignore[attr-defined]
    return cached


def _not_compared(report: CaseReport, backends: Sequence[Backend]) -> str | None:
    """Why no comparison was possible (backends lacking the case's features), or None."""
    sat_out = [b for b in backends if report.status.get(b.name) is Outcome.SKIP]
    ran = [b.name for b in backends if b not in sat_out]
    if not sat_out or len(ran) >= min(2, len(backends)):
        return None
    reasons = "; ".join(f"{b.name} {b.version()} {report.skip_reasons[b.name]}" for b in sat_out)
    if not ran:
        return reasons
    return f"{reasons} (not compared; {', '.join(ran)} met the case's expectations alone)"


class ScenarioCaseItem(pytest.Item):
    """One case, run on every backend in lockstep."""

    def __init__(self, *, case: Case, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.case = case
        for feature in sorted(case.features):
            self.add_marker(feature)

    def runtest(self) -> None:
        try:
            backends = _backends(self.config)
        except pytest.UsageError as exc:
            raise _BackendsUnavailableError(str(exc)) from None
        report = run_case(self.case, backends)
        for backend in backends:
            self.user_properties.append((f"{backend.name}_version", backend.version()))
            status = report.status.get(backend.name)  # none if the case stopped early
            self.user_properties.append(
                (f"{backend.name}_status", "unfinished" if status is None else status.value)
            )
            if backend.name in report.skip_reasons:
                why = report.skip_reasons[backend.name]
                self.user_properties.append((f"{backend.name}_skip_reason", why))
        if not report.passed:
            raise _ConformanceError(report)
        if report.xfails:
            pytest.xfail("; ".join(f"{b}: known divergence {d}" for b, d in report.xfails.items()))
        not_compared = _not_compared(report, backends)
        if not_compared is not None:
            pytest.skip(not_compared)

    def repr_failure(self, excinfo: pytest.ExceptionInfo[BaseException], style: Any = None) -> str:
        if isinstance(excinfo.value, _ConformanceError):
            report = excinfo.value.report
            header = f"{self.case.qualified_name} ({self.case.file.path})"
            lines = [header, *failure_lines(report)]
            aborted = report.aborted  # why the case stopped early
            if aborted:
                lines.append(f"  {aborted}")
            return "\n".join(lines)
        if isinstance(excinfo.value, _BackendsUnavailableError):
            return str(excinfo.value)
        return str(super().repr_failure(excinfo))

    def reportinfo(self) -> tuple[Path, int, str]:
        return self.path, 0, self.case.qualified_name


@pytest.hookimpl(wrapper=True)
def pytest_runtest_makereport(
    item: pytest.Item, call: pytest.CallInfo[None]
) -> Generator[None, pytest.TestReport, pytest.TestReport]:
    """A skipped case is reported at its scenario file, not at this module's ``pytest.skip``."""
    report = yield
    skipped = report.skipped and not hasattr(report, "wasxfail")
    if isinstance(item, ScenarioCaseItem) and skipped and isinstance(report.longrepr, tuple):
        _, _, message = report.longrepr
        report.longrepr = (str(item.path), 1, message)
    return report
