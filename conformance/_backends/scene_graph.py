"""A backend over any pydrake-compatible API: real pydrake, or reimpl.

The same code drives both, so every run also checks that reimpl is a drop-in:
it calls the API only with Drake's keyword names (``declaration=``,
``set_A=``, ``geometry_set=``, ``filter_id=``), which also catches binding
drift between Drake releases.

Names in commands resolve as follows: ``world`` is the world frame;
``@unknown`` is an id this SceneGraph never issued; ``@foreign`` is an id
issued by another SceneGraph; a removed geometry's name still resolves to its
(now stale) id. The model ops (a MultibodyPlant and its parsers) and their
names are ``backends.multibody``'s; the posed scenes and proximity queries
are ``backends.queries``'s.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from functools import partial
from typing import Any

from conformance._backends.api import Api
from conformance._backends.multibody import MultibodyCommands, binding_error, model_features
from conformance._backends.queries import QueryCommands
from conformance._grammar import FEATURE_BINDINGS, GRAMMAR, release_features
from conformance._policy.guards import GUARDS, armed_guards
from conformance._policy.release_facts import fact_holds
from conformance.protocol import (
    MODEL,
    Command,
    ErrorInfo,
    ErrorKind,
    LocationState,
    Observation,
    Pair,
    Result,
    UnknownNameError,
    classify_assertion,
    classify_error,
    normalise_message,
    sample_pairs,
)

__all__ = [
    "BASE_FEATURES",
    "Api",
    "RefusedCallError",
    "SceneGraphBackend",
    "UnknownNameError",
]

WORLD = "world"
UNKNOWN = "@unknown"
FOREIGN = "@foreign"
DEFAULT_SOURCE = "source"

#: What an implementation raises for a call it rejects (IndexError: pybind11's
#: std::out_of_range). Anything else is a broken backend, not a Result.
_IMPLEMENTATION_ERRORS = (RuntimeError, TypeError, ValueError, IndexError)

#: Feature tags every SceneGraph-based backend supports on every release.
BASE_FEATURES = frozenset({"core", "transient", "contexts", "errors", "roles", "quirk", "queries"})
#: SceneGraph feature tags that some releases lack (``grammar.FEATURE_BINDINGS``).
_RELEASED_FEATURES = frozenset({"activation", "scope", "gltf_meshes"})


#: The roles whose geometries ``LocationState.counts`` counts.
_COUNTED_ROLES = ("proximity", "illustration", "perception")


#: The ``LocationState.counts`` key that holds GetCollisionCandidates' error, if it raised.
CANDIDATES_ERROR = "GetCollisionCandidates"


def _answer(read: Callable[[], Any]) -> Any:
    """``read()``, or ``"error: <normalised message>"`` if the implementation rejects it."""
    try:
        return read()
    except _IMPLEMENTATION_ERRORS as exc:
        return f"error: {classify_error(exc).message}"


def _count(read: Callable[[], Any]) -> int:
    return int(read())


class RefusedCallError(Exception):
    """Raised (and reported as ErrorKind.REFUSED) for a call the harness will not make."""


@dataclass
class _Label:
    filter_id: Any
    location: str


class SceneGraphBackend(QueryCommands, MultibodyCommands):
    """Executes scenario commands on ``api.geometry.SceneGraph`` (the model commands on a
    MultibodyPlant registered with it: ``MultibodyCommands``; the poses and proximity
    queries: ``QueryCommands``)."""

    def __init__(self, api: Api) -> None:
        self.api = api
        self.name = api.name
        #: The release guards armed for the current run (``policy.guards``).
        self.armed: frozenset[str] = armed_guards([api.version])
        #: The binding rows (``CommandSpec.binding``) that hold for its release.
        self._bound = frozenset(
            op.binding
            for op in GRAMMAR.values()
            if op.binding is not None and fact_holds(op.binding, api.version)
        )
        self.reset()

    def arm_guards(self, ids: frozenset[str]) -> None:
        """Arms the release guards ``ids`` (the run's backends need them)."""
        self.armed = ids

    # ------------------------------------------------------------ protocol
    def version(self) -> str:
        return self.api.version

    def features(self) -> frozenset[str]:
        """The base tags, the model tags its modules allow, and the tags its release has: the
        release table decides (``grammar.FEATURE_BINDINGS``), not the api's attributes."""
        released = release_features(self.version()) & _RELEASED_FEATURES
        assert FEATURE_BINDINGS.keys() >= _RELEASED_FEATURES
        return BASE_FEATURES | released | model_features(self.api)

    def reset(self) -> None:
        g = self.api.geometry
        self.scene_graph = g.SceneGraph()
        self.sources: dict[str, Any] = {}
        self.frames: dict[str, Any] = {WORLD: self.scene_graph.world_frame_id()}
        self.geometries: dict[str, Any] = {}
        self.names_by_value: dict[int, str] = {}
        self.contexts: dict[str, Any] = {}
        self.labels: dict[str, _Label] = {}
        self._unknown: dict[str, Any] = {}
        self._foreign: dict[str, Any] = {}
        self._reset_models()
        self._reset_queries()

    def execute(self, command: Command) -> Result:
        op = GRAMMAR.get(command.op)
        if op is None or op.handler is None:
            raise UnknownNameError("command", command.op)
        handler: Callable[[Mapping[str, Any]], Any] = getattr(self, op.handler)
        try:
            if op.binding is not None and op.binding not in self._bound:
                raise binding_error(self.api, op.binding)
            return Result(value=handler(command.args))
        except UnknownNameError:
            raise
        except RefusedCallError as exc:
            return Result(error=ErrorInfo(ErrorKind.REFUSED, str(exc)))
        except _IMPLEMENTATION_ERRORS as exc:
            return Result(error=classify_error(exc))
        except SystemExit as exc:  # a failed DRAKE_DEMAND is an answer; any other exit is not
            assertion = classify_assertion(exc)
            if assertion is None:
                raise
            return Result(error=assertion)

    def observe(self) -> Observation:
        sample = sample_pairs(list(self.geometries))
        model = replace(self._observe(None, sample), filter_groups=self._filter_groups())
        locations = {MODEL: model}
        for name, context in self.contexts.items():
            locations[name] = self._observe(context, sample)
        return Observation(locations)

    # ------------------------------------------------------------- helpers
    def _require(self, fact: str) -> None:
        """A binding error unless the binding row ``fact`` holds for this backend's release."""
        if not fact_holds(fact, self.version()):
            raise binding_error(self.api, fact)

    def _observe(self, context: Any, sample: Sequence[Pair]) -> LocationState:
        inspector = self._inspector(context)
        manager = self._manager(context)
        counts = self._counts(inspector)
        try:
            pairs = self._candidates(inspector)
        except _IMPLEMENTATION_ERRORS as exc:
            # A failed parse can leave a proximity geometry that never reached the
            # engine; Drake's GetCollisionCandidates then raises (IndexError) and that
            # is the answer to compare, not a broken harness.
            pairs = frozenset()
            counts[CANDIDATES_ERROR] = f"error: {classify_error(exc).message}"
        active = {
            label: bool(manager.IsActive(filter_id=entry.filter_id))
            for label, entry in self.labels.items()
        }
        return LocationState(
            frozenset(pairs),
            bool(manager.has_transient_history()),
            active,
            filtered={pair: self._filtered(inspector, pair) for pair in sample},
            counts=counts,
        )

    def _candidates(self, inspector: Any) -> frozenset[Pair]:
        """GetCollisionCandidates by geometry names, each pair in name order."""
        pairs: set[Pair] = set()
        for a, b in inspector.GetCollisionCandidates():
            na, nb = self.names_by_value[a.get_value()], self.names_by_value[b.get_value()]
            pairs.add((na, nb) if na < nb else (nb, na))
        return frozenset(pairs)

    def _filtered(self, inspector: Any, pair: Pair) -> bool | str:
        """CollisionFiltered of a sampled pair, or ``"error: <message>"``, the message
        normalised after the two ids in it are replaced by their names (so it still says
        which geometry was at fault)."""
        ids = [self.geometries[name] for name in pair]
        try:
            return bool(inspector.CollisionFiltered(geometry_id1=ids[0], geometry_id2=ids[1]))
        except _IMPLEMENTATION_ERRORS as exc:
            message = str(exc).splitlines()[0] if str(exc) else ""
            for name, geometry_id in zip(pair, ids, strict=True):
                message = re.sub(rf"\b{geometry_id.get_value()}\b", name, message)
            return f"error: {normalise_message(message)}"

    def _counts(self, inspector: Any) -> dict[str, int | str]:
        """The inspector's counts (``LocationState.counts``), by key."""
        g = self.api.geometry
        reads: dict[str, Callable[[], Any]] = {
            "sources": inspector.num_sources,
            "frames": inspector.num_frames,
            "geometries": inspector.num_geometries,
            "anchored": inspector.NumAnchoredGeometries,
            "dynamic": inspector.NumDynamicGeometries,
        }
        for role in _COUNTED_ROLES:
            value = self._role(role)
            reads[f"role {role}"] = partial(inspector.NumGeometriesWithRole, role=value)
        proximity = g.Role.kProximity
        for name, frame_id in self.frames.items():
            reads[f"frame {name}"] = partial(inspector.NumGeometriesForFrame, frame_id=frame_id)
            reads[f"frame {name} proximity"] = partial(
                inspector.NumGeometriesForFrameWithRole, frame_id=frame_id, role=proximity
            )
        for name, source_id in self.sources.items():
            reads[f"source {name} frames"] = partial(
                inspector.NumFramesForSource, source_id=source_id
            )
        return {key: _answer(partial(_count, read)) for key, read in reads.items()}

    def _context(self, args: Mapping[str, Any]) -> Any:
        name = args.get("context")
        if name is None or name == MODEL:
            return None
        try:
            return self.contexts[name]
        except KeyError:
            raise UnknownNameError("context", name) from None

    def _inspector(self, context: Any) -> Any:
        if context is None:
            return self.scene_graph.model_inspector()
        return self.scene_graph.get_query_output_port().Eval(context).inspector()

    def _manager(self, context: Any) -> Any:
        # N.B. Always a fresh manager: a model manager held across
        # CreateDefaultContext() goes stale in pydrake >= 1.30.
        if context is None:
            return self.scene_graph.collision_filter_manager()
        return self.scene_graph.collision_filter_manager(context=context)

    def _source(self, args: Mapping[str, Any]) -> Any:
        name = args.get("source", DEFAULT_SOURCE)
        if name not in self.sources:
            if name != DEFAULT_SOURCE:
                raise UnknownNameError("source", name)
            self.sources[name] = self.scene_graph.RegisterSource(name=name)
        return self.sources[name]

    def _foreign_ids(self) -> Mapping[str, Any]:
        if not self._foreign:
            g, m = self.api.geometry, self.api.math
            other = g.SceneGraph()
            source = other.RegisterSource(name="foreign")
            frame = other.RegisterFrame(source_id=source, frame=g.GeometryFrame(frame_name="f"))
            geometry = other.RegisterGeometry(
                source_id=source,
                frame_id=frame,
                geometry=g.GeometryInstance(
                    X_PG=m.RigidTransform(), shape=g.Sphere(radius=1.0), name="foreign"
                ),
            )
            other.AssignRole(
                source_id=source, geometry_id=geometry, properties=g.ProximityProperties()
            )
            self._foreign = {"frame": frame, "geometry": geometry, "scene_graph": other}
        return self._foreign

    def _special(self, kind: str, name: str) -> Any:
        g = self.api.geometry
        if name == FOREIGN:
            return self._foreign_ids()[kind]
        if kind not in self._unknown:
            id_type = g.GeometryId if kind == "geometry" else g.FrameId
            self._unknown[kind] = id_type.get_new_id()
        return self._unknown[kind]

    def _ref(self, kind: str, name: str) -> Any:
        """The id a geometry or frame name stands for (see the module doc)."""
        if name in (UNKNOWN, FOREIGN):
            return self._special(kind, name)
        table = self.geometries if kind == "geometry" else self.frames
        try:
            return table[name]
        except KeyError:
            raise UnknownNameError(kind, name) from None

    def _geometry(self, name: str) -> Any:
        return self._ref("geometry", name)

    def _frame(self, name: str) -> Any:
        return self._ref("frame", name)

    def _label(self, name: str) -> Any:
        if name == UNKNOWN:
            if "filter" not in self._unknown:
                self._unknown["filter"] = self.api.geometry.FilterId.get_new_id()
            return self._unknown["filter"]
        try:
            return self.labels[name].filter_id
        except KeyError:
            raise UnknownNameError("declaration label", name) from None

    def geometry_set(self, spec: Mapping[str, Sequence[str]]) -> Any:
        """``{"geometries": [...], "frames": [...]}`` → GeometrySet (keyword form)."""
        return self.api.geometry.GeometrySet(
            geometry_ids=[self._geometry(n) for n in spec.get("geometries", ())],
            frame_ids=[self._frame(n) for n in spec.get("frames", ())],
        )

    def declaration(self, spec: Mapping[str, Any]) -> Any:
        g = self.api.geometry
        scope = spec.get("scope")
        if scope is None:
            declaration = g.CollisionFilterDeclaration()
        else:
            value = {"all": "kAll", "omit_deformable": "kOmitDeformable"}[scope]
            declaration = g.CollisionFilterDeclaration(scope=getattr(g.CollisionFilterScope, value))
        for statement in spec.get("statements", ()):
            op = statement["op"]
            if op.endswith("_within"):
                method = "ExcludeWithin" if op == "exclude_within" else "AllowWithin"
                result = getattr(declaration, method)(
                    geometry_set=self.geometry_set(statement["set"])
                )
            else:
                method = "ExcludeBetween" if op == "exclude_between" else "AllowBetween"
                result = getattr(declaration, method)(
                    set_A=self.geometry_set(statement["a"]),
                    set_B=self.geometry_set(statement["b"]),
                )
            if result is not declaration:
                raise RuntimeError(f"{method} did not return the declaration itself")
        return declaration

    def _properties(self, role: str) -> Any:
        g = self.api.geometry
        return {
            "proximity": g.ProximityProperties,
            "illustration": g.IllustrationProperties,
            "perception": g.PerceptionProperties,
        }[role]()

    def _role(self, role: str) -> Any:
        g = self.api.geometry
        return {
            "proximity": g.Role.kProximity,
            "illustration": g.Role.kIllustration,
            "perception": g.Role.kPerception,
            "unassigned": g.Role.kUnassigned,
        }[role]

    # ------------------------------------------------------------ commands
    def register_source(self, args: Mapping[str, Any]) -> None:
        self.sources[args["name"]] = self.scene_graph.RegisterSource(name=args["name"])

    def register_frame(self, args: Mapping[str, Any]) -> None:
        g = self.api.geometry
        source = self._source(args)
        frame = g.GeometryFrame(frame_name=args.get("drake_name", args["name"]))
        parent = args.get("parent")
        if parent is None:
            frame_id = self.scene_graph.RegisterFrame(source_id=source, frame=frame)
        else:
            frame_id = self.scene_graph.RegisterFrame(
                source_id=source, parent_id=self._frame(parent), frame=frame
            )
        self.frames[args["name"]] = frame_id

    def register_geometry(self, args: Mapping[str, Any]) -> None:
        g = self.api.geometry
        source = self._source(args)
        name = args["name"]
        instance = g.GeometryInstance(
            X_PG=self.rigid_transform(args.get("pose")),
            shape=self.shape(args.get("shape")),
            name=args.get("drake_name", name),
        )
        frame = args.get("frame", WORLD)
        context = self._context(args)
        if context is not None:
            geometry_id = self.scene_graph.RegisterGeometry(
                context=context, source_id=source, frame_id=self._frame(frame), geometry=instance
            )
        elif frame == WORLD:
            geometry_id = self.scene_graph.RegisterAnchoredGeometry(
                source_id=source, geometry=instance
            )
        else:
            geometry_id = self.scene_graph.RegisterGeometry(
                source_id=source, frame_id=self._frame(frame), geometry=instance
            )
        self.geometries[name] = geometry_id
        self.names_by_value[geometry_id.get_value()] = name
        for role in args.get("roles", ()):
            self.assign_role({**args, "geometry": name, "role": role})

    def assign_role(self, args: Mapping[str, Any]) -> None:
        g = self.api.geometry
        kwargs = {
            "source_id": self._source(args),
            "geometry_id": self._geometry(args["geometry"]),
            "properties": self._properties(args["role"]),
            "assign": g.RoleAssign.kReplace
            if args.get("assign") == "replace"
            else g.RoleAssign.kNew,
        }
        context = self._context(args)
        if context is not None:
            kwargs["context"] = context
        self.scene_graph.AssignRole(**kwargs)

    def remove_role(self, args: Mapping[str, Any]) -> int:
        kwargs: dict[str, Any] = {"source_id": self._source(args), "role": self._role(args["role"])}
        if "frame" in args:
            self._require("remove-role-by-frame-since-1.13")
            kwargs["frame_id"] = self._frame(args["frame"])
        else:
            kwargs["geometry_id"] = self._geometry(args["geometry"])
        context = self._context(args)
        if context is not None:
            kwargs["context"] = context
        return int(self.scene_graph.RemoveRole(**kwargs))

    def remove_geometry(self, args: Mapping[str, Any]) -> None:
        kwargs = {"source_id": self._source(args), "geometry_id": self._geometry(args["geometry"])}
        context = self._context(args)
        if context is not None:
            kwargs["context"] = context
        self.scene_graph.RemoveGeometry(**kwargs)

    def apply(self, args: Mapping[str, Any]) -> None:
        declaration = self.declaration(args["declaration"])
        self._manager(self._context(args)).Apply(declaration=declaration)

    def apply_transient(self, args: Mapping[str, Any]) -> None:
        """ApplyTransient; the label names the FilterId it returns.

        If the call fails, the label names a FilterId that was never issued
        (as ``@unknown`` does), so later steps may still use it.
        """
        location = args.get("context", MODEL)
        try:
            declaration = self.declaration(args["declaration"])
            filter_id = self._manager(self._context(args)).ApplyTransient(declaration=declaration)
        except _IMPLEMENTATION_ERRORS:
            self.labels[args["label"]] = _Label(self.api.geometry.FilterId.get_new_id(), location)
            raise
        self.labels[args["label"]] = _Label(filter_id, location)

    def remove_declaration(self, args: Mapping[str, Any]) -> bool:
        filter_id = self._label(args["label"])
        return bool(self._manager(self._context(args)).RemoveDeclaration(filter_id=filter_id))

    def is_active(self, args: Mapping[str, Any]) -> bool:
        filter_id = self._label(args["label"])
        return bool(self._manager(self._context(args)).IsActive(filter_id=filter_id))

    def has_transient_history(self, args: Mapping[str, Any]) -> bool:
        return bool(self._manager(self._context(args)).has_transient_history())

    def _refuse(self, guard: str) -> None:
        """Raises RefusedCallError if the run armed ``guard`` (``policy.guards``)."""
        if guard in self.armed:
            raise RefusedCallError(GUARDS[guard].message())

    def _refuse_anchored(self, geometry_set: Any, context: Any) -> None:
        """Refuses (de)activation of anchored proximity geometry while its guard is armed.

        N.B. pydrake 1.55-1.58 abort the process in
        ProximityEngine::ApplyActiveStatusChange for anchored geometry (see
        the known divergence "deactivate-anchored-aborts").
        """
        if "deactivate-anchored-aborts" not in self.armed:
            return
        inspector = self._inspector(context)
        try:
            ids = inspector.GetGeometryIds(
                geometry_set=geometry_set, role=self.api.geometry.Role.kProximity
            )
        except RuntimeError:
            return  # Unknown ids: let the implementation report them.
        world = self.scene_graph.world_frame_id()
        if any(inspector.GetFrameId(geometry_id=g) == world for g in ids):
            self._refuse("deactivate-anchored-aborts")

    def activate(self, args: Mapping[str, Any]) -> None:
        context = self._context(args)
        geometry_set = self.geometry_set(args["set"])
        self._refuse_anchored(geometry_set, context)
        self._manager(context).Activate(geometry_set=geometry_set)

    def deactivate(self, args: Mapping[str, Any]) -> None:
        context = self._context(args)
        geometry_set = self.geometry_set(args["set"])
        self._refuse_anchored(geometry_set, context)
        self._manager(context).Deactivate(geometry_set=geometry_set)

    def collision_filtered(self, args: Mapping[str, Any]) -> bool:
        a, b = args["pair"]
        inspector = self._inspector(self._context(args))
        return bool(
            inspector.CollisionFiltered(
                geometry_id1=self._geometry(a), geometry_id2=self._geometry(b)
            )
        )

    def create_context(self, args: Mapping[str, Any]) -> None:
        self.contexts[args["name"]] = self.scene_graph.CreateDefaultContext()

    def clone_context(self, args: Mapping[str, Any]) -> None:
        """Clones a context, after fixing its poses on every source's pose port.

        The poses are those ``set_poses`` stored for it (identity for the
        rest: ``QueryCommands._fix_poses``), and the clone inherits them.

        N.B. pydrake refuses to clone a context whose query port was evaluated
        (the harness observes after every step) unless each source with frames
        has its pose port fixed with one pose per frame. A context made before
        a source was registered lacks that source's port; once SetDefaultContext
        gives it the source's frames, fixing the port or cloning aborts
        pydrake, so the guard "older-context-pose-port-aborts" refuses it.
        """
        source = self._context({"context": args["from"]})
        self._fix_poses(source, args["from"])
        self.contexts[args["name"]] = source.Clone()
        self.poses[args["name"]] = dict(self.poses.get(args["from"], {}))

    def set_default_context(self, args: Mapping[str, Any]) -> None:
        self._require("set-default-context-keyword-since-1.15")
        self.scene_graph.SetDefaultContext(context=self._context(args))
