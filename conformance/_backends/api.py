"""``Api``: the modules of a pydrake-compatible implementation, which one backend class drives.

Its own module, so the backend's handler modules (``scene_graph``,
``multibody``) and the modules that make an ``Api`` (``pydrake_api``,
``reimpl_api``) share it without importing each other.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import ModuleType

__all__ = ["Api"]


@dataclass(frozen=True)
class Api:
    """The modules of a pydrake-compatible implementation.

    The multibody modules (``pydrake.multibody.plant``, ``.tree``,
    ``.parsing``) are optional: without them the model feature tags are
    missing and model cases are skipped.
    """

    name: str
    #: The Drake release whose behaviour this implementation has (for since/until).
    version: str
    geometry: ModuleType
    math: ModuleType
    plant: ModuleType | None = None
    tree: ModuleType | None = None
    parsing: ModuleType | None = None
