// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btCollisionShape.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"

void btCollisionShape::getBoundingSphere(btVector3& center, btScalar& radius) const
{
	btVector3 aabbMin, aabbMax;
	getAabb(btTransform::getIdentity(), aabbMin, aabbMax);
	radius = (aabbMax - aabbMin).length() * btScalar(0.5);
	center = (aabbMin + aabbMax) * btScalar(0.5);
}

btScalar btCollisionShape::getAngularMotionDisc() const
{
	btVector3 center;
	btScalar radius;
	getBoundingSphere(center, radius);
	return center.length() + radius;
}

btScalar btCollisionShape::getContactBreakingThreshold(btScalar defaultContactThresholdFactor) const
{
	return getAngularMotionDisc() * defaultContactThresholdFactor;
}

void btCollisionShape::calculateTemporalAabb(const btTransform& curTrans, const btVector3& linvel,
                                             const btVector3& angvel, btScalar timeStep, btVector3& temporalAabbMin,
                                             btVector3& temporalAabbMax) const
{
	getAabb(curTrans, temporalAabbMin, temporalAabbMax);

	// Linear motion only moves the side the body travels towards.
	const btVector3 linMotion = linvel * timeStep;
	btVector3 growMin(0, 0, 0), growMax(0, 0, 0);
	for (int axis = 0; axis < 3; ++axis)
	{
		if (linMotion[axis] > btScalar(0) && linMotion[axis] <= SIMD_INFINITY)
			growMax[axis] = linMotion[axis];
		else if (linMotion[axis] < btScalar(0) && linMotion[axis] >= -SIMD_INFINITY)
			growMin[axis] = linMotion[axis];
	}

	// No point of the shape moves further than |angle| * disc under a rotation by angle.
	btScalar angularMotion = angvel.length() * getAngularMotionDisc() * timeStep;
	// Bad velocities or time steps (NaN, infinite) are ignored rather than written into the box.
	btAssert(caliber::isFinite(linMotion) && btIsFinite(angularMotion));
	if (!(angularMotion >= btScalar(0) && angularMotion <= SIMD_INFINITY)) angularMotion = btScalar(0);
	const btVector3 angularGrow(angularMotion, angularMotion, angularMotion);
	temporalAabbMin += growMin - angularGrow;
	temporalAabbMax += growMax + angularGrow;
}
