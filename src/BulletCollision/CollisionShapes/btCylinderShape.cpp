// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btCylinderShape.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"

btCylinderShape::btCylinderShape(const btVector3& halfExtents) : m_upAxis(1)
{
	m_shapeType = CYLINDER_SHAPE_PROXYTYPE;
	setDimensions(1, halfExtents);
}

void btCylinderShape::setDimensions(int upAxis, const btVector3& halfExtents)
{
	m_upAxis = upAxis;
	const btVector3 outer = caliber::checkSize(halfExtents) * m_localScaling;
	m_collisionMargin = CONVEX_DISTANCE_MARGIN;
	// A thin cylinder gets a margin of at most a tenth of its smallest used dimension.
	const btScalar smallest = btMin(outer[m_upAxis], outer[radiusAxis()]);
	if (btScalar(0.1) * smallest < m_collisionMargin) m_collisionMargin = btScalar(0.1) * smallest;
	const btScalar m = m_collisionMargin;
	m_implicitShapeDimensions = outer - btVector3(m, m, m);
	// The unused third half extent may be smaller than the margin; keep it non-negative.
	m_implicitShapeDimensions.setMax(btVector3(0, 0, 0));
}

void btCylinderShape::setMargin(btScalar collisionMargin)
{
	const btVector3 outer = getHalfExtentsWithMargin();
	btConvexInternalShape::setMargin(collisionMargin);
	const btScalar largestAllowed = btMin(outer[m_upAxis], outer[radiusAxis()]);
	if (m_collisionMargin > largestAllowed) m_collisionMargin = largestAllowed;
	const btScalar m = m_collisionMargin;
	m_implicitShapeDimensions = outer - btVector3(m, m, m);
	m_implicitShapeDimensions.setMax(btVector3(0, 0, 0));
}

void btCylinderShape::setLocalScaling(const btVector3& scaling)
{
	const btVector3 oldScaling = m_localScaling;
	const btVector3 outer = getHalfExtentsWithMargin();
	btConvexInternalShape::setLocalScaling(scaling);
	btVector3 newOuter(0, 0, 0);
	for (int axis = 0; axis < 3; ++axis)
	{
		// A zero old scaling has lost the unscaled size; the shape stays flat on that axis.
		newOuter[axis] =
		    oldScaling[axis] > btScalar(0) ? outer[axis] / oldScaling[axis] * m_localScaling[axis] : btScalar(0);
	}
	const btScalar m = btMin(m_collisionMargin, btMin(newOuter[m_upAxis], newOuter[radiusAxis()]));
	m_collisionMargin = m;
	m_implicitShapeDimensions = newOuter - btVector3(m, m, m);
	m_implicitShapeDimensions.setMax(btVector3(0, 0, 0));
}

btVector3 btCylinderShape::localGetSupportingVertexWithoutMargin(const btVector3& vec) const
{
	const int up = m_upAxis;
	const int a = (up + 1) % 3, b = (up + 2) % 3;
	const btScalar radius = m_implicitShapeDimensions[radiusAxis()];
	const btScalar halfHeight = m_implicitShapeDimensions[up];
	btVector3 result(0, 0, 0);
	result[up] = vec[up] < btScalar(0) ? -halfHeight : halfHeight;
	const btScalar radial = btSqrt(vec[a] * vec[a] + vec[b] * vec[b]);
	// For a direction along the axis every point of the cap is a support; the cap centre is chosen.
	// A NaN radial length compares false and lands there too.
	if (radial > SIMD_EPSILON * SIMD_EPSILON && radial <= SIMD_INFINITY)
	{
		const btScalar scale = radius / radial;
		result[a] = vec[a] * scale;
		result[b] = vec[b] * scale;
	}
	return result;
}

void btCylinderShape::batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors,
                                                                        btVector3* supportVerticesOut,
                                                                        int numVectors) const
{
	for (int i = 0; i < numVectors; ++i) supportVerticesOut[i] = localGetSupportingVertexWithoutMargin(vectors[i]);
}

void btCylinderShape::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const
{
	if (!caliber::checkAabbTransform(t, aabbMin, aabbMax)) return;
	// Core disc of radius r at +-h along the world axis u: on world axis i it reaches h |u_i| + r sqrt(1 - u_i^2);
	// the margin sphere adds m on every axis.
	const btVector3 up = t.getBasis().getColumn(m_upAxis);
	const btScalar r = m_implicitShapeDimensions[radiusAxis()];
	const btScalar h = m_implicitShapeDimensions[m_upAxis];
	const btScalar m = getMargin();
	btVector3 extent(0, 0, 0);
	for (int axis = 0; axis < 3; ++axis)
	{
		const btScalar u = up[axis];
		const btScalar across = btScalar(1) - u * u;
		extent[axis] = h * btFabs(u) + r * btSqrt(across > btScalar(0) ? across : btScalar(0)) + m;
	}
	aabbMin = t.getOrigin() - extent;
	aabbMax = t.getOrigin() + extent;
}

void btCylinderShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const
{
	if (!caliber::checkMass(mass, inertia)) return;
	const btVector3 outer = getHalfExtentsWithMargin();
	const btScalar r = outer[radiusAxis()];
	const btScalar fullHeight = btScalar(2) * outer[m_upAxis];
	const btScalar axial = mass * r * r * btScalar(0.5);
	const btScalar across = mass * (btScalar(3) * r * r + fullHeight * fullHeight) / btScalar(12);
	inertia.setValue(across, across, across);
	inertia[m_upAxis] = axial;
}

btCylinderShapeX::btCylinderShapeX(const btVector3& halfExtents) : btCylinderShape(halfExtents)
{
	setDimensions(0, halfExtents);
}

btCylinderShapeZ::btCylinderShapeZ(const btVector3& halfExtents) : btCylinderShape(halfExtents)
{
	setDimensions(2, halfExtents);
}
