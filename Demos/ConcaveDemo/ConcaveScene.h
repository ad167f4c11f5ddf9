// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_CONCAVE_SCENE_H
#define CALIBER_DEMOS_CONCAVE_SCENE_H
// ConcaveDemo's scene: the rolling landscape y = h(x, z) = 0.6 sin(0.35 x) cos(0.3 z) as a triangle mesh
// (a 40 x 40 grid of quads, two triangles each) or a height field (41 x 41 float samples), with 48
// spheres, boxes and capsules dropped on it from a few metres. Used by ConcaveDemo, which measures it,
// and by the demo browser.

#include <memory>
#include <vector>

#include "DemoWorld.h"
#include "btBulletDynamicsCommon.h"

namespace concave_demo
{
/// The terrain's height at (x, z).
btScalar terrainHeight(btScalar x, btScalar z);

enum Terrain
{
	kTriangleMesh,
	kHeightField
};

/// The world, one terrain and the dropped bodies. ConcaveDemo runs both terrains in one world (build,
/// run, clear, build again), as it always has, so that its state is the same bit for bit.
class Scene
{
public:
	Scene();
	~Scene();
	Scene(const Scene&) = delete;
	Scene& operator=(const Scene&) = delete;
	btDiscreteDynamicsWorld& world() { return m_world; }
	/// Adds the terrain and drops the 48 bodies on it (after clear() when it was built before).
	void build(Terrain terrain);
	/// Removes and deletes the bodies, then the terrain.
	void clear();
	/// The dropped bodies, in the order they were added.
	const std::vector<btRigidBody*>& bodies() const { return m_bodies; }

private:
	caliber::demo::DemoWorld m_demoWorld;  // the demos' usual world
	btDiscreteDynamicsWorld& m_world{m_demoWorld.world()};
	// The terrain's data (the shapes keep pointers into it).
	btAlignedObjectArray<float> m_heights;
	btAlignedObjectArray<btScalar> m_vertices;
	btAlignedObjectArray<int> m_indices;
	std::unique_ptr<btTriangleIndexVertexArray> m_mesh;
	std::vector<std::unique_ptr<btCollisionShape>> m_shapes;
	std::unique_ptr<btRigidBody> m_terrain;
	std::vector<btRigidBody*> m_bodies;
	std::vector<std::unique_ptr<btDefaultMotionState>> m_motions;
};
}  // namespace concave_demo

#endif
