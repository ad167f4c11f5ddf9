// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h"

#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "BulletCollision/NarrowPhaseCollision/btConvexPenetrationDepthSolver.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkConvergence.h"

// GJK on the cores: each step asks both shapes for their margin-free support point along the current
// closest point v of the simplex, stops when the lower bound v.w / |v| meets the upper bound |v|, and
// then moves the witnesses out by the margins. Work is done relative to the midpoint of the origins.

namespace
{
const int kMaxIterations = 1000;
// Relative slack when comparing the overlaps along +n and -n (a few hundred ulps).
const btScalar kRelativeTolerance = btScalar(256) * SIMD_EPSILON;
// Cores closer than this (length units) after a degenerate GJK ending are checked by the depth solver.
const btScalar kDegenerateContactTolerance = btScalar(1e-3);

// Squared length under which a closest point counts as the origin (rounding of coordinates of size scale).
btScalar overlapThreshold(btScalar scaleSquared)
{
	return btScalar(16) * SIMD_EPSILON * SIMD_EPSILON * (scaleSquared + btScalar(1));
}

btVector3 worldSupport(const btConvexShape* shape, const btTransform& t, const btVector3& dir, btScalar margin)
{
	btVector3 point = t(shape->localGetSupportingVertexWithoutMargin(dir * t.getBasis()));
	if (margin != btScalar(0))
	{
		btVector3 unit = dir;
		unit.safeNormalize();
		point += unit * margin;
	}
	return point;
}
}  // namespace

btGjkPairDetector::btGjkPairDetector(const btConvexShape* objectA, const btConvexShape* objectB,
                                     btSimplexSolverInterface* simplexSolver,
                                     btConvexPenetrationDepthSolver* penetrationDepthSolver)
    : m_cachedSeparatingAxis(btScalar(0), btScalar(1), btScalar(0)),
      m_penetrationDepthSolver(penetrationDepthSolver),
      m_simplexSolver(simplexSolver),
      m_minkowskiA(objectA),
      m_minkowskiB(objectB),
      m_shapeTypeA(objectA ? objectA->getShapeType() : 0),
      m_shapeTypeB(objectB ? objectB->getShapeType() : 0),
      m_marginA(objectA ? objectA->getMargin() : btScalar(0)),
      m_marginB(objectB ? objectB->getMargin() : btScalar(0)),
      m_ignoreMargin(false),
      m_cachedSeparatingDistance(btScalar(0)),
      m_useShapeMargins(true),
      m_lastUsedMethod(-1),
      m_curIter(0),
      m_degenerateSimplex(0),
      m_catchDegeneracies(1),
      m_fixContactNormalDirection(1)
{
}

btGjkPairDetector::btGjkPairDetector(const btConvexShape* objectA, const btConvexShape* objectB, int shapeTypeA,
                                     int shapeTypeB, btScalar marginA, btScalar marginB,
                                     btSimplexSolverInterface* simplexSolver,
                                     btConvexPenetrationDepthSolver* penetrationDepthSolver)
    : m_cachedSeparatingAxis(btScalar(0), btScalar(1), btScalar(0)),
      m_penetrationDepthSolver(penetrationDepthSolver),
      m_simplexSolver(simplexSolver),
      m_minkowskiA(objectA),
      m_minkowskiB(objectB),
      m_shapeTypeA(shapeTypeA),
      m_shapeTypeB(shapeTypeB),
      m_marginA(marginA),
      m_marginB(marginB),
      m_ignoreMargin(false),
      m_cachedSeparatingDistance(btScalar(0)),
      m_useShapeMargins(false),
      m_lastUsedMethod(-1),
      m_curIter(0),
      m_degenerateSimplex(0),
      m_catchDegeneracies(1),
      m_fixContactNormalDirection(1)
{
}

void btGjkPairDetector::getClosestPoints(const ClosestPointInput& input, Result& output, btIDebugDraw* debugDraw,
                                         bool swapResults)
{
	(void)swapResults;
	getClosestPointsNonVirtual(input, output, debugDraw);
}

void btGjkPairDetector::getClosestPointsNonVirtual(const ClosestPointInput& input, Result& output,
                                                   btIDebugDraw* debugDraw)
{
	m_cachedSeparatingDistance = btScalar(0);
	m_lastUsedMethod = -1;
	m_curIter = 0;
	m_degenerateSimplex = 0;
	btAssert(m_minkowskiA && m_minkowskiB && m_simplexSolver);
	btAssert(caliber::isFinite(input.m_transformA) && caliber::isFinite(input.m_transformB));
	if (!m_minkowskiA || !m_minkowskiB || !m_simplexSolver || !caliber::isFinite(input.m_transformA) ||
	    !caliber::isFinite(input.m_transformB))
		return;

	const btVector3 offset = (input.m_transformA.getOrigin() + input.m_transformB.getOrigin()) * btScalar(0.5);
	btTransform transA = input.m_transformA;
	btTransform transB = input.m_transformB;
	transA.getOrigin() -= offset;
	transB.getOrigin() -= offset;

	btScalar marginA = m_useShapeMargins ? m_minkowskiA->getMargin() : m_marginA;
	btScalar marginB = m_useShapeMargins ? m_minkowskiB->getMargin() : m_marginB;
	if (m_ignoreMargin) marginA = marginB = btScalar(0);
	const btScalar marginSum = marginA + marginB;
	const btScalar maxDistance = btSqrt(btMax(input.m_maximumDistanceSquared, btScalar(0)));

	btSimplexSolverInterface& simplex = *m_simplexSolver;
	simplex.reset();
	btVector3 v = m_cachedSeparatingAxis;
	if (!caliber::isFinite(v) || v.fuzzyZero()) v.setValue(btScalar(0), btScalar(1), btScalar(0));

	btScalar squaredDistance = BT_LARGE_FLOAT;
	bool coresOverlap = false;
	bool failed = false;
	// The witnesses of the last closest point that made progress.
	btVector3 previousA(btScalar(0), btScalar(0), btScalar(0)), previousB(btScalar(0), btScalar(0), btScalar(0));
	bool haveWitnesses = false, keepPrevious = false;
	for (;;)
	{
		const btVector3 supportA = worldSupport(m_minkowskiA, transA, -v, btScalar(0));
		const btVector3 supportB = worldSupport(m_minkowskiB, transB, v, btScalar(0));
		const btVector3 w = supportA - supportB;
		if (!caliber::isFinite(w))
		{
			failed = true;
			m_degenerateSimplex = 9;
			break;
		}
		const btScalar delta = v.dot(w);
		// v.w / |v| is a lower bound on the core distance for any v, the starting axis included (a
		// good one, such as a triangle's normal, then ends a query in one step): once the reported
		// distance must exceed the maximum, nothing will be reported.
		if (delta > btScalar(0))
		{
			const btScalar lengthSquared = squaredDistance < BT_LARGE_FLOAT ? squaredDistance : v.length2();
			const btScalar lowerBound = delta / btSqrt(lengthSquared);
			if (lowerBound - marginSum > maxDistance)
			{
				// v separates the pair by more than the maximum: the axis to start from next time.
				m_cachedSeparatingAxis = v;
				return;
			}
		}
		if (squaredDistance < BT_LARGE_FLOAT && caliber_gjk::boundsMet(squaredDistance, delta, simplex.maxVertex()))
		{
			m_degenerateSimplex = delta >= squaredDistance ? 2 : 0;
			break;
		}
		// The bounds have not met, so w is new information even within the solver's equal-vertex
		// threshold; only a numerical duplicate ends the search (see btGjkConvergence.h).
		if (caliber_gjk::isDuplicateVertex(simplex, w))
		{
			m_degenerateSimplex = 1;
			break;
		}
		simplex.addVertex(w, supportA, supportB);
		btVector3 next;
		if (!simplex.closest(next))
		{
			m_degenerateSimplex = 3;
			failed = !caliber::isFinite(next);
			break;
		}
		if (next.length2() <= overlapThreshold(simplex.maxVertex()))
		{
			v = next;
			coresOverlap = true;
			m_degenerateSimplex = 6;
			break;
		}
		const btScalar previous = squaredDistance;
		const btScalar nextSquared = next.length2();
		if (previous - nextSquared <= SIMD_EPSILON * previous)
		{
			// No progress. When rounding on a sliver simplex made the new closest point worse, its
			// direction can be off by far more than its length: the previous point is the answer.
			keepPrevious = haveWitnesses && nextSquared > previous;
			if (!keepPrevious)
			{
				squaredDistance = nextSquared;
				v = next;
			}
			m_degenerateSimplex = 12;
			break;
		}
		squaredDistance = nextSquared;
		v = next;
		simplex.compute_points(previousA, previousB);
		haveWitnesses = true;
		if (++m_curIter > kMaxIterations) break;
		if (simplex.fullSimplex())
		{
			coresOverlap = true;
			m_degenerateSimplex = 13;
			break;
		}
	}
	if (failed) return;

	bool isValid = false;
	btScalar distance = btScalar(0);
	btVector3 normalInB(btScalar(0), btScalar(1), btScalar(0));
	btVector3 pointOnA, pointOnB;
	if (!coresOverlap)
	{
		if (keepPrevious)
		{
			pointOnA = previousA;
			pointOnB = previousB;
		}
		else
		{
			simplex.compute_points(pointOnA, pointOnB);
		}
		const btVector3 delta = pointOnA - pointOnB;
		const btScalar lengthSquared = delta.length2();
		if (lengthSquared > overlapThreshold(simplex.maxVertex()) && caliber::isFinite(delta))
		{
			const btScalar length = btSqrt(lengthSquared);
			normalInB = delta / length;
			pointOnA -= normalInB * marginA;
			pointOnB += normalInB * marginB;
			distance = length - marginSum;
			isValid = true;
			m_lastUsedMethod = 1;
		}
		else
		{
			coresOverlap = true;
			m_degenerateSimplex = 5;
		}
	}

	const bool checkDegenerate =
	    m_catchDegeneracies && m_degenerateSimplex && isValid && distance + marginSum < kDegenerateContactTolerance;
	if ((coresOverlap || checkDegenerate) && m_penetrationDepthSolver)
	{
		btVector3 solverAxis(btScalar(0), btScalar(0), btScalar(0));
		btVector3 solverA(btScalar(0), btScalar(0), btScalar(0));
		btVector3 solverB(btScalar(0), btScalar(0), btScalar(0));
		const bool penetrating = m_penetrationDepthSolver->calcPenDepth(
		    simplex, m_minkowskiA, m_minkowskiB, transA, transB, solverAxis, solverA, solverB, debugDraw);
		const btVector3 delta = solverB - solverA;
		const btScalar lengthSquared = delta.length2();
		if (penetrating && caliber::isFinite(delta) && caliber::isFinite(solverAxis))
		{
			btVector3 normal = solverAxis;
			btScalar depthDistance = btScalar(0);
			if (lengthSquared > SIMD_EPSILON * SIMD_EPSILON)
			{
				const btScalar length = btSqrt(lengthSquared);
				normal = delta / length;
				depthDistance = -length;
			}
			if (normal.length2() > SIMD_EPSILON && (!isValid || depthDistance < distance))
			{
				normalInB = normal.normalized();
				distance = depthDistance;
				pointOnA = solverA;
				pointOnB = solverB;
				isValid = true;
				m_lastUsedMethod = 3;
			}
			else
			{
				m_lastUsedMethod = 4;
			}
		}
		else
		{
			// The solver found the full shapes apart (or failed): a finite, non-zero gap is still a result.
			const btScalar length = btSqrt(lengthSquared);
			if (!isValid && caliber::isFinite(delta) && length > SIMD_EPSILON)
			{
				normalInB = -delta / length;
				distance = length;
				pointOnA = solverA;
				pointOnB = solverB;
				isValid = true;
				m_lastUsedMethod = 6;
			}
			else
			{
				m_lastUsedMethod = 5;
			}
		}
	}

	if (!isValid || !(distance < btScalar(0) || distance * distance < input.m_maximumDistanceSquared)) return;

	if (m_fixContactNormalDirection && distance < btScalar(0))
	{
		// The overlap along +n (A on the +n side of B) must not exceed the overlap along -n; otherwise
		// the solver returned the normal the wrong way round.
		const btScalar overlapPlus = worldSupport(m_minkowskiB, transB, normalInB, marginB).dot(normalInB) -
		                             worldSupport(m_minkowskiA, transA, -normalInB, marginA).dot(normalInB);
		const btScalar overlapMinus = worldSupport(m_minkowskiA, transA, normalInB, marginA).dot(normalInB) -
		                              worldSupport(m_minkowskiB, transB, -normalInB, marginB).dot(normalInB);
		if (overlapMinus < overlapPlus - kRelativeTolerance * (btFabs(overlapPlus) + btScalar(1)))
			normalInB = -normalInB;
	}

	m_cachedSeparatingAxis = normalInB;
	m_cachedSeparatingDistance = distance;
	output.addContactPoint(normalInB, pointOnB + offset, distance);
}
