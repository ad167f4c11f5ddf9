// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_MESH_CONTACT_COLLECTOR_H
#define CALIBER_MESH_CONTACT_COLLECTOR_H

// Gathers the contacts a convex makes with the triangles of a mesh or height field in one frame, drops
// those on edges and vertices that continue a face the convex touches (internal edges), and hands the
// rest to the pair's result (at most 4, spanning the largest area, when it holds the face points). Internal.

#include "BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h"
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"

namespace caliber
{
struct MeshContactScratch;

/// A result the per-triangle algorithms write to in place of the pair's own (it copies its bodies,
/// manifold and reach). Storage is per thread and reused, so steady-state frames allocate nothing.
class MeshContactCollector : public btManifoldResult
{
public:
	/// Collects for the pair of `pairResult`; convexIsBody0 says which side of it the convex is. With
	/// holdFacePoints (face-clipped boxes and hulls: several points per triangle) every point waits for
	/// flush, which keeps the best 4; without, points on a triangle's face go straight to the pair's result
	/// (they are never dropped) and only edge and vertex points wait.
	MeshContactCollector(btManifoldResult& pairResult, bool convexIsBody0, btScalar triangleMargin,
	                     bool holdFacePoints);
	MeshContactCollector(const MeshContactCollector&) = delete;
	MeshContactCollector& operator=(const MeshContactCollector&) = delete;

	/// Records a point of the triangle the concave side's wrapper holds (its shape and identifiers are set
	/// by the triangle callback): normal from the triangle towards the convex, point on the triangle.
	void addContactPoint(const btVector3& normalOnBInWorld, const btVector3& pointInWorld, btScalar depth) override;
	/// Drops the internal-edge points among those held, keeps at most 4 and adds them to the pair's result,
	/// each with its triangle as the concave side (so contact callbacks see the triangle, its part and index).
	void flush(const btCollisionObjectWrapper* concaveWrap);

private:
	btManifoldResult& m_pairResult;
	MeshContactScratch& m_scratch;
	bool m_convexIsBody0;
	bool m_holdFacePoints;
	btScalar m_triangleMargin;
};
}  // namespace caliber

#endif  // CALIBER_MESH_CONTACT_COLLECTOR_H
