"""Model instances: the named groups a plant's elements belong to, and scoped names.

Drake counterpart: the model instances of MultibodyPlant (multibody_tree.cc,
model_instance.cc). Measured on pydrake 1.51.1:

- Instances 0 (``WorldModelInstance``) and 1 (``DefaultModelInstance``)
  always exist; ``AddModelInstance`` appends the next index. A name is
  unique, and never empty (an empty one ends the program: SystemExit).
- ``scoped(x)`` is ``instance::x`` for instances ≥ 2 and plain ``x`` in the
  world and default instances; SceneGraph frames and geometries are named so.
- An index is checked where Drake's table for the call checks it, each with
  its own error: a name lookup (``_instance``), a per-instance table such as
  the counts and q (``_indexed_instance``), an element listing
  (``_listed_instance``, SystemExit).
- ``RenameModelInstance`` renames in ``_rename_instance``, which the
  SceneGraph source extends to the scoped names it registered.
"""

from __future__ import annotations

from typing import NoReturn

from reimpl._release import release
from reimpl.multibody._errors import DuplicateNameError, FinalizedError, NotFoundError
from reimpl.multibody.plant._demands import fail_demand
from reimpl.multibody.plant._phase import PlantPhase
from reimpl.multibody.tree import ModelInstanceIndex

__all__ = ["PREDEFINED_INSTANCES", "ModelInstances"]

_WORLD_INSTANCE_NAME = "WorldModelInstance"
_DEFAULT_INSTANCE_NAME = "DefaultModelInstance"
#: The instances every plant has (world and default); they do not scope names.
PREDEFINED_INSTANCES = 2


#: Whether naming a model instance ``""`` fails Drake's demand (release fact
#: empty-model-instance-name-demand-since-1.25); up to 1.24 ``""`` is a name like any
#: other (measured on 1.12.0 to 1.58.0).
_EMPTY_NAME_REFUSED = release.has("empty-model-instance-name-demand-since-1.25")


def _empty_instance_name() -> NoReturn:
    """What pydrake raises (SystemExit, measured) naming a model instance ``""``."""
    fail_demand("ModelInstance.set_name")


class ModelInstances(PlantPhase):
    """The plant's model instances, by index: their names."""

    def __init__(self) -> None:
        super().__init__()
        self._instance_names = [_WORLD_INSTANCE_NAME, _DEFAULT_INSTANCE_NAME]

    def _scoped(self, model_instance: ModelInstanceIndex, name: str) -> str:
        """``instance::name`` for instances ≥ 2; ``name`` in the world and default ones."""
        if int(model_instance) < PREDEFINED_INSTANCES:
            return name
        return f"{self._instance_names[int(model_instance)]}::{name}"

    def AddModelInstance(self, name: str) -> ModelInstanceIndex:
        """Adds an empty model instance; an empty ``name`` ends the program as on pydrake."""
        if self._finalized:
            raise FinalizedError(
                "This MultibodyTree is finalized already. Therefore adding more model "
                "instances is not allowed. See documentation for Finalize() for details."
            )
        self._check_new_instance_name(name)
        if not name and _EMPTY_NAME_REFUSED:
            _empty_instance_name()
        self._instance_names.append(name)
        return ModelInstanceIndex(len(self._instance_names) - 1)

    def _check_new_instance_name(self, name: str) -> None:
        if name in self._instance_names:
            raise DuplicateNameError(
                f"This model already contains a model instance named '{name}'. Model instance "
                "names must be unique within a given model."
            )

    def num_model_instances(self) -> int:
        return len(self._instance_names)

    def HasModelInstanceNamed(self, name: str) -> bool:
        return name in self._instance_names

    def GetModelInstanceByName(self, name: str) -> ModelInstanceIndex:
        if name not in self._instance_names:
            known = ", ".join(f"'{n}'" for n in sorted(self._instance_names))
            listed = f" The current model instances are {known}."
            raise NotFoundError(
                f"GetModelInstanceByName(): There is no model instance named '{name}'."
                + (listed if release.has("model-instance-names-in-error-since-1.14") else "")
            )
        return ModelInstanceIndex(self._instance_names.index(name))

    def GetModelInstanceName(self, model_instance: ModelInstanceIndex) -> str:
        return self._instance_names[self._instance(model_instance)]

    def _instance(self, model_instance: ModelInstanceIndex) -> int:
        """The index; Drake's name lookup's error if no instance has it."""
        index = int(model_instance)
        if not 0 <= index < len(self._instance_names):
            raise NotFoundError(f"There is no model instance id {index} in the model.")
        return index

    def _indexed_instance(self, model_instance: ModelInstanceIndex) -> int:
        """The index; the error of Drake's per-instance tables (the counts, q and
        its names), measured on pydrake 1.51.1 and 1.58.0."""
        index = int(model_instance)
        if index < 0:
            raise NotFoundError(
                "The given default-constructed ModelInstanceIndex() cannot be used. You must "
                "pass a valid integer as the index."
            )
        if index >= len(self._instance_names):
            raise NotFoundError(
                f"The given ModelInstanceIndex({index}) is out of bounds (must be less than "
                f"{len(self._instance_names)})"
            )
        return index

    def _listed_instance(self, method: str, model_instance: ModelInstanceIndex) -> int:
        """The index; the SystemExit of Drake's element listings (multibody_tree.cc,
        measured): the demand ``<method>.instance``."""
        index = int(model_instance)
        if not 0 <= index < len(self._instance_names):
            fail_demand(f"{method}.instance")
        return index

    @release.binding("rename-model-instance-since-1.20")
    def RenameModelInstance(self, model_instance: ModelInstanceIndex, name: str) -> None:
        """Renames the instance, and the scoped names of its SceneGraph frames and geometries.

        As Drake does it: every frame of this plant's source whose frame group is
        the instance, and every geometry on such a frame (whoever registered it),
        named ``old::x`` becomes ``new::x``; other names (a frame the user
        renamed, an unscoped name) are left alone. After Finalize, pydrake
        raises SystemExit (a DRAKE_THROW_UNLESS in multibody_plant.cc, at line
        1372 on 1.51.1 and 1320 on 1.58.0: the demand
        ``RenameModelInstance.finalized``), and so does reimpl. An empty ``name``
        raises SystemExit as on pydrake since 1.25 (which, measured on 1.51.1,
        still registers ``""``; reimpl leaves the instance as it was); up to 1.24
        it is a new name like any other.
        """
        if self._finalized:
            fail_demand("RenameModelInstance.finalized")
        index = self._instance(model_instance)
        old = self._instance_names[index]
        if name == old:
            return
        if not name and _EMPTY_NAME_REFUSED:
            _empty_instance_name()
        self._check_new_instance_name(name)
        self._rename_instance(index, old, name)

    def _rename_instance(self, index: int, old: str, name: str) -> None:
        """Gives instance ``index`` its new name (the SceneGraph source renames more)."""
        self._instance_names[index] = name
