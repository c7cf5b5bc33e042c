"""Plain data structs bound the way pydrake binds Drake's serializable structs.

pydrake binds a C++ struct with a ``Serialize`` method (``RemoteParams``, the
model-directive structs, ``schema.Transform``) through ``ParamInit``,
``DefAttributesUsingSerialize`` and ``DefReprUsingSerialize``. Measured on
pydrake 1.51.1, such a class:

=================================  ==================================================
 construction                       keywords only, each a field; a positional argument
                                    is pybind11's "incompatible constructor arguments"
                                    TypeError; an unknown keyword is AttributeError
 a field                            read and written as an attribute; a value of the
                                    wrong type is pybind11's TypeError; a list field
                                    reads as a new list each time (appending to it
                                    changes nothing), a vector as a read-only array,
                                    a struct field as the struct itself
 ``repr`` and ``str``               ``Name(field=value, ...)`` in ``Serialize`` order
 ``copy.copy``, ``copy.deepcopy``   a deep copy
 ``==``                             identity (no comparison is bound)
 pickling                           TypeError ``cannot pickle '<module>.Name' object``
=================================  ==================================================

A subclass lists its fields in ``FIELDS`` (in ``Serialize`` order).
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, ClassVar, Self

import numpy as np

from reimpl.common._pybind_text import incompatible_arguments

__all__ = ["Field", "Struct", "as_vector", "optional_of", "str_list", "string", "vector"]

Check = Callable[[object], bool]


def string(value: object) -> bool:
    """pybind11's ``str`` caster: a str, or bytes (decoded as UTF-8)."""
    return isinstance(value, str | bytes)


def str_list(value: object) -> bool:
    """pybind11's ``list[str]`` caster: a list or tuple of strings."""
    return isinstance(value, list | tuple) and all(isinstance(v, str | bytes) for v in value)


def vector(size: int | None) -> Check:
    """pybind11's Eigen vector caster: numbers, ``size`` of them (any number if None)."""

    def check(value: object) -> bool:
        try:
            array = np.asarray(value, dtype=float)
        except (TypeError, ValueError):
            return False
        return array.ndim == 1 and (size is None or array.shape == (size,))

    return check


def as_vector(value: Any) -> np.ndarray:
    return np.array(value, dtype=float)


def optional_of(check: Check) -> Check:
    def optional(value: object) -> bool:
        return value is None or check(value)

    return optional


def _text(value: Any) -> Any:
    """Decodes bytes as pybind11's str caster does."""
    return value.decode() if isinstance(value, bytes) else value


@dataclass(frozen=True)
class Field:
    """One field: its name, its type's name (for pybind11's messages), check and default."""

    name: str
    type_name: str
    check: Check
    default: Callable[[], Any]
    #: the stored value from an accepted one (e.g. bytes -> str, tuple -> list)
    convert: Callable[[Any], Any] = _text


class Struct:
    """A pydrake-bound serializable struct (see the module docstring)."""

    FIELDS: ClassVar[tuple[Field, ...]] = ()
    #: the module and qualified name messages name the class by
    MODULE: ClassVar[str] = ""
    QUALNAME: ClassVar[str] = ""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        if args:
            shown = ", ".join(repr(a) for a in args)
            raise TypeError(
                f"{incompatible_arguments('__init__')}. The following argument types "
                f"are supported:\n    1. {self._owner()}(**kwargs)\n\nInvoked with: {shown}"
            )
        for spec in self.FIELDS:
            object.__setattr__(self, "_" + spec.name, spec.default())
        for name, value in kwargs.items():
            setattr(self, name, value)

    @classmethod
    def _owner(cls) -> str:
        return f"{cls.MODULE}.{cls.QUALNAME or cls.__name__}"

    @classmethod
    def _short_name(cls) -> str:
        """The class's own name, without the classes it is nested in."""
        return (cls.QUALNAME or cls.__name__).rsplit(".", 1)[-1]

    def __setattr__(self, name: str, value: Any) -> None:
        spec = self._field(name)
        if not spec.check(value):
            raise TypeError(
                "(): incompatible function arguments. The following argument types are "
                f"supported:\n    1. (self: {self._owner()}, arg0: {spec.type_name}) -> None\n\n"
                f"Invoked with: {self!r}, {value!r}"
            )
        object.__setattr__(self, "_" + name, spec.convert(value))

    def __getattr__(self, name: str) -> Any:
        # Only reached for names that are not stored: fields are stored as "_<name>".
        if name.startswith("_"):
            raise AttributeError(name)
        value = object.__getattribute__(self, "_" + self._field(name).name)
        if isinstance(value, list | dict):
            return type(value)(value)
        if isinstance(value, np.ndarray):
            view = value.view()
            view.flags.writeable = False
            return view
        return value

    @classmethod
    def _field(cls, name: str) -> Field:
        for spec in cls.FIELDS:
            if spec.name == name:
                return spec
        raise AttributeError(f"'{cls.MODULE}.{cls.__name__}' object has no attribute '{name}'")

    def _values(self) -> list[tuple[str, Any]]:
        return [(spec.name, object.__getattribute__(self, "_" + spec.name)) for spec in self.FIELDS]

    def __repr__(self) -> str:
        fields = ", ".join(f"{name}={_repr(value)}" for name, value in self._values())
        return f"{self._short_name()}({fields})"

    def __copy__(self) -> Self:
        return self.__deepcopy__({})

    def __deepcopy__(self, memo: dict[int, Any]) -> Self:
        clone = type(self).__new__(type(self))
        for name, value in self._values():
            object.__setattr__(clone, "_" + name, copy.deepcopy(value, memo))
        return clone

    def __reduce__(self) -> Any:
        raise TypeError(f"cannot pickle '{self.MODULE}.{self._short_name()}' object")


def _repr(value: Any) -> str:
    """pybind11 prints a struct field with Python's repr (numpy arrays as numpy does)."""
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k!r}: {_repr(v)}" for k, v in value.items()) + "}"
    if isinstance(value, list):
        return "[" + ", ".join(_repr(v) for v in value) + "]"
    return repr(value)
