"""Where an SDFormat name leads in the plant, seen from the model being added (Drake 1.51.1).

Names in a model ``m`` (instance ``p::m`` with a parse prefix ``p``) are
relative to it: ``x`` is ``x`` in ``p::m``, ``inner::x`` is ``x`` in
``p::m::inner``. Seen from a world, ``m::x`` is ``x`` in ``m``; ``world`` (or
nothing) is the world body. Conversely a body's *relative name* is the name
that reaches it from the model (``inner::x``), as Drake's GetRelativeBodyName.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Protocol

from reimpl.math import RigidTransform
from reimpl.multibody.parsing import _scoped_name as scoped
from reimpl.multibody.parsing._sdf_graph import join
from reimpl.multibody.parsing._xml import XmlElement

__all__ = ["Reporter", "Scope"]

_WORLD = "world"


class Reporter(Protocol):
    """Drake's SDFormatDiagnostic for the document being added."""

    def error(self, element: XmlElement, message: str) -> Exception: ...

    def warn(self, element: XmlElement, message: str) -> None: ...

    def check_supported(self, element: XmlElement, supported: frozenset[str]) -> None: ...


@dataclass
class Scope:
    """A model (or the world) being added: its instance, graph name, and pose in the world."""

    plant: Any
    instance: Any
    #: the instance name ("" for the world)
    name: str
    #: the model's vertex in the graphs ("" for the world)
    vertex: str
    X_WM: RigidTransform
    world: bool = False

    @property
    def frame_scope(self) -> str:
        """The graph vertex the scope's poses are resolved from."""
        return _WORLD if self.world else join(self.vertex, "__model__")

    def vertex_of(self, name: str) -> str:
        return join(self.vertex, name)

    def instance_and_local(self, name: str) -> tuple[Any, str]:
        """GetResolvedModelInstanceAndLocalName: ``inner::x`` is ``x`` in ``<scope>::inner``."""
        namespace, local = scoped.split(name)
        if not namespace:
            return self.instance, local
        return self.plant.GetModelInstanceByName(scoped.join(self.name, namespace)), local

    def body(self, link: str) -> Any:
        """GetBodyByLinkSpecificationName: ``world`` (or nothing) is the world body."""
        if link in ("", _WORLD):
            return self.plant.world_body()
        instance, local = self.instance_and_local(link)
        return self.plant.GetBodyByName(local, instance)

    def relative_body_name(self, body: Any) -> str:
        """GetRelativeBodyName: the body's name as seen from the scope's model."""
        body_instance = self.plant.GetModelInstanceName(body.model_instance())
        if self.world:
            return scoped.join(body_instance, body.name())
        if body.model_instance() != self.instance:
            return scoped.join(body_instance.removeprefix(f"{self.name}::"), body.name())
        return str(body.name())
