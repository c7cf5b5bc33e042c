"""The public model-directives functions of ``pydrake.multibody.parsing``.

``LoadModelDirectives(filename)`` and ``LoadModelDirectivesFromString(text)``
read a document into ``ModelDirectives`` (checked: an invalid directive is
SystemExit); ``ProcessModelDirectives`` runs them into a plant through a
Parser, as one parse (one collision-filter resolution), at global scope (the
Parser's model-name prefix is not applied); ``FlattenModelDirectives`` inlines
every ``add_directives``, applying its namespace to the names inside;
``GetScopedFrameByName[Maybe]`` look a frame up by scoped name.
"""

from __future__ import annotations

import os
from typing import Any

from reimpl._overload import Overload, Param, dispatch, instance_of
from reimpl.common._drake_demand import failed_demand
from reimpl.multibody.parsing import _scoped_name as scoped
from reimpl.multibody.parsing._binding import is_path, is_str
from reimpl.multibody.parsing._directive_structs import (
    AddCollisionFilterGroup,
    AddFrame,
    ModelDirective,
    ModelDirectives,
    is_valid,
)
from reimpl.multibody.parsing._directive_yaml import load_directives
from reimpl.multibody.parsing._directives import (
    ModelInstanceInfo,
    checked,
    dmd_join,
    load_model_directives,
    scoped_frame,
    scoped_frame_maybe,
)
from reimpl.multibody.parsing._package_map import PackageMap
from reimpl.multibody.parsing._parser import Parser
from reimpl.multibody.parsing._resolve_uri import UriError, resolve_uri
from reimpl.multibody.plant import MultibodyPlant

__all__ = [
    "FlattenModelDirectives",
    "GetScopedFrameByName",
    "GetScopedFrameByNameMaybe",
    "LoadModelDirectives",
    "LoadModelDirectivesFromString",
    "ModelInstanceInfo",
    "ProcessModelDirectives",
]

_MODULE = "reimpl.multibody.parsing"


def LoadModelDirectives(*args: Any, **kwargs: Any) -> ModelDirectives:
    """The directives of the file ``filename``."""
    overloads = (Overload((Param("filename", is_path),), lambda filename: filename),)
    filename = dispatch(_MODULE, "LoadModelDirectives", overloads, args, kwargs)
    return load_model_directives(os.fspath(filename))


def LoadModelDirectivesFromString(*args: Any, **kwargs: Any) -> ModelDirectives:
    """The directives of the YAML text ``model_directives``."""
    overloads = (Overload((Param("model_directives", is_str),), _same),)
    text = dispatch(_MODULE, "LoadModelDirectivesFromString", overloads, args, kwargs)
    return checked(load_directives(text, "<string>"))


def ProcessModelDirectives(*args: Any, **kwargs: Any) -> list[ModelInstanceInfo]:
    """``(directives, parser)`` or ``(directives, plant, parser=None)``: runs the
    directives into the parser's plant; the models ``add_model`` added."""
    directives = Param("directives", instance_of(ModelDirectives))
    overloads = (
        Overload((directives, Param("parser", instance_of(Parser))), _process),
        Overload(
            (
                directives,
                Param("plant", instance_of(MultibodyPlant)),
                Param("parser", instance_of(Parser), None),
            ),
            lambda directives, plant, parser: _process(directives, parser or Parser(plant=plant)),
        ),
    )
    return dispatch(_MODULE, "ProcessModelDirectives", overloads, args, kwargs)  # type: ignore[no-any-return]


def _process(directives: ModelDirectives, parser: Parser) -> list[ModelInstanceInfo]:
    return parser._process_directives(directives)


def GetScopedFrameByName(*args: Any, **kwargs: Any) -> Any:
    """The frame ``full_name`` names: ``world``, ``instance::frame`` or ``frame``."""
    overloads = (Overload((Param("plant", _is_plant), Param("full_name", is_str)), scoped_frame),)
    return dispatch(_MODULE, "GetScopedFrameByName", overloads, args, kwargs)


def GetScopedFrameByNameMaybe(*args: Any, **kwargs: Any) -> Any:
    """As GetScopedFrameByName, but None where it would raise."""
    overloads = (
        Overload((Param("plant", _is_plant), Param("full_name", is_str)), scoped_frame_maybe),
    )
    return dispatch(_MODULE, "GetScopedFrameByNameMaybe", overloads, args, kwargs)


def _same(model_directives: str) -> str:
    return model_directives


def _is_plant(value: object) -> bool:
    return isinstance(value, MultibodyPlant)


# ---------------------------------------------------------------- flattening
def FlattenModelDirectives(*args: Any, **kwargs: Any) -> ModelDirectives:
    """The directives with every ``add_directives`` replaced by its file's
    directives, their names moved into its namespace (Drake's rules, below)."""
    overloads = (
        Overload(
            (
                Param("directives", instance_of(ModelDirectives)),
                Param("package_map", instance_of(PackageMap)),
            ),
            lambda directives, package_map: _flatten(directives, package_map, ""),
        ),
    )
    return dispatch(_MODULE, "FlattenModelDirectives", overloads, args, kwargs)  # type: ignore[no-any-return]


def _flatten(
    directives: ModelDirectives, package_map: PackageMap, namespace: str
) -> ModelDirectives:
    out: list[ModelDirective] = []
    for directive in directives.directives:
        fields = directive._set_fields()
        if not fields:
            continue
        kind, struct = fields[0]
        if kind == "add_directives":
            try:
                path = resolve_uri(package_map, struct.file, None)
            except UriError as exc:
                raise UriError(f"error: {exc}") from None
            inner = namespace
            if struct.model_namespace is not None:
                inner = dmd_join(namespace, struct.model_namespace)
            out += _flatten(load_model_directives(path), package_map, inner).directives
        else:
            out.append(ModelDirective(**{kind: _FLATTEN[kind](struct, namespace)}))
    return ModelDirectives(directives=out)


def _named(struct: Any, namespace: str, *names: str) -> Any:
    """A copy of ``struct`` with each field in ``names`` moved into ``namespace``."""
    result = struct.__deepcopy__({})
    if namespace:
        for name in names:
            setattr(result, name, dmd_join(namespace, getattr(struct, name)))
    return result


def _flatten_frame(frame: AddFrame, namespace: str) -> AddFrame:
    """An unscoped frame name also takes its base frame's namespace."""
    if not is_valid(frame):
        raise failed_demand("ApplyDirectiveNamespace.valid")
    result = frame.__deepcopy__({})
    if namespace:
        result.name = dmd_join(namespace, frame.name)
        result.X_PF.base_frame = dmd_join(namespace, frame.X_PF.base_frame)
    frame_namespace, element = scoped.split(frame.name)
    if not frame_namespace:
        base_namespace, _ = scoped.split(frame.X_PF.base_frame)
        result.name = dmd_join(namespace, dmd_join(base_namespace, element))
    return result


def _flatten_group(group: AddCollisionFilterGroup, namespace: str) -> AddCollisionFilterGroup:
    """The group's full name is split again into name and ``model_namespace``.

    N.B. As in Drake 1.51.1, ``member_groups`` is dropped when a namespace applies.
    """
    if not namespace:
        return group.__deepcopy__({})
    full = dmd_join(namespace, dmd_join(group.model_namespace or "", group.name))
    full_namespace, element = scoped.split(full)
    return AddCollisionFilterGroup(
        name=element,
        model_namespace=full_namespace or None,
        members=group.members,
        ignored_collision_filter_groups=group.ignored_collision_filter_groups,
    )


_FLATTEN: dict[str, Any] = {
    "add_weld": lambda weld, ns: _named(weld, ns, "parent", "child"),
    "add_model": lambda model, ns: _named(model, ns, "name"),
    "add_model_instance": lambda instance, ns: _named(instance, ns, "name"),
    "add_frame": _flatten_frame,
    "add_collision_filter_group": _flatten_group,
}
