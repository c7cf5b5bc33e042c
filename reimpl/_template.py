"""Scalar-template aliases: ``RigidTransform_[float]`` and friends.

pydrake binds each C++ class template as a ``TemplateClass`` named with a
trailing underscore; indexing it with a scalar type gives the class, and the
default instantiation is also exported under the plain name
(``SceneGraph_[float] is SceneGraph``). reimpl follows only the ``double``
scalar, so ``float`` is the one parameter its scalar templates accept.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

__all__ = ["TemplateClass", "scalar_template"]


def _param_name(param: object) -> str:
    return getattr(param, "__name__", repr(param))


class TemplateClass:
    """A name indexed by type parameters, as pydrake's ``TemplateClass``."""

    def __init__(self, module: str, name: str) -> None:
        self._module = module
        self._name = name
        self._instantiations: dict[tuple[Any, ...], Any] = {}
        self._lazy: list[Callable[[], None]] = []

    @property
    def param_list(self) -> list[tuple[Any, ...]]:
        self._resolve()
        return list(self._instantiations)

    def add_instantiation(self, param: Any, instantiation: Any) -> None:
        key = param if isinstance(param, tuple) else (param,)
        self._instantiations[key] = instantiation

    def add_lazy(self, register: Callable[[], None]) -> None:
        """Defers registrations that would import a module that imports this one."""
        self._lazy.append(register)

    def _resolve(self) -> None:
        while self._lazy:
            self._lazy.pop(0)()

    def __getitem__(self, param: Any) -> Any:
        self._resolve()
        key = param if isinstance(param, tuple) else (param,)
        try:
            return self._instantiations[key]
        except (KeyError, TypeError):
            names = ", ".join(_param_name(p) for p in key)
            raise RuntimeError(f"Invalid instantiation: {self._name}[{names}]") from None

    def __str__(self) -> str:
        return f"<TemplateClass {self._module}.{self._name}>"


def scalar_template(module: str, name: str, cls: type) -> TemplateClass:
    """``name`` (e.g. ``SceneGraph_``) with ``cls`` as its ``float`` instantiation."""
    template = TemplateClass(module, name)
    template.add_instantiation(float, cls)
    return template
