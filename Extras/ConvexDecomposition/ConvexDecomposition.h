// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_EXTRAS_CONVEX_DECOMPOSITION_H
#define CALIBER_EXTRAS_CONVEX_DECOMPOSITION_H

/// Approximate convex decomposition of a closed triangle mesh by recursive plane splits, and a
/// btCompoundShape from the result. The algorithm and its limits: docs/extras.md, "Convex decomposition".

#include <memory>
#include <string>
#include <vector>

#include "BulletCollision/CollisionShapes/btCompoundShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btVector3.h"

namespace caliber
{
/// What the decomposition may do.
struct ConvexDecompositionParameters
{
	/// At most this many hulls (at least 1).
	int maxHulls = 16;
	/// Splitting stops once the hulls' total volume exceeds the mesh's by at most this fraction of the
	/// mesh's volume (0.02: the hulls cover at most 2 % more than the mesh).
	double concavityTolerance = 0.02;
	/// Candidate planes tried per axis at each split (1 to 256): evenly spaced, plus the piece's vertex
	/// coordinates, where the corners of machined parts are.
	int planesPerAxis = 16;
};

/// One convex piece of the result.
struct ConvexDecompositionHull
{
	/// The hull's corners, in the mesh's coordinates.
	btAlignedObjectArray<btVector3> vertices;
	/// The hull's volume and centre of volume.
	double volume = 0;
	btVector3 centroid = btVector3(0, 0, 0);
	/// The volume of the part of the mesh this hull covers (at most volume).
	double meshVolume = 0;
};

/// The result of a decomposition.
struct ConvexDecompositionResult
{
	std::vector<ConvexDecompositionHull> hulls;
	/// The mesh's volume, and the hulls' total volume (they do not overlap: each lies in its own cell of
	/// the splitting planes, so this is also the volume of their union).
	double meshVolume = 0;
	double hullVolume = 0;
	/// True when (hullVolume - meshVolume) / meshVolume is within the tolerance; false when maxHulls, or
	/// the lack of a plane that helps, stopped the splitting first.
	bool withinTolerance = false;
	/// Repairs made to the input (an inward-wound mesh is turned outwards; duplicate vertices welded).
	std::vector<std::string> warnings;
	/// Why the decomposition failed; empty on success (hulls is then non-empty).
	std::string error;

	bool ok() const { return error.empty(); }
	/// (hullVolume - meshVolume) / meshVolume: how much more the hulls cover than the mesh.
	double volumeError() const { return meshVolume > 0 ? (hullVolume - meshVolume) / meshVolume : 0; }
};

/// Decomposes the closed mesh (numIndices / 3 triangles into vertices, wound either way consistently) into
/// at most parameters.maxHulls convex hulls. Bad meshes fail with result.error and no hulls: fewer than 4
/// triangles, an index out of range, a non-finite or huge (beyond 1e15) coordinate, an open or
/// non-manifold mesh (an edge not shared by exactly two triangles in opposite directions), no volume.
/// Bad parameters (maxHulls < 1, a negative or NaN tolerance, planesPerAxis outside 1..256) and null
/// arrays with non-zero counts are programming errors: btAssert, else a failed result.
bool decomposeConvex(const btVector3* vertices, int numVertices, const int* indices, int numIndices,
                     const ConvexDecompositionParameters& parameters, ConvexDecompositionResult& result);

/// A compound of the hulls, ready for a btRigidBody (set its mass and use calculatePrincipalAxisTransform
/// for a dynamic body). Each child is a btConvexHullShape placed at its hull's centroid, shrunk by its
/// collision margin so that hull plus margin has the hull's faces (caliber::makeMarginHullShape).
struct DecompositionShape
{
	std::vector<std::unique_ptr<btConvexHullShape>> hulls;
	/// Declared after hulls: destroyed first, while its children still exist.
	std::unique_ptr<btCompoundShape> compound;
};

/// Builds the compound for result's hulls; null compound when there are none.
DecompositionShape buildDecompositionShape(const ConvexDecompositionResult& result);

/// Volume of the convex hull of points (0 for fewer than 4 points or a flat set); the centre of volume
/// goes to centroid when it is given.
double convexHullVolume(const btAlignedObjectArray<btVector3>& points, btVector3* centroid = nullptr);
}  // namespace caliber

#endif  // CALIBER_EXTRAS_CONVEX_DECOMPOSITION_H
