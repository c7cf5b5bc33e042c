"""``python -m conformance models``: your own model files, parsed by every backend and compared.

Each PATH is a model file (``.urdf``, ``.sdf``, ``.dmd.yaml``, a MuJoCo
``.xml``, an ``.obj`` mesh) or a folder searched for them (``.obj`` files only
with ``--obj``); a folder's packages (every ``package.xml`` below it) are
added to each parse's package map, and a file's are those of the nearest
folder above it that holds a ``package.xml`` (else its own folder). Every
file is a case (``corpus.model_files``): parse, Finalize, then what the plant
holds by scoped name (models, bodies, frames, joints, geometries with shape
and roles), and the candidate pairs after each step; files that may declare
collision filter groups also compare the parser's group report.

A file that every backend rejects with the same message agrees: the answer
is the error. A backend that breaks on one file (raises from an observation,
times out) is reported there, and the other files still run. Exit codes are
``run``'s: 0 every file agrees, 1 a backend disagrees with the reference, 2
bad input or a backend that broke.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TextIO

from conformance.backends.loader import BackendLoadError
from conformance.cli.exit_codes import EXIT_FAILURE, EXIT_OK, EXIT_USAGE
from conformance.cli.options import add_backend_options, refuse
from conformance.cli.run import load_backends, run_cases, write_outputs
from conformance.corpus.loader import PACKAGE_MANIFEST, Case, ScenarioError
from conformance.corpus.model_files import find_model_files, is_model_file, model_scenario
from conformance.run.outputs import unwritable
from conformance.run.report import RunReport
from conformance.run.runner import choose_reference

__all__ = ["add_models_parser", "model_file_cases", "models_command"]


def add_models_parser(commands: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    models = commands.add_parser(
        "models",
        help="parse your model files on every backend and compare what each gives",
        description=__doc__.split("\n\n")[1] if __doc__ else None,
    )
    models.add_argument(
        "paths", nargs="+", type=Path, metavar="PATH", help="model files or folders of them"
    )
    models.add_argument(
        "--backend",
        action="append",
        dest="backends",
        metavar="SPEC",
        help="reimpl, pydrake, drake==X.Y.Z or package.module:attribute "
        "(repeatable; default: reimpl and pydrake)",
    )
    models.add_argument(
        "--reference",
        metavar="NAME",
        help="the backend others are judged against (default: pydrake if given, else the first)",
    )
    models.add_argument(
        "--obj",
        action="store_true",
        help="also parse the .obj files found below a folder (as one-body mesh models)",
    )
    models.add_argument("--json", type=Path, metavar="FILE", help="write a JSON report")
    models.add_argument("--junit", type=Path, metavar="FILE", help="write a JUnit XML report")
    add_backend_options(
        models,
        strict="report known divergences as failures, not xfail",
        timeout="is a timeout",
        quiet="no per-file progress lines",
    )


def _package_root(file: Path) -> Path:
    """The nearest folder above ``file`` holding a package manifest, else its own folder."""
    for folder in file.parents:
        if (folder / PACKAGE_MANIFEST).is_file():
            return folder
    return file.parent


#: What a model file is, for messages.
_KINDS = ".urdf, .sdf, .dmd.yaml, MuJoCo .xml, .obj"


def model_file_cases(paths: list[Path], *, obj: bool = False) -> list[Case]:
    """The cases of the model files at ``paths`` (files, or folders searched for them;
    the ``.obj`` files in a folder only with ``obj``)."""
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
        scenario = model_scenario(folder, files, description=f"the model files below {folder}")
        cases += scenario.cases
    return cases


def models_command(args: argparse.Namespace, out: TextIO, err: TextIO) -> int:
    """Runs ``models``; returns the exit code (see ``conformance.cli.exit_codes``)."""
    problems = [
        f"--{option} {path}: {problem}"
        for option, path in (("json", args.json), ("junit", args.junit))
        if path is not None and (problem := unwritable(path)) is not None
    ]
    if refuse(problems, err):
        return EXIT_USAGE
    try:
        backends = load_backends(
            args.backends, python=args.python, step_timeout=args.step_timeout or None
        )
        reference = choose_reference(backends, args.reference).name
        cases = model_file_cases(args.paths, obj=args.obj)
    except (BackendLoadError, ScenarioError, ValueError) as exc:
        err.write(f"error: {exc}\n")
        return EXIT_USAGE
    report = RunReport(
        backends, specs=list(args.backends or ("reimpl", "pydrake")), reference=reference
    )
    code = run_cases(args, cases, report, err, bad_models_are_input_errors=False, keep_going=True)
    write_outputs(args, report, out, err)
    if code == EXIT_OK and report.failed:
        code = EXIT_FAILURE
    return code
