"""A parsed name held by model instance *index*, so that renaming the instance
renames it too (Drake's ``InstancedName``, the fix of issue #21316).

``a::b::g`` whose namespace ``a::b`` is a model instance is held as
(index of ``a::b``, ``g``); an unscoped name (a group declared at global scope
in model directives) as (None, ``g``). The Parser keeps every parse's groups
this way and spells them with the instances' current names when asked, so
(measured on pydrake 1.51.1), after ``plant.RenameModelInstance(m, "x0")``,
group ``r::g`` reads ``x0::g``, and loading the same model again as ``r`` adds
``r::g`` beside it. Two global groups of the same name in two parses still
clash: the second parse ends the program (SystemExit) when its groups are
merged, after its models and filters were added.

Drake orders instanced names with the global ones first, then by instance
index, then by name.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from reimpl.multibody.parsing import _scoped_name as scoped
from reimpl.multibody.tree import ModelInstanceIndex

__all__ = ["InstancedName", "instanced", "order", "spelled"]


@dataclass(frozen=True)
class InstancedName:
    #: the model instance's index; None for a name declared at global scope
    index: int | None
    name: str


def order(name: InstancedName) -> tuple[bool, int, str]:
    """Drake's ``operator<=>``: an empty optional first, then index, then name."""
    return (name.index is not None, name.index or 0, name.name)


def instanced(plant: Any, full_name: str) -> InstancedName:
    """The instanced form of a fully scoped name (its namespace must be an instance)."""
    namespace, element = scoped.split(full_name)
    if plant.HasModelInstanceNamed(namespace):
        return InstancedName(int(plant.GetModelInstanceByName(namespace)), element)
    return InstancedName(None, element)


def spelled(plant: Any, name: InstancedName) -> str:
    """The scoped name, with the model instance's current name."""
    if name.index is None:
        return name.name
    return scoped.join(plant.GetModelInstanceName(ModelInstanceIndex(name.index)), name.name)
