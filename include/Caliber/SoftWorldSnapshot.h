// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SOFT_WORLD_SNAPSHOT_H
#define CALIBER_SOFT_WORLD_SNAPSHOT_H

/// Snapshot and restore of a running btSoftRigidDynamicsWorld: everything caliber::saveWorldState holds
/// (Caliber/WorldSnapshot.h) plus each soft body's state (nodes, velocities, forces, link, anchor, tetra and
/// joint solver state, pose fit, clusters, the skin's rest volume and tethers), so that stepping on from a
/// restored state is bit-identical to never having stopped. What is held, the limits and the error rules:
/// docs/serialization.md, "Soft bodies in snapshots".

#include <stddef.h>

#include "Caliber/WorldSnapshot.h"
#include "LinearMath/btAlignedObjectArray.h"

class btSoftRigidDynamicsWorld;

namespace caliber
{
/// Replaces buffer's contents with the world's state; false (with the reason, buffer empty) for a world
/// the snapshot cannot hold (as saveWorldState).
bool saveSoftWorldState(const btSoftRigidDynamicsWorld& world, btAlignedObjectArray<unsigned char>& buffer,
                        SnapshotError* error = 0);
/// Writes a snapshot back into world, which must hold the same objects, joints and soft bodies, each soft
/// body with the same nodes, links, faces, tetras, anchors, clusters and joints. False with the reason,
/// and world unchanged, otherwise (a changed topology included).
bool restoreSoftWorldState(btSoftRigidDynamicsWorld& world, const unsigned char* data, size_t size,
                           SnapshotError* error = 0);
/// Validation mode: true when world's state equals the snapshot bit for bit; otherwise the first
/// difference (section "soft body" for a soft body's state).
bool compareSoftWorldState(const btSoftRigidDynamicsWorld& world, const unsigned char* data, size_t size,
                           SnapshotDifference* difference = 0, SnapshotError* error = 0);
}  // namespace caliber

#endif  // CALIBER_SOFT_WORLD_SNAPSHOT_H
