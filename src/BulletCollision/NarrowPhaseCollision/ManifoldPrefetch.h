// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_MANIFOLD_PREFETCH_H
#define CALIBER_MANIFOLD_PREFETCH_H

// Internal: cache prefetches of a manifold by address, for loops that walk manifolds scattered over the
// heap (the pair loop, the solver's contact conversion). btPersistentManifold keeps its point cache
// first and its point count right after the two body pointers; its constructors assert that these
// addresses agree with the layout assumed here.

#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"

namespace caliber
{
// The point cache follows the btTypedObject base, rounded up to the points' alignment.
constexpr size_t kManifoldPointsOffset =
    (sizeof(btTypedObject) + alignof(btManifoldPoint) - 1) / alignof(btManifoldPoint) * alignof(btManifoldPoint);

// First byte of the manifold's point cache.
inline const char* manifoldPointBytes(const btPersistentManifold* manifold)
{
	return reinterpret_cast<const char*>(manifold) + kManifoldPointsOffset;
}

// The point count, which follows the full point cache and the two body pointers.
inline const char* manifoldHeaderBytes(const btPersistentManifold* manifold)
{
	return manifoldPointBytes(manifold) + MANIFOLD_CACHE_SIZE * sizeof(btManifoldPoint) +
	       2 * sizeof(const btCollisionObject*);
}

// Requests the cache line with the point count, bodies and thresholds (never faults). Loops call it a
// few manifolds ahead, then prefetchManifoldPoints closer, once the count has arrived.
inline void prefetchManifoldHeader(const btPersistentManifold* manifold)
{
#if defined(__GNUC__)
	__builtin_prefetch(manifoldHeaderBytes(manifold));
#else
	(void)manifold;
#endif
}

// Requests the cache lines of the points the manifold holds (none when it is empty). Reads the count.
inline void prefetchManifoldPoints(const btPersistentManifold* manifold)
{
#if defined(__GNUC__)
	const char* first = manifoldPointBytes(manifold);
	const char* end = first + manifold->getNumContacts() * sizeof(btManifoldPoint);
	for (const char* line = first; line < end; line += 64) __builtin_prefetch(line);
#else
	(void)manifold;
#endif
}

// Requests every cache line of the manifold. An algorithm calls it on entry: the manifold is usually cold
// (a thousand manifolds do not stay in cache from one step to the next) and is needed after the shapes
// and transforms are read, so the misses overlap with that work instead of following each other.
inline void prefetchWholeManifold(const btPersistentManifold* manifold)
{
#if defined(__GNUC__)
	const char* bytes = reinterpret_cast<const char*>(manifold);
	for (int offset = 0; offset < int(sizeof(btPersistentManifold)); offset += 64) __builtin_prefetch(bytes + offset);
#else
	(void)manifold;
#endif
}
}  // namespace caliber

#endif  // CALIBER_MANIFOLD_PREFETCH_H
