// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_PERSISTENT_MANIFOLD_H
#define BT_PERSISTENT_MANIFOLD_H

/// btPersistentManifold: up to four contact points between two bodies, kept across frames.

#include "BulletCollision/NarrowPhaseCollision/btManifoldPoint.h"
#include "LinearMath/btAlignedAllocator.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

class btCollisionObject;
class btPersistentManifold;
struct btCollisionObjectDoubleData;
struct btCollisionObjectFloatData;

/// Breaking threshold given to manifolds by their default constructor (0.02).
extern btScalar gContactBreakingThreshold;

/// Called with a point's user data when the point is removed; the return value is ignored.
typedef bool (*ContactDestroyedCallback)(void* userPersistentData);
/// Called for each point that survives refreshContactPoints, with the manifold's two bodies.
typedef bool (*ContactProcessedCallback)(btManifoldPoint& cp, void* body0, void* body1);
/// Called when a manifold gets its first point.
typedef void (*ContactStartedCallback)(btPersistentManifold* const& manifold);
/// Called when a manifold loses its last point.
typedef void (*ContactEndedCallback)(btPersistentManifold* const& manifold);

/// Global hook for removed points with user data (null: none).
extern ContactDestroyedCallback gContactDestroyedCallback;
/// Global hook for refreshed points (null: none).
extern ContactProcessedCallback gContactProcessedCallback;
/// Global hook for manifolds that get their first point (null: none).
extern ContactStartedCallback gContactStartedCallback;
/// Global hook for manifolds that lose their last point (null: none).
extern ContactEndedCallback gContactEndedCallback;

/// Type tags of contact manifolds (btTypedObject::m_objectType).
enum btContactManifoldTypes
{
	/// Lower bound of manifold type tags.
	MIN_CONTACT_MANIFOLD_TYPE = 1024,
	/// Tag of btPersistentManifold.
	BT_PERSISTENT_MANIFOLD_TYPE
};

/// Maximum number of points in a manifold.
#define MANIFOLD_CACHE_SIZE 4

/// A contact cache between two bodies that keeps at most MANIFOLD_CACHE_SIZE points, choosing the
/// deepest point and the largest contact area when full. Bodies are stored, never dereferenced.
ATTRIBUTE_ALIGNED16(class)
btPersistentManifold : public btTypedObject
{
	btManifoldPoint m_pointCache[MANIFOLD_CACHE_SIZE];
	const btCollisionObject* m_body0;
	const btCollisionObject* m_body1;
	int m_cachedPoints;
	btScalar m_contactBreakingThreshold;
	btScalar m_contactProcessingThreshold;

	// Index of the point to overwrite when the cache is full (Bullet's name; see the .cpp).
	int sortCachedPoints(const btManifoldPoint& pt);

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Companion id of body A, for the constraint solver.
	int m_companionIdA;
	/// Companion id of body B, for the constraint solver.
	int m_companionIdB;
	/// Index of the manifold in the dispatcher's array.
	int m_index1a;

	/// An empty manifold with no bodies, gContactBreakingThreshold and an unlimited processing threshold.
	btPersistentManifold();

	/// An empty manifold between two bodies. A negative or NaN breaking threshold asserts and is stored
	/// as 0 in release; a NaN processing threshold asserts and is stored as 0 in release.
	btPersistentManifold(const btCollisionObject* body0, const btCollisionObject* body1, int,
	                     btScalar contactBreakingThreshold, btScalar contactProcessingThreshold);

	/// First body.
	SIMD_FORCE_INLINE const btCollisionObject* getBody0() const { return m_body0; }
	/// Second body.
	SIMD_FORCE_INLINE const btCollisionObject* getBody1() const { return m_body1; }
	/// Sets both bodies (points are kept).
	void setBodies(const btCollisionObject* body0, const btCollisionObject* body1)
	{
		m_body0 = body0;
		m_body1 = body1;
	}

	/// Releases a point's user data through gContactDestroyedCallback and nulls it (when both are set).
	void clearUserCache(btManifoldPoint & pt);

	/// Number of points in the cache.
	SIMD_FORCE_INLINE int getNumContacts() const { return m_cachedPoints; }

	/// Sets the number of points; outside [0, MANIFOLD_CACHE_SIZE] asserts and is clamped in release.
	void setNumContacts(int cachedPoints);

	/// Point at index; out of range asserts, and in release the index is clamped into the cache array.
	SIMD_FORCE_INLINE const btManifoldPoint& getContactPoint(int index) const
	{
		btAssert(index >= 0 && index < m_cachedPoints);
		return m_pointCache[index < 0 ? 0 : (index < MANIFOLD_CACHE_SIZE ? index : int(MANIFOLD_CACHE_SIZE) - 1)];
	}
	/// Point at index; out of range asserts, and in release the index is clamped into the cache array.
	SIMD_FORCE_INLINE btManifoldPoint& getContactPoint(int index)
	{
		btAssert(index >= 0 && index < m_cachedPoints);
		return m_pointCache[index < 0 ? 0 : (index < MANIFOLD_CACHE_SIZE ? index : int(MANIFOLD_CACHE_SIZE) - 1)];
	}

	/// Distance beyond which points are dropped.
	btScalar getContactBreakingThreshold() const { return m_contactBreakingThreshold; }
	/// Distance below which the solver processes points.
	btScalar getContactProcessingThreshold() const { return m_contactProcessingThreshold; }
	/// Sets the breaking threshold; negative or NaN asserts and is stored as 0 in release.
	void setContactBreakingThreshold(btScalar contactBreakingThreshold);
	/// Sets the processing threshold; NaN asserts and is stored as 0 in release.
	void setContactProcessingThreshold(btScalar contactProcessingThreshold);

	/// Index of the cached point whose local point A is closest to newPoint's and strictly within the
	/// breaking threshold, or -1 (a zero threshold never matches).
	int getCacheEntry(const btManifoldPoint& newPoint) const;

	/// Adds a point and returns its index; when full, overwrites the point chosen to keep the deepest
	/// point and the largest area. isPredictive does not change the rule. A point with a NaN or infinite
	/// field asserts and, in release, is rejected: nothing is stored and -1 is returned.
	int addManifoldPoint(const btManifoldPoint& newPoint, bool isPredictive = false);

	/// Removes a point, moving the last point into its place; out of range asserts and does nothing in
	/// release.
	void removeContactPoint(int index);

	/// Overwrites a point, keeping its applied impulses, previous RHS, lifetime and user data for warm
	/// starting; out of range or a non-finite newPoint asserts and does nothing in release.
	void replaceContactPoint(const btManifoldPoint& newPoint, int insertIndex);

	/// True when the point's distance does not exceed the breaking threshold.
	bool validContactDistance(const btManifoldPoint& pt) const { return pt.m_distance1 <= m_contactBreakingThreshold; }

	/// Recomputes world positions and distances from the two transforms, ages every point by one, drops
	/// points that separated or slid sideways beyond the breaking threshold, and reports the rest to
	/// gContactProcessedCallback. A non-finite transform asserts and leaves the manifold unchanged in release.
	void refreshContactPoints(const btTransform& trA, const btTransform& trB);

	/// Removes all points (releasing their user data); calls gContactEndedCallback when it had points.
	void clearManifold();

	/// Bytes of the struct serialize() writes (btPersistentManifoldFloatData or DoubleData).
	int calculateSerializeBufferSize() const;
	/// Writes manifold (Bullet's signature: the manifold to write is passed, usually this) into dataBuffer:
	/// every point, the thresholds, companion ids and the two objects' ids; returns the struct's name.
	const char* serialize(const class btPersistentManifold* manifold, void* dataBuffer,
	                      class btSerializer* serializer) const;
	/// Replaces the points, thresholds and companion ids by those of the data (the bodies are not
	/// changed: the caller resolves them). A point count outside [0, MANIFOLD_CACHE_SIZE] or non-finite
	/// numbers are reported through btReportWarning and leave the manifold without points.
	void deSerialize(const struct btPersistentManifoldDoubleData* manifoldDataPtr);
	/// As above, from single precision data.
	void deSerialize(const struct btPersistentManifoldFloatData* manifoldDataPtr);
};

// clang-format off
/// File layout of btPersistentManifoldDoubleData in .bullet files (Bullet's struct and field names;
/// tools/makedna reads it). Bullet's declaration puts m_padding after the two thresholds, where the
/// compiler then adds padding its DNA does not describe; here m_padding comes before the doubles so
/// every offset is the sum of the sizes before it. Readers match fields by name, so files agree.
struct btPersistentManifoldDoubleData
{
	btVector3DoubleData m_pointCacheLocalPointA[4];
	btVector3DoubleData m_pointCacheLocalPointB[4];
	btVector3DoubleData m_pointCachePositionWorldOnA[4];
	btVector3DoubleData m_pointCachePositionWorldOnB[4];
	btVector3DoubleData m_pointCacheNormalWorldOnB[4];
	btVector3DoubleData m_pointCacheLateralFrictionDir1[4];
	btVector3DoubleData m_pointCacheLateralFrictionDir2[4];
	double m_pointCacheDistance[4];
	double m_pointCacheAppliedImpulse[4];
	double m_pointCachePrevRHS[4];
	double m_pointCacheCombinedFriction[4];
	double m_pointCacheCombinedRollingFriction[4];
	double m_pointCacheCombinedSpinningFriction[4];
	double m_pointCacheCombinedRestitution[4];
	int m_pointCachePartId0[4];
	int m_pointCachePartId1[4];
	int m_pointCacheIndex0[4];
	int m_pointCacheIndex1[4];
	int m_pointCacheContactPointFlags[4];
	double m_pointCacheAppliedImpulseLateral1[4];
	double m_pointCacheAppliedImpulseLateral2[4];
	double m_pointCacheContactMotion1[4];
	double m_pointCacheContactMotion2[4];
	double m_pointCacheContactCFM[4];
	double m_pointCacheCombinedContactStiffness1[4];
	double m_pointCacheContactERP[4];
	double m_pointCacheCombinedContactDamping1[4];
	double m_pointCacheFrictionCFM[4];
	int m_pointCacheLifeTime[4];
	int m_numCachedPoints;
	int m_companionIdA;
	int m_companionIdB;
	int m_index1a;
	int m_objectType;
	int m_padding;
	double m_contactBreakingThreshold;
	double m_contactProcessingThreshold;
	btCollisionObjectDoubleData* m_body0;
	btCollisionObjectDoubleData* m_body1;
};

/// File layout of btPersistentManifoldFloatData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btPersistentManifoldFloatData
{
	btVector3FloatData m_pointCacheLocalPointA[4];
	btVector3FloatData m_pointCacheLocalPointB[4];
	btVector3FloatData m_pointCachePositionWorldOnA[4];
	btVector3FloatData m_pointCachePositionWorldOnB[4];
	btVector3FloatData m_pointCacheNormalWorldOnB[4];
	btVector3FloatData m_pointCacheLateralFrictionDir1[4];
	btVector3FloatData m_pointCacheLateralFrictionDir2[4];
	float m_pointCacheDistance[4];
	float m_pointCacheAppliedImpulse[4];
	float m_pointCachePrevRHS[4];
	float m_pointCacheCombinedFriction[4];
	float m_pointCacheCombinedRollingFriction[4];
	float m_pointCacheCombinedSpinningFriction[4];
	float m_pointCacheCombinedRestitution[4];
	int m_pointCachePartId0[4];
	int m_pointCachePartId1[4];
	int m_pointCacheIndex0[4];
	int m_pointCacheIndex1[4];
	int m_pointCacheContactPointFlags[4];
	float m_pointCacheAppliedImpulseLateral1[4];
	float m_pointCacheAppliedImpulseLateral2[4];
	float m_pointCacheContactMotion1[4];
	float m_pointCacheContactMotion2[4];
	float m_pointCacheContactCFM[4];
	float m_pointCacheCombinedContactStiffness1[4];
	float m_pointCacheContactERP[4];
	float m_pointCacheCombinedContactDamping1[4];
	float m_pointCacheFrictionCFM[4];
	int m_pointCacheLifeTime[4];
	int m_numCachedPoints;
	int m_companionIdA;
	int m_companionIdB;
	int m_index1a;
	int m_objectType;
	float m_contactBreakingThreshold;
	float m_contactProcessingThreshold;
	int m_padding;
	btCollisionObjectFloatData* m_body0;
	btCollisionObjectFloatData* m_body1;
};
// clang-format on

#ifdef BT_USE_DOUBLE_PRECISION
#define btPersistentManifoldData btPersistentManifoldDoubleData
#define btPersistentManifoldDataName "btPersistentManifoldDoubleData"
#else
#define btPersistentManifoldData btPersistentManifoldFloatData
#define btPersistentManifoldDataName "btPersistentManifoldFloatData"
#endif

#endif  // BT_PERSISTENT_MANIFOLD_H
