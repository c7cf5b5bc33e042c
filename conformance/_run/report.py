"""Run results as people and CI want them: a summary table, failure details, JUnit, JSON.

The table has a column per backend; the reference backend (the oracle that
disagreements are judged against) is marked ``[reference]``. Each failure
names the backend at fault and whether the expected value came from the case
or from the reference. Known divergences show as ``xfail`` with their id.
Rerun hints repeat the ``--backend`` specs exactly as given.
"""

from __future__ import annotations

import json
import shlex
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TextIO

from conformance._engine import Outcome
from conformance._run.case_report import CaseReport
from conformance.protocol import Backend

__all__ = ["RunReport", "failure_lines", "write_json", "write_junit"]


@dataclass
class RunReport:
    """Everything a run found, in corpus order."""

    backends: Sequence[Backend]
    cases: list[CaseReport] = field(default_factory=list)
    aborted: str | None = None  # why the run stopped early, if it did
    #: The ``--backend`` specs as given, one per backend (default: the names).
    specs: Sequence[str] = ()
    #: The reference backend's name (``runner.choose_reference``).
    reference: str | None = None
    #: Extra options that a rerun must repeat (e.g. ``--strict-divergences``).
    rerun_options: Sequence[str] = ()
    #: Scenario files and cases left out as malformed, one message each.
    input_errors: Sequence[str] = ()

    def count(self, backend: str, status: Outcome) -> int:
        return sum(1 for c in self.cases if c.status.get(backend) is status)

    @property
    def failed(self) -> list[CaseReport]:
        return [c for c in self.cases if not c.passed]

    def print_summary(self, out: TextIO) -> None:
        files: dict[str, list[CaseReport]] = {}
        for case in self.cases:
            files.setdefault(case.case.file.name, []).append(case)
        names = [b.name for b in self.backends]
        header = [
            "scenario file",
            "cases",
            *[
                f"{b.name} ({b.version()})"
                + (" [reference]" if b.name == self.reference and len(self.backends) > 1 else "")
                for b in self.backends
            ],
        ]
        rows = [header]
        for file, cases in files.items():
            row = [file, str(len(cases))]
            for name in names:
                row.append(_cell(sum(1 for c in cases if c.status.get(name) is s) for s in Outcome))
            rows.append(row)
        total = ["total", str(len(self.cases))]
        total += [_cell(self.count(n, s) for s in Outcome) for n in names]
        rows.append(total)
        widths = [max(len(r[i]) for r in rows) for i in range(len(header))]
        for i, row in enumerate(rows):
            if i in (1, len(rows) - 1):
                out.write("  ".join("-" * w for w in widths) + "\n")
            out.write("  ".join(cell.ljust(w) for cell, w in zip(row, widths, strict=True)) + "\n")

    def print_failures(self, out: TextIO, *, prog: str) -> None:
        for case in self.failed:
            verdict = "FAIL" if case.aborted is None else "ERROR"
            out.write(f"\n{verdict} {case.case.qualified_name}\n")
            for line in failure_lines(case):
                out.write(line + "\n")
            if case.aborted is not None:
                out.write(f"  {case.aborted}\n")
            if case.log:
                out.write("  Drake's log during the case:\n")
                out.writelines(f"    {line}\n" for line in case.log)
            rerun = [
                *prog.split(),
                "run",
                str(case.case.file.path),
                "--case",
                case.case.qualified_name,
            ]
            specs = self.specs or [b.name for b in self.backends]
            rerun += [arg for spec in specs for arg in ("--backend", spec)]
            rerun += list(self.rerun_options)
            out.write(f"  rerun: {shlex.join(rerun)}\n")

    def print_xfails(self, out: TextIO) -> None:
        """One line per case and backend that failed as a known divergence."""
        for case in self.cases:
            for backend, divergence in case.xfails.items():
                out.write(f"xfail {case.case.qualified_name} [{backend}]: {divergence}\n")

    def print_skips(self, out: TextIO) -> None:
        """Why cases were skipped, one line per reason and backend, with a count."""
        reasons: dict[tuple[str, str], int] = {}
        for case in self.cases:
            for backend, reason in case.skip_reasons.items():
                reasons[backend, reason] = reasons.get((backend, reason), 0) + 1
        for (backend, reason), count in sorted(reasons.items()):
            out.write(f"skip {backend}: {count} case(s): {reason}\n")

    def to_json(self) -> dict[str, Any]:
        return {
            "backends": {b.name: {"version": b.version()} for b in self.backends},
            "reference": self.reference,
            "summary": {
                b.name: {s.value: self.count(b.name, s) for s in Outcome} for b in self.backends
            },
            "aborted": self.aborted,
            "input_errors": list(self.input_errors),
            "cases": [
                {
                    "qualified_name": c.case.qualified_name,
                    "status": {k: v.value for k, v in c.status.items()},
                    "skip_reasons": c.skip_reasons,
                    "xfails": c.xfails,
                    "aborted": c.aborted,
                    "failures": [f.to_json() for f in c.failures],
                }
                for c in self.cases
            ],
        }


def failure_lines(case: CaseReport) -> list[str]:
    """The failures of the backends that failed ``case``: what, expected (from where), actual."""
    lines = []
    for failure in case.failures:
        if case.status.get(failure.backend) is Outcome.FAIL:
            lines.append(f"  {failure.step}: {failure.what} [{failure.backend} failed]")
            lines.append(f"    expected: {_show(failure.expected)}  ({failure.source})")
            lines.append(f"    actual:   {_show(failure.actual)}")
    return lines


#: Always shown in a table cell; the others (error, timeout) only when they occur.
_ALWAYS_SHOWN = (Outcome.PASS, Outcome.FAIL, Outcome.XFAIL, Outcome.SKIP)


def _cell(counts: Any) -> str:
    return ", ".join(
        f"{count} {status.value}"
        for status, count in zip(Outcome, counts, strict=True)
        if count or status in _ALWAYS_SHOWN
    )


def _show(value: Any) -> str:
    return json.dumps(value, sort_keys=True) if not isinstance(value, str) else value


def write_json(report: RunReport, path: Path) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(report.to_json(), indent=2, sort_keys=True) + "\n")


def write_junit(report: RunReport, path: Path) -> None:
    """One <testcase> per case and backend; classname is the scenario file."""
    suite = ET.Element("testsuite", name="conformance")
    counts = {"tests": 0, "failures": 0, "errors": 0, "skipped": 0}
    for case in report.cases:
        for backend in report.backends:
            status = case.status.get(backend.name)
            if status is None:
                continue
            counts["tests"] += 1
            element = ET.SubElement(
                suite,
                "testcase",
                classname=case.case.file.name,
                name=f"{case.case.description} [{backend.name}]",
            )
            if status is Outcome.SKIP:
                counts["skipped"] += 1
                ET.SubElement(element, "skipped", message=case.skip_reasons.get(backend.name, ""))
            elif status is Outcome.XFAIL:
                counts["skipped"] += 1
                divergence = case.xfails.get(backend.name, "")
                ET.SubElement(element, "skipped", type="xfail", message=f"xfail: {divergence}")
            elif status in (Outcome.ERROR, Outcome.TIMEOUT, Outcome.CRASH):
                counts["errors"] += 1
                error = ET.SubElement(element, "error", type=status.value, message=status.value)
                error.text = case.aborted or ""
            elif status is Outcome.FAIL:
                counts["failures"] += 1
                failures = case.failures_of(backend.name)
                failure = ET.SubElement(element, "failure", message=failures[0].what)
                failure.text = "\n".join(
                    f"{f.step}: {f.what} [{f.backend}] expected {_show(f.expected)}, "
                    f"actual {_show(f.actual)}"
                    for f in failures
                )
    for message in report.input_errors:
        counts["tests"] += 1
        counts["errors"] += 1
        element = ET.SubElement(suite, "testcase", classname="corpus", name=message[:200])
        error = ET.SubElement(element, "error", type="input", message="bad scenario input")
        error.text = message
    for key, value in counts.items():
        suite.set(key, str(value))
    ET.indent(suite)
    path.parent.mkdir(parents=True, exist_ok=True)
    ET.ElementTree(suite).write(path, encoding="utf-8", xml_declaration=True)
