// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "HullShapes/MarginHullShape.h"

#include "LinearMath/btConvexHullComputer.h"

namespace caliber
{
std::unique_ptr<btConvexHullShape> makeMarginHullShape(const btAlignedObjectArray<btVector3>& corners)
{
	if (corners.size() < 4) return nullptr;
	std::unique_ptr<btConvexHullShape> shape(new btConvexHullShape());
	btConvexHullComputer hull;
	// The clamp limits the shrink to a quarter of the inner radius; the computer reports what it applied.
	const btScalar applied =
	    hull.compute(&corners[0][0], sizeof(btVector3), corners.size(), shape->getMargin(), btScalar(0.25));
	if (hull.faces.size() < 4 || !(applied > 0)) return nullptr;  // flat: no inner radius to shrink into
	shape->setMargin(applied);
	for (int i = 0; i < hull.vertices.size(); ++i) shape->addPoint(hull.vertices[i], false);
	shape->recalcLocalAabb();
	return shape;
}
}  // namespace caliber
