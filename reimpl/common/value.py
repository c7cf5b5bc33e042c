"""Type-erased values: ``AbstractValue`` and ``Value[T]`` (pydrake.common.value).

Geometry properties hold their values as AbstractValues, and
``GetPropertiesInGroup`` hands them out as such. ``Value`` is a template:
``Value[float]``, ``Value[str]``, ``Value[bool]`` hold converted copies (the
C++ ``double``, ``std::string`` and ``bool``); ``Value[object]`` holds any
Python object; other instantiations hold an instance of their class.
``Value(x)`` and ``AbstractValue.Make(x)`` pick the instantiation from the
type of ``x``, as pydrake does (an ``int`` is a Python object).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, ClassVar

from reimpl._release import release
from reimpl._template import TemplateClass
from reimpl.common._pybind_text import incompatible_arguments, no_constructor

__all__ = ["AbstractValue", "Value", "cpp_type_name", "register_value_type"]

# N.B. pydrake names instantiations with these two characters, e.g. Value𝓣float𝓤.
_OPEN, _CLOSE = "\U0001d4e3", "\U0001d4e4"


class AbstractValue:
    """A value whose type is known at run time only."""

    _param: ClassVar[Any] = None
    _cpp_name: ClassVar[str] = ""
    _convert: ClassVar[Callable[[Any], Any] | None] = None
    _value: Any

    def __init__(self, *args: object, **kwargs: object) -> None:
        raise no_constructor("reimpl.common.value.AbstractValue")

    @staticmethod
    def Make(value: object) -> AbstractValue:
        """A ``Value`` of the instantiation that fits ``type(value)``."""
        cls = _INSTANTIATIONS.get(type(value))
        if cls is None:
            # N.B. Subclasses convert too (numpy.float64 is held as a double).
            base = next((t for t in (float, str) if isinstance(value, t)), object)
            cls = _INSTANTIATIONS[base]
        return cls(value)

    def get_value(self) -> Any:
        return self._value

    def get_mutable_value(self) -> Any:
        if self._convert is not None:
            raise RuntimeError(
                "Cannot get mutable value (or reference) for a type-conversion type: "
                f"{self._param!r}"
            )
        return self._value

    def set_value(self, value: object) -> None:
        convert = type(self)._convert
        self._value = convert(value) if convert is not None else value

    def Clone(self) -> AbstractValue:
        return type(self)(self._value)

    def SetFrom(self, other: AbstractValue) -> None:
        if type(other) is not type(self):
            raise RuntimeError(
                f"AbstractValue: a request to cast to '{self._cpp_name}' failed because the "
                f"value was created using the static type '{other._cpp_name}'."
            )
        self._value = other._value

    def __copy__(self) -> AbstractValue:
        return self.Clone()

    def __deepcopy__(self, memo: dict[int, object]) -> AbstractValue:
        return self.Clone()


class _ValueTemplate(TemplateClass):
    """``Value[T]`` indexes; ``Value(x)`` makes, as ``AbstractValue.Make(x)``."""

    def __call__(self, value: object) -> AbstractValue:
        return AbstractValue.Make(value)


Value = _ValueTemplate("reimpl.common.value", "Value")
_INSTANTIATIONS: dict[Any, type[AbstractValue]] = {}


def _instantiate(param: Any, cpp_name: str, convert: Callable[[Any], Any] | None) -> None:
    def init(self: AbstractValue, value: object) -> None:
        if value is None and param is object and not release.has("value-of-none-until-1.57"):
            # 1.58: None means "default-construct", and a Python object has no default.
            raise TypeError("object() takes no arguments")
        if convert is None and param is not object and not isinstance(value, param):
            raise TypeError(
                f"{incompatible_arguments('__init__')}. The following argument "
                f"types are supported:\n    1. {type(self).__name__}(arg0: {param.__name__})"
                f"\n\nInvoked with: {value!r}"
            )
        self._value = convert(value) if convert is not None else value

    name = f"Value{_OPEN}{param.__name__}{_CLOSE}"
    cls = type(
        name,
        (AbstractValue,),
        {
            "__init__": init,
            "__module__": "reimpl.common.value",
            "__qualname__": name,
            "_param": param,
            "_cpp_name": cpp_name,
            "_convert": staticmethod(convert) if convert is not None else None,
        },
    )
    _INSTANTIATIONS[param] = cls
    Value.add_instantiation(param, cls)


def register_value_type(cls: type, cpp_name: str) -> None:
    """Makes ``Value[cls]`` exist; ``cpp_name`` is how Drake prints its C++ type."""
    _instantiate(cls, cpp_name, None)


def cpp_type_name(value: AbstractValue) -> str:
    """The C++ type Drake names for the value (NiceTypeName), e.g. ``std::string``."""
    return value._cpp_name


_instantiate(str, "std::string", str)
_instantiate(bool, "bool", bool)
_instantiate(float, "double", float)
_instantiate(object, "drake::pydrake::Object", None)
