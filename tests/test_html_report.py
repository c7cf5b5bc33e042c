"""report.html (``conformance._run.html_report``) and the heatmap of changing rows.

The page is read back with the standard library's ``html.parser``: the rows
that change come first, the rows alike everywhere are folded into one closed
``<details>``, and each changed cell holds the first step that differs with
both answers. The runs are real: a mutant of reimpl against pydrake in this
process, and (where cached) Drake releases in their own environments. The
``browser`` test loads the page in a headless Chromium (skipped without one).
"""

from __future__ import annotations

import io
import json
import shutil
import subprocess
from dataclasses import dataclass, field
from html.parser import HTMLParser
from pathlib import Path

import pytest

from conformance._backends.env_cache import missing_releases
from conformance._corpus.loader import Case, load_corpus
from conformance._run.html_report import html_report
from conformance._run.matrix import Cell, Matrix, Outcome, ReleaseRun, run_matrix
from conformance._run.matrix_report import write_heatmap, write_report
from conformance._run.report_rows import bands, release_baselines, rows, sections
from conformance.cli.main import main

SCENARIOS = Path(__file__).resolve().parents[1] / "scenarios"
MUTANT = "conformance._testing.mutants:reverse_statement_order"
MUTANT_NAME = "mutant:reverse_statement_order"
HISTORY = "transient/history > removing an earlier declaration replays the later ones on the "
LINES_1_7 = "transient/table1 > Table 1 lines 1-7 hold step by step"
UNDEFINED_GROUP = (
    "models/model_errors > ignoring an undefined group is an error naming the scoped group"
)
TABLE_1 = "transient/table1 > Table 1 lines 1-7 hold step by step"
_VOID = frozenset({"meta", "br", "hr", "img", "input", "link"})


# ------------------------------------------------------------------ reading the page
@dataclass
class Node:
    tag: str
    attrs: dict[str, str]
    #: Child elements and text, in document order.
    content: list[Node | str] = field(default_factory=list)

    @property
    def classes(self) -> set[str]:
        return set(self.attrs.get("class", "").split())

    @property
    def children(self) -> list[Node]:
        return [c for c in self.content if isinstance(c, Node)]

    def all(self, tag: str, cls: str | None = None) -> list[Node]:
        """Every descendant ``tag`` (with class ``cls``), in document order."""
        found = []
        for child in self.children:
            if tag in (child.tag, "*") and (cls is None or cls in child.classes):
                found.append(child)
            found += child.all(tag, cls)
        return found

    def one(self, tag: str, cls: str | None = None) -> Node:
        (found,) = self.all(tag, cls)
        return found

    def by_id(self, name: str) -> Node:
        (found,) = [n for n in self.all("*") if n.attrs.get("id") == name] or [None]
        assert found is not None, name
        return found

    def words(self) -> str:
        return "".join(c if isinstance(c, str) else c.words() for c in self.content)


class _Tree(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.root = Node("#document", {})
        self.stack = [self.root]

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        node = Node(tag, {k: v or "" for k, v in attrs})
        self.stack[-1].content.append(node)
        if tag not in _VOID:
            self.stack.append(node)

    def handle_endtag(self, tag: str) -> None:
        if tag in _VOID or all(n.tag != tag for n in self.stack):
            return
        while self.stack[-1].tag != tag:  # N.B. the page closes every element it opens
            self.stack.pop()
        self.stack.pop()

    def handle_data(self, data: str) -> None:
        self.stack[-1].content.append(data)


def parse(page: str) -> Node:
    tree = _Tree()
    tree.feed(page)
    tree.close()
    assert tree.stack == [tree.root], "an element is left open"
    return tree.root


def row_cases(root: Node) -> list[str]:
    """The data-case of every row of the page, in document order."""
    return [tr.attrs["data-case"] for tr in root.all("tr", "row")]


def step_of(cell: Node) -> dict[str, object]:
    """A changed cell's first differing step: where, and each column's answer."""
    detail = cell.one("div", "step-detail")
    columns = [dt.words() for dt in detail.all("dt")]
    answers = [dd.one("pre").words() for dd in detail.all("dd")]
    return {
        "where": detail.one("b", "where").words(),
        "answers": dict(zip(columns, answers, strict=True)),
    }


def assert_self_contained(page: str) -> None:
    for outside in ("http://", "https://", "<script", "<link", "src=", "@import", "url("):
        assert outside not in page, outside


# ------------------------------------------------------------------ run --report
@pytest.fixture(scope="module")
def run_page(tmp_path_factory: pytest.TempPathFactory) -> tuple[int, Path]:
    folder = tmp_path_factory.mktemp("run") / "report"
    out, err = io.StringIO(), io.StringIO()
    code = main(
        [
            "run",
            str(SCENARIOS / "transient"),
            "--backend",
            MUTANT,
            "--backend",
            "pydrake",
            "--report",
            str(folder),
            "-q",
        ],
        out=out,
        err=err,
    )
    assert f"wrote {folder / 'report.html'}" in out.getvalue()
    return code, folder


def test_run_report_puts_the_cases_the_mutant_fails_on_top_and_folds_the_other_nine(
    run_page: tuple[int, Path],
) -> None:
    """reverse_statement_order fails 3 of the 12 transient cases against pydrake 1.51.1
    (measured); they are the page's first rows, and the 9 others are one closed count."""
    code, folder = run_page
    assert code == 1
    document = json.loads((folder / "report.json").read_text())
    failed = [c["qualified_name"] for c in document["cases"] if c["status"][MUTANT_NAME] == "fail"]
    assert len(failed) == 3
    assert len(document["cases"]) == 12
    page = (folder / "report.html").read_text()
    assert_self_contained(page)
    root = parse(page)
    changed = [tr.attrs["data-case"] for tr in root.by_id("changed-rows").all("tr", "row")]
    assert changed == failed
    assert row_cases(root)[:3] == failed  # on top of the page
    alike = root.by_id("alike")
    assert alike.tag == "details"
    assert "open" not in alike.attrs
    assert alike.one("summary").words().startswith("9 case(s) answer alike on both columns")
    assert len(alike.all("tr", "row")) == 9
    assert root.one("p", "summary").words() == (
        "12 cases on 2 column(s): 3 change across them, 0 fail alike everywhere, "
        "9 answer alike everywhere."
    )


def test_a_changed_cell_of_run_opens_the_first_differing_step_with_both_answers(
    run_page: tuple[int, Path],
) -> None:
    """Measured on pydrake 1.51.1: after step 1 of the history case pydrake's C at the model
    is [g0-g2] and the mutant's empty; Table 1 lines 1-7 first differ at step 4, alike."""
    _, folder = run_page
    root = parse((folder / "report.html").read_text())
    rows = {tr.attrs["data-case"]: tr for tr in root.all("tr", "row")}
    history = next(tr for name, tr in rows.items() if name.startswith(HISTORY))
    reference, mutant = history.all("td", "cell")
    assert reference.attrs["data-column"] == "pydrake"  # the reference is the first column
    assert "k-pass" in reference.classes
    assert not reference.all("details")
    assert {"k-fail", "changed-cell"} <= mutant.classes
    assert step_of(mutant) == {
        "where": "step 1",
        "answers": {"pydrake": '["g0-g2"]', MUTANT_NAME: "[]"},
    }
    assert step_of(rows[LINES_1_7].all("td", "cell")[1]) == {
        "where": "step 4",
        "answers": {"pydrake": '["g0-g2"]', MUTANT_NAME: "[]"},
    }


def test_run_report_refuses_a_report_folder_that_is_a_file(tmp_path: Path) -> None:
    (tmp_path / "taken").write_text("")
    err = io.StringIO()
    code = main(["run", "--report", str(tmp_path / "taken")], out=io.StringIO(), err=err)
    assert code == 2
    assert f"--report {tmp_path / 'taken'}: {tmp_path / 'taken'} is not a folder" in err.getvalue()


# ------------------------------------------------------------------ expected breaks
def _two_releases(cells: dict[str, tuple[Cell, Cell]]) -> Matrix:
    """A matrix of two releases holding ``cells`` (case → the two releases' cells)."""
    matrix = Matrix(["1.30.0", "1.51.1"], list(cells))
    for index, version in enumerate(matrix.versions):
        run = ReleaseRun(version, python="3.11")
        run.cells = {case: pair[index] for case, pair in cells.items()}
        matrix.runs[version] = run
    return matrix


def test_an_expected_crash_is_drawn_and_named_unlike_an_unexpected_one() -> None:
    """The cells are as ``matrix.outcome_of`` gives them: a crash that the crash row
    undefined-ignored-group-aborts records (1.30.0's answer) has ``expected_by``; one that
    nothing expects has none, fails, and its row goes first."""
    matrix = _two_releases(
        {
            "a > recorded": (
                Cell(Outcome.CRASH, "step 1: worker died", "undefined-ignored-group-aborts"),
                Cell(Outcome.PASS),
            ),
            "a > same": (Cell(Outcome.PASS), Cell(Outcome.PASS)),
            "a > unexpected": (Cell(Outcome.CRASH, "step 2: worker died"), Cell(Outcome.PASS)),
        }
    )
    root = parse(html_report(matrix, release_baselines(matrix), title="t", baseline="b"))
    assert row_cases(root) == ["a > unexpected", "a > recorded", "a > same"]
    unexpected, recorded = (tr.all("td", "cell")[0] for tr in root.all("tr", "row")[:2])
    assert "k-crash" in unexpected.classes
    assert "k-expected-crash" not in unexpected.classes
    assert "k-expected-crash" in recorded.classes
    assert unexpected.words().startswith("‼ crash")
    assert recorded.words().startswith("◇ expected crash")
    assert "expected by undefined-ignored-group-aborts" in recorded.words()


# ------------------------------------------------------------------ the heatmap
def _size(png: Path) -> tuple[int, int]:
    """A PNG's width and height (its IHDR chunk)."""
    data = png.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")


def test_the_heatmap_draws_only_the_changing_rows(tmp_path: Path) -> None:
    alike = {f"f > alike {i}": (Cell(Outcome.PASS), Cell(Outcome.PASS)) for i in range(60)}
    two = {f"f > changed {i}": (Cell(Outcome.SKIP), Cell(Outcome.PASS)) for i in range(2)}
    few = _size(write_heatmap(_two_releases(two | alike), tmp_path / "few.png"))
    only = _size(write_heatmap(_two_releases(two), tmp_path / "two.png"))
    assert few == only  # the 60 alike rows are not drawn
    none = _size(write_heatmap(_two_releases(alike), tmp_path / "none.png"))
    assert none[1] < few[1]
    assert none[1] <= 140  # one line of words


def test_cases_that_look_alike_are_one_heatmap_row_and_a_failing_case_keeps_its_own(
    tmp_path: Path,
) -> None:
    arrive = {f"f > arrives {i}": (Cell(Outcome.SKIP), Cell(Outcome.PASS)) for i in range(40)}
    failing = {
        f"f > fails {i}": (Cell(Outcome.FAIL, "step 1: no error"), Cell(Outcome.PASS))
        for i in range(2)
    }
    matrix = _two_releases(failing | arrive)
    drawn = bands(sections(rows(matrix, release_baselines(matrix))).changed)
    assert [b.label for b in drawn] == [
        "f > fails 0",
        "f > fails 1",
        "40 cases: unsupported 1.30.0 · pass 1.51.1",
    ]
    many = _size(write_heatmap(_two_releases(dict(list(arrive.items())[:40])), tmp_path / "a.png"))
    two = _size(write_heatmap(_two_releases(dict(list(arrive.items())[:20])), tmp_path / "b.png"))
    assert many == two  # 40 alike rows are drawn as one, as 20 are


# ------------------------------------------------------------------ real releases
def _cached(version: str) -> bool:
    return not missing_releases([version])  # the tests' cache, or the real one (read-only)


def _case(name: str) -> Case:
    return next(c for f in load_corpus() for c in f.cases if c.qualified_name == name)


@pytest.mark.skipif(
    not (_cached("1.30.0") and _cached("1.51.1")), reason="needs cached Drake 1.30.0 and 1.51.1"
)
def test_a_release_matrix_page_shows_the_1_30_crash_row_and_its_first_differing_step(
    tmp_path: Path,
) -> None:
    """Measured: Drake 1.30.0's worker dies on an undefined ignored group in add_models
    (the crash row undefined-ignored-group-aborts records it: pass as expected there);
    1.51.1 answers every step. Table 1 is alike on both."""
    matrix = run_matrix(["1.30.0", "1.51.1"], [_case(TABLE_1), _case(UNDEFINED_GROUP)], jobs=2)
    paths = write_report(matrix, tmp_path)
    assert [p.name for p in paths] == ["report.json", "report.md", "report.html", "heatmap.png"]
    root = parse(paths[2].read_text())
    assert row_cases(root) == [UNDEFINED_GROUP, TABLE_1]
    old, new = root.all("tr", "row")[0].all("td", "cell")
    assert "k-expected-crash" in old.classes
    assert step_of(new) == {
        "where": "end",
        "answers": {
            "1.30.0": "0 of 1: BackendCrashError at step 1 (add_models)",
            "1.51.1": "all 1",
        },
    }


# ------------------------------------------------------------------ a real browser
@pytest.mark.browser
@pytest.mark.skipif(shutil.which("chromium") is None, reason="no chromium on PATH")
def test_chromium_renders_the_run_page_with_the_changed_rows_first(
    run_page: tuple[int, Path], tmp_path: Path
) -> None:
    """Headless Chromium loads the page from disk (no network) and its DOM keeps the
    changed rows first and the first changed cell open."""
    _, folder = run_page
    url = (folder / "report.html").as_uri()
    chromium = ["chromium", "--headless", "--no-sandbox", "--disable-gpu"]
    dom = subprocess.run(
        [*chromium, "--dump-dom", url], capture_output=True, text=True, timeout=120, check=True
    ).stdout
    root = parse(dom)
    first = root.all("tr", "row")[0]
    assert first.attrs["data-case"].startswith(HISTORY)
    assert "open" in first.one("details", "step").attrs
    shot = tmp_path / "shot.png"
    subprocess.run(
        [*chromium, f"--screenshot={shot}", "--window-size=1200,900", url],
        capture_output=True,
        timeout=120,
        check=True,
    )
    assert shot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
