"""``python -m conformance new-backend DIR``: the backend skeleton, written where you want it.

It writes ``DIR/my_backend.py``, the skeleton of ``examples/my_backend.py``
(shipped in the wheel as ``conformance/_examples``), and prints the command
that runs it against pydrake. As written it forwards to reimpl, so it passes
the corpus; the skeleton's docstrings say what to replace.

Exit codes: 0 written; 2 the file exists already (nothing is overwritten),
or DIR cannot be written.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TextIO

from conformance._corpus_root import examples_root
from conformance.cli.exit_codes import EXIT_OK, EXIT_USAGE

__all__ = ["SKELETON", "add_new_backend_parser", "backend_spec", "new_backend_command"]

#: The skeleton's file name, in the examples and where it is written.
SKELETON = "my_backend.py"


def add_new_backend_parser(commands: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    parser = commands.add_parser(
        "new-backend",
        help=f"write the backend skeleton to DIR/{SKELETON} (it passes the corpus as written: "
        "replace its calls with your implementation's)",
    )
    parser.add_argument("dir", type=Path, metavar="DIR", help="the folder to write it in")


def backend_spec(folder: Path) -> tuple[str, Path]:
    """(``--backend`` spec, the folder to run it from) for the skeleton in ``folder``: a
    dotted module path from the folder's parent when its name is an identifier."""
    folder = folder.resolve()
    if folder.name.isidentifier():
        return f"{folder.name}.{Path(SKELETON).stem}:MyBackend", folder.parent
    return f"{Path(SKELETON).stem}:MyBackend", folder


def new_backend_command(args: argparse.Namespace, out: TextIO, err: TextIO) -> int:
    """Runs ``new-backend``; returns the exit code."""
    target = args.dir / SKELETON
    if target.exists():
        err.write(f"error: {target} exists already (nothing was written)\n")
        return EXIT_USAGE
    try:
        args.dir.mkdir(parents=True, exist_ok=True)
        target.write_text((examples_root() / SKELETON).read_text(encoding="utf-8"), "utf-8")
    except OSError as exc:
        err.write(f"error: {args.dir}: {exc.strerror or exc}\n")
        return EXIT_USAGE
    spec, where = backend_spec(args.dir)
    out.write(
        f"wrote {target}\n"
        f"run it against Drake, from {where}:\n"
        f"    python -m conformance run --backend {spec} --backend pydrake\n"
    )
    return EXIT_OK
