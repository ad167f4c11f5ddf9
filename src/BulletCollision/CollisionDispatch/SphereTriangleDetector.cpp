// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/SphereTriangleDetector.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btTriangleShape.h"
#include "BulletCollision/NarrowPhaseCollision/ClosestPointOnTriangle.h"

SphereTriangleDetector::SphereTriangleDetector(btSphereShape* sphere, btTriangleShape* triangle,
                                               btScalar contactBreakingThreshold)
    : m_sphere(sphere), m_triangle(triangle), m_contactBreakingThreshold(contactBreakingThreshold)
{
}

bool SphereTriangleDetector::collide(const btVector3& sphereCenter, btVector3& point, btVector3& resultNormal,
                                     btScalar& depth, btScalar& timeOfImpact, btScalar contactBreakingThreshold)
{
	timeOfImpact = btScalar(1);
	const btVector3& a = m_triangle->getVertexPtr(0);
	const btVector3& b = m_triangle->getVertexPtr(1);
	const btVector3& c = m_triangle->getVertexPtr(2);
	const btScalar radius = m_sphere->getRadius();

	point = caliber::closestPointOnTriangle(sphereCenter, a, b, c);
	const btVector3 offset = sphereCenter - point;
	const btScalar distance = offset.length();
	if (distance - radius > contactBreakingThreshold) return false;

	const btScalar scale = btMax(btMax((b - a).length(), (c - a).length()), btScalar(1));
	if (distance > SIMD_EPSILON * scale)
	{
		resultNormal = offset / distance;
	}
	else
	{
		// The centre lies on the triangle: push out along the face normal (any unit vector for a
		// degenerate triangle, which has no face to push through).
		btVector3 faceNormal = (b - a).cross(c - a);
		const btScalar normalLength = faceNormal.length();
		resultNormal = normalLength > SIMD_EPSILON ? faceNormal / normalLength : btVector3(0, 1, 0);
	}
	depth = distance - radius;
	return true;
}

void SphereTriangleDetector::getClosestPoints(const ClosestPointInput& input, Result& output, btIDebugDraw*,
                                              bool swapResults)
{
	const bool usable =
	    m_sphere && m_triangle && caliber::isFinite(input.m_transformA) && caliber::isFinite(input.m_transformB);
	btAssert(usable && "SphereTriangleDetector: null shape or non-finite transform");
	if (!usable) return;

	const btTransform& triangleTransform = input.m_transformB;
	const btVector3 centreInTriangle = triangleTransform.invXform(input.m_transformA.getOrigin());
	btVector3 point, normal;
	btScalar depth, timeOfImpact;
	if (!collide(centreInTriangle, point, normal, depth, timeOfImpact, m_contactBreakingThreshold)) return;

	const btVector3 normalWorld = triangleTransform.getBasis() * normal;
	const btVector3 pointWorld = triangleTransform(point);
	if (swapResults)
	{
		// Reported as (triangle, sphere): the normal points at the triangle, the point lies on the sphere.
		output.addContactPoint(-normalWorld, pointWorld + normalWorld * depth, depth);
	}
	else
	{
		output.addContactPoint(normalWorld, pointWorld, depth);
	}
}
