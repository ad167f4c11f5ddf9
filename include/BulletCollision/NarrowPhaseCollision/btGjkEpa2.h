// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_GJK_EPA2_H
#define BT_GJK_EPA2_H

/// btGjkEpaSolver2: distance (GJK) and penetration depth (EPA) between two convex shapes.

#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "LinearMath/btTransform.h"

/// GJK distance and EPA penetration queries between two convex shapes placed by world transforms.
/// Conventions for every query: normal points from shape1 towards shape0, and
/// witnesses[0] = witnesses[1] + normal * distance (distance < 0 when the shapes overlap).
/// Bad input (a null shape or a non-finite transform) asserts; in release builds the query returns
/// false with status GJK_Failed, zero witnesses and normal, and distance 0.
struct btGjkEpaSolver2
{
	/// What a query found.
	struct sResults
	{
		/// Outcome of the query.
		enum eStatus
		{
			Separated,    ///< the shapes do not overlap; distance > 0
			Penetrating,  ///< the shapes overlap; distance <= 0 is minus the penetration depth
			GJK_Failed,   ///< bad input, or the distance iteration could not run
			EPA_Failed    ///< overlap found, but the depth could not be measured (e.g. a flat Minkowski difference)
		} status;
		/// Closest (or deepest) points in world space: [0] on shape0, [1] on shape1.
		btVector3 witnesses[2];
		/// Unit normal from shape1 towards shape0 (zero after a failure).
		btVector3 normal;
		/// Signed distance: positive when separated, minus the depth when penetrating.
		btScalar distance;
	};

	/// Bytes of stack one query uses for its simplex and polytope.
	static int StackSizeRequirement();
	/// Distance between the margin-free cores of the shapes (as Bullet: margins are not included).
	/// Returns true (status Separated) when they are apart; false when the cores overlap (status
	/// Penetrating, distance 0, witnesses at the overlap) or on failure.
	static bool Distance(const btConvexShape* shape0, const btTransform& wtrs0, const btConvexShape* shape1,
	                     const btTransform& wtrs1, const btVector3& guess, sResults& results);
	/// Penetration depth by EPA of the shapes (with their margins when usemargins). Returns true (status
	/// Penetrating) when they overlap; false with status Separated and the distance results when apart,
	/// or with status GJK_Failed/EPA_Failed (zero witnesses and normal, distance 0) on failure.
	static bool Penetration(const btConvexShape* shape0, const btTransform& wtrs0, const btConvexShape* shape1,
	                        const btTransform& wtrs1, const btVector3& guess, sResults& results,
	                        bool usemargins = true);
	/// Signed distance from a sphere of radius margin at position to shape0 (with its margin); results
	/// holds witnesses[0] on shape0 and witnesses[1] on the sphere. Returns SIMD_INFINITY on failure.
	static btScalar SignedDistance(const btVector3& position, btScalar margin, const btConvexShape* shape0,
	                               const btTransform& wtrs0, sResults& results);
	/// Signed distance between the shapes with their margins: Distance of the cores less the margins,
	/// or Penetration when the cores overlap. Returns false only on failure.
	static bool SignedDistance(const btConvexShape* shape0, const btTransform& wtrs0, const btConvexShape* shape1,
	                           const btTransform& wtrs1, const btVector3& guess, sResults& results);
};

#endif  // BT_GJK_EPA2_H
