// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BenchmarkScenes.h"

#include "../RagdollDemo/Ragdoll.h"

#include <stdio.h>

#include <cmath>
#include <cstdarg>
#include <functional>

namespace benchmark_demo
{
namespace
{
btTransform at(const btVector3& origin, const btQuaternion& rotation = btQuaternion::getIdentity())
{
	return btTransform(rotation, origin);
}

bool isFinite(const btVector3& v) { return btIsFinite(v.x()) && btIsFinite(v.y()) && btIsFinite(v.z()); }

// The barrel of scenes.md: 43 points on three octagons (17 on each rim, 9 on the waist, duplicates
// included so that support mapping costs what the original does).
btConvexHullShape* makeTaruHull()
{
	btConvexHullShape* hull = new btConvexHullShape();
	const btScalar rimY = btScalar(1.99237), rimRadius = btScalar(1.08664), waistRadius = btScalar(1.82224);
	for (int k = 0; k < 17; ++k)
	{
		const btScalar angle = SIMD_PI / 4 * btScalar(k % 8);
		hull->addPoint(btVector3(rimRadius * btCos(angle), rimY, rimRadius * btSin(angle)), false);
		hull->addPoint(btVector3(rimRadius * btCos(angle), -rimY, rimRadius * btSin(angle)), false);
	}
	for (int k = 0; k < 9; ++k)
	{
		const btScalar angle = SIMD_PI / 4 * btScalar(k % 8);
		hull->addPoint(btVector3(waistRadius * btCos(angle), 0, waistRadius * btSin(angle)), false);
	}
	hull->recalcLocalAabb();
	return hull;
}

// Counts and extremes over the dynamic bodies.
struct Census
{
	int bodies = 0, nonFinite = 0, faster01 = 0, faster1 = 0;
	btScalar minY = BT_LARGE_FLOAT, maxY = -BT_LARGE_FLOAT, maxSpeed = 0, maxSpread = 0;

	explicit Census(const std::vector<btRigidBody*>& dynamic)
	{
		for (const btRigidBody* body : dynamic)
		{
			++bodies;
			const btVector3& p = body->getCenterOfMassPosition();
			const btScalar speed = body->getLinearVelocity().length();
			if (!isFinite(p) || !btIsFinite(speed))
			{
				++nonFinite;
				continue;
			}
			minY = btMin(minY, p.y());
			maxY = btMax(maxY, p.y());
			maxSpeed = btMax(maxSpeed, speed);
			maxSpread = btMax(maxSpread, btSqrt(p.x() * p.x() + p.z() * p.z()));
			if (speed > btScalar(0.1)) ++faster01;
			if (speed > btScalar(1)) ++faster1;
		}
	}
};

std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* fmt, ...)
{
	char buffer[512];
	va_list args;
	va_start(args, fmt);
	vsnprintf(buffer, sizeof(buffer), fmt, args);
	va_end(args);
	return buffer;
}

// Bodies more than 0.1 m from where they should rest (their start, at the resting height restY).
int displacedFromRest(const std::vector<btRigidBody*>& bodies, const std::vector<btTransform>& start, size_t first,
                      size_t last, const std::function<btScalar(size_t)>& restY)
{
	int displaced = 0;
	for (size_t i = first; i < last; ++i)
	{
		btVector3 rest = start[i].getOrigin();
		rest.setY(restY(i));
		if ((bodies[i]->getCenterOfMassPosition() - rest).length() > btScalar(0.1)) ++displaced;
	}
	return displaced;
}

// ---- scene 1: 3008 boxes falling as a column -----------------------------------------------------
class Boxes3000 : public Scene
{
public:
	Boxes3000()
	{
		addBenchmarkGround();
		btBoxShape* box = own(new btBoxShape(btVector3(1, 1, 1)));
		btScalar offset = -12;  // 8 boxes at pitch 3, centred
		for (int k = 0; k < 47; ++k)
		{
			for (int j = 0; j < 8; ++j)
				for (int i = 0; i < 8; ++i)
					addBody(box, 2,
					        at(btVector3(offset + 3 * btScalar(i), 2 + 3 * btScalar(k), offset + 3 * btScalar(j))));
			offset -= btScalar(0.35);
		}
	}
	bool report(std::string& line) const override
	{
		const Census c(dynamicBodies());
		line = format(
		    "min y %.3f (resting centre 1.0), max y %.2f (start 140), spread %.1f m, faster than 0.1 m/s %d, "
		    "than 1 m/s %d, max speed %.1f, non-finite %d",
		    double(c.minY), double(c.maxY), double(c.maxSpread), c.faster01, c.faster1, double(c.maxSpeed),
		    c.nonFinite);
		return c.nonFinite == 0 && c.minY > btScalar(0.9);
	}
};

// ---- scene 2: pyramid, three walls and a circular tower of 1076 boxes ---------------------------
class Stack1000 : public Scene
{
public:
	size_t m_pyramidEnd = 0, m_wallsEnd = 0;
	Stack1000()
	{
		addBenchmarkGround();
		btBoxShape* box = own(new btBoxShape(btVector3(1, 1, 1)));
		const btScalar pitch = btScalar(2.04) + btScalar(0.0001);
		for (int level = 0; level < 12; ++level)
		{
			const int n = 12 - level;
			for (int j = 0; j < n; ++j)
				for (int i = 0; i < n; ++i)
					addBody(box, 1,
					        at(btVector3(-20 + (btScalar(i) - btScalar(n - 1) / 2) * pitch, 1 + pitch * btScalar(level),
					                     (btScalar(j) - btScalar(n - 1) / 2) * pitch)));
		}
		m_pyramidEnd = dynamicBodies().size();
		const btScalar wallX[3] = {-2, 4, 10};
		for (btScalar x : wallX)
			for (int row = 0; row < 12; ++row)
			{
				const int n = 12 - row;
				for (int i = 0; i < n; ++i)
					addBody(box, 1, at(btVector3(x, 1 + 2 * btScalar(row), (btScalar(i) - btScalar(n - 1) / 2) * 2)));
			}
		m_wallsEnd = dynamicBodies().size();
		const btScalar radius = btScalar(1.3) * 24 / SIMD_PI;
		for (int ring = 0; ring < 8; ++ring)
			for (int i = 0; i < 24; ++i)
			{
				const btScalar angle =
				    SIMD_PI + btScalar(i) * SIMD_RADS_PER_DEG * 15 + (ring % 2) * SIMD_RADS_PER_DEG * btScalar(7.5);
				addBody(box, 1,
				        at(btVector3(25 + radius * btCos(angle), 1 + 2 * btScalar(ring), radius * btSin(angle)),
				           btQuaternion(btVector3(0, 1, 0), -angle)));
			}
	}
	bool report(std::string& line) const override
	{
		const Census c(dynamicBodies());
		const btScalar pitch = btScalar(2.0401);
		auto pyramidRest = [&](size_t i)
		{
			const btScalar level = btScalar(std::floor((m_start[i].getOrigin().y() - 1) / pitch + btScalar(0.5)));
			return 1 + 2 * level;
		};
		auto startY = [&](size_t i) { return m_start[i].getOrigin().y(); };
		const int pyramid = displacedFromRest(dynamicBodies(), m_start, 0, m_pyramidEnd, pyramidRest);
		const int walls = displacedFromRest(dynamicBodies(), m_start, m_pyramidEnd, m_wallsEnd, startY);
		const int tower = displacedFromRest(dynamicBodies(), m_start, m_wallsEnd, dynamicBodies().size(), startY);
		line = format(
		    "more than 0.1 m from rest: pyramid %d/%d, walls %d/%d, tower %d/%d; pyramid top y %.3f "
		    "(ideal 23.0), tower top %.3f (15.0), max speed %.3f, non-finite %d",
		    pyramid, int(m_pyramidEnd), walls, int(m_wallsEnd - m_pyramidEnd), tower,
		    int(dynamicBodies().size() - m_wallsEnd),
		    double(dynamicBodies()[m_pyramidEnd - 1]->getCenterOfMassPosition().y()),
		    double(dynamicBodies().back()->getCenterOfMassPosition().y()), double(c.maxSpeed), c.nonFinite);
		return c.nonFinite == 0 && c.minY > btScalar(0.9);
	}
};

// ---- scene 4: 960 barrels with polyhedral features -----------------------------------------------
class Convex1000 : public Scene
{
public:
	Convex1000()
	{
		addBenchmarkGround();
		btConvexHullShape* hull = own(makeTaruHull());
		hull->initializePolyhedralFeatures();
		btScalar spacing = btScalar(1.5);
		btScalar offset = -4 * (3 + spacing);
		btScalar y = 3;
		for (int k = 0; k < 15; ++k)
		{
			for (int j = 0; j < 8; ++j)
				for (int i = 0; i < 8; ++i)
					addBody(
					    hull, 1,
					    at(btVector3(offset + (3 + spacing) * btScalar(i), y, offset + (3 + spacing) * btScalar(j))));
			offset -= btScalar(0.525);
			y += 3 + spacing;
			spacing *= btScalar(1.01);
		}
	}
	bool report(std::string& line) const override
	{
		const Census c(dynamicBodies());
		line = format("min y %.2f (a barrel on its side rests at 1.82), faster than 0.1 m/s %d of %d, non-finite %d",
		              double(c.minY), c.faster01, c.bodies, c.nonFinite);
		return c.nonFinite == 0 && c.minY > btScalar(1.0);
	}
};

// ---- scenes 5-7: primitives or barrels on the landscape, and rays -------------------------------
class OnLandscape : public Scene
{
public:
	explicit OnLandscape(bool barrels)
	{
		addLandscape();
		btConvexHullShape* hull = barrels ? own(makeTaruHull()) : 0;
		unsigned int seed = 12345;
		btScalar spacing = 2;
		for (int k = 0; k < 10; ++k)
		{
			const btScalar pitch = 3 + spacing;
			for (int j = 0; j < 10; ++j)
				for (int i = 0; i < 10; ++i)
				{
					const btVector3 grid((btScalar(i) - btScalar(4.5)) * pitch, 20 + btScalar(k) * pitch,
					                     (btScalar(j) - btScalar(4.5)) * pitch);
					const btVector3 origin = btVector3(0, 25, 0) + btVector3(5, 1, 5) * grid;
					if (barrels)
					{
						addBody(hull, 1, at(origin));
						continue;
					}
					seed = seed * 1664525u + 1013904223u;
					const int choice = int((seed >> 8) % 9);
					const btScalar r = btScalar(0.5) * btScalar(1 + choice % 3);
					btCollisionShape* shape = 0;
					if (choice / 3 == 0)
						shape = own(new btBoxShape(btVector3(r, r, r) * btScalar(1.5)));
					else if (choice / 3 == 1)
						shape = own(new btSphereShape(btScalar(1.5) * r));
					else
						shape = own(new btCapsuleShape(r, 2 * r));
					addBody(shape, r, at(origin));
				}
			spacing *= btScalar(1.1);
		}
	}
	bool report(std::string& line) const override
	{
		const Census c(dynamicBodies());
		int offEdge = 0, tunnelled = 0;
		for (const btRigidBody* body : dynamicBodies())
		{
			const btVector3& p = body->getCenterOfMassPosition();
			if (btFabs(p.x()) > 250 || btFabs(p.z()) > 250)
			{
				++offEdge;
				continue;
			}
			// Tunnelled: the centre is below the terrain's surface straight beneath it (a ray against the
			// static terrain only gives the surface of the triangles themselves).
			const btVector3 from(p.x(), 1000, p.z()), to(p.x(), -1000, p.z());
			btCollisionWorld::ClosestRayResultCallback down(from, to);
			down.m_collisionFilterMask = btBroadphaseProxy::StaticFilter;
			worldConst().rayTest(from, to, down);
			if (down.hasHit() && p.y() < down.m_hitPointWorld.y()) ++tunnelled;
		}
		line = format("tunnelled %d, off the terrain edge %d, min y %.1f, non-finite %d", tunnelled, offEdge,
		              double(c.minY), c.nonFinite);
		return c.nonFinite == 0 && tunnelled == 0;
	}
};

class Raycast : public OnLandscape
{
public:
	long m_hits = 0, m_rays = 0;
	double m_lastSum = 0, m_checksum = 0;
	Raycast() : OnLandscape(true) {}
	void afterStep() override
	{
		const btVector3 from(0, 50, 0);
		double sum = 0;
		for (int i = 0; i < 500; ++i)
		{
			const btScalar yaw = btScalar(i) * 4 * SIMD_PI / 500;
			const btVector3 to(2500 * btCos(yaw), -1000, 2500 * btSin(yaw));
			btCollisionWorld::ClosestRayResultCallback callback(from, to);
			world().rayTest(from, to, callback);
			++m_rays;
			if (callback.hasHit())
			{
				++m_hits;
				sum += double((callback.m_hitPointWorld - from).length());
			}
		}
		m_lastSum = sum;
		m_checksum += sum;
	}
	bool report(std::string& line) const override
	{
		std::string base;
		const bool ok = OnLandscape::report(base);
		line =
		    base + format("; rays hit %ld of %ld, last frame's hit distances sum to %.3f", m_hits, m_rays, m_lastSum);
		return ok && m_hits == m_rays;
	}
};

// ---- scene 8: Jolt's pyramid --------------------------------------------------------------------
class PyramidJolt : public Scene
{
public:
	PyramidJolt()
	{
		world().getSolverInfo().m_numIterations = 10;
		btBoxShape* floorShape = own(new btBoxShape(btVector3(50, 1, 50)));
		addBody(floorShape, 0, at(btVector3(0, -1, 0)));
		btBoxShape* box = own(new btBoxShape(btVector3(1, 1, 1)));
		for (int level = 0; level < 15; ++level)
		{
			const int n = 15 - level;
			for (int j = 0; j < n; ++j)
				for (int i = 0; i < n; ++i)
					addBody(box, 1,
					        at(btVector3((btScalar(i) - btScalar(n - 1) / 2) * 2, 1 + btScalar(2.5) * btScalar(level),
					                     (btScalar(j) - btScalar(n - 1) / 2) * 2)));
		}
	}
	bool report(std::string& line) const override
	{
		const Census c(dynamicBodies());
		auto rest = [&](size_t i)
		{ return 1 + 2 * btScalar(std::floor((m_start[i].getOrigin().y() - 1) / btScalar(2.5) + btScalar(0.5))); };
		const int displaced = displacedFromRest(dynamicBodies(), m_start, 0, dynamicBodies().size(), rest);
		line = format("more than 0.1 m from rest: %d/%d; top at %.3f (rest 29.0), non-finite %d", displaced, c.bodies,
		              double(dynamicBodies().back()->getCenterOfMassPosition().y()), c.nonFinite);
		return c.nonFinite == 0 && c.minY > btScalar(0.9);
	}
};
// ---- scene 3: 136 ragdolls -------------------------------------------------------------------------
class Ragdolls : public Scene, public ragdoll::Owner
{
public:
	std::vector<ragdoll::Ragdoll> m_ragdolls;
	Ragdolls()
	{
		addBenchmarkGround();
		// Rows of 16, 15, ..., 1 ragdolls at scale 3.5; each row 7 m higher and 2 m further back.
		m_ragdolls.reserve(136);
		btVector3 offset(0, 1, 0);
		for (int n = 16; n > 0; --n)
		{
			for (int i = 0; i < n; ++i)
			{
				offset.setX(-3 * btScalar(n) + 6 * btScalar(i));
				m_ragdolls.emplace_back();
				ragdoll::build(*this, offset, btScalar(3.5), m_ragdolls.back());
			}
			offset.setY(offset.y() + 7);
			offset.setZ(offset.z() - 2);
		}
	}
	btCollisionShape* keepShape(btCollisionShape* shape) override { return own(shape); }
	btRigidBody* addBody(btCollisionShape* shape, btScalar mass, const btTransform& pose) override
	{
		return Scene::addBody(shape, mass, pose);
	}
	void addJoint(btTypedConstraint* joint) override { Scene::addJoint(joint); }
	bool report(std::string& line) const override
	{
		const Census c(dynamicBodies());
		btScalar worst = 0, sum = 0;
		for (const ragdoll::Ragdoll& r : m_ragdolls)
			for (int j = 0; j < ragdoll::Ragdoll::NUM_JOINTS; ++j)
			{
				worst = btMax(worst, r.pivotError(j));
				sum += r.pivotError(j);
			}
		const int joints = int(m_ragdolls.size()) * ragdoll::Ragdoll::NUM_JOINTS;
		line = format(
		    "joints %d, pivot error max %.4f m mean %.5f m (Bullet 3.24: 0.0532 / 0.00433); min y %.3f, "
		    "max speed %.2f, non-finite %d",
		    joints, double(worst), double(sum / btScalar(joints)), double(c.minY), double(c.maxSpeed), c.nonFinite);
		return c.nonFinite == 0 && worst < btScalar(0.5);
	}
};
}  // namespace

btScalar landscapeHeight(btScalar x, btScalar z)
{
	const double xd = double(x), zd = double(z);
	return btScalar(12 + 36 * std::exp(-(xd * xd + zd * zd) / (2 * 110.0 * 110.0)) +
	                12 * std::sin(.029 * xd + .5) * std::cos(.025 * zd - .3) +
	                4 * std::sin(.071 * xd - .053 * zd + 1.1) + 1.8 * std::cos(.149 * zd + .107 * xd) +
	                0.8 * std::sin(.29 * xd + .9) * std::sin(.31 * zd));
}

Scene::Scene()
    : m_configuration(new btDefaultCollisionConfiguration()),
      m_dispatcher(new btCollisionDispatcher(m_configuration.get())),
      m_broadphase(new btDbvtBroadphase()),
      m_solver(new btSequentialImpulseConstraintSolver()),
      m_world(
          new btDiscreteDynamicsWorld(m_dispatcher.get(), m_broadphase.get(), m_solver.get(), m_configuration.get()))
{
	m_world->setGravity(btVector3(0, -10, 0));
	btContactSolverInfo& info = m_world->getSolverInfo();
	info.m_solverMode = SOLVER_SIMD | SOLVER_USE_WARMSTARTING | SOLVER_ENABLE_FRICTION_DIRECTION_CACHING;
	info.m_numIterations = 5;
}

Scene::~Scene()
{
	for (auto& joint : m_joints) m_world->removeConstraint(joint.get());
	for (btRigidBody* body : m_bodies)
	{
		m_world->removeRigidBody(body);
		delete body;
	}
}

btRigidBody* Scene::addBody(btCollisionShape* shape, btScalar mass, const btTransform& pose)
{
	btVector3 inertia(0, 0, 0);
	if (mass > 0) shape->calculateLocalInertia(mass, inertia);
	m_motionStates.emplace_back(new btDefaultMotionState(pose));
	btRigidBody::btRigidBodyConstructionInfo info(mass, m_motionStates.back().get(), shape, inertia);
	btRigidBody* body = new btRigidBody(info);
	m_world->addRigidBody(body);
	m_bodies.push_back(body);
	if (mass > 0)
	{
		m_dynamic.push_back(body);
		m_start.push_back(pose);
	}
	return body;
}

void Scene::addJoint(btTypedConstraint* joint)
{
	m_joints.emplace_back(joint);
	m_world->addConstraint(joint, true);
}

void Scene::addBenchmarkGround() { addBody(own(new btBoxShape(btVector3(250, 50, 250))), 0, at(btVector3(0, -50, 0))); }

void Scene::addLandscape()
{
	// 128 x 128 quads of 3.90625 over [-250, 250]^2, as 8 tiles of 64 x 32 quads with 16-bit indices.
	const btScalar step = btScalar(3.90625);
	for (int tile = 0; tile < 8; ++tile)
	{
		const int tileX = tile % 2, tileZ = tile / 2;  // 2 tiles of 64 quads in x, 4 of 32 in z
		std::vector<btScalar> vertices;
		std::vector<unsigned short> indices;
		for (int j = 0; j <= 32; ++j)
			for (int i = 0; i <= 64; ++i)
			{
				const btScalar x = -250 + step * btScalar(tileX * 64 + i);
				const btScalar z = -250 + step * btScalar(tileZ * 32 + j);
				vertices.push_back(x);
				vertices.push_back(landscapeHeight(x, z));
				vertices.push_back(z);
			}
		for (int j = 0; j < 32; ++j)
			for (int i = 0; i < 64; ++i)
			{
				const unsigned short v00 = (unsigned short)(j * 65 + i), v01 = (unsigned short)(v00 + 1);
				const unsigned short v10 = (unsigned short)(v00 + 65), v11 = (unsigned short)(v10 + 1);
				const unsigned short quad[6] = {v00, v10, v01, v01, v10, v11};
				indices.insert(indices.end(), quad, quad + 6);
			}
		m_vertexData.push_back(std::move(vertices));
		m_indexData.push_back(std::move(indices));
		btIndexedMesh part;
		part.m_numTriangles = int(m_indexData.back().size() / 3);
		part.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(m_indexData.back().data());
		part.m_triangleIndexStride = 3 * int(sizeof(unsigned short));
		part.m_numVertices = int(m_vertexData.back().size() / 3);
		part.m_vertexBase = reinterpret_cast<const unsigned char*>(m_vertexData.back().data());
		part.m_vertexStride = 3 * int(sizeof(btScalar));
		part.m_indexType = PHY_SHORT;
		part.m_vertexType = sizeof(btScalar) == sizeof(double) ? PHY_DOUBLE : PHY_FLOAT;
		btTriangleIndexVertexArray* mesh = new btTriangleIndexVertexArray();
		mesh->addIndexedMesh(part, PHY_SHORT);
		m_meshes.emplace_back(mesh);
		btBvhTriangleMeshShape* shape = own(new btBvhTriangleMeshShape(mesh, true));
		btRigidBody* terrain = addBody(shape, 0, at(btVector3(0, -25, 0)));
		terrain->setFriction(btScalar(0.9));
	}
}

std::vector<std::string> sceneNames()
{
	return {"boxes3000", "stack1000",   "ragdolls136", "convex1000",
	        "prim_mesh", "convex_mesh", "raycast",     "pyramid_jolt"};
}

std::unique_ptr<Scene> makeScene(const std::string& name)
{
	if (name == "boxes3000") return std::unique_ptr<Scene>(new Boxes3000());
	if (name == "stack1000") return std::unique_ptr<Scene>(new Stack1000());
	if (name == "ragdolls136") return std::unique_ptr<Scene>(new Ragdolls());
	if (name == "convex1000") return std::unique_ptr<Scene>(new Convex1000());
	if (name == "prim_mesh") return std::unique_ptr<Scene>(new OnLandscape(false));
	if (name == "convex_mesh") return std::unique_ptr<Scene>(new OnLandscape(true));
	if (name == "raycast") return std::unique_ptr<Scene>(new Raycast());
	if (name == "pyramid_jolt") return std::unique_ptr<Scene>(new PyramidJolt());
	return std::unique_ptr<Scene>();
}
}  // namespace benchmark_demo
