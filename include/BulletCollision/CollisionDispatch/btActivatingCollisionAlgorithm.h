// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_ACTIVATING_COLLISION_ALGORITHM_H
#define BT_ACTIVATING_COLLISION_ALGORITHM_H

/// btActivatingCollisionAlgorithm: the base of the algorithms that produce contacts between bodies.

#include "BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h"

/// Base class of the contact-producing algorithms (Bullet's hook for waking bodies; activation itself is
/// done by the world's island manager).
class btActivatingCollisionAlgorithm : public btCollisionAlgorithm
{
public:
	/// An algorithm bound to ci's dispatcher.
	btActivatingCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci);
	/// An algorithm bound to ci's dispatcher for the given pair.
	btActivatingCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
	                               const btCollisionObjectWrapper* body0Wrap,
	                               const btCollisionObjectWrapper* body1Wrap);
	/// Algorithms are destroyed through base pointers.
	~btActivatingCollisionAlgorithm() override;
};

#endif  // BT_ACTIVATING_COLLISION_ALGORITHM_H
