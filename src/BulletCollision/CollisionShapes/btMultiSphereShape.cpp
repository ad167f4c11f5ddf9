// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btMultiSphereShape.h"

#include "BulletCollision/CollisionShapes/ConvexHullMassProperties.h"
#include "BulletCollision/CollisionShapes/btShapeGuards.h"

btMultiSphereShape::btMultiSphereShape(const btVector3* positions, const btScalar* radi, int numSpheres)
{
	m_shapeType = MULTI_SPHERE_SHAPE_PROXYTYPE;
	const bool usable = numSpheres <= 0 || (positions != 0 && radi != 0);
	btAssert(usable);
	if (usable)
	{
		for (int i = 0; i < numSpheres; ++i)
		{
			btAssert(caliber::isFinite(positions[i]) && "btMultiSphereShape: non-finite centre");
			btAssert(radi[i] >= 0 && btIsFinite(radi[i]) && "btMultiSphereShape: bad radius");
			if (!caliber::isFinite(positions[i])) continue;
			m_localPositionArray.push_back(positions[i]);
			m_radiArray.push_back(caliber::sanitizeDimension(radi[i]));
		}
	}
	recalcLocalAabb();
}

const btVector3& btMultiSphereShape::getSpherePosition(int index) const
{
	static const btVector3 origin(0, 0, 0);
	btAssert(index >= 0 && index < m_localPositionArray.size());
	if (index < 0 || index >= m_localPositionArray.size()) return origin;
	return m_localPositionArray[index];
}

btScalar btMultiSphereShape::getSphereRadius(int index) const
{
	btAssert(index >= 0 && index < m_radiArray.size());
	if (index < 0 || index >= m_radiArray.size()) return 0;
	return m_radiArray[index];
}

btVector3 btMultiSphereShape::localGetSupportingVertexWithoutMargin(const btVector3& vec) const
{
	const int count = m_localPositionArray.size();
	if (count == 0) return btVector3(0, 0, 0);
	const btVector3 dir = caliber::supportDirection(vec).normalized();
	// Support of the ellipsoid c S + r S B along d: c S + r S (S d) / |S d|.
	const btVector3 scaledDir = dir * m_localScaling;
	const btScalar scaledLength = scaledDir.length();
	const btVector3 radial =
	    scaledLength > SIMD_EPSILON ? m_localScaling * scaledDir / scaledLength : btVector3(0, 0, 0);
	btVector3 best(0, 0, 0);
	btScalar bestDot = -SIMD_INFINITY;
	for (int i = 0; i < count; ++i)
	{
		const btVector3 p = m_localPositionArray[i] * m_localScaling + m_radiArray[i] * radial;
		const btScalar d = p.dot(dir);
		if (i == 0 || d > bestDot)
		{
			best = p;
			bestDot = d;
		}
	}
	return best - getMargin() * dir;
}

void btMultiSphereShape::batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors,
                                                                           btVector3* supportVerticesOut,
                                                                           int numVectors) const
{
	for (int j = 0; j < numVectors; ++j)
		supportVerticesOut[j] = btMultiSphereShape::localGetSupportingVertexWithoutMargin(vectors[j]);
}

void btMultiSphereShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const
{
	btAssert(mass >= 0 && btIsFinite(mass));
	inertia.setValue(0, 0, 0);
	if (!(mass >= 0 && btIsFinite(mass))) return;
	if (caliber::sampledSupportInertia(*this, mass, inertia) && caliber::isFinite(inertia)) return;
	caliber::aabbBoxInertia(*this, mass, inertia);
}
