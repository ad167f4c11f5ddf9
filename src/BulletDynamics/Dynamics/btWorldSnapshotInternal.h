// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_WORLD_SNAPSHOT_INTERNAL_H
#define CALIBER_WORLD_SNAPSHOT_INTERNAL_H

// The parts of a world snapshot (docs/serialization.md, "Snapshot and restore"): btWorldSnapshot.cpp
// writes the header, the world, the objects, the joints and the solver and drives save, restore and
// compare; btWorldSnapshotCollision.cpp writes the broadphase, the pairs with their collision
// algorithms, and the contact manifolds.

#include "BulletDynamics/Dynamics/btWorldSnapshotStream.h"
#include "Caliber/WorldSnapshot.h"
#include "LinearMath/btAlignedObjectArray.h"

class btDiscreteDynamicsWorld;
class btCollisionObject;
class btCollisionAlgorithm;

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

/// What a layer above BulletDynamics adds to a snapshot (the soft bodies: src/BulletSoftBody/
/// btSoftBodySnapshot.cpp), which this layer cannot name: objects of its own internal type (their collision
/// object fields are held as every object's), collision algorithms that keep no state between steps (made
/// again by the dispatcher on restore), and a part of its own at the end of the snapshot.
struct SnapshotExtension
{
	/// True for objects whose remaining state save and read hold.
	bool (*acceptsObject)(const btCollisionObject& object);
	/// True for algorithms with no state between steps.
	bool (*statelessAlgorithm)(const btCollisionAlgorithm* algorithm);
	/// Writes the extension's part; false (with the reason) for a world it cannot hold.
	bool (*save)(btDiscreteDynamicsWorld& world, SnapshotWriter& out, char* error, size_t errorSize);
	/// Reads it: a dry run checks it against world, an applying run writes it.
	void (*read)(btDiscreteDynamicsWorld& world, SnapshotReader& in);
};

/// The extension of the snapshot call in progress on this thread (0 for the plain world functions).
const SnapshotExtension* currentExtension();
}  // namespace snapshot

/// saveWorldState, restoreWorldState and compareWorldState with an extension (0: the plain functions).
bool saveWorldStateWith(const btDiscreteDynamicsWorld& world, btAlignedObjectArray<unsigned char>& buffer,
                        SnapshotError* error, const snapshot::SnapshotExtension* extension);
bool restoreWorldStateWith(btDiscreteDynamicsWorld& world, const unsigned char* data, size_t size, SnapshotError* error,
                           const snapshot::SnapshotExtension* extension);
bool compareWorldStateWith(const btDiscreteDynamicsWorld& world, const unsigned char* data, size_t size,
                           SnapshotDifference* difference, SnapshotError* error,
                           const snapshot::SnapshotExtension* extension);
}  // namespace caliber

#endif  // CALIBER_WORLD_SNAPSHOT_INTERNAL_H
