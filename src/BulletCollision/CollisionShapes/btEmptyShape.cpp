// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btEmptyShape.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"

btEmptyShape::btEmptyShape() : m_localScaling(btScalar(1), btScalar(1), btScalar(1))
{
	m_shapeType = EMPTY_SHAPE_PROXYTYPE;
}

btEmptyShape::~btEmptyShape() {}

void btEmptyShape::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const
{
	if (!caliber::checkAabbTransform(t, aabbMin, aabbMax)) return;
	const btScalar m = getMargin();
	const btVector3 margin(m, m, m);
	aabbMin = t.getOrigin() - margin;
	aabbMax = t.getOrigin() + margin;
}

void btEmptyShape::setLocalScaling(const btVector3& scaling)
{
	btAssert(caliber::isFinite(scaling));
	if (caliber::isFinite(scaling)) m_localScaling = scaling;
}

void btEmptyShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const
{
	(void)mass;
	inertia.setValue(btScalar(0), btScalar(0), btScalar(0));
}
