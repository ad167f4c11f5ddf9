// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btConeShape.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"

namespace
{
// The scaled radius, height and sine of the half angle from the unscaled sizes, which the cone keeps
// in m_implicitShapeDimensions as Bullet does (the radius on the two radial axes, the height on the up
// axis): rescaling from them never accumulates rounding or loses a size to a zero scale.
void scaledConeSizes(const btVector3& unscaled, const btVector3& scaling, const int* coneIndices, btScalar& radius,
                     btScalar& height, btScalar& sinAngle)
{
	const int up = coneIndices[1];
	const btScalar radialScale = btScalar(0.5) * (scaling[coneIndices[0]] + scaling[coneIndices[2]]);
	radius = unscaled[coneIndices[0]] * radialScale;
	height = unscaled[up] * scaling[up];
	const btScalar slant = btSqrt(radius * radius + height * height);
	sinAngle = slant > btScalar(0) ? radius / slant : btScalar(0);
}

btVector3 unscaledConeDimensions(btScalar radius, btScalar height, int up)
{
	btVector3 dimensions(radius, radius, radius);
	dimensions[up] = height;
	return dimensions;
}
}  // namespace

btConeShape::btConeShape(btScalar radius, btScalar height) : m_sinAngle(0), m_radius(0), m_height(0)
{
	m_shapeType = CONE_SHAPE_PROXYTYPE;
	m_coneIndices[0] = 0;
	m_coneIndices[1] = 1;
	m_coneIndices[2] = 2;
	m_implicitShapeDimensions = unscaledConeDimensions(caliber::checkSize(radius), caliber::checkSize(height), 1);
	scaledConeSizes(m_implicitShapeDimensions, m_localScaling, m_coneIndices, m_radius, m_height, m_sinAngle);
}

void btConeShape::setRadius(btScalar radius)
{
	const btScalar r = caliber::checkSize(radius);
	const btScalar radialScale = btScalar(0.5) * (m_localScaling[m_coneIndices[0]] + m_localScaling[m_coneIndices[2]]);
	const btScalar unscaledRadius = radialScale > btScalar(0) ? r / radialScale : r;
	m_implicitShapeDimensions =
	    unscaledConeDimensions(unscaledRadius, m_implicitShapeDimensions[m_coneIndices[1]], m_coneIndices[1]);
	scaledConeSizes(m_implicitShapeDimensions, m_localScaling, m_coneIndices, m_radius, m_height, m_sinAngle);
	m_radius = r;  // exactly what was asked for, even where scaling rounds
}

void btConeShape::setHeight(btScalar height)
{
	const btScalar h = caliber::checkSize(height);
	const int up = m_coneIndices[1];
	const btScalar axialScale = m_localScaling[up];
	m_implicitShapeDimensions[up] = axialScale > btScalar(0) ? h / axialScale : h;
	scaledConeSizes(m_implicitShapeDimensions, m_localScaling, m_coneIndices, m_radius, m_height, m_sinAngle);
	m_height = h;
}

void btConeShape::setConeUpIndex(int upIndex)
{
	btAssert(upIndex >= 0 && upIndex <= 2);
	const btScalar oldUnscaledRadius = m_implicitShapeDimensions[m_coneIndices[0]];
	const btScalar oldUnscaledHeight = m_implicitShapeDimensions[m_coneIndices[1]];
	switch (upIndex)
	{
		case 0:
			m_coneIndices[0] = 1;
			m_coneIndices[1] = 0;
			m_coneIndices[2] = 2;
			break;
		case 1:
			m_coneIndices[0] = 0;
			m_coneIndices[1] = 1;
			m_coneIndices[2] = 2;
			break;
		case 2:
			m_coneIndices[0] = 0;
			m_coneIndices[1] = 2;
			m_coneIndices[2] = 1;
			break;
		default:
			return;
	}
	// The sizes follow the axis: the radius moves to the new radial axes, the height to the new up axis.
	m_implicitShapeDimensions = unscaledConeDimensions(oldUnscaledRadius, oldUnscaledHeight, m_coneIndices[1]);
	scaledConeSizes(m_implicitShapeDimensions, m_localScaling, m_coneIndices, m_radius, m_height, m_sinAngle);
}

void btConeShape::setLocalScaling(const btVector3& scaling)
{
	btConvexInternalShape::setLocalScaling(scaling);
	scaledConeSizes(m_implicitShapeDimensions, m_localScaling, m_coneIndices, m_radius, m_height, m_sinAngle);
}

btVector3 btConeShape::localGetSupportingVertexWithoutMargin(const btVector3& vec) const
{
	const int up = m_coneIndices[1], a = m_coneIndices[0], b = m_coneIndices[2];
	const btScalar halfHeight = btScalar(0.5) * m_height;
	btVector3 result(0, 0, 0);
	// The apex wins when the direction is within the cone's half angle of the axis, measured as
	// vec_up > |vec| sin(half angle) (the apex's projection beats every rim point's).
	const btScalar length = vec.length();
	if (vec[up] > length * m_sinAngle)
	{
		result[up] = halfHeight;
		return result;
	}
	result[up] = -halfHeight;
	const btScalar radial = btSqrt(vec[a] * vec[a] + vec[b] * vec[b]);
	// NaN or zero radial length: the centre of the base (a support for vec straight down).
	if (radial > SIMD_EPSILON * SIMD_EPSILON && radial <= SIMD_INFINITY)
	{
		const btScalar scale = m_radius / radial;
		result[a] = vec[a] * scale;
		result[b] = vec[b] * scale;
	}
	return result;
}

void btConeShape::batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors,
                                                                    btVector3* supportVerticesOut, int numVectors) const
{
	for (int i = 0; i < numVectors; ++i) supportVerticesOut[i] = localGetSupportingVertexWithoutMargin(vectors[i]);
}

void btConeShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const
{
	if (!caliber::checkMass(mass, inertia)) return;
	const btScalar r = m_radius, h = m_height;
	const btScalar axial = btScalar(0.3) * mass * r * r;
	const btScalar across = mass * (btScalar(0.15) * r * r + btScalar(0.0375) * h * h);
	inertia.setValue(across, across, across);
	inertia[m_coneIndices[1]] = axial;
}

btConeShapeX::btConeShapeX(btScalar radius, btScalar height) : btConeShape(radius, height) { setConeUpIndex(0); }

btConeShapeZ::btConeShapeZ(btScalar radius, btScalar height) : btConeShape(radius, height) { setConeUpIndex(2); }
