// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btRigidBody on its own: mass properties, forces and impulses against Newton-Euler by hand, damping
// against its closed form, prediction, sleeping bookkeeping, kinematic velocities, the gyroscopic
// terms against conservation laws, and bad input.

#include <gtest/gtest.h>

#include <limits>

#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "LinearMath/btDefaultMotionState.h"
#include "LinearMath/btTransformUtil.h"
#include "LinearMath/btWarningHook.h"

namespace
{
// Float rounding of a handful of operations on values of order 1-10.
const btScalar kTight = btScalar(1e-5);

btTransform pose(const btVector3& origin, const btQuaternion& rotation = btQuaternion::getIdentity())
{
	return btTransform(rotation, origin);
}

void expectNear(const btVector3& actual, const btVector3& expected, btScalar tolerance, const char* what)
{
	for (int axis = 0; axis < 3; ++axis)
		EXPECT_NEAR(actual[axis], expected[axis], tolerance) << what << " axis " << axis;
}
}  // namespace

TEST(RigidBody, ConstructionTakesTheInfoAndMassZeroMakesAStaticBody)
{
	btBoxShape box(btVector3(1, 2, 3));
	btVector3 inertia;
	box.calculateLocalInertia(2, inertia);
	btDefaultMotionState motion(pose(btVector3(1, 2, 3)));
	btRigidBody::btRigidBodyConstructionInfo info(2, &motion, &box, inertia);
	btRigidBody body(info);
	EXPECT_EQ(body.getInternalType(), int(btCollisionObject::CO_RIGID_BODY));
	EXPECT_EQ(btRigidBody::upcast(static_cast<btCollisionObject*>(&body)), &body);
	EXPECT_EQ(body.getMass(), btScalar(2));
	EXPECT_EQ(body.getInvMass(), btScalar(0.5));
	EXPECT_FALSE(body.isStaticObject());
	EXPECT_EQ(body.getCenterOfMassPosition(), btVector3(1, 2, 3)) << "the transform comes from the motion state";
	EXPECT_EQ(body.getFriction(), btScalar(0.5));
	EXPECT_EQ(body.getLinearSleepingThreshold(), btScalar(0.8));
	EXPECT_EQ(body.getAngularSleepingThreshold(), btScalar(1));
	EXPECT_EQ(body.getFlags(), int(BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY));
	expectNear(body.getLocalInertia(), inertia, kTight * 10, "local inertia");

	btRigidBody ground(0, 0, &box);
	EXPECT_TRUE(ground.isStaticObject());
	EXPECT_EQ(ground.getInvMass(), btScalar(0));
	EXPECT_EQ(ground.getMass(), btScalar(0));
	btCollisionObject plain;
	EXPECT_TRUE(btRigidBody::upcast(&plain) == 0);
}

// Impulse J at arm r: dv = J / m, dw = I_world^-1 (r x J), with I_world = R I_local R^T.
TEST(RigidBody, ImpulsesChangeVelocitiesAsNewtonEulerSays)
{
	btBoxShape box(btVector3(1, btScalar(0.5), btScalar(0.25)));
	const btScalar mass = 3;
	btVector3 inertia;
	box.calculateLocalInertia(mass, inertia);
	btRigidBody body(mass, 0, &box, inertia);
	const btQuaternion rotation(btVector3(1, 2, 3).normalized(), btScalar(0.7));
	body.setCenterOfMassTransform(pose(btVector3(0, 0, 0), rotation));

	const btVector3 impulse(1, -2, btScalar(0.5));
	const btVector3 arm(btScalar(0.3), btScalar(0.2), btScalar(-0.1));
	body.applyImpulse(impulse, arm);
	expectNear(body.getLinearVelocity(), impulse / mass, kTight, "linear");
	const btMatrix3x3 basis(rotation);
	const btMatrix3x3 inverseInertiaWorld =
	    basis * btMatrix3x3(1 / inertia.x(), 0, 0, 0, 1 / inertia.y(), 0, 0, 0, 1 / inertia.z()) * basis.transpose();
	expectNear(body.getAngularVelocity(), inverseInertiaWorld * arm.cross(impulse), kTight * 10, "angular");
	// The velocity of the hit point follows: v + w x r.
	expectNear(body.getVelocityInLocalPoint(arm), body.getLinearVelocity() + body.getAngularVelocity().cross(arm),
	           kTight, "point velocity");

	// computeImpulseDenominator is n . (1/m + (I^-1 (r x n)) x r): the inverse effective mass.
	const btVector3 normal = btVector3(0, 1, 1).normalized();
	const btVector3 point = body.getCenterOfMassPosition() + arm;
	const btScalar expected = 1 / mass + normal.dot((inverseInertiaWorld * arm.cross(normal)).cross(arm));
	EXPECT_NEAR(body.computeImpulseDenominator(point, normal), expected, kTight);
	EXPECT_NEAR(body.computeAngularImpulseDenominator(normal), normal.dot(inverseInertiaWorld * normal), kTight);
}

TEST(RigidBody, LinearAndAngularFactorsLockAxes)
{
	btSphereShape sphere(1);
	btVector3 inertia;
	sphere.calculateLocalInertia(2, inertia);
	btRigidBody body(2, 0, &sphere, inertia);
	body.setLinearFactor(btVector3(1, 0, 1));
	body.setAngularFactor(btVector3(0, 1, 0));
	body.applyImpulse(btVector3(2, 2, 2), btVector3(1, 1, 1));
	EXPECT_EQ(body.getLinearVelocity().y(), btScalar(0));
	EXPECT_NEAR(body.getLinearVelocity().x(), btScalar(1), kTight);
	EXPECT_EQ(body.getAngularVelocity().x(), btScalar(0));
	EXPECT_EQ(body.getAngularVelocity().z(), btScalar(0));
	body.applyCentralForce(btVector3(0, 10, 0));
	EXPECT_EQ(body.getTotalForce(), btVector3(0, 0, 0)) << "a force along a locked axis is dropped";
}

// Semi-implicit Euler on velocities: after integrateVelocities(h), v = v0 + (F / m) h, w = w0 + I^-1 T h.
TEST(RigidBody, ForcesGravityAndTorqueIntegrateIntoVelocities)
{
	btSphereShape sphere(btScalar(0.5));
	const btScalar mass = 4;
	btVector3 inertia;
	sphere.calculateLocalInertia(mass, inertia);  // 2/5 m r^2 = 0.4
	btRigidBody body(mass, 0, &sphere, inertia);
	body.setGravity(btVector3(0, -10, 0));
	EXPECT_EQ(body.getGravity(), btVector3(0, -10, 0));
	body.applyGravity();
	body.applyForce(btVector3(8, 0, 0), btVector3(0, btScalar(0.5), 0));
	EXPECT_EQ(body.getTotalForce(), btVector3(8, -40, 0));
	const btScalar h = btScalar(1) / 60;
	body.integrateVelocities(h);
	expectNear(body.getLinearVelocity(), btVector3(2 * h, -10 * h, 0), kTight, "linear");
	// Torque r x F = (0, 0.5, 0) x (8, 0, 0) = (0, 0, -4); w = -4 / 0.4 h.
	expectNear(body.getAngularVelocity(), btVector3(0, 0, -10 * h), kTight, "angular");
	body.clearForces();
	EXPECT_EQ(body.getTotalForce(), btVector3(0, 0, 0));
	EXPECT_EQ(body.getTotalTorque(), btVector3(0, 0, 0));

	btRigidBody ground(0, 0, &sphere);
	ground.setGravity(btVector3(0, -10, 0));
	ground.applyGravity();
	ground.integrateVelocities(h);
	EXPECT_EQ(ground.getLinearVelocity(), btVector3(0, 0, 0)) << "static bodies do not move";
}

// (1 - d)^h per step: sixty steps of 1/60 s equal one second, v (1 - d).
TEST(RigidBody, DampingFollowsItsClosedFormIndependentOfStepSize)
{
	btSphereShape sphere(1);
	btRigidBody body(1, 0, &sphere, btVector3(1, 1, 1));
	body.setDamping(btScalar(0.3), btScalar(0.6));
	body.setLinearVelocity(btVector3(10, 0, 0));
	body.setAngularVelocity(btVector3(0, 5, 0));
	for (int i = 0; i < 60; ++i) body.applyDamping(btScalar(1) / 60);
	EXPECT_NEAR(body.getLinearVelocity().x(), btScalar(7), btScalar(1e-4));
	EXPECT_NEAR(body.getAngularVelocity().y(), btScalar(2), btScalar(1e-4));
	body.setDamping(-1, 2);
	EXPECT_EQ(body.getLinearDamping(), btScalar(0)) << "clamped to [0, 1]";
	EXPECT_EQ(body.getAngularDamping(), btScalar(1));
}

TEST(RigidBody, PredictionMovesAlongTheVelocities)
{
	btSphereShape sphere(1);
	btRigidBody body(1, 0, &sphere, btVector3(1, 1, 1));
	body.setCenterOfMassTransform(pose(btVector3(1, 2, 3)));
	body.setLinearVelocity(btVector3(3, 0, -6));
	body.setAngularVelocity(btVector3(0, 2, 0));
	btTransform predicted;
	body.predictIntegratedTransform(btScalar(0.25), predicted);
	expectNear(predicted.getOrigin(), btVector3(btScalar(1.75), 2, btScalar(1.5)), kTight, "origin");
	EXPECT_NEAR(predicted.getRotation().getAngle(), btScalar(0.5), kTight) << "2 rad/s for 0.25 s";
	body.proceedToTransform(predicted);
	expectNear(body.getCenterOfMassPosition(), predicted.getOrigin(), 0, "proceeded");
	expectNear(body.getInterpolationWorldTransform().getOrigin(), predicted.getOrigin(), 0, "interpolation");
}

TEST(RigidBody, SleepingNeedsTheDeactivationTimeBelowBothThresholds)
{
	btSphereShape sphere(1);
	btRigidBody body(1, 0, &sphere, btVector3(1, 1, 1));
	body.setSleepingThresholds(btScalar(0.5), btScalar(0.5));
	body.setLinearVelocity(btVector3(btScalar(0.4), 0, 0));
	const btScalar h = btScalar(0.25);
	// gDeactivationTime is 2 s: after 8 quarter-seconds the body has been still for exactly 2 s, which is
	// not yet more than 2.
	for (int i = 0; i < 8; ++i) body.updateDeactivation(h);
	EXPECT_FALSE(body.wantsSleeping());
	body.updateDeactivation(h);
	EXPECT_TRUE(body.wantsSleeping());
	// One fast step resets the clock.
	body.setAngularVelocity(btVector3(0, 1, 0));
	body.updateDeactivation(h);
	EXPECT_FALSE(body.wantsSleeping());
	EXPECT_EQ(body.getDeactivationTime(), btScalar(0));
	// Never with DISABLE_DEACTIVATION or gDisableDeactivation.
	body.setAngularVelocity(btVector3(0, 0, 0));
	for (int i = 0; i < 20; ++i) body.updateDeactivation(h);
	gDisableDeactivation = true;
	EXPECT_FALSE(body.wantsSleeping());
	gDisableDeactivation = false;
	EXPECT_TRUE(body.wantsSleeping());
	body.forceActivationState(DISABLE_DEACTIVATION);
	EXPECT_FALSE(body.wantsSleeping());
}

TEST(RigidBody, KinematicBodyDerivesItsVelocityFromItsMotionState)
{
	btBoxShape box(btVector3(1, 1, 1));
	btDefaultMotionState motion(pose(btVector3(0, 0, 0)));
	btRigidBody body(0, &motion, &box);
	body.setCollisionFlags(body.getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
	EXPECT_TRUE(body.isKinematicObject());
	const btScalar h = btScalar(0.5);
	body.saveKinematicState(h);
	motion.setWorldTransform(pose(btVector3(1, 0, -2), btQuaternion(btVector3(0, 1, 0), btScalar(0.25))));
	body.saveKinematicState(h);
	expectNear(body.getLinearVelocity(), btVector3(2, 0, -4), kTight, "from the move over h");
	expectNear(body.getAngularVelocity(), btVector3(0, btScalar(0.5), 0), kTight, "0.25 rad over 0.5 s");
	expectNear(body.getCenterOfMassPosition(), btVector3(1, 0, -2), 0, "pose read from the motion state");
}

// A free asymmetric body: the implicit gyroscopic step keeps the world angular momentum L = R I w
// (implicit Euler only loses energy, slowly) and never gains energy; the spin about the unstable
// middle axis flips, as it must (Dzhanibekov effect).
TEST(RigidBody, ImplicitGyroscopicStepKeepsAngularMomentumAndNeverGainsEnergy)
{
	btBoxShape box(btVector3(btScalar(0.1), btScalar(0.5), btScalar(1)));
	btVector3 inertia;
	box.calculateLocalInertia(1, inertia);
	btRigidBody body(1, 0, &box, inertia);
	body.setAngularVelocity(btVector3(btScalar(0.01), 4, btScalar(0.01)));
	const btScalar h = btScalar(1) / 240;
	const btMatrix3x3 inertiaLocal(inertia.x(), 0, 0, 0, inertia.y(), 0, 0, 0, inertia.z());
	auto momentum = [&]()
	{
		const btMatrix3x3& basis = body.getCenterOfMassTransform().getBasis();
		return basis * (inertiaLocal * (basis.transpose() * body.getAngularVelocity()));
	};
	auto energy = [&]() { return btScalar(0.5) * body.getAngularVelocity().dot(momentum()); };
	const btVector3 startMomentum = momentum();
	const btScalar startEnergy = energy();
	btScalar previousEnergy = startEnergy;
	bool flipped = false;
	for (int step = 0; step < 240 * 4; ++step)
	{
		body.setAngularVelocity(body.getAngularVelocity() + body.computeGyroscopicImpulseImplicit_Body(h));
		btTransform next;
		body.predictIntegratedTransform(h, next);
		body.proceedToTransform(next);
		const btScalar e = energy();
		ASSERT_LE(e, previousEnergy * (1 + btScalar(1e-5))) << "step " << step;
		previousEnergy = e;
		const btVector3 spinBody = body.getCenterOfMassTransform().getBasis().transpose() * body.getAngularVelocity();
		if (spinBody.y() < 0) flipped = true;
	}
	EXPECT_TRUE(flipped) << "the intermediate-axis spin must flip within 4 s";
	// Drift of |L| over 960 steps: implicit Euler damps a little per flip; 5% bounds it loosely.
	EXPECT_NEAR(momentum().length(), startMomentum.length(), startMomentum.length() * btScalar(0.05));
	EXPECT_GT(energy(), startEnergy * btScalar(0.8)) << "not damped away";

	// The explicit torque is w x (I w), clamped to the given length.
	const btVector3 torque = body.computeGyroscopicForceExplicit(btScalar(1e30));
	expectNear(torque, body.getAngularVelocity().cross(momentum()), btScalar(1e-4), "explicit torque");
	EXPECT_NEAR(body.computeGyroscopicForceExplicit(btScalar(1e-3)).length(), btScalar(1e-3), btScalar(1e-6));
}

TEST(RigidBody, BadInputIsRejectedAndLeavesTheBodyUsable)
{
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	btSphereShape sphere(1);
	btRigidBody body(1, 0, &sphere, btVector3(1, 1, 1));
	body.setLinearVelocity(btVector3(1, 0, 0));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btRigidBody(-1, 0, &sphere, btVector3(1, 1, 1)), "mass must be finite");
	EXPECT_DEATH(body.setMassProps(1, btVector3(1, -1, 1)), "inertia must be finite");
	EXPECT_DEATH(body.applyCentralImpulse(btVector3(nan, 0, 0)), "non-finite impulse");
	EXPECT_DEATH(body.applyForce(btVector3(0, 0, 0), btVector3(nan, 0, 0)), "non-finite force");
	EXPECT_DEATH(body.setLinearVelocity(btVector3(0, nan, 0)), "non-finite velocity");
#else
	btRigidBody negative(-1, 0, &sphere, btVector3(1, 1, 1));
	EXPECT_TRUE(negative.isStaticObject()) << "a negative mass is treated as 0: static";
	btRigidBody notANumber(nan, 0, &sphere, btVector3(1, 1, 1));
	EXPECT_TRUE(notANumber.isStaticObject());
	btRigidBody badInertia(1, 0, &sphere, btVector3(1, -1, nan));
	EXPECT_EQ(badInertia.getInvInertiaDiagLocal(), btVector3(1, 0, 0)) << "rejected axes do not turn";
	body.applyCentralImpulse(btVector3(nan, 0, 0));
	body.applyImpulse(btVector3(1, 0, 0), btVector3(nan, 0, 0));
	body.applyForce(btVector3(0, 0, 0), btVector3(nan, 0, 0));
	body.applyTorque(btVector3(0, nan, 0));
	body.setLinearVelocity(btVector3(0, nan, 0));
	body.setAngularVelocity(btVector3(0, nan, 0));
#endif
	EXPECT_EQ(body.getLinearVelocity(), btVector3(1, 0, 0)) << "bad input left the velocity alone";
	EXPECT_EQ(body.getTotalForce(), btVector3(0, 0, 0));
	body.applyCentralImpulse(btVector3(1, 0, 0));
	EXPECT_EQ(body.getLinearVelocity(), btVector3(2, 0, 0)) << "and the body still works";
}

TEST(RigidBody, NonFiniteDampingAndBadFactorsAreReportedAndIgnored)
{
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	const btScalar inf = std::numeric_limits<btScalar>::infinity();
	btSphereShape sphere(1);
	btRigidBody body(1, 0, &sphere, btVector3(1, 1, 1));
	body.setDamping(btScalar(0.1), btScalar(0.2));
	body.setLinearFactor(btVector3(1, 0, 1));
	body.setAngularFactor(btVector3(0, 1, 0));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(body.setDamping(nan, 0), "non-finite damping");
	EXPECT_DEATH(body.setLinearFactor(btVector3(-1, 1, 1)), "factors must be finite");
	EXPECT_DEATH(body.setAngularFactor(inf), "factors must be finite");
#else
	int warnings = 0;
	btSetWarningHook([](const char*, void* count) { ++*static_cast<int*>(count); }, &warnings);
	body.setDamping(nan, 0);
	body.setDamping(0, inf);
	body.setLinearFactor(btVector3(-1, 1, 1));
	body.setLinearFactor(btVector3(1, nan, 1));
	body.setAngularFactor(inf);
	body.setAngularFactor(btVector3(0, -2, 0));
	btSetWarningHook(0, 0);
	EXPECT_EQ(warnings, 6) << "every rejected call is reported once";
	btRigidBody::btRigidBodyConstructionInfo info(1, 0, &sphere, btVector3(1, 1, 1));
	info.m_linearDamping = nan;
	info.m_friction = -1;
	info.m_restitution = nan;
	btRigidBody fromInfo(info);
	EXPECT_EQ(fromInfo.getLinearDamping(), btScalar(0)) << "a rejected damping leaves none";
	EXPECT_EQ(fromInfo.getFriction(), btScalar(0.5)) << "a rejected material keeps the default";
	EXPECT_EQ(fromInfo.getRestitution(), btScalar(0));
#endif
	EXPECT_EQ(body.getLinearDamping(), btScalar(0.1)) << "the last valid settings stay";
	EXPECT_EQ(body.getAngularDamping(), btScalar(0.2));
	EXPECT_EQ(body.getLinearFactor(), btVector3(1, 0, 1));
	EXPECT_EQ(body.getAngularFactor(), btVector3(0, 1, 0));
	// The locked axes still lock: an impulse along y moves nothing, one along x does.
	body.applyCentralImpulse(btVector3(1, 1, 0));
	EXPECT_EQ(body.getLinearVelocity(), btVector3(1, 0, 0));
}
