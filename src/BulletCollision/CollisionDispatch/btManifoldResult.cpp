// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "BulletCollision/CollisionDispatch/btPairPoseCache.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "LinearMath/btMinMax.h"

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
}  // namespace

btScalar btManifoldResult::calculateCombinedRestitution(const btCollisionObject* body0, const btCollisionObject* body1)
{
	return body0->getRestitution() * body1->getRestitution();
}

btScalar btManifoldResult::calculateCombinedFriction(const btCollisionObject* body0, const btCollisionObject* body1)
{
	return clampFriction(body0->getFriction() * body1->getFriction());
}

btScalar btManifoldResult::calculateCombinedRollingFriction(const btCollisionObject* body0,
                                                            const btCollisionObject* body1)
{
	return clampFriction(body0->getRollingFriction() * body1->getFriction() +
	                     body0->getFriction() * body1->getRollingFriction());
}

btScalar btManifoldResult::calculateCombinedSpinningFriction(const btCollisionObject* body0,
                                                             const btCollisionObject* body1)
{
	return clampFriction(body0->getSpinningFriction() * body1->getFriction() +
	                     body0->getFriction() * body1->getSpinningFriction());
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

void btManifoldResult::addContactPoint(const btVector3& normalOnBInWorld, const btVector3& pointInWorld, btScalar depth)
{
	if (!m_manifoldPtr || !m_body0Wrap || !m_body1Wrap) return;

	const bool finiteInput =
	    caliber::isFinite(normalOnBInWorld) && caliber::isFinite(pointInWorld) && btIsFinite(depth);
	btAssert(finiteInput && "btManifoldResult::addContactPoint: non-finite contact");
	if (!finiteInput) return;

	if (depth > m_manifoldPtr->getContactBreakingThreshold() + m_closestPointDistanceThreshold) return;

	// Points are stored in the manifold's body order; the algorithm reports in its own (body0Wrap first)
	// order, which differs when the manifold was created for the swapped pair.
	const bool isSwapped = m_manifoldPtr->getBody0() != m_body0Wrap->getCollisionObject();
	const bool isNewCollision = m_manifoldPtr->getNumContacts() == 0;
	const btCollisionObjectWrapper* wrapA = isSwapped ? m_body1Wrap : m_body0Wrap;
	const btCollisionObjectWrapper* wrapB = isSwapped ? m_body0Wrap : m_body1Wrap;

	const btVector3 pointA = pointInWorld + normalOnBInWorld * depth;
	const btVector3 localA = wrapA->getCollisionObject()->getWorldTransform().invXform(pointA);
	const btVector3 localB = wrapB->getCollisionObject()->getWorldTransform().invXform(pointInWorld);

	btManifoldPoint newPt(localA, localB, normalOnBInWorld, depth);
	newPt.m_positionWorldOnA = pointA;
	newPt.m_positionWorldOnB = pointInWorld;

	const btCollisionObject* body0 = m_body0Wrap->getCollisionObject();
	const btCollisionObject* body1 = m_body1Wrap->getCollisionObject();
	newPt.m_combinedFriction = gCalculateCombinedFrictionCallback(body0, body1);
	newPt.m_combinedRestitution = gCalculateCombinedRestitutionCallback(body0, body1);
	newPt.m_combinedRollingFriction = gCalculateCombinedRollingFrictionCallback(body0, body1);
	newPt.m_combinedSpinningFriction = gCalculateCombinedSpinningFrictionCallback(body0, body1);

	const int flags0 = body0->getCollisionFlags();
	const int flags1 = body1->getCollisionFlags();
	if ((flags0 | flags1) & btCollisionObject::CF_HAS_CONTACT_STIFFNESS_DAMPING)
	{
		newPt.m_combinedContactDamping1 = gCalculateCombinedContactDampingCallback(body0, body1);
		newPt.m_combinedContactStiffness1 = gCalculateCombinedContactStiffnessCallback(body0, body1);
		newPt.m_contactPointFlags |= BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING;
	}
	if ((flags0 | flags1) & btCollisionObject::CF_HAS_FRICTION_ANCHOR)
		newPt.m_contactPointFlags |= BT_CONTACT_FLAG_FRICTION_ANCHOR;

	newPt.m_partId0 = isSwapped ? m_partId1 : m_partId0;
	newPt.m_partId1 = isSwapped ? m_partId0 : m_partId1;
	newPt.m_index0 = isSwapped ? m_index1 : m_index0;
	newPt.m_index1 = isSwapped ? m_index0 : m_index1;

	int insertIndex = m_manifoldPtr->getCacheEntry(newPt);
	if (insertIndex >= 0)
	{
		// A replaced point keeps its old friction directions (its lateral impulses were solved along them).
		m_manifoldPtr->replaceContactPoint(newPt, insertIndex);
	}
	else
	{
		btPlaneSpace1(newPt.m_normalWorldOnB, newPt.m_lateralFrictionDir1, newPt.m_lateralFrictionDir2);
		insertIndex = m_manifoldPtr->addManifoldPoint(newPt);
	}
	if (insertIndex < 0) return;

	if (gContactAddedCallback && ((flags0 | flags1) & btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK))
	{
		btManifoldPoint& stored = m_manifoldPtr->getContactPoint(insertIndex);
		(*gContactAddedCallback)(stored, wrapA, stored.m_partId0, stored.m_index0, wrapB, stored.m_partId1,
		                         stored.m_index1);
	}
	if (gContactStartedCallback && isNewCollision) gContactStartedCallback(m_manifoldPtr);
}

void caliber::refreshPointMaterials(btPersistentManifold& manifold, const btCollisionObject* object0,
                                    const btCollisionObject* object1)
{
	const int points = manifold.getNumContacts();
	if (points == 0) return;
	// The same values and flags addContactPoint gives a new point (replaceContactPoint keeps them).
	const btScalar friction = gCalculateCombinedFrictionCallback(object0, object1);
	const btScalar restitution = gCalculateCombinedRestitutionCallback(object0, object1);
	const btScalar rolling = gCalculateCombinedRollingFrictionCallback(object0, object1);
	const btScalar spinning = gCalculateCombinedSpinningFrictionCallback(object0, object1);
	const int flags = object0->getCollisionFlags() | object1->getCollisionFlags();
	const bool stiffness = (flags & btCollisionObject::CF_HAS_CONTACT_STIFFNESS_DAMPING) != 0;
	const btScalar damping = stiffness ? gCalculateCombinedContactDampingCallback(object0, object1) : btScalar(0);
	const btScalar stiffnessValue = stiffness ? gCalculateCombinedContactStiffnessCallback(object0, object1) : btScalar(0);
	for (int i = 0; i < points; ++i)
	{
		btManifoldPoint& point = manifold.getContactPoint(i);
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
