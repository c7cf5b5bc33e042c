"""Vendors the model files of a Drake checkout (and what they reference) into ``drake/``.

Usage::

    python scenarios/real_models/vendor.py /path/to/drake-checkout [--commit SHA] \
        [--models /path/to/RobotLocomotion-models --models-commit SHA]

Copies, keeping Drake's paths:

* every URDF, SDFormat and model-directives file (``*.urdf``, ``*.sdf``, ``*.dmd.yaml``)
  outside Bazel's output folders;
* the data files beside each of them (one folder deep), and every data file under
  ``multibody/parsing/test/`` (the parser tests' packages, meshes and includes);
* Drake's root ``package.xml`` (the package ``drake``) and ``LICENSE.TXT``.

A data file is anything but source code and build files (see ``_CODE``).

With ``--models``, a checkout of RobotLocomotion/models (Drake's ``drake_models``
package, at the commit the Drake release pins) is vendored into ``drake_models/``:
its ``package.xml``, every model file, every licence file, every file a model
file (of it, or of Drake's checkout) names by URI (``package://drake_models/...``
or a relative path; not what a named glTF file names in turn: Drake reads a mesh
file's contents at parse time only for collision geometry, whose meshes here are
``.obj`` and ``.vtk``).

The copy is deterministic: run it again on the same commits and ``git diff``
shows nothing.
"""

from __future__ import annotations

import argparse
import json
import re
import shutil
import sys
from pathlib import Path

__all__ = ["data_files", "model_files", "models_files", "vendor"]

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


#: A URI in a model file: ``package://drake_models/x`` or a file name in an attribute or
#: element (``filename="x"``, ``<uri>x</uri>``).
_URI = re.compile(r'(?:filename="|<uri>|file: *"?)([^"<\s]+)')
_PACKAGE = "package://drake_models/"
_LICENCE = re.compile(r"^(LICEN[CS]E|COPYING)", re.IGNORECASE)


def models_files(root: Path, drake: Path | None = None) -> list[Path]:
    """What to vendor of RobotLocomotion/models (see the module doc), relative, sorted; with
    ``drake`` (a checkout), the files its own model files name there too."""
    every = _walk(root)
    chosen = {Path("package.xml")} | {p for p in every if _LICENCE.match(p.name)}
    for model in model_files(drake) if drake is not None else []:
        text = (drake / model).read_text(encoding="utf-8", errors="replace")
        for named in _URI.findall(text):
            if named.startswith(_PACKAGE) and (root / named.removeprefix(_PACKAGE)).is_file():
                chosen.add(Path(named.removeprefix(_PACKAGE)))
    for model in (p for p in every if p.name.endswith(MODEL_SUFFIXES)):
        chosen.add(model)
        text = (root / model).read_text(encoding="utf-8", errors="replace")
        for named in _URI.findall(text):
            if named.startswith(_PACKAGE):
                candidate = Path(named.removeprefix(_PACKAGE))
            elif "://" not in named:
                candidate = Path(os_normpath(model.parent / named))
            else:
                continue
            if (root / candidate).is_file():
                chosen.add(candidate)
    chosen |= {buffer for gltf in _collision_gltf(root, every) for buffer in _buffers(root, gltf)}
    return sorted(chosen)


_COLLISION = re.compile(r"<collision\b.*?</collision>", re.DOTALL)


def _collision_gltf(root: Path, every: list[Path]) -> set[Path]:
    """The glTF files that a model file names inside a ``<collision>`` element."""
    found = set()
    for model in (p for p in every if p.name.endswith((".urdf", ".sdf"))):
        text = (root / model).read_text(encoding="utf-8", errors="replace")
        for block in _COLLISION.findall(text):
            for named in _URI.findall(block):
                if named.startswith(_PACKAGE) and named.endswith(".gltf"):
                    found.add(Path(named.removeprefix(_PACKAGE)))
                elif named.endswith(".gltf") and "://" not in named:
                    found.add(Path(os_normpath(model.parent / named)))
    return found


def _buffers(root: Path, gltf: Path) -> list[Path]:
    """The binary buffers a glTF file names (not its images: a mesh's shape is in its buffers)."""
    try:
        data = json.loads((root / gltf).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return []
    uris = [b.get("uri", "") for b in data.get("buffers", []) if isinstance(b, dict)]
    found = [Path(os_normpath(gltf.parent / uri)) for uri in uris if uri and ":" not in uri]
    return [p for p in found if (root / p).is_file()]


def os_normpath(path: Path) -> str:
    """``a/b/../c`` as ``a/c`` (the path need not exist)."""
    parts: list[str] = []
    for part in path.parts:
        if part == "..":
            if parts:
                parts.pop()
        elif part != ".":
            parts.append(part)
    return "/".join(parts)


def _copy(root: Path, files: list[Path], target: Path, commit: str | None) -> int:
    if target.exists():
        shutil.rmtree(target)
    for relative in files:
        destination = target / relative
        destination.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(root / relative, destination)
    if commit:
        (target / "COMMIT").write_text(f"{commit}\n", encoding="utf-8")
    return len(files)


def vendor(root: Path, target: Path, commit: str | None) -> int:
    return _copy(root, data_files(root), target, commit)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("checkout", type=Path, help="a Drake checkout (RobotLocomotion/drake)")
    parser.add_argument("--commit", help="the checkout's commit, recorded in drake/COMMIT")
    parser.add_argument("--target", type=Path, default=HERE / "drake")
    parser.add_argument("--models", type=Path, help="a checkout of RobotLocomotion/models")
    parser.add_argument("--models-commit", help="its commit, recorded in drake_models/COMMIT")
    args = parser.parse_args(argv)
    if not (args.checkout / "multibody" / "parsing").is_dir():
        print(f"error: {args.checkout} is not a Drake checkout", file=sys.stderr)
        return 2
    count = vendor(args.checkout.resolve(), args.target, args.commit)
    print(f"vendored {count} files into {args.target}")
    if args.models is not None:
        target = args.target.parent / "drake_models"
        models = args.models.resolve()
        count = _copy(
            models, models_files(models, args.checkout.resolve()), target, args.models_commit
        )
        print(f"vendored {count} files into {target}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
