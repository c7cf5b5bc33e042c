"""The docs cannot drift from the command line, the repository, or what CI runs.

- Each subcommand's ``--help`` options equal the options table its docs page holds: a
  Markdown table right after ``<!-- options: NAME -->`` whose first column lists each
  option in backquotes (``-q``, ``--quiet``), positionals by their metavar.
- Every repository path README.md and docs/ name (in backquotes or as a link) exists.
- Every fenced shell command of README.md that starts with ``python -m conformance`` is run
  by CI (.ci/run) or by a test, as RUNNERS says; a README command missing from RUNNERS fails.

The numbers the docs quote are held by ``cog --check`` (docs/facts.py), run in CI.
"""

from __future__ import annotations

import argparse
import re
import shlex
from dataclasses import dataclass
from pathlib import Path

import pytest

from conformance.cli.main import _parser

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
README = ROOT / "README.md"
PAGES = sorted(DOCS.glob("*.md"))
#: Reports written by commands, not by hand: their paths are the command's business.
GENERATED = {DOCS / "release_facts.md"}


def _subcommands() -> dict[str, argparse.ArgumentParser]:
    parser = _parser()
    (action,) = (a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return {"conformance": parser, **action.choices}


def _help_options(parser: argparse.ArgumentParser) -> set[str]:
    """Every option string and positional metavar the parser's --help lists, but -h."""
    names: set[str] = set()
    for action in parser._actions:
        if isinstance(action, argparse._HelpAction | argparse._SubParsersAction):
            continue
        if action.option_strings:
            names.update(action.option_strings)
        else:
            metavar = action.metavar if isinstance(action.metavar, str) else action.dest
            names.add(metavar)
    return names


_OPTIONS_TABLE = re.compile(r"<!-- options: ([\w-]+) -->\n((?:\|.*\n)+)")


def _documented_options() -> dict[str, tuple[Path, set[str]]]:
    """Each options table of docs/: its subcommand, page and the names in its first column."""
    tables: dict[str, tuple[Path, set[str]]] = {}
    for page in PAGES:
        for name, table in _OPTIONS_TABLE.findall(page.read_text(encoding="utf-8")):
            assert name not in tables, f"{name} has options tables in {tables[name][0]} and {page}"
            rows = table.splitlines()[2:]  # the header and the --- line
            names: set[str] = set()
            for row in rows:
                first = row.split("|")[1]
                for span in re.findall(r"`([^`]+)`", first):
                    names.add(span.split()[0])
            tables[name] = (page, names)
    return tables


@pytest.mark.parametrize("command", sorted(_subcommands()))
def test_a_subcommands_docs_table_lists_exactly_the_options_of_its_help(command: str) -> None:
    tables = _documented_options()
    assert command in tables, f"no '<!-- options: {command} -->' table in docs/*.md"
    page, documented = tables[command]
    helped = _help_options(_subcommands()[command])
    assert documented == helped, (
        f"{page.name}: only in the docs {sorted(documented - helped)}, "
        f"only in --help {sorted(helped - documented)}"
    )


def test_every_options_table_belongs_to_a_subcommand() -> None:
    assert set(_documented_options()) <= set(_subcommands())


# ------------------------------------------------------------------------ paths named
_TOP = ("reimpl", "conformance", "scenarios", "tests", "examples", "benchmarks", "docs", ".ci")
#: Paths the docs name that a run makes, not the repository.
_MADE_BY_RUNS = {"scenarios/regressions", "scenarios/regressions/"}


def _named_paths(page: Path) -> set[str]:
    text = page.read_text(encoding="utf-8")
    spans = set(re.findall(r"`([^`\n]+)`", text))
    links = {
        target for target in re.findall(r"\]\(([^)\s#]+)(?:#[^)]*)?\)", text) if "://" not in target
    }
    paths = {span for span in spans if span.split("/", 1)[0] in _TOP and " " not in span}
    return paths | {f"link:{target}" for target in links}


@pytest.mark.parametrize(
    "page", [README, *(p for p in PAGES if p not in GENERATED)], ids=lambda p: p.name
)
def test_every_repository_path_a_page_names_exists(page: Path) -> None:
    missing = []
    for named in sorted(_named_paths(page)):
        if named.startswith("link:"):
            path = (page.parent / named.removeprefix("link:")).resolve()
        else:
            if named in _MADE_BY_RUNS or "*" in named or "<" in named:
                continue
            path = ROOT / named.split("::")[0].split(":")[0]
        if not path.exists():
            missing.append(named)
    assert not missing, f"{page.name} names paths that do not exist: {missing}"


# ------------------------------------------------------------- README commands and runners
@dataclass(frozen=True)
class Runner:
    """Where a README command runs: .ci/run's line, or a test holding its arguments."""

    path: str
    #: .ci/run: the line that runs it. A test: its function name.
    where: str


_CI = ".ci/run"
RUNNERS: dict[str, Runner] = {
    "python -m conformance run": Runner(
        _CI,
        "python3 -m conformance run -q --junit reports/conformance-junit.xml "
        "--json reports/conformance.json",
    ),
    "python -m conformance matrix --drake 1.58.0 --report out": Runner(
        _CI, "python3 -m conformance matrix --drake 1.58.0 --report reports/matrix-1.58.0 -q"
    ),
    'python -m conformance bisect "*failing apply keeps its earlier statement*" --good 1.56.0 '
    "--bad 1.57.0 --by behaviour": Runner(
        "tests/test_matrix.py",
        "test_bisect_finds_that_1_57_stopped_a_failed_apply_writing_the_persistent_base",
    ),
    # The test runs the skeleton (MyBackend and pydrake_like) on two corpus files.
    "python -m conformance run --backend examples.my_backend:MyBackend --backend pydrake": Runner(
        "tests/test_cli_faults.py", "test_the_example_backend_skeleton_passes_against_pydrake"
    ),
    "python -m conformance run --backend exec:'node examples/node_backend/backend.js' "
    "--backend pydrake": Runner(
        _CI,
        "python3 -m conformance run --backend exec:'node examples/node_backend/backend.js' "
        "--backend pydrake",
    ),
    "python -m conformance fuzz --seed 1 --max-examples 300 --coverage": Runner(
        _CI,
        "python3 -m conformance fuzz --seed 1 --max-examples 300 --out reports/regressions "
        "--coverage --json reports/fuzz.json",
    ),
    "python -m conformance models my_robot --drake 1.51.1 1.58.0 --report report": Runner(
        _CI,
        "../../.venv-wheel/bin/python -m conformance models my_robot --drake 1.51.1 1.58.0 "
        "--report report -q",
    ),
    "python -m conformance models my_robot --drake 1.51.1 --save golden.json": Runner(
        _CI,
        "../../.venv-wheel/bin/python -m conformance models my_robot --drake 1.51.1 "
        "--save golden.json -q",
    ),
    "python -m conformance models my_robot --drake 1.58.0 --check golden.json": Runner(
        _CI,
        "../../.venv-wheel/bin/python -m conformance models my_robot --drake 1.58.0 "
        "--check golden.json",
    ),
}

#: Options whose value names where output goes: a runner may write elsewhere.
_OUTPUT_OPTIONS = {"--report", "--out", "--json", "--junit"}
#: Options that change only how much is printed.
_QUIET = {"-q", "--quiet"}


def _readme_commands() -> list[str]:
    commands = []
    text = README.read_text(encoding="utf-8")
    for block in re.findall(r"```(?:bash|sh|console)\n(.*?)```", text, re.S):
        for raw in block.replace("\\\n", " ").splitlines():
            line = raw.split(" #")[0].strip()
            if line.startswith("python -m conformance"):
                commands.append(" ".join(line.split()))
    return commands


def _arguments(command: str) -> tuple[list[str], dict[str, str]]:
    """The words after ``-m conformance``: positionals and flags in order, output paths aside."""
    words = shlex.split(command)
    words = words[words.index("conformance") + 1 :]
    kept: list[str] = []
    outputs: dict[str, str] = {}
    index = 0
    while index < len(words):
        word = words[index]
        if word in _OUTPUT_OPTIONS:
            outputs[word] = words[index + 1]
            index += 2
            continue
        if word not in _QUIET:
            kept.append(word)
        index += 1
    return kept, outputs


def test_every_readme_command_has_a_runner_and_every_runner_a_readme_command() -> None:
    shown = _readme_commands()
    assert shown, "README.md shows no python -m conformance command"
    assert set(shown) == set(RUNNERS), (
        f"in README.md without a runner: {sorted(set(shown) - set(RUNNERS))}; "
        f"runners for no README command: {sorted(set(RUNNERS) - set(shown))}"
    )


@pytest.mark.parametrize("command", sorted(RUNNERS))
def test_a_readme_command_is_run_by_ci_or_a_test(command: str) -> None:
    runner = RUNNERS[command]
    source = (ROOT / runner.path).read_text(encoding="utf-8")
    words, outputs = _arguments(command)
    if runner.path == _CI:
        assert runner.where in source, f"{runner.path} no longer runs: {runner.where}"
        ran, ran_outputs = _arguments(runner.where)
        assert ran == words, f"{runner.path} runs {ran}, the README shows {words}"
        assert set(outputs) <= set(ran_outputs), f"{runner.path} writes no {sorted(outputs)}"
    else:
        # The test with its decorators (a parametrize may give part of a word).
        match = re.search(
            rf"(?:^@.*\n)*^def {runner.where}\(.*?(?=^\S)", source + "\nend", re.S | re.M
        )
        assert match, f"{runner.path} has no test {runner.where}"
        body = match.group(0).lower()
        parts = [part for word in words for part in re.split(r"[:=]", word) if part]
        absent = [part for part in parts if part.lower() not in body]
        assert not absent, f"{runner.where} does not pass {absent}"
