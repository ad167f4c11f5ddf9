// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btConvexTriangleClipping.h"

#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "BulletCollision/CollisionShapes/btConvexPolyhedron.h"
#include "BulletCollision/CollisionShapes/btPolyhedralConvexShape.h"

namespace caliber
{
namespace
{
// A face of the convex after clipping has at most its own corners plus one per triangle side. A hull's
// face with more corners (a fine cylinder's cap) keeps its first 32 in its own order: a smaller polygon
// inside the face, still exact points of it.
const int kMaxFaceCorners = 32;
const int kMaxClipped = kMaxFaceCorners + 3;

// Deeper than this below a triangle's plane the face normal is not trusted as the way out (a triangle's
// edge may be poking into a side); well beyond what a speculative contact lets a body sink in one step.
const btScalar kFaceDepthLimit = btScalar(0.1);
// Beyond the depth limit by this much, rounding cannot bring a box's lowest point back within it.
const btScalar kDepthSlack = btScalar(0.01);

// When the face's points over the triangle are this close to the convex's lowest point, the lowest point
// is taken to be over the triangle (a box resting on a face tilted by rounding); farther, the contact is
// at an edge too. A tenth of the default breaking threshold (0.02).
const btScalar kFaceLevelTolerance = btScalar(0.002);

// GJK's normal for a convex resting on a face is the face normal to within its tolerance; a normal leaning
// further (about 2.5 degrees) comes from an edge or a vertex, where one GJK point is the right answer. A
// polyhedron's face is taken as the face over a triangle within the same angle.
const btScalar kFaceNormalCosine = btScalar(0.999);

// A point closer than this fraction of a triangle's longest edge to one of its edges is on it (the mesh
// collector's tolerance for a point on an edge).
const btScalar kOnTriangleEdge = btScalar(1e-3);

// Hull vertices this close to the supporting plane, as a fraction of the hull's extent along the normal,
// form its face there: it catches a face tilted by about a degree (a hull settling on a face) whose
// vertices are not quite level. Each point keeps its own distance, so a vertex taken in that is a little
// higher only gives a point a little farther away.
const btScalar kHullFaceBand = btScalar(0.02);

// A hull lying on an edge gets the face it tips onto when the reach is more than this fraction of its extent
// along the normal: the face's far side can come down within the step (a landing, a fast tip); less, and
// its points within reach lie next to the edge, which holds the hull already.
const btScalar kWrapReach = btScalar(0.25);

struct Polygon
{
	btVector3 corners[kMaxClipped];
	int count = 0;
};

// The box's face most opposed to the normal, in world space (boxes carry their margin in their extents).
// localNormal is the normal in the box's frame.
void boxFace(const btBoxShape& box, const btTransform& transform, const btVector3& localNormal, Polygon& face)
{
	const btVector3 direction = -localNormal;
	int axis = 0;
	for (int i = 1; i < 3; ++i)
		if (btFabs(direction[i]) > btFabs(direction[axis])) axis = i;
	const btVector3 half = box.getHalfExtentsWithMargin();
	const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
	const btScalar signs[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
	for (int c = 0; c < 4; ++c)
	{
		btVector3 local;
		local[axis] = direction[axis] < 0 ? -half[axis] : half[axis];
		local[a1] = signs[c][0] * half[a1];
		local[a2] = signs[c][1] * half[a2];
		face.corners[c] = transform(local);
	}
	face.count = 4;
}

// A number that grows with the angle of (x, y) as atan2(y, x) does, over the same range (-pi, pi] cut
// at the same place, without the trigonometry: only the order of the corners around the face matters.
btScalar pseudoAngle(btScalar x, btScalar y)
{
	const btScalar sum = btFabs(x) + btFabs(y);
	if (!(sum > 0)) return 0;
	// 0 along +x, 1 along +y, 2 along -x, 3 along -y, linear in between.
	btScalar diamond;
	if (y >= 0)
		diamond = x >= 0 ? y / sum : 1 - x / sum;
	else
		diamond = x < 0 ? 2 - y / sum : 3 + x / sum;
	return diamond > 2 ? diamond - 4 : diamond;
}

// Orders the face's corners by angle around their centre in the plane across the normal (insertion sort:
// a face is small), so that they form a polygon.
void orderAroundCentre(const btVector3& normal, Polygon& face)
{
	btVector3 centre(0, 0, 0);
	for (int i = 0; i < face.count; ++i) centre += face.corners[i];
	centre /= btScalar(face.count);
	btVector3 tangent0, tangent1;
	btPlaneSpace1(normal, tangent0, tangent1);
	btScalar angles[kMaxClipped];
	for (int i = 0; i < face.count; ++i)
	{
		const btVector3 offset = face.corners[i] - centre;
		angles[i] = pseudoAngle(offset.dot(tangent0), offset.dot(tangent1));
	}
	for (int i = 1; i < face.count; ++i)
	{
		const btScalar angle = angles[i];
		const btVector3 corner = face.corners[i];
		int j = i - 1;
		for (; j >= 0 && angles[j] > angle; --j)
		{
			angles[j + 1] = angles[j];
			face.corners[j + 1] = face.corners[j];
		}
		angles[j + 1] = angle;
		face.corners[j + 1] = corner;
	}
}

// Depths are found in chunks of this many points, on the stack.
const int kDepthChunk = 64;

// depths[i] = points[i] . direction for count <= kDepthChunk points, and their extremes (deepest and
// shallowest are updated); four at a time in SSE builds (as the hull's own support search does), which
// makes the band below cost about what two support searches do.
void dotsOf(const btVector3* points, int count, const btVector3& direction, btScalar* depths, btScalar& deepest,
            btScalar& shallowest)
{
	int i = 0;
#ifdef BT_USE_SSE
	if (count >= 4)
	{
		const __m128 dx = _mm_set1_ps(direction.x());
		const __m128 dy = _mm_set1_ps(direction.y());
		const __m128 dz = _mm_set1_ps(direction.z());
		__m128 laneMax = _mm_set1_ps(deepest);
		__m128 laneMin = _mm_set1_ps(shallowest);
		for (; i + 4 <= count; i += 4)
		{
			__m128 v0 = points[i + 0].get128();
			__m128 v1 = points[i + 1].get128();
			__m128 v2 = points[i + 2].get128();
			__m128 v3 = points[i + 3].get128();
			_MM_TRANSPOSE4_PS(v0, v1, v2, v3);  // v0 = x lanes, v1 = y lanes, v2 = z lanes
			const __m128 dots = _mm_add_ps(_mm_add_ps(_mm_mul_ps(v0, dx), _mm_mul_ps(v1, dy)), _mm_mul_ps(v2, dz));
			_mm_storeu_ps(depths + i, dots);
			laneMax = _mm_max_ps(laneMax, dots);
			laneMin = _mm_min_ps(laneMin, dots);
		}
		alignas(16) float highs[4], lows[4];
		_mm_store_ps(highs, laneMax);
		_mm_store_ps(lows, laneMin);
		for (int lane = 0; lane < 4; ++lane)
		{
			deepest = btMax(deepest, highs[lane]);
			shallowest = btMin(shallowest, lows[lane]);
		}
	}
#endif
	for (; i < count; ++i)
	{
		depths[i] = direction.dot(points[i]);
		deepest = btMax(deepest, depths[i]);
		shallowest = btMin(shallowest, depths[i]);
	}
}

// A hull lying on an edge (the band holds 2 points) with its centre of mass off to one side tips onto the
// face next to it on that side (a box landing on an edge at speed turns onto its face within a step or
// two). Like a polyhedron's face most opposed to the normal, that face gives the speculative points that
// stop the face coming down. The supporting plane is turned about the edge towards the centre of mass (the
// shape's origin) until it meets other points: the points it meets form the face. A hull balanced over
// its edge gets none: it tips no way yet, and speculative points on a face it is not turning onto only
// took impulses from the solver's iterations at a hard landing and turned it (a prism landing on its edge
// at 120 m/s went 9 cm deep instead of 3 mm). A hull on a vertex gets none either (it tips onto an edge
// first; the search would cost a square root per point). `down` is the unit local direction towards the
// triangle (the scaled points are measured along it), `extent` the hull's extent along it; sources holds
// the edge's 2 points and gets the face's (at most kMaxFaceCorners). False, changing nothing, when there
// is no such face.
bool wrapToTiltedFace(const btVector3* points, int numPoints, const btVector3& scaling, const btVector3& down,
                      btScalar extent, const btVector3** sources, int& count)
{
	if (count != 2 || numPoints < 3 || !(extent > 0)) return false;
	// In the scaled frame: up is the unit direction away from the triangle.
	btVector3 up = -down;
	const btScalar upLength = up.length();
	if (!(upLength > 0)) return false;
	up /= upLength;
	const btVector3 a = *sources[0] * scaling;
	btVector3 along = *sources[1] * scaling - a;
	// Offsets across the edge shorter than this are on it; a centre of mass this close over the edge is
	// balanced on it.
	const btScalar onLine2 = btScalar(1e-6) * extent * extent;
	const btScalar balanced2 = kHullFaceBand * kHullFaceBand * extent * extent;
	if (!(along.length2() > onLine2)) return false;
	along.normalize();
	// The plane across the edge: level (upright, the part of up across the edge) and sideways.
	btVector3 upright = up - along * along.dot(up);
	if (!(upright.length2() > btScalar(1e-6))) return false;  // an edge standing straight up
	upright.normalize();
	const btVector3 sideways = along.cross(upright);
	// The side the centre of mass is on; none when it is over the edge.
	const btScalar centreAcross = (-a).dot(sideways);
	if (!(centreAcross * centreAcross > balanced2)) return false;
	const btVector3 towards = centreAcross > 0 ? sideways : -sideways;
	// The least slope (height over distance across) on that side is the face's; the points within the band
	// of that plane (measured along its normal) form the face.
	btScalar slope = BT_LARGE_FLOAT;
	for (int i = 0; i < numPoints; ++i)
	{
		const btVector3 r = points[i] * scaling - a;
		const btScalar across = r.dot(towards);
		if (!(across > 0) || !(across * across > onLine2)) continue;
		slope = btMin(slope, r.dot(upright) / across);
	}
	if (!(slope < BT_LARGE_FLOAT)) return false;
	const btVector3 planeNormal = (upright - towards * slope) / btSqrt(btScalar(1) + slope * slope);
	const btScalar tolerance = kHullFaceBand * btScalar(0.5) * extent;
	const btVector3* face[kMaxFaceCorners];
	int numFace = 0;
	for (int i = 0; i < numPoints && numFace < kMaxFaceCorners; ++i)
	{
		if (!((points[i] * scaling - a).dot(planeNormal) <= tolerance)) continue;
		bool duplicate = false;
		for (int j = 0; j < numFace && !duplicate; ++j)
			duplicate = face[j]->x() == points[i].x() && face[j]->y() == points[i].y() && face[j]->z() == points[i].z();
		if (!duplicate) face[numFace++] = &points[i];
	}
	if (numFace < 3) return false;
	for (int i = 0; i < numFace; ++i) sources[i] = face[i];
	count = numFace;
	return true;
}

// The points (times scaling) within kHullFaceBand of the convex's extent along the local direction `down`
// (towards the triangle) below the deepest, one copy of each, in world space moved out by `outwards`:
// the convex's face there, ordered around its centre; 2 points for an edge (a box or barrel landing on
// an edge, clipped as a segment); none for a vertex, where GJK's point is the contact. False, building
// nothing, when the deepest point's depth is below leastDeepest (the convex is out of reach).
bool bandFace(const btVector3* points, int numPoints, const btVector3& scaling, const btVector3& down,
              const btTransform& transform, const btVector3& normal, const btVector3& outwards, btScalar reach,
              btScalar leastDeepest, Polygon& face)
{
	face.count = 0;
	if (numPoints < 2) return true;
	const btVector3 direction = down * scaling;  // unscaled points dotted with it give scaled depths
	btScalar depths[kDepthChunk];
	btScalar deepest = -BT_LARGE_FLOAT, shallowest = BT_LARGE_FLOAT;
	for (int start = 0; start < numPoints; start += kDepthChunk)
	{
		dotsOf(points + start, btMin(kDepthChunk, numPoints - start), direction, depths, deepest, shallowest);
	}
	// The lowest point is out of reach: no face is built (most triangles a mesh query returns).
	if (deepest < leastDeepest) return false;
	const btScalar threshold = deepest - kHullFaceBand * (deepest - shallowest);
	// Non-finite points (bad input, warned about where they were set) give no face: GJK decides.
	if (!btIsFinite(threshold)) return true;
	const btVector3* sources[kMaxFaceCorners];
	// A hull of one chunk still has its depths; larger ones are dotted again, chunk by chunk.
	for (int start = 0; start < numPoints && face.count < kMaxFaceCorners; start += kDepthChunk)
	{
		const int count = btMin(kDepthChunk, numPoints - start);
		btScalar unusedHigh = deepest, unusedLow = shallowest;
		if (numPoints > kDepthChunk) dotsOf(points + start, count, direction, depths, unusedHigh, unusedLow);
		// Most points are far from the band: in SSE builds four depths are tested at once.
		int inBand[kDepthChunk];
		int numInBand = 0;
		int i = 0;
#ifdef BT_USE_SSE
		const __m128 limit = _mm_set1_ps(threshold);
		for (; i + 4 <= count; i += 4)
		{
			const int mask = _mm_movemask_ps(_mm_cmpge_ps(_mm_loadu_ps(depths + i), limit));
			if (mask == 0) continue;
			for (int lane = 0; lane < 4; ++lane)
				if (mask & (1 << lane)) inBand[numInBand++] = i + lane;
		}
#endif
		for (; i < count; ++i)
			if (depths[i] >= threshold) inBand[numInBand++] = i;
		for (int k = 0; k < numInBand && face.count < kMaxFaceCorners; ++k)
		{
			// Hulls often list a point twice (a closed ring, as copies); one copy is enough.
			const btVector3& point = points[start + inBand[k]];
			bool duplicate = false;
			for (int j = 0; j < face.count && !duplicate; ++j)
				duplicate =
				    sources[j]->x() == point.x() && sources[j]->y() == point.y() && sources[j]->z() == point.z();
			if (duplicate) continue;
			sources[face.count] = &point;
			face.corners[face.count++] = transform(point * scaling) + outwards;
		}
	}
	// The face it tips onto only when the reach covers much of it (a fast landing or tipping): otherwise its
	// points within reach lie next to the edge, which holds the hull already, and the search would be paid
	// for nothing (on every triangle near a hull rolling on a curved mesh).
	if (face.count == 2 && reach > kWrapReach * (deepest - shallowest) &&
	    wrapToTiltedFace(points, numPoints, scaling, down, deepest - shallowest, sources, face.count))
	{
		for (int i = 0; i < face.count; ++i) face.corners[i] = transform(*sources[i] * scaling) + outwards;
	}
	if (face.count < 2)
		face.count = 0;
	else if (face.count > 3)  // any order of 2 or 3 points is a polygon already
		orderAroundCentre(normal, face);
	return true;
}

// A btConvexHullShape's face over the triangle from its points (see bandFace), moved out by the margin
// (the hull's surface is its points' hull grown by it). False, building nothing, when the hull's lowest
// point along the normal is above lowestAllowed (world height along the normal).
bool hullPointsFace(const btConvexHullShape& hull, const btTransform& transform, const btVector3& normal,
                    btScalar reach, btScalar lowestAllowed, Polygon& face)
{
	face.count = 0;
	const btVector3* points = hull.getUnscaledPoints();
	if (!points) return true;
	// A point's height along the normal is origin . normal - margin - its depth along down.
	const btScalar leastDeepest = transform.getOrigin().dot(normal) - hull.getMargin() - lowestAllowed;
	return bandFace(points, hull.getNumPoints(), hull.getLocalScaling(), -normal * transform.getBasis(), transform,
	                normal, -normal * hull.getMargin(), reach, leastDeepest, face);
}

// A polyhedron's face over the triangle: its face most opposed to the normal when that lies on the
// triangle (within GJK's face tolerance), corners in the polyhedron's own order, moved out by the margin
// (hulls' polyhedra are their margin-free cores). Otherwise, and for a polyhedron without faces, its
// vertices in the band, or the face it tips onto (see bandFace).
void polyhedronFace(const btConvexPolyhedron& polyhedron, btScalar margin, const btTransform& transform,
                    const btVector3& normal, btScalar reach, Polygon& face)
{
	face.count = 0;
	const btVector3 local = normal * transform.getBasis();
	int best = -1;
	btScalar bestDot = 0;
	for (int f = 0; f < polyhedron.m_faces.size(); ++f)
	{
		const btScalar* plane = polyhedron.m_faces[f].m_plane;
		const btScalar along = plane[0] * local.x() + plane[1] * local.y() + plane[2] * local.z();
		if (along < bestDot)
		{
			bestDot = along;
			best = f;
		}
	}
	const int numVertices = polyhedron.m_vertices.size();
	const btVector3 outwards = -normal * margin;
	// A face tilted beyond GJK's face tolerance is not lying on the triangle: the polyhedron lies on an
	// edge or a vertex, and its face is found from its vertices as a hull's is (the face on its centre of
	// mass's side, which it tips onto; none when balanced: two faces equally tilted either side of an edge
	// are no guide).
	if (best < 0 || polyhedron.m_faces[best].m_indices.size() < 3 || -bestDot < kFaceNormalCosine)
	{
		if (numVertices > 0)
			bandFace(&polyhedron.m_vertices[0], numVertices, btVector3(1, 1, 1), -local, transform, normal, outwards,
			         reach, -BT_LARGE_FLOAT, face);
		return;
	}
	const btAlignedObjectArray<int>& indices = polyhedron.m_faces[best].m_indices;
	for (int i = 0; i < indices.size() && face.count < kMaxFaceCorners; ++i)
	{
		const int index = indices[i];
		if (index < 0 || index >= numVertices) continue;
		face.corners[face.count++] = transform(polyhedron.m_vertices[index]) + outwards;
	}
	if (face.count < 3) face.count = 0;
}

// A hull's face over the triangle: from its polyhedron when it has one, else from its points. False,
// building nothing, when a hull's points show it out of reach: its lowest point along the normal is above
// lowestAllowed (BT_LARGE_FLOAT: never; a polyhedron's face is always built, and its corners tell).
bool convexFace(const btConvexShape& convex, const btTransform& transform, const btVector3& normal, btScalar reach,
                btScalar lowestAllowed, Polygon& face)
{
	face.count = 0;
	const btConvexPolyhedron* polyhedron = static_cast<const btPolyhedralConvexShape&>(convex).getConvexPolyhedron();
	if (polyhedron)
		polyhedronFace(*polyhedron, convex.getMargin(), transform, normal, reach, face);
	else if (convex.getShapeType() == CONVEX_HULL_SHAPE_PROXYTYPE)
		return hullPointsFace(static_cast<const btConvexHullShape&>(convex), transform, normal, reach, lowestAllowed,
		                      face);
	return true;
}

// Sutherland-Hodgman: keeps the part of the closed polygon in on the side (x - origin) . side <= 0.
// Returns false, writing nothing, when all of it is on that side already (no cut needed). Each corner's
// distance is found once, and the count is kept in a register (out may not alias in, but the compiler
// cannot know: a count in memory is reloaded after every store).
bool clipBySide(const Polygon& in, Polygon& out, const btVector3& origin, const btVector3& side)
{
	const int count = in.count;
	btScalar distances[kMaxClipped];
	bool inside = true;
	for (int i = 0; i < count; ++i)
	{
		distances[i] = (in.corners[i] - origin).dot(side);
		inside = inside && distances[i] <= 0;
	}
	if (inside) return false;
	int written = 0;
	int previous = count - 1;
	for (int i = 0; i < count; ++i)
	{
		const btScalar previousDistance = distances[previous];
		const btScalar distance = distances[i];
		if ((previousDistance < 0) != (distance < 0))
		{
			const btScalar t = previousDistance / (previousDistance - distance);
			const btVector3& from = in.corners[previous];
			if (written < kMaxClipped) out.corners[written++] = from + (in.corners[i] - from) * t;
		}
		if (distance <= 0 && written < kMaxClipped) out.corners[written++] = in.corners[i];
		previous = i;
	}
	out.count = written;
	return true;
}

// Keeps the part of the segment (a 2-corner polygon) on the side (x - origin) . side <= 0; count 0 when
// none of it is.
void clipSegmentBySide(Polygon& segment, const btVector3& origin, const btVector3& side)
{
	const btScalar d0 = (segment.corners[0] - origin).dot(side);
	const btScalar d1 = (segment.corners[1] - origin).dot(side);
	if (d0 > 0 && d1 > 0)
	{
		segment.count = 0;
		return;
	}
	if (d0 <= 0 && d1 <= 0) return;
	const btVector3 cut = segment.corners[0] + (segment.corners[1] - segment.corners[0]) * (d0 / (d0 - d1));
	segment.corners[d0 > 0 ? 0 : 1] = cut;
}
}  // namespace

int chooseManifoldPoints(const btVector3* points, const btScalar* distances, int count, const btVector3& normal,
                         int chosen[4])
{
	if (count <= 0) return 0;
	int deepest = 0;
	btVector3 centre(0, 0, 0);
	for (int i = 0; i < count; ++i)
	{
		if (distances[i] < distances[deepest]) deepest = i;
		centre += points[i];
	}
	centre /= btScalar(count);
	// The corners of the patch, not its deepest point first: points of a flat contact have equal depths up
	// to rounding, and a point inside the patch would waste a slot.
	int first = 0;
	btScalar firstDistance2 = -1;
	for (int i = 0; i < count; ++i)
	{
		const btScalar distance2 = (points[i] - centre).length2();
		if (distance2 > firstDistance2)
		{
			firstDistance2 = distance2;
			first = i;
		}
	}
	int numChosen = 0;
	chosen[numChosen++] = first;
	int farthest = -1;
	btScalar farthestDistance2 = SIMD_EPSILON;
	for (int i = 0; i < count; ++i)
	{
		const btScalar distance2 = (points[i] - points[first]).length2();
		if (distance2 > farthestDistance2)
		{
			farthestDistance2 = distance2;
			farthest = i;
		}
	}
	if (farthest >= 0)
	{
		chosen[numChosen++] = farthest;
		const btVector3 line = points[farthest] - points[first];
		int left = -1, right = -1;
		btScalar leftArea = SIMD_EPSILON * farthestDistance2, rightArea = -SIMD_EPSILON * farthestDistance2;
		for (int i = 0; i < count; ++i)
		{
			const btScalar area = line.cross(points[i] - points[first]).dot(normal);
			if (area > leftArea)
			{
				leftArea = area;
				left = i;
			}
			else if (area < rightArea)
			{
				rightArea = area;
				right = i;
			}
		}
		// In order around the patch (first, left, farthest, right), not diagonal pairs first: the solver
		// takes a manifold's points in this order, and on a narrow face that rocks by solver noise, solving
		// the two ends of one diagonal and then of the other biased the single velocity-following friction
		// row into a one-way creep (a resting 12-sided prism crept 1 mm/s); in order around it the rocking
		// stays symmetric and the body still.
		if (left >= 0)
		{
			chosen[numChosen++] = left;
			btSwap(chosen[numChosen - 1], chosen[numChosen - 2]);
		}
		if (right >= 0) chosen[numChosen++] = right;
	}
	// The deepest point carries the contact when the others are clearly shallower (a tilted face landing
	// on its lowest corner): it takes the last slot unless a chosen point is within a millimetre of it.
	btScalar chosenDeepest = BT_LARGE_FLOAT;
	bool haveDeepest = false;
	for (int i = 0; i < numChosen; ++i)
	{
		chosenDeepest = btMin(chosenDeepest, distances[chosen[i]]);
		haveDeepest = haveDeepest || chosen[i] == deepest;
	}
	if (!haveDeepest && distances[deepest] < chosenDeepest - btScalar(0.001))
	{
		if (numChosen < 4)
			chosen[numChosen++] = deepest;
		else
			chosen[numChosen - 1] = deepest;
	}
	return numChosen;
}

namespace
{
// The points a triangle reports: at most 4 of count (chooseManifoldPoints), else all. Writes their indices
// to chosen and returns how many.
int chooseAtMostFour(const btVector3* points, const btScalar* distances, int count, const btVector3& normal,
                     int chosen[kMaxClipped])
{
	if (count > 4) return chooseManifoldPoints(points, distances, count, normal, chosen);
	for (int i = 0; i < count; ++i) chosen[i] = i;
	return count;
}
}  // namespace

bool worldTriangleOf(const btTriangleShape& triangle, const btTransform& transform, WorldTriangle& world)
{
	for (int k = 0; k < 3; ++k) world.corners[k] = transform(triangle.m_vertices1[k]);
	const btVector3 edge1 = world.corners[1] - world.corners[0];
	const btVector3 edge2 = world.corners[2] - world.corners[0];
	world.windingNormal = edge1.cross(edge2);
	world.normalLength2 = world.windingNormal.length2();
	return world.normalLength2 > SIMD_EPSILON * edge1.length2() * edge2.length2() && btIsFinite(world.normalLength2);
}

TriangleClipping triangleClippingOf(const btCollisionShape& convex)
{
	switch (convex.getShapeType())
	{
		case BOX_SHAPE_PROXYTYPE:
			return kClipBeforeGjk;
		case CONVEX_HULL_SHAPE_PROXYTYPE:
			return kClipAfterGjk;
		case TETRAHEDRAL_SHAPE_PROXYTYPE:
		case CONVEX_TRIANGLEMESH_SHAPE_PROXYTYPE:
		case CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE:
			// Their face comes from the polyhedron, which initializePolyhedralFeatures builds.
			return static_cast<const btPolyhedralConvexShape&>(convex).getConvexPolyhedron() ? kClipAfterGjk
			                                                                                 : kNoClipping;
		default:
			return kNoClipping;
	}
}

namespace
{
// When faceContactOn is asked, which decides what it may report.
enum FaceSearch
{
	kFaceSearch,             // the face's points within reach, whatever the outcome
	kFaceNormalIsTheWayOut,  // GJK and the depth solver found the face normal: a deep face holds too
};
TriangleFaceOutcome faceContactOn(const WorldTriangle& world, const btConvexShape& convex,
                                  const btTransform& convexTransform, const btTriangleShape& triangle, btScalar reach,
                                  btDiscreteCollisionDetectorInterface::Result& out, FaceSearch search = kFaceSearch);
int triangleUnderConvexFace(const WorldTriangle& world, const btConvexShape& convex, const btTransform& convexTransform,
                            const btTriangleShape& triangle, const btVector3& gjkNormal, btScalar touching,
                            btDiscreteCollisionDetectorInterface::Result& out);
}  // namespace

TriangleFaceOutcome triangleFaceContact(const btConvexShape& convex, const btTransform& convexTransform,
                                        const btTriangleShape& triangle, const btTransform& triangleTransform,
                                        btScalar reach, btDiscreteCollisionDetectorInterface::Result& out)
{
	WorldTriangle world;
	if (!worldTriangleOf(triangle, triangleTransform, world)) return kTriangleNeedsGjk;
	return faceContactOn(world, convex, convexTransform, triangle, reach, out);
}

TriangleFaceOutcome hullTriangleFaceContactBeforeGjk(const btConvexShape& convex, const btTransform& convexTransform,
                                                     const btTriangleShape& triangle,
                                                     const btTransform& triangleTransform, btScalar reach,
                                                     btDiscreteCollisionDetectorInterface::Result& out,
                                                     TriangleFaceSearch& search)
{
	search.done = false;
	search.count = 0;
	if (!worldTriangleOf(triangle, triangleTransform, search.world)) return kTriangleNeedsGjk;
	search.outcome = faceContactOn(search.world, convex, convexTransform, triangle, reach, search);
	search.done = true;
	if (search.outcome == kTriangleFaceContact) search.replay(out);
	return search.outcome == kTriangleFaceContact || search.outcome == kTriangleOutOfReach ? search.outcome
	                                                                                        : kTriangleNeedsGjk;
}

TriangleFaceOutcome triangleFaceContactAlongGjkNormal(const btConvexShape& convex, const btTransform& convexTransform,
                                                      const btTriangleShape& triangle,
                                                      const btTransform& triangleTransform, btScalar reach,
                                                      const btVector3& gjkNormal, btScalar gjkDistance,
                                                      btScalar touching,
                                                      btDiscreteCollisionDetectorInterface::Result& out,
                                                      const TriangleFaceSearch* before)
{
	// The face test in the triangle's frame first: most normals GJK finds against a mesh (edges, vertices)
	// are not a face's, and the corners need not be moved to world space for them.
	const btVector3* v = triangle.m_vertices1;
	const btVector3 face = (v[1] - v[0]).cross(v[2] - v[0]);
	const btVector3 localNormal = gjkNormal * triangleTransform.getBasis();
	const btScalar along = face.dot(localNormal);
	const btScalar normalLength2 = localNormal.length2();
	// A zero or non-finite normal (GJK gave none) is no face's.
	if (!(normalLength2 > 0) || !btIsFinite(normalLength2)) return kTriangleNeedsGjk;
	WorldTriangle found;
	const bool searched = before && before->done;
	if (!searched && !worldTriangleOf(triangle, triangleTransform, found)) return kTriangleNeedsGjk;
	const WorldTriangle& world = searched ? before->world : found;
	if (along * along >= kFaceNormalCosine * kFaceNormalCosine * face.length2() * normalLength2)
	{
		// Points found before GJK are this search's too (only a deep face, found nothing then, differs).
		if (before && before->done && before->outcome == kTriangleFacePointsAndGjk)
		{
			before->replay(out);
			return before->outcome;
		}
		return faceContactOn(world, convex, convexTransform, triangle, reach, out, kFaceNormalIsTheWayOut);
	}
	// The convex's face lies on the triangle's edge or vertex (a ridge, a peak): the triangle's part under
	// the face, along the face's normal, is the whole contact.
	if (gjkDistance <= touching &&
	    triangleUnderConvexFace(world, convex, convexTransform, triangle, gjkNormal, touching, out) > 0)
		return kTriangleFaceContact;
	// Only a convex closing in (a fast landing, a tip onto a face) can bring a face down onto the triangle
	// within the step; at rest (reach about the breaking threshold) GJK's point is the contact, and the
	// face search is spared for every triangle around a hull lying on a curved mesh.
	if (!(reach > 2 * touching)) return kTriangleNeedsGjk;
	// GJK's nearest feature is the triangle's edge or vertex, but part of the convex's face may still lie
	// over the triangle within reach: a hull tipping onto a face that overhangs the triangle it landed on
	// (its face's points over the neighbours are what stop it there), or a face resting across a ridge or a
	// vertex. Those points are reported along the face normal, as a box's are; GJK's point is added too
	// (the collector drops it when the edge is internal).
	TriangleFaceOutcome outcome;
	if (before && before->done)
	{
		outcome = before->outcome;
		before->replay(out);
	}
	else
	{
		outcome = faceContactOn(world, convex, convexTransform, triangle, reach, out);
	}
	return outcome == kTriangleNeedsGjk || outcome == kTriangleOutOfReach ? kTriangleNeedsGjk
	                                                                      : kTriangleFacePointsAndGjk;
}

namespace
{
// The convex's face touching a triangle's edge or vertex (GJK's normal is the face's, not the triangle's):
// the triangle clipped against the face's side planes, its points within `touching` of the face's plane
// reported with the face's normal (at most 4, spanning the largest area). A face resting across a ridge
// or on a vertex is held at the ends of the ridge's segment under it, not at GJK's single point (on which
// it rocked and crept), and its normal is the face's, not a triangle's tilted one. Returns how many.
int triangleUnderConvexFace(const WorldTriangle& world, const btConvexShape& convex, const btTransform& convexTransform,
                            const btTriangleShape& triangle, const btVector3& gjkNormal, btScalar touching,
                            btDiscreteCollisionDetectorInterface::Result& out)
{
	btVector3 normal = gjkNormal;  // from the triangle towards the convex
	const btScalar length2 = normal.length2();
	if (!(length2 > 0) || !btIsFinite(length2)) return 0;
	normal /= btSqrt(length2);
	Polygon face;
	if (convex.getShapeType() == BOX_SHAPE_PROXYTYPE)
		boxFace(static_cast<const btBoxShape&>(convex), convexTransform, normal * convexTransform.getBasis(), face);
	else
		convexFace(convex, convexTransform, normal, 0, BT_LARGE_FLOAT, face);  // across the normal, never tilted
	if (face.count < 3) return 0;
	// The face's own normal (Newell's, robust for any polygon in order), facing the triangle; only a face
	// across GJK's normal is the contact (a tilted face found by wrapping is not).
	btVector3 outwards(0, 0, 0);
	for (int i = 0; i < face.count; ++i)
	{
		const btVector3& a = face.corners[i];
		const btVector3& b = face.corners[i + 1 == face.count ? 0 : i + 1];
		outwards += btVector3((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()),
		                      (a.x() - b.x()) * (a.y() + b.y()));
	}
	const btScalar outwardsLength = outwards.length();
	if (!(outwardsLength > 0)) return 0;
	outwards /= outwardsLength;
	if (outwards.dot(normal) > 0) outwards = -outwards;
	if (-outwards.dot(normal) < kFaceNormalCosine) return 0;
	btVector3 centre(0, 0, 0);
	for (int i = 0; i < face.count; ++i) centre += face.corners[i];
	centre /= btScalar(face.count);

	Polygon clippedA, clippedB;
	clippedA.count = 3;
	for (int k = 0; k < 3; ++k) clippedA.corners[k] = world.corners[k];
	Polygon* in = &clippedA;
	Polygon* clipped = &clippedB;
	for (int i = 0; i < face.count && in->count > 0; ++i)
	{
		const btVector3& from = face.corners[i];
		btVector3 side = (face.corners[i + 1 == face.count ? 0 : i + 1] - from).cross(outwards);
		if ((centre - from).dot(side) > 0) side = -side;  // facing out of the face
		if (clipBySide(*in, *clipped, from, side)) btSwap(in, clipped);
	}
	// Separation from the face's plane along its normal; the triangle's surface is grown by its margin.
	const btScalar margin = triangle.getMargin();
	const btVector3 contactNormal = -outwards;
	btScalar separations[kMaxClipped];
	btScalar closest = BT_LARGE_FLOAT;
	for (int i = 0; i < in->count; ++i)
	{
		separations[i] = (in->corners[i] - face.corners[0]).dot(outwards) - margin;
		closest = btMin(closest, separations[i]);
	}
	// The triangle's points at the level of its closest: the ridge's segment, or the vertex, under the
	// face (a sloping triangle's points farther down are not touching and would crowd out the segment's
	// ends when 4 are chosen).
	const btScalar level = btMin(touching, closest + kFaceLevelTolerance);
	// Only points on the triangle's edges or vertices: a point inside it lies under a corner of the face,
	// a vertex-face contact whose normal is the triangle's (reported along it by the face path), not the
	// face's (a hull lying on a flat mesh got points leaning with its side face there, and rested on them).
	const btVector3 edges[3] = {world.corners[1] - world.corners[0], world.corners[2] - world.corners[1],
	                            world.corners[0] - world.corners[2]};
	const btScalar longest2 = btMax(btMax(edges[0].length2(), edges[1].length2()), edges[2].length2());
	const btScalar onEdge2 = kOnTriangleEdge * kOnTriangleEdge * longest2;
	btVector3 points[kMaxClipped];
	btScalar distances[kMaxClipped];
	int count = 0;
	for (int i = 0; i < in->count; ++i)
	{
		const btScalar distance = separations[i];
		if (!(distance <= level) || distance < -kFaceDepthLimit) continue;
		bool onBoundary = false;
		for (int k = 0; k < 3 && !onBoundary; ++k)
		{
			const btVector3 offset = in->corners[i] - world.corners[k];
			const btScalar length2 = edges[k].length2();
			const btScalar t = btMax(btScalar(0), btMin(btScalar(1), offset.dot(edges[k]) / length2));
			onBoundary = (offset - edges[k] * t).length2() <= onEdge2;
		}
		if (!onBoundary) continue;
		points[count] = in->corners[i] + contactNormal * margin;
		distances[count] = distance;
		++count;
	}
	int chosen[kMaxClipped];
	const int numChosen = chooseAtMostFour(points, distances, count, contactNormal, chosen);
	for (int i = 0; i < numChosen; ++i) out.addContactPoint(contactNormal, points[chosen[i]], distances[chosen[i]]);
	return numChosen;
}

// Says early, for a box, that a triangle is out of reach (or far below the box, for GJK) by separating
// axes in closed form: the triangle's normal, unnormalised and compared squared (no square root or
// division for the many triangles a mesh query returns out of reach: their latency, not their count, is
// what they cost), then its three side planes. kTriangleFaceContact means "no verdict, go on".
TriangleFaceOutcome boxOutOfReachVerdict(const WorldTriangle& world, const btBoxShape& box,
                                         const btTransform& convexTransform, const btTriangleShape& triangle,
                                         btScalar reach)
{
	const btVector3* corners = world.corners;
	const btVector3& normal = world.windingNormal;
	const btScalar normalLength2 = world.normalLength2;
	const btVector3 local = normal * convexTransform.getBasis();
	const btVector3 half = box.getHalfExtentsWithMargin();
	const btScalar centre = normal.dot(convexTransform.getOrigin() - corners[0]);
	const btScalar clearance =
	    btFabs(centre) - btFabs(local.x()) * half.x() - btFabs(local.y()) * half.y() - btFabs(local.z()) * half.z();
	// The exact tests of faceContactOn decide the cases near the limits (rounding differs a little here).
	const btScalar slack = btScalar(1.0001);
	if (clearance > 0)
	{
		const btScalar allowed = reach + triangle.getMargin();
		if (allowed >= 0 && clearance * clearance > allowed * allowed * normalLength2 * slack)
			return kTriangleOutOfReach;
	}
	else
	{
		// Far below the plane (the plane of a neighbour of the triangle the box is on): GJK's, as in
		// faceContactOn, found without building the face.
		const btScalar below = kFaceDepthLimit + kDepthSlack - triangle.getMargin();
		if (below > 0 && clearance * clearance > below * below * normalLength2 * slack) return kTriangleNeedsGjk;
	}
	// The triangle's side planes are separating axes too: a triangle beside the box (inside its AABB, which
	// the mesh query tests, but not under it) is out of reach when the whole box lies beyond one edge's side
	// plane by more than reach. Without this, such triangles clip to nothing and go to GJK.
	const btScalar allowed = reach + triangle.getMargin();
	if (allowed >= 0)
	{
		const btVector3 edges[3] = {corners[1] - corners[0], corners[2] - corners[1], corners[0] - corners[2]};
		for (int k = 0; k < 3; ++k)
		{
			const btVector3 side = edges[k].cross(normal);  // outwards, length |edge| |normal|
			const btVector3 sideLocal = side * convexTransform.getBasis();
			const btScalar gap = side.dot(convexTransform.getOrigin() - corners[k]) -
			                     btFabs(sideLocal.x()) * half.x() - btFabs(sideLocal.y()) * half.y() -
			                     btFabs(sideLocal.z()) * half.z();
			if (gap > 0 && gap * gap > allowed * allowed * side.length2() * slack) return kTriangleOutOfReach;
		}
	}
	return kTriangleFaceContact;
}

// Cuts the face by the triangle's prism: a side plane through each edge, containing the normal, facing out
// (faces inside the prism, a convex over a large triangle, need no cut). Returns the polygon holding the
// result (face or scratch).
Polygon* clipFaceToTrianglePrism(Polygon& face, Polygon& scratch, const btVector3* corners,
                                 const btVector3& windingNormal)
{
	Polygon* in = &face;
	Polygon* clipped = &scratch;
	for (int edge = 0; edge < 3 && in->count > 0; ++edge)
	{
		const btVector3& from = corners[edge];
		// Outwards whichever face the convex is in front of (no test of the third corner: the sliver test
		// leaves no triangle whose winding rounding could turn).
		const btVector3 side = (corners[edge == 2 ? 0 : edge + 1] - from).cross(windingNormal);
		// An edge of a hull is a segment (a closed 2-corner polygon would come back with a point twice).
		if (in->count == 2)
			clipSegmentBySide(*in, from, side);
		else if (clipBySide(*in, *clipped, from, side))
			btSwap(in, clipped);
	}
	return in;
}

// The clipped corners within reach of the triangle's plane and their distances; returns how many and the
// closest distance.
struct PointsWithinReach
{
	btVector3 points[kMaxClipped];
	btScalar distances[kMaxClipped];
	int count = 0;
	btScalar closest = BT_LARGE_FLOAT;
};

void pointsWithinReach(const Polygon& clipped, const btVector3& normal, btScalar planeOffset, btScalar reach,
                       PointsWithinReach& within)
{
	for (int i = 0; i < clipped.count; ++i)
	{
		const btScalar distance = clipped.corners[i].dot(normal) - planeOffset;
		if (!(distance <= reach)) continue;
		within.points[within.count] = clipped.corners[i];
		within.distances[within.count] = distance;
		within.closest = btMin(within.closest, distance);
		++within.count;
	}
}

// Reports the points (at most 4 a triangle: choosing here costs less than handing the collector more
// points), each on the triangle's surface.
void reportPointsWithinReach(const PointsWithinReach& within, const btVector3& normal,
                             btDiscreteCollisionDetectorInterface::Result& out)
{
	int chosen[kMaxClipped];
	const int numChosen = chooseAtMostFour(within.points, within.distances, within.count, normal, chosen);
	for (int i = 0; i < numChosen; ++i)
	{
		const int k = chosen[i];
		out.addContactPoint(normal, within.points[k] - normal * within.distances[k], within.distances[k]);
	}
}

TriangleFaceOutcome faceContactOn(const WorldTriangle& world, const btConvexShape& convex,
                                  const btTransform& convexTransform, const btTriangleShape& triangle, btScalar reach,
                                  btDiscreteCollisionDetectorInterface::Result& out, FaceSearch search)
{
	const btVector3* corners = world.corners;
	if (convex.getShapeType() == BOX_SHAPE_PROXYTYPE)
	{
		const TriangleFaceOutcome verdict = boxOutOfReachVerdict(world, static_cast<const btBoxShape&>(convex),
		                                                         convexTransform, triangle, reach);
		if (verdict != kTriangleFaceContact) return verdict;
	}
	btVector3 normal = world.windingNormal;
	normal /= btSqrt(world.normalLength2);
	// Two-sided: the face the convex's centre is in front of (GJK starts from the same side).
	// The normal of the corners' own winding: each edge crossed with it points out of the triangle.
	const btVector3 windingNormal = normal;
	if (normal.dot(convexTransform.getOrigin() - corners[0]) < 0) normal = -normal;

	// Distances to the triangle's plane, which its margin moves out. The normal separates the two by at
	// least the convex's lowest point's distance.
	const btScalar planeOffset = corners[0].dot(normal) + triangle.getMargin();
	Polygon face, scratch;
	if (convex.getShapeType() == BOX_SHAPE_PROXYTYPE)
	{
		// Most triangles a mesh query returns are out of reach: the box's lowest point, in closed form, says
		// so before any face is built.
		const btBoxShape& box = static_cast<const btBoxShape&>(convex);
		const btVector3 local = normal * convexTransform.getBasis();
		const btVector3 half = box.getHalfExtentsWithMargin();
		const btScalar lowestPoint = convexTransform.getOrigin().dot(normal) - btFabs(local.x()) * half.x() -
		                             btFabs(local.y()) * half.y() - btFabs(local.z()) * half.z();
		if (lowestPoint - planeOffset > reach) return kTriangleOutOfReach;
		boxFace(box, convexTransform, local, face);
	}
	else if (!convexFace(convex, convexTransform, normal, reach, planeOffset + reach, face))
	{
		return kTriangleOutOfReach;
	}
	if (face.count == 0) return kTriangleNeedsGjk;

	// The face holds the convex's lowest point along the normal.
	btScalar lowest = BT_LARGE_FLOAT;
	for (int i = 0; i < face.count; ++i) lowest = btMin(lowest, face.corners[i].dot(normal));
	lowest -= planeOffset;
	if (lowest > reach) return kTriangleOutOfReach;
	// Deep in, the face normal may not be the way out (a triangle's edge poking into a side): GJK and the
	// depth solver decide, as for every other shape.
	// Unless GJK and the depth solver found the face normal to be the way out: then the whole face holds
	// the convex as it is pushed out (a hull spun onto its face by a fast landing, found deep a step later,
	// rocked about GJK's single point and sank further).
	if ((lowest < -kFaceDepthLimit && search != kFaceNormalIsTheWayOut) || face.count < 2) return kTriangleNeedsGjk;

	const Polygon* clipped = clipFaceToTrianglePrism(face, scratch, corners, windingNormal);
	PointsWithinReach within;
	pointsWithinReach(*clipped, normal, planeOffset, reach, within);
	if (within.count == 0) return kTriangleNeedsGjk;
	// The lowest point over the triangle: the face normal is the closest direction, nothing more to find.
	// Otherwise the lowest point is beyond an edge, where the nearest feature may be that edge (GJK's).
	const TriangleFaceOutcome outcome =
	    within.closest <= lowest + kFaceLevelTolerance ? kTriangleFaceContact : kTriangleFacePointsAndGjk;
	reportPointsWithinReach(within, normal, out);
	return outcome;
}
}  // namespace
}  // namespace caliber
