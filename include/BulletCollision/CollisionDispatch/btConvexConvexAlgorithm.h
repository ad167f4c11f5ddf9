// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CONVEX_CONVEX_ALGORITHM_H
#define BT_CONVEX_CONVEX_ALGORITHM_H

/// btConvexConvexAlgorithm: contacts of any two convex shapes by GJK and a penetration depth solver,
/// with polyhedral clipping for a full manifold when both shapes carry btConvexPolyhedron features.

#include <new>

#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btCollisionCreateFunc.h"
#include "BulletCollision/NarrowPhaseCollision/btPolyhedralContactClipping.h"

class btConvexPenetrationDepthSolver;
class btPersistentManifold;

/// Runs btGjkPairDetector (margins included, the depth solver for overlaps). When both shapes are
/// polyhedral and initializePolyhedralFeatures was called on them, the GJK normal (or, with
/// btDispatcherInfo::m_enableSatConvex, btPolyhedralContactClipping::findSeparatingAxis) feeds
/// clipHullAgainstHull, which fills the manifold in one pass (depths corrected for the margins of
/// non-box hulls). Otherwise one point per frame is added, plus optional perturbed points
/// (setConvexConvexMultipointIterations) while the manifold has few points.
class btConvexConvexAlgorithm : public btActivatingCollisionAlgorithm
{
	btConvexPenetrationDepthSolver* m_pdSolver;
	btVertexArray worldVertsB1;
	btVertexArray worldVertsB2;
	bool m_ownManifold;
	btPersistentManifold* m_manifoldPtr;
	bool m_lowLevelOfDetail;
	int m_numPerturbationIterations;
	int m_minimumPointsPerturbationThreshold;
	// GJK's axis at the end of the last step (world space, from B towards A), where the next starts.
	btVector3 m_lastSeparatingAxis;
	bool m_haveLastSeparatingAxis;

public:
	/// An algorithm filling mf, or its own manifold (made at the first processCollision) when mf is null.
	btConvexConvexAlgorithm(btPersistentManifold* mf, const btCollisionAlgorithmConstructionInfo& ci,
	                        const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
	                        btConvexPenetrationDepthSolver* pdSolver, int numPerturbationIterations,
	                        int minimumPointsPerturbationThreshold);
	/// Releases an owned manifold through the dispatcher.
	~btConvexConvexAlgorithm() override;

	/// Writes the contacts and refreshes an owned manifold.
	void processCollision(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
	                      const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// When either body moved more than its CCD motion threshold (current to interpolation transform):
	/// the earliest time each body's shape hits the other's CCD swept sphere (btGjkConvexCast), also
	/// lowering both bodies' hit fractions; otherwise (or without a hit) 1.
	btScalar calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
	                               const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// Appends the owned manifold.
	void getAllContactManifolds(btManifoldArray& manifoldArray) override;

	/// Kept for source compatibility (no lower level of detail exists).
	void setLowLevelOfDetail(bool useLowLevel) { m_lowLevelOfDetail = useLowLevel; }
	/// The manifold the algorithm fills.
	const btPersistentManifold* getManifold() { return m_manifoldPtr; }

	/// Factory of btConvexConvexAlgorithm with the penetration depth solver to use.
	struct CreateFunc : public btCollisionAlgorithmCreateFunc
	{
		/// Penetration depth solver given to each algorithm (not owned).
		btConvexPenetrationDepthSolver* m_pdSolver;
		/// Perturbed GJK runs per frame (0: none).
		int m_numPerturbationIterations;
		/// Perturbed runs happen only while the manifold has fewer points than this.
		int m_minimumPointsPerturbationThreshold;

		/// A factory using pdSolver, without perturbation.
		CreateFunc(btConvexPenetrationDepthSolver* pdSolver);
		/// Owns nothing.
		~CreateFunc() override;

		/// A new algorithm sharing ci.m_manifold.
		btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
		                                               const btCollisionObjectWrapper* body0Wrap,
		                                               const btCollisionObjectWrapper* body1Wrap) override;
	};
};

#endif  // BT_CONVEX_CONVEX_ALGORITHM_H
