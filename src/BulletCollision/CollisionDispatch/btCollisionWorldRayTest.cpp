// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <cstring>

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
bool startsInsidePolyhedron(const btConvexShape* shape, const btVector3& startLocal)
{
	if (!shape->isPolyhedral()) return false;
	const btConvexPolyhedron* polyhedron = static_cast<const btPolyhedralConvexShape*>(shape)->getConvexPolyhedron();
	if (!polyhedron || polyhedron->m_faces.size() < 4) return false;
	const btScalar depth = -shape->getMargin();
	for (int i = 0; i < polyhedron->m_faces.size(); ++i)
	{
		const btScalar* plane = polyhedron->m_faces[i].m_plane;
		if (!(startLocal.x() * plane[0] + startLocal.y() * plane[1] + startLocal.z() * plane[2] + plane[3] < depth))
			return false;
	}
	return true;
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

// False when the cast of the segment from -> to against the shape cannot report a hit below maxFraction:
// the segment misses the shape's local AABB grown by convexCastReach() and by the rounding of the
// coordinates involved, or enters it only at or beyond maxFraction (the cast's point lies within the reach
// of the shape wherever it hits, so a hit lies inside the grown box), or a plane through the segment's line
// keeps the whole shape farther than that. A few dozen instructions and one support scan instead of a
// cast, which needs several support scans to show a miss. Only for shapes whose getAabb is a cheap bound of
// the shape with its margin (the cached boxes of hulls, point clouds, convex meshes and multi-spheres, and
// the closed forms of capsules and cylinders); other shapes always go to the cast.
bool castMayHitConvex(const btConvexShape* shape, const btTransform& shapeTransform, const btVector3& from,
                      const btVector3& to, btScalar maxFraction)
{
	switch (shape->getShapeType())
	{
		case CONVEX_HULL_SHAPE_PROXYTYPE:
		case CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE:
		case CONVEX_TRIANGLEMESH_SHAPE_PROXYTYPE:
		case MULTI_SPHERE_SHAPE_PROXYTYPE:
		case CAPSULE_SHAPE_PROXYTYPE:
		case CYLINDER_SHAPE_PROXYTYPE:
			break;
		default:
			return true;
	}
	static const btScalar reach = convexCastReach();
	btTransform identity;
	identity.setIdentity();
	btVector3 boxMin, boxMax;
	shape->getAabb(identity, boxMin, boxMax);
	const btVector3 start = shapeTransform.invXform(from);
	const btVector3 direction = shapeTransform.invXform(to) - start;
	btScalar scale = btScalar(0);
	for (int axis = 0; axis < 3; ++axis)
		scale = btMax(scale, btMax(btMax(btFabs(start[axis]), btFabs(start[axis] + direction[axis])),
		                           btMax(btFabs(boxMin[axis]), btFabs(boxMax[axis]))));
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
	if (!castMayHitConvex(convexShape, wrap->getWorldTransform(), rayFromTrans.getOrigin(), rayToTrans.getOrigin(),
	                      resultCallback.m_closestHitFraction))
		return;
	if (startsInsidePolyhedron(convexShape, wrap->getWorldTransform().invXform(rayFromTrans.getOrigin()))) return;
	// The ray is a point (a sphere of radius 0 and no margin) cast against the shape.
	btSphereShape point(btScalar(0));
	point.setMargin(btScalar(0));
	btVoronoiSimplexSolver simplexSolver;
	btConvexCast::CastResult castResult;
	bool hit;
	// As in Bullet, a ray that starts inside the shape does not hit it (the casts' kMiss), which also spares
	// the depth query a start-in-contact cast would make for its normal.
	const btTransform& shapeTransform = wrap->getWorldTransform();
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

// A ray against a BVH mesh: the tree walk skips boxes beyond the closest hit so far (the callback's
// m_hitFraction, which its reportHit lowers), which leaves the hits found unchanged.
void castRayAgainstBvhMesh(btBvhTriangleMeshShape& mesh, btTriangleRaycastCallback& callback, const btVector3& from,
                           const btVector3& to)
{
	const btVector3 zero(0, 0, 0);
	caliber::castAgainstBvhMesh(mesh, &callback, from, to, zero, zero, &callback.m_hitFraction);
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
	if ((shapeType == TRIANGLE_MESH_SHAPE_PROXYTYPE && std::strcmp(concave->getName(), "BVHTRIANGLEMESH") == 0) ||
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
