// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_BVH_TRIANGLE_MESH_SHAPE_H
#define BT_BVH_TRIANGLE_MESH_SHAPE_H

#include "BulletCollision/CollisionShapes/btOptimizedBvh.h"
#include "BulletCollision/CollisionShapes/btTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btStridingMeshInterface.h"
#include "BulletCollision/CollisionShapes/btTriangleInfoMap.h"

struct btTriangleInfoMap;

/// A static triangle mesh with a btOptimizedBvh over its triangles: box queries, ray casts and box casts
/// visit only the triangles whose (possibly quantized, always conservative) box they touch. Changing the
/// local scaling rebuilds the tree; moving vertices needs refitTree or partialRefitTree.
ATTRIBUTE_ALIGNED16(class)
btBvhTriangleMeshShape : public btTriangleMeshShape
{
	btOptimizedBvh* m_bvh;
	btTriangleInfoMap* m_triangleInfoMap;
	bool m_useQuantizedAabbCompression;
	bool m_ownsBvh;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// A shape over meshInterface (not owned); buildBvh builds the tree now (quantized within the
	/// mesh's AABB when useQuantizedAabbCompression), else call buildOptimizedBvh or setOptimizedBvh.
	btBvhTriangleMeshShape(btStridingMeshInterface * meshInterface, bool useQuantizedAabbCompression,
	                       bool buildBvh = true);

	/// As above, quantizing within [bvhAabbMin, bvhAabbMax] (extended to the mesh if it does not
	/// contain it).
	btBvhTriangleMeshShape(btStridingMeshInterface * meshInterface, bool useQuantizedAabbCompression,
	                       const btVector3& bvhAabbMin, const btVector3& bvhAabbMax, bool buildBvh = true);

	/// Deletes the tree if the shape owns it.
	virtual ~btBvhTriangleMeshShape();

	/// True when the shape deletes its tree.
	bool getOwnsBvh() const { return m_ownsBvh; }

	/// Reports every triangle whose box the segment raySource -> rayTarget (local space) touches; callers
	/// run the exact ray-triangle test. Without a tree: every triangle whose box overlaps the segment's box.
	void performRaycast(btTriangleCallback * callback, const btVector3& raySource, const btVector3& rayTarget);

	/// Reports every triangle whose box is touched by the box [boxMin, boxMax] (relative to the moving
	/// point) swept from boxSource to boxTarget. Without a tree: every triangle whose box overlaps the
	/// swept box's bounds.
	void performConvexcast(btTriangleCallback * callback, const btVector3& boxSource, const btVector3& boxTarget,
	                       const btVector3& boxMin, const btVector3& boxMax);

	/// Reports every triangle whose tree box overlaps [aabbMin, aabbMax] (brute force without a tree).
	void processAllTriangles(btTriangleCallback * callback, const btVector3& aabbMin, const btVector3& aabbMax)
	    const override;

	/// Refits the whole tree to the moved vertices (quantized within [aabbMin, aabbMax]) and recomputes
	/// the local AABB.
	void refitTree(const btVector3& aabbMin, const btVector3& aabbMax);

	/// Refits the part of the tree overlapping [aabbMin, aabbMax] (the region where vertices moved) and
	/// grows the local AABB to contain that region.
	void partialRefitTree(const btVector3& aabbMin, const btVector3& aabbMax);

	/// "BVHTRIANGLEMESH", as in Bullet.
	const char* getName() const override { return "BVHTRIANGLEMESH"; }

	/// Sets the mesh scaling and, when it changed, rebuilds the tree.
	void setLocalScaling(const btVector3& scaling) override;

	/// The tree (0 when not built).
	btOptimizedBvh* getOptimizedBvh() { return m_bvh; }

	/// Uses bvh (not owned; built for this mesh at scaling) instead of the shape's own tree (deleted if
	/// owned); the mesh scaling is set to scaling without rebuilding.
	void setOptimizedBvh(btOptimizedBvh * bvh, const btVector3& localScaling = btVector3(1, 1, 1));

	/// (Re)builds an owned tree over the current vertices and scaling.
	void buildOptimizedBvh();

	/// True when the tree boxes are quantized.
	bool usesQuantizedAabbCompression() const { return m_useQuantizedAabbCompression; }

	/// Stores a triangle info map (not owned) for internal-edge smoothing.
	void setTriangleInfoMap(btTriangleInfoMap * triangleInfoMap) { m_triangleInfoMap = triangleInfoMap; }
	/// The triangle info map (0 when none).
	const btTriangleInfoMap* getTriangleInfoMap() const { return m_triangleInfoMap; }
	/// The triangle info map (0 when none).
	btTriangleInfoMap* getTriangleInfoMap() { return m_triangleInfoMap; }

public:
	/// Bytes of the data struct serialize() writes.
	int calculateSerializeBufferSize() const override;
	/// Writes the shape's data struct into dataBuffer and returns the struct's name.
	const char* serialize(void* dataBuffer, btSerializer* serializer) const override;
	/// Writes the BVH alone as a chunk of its own (a file of precomputed trees; nothing without a tree).
	virtual void serializeSingleBvh(btSerializer * serializer) const;
	/// Writes the triangle info map alone as a chunk of its own (nothing without a map).
	virtual void serializeSingleTriangleInfoMap(btSerializer * serializer) const;
};

// clang-format off
/// File layout of btTriangleMeshShapeData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btTriangleMeshShapeData
{
	btCollisionShapeData m_collisionShapeData;
	btStridingMeshInterfaceData m_meshInterface;
	btQuantizedBvhFloatData* m_quantizedFloatBvh;
	btQuantizedBvhDoubleData* m_quantizedDoubleBvh;
	btTriangleInfoMapData* m_triangleInfoMap;
	float m_collisionMargin;
	char m_pad3[4];
};

// clang-format on

#endif  // BT_BVH_TRIANGLE_MESH_SHAPE_H
