// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// CollisionInterfaceDemo: collision detection without dynamics, headless. A btCollisionWorld holds a static floor, a
// static crate and a static pillar, and a sphere that the program moves by hand: it comes down onto the floor, slides
// along it into the crate, then lifts off. Each frame, performDiscreteCollisionDetection updates the broadphase and the
// narrowphase, and the demo prints every contact point of the dispatcher's manifolds. The static objects use the usual
// filter (group StaticFilter, mask everything but StaticFilter) so that they never test against each other. The demo
// checks the contacts against the analytic distances (sphere above a face: height minus radius) and exits 1 when a
// contact is missing, wrong, or present where the shapes are clearly apart. --frames N (1 to 12) stops
// the script after frame N; --png shows the last frame with its contact points (docs/demos.md).

#include "DemoPictures.h"
#include "DemoPrograms.h"
#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "btBulletCollisionCommon.h"

#include <stdio.h>

namespace
{
enum ObjectIndex
{
	kFloor,
	kCrate,
	kPillar,
	kSphere,
	kObjectCount
};
const char* const kObjectNames[kObjectCount] = {"floor", "crate", "pillar", "sphere"};

/// One frame of the sphere's path, with the analytic signed distances (margins included) to the floor and to the crate.
struct Frame
{
	btScalar x, y;
	btScalar floorDistance, crateDistance;
};

/// A contact must match its analytic distance to this tolerance: the sphere-box and sphere-mesh algorithms are exact up
/// to float rounding at unit scale.
const btScalar kDistanceTolerance = btScalar(1e-3);
/// Farther apart than this, a pair must have no contact point: the breaking threshold is at most
/// gContactBreakingThreshold (0.02), so 0.1 leaves a wide gap.
const btScalar kClearlyApart = btScalar(0.1);

/// Prints the contacts of the frame; returns the smallest distance found per pair with the sphere (BT_LARGE_FLOAT when
/// the pair has no contact point).
void printContacts(btCollisionDispatcher& dispatcher, btScalar closestToSphere[kObjectCount])
{
	for (int i = 0; i < kObjectCount; ++i)
	{
		closestToSphere[i] = btScalar(BT_LARGE_FLOAT);
	}
	for (int m = 0; m < dispatcher.getNumManifolds(); ++m)
	{
		const btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(m);
		const int index0 = manifold->getBody0()->getUserIndex();
		const int index1 = manifold->getBody1()->getUserIndex();
		for (int p = 0; p < manifold->getNumContacts(); ++p)
		{
			const btManifoldPoint& point = manifold->getContactPoint(p);
			const btVector3& position = point.getPositionWorldOnB();
			const btVector3& normal = point.m_normalWorldOnB;
			printf(
			    "    %s - %s: distance %8.4f at (%6.3f %6.3f %6.3f), normal on %s "
			    "(%6.3f %6.3f %6.3f)\n",
			    kObjectNames[index0], kObjectNames[index1], double(point.getDistance()), double(position.x()),
			    double(position.y()), double(position.z()), kObjectNames[index1], double(normal.x()),
			    double(normal.y()), double(normal.z()));
			const int other = index0 == kSphere ? index1 : (index1 == kSphere ? index0 : -1);
			if (other >= 0 && point.getDistance() < closestToSphere[other])
			{
				closestToSphere[other] = point.getDistance();
			}
		}
	}
}

/// Checks one pair against its analytic distance; returns false (and says why) on a mismatch.
bool checkPair(const char* name, btScalar analytic, btScalar found)
{
	if (analytic <= 0 && btFabs(found - analytic) > kDistanceTolerance)
	{
		printf(
		    "    WRONG: sphere - %s should touch at distance %.4f, closest "
		    "contact %.4f\n",
		    name, double(analytic), double(found));
		return false;
	}
	if (analytic >= kClearlyApart && found < btScalar(BT_LARGE_FLOAT))
	{
		printf("    WRONG: sphere - %s are %.4f apart but have a contact point\n", name, double(analytic));
		return false;
	}
	return true;
}
}  // namespace

int caliber::demo::collisionInterfaceDemo(int argc, char** argv)
{
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "CollisionInterfaceDemo";
	commandLine.defaultFrames = 12;  // the script's length (frames[] below)
	commandLine.maxFrames = 12;
	commandLine.debugDrawMode = btIDebugDraw::DBG_DrawContactPoints;
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();
	// Only the sphere moves; the picture shows the whole floor with the crate and the pillar.
	pictures.setFocus(btVector3(-5, 0, -3), btVector3(5, 2.5f, 3));

	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btCollisionWorld world(&dispatcher, &broadphase, &configuration);

	// Floor: a slab whose top face is y = 0.5. Crate: a unit cube resting on it at x = 2 (faces x = 1.5 and 2.5, y =
	// 0.5 to 1.5). Pillar: a cylinder standing at z = -2, out of the sphere's way. Sphere: radius 0.5, moved by the
	// program.
	btBoxShape floorShape(btVector3(5, btScalar(0.5), 3));
	btBoxShape crateShape(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	btCylinderShape pillarShape(btVector3(btScalar(0.4), 1, btScalar(0.4)));
	btSphereShape sphereShape(btScalar(0.5));

	btCollisionObject objects[kObjectCount];
	btCollisionShape* const shapes[kObjectCount] = {&floorShape, &crateShape, &pillarShape, &sphereShape};
	const btVector3 positions[kObjectCount] = {btVector3(0, 0, 0), btVector3(2, 1, 0), btVector3(0, btScalar(1.5), -2),
	                                           btVector3(-2, btScalar(1.5), 0)};
	for (int i = 0; i < kObjectCount; ++i)
	{
		objects[i].setCollisionShape(shapes[i]);
		objects[i].setWorldTransform(btTransform(btQuaternion::getIdentity(), positions[i]));
		objects[i].setUserIndex(i);
		if (i == kSphere)
		{
			world.addCollisionObject(&objects[i]);
		}
		else
		{
			objects[i].setCollisionFlags(objects[i].getCollisionFlags() | btCollisionObject::CF_STATIC_OBJECT);
			world.addCollisionObject(&objects[i], btBroadphaseProxy::StaticFilter,
			                         btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter);
		}
	}

	// The sphere's path. Floor distance = y - 0.5 (top face) - 0.5 (radius). While the sphere is level with the crate
	// (y in [0.5, 1.5]) its crate distance is 1.5 (crate face) - x - 0.5 = 1 - x; at the last frame it is above and
	// beside the crate's top edge (1.5, 1.5): sqrt(0.4^2 + 1^2) - 0.5.
	const Frame frames[] = {
	    {-2, btScalar(1.5), btScalar(0.5), 3},
	    {-2, btScalar(1.2), btScalar(0.2), 3},
	    {-2, btScalar(1.05), btScalar(0.05), 3},
	    {-2, btScalar(0.99), btScalar(-0.01), 3},
	    {-2, btScalar(0.95), btScalar(-0.05), 3},
	    {-1, btScalar(0.95), btScalar(-0.05), 2},
	    {0, btScalar(0.95), btScalar(-0.05), 1},
	    {btScalar(0.5), btScalar(0.95), btScalar(-0.05), btScalar(0.5)},
	    {btScalar(0.9), btScalar(0.95), btScalar(-0.05), btScalar(0.1)},
	    {btScalar(1.05), btScalar(0.95), btScalar(-0.05), btScalar(-0.05)},
	    {btScalar(1.1), btScalar(0.95), btScalar(-0.05), btScalar(-0.1)},
	    {btScalar(1.1), btScalar(2.5), btScalar(1.5), btSqrt(btScalar(1.16)) - btScalar(0.5)},
	};
	const int frameCount = btMin(int(sizeof(frames) / sizeof(frames[0])), pictures.frames());

	bool good = true;
	for (int f = 0; f < frameCount; ++f)
	{
		const Frame& frame = frames[f];
		objects[kSphere].setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(frame.x, frame.y, 0)));
		world.performDiscreteCollisionDetection();

		printf("frame %2d: sphere at (%5.2f %5.2f 0.00), %d manifold(s)\n", f, double(frame.x), double(frame.y),
		       dispatcher.getNumManifolds());
		btScalar closest[kObjectCount];
		printContacts(dispatcher, closest);
		good = checkPair("floor", frame.floorDistance, closest[kFloor]) && good;
		good = checkPair("crate", frame.crateDistance, closest[kCrate]) && good;
		// The pillar stays at least 1.1 from the sphere's path.
		good = checkPair("pillar", btScalar(1.1), closest[kPillar]) && good;
		pictures.frame(world, f + 1);
	}

	for (int i = 0; i < kObjectCount; ++i)
	{
		world.removeCollisionObject(&objects[i]);
	}
	printf(good ? "Every frame's contacts match the analytic distances.\n" : "MISMATCH (see above)\n");
	return pictures.finish(good ? 0 : 1);
}
