"""The errors of ``reimpl.legacy``; each says which rule of the RigidBodyTree era was broken.

They subclass RuntimeError (as the RBT's ``std::runtime_error`` did), except
``MappingInputError``, a ValueError for malformed input to the mappings.
"""

from __future__ import annotations

__all__ = [
    "DuplicateGroupError",
    "LegacyError",
    "LegacyUrdfError",
    "MappingInputError",
    "TooManyGroupsError",
    "UniversalGroupError",
    "UnknownCliqueError",
    "UnknownGroupError",
    "UnknownLinkError",
]


class LegacyError(RuntimeError):
    """The base of every error of a legacy filter representation."""


class TooManyGroupsError(LegacyError):
    """Raised when a group is defined beyond the 128 bits of the mask (bit 0 is the
    universal group, so 127 user groups), or when ``to_groups`` would need more."""


class DuplicateGroupError(LegacyError):
    """Raised when a group name is defined twice in one session (one parse)."""


class UnknownGroupError(LegacyError):
    """Raised when a group that receives members or ignores is not defined (a name
    outside the current session, or a bit never handed out)."""


class UniversalGroupError(LegacyError):
    """Raised when bit 0 is given members or ignores: every element belongs to the
    universal group and the group itself ignores nothing (it may only be ignored)."""


class UnknownCliqueError(LegacyError):
    """Raised when an element is added to a clique id that ``new_clique`` never issued."""


class LegacyUrdfError(LegacyError):
    """Raised when a URDF cannot be read with the RigidBodyTree-era rules: malformed
    XML, a missing required attribute, a duplicate group. The message starts with
    ``<source>:<line>:`` and names the element."""


class UnknownLinkError(LegacyUrdfError):
    """Raised when a ``<member link=...>`` of an unprefixed group names no link of the
    robot (an error then, unlike ignoring an undefined group)."""


class MappingInputError(ValueError):
    """Raised when a mapping gets a pair that is not two distinct known elements, or
    an unknown method name."""
