// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "ConstraintScene.h"

namespace constraint_demo
{
namespace
{
btTransform at(const btVector3& origin, const btQuaternion& q = btQuaternion::getIdentity())
{
	return btTransform(q, origin);
}
}  // namespace

Scene::Scene()
{
	world().setGravity(btVector3(0, -10, 0));
	// Ball joint: a 1 m pendulum released at 60 degrees from a pivot at (0, 5, 0).
	const btScalar theta = SIMD_PI / 3;
	bob = body(new btSphereShape(btScalar(0.1)), 1,
	           at(btVector3(btSin(theta), 5 - btCos(theta), 0), btQuaternion(btVector3(0, 0, 1), theta)));
	ball = joint(new btPoint2PointConstraint(*bob, btVector3(0, 1, 0)));

	// Door: hinged about y at its edge, limited to -30..+45 degrees, pushed by a torque that flips
	// every second.
	door = body(new btBoxShape(btVector3(0.5, 1, 0.05)), 10, at(btVector3(3.5, 5, 0)));
	doorHinge = joint(new btHingeConstraint(*door, btVector3(-0.5, 0, 0), btVector3(0, 1, 0)));
	doorHinge->setLimit(-SIMD_PI / 6, SIMD_PI / 4);

	// Wheel: a motor spins it up to 2 turns per second with at most 0.05 N m s per step.
	wheel = body(new btCylinderShapeZ(btVector3(0.5, 0.5, 0.1)), 5, at(btVector3(6, 5, 0)));
	axle = joint(new btHingeConstraint(*wheel, btVector3(0, 0, 0), btVector3(0, 0, 1)));
	axle->enableAngularMotor(true, 4 * SIMD_PI, btScalar(0.05));

	// Limb: a capsule hanging from a cone-twist joint (30-degree cone), kicked sideways.
	limb = body(new btCapsuleShape(btScalar(0.1), 1), 1, at(btVector3(9, 4, 0)));
	btTransform frameInLimb(btMatrix3x3(0, -1, 0, 1, 0, 0, 0, 0, 1), btVector3(0, 1, 0));
	shoulder = joint(new btConeTwistConstraint(*limb, frameInLimb));
	shoulder->setLimit(SIMD_PI / 6, SIMD_PI / 6, btScalar(0.3));
	limb->applyCentralImpulse(btVector3(4, 0, 2));

	// Slider: a carriage on a rail tilted 30 degrees, driven up by a motor (at most 20 N) to its upper
	// limit 1 m along, which it reaches and holds.
	const btQuaternion tilt(btVector3(0, 0, 1), SIMD_PI / 6);
	carriage = body(new btBoxShape(btVector3(0.2, 0.1, 0.1)), 1, at(btVector3(12, 5, 0), tilt));
	rail = joint(new btSliderConstraint(*carriage, btTransform::getIdentity(), true));
	rail->setLowerLinLimit(-1);
	rail->setUpperLinLimit(1);
	rail->setLowerAngLimit(0);
	rail->setUpperAngLimit(0);
	rail->setPoweredLinMotor(true);
	rail->setTargetLinMotorVelocity(1);
	rail->setMaxLinMotorForce(20);

	// Gears: two wheels on hinges, geared 2:1; the small one is driven at 2 turns per second.
	small = body(new btCylinderShapeZ(btVector3(0.25, 0.25, 0.1)), 1, at(btVector3(15, 5, 0)));
	large = body(new btCylinderShapeZ(btVector3(0.5, 0.5, 0.1)), 1, at(btVector3(15.75, 5, 0)));
	smallAxle = joint(new btHingeConstraint(*small, btVector3(0, 0, 0), btVector3(0, 0, 1)));
	joint(new btHingeConstraint(*large, btVector3(0, 0, 0), btVector3(0, 0, 1)));
	joint(new btGearConstraint(*small, *large, btVector3(0, 0, 1), btVector3(0, 0, 1), 2));
	smallAxle->enableAngularMotor(true, 4 * SIMD_PI, 1);

	// Spring: a 1 kg weight on a vertical 6-DoF spring (k = 40 N/m, lightly damped) to the world,
	// released at the spring's rest length: it bobs about m g / k = 0.25 m lower and settles there.
	weight = body(new btBoxShape(btVector3(0.1, 0.1, 0.1)), 1, at(btVector3(18, 5, 0)));
	spring = joint(new btGeneric6DofSpring2Constraint(*weight, btTransform::getIdentity()));
	spring->setLinearLowerLimit(btVector3(0, 1, 0));  // y free (lower > upper), x and z locked
	spring->setLinearUpperLimit(btVector3(0, -1, 0));
	spring->enableSpring(1, true);
	spring->setStiffness(1, 40);
	spring->setDamping(1, btScalar(0.5));
	spring->setEquilibriumPoint(1, 0);

	// Weld: an L of two boxes joined by a fixed joint, thrown spinning: it turns as one body.
	armA = body(new btBoxShape(btVector3(0.5, 0.1, 0.1)), 1, at(btVector3(21, 6, 0)));
	armB = body(new btBoxShape(btVector3(0.1, 0.5, 0.1)), 1, at(btVector3(21.4, 6.6, 0)));
	joint(new btFixedConstraint(*armA, *armB, at(btVector3(0.4, 0, 0)), at(btVector3(0, -0.6, 0))));
	armA->setAngularVelocity(btVector3(0, 0, 3));

	// Cardan joint: an input shaft along x driven at 2 rad/s by a hinge motor, a universal joint at its end
	// and an output shaft bent 30 degrees up, both on hinges to the world through their centres. The
	// output turns at between cos 30 = 0.866 and 1 / cos 30 = 1.155 times the input's rate.
	input = body(new btBoxShape(btVector3(0.5, 0.05, 0.05)), 1, at(btVector3(24.5, 5, 0)));
	output = body(new btBoxShape(btVector3(0.5, 0.05, 0.05)), 1,
	              at(btVector3(25, 5, 0) + outputAxis * btScalar(0.5), btQuaternion(btVector3(0, 0, 1), bend)));
	inputBearing = joint(new btHingeConstraint(*input, btVector3(0, 0, 0), btVector3(1, 0, 0)));
	joint(new btHingeConstraint(*output, btVector3(0, 0, 0), btVector3(1, 0, 0)));
	joint(new btUniversalConstraint(*input, *output, btVector3(25, 5, 0), btVector3(0, 0, 1),
	                                btVector3(-btSin(bend), btCos(bend), 0)));
	inputBearing->enableAngularMotor(true, 2, 10);
}

Scene::~Scene()
{
	for (auto& joint : m_joints) world().removeConstraint(joint.get());
	for (auto& body : m_bodies) world().removeRigidBody(body.get());
}

btRigidBody* Scene::body(btCollisionShape* shape, btScalar mass, const btTransform& pose)
{
	m_shapes.emplace_back(shape);
	btVector3 inertia(0, 0, 0);
	if (mass > 0) shape->calculateLocalInertia(mass, inertia);
	btRigidBody::btRigidBodyConstructionInfo info(mass, 0, shape, inertia);
	info.m_startWorldTransform = pose;
	m_bodies.emplace_back(new btRigidBody(info));
	m_bodies.back()->setActivationState(DISABLE_DEACTIVATION);
	world().addRigidBody(m_bodies.back().get());
	return m_bodies.back().get();
}

void Scene::step(int frame)
{
	door->applyTorque(btVector3(0, (frame / 60) % 2 ? -40 : 40, 0));
	world().stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.));
}
}  // namespace constraint_demo
