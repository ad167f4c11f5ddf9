// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SOFTBODY_RIGIDBODY_COLLISION_CONFIGURATION
#define BT_SOFTBODY_RIGIDBODY_COLLISION_CONFIGURATION

/// btSoftBodyRigidBodyCollisionConfiguration: the default configuration plus the soft body pairs.

#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"

/// Adds the algorithms of soft-rigid pairs (btSoftRigidCollisionAlgorithm) and soft-soft pairs
/// (btSoftSoftCollisionAlgorithm) to btDefaultCollisionConfiguration.
class btSoftBodyRigidBodyCollisionConfiguration : public btDefaultCollisionConfiguration
{
	btCollisionAlgorithmCreateFunc* m_softSoftCreateFunc;
	btCollisionAlgorithmCreateFunc* m_softRigidConvexCreateFunc;
	btCollisionAlgorithmCreateFunc* m_swappedSoftRigidConvexCreateFunc;
	btCollisionAlgorithmCreateFunc* m_softRigidConcaveCreateFunc;
	btCollisionAlgorithmCreateFunc* m_swappedSoftRigidConcaveCreateFunc;

public:
	/// The default configuration's pools and algorithms, plus the soft body ones.
	btSoftBodyRigidBodyCollisionConfiguration(
	    const btDefaultCollisionConstructionInfo& constructionInfo = btDefaultCollisionConstructionInfo());
	virtual ~btSoftBodyRigidBodyCollisionConfiguration();

	/// The soft body algorithms for pairs with a soft body, the default ones otherwise.
	virtual btCollisionAlgorithmCreateFunc* getCollisionAlgorithmCreateFunc(int proxyType0, int proxyType1);
};

#endif  // BT_SOFTBODY_RIGIDBODY_COLLISION_CONFIGURATION
