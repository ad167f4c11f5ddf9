// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btUniformScalingShape.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"

btUniformScalingShape::btUniformScalingShape(btConvexShape* convexChildShape, btScalar uniformScalingFactor)
    : m_childConvexShape(convexChildShape), m_uniformScalingFactor(caliber::sanitizeDimension(uniformScalingFactor))
{
	m_shapeType = UNIFORM_SCALING_SHAPE_PROXYTYPE;
	btAssert(convexChildShape != 0);
	btAssert(uniformScalingFactor >= 0 && btIsFinite(uniformScalingFactor));
}

btUniformScalingShape::~btUniformScalingShape() {}

btVector3 btUniformScalingShape::localGetSupportingVertexWithoutMargin(const btVector3& vec) const
{
	if (!m_childConvexShape) return btVector3(0, 0, 0);
	return m_childConvexShape->localGetSupportingVertexWithoutMargin(caliber::supportDirection(vec)) *
	       m_uniformScalingFactor;
}

btVector3 btUniformScalingShape::localGetSupportingVertex(const btVector3& vec) const
{
	if (!m_childConvexShape) return btVector3(0, 0, 0);
	return m_childConvexShape->localGetSupportingVertex(caliber::supportDirection(vec)) * m_uniformScalingFactor;
}

void btUniformScalingShape::batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors,
                                                                              btVector3* supportVerticesOut,
                                                                              int numVectors) const
{
	if (!m_childConvexShape)
	{
		for (int j = 0; j < numVectors; ++j) supportVerticesOut[j].setValue(0, 0, 0);
		return;
	}
	m_childConvexShape->batchedUnitVectorGetSupportingVertexWithoutMargin(vectors, supportVerticesOut, numVectors);
	for (int j = 0; j < numVectors; ++j) supportVerticesOut[j] *= m_uniformScalingFactor;
}

void btUniformScalingShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const
{
	inertia.setValue(0, 0, 0);
	if (!m_childConvexShape) return;
	btVector3 childInertia;
	m_childConvexShape->calculateLocalInertia(mass, childInertia);
	inertia = childInertia * (m_uniformScalingFactor * m_uniformScalingFactor);
}

void btUniformScalingShape::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const
{
	if (!caliber::checkAabbTransform(t, aabbMin, aabbMax)) return;
	if (!m_childConvexShape)
	{
		aabbMin = aabbMax = t.getOrigin();
		return;
	}
	// R (s x) + o = s (R x) + o: the child's box under the rotation alone, scaled, then moved.
	const btTransform rotation(t.getBasis(), btVector3(0, 0, 0));
	btVector3 childMin, childMax;
	m_childConvexShape->getAabb(rotation, childMin, childMax);
	aabbMin = childMin * m_uniformScalingFactor + t.getOrigin();
	aabbMax = childMax * m_uniformScalingFactor + t.getOrigin();
}

void btUniformScalingShape::getAabbSlow(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const
{
	if (!caliber::checkAabbTransform(t, aabbMin, aabbMax)) return;
	if (!m_childConvexShape)
	{
		aabbMin = aabbMax = t.getOrigin();
		return;
	}
	const btTransform rotation(t.getBasis(), btVector3(0, 0, 0));
	btVector3 childMin, childMax;
	m_childConvexShape->getAabbSlow(rotation, childMin, childMax);
	aabbMin = childMin * m_uniformScalingFactor + t.getOrigin();
	aabbMax = childMax * m_uniformScalingFactor + t.getOrigin();
}

void btUniformScalingShape::setLocalScaling(const btVector3& scaling)
{
	if (m_childConvexShape) m_childConvexShape->setLocalScaling(scaling);
}

const btVector3& btUniformScalingShape::getLocalScaling() const
{
	static const btVector3 unit(1, 1, 1);
	return m_childConvexShape ? m_childConvexShape->getLocalScaling() : unit;
}

void btUniformScalingShape::setMargin(btScalar margin)
{
	if (m_childConvexShape) m_childConvexShape->setMargin(margin);
}

btScalar btUniformScalingShape::getMargin() const
{
	return m_childConvexShape ? m_childConvexShape->getMargin() * m_uniformScalingFactor : btScalar(0);
}

int btUniformScalingShape::getNumPreferredPenetrationDirections() const
{
	return m_childConvexShape ? m_childConvexShape->getNumPreferredPenetrationDirections() : 0;
}

void btUniformScalingShape::getPreferredPenetrationDirection(int index, btVector3& penetrationVector) const
{
	if (!m_childConvexShape)
	{
		penetrationVector.setValue(0, 0, 0);
		return;
	}
	m_childConvexShape->getPreferredPenetrationDirection(index, penetrationVector);
}
