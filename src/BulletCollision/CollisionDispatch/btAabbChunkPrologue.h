// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_AABB_CHUNK_PROLOGUE_H
#define CALIBER_AABB_CHUNK_PROLOGUE_H

class btCollisionWorld;

namespace caliber
{
/// Work that must be done on a collision world's objects before their boxes are computed, and that each
/// object does on its own (it reads and writes only that object), so that the world's next updateAabbs can
/// do it chunk by chunk just before the boxes of the same chunk, on the thread that computes them. The
/// dynamics world hands its prediction (predictUnconstraintMotion) over this way: in the box loop whose
/// task 0 makes the broadphase's tree moves in order (docs/threading.md), the other threads then predict
/// and compute the boxes of the later objects while the tree moves run, instead of predicting in a loop
/// of their own before it.
class AabbChunkPrologue
{
public:
	virtual ~AabbChunkPrologue() {}
	/// The work for the world's objects [objectBegin, objectEnd) (indices of its object array). Called once
	/// for each chunk of a partition of [0, number of objects), from any thread, chunks in any order and at
	/// once; each object's work must depend on that object only.
	virtual void prepareObjects(int objectBegin, int objectEnd) const = 0;
	/// The work for every object, called on the calling thread instead of prepareObjects when updateAabbs
	/// takes a path without chunks (it may run a parallel loop of its own).
	virtual void prepareAll() const = 0;
};

/// Makes the next updateAabbs of `world` on this thread do `prologue` (exactly once: chunk by chunk, or by
/// prepareAll before anything else), then forget it. Null forgets a prologue that was set. The caller must
/// call updateAabbs (or performDiscreteCollisionDetection) of that world next on this thread, while
/// `prologue` lives, and must do the work itself when takeAabbChunkPrologue says it was not taken.
void setAabbChunkPrologue(const btCollisionWorld* world, const AabbChunkPrologue* prologue);

/// True when a prologue set for `world` was taken by an updateAabbs since setAabbChunkPrologue (and clears
/// what was set either way).
bool takeAabbChunkPrologueDone(const btCollisionWorld* world);
}  // namespace caliber

#endif
