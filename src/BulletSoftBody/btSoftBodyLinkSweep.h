// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SOFT_BODY_LINK_SWEEP_H
#define CALIBER_SOFT_BODY_LINK_SWEEP_H

// The link sweeps of the position solve (XPBD distance constraints, docs/soft-bodies.md, "Links"). Each step
// packs what the sweeps read of each link (its two node indices, rest length and this step's compliance:
// 16 bytes instead of btSoftBody::Link's 80) into an array in link order, so that the sweeps, which run
// several times a step, stream a fifth of the memory (docs/soft-bodies.md, "Speed"). The same pass, the only
// one over the links in a step, fingerprints them for the tethers and the link colouring, which are rebuilt
// when what they depend on changes. The multipliers are kept only while a later sweep of the same (sub)step
// will read them. Caliber-only state, in a side table keyed by the body.

#include <cstdint>

#include "BulletSoftBody/btSoftBody.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "btSoftBodyLinkColours.h"

namespace caliber
{
struct SoftLinkSweep
{
	/// What a sweep reads of a link, in the order of m_links.
	struct PackedLink
	{
		int a, b;             // node indices
		btScalar restLength;  // m_rl
		btScalar compliance;  // this step's (the material's factor times m_c0); negative: the link is off
	};
	/// Fingerprints of the links of one block of kLinkBlock links (a fixed split: the same at any thread count).
	struct BlockSignature
	{
		uint64_t nodes;     // the node indices
		unsigned tethered;  // the rest lengths and which links are inextensible
	};
	btAlignedObjectArray<PackedLink> links;
	btAlignedObjectArray<btScalar> multipliers;  // the XPBD multipliers, while a (sub)step has sweeps left
	btAlignedObjectArray<BlockSignature> blocks;
	uint64_t nodeSignature = 0;    // what the link colouring depends on (with the node count; several blocks only)
	unsigned tetherSignature = 0;  // the links' part of what the tethers depend on
	bool unsolved = false;         // packed since the last position solve (by this step's predictMotion)
};

/// Packs the body's links for its sweeps, with the compliance of piterations sweeps a step (the material's
/// kLST may have changed since the last step), and fingerprints them. Once per step, in predictMotion.
SoftLinkSweep& packSoftLinks(btSoftBody& body, int piterations);
/// The links packed for this step's position solve: packSoftLinks's, or packed now if no prediction packed
/// them since the last solve (a solve called on its own).
SoftLinkSweep& startSoftLinkStep(btSoftBody& body, int piterations);
/// Whether links of material kLST count as inextensible for the tethers: piterations sweeps close at least
/// 99% of a lone link's error in a step (kStep = 1 - (1 - kLST)^piterations, docs/soft-bodies.md).
bool inextensibleLinks(btScalar kLST, int piterations);
/// One Gauss-Seidel sweep over the links packed by startSoftLinkStep, with the substep dt, colour by colour
/// (colours: 0 for a body of one block). first: the (sub)step's first sweep (the multipliers start at zero);
/// last: no later sweep of this (sub)step reads the multipliers.
void solveSoftLinks(btSoftBody& body, SoftLinkSweep& sweep, btScalar dt, const SoftLinkColours* colours, bool first,
                    bool last);
/// Forgets the body's packed links (its destructor).
void releaseSoftLinkSweep(const btSoftBody& body);

}  // namespace caliber

#endif  // CALIBER_SOFT_BODY_LINK_SWEEP_H
