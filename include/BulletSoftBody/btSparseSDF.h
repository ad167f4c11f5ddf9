// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SPARSE_SDF_H
#define BT_SPARSE_SDF_H

/// btSparseSdf: Bullet's cache of signed distance fields of rigid shapes, kept for source
/// compatibility. Caliber's soft-rigid collision measures distances to the shapes directly
/// (docs/soft-bodies.md), so there is no field to cache: Initialize, Reset, GarbageCollect and
/// RemoveReferences only keep the counters programs may print, and Evaluate answers exactly.

#include "BulletCollision/CollisionShapes/btCollisionShape.h"
#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkEpa2.h"
#include "LinearMath/btTransform.h"

/// The signed-distance cache of btSoftBodyWorldInfo (CELLSIZE is Bullet's cell resolution, unused).
template <const int CELLSIZE>
struct btSparseSdf
{
	/// Edge of one voxel in Bullet's cache (kept for programs that read it).
	btScalar voxelsz;
	/// Cells allocated (always 0: nothing is cached).
	int ncells;
	/// Largest number of cells Bullet would keep (Initialize's clampCells).
	int m_clampCells;
	/// Evaluate calls since the last Reset.
	int nqueries;
	/// Cache probes since the last Reset (always 0).
	int nprobes;
	/// Garbage collections so far.
	int puid;

	btSparseSdf() : voxelsz(btScalar(0.25)), ncells(0), m_clampCells(256 * 1024), nqueries(0), nprobes(0), puid(0) {}

	/// Prepares the cache (the sizes are accepted for compatibility).
	void Initialize(int hashsize = 2383, int clampCells = 256 * 1024)
	{
		(void)hashsize;
		m_clampCells = clampCells;
		Reset();
	}
	/// Forgets every cell and counter.
	void Reset()
	{
		ncells = 0;
		nqueries = 0;
		nprobes = 0;
	}
	/// Drops cells older than lifetime frames (none exist).
	void GarbageCollect(int lifetime = 256)
	{
		(void)lifetime;
		++puid;
	}
	/// Forgets the cells of one shape; returns how many were dropped (0).
	int RemoveReferences(btCollisionShape* pcs)
	{
		(void)pcs;
		return 0;
	}
	/// Signed distance from x (in shape space) to a convex shape, less margin, with the outward normal;
	/// non-convex shapes answer SIMD_INFINITY (Caliber's soft bodies never ask).
	btScalar Evaluate(const btVector3& x, const btCollisionShape* shape, btVector3& normal, btScalar margin)
	{
		++nqueries;
		normal.setValue(0, 0, 0);
		if (!shape || !shape->isConvex()) return SIMD_INFINITY;
		btGjkEpaSolver2::sResults res;
		btTransform identity;
		identity.setIdentity();
		const btScalar d =
		    btGjkEpaSolver2::SignedDistance(x, 0, static_cast<const btConvexShape*>(shape), identity, res);
		if (d == SIMD_INFINITY) return d;
		// Outward: from the surface point towards x (towards the surface from inside).
		btVector3 n = d >= 0 ? x - res.witnesses[0] : res.witnesses[0] - x;
		if (n.length2() > SIMD_EPSILON * SIMD_EPSILON) normal = n.normalized();
		return d - margin;
	}
};

#endif  // BT_SPARSE_SDF_H
