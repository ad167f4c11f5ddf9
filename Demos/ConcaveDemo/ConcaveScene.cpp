// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "ConcaveScene.h"

#include "BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h"

namespace concave_demo
{
namespace
{
const int kQuads = 40;  // per side; grid spacing 1, centred on the origin
const btScalar kHalf = btScalar(kQuads) / 2;
}  // namespace

btScalar terrainHeight(btScalar x, btScalar z)
{
	return btScalar(0.6) * btSin(btScalar(0.35) * x) * btCos(btScalar(0.3) * z);
}

Scene::Scene()
{
	m_world.setGravity(btVector3(0, -10, 0));
	// The samples, shared by both terrains: (kQuads + 1)^2 heights, x fastest.
	const int samples = kQuads + 1;
	for (int j = 0; j < samples; ++j)
		for (int i = 0; i < samples; ++i)
		{
			const btScalar x = btScalar(i) - kHalf, z = btScalar(j) - kHalf;
			m_heights.push_back(float(terrainHeight(x, z)));
			m_vertices.push_back(x);
			m_vertices.push_back(terrainHeight(x, z));
			m_vertices.push_back(z);
		}
	for (int j = 0; j < kQuads; ++j)
		for (int i = 0; i < kQuads; ++i)
		{
			const int a = j * samples + i, b = a + 1, c = a + samples, d = c + 1;
			const int quad[6] = {a, c, b, b, c, d};
			for (int k = 0; k < 6; ++k) m_indices.push_back(quad[k]);
		}
}

void Scene::build(Terrain terrain)
{
	clear();
	const int samples = kQuads + 1;
	if (terrain == kTriangleMesh)
	{
		m_mesh.reset(new btTriangleIndexVertexArray(m_indices.size() / 3, &m_indices[0], 3 * int(sizeof(int)),
		                                            m_vertices.size() / 3, &m_vertices[0],
		                                            3 * int(sizeof(btScalar))));
		m_shapes.emplace_back(new btBvhTriangleMeshShape(m_mesh.get(), true));
		m_terrain.reset(new btRigidBody(btRigidBody::btRigidBodyConstructionInfo(0, 0, m_shapes.back().get())));
	}
	else
	{
		// A height field is centred on its AABB: lift the body by the middle of the height range so that
		// sample heights are world heights.
		const btScalar minHeight = -btScalar(0.6), maxHeight = btScalar(0.6);
		m_shapes.emplace_back(
		    new btHeightfieldTerrainShape(samples, samples, &m_heights[0], minHeight, maxHeight, 1, false));
		btRigidBody::btRigidBodyConstructionInfo info(0, 0, m_shapes.back().get());
		info.m_startWorldTransform.setOrigin(btVector3(0, (minHeight + maxHeight) / 2, 0));
		m_terrain.reset(new btRigidBody(info));
	}
	m_world.addRigidBody(m_terrain.get());

	btCollisionShape* sphere = new btSphereShape(btScalar(0.4));
	btCollisionShape* box = new btBoxShape(btVector3(btScalar(0.35), btScalar(0.35), btScalar(0.35)));
	btCollisionShape* capsule = new btCapsuleShape(btScalar(0.3), btScalar(0.6));
	m_shapes.emplace_back(sphere);
	m_shapes.emplace_back(box);
	m_shapes.emplace_back(capsule);
	btCollisionShape* shapes[3] = {sphere, box, capsule};
	for (int i = 0; i < 48; ++i)
	{
		btCollisionShape* shape = shapes[i % 3];
		btVector3 inertia;
		shape->calculateLocalInertia(1, inertia);
		const btScalar x = btScalar(1.6) * btScalar(i % 7 - 3);
		const btScalar z = btScalar(1.6) * btScalar((i / 7) % 7 - 3);
		const btVector3 origin(x, 2 + btScalar(0.9) * btScalar(i / 49 + (i % 5)), z);
		m_motions.emplace_back(new btDefaultMotionState(
		    btTransform(btQuaternion(btVector3(1, 1, 0).normalized(), btScalar(0.3) * i), origin)));
		btRigidBody* body =
		    new btRigidBody(btRigidBody::btRigidBodyConstructionInfo(1, m_motions.back().get(), shape, inertia));
		body->setFriction(btScalar(0.8));
		body->setRollingFriction(btScalar(0.02));
		m_world.addRigidBody(body);
		m_bodies.push_back(body);
	}
}

Scene::~Scene() { clear(); }

void Scene::clear()
{
	for (btRigidBody* body : m_bodies)
	{
		m_world.removeRigidBody(body);
		delete body;
	}
	m_bodies.clear();
	m_motions.clear();
	if (m_terrain) m_world.removeRigidBody(m_terrain.get());
	m_terrain.reset();
	m_shapes.clear();
	m_mesh.reset();
}
}  // namespace concave_demo
