// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_WORLD_SNAPSHOT_H
#define CALIBER_WORLD_SNAPSHOT_H

/// Snapshot and restore of a running btDiscreteDynamicsWorld (rollback, netcode): the complete state the
/// next step reads, as bytes, so that stepping on from a restored state is bit-identical to never having
/// stopped. A Caliber addition (Bullet's .bullet files hold objects, not a running state); what a
/// snapshot holds, its limits and its error rules are in docs/serialization.md, "Snapshot and restore".

#include <stddef.h>

#include "LinearMath/btAlignedObjectArray.h"

class btDiscreteDynamicsWorld;

namespace caliber
{
/// Why a save, restore or compare failed: one line of text, for example "object 12: shape type 0,
/// snapshot has 8".
struct SnapshotError
{
	char message[256];
};

/// The first field in which a world differs from a snapshot (compareWorldState).
struct SnapshotDifference
{
	/// Which part: "world", "object", "joint", "solver", "broadphase", "pair", "manifold", "header".
	char section[16];
	/// The index within the part (object index in the world's collision object array, joint index,
	/// pair index, manifold index in the dispatcher's array, ...), -1 where none applies.
	int index;
	/// The field, for example "m_linearVelocity" or "point 2 m_appliedImpulse".
	char field[64];
	/// Byte offset of the field in the snapshot.
	size_t offset;
};

/// Replaces buffer's contents with the world's state. Returns false (with the
/// reason in error when given, and buffer emptied) for a world the snapshot cannot hold: see the
/// documented limits (compound shapes, soft bodies, actions, broadphases other than btDbvtBroadphase, ...).
bool saveWorldState(const btDiscreteDynamicsWorld& world, btAlignedObjectArray<unsigned char>& buffer,
                    SnapshotError* error = 0);

/// Writes a snapshot back into world, which must hold the same objects (same types, shapes and order)
/// and joints as the world it was saved from. Returns false with the reason in error, and world
/// unchanged, for a buffer that is truncated, not a snapshot, from another build (precision, version) or
/// from a world with other objects. Never call it from inside a step other than from the internal tick
/// callbacks (docs/serialization.md).
bool restoreWorldState(btDiscreteDynamicsWorld& world, const unsigned char* data, size_t size,
                       SnapshotError* error = 0);

/// Validation mode: true when world's state equals the snapshot bit for bit; otherwise false and, when
/// difference is given, the first field that differs (or, for a buffer that is not a readable
/// snapshot, section "header" and the reason in error).
bool compareWorldState(const btDiscreteDynamicsWorld& world, const unsigned char* data, size_t size,
                       SnapshotDifference* difference = 0, SnapshotError* error = 0);
}  // namespace caliber

#endif  // CALIBER_WORLD_SNAPSHOT_H
