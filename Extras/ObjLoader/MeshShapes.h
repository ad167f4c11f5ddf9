// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_EXTRAS_MESH_SHAPES_H
#define CALIBER_EXTRAS_MESH_SHAPES_H

/// Collision shapes from loaded meshes: a static BVH mesh over all groups, or one convex hull per group.

#include <memory>
#include <vector>

#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h"
#include "ObjLoader/ObjLoader.h"

namespace caliber
{
/// A btTriangleIndexVertexArray that owns copies of its vertices and indices, one subpart per added mesh,
/// so it needs nothing else kept alive (a plain btTriangleIndexVertexArray points into the user's arrays).
class OwnedTriangleIndexVertexArray : public btTriangleIndexVertexArray
{
public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Appends mesh as a new subpart. Meshes without triangles, or with an index outside their vertices,
	/// are skipped and give false (btAssert on a bad index: ObjMesh never has one).
	bool addMesh(const ObjMesh& mesh);

private:
	struct Part
	{
		std::vector<btScalar> coordinates;  // x, y, z per vertex
		std::vector<int> indices;
	};
	std::vector<std::unique_ptr<Part>> m_parts;  // separate blocks: the subparts' pointers stay valid
};

/// A static triangle-mesh shape together with the mesh it reads (the shape does not own it).
struct StaticMeshShape
{
	/// Declared first so that it is destroyed after the shape.
	std::unique_ptr<OwnedTriangleIndexVertexArray> mesh;
	/// The shape, with its quantized BVH built.
	std::unique_ptr<btBvhTriangleMeshShape> shape;
};

/// One btBvhTriangleMeshShape over every mesh of model (one subpart each). A model that did not load, or
/// has no triangles, gives an empty result (both pointers null).
StaticMeshShape buildStaticMeshShape(const ObjModel& model);

/// The convex hull of mesh's vertices, reduced to the hull's corners (optimizeConvexHull). Null when the
/// mesh has fewer than 4 vertices or they are all in one plane (no volume to simulate).
std::unique_ptr<btConvexHullShape> buildConvexHullShape(const ObjMesh& mesh);

/// buildConvexHullShape for each mesh of model, in order; a null entry where a mesh has no volume.
std::vector<std::unique_ptr<btConvexHullShape>> buildConvexHullShapes(const ObjModel& model);
}  // namespace caliber

#endif  // CALIBER_EXTRAS_MESH_SHAPES_H
