// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CD_HULL_H
#define BT_CD_HULL_H

/// HullLibrary: the convex hull of a point cloud as an indexed triangle (or polygon) mesh, with an
/// optional limit on its vertex count. Built on btConvexHullComputer, so the hull's topology is exact.
///
/// Output conventions:
/// - m_OutputVertices are the hull's corners, copies of input points in ascending input order.
/// - With QF_TRIANGLES, m_Indices holds three vertex indices per triangle, counter-clockwise seen from
///   outside (clockwise with QF_REVERSE_ORDER); each planar hull face is fan-triangulated from its
///   first corner, so a hull with V corners has 2V - 4 triangles. mNumFaces counts the triangles.
/// - Without QF_TRIANGLES, mPolygons is true and m_Indices holds each face as its corner count followed
///   by its corners, in the same winding; mNumFaces counts the faces.
///
/// Limits: the vertex limit is min(mMaxVertices, (mMaxFaces + 4) / 2), so that the triangle count
/// 2V - 4 also respects mMaxFaces. When the hull has more corners, a subset is chosen greedily: an
/// initial tetrahedron of extreme corners, then rounds in which every face of the hull of the chosen
/// corners takes the remaining corner farthest outside it (corners are assigned to the face they are
/// farthest outside of; the farthest are taken first while the limit allows). Corners within
/// mNormalEpsilon times the chosen hull's bounding-box diagonal of it count as inside, so the reduced
/// hull may stop short of the limit. The result is the hull of the chosen corners.
///
/// Failure (QE_FAIL, empty result): null vertices, mVcount 0, a stride below three btScalars, a
/// non-finite coordinate, no four non-coplanar points, or a vertex limit below 4.

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btVector3.h"

/// An array of unsigned indices.
typedef btAlignedObjectArray<unsigned int> TUIntArray;

/// The mesh CreateConvexHull produces (see the conventions at the top of this header).
class HullResult
{
public:
	/// An empty result.
	HullResult() : mPolygons(true), mNumOutputVertices(0), mNumFaces(0), mNumIndices(0) {}

	/// True when m_Indices holds counted polygons rather than triangles.
	bool mPolygons;
	/// Number of hull vertices (m_OutputVertices.size()).
	unsigned int mNumOutputVertices;
	/// The hull vertices.
	btAlignedObjectArray<btVector3> m_OutputVertices;
	/// Number of triangles, or of polygons when mPolygons.
	unsigned int mNumFaces;
	/// Number of entries in m_Indices.
	unsigned int mNumIndices;
	/// Triangle corners, or counted polygons when mPolygons.
	btAlignedObjectArray<unsigned int> m_Indices;
};

/// Output options of HullDesc.
enum HullFlag
{
	QF_TRIANGLES = (1 << 0),      ///< output triangles instead of polygons
	QF_REVERSE_ORDER = (1 << 1),  ///< clockwise seen from outside instead of counter-clockwise
	QF_DEFAULT = QF_TRIANGLES     ///< the default: counter-clockwise triangles
};

/// The input of CreateConvexHull: the points, output flags and limits.
class HullDesc
{
public:
	/// No points, QF_DEFAULT, default limits.
	HullDesc()
	    : mFlags(QF_DEFAULT),
	      mVcount(0),
	      mVertices(0),
	      mVertexStride(sizeof(btVector3)),
	      mNormalEpsilon(btScalar(0.001)),
	      mMaxVertices(4096),
	      mMaxFaces(4096)
	{
	}

	/// vcount points starting at vertices, stride bytes apart (each point is three btScalars).
	HullDesc(HullFlag flag, unsigned int vcount, const btVector3* vertices, unsigned int stride = sizeof(btVector3))
	    : mFlags(flag),
	      mVcount(vcount),
	      mVertices(vertices),
	      mVertexStride(stride),
	      mNormalEpsilon(btScalar(0.001)),
	      mMaxVertices(4096),
	      mMaxFaces(4096)
	{
	}

	/// True when flag is set.
	bool HasHullFlag(HullFlag flag) const { return (mFlags & flag) != 0; }
	/// Sets flag.
	void SetHullFlag(HullFlag flag) { mFlags |= flag; }
	/// Clears flag.
	void ClearHullFlag(HullFlag flag) { mFlags &= ~static_cast<unsigned int>(flag); }

	/// HullFlag bits.
	unsigned int mFlags;
	/// Number of input points.
	unsigned int mVcount;
	/// The first input point.
	const btVector3* mVertices;
	/// Bytes from one input point to the next.
	unsigned int mVertexStride;
	/// Relative tolerance of the vertex reduction (see the top of this header).
	btScalar mNormalEpsilon;
	/// Largest number of output vertices.
	unsigned int mMaxVertices;
	/// Largest number of output triangles (limits the vertices to (mMaxFaces + 4) / 2).
	unsigned int mMaxFaces;
};

/// Result codes of HullLibrary.
enum HullError
{
	QE_OK,   ///< success
	QE_FAIL  ///< bad or degenerate input; the result is empty
};

/// Builds convex hull meshes from HullDesc point clouds.
class HullLibrary
{
public:
	/// Replaces result with the hull of desc's points; on QE_FAIL the result is empty.
	HullError CreateConvexHull(const HullDesc& desc, HullResult& result);
	/// Empties result and frees its arrays; always QE_OK.
	HullError ReleaseResult(HullResult& result);
};

#endif  // BT_CD_HULL_H
