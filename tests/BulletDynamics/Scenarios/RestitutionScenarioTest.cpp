// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Restitution through the whole world: rebound heights against e^2 h whatever the phase of the impact
// within a step, elastic collisions that keep their energy, and momentum exact through a bounce.

#include <gtest/gtest.h>

#include <vector>

#include "../Dynamics/DynamicsWorldTestUtil.h"

using caliber_test::TestWorld;

namespace
{
const btScalar kGravity = btScalar(9.81);

enum class DropShape
{
	Sphere,
	Box
};

struct Rebound
{
	btScalar apex;         // highest point of the body's bottom after its first bounce
	btScalar restingJump;  // for e = 0: highest point of the bottom after it first stopped falling
};

// Drops a body (bottom at dropHeight above a static box ground, combined restitution e, friction 0.5)
// and measures its first rebound, stepping at h.
Rebound dropAndMeasure(DropShape kind, btScalar e, btScalar dropHeight, btScalar h)
{
	TestWorld w(btVector3(0, -kGravity, 0));
	w.addGround(btScalar(1), btScalar(1));  // combined restitution e * 1, combined friction 0.5 * 1
	const btScalar halfHeight = btScalar(0.5);
	btCollisionShape* shape = kind == DropShape::Sphere
	                              ? static_cast<btCollisionShape*>(w.shape<btSphereShape>(halfHeight))
	                              : static_cast<btCollisionShape*>(w.shape<btBoxShape>(btVector3(0.5, 0.5, 0.5)));
	btRigidBody* body = w.addBody(shape, 1, btVector3(0, dropHeight + halfHeight, 0));
	body->setRestitution(e);
	body->setFriction(btScalar(0.5));
	body->setActivationState(DISABLE_DEACTIVATION);

	Rebound result = {0, 0};
	bool stoppedFalling = false;
	btScalar previousVy = 0;
	const int maxSteps = int(btScalar(4) / h);
	int stepsAfterStop = 0;
	for (int i = 0; i < maxSteps; ++i)
	{
		w.run(1, h);
		const btScalar vy = body->getLinearVelocity().y();
		const btScalar bottom = body->getCenterOfMassPosition().y() - halfHeight;
		if (!stoppedFalling && vy >= btScalar(0) && previousVy < btScalar(0)) stoppedFalling = true;
		if (stoppedFalling)
		{
			result.restingJump = btMax(result.restingJump, bottom);
			result.apex = btMax(result.apex, bottom);
			// The first apex: the body rose and now falls again.
			if (e > btScalar(0) && previousVy > btScalar(0) && vy <= btScalar(0)) break;
			if (e == btScalar(0) && ++stepsAfterStop > int(btScalar(0.5) / h)) break;
		}
		previousVy = vy;
	}
	return result;
}

void expectReboundsMatchRestitutionSquared(DropShape kind, const char* name)
{
	// The impact falls at 20 phases within a step: the drop height grows by a twentieth of one step's
	// travel at the impact speed each time. Semi-implicit Euler samples a parabola whose apex is
	// g h^2 / 8 (0.3 mm at 60 Hz) above the released height, so the sampled rebound apex can differ from
	// e^2 h by that much besides the contact's own error; 3 % of e^2 h is far larger.
	const btScalar baseHeight = btScalar(2);
	const btScalar impactSpeed = btSqrt(2 * kGravity * baseHeight);
	const btScalar restitutions[] = {btScalar(0.2), btScalar(0.5), btScalar(0.8), btScalar(1)};
	const btScalar steps[] = {btScalar(1. / 60.), btScalar(1. / 120.)};
	for (btScalar h : steps)
	{
		for (btScalar e : restitutions)
		{
			for (int phase = 0; phase < 20; ++phase)
			{
				const btScalar height = baseHeight + impactSpeed * h * btScalar(phase) / btScalar(20);
				const Rebound r = dropAndMeasure(kind, e, height, h);
				const btScalar ideal = e * e * height;
				EXPECT_NEAR(r.apex, ideal, btScalar(0.03) * ideal)
				    << name << " e " << e << " h " << h << " phase " << phase << "/20 dropped from " << height;
			}
		}
		for (int phase = 0; phase < 20; ++phase)
		{
			// e = 0: no rebound at all, at the same 20 impact phases. The body may settle by at most one step's fall under gravity (g h^2)
			// and never rises above the surface by more than that.
			const btScalar height = baseHeight + impactSpeed * h * btScalar(phase) / btScalar(20);
			const Rebound r = dropAndMeasure(kind, 0, height, h);
			EXPECT_LT(r.restingJump, kGravity * h * h) << name << " e 0 h " << h << " phase " << phase;
		}
	}
}

btScalar kineticEnergy(const std::vector<btRigidBody*>& bodies)
{
	btScalar energy = 0;
	for (btRigidBody* body : bodies)
	{
		if (body->getInvMass() == btScalar(0)) continue;
		const btVector3 v = body->getLinearVelocity();
		const btVector3 w = body->getAngularVelocity();
		const btMatrix3x3& r = body->getWorldTransform().getBasis();
		const btVector3 localW = w * r;
		const btVector3 inertia = body->getLocalInertia();
		energy += btScalar(0.5) * body->getMass() * v.length2() +
		          btScalar(0.5) * (inertia.x() * localW.x() * localW.x() + inertia.y() * localW.y() * localW.y() +
		                           inertia.z() * localW.z() * localW.z());
	}
	return energy;
}

// A fixed-seed generator for reproducible scenes, the same on every platform.
struct SceneRandom
{
	unsigned state = 12345u;
	btScalar uniform(btScalar lo, btScalar hi)
	{
		state = state * 1664525u + 1013904223u;
		return lo + (hi - lo) * btScalar((state >> 8) & 0xffffu) / btScalar(0xffff);
	}
};
}  // namespace

TEST(RestitutionScenario, SphereReboundsReachRestitutionSquaredTimesTheDropAtEveryImpactPhase)
{
	expectReboundsMatchRestitutionSquared(DropShape::Sphere, "sphere");
}

TEST(RestitutionScenario, BoxLandingFlatReboundsReachRestitutionSquaredTimesTheDropAtEveryImpactPhase)
{
	expectReboundsMatchRestitutionSquared(DropShape::Box, "box");
}

TEST(RestitutionScenario, ElasticSpheresInAClosedBoxKeepTheirKineticEnergy)
{
	// 50 elastic spheres in zero gravity inside a closed box of six static walls, all with restitution 1,
	// no friction, no damping: every collision is elastic, so the kinetic energy never changes. 5 % is
	// the allowance for the solver: Gauss-Seidel sweeps over simultaneous contacts of a cluster are not
	// an exact elastic multi-body impact.
	TestWorld w(btVector3(0, 0, 0));
	const btScalar halfRoom = 5;
	const btScalar wall = btScalar(0.5);
	btCollisionShape* slab = w.shape<btBoxShape>(btVector3(halfRoom + 2 * wall, wall, halfRoom + 2 * wall));
	const btVector3 wallCentres[] = {btVector3(0, -halfRoom - wall, 0), btVector3(0, halfRoom + wall, 0)};
	for (const btVector3& c : wallCentres) w.addBody(slab, 0, c)->setRestitution(1);
	btTransform sideX(btQuaternion(btVector3(0, 0, 1), SIMD_HALF_PI));
	btTransform sideZ(btQuaternion(btVector3(1, 0, 0), SIMD_HALF_PI));
	for (int s = -1; s <= 1; s += 2)
	{
		sideX.setOrigin(btVector3(btScalar(s) * (halfRoom + wall), 0, 0));
		sideZ.setOrigin(btVector3(0, 0, btScalar(s) * (halfRoom + wall)));
		w.addBody(slab, 0, sideX)->setRestitution(1);
		w.addBody(slab, 0, sideZ)->setRestitution(1);
	}
	for (btRigidBody* body : w.bodies()) body->setFriction(0);

	SceneRandom random;
	btCollisionShape* ball = w.shape<btSphereShape>(btScalar(0.5));
	for (int i = 0; i < 5; ++i)
		for (int j = 0; j < 5; ++j)
			for (int k = 0; k < 2; ++k)
			{
				const btVector3 at(btScalar(i - 2) * btScalar(1.7), btScalar(k) * btScalar(3) - btScalar(1.5),
				                   btScalar(j - 2) * btScalar(1.7));
				btRigidBody* b = w.addBody(ball, 1, at);
				b->setRestitution(1);
				b->setFriction(0);
				b->setDamping(0, 0);
				b->setActivationState(DISABLE_DEACTIVATION);
				b->setLinearVelocity(btVector3(random.uniform(-4, 4), random.uniform(-4, 4), random.uniform(-4, 4)));
			}
	const btScalar e0 = kineticEnergy(w.bodies());
	btScalar lowest = e0, highest = e0;
	for (int step = 0; step < 3000; ++step)
	{
		w.run(1);
		const btScalar e = kineticEnergy(w.bodies());
		lowest = btMin(lowest, e);
		highest = btMax(highest, e);
		if (btFabs(e - e0) > btScalar(0.05) * e0)
		{
			ADD_FAILURE() << "step " << step << ": kinetic energy " << e << ", started at " << e0;
			break;
		}
	}
	RecordProperty("lowestEnergyRatio", std::to_string(lowest / e0));
	RecordProperty("highestEnergyRatio", std::to_string(highest / e0));
}

TEST(RestitutionScenario, IsolatedElasticPairKeepsEnergyAndMomentumExactly)
{
	// Two spheres of different mass meet off centre in zero gravity, with restitution 1 and no friction:
	// the impulse acts along the line of centres at one point, so linear momentum, angular momentum and
	// kinetic energy all come out as they went in. Tried at several impact phases within the step.
	for (int phase = 0; phase < 8; ++phase)
	{
		TestWorld w(btVector3(0, 0, 0));
		btRigidBody* a = w.addBody(w.shape<btSphereShape>(btScalar(0.5)), 1, btVector3(-2, 0, 0));
		btRigidBody* b = w.addBody(w.shape<btSphereShape>(btScalar(0.3)), 3,
		                           btVector3(btScalar(1) + btScalar(phase) * btScalar(0.011), btScalar(0.4), 0));
		for (btRigidBody* body : w.bodies())
		{
			body->setRestitution(1);
			body->setFriction(0);
			body->setDamping(0, 0);
			body->setActivationState(DISABLE_DEACTIVATION);
		}
		a->setLinearVelocity(btVector3(4, 0, btScalar(0.5)));
		b->setLinearVelocity(btVector3(-2, 0, 0));
		auto momentum = [&]() { return a->getLinearVelocity() * a->getMass() + b->getLinearVelocity() * b->getMass(); };
		auto angularMomentum = [&]()
		{
			btVector3 l(0, 0, 0);
			for (btRigidBody* body : {a, b})
				l += body->getCenterOfMassPosition().cross(body->getLinearVelocity() * body->getMass()) +
				     body->getAngularVelocity() * body->getLocalInertia().x();  // spheres: isotropic inertia
			return l;
		};
		const btVector3 p0 = momentum();
		const btVector3 l0 = angularMomentum();
		const btScalar e0 = kineticEnergy(w.bodies());
		w.run(60);
		// They met: the light sphere no longer moves at its starting velocity.
		ASSERT_GT((a->getLinearVelocity() - btVector3(4, 0, btScalar(0.5))).length(), btScalar(1)) << "phase " << phase;
		const btVector3 p1 = momentum();
		const btVector3 l1 = angularMomentum();
		// Float rounding of a few dozen operations on values of order 10 (relative 1e-6), and 1e-12 in double.
		const btScalar tolerance = sizeof(btScalar) == 4 ? btScalar(2e-5) : btScalar(1e-9);
		for (int axis = 0; axis < 3; ++axis)
		{
			EXPECT_NEAR(p1[axis], p0[axis], tolerance) << "phase " << phase << " axis " << axis;
			EXPECT_NEAR(l1[axis], l0[axis], tolerance * 4) << "phase " << phase << " axis " << axis;
		}
		EXPECT_NEAR(kineticEnergy(w.bodies()), e0, tolerance * e0) << "phase " << phase;
	}
}
