// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"

#include "BulletCollision/NarrowPhaseCollision/ManifoldPrefetch.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifoldBuilds.h"
#include "LinearMath/btCpuFeatures.h"
#include "LinearMath/btMinMax.h"
#include "LinearMath/btSimdBatch.h"

btScalar gContactBreakingThreshold = btScalar(0.02);
ContactDestroyedCallback gContactDestroyedCallback = 0;
ContactProcessedCallback gContactProcessedCallback = 0;
ContactStartedCallback gContactStartedCallback = 0;
ContactEndedCallback gContactEndedCallback = 0;

namespace
{
bool isFinitePoint(const btManifoldPoint& pt)
{
	return caliber::isFinite(pt.m_localPointA) && caliber::isFinite(pt.m_localPointB) &&
	       caliber::isFinite(pt.m_positionWorldOnA) && caliber::isFinite(pt.m_positionWorldOnB) &&
	       caliber::isFinite(pt.m_normalWorldOnB) && btIsFinite(pt.m_distance1);
}

// Twice the area of a quadrilateral is the length of the cross product of its diagonals. Which pair
// of the four points forms the diagonals depends on their order, so all three ways of splitting the
// four points into two pairs are tried and the largest is kept; the square avoids a sqrt.
btScalar areaMeasure(const btVector3& p0, const btVector3& p1, const btVector3& p2, const btVector3& p3)
{
	const btScalar split01 = (p0 - p1).cross(p2 - p3).length2();
	const btScalar split02 = (p0 - p2).cross(p1 - p3).length2();
	const btScalar split03 = (p0 - p3).cross(p1 - p2).length2();
	return btMax(split01, btMax(split02, split03));
}

// A threshold must be a non-negative number; anything else asserts and becomes 0.
btScalar sanitizedBreakingThreshold(btScalar threshold)
{
	btAssert(threshold >= btScalar(0));
	return threshold >= btScalar(0) ? threshold : btScalar(0);
}

// refreshContactPoints' first pass: when both transforms are finite, every point's world positions, distance
// and age, and which points stay (bit i set when point i is within the breaking threshold along the normal
// and has not slid across it further than the threshold); -1 when a transform is not finite. Inlined into
// the two builds below.
SIMD_FORCE_INLINE int refreshWorldPoints(btManifoldPoint* points, int count, const btTransform& trA,
                                         const btTransform& trB, btScalar threshold)
{
	const bool finite = caliber::isFinite(trA) && caliber::isFinite(trB);
	btAssert(finite);
	if (!finite) return -1;

	// The bases turned into columns once for all points (the same bits as trA(p) and trB(p)).
	const caliber::ColumnTransform toWorldA(trA), toWorldB(trB);
	const btScalar threshold2 = threshold * threshold;
	int kept = 0;
	for (int i = 0; i < count; ++i)
	{
		btManifoldPoint& point = points[i];
		point.m_positionWorldOnA = toWorldA(point.m_localPointA);
		point.m_positionWorldOnB = toWorldB(point.m_localPointB);
		point.m_distance1 = (point.m_positionWorldOnA - point.m_positionWorldOnB).dot(point.m_normalWorldOnB);
		++point.m_lifeTime;
		const btVector3 projectedOnB = point.m_positionWorldOnA - point.m_normalWorldOnB * point.m_distance1;
		const btScalar drift2 = (point.m_positionWorldOnB - projectedOnB).length2();
		if (point.m_distance1 <= threshold && !(drift2 > threshold2)) kept |= 1 << i;
	}
	return kept;
}

// The first pass compiled a second time for AVX2 (VEX encoding, three operands: no register copy before
// each two-operand SSE operation), chosen at load. Only AVX2, never FMA: every operation rounds as in the
// baseline, in the same order, so the points get the same bits (see LinearMath/btCpuFeatures.h).
#if CALIBER_AVX2_BUILDS
__attribute__((target("avx2"))) int refreshWorldPointsAvx2(btManifoldPoint* points, int count, const btTransform& trA,
                                                            const btTransform& trB, btScalar threshold)
{
	return refreshWorldPoints(points, count, trA, trB, threshold);
}
const bool g_avx2Refresh = caliber::detectAvx2();
#endif

btScalar sanitizedProcessingThreshold(btScalar threshold)
{
	const bool isNumber = threshold == threshold;
	btAssert(isNumber);
	return isNumber ? threshold : btScalar(0);
}
}  // namespace

btPersistentManifold::btPersistentManifold()
    : btTypedObject(BT_PERSISTENT_MANIFOLD_TYPE),
      m_body0(0),
      m_body1(0),
      m_cachedPoints(0),
      m_contactBreakingThreshold(gContactBreakingThreshold),
      m_contactProcessingThreshold(btScalar(BT_LARGE_FLOAT)),
      m_companionIdA(0),
      m_companionIdB(0),
      m_index1a(0)
{
	// caliber::prefetchManifoldHeader and prefetchManifoldPoints find these two fields by address.
	btAssert(reinterpret_cast<const char*>(m_pointCache) == caliber::manifoldPointBytes(this) &&
	         reinterpret_cast<const char*>(&m_cachedPoints) == caliber::manifoldHeaderBytes(this));
}

btPersistentManifold::btPersistentManifold(const btCollisionObject* body0, const btCollisionObject* body1, int,
                                           btScalar contactBreakingThreshold, btScalar contactProcessingThreshold)
    : btTypedObject(BT_PERSISTENT_MANIFOLD_TYPE),
      m_body0(body0),
      m_body1(body1),
      m_cachedPoints(0),
      m_contactBreakingThreshold(sanitizedBreakingThreshold(contactBreakingThreshold)),
      m_contactProcessingThreshold(sanitizedProcessingThreshold(contactProcessingThreshold)),
      m_companionIdA(0),
      m_companionIdB(0),
      m_index1a(0)
{
	// caliber::prefetchManifoldHeader and prefetchManifoldPoints find these two fields by address.
	btAssert(reinterpret_cast<const char*>(m_pointCache) == caliber::manifoldPointBytes(this) &&
	         reinterpret_cast<const char*>(&m_cachedPoints) == caliber::manifoldHeaderBytes(this));
}

void btPersistentManifold::clearUserCache(btManifoldPoint& pt)
{
	if (pt.m_userPersistentData && gContactDestroyedCallback)
	{
		void* data = pt.m_userPersistentData;
		pt.m_userPersistentData = 0;
		(*gContactDestroyedCallback)(data);
	}
}

void btPersistentManifold::setNumContacts(int cachedPoints)
{
	btAssert(cachedPoints >= 0 && cachedPoints <= MANIFOLD_CACHE_SIZE);
	m_cachedPoints = btMax(0, btMin(cachedPoints, int(MANIFOLD_CACHE_SIZE)));
}

void btPersistentManifold::setContactBreakingThreshold(btScalar contactBreakingThreshold)
{
	m_contactBreakingThreshold = sanitizedBreakingThreshold(contactBreakingThreshold);
}

void btPersistentManifold::setContactProcessingThreshold(btScalar contactProcessingThreshold)
{
	m_contactProcessingThreshold = sanitizedProcessingThreshold(contactProcessingThreshold);
}

int btPersistentManifold::getCacheEntry(const btManifoldPoint& newPoint) const
{
	btScalar closestDistance2 = m_contactBreakingThreshold * m_contactBreakingThreshold;
	int closest = -1;
	for (int i = 0; i < m_cachedPoints; ++i)
	{
		const btScalar distance2 = (m_pointCache[i].m_localPointA - newPoint.m_localPointA).length2();
		if (distance2 < closestDistance2)
		{
			closestDistance2 = distance2;
			closest = i;
		}
	}
	return closest;
}

// The deepest point carries the most penetration to resolve, so it is never replaced (unless the new
// point is deeper still, in which case any point may go). Among the remaining candidates, the one whose
// replacement by the new point leaves the largest area measure wins, so the kept points span the contact
// patch as widely as possible; ties go to the lowest index.
int btPersistentManifold::sortCachedPoints(const btManifoldPoint& newPoint)
{
	int deepest = -1;
	btScalar deepestDistance = newPoint.m_distance1;
	for (int i = 0; i < MANIFOLD_CACHE_SIZE; ++i)
	{
		if (m_pointCache[i].m_distance1 < deepestDistance)
		{
			deepestDistance = m_pointCache[i].m_distance1;
			deepest = i;
		}
	}

	int best = -1;
	btScalar bestMeasure = btScalar(-1);
	for (int replaced = 0; replaced < MANIFOLD_CACHE_SIZE; ++replaced)
	{
		if (replaced == deepest) continue;
		btVector3 kept[MANIFOLD_CACHE_SIZE];
		for (int i = 0; i < MANIFOLD_CACHE_SIZE; ++i)
			kept[i] = (i == replaced) ? newPoint.m_localPointA : m_pointCache[i].m_localPointA;
		const btScalar measure = areaMeasure(kept[0], kept[1], kept[2], kept[3]);
		if (measure > bestMeasure)
		{
			bestMeasure = measure;
			best = replaced;
		}
	}
	// Only reachable when coordinates so large that the measure overflows to NaN: replace any non-deepest point.
	if (best < 0) best = (deepest == 0) ? 1 : 0;
	return best;
}

int btPersistentManifold::addManifoldPoint(const btManifoldPoint& newPoint, bool isPredictive)
{
	(void)isPredictive;
	const bool finite = isFinitePoint(newPoint);
	btAssert(finite);
	if (!finite) return -1;

	int insertIndex = m_cachedPoints;
	if (insertIndex == MANIFOLD_CACHE_SIZE)
	{
		insertIndex = sortCachedPoints(newPoint);
		clearUserCache(m_pointCache[insertIndex]);
	}
	else
	{
		++m_cachedPoints;
	}
	m_pointCache[insertIndex] = newPoint;
	if (m_cachedPoints == 1 && gContactStartedCallback)
	{
		btPersistentManifold* self = this;
		(*gContactStartedCallback)(self);
	}
	return insertIndex;
}

void btPersistentManifold::removeContactPoint(int index)
{
	btAssert(index >= 0 && index < m_cachedPoints);
	if (index < 0 || index >= m_cachedPoints) return;
	clearUserCache(m_pointCache[index]);
	const int last = m_cachedPoints - 1;
	if (index != last) m_pointCache[index] = m_pointCache[last];
	// The moved-from slot must not keep a second reference to the user data now owned by `index`.
	m_pointCache[last].m_userPersistentData = 0;
	m_pointCache[last].m_appliedImpulse = 0;
	m_pointCache[last].m_appliedImpulseLateral1 = 0;
	m_pointCache[last].m_appliedImpulseLateral2 = 0;
	m_pointCache[last].m_lifeTime = 0;
	m_cachedPoints = last;
	if (m_cachedPoints == 0 && gContactEndedCallback)
	{
		btPersistentManifold* self = this;
		(*gContactEndedCallback)(self);
	}
}

void btPersistentManifold::replaceContactPoint(const btManifoldPoint& newPoint, int insertIndex)
{
	btAssert(insertIndex >= 0 && insertIndex < m_cachedPoints);
	const bool finite = isFinitePoint(newPoint);
	btAssert(finite);
	if (insertIndex < 0 || insertIndex >= m_cachedPoints || !finite) return;

	// The solver converges in fewer iterations when it starts from the impulses of the previous frame.
	const btManifoldPoint& old = m_pointCache[insertIndex];
	const btScalar appliedImpulse = old.m_appliedImpulse;
	const btScalar prevRHS = old.m_prevRHS;
	const btScalar lateral1 = old.m_appliedImpulseLateral1;
	const btScalar lateral2 = old.m_appliedImpulseLateral2;
	const int lifeTime = old.m_lifeTime;
	void* userData = old.m_userPersistentData;
	// The lateral impulses are only meaningful along the directions they were solved in.
	const btVector3 lateralDir1 = old.m_lateralFrictionDir1;
	const btVector3 lateralDir2 = old.m_lateralFrictionDir2;

	m_pointCache[insertIndex] = newPoint;
	btManifoldPoint& point = m_pointCache[insertIndex];
	point.m_appliedImpulse = appliedImpulse;
	point.m_prevRHS = prevRHS;
	point.m_appliedImpulseLateral1 = lateral1;
	point.m_appliedImpulseLateral2 = lateral2;
	point.m_lifeTime = lifeTime;
	point.m_userPersistentData = userData;
	if (!(newPoint.m_contactPointFlags & BT_CONTACT_FLAG_LATERAL_FRICTION_INITIALIZED))
	{
		point.m_lateralFrictionDir1 = lateralDir1;
		point.m_lateralFrictionDir2 = lateralDir2;
	}
}

void btPersistentManifold::refreshContactPoints(const btTransform& trA, const btTransform& trB)
{
#if CALIBER_AVX2_BUILDS
	const int kept = g_avx2Refresh
	                     ? refreshWorldPointsAvx2(m_pointCache, m_cachedPoints, trA, trB, m_contactBreakingThreshold)
	                     : refreshWorldPoints(m_pointCache, m_cachedPoints, trA, trB, m_contactBreakingThreshold);
#else
	const int kept = refreshWorldPoints(m_pointCache, m_cachedPoints, trA, trB, m_contactBreakingThreshold);
#endif
	if (kept < 0) return;

	// Backwards, so that the point moved into a removed slot has already been examined: the point at index
	// i is still the first pass's point i, and its verdict stands. With no callback to run, that is all.
	if (!gContactProcessedCallback && !gContactDestroyedCallback && !gContactEndedCallback)
	{
		if (kept == (1 << m_cachedPoints) - 1) return;
		for (int i = m_cachedPoints - 1; i >= 0; --i)
			if (!(kept & (1 << i))) removeContactPoint(i);
		return;
	}
	// With callbacks, each point is judged again when its turn comes, after the callbacks before it ran
	// (which may change the manifold), as always.
	const btScalar threshold2 = m_contactBreakingThreshold * m_contactBreakingThreshold;
	for (int i = m_cachedPoints - 1; i >= 0; --i)
	{
		const btManifoldPoint& point = m_pointCache[i];
		if (!validContactDistance(point))
		{
			removeContactPoint(i);
			continue;
		}
		const btVector3 projectedOnB = point.m_positionWorldOnA - point.m_normalWorldOnB * point.m_distance1;
		const btScalar drift2 = (point.m_positionWorldOnB - projectedOnB).length2();
		if (drift2 > threshold2)
		{
			removeContactPoint(i);
			continue;
		}
		if (gContactProcessedCallback) (*gContactProcessedCallback)(m_pointCache[i], (void*)m_body0, (void*)m_body1);
	}
}

bool caliber::refreshContactPointsUsesAvx2()
{
#if CALIBER_AVX2_BUILDS
	return g_avx2Refresh;
#else
	return false;
#endif
}

int caliber::refreshWorldPointsIn(btManifoldPoint* points, int count, const btTransform& trA, const btTransform& trB,
                                  btScalar threshold, bool avx2)
{
	btAssert(count >= 0 && count <= MANIFOLD_CACHE_SIZE);
#if CALIBER_AVX2_BUILDS
	if (avx2 && g_avx2Refresh) return refreshWorldPointsAvx2(points, count, trA, trB, threshold);
#endif
	(void)avx2;
	return refreshWorldPoints(points, count, trA, trB, threshold);
}

void btPersistentManifold::clearManifold()
{
	const int hadPoints = m_cachedPoints;
	for (int i = 0; i < m_cachedPoints; ++i) clearUserCache(m_pointCache[i]);
	m_cachedPoints = 0;
	if (hadPoints > 0 && gContactEndedCallback)
	{
		btPersistentManifold* self = this;
		(*gContactEndedCallback)(self);
	}
}
