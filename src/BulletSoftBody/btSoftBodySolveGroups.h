// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SOFT_BODY_SOLVE_GROUPS_H
#define CALIBER_SOFT_BODY_SOLVE_GROUPS_H

// The soft bodies' position solves on the task scheduler (docs/soft-bodies.md, "Threads"). A body's solve
// writes its own nodes and, through its contacts, anchors and joints, the rigid bodies it can move, the nodes
// of other soft bodies' faces (VF_SS) and other bodies' clusters (CL_SS, joints). Bodies linked so, directly
// or through others, form a group; groups share nothing a solve writes, so they run on different threads
// while each group's bodies are solved in the world's order, as on one thread: the same bits at any thread
// count and any split of the loop.

#include "BulletSoftBody/btSoftBody.h"
#include "LinearMath/btAlignedObjectArray.h"

namespace caliber
{
/// The groups of a step, and the scratch that finds them (kept from step to step: no allocation once
/// the sizes settle).
struct SoftSolveGroups
{
	btAlignedObjectArray<int> members;  // the bodies' indices, group after group, ascending in each group
	btAlignedObjectArray<int> starts;   // group g is members[starts[g], starts[g + 1])
	int groupCount() const { return starts.size() > 0 ? starts.size() - 1 : 0; }

	// scratch
	struct Link
	{
		const void* object;  // what a solve writes besides its own body: a rigid body or another soft body
		int body;            // the index of the body whose solve writes it
	};
	struct FaceRange
	{
		const btSoftBody::Face *begin, *end;
		const btSoftBody* body;
	};
	btAlignedObjectArray<Link> links;
	btAlignedObjectArray<FaceRange> faceRanges;
	btAlignedObjectArray<int> parent, groupOf, counts;
};

/// Finds the groups of bodies[i] for the i with solve[i] set (the others are left out). count > 0.
void findSoftSolveGroups(btSoftBody* const* bodies, const char* solve, int count, SoftSolveGroups& groups);
}  // namespace caliber

#endif  // CALIBER_SOFT_BODY_SOLVE_GROUPS_H
