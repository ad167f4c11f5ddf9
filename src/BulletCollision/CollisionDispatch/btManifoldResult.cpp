// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "BulletCollision/CollisionDispatch/btManifoldResultBuilds.h"
#include "BulletCollision/CollisionDispatch/btPairPoseCache.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "LinearMath/btCpuFeatures.h"
#include "LinearMath/btMemberAccess.h"
#include "LinearMath/btMinMax.h"

CALIBER_MEMBER_ACCESS(ResultPartId0, btManifoldResult, int, m_partId0)
CALIBER_MEMBER_ACCESS(ResultPartId1, btManifoldResult, int, m_partId1)
CALIBER_MEMBER_ACCESS(ResultIndex0, btManifoldResult, int, m_index0)
CALIBER_MEMBER_ACCESS(ResultIndex1, btManifoldResult, int, m_index1)

ContactAddedCallback gContactAddedCallback = 0;
CalculateCombinedCallback gCalculateCombinedRestitutionCallback = &btManifoldResult::calculateCombinedRestitution;
CalculateCombinedCallback gCalculateCombinedFrictionCallback = &btManifoldResult::calculateCombinedFriction;
CalculateCombinedCallback gCalculateCombinedRollingFrictionCallback =
    &btManifoldResult::calculateCombinedRollingFriction;
CalculateCombinedCallback gCalculateCombinedSpinningFrictionCallback =
    &btManifoldResult::calculateCombinedSpinningFriction;
CalculateCombinedCallback gCalculateCombinedContactDampingCallback = &btManifoldResult::calculateCombinedContactDamping;
CalculateCombinedCallback gCalculateCombinedContactStiffnessCallback =
    &btManifoldResult::calculateCombinedContactStiffness;

namespace
{
// Combined friction is capped so that a pair of very grippy materials cannot make the solver's friction
// cone explode (Bullet uses the same bound).
const btScalar kMaxCombinedFriction = btScalar(10);

btScalar clampFriction(btScalar value) { return btClamped(value, -kMaxCombinedFriction, kMaxCombinedFriction); }

// The combined value of a callback: the default's body inlined when the callback is the default (most
// programs never change them, and a call through the pointer cost a point about 40 instructions), the
// callback itself otherwise. The same operations either way, so the same bits.
#define CALIBER_COMBINED(callback, function, body0, body1) \
	((callback) == &btManifoldResult::function ? combined::function(body0, body1) : (callback)(body0, body1))

// The defaults' bodies, visible here so that the calls above inline (btManifoldResult's static functions
// are the same expressions).
namespace combined
{
inline btScalar calculateCombinedRestitution(const btCollisionObject* body0, const btCollisionObject* body1)
{
	return body0->getRestitution() * body1->getRestitution();
}
inline btScalar calculateCombinedFriction(const btCollisionObject* body0, const btCollisionObject* body1)
{
	return clampFriction(body0->getFriction() * body1->getFriction());
}
inline btScalar calculateCombinedRollingFriction(const btCollisionObject* body0, const btCollisionObject* body1)
{
	return clampFriction(body0->getRollingFriction() * body1->getFriction() +
	                     body0->getFriction() * body1->getRollingFriction());
}
inline btScalar calculateCombinedSpinningFriction(const btCollisionObject* body0, const btCollisionObject* body1)
{
	return clampFriction(body0->getSpinningFriction() * body1->getFriction() +
	                     body0->getFriction() * body1->getSpinningFriction());
}
}  // namespace combined

// The four material values every point gets, in the order addContactPoint has always asked for them.
struct PointMaterial
{
	btScalar friction, restitution, rolling, spinning;

	PointMaterial(const btCollisionObject* body0, const btCollisionObject* body1)
	    : friction(CALIBER_COMBINED(gCalculateCombinedFrictionCallback, calculateCombinedFriction, body0, body1)),
	      restitution(
	          CALIBER_COMBINED(gCalculateCombinedRestitutionCallback, calculateCombinedRestitution, body0, body1)),
	      rolling(CALIBER_COMBINED(gCalculateCombinedRollingFrictionCallback, calculateCombinedRollingFriction, body0,
	                               body1)),
	      spinning(CALIBER_COMBINED(gCalculateCombinedSpinningFrictionCallback, calculateCombinedSpinningFriction,
	                                body0, body1))
	{
	}
};
#undef CALIBER_COMBINED
}  // namespace

btScalar btManifoldResult::calculateCombinedRestitution(const btCollisionObject* body0, const btCollisionObject* body1)
{
	return combined::calculateCombinedRestitution(body0, body1);
}

btScalar btManifoldResult::calculateCombinedFriction(const btCollisionObject* body0, const btCollisionObject* body1)
{
	return combined::calculateCombinedFriction(body0, body1);
}

btScalar btManifoldResult::calculateCombinedRollingFriction(const btCollisionObject* body0,
                                                            const btCollisionObject* body1)
{
	return combined::calculateCombinedRollingFriction(body0, body1);
}

btScalar btManifoldResult::calculateCombinedSpinningFriction(const btCollisionObject* body0,
                                                             const btCollisionObject* body1)
{
	return combined::calculateCombinedSpinningFriction(body0, body1);
}

btScalar btManifoldResult::calculateCombinedContactDamping(const btCollisionObject* body0,
                                                           const btCollisionObject* body1)
{
	return body0->getContactDamping() + body1->getContactDamping();
}

btScalar btManifoldResult::calculateCombinedContactStiffness(const btCollisionObject* body0,
                                                             const btCollisionObject* body1)
{
	// setContactStiffnessAndDamping keeps stiffness >= SIMD_EPSILON, so neither division is by zero.
	const btScalar compliance = btScalar(1) / body0->getContactStiffness() + btScalar(1) / body1->getContactStiffness();
	return btScalar(1) / compliance;
}

btManifoldResult::btManifoldResult(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap)
    : m_manifoldPtr(0),
      m_body0Wrap(body0Wrap),
      m_body1Wrap(body1Wrap),
      m_partId0(body0Wrap ? body0Wrap->m_partId : -1),
      m_partId1(body1Wrap ? body1Wrap->m_partId : -1),
      m_index0(body0Wrap ? body0Wrap->m_index : -1),
      m_index1(body1Wrap ? body1Wrap->m_index : -1),
      m_closestPointDistanceThreshold(0)
{
}

void btManifoldResult::refreshContactPoints()
{
	btAssert(m_manifoldPtr);
	if (!m_manifoldPtr || !m_body0Wrap || !m_body1Wrap || m_manifoldPtr->getNumContacts() == 0) return;
	const bool isSwapped = m_manifoldPtr->getBody0() != m_body0Wrap->getCollisionObject();
	// Points found within the extra (speculative) distance must survive the refresh that follows.
	const btScalar breakingThreshold = m_manifoldPtr->getContactBreakingThreshold();
	if (m_closestPointDistanceThreshold > btScalar(0))
		m_manifoldPtr->setContactBreakingThreshold(breakingThreshold + m_closestPointDistanceThreshold);
	if (isSwapped)
		m_manifoldPtr->refreshContactPoints(m_body1Wrap->getCollisionObject()->getWorldTransform(),
		                                    m_body0Wrap->getCollisionObject()->getWorldTransform());
	else
		m_manifoldPtr->refreshContactPoints(m_body0Wrap->getCollisionObject()->getWorldTransform(),
		                                    m_body1Wrap->getCollisionObject()->getWorldTransform());
	m_manifoldPtr->setContactBreakingThreshold(breakingThreshold);
}

namespace
{
// btManifoldResult::addContactPoint's body, inlined into the two builds below.
SIMD_FORCE_INLINE void addPoint(btManifoldResult& result, const btVector3& normalOnBInWorld,
                                const btVector3& pointInWorld, btScalar depth)
{
	btPersistentManifold* const manifoldPtr = result.getPersistentManifold();
	const btCollisionObjectWrapper* const body0Wrap = result.getBody0Wrap();
	const btCollisionObjectWrapper* const body1Wrap = result.getBody1Wrap();
	if (!manifoldPtr || !body0Wrap || !body1Wrap) return;
	const btScalar closestPointDistanceThreshold = result.m_closestPointDistanceThreshold;
	const int resultPartId0 = result.*memberOf(caliber::ResultPartId0{});
	const int resultPartId1 = result.*memberOf(caliber::ResultPartId1{});
	const int resultIndex0 = result.*memberOf(caliber::ResultIndex0{});
	const int resultIndex1 = result.*memberOf(caliber::ResultIndex1{});

	const bool finiteInput =
	    caliber::isFinite(normalOnBInWorld) && caliber::isFinite(pointInWorld) && btIsFinite(depth);
	btAssert(finiteInput && "btManifoldResult::addContactPoint: non-finite contact");
	if (!finiteInput) return;

	btPersistentManifold& manifold = *manifoldPtr;
	if (depth > manifold.getContactBreakingThreshold() + closestPointDistanceThreshold) return;

	// Points are stored in the manifold's body order; the algorithm reports in its own (body0Wrap first)
	// order, which differs when the manifold was created for the swapped pair.
	const bool isSwapped = manifold.getBody0() != body0Wrap->getCollisionObject();
	const bool isNewCollision = manifold.getNumContacts() == 0;
	const btCollisionObjectWrapper* wrapA = isSwapped ? body1Wrap : body0Wrap;
	const btCollisionObjectWrapper* wrapB = isSwapped ? body0Wrap : body1Wrap;

	const btVector3 pointA = pointInWorld + normalOnBInWorld * depth;
	const btVector3 localA = wrapA->getCollisionObject()->getWorldTransform().invXform(pointA);
	const btVector3 localB = wrapB->getCollisionObject()->getWorldTransform().invXform(pointInWorld);

	const btCollisionObject* body0 = body0Wrap->getCollisionObject();
	const btCollisionObject* body1 = body1Wrap->getCollisionObject();
	const PointMaterial material(body0, body1);
	const int flags0 = body0->getCollisionFlags();
	const int flags1 = body1->getCollisionFlags();
	const bool stiffness = ((flags0 | flags1) & btCollisionObject::CF_HAS_CONTACT_STIFFNESS_DAMPING) != 0;
	const btScalar damping = stiffness ? gCalculateCombinedContactDampingCallback(body0, body1) : btScalar(0);
	const btScalar stiffnessValue =
	    stiffness ? gCalculateCombinedContactStiffnessCallback(body0, body1) : btScalar(0);
	int pointFlags = stiffness ? int(BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING) : 0;
	if ((flags0 | flags1) & btCollisionObject::CF_HAS_FRICTION_ANCHOR) pointFlags |= BT_CONTACT_FLAG_FRICTION_ANCHOR;
	const int partId0 = isSwapped ? resultPartId1 : resultPartId0;
	const int partId1 = isSwapped ? resultPartId0 : resultPartId1;
	const int index0 = isSwapped ? resultIndex1 : resultIndex0;
	const int index1 = isSwapped ? resultIndex0 : resultIndex1;

	// getCacheEntry's search (the stored point whose local point A is closest, strictly within the
	// breaking threshold), on localA alone.
	int insertIndex = -1;
	// The points are one array: indexed from the first, without getContactPoint's clamp per point.
	const int points = manifold.getNumContacts();
	btManifoldPoint* const stored = points > 0 ? &manifold.getContactPoint(0) : nullptr;
	{
		btScalar closestDistance2 = manifold.getContactBreakingThreshold() * manifold.getContactBreakingThreshold();
		for (int i = 0; i < points; ++i)
		{
			const btScalar distance2 = (stored[i].m_localPointA - localA).length2();
			if (distance2 < closestDistance2)
			{
				closestDistance2 = distance2;
				insertIndex = i;
			}
		}
	}
	if (insertIndex >= 0)
	{
		// replaceContactPoint with the new point written in place: what a new point sets is overwritten,
		// the impulses, previous RHS, lifetime, user data and friction directions are kept (the lateral
		// impulses were solved along those directions; a new point never has
		// BT_CONTACT_FLAG_LATERAL_FRICTION_INITIALIZED), and what a new point leaves at zero is zeroed.
		// Building the point and copying it in cost about a hundred instructions a point.
		const bool finite = caliber::isFinite(localA) && caliber::isFinite(localB) && caliber::isFinite(pointA);
		btAssert(finite);
		if (finite)
		{
			btManifoldPoint& point = stored[insertIndex];
			point.m_localPointA = localA;
			point.m_localPointB = localB;
			point.m_positionWorldOnB = pointInWorld;
			point.m_positionWorldOnA = pointA;
			point.m_normalWorldOnB = normalOnBInWorld;
			point.m_distance1 = depth;
			point.m_combinedFriction = material.friction;
			point.m_combinedRollingFriction = material.rolling;
			point.m_combinedSpinningFriction = material.spinning;
			point.m_combinedRestitution = material.restitution;
			point.m_partId0 = partId0;
			point.m_partId1 = partId1;
			point.m_index0 = index0;
			point.m_index1 = index1;
			point.m_contactPointFlags = pointFlags;
			point.m_contactMotion1 = btScalar(0);
			point.m_contactMotion2 = btScalar(0);
			point.m_contactCFM = btScalar(0);
			point.m_combinedContactStiffness1 = stiffnessValue;
			point.m_contactERP = btScalar(0);
			point.m_combinedContactDamping1 = damping;
			point.m_frictionCFM = btScalar(0);
		}
	}
	else
	{
		btManifoldPoint newPt(localA, localB, normalOnBInWorld, depth);
		newPt.m_positionWorldOnA = pointA;
		newPt.m_positionWorldOnB = pointInWorld;
		newPt.m_combinedFriction = material.friction;
		newPt.m_combinedRestitution = material.restitution;
		newPt.m_combinedRollingFriction = material.rolling;
		newPt.m_combinedSpinningFriction = material.spinning;
		newPt.m_combinedContactDamping1 = damping;
		newPt.m_combinedContactStiffness1 = stiffnessValue;
		newPt.m_contactPointFlags = pointFlags;
		newPt.m_partId0 = partId0;
		newPt.m_partId1 = partId1;
		newPt.m_index0 = index0;
		newPt.m_index1 = index1;
		btPlaneSpace1(newPt.m_normalWorldOnB, newPt.m_lateralFrictionDir1, newPt.m_lateralFrictionDir2);
		insertIndex = manifold.addManifoldPoint(newPt);
	}
	if (insertIndex < 0) return;

	if (gContactAddedCallback && ((flags0 | flags1) & btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK))
	{
		btManifoldPoint& stored = manifold.getContactPoint(insertIndex);
		(*gContactAddedCallback)(stored, wrapA, stored.m_partId0, stored.m_index0, wrapB, stored.m_partId1,
		                         stored.m_index1);
	}
	if (gContactStartedCallback && isNewCollision) gContactStartedCallback(manifoldPtr);
}

// The body compiled a second time for AVX2 (VEX encoding: three operands, no register copy before each
// two-operand SSE operation), chosen at load; the baseline is a call of its own, so that the choice costs
// the caller no stack frame. Only AVX2, never FMA: the same operations round the same way in the same order,
// so the points get the same bits (see LinearMath/btCpuFeatures.h).
#if CALIBER_AVX2_BUILDS
__attribute__((target("avx2"))) void addPointAvx2(btManifoldResult& result, const btVector3& normalOnBInWorld,
                                                   const btVector3& pointInWorld, btScalar depth)
{
	addPoint(result, normalOnBInWorld, pointInWorld, depth);
}
const bool g_avx2Points = caliber::detectAvx2();
#endif

__attribute__((noinline)) void addPointBaseline(btManifoldResult& result, const btVector3& normalOnBInWorld,
                                                const btVector3& pointInWorld, btScalar depth)
{
	addPoint(result, normalOnBInWorld, pointInWorld, depth);
}
}  // namespace

void btManifoldResult::addContactPoint(const btVector3& normalOnBInWorld, const btVector3& pointInWorld, btScalar depth)
{
#if CALIBER_AVX2_BUILDS
	if (g_avx2Points)
	{
		addPointAvx2(*this, normalOnBInWorld, pointInWorld, depth);
		return;
	}
#endif
	addPointBaseline(*this, normalOnBInWorld, pointInWorld, depth);
}

bool caliber::addContactPointUsesAvx2()
{
#if CALIBER_AVX2_BUILDS
	return g_avx2Points;
#else
	return false;
#endif
}

void caliber::addContactPointIn(btManifoldResult& result, const btVector3& normalOnBInWorld,
                                const btVector3& pointInWorld, btScalar depth, bool avx2)
{
#if CALIBER_AVX2_BUILDS
	if (avx2 && g_avx2Points)
	{
		addPointAvx2(result, normalOnBInWorld, pointInWorld, depth);
		return;
	}
#endif
	(void)avx2;
	addPointBaseline(result, normalOnBInWorld, pointInWorld, depth);
}

void caliber::refreshPointMaterials(btPersistentManifold& manifold, const btCollisionObject* object0,
                                    const btCollisionObject* object1)
{
	const int points = manifold.getNumContacts();
	if (points == 0) return;
	// The same values and flags addContactPoint gives a new point (replaceContactPoint keeps them).
	const PointMaterial material(object0, object1);
	const btScalar friction = material.friction, restitution = material.restitution;
	const btScalar rolling = material.rolling, spinning = material.spinning;
	const int flags = object0->getCollisionFlags() | object1->getCollisionFlags();
	const bool stiffness = (flags & btCollisionObject::CF_HAS_CONTACT_STIFFNESS_DAMPING) != 0;
	const btScalar damping = stiffness ? gCalculateCombinedContactDampingCallback(object0, object1) : btScalar(0);
	const btScalar stiffnessValue = stiffness ? gCalculateCombinedContactStiffnessCallback(object0, object1) : btScalar(0);
	// The points are one array: indexed from the first, without getContactPoint's clamp per point.
	btManifoldPoint* const stored = &manifold.getContactPoint(0);
	for (int i = 0; i < points; ++i)
	{
		btManifoldPoint& point = stored[i];
		point.m_combinedFriction = friction;
		point.m_combinedRestitution = restitution;
		point.m_combinedRollingFriction = rolling;
		point.m_combinedSpinningFriction = spinning;
		if (stiffness)
		{
			point.m_combinedContactDamping1 = damping;
			point.m_combinedContactStiffness1 = stiffnessValue;
			point.m_contactPointFlags |= BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING;
		}
		else
		{
			point.m_contactPointFlags &= ~BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING;
		}
		if (flags & btCollisionObject::CF_HAS_FRICTION_ANCHOR)
			point.m_contactPointFlags |= BT_CONTACT_FLAG_FRICTION_ANCHOR;
		else
			point.m_contactPointFlags &= ~BT_CONTACT_FLAG_FRICTION_ANCHOR;
	}
}
