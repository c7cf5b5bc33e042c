"""Running model directives into a plant (Drake's detail_dmd_parser.cc, 1.51.1).

Directives run in order, in a *namespace*: the Parser's model-name prefix at
the top, ``ns::model_namespace`` inside ``add_directives``. A name a directive
writes is read in the namespace, ``join(ns, name)``, except ``world`` which is
always the world frame. A frame name ``a::b::f`` is frame ``f`` of model
instance ``a::b`` (GetModelInstanceByName's error if there is none); an
unscoped ``f`` is searched plant-wide (GetFrameByName's errors).

===========================  ====================================================
 directive                    effect
===========================  ====================================================
 add_model                    the single model of ``file`` (a URL, never
                              relative) as instance ``join(ns, name)``; then its
                              ``default_joint_positions`` and
                              ``default_free_body_pose``
 add_model_instance           an empty instance ``join(ns, name)`` (auto-renamed
                              if the Parser auto-renames); not returned
 add_frame                    FixedOffsetFrame at ``X_PF`` from ``X_PF.base_frame``,
                              in instance ``join(ns, a)`` when the name is
                              ``a::f``, else in the base frame's instance
 add_weld                     WeldFrames(parent, child, ``X_PC``); the *child* is
                              looked up first (its errors come first, as GCC
                              evaluates Drake's arguments right to left); the
                              child must be in an instance this document added
                              (else SystemExit, ``condition 'found' failed``)
 add_collision_filter_group   with a SceneGraph only: a group read in instance
                              ``ns`` if ``ns`` is not empty, else in
                              ``model_namespace`` if given, else at global scope
 add_directives               ``file``'s directives in ``join(ns,
                              model_namespace)``, which must be an existing
                              model instance (else RuntimeError ``Namespace
                              ... does not exist``, since 1.58 ``error: ...``)
===========================  ====================================================

Errors from URIs, groups and default poses carry no source (``error: ...``).
Each ``add_model`` yields a ``ModelInstanceInfo`` (see _model_directives);
the welds fill in the parent and child frame names and ``X_PC``.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from reimpl._release import release
from reimpl.common._drake_demand import failed_demand
from reimpl.common._pybind_text import no_constructor
from reimpl.math import RigidTransform
from reimpl.multibody.parsing import _scoped_name as scoped
from reimpl.multibody.parsing._diagnostics import Diagnostics
from reimpl.multibody.parsing._directive_structs import (
    AddCollisionFilterGroup,
    AddDirectives,
    AddFrame,
    AddModel,
    AddModelInstance,
    AddWeld,
    ModelDirectives,
    is_valid,
)
from reimpl.multibody.parsing._directive_yaml import load_directives
from reimpl.multibody.parsing._parse_context import ModelSource, ParseContext
from reimpl.multibody.parsing._resolve_uri import UriError, resolve_uri
from reimpl.multibody.tree import FixedOffsetFrame, QuaternionFloatingJoint

__all__ = [
    "ModelInstanceInfo",
    "load_model_directives",
    "process_directives",
    "read_directives",
    "scoped_frame",
    "scoped_frame_maybe",
]


class ModelInstanceInfo:
    """What one ``add_model`` added, and where a weld attached it.

    N.B. As in pydrake, it cannot be constructed from Python and its fields are
    read-only.
    """

    X_PC: Any
    child_frame_name: str
    model_instance: Any
    model_name: str
    model_path: str
    parent_frame_name: str
    __slots__ = (
        "X_PC",
        "child_frame_name",
        "model_instance",
        "model_name",
        "model_path",
        "parent_frame_name",
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        raise no_constructor("reimpl.multibody.parsing.ModelInstanceInfo")

    @classmethod
    def _make(cls, model_instance: Any, model_name: str, model_path: str) -> ModelInstanceInfo:
        info = cls.__new__(cls)
        for name, value in (
            ("model_instance", model_instance),
            ("model_name", model_name),
            ("model_path", model_path),
            ("parent_frame_name", ""),
            ("child_frame_name", ""),
            ("X_PC", RigidTransform()),
        ):
            object.__setattr__(info, name, value)
        return info

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError(f"property of '{type(self).__name__}' object has no setter")


def scoped_frame(plant: Any, full_name: str) -> Any:
    """Drake's ``GetScopedFrameByName``: ``world``, ``instance::frame`` or ``frame``."""
    if full_name == "world":
        return plant.world_frame()
    namespace, element = scoped.split(full_name)
    if namespace:
        return plant.GetFrameByName(element, plant.GetModelInstanceByName(namespace))
    return plant.GetFrameByName(element)


def scoped_frame_maybe(plant: Any, full_name: str) -> Any:
    """Drake's ``GetScopedFrameByNameMaybe``: the frame, or None."""
    if full_name == "world":
        return plant.world_frame()
    namespace, element = scoped.split(full_name)
    if namespace:
        if plant.HasModelInstanceNamed(namespace):
            instance = plant.GetModelInstanceByName(namespace)
            if plant.HasFrameNamed(element, instance):
                return plant.GetFrameByName(element, instance)
    elif plant.HasFrameNamed(element):
        return plant.GetFrameByName(element)
    return None


def dmd_join(namespace: str, name: str) -> str:
    """Drake's ``DmdScopedNameJoin``: ``world`` stays ``world``."""
    return name if name == "world" else scoped.join(namespace, name)


def load_model_directives(path: str) -> ModelDirectives:
    """Drake's ``LoadModelDirectives`` of a file: read, then checked (SystemExit)."""
    if not os.path.exists(path):
        raise RuntimeError(f"No such file {path} during LoadModelDirectives")
    with open(path, encoding="utf-8") as stream:
        return checked(load_directives(stream.read(), path))


def checked(directives: ModelDirectives) -> ModelDirectives:
    """``directives``, which must be valid: their first problem (see _directive_structs)
    is the error ``error: <problem>`` (ModelParseError, not logged) since Drake 1.58;
    up to 1.57 it is logged and then Drake's DRAKE_THROW_UNLESS(IsValid()) fails
    (SystemExit). Measured on pydrake 1.51.1 and 1.52.0 to 1.58.0."""
    if release.has("directives-invalid-error-since-1.58"):
        problem = directives._problem()
        if problem is not None:
            raise Diagnostics(None).error(problem)
    elif not is_valid(directives):
        raise failed_demand("LoadModelDirectives.valid")
    return directives


@dataclass
class _Run:
    """One ``ParseModelDirectives`` call: the context and the models it added."""

    context: ParseContext
    added: list[ModelInstanceInfo] = field(default_factory=list)

    @property
    def plant(self) -> Any:
        return self.context.plant

    @property
    def diagnostics(self) -> Diagnostics:
        return Diagnostics(None, self.context.strict)

    def resolve(self, uri: str) -> str:
        try:
            return resolve_uri(self.context.package_map, uri, None, warn=self.diagnostics.warning)
        except UriError as exc:
            raise self.diagnostics.error(str(exc)) from None

    def frame(self, namespace: str, name: str) -> Any:
        return scoped_frame(self.plant, dmd_join(namespace, name))

    def run(self, directives: ModelDirectives, namespace: str) -> None:
        for directive in directives.directives:
            ((kind, struct),) = directive._set_fields()[:1] or (("", None),)
            if struct is not None:
                getattr(self, kind)(struct, namespace)

    # ----------------------------------------------------------- directives
    def add_model(self, model: AddModel, namespace: str) -> None:
        path = self.resolve(model.file)
        if path.lower().endswith(".dmd.yaml"):
            raise self.diagnostics.error(
                f"'{os.path.abspath(path)}' is a model directives data source; it is always "
                "an error to pass a model directives source to a single-model parser method. "
                "Use AddModels() instead."
            )
        # N.B. The readers take a name without "::": "a::m" in ns is m in scope ns::a.
        scope, name = scoped.split(scoped.join(namespace, model.name))
        instances = self.context.read_file(self.context, path, name, scope)
        instance = instances[0]
        for joint_name, positions in model.default_joint_positions.items():
            self._default_positions(self.plant.GetJointByName(joint_name, instance), positions)
        for child_name, pose in model.default_free_body_pose.items():
            base = pose.base_frame if pose.base_frame is not None else "world"
            parent = self.plant.world_frame() if base == "world" else self.frame(namespace, base)
            self._default_pose(instance, parent, child_name, pose.GetDeterministicValue())
        info = ModelInstanceInfo._make(instance, scoped.join(namespace, model.name), path)
        self.added.append(info)

    def _default_positions(self, joint: Any, positions: Any) -> None:
        """Joint::set_default_positions, with Drake's message for a wrong size."""
        if len(positions) != joint.num_positions():
            instance = self.plant.GetModelInstanceName(joint.model_instance())
            name = scoped.join(instance, joint.name())
            raise RuntimeError(
                f"set_default_positions: The number of positions in the input "
                f"({len(positions)}) does not match the number of positions of the joint "
                f"'{name}' ({joint.num_positions()})."
            )
        joint.set_default_positions(positions)

    def _default_pose(self, instance: Any, parent: Any, child_name: str, X_PC: Any) -> None:
        """Poses body ``child_name`` (the instance's only body if empty, since 1.33) at X_PC."""
        plant = self.plant
        if not release.has("directives-default-pose-frame-since-1.28"):
            child = plant.GetBodyByName(child_name, instance).body_frame()  # a body's name
        elif child_name or not release.has("directives-default-pose-empty-name-since-1.33"):
            child = plant.GetFrameByName(child_name, instance)  # up to 1.32, '' too
        else:
            bodies = plant.GetBodyIndices(instance)
            if len(bodies) != 1:
                raise self.diagnostics.error(
                    f"Model instance '{plant.GetModelInstanceName(instance)}' cannot use an "
                    "empty frame name for its default_free_body_pose in add_model because it "
                    f"has {len(bodies)} (not 1) bodies."
                )
            child = plant.get_body(bodies[0]).body_frame()
        identity = np.array_equal(child.GetFixedPoseInBodyFrame().GetAsMatrix4(), np.eye(4))
        if parent is plant.world_frame() and identity:
            plant.SetDefaultFloatingBaseBodyPose(child.body(), X_PC)
            return
        joint_name = child.body().name()
        while plant.HasJointNamed(joint_name, instance):
            joint_name = "_" + joint_name
        joint = plant.AddJoint(QuaternionFloatingJoint(joint_name, parent, child))
        joint._set_default_pose(X_PC)  # N.B. Drake's Joint::SetDefaultPose.

    def add_model_instance(self, instance: AddModelInstance, namespace: str) -> None:
        self.context.add_model_instance(scoped.join(namespace, instance.name))

    def add_frame(self, frame: AddFrame, namespace: str) -> None:
        base_frame = frame.X_PF.base_frame
        if not base_frame:
            raise RuntimeError("add_frame directive with empty base frame is ambiguous")
        frame_namespace, element = scoped.split(frame.name)
        instance = None
        if frame_namespace:
            instance = self.plant.GetModelInstanceByName(scoped.join(namespace, frame_namespace))
        base = self.frame(namespace, base_frame)
        X_PF = frame.X_PF.GetDeterministicValue()
        if instance is None:
            instance = base.model_instance()
        self.plant.AddFrame(FixedOffsetFrame(element, base, X_PF, instance))

    def add_weld(self, weld: AddWeld, namespace: str) -> None:
        X_PC = weld.X_PC.GetDeterministicValue() if weld.X_PC is not None else RigidTransform()
        # N.B. Drake's arguments are evaluated right to left: the child first.
        child = self.frame(namespace, weld.child)
        parent = self.frame(namespace, weld.parent)
        self.plant.WeldFrames(parent, child, X_PC)
        infos = [i for i in self.added if i.model_instance == child.model_instance()]
        for info in infos:
            object.__setattr__(info, "parent_frame_name", parent.name())
            object.__setattr__(info, "child_frame_name", child.name())
            object.__setattr__(info, "X_PC", X_PC)
        if not infos and release.has("directives-unmatched-weld-error-since-1.58"):
            model = self.plant.GetModelInstanceName(child.model_instance())
            raise self.diagnostics.error(
                f"add_weld: child frame '{child.name()}' (model instance '{model}') does not "
                "match any model added by these directives"
            )
        if not infos:  # up to 1.57: a failed DRAKE_DEMAND
            raise failed_demand("AddWeld.found")

    def add_collision_filter_group(self, group: AddCollisionFilterGroup, namespace: str) -> None:
        if not self.plant.geometry_source_is_registered():
            return
        scope = namespace or group.model_namespace or ""
        if scope:
            scope = self.plant.GetModelInstanceName(self.plant.GetModelInstanceByName(scope))
        resolver = self.context.resolver
        resolver.add_group(
            self.diagnostics,
            None,
            group_name=group.name,
            body_names=set(group.members),
            member_group_names=set(group.member_groups),
            scope=scope,
        )
        for other in group.ignored_collision_filter_groups:
            resolver.add_pair(self.diagnostics, None, group.name, other, scope)

    def add_directives(self, sub: AddDirectives, namespace: str) -> None:
        inner = scoped.join(namespace, sub.model_namespace or "")
        if inner and not self.plant.HasModelInstanceNamed(inner):
            problem = f"Namespace '{inner}' does not exist as model instance"
            # Since 1.58 a parse error ('error: ...'); up to 1.57 a bare RuntimeError.
            if release.has("directives-namespace-error-wording-since-1.58"):
                raise self.diagnostics.error(problem)
            raise RuntimeError(problem)
        path = self.resolve(sub.file)
        self.run(load_model_directives(path), inner)


def process_directives(
    context: ParseContext, directives: ModelDirectives, namespace: str
) -> list[ModelInstanceInfo]:
    """Runs ``directives`` in ``namespace``; the models that ``add_model``s added."""
    run = _Run(context)
    run.run(directives, namespace)
    return run.added


def read_directives(
    context: ParseContext, source: ModelSource, model_name: str | None, parent_scope: str
) -> list[Any]:
    """The Parser's reader of a ``.dmd.yaml`` file or text: the added instances."""
    del model_name  # N.B. A directives document names its own models.
    if source.path is not None:
        directives = load_model_directives(source.path)
    else:
        directives = checked(load_directives(source.text, "<string>"))
    infos = process_directives(context, directives, parent_scope)
    return [info.model_instance for info in infos]
