"""Context and ports: the parts of pydrake.systems.framework SceneGraph scripts touch.

A Context owns a copy of the model's GeometryState, taken when the context is
created; ports give access to it (query output) or feed it (pose input).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from reimpl.geometry.geometry_state import GeometryState

__all__ = ["Context", "InputPort", "OutputPort"]


class Context:
    """The state of one SceneGraph evaluation; independent of the model once made."""

    def __init__(self, *args: object, **kwargs: object) -> None:
        raise TypeError("reimpl.systems.framework.Context: No constructor defined!")

    _geometry_state: GeometryState
    _system_id: int
    _fixed_inputs: dict[int, Any]
    _clone_check: Callable[[Context], None] | None
    _num_input_ports: int

    @classmethod
    def _make(cls, state: GeometryState, system_id: int, num_input_ports: int) -> Context:
        context = object.__new__(cls)
        context._geometry_state = state
        context._system_id = system_id
        context._fixed_inputs = {}
        context._clone_check = None
        # N.B. Fixed at creation: ports of sources registered later are missing.
        context._num_input_ports = num_input_ports
        return context

    def num_input_ports(self) -> int:
        return self._num_input_ports

    def Clone(self) -> Context:
        """A deep copy: filters and transient history (same FilterIds) included."""
        if self._clone_check is not None:
            self._clone_check(self)
        clone = Context._make(self._geometry_state.clone(), self._system_id, self._num_input_ports)
        clone._fixed_inputs = dict(self._fixed_inputs)
        return clone


class OutputPort:
    """An output port whose value is computed from a context."""

    def __init__(self, name: str, calc: Callable[[Context], Any]) -> None:
        self._name = name
        self._calc = calc

    def get_name(self) -> str:
        return self._name

    def Eval(self, context: Context) -> Any:
        return self._calc(context)


class FixedInputPortValue:
    """What InputPort.FixValue returns."""

    def __init__(self, value: object) -> None:
        self._value = value

    def GetMutableData(self) -> object:
        return self._value


class InputPort:
    """An input port; FixValue stores a value in one context."""

    def __init__(self, name: str, index: int) -> None:
        self._name = name
        self._index = index

    def get_name(self) -> str:
        return self._name

    def get_index(self) -> int:
        return self._index

    def FixValue(self, context: Context, value: object) -> FixedInputPortValue:
        context._fixed_inputs[self._index] = value
        return FixedInputPortValue(value)

    def HasValue(self, context: Context) -> bool:
        return self._index in context._fixed_inputs
