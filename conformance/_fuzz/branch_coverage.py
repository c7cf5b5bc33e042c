"""Branch coverage of reimpl during a campaign, reported by function and used as feedback.

``BranchCoverage`` runs coverage.py (branch mode, in memory, no data file)
over ``MEASURED`` (``reimpl/geometry`` and ``reimpl/multibody``) while a
campaign runs; ``report`` then lists, by function, the lines and branches
that never ran (``FunctionGap``). Code outside any function (module level)
is left out: a campaign imports every module before it measures
(``campaign.load_local_modules``).

**Feedback** (``example_feedback``): at the end of each example the number
of reimpl arcs (branches taken) that no earlier example of the run took is
given to ``hypothesis.target`` under the label ``NEW_BRANCHES``. Hypothesis's
``target`` phase then mutates the examples that found the most new
branches, and keeps a mutation only where it finds more: coverage-guided
search on top of the generator. Only a measuring campaign calls ``target``
with it, so ``fuzz --seed S`` without ``--coverage`` draws what it always
drew; the model campaign measures without it unless asked
(``ModelCampaign.branch_feedback``).

Why this and not HypoFuzz or atheris (tried in May 2026 on this machine):
HypoFuzz 25.11 is under its own non-commercial licence (no modification or
redistribution, commercial use needs a paid licence), which an open-source
harness cannot depend on, not even as an extra. atheris (Apache-2.0) would
replace Hypothesis's generator and shrinker with libFuzzer's, and with them
the grammar-aware draws and the scenario findings. coverage.py is
Apache-2.0 and ``hypothesis.target`` is Hypothesis's own (MPL-2.0).

Long campaigns run this on many cores and machines through the fuzz shards
(``tests/test_fuzz_shards.py``: ``CONFORMANCE_FUZZ_COVERAGE=1`` turns it on
in every shard; ``CONFORMANCE_FUZZ_DB`` shares Hypothesis's example
database, in which the ``target`` phase's best examples are kept too).
"""

from __future__ import annotations

import importlib.util
import json
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hypothesis import target

__all__ = [
    "MEASURED",
    "NEW_BRANCHES",
    "BranchCoverage",
    "BranchReport",
    "FunctionGap",
    "example_feedback",
]

#: The packages whose branches a campaign measures.
MEASURED = ("reimpl.geometry", "reimpl.multibody")
#: The ``hypothesis.target`` label of the feedback.
NEW_BRANCHES = "new reimpl branches"

#: The instance measuring now (coverage.py measures one at a time in a process).
_measuring: list[BranchCoverage] = []


def _folder(package: str) -> str:
    spec = importlib.util.find_spec(package)
    if spec is None or not spec.submodule_search_locations:
        raise ImportError(f"{package} is not a package")
    return str(Path(next(iter(spec.submodule_search_locations))))


@dataclass(frozen=True)
class FunctionGap:
    """A function with lines or branches that never ran."""

    file: str
    function: str
    start_line: int
    missing_lines: tuple[int, ...]
    #: (from line, to line); a negative "to" is an exit from the function.
    missing_branches: tuple[tuple[int, int], ...]
    #: Statements of the function, and how many ran.
    statements: int
    covered: int

    @property
    def never_called(self) -> bool:
        return self.covered == 0


@dataclass(frozen=True)
class BranchReport:
    """What a measured run covered of ``MEASURED``."""

    statements: int
    covered_lines: int
    branches: int
    covered_branches: int
    gaps: tuple[FunctionGap, ...]

    def function(self, qualname: str) -> FunctionGap | None:
        """The gap of the function of this qualified name (any file), or None if covered."""
        return next((g for g in self.gaps if g.function == qualname), None)

    def table(self, *, limit: int = 40) -> str:
        """What ``fuzz --coverage`` prints: the totals, then the functions never called,
        then up to ``limit`` partly run functions with their missing lines and branches."""
        never = [g for g in self.gaps if g.never_called]
        partly = sorted(
            (g for g in self.gaps if not g.never_called),
            key=lambda g: (-len(g.missing_branches) - len(g.missing_lines), g.file, g.start_line),
        )
        lines = [
            f"reimpl branches: {self.covered_branches} of {self.branches} branches and "
            f"{self.covered_lines} of {self.statements} lines run "
            f"(reimpl/geometry, reimpl/multibody; function bodies); "
            f"{len(never)} functions never called, {len(partly)} partly run"
        ]
        if never:
            lines.append("  never called:")
            by_file: dict[str, list[str]] = {}
            for gap in never:
                by_file.setdefault(gap.file, []).append(gap.function)
            for file, names in sorted(by_file.items()):
                lines.append(f"    {file}: {', '.join(names)}")
        if partly:
            lines.append("  partly run (missing lines; missing branches from->to):")
        for gap in partly[:limit]:
            arcs = " ".join(f"{a}->{b}" for a, b in gap.missing_branches)
            lines.append(
                f"    {gap.file}:{gap.start_line} {gap.function}: "
                f"lines {_ranges(gap.missing_lines) or '-'}; branches {arcs or '-'}"
            )
        if len(partly) > limit:
            lines.append(f"    ... and {len(partly) - limit} more (--json has them all)")
        return "\n".join(lines)

    def to_json(self) -> dict[str, Any]:
        return {
            "statements": self.statements,
            "covered_lines": self.covered_lines,
            "branches": self.branches,
            "covered_branches": self.covered_branches,
            "functions": [
                {
                    "file": g.file,
                    "function": g.function,
                    "start_line": g.start_line,
                    "missing_lines": list(g.missing_lines),
                    "missing_branches": [list(arc) for arc in g.missing_branches],
                }
                for g in self.gaps
            ],
        }


def _ranges(numbers: tuple[int, ...]) -> str:
    """1, 2, 3, 7 → '1-3, 7'."""
    runs: list[list[int]] = []
    for n in numbers:
        if runs and runs[-1][1] == n - 1:
            runs[-1][1] = n
        else:
            runs.append([n, n])
    return ", ".join(f"{a}" if a == b else f"{a}-{b}" for a, b in runs)


class BranchCoverage:
    """coverage.py over ``packages`` while ``measuring``; see the module doc."""

    def __init__(self, packages: tuple[str, ...] = MEASURED, *, feedback: bool = True) -> None:
        import coverage  # noqa: PLC0415 (only a measuring campaign needs it)

        self.packages = packages
        #: Give each example's new branches to ``hypothesis.target`` (False: measure only,
        #: as ``benchmarks/bench_guidance.py`` does to weigh the feedback).
        self.feedback = feedback
        self._coverage = coverage.Coverage(
            branch=True,
            data_file=None,
            source=[_folder(p) for p in packages],
            config_file=False,
        )
        self._arcs_seen = 0

    @contextmanager
    def measuring(self) -> Iterator[BranchCoverage]:
        """Measures in the block; ``example_feedback`` targets new branches meanwhile."""
        if _measuring:
            raise RuntimeError("branch coverage is already being measured")
        self._coverage.start()
        _measuring.append(self)
        try:
            yield self
        finally:
            _measuring.clear()
            self._coverage.stop()

    def new_arcs(self) -> int:
        """Arcs taken since the last call that no earlier call saw."""
        data = self._coverage.get_data()
        total = sum(len(data.arcs(f) or ()) for f in data.measured_files())
        new, self._arcs_seen = total - self._arcs_seen, total
        return new

    def report(self) -> BranchReport:
        """The gaps, by function (coverage.py's JSON report, read back)."""
        with tempfile.TemporaryDirectory() as folder:
            path = Path(folder) / "coverage.json"
            self._coverage.json_report(outfile=str(path))
            data = json.loads(path.read_text())
        gaps: list[FunctionGap] = []
        totals = [0, 0, 0, 0]
        root = Path(_folder("reimpl")).parent
        for file, entry in data["files"].items():
            name = _relative(file, root)
            for function, info in entry["functions"].items():
                if not function:  # module level: run at import, before measuring
                    continue
                summary = info["summary"]
                totals[0] += summary["num_statements"]
                totals[1] += summary["covered_lines"]
                totals[2] += summary.get("num_branches", 0)
                totals[3] += summary.get("covered_branches", 0)
                if info["missing_lines"] or info["missing_branches"]:
                    gaps.append(
                        FunctionGap(
                            file=name,
                            function=function,
                            start_line=info.get("start_line", 0),
                            missing_lines=tuple(info["missing_lines"]),
                            missing_branches=tuple(tuple(a) for a in info["missing_branches"]),
                            statements=summary["num_statements"],
                            covered=summary["covered_lines"],
                        )
                    )
        gaps.sort(key=lambda g: (g.file, g.start_line))
        return BranchReport(
            statements=totals[0],
            covered_lines=totals[1],
            branches=totals[2],
            covered_branches=totals[3],
            gaps=tuple(gaps),
        )


def _relative(file: str, root: Path) -> str:
    try:
        return str(Path(file).resolve().relative_to(root.resolve()))
    except ValueError:
        return file


def example_feedback() -> None:
    """At the end of an example: ``target`` the new branches it took (while measuring)."""
    for measuring in _measuring:
        if measuring.feedback:
            target(float(measuring.new_arcs()), label=NEW_BRANCHES)
