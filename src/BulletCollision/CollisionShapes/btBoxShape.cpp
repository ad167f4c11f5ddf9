// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btBoxShape.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"

namespace
{
// The corner of the centred box of half extents h in the octant of vec (negative side for 0 or NaN).
SIMD_FORCE_INLINE btVector3 boxCorner(const btVector3& h, const btVector3& vec)
{
	return btVector3(vec.x() > btScalar(0) ? h.x() : -h.x(), vec.y() > btScalar(0) ? h.y() : -h.y(),
	                 vec.z() > btScalar(0) ? h.z() : -h.z());
}
}  // namespace

btBoxShape::btBoxShape(const btVector3& boxHalfExtents)
{
	m_shapeType = BOX_SHAPE_PROXYTYPE;
	const btVector3 outer = caliber::checkSize(boxHalfExtents) * m_localScaling;
	setSafeMargin(outer);
	const btScalar m = getMargin();
	m_implicitShapeDimensions = outer - btVector3(m, m, m);
}

btVector3 btBoxShape::localGetSupportingVertex(const btVector3& vec) const
{
	return boxCorner(getHalfExtentsWithMargin(), vec);
}

btVector3 btBoxShape::localGetSupportingVertexWithoutMargin(const btVector3& vec) const
{
	return boxCorner(m_implicitShapeDimensions, vec);
}

void btBoxShape::batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors,
                                                                   btVector3* supportVerticesOut, int numVectors) const
{
	for (int i = 0; i < numVectors; ++i) supportVerticesOut[i] = boxCorner(m_implicitShapeDimensions, vectors[i]);
}

void btBoxShape::setMargin(btScalar collisionMargin)
{
	const btVector3 outer = getHalfExtentsWithMargin();
	btConvexInternalShape::setMargin(collisionMargin);
	const btScalar largestAllowed = outer[outer.minAxis()];
	if (m_collisionMargin > largestAllowed) m_collisionMargin = largestAllowed;
	const btScalar m = m_collisionMargin;
	m_implicitShapeDimensions = outer - btVector3(m, m, m);
}

void btBoxShape::setLocalScaling(const btVector3& scaling)
{
	const btVector3 oldScaling = m_localScaling;
	const btVector3 outer = getHalfExtentsWithMargin();
	btConvexInternalShape::setLocalScaling(scaling);
	btVector3 newOuter(0, 0, 0);
	for (int axis = 0; axis < 3; ++axis)
	{
		// A zero old scaling has lost the unscaled size; the box stays flat on that axis.
		newOuter[axis] =
		    oldScaling[axis] > btScalar(0) ? outer[axis] / oldScaling[axis] * m_localScaling[axis] : btScalar(0);
	}
	const btScalar m = btMin(m_collisionMargin, newOuter[newOuter.minAxis()]);
	m_collisionMargin = m;
	m_implicitShapeDimensions = newOuter - btVector3(m, m, m);
}

void btBoxShape::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const
{
	if (!caliber::checkAabbTransform(t, aabbMin, aabbMax)) return;
	btTransformAabb(getHalfExtentsWithMargin(), btScalar(0), t, aabbMin, aabbMax);
}

void btBoxShape::getBoundingSphere(btVector3& center, btScalar& radius) const
{
	center.setValue(btScalar(0), btScalar(0), btScalar(0));
	radius = getHalfExtentsWithMargin().length();
}

void btBoxShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const
{
	if (!caliber::checkMass(mass, inertia)) return;
	const btVector3 sides = btScalar(2) * getHalfExtentsWithMargin();
	const btScalar x2 = sides.x() * sides.x(), y2 = sides.y() * sides.y(), z2 = sides.z() * sides.z();
	const btScalar k = mass / btScalar(12);
	inertia.setValue(k * (y2 + z2), k * (x2 + z2), k * (x2 + y2));
}

void btBoxShape::getPlane(btVector3& planeNormal, btVector3& planeSupport, int i) const
{
	btVector4 plane;
	getPlaneEquation(plane, i);
	planeNormal.setValue(plane.x(), plane.y(), plane.z());
	// The corner farthest along the normal lies on this face of the full box.
	planeSupport = localGetSupportingVertex(planeNormal);
}

void btBoxShape::getVertex(int i, btVector3& vtx) const
{
	btAssert(i >= 0 && i < 8);
	const btVector3 h = getHalfExtentsWithMargin();
	vtx.setValue((i & 1) ? -h.x() : h.x(), (i & 2) ? -h.y() : h.y(), (i & 4) ? -h.z() : h.z());
}

void btBoxShape::getPlaneEquation(btVector4& plane, int i) const
{
	btAssert(i >= 0 && i < 6);
	if (i < 0 || i >= 6) i = 0;
	const btVector3& h = m_implicitShapeDimensions;
	const int axis = i >> 1;
	const btScalar sign = (i & 1) ? btScalar(-1) : btScalar(1);
	btVector3 normal(0, 0, 0);
	normal[axis] = sign;
	plane = btVector4(normal);
	plane.setW(-h[axis]);
}

void btBoxShape::getEdge(int i, btVector3& pa, btVector3& pb) const
{
	btAssert(i >= 0 && i < 12);
	// Edges join corners that differ in one bit: edges 0..3 run along x, 4..7 along y, 8..11 along z.
	static const int edgeCorners[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
	                                       {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
	const int edge = (i >= 0 && i < 12) ? i : 0;
	getVertex(edgeCorners[edge][0], pa);
	getVertex(edgeCorners[edge][1], pb);
}

bool btBoxShape::isInside(const btVector3& pt, btScalar tolerance) const
{
	const btVector3& h = m_implicitShapeDimensions;
	return btFabs(pt.x()) <= h.x() + tolerance && btFabs(pt.y()) <= h.y() + tolerance &&
	       btFabs(pt.z()) <= h.z() + tolerance;
}

void btBoxShape::getPreferredPenetrationDirection(int index, btVector3& penetrationVector) const
{
	btAssert(index >= 0 && index < 6);
	penetrationVector.setValue(0, 0, 0);
	if (index < 0 || index >= 6) return;
	penetrationVector[index >> 1] = (index & 1) ? btScalar(-1) : btScalar(1);
}
