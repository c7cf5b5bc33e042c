"""Measures how far reimpl's numbers lie from pydrake's in examples/mesh_robot_queries.py.

The script (Drake's Jaco arm, seven ``.obj`` collision meshes, beside a box and a
cylinder, five configurations) runs twice in fresh interpreters, its numbers printed to
17 significant digits: as written (pydrake) and with its imports switched to reimpl (the
switch tests/dropin.py makes). The lines must match but for their numbers; the report
holds the largest ``|pydrake - reimpl|`` per kind of line (depth, distance, point
distance) and shape pair, and the count of lines.

Usage: python3 benchmarks/measure_mesh_script.py [--json FILE]

The committed report is ``docs/reports/mesh_script.json``; docs/queries.md quotes it
(``docs/facts.py``: ``mesh_script_differences``).
"""

from __future__ import annotations

import argparse
import importlib.metadata
import json
import os
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = ROOT / "examples" / "mesh_robot_queries.py"
_NUMBER = re.compile(r"\((\S+)\)(?: to the wrist)?: (depth|distance|point distance) (\S+)$")


def _as_reimpl(script: str) -> str:
    return "".join(
        line.replace("pydrake.", "reimpl.", 1)
        if line.startswith(("from pydrake.", "import pydrake."))
        else line
        for line in script.splitlines(keepends=True)
    )


def _run(script: str) -> list[str]:
    path = os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH")) if p)
    done = subprocess.run(
        [sys.executable, "-c", script],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env=dict(os.environ, PYTHONPATH=path),
        check=True,
    )
    return done.stdout.splitlines()


def measure() -> dict[str, Any]:
    precise = SCRIPT.read_text(encoding="utf-8").replace(":.6f}", ":.17g}")
    theirs, mine = _run(precise), _run(_as_reimpl(precise))
    if len(theirs) != len(mine):
        raise SystemExit(f"{len(theirs)} lines from pydrake, {len(mine)} from reimpl")
    largest: dict[str, float] = {}
    for want, got in zip(theirs, mine, strict=True):
        number_want, number_got = _NUMBER.search(want), _NUMBER.search(got)
        if number_want is None or number_got is None:
            if want != got:
                raise SystemExit(f"lines differ: {want!r} / {got!r}")
            continue
        if want[: number_want.start(3)] != got[: number_got.start(3)]:
            raise SystemExit(f"lines differ: {want!r} / {got!r}")
        key = f"{number_want[2]} {number_want[1]}"
        difference = abs(float(number_want[3]) - float(number_got[3]))
        largest[key] = max(largest.get(key, 0.0), difference)
    return {
        "command": "python3 benchmarks/measure_mesh_script.py",
        "pydrake": importlib.metadata.version("drake"),
        "lines": len(theirs),
        "largest": dict(sorted(largest.items(), key=lambda item: -item[1])),
    }


def main(argv: list[str]) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", type=Path)
    args = parser.parse_args(argv)
    text = json.dumps(measure(), indent=1) + "\n"
    if args.json is not None:
        args.json.write_text(text, encoding="utf-8")
    print(text)


if __name__ == "__main__":
    main(sys.argv[1:])
