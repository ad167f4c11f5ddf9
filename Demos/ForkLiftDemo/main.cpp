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
#include "WorldScene.h"
#include "btBulletDynamicsCommon.h"

namespace
{
const btScalar kStep = btScalar(1. / 60.);
int failures = 0;

void check(bool ok, const char* what)
{
	printf("  check: %s: %s\n", what, ok ? "ok" : "FAILED");
	if (!ok) ++failures;
}

struct Bodies
{
	btAlignedObjectArray<btCollisionShape*> shapes;
	btAlignedObjectArray<btRigidBody*> bodies;
	btDiscreteDynamicsWorld* world;

	btRigidBody* box(const btVector3& halfExtents, btScalar mass, const btVector3& origin, btScalar friction = 1)
	{
		btBoxShape* shape = new btBoxShape(halfExtents);
		shapes.push_back(shape);
		btVector3 inertia(0, 0, 0);
		if (mass > 0) shape->calculateLocalInertia(mass, inertia);
		btRigidBody* body = new btRigidBody(btRigidBody::btRigidBodyConstructionInfo(
		    mass, new btDefaultMotionState(btTransform(btQuaternion::getIdentity(), origin)), shape, inertia));
		body->setFriction(friction);
		if (mass > 0) body->setActivationState(DISABLE_DEACTIVATION);
		bodies.push_back(body);
		world->addRigidBody(body);
		return body;
	}
	~Bodies()
	{
		for (int i = bodies.size() - 1; i >= 0; --i)
		{
			world->removeRigidBody(bodies[i]);
			delete bodies[i]->getMotionState();
			delete bodies[i];
		}
		for (int i = 0; i < shapes.size(); ++i) delete shapes[i];
	}
};
}  // namespace

int main(int argc, char** argv)
{
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "ForkLiftDemo";
	commandLine.defaultFrames = 1000000;  // more than the script takes: by default it runs to its end
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();

	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
	world.setGravity(btVector3(0, -10, 0));
	Bodies parts;
	parts.world = &world;

	parts.box(btVector3(50, 1, 50), 0, btVector3(0, -1, 0));  // ground, top at y = 0
	// Two rails 0.3 m high, 0.7 m apart inside, and the load on them.
	parts.box(btVector3(btScalar(0.1), btScalar(0.15), btScalar(0.6)), 0, btVector3(btScalar(-0.45), btScalar(0.15), 10));
	parts.box(btVector3(btScalar(0.1), btScalar(0.15), btScalar(0.6)), 0, btVector3(btScalar(0.45), btScalar(0.15), 10));
	btRigidBody* load = parts.box(btVector3(btScalar(0.5), btScalar(0.4), btScalar(0.5)), 100,
	                              btVector3(0, btScalar(0.7), 10));

	// The fork lift: chassis, mast (hinged to the chassis' front), fork (sliding up the mast).
	const btScalar chassisY = btScalar(1.05);
	btRigidBody* chassis = parts.box(btVector3(btScalar(0.9), btScalar(0.4), btScalar(1.8)), 800, btVector3(0, chassisY, 0));
	btRigidBody* mast = parts.box(btVector3(btScalar(0.8), btScalar(1.2), btScalar(0.05)), 50,
	                              btVector3(0, btScalar(1.45), btScalar(1.95)));
	const btVector3 forkStart(0, btScalar(0.15), btScalar(2.62));
	btRigidBody* fork = parts.box(btVector3(btScalar(0.3), btScalar(0.05), btScalar(0.6)), 20, forkStart);

	btHingeConstraint hinge(*chassis, *mast, btVector3(0, btScalar(0.25) - chassisY, btScalar(1.95)),
	                        btVector3(0, btScalar(-1.2), 0), btVector3(1, 0, 0), btVector3(1, 0, 0));
	hinge.setLimit(btScalar(-0.01), btScalar(0.01));
	world.addConstraint(&hinge, true);
	// The slide axis is the frames' x axis, turned to point up; position 0 is the fork's start.
	const btQuaternion xToUp(btVector3(0, 0, 1), SIMD_HALF_PI);
	btSliderConstraint slider(*mast, *fork,
	                          btTransform(xToUp, forkStart - mast->getCenterOfMassPosition()),
	                          btTransform(xToUp, btVector3(0, 0, 0)), true);
	slider.setLowerLinLimit(0);
	slider.setUpperLinLimit(btScalar(1.5));
	slider.setLowerAngLimit(0);
	slider.setUpperAngLimit(0);
	slider.setPoweredLinMotor(true);
	slider.setMaxLinMotorForce(5000);
	slider.setTargetLinMotorVelocity(0);
	world.addConstraint(&slider, true);

	btRaycastVehicle::btVehicleTuning tuning;
	tuning.m_suspensionStiffness = 40;
	tuning.m_suspensionCompression = btScalar(6.3);  // about critical for k = 40 per kg on four wheels
	tuning.m_suspensionDamping = btScalar(6.3);
	tuning.m_frictionSlip = 1;
	btDefaultVehicleRaycaster raycaster(&world);
	btRaycastVehicle vehicle(tuning, chassis, &raycaster);
	vehicle.setCoordinateSystem(0, 1, 2);
	for (int i = 0; i < 4; ++i)
		vehicle.addWheel(btVector3((i & 1) ? btScalar(-0.8) : btScalar(0.8), btScalar(-0.1), i < 2 ? btScalar(1.3) : btScalar(-1.3)),
		                 btVector3(0, -1, 0), btVector3(-1, 0, 0), btScalar(0.6), btScalar(0.4), tuning, i < 2);
	world.addAction(&vehicle);

	pictures.setDecorator([&](caliber::demo::Scene& scene) { caliber::demo::addVehicleWheels(scene, vehicle, btScalar(0.24)); });

	btScalar t = 0;
	// --frames: once the budget is spent no phase steps any more, and the unfinished phases' checks are skipped.
	caliber::demo::StepBudget budget = pictures.stepBudget();
	auto run = [&](int count) {
		for (int i = 0; i < count && !budget.spent(); ++i)
		{
			world.stepSimulation(kStep, 1, kStep);
			budget.count();
			t += kStep;
		}
	};
	auto judge = [&](bool ok, const char* what) {
		if (budget.reached(what)) check(ok, what);
	};
	auto report = [&](const char* phase)
	{
		const btVector3 c = chassis->getCenterOfMassPosition(), l = load->getCenterOfMassPosition();
		printf("%-8s t %5.2f s  fork lift z %6.2f  speed %5.1f km/h  fork height %5.2f m  load (%5.2f, %5.2f, %5.2f)\n",
		       phase, t, c.z(), vehicle.getCurrentSpeedKmHour(), slider.getLinearPos(), l.x(), l.y(), l.z());
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
	run(120);
	report("ready");

	// To the load, fork low, slowing near it, until the fork is centred under it.
	const btScalar forkAhead = fork->getCenterOfMassPosition().z() - chassis->getCenterOfMassPosition().z();
	for (int i = 0; i < 1200 && !budget.spent(); ++i)
	{
		const btScalar left = load->getCenterOfMassPosition().z() - fork->getCenterOfMassPosition().z();
		if (left < btScalar(0.02)) break;
		drive(btMin(btScalar(1.5), btMax(btScalar(0.2), left)));
		run(1);
		if (i % 60 == 0) report("approach");
	}
	stop();
	run(60);
	report("under");
	const btVector3 forkAtLoad = fork->getCenterOfMassPosition();
	judge(fabs(forkAtLoad.z() - load->getCenterOfMassPosition().z()) < 0.15 && fabs(forkAtLoad.x()) < 0.1,
	      "the fork is under the load");
	printf("  fork %.2f m ahead of the chassis' centre\n", double(forkAhead));

	// Lift.
	slider.setTargetLinMotorVelocity(btScalar(0.4));
	for (int i = 0; i < 300 && slider.getLinearPos() < btScalar(1.0) && !budget.spent(); ++i)
	{
		run(1);
		if (i % 60 == 0) report("lift");
	}
	slider.setTargetLinMotorVelocity(0);
	run(60);
	report("lifted");
	const btScalar loadBottom = load->getCenterOfMassPosition().y() - btScalar(0.4);
	judge(loadBottom > btScalar(0.3) + btScalar(0.6), "the load is lifted well above the rails");

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
	for (int i = 0; i < 900 && chassis->getCenterOfMassPosition().z() > startZ - 5 && !budget.spent(); ++i)
	{
		drive(btScalar(-1.0));
		run(1);
		stayedOnFork = stayedOnFork && onFork();
		const btVector3 offset = load->getCenterOfMassPosition() - fork->getCenterOfMassPosition();
		slide = btMax(slide, btSqrt(offset.x() * offset.x() + offset.z() * offset.z()));
		if (i % 60 == 0) report("carry");
	}
	stop();
	run(90);
	report("carried");
	judge(chassis->getCenterOfMassPosition().z() < startZ - btScalar(4.9), "reversed 5 m");
	printf("  the load's centre was at most %.2f m from the fork's centre\n", double(slide));
	judge(stayedOnFork, "the load stayed on the fork");

	// Set it down on the ground.
	slider.setTargetLinMotorVelocity(btScalar(-0.4));
	run(300);
	report("lowered");
	run(120);
	report("rest");
	judge(slider.getLinearPos() < btScalar(0.02) && onFork() && load->getLinearVelocity().length() < btScalar(0.01),
	      "lowered, the load rests on the fork");

	pictures.capture(world);
	world.removeAction(&vehicle);
	world.removeConstraint(&slider);
	world.removeConstraint(&hinge);
	printf("ForkLiftDemo: %s\n", failures ? "FAILED" : "all checks passed");
	return pictures.finish(failures ? 1 : 0);
}
