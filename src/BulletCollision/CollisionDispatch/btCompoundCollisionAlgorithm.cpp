// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btCompoundCollisionAlgorithm.h"

#include "BulletCollision/CollisionDispatch/btAlgorithmUtil.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "BulletCollision/CollisionShapes/btCompoundShape.h"
#include "LinearMath/btAabbUtil2.h"

btShapePairCallback gCompoundChildShapePairCallback = 0;

namespace
{
// Visits the children near the other object: makes the child's algorithm on first overlap and runs it
// with the result pointed at the child.
struct CompoundChildVisitor : public btDbvt::ICollide
{
	const btCollisionObjectWrapper* m_compoundWrap;
	const btCollisionObjectWrapper* m_otherWrap;
	btDispatcher* m_dispatcher;
	const btDispatcherInfo& m_dispatchInfo;
	btManifoldResult* m_resultOut;
	btCollisionAlgorithm** m_childAlgorithms;
	btPersistentManifold* m_sharedManifold;
	bool m_isSwapped;
	btVector3 m_otherAabbMin;
	btVector3 m_otherAabbMax;

	CompoundChildVisitor(const btCollisionObjectWrapper* compoundWrap, const btCollisionObjectWrapper* otherWrap,
	                     btDispatcher* dispatcher, const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut,
	                     btCollisionAlgorithm** childAlgorithms, btPersistentManifold* sharedManifold, bool isSwapped)
	    : m_compoundWrap(compoundWrap),
	      m_otherWrap(otherWrap),
	      m_dispatcher(dispatcher),
	      m_dispatchInfo(dispatchInfo),
	      m_resultOut(resultOut),
	      m_childAlgorithms(childAlgorithms),
	      m_sharedManifold(sharedManifold),
	      m_isSwapped(isSwapped)
	{
	}

	void processChild(int index)
	{
		const btCompoundShape* compound = static_cast<const btCompoundShape*>(m_compoundWrap->getCollisionShape());
		const btCollisionShape* childShape = compound->getChildShape(index);
		if (gCompoundChildShapePairCallback &&
		    !gCompoundChildShapePairCallback(m_otherWrap->getCollisionShape(), childShape))
			return;
		const btTransform childWorld = m_compoundWrap->getWorldTransform() * compound->getChildTransform(index);
		btVector3 childMin, childMax;
		childShape->getAabb(childWorld, childMin, childMax);
		if (!TestAabbAgainstAabb2(childMin, childMax, m_otherAabbMin, m_otherAabbMax)) return;

		btCollisionObjectWrapper childWrap(m_compoundWrap, childShape, m_compoundWrap->getCollisionObject(), childWorld,
		                                   -1, index);
		const btCollisionObjectWrapper* wrap0 = m_isSwapped ? m_otherWrap : &childWrap;
		const btCollisionObjectWrapper* wrap1 = m_isSwapped ? &childWrap : m_otherWrap;
		btCollisionAlgorithm*& algorithm = m_childAlgorithms[index];
		if (!algorithm)
		{
			// Always the contact algorithm: it is cached for the pair's life, and a contact distance above
			// zero is the normal case here (the dispatcher's speculative reach for any moving pair). The
			// closest-point table would give two boxes a one-point GJK algorithm for good, and a compound
			// landing flat on such points turns and slides. Contact algorithms honour the distance too.
			algorithm = m_dispatcher->findAlgorithm(wrap0, wrap1, m_sharedManifold, BT_CONTACT_POINT_ALGORITHMS);
			if (!algorithm) return;
		}
		const btCollisionObjectWrapper* saved0 = m_resultOut->getBody0Wrap();
		const btCollisionObjectWrapper* saved1 = m_resultOut->getBody1Wrap();
		m_resultOut->setBody0Wrap(wrap0);
		m_resultOut->setBody1Wrap(wrap1);
		if (m_isSwapped)
			m_resultOut->setShapeIdentifiersB(-1, index);
		else
			m_resultOut->setShapeIdentifiersA(-1, index);
		algorithm->processCollision(wrap0, wrap1, m_dispatchInfo, m_resultOut);
		m_resultOut->setBody0Wrap(saved0);
		m_resultOut->setBody1Wrap(saved1);
	}

	void Process(const btDbvtNode* leaf) override { processChild(leaf->dataAsInt); }
};
}  // namespace

btCompoundCollisionAlgorithm::btCompoundCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
                                                           const btCollisionObjectWrapper* body0Wrap,
                                                           const btCollisionObjectWrapper* body1Wrap, bool isSwapped)
    : btActivatingCollisionAlgorithm(ci, body0Wrap, body1Wrap),
      m_isSwapped(isSwapped),
      m_sharedManifold(ci.m_manifold),
      m_ownsManifold(false),
      m_compoundShapeRevision(0)
{
	const btCollisionObjectWrapper* compoundWrap = isSwapped ? body1Wrap : body0Wrap;
	btAssert(compoundWrap->getCollisionShape()->isCompound());
	m_compoundShapeRevision =
	    static_cast<const btCompoundShape*>(compoundWrap->getCollisionShape())->getUpdateRevision();
	preallocateChildAlgorithms(body0Wrap, body1Wrap);
}

btCompoundCollisionAlgorithm::~btCompoundCollisionAlgorithm() { removeChildAlgorithms(); }

void btCompoundCollisionAlgorithm::preallocateChildAlgorithms(const btCollisionObjectWrapper* body0Wrap,
                                                              const btCollisionObjectWrapper* body1Wrap)
{
	const btCollisionObjectWrapper* compoundWrap = m_isSwapped ? body1Wrap : body0Wrap;
	const btCompoundShape* compound = static_cast<const btCompoundShape*>(compoundWrap->getCollisionShape());
	// Algorithms are made lazily, when a child first overlaps; the array itself is sized once per revision.
	m_childCollisionAlgorithms.resize(compound->getNumChildShapes());
	for (int i = 0; i < m_childCollisionAlgorithms.size(); ++i) m_childCollisionAlgorithms[i] = 0;
}

void btCompoundCollisionAlgorithm::removeChildAlgorithms()
{
	for (int i = 0; i < m_childCollisionAlgorithms.size(); ++i)
	{
		if (!m_childCollisionAlgorithms[i]) continue;
		m_childCollisionAlgorithms[i]->~btCollisionAlgorithm();
		m_dispatcher->freeCollisionAlgorithm(m_childCollisionAlgorithms[i]);
		m_childCollisionAlgorithms[i] = 0;
	}
}

void btCompoundCollisionAlgorithm::processCollision(const btCollisionObjectWrapper* body0Wrap,
                                                    const btCollisionObjectWrapper* body1Wrap,
                                                    const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut)
{
	if (!resultOut || !caliber::pairIsUsable(body0Wrap, body1Wrap))
	{
		removeChildAlgorithms();
		return;
	}
	const btCollisionObjectWrapper* compoundWrap = m_isSwapped ? body1Wrap : body0Wrap;
	const btCollisionObjectWrapper* otherWrap = m_isSwapped ? body0Wrap : body1Wrap;
	const btCompoundShape* compound = static_cast<const btCompoundShape*>(compoundWrap->getCollisionShape());

	if (compound->getUpdateRevision() != m_compoundShapeRevision ||
	    compound->getNumChildShapes() != m_childCollisionAlgorithms.size())
	{
		removeChildAlgorithms();
		preallocateChildAlgorithms(body0Wrap, body1Wrap);
		m_compoundShapeRevision = compound->getUpdateRevision();
	}
	if (m_childCollisionAlgorithms.size() == 0) return;

	// The other object's AABB, grown so that children within the breaking distance keep their contacts.
	const btScalar grow = otherWrap->getCollisionShape()->getContactBreakingThreshold(gContactBreakingThreshold) +
	                      resultOut->m_closestPointDistanceThreshold;
	btVector3 otherMin, otherMax;
	otherWrap->getCollisionShape()->getAabb(otherWrap->getWorldTransform(), otherMin, otherMax);
	otherMin -= btVector3(grow, grow, grow);
	otherMax += btVector3(grow, grow, grow);

	CompoundChildVisitor visitor(compoundWrap, otherWrap, m_dispatcher, dispatchInfo, resultOut,
	                             &m_childCollisionAlgorithms[0], m_sharedManifold, m_isSwapped);
	visitor.m_otherAabbMin = otherMin;
	visitor.m_otherAabbMax = otherMax;

	const btDbvt* tree = compound->getDynamicAabbTree();
	if (tree && tree->m_root)
	{
		// The tree lives in the compound's frame: query it with the other's AABB seen from there.
		const btTransform otherInCompound =
		    compoundWrap->getWorldTransform().inverse() * otherWrap->getWorldTransform();
		btVector3 localMin, localMax;
		otherWrap->getCollisionShape()->getAabb(otherInCompound, localMin, localMax);
		localMin -= btVector3(grow, grow, grow);
		localMax += btVector3(grow, grow, grow);
		tree->collideTVNoStackAlloc(tree->m_root, btDbvtVolume::FromMM(localMin, localMax), stack2, visitor);
	}
	else
	{
		for (int i = 0; i < m_childCollisionAlgorithms.size(); ++i) visitor.processChild(i);
	}

	// Children that no longer overlap drop their algorithm (and with it their manifold and stale points).
	for (int i = 0; i < m_childCollisionAlgorithms.size(); ++i)
	{
		if (!m_childCollisionAlgorithms[i]) continue;
		btVector3 childMin, childMax;
		compound->getChildShape(i)->getAabb(compoundWrap->getWorldTransform() * compound->getChildTransform(i),
		                                    childMin, childMax);
		if (TestAabbAgainstAabb2(childMin, childMax, otherMin, otherMax)) continue;
		m_childCollisionAlgorithms[i]->~btCollisionAlgorithm();
		m_dispatcher->freeCollisionAlgorithm(m_childCollisionAlgorithms[i]);
		m_childCollisionAlgorithms[i] = 0;
	}
}

btScalar btCompoundCollisionAlgorithm::calculateTimeOfImpact(btCollisionObject*, btCollisionObject*,
                                                             const btDispatcherInfo&, btManifoldResult*)
{
	return btScalar(1);
}

void btCompoundCollisionAlgorithm::getAllContactManifolds(btManifoldArray& manifolds)
{
	for (int i = 0; i < m_childCollisionAlgorithms.size(); ++i)
		if (m_childCollisionAlgorithms[i]) m_childCollisionAlgorithms[i]->getAllContactManifolds(manifolds);
}
