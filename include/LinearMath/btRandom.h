// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_GEN_RANDOM_H
#define BT_GEN_RANDOM_H

/// A small global pseudo-random generator with Bullet's GEN_ names. Unlike rand(), its sequence is
/// the same on every platform and standard library, so scenes built from it are reproducible.
/// Not thread-safe (one global state), like rand().

#include "LinearMath/btScalar.h"

/// The largest value GEN_rand returns.
#define GEN_RAND_MAX 0x7fffffffu

/// The generator's state (a 64-bit PCG-style linear congruential state).
inline unsigned long long& btGenRandomState()
{
	static unsigned long long state = 0x853c49e6748fea9bull;
	return state;
}

/// Restarts the sequence from seed.
inline void GEN_srand(unsigned int seed)
{
	btGenRandomState() = 0x853c49e6748fea9bull ^ (0x9e3779b97f4a7c15ull * (seed + 1ull));
}

/// The next value in [0, GEN_RAND_MAX].
inline unsigned int GEN_rand()
{
	unsigned long long& state = btGenRandomState();
	state = state * 6364136223846793005ull + 1442695040888963407ull;
	// Output the well-mixed high bits, with an xorshift to break up the LCG's lattice.
	unsigned long long x = state;
	x ^= x >> 29;
	return static_cast<unsigned int>(x >> 33) & GEN_RAND_MAX;
}

#endif  // BT_GEN_RANDOM_H
