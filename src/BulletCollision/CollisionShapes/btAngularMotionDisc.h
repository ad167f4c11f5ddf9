// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_ANGULAR_MOTION_DISC_H
#define CALIBER_ANGULAR_MOTION_DISC_H

// Internal: shape->getAngularMotionDisc() without its virtual calls for a plain btBoxShape. The near
// callback asks it of each turning body's shape for every pair and step (in stack1000 about ten thousand
// times a step, some 47 instructions each: two virtual calls, the bounding sphere, two square roots).

#include <typeinfo>

#include "BulletCollision/CollisionShapes/btBoxShape.h"

namespace caliber
{
/// The same value as shape->getAngularMotionDisc(), bit for bit. For a btBoxShape itself (not a subclass,
/// which may override any of the virtuals involved), the operations of btCollisionShape::getAngularMotionDisc
/// on btBoxShape::getBoundingSphere, inlined: the sphere's radius is the length of the half extents with
/// the margin, its centre the origin (length 0), and the disc is the centre's length plus the radius.
inline btScalar angularMotionDisc(const btCollisionShape* shape)
{
	if (shape->getShapeType() == BOX_SHAPE_PROXYTYPE && typeid(*shape) == typeid(btBoxShape))
	{
		const btBoxShape* box = static_cast<const btBoxShape*>(shape);
		const btScalar margin = box->getMarginNV();  // what btBoxShape's getMargin returns
		const btScalar radius = (box->getHalfExtentsWithoutMargin() + btVector3(margin, margin, margin)).length();
		const btScalar centreLength = btScalar(0);  // kept as an addition: 0 + radius, as the virtual path
		return centreLength + radius;
	}
	return shape->getAngularMotionDisc();
}
}  // namespace caliber

#endif  // CALIBER_ANGULAR_MOTION_DISC_H
