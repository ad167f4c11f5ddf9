// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Angular momentum of a crowd of colliding bodies in zero gravity: contacts push both bodies at one
// point with equal and opposite impulses, so they exchange angular momentum and never create it.

#include <gtest/gtest.h>

#include "../Dynamics/DynamicsWorldTestUtil.h"

using caliber_test::TestWorld;

namespace
{
struct SceneRandom
{
	unsigned state = 2024u;
	btScalar uniform(btScalar lo, btScalar hi)
	{
		state = state * 1664525u + 1013904223u;
		return lo + (hi - lo) * btScalar((state >> 8) & 0xffffu) / btScalar(0xffff);
	}
};

// Total angular momentum about the origin, and its scale: the sum of the magnitudes of its parts.
btVector3 angularMomentum(const std::vector<btRigidBody*>& bodies, btScalar* scale)
{
	btVector3 total(0, 0, 0);
	*scale = 0;
	for (btRigidBody* body : bodies)
	{
		const btMatrix3x3& r = body->getWorldTransform().getBasis();
		const btMatrix3x3 inertiaWorld = r.scaled(body->getLocalInertia()) * r.transpose();
		const btVector3 spin = inertiaWorld * body->getAngularVelocity();
		const btVector3 orbit = body->getCenterOfMassPosition().cross(body->getLinearVelocity() * body->getMass());
		total += spin + orbit;
		*scale += spin.length() + orbit.length();
	}
	return total;
}
}  // namespace

TEST(AngularMomentumScenario, ThirtyMixedBodiesCollidingKeepTheirAngularMomentum)
{
	// 10 spheres, 10 boxes and 10 capsules thrown together, inelastic (e = 0) with friction 0.5, in zero
	// gravity: 1200 steps of collisions, piles and free tumbling. The goal is float rounding of the sums
	// (relative 1e-7 per operation, thousands of contacts): 1e-5 of the scale.
	TestWorld w(btVector3(0, 0, 0));
	SceneRandom random;
	btCollisionShape* shapes[3] = {w.shape<btSphereShape>(btScalar(0.4)),
	                               w.shape<btBoxShape>(btVector3(btScalar(0.5), btScalar(0.3), btScalar(0.2))),
	                               w.shape<btCapsuleShape>(btScalar(0.25), btScalar(0.8))};
	for (int i = 0; i < 30; ++i)
	{
		const btVector3 at(random.uniform(-4, 4), random.uniform(-4, 4), random.uniform(-4, 4));
		const btQuaternion turn(btVector3(random.uniform(-1, 1), random.uniform(-1, 1), 1).normalized(),
		                        random.uniform(0, 3));
		btRigidBody* body = w.addBody(shapes[i % 3], random.uniform(1, 3), btTransform(turn, at));
		body->setRestitution(0);
		body->setFriction(btScalar(0.5));
		body->setDamping(0, 0);
		body->setActivationState(DISABLE_DEACTIVATION);
		body->setLinearVelocity(-at * btScalar(0.6) +
		                        btVector3(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)));
		body->setAngularVelocity(btVector3(random.uniform(-2, 2), random.uniform(-2, 2), random.uniform(-2, 2)));
	}
	btScalar scale = 0;
	const btVector3 start = angularMomentum(w.bodies(), &scale);
	btScalar worst = 0;
	for (int step = 0; step < 1200; ++step)
	{
		w.run(1);
		btScalar scaleNow = 0;
		const btVector3 now = angularMomentum(w.bodies(), &scaleNow);
		worst = btMax(worst, (now - start).length() / scale);
	}
	EXPECT_LT(worst, btScalar(1e-5));
}

TEST(AngularMomentumScenario, FreeBoxSpinningNearItsIntermediateAxisFlipsAndKeepsMomentumAndEnergy)
{
	// The tennis-racket (Dzhanibekov) effect: spin about the intermediate principal axis is unstable, and
	// a free box started close to it flips over and back, again and again, while its angular momentum
	// and kinetic energy stay exactly what they were. 10 minutes at 60 Hz.
	TestWorld w(btVector3(0, 0, 0));
	const btVector3 halfExtents(1, btScalar(0.5), btScalar(0.2));
	btRigidBody* box = w.addBody(w.shape<btBoxShape>(halfExtents), 1, btVector3(0, 0, 0));
	box->setDamping(0, 0);
	box->setActivationState(DISABLE_DEACTIVATION);
	box->setAngularVelocity(btVector3(btScalar(0.05), 5, btScalar(0.05)));
	const btVector3 inertia = box->getLocalInertia();
	auto energy = [&]()
	{
		const btVector3 local = box->getAngularVelocity() * box->getWorldTransform().getBasis();
		return btScalar(0.5) * (local * local).dot(inertia);
	};
	auto momentum = [&]()
	{
		const btMatrix3x3& r = box->getWorldTransform().getBasis();
		return r * ((box->getAngularVelocity() * r) * inertia);
	};
	const btScalar e0 = energy();
	const btVector3 l0 = momentum();
	btScalar worstEnergy = 0;
	int flips = 0;
	btScalar previous = 1;
	for (int step = 0; step < 36000; ++step)
	{
		w.run(1);
		worstEnergy = btMax(worstEnergy, btFabs(energy() - e0) / e0);
		// The intermediate axis (the box's y) against the momentum: its sign changes at every flip.
		const btScalar along = box->getWorldTransform().getBasis().getColumn(1).dot(l0);
		if ((along > 0) != (previous > 0)) ++flips;
		previous = along;
	}
	// The flip period here is a few seconds: dozens in ten minutes (Bullet's integrator damps it out).
	EXPECT_GT(flips, 50);
	// The split into principal rotations is second order: its energy error stays bounded at about
	// (w h)^2 (7e-3 here) instead of growing; L is kept to float rounding, which accumulates a few parts
	// in 10^8 per step (1e-3 over 36000 steps; 1e-12 in double).
	EXPECT_LT(worstEnergy, btScalar(0.01));
	EXPECT_LT((momentum() - l0).length() / l0.length(), sizeof(btScalar) == 4 ? btScalar(3e-3) : btScalar(1e-8));
}
