// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_INTERNAL_EDGE_UTILITY_H
#define BT_INTERNAL_EDGE_UTILITY_H

/// Internal-edge smoothing: objects sliding over a triangle mesh or height field otherwise bump on the
/// edges shared by two triangles, because each triangle reports contacts with its own edges. Generate the
/// edge angles once, then correct each new contact from gContactAddedCallback. See
/// docs/meshes-heightfields-and-compounds.md ("Internal edges").

#include "BulletCollision/BroadphaseCollision/btQuantizedBvh.h"
#include "BulletCollision/CollisionShapes/btTriangleInfoMap.h"
#include "LinearMath/btScalar.h"

class btBvhTriangleMeshShape;
class btHeightfieldTerrainShape;
class btManifoldPoint;
struct btCollisionObjectWrapper;

/// Options of btAdjustInternalEdgeContacts (bit flags).
enum btInternalEdgeAdjustFlags
{
	/// The mesh's outside is the back of its triangles (clockwise winding): contacts are corrected there.
	BT_TRIANGLE_CONVEX_BACKFACE_MODE = 1,
	/// Also correct contacts on the other face at edges that are planar or concave seen from the usual face.
	BT_TRIANGLE_CONCAVE_DOUBLE_SIDED = 2,
	/// Also correct contacts on the other face at edges that are convex seen from the usual face.
	BT_TRIANGLE_CONVEX_DOUBLE_SIDED = 4
};

/// Fills triangleInfoMap (cleared first) with the angle of every edge that trimeshShape's triangles
/// share, and attaches the map to the shape (not owned). Null arguments assert and do nothing.
void btGenerateInternalEdgeInfo(btBvhTriangleMeshShape* trimeshShape, btTriangleInfoMap* triangleInfoMap);

/// The same for a height field, keyed by btInternalEdgeHeightfieldKey.
void btGenerateInternalEdgeInfo(btHeightfieldTerrainShape* trimeshShape, btTriangleInfoMap* triangleInfoMap);

/// Corrects a new contact on triangle (partId0, index0) of the mesh seen through trimeshColObj0Wrap (the
/// wrapper gContactAddedCallback passes for the mesh side, whose shape is a btTriangleShape): a normal that
/// leans over an internal edge or vertex into the region the neighbouring triangle covers is turned back to
/// the face normal (or the nearest normal of a convex edge), with the point and distance made consistent.
/// The mesh may be either body of cp. Without a triangle info map on the mesh the contact is left as is.
void btAdjustInternalEdgeContacts(btManifoldPoint& cp, const btCollisionObjectWrapper* trimeshColObj0Wrap,
                                  const btCollisionObjectWrapper* otherColObj1Wrap, int partId0, int index0,
                                  int normalAdjustFlags = 0);

/// Key of triangle (partId, triangleIndex) of a btBvhTriangleMeshShape in its btTriangleInfoMap, as in
/// Bullet: partId in the top MAX_NUM_PARTS_IN_BITS bits, the index below (the layout of the BVH leaves).
inline int btInternalEdgeMeshKey(int partId, int triangleIndex)
{
	const unsigned int indexBits = 31u - MAX_NUM_PARTS_IN_BITS;
	const unsigned int key = (static_cast<unsigned int>(partId) << indexBits) |
	                         (static_cast<unsigned int>(triangleIndex) & ((1u << indexBits) - 1u));
	return static_cast<int>(key & 0x7fffffffu);
}

/// Key of a height-field triangle (partId 2 * x + half, triangleIndex y) in its btTriangleInfoMap: the bits
/// of partId and triangleIndex interleaved, unique for grids up to 32768 x 32768 cells whatever their width.
inline int btInternalEdgeHeightfieldKey(int partId, int triangleIndex)
{
	unsigned int key = 0;
	for (unsigned int bit = 0; bit < 16u; ++bit)
	{
		key |= ((static_cast<unsigned int>(partId) >> bit) & 1u) << (2u * bit);
		key |= ((static_cast<unsigned int>(triangleIndex) >> bit) & 1u) << (2u * bit + 1u);
	}
	return static_cast<int>(key & 0x7fffffffu);
}

#endif  // BT_INTERNAL_EDGE_UTILITY_H
