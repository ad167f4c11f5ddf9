// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btTetrahedronShape.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"

namespace
{
const int kEdgeEnds[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
}

btBU_Simplex1to4::btBU_Simplex1to4() : m_numVertices(0)
{
	m_shapeType = TETRAHEDRAL_SHAPE_PROXYTYPE;
	recalcLocalAabb();
}

btBU_Simplex1to4::btBU_Simplex1to4(const btVector3& pt0) : m_numVertices(0)
{
	m_shapeType = TETRAHEDRAL_SHAPE_PROXYTYPE;
	addVertex(pt0);
}

btBU_Simplex1to4::btBU_Simplex1to4(const btVector3& pt0, const btVector3& pt1) : m_numVertices(0)
{
	m_shapeType = TETRAHEDRAL_SHAPE_PROXYTYPE;
	addVertex(pt0);
	addVertex(pt1);
}

btBU_Simplex1to4::btBU_Simplex1to4(const btVector3& pt0, const btVector3& pt1, const btVector3& pt2) : m_numVertices(0)
{
	m_shapeType = TETRAHEDRAL_SHAPE_PROXYTYPE;
	addVertex(pt0);
	addVertex(pt1);
	addVertex(pt2);
}

btBU_Simplex1to4::btBU_Simplex1to4(const btVector3& pt0, const btVector3& pt1, const btVector3& pt2,
                                   const btVector3& pt3)
    : m_numVertices(0)
{
	m_shapeType = TETRAHEDRAL_SHAPE_PROXYTYPE;
	addVertex(pt0);
	addVertex(pt1);
	addVertex(pt2);
	addVertex(pt3);
}

void btBU_Simplex1to4::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const
{
	btPolyhedralConvexAabbCachingShape::getAabb(t, aabbMin, aabbMax);
}

void btBU_Simplex1to4::addVertex(const btVector3& pt)
{
	btAssert(m_numVertices < 4 && "btBU_Simplex1to4: already 4 vertices");
	btAssert(caliber::isFinite(pt) && "btBU_Simplex1to4: non-finite vertex");
	if (m_numVertices < 4 && caliber::isFinite(pt)) m_vertices[m_numVertices++] = pt;
	recalcLocalAabb();
}

int btBU_Simplex1to4::getNumEdges() const
{
	switch (m_numVertices)
	{
		case 2:
			return 1;
		case 3:
			return 3;
		case 4:
			return 6;
		default:
			return 0;
	}
}

void btBU_Simplex1to4::getEdge(int i, btVector3& pa, btVector3& pb) const
{
	btAssert(i >= 0 && i < getNumEdges());
	if (i < 0 || i >= getNumEdges())
	{
		pa.setValue(0, 0, 0);
		pb.setValue(0, 0, 0);
		return;
	}
	getVertex(kEdgeEnds[i][0], pa);
	getVertex(kEdgeEnds[i][1], pb);
}

void btBU_Simplex1to4::getVertex(int i, btVector3& vtx) const
{
	btAssert(i >= 0 && i < m_numVertices);
	if (i < 0 || i >= m_numVertices)
	{
		vtx.setValue(0, 0, 0);
		return;
	}
	vtx = m_vertices[i] * m_localScaling;
}

int btBU_Simplex1to4::getNumPlanes() const
{
	if (m_numVertices == 3) return 2;
	if (m_numVertices == 4) return 4;
	return 0;
}

void btBU_Simplex1to4::getPlane(btVector3& planeNormal, btVector3& planeSupport, int i) const
{
	planeNormal.setValue(0, 0, 0);
	planeSupport.setValue(0, 0, 0);
	btAssert(i >= 0 && i < getNumPlanes());
	if (i < 0 || i >= getNumPlanes()) return;
	btVector3 v[4];
	for (int k = 0; k < m_numVertices; ++k) getVertex(k, v[k]);
	btVector3 a, b, c, opposite(0, 0, 0);  // set for tetrahedra only; zeroed for g++'s -Wmaybe-uninitialized (TSan build)
	if (m_numVertices == 3)
	{
		a = v[0];
		b = v[1];
		c = v[2];
	}
	else
	{
		// Face i is the one without vertex i.
		int corners[3], n = 0;
		for (int k = 0; k < 4; ++k)
			if (k != i) corners[n++] = k;
		a = v[corners[0]];
		b = v[corners[1]];
		c = v[corners[2]];
		opposite = v[i];
	}
	btVector3 normal = (b - a).cross(c - a);
	const btScalar scale = (b - a).length2() + (c - a).length2();
	const btScalar length2 = normal.length2();
	planeSupport = a;
	if (!(length2 > SIMD_EPSILON * SIMD_EPSILON * scale * scale) || !btIsFinite(length2)) return;
	normal /= btSqrt(length2);
	if (m_numVertices == 3)
	{
		planeNormal = (i == 0) ? normal : -normal;
		return;
	}
	// Outward: the opposite vertex must be behind the face.
	planeNormal = (opposite - a).dot(normal) > 0 ? -normal : normal;
}

int btBU_Simplex1to4::getIndex(int i) const
{
	(void)i;
	return 0;
}

bool btBU_Simplex1to4::isInside(const btVector3& pt, btScalar tolerance) const
{
	if (m_numVertices != 4) return false;
	for (int i = 0; i < 4; ++i)
	{
		btVector3 normal, support;
		getPlane(normal, support, i);
		if (normal.isZero()) return false;
		if ((pt - support).dot(normal) > tolerance) return false;
	}
	return true;
}
