// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_CAPSULE_CAPSULE_CONTACT_H
#define CALIBER_CAPSULE_CAPSULE_CONTACT_H

// Capsule against capsule in closed form: the closest points of the two core segments, then the radii.
// Exact, and several times cheaper than GJK on the two support functions (ragdolls are all capsules).

#include "BulletCollision/CollisionShapes/btCapsuleShape.h"
#include "LinearMath/btTransform.h"

namespace caliber
{
/// The closest points of segments [p0, p1] and [q0, q1] (parameters s, t in [0, 1] along each).
void closestPointsOfSegments(const btVector3& p0, const btVector3& p1, const btVector3& q0, const btVector3& q1,
                             btScalar& s, btScalar& t);

/// Contact between capsules a (at ta) and b (at tb): false when their core segments cross (no direction
/// to separate along; the caller falls back to the general algorithm). Otherwise normalOnB points from b
/// towards a, pointOnB is on b's surface, and distance is the gap between the surfaces (negative when
/// they overlap).
bool capsuleCapsuleContact(const btCapsuleShape& a, const btTransform& ta, const btCapsuleShape& b,
                           const btTransform& tb, btVector3& normalOnB, btVector3& pointOnB, btScalar& distance);
}  // namespace caliber

#endif  // CALIBER_CAPSULE_CAPSULE_CONTACT_H
