// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "LinearMath/btWarningHook.h"

namespace
{
// Material and CCD coefficients are finite and never negative; anything else would spread NaN or
// turn friction into a driving force. Reports and returns false for such a value (release builds).
bool acceptCoefficient(btScalar value, const char* warning)
{
	const bool valid = value >= btScalar(0) && btIsFinite(value);
	if (!valid) btReportWarning(warning);
	btAssert(valid && "btCollisionObject: a material or CCD coefficient must be finite and >= 0");
	return valid;
}
}  // namespace

btCollisionObject::btCollisionObject()
    : m_interpolationLinearVelocity(0, 0, 0),
      m_interpolationAngularVelocity(0, 0, 0),
      m_anisotropicFriction(1, 1, 1),
      m_hasAnisotropicFriction(CF_ANISOTROPIC_FRICTION_DISABLED),
      m_contactProcessingThreshold(btScalar(BT_LARGE_FLOAT)),
      m_broadphaseHandle(0),
      m_collisionShape(0),
      m_extensionPointer(0),
      m_rootCollisionShape(0),
      m_collisionFlags(CF_STATIC_OBJECT),
      m_islandTag1(-1),
      m_companionId(-1),
      m_worldArrayIndex(-1),
      m_activationState1(ACTIVE_TAG),
      m_deactivationTime(btScalar(0)),
      m_friction(btScalar(0.5)),
      m_restitution(btScalar(0)),
      m_rollingFriction(btScalar(0)),
      m_spinningFriction(btScalar(0)),
      m_contactDamping(btScalar(0.1)),
      m_contactStiffness(btScalar(BT_LARGE_FLOAT)),
      m_internalType(CO_COLLISION_OBJECT),
      m_userObjectPointer(0),
      m_userIndex2(-1),
      m_userIndex(-1),
      m_userIndex3(-1),
      m_hitFraction(btScalar(1)),
      m_ccdSweptSphereRadius(btScalar(0)),
      m_ccdMotionThreshold(btScalar(0)),
      m_checkCollideWith(0),
      m_updateRevision(0),
      m_customDebugColorRGB(0, 0, 0)
{
	m_worldTransform.setIdentity();
	m_interpolationWorldTransform.setIdentity();
}

btCollisionObject::~btCollisionObject() {}

void btCollisionObject::setIgnoreCollisionCheck(const btCollisionObject* co, bool ignoreCollisionCheck)
{
	const int index = m_objectsWithoutCollisionCheck.findLinearSearch(co);
	const bool listed = index < m_objectsWithoutCollisionCheck.size();
	if (ignoreCollisionCheck)
	{
		// Kept unique so that one "false" call is enough to undo any number of "true" calls.
		if (!listed) m_objectsWithoutCollisionCheck.push_back(co);
	}
	else if (listed)
	{
		m_objectsWithoutCollisionCheck.swap(index, m_objectsWithoutCollisionCheck.size() - 1);
		m_objectsWithoutCollisionCheck.pop_back();
	}
	m_checkCollideWith = m_objectsWithoutCollisionCheck.size() > 0 ? 1 : 0;
}

bool btCollisionObject::checkCollideWithOverride(const btCollisionObject* co) const
{
	return m_objectsWithoutCollisionCheck.findLinearSearch(co) >= m_objectsWithoutCollisionCheck.size();
}

void btCollisionObject::setActivationState(int newState) const
{
	// These two states are user decisions that only forceActivationState may override.
	if (m_activationState1 != DISABLE_DEACTIVATION && m_activationState1 != DISABLE_SIMULATION)
		m_activationState1 = newState;
}

void btCollisionObject::forceActivationState(int newState) const { m_activationState1 = newState; }

void btCollisionObject::activate(bool forceActivation) const
{
	if (forceActivation || (m_collisionFlags & (CF_STATIC_OBJECT | CF_KINEMATIC_OBJECT)) == 0)
	{
		setActivationState(ACTIVE_TAG);
		m_deactivationTime = btScalar(0);
	}
}

void btCollisionObject::setRestitution(btScalar rest)
{
	if (!acceptCoefficient(rest, "Caliber: setRestitution: negative or non-finite; ignored\n")) return;
	m_updateRevision++;
	m_restitution = rest;
}

void btCollisionObject::setFriction(btScalar frict)
{
	if (!acceptCoefficient(frict, "Caliber: setFriction: negative or non-finite; ignored\n")) return;
	m_updateRevision++;
	m_friction = frict;
}

void btCollisionObject::setRollingFriction(btScalar frict)
{
	if (!acceptCoefficient(frict, "Caliber: setRollingFriction: negative or non-finite; ignored\n")) return;
	m_updateRevision++;
	m_rollingFriction = frict;
}

void btCollisionObject::setSpinningFriction(btScalar frict)
{
	if (!acceptCoefficient(frict, "Caliber: setSpinningFriction: negative or non-finite; ignored\n")) return;
	m_updateRevision++;
	m_spinningFriction = frict;
}

void btCollisionObject::setCcdSweptSphereRadius(btScalar radius)
{
	if (!acceptCoefficient(radius, "Caliber: setCcdSweptSphereRadius: negative or non-finite; ignored\n")) return;
	m_ccdSweptSphereRadius = radius;
}

void btCollisionObject::setCcdMotionThreshold(btScalar ccdMotionThreshold)
{
	if (!acceptCoefficient(ccdMotionThreshold, "Caliber: setCcdMotionThreshold: negative or non-finite; ignored\n"))
		return;
	m_ccdMotionThreshold = ccdMotionThreshold;
}

void btCollisionObject::setContactStiffnessAndDamping(btScalar stiffness, btScalar damping)
{
	if (!btIsFinite(stiffness) ||
	    !acceptCoefficient(damping, "Caliber: setContactStiffnessAndDamping: bad damping; ignored\n"))
	{
		if (!btIsFinite(stiffness)) btReportWarning("Caliber: setContactStiffnessAndDamping: non-finite stiffness; ignored\n");
		btAssert(btIsFinite(stiffness) && "setContactStiffnessAndDamping: non-finite stiffness");
		return;
	}
	m_updateRevision++;
	m_contactStiffness = stiffness < SIMD_EPSILON ? SIMD_EPSILON : stiffness;
	m_contactDamping = damping;
	m_collisionFlags |= CF_HAS_CONTACT_STIFFNESS_DAMPING;
}

void btCollisionObject::setWorldTransform(const btTransform& worldTrans)
{
	const bool finite = caliber::isFinite(worldTrans);
	btAssert(finite && "btCollisionObject::setWorldTransform: non-finite transform");
	if (!finite) return;
	m_updateRevision++;
	m_worldTransform = worldTrans;
}
