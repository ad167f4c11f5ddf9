// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// ConstraintDemo: one of each joint type at work, printing its angles and positions every half
// second: a ball-joint pendulum, a door on a limited hinge pushed by a torque, a motor-driven wheel, a
// limb on a cone-twist joint kicked into its cone, and further joint types as Caliber has them.
// --png (joint frames and limits drawn over the bodies), --frames (default 300; shorter runs skip the
// end-state checks) and --png-sequence: docs/demos.md.

#include <cstdio>
#include <memory>
#include <vector>

#include "DemoPictures.h"
#include "btBulletDynamicsCommon.h"

namespace
{
class Demo
{
public:
	Demo() : m_dispatcher(&m_configuration), m_world(&m_dispatcher, &m_broadphase, &m_solver, &m_configuration)
	{
		m_world.setGravity(btVector3(0, -10, 0));
	}
	~Demo()
	{
		for (auto& joint : m_joints) m_world.removeConstraint(joint.get());
		for (auto& body : m_bodies) m_world.removeRigidBody(body.get());
	}
	btRigidBody* body(btCollisionShape* shape, btScalar mass, const btTransform& pose)
	{
		m_shapes.emplace_back(shape);
		btVector3 inertia(0, 0, 0);
		if (mass > 0) shape->calculateLocalInertia(mass, inertia);
		btRigidBody::btRigidBodyConstructionInfo info(mass, 0, shape, inertia);
		info.m_startWorldTransform = pose;
		m_bodies.emplace_back(new btRigidBody(info));
		m_bodies.back()->setActivationState(DISABLE_DEACTIVATION);
		m_world.addRigidBody(m_bodies.back().get());
		return m_bodies.back().get();
	}
	template <class Joint>
	Joint* joint(Joint* j)
	{
		m_joints.emplace_back(j);
		m_world.addConstraint(j, true);
		return j;
	}
	btDiscreteDynamicsWorld& world() { return m_world; }

private:
	btDefaultCollisionConfiguration m_configuration;
	btCollisionDispatcher m_dispatcher;
	btDbvtBroadphase m_broadphase;
	btSequentialImpulseConstraintSolver m_solver;
	btDiscreteDynamicsWorld m_world;
	std::vector<std::unique_ptr<btCollisionShape>> m_shapes;
	std::vector<std::unique_ptr<btRigidBody>> m_bodies;
	std::vector<std::unique_ptr<btTypedConstraint>> m_joints;
};

btTransform at(const btVector3& origin, const btQuaternion& q = btQuaternion::getIdentity())
{
	return btTransform(q, origin);
}
}  // namespace

int main(int argc, char** argv)
{
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "ConstraintDemo";
	commandLine.defaultFrames = 300;
	commandLine.sequences = true;
	commandLine.debugDrawMode = btIDebugDraw::DBG_DrawConstraints | btIDebugDraw::DBG_DrawConstraintLimits;
	commandLine.defaultWidth = 960;  // the joints stand in a 27 m row
	commandLine.defaultHeight = 320;
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();
	// The joints stand in a row along x, at heights 4 to 7; the welded L is thrown and falls away, so the
	// picture frames the row (from the front) rather than everything that moves.
	pictures.setViewDirection(btVector3(0, -0.15f, -1));
	pictures.setFocus(btVector3(-0.5f, 3.8f, -0.5f), btVector3(26.5f, 6.2f, 0.5f));
	Demo d;
	// Ball joint: a 1 m pendulum released at 60 degrees from a pivot at (0, 5, 0).
	const btScalar theta = SIMD_PI / 3;
	btRigidBody* bob =
	    d.body(new btSphereShape(btScalar(0.1)), 1,
	           at(btVector3(btSin(theta), 5 - btCos(theta), 0), btQuaternion(btVector3(0, 0, 1), theta)));
	btPoint2PointConstraint* ball = d.joint(new btPoint2PointConstraint(*bob, btVector3(0, 1, 0)));

	// Door: hinged about y at its edge, limited to -30..+45 degrees, pushed by a torque that flips
	// every second.
	btRigidBody* door = d.body(new btBoxShape(btVector3(0.5, 1, 0.05)), 10, at(btVector3(3.5, 5, 0)));
	btHingeConstraint* doorHinge = d.joint(new btHingeConstraint(*door, btVector3(-0.5, 0, 0), btVector3(0, 1, 0)));
	doorHinge->setLimit(-SIMD_PI / 6, SIMD_PI / 4);

	// Wheel: a motor spins it up to 2 turns per second with at most 0.05 N m s per step.
	btRigidBody* wheel = d.body(new btCylinderShapeZ(btVector3(0.5, 0.5, 0.1)), 5, at(btVector3(6, 5, 0)));
	btHingeConstraint* axle = d.joint(new btHingeConstraint(*wheel, btVector3(0, 0, 0), btVector3(0, 0, 1)));
	axle->enableAngularMotor(true, 4 * SIMD_PI, btScalar(0.05));

	// Limb: a capsule hanging from a cone-twist joint (30-degree cone), kicked sideways.
	btRigidBody* limb = d.body(new btCapsuleShape(btScalar(0.1), 1), 1, at(btVector3(9, 4, 0)));
	btTransform frameInLimb(btMatrix3x3(0, -1, 0, 1, 0, 0, 0, 0, 1), btVector3(0, 1, 0));
	btConeTwistConstraint* shoulder = d.joint(new btConeTwistConstraint(*limb, frameInLimb));
	shoulder->setLimit(SIMD_PI / 6, SIMD_PI / 6, btScalar(0.3));
	limb->applyCentralImpulse(btVector3(4, 0, 2));

	// Slider: a carriage on a rail tilted 30 degrees, driven up by a motor (at most 20 N) to its upper
	// limit 1 m along, which it reaches and holds.
	const btQuaternion tilt(btVector3(0, 0, 1), SIMD_PI / 6);
	btRigidBody* carriage = d.body(new btBoxShape(btVector3(0.2, 0.1, 0.1)), 1, at(btVector3(12, 5, 0), tilt));
	btSliderConstraint* rail = d.joint(new btSliderConstraint(*carriage, btTransform::getIdentity(), true));
	rail->setLowerLinLimit(-1);
	rail->setUpperLinLimit(1);
	rail->setLowerAngLimit(0);
	rail->setUpperAngLimit(0);
	rail->setPoweredLinMotor(true);
	rail->setTargetLinMotorVelocity(1);
	rail->setMaxLinMotorForce(20);

	// Gears: two wheels on hinges, geared 2:1; the small one is driven at 2 turns per second.
	btRigidBody* small = d.body(new btCylinderShapeZ(btVector3(0.25, 0.25, 0.1)), 1, at(btVector3(15, 5, 0)));
	btRigidBody* large = d.body(new btCylinderShapeZ(btVector3(0.5, 0.5, 0.1)), 1, at(btVector3(15.75, 5, 0)));
	btHingeConstraint* smallAxle = d.joint(new btHingeConstraint(*small, btVector3(0, 0, 0), btVector3(0, 0, 1)));
	d.joint(new btHingeConstraint(*large, btVector3(0, 0, 0), btVector3(0, 0, 1)));
	d.joint(new btGearConstraint(*small, *large, btVector3(0, 0, 1), btVector3(0, 0, 1), 2));
	smallAxle->enableAngularMotor(true, 4 * SIMD_PI, 1);

	// Spring: a 1 kg weight on a vertical 6-DoF spring (k = 40 N/m, lightly damped) to the world,
	// released at the spring's rest length: it bobs about m g / k = 0.25 m lower and settles there.
	btRigidBody* weight = d.body(new btBoxShape(btVector3(0.1, 0.1, 0.1)), 1, at(btVector3(18, 5, 0)));
	btGeneric6DofSpring2Constraint* spring =
	    d.joint(new btGeneric6DofSpring2Constraint(*weight, btTransform::getIdentity()));
	spring->setLinearLowerLimit(btVector3(0, 1, 0));  // y free (lower > upper), x and z locked
	spring->setLinearUpperLimit(btVector3(0, -1, 0));
	spring->enableSpring(1, true);
	spring->setStiffness(1, 40);
	spring->setDamping(1, btScalar(0.5));
	spring->setEquilibriumPoint(1, 0);

	// Weld: an L of two boxes joined by a fixed joint, thrown spinning: it turns as one body.
	btRigidBody* armA = d.body(new btBoxShape(btVector3(0.5, 0.1, 0.1)), 1, at(btVector3(21, 6, 0)));
	btRigidBody* armB = d.body(new btBoxShape(btVector3(0.1, 0.5, 0.1)), 1, at(btVector3(21.4, 6.6, 0)));
	d.joint(new btFixedConstraint(*armA, *armB, at(btVector3(0.4, 0, 0)), at(btVector3(0, -0.6, 0))));
	armA->setAngularVelocity(btVector3(0, 0, 3));

	// Cardan joint: an input shaft along x driven at 2 rad/s by a hinge motor, a universal joint at its end
	// and an output shaft bent 30 degrees up, both on hinges to the world through their centres. The
	// output turns at between cos 30 = 0.866 and 1 / cos 30 = 1.155 times the input's rate.
	const btScalar bend = SIMD_PI / 6;
	const btVector3 outputAxis(btCos(bend), btSin(bend), 0);
	btRigidBody* input = d.body(new btBoxShape(btVector3(0.5, 0.05, 0.05)), 1, at(btVector3(24.5, 5, 0)));
	btRigidBody* output =
	    d.body(new btBoxShape(btVector3(0.5, 0.05, 0.05)), 1,
	           at(btVector3(25, 5, 0) + outputAxis * btScalar(0.5), btQuaternion(btVector3(0, 0, 1), bend)));
	btHingeConstraint* inputBearing = d.joint(new btHingeConstraint(*input, btVector3(0, 0, 0), btVector3(1, 0, 0)));
	d.joint(new btHingeConstraint(*output, btVector3(0, 0, 0), btVector3(1, 0, 0)));
	d.joint(new btUniversalConstraint(*input, *output, btVector3(25, 5, 0), btVector3(0, 0, 1),
	                                  btVector3(-btSin(bend), btCos(bend), 0)));
	inputBearing->enableAngularMotor(true, 2, 10);
	btScalar slowest = BT_LARGE_FLOAT, fastest = 0;

	std::printf(
	    "ConstraintDemo: ball joint, limited hinge (door), hinge motor (wheel), cone-twist (limb), slider\n"
	    "(carriage on a tilted rail), gears (2:1), 6-DoF spring (weight), fixed joint (welded L), universal (Cardan "
	    "shafts)\n");
	std::printf("%5s | %9s %9s | %10s | %12s | %9s %9s | %9s | %9s %9s | %9s | %9s\n", "time", "ball ang", "ball gap",
	            "door ang", "wheel rad/s", "limb swing", "twist", "carriage", "small w", "large w", "weight y",
	            "weld gap");
	bool ok = true;
	for (int frame = 1; frame <= pictures.frames(); ++frame)
	{
		door->applyTorque(btVector3(0, (frame / 60) % 2 ? -40 : 40, 0));
		d.world().stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.));
		pictures.frame(d.world(), frame);
		const btVector3 p = bob->getCenterOfMassPosition() - btVector3(0, 5, 0);
		const btScalar ballGap = (bob->getCenterOfMassTransform()(ball->getPivotInA()) - ball->getPivotInB()).length();
		shoulder->calcAngleInfo();
		if (frame > 60)
		{
			const btScalar ratio = output->getAngularVelocity().dot(outputAxis) / input->getAngularVelocity().x();
			slowest = btMin(slowest, ratio);
			fastest = btMax(fastest, ratio);
		}
		if (frame % 30 == 0)
			std::printf("%4.1fs | %9.4f %9.2e | %10.4f | %12.4f | %9.4f %9.4f | %9.4f | %9.4f %9.4f | %9.4f | %9.2e\n",
			            frame / 60.0, double(btAtan2(p.x(), -p.y())), double(ballGap),
			            double(doorHinge->getHingeAngle()), double(wheel->getAngularVelocity().z()),
			            double(shoulder->getSwingAngle()), double(shoulder->getTwistAngle()),
			            double(rail->getLinearPos()), double(small->getAngularVelocity().z()),
			            double(large->getAngularVelocity().z()), double(weight->getCenterOfMassPosition().y() - 5),
			            double((armA->getCenterOfMassTransform()(btVector3(0.4, 0, 0)) -
			                    armB->getCenterOfMassTransform()(btVector3(0, -0.6, 0)))
			                       .length()));
		ok = ok && ballGap < btScalar(0.01) && doorHinge->getHingeAngle() < SIMD_PI / 4 + btScalar(0.01) &&
		     doorHinge->getHingeAngle() > -SIMD_PI / 6 - btScalar(0.01);
	}
	const bool wheelAtSpeed = btFabs(wheel->getAngularVelocity().z() - 4 * SIMD_PI) < btScalar(0.01);
	// Settled on the spring: m g / k below the rest length, within the damped oscillation's remainder.
	const bool springSettled = btFabs(weight->getCenterOfMassPosition().y() - 5 + btScalar(0.25)) < btScalar(0.05);
	const bool carriageAtLimit = btFabs(rail->getLinearPos() - 1) < btScalar(0.01);
	// Gear ratio 2: the large wheel turns at half the small one's speed, the other way.
	const bool geared = btFabs(large->getAngularVelocity().z() + small->getAngularVelocity().z() / 2) < btScalar(0.01);
	std::printf(
	    "ball joint held, door within its limits: %s; wheel at its motor's 12.566 rad/s: %s; carriage at "
	    "its upper limit: %s; gears at 2:1: %s; weight near m g / k below its rest: %s\n",
	    ok ? "yes" : "NO", wheelAtSpeed ? "yes" : "NO", carriageAtLimit ? "yes" : "NO", geared ? "yes" : "NO",
	    springSettled ? "yes" : "NO");
	// The Cardan ratio swings between cos and 1 / cos of the bend (to the solver's precision).
	const bool cardan =
	    btFabs(slowest - btCos(bend)) < btScalar(0.01) && btFabs(fastest - 1 / btCos(bend)) < btScalar(0.01);
	std::printf("Cardan shafts: output / input rate from %.4f to %.4f (cos 30 = 0.8660, 1 / cos 30 = 1.1547): %s\n",
	            double(slowest), double(fastest), cardan ? "yes" : "NO");
	if (pictures.shortened())
	{
		// The end states need the whole run; the joints must have held all along, however short.
		std::printf("end states not checked (--frames %d is shorter than 300)\n", pictures.frames());
		return pictures.finish(ok ? 0 : 1);
	}
	return pictures.finish(ok && wheelAtSpeed && carriageAtLimit && geared && springSettled && cardan ? 0 : 1);
}
