"""The public names of the collision-filter subset: pydrake's ``dir()`` against reimpl's.

Not a port of a Drake test: a drop-in check. For each module and class of the
subset below, every public name the installed pydrake has must exist on
reimpl, or be listed in ``LEFT_OUT`` with the reason it is left out. A name
pydrake gains (a new release) fails here until it is added or listed; a listed
name reimpl gains fails here until it leaves the list; a listed name must
exist in the pydrake it is listed for (1.51.1, or the release named).

Runs on whichever pydrake is installed (1.51.1, or 1.58.0 with
``PYTHONPATH=<worktree> /tmp/venv158/bin/python -m pytest ...``).
"""

from __future__ import annotations

import importlib
import importlib.metadata
from collections.abc import Iterable
from types import ModuleType

import pytest

#: Module → the classes of the subset it holds (the module itself is compared too).
SUBSET: dict[str, tuple[str, ...]] = {
    "geometry": (
        "SceneGraph",
        "SceneGraphInspector",
        "CollisionFilterManager",
        "CollisionFilterDeclaration",
        "CollisionFilterScope",
        "GeometrySet",
        "GeometryInstance",
        "GeometryFrame",
        "QueryObject",
        "FramePoseVector",
        "PenetrationAsPointPair",
        "SignedDistancePair",
        "Shape",
        "Box",
        "Sphere",
        "Cylinder",
        "Capsule",
        "Ellipsoid",
        "HalfSpace",
        "Mesh",
        "Convex",
        "MeshcatCone",
        "MeshSource",
        "GeometryId",
        "FrameId",
        "SourceId",
        "FilterId",
        "Role",
        "RoleAssign",
        "GeometryProperties",
        "ProximityProperties",
        "IllustrationProperties",
        "PerceptionProperties",
    ),
    "multibody.plant": ("MultibodyPlant", "CoulombFriction", "MultibodyPlantConfig"),
    "multibody.tree": (
        "RigidBody",
        "Frame",
        "RigidBodyFrame",
        "FixedOffsetFrame",
        "Joint",
        "WeldJoint",
        "RevoluteJoint",
        "PrismaticJoint",
        "BallRpyJoint",
        "UniversalJoint",
        "PlanarJoint",
        "QuaternionFloatingJoint",
        "RpyFloatingJoint",
        "ScrewJoint",
        "BodyIndex",
        "FrameIndex",
        "JointIndex",
        "ModelInstanceIndex",
        "SpatialInertia",
        "UnitInertia",
        "RotationalInertia",
        "ScopedName",
    ),
    "multibody.parsing": ("Parser", "PackageMap", "CollisionFilterGroups"),
    "math": ("RigidTransform", "RotationMatrix", "RollPitchYaw"),
}

JOINTS = tuple(
    f"multibody.tree.{j}"
    for j in (
        "Joint",
        "WeldJoint",
        "RevoluteJoint",
        "PrismaticJoint",
        "BallRpyJoint",
        "UniversalJoint",
        "PlanarJoint",
        "QuaternionFloatingJoint",
        "RpyFloatingJoint",
        "ScrewJoint",
    )
)
FRAMES = tuple(f"multibody.tree.{f}" for f in ("Frame", "RigidBodyFrame", "FixedOffsetFrame"))
INERTIAS = tuple(
    f"multibody.tree.{i}" for i in ("SpatialInertia", "UnitInertia", "RotationalInertia")
)

# Reasons.
SYSTEMS = (
    "systems framework beyond contexts and ports (events, state, caching, scalar conversion, "
    "graphviz): every name pydrake's LeafSystem has, see LEAF_SYSTEM"
)
SCALARS = (
    "a scalar-template instantiation's mangled name (𝓣AutoDiffXd𝓤 ...): reimpl is "
    "double-only and binds ``X_[float]`` through a TemplateClass"
)
IMPORTS = "a module pydrake's package imports into its namespace"
RENDERING = "rendering (render engines, cameras, images, labels)"
VISUALIZATION = "visualization (Meshcat, DrakeVisualizer, colors)"
HYDROELASTIC = "hydroelastic contact (compliant/rigid meshes, contact surfaces)"
MESH_DATA = (
    "mesh contents beyond the convex hull (surface and volume meshes, fields, in-memory meshes)"
)
BOUNDING = "bounding volumes (AABB/OBB)"
DEFORMABLE = "deformable bodies and geometries"
SHAPE_CHANGE = "changing a registered geometry's shape"
DYNAMICS = "dynamics: mass, inertia, Jacobians, forces, energies, velocities, accelerations"
VELOCITIES = "velocities and accelerations of joints, bodies and frames (reimpl tracks q only)"
ACTUATION = "actuators, actuation ports and effort limits"
CONSTRAINTS = "constraints (coupler, distance, ball, weld, tendon)"
CONTACT = "contact models and their parameters"
FORCE_ELEMENTS = "force elements (springs, bushings, gravity, hinges)"
PORTS = "ports other than geometry_pose and geometry_query"
LIMIT_SETTERS = "limit setters and plant-wide limit arrays (joints read back their own limits)"
STATE_ARRAYS = "state-vector helpers (q/v arrays, selector matrices, state names)"
LOCKING = "joint and body locking (a context parameter)"
RANDOM = "random state distributions"
TOPOLOGY_EDIT = "topology editing or options (joint removal, loop topology, base joint type)"
DEPRECATED = "deprecated in 1.51.1 and gone in 1.58.0: use the new name"
CONTEXT_PARAMETERS = "per-context parameters (damping, frame poses)"
POSE_CONVERSIONS = (
    "conversions needing types reimpl does not have (Quaternion, AngleAxis, Isometry3) or "
    "Drake's own extraction algorithm (ToRollPitchYaw)"
)
MATH = "numerical math beyond rigid transforms (Riccati, Lyapunov, B-splines, quaternions, ...)"
RATES = "rates of roll-pitch-yaw angles (velocities)"
NANOBIND_INT = "1.58.0 binds Role with nanobind as an int-like enum, so it carries int's methods"
NEW_IN_1_58 = "new in 1.58.0 (reimpl follows 1.51.1)"

#: (reason, targets, names, the one release whose pydrake has them, or None: 1.51.1 and 1.58.0)
Entry = tuple[str, tuple[str, ...], str, str | None]

LEFT_OUT: tuple[Entry, ...] = (
    # ------------------------------------------------------------- geometry
    (IMPORTS, ("geometry",), "all optimization os socket subprocess sys", None),
    (
        RENDERING,
        ("geometry",),
        "ClippingRange ColorRenderCamera DepthRange DepthRenderCamera EnvironmentMap "
        "EquirectangularMap GltfExtension LightParameter MakeRenderEngineGl "
        "MakeRenderEngineGltfClient MakeRenderEngineVtk NullTexture RenderCameraCore "
        "RenderEngine RenderEngineGlParams RenderEngineGltfClientParams RenderEngineVtkParams "
        "RenderLabel SsaoParameter kHasRenderEngineGl kHasRenderEngineGltfClient "
        "kHasRenderEngineVtk",
        None,
    ),
    (
        VISUALIZATION,
        ("geometry",),
        "DrakeVisualizer DrakeVisualizerParams DrakeVisualizer_ MakePhongIllustrationProperties "
        "Meshcat MeshcatAnimation MeshcatParams MeshcatPointCloudVisualizer "
        "MeshcatPointCloudVisualizer_ MeshcatVisualizer MeshcatVisualizerParams "
        "MeshcatVisualizer_ StartMeshcat",
        None,
    ),
    (VISUALIZATION, ("geometry",), "MeshcatVisualizerSurfaceVelocityData", "1.58.0"),
    (
        HYDROELASTIC,
        ("geometry",),
        "AddCompliantHydroelasticProperties AddCompliantHydroelasticPropertiesForHalfSpace "
        "AddContactMaterial AddRigidHydroelasticProperties ContactSurface ContactSurface_ "
        "DefaultProximityProperties HydroelasticContactRepresentation Plane Plane_ "
        "SceneGraphConfig",
        None,
    ),
    (
        MESH_DATA,
        ("geometry",),
        "ConvertVolumeToSurfaceMesh InMemoryMesh PolygonSurfaceMeshFieldLinear "
        "PolygonSurfaceMeshFieldLinear_ PolygonSurfaceMesh_ ReadObjToTriangleSurfaceMesh "
        "RefineVolumeMesh RefineVolumeMeshIntoVtkFileContents SurfaceTriangle "
        "TriangleSurfaceMesh TriangleSurfaceMeshFieldLinear TriangleSurfaceMeshFieldLinear_ "
        "TriangleSurfaceMesh_ VolumeElement VolumeMesh VolumeMesh_",
        None,
    ),
    (
        BOUNDING,
        ("geometry",),
        "Aabb CalcObb ComputeAabbForTriangleMesh ComputeAabbForVolumeMesh "
        "ComputeObbForTriangleMesh ComputeObbForVolumeMesh Obb",
        None,
    ),
    (DEFORMABLE, ("geometry",), "GeometryConfigurationVector GeometryConfigurationVector_", None),
    (
        RENDERING,
        ("geometry.SceneGraph",),
        "AddRenderer GetRendererParameterYaml GetRendererTypeName HasRenderer RemoveRenderer "
        "RendererCount",
        None,
    ),
    (SHAPE_CHANGE, ("geometry.SceneGraph",), "ChangeShape", None),
    (DEFORMABLE, ("geometry.SceneGraph",), "RegisterDeformableGeometry", None),
    (HYDROELASTIC, ("geometry.SceneGraph",), "get_config set_config", None),
    (
        DEFORMABLE,
        ("geometry.SceneGraphInspector",),
        "GetAllDeformableGeometryIds GetReferenceMesh IsDeformableGeometry "
        "NumDeformableGeometriesWithRole",
        None,
    ),
    (MESH_DATA, ("geometry.SceneGraphInspector",), "GetConvexHull", None),
    (HYDROELASTIC, ("geometry.SceneGraphInspector",), "maybe_get_hydroelastic_mesh", None),
    (BOUNDING, ("geometry.SceneGraphInspector",), "GetObbInGeometryFrame", None),
    (BOUNDING, ("geometry.QueryObject",), "ComputeAabbInWorld ComputeObbInWorld", None),
    (
        HYDROELASTIC,
        ("geometry.QueryObject",),
        "ComputeContactSurfaces ComputeContactSurfacesWithFallback",
        None,
    ),
    (DEFORMABLE, ("geometry.QueryObject",), "GetConfigurationsInWorld", None),
    (
        RENDERING,
        ("geometry.QueryObject",),
        "RenderColorImage RenderDepthImage RenderLabelImage",
        None,
    ),
    (
        NANOBIND_INT,
        ("geometry.Role",),
        "as_integer_ratio bit_count bit_length conjugate denominator from_bytes imag "
        "is_integer numerator real to_bytes",
        "1.58.0",
    ),
    # ------------------------------------------------------- multibody.plant
    (
        CONTACT,
        ("multibody.plant",),
        "CalcContactFrictionFromSurfaceProperties ContactModel ContactResults ContactResults_ "
        "DiscreteContactApproximation DiscreteContactSolver HydroelasticContactInfo "
        "HydroelasticContactInfo_ PointPairContactInfo PointPairContactInfo_",
        None,
    ),
    (VISUALIZATION, ("multibody.plant",), "ConnectContactResultsToDrakeVisualizer", None),
    (VISUALIZATION, ("multibody.plant",), "ContactResultsToLcmSystem", None),
    (
        DEFORMABLE,
        ("multibody.plant",),
        "DeformableContactInfo DeformableContactInfo_ DeformableModel PhysicalModel",
        None,
    ),
    (CONSTRAINTS, ("multibody.plant",), "DistanceConstraintParams", None),
    (
        FORCE_ELEMENTS,
        ("multibody.plant",),
        "ExternallyAppliedSpatialForce ExternallyAppliedSpatialForceMultiplexer "
        "ExternallyAppliedSpatialForceMultiplexer_ ExternallyAppliedSpatialForce_ Propeller "
        "PropellerInfo Propeller_ Wing Wing_",
        None,
    ),
    (TOPOLOGY_EDIT, ("multibody.plant",), "BaseBodyJointType", "1.58.0"),
    (
        DYNAMICS,
        ("multibody.plant.MultibodyPlant",),
        "AddForceElement CalcBiasCenterOfMassTranslationalAcceleration "
        "CalcBiasSpatialAcceleration CalcBiasTerm CalcBiasTranslationalAcceleration "
        "CalcCenterOfMassPositionInWorld CalcCenterOfMassTranslationalAccelerationInWorld "
        "CalcCenterOfMassTranslationalVelocityInWorld CalcForceElementsContribution "
        "CalcGeneralizedForces CalcGravityGeneralizedForces CalcInverseDynamics "
        "CalcJacobianAngularVelocity CalcJacobianCenterOfMassTranslationalVelocity "
        "CalcJacobianPositionVector CalcJacobianSpatialVelocity "
        "CalcJacobianTranslationalVelocity CalcMassMatrix CalcMassMatrixViaInverseDynamics "
        "CalcPointsPositions CalcPointsVelocities CalcSpatialAccelerationsFromVdot "
        "CalcSpatialInertia CalcSpatialMomentumInWorldAboutPoint CalcTotalMass "
        "EvalBodySpatialAccelerationInWorld EvalBodySpatialVelocityInWorld get_force_element "
        "gravity_field is_gravity_enabled mutable_gravity_field num_force_elements "
        "set_gravity_enabled",
        None,
    ),
    (DYNAMICS, ("multibody.plant.MultibodyPlant",), "num_misc_continuous_states", "1.58.0"),
    (
        VELOCITIES,
        ("multibody.plant.MultibodyPlant",),
        "GetPositionsAndVelocities GetVelocities IsVelocityEqualToQDot MakeQDotToVelocityMap "
        "MakeVelocityToQDotMap MapQDotToVelocity MapVelocityToQDot SetDefaultState "
        "SetFreeBodySpatialVelocity SetPositionsAndVelocities SetVelocities",
        None,
    ),
    (
        STATE_ARRAYS,
        ("multibody.plant.MultibodyPlant",),
        "GetPositionsFromArray GetVelocitiesFromArray "
        "MakeStateSelectorMatrix SetPositionsInArray SetVelocitiesInArray",
        None,
    ),
    (
        ACTUATION,
        ("multibody.plant.MultibodyPlant",),
        "AddJointActuator GetActuatedJointIndices GetActuationFromArray GetActuatorNames "
        "GetEffortLowerLimits GetEffortUpperLimits GetJointActuatorByName "
        "GetJointActuatorIndices HasJointActuatorNamed MakeActuationMatrix "
        "MakeActuationMatrixPseudoinverse MakeActuatorSelectorMatrix "
        "RemoveAllJointActuatorEffortLimits RemoveJointActuator SetActuationInArray "
        "get_actuation_input_port get_desired_state_input_port get_joint_actuator "
        "get_mutable_joint_actuator get_net_actuation_output_port has_joint_actuator "
        "num_actuated_dofs num_actuators",
        None,
    ),
    (
        CONSTRAINTS,
        ("multibody.plant.MultibodyPlant",),
        "AddBallConstraint AddCouplerConstraint AddDistanceConstraint AddWeldConstraint "
        "GetConstraintActiveStatus GetConstraintIds GetDefaultDistanceConstraintParams "
        "GetDistanceConstraintParams RemoveConstraint SetConstraintActiveStatus "
        "SetDistanceConstraintParams",
        None,
    ),
    (
        CONSTRAINTS,
        ("multibody.plant.MultibodyPlant",),
        "AddTendonConstraint num_loop_constraints",
        "1.58.0",
    ),
    (
        CONTACT,
        ("multibody.plant.MultibodyPlant",),
        "GetDefaultContactSurfaceRepresentation get_contact_model "
        "get_contact_penalty_method_time_scale get_contact_results_output_port "
        "get_contact_surface_representation get_discrete_contact_approximation "
        "get_discrete_contact_solver get_generalized_contact_forces_output_port "
        "get_reaction_forces_output_port get_sap_near_rigid_threshold set_contact_model "
        "set_contact_surface_representation set_discrete_contact_approximation "
        "set_penetration_allowance set_sap_near_rigid_threshold set_stiction_tolerance",
        None,
    ),
    (
        CONTACT,
        ("multibody.plant.MultibodyPlant",),
        "GetSurfaceVelocityAxis SetSurfaceVelocityAxis get_surface_displacements_output_port "
        "get_surface_speeds_input_port",
        "1.58.0",
    ),
    (
        PORTS,
        ("multibody.plant.MultibodyPlant",),
        "SetUseSampledOutputPorts get_applied_generalized_force_input_port "
        "get_applied_spatial_force_input_port get_body_poses_output_port "
        "get_body_spatial_accelerations_output_port get_body_spatial_velocities_output_port "
        "get_generalized_acceleration_output_port get_state_output_port "
        "has_sampled_output_ports",
        None,
    ),
    (
        DEFORMABLE,
        ("multibody.plant.MultibodyPlant",),
        "deformable_model get_deformable_body_configuration_output_port mutable_deformable_model",
        None,
    ),
    (
        LIMIT_SETTERS,
        ("multibody.plant.MultibodyPlant",),
        "GetAccelerationLowerLimits GetAccelerationUpperLimits GetPositionLowerLimits "
        "GetPositionUpperLimits GetVelocityLowerLimits GetVelocityUpperLimits",
        None,
    ),
    (
        TOPOLOGY_EDIT,
        ("multibody.plant.MultibodyPlant",),
        "GetTopologyGraphvizString RemoveJoint SetFloatingBaseBodyPoseInAnchoredFrame "
        "SetFloatingBaseBodyPoseInWorldFrame",
        None,
    ),
    (
        TOPOLOGY_EDIT,
        ("multibody.plant.MultibodyPlant",),
        "GetBaseBodyJointType GetEnableLoopTopology SetBaseBodyJointType SetEnableLoopTopology",
        "1.58.0",
    ),
    (
        DEPRECATED,
        ("multibody.plant.MultibodyPlant",),
        "GetUniqueFreeBaseBodyOrThrow HasUniqueFreeBaseBody",
        "1.51.1",
    ),
    # -------------------------------------------------------- multibody.tree
    (DYNAMICS, ("multibody.tree",), "CalcSpatialInertia JacobianWrtVariable", None),
    (DEFORMABLE, ("multibody.tree",), "DeformableBody DeformableBodyId DeformableBodyIndex", None),
    (
        FORCE_ELEMENTS,
        ("multibody.tree",),
        "DoorHinge DoorHingeConfig DoorHinge_ ForceDensityField ForceDensityField_ ForceElement "
        "ForceElementIndex ForceElement_ GravityForceField GravityForceField_ "
        "LinearBushingRollPitchYaw LinearBushingRollPitchYaw_ LinearSpringDamper "
        "LinearSpringDamper_ MultibodyForces MultibodyForces_ PrismaticSpring PrismaticSpring_ "
        "RevoluteSpring RevoluteSpring_ UniformGravityFieldElement UniformGravityFieldElement_",
        None,
    ),
    (
        ACTUATION,
        ("multibody.tree",),
        "JointActuator JointActuatorIndex JointActuator_ PdControllerGains",
        None,
    ),
    (CONSTRAINTS, ("multibody.tree",), "MultibodyConstraintId", None),
    (
        DYNAMICS,
        ("multibody.tree.RigidBody",),
        "AddInForce AddInForceInWorld CalcCenterOfMassInBodyFrame "
        "CalcCenterOfMassTranslationalAccelerationInWorld "
        "CalcCenterOfMassTranslationalVelocityInWorld CalcSpatialInertiaInBodyFrame "
        "EvalSpatialAccelerationInWorld EvalSpatialVelocityInWorld GetForceInWorld "
        "SetCenterOfMassInBodyFrame SetMass SetSpatialInertiaInBodyFrame default_com "
        "default_rotational_inertia default_unit_inertia get_mass",
        None,
    ),
    (LOCKING, ("multibody.tree.RigidBody", *JOINTS), "Lock Unlock is_locked", None),
    (
        VELOCITIES,
        FRAMES,
        "CalcAngularVelocity CalcRelativeSpatialAcceleration "
        "CalcRelativeSpatialAccelerationInWorld CalcRelativeSpatialVelocity "
        "CalcRelativeSpatialVelocityInWorld CalcSpatialAcceleration "
        "CalcSpatialAccelerationInWorld CalcSpatialVelocity CalcSpatialVelocityInWorld "
        "EvalAngularVelocityInWorld",
        None,
    ),
    (CONTEXT_PARAMETERS, ("multibody.tree.FixedOffsetFrame",), "SetPoseInParentFrame", None),
    (DYNAMICS, JOINTS, "AddInDamping AddInOneForce", None),
    (VELOCITIES, JOINTS, "GetOneVelocity", None),
    (
        CONTEXT_PARAMETERS,
        JOINTS,
        "GetDampingVector SetDampingVector set_default_damping_vector",
        None,
    ),
    (
        LIMIT_SETTERS,
        JOINTS,
        "set_acceleration_limits set_position_limits set_velocity_limits",
        None,
    ),
    (
        POSE_CONVERSIONS,
        JOINTS,
        "GetDefaultPose GetDefaultPosePair SetDefaultPose SetDefaultPosePair",
        None,
    ),
    (
        CONTEXT_PARAMETERS,
        (
            "multibody.tree.RevoluteJoint",
            "multibody.tree.PrismaticJoint",
            "multibody.tree.ScrewJoint",
        ),
        "GetDamping SetDamping",
        None,
    ),
    (
        CONTEXT_PARAMETERS,
        ("multibody.tree.RevoluteJoint", "multibody.tree.PrismaticJoint"),
        "set_default_damping",
        None,
    ),
    (VELOCITIES, ("multibody.tree.RevoluteJoint",), "get_angular_rate set_angular_rate", None),
    (
        VELOCITIES,
        ("multibody.tree.PrismaticJoint",),
        "get_translation_rate set_translation_rate",
        None,
    ),
    (
        VELOCITIES,
        ("multibody.tree.UniversalJoint",),
        "get_angular_rates set_angular_rates",
        None,
    ),
    (
        VELOCITIES,
        (
            "multibody.tree.BallRpyJoint",
            "multibody.tree.PlanarJoint",
            "multibody.tree.QuaternionFloatingJoint",
            "multibody.tree.RpyFloatingJoint",
            "multibody.tree.ScrewJoint",
        ),
        "get_angular_velocity set_angular_velocity",
        None,
    ),
    (
        VELOCITIES,
        (
            "multibody.tree.PlanarJoint",
            "multibody.tree.QuaternionFloatingJoint",
            "multibody.tree.RpyFloatingJoint",
            "multibody.tree.ScrewJoint",
        ),
        "get_translational_velocity set_translational_velocity",
        None,
    ),
    (RANDOM, ("multibody.tree.RevoluteJoint",), "set_random_angle_distribution", None),
    (RANDOM, ("multibody.tree.PrismaticJoint",), "set_random_translation_distribution", None),
    (
        RANDOM,
        (
            "multibody.tree.BallRpyJoint",
            "multibody.tree.UniversalJoint",
            "multibody.tree.RpyFloatingJoint",
        ),
        "set_random_angles_distribution",
        None,
    ),
    (
        RANDOM,
        ("multibody.tree.PlanarJoint", "multibody.tree.ScrewJoint"),
        "set_random_pose_distribution",
        None,
    ),
    (
        RANDOM,
        ("multibody.tree.QuaternionFloatingJoint", "multibody.tree.RpyFloatingJoint"),
        "set_random_translation_distribution",
        None,
    ),
    (
        RANDOM,
        ("multibody.tree.QuaternionFloatingJoint",),
        "set_random_quaternion_distribution set_random_quaternion_distribution_to_uniform",
        None,
    ),
    (
        POSE_CONVERSIONS,
        ("multibody.tree.QuaternionFloatingJoint",),
        "SetQuaternion get_default_quaternion get_quaternion set_default_quaternion",
        None,
    ),
    (
        DYNAMICS,
        ("multibody.tree.SpatialInertia",),
        "CalcComMoment CalcPrincipalSemiDiametersAndPoseForSolidEllipsoid CalcRotationalInertia "
        "CopyToFullMatrix6 HollowSphereWithDensity HollowSphereWithMass IsNaN "
        "IsPhysicallyValid ReExpress SetNaN Shift SolidBoxWithDensity SolidCapsuleWithDensity "
        "SolidCapsuleWithMass SolidCubeWithDensity SolidCylinderWithDensity "
        "SolidCylinderWithDensityAboutEnd SolidCylinderWithMass SolidCylinderWithMassAboutEnd "
        "SolidEllipsoidWithDensity SolidEllipsoidWithMass ThinRodWithMass "
        "ThinRodWithMassAboutEnd",
        None,
    ),
    (
        DYNAMICS,
        ("multibody.tree.UnitInertia", "multibody.tree.RotationalInertia"),
        "CalcMaximumPossibleMomentOfInertia CalcPrincipalMomentsAndAxesOfInertia "
        "CalcPrincipalMomentsOfInertia CopyToFullMatrix3 CouldBePhysicallyValid IsNaN "
        "IsNearlyEqualTo IsZero ReExpress SetToNaN SetZero ShiftFromCenterOfMass "
        "ShiftToCenterOfMass ShiftToThenAwayFromCenterOfMass Trace TriaxiallySymmetric cols "
        "get_moments get_products rows",
        None,
    ),
    (
        DYNAMICS,
        ("multibody.tree.UnitInertia",),
        "AxiallySymmetric HollowSphere PointMass SetFromRotationalInertia SolidBox "
        "SolidCapsule SolidCube SolidCylinder SolidCylinderAboutEnd SolidEllipsoid SolidSphere "
        "StraightLine ThinRod",
        None,
    ),
    # ------------------------------------------------------------------ math
    (
        MATH,
        ("math",),
        "AreQuaternionsEqualForOrientation BalanceQuadraticForms BarycentricMesh BsplineBasis "
        "BsplineBasis_ CalculateAngularVelocityExpressedInBFromQuaternionDt "
        "CalculateQuaternionDtConstraintViolation "
        "CalculateQuaternionDtFromAngularVelocityExpressedInB ClosestQuaternion "
        "ComputeNumericalGradient ContinuousAlgebraicRiccatiEquation "
        "DecomposePSDmatrixIntoXtransposeTimesX DecomposePositiveQuadraticForm "
        "DiscreteAlgebraicRiccatiEquation ExtractPrincipalSubmatrix "
        "IsBothQuaternionAndQuaternionDtOK IsPositiveDefinite IsQuaternionValid IsSymmetric "
        "KnotVectorType NumericalGradientMethod NumericalGradientOption "
        "QuaternionToCanonicalForm RealContinuousLyapunovEquation RealDiscreteLyapunovEquation "
        "SoftOverMax SoftOverMin SoftUnderMax SoftUnderMin ToLowerTriangularColumnsFromMatrix "
        "ToSymmetricMatrixFromLowerTriangularColumns UniformlyRandomAngleAxis "
        "UniformlyRandomQuaternion UniformlyRandomRPY UniformlyRandomRotationMatrix "
        "VectorToSkewSymmetric abs acos arccos arcsin arctan arctan2 asin atan atan2 ceil cos "
        "cosh eq exp floor ge gt inv is_quaternion_in_canonical_form isnan le log lt matmul max "
        "min ne pow sin sinh sqrt tan tanh wrap_to",
        None,
    ),
    (IMPORTS, ("math",), "functools operator", None),
    (
        POSE_CONVERSIONS,
        ("math.RigidTransform",),
        "GetAsIsometry3 MakeUnchecked SetFromIsometry3 cast",
        None,
    ),
    (
        POSE_CONVERSIONS,
        ("math.RotationMatrix",),
        "IsValid MakeFromOneVector MakeUnchecked ProjectToRotationMatrix ToAngleAxis "
        "ToQuaternion ToRollPitchYaw cast set",
        None,
    ),
    (NEW_IN_1_58, ("math.RotationMatrix",), "IsExactlyEqualTo IsNearlyEqualTo", "1.58.0"),
    (
        RATES,
        ("math.RollPitchYaw",),
        "CalcAngularVelocityInChildFromRpyDt CalcAngularVelocityInParentFromRpyDt "
        "CalcRotationMatrixDt CalcRpyDDtFromAngularAccelInChild "
        "CalcRpyDDtFromRpyDtAndAngularAccelInParent CalcRpyDtFromAngularVelocityInChild "
        "CalcRpyDtFromAngularVelocityInParent",
        None,
    ),
    (POSE_CONVERSIONS, ("math.RollPitchYaw",), "ToQuaternion", None),
    (NEW_IN_1_58, ("math.RollPitchYaw",), "IsNearlyEqualTo", "1.58.0"),
)


RELEASE = importlib.metadata.version("drake")
#: The classes whose LeafSystem names are left out (SYSTEMS).
SYSTEM_CLASSES = ("geometry.SceneGraph", "multibody.plant.MultibodyPlant")


def _public(names: Iterable[str]) -> set[str]:
    return {n for n in names if not n.startswith("_")}


def _resolve(root: str, target: str) -> object:
    """``geometry.SceneGraph`` under ``pydrake`` or ``reimpl``: a module or a class."""
    for split in range(target.count(".") + 1, 0, -1):
        module_name = ".".join(target.split(".")[:split])
        try:
            obj: object = importlib.import_module(f"{root}.{module_name}")
        except ModuleNotFoundError:
            continue
        for attribute in target.split(".")[split:]:
            obj = getattr(obj, attribute)
        return obj
    raise LookupError(target)


def _targets() -> list[str]:
    targets = []
    for module, classes in SUBSET.items():
        targets.append(module)
        targets.extend(f"{module}.{c}" for c in classes)
    return targets


def _applies(release: str | None) -> bool:
    return release is None or release == RELEASE


def _left_out(target: str, *, applicable_only: bool) -> dict[str, str]:
    """Name → reason for ``target``: the listed names, then the rules (LeafSystem, scalars)."""
    reasons: dict[str, str] = {}
    for reason, targets, names, release in LEFT_OUT:
        if target in targets and (_applies(release) or not applicable_only):
            reasons.update(dict.fromkeys(names.split(), reason))
    return reasons


def _rule_reason(target: str, name: str) -> str | None:
    if "𝓣" in name:
        return SCALARS
    if target in SYSTEM_CLASSES and name in LEAF_SYSTEM:
        return SYSTEMS
    return None


def _leaf_system_names() -> frozenset[str]:
    framework: ModuleType = importlib.import_module("pydrake.systems.framework")
    return frozenset(_public(dir(framework.LeafSystem)))


LEAF_SYSTEM = _leaf_system_names()


@pytest.mark.parametrize("target", _targets())
def test_every_pydrake_name_is_in_reimpl_or_left_out_with_a_reason(target: str) -> None:
    pydrake_names = _public(dir(_resolve("pydrake", target)))
    reimpl_names = _public(dir(_resolve("reimpl", target)))
    listed = _left_out(target, applicable_only=True)
    unexplained = sorted(
        name
        for name in pydrake_names - reimpl_names
        if name not in listed and _rule_reason(target, name) is None
    )
    assert unexplained == [], (
        f"pydrake {RELEASE} {target} has names reimpl lacks and LEFT_OUT does not list"
    )


@pytest.mark.parametrize("target", _targets())
def test_a_left_out_name_is_missing_from_reimpl(target: str) -> None:
    reimpl_names = _public(dir(_resolve("reimpl", target)))
    stale = sorted(set(_left_out(target, applicable_only=False)) & reimpl_names)
    assert stale == [], f"reimpl now has these: take them off LEFT_OUT for {target}"


@pytest.mark.parametrize("target", _targets())
def test_a_left_out_name_exists_in_pydrake(target: str) -> None:
    pydrake_names = _public(dir(_resolve("pydrake", target)))
    unknown = sorted(set(_left_out(target, applicable_only=True)) - pydrake_names)
    assert unknown == [], f"pydrake {RELEASE} {target} has no such names"


def test_every_entry_names_a_reason_and_a_target_of_the_subset() -> None:
    targets = set(_targets())
    for reason, entry_targets, names, release in LEFT_OUT:
        assert reason
        assert names.split()
        assert set(entry_targets) <= targets, entry_targets
        assert release in {None, "1.51.1", "1.58.0"}
