// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h"

#include <new>

#include "BulletCollision/BroadphaseCollision/btBroadphaseProxy.h"
#include "BulletSoftBody/btSoftBodyConcaveCollisionAlgorithm.h"
#include "BulletSoftBody/btSoftRigidCollisionAlgorithm.h"
#include "BulletSoftBody/btSoftSoftCollisionAlgorithm.h"
#include "LinearMath/btAlignedAllocator.h"

namespace
{
template <class T>
T* makeCreateFunc(bool swapped)
{
	T* f = new (btAlignedAlloc(sizeof(T), 16)) T();
	f->m_swapped = swapped;
	return f;
}

void destroyCreateFunc(btCollisionAlgorithmCreateFunc* f)
{
	if (!f) return;
	f->~btCollisionAlgorithmCreateFunc();
	btAlignedFree(f);
}
}  // namespace

btSoftBodyRigidBodyCollisionConfiguration::btSoftBodyRigidBodyCollisionConfiguration(
    const btDefaultCollisionConstructionInfo& constructionInfo)
    : btDefaultCollisionConfiguration(constructionInfo)
{
	m_softSoftCreateFunc = makeCreateFunc<btSoftSoftCollisionAlgorithm::CreateFunc>(false);
	m_softRigidConvexCreateFunc = makeCreateFunc<btSoftRigidCollisionAlgorithm::CreateFunc>(false);
	m_swappedSoftRigidConvexCreateFunc = makeCreateFunc<btSoftRigidCollisionAlgorithm::CreateFunc>(true);
	m_softRigidConcaveCreateFunc = makeCreateFunc<btSoftBodyConcaveCollisionAlgorithm::CreateFunc>(false);
	m_swappedSoftRigidConcaveCreateFunc = makeCreateFunc<btSoftBodyConcaveCollisionAlgorithm::SwappedCreateFunc>(true);
}

btSoftBodyRigidBodyCollisionConfiguration::~btSoftBodyRigidBodyCollisionConfiguration()
{
	destroyCreateFunc(m_softSoftCreateFunc);
	destroyCreateFunc(m_softRigidConvexCreateFunc);
	destroyCreateFunc(m_swappedSoftRigidConvexCreateFunc);
	destroyCreateFunc(m_softRigidConcaveCreateFunc);
	destroyCreateFunc(m_swappedSoftRigidConcaveCreateFunc);
}

btCollisionAlgorithmCreateFunc* btSoftBodyRigidBodyCollisionConfiguration::getCollisionAlgorithmCreateFunc(
    int proxyType0, int proxyType1)
{
	const bool soft0 = proxyType0 == SOFTBODY_SHAPE_PROXYTYPE, soft1 = proxyType1 == SOFTBODY_SHAPE_PROXYTYPE;
	if (soft0 && soft1) return m_softSoftCreateFunc;
	if (soft0)
		return btBroadphaseProxy::isConvex(proxyType1) ? m_softRigidConvexCreateFunc : m_softRigidConcaveCreateFunc;
	if (soft1)
		return btBroadphaseProxy::isConvex(proxyType0) ? m_swappedSoftRigidConvexCreateFunc
		                                               : m_swappedSoftRigidConcaveCreateFunc;
	return btDefaultCollisionConfiguration::getCollisionAlgorithmCreateFunc(proxyType0, proxyType1);
}
