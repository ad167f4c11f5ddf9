// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_PAIR_POSE_CACHE_H
#define CALIBER_PAIR_POSE_CACHE_H

// The contact cache of a convex pair (in the spirit of Jolt's body pair cache): when no point of one
// body has moved by more than a small distance relative to the other since their contacts were last
// found, and the pair is not closing faster than that per step, the contacts found then are the
// contacts now. Refreshing the manifold (the same points at their new world positions, with their new
// distances) then replaces the narrowphase. The motion is measured from the pose of the last full
// detection, not the last step's, so small motions cannot add up unseen. See include/Caliber/ContactCache.h.

#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h"
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "LinearMath/btTransform.h"

namespace caliber
{
/// The process-wide distance (include/Caliber/ContactCache.h); 0 when the cache is off.
btScalar contactCacheDistance();

/// Sizes of the cached algorithms the factories make (the collision configuration sizes its pool for them).
int cachedBoxBoxAlgorithmSize();
int cachedConvexConvexAlgorithmSize();

/// Gives the points of manifold the material values a detection gives the points it reports (combined
/// friction, restitution, rolling and spinning friction, contact stiffness and damping, the friction
/// anchor flag), from the objects as they are now: a cached pair takes a material change at once.
/// object0 and object1 in the order of the algorithm's wrappers, as btManifoldResult::addContactPoint.
void refreshPointMaterials(btPersistentManifold& manifold, const btCollisionObject* object0,
                           const btCollisionObject* object1);

/// What the cache knows of the two shapes: their boxes in their own frames (margins and scaling
/// included). A shape that was resized, rescaled or given another margin no longer matches, and the pair
/// is detected again.
struct PairShapes
{
	btVector3 min0{0, 0, 0}, max0{0, 0, 0}, min1{0, 0, 0}, max1{0, 0, 0};

	bool operator==(const PairShapes& o) const
	{
#if defined(BT_USE_SSE)
		// btVector3's == on x, y and z of all four at once (the same IEEE comparisons, w ignored): the pair
		// loop asks this of every cached pair every step.
		const __m128 equal = _mm_and_ps(
		    _mm_and_ps(_mm_cmpeq_ps(min0.get128(), o.min0.get128()), _mm_cmpeq_ps(max0.get128(), o.max0.get128())),
		    _mm_and_ps(_mm_cmpeq_ps(min1.get128(), o.min1.get128()), _mm_cmpeq_ps(max1.get128(), o.max1.get128())));
		return (_mm_movemask_ps(equal) & 7) == 7;
#else
		return min0 == o.min0 && max0 == o.max0 && min1 == o.min1 && max1 == o.max1;
#endif
	}
	/// How far from its origin a point of shape 1 can be.
	btScalar extent1() const
	{
		const btVector3 far(btMax(btFabs(min1.x()), btFabs(max1.x())), btMax(btFabs(min1.y()), btFabs(max1.y())),
		                    btMax(btFabs(min1.z()), btFabs(max1.z())));
		return far.length();
	}
};

/// The pose of body 1 in body 0's frame at the last full detection, the reach (speculative distance) the
/// detection used, and the two shapes then.
struct PairPoseCache
{
	// Zero until stored, so that a snapshot of an unused cache has defined bytes.
	btVector3 offset{0, 0, 0};                                                                ///< R0^T (p1 - p0)
	btVector3 turnColumns[3] = {btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(0, 0, 0)};  ///< columns of R0^T R1
	btScalar reach = btScalar(0);
	PairShapes shapes;
	int points = 0;  ///< the manifold's points after the detection
	bool valid = false;

	/// True when the cached contacts still hold: every point of body 1 moved less than the cache distance
	/// relative to body 0, and this query's reach is within the larger of the cached reach and that
	/// distance (a pair closing faster than that gets a full detection, which may add speculative points).
	/// A manifold that lost or gained points since (a refresh dropped one that drifted apart, the program
	/// cleared it) is detected again too.
	/// distance is contactCacheDistance(), read once by the caller.
	bool covers(const btTransform& t0, const btTransform& t1, btScalar queryReach, const PairShapes& shapesNow,
	            int pointsNow, btScalar distance) const
	{
		if (!valid || pointsNow != points || !(shapesNow == shapes)) return false;
		if (!(queryReach <= btMax(reach, distance))) return false;
		const btMatrix3x3& r0 = t0.getBasis();
		const btMatrix3x3& r1 = t1.getBasis();
		// A point q of body 1 (in its frame) sits at offset + sum_k q_k column_k in body 0's frame, so it
		// moved by at most |d offset| + sum_k |q_k| |d column_k| <= |d offset| + extent1 |(|d column_k|)_k|.
		const btScalar moved = ((t1.getOrigin() - t0.getOrigin()) * r0 - offset).length();
		btScalar turn2 = btScalar(0);
		for (int k = 0; k < 3; ++k) turn2 += (r1.getColumn(k) * r0 - turnColumns[k]).length2();
		return moved + shapes.extent1() * btSqrt(turn2) <= distance;
	}
	/// Remembers the pose, reach, shapes and point count of a full detection.
	void store(const btTransform& t0, const btTransform& t1, btScalar queryReach, const PairShapes& shapesNow,
	           int pointsNow)
	{
		shapes = shapesNow;
		points = pointsNow;
		const btMatrix3x3& r0 = t0.getBasis();
		const btMatrix3x3& r1 = t1.getBasis();
		offset = (t1.getOrigin() - t0.getOrigin()) * r0;
		for (int k = 0; k < 3; ++k) turnColumns[k] = r1.getColumn(k) * r0;
		reach = queryReach;
		valid = true;
	}
};

/// The cached step of an algorithm that owns manifold: when cache covers the pair (poses of the query's
/// wrappers, its reach, the shapes, the manifold's point count), gives the points their current materials,
/// refreshes them and returns true; otherwise returns false, and the caller detects and stores. distance is
/// contactCacheDistance(), read once per query by the caller (each read was a call and spilled the caller's registers).
inline bool keepCachedContacts(const PairPoseCache& cache, btPersistentManifold* manifold, const PairShapes& shapes,
                               const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
                               btManifoldResult* resultOut, btScalar distance)
{
	// A non-finite pose never passes the test: the full path reports it.
	if (!manifold || !cache.covers(body0Wrap->getWorldTransform(), body1Wrap->getWorldTransform(),
	                               resultOut->m_closestPointDistanceThreshold, shapes, manifold->getNumContacts(),
	                               distance))
		return false;
	resultOut->setPersistentManifold(manifold);
	refreshPointMaterials(*manifold, body0Wrap->getCollisionObject(), body1Wrap->getCollisionObject());
	resultOut->refreshContactPoints();
	return true;
}

/// Whether a pair's reach (how far it may close this step) lets the cache keep or remember its contacts: a
/// pair that may close more than four cache distances moves too fast for its contacts to hold at the next
/// step, so it is detected and not remembered (a pair in free fall pays nothing for the cache). Pairs a
/// little faster than the distance are remembered: the solver often stops them within the step.
inline bool slowEnoughForContactCache(btScalar reach, btScalar distance) { return reach <= btScalar(4) * distance; }

/// Whether a pair may use the cache at all: the cache is on, the algorithm owns its manifold (a shared
/// one collects other queries' points too), and no contact-added callback asks to see every point of
/// every step (CF_CUSTOM_MATERIAL_CALLBACK).
inline bool pairMayUseContactCache(bool ownsManifold, const btCollisionObjectWrapper* body0Wrap,
                                   const btCollisionObjectWrapper* body1Wrap, btScalar distance)
{
	if (!ownsManifold || !(distance > btScalar(0))) return false;
	const int flags =
	    body0Wrap->getCollisionObject()->getCollisionFlags() | body1Wrap->getCollisionObject()->getCollisionFlags();
	return !(flags & btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
}
}  // namespace caliber

#endif  // CALIBER_PAIR_POSE_CACHE_H
