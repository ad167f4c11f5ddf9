// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btDiscreteDynamicsWorld::setApplySpeculativeContactRestitution: the world's predictive manifolds (which
// only a subclass makes in Caliber, as Bullet's CCD does) bounce with their bodies' combined restitution
// when it is on, and keep the restitution they were made with when it is off; the dispatcher's own
// contacts, speculative or touching, are not affected.

#include <gtest/gtest.h>

#include "BulletDynamics/Dynamics/btSpeculativeContactRestitution.h"
#include "btBulletDynamicsCommon.h"

namespace
{
const btScalar kGravity = btScalar(9.81);
const btScalar kRadius = btScalar(0.5);
const btScalar kStep = btScalar(1. / 60.);

// A world whose only contact between the ball and the ground is a predictive one made each substep as
// Bullet's createPredictiveContactsInternal makes it: the closest points along the ground's normal, no
// restitution. The dispatcher is told not to collide the pair, so nothing else holds the ball.
class PredictiveGroundWorld : public btDiscreteDynamicsWorld
{
public:
	using btDiscreteDynamicsWorld::btDiscreteDynamicsWorld;
	btRigidBody* ball = nullptr;
	btRigidBody* ground = nullptr;
	btScalar groundTop = 0;
	bool addNullEntry = false;

protected:
	void createPredictiveContacts(btScalar timeStep) override
	{
		btDiscreteDynamicsWorld::createPredictiveContacts(timeStep);
		const btVector3 centre = ball->getWorldTransform().getOrigin();
		const btVector3 onBall = centre - btVector3(0, kRadius, 0);
		const btVector3 onGround(centre.x(), groundTop, centre.z());
		btPersistentManifold* manifold = m_dispatcher1->getNewManifold(ball, ground);
		btManifoldPoint point(ball->getWorldTransform().invXform(onBall),
		                      ground->getWorldTransform().invXform(onGround), btVector3(0, 1, 0),
		                      onBall.y() - groundTop);
		point.m_positionWorldOnA = onBall;
		point.m_positionWorldOnB = onGround;
		point.m_combinedFriction = btManifoldResult::calculateCombinedFriction(ball, ground);
		point.m_combinedRestitution = 0;  // as Bullet's predictive contacts
		manifold->addManifoldPoint(point, true);
		m_predictiveManifolds.push_back(manifold);
	}
};

struct Drop
{
	btScalar lowest;   // lowest the ball's bottom went, m above the ground
	btScalar rebound;  // highest the bottom rose after the ball first stopped falling, m above the ground
};

// Drops the ball (restitution e, ground restitution 1) with its bottom at height above the ground and
// follows it until its first rebound's apex (or 1 s after it stopped falling).
Drop dropOnPredictiveContact(bool applyRestitution, btScalar e, btScalar height)
{
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	PredictiveGroundWorld world(&dispatcher, &broadphase, &solver, &configuration);
	world.setGravity(btVector3(0, -kGravity, 0));
	world.setApplySpeculativeContactRestitution(applyRestitution);

	btBoxShape groundShape(btVector3(50, 1, 50));
	btRigidBody ground(0, nullptr, &groundShape);
	ground.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0)));
	ground.setRestitution(1);
	btSphereShape ballShape(kRadius);
	btVector3 inertia;
	ballShape.calculateLocalInertia(1, inertia);
	btRigidBody ball(1, nullptr, &ballShape, inertia);
	ball.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, height + kRadius, 0)));
	ball.setRestitution(e);
	ball.setActivationState(DISABLE_DEACTIVATION);
	ball.setIgnoreCollisionCheck(&ground, true);
	world.addRigidBody(&ground);
	world.addRigidBody(&ball);
	world.ball = &ball;
	world.ground = &ground;

	Drop drop = {height, 0};
	bool stopped = false;
	int stepsAfterStop = 0;
	btScalar previousVy = 0;
	for (int i = 0; i < int(btScalar(4) / kStep); ++i)
	{
		world.stepSimulation(kStep, 0, kStep);
		const btScalar bottom = ball.getWorldTransform().getOrigin().y() - kRadius;
		const btScalar vy = ball.getLinearVelocity().y();
		drop.lowest = btMin(drop.lowest, bottom);
		if (!stopped && vy >= btScalar(0) && previousVy < btScalar(0)) stopped = true;
		if (stopped)
		{
			drop.rebound = btMax(drop.rebound, bottom);
			if ((previousVy > btScalar(0) && vy <= btScalar(0)) || ++stepsAfterStop > 60) break;
		}
		previousVy = vy;
	}
	world.removeRigidBody(&ball);
	world.removeRigidBody(&ground);
	return drop;
}
}  // namespace

TEST(SpeculativeContactRestitution, PredictiveContactsDoNotBounceByDefault)
{
	// The predictive contact alone stops the ball at the surface (it never sinks by more than one
	// step's fall under gravity, g h^2) and, carrying no restitution, does not bounce it.
	const Drop drop = dropOnPredictiveContact(false, btScalar(0.8), 2);
	EXPECT_GT(drop.lowest, -kGravity * kStep * kStep);
	EXPECT_LT(drop.rebound, kGravity * kStep * kStep);
}

TEST(SpeculativeContactRestitution, PredictiveContactsBounceToRestitutionSquaredTimesTheDropWhenApplied)
{
	// With the flag the predictive point takes the combined restitution 0.8 * 1 and the solver's
	// restitution pass bounces it like any contact: e^2 h, within 3 % as the dispatcher's contacts
	// (RestitutionScenarioTest), at impacts falling at several phases within a step.
	const btScalar e = btScalar(0.8);
	const btScalar impactSpeed = btSqrt(2 * kGravity * 2);
	for (int phase = 0; phase < 20; phase += 5)
	{
		const btScalar height = 2 + impactSpeed * kStep * btScalar(phase) / btScalar(20);
		const Drop drop = dropOnPredictiveContact(true, e, height);
		EXPECT_NEAR(drop.rebound, e * e * height, btScalar(0.03) * e * e * height) << "phase " << phase << "/20";
		EXPECT_GT(drop.lowest, -kGravity * kStep * kStep) << "phase " << phase << "/20";
	}
}

TEST(SpeculativeContactRestitution, UsesTheDefaultCombinationWhenTheCallbackIsNull)
{
	// Misuse: a null gCalculateCombinedRestitutionCallback. The predictive points take the product of the
	// restitutions, as the default callback gives.
	CalculateCombinedCallback saved = gCalculateCombinedRestitutionCallback;
	gCalculateCombinedRestitutionCallback = nullptr;
	const Drop drop = dropOnPredictiveContact(true, btScalar(0.5), 2);
	gCalculateCombinedRestitutionCallback = saved;
	EXPECT_NEAR(drop.rebound, btScalar(0.25) * 2, btScalar(0.03) * btScalar(0.25) * 2);
}

TEST(SpeculativeContactRestitution, DispatcherContactsBounceTheSameWithTheFlagOnOrOff)
{
	// Caliber's own speculative contacts are the dispatcher's: they bounce either way, bit for bit.
	btVector3 finalPosition[2];
	for (int flag = 0; flag < 2; ++flag)
	{
		btDefaultCollisionConfiguration configuration;
		btCollisionDispatcher dispatcher(&configuration);
		btDbvtBroadphase broadphase;
		btSequentialImpulseConstraintSolver solver;
		btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
		world.setGravity(btVector3(0, -kGravity, 0));
		world.setApplySpeculativeContactRestitution(flag != 0);
		btBoxShape groundShape(btVector3(50, 1, 50));
		btRigidBody ground(0, nullptr, &groundShape);
		ground.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0)));
		ground.setRestitution(1);
		btSphereShape ballShape(kRadius);
		btRigidBody ball(1, nullptr, &ballShape, btVector3(btScalar(0.1), btScalar(0.1), btScalar(0.1)));
		ball.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, 3, 0)));
		ball.setRestitution(btScalar(0.8));
		world.addRigidBody(&ground);
		world.addRigidBody(&ball);
		btScalar highestAfterBounce = 0;
		for (int i = 0; i < 120; ++i)
		{
			world.stepSimulation(kStep, 0, kStep);
			if (i > 50) highestAfterBounce = btMax(highestAfterBounce, ball.getWorldTransform().getOrigin().y());
		}
		EXPECT_GT(highestAfterBounce, btScalar(1)) << "flag " << flag << ": the ball bounced";
		finalPosition[flag] = ball.getWorldTransform().getOrigin();
		world.removeRigidBody(&ball);
		world.removeRigidBody(&ground);
	}
	EXPECT_EQ(finalPosition[0], finalPosition[1]);
}

TEST(SpeculativeContactRestitution, NullEntriesAndManifoldsWithoutBodiesAreSkipped)
{
	// Misuse of the array a subclass fills: a null entry and a manifold without bodies change nothing and
	// do not stop the manifolds after them from getting their restitution.
	btSphereShape shape(kRadius);
	btRigidBody a(1, nullptr, &shape), b(1, nullptr, &shape);
	a.setRestitution(btScalar(0.5));
	b.setRestitution(btScalar(0.6));
	btPersistentManifold bodiless(nullptr, nullptr, 0, btScalar(0.02), btScalar(0.02));
	btPersistentManifold real(&a, &b, 0, btScalar(0.02), btScalar(0.02));
	btManifoldPoint point(btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(0, 1, 0), btScalar(0.01));
	bodiless.addManifoldPoint(point);
	real.addManifoldPoint(point);
	btAlignedObjectArray<btPersistentManifold*> manifolds;
	manifolds.push_back(nullptr);
	manifolds.push_back(&bodiless);
	manifolds.push_back(&real);
	caliber::giveSpeculativeContactsRestitution(manifolds);
	EXPECT_EQ(bodiless.getContactPoint(0).m_combinedRestitution, btScalar(0));
	EXPECT_FLOAT_EQ(real.getContactPoint(0).m_combinedRestitution, btScalar(0.3));
}
