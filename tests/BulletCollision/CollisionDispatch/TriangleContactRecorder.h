// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_TEST_TRIANGLE_CONTACT_RECORDER_H
#define CALIBER_TEST_TRIANGLE_CONTACT_RECORDER_H

// A result that records the points a convex-triangle contact function reports (tests only).

#include <vector>

#include "BulletCollision/NarrowPhaseCollision/btDiscreteCollisionDetectorInterface.h"

namespace caliber_test
{
struct TrianglePoint
{
	btVector3 normal;
	btVector3 onTriangle;
	btScalar distance;
};

struct TriangleContactRecorder : public btDiscreteCollisionDetectorInterface::Result
{
	std::vector<TrianglePoint> points;
	void setShapeIdentifiersA(int, int) override {}
	void setShapeIdentifiersB(int, int) override {}
	void addContactPoint(const btVector3& normal, const btVector3& onTriangle, btScalar distance) override
	{
		points.push_back(TrianglePoint{normal, onTriangle, distance});
	}
	/// The smallest distance reported (BT_LARGE_FLOAT when none).
	btScalar closest() const
	{
		btScalar best = BT_LARGE_FLOAT;
		for (const TrianglePoint& p : points) best = btMin(best, p.distance);
		return best;
	}
};
}  // namespace caliber_test

#endif  // CALIBER_TEST_TRIANGLE_CONTACT_RECORDER_H
