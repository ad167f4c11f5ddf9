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

// Why the GJK loop stopped (the public m_degenerateSimplex). Hitting the iteration limit leaves
// kConverged: the last closest point is used as it is.
enum GjkStop
{
	kConverged = 0,              // the lower and upper bounds on the distance met
	kRepeatedSupport = 1,        // the new support point duplicates a vertex of the simplex
	kLowerBoundPassedUpper = 2,  // bounds met with v.w >= |v|^2 (rounding on a flat face)
	kSimplexSolverFailed = 3,    // the simplex solver found no closest point
	kWitnessesCoincide = 5,      // the cores' closest points are too close for a normal
	kClosestPointAtOrigin = 6,   // the simplex reached the origin: the cores overlap
	kNonFiniteSupport = 9,       // a shape returned a non-finite support point
	kNoProgress = 12,            // the closest point stopped getting closer
	kFullSimplex = 13,           // a tetrahedron enclosing the origin: the cores overlap
};

// How the query got its result (the public m_lastUsedMethod).
enum GjkMethod
{
	kNoResult = -1,
	kGjkDistance = 1,             // GJK's closest points, moved out by the margins
	kDepthSolver = 3,             // the penetration depth solver's points
	kGjkKeptOverDepthSolver = 4,  // the depth solver ran but GJK's result was deeper or its normal unusable
	kDepthSolverFailed = 5,
	kDepthSolverGap = 6,  // the depth solver found the shapes apart; its gap is the result
};

// The pair as GJK works on it: both shapes in a frame centred between their origins (offset is where
// that centre lies in the world), with the margins this query uses.
struct CentredPair
{
	const btConvexShape* shapeA;
	const btConvexShape* shapeB;
	btTransform transA, transB;
	btVector3 offset;
	btScalar marginA, marginB, marginSum;
};

// Where the GJK loop left the search.
struct GjkOutcome
{
	btVector3 v;  // the closest point of the simplex to the origin (or the separating axis)
	btScalar squaredDistance;
	int stop;  // GjkStop
	int iterations;
	bool separatedBeyondMaximum;  // v proved the pair farther apart than the maximum distance
	bool coresOverlap;
	bool failed;  // nothing can be reported
	// The witnesses of the last closest point that made progress, and whether they are the answer.
	btVector3 previousA, previousB;
	bool keepPrevious;
};

// The contact being built: the normal points from B towards A, the points are in the centred frame.
struct Candidate
{
	bool isValid;
	btScalar distance;
	btVector3 normalInB, pointOnA, pointOnB;
	int method;  // GjkMethod

	// Takes the depth solver's witnesses (already on the shapes' surfaces) as the contact.
	void takeWitnesses(const btVector3& normal, btScalar signedDistance, const btVector3& onA, const btVector3& onB,
	                   int how)
	{
		normalInB = normal;
		distance = signedDistance;
		pointOnA = onA;
		pointOnB = onB;
		isValid = true;
		method = how;
	}
};

// GJK on the margin-free cores from the axis start: each step asks both shapes for their support
// point along the current closest point v of the simplex and stops when the lower bound v.w / |v|
// meets the upper bound |v|, or when the search degenerates.
GjkOutcome runGjk(const CentredPair& pair, btSimplexSolverInterface& simplex, const btVector3& start,
                  btScalar maxDistance)
{
	GjkOutcome out;
	out.v = start;
	out.squaredDistance = BT_LARGE_FLOAT;
	out.stop = kConverged;
	out.iterations = 0;
	out.separatedBeyondMaximum = false;
	out.coresOverlap = false;
	out.failed = false;
	out.previousA.setValue(btScalar(0), btScalar(0), btScalar(0));
	out.previousB.setValue(btScalar(0), btScalar(0), btScalar(0));
	out.keepPrevious = false;
	bool haveWitnesses = false;
	btVector3& v = out.v;
	for (;;)
	{
		const btVector3 supportA = worldSupport(pair.shapeA, pair.transA, -v, btScalar(0));
		const btVector3 supportB = worldSupport(pair.shapeB, pair.transB, v, btScalar(0));
		const btVector3 w = supportA - supportB;
		if (!caliber::isFinite(w))
		{
			out.failed = true;
			out.stop = kNonFiniteSupport;
			return out;
		}
		const btScalar delta = v.dot(w);
		// v.w / |v| is a lower bound on the core distance for any v, the starting axis included (a
		// good one, such as a triangle's normal, then ends a query in one step): once the reported
		// distance must exceed the maximum, nothing will be reported.
		if (delta > btScalar(0))
		{
			const btScalar lengthSquared = out.squaredDistance < BT_LARGE_FLOAT ? out.squaredDistance : v.length2();
			const btScalar lowerBound = delta / btSqrt(lengthSquared);
			if (lowerBound - pair.marginSum > maxDistance)
			{
				out.separatedBeyondMaximum = true;
				return out;
			}
		}
		if (out.squaredDistance < BT_LARGE_FLOAT &&
		    caliber::gjk::boundsMet(out.squaredDistance, delta, simplex.maxVertex()))
		{
			out.stop = delta >= out.squaredDistance ? kLowerBoundPassedUpper : kConverged;
			return out;
		}
		// The bounds have not met, so w is new information even within the solver's equal-vertex
		// threshold; only a numerical duplicate ends the search (see btGjkConvergence.h).
		if (caliber::gjk::isDuplicateVertex(simplex, w))
		{
			out.stop = kRepeatedSupport;
			return out;
		}
		simplex.addVertex(w, supportA, supportB);
		btVector3 next;
		if (!simplex.closest(next))
		{
			out.stop = kSimplexSolverFailed;
			out.failed = !caliber::isFinite(next);
			return out;
		}
		if (next.length2() <= overlapThreshold(simplex.maxVertex()))
		{
			v = next;
			out.coresOverlap = true;
			out.stop = kClosestPointAtOrigin;
			return out;
		}
		const btScalar previous = out.squaredDistance;
		const btScalar nextSquared = next.length2();
		if (previous - nextSquared <= SIMD_EPSILON * previous)
		{
			// No progress. When rounding on a sliver simplex made the new closest point worse, its
			// direction can be off by far more than its length: the previous point is the answer.
			out.keepPrevious = haveWitnesses && nextSquared > previous;
			if (!out.keepPrevious)
			{
				out.squaredDistance = nextSquared;
				v = next;
			}
			out.stop = kNoProgress;
			return out;
		}
		out.squaredDistance = nextSquared;
		v = next;
		simplex.compute_points(out.previousA, out.previousB);
		haveWitnesses = true;
		if (++out.iterations > kMaxIterations) return out;
		if (simplex.fullSimplex())
		{
			out.coresOverlap = true;
			out.stop = kFullSimplex;
			return out;
		}
	}
}

// The cores are apart: the witnesses GJK ended with, moved out by the margins. When they are too
// close for a normal, the cores count as overlapping instead.
void takeGjkWitnesses(const CentredPair& pair, btSimplexSolverInterface& simplex, GjkOutcome& gjk, Candidate& contact)
{
	if (gjk.keepPrevious)
	{
		contact.pointOnA = gjk.previousA;
		contact.pointOnB = gjk.previousB;
	}
	else
	{
		simplex.compute_points(contact.pointOnA, contact.pointOnB);
	}
	const btVector3 delta = contact.pointOnA - contact.pointOnB;
	const btScalar lengthSquared = delta.length2();
	if (lengthSquared > overlapThreshold(simplex.maxVertex()) && caliber::isFinite(delta))
	{
		const btScalar length = btSqrt(lengthSquared);
		contact.normalInB = delta / length;
		contact.pointOnA -= contact.normalInB * pair.marginA;
		contact.pointOnB += contact.normalInB * pair.marginB;
		contact.distance = length - pair.marginSum;
		contact.isValid = true;
		contact.method = kGjkDistance;
	}
	else
	{
		gjk.coresOverlap = true;
		gjk.stop = kWitnessesCoincide;
	}
}

// The penetration depth solver's answer replaces the candidate when it is deeper (or the candidate is
// not valid). When the solver finds the full shapes apart, a finite, non-zero gap is still a result.
void consultDepthSolver(const CentredPair& pair, btConvexPenetrationDepthSolver& solver,
                        btSimplexSolverInterface& simplex, btIDebugDraw* debugDraw, Candidate& contact)
{
	btVector3 solverAxis(btScalar(0), btScalar(0), btScalar(0));
	btVector3 solverA(btScalar(0), btScalar(0), btScalar(0));
	btVector3 solverB(btScalar(0), btScalar(0), btScalar(0));
	const bool penetrating = solver.calcPenDepth(simplex, pair.shapeA, pair.shapeB, pair.transA, pair.transB,
	                                             solverAxis, solverA, solverB, debugDraw);
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
		if (normal.length2() > SIMD_EPSILON && (!contact.isValid || depthDistance < contact.distance))
			contact.takeWitnesses(normal.normalized(), depthDistance, solverA, solverB, kDepthSolver);
		else
		{
			contact.method = kGjkKeptOverDepthSolver;
		}
		return;
	}
	const btScalar length = btSqrt(lengthSquared);
	if (!contact.isValid && caliber::isFinite(delta) && length > SIMD_EPSILON)
		contact.takeWitnesses(-delta / length, length, solverA, solverB, kDepthSolverGap);
	else
	{
		contact.method = kDepthSolverFailed;
	}
}

// A penetration normal must point from B towards A: the overlap along +n (A on the +n side of B) must
// not exceed the overlap along -n; otherwise the solver returned the normal the wrong way round.
void orientPenetrationNormal(const CentredPair& pair, Candidate& contact)
{
	const btVector3 n = contact.normalInB;
	const btScalar overlapPlus = worldSupport(pair.shapeB, pair.transB, n, pair.marginB).dot(n) -
	                             worldSupport(pair.shapeA, pair.transA, -n, pair.marginA).dot(n);
	const btScalar overlapMinus = worldSupport(pair.shapeA, pair.transA, n, pair.marginA).dot(n) -
	                              worldSupport(pair.shapeB, pair.transB, -n, pair.marginB).dot(n);
	if (overlapMinus < overlapPlus - kRelativeTolerance * (btFabs(overlapPlus) + btScalar(1))) contact.normalInB = -n;
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
	m_lastUsedMethod = kNoResult;
	m_curIter = 0;
	m_degenerateSimplex = kConverged;
	btAssert(m_minkowskiA && m_minkowskiB && m_simplexSolver);
	btAssert(caliber::isFinite(input.m_transformA) && caliber::isFinite(input.m_transformB));
	if (!m_minkowskiA || !m_minkowskiB || !m_simplexSolver || !caliber::isFinite(input.m_transformA) ||
	    !caliber::isFinite(input.m_transformB))
		return;

	// Work relative to the midpoint of the origins: coordinates stay small for distant pairs.
	CentredPair pair;
	pair.shapeA = m_minkowskiA;
	pair.shapeB = m_minkowskiB;
	pair.offset = (input.m_transformA.getOrigin() + input.m_transformB.getOrigin()) * btScalar(0.5);
	pair.transA = input.m_transformA;
	pair.transB = input.m_transformB;
	pair.transA.getOrigin() -= pair.offset;
	pair.transB.getOrigin() -= pair.offset;
	pair.marginA = m_useShapeMargins ? m_minkowskiA->getMargin() : m_marginA;
	pair.marginB = m_useShapeMargins ? m_minkowskiB->getMargin() : m_marginB;
	if (m_ignoreMargin) pair.marginA = pair.marginB = btScalar(0);
	pair.marginSum = pair.marginA + pair.marginB;
	const btScalar maxDistance = btSqrt(btMax(input.m_maximumDistanceSquared, btScalar(0)));

	btSimplexSolverInterface& simplex = *m_simplexSolver;
	simplex.reset();
	btVector3 start = m_cachedSeparatingAxis;
	if (!caliber::isFinite(start) || start.fuzzyZero()) start.setValue(btScalar(0), btScalar(1), btScalar(0));
	GjkOutcome gjk = runGjk(pair, simplex, start, maxDistance);
	m_curIter = gjk.iterations;
	m_degenerateSimplex = gjk.stop;
	if (gjk.separatedBeyondMaximum)
	{
		// The axis that proved it is the one to start from next time.
		m_cachedSeparatingAxis = gjk.v;
		return;
	}
	if (gjk.failed) return;

	Candidate contact;
	contact.isValid = false;
	contact.distance = btScalar(0);
	contact.normalInB.setValue(btScalar(0), btScalar(1), btScalar(0));
	contact.method = kNoResult;
	if (!gjk.coresOverlap) takeGjkWitnesses(pair, simplex, gjk, contact);
	m_degenerateSimplex = gjk.stop;

	// A degenerate ending close to contact is checked by the depth solver too.
	const bool checkDegenerate = m_catchDegeneracies && gjk.stop != kConverged && contact.isValid &&
	                             contact.distance + pair.marginSum < kDegenerateContactTolerance;
	if ((gjk.coresOverlap || checkDegenerate) && m_penetrationDepthSolver)
		consultDepthSolver(pair, *m_penetrationDepthSolver, simplex, debugDraw, contact);
	m_lastUsedMethod = contact.method;

	if (!contact.isValid ||
	    !(contact.distance < btScalar(0) || contact.distance * contact.distance < input.m_maximumDistanceSquared))
		return;
	if (m_fixContactNormalDirection && contact.distance < btScalar(0)) orientPenetrationNormal(pair, contact);

	m_cachedSeparatingAxis = contact.normalInB;
	m_cachedSeparatingDistance = contact.distance;
	output.addContactPoint(contact.normalInB, contact.pointOnB + pair.offset, contact.distance);
}
