// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_TRANSFORM_UTIL_H
#define BT_TRANSFORM_UTIL_H

/// Integrating transforms over a time step, and velocities from two transforms.

#include "LinearMath/btTransform.h"

/// The largest rotation integrateTransform applies in one step (a quarter turn / 2); faster spins
/// are clamped so that a single step never turns a body so far that its direction is ambiguous.
#define ANGULAR_MOTION_THRESHOLD (btScalar(0.5) * SIMD_HALF_PI)

/// The corner of a centred box (half extents) furthest along supportDir.
SIMD_FORCE_INLINE btVector3 btAabbSupport(const btVector3& halfExtents, const btVector3& supportDir)
{
	return btVector3(supportDir.x() < btScalar(0.0) ? -halfExtents.x() : halfExtents.x(),
	                 supportDir.y() < btScalar(0.0) ? -halfExtents.y() : halfExtents.y(),
	                 supportDir.z() < btScalar(0.0) ? -halfExtents.z() : halfExtents.z());
}

/// Static helpers that move transforms by velocities and recover velocities from transforms.
class btTransformUtil
{
public:
	/// predictedTransform = curTrans moved for timeStep by the world-space linear velocity linvel and
	/// angular velocity angvel (exact exponential map of the rotation, angle clamped to
	/// ANGULAR_MOTION_THRESHOLD per step).
	static void integrateTransform(const btTransform& curTrans, const btVector3& linvel, const btVector3& angvel,
	                               btScalar timeStep, btTransform& predictedTransform);

	/// Velocities that take (pos0, orn0) to (pos1, orn1) in timeStep, rotating the short way round.
	/// timeStep must be positive; otherwise (asserts in debug) both velocities are zero.
	static void calculateVelocityQuaternion(const btVector3& pos0, const btVector3& pos1, const btQuaternion& orn0,
	                                        const btQuaternion& orn1, btScalar timeStep, btVector3& linVel,
	                                        btVector3& angVel);

	/// Unit axis and angle in [0, pi] of the rotation from orn0 to orn1a (the short way round).
	static void calculateDiffAxisAngleQuaternion(const btQuaternion& orn0, const btQuaternion& orn1a, btVector3& axis,
	                                             btScalar& angle);

	/// Velocities that take transform0 to transform1 in timeStep (see calculateVelocityQuaternion).
	static void calculateVelocity(const btTransform& transform0, const btTransform& transform1, btScalar timeStep,
	                              btVector3& linVel, btVector3& angVel);

	/// Unit axis and angle in [0, pi] of the rotation from transform0's basis to transform1's.
	static void calculateDiffAxisAngle(const btTransform& transform0, const btTransform& transform1, btVector3& axis,
	                                   btScalar& angle);
};

/// Keeps a conservative lower bound on the distance between two convex objects as they move, so a
/// narrowphase query can be skipped while the bound stays positive.
class btConvexSeparatingDistanceUtil
{
	btQuaternion m_ornA;
	btQuaternion m_ornB;
	btVector3 m_posA;
	btVector3 m_posB;
	btVector3 m_separatingNormal;
	btScalar m_boundingRadiusA;
	btScalar m_boundingRadiusB;
	btScalar m_separatingDistance;

public:
	/// The radii bound each object around its origin; they turn angular motion into distance.
	btConvexSeparatingDistanceUtil(btScalar boundingRadiusA, btScalar boundingRadiusB);

	/// The current lower bound; 0 or less means "may touch, run the narrowphase".
	btScalar getConservativeSeparatingDistance() const { return m_separatingDistance; }

	/// Moves both objects to new transforms and lowers the bound by the largest approach the motion allows.
	void updateSeparatingDistance(const btTransform& transA, const btTransform& transB);

	/// Starts tracking from a narrowphase result: separatingVector is the unit normal pointing from B
	/// towards A (Bullet's normal on B) and separatingDistance the distance found.
	void initSeparatingDistance(const btVector3& separatingVector, btScalar separatingDistance,
	                            const btTransform& transA, const btTransform& transB);
};

#endif  // BT_TRANSFORM_UTIL_H
