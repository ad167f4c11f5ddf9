// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_EXTRAS_BSP_CONVERTER_H
#define CALIBER_EXTRAS_BSP_CONVERTER_H

/// Solid BSP brushes to convex hulls, and a static level shape from them (docs/extras.md, "BSP levels").

#include <memory>
#include <string>
#include <vector>

#include "BspLoader/BspLoader.h"
#include "BulletCollision/CollisionShapes/btCompoundShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"

namespace caliber
{
/// Largest plane offset accepted (Quake 3 maps stay within +-65536 units).
const double kBspMaxPlaneOffset = 1e6;

/// One solid brush as the corners of its convex hull, scaled.
struct BspConvexPiece
{
	btAlignedObjectArray<btVector3> vertices;
	/// Index into BspLevel::brushes.
	int brush = 0;
};

/// The result of converting a level's brushes.
struct BspConversion
{
	std::vector<BspConvexPiece> pieces;
	/// One message per solid brush that was skipped, naming the brush and why (open, empty, non-finite).
	std::vector<std::string> warnings;
	/// Brushes skipped because their contents are not solid (water, fog, clip-less detail, ...).
	int nonSolidBrushes = 0;
};

/// The corners of the solid bounded by planes (btGeometryUtil's form, outward). False, with the reason in
/// why, when a plane is not finite, has a zero normal or an offset beyond kBspMaxPlaneOffset, when the
/// planes leave the solid open (unbounded) or empty, or when the solid is flat.
bool brushToConvexVertices(const btAlignedObjectArray<btVector3>& planes, btAlignedObjectArray<btVector3>& vertices,
                           std::string& why);

/// Converts every solid brush of level (contents with kBspContentsSolid), multiplying coordinates by scale
/// (Quake units to metres: 1/32 makes a 56-unit player 1.75 m tall). A level that did not load, or a scale
/// that is not finite and positive, gives no pieces and one warning (btAssert on the scale).
BspConversion convertBspBrushes(const BspLevel& level, btScalar scale);

/// A static level: one btCompoundShape with a btConvexHullShape child per piece (children at the identity,
/// their corners in level coordinates, each shrunk by its collision margin so that hull plus margin has the
/// brush's faces: caliber::makeMarginHullShape). The compound does not own its children, so they are kept here.
struct BspLevelShape
{
	std::vector<std::unique_ptr<btConvexHullShape>> hulls;
	/// Declared after hulls: destroyed first, while its children still exist.
	std::unique_ptr<btCompoundShape> compound;
};

/// Builds the level shape from conversion's pieces; null compound when there are none.
BspLevelShape buildBspLevelShape(const BspConversion& conversion);
}  // namespace caliber

#endif  // CALIBER_EXTRAS_BSP_CONVERTER_H
