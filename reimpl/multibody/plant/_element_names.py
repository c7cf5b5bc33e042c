"""Finding a plant's bodies, frames and joints by name, with Drake's errors.

Drake counterpart: MultibodyTree's ``Has*Named``, ``Get*ByName`` and
``NumBodiesWithName`` (multibody_tree.cc). Measured on pydrake 1.51.1:

- With a ``model_instance``, the element of that name in that instance (the
  instance checked first); without one, the one element of that name in any
  instance: a name held in several instances is an error even for ``Has``.
- ``Get*ByName`` names what exists instead, in this order: the other model
  instances that hold the name; that there are no elements of the kind;
  else, per instance holding any, its names sorted.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TypeVar

from reimpl._release import release
from reimpl.multibody._errors import NotFoundError
from reimpl.multibody.plant._elements import Elements
from reimpl.multibody.tree import Frame, Joint, ModelInstanceIndex, RigidBody

__all__ = ["ElementNames"]

_E = TypeVar("_E", RigidBody, Frame, Joint)


def _instance_order(element: RigidBody | Frame | Joint) -> int:
    return int(element.model_instance())


class ElementNames(Elements):
    """The lookups by name of bodies, frames and joints."""

    def HasBodyNamed(self, name: str, model_instance: ModelInstanceIndex | None = None) -> bool:
        """Whether a body has the name (in ``model_instance``); see ``_has_named``."""
        return self._has_named("RigidBody", self._bodies, name, model_instance)

    def HasFrameNamed(self, name: str, model_instance: ModelInstanceIndex | None = None) -> bool:
        return self._has_named("Frame", self._frames, name, model_instance)

    def HasJointNamed(self, name: str, model_instance: ModelInstanceIndex | None = None) -> bool:
        return self._has_named("Joint", self._joints, name, model_instance)

    def _has_named(
        self,
        kind: str,
        elements: Sequence[_E],
        name: str,
        model_instance: ModelInstanceIndex | None,
    ) -> bool:
        """Without ``model_instance``, a name held in several instances raises (measured)."""
        found = sorted(self._named(elements, name, model_instance), key=_instance_order)
        if model_instance is None and len(found) > 1:
            instances = ", ".join(self.GetModelInstanceName(e.model_instance()) for e in found)
            raise NotFoundError(
                f"Has{kind}Named(): A {kind} named '{name}' appears in multiple model instances "
                f"({instances}); you must provide a model_instance argument to disambiguate."
            )
        return bool(found)

    def NumBodiesWithName(self, name: str) -> int:
        """How many bodies, in all model instances, have the name."""
        return len(self._named(self._bodies, name, None))

    def GetBodyByName(
        self, name: str, model_instance: ModelInstanceIndex | None = None
    ) -> RigidBody:
        method, kind = (
            ("GetRigidBodyByName", "RigidBody")
            if release.has("rigid-body-wording-since-1.25")
            else ("GetBodyByName", "Body")
        )
        return self._get_by_name(method, kind, self._bodies, name, model_instance)

    def GetRigidBodyByName(
        self, name: str, model_instance: ModelInstanceIndex | None = None
    ) -> RigidBody:
        return self.GetBodyByName(name, model_instance)

    def GetFrameByName(self, name: str, model_instance: ModelInstanceIndex | None = None) -> Frame:
        return self._get_by_name("GetFrameByName", "Frame", self._frames, name, model_instance)

    def GetJointByName(self, name: str, model_instance: ModelInstanceIndex | None = None) -> Joint:
        return self._get_by_name("GetJointByName", "Joint", self._joints, name, model_instance)

    def GetMutableJointByName(
        self, name: str, model_instance: ModelInstanceIndex | None = None
    ) -> Joint:
        return self.GetJointByName(name, model_instance)

    def _named(
        self, elements: Sequence[_E], name: str, model_instance: ModelInstanceIndex | None
    ) -> list[_E]:
        if model_instance is not None:
            self._instance(model_instance)
        return [
            e
            for e in elements
            if e.name() == name and (model_instance is None or e.model_instance() == model_instance)
        ]

    def _get_by_name(
        self,
        method: str,
        kind: str,
        elements: Sequence[_E],
        name: str,
        model_instance: ModelInstanceIndex | None,
    ) -> _E:
        """The one element named ``name`` (in ``model_instance``), or Drake's error.

        The error lists, per instance holding any, the valid names (sorted).
        """
        found = sorted(self._named(elements, name, model_instance), key=_instance_order)
        if found:
            if len(found) > 1:
                instances = ", ".join(self.GetModelInstanceName(e.model_instance()) for e in found)
                raise NotFoundError(
                    f"{method}(): A {kind} named '{name}' appears in multiple model instances "
                    f"({instances}); you must provide a model_instance argument to disambiguate."
                )
            return found[0]
        elsewhere = sorted(self._named(elements, name, None), key=_instance_order)
        if elsewhere and model_instance is not None:
            instances = ", ".join(self.GetModelInstanceName(e.model_instance()) for e in elsewhere)
            raise NotFoundError(
                f"{method}(): There is no {kind} named '{name}' in the model instance named "
                f"'{self.GetModelInstanceName(model_instance)}', but one does exist in other "
                f"model instances ({instances})."
            )
        if not release.has("element-names-per-instance-since-1.24"):
            every = ", ".join(sorted({e.name() for e in elements}))
            raise NotFoundError(
                f"{method}(): There is no {kind} named '{name}' anywhere in the model "
                f"(valid names are: {every})"
            )
        if not elements:
            raise NotFoundError(f"{method}(): There are no {kind}s defined in the model")
        valid = []
        for index, instance_name in enumerate(self._instance_names):
            names = sorted(e.name() for e in elements if int(e.model_instance()) == index)
            if names:
                valid.append(
                    f"valid names in model instance '{instance_name}' are: {', '.join(names)}"
                )
        raise NotFoundError(
            f"{method}(): There is no {kind} named '{name}' anywhere in the model "
            f"({'; '.join(valid)})"
        )
