// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The raycast vehicle against first principles: static sag, coasting, braking distance, cornering
// radius, wheel spin, and rest without drift (docs/actions.md gives the model these follow).

#include <gtest/gtest.h>

#include <vector>

#include "VehicleTestUtil.h"

using caliber_test::CarSpec;
using caliber_test::TestCar;
using caliber_test::TestWorld;

namespace
{
const btScalar kStep = btScalar(1. / 60.);
const btScalar kGravity = 10;  // TestWorld's

// A flat road large enough for every run here (the test world's ground is 100 m across).
void addRoad(TestWorld& w) { w.addBody(w.shape<btBoxShape>(btVector3(500, 1, 500)), 0, btVector3(0, -1, 0)); }

void settle(TestWorld& w, int steps = 240) { w.run(steps, kStep); }

// The chassis' largest distance from start over the next steps.
btScalar largestExcursion(TestWorld& w, TestCar& car, const btVector3& start, int steps)
{
	btScalar worst = 0;
	for (int i = 0; i < steps; ++i)
	{
		w.run(1, kStep);
		worst = btMax(worst, (car.chassis()->getCenterOfMassPosition() - start).length());
	}
	return worst;
}

// Least-squares circle through points in the ground plane (x, z): Kasa's algebraic fit.
btScalar fittedRadius(const std::vector<btVector3>& points)
{
	double sxx = 0, sxz = 0, szz = 0, sx = 0, sz = 0, sxr = 0, szr = 0, sr = 0;
	const double n = double(points.size());
	for (const btVector3& p : points)
	{
		const double x = p.x(), z = p.z(), r = x * x + z * z;
		sxx += x * x, sxz += x * z, szz += z * z, sx += x, sz += z, sxr += x * r, szr += z * r, sr += r;
	}
	// Solve [sxx sxz sx; sxz szz sz; sx sz n] [a b c] = [sxr szr sr]; circle x^2+z^2 = a x + b z + c.
	double m[3][4] = {{sxx, sxz, sx, sxr}, {sxz, szz, sz, szr}, {sx, sz, n, sr}};
	for (int col = 0; col < 3; ++col)
		for (int row = col + 1; row < 3; ++row)
		{
			const double f = m[row][col] / m[col][col];
			for (int k = col; k < 4; ++k) m[row][k] -= f * m[col][k];
		}
	double sol[3];
	for (int row = 2; row >= 0; --row)
	{
		double v = m[row][3];
		for (int k = row + 1; k < 3; ++k) v -= m[row][k] * sol[k];
		sol[row] = v / m[row][row];
	}
	const double cx = sol[0] / 2, cz = sol[1] / 2;
	return btScalar(std::sqrt(sol[2] + cx * cx + cz * cz));
}
}  // namespace

TEST(RaycastVehiclePhysics, StaticSagIsMassTimesGravityOverStiffnessTimesWheels)
{
	// Stiffness is per unit chassis mass (Bullet's convention): each wheel pushes with k m x, so n
	// wheels carry m g at x = m g / (k m n) = g / (k n).
	TestWorld w;
	addRoad(w);
	CarSpec spec;
	TestCar car(w, spec);
	settle(w, 600);
	const btScalar expectedSag = kGravity / (spec.stiffness * 4);
	for (int i = 0; i < 4; ++i)
	{
		const btWheelInfo& wheel = car.vehicle()->getWheelInfo(i);
		ASSERT_TRUE(wheel.m_raycastInfo.m_isInContact);
		const btScalar sag = spec.restLength - wheel.m_raycastInfo.m_suspensionLength;
		EXPECT_NEAR(sag, expectedSag, btScalar(1e-4)) << "wheel " << i;
		EXPECT_NEAR(wheel.m_wheelsSuspensionForce, spec.mass * kGravity / 4, btScalar(0.5)) << "wheel " << i;
	}
	// The chassis sits where the geometry says: wheel radius + suspension length above the ground.
	const btScalar expectedHeight = spec.radius + spec.restLength - expectedSag - spec.hardPointY;
	EXPECT_NEAR(car.chassis()->getCenterOfMassPosition().y(), expectedHeight, btScalar(1e-3));
}

TEST(RaycastVehiclePhysics, CoastingKeepsItsSpeedWithoutRollingResistance)
{
	// The documented rolling resistance is zero: a free-rolling car on flat ground, with no damping on
	// the chassis, keeps its speed; the tolerance covers the suspension's settling after the start.
	TestWorld w;
	addRoad(w);
	TestCar car(w);
	settle(w);
	car.chassis()->setLinearVelocity(btVector3(0, 0, 10));
	w.run(30, kStep);
	const btScalar start = car.forwardSpeed();
	w.run(300, kStep);
	EXPECT_NEAR(car.forwardSpeed(), start, btScalar(0.005) * start) << "speed after 5 s of coasting";
	EXPECT_NEAR(car.vehicle()->getCurrentSpeedKmHour(), btScalar(3.6) * car.forwardSpeed(), btScalar(0.1));
}

TEST(RaycastVehiclePhysics, WheelSpinMatchesGroundSpeedOverRadius)
{
	TestWorld w;
	addRoad(w);
	TestCar car(w);
	settle(w);
	car.chassis()->setLinearVelocity(btVector3(0, 0, 8));
	w.run(60, kStep);
	for (int i = 0; i < 4; ++i)
	{
		const btWheelInfo& wheel = car.vehicle()->getWheelInfo(i);
		const btScalar spin = wheel.m_deltaRotation / kStep;
		EXPECT_NEAR(spin, car.forwardSpeed() / car.spec().radius, btScalar(0.002) * spin) << "wheel " << i;
	}
	// The rendered wheel turns with it: its frame rotates about the axle by the accumulated angle.
	const btScalar before = car.vehicle()->getWheelInfo(0).m_rotation;
	w.run(30, kStep);
	const btScalar after = car.vehicle()->getWheelInfo(0).m_rotation;
	EXPECT_NEAR(after - before, car.forwardSpeed() * btScalar(0.5) / car.spec().radius, btScalar(0.02));
}

TEST(RaycastVehiclePhysics, BrakingDistanceFrom20MetresPerSecondIsVSquaredOverTwoMuG)
{
	// Brakes far stronger than the grip: every tyre slides at the friction circle, frictionSlip times
	// its suspension force, and the loads add up to m g, so the car stops in v^2 / (2 mu g).
	TestWorld w;
	addRoad(w);
	CarSpec spec;
	TestCar car(w, spec);
	settle(w);
	car.chassis()->setLinearVelocity(btVector3(0, 0, 20));
	w.run(2, kStep);
	const btScalar v0 = car.forwardSpeed();
	const btScalar z0 = car.chassis()->getCenterOfMassPosition().z();
	car.brake(1e4);
	int steps = 0;
	while (car.forwardSpeed() > btScalar(0.01) && steps < 1200)
	{
		w.run(1, kStep);
		++steps;
	}
	const btScalar distance = car.chassis()->getCenterOfMassPosition().z() - z0;
	const btScalar expected = v0 * v0 / (2 * spec.frictionSlip * kGravity);
	// 2%: the load moves to the front while pitching, and the step is discrete (v h = 0.33 m at first).
	EXPECT_NEAR(distance, expected, btScalar(0.02) * expected) << "stopped after " << steps << " steps";
	for (int i = 0; i < 4; ++i) EXPECT_EQ(car.vehicle()->getWheelInfo(i).m_skidInfo, btScalar(1));
}

TEST(RaycastVehiclePhysics, LowSpeedCorneringRadiusIsWheelbaseOverTanSteering)
{
	// Kinematic steering at low speed (no tyre slip): the rear axle's centre runs on a circle of radius
	// wheelbase / tan(steer), steer being the bicycle model's angle. The front wheels get Ackermann's
	// angles for that circle, atan(wheelbase / (R -+ half track)), so no tyre has to slide.
	TestWorld w;
	addRoad(w);
	CarSpec spec;
	TestCar car(w, spec);
	settle(w);
	const btScalar steer = btScalar(0.15);
	const btScalar wheelbase = 2 * spec.halfWheelbase;
	const btScalar expected = wheelbase / btTan(steer);
	// Positive steering turns towards +x, where wheel 0 is: it is the inner wheel.
	car.vehicle()->setSteeringValue(btAtan(wheelbase / (expected - spec.halfTrack)), 0);
	car.vehicle()->setSteeringValue(btAtan(wheelbase / (expected + spec.halfTrack)), 1);
	car.chassis()->setLinearVelocity(btVector3(0, 0, 3));
	w.run(60, kStep);
	std::vector<btVector3> path;
	for (int i = 0; i < 600; ++i)
	{
		w.run(1, kStep);
		path.push_back(car.rearAxleCentre());
	}
	// 1%: the lateral acceleration v^2 / R = 0.5 m/s^2 rolls the body slightly, moving the contacts.
	EXPECT_NEAR(fittedRadius(path), expected, btScalar(0.01) * expected);
	EXPECT_GT(car.forwardSpeed(), btScalar(2.9)) << "no tyre scrubs, so the car keeps its speed";
}

TEST(RaycastVehiclePhysics, AtRestNoDriftOrJitterOverTenSeconds)
{
	TestWorld w;
	addRoad(w);
	TestCar car(w);
	settle(w, 300);
	const btVector3 start = car.chassis()->getCenterOfMassPosition();
	const btScalar worst = largestExcursion(w, car, start, 600);
	EXPECT_LT(worst, btScalar(1e-4)) << "largest excursion over 10 s (m)";
}

TEST(RaycastVehiclePhysics, BrakedAtStandstillOnASlopeNeitherCreepsNorJitters)
{
	// A 10% slope: gravity pulls the car downhill by m g sin(a) = 800 N, the brakes hold up to 100 N s
	// per substep each. Bullet's brake jitters here and lets the car creep.
	const btScalar slope = btScalar(0.1);
	TestWorld w;
	btRigidBody* ground = w.addBody(w.shape<btBoxShape>(btVector3(50, 1, 50)), 0,
	                                btTransform(btQuaternion(btVector3(1, 0, 0), -slope), btVector3(0, -1, 0)));
	(void)ground;
	TestCar car(w, CarSpec(), btTransform(btQuaternion(btVector3(1, 0, 0), -slope), btVector3(0, 1, 0)));
	car.brake(100);
	settle(w, 300);
	const btVector3 start = car.chassis()->getCenterOfMassPosition();
	const btScalar worst = largestExcursion(w, car, start, 600);
	EXPECT_LT(worst, btScalar(1e-4)) << "largest excursion over 10 s (m)";
	// Released, it rolls down the hill (the slope is real).
	car.brake(0);
	w.run(120, kStep);
	EXPECT_GT((car.chassis()->getCenterOfMassPosition() - start).length(), btScalar(1));
}

TEST(RaycastVehiclePhysics, EngineForceIsLimitedByGripWhenTheSideImpulseIsZero)
{
	// Straight ahead the side impulse is exactly 0 (or -0); the engine asks for 2 g of acceleration on
	// tyres with mu = 0.8, so the friction circle must cap it at mu g (Bullet skips the cap then).
	TestWorld w;
	addRoad(w);
	CarSpec spec;
	TestCar car(w, spec);
	settle(w);
	car.engine(spec.mass * 2 * kGravity / 4);
	const btScalar v0 = car.forwardSpeed();
	w.run(60, kStep);
	const btScalar acceleration = (car.forwardSpeed() - v0) / btScalar(1);
	EXPECT_LE(acceleration, spec.frictionSlip * kGravity * btScalar(1.01));
	EXPECT_GT(acceleration, spec.frictionSlip * kGravity * btScalar(0.9));
	EXPECT_LT(car.vehicle()->getWheelInfo(0).m_skidInfo, btScalar(1));
}

TEST(RaycastVehiclePhysics, WheelClimbsAPlankInsteadOfSinkingIntoIt)
{
	// A plank 5 cm high and 15 cm wide across the road. One ray at the wheel's centre would let the
	// tyre sink into it until the centre is above it (5 cm); the wheel's rays span its whole circle,
	// and where neighbouring rays see different surfaces the edge between them is found by bisection,
	// so the tyre never overlaps the plank by more than 1/32 of the rays' spacing times the circle's
	// slope there (3 mm).
	TestWorld w;
	addRoad(w);
	const btScalar plankHalfWidth = btScalar(0.075), plankHeight = btScalar(0.05), plankZ = 4;
	w.addBody(w.shape<btBoxShape>(btVector3(5, plankHeight / 2, plankHalfWidth)), 0,
	          btVector3(0, plankHeight / 2, plankZ));
	TestCar car(w);
	settle(w);
	car.chassis()->setLinearVelocity(btVector3(0, 0, 1));
	btScalar worstOverlap = 0;
	for (int i = 0; i < 420; ++i)
	{
		w.run(1, kStep);
		const btWheelInfo& wheel = car.vehicle()->getWheelInfo(0);
		const btVector3 centre =
		    wheel.m_raycastInfo.m_hardPointWS + wheel.m_raycastInfo.m_wheelDirectionWS * wheel.m_raycastInfo.m_suspensionLength;
		// Distance from the wheel's centre to the plank's cross-section (a rectangle in y, z).
		const btScalar dz = btMax(btScalar(0), btFabs(centre.z() - plankZ) - plankHalfWidth);
		const btScalar dy = btMax(btScalar(0), centre.y() - plankHeight);
		worstOverlap = btMax(worstOverlap, car.spec().radius - btSqrt(dz * dz + dy * dy));
	}
	EXPECT_GT(car.vehicle()->getWheelInfo(0).m_raycastInfo.m_hardPointWS.z(), plankZ + 1) << "the car crossed it";
	EXPECT_LT(worstOverlap, btScalar(0.003)) << "deepest overlap of tyre and plank (m)";
}

TEST(RaycastVehiclePhysics, BrakedCarCarryingAJointedMastDoesNotCreep)
{
	// A 50 kg mast hinged to the car's front and held by the hinge's limits (a fork lift's): its weight
	// reaches the chassis through the solver, after which the tyre rows cannot anticipate it, so only
	// the held wheels' anchors keep the car in place. Without them it creeps 16 cm in 10 s.
	TestWorld w;
	addRoad(w);
	CarSpec spec;
	TestCar car(w, spec);
	btRigidBody* mast = w.addBody(w.shape<btBoxShape>(btVector3(btScalar(0.8), btScalar(1.2), btScalar(0.05))), 50,
	                              btVector3(0, btScalar(1.45), btScalar(2.1)));
	mast->setActivationState(DISABLE_DEACTIVATION);
	btHingeConstraint* hinge = w.addJoint<btHingeConstraint>(
	    true, *car.chassis(), *mast, btVector3(0, btScalar(-0.75), btScalar(2.1)), btVector3(0, btScalar(-1.2), 0),
	    btVector3(1, 0, 0), btVector3(1, 0, 0));
	hinge->setLimit(btScalar(-0.01), btScalar(0.01));
	car.brake(50);
	settle(w, 300);
	const btVector3 start = car.chassis()->getCenterOfMassPosition();
	const btScalar worst = largestExcursion(w, car, start, 600);
	EXPECT_LT(worst, btScalar(1e-3)) << "largest excursion over 10 s (m)";
}
