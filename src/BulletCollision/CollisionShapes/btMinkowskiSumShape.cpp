// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btMinkowskiSumShape.h"

#include "BulletCollision/CollisionShapes/ConvexHullMassProperties.h"
#include "BulletCollision/CollisionShapes/btShapeGuards.h"

btMinkowskiSumShape::btMinkowskiSumShape(const btConvexShape* shapeA, const btConvexShape* shapeB)
    : m_transA(btTransform::getIdentity()), m_transB(btTransform::getIdentity()), m_shapeA(shapeA), m_shapeB(shapeB)
{
	m_shapeType = MINKOWSKI_SUM_SHAPE_PROXYTYPE;
	btAssert(shapeA != 0 && shapeB != 0);
}

btVector3 btMinkowskiSumShape::localGetSupportingVertexWithoutMargin(const btVector3& vec) const
{
	const btVector3 dir = caliber::supportDirection(vec);
	// A child's support is queried in its own frame: the direction rotated by the inverse basis.
	const btVector3 supportA =
	    m_shapeA ? m_transA(m_shapeA->localGetSupportingVertexWithoutMargin(dir * m_transA.getBasis()))
	             : m_transA.getOrigin();
	// Bullet's convention: B enters negated, so the shape is A + (-B), the configuration-space
	// obstacle that convex casts and GJK work with; B's support is taken along -dir.
	const btVector3 supportB =
	    m_shapeB ? m_transB(m_shapeB->localGetSupportingVertexWithoutMargin(-dir * m_transB.getBasis()))
	             : m_transB.getOrigin();
	return supportA - supportB;
}

void btMinkowskiSumShape::batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors,
                                                                            btVector3* supportVerticesOut,
                                                                            int numVectors) const
{
	for (int j = 0; j < numVectors; ++j)
		supportVerticesOut[j] = btMinkowskiSumShape::localGetSupportingVertexWithoutMargin(vectors[j]);
}

void btMinkowskiSumShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const
{
	btAssert(mass >= 0 && btIsFinite(mass));
	inertia.setValue(0, 0, 0);
	if (!(mass >= 0 && btIsFinite(mass))) return;
	if (caliber::sampledSupportInertia(*this, mass, inertia) && caliber::isFinite(inertia)) return;
	caliber::aabbBoxInertia(*this, mass, inertia);
}

btScalar btMinkowskiSumShape::getMargin() const
{
	return (m_shapeA ? m_shapeA->getMargin() : btScalar(0)) + (m_shapeB ? m_shapeB->getMargin() : btScalar(0));
}
