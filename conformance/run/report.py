"""Run results as people and CI want them: a summary table, failure details, JUnit, JSON."""

from __future__ import annotations

import json
import shlex
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TextIO

from conformance.protocol import Backend
from conformance.run.runner import CaseReport, Status

__all__ = ["RunReport", "write_json", "write_junit"]


@dataclass
class RunReport:
    """Everything a run found, in corpus order."""

    backends: Sequence[Backend]
    cases: list[CaseReport] = field(default_factory=list)
    aborted: str | None = None  # why the run stopped early, if it did

    def count(self, backend: str, status: Status) -> int:
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
            *[f"{b.name} ({b.version()})" for b in self.backends],
        ]
        rows = [header]
        for file, cases in files.items():
            row = [file, str(len(cases))]
            for name in names:
                row.append(_cell(sum(1 for c in cases if c.status.get(name) is s) for s in Status))
            rows.append(row)
        total = ["total", str(len(self.cases))]
        total += [_cell(self.count(n, s) for s in Status) for n in names]
        rows.append(total)
        widths = [max(len(r[i]) for r in rows) for i in range(len(header))]
        for i, row in enumerate(rows):
            if i in (1, len(rows) - 1):
                out.write("  ".join("-" * w for w in widths) + "\n")
            out.write("  ".join(cell.ljust(w) for cell, w in zip(row, widths, strict=True)) + "\n")

    def print_failures(self, out: TextIO, *, prog: str) -> None:
        for case in self.failed:
            out.write(f"\nFAIL {case.case.qualified_name}\n")
            for failure in case.failures:
                out.write(f"  {failure.step}: {failure.what} [{failure.backend}]\n")
                out.write(f"    expected: {_show(failure.expected)}\n")
                out.write(f"    actual:   {_show(failure.actual)}\n")
            rerun = [
                *prog.split(),
                "run",
                str(case.case.file.path),
                "--case",
                case.case.description,
            ]
            rerun += [arg for b in self.backends for arg in ("--backend", b.name)]
            out.write(f"  rerun: {shlex.join(rerun)}\n")

    def to_json(self) -> dict[str, Any]:
        return {
            "backends": {b.name: {"version": b.version()} for b in self.backends},
            "summary": {
                b.name: {s.value: self.count(b.name, s) for s in Status} for b in self.backends
            },
            "aborted": self.aborted,
            "cases": [
                {
                    "qualified_name": c.case.qualified_name,
                    "status": {k: v.value for k, v in c.status.items()},
                    "skip_reasons": c.skip_reasons,
                    "failures": [f.to_json() for f in c.failures],
                }
                for c in self.cases
            ],
        }


def _cell(counts: Any) -> str:
    passed, failed, skipped = counts
    return f"{passed} pass, {failed} fail, {skipped} skip"


def _show(value: Any) -> str:
    return json.dumps(value, sort_keys=True) if not isinstance(value, str) else value


def write_json(report: RunReport, path: Path) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(report.to_json(), indent=2, sort_keys=True) + "\n")


def write_junit(report: RunReport, path: Path) -> None:
    """One <testcase> per case and backend; classname is the scenario file."""
    suite = ET.Element("testsuite", name="conformance")
    counts = {"tests": 0, "failures": 0, "skipped": 0}
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
            if status is Status.SKIP:
                counts["skipped"] += 1
                ET.SubElement(element, "skipped", message=case.skip_reasons.get(backend.name, ""))
            elif status is Status.FAIL:
                counts["failures"] += 1
                failures = case.failures_of(backend.name)
                failure = ET.SubElement(element, "failure", message=failures[0].what)
                failure.text = "\n".join(
                    f"{f.step}: {f.what} [{f.backend}] expected {_show(f.expected)}, "
                    f"actual {_show(f.actual)}"
                    for f in failures
                )
    for key, value in counts.items():
        suite.set(key, str(value))
    suite.set("errors", "0")
    ET.indent(suite)
    path.parent.mkdir(parents=True, exist_ok=True)
    ET.ElementTree(suite).write(path, encoding="utf-8", xml_declaration=True)
