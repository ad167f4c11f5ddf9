// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_BROADPHASE_PROXY_H
#define BT_BROADPHASE_PROXY_H

#include "LinearMath/btScalar.h"
#include "LinearMath/btVector3.h"
#include "LinearMath/btAlignedAllocator.h"

/// Shape type tags. The order and values are Bullet's: the ranges between the *_START_HERE / *_END_HERE
/// markers classify shapes (polyhedral, implicit convex, concave) and dispatch tables are indexed by them.
enum BroadphaseNativeTypes
{
	BOX_SHAPE_PROXYTYPE = 0,
	TRIANGLE_SHAPE_PROXYTYPE,
	TETRAHEDRAL_SHAPE_PROXYTYPE,
	CONVEX_TRIANGLEMESH_SHAPE_PROXYTYPE,
	CONVEX_HULL_SHAPE_PROXYTYPE,
	CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE,
	CUSTOM_POLYHEDRAL_SHAPE_TYPE,
	IMPLICIT_CONVEX_SHAPES_START_HERE,
	SPHERE_SHAPE_PROXYTYPE,
	MULTI_SPHERE_SHAPE_PROXYTYPE,
	CAPSULE_SHAPE_PROXYTYPE,
	CONE_SHAPE_PROXYTYPE,
	CONVEX_SHAPE_PROXYTYPE,
	CYLINDER_SHAPE_PROXYTYPE,
	UNIFORM_SCALING_SHAPE_PROXYTYPE,
	MINKOWSKI_SUM_SHAPE_PROXYTYPE,
	MINKOWSKI_DIFFERENCE_SHAPE_PROXYTYPE,
	BOX_2D_SHAPE_PROXYTYPE,
	CONVEX_2D_SHAPE_PROXYTYPE,
	CUSTOM_CONVEX_SHAPE_TYPE,
	CONCAVE_SHAPES_START_HERE,
	TRIANGLE_MESH_SHAPE_PROXYTYPE,
	SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE,
	FAST_CONCAVE_MESH_PROXYTYPE,
	TERRAIN_SHAPE_PROXYTYPE,
	GIMPACT_SHAPE_PROXYTYPE,
	MULTIMATERIAL_TRIANGLE_MESH_PROXYTYPE,
	EMPTY_SHAPE_PROXYTYPE,
	STATIC_PLANE_PROXYTYPE,
	CUSTOM_CONCAVE_SHAPE_TYPE,
	SDF_SHAPE_PROXYTYPE = CUSTOM_CONCAVE_SHAPE_TYPE,
	CONCAVE_SHAPES_END_HERE,
	COMPOUND_SHAPE_PROXYTYPE,
	SOFTBODY_SHAPE_PROXYTYPE,
	HFFLUID_SHAPE_PROXYTYPE,
	HFFLUID_BUOYANT_CONVEX_SHAPE_PROXYTYPE,
	INVALID_SHAPE_PROXYTYPE,
	MAX_BROADPHASE_COLLISION_TYPES
};

/// A broadphase's handle of one collision object: its world AABB, filter group and mask, and the object.
ATTRIBUTE_ALIGNED16(struct)
btBroadphaseProxy
{
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Bullet's predefined filter groups; users may define their own bits above these.
	enum CollisionFilterGroups
	{
		DefaultFilter = 1,
		StaticFilter = 2,
		KinematicFilter = 4,
		DebrisFilter = 8,
		SensorTrigger = 16,
		CharacterFilter = 32,
		AllFilter = -1
	};

	/// The owner of the proxy, usually a btCollisionObject.
	void* m_clientObject;
	/// The groups this proxy belongs to (bit mask).
	int m_collisionFilterGroup;
	/// The groups this proxy collides with (bit mask).
	int m_collisionFilterMask;
	/// A number unique among the proxies of one broadphase, used to order pairs deterministically.
	int m_uniqueId;
	/// Lower corner of the world AABB.
	btVector3 m_aabbMin;
	/// Upper corner of the world AABB.
	btVector3 m_aabbMax;

	/// The unique id.
	SIMD_FORCE_INLINE int getUid() const { return m_uniqueId; }

	/// An empty proxy (no client, filter group and mask 0, id 0, AABB at the origin).
	btBroadphaseProxy()
	    : m_clientObject(0),
	      m_collisionFilterGroup(0),
	      m_collisionFilterMask(0),
	      m_uniqueId(0),
	      m_aabbMin(btScalar(0), btScalar(0), btScalar(0)),
	      m_aabbMax(btScalar(0), btScalar(0), btScalar(0))
	{
	}

	/// A proxy for userPtr with the given AABB and filtering (id 0 until a broadphase assigns one).
	btBroadphaseProxy(const btVector3& aabbMin, const btVector3& aabbMax, void* userPtr, int collisionFilterGroup,
	                  int collisionFilterMask)
	    : m_clientObject(userPtr),
	      m_collisionFilterGroup(collisionFilterGroup),
	      m_collisionFilterMask(collisionFilterMask),
	      m_uniqueId(0),
	      m_aabbMin(aabbMin),
	      m_aabbMax(aabbMax)
	{
	}

	/// True for shapes described by vertices and faces (box, triangle, hulls, ...).
	static SIMD_FORCE_INLINE bool isPolyhedral(int proxyType) { return proxyType < IMPLICIT_CONVEX_SHAPES_START_HERE; }
	/// True for every convex shape type.
	static SIMD_FORCE_INLINE bool isConvex(int proxyType) { return proxyType < CONCAVE_SHAPES_START_HERE; }
	/// True for concave shapes that never move (everything concave except GImpact meshes).
	static SIMD_FORCE_INLINE bool isNonMoving(int proxyType)
	{
		return isConcave(proxyType) && proxyType != GIMPACT_SHAPE_PROXYTYPE;
	}
	/// True for the concave shape types (triangle meshes, terrain, plane, empty, custom concave).
	static SIMD_FORCE_INLINE bool isConcave(int proxyType)
	{
		return proxyType > CONCAVE_SHAPES_START_HERE && proxyType < CONCAVE_SHAPES_END_HERE;
	}
	/// True for the compound shape.
	static SIMD_FORCE_INLINE bool isCompound(int proxyType) { return proxyType == COMPOUND_SHAPE_PROXYTYPE; }
	/// True for the soft body shape.
	static SIMD_FORCE_INLINE bool isSoftBody(int proxyType) { return proxyType == SOFTBODY_SHAPE_PROXYTYPE; }
	/// True for shapes of unbounded extent (the static plane).
	static SIMD_FORCE_INLINE bool isInfinite(int proxyType) { return proxyType == STATIC_PLANE_PROXYTYPE; }
	/// True for the 2D convex shapes.
	static SIMD_FORCE_INLINE bool isConvex2d(int proxyType)
	{
		return proxyType == BOX_2D_SHAPE_PROXYTYPE || proxyType == CONVEX_2D_SHAPE_PROXYTYPE;
	}
};

class btCollisionAlgorithm;

/// Two overlapping proxies, and the narrowphase algorithm the dispatcher made for them (if any).
ATTRIBUTE_ALIGNED16(struct)
btBroadphasePair
{
	/// An empty pair.
	btBroadphasePair() : m_pProxy0(0), m_pProxy1(0), m_algorithm(0), m_internalInfo1(0) {}

	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// A pair of proxy0 and proxy1, stored with the lower unique id first so that (a, b) and (b, a) are
	/// the same pair.
	btBroadphasePair(btBroadphaseProxy & proxy0, btBroadphaseProxy & proxy1)
	{
		if (proxy0.m_uniqueId < proxy1.m_uniqueId)
		{
			m_pProxy0 = &proxy0;
			m_pProxy1 = &proxy1;
		}
		else
		{
			m_pProxy0 = &proxy1;
			m_pProxy1 = &proxy0;
		}
		m_algorithm = 0;
		m_internalInfo1 = 0;
	}

	/// The proxy with the lower unique id.
	btBroadphaseProxy* m_pProxy0;
	/// The proxy with the higher unique id.
	btBroadphaseProxy* m_pProxy1;
	/// The narrowphase algorithm for this pair, or null until the dispatcher creates one.
	mutable btCollisionAlgorithm* m_algorithm;
	/// Scratch space for the pair cache and its users.
	union
	{
		void* m_internalInfo1;
		int m_internalTmpValue;
	};
};

/// Orders pairs by (proxy0 id, proxy1 id, algorithm address), descending, so that duplicates are adjacent
/// after sorting and pairs that have an algorithm come first.
class btBroadphasePairSortPredicate
{
public:
	/// True when a sorts before b.
	bool operator()(const btBroadphasePair& a, const btBroadphasePair& b) const
	{
		const int uidA0 = a.m_pProxy0 ? a.m_pProxy0->m_uniqueId : -1;
		const int uidB0 = b.m_pProxy0 ? b.m_pProxy0->m_uniqueId : -1;
		const int uidA1 = a.m_pProxy1 ? a.m_pProxy1->m_uniqueId : -1;
		const int uidB1 = b.m_pProxy1 ? b.m_pProxy1->m_uniqueId : -1;
		if (uidA0 != uidB0) return uidA0 > uidB0;
		if (uidA1 != uidB1) return uidA1 > uidB1;
		return a.m_algorithm > b.m_algorithm;
	}
};

/// Two pairs are equal when they join the same two proxies (in stored order).
SIMD_FORCE_INLINE bool operator==(const btBroadphasePair& a, const btBroadphasePair& b)
{
	return (a.m_pProxy0 == b.m_pProxy0) && (a.m_pProxy1 == b.m_pProxy1);
}

#endif  // BT_BROADPHASE_PROXY_H
