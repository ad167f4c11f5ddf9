// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Box-box detection (btBoxBoxDetector::getClosestPoints), written once and built twice: btBoxBoxDetector.cpp
// includes this file in one namespace for the library's baseline instruction set and in another for AVX2
// (VEX encoding, no FMA: the same operations in the same order, so the same points), and picks one per call.
// No include guard: it is meant to be included more than once.

// Edge pairs whose unit cross product is shorter than this (squared, about 0.06 degrees) are parallel;
// their axis is covered by the face normals.
const btScalar kParallelCross2 = btScalar(1e-6);
// An edge axis replaces a face axis only when it separates more by this share of the boxes' size, so
// that near ties (rounding, resting contacts) keep the face axis and its stable 4-point manifold.
const btScalar kEdgeAxisBias = btScalar(1e-4);
// Clip points closer than this share of the boxes' size are one point (a zero-size face collapses).
const btScalar kMergeDistance = btScalar(1e-6);

// Polygons here have at most 8 vertices: a quad clipped by 4 lines gains at most one vertex per line.
const int kMaxClipVertices = 8;

struct BoxFrame
{
	btVector3 centre;
	btVector3 axis[3];
	btVector3 half;
};

// Polygon buffers hold one vertex more than a polygon can have: the clip writes every candidate vertex
// and keeps it by advancing the count.
const int kClipBufferSize = kMaxClipVertices + 1;

// Keeps the part of polygon (in, inCount) with sign * p[coordinate] <= limit; returns the new count. Without
// branches on the vertices' sides: which corners a face keeps varies from pair to pair, and a mispredicted
// branch costs more than computing a crossing that is then dropped.
int clipAgainstLine(const btVector3* in, int inCount, int coordinate, btScalar sign, btScalar limit, btVector3* out)
{
	int outCount = 0;
	if (inCount == 0) return 0;
	btVector3 previous = in[inCount - 1];
	btScalar previousDistance = sign * previous[coordinate] - limit;
	for (int i = 0; i < inCount; ++i)
	{
		const btVector3& current = in[i];
		const btScalar currentDistance = sign * current[coordinate] - limit;
		const bool previousInside = previousDistance <= 0, currentInside = currentDistance <= 0;
		// Kept only for opposite signs, where the denominator is not zero (otherwise the value is dropped).
		// btVector3::lerp's operations lane by lane (x, y and z as lerp gives them; w is never read).
		out[outCount] = previous + (current - previous) * (previousDistance / (previousDistance - currentDistance));
		outCount += int((previousInside != currentInside) & (outCount < kMaxClipVertices));
		out[outCount] = current;
		outCount += int(currentInside & (outCount < kMaxClipVertices));
		previous = current;
		previousDistance = currentDistance;
	}
	return outCount;
}

btScalar quadArea2(const btVector3& a, const btVector3& b, const btVector3& c, const btVector3& d)
{
	// Shoelace over (x, y) of a quad whose corners are in polygon order.
	return btFabs((a.x() * b.y() - b.x() * a.y()) + (b.x() * c.y() - c.x() * b.y()) + (c.x() * d.y() - d.x() * c.y()) +
	              (d.x() * a.y() - a.x() * d.y()));
}

// Reduces points (in convex polygon order, (x, y) in the reference face plane) to the 4 spanning the
// largest area; the first maximum in lexicographic index order wins, so the choice is deterministic.
int keepLargestQuad(btVector3* points, btScalar* depths, int count)
{
	if (count <= 4) return count;
	int best[4] = {0, 1, 2, 3};
	btScalar bestArea = -1;
	for (int i = 0; i < count; ++i)
		for (int j = i + 1; j < count; ++j)
			for (int k = j + 1; k < count; ++k)
				for (int l = k + 1; l < count; ++l)
				{
					const btScalar area = quadArea2(points[i], points[j], points[k], points[l]);
					if (area > bestArea)
					{
						bestArea = area;
						best[0] = i;
						best[1] = j;
						best[2] = k;
						best[3] = l;
					}
				}
	btVector3 keptPoints[4];
	btScalar keptDepths[4];
	for (int n = 0; n < 4; ++n)
	{
		keptPoints[n] = points[best[n]];
		keptDepths[n] = depths[best[n]];
	}
	for (int n = 0; n < 4; ++n)
	{
		points[n] = keptPoints[n];
		depths[n] = keptDepths[n];
	}
	return 4;
}

// Which box (0 = A, 1 = B) and axis index give the face axis, or the edge pair for edge axes.
struct BestAxis
{
	int kind;  // 0: face of A, 1: face of B, 2: edge of A x edge of B
	int indexA;
	int indexB;
	btVector3 normal;  // unit, from B towards A
	btScalar separation;
	btScalar edgeLength2;  // edge axes: |edge A x edge B|^2
};

// The edge axes a_i x b_j, of length sqrt(1 - R[i][j]^2). With (i, i1, i2) and (j, j1, j2) cyclic:
// a_i1 . (a_i x b_j) = -R[i2][j], a_i2 . (a_i x b_j) = R[i1][j], and b_j1, b_j2 likewise, so the radii and
// the centre distance along the axis come from R and t alone.
struct EdgeAxes
{
	const btScalar (&R)[3][3];
	const btScalar (&absR)[3][3];
	const btScalar (&t)[3];
	const btVector3& halfA;
	const btVector3& halfB;
	btScalar maxDistance;
	btScalar edgeBias;

	/// Axis a_i x b_j: true when it separates the boxes by more than maxDistance, else best is updated.
	template <int i, int j>
	SIMD_FORCE_INLINE bool test(BestAxis& best) const
	{
		const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
		const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
		// |a_i x b_j|^2 from its two components in A's frame (b_j there is column j of R). 1 - R[i][j]^2
		// would lose every digit to cancellation for near-parallel edges, exactly where the cut-off and the
		// face-axis bias must decide.
		const btScalar length2 = R[i1][j] * R[i1][j] + R[i2][j] * R[i2][j];
		if (!(length2 > kParallelCross2)) return false;
		const btScalar radiusA = halfA[i1] * absR[i2][j] + halfA[i2] * absR[i1][j];
		const btScalar radiusB = halfB[j1] * absR[i][j2] + halfB[j2] * absR[i][j1];
		const btScalar centreDistance = t[i2] * R[i1][j] - t[i1] * R[i2][j];
		const btScalar separation = (btFabs(centreDistance) - radiusA - radiusB) / btSqrt(length2);
		if (separation > maxDistance) return true;
		if (separation > best.separation + edgeBias)
		{
			best.kind = 2;
			best.indexA = i;
			best.indexB = j;
			best.separation = separation;
			best.edgeLength2 = length2;
		}
		return false;
	}
};

void report(btDiscreteCollisionDetectorInterface::Result& output, bool swapResults, const btVector3& normal,
            const btVector3& pointOnB, btScalar depth)
{
	if (swapResults)
		output.addContactPoint(-normal, pointOnB + normal * depth, depth);
	else
		output.addContactPoint(normal, pointOnB, depth);
}

// Face contact: the reference box's face with outward normal referenceNormal (one of its axes, signed)
// against the incident box's most opposed face. Reports points on B.
void faceContact(const BoxFrame& reference, int referenceAxis, const btVector3& referenceNormal,
                 const BoxFrame& incident, bool referenceIsA, const btVector3& normalBtoA, btScalar maxDistance,
                 btScalar mergeDistance, btDiscreteCollisionDetectorInterface::Result& output, bool swapResults)
{
	const int uAxis = (referenceAxis + 1) % 3, vAxis = (referenceAxis + 2) % 3;
	const btVector3& u = reference.axis[uAxis];
	const btVector3& v = reference.axis[vAxis];

	int incidentAxis = 0;
	btScalar largest = -1;
	for (int j = 0; j < 3; ++j)
	{
		const btScalar alignment = btFabs(incident.axis[j].dot(referenceNormal));
		const bool better = alignment > largest;  // selects without a branch
		largest = better ? alignment : largest;
		incidentAxis = better ? j : incidentAxis;
	}
	const btScalar faceSign = incident.axis[incidentAxis].dot(referenceNormal) > 0 ? btScalar(-1) : btScalar(1);
	const btVector3 faceCentre =
	    incident.centre + incident.axis[incidentAxis] * (faceSign * incident.half[incidentAxis]);
	const int pAxis = (incidentAxis + 1) % 3, qAxis = (incidentAxis + 2) % 3;
	const btVector3 edgeP = incident.axis[pAxis] * incident.half[pAxis];
	const btVector3 edgeQ = incident.axis[qAxis] * incident.half[qAxis];

	// Incident corners in the reference face frame: x along u, y along v, z along the outward normal.
	btVector3 polygon[kClipBufferSize], scratch[kClipBufferSize];
	const btVector3 corners[4] = {faceCentre + edgeP + edgeQ, faceCentre - edgeP + edgeQ, faceCentre - edgeP - edgeQ,
	                              faceCentre + edgeP - edgeQ};
	for (int i = 0; i < 4; ++i)
	{
		const btVector3 relative = corners[i] - reference.centre;
		polygon[i].setValue(relative.dot(u), relative.dot(v), relative.dot(referenceNormal));
	}
	int count = 4;
	const btScalar hu = reference.half[uAxis], hv = reference.half[vAxis];
	count = clipAgainstLine(polygon, count, 0, btScalar(1), hu, scratch);
	count = clipAgainstLine(scratch, count, 0, btScalar(-1), hu, polygon);
	count = clipAgainstLine(polygon, count, 1, btScalar(1), hv, scratch);
	count = clipAgainstLine(scratch, count, 1, btScalar(-1), hv, polygon);

	// Keep the points near enough, merging coincident neighbours (order stays convex).
	btVector3 points[kMaxClipVertices];
	btScalar depths[kMaxClipVertices];
	int kept = 0;
	const btScalar referenceOffset = reference.half[referenceAxis];
	for (int i = 0; i < count; ++i)
	{
		// Written, then kept by advancing kept (kept <= i < count, so the slot exists).
		const btScalar depth = polygon[i].z() - referenceOffset;
		const bool withinReach = depth <= maxDistance;
		const bool merges =
		    kept > 0 && (points[btMax(kept - 1, 0)] - polygon[i]).length2() <= mergeDistance * mergeDistance;
		points[kept] = polygon[i];
		depths[kept] = depth;
		kept += int(withinReach & !merges);
	}
	if (kept > 1 && (points[kept - 1] - points[0]).length2() <= mergeDistance * mergeDistance) --kept;
	kept = keepLargestQuad(points, depths, kept);

	for (int i = 0; i < kept; ++i)
	{
		const btVector3 world =
		    reference.centre + u * points[i].x() + v * points[i].y() + referenceNormal * points[i].z();
		// The clipped points lie on the incident box; when that is A, their partner on B is on B's face.
		const btVector3 pointOnB = referenceIsA ? world : world - referenceNormal * depths[i];
		report(output, swapResults, normalBtoA, pointOnB, depths[i]);
	}
}

// Edge contact: the edge of A deepest towards B against the edge of B deepest towards A.
void edgeContact(const BoxFrame& a, int edgeA, const BoxFrame& b, int edgeB, btScalar crossLength2,
                 const btVector3& normalBtoA, btScalar maxDistance,
                 btDiscreteCollisionDetectorInterface::Result& output, bool swapResults)
{
	btVector3 centreA = a.centre, centreB = b.centre;
	for (int k = 0; k < 3; ++k)
	{
		if (k != edgeA) centreA += a.axis[k] * (a.axis[k].dot(normalBtoA) > 0 ? -a.half[k] : a.half[k]);
		if (k != edgeB) centreB += b.axis[k] * (b.axis[k].dot(normalBtoA) >= 0 ? b.half[k] : -b.half[k]);
	}
	// Closest points of the lines centre + t * direction, t clamped to the half lengths.
	const btVector3& directionA = a.axis[edgeA];
	const btVector3& directionB = b.axis[edgeB];
	const btVector3 offset = centreA - centreB;
	const btScalar cosine = directionA.dot(directionB);
	const btScalar alongA = directionA.dot(offset), alongB = directionB.dot(offset);
	// 1 - cosine^2, but from the cross product's components: no cancellation for near-parallel edges,
	// and > kParallelCross2 for a chosen edge axis.
	const btScalar denominator = crossLength2;
	btScalar s = (cosine * alongB - alongA) / denominator;
	s = btMax(-a.half[edgeA], btMin(a.half[edgeA], s));
	btScalar t = cosine * s + alongB;
	if (t < -b.half[edgeB] || t > b.half[edgeB])
	{
		t = btMax(-b.half[edgeB], btMin(b.half[edgeB], t));
		s = btMax(-a.half[edgeA], btMin(a.half[edgeA], cosine * t - alongA));
	}
	const btVector3 onA = centreA + directionA * s;
	const btVector3 onB = centreB + directionB * t;
	const btScalar depth = (onA - onB).dot(normalBtoA);
	if (depth <= maxDistance) report(output, swapResults, normalBtoA, onB, depth);
}

// The whole detection of two boxes (btBoxBoxDetector::getClosestPoints with its boxes).
void closestPoints(const btBoxShape* box1, const btBoxShape* box2,
                   const btDiscreteCollisionDetectorInterface::ClosestPointInput& input,
                   btDiscreteCollisionDetectorInterface::Result& output, bool swapResults)
{
	const bool usable =
	    box1 && box2 && caliber::isFinite(input.m_transformA) && caliber::isFinite(input.m_transformB);
	btAssert(usable && "btBoxBoxDetector: null box or non-finite transform");
	if (!usable) return;

	// A NaN or negative limit reports touching and penetrating points only.
	const btScalar maxDistanceSquared = input.m_maximumDistanceSquared;
	const btScalar maxDistance = maxDistanceSquared > 0 ? btSqrt(maxDistanceSquared) : btScalar(0);

	BoxFrame a, b;
	a.centre = input.m_transformA.getOrigin();
	b.centre = input.m_transformB.getOrigin();
	a.half = box1->getHalfExtentsWithMargin();
	b.half = box2->getHalfExtentsWithMargin();
	for (int i = 0; i < 3; ++i)
	{
		a.axis[i] = input.m_transformA.getBasis().getColumn(i);
		b.axis[i] = input.m_transformB.getBasis().getColumn(i);
	}
	const btVector3 delta = b.centre - a.centre;
	const btScalar size = a.half[a.half.maxAxis()] + b.half[b.half.maxAxis()];

	// Separating-axis test in A's frame: R[i][j] = a_i . b_j and t = delta in A's frame give every axis's
	// radii and centre distance from 9 + 3 dot products, instead of 6 per axis for 15 axes. The normal
	// from B towards A along axis.
	auto orient = [&](const btVector3& axis) { return delta.dot(axis) > 0 ? -axis : axis; };
	btScalar R[3][3], absR[3][3], t[3];
	for (int i = 0; i < 3; ++i)
	{
		t[i] = delta.dot(a.axis[i]);
		for (int j = 0; j < 3; ++j)
		{
			R[i][j] = a.axis[i].dot(b.axis[j]);
			absR[i][j] = btFabs(R[i][j]);
		}
	}

	BestAxis best;
	best.kind = -1;
	best.indexA = best.indexB = 0;
	best.separation = -SIMD_INFINITY;
	best.edgeLength2 = btScalar(1);
	best.normal.setValue(0, 0, 1);
	// Face axes of A: A's radius is its half extent, B's is its extents projected with |R|.
	for (int i = 0; i < 3; ++i)
	{
		const btScalar radiusB = b.half[0] * absR[i][0] + b.half[1] * absR[i][1] + b.half[2] * absR[i][2];
		const btScalar separation = btFabs(t[i]) - a.half[i] - radiusB;
		if (separation > maxDistance) return;
		// The deepest axis is selected without branches: which one wins varies from pair to pair.
		const bool better = separation > best.separation;
		best.kind = better ? 0 : best.kind;
		best.indexA = best.indexB = better ? i : best.indexA;
		best.separation = better ? separation : best.separation;
	}
	// Face axes of B: the same with the roles exchanged (delta . b_j = sum_i t_i R[i][j]).
	for (int j = 0; j < 3; ++j)
	{
		const btScalar radiusA = a.half[0] * absR[0][j] + a.half[1] * absR[1][j] + a.half[2] * absR[2][j];
		const btScalar centreDistance = t[0] * R[0][j] + t[1] * R[1][j] + t[2] * R[2][j];
		const btScalar separation = btFabs(centreDistance) - radiusA - b.half[j];
		if (separation > maxDistance) return;
		const bool better = separation > best.separation;
		best.kind = better ? 1 : best.kind;
		best.indexA = best.indexB = better ? j : best.indexA;
		best.separation = better ? separation : best.separation;
	}
	if (best.kind >= 0) best.normal = orient(best.kind == 0 ? a.axis[best.indexA] : b.axis[best.indexB]);

	// Edge axes a_i x b_j, of length sqrt(1 - R[i][j]^2). With (i, i1, i2) and (j, j1, j2) cyclic:
	// a_i1 . (a_i x b_j) = -R[i2][j], a_i2 . (a_i x b_j) = R[i1][j], and b_j1, b_j2 likewise, so the
	// radii and the centre distance along the axis come from R and t alone.
	const btScalar edgeBias = kEdgeAxisBias * size;
	const EdgeAxes edges = {R, absR, t, a.half, b.half, maxDistance, edgeBias};
	// In the order i = 0, 1, 2, and j = 0, 1, 2 for each i, with constant indices (a loop kept them in
	// memory and computed the cyclic ones at run time).
	if (edges.test<0, 0>(best) || edges.test<0, 1>(best) || edges.test<0, 2>(best) || edges.test<1, 0>(best) ||
	    edges.test<1, 1>(best) || edges.test<1, 2>(best) || edges.test<2, 0>(best) || edges.test<2, 1>(best) ||
	    edges.test<2, 2>(best))
		return;
	if (best.kind == 2) best.normal = orient(a.axis[best.indexA].cross(b.axis[best.indexB]).normalized());

	const btScalar mergeDistance = kMergeDistance * size + SIMD_EPSILON;
	if (best.kind == 0)
		faceContact(a, best.indexA, -best.normal, b, true, best.normal, maxDistance, mergeDistance, output,
		            swapResults);
	else if (best.kind == 1)
		faceContact(b, best.indexB, best.normal, a, false, best.normal, maxDistance, mergeDistance, output,
		            swapResults);
	else if (best.kind == 2)
		edgeContact(a, best.indexA, b, best.indexB, best.edgeLength2, best.normal, maxDistance, output, swapResults);
}

