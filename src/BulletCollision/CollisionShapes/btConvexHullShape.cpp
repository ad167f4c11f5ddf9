// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "LinearMath/btConvexHullComputer.h"

#include <cstring>

namespace
{
// Points this many distinct ones or more are not checked for duplicates any more: the check costs
// a scan of the distinct points per point added, and duplicates matter most in small hulls.
const int kDeduplicatedPointLimit = 128;
// Scalars per block of the support lanes: four x, four y, four z.
const int kBlockScalars = 12;

bool sameBits(btScalar a, btScalar b) { return std::memcmp(&a, &b, sizeof(btScalar)) == 0; }

// The index of the first of count points, stored as btConvexHullShape::m_supportLanes, with the largest
// dot product with direction, each rounded as btVector3::dot rounds it ((x dx + y dy) + z dz); NaN
// products are skipped. -1 when no product exceeds minus infinity (all NaN or -inf after overflow),
// where the caller asks maxDot.
SIMD_FORCE_INLINE int firstLargestDotLane(const btScalar* lanes, int count, const btVector3& direction)
{
	const int blocks = (count + 3) / 4;
#ifdef BT_USE_SSE
	const __m128 dx = _mm_set1_ps(direction.x());
	const __m128 dy = _mm_set1_ps(direction.y());
	const __m128 dz = _mm_set1_ps(direction.z());
	// Each lane keeps its best product and that product's first index; a NaN product compares false
	// and _mm_max_ps then keeps the lane's best (its second operand).
	__m128 laneBest = _mm_set1_ps(-SIMD_INFINITY);
	__m128i laneIndex = _mm_set1_epi32(-1);
	__m128i currentIndex = _mm_setr_epi32(0, 1, 2, 3);
	const __m128i four = _mm_set1_epi32(4);
	for (int b = 0; b < blocks; ++b, lanes += kBlockScalars)
	{
		const __m128 dots =
		    _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_load_ps(lanes), dx), _mm_mul_ps(_mm_load_ps(lanes + 4), dy)),
		               _mm_mul_ps(_mm_load_ps(lanes + 8), dz));
		const __m128i betterMask = _mm_castps_si128(_mm_cmpgt_ps(dots, laneBest));
		laneBest = _mm_max_ps(dots, laneBest);
		laneIndex = _mm_or_si128(_mm_and_si128(betterMask, currentIndex), _mm_andnot_si128(betterMask, laneIndex));
		currentIndex = _mm_add_epi32(currentIndex, four);
	}
	alignas(16) float values[4];
	alignas(16) int indices[4];
	_mm_store_ps(values, laneBest);
	_mm_store_si128(reinterpret_cast<__m128i*>(indices), laneIndex);
	int bestIndex = -1;
	float best = 0;
	for (int lane = 0; lane < 4; ++lane)
	{
		if (indices[lane] < 0) continue;
		if (bestIndex < 0 || values[lane] > best || (values[lane] == best && indices[lane] < bestIndex))
		{
			best = values[lane];
			bestIndex = indices[lane];
		}
	}
	return bestIndex;
#else
	int bestIndex = -1;
	btScalar best = -SIMD_INFINITY;
	for (int b = 0; b < blocks; ++b, lanes += kBlockScalars)
	{
		for (int lane = 0; lane < 4; ++lane)
		{
			const btScalar d =
			    (lanes[lane] * direction.x() + lanes[4 + lane] * direction.y()) + lanes[8 + lane] * direction.z();
			if (d > best)
			{
				best = d;
				bestIndex = 4 * b + lane;
			}
		}
	}
	return bestIndex;
#endif
}
}  // namespace

btConvexHullShape::btConvexHullShape(const btScalar* points, int numPoints, int stride)
    : m_supportCount(0), m_supportLanesValid(true)
{
	m_shapeType = CONVEX_HULL_SHAPE_PROXYTYPE;
	const bool usable = points != 0 && stride >= int(3 * sizeof(btScalar));
	btAssert(numPoints <= 0 || usable);
	if (usable && numPoints > 0)
	{
		m_unscaledPoints.reserve(numPoints);
		const unsigned char* bytes = reinterpret_cast<const unsigned char*>(points);
		for (int i = 0; i < numPoints; ++i)
		{
			const btScalar* p = reinterpret_cast<const btScalar*>(bytes + size_t(i) * size_t(stride));
			addPoint(btVector3(p[0], p[1], p[2]), false);
		}
	}
	recalcLocalAabb();
}

void btConvexHullShape::addPoint(const btVector3& point, bool recalculateLocalAabb)
{
	btAssert(caliber::isFinite(point) && "btConvexHullShape: non-finite point");
	if (caliber::isFinite(point))
	{
		m_unscaledPoints.push_back(point);
		m_unscaledPoints[m_unscaledPoints.size() - 1][3] = 0;
		if (m_supportLanesValid)
			appendSupportLane(point);
		else
			rebuildSupportLanes();
	}
	if (recalculateLocalAabb) recalcLocalAabb();
}

void btConvexHullShape::optimizeConvexHull()
{
	if (m_unscaledPoints.size() == 0) return;
	btConvexHullComputer hull;
	hull.compute(&m_unscaledPoints[0].x(), int(sizeof(btVector3)), m_unscaledPoints.size(), 0, 0);
	if (hull.vertices.size() == 0) return;
	m_unscaledPoints.resize(0);
	m_supportLanes.resize(0);
	m_supportCount = 0;
	m_supportLanesValid = true;
	for (int i = 0; i < hull.vertices.size(); ++i) addPoint(hull.vertices[i], false);
	recalcLocalAabb();
}

void btConvexHullShape::rebuildSupportLanes()
{
	m_supportLanes.resize(0);
	m_supportCount = 0;
	m_supportLanesValid = true;
	for (int i = 0; i < m_unscaledPoints.size(); ++i) appendSupportLane(m_unscaledPoints[i]);
}

void btConvexHullShape::appendSupportLane(const btVector3& point)
{
	const btScalar x = point.x(), y = point.y(), z = point.z();
	if (m_supportCount < kDeduplicatedPointLimit)
	{
		for (int i = 0; i < m_supportCount; ++i)
		{
			const btScalar* block = &m_supportLanes[(i / 4) * kBlockScalars];
			const int lane = i % 4;
			if (sameBits(block[lane], x) && sameBits(block[4 + lane], y) && sameBits(block[8 + lane], z)) return;
		}
	}
	const int lane = m_supportCount % 4;
	if (lane == 0)
	{
		// A new block, its unused lanes filled with the first point: the scan keeps the lowest index
		// among equal dot products, so a copy never wins over the original.
		const btScalar first[3] = {m_supportCount ? m_supportLanes[0] : x, m_supportCount ? m_supportLanes[4] : y,
		                           m_supportCount ? m_supportLanes[8] : z};
		for (int k = 0; k < kBlockScalars; ++k) m_supportLanes.push_back(first[k / 4]);
	}
	btScalar* block = &m_supportLanes[(m_supportCount / 4) * kBlockScalars];
	block[lane] = x;
	block[4 + lane] = y;
	block[8 + lane] = z;
	++m_supportCount;
}

btVector3 btConvexHullShape::localGetSupportingVertexWithoutMargin(const btVector3& vec) const
{
	if (m_unscaledPoints.size() == 0) return btVector3(0, 0, 0);
	// The support of S P along d is S times the support of P along S d (S diagonal).
	const btVector3 scaledDir = caliber::supportDirection(vec) * m_localScaling;
	// The distinct points give maxDot's answer over all of them bitwise: ties keep the first point, and
	// a later copy of a point never beats it.
	if (m_supportLanesValid && m_supportCount > 0)
	{
		const int index = firstLargestDotLane(&m_supportLanes[0], m_supportCount, scaledDir);
		if (index >= 0)
		{
			const btScalar* block = &m_supportLanes[(index / 4) * kBlockScalars];
			const int lane = index % 4;
			return btVector3(block[lane], block[4 + lane], block[8 + lane]) * m_localScaling;
		}
	}
	btScalar best;
	const long index = scaledDir.maxDot(&m_unscaledPoints[0], m_unscaledPoints.size(), best);
	if (index < 0) return btVector3(0, 0, 0);
	return m_unscaledPoints[int(index)] * m_localScaling;
}

void btConvexHullShape::batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors,
                                                                          btVector3* supportVerticesOut,
                                                                          int numVectors) const
{
	for (int j = 0; j < numVectors; ++j)
		supportVerticesOut[j] = btConvexHullShape::localGetSupportingVertexWithoutMargin(vectors[j]);
}

int btConvexHullShape::getNumVertices() const { return m_unscaledPoints.size(); }

int btConvexHullShape::getNumEdges() const { return m_unscaledPoints.size(); }

void btConvexHullShape::getEdge(int i, btVector3& pa, btVector3& pb) const
{
	const int n = m_unscaledPoints.size();
	btAssert(i >= 0 && i < n);
	if (i < 0 || i >= n)
	{
		pa.setValue(0, 0, 0);
		pb.setValue(0, 0, 0);
		return;
	}
	pa = getScaledPoint(i);
	pb = getScaledPoint((i + 1) % n);
}

void btConvexHullShape::getVertex(int i, btVector3& vtx) const { vtx = getScaledPoint(i); }

int btConvexHullShape::getNumPlanes() const { return 0; }

void btConvexHullShape::getPlane(btVector3& planeNormal, btVector3& planeSupport, int i) const
{
	(void)i;
	btAssert(false && "btConvexHullShape::getPlane: the hull stores no planes");
	planeNormal.setValue(0, 0, 0);
	planeSupport.setValue(0, 0, 0);
}

bool btConvexHullShape::isInside(const btVector3& pt, btScalar tolerance) const
{
	(void)pt;
	(void)tolerance;
	btAssert(false && "btConvexHullShape::isInside is not supported");
	return false;
}
