// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_WORLD_SNAPSHOT_INTERNAL_H
#define CALIBER_WORLD_SNAPSHOT_INTERNAL_H

// The parts of a world snapshot (docs/serialization.md, "Snapshot and restore"): btWorldSnapshot.cpp
// writes the header, the world, the objects, the joints and the solver and drives save, restore and
// compare; btWorldSnapshotCollision.cpp writes the broadphase, the pairs with their collision
// algorithms, and the contact manifolds.

#include "BulletDynamics/Dynamics/btWorldSnapshotStream.h"
#include "LinearMath/btAlignedObjectArray.h"

class btDiscreteDynamicsWorld;

namespace caliber
{
namespace snapshot
{
/// Writes the broadphase, pairs and manifolds; false (with the reason) for a world whose collision
/// state the snapshot cannot hold.
bool saveCollisionState(btDiscreteDynamicsWorld& world, SnapshotWriter& out, char* error, size_t errorSize);

/// Checks that world's collision state can be replaced (the parts it needs are supported); false with
/// the reason otherwise. Touches nothing.
bool collisionStateReplaceable(btDiscreteDynamicsWorld& world, char* error, size_t errorSize);

/// Reads the broadphase, pairs and manifolds. A dry run only checks them against world; otherwise
/// world's pairs, algorithms and manifolds are rebuilt as the snapshot has them. A failure while
/// applying leaves world's collision state incomplete (the caller restores its backup).
bool readCollisionState(btDiscreteDynamicsWorld& world, SnapshotReader& in);
}  // namespace snapshot
}  // namespace caliber

#endif  // CALIBER_WORLD_SNAPSHOT_INTERNAL_H
