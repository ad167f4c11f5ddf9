// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btSoftRigidDynamicsWorld: the rigid pipeline of btDiscreteDynamicsWorld with the soft bodies'
// stages around it (docs/soft-bodies.md, "The step").

#include "BulletSoftBody/btSoftRigidDynamicsWorld.h"

#include <new>

#include "BulletSoftBody/btDefaultSoftBodySolver.h"
#include "BulletSoftBody/btSoftBodyHelpers.h"
#include "BulletSoftBody/btSoftBodySolvers.h"
#include "LinearMath/btQuickprof.h"
#include "btSoftBodyInternal.h"

btSoftRigidDynamicsWorld::btSoftRigidDynamicsWorld(btDispatcher* dispatcher, btBroadphaseInterface* pairCache,
                                                   btConstraintSolver* constraintSolver,
                                                   btCollisionConfiguration* collisionConfiguration,
                                                   btSoftBodySolver* softBodySolver)
    : btDiscreteDynamicsWorld(dispatcher, pairCache, constraintSolver, collisionConfiguration),
      m_softBodySolver(softBodySolver),
      m_ownsSolver(false)
{
	if (!m_softBodySolver)
	{
		void* mem = btAlignedAlloc(sizeof(btDefaultSoftBodySolver), 16);
		m_softBodySolver = new (mem) btDefaultSoftBodySolver();
		m_ownsSolver = true;
	}
	m_drawFlags = fDrawFlags::Std;
	m_drawNodeTree = true;
	m_drawFaceTree = false;
	m_drawClusterTree = false;
	m_sbi.m_broadphase = pairCache;
	m_sbi.m_dispatcher = dispatcher;
	m_sbi.m_sparsesdf.Initialize();
	m_sbi.m_sparsesdf.Reset();
	m_sbi.air_density = btScalar(1.2);
	m_sbi.water_density = 0;
	m_sbi.water_offset = 0;
	m_sbi.water_normal.setValue(0, 0, 0);
	m_sbi.m_gravity.setValue(0, -10, 0);
}

btSoftRigidDynamicsWorld::~btSoftRigidDynamicsWorld()
{
	if (m_ownsSolver)
	{
		m_softBodySolver->~btSoftBodySolver();
		btAlignedFree(m_softBodySolver);
	}
}

void btSoftRigidDynamicsWorld::predictUnconstraintMotion(btScalar timeStep)
{
	btDiscreteDynamicsWorld::predictUnconstraintMotion(timeStep);
	BT_PROFILE("predictUnconstraintMotionSoftBody");
	m_softBodySolver->predictMotion(timeStep);
}

void btSoftRigidDynamicsWorld::internalSingleStepSimulation(btScalar timeStep)
{
	m_softBodySolver->optimize(m_softBodies);
	// Rigid step: its prediction stage predicts the soft bodies too, and its collision stage finds
	// their contacts (btSoftRigidCollisionAlgorithm); rigid bodies move first.
	btDiscreteDynamicsWorld::internalSingleStepSimulation(timeStep);
	solveSoftBodiesConstraints(timeStep);
	m_softBodySolver->updateSoftBodies();
}

void btSoftRigidDynamicsWorld::solveSoftBodiesConstraints(btScalar timeStep)
{
	BT_PROFILE("solveSoftConstraints");
	m_softBodySolver->solveConstraints(timeStep);
}

void btSoftRigidDynamicsWorld::addSoftBody(btSoftBody* body, int collisionFilterGroup, int collisionFilterMask)
{
	btAssert(body && "btSoftRigidDynamicsWorld::addSoftBody: null body");
	if (!body) return;
	const bool present = m_softBodies.findLinearSearch(body) != m_softBodies.size();
	btAssert(!present && "btSoftRigidDynamicsWorld::addSoftBody: body added twice");
	if (present)
	{
		btReportWarning("Caliber: addSoftBody: the soft body is already in this world; call ignored\n",
		                getDebugDrawer());
		return;
	}
	body->setSoftBodySolver(m_softBodySolver);
	body->updateBounds();
	m_softBodies.push_back(body);
	btCollisionWorld::addCollisionObject(body, collisionFilterGroup, collisionFilterMask);
}

void btSoftRigidDynamicsWorld::removeSoftBody(btSoftBody* body)
{
	btAssert(body && "btSoftRigidDynamicsWorld::removeSoftBody: null body");
	if (!body) return;
	const bool present = m_softBodies.findLinearSearch(body) != m_softBodies.size();
	btAssert(present && "btSoftRigidDynamicsWorld::removeSoftBody: body is not in this world");
	if (!present)
	{
		btReportWarning("Caliber: removeSoftBody: the soft body is not in this world; call ignored\n",
		                getDebugDrawer());
		return;
	}
	m_softBodies.remove(body);
	body->m_rcontacts.resize(0);
	btCollisionWorld::removeCollisionObject(body);
}

void btSoftRigidDynamicsWorld::removeCollisionObject(btCollisionObject* collisionObject)
{
	btSoftBody* body = btSoftBody::upcast(collisionObject);
	if (body)
		removeSoftBody(body);
	else
		btDiscreteDynamicsWorld::removeCollisionObject(collisionObject);
}

void btSoftRigidDynamicsWorld::debugDrawWorld()
{
	btDiscreteDynamicsWorld::debugDrawWorld();
	btIDebugDraw* drawer = getDebugDrawer();
	if (!drawer) return;
	for (int i = 0; i < m_softBodies.size(); ++i)
	{
		btSoftBody* psb = m_softBodies[i];
		btSoftBodyHelpers::Draw(psb, drawer, m_drawFlags);
		if (m_drawNodeTree && (m_drawFlags & fDrawFlags::NodeTree)) btSoftBodyHelpers::DrawNodeTree(psb, drawer);
		if (m_drawFaceTree && (m_drawFlags & fDrawFlags::FaceTree)) btSoftBodyHelpers::DrawFaceTree(psb, drawer);
	}
}

namespace
{
// Reports the nearest face of a soft body hit by the ray to the callback.
void rayTestSoftBody(const btVector3& from, const btVector3& to, btSoftBody* body,
                     btCollisionWorld::RayResultCallback& callback)
{
	btSoftBody::sRayCast hit;
	if (!body->rayTest(from, to, hit) || hit.fraction >= callback.m_closestHitFraction) return;
	btCollisionWorld::LocalShapeInfo shapeInfo;
	shapeInfo.m_shapePart = 0;
	shapeInfo.m_triangleIndex = hit.index;
	// The face's normal, turned to face the ray.
	const btSoftBody::Face& f = body->m_faces[hit.index];
	btVector3 normal = (f.m_n[1]->m_x - f.m_n[0]->m_x).cross(f.m_n[2]->m_x - f.m_n[0]->m_x);
	if (normal.length2() > SIMD_EPSILON) normal.normalize();
	if (normal.dot(to - from) > 0) normal = -normal;
	btCollisionWorld::LocalRayResult result(body, &shapeInfo, normal, hit.fraction);
	callback.addSingleResult(result, true);
}
}  // namespace

void btSoftRigidDynamicsWorld::rayTest(const btVector3& rayFromWorld, const btVector3& rayToWorld,
                                       RayResultCallback& resultCallback) const
{
	btDiscreteDynamicsWorld::rayTest(rayFromWorld, rayToWorld, resultCallback);
	if (!caliber::isFinite(rayFromWorld) || !caliber::isFinite(rayToWorld)) return;
	for (int i = 0; i < m_softBodies.size(); ++i)
	{
		btSoftBody* body = m_softBodies[i];
		if (!body->getBroadphaseHandle() || !resultCallback.needsCollision(body->getBroadphaseHandle())) continue;
		rayTestSoftBody(rayFromWorld, rayToWorld, body, resultCallback);
	}
}

void btSoftRigidDynamicsWorld::rayTestSingle(const btTransform& rayFromTrans, const btTransform& rayToTrans,
                                             btCollisionObject* collisionObject, const btCollisionShape* collisionShape,
                                             const btTransform& colObjWorldTransform, RayResultCallback& resultCallback)
{
	btSoftBody* body = btSoftBody::upcast(collisionObject);
	if (body)
		rayTestSoftBody(rayFromTrans.getOrigin(), rayToTrans.getOrigin(), body, resultCallback);
	else
		btCollisionWorld::rayTestSingle(rayFromTrans, rayToTrans, collisionObject, collisionShape, colObjWorldTransform,
		                                resultCallback);
}
