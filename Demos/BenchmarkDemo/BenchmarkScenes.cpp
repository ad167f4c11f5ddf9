// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BenchmarkScenes.h"

#include "BulletCollision/CollisionDispatch/btCollisionDispatcherMt.h"
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolverMt.h"

#include "../RagdollDemo/Ragdoll.h"

#include <stdio.h>

#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstring>
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

// Bullet's "Taru" barrel, regenerated (Bullet ships it as data): 43 points on three octagons, bottom rim,
// waist, top rim (17, 9 and 17 points: each rim's octagon twice, the waist's once, and one more point at
// -90 degrees on each), duplicates included so that support mapping costs what the original does.
// Angles in double, as the reference program computes them.
btConvexHullShape* makeTaruHull()
{
	btConvexHullShape* hull = new btConvexHullShape();
	const double ringY[3] = {-1.99237, 0.0, 1.99237};
	const double ringRadius[3] = {1.08664, 1.82224, 1.08664};
	const int octagons[3] = {2, 1, 2};
	const double pi = 3.14159265358979323846;
	for (int ring = 0; ring < 3; ++ring)
	{
		for (int copy = 0; copy < octagons[ring]; ++copy)
			for (int k = 0; k < 8; ++k)
			{
				const double angle = k * (pi / 4.0);
				hull->addPoint(btVector3(btScalar(ringRadius[ring] * std::cos(angle)), btScalar(ringY[ring]),
				                         btScalar(ringRadius[ring] * std::sin(angle))),
				               false);
			}
		hull->addPoint(btVector3(0, btScalar(ringY[ring]), btScalar(-ringRadius[ring])), false);
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

// The verdict on a stack's displaced count. Boxes start with gaps between them, so until the gaps have
// closed and the impacts died down (settledFrames) the count measures the settling, not the stack: it
// is then printed and marked as not judged. From settledFrames on, every box must be at rest (as in
// the reference results, Bullet's and ours).
std::string displacedVerdict(int displaced, int frames, int settledFrames, bool& ok)
{
	if (frames < settledFrames)
		return format("not judged: still settling at %d frames, judged from %d", frames, settledFrames);
	ok = ok && displaced == 0;
	return "judged: must be 0";
}

// ---- scene 1: 3008 boxes falling as a column -----------------------------------------------------
class Boxes3000 : public Scene
{
public:
	Boxes3000()
	{
		addBenchmarkGround();
		btBoxShape* box = own(new btBoxShape(btVector3(1, 1, 1)));
		// 8 x 8 boxes a layer at pitch 3 (1 m gaps), 47 layers 3 m apart; each layer's corner moves by
		// -0.35 in x and z.
		btScalar corner = -12, y = 2;
		for (int k = 0; k < 47; ++k)
		{
			for (int j = 0; j < 8; ++j)
				for (int i = 0; i < 8; ++i)
					addBody(box, 2, at(btVector3(corner + btScalar(i) * 3, y, corner + btScalar(j) * 3)));
			corner -= btScalar(0.05) * 7;
			y += 3;
		}
	}
	bool report(std::string& line, int /*frames*/) const override
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
	// The top of the pyramid falls 11 gaps of 0.04 m (0.44 m, 0.3 s): settled by half a second, the
	// length of CI's quick run.
	static const int kSettledFrames = 30;
	size_t m_pyramidEnd = 0, m_wallsEnd = 0;
	Stack1000()
	{
		addBenchmarkGround();
		btBoxShape* box = own(new btBoxShape(btVector3(1, 1, 1)));
		// The pyramid: levels of 12 x 12 down to 1 x 1 boxes at pitch 2.04 + 0.0001 (gaps of about 0.04 m),
		// each level's corner 1.02 further in; the base's corner at (-20 - 6 pitch, 1, -6 pitch).
		const btScalar halfPitch = btScalar(1.02), pitch = 2 * halfPitch + btScalar(0.0001);
		btScalar corner = -12 * pitch * btScalar(0.5), y = 1;
		for (int n = 12; n > 0; --n)
		{
			for (int j = 0; j < n; ++j)
				for (int i = 0; i < n; ++i)
					addBody(box, 1,
					        at(btVector3(-20, 0, 0) +
					           btVector3(corner + btScalar(i) * pitch, y, corner + btScalar(j) * pitch)));
			corner += halfPitch;
			y += pitch;
		}
		m_pyramidEnd = dynamicBodies().size();
		// Three triangular walls along z, 12 boxes at the base, touching.
		const btScalar wallX[3] = {-2, 4, 10};
		for (btScalar x : wallX)
		{
			btScalar z = -12, wallY = 1;
			for (int n = 12; n > 0; --n)
			{
				for (int i = 0; i < n; ++i) addBody(box, 1, at(btVector3(x, wallY, z + btScalar(i) * 2)));
				z += 1;
				wallY += 2;
			}
		}
		m_wallsEnd = dynamicBodies().size();
		// The tower: 8 rings of 24 boxes at 15 degrees, each ring turned 7.5 degrees further, every box
		// turned to face the centre.
		const btScalar pi = btScalar(3.14159265358979323846);
		const btScalar radius = btScalar(1.3) * 24 / pi;
		btScalar ringY = 1;
		for (int ring = 0; ring < 8; ++ring)
		{
			for (int i = 0; i < 24; ++i)
			{
				const btScalar angle = pi + btScalar(ring) * (pi / 24) + btScalar(i) * (2 * pi / 24);
				addBody(box, 1,
				        at(btVector3(25, 0, 0) + btVector3(radius * btSin(angle), ringY, radius * btCos(angle)),
				           btQuaternion(btVector3(0, 1, 0), angle)));
			}
			ringY += 2;
		}
	}
	bool report(std::string& line, int frames) const override
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
		bool ok = c.nonFinite == 0 && c.minY > btScalar(0.9);
		const std::string verdict = displacedVerdict(pyramid + walls + tower, frames, kSettledFrames, ok);
		line = format(
		    "more than 0.1 m from rest: pyramid %d/%d, walls %d/%d, tower %d/%d (%s); pyramid top y %.3f "
		    "(ideal 23.0), tower top %.3f (15.0), max speed %.3f, non-finite %d",
		    pyramid, int(m_pyramidEnd), walls, int(m_wallsEnd - m_pyramidEnd), tower,
		    int(dynamicBodies().size() - m_wallsEnd), verdict.c_str(),
		    double(dynamicBodies()[m_pyramidEnd - 1]->getCenterOfMassPosition().y()),
		    double(dynamicBodies().back()->getCenterOfMassPosition().y()), double(c.maxSpeed), c.nonFinite);
		return ok;
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
		// 8 x 8 barrels a layer at pitch 3 + spacing; spacing starts at 1.5 and grows by 1 % a layer, and each
		// layer's corner moves by -0.35 spacing in x and z.
		btScalar spacing = btScalar(1.5);
		btScalar corner = -8 * (3 + spacing) * btScalar(0.5);
		btScalar y = 3;
		for (int k = 0; k < 15; ++k)
		{
			for (int j = 0; j < 8; ++j)
				for (int i = 0; i < 8; ++i)
					addBody(
					    hull, 1,
					    at(btVector3(corner + btScalar(i) * (3 + spacing), y, corner + btScalar(j) * (3 + spacing))));
			corner -= btScalar(0.05) * spacing * 7;
			spacing *= btScalar(1.01);
			y += 3 + spacing;
		}
	}
	bool report(std::string& line, int /*frames*/) const override
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
		btConvexHullShape* hull = barrels ? own(makeTaruHull()) : 0;
		unsigned int seed = 12345;
		// A grid p of 10 x 10 x 10 at pitch 3 + spacing (spacing 2, growing by 10 % a layer, each layer's
		// corner moving by -0.45 spacing), the first layer at y = 20; a body at (0, 25, 0) + (5, 1, 5) p.
		btScalar spacing = 2;
		btScalar corner = -10 * (3 + spacing) * btScalar(0.5);
		btVector3 grid(0, 20, 0);
		for (int k = 0; k < 10; ++k)
		{
			for (int j = 0; j < 10; ++j)
			{
				grid.setZ(corner + btScalar(j) * (3 + spacing));
				for (int i = 0; i < 10; ++i)
				{
					grid.setX(corner + btScalar(i) * (3 + spacing));
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
			}
			corner -= btScalar(0.05) * spacing * 9;
			spacing *= btScalar(1.1);
			grid.setY(grid.y() + 3 + spacing);
		}
		addLandscape();  // after the bodies, as in the reference program (the order of bodies is the order of work)
	}
	bool report(std::string& line, int /*frames*/) const override
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
	enum
	{
		NUM_RAYS = 500
	};
	long m_hits = 0, m_rays = 0;
	double m_lastSum = 0, m_checksum = 0;
	// FNV-1a over every ray's result (hit object's index, fraction and normal bits): equal hashes mean the
	// same hits, bit for bit, whatever order the queries visit the objects in.
	uint64_t m_rayHash = 1469598103934665603ull;
	btVector3 m_to[NUM_RAYS];
	// Ray i turns i 4 pi / 500 about y (two full turns: 250 directions, each cast twice), 2500 m out
	// and down to y = -1000.
	Raycast() : OnLandscape(true)
	{
		const btScalar turnPerRay = 2 * SIMD_2_PI / NUM_RAYS;
		for (int i = 0; i < NUM_RAYS; ++i)
		{
			m_to[i] = btVector3(0, 50, 0) +
			          quatRotate(btQuaternion(btVector3(0, 1, 0), turnPerRay * btScalar(i)), btVector3(1, 0, 0)) * 2500;
			m_to[i].setY(-1000);
		}
	}
	void afterStep() override
	{
		const btVector3 from(0, 50, 0);
		double sum = 0;
		for (int i = 0; i < NUM_RAYS; ++i)
		{
			const btVector3& to = m_to[i];
			btCollisionWorld::ClosestRayResultCallback callback(from, to);
			world().rayTest(from, to, callback);
			++m_rays;
			if (callback.hasHit())
			{
				++m_hits;
				sum += double((callback.m_hitPointWorld - from).length());
			}
			hashRayResult(callback);
		}
		m_lastSum = sum;
		m_checksum += sum;
	}
	void hashRayResult(const btCollisionWorld::ClosestRayResultCallback& callback)
	{
		const int object = callback.m_collisionObject ? callback.m_collisionObject->getWorldArrayIndex() : -1;
		const btScalar values[4] = {callback.m_closestHitFraction, callback.m_hitNormalWorld.x(),
		                            callback.m_hitNormalWorld.y(), callback.m_hitNormalWorld.z()};
		unsigned char bytes[sizeof(object) + sizeof(values)];
		memcpy(bytes, &object, sizeof(object));
		memcpy(bytes + sizeof(object), values, sizeof(values));
		for (unsigned char byte : bytes)
		{
			m_rayHash ^= byte;
			m_rayHash *= 1099511628211ull;
		}
	}
	bool report(std::string& line, int frames) const override
	{
		std::string base;
		const bool ok = OnLandscape::report(base, frames);
		line = base + format("; rays hit %ld of %ld, last frame's hit distances sum to %.3f, all frames' to %.3f, "
		                     "ray hash %016llx",
		                     m_hits, m_rays, m_lastSum, m_checksum, (unsigned long long)m_rayHash);
		return ok && m_hits == m_rays;
	}
};

// ---- scene 8: Jolt's pyramid --------------------------------------------------------------------
class PyramidJolt : public Scene
{
public:
	// The top level falls 14 gaps of 0.5 m (7 m, 1.2 s) while the levels below it land and settle; all
	// are at rest after 1.5 s, so the count is judged from 2 s on.
	static const int kSettledFrames = 120;
	PyramidJolt()
	{
		world().getSolverInfo().m_numIterations = 10;
		btBoxShape* floorShape = own(new btBoxShape(btVector3(50, 1, 50)));
		addBody(floorShape, 0, at(btVector3(0, -1, 0)));
		btBoxShape* box = own(new btBoxShape(btVector3(1, 1, 1)));
		// Level i holds 15 - i boxes a side on the cells i / 2 ... 14 - (i + 1) / 2 of a 2 m grid whose
		// corner is at -15, odd levels shifted by half a box; levels 2.5 m apart (0.5 m gaps that settle).
		for (int level = 0; level < 15; ++level)
			for (int i = level / 2; i < 15 - (level + 1) / 2; ++i)
				for (int j = level / 2; j < 15 - (level + 1) / 2; ++j)
				{
					const btScalar shift = (level & 1) ? 1 : 0;
					btRigidBody* body =
					    addBody(box, 1,
					            at(btVector3(-15 + 2 * btScalar(i) + shift, 1 + btScalar(2.5) * btScalar(level),
					                         -15 + 2 * btScalar(j) + shift)));
					body->setActivationState(DISABLE_DEACTIVATION);
				}
	}
	bool report(std::string& line, int frames) const override
	{
		const Census c(dynamicBodies());
		auto rest = [&](size_t i)
		{ return 1 + 2 * btScalar(std::floor((m_start[i].getOrigin().y() - 1) / btScalar(2.5) + btScalar(0.5))); };
		const int displaced = displacedFromRest(dynamicBodies(), m_start, 0, dynamicBodies().size(), rest);
		bool ok = c.nonFinite == 0 && c.minY > btScalar(0.9);
		const std::string verdict = displacedVerdict(displaced, frames, kSettledFrames, ok);
		line =
		    format("more than 0.1 m from rest: %d/%d (%s); top at %.3f (rest 29.0), max speed %.3f, non-finite %d",
		           displaced, c.bodies, verdict.c_str(), double(dynamicBodies().back()->getCenterOfMassPosition().y()),
		           double(c.maxSpeed), c.nonFinite);
		return ok;
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
	bool report(std::string& line, int /*frames*/) const override
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

namespace
{
bool gMultithreadedWorld = false;

btDefaultCollisionConfiguration* makeConfiguration()
{
	if (!gMultithreadedWorld) return new btDefaultCollisionConfiguration();
	// Bullet's multithreaded examples give the pools room for every pair of a large scene.
	btDefaultCollisionConstructionInfo info;
	info.m_defaultMaxPersistentManifoldPoolSize = 80000;
	info.m_defaultMaxCollisionAlgorithmPoolSize = 80000;
	return new btDefaultCollisionConfiguration(info);
}
}  // namespace

void setMultithreadedWorld(bool multithreaded) { gMultithreadedWorld = multithreaded; }

Scene::Scene()
    : m_configuration(makeConfiguration()),
      m_dispatcher(gMultithreadedWorld ? new btCollisionDispatcherMt(m_configuration.get(), 40)
                                       : new btCollisionDispatcher(m_configuration.get())),
      m_broadphase(new btDbvtBroadphase()),
      m_solver(gMultithreadedWorld ? new btSequentialImpulseConstraintSolverMt()
                                   : new btSequentialImpulseConstraintSolver()),
      m_solverPool(gMultithreadedWorld ? new btConstraintSolverPoolMt(BT_MAX_THREAD_COUNT) : 0),
      m_world(gMultithreadedWorld
                  ? new btDiscreteDynamicsWorldMt(m_dispatcher.get(), m_broadphase.get(), m_solverPool.get(),
                                                  m_solver.get(), m_configuration.get())
                  : new btDiscreteDynamicsWorld(m_dispatcher.get(), m_broadphase.get(), m_solver.get(),
                                                m_configuration.get()))
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
