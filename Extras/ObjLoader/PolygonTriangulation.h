// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_EXTRAS_POLYGON_TRIANGULATION_H
#define CALIBER_EXTRAS_POLYGON_TRIANGULATION_H

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btVector3.h"

namespace caliber
{
/// Triangulates the simple polygon points[0..count) (3D, roughly planar, either winding) by ear clipping in
/// its best-fit plane, appending count - 2 triangles as indices into points, wound like the polygon.
/// Self-intersecting or degenerate polygons still give count - 2 triangles (the least bad ear is taken
/// when no proper ear exists), so nothing is lost or looped forever. count < 3 appends nothing.
void triangulatePolygon(const btVector3* points, int count, btAlignedObjectArray<int>& trianglesOut);
}  // namespace caliber

#endif  // CALIBER_EXTRAS_POLYGON_TRIANGULATION_H
