// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_LONE_ISLAND_SINK_H
#define CALIBER_LONE_ISLAND_SINK_H

class btCollisionObject;

namespace caliber
{
/// A Caliber-only second face of a btSimulationIslandManager::IslandCallback. When the callback handed to
/// btSimulationIslandManager::processIslands also derives from this, the manager hands it runs of lone
/// islands (one awake body, no manifold) in one call instead of one processIsland call each; every other
/// island still goes to processIsland, and the calls keep the islands' order. A user's callback, which does
/// not derive from this, sees exactly Bullet's calls.
///
/// processLoneIslands(bodies, islandIds, count) must do what count calls
/// processIsland(&bodies[i], 1, 0, 0, islandIds[i]) would, in that order.
class LoneIslandSink
{
public:
	virtual ~LoneIslandSink() {}
	virtual void processLoneIslands(btCollisionObject** bodies, const int* islandIds, int count) = 0;
};
}  // namespace caliber

#endif  // CALIBER_LONE_ISLAND_SINK_H
