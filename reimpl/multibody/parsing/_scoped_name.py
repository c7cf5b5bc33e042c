"""Scoped names: ``namespace::element``, as the parsers build them.

Every name a model file writes is read relative to the model instance it
appears in: ``join("top::inner", "x") == "top::inner::x"``, and a name that is
itself scoped reaches into nested models, ``join("top", "inner::x")``. An empty
part adds nothing: ``join("", "x") == "x"``.
"""

from __future__ import annotations

__all__ = ["DELIMITER", "is_scoped", "join", "split"]

DELIMITER = "::"


def join(*names: str) -> str:
    """The non-empty ``names`` joined with ``::``."""
    return DELIMITER.join(name for name in names if name)


def split(scoped_name: str) -> tuple[str, str]:
    """``(namespace, element)`` at the last delimiter; the namespace may be empty."""
    namespace, _, element = scoped_name.rpartition(DELIMITER)
    return namespace, element


def is_scoped(name: str) -> bool:
    return DELIMITER in name
