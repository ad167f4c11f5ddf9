// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "Caliber/ContactCache.h"

#include <atomic>

#include "BulletCollision/CollisionDispatch/btPairPoseCache.h"
#include "LinearMath/btWarningHook.h"

namespace caliber
{
namespace
{
// Read once per pair and step: a relaxed atomic, so that setting it while another thread steps is no race.
std::atomic<btScalar> g_distance{btScalar(0.001)};
}  // namespace

btScalar contactCacheDistance() { return g_distance.load(std::memory_order_relaxed); }

void setContactCacheDistance(btScalar distance)
{
	const bool valid = distance >= btScalar(0) && distance < SIMD_INFINITY;  // false for NaN
	btAssert(valid && "setContactCacheDistance: the distance must be finite and not negative");
	if (!valid)
	{
		btReportWarning(
		    "caliber::setContactCacheDistance: not a finite distance >= 0; the cache distance is unchanged");
		return;
	}
	g_distance.store(distance, std::memory_order_relaxed);
}

btScalar getContactCacheDistance() { return contactCacheDistance(); }
}  // namespace caliber
