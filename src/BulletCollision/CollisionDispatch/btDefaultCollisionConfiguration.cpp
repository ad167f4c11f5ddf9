// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionDispatch/btPairPoseCache.h"

#include "BulletCollision/BroadphaseCollision/btBroadphaseProxy.h"
#include "BulletCollision/CollisionDispatch/btBoxBoxCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btCompoundCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btCompoundCompoundCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btConvexConcaveCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btConvexConvexAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btConvexPlaneCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btEmptyCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btSphereBoxCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btSphereSphereCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btSphereTriangleCollisionAlgorithm.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h"
#include "BulletCollision/NarrowPhaseCollision/btMinkowskiPenetrationDepthSolver.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "LinearMath/btPoolAllocator.h"

namespace
{
int atLeastOne(int count)
{
	btAssert(count >= 1 && "btDefaultCollisionConfiguration: pool size must be at least 1");
	return count >= 1 ? count : 1;
}

template <class T>
int maxSize(int current)
{
	return current > int(sizeof(T)) ? current : int(sizeof(T));
}

btCollisionAlgorithmCreateFunc* swappedFactory(btCollisionAlgorithmCreateFunc* factory)
{
	factory->m_swapped = true;
	return factory;
}
}  // namespace

btDefaultCollisionConfiguration::btDefaultCollisionConfiguration(const btDefaultCollisionConstructionInfo& info)
    : m_persistentManifoldPoolSize(0),
      m_persistentManifoldPool(0),
      m_ownsPersistentManifoldPool(false),
      m_collisionAlgorithmPool(0),
      m_ownsCollisionAlgorithmPool(false),
      m_pdSolver(0)
{
	if (info.m_useEpaPenetrationAlgorithm)
		m_pdSolver = new btGjkEpaPenetrationDepthSolver();
	else
		m_pdSolver = new btMinkowskiPenetrationDepthSolver();

	m_convexConvexCreateFunc = new btConvexConvexAlgorithm::CreateFunc(m_pdSolver);
	m_convexConcaveCreateFunc = new btConvexConcaveCollisionAlgorithm::CreateFunc();
	m_swappedConvexConcaveCreateFunc = new btConvexConcaveCollisionAlgorithm::SwappedCreateFunc();
	m_compoundCreateFunc = new btCompoundCollisionAlgorithm::CreateFunc();
	m_compoundCompoundCreateFunc = new btCompoundCompoundCollisionAlgorithm::CreateFunc();
	m_swappedCompoundCreateFunc = new btCompoundCollisionAlgorithm::SwappedCreateFunc();
	m_emptyCreateFunc = new btEmptyAlgorithm::CreateFunc();
	m_sphereSphereCF = new btSphereSphereCollisionAlgorithm::CreateFunc();
	m_sphereBoxCF = new btSphereBoxCollisionAlgorithm::CreateFunc();
	m_boxSphereCF = swappedFactory(new btSphereBoxCollisionAlgorithm::CreateFunc());
	m_boxBoxCF = new btBoxBoxCollisionAlgorithm::CreateFunc();
	m_sphereTriangleCF = new btSphereTriangleCollisionAlgorithm::CreateFunc();
	m_triangleSphereCF = swappedFactory(new btSphereTriangleCollisionAlgorithm::CreateFunc());
	m_convexPlaneCF = new btConvexPlaneCollisionAlgorithm::CreateFunc();
	m_planeConvexCF = swappedFactory(new btConvexPlaneCollisionAlgorithm::CreateFunc());

	// Every algorithm the table can create must fit one pool element.
	int algorithmSize = info.m_customCollisionAlgorithmMaxElementSize;
	algorithmSize = maxSize<btConvexConvexAlgorithm>(algorithmSize);
	algorithmSize = maxSize<btConvexConcaveCollisionAlgorithm>(algorithmSize);
	algorithmSize = maxSize<btCompoundCollisionAlgorithm>(algorithmSize);
	algorithmSize = maxSize<btCompoundCompoundCollisionAlgorithm>(algorithmSize);
	algorithmSize = maxSize<btEmptyAlgorithm>(algorithmSize);
	algorithmSize = maxSize<btSphereSphereCollisionAlgorithm>(algorithmSize);
	algorithmSize = maxSize<btSphereBoxCollisionAlgorithm>(algorithmSize);
	algorithmSize = maxSize<btBoxBoxCollisionAlgorithm>(algorithmSize);
	algorithmSize = btMax(algorithmSize, caliber::cachedBoxBoxAlgorithmSize());
	algorithmSize = btMax(algorithmSize, caliber::cachedConvexConvexAlgorithmSize());
	algorithmSize = maxSize<btSphereTriangleCollisionAlgorithm>(algorithmSize);
	algorithmSize = maxSize<btConvexPlaneCollisionAlgorithm>(algorithmSize);

	if (info.m_persistentManifoldPool)
	{
		m_persistentManifoldPool = info.m_persistentManifoldPool;
	}
	else
	{
		m_persistentManifoldPoolSize = atLeastOne(info.m_defaultMaxPersistentManifoldPoolSize);
		m_persistentManifoldPool = new btPoolAllocator(int(sizeof(btPersistentManifold)), m_persistentManifoldPoolSize);
		m_ownsPersistentManifoldPool = true;
	}
	if (info.m_collisionAlgorithmPool)
	{
		m_collisionAlgorithmPool = info.m_collisionAlgorithmPool;
	}
	else
	{
		m_collisionAlgorithmPool =
		    new btPoolAllocator(algorithmSize, atLeastOne(info.m_defaultMaxCollisionAlgorithmPoolSize));
		m_ownsCollisionAlgorithmPool = true;
	}
}

btDefaultCollisionConfiguration::~btDefaultCollisionConfiguration()
{
	if (m_ownsCollisionAlgorithmPool) delete m_collisionAlgorithmPool;
	if (m_ownsPersistentManifoldPool) delete m_persistentManifoldPool;
	delete m_convexConvexCreateFunc;
	delete m_convexConcaveCreateFunc;
	delete m_swappedConvexConcaveCreateFunc;
	delete m_compoundCreateFunc;
	delete m_compoundCompoundCreateFunc;
	delete m_swappedCompoundCreateFunc;
	delete m_emptyCreateFunc;
	delete m_sphereSphereCF;
	delete m_sphereBoxCF;
	delete m_boxSphereCF;
	delete m_boxBoxCF;
	delete m_sphereTriangleCF;
	delete m_triangleSphereCF;
	delete m_convexPlaneCF;
	delete m_planeConvexCF;
	delete m_pdSolver;
}

btCollisionAlgorithmCreateFunc* btDefaultCollisionConfiguration::getCollisionAlgorithmCreateFunc(int proxyType0,
                                                                                                 int proxyType1)
{
	if (proxyType0 == SPHERE_SHAPE_PROXYTYPE && proxyType1 == SPHERE_SHAPE_PROXYTYPE) return m_sphereSphereCF;
	if (proxyType0 == SPHERE_SHAPE_PROXYTYPE && proxyType1 == BOX_SHAPE_PROXYTYPE) return m_sphereBoxCF;
	if (proxyType0 == BOX_SHAPE_PROXYTYPE && proxyType1 == SPHERE_SHAPE_PROXYTYPE) return m_boxSphereCF;
	if (proxyType0 == BOX_SHAPE_PROXYTYPE && proxyType1 == BOX_SHAPE_PROXYTYPE) return m_boxBoxCF;
	return getClosestPointsAlgorithmCreateFunc(proxyType0, proxyType1);
}

btCollisionAlgorithmCreateFunc* btDefaultCollisionConfiguration::getClosestPointsAlgorithmCreateFunc(int proxyType0,
                                                                                                     int proxyType1)
{
	const bool convex0 = btBroadphaseProxy::isConvex(proxyType0);
	const bool convex1 = btBroadphaseProxy::isConvex(proxyType1);
	if (proxyType0 == SPHERE_SHAPE_PROXYTYPE && proxyType1 == SPHERE_SHAPE_PROXYTYPE) return m_sphereSphereCF;
	if (proxyType0 == SPHERE_SHAPE_PROXYTYPE && proxyType1 == TRIANGLE_SHAPE_PROXYTYPE) return m_sphereTriangleCF;
	if (proxyType0 == TRIANGLE_SHAPE_PROXYTYPE && proxyType1 == SPHERE_SHAPE_PROXYTYPE) return m_triangleSphereCF;
	if (convex0 && proxyType1 == STATIC_PLANE_PROXYTYPE) return m_convexPlaneCF;
	if (proxyType0 == STATIC_PLANE_PROXYTYPE && convex1) return m_planeConvexCF;
	if (convex0 && convex1) return m_convexConvexCreateFunc;

	btCollisionAlgorithmCreateFunc* chosen = 0;
	if (convex0 && btBroadphaseProxy::isConcave(proxyType1))
		chosen = m_convexConcaveCreateFunc;
	else if (btBroadphaseProxy::isConcave(proxyType0) && convex1)
		chosen = m_swappedConvexConcaveCreateFunc;
	else if (btBroadphaseProxy::isCompound(proxyType0) && btBroadphaseProxy::isCompound(proxyType1))
		chosen = m_compoundCompoundCreateFunc;
	else if (btBroadphaseProxy::isCompound(proxyType0))
		chosen = m_compoundCreateFunc;
	else if (btBroadphaseProxy::isCompound(proxyType1))
		chosen = m_swappedCompoundCreateFunc;
	return chosen ? chosen : m_emptyCreateFunc;
}

void btDefaultCollisionConfiguration::setConvexConvexMultipointIterations(int numPerturbationIterations,
                                                                          int minimumPointsPerturbationThreshold)
{
	btConvexConvexAlgorithm::CreateFunc* factory =
	    static_cast<btConvexConvexAlgorithm::CreateFunc*>(m_convexConvexCreateFunc);
	factory->m_numPerturbationIterations = numPerturbationIterations;
	factory->m_minimumPointsPerturbationThreshold = minimumPointsPerturbationThreshold;
}

void btDefaultCollisionConfiguration::setPlaneConvexMultipointIterations(int numPerturbationIterations,
                                                                         int minimumPointsPerturbationThreshold)
{
	btConvexPlaneCollisionAlgorithm::CreateFunc* convexPlane =
	    static_cast<btConvexPlaneCollisionAlgorithm::CreateFunc*>(m_convexPlaneCF);
	convexPlane->m_numPerturbationIterations = numPerturbationIterations;
	convexPlane->m_minimumPointsPerturbationThreshold = minimumPointsPerturbationThreshold;
	btConvexPlaneCollisionAlgorithm::CreateFunc* planeConvex =
	    static_cast<btConvexPlaneCollisionAlgorithm::CreateFunc*>(m_planeConvexCF);
	planeConvex->m_numPerturbationIterations = numPerturbationIterations;
	planeConvex->m_minimumPointsPerturbationThreshold = minimumPointsPerturbationThreshold;
}
