// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// VehicleDemo: a raycast vehicle (800 kg, four wheels of radius 0.4 m) on a 128 m height field with a
// patch of bumps, a ramp up to a 1 m plateau and down again, headless. The car settles on its springs,
// drives off over the bumps and the ramp, brakes to a stop, then drives a circle. It prints speed,
// wheel contacts and suspension lengths as it goes.
// Checks: at rest each spring is compressed by g / (k n) (stiffness per unit chassis mass, n = 4
// wheels) within 1 mm; the car climbs onto the plateau with all wheels on the ground; braking stops it
// within v^2 / (2 mu g) + 10%; the circle's radius is wheelbase / tan(steer) within 5%; the chassis
// stays upright. Exit 1 when a check fails. --frames N stops the script after N steps (the whole
// script is about 2900); the checks of the phases it did not finish are skipped. --png shows the last
// frame with the wheels (docs/demos.md).

#include <math.h>
#include <stdio.h>

#include <vector>

#include "DemoPictures.h"
#include "DemoScript.h"
#include "VehicleScene.h"
#include "WorldScene.h"

namespace
{
using namespace vehicle_demo;
const btScalar kStep = btScalar(1. / 60.);

int wheelsOnGround(const btRaycastVehicle& car)
{
	int n = 0;
	for (int i = 0; i < car.getNumWheels(); ++i) n += car.getWheelInfo(i).m_raycastInfo.m_isInContact ? 1 : 0;
	return n;
}

void printState(const char* phase, btScalar t, const btRaycastVehicle& car)
{
	const btVector3 p = car.getChassisWorldTransform().getOrigin();
	printf("%-8s t %5.2f s  z %7.2f  y %5.2f  speed %6.1f km/h  wheels on ground %d  suspension", phase, t, p.z(),
	       p.y(), car.getCurrentSpeedKmHour(), wheelsOnGround(car));
	for (int i = 0; i < car.getNumWheels(); ++i) printf(" %.3f", car.getWheelInfo(i).m_raycastInfo.m_suspensionLength);
	printf(" m\n");
}

double fittedRadius(const std::vector<btVector3>& points)
{
	// Kasa's algebraic least-squares circle in the ground plane.
	double m[3][4] = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}};
	for (const btVector3& p : points)
	{
		const double row[4] = {p.x(), p.z(), 1, p.x() * p.x() + p.z() * p.z()};
		for (int i = 0; i < 3; ++i)
			for (int k = 0; k < 4; ++k) m[i][k] += row[i] * row[k];
	}
	for (int c = 0; c < 3; ++c)
		for (int r = c + 1; r < 3; ++r)
		{
			const double f = m[r][c] / m[c][c];
			for (int k = c; k < 4; ++k) m[r][k] -= f * m[c][k];
		}
	double s[3];
	for (int r = 2; r >= 0; --r)
	{
		double v = m[r][3];
		for (int k = r + 1; k < 3; ++k) v -= m[r][k] * s[k];
		s[r] = v / m[r][r];
	}
	return sqrt(s[2] + s[0] * s[0] / 4 + s[1] * s[1] / 4);
}
}  // namespace

int main(int argc, char** argv)
{
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "VehicleDemo";
	commandLine.defaultFrames = 1000000;  // more than the script takes: by default it runs to its end
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();

	vehicle_demo::Scene scene;
	btDiscreteDynamicsWorld& world = scene.world();
	btRigidBody& chassis = scene.chassis();
	btRaycastVehicle& car = scene.car();

	pictures.setDecorator([&](caliber::demo::Scene& drawing) {
		caliber::demo::addVehicleWheels(drawing, car, kWheelWidth);
		// Frame the car and a few metres around it.
		const btVector3 p = chassis.getCenterOfMassPosition();
		drawing.focusOn(p - btVector3(3, 1, 4), p + btVector3(3, 2, 4));
	});

	// --frames: once the budget is spent no phase steps any more, and the unfinished phases' checks are skipped.
	caliber::demo::DemoScript script(world, kStep, pictures.stepBudget());
	bool upright = true;
	auto watch = [&]() { upright = upright && chassis.getWorldTransform().getBasis().getColumn(1).y() > btScalar(0.9); };

	printf("VehicleDemo: an 800 kg car on a height field (bumps, a 1 m ramp), k = %.0f per kg, mu = %.1f\n",
	       double(kStiffness), double(kFriction));
	script.run(180);
	printState("settled", script.time(), car);
	const btScalar sag = kGravity / (kStiffness * 4);
	bool sagOk = wheelsOnGround(car) == 4;
	for (int i = 0; i < 4; ++i)
		sagOk = sagOk && fabs(kRestLength - car.getWheelInfo(i).m_raycastInfo.m_suspensionLength - sag) < 1e-3;
	printf("  expected static sag g / (k n) = %.4f m\n", double(sag));
	script.judge(sagOk, "static sag on all four wheels");

	// Drive: rear-wheel drive over the bumps and the ramp, until past the plateau.
	car.applyEngineForce(1200, 2);
	car.applyEngineForce(1200, 3);
	btScalar highest = 0;
	bool allWheelsOnPlateau = false;
	for (int i = 0; i < 1200 && chassis.getCenterOfMassPosition().z() < 25 && !script.spent(); ++i)
	{
		script.run(1);
		watch();
		const btVector3 p = chassis.getCenterOfMassPosition();
		highest = btMax(highest, p.y());
		if (p.z() > 2 && p.z() < 6 && wheelsOnGround(car) == 4) allWheelsOnPlateau = true;
		if (i % 60 == 0) printState("drive", script.time(), car);
	}
	printState("drive", script.time(), car);
	script.judge(highest > btScalar(1.8), "the car climbed the ramp onto the 1 m plateau");
	script.judge(allWheelsOnPlateau, "all four wheels on the ground on the plateau");

	// Brake hard: every tyre slides at its grip.
	car.applyEngineForce(0, 2);
	car.applyEngineForce(0, 3);
	const btScalar v0 = chassis.getLinearVelocity().length();
	const btScalar z0 = chassis.getCenterOfMassPosition().z();
	for (int i = 0; i < 4; ++i) car.setBrake(200, i);
	for (int i = 0; i < 600 && btFabs(chassis.getLinearVelocity().z()) > btScalar(0.01) && !script.spent(); ++i)
	{
		script.run(1);
		watch();
		if (i % 30 == 0) printState("brake", script.time(), car);
	}
	const btScalar distance = chassis.getCenterOfMassPosition().z() - z0;
	const btScalar expected = v0 * v0 / (2 * kFriction * kGravity);
	printState("stopped", script.time(), car);
	printf("  braking from %.2f m/s: %.2f m (v^2 / (2 mu g) = %.2f m)\n", double(v0), double(distance),
	       double(expected));
	script.judge(fabs(distance - expected) < 0.1 * expected, "braking distance");

	// A circle at walking pace, front wheels at Ackermann's angles for the bicycle angle 0.3 rad.
	for (int i = 0; i < 4; ++i) car.setBrake(0, i);
	const btScalar steer = btScalar(0.3), wheelbase = 2 * kHalfWheelbase;
	const btScalar radius = wheelbase / btTan(steer);
	car.setSteeringValue(btAtan(wheelbase / (radius - kHalfTrack)), 0);
	car.setSteeringValue(btAtan(wheelbase / (radius + kHalfTrack)), 1);
	std::vector<btVector3> path;
	for (int i = 0; i < 1500 && !script.spent(); ++i)
	{
		const btScalar speed = car.getCurrentSpeedKmHour() / btScalar(3.6);
		const btScalar throttle = btMax(btScalar(-1500), btMin(btScalar(1500), 800 * (4 - speed)));
		car.applyEngineForce(throttle, 2);
		car.applyEngineForce(throttle, 3);
		script.run(1);
		watch();
		if (i >= 300) path.push_back(chassis.getWorldTransform()(btVector3(0, 0, -kHalfWheelbase)));
		if (i % 150 == 0) printState("circle", script.time(), car);
	}
	const double measured = path.size() >= 3 ? fittedRadius(path) : 0;  // a shortened run may not reach the circle
	printf("  circle of the rear axle: radius %.2f m (wheelbase / tan(steer) = %.2f m)\n", measured, double(radius));
	script.judge(fabs(measured - radius) < 0.05 * radius, "cornering radius");
	script.check(upright, "the chassis stayed upright");

	pictures.capture(world);
	return pictures.finish(script.verdict("VehicleDemo"));
}
