// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btCapsuleTriangleContact.h"

#include "BulletCollision/CollisionDispatch/btCapsuleCapsuleContact.h"

namespace caliber
{
namespace
{
// An edge point counts only when it is nearer than the face by this much: level with the face, the face
// points already hold the capsule (a tenth of the default breaking threshold, as face clipping uses).
const btScalar kEdgeCloserBy = btScalar(0.002);

struct EdgeContact
{
	btVector3 onSegment;
	btVector3 onTriangle;
	btScalar distance2 = BT_LARGE_FLOAT;
};

// The closest points of the core segment and the triangle's boundary.
EdgeContact closestEdgeContact(const btVector3& p0, const btVector3& p1, const btVector3* corners)
{
	EdgeContact best;
	for (int k = 0; k < 3; ++k)
	{
		const btVector3& from = corners[k];
		const btVector3& to = corners[k == 2 ? 0 : k + 1];
		btScalar s, t;
		closestPointsOfSegments(p0, p1, from, to, s, t);
		const btVector3 onSegment = p0 + (p1 - p0) * s;
		const btVector3 onEdge = from + (to - from) * t;
		const btScalar distance2 = (onSegment - onEdge).length2();
		if (distance2 < best.distance2)
		{
			best.onSegment = onSegment;
			best.onTriangle = onEdge;
			best.distance2 = distance2;
		}
	}
	return best;
}
}  // namespace

TriangleFaceOutcome capsuleTriangleContact(const btCapsuleShape& capsule, const btTransform& capsuleTransform,
                                           const btTriangleShape& triangle, const btTransform& triangleTransform,
                                           btScalar reach, btDiscreteCollisionDetectorInterface::Result& out)
{
	const btVector3 corners[3] = {triangleTransform(triangle.m_vertices1[0]),
	                              triangleTransform(triangle.m_vertices1[1]),
	                              triangleTransform(triangle.m_vertices1[2])};
	const btVector3 edge1 = corners[1] - corners[0];
	const btVector3 edge2 = corners[2] - corners[0];
	const btVector3 windingNormal = edge1.cross(edge2);
	const btScalar normalLength2 = windingNormal.length2();
	// A sliver's cross product is mostly rounding; GJK's point is better there.
	if (!(normalLength2 > SIMD_EPSILON * edge1.length2() * edge2.length2()) || !btIsFinite(normalLength2))
		return kTriangleNeedsGjk;

	const btVector3 axis = capsuleTransform.getBasis().getColumn(capsule.getUpAxis()) * capsule.getHalfHeight();
	const btVector3 p0 = capsuleTransform.getOrigin() - axis;
	const btVector3 p1 = capsuleTransform.getOrigin() + axis;
	const btScalar surface = capsule.getRadius() + triangle.getMargin();
	// The core segment and the triangle touch within reach when they are at most this far apart.
	const btScalar allowed = reach + surface;
	if (!(allowed > 0)) return kTriangleOutOfReach;

	// Heights of the segment's ends over the plane, unnormalised; both beyond reach on one side: nothing.
	const btScalar side0 = windingNormal.dot(p0 - corners[0]);
	const btScalar side1 = windingNormal.dot(p1 - corners[0]);
	if ((side0 > 0) != (side1 > 0) || side0 == 0 || side1 == 0) return kTriangleNeedsGjk;
	const btScalar nearest = btMin(btFabs(side0), btFabs(side1));
	if (nearest * nearest > allowed * allowed * normalLength2) return kTriangleOutOfReach;

	const btScalar inverseLength = 1 / btSqrt(normalLength2);
	// Two-sided: the face the capsule is in front of.
	const btVector3 normal = windingNormal * (side0 > 0 ? inverseLength : -inverseLength);
	const btScalar height0 = btFabs(side0) * inverseLength;
	const btScalar height1 = btFabs(side1) * inverseLength;

	// The part [low, high] of the segment over the triangle: its prism's side planes, facing out.
	btScalar low = 0, high = 1;
	for (int k = 0; k < 3 && low <= high; ++k)
	{
		const btVector3& from = corners[k];
		const btVector3 side = (corners[k == 2 ? 0 : k + 1] - from).cross(windingNormal);
		const btScalar d0 = side.dot(p0 - from), d1 = side.dot(p1 - from);
		if (d0 > 0 && d1 > 0) high = -1;  // wholly outside this side
		else if (d0 > 0)
			low = btMax(low, d0 / (d0 - d1));
		else if (d1 > 0)
			high = btMin(high, d0 / (d0 - d1));
	}

	int reported = 0;
	btScalar faceHeight = BT_LARGE_FLOAT;
	if (low <= high)
	{
		const btScalar ends[2] = {low, high};
		// Heights are linear along the segment: the part's ends hold its extremes.
		const int numEnds = (high - low) * (capsule.getHalfHeight() * 2) > kEdgeCloserBy ? 2 : 1;
		for (int e = 0; e < numEnds; ++e)
		{
			const btScalar t = ends[e];
			const btScalar height = height0 + (height1 - height0) * t;
			faceHeight = btMin(faceHeight, height);
			const btScalar depth = height - surface;
			if (!(depth <= reach)) continue;
			const btVector3 onSegment = p0 + (p1 - p0) * t;
			out.addContactPoint(normal, onSegment - normal * (height - triangle.getMargin()), depth);
			++reported;
		}
		// The segment's lowest point is over the triangle: the face holds the whole contact.
		if (btMin(height0, height1) >= faceHeight - kEdgeCloserBy) return reported ? kTriangleFaceContact : kTriangleOutOfReach;
	}

	// Part of the segment is beyond an edge and lower there (or all of it is): the boundary's closest point.
	const EdgeContact edge = closestEdgeContact(p0, p1, corners);
	const btScalar tiny = btScalar(1e-10) * surface * surface;
	if (!(edge.distance2 > tiny)) return reported ? kTriangleFaceContact : kTriangleNeedsGjk;
	const btScalar distance = btSqrt(edge.distance2);
	if (distance - surface <= reach && distance < faceHeight - kEdgeCloserBy)
	{
		const btVector3 edgeNormal = (edge.onSegment - edge.onTriangle) / distance;
		out.addContactPoint(edgeNormal, edge.onTriangle + edgeNormal * triangle.getMargin(), distance - surface);
		++reported;
	}
	return reported ? kTriangleFaceContact : kTriangleOutOfReach;
}
}  // namespace caliber
