// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Bullet's protected and public interface of btSequentialImpulseConstraintSolver, as a subclass written
// for Bullet uses it: an overridden convertContacts is called, replaced row solvers are used for every
// row (a do-nothing row solver lets a box fall through the ground), restitutionCurve and
// applyAnisotropicFriction mean what Bullet says, and anisotropic friction acts in the world.

#include <gtest/gtest.h>

#include <memory>

#include "btBulletDynamicsCommon.h"

namespace
{
// A subclass in Bullet's style: it counts the manifolds it converts and reaches Bullet's protected helpers.
class CountingSolver : public btSequentialImpulseConstraintSolver
{
public:
	int convertedManifolds = 0;
	void convertContacts(btPersistentManifold** manifoldPtr, int numManifolds,
	                     const btContactSolverInfo& infoGlobal) override
	{
		convertedManifolds += numManifolds;
		btSequentialImpulseConstraintSolver::convertContacts(manifoldPtr, numManifolds, infoGlobal);
	}
	btScalar curve(btScalar velocity, btScalar restitution, btScalar threshold)
	{
		return restitutionCurve(velocity, restitution, threshold);
	}
	static void anisotropic(btCollisionObject* object, btVector3& direction, int mode)
	{
		applyAnisotropicFriction(object, direction, mode);
	}
};

// A world with a static ground (top at y = 0) and a unit box resting on it, with the given solver.
struct BoxOnGround
{
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher{&configuration};
	btDbvtBroadphase broadphase;
	std::unique_ptr<btDiscreteDynamicsWorld> world;
	btBoxShape groundShape{btVector3(50, 1, 50)};
	btBoxShape boxShape{btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5))};
	std::unique_ptr<btRigidBody> ground, box;

	explicit BoxOnGround(btConstraintSolver* solver)
	{
		world.reset(new btDiscreteDynamicsWorld(&dispatcher, &broadphase, solver, &configuration));
		world->setGravity(btVector3(0, -10, 0));
		ground.reset(new btRigidBody(0, 0, &groundShape));
		ground->setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0)));
		world->addRigidBody(ground.get());
		btVector3 inertia;
		boxShape.calculateLocalInertia(1, inertia);
		box.reset(new btRigidBody(1, 0, &boxShape, inertia));
		box->setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(0.5), 0)));
		box->setActivationState(DISABLE_DEACTIVATION);
		world->addRigidBody(box.get());
	}
	~BoxOnGround()
	{
		world->removeRigidBody(box.get());
		world->removeRigidBody(ground.get());
	}
	void run(int steps)
	{
		for (int i = 0; i < steps; ++i) world->stepSimulation(btScalar(1. / 60.), 0);
	}
};

int g_genericCalls = 0;
int g_lowerLimitCalls = 0;
btSingleConstraintRowSolver g_realGeneric = 0;
btSingleConstraintRowSolver g_realLowerLimit = 0;

btScalar countingGeneric(btSolverBody& a, btSolverBody& b, const btSolverConstraint& row)
{
	++g_genericCalls;
	return g_realGeneric(a, b, row);
}
btScalar countingLowerLimit(btSolverBody& a, btSolverBody& b, const btSolverConstraint& row)
{
	++g_lowerLimitCalls;
	return g_realLowerLimit(a, b, row);
}
btScalar doNothing(btSolverBody&, btSolverBody&, const btSolverConstraint&) { return 0; }
}  // namespace

TEST(SequentialImpulseSolverInterface, OverriddenConvertContactsIsCalledAndContactsStillHold)
{
	CountingSolver solver;
	BoxOnGround scene(&solver);
	scene.run(60);
	EXPECT_GT(solver.convertedManifolds, 0);
	// Resting on the ground: its centre at half its size, within the solver's millimetre slop.
	EXPECT_NEAR(scene.box->getCenterOfMassPosition().y(), 0.5, 0.005);
}

TEST(SequentialImpulseSolverInterface, ReplacedRowSolversAreUsedForEveryRow)
{
	btSequentialImpulseConstraintSolver solver;
	g_realGeneric = solver.getScalarConstraintRowSolverGeneric();
	g_realLowerLimit = solver.getScalarConstraintRowSolverLowerLimit();
	ASSERT_EQ(solver.getActiveConstraintRowSolverGeneric(), g_realGeneric);
	ASSERT_EQ(solver.getActiveConstraintRowSolverLowerLimit(), g_realLowerLimit);
	solver.setConstraintRowSolverGeneric(&countingGeneric);
	solver.setConstraintRowSolverLowerLimit(&countingLowerLimit);
	g_genericCalls = g_lowerLimitCalls = 0;
	BoxOnGround scene(&solver);
	scene.run(60);
	// Contact rows go through the lower-limit solver, friction rows through the generic one.
	EXPECT_GT(g_lowerLimitCalls, 0);
	EXPECT_GT(g_genericCalls, 0);
	// Delegating to Caliber's kernels, the box rests as with the built-in sweep.
	EXPECT_NEAR(scene.box->getCenterOfMassPosition().y(), 0.5, 0.005);
}

TEST(SequentialImpulseSolverInterface, ARowSolverThatDoesNothingLetsTheBoxFallThrough)
{
	btSequentialImpulseConstraintSolver solver;
	solver.setConstraintRowSolverGeneric(&doNothing);
	solver.setConstraintRowSolverLowerLimit(&doNothing);
	BoxOnGround scene(&solver);
	// Speculative contacts and split impulses still push (they are not velocity rows), so the box is not in
	// free fall; but without the velocity rows it cannot stay at rest on the ground: after a second it has
	// sunk far below the 5 mm slop a working solver keeps.
	scene.run(60);
	EXPECT_LT(scene.box->getCenterOfMassPosition().y(), 0.4);
}

TEST(SequentialImpulseSolverInterface, RestitutionCurveIsBulletsThresholdedRebound)
{
	CountingSolver solver;
	// Approaching at 2 m/s with e = 0.5: rebound target 1 m/s; slower than the 1 m/s threshold: none.
	EXPECT_FLOAT_EQ(solver.curve(-2, btScalar(0.5), 1), 1);
	EXPECT_FLOAT_EQ(solver.curve(btScalar(-0.5), btScalar(0.5), 1), 0);
}

TEST(SequentialImpulseSolverInterface, AnisotropicFrictionScalesTheDirectionInTheObjectsFrame)
{
	btCollisionObject object;
	// Turned 90 degrees about y: the object's x axis is the world's -z.
	object.setWorldTransform(btTransform(btQuaternion(btVector3(0, 1, 0), SIMD_HALF_PI)));
	btVector3 direction(0, 0, 1);
	CountingSolver::anisotropic(&object, direction, btCollisionObject::CF_ANISOTROPIC_FRICTION);
	EXPECT_NEAR(direction.length(), 1, 1e-6) << "without anisotropic friction set, unchanged";
	object.setAnisotropicFriction(btVector3(0, 1, 1));
	CountingSolver::anisotropic(&object, direction, btCollisionObject::CF_ANISOTROPIC_FRICTION);
	EXPECT_NEAR(direction.length(), 0, 1e-6) << "world z is the object's x, whose factor is 0";
	btVector3 across(1, 0, 0);
	CountingSolver::anisotropic(&object, across, btCollisionObject::CF_ANISOTROPIC_FRICTION);
	EXPECT_NEAR(across.x(), 1, 1e-6) << "world x is the object's z, whose factor is 1";
}

TEST(SequentialImpulseSolverInterface, AnisotropicFrictionLetsABoxSlideFreelyAlongItsFrictionlessAxis)
{
	for (int axis = 0; axis < 2; ++axis)
	{
		SCOPED_TRACE(axis == 0 ? "sliding along the frictionless x" : "sliding along z, with friction");
		btSequentialImpulseConstraintSolver solver;
		BoxOnGround scene(&solver);
		scene.box->setFriction(btScalar(0.5));
		scene.ground->setFriction(btScalar(1));  // combined friction: the product, 0.5
		scene.box->setAnisotropicFriction(btVector3(0, 1, 1));
		scene.run(10);
		const btVector3 velocity = axis == 0 ? btVector3(4, 0, 0) : btVector3(0, 0, 4);
		scene.box->setLinearVelocity(velocity);
		scene.run(30);
		const btScalar speed = scene.box->getLinearVelocity().length();
		if (axis == 0)
		{
			// No friction along the box's x: it keeps its 4 m/s (0.5 s of mu g = 2.5 m/s/s would take 1.25).
			EXPECT_GT(speed, btScalar(3.9));
		}
		else
		{
			// Coulomb friction along z: 4 - mu g t = 4 - 0.5 * 10 * 0.5 = 1.5 m/s, within a step's worth.
			EXPECT_NEAR(speed, 1.5, 0.1);
		}
	}
}
