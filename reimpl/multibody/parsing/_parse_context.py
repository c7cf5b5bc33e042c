"""What one parse (one ``Parser.AddModels*`` call) shares between the readers."""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from reimpl.multibody.parsing._collision_filter_group_resolver import (
    CollisionFilterGroupResolver,
)
from reimpl.multibody.parsing._diagnostics import Diagnostics, literal_string_name
from reimpl.multibody.parsing._package_map import PackageMap

__all__ = ["ModelSource", "ParseContext"]


@dataclass(frozen=True)
class ModelSource:
    """Model text, and where it came from (a file, or a string of ``file_type``)."""

    text: str
    file_type: str
    path: str | None = None
    #: How messages name a file, where not by its path (SDFormat: ``//abs/path``).
    label: str | None = None

    def diagnostics(self, strict: bool) -> Diagnostics:
        name = self.label or self.path or literal_string_name(self.file_type)
        return Diagnostics(name, strict)

    @property
    def root_dir(self) -> str | None:
        """Where relative URIs start; model text has none."""
        return os.path.dirname(os.path.abspath(self.path)) if self.path else None


#: Reads ``source`` into the plant: (context, source, model name, parent scope) -> instances.
Reader = Callable[["ParseContext", ModelSource, "str | None", str], list[Any]]


@dataclass
class ParseContext:
    """The plant, packages and group resolver of one parse, and how to read a file."""

    plant: Any
    package_map: PackageMap
    resolver: CollisionFilterGroupResolver
    auto_renaming: bool
    strict: bool
    read_file: Callable[[ParseContext, str, str | None, str], list[Any]]
    #: the DiagramBuilder the Parser was given, if any (MuJoCo cameras need one)
    builder: Any = None

    def has_scene_graph(self) -> bool:
        return bool(self.plant.geometry_source_is_registered())

    def add_model_instance(self, name: str) -> Any:
        """A new model instance; with auto-renaming a taken name gets ``_1``, ``_2``, ..."""
        plant = self.plant
        if self.auto_renaming and plant.HasModelInstanceNamed(name):
            suffix = 1
            while plant.HasModelInstanceNamed(f"{name}_{suffix}"):
                suffix += 1
            name = f"{name}_{suffix}"
        return plant.AddModelInstance(name)
