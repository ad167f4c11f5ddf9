// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_CAPSULE_TRIANGLE_CONTACT_H
#define CALIBER_CAPSULE_TRIANGLE_CONTACT_H

// Capsule against a mesh triangle in closed form: the capsule's core segment clipped against the
// triangle's prism gives the face contact (both ends of a capsule lying on the face, not one point that
// lets it roll), and the segment against the triangle's edges gives the edge contact. Exact, and cheaper
// than GJK on the two support functions. Internal.

#include "BulletCollision/CollisionDispatch/btConvexTriangleClipping.h"
#include "BulletCollision/CollisionShapes/btCapsuleShape.h"

namespace caliber
{
/// Reports to out (normal from the triangle towards the capsule, point on the triangle's surface, its
/// margin included) the capsule's contacts with the triangle within reach: at most two face points (the
/// ends of the part of the core segment over the triangle) and the closest edge point when an edge is
/// nearer than the face. Returns kTriangleOutOfReach when nothing is within reach, kTriangleFaceContact
/// when the points reported are the whole contact, and kTriangleNeedsGjk, reporting nothing, when the
/// core segment meets the triangle's plane (deep: no direction to separate along) or the triangle is a
/// sliver.
TriangleFaceOutcome capsuleTriangleContact(const btCapsuleShape& capsule, const btTransform& capsuleTransform,
                                           const btTriangleShape& triangle, const btTransform& triangleTransform,
                                           btScalar reach, btDiscreteCollisionDetectorInterface::Result& out);
}  // namespace caliber

#endif  // CALIBER_CAPSULE_TRIANGLE_CONTACT_H
