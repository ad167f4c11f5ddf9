// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_TESTS_SOFT_BODY_TEST_UTIL_H
#define CALIBER_TESTS_SOFT_BODY_TEST_UTIL_H

// A soft-rigid world for tests: it owns its parts, shapes, rigid bodies and soft bodies and deletes
// them in the right order.

#include <cstdint>
#include <cstring>
#include <memory>
#include <utility>
#include <vector>

#include "btBulletSoftBodyCommon.h"

namespace caliber_test
{
/// Two nodes at a and b (masses m0, m1; 0 pins a node) joined by one link, in zero gravity; the caller owns it.
inline std::unique_ptr<btSoftBody> twoNodeLink(btSoftBodyWorldInfo& info, const btVector3& a, const btVector3& b,
                                               btScalar m0, btScalar m1)
{
	info.m_gravity.setValue(0, 0, 0);
	const btVector3 x[2] = {a, b};
	const btScalar m[2] = {m0, m1};
	std::unique_ptr<btSoftBody> body(new btSoftBody(&info, 2, x, m));
	body->appendLink(0, 1);
	return body;
}

class SoftTestWorld
{
public:
	explicit SoftTestWorld(const btVector3& gravity = btVector3(0, -10, 0))
	    : m_dispatcher(&m_configuration), m_world(&m_dispatcher, &m_broadphase, &m_solver, &m_configuration)
	{
		m_world.setGravity(gravity);
		m_world.getWorldInfo().m_gravity = gravity;
	}
	~SoftTestWorld()
	{
		for (btSoftBody* s : m_softs)
		{
			if (m_world.getSoftBodyArray().findLinearSearch(s) != m_world.getSoftBodyArray().size())
				m_world.removeSoftBody(s);
			delete s;
		}
		for (auto& b : m_bodies)
			if (b->getBroadphaseHandle()) m_world.removeRigidBody(b.get());
	}

	btSoftRigidDynamicsWorld& world() { return m_world; }
	btSoftBodyWorldInfo& info() { return m_world.getWorldInfo(); }

	/// A shape kept alive for the world's lifetime.
	template <class Shape, class... Args>
	Shape* shape(Args&&... args)
	{
		Shape* s = new Shape(std::forward<Args>(args)...);
		m_shapes.emplace_back(s);
		return s;
	}

	/// A rigid body of mass (0: static) at pos, added to the world.
	btRigidBody* addRigid(btScalar mass, const btVector3& pos, btCollisionShape* collisionShape)
	{
		btVector3 inertia(0, 0, 0);
		if (mass > 0) collisionShape->calculateLocalInertia(mass, inertia);
		btTransform t;
		t.setIdentity();
		t.setOrigin(pos);
		btRigidBody::btRigidBodyConstructionInfo ci(mass, 0, collisionShape, inertia);
		ci.m_startWorldTransform = t;
		m_bodies.emplace_back(new btRigidBody(ci));
		m_world.addRigidBody(m_bodies.back().get());
		return m_bodies.back().get();
	}

	/// A static ground box whose top face is at y = 0.
	btRigidBody* addGround() { return addRigid(0, btVector3(0, -5, 0), shape<btBoxShape>(btVector3(50, 5, 50))); }

	/// Takes ownership of s and adds it to the world (unless add is false).
	btSoftBody* addSoft(btSoftBody* s, bool add = true)
	{
		m_softs.push_back(s);
		if (add) m_world.addSoftBody(s);
		return s;
	}

	void step(int frames, btScalar dt = btScalar(1) / 60)
	{
		for (int i = 0; i < frames; ++i) m_world.stepSimulation(dt, 1, dt);
	}

private:
	btSoftBodyRigidBodyCollisionConfiguration m_configuration;
	btCollisionDispatcher m_dispatcher;
	btDbvtBroadphase m_broadphase;
	btSequentialImpulseConstraintSolver m_solver;
	btSoftRigidDynamicsWorld m_world;
	std::vector<std::unique_ptr<btCollisionShape>> m_shapes;
	std::vector<std::unique_ptr<btRigidBody>> m_bodies;
	std::vector<btSoftBody*> m_softs;
};

/// A rigid box of soft nodes, added to w: its 8 corners (mass / 8 each), every pair linked inextensibly,
/// 10 sweeps, one cluster, no friction, colliding as collisions says (clusters only, e.g. CL_RS or CL_SS).
inline btSoftBody* rigidSoftBox(SoftTestWorld& w, const btVector3& centre, const btVector3& half, btScalar mass,
                                int collisions)
{
	btVector3 corners[8];
	for (int i = 0; i < 8; ++i)
		corners[i] = centre + btVector3(i & 1 ? half.x() : -half.x(), i & 2 ? half.y() : -half.y(),
		                                i & 4 ? half.z() : -half.z());
	btSoftBody* b = btSoftBodyHelpers::CreateFromConvexHull(w.info(), corners, 8, false);
	for (int i = 0; i < b->m_nodes.size(); ++i)
		for (int j = i + 1; j < b->m_nodes.size(); ++j) b->appendLink(i, j, 0, true);
	b->m_materials[0]->m_kLST = 1;
	b->setTotalMass(mass);
	b->m_cfg.piterations = 10;
	b->m_cfg.kDF = 0;
	b->m_cfg.collisions = collisions;
	b->generateClusters(1);
	return w.addSoft(b);
}

/// Lowest node height of a body.
inline btScalar lowestNodeY(const btSoftBody& s)
{
	btScalar y = BT_LARGE_FLOAT;
	for (int i = 0; i < s.m_nodes.size(); ++i) y = btMin(y, s.m_nodes[i].m_x.y());
	return y;
}

/// Total linear momentum of the free nodes.
inline btVector3 nodeMomentum(const btSoftBody& s)
{
	btVector3 p(0, 0, 0);
	for (int i = 0; i < s.m_nodes.size(); ++i)
		if (s.m_nodes[i].m_im > 0) p += s.m_nodes[i].m_v / s.m_nodes[i].m_im;
	return p;
}

/// FNV-1a hash of the node positions (bit-identical runs hash alike).
inline uint64_t hashNodes(const btSoftBody& s)
{
	uint64_t h = 1469598103934665603ull;
	for (int i = 0; i < s.m_nodes.size(); ++i)
		for (int a = 0; a < 3; ++a)
		{
			btScalar v = s.m_nodes[i].m_x[a];
			unsigned char bytes[sizeof(btScalar)];
			std::memcpy(bytes, &v, sizeof v);
			for (unsigned char b : bytes) h = (h ^ b) * 1099511628211ull;
		}
	return h;
}
}  // namespace caliber_test

#endif  // CALIBER_TESTS_SOFT_BODY_TEST_UTIL_H
