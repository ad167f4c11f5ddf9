// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/NarrowPhaseCollision/btGjkEpa2.h"

#include "BulletCollision/NarrowPhaseCollision/btGjkConvergence.h"
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"

// GJK runs on the Minkowski difference D = A - B with btVoronoiSimplexSolver as its simplex. When D
// holds the origin, EPA grows a polytope inside D from GJK's final simplex, always splitting the face
// nearest the origin, until the support point along that face's normal is no further out than the face.
// Both work relative to the midpoint of the two origins so that far-away pairs keep their precision.

namespace
{
const int kMaxGjkIterations = 128;
const int kMaxEpaVertices = 128;
const int kMaxEpaFaces = 2 * kMaxEpaVertices;  // a closed triangulated polytope has 2V - 4 faces
const int kMaxEpaIterations = kMaxEpaVertices - 4;

// Relative accuracy GJK and EPA stop at: a few hundred ulps, far above rounding in the dot products.
const btScalar kRelativeTolerance = btScalar(256) * SIMD_EPSILON;

// Relative gap between EPA's lower and upper depth bounds below which the lower one is reported.
const btScalar kBoundsAgreement = btScalar(1e-4);

// One side of the Minkowski difference: a convex shape, or (shape == nullptr) a point; either grown by
// margin. The transform is already shifted by the query's offset.
struct SupportSide
{
	const btConvexShape* shape;
	btTransform transform;
	btScalar margin;

	// The point of this side furthest along the world direction dir.
	btVector3 support(const btVector3& dir) const
	{
		btVector3 point = transform.getOrigin();
		if (shape) point = transform(shape->localGetSupportingVertexWithoutMargin(dir * transform.getBasis()));
		if (margin != btScalar(0))
		{
			btVector3 unit = dir;
			unit.safeNormalize();
			point += unit * margin;
		}
		return point;
	}
};

struct MinkowskiDifference
{
	SupportSide a;
	SupportSide b;

	// Support of A - B along dir, with the points of A and B it came from.
	btVector3 support(const btVector3& dir, btVector3& onA, btVector3& onB) const
	{
		onA = a.support(dir);
		onB = b.support(-dir);
		return onA - onB;
	}
};

enum class GjkOutcome
{
	Separated,
	Overlapping,
	Failed
};

// Runs GJK; on return the simplex holds the final simplex and v the closest point of D to the origin.
GjkOutcome runGjk(const MinkowskiDifference& diff, const btVector3& guess, btVoronoiSimplexSolver& simplex,
                  btVector3& v)
{
	simplex.reset();
	btVector3 dir = guess;
	if (!caliber::isFinite(dir) || dir.fuzzyZero()) dir.setValue(btScalar(1), btScalar(0), btScalar(0));
	btVector3 onA, onB;
	btVector3 w = diff.support(-dir, onA, onB);
	if (!caliber::isFinite(w)) return GjkOutcome::Failed;
	simplex.addVertex(w, onA, onB);
	v = w;
	btScalar distanceSquared = v.length2();
	for (int iteration = 0; iteration < kMaxGjkIterations; ++iteration)
	{
		const btScalar scale = simplex.maxVertex();
		// Touching counts as overlapping: the origin is within rounding of D.
		if (distanceSquared <= btScalar(16) * SIMD_EPSILON * SIMD_EPSILON * (scale + btScalar(1)))
			return GjkOutcome::Overlapping;
		w = diff.support(-v, onA, onB);
		if (!caliber::isFinite(w)) return GjkOutcome::Failed;
		if (caliber::gjk::boundsMet(distanceSquared, v.dot(w), scale)) return GjkOutcome::Separated;
		// Only a numerical duplicate ends an unconverged search (see btGjkConvergence.h).
		if (caliber::gjk::isDuplicateVertex(simplex, w)) break;
		simplex.addVertex(w, onA, onB);
		btVector3 next;
		if (!simplex.closest(next)) return GjkOutcome::Failed;
		if (simplex.fullSimplex()) return GjkOutcome::Overlapping;
		const btScalar nextSquared = next.length2();
		const btScalar lastVDotW = v.dot(w);
		v = next;
		// No progress: v is as close as the arithmetic allows.
		if (distanceSquared - nextSquared <= SIMD_EPSILON * distanceSquared)
		{
			distanceSquared = nextSquared;
			// A face through the origin leaves |v| at its rounding, which for a thin triangle exceeds the
			// touching threshold below (1.7e-15 in double). The support plane did not separate (v.w <= 0)
			// and |v| is below a repeat's distance: touching, which counts as overlapping.
			const btScalar touching = caliber::gjk::kDuplicateVertexDistance;
			if (lastVDotW <= btScalar(0) &&
			    distanceSquared <= touching * touching * (simplex.maxVertex() + btScalar(1)))
				return GjkOutcome::Overlapping;
			break;
		}
		distanceSquared = nextSquared;
	}
	if (distanceSquared <= btScalar(16) * SIMD_EPSILON * SIMD_EPSILON * (simplex.maxVertex() + btScalar(1)))
		return GjkOutcome::Overlapping;
	return GjkOutcome::Separated;
}

struct EpaFace
{
	int vertex[3];
	btVector3 normal;   // outward unit normal (zero for a degenerate face)
	btScalar distance;  // normal . vertex, BT_LARGE_FLOAT for a degenerate face
};

struct EpaEdge
{
	int from;
	int to;
};

// The expanding polytope, in fixed arrays sized for the worst case so that EPA never allocates.
struct EpaPolytope
{
	btVector3 w[kMaxEpaVertices];
	btVector3 onA[kMaxEpaVertices];
	btVector3 onB[kMaxEpaVertices];
	int numVertices;
	EpaFace faces[kMaxEpaFaces];
	int numFaces;
	EpaEdge horizon[3 * kMaxEpaFaces];
	int numHorizon;

	int addVertex(const btVector3& wv, const btVector3& a, const btVector3& b)
	{
		w[numVertices] = wv;
		onA[numVertices] = a;
		onB[numVertices] = b;
		return numVertices++;
	}

	bool addFace(int i0, int i1, int i2)
	{
		if (numFaces >= kMaxEpaFaces) return false;
		EpaFace& face = faces[numFaces++];
		face.vertex[0] = i0;
		face.vertex[1] = i1;
		face.vertex[2] = i2;
		const btVector3 n = (w[i1] - w[i0]).cross(w[i2] - w[i0]);
		const btScalar length = n.length();
		const btScalar edgeScale = (w[i1] - w[i0]).length2() + (w[i2] - w[i0]).length2();
		const btScalar distance = length > btScalar(0) ? n.dot(w[i0]) / length : btScalar(0);
		// The origin is inside the polytope, so a face it lies clearly outside of has been wound the wrong
		// way by rounding (a nearly flat horizon fan): it must never be chosen or seen.
		const btScalar flippedLimit = -kRelativeTolerance * (btSqrt(edgeScale) + w[i0].length());
		if (length > SIMD_EPSILON * edgeScale && length > btScalar(0) && distance >= flippedLimit)
		{
			face.normal = n / length;
			face.distance = distance;
		}
		else
		{
			face.normal.setValue(btScalar(0), btScalar(0), btScalar(0));
			face.distance = BT_LARGE_FLOAT;
		}
		return true;
	}

	void addHorizonEdge(int from, int to)
	{
		// An edge shared by two removed faces appears once in each direction: both copies cancel.
		for (int i = 0; i < numHorizon; ++i)
		{
			if (horizon[i].from == to && horizon[i].to == from)
			{
				horizon[i] = horizon[--numHorizon];
				return;
			}
		}
		horizon[numHorizon].from = from;
		horizon[numHorizon].to = to;
		++numHorizon;
	}
};

// Volume (times 6) of the tetrahedron of the four points.
btScalar tetrahedronVolume6(const btVector3& a, const btVector3& b, const btVector3& c, const btVector3& d)
{
	return (b - a).dot((c - a).cross(d - a));
}

// Grows GJK's final simplex (1 to 4 vertices, holding the origin) to a tetrahedron of non-zero volume.
// Returns false when D is flat (every direction tried stays in one plane).
bool buildInitialTetrahedron(const MinkowskiDifference& diff, EpaPolytope& poly)
{
	btVector3 onA, onB;
	btScalar scale = btScalar(0);
	for (int i = 0; i < poly.numVertices; ++i) scale = btMax(scale, poly.w[i].length2());
	if (poly.numVertices == 4 &&
	    btFabs(tetrahedronVolume6(poly.w[0], poly.w[1], poly.w[2], poly.w[3])) <= SIMD_EPSILON * scale * btSqrt(scale))
		poly.numVertices = 3;  // a flat GJK tetrahedron: rebuild from one face
	static const btVector3 kAxes[6] = {btVector3(1, 0, 0),  btVector3(0, 1, 0),  btVector3(0, 0, 1),
	                                   btVector3(-1, 0, 0), btVector3(0, -1, 0), btVector3(0, 0, -1)};
	if (poly.numVertices == 1)
	{
		for (const btVector3& axis : kAxes)
		{
			const btVector3 wv = diff.support(axis, onA, onB);
			if ((wv - poly.w[0]).length2() > SIMD_EPSILON * (scale + wv.length2()))
			{
				poly.addVertex(wv, onA, onB);
				break;
			}
		}
		if (poly.numVertices < 2) return false;
	}
	if (poly.numVertices == 2)
	{
		const btVector3 line = poly.w[1] - poly.w[0];
		btVector3 axis(btScalar(0), btScalar(0), btScalar(0));
		axis[line.absolute().minAxis()] = btScalar(1);
		const btVector3 side1 = line.cross(axis).normalized();
		const btVector3 side2 = line.cross(side1).normalized();
		const btVector3 tries[4] = {side1, -side1, side2, -side2};
		for (const btVector3& dir : tries)
		{
			const btVector3 wv = diff.support(dir, onA, onB);
			const btScalar offLine = (wv - poly.w[0]).cross(line).length2();
			if (offLine > SIMD_EPSILON * line.length2() * ((wv - poly.w[0]).length2() + line.length2()))
			{
				poly.addVertex(wv, onA, onB);
				break;
			}
		}
		if (poly.numVertices < 3) return false;
	}
	if (poly.numVertices == 3)
	{
		const btVector3 n = (poly.w[1] - poly.w[0]).cross(poly.w[2] - poly.w[0]);
		if (n.fuzzyZero()) return false;
		const btVector3 tries[2] = {n, -n};
		for (const btVector3& dir : tries)
		{
			const btVector3 wv = diff.support(dir, onA, onB);
			const btScalar height = n.dot(wv - poly.w[0]);
			if (height * height > SIMD_EPSILON * n.length2() * (scale + wv.length2()))
			{
				poly.addVertex(wv, onA, onB);
				break;
			}
		}
		if (poly.numVertices < 4) return false;
	}
	// Wind each face so that its normal points away from the opposite vertex.
	static const int kFaces[4][4] = {{0, 1, 2, 3}, {0, 3, 1, 2}, {0, 2, 3, 1}, {1, 3, 2, 0}};
	for (const int* f : kFaces)
	{
		const btVector3 n = (poly.w[f[1]] - poly.w[f[0]]).cross(poly.w[f[2]] - poly.w[f[0]]);
		if (n.dot(poly.w[f[3]] - poly.w[f[0]]) > btScalar(0))
			poly.addFace(f[0], f[2], f[1]);
		else
			poly.addFace(f[0], f[1], f[2]);
	}
	return true;
}

int closestFace(const EpaPolytope& poly)
{
	int best = -1;
	btScalar bestDistance = BT_LARGE_FLOAT;
	for (int i = 0; i < poly.numFaces; ++i)
	{
		if (poly.faces[i].distance < bestDistance)
		{
			bestDistance = poly.faces[i].distance;
			best = i;
		}
	}
	return best;
}

// Unnormalised barycentric weights of the origin's projection on the face's plane; returns their sum
// (twice the face's area, 0 for a degenerate face).
btScalar faceWeights(const EpaPolytope& poly, const EpaFace& face, btScalar* weight)
{
	const btVector3& n = face.normal;
	const btVector3 p = n * btMax(face.distance, btScalar(0));
	const btVector3& a = poly.w[face.vertex[0]];
	const btVector3& b = poly.w[face.vertex[1]];
	const btVector3& c = poly.w[face.vertex[2]];
	weight[0] = (b - p).cross(c - p).dot(n);
	weight[1] = (c - p).cross(a - p).dot(n);
	weight[2] = (a - p).cross(b - p).dot(n);
	return weight[0] + weight[1] + weight[2];
}

// Witnesses from the origin's projection on the face (weights clamped to the face), normal from B to A
// and depth. Returns false for a degenerate face or non-finite results.
bool witnessesFromFace(const EpaPolytope& poly, const EpaFace& face, btVector3& witnessA, btVector3& witnessB,
                       btVector3& normalBtoA, btScalar& depth)
{
	btScalar weight[3];
	faceWeights(poly, face, weight);
	btScalar sum = btScalar(0);
	for (btScalar& x : weight)
	{
		x = btMax(x, btScalar(0));
		sum += x;
	}
	if (!(sum > btScalar(0)) || !(face.distance < BT_LARGE_FLOAT)) return false;
	witnessA.setValue(btScalar(0), btScalar(0), btScalar(0));
	witnessB = witnessA;
	for (int i = 0; i < 3; ++i)
	{
		witnessA += poly.onA[face.vertex[i]] * (weight[i] / sum);
		witnessB += poly.onB[face.vertex[i]] * (weight[i] / sum);
	}
	normalBtoA = -face.normal;
	depth = btMax(face.distance, btScalar(0));
	// Where the weights were clamped (the origin projects outside the face) the interpolated points are
	// no longer a normal's length apart: keep their midpoint and separate them along the normal, so that
	// the witnesses always agree with the normal and depth.
	const btVector3 middle = (witnessA + witnessB) * btScalar(0.5);
	witnessA = middle + face.normal * (depth * btScalar(0.5));
	witnessB = middle - face.normal * (depth * btScalar(0.5));
	return caliber::isFinite(witnessA) && caliber::isFinite(witnessB);
}

// EPA from the simplex GJK ended with. Fills the penetration results; returns false when it fails.
bool runEpa(const MinkowskiDifference& diff, const btVoronoiSimplexSolver& simplex, EpaPolytope& poly,
            btVector3& witnessA, btVector3& witnessB, btVector3& normalBtoA, btScalar& depth)
{
	poly.numVertices = simplex.getSimplex(poly.onA, poly.onB, poly.w);
	poly.numFaces = 0;
	if (poly.numVertices < 1 || !buildInitialTetrahedron(diff, poly)) return false;

	int best = closestFace(poly);
	// The depth lies between two bounds: the nearest face's distance (the polytope is inside D) and the
	// support distance of D along any normal tried (moving by it along that normal separates the
	// shapes). On curved parts of D the upper bound converges quadratically in the normal's error while
	// the lower one needs the polytope refined all around, so unless a face converged on its own the
	// answer takes the normal of the best upper bound. Faces refer to vertices, which are never
	// removed: a copy of a face stays valid whatever later expansion steps do.
	EpaFace upperFace = poly.faces[best >= 0 ? best : 0];
	btScalar upperDistance = BT_LARGE_FLOAT;
	bool converged = false;
	bool expansionFailed = false;
	for (int iteration = 0; iteration < kMaxEpaIterations && best >= 0; ++iteration)
	{
		const EpaFace face = poly.faces[best];
		btVector3 onA, onB;
		const btVector3 wv = diff.support(face.normal, onA, onB);
		if (!caliber::isFinite(wv)) return false;
		const btScalar supportDistance = face.normal.dot(wv);
		if (face.distance < BT_LARGE_FLOAT && supportDistance < upperDistance)
		{
			upperDistance = supportDistance;
			upperFace = face;
		}
		const btScalar tolerance = kRelativeTolerance * (btFabs(face.distance) + btSqrt(wv.length2())) + SIMD_EPSILON;
		// Converged: D reaches no further than this face along its normal.
		if (supportDistance - face.distance <= tolerance)
		{
			converged = true;
			break;
		}
		// The nearest face has caught up with the best upper bound: that bound is the depth.
		if (upperDistance - face.distance <= tolerance) break;
		if (poly.numVertices >= kMaxEpaVertices) break;
		const int newIndex = poly.addVertex(wv, onA, onB);
		const btScalar visibilityTolerance = btScalar(16) * SIMD_EPSILON * (wv.length() + btScalar(1));
		// Remove every face that sees the new vertex; the boundary of the removed region is the horizon.
		poly.numHorizon = 0;
		for (int i = 0; i < poly.numFaces;)
		{
			const EpaFace& f = poly.faces[i];
			// Any face the new vertex is in front of (beyond rounding) goes: keeping a nearly-visible face
			// would leave a fold in which later faces can be wound the wrong way.
			const bool visible = (i == best) || f.normal.dot(wv - poly.w[f.vertex[0]]) > visibilityTolerance;
			if (!visible)
			{
				++i;
				continue;
			}
			poly.addHorizonEdge(f.vertex[0], f.vertex[1]);
			poly.addHorizonEdge(f.vertex[1], f.vertex[2]);
			poly.addHorizonEdge(f.vertex[2], f.vertex[0]);
			if (i == best) best = -2;  // removed
			poly.faces[i] = poly.faces[--poly.numFaces];
			if (best == poly.numFaces) best = i;
		}
		for (int e = 0; e < poly.numHorizon && !expansionFailed; ++e)
			expansionFailed = !poly.addFace(poly.horizon[e].from, poly.horizon[e].to, newIndex);
		best = closestFace(poly);
		// Rounding can make the visible region a ring rather than a disc; the polytope then stops being a
		// sphere and may outgrow its arrays. Keep the last good face.
		if (expansionFailed || best < 0)
		{
			expansionFailed = true;
			break;
		}
	}
	if (!converged || best < 0)
	{
		if (!(upperDistance < BT_LARGE_FLOAT)) return false;
		if (!witnessesFromFace(poly, upperFace, witnessA, witnessB, normalBtoA, depth)) return false;
		// Where the bounds agree closely the lower one is kept (the polytope lies inside D, so it is never
		// too deep); a coarse polytope (every direction about equally deep) gives the upper one.
		btScalar reported = upperDistance;
		if (!expansionFailed && best >= 0 &&
		    upperDistance - poly.faces[best].distance <= kBoundsAgreement * (btFabs(upperDistance) + btScalar(1)))
			reported = poly.faces[best].distance;
		// Separate the witnesses to that depth about their midpoint.
		const btVector3 middle = (witnessA + witnessB) * btScalar(0.5);
		depth = btMax(reported, btScalar(0));
		witnessA = middle - normalBtoA * (depth * btScalar(0.5));
		witnessB = middle + normalBtoA * (depth * btScalar(0.5));
		return caliber::isFinite(witnessA) && caliber::isFinite(witnessB);
	}

	// Flat sides of D are split into coplanar faces at the same distance up to rounding; the witnesses
	// come from the one the origin projects into (the least negative barycentric weight). A face at the
	// same distance but tilted (on a curved side of D) is not part of the converged side: its normal
	// would be wrong by its tilt.
	const EpaFace& bestFace = poly.faces[best];
	const btScalar slack = kRelativeTolerance * (btFabs(bestFace.distance) + btScalar(1));
	const btScalar coplanarCosine = btScalar(1) - kRelativeTolerance;
	int chosen = best;
	btScalar chosenScore = -BT_LARGE_FLOAT;
	btScalar weight[3];
	for (int i = 0; i < poly.numFaces; ++i)
	{
		if (!(poly.faces[i].distance <= bestFace.distance + slack)) continue;
		if (i != best && !(poly.faces[i].normal.dot(bestFace.normal) >= coplanarCosine)) continue;
		const btScalar total = faceWeights(poly, poly.faces[i], weight);
		if (!(total > btScalar(0))) continue;
		const btScalar score = btMin(weight[0], btMin(weight[1], weight[2])) / total;
		if (score > chosenScore)
		{
			chosenScore = score;
			chosen = i;
		}
	}
	return witnessesFromFace(poly, poly.faces[chosen], witnessA, witnessB, normalBtoA, depth);
}

void setFailure(btGjkEpaSolver2::sResults& results, btGjkEpaSolver2::sResults::eStatus status)
{
	results.status = status;
	results.witnesses[0].setValue(btScalar(0), btScalar(0), btScalar(0));
	results.witnesses[1] = results.witnesses[0];
	results.normal = results.witnesses[0];
	results.distance = btScalar(0);
}

// Shared set-up of the two-shape queries; returns false (results set to GJK_Failed) for bad input.
bool setUp(const btConvexShape* shape0, const btTransform& wtrs0, const btConvexShape* shape1, const btTransform& wtrs1,
           bool usemargins, MinkowskiDifference& diff, btVector3& offset, btGjkEpaSolver2::sResults& results)
{
	btAssert(shape0 && shape1);
	btAssert(caliber::isFinite(wtrs0) && caliber::isFinite(wtrs1));
	if (!shape0 || !shape1 || !caliber::isFinite(wtrs0) || !caliber::isFinite(wtrs1))
	{
		setFailure(results, btGjkEpaSolver2::sResults::GJK_Failed);
		return false;
	}
	offset = (wtrs0.getOrigin() + wtrs1.getOrigin()) * btScalar(0.5);
	diff.a.shape = shape0;
	diff.a.transform = wtrs0;
	diff.a.transform.getOrigin() -= offset;
	diff.a.margin = usemargins ? shape0->getMargin() : btScalar(0);
	diff.b.shape = shape1;
	diff.b.transform = wtrs1;
	diff.b.transform.getOrigin() -= offset;
	diff.b.margin = usemargins ? shape1->getMargin() : btScalar(0);
	return true;
}

// Separated results from GJK's final simplex.
bool fillSeparated(btVoronoiSimplexSolver& simplex, const btVector3& offset, btGjkEpaSolver2::sResults& results)
{
	btVector3 onA, onB;
	simplex.compute_points(onA, onB);
	const btVector3 delta = onA - onB;
	const btScalar length = delta.length();
	if (!(length > btScalar(0)) || !caliber::isFinite(delta))
	{
		setFailure(results, btGjkEpaSolver2::sResults::GJK_Failed);
		return false;
	}
	results.status = btGjkEpaSolver2::sResults::Separated;
	results.witnesses[0] = onA + offset;
	results.witnesses[1] = onB + offset;
	results.normal = delta / length;
	results.distance = length;
	return true;
}

bool penetration(const MinkowskiDifference& diff, const btVector3& offset, const btVector3& guess,
                 btGjkEpaSolver2::sResults& results)
{
	btVoronoiSimplexSolver simplex;
	btVector3 v;
	const GjkOutcome outcome = runGjk(diff, guess, simplex, v);
	if (outcome == GjkOutcome::Failed)
	{
		setFailure(results, btGjkEpaSolver2::sResults::GJK_Failed);
		return false;
	}
	if (outcome == GjkOutcome::Separated)
	{
		fillSeparated(simplex, offset, results);
		return false;
	}
	EpaPolytope poly;
	btVector3 witnessA, witnessB, normal;
	btScalar depth;
	if (!runEpa(diff, simplex, poly, witnessA, witnessB, normal, depth))
	{
		setFailure(results, btGjkEpaSolver2::sResults::EPA_Failed);
		return false;
	}
	results.status = btGjkEpaSolver2::sResults::Penetrating;
	results.witnesses[0] = witnessA + offset;
	results.witnesses[1] = witnessB + offset;
	results.normal = normal;
	results.distance = -depth;
	return true;
}
}  // namespace

int btGjkEpaSolver2::StackSizeRequirement()
{
	return int(sizeof(btVoronoiSimplexSolver) + sizeof(EpaPolytope) + sizeof(MinkowskiDifference));
}

bool btGjkEpaSolver2::Distance(const btConvexShape* shape0, const btTransform& wtrs0, const btConvexShape* shape1,
                               const btTransform& wtrs1, const btVector3& guess, sResults& results)
{
	MinkowskiDifference diff;
	btVector3 offset;
	if (!setUp(shape0, wtrs0, shape1, wtrs1, false, diff, offset, results)) return false;
	btVoronoiSimplexSolver simplex;
	btVector3 v;
	const GjkOutcome outcome = runGjk(diff, guess, simplex, v);
	if (outcome == GjkOutcome::Failed)
	{
		setFailure(results, sResults::GJK_Failed);
		return false;
	}
	if (outcome == GjkOutcome::Overlapping)
	{
		btVector3 onA, onB;
		simplex.compute_points(onA, onB);
		results.status = sResults::Penetrating;
		results.witnesses[0] = onA + offset;
		results.witnesses[1] = onB + offset;
		results.normal.setValue(btScalar(0), btScalar(0), btScalar(0));
		results.distance = btScalar(0);
		return false;
	}
	return fillSeparated(simplex, offset, results);
}

bool btGjkEpaSolver2::Penetration(const btConvexShape* shape0, const btTransform& wtrs0, const btConvexShape* shape1,
                                  const btTransform& wtrs1, const btVector3& guess, sResults& results, bool usemargins)
{
	MinkowskiDifference diff;
	btVector3 offset;
	if (!setUp(shape0, wtrs0, shape1, wtrs1, usemargins, diff, offset, results)) return false;
	return penetration(diff, offset, guess, results);
}

btScalar btGjkEpaSolver2::SignedDistance(const btVector3& position, btScalar margin, const btConvexShape* shape0,
                                         const btTransform& wtrs0, sResults& results)
{
	btAssert(shape0 && caliber::isFinite(wtrs0) && caliber::isFinite(position) && btIsFinite(margin) &&
	         margin >= btScalar(0));
	if (!shape0 || !caliber::isFinite(wtrs0) || !caliber::isFinite(position) || !btIsFinite(margin) ||
	    margin < btScalar(0))
	{
		setFailure(results, sResults::GJK_Failed);
		return SIMD_INFINITY;
	}
	const btVector3 offset = (wtrs0.getOrigin() + position) * btScalar(0.5);
	MinkowskiDifference diff;
	diff.a.shape = shape0;
	diff.a.transform = wtrs0;
	diff.a.transform.getOrigin() -= offset;
	diff.a.margin = btScalar(0);
	diff.b.shape = nullptr;
	diff.b.transform.setIdentity();
	diff.b.transform.setOrigin(position - offset);
	diff.b.margin = btScalar(0);
	const btScalar totalMargin = shape0->getMargin() + margin;

	btVoronoiSimplexSolver simplex;
	btVector3 v;
	const GjkOutcome outcome = runGjk(diff, wtrs0.getOrigin() - position, simplex, v);
	if (outcome == GjkOutcome::Failed)
	{
		setFailure(results, sResults::GJK_Failed);
		return SIMD_INFINITY;
	}
	if (outcome == GjkOutcome::Separated && fillSeparated(simplex, offset, results))
	{
		// Push the core witnesses out by the margins along the normal.
		results.witnesses[0] -= results.normal * shape0->getMargin();
		results.witnesses[1] += results.normal * margin;
		results.distance -= totalMargin;
		results.status = results.distance > btScalar(0) ? sResults::Separated : sResults::Penetrating;
		return results.distance;
	}
	// The point is inside the core: measure the depth with margins included.
	diff.a.margin = shape0->getMargin();
	diff.b.margin = margin;
	if (!penetration(diff, offset, wtrs0.getOrigin() - position, results)) return SIMD_INFINITY;
	return results.distance;
}

bool btGjkEpaSolver2::SignedDistance(const btConvexShape* shape0, const btTransform& wtrs0, const btConvexShape* shape1,
                                     const btTransform& wtrs1, const btVector3& guess, sResults& results)
{
	MinkowskiDifference diff;
	btVector3 offset;
	if (!setUp(shape0, wtrs0, shape1, wtrs1, false, diff, offset, results)) return false;
	btVoronoiSimplexSolver simplex;
	btVector3 v;
	const GjkOutcome outcome = runGjk(diff, guess, simplex, v);
	if (outcome == GjkOutcome::Failed)
	{
		setFailure(results, sResults::GJK_Failed);
		return false;
	}
	if (outcome == GjkOutcome::Separated && fillSeparated(simplex, offset, results))
	{
		const btScalar margin0 = shape0->getMargin();
		const btScalar margin1 = shape1->getMargin();
		results.witnesses[0] -= results.normal * margin0;
		results.witnesses[1] += results.normal * margin1;
		results.distance -= margin0 + margin1;
		results.status = results.distance > btScalar(0) ? sResults::Separated : sResults::Penetrating;
		return true;
	}
	diff.a.margin = shape0->getMargin();
	diff.b.margin = shape1->getMargin();
	return penetration(diff, offset, guess, results);
}
