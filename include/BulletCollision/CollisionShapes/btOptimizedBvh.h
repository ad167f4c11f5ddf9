// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_OPTIMIZED_BVH_H
#define BT_OPTIMIZED_BVH_H

#include "BulletCollision/BroadphaseCollision/btQuantizedBvh.h"

class btStridingMeshInterface;

/// A btQuantizedBvh over the triangles of a btStridingMeshInterface: one leaf per readable triangle
/// (scaled vertices), boxes refitted after the vertices move. Quantized trees need part ids below 2^10
/// and triangle indices below 2^21; larger meshes assert and are built unquantized in release builds.
ATTRIBUTE_ALIGNED16(class)
btOptimizedBvh : public btQuantizedBvh
{
public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// An empty BVH.
	btOptimizedBvh();
	/// BVHs are deleted through base pointers.
	virtual ~btOptimizedBvh();

	/// Builds the tree over the triangles of triangles. With useQuantizedAabbCompression the boxes are
	/// quantized within [bvhAabbMin, bvhAabbMax] grown by 1; the box is extended to the triangles if it
	/// does not contain them, so quantization stays conservative. A null mesh asserts and gives an empty
	/// tree.
	void build(btStridingMeshInterface * triangles, bool useQuantizedAabbCompression, const btVector3& bvhAabbMin,
	           const btVector3& bvhAabbMax);

	/// Recomputes every box from the current vertices (same triangles, moved vertices). Quantized trees
	/// requantize within [aabbMin, aabbMax] grown by 1 (extended to the triangles when needed).
	void refit(btStridingMeshInterface * triangles, const btVector3& aabbMin, const btVector3& aabbMax);

	/// Recomputes the boxes of the leaves whose box overlaps [aabbMin, aabbMax] (the region whose
	/// vertices moved, covering their old positions) and of their ancestors. If a moved triangle leaves
	/// the quantization box, the whole tree is refitted with a larger one.
	void refitPartial(btStridingMeshInterface * triangles, const btVector3& aabbMin, const btVector3& aabbMax);

	/// Recomputes the boxes of nodes [firstNode, endNode) from the mesh (leaves) and their children
	/// (internal nodes, which must lie after them), last to first. Quantized leaves are clamped to the
	/// quantization box. index is unused (Bullet's signature).
	void updateBvhNodes(btStridingMeshInterface * meshInterface, int firstNode, int endNode, int index);

	/// btQuantizedBvh::serialize(o_alignedDataBuffer, i_dataBufferSize, i_swapEndian).
	virtual bool serializeInPlace(void* o_alignedDataBuffer, unsigned i_dataBufferSize, bool i_swapEndian) const;
	/// As btQuantizedBvh::deSerializeInPlace, building a btOptimizedBvh in the block (refit and
	/// refitPartial then work on the block's arrays).
	static btOptimizedBvh* deSerializeInPlace(void* i_alignedDataBuffer, unsigned int i_dataBufferSize,
	                                          bool i_swapEndian);
};

#endif  // BT_OPTIMIZED_BVH_H
