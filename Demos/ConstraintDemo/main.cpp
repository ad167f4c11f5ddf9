// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// ConstraintDemo: one of each joint type at work, printing its angles and positions every half
// second: a ball-joint pendulum, a door on a limited hinge pushed by a torque, a motor-driven wheel, a
// limb on a cone-twist joint kicked into its cone, and further joint types as Caliber has them.
// --png (joint frames and limits drawn over the bodies), --frames (default 300; shorter runs skip the
// end-state checks) and --png-sequence: docs/demos.md.

#include <cstdio>
#include <memory>
#include <vector>

#include "ConstraintScene.h"
#include "DemoPictures.h"
#include "btBulletDynamicsCommon.h"

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
	constraint_demo::Scene d;
	btRigidBody* bob = d.bob;
	btPoint2PointConstraint* ball = d.ball;
	btHingeConstraint* doorHinge = d.doorHinge;
	btRigidBody* wheel = d.wheel;
	btConeTwistConstraint* shoulder = d.shoulder;
	btSliderConstraint* rail = d.rail;
	btRigidBody* small = d.small;
	btRigidBody* large = d.large;
	btRigidBody* weight = d.weight;
	btRigidBody* armA = d.armA;
	btRigidBody* armB = d.armB;
	btRigidBody* input = d.input;
	btRigidBody* output = d.output;
	const btScalar bend = d.bend;
	const btVector3 outputAxis = d.outputAxis;
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
		d.step(frame);
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
