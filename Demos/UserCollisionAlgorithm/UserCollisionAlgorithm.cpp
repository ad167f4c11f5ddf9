// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// UserCollisionAlgorithm: plugging your own narrowphase into the dispatcher, headless. The program writes a collision
// algorithm for sphere-sphere pairs (the exact contact along the line of centres), registers its factory with
// btCollisionDispatcher::registerCollisionCreateFunc, and runs a small btCollisionWorld of three spheres and a box
// while one sphere moves. It prints every manifold, marking those the user algorithm filled, and checks that every
// sphere-sphere pair went through the user algorithm, that the sphere-box pair kept the default one, and that the
// contact distances are the analytic ones. The demo exits 1 when any of that is not so. --frames N (1 to
// 4) stops after frame N; --png shows the last frame with its contact points (docs/demos.md).

#include "DemoPictures.h"
#include "DemoPrograms.h"
#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "btBulletCollisionCommon.h"

#include <stdio.h>

namespace
{
/// The manifolds the user algorithm owns right now, and how often it ran: the demo's evidence that the dispatcher
/// called it.
btAlignedObjectArray<const btPersistentManifold*> gUserManifolds;
int gUserAlgorithmCalls = 0;

/// A user collision algorithm for two spheres: one contact point on B's surface along the line of centres, at distance
/// |cA - cB| - rA - rB, kept while it is within the manifold's breaking threshold.
class SphereSphereUserAlgorithm : public btCollisionAlgorithm
{
public:
	/// Makes the manifold of the pair through the dispatcher, which owns manifold memory.
	SphereSphereUserAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* body0,
	                          const btCollisionObjectWrapper* body1)
	    : btCollisionAlgorithm(ci),
	      m_manifold(m_dispatcher->getNewManifold(body0->getCollisionObject(), body1->getCollisionObject()))
	{
		gUserManifolds.push_back(m_manifold);
	}
	/// Gives the manifold back to the dispatcher.
	~SphereSphereUserAlgorithm() override
	{
		gUserManifolds.remove(m_manifold);
		m_dispatcher->releaseManifold(m_manifold);
	}

	/// Replaces the manifold's point with the current contact (or removes it when the spheres are apart).
	void processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
	                      const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override
	{
		(void)dispatchInfo;
		++gUserAlgorithmCalls;
		resultOut->setPersistentManifold(m_manifold);
		m_manifold->clearManifold();
		const btScalar radius0 = static_cast<const btSphereShape*>(body0->getCollisionShape())->getRadius();
		const btScalar radius1 = static_cast<const btSphereShape*>(body1->getCollisionShape())->getRadius();
		const btVector3 centre0 = body0->getWorldTransform().getOrigin();
		const btVector3 centre1 = body1->getWorldTransform().getOrigin();
		const btVector3 between = centre0 - centre1;
		const btScalar centreDistance = between.length();
		const btScalar distance = centreDistance - radius0 - radius1;
		if (centreDistance <= SIMD_EPSILON || distance > m_manifold->getContactBreakingThreshold())
		{
			return;  // apart, or concentric (no direction to report; not part of this
			         // demo)
		}
		const btVector3 normalOnB = between / centreDistance;
		resultOut->addContactPoint(normalOnB, centre1 + normalOnB * radius1, distance);
	}
	/// No continuous collision in this demo: the pair never reports an earlier time of impact.
	btScalar calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
	                               const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override
	{
		(void)body0;
		(void)body1;
		(void)dispatchInfo;
		(void)resultOut;
		return btScalar(1);
	}
	/// The pair's one manifold.
	void getAllContactManifolds(btManifoldArray& manifoldArray) override { manifoldArray.push_back(m_manifold); }

	/// The factory registered with the dispatcher: algorithms live in the dispatcher's algorithm memory.
	struct CreateFunc : public btCollisionAlgorithmCreateFunc
	{
		btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
		                                               const btCollisionObjectWrapper* body0,
		                                               const btCollisionObjectWrapper* body1) override
		{
			void* memory = ci.m_dispatcher1->allocateCollisionAlgorithm(int(sizeof(SphereSphereUserAlgorithm)));
			return new (memory) SphereSphereUserAlgorithm(ci, body0, body1);
		}
	};

private:
	btPersistentManifold* m_manifold;
};

enum ObjectIndex
{
	kSphereA,
	kSphereB,
	kSphereC,
	kBox,
	kObjectCount
};
const char* const kObjectNames[kObjectCount] = {"sphere A", "sphere B", "sphere C", "box"};
}  // namespace

int caliber::demo::userCollisionAlgorithmDemo(int argc, char** argv)
{
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "UserCollisionAlgorithm";
	commandLine.defaultFrames = 4;  // the script's length (heightsOfC below)
	commandLine.maxFrames = 4;
	commandLine.debugDrawMode = btIDebugDraw::DBG_DrawContactPoints;
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();

	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	// The factory must outlive the dispatcher's algorithms, so it is declared before the world.
	SphereSphereUserAlgorithm::CreateFunc userCreateFunc;
	dispatcher.registerCollisionCreateFunc(SPHERE_SHAPE_PROXYTYPE, SPHERE_SHAPE_PROXYTYPE, &userCreateFunc);
	btDbvtBroadphase broadphase;
	btCollisionWorld world(&dispatcher, &broadphase, &configuration);

	// Unit spheres A at the origin and B at x = 1.5 (overlapping by 0.5); C starts 1 above A and comes down; a unit box
	// at x = -1.9 overlaps A by 0.1 (its face is at x = -0.9).
	btSphereShape sphereShape(1);
	btBoxShape boxShape(btVector3(1, 1, 1));
	btCollisionObject objects[kObjectCount];
	btCollisionShape* const shapes[kObjectCount] = {&sphereShape, &sphereShape, &sphereShape, &boxShape};
	const btVector3 positions[kObjectCount] = {btVector3(0, 0, 0), btVector3(btScalar(1.5), 0, 0), btVector3(0, 3, 0),
	                                           btVector3(btScalar(-1.9), 0, 0)};
	for (int i = 0; i < kObjectCount; ++i)
	{
		objects[i].setCollisionShape(shapes[i]);
		objects[i].setWorldTransform(btTransform(btQuaternion::getIdentity(), positions[i]));
		objects[i].setUserIndex(i);
		world.addCollisionObject(&objects[i]);
	}

	// Sphere-sphere contacts expected per frame: A-B always (0.5 deep); A-C from height 1.9 on (C is then 0.1, then 0.2
	// deep). B-C stays apart: sqrt(1.5^2 + h^2) - 2 >= 0.34.
	const btScalar heightsOfC[] = {3, btScalar(2.5), btScalar(1.9), btScalar(1.8)};
	const int expectedSphereContacts[] = {1, 1, 2, 2};
	bool good = true;
	for (int frame = 0; frame < pictures.frames(); ++frame)
	{
		objects[kSphereC].setWorldTransform(
		    btTransform(btQuaternion::getIdentity(), btVector3(0, heightsOfC[frame], 0)));
		const int callsBefore = gUserAlgorithmCalls;
		world.performDiscreteCollisionDetection();
		printf(
		    "frame %d: sphere C at height %.2f, user algorithm ran %d time(s), "
		    "%d manifold(s)\n",
		    frame, double(heightsOfC[frame]), gUserAlgorithmCalls - callsBefore, dispatcher.getNumManifolds());

		int sphereContacts = 0;
		for (int m = 0; m < dispatcher.getNumManifolds(); ++m)
		{
			const btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(m);
			const btCollisionObject* body0 = manifold->getBody0();
			const btCollisionObject* body1 = manifold->getBody1();
			const bool isUser = gUserManifolds.findLinearSearch(manifold) < gUserManifolds.size();
			const bool bothSpheres = body0->getUserIndex() != kBox && body1->getUserIndex() != kBox;
			printf("  %s - %s (%s algorithm), %d point(s)\n", kObjectNames[body0->getUserIndex()],
			       kObjectNames[body1->getUserIndex()], isUser ? "user" : "default", manifold->getNumContacts());
			if (isUser != bothSpheres)
			{
				printf("  WRONG: %s\n", bothSpheres ? "a sphere pair bypassed the user algorithm"
				                                    : "the user algorithm ran on a sphere-box pair");
				good = false;
			}
			sphereContacts += bothSpheres ? manifold->getNumContacts() : 0;
			for (int p = 0; p < manifold->getNumContacts(); ++p)
			{
				const btManifoldPoint& point = manifold->getContactPoint(p);
				const btVector3& position = point.getPositionWorldOnB();
				printf("    distance %8.4f at (%6.3f %6.3f %6.3f)\n", double(point.getDistance()), double(position.x()),
				       double(position.y()), double(position.z()));
				// Analytic: two spheres are |cA - cB| - 2 apart (unit radii); the box face is 0.1 inside A.
				const btScalar analytic =
				    bothSpheres
				        ? (body0->getWorldTransform().getOrigin() - body1->getWorldTransform().getOrigin()).length() - 2
				        : btScalar(-0.1);
				if (btFabs(point.getDistance() - analytic) > btScalar(1e-3))
				{
					printf("    WRONG: expected distance %.4f\n", double(analytic));
					good = false;
				}
			}
		}
		if (sphereContacts != expectedSphereContacts[frame])
		{
			printf("  WRONG: %d sphere-sphere contact(s), expected %d\n", sphereContacts,
			       expectedSphereContacts[frame]);
			good = false;
		}
		pictures.frame(world, frame + 1);
	}
	if (gUserAlgorithmCalls == 0)
	{
		printf("WRONG: the dispatcher never called the user algorithm\n");
		good = false;
	}

	for (int i = 0; i < kObjectCount; ++i)
	{
		world.removeCollisionObject(&objects[i]);
	}
	printf(good ? "The dispatcher used the user algorithm for every sphere pair.\n" : "MISMATCH (see above)\n");
	return pictures.finish(good ? 0 : 1);
}
