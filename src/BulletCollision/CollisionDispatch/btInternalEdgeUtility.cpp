// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btInternalEdgeUtility.h"

#include <cmath>
#include <cstring>

#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h"
#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h"
#include "BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "BulletCollision/CollisionShapes/btTriangleCallback.h"
#include "BulletCollision/CollisionShapes/btTriangleShape.h"
#include "BulletCollision/NarrowPhaseCollision/btManifoldPoint.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btMinMax.h"

namespace
{
// ---------------------------------------------------------------------------------------------------------
// Generation
// ---------------------------------------------------------------------------------------------------------

// Gathers every triangle of a concave shape (three vertices and the info-map key of each).
class TriangleGatherer : public btTriangleCallback
{
public:
	explicit TriangleGatherer(bool heightfieldKeys) : m_heightfieldKeys(heightfieldKeys) {}

	void processTriangle(btVector3* triangle, int partId, int triangleIndex) override
	{
		m_vertices.push_back(triangle[0]);
		m_vertices.push_back(triangle[1]);
		m_vertices.push_back(triangle[2]);
		m_keys.push_back(m_heightfieldKeys ? btInternalEdgeHeightfieldKey(partId, triangleIndex)
		                                   : btInternalEdgeMeshKey(partId, triangleIndex));
	}

	btAlignedObjectArray<btVector3> m_vertices;
	btAlignedObjectArray<int> m_keys;

private:
	bool m_heightfieldKeys;
};

// Cells along each axis are packed in 21 bits of a 64-bit key; the cell size is chosen so that the mesh spans
// at most 2^20 cells per axis.
const int kCellBits = 21;
const btScalar kMaxCellsPerAxis = btScalar(1 << 20);

unsigned long long packCell(long long cx, long long cy, long long cz)
{
	const unsigned long long mask = (1ull << kCellBits) - 1ull;
	return (static_cast<unsigned long long>(cx) & mask) | ((static_cast<unsigned long long>(cy) & mask) << kCellBits) |
	       ((static_cast<unsigned long long>(cz) & mask) << (2 * kCellBits));
}

// Welds vertices closer than the map's tolerance: a spatial hash with cells at least as large as the tolerance,
// so that a vertex's twin lies in one of the 27 cells around it. Open addressing, one chain of welded
// vertices per occupied cell; linear in the number of vertices.
class VertexWelder
{
public:
	VertexWelder(const btAlignedObjectArray<btVector3>& vertices, btScalar equalDistance2)
	    : m_equalDistance2(btMax(equalDistance2, btScalar(0)))
	{
		m_boxMin.setValue(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
		btVector3 boxMax = -m_boxMin;
		bool any = false;
		for (int i = 0; i < vertices.size(); ++i)
		{
			// Non-finite vertices belong to skipped triangles and are never welded.
			if (!caliber::isFinite(vertices[i])) continue;
			m_boxMin.setMin(vertices[i]);
			boxMax.setMax(vertices[i]);
			any = true;
		}
		btScalar extent = btScalar(0);
		if (any)
			for (int axis = 0; axis < 3; ++axis) extent = btMax(extent, boxMax[axis] - m_boxMin[axis]);
		else
			m_boxMin.setValue(0, 0, 0);
		m_cellSize = btMax(btSqrt(m_equalDistance2), extent / kMaxCellsPerAxis);
		if (!(m_cellSize > btScalar(0)) || !btIsFinite(m_cellSize)) m_cellSize = btScalar(1);

		int capacity = 16;
		while (capacity < 2 * vertices.size()) capacity *= 2;
		m_slotKeys.resize(capacity);
		m_slotHeads.resize(capacity);
		for (int s = 0; s < capacity; ++s) m_slotHeads[s] = -1;
	}

	// The id of the welded vertex v belongs to (a new id when no earlier vertex is close enough).
	int weld(const btVector3& v)
	{
		long long cell[3];
		for (int axis = 0; axis < 3; ++axis)
		{
			// Within [0, 2^20] for every vertex of the box; clamped so that the conversion is always defined
			// (a mesh spanning close to the float range overflows the extent).
			btScalar q = std::floor((v[axis] - m_boxMin[axis]) / m_cellSize);
			if (!(q >= btScalar(0))) q = btScalar(0);
			if (q > kMaxCellsPerAxis) q = kMaxCellsPerAxis;
			cell[axis] = static_cast<long long>(q);
		}
		for (long long dz = -1; dz <= 1; ++dz)
			for (long long dy = -1; dy <= 1; ++dy)
				for (long long dx = -1; dx <= 1; ++dx)
				{
					const int slot = findSlot(packCell(cell[0] + dx, cell[1] + dy, cell[2] + dz));
					for (int id = m_slotHeads[slot]; id >= 0; id = m_next[id])
						if ((m_welded[id] - v).length2() <= m_equalDistance2) return id;
				}
		const int slot = findSlot(packCell(cell[0], cell[1], cell[2]));
		const int id = m_welded.size();
		m_welded.push_back(v);
		m_next.push_back(m_slotHeads[slot]);
		m_slotKeys[slot] = packCell(cell[0], cell[1], cell[2]);
		m_slotHeads[slot] = id;
		return id;
	}

private:
	// The slot holding key, or the empty slot where it would go (the table is never more than half full).
	int findSlot(unsigned long long key) const
	{
		const unsigned long long mixed = key * 0x9E3779B97F4A7C15ull;
		const int mask = m_slotKeys.size() - 1;
		int slot = static_cast<int>(mixed >> 40) & mask;
		while (m_slotHeads[slot] >= 0 && m_slotKeys[slot] != key) slot = (slot + 1) & mask;
		return slot;
	}

	btScalar m_equalDistance2;
	btScalar m_cellSize;
	btVector3 m_boxMin;
	btAlignedObjectArray<unsigned long long> m_slotKeys;
	btAlignedObjectArray<int> m_slotHeads;
	btAlignedObjectArray<btVector3> m_welded;
	btAlignedObjectArray<int> m_next;
};

// One triangle edge, named by its welded end points (smaller id first) so that shared edges sort together.
struct HalfEdge
{
	unsigned long long m_key;
	int m_triangle;
	int m_edge;
};

struct HalfEdgeLess
{
	bool operator()(const HalfEdge& a, const HalfEdge& b) const
	{
		if (a.m_key != b.m_key) return a.m_key < b.m_key;
		if (a.m_triangle != b.m_triangle) return a.m_triangle < b.m_triangle;
		return a.m_edge < b.m_edge;
	}
};

btScalar& edgeAngle(btTriangleInfo& info, int edge)
{
	if (edge == 0) return info.m_edgeV0V1Angle;
	if (edge == 1) return info.m_edgeV1V2Angle;
	return info.m_edgeV2V0Angle;
}

btScalar edgeAngle(const btTriangleInfo& info, int edge)
{
	if (edge == 0) return info.m_edgeV0V1Angle;
	if (edge == 1) return info.m_edgeV1V2Angle;
	return info.m_edgeV2V0Angle;
}

// Records in info the angle of edge `edge` of a triangle with unit normal normal, whose neighbour has unit
// normal neighbourNormal (already negated when the two are wound opposite ways).
void recordEdge(btTriangleInfo& info, int edge, const btVector3& edgeStart, const btVector3& edgeEnd,
                const btVector3& normal, const btVector3& neighbourNormal, bool swapped, const btTriangleInfoMap& map)
{
	const btVector3 outward = (edgeEnd - edgeStart).normalized().cross(normal);
	const btScalar towardsOutside = neighbourNormal.dot(outward);
	btScalar angle = btAtan2(towardsOutside, neighbourNormal.dot(normal));
	if (btFabs(angle) < map.m_planarEpsilon) angle = btScalar(0);
	edgeAngle(info, edge) = angle;
	if (angle != btScalar(0) && towardsOutside > map.m_convexEpsilon) info.m_flags |= (TRI_INFO_V0V1_CONVEX << edge);
	if (swapped) info.m_flags |= (TRI_INFO_V0V1_SWAP_NORMALB << edge);
}

void generateFromTriangles(const TriangleGatherer& gathered, btTriangleInfoMap& map)
{
	const int numTriangles = gathered.m_keys.size();
	btAlignedObjectArray<btVector3> normals;
	normals.resize(numTriangles);
	btAlignedObjectArray<int> welded;
	welded.resize(3 * numTriangles);
	btAlignedObjectArray<bool> usable;
	usable.resize(numTriangles);

	VertexWelder welder(gathered.m_vertices, map.m_equalVertexThreshold);
	for (int t = 0; t < numTriangles; ++t)
	{
		const btVector3* v = &gathered.m_vertices[3 * t];
		const btVector3 cross = (v[1] - v[0]).cross(v[2] - v[0]);
		const btScalar area2 = cross.length2();
		// Zero-area and non-finite triangles have no normal: they get no entry and are nobody's neighbour.
		usable[t] = caliber::isFinite(v[0]) && caliber::isFinite(v[1]) && caliber::isFinite(v[2]) &&
		            btIsFinite(area2) && area2 > map.m_zeroAreaThreshold && area2 > btScalar(0);
		normals[t] = usable[t] ? cross / btSqrt(area2) : btVector3(0, 0, 0);
		for (int k = 0; k < 3; ++k) welded[3 * t + k] = usable[t] ? welder.weld(v[k]) : -1;
		// Welding may collapse a thin triangle to a segment; such a triangle has no well-defined edges either.
		if (usable[t] && (welded[3 * t] == welded[3 * t + 1] || welded[3 * t + 1] == welded[3 * t + 2] ||
		                  welded[3 * t + 2] == welded[3 * t]))
			usable[t] = false;
		if (!usable[t]) continue;
		// Two triangles with the same key (a part or index beyond the key's bits) cannot both be described.
		if (map.find(btHashInt(gathered.m_keys[t])))
		{
			btAssert(!"btGenerateInternalEdgeInfo: two triangles share an info-map key");
			usable[t] = false;
			continue;
		}
		map.insert(btHashInt(gathered.m_keys[t]), btTriangleInfo());
	}

	btAlignedObjectArray<HalfEdge> halfEdges;
	halfEdges.reserve(3 * numTriangles);
	for (int t = 0; t < numTriangles; ++t)
	{
		if (!usable[t]) continue;
		for (int k = 0; k < 3; ++k)
		{
			const unsigned long long a = static_cast<unsigned int>(welded[3 * t + k]);
			const unsigned long long b = static_cast<unsigned int>(welded[3 * t + (k + 1) % 3]);
			HalfEdge edge;
			edge.m_key = a < b ? ((a << 32) | b) : ((b << 32) | a);
			edge.m_triangle = t;
			edge.m_edge = k;
			halfEdges.push_back(edge);
		}
	}
	halfEdges.quickSort(HalfEdgeLess());

	for (int first = 0; first < halfEdges.size();)
	{
		int end = first + 1;
		while (end < halfEdges.size() && halfEdges[end].m_key == halfEdges[first].m_key) ++end;
		// Exactly two triangles: a manifold edge. Border edges (one) keep "no neighbour"; non-manifold edges
		// (three or more) too, since no single neighbour bounds the contact normals there.
		if (end - first == 2)
		{
			const HalfEdge& ea = halfEdges[first];
			const HalfEdge& eb = halfEdges[first + 1];
			const int ta = ea.m_triangle, tb = eb.m_triangle;
			// Consistently wound neighbours run along the shared edge in opposite directions.
			const bool swapped = welded[3 * ta + ea.m_edge] == welded[3 * tb + eb.m_edge];
			const btVector3 normalA = normals[ta];
			const btVector3 normalB = swapped ? -normals[tb] : normals[tb];
			const btVector3* va = &gathered.m_vertices[3 * ta];
			const btVector3* vb = &gathered.m_vertices[3 * tb];
			btTriangleInfo* infoA = map.find(btHashInt(gathered.m_keys[ta]));
			btTriangleInfo* infoB = map.find(btHashInt(gathered.m_keys[tb]));
			if (infoA && infoB)
			{
				recordEdge(*infoA, ea.m_edge, va[ea.m_edge], va[(ea.m_edge + 1) % 3], normalA, normalB, swapped, map);
				recordEdge(*infoB, eb.m_edge, vb[eb.m_edge], vb[(eb.m_edge + 1) % 3], normals[tb],
				           swapped ? -normalA : normalA, swapped, map);
			}
		}
		first = end;
	}
}

void gatherAll(const btConcaveShape& shape, TriangleGatherer& gatherer)
{
	btVector3 aabbMin, aabbMax;
	shape.getAabb(btTransform::getIdentity(), aabbMin, aabbMax);
	if (!caliber::isFinite(aabbMin) || !caliber::isFinite(aabbMax)) return;
	// A little slack so that triangles lying on the box faces are reported whatever the rounding.
	const btVector3 slack = (aabbMax - aabbMin) * btScalar(0.01) + btVector3(1, 1, 1);
	shape.processAllTriangles(&gatherer, aabbMin - slack, aabbMax + slack);
}

// ---------------------------------------------------------------------------------------------------------
// Adjustment
// ---------------------------------------------------------------------------------------------------------

// The info map of the mesh a triangle wrapper belongs to, and whether it is keyed as a height field.
const btTriangleInfoMap* findInfoMap(const btCollisionObjectWrapper* triangleWrap, bool& heightfieldKeys)
{
	const btCollisionShape* candidates[2] = {
	    triangleWrap->m_parent ? triangleWrap->m_parent->getCollisionShape() : 0,
	    triangleWrap->getCollisionObject() ? triangleWrap->getCollisionObject()->getCollisionShape() : 0};
	for (int c = 0; c < 2; ++c)
	{
		const btCollisionShape* shape = candidates[c];
		if (!shape) continue;
		heightfieldKeys = false;
		switch (shape->getShapeType())
		{
			case TRIANGLE_MESH_SHAPE_PROXYTYPE:
				// btTriangleMeshShape shares the type; only the BVH mesh carries a map.
				if (strcmp(shape->getName(), "BVHTRIANGLEMESH") == 0)
					return static_cast<const btBvhTriangleMeshShape*>(shape)->getTriangleInfoMap();
				break;
			case MULTIMATERIAL_TRIANGLE_MESH_PROXYTYPE:
				// btMultimaterialTriangleMeshShape, a btBvhTriangleMeshShape.
				return static_cast<const btBvhTriangleMeshShape*>(shape)->getTriangleInfoMap();
			case SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE:
			{
				const btBvhTriangleMeshShape* child =
				    static_cast<const btScaledBvhTriangleMeshShape*>(shape)->getChildShape();
				return child ? child->getTriangleInfoMap() : 0;
			}
			case TERRAIN_SHAPE_PROXYTYPE:
				heightfieldKeys = true;
				return static_cast<const btHeightfieldTerrainShape*>(shape)->getTriangleInfoMap();
			default:
				break;
		}
	}
	return 0;
}

// Squared distance from p to segment [a, b].
btScalar segmentDistance2(const btVector3& p, const btVector3& a, const btVector3& b)
{
	const btVector3 ab = b - a;
	const btScalar len2 = ab.length2();
	btScalar t = len2 > btScalar(0) ? (p - a).dot(ab) / len2 : btScalar(0);
	t = btClamped(t, btScalar(0), btScalar(1));
	return (a + ab * t - p).length2();
}

// Squared distance from p to the triangle v (unit normal normal).
btScalar triangleDistance2(const btVector3& p, const btVector3* v, const btVector3& normal)
{
	bool inside = true;
	for (int k = 0; k < 3; ++k)
		if ((v[(k + 1) % 3] - v[k]).cross(p - v[k]).dot(normal) < btScalar(0)) inside = false;
	if (inside)
	{
		const btScalar h = (p - v[0]).dot(normal);
		return h * h;
	}
	btScalar best = segmentDistance2(p, v[0], v[1]);
	best = btMin(best, segmentDistance2(p, v[1], v[2]));
	return btMin(best, segmentDistance2(p, v[2], v[0]));
}

// Which body of cp the mesh is (0: A, 1: B, -1: cannot tell), from the stored local points: each body's
// transform maps its own local point onto its world point. Both objects at the same pose cannot be told apart.
int meshSideFromLocalPoints(const btManifoldPoint& cp, const btCollisionObject* mesh, const btCollisionObject* other)
{
	if (!mesh || !other) return -1;
	const btTransform& meshTransform = mesh->getWorldTransform();
	const btTransform& otherTransform = other->getWorldTransform();
	const btScalar meshIsA = (meshTransform(cp.m_localPointA) - cp.m_positionWorldOnA).length2() +
	                         (otherTransform(cp.m_localPointB) - cp.m_positionWorldOnB).length2();
	const btScalar meshIsB = (meshTransform(cp.m_localPointB) - cp.m_positionWorldOnB).length2() +
	                         (otherTransform(cp.m_localPointA) - cp.m_positionWorldOnA).length2();
	if (!btIsFinite(meshIsA) || !btIsFinite(meshIsB)) return -1;
	// The right assignment reproduces the points up to rounding; the wrong one is off by the bodies' offset.
	const btScalar scale = btScalar(1) + cp.m_positionWorldOnA.length2() + cp.m_positionWorldOnB.length2();
	const btScalar relative = SIMD_EPSILON * btScalar(256);
	const btScalar noise = scale * relative * relative;
	if (meshIsA <= noise && meshIsB > btScalar(4) * noise) return 0;
	if (meshIsB <= noise && meshIsA > btScalar(4) * noise) return 1;
	return -1;
}

// One edge of the contact triangle as the clamp sees it.
struct EdgeConstraint
{
	bool m_active;      // the edge has a neighbour, is near the contact, and is handled on this side
	btVector3 m_along;  // unit edge direction
	btVector3 m_out;    // unit in-plane direction away from the triangle
	btScalar m_upper;   // largest allowed tilt from the face towards m_out (0 unless convex from this side)
};

// Tilts normal (unit, local) back into [.., upper] around one edge; true when it changed.
bool clampAroundEdge(btVector3& normal, const btVector3& face, const EdgeConstraint& edge)
{
	const btScalar along = normal.dot(edge.m_along);
	const btScalar up = normal.dot(face);
	const btScalar out = normal.dot(edge.m_out);
	const btScalar tilt = btAtan2(out, up);
	// A tilt within float noise of the limit is not a bump; leaving it avoids rewriting resting contacts.
	const btScalar kTiltSlack = btScalar(1e-5);
	if (tilt <= edge.m_upper + kTiltSlack) return false;
	const btScalar radial = btSqrt(up * up + out * out);
	btVector3 clamped = edge.m_along * along + (face * btCos(edge.m_upper) + edge.m_out * btSin(edge.m_upper)) * radial;
	const btScalar len2 = clamped.length2();
	if (!(len2 > SIMD_EPSILON)) return false;
	normal = clamped / btSqrt(len2);
	return true;
}
}  // namespace

void btGenerateInternalEdgeInfo(btBvhTriangleMeshShape* trimeshShape, btTriangleInfoMap* triangleInfoMap)
{
	btAssert(trimeshShape && triangleInfoMap && "btGenerateInternalEdgeInfo: null shape or map");
	if (!trimeshShape || !triangleInfoMap) return;
	triangleInfoMap->clear();
	TriangleGatherer gatherer(false);
	gatherAll(*trimeshShape, gatherer);
	generateFromTriangles(gatherer, *triangleInfoMap);
	trimeshShape->setTriangleInfoMap(triangleInfoMap);
}

void btGenerateInternalEdgeInfo(btHeightfieldTerrainShape* trimeshShape, btTriangleInfoMap* triangleInfoMap)
{
	btAssert(trimeshShape && triangleInfoMap && "btGenerateInternalEdgeInfo: null shape or map");
	if (!trimeshShape || !triangleInfoMap) return;
	triangleInfoMap->clear();
	TriangleGatherer gatherer(true);
	gatherAll(*trimeshShape, gatherer);
	generateFromTriangles(gatherer, *triangleInfoMap);
	trimeshShape->setTriangleInfoMap(triangleInfoMap);
}

namespace
{
// Clamps the contact normal n (mesh frame) to what the triangle's neighbours allow; true when it changed.
// Near a vertex whose two edges are both flat or concave from this side, the only normal the neighbours
// leave is the face normal (when the contact leans outward over either edge); elsewhere each active edge
// clamps n around itself.
bool clampNormalToNeighbours(btVector3& n, const btVector3& face, const EdgeConstraint* edges,
                             const btVector3& meshPoint, const btVector3* v, btScalar nearDistance2)
{
	for (int k = 0; k < 3; ++k)
	{
		const EdgeConstraint& before = edges[(k + 2) % 3];
		const EdgeConstraint& after = edges[k];
		if (!before.m_active || !after.m_active || before.m_upper > btScalar(0) || after.m_upper > btScalar(0))
			continue;
		if ((meshPoint - v[k]).length2() > nearDistance2) continue;
		if (n.dot(before.m_out) > btScalar(0) || n.dot(after.m_out) > btScalar(0))
		{
			n = face;
			return true;
		}
	}
	bool changed = false;
	for (int k = 0; k < 3; ++k)
		if (edges[k].m_active && clampAroundEdge(n, face, edges[k])) changed = true;
	return changed;
}

// Writes the new normal n (mesh frame) into the point. The other body's point stays; the mesh point moves
// along the new normal so that point, normal and distance agree (it stays on the triangle's plane or edge
// line).
void writeAdjustedNormal(btManifoldPoint& cp, const btTransform& meshTransform, const btCollisionObject* meshObject,
                         bool meshIsA, const btVector3& n)
{
	const btVector3 outWorld = meshTransform.getBasis() * n;
	const btVector3 meshWorld = meshIsA ? cp.m_positionWorldOnA : cp.m_positionWorldOnB;
	const btVector3 otherWorld = meshIsA ? cp.m_positionWorldOnB : cp.m_positionWorldOnA;
	const btScalar distance = (otherWorld - meshWorld).dot(outWorld);
	const btVector3 newMeshWorld = otherWorld - outWorld * distance;
	cp.m_distance1 = distance;
	if (meshIsA)
	{
		cp.m_normalWorldOnB = -outWorld;
		cp.m_positionWorldOnA = newMeshWorld;
		if (meshObject) cp.m_localPointA = meshObject->getWorldTransform().invXform(newMeshWorld);
	}
	else
	{
		cp.m_normalWorldOnB = outWorld;
		cp.m_positionWorldOnB = newMeshWorld;
		if (meshObject) cp.m_localPointB = meshObject->getWorldTransform().invXform(newMeshWorld);
	}
	if (!(cp.m_contactPointFlags & BT_CONTACT_FLAG_LATERAL_FRICTION_INITIALIZED))
		btPlaneSpace1(cp.m_normalWorldOnB, cp.m_lateralFrictionDir1, cp.m_lateralFrictionDir2);
}
}  // namespace

void btAdjustInternalEdgeContacts(btManifoldPoint& cp, const btCollisionObjectWrapper* trimeshColObj0Wrap,
                                  const btCollisionObjectWrapper* otherColObj1Wrap, int partId0, int index0,
                                  int normalAdjustFlags)
{
	btAssert(trimeshColObj0Wrap && otherColObj1Wrap && "btAdjustInternalEdgeContacts: null wrapper");
	if (!trimeshColObj0Wrap || !otherColObj1Wrap) return;
	const btCollisionShape* shape = trimeshColObj0Wrap->getCollisionShape();
	if (!shape || shape->getShapeType() != TRIANGLE_SHAPE_PROXYTYPE) return;

	bool heightfieldKeys = false;
	const btTriangleInfoMap* map = findInfoMap(trimeshColObj0Wrap, heightfieldKeys);
	if (!map) return;
	const int key =
	    heightfieldKeys ? btInternalEdgeHeightfieldKey(partId0, index0) : btInternalEdgeMeshKey(partId0, index0);
	const btTriangleInfo* info = map->find(btHashInt(key));
	if (!info) return;

	const btTriangleShape* triangle = static_cast<const btTriangleShape*>(shape);
	const btVector3* v = triangle->m_vertices1;
	const btVector3 cross = (v[1] - v[0]).cross(v[2] - v[0]);
	const btScalar area2 = cross.length2();
	if (!btIsFinite(area2) || !(area2 > map->m_zeroAreaThreshold) || !(area2 > btScalar(0))) return;
	const btVector3 normal = cross / btSqrt(area2);

	const btTransform& meshTransform = trimeshColObj0Wrap->getWorldTransform();
	if (!caliber::isFinite(meshTransform) || !caliber::isFinite(cp.m_normalWorldOnB) ||
	    !caliber::isFinite(cp.m_positionWorldOnA) || !caliber::isFinite(cp.m_positionWorldOnB))
		return;

	const btCollisionObject* meshObject = trimeshColObj0Wrap->getCollisionObject();
	const btVector3 localA = meshTransform.invXform(cp.m_positionWorldOnA);
	const btVector3 localB = meshTransform.invXform(cp.m_positionWorldOnB);
	const int side = meshSideFromLocalPoints(cp, meshObject, otherColObj1Wrap->getCollisionObject());
	const bool meshIsA =
	    side >= 0 ? side == 0 : triangleDistance2(localA, v, normal) < triangleDistance2(localB, v, normal);
	const btVector3 meshPoint = meshIsA ? localA : localB;

	// The contact normal pointing out of the mesh, in the mesh frame.
	btVector3 n = meshTransform.getBasis().transpose() * (meshIsA ? -cp.m_normalWorldOnB : cp.m_normalWorldOnB);
	const btScalar nLength2 = n.length2();
	if (!(nLength2 > SIMD_EPSILON)) return;
	n /= btSqrt(nLength2);

	const btVector3 usualFace = (normalAdjustFlags & BT_TRIANGLE_CONVEX_BACKFACE_MODE) ? -normal : normal;
	// Edge angles are stored for the front face; seen from the back every angle changes sign.
	const btScalar usualSign = usualFace.dot(normal) > btScalar(0) ? btScalar(1) : btScalar(-1);
	const btScalar nearDistance2 = map->m_edgeDistanceThreshold * map->m_edgeDistanceThreshold;

	// The edges with a neighbour near the contact point.
	bool nearEdge[3];
	btScalar angles[3];
	btVector3 along[3], out[3];
	for (int k = 0; k < 3; ++k)
	{
		angles[k] = edgeAngle(*info, k);
		// Valid angles lie in [-pi, pi]; SIMD_2_PI marks an edge without a neighbour.
		nearEdge[k] = btFabs(angles[k]) <= SIMD_PI + btScalar(1e-3) &&
		              btFabs(angles[k]) <= map->m_maxEdgeAngleThreshold &&
		              segmentDistance2(meshPoint, v[k], v[(k + 1) % 3]) <= nearDistance2;
		along[k] = (v[(k + 1) % 3] - v[k]).normalized();
		out[k] = along[k].cross(normal);
	}

	// Which face the other body touches. Past a convex edge the usual side extends beyond the face's plane,
	// up to the neighbour's plane: a normal there leans over the edge, it does not come from behind.
	bool onUsualSide = n.dot(usualFace) >= btScalar(0);
	for (int k = 0; k < 3 && !onUsualSide; ++k)
	{
		const btScalar convexAngle = angles[k] * usualSign;
		if (!nearEdge[k] || !(convexAngle > btScalar(0))) continue;
		const btScalar tilt = btAtan2(n.dot(out[k]), n.dot(usualFace));
		if (tilt > SIMD_HALF_PI && tilt <= SIMD_HALF_PI + convexAngle) onUsualSide = true;
	}
	const btVector3 face = onUsualSide ? usualFace : -usualFace;
	const btScalar angleSign = face.dot(normal) > btScalar(0) ? btScalar(1) : btScalar(-1);

	EdgeConstraint edges[3];
	for (int k = 0; k < 3; ++k)
	{
		EdgeConstraint& edge = edges[k];
		edge.m_active = false;
		if (!nearEdge[k]) continue;
		if (!onUsualSide)
		{
			const bool convexFromUsualSide = angles[k] * usualSign > btScalar(0);
			const int needed = convexFromUsualSide ? BT_TRIANGLE_CONVEX_DOUBLE_SIDED : BT_TRIANGLE_CONCAVE_DOUBLE_SIDED;
			if (!(normalAdjustFlags & needed)) continue;
		}
		edge.m_along = along[k];
		edge.m_out = out[k];
		edge.m_upper = btMax(angles[k] * angleSign, btScalar(0));
		edge.m_active = true;
	}

	if (!clampNormalToNeighbours(n, face, edges, meshPoint, v, nearDistance2)) return;
	writeAdjustedNormal(cp, meshTransform, meshObject, meshIsA, n);
}
