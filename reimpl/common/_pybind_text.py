"""pybind11's TypeError messages, as the release reimpl follows words them.

Drake up to 1.57 builds its bindings with a pybind11 that says
``<module>.<Class>: No constructor defined!`` and, for a constructor no
overload accepts, ``__init__(): incompatible constructor arguments``; 1.58's
says ``no constructor defined!`` and ``incompatible function arguments``
(the release fact pybind-wording-until-1.57; measured on 1.51.1, 1.57.0 and
1.58.0).
"""

from __future__ import annotations

from reimpl._release import release

__all__ = ["cannot_pickle", "incompatible_arguments", "no_constructor"]

_OLD_PYBIND = release.has("pybind-wording-until-1.57")


def no_constructor(qualified_name: str) -> TypeError:
    """The TypeError of calling a bound class that has no constructor."""
    defined = "No constructor defined!" if _OLD_PYBIND else "no constructor defined!"
    return TypeError(f"{qualified_name}: {defined}")


def cannot_pickle(qualified_name: str) -> TypeError:
    """The TypeError of copying, deep-copying or pickling a bound class that binds none of
    them: pybind11 objects fall back to ``__reduce_ex__``, which refuses (measured on
    pydrake 1.51.1 and 1.58.0 for GeometrySet, CollisionFilterDeclaration and
    CollisionFilterManager: ``copy.copy``, ``copy.deepcopy`` and ``pickle.dumps`` alike)."""
    return TypeError(f"cannot pickle '{qualified_name}' object")


def incompatible_arguments(name: str) -> str:
    """``<name>(): incompatible <constructor|function> arguments`` (no overload accepted)."""
    what = "constructor" if name == "__init__" and _OLD_PYBIND else "function"
    return f"{name}(): incompatible {what} arguments"
