// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The contact set-up runs an AVX2 build of its point fill on processors that have AVX2 (btContactRowSetup.h):
// the same operations in the same order, so every row must have the bits of the baseline (SSE) build. These
// tests fill the rows of many varied points both ways, degenerate ones included, and compare every byte of
// every row, the points' friction directions and flags, and the bodies' velocities after the warm starts.

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "BulletDynamics/ConstraintSolver/btContactRowSetup.h"
#include "BulletDynamics/ConstraintSolver/btSolverScratch.h"
#include "btBulletDynamicsCommon.h"

namespace
{
// A small deterministic generator (xorshift), so that a failure can be replayed.
struct Random
{
	uint32_t state = 0x9e3779b9u;
	uint32_t next()
	{
		state ^= state << 13;
		state ^= state >> 17;
		state ^= state << 5;
		return state;
	}
	btScalar uniform(btScalar lo, btScalar hi) { return lo + (hi - lo) * btScalar(next() % 1000001u) / btScalar(1000000); }
	btVector3 vector(btScalar scale) { return btVector3(uniform(-scale, scale), uniform(-scale, scale), uniform(-scale, scale)); }
	btVector3 unitVector()
	{
		btVector3 v = vector(1);
		if (v.length2() < btScalar(1e-4)) v.setValue(0, 1, 0);
		return v.normalized();
	}
	bool chance(int percent) { return int(next() % 100u) < percent; }
};

// Bodies of every kind a contact row meets: dynamic (turned, uneven inertia), with locked axes, static with
// a rigid body, and the solver's fixed body without one.
struct Bodies
{
	btBoxShape shape{btVector3(btScalar(0.5), btScalar(0.25), btScalar(1))};
	std::vector<std::unique_ptr<btRigidBody>> rigid;
	btAlignedObjectArray<btSolverBody> solver;

	explicit Bodies(Random& random)
	{
		const btScalar masses[] = {1, btScalar(3.5), btScalar(0.02), 0, 40, 1};
		for (int i = 0; i < 6; ++i)
		{
			btVector3 inertia(0, 0, 0);
			if (masses[i] > 0) shape.calculateLocalInertia(masses[i], inertia);
			btRigidBody::btRigidBodyConstructionInfo info(masses[i], nullptr, &shape, inertia);
			rigid.emplace_back(new btRigidBody(info));
			btRigidBody& body = *rigid.back();
			btTransform pose(btQuaternion(random.unitVector(), random.uniform(0, 3)), random.vector(5));
			body.setWorldTransform(pose);
			body.updateInertiaTensor();
			if (i == 1) body.setAngularFactor(btVector3(0, 1, 0));
			if (i == 5) body.setLinearFactor(btVector3(1, 0, 1));
			if (masses[i] > 0)
			{
				body.applyCentralForce(random.vector(30));
				body.applyTorque(random.vector(5));
			}
		}
		// Anisotropic friction, sliding on one body and rolling on another.
		rigid[2]->setAnisotropicFriction(btVector3(1, btScalar(0.2), btScalar(0.6)),
		                                 btCollisionObject::CF_ANISOTROPIC_FRICTION);
		rigid[4]->setAnisotropicFriction(btVector3(btScalar(0.5), 1, btScalar(0.3)),
		                                 btCollisionObject::CF_ANISOTROPIC_ROLLING_FRICTION);
		for (int i = 0; i < 7; ++i)
		{
			btSolverBody body;
			std::memset(static_cast<void*>(&body), 0, sizeof(body));
			body.m_worldTransform.setIdentity();
			if (i < 6)
			{
				btRigidBody& rb = *rigid[i];
				body.m_originalBody = &rb;
				body.m_worldTransform = rb.getWorldTransform();
				body.m_invMass = rb.getLinearFactor() * rb.getInvMass();
				body.m_angularFactor = rb.getAngularFactor();
				body.m_linearFactor = rb.getLinearFactor();
				if (rb.getInvMass() > 0)
				{
					body.m_linearVelocity = random.vector(3);
					body.m_angularVelocity = random.vector(2);
				}
			}
			solver.push_back(body);  // index 6: the fixed body, no rigid body, nothing moves it
		}
	}
};

// A point between two of the bodies, with the variety the set-up branches on.
btManifoldPoint makePoint(Random& random, const btSolverBody& a, const btSolverBody& b, int kind)
{
	btVector3 normal = random.unitVector();
	if (kind % 5 == 1) normal.setValue(0, 1, 0);  // axis-aligned (btPlaneSpace1's own branch)
	if (kind % 5 == 2) normal.setValue(0, 0, -1);
	const btVector3 onB = (a.m_worldTransform.getOrigin() + b.m_worldTransform.getOrigin()) * btScalar(0.5) +
	                      random.vector(btScalar(0.5));
	const btScalar distance = kind % 7 == 3 ? btScalar(0) : random.uniform(btScalar(-0.05), btScalar(0.02));
	btManifoldPoint cp(btVector3(0, 0, 0), btVector3(0, 0, 0), normal, distance);
	cp.m_positionWorldOnB = onB;
	cp.m_positionWorldOnA = onB + normal * distance;
	cp.m_combinedFriction = random.uniform(0, 1);
	cp.m_combinedRestitution = random.chance(20) ? random.uniform(btScalar(0.1), 1) : btScalar(0);
	cp.m_combinedRollingFriction = random.chance(15) ? random.uniform(0, btScalar(0.1)) : btScalar(0);
	cp.m_combinedSpinningFriction = random.chance(15) ? random.uniform(0, btScalar(0.1)) : btScalar(0);
	cp.m_appliedImpulse = random.uniform(0, 5);
	cp.m_appliedImpulseLateral1 = random.uniform(-1, 1);
	cp.m_appliedImpulseLateral2 = random.chance(50) ? random.uniform(-1, 1) : btScalar(0);
	btPlaneSpace1(normal, cp.m_lateralFrictionDir1, cp.m_lateralFrictionDir2);
	if (random.chance(20)) cp.m_contactMotion1 = random.uniform(-1, 1);
	if (random.chance(20)) cp.m_contactMotion2 = random.uniform(-1, 1);
	if (random.chance(20)) cp.m_frictionCFM = random.uniform(0, btScalar(0.01));
	if (random.chance(15))
	{
		cp.m_contactCFM = random.uniform(0, btScalar(0.1));
		cp.m_contactPointFlags |= BT_CONTACT_FLAG_HAS_CONTACT_CFM;
	}
	if (random.chance(15))
	{
		cp.m_contactERP = random.uniform(0, 1);
		cp.m_contactPointFlags |= BT_CONTACT_FLAG_HAS_CONTACT_ERP;
	}
	if (random.chance(15)) cp.m_contactPointFlags |= BT_CONTACT_FLAG_LATERAL_FRICTION_INITIALIZED;
	// Degenerate values: denormal and huge impulses, a distance of -0.
	if (kind % 11 == 4) cp.m_appliedImpulse = std::numeric_limits<btScalar>::denorm_min();
	if (kind % 13 == 5) cp.m_appliedImpulseLateral1 = btScalar(1e30);
	if (kind % 17 == 6) cp.m_distance1 = btScalar(-0.0);
	return cp;
}

struct Fill
{
	btAlignedObjectArray<btSolverBody> bodies;
	btConstraintArray contacts, friction, rolling;
	std::vector<btManifoldPoint> points;
};

// Pools of the right size, every byte set to the same pattern (so that bytes the fill leaves alone compare
// equal and bytes it writes are compared).
void preparePools(Fill& fill, int numContacts, int numFriction, int numRolling)
{
	for (btConstraintArray* pool : {&fill.contacts, &fill.friction, &fill.rolling})
	{
		const int size = pool == &fill.contacts ? numContacts : pool == &fill.friction ? numFriction : numRolling;
		pool->resizeNoInitialize(size);
		if (size > 0) std::memset(static_cast<void*>(&(*pool)[0]), 0xa5, sizeof(btSolverConstraint) * size);
	}
}

struct Plan
{
	int solverBodyIdA, solverBodyIdB, contactRow, firstFrictionRow, firstRollingRow;
	btVector3 relPos1, relPos2;
};

// Fills every point's rows in the chosen build, with the warm starts as fillContactPointRowsIn's warmStarts
// says (0 none, 1 the serial set-up's, 2 the Mt set-up's).
void fillAll(Fill& fill, const std::vector<Plan>& plans, const Bodies& bodies, const btContactSolverInfo& info,
             bool avx2, int warmStarts)
{
	const caliber::ContactRowPools pools = {&fill.bodies, &fill.contacts, &fill.friction, &fill.rolling};
	for (size_t i = 0; i < plans.size(); ++i)
	{
		caliber::ContactPointRows point;
		point.cp = &fill.points[i];
		point.object0 = fill.bodies[plans[i].solverBodyIdA].m_originalBody;
		point.object1 = fill.bodies[plans[i].solverBodyIdB].m_originalBody;
		// The fixed body's manifold partner: any object without anisotropic friction.
		if (!point.object0) point.object0 = bodies.rigid[0].get();
		if (!point.object1) point.object1 = bodies.rigid[0].get();
		point.solverBodyIdA = plans[i].solverBodyIdA;
		point.solverBodyIdB = plans[i].solverBodyIdB;
		point.contactRow = plans[i].contactRow;
		point.firstFrictionRow = plans[i].firstFrictionRow;
		point.firstRollingRow = plans[i].firstRollingRow;
		point.relPos1 = plans[i].relPos1;
		point.relPos2 = plans[i].relPos2;
		caliber::fillContactPointRowsIn(pools, point, info, avx2, warmStarts);
	}
}

bool sameBytes(const void* a, const void* b, size_t size) { return std::memcmp(a, b, size) == 0; }

// Two rows are the same when every byte is, except the point they refer to, which is the same point of each
// fill's own copy of the points.
bool sameRow(const btSolverConstraint& a, const Fill& fillA, const btSolverConstraint& b, const Fill& fillB)
{
	const btManifoldPoint* pointA = static_cast<const btManifoldPoint*>(a.m_originalContactPoint);
	const btManifoldPoint* pointB = static_cast<const btManifoldPoint*>(b.m_originalContactPoint);
	if (pointA - fillA.points.data() != pointB - fillB.points.data()) return false;
	unsigned char bytesA[sizeof(btSolverConstraint)], bytesB[sizeof(btSolverConstraint)];
	std::memcpy(bytesA, static_cast<const void*>(&a), sizeof(bytesA));
	std::memcpy(bytesB, static_cast<const void*>(&b), sizeof(bytesB));
	const size_t pointer = offsetof(btSolverConstraint, m_originalContactPoint);
	std::memset(bytesA + pointer, 0, sizeof(void*));
	std::memset(bytesB + pointer, 0, sizeof(void*));
	return sameBytes(bytesA, bytesB, sizeof(bytesA));
}

// Fills 600 points between every pair of the bodies both ways under info and compares the results.
void expectSameRowsBothWays(const btContactSolverInfo& info, uint32_t seed, int warmStarts)
{
	Random random;
	random.state = seed;
	Bodies bodies(random);
	const int numBodies = bodies.solver.size();
	const int frictionRows = caliber::frictionRowsPerContact(info);

	Fill baseline;
	baseline.bodies = bodies.solver;
	std::vector<Plan> plans;
	int numFriction = 0, numRolling = 0;
	for (int i = 0; i < 600; ++i)
	{
		Plan plan;
		plan.solverBodyIdA = int(random.next() % unsigned(numBodies));
		plan.solverBodyIdB = int(random.next() % unsigned(numBodies));
		if (plan.solverBodyIdB == plan.solverBodyIdA) plan.solverBodyIdB = (plan.solverBodyIdA + 1) % numBodies;
		// Degenerate pairs too: two bodies at the same velocities (no tangential velocity: the fixed basis).
		btManifoldPoint cp = makePoint(random, baseline.bodies[plan.solverBodyIdA], baseline.bodies[plan.solverBodyIdB], i);
		const btVector3 contactPoint = (cp.m_positionWorldOnA + cp.m_positionWorldOnB) * btScalar(0.5);
		plan.relPos1 = contactPoint - baseline.bodies[plan.solverBodyIdA].m_worldTransform.getOrigin();
		plan.relPos2 = contactPoint - baseline.bodies[plan.solverBodyIdB].m_worldTransform.getOrigin();
		if (i % 9 == 0) plan.relPos1 = plan.relPos2 = btVector3(0, 0, 0);  // at both centres
		plan.contactRow = i;
		plan.firstFrictionRow = numFriction;
		plan.firstRollingRow = numRolling;
		numFriction += frictionRows;
		numRolling += caliber::rollingRowsOf(cp);
		baseline.points.push_back(cp);
		plans.push_back(plan);
	}
	// Some pairs at rest relative to each other and some sliding exactly at the noise threshold's order.
	baseline.bodies[5].m_linearVelocity = baseline.bodies[0].m_linearVelocity;
	baseline.bodies[5].m_angularVelocity = btVector3(0, 0, 0);
	baseline.bodies[0].m_angularVelocity = btVector3(0, 0, 0);
	baseline.bodies[3].m_linearVelocity = btVector3(btScalar(3.4e-4), 0, 0);
	Fill wide;
	wide.bodies = baseline.bodies;
	wide.points = baseline.points;
	preparePools(baseline, int(plans.size()), numFriction, numRolling);
	preparePools(wide, int(plans.size()), numFriction, numRolling);
	fillAll(baseline, plans, bodies, info, false, warmStarts);
	fillAll(wide, plans, bodies, info, true, warmStarts);

	for (size_t i = 0; i < plans.size(); ++i)
	{
		SCOPED_TRACE(testing::Message() << "point " << i);
		EXPECT_TRUE(sameRow(baseline.contacts[int(i)], baseline, wide.contacts[int(i)], wide));
		const btManifoldPoint& p = baseline.points[i];
		const btManifoldPoint& q = wide.points[i];
		EXPECT_TRUE(sameBytes(&p.m_lateralFrictionDir1, &q.m_lateralFrictionDir1, sizeof(btVector3)));
		EXPECT_TRUE(sameBytes(&p.m_lateralFrictionDir2, &q.m_lateralFrictionDir2, sizeof(btVector3)));
		EXPECT_EQ(p.m_contactPointFlags, q.m_contactPointFlags);
	}
	for (int r = 0; r < numFriction; ++r)
		EXPECT_TRUE(sameRow(baseline.friction[r], baseline, wide.friction[r], wide)) << "friction row " << r;
	for (int r = 0; r < numRolling; ++r)
		EXPECT_TRUE(sameRow(baseline.rolling[r], baseline, wide.rolling[r], wide)) << "rolling row " << r;
	// The warm starts change the bodies' velocity deltas only.
	for (int b = 0; b < numBodies; ++b)
	{
		EXPECT_TRUE(sameBytes(&baseline.bodies[b].m_deltaLinearVelocity, &wide.bodies[b].m_deltaLinearVelocity,
		                      sizeof(btVector3)))
		    << "body " << b;
		EXPECT_TRUE(sameBytes(&baseline.bodies[b].m_deltaAngularVelocity, &wide.bodies[b].m_deltaAngularVelocity,
		                      sizeof(btVector3)))
		    << "body " << b;
	}
}

btContactSolverInfo infoWith(int solverMode)
{
	btContactSolverInfo info;
	info.m_timeStep = btScalar(1) / btScalar(60);
	info.m_solverMode = solverMode;
	return info;
}

bool haveAvx2Build()
{
	if (caliber::contactPointRowsUseAvx2()) return true;
	return false;
}
}  // namespace

TEST(ContactPointRowFill, Avx2BuildGivesTheBaselineBitsUnderTheDefaultSolverMode)
{
	if (!haveAvx2Build()) GTEST_SKIP() << "no AVX2 build of the set-up on this processor or build";
	const btContactSolverInfo info = infoWith(btContactSolverInfo().m_solverMode);
	expectSameRowsBothWays(info, 0x12345678u, 0);
	expectSameRowsBothWays(info, 0x0badf00du, 1);
	expectSameRowsBothWays(info, 0x600dcafeu, 2);
}

TEST(ContactPointRowFill, Avx2BuildGivesTheBaselineBitsUnderOtherSolverModes)
{
	if (!haveAvx2Build()) GTEST_SKIP() << "no AVX2 build of the set-up on this processor or build";
	const int base = btContactSolverInfo().m_solverMode;
	const int modes[] = {
	    base | SOLVER_USE_2_FRICTION_DIRECTIONS,
	    base & ~SOLVER_USE_WARMSTARTING,
	    base | SOLVER_ENABLE_FRICTION_DIRECTION_CACHING | SOLVER_DISABLE_VELOCITY_DEPENDENT_FRICTION_DIRECTION,
	    base | SOLVER_ENABLE_FRICTION_DIRECTION_CACHING | SOLVER_USE_2_FRICTION_DIRECTIONS,
	};
	uint32_t seed = 0x2468aceu;
	for (int mode : modes)
	{
		SCOPED_TRACE(testing::Message() << "solver mode " << mode);
		btContactSolverInfo info = infoWith(mode);
		expectSameRowsBothWays(info, seed++, 1);
		info.m_splitImpulse = 0;  // Baumgarte in every row's target
		info.m_globalCfm = btScalar(1e-3);
		info.m_warmstartingFactor = btScalar(0.7);
		expectSameRowsBothWays(info, seed++, 2);
	}
}

TEST(ContactPointRowFill, BaselineRowsAreTheRowsOfTheSolverSetup)
{
	// The comparison above is only meaningful if both builds fill rows at all: a normal row's Jacobian is the
	// point's normal, its lower limit 0, and a friction row's direction is orthogonal to the normal.
	Random random;
	Bodies bodies(random);
	btManifoldPoint cp = makePoint(random, bodies.solver[0], bodies.solver[6], 1);
	const btContactSolverInfo info = infoWith(btContactSolverInfo().m_solverMode);
	Plan plan = {0, 6, 0, 0, 0, btVector3(btScalar(0.1), btScalar(-0.5), 0), btVector3(1, 2, 3)};
	for (bool avx2 : {false, true})
	{
		Fill copy;
		copy.bodies = bodies.solver;
		copy.points.push_back(cp);
		preparePools(copy, 1, caliber::frictionRowsPerContact(info), caliber::rollingRowsOf(cp));
		fillAll(copy, {plan}, bodies, info, avx2, 1);
		const btSolverConstraint& row = copy.contacts[0];
		EXPECT_EQ(row.m_contactNormal1, cp.m_normalWorldOnB);
		EXPECT_EQ(row.m_lowerLimit, btScalar(0));
		EXPECT_EQ(row.m_solverBodyIdA, 0);
		EXPECT_EQ(row.m_solverBodyIdB, 6);
		EXPECT_GT(row.m_jacDiagABInv, btScalar(0));
		// Float rounding of a unit direction's dot product with the unit normal: a few ulps of 1.
		EXPECT_NEAR(copy.friction[0].m_contactNormal1.dot(cp.m_normalWorldOnB), 0, 1e-6);
	}
}

