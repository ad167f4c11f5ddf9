# The headers tools/makedna reads, in the order their structs enter the DNA (used by CMakeLists.txt).
set(CALIBER_DNA_HEADERS
  src/LinearMath/SerializerDnaExtras.h
  include/LinearMath/btVector3.h
  include/LinearMath/btQuaternion.h
  include/LinearMath/btMatrix3x3.h
  include/LinearMath/btTransform.h
  include/BulletCollision/BroadphaseCollision/btQuantizedBvh.h
  include/BulletCollision/CollisionShapes/btCollisionShape.h
  include/BulletCollision/CollisionShapes/btStaticPlaneShape.h
  include/BulletCollision/CollisionShapes/btConvexInternalShape.h
  include/BulletCollision/CollisionShapes/btMultiSphereShape.h
  include/BulletCollision/CollisionShapes/btStridingMeshInterface.h
  include/BulletCollision/CollisionShapes/btTriangleInfoMap.h
  include/BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h
  include/BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h
  include/BulletCollision/CollisionShapes/btCompoundShape.h
  include/BulletCollision/CollisionShapes/btCylinderShape.h
  include/BulletCollision/CollisionShapes/btConeShape.h
  include/BulletCollision/CollisionShapes/btCapsuleShape.h
  include/BulletCollision/CollisionShapes/btConvexHullShape.h
  include/BulletCollision/CollisionDispatch/btCollisionObject.h
  include/BulletCollision/NarrowPhaseCollision/btPersistentManifold.h
  include/BulletDynamics/ConstraintSolver/btContactSolverInfo.h
  include/BulletDynamics/Dynamics/btDynamicsWorld.h
  include/BulletDynamics/Dynamics/btRigidBody.h
  include/BulletDynamics/ConstraintSolver/btTypedConstraint.h
  include/BulletDynamics/ConstraintSolver/btPoint2PointConstraint.h
  include/BulletDynamics/ConstraintSolver/btHingeConstraint.h
  include/BulletDynamics/ConstraintSolver/btConeTwistConstraint.h
  include/BulletDynamics/ConstraintSolver/btGeneric6DofConstraint.h
  include/BulletDynamics/ConstraintSolver/btGeneric6DofSpringConstraint.h
  include/BulletDynamics/ConstraintSolver/btGeneric6DofSpring2Constraint.h
  include/BulletDynamics/ConstraintSolver/btSliderConstraint.h
  include/BulletDynamics/ConstraintSolver/btGearConstraint.h
  include/BulletSoftBody/btSoftBodyData.h)
set(CALIBER_DNA_OPTIONS --also ListBase --also btPositionAndRadius --skip btContactSolverInfoData)
set(CALIBER_DNA_TABLE src/LinearMath/SerializerDnaTables.inc)
set(CALIBER_DNA_FIELDS tests/Serialize/DnaLayoutFields.inc)
