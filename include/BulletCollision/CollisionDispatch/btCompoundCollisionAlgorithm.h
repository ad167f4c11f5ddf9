// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_COMPOUND_COLLISION_ALGORITHM_H
#define BT_COMPOUND_COLLISION_ALGORITHM_H

/// btCompoundCollisionAlgorithm: contacts of a compound shape's children with another (non-compound) shape.

#include <new>

#include "BulletCollision/BroadphaseCollision/btDbvt.h"
#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btCollisionCreateFunc.h"
#include "LinearMath/btAlignedObjectArray.h"

class btCollisionShape;
class btCompoundShape;

/// Filter for pairs of child shapes (compound algorithms skip a pair when it returns false; null: none).
typedef bool (*btShapePairCallback)(const btCollisionShape* pShape0, const btCollisionShape* pShape1);
/// Global child-pair filter of the compound algorithms (null by default).
extern btShapePairCallback gCompoundChildShapePairCallback;

/// Finds the children whose AABBs overlap the other object's (through the compound's AABB tree, or all
/// children without one) and runs a cached algorithm per child; a child's algorithm (and its manifold)
/// is made when its AABB first overlaps and released when it stops overlapping, and all are rebuilt
/// when the compound's update revision changes. isSwapped means body 0 is the other object.
class btCompoundCollisionAlgorithm : public btActivatingCollisionAlgorithm
{
protected:
	/// Tree traversal stack, kept between frames.
	btNodeStack stack2;
	/// Scratch manifold list, kept between frames.
	btManifoldArray manifoldArray;
	/// One algorithm per child (null while the child does not overlap).
	btAlignedObjectArray<btCollisionAlgorithm*> m_childCollisionAlgorithms;
	/// True when body 0 is the other object.
	bool m_isSwapped;
	/// A manifold given by the caller, shared with the children (null: each child owns its manifold).
	btPersistentManifold* m_sharedManifold;
	/// Kept for Bullet's layout; the children own their manifolds.
	bool m_ownsManifold;
	/// The compound's update revision the child array was built for.
	int m_compoundShapeRevision;

	/// Destroys every child algorithm.
	void removeChildAlgorithms();
	/// Sizes the child array to the compound's children, all null.
	void preallocateChildAlgorithms(const btCollisionObjectWrapper* body0Wrap,
	                                const btCollisionObjectWrapper* body1Wrap);

public:
	/// An algorithm for the pair.
	btCompoundCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
	                             const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
	                             bool isSwapped);
	/// Destroys the child algorithms.
	~btCompoundCollisionAlgorithm() override;

	/// The algorithm of child n (may be null).
	btCollisionAlgorithm* getChildAlgorithm(int n) const { return m_childCollisionAlgorithms[n]; }

	/// Collides the overlapping children with the other object.
	void processCollision(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
	                      const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// Always 1 for now: continuous collision is handled by the world's CCD.
	btScalar calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
	                               const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// Appends the children's manifolds.
	void getAllContactManifolds(btManifoldArray& manifoldArray) override;

	/// Factory for the (compound, other) order.
	struct CreateFunc : public btCollisionAlgorithmCreateFunc
	{
		/// A new algorithm.
		btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
		                                               const btCollisionObjectWrapper* body0Wrap,
		                                               const btCollisionObjectWrapper* body1Wrap) override
		{
			void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(btCompoundCollisionAlgorithm));
			return new (mem) btCompoundCollisionAlgorithm(ci, body0Wrap, body1Wrap, false);
		}
	};

	/// Factory for the (other, compound) order.
	struct SwappedCreateFunc : public btCollisionAlgorithmCreateFunc
	{
		/// A new algorithm.
		btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
		                                               const btCollisionObjectWrapper* body0Wrap,
		                                               const btCollisionObjectWrapper* body1Wrap) override
		{
			void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(btCompoundCollisionAlgorithm));
			return new (mem) btCompoundCollisionAlgorithm(ci, body0Wrap, body1Wrap, true);
		}
	};
};

#endif  // BT_COMPOUND_COLLISION_ALGORITHM_H
