// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_CONVEX_DECOMPOSITION_SCENE_H
#define CALIBER_DEMOS_CONVEX_DECOMPOSITION_SCENE_H
// ConvexDecompositionDemo's world: three concave meshes split into convex hulls (decompose(), which
// prints each result) and dropped as compounds on the ground (z up): the torus and the L bracket from
// 0.5 m, tilted, the cup upright with a ball above it. Used by ConvexDecompositionDemo, which checks
// the decompositions and where the bodies come to rest, and by the demo browser.

#include <memory>
#include <vector>

#include "ConvexDecomposition/ConvexDecomposition.h"
#include "ConvexDecomposition/ExampleMeshes.h"
#include "DemoWorld.h"
#include "btBulletDynamicsCommon.h"

namespace convex_decomposition_demo
{
struct Decomposed
{
	const char* name;
	caliber::ConvexDecompositionResult result;
	caliber::DecompositionShape shape;
	std::unique_ptr<btCompoundShape> centred;  // children moved so that the centre of mass is the origin
	btTransform principal;
	btVector3 inertia;
	double milliseconds = 0;
};

/// Splits mesh into at most 32 hulls within 5 % of its volume, prints the result line, and makes the
/// centred compound; false (with the error printed) when the decomposition fails.
bool decompose(const char* name, const caliber::ExampleMesh& mesh, Decomposed& out);

/// The ground, the three compounds and the ball (the Decomposed must outlive the scene), ready to step.
class Scene
{
public:
	Scene(Decomposed& torus, Decomposed& cup, Decomposed& bracket);
	~Scene();
	btDiscreteDynamicsWorld& world() { return m_physics.world(); }
	/// The torus, the cup and the bracket, in that order.
	const std::vector<std::unique_ptr<btRigidBody>>& bodies() const { return m_bodies; }
	btRigidBody& ball() { return *m_ball; }

private:
	caliber::demo::DemoWorld m_physics;  // the world, first in and last out
	btStaticPlaneShape m_groundShape{btVector3(0, 0, 1), 0};
	std::unique_ptr<btRigidBody> m_ground;
	std::vector<std::unique_ptr<btRigidBody>> m_bodies;
	btSphereShape m_ballShape{btScalar(0.08)};
	std::unique_ptr<btRigidBody> m_ball;
};
}  // namespace convex_decomposition_demo

#endif
