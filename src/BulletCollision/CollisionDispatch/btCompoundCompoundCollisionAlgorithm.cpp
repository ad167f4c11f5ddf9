// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btCompoundCompoundCollisionAlgorithm.h"

#include "BulletCollision/CollisionDispatch/btAlgorithmUtil.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "BulletCollision/CollisionShapes/btCompoundShape.h"
#include "LinearMath/btAabbUtil2.h"

namespace
{
typedef btCompoundCompoundCollisionAlgorithm::ChildPairKey PairKey;
typedef btCompoundCompoundCollisionAlgorithm::ChildPairAlgorithm PairAlgorithm;

// Calls visit(index) for every child of compound (placed by its world transform) whose AABB may overlap
// the world box [worldMin, worldMax]: through the AABB tree when there is one.
struct ChildCollector : public btDbvt::ICollide
{
	btAlignedObjectArray<int>* m_out;
	void Process(const btDbvtNode* leaf) override { m_out->push_back(leaf->dataAsInt); }
};

void childrenNear(const btCompoundShape* compound, const btTransform& compoundWorld, const btVector3& worldMin,
                  const btVector3& worldMax, btNodeStack& stack, btAlignedObjectArray<int>& out)
{
	out.resize(0);
	const btDbvt* tree = compound->getDynamicAabbTree();
	if (tree && tree->m_root)
	{
		// The box in the compound's frame: the AABB of the world box's corners mapped back.
		const btTransform toLocal = compoundWorld.inverse();
		const btVector3 centre = toLocal((worldMin + worldMax) * btScalar(0.5));
		const btVector3 halfExtents = (worldMax - worldMin) * btScalar(0.5);
		const btMatrix3x3 absBasis = toLocal.getBasis().absolute();
		const btVector3 localHalf(absBasis[0].dot(halfExtents), absBasis[1].dot(halfExtents),
		                          absBasis[2].dot(halfExtents));
		ChildCollector collector;
		collector.m_out = &out;
		tree->collideTVNoStackAlloc(tree->m_root, btDbvtVolume::FromMM(centre - localHalf, centre + localHalf), stack,
		                            collector);
		return;
	}
	for (int i = 0; i < compound->getNumChildShapes(); ++i) out.push_back(i);
}
}  // namespace

btCompoundCompoundCollisionAlgorithm::btCompoundCompoundCollisionAlgorithm(
    const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* body0Wrap,
    const btCollisionObjectWrapper* body1Wrap, bool isSwapped)
    : btCompoundCollisionAlgorithm(ci, body0Wrap, body1Wrap, false), m_frame(0)
{
	(void)isSwapped;
	m_compoundShapeRevision0 = static_cast<const btCompoundShape*>(body0Wrap->getCollisionShape())->getUpdateRevision();
	m_compoundShapeRevision1 = static_cast<const btCompoundShape*>(body1Wrap->getCollisionShape())->getUpdateRevision();
}

btCompoundCompoundCollisionAlgorithm::~btCompoundCompoundCollisionAlgorithm() { removeChildAlgorithms(); }

void btCompoundCompoundCollisionAlgorithm::removeChildAlgorithms()
{
	for (int i = 0; i < m_childPairAlgorithms.size(); ++i)
	{
		PairAlgorithm* entry = m_childPairAlgorithms.getAtIndex(i);
		if (!entry || !entry->m_algorithm) continue;
		entry->m_algorithm->~btCollisionAlgorithm();
		m_dispatcher->freeCollisionAlgorithm(entry->m_algorithm);
	}
	m_childPairAlgorithms.clear();
}

void btCompoundCompoundCollisionAlgorithm::processCollision(const btCollisionObjectWrapper* body0Wrap,
                                                            const btCollisionObjectWrapper* body1Wrap,
                                                            const btDispatcherInfo& dispatchInfo,
                                                            btManifoldResult* resultOut)
{
	if (!resultOut || !caliber::pairIsUsable(body0Wrap, body1Wrap))
	{
		removeChildAlgorithms();
		return;
	}
	const btCompoundShape* compound0 = static_cast<const btCompoundShape*>(body0Wrap->getCollisionShape());
	const btCompoundShape* compound1 = static_cast<const btCompoundShape*>(body1Wrap->getCollisionShape());
	if (compound0->getUpdateRevision() != m_compoundShapeRevision0 ||
	    compound1->getUpdateRevision() != m_compoundShapeRevision1)
	{
		removeChildAlgorithms();
		m_compoundShapeRevision0 = compound0->getUpdateRevision();
		m_compoundShapeRevision1 = compound1->getUpdateRevision();
	}
	++m_frame;

	const btScalar grow = gContactBreakingThreshold + resultOut->m_closestPointDistanceThreshold;
	const btVector3 growVector(grow, grow, grow);
	btVector3 min1, max1;
	compound1->getAabb(body1Wrap->getWorldTransform(), min1, max1);
	min1 -= growVector;
	max1 += growVector;

	// Children of compound 0 near compound 1, then, for each, children of compound 1 near that child.
	btAlignedObjectArray<int>& near0 = m_near0;
	btAlignedObjectArray<int>& near1 = m_near1;
	childrenNear(compound0, body0Wrap->getWorldTransform(), min1, max1, stack2, near0);
	// The contact algorithms, as for a compound against a convex (see btCompoundCollisionAlgorithm.cpp).
	const ebtDispatcherQueryType queryType = BT_CONTACT_POINT_ALGORITHMS;
	const btCollisionObjectWrapper* saved0 = resultOut->getBody0Wrap();
	const btCollisionObjectWrapper* saved1 = resultOut->getBody1Wrap();
	for (int a = 0; a < near0.size(); ++a)
	{
		const int index0 = near0[a];
		const btCollisionShape* child0 = compound0->getChildShape(index0);
		const btTransform world0 = body0Wrap->getWorldTransform() * compound0->getChildTransform(index0);
		btVector3 min0, max0;
		child0->getAabb(world0, min0, max0);
		min0 -= growVector;
		max0 += growVector;
		childrenNear(compound1, body1Wrap->getWorldTransform(), min0, max0, stack2, near1);
		for (int b = 0; b < near1.size(); ++b)
		{
			const int index1 = near1[b];
			const btCollisionShape* child1 = compound1->getChildShape(index1);
			if (gCompoundChildShapePairCallback && !gCompoundChildShapePairCallback(child0, child1)) continue;
			const btTransform world1 = body1Wrap->getWorldTransform() * compound1->getChildTransform(index1);
			btVector3 childMin1, childMax1;
			child1->getAabb(world1, childMin1, childMax1);
			if (!TestAabbAgainstAabb2(min0, max0, childMin1, childMax1)) continue;

			btCollisionObjectWrapper wrap0(body0Wrap, child0, body0Wrap->getCollisionObject(), world0, -1, index0);
			btCollisionObjectWrapper wrap1(body1Wrap, child1, body1Wrap->getCollisionObject(), world1, -1, index1);
			const PairKey key(index0, index1);
			PairAlgorithm* entry = m_childPairAlgorithms.find(key);
			if (!entry)
			{
				PairAlgorithm created;
				created.m_algorithm = m_dispatcher->findAlgorithm(&wrap0, &wrap1, m_sharedManifold, queryType);
				created.m_lastFrame = m_frame;
				if (!created.m_algorithm) continue;
				m_childPairAlgorithms.insert(key, created);
				entry = m_childPairAlgorithms.find(key);
			}
			entry->m_lastFrame = m_frame;
			resultOut->setBody0Wrap(&wrap0);
			resultOut->setBody1Wrap(&wrap1);
			resultOut->setShapeIdentifiersA(-1, index0);
			resultOut->setShapeIdentifiersB(-1, index1);
			entry->m_algorithm->processCollision(&wrap0, &wrap1, dispatchInfo, resultOut);
		}
	}
	resultOut->setBody0Wrap(saved0);
	resultOut->setBody1Wrap(saved1);

	// Pairs that were not near each other this frame drop their algorithm and manifold.
	m_removePairs.resize(0);
	for (int i = 0; i < m_childPairAlgorithms.size(); ++i)
	{
		const PairAlgorithm* entry = m_childPairAlgorithms.getAtIndex(i);
		if (entry && entry->m_lastFrame != m_frame) m_removePairs.push_back(m_childPairAlgorithms.getKeyAtIndex(i));
	}
	for (int i = 0; i < m_removePairs.size(); ++i)
	{
		PairAlgorithm* entry = m_childPairAlgorithms.find(m_removePairs[i]);
		if (!entry) continue;
		entry->m_algorithm->~btCollisionAlgorithm();
		m_dispatcher->freeCollisionAlgorithm(entry->m_algorithm);
		m_childPairAlgorithms.remove(m_removePairs[i]);
	}
}

btScalar btCompoundCompoundCollisionAlgorithm::calculateTimeOfImpact(btCollisionObject*, btCollisionObject*,
                                                                     const btDispatcherInfo&, btManifoldResult*)
{
	return btScalar(1);
}

void btCompoundCompoundCollisionAlgorithm::getAllContactManifolds(btManifoldArray& manifolds)
{
	for (int i = 0; i < m_childPairAlgorithms.size(); ++i)
	{
		const PairAlgorithm* entry = m_childPairAlgorithms.getAtIndex(i);
		if (entry && entry->m_algorithm) entry->m_algorithm->getAllContactManifolds(manifolds);
	}
}
