"""How ``System.SetDefaultContext`` takes its context, by release.

pydrake binds ``SetDefaultContext`` once, on ``System``, for every system
(SceneGraph, MultibodyPlant, Diagram). Since Drake 1.15 its argument is
named ``context``; up to 1.14 it is the unnamed ``arg0``, so
``SetDefaultContext(context=c)`` is pybind11's "incompatible function
arguments" TypeError and only the positional call binds
(set-default-context-keyword-since-1.15; measured on pydrake 1.14.0 and 1.15.0:
``(self: System, arg0: Context)`` and ``(self: System, context: Context)``).
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any, TypeVar

from reimpl._overload import Overload, Param, dispatch
from reimpl._release import release

__all__ = ["context_argument"]

_Method = TypeVar("_Method", bound=Callable[..., Any])

#: The binding's owner as reimpl names it in the TypeError.
_OWNER = "reimpl.systems.framework.System"


def context_argument(method: _Method) -> _Method:
    """``method(self, context)`` as the release binds it: by keyword ``context`` since
    1.15, else by position only (the keyword call raises pybind11's TypeError)."""
    if release.has("set-default-context-keyword-since-1.15"):
        return method
    # The context's type is checked by the method itself (Drake's context-system check).
    overloads = (
        Overload((Param("arg0", lambda value: True),), lambda self, arg0: method(self, arg0)),
    )

    @functools.wraps(method)
    def positional(self: Any, *args: Any, **kwargs: Any) -> Any:
        return dispatch(_OWNER, method.__name__, overloads, args, kwargs, receiver=self)

    return positional  # type: ignore[return-value]
