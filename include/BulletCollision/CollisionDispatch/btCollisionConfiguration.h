// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_COLLISION_CONFIGURATION
#define BT_COLLISION_CONFIGURATION

/// btCollisionConfiguration: the memory pools and the algorithm table a dispatcher uses.

struct btCollisionAlgorithmCreateFunc;
class btPoolAllocator;

/// Supplies the pools for manifolds and algorithms, and the algorithm factory of each pair of shape
/// types (for contact generation and for closest-point queries).
class btCollisionConfiguration
{
public:
	/// Configurations are deleted through base pointers.
	virtual ~btCollisionConfiguration() {}

	/// Pool of persistent manifolds.
	virtual btPoolAllocator* getPersistentManifoldPool() = 0;
	/// Pool of collision algorithms.
	virtual btPoolAllocator* getCollisionAlgorithmPool() = 0;
	/// Factory of the contact algorithm for shapes of types proxyType0 and proxyType1.
	virtual btCollisionAlgorithmCreateFunc* getCollisionAlgorithmCreateFunc(int proxyType0, int proxyType1) = 0;
	/// Factory of the closest-points algorithm for shapes of types proxyType0 and proxyType1.
	virtual btCollisionAlgorithmCreateFunc* getClosestPointsAlgorithmCreateFunc(int proxyType0, int proxyType1) = 0;
};

#endif  // BT_COLLISION_CONFIGURATION
