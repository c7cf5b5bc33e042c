"""Scoped names: ``namespace::element``, as the parsers build them.

Every name a model file writes is read relative to the model instance it
appears in: ``join("top::inner", "x") == "top::inner::x"``, and a name that is
itself scoped reaches into nested models, ``join("top", "inner::x")``. An empty
part adds nothing: ``join("", "x") == "x"``.

Drake's ScopedName (since 1.14) keeps names in a canonical form, ``parse``: no
leading or trailing delimiter, no repeated one. The collision filter group
resolver qualifies a name read in a model instance with it (``qualify``), so
``::a`` and ``a::`` in model ``r`` both mean ``r::a`` (measured on pydrake
1.14.0 and 1.51.1; up to 1.13 such a name is an error, see
``_collision_filter_group_resolver``).
"""

from __future__ import annotations

__all__ = ["DELIMITER", "is_scoped", "join", "parse", "qualify", "split"]

DELIMITER = "::"
_REPEATED = DELIMITER * 2


def join(*names: str) -> str:
    """The non-empty ``names`` joined with ``::``."""
    return DELIMITER.join(name for name in names if name)


def split(scoped_name: str) -> tuple[str, str]:
    """``(namespace, element)`` at the last delimiter; the namespace may be empty."""
    namespace, _, element = scoped_name.rpartition(DELIMITER)
    return namespace, element


def is_scoped(name: str) -> bool:
    return DELIMITER in name


def parse(scoped_name: str) -> str:
    """Drake's ScopedName::Parse: trailing, then leading delimiters removed, then each
    repeated delimiter (the rightmost ``::::`` first) collapsed to one."""
    name = scoped_name
    while name.endswith(DELIMITER):
        name = name[: -len(DELIMITER)]
    while name.startswith(DELIMITER):
        name = name[len(DELIMITER) :]
    while (repeat := name.rfind(_REPEATED)) != -1:
        name = name[:repeat] + DELIMITER + name[repeat + len(_REPEATED) :]
    return name


def qualify(scope: str, name: str) -> str:
    """``name`` read in model instance ``scope`` (Drake's FullyQualify): itself in the
    global scope (``scope == ""``), else ``parse(scope + "::" + name)``."""
    return name if not scope else parse(f"{scope}{DELIMITER}{name}")
