// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "LinearMath/btConvexHullComputer.h"

btConvexHullShape::btConvexHullShape(const btScalar* points, int numPoints, int stride)
{
	m_shapeType = CONVEX_HULL_SHAPE_PROXYTYPE;
	const bool usable = points != 0 && stride >= int(3 * sizeof(btScalar));
	btAssert(numPoints <= 0 || usable);
	if (usable && numPoints > 0)
	{
		m_unscaledPoints.reserve(numPoints);
		const unsigned char* bytes = reinterpret_cast<const unsigned char*>(points);
		for (int i = 0; i < numPoints; ++i)
		{
			const btScalar* p = reinterpret_cast<const btScalar*>(bytes + size_t(i) * size_t(stride));
			addPoint(btVector3(p[0], p[1], p[2]), false);
		}
	}
	recalcLocalAabb();
}

void btConvexHullShape::addPoint(const btVector3& point, bool recalculateLocalAabb)
{
	btAssert(caliberIsFinite(point) && "btConvexHullShape: non-finite point");
	if (caliberIsFinite(point))
	{
		m_unscaledPoints.push_back(point);
		m_unscaledPoints[m_unscaledPoints.size() - 1][3] = 0;
	}
	if (recalculateLocalAabb) recalcLocalAabb();
}

void btConvexHullShape::optimizeConvexHull()
{
	if (m_unscaledPoints.size() == 0) return;
	btConvexHullComputer hull;
	hull.compute(&m_unscaledPoints[0].x(), int(sizeof(btVector3)), m_unscaledPoints.size(), 0, 0);
	if (hull.vertices.size() == 0) return;
	m_unscaledPoints.resize(0);
	for (int i = 0; i < hull.vertices.size(); ++i) addPoint(hull.vertices[i], false);
	recalcLocalAabb();
}

btVector3 btConvexHullShape::localGetSupportingVertexWithoutMargin(const btVector3& vec) const
{
	if (m_unscaledPoints.size() == 0) return btVector3(0, 0, 0);
	// The support of S P along d is S times the support of P along S d (S diagonal).
	const btVector3 scaledDir = caliberSupportDirection(vec) * m_localScaling;
	btScalar best;
	const long index = scaledDir.maxDot(&m_unscaledPoints[0], m_unscaledPoints.size(), best);
	if (index < 0) return btVector3(0, 0, 0);
	return m_unscaledPoints[int(index)] * m_localScaling;
}

void btConvexHullShape::batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors,
                                                                          btVector3* supportVerticesOut,
                                                                          int numVectors) const
{
	for (int j = 0; j < numVectors; ++j)
		supportVerticesOut[j] = btConvexHullShape::localGetSupportingVertexWithoutMargin(vectors[j]);
}

int btConvexHullShape::getNumVertices() const { return m_unscaledPoints.size(); }

int btConvexHullShape::getNumEdges() const { return m_unscaledPoints.size(); }

void btConvexHullShape::getEdge(int i, btVector3& pa, btVector3& pb) const
{
	const int n = m_unscaledPoints.size();
	btAssert(i >= 0 && i < n);
	if (i < 0 || i >= n)
	{
		pa.setValue(0, 0, 0);
		pb.setValue(0, 0, 0);
		return;
	}
	pa = getScaledPoint(i);
	pb = getScaledPoint((i + 1) % n);
}

void btConvexHullShape::getVertex(int i, btVector3& vtx) const { vtx = getScaledPoint(i); }

int btConvexHullShape::getNumPlanes() const { return 0; }

void btConvexHullShape::getPlane(btVector3& planeNormal, btVector3& planeSupport, int i) const
{
	(void)i;
	btAssert(false && "btConvexHullShape::getPlane: the hull stores no planes");
	planeNormal.setValue(0, 0, 0);
	planeSupport.setValue(0, 0, 0);
}

bool btConvexHullShape::isInside(const btVector3& pt, btScalar tolerance) const
{
	(void)pt;
	(void)tolerance;
	btAssert(false && "btConvexHullShape::isInside is not supported");
	return false;
}
