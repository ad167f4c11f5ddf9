// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// ForkLiftDemo: the manual's fork lift, headless. A raycast vehicle (800 kg chassis, four wheels)
// carries a mast on a hinge at its front (held upright by the hinge's limits) and a fork that a
// slider's motor raises and lowers along the mast. A 100 kg load sits on two rails 10 m ahead, with a
// gap under it for the fork. The fork lift drives to the load with the fork low, slides the fork
// under it, lifts it, reverses 5 m carrying it, and lowers it again. It prints the fork lift's position,
// the fork's height and the load's position as it goes.
// Checks: the fork ends under the load; the load is lifted off the rails (its bottom above them by
// most of the fork's travel); the load stays on the fork while carried (resting on it, its centre
// over the plate); lowered, it rests on the fork at the bottom of its travel. Exit 1 when a check fails.
// --frames N stops the script after N steps (the whole script is about 1500); the checks of the phases
// it did not finish are skipped. --png shows the last frame with the wheels (docs/demos.md).

#include <math.h>
#include <stdio.h>

#include "DemoPictures.h"
#include "DemoScript.h"
#include "ForkLiftScene.h"
#include "WorldScene.h"

namespace
{
const btScalar kStep = btScalar(1. / 60.);
}  // namespace

int main(int argc, char** argv)
{
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "ForkLiftDemo";
	commandLine.defaultFrames = 1000000;  // more than the script takes: by default it runs to its end
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();

	fork_lift_demo::Scene scene;
	btDiscreteDynamicsWorld& world = scene.world();
	btRigidBody* load = scene.load();
	btRigidBody* chassis = scene.chassis();
	btRigidBody* fork = scene.fork();
	btSliderConstraint& slider = scene.slider();
	btRaycastVehicle& vehicle = scene.vehicle();

	pictures.setDecorator([&](caliber::demo::Scene& drawing) {
		caliber::demo::addVehicleWheels(drawing, vehicle, fork_lift_demo::kWheelWidth);
	});

	// --frames: once the budget is spent no phase steps any more, and the unfinished phases' checks are skipped.
	caliber::demo::DemoScript script(world, kStep, pictures.stepBudget());
	auto report = [&](const char* phase)
	{
		const btVector3 c = chassis->getCenterOfMassPosition(), l = load->getCenterOfMassPosition();
		printf("%-8s t %5.2f s  fork lift z %6.2f  speed %5.1f km/h  fork height %5.2f m  load (%5.2f, %5.2f, %5.2f)\n",
		       phase, script.time(), c.z(), vehicle.getCurrentSpeedKmHour(), slider.getLinearPos(), l.x(), l.y(), l.z());
	};
	// Drives the rear wheels towards speed (m/s, negative: reverse) with a bounded force.
	auto drive = [&](btScalar speed) {
		const btScalar now = chassis->getLinearVelocity().dot(vehicle.getForwardVector());
		const btScalar force = btMax(btScalar(-3000), btMin(btScalar(3000), 2000 * (speed - now)));
		vehicle.applyEngineForce(force, 2);
		vehicle.applyEngineForce(force, 3);
		for (int i = 0; i < 4; ++i) vehicle.setBrake(0, i);
	};
	auto stop = [&]() {
		vehicle.applyEngineForce(0, 2);
		vehicle.applyEngineForce(0, 3);
		for (int i = 0; i < 4; ++i) vehicle.setBrake(50, i);
	};

	printf("ForkLiftDemo: an 800 kg fork lift fetches a 100 kg load from rails 10 m ahead\n");
	script.run(120);
	report("ready");

	// To the load, fork low, slowing near it, until the fork is centred under it.
	const btScalar forkAhead = fork->getCenterOfMassPosition().z() - chassis->getCenterOfMassPosition().z();
	for (int i = 0; i < 1200 && !script.spent(); ++i)
	{
		const btScalar left = load->getCenterOfMassPosition().z() - fork->getCenterOfMassPosition().z();
		if (left < btScalar(0.02)) break;
		drive(btMin(btScalar(1.5), btMax(btScalar(0.2), left)));
		script.run(1);
		if (i % 60 == 0) report("approach");
	}
	stop();
	script.run(60);
	report("under");
	const btVector3 forkAtLoad = fork->getCenterOfMassPosition();
	script.judge(fabs(forkAtLoad.z() - load->getCenterOfMassPosition().z()) < 0.15 && fabs(forkAtLoad.x()) < 0.1,
	      "the fork is under the load");
	printf("  fork %.2f m ahead of the chassis' centre\n", double(forkAhead));

	// Lift.
	slider.setTargetLinMotorVelocity(btScalar(0.4));
	for (int i = 0; i < 300 && slider.getLinearPos() < btScalar(1.0) && !script.spent(); ++i)
	{
		script.run(1);
		if (i % 60 == 0) report("lift");
	}
	slider.setTargetLinMotorVelocity(0);
	script.run(60);
	report("lifted");
	const btScalar loadBottom = load->getCenterOfMassPosition().y() - btScalar(0.4);
	script.judge(loadBottom > btScalar(0.3) + btScalar(0.6), "the load is lifted well above the rails");

	// Carry it 5 m backwards.
	const btScalar startZ = chassis->getCenterOfMassPosition().z();
	// On the fork: the load's bottom on the fork's top (within 2 cm) and its centre over the fork plate
	// (within a quarter metre of the plate's centre, the plate being 1.2 m deep).
	auto onFork = [&]() {
		const btVector3 offset = load->getCenterOfMassPosition() - fork->getCenterOfMassPosition();
		const btScalar gap = offset.dot(fork->getWorldTransform().getBasis().getColumn(1)) - btScalar(0.45);
		const btVector3 across = offset - fork->getWorldTransform().getBasis().getColumn(1) *
		                                      offset.dot(fork->getWorldTransform().getBasis().getColumn(1));
		return btFabs(gap) < btScalar(0.02) && across.length() < btScalar(0.25);
	};
	bool stayedOnFork = onFork();
	btScalar slide = 0;
	for (int i = 0; i < 900 && chassis->getCenterOfMassPosition().z() > startZ - 5 && !script.spent(); ++i)
	{
		drive(btScalar(-1.0));
		script.run(1);
		stayedOnFork = stayedOnFork && onFork();
		const btVector3 offset = load->getCenterOfMassPosition() - fork->getCenterOfMassPosition();
		slide = btMax(slide, btSqrt(offset.x() * offset.x() + offset.z() * offset.z()));
		if (i % 60 == 0) report("carry");
	}
	stop();
	script.run(90);
	report("carried");
	script.judge(chassis->getCenterOfMassPosition().z() < startZ - btScalar(4.9), "reversed 5 m");
	printf("  the load's centre was at most %.2f m from the fork's centre\n", double(slide));
	script.judge(stayedOnFork, "the load stayed on the fork");

	// Set it down on the ground.
	slider.setTargetLinMotorVelocity(btScalar(-0.4));
	script.run(300);
	report("lowered");
	script.run(120);
	report("rest");
	script.judge(slider.getLinearPos() < btScalar(0.02) && onFork() && load->getLinearVelocity().length() < btScalar(0.01),
	      "lowered, the load rests on the fork");

	pictures.capture(world);
	return pictures.finish(script.verdict("ForkLiftDemo"));
}
