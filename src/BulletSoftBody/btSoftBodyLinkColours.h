// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SOFT_BODY_LINK_COLOURS_H
#define CALIBER_SOFT_BODY_LINK_COLOURS_H

// The order of the link sweeps. The links are cut into blocks of kLinkBlock consecutive links (in
// index order, so a sweep still carries a correction along a chain within a block as the serial sweep
// does), and the blocks are coloured so that no two blocks of a colour share a node: a colour's blocks
// can be solved at once on the task scheduler and give the bits of one thread. The colouring is greedy
// in block order and depends on the links alone, never on the thread count, and the serial sweep uses
// the same order, so every thread count (and the single-threaded library) gives the same result. A
// body with at most kLinkBlock links is one block: its sweep is the plain index order. Caliber-only
// state, in a side table keyed by the body.

#include <cstdint>

#include "BulletSoftBody/btSoftBody.h"
#include "LinearMath/btAlignedObjectArray.h"

namespace caliber
{
/// Links per block (a fixed number: the order must not depend on the thread count).
const int kLinkBlock = 1024;

struct SoftLinkColours
{
	btAlignedObjectArray<int> blocks;  // block indices, colour by colour (in block order inside a colour)
	btAlignedObjectArray<int> start;   // colour c is blocks[start[c], start[c + 1])
	// What the colouring was built from: rebuilt when any of it changes.
	int nodeCount = -1;
	int linkCount = -1;
	uint64_t signature = 0;
};

/// The body's link colouring, rebuilt when its links' nodes changed (checked when refresh is set, or when
/// the counts changed; this packs the links, see btSoftBodyLinkSweep.h).
SoftLinkColours& softLinkColours(btSoftBody& body, bool refresh = true);
/// The same check with the fingerprint of the links' node indices given (SoftLinkSweep::nodeSignature of
/// the step's packing): once per step, in predictMotion.
SoftLinkColours& refreshSoftLinkColours(btSoftBody& body, uint64_t nodeSignature);
/// Forgets the body's colouring (its destructor).
void releaseSoftLinkColours(const btSoftBody& body);

}  // namespace caliber

#endif  // CALIBER_SOFT_BODY_LINK_COLOURS_H
