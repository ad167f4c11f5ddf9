// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_MANIFOLD_OWNERS_H
#define CALIBER_MANIFOLD_OWNERS_H

// Caliber-only: which thread last wrote each manifold of a multithreaded dispatcher, kept from step to
// step beside btCollisionDispatcherMt (Bullet's class declares no such state). The Mt solver notes the
// thread that writes a manifold's impulses back; the next narrowphase gives each pair's chunk to that
// thread where it can, so the manifold's points are still in that core's cache (docs/threading.md, "The
// narrowphase"). Only a hint: which thread runs a pair never changes a result, and a stale or unknown
// owner only costs cache misses.

#include "LinearMath/btScalar.h"

class btDispatcher;
class btPersistentManifold;

namespace caliber
{
/// Turns the narrowphase's affinity on or off (process-wide; off by default). On: the Mt solver notes the
/// owners and the parallel narrowphase lays its pairs out by them. Off: the pairs go in pair order and
/// nothing is noted. Results are the same either way. Off by default because on the shared 2-core host of
/// the sixteenth session it made stack1000's narrowphase slower at two threads (docs/threading.md,
/// "Affinity, the narrowphase"). Set it between steps.
void setNarrowphaseAffinity(bool on);
bool narrowphaseAffinity();

/// No owner known (a new manifold, one solved outside the Mt solver's batches, or a thread index of 255
/// or more).
const unsigned char kNoManifoldOwner = 0xff;

/// Writes owners for one solve; made on the solving thread before the write-back's loop, then used from
/// the loop's threads (each manifold by one thread only).
struct ManifoldOwnerWriter
{
	unsigned char* owners = nullptr;              // per manifold index of the dispatcher
	btPersistentManifold* const* live = nullptr;  // the dispatcher's manifolds, to check an index
	int count = 0;

	explicit operator bool() const { return owners != nullptr; }
	/// Notes thread as manifold's owner if manifold is one of the dispatcher's (a user's own manifold
	/// passed to the solver is left alone).
	void note(const btPersistentManifold* manifold, int index, unsigned int thread) const
	{
		if (index < 0 || index >= count || live[index] != manifold) return;
		// Written only when it changes: two threads note manifolds whose bytes share cache lines, and in
		// the steady state a manifold's writer stays the same from step to step.
		const unsigned char owner = thread < kNoManifoldOwner ? (unsigned char)thread : kNoManifoldOwner;
		if (owners[index] != owner) owners[index] = owner;
	}
};

/// The writer for dispatcher's owner table; empty (nothing noted) when the affinity is off or dispatcher
/// keeps no table (it is not a btCollisionDispatcherMt, or none of its narrowphases ran on threads yet).
/// One look-up per call.
ManifoldOwnerWriter manifoldOwnerWriter(btDispatcher* dispatcher);

/// The thread noted as manifold's owner in dispatcher's table, or -1 when none is known (for tests and
/// diagnostics).
int manifoldOwner(const btDispatcher* dispatcher, const btPersistentManifold* manifold);
/// Drops dispatcher's table (its destructor).
void releaseManifoldOwners(const btDispatcher* dispatcher);
}  // namespace caliber

#endif  // CALIBER_MANIFOLD_OWNERS_H
