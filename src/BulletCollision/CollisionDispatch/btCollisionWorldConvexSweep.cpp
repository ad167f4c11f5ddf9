// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <cstring>

#include "BulletCollision/BroadphaseCollision/btDbvt.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btCompoundShape.h"
#include "BulletCollision/CollisionShapes/btConcaveShape.h"
#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "BulletCollision/CollisionShapes/btStaticPlaneShape.h"
#include "BulletCollision/NarrowPhaseCollision/btContinuousConvexCollision.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h"
#include "BulletCollision/NarrowPhaseCollision/btRaycastCallback.h"
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"
#include "LinearMath/btQuickprof.h"
#include "LinearMath/btTransformUtil.h"

// btCollisionWorld::convexSweepTest and the per-object sweeps: the broadphase visits the objects whose
// boxes the swept shape's box crosses, and each object's shape is swept against by the method that suits it.

namespace
{
typedef btCollisionWorld::ConvexResultCallback ConvexResultCallback;
typedef btCollisionWorld::LocalConvexResult LocalConvexResult;
typedef btCollisionWorld::LocalShapeInfo LocalShapeInfo;

// Hands the hits of a triangle sweep (world space, as btTriangleConvexcastCallback reports them) to the
// user's callback with the part and triangle in LocalShapeInfo.
class BridgeTriangleConvexcastCallback : public btTriangleConvexcastCallback
{
public:
	BridgeTriangleConvexcastCallback(const btConvexShape* castShape, const btTransform& from, const btTransform& to,
	                                 ConvexResultCallback& resultCallback, const btCollisionObject* collisionObject,
	                                 const btTransform& triangleToWorld, btScalar triangleMargin,
	                                 btScalar allowedPenetration)
	    : btTriangleConvexcastCallback(castShape, from, to, triangleToWorld, triangleMargin),
	      m_resultCallback(resultCallback),
	      m_collisionObject(collisionObject)
	{
		m_hitFraction = resultCallback.m_closestHitFraction;
		m_allowedPenetration = allowedPenetration;
	}

	btScalar reportHit(const btVector3& hitNormalLocal, const btVector3& hitPointLocal, btScalar hitFraction,
	                   int partId, int triangleIndex) override
	{
		if (hitFraction > m_resultCallback.m_closestHitFraction) return m_hitFraction;
		LocalShapeInfo shapeInfo;
		shapeInfo.m_shapePart = partId;
		shapeInfo.m_triangleIndex = triangleIndex;
		LocalConvexResult convexResult(m_collisionObject, &shapeInfo, hitNormalLocal, hitPointLocal, hitFraction);
		return m_resultCallback.addSingleResult(convexResult, true);
	}

private:
	ConvexResultCallback& m_resultCallback;
	const btCollisionObject* m_collisionObject;
};

// Passes hits of one compound child to the user's callback, naming the child when the child's own sweep
// did not, and keeps the closest-hit bound in step with the user's.
class CompoundChildConvexCallback : public ConvexResultCallback
{
public:
	CompoundChildConvexCallback(int childIndex, ConvexResultCallback& userCallback)
	    : m_userCallback(userCallback), m_childIndex(childIndex)
	{
		m_closestHitFraction = userCallback.m_closestHitFraction;
		m_collisionFilterGroup = userCallback.m_collisionFilterGroup;
		m_collisionFilterMask = userCallback.m_collisionFilterMask;
	}

	bool needsCollision(btBroadphaseProxy* proxy0) const override { return m_userCallback.needsCollision(proxy0); }

	btScalar addSingleResult(LocalConvexResult& convexResult, bool normalInWorldSpace) override
	{
		LocalShapeInfo shapeInfo;
		shapeInfo.m_shapePart = -1;
		shapeInfo.m_triangleIndex = m_childIndex;
		if (!convexResult.m_localShapeInfo) convexResult.m_localShapeInfo = &shapeInfo;
		const btScalar bound = m_userCallback.addSingleResult(convexResult, normalInWorldSpace);
		m_closestHitFraction = m_userCallback.m_closestHitFraction;
		return bound;
	}

private:
	ConvexResultCallback& m_userCallback;
	int m_childIndex;
};

// The box, relative to the shape's origin, that holds castShape at every orientation between from and to:
// the exact box when the orientation does not change, otherwise the box around its bounding sphere.
void sweptShapeLocalBox(const btConvexShape* castShape, const btMatrix3x3& fromBasis, const btMatrix3x3& toBasis,
                        btVector3& boxMin, btVector3& boxMax)
{
	btTransform rotation(toBasis, btVector3(0, 0, 0));
	castShape->getAabb(rotation, boxMin, boxMax);
	bool sameBasis = true;
	for (int row = 0; row < 3; row++) sameBasis = sameBasis && fromBasis[row] == toBasis[row];
	if (sameBasis) return;
	btVector3 center;
	btScalar radius;
	castShape->getBoundingSphere(center, radius);
	const btScalar reach = center.length() + radius;
	boxMin.setMin(btVector3(-reach, -reach, -reach));
	boxMax.setMax(btVector3(reach, reach, reach));
}

// Ray test of one compound child (a leaf of the compound's child tree, or a child by index).
struct CompoundSweepTester : btDbvt::ICollide
{
	CompoundSweepTester(const btConvexShape* castShape, const btTransform& from, const btTransform& to,
	                    const btCollisionObjectWrapper* compoundWrap, const btCompoundShape* compound,
	                    ConvexResultCallback& resultCallback, btScalar allowedPenetration)
	    : m_castShape(castShape),
	      m_from(from),
	      m_to(to),
	      m_compoundWrap(compoundWrap),
	      m_compound(compound),
	      m_resultCallback(resultCallback),
	      m_allowedPenetration(allowedPenetration)
	{
	}

	void processChild(int childIndex)
	{
		if (m_resultCallback.m_closestHitFraction <= btScalar(0)) return;
		const btTransform childWorldTransform =
		    m_compoundWrap->getWorldTransform() * m_compound->getChildTransform(childIndex);
		btCollisionObjectWrapper childWrap(m_compoundWrap, m_compound->getChildShape(childIndex),
		                                   m_compoundWrap->getCollisionObject(), childWorldTransform, -1, childIndex);
		CompoundChildConvexCallback childCallback(childIndex, m_resultCallback);
		btCollisionWorld::objectQuerySingleInternal(m_castShape, m_from, m_to, &childWrap, childCallback,
		                                            m_allowedPenetration);
	}

	void Process(const btDbvtNode* leaf) override { processChild(leaf->dataAsInt); }

	const btConvexShape* m_castShape;
	const btTransform& m_from;
	const btTransform& m_to;
	const btCollisionObjectWrapper* m_compoundWrap;
	const btCompoundShape* m_compound;
	ConvexResultCallback& m_resultCallback;
	btScalar m_allowedPenetration;
};

void reportCastResult(const btConvexCast::CastResult& castResult, const btCollisionObject* object,
                      ConvexResultCallback& resultCallback)
{
	// A zero normal means the cast found no direction (degenerate overlapping start); dropped.
	if (!(castResult.m_normal.length2() > btScalar(1e-4))) return;
	if (!(castResult.m_fraction < resultCallback.m_closestHitFraction)) return;
	LocalConvexResult convexResult(object, 0, castResult.m_normal.normalized(), castResult.m_hitPoint,
	                               castResult.m_fraction);
	resultCallback.addSingleResult(convexResult, true);
}

void sweepConcave(const btConvexShape* castShape, const btTransform& from, const btTransform& to,
                  const btConcaveShape* concave, const btCollisionObjectWrapper* wrap,
                  ConvexResultCallback& resultCallback, btScalar allowedPenetration)
{
	const btTransform& worldTransform = wrap->getWorldTransform();
	const btVector3 fromLocal = worldTransform.invXform(from.getOrigin());
	const btVector3 toLocal = worldTransform.invXform(to.getOrigin());
	const btMatrix3x3 worldToLocal = worldTransform.getBasis().transpose();
	btVector3 boxMin, boxMax;
	sweptShapeLocalBox(castShape, worldToLocal * from.getBasis(), worldToLocal * to.getBasis(), boxMin, boxMax);

	BridgeTriangleConvexcastCallback callback(castShape, from, to, resultCallback, wrap->getCollisionObject(),
	                                          worldTransform, concave->getMargin(), allowedPenetration);
	if ((concave->getShapeType() == TRIANGLE_MESH_SHAPE_PROXYTYPE &&
	     std::strcmp(concave->getName(), "BVHTRIANGLEMESH") == 0) ||
	    concave->getShapeType() == MULTIMATERIAL_TRIANGLE_MESH_PROXYTYPE)
	{
		btBvhTriangleMeshShape* mesh =
		    const_cast<btBvhTriangleMeshShape*>(static_cast<const btBvhTriangleMeshShape*>(concave));
		mesh->performConvexcast(&callback, fromLocal, toLocal, boxMin, boxMax);
		return;
	}
	btVector3 sweepMin = fromLocal, sweepMax = fromLocal;
	sweepMin.setMin(toLocal);
	sweepMax.setMax(toLocal);
	concave->processAllTriangles(&callback, sweepMin + boxMin, sweepMax + boxMax);
}

// Visited by the broadphase for each object whose box the swept shape's box crosses.
struct WorldSweepCallback : public btBroadphaseRayCallback
{
	WorldSweepCallback(const btConvexShape* castShape, const btTransform& from, const btTransform& to,
	                   ConvexResultCallback& resultCallback, btScalar allowedPenetration)
	    : m_castShape(castShape),
	      m_from(from),
	      m_to(to),
	      m_resultCallback(resultCallback),
	      m_allowedPenetration(allowedPenetration)
	{
		const btVector3 direction = to.getOrigin() - from.getOrigin();
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
		if (m_resultCallback.m_closestHitFraction <= btScalar(0)) return false;
		btCollisionObject* collisionObject = static_cast<btCollisionObject*>(proxy->m_clientObject);
		if (m_resultCallback.needsCollision(collisionObject->getBroadphaseHandle()))
		{
			btCollisionWorld::objectQuerySingle(
			    m_castShape, m_from, m_to, collisionObject, collisionObject->getCollisionShape(),
			    collisionObject->getWorldTransform(), m_resultCallback, m_allowedPenetration);
			m_lambda_max = btMin(m_lambda_max, m_resultCallback.m_closestHitFraction);
		}
		return true;
	}

	const btConvexShape* m_castShape;
	const btTransform& m_from;
	const btTransform& m_to;
	ConvexResultCallback& m_resultCallback;
	btScalar m_allowedPenetration;
};
}  // namespace

void btCollisionWorld::convexSweepTest(const btConvexShape* castShape, const btTransform& convexFromWorld,
                                       const btTransform& convexToWorld, ConvexResultCallback& resultCallback,
                                       btScalar allowedCcdPenetration) const
{
	BT_PROFILE("convexSweepTest");
	btAssert(castShape && "btCollisionWorld::convexSweepTest: null shape");
	const bool finite =
	    caliber::isFinite(convexFromWorld) && caliber::isFinite(convexToWorld) && btIsFinite(allowedCcdPenetration);
	btAssert(finite && "btCollisionWorld::convexSweepTest: non-finite transform");
	if (!castShape || !finite || !m_broadphasePairCache) return;

	btVector3 boxMin, boxMax;
	sweptShapeLocalBox(castShape, convexFromWorld.getBasis(), convexToWorld.getBasis(), boxMin, boxMax);
	WorldSweepCallback sweepCallback(castShape, convexFromWorld, convexToWorld, resultCallback, allowedCcdPenetration);
	m_broadphasePairCache->rayTest(convexFromWorld.getOrigin(), convexToWorld.getOrigin(), sweepCallback, boxMin,
	                               boxMax);
}

void btCollisionWorld::objectQuerySingle(const btConvexShape* castShape, const btTransform& convexFromTrans,
                                         const btTransform& convexToTrans, btCollisionObject* collisionObject,
                                         const btCollisionShape* collisionShape,
                                         const btTransform& colObjWorldTransform, ConvexResultCallback& resultCallback,
                                         btScalar allowedPenetration)
{
	btCollisionObjectWrapper wrap(0, collisionShape, collisionObject, colObjWorldTransform, -1, -1);
	objectQuerySingleInternal(castShape, convexFromTrans, convexToTrans, &wrap, resultCallback, allowedPenetration);
}

void btCollisionWorld::objectQuerySingleInternal(const btConvexShape* castShape, const btTransform& convexFromTrans,
                                                 const btTransform& convexToTrans,
                                                 const btCollisionObjectWrapper* colObjWrap,
                                                 ConvexResultCallback& resultCallback, btScalar allowedPenetration)
{
	btAssert(castShape && colObjWrap && colObjWrap->getCollisionShape());
	if (!castShape || !colObjWrap || !colObjWrap->getCollisionShape()) return;
	const bool finite = caliber::isFinite(convexFromTrans) && caliber::isFinite(convexToTrans) &&
	                    caliber::isFinite(colObjWrap->getWorldTransform());
	btAssert(finite && "btCollisionWorld::objectQuerySingle: non-finite transform");
	if (!finite) return;

	const btCollisionShape* shape = colObjWrap->getCollisionShape();
	const btTransform& worldTransform = colObjWrap->getWorldTransform();
	const btCollisionObject* object = colObjWrap->getCollisionObject();
	btConvexCast::CastResult castResult;
	castResult.m_allowedPenetration = allowedPenetration;

	if (shape->isConvex())
	{
		BT_PROFILE("convexSweepConvex");
		btVoronoiSimplexSolver simplexSolver;
		btGjkEpaPenetrationDepthSolver depthSolver;
		btContinuousConvexCollision cast(castShape, static_cast<const btConvexShape*>(shape), &simplexSolver,
		                                 &depthSolver);
		if (cast.calcTimeOfImpact(convexFromTrans, convexToTrans, worldTransform, worldTransform, castResult))
			reportCastResult(castResult, object, resultCallback);
	}
	else if (shape->getShapeType() == STATIC_PLANE_PROXYTYPE)
	{
		BT_PROFILE("convexSweepPlane");
		btContinuousConvexCollision cast(castShape, static_cast<const btStaticPlaneShape*>(shape));
		if (cast.calcTimeOfImpact(convexFromTrans, convexToTrans, worldTransform, worldTransform, castResult))
			reportCastResult(castResult, object, resultCallback);
	}
	else if (shape->isConcave())
	{
		BT_PROFILE("convexSweepConcave");
		sweepConcave(castShape, convexFromTrans, convexToTrans, static_cast<const btConcaveShape*>(shape), colObjWrap,
		             resultCallback, allowedPenetration);
	}
	else if (shape->isCompound())
	{
		BT_PROFILE("convexSweepCompound");
		const btCompoundShape* compound = static_cast<const btCompoundShape*>(shape);
		CompoundSweepTester tester(castShape, convexFromTrans, convexToTrans, colObjWrap, compound, resultCallback,
		                           allowedPenetration);
		const btDbvt* tree = compound->getDynamicAabbTree();
		if (tree)
		{
			if (!tree->m_root) return;
			// The swept shape's box in the compound's frame, over the whole motion.
			const btMatrix3x3 worldToLocal = worldTransform.getBasis().transpose();
			btVector3 boxMin, boxMax;
			sweptShapeLocalBox(castShape, worldToLocal * convexFromTrans.getBasis(),
			                   worldToLocal * convexToTrans.getBasis(), boxMin, boxMax);
			btVector3 sweepMin = worldTransform.invXform(convexFromTrans.getOrigin());
			btVector3 sweepMax = sweepMin;
			const btVector3 toLocal = worldTransform.invXform(convexToTrans.getOrigin());
			sweepMin.setMin(toLocal);
			sweepMax.setMax(toLocal);
			const btDbvtVolume bounds = btDbvtVolume::FromMM(sweepMin + boxMin, sweepMax + boxMax);
			tree->collideTV(tree->m_root, bounds, tester);
		}
		else
		{
			for (int i = 0; i < compound->getNumChildShapes(); i++) tester.processChild(i);
		}
	}
}
