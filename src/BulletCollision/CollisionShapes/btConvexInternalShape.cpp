// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btConvexInternalShape.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"

btConvexInternalShape::btConvexInternalShape()
    : m_localScaling(btScalar(1), btScalar(1), btScalar(1)),
      m_implicitShapeDimensions(btScalar(0), btScalar(0), btScalar(0)),
      m_collisionMargin(CONVEX_DISTANCE_MARGIN),
      m_padding(btScalar(0))
{
}

btConvexInternalShape::~btConvexInternalShape() {}

btVector3 btConvexInternalShape::localGetSupportingVertex(const btVector3& vec) const
{
	btVector3 dir = caliber::supportDirection(vec);
	const btVector3 core = localGetSupportingVertexWithoutMargin(dir);
	return core + getMargin() * dir.safeNormalize();
}

void btConvexInternalShape::setSafeMargin(btScalar minDimension, btScalar defaultMarginMultiplier)
{
	const btScalar safeMargin = defaultMarginMultiplier * minDimension;
	if (safeMargin < getMargin()) setMargin(safeMargin);
}

void btConvexInternalShape::setSafeMargin(const btVector3& halfExtents, btScalar defaultMarginMultiplier)
{
	const btScalar minDimension = halfExtents[halfExtents.minAxis()];
	setSafeMargin(minDimension, defaultMarginMultiplier);
}

void btConvexInternalShape::getAabbSlow(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const
{
	if (!caliber::checkAabbTransform(t, aabbMin, aabbMax)) return;
	const btMatrix3x3& basis = t.getBasis();
	for (int axis = 0; axis < 3; ++axis)
	{
		// World axis e expressed in local coordinates is row `axis` of the basis.
		const btVector3 localAxis = basis[axis];
		aabbMax[axis] = t(localGetSupportingVertex(localAxis))[axis];
		aabbMin[axis] = t(localGetSupportingVertex(-localAxis))[axis];
	}
	aabbMin[3] = aabbMax[3] = btScalar(0);
}

void btConvexInternalShape::setLocalScaling(const btVector3& scaling)
{
	btAssert(caliber::isFinite(scaling));
	if (!caliber::isFinite(scaling)) return;
	m_localScaling = scaling.absolute();
}

void btConvexInternalShape::setMargin(btScalar margin)
{
	btAssert(margin >= btScalar(0) && btIsFinite(margin));
	m_collisionMargin = (margin >= btScalar(0) && btIsFinite(margin)) ? margin : btScalar(0);
}

void btConvexInternalShape::getPreferredPenetrationDirection(int index, btVector3& penetrationVector) const
{
	(void)index;
	btAssert(false && "getPreferredPenetrationDirection: this shape has none");
	penetrationVector.setValue(btScalar(0), btScalar(0), btScalar(0));
}

// ---- btConvexInternalAabbCachingShape -----------------------------------------------------------

btConvexInternalAabbCachingShape::btConvexInternalAabbCachingShape()
    : m_localAabbMin(btScalar(1), btScalar(1), btScalar(1)),
      m_localAabbMax(btScalar(-1), btScalar(-1), btScalar(-1)),
      m_isLocalAabbValid(false)
{
}

void btConvexInternalAabbCachingShape::getNonvirtualAabb(const btTransform& trans, btVector3& aabbMin,
                                                         btVector3& aabbMax, btScalar margin) const
{
	if (!caliber::checkAabbTransform(trans, aabbMin, aabbMax)) return;
	btAssert(m_isLocalAabbValid);
	if (!m_isLocalAabbValid)
	{
		// No cached box yet: fall back to the support function.
		getAabbSlow(trans, aabbMin, aabbMax);
		return;
	}
	btTransformAabb(m_localAabbMin, m_localAabbMax, margin, trans, aabbMin, aabbMax);
}

void btConvexInternalAabbCachingShape::setLocalScaling(const btVector3& scaling)
{
	btConvexInternalShape::setLocalScaling(scaling);
	recalcLocalAabb();
}

void btConvexInternalAabbCachingShape::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const
{
	getNonvirtualAabb(t, aabbMin, aabbMax, getMargin());
}

void btConvexInternalAabbCachingShape::recalcLocalAabb()
{
	btVector3 aabbMin, aabbMax;
	caliber::localAabbFromSupports(*this, aabbMin, aabbMax);
	setCachedLocalAabb(aabbMin, aabbMax);
}
