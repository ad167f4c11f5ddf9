// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btSphereShape.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"

btSphereShape::btSphereShape(btScalar radius)
{
	m_shapeType = SPHERE_SHAPE_PROXYTYPE;
	setUnscaledRadius(radius);
}

void btSphereShape::setUnscaledRadius(btScalar radius)
{
	const btScalar r = caliber::checkSize(radius);
	m_implicitShapeDimensions.setValue(r, btScalar(0), btScalar(0));
	btConvexInternalShape::setMargin(r);
}

btVector3 btSphereShape::localGetSupportingVertex(const btVector3& vec) const
{
	btVector3 dir = caliber::supportDirection(vec);
	return getRadius() * dir.safeNormalize();
}

btVector3 btSphereShape::localGetSupportingVertexWithoutMargin(const btVector3& vec) const
{
	(void)vec;
	return btVector3(btScalar(0), btScalar(0), btScalar(0));
}

void btSphereShape::batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors,
                                                                      btVector3* supportVerticesOut,
                                                                      int numVectors) const
{
	(void)vectors;
	for (int i = 0; i < numVectors; ++i) supportVerticesOut[i].setValue(btScalar(0), btScalar(0), btScalar(0));
}

void btSphereShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const
{
	if (!caliber::checkMass(mass, inertia)) return;
	const btScalar r = getRadius();
	const btScalar i = btScalar(0.4) * mass * r * r;
	inertia.setValue(i, i, i);
}

void btSphereShape::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const
{
	if (!caliber::checkAabbTransform(t, aabbMin, aabbMax)) return;
	const btScalar r = getRadius();
	const btVector3 extent(r, r, r);
	aabbMin = t.getOrigin() - extent;
	aabbMax = t.getOrigin() + extent;
}
