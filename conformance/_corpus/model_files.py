"""Cases for model files that nobody wrote for this harness: a case per file.

A model file below a folder (``*.urdf``, ``*.sdf``, ``*.dmd.yaml``, and a
``*.xml`` whose first element is ``<mujoco>``, a MuJoCo model; ``*.obj`` too,
as a one-body mesh model, when asked: ``find_model_files(folder, obj=True)``)
is the case ``<path below the folder>``:

1. ``add_models`` with ``folder`` and ``path``: a new Parser whose package map
   holds the folder's packages (``PopulateFromFolder``), then
   ``AddModels(file_name=)``;
2. ``finalize``;
3. ``model_inventory``: the model instances, bodies, frames, joints and
   geometries (shape, roles) by scoped name;

and C is observed after each step, so the candidate pairs are compared pair
by pair too. A file that may declare collision filter groups (its text names
``collision_filter_group``, or it includes other files) also gets the case
``<path> (filter groups)``: ``add_models``, then ``collision_filter_groups``
(Drake ≥ 1.31, so that older releases still run the first case).

No case expects anything unless ``expected_errors`` says a step fails: two
backends are compared with each other, the reference being the oracle. A
corpus of such cases (``scenarios/real_models``) records the errors pydrake
gives, so that every backend must give them too.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

from conformance._corpus.loader import ScenarioFile, scenario_from_data

__all__ = [
    "GROUPS_SUFFIX",
    "MODEL_SUFFIXES",
    "OBJ_SUFFIX",
    "find_model_files",
    "is_model_file",
    "model_cases",
    "model_scenario",
]

#: The suffixes of model files (an ``.xml`` one only when it is MuJoCo's: ``is_model_file``).
MODEL_SUFFIXES = (".urdf", ".sdf", ".dmd.yaml", ".xml")
#: A mesh Drake parses as a one-body model; a model file only when asked for.
OBJ_SUFFIX = ".obj"
#: What may come before an XML file's first element: blanks, a declaration, comments,
#: a DOCTYPE.
_XML_PROLOG = re.compile(r"(?:\s+|<\?.*?\?>|<!--.*?-->|<![^>]*>)*", re.DOTALL)
_MUJOCO_ROOT = re.compile(r"<\s*mujoco[\s/>]")
#: How much of an ``.xml`` file is read to find its first element.
_XML_HEAD = 65536
#: Folders that hold build outputs or version control, never a user's models.
_SKIPPED_FOLDERS = frozenset({".git", "bazel-bin", "bazel-out", "bazel-testlogs", "__pycache__"})
#: The description suffix of a file's filter-group case.
GROUPS_SUFFIX = " (filter groups)"
#: Text that makes a file's filter-group case worth running.
_GROUP_HINTS = ("collision_filter_group", "<include")

#: The ops of a file's case, then those of its filter-group case.
_STEPS: tuple[tuple[str, ...], ...] = (
    ("add_models", "finalize", "model_inventory"),
    ("add_models", "collision_filter_groups"),
)


def _is_mujoco(path: Path) -> bool:
    """Whether the XML file's first element is ``<mujoco>`` (not, e.g., a ``package.xml``)."""
    try:
        with path.open(encoding="utf-8", errors="replace") as stream:
            head = stream.read(_XML_HEAD)
    except OSError:
        return False
    text = head.lstrip("\ufeff")
    prolog = _XML_PROLOG.match(text)
    return _MUJOCO_ROOT.match(text, prolog.end() if prolog else 0) is not None


def is_model_file(path: Path, *, obj: bool = False) -> bool:
    """Whether ``path`` names a model file (an ``.obj`` one only with ``obj``)."""
    name = path.name.lower()
    if name.endswith(OBJ_SUFFIX):
        return obj
    if name.endswith(".xml"):
        return _is_mujoco(path)
    return name.endswith(MODEL_SUFFIXES)


def find_model_files(folder: Path, *, obj: bool = False) -> list[Path]:
    """The model files below ``folder``, relative to it, in sorted order (``.obj`` files
    too with ``obj``)."""
    found = []
    for parent, folders, names in os.walk(folder):
        folders[:] = sorted(f for f in folders if f not in _SKIPPED_FOLDERS)
        found += [
            Path(parent, name).relative_to(folder)
            for name in names
            if is_model_file(Path(parent, name), obj=obj)
        ]
    return sorted(found)


def _may_declare_groups(path: Path) -> bool:
    try:
        text = path.read_text(encoding="utf-8", errors="replace")
    except OSError:
        return True
    return any(hint in text for hint in _GROUP_HINTS)


def model_cases(
    folder: Path,
    files: Iterable[Path],
    *,
    folder_arg: str | None = None,
    packages: Mapping[str, str] | None = None,
) -> list[dict[str, Any]]:
    """The raw cases (scenario data) of ``files``, relative paths below ``folder``.

    ``folder_arg`` is what the steps write as ``folder`` (default: ``folder``
    itself; a corpus file writes it relative to itself); ``packages`` (name:
    folder) are added to each parse's package map besides the folder's own.
    """
    cases = []
    for relative in files:
        path = relative.as_posix()
        descriptions = [path]
        if _may_declare_groups(folder / relative):
            descriptions.append(path + GROUPS_SUFFIX)
        for description, ops in zip(descriptions, _STEPS, strict=False):
            steps: list[dict[str, Any]] = []
            for op in ops:
                step: dict[str, Any] = {"op": op}
                if op == "add_models":
                    step.update(folder=folder_arg or str(folder), path=path)
                    if packages:
                        step["packages"] = dict(packages)
                steps.append(step)
            cases.append({"description": description, "steps": steps})
    return cases


def model_scenario(
    folder: Path,
    files: Sequence[Path],
    *,
    description: str,
    packages: Mapping[str, str] | None = None,
) -> ScenarioFile:
    """The loaded scenario of ``files`` below ``folder``, named after the folder: its cases
    are ``<folder name> > <path>``."""
    data = {
        "description": description,
        "features": ["multibody", "parsing"],
        "cases": model_cases(folder, files, packages=packages),
    }
    return scenario_from_data(data, folder.parent / f"{folder.name}.json", root=folder.parent)
