"""Shared setup for the ported parsing tests: a plant, its SceneGraph and a Parser.

pydrake's Parser does not keep its plant alive, nor does a plant its SceneGraph,
so ``Parsing`` holds all three for the test's lifetime.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from importlib.metadata import version
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

from conformance._policy.release_facts import fact_holds
from conformance._policy.versions import version_in_range
from reimpl._release import release as reimpl_release

__all__ = [
    "INVALID_DIRECTIVES",
    "Parsing",
    "fact_holds_for",
    "follows_1_51",
    "invalid_directive",
    "names_of",
    "write",
]

#: pydrake 1.51.1's SystemExit for a directive that is not valid
INVALID_DIRECTIVES = (
    "Failure at external/drake+/multibody/parsing/detail_dmd_parser.cc:332 in "
    "LoadModelDirectives(): condition 'directives.IsValid()' failed."
)


def follows_1_51(drake: ModuleType) -> bool:
    """Whether the implementation is Drake 1.51: reimpl's release (REIMPL_DRAKE_RELEASE,
    which tests/conftest.py sets to the installed pydrake's), or the installed pydrake."""
    followed = reimpl_release.version if drake.__name__ == "reimpl" else version("drake")
    return version_in_range(followed, "1.51", "1.51")


def fact_holds_for(drake: ModuleType, fact_id: str) -> bool:
    """Whether the release fact ``fact_id`` holds for the implementation's release: reimpl's
    (REIMPL_DRAKE_RELEASE), or the installed pydrake's."""
    if drake.__name__ == "reimpl":
        return reimpl_release.has(fact_id)
    return fact_holds(fact_id, version("drake"))


@contextmanager
def invalid_directive(drake: ModuleType, problem: str) -> Iterator[None]:
    """Expects directives to be refused as invalid.

    Measured: up to 1.57 pydrake logs ``problem`` and raises SystemExit (Drake's
    DRAKE_THROW_UNLESS(IsValid())); since 1.58 RuntimeError ``error: <problem>``
    (release fact directives-invalid-error-since-1.58).
    """
    if not fact_holds_for(drake, "directives-invalid-error-since-1.58"):
        with pytest.raises(SystemExit) as exit_info:
            yield
        assert str(exit_info.value) == INVALID_DIRECTIVES
    else:
        with pytest.raises(RuntimeError) as error_info:
            yield
        assert str(error_info.value) == f"error: {problem}"


def names_of(plant: Any, instances: list[Any]) -> list[str]:
    return [plant.GetModelInstanceName(model_instance=i) for i in instances]


def write(folder: Path, name: str, text: str) -> Path:
    path = folder / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


@dataclass
class Parsing:
    """A plant (with a SceneGraph unless ``scene_graph=False``) and a Parser of it."""

    drake: ModuleType
    scene_graph: bool = True
    plant: Any = field(init=False)
    sg: Any = field(init=False)
    parser: Any = field(init=False)

    def __post_init__(self) -> None:
        self.plant = self.drake.multibody.plant.MultibodyPlant(time_step=0.0)
        self.sg = self.drake.geometry.SceneGraph() if self.scene_graph else None
        if self.sg is not None:
            self.plant.RegisterAsSourceForSceneGraph(scene_graph=self.sg)
        self.parser = self.drake.multibody.parsing.Parser(plant=self.plant)

    def add(self, text: str, file_type: str) -> list[str]:
        """Parses model text; the names of the model instances it added."""
        added = self.parser.AddModels(file_contents=text, file_type=file_type)
        return names_of(self.plant, added)

    def groups(self) -> tuple[dict[str, set[str]], set[tuple[str, str]]]:
        report = self.parser.GetCollisionFilterGroups()
        return report.groups(), report.exclusion_pairs()

    def geometry(self, name: str) -> Any:
        """The id of the geometry named ``name`` (scoped, as SceneGraph names it)."""
        inspector = self.sg.model_inspector()
        (found,) = [g for g in inspector.GetAllGeometryIds() if inspector.GetName(g) == name]
        return found

    def filtered(self, a: str, b: str) -> bool:
        inspector = self.sg.model_inspector()
        return bool(
            inspector.CollisionFiltered(
                geometry_id1=self.geometry(a), geometry_id2=self.geometry(b)
            )
        )
