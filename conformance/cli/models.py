"""``python -m conformance models``: your own model files, on implementations or Drake releases.

Each PATH is a model file (``.urdf``, ``.sdf``, ``.dmd.yaml``, a MuJoCo
``.xml``, an ``.obj`` mesh) or a folder searched for them (``.obj`` files only
with ``--obj``); a folder's packages (every ``package.xml`` below it) are
added to each parse's package map, as ``PackageMap.PopulateFromFolder`` finds
them, and a file's are those of the nearest folder above it that holds a
``package.xml`` (else its own folder); ``--package NAME=PATH`` adds more.
Every file is a case (``corpus.model_files``): parse, Finalize, then what the
plant holds by scoped name (models, bodies, frames, joints, geometries with
shape and roles), the candidate pairs, and for files that may declare
collision filter groups the parser's group report.

Columns are implementations (``--backend``, default reimpl and pydrake), each
compared with the reference, or Drake releases (``--drake``, each in its own
environment, ``--jobs`` at a time), each compared with the one before. The
output lists, per file, every difference by scoped name; ``--report DIR``
writes report.json, report.md, report.html and heatmap.png. ``--save FILE`` writes one
column's answers as a golden file; ``--check FILE`` compares each column with
it.

Exit codes, as ``matrix``: 0 nothing failing; 1 a file broke an
implementation (error, crash, timeout), or, with ``--backend``, an
implementation differs from the reference, or, with ``--check``, a column
differs from the golden file; 2 bad input, or a column that could not run.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Sequence
from pathlib import Path
from typing import TextIO

from conformance._backends.loader import BackendLoadError
from conformance._backends.releases import ReleaseSpecError, expand
from conformance._corpus.loader import PACKAGE_MANIFEST, Case, ScenarioError
from conformance._corpus.model_files import find_model_files, is_model_file, model_scenario
from conformance._run.matrix import Matrix, ReleaseRun, run_backends, run_matrix
from conformance._run.models_report import (
    Comparison,
    GoldenError,
    change_lines,
    comparisons,
    golden_changes,
    load_golden,
    save_golden,
    write_models_report,
)
from conformance._run.outputs import unwritable
from conformance._run.runner import reference_name
from conformance.cli.exit_codes import EXIT_FAILURE, EXIT_OK, EXIT_USAGE
from conformance.cli.options import add_backend_options, refuse
from conformance.cli.run import load_backends

__all__ = ["add_models_parser", "model_file_cases", "models_command"]


def _package(text: str) -> tuple[str, Path]:
    """``NAME=PATH`` (an existing folder)."""
    name, equals, path = text.partition("=")
    if not equals or not name or not path:
        raise argparse.ArgumentTypeError(f"expected NAME=PATH, got {text!r}")
    if not Path(path).is_dir():
        raise argparse.ArgumentTypeError(f"{path!r} is not a folder")
    return name, Path(path).resolve()


def add_models_parser(commands: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    models = commands.add_parser(
        "models",
        help="parse your model files on implementations or Drake releases and compare them",
        description=__doc__.split("\n\n")[1] if __doc__ else None,
    )
    models.add_argument(
        "paths", nargs="+", type=Path, metavar="PATH", help="model files or folders of them"
    )
    columns = models.add_mutually_exclusive_group()
    columns.add_argument(
        "--backend",
        action="append",
        dest="backends",
        metavar="SPEC",
        help="an implementation: reimpl, pydrake, drake==X.Y.Z, exec:'CMD ARGS' or "
        "package.module:attribute (repeatable; default: reimpl and pydrake)",
    )
    columns.add_argument(
        "--drake",
        nargs="+",
        metavar="SPEC",
        help="Drake releases, each in its own environment: 1.30.0, or a range 1.40..1.58",
    )
    models.add_argument(
        "--reference",
        metavar="NAME",
        help="with --backend: the one others are compared with (default: pydrake if given, "
        "else the first)",
    )
    models.add_argument(
        "--package",
        action="append",
        default=[],
        type=_package,
        metavar="NAME=PATH",
        help="a package besides those found below the folders (repeatable)",
    )
    models.add_argument(
        "--obj",
        action="store_true",
        help="also parse the .obj files found below a folder (as one-body mesh models)",
    )
    models.add_argument(
        "--report",
        type=Path,
        metavar="DIR",
        help="write report.json, report.md, report.html, heatmap.png",
    )
    golden = models.add_mutually_exclusive_group()
    golden.add_argument(
        "--save", type=Path, metavar="FILE", help="write the (one) column's answers to FILE"
    )
    golden.add_argument(
        "--check",
        type=Path,
        metavar="FILE",
        help="compare each column with the answers saved in FILE; exit 1 on a change",
    )
    models.add_argument(
        "--jobs", type=int, default=2, metavar="J", help="with --drake: releases run at a time"
    )
    add_backend_options(
        models,
        strict="report known divergences as failures (unused: model files have none)",
        timeout="is a timeout",
        quiet="no progress lines",
    )


def _package_root(file: Path) -> Path:
    """The nearest folder above ``file`` holding a package manifest, else its own folder."""
    for folder in file.parents:
        if (folder / PACKAGE_MANIFEST).is_file():
            return folder
    return file.parent


#: What a model file is, for messages.
_KINDS = ".urdf, .sdf, .dmd.yaml, MuJoCo .xml, .obj"


def model_file_cases(
    paths: Sequence[Path], *, obj: bool = False, packages: dict[str, str] | None = None
) -> list[Case]:
    """The cases of the model files at ``paths`` (files, or folders searched for them;
    the ``.obj`` files in a folder only with ``obj``); ``packages`` are added to each
    parse."""
    cases: list[Case] = []
    for given in paths:
        path = given.resolve()
        if path.is_dir():
            folder, files = path, find_model_files(path, obj=obj)
            if not files:
                raise ScenarioError(str(given), f"no model files ({_KINDS}) below this folder")
        elif path.is_file() and is_model_file(path, obj=True):
            folder = _package_root(path)
            files = [path.relative_to(folder)]
        elif path.exists():
            raise ScenarioError(str(given), f"not a model file ({_KINDS})")
        else:
            raise ScenarioError(str(given), "no such file or folder")
        scenario = model_scenario(
            folder, files, description=f"the model files below {folder}", packages=packages
        )
        cases += scenario.cases
    return cases


def _problems(args: argparse.Namespace) -> list[str]:
    problems = []
    if args.jobs < 1:
        problems.append(f"--jobs must be at least 1, got {args.jobs}")
    if args.report is not None and (problem := unwritable(args.report / "report.json")):
        problems.append(f"--report {args.report}: {problem}")
    if args.save is not None and (problem := unwritable(args.save)):
        problems.append(f"--save {args.save}: {problem}")
    if args.check is not None and not args.check.is_file():
        problems.append(f"--check {args.check}: no such file")
    if args.reference is not None and args.drake:
        problems.append("--reference is for --backend: releases are compared in order")
    return problems


class _Progress:
    """A line per column when it ends (and every ``every`` s while a long one runs)."""

    def __init__(self, err: TextIO, *, quiet: bool, every: float = 10.0) -> None:
        self.err, self.quiet, self.every = err, quiet, every
        self.start = self.last = time.perf_counter()

    def write(self, line: str) -> None:
        if not self.quiet:
            self.err.write(line + "\n")
            self.err.flush()

    def case(self, column: str, done: int, total: int) -> None:
        now = time.perf_counter()
        if now - self.last >= self.every:
            self.last = now
            self.write(f"  {column}: {done}/{total} cases")

    def column(self, run: ReleaseRun) -> None:
        if run.error:
            self.write(f"  {run.version}: could not run: {run.error}")
        else:
            self.write(f"  {run.version}: {len(run.cells)} cases [{run.seconds:.1f} s]")


def _run(args: argparse.Namespace, cases: list[Case], progress: _Progress) -> tuple[Matrix, str]:
    """The run's matrix, and its title."""
    timeout = args.step_timeout or None
    if args.drake:
        versions = expand(args.drake)
        progress.write(f"models: {len(cases)} cases on drake {', '.join(versions)}")
        matrix = run_matrix(
            versions,
            cases,
            jobs=args.jobs,
            python=args.python,
            step_timeout=timeout,
            on_case=progress.case,
            on_release=progress.column,
            log=progress.write,
        )
        return matrix, "Model files across Drake releases"
    backends = load_backends(args.backends, python=args.python, step_timeout=timeout)
    progress.write(f"models: {len(cases)} cases on {', '.join(b.name for b in backends)}")
    matrix = run_backends(backends, cases, step_timeout=timeout, on_case=progress.case)
    for name in matrix.versions:
        progress.column(matrix.runs[name])
    return matrix, "Model files on implementations"


def _reference(args: argparse.Namespace, matrix: Matrix) -> str | None:
    return None if args.drake else reference_name(matrix.versions, args.reference)


def _print(out: TextIO, found: Sequence[Comparison], files: int, *, releases: bool) -> None:
    """Each comparison's headline, then each changed file and its changes in full."""
    for comparison in found:
        if releases or comparison.older.startswith("golden"):
            head = f"{comparison.older} → {comparison.newer}"
            verdict = ("changed", "no change in")
        else:
            head = f"{comparison.newer} against {comparison.older}"
            verdict = ("differ", "agrees on all")
        if not comparison.changes:
            out.write(f"{head}: {verdict[1]} {files} file(s)\n")
            continue
        out.write(f"{head}: {len(comparison.files)} of {files} file(s) {verdict[0]}\n")
        out.writelines(line + "\n" for line in change_lines(comparison))


def models_command(args: argparse.Namespace, out: TextIO, err: TextIO) -> int:
    """Runs ``models``; returns the exit code (see the module doc)."""
    if refuse(_problems(args), err):
        return EXIT_USAGE
    progress = _Progress(err, quiet=args.quiet)
    packages = {name: str(path) for name, path in args.package}
    try:
        golden = load_golden(args.check) if args.check is not None else None
        cases = model_file_cases(args.paths, obj=args.obj, packages=packages)
        matrix, title = _run(args, cases, progress)
        reference = _reference(args, matrix)
    except (BackendLoadError, ReleaseSpecError, ScenarioError, GoldenError, ValueError) as exc:
        err.write(f"error: {exc}\n")
        return EXIT_USAGE
    except KeyboardInterrupt:
        err.write("interrupted: no report written\n")
        return EXIT_USAGE
    files = len({case.description.removesuffix(" (filter groups)") for case in cases})
    found = comparisons(matrix, cases, reference=reference)
    checked = [
        golden_changes(golden, matrix, cases, column)
        for column in matrix.versions
        if golden is not None and matrix.runs[column].error is None
    ]
    _print(out, [*found, *checked], files, releases=bool(args.drake))
    if args.report is not None:
        for path in write_models_report(
            matrix, cases, [*found, *checked], args.report, title=title, reference=reference
        ):
            out.write(f"wrote {path}\n")
    code = _exit_code(args, matrix, found, checked, err)
    if args.save is not None:
        columns = [v for v in matrix.versions if matrix.runs[v].error is None]
        if len(columns) != 1:
            err.write(f"error: --save needs exactly one column that ran, got {columns}\n")
            return EXIT_USAGE
        save_golden(args.save, matrix, cases, columns[0])
        out.write(f"wrote {args.save} ({columns[0]}'s answers)\n")
    return code


def _exit_code(
    args: argparse.Namespace,
    matrix: Matrix,
    found: Sequence[Comparison],
    checked: Sequence[Comparison],
    err: TextIO,
) -> int:
    for version in matrix.broken_releases:
        err.write(f"error: {matrix.runs[version].error}\n")
    if matrix.broken_releases:
        return EXIT_USAGE
    broke = matrix.failing
    if broke:
        err.write(f"{len(broke)} case(s) broke an implementation; see the report\n")
    differs = not args.drake and any(c.changes for c in found)
    changed = any(c.changes for c in checked)
    return EXIT_FAILURE if broke or differs or changed else EXIT_OK
