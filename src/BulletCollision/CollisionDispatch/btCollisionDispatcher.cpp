// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"

#include <new>

#include "BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h"
#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"
#include "BulletCollision/CollisionDispatch/btCollisionConfiguration.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h"
#include "BulletCollision/CollisionDispatch/btManifoldAllocation.h"
#include "BulletCollision/CollisionDispatch/btManifoldOwners.h"
#include "BulletCollision/CollisionShapes/btAngularMotionDisc.h"
#include "BulletCollision/CollisionShapes/btCollisionShape.h"
#include "LinearMath/btAlignedAllocator.h"
#include "LinearMath/btPoolAllocator.h"

namespace
{
bool isValidShapeType(int type) { return type >= 0 && type < MAX_BROADPHASE_COLLISION_TYPES; }

// Hands every pair of the cache to the dispatcher's near callback; never removes a pair (the broadphase
// decides when pairs end).
struct NearCallbackVisitor : public btOverlapCallback
{
	btCollisionDispatcher& m_dispatcher;
	const btDispatcherInfo& m_dispatchInfo;

	NearCallbackVisitor(btCollisionDispatcher& dispatcher, const btDispatcherInfo& dispatchInfo)
	    : m_dispatcher(dispatcher), m_dispatchInfo(dispatchInfo)
	{
	}

	bool processOverlap(btBroadphasePair& pair) override
	{
		(*m_dispatcher.getNearCallback())(pair, m_dispatcher, m_dispatchInfo);
		return false;
	}
};
}  // namespace

btCollisionDispatcher::btCollisionDispatcher(btCollisionConfiguration* collisionConfiguration)
    : m_dispatcherFlags(CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD),
      m_nearCallback(&btCollisionDispatcher::defaultNearCallback),
      m_collisionAlgorithmPoolAllocator(0),
      m_persistentManifoldPoolAllocator(0),
      m_collisionConfiguration(collisionConfiguration)
{
	btAssert(collisionConfiguration && "btCollisionDispatcher needs a collision configuration");
	// Without a configuration (release) the matrix stays empty: every pair gets no algorithm, and
	// manifolds and algorithms come from the heap.
	for (int i = 0; i < MAX_BROADPHASE_COLLISION_TYPES; ++i)
	{
		for (int j = 0; j < MAX_BROADPHASE_COLLISION_TYPES; ++j)
		{
			m_doubleDispatchContactPoints[i][j] =
			    collisionConfiguration ? collisionConfiguration->getCollisionAlgorithmCreateFunc(i, j) : 0;
			m_doubleDispatchClosestPoints[i][j] =
			    collisionConfiguration ? collisionConfiguration->getClosestPointsAlgorithmCreateFunc(i, j) : 0;
		}
	}
	if (collisionConfiguration)
	{
		m_collisionAlgorithmPoolAllocator = collisionConfiguration->getCollisionAlgorithmPool();
		m_persistentManifoldPoolAllocator = collisionConfiguration->getPersistentManifoldPool();
	}
}

btCollisionDispatcher::~btCollisionDispatcher()
{
	// Normally the world has released every manifold through its algorithms already; whatever is left
	// would otherwise leak (heap manifolds) or keep pool elements busy.
	while (m_manifoldsPtr.size()) releaseManifold(m_manifoldsPtr[m_manifoldsPtr.size() - 1]);
	caliber::releaseManifoldOwners(this);  // a btCollisionDispatcherMt's (btManifoldOwners.h)
}

void btCollisionDispatcher::registerCollisionCreateFunc(int proxyType0, int proxyType1,
                                                        btCollisionAlgorithmCreateFunc* createFunc)
{
	btAssert(isValidShapeType(proxyType0) && isValidShapeType(proxyType1) && createFunc);
	if (!isValidShapeType(proxyType0) || !isValidShapeType(proxyType1) || !createFunc) return;
	m_doubleDispatchContactPoints[proxyType0][proxyType1] = createFunc;
}

void btCollisionDispatcher::registerClosestPointsCreateFunc(int proxyType0, int proxyType1,
                                                            btCollisionAlgorithmCreateFunc* createFunc)
{
	btAssert(isValidShapeType(proxyType0) && isValidShapeType(proxyType1) && createFunc);
	if (!isValidShapeType(proxyType0) || !isValidShapeType(proxyType1) || !createFunc) return;
	m_doubleDispatchClosestPoints[proxyType0][proxyType1] = createFunc;
}

btPersistentManifold* btCollisionDispatcher::getNewManifold(const btCollisionObject* b0, const btCollisionObject* b1)
{
	btAssert(b0 && b1 && b0->getCollisionShape() && b1->getCollisionShape());
	const caliber::ManifoldThresholds thresholds =
	    caliber::manifoldThresholds(b0, b1, (m_dispatcherFlags & CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD) != 0);

	void* memory = caliber::allocateManifoldMemory(
	    m_persistentManifoldPoolAllocator, !(m_dispatcherFlags & CD_DISABLE_CONTACTPOOL_DYNAMIC_ALLOCATION));
	if (!memory) return 0;
	btPersistentManifold* manifold =
	    new (memory) btPersistentManifold(b0, b1, 0, thresholds.breaking, thresholds.processing);
	manifold->m_index1a = m_manifoldsPtr.size();
	m_manifoldsPtr.push_back(manifold);
	return manifold;
}

void btCollisionDispatcher::releaseManifold(btPersistentManifold* manifold)
{
	if (!manifold) return;
	const int index = manifold->m_index1a;
	const bool owned = index >= 0 && index < m_manifoldsPtr.size() && m_manifoldsPtr[index] == manifold;
	btAssert(owned && "releaseManifold: not a live manifold of this dispatcher");
	if (!owned) return;

	clearManifold(manifold);
	// Swap with the last so removal is O(1); the moved manifold learns its new index.
	const int last = m_manifoldsPtr.size() - 1;
	m_manifoldsPtr.swap(index, last);
	m_manifoldsPtr[index]->m_index1a = index;
	m_manifoldsPtr.pop_back();

	manifold->~btPersistentManifold();
	if (m_persistentManifoldPoolAllocator && m_persistentManifoldPoolAllocator->validPtr(manifold))
		m_persistentManifoldPoolAllocator->freeMemory(manifold);
	else
		btAlignedFree(manifold);
}

void btCollisionDispatcher::clearManifold(btPersistentManifold* manifold)
{
	btAssert(manifold);
	if (manifold) manifold->clearManifold();
}

btCollisionAlgorithm* btCollisionDispatcher::findAlgorithm(const btCollisionObjectWrapper* body0Wrap,
                                                           const btCollisionObjectWrapper* body1Wrap,
                                                           btPersistentManifold* sharedManifold,
                                                           ebtDispatcherQueryType queryType)
{
	const bool usable = body0Wrap && body1Wrap && body0Wrap->getCollisionShape() && body1Wrap->getCollisionShape();
	btAssert(usable && "findAlgorithm needs two wrappers with shapes");
	if (!usable) return 0;
	const int type0 = body0Wrap->getCollisionShape()->getShapeType();
	const int type1 = body1Wrap->getCollisionShape()->getShapeType();
	btAssert(isValidShapeType(type0) && isValidShapeType(type1));
	if (!isValidShapeType(type0) || !isValidShapeType(type1)) return 0;

	btCollisionAlgorithmCreateFunc* createFunc = queryType == BT_CLOSEST_POINT_ALGORITHMS
	                                                 ? m_doubleDispatchClosestPoints[type0][type1]
	                                                 : m_doubleDispatchContactPoints[type0][type1];
	if (!createFunc) return 0;
	btCollisionAlgorithmConstructionInfo ci;
	ci.m_dispatcher1 = this;
	ci.m_manifold = sharedManifold;
	return createFunc->CreateCollisionAlgorithm(ci, body0Wrap, body1Wrap);
}

bool btCollisionDispatcher::needsCollision(const btCollisionObject* body0, const btCollisionObject* body1)
{
	btAssert(body0 && body1);
	if (!body0 || !body1) return false;
	// Two sleeping (or static, which the dynamics world puts to sleep) objects cannot produce anything new.
	if (!(m_dispatcherFlags & CD_STATIC_STATIC_REPORTED) && !body0->isActive() && !body1->isActive()) return false;
	return body0->checkCollideWith(body1) && body1->checkCollideWith(body0);
}

bool btCollisionDispatcher::needsResponse(const btCollisionObject* body0, const btCollisionObject* body1)
{
	btAssert(body0 && body1);
	if (!body0 || !body1) return false;
	if (!body0->hasContactResponse() || !body1->hasContactResponse()) return false;
	// Nothing can be pushed when neither object is dynamic.
	return !body0->isStaticOrKinematicObject() || !body1->isStaticOrKinematicObject();
}

void btCollisionDispatcher::dispatchAllCollisionPairs(btOverlappingPairCache* pairCache,
                                                      const btDispatcherInfo& dispatchInfo, btDispatcher* dispatcher)
{
	(void)dispatcher;
	btAssert(pairCache);
	if (!pairCache) return;
	NearCallbackVisitor visitor(*this, dispatchInfo);
	pairCache->processAllOverlappingPairs(&visitor, this, dispatchInfo);
}

void btCollisionDispatcher::setNearCallback(btNearCallback nearCallback)
{
	m_nearCallback = nearCallback ? nearCallback : &btCollisionDispatcher::defaultNearCallback;
}

void btCollisionDispatcher::defaultNearCallback(btBroadphasePair& collisionPair, btCollisionDispatcher& dispatcher,
                                                const btDispatcherInfo& dispatchInfo)
{
	if (!collisionPair.m_pProxy0 || !collisionPair.m_pProxy1) return;
	btCollisionObject* colObj0 = static_cast<btCollisionObject*>(collisionPair.m_pProxy0->m_clientObject);
	btCollisionObject* colObj1 = static_cast<btCollisionObject*>(collisionPair.m_pProxy1->m_clientObject);
	if (!colObj0 || !colObj1 || !colObj0->getCollisionShape() || !colObj1->getCollisionShape()) return;
	if (!dispatcher.needsCollision(colObj0, colObj1)) return;

	btCollisionObjectWrapper wrap0(0, colObj0->getCollisionShape(), colObj0, colObj0->getWorldTransform(), -1, -1);
	btCollisionObjectWrapper wrap1(0, colObj1->getCollisionShape(), colObj1, colObj1->getWorldTransform(), -1, -1);
	// The algorithm lives with the pair: made once, freed by the pair cache when the pair ends.
	if (!collisionPair.m_algorithm)
		collisionPair.m_algorithm = dispatcher.findAlgorithm(&wrap0, &wrap1, 0, BT_CONTACT_POINT_ALGORITHMS);
	if (!collisionPair.m_algorithm) return;

	btManifoldResult result(&wrap0, &wrap1);
	if (dispatchInfo.m_useContinuous && dispatchInfo.m_timeStep > btScalar(0))
	{
		// Speculative contacts: points are kept up to the distance the pair can close in one step, so a
		// fast body meets the surface in the solver (which lets it close the gap and no more) instead of
		// being found deep inside it a step later, or past a thin mesh.
		const btVector3 relative =
		    colObj0->getInterpolationLinearVelocity() - colObj1->getInterpolationLinearVelocity();
		// The angular motion disc costs a bounding-sphere computation: only asked of turning bodies (and
		// worked out inline for plain boxes, btAngularMotionDisc.h).
		btScalar angular = btScalar(0);
		const btScalar spin0 = colObj0->getInterpolationAngularVelocity().length2();
		const btScalar spin1 = colObj1->getInterpolationAngularVelocity().length2();
		if (spin0 > btScalar(0)) angular += btSqrt(spin0) * caliber::angularMotionDisc(colObj0->getCollisionShape());
		if (spin1 > btScalar(0)) angular += btSqrt(spin1) * caliber::angularMotionDisc(colObj1->getCollisionShape());
		const btScalar closing = (relative.length() + angular) * dispatchInfo.m_timeStep;
		if (btIsFinite(closing)) result.m_closestPointDistanceThreshold = closing;
	}
	if (dispatchInfo.m_dispatchFunc == btDispatcherInfo::DISPATCH_DISCRETE)
	{
		collisionPair.m_algorithm->processCollision(&wrap0, &wrap1, dispatchInfo, &result);
	}
	else
	{
		const btScalar toi = collisionPair.m_algorithm->calculateTimeOfImpact(colObj0, colObj1, dispatchInfo, &result);
		if (toi < dispatchInfo.m_timeOfImpact) dispatchInfo.m_timeOfImpact = toi;
	}
}

void* btCollisionDispatcher::allocateCollisionAlgorithm(int size)
{
	btAssert(size > 0);
	if (size <= 0) size = 1;
	void* memory = m_collisionAlgorithmPoolAllocator ? m_collisionAlgorithmPoolAllocator->allocate(size) : 0;
	return memory ? memory : btAlignedAlloc(size_t(size), 16);
}

void btCollisionDispatcher::freeCollisionAlgorithm(void* ptr)
{
	if (!ptr) return;
	if (m_collisionAlgorithmPoolAllocator && m_collisionAlgorithmPoolAllocator->validPtr(ptr))
		m_collisionAlgorithmPoolAllocator->freeMemory(ptr);
	else
		btAlignedFree(ptr);
}
