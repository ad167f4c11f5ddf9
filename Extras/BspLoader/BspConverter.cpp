// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BspLoader/BspConverter.h"

#include <cmath>

#include "HullShapes/MarginHullShape.h"
#include "LinearMath/btConvexHullComputer.h"
#include "LinearMath/btGeometryUtil.h"

namespace caliber
{
namespace
{
// How far (as a unit-normal offset) the origin must lie inside the hull of the normals for the planes to
// count as closed. A brush open by less than this in some direction would be a sliver hundreds of times
// longer than wide, which no level meant.
const double kClosedMargin = 1e-3;

// Intersection of half-spaces n.p + w <= 0 is bounded exactly when no direction u has n.u <= 0 for every
// plane, that is when the origin lies strictly inside the convex hull of the normals.
bool planesAreClosed(const btAlignedObjectArray<btVector3>& planes)
{
	btAlignedObjectArray<btVector3> normals;
	for (int i = 0; i < planes.size(); ++i) normals.push_back(btVector3(planes[i].x(), planes[i].y(), planes[i].z()));
	btAlignedObjectArray<btVector3> normalHull;
	btGeometryUtil::getPlaneEquationsFromVertices(normals, normalHull);
	if (normalHull.size() < 4) return false;  // the normals are flat (or fewer than 4): open along their plane
	for (int i = 0; i < normalHull.size(); ++i)
		if (!(normalHull[i].w() < -kClosedMargin)) return false;
	return true;
}
}  // namespace

bool brushToConvexVertices(const btAlignedObjectArray<btVector3>& planes, btAlignedObjectArray<btVector3>& vertices,
                           std::string& why)
{
	vertices.resize(0);
	if (planes.size() < 4)
	{
		why = "has " + std::to_string(planes.size()) + " planes; a closed solid needs at least 4";
		return false;
	}
	btAlignedObjectArray<btVector3> unitPlanes;
	for (int i = 0; i < planes.size(); ++i)
	{
		const btVector3& plane = planes[i];
		if (!std::isfinite(plane.x()) || !std::isfinite(plane.y()) || !std::isfinite(plane.z()) ||
		    !std::isfinite(plane.w()))
		{
			why = "plane " + std::to_string(i) + " is not finite";
			return false;
		}
		const btScalar length = btVector3(plane.x(), plane.y(), plane.z()).length();
		if (!(length > btScalar(1e-6)) || std::fabs(double(plane.w()) / length) > kBspMaxPlaneOffset)
		{
			why = "plane " + std::to_string(i) + " has a zero normal or an offset beyond 1e6";
			return false;
		}
		btVector3 unit(plane.x() / length, plane.y() / length, plane.z() / length);
		unit.setW(plane.w() / length);
		unitPlanes.push_back(unit);
	}
	if (!planesAreClosed(unitPlanes))
	{
		why = "is open: its planes do not enclose a bounded solid";
		return false;
	}
	btGeometryUtil::getVerticesFromPlaneEquations(unitPlanes, vertices);
	if (vertices.size() < 4)
	{
		why = "is empty: its planes leave no solid between them";
		vertices.resize(0);
		return false;
	}
	btConvexHullComputer hull;
	hull.compute(&vertices[0][0], sizeof(btVector3), vertices.size(), 0, 0);
	if (hull.faces.size() < 4)
	{
		why = "is flat: its planes enclose no volume";
		vertices.resize(0);
		return false;
	}
	return true;
}

BspConversion convertBspBrushes(const BspLevel& level, btScalar scale)
{
	BspConversion conversion;
	if (!level.ok())
	{
		conversion.warnings.push_back("the level did not load: " + level.error);
		return conversion;
	}
	if (!(scale > 0) || !std::isfinite(scale))
	{
		btAssert(!"convertBspBrushes: scale must be finite and positive");
		conversion.warnings.push_back("the scale is not finite and positive");
		return conversion;
	}
	for (std::size_t b = 0; b < level.brushes.size(); ++b)
	{
		const BspBrush& brush = level.brushes[b];
		if (!(brush.contents & kBspContentsSolid))
		{
			++conversion.nonSolidBrushes;
			continue;
		}
		BspConvexPiece piece;
		std::string why;
		if (!brushToConvexVertices(brush.planes, piece.vertices, why))
		{
			conversion.warnings.push_back("brush " + std::to_string(b) + " skipped: it " + why);
			continue;
		}
		for (int i = 0; i < piece.vertices.size(); ++i) piece.vertices[i] *= scale;
		piece.brush = int(b);
		conversion.pieces.push_back(piece);
	}
	return conversion;
}

BspLevelShape buildBspLevelShape(const BspConversion& conversion)
{
	BspLevelShape level;
	if (conversion.pieces.empty()) return level;
	level.compound.reset(new btCompoundShape(true, int(conversion.pieces.size())));
	btTransform identity;
	identity.setIdentity();
	for (const BspConvexPiece& piece : conversion.pieces)
	{
		std::unique_ptr<btConvexHullShape> hull = makeMarginHullShape(piece.vertices);
		if (!hull) continue;  // cannot happen: every piece has volume
		level.compound->addChildShape(identity, hull.get());
		level.hulls.push_back(std::move(hull));
	}
	return level;
}
}  // namespace caliber
