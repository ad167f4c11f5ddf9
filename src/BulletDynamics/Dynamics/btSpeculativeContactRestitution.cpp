// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/Dynamics/btSpeculativeContactRestitution.h"

#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"

void caliber::giveSpeculativeContactsRestitution(const btAlignedObjectArray<btPersistentManifold*>& predictiveManifolds)
{
	for (int i = 0; i < predictiveManifolds.size(); ++i)
	{
		btPersistentManifold* manifold = predictiveManifolds[i];
		if (!manifold || !manifold->getBody0() || !manifold->getBody1()) continue;
		// The same combination as the dispatcher's points (btManifoldResult), so that a predictive point
		// bounces exactly as a contact between the same bodies found by collision detection would.
		const CalculateCombinedCallback combine = gCalculateCombinedRestitutionCallback
		                                              ? gCalculateCombinedRestitutionCallback
		                                              : &btManifoldResult::calculateCombinedRestitution;
		const btScalar restitution = combine(manifold->getBody0(), manifold->getBody1());
		for (int p = 0; p < manifold->getNumContacts(); ++p)
			manifold->getContactPoint(p).m_combinedRestitution = restitution;
	}
}
