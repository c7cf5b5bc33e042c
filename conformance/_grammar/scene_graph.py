"""The SceneGraph commands: registration, roles, filter declarations, contexts, activation.

One row per op. Each names its arguments with their kinds (``ArgKind``), the
feature tag a backend needs, and, where the call is younger than Drake 1.12,
the release that added it. ``SceneGraphBackend`` has one method per op.
"""

from __future__ import annotations

from conformance._grammar.spec import Arg, ArgKind, CommandSpec

__all__ = ["SCENE_GRAPH_COMMANDS"]

K = ArgKind

_SOURCE = Arg("source", K.SOURCE)
_CONTEXT = Arg("context", K.CONTEXT)

SCENE_GRAPH_COMMANDS: tuple[CommandSpec, ...] = (
    CommandSpec(
        "check",
        (),
        "core",
        "Runs nothing; checks its expectations against the current state.",
        harness_only=True,
    ),
    CommandSpec(
        "register_source", (Arg("name", K.NEW_SOURCE, True),), "core", "SceneGraph.RegisterSource"
    ),
    CommandSpec(
        "register_frame",
        (
            Arg("name", K.NEW_FRAME, True),
            Arg("drake_name", K.TEXT),
            Arg("parent", K.FRAME),
            _SOURCE,
        ),
        "core",
        "SceneGraph.RegisterFrame, under the world or under ``parent``",
    ),
    CommandSpec(
        "register_geometry",
        (
            Arg("name", K.NEW_GEOMETRY, True),
            Arg("drake_name", K.TEXT),
            Arg("frame", K.FRAME, True),
            _SOURCE,
            _CONTEXT,
            Arg("roles", K.ROLES),
            Arg("shape", K.SHAPE),
            Arg("pose", K.POSE),
        ),
        "core",
        "RegisterGeometry (RegisterAnchoredGeometry on the world frame) of a GeometryInstance("
        "X_PG=pose, shape=shape (default: a sphere of radius 0.1)), then AssignRole per role",
    ),
    CommandSpec(
        "assign_role",
        (
            Arg("geometry", K.GEOMETRY, True),
            Arg("role", K.ROLE, True),
            Arg("assign", K.ASSIGN),
            _SOURCE,
            _CONTEXT,
        ),
        "roles",
        "SceneGraph.AssignRole with empty properties (RoleAssign.kNew or kReplace)",
    ),
    CommandSpec(
        "remove_role",
        (
            Arg("geometry", K.GEOMETRY),
            Arg("frame", K.FRAME),
            Arg("role", K.ANY_ROLE, True),
            _SOURCE,
            _CONTEXT,
        ),
        "roles",
        "SceneGraph.RemoveRole of one geometry, or of every geometry on a frame; returns a count",
        one_of=(("geometry", "frame"),),
    ),
    CommandSpec(
        "remove_geometry",
        (Arg("geometry", K.GEOMETRY, True), _SOURCE, _CONTEXT),
        "core",
        "SceneGraph.RemoveGeometry",
    ),
    CommandSpec(
        "apply",
        (Arg("declaration", K.DECLARATION, True), _CONTEXT),
        "core",
        "CollisionFilterManager.Apply (persistent)",
    ),
    CommandSpec(
        "apply_transient",
        (Arg("declaration", K.DECLARATION, True), Arg("label", K.NEW_LABEL, True), _CONTEXT),
        "transient",
        "CollisionFilterManager.ApplyTransient; ``label`` names the FilterId it returns",
    ),
    CommandSpec(
        "remove_declaration",
        (Arg("label", K.LABEL, True), _CONTEXT),
        "transient",
        "CollisionFilterManager.RemoveDeclaration; returns a bool",
    ),
    CommandSpec(
        "is_active",
        (Arg("label", K.LABEL, True), _CONTEXT),
        "transient",
        "CollisionFilterManager.IsActive; returns a bool",
    ),
    CommandSpec(
        "has_transient_history",
        (_CONTEXT,),
        "transient",
        "CollisionFilterManager.has_transient_history; returns a bool",
    ),
    CommandSpec(
        "activate",
        (Arg("set", K.SET, True), _CONTEXT),
        "activation",
        "CollisionFilterManager.Activate",
        binding="activation-since-1.55",
    ),
    CommandSpec(
        "deactivate",
        (Arg("set", K.SET, True), _CONTEXT),
        "activation",
        "CollisionFilterManager.Deactivate",
        binding="activation-since-1.55",
    ),
    CommandSpec(
        "collision_filtered",
        (Arg("pair", K.PAIR, True), _CONTEXT),
        "core",
        "SceneGraphInspector.CollisionFiltered; returns a bool",
    ),
    CommandSpec(
        "create_context",
        (Arg("name", K.NEW_CONTEXT, True),),
        "contexts",
        "SceneGraph.CreateDefaultContext",
    ),
    CommandSpec(
        "clone_context",
        (Arg("name", K.NEW_CONTEXT, True), Arg("from", K.CONTEXT, True)),
        "contexts",
        "Context.Clone, after fixing identity poses on every source's pose port",
    ),
    CommandSpec(
        "set_default_context",
        (Arg("context", K.CONTEXT, True),),
        "contexts",
        "SceneGraph.SetDefaultContext",
    ),
)
