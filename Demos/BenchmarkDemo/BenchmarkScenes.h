// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_BENCHMARK_SCENES_H
#define CALIBER_BENCHMARK_SCENES_H

// The benchmark scenes (Bullet's benchmark scenes and Jolt's pyramid; docs/rigid-body-dynamics.md),
// body for body as the reference program that measured Bullet builds them: same positions, same
// order, same arithmetic, so that both print the same state hash against the same library.

#include <memory>
#include <string>
#include <vector>

#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorldMt.h"
#include "btBulletDynamicsCommon.h"

namespace benchmark_demo
{
/// The world the scenes are built in: 0 (the default), btDiscreteDynamicsWorld as Bullet's benchmark
/// builds it; 1 or more, Bullet 2.89's multithreaded world (btCollisionDispatcherMt, a solver pool, the
/// Mt solver, btDiscreteDynamicsWorldMt) as Bullet's multithreaded examples build it. The caller sets the
/// task scheduler and its thread count.
void setMultithreadedWorld(bool multithreaded);

/// One world and everything it owns.
class Scene
{
public:
	Scene();
	virtual ~Scene();

	btDiscreteDynamicsWorld& world() { return *m_world; }
	const btDiscreteDynamicsWorld& worldConst() const { return *m_world; }

	/// A shape owned by the scene.
	template <class Shape>
	Shape* own(Shape* shape)
	{
		m_shapes.emplace_back(shape);
		return shape;
	}
	/// A body (mass 0: static) with a default motion state, friction 0.5, restitution 0.
	btRigidBody* addBody(btCollisionShape* shape, btScalar mass, const btTransform& pose);
	/// A joint owned by the scene, added with collisions between its bodies disabled.
	void addJoint(btTypedConstraint* joint);
	/// Bullet's benchmark ground: a static box (250, 50, 250) at (0, -50, 0).
	void addBenchmarkGround();
	/// The procedural stand-in for Bullet's landscape: 8 BVH mesh tiles, 32768 triangles, body at (0, -25, 0).
	void addLandscape();

	const std::vector<btRigidBody*>& dynamicBodies() const { return m_dynamic; }
	/// Called after each step (the raycast scene casts its rays here).
	virtual void afterStep() {}
	/// The scene's sanity figures after frames steps, one line; returns false when a figure shows a
	/// broken simulation.
	virtual bool report(std::string& line, int frames) const = 0;

	/// Start poses of the dynamic bodies (same order as dynamicBodies()).
	std::vector<btTransform> m_start;

private:
	std::unique_ptr<btDefaultCollisionConfiguration> m_configuration;
	std::unique_ptr<btCollisionDispatcher> m_dispatcher;
	std::unique_ptr<btDbvtBroadphase> m_broadphase;
	std::unique_ptr<btSequentialImpulseConstraintSolver> m_solver;
	std::unique_ptr<btConstraintSolverPoolMt> m_solverPool;  // the multithreaded world's
	std::unique_ptr<btDiscreteDynamicsWorld> m_world;
	std::vector<std::unique_ptr<btCollisionShape>> m_shapes;
	std::vector<std::unique_ptr<btStridingMeshInterface>> m_meshes;
	std::vector<std::vector<btScalar>> m_vertexData;
	std::vector<std::vector<unsigned short>> m_indexData;
	std::vector<std::unique_ptr<btDefaultMotionState>> m_motionStates;
	std::vector<btRigidBody*> m_bodies;
	std::vector<btRigidBody*> m_dynamic;
	std::vector<std::unique_ptr<btTypedConstraint>> m_joints;
};

/// Names of the scenes, in order.
std::vector<std::string> sceneNames();
/// Builds the named scene (0 for an unknown name).
std::unique_ptr<Scene> makeScene(const std::string& name);
/// Height of the procedural landscape at (x, z), in landscape-local coordinates.
btScalar landscapeHeight(btScalar x, btScalar z);
}  // namespace benchmark_demo

#endif  // CALIBER_BENCHMARK_SCENES_H
