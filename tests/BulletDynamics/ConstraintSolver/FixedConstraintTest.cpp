// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btFixedConstraint: welded bodies move as one rigid body (exact momentum and angular momentum, a
// relative pose held within the solver's drift bound), and a welded cantilever carries its load with
// the shear force and bending moment of statics.

#include <gtest/gtest.h>

#include <cmath>

#include "BulletDynamics/ConstraintSolver/btFixedConstraint.h"
#include "JointTestUtil.h"

using caliber_test::TestWorld;

namespace
{
const btScalar kG = btScalar(10);

btTransform at(const btVector3& origin) { return btTransform(btQuaternion::getIdentity(), origin); }

// The angle of the rotation q, from its vector part |q.xyz| = sin(angle / 2) (accurate near 0, where
// acos of the scalar part is not).
btScalar turnAngle(const btQuaternion& q)
{
	const btScalar s = btSqrt(q.x() * q.x() + q.y() * q.y() + q.z() * q.z());
	return 2 * btAsin(btMin(btScalar(1), s));
}
}  // namespace

TEST(FixedConstraint, WeldedBodiesFallAndSpinAsOneRigidBody)
{
	// Two balls (1 kg and 3 kg, 1 m apart) welded at the midpoint, thrown spinning at 3 rad/s and
	// falling. The six locked rows are one exact block, so at the end of every step the pair moves as a
	// rigid body: equal angular velocities, and every impulse internal (equal and opposite at the
	// weld point), so the centre of mass falls exactly as a free particle does and the angular momentum
	// about it stays exactly what it was (spheres: no gyroscopic torque). The pose drifts only because
	// each ball moves in a straight line during the step while the pair turns: the separation grows by
	// |r| (sqrt(1 + (w h)^2) - 1) ~ |r| (w h)^2 / 2 per step, which the world's ERP removes, so it stays
	// within |r| (w h)^2 / (2 erp). The relative rotation does not drift (equal angular velocities).
	const btScalar h = btScalar(1. / 60.), m1 = 1, m2 = 3, spin = 3;
	TestWorld w(btVector3(0, -kG, 0));
	btCollisionShape* ball = w.shape<btSphereShape>(btScalar(0.2));
	btRigidBody* a = w.addBody(ball, m1, btVector3(0, 0, 0));
	btRigidBody* b = w.addBody(ball, m2, btVector3(1, 0, 0));
	btFixedConstraint* weld =
	    w.addJoint<btFixedConstraint>(true, *a, *b, at(btVector3(0.5, 0, 0)), at(btVector3(-0.5, 0, 0)));
	EXPECT_EQ(weld->getConstraintType(), D6_SPRING_2_CONSTRAINT_TYPE) << "as in Bullet";
	for (int i = 0; i < 6; ++i) EXPECT_TRUE(weld->isLimited(i));

	// A rigid motion: the centre of mass at x = 0.75 moving at V, turning at omega about a slanted axis.
	const btVector3 omega = btVector3(0.3, 0.4, 1).normalized() * spin, centreVelocity(1, 2, 0);
	const btVector3 centre0(0.75, 0, 0);
	for (btRigidBody* body : {a, b})
	{
		body->setLinearVelocity(centreVelocity + omega.cross(body->getCenterOfMassPosition() - centre0));
		body->setAngularVelocity(omega);
		body->setActivationState(DISABLE_DEACTIVATION);
	}
	auto centre = [&]() { return (a->getCenterOfMassPosition() * m1 + b->getCenterOfMassPosition() * m2) / (m1 + m2); };
	auto angularMomentum = [&]()
	{
		const btVector3 c = centre();
		const btVector3 v = (a->getLinearVelocity() * m1 + b->getLinearVelocity() * m2) / (m1 + m2);
		btVector3 L(0, 0, 0);
		for (btRigidBody* body : {a, b})
		{
			const btScalar m = 1 / body->getInvMass();
			L += (body->getCenterOfMassPosition() - c).cross(body->getLinearVelocity() - v) * m;
			L += body->getAngularVelocity() / body->getInvInertiaDiagLocal().x();
		}
		return L;
	};
	const btVector3 L0 = angularMomentum();
	const btScalar erp = w.world()->getSolverInfo().m_erp;
	const btScalar separationBound = 1 * (spin * h) * (spin * h) / (2 * erp);
	btScalar worstSeparation = 0, worstTurn = 0, worstMomentum = 0, worstSpinMismatch = 0;
	const int steps = 120;
	for (int i = 0; i < steps; ++i)
	{
		w.run(1, h);
		worstSeparation =
		    btMax(worstSeparation, btFabs((b->getCenterOfMassPosition() - a->getCenterOfMassPosition()).length() - 1));
		worstTurn = btMax(worstTurn, turnAngle(a->getOrientation().inverse() * b->getOrientation()));
		worstMomentum = btMax(worstMomentum, (angularMomentum() - L0).length());
		worstSpinMismatch = btMax(worstSpinMismatch, (a->getAngularVelocity() - b->getAngularVelocity()).length());
	}
	EXPECT_LT(worstSeparation, separationBound);
	// Float rounding: the block is solved by Gauss-Jordan on a 6x6 matrix whose condition number is 67
	// for these masses and arms, so each step's result carries up to ~1e-5 relative error on velocities
	// of a few m/s; the momentum check accumulates such roundings over 120 steps.
	EXPECT_LT(worstTurn, 1e-5);
	EXPECT_LT(worstSpinMismatch, 1e-4);
	EXPECT_LT(worstMomentum, 5e-5 * L0.length());
	// The centre of mass: semi-implicit Euler under gravity alone, y_n = v0 n h - g h^2 n (n + 1) / 2.
	const double t = steps * h;
	const btVector3 expectedCentre =
	    centre0 + centreVelocity * btScalar(t) - btVector3(0, btScalar(kG * h * h * steps * (steps + 1) / 2.0), 0);
	EXPECT_NEAR((centre() - expectedCentre).length(), 0, 1e-4);
	EXPECT_GT(turnAngle(a->getOrientation()), 0.5) << "the pair did turn";
}

TEST(FixedConstraint, WeldedCantileverCarriesItsLoadWithTheMomentOfStatics)
{
	// A beam of length L and mass m welded at one end to a static wall, with a force F pushing its tip
	// down. The wall is immovable, so the six locked rows (one exact block) cancel each step's weight
	// and load exactly: the beam does not droop at all (float rounding). The joint carries the statics
	// of a cantilever root: shear m g + F upwards and bending moment m g L / 2 + F L about z.
	// Tolerance: float rounding of the impulses (relative 1e-5).
	const btScalar h = btScalar(1. / 60.), L = 2, m = 3, load = 7;
	TestWorld w(btVector3(0, -kG, 0));
	btRigidBody* wall = w.addBody(w.shape<btBoxShape>(btVector3(0.5, 1, 1)), 0, btVector3(-0.5, 0, 0));
	btRigidBody* beam = w.addBody(w.shape<btBoxShape>(btVector3(L / 2, 0.05, 0.05)), m, btVector3(L / 2, 0, 0));
	beam->setActivationState(DISABLE_DEACTIVATION);
	btFixedConstraint* weld =
	    w.addJoint<btFixedConstraint>(true, *wall, *beam, at(btVector3(0.5, 0, 0)), at(btVector3(-L / 2, 0, 0)));
	btJointFeedback feedback;
	weld->setJointFeedback(&feedback);
	weld->enableFeedback(true);
	const btVector3 tip(L / 2, 0, 0);
	btScalar worstDroop = 0;
	for (int i = 0; i < 60; ++i)
	{
		beam->applyForce(btVector3(0, -load, 0), beam->getCenterOfMassTransform().getBasis() * tip);
		w.run(1, h);
		worstDroop = btMax(worstDroop, btFabs(beam->getCenterOfMassTransform()(tip).y()));
	}
	EXPECT_LT(worstDroop, 1e-6);
	const btScalar shear = m * kG + load;
	EXPECT_NEAR(feedback.m_appliedForceBodyB.y(), shear, 1e-5 * shear);
	EXPECT_NEAR(feedback.m_appliedForceBodyB.x(), 0, 1e-5 * shear);
	// The joint's torque on the beam about the beam's centre, less the moment of its force acting at
	// the weld point, is the moment at the weld.
	const btVector3 weldArm = btVector3(0, 0, 0) - beam->getCenterOfMassPosition();
	const btVector3 rootMoment = feedback.m_appliedTorqueBodyB - weldArm.cross(feedback.m_appliedForceBodyB);
	const btScalar moment = m * kG * L / 2 + load * L;
	EXPECT_NEAR(rootMoment.z(), moment, 1e-5 * moment);
	EXPECT_NEAR(btVector3(rootMoment.x(), rootMoment.y(), 0).length(), 0, 1e-5 * moment);
	EXPECT_NEAR((feedback.m_appliedForceBodyA + feedback.m_appliedForceBodyB).length(), 0, 1e-5 * shear);
}
