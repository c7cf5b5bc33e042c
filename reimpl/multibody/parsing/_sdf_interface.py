"""Drake's custom parsers for SDFormat ``<include>``s of URDF files (libsdformat's Interface API).

While libsdformat builds a model (or world) holding ``<include>`` of a
``.urdf`` (any case), Drake parses that file into the plant at once, before
any model of the SDFormat document is added (measured on pydrake 1.51.1: the
URDF's model instance comes first). Then it tells libsdformat what the URDF
made, so SDFormat names and poses can refer to it:

* the instance is ``<absolute parent>::<name>``, ``<name>`` the include's
  ``<name>`` or the robot's; the absolute parent is the chain of the
  include's enclosing model names, merged models skipped (a world's include
  has none; the Parser's model-name prefix is not applied);
* with ``merge="true"`` the URDF is added to the enclosing model's instance
  (made now if it does not exist yet), and its model frame is
  ``_merged__<name>__model__``;
* its first body holds a new frame ``__model__`` (or the merged frame name);
* links are its new bodies (pose in the model frame), frames its new named
  frames other than bodies' and the model frame (attached to their body),
  joints its new joints (child body, pose on the child).

MuJoCo ``.xml`` files are taken the same way (``_mjcf``; the model name is
the include's ``<name>`` or ``<mujoco model>``).

Errors: ``//include/static`` is refused; a model with no link (body) is
``Model must have at least one link.``. Other files (``.dmd.yaml``, …) are
dropped silently.

A custom file whose parse reports a warning is dropped too, its bodies left in
the plant: Drake hands its warnings to libsdformat as errors, and libsdformat
then leaves the interface model out (``warned``). So SDFormat names cannot
refer to it, it is not a link of the enclosing model (which, with nothing
else, is ``A model must have at least one link.``), and up to 1.22 its
``merge="true"`` is not refused. Measured on pydrake 1.12.0, 1.16.0, 1.22.0,
1.23.0, 1.24.0, 1.25.0, 1.51.1 and 1.58.0 with a URDF ``<robot version>`` and
a MuJoCo ``<compiler fitaabb>`` (unsupported attributes), included and
merge-included.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any

from reimpl._release import release
from reimpl.math import RigidTransform
from reimpl.multibody import kinematics
from reimpl.multibody.parsing import _scoped_name as scoped
from reimpl.multibody.parsing._diagnostics import Diagnostics, recorded_warnings
from reimpl.multibody.parsing._parse_context import ParseContext
from reimpl.multibody.parsing._sdf_graph import GFrame, GJoint, GLink, GModel
from reimpl.multibody.parsing._sdf_poses import GzPose
from reimpl.multibody.tree import FixedOffsetFrame

__all__ = ["InterfaceModel", "is_custom_file", "load_interface_model", "merged_frame_name"]


def merged_frame_name(model_name: str) -> str:
    """libsdformat's computeMergedModelProxyFrameName."""
    return f"_merged__{model_name}__model__"


#: The files Drake's custom parsers take from an SDFormat <include> (any case): MuJoCo
#: ``.xml`` since 1.23 (sdf-include-mjcf-since-1.23: Drake's detail_sdf_parser.cc has no
#: .xml case before v1.23.0; measured with top_merge_include.sdf on pydrake 1.16.0,
#: 1.20.0 and 1.22.0, whose arm.xml model stays empty).
_CUSTOM_SUFFIXES = (".urdf", ".xml") if release.has("sdf-include-mjcf-since-1.23") else (".urdf",)


def is_custom_file(path: str) -> bool:
    """Whether Drake's custom parsers take the file (``.urdf`` or ``.xml``, any case)."""
    return path.lower().endswith(_CUSTOM_SUFFIXES)


def _gz(X: RigidTransform) -> GzPose:
    """Drake's ToIgnitionPose3d: the quaternion of the rotation, and the translation."""
    w, x, y, z = kinematics.quaternion_from_rotation(X.rotation().matrix())
    p = X.translation()
    return GzPose((float(w), float(x), float(y), float(z)), (float(p[0]), float(p[1]), float(p[2])))


@dataclass
class InterfaceModel:
    """What a custom-parsed include made, as libsdformat sees it."""

    name: str
    instance: Any
    merged: bool
    canonical_link: str
    #: X_PM: the model frame in the parent frame (the include's pose, when given, replaces it)
    X_PM: GzPose
    links: list[GLink] = field(default_factory=list)
    frames: list[GFrame] = field(default_factory=list)
    joints: list[GJoint] = field(default_factory=list)
    #: the include's ``<pose>`` (relative_to, X), ``<placement_frame>``
    include_pose: tuple[str, GzPose] | None = None
    placement_frame: str = ""
    #: whether its parse reported a warning (then libsdformat leaves it out)
    warned: bool = False

    @property
    def model_frame(self) -> str:
        return merged_frame_name(self.name) if self.merged else "__model__"

    def graph_model(self) -> GModel:
        """The interface model as a nested model of the graphs (not merged)."""
        relative_to, X = self.include_pose if self.include_pose else ("", self.X_PM)
        return GModel(
            name=self.name,
            pose=X,
            relative_to=relative_to,
            canonical_link=self.canonical_link,
            placement_frame=self.placement_frame,
            kind="Interface Model",
            links=list(self.links),
            frames=list(self.frames),
            joints=list(self.joints),
        )


@dataclass
class _MergingContext(ParseContext):
    """A parse context whose new model instance is an existing one (Drake's MergeModel)."""

    target: Any = None
    requested: str = ""

    def add_model_instance(self, name: str) -> Any:
        self.requested = name
        return self.target


def load_interface_model(
    context: ParseContext,
    path: str,
    *,
    local_name: str | None,
    parent_name: str | None,
    merge: bool,
    static: bool,
) -> InterfaceModel:
    """Parses the custom file at ``path`` into the plant (Drake's ParseNestedInterfaceModel)."""
    if static:
        raise Diagnostics(None).error(
            "Drake does not yet support //include/static for custom nesting."
        )
    plant = context.plant
    if merge:
        target_name = parent_name or ""
        if plant.HasModelInstanceNamed(target_name):
            instance = plant.GetModelInstanceByName(target_name)
        else:
            instance = plant.AddModelInstance(target_name)
        before = _snapshot(plant, instance)
        fields = {f.name: getattr(context, f.name) for f in dataclasses.fields(ParseContext)}
        merging = _MergingContext(**fields, target=instance)
        with recorded_warnings() as warnings:
            context.read_file(merging, path, local_name, "")
        name = merging.requested
    else:
        with recorded_warnings() as warnings:
            instance = context.read_file(context, path, local_name, parent_name or "")[0]
        name = scoped.split(plant.GetModelInstanceName(instance))[1]
        before = ([], [], [])
    bodies = plant.GetBodyIndices(instance)
    if not bodies:
        raise Diagnostics(None).error("Model must have at least one link.")
    model = InterfaceModel(name, instance, merge, "", GzPose(), warned=bool(warnings))
    canonical = plant.get_body(bodies[0])
    plant.AddFrame(
        FixedOffsetFrame(model.model_frame, canonical.body_frame(), RigidTransform(), instance)
    )
    _describe(plant, model, before)
    return model


def _snapshot(plant: Any, instance: Any) -> tuple[list[Any], list[Any], list[Any]]:
    return (
        list(plant.GetBodyIndices(instance)),
        list(plant.GetFrameIndices(instance)),
        list(plant.GetJointIndices(instance)),
    )


def _describe(
    plant: Any, model: InterfaceModel, before: tuple[list[Any], list[Any], list[Any]]
) -> None:
    """ConvertToInterfaceModel: the new bodies, frames and joints, in the model frame."""
    instance = model.instance
    bodies, frames, joints = (
        [index for index in now if index not in set(old)]
        for now, old in zip(_snapshot(plant, instance), before, strict=True)
    )
    model_frame = plant.GetFrameByName(model.model_frame, instance)
    model.canonical_link = model_frame.body().name()
    X_WM = plant.GetDefaultFloatingBaseBodyPose(model_frame.body()).multiply(
        model_frame.GetFixedPoseInBodyFrame()
    )
    model.X_PM = _gz(X_WM)
    X_MW = X_WM.inverse()
    for index in bodies:
        body = plant.get_body(index)
        X_ML = X_MW.multiply(plant.GetDefaultFloatingBaseBodyPose(body))
        model.links.append(GLink(body.name(), _gz(X_ML), "__model__", "Interface Link"))
    for index in frames:
        frame = plant.get_frame(index)
        name = frame.name()
        if frame.model_instance() != instance or not name or name == model.model_frame:
            continue
        if plant.HasBodyNamed(name, instance):
            continue
        attached_to = frame.body().name()
        X = _gz(frame.GetFixedPoseInBodyFrame())
        model.frames.append(GFrame(name, X, attached_to, attached_to, "Interface Frame"))
    for index in joints:
        joint = plant.get_joint(index)
        X_CJ = _gz(joint.frame_on_child().GetFixedPoseInBodyFrame())
        child = joint.child_body().name()
        model.joints.append(GJoint(joint.name(), child, X_CJ, child, "Interface Joint"))
