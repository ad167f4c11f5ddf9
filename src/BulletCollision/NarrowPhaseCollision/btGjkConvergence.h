// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_GJK_CONVERGENCE_H
#define CALIBER_GJK_CONVERGENCE_H
// When GJK may stop, shared by btGjkPairDetector and btGjkEpaSolver2 (internal, not public API).
//
// GJK keeps an upper bound |v| (the closest point of the simplex) and a lower bound v.w / |v| (the
// support plane through the new support point w) on the distance from the origin to the Minkowski
// difference. It may stop only when the two meet, or when w cannot move v any more.
#include "BulletCollision/NarrowPhaseCollision/btSimplexSolverInterface.h"
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"
#include "LinearMath/btScalar.h"
#include "LinearMath/btVector3.h"

namespace caliber
{
namespace gjk
{
/// Gap between the bounds, relative to the distance, at which GJK has converged: on a curved
/// Minkowski difference a gap e at distance d leaves the direction of v free by sqrt(2 e / d), so the
/// relative gap 256 ulps keeps the normal within ~0.5 degree at any distance.
const btScalar kRelativeGap = btScalar(256) * SIMD_EPSILON;
/// Gap between the bounds, relative to the coordinates' size, that the rounding of v . w leaves
/// (a few ulps): below it the bounds cannot be told apart.
const btScalar kRoundingGap = btScalar(4) * SIMD_EPSILON;

/// True when the bounds have met. squaredDistance is |v|^2, vDotW is v . w for the support point w
/// along -v, maxVertexSquared the simplex's largest squared vertex length. The tolerance on
/// |v|^2 - v.w = |v| (|v| - lower bound) is a distance times |v|: an absolute tolerance on |v|^2 - v.w
/// would let GJK stop at any |v| below ~1e-6 with the lower bound far below zero (overlapping cores
/// reported as touching).
inline bool boundsMet(btScalar squaredDistance, btScalar vDotW, btScalar maxVertexSquared)
{
	const btScalar gap = squaredDistance - vDotW;
	return gap <= kRelativeGap * squaredDistance + kRoundingGap * btSqrt(squaredDistance * maxVertexSquared);
}

/// Distance, relative to the coordinates' size, under which a support point repeats a vertex. The
/// simplex's closest point is computed in double: a sliver of relative width 1e-6 still gets it to
/// ~1e-16 / 1e-12 of its width (and in float builds 1e-6 is only ~8 ulps of the coordinates), while
/// narrower slivers would lose it, in double builds above all. On a rim of radius 0.3 it is an
/// angle of 3e-6 rad, far below any tolerance on the normal.
const btScalar kDuplicateVertexDistance = btScalar(1e-6);

/// True when w coincides with a vertex of the simplex (or the last vertex added) to within
/// kDuplicateVertexDistance, so that adding it cannot usefully move the closest point. The solver's
/// own inSimplex() uses the equal-vertex threshold (1e-2 units in float), which on a curved surface
/// is met by successive supports long before the distance is found; GJK must not stop there.
inline bool isDuplicateVertex(const btSimplexSolverInterface& simplex, const btVector3& w)
{
	btScalar scaleSquared = w.length2();
	for (int i = 0; i < simplex.m_numVertices; ++i)
		scaleSquared = btMax(scaleSquared, simplex.m_simplexVectorW[i].length2());
	const btScalar threshold = kDuplicateVertexDistance * kDuplicateVertexDistance * (scaleSquared + btScalar(1));
	for (int i = 0; i < simplex.m_numVertices; ++i)
		if (simplex.m_simplexVectorW[i].distance2(w) <= threshold) return true;
	return w == simplex.m_lastW;
}
}  // namespace gjk
}  // namespace caliber

#endif
