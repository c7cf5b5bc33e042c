"""The query commands of ``grammar.queries``: posed scenes and QueryObject queries, one method
per op.

``QueryCommands`` is a mixin of ``SceneGraphBackend``. It keeps, per location
(``model`` or a context name), the poses ``set_poses`` stored: frame id
value → ``X_PF``. Before each query at a location it fixes, on every
source with frames (the plant's too), a ``FramePoseVector`` holding each
frame's stored pose (identity if none), then evaluates the query output
port; at the model each query uses a fresh ``CreateDefaultContext()``.
SceneGraph then composes ``X_WF = X_WP · X_PF`` and ``X_WG = X_WF · X_FG``.

N.B. A QueryObject refers to the context it was evaluated on (pydrake
segfaults if it outlives it): ``_posed`` returns both, and every handler
holds the context until its result is plain JSON.

Results name geometries, never ids, and each pair is sorted: where Drake's
``id_A`` has the larger name, the record swaps ``p_WCa`` ↔ ``p_WCb`` (or
``p_ACa`` ↔ ``p_BCb``) and negates ``nhat_BA_W``, which is the same contact
seen from the other side (the normal points from B into A).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping
from typing import TYPE_CHECKING, Any

from conformance._grammar.queries import (
    DEFAULT_SHAPE,
    MESH_SHAPES,
    SHAPE_OF_CLASS,
    SHAPES,
    mesh_root,
)
from conformance.protocol import MODEL

if TYPE_CHECKING:
    from conformance._backends.api import Api

__all__ = ["QueryCommands"]

#: Record fields swapped when a pair is put in name order (the normal is negated).
_SWAPPED = (("p_WCa", "p_WCb"), ("p_ACa", "p_BCb"))
_NORMAL = "nhat_BA_W"


def _vector(value: Iterable[Any]) -> list[float]:
    return [float(x) for x in value]


def _pose_json(X: Any) -> dict[str, Any]:
    """``{"xyz": p, "rotation": R}`` of a RigidTransform (R by rows)."""
    return {
        "xyz": _vector(X.translation()),
        "rotation": [_vector(row) for row in X.rotation().matrix()],
    }


def _in_name_order(record: dict[str, Any]) -> dict[str, Any]:
    """``record`` with its pair sorted by name (see the module doc)."""
    a, b = record["pair"]
    if a <= b:
        return record
    swapped = {**record, "pair": [b, a], "shapes": record["shapes"][::-1]}
    for first, second in _SWAPPED:
        if first in record:
            swapped[first], swapped[second] = record[second], record[first]
    swapped[_NORMAL] = [-x for x in record[_NORMAL]]
    return swapped


class QueryCommands:
    """The query ops (see the module doc); mixed into ``SceneGraphBackend``."""

    # Provided by SceneGraphBackend.
    api: Api
    scene_graph: Any
    sources: dict[str, Any]
    names_by_value: dict[int, str]
    _context: Callable[[Mapping[str, Any]], Any]
    _inspector: Callable[[Any], Any]
    _geometry: Callable[[str], Any]
    _frame: Callable[[str], Any]
    _refuse: Callable[[str], None]

    def _reset_queries(self) -> None:
        """Forgets every stored pose."""
        #: location → frame id value → X_PF (a RigidTransform of the api).
        self.poses: dict[str, dict[int, Any]] = {}

    # ------------------------------------------------------------- values
    def shape(self, spec: Mapping[str, Any] | None) -> Any:
        """A grammar shape (``grammar.queries.SHAPES``) → the api's Shape (keyword form)."""
        spec = DEFAULT_SHAPE if spec is None else spec
        mesh_class = MESH_SHAPES.get(spec["type"])
        if mesh_class is not None:
            return getattr(self.api.geometry, mesh_class)(
                filename=str(mesh_root() / spec["path"]), scale=float(spec.get("scale", 1.0))
            )
        class_name, keys = SHAPES[spec["type"]]
        return getattr(self.api.geometry, class_name)(**{key: spec[key] for key in keys})

    def rigid_transform(self, spec: Mapping[str, Any] | None) -> Any:
        """``{"xyz", "rpy"}`` → ``RigidTransform(rpy=RollPitchYaw(rpy=rpy), p=xyz)``."""
        m = self.api.math
        spec = spec or {}
        return m.RigidTransform(
            rpy=m.RollPitchYaw(rpy=list(spec.get("rpy", (0.0, 0.0, 0.0)))),
            p=list(spec.get("xyz", (0.0, 0.0, 0.0))),
        )

    # ------------------------------------------------------------- posing
    def _location(self, args: Mapping[str, Any]) -> tuple[str, Any]:
        """(location name, its context or None for the model); unknown contexts raise."""
        return args.get("context", MODEL), self._context(args)

    def _fix_poses(self, context: Any, location: str) -> None:
        """Fixes every source's pose port in ``context`` with ``location``'s stored poses.

        N.B. A context made before a source was registered lacks the source's
        pose port; fixing it aborts pydrake, so the guard
        "older-context-pose-port-aborts" refuses it where armed.
        """
        g, m = self.api.geometry, self.api.math
        stored = self.poses.get(location, {})
        inspector = self._inspector(context)
        for source_id in self.sources.values():
            if not inspector.SourceIsRegistered(source_id=source_id):
                continue
            frames = inspector.FramesForSource(source_id=source_id)
            if not frames:
                continue
            port = self.scene_graph.get_source_pose_port(source_id)
            if int(port.get_index()) >= context.num_input_ports():
                self._refuse("older-context-pose-port-aborts")
            poses = g.FramePoseVector()
            for frame_id in frames:
                X_PF = stored.get(frame_id.get_value())
                poses.set_value(id=frame_id, value=m.RigidTransform() if X_PF is None else X_PF)
            port.FixValue(context=context, value=poses)

    def _posed(self, args: Mapping[str, Any]) -> tuple[Any, Any]:
        """(context, QueryObject) at the step's location, posed (see the module doc).

        Keep the context while the QueryObject is used.
        """
        location, context = self._location(args)
        if context is None:
            context = self.scene_graph.CreateDefaultContext()
        self._fix_poses(context, location)
        return context, self.scene_graph.get_query_output_port().Eval(context)

    def _name(self, geometry_id: Any) -> str:
        value = geometry_id.get_value()
        return self.names_by_value.get(value, f"#{value}")

    def _shape_name(self, inspector: Any, geometry_id: Any) -> str:
        class_name = type(inspector.GetShape(geometry_id=geometry_id)).__name__
        return SHAPE_OF_CLASS.get(class_name, class_name)

    def _record(self, inspector: Any, item: Any, fields: Mapping[str, str]) -> dict[str, Any]:
        """The name-ordered record of a result: ``pair``, ``shapes`` and ``fields``."""
        ids = (item.id_A, item.id_B)
        record: dict[str, Any] = {
            "pair": [self._name(i) for i in ids],
            "shapes": [self._shape_name(inspector, i) for i in ids],
        }
        for key, attribute in fields.items():
            value = getattr(item, attribute)
            record[key] = float(value) if key in ("depth", "distance") else _vector(value)
        return record

    # ------------------------------------------------------------ commands
    def set_poses(self, args: Mapping[str, Any]) -> None:
        location, _ = self._location(args)
        poses = {
            self._frame(name).get_value(): self.rigid_transform(pose)
            for name, pose in args["poses"].items()
        }
        self.poses.setdefault(location, {}).update(poses)

    def compute_point_pair_penetration(self, args: Mapping[str, Any]) -> list[dict[str, Any]]:
        context, query = self._posed(args)
        inspector = query.inspector()
        fields = {k: k for k in ("depth", "p_WCa", "p_WCb", _NORMAL)}
        records = [
            _in_name_order(self._record(inspector, item, fields))
            for item in query.ComputePointPairPenetration()
        ]
        del context
        return sorted(records, key=lambda r: r["pair"])

    def has_collisions(self, args: Mapping[str, Any]) -> bool:
        context, query = self._posed(args)
        answer = bool(query.HasCollisions())
        del context
        return answer

    def find_collision_candidates(self, args: Mapping[str, Any]) -> list[list[str]]:
        context, query = self._posed(args)
        pairs = sorted(
            sorted([self._name(a), self._name(b)]) for a, b in query.FindCollisionCandidates()
        )
        del context
        return pairs

    def compute_signed_distance_pairwise_closest_points(
        self, args: Mapping[str, Any]
    ) -> list[dict[str, Any]]:
        context, query = self._posed(args)
        inspector = query.inspector()
        max_distance = float(args.get("max_distance", math.inf))
        fields = {k: k for k in ("distance", "p_ACa", "p_BCb", _NORMAL)}
        records = [
            _in_name_order(self._record(inspector, item, fields))
            for item in query.ComputeSignedDistancePairwiseClosestPoints(max_distance=max_distance)
        ]
        del context
        return sorted(records, key=lambda r: r["pair"])

    def compute_signed_distance_pair_closest_points(
        self, args: Mapping[str, Any]
    ) -> dict[str, Any]:
        a, b = args["pair"]
        context, query = self._posed(args)
        item = query.ComputeSignedDistancePairClosestPoints(
            geometry_id_A=self._geometry(a), geometry_id_B=self._geometry(b)
        )
        fields = {k: k for k in ("distance", "p_ACa", "p_BCb", _NORMAL)}
        record = self._record(query.inspector(), item, fields)
        del context
        return record

    def compute_signed_distance_to_point(self, args: Mapping[str, Any]) -> list[dict[str, Any]]:
        context, query = self._posed(args)
        inspector = query.inspector()
        threshold = float(args.get("threshold", math.inf))
        records = [
            {
                "geometry": self._name(item.id_G),
                "shape": self._shape_name(inspector, item.id_G),
                "distance": float(item.distance),
                "p_GN": _vector(item.p_GN),
                "grad_W": _vector(item.grad_W),
            }
            for item in query.ComputeSignedDistanceToPoint(
                p_WQ=[float(x) for x in args["p_WQ"]], threshold=threshold
            )
        ]
        del context
        return sorted(records, key=lambda r: r["geometry"])

    def x_wg(self, args: Mapping[str, Any]) -> dict[str, Any]:
        geometry_id = self._geometry(args["geometry"])
        context, query = self._posed(args)
        pose = _pose_json(query.GetPoseInWorld(geometry_id=geometry_id))
        del context
        return pose

    def x_wf(self, args: Mapping[str, Any]) -> dict[str, Any]:
        frame_id = self._frame(args["frame"])
        context, query = self._posed(args)
        pose = _pose_json(query.GetPoseInWorld(frame_id=frame_id))
        del context
        return pose
