// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btCapsuleShape.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"

btCapsuleShape::btCapsuleShape() : m_upAxis(1), m_unscaledDimensions(0, 0, 0) { m_shapeType = CAPSULE_SHAPE_PROXYTYPE; }

btCapsuleShape::btCapsuleShape(btScalar radius, btScalar height) : m_upAxis(1), m_unscaledDimensions(0, 0, 0)
{
	m_shapeType = CAPSULE_SHAPE_PROXYTYPE;
	setDimensions(1, radius, height);
}

void btCapsuleShape::setDimensions(int upAxis, btScalar radius, btScalar height)
{
	m_upAxis = upAxis;
	const btScalar r = caliber::checkSize(radius);
	const btScalar halfHeight = btScalar(0.5) * caliber::checkSize(height);
	m_unscaledDimensions.setValue(r, r, r);
	m_unscaledDimensions[upAxis] = halfHeight;
	btCapsuleShape::setLocalScaling(m_localScaling);
}

void btCapsuleShape::setLocalScaling(const btVector3& scaling)
{
	btConvexInternalShape::setLocalScaling(scaling);
	m_implicitShapeDimensions = m_unscaledDimensions * m_localScaling;
	// The whole radius is the margin.
	m_collisionMargin = getRadius();
}

btVector3 btCapsuleShape::localGetSupportingVertexWithoutMargin(const btVector3& vec) const
{
	btVector3 end(0, 0, 0);
	// NaN compares false, so a NaN component picks the upper end like a perpendicular vec does.
	end[m_upAxis] = vec[m_upAxis] < btScalar(0) ? -getHalfHeight() : getHalfHeight();
	return end;
}

void btCapsuleShape::batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors,
                                                                       btVector3* supportVerticesOut,
                                                                       int numVectors) const
{
	for (int i = 0; i < numVectors; ++i) supportVerticesOut[i] = localGetSupportingVertexWithoutMargin(vectors[i]);
}

void btCapsuleShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const
{
	if (!caliber::checkMass(mass, inertia)) return;
	const btScalar r = getRadius();
	const btScalar h = btScalar(2) * getHalfHeight();  // cylinder length
	const btScalar cylinderVolume = SIMD_PI * r * r * h;
	const btScalar sphereVolume = btScalar(4.0 / 3.0) * SIMD_PI * r * r * r;
	const btScalar volume = cylinderVolume + sphereVolume;
	if (!(volume > btScalar(0)))
	{
		inertia.setValue(0, 0, 0);
		return;
	}
	const btScalar cylinderMass = mass * cylinderVolume / volume;
	const btScalar sphereMass = mass * sphereVolume / volume;  // both hemispheres
	// Axis: the cylinder's m r^2 / 2 plus a full sphere's 2/5 m r^2.
	const btScalar axial = cylinderMass * r * r * btScalar(0.5) + sphereMass * btScalar(0.4) * r * r;
	// Across: each hemisphere has 83/320 m r^2 about its own centre of mass, which lies 3r/8 from its flat
	// face, i.e. h/2 + 3r/8 from the capsule centre; the parallel-axis shift sums to
	// m (2/5 r^2 + h^2/4 + 3 h r / 8) for the pair.
	const btScalar across = cylinderMass * (r * r / btScalar(4) + h * h / btScalar(12)) +
	                        sphereMass * (btScalar(0.4) * r * r + h * h / btScalar(4) + btScalar(0.375) * h * r);
	inertia.setValue(across, across, across);
	inertia[m_upAxis] = axial;
}

void btCapsuleShape::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const
{
	if (!caliber::checkAabbTransform(t, aabbMin, aabbMax)) return;
	// The segment end points are +-halfHeight * (world up axis): their box, grown by the radius sphere.
	const btVector3 up = t.getBasis().getColumn(m_upAxis);
	const btScalar r = getRadius();
	const btVector3 extent = up.absolute() * getHalfHeight() + btVector3(r, r, r);
	aabbMin = t.getOrigin() - extent;
	aabbMax = t.getOrigin() + extent;
}

btCapsuleShapeX::btCapsuleShapeX(btScalar radius, btScalar height) { setDimensions(0, radius, height); }

btCapsuleShapeZ::btCapsuleShapeZ(btScalar radius, btScalar height) { setDimensions(2, radius, height); }
