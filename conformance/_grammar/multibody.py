"""The model commands: a MultibodyPlant on the case's SceneGraph, and the model files it parses.

One row per op, as in ``grammar.scene_graph``; ``backends.multibody`` has one
method per op. The plant is made at the first of these steps:
``MultibodyPlant(time_step=0.0)``, registered as a source of the case's
SceneGraph. They mix freely with the SceneGraph ops, so a case can declare
filters on top of a parsed model, by the scoped names of its bodies
(``m::l1``, a frame) and geometries (``m::l1/Sphere``).

Feature tags (a release fact: ``grammar.FEATURE_BINDINGS``):

==========================  ============================================  ==============
tag                         ops                                           release fact
==========================  ============================================  ==============
``multibody``               bodies, joints, welds, geometry, Finalize     (every one)
``parsing``                 ``add_models`` (URDF, SDFormat, directives)   (every one)
``adjacency_opt_out``       ``set_adjacent_filters``                      ≥ 1.13
``filter_groups_report``    ``collision_filter_groups``                   ≥ 1.31
==========================  ============================================  ==============
"""

from __future__ import annotations

from conformance._grammar.spec import Arg, ArgKind, CommandSpec, Comparison

__all__ = ["JOINT_TYPES", "MODEL_COMMANDS"]

K = ArgKind

#: The joint types of ``add_joint`` (the pydrake class of each is in ``backends.multibody``).
JOINT_TYPES: tuple[str, ...] = tuple(K.JOINT_TYPE.schema["enum"])

_GEOMETRY_ARGS = (
    Arg("name", K.NEW_GEOMETRY, True),
    Arg("body", K.BODY, True),
    Arg("drake_name", K.TEXT),
)

MODEL_COMMANDS: tuple[CommandSpec, ...] = (
    CommandSpec(
        "add_models",
        (
            Arg("text", K.MODEL_TEXT),
            Arg("path", K.PATH),
            Arg("format", K.MODEL_FORMAT),
            Arg("prefix", K.MODEL_INSTANCE),
            Arg("auto_renaming", K.BOOL),
            Arg("files", K.FILES),
            Arg("folder", K.FOLDER),
            Arg("reuse_parser", K.BOOL),
            Arg("packages", K.PACKAGES),
        ),
        "parsing",
        "A new Parser(plant=[, model_name_prefix=]) (with ``reuse_parser``: the last "
        "add_models' Parser, and no ``prefix``): AddModelsFromString(file_contents=, "
        "file_type=) or AddModels(file_name=); ``files`` form the package 'pkg', and each "
        "folder of them holding a package.xml is a package too (PopulateFromFolder(path=) "
        "on the case's folder); with ``folder``, ``path`` is below it and its packages are "
        "added (PopulateFromFolder(path=), replacing default packages of the same name); "
        "``packages`` are added before both (Add(package_name=, package_path=), replacing "
        "a package of the same name); returns the new model instances' names",
        one_of=(("text", "path"),),
        needs=(("text", ("format",)), ("folder", ("path",))),
        domain="model",
        scoped_names=True,
    ),
    CommandSpec(
        "collision_filter_groups",
        (),
        "filter_groups_report",
        "The last add_models Parser's GetCollisionFilterGroups(): returns "
        '{"groups": {name: sorted members}, "pairs": sorted [a, b] lists}',
        binding="filter-groups-report-since-1.31",
        domain="model",
    ),
    CommandSpec(
        "model_inventory",
        (),
        "multibody",
        'What the plant holds, by scoped name: returns {"models", "bodies", '
        '"frames", "joints" ("m::j (type)"), "geometries" '
        '("frame/name: Shape [roles]")}, each a sorted list',
        domain="model",
        compare=Comparison.INVENTORY,
    ),
    CommandSpec(
        "rename_model_instance",
        (Arg("model", K.MODEL_INSTANCE, True), Arg("name", K.MODEL_INSTANCE, True)),
        "multibody",
        "MultibodyPlant.RenameModelInstance(model_instance=GetModelInstanceByName(name=model), "
        "name=name); a parse after it may reuse the old name (Drake issue #21316)",
        binding="rename-model-instance-since-1.20",
        domain="model",
        scoped_names=True,
    ),
    CommandSpec(
        "add_rigid_body",
        (Arg("name", K.NEW_BODY, True), Arg("model", K.MODEL_INSTANCE)),
        "multibody",
        "MultibodyPlant.AddRigidBody in ``model`` (made by AddModelInstance if new; default: "
        "the default model instance); ``name`` is also the body's frame",
        domain="model",
    ),
    CommandSpec(
        "add_joint",
        (
            Arg("name", K.TEXT, True),
            Arg("type", K.JOINT_TYPE, True),
            Arg("parent", K.BODY, True),
            Arg("child", K.BODY, True),
        ),
        "multibody",
        "MultibodyPlant.AddJoint of a new joint of ``type`` between the bodies' frames",
        domain="model",
    ),
    CommandSpec(
        "weld_frames",
        (Arg("parent", K.BODY, True), Arg("child", K.BODY, True)),
        "multibody",
        "MultibodyPlant.WeldFrames of the bodies' frames",
        domain="model",
    ),
    CommandSpec(
        "register_collision_geometry",
        _GEOMETRY_ARGS,
        "multibody",
        "MultibodyPlant.RegisterCollisionGeometry: a sphere on ``body`` (the world body: anchored)",
        domain="model",
    ),
    CommandSpec(
        "register_visual_geometry",
        _GEOMETRY_ARGS,
        "multibody",
        "MultibodyPlant.RegisterVisualGeometry: a sphere on ``body``",
        domain="model",
    ),
    CommandSpec(
        "set_adjacent_filters",
        (Arg("value", K.BOOL, True),),
        "adjacency_opt_out",
        "MultibodyPlant.set_adjacent_bodies_collision_filters",
        binding="adjacent-filters-opt-out-since-1.13",
        domain="model",
    ),
    CommandSpec(
        "finalize",
        (),
        "multibody",
        "MultibodyPlant.Finalize: adjacent bodies and welded subgraphs are filtered",
        domain="model",
    ),
)
