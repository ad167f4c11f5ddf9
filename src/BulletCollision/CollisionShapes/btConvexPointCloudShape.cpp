// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btConvexPointCloudShape.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"

btConvexPointCloudShape::btConvexPointCloudShape() : m_unscaledPoints(0), m_numPoints(0)
{
	m_shapeType = CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE;
	recalcLocalAabb();
}

btConvexPointCloudShape::btConvexPointCloudShape(btVector3* points, int numPoints, const btVector3& localScaling,
                                                 bool computeAabb)
    : m_unscaledPoints(0), m_numPoints(0)
{
	m_shapeType = CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE;
	setPoints(points, numPoints, computeAabb, localScaling);
}

void btConvexPointCloudShape::setPoints(btVector3* points, int numPoints, bool computeAabb,
                                        const btVector3& localScaling)
{
	const bool usable = numPoints >= 0 && (points != 0 || numPoints == 0);
	btAssert(usable);
	m_unscaledPoints = usable ? points : 0;
	m_numPoints = usable ? numPoints : 0;
#if CALIBER_ASSERTS_ENABLED
	for (int i = 0; i < m_numPoints; ++i) btAssert(caliber::isFinite(m_unscaledPoints[i]) && "non-finite point");
#endif
	btConvexInternalShape::setLocalScaling(localScaling);
	if (computeAabb) recalcLocalAabb();
}

btVector3 btConvexPointCloudShape::getScaledPoint(int index) const
{
	btAssert(index >= 0 && index < m_numPoints);
	if (index < 0 || index >= m_numPoints) return btVector3(0, 0, 0);
	return m_unscaledPoints[index] * m_localScaling;
}

btVector3 btConvexPointCloudShape::localGetSupportingVertexWithoutMargin(const btVector3& vec) const
{
	if (m_numPoints <= 0) return btVector3(0, 0, 0);
	const btVector3 scaledDir = caliber::supportDirection(vec) * m_localScaling;
	btScalar best;
	const long index = scaledDir.maxDot(m_unscaledPoints, m_numPoints, best);
	if (index >= 0 && btIsFinite(best) && caliber::isFinite(m_unscaledPoints[index]))
		return m_unscaledPoints[index] * m_localScaling;
	// Some point is infinite (or none is finite): scan again over the finite points only.
	btVector3 support(0, 0, 0);
	bool found = false;
	for (int i = 0; i < m_numPoints; ++i)
	{
		if (!caliber::isFinite(m_unscaledPoints[i])) continue;
		const btScalar d = scaledDir.dot(m_unscaledPoints[i]);
		if (!found || d > best)
		{
			best = d;
			support = m_unscaledPoints[i];
			found = true;
		}
	}
	return support * m_localScaling;
}

void btConvexPointCloudShape::batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors,
                                                                                btVector3* supportVerticesOut,
                                                                                int numVectors) const
{
	for (int j = 0; j < numVectors; ++j)
		supportVerticesOut[j] = btConvexPointCloudShape::localGetSupportingVertexWithoutMargin(vectors[j]);
}

int btConvexPointCloudShape::getNumVertices() const { return m_numPoints; }

int btConvexPointCloudShape::getNumEdges() const { return m_numPoints; }

void btConvexPointCloudShape::getEdge(int i, btVector3& pa, btVector3& pb) const
{
	btAssert(i >= 0 && i < m_numPoints);
	if (i < 0 || i >= m_numPoints)
	{
		pa.setValue(0, 0, 0);
		pb.setValue(0, 0, 0);
		return;
	}
	pa = getScaledPoint(i);
	pb = getScaledPoint((i + 1) % m_numPoints);
}

void btConvexPointCloudShape::getVertex(int i, btVector3& vtx) const { vtx = getScaledPoint(i); }

int btConvexPointCloudShape::getNumPlanes() const { return 0; }

void btConvexPointCloudShape::getPlane(btVector3& planeNormal, btVector3& planeSupport, int i) const
{
	(void)i;
	btAssert(false && "btConvexPointCloudShape::getPlane: no planes are stored");
	planeNormal.setValue(0, 0, 0);
	planeSupport.setValue(0, 0, 0);
}

bool btConvexPointCloudShape::isInside(const btVector3& pt, btScalar tolerance) const
{
	(void)pt;
	(void)tolerance;
	btAssert(false && "btConvexPointCloudShape::isInside is not supported");
	return false;
}
