// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// HelloWorld: the program of the Bullet manual's first chapter, in our words, and the same scene as
// README's example: a world with the default collision configuration, a dbvt broadphase and the
// sequential-impulse solver; a static ground box whose top face is y = 0; a 1 kg ball of radius 1 m
// released at y = 10. It steps 150 times at 60 Hz and prints the ball's height every half second
// (README's lines, word for word), then checks what it printed:
// - while the ball falls freely, the height read from its motion state after step n is the
//   integrator's exact answer: semi-implicit Euler puts the body at y_n = 10 - g h^2 n (n + 1) / 2,
//   and the motion state, interpolated as in Bullet, shows it one substep behind, y_(n-1);
// - at the end the ball rests on the ground at its radius, y = 1 within a centimetre.
// Exit 1 when either check fails. With --frames shorter than 150 the rest check is skipped. --png:
// docs/demos.md.

#include <math.h>
#include <stdio.h>

#include "DemoPictures.h"
#include "HelloWorldScene.h"

int main(int argc, char** argv)
{
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "HelloWorld";
	commandLine.defaultFrames = 150;
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();

	hello_world::Scene scene;  // HelloWorldScene.h: the world, the ground and the ball
	btDiscreteDynamicsWorld& world = scene.world();
	btDefaultMotionState& ballMotionState = scene.ballMotionState();
	const btScalar gravity = hello_world::kGravity;
	const btScalar ballRadius = hello_world::kBallRadius, releaseHeight = hello_world::kReleaseHeight;

	const btScalar stepSeconds = btScalar(1) / 60;
	double worstFreeFallError = 0;
	btScalar height = releaseHeight;
	for (int step = 1; step <= pictures.frames(); ++step)
	{
		world.stepSimulation(stepSeconds, 10);
		pictures.frame(world, step);
		btTransform pose;
		ballMotionState.getWorldTransform(pose);
		height = pose.getOrigin().getY();
		if (step % 30 == 0) printf("t = %.1f s: ball at height %.2f m\n", step / 60.0, double(height));

		// Free fall lasts until the ball's bottom reaches the ground, about 1.4 s in.
		const double expected =
		    double(releaseHeight) - double(gravity) * double(stepSeconds) * double(stepSeconds) * (step - 1) * step / 2;
		if (expected > 1.2 * double(ballRadius))
		{
			const double error = fabs(double(height) - expected);
			if (error > worstFreeFallError) worstFreeFallError = error;
		}
	}

	const bool freeFallOk = worstFreeFallError < 1e-3;
	const bool restOk = pictures.shortened() || btFabs(height - ballRadius) < btScalar(0.01);
	printf("free fall: worst deviation from y = 10 - g h^2 (n - 1) n / 2 is %.2g m (limit 1e-3): %s\n",
	       worstFreeFallError, freeFallOk ? "ok" : "FAILED");
	if (pictures.shortened())
		printf("at rest: not checked (--frames %d is shorter than 150)\n", pictures.frames());
	else
		printf("at rest: height %.4f m, the radius is 1 (limit 0.01): %s\n", double(height), restOk ? "ok" : "FAILED");

	return pictures.finish(freeFallOk && restOk ? 0 : 1);
}
