// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btPolyhedralConvexShape.h"

#include "BulletCollision/CollisionShapes/ConvexHullMassProperties.h"
#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "LinearMath/btGeometryUtil.h"

btPolyhedralConvexShape::btPolyhedralConvexShape() : m_polyhedron(0) {}

btPolyhedralConvexShape::btPolyhedralConvexShape(const btPolyhedralConvexShape& other)
    : btConvexInternalShape(other), m_polyhedron(0)
{
	if (other.m_polyhedron) m_polyhedron = new btConvexPolyhedron(*other.m_polyhedron);
}

btPolyhedralConvexShape& btPolyhedralConvexShape::operator=(const btPolyhedralConvexShape& other)
{
	if (this == &other) return *this;
	btConvexInternalShape::operator=(other);
	delete m_polyhedron;
	m_polyhedron = other.m_polyhedron ? new btConvexPolyhedron(*other.m_polyhedron) : 0;
	return *this;
}

btPolyhedralConvexShape::~btPolyhedralConvexShape() { delete m_polyhedron; }

bool btPolyhedralConvexShape::initializePolyhedralFeatures(int shiftVerticesByMargin)
{
	btAlignedObjectArray<btVector3> vertices;
	vertices.resize(btMax(getNumVertices(), 0));
	for (int i = 0; i < vertices.size(); ++i) getVertex(i, vertices[i]);

	btConvexPolyhedron* poly = new btConvexPolyhedron();
	bool hasFaces = caliber::buildConvexPolyhedron(vertices.size() ? &vertices[0] : 0, vertices.size(), *poly);
	if (hasFaces && shiftVerticesByMargin && getMargin() > 0)
	{
		btAlignedObjectArray<btVector3> planes;
		for (int f = 0; f < poly->m_faces.size(); ++f)
		{
			const btFace& face = poly->m_faces[f];
			btVector3 plane(face.m_plane[0], face.m_plane[1], face.m_plane[2]);
			plane[3] = face.m_plane[3] - getMargin();
			planes.push_back(plane);
		}
		btAlignedObjectArray<btVector3> shifted;
		btGeometryUtil::getVerticesFromPlaneEquations(planes, shifted);
		// A flat hull's two planes bound nothing: keep the unshifted polygon then.
		btConvexPolyhedron shiftedPoly;
		if (shifted.size() >= 4 && caliber::buildConvexPolyhedron(&shifted[0], shifted.size(), shiftedPoly))
			*poly = shiftedPoly;
	}
	btAssert(hasFaces && "initializePolyhedralFeatures: fewer than 3 non-collinear vertices");
	delete m_polyhedron;
	m_polyhedron = 0;
	if (!hasFaces)
	{
		delete poly;
		return false;
	}
	m_polyhedron = poly;
	return true;
}

void btPolyhedralConvexShape::setPolyhedralFeatures(btConvexPolyhedron& polyhedron)
{
	if (m_polyhedron == &polyhedron) return;
	delete m_polyhedron;
	m_polyhedron = new btConvexPolyhedron(polyhedron);
}

btVector3 btPolyhedralConvexShape::localGetSupportingVertexWithoutMargin(const btVector3& vec) const
{
	const btVector3 dir = caliber::supportDirection(vec);
	btVector3 best(0, 0, 0);
	btScalar bestDot = -SIMD_INFINITY;
	bool found = false;
	const int count = getNumVertices();
	for (int i = 0; i < count; ++i)
	{
		btVector3 vertex;
		getVertex(i, vertex);
		const btScalar d = dir.dot(vertex);
		// NaN products never win, and an infinite vertex is never a usable support point.
		if ((!found || d > bestDot) && btIsFinite(d))
		{
			best = vertex;
			bestDot = d;
			found = true;
		}
	}
	return best;
}

void btPolyhedralConvexShape::batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors,
                                                                                btVector3* supportVerticesOut,
                                                                                int numVectors) const
{
	for (int j = 0; j < numVectors; ++j)
		supportVerticesOut[j] = btPolyhedralConvexShape::localGetSupportingVertexWithoutMargin(vectors[j]);
}

void btPolyhedralConvexShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const
{
	btAssert(mass >= 0 && btIsFinite(mass));
	inertia.setValue(0, 0, 0);
	if (!(mass >= 0 && btIsFinite(mass))) return;

	btAlignedObjectArray<btVector3> vertices;
	for (int i = 0; i < getNumVertices(); ++i)
	{
		btVector3 vertex;
		getVertex(i, vertex);
		if (caliber::isFinite(vertex)) vertices.push_back(vertex);
	}
	if (vertices.size() >= 4 && caliber::solidHullInertia(&vertices[0], vertices.size(), mass, inertia) &&
	    caliber::isFinite(inertia))
		return;

	// No volume: the solid box of the AABB grown by the margin (Bullet's formula), I = m (b^2 + c^2) / 12.
	btVector3 aabbMin(0, 0, 0), aabbMax(0, 0, 0);
	for (int i = 0; i < vertices.size(); ++i)
	{
		if (i == 0) aabbMin = aabbMax = vertices[0];
		aabbMin.setMin(vertices[i]);
		aabbMax.setMax(vertices[i]);
	}
	const btVector3 sides = (aabbMax - aabbMin) + btScalar(2) * btVector3(getMargin(), getMargin(), getMargin());
	const btVector3 s2 = sides * sides;
	inertia = (mass / btScalar(12)) * btVector3(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y());
}

// ---- btPolyhedralConvexAabbCachingShape ---------------------------------------------------------

btPolyhedralConvexAabbCachingShape::btPolyhedralConvexAabbCachingShape()
    : m_localAabbMin(1, 1, 1), m_localAabbMax(-1, -1, -1), m_isLocalAabbValid(false)
{
}

void btPolyhedralConvexAabbCachingShape::getNonvirtualAabb(const btTransform& trans, btVector3& aabbMin,
                                                           btVector3& aabbMax, btScalar margin) const
{
	if (!caliber::checkAabbTransform(trans, aabbMin, aabbMax)) return;
	btAssert(m_isLocalAabbValid);
	if (!m_isLocalAabbValid)
	{
		getAabbSlow(trans, aabbMin, aabbMax);
		return;
	}
	btTransformAabb(m_localAabbMin, m_localAabbMax, margin, trans, aabbMin, aabbMax);
}

void btPolyhedralConvexAabbCachingShape::setLocalScaling(const btVector3& scaling)
{
	btConvexInternalShape::setLocalScaling(scaling);
	recalcLocalAabb();
}

void btPolyhedralConvexAabbCachingShape::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const
{
	getNonvirtualAabb(t, aabbMin, aabbMax, getMargin());
}

void btPolyhedralConvexAabbCachingShape::recalcLocalAabb()
{
	btVector3 aabbMin, aabbMax;
	caliber::localAabbFromSupports(*this, aabbMin, aabbMax);
	setCachedLocalAabb(aabbMin, aabbMax);
}
