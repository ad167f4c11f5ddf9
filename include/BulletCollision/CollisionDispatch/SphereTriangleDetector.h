// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SPHERE_TRIANGLE_DETECTOR_H
#define BT_SPHERE_TRIANGLE_DETECTOR_H

/// SphereTriangleDetector: the exact contact of a sphere and a (two-sided) triangle.

#include "BulletCollision/NarrowPhaseCollision/btDiscreteCollisionDetectorInterface.h"

class btSphereShape;
class btTriangleShape;

/// Finds the closest point of a triangle to a sphere's centre (face, edge or vertex region) and reports
/// one point when the sphere surface is within the breaking threshold: the normal from the triangle
/// towards the centre (the face normal, on the centre's side, when the centre lies in the triangle), the
/// point on the triangle and distance - radius. The triangle is thin (its margin is not added), and both
/// faces collide. A degenerate (zero-area) triangle is treated as its edges.
struct SphereTriangleDetector : public btDiscreteCollisionDetectorInterface
{
	/// Reports the contact of the sphere (transform A) and the triangle (transform B); with swapResults
	/// the pair is reported as (triangle, sphere).
	void getClosestPoints(const ClosestPointInput& input, Result& output, btIDebugDraw* debugDraw,
	                      bool swapResults = false) override;

	/// A detector for the pair; contactBreakingThreshold is how far apart points are still reported.
	SphereTriangleDetector(btSphereShape* sphere, btTriangleShape* triangle, btScalar contactBreakingThreshold);
	/// Nothing is owned.
	~SphereTriangleDetector() override {}

	/// The contact for a centre given in the triangle's frame: point on the triangle, normal towards the
	/// centre and signed distance. timeOfImpact is set to 1 (no motion is considered). Returns false when
	/// the sphere is farther than contactBreakingThreshold.
	bool collide(const btVector3& sphereCenter, btVector3& point, btVector3& resultNormal, btScalar& depth,
	             btScalar& timeOfImpact, btScalar contactBreakingThreshold);

private:
	btSphereShape* m_sphere;
	btTriangleShape* m_triangle;
	btScalar m_contactBreakingThreshold;
};

#endif  // BT_SPHERE_TRIANGLE_DETECTOR_H
