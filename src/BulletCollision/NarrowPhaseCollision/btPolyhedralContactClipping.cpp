// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/NarrowPhaseCollision/btPolyhedralContactClipping.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"

int gExpectedNbTests = 0;
int gActualNbTests = 0;

namespace
{
// Two edge directions whose unit cross product is shorter than this (squared, about 0.06 degrees) are
// parallel: their cross product is no axis, and the face normals already cover that contact.
const btScalar kParallelCross2 = btScalar(1e-6);
// An edge axis replaces the best face axis only when its overlap is smaller by this share of the hulls'
// size: near ties are rounding, and a face axis gives a stable multi-point manifold.
const btScalar kEdgeAxisBias = btScalar(1e-5);

// The counters are diagnostics shared by all threads; one relaxed atomic add per query keeps them
// race-free without a std::atomic in the Bullet-compatible declaration.
void addToCounter(int& counter, int amount)
{
#if defined(__GNUC__) || defined(__clang__)
	__atomic_fetch_add(&counter, amount, __ATOMIC_RELAXED);
#else
	counter += amount;
#endif
}

bool faceIndicesValid(const btFace& face, int vertexCount)
{
	if (face.m_indices.size() < 3) return false;
	for (int i = 0; i < face.m_indices.size(); ++i)
		if (face.m_indices[i] < 0 || face.m_indices[i] >= vertexCount) return false;
	return true;
}

btVector3 faceNormal(const btFace& face) { return btVector3(face.m_plane[0], face.m_plane[1], face.m_plane[2]); }

// Extent of the placed hull along the unit world axis, in one pass over the vertices (the witnesses that
// btConvexPolyhedron::project also finds are not needed here).
void projectHull(const btConvexPolyhedron& hull, const btTransform& trans, const btVector3& axis, btScalar& minProj,
                 btScalar& maxProj)
{
	const btVector3 localAxis = axis * trans.getBasis();
	const btVector3* vertices = &hull.m_vertices[0];
	btScalar lo = localAxis.dot(vertices[0]), hi = lo;
	for (int i = 1; i < hull.m_vertices.size(); ++i)
	{
		const btScalar d = localAxis.dot(vertices[i]);
		lo = btMin(lo, d);
		hi = btMax(hi, d);
	}
	const btScalar offset = axis.dot(trans.getOrigin());
	minProj = lo + offset;
	maxProj = hi + offset;
}

// Overlap of the two hulls' projections on the unit axis. Returns false when they are apart. Otherwise
// overlap is the smaller of the two ways to separate them and sign is +1 when A should move along
// +axis (A lies on the positive side), -1 otherwise; equal overlaps are decided by the centres.
bool axisOverlap(const btConvexPolyhedron& hullA, const btConvexPolyhedron& hullB, const btTransform& transA,
                 const btTransform& transB, const btVector3& axis, const btVector3& centreDelta, btScalar& overlap,
                 btScalar& sign)
{
	btScalar minA, maxA, minB, maxB;
	projectHull(hullA, transA, axis, minA, maxA);
	projectHull(hullB, transB, axis, minB, maxB);
	const btScalar aAbove = maxB - minA;
	const btScalar aBelow = maxA - minB;
	if (aAbove < 0 || aBelow < 0) return false;
	if (aAbove < aBelow || (aAbove == aBelow && centreDelta.dot(axis) >= 0))
	{
		overlap = aAbove;
		sign = btScalar(1);
	}
	else
	{
		overlap = aBelow;
		sign = btScalar(-1);
	}
	return true;
}

// The edge of the hull parallel to localDirection whose midpoint reaches farthest along localSupport,
// in world space. False when the faces hold no such edge.
bool extremeParallelEdge(const btConvexPolyhedron& hull, const btTransform& trans, const btVector3& localDirection,
                         const btVector3& localSupport, btVector3& start, btVector3& end)
{
	const int vertexCount = hull.m_vertices.size();
	btScalar bestScore = -SIMD_INFINITY;
	int bestA = -1, bestB = -1;
	for (int f = 0; f < hull.m_faces.size(); ++f)
	{
		const btFace& face = hull.m_faces[f];
		if (!faceIndicesValid(face, vertexCount)) continue;
		const int n = face.m_indices.size();
		for (int i = 0; i < n; ++i)
		{
			const int a = face.m_indices[i], b = face.m_indices[(i + 1) % n];
			const btVector3 edge = hull.m_vertices[b] - hull.m_vertices[a];
			const btScalar length2 = edge.length2();
			if (!(length2 > 0) || edge.cross(localDirection).length2() > kParallelCross2 * length2) continue;
			const btScalar score = (hull.m_vertices[a] + hull.m_vertices[b]).dot(localSupport);
			if (score > bestScore)
			{
				bestScore = score;
				bestA = a;
				bestB = b;
			}
		}
	}
	if (bestA < 0) return false;
	start = trans(hull.m_vertices[bestA]);
	end = trans(hull.m_vertices[bestB]);
	return true;
}

// Closest points of segments [p0, p1] and [q0, q1] (clamped line parameters).
void segmentClosestPoints(const btVector3& p0, const btVector3& p1, const btVector3& q0, const btVector3& q1,
                          btVector3& onP, btVector3& onQ)
{
	const btVector3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
	const btScalar a = d1.dot(d1), e = d2.dot(d2), b = d1.dot(d2), c = d1.dot(r), f = d2.dot(r);
	btScalar s = 0, t = 0;
	const btScalar denominator = a * e - b * b;
	if (a > SIMD_EPSILON && e > SIMD_EPSILON)
	{
		if (denominator > SIMD_EPSILON * a * e)
			s = btMax(btScalar(0), btMin(btScalar(1), (b * f - c * e) / denominator));
		t = (b * s + f) / e;
		if (t < 0 || t > 1)
		{
			t = btMax(btScalar(0), btMin(btScalar(1), t));
			s = btMax(btScalar(0), btMin(btScalar(1), (b * t - c) / a));
		}
	}
	else if (e > SIMD_EPSILON)
	{
		t = btMax(btScalar(0), btMin(btScalar(1), f / e));
	}
	else if (a > SIMD_EPSILON)
	{
		s = btMax(btScalar(0), btMin(btScalar(1), -c / a));
	}
	onP = p0 + d1 * s;
	onQ = q0 + d2 * t;
}

// Above this many unique edge pairs the edge axes come from the Gauss map instead: only pairs of edges
// whose arcs cross on the unit sphere span a face of the Minkowski difference, and only those can
// separate or give the least overlap. Small hulls (boxes: 9 pairs) keep the plain loop.
const int kGaussMapPairThreshold = 64;

// An edge of a placed hull: world end points and the outward world normals of its two faces.
struct WorldEdge
{
	btVector3 start;
	btVector3 end;
	btVector3 normal1;
	btVector3 normal2;
	int startIndex;
	int endIndex;
	bool paired;
};

// Fills edges with each edge of the hull once, in world space, with both adjacent face normals. An edge
// found in one face only (an open or broken hull) is marked unpaired and always tested.
void collectWorldEdges(const btConvexPolyhedron& hull, const btTransform& trans, btAlignedObjectArray<WorldEdge>& edges)
{
	edges.resize(0);
	const int vertexCount = hull.m_vertices.size();
	for (int f = 0; f < hull.m_faces.size(); ++f)
	{
		const btFace& face = hull.m_faces[f];
		if (!faceIndicesValid(face, vertexCount)) continue;
		const btVector3 normal = trans.getBasis() * faceNormal(face);
		const int n = face.m_indices.size();
		for (int i = 0; i < n; ++i)
		{
			const int a = btMin(face.m_indices[i], face.m_indices[(i + 1) % n]);
			const int b = btMax(face.m_indices[i], face.m_indices[(i + 1) % n]);
			bool matched = false;
			for (int k = 0; k < edges.size() && !matched; ++k)
			{
				WorldEdge& edge = edges[k];
				if (edge.startIndex != a || edge.endIndex != b || edge.paired) continue;
				edge.normal2 = normal;
				edge.paired = true;
				matched = true;
			}
			if (matched) continue;
			WorldEdge edge;
			edge.start = trans(hull.m_vertices[a]);
			edge.end = trans(hull.m_vertices[b]);
			edge.normal1 = edge.normal2 = normal;
			edge.startIndex = a;
			edge.endIndex = b;
			edge.paired = false;
			edges.push_back(edge);
		}
	}
}

// True when the Gauss-map arc a-b (A's face normals) crosses the arc c-d (B's face normals, negated),
// i.e. the edge pair spans a face of the Minkowski difference A - B. Touching arcs count as crossing
// (a few extra axes are harmless; a missed one is not).
bool arcsCross(const btVector3& a, const btVector3& b, const btVector3& c, const btVector3& d)
{
	const btVector3 bxa = b.cross(a), dxc = d.cross(c);
	const btScalar cba = c.dot(bxa), dba = d.dot(bxa), adc = a.dot(dxc), bdc = b.dot(dxc);
	return cba * dba <= 0 && adc * bdc <= 0 && cba * bdc >= 0;
}

btScalar hullSize(const btConvexPolyhedron& hull) { return hull.mE.length(); }

// Half width along the unit world axis of a solid known to lie inside the hull around its centre: the
// larger of the inner sphere and the inner box (m_extents), both built by btConvexPolyhedron.
btScalar innerRadius(const btConvexPolyhedron& hull, const btMatrix3x3& basis, const btVector3& axis)
{
	const btVector3 local = axis * basis;
	const btScalar boxRadius = btFabs(local.x()) * hull.m_extents.x() + btFabs(local.y()) * hull.m_extents.y() +
	                           btFabs(local.z()) * hull.m_extents.z();
	return btMax(hull.m_radius, boxRadius);
}
}  // namespace

namespace
{
// The search for the axis of least overlap (SAT) of two hulls: the face normals of both, then the cross
// products of their edges, every candidate axis tested by axisOverlap.
struct AxisSearch
{
	const btConvexPolyhedron& hullA;
	const btConvexPolyhedron& hullB;
	const btTransform& transA;
	const btTransform& transB;
	btVector3 centreDelta;
	btScalar edgeBias;  // an edge axis must beat the best face axis by this much (faces give better contacts)
	// The inner solids overlap at least this much along an axis, so an axis whose bound is no better than
	// the best overlap so far can neither separate (best >= 0) nor win, and is not projected. Only hulls
	// with an inner sphere (built by initialize()) have a centre known to be inside.
	bool canCull;
	btScalar bestOverlap = SIMD_INFINITY;
	btVector3 bestAxis = btVector3(0, 0, 1);
	int bestEdgeA = -1, bestEdgeB = -1;  // the winning unique edges (all-pairs path)
	// Witness segments of a winning edge pair found on the Gauss-map path.
	bool gaussEdgeWins = false;
	btVector3 gaussA0 = btVector3(0, 0, 0), gaussA1 = btVector3(0, 0, 0);
	btVector3 gaussB0 = btVector3(0, 0, 0), gaussB1 = btVector3(0, 0, 0);
	int expected = 0, actual = 0;
	bool separated = false;

	AxisSearch(const btConvexPolyhedron& a, const btConvexPolyhedron& b, const btTransform& ta, const btTransform& tb)
	    : hullA(a),
	      hullB(b),
	      transA(ta),
	      transB(tb),
	      centreDelta(ta(a.m_localCenter) - tb(b.m_localCenter)),
	      edgeBias(kEdgeAxisBias * (hullSize(a) + hullSize(b))),
	      canCull(a.m_radius > 0 && b.m_radius > 0)
	{
	}

	btScalar overlapLowerBound(const btVector3& axis) const
	{
		if (!canCull) return -SIMD_INFINITY;
		return innerRadius(hullA, transA.getBasis(), axis) + innerRadius(hullB, transB.getBasis(), axis) -
		       btFabs(centreDelta.dot(axis));
	}

	// Tests the unit axis unless it cannot beat `bound`; true when it overlaps less than bound (the caller
	// then records it as the best).
	bool improves(const btVector3& unitAxis, btScalar bound, btVector3& signedAxis, btScalar& overlap)
	{
		if (overlapLowerBound(unitAxis) >= bound) return false;
		++actual;
		btScalar sign;
		if (!axisOverlap(hullA, hullB, transA, transB, unitAxis, centreDelta, overlap, sign))
		{
			separated = true;
			return false;
		}
		signedAxis = unitAxis * sign;
		return overlap < bound;
	}

	// Face normals of A, then of B: the first strictly smaller overlap wins, so ties keep the earlier face.
	void testFaceNormals()
	{
		for (int hullIndex = 0; hullIndex < 2 && !separated; ++hullIndex)
		{
			const btConvexPolyhedron& hull = hullIndex == 0 ? hullA : hullB;
			const btMatrix3x3& basis = hullIndex == 0 ? transA.getBasis() : transB.getBasis();
			for (int f = 0; f < hull.m_faces.size() && !separated; ++f)
			{
				++expected;
				const btVector3 axis = basis * faceNormal(hull.m_faces[f]);
				const btScalar length2 = axis.length2();
				if (!(length2 > SIMD_EPSILON)) continue;
				btVector3 signedAxis;
				btScalar overlap;
				if (improves(axis / btSqrt(length2), bestOverlap, signedAxis, overlap))
				{
					bestOverlap = overlap;
					bestAxis = signedAxis;
				}
			}
		}
	}

	// Every pair of unique edges (small hulls).
	void testAllEdgePairs()
	{
		for (int ea = 0; ea < hullA.m_uniqueEdges.size() && !separated; ++ea)
		{
			const btVector3 edgeA = transA.getBasis() * hullA.m_uniqueEdges[ea];
			for (int eb = 0; eb < hullB.m_uniqueEdges.size() && !separated; ++eb)
			{
				++expected;
				const btVector3 edgeB = transB.getBasis() * hullB.m_uniqueEdges[eb];
				const btVector3 axis = edgeA.cross(edgeB);
				const btScalar length2 = axis.length2();
				if (!(length2 > kParallelCross2 * edgeA.length2() * edgeB.length2())) continue;
				btVector3 signedAxis;
				btScalar overlap;
				if (improves(axis / btSqrt(length2), bestOverlap - edgeBias, signedAxis, overlap))
				{
					bestOverlap = overlap;
					bestAxis = signedAxis;
					bestEdgeA = ea;
					bestEdgeB = eb;
				}
			}
		}
	}

	// The edge pairs whose arcs cross on the Gauss map (the Minkowski difference's faces; large hulls).
	void testGaussMapEdgePairs()
	{
		// Per-thread scratch: no allocation once the arrays have grown to the largest hulls seen.
		static thread_local btAlignedObjectArray<WorldEdge> edgesA, edgesB;
		collectWorldEdges(hullA, transA, edgesA);
		collectWorldEdges(hullB, transB, edgesB);
		for (int ea = 0; ea < edgesA.size() && !separated; ++ea)
		{
			const WorldEdge& a = edgesA[ea];
			const btVector3 edgeA = a.end - a.start;
			for (int eb = 0; eb < edgesB.size() && !separated; ++eb)
			{
				++expected;
				const WorldEdge& b = edgesB[eb];
				if (a.paired && b.paired && !arcsCross(a.normal1, a.normal2, -b.normal1, -b.normal2)) continue;
				const btVector3 edgeB = b.end - b.start;
				const btVector3 axis = edgeA.cross(edgeB);
				const btScalar length2 = axis.length2();
				if (!(length2 > kParallelCross2 * edgeA.length2() * edgeB.length2())) continue;
				btVector3 signedAxis;
				btScalar overlap;
				if (improves(axis / btSqrt(length2), bestOverlap - edgeBias, signedAxis, overlap))
				{
					bestOverlap = overlap;
					bestAxis = signedAxis;
					gaussEdgeWins = true;
					gaussA0 = a.start;
					gaussA1 = a.end;
					gaussB0 = b.start;
					gaussB1 = b.end;
				}
			}
		}
	}

	// When an edge pair won: the contact point between the witness edges.
	void addEdgeContact(const btVector3& sep, btDiscreteCollisionDetectorInterface::Result& resultOut) const
	{
		if (bestEdgeA >= 0)
		{
			// The witness edges: A's edge deepest towards B (along -sep), B's deepest towards A (along +sep).
			btVector3 a0, a1, b0, b1;
			const bool foundA =
			    extremeParallelEdge(hullA, transA, hullA.m_uniqueEdges[bestEdgeA], (-sep) * transA.getBasis(), a0, a1);
			const bool foundB =
			    extremeParallelEdge(hullB, transB, hullB.m_uniqueEdges[bestEdgeB], sep * transB.getBasis(), b0, b1);
			if (foundA && foundB)
			{
				btVector3 onA, onB;
				segmentClosestPoints(a0, a1, b0, b1, onA, onB);
				resultOut.addContactPoint(sep, onB, -bestOverlap);
			}
		}
		else if (gaussEdgeWins)
		{
			// The Minkowski face's own edges are the witnesses.
			btVector3 onA, onB;
			segmentClosestPoints(gaussA0, gaussA1, gaussB0, gaussB1, onA, onB);
			resultOut.addContactPoint(sep, onB, -bestOverlap);
		}
	}
};
}  // namespace

bool btPolyhedralContactClipping::findSeparatingAxis(const btConvexPolyhedron& hullA, const btConvexPolyhedron& hullB,
                                                     const btTransform& transA, const btTransform& transB,
                                                     btVector3& sep,
                                                     btDiscreteCollisionDetectorInterface::Result& resultOut)
{
	const bool usable = hullA.m_vertices.size() > 0 && hullB.m_vertices.size() > 0 && hullA.m_faces.size() > 0 &&
	                    hullB.m_faces.size() > 0 && caliber::isFinite(transA) && caliber::isFinite(transB);
	btAssert(usable && "findSeparatingAxis: hull without faces or vertices, or non-finite transform");
	if (!usable) return false;

	AxisSearch search(hullA, hullB, transA, transB);
	search.testFaceNormals();
	if (!search.separated)
	{
		if (hullA.m_uniqueEdges.size() * hullB.m_uniqueEdges.size() <= kGaussMapPairThreshold)
			search.testAllEdgePairs();
		else
			search.testGaussMapEdgePairs();
	}
	addToCounter(gExpectedNbTests, search.expected);
	addToCounter(gActualNbTests, search.actual);
	if (search.separated || !(search.bestOverlap < SIMD_INFINITY)) return false;
	sep = search.bestAxis;
	search.addEdgeContact(sep, resultOut);
	return true;
}

void btPolyhedralContactClipping::clipFace(const btVertexArray& pVtxIn, btVertexArray& ppVtxOut,
                                           const btVector3& planeNormalWS, btScalar planeEqWS)
{
	btAssert(&pVtxIn != &ppVtxOut && "clipFace: input and output must differ");
	const int count = pVtxIn.size();
	if (count == 0 || &pVtxIn == &ppVtxOut) return;
	btVector3 previous = pVtxIn[count - 1];
	btScalar previousDistance = planeNormalWS.dot(previous) + planeEqWS;
	for (int i = 0; i < count; ++i)
	{
		const btVector3& current = pVtxIn[i];
		const btScalar currentDistance = planeNormalWS.dot(current) + planeEqWS;
		const bool previousInside = previousDistance <= 0;
		const bool currentInside = currentDistance <= 0;
		// The signs differ whenever the edge crosses, so the denominator is never zero.
		if (previousInside != currentInside)
			ppVtxOut.push_back(previous.lerp(current, previousDistance / (previousDistance - currentDistance)));
		if (currentInside) ppVtxOut.push_back(current);
		previous = current;
		previousDistance = currentDistance;
	}
}

void btPolyhedralContactClipping::clipFaceAgainstHull(const btVector3& separatingNormal,
                                                      const btConvexPolyhedron& hullA, const btTransform& transA,
                                                      btVertexArray& worldVertsB1, btVertexArray& worldVertsB2,
                                                      const btScalar minDist, btScalar maxDist,
                                                      btDiscreteCollisionDetectorInterface::Result& resultOut)
{
	const btScalar normalLength2 = separatingNormal.length2();
	const bool usable =
	    caliber::isFinite(separatingNormal) && normalLength2 > SIMD_EPSILON && caliber::isFinite(transA);
	btAssert(usable && "clipFaceAgainstHull: zero or non-finite normal, or non-finite transform");
	if (!usable) return;
	const btVector3 normal = separatingNormal / btSqrt(normalLength2);

	// A's reference face is the one most opposed to the normal (it faces B).
	const int vertexCount = hullA.m_vertices.size();
	int referenceFace = -1;
	btScalar lowest = SIMD_INFINITY;
	for (int f = 0; f < hullA.m_faces.size(); ++f)
	{
		if (!faceIndicesValid(hullA.m_faces[f], vertexCount)) continue;
		const btScalar alignment = (transA.getBasis() * faceNormal(hullA.m_faces[f])).dot(normal);
		if (alignment < lowest)
		{
			lowest = alignment;
			referenceFace = f;
		}
	}
	if (referenceFace < 0 || worldVertsB1.size() == 0) return;
	const btFace& face = hullA.m_faces[referenceFace];
	const btVector3 faceNormalWS = transA.getBasis() * faceNormal(face);
	const btScalar facePlaneWS = face.m_plane[3] - faceNormalWS.dot(transA.getOrigin());

	btVector3 faceCentre(0, 0, 0);
	const int cornerCount = face.m_indices.size();
	for (int i = 0; i < cornerCount; ++i) faceCentre += hullA.m_vertices[face.m_indices[i]];
	faceCentre = transA(faceCentre / btScalar(cornerCount));

	// Clip against the side planes through each edge of the reference face; each side normal is turned
	// away from the face centre, so a face stored with the other winding clips the same.
	btVertexArray* input = &worldVertsB1;
	btVertexArray* output = &worldVertsB2;
	for (int i = 0; i < cornerCount && input->size() > 0; ++i)
	{
		const btVector3 start = transA(hullA.m_vertices[face.m_indices[i]]);
		const btVector3 end = transA(hullA.m_vertices[face.m_indices[(i + 1) % cornerCount]]);
		btVector3 side = (end - start).cross(faceNormalWS);
		const btScalar sideLength2 = side.length2();
		if (!(sideLength2 > SIMD_EPSILON * SIMD_EPSILON)) continue;
		side /= btSqrt(sideLength2);
		if (side.dot(faceCentre - start) > 0) side = -side;
		output->resize(0);
		clipFace(*input, *output, side, -side.dot(start));
		btSwap(input, output);
	}

	for (int i = 0; i < input->size(); ++i)
	{
		const btVector3& point = (*input)[i];
		btScalar depth = faceNormalWS.dot(point) + facePlaneWS;
		if (!(depth <= maxDist)) continue;
		if (depth < minDist) depth = minDist;
		resultOut.addContactPoint(normal, point, depth);
	}
}

void btPolyhedralContactClipping::clipHullAgainstHull(const btVector3& separatingNormal1,
                                                      const btConvexPolyhedron& hullA, const btConvexPolyhedron& hullB,
                                                      const btTransform& transA, const btTransform& transB,
                                                      const btScalar minDist, btScalar maxDist,
                                                      btVertexArray& worldVertsB1, btVertexArray& worldVertsB2,
                                                      btDiscreteCollisionDetectorInterface::Result& resultOut)
{
	const btScalar normalLength2 = separatingNormal1.length2();
	const bool usable = caliber::isFinite(separatingNormal1) && normalLength2 > SIMD_EPSILON &&
	                    caliber::isFinite(transA) && caliber::isFinite(transB);
	btAssert(usable && "clipHullAgainstHull: zero or non-finite normal, or non-finite transform");
	if (!usable) return;
	const btVector3 normal = separatingNormal1 / btSqrt(normalLength2);

	// B's incident face is the one most aligned with the normal (it faces A).
	const int vertexCount = hullB.m_vertices.size();
	int incidentFace = -1;
	btScalar highest = -SIMD_INFINITY;
	for (int f = 0; f < hullB.m_faces.size(); ++f)
	{
		if (!faceIndicesValid(hullB.m_faces[f], vertexCount)) continue;
		const btScalar alignment = (transB.getBasis() * faceNormal(hullB.m_faces[f])).dot(normal);
		if (alignment > highest)
		{
			highest = alignment;
			incidentFace = f;
		}
	}
	if (incidentFace < 0) return;
	const btFace& face = hullB.m_faces[incidentFace];
	worldVertsB1.resize(0);
	for (int i = 0; i < face.m_indices.size(); ++i) worldVertsB1.push_back(transB(hullB.m_vertices[face.m_indices[i]]));
	clipFaceAgainstHull(normal, hullA, transA, worldVertsB1, worldVertsB2, minDist, maxDist, resultOut);
}
