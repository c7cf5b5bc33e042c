"""MultibodyPlant: model instances, bodies, joints, their geometry, and Finalize.

Drake counterpart: drake/multibody/plant/multibody_plant.h, as bound in
``pydrake.multibody.plant``. reimpl keeps what collision filtering and naming
need:

- Model instances 0 (``WorldModelInstance``) and 1 (``DefaultModelInstance``)
  always exist; the world body is body 0 and its frame is frame 0.
- Registered as a SceneGraph source (``RegisterAsSourceForSceneGraph``, or
  ``AddMultibodyPlantSceneGraph``), the plant gives every body but the world a
  SceneGraph frame named ``scoped(B)`` with frame group = B's instance index;
  the world body's frame is the world frame. A body's geometry goes on its
  frame (the world body's is anchored), named ``scoped(name)``.
- ``scoped(x)`` is ``instance::x`` for instances ≥ 2 and plain ``x`` in the
  world and default instances.
- ``Finalize()`` gives every tree not connected to the world a
  QuaternionFloatingJoint named after its base body (see _link_joint_graph),
  then declares the default collision filters (see _default_filters), and
  lays out the positions q (see kinematics: depth first from the world).
- A plant context holds q (initially the joints' default positions). The
  ``geometry_pose`` output port gives, for every body with a SceneGraph frame
  but the world, X_WB at the context's q (the FramePoseVector SceneGraph reads
  from its source pose port); the ``geometry_query`` input port reads the
  SceneGraph's QueryObject. ``AddMultibodyPlantSceneGraph`` connects both.
"""

# The rooms of this package, each one concept (its docstring states its rule):
#
#   _multibody_plant      MultibodyPlant: the bases below, composed; its construction
#   _phase                building, then finalized: the checks of each phase
#   _model_instances      model instances and scoped names
#   _elements             bodies, frames and joints: adding them, by index
#   _element_names        bodies, frames and joints by name
#   _topology             welds, floating and base bodies, the forest Finalize builds
#   _positions            a context's q, the joints' defaults as q
#   _state_names          the names of q and v
#   _poses                kinematics: body and frame poses, free bodies
#   _scene_graph_source   the plant as a SceneGraph source: a frame per body
#   _geometry_registration  collision and visual geometry
#   _geometry_ports       the geometry_pose and geometry_query ports
#   _collision_filters    the filters the plant declares (Finalize's, group pairs)
#   _finalize             Finalize's steps
#   _coulomb_friction     CoulombFriction
#   _diagram              AddMultibodyPlantSceneGraph, MultibodyPlantConfig, ...
#   _demands              Drake's failed preconditions as pydrake reports them

from __future__ import annotations

from reimpl._template import scalar_template
from reimpl.multibody.plant._coulomb_friction import CoulombFriction
from reimpl.multibody.plant._diagram import (
    AddMultibodyPlant,
    AddMultibodyPlantSceneGraph,
    ApplyMultibodyPlantConfig,
    MultibodyPlantConfig,
)
from reimpl.multibody.plant._multibody_plant import MultibodyPlant

__all__ = [
    "AddMultibodyPlant",
    "AddMultibodyPlantSceneGraph",
    "ApplyMultibodyPlantConfig",
    "CoulombFriction",
    "CoulombFriction_",
    "MultibodyPlant",
    "MultibodyPlantConfig",
    "MultibodyPlant_",
]

MultibodyPlant_ = scalar_template("reimpl.multibody.plant", "MultibodyPlant_", MultibodyPlant)
CoulombFriction_ = scalar_template("reimpl.multibody.plant", "CoulombFriction_", CoulombFriction)

# Public names report this package as their module, as pydrake's report theirs
# (reprs, pickles, help).
for _public in (
    AddMultibodyPlant,
    AddMultibodyPlantSceneGraph,
    ApplyMultibodyPlantConfig,
    CoulombFriction,
    MultibodyPlant,
    MultibodyPlantConfig,
):
    _public.__module__ = __name__
del _public
