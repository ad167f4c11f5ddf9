// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SOFT_BODY_NORMALS_H
#define CALIBER_SOFT_BODY_NORMALS_H

// btSoftBody::updateNormals on the task scheduler's threads (docs/soft-bodies.md, "Threads"). One thread
// adds each face's normal (its edges' cross product) to its three nodes' in face order. On several threads
// the faces' normals are computed in chunks, then each node sums those of its faces in face order (a
// node's list of faces, kept in a side table keyed by the body and rebuilt when the faces change): the
// same additions in the same order, so the same bits.

#include "BulletSoftBody/btSoftBody.h"

namespace caliber
{
/// True when updateNormals should take updateNormalsOnThreads: a body of more than 1024 faces, a task
/// scheduler of several threads, and this thread not inside a parallel loop's body (where a loop would
/// run serially: the bodies are already spread over the threads).
bool normalsOnThreads(const btSoftBody& body);
/// The node and face normals as btSoftBody::updateNormals gives them, in chunks on the task scheduler.
void updateNormalsOnThreads(btSoftBody& body);
/// Forgets the body's node-to-face lists (its destructor).
void releaseNodeFaces(const btSoftBody& body);
}  // namespace caliber

#endif  // CALIBER_SOFT_BODY_NORMALS_H
