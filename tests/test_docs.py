"""The docs cannot drift from the command line, the repository, or what CI runs.

- Each subcommand's ``--help`` options equal the options table its docs page holds: a
  Markdown table right after ``<!-- options: NAME -->`` whose first column lists each
  option in backquotes (``-q``, ``--quiet``), positionals by their metavar.
- Every repository path README.md and docs/ name (in backquotes or as a link) exists.
- Every command a fenced bash block of README.md or docs/ shows that starts with
  ``python -m conformance``, ``python -m pytest``, ``pytest`` (after ``NAME=value``
  variables) or ``pip install`` is run by a CI line (.ci/run) or a test, as RUNNERS says,
  with the exit status the docs give it; one missing from RUNNERS fails. Usage synopses
  (``[--opt ...]``) are skipped; a *bounded* runner narrows only what _NARROWS allows.

The numbers the docs quote are held by ``cog --check`` (docs/facts.py), run in CI.
"""

from __future__ import annotations

import argparse
import re
import shlex
from dataclasses import dataclass, replace
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


# ------------------------------------------------------ shown commands and their runners
_PROGRAMS = ("python -m conformance", "python -m pytest", "pytest", "pip install")
#: Shown commands that are not of a checked kind, and why.
UNCHECKED = {"bash .ci/run": "CI's entry point itself: the runners below are its lines"}


def _shown_commands() -> dict[str, list[str]]:
    """Each command of a fenced bash/sh/console block of README.md and docs/, by page.

    Backslash continuations are joined and `` # `` comments dropped. A line holding a word
    that starts with ``[`` (``[--seed S]``, ``[PATHS...]``) is a usage synopsis, syntax
    rather than a command, and is skipped, as are a synopsis' continuation lines (each starts
    with ``[``).
    """
    shown: dict[str, list[str]] = {}
    for page in [README, *(p for p in PAGES if p not in GENERATED)]:
        text = page.read_text(encoding="utf-8")
        for block in re.findall(r"```(?:bash|sh|console)\n(.*?)```", text, re.S):
            for raw in block.replace("\\\n", " ").splitlines():
                words = raw.split(" #")[0].split()
                if words and not any(word.startswith("[") for word in words):
                    shown.setdefault(" ".join(words), []).append(page.name)
    return shown


def _checked(command: str) -> bool:
    """A command after its ``NAME=value`` environment starts with one of _PROGRAMS."""
    words = command.split()
    while words and re.fullmatch(r"[A-Z_]+=\S*", words[0]):
        words.pop(0)
    return any(" ".join(words).startswith(program) for program in _PROGRAMS)


@dataclass(frozen=True)
class Runner:
    """Where a shown command runs: .ci/run's line, or a test holding its arguments.

    ``exit`` is the status the docs give the command: a CI line that exits 0 runs plainly
    under ``set -e`` (no ``if``, ``!``, ``||`` or ``&&`` around it); one that exits N otherwise is
    run as ``exits N COMMAND`` (.ci/run's helper, which fails on any other status). A test
    asserts it (``EXIT_OK``/``ExitCode.OK``/``== 0``, ``EXIT_FAILURE``/``== 1``).

    ``bounds`` make a *bounded* runner of a command heavy by nature: each is (the shown
    words, the runner's words) for one option, env variable or path that _NARROWS allows,
    and must narrow it (fewer releases, seeds, examples or seconds, a case glob added,
    folders below the shown one). Every other argument is the same.
    """

    path: str
    #: .ci/run: the line that runs it. A test: its function name.
    where: str
    exit: int = 0
    bounds: tuple[tuple[str, str], ...] = ()


def _release(version: str, fill: int) -> tuple[int, ...]:
    parts = [int(part) for part in version.split(".")]
    return tuple(parts + [fill] * (3 - len(parts)))


def _span(spec: str) -> tuple[tuple[int, ...], tuple[int, ...]]:
    """The releases a ``--drake`` spec names: ``1.30.0``, or ``1.12..1.58``."""
    first, _, last = spec.partition("..")
    return _release(first, 0), _release(last or first, 10**9 if last else 0)


def _within(ran: list[str], shown: list[str]) -> bool:
    spans = [_span(spec) for spec in shown]
    return all(
        any(lo <= _span(spec)[0] and _span(spec)[1] <= hi for lo, hi in spans) for spec in ran
    )


def _seeds(value: str) -> range:
    first, _, last = value.partition("-")
    return range(int(first), int(last or first) + 1)


#: What a bound may change, and how it must narrow: (shown values, ran values) -> narrows.
#: A bound whose shown words are empty adds the option, narrowing its default (fuzz: 100
#: examples, 50 steps; tests/test_fuzz_shards.py: 50 examples; every case).
_NARROWS = {
    "--drake": lambda shown, ran: _within(ran, shown),
    "--good": lambda shown, ran: _release(ran[0], 0) >= _release(shown[0], 0),
    "--bad": lambda shown, ran: _release(ran[0], 0) <= _release(shown[0], 0),
    "--time-budget": lambda shown, ran: float(ran[0]) < float(shown[0]),
    "--shrink-time": lambda shown, ran: float(ran[0]) < float(shown[0]),
    "--max-examples": lambda shown, ran: int(ran[0]) < int(shown[0] if shown else 100),
    "--steps": lambda shown, ran: int(ran[0]) < int(shown[0] if shown else 50),
    "--case": lambda shown, ran: not shown,
    "CONFORMANCE_FUZZ_SEEDS": lambda shown, ran: set(_seeds(ran[0])) < set(_seeds(shown[0])),
    "CONFORMANCE_FUZZ_EXAMPLES": lambda shown, ran: int(ran[0]) < int(shown[0] if shown else 50),
    "PATH": lambda shown, ran: all(path.startswith(shown[0].rstrip("/") + "/") for path in ran),
}


def _bound_name(words: list[str]) -> tuple[str, list[str]]:
    """A bound's option (or env variable, or PATH) and its values."""
    if not words:
        return "", []
    if "=" in words[0] and not words[0].startswith("-"):
        name, _, value = words[0].partition("=")
        return name, [value]
    if words[0].startswith("-"):
        return words[0], words[1:]
    return "PATH", words


_CI = ".ci/run"
_WHEEL = "../../.venv-wheel/bin/python"
_TRANSIENT = ("", "--case transient/*")
RUNNERS: dict[str, Runner] = {
    "pip install -e '.[dev]' -c constraints.txt": Runner(
        _CI, "python3 -m pip install --quiet -e '.[dev]' -c constraints.txt"
    ),
    "python -m conformance run": Runner(
        _CI,
        "python3 -m conformance run -q --junit reports/conformance-junit.xml "
        "--json reports/conformance.json",
    ),
    "python -m pytest -n auto": Runner(_CI, "python3 -m pytest -n auto"),
    "python -m conformance --version": Runner(
        "tests/test_cli_faults.py", "test_version_names_the_package_and_the_installed_drake"
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
        "--backend pydrake -q --json reports/node-backend.json",
    ),
    "python -m conformance fuzz --seed 1 --max-examples 300 --coverage": Runner(
        _CI,
        "python3 -m conformance fuzz --seed 1 --max-examples 300 --out reports/regressions "
        "--coverage --json reports/fuzz.json",
    ),
    "CONFORMANCE_FUZZ_COVERAGE=1 CONFORMANCE_FUZZ_SEEDS=0-63 CONFORMANCE_FUZZ_DB=/shared/fuzz-db "
    "pytest -m fuzz -n auto tests/test_fuzz_shards.py": Runner(
        _CI,
        "CONFORMANCE_FUZZ_COVERAGE=1 CONFORMANCE_FUZZ_SEEDS=0-1 CONFORMANCE_FUZZ_EXAMPLES=20 "
        "CONFORMANCE_FUZZ_DB=reports/fuzz-db python3 -m pytest -m fuzz -n auto "
        "tests/test_fuzz_shards.py -q",
        bounds=(
            ("CONFORMANCE_FUZZ_SEEDS=0-63", "CONFORMANCE_FUZZ_SEEDS=0-1"),
            ("", "CONFORMANCE_FUZZ_EXAMPLES=20"),
        ),
    ),
    "python -m conformance models my_robot --drake 1.51.1 1.58.0 --report report": Runner(
        _CI, f"{_WHEEL} -m conformance models my_robot --drake 1.51.1 1.58.0 --report report -q"
    ),
    "python -m conformance models my_robot --drake 1.51.1 --save golden.json": Runner(
        _CI, f"{_WHEEL} -m conformance models my_robot --drake 1.51.1 --save golden.json -q"
    ),
    "python -m conformance models my_robot --drake 1.58.0 --check golden.json": Runner(
        _CI,
        f"{_WHEEL} -m conformance models my_robot --drake 1.58.0 --check golden.json -q",
        exit=1,
    ),
    # docs/models.md (CI writes the user's files: a folder at path/to/, a directives file)
    "python -m conformance models path/to/my_robot/": Runner(
        _CI, f"{_WHEEL} -m conformance models path/to/my_robot/ -q"
    ),
    # Exit 1: 1.55.0 makes no frame for Acrobot's identity joint origin, so the file differs.
    "python -m conformance models my_cell.dmd.yaml --backend drake==1.54.0 "
    "--backend drake==1.55.0": Runner(
        _CI,
        f"{_WHEEL} -m conformance models my_cell.dmd.yaml --backend drake==1.54.0 "
        "--backend drake==1.55.0",
        exit=1,
    ),
    "python -m conformance models scenarios/real_models/drake/examples "
    "--package drake=scenarios/real_models/drake "
    "--package drake_models=scenarios/real_models/drake_models --drake 1.30.0 1.51.1 1.58.0 "
    "--report docs/models/drake-examples": Runner(
        _CI,
        "python3 -m conformance models scenarios/real_models/drake/examples "
        "--package drake=scenarios/real_models/drake "
        "--package drake_models=scenarios/real_models/drake_models "
        "--drake 1.30.0 1.51.1 1.58.0 --report reports/models-examples -q",
    ),
    # docs/fuzzing.md
    "python -m conformance fuzz --backend conformance._testing.mutants:reverse_statement_order "
    "--out /tmp/findings --shrink-time 30": Runner(
        "tests/test_fuzz_cli.py",
        "test_a_divergence_exits_1_and_is_written_as_a_valid_scenario",
        exit=1,
        bounds=(("--shrink-time 30", "--shrink-time 10"),),
    ),
    "python -m conformance fuzz --backend drake==1.51.1 --against drake==1.58.0 "
    "--time-budget 180": Runner(
        _CI,
        "python3 -m conformance fuzz --backend drake==1.51.1 --against drake==1.58.0 "
        "--time-budget 1 --steps 10 -q",
        bounds=(("--time-budget 180", "--time-budget 1"), ("", "--steps 10")),
    ),
    "CONFORMANCE_FUZZ_SEEDS=0-63 CONFORMANCE_FUZZ_EXAMPLES=200 "
    "pytest -m fuzz -n auto tests/test_fuzz_shards.py": Runner(
        _CI,
        "CONFORMANCE_FUZZ_SEEDS=0-1 CONFORMANCE_FUZZ_EXAMPLES=5 "
        "python3 -m pytest -m fuzz -n auto tests/test_fuzz_shards.py -q",
        bounds=(
            ("CONFORMANCE_FUZZ_SEEDS=0-63", "CONFORMANCE_FUZZ_SEEDS=0-1"),
            ("CONFORMANCE_FUZZ_EXAMPLES=200", "CONFORMANCE_FUZZ_EXAMPLES=5"),
        ),
    ),
    # docs/releases.md
    "python -m conformance matrix --drake 1.30.0 1.58.0 --report out/": Runner(
        _CI,
        f"{_WHEEL} -m conformance matrix --drake 1.30.0 1.58.0 --case 'transient/*' "
        "--report wheel-matrix -q",
        bounds=(_TRANSIENT,),
    ),
    "python -m conformance matrix --drake 1.12..1.58 --jobs 2 --report out/": Runner(
        _CI,
        "python3 -m conformance matrix --drake 1.52..1.53 --jobs 2 --case 'transient/*' "
        "--report reports/matrix-range -q",
        bounds=(("--drake 1.12..1.58", "--drake 1.52..1.53"), _TRANSIENT),
    ),
    # CI also holds the answer: first release that differs by behaviour: 1.52.0.
    'python -m conformance bisect "*failing apply_transient with a bad frame*" --good 1.12.0 '
    "--bad 1.58.0 --by behaviour": Runner(
        _CI,
        'python3 -m conformance bisect "*failing apply_transient with a bad frame*" '
        "--good 1.51.1 --bad 1.53.0 --by behaviour",
        bounds=(("--good 1.12.0", "--good 1.51.1"), ("--bad 1.58.0", "--bad 1.53.0")),
    ),
    "python -m conformance run --backend reimpl==1.58.0 --backend drake==1.58.0": Runner(
        _CI,
        "python3 -m conformance run --backend reimpl==1.58.0 --backend drake==1.58.0 "
        "--case 'transient/*' -q",
        bounds=(_TRANSIENT,),
    ),
    "python -m conformance matrix --drake 1.30.0 1.58.0 --backend reimpl==1.30.0 "
    "--backend reimpl==1.58.0": Runner(
        _CI,
        "python3 -m conformance matrix --drake 1.30.0 1.58.0 --backend reimpl==1.30.0 "
        "--backend reimpl==1.58.0 --case 'transient/*' --report reports/matrix-reimpl -q",
        bounds=(_TRANSIENT,),
    ),
    # docs/user-guide.md
    "python -m conformance run --backend reimpl --backend drake==1.58.0": Runner(
        _CI,
        "python3 -m conformance run --backend reimpl --backend drake==1.58.0 "
        "--case 'transient/*' -q",
        bounds=(_TRANSIENT,),
    ),
    "python -m conformance fuzz --backend reimpl --against drake==1.58.0 --seed 1": Runner(
        _CI,
        "python3 -m conformance fuzz --backend reimpl --against drake==1.58.0 --seed 1 "
        "--max-examples 20 --steps 10 -q",
        bounds=(("", "--max-examples 20"), ("", "--steps 10")),
    ),
    "python -m pytest scenarios/ -n auto --junitxml=report.xml": Runner(
        _CI,
        "python3 -m pytest scenarios/statements scenarios/transient scenarios/queries -q "
        "-n auto --junitxml=reports/scenarios-junit.xml",
        bounds=(("scenarios/", "scenarios/statements scenarios/transient scenarios/queries"),),
    ),
    "python -m pytest scenarios/ --conformance-backend reimpl "
    "--conformance-backend mypkg.backend:Backend": Runner(
        "tests/test_pytest_plugin.py",
        "test_a_users_backend_module_runs_a_scenario_folder_beside_reimpl",
    ),
    "python -m pytest my/case.json": Runner(
        "tests/test_pytest_plugin.py",
        "test_a_scenario_file_named_on_the_command_line_is_collected_anywhere",
    ),
}

#: Options (and env variables) whose value names where output goes: a runner may write
#: elsewhere, but must write the same kinds.
_OUTPUT_OPTIONS = {"--report", "--out", "--json", "--junit", "--junitxml", "CONFORMANCE_FUZZ_DB"}
#: Options that change only how much is printed.
_QUIET = {"-q", "--quiet"}


@dataclass(frozen=True)
class _Parsed:
    """A command: its environment, program and arguments, output paths and -q aside."""

    env: tuple[str, ...]
    program: str
    words: tuple[str, ...]
    outputs: frozenset[str]

    def _replace_words(self, old: list[str], new: list[str], *, env: bool) -> _Parsed:
        if env:
            return replace(self, env=tuple(sorted(_without(self.env, old, new))))
        return replace(self, words=_without(self.words, old, new))


def _parse(command: str) -> _Parsed:
    """``python``, ``python3`` or a venv's python with ``-m X`` is program X."""
    words = shlex.split(command)
    env: list[str] = []
    while re.fullmatch(r"[A-Z_]+=\S*", words[0]):
        env.append(words.pop(0))
    if re.fullmatch(r"(\S*/)?python3?", words[0]):
        words = words[2:] if words[1] == "-m" else words[1:]
    program, args = words[0], words[1:]
    if program == "pip":
        program, args = "pip " + args[0], args[1:]
    kept: list[str] = []
    outputs = {name.split("=")[0] for name in env} & _OUTPUT_OPTIONS
    index = 0
    while index < len(args):
        word = args[index]
        option = word.split("=")[0]
        if option in _OUTPUT_OPTIONS:
            outputs.add(option)
            index += 1 if "=" in word else 2
            continue
        if word not in _QUIET:
            kept.append(word)
        index += 1
    env = [word for word in env if word.split("=")[0] not in _OUTPUT_OPTIONS]
    return _Parsed(tuple(sorted(env)), program, tuple(kept), frozenset(outputs))


def _without(words: tuple[str, ...], old: list[str], new: list[str]) -> tuple[str, ...]:
    """``words`` with the run ``old`` replaced by ``new``; an error if ``old`` is absent."""
    for start in range(len(words) - len(old) + 1):
        if list(words[start : start + len(old)]) == old:
            return (*words[:start], *new, *words[start + len(old) :])
    raise AssertionError(f"no {old} in {list(words)}")


def _bounded(
    shown: _Parsed, ran: _Parsed | None, bounds: tuple[tuple[str, str], ...]
) -> tuple[_Parsed, _Parsed | None, list[str]]:
    """``shown`` with each bound applied, and ``ran`` without the options a bound adds (which
    are returned too), after checking that each bound is one _NARROWS allows and narrows."""
    added: list[str] = []
    for shown_words, ran_words in bounds:
        old, new = shlex.split(shown_words), shlex.split(ran_words)
        name, ran_values = _bound_name(new)
        old_name, shown_values = _bound_name(old)
        assert name in _NARROWS, f"{name} is no option a bounded runner may narrow"
        assert old_name in (name, ""), f"the bound {shown_words!r} -> {ran_words!r} renames"
        assert _NARROWS[name](shown_values, ran_values), f"{ran_words!r} widens {shown_words!r}"
        in_env = name.isupper() and name != "PATH"
        if not old:
            added += new
            if ran is not None:
                ran = ran._replace_words(new, [], env=in_env)
        else:
            shown = shown._replace_words(old, new, env=in_env)
    return shown, ran, added


def _ci_line(source: str, where: str) -> str:
    """The logical line of .ci/run (continuations joined) that is ``where``, but for an
    ``exits N`` before it and a pipe or redirection after it."""
    wanted = " ".join(where.split())
    for raw in source.replace("\\\n", " ").splitlines():
        line = " ".join(raw.split())
        command = re.sub(r"^exits \d+ ", "", line)
        if re.split(r" (?:\||2?>) ", command)[0] == wanted:
            return line
    raise AssertionError(f"{_CI} no longer runs: {where}")


#: How a test asserts an exit status.
_EXIT_ASSERTS = {
    0: r"EXIT_OK|ExitCode\.OK|== 0\b",
    1: r"EXIT_FAILURE|ExitCode\.TESTS_FAILED|== 1\b",
}


def test_every_shown_command_has_a_runner_and_every_runner_a_shown_command() -> None:
    shown = _shown_commands()
    others = {command: pages for command, pages in shown.items() if not _checked(command)}
    assert set(others) == set(UNCHECKED), f"shown commands of no checked kind: {others}"
    checked = {command: pages for command, pages in shown.items() if _checked(command)}
    assert set(checked) == set(RUNNERS), (
        "shown without a runner: "
        f"{ {c: p for c, p in checked.items() if c not in RUNNERS} }; "
        f"runners for no shown command: {sorted(set(RUNNERS) - set(checked))}"
    )


def test_usage_synopses_are_skipped_and_nothing_else() -> None:
    """The synopses of fuzz and run are not commands; the command under one still is."""
    shown = _shown_commands()
    assert not [command for command in shown if "[" in command.split()[0]]
    assert not [command for command in shown if "SEC" in command.split()]
    assert "python -m conformance --version" in shown


@pytest.mark.parametrize("command", sorted(RUNNERS))
def test_a_shown_command_is_run_by_ci_or_a_test_and_exits_as_the_docs_say(command: str) -> None:
    runner = RUNNERS[command]
    source = (ROOT / runner.path).read_text(encoding="utf-8")
    shown = _parse(command)
    if runner.path == _CI:
        line = _ci_line(source, runner.where)
        shown, ran, _ = _bounded(shown, _parse(runner.where), runner.bounds)
        assert ran is not None
        assert (ran.env, ran.program, ran.words) == (shown.env, shown.program, shown.words), (
            f"{runner.path} runs {ran}, the docs show (bounds applied) {shown}"
        )
        assert shown.outputs <= ran.outputs, f"{runner.path} writes no {sorted(shown.outputs)}"
        if runner.exit == 0:
            # set -e stops CI on any other status, unless a condition or list holds it.
            assert not re.match(r"(if|elif|while|until|!|exits) ", line), line
            assert not re.search(r"\|\||&&", line), line
        else:
            assert line.startswith(f"exits {runner.exit} "), f"not run as exits {runner.exit}"
    else:
        # The test with its decorators (a parametrize may give part of a word), to the next
        # line at the margin that does not close its signature.
        match = re.search(
            rf"(?:^@.*\n)*^def {runner.where}\(.*?(?=^[^\s)])", source + "\nend", re.S | re.M
        )
        assert match, f"{runner.path} has no test {runner.where}"
        body = match.group(0)
        shown, _, added = _bounded(shown, None, runner.bounds)
        # The program aside: a test may call main() or run the module in a subprocess.
        words = [*shown.env, *shown.words, *added]
        parts = [part for word in words for part in re.split(r"[:=]", word) if part]
        absent = [part for part in parts if part.lower() not in body.lower()]
        assert not absent, f"{runner.where} does not pass {absent}"
        assert re.search(_EXIT_ASSERTS[runner.exit], body), f"asserts no exit {runner.exit}"


def test_a_bound_must_narrow_an_option_the_rules_name() -> None:
    matrix = _parse("python -m conformance matrix --drake 1.12..1.58 --jobs 2")
    narrowed, _, _ = _bounded(matrix, None, (("--drake 1.12..1.58", "--drake 1.57..1.58"),))
    assert narrowed.words == ("matrix", "--drake", "1.57..1.58", "--jobs", "2")
    with pytest.raises(AssertionError, match="widens"):
        _bounded(matrix, None, (("--drake 1.12..1.58", "--drake 1.0..1.58"),))
    with pytest.raises(AssertionError, match="no option a bounded runner may narrow"):
        _bounded(matrix, None, (("--jobs 2", "--jobs 1"),))
    with pytest.raises(AssertionError, match="renames"):
        _bounded(matrix, None, (("--jobs 2", "--case x"),))
    shards = _parse("CONFORMANCE_FUZZ_SEEDS=0-63 pytest -m fuzz")
    with pytest.raises(AssertionError, match="widens"):
        _bounded(shards, None, (("CONFORMANCE_FUZZ_SEEDS=0-63", "CONFORMANCE_FUZZ_SEEDS=60-70"),))
    with pytest.raises(AssertionError, match="widens"):
        _bounded(shards, None, (("", "CONFORMANCE_FUZZ_EXAMPLES=80"),))  # the default is 50
    with pytest.raises(AssertionError, match="widens"):
        _bounded(_parse("pytest scenarios/"), None, (("scenarios/", "tests/"),))
