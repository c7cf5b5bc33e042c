"""Measures where a pydrake release reports each DRAKE_DEMAND reimpl reproduces.

A failed DRAKE_DEMAND (or DRAKE_THROW_UNLESS) reaches Python as SystemExit
``Failure at <file>:<line> in <function>(): condition '<condition>' failed.``;
the file and line are those of the release's own sources, so they move from
release to release (and the function or condition, rarely). Each demand of
tools/demand_triggers.py is failed once through pydrake's public API, and the
four parts are read from the message.

Usage, with the pydrake to measure installed in the running Python (run it from
a directory outside the repository, so that nothing of the project is imported)::

    python tools/measure_demand_lines.py            # prints one release's JSON

and, from the repository, to measure several environments into reimpl's table
(a release measured again replaces its row)::

    python3 tools/measure_demand_lines.py --collect reimpl/common/demand_lines.json \\
        ~/.cache/drake-filter-conformance/drake-*/bin/python

One release's JSON is ``{"release": "X.Y.Z", "demands": {id: [file, line,
function, condition]}, "not_demands": {id: "<Exception>: <first line>"}}``: a
demand that the release does not reach (it raises something else, lacks the
API, or the call returns) is listed under ``not_demands`` with what happened.
"""

from __future__ import annotations

import argparse
import json
import re
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

from demand_triggers import TRIGGERS  # N.B. tools/ is this script's sys.path[0].

#: The message, and what some demands add after it (a shape's ``radius = -1.0.``).
_FAILURE = re.compile(
    r"^Failure at (.+):(\d+) in (\w+)\(\): condition '(.*)' failed\.(?: [^']*)?$", re.S
)


def measure() -> dict[str, Any]:
    """This Python's pydrake: each demand's [file, line, function, condition], or what
    happened instead."""
    from importlib.metadata import version  # noqa: PLC0415

    import pydrake  # noqa: PLC0415

    demands: dict[str, list[Any]] = {}
    others: dict[str, str] = {}
    for demand, trigger in TRIGGERS.items():
        try:
            trigger(pydrake)
        except SystemExit as exit_:
            found = _FAILURE.match(str(exit_))
            if found is not None:
                path, line, function, condition = found.groups()
                demands[demand] = [path, int(line), function, condition]
                continue
            others[demand] = f"SystemExit: {str(exit_).splitlines()[0]}"
        except Exception as error:  # N.B. Recorded: the release differs here.
            others[demand] = f"{type(error).__name__}: {(str(error).splitlines() or [''])[0]}"
        else:
            others[demand] = "returned"
    return {"release": version("drake"), "demands": demands, "not_demands": others}


def _release_key(release: str) -> tuple[int, ...]:
    return tuple(int(part) for part in release.split("."))


def collect(table: Path, pythons: list[str]) -> None:
    """Runs ``measure`` under each Python and merges the releases into ``table``."""
    data = json.loads(table.read_text("utf-8")) if table.exists() else {}
    releases: dict[str, Any] = dict(data.get("releases", {}))
    with tempfile.TemporaryDirectory() as cwd:
        for python in pythons:
            run = subprocess.run(
                [python, str(Path(__file__).resolve())],
                capture_output=True,
                text=True,
                check=False,
                cwd=cwd,
            )
            if run.returncode != 0:  # e.g. an environment still being built
                print(f"{python}: skipped ({run.stderr.splitlines()[-1:]})", file=sys.stderr)
                continue
            measured = json.loads(run.stdout)
            releases[measured["release"]] = {
                "demands": measured["demands"],
                "not_demands": measured["not_demands"],
            }
            print(f"{measured['release']}: {len(measured['demands'])} demands", file=sys.stderr)
    data["releases"] = {r: releases[r] for r in sorted(releases, key=_release_key)}
    table.write_text(json.dumps(data, indent=2) + "\n", "utf-8")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--collect", type=Path, metavar="TABLE", help="merge into TABLE")
    parser.add_argument("pythons", nargs="*", help="with --collect: the Pythons to measure")
    args = parser.parse_args()
    if args.collect is None:
        print(json.dumps(measure(), indent=2))
    else:
        collect(args.collect, args.pythons)


if __name__ == "__main__":
    main()
