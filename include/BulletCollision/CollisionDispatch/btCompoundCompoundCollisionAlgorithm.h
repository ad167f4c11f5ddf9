// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_COMPOUND_COMPOUND_COLLISION_ALGORITHM_H
#define BT_COMPOUND_COMPOUND_COLLISION_ALGORITHM_H

/// btCompoundCompoundCollisionAlgorithm: contacts between the children of two compound shapes.

#include <new>

#include "BulletCollision/CollisionDispatch/btCompoundCollisionAlgorithm.h"
#include "LinearMath/btHashMap.h"

/// Finds the overlapping child pairs through both compounds' AABB trees (or all children without a
/// tree) and runs one cached algorithm per child pair, kept in a hash map keyed by the two child indices.
/// Pairs not visited in a frame lose their algorithm (and manifold); all are dropped when either
/// compound's update revision changes.
class btCompoundCompoundCollisionAlgorithm : public btCompoundCollisionAlgorithm
{
public:
	/// Key of a child pair (child index in compound 0, in compound 1).
	struct ChildPairKey
	{
		/// Child index in body 0's compound.
		int m_index0;
		/// Child index in body 1's compound.
		int m_index1;
		/// An invalid key (for arrays).
		ChildPairKey() : m_index0(-1), m_index1(-1) {}
		/// A key for the pair.
		ChildPairKey(int index0, int index1) : m_index0(index0), m_index1(index1) {}
		/// Hash of both indices.
		unsigned int getHash() const
		{
			const unsigned int mixed = unsigned(m_index0) * 2654435761u ^ (unsigned(m_index1) + 0x9e3779b9u);
			return mixed ^ (mixed >> 15);
		}
		/// Same pair.
		bool equals(const ChildPairKey& other) const
		{
			return m_index0 == other.m_index0 && m_index1 == other.m_index1;
		}
	};
	/// A cached child-pair algorithm and the frame it was last used in.
	struct ChildPairAlgorithm
	{
		/// The algorithm (owned).
		btCollisionAlgorithm* m_algorithm;
		/// Frame number of its last use.
		int m_lastFrame;
	};

protected:
	/// The cached child-pair algorithms.
	btHashMap<ChildPairKey, ChildPairAlgorithm> m_childPairAlgorithms;
	/// Keys of pairs to drop (kept to avoid allocating each frame).
	btAlignedObjectArray<ChildPairKey> m_removePairs;
	/// Update revision of compound 0 the cache was built for.
	int m_compoundShapeRevision0;
	/// Update revision of compound 1 the cache was built for.
	int m_compoundShapeRevision1;
	/// Frames processed so far.
	int m_frame;
	/// Children of compound 0 near compound 1 (scratch, kept between frames).
	btAlignedObjectArray<int> m_near0;
	/// Children of compound 1 near one child of compound 0 (scratch, kept between frames).
	btAlignedObjectArray<int> m_near1;

	/// Destroys every cached child-pair algorithm.
	void removeChildAlgorithms();

public:
	/// An algorithm for two compound objects (isSwapped is accepted for Bullet's signature and ignored).
	btCompoundCompoundCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
	                                     const btCollisionObjectWrapper* body0Wrap,
	                                     const btCollisionObjectWrapper* body1Wrap, bool isSwapped);
	/// Destroys the cached algorithms.
	~btCompoundCompoundCollisionAlgorithm() override;

	/// Collides the overlapping child pairs.
	void processCollision(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
	                      const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// Always 1 for now: continuous collision is handled by the world's CCD.
	btScalar calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
	                               const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// Appends the manifolds of every cached child pair.
	void getAllContactManifolds(btManifoldArray& manifoldArray) override;

	/// Factory.
	struct CreateFunc : public btCollisionAlgorithmCreateFunc
	{
		/// A new algorithm.
		btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
		                                               const btCollisionObjectWrapper* body0Wrap,
		                                               const btCollisionObjectWrapper* body1Wrap) override
		{
			void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(btCompoundCompoundCollisionAlgorithm));
			return new (mem) btCompoundCompoundCollisionAlgorithm(ci, body0Wrap, body1Wrap, false);
		}
	};
	/// Factory (same algorithm: the pair is symmetric).
	struct SwappedCreateFunc : public btCollisionAlgorithmCreateFunc
	{
		/// A new algorithm.
		btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
		                                               const btCollisionObjectWrapper* body0Wrap,
		                                               const btCollisionObjectWrapper* body1Wrap) override
		{
			void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(btCompoundCompoundCollisionAlgorithm));
			return new (mem) btCompoundCompoundCollisionAlgorithm(ci, body0Wrap, body1Wrap, true);
		}
	};
};

#endif  // BT_COMPOUND_COMPOUND_COLLISION_ALGORITHM_H
