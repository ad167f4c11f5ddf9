// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_DYNAMICS_WORLD_H
#define BT_DYNAMICS_WORLD_H

#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletDynamics/ConstraintSolver/btContactSolverInfo.h"
#include "LinearMath/btWarningHook.h"

class btActionInterface;
class btConstraintSolver;
class btDynamicsWorld;
class btRigidBody;
class btTypedConstraint;

/// Called once per internal substep (before or after it, see setInternalTickCallback).
typedef void (*btInternalTickCallback)(btDynamicsWorld* world, btScalar timeStep);

/// Which world a btDynamicsWorld is (Bullet's numbering).
enum btDynamicsWorldType
{
	BT_SIMPLE_DYNAMICS_WORLD = 1,
	BT_DISCRETE_DYNAMICS_WORLD = 2,
	BT_CONTINUOUS_DYNAMICS_WORLD = 3,
	BT_SOFT_RIGID_DYNAMICS_WORLD = 4,
	BT_GPU_DYNAMICS_WORLD = 5,
	BT_SOFT_MULTIBODY_DYNAMICS_WORLD = 6,
	BT_DEFORMABLE_MULTIBODY_DYNAMICS_WORLD = 7
};

/// A collision world whose objects move: rigid bodies, actions and a constraint solver.
class btDynamicsWorld : public btCollisionWorld
{
protected:
	btInternalTickCallback m_internalTickCallback;
	btInternalTickCallback m_internalPreTickCallback;
	void* m_worldUserInfo;
	btContactSolverInfo m_solverInfo;

public:
	btDynamicsWorld(btDispatcher* dispatcher, btBroadphaseInterface* broadphase,
	                btCollisionConfiguration* collisionConfiguration)
	    : btCollisionWorld(dispatcher, broadphase, collisionConfiguration),
	      m_internalTickCallback(0),
	      m_internalPreTickCallback(0),
	      m_worldUserInfo(0)
	{
	}

	virtual ~btDynamicsWorld() {}

	/// Advances the world by timeStep seconds in fixed substeps of fixedTimeStep, at most maxSubSteps of
	/// them (0: one substep of timeStep); returns the number of substeps taken.
	virtual int stepSimulation(btScalar timeStep, int maxSubSteps = 1,
	                           btScalar fixedTimeStep = btScalar(1.) / btScalar(60.)) = 0;

	virtual void debugDrawWorld() = 0;

	/// Worlds without joints (btSimpleDynamicsWorld) refuse a joint with a warning; btDiscreteDynamicsWorld
	/// solves them.
	virtual void addConstraint(btTypedConstraint* constraint, bool disableCollisionsBetweenLinkedBodies = false)
	{
		(void)constraint;
		(void)disableCollisionsBetweenLinkedBodies;
		btAssert(!"btDynamicsWorld::addConstraint: this world does not solve joints");
		btReportWarning("Caliber: addConstraint: this world does not solve joints; the constraint is ignored\n",
		                getDebugDrawer());
	}
	virtual void removeConstraint(btTypedConstraint* constraint) { (void)constraint; }

	virtual void addAction(btActionInterface* action) = 0;
	virtual void removeAction(btActionInterface* action) = 0;

	/// The gravity acceleration given to every body (except those with BT_DISABLE_WORLD_GRAVITY).
	virtual void setGravity(const btVector3& gravity) = 0;
	virtual btVector3 getGravity() const = 0;

	/// Hands every moving body's (interpolated) transform to its motion state.
	virtual void synchronizeMotionStates() = 0;

	virtual void addRigidBody(btRigidBody* body) = 0;
	virtual void addRigidBody(btRigidBody* body, int group, int mask) = 0;
	virtual void removeRigidBody(btRigidBody* body) = 0;

	virtual void setConstraintSolver(btConstraintSolver* solver) = 0;
	virtual btConstraintSolver* getConstraintSolver() = 0;

	virtual int getNumConstraints() const { return 0; }
	virtual btTypedConstraint* getConstraint(int index)
	{
		(void)index;
		return 0;
	}
	virtual const btTypedConstraint* getConstraint(int index) const
	{
		(void)index;
		return 0;
	}

	virtual btDynamicsWorldType getWorldType() const = 0;

	/// Zeroes the accumulated forces of every body.
	virtual void clearForces() = 0;

	/// Installs the callback called after (or, with isPreTick, before) each internal substep.
	void setInternalTickCallback(btInternalTickCallback cb, void* worldUserInfo = 0, bool isPreTick = false)
	{
		if (isPreTick)
			m_internalPreTickCallback = cb;
		else
			m_internalTickCallback = cb;
		m_worldUserInfo = worldUserInfo;
	}

	void setWorldUserInfo(void* worldUserInfo) { m_worldUserInfo = worldUserInfo; }
	void* getWorldUserInfo() const { return m_worldUserInfo; }

	btContactSolverInfo& getSolverInfo() { return m_solverInfo; }
	const btContactSolverInfo& getSolverInfo() const { return m_solverInfo; }

	/// Older names for addAction/removeAction.
	virtual void addVehicle(btActionInterface* vehicle) { (void)vehicle; }
	virtual void removeVehicle(btActionInterface* vehicle) { (void)vehicle; }
	virtual void addCharacter(btActionInterface* character) { (void)character; }
	virtual void removeCharacter(btActionInterface* character) { (void)character; }
};

// clang-format off
/// File layout of btDynamicsWorldDoubleData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btDynamicsWorldDoubleData
{
	btContactSolverInfoDoubleData m_solverInfo;
	btVector3DoubleData m_gravity;
};

/// File layout of btDynamicsWorldFloatData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btDynamicsWorldFloatData
{
	btContactSolverInfoFloatData m_solverInfo;
	btVector3FloatData m_gravity;
};

// clang-format on

#endif  // BT_DYNAMICS_WORLD_H
