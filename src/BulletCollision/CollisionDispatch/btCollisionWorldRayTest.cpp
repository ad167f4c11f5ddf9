// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <cstring>
#include <typeinfo>

#include "BulletCollision/BroadphaseCollision/QuantizedBvhCast.h"
#include "BulletCollision/BroadphaseCollision/btDbvt.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/BvhMeshCast.h"
#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btCompoundShape.h"
#include "BulletCollision/CollisionShapes/btConcaveShape.h"
#include "BulletCollision/CollisionShapes/btConvexPolyhedron.h"
#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h"
#include "BulletCollision/CollisionShapes/btPolyhedralConvexShape.h"
#include "BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btStaticPlaneShape.h"
#include "BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h"
#include "BulletCollision/CollisionShapes/btMeshTriangleAccess.h"
#include "BulletCollision/NarrowPhaseCollision/TriangleRayTest.h"
#include "BulletCollision/NarrowPhaseCollision/btConvexCastHelpers.h"
#include "BulletCollision/NarrowPhaseCollision/btRaycastCallback.h"
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"
#include "LinearMath/btQuickprof.h"

// btCollisionWorld::rayTest and the per-object ray tests: the broadphase visits the objects whose boxes
// the ray crosses, and each object's shape is tested by the method that suits it.

namespace
{
typedef btCollisionWorld::RayResultCallback RayResultCallback;
typedef btCollisionWorld::LocalRayResult LocalRayResult;
typedef btCollisionWorld::LocalShapeInfo LocalShapeInfo;

// Hands the hits of a triangle ray test (shape frame) to the user's callback, with the normal in world
// space and the part and triangle in LocalShapeInfo. scaleInverse maps normals from the triangles' frame to
// the shape's frame (1 except for scaled meshes, whose triangles are tested unscaled).
class BridgeTriangleRaycastCallback : public btTriangleRaycastCallback
{
public:
	BridgeTriangleRaycastCallback(const btVector3& from, const btVector3& to, RayResultCallback& resultCallback,
	                              const btCollisionObject* collisionObject, const btTransform& colObjWorldTransform,
	                              const btVector3& normalScale)
	    : btTriangleRaycastCallback(from, to, resultCallback.m_flags),
	      m_resultCallback(resultCallback),
	      m_collisionObject(collisionObject),
	      m_colObjWorldTransform(colObjWorldTransform),
	      m_normalScale(normalScale)
	{
		m_hitFraction = resultCallback.m_closestHitFraction;
	}

	btScalar reportHit(const btVector3& hitNormalLocal, btScalar hitFraction, int partId, int triangleIndex) override
	{
		LocalShapeInfo shapeInfo;
		shapeInfo.m_shapePart = partId;
		shapeInfo.m_triangleIndex = triangleIndex;
		btVector3 normalInShape = hitNormalLocal * m_normalScale;
		const btScalar length2 = normalInShape.length2();
		if (length2 > btScalar(0)) normalInShape /= btSqrt(length2);
		LocalRayResult rayResult(m_collisionObject, &shapeInfo, m_colObjWorldTransform.getBasis() * normalInShape,
		                         hitFraction);
		return m_resultCallback.addSingleResult(rayResult, true);
	}

private:
	RayResultCallback& m_resultCallback;
	const btCollisionObject* m_collisionObject;
	const btTransform& m_colObjWorldTransform;
	btVector3 m_normalScale;
};

// Passes hits of one compound child to the user's callback, naming the child in LocalShapeInfo when the
// child's own test did not (convex children), and keeps the closest-hit bound in step with the user's.
class CompoundChildRayCallback : public RayResultCallback
{
public:
	CompoundChildRayCallback(int childIndex, RayResultCallback& userCallback)
	    : m_userCallback(userCallback), m_childIndex(childIndex)
	{
		m_closestHitFraction = userCallback.m_closestHitFraction;
		m_collisionFilterGroup = userCallback.m_collisionFilterGroup;
		m_collisionFilterMask = userCallback.m_collisionFilterMask;
		m_flags = userCallback.m_flags;
	}

	bool needsCollision(btBroadphaseProxy* proxy0) const override { return m_userCallback.needsCollision(proxy0); }

	btScalar addSingleResult(LocalRayResult& rayResult, bool normalInWorldSpace) override
	{
		LocalShapeInfo shapeInfo;
		shapeInfo.m_shapePart = -1;
		shapeInfo.m_triangleIndex = m_childIndex;
		if (!rayResult.m_localShapeInfo) rayResult.m_localShapeInfo = &shapeInfo;
		const btScalar bound = m_userCallback.addSingleResult(rayResult, normalInWorldSpace);
		m_collisionObject = m_userCallback.m_collisionObject;
		m_closestHitFraction = m_userCallback.m_closestHitFraction;
		return bound;
	}

private:
	RayResultCallback& m_userCallback;
	int m_childIndex;
};

// Ray test of one compound child (a leaf of the compound's child tree, or a child by index).
struct CompoundRayTester : btDbvt::ICollide
{
	CompoundRayTester(const btCollisionObjectWrapper* compoundWrap, const btCompoundShape* compound,
	                  const btTransform& rayFromTrans, const btTransform& rayToTrans, RayResultCallback& resultCallback)
	    : m_compoundWrap(compoundWrap),
	      m_compound(compound),
	      m_rayFromTrans(rayFromTrans),
	      m_rayToTrans(rayToTrans),
	      m_resultCallback(resultCallback)
	{
	}

	void processChild(int childIndex)
	{
		if (m_resultCallback.m_closestHitFraction <= btScalar(0)) return;
		const btTransform childWorldTransform =
		    m_compoundWrap->getWorldTransform() * m_compound->getChildTransform(childIndex);
		btCollisionObjectWrapper childWrap(m_compoundWrap, m_compound->getChildShape(childIndex),
		                                   m_compoundWrap->getCollisionObject(), childWorldTransform, -1, childIndex);
		CompoundChildRayCallback childCallback(childIndex, m_resultCallback);
		btCollisionWorld::rayTestSingleInternal(m_rayFromTrans, m_rayToTrans, &childWrap, childCallback);
	}

	void Process(const btDbvtNode* leaf) override { processChild(leaf->dataAsInt); }

	const btCollisionObjectWrapper* m_compoundWrap;
	const btCompoundShape* m_compound;
	const btTransform& m_rayFromTrans;
	const btTransform& m_rayToTrans;
	RayResultCallback& m_resultCallback;
};

// A plane is infinite: intersect it directly instead of building triangles around the ray. Same rules as
// the triangle ray test: a hit needs a strict sign change, the normal faces the ray origin unless
// kF_KeepUnflippedNormal, and kF_FilterBackfaces skips rays that start behind the plane.
void rayTestPlane(const btVector3& fromLocal, const btVector3& toLocal, const btStaticPlaneShape* plane,
                  const btCollisionObjectWrapper* wrap, RayResultCallback& resultCallback)
{
	const btVector3& normal = plane->getPlaneNormal();
	const btScalar distFrom = normal.dot(fromLocal) - plane->getPlaneConstant();
	const btScalar distTo = normal.dot(toLocal) - plane->getPlaneConstant();
	if (!(distFrom * distTo < btScalar(0))) return;
	if ((resultCallback.m_flags & btTriangleRaycastCallback::kF_FilterBackfaces) && distFrom < btScalar(0)) return;
	const btScalar fraction = distFrom / (distFrom - distTo);
	if (!(fraction < resultCallback.m_closestHitFraction)) return;
	const bool keepNormal = (resultCallback.m_flags & btTriangleRaycastCallback::kF_KeepUnflippedNormal) != 0;
	const btVector3 normalLocal = (keepNormal || distFrom > btScalar(0)) ? normal : -normal;
	LocalShapeInfo shapeInfo;
	shapeInfo.m_shapePart = -1;
	shapeInfo.m_triangleIndex = -1;
	LocalRayResult rayResult(wrap->getCollisionObject(), &shapeInfo, wrap->getWorldTransform().getBasis() * normalLocal,
	                         fraction);
	resultCallback.addSingleResult(rayResult, true);
}

void reportConvexHit(const btCollisionObjectWrapper* wrap, const btVector3& normalWorld, btScalar fraction,
                     RayResultCallback& resultCallback)
{
	if (!(fraction < resultCallback.m_closestHitFraction)) return;
	LocalRayResult rayResult(wrap->getCollisionObject(), 0, normalWorld, fraction);
	resultCallback.addSingleResult(rayResult, true);
}

// Closed-form sphere test. A start inside the sphere is no hit (as in Bullet: rays leave the shapes they
// start in); a start on its surface that heads in hits at 0.
void rayTestSphere(const btVector3& from, const btVector3& to, const btSphereShape* sphere,
                   const btCollisionObjectWrapper* wrap, RayResultCallback& resultCallback)
{
	const btVector3 center = wrap->getWorldTransform().getOrigin();
	const btScalar radius = sphere->getRadius();
	const btVector3 direction = to - from;
	const btVector3 offset = from - center;
	const btScalar startGap = offset.dot(offset) - radius * radius;
	if (startGap < btScalar(0)) return;
	const btScalar a = direction.dot(direction);
	const btScalar b = offset.dot(direction);
	if (!(a > btScalar(0)) || b >= btScalar(0)) return;  // no motion, or moving away
	const btScalar discriminant = b * b - a * startGap;
	if (discriminant < btScalar(0)) return;
	// t = (-b - sqrt(disc)) / a written without the cancellation of two close numbers.
	const btScalar fraction = startGap / (-b + btSqrt(discriminant));
	if (fraction > btScalar(1)) return;
	const btVector3 normal = (offset + direction * fraction) / radius;
	reportConvexHit(wrap, normal.normalized(), fraction, resultCallback);
}

// Closed-form box test (slabs in the box frame) against the box's outer faces, which is the box Bullet's
// default ray test sees. The ray hits where it enters the box: a start inside is no hit (as in Bullet), a
// start on a face that heads in hits at 0.
void rayTestBox(const btVector3& from, const btVector3& to, const btBoxShape* box, const btCollisionObjectWrapper* wrap,
                RayResultCallback& resultCallback)
{
	const btTransform& worldTransform = wrap->getWorldTransform();
	const btVector3 start = worldTransform.invXform(from);
	const btVector3 direction = worldTransform.invXform(to) - start;
	const btVector3 halfExtents = box->getHalfExtentsWithMargin();
	btScalar enter = btScalar(0), exit = btScalar(1);
	int enterAxis = -1;
	for (int axis = 0; axis < 3; axis++)
	{
		const btScalar half = halfExtents[axis];
		if (direction[axis] == btScalar(0))
		{
			if (start[axis] < -half || start[axis] > half) return;
			continue;
		}
		const btScalar inverse = btScalar(1) / direction[axis];
		btScalar tNear = (-half - start[axis]) * inverse;
		btScalar tFar = (half - start[axis]) * inverse;
		if (tNear > tFar) btSwap(tNear, tFar);
		// tNear >= 0 once the start is outside this slab or on its entry face.
		if (tNear > enter || (enterAxis < 0 && tNear >= enter))
		{
			enter = tNear;
			enterAxis = axis;
		}
		exit = btMin(exit, tFar);
		if (enter > exit) return;
	}
	if (enterAxis < 0) return;  // starts inside: the ray never enters the box
	btVector3 normalLocal(0, 0, 0);
	normalLocal[enterAxis] = direction[enterAxis] > btScalar(0) ? btScalar(-1) : btScalar(1);
	reportConvexHit(wrap, worldTransform.getBasis() * normalLocal, btMax(enter, btScalar(0)), resultCallback);
}

// A start more than the margin behind every face plane of a hull's polyhedral features
// (initializePolyhedralFeatures, with or without its margin shift; the features the contact clipping
// trusts) is inside the shape: the ray cannot hit it (Bullet's rule, see rayTestConvex). A few dot
// products instead of the cast's loop, which needs a full simplex (four or more support scans) to show
// that a start is inside. Shapes without features, and starts near the surface, go to the cast.
const btConvexPolyhedron* polyhedralFeatures(const btConvexShape* shape)
{
	if (!shape->isPolyhedral()) return 0;
	const btConvexPolyhedron* polyhedron = static_cast<const btPolyhedralConvexShape*>(shape)->getConvexPolyhedron();
	return polyhedron && polyhedron->m_faces.size() >= 4 ? polyhedron : 0;
}

bool startsInsidePolyhedron(const btConvexShape* shape, const btVector3& startLocal)
{
	const btConvexPolyhedron* polyhedron = polyhedralFeatures(shape);
	if (!polyhedron) return false;
	const btScalar depth = -shape->getMargin();
	for (int i = 0; i < polyhedron->m_faces.size(); ++i)
	{
		const btScalar* plane = polyhedron->m_faces[i].m_plane;
		if (!(startLocal.x() * plane[0] + startLocal.y() * plane[1] + startLocal.z() * plane[2] + plane[3] < depth))
			return false;
	}
	return true;
}

// True when the origin lies at least clearance inside the plane through p0, p1, p2 on the side of
// opposite (points relative to the ray's start); false for a flat (or NaN) face.
bool originInsideFace(const btVector3& p0, const btVector3& p1, const btVector3& p2, const btVector3& opposite,
                      btScalar clearance)
{
	btVector3 normal = (p1 - p0).cross(p2 - p0);
	const btScalar side = normal.dot(opposite - p0);
	if (!(side != btScalar(0))) return false;
	if (side > btScalar(0)) normal = -normal;  // outward
	// The origin's distance inside: normal . (p0 - 0) / |normal|.
	return normal.dot(p0) >= clearance * normal.length();
}

// The faces of a tetrahedron y[0..3]: three corners, then the opposite corner.
const int kTetrahedronFaces[4][4] = {{0, 1, 2, 3}, {0, 3, 1, 2}, {0, 2, 3, 1}, {1, 3, 2, 0}};

// The certificate of startsInsideCore, checked on its own whatever found the points: the origin is at least
// clearance inside every face of the tetrahedron y[0..3] (returns -1), or inside all but the one face
// returned, where extra (when given) is beyond that face and the origin is at least clearance inside the
// other three faces of the tetrahedron extra makes with it. In the second case a ball of radius clearance
// about the origin lies in the union of the two tetrahedra (its part on the first's side of the shared face
// in the first, the rest in the second). Returns -2 when neither holds.
int tetrahedraContainOrigin(const btVector3* y, btScalar clearance, const btVector3* extra)
{
	int failed = -1;
	for (int f = 0; f < 4; ++f)
	{
		const int* c = kTetrahedronFaces[f];
		if (originInsideFace(y[c[0]], y[c[1]], y[c[2]], y[c[3]], clearance)) continue;
		if (failed >= 0) return -2;
		failed = f;
	}
	if (failed < 0) return -1;
	if (!extra) return failed;
	const int* c = kTetrahedronFaces[failed];
	const btVector3& e = *extra;
	// extra beyond the shared face: on the other side of it from the first tetrahedron's fourth corner.
	btVector3 normal = (y[c[1]] - y[c[0]]).cross(y[c[2]] - y[c[0]]);
	if (!((normal.dot(e - y[c[0]]) > btScalar(0)) != (normal.dot(y[c[3]] - y[c[0]]) > btScalar(0)) &&
	      normal.dot(e - y[c[0]]) != btScalar(0)))
		return -2;
	if (originInsideFace(e, y[c[0]], y[c[1]], y[c[2]], clearance) &&
	    originInsideFace(e, y[c[1]], y[c[2]], y[c[0]], clearance) &&
	    originInsideFace(e, y[c[2]], y[c[0]], y[c[1]], clearance))
		return -1;
	return -2;
}

// The distance from the origin to a point of the segment a b (points relative to the ray's start): the point
// is formed with its weight clamped to [0, 1], so it lies on the segment whatever the rounding, and its
// length is measured.
btScalar distanceToSegment(const btVector3& a, const btVector3& b)
{
	const btVector3 ab = b - a;
	const btScalar length2 = ab.length2();
	const btScalar t = length2 > btScalar(0) ? btMax(btScalar(0), btMin(btScalar(1), -a.dot(ab) / length2)) : btScalar(0);
	return (a + ab * t).length();
}

// The distance from the origin to a point of the triangle a b c found as distanceToSegment does: the
// projection of the origin when its barycentric weights are all at least 0 (the point is then formed from
// them), else the nearest of the edges.
btScalar distanceToTriangle(const btVector3& a, const btVector3& b, const btVector3& c)
{
	const btVector3 normal = (b - a).cross(c - a);
	const btScalar normal2 = normal.length2();
	if (normal2 > btScalar(0))
	{
		const btVector3 projection = normal * (normal.dot(a) / normal2);
		const btScalar wa = (b - projection).cross(c - projection).dot(normal);
		const btScalar wb = (c - projection).cross(a - projection).dot(normal);
		const btScalar wc = (a - projection).cross(b - projection).dot(normal);
		const btScalar sum = wa + wb + wc;
		if (wa >= btScalar(0) && wb >= btScalar(0) && wc >= btScalar(0) && sum > btScalar(0))
			return ((a * wa + b * wb + c * wc) / sum).length();
	}
	return btMin(distanceToSegment(a, b), btMin(distanceToSegment(b, c), distanceToSegment(c, a)));
}

// The distance from the origin to a point of the convex hull of y[0 .. count), count 1 to 3 (an upper bound of
// the distance to the core when the points are core points).
btScalar distanceToSimplex(const btVector3* y, int count)
{
	if (count == 1) return y[0].length();
	if (count == 2) return distanceToSegment(y[0], y[1]);
	return distanceToTriangle(y[0], y[1], y[2]);
}

// The search direction from a simplex of one to three points relative to the start (y[count - 1] the
// newest) towards the origin, keeping in y only the points of the feature nearest the origin (GJK's
// containment search, with Voronoi regions judged by the signs of a few products). False when the origin
// lies on the simplex's line or plane, where no direction is left.
bool nextSearchDirection(btVector3* y, int& count, btVector3& direction)
{
	const btVector3 a = y[count - 1];
	const btVector3 toOrigin = -a;
	if (count == 1)
	{
		direction = toOrigin;
		return true;
	}
	if (count == 2)
	{
		const btVector3 ab = y[0] - a;
		if (ab.dot(toOrigin) > btScalar(0))
			direction = ab.cross(toOrigin).cross(ab);
		else
		{
			y[0] = a;
			count = 1;
			direction = toOrigin;
		}
		return direction.length2() > btScalar(0);
	}
	// A triangle: b = y[1], c = y[0].
	const btVector3 b = y[1], c = y[0];
	const btVector3 ab = b - a, ac = c - a;
	const btVector3 normal = ab.cross(ac);
	if (normal.cross(ac).dot(toOrigin) > btScalar(0))
	{
		// Beyond edge ac.
		y[1] = a;
		count = 2;
		return nextSearchDirection(y, count, direction);
	}
	if (ab.cross(normal).dot(toOrigin) > btScalar(0))
	{
		// Beyond edge ab.
		y[0] = b;
		y[1] = a;
		count = 2;
		return nextSearchDirection(y, count, direction);
	}
	const btScalar side = normal.dot(toOrigin);
	direction = side > btScalar(0) ? normal : -normal;
	return side != btScalar(0);
}

// True when the start is inside the shape (its core, the support points without margin, grown by the
// margin) by more than clearance, the rounding of the coordinates involved: then every support plane the
// cast's support mapping gives has the start more than that inside it, so the cast never advances, and it
// returns no hit (Bullet's rule, see rayTestConvex) after a full simplex (four or more support scans and as
// many of the Voronoi simplex solver's closest-point steps). Two certificates, each checked on its own
// whatever found its points: a tetrahedron of core points (or two sharing a face) with the start inside by
// clearance (tetrahedraContainOrigin), or a point of a segment or triangle of core points within the margin
// less clearance of the start (the start in the margin band, or in the core near a face). GJK's containment
// search finds them in about four support scans and a few cross products. For shapes without polyhedral
// features (startsInsidePolyhedron answers for the others); false (go to the cast) when none is found.
bool startsInsideCore(const btConvexShape* shape, const btVector3& startLocal, const btVector3& firstDirection,
                      btScalar clearance)
{
	// A core point this close to the start puts the start inside the shape (core and margin) by clearance.
	const btScalar nearEnough = shape->getMargin() - clearance;
	btVector3 y[4];
	int count = 0;
	btVector3 direction = firstDirection.fuzzyZero() ? btVector3(1, 0, 0) : firstDirection;
	for (int step = 0; step < 12; ++step)
	{
		const btVector3 support = shape->localGetSupportingVertexWithoutMargin(direction) - startLocal;
		// The core's support plane along direction does not pass the start: not inside (or not by enough).
		if (!(support.dot(direction) > btScalar(0)))
			return count > 0 && distanceToSimplex(y, count) <= nearEnough;
		y[count++] = support;
		if (count == 4)
		{
			const int face = tetrahedraContainOrigin(y, clearance, 0);
			if (face == -1) return true;
			if (face >= 0)
			{
				const int* c = kTetrahedronFaces[face];
				btVector3 outward = (y[c[1]] - y[c[0]]).cross(y[c[2]] - y[c[0]]);
				if (outward.dot(y[c[3]] - y[c[0]]) > btScalar(0)) outward = -outward;
				// The origin is inside but too close to this one face (it lies on a plane of symmetry of the
				// shape, say): the tetrahedron on the face's other side, up to the support point beyond it, may
				// cover the rest of the ball. (Outside the face: GJK's next step below.)
				if (!(outward.dot(-y[c[0]]) > btScalar(0)))
				{
					if (distanceToTriangle(y[c[0]], y[c[1]], y[c[2]]) <= nearEnough) return true;
					const btVector3 beyond = shape->localGetSupportingVertexWithoutMargin(outward) - startLocal;
					return tetrahedraContainOrigin(y, clearance, &beyond) == -1;
				}
			}
			// Keep the face (with the newest point) the origin lies beyond, and search along its normal.
			const btVector3 a = y[3];
			const int others[3][2] = {{2, 1}, {1, 0}, {0, 2}};
			bool outside = false;
			for (const int* o : others)
			{
				const btVector3 b = y[o[0]], c = y[o[1]];
				const btVector3 d = y[3 - o[0] - o[1]];  // the face's opposite point (indices 0, 1, 2 sum to 3)
				btVector3 normal = (b - a).cross(c - a);
				if (normal.dot(d - a) > btScalar(0)) normal = -normal;
				if (normal.dot(-a) > btScalar(0))
				{
					y[0] = c;
					y[1] = b;
					y[2] = a;
					count = 3;
					direction = normal;
					outside = true;
					break;
				}
			}
			// Inside all faces but too close to several: the nearest of them may still be near enough.
			if (!outside)
			{
				for (const int* f : kTetrahedronFaces)
					if (distanceToTriangle(y[f[0]], y[f[1]], y[f[2]]) <= nearEnough) return true;
				return false;
			}
			continue;
		}
		// No direction left: the origin lies on the simplex (up to rounding), which measures that.
		if (!nextSearchDirection(y, count, direction)) return distanceToSimplex(y, count) <= nearEnough;
	}
	return false;
}

// The distance from a convex shape (margin included) within which the ray casts below may report a hit:
// the subsimplex cast stops once its point is within sqrt(m_subSimplexCastEpsilon) of the shape, the GJK
// cast once the distance is below kCastDistanceTolerance, and a cast out of iterations accepts
// kCastExhaustedAcceptDistance. Four times the largest of them leaves room for GJK's own distance error.
btScalar convexCastReach()
{
	const btConvexCast::CastResult defaults;
	btScalar reach = btSqrt(btMax(defaults.m_subSimplexCastEpsilon, btScalar(0)));
	reach = btMax(reach, caliber::kCastDistanceTolerance);
	reach = btMax(reach, caliber::kCastExhaustedAcceptDistance);
	return btScalar(4) * reach;
}

// The shapes whose getAabb is a cheap bound of the shape with its margin (the cached boxes of hulls, point
// clouds, convex meshes and multi-spheres, and the closed forms of capsules and cylinders): their ray tests
// start with the rejects below; other shapes always go to the cast.
bool hasCheapLocalBox(const btConvexShape* shape)
{
	switch (shape->getShapeType())
	{
		case CONVEX_HULL_SHAPE_PROXYTYPE:
		case CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE:
		case CONVEX_TRIANGLEMESH_SHAPE_PROXYTYPE:
		case MULTI_SPHERE_SHAPE_PROXYTYPE:
		case CAPSULE_SHAPE_PROXYTYPE:
		case CYLINDER_SHAPE_PROXYTYPE:
			return true;
		default:
			return false;
	}
}

// The ray in a shape's frame, with the shape's local box (margin included) and the largest coordinate
// involved (the rays' ends and the box, in the shape's frame).
struct LocalConvexRay
{
	btVector3 start;
	btVector3 direction;
	btVector3 boxMin;
	btVector3 boxMax;
	btScalar scale;
};

LocalConvexRay localConvexRay(const btConvexShape* shape, const btTransform& shapeTransform, const btVector3& from,
                              const btVector3& to)
{
	LocalConvexRay ray;
	btTransform identity;
	identity.setIdentity();
	shape->getAabb(identity, ray.boxMin, ray.boxMax);
	ray.start = shapeTransform.invXform(from);
	ray.direction = shapeTransform.invXform(to) - ray.start;
	ray.scale = btScalar(0);
	for (int axis = 0; axis < 3; ++axis)
		ray.scale = btMax(ray.scale, btMax(btMax(btFabs(ray.start[axis]), btFabs(ray.start[axis] + ray.direction[axis])),
		                                   btMax(btFabs(ray.boxMin[axis]), btFabs(ray.boxMax[axis]))));
	return ray;
}

// False when the cast of the segment from -> to against the shape cannot report a hit below maxFraction:
// the segment misses the shape's local AABB grown by convexCastReach() and by the rounding of the
// coordinates involved, or enters it only at or beyond maxFraction (the cast's point lies within the reach
// of the shape wherever it hits, so a hit lies inside the grown box), or a plane through the segment's line
// keeps the whole shape farther than that. A few dozen instructions and one support scan instead of a
// cast, which needs several support scans to show a miss. Only for the shapes
// hasCheapLocalBox accepts.
bool castMayHitConvex(const btConvexShape* shape, const LocalConvexRay& ray, btScalar maxFraction)
{
	static const btScalar reach = convexCastReach();
	const btVector3& start = ray.start;
	const btVector3& direction = ray.direction;
	const btVector3& boxMin = ray.boxMin;
	const btVector3& boxMax = ray.boxMax;
	const btScalar scale = ray.scale;
	const btScalar grow = reach + btScalar(64) * SIMD_EPSILON * scale;
	btScalar enter = btScalar(0), exit = btMin(maxFraction, btScalar(1));
	for (int axis = 0; axis < 3; ++axis)
	{
		const btScalar lo = boxMin[axis] - grow, hi = boxMax[axis] + grow;
		if (direction[axis] == btScalar(0))
		{
			if (start[axis] < lo || start[axis] > hi) return false;
			continue;
		}
		const btScalar inverse = btScalar(1) / direction[axis];
		btScalar tNear = (lo - start[axis]) * inverse;
		btScalar tFar = (hi - start[axis]) * inverse;
		if (tNear > tFar) btSwap(tNear, tFar);
		enter = btMax(enter, tNear);
		exit = btMin(exit, tFar);
		// Not "enter >= exit": a hit at exactly maxFraction would not be reported either, but a box the
		// segment only touches must not be skipped for rounding's sake.
		if (enter > exit) return false;
	}
	// The plane through the ray's line facing the shape's box centre: when the whole shape (its support
	// against the plane's normal, margin included, as the casts compute it) lies more than the reach beyond
	// it, every point of the ray is farther than the reach from the shape. One support scan instead of the
	// cast's several, for rays that cross the box but pass beside the shape.
	const btScalar length2 = direction.length2();
	if (!(length2 > btScalar(0))) return true;
	const btVector3 toCentre = (boxMin + boxMax) * btScalar(0.5) - start;
	const btVector3 across = toCentre - direction * (toCentre.dot(direction) / length2);
	const btScalar across2 = across.length2();
	if (!(across2 > SIMD_EPSILON * SIMD_EPSILON * scale * scale)) return true;
	const btVector3 normal = across / btSqrt(across2);
	const btVector3 nearest = shape->localGetSupportingVertexWithoutMargin(-normal) - normal * shape->getMargin();
	return !(normal.dot(nearest - start) > grow);
}

// startsInsideCore is tried on the shapes without polyhedral features whose core is a solid (not the
// segment or points of capsules and multi-spheres, whose margins are their radii), for starts inside their
// local box, where a start inside the shape can be.
bool mayCertifyStartInsideCore(const btConvexShape* shape, const LocalConvexRay& ray)
{
	switch (shape->getShapeType())
	{
		case CONVEX_HULL_SHAPE_PROXYTYPE:
		case CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE:
		case CONVEX_TRIANGLEMESH_SHAPE_PROXYTYPE:
		case CYLINDER_SHAPE_PROXYTYPE:
			break;
		default:
			return false;
	}
	for (int axis = 0; axis < 3; ++axis)
		if (!(ray.start[axis] > ray.boxMin[axis] && ray.start[axis] < ray.boxMax[axis])) return false;
	return !polyhedralFeatures(shape);
}

// How far inside the core's tetrahedron the start must be for startsInsideCore: 64 ulps of the largest
// coordinate the cast's support planes are computed from (the start and the shape's origin in the world,
// and the start and the box in the shape's frame), far above the few roundings of one support plane. The
// margin between the core and the surface is more room on top.
btScalar startInsideClearance(const LocalConvexRay& ray, const btVector3& fromWorld, const btVector3& originWorld)
{
	btScalar scale = btScalar(0);
	for (int axis = 0; axis < 3; ++axis)
		scale = btMax(scale, btMax(btMax(btFabs(fromWorld[axis]), btFabs(originWorld[axis])),
		                           btMax(btFabs(ray.start[axis]), btMax(btFabs(ray.boxMin[axis]), btFabs(ray.boxMax[axis])))));
	return btScalar(64) * SIMD_EPSILON * scale;
}

void rayTestConvex(const btTransform& rayFromTrans, const btTransform& rayToTrans, const btConvexShape* convexShape,
                   const btCollisionObjectWrapper* wrap, RayResultCallback& resultCallback)
{
	// Spheres and boxes, the commonest ray targets, are intersected in closed form: exact and several times
	// faster than a cast. kF_UseGjkConvexCastRaytest asks for the cast explicitly.
	if (!(resultCallback.m_flags & btTriangleRaycastCallback::kF_UseGjkConvexCastRaytest))
	{
		if (convexShape->getShapeType() == SPHERE_SHAPE_PROXYTYPE)
		{
			rayTestSphere(rayFromTrans.getOrigin(), rayToTrans.getOrigin(),
			              static_cast<const btSphereShape*>(convexShape), wrap, resultCallback);
			return;
		}
		if (convexShape->getShapeType() == BOX_SHAPE_PROXYTYPE)
		{
			rayTestBox(rayFromTrans.getOrigin(), rayToTrans.getOrigin(), static_cast<const btBoxShape*>(convexShape),
			           wrap, resultCallback);
			return;
		}
	}
	const btTransform& shapeTransform = wrap->getWorldTransform();
	if (hasCheapLocalBox(convexShape))
	{
		const LocalConvexRay local =
		    localConvexRay(convexShape, shapeTransform, rayFromTrans.getOrigin(), rayToTrans.getOrigin());
		if (!castMayHitConvex(convexShape, local, resultCallback.m_closestHitFraction)) return;
		if (startsInsidePolyhedron(convexShape, local.start)) return;
		if (mayCertifyStartInsideCore(convexShape, local) &&
		    startsInsideCore(convexShape, local.start, local.start - (local.boxMin + local.boxMax) * btScalar(0.5),
		                     startInsideClearance(local, rayFromTrans.getOrigin(), shapeTransform.getOrigin())))
			return;
	}
	else if (startsInsidePolyhedron(convexShape, shapeTransform.invXform(rayFromTrans.getOrigin())))
		return;
	// The ray is a point (a sphere of radius 0 and no margin) cast against the shape.
	btSphereShape point(btScalar(0));
	point.setMargin(btScalar(0));
	btVoronoiSimplexSolver simplexSolver;
	btConvexCast::CastResult castResult;
	bool hit;
	// As in Bullet, a ray that starts inside the shape does not hit it (the casts' kMiss), which also spares
	// the depth query a start-in-contact cast would make for its normal.
	if (resultCallback.m_flags & btTriangleRaycastCallback::kF_UseGjkConvexCastRaytest)
		hit = caliber::gjkCast(&point, convexShape, &simplexSolver, rayFromTrans, rayToTrans, shapeTransform,
		                       shapeTransform, castResult, caliber::StartInContact::kMiss);
	else
		hit = caliber::subsimplexCast(&point, convexShape, &simplexSolver, rayFromTrans, rayToTrans, shapeTransform,
		                              shapeTransform, castResult, caliber::StartInContact::kMiss);
	// A zero normal means the cast found no direction; such a hit is dropped.
	if (!hit || !(castResult.m_normal.length2() > btScalar(1e-4))) return;
	if (!(castResult.m_fraction < resultCallback.m_closestHitFraction)) return;
	LocalRayResult rayResult(wrap->getCollisionObject(), 0, castResult.m_normal.normalized(), castResult.m_fraction);
	resultCallback.addSingleResult(rayResult, true);
}

// The leaves the ray's tree walk reaches, read into triangles for the triangle ray test. A
// btTriangleIndexVertexArray itself (not a subclass, which may lock) is read straight from its
// btIndexedMesh parts when a part has 32- or 16-bit indices and btScalar vertices: no virtual lock and unlock
// per walk and no type switch per vertex. Other interfaces and layouts go through caliber::ReadOnlyMeshPart
// (locked while consecutive leaves use the part). Either way the triangles are the same values (vertex times
// the interface's scaling) with the same checks: an index out of range or a vertex that is not finite
// asserts and skips the triangle.
class RayMeshNodeCallback : public btNodeOverlapCallback
{
public:
	RayMeshNodeCallback(const btStridingMeshInterface& mesh, BridgeTriangleRaycastCallback& callback)
	    : m_mesh(mesh),
	      m_indexedMeshes(typeid(mesh) == typeid(btTriangleIndexVertexArray)
	                          ? &static_cast<const btTriangleIndexVertexArray&>(mesh).getIndexedMeshArray()
	                          : 0),
	      m_scaling(mesh.getScaling()),
	      m_callback(callback),
	      m_rayFinite(caliber::isFinite(callback.m_from) && caliber::isFinite(callback.m_to)),
	      m_selectedPart(-1),
	      m_direct(0)
	{
	}

	void processNode(int partId, int triangleIndex) override
	{
		btVector3 triangle[3];
		if (partId != m_selectedPart) selectPart(partId);
		bool read;
		if (!m_direct)
			read = m_part.readTriangle(triangleIndex, m_scaling, triangle);
		else if (m_direct->m_indexType == PHY_SHORT)
			read = readDirect<unsigned short>(triangleIndex, triangle);
		else
			read = readDirect<unsigned int>(triangleIndex, triangle);
		if (!read) return;
		// Both reads check the vertices; with the ray checked once per walk, the triangle test skips its own
		// checks (the same test processTriangle runs after them).
		if (m_rayFinite)
			caliber::testRayAgainstFiniteTriangle(m_callback, triangle, partId, triangleIndex);
		else
			m_callback.btTriangleRaycastCallback::processTriangle(triangle, partId, triangleIndex);
	}

private:
	// A part is read directly when it has this layout and is readable as ReadOnlyMeshPart::acquire judges it.
	static bool directLayout(const btIndexedMesh& part)
	{
#ifdef BT_USE_DOUBLE_PRECISION
		const PHY_ScalarType scalarType = PHY_DOUBLE;
#else
		const PHY_ScalarType scalarType = PHY_FLOAT;
#endif
		const int indexSize = part.m_indexType == PHY_INTEGER ? int(sizeof(unsigned int))
		                      : part.m_indexType == PHY_SHORT ? int(sizeof(unsigned short))
		                                                      : 0;
		return part.m_vertexType == scalarType && indexSize > 0 && part.m_numTriangles > 0 && part.m_vertexBase != 0 &&
		       part.m_triangleIndexBase != 0 && part.m_numVertices >= 0 &&
		       part.m_vertexStride >= int(3 * sizeof(btScalar)) && part.m_triangleIndexStride >= 3 * indexSize;
	}

	void selectPart(int partId)
	{
		m_selectedPart = partId;
		m_direct = 0;
		if (m_indexedMeshes && partId >= 0 && partId < m_indexedMeshes->size() &&
		    directLayout((*m_indexedMeshes)[partId]))
		{
			m_direct = &(*m_indexedMeshes)[partId];
			m_part.release();
			return;
		}
		if (m_part.part() != partId) m_part.acquire(&m_mesh, partId);
	}

	template <class Index>
	bool readDirect(int triangleIndex, btVector3* out) const
	{
		const btIndexedMesh& part = *m_direct;
		if (triangleIndex < 0 || triangleIndex >= part.m_numTriangles)
		{
			btAssert(triangleIndex >= 0 && triangleIndex < part.m_numTriangles && "mesh triangle out of range");
			return false;
		}
		Index indices[3];
		std::memcpy(indices, part.m_triangleIndexBase + size_t(triangleIndex) * size_t(part.m_triangleIndexStride),
		            sizeof(indices));
		for (int k = 0; k < 3; ++k)
		{
			if (indices[k] >= unsigned(part.m_numVertices))
			{
				btAssert(indices[k] < unsigned(part.m_numVertices) && "mesh index out of range");
				return false;
			}
			btScalar v[3];
			std::memcpy(v, part.m_vertexBase + size_t(indices[k]) * size_t(part.m_vertexStride), sizeof(v));
			out[k] = btVector3(v[0], v[1], v[2]) * m_scaling;
			if (!caliber::isFinite(out[k]))
			{
				btAssert(caliber::isFinite(out[k]) && "mesh vertex not finite");
				return false;
			}
		}
		return true;
	}

	const btStridingMeshInterface& m_mesh;
	const IndexedMeshArray* m_indexedMeshes;  // the parts, when the interface is a btTriangleIndexVertexArray
	const btVector3 m_scaling;
	BridgeTriangleRaycastCallback& m_callback;
	const bool m_rayFinite;         // the callback's m_from and m_to are finite
	int m_selectedPart;             // the part selectPart last chose, or -1
	const btIndexedMesh* m_direct;  // that part when it is read directly, else null (m_part holds it)
	caliber::ReadOnlyMeshPart m_part;
};

// A ray against a BVH mesh: the tree walk skips boxes beyond the closest hit so far (the callback's
// m_hitFraction, which its reportHit lowers), which leaves the hits found unchanged. The walk of
// caliber::castAgainstBvhMesh, with the leaves read by RayMeshNodeCallback.
void castRayAgainstBvhMesh(btBvhTriangleMeshShape& mesh, BridgeTriangleRaycastCallback& callback, const btVector3& from,
                           const btVector3& to)
{
	const btStridingMeshInterface* meshInterface = mesh.getMeshInterface();
	const btOptimizedBvh* bvh = mesh.getOptimizedBvh();
	const btVector3 zero(0, 0, 0);
	if (!meshInterface || !bvh)
	{
		caliber::castAgainstBvhMesh(mesh, &callback, from, to, zero, zero, &callback.m_hitFraction);
		return;
	}
	RayMeshNodeCallback nodes(*meshInterface, callback);
	caliber::reportBoxCastOverlappingNodes(*bvh, &nodes, from, to, zero, zero, &callback.m_hitFraction);
}

// Whether a triangle-mesh shape's getName() is btBvhTriangleMeshShape's. The linker merges equal string
// literals, so the name's pointer usually settles it without comparing the characters; the comparison is the
// fallback (a build that does not merge them, or a user subclass that returns its own copy).
bool namedBvhTriangleMesh(const char* name)
{
	static const char* const kBvhMeshName = "BVHTRIANGLEMESH";
	return name == kBvhMeshName || (name && std::strcmp(name, kBvhMeshName) == 0);
}

void rayTestConcave(const btTransform& rayFromTrans, const btTransform& rayToTrans, const btConcaveShape* concave,
                    const btCollisionObjectWrapper* wrap, RayResultCallback& resultCallback)
{
	const btTransform& worldTransform = wrap->getWorldTransform();
	const btVector3 fromLocal = worldTransform.invXform(rayFromTrans.getOrigin());
	const btVector3 toLocal = worldTransform.invXform(rayToTrans.getOrigin());
	const btCollisionObject* object = wrap->getCollisionObject();
	const btVector3 unitScale(btScalar(1), btScalar(1), btScalar(1));
	const int shapeType = concave->getShapeType();

	if (shapeType == STATIC_PLANE_PROXYTYPE)
	{
		rayTestPlane(fromLocal, toLocal, static_cast<const btStaticPlaneShape*>(concave), wrap, resultCallback);
		return;
	}
	// Only btBvhTriangleMeshShape and its multimaterial subclass are known to have performRaycast
	// (btTriangleMeshShape shares the type).
	if ((shapeType == TRIANGLE_MESH_SHAPE_PROXYTYPE && namedBvhTriangleMesh(concave->getName())) ||
	    shapeType == MULTIMATERIAL_TRIANGLE_MESH_PROXYTYPE)
	{
		btBvhTriangleMeshShape* mesh =
		    const_cast<btBvhTriangleMeshShape*>(static_cast<const btBvhTriangleMeshShape*>(concave));
		BridgeTriangleRaycastCallback callback(fromLocal, toLocal, resultCallback, object, worldTransform, unitScale);
		castRayAgainstBvhMesh(*mesh, callback, fromLocal, toLocal);
		return;
	}
	if (shapeType == SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE)
	{
		const btScaledBvhTriangleMeshShape* scaled = static_cast<const btScaledBvhTriangleMeshShape*>(concave);
		const btVector3& scale = scaled->getLocalScaling();
		const bool invertible = scale.x() != btScalar(0) && scale.y() != btScalar(0) && scale.z() != btScalar(0);
		if (invertible && scaled->getChildShape())
		{
			// The segment maps to the unscaled mesh with the same fractions; normals map back by the inverse
			// transpose of the scaling, i.e. they are divided by it.
			const btVector3 inverseScale(btScalar(1) / scale.x(), btScalar(1) / scale.y(), btScalar(1) / scale.z());
			const btVector3 fromChild = fromLocal * inverseScale;
			const btVector3 toChild = toLocal * inverseScale;
			BridgeTriangleRaycastCallback callback(fromChild, toChild, resultCallback, object, worldTransform,
			                                       inverseScale);
			castRayAgainstBvhMesh(*const_cast<btBvhTriangleMeshShape*>(scaled->getChildShape()), callback, fromChild,
			                      toChild);
			return;
		}
	}
	if (shapeType == TERRAIN_SHAPE_PROXYTYPE && std::strcmp(concave->getName(), "HEIGHTFIELD") == 0)
	{
		const btHeightfieldTerrainShape* terrain = static_cast<const btHeightfieldTerrainShape*>(concave);
		BridgeTriangleRaycastCallback callback(fromLocal, toLocal, resultCallback, object, worldTransform, unitScale);
		terrain->performRaycast(&callback, fromLocal, toLocal);
		return;
	}

	// Any other concave shape: the triangles inside the ray's box.
	BridgeTriangleRaycastCallback callback(fromLocal, toLocal, resultCallback, object, worldTransform, unitScale);
	btVector3 boxMin = fromLocal, boxMax = fromLocal;
	boxMin.setMin(toLocal);
	boxMax.setMax(toLocal);
	concave->processAllTriangles(&callback, boxMin, boxMax);
}

// Visited by the broadphase for each object whose box the ray crosses.
struct WorldRayCallback : public btBroadphaseRayCallback
{
	WorldRayCallback(const btVector3& rayFromWorld, const btVector3& rayToWorld, RayResultCallback& resultCallback)
	    : m_resultCallback(resultCallback)
	{
		m_rayFromTrans.setIdentity();
		m_rayFromTrans.setOrigin(rayFromWorld);
		m_rayToTrans.setIdentity();
		m_rayToTrans.setOrigin(rayToWorld);
		const btVector3 direction = rayToWorld - rayFromWorld;
		for (int axis = 0; axis < 3; axis++)
		{
			m_rayDirectionInverse[axis] =
			    direction[axis] == btScalar(0) ? btScalar(BT_LARGE_FLOAT) : btScalar(1) / direction[axis];
			m_signs[axis] = m_rayDirectionInverse[axis] < btScalar(0) ? 1u : 0u;
		}
		m_lambda_max = resultCallback.m_closestHitFraction;
	}

	bool process(const btBroadphaseProxy* proxy) override
	{
		// A hit at fraction 0 cannot be beaten.
		if (m_resultCallback.m_closestHitFraction <= btScalar(0)) return false;
		btCollisionObject* collisionObject = static_cast<btCollisionObject*>(proxy->m_clientObject);
		if (m_resultCallback.needsCollision(collisionObject->getBroadphaseHandle()))
		{
			btCollisionWorld::rayTestSingle(m_rayFromTrans, m_rayToTrans, collisionObject,
			                                collisionObject->getCollisionShape(), collisionObject->getWorldTransform(),
			                                m_resultCallback);
			// Closest-hit callbacks shrink the bound; the broadphase may then skip boxes beyond it.
			m_lambda_max = btMin(m_lambda_max, m_resultCallback.m_closestHitFraction);
		}
		return true;
	}

	btTransform m_rayFromTrans;
	btTransform m_rayToTrans;
	RayResultCallback& m_resultCallback;
};
}  // namespace

void btCollisionWorld::rayTest(const btVector3& rayFromWorld, const btVector3& rayToWorld,
                               RayResultCallback& resultCallback) const
{
	BT_PROFILE("rayTest");
	const bool finite = caliber::isFinite(rayFromWorld) && caliber::isFinite(rayToWorld);
	btAssert(finite && "btCollisionWorld::rayTest: non-finite ray");
	if (!finite || !m_broadphasePairCache) return;
	WorldRayCallback rayCallback(rayFromWorld, rayToWorld, resultCallback);
	m_broadphasePairCache->rayTest(rayFromWorld, rayToWorld, rayCallback, btVector3(0, 0, 0), btVector3(0, 0, 0));
}

void btCollisionWorld::rayTestSingle(const btTransform& rayFromTrans, const btTransform& rayToTrans,
                                     btCollisionObject* collisionObject, const btCollisionShape* collisionShape,
                                     const btTransform& colObjWorldTransform, RayResultCallback& resultCallback)
{
	btCollisionObjectWrapper wrap(0, collisionShape, collisionObject, colObjWorldTransform, -1, -1);
	rayTestSingleInternal(rayFromTrans, rayToTrans, &wrap, resultCallback);
}

void btCollisionWorld::rayTestSingleInternal(const btTransform& rayFromTrans, const btTransform& rayToTrans,
                                             const btCollisionObjectWrapper* collisionObjectWrap,
                                             RayResultCallback& resultCallback)
{
	btAssert(collisionObjectWrap && collisionObjectWrap->getCollisionShape());
	if (!collisionObjectWrap || !collisionObjectWrap->getCollisionShape()) return;
	const bool finite = caliber::isFinite(rayFromTrans.getOrigin()) && caliber::isFinite(rayToTrans.getOrigin()) &&
	                    caliber::isFinite(collisionObjectWrap->getWorldTransform());
	btAssert(finite && "btCollisionWorld::rayTestSingle: non-finite ray or object transform");
	if (!finite) return;

	const btCollisionShape* shape = collisionObjectWrap->getCollisionShape();
	if (shape->isConvex())
	{
		rayTestConvex(rayFromTrans, rayToTrans, static_cast<const btConvexShape*>(shape), collisionObjectWrap,
		              resultCallback);
	}
	else if (shape->isConcave())
	{
		rayTestConcave(rayFromTrans, rayToTrans, static_cast<const btConcaveShape*>(shape), collisionObjectWrap,
		               resultCallback);
	}
	else if (shape->isCompound())
	{
		BT_PROFILE("rayTestCompound");
		const btCompoundShape* compound = static_cast<const btCompoundShape*>(shape);
		CompoundRayTester tester(collisionObjectWrap, compound, rayFromTrans, rayToTrans, resultCallback);
		const btDbvt* tree = compound->getDynamicAabbTree();
		if (tree && tree->m_root)
		{
			const btTransform& worldTransform = collisionObjectWrap->getWorldTransform();
			btDbvt::rayTest(tree->m_root, worldTransform.invXform(rayFromTrans.getOrigin()),
			                worldTransform.invXform(rayToTrans.getOrigin()), tester);
		}
		else if (!tree)
		{
			for (int i = 0; i < compound->getNumChildShapes(); i++) tester.processChild(i);
		}
	}
	// Other shape kinds (soft bodies, fluids) are not ray-tested here.
}
