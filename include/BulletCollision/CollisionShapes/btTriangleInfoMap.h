// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef _BT_TRIANGLE_INFO_MAP_H
#define _BT_TRIANGLE_INFO_MAP_H

#include "LinearMath/btHashMap.h"
#include "LinearMath/btScalar.h"

// Flag bits of btTriangleInfo::m_flags, one per triangle edge (V0V1, V1V2, V2V0).

/// The edge V0-V1 joins its neighbour convexly.
#define TRI_INFO_V0V1_CONVEX 1
/// The edge V1-V2 joins its neighbour convexly.
#define TRI_INFO_V1V2_CONVEX 2
/// The edge V2-V0 joins its neighbour convexly.
#define TRI_INFO_V2V0_CONVEX 4

/// The neighbour across V0-V1 is wound opposite to this triangle (its normal must be negated).
#define TRI_INFO_V0V1_SWAP_NORMALB 8
/// The neighbour across V1-V2 is wound opposite to this triangle (its normal must be negated).
#define TRI_INFO_V1V2_SWAP_NORMALB 16
/// The neighbour across V2-V0 is wound opposite to this triangle (its normal must be negated).
#define TRI_INFO_V2V0_SWAP_NORMALB 32

/// Internal-edge information of one mesh triangle: for each edge, the signed angle to the neighbouring
/// triangle (SIMD_2_PI when there is no neighbour) and the TRI_INFO_* flags.
struct btTriangleInfo
{
	/// No neighbour information: every angle SIMD_2_PI, no flags.
	btTriangleInfo() : m_flags(0), m_edgeV0V1Angle(SIMD_2_PI), m_edgeV1V2Angle(SIMD_2_PI), m_edgeV2V0Angle(SIMD_2_PI) {}

	/// TRI_INFO_* bits.
	int m_flags;
	/// Angle between this triangle and its neighbour across V0-V1 (SIMD_2_PI: no neighbour).
	btScalar m_edgeV0V1Angle;
	/// Angle between this triangle and its neighbour across V1-V2 (SIMD_2_PI: no neighbour).
	btScalar m_edgeV1V2Angle;
	/// Angle between this triangle and its neighbour across V2-V0 (SIMD_2_PI: no neighbour).
	btScalar m_edgeV2V0Angle;
};

/// The map from a triangle's hash key (part and triangle index) to its btTriangleInfo.
typedef btHashMap<btHashInt, btTriangleInfo> btInternalTriangleInfoMap;

/// Internal-edge information of a whole mesh, with the tolerances used when it is generated and applied.
struct btTriangleInfoMap : public btInternalTriangleInfoMap
{
	/// Dot-product tolerance deciding whether an edge or contact normal counts as convex.
	btScalar m_convexEpsilon;
	/// Tolerance under which two neighbouring triangles count as coplanar (zero edge angle).
	btScalar m_planarEpsilon;
	/// Squared distance under which two vertices count as the same vertex when finding neighbours.
	btScalar m_equalVertexThreshold;
	/// Distance under which a contact point counts as lying on a triangle edge.
	btScalar m_edgeDistanceThreshold;
	/// Edges whose neighbours meet at a larger angle than this are left alone.
	btScalar m_maxEdgeAngleThreshold;
	/// Squared cross-product length under which a triangle counts as degenerate (zero area).
	btScalar m_zeroAreaThreshold;

	/// An empty map with Bullet's default tolerances.
	btTriangleInfoMap()
	    : m_convexEpsilon(btScalar(0)),
	      m_planarEpsilon(btScalar(0.0001)),
	      m_equalVertexThreshold(btScalar(0.0001) * btScalar(0.0001)),
	      m_edgeDistanceThreshold(btScalar(0.1)),
	      m_maxEdgeAngleThreshold(SIMD_2_PI),
	      m_zeroAreaThreshold(btScalar(0.0001) * btScalar(0.0001))
	{
	}

	/// Maps may be deleted through base pointers of derived types.
	virtual ~btTriangleInfoMap() {}

	/// Bytes of the struct serialize() writes (btTriangleInfoMapData).
	virtual int calculateSerializeBufferSize() const;
	/// Writes the map's struct into dataBuffer and its arrays (hash table, links, values, keys) as
	/// chunks of their own; returns the struct's name.
	virtual const char* serialize(void* dataBuffer, class btSerializer* serializer) const;
	/// Replaces the map's entries and tolerances by those of data. The entries are inserted anew from
	/// the key and value arrays (the stored hash table and links are not trusted); counts that disagree,
	/// missing arrays or non-finite numbers are reported through btReportWarning and leave an empty map.
	void deSerialize(struct btTriangleInfoMapData & data);
};

// clang-format off
/// File layout of btTriangleInfoData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btTriangleInfoData
{
	int m_flags;
	float m_edgeV0V1Angle;
	float m_edgeV1V2Angle;
	float m_edgeV2V0Angle;
};

/// File layout of btTriangleInfoMapData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btTriangleInfoMapData
{
	int* m_hashTablePtr;
	int* m_nextPtr;
	btTriangleInfoData* m_valueArrayPtr;
	int* m_keyArrayPtr;
	float m_convexEpsilon;
	float m_planarEpsilon;
	float m_equalVertexThreshold;
	float m_edgeDistanceThreshold;
	float m_zeroAreaThreshold;
	int m_nextSize;
	int m_hashTableSize;
	int m_numValues;
	int m_numKeys;
	char m_padding[4];
};

// clang-format on

#endif  // _BT_TRIANGLE_INFO_MAP_H
