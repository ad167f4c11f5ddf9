// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_BVH_TRIANGLE_MATERIAL_MESH_SHAPE_H
#define BT_BVH_TRIANGLE_MATERIAL_MESH_SHAPE_H

#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btMaterial.h"

class btTriangleIndexVertexMaterialArray;

/// A btBvhTriangleMeshShape whose triangles each carry a material (friction, restitution) looked up
/// from the mesh's btTriangleIndexVertexMaterialArray tables: typically read in a contact-added
/// callback or after a ray hit, with the part id and triangle index the contact or hit reports.
/// It collides, casts and builds its BVH exactly as btBvhTriangleMeshShape; its shape type is
/// MULTIMATERIAL_TRIANGLE_MESH_PROXYTYPE.
ATTRIBUTE_ALIGNED16(class)
btMultimaterialTriangleMeshShape : public btBvhTriangleMeshShape
{
public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// meshInterface must be a btTriangleIndexVertexMaterialArray (not owned); with any other
	/// interface the shape still collides but every material lookup asserts and gives null.
	btMultimaterialTriangleMeshShape(btStridingMeshInterface * meshInterface, bool useQuantizedAabbCompression,
	                                 bool buildBvh = true);

	/// As above, quantizing the BVH within [bvhAabbMin, bvhAabbMax].
	btMultimaterialTriangleMeshShape(btStridingMeshInterface * meshInterface, bool useQuantizedAabbCompression,
	                                 const btVector3& bvhAabbMin, const btVector3& bvhAabbMax, bool buildBvh = true);

	virtual ~btMultimaterialTriangleMeshShape();

	virtual const char* getName() const { return "MULTIMATERIALTRIANGLEMESH"; }

	/// The material of triangle triIndex of subpart partID: a pointer into the user's material table.
	/// Null (after an assert) when the mesh has no material tables, partID or triIndex is out of range,
	/// the index type is neither PHY_INTEGER nor PHY_SHORT, or the stored material index is out of range.
	const btMaterial* getMaterialProperties(int partID, int triIndex);

private:
	btTriangleIndexVertexMaterialArray* m_materialMesh;
};

#endif  // BT_BVH_TRIANGLE_MATERIAL_MESH_SHAPE_H
