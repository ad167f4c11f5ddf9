// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SPIN_MOMENTUM_H
#define CALIBER_SPIN_MOMENTUM_H

// The gyroscopic effect as conservation: a free body keeps its angular momentum L = R I R^T w as it
// turns. This is how Caliber implements Bullet's default BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY:
// the turn over a step is the free rigid body's motion, split symmetrically into rotations about the
// body's principal axes (each an exact rotation that keeps L; the symmetric split is second order and
// keeps the energy bounded, where turning by w h and then re-deriving w from L gains energy step after
// step). Contact impulses, computed with the inertia of the step's start, exchange angular momentum
// between bodies without creating any, so a crowd of colliding bodies keeps its total to rounding.

#include "BulletDynamics/Dynamics/btRigidBody.h"

namespace caliber
{
/// Whether body's spin follows its angular momentum when it turns (see above): the flag is set, the
/// body turns freely about every axis, its inertia is anisotropic (isotropic spin needs nothing), and
/// no joint holds it. A jointed body keeps Bullet's update (turn by w h, gyroscopic change of w): its
/// joints act during the step, so it does not turn as a free body would, and every body of a rigid
/// assembly must turn by the same w h for the joints to hold to rounding.
inline bool spinFollowsAngularMomentum(const btRigidBody& body)
{
	if (!(body.getFlags() & BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY)) return false;
	if (body.getNumConstraintRefs() > 0) return false;
	const btVector3& factor = body.getAngularFactor();
	if (factor.x() != btScalar(1) || factor.y() != btScalar(1) || factor.z() != btScalar(1)) return false;
	const btVector3& inverse = body.getInvInertiaDiagLocal();
	if (!(inverse.x() > btScalar(0) && inverse.y() > btScalar(0) && inverse.z() > btScalar(0))) return false;
	return !(inverse.x() == inverse.y() && inverse.y() == inverse.z());
}

/// Whether body's inertia is the same about every axis (its inverse diagonal has three equal entries).
inline bool hasIsotropicInertia(const btRigidBody& body)
{
	const btVector3& inverse = body.getInvInertiaDiagLocal();
	return inverse.x() == inverse.y() && inverse.y() == inverse.z();
}

/// The angular velocity with which body, turned from basis `from` to basis `to`, carries the angular
/// momentum it had with its present angular velocity in `from`.
inline btVector3 angularVelocityAfterTurn(const btRigidBody& body, const btMatrix3x3& from, const btMatrix3x3& to)
{
	const btVector3& inverse = body.getInvInertiaDiagLocal();
	const btVector3 inertia(btScalar(1) / inverse.x(), btScalar(1) / inverse.y(), btScalar(1) / inverse.z());
	const btVector3 momentum = from * ((body.getAngularVelocity() * from) * inertia);  // R I R^T w
	return to * ((momentum * to) * inverse);
}
/// tan(angle / 2), by its series where that is exact to rounding (a step's turn is usually small).
inline btScalar tanOfHalf(btScalar angle)
{
	const btScalar x = btScalar(0.5) * angle;
	const btScalar x2 = x * x;
	// The series' next term, 17 x^7 / 315, is below 1e-16 relative to x for |x| < 0.005.
	if (x2 < btScalar(0.005 * 0.005))
		return x * (btScalar(1) + x2 * (btScalar(1) / btScalar(3) + x2 * btScalar(2. / 15.)));
	return btTan(x);
}

/// The orientation after a free turn of timeStep from `start`, with the angular momentum body has now,
/// and the angular velocity that carries it there (see above).
inline void turnFreely(const btRigidBody& body, const btQuaternion& start, btScalar timeStep, btQuaternion& end,
                       btVector3& angularVelocityAtEnd)
{
	const btVector3& inverse = body.getInvInertiaDiagLocal();
	const btVector3 inertia(btScalar(1) / inverse.x(), btScalar(1) / inverse.y(), btScalar(1) / inverse.z());
	btVector3 momentum = (body.getAngularVelocity() * btMatrix3x3(start)) * inertia;  // in the body frame
	btQuaternion turn(0, 0, 0, 1);
	// A rotation about body axis `axis` by the angle its momentum gives over dt. Rational form: the
	// unnormalised quaternion (t axis, 1) turns by 2 atan t, and the momentum turns back by the same
	// angle with cos = (1 - t^2) / (1 + t^2), sin = 2 t / (1 + t^2). With t = tan(angle / 2) the angle is
	// exact, so a body spinning about a principal axis turns by exactly w h, as with Bullet's update.
	auto aboutAxis = [&](int axis, btScalar dt)
	{
		const btScalar t = tanOfHalf(dt * momentum[axis] * inverse[axis]);
		btScalar q[3] = {0, 0, 0};
		q[axis] = t;
		turn *= btQuaternion(q[0], q[1], q[2], btScalar(1));
		const btScalar scale = btScalar(1) / (btScalar(1) + t * t);
		const btScalar c = (btScalar(1) - t * t) * scale, s = btScalar(2) * t * scale;
		const int i = (axis + 1) % 3, j = (axis + 2) % 3;
		const btScalar mi = momentum[i], mj = momentum[j];
		momentum[i] = c * mi + s * mj;
		momentum[j] = c * mj - s * mi;
	};
	const btScalar half = btScalar(0.5) * timeStep;
	aboutAxis(0, half);
	aboutAxis(1, half);
	aboutAxis(2, timeStep);
	aboutAxis(1, half);
	aboutAxis(0, half);
	end = (start * turn).normalized();
	angularVelocityAtEnd = btMatrix3x3(end) * (momentum * inverse);
}
}  // namespace caliber

#endif  // CALIBER_SPIN_MOMENTUM_H
