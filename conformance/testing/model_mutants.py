"""Model mutants: reimpl's multibody modules with one deliberate bug each, for ``fuzz --models``.

As for the SceneGraph mutants (``conformance.testing.mutants``), a model
mutant touches nothing inside reimpl and monkeypatches nothing: it is the
reimpl ``Api`` in which one multibody module (``tree``, ``plant`` or
``parsing``) is a copy whose class under test is a subclass of reimpl's
public class. The bug is written with pydrake's public names only (a joint's
``type_name()``), so a plain reimpl backend in the same process is
unaffected.

Use one as a backend spec, ``conformance.testing.model_mutants:<name>``, e.g.
``python -m conformance fuzz --models --backend
conformance.testing.model_mutants:rpy_floating_unfiltered``.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from types import ModuleType
from typing import Any

from conformance.backends.reimpl_api import reimpl_api
from conformance.backends.scene_graph import Api, SceneGraphBackend

__all__ = ["MODEL_MUTANTS", "ModelMutant", "model_mutant_backend"]


def _rpy_floating_as_quaternion(tree: ModuleType) -> Mapping[str, type]:
    """An RpyFloatingJoint that reports QuaternionFloatingJoint's type name."""

    class RpyFloatingJoint(tree.RpyFloatingJoint):  # type: ignore[name-defined,misc]
        kTypeName = tree.QuaternionFloatingJoint.kTypeName

    return {"RpyFloatingJoint": RpyFloatingJoint}


@dataclass(frozen=True)
class ModelMutant:
    """One injected bug: its name, what is wrong, and the classes that carry it.

    ``module`` names the Api's multibody module (``tree``, ``plant`` or
    ``parsing``) and ``classes`` makes its replaced classes from reimpl's.
    """

    name: str
    bug: str
    module: str
    classes: Callable[[ModuleType], Mapping[str, type]] = field(repr=False)

    def api(self) -> Api:
        """reimpl's Api with the mutated copy of ``module``."""
        api = reimpl_api()
        original: ModuleType | None = getattr(api, self.module)
        if original is None:
            raise RuntimeError(f"reimpl has no multibody.{self.module} module to mutate")
        copy = ModuleType(f"{__name__}.{self.name}.{self.module}", f"{original.__name__}, mutated")
        for name in getattr(original, "__all__", ()):
            setattr(copy, name, getattr(original, name))
        for name, cls in self.classes(original).items():
            setattr(copy, name, cls)
        changes: dict[str, Any] = {"name": f"mutant:{self.name}", self.module: copy}
        return dataclasses.replace(api, **changes)


MODEL_MUTANTS: dict[str, ModelMutant] = {
    mutant.name: mutant
    for mutant in (
        ModelMutant(
            "rpy_floating_unfiltered",
            "An RpyFloatingJoint is taken for a QuaternionFloatingJoint, so Finalize does not "
            "filter its two bodies (Drake filters every joint type but the quaternion one).",
            "tree",
            _rpy_floating_as_quaternion,
        ),
    )
}


def model_mutant_backend(name: str) -> SceneGraphBackend:
    """A fresh backend for the model mutant ``name`` (a key of MODEL_MUTANTS)."""
    return SceneGraphBackend(MODEL_MUTANTS[name].api())


def __getattr__(name: str) -> Callable[[], SceneGraphBackend]:
    """``conformance.testing.model_mutants:<name>`` as a backend spec: a zero-argument factory."""
    if name in MODEL_MUTANTS:
        return lambda: model_mutant_backend(name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
