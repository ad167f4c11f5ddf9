// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_HEIGHTFIELD_TERRAIN_SHAPE_H
#define BT_HEIGHTFIELD_TERRAIN_SHAPE_H

#include "BulletCollision/CollisionShapes/btConcaveShape.h"

struct btTriangleInfoMap;

/// A static terrain: a regular grid of height samples (width x length, stored row by row, x fastest)
/// that the shape reads in place (the caller keeps the array alive and may change it, keeping the
/// samples inside [minHeight, maxHeight]). Sample (x, y) lies at grid position (x, y) on the two axes
/// other than upAxis, at its height along upAxis. The shape is centred on its AABB: the local origin is
/// the middle of the grid and of [minHeight, maxHeight]. Each grid cell is two triangles; see
/// docs/collision-shapes-and-narrowphase.md ("Height fields") for the split rules, the winding, the
/// triangle ids and the handling of bad input.
ATTRIBUTE_ALIGNED16(class)
btHeightfieldTerrainShape : public btConcaveShape
{
protected:
	/// Unscaled local AABB in grid coordinates: [0, width-1] x [minHeight, maxHeight] x [0, length-1].
	btVector3 m_localAabbMin;
	/// Upper corner of the unscaled grid-coordinate AABB.
	btVector3 m_localAabbMax;
	/// Centre of the grid-coordinate AABB: subtracted from grid coordinates to centre the shape.
	btVector3 m_localOrigin;

	/// Samples along the first grid axis (0 for an empty shape).
	int m_heightStickWidth;
	/// Samples along the second grid axis (0 for an empty shape).
	int m_heightStickLength;
	/// Lowest height any sample may have (after heightScale).
	btScalar m_minHeight;
	/// Highest height any sample may have (after heightScale).
	btScalar m_maxHeight;
	/// Grid span along the first grid axis (width - 1).
	btScalar m_width;
	/// Grid span along the second grid axis (length - 1).
	btScalar m_length;
	/// Factor applied to integer samples (PHY_SHORT, PHY_UCHAR); float and double samples are used as is.
	btScalar m_heightScale;
	/// The caller's samples, read in place (null for an empty shape).
	const void* m_heightfieldDataUnknown;
	/// m_heightfieldDataUnknown as bytes, for subclasses (Bullet keeps these typed views in a union; here they
	/// are separate pointers so that reading any of them is defined).
	const unsigned char* m_heightfieldDataUnsignedChar;
	/// m_heightfieldDataUnknown as shorts, for subclasses.
	const short* m_heightfieldDataShort;
	/// m_heightfieldDataUnknown as floats, for subclasses.
	const float* m_heightfieldDataFloat;
	/// m_heightfieldDataUnknown as doubles, for subclasses.
	const double* m_heightfieldDataDouble;
	/// The type of the samples.
	PHY_ScalarType m_heightDataType;
	/// Split every cell along the (x, y)-(x+1, y+1) diagonal.
	bool m_flipQuadEdges;
	/// Alternate the split diagonal in a checkerboard pattern.
	bool m_useDiamondSubdivision;
	/// Alternate the split diagonal row by row.
	bool m_useZigzagSubdivision;
	/// Report triangles wound clockwise seen from +up instead of counter-clockwise.
	bool m_flipTriangleWinding;
	/// The axis heights are measured along (0, 1 or 2).
	int m_upAxis;
	/// The local axis of the first grid index (x).
	int m_gridAxis0;
	/// The local axis of the second grid index (y).
	int m_gridAxis1;
	/// Per-axis scaling of grid spacing and heights.
	btVector3 m_localScaling;
	/// A free value for the user (Bullet's m_userValue3).
	btScalar m_userValue3;
	/// Internal-edge information for this shape, owned by the caller (may be null).
	btTriangleInfoMap* m_triangleInfoMap;

	/// Height of sample (x, y) after heightScale, unclamped (reads the caller's array).
	virtual btScalar getRawHeightFieldValue(int x, int y) const;

	/// Shared constructor body: validates the input and sets up the grid (or an empty shape).
	void initialize(int heightStickWidth, int heightStickLength, const void* heightfieldData, btScalar heightScale,
	                btScalar minHeight, btScalar maxHeight, int upAxis, PHY_ScalarType heightDataType,
	                bool flipQuadEdges);

	/// Height of sample (x, y) clamped to [minHeight, maxHeight]; false (and no height) when it is not finite.
	bool getClampedHeight(int x, int y, btScalar& height) const;
	/// True when cell (x, y) is split along its (x, y)-(x+1, y+1) diagonal.
	bool cellUsesMainDiagonal(int x, int y) const;
	/// Reports the triangles of cell (x, y) whose AABB overlaps [queryMin, queryMax] (no test when null).
	void processCell(btTriangleCallback * callback, int x, int y, const btVector3* queryMin, const btVector3* queryMax)
	    const;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// The general constructor: samples of heightDataType (PHY_FLOAT, PHY_DOUBLE, PHY_SHORT or PHY_UCHAR),
	/// integer samples multiplied by heightScale, heights within [minHeight, maxHeight].
	btHeightfieldTerrainShape(int heightStickWidth, int heightStickLength, const void* heightfieldData,
	                          btScalar heightScale, btScalar minHeight, btScalar maxHeight, int upAxis,
	                          PHY_ScalarType heightDataType, bool flipQuadEdges);

	/// The legacy constructor: float samples, or unsigned char samples scaled by maxHeight / 65535 (as in
	/// Bullet); the minimum height is 0.
	btHeightfieldTerrainShape(int heightStickWidth, int heightStickLength, const void* heightfieldData,
	                          btScalar maxHeight, int upAxis, bool useFloatData, bool flipQuadEdges);

	/// Typed constructor for float samples used as heights.
	btHeightfieldTerrainShape(int heightStickWidth, int heightStickLength, const float* heightfieldData,
	                          btScalar minHeight, btScalar maxHeight, int upAxis, bool flipQuadEdges);

	/// Typed constructor for double samples used as heights.
	btHeightfieldTerrainShape(int heightStickWidth, int heightStickLength, const double* heightfieldData,
	                          btScalar minHeight, btScalar maxHeight, int upAxis, bool flipQuadEdges);

	/// The legacy constructor reached with float samples (exists so that legacy calls with a float pointer
	/// do not clash with the typed float constructor); same behaviour as the void* legacy constructor.
	btHeightfieldTerrainShape(int heightStickWidth, int heightStickLength, const float* heightfieldData,
	                          btScalar maxHeight, int upAxis, bool useFloatData, bool flipQuadEdges);

	/// The legacy constructor reached with double samples (see the float overload above).
	btHeightfieldTerrainShape(int heightStickWidth, int heightStickLength, const double* heightfieldData,
	                          btScalar maxHeight, int upAxis, bool useFloatData, bool flipQuadEdges);

	/// Typed constructor for short samples multiplied by heightScale.
	btHeightfieldTerrainShape(int heightStickWidth, int heightStickLength, const short* heightfieldData,
	                          btScalar heightScale, btScalar minHeight, btScalar maxHeight, int upAxis,
	                          bool flipQuadEdges);

	/// Typed constructor for unsigned char samples multiplied by heightScale.
	btHeightfieldTerrainShape(int heightStickWidth, int heightStickLength, const unsigned char* heightfieldData,
	                          btScalar heightScale, btScalar minHeight, btScalar maxHeight, int upAxis,
	                          bool flipQuadEdges);

	/// Shapes are deleted through base pointers.
	virtual ~btHeightfieldTerrainShape();

	/// Alternate the split diagonal in a checkerboard pattern (cells with x + y even use the main diagonal).
	void setUseDiamondSubdivision(bool useDiamondSubdivision = true)
	{
		m_useDiamondSubdivision = useDiamondSubdivision;
	}
	/// Alternate the split diagonal row by row (rows with even y use the main diagonal).
	void setUseZigzagSubdivision(bool useZigzagSubdivision = true) { m_useZigzagSubdivision = useZigzagSubdivision; }
	/// Split every cell along the main diagonal (x, y)-(x+1, y+1) instead of (x+1, y)-(x, y+1).
	void setFlipQuadEdges(bool flipQuadEdges) { m_flipQuadEdges = flipQuadEdges; }
	/// Wind triangles clockwise seen from +up instead of counter-clockwise.
	void setFlipTriangleWinding(bool flipTriangleWinding) { m_flipTriangleWinding = flipTriangleWinding; }

	/// The world AABB under t: the box of the whole grid and [minHeight, maxHeight], scaled, grown by the margin.
	void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;

	/// Reports exactly the triangles whose AABB overlaps the closed local box [aabbMin, aabbMax] (only the
	/// cells the box covers are visited). Triangles with a non-finite sample are skipped.
	void processAllTriangles(btTriangleCallback * callback, const btVector3& aabbMin, const btVector3& aabbMax)
	    const override;

	/// Zero: a height field is for static bodies.
	void calculateLocalInertia(btScalar mass, btVector3 & inertia) const override;

	/// Scales grid spacing and heights per axis (a non-finite or zero component asserts and is ignored).
	void setLocalScaling(const btVector3& scaling) override;
	/// The local scaling.
	const btVector3& getLocalScaling() const override { return m_localScaling; }

	/// The local (centred, scaled) position of sample (x, y), its height clamped to [minHeight, maxHeight].
	void getVertex(int x, int y, btVector3& vertex) const;

	/// Reports the triangles of the cells the segment raySource-rayTarget (local coordinates) crosses, walking
	/// the grid along the segment; cells whose height range the segment misses are skipped.
	void performRaycast(btTriangleCallback * callback, const btVector3& raySource, const btVector3& rayTarget) const;

	/// Kept for Bullet compatibility; a no-op: queries visit only the cells they need without an accelerator.
	void buildAccelerator(int chunkSize = 16);
	/// Kept for Bullet compatibility; a no-op (see buildAccelerator).
	void clearAccelerator();

	/// The up axis (0, 1 or 2).
	int getUpAxis() const { return m_upAxis; }

	/// "HEIGHTFIELD".
	const char* getName() const override { return "HEIGHTFIELD"; }

	/// Stores a free user value.
	void setUserValue3(btScalar value) { m_userValue3 = value; }
	/// The free user value (0 by default).
	btScalar getUserValue3() const { return m_userValue3; }

	/// The caller-owned internal-edge information (null by default).
	const btTriangleInfoMap* getTriangleInfoMap() const { return m_triangleInfoMap; }
	/// The caller-owned internal-edge information (null by default).
	btTriangleInfoMap* getTriangleInfoMap() { return m_triangleInfoMap; }
	/// Attaches internal-edge information (not owned; may be null).
	void setTriangleInfoMap(btTriangleInfoMap * map) { m_triangleInfoMap = map; }

	/// The caller's sample array as bytes (null for an empty shape).
	const unsigned char* getHeightfieldRawData() const
	{
		return static_cast<const unsigned char*>(m_heightfieldDataUnknown);
	}
};

#endif  // BT_HEIGHTFIELD_TERRAIN_SHAPE_H
