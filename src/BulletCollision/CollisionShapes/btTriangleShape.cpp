// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btTriangleShape.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"

btTriangleShape::btTriangleShape()
{
	m_shapeType = TRIANGLE_SHAPE_PROXYTYPE;
	m_vertices1[0].setValue(0, 0, 0);
	m_vertices1[1].setValue(0, 0, 0);
	m_vertices1[2].setValue(0, 0, 0);
}

btTriangleShape::btTriangleShape(const btVector3& p0, const btVector3& p1, const btVector3& p2)
{
	m_shapeType = TRIANGLE_SHAPE_PROXYTYPE;
	m_vertices1[0] = p0;
	m_vertices1[1] = p1;
	m_vertices1[2] = p2;
}

void btTriangleShape::getEdge(int i, btVector3& pa, btVector3& pb) const
{
	const int a = caliber::triangleCornerIndex(i);
	pa = m_vertices1[a];
	pb = m_vertices1[(a + 1) % 3];
}

void btTriangleShape::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const
{
	getAabbSlow(t, aabbMin, aabbMax);
}

btVector3 btTriangleShape::localGetSupportingVertexWithoutMargin(const btVector3& dir) const
{
	const btVector3 d = caliber::supportDirection(dir);
	const btVector3 dots = d.dot3(m_vertices1[0], m_vertices1[1], m_vertices1[2]);
	int best = 0;
	if (dots.y() > dots[best]) best = 1;
	if (dots.z() > dots[best]) best = 2;
	return m_vertices1[best];
}

void btTriangleShape::batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors,
                                                                        btVector3* supportVerticesOut,
                                                                        int numVectors) const
{
	for (int j = 0; j < numVectors; ++j)
		supportVerticesOut[j] = btTriangleShape::localGetSupportingVertexWithoutMargin(vectors[j]);
}

void btTriangleShape::getPlane(btVector3& planeNormal, btVector3& planeSupport, int i) const
{
	getPlaneEquation(i, planeNormal, planeSupport);
}

void btTriangleShape::calcNormal(btVector3& normal) const
{
	const btVector3 e1 = m_vertices1[1] - m_vertices1[0];
	const btVector3 e2 = m_vertices1[2] - m_vertices1[0];
	const btVector3 n = e1.cross(e2);
	// Zero area relative to the edges' size (a cross product below rounding) means no direction.
	const btScalar scale = e1.length2() + e2.length2();
	const btScalar length2 = n.length2();
	if (!(length2 > SIMD_EPSILON * SIMD_EPSILON * scale * scale) || !btIsFinite(length2))
	{
		normal.setValue(0, 0, 0);
		return;
	}
	normal = n / btSqrt(length2);
}

void btTriangleShape::getPlaneEquation(int i, btVector3& planeNormal, btVector3& planeSupport) const
{
	(void)i;
	calcNormal(planeNormal);
	planeSupport = m_vertices1[0];
}

void btTriangleShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const
{
	(void)mass;
	inertia.setValue(0, 0, 0);
}

bool btTriangleShape::isInside(const btVector3& pt, btScalar tolerance) const
{
	btVector3 normal;
	calcNormal(normal);
	if (normal.isZero()) return false;
	const btScalar planeDistance = (pt - m_vertices1[0]).dot(normal);
	if (!(planeDistance >= -tolerance && planeDistance <= tolerance)) return false;
	for (int i = 0; i < 3; ++i)
	{
		const btVector3& a = m_vertices1[i];
		const btVector3& b = m_vertices1[(i + 1) % 3];
		// For a counter-clockwise triangle (seen along -normal) (b - a) x normal points out of edge ab.
		const btVector3 outward = (b - a).cross(normal).normalized();
		if ((pt - a).dot(outward) > tolerance) return false;
	}
	return true;
}

void btTriangleShape::getPreferredPenetrationDirection(int index, btVector3& penetrationVector) const
{
	calcNormal(penetrationVector);
	if (index != 0) penetrationVector = -penetrationVector;
}
