// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SOFT_RIGID_DYNAMICS_WORLD_H
#define BT_SOFT_RIGID_DYNAMICS_WORLD_H

/// btSoftRigidDynamicsWorld: the rigid-body world that also steps soft bodies (docs/soft-bodies.md
/// draws where they run in the step).

#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h"
#include "BulletSoftBody/btSoftBody.h"

class btSoftBodySolver;
class btSerializer;

typedef btAlignedObjectArray<btSoftBody*> btSoftBodyArray;

/// A btDiscreteDynamicsWorld whose substeps also predict, collide and solve its soft bodies.
class btSoftRigidDynamicsWorld : public btDiscreteDynamicsWorld
{
	btSoftBodyArray m_softBodies;
	int m_drawFlags;
	bool m_drawNodeTree;
	bool m_drawFaceTree;
	bool m_drawClusterTree;
	btSoftBodyWorldInfo m_sbi;
	btSoftBodySolver* m_softBodySolver;
	bool m_ownsSolver;

protected:
	/// The rigid bodies' prediction, then the soft bodies' (their bounds then reach the broadphase).
	virtual void predictUnconstraintMotion(btScalar timeStep);
	/// The rigid substep, then the soft bodies' constraints and contacts.
	virtual void internalSingleStepSimulation(btScalar timeStep);
	/// Solves the soft bodies' constraints and contacts over timeStep.
	void solveSoftBodiesConstraints(btScalar timeStep);
	/// Writes each soft body as a btSoftBodyFloatData chunk (BT_SOFTBODY_CODE) with its parts.
	void serializeSoftBodies(btSerializer* serializer);

public:
	/// A world on these parts (not owned); softBodySolver 0 makes a btDefaultSoftBodySolver (owned).
	btSoftRigidDynamicsWorld(btDispatcher* dispatcher, btBroadphaseInterface* pairCache,
	                         btConstraintSolver* constraintSolver, btCollisionConfiguration* collisionConfiguration,
	                         btSoftBodySolver* softBodySolver = 0);
	virtual ~btSoftRigidDynamicsWorld();

	/// Draws the rigid world, then each soft body with getDrawFlags().
	virtual void debugDrawWorld();
	/// Adds a soft body (not owned) with a collision filter.
	void addSoftBody(btSoftBody* body, int collisionFilterGroup = btBroadphaseProxy::DefaultFilter,
	                 int collisionFilterMask = btBroadphaseProxy::AllFilter);
	/// Removes a soft body (the caller deletes it).
	void removeSoftBody(btSoftBody* body);
	/// Removes any collision object; soft bodies through removeSoftBody.
	virtual void removeCollisionObject(btCollisionObject* collisionObject);

	/// btSoftBodyHelpers' fDrawFlags for debugDrawWorld.
	int getDrawFlags() const { return m_drawFlags; }
	/// Sets the draw flags.
	void setDrawFlags(int f) { m_drawFlags = f; }
	/// The information shared by the soft bodies of this world.
	btSoftBodyWorldInfo& getWorldInfo() { return m_sbi; }
	/// The information shared by the soft bodies of this world.
	const btSoftBodyWorldInfo& getWorldInfo() const { return m_sbi; }
	/// BT_SOFT_RIGID_DYNAMICS_WORLD.
	virtual btDynamicsWorldType getWorldType() const { return BT_SOFT_RIGID_DYNAMICS_WORLD; }
	/// The soft bodies, in the order added.
	btSoftBodyArray& getSoftBodyArray() { return m_softBodies; }
	/// The soft bodies, in the order added.
	const btSoftBodyArray& getSoftBodyArray() const { return m_softBodies; }

	/// Writes the world into serializer as a complete .bullet file: the rigid world's content, then the soft
	/// bodies (docs/serialization.md, "Soft bodies").
	virtual void serialize(btSerializer* serializer);

	/// Ray test of rigid objects and soft bodies' faces (a soft hit reports the face in m_triangleIndex).
	virtual void rayTest(const btVector3& rayFromWorld, const btVector3& rayToWorld,
	                     RayResultCallback& resultCallback) const;
	/// One object against the ray: soft bodies by their faces, the rest as btCollisionWorld does.
	static void rayTestSingle(const btTransform& rayFromTrans, const btTransform& rayToTrans,
	                          btCollisionObject* collisionObject, const btCollisionShape* collisionShape,
	                          const btTransform& colObjWorldTransform, RayResultCallback& resultCallback);
};

#endif  // BT_SOFT_RIGID_DYNAMICS_WORLD_H
