// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btTransformUtil.h"

void btTransformUtil::integrateTransform(const btTransform& curTrans, const btVector3& linvel, const btVector3& angvel,
                                         btScalar timeStep, btTransform& predictedTransform)
{
	predictedTransform.setOrigin(curTrans.getOrigin() + linvel * timeStep);

	btVector3 spin = angvel;
	btScalar speed = spin.length();
	if (speed * timeStep > ANGULAR_MOTION_THRESHOLD)
	{
		// Keep the axis, limit the angle of this step to the threshold.
		const btScalar clampedSpeed = ANGULAR_MOTION_THRESHOLD / timeStep;
		spin *= clampedSpeed / speed;
		speed = clampedSpeed;
	}

	// The rotation by angle |w| dt about w / |w| is the quaternion (w * sin(h) / |w|, cos(h)) with
	// h = |w| dt / 2. sin(h) / |w| loses precision for tiny |w|, so use its series there.
	const btScalar halfAngle = btScalar(0.5) * speed * timeStep;
	btScalar sinHalfOverSpeed;
	if (halfAngle < btScalar(1e-3))
	{
		// sin(h) / h = 1 - h^2/6 + h^4/120 - ...; the next term is below 2e-22 here.
		const btScalar h2 = halfAngle * halfAngle;
		sinHalfOverSpeed = btScalar(0.5) * timeStep * (btScalar(1.0) - h2 / btScalar(6.0) + h2 * h2 / btScalar(120.0));
	}
	else
		sinHalfOverSpeed = btSin(halfAngle) / speed;
	const btVector3 axisPart = spin * sinHalfOverSpeed;
	const btQuaternion step(axisPart.x(), axisPart.y(), axisPart.z(), btCos(halfAngle));

	btQuaternion predicted = step * curTrans.getRotation();
	predicted.safeNormalize();
	predictedTransform.setRotation(predicted);
}

void btTransformUtil::calculateVelocityQuaternion(const btVector3& pos0, const btVector3& pos1,
                                                  const btQuaternion& orn0, const btQuaternion& orn1, btScalar timeStep,
                                                  btVector3& linVel, btVector3& angVel)
{
	btAssert(timeStep > btScalar(0));
	if (!(timeStep > btScalar(0)))
	{
		linVel.setValue(0, 0, 0);
		angVel.setValue(0, 0, 0);
		return;
	}
	linVel = (pos1 - pos0) / timeStep;
	btVector3 axis;
	btScalar angle;
	calculateDiffAxisAngleQuaternion(orn0, orn1, axis, angle);
	angVel = axis * (angle / timeStep);
}

namespace
{
// Axis and angle of a rotation quaternion, taking the short way round (angle in [0, pi]).
void axisAngleShortestPath(btQuaternion rotation, btVector3& axis, btScalar& angle)
{
	if (rotation.w() < btScalar(0)) rotation = -rotation;
	const btVector3 vectorPart(rotation.x(), rotation.y(), rotation.z());
	const btScalar sinHalfAngle = vectorPart.length();
	// atan2 rather than acos(w): acos is flat near w = 1, so small angles would round to 0.
	angle = btScalar(2.0) * btAtan2(sinHalfAngle, rotation.w());
	if (sinHalfAngle > btScalar(0))
		axis = vectorPart / sinHalfAngle;
	else
		axis.setValue(btScalar(1.0), btScalar(0.0), btScalar(0.0));
}
}  // namespace

void btTransformUtil::calculateDiffAxisAngleQuaternion(const btQuaternion& orn0, const btQuaternion& orn1a,
                                                       btVector3& axis, btScalar& angle)
{
	btQuaternion difference = orn1a * orn0.inverse();
	difference.safeNormalize();
	axisAngleShortestPath(difference, axis, angle);
}

void btTransformUtil::calculateVelocity(const btTransform& transform0, const btTransform& transform1, btScalar timeStep,
                                        btVector3& linVel, btVector3& angVel)
{
	btAssert(timeStep > btScalar(0));
	if (!(timeStep > btScalar(0)))
	{
		linVel.setValue(0, 0, 0);
		angVel.setValue(0, 0, 0);
		return;
	}
	linVel = (transform1.getOrigin() - transform0.getOrigin()) / timeStep;
	btVector3 axis;
	btScalar angle;
	calculateDiffAxisAngle(transform0, transform1, axis, angle);
	angVel = axis * (angle / timeStep);
}

void btTransformUtil::calculateDiffAxisAngle(const btTransform& transform0, const btTransform& transform1,
                                             btVector3& axis, btScalar& angle)
{
	// For rotation matrices the inverse is the transpose.
	const btMatrix3x3 difference = transform1.getBasis().timesTranspose(transform0.getBasis());
	btQuaternion rotation;
	difference.getRotation(rotation);
	rotation.safeNormalize();
	axisAngleShortestPath(rotation, axis, angle);
}

btConvexSeparatingDistanceUtil::btConvexSeparatingDistanceUtil(btScalar boundingRadiusA, btScalar boundingRadiusB)
    : m_ornA(btQuaternion::getIdentity()),
      m_ornB(btQuaternion::getIdentity()),
      m_posA(0, 0, 0),
      m_posB(0, 0, 0),
      m_separatingNormal(0, 0, 0),
      m_boundingRadiusA(boundingRadiusA),
      m_boundingRadiusB(boundingRadiusB),
      m_separatingDistance(0.f)
{
}

void btConvexSeparatingDistanceUtil::updateSeparatingDistance(const btTransform& transA, const btTransform& transB)
{
	const btVector3 toPosA = transA.getOrigin();
	const btVector3 toPosB = transB.getOrigin();
	const btQuaternion toOrnA = transA.getRotation();
	const btQuaternion toOrnB = transB.getRotation();

	if (m_separatingDistance > btScalar(0.0))
	{
		// Displacements over the update (velocities over a unit time step).
		btVector3 linVelA, angVelA, linVelB, angVelB;
		btTransformUtil::calculateVelocityQuaternion(m_posA, toPosA, m_ornA, toOrnA, btScalar(1.), linVelA, angVelA);
		btTransformUtil::calculateVelocityQuaternion(m_posB, toPosB, m_ornB, toOrnB, btScalar(1.), linVelB, angVelB);
		// A point at radius r on a body turning by angle a moves at most r * a.
		const btScalar rotationalApproach = angVelA.length() * m_boundingRadiusA + angVelB.length() * m_boundingRadiusB;
		// The normal points from B to A: B moving along it (relative to A) closes the gap.
		btScalar linearApproach = (linVelB - linVelA).dot(m_separatingNormal);
		if (linearApproach < btScalar(0.0)) linearApproach = btScalar(0.0);
		m_separatingDistance -= rotationalApproach + linearApproach;
	}

	m_posA = toPosA;
	m_posB = toPosB;
	m_ornA = toOrnA;
	m_ornB = toOrnB;
}

void btConvexSeparatingDistanceUtil::initSeparatingDistance(const btVector3& separatingVector,
                                                            btScalar separatingDistance, const btTransform& transA,
                                                            const btTransform& transB)
{
	m_separatingDistance = separatingDistance;
	if (m_separatingDistance > btScalar(0.0))
	{
		m_separatingNormal = separatingVector;
		m_posA = transA.getOrigin();
		m_posB = transB.getOrigin();
		m_ornA = transA.getRotation();
		m_ornB = transB.getRotation();
	}
}
