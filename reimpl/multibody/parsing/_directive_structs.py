"""The model-directive structs (drake/multibody/parsing/model_directives.h).

A ``ModelDirectives`` holds a list of ``ModelDirective``; each of those holds
exactly one of ``add_model``, ``add_model_instance``, ``add_frame``,
``add_weld``, ``add_collision_filter_group``, ``add_directives``. The fields
are Drake's, in Drake's order (which is the order of their ``repr``), bound as
pydrake binds them (see reimpl.common._struct).

Each struct's ``_problem()`` is the first reason it is invalid (None if valid),
by the table below; ``is_valid(struct)`` is Drake's ``IsValid()``, which logs
that problem as an error on the ``drake`` logger and is then False (measured on
pydrake 1.51.1, 1.57.0 and 1.58.0). Loading a document checks it (see
reimpl.multibody.parsing._directives.checked):

==============================  =================================================
 directive                       valid when
==============================  =================================================
 ModelDirective                  exactly one field is set, and that one is valid
 add_model                       ``file``, then ``name``, non-empty; every
                                 ``default_free_body_pose`` deterministic
 add_model_instance              ``name`` non-empty
 add_frame                       ``name`` non-empty; ``X_PF.base_frame`` given and
                                 non-empty; ``X_PF`` deterministic
 add_weld                        ``parent``, then ``child``, non-empty; ``X_PC``
                                 (if given) has no ``base_frame`` and is
                                 deterministic
 add_collision_filter_group      ``name`` non-empty; ``members`` or
                                 ``member_groups`` non-empty
 add_directives                  ``file`` non-empty
==============================  =================================================
"""

from __future__ import annotations

import logging
from typing import Any

from reimpl.common._struct import Field, Struct, as_vector, optional_of, str_list, string, vector
from reimpl.common.schema import Transform

__all__ = [
    "AddCollisionFilterGroup",
    "AddDirectives",
    "AddFrame",
    "AddModel",
    "AddModelInstance",
    "AddWeld",
    "ModelDirective",
    "ModelDirectives",
    "is_valid",
]

_LOG = logging.getLogger("drake")
_MODULE = "reimpl.multibody.parsing"
_TRANSFORM = "pydrake.common.schema.Transform"


def is_valid(struct: Any) -> bool:
    """Drake's ``IsValid()`` of a directive struct: its first problem is logged."""
    problem: str | None = struct._problem()
    if problem is not None:
        _LOG.error(problem)
    return problem is None


def _str_field(name: str) -> Field:
    return Field(name, "str", string, str)


def _optional_str_field(name: str) -> Field:
    return Field(name, "Optional[str]", optional_of(string), lambda: None)


def _list_field(name: str) -> Field:
    return Field(name, "list[str]", str_list, list, lambda v: [_text(x) for x in v])


def _text(value: Any) -> Any:
    return value.decode() if isinstance(value, bytes) else value


def _instance_of(kind: type) -> Any:
    return lambda value: isinstance(value, kind)


def _dict_of(check: Any) -> Any:
    def is_dict(value: object) -> bool:
        return isinstance(value, dict) and all(
            isinstance(k, str) and check(v) for k, v in value.items()
        )

    return is_dict


class AddWeld(Struct):
    """Welds frame ``child`` to frame ``parent`` at ``X_PC`` (identity if None)."""

    MODULE = _MODULE
    FIELDS = (
        _str_field("parent"),
        _str_field("child"),
        Field(
            "X_PC", f"Optional[{_TRANSFORM}]", optional_of(_instance_of(Transform)), lambda: None
        ),
    )

    def _problem(self) -> str | None:
        if not self.parent:
            return "add_weld: `parent` must be non-empty"
        if not self.child:
            return "add_weld: `child` must be non-empty"
        if self.X_PC is not None:
            if self.X_PC.base_frame is not None:
                return (
                    "add_weld: `X_PC` must not specify a `base_frame`; the pose is always in "
                    "the parent frame."
                )
            if not self.X_PC.IsDeterministic():
                return (
                    "add_weld: `X_PC` must specify a deterministic transform, not a distribution."
                )
        return None


class AddModel(Struct):
    """Adds the models of ``file`` (a URL) as model instance ``name``."""

    MODULE = _MODULE
    FIELDS = (
        _str_field("file"),
        _str_field("name"),
        Field(
            "default_joint_positions",
            "dict[str, numpy.ndarray[numpy.float64[m, 1]]]",
            _dict_of(vector(None)),
            dict,
            lambda value: {k: as_vector(v) for k, v in value.items()},
        ),
        Field(
            "default_free_body_pose",
            f"dict[str, {_TRANSFORM}]",
            _dict_of(_instance_of(Transform)),
            dict,
            dict,
        ),
    )

    def _problem(self) -> str | None:
        if not self.file:
            return "add_model: `file` must be non-empty"
        if not self.name:
            return "add_model: `name` must be non-empty"
        for pose in self.default_free_body_pose.values():
            if not pose.IsDeterministic():
                return (
                    "add_model: `default_free_body_pose` must specify a deterministic "
                    "transform, not a distribution."
                )
        return None


class AddModelInstance(Struct):
    """Adds an empty model instance ``name`` (a namespace for frames)."""

    MODULE = _MODULE
    FIELDS = (_str_field("name"),)

    def _problem(self) -> str | None:
        return None if self.name else "add_model_instance: `name` must be non-empty"


class AddFrame(Struct):
    """Adds a fixed frame ``name`` at ``X_PF`` from frame ``X_PF.base_frame``."""

    MODULE = _MODULE
    FIELDS = (
        _str_field("name"),
        Field("X_PF", _TRANSFORM, _instance_of(Transform), Transform, lambda v: v),
    )

    def _problem(self) -> str | None:
        if not self.name:
            return "add_frame: `name` must be non-empty"
        if not self.X_PF.base_frame:
            return "add_frame: `X_PF.base_frame` must be defined"
        if not self.X_PF.IsDeterministic():
            return "add_frame: `X_PF` must specify a deterministic transform, not a distribution."
        return None


class AddCollisionFilterGroup(Struct):
    """Declares a collision filter group and the groups it ignores."""

    MODULE = _MODULE
    FIELDS = (
        _str_field("name"),
        _list_field("members"),
        _list_field("member_groups"),
        _optional_str_field("model_namespace"),
        _list_field("ignored_collision_filter_groups"),
    )

    def _problem(self) -> str | None:
        if not self.name:
            return "add_collision_filter_group: `name` must be non-empty"
        if not self.members and not self.member_groups:
            return (
                "add_collision_filter_group: at least one of `members` or `member_groups` "
                "must be non-empty"
            )
        return None


class AddDirectives(Struct):
    """Runs the directives of ``file`` in namespace ``model_namespace``."""

    MODULE = _MODULE
    FIELDS = (_str_field("file"), _optional_str_field("model_namespace"))

    def _problem(self) -> str | None:
        return None if self.file else "add_directives: `file` must be non-empty"


#: ModelDirective's fields, in Drake's order, and their structs
DIRECTIVE_KINDS: tuple[tuple[str, type[Struct]], ...] = (
    ("add_model", AddModel),
    ("add_model_instance", AddModelInstance),
    ("add_frame", AddFrame),
    ("add_weld", AddWeld),
    ("add_collision_filter_group", AddCollisionFilterGroup),
    ("add_directives", AddDirectives),
)


class ModelDirective(Struct):
    """One directive: exactly one of its fields is set."""

    MODULE = _MODULE
    FIELDS = tuple(
        Field(
            name,
            f"Optional[pydrake.multibody.parsing.{kind.__name__}]",
            optional_of(_instance_of(kind)),
            lambda: None,
            lambda v: v,
        )
        for name, kind in DIRECTIVE_KINDS
    )

    def _set_fields(self) -> list[tuple[str, Any]]:
        """The (name, struct) of each field that is set."""
        return [(name, value) for name, value in self._values() if value is not None]

    def _problem(self) -> str | None:
        fields = self._set_fields()
        if len(fields) != 1:
            return (
                "directive: Specify one of `add_model`, `add_model_instance`, `add_frame`, "
                "`add_collision_filter_group`, or `add_directives`"
            )
        problem: str | None = fields[0][1]._problem()
        return problem


class ModelDirectives(Struct):
    """A directives document: its ``directives``, run in order."""

    MODULE = _MODULE
    FIELDS = (
        Field(
            "directives",
            "list[pydrake.multibody.parsing.ModelDirective]",
            lambda v: isinstance(v, list | tuple) and all(isinstance(d, ModelDirective) for d in v),
            list,
            list,
        ),
    )

    def _problem(self) -> str | None:
        problems = (directive._problem() for directive in self.directives)
        return next((p for p in problems if p is not None), None)
