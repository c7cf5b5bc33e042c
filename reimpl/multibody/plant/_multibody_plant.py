"""MultibodyPlant: the plant, made of its parts (one room each, see the package's map).

The class adds to its parts only its construction: the time step (which
Drake demands be ≥ 0), and the world body, added once every part is ready
for bodies. Its bases, by what they add (each extends the ones it names):

- PlantPhase: building, then finalized; ModelInstances; Elements (bodies,
  frames, joints); ElementNames (lookups by name);
- Topology (welds, floating bases, the forest); Positions (q); StateNames;
  Poses (kinematics);
- SceneGraphSource (frames); GeometryRegistration; GeometryPorts;
- CollisionFilters; Finalization (Finalize).
"""

from __future__ import annotations

from reimpl.multibody.plant._demands import demand
from reimpl.multibody.plant._finalize import Finalization
from reimpl.multibody.plant._geometry_ports import GeometryPorts
from reimpl.multibody.plant._geometry_registration import GeometryRegistration
from reimpl.multibody.plant._state_names import StateNames
from reimpl.multibody.tree import RigidBody, world_model_instance

__all__ = ["MultibodyPlant"]

_WORLD_BODY_NAME = "world"


class MultibodyPlant(Finalization, GeometryPorts, GeometryRegistration, StateNames):
    """Bodies joined by joints, grouped in model instances, with geometry in a SceneGraph.

    Finalize filters collisions, when the plant is a SceneGraph source, by
    ``C ← C − {(g,h) : frame(g)=F(child), frame(h)=F(parent)}`` for adjacent
    bodies and ``C ← C − {(g,h) : frame(g), frame(h) ∈ F(S)}`` for each welded
    set S (see reimpl.multibody._default_filters).
    """

    _cpp_type = "drake::multibody::MultibodyPlant<double>"

    def __init__(self, time_step: float) -> None:
        super().__init__()
        # N.B. pydrake demands this in multibody_plant.cc (SystemExit, measured).
        demand(time_step >= 0, "MultibodyPlant.time_step")
        self._time_step = float(time_step)
        world = RigidBody(_WORLD_BODY_NAME, world_model_instance())
        self._add_body(world)

    def time_step(self) -> float:
        return self._time_step
