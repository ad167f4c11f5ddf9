// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// ConvexDecompositionDemo: concave meshes as dynamic bodies, headless. Three closed meshes of our own
// making (a torus, a cup and an L-shaped bracket, Extras/ConvexDecomposition/ExampleMeshes.h) are split
// into at most 32 convex hulls each with a 5 % volume tolerance; the demo prints each one's hull count,
// the hulls' volume excess over the mesh (the "volume error") and the time taken. The hulls become
// compounds that are dropped on the ground (z up), with a ball dropped into the cup. Checks: every
// decomposition is within the tolerance, the torus needs at least 4 hulls and the bracket and cup at
// least 2; after 4 s every body is at rest on the ground, none ever more than 1 cm below it, and the ball lies on the
// cup's floor inside it (it would sit on the rim if the cup were one hull). Exit 1 when a check fails.

#include "DemoPictures.h"

#include <stdio.h>

#include <memory>
#include <vector>

#include "ConvexDecomposition/ExampleMeshes.h"
#include "ConvexDecompositionScene.h"

namespace
{
using convex_decomposition_demo::decompose;
using convex_decomposition_demo::Decomposed;

// The lowest point of a body made of convex children (margins included), from their support points.
btScalar lowestPoint(const btRigidBody& body)
{
	const btCompoundShape* compound = static_cast<const btCompoundShape*>(body.getCollisionShape());
	btScalar lowest = BT_LARGE_FLOAT;
	for (int i = 0; i < compound->getNumChildShapes(); ++i)
	{
		const btTransform child = body.getWorldTransform() * compound->getChildTransform(i);
		const btVector3 down = child.getBasis().transpose() * btVector3(0, 0, -1);
		const btConvexShape* shape = static_cast<const btConvexShape*>(compound->getChildShape(i));
		lowest = btMin(lowest, (child * shape->localGetSupportingVertex(down)).z());
	}
	return lowest;
}
}  // namespace

int main(int argc, char** argv)
{
	caliber::demo::DemoPictures pictures(argc, argv, "ConvexDecompositionDemo");
	if (!pictures.ok()) return pictures.exitCode();
	Decomposed torus, cup, bracket;
	bool ok = decompose("torus", caliber::makeTorusMesh(btScalar(0.4), btScalar(0.12), 24, 12), torus);
	ok =
	    decompose("cup", caliber::makeCupMesh(btScalar(0.3), btScalar(0.04), btScalar(0.4), btScalar(0.05), 24), cup) &&
	    ok;
	ok = decompose("bracket", caliber::makeLBracketMesh(btScalar(0.6), btScalar(0.15), btScalar(0.15)), bracket) && ok;
	if (!ok) return 1;

	// ConvexDecompositionScene.h: the torus and the bracket dropped, the cup upright with a ball above it.
	convex_decomposition_demo::Scene scene(torus, cup, bracket);
	btDiscreteDynamicsWorld& world = scene.world();
	const std::vector<std::unique_ptr<btRigidBody>>& bodies = scene.bodies();
	btRigidBody& ball = scene.ball();

	btScalar lowest = BT_LARGE_FLOAT;
	for (int second = 1; second <= 4; ++second)
	{
		for (int step = 0; step < 60; ++step)
		{
			world.stepSimulation(btScalar(1) / 60, 0);
			for (const auto& body : bodies) lowest = btMin(lowest, lowestPoint(*body));
		}
		printf("t = %d s: torus z %.3f, cup z %.3f, bracket z %.3f, ball (%.3f %.3f %.3f)\n", second,
		       bodies[0]->getCenterOfMassPosition().z(), bodies[1]->getCenterOfMassPosition().z(),
		       bodies[2]->getCenterOfMassPosition().z(), ball.getCenterOfMassPosition().x(),
		       ball.getCenterOfMassPosition().y(), ball.getCenterOfMassPosition().z());
	}
	int resting = 0;
	for (const auto& body : bodies) resting += body->getLinearVelocity().length() < btScalar(0.1);
	const btVector3 ballAt = ball.getCenterOfMassPosition() - bodies[1]->getCenterOfMassPosition();
	const btScalar ballHeight = ball.getCenterOfMassPosition().z();
	// The picture: the world as the run ends (z up, so seen from above at a slant).
	pictures.setViewDirection(btVector3(btScalar(0.3), btScalar(0.8), btScalar(-1)));
	pictures.capture(world);

	const bool tolerances =
	    torus.result.withinTolerance && cup.result.withinTolerance && bracket.result.withinTolerance;
	const bool counts =
	    torus.result.hulls.size() >= 4 && cup.result.hulls.size() >= 2 && bracket.result.hulls.size() >= 2;
	// The ball (radius 0.08) on the cup's floor (0.05 thick) has its centre near 0.13 m; on the rim it would be 0.48 m.
	const bool inCup = ballHeight < btScalar(0.2) && btVector3(ballAt.x(), ballAt.y(), 0).length() < btScalar(0.26);
	const bool grounded = lowest > btScalar(-0.01) && resting == 3;
	printf("check: every decomposition within 5 %%: %s\n", tolerances ? "ok" : "FAILED");
	printf("check: hull counts (torus >= 4, cup >= 2, bracket >= 2): %s\n", counts ? "ok" : "FAILED");
	printf("check: bodies at rest on the ground (lowest point %.3f m, %d of 3 at rest): %s\n", lowest, resting,
	       grounded ? "ok" : "FAILED");
	printf("check: the ball lies in the cup (centre %.3f m up): %s\n", ballHeight, inCup ? "ok" : "FAILED");
	return pictures.finish((tolerances && counts && grounded && inCup) ? 0 : 1);
}
