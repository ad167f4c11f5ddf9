// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_BVH_MESH_CAST_H
#define CALIBER_BVH_MESH_CAST_H

// Internal: the ray and box-cast path of btBvhTriangleMeshShape with an optional upper bound on the
// fraction. The world's ray test passes its callback's closest hit fraction, so the tree walk skips the
// boxes beyond the closest hit so far; btBvhTriangleMeshShape::performRaycast and performConvexcast pass none.

#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"

namespace caliber
{
// As btBvhTriangleMeshShape::performConvexcast (a ray when boxMin == boxMax == 0); with maxFraction, tree
// boxes the sweep only reaches beyond *maxFraction are skipped (read at every box, so the callback may
// lower it as it reports closer hits).
void castAgainstBvhMesh(btBvhTriangleMeshShape& mesh, btTriangleCallback* callback, const btVector3& boxSource,
                        const btVector3& boxTarget, const btVector3& boxMin, const btVector3& boxMax,
                        const btScalar* maxFraction);
}  // namespace caliber

#endif  // CALIBER_BVH_MESH_CAST_H
