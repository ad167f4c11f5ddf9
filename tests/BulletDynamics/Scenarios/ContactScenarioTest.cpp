// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Contacts through the whole world: resting, bouncing, sliding and sticking, collisions conserving
// momentum, and the impulses the solver leaves in the manifolds.

#include <gtest/gtest.h>

#include "../Dynamics/DynamicsWorldTestUtil.h"

using caliber_test::TestWorld;

namespace
{
const btScalar kStep = btScalar(1. / 60.);
const btScalar kGravity = 10;
// The distance gravity moves a body in one step, g h^2: the scale of what one semi-implicit Euler step
// can push a resting body into its support before the contact answers.
const btScalar kOneStepSag = kGravity * kStep * kStep;
}  // namespace

TEST(ContactScenario, RestingSphereSettlesAtItsRadiusOnABox)
{
	TestWorld w;
	w.addGround();
	const btScalar radius = btScalar(0.5);
	btRigidBody* ball = w.addBody(w.shape<btSphereShape>(radius), 1, btVector3(0, 2, 0));
	w.run(180);
	EXPECT_NEAR(ball->getCenterOfMassPosition().y(), radius, kOneStepSag);
	EXPECT_NEAR(ball->getLinearVelocity().length(), 0, kGravity * kStep);
}

TEST(ContactScenario, RestingSphereSettlesAtItsRadiusOnAPlane)
{
	TestWorld w;
	btRigidBody* plane = w.addBody(w.shape<btStaticPlaneShape>(btVector3(0, 1, 0), btScalar(0)), 0, btVector3(0, 0, 0));
	plane->setRestitution(1);
	const btScalar radius = btScalar(0.25);
	btRigidBody* ball = w.addBody(w.shape<btSphereShape>(radius), 1, btVector3(3, 1, -2));
	w.run(180);
	EXPECT_NEAR(ball->getCenterOfMassPosition().y(), radius, kOneStepSag);
}

TEST(ContactScenario, RestingBodyCarriesItsWeightInTheManifold)
{
	// At rest the normal impulses of one step add up to the weight times the step, m g h.
	TestWorld w;
	w.addGround();
	const btScalar mass = 3;
	w.addBody(w.shape<btBoxShape>(btVector3(0.5, 0.5, 0.5)), mass, btVector3(0, btScalar(0.5), 0));
	w.run(60);
	btScalar total = 0;
	int points = 0;
	for (int i = 0; i < w.dispatcher()->getNumManifolds(); ++i)
	{
		btPersistentManifold* manifold = w.dispatcher()->getManifoldByIndexInternal(i);
		for (int j = 0; j < manifold->getNumContacts(); ++j)
		{
			total += manifold->getContactPoint(j).getAppliedImpulse();
			++points;
		}
	}
	EXPECT_EQ(points, 4);
	// The solver's iterations converge to within a few percent of the exact weight.
	EXPECT_NEAR(total, mass * kGravity * kStep, btScalar(0.05) * mass * kGravity * kStep);
}

TEST(ContactScenario, BounceHeightsShrinkByRestitutionSquared)
{
	// A ball with restitution e on a ground with restitution 1 (combined e) leaves each bounce with e times
	// its arrival speed, so each apex height (above the contact height) is e^2 times the last. The apex is
	// sampled once per step: the error is at most v h per sample (about 0.03 of the first height here).
	TestWorld w;
	w.addGround(btScalar(0), btScalar(1));
	const btScalar e = btScalar(0.8);
	const btScalar radius = btScalar(0.25);
	btRigidBody* ball = w.addBody(w.shape<btSphereShape>(radius), 1, btVector3(0, btScalar(2.25), 0));
	ball->setRestitution(e);
	ball->setFriction(0);
	std::vector<btScalar> apexes;
	btScalar previousVy = 0;
	for (int i = 0; i < 600 && apexes.size() < 3; ++i)
	{
		w.run(1);
		const btScalar vy = ball->getLinearVelocity().y();
		if (previousVy > 0 && vy <= 0) apexes.push_back(ball->getCenterOfMassPosition().y() - radius);
		previousVy = vy;
	}
	ASSERT_EQ(apexes.size(), 3u);
	EXPECT_NEAR(apexes[0] / btScalar(2.0), e * e, btScalar(0.04));
	EXPECT_NEAR(apexes[1] / apexes[0], e * e, btScalar(0.04));
	EXPECT_NEAR(apexes[2] / apexes[1], e * e, btScalar(0.06));
}

namespace
{
// A box on a horizontal floor under gravity tilted by angle: the same as a box on a slope of that angle.
btScalar slideDistance(btScalar angleRadians, btScalar mu, btScalar seconds, btScalar* speedOut,
                       int extraSolverMode = 0)
{
	TestWorld w(btVector3(kGravity * btSin(angleRadians), -kGravity * btCos(angleRadians), 0));
	w.world()->getSolverInfo().m_solverMode |= extraSolverMode;
	w.addGround(btScalar(1), btScalar(0));  // combined friction = mu * 1
	btRigidBody* box = w.addBody(w.shape<btBoxShape>(btVector3(0.5, 0.25, 0.5)), 1, btVector3(0, btScalar(0.25), 0));
	box->setFriction(mu);
	box->setActivationState(DISABLE_DEACTIVATION);
	w.run(int(seconds / kStep + btScalar(0.5)));
	if (speedOut) *speedOut = box->getLinearVelocity().x();
	return box->getCenterOfMassPosition().x();
}
}  // namespace

TEST(ContactScenario, BoxOnSlopeSticksBelowTheFrictionAngle)
{
	// mu = 0.5: the friction angle is atan(0.5) = 26.6 degrees. At 20 degrees it holds: over two seconds
	// it may creep no more than one step of the free acceleration would move it (g sin h^2 per step,
	// a few millimetres in all).
	const btScalar creep = slideDistance(btScalar(20) * SIMD_RADS_PER_DEG, btScalar(0.5), 2, 0);
	EXPECT_LT(btFabs(creep), btScalar(0.01));
}

TEST(ContactScenario, BoxOnSlopeSlidesAboveTheFrictionAngleWithTheCoulombAcceleration)
{
	// At 40 degrees with mu = 0.5 it slides with a = g (sin - mu cos) = 2.60 m/s^2, so after t seconds
	// v = a t. The discrete Coulomb model reproduces that to the solver's convergence: 2 %.
	const btScalar angle = btScalar(40) * SIMD_RADS_PER_DEG;
	const btScalar mu = btScalar(0.5);
	const btScalar a = kGravity * (btSin(angle) - mu * btCos(angle));
	btScalar speed = 0;
	slideDistance(angle, mu, 1, &speed);
	EXPECT_NEAR(speed, a * 1, btScalar(0.02) * a);
	// The same with two friction directions: the second, across the sliding, carries no impulse.
	slideDistance(angle, mu, 1, &speed, SOLVER_USE_2_FRICTION_DIRECTIONS);
	EXPECT_NEAR(speed, a * 1, btScalar(0.02) * a);
	// And both hold the box below the friction angle.
	EXPECT_LT(btFabs(slideDistance(btScalar(20) * SIMD_RADS_PER_DEG, mu, 2, 0, SOLVER_USE_2_FRICTION_DIRECTIONS)),
	          btScalar(0.01));
}

TEST(ContactScenario, CollisionsConserveLinearAndAngularMomentum)
{
	// No gravity, no static bodies: whatever the contacts do, total linear momentum and total angular
	// momentum about the origin (spin plus orbital) are unchanged, to float rounding.
	TestWorld w(btVector3(0, 0, 0));
	// Split impulse corrects penetration by moving positions, not velocities; moving two bodies apart
	// shifts the orbital part of angular momentum (r x p) by up to depth times momentum. Velocities are
	// what the conservation laws speak about, so this test corrects penetration through velocities.
	w.world()->getSolverInfo().m_splitImpulse = 0;
	// A cube and a sphere: both have isotropic inertia, so in free flight I w is exactly constant (no
	// gyroscopic term to integrate) and any change of angular momentum would come from the contacts.
	btRigidBody* a = w.addBody(w.shape<btBoxShape>(btVector3(0.4, 0.4, 0.4)), 2, btVector3(-2, btScalar(0.2), 0));
	btRigidBody* b = w.addBody(w.shape<btSphereShape>(btScalar(0.5)), 1, btVector3(2, -btScalar(0.1), btScalar(0.1)));
	a->setLinearVelocity(btVector3(3, 0, 0));
	a->setAngularVelocity(btVector3(0, 0, 1));
	b->setLinearVelocity(btVector3(-4, btScalar(0.3), 0));
	a->setRestitution(btScalar(0.5));
	b->setRestitution(btScalar(0.5));
	auto momentum = [&]()
	{
		btVector3 p(0, 0, 0);
		for (btRigidBody* body : w.bodies()) p += body->getLinearVelocity() * body->getMass();
		return p;
	};
	auto angularMomentum = [&]()
	{
		btVector3 l(0, 0, 0);
		for (btRigidBody* body : w.bodies())
		{
			const btMatrix3x3& r = body->getWorldTransform().getBasis();
			const btMatrix3x3 inertiaWorld = r.scaled(body->getLocalInertia()) * r.transpose();
			l += inertiaWorld * body->getAngularVelocity();
			l += body->getCenterOfMassPosition().cross(body->getLinearVelocity() * body->getMass());
		}
		return l;
	};
	const btVector3 p0 = momentum();
	const btVector3 l0 = angularMomentum();
	bool touched = false;
	for (int i = 0; i < 90; ++i)
	{
		w.run(1);
		touched = touched || (w.dispatcher()->getNumManifolds() > 0 &&
		                      w.dispatcher()->getManifoldByIndexInternal(0)->getNumContacts() > 0);
	}
	ASSERT_TRUE(touched);
	// They did collide: the box no longer moves at its initial speed.
	EXPECT_GT(btFabs(a->getLinearVelocity().x() - 3), btScalar(0.5));
	const btVector3 p1 = momentum();
	const btVector3 l1 = angularMomentum();
	for (int axis = 0; axis < 3; ++axis)
	{
		// Float rounding of sums of a few dozen products of order 1-10.
		EXPECT_NEAR(p1[axis], p0[axis], 1e-4) << "linear momentum axis " << axis;
		EXPECT_NEAR(l1[axis], l0[axis], 1e-4) << "angular momentum axis " << axis;
	}
}

TEST(ContactScenario, KinematicBodyPushesADynamicOne)
{
	TestWorld w;
	w.addGround(btScalar(0), btScalar(0));
	btCollisionShape* box = w.shape<btBoxShape>(btVector3(0.5, 0.5, 0.5));
	btRigidBody* pusher = w.addBody(box, 0, btVector3(-2, btScalar(0.5), 0));
	pusher->setCollisionFlags(pusher->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
	pusher->setActivationState(DISABLE_DEACTIVATION);
	btRigidBody* pushed = w.addBody(box, 1, btVector3(0, btScalar(0.5), 0));
	pushed->setFriction(0);
	const btScalar speed = 2;
	btTransform pose = pusher->getWorldTransform();
	for (int i = 0; i < 120; ++i)
	{
		pose.getOrigin() += btVector3(speed * kStep, 0, 0);
		pusher->getMotionState()->setWorldTransform(pose);
		w.run(1);
	}
	// The kinematic body followed its motion state exactly, whatever it touched.
	EXPECT_NEAR(pusher->getCenterOfMassPosition().x(), -2 + 120 * speed * kStep, 1e-4);
	// The dynamic box is ahead of it and moves with it (no friction: it keeps at least the pusher's speed).
	EXPECT_GT(pushed->getCenterOfMassPosition().x(), pusher->getCenterOfMassPosition().x() + btScalar(0.95));
	EXPECT_GT(pushed->getLinearVelocity().x(), speed * btScalar(0.95));
}
