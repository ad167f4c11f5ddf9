// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_CONTACT_COLOURING_H
#define CALIBER_CONTACT_COLOURING_H

// The colours of a large solve's contact manifolds (btSequentialImpulseConstraintSolverMt): no two
// manifolds of a colour share a moving solver body, and the colours, swept in order, meet each stack's
// contacts from the bottom up. Why that order, and the measurements: docs/threading.md, "The colouring
// of a large island".

#include <stdint.h>

#include "BulletDynamics/ConstraintSolver/btSolverBody.h"
#include "LinearMath/btAlignedObjectArray.h"

namespace caliber
{
/// Colours contact manifolds by level along gravity, reusing its arrays from solve to solve.
class ContactColouring
{
public:
	/// Colours of the level sweep (one bit each in a body's mask). A body's manifolds beyond them go to
	/// colours after these, in rounds of the same size.
	static const int kLevelColours = 32;

	/// Colours numManifolds manifolds; manifold m's solver bodies are ends[m * stride] and
	/// ends[m * stride + 1]. fixedBodyId is the entry static objects share (it joins any colour; -1 for
	/// none); up points against gravity (zero: no stacks, the order is the bodies' index order).
	void colour(const int* ends, int stride, int numManifolds, const btSolverBody* bodies, int numBodies,
	            int fixedBodyId, const btVector3& up);

	/// Colours used (some of the level colours may be empty).
	int numColours() const { return m_numColours; }
	/// Each manifold's colour, after colour().
	const btAlignedObjectArray<int>& manifoldColour() const { return m_manifoldColour; }

private:
	btAlignedObjectArray<int> m_manifoldColour;
	btAlignedObjectArray<btScalar> m_height;       // per body, along up
	btAlignedObjectArray<int> m_lower, m_upper;    // per manifold: its lower and upper end
	btAlignedObjectArray<int> m_aboveStart;        // per body (and one past): its first entry in m_above
	btAlignedObjectArray<int> m_above;             // the bodies resting on each body
	btAlignedObjectArray<int> m_depth;             // per body: 1 at the bottom of its stack, 0 unreached
	btAlignedObjectArray<int> m_queue;             // the breadth-first walk up the stacks
	btAlignedObjectArray<int> m_keyStart;          // counting sort of the manifolds by depth
	btAlignedObjectArray<int> m_order;             // the manifolds from the bottom up
	btAlignedObjectArray<uint32_t> m_taken;        // per body: the colours its manifolds took
	btAlignedObjectArray<int> m_supportLevel;      // per body: one past the level of its supports
	btAlignedObjectArray<int> m_overflow, m_next;  // manifolds left for the later rounds
	int m_numColours = 0;
};

/// The direction a solve's stacks stand in: against the gravity of its first moving body, or zero when
/// no moving body has gravity.
btVector3 solveUpDirection(const btSolverBody* bodies, int numBodies);
}  // namespace caliber

#endif
