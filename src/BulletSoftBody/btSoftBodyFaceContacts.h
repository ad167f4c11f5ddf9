// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SOFT_BODY_FACE_CONTACTS_H
#define CALIBER_SOFT_BODY_FACE_CONTACTS_H

// Rigid corners against soft faces: node contacts alone let a sharp corner pass between the nodes of a
// coarse cloth, so each corner of a polyhedral rigid shape (a box: its corners, points along its edges
// and its faces' centres) that comes within the margin of a face this step is kept on the side of the
// face it started on. Found with the node contacts (btSoftBodyCollision.cpp), solved with them
// (btSoftBodySolve.cpp). Caliber-only state, kept in a side table keyed by the body (btSoftBody
// declares what Bullet's does).

#include "BulletSoftBody/btSoftBody.h"
#include "LinearMath/btAlignedObjectArray.h"

namespace caliber
{
struct SoftFaceContact
{
	btSoftBody::Face* face;
	const btCollisionObject* object;
	btVector3 local;     // the corner (or box point), in the object's frame
	btVector3 weights;   // barycentric weights of the face point the corner is held against
	btScalar side;       // +1 or -1: the side of the face (along its winding normal) the corner is kept on
	btScalar thickness;  // distance kept between corner and face (the shape's margin outside its corners)
	btScalar hardness;   // fraction of the error closed per solve (1 against static and kinematic objects)
};

struct SoftFaceContacts
{
	btAlignedObjectArray<SoftFaceContact> contacts;  // this step's
	// The faces' boxes over the step (start and predicted node positions), built by the first pair of
	// a step with points near the body and bucketed by their low x, so that each pair scans only the
	// faces in its own x range.
	struct FaceBox
	{
		btVector3 lo, hi;
		int face;
	};
	btAlignedObjectArray<FaceBox> boxes;    // by bucket
	btAlignedObjectArray<int> bucketStart;  // bucket i holds boxes[bucketStart[i] .. bucketStart[i + 1])
	btAlignedObjectArray<FaceBox> scratch;  // by face, while bucketing
	btAlignedObjectArray<int> fill;         // scratch
	btScalar widest = 0;                    // the widest face box along x
	btScalar minX = 0, cell = 1;            // bucket i starts at minX + i cell
	/// The bucket of low x x, clamped to 0 .. buckets - 1.
	int bucketOf(btScalar x, int buckets) const
	{
		const btScalar f = (x - minX) / cell;
		if (!(f > 0)) return 0;  // also NaN
		return f >= btScalar(buckets) ? buckets - 1 : int(f);
	}
	bool boxesValid = false;
};

/// The body's face contacts (cleared in predictMotion, filled by the collision pass).
SoftFaceContacts& softFaceContacts(const btSoftBody& body);
/// Forgets the body's face contacts (its destructor).
void releaseSoftFaceContacts(const btSoftBody& body);
/// Forgets the lists the body's node contacts are gathered in by chunks (its destructor).
void releaseNodeContactChunks(const btSoftBody& body);
}  // namespace caliber

#endif  // CALIBER_SOFT_BODY_FACE_CONTACTS_H
