// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "Ragdoll.h"

namespace ragdoll
{
namespace
{
const btScalar kHalfPi = SIMD_HALF_PI, kQuarterPi = SIMD_HALF_PI * btScalar(0.5);

// A capsule: radius and cylinder height, centre (x, y), and its tilt about z in quarter turns.
struct Part
{
	btScalar radius, height, x, y, quarterTurnsZ;
};

// pelvis, spine, head, left thigh, left shin, right thigh, right shin, left upper arm, left forearm,
// right upper arm, right forearm (arms lie horizontal).
const Part kParts[Ragdoll::NUM_BODIES] = {
    {0.15f, 0.20f, 0, 1.00f, 0},      {0.15f, 0.28f, 0, 1.20f, 0},      {0.10f, 0.05f, 0, 1.60f, 0},
    {0.07f, 0.45f, -0.18f, 0.65f, 0}, {0.05f, 0.37f, -0.18f, 0.20f, 0}, {0.07f, 0.45f, 0.18f, 0.65f, 0},
    {0.05f, 0.37f, 0.18f, 0.20f, 0},  {0.05f, 0.33f, -0.35f, 1.45f, 1}, {0.04f, 0.25f, -0.70f, 1.45f, 1},
    {0.05f, 0.33f, 0.35f, 1.45f, -1}, {0.04f, 0.25f, 0.70f, 1.45f, -1}};

// A joint between parts a and b: each frame is a rotation (Euler: about y, then z) and an origin (x, y)
// in its body; a hinge has limits (low, high), a cone-twist (swing 1, swing 2, twist).
struct JointSpec
{
	bool hinge;
	int a, b;
	btScalar yawA, rollA, xA, yA;
	btScalar yawB, rollB, xB, yB;
	btScalar limit0, limit1, limit2;
};

const JointSpec kJoints[Ragdoll::NUM_JOINTS] = {
    {true, 0, 1, kHalfPi, 0, 0, 0.15f, kHalfPi, 0, 0, -0.15f, -kQuarterPi, kHalfPi, 0},
    {false, 1, 2, 0, kHalfPi, 0, 0.30f, 0, kHalfPi, 0, -0.14f, kQuarterPi, kQuarterPi, kHalfPi},
    {false, 0, 3, 0, -5 * kQuarterPi, -0.18f, -0.10f, 0, -5 * kQuarterPi, 0, 0.225f, kQuarterPi, kQuarterPi, 0},
    {true, 3, 4, kHalfPi, 0, 0, -0.225f, kHalfPi, 0, 0, 0.185f, 0, kHalfPi, 0},
    {false, 0, 5, 0, kQuarterPi, 0.18f, -0.10f, 0, kQuarterPi, 0, 0.225f, kQuarterPi, kQuarterPi, 0},
    {true, 5, 6, kHalfPi, 0, 0, -0.225f, kHalfPi, 0, 0, 0.185f, 0, kHalfPi, 0},
    {false, 1, 7, 0, SIMD_PI, -0.2f, 0.15f, 0, kHalfPi, 0, -0.18f, kHalfPi, kHalfPi, 0},
    {true, 7, 8, kHalfPi, 0, 0, 0.18f, kHalfPi, 0, 0, -0.14f, -kHalfPi, 0, 0},
    {false, 1, 9, 0, 0, 0.2f, 0.15f, 0, kHalfPi, 0, -0.18f, kHalfPi, kHalfPi, 0},
    {true, 9, 10, kHalfPi, 0, 0, 0.18f, kHalfPi, 0, 0, -0.14f, -kHalfPi, 0, 0}};

btTransform frame(btScalar yaw, btScalar roll, btScalar x, btScalar y, btScalar scale)
{
	btTransform t;
	t.setIdentity();
	t.getBasis().setEulerZYX(0, yaw, roll);
	t.setOrigin(btVector3(x, y, 0) * scale);
	return t;
}
}  // namespace

btScalar Ragdoll::pivotError(int j) const
{
	const btTypedConstraint* joint = joints[j];
	const btVector3 a = joint->getRigidBodyA().getCenterOfMassTransform() * frameInA[j].getOrigin();
	const btVector3 b = joint->getRigidBodyB().getCenterOfMassTransform() * frameInB[j].getOrigin();
	return (a - b).length();
}

void build(Owner& owner, const btVector3& offset, btScalar scale, Ragdoll& out)
{
	for (int i = 0; i < Ragdoll::NUM_BODIES; ++i)
	{
		const Part& p = kParts[i];
		btCollisionShape* capsule = owner.keepShape(new btCapsuleShape(p.radius * scale, p.height * scale));
		btTransform pose;
		pose.setIdentity();
		pose.getBasis().setEulerZYX(0, 0, p.quarterTurnsZ * kHalfPi);
		pose.setOrigin(offset + btVector3(p.x, p.y, 0) * scale);
		btRigidBody* body = owner.addBody(capsule, 1, pose);
		body->setDamping(btScalar(0.05), btScalar(0.85));
		body->setDeactivationTime(btScalar(0.8));
		body->setSleepingThresholds(btScalar(1.6), btScalar(2.5));
		out.bodies[i] = body;
	}
	for (int j = 0; j < Ragdoll::NUM_JOINTS; ++j)
	{
		const JointSpec& s = kJoints[j];
		out.frameInA[j] = frame(s.yawA, s.rollA, s.xA, s.yA, scale);
		out.frameInB[j] = frame(s.yawB, s.rollB, s.xB, s.yB, scale);
		btRigidBody& a = *out.bodies[s.a];
		btRigidBody& b = *out.bodies[s.b];
		if (s.hinge)
		{
			btHingeConstraint* hinge = new btHingeConstraint(a, b, out.frameInA[j], out.frameInB[j]);
			hinge->setLimit(s.limit0, s.limit1);
			out.joints[j] = hinge;
		}
		else
		{
			btConeTwistConstraint* cone = new btConeTwistConstraint(a, b, out.frameInA[j], out.frameInB[j]);
			cone->setLimit(s.limit0, s.limit1, s.limit2);
			out.joints[j] = cone;
		}
		owner.addJoint(out.joints[j]);
	}
}
}  // namespace ragdoll
