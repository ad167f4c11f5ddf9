// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_MANIFOLD_CONTACT_POINT_H
#define BT_MANIFOLD_CONTACT_POINT_H

/// btManifoldPoint: one contact point of a persistent manifold, with its solver state.

#include "LinearMath/btTransformUtil.h"
#include "LinearMath/btVector3.h"

/// Bits of btManifoldPoint::m_contactPointFlags.
enum btContactPointFlags
{
	/// m_lateralFrictionDir1/2 hold user-chosen friction directions.
	BT_CONTACT_FLAG_LATERAL_FRICTION_INITIALIZED = 1,
	/// m_contactCFM is set for this point.
	BT_CONTACT_FLAG_HAS_CONTACT_CFM = 2,
	/// m_contactERP is set for this point.
	BT_CONTACT_FLAG_HAS_CONTACT_ERP = 4,
	/// m_combinedContactStiffness1/m_combinedContactDamping1 are set for this point.
	BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING = 8,
	/// The point is a friction anchor.
	BT_CONTACT_FLAG_FRICTION_ANCHOR = 16,
};

/// A contact between two bodies: local and world positions, normal, distance and warm-start state.
class btManifoldPoint
{
public:
	/// A zeroed point with no user data.
	btManifoldPoint()
	    : m_localPointA(0, 0, 0),
	      m_localPointB(0, 0, 0),
	      m_positionWorldOnB(0, 0, 0),
	      m_positionWorldOnA(0, 0, 0),
	      m_normalWorldOnB(0, 0, 0),
	      m_distance1(0),
	      m_combinedFriction(0),
	      m_combinedRollingFriction(0),
	      m_combinedSpinningFriction(0),
	      m_combinedRestitution(0),
	      m_partId0(0),
	      m_partId1(0),
	      m_index0(0),
	      m_index1(0),
	      m_userPersistentData(0),
	      m_contactPointFlags(0),
	      m_appliedImpulse(0),
	      m_prevRHS(0),
	      m_appliedImpulseLateral1(0),
	      m_appliedImpulseLateral2(0),
	      m_contactMotion1(0),
	      m_contactMotion2(0),
	      m_contactCFM(0),
	      m_combinedContactStiffness1(0),
	      m_contactERP(0),
	      m_combinedContactDamping1(0),
	      m_frictionCFM(0),
	      m_lifeTime(0),
	      m_lateralFrictionDir1(0, 0, 0),
	      m_lateralFrictionDir2(0, 0, 0)
	{
	}

	/// A new point from its local positions on A and B, the normal on B and the signed distance.
	btManifoldPoint(const btVector3& pointA, const btVector3& pointB, const btVector3& normal, btScalar distance)
	    : btManifoldPoint()
	{
		m_localPointA = pointA;
		m_localPointB = pointB;
		m_normalWorldOnB = normal;
		m_distance1 = distance;
	}

	/// Contact point in the local frame of body A.
	btVector3 m_localPointA;
	/// Contact point in the local frame of body B.
	btVector3 m_localPointB;
	/// Contact point on B in world space.
	btVector3 m_positionWorldOnB;
	/// Contact point on A in world space.
	btVector3 m_positionWorldOnA;
	/// Contact normal in world space, pointing from B towards A.
	btVector3 m_normalWorldOnB;

	/// Signed distance along the normal; negative when penetrating.
	btScalar m_distance1;
	/// Friction coefficient combined from both bodies.
	btScalar m_combinedFriction;
	/// Rolling friction combined from both bodies.
	btScalar m_combinedRollingFriction;
	/// Spinning friction combined from both bodies.
	btScalar m_combinedSpinningFriction;
	/// Restitution combined from both bodies.
	btScalar m_combinedRestitution;

	/// Part id of the child shape on body 0.
	int m_partId0;
	/// Part id of the child shape on body 1.
	int m_partId1;
	/// Triangle or child index on body 0.
	int m_index0;
	/// Triangle or child index on body 1.
	int m_index1;

	/// User data attached to the point; released through gContactDestroyedCallback.
	mutable void* m_userPersistentData;
	/// btContactPointFlags bits.
	int m_contactPointFlags;

	/// Normal impulse applied by the solver, kept for warm starting.
	btScalar m_appliedImpulse;
	/// Right-hand side of the previous solve.
	btScalar m_prevRHS;
	/// Impulse applied along the first friction direction.
	btScalar m_appliedImpulseLateral1;
	/// Impulse applied along the second friction direction.
	btScalar m_appliedImpulseLateral2;
	/// Target relative velocity along the first friction direction.
	btScalar m_contactMotion1;
	/// Target relative velocity along the second friction direction.
	btScalar m_contactMotion2;

	/// Constraint force mixing of the normal row (a separate member, not a union with the stiffness).
	btScalar m_contactCFM;
	/// Combined contact stiffness when BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING is set.
	btScalar m_combinedContactStiffness1;
	/// Error reduction parameter of the normal row.
	btScalar m_contactERP;
	/// Combined contact damping when BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING is set.
	btScalar m_combinedContactDamping1;
	/// Constraint force mixing of the friction rows.
	btScalar m_frictionCFM;

	/// Number of refreshes the point has survived.
	int m_lifeTime;

	/// First friction direction.
	btVector3 m_lateralFrictionDir1;
	/// Second friction direction.
	btVector3 m_lateralFrictionDir2;

	/// Signed distance along the normal.
	btScalar getDistance() const { return m_distance1; }
	/// Number of refreshes the point has survived.
	int getLifeTime() const { return m_lifeTime; }
	/// Contact point on A in world space.
	const btVector3& getPositionWorldOnA() const { return m_positionWorldOnA; }
	/// Contact point on B in world space.
	const btVector3& getPositionWorldOnB() const { return m_positionWorldOnB; }
	/// Sets the signed distance.
	void setDistance(btScalar dist) { m_distance1 = dist; }
	/// Normal impulse applied by the solver.
	btScalar getAppliedImpulse() const { return m_appliedImpulse; }
};

#endif  // BT_MANIFOLD_CONTACT_POINT_H
