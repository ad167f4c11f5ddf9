// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btStaticPlaneShape.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"

btStaticPlaneShape::btStaticPlaneShape(const btVector3& planeNormal, btScalar planeConstant)
    : m_localAabbMin(-BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT),
      m_localAabbMax(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT),
      m_planeNormal(planeNormal),
      m_planeConstant(planeConstant),
      m_localScaling(btScalar(1), btScalar(1), btScalar(1))
{
	m_shapeType = STATIC_PLANE_PROXYTYPE;
	const bool normalValid = caliber::isFinite(planeNormal) && !planeNormal.fuzzyZero();
	btAssert(normalValid && "btStaticPlaneShape: zero or non-finite normal");
	if (normalValid)
		m_planeNormal.safeNormalize();
	else
		m_planeNormal.setValue(btScalar(1), btScalar(0), btScalar(0));
	btAssert(btIsFinite(planeConstant) && "btStaticPlaneShape: non-finite constant");
	if (!btIsFinite(planeConstant)) m_planeConstant = btScalar(0);
}

btStaticPlaneShape::~btStaticPlaneShape() {}

void btStaticPlaneShape::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const
{
	(void)t;
	aabbMin = m_localAabbMin;
	aabbMax = m_localAabbMax;
}

void btStaticPlaneShape::processAllTriangles(btTriangleCallback* callback, const btVector3& aabbMin,
                                             const btVector3& aabbMax) const
{
	const bool boxValid = caliber::isFinite(aabbMin) && caliber::isFinite(aabbMax);
	btAssert(boxValid && callback);
	if (!boxValid || !callback) return;

	const btVector3 halfExtents = (aabbMax - aabbMin) * btScalar(0.5);
	const btScalar radius = halfExtents.length();
	const btVector3 center = (aabbMax + aabbMin) * btScalar(0.5);

	// Two in-plane unit tangents with tangent0 x tangent1 = normal, so corners in the order
	// (-,-), (+,-), (+,+), (-,+) run counter-clockwise seen from the normal side.
	btVector3 tangent0, tangent1;
	btPlaneSpace1(m_planeNormal, tangent0, tangent1);
	if (tangent0.cross(tangent1).dot(m_planeNormal) < btScalar(0)) btSwap(tangent0, tangent1);

	const btVector3 projectedCenter = center - (m_planeNormal.dot(center) - m_planeConstant) * m_planeNormal;
	const btVector3 u = tangent0 * radius, v = tangent1 * radius;

	btVector3 triangle[3];
	triangle[0] = projectedCenter - u - v;
	triangle[1] = projectedCenter + u - v;
	triangle[2] = projectedCenter + u + v;
	callback->processTriangle(triangle, 0, 0);

	triangle[0] = projectedCenter - u - v;
	triangle[1] = projectedCenter + u + v;
	triangle[2] = projectedCenter - u + v;
	callback->processTriangle(triangle, 0, 1);
}

void btStaticPlaneShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const
{
	(void)mass;
	inertia.setValue(btScalar(0), btScalar(0), btScalar(0));
}

void btStaticPlaneShape::setLocalScaling(const btVector3& scaling)
{
	btAssert(caliber::isFinite(scaling));
	if (caliber::isFinite(scaling)) m_localScaling = scaling;
}
