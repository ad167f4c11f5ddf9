// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_RAYCASTVEHICLE_H
#define BT_RAYCASTVEHICLE_H

/// btRaycastVehicle: a rigid body driven on wheels that are rays with springs (docs/actions.md), and
/// btDefaultVehicleRaycaster, the world's ray test as the vehicle's raycaster.

#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "BulletDynamics/Dynamics/btActionInterface.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "btVehicleRaycaster.h"
#include "btWheelInfo.h"

class btDynamicsWorld;
class btIDebugDraw;

/// A vehicle: a chassis rigid body held up by one spring per wheel, each wheel a set of rays cast
/// down the suspension, with tyre friction, driving and braking at the wheel contacts. Add it to the
/// world with addAction (or addVehicle); it is updated once per substep after the bodies moved.
class btRaycastVehicle : public btActionInterface
{
	btAlignedObjectArray<btVector3> m_forwardWS;
	btAlignedObjectArray<btVector3> m_axle;
	btAlignedObjectArray<btScalar> m_forwardImpulse;
	btAlignedObjectArray<btScalar> m_sideImpulse;

	int m_userConstraintType;
	int m_userConstraintId;

public:
	/// The suspension and tyre values addWheel gives new wheels (Bullet's defaults).
	class btVehicleTuning
	{
	public:
		/// Bullet's defaults: stiffness 5.88, compression 0.83, damping 0.88, travel 500 cm,
		/// friction slip 10.5, max suspension force 6000.
		btVehicleTuning()
		    : m_suspensionStiffness(btScalar(5.88)),
		      m_suspensionCompression(btScalar(0.83)),
		      m_suspensionDamping(btScalar(0.88)),
		      m_maxSuspensionTravelCm(btScalar(500.)),
		      m_frictionSlip(btScalar(10.5)),
		      m_maxSuspensionForce(btScalar(6000.))
		{
		}
		/// Spring stiffness per unit chassis mass (1/s^2).
		btScalar m_suspensionStiffness;
		/// Damping per unit chassis mass while compressing (1/s).
		btScalar m_suspensionCompression;
		/// Damping per unit chassis mass while extending (1/s).
		btScalar m_suspensionDamping;
		/// Travel either side of the rest length, in centimetres.
		btScalar m_maxSuspensionTravelCm;
		/// Tyre friction coefficient.
		btScalar m_frictionSlip;
		/// Largest suspension force (newtons).
		btScalar m_maxSuspensionForce;
	};

private:
	btVehicleRaycaster* m_vehicleRaycaster;
	btScalar m_pitchControl;
	btScalar m_steeringValue;
	btScalar m_currentVehicleSpeedKmHour;

	btRigidBody* m_chassisBody;

	int m_indexRightAxis;
	int m_indexUpAxis;
	int m_indexForwardAxis;

	void defaultInit(const btVehicleTuning& tuning);

public:
	/// A vehicle without wheels on chassis, casting its wheels' rays with raycaster. Neither may be
	/// null (docs/bad-input.md); both must outlive the vehicle.
	btRaycastVehicle(const btVehicleTuning& tuning, btRigidBody* chassis, btVehicleRaycaster* raycaster);

	~btRaycastVehicle() override;

	/// The world's per-substep call: updateVehicle(step).
	void updateAction(btCollisionWorld* collisionWorld, btScalar step) override
	{
		(void)collisionWorld;
		updateVehicle(step);
	}

	/// Draws each wheel's axle and its contact.
	void debugDraw(btIDebugDraw* debugDrawer) override;

	/// The chassis' world transform.
	const btTransform& getChassisWorldTransform() const;

	/// Casts the wheel's rays and sets its contact and suspension length; returns the depth of the
	/// contact along the suspension (-1 when the wheel is in the air).
	btScalar rayCast(btWheelInfo& wheel);

	/// One update: wheel transforms, rays, suspension, friction, wheel spin.
	virtual void updateVehicle(btScalar step);

	/// Puts every wheel at its rest length, off the ground.
	void resetSuspension();

	/// Steering angle of a wheel.
	btScalar getSteeringValue(int wheel) const;

	/// Sets a wheel's steering angle (radians).
	void setSteeringValue(btScalar steering, int wheel);

	/// Sets a wheel's driving force (newtons, along the wheel's forward direction).
	void applyEngineForce(btScalar force, int wheel);

	/// A wheel's world transform as of the last updateWheelTransform.
	const btTransform& getWheelTransformWS(int wheelIndex) const;

	/// Recomputes a wheel's world transform (interpolatedTransform: from the motion state).
	void updateWheelTransform(int wheelIndex, bool interpolatedTransform = true);

	/// Adds a wheel and returns it (the reference stays valid until the next addWheel).
	btWheelInfo& addWheel(const btVector3& connectionPointCS0, const btVector3& wheelDirectionCS0,
	                      const btVector3& wheelAxleCS, btScalar suspensionRestLength, btScalar wheelRadius,
	                      const btVehicleTuning& tuning, bool isFrontWheel);

	/// Number of wheels.
	inline int getNumWheels() const { return int(m_wheelInfo.size()); }

	/// The wheels.
	btAlignedObjectArray<btWheelInfo> m_wheelInfo;

	/// A wheel.
	const btWheelInfo& getWheelInfo(int index) const;

	/// A wheel.
	btWheelInfo& getWheelInfo(int index);

	/// Recomputes a wheel's hard point, suspension direction and axle in world space.
	void updateWheelTransformsWS(btWheelInfo& wheel, bool interpolatedTransform = true);

	/// Sets a wheel's largest braking impulse per substep (newton seconds, >= 0).
	void setBrake(btScalar brake, int wheelIndex);

	/// Stored for Bullet compatibility; not used by the simulation (as in Bullet).
	void setPitchControl(btScalar pitch) { m_pitchControl = pitch; }

	/// Computes each wheel's suspension force from its compression and compression rate.
	void updateSuspension(btScalar deltaTime);

	/// Applies tyre friction, driving and braking at the wheel contacts.
	virtual void updateFriction(btScalar timeStep);

	/// The chassis.
	inline btRigidBody* getRigidBody() { return m_chassisBody; }

	/// The chassis.
	const btRigidBody* getRigidBody() const { return m_chassisBody; }

	/// Index of the chassis axis pointing right.
	inline int getRightAxis() const { return m_indexRightAxis; }
	/// Index of the chassis axis pointing up.
	inline int getUpAxis() const { return m_indexUpAxis; }
	/// Index of the chassis axis pointing forward.
	inline int getForwardAxis() const { return m_indexForwardAxis; }

	/// The chassis' forward axis in world space.
	btVector3 getForwardVector() const;

	/// Chassis speed in km/h, negative when moving backwards.
	btScalar getCurrentSpeedKmHour() const { return m_currentVehicleSpeedKmHour; }

	/// Chooses which chassis axes are right, up and forward (0, 1, 2 = x, y, z; a permutation).
	virtual void setCoordinateSystem(int rightIndex, int upIndex, int forwardIndex);

	/// Free for the user (from Bullet's constraint days).
	int getUserConstraintType() const { return m_userConstraintType; }
	/// Free for the user.
	void setUserConstraintType(int userConstraintType) { m_userConstraintType = userConstraintType; }
	/// Free for the user.
	void setUserConstraintId(int uid) { m_userConstraintId = uid; }
	/// Free for the user.
	int getUserConstraintId() const { return m_userConstraintId; }
};

/// The vehicle raycaster over a dynamics world's ray test. It skips the vehicle's own chassis and
/// objects without contact response, and honours the chassis' collision filter group and mask.
class btDefaultVehicleRaycaster : public btVehicleRaycaster
{
	btDynamicsWorld* m_dynamicsWorld;

public:
	/// A raycaster over world (which must outlive it).
	btDefaultVehicleRaycaster(btDynamicsWorld* world) : m_dynamicsWorld(world) {}

	/// The closest hit between from and to.
	void* castRay(const btVector3& from, const btVector3& to, btVehicleRaycasterResult& result) override;
};

#endif  // BT_RAYCASTVEHICLE_H
