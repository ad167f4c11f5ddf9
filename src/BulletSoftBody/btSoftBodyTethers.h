// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SOFT_BODY_TETHERS_H
#define CALIBER_SOFT_BODY_TETHERS_H

// Tethers (long range attachments, after Kim, Chentanez and Mueller 2012): each free node reached from
// a fixed node through inextensible links (whose sweeps close 99% of their error a step) may be no farther from its
// nearest such fixed node than the shortest path of rest lengths between them. Gauss-Seidel sweeps carry a pull along a
// chain one link per sweep, so a hanging cloth or rope held only by its links stretches far beyond
// what inextensible links allow; a tether stops that in one projection per sweep. Caliber-only state,
// kept in a side table keyed by the body (btSoftBody declares what Bullet's does).

#include "BulletSoftBody/btSoftBody.h"
#include "LinearMath/btAlignedObjectArray.h"

namespace caliber
{
struct SoftBodyTethers
{
	struct Tether
	{
		int node;        // the free node
		int anchor;      // its nearest fixed node through inextensible links
		btScalar reach;  // the shortest path of rest lengths between them
	};
	btAlignedObjectArray<Tether> tethers;
	// Every link inextensible and the body closed: its volume is capped at restVolume when pressurised.
	bool inextensibleSkin = false;
	btScalar restVolume = 0;  // the volume when the state was built
	// What the tethers were built from: rebuilt when any of it changes.
	int nodeCount = -1;
	int linkCount = -1;
	unsigned signature = 0;
};

/// The body's tethers (and skin state), rebuilt when its nodes, links, fixed nodes, materials or rest
/// lengths changed (checked when refresh is set, or when the counts changed; this packs the links, see
/// btSoftBodyLinkSweep.h).
SoftBodyTethers& softBodyTethers(btSoftBody& body, bool refresh = true);
/// The same check with the links' part of the fingerprint given (SoftLinkSweep::tetherSignature of the
/// step's packing): once per step, in predictMotion.
SoftBodyTethers& refreshSoftBodyTethers(btSoftBody& body, unsigned linkSignature);
/// Forgets the body's tethers (its destructor).
void releaseSoftBodyTethers(const btSoftBody& body);
/// Pulls each tethered node back within its reach of its fixed node.
void solveTethers(btSoftBody& body, const SoftBodyTethers& tethers);

}  // namespace caliber

#endif  // CALIBER_SOFT_BODY_TETHERS_H
