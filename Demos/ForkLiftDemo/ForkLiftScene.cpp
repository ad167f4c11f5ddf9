// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "ForkLiftScene.h"

namespace fork_lift_demo
{
Scene::Scene()
{
	m_world.setGravity(btVector3(0, -10, 0));
	box(btVector3(50, 1, 50), 0, btVector3(0, -1, 0));  // ground, top at y = 0
	// Two rails 0.3 m high, 0.7 m apart inside, and the load on them.
	box(btVector3(btScalar(0.1), btScalar(0.15), btScalar(0.6)), 0, btVector3(btScalar(-0.45), btScalar(0.15), 10));
	box(btVector3(btScalar(0.1), btScalar(0.15), btScalar(0.6)), 0, btVector3(btScalar(0.45), btScalar(0.15), 10));
	m_load = box(btVector3(btScalar(0.5), btScalar(0.4), btScalar(0.5)), 100, btVector3(0, btScalar(0.7), 10));

	// The fork lift: chassis, mast (hinged to the chassis' front), fork (sliding up the mast).
	const btScalar chassisY = btScalar(1.05);
	m_chassis = box(btVector3(btScalar(0.9), btScalar(0.4), btScalar(1.8)), 800, btVector3(0, chassisY, 0));
	m_mast = box(btVector3(btScalar(0.8), btScalar(1.2), btScalar(0.05)), 50, btVector3(0, btScalar(1.45), btScalar(1.95)));
	const btVector3 forkStart(0, btScalar(0.15), btScalar(2.62));
	m_fork = box(btVector3(btScalar(0.3), btScalar(0.05), btScalar(0.6)), 20, forkStart);

	m_hinge.reset(new btHingeConstraint(*m_chassis, *m_mast, btVector3(0, btScalar(0.25) - chassisY, btScalar(1.95)),
	                                    btVector3(0, btScalar(-1.2), 0), btVector3(1, 0, 0), btVector3(1, 0, 0)));
	m_hinge->setLimit(btScalar(-0.01), btScalar(0.01));
	m_world.addConstraint(m_hinge.get(), true);
	// The slide axis is the frames' x axis, turned to point up; position 0 is the fork's start.
	const btQuaternion xToUp(btVector3(0, 0, 1), SIMD_HALF_PI);
	m_slider.reset(new btSliderConstraint(*m_mast, *m_fork,
	                                      btTransform(xToUp, forkStart - m_mast->getCenterOfMassPosition()),
	                                      btTransform(xToUp, btVector3(0, 0, 0)), true));
	m_slider->setLowerLinLimit(0);
	m_slider->setUpperLinLimit(btScalar(1.5));
	m_slider->setLowerAngLimit(0);
	m_slider->setUpperAngLimit(0);
	m_slider->setPoweredLinMotor(true);
	m_slider->setMaxLinMotorForce(5000);
	m_slider->setTargetLinMotorVelocity(0);
	m_world.addConstraint(m_slider.get(), true);

	m_tuning.m_suspensionStiffness = 40;
	m_tuning.m_suspensionCompression = btScalar(6.3);  // about critical for k = 40 per kg on four wheels
	m_tuning.m_suspensionDamping = btScalar(6.3);
	m_tuning.m_frictionSlip = 1;
	m_raycaster.reset(new btDefaultVehicleRaycaster(&m_world));
	m_vehicle.reset(new btRaycastVehicle(m_tuning, m_chassis, m_raycaster.get()));
	m_vehicle->setCoordinateSystem(0, 1, 2);
	for (int i = 0; i < 4; ++i)
		m_vehicle->addWheel(
		    btVector3((i & 1) ? btScalar(-0.8) : btScalar(0.8), btScalar(-0.1), i < 2 ? btScalar(1.3) : btScalar(-1.3)),
		    btVector3(0, -1, 0), btVector3(-1, 0, 0), btScalar(0.6), btScalar(0.4), m_tuning, i < 2);
	m_world.addAction(m_vehicle.get());
}

Scene::~Scene()
{
	m_world.removeAction(m_vehicle.get());
	m_world.removeConstraint(m_slider.get());
	m_world.removeConstraint(m_hinge.get());
	for (int i = m_bodies.size() - 1; i >= 0; --i)
	{
		m_world.removeRigidBody(m_bodies[i]);
		delete m_bodies[i]->getMotionState();
		delete m_bodies[i];
	}
	for (int i = 0; i < m_shapes.size(); ++i) delete m_shapes[i];
}

btRigidBody* Scene::box(const btVector3& halfExtents, btScalar mass, const btVector3& origin, btScalar friction)
{
	btBoxShape* shape = new btBoxShape(halfExtents);
	m_shapes.push_back(shape);
	btVector3 inertia(0, 0, 0);
	if (mass > 0) shape->calculateLocalInertia(mass, inertia);
	btRigidBody* body = new btRigidBody(btRigidBody::btRigidBodyConstructionInfo(
	    mass, new btDefaultMotionState(btTransform(btQuaternion::getIdentity(), origin)), shape, inertia));
	body->setFriction(friction);
	if (mass > 0) body->setActivationState(DISABLE_DEACTIVATION);
	m_bodies.push_back(body);
	m_world.addRigidBody(body);
	return body;
}

void Scene::drive(btScalar throttle, btScalar steering, btScalar lift, bool brake)
{
	// Towards 2 m/s with a bounded force, as the demo's script drives.
	const btScalar target = 2 * btMax(btScalar(-1), btMin(btScalar(1), throttle));
	const btScalar now = m_chassis->getLinearVelocity().dot(m_vehicle->getForwardVector());
	const btScalar force = throttle == 0 ? btScalar(0) : btMax(btScalar(-3000), btMin(btScalar(3000), 2000 * (target - now)));
	m_vehicle->applyEngineForce(force, 2);
	m_vehicle->applyEngineForce(force, 3);
	const btScalar angle = btScalar(0.4) * btMax(btScalar(-1), btMin(btScalar(1), steering));
	m_vehicle->setSteeringValue(angle, 0);
	m_vehicle->setSteeringValue(angle, 1);
	for (int i = 0; i < 4; ++i) m_vehicle->setBrake(brake ? 50 : 0, i);
	m_slider->setTargetLinMotorVelocity(btScalar(0.4) * btMax(btScalar(-1), btMin(btScalar(1), lift)));
}
}  // namespace fork_lift_demo
