// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SIMPLE_DYNAMICS_WORLD_H
#define BT_SIMPLE_DYNAMICS_WORLD_H

#include "BulletDynamics/Dynamics/btDynamicsWorld.h"
#include "LinearMath/btAlignedObjectArray.h"

class btDispatcher;
class btOverlappingPairCache;
class btConstraintSolver;

/// The minimal rigid-body world, for tests and teaching: one variable step per stepSimulation call (no
/// substeps, no interpolation), every manifold solved in one group, no islands, no sleeping, no CCD, no
/// actions. btDiscreteDynamicsWorld is the one to use.
class btSimpleDynamicsWorld : public btDynamicsWorld
{
protected:
	btConstraintSolver* m_constraintSolver;
	bool m_ownsConstraintSolver;
	btVector3 m_gravity;

	void predictUnconstraintMotion(btScalar timeStep);
	void integrateTransforms(btScalar timeStep);

public:
	/// The solver is not owned (it must not be null).
	btSimpleDynamicsWorld(btDispatcher* dispatcher, btBroadphaseInterface* pairCache,
	                      btConstraintSolver* constraintSolver, btCollisionConfiguration* collisionConfiguration);
	virtual ~btSimpleDynamicsWorld();

	/// One step of timeStep seconds (maxSubSteps and fixedTimeStep are ignored); returns 1, or 0 for a
	/// zero or invalid time step.
	int stepSimulation(btScalar timeStep, int maxSubSteps = 1,
	                   btScalar fixedTimeStep = btScalar(1.) / btScalar(60.)) override;

	void setGravity(const btVector3& gravity) override;
	btVector3 getGravity() const override;

	void addRigidBody(btRigidBody* body) override;
	void addRigidBody(btRigidBody* body, int group, int mask) override;
	void removeRigidBody(btRigidBody* body) override;

	void debugDrawWorld() override;

	/// Actions need btDiscreteDynamicsWorld; here they are refused with a warning.
	void addAction(btActionInterface* action) override;
	void removeAction(btActionInterface* action) override;

	void removeCollisionObject(btCollisionObject* collisionObject) override;

	void updateAabbs() override;

	void synchronizeMotionStates() override;

	void setConstraintSolver(btConstraintSolver* solver) override;
	btConstraintSolver* getConstraintSolver() override;

	btDynamicsWorldType getWorldType() const override { return BT_SIMPLE_DYNAMICS_WORLD; }

	void clearForces() override;
};

#endif  // BT_SIMPLE_DYNAMICS_WORLD_H
