// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// ConcaveDemo: rigid bodies on concave static terrain, headless. The same rolling landscape
// y = h(x, z) = 0.6 sin(0.35 x) cos(0.3 z) is built twice, as a btBvhTriangleMeshShape (a 40 x 40 grid of
// quads, two triangles each) and as a btHeightfieldTerrainShape (41 x 41 float samples). On each, 48
// bodies (spheres, boxes and capsules, every shape at least 0.3 thick) are dropped from a few metres
// and left for 6 seconds. Each second the demo prints the lowest clearance (body centre above the
// terrain beneath it), the number of sleeping bodies and of bodies slower than 0.1 m/s. Checks: no
// body ever falls through (its centre stays at least 0.2 above h(x, z): every shape is thicker than
// that, and the flat triangles differ from h by under 1 cm), and at least half of them are at rest
// (slower than 0.1 m/s) by the end; spheres on a slope may keep rolling, and one rolling body keeps
// its whole pile's island awake. Exit 1 when a check fails. --frames N runs N steps on each terrain
// (default 360; shorter runs skip the at-rest check); --png shows the height field's last frame;
// --png-sequence covers both terrains (docs/demos.md).

#include <math.h>
#include <stdio.h>

#include "DemoPictures.h"
#include "btBulletDynamicsCommon.h"

namespace
{
const int kQuads = 40;  // per side; grid spacing 1, centred on the origin
const btScalar kHalf = btScalar(kQuads) / 2;

btScalar terrainHeight(btScalar x, btScalar z)
{
	return btScalar(0.6) * btSin(btScalar(0.35) * x) * btCos(btScalar(0.3) * z);
}

// Drops bodies on the terrain body already in world; returns true when the checks pass.
bool dropBodiesOn(const char* name, btDiscreteDynamicsWorld& world, caliber::demo::DemoPictures& pictures)
{
	btSphereShape sphere(btScalar(0.4));
	btBoxShape box(btVector3(btScalar(0.35), btScalar(0.35), btScalar(0.35)));
	btCapsuleShape capsule(btScalar(0.3), btScalar(0.6));
	btCollisionShape* shapes[3] = {&sphere, &box, &capsule};
	btAlignedObjectArray<btRigidBody*> bodies;
	btAlignedObjectArray<btDefaultMotionState*> motions;
	for (int i = 0; i < 48; ++i)
	{
		btCollisionShape* shape = shapes[i % 3];
		btVector3 inertia;
		shape->calculateLocalInertia(1, inertia);
		const btScalar x = btScalar(1.6) * btScalar(i % 7 - 3);
		const btScalar z = btScalar(1.6) * btScalar((i / 7) % 7 - 3);
		const btVector3 origin(x, 2 + btScalar(0.9) * btScalar(i / 49 + (i % 5)), z);
		btDefaultMotionState* motion = new btDefaultMotionState(
		    btTransform(btQuaternion(btVector3(1, 1, 0).normalized(), btScalar(0.3) * i), origin));
		btRigidBody* body = new btRigidBody(btRigidBody::btRigidBodyConstructionInfo(1, motion, shape, inertia));
		body->setFriction(btScalar(0.8));
		body->setRollingFriction(btScalar(0.02));
		world.addRigidBody(body);
		bodies.push_back(body);
		motions.push_back(motion);
	}

	btScalar lowestClearance = BT_LARGE_FLOAT;
	int sleeping = 0;
	int slow = 0;
	for (int frame = 1; frame <= pictures.frames(); ++frame)
	{
		world.stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.));
		for (int b = 0; b < bodies.size(); ++b)
		{
			const btVector3& p = bodies[b]->getCenterOfMassPosition();
			lowestClearance = btMin(lowestClearance, p.getY() - terrainHeight(p.getX(), p.getZ()));
		}
		pictures.frame(world, frame);
		if (frame % 60 != 0 && frame != pictures.frames()) continue;
		sleeping = 0;
		slow = 0;
		for (int b = 0; b < bodies.size(); ++b)
		{
			if (bodies[b]->getActivationState() == ISLAND_SLEEPING) ++sleeping;
			if (bodies[b]->getLinearVelocity().length() < btScalar(0.1)) ++slow;
		}
		if (frame % 60 == 0)
			printf("%s, t=%d s: lowest clearance %.3f, sleeping %d/%d, slower than 0.1 m/s %d\n", name, frame / 60,
			       double(lowestClearance), sleeping, bodies.size(), slow);
		else
			printf("%s, t=%.3f s: lowest clearance %.3f, sleeping %d/%d, slower than 0.1 m/s %d\n", name, frame / 60.0,
			       double(lowestClearance), sleeping, bodies.size(), slow);
	}
	for (int b = 0; b < bodies.size(); ++b)
	{
		world.removeRigidBody(bodies[b]);
		delete bodies[b];
		delete motions[b];
	}
	const bool noneFellThrough = lowestClearance > btScalar(0.2);
	if (pictures.shortened())
	{
		printf(
		    "%s: nothing fell through (lowest clearance %.3f > 0.2): %s; at rest not checked (--frames %d is "
		    "shorter than 360)\n",
		    name, double(lowestClearance), noneFellThrough ? "ok" : "FAILED", pictures.frames());
		return noneFellThrough;
	}
	const bool mostAtRest = 2 * slow >= bodies.size();
	printf("%s: nothing fell through (lowest clearance %.3f > 0.2): %s; at rest (< 0.1 m/s) %d of %d: %s\n", name,
	       double(lowestClearance), noneFellThrough ? "ok" : "FAILED", slow, bodies.size(),
	       mostAtRest ? "ok" : "FAILED");
	return noneFellThrough && mostAtRest;
}
}  // namespace

int main(int argc, char** argv)
{
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "ConcaveDemo";
	commandLine.defaultFrames = 360;
	commandLine.sequences = true;
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();

	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
	world.setGravity(btVector3(0, -10, 0));

	// The samples, shared by both terrains: (kQuads + 1)^2 heights, x fastest.
	const int samples = kQuads + 1;
	btAlignedObjectArray<float> heights;
	btAlignedObjectArray<btScalar> vertices;
	btAlignedObjectArray<int> indices;
	for (int j = 0; j < samples; ++j)
		for (int i = 0; i < samples; ++i)
		{
			const btScalar x = btScalar(i) - kHalf, z = btScalar(j) - kHalf;
			heights.push_back(float(terrainHeight(x, z)));
			vertices.push_back(x);
			vertices.push_back(terrainHeight(x, z));
			vertices.push_back(z);
		}
	for (int j = 0; j < kQuads; ++j)
		for (int i = 0; i < kQuads; ++i)
		{
			const int a = j * samples + i, b = a + 1, c = a + samples, d = c + 1;
			const int quad[6] = {a, c, b, b, c, d};
			for (int k = 0; k < 6; ++k) indices.push_back(quad[k]);
		}

	bool ok = true;
	{
		btTriangleIndexVertexArray mesh(indices.size() / 3, &indices[0], 3 * int(sizeof(int)), vertices.size() / 3,
		                                &vertices[0], 3 * int(sizeof(btScalar)));
		btBvhTriangleMeshShape meshShape(&mesh, true);
		btRigidBody terrain(btRigidBody::btRigidBodyConstructionInfo(0, 0, &meshShape));
		world.addRigidBody(&terrain);
		ok = dropBodiesOn("triangle mesh", world, pictures) && ok;
		world.removeRigidBody(&terrain);
	}
	{
		// A height field is centred on its AABB: lift the body by the middle of the height range so that
		// sample heights are world heights.
		const btScalar minHeight = -btScalar(0.6), maxHeight = btScalar(0.6);
		btHeightfieldTerrainShape fieldShape(samples, samples, &heights[0], minHeight, maxHeight, 1, false);
		btRigidBody::btRigidBodyConstructionInfo info(0, 0, &fieldShape);
		info.m_startWorldTransform.setOrigin(btVector3(0, (minHeight + maxHeight) / 2, 0));
		btRigidBody terrain(info);
		world.addRigidBody(&terrain);
		ok = dropBodiesOn("height field", world, pictures) && ok;
		world.removeRigidBody(&terrain);
	}
	return pictures.finish(ok ? 0 : 1);
}
