// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_COLLISION_WORLD_H
#define BT_COLLISION_WORLD_H

/// btCollisionWorld: the collision objects of a scene, their broadphase proxies and the queries on them
/// (ray tests, convex sweeps, contact tests). Design notes: docs/collision-world-and-queries.md.

#include "BulletCollision/BroadphaseCollision/btBroadphaseInterface.h"
#include "BulletCollision/BroadphaseCollision/btBroadphaseProxy.h"
#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

class btCollisionConfiguration;
class btCollisionShape;
class btConvexShape;
class btIDebugDraw;
class btManifoldPoint;
class btSerializer;

/// Keeps collision objects in a broadphase, runs the narrowphase over the overlapping pairs through a
/// dispatcher (performDiscreteCollisionDetection), and answers ray, convex-sweep and contact queries.
/// The world owns neither its objects nor the dispatcher, broadphase and configuration it is given.
class btCollisionWorld
{
protected:
	/// The objects of the world, in insertion order (each knows its index: getWorldArrayIndex).
	btAlignedObjectArray<btCollisionObject*> m_collisionObjects;
	/// Finds algorithms and owns the manifolds (not owned by the world).
	btDispatcher* m_dispatcher1;
	/// Settings handed to the narrowphase.
	btDispatcherInfo m_dispatchInfo;
	/// The broadphase (not owned by the world).
	btBroadphaseInterface* m_broadphasePairCache;
	/// Debug drawer (not owned; may be null).
	btIDebugDraw* m_debugDrawer;
	/// When true (the default, as in Bullet) updateAabbs updates every object, not only active ones.
	bool m_forceUpdateAllAabbs;

	/// Writes every shape (once) and every plain collision object as chunks (docs/serialization.md).
	void serializeCollisionObjects(btSerializer* serializer);
	/// With BT_SERIALIZE_CONTACT_MANIFOLDS, writes every manifold of the dispatcher, in its order.
	void serializeContactManifolds(btSerializer* serializer);

public:
	/// A world over the given dispatcher and broadphase; the configuration is not used by the world itself.
	btCollisionWorld(btDispatcher* dispatcher, btBroadphaseInterface* broadphasePairCache,
	                 btCollisionConfiguration* collisionConfiguration);
	/// Removes the proxies of the remaining objects from the broadphase (the objects are not deleted).
	virtual ~btCollisionWorld();

	/// Replaces the broadphase (the caller moves the proxies; the world does not).
	void setBroadphase(btBroadphaseInterface* pairCache) { m_broadphasePairCache = pairCache; }
	/// The broadphase.
	const btBroadphaseInterface* getBroadphase() const { return m_broadphasePairCache; }
	/// The broadphase.
	btBroadphaseInterface* getBroadphase() { return m_broadphasePairCache; }
	/// The broadphase's overlapping pair cache.
	btOverlappingPairCache* getPairCache() { return m_broadphasePairCache->getOverlappingPairCache(); }
	/// The dispatcher.
	btDispatcher* getDispatcher() { return m_dispatcher1; }
	/// The dispatcher.
	const btDispatcher* getDispatcher() const { return m_dispatcher1; }

	/// Recomputes one object's world AABB (grown by the contact breaking threshold) and hands it to the
	/// broadphase. A non-finite or huge AABB takes a dynamic object out of the simulation (see docs).
	void updateSingleAabb(btCollisionObject* colObj);
	/// Updates the AABBs of all objects (getForceUpdateAllAabbs) or of the active, non-static ones.
	virtual void updateAabbs();
	/// Lets the broadphase bring its pair cache up to date.
	virtual void computeOverlappingPairs();

	/// Sets the debug drawer (not owned; null turns debug drawing off).
	virtual void setDebugDrawer(btIDebugDraw* debugDrawer) { m_debugDrawer = debugDrawer; }
	/// The debug drawer (may be null).
	virtual btIDebugDraw* getDebugDrawer() { return m_debugDrawer; }
	/// Draws wireframes, AABBs and contact points according to the drawer's debug mode.
	virtual void debugDrawWorld();
	/// Draws one shape placed by worldTransform as a wireframe in color.
	virtual void debugDrawObject(const btTransform& worldTransform, const btCollisionShape* shape,
	                             const btVector3& color);

	/// Which part of a shape a query hit: mesh part and triangle, or -1 and the compound child index.
	struct LocalShapeInfo
	{
		/// Mesh part (or -1).
		int m_shapePart;
		/// Triangle index, or compound child index.
		int m_triangleIndex;
	};

	/// One hit of a ray test.
	struct LocalRayResult
	{
		/// A hit of collisionObject at hitFraction with the given normal.
		LocalRayResult(const btCollisionObject* collisionObject, LocalShapeInfo* localShapeInfo,
		               const btVector3& hitNormalLocal, btScalar hitFraction)
		    : m_collisionObject(collisionObject),
		      m_localShapeInfo(localShapeInfo),
		      m_hitNormalLocal(hitNormalLocal),
		      m_hitFraction(hitFraction)
		{
		}

		/// The object hit.
		const btCollisionObject* m_collisionObject;
		/// Part and triangle/child hit (null for plain convex shapes).
		LocalShapeInfo* m_localShapeInfo;
		/// Unit normal, in world space or the object's frame (see addSingleResult's normalInWorldSpace).
		btVector3 m_hitNormalLocal;
		/// Fraction of the ray at the hit, in [0, 1].
		btScalar m_hitFraction;
	};

	/// Receives the hits of rayTest. The ray test skips hits at or beyond m_closestHitFraction, which
	/// addSingleResult's return value replaces (return the hit fraction to keep only closer hits).
	struct RayResultCallback
	{
		/// Hits at or beyond this fraction are not reported.
		btScalar m_closestHitFraction;
		/// The last object reported (null: no hit).
		const btCollisionObject* m_collisionObject;
		/// Groups the ray belongs to.
		int m_collisionFilterGroup;
		/// Groups the ray hits.
		int m_collisionFilterMask;
		/// btTriangleRaycastCallback::EFlags bits (back-face culling, normals, convex ray test method).
		unsigned int m_flags;

		/// Callbacks are deleted through base pointers.
		virtual ~RayResultCallback() {}
		/// True when something was hit.
		bool hasHit() const { return m_collisionObject != 0; }

		/// No hit yet; default filter group, all masks, no flags.
		RayResultCallback()
		    : m_closestHitFraction(btScalar(1)),
		      m_collisionObject(0),
		      m_collisionFilterGroup(btBroadphaseProxy::DefaultFilter),
		      m_collisionFilterMask(btBroadphaseProxy::AllFilter),
		      m_flags(0)
		{
		}

		/// True when the ray may hit the proxy's object: group/mask both ways.
		virtual bool needsCollision(btBroadphaseProxy* proxy0) const
		{
			return (proxy0->m_collisionFilterGroup & m_collisionFilterMask) != 0 &&
			       (m_collisionFilterGroup & proxy0->m_collisionFilterMask) != 0;
		}

		/// One hit; returns the new m_closestHitFraction bound.
		virtual btScalar addSingleResult(LocalRayResult& rayResult, bool normalInWorldSpace) = 0;
	};

	/// Keeps the closest hit of a ray.
	struct ClosestRayResultCallback : public RayResultCallback
	{
		/// A callback for the ray rayFromWorld -> rayToWorld (used to compute the hit point).
		ClosestRayResultCallback(const btVector3& rayFromWorld, const btVector3& rayToWorld)
		    : m_rayFromWorld(rayFromWorld),
		      m_rayToWorld(rayToWorld),
		      m_hitNormalWorld(btScalar(0), btScalar(0), btScalar(0)),
		      m_hitPointWorld(btScalar(0), btScalar(0), btScalar(0))
		{
		}

		/// Start of the ray (world).
		btVector3 m_rayFromWorld;
		/// End of the ray (world).
		btVector3 m_rayToWorld;
		/// Unit normal of the closest hit (world).
		btVector3 m_hitNormalWorld;
		/// Point of the closest hit (world).
		btVector3 m_hitPointWorld;

		/// Keeps the hit (the ray test only reports hits closer than the current one).
		btScalar addSingleResult(LocalRayResult& rayResult, bool normalInWorldSpace) override
		{
			btAssert(rayResult.m_hitFraction <= m_closestHitFraction);
			m_closestHitFraction = rayResult.m_hitFraction;
			m_collisionObject = rayResult.m_collisionObject;
			m_hitNormalWorld = normalInWorldSpace
			                       ? rayResult.m_hitNormalLocal
			                       : m_collisionObject->getWorldTransform().getBasis() * rayResult.m_hitNormalLocal;
			m_hitPointWorld.setInterpolate3(m_rayFromWorld, m_rayToWorld, rayResult.m_hitFraction);
			return rayResult.m_hitFraction;
		}
	};

	/// Keeps every hit of a ray, in the order found (one per object and triangle/child).
	struct AllHitsRayResultCallback : public RayResultCallback
	{
		/// A callback for the ray rayFromWorld -> rayToWorld.
		AllHitsRayResultCallback(const btVector3& rayFromWorld, const btVector3& rayToWorld)
		    : m_rayFromWorld(rayFromWorld), m_rayToWorld(rayToWorld)
		{
		}

		/// Object of each hit.
		btAlignedObjectArray<const btCollisionObject*> m_collisionObjects;
		/// Start of the ray (world).
		btVector3 m_rayFromWorld;
		/// End of the ray (world).
		btVector3 m_rayToWorld;
		/// Unit normal of each hit (world).
		btAlignedObjectArray<btVector3> m_hitNormalWorld;
		/// Point of each hit (world).
		btAlignedObjectArray<btVector3> m_hitPointWorld;
		/// Fraction of each hit.
		btAlignedObjectArray<btScalar> m_hitFractions;

		/// Appends the hit and keeps the bound at its current value, so that every hit is reported.
		btScalar addSingleResult(LocalRayResult& rayResult, bool normalInWorldSpace) override
		{
			m_collisionObject = rayResult.m_collisionObject;
			m_collisionObjects.push_back(rayResult.m_collisionObject);
			m_hitNormalWorld.push_back(normalInWorldSpace ? rayResult.m_hitNormalLocal
			                                              : m_collisionObject->getWorldTransform().getBasis() *
			                                                    rayResult.m_hitNormalLocal);
			btVector3 hitPoint;
			hitPoint.setInterpolate3(m_rayFromWorld, m_rayToWorld, rayResult.m_hitFraction);
			m_hitPointWorld.push_back(hitPoint);
			m_hitFractions.push_back(rayResult.m_hitFraction);
			return m_closestHitFraction;
		}
	};

	/// One hit of a convex sweep.
	struct LocalConvexResult
	{
		/// A hit of hitCollisionObject at hitFraction with the given normal and point.
		LocalConvexResult(const btCollisionObject* hitCollisionObject, LocalShapeInfo* localShapeInfo,
		                  const btVector3& hitNormalLocal, const btVector3& hitPointLocal, btScalar hitFraction)
		    : m_hitCollisionObject(hitCollisionObject),
		      m_localShapeInfo(localShapeInfo),
		      m_hitNormalLocal(hitNormalLocal),
		      m_hitPointLocal(hitPointLocal),
		      m_hitFraction(hitFraction)
		{
		}

		/// The object hit.
		const btCollisionObject* m_hitCollisionObject;
		/// Part and triangle/child hit (null for plain convex shapes).
		LocalShapeInfo* m_localShapeInfo;
		/// Unit normal from the object towards the swept shape (world space when normalInWorldSpace).
		btVector3 m_hitNormalLocal;
		/// Contact point on the object (world space, as in Bullet).
		btVector3 m_hitPointLocal;
		/// Fraction of the sweep at the hit, in [0, 1].
		btScalar m_hitFraction;
	};

	/// Receives the hits of convexSweepTest. Hits at or beyond m_closestHitFraction are skipped;
	/// addSingleResult's return value replaces it.
	struct ConvexResultCallback
	{
		/// Hits at or beyond this fraction are not reported.
		btScalar m_closestHitFraction;
		/// Groups the swept shape belongs to.
		int m_collisionFilterGroup;
		/// Groups the swept shape hits.
		int m_collisionFilterMask;

		/// No hit yet; default filter group, all masks.
		ConvexResultCallback()
		    : m_closestHitFraction(btScalar(1)),
		      m_collisionFilterGroup(btBroadphaseProxy::DefaultFilter),
		      m_collisionFilterMask(btBroadphaseProxy::AllFilter)
		{
		}
		/// Callbacks are deleted through base pointers.
		virtual ~ConvexResultCallback() {}

		/// True when a hit closer than the full sweep was kept.
		bool hasHit() const { return m_closestHitFraction < btScalar(1); }

		/// True when the sweep may hit the proxy's object: group/mask both ways.
		virtual bool needsCollision(btBroadphaseProxy* proxy0) const
		{
			return (proxy0->m_collisionFilterGroup & m_collisionFilterMask) != 0 &&
			       (m_collisionFilterGroup & proxy0->m_collisionFilterMask) != 0;
		}

		/// One hit; returns the new m_closestHitFraction bound.
		virtual btScalar addSingleResult(LocalConvexResult& convexResult, bool normalInWorldSpace) = 0;
	};

	/// Keeps the closest hit of a convex sweep.
	struct ClosestConvexResultCallback : public ConvexResultCallback
	{
		/// A callback for a sweep from convexFromWorld to convexToWorld (origins of the swept shape).
		ClosestConvexResultCallback(const btVector3& convexFromWorld, const btVector3& convexToWorld)
		    : m_convexFromWorld(convexFromWorld),
		      m_convexToWorld(convexToWorld),
		      m_hitNormalWorld(btScalar(0), btScalar(0), btScalar(0)),
		      m_hitPointWorld(btScalar(0), btScalar(0), btScalar(0)),
		      m_hitCollisionObject(0)
		{
		}

		/// Start of the sweep (world).
		btVector3 m_convexFromWorld;
		/// End of the sweep (world).
		btVector3 m_convexToWorld;
		/// Unit normal of the closest hit, from the object towards the swept shape (world).
		btVector3 m_hitNormalWorld;
		/// Contact point of the closest hit, on the object (world).
		btVector3 m_hitPointWorld;
		/// The object of the closest hit.
		const btCollisionObject* m_hitCollisionObject;

		/// Keeps the hit (the sweep only reports hits closer than the current one).
		btScalar addSingleResult(LocalConvexResult& convexResult, bool normalInWorldSpace) override
		{
			m_hitCollisionObject = convexResult.m_hitCollisionObject;
			m_closestHitFraction = convexResult.m_hitFraction;
			m_hitNormalWorld = normalInWorldSpace ? convexResult.m_hitNormalLocal
			                                      : m_hitCollisionObject->getWorldTransform().getBasis() *
			                                            convexResult.m_hitNormalLocal;
			m_hitPointWorld = convexResult.m_hitPointLocal;
			return convexResult.m_hitFraction;
		}
	};

	/// Receives the contact points of contactTest and contactPairTest.
	struct ContactResultCallback
	{
		/// Groups the query object belongs to.
		int m_collisionFilterGroup;
		/// Groups the query object collides with.
		int m_collisionFilterMask;
		/// Extra separation, beyond the contact breaking threshold, up to which points are reported.
		btScalar m_closestDistanceThreshold;

		/// Default filter group, all masks, threshold 0.
		ContactResultCallback()
		    : m_collisionFilterGroup(btBroadphaseProxy::DefaultFilter),
		      m_collisionFilterMask(btBroadphaseProxy::AllFilter),
		      m_closestDistanceThreshold(btScalar(0))
		{
		}
		/// Callbacks are deleted through base pointers.
		virtual ~ContactResultCallback() {}

		/// True when the query object may touch the proxy's object: group/mask both ways.
		virtual bool needsCollision(btBroadphaseProxy* proxy0) const
		{
			return (proxy0->m_collisionFilterGroup & m_collisionFilterMask) != 0 &&
			       (m_collisionFilterGroup & proxy0->m_collisionFilterMask) != 0;
		}

		/// One contact point (not stored in any manifold); the return value is ignored.
		virtual btScalar addSingleResult(btManifoldPoint& cp, const btCollisionObjectWrapper* colObj0Wrap, int partId0,
		                                 int index0, const btCollisionObjectWrapper* colObj1Wrap, int partId1,
		                                 int index1) = 0;
	};

	/// Number of objects in the world.
	int getNumCollisionObjects() const { return m_collisionObjects.size(); }

	/// Reports to resultCallback the objects the segment rayFromWorld -> rayToWorld hits (see docs).
	virtual void rayTest(const btVector3& rayFromWorld, const btVector3& rayToWorld,
	                     RayResultCallback& resultCallback) const;

	/// Sweeps castShape from `from` to `to` (translation and rotation) and reports the
	/// objects it hits. allowedCcdPenetration lets the sweep continue into that much overlap.
	void convexSweepTest(const btConvexShape* castShape, const btTransform& from, const btTransform& to,
	                     ConvexResultCallback& resultCallback, btScalar allowedCcdPenetration = btScalar(0)) const;

	/// Reports every contact point between colObj and the objects whose AABBs overlap its AABB.
	void contactTest(btCollisionObject* colObj, ContactResultCallback& resultCallback);

	/// Reports the contact points between colObjA and colObjB (they need not be in the world).
	void contactPairTest(btCollisionObject* colObjA, btCollisionObject* colObjB, ContactResultCallback& resultCallback);

	/// Ray test against one object (collisionShape placed by colObjWorldTransform).
	static void rayTestSingle(const btTransform& rayFromTrans, const btTransform& rayToTrans,
	                          btCollisionObject* collisionObject, const btCollisionShape* collisionShape,
	                          const btTransform& colObjWorldTransform, RayResultCallback& resultCallback);

	/// Ray test against the shape of a wrapper (used for compound children).
	static void rayTestSingleInternal(const btTransform& rayFromTrans, const btTransform& rayToTrans,
	                                  const btCollisionObjectWrapper* collisionObjectWrap,
	                                  RayResultCallback& resultCallback);

	/// Convex sweep against one object (collisionShape placed by colObjWorldTransform).
	static void objectQuerySingle(const btConvexShape* castShape, const btTransform& rayFromTrans,
	                              const btTransform& rayToTrans, btCollisionObject* collisionObject,
	                              const btCollisionShape* collisionShape, const btTransform& colObjWorldTransform,
	                              ConvexResultCallback& resultCallback, btScalar allowedPenetration);

	/// Convex sweep against the shape of a wrapper (used for compound children).
	static void objectQuerySingleInternal(const btConvexShape* castShape, const btTransform& convexFromTrans,
	                                      const btTransform& convexToTrans, const btCollisionObjectWrapper* colObjWrap,
	                                      ConvexResultCallback& resultCallback, btScalar allowedPenetration);

	/// Adds an object with its filter group and mask and creates its broadphase proxy. Adding an object
	/// twice asserts and is ignored in release.
	virtual void addCollisionObject(btCollisionObject* collisionObject,
	                                int collisionFilterGroup = btBroadphaseProxy::DefaultFilter,
	                                int collisionFilterMask = btBroadphaseProxy::AllFilter);

	/// Recreates the object's proxy (after its shape type or filter changed), keeping group and mask.
	virtual void refreshBroadphaseProxy(btCollisionObject* collisionObject);

	/// The objects of the world.
	btCollisionObjectArray& getCollisionObjectArray() { return m_collisionObjects; }
	/// The objects of the world.
	const btCollisionObjectArray& getCollisionObjectArray() const { return m_collisionObjects; }

	/// Removes an object and its proxy (and pairs). Removing an object not in the world asserts and is
	/// ignored in release.
	virtual void removeCollisionObject(btCollisionObject* collisionObject);

	/// One collision step: updateAabbs, computeOverlappingPairs, then the narrowphase over all pairs.
	virtual void performDiscreteCollisionDetection();

	/// Settings handed to the narrowphase.
	btDispatcherInfo& getDispatchInfo() { return m_dispatchInfo; }
	/// Settings handed to the narrowphase.
	const btDispatcherInfo& getDispatchInfo() const { return m_dispatchInfo; }

	/// Whether updateAabbs updates every object (true by default).
	bool getForceUpdateAllAabbs() const { return m_forceUpdateAllAabbs; }
	/// Sets whether updateAabbs updates every object, or only active non-static ones.
	void setForceUpdateAllAabbs(bool forceUpdateAllAabbs) { m_forceUpdateAllAabbs = forceUpdateAllAabbs; }

	/// Writes the world into serializer as a complete .bullet file (start, shapes, objects, finish).
	virtual void serialize(btSerializer* serializer);
};

#endif  // BT_COLLISION_WORLD_H
