// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h"

#include <cmath>
#include <cstddef>

#include "BulletCollision/CollisionShapes/btShapeGuards.h"

namespace
{
// Slack, in grid cells, that the ray walk adds around the segment so that rounding in the transform to grid
// coordinates never drops a cell the segment touches (the exact triangle tests are left to the caller).
const btScalar kRayCellSlack = btScalar(1e-3);

// floor(value) as an int, value first clamped to [lo, hi] so that huge or tiny inputs never overflow.
int clampedFloor(btScalar value, int lo, int hi)
{
	const btScalar clamped = btClamped(value, btScalar(lo), btScalar(hi));
	return btClamped(static_cast<int>(std::floor(clamped)), lo, hi);
}

bool dataTypeSupported(PHY_ScalarType type)
{
	return type == PHY_FLOAT || type == PHY_DOUBLE || type == PHY_SHORT || type == PHY_UCHAR;
}
}  // namespace

btHeightfieldTerrainShape::btHeightfieldTerrainShape(int heightStickWidth, int heightStickLength,
                                                     const void* heightfieldData, btScalar heightScale,
                                                     btScalar minHeight, btScalar maxHeight, int upAxis,
                                                     PHY_ScalarType heightDataType, bool flipQuadEdges)
{
	initialize(heightStickWidth, heightStickLength, heightfieldData, heightScale, minHeight, maxHeight, upAxis,
	           heightDataType, flipQuadEdges);
}

btHeightfieldTerrainShape::btHeightfieldTerrainShape(int heightStickWidth, int heightStickLength,
                                                     const void* heightfieldData, btScalar maxHeight, int upAxis,
                                                     bool useFloatData, bool flipQuadEdges)
{
	// Bullet's legacy scale for byte samples is maxHeight / 65535; kept so old scenes keep their heights.
	initialize(heightStickWidth, heightStickLength, heightfieldData, maxHeight / btScalar(65535), btScalar(0),
	           maxHeight, upAxis, useFloatData ? PHY_FLOAT : PHY_UCHAR, flipQuadEdges);
}

btHeightfieldTerrainShape::btHeightfieldTerrainShape(int heightStickWidth, int heightStickLength,
                                                     const float* heightfieldData, btScalar minHeight,
                                                     btScalar maxHeight, int upAxis, bool flipQuadEdges)
{
	initialize(heightStickWidth, heightStickLength, heightfieldData, btScalar(1), minHeight, maxHeight, upAxis,
	           PHY_FLOAT, flipQuadEdges);
}

btHeightfieldTerrainShape::btHeightfieldTerrainShape(int heightStickWidth, int heightStickLength,
                                                     const double* heightfieldData, btScalar minHeight,
                                                     btScalar maxHeight, int upAxis, bool flipQuadEdges)
{
	initialize(heightStickWidth, heightStickLength, heightfieldData, btScalar(1), minHeight, maxHeight, upAxis,
	           PHY_DOUBLE, flipQuadEdges);
}

btHeightfieldTerrainShape::btHeightfieldTerrainShape(int heightStickWidth, int heightStickLength,
                                                     const float* heightfieldData, btScalar maxHeight, int upAxis,
                                                     bool useFloatData, bool flipQuadEdges)
{
	initialize(heightStickWidth, heightStickLength, heightfieldData, maxHeight / btScalar(65535), btScalar(0),
	           maxHeight, upAxis, useFloatData ? PHY_FLOAT : PHY_UCHAR, flipQuadEdges);
}

btHeightfieldTerrainShape::btHeightfieldTerrainShape(int heightStickWidth, int heightStickLength,
                                                     const double* heightfieldData, btScalar maxHeight, int upAxis,
                                                     bool useFloatData, bool flipQuadEdges)
{
	initialize(heightStickWidth, heightStickLength, heightfieldData, maxHeight / btScalar(65535), btScalar(0),
	           maxHeight, upAxis, useFloatData ? PHY_FLOAT : PHY_UCHAR, flipQuadEdges);
}

btHeightfieldTerrainShape::btHeightfieldTerrainShape(int heightStickWidth, int heightStickLength,
                                                     const short* heightfieldData, btScalar heightScale,
                                                     btScalar minHeight, btScalar maxHeight, int upAxis,
                                                     bool flipQuadEdges)
{
	initialize(heightStickWidth, heightStickLength, heightfieldData, heightScale, minHeight, maxHeight, upAxis,
	           PHY_SHORT, flipQuadEdges);
}

btHeightfieldTerrainShape::btHeightfieldTerrainShape(int heightStickWidth, int heightStickLength,
                                                     const unsigned char* heightfieldData, btScalar heightScale,
                                                     btScalar minHeight, btScalar maxHeight, int upAxis,
                                                     bool flipQuadEdges)
{
	initialize(heightStickWidth, heightStickLength, heightfieldData, heightScale, minHeight, maxHeight, upAxis,
	           PHY_UCHAR, flipQuadEdges);
}

btHeightfieldTerrainShape::~btHeightfieldTerrainShape() {}

void btHeightfieldTerrainShape::initialize(int heightStickWidth, int heightStickLength, const void* heightfieldData,
                                           btScalar heightScale, btScalar minHeight, btScalar maxHeight, int upAxis,
                                           PHY_ScalarType heightDataType, bool flipQuadEdges)
{
	m_shapeType = TERRAIN_SHAPE_PROXYTYPE;
	m_heightScale = heightScale;
	m_heightDataType = heightDataType;
	m_flipQuadEdges = flipQuadEdges;
	m_useDiamondSubdivision = false;
	m_useZigzagSubdivision = false;
	m_flipTriangleWinding = false;
	m_localScaling.setValue(btScalar(1), btScalar(1), btScalar(1));
	m_userValue3 = btScalar(0);
	m_triangleInfoMap = 0;

	btAssert(upAxis >= 0 && upAxis <= 2 && "btHeightfieldTerrainShape: upAxis must be 0, 1 or 2");
	m_upAxis = (upAxis >= 0 && upAxis <= 2) ? upAxis : 1;
	m_gridAxis0 = m_upAxis == 0 ? 1 : 0;
	m_gridAxis1 = m_upAxis == 2 ? 1 : 2;

	btAssert(!(minHeight > maxHeight) && "btHeightfieldTerrainShape: minHeight > maxHeight");
	if (minHeight > maxHeight) btSwap(minHeight, maxHeight);
	m_minHeight = minHeight;
	m_maxHeight = maxHeight;

	const bool sizeValid = heightStickWidth >= 2 && heightStickLength >= 2;
	const bool valuesValid = btIsFinite(minHeight) && btIsFinite(maxHeight) && btIsFinite(heightScale);
	const bool typeValid = dataTypeSupported(heightDataType);
	btAssert(sizeValid && "btHeightfieldTerrainShape: width and length must be at least 2");
	btAssert(heightfieldData && "btHeightfieldTerrainShape: null height data");
	btAssert(valuesValid && "btHeightfieldTerrainShape: non-finite height range or scale");
	btAssert(typeValid && "btHeightfieldTerrainShape: unsupported height data type");
	const bool valid = sizeValid && heightfieldData && valuesValid && typeValid;

	// An invalid shape becomes empty: no samples, no triangles, a zero-size AABB at the origin.
	m_heightStickWidth = valid ? heightStickWidth : 0;
	m_heightStickLength = valid ? heightStickLength : 0;
	m_heightfieldDataUnknown = valid ? heightfieldData : 0;
	m_heightfieldDataUnsignedChar = static_cast<const unsigned char*>(m_heightfieldDataUnknown);
	m_heightfieldDataShort = static_cast<const short*>(m_heightfieldDataUnknown);
	m_heightfieldDataFloat = static_cast<const float*>(m_heightfieldDataUnknown);
	m_heightfieldDataDouble = static_cast<const double*>(m_heightfieldDataUnknown);
	if (!valid)
	{
		m_minHeight = m_maxHeight = btScalar(0);
		m_heightScale = btScalar(0);
	}
	m_width = valid ? btScalar(heightStickWidth - 1) : btScalar(0);
	m_length = valid ? btScalar(heightStickLength - 1) : btScalar(0);

	m_localAabbMin.setValue(btScalar(0), btScalar(0), btScalar(0));
	m_localAabbMax.setValue(btScalar(0), btScalar(0), btScalar(0));
	m_localAabbMin[m_upAxis] = m_minHeight;
	m_localAabbMax[m_upAxis] = m_maxHeight;
	m_localAabbMax[m_gridAxis0] = m_width;
	m_localAabbMax[m_gridAxis1] = m_length;
	m_localOrigin = (m_localAabbMin + m_localAabbMax) * btScalar(0.5);
}

btScalar btHeightfieldTerrainShape::getRawHeightFieldValue(int x, int y) const
{
	const bool inside = x >= 0 && y >= 0 && x < m_heightStickWidth && y < m_heightStickLength;
	btAssert(inside && "getRawHeightFieldValue: sample index out of range");
	// The typed pointers are all null for an empty shape, whose size is 0, so inside is false then.
	if (!inside) return btScalar(0);
	// size_t arithmetic: width * length may exceed the int range for very large grids.
	const size_t index = size_t(y) * size_t(m_heightStickWidth) + size_t(x);
	switch (m_heightDataType)
	{
		case PHY_FLOAT:
			return btScalar(m_heightfieldDataFloat[index]);
		case PHY_DOUBLE:
			return btScalar(m_heightfieldDataDouble[index]);
		case PHY_SHORT:
			return btScalar(m_heightfieldDataShort[index]) * m_heightScale;
		case PHY_UCHAR:
			return btScalar(m_heightfieldDataUnsignedChar[index]) * m_heightScale;
		default:
			return btScalar(0);
	}
}

bool btHeightfieldTerrainShape::getClampedHeight(int x, int y, btScalar& height) const
{
	const btScalar raw = getRawHeightFieldValue(x, y);
	if (!btIsFinite(raw)) return false;
	// Samples outside the declared range are clamped so that the AABB always contains every triangle.
	height = btClamped(raw, m_minHeight, m_maxHeight);
	return true;
}

bool btHeightfieldTerrainShape::cellUsesMainDiagonal(int x, int y) const
{
	return m_flipQuadEdges || (m_useDiamondSubdivision && ((x + y) & 1) == 0) ||
	       (m_useZigzagSubdivision && (y & 1) == 0);
}

void btHeightfieldTerrainShape::getVertex(int x, int y, btVector3& vertex) const
{
	const bool inside = x >= 0 && y >= 0 && x < m_heightStickWidth && y < m_heightStickLength;
	btAssert(inside && "getVertex: sample index out of range");
	btScalar height = m_localOrigin[m_upAxis];
	if (inside && !getClampedHeight(x, y, height)) height = m_localOrigin[m_upAxis];
	vertex[m_gridAxis0] = (btScalar(x) - m_localOrigin[m_gridAxis0]) * m_localScaling[m_gridAxis0];
	vertex[m_gridAxis1] = (btScalar(y) - m_localOrigin[m_gridAxis1]) * m_localScaling[m_gridAxis1];
	vertex[m_upAxis] = (height - m_localOrigin[m_upAxis]) * m_localScaling[m_upAxis];
	vertex[3] = btScalar(0);
}

void btHeightfieldTerrainShape::processCell(btTriangleCallback* callback, int x, int y, const btVector3* queryMin,
                                            const btVector3* queryMax) const
{
	// Corners in the order (x, y), (x+1, y), (x+1, y+1), (x, y+1): counter-clockwise in the (grid axis 0,
	// grid axis 1) plane.
	btScalar heights[4];
	bool finite[4];
	finite[0] = getClampedHeight(x, y, heights[0]);
	finite[1] = getClampedHeight(x + 1, y, heights[1]);
	finite[2] = getClampedHeight(x + 1, y + 1, heights[2]);
	finite[3] = getClampedHeight(x, y + 1, heights[3]);

	btVector3 corners[4];
	const btScalar u0 = (btScalar(x) - m_localOrigin[m_gridAxis0]) * m_localScaling[m_gridAxis0];
	const btScalar u1 = (btScalar(x + 1) - m_localOrigin[m_gridAxis0]) * m_localScaling[m_gridAxis0];
	const btScalar v0 = (btScalar(y) - m_localOrigin[m_gridAxis1]) * m_localScaling[m_gridAxis1];
	const btScalar v1 = (btScalar(y + 1) - m_localOrigin[m_gridAxis1]) * m_localScaling[m_gridAxis1];
	const btScalar us[4] = {u0, u1, u1, u0};
	const btScalar vs[4] = {v0, v0, v1, v1};
	for (int i = 0; i < 4; ++i)
	{
		corners[i][m_gridAxis0] = us[i];
		corners[i][m_gridAxis1] = vs[i];
		corners[i][m_upAxis] =
		    finite[i] ? (heights[i] - m_localOrigin[m_upAxis]) * m_localScaling[m_upAxis] : btScalar(0);
		corners[i][3] = btScalar(0);
	}

	// Triangles listed counter-clockwise in the grid plane face +up when (grid0, grid1, up) is a right-handed
	// frame (up axis 0 or 2, with positive scaling); otherwise two vertices are swapped on output.
	const bool gridFrameLeftHanded = (m_upAxis == 1);
	const bool scalingMirrors = (m_localScaling.x() * m_localScaling.y() * m_localScaling.z()) < btScalar(0);
	const bool swapWinding = (gridFrameLeftHanded != scalingMirrors) != m_flipTriangleWinding;

	static const int kMainDiagonal[2][3] = {{0, 1, 2}, {0, 2, 3}};
	static const int kOtherDiagonal[2][3] = {{0, 1, 3}, {1, 2, 3}};
	const int(*split)[3] = cellUsesMainDiagonal(x, y) ? kMainDiagonal : kOtherDiagonal;

	for (int k = 0; k < 2; ++k)
	{
		const int a = split[k][0], b = split[k][1], c = split[k][2];
		if (!(finite[a] && finite[b] && finite[c])) continue;
		btVector3 triangle[3] = {corners[a], corners[b], corners[c]};
		if (queryMin)
		{
			btVector3 triMin = triangle[0], triMax = triangle[0];
			triMin.setMin(triangle[1]);
			triMin.setMin(triangle[2]);
			triMax.setMax(triangle[1]);
			triMax.setMax(triangle[2]);
			if (triMin.x() > queryMax->x() || triMax.x() < queryMin->x() || triMin.y() > queryMax->y() ||
			    triMax.y() < queryMin->y() || triMin.z() > queryMax->z() || triMax.z() < queryMin->z())
				continue;
		}
		if (swapWinding) btSwap(triangle[1], triangle[2]);
		callback->processTriangle(triangle, 2 * x + k, y);
	}
}

void btHeightfieldTerrainShape::processAllTriangles(btTriangleCallback* callback, const btVector3& aabbMin,
                                                    const btVector3& aabbMax) const
{
	const bool boxValid = caliber::isFinite(aabbMin) && caliber::isFinite(aabbMax);
	btAssert(callback && boxValid && "processAllTriangles: null callback or non-finite box");
	if (!callback || !boxValid || m_heightStickWidth < 2) return;

	// The query in grid coordinates; a negative scaling swaps the ends of an axis.
	btScalar gridMin[3], gridMax[3];
	for (int axis = 0; axis < 3; ++axis)
	{
		const btScalar a = aabbMin[axis] / m_localScaling[axis] + m_localOrigin[axis];
		const btScalar b = aabbMax[axis] / m_localScaling[axis] + m_localOrigin[axis];
		gridMin[axis] = btMin(a, b);
		gridMax[axis] = btMax(a, b);
	}
	if (gridMax[m_upAxis] < m_minHeight || gridMin[m_upAxis] > m_maxHeight) return;

	// Cells [floor(min) - 1, floor(max)] cover every cell the closed box touches, even after rounding in the
	// transform above; the exact per-triangle AABB test in processCell drops the extra border cells.
	const int lastX = m_heightStickWidth - 2, lastY = m_heightStickLength - 2;
	const int startX = clampedFloor(gridMin[m_gridAxis0], -1, lastX + 1) - 1;
	const int endX = clampedFloor(gridMax[m_gridAxis0], -1, lastX + 1);
	const int startY = clampedFloor(gridMin[m_gridAxis1], -1, lastY + 1) - 1;
	const int endY = clampedFloor(gridMax[m_gridAxis1], -1, lastY + 1);

	btVector3 queryMin = aabbMin, queryMax = aabbMax;
	queryMin.setMin(aabbMax);
	queryMax.setMax(aabbMin);
	for (int y = btMax(startY, 0); y <= btMin(endY, lastY); ++y)
		for (int x = btMax(startX, 0); x <= btMin(endX, lastX); ++x) processCell(callback, x, y, &queryMin, &queryMax);
}

void btHeightfieldTerrainShape::performRaycast(btTriangleCallback* callback, const btVector3& raySource,
                                               const btVector3& rayTarget) const
{
	const bool rayValid = caliber::isFinite(raySource) && caliber::isFinite(rayTarget);
	btAssert(callback && rayValid && "performRaycast: null callback or non-finite ray");
	if (!callback || !rayValid || m_heightStickWidth < 2) return;

	// The segment in grid coordinates: major/minor grid axes and raw heights.
	btVector3 from(0, 0, 0), to(0, 0, 0);
	for (int axis = 0; axis < 3; ++axis)
	{
		from[axis] = raySource[axis] / m_localScaling[axis] + m_localOrigin[axis];
		to[axis] = rayTarget[axis] / m_localScaling[axis] + m_localOrigin[axis];
	}
	const btVector3 delta = to - from;

	// Clip the parameter range to the grid rectangle (grown by the slack).
	btScalar t0 = btScalar(0), t1 = btScalar(1);
	const int gridAxes[2] = {m_gridAxis0, m_gridAxis1};
	const btScalar spans[2] = {m_width, m_length};
	for (int i = 0; i < 2; ++i)
	{
		const int axis = gridAxes[i];
		const btScalar lo = -kRayCellSlack, hi = spans[i] + kRayCellSlack;
		if (delta[axis] == btScalar(0))
		{
			if (from[axis] < lo || from[axis] > hi) return;
			continue;
		}
		btScalar ta = (lo - from[axis]) / delta[axis], tb = (hi - from[axis]) / delta[axis];
		if (ta > tb) btSwap(ta, tb);
		t0 = btMax(t0, ta);
		t1 = btMin(t1, tb);
	}
	if (t0 > t1) return;

	// Walk the cells column by column along the axis the segment moves most on; each column covers the
	// parameter range where the segment is inside it, and the minor-axis cells of that range.
	const bool majorIsAxis0 = btFabs(delta[m_gridAxis0]) >= btFabs(delta[m_gridAxis1]);
	const int major = majorIsAxis0 ? m_gridAxis0 : m_gridAxis1;
	const int minor = majorIsAxis0 ? m_gridAxis1 : m_gridAxis0;
	const int lastMajor = (majorIsAxis0 ? m_heightStickWidth : m_heightStickLength) - 2;
	const int lastMinor = (majorIsAxis0 ? m_heightStickLength : m_heightStickWidth) - 2;
	const btScalar heightSlack = kRayCellSlack * (btScalar(1) + btFabs(m_minHeight) + btFabs(m_maxHeight));

	const btScalar majorA = from[major] + t0 * delta[major], majorB = from[major] + t1 * delta[major];
	int firstColumn = clampedFloor(btMin(majorA, majorB) - kRayCellSlack, 0, lastMajor);
	int lastColumn = clampedFloor(btMax(majorA, majorB) + kRayCellSlack, 0, lastMajor);
	const int columnStep = delta[major] < btScalar(0) ? -1 : 1;
	if (columnStep < 0) btSwap(firstColumn, lastColumn);

	for (int column = firstColumn;; column += columnStep)
	{
		btScalar ta = t0, tb = t1;
		if (delta[major] != btScalar(0))
		{
			ta = (btScalar(column) - kRayCellSlack - from[major]) / delta[major];
			tb = (btScalar(column + 1) + kRayCellSlack - from[major]) / delta[major];
			if (ta > tb) btSwap(ta, tb);
			ta = btMax(ta, t0);
			tb = btMin(tb, t1);
		}
		if (ta <= tb)
		{
			const btScalar minorA = from[minor] + ta * delta[minor], minorB = from[minor] + tb * delta[minor];
			int firstRow = clampedFloor(btMin(minorA, minorB) - kRayCellSlack, 0, lastMinor);
			int lastRow = clampedFloor(btMax(minorA, minorB) + kRayCellSlack, 0, lastMinor);
			const int rowStep = delta[minor] < btScalar(0) ? -1 : 1;
			if (rowStep < 0) btSwap(firstRow, lastRow);
			const btScalar heightA = from[m_upAxis] + ta * delta[m_upAxis];
			const btScalar heightB = from[m_upAxis] + tb * delta[m_upAxis];
			const btScalar rayLow = btMin(heightA, heightB) - heightSlack;
			const btScalar rayHigh = btMax(heightA, heightB) + heightSlack;
			for (int row = firstRow;; row += rowStep)
			{
				const int x = majorIsAxis0 ? column : row;
				const int y = majorIsAxis0 ? row : column;
				// Skip the cell when the segment passes wholly above or below its samples.
				btScalar cellLow = BT_LARGE_FLOAT, cellHigh = -BT_LARGE_FLOAT;
				bool allFinite = true;
				for (int corner = 0; corner < 4; ++corner)
				{
					btScalar h;
					if (!getClampedHeight(x + (corner & 1), y + (corner >> 1), h))
					{
						allFinite = false;
						break;
					}
					cellLow = btMin(cellLow, h);
					cellHigh = btMax(cellHigh, h);
				}
				if (!allFinite || !(rayHigh < cellLow || rayLow > cellHigh)) processCell(callback, x, y, 0, 0);
				if (row == lastRow) break;
			}
		}
		if (column == lastColumn) break;
	}
}

void btHeightfieldTerrainShape::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const
{
	if (!caliber::checkAabbTransform(t, aabbMin, aabbMax)) return;
	const btVector3 halfExtents = ((m_localAabbMax - m_localAabbMin) * m_localScaling).absolute() * btScalar(0.5);
	const btMatrix3x3 absoluteBasis = t.getBasis().absolute();
	const btScalar margin = getMargin();
	const btVector3 extent =
	    halfExtents.dot3(absoluteBasis[0], absoluteBasis[1], absoluteBasis[2]) + btVector3(margin, margin, margin);
	aabbMin = t.getOrigin() - extent;
	aabbMax = t.getOrigin() + extent;
}

void btHeightfieldTerrainShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const
{
	(void)mass;
	inertia.setValue(btScalar(0), btScalar(0), btScalar(0));
}

void btHeightfieldTerrainShape::setLocalScaling(const btVector3& scaling)
{
	const bool valid = caliber::isFinite(scaling) && scaling.x() != btScalar(0) && scaling.y() != btScalar(0) &&
	                   scaling.z() != btScalar(0);
	btAssert(valid && "btHeightfieldTerrainShape::setLocalScaling: non-finite or zero scaling");
	if (valid) m_localScaling = scaling;
}

void btHeightfieldTerrainShape::buildAccelerator(int chunkSize) { (void)chunkSize; }

void btHeightfieldTerrainShape::clearAccelerator() {}
