"""Vendors the model files of a Drake checkout (and what they reference) into ``drake/``.

Usage::

    python scenarios/real_models/vendor.py /path/to/drake-checkout [--commit SHA]

Copies, keeping Drake's paths:

* every URDF, SDFormat and model-directives file (``*.urdf``, ``*.sdf``, ``*.dmd.yaml``)
  outside Bazel's output folders;
* the data files beside each of them (one folder deep), and every data file under
  ``multibody/parsing/test/`` (the parser tests' packages, meshes and includes);
* Drake's root ``package.xml`` (the package ``drake``) and ``LICENSE.TXT``.

A data file is anything but source code and build files (see ``_CODE``). The copy is
deterministic: run it again on the same commit and ``git diff`` shows nothing.
"""

from __future__ import annotations

import argparse
import shutil
import sys
from pathlib import Path

__all__ = ["data_files", "model_files", "vendor"]

MODEL_SUFFIXES = (".urdf", ".sdf", ".dmd.yaml")
#: Suffixes that are code or build files, never model data.
_CODE = frozenset(
    {".cc", ".h", ".py", ".bazel", ".bzl", ".md", ".ipynb", ".sh", ".cmake", ".in", ".pyi"}
)
_SKIP_DIRS = frozenset({".git", "bazel-bin", "bazel-out", "bazel-testlogs", "build"})
#: Whole subtrees whose data files are all vendored (the parser tests' packages).
_WHOLE_TREES = ("multibody/parsing/test",)
_ROOT_FILES = ("package.xml", "LICENSE.TXT")
HERE = Path(__file__).resolve().parent


def _walk(root: Path) -> list[Path]:
    found = []
    for path in sorted(root.rglob("*")):
        relative = path.relative_to(root)
        if path.is_file() and not _SKIP_DIRS.intersection(relative.parts):
            found.append(relative)
    return found


def model_files(root: Path) -> list[Path]:
    """The model files of the checkout, relative to it, sorted."""
    return [p for p in _walk(root) if p.name.endswith(MODEL_SUFFIXES)]


def _is_data(path: Path) -> bool:
    return path.suffix not in _CODE and path.name != "BUILD"


def data_files(root: Path) -> list[Path]:
    """Every file to vendor, relative to the checkout, sorted."""
    every = _walk(root)
    models = {p for p in every if p.name.endswith(MODEL_SUFFIXES)}
    folders = {p.parent for p in models}
    chosen = set(models) | {Path(name) for name in _ROOT_FILES}
    for path in every:
        in_tree = any(path.is_relative_to(tree) for tree in _WHOLE_TREES)
        if _is_data(path) and (path.parent in folders or in_tree):
            chosen.add(path)
    return sorted(chosen)


def vendor(root: Path, target: Path, commit: str | None) -> int:
    if target.exists():
        shutil.rmtree(target)
    files = data_files(root)
    for relative in files:
        destination = target / relative
        destination.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(root / relative, destination)
    if commit:
        (target / "COMMIT").write_text(f"{commit}\n", encoding="utf-8")
    return len(files)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("checkout", type=Path, help="a Drake checkout (RobotLocomotion/drake)")
    parser.add_argument("--commit", help="the checkout's commit, recorded in drake/COMMIT")
    parser.add_argument("--target", type=Path, default=HERE / "drake")
    args = parser.parse_args(argv)
    if not (args.checkout / "multibody" / "parsing").is_dir():
        print(f"error: {args.checkout} is not a Drake checkout", file=sys.stderr)
        return 2
    count = vendor(args.checkout.resolve(), args.target, args.commit)
    print(f"vendored {count} files into {args.target}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
