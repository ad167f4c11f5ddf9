// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// caliber::saveWorldState / restoreWorldState / compareWorldState: stepping on from a restored snapshot is
// bit-identical to never having stopped (the rollback case), in the same world and in a second world
// built the same way (the netcode case), for small versions of the benchmark scenes (a pile of mixed
// shapes, a stack, jointed chains with every kind of joint and a motor, convex hulls and spheres on a
// BVH mesh, bodies falling asleep, fast CCD bodies); and bad buffers are refused with the world unchanged.

#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "BulletDynamics/Dynamics/DynamicsWorldTestUtil.h"
#include "BulletCollision/CollisionDispatch/btGhostObject.h"
#include "BulletDynamics/Character/btKinematicCharacterController.h"
#include "Caliber/WorldSnapshot.h"

namespace
{
using caliber_test::TestWorld;
using Bytes = btAlignedObjectArray<unsigned char>;

// ---- the scenes ---------------------------------------------------------------------------------

btTransform pose(const btVector3& origin, btScalar yaw = 0, btScalar pitch = 0)
{
	btQuaternion q;
	q.setEulerZYX(0, yaw, pitch);
	return btTransform(q, origin);
}

// Boxes, spheres, capsules and cylinders dropped in layers onto a box ground: box-box, sphere-box,
// sphere-sphere and GJK (convex-convex) pairs, contacts appearing and breaking.
void buildPile(TestWorld& t)
{
	t.addGround(btScalar(0.6), btScalar(0.1));
	btCollisionShape* box = t.shape<btBoxShape>(btVector3(0.5, 0.5, 0.5));
	btCollisionShape* sphere = t.shape<btSphereShape>(btScalar(0.5));
	btCollisionShape* capsule = t.shape<btCapsuleShape>(btScalar(0.3), btScalar(0.8));
	btCollisionShape* cylinder = t.shape<btCylinderShape>(btVector3(0.4, 0.5, 0.4));
	btCollisionShape* shapes[4] = {box, sphere, capsule, cylinder};
	int k = 0;
	for (int layer = 0; layer < 3; ++layer)
		for (int x = 0; x < 3; ++x)
			for (int z = 0; z < 3; ++z, ++k)
				t.addBody(shapes[k % 4], 1,
				          pose(btVector3(x * 1.1 - 1.1 + 0.1 * layer, 0.6 + 1.3 * layer, z * 1.1 - 1.1),
				               btScalar(0.3 * k), btScalar(0.2 * layer)));
}

// A tower of boxes resting on each other: long-lived manifolds whose warm starts carry the stack.
void buildStack(TestWorld& t)
{
	t.addGround(btScalar(0.8), btScalar(0));
	btCollisionShape* box = t.shape<btBoxShape>(btVector3(0.5, 0.25, 0.5));
	for (int i = 0; i < 10; ++i) t.addBody(box, 1, pose(btVector3(0.01 * (i % 3), 0.25 + 0.5 * i, 0)));
}

// Hulls with polyhedral features stacked on a hull slab: clipped manifolds, whose pairs keep their contacts
// in the contact cache while they rest (include/Caliber/ContactCache.h).
void buildPolyhedralStack(TestWorld& t)
{
	btConvexHullShape* slab = t.shape<btConvexHullShape>();
	btConvexHullShape* block = t.shape<btConvexHullShape>();
	for (int i = 0; i < 8; ++i)
	{
		const btScalar sx = (i & 1) ? 1 : -1, sy = (i & 2) ? 1 : -1, sz = (i & 4) ? 1 : -1;
		slab->addPoint(btVector3(4 * sx, btScalar(0.5) * sy, 4 * sz));
		block->addPoint(btVector3(btScalar(0.5) * sx, btScalar(0.25) * sy, btScalar(0.5) * sz));
	}
	slab->initializePolyhedralFeatures();
	block->initializePolyhedralFeatures();
	t.addBody(slab, 0, btVector3(0, btScalar(-0.5), 0));
	for (int i = 0; i < 6; ++i) t.addBody(block, 1, pose(btVector3(0.01 * (i % 3), 0.26 + 0.5 * i, 0)));
}

// Chains hanging from static anchors, one per joint kind, swinging into each other and onto the ground:
// hinge (with a motor and limits), accumulated-angle hinge, cone twist, ball, slider, 6-DoF, 6-DoF spring,
// 6-DoF spring2, universal, fixed. Joint warm starts, limits, motors and the position correction.
void buildJoints(TestWorld& t)
{
	t.addGround(btScalar(0.5), btScalar(0));
	btCollisionShape* link = t.shape<btCapsuleShape>(btScalar(0.15), btScalar(0.5));
	btCollisionShape* anchorShape = t.shape<btBoxShape>(btVector3(0.1, 0.1, 0.1));
	for (int chain = 0; chain < 10; ++chain)
	{
		const btScalar x = btScalar(chain) * btScalar(0.7) - 3;
		btRigidBody* previous = t.addBody(anchorShape, 0, pose(btVector3(x, 6, 0)));
		for (int i = 0; i < 4; ++i)
		{
			// Links lean sideways so that the chains swing and hit their neighbours.
			btRigidBody* body =
			    t.addBody(link, 1, pose(btVector3(x + 0.3 * (i + 1), 5.6 - 0.6 * i, 0.1 * chain), 0, btScalar(1.2)));
			const btVector3 pivotPrev(0, previous->getInvMass() == 0 ? btScalar(-0.1) : btScalar(-0.4), 0);
			const btVector3 pivotThis(0, btScalar(0.4), 0);
			btTransform frameA(btQuaternion::getIdentity(), pivotPrev), frameB(btQuaternion::getIdentity(), pivotThis);
			switch (chain)
			{
				case 0:
				{
					btHingeConstraint* hinge = t.addJoint<btHingeConstraint>(
					    true, *previous, *body, pivotPrev, pivotThis, btVector3(0, 0, 1), btVector3(0, 0, 1));
					hinge->setLimit(-1, 1);
					if (i == 0) hinge->enableAngularMotor(true, 2, 5);
					break;
				}
				case 1:
					t.addJoint<btHingeAccumulatedAngleConstraint>(true, *previous, *body, pivotPrev, pivotThis,
					                                              btVector3(0, 0, 1), btVector3(0, 0, 1));
					break;
				case 2:
				{
					btConeTwistConstraint* cone =
					    t.addJoint<btConeTwistConstraint>(true, *previous, *body, frameA, frameB);
					cone->setLimit(btScalar(0.6), btScalar(0.6), btScalar(0.4));
					break;
				}
				case 3:
					t.addJoint<btPoint2PointConstraint>(true, *previous, *body, pivotPrev, pivotThis);
					break;
				case 4:
				{
					btSliderConstraint* slider =
					    t.addJoint<btSliderConstraint>(true, *previous, *body, frameA, frameB, true);
					slider->setLowerLinLimit(-0.2);
					slider->setUpperLinLimit(0.2);
					break;
				}
				case 5:
				{
					btGeneric6DofConstraint* dof =
					    t.addJoint<btGeneric6DofConstraint>(true, *previous, *body, frameA, frameB, true);
					dof->setAngularLowerLimit(btVector3(-0.5, -0.5, -0.5));
					dof->setAngularUpperLimit(btVector3(0.5, 0.5, 0.5));
					break;
				}
				case 6:
				{
					btGeneric6DofSpringConstraint* spring =
					    t.addJoint<btGeneric6DofSpringConstraint>(true, *previous, *body, frameA, frameB, true);
					spring->setLinearLowerLimit(btVector3(0, -0.1, 0));
					spring->setLinearUpperLimit(btVector3(0, 0.1, 0));
					spring->enableSpring(1, true);
					spring->setStiffness(1, 50);
					break;
				}
				case 7:
				{
					btGeneric6DofSpring2Constraint* spring2 =
					    t.addJoint<btGeneric6DofSpring2Constraint>(true, *previous, *body, frameA, frameB);
					spring2->setAngularLowerLimit(btVector3(-0.4, -0.4, -0.4));
					spring2->setAngularUpperLimit(btVector3(0.4, 0.4, 0.4));
					spring2->enableMotor(5, true);
					spring2->setTargetVelocity(5, 1);
					spring2->setMaxMotorForce(5, 3);
					break;
				}
				case 8:
					if (previous->getInvMass() == 0)
						t.addJoint<btPoint2PointConstraint>(true, *previous, *body, pivotPrev, pivotThis);
					else
						t.addJoint<btUniversalConstraint>(true, *previous, *body,
						                                  previous->getWorldTransform().getOrigin(), btVector3(0, 0, 1),
						                                  btVector3(1, 0, 0));
					break;
				default:
					t.addJoint<btFixedConstraint>(true, *previous, *body, frameA, frameB);
					break;
			}
			previous = body;
		}
	}
	// Half the joints report their applied impulse (which the trace then compares).
	for (int j = 0; j < t.world()->getNumConstraints(); j += 2) t.world()->getConstraint(j)->enableFeedback(true);
}

// Convex hulls, boxes, spheres and capsules on a bumpy BVH triangle mesh: the mesh algorithm with its
// triangle algorithm and the mesh contact collector.
struct MeshOwner
{
	btTriangleMesh mesh;
};
std::vector<std::unique_ptr<MeshOwner>> g_meshes;

void buildMesh(TestWorld& t)
{
	g_meshes.emplace_back(new MeshOwner());
	btTriangleMesh& mesh = g_meshes.back()->mesh;
	const int cells = 8;
	auto height = [](int i, int j)
	{ return btScalar(0.3) * btSin(btScalar(i) * btScalar(0.9)) * btCos(btScalar(j) * btScalar(0.7)); };
	for (int i = 0; i < cells; ++i)
		for (int j = 0; j < cells; ++j)
		{
			const btVector3 a(i - 4, height(i, j), j - 4), b(i + 1 - 4, height(i + 1, j), j - 4);
			const btVector3 c(i - 4, height(i, j + 1), j + 1 - 4), d(i + 1 - 4, height(i + 1, j + 1), j + 1 - 4);
			mesh.addTriangle(a, b, c);
			mesh.addTriangle(b, d, c);
		}
	btBvhTriangleMeshShape* ground = t.shape<btBvhTriangleMeshShape>(&mesh, true);
	t.addBody(ground, 0, btVector3(0, 0, 0));
	btConvexHullShape* hull = t.shape<btConvexHullShape>();
	for (int k = 0; k < 12; ++k)
	{
		const btScalar angle = btScalar(k) * SIMD_2_PI / 12;
		hull->addPoint(btVector3(btCos(angle) * btScalar(0.5), (k % 2) ? btScalar(0.4) : btScalar(-0.4),
		                         btSin(angle) * btScalar(0.5)));
	}
	btCollisionShape* shapes[4] = {hull, t.shape<btBoxShape>(btVector3(0.3, 0.3, 0.3)),
	                               t.shape<btSphereShape>(btScalar(0.35)),
	                               t.shape<btCapsuleShape>(btScalar(0.2), btScalar(0.5))};
	for (int k = 0; k < 16; ++k)
		t.addBody(shapes[k % 4], 1,
		          pose(btVector3((k % 4) * 1.5 - 2.2, 1 + 0.8 * (k / 4), (k / 4) * 1.4 - 2.0), btScalar(0.4 * k),
		               btScalar(0.3)));
}

// Three boxes on the ground, a capsule hinged to the top one: every part of a snapshot, small.
void buildSmall(TestWorld& t)
{
	t.addGround(btScalar(0.8), btScalar(0));
	btCollisionShape* box = t.shape<btBoxShape>(btVector3(0.5, 0.25, 0.5));
	btRigidBody* top = 0;
	for (int i = 0; i < 3; ++i) top = t.addBody(box, 1, pose(btVector3(0.02 * i, 0.25 + 0.5 * i, 0)));
	btRigidBody* arm =
	    t.addBody(t.shape<btCapsuleShape>(btScalar(0.1), btScalar(0.6)), 1, pose(btVector3(0.5, 1.6, 0)));
	t.addJoint<btHingeConstraint>(true, *top, *arm, btVector3(0.5, 0.25, 0), btVector3(0, -0.4, 0), btVector3(0, 0, 1),
	                              btVector3(0, 0, 1));
}

// Boxes that settle on the ground and fall asleep (islands go to sleep, deactivation times count), and
// one that keeps a sleeping island company until it is woken by a late falling box.
void buildSleepers(TestWorld& t)
{
	t.addGround(btScalar(1), btScalar(0));
	btCollisionShape* box = t.shape<btBoxShape>(btVector3(0.5, 0.5, 0.5));
	for (int i = 0; i < 6; ++i) t.addBody(box, 1, pose(btVector3(i * 2 - 5, 0.5 + 0.01 * i, 0)));
	t.addBody(box, 1, pose(btVector3(-5, 0.5 + 1.02, 0)));
	t.addBody(box, 1, pose(btVector3(3, 30, 0), btScalar(0.5)));  // falls onto a sleeping box after ~2.4 s
}

// Small fast spheres and a thin fast box with CCD shot at thin walls (swept, clamped at impact).
void buildCcd(TestWorld& t)
{
	t.addGround(btScalar(0.5), btScalar(0.3));
	btCollisionShape* wall = t.shape<btBoxShape>(btVector3(0.05, 2, 4));
	t.addBody(wall, 0, btVector3(5, 2, 0));
	t.addBody(wall, 0, btVector3(-5, 2, 0));
	btCollisionShape* pellet = t.shape<btSphereShape>(btScalar(0.1));
	btCollisionShape* plate = t.shape<btBoxShape>(btVector3(0.3, 0.02, 0.3));
	for (int i = 0; i < 6; ++i)
	{
		btRigidBody* body =
		    t.addBody(i % 2 ? plate : pellet, btScalar(0.2), pose(btVector3(0, 1 + 0.4 * i, -2 + 0.8 * i)));
		body->setLinearVelocity(btVector3(i % 2 ? -90 : 120, 1, 0));
		body->setCcdMotionThreshold(btScalar(0.05));
		body->setCcdSweptSphereRadius(btScalar(0.08));
		body->setRestitution(btScalar(0.5));
	}
}

// Compound bodies dropped onto each other, onto a box ground and onto a BVH mesh: the compound
// algorithm's child algorithms (box-box, sphere-box, GJK, and convex-mesh for children on the mesh), the
// compound-compound algorithm's child pairs, and a compound holding a compound (nested algorithms).
void buildCompounds(TestWorld& t)
{
	t.addGround(btScalar(0.7), btScalar(0));
	g_meshes.emplace_back(new MeshOwner());
	btTriangleMesh& mesh = g_meshes.back()->mesh;
	for (int i = 0; i < 4; ++i)
		for (int j = 0; j < 4; ++j)
		{
			const btScalar y = btScalar(0.05) * btScalar((i + j) % 3);
			const btVector3 a(i + 3, y, j - 2), b(i + 4, y, j - 2), c(i + 3, y, j - 1), d(i + 4, y, j - 1);
			mesh.addTriangle(a, b, c);
			mesh.addTriangle(b, d, c);
		}
	t.addBody(t.shape<btBvhTriangleMeshShape>(&mesh, true), 0, btVector3(0, btScalar(0.01), 0));
	btCollisionShape* box = t.shape<btBoxShape>(btVector3(0.4, 0.2, 0.2));
	btCollisionShape* ball = t.shape<btSphereShape>(btScalar(0.25));
	btCollisionShape* capsule = t.shape<btCapsuleShape>(btScalar(0.15), btScalar(0.4));
	btCompoundShape* ell = t.shape<btCompoundShape>();
	ell->addChildShape(pose(btVector3(0, 0, 0)), box);
	ell->addChildShape(pose(btVector3(0.3, 0.4, 0), btScalar(0), btScalar(1.5707963)), box);
	ell->addChildShape(pose(btVector3(-0.5, 0, 0)), ball);
	btCompoundShape* dumbbell = t.shape<btCompoundShape>();
	dumbbell->addChildShape(pose(btVector3(0, 0, 0), btScalar(0), btScalar(1.5707963)), capsule);
	dumbbell->addChildShape(pose(btVector3(0, 0, 0.45)), ball);
	dumbbell->addChildShape(pose(btVector3(0, 0, -0.45)), ball);
	btCompoundShape* nested = t.shape<btCompoundShape>();
	nested->addChildShape(pose(btVector3(0, 0, 0)), ell);
	nested->addChildShape(pose(btVector3(0, -0.3, 0.5)), box);
	btCompoundShape* shapes[3] = {ell, dumbbell, nested};
	for (int k = 0; k < 9; ++k)
		t.addBody(shapes[k % 3], 1,
		          pose(btVector3((k % 3) * 1.3 - 1.3 + (k >= 6 ? 4.5 : 0), 0.6 + 0.9 * (k / 3) * (k >= 6 ? 0 : 1),
		                         (k / 3) * 0.25),
		               btScalar(0.5 * k), btScalar(0.2 * k)));
}

// Two compounds, one resting on the other, on a box ground: a tiny scene for a long run.
void buildCompoundPair(TestWorld& t)
{
	t.addGround(btScalar(0.8), btScalar(0));
	btCompoundShape* pair = t.shape<btCompoundShape>();
	btCollisionShape* box = t.shape<btBoxShape>(btVector3(0.5, 0.2, 0.2));
	pair->addChildShape(pose(btVector3(0, 0, -0.25)), box);
	pair->addChildShape(pose(btVector3(0, 0, 0.25)), box);
	t.addBody(pair, 1, pose(btVector3(0, 0.2, 0)));
	t.addBody(pair, 1, pose(btVector3(0.1, 0.7, 0), btScalar(0.9)));
}

// A raycast vehicle driving and steering over a box ground into a few loose boxes: the wheels' rays,
// suspension, spin and tyre friction carry from step to step, and the chassis has contacts of its own.
// Scenes' extra objects are kept by their TestWorld and listed here while they live, for the trace.
template <class Owner>
struct Registered
{
	static std::vector<Owner*>& all()
	{
		static std::vector<Owner*> owners;
		return owners;
	}
	Registered() { all().push_back(static_cast<Owner*>(this)); }
	~Registered()
	{
		std::vector<Owner*>& owners = all();
		for (size_t i = 0; i < owners.size(); ++i)
			if (owners[i] == static_cast<Owner*>(this)) owners.erase(owners.begin() + long(i));
	}
	Registered(const Registered&) = delete;
	Registered& operator=(const Registered&) = delete;
};

struct VehicleOwner : Registered<VehicleOwner>
{
	btDynamicsWorld* world;
	std::unique_ptr<btDefaultVehicleRaycaster> raycaster;
	std::unique_ptr<btRaycastVehicle> vehicle;
};
std::vector<VehicleOwner*>& g_vehicles = Registered<VehicleOwner>::all();

void buildVehicle(TestWorld& t)
{
	t.addGround(btScalar(0.9), btScalar(0));
	btCollisionShape* crate = t.shape<btBoxShape>(btVector3(0.3, 0.3, 0.3));
	for (int i = 0; i < 3; ++i) t.addBody(crate, btScalar(0.5), pose(btVector3(0.4 * i - 0.4, 0.3, 6 + 0.7 * i)));
	btRigidBody* chassis = t.addBody(t.shape<btBoxShape>(btVector3(0.8, 0.25, 1.8)), 400, pose(btVector3(0, 1.0, 0)));
	chassis->setActivationState(DISABLE_DEACTIVATION);
	VehicleOwner& owner = *t.keep(new VehicleOwner());
	owner.world = t.world();
	owner.raycaster.reset(new btDefaultVehicleRaycaster(t.world()));
	btRaycastVehicle::btVehicleTuning tuning;
	owner.vehicle.reset(new btRaycastVehicle(tuning, chassis, owner.raycaster.get()));
	owner.vehicle->setCoordinateSystem(0, 1, 2);
	for (int w = 0; w < 4; ++w)
	{
		const btVector3 at(w % 2 ? 0.9 : -0.9, 0.0, w < 2 ? 1.4 : -1.4);
		btWheelInfo& wheel = owner.vehicle->addWheel(at, btVector3(0, -1, 0), btVector3(-1, 0, 0), btScalar(0.6),
		                                             btScalar(0.4), tuning, w < 2);
		wheel.m_suspensionStiffness = 20;
		wheel.m_wheelsDampingRelaxation = btScalar(2.3);
		wheel.m_wheelsDampingCompression = btScalar(4.4);
		wheel.m_frictionSlip = 1000;
		wheel.m_rollInfluence = btScalar(0.1);
	}
	t.world()->addAction(owner.vehicle.get());
	for (int w = 2; w < 4; ++w) owner.vehicle->applyEngineForce(800, w);
	for (int w = 0; w < 2; ++w) owner.vehicle->setSteeringValue(btScalar(0.12), w);
}

// Boxes and spheres falling through two sensor volumes onto the ground: a plain btGhostObject (its
// list of overlapping objects) and a btPairCachingGhostObject whose own pairs are dispatched after every
// step, as a character controller does (their algorithms and manifolds are in the dispatcher's array).
struct GhostOwner : Registered<GhostOwner>
{
	btDynamicsWorld* world;
	std::unique_ptr<btGhostPairCallback> callback;
	std::unique_ptr<btGhostObject> sensor;
	std::unique_ptr<btPairCachingGhostObject> cachingSensor;
};
std::vector<GhostOwner*>& g_ghosts = Registered<GhostOwner>::all();

void dispatchGhostPairs(btDynamicsWorld* world, btScalar)
{
	for (const auto& owner : g_ghosts)
		if (owner->world == world)
			world->getDispatcher()->dispatchAllCollisionPairs(owner->cachingSensor->getOverlappingPairCache(),
			                                                  world->getDispatchInfo(), world->getDispatcher());
}

void buildGhosts(TestWorld& t)
{
	t.addGround(btScalar(0.8), btScalar(0));
	GhostOwner& owner = *t.keep(new GhostOwner());
	owner.world = t.world();
	owner.callback.reset(new btGhostPairCallback());
	t.world()->getPairCache()->setInternalGhostPairCallback(owner.callback.get());
	owner.sensor.reset(new btGhostObject());
	owner.sensor->setCollisionShape(t.shape<btSphereShape>(btScalar(1.2)));
	owner.sensor->setWorldTransform(pose(btVector3(-1, 1.5, 0)));
	owner.sensor->setCollisionFlags(btCollisionObject::CF_NO_CONTACT_RESPONSE);
	t.world()->addCollisionObject(owner.sensor.get(), btBroadphaseProxy::SensorTrigger,
	                              btBroadphaseProxy::AllFilter & ~btBroadphaseProxy::SensorTrigger);
	owner.cachingSensor.reset(new btPairCachingGhostObject());
	owner.cachingSensor->setCollisionShape(t.shape<btBoxShape>(btVector3(1.5, 0.8, 1.5)));
	owner.cachingSensor->setWorldTransform(pose(btVector3(1, 0.9, 0), btScalar(0.3)));
	owner.cachingSensor->setCollisionFlags(btCollisionObject::CF_NO_CONTACT_RESPONSE);
	t.world()->addCollisionObject(owner.cachingSensor.get(), btBroadphaseProxy::SensorTrigger,
	                              btBroadphaseProxy::AllFilter & ~btBroadphaseProxy::SensorTrigger);
	t.world()->setInternalTickCallback(dispatchGhostPairs, 0, false);
	btCollisionShape* box = t.shape<btBoxShape>(btVector3(0.3, 0.3, 0.3));
	btCollisionShape* ball = t.shape<btSphereShape>(btScalar(0.3));
	for (int k = 0; k < 8; ++k)
		t.addBody(k % 2 ? ball : box, 1, pose(btVector3(0.55 * k - 2, 3 + 0.4 * k, 0.1 * (k % 3)), btScalar(0.3 * k)));
}

// A kinematic character walking up three steps and across a few loose boxes it pushes: its ghost's
// pairs, the controller's step, fall and contact state carry from step to step.
struct CharacterOwner : Registered<CharacterOwner>
{
	btDynamicsWorld* world;
	std::unique_ptr<btGhostPairCallback> callback;
	std::unique_ptr<btCapsuleShape> capsule;
	std::unique_ptr<btPairCachingGhostObject> ghost;
	std::unique_ptr<btKinematicCharacterController> controller;
};
std::vector<CharacterOwner*>& g_characters = Registered<CharacterOwner>::all();

void buildCharacter(TestWorld& t)
{
	t.addGround(btScalar(0.8), btScalar(0));
	for (int i = 0; i < 3; ++i)
	{
		const btScalar top = btScalar(0.25) * (i + 1);
		btBoxShape* step = t.shape<btBoxShape>(btVector3(1.5, top / 2, 0.5));
		t.addBody(step, 0, pose(btVector3(0, top / 2, 2.5 + i)));
	}
	btCollisionShape* crate = t.shape<btBoxShape>(btVector3(0.25, 0.25, 0.25));
	for (int i = 0; i < 3; ++i) t.addBody(crate, btScalar(0.3), pose(btVector3(0.6 * i - 0.6, 1.1, 5.6)));
	CharacterOwner& owner = *t.keep(new CharacterOwner());
	owner.world = t.world();
	owner.callback.reset(new btGhostPairCallback());
	t.world()->getPairCache()->setInternalGhostPairCallback(owner.callback.get());
	owner.capsule.reset(new btCapsuleShape(btScalar(0.3), btScalar(0.8)));
	owner.ghost.reset(new btPairCachingGhostObject());
	owner.ghost->setCollisionShape(owner.capsule.get());
	owner.ghost->setCollisionFlags(btCollisionObject::CF_CHARACTER_OBJECT);
	owner.ghost->setWorldTransform(pose(btVector3(0.5, 0.75, 0)));
	t.world()->addCollisionObject(owner.ghost.get(), btBroadphaseProxy::CharacterFilter,
	                              btBroadphaseProxy::StaticFilter | btBroadphaseProxy::DefaultFilter);
	owner.controller.reset(
	    new btKinematicCharacterController(owner.ghost.get(), owner.capsule.get(), btScalar(0.35), btVector3(0, 1, 0)));
	owner.controller->setGravity(btVector3(0, -10, 0));
	t.world()->addAction(owner.controller.get());
	owner.controller->setWalkDirection(btVector3(0.002, 0, 0.06));
}

// ---- the state trace ----------------------------------------------------------------------------

void append(std::vector<unsigned char>& trace, const void* data, size_t size)
{
	const unsigned char* bytes = static_cast<const unsigned char*>(data);
	trace.insert(trace.end(), bytes, bytes + size);
}

void appendVector(std::vector<unsigned char>& trace, const btVector3& v)
{
	append(trace, v.m_floats, 3 * sizeof(btScalar));
}

// Every body's pose, velocities and activation, and every manifold's points with their impulses.
void recordState(btDiscreteDynamicsWorld& world, std::vector<unsigned char>& trace)
{
	for (int i = 0; i < world.getNumCollisionObjects(); ++i)
	{
		const btCollisionObject* object = world.getCollisionObjectArray()[i];
		const btTransform& t = object->getWorldTransform();
		for (int r = 0; r < 3; ++r) appendVector(trace, t.getBasis()[r]);
		appendVector(trace, t.getOrigin());
		const int state = object->getActivationState();
		append(trace, &state, sizeof(state));
		if (const btRigidBody* body = btRigidBody::upcast(object))
		{
			appendVector(trace, body->getLinearVelocity());
			appendVector(trace, body->getAngularVelocity());
		}
	}
	btDispatcher* dispatcher = world.getDispatcher();
	for (int m = 0; m < dispatcher->getNumManifolds(); ++m)
	{
		const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
		const int points = manifold->getNumContacts();
		append(trace, &points, sizeof(points));
		for (int p = 0; p < points; ++p)
		{
			const btManifoldPoint& point = manifold->getContactPoint(p);
			appendVector(trace, point.m_positionWorldOnB);
			append(trace, &point.m_distance1, sizeof(btScalar));
			append(trace, &point.m_appliedImpulse, sizeof(btScalar));
			append(trace, &point.m_appliedImpulseLateral1, sizeof(btScalar));
		}
	}
	for (int j = 0; j < world.getNumConstraints(); ++j)
	{
		const btTypedConstraint* joint = world.getConstraint(j);
		const btScalar impulse = joint->needsFeedback() ? joint->getAppliedImpulse() : btScalar(0);
		append(trace, &impulse, sizeof(impulse));
	}
	for (const auto& owner : g_ghosts)
	{
		if (owner->world != &world) continue;
		for (btGhostObject* ghost : {owner->sensor.get(), static_cast<btGhostObject*>(owner->cachingSensor.get())})
		{
			const int count = ghost->getNumOverlappingObjects();
			append(trace, &count, sizeof(count));
			for (int k = 0; k < count; ++k)
			{
				const int index = ghost->getOverlappingObject(k)->getWorldArrayIndex();
				append(trace, &index, sizeof(index));
			}
		}
		const int pairs = owner->cachingSensor->getOverlappingPairCache()->getNumOverlappingPairs();
		append(trace, &pairs, sizeof(pairs));
	}
	for (const auto& owner : g_characters)
	{
		if (owner->world != &world) continue;
		appendVector(trace, owner->ghost->getWorldTransform().getOrigin());
		const bool onGround = owner->controller->onGround();
		append(trace, &onGround, sizeof(onGround));
		appendVector(trace, owner->controller->getLinearVelocity());
	}
	for (const auto& owner : g_vehicles)
	{
		if (owner->world != &world) continue;
		for (int w = 0; w < owner->vehicle->getNumWheels(); ++w)
		{
			const btWheelInfo& wheel = owner->vehicle->getWheelInfo(w);
			append(trace, &wheel.m_rotation, sizeof(btScalar));
			append(trace, &wheel.m_raycastInfo.m_suspensionLength, sizeof(btScalar));
			append(trace, &wheel.m_skidInfo, sizeof(btScalar));
			appendVector(trace, wheel.m_worldTransform.getOrigin());
		}
	}
}

// Steps n fixed steps, recording the state after each; one trace per step.
std::vector<std::vector<unsigned char>> runRecorded(TestWorld& t, int steps, btScalar h = btScalar(1. / 60.))
{
	std::vector<std::vector<unsigned char>> traces(steps);
	for (int s = 0; s < steps; ++s)
	{
		t.run(1, h);
		recordState(*t.world(), traces[s]);
	}
	return traces;
}

// The first step whose trace differs, -1 when all agree.
int firstDifference(const std::vector<std::vector<unsigned char>>& a, const std::vector<std::vector<unsigned char>>& b)
{
	if (a.size() != b.size()) return 0;
	for (size_t s = 0; s < a.size(); ++s)
		if (a[s] != b[s]) return int(s);
	return -1;
}

std::string describe(const caliber::SnapshotDifference& d)
{
	return std::string(d.section) + " " + std::to_string(d.index) + ": " + d.field;
}

using Builder = std::function<void(TestWorld&)>;
using WorldFactory = std::function<std::unique_ptr<TestWorld>()>;

std::unique_ptr<TestWorld> plainWorld() { return std::unique_ptr<TestWorld>(new TestWorld()); }
// Bullet's multithreaded world with a pool of two solvers and a large-batch solver (run on the calling
// thread unless a scheduler is set: the pool's per-solver state and shared warm starts are what count).
std::unique_ptr<TestWorld> simpleBroadphaseWorld()
{
	return std::unique_ptr<TestWorld>(new TestWorld(new btSimpleBroadphase()));
}
std::unique_ptr<TestWorld> sweepWorld()
{
	return std::unique_ptr<TestWorld>(new TestWorld(new btAxisSweep3(btVector3(-60, -20, -60), btVector3(60, 60, 60))));
}
std::unique_ptr<TestWorld> sweep32World()
{
	return std::unique_ptr<TestWorld>(
	    new TestWorld(new bt32BitAxisSweep3(btVector3(-60, -20, -60), btVector3(60, 60, 60))));
}
std::unique_ptr<TestWorld> mtWorld()
{
	return std::unique_ptr<TestWorld>(new TestWorld(TestWorld::Multithreaded(), 2));
}

// Runs warmup steps, saves, runs steps more (trace A), restores, checks the world equals the snapshot,
// runs steps again (trace B, which must equal A bit for bit); then restores into a second, freshly
// built world and runs steps (trace C, also equal to A).
void expectRollbackIsExact(const Builder& build, int warmup, int steps, btScalar h = btScalar(1. / 60.),
                           const WorldFactory& make = plainWorld)
{
	std::unique_ptr<TestWorld> first = make();
	TestWorld& t = *first;
	build(t);
	t.run(warmup, h);
	Bytes snapshot;
	caliber::SnapshotError error;
	ASSERT_TRUE(caliber::saveWorldState(*t.world(), snapshot, &error)) << error.message;
	ASSERT_GT(snapshot.size(), 0);
	const auto original = runRecorded(t, steps, h);

	caliber::SnapshotDifference difference;
	EXPECT_FALSE(caliber::compareWorldState(*t.world(), &snapshot[0], snapshot.size(), &difference))
	    << "the world moved on, so it must differ from the snapshot";

	ASSERT_TRUE(caliber::restoreWorldState(*t.world(), &snapshot[0], snapshot.size(), &error)) << error.message;
	EXPECT_TRUE(caliber::compareWorldState(*t.world(), &snapshot[0], snapshot.size(), &difference))
	    << "after restore: " << describe(difference);
	const auto replay = runRecorded(t, steps, h);
	EXPECT_EQ(firstDifference(original, replay), -1) << "same world, replay differs from this step on";

	std::unique_ptr<TestWorld> second = make();
	TestWorld& other = *second;
	build(other);
	ASSERT_TRUE(caliber::restoreWorldState(*other.world(), &snapshot[0], snapshot.size(), &error)) << error.message;
	EXPECT_TRUE(caliber::compareWorldState(*other.world(), &snapshot[0], snapshot.size(), &difference))
	    << "second world after restore: " << describe(difference);
	const auto remote = runRecorded(other, steps, h);
	EXPECT_EQ(firstDifference(original, remote), -1) << "second world differs from this step on";
}

// ---- bit-identical continuation -----------------------------------------------------------------
// Each run compares every step's record, so a run of n steps checks the state after 1, 10, ... n steps.

TEST(WorldSnapshot, PileContinuesBitIdenticallyFor150Steps) { expectRollbackIsExact(buildPile, 30, 150); }

TEST(WorldSnapshot, StackContinuesBitIdenticallyFor1000Steps) { expectRollbackIsExact(buildStack, 20, 1000); }

TEST(WorldSnapshot, PolyhedralHullStackContinuesBitIdenticallyFor300Steps)
{
	// Saved once the stack rests, so that its pairs hold contact caches.
	expectRollbackIsExact(buildPolyhedralStack, 120, 300);
}

// 120 steps: 1000 take 40 s under ASan; the 1000-frame joint check is BenchmarkDemo ragdolls136 (docs/serialization.md).
TEST(WorldSnapshot, JointChainsContinueBitIdenticallyFor120Steps) { expectRollbackIsExact(buildJoints, 25, 120); }

TEST(WorldSnapshot, JointChainsAt120HertzContinueBitIdentically)
{
	// Another step than the 1/60 s a freshly built hinge or cone twist assumes for its last rows.
	expectRollbackIsExact(buildJoints, 25, 30, btScalar(1. / 120.));
}

TEST(WorldSnapshot, HullsOnAMeshContinueBitIdenticallyFor150Steps) { expectRollbackIsExact(buildMesh, 45, 150); }

TEST(WorldSnapshot, SleepingBodiesContinueBitIdenticallyFor1000Steps)
{
	expectRollbackIsExact(buildSleepers, 60, 1000);  // saved while settling; sleep and the late wake-up follow
	expectRollbackIsExact(buildSleepers, 150, 10);   // saved with bodies asleep
}

TEST(WorldSnapshot, CcdBodiesContinueBitIdenticallyFor1000Steps) { expectRollbackIsExact(buildCcd, 2, 1000); }

TEST(WorldSnapshot, SimpleBroadphasePileContinuesBitIdenticallyFor150Steps)
{
	// btSimpleBroadphase: each proxy's box (sleeping bodies' boxes are not refreshed) and the pairs.
	expectRollbackIsExact(buildPile, 30, 150, btScalar(1. / 60.), simpleBroadphaseWorld);
}

TEST(WorldSnapshot, SimpleBroadphaseSleepersContinueBitIdenticallyFor1000Steps)
{
	expectRollbackIsExact(buildSleepers, 30, 1000, btScalar(1. / 60.), simpleBroadphaseWorld);
}

TEST(WorldSnapshot, AxisSweepPileContinuesBitIdenticallyFor150Steps)
{
	// btAxisSweep3: the sorted edge lists (their order among equal positions) and each proxy's box.
	expectRollbackIsExact(buildPile, 30, 150, btScalar(1. / 60.), sweepWorld);
}

TEST(WorldSnapshot, AxisSweep32SleepersContinueBitIdenticallyFor1000Steps)
{
	expectRollbackIsExact(buildSleepers, 30, 1000, btScalar(1. / 60.), sweep32World);
}

namespace
{
// The objects a grid of vertical rays meets, each ray's hits in the order the broadphase visits them
// (all-hits callbacks keep that order; closest-hit callbacks keep the first of two tied hits).
std::vector<int> rayVisitOrder(btDiscreteDynamicsWorld& world)
{
	std::vector<int> order;
	for (int i = -4; i <= 4; ++i)
		for (int k = -4; k <= 4; ++k)
		{
			const btVector3 from(btScalar(0.5 * i), 30, btScalar(0.5 * k)),
			    to(btScalar(0.5 * i), -5, btScalar(0.5 * k));
			btCollisionWorld::AllHitsRayResultCallback hits(from, to);
			world.rayTest(from, to, hits);
			for (int h = 0; h < hits.m_collisionObjects.size(); ++h)
				order.push_back(hits.m_collisionObjects[h]->getWorldArrayIndex());
			order.push_back(-1);
		}
	return order;
}
}  // namespace

TEST(WorldSnapshot, AxisSweepRayAcceleratorVisitsObjectsInTheSavedOrderAfterRestore)
{
	// btAxisSweep3's ray accelerator is a dbvt of its own: its tree decides the order in which ray tests
	// visit objects. After a restore, in the same world and in a fresh one, rays must meet the objects in
	// the order they did when the snapshot was taken.
	std::unique_ptr<TestWorld> first = sweepWorld();
	buildPile(*first);
	first->run(30, btScalar(1. / 60.));
	Bytes snapshot;
	caliber::SnapshotError error;
	ASSERT_TRUE(caliber::saveWorldState(*first->world(), snapshot, &error)) << error.message;
	const std::vector<int> saved = rayVisitOrder(*first->world());
	int hits = 0;
	for (int o : saved) hits += o >= 0;
	ASSERT_GT(hits, 100);
	first->run(200, btScalar(1. / 60.));
	ASSERT_NE(rayVisitOrder(*first->world()), saved) << "the pile must have moved";
	ASSERT_TRUE(caliber::restoreWorldState(*first->world(), &snapshot[0], snapshot.size(), &error)) << error.message;
	EXPECT_EQ(rayVisitOrder(*first->world()), saved);
	std::unique_ptr<TestWorld> second = sweepWorld();
	buildPile(*second);
	second->run(7, btScalar(1. / 60.));
	ASSERT_TRUE(caliber::restoreWorldState(*second->world(), &snapshot[0], snapshot.size(), &error)) << error.message;
	EXPECT_EQ(rayVisitOrder(*second->world()), saved);
}

TEST(WorldSnapshot, AxisSweepJointChainsContinueBitIdenticallyFor120Steps)
{
	expectRollbackIsExact(buildJoints, 25, 120, btScalar(1. / 60.), sweepWorld);
}

TEST(WorldSnapshot, MtWorldWithJointsContinuesBitIdenticallyFor120Steps)
{
	// The pool's solvers' order state and the warm starts they share (joints: the shared store).
	expectRollbackIsExact(buildJoints, 25, 120, btScalar(1. / 60.), mtWorld);
}

TEST(WorldSnapshot, MtWorldPileContinuesBitIdenticallyFor150Steps)
{
	expectRollbackIsExact(buildPile, 30, 150, btScalar(1. / 60.), mtWorld);
}

TEST(WorldSnapshot, MtWorldStackContinuesBitIdenticallyFor1000Steps)
{
	expectRollbackIsExact(buildStack, 20, 1000, btScalar(1. / 60.), mtWorld);
}

TEST(WorldSnapshot, GhostsContinueBitIdenticallyFor150Steps)
{
	// Saved at step 45: the pair-caching ghost has pairs with algorithms and manifolds.
	expectRollbackIsExact(buildGhosts, 45, 150);
}

TEST(WorldSnapshot, GhostsSavedAfterObjectsLeftThemContinueBitIdentically)
{
	// Saved at step 125: objects have left both ghosts, so their lists are no longer in pair order.
	expectRollbackIsExact(buildGhosts, 125, 60);
}

TEST(WorldSnapshot, GhostsSavedBeforeAnythingOverlapsContinueBitIdentically)
{
	expectRollbackIsExact(buildGhosts, 1, 60);
}

TEST(WorldSnapshot, CharacterContinuesBitIdenticallyFor200Steps) { expectRollbackIsExact(buildCharacter, 20, 200); }

TEST(WorldSnapshot, CharacterSavedWhileFallingContinuesBitIdentically)
{
	// Saved in its first fall onto the ground (vertical velocity and offset in progress).
	expectRollbackIsExact(buildCharacter, 2, 60);
}

TEST(WorldSnapshot, VehicleContinuesBitIdenticallyFor200Steps) { expectRollbackIsExact(buildVehicle, 30, 200); }

TEST(WorldSnapshot, VehicleSavedInTheAirContinuesBitIdentically)
{
	// Saved before the wheels first touch: contact, suspension and friction state start after the save.
	expectRollbackIsExact(buildVehicle, 1, 60);
}

TEST(WorldSnapshot, CompoundsContinueBitIdenticallyFor150Steps) { expectRollbackIsExact(buildCompounds, 40, 150); }

TEST(WorldSnapshot, CompoundPairContinuesBitIdenticallyFor1000Steps)
{
	expectRollbackIsExact(buildCompoundPair, 30, 1000);
}

TEST(WorldSnapshot, CompoundsSavedBeforeTheyTouchContinueBitIdentically)
{
	// Saved while the compounds fall: child algorithms are made after the save, during the replay.
	expectRollbackIsExact(buildCompounds, 1, 60);
}

TEST(WorldSnapshot, SnapshotsOfTheSameStateAreEqualBytes)
{
	// Two worlds built and stepped alike save the same bytes: a snapshot holds no addresses.
	TestWorld a, b;
	buildPile(a);
	buildPile(b);
	a.run(30);
	b.run(30);
	Bytes sa, sb;
	ASSERT_TRUE(caliber::saveWorldState(*a.world(), sa));
	ASSERT_TRUE(caliber::saveWorldState(*b.world(), sb));
	ASSERT_EQ(sa.size(), sb.size());
	EXPECT_EQ(0, memcmp(&sa[0], &sb[0], size_t(sa.size())));
}

TEST(WorldSnapshot, RepeatedRollbackGivesTheSameFutureEachTime)
{
	// The netcode loop: restore the same snapshot many times, step a few frames each time.
	TestWorld t;
	buildJoints(t);
	t.run(10);
	Bytes snapshot;
	ASSERT_TRUE(caliber::saveWorldState(*t.world(), snapshot));
	const auto first = runRecorded(t, 5);
	for (int round = 0; round < 4; ++round)
	{
		ASSERT_TRUE(caliber::restoreWorldState(*t.world(), &snapshot[0], snapshot.size()));
		EXPECT_EQ(firstDifference(first, runRecorded(t, 5)), -1) << "round " << round;
	}
}

// ---- validation mode ----------------------------------------------------------------------------

TEST(WorldSnapshot, CompareNamesTheFirstDifferingField)
{
	TestWorld t;
	buildStack(t);
	t.run(5);
	Bytes snapshot;
	ASSERT_TRUE(caliber::saveWorldState(*t.world(), snapshot));
	caliber::SnapshotDifference difference;
	EXPECT_TRUE(caliber::compareWorldState(*t.world(), &snapshot[0], snapshot.size(), &difference));

	// Object 4 (the fourth box; the ground is object 0) gets a force.
	t.bodies()[4]->applyCentralForce(btVector3(0, 0, btScalar(0.25)));
	ASSERT_FALSE(caliber::compareWorldState(*t.world(), &snapshot[0], snapshot.size(), &difference));
	EXPECT_STREQ(difference.section, "object");
	EXPECT_EQ(difference.index, 4);
	EXPECT_STREQ(difference.field, "m_totalForce");
}

TEST(WorldSnapshot, CompareNamesAManifoldPointField)
{
	TestWorld t;
	buildStack(t);
	t.run(5);
	Bytes snapshot;
	ASSERT_TRUE(caliber::saveWorldState(*t.world(), snapshot));
	btPersistentManifold* manifold = t.world()->getDispatcher()->getManifoldByIndexInternal(2);
	ASSERT_GT(manifold->getNumContacts(), 1);
	manifold->getContactPoint(1).m_appliedImpulse += btScalar(1);
	caliber::SnapshotDifference difference;
	ASSERT_FALSE(caliber::compareWorldState(*t.world(), &snapshot[0], snapshot.size(), &difference));
	EXPECT_STREQ(difference.section, "manifold");
	EXPECT_EQ(difference.index, 2);
	EXPECT_STREQ(difference.field, "[1] m_appliedImpulse");
}

// ---- bad input ----------------------------------------------------------------------------------

// The world's state as bytes, to show that a refused restore changed nothing.
Bytes stateOf(btDiscreteDynamicsWorld& world)
{
	Bytes bytes;
	EXPECT_TRUE(caliber::saveWorldState(world, bytes));
	return bytes;
}

void expectUnchanged(btDiscreteDynamicsWorld& world, const Bytes& before)
{
	caliber::SnapshotDifference difference;
	EXPECT_TRUE(caliber::compareWorldState(world, &before[0], before.size(), &difference)) << describe(difference);
}

TEST(WorldSnapshotBadInput, TruncatedBuffersAreRefusedAndChangeNothing)
{
	TestWorld t;
	buildStack(t);
	t.run(20);
	Bytes snapshot = stateOf(*t.world());
	t.run(7);
	const Bytes before = stateOf(*t.world());
	const int size = snapshot.size();
	const int cuts[] = {1, 7, 8, 12, 20, 24, 40, size / 7, size / 3, size / 2, size - 100, size - 9, size - 1};
	for (int cut : cuts)
	{
		caliber::SnapshotError error;
		error.message[0] = 0;
		EXPECT_FALSE(caliber::restoreWorldState(*t.world(), &snapshot[0], size_t(cut), &error)) << cut;
		EXPECT_NE(std::string(error.message), "") << cut;
	}
	expectUnchanged(*t.world(), before);
	t.run(3);  // and it keeps simulating
}

TEST(WorldSnapshotBadInput, WrongMagicVersionPrecisionOrByteOrderAreRefused)
{
	TestWorld t;
	buildStack(t);
	t.run(5);
	const Bytes good = stateOf(*t.world());
	t.run(5);
	const Bytes before = stateOf(*t.world());
	struct Patch
	{
		int offset;
		const char* expected;
	} patches[] = {{0, "magic"}, {8, "version"}, {12, "byte order"}, {16, "precision"}, {20, "bytes"}};
	for (const Patch& patch : patches)
	{
		Bytes bad = good;
		bad[patch.offset] ^= 0x40;
		caliber::SnapshotError error;
		EXPECT_FALSE(caliber::restoreWorldState(*t.world(), &bad[0], bad.size(), &error));
		EXPECT_NE(std::string(error.message).find(patch.expected), std::string::npos) << error.message;
	}
	Bytes longer = good;
	longer.push_back(0);
	caliber::SnapshotError error;
	EXPECT_FALSE(caliber::restoreWorldState(*t.world(), &longer[0], longer.size(), &error));
	expectUnchanged(*t.world(), before);
}

TEST(WorldSnapshotBadInput, SnapshotOfAnotherWorldIsRefused)
{
	TestWorld source;
	buildStack(source);
	source.run(5);
	const Bytes snapshot = stateOf(*source.world());

	// One body more.
	TestWorld more;
	buildStack(more);
	more.addBody(more.shape<btSphereShape>(btScalar(0.5)), 1, btVector3(5, 1, 5));
	more.run(3);
	Bytes before = stateOf(*more.world());
	caliber::SnapshotError error;
	EXPECT_FALSE(caliber::restoreWorldState(*more.world(), &snapshot[0], snapshot.size(), &error));
	EXPECT_NE(std::string(error.message).find("collision objects"), std::string::npos) << error.message;
	expectUnchanged(*more.world(), before);
	more.run(3);

	// Same count, another shape.
	TestWorld shapes;
	shapes.addGround(btScalar(0.8), btScalar(0));
	btCollisionShape* sphere = shapes.shape<btSphereShape>(btScalar(0.25));
	for (int i = 0; i < 10; ++i) shapes.addBody(sphere, 1, btVector3(0, btScalar(0.25) + btScalar(0.5) * i, 0));
	before = stateOf(*shapes.world());
	EXPECT_FALSE(caliber::restoreWorldState(*shapes.world(), &snapshot[0], snapshot.size(), &error));
	EXPECT_NE(std::string(error.message).find("shape type"), std::string::npos) << error.message;
	expectUnchanged(*shapes.world(), before);

	// Same bodies, one joint more.
	TestWorld jointed;
	buildStack(jointed);
	jointed.addJoint<btPoint2PointConstraint>(false, *jointed.bodies()[1], *jointed.bodies()[2], btVector3(0, 0.25, 0),
	                                          btVector3(0, -0.25, 0));
	before = stateOf(*jointed.world());
	EXPECT_FALSE(caliber::restoreWorldState(*jointed.world(), &snapshot[0], snapshot.size(), &error));
	EXPECT_NE(std::string(error.message).find("joints"), std::string::npos) << error.message;
	expectUnchanged(*jointed.world(), before);
}

TEST(WorldSnapshotBadInput, NoDataIsRefused)
{
	TestWorld t;
	buildStack(t);
	caliber::SnapshotError error;
	EXPECT_FALSE(caliber::restoreWorldState(*t.world(), 0, 0, &error));
	EXPECT_NE(std::string(error.message), "");
	const unsigned char byte = 0;
	EXPECT_FALSE(caliber::restoreWorldState(*t.world(), &byte, 0, &error));
	EXPECT_FALSE(caliber::restoreWorldState(*t.world(), 0, 0));  // no error struct: still refused
	caliber::SnapshotDifference difference;
	EXPECT_FALSE(caliber::compareWorldState(*t.world(), 0, 0, &difference, &error));
}

#if CALIBER_ASSERTS_ENABLED
TEST(WorldSnapshotDeathTest, NullDataWithASizeAsserts)
{
	TestWorld t;
	buildStack(t);
	EXPECT_DEATH(caliber::restoreWorldState(*t.world(), 0, 16), "assertion failed");
}
#else
TEST(WorldSnapshotBadInput, NullDataWithASizeIsRefused)
{
	TestWorld t;
	buildStack(t);
	caliber::SnapshotError error;
	EXPECT_FALSE(caliber::restoreWorldState(*t.world(), 0, 16, &error));
	EXPECT_NE(std::string(error.message), "");
}
#endif

TEST(WorldSnapshotBadInput, CorruptedBytesNeverCrashAndFailedRestoresChangeNothing)
{
	// Every byte position of a small world's snapshot flipped in turn: each restore either succeeds (a
	// value changed, e.g. a velocity) or is refused with the world unchanged; the world steps on either way.
	TestWorld t;
	buildSmall(t);
	t.run(8);
	const Bytes good = stateOf(*t.world());
	int refused = 0;
	for (int k = 0; k < good.size(); k += 3)
	{
		Bytes bad = good;
		bad[k] ^= 0x5a;
		const Bytes before = stateOf(*t.world());
		caliber::SnapshotError error;
		if (!caliber::restoreWorldState(*t.world(), &bad[0], bad.size(), &error))
		{
			++refused;
			expectUnchanged(*t.world(), before);
		}
		ASSERT_TRUE(caliber::restoreWorldState(*t.world(), &good[0], good.size(), &error)) << error.message;
	}
	EXPECT_GT(refused, 0);
	t.run(2);
}

TEST(WorldSnapshotBadInput, UnsupportedWorldsAreRefusedOnSave)
{
	// Compounds nested deeper than the snapshot's limit (8 levels of algorithms).
	TestWorld t;
	t.addGround();
	btCollisionShape* inner = t.shape<btBoxShape>(btVector3(0.5, 0.5, 0.5));
	for (int level = 0; level < 10; ++level)
	{
		btCompoundShape* compound = t.shape<btCompoundShape>();
		compound->addChildShape(btTransform::getIdentity(), inner);
		inner = compound;
	}
	t.addBody(inner, 1, btVector3(0, 0.4, 0));
	t.run(3);
	Bytes buffer;
	buffer.push_back(7);
	caliber::SnapshotError error;
	EXPECT_FALSE(caliber::saveWorldState(*t.world(), buffer, &error));
	EXPECT_NE(std::string(error.message).find("does not support"), std::string::npos) << error.message;
	EXPECT_EQ(buffer.size(), 0);
}

TEST(WorldSnapshotBadInput, VehicleSnapshotIntoAWorldWithoutItOrWithOtherWheelsIsRefused)
{
	TestWorld t;
	buildVehicle(t);
	t.run(10);
	Bytes snapshot;
	caliber::SnapshotError error;
	ASSERT_TRUE(caliber::saveWorldState(*t.world(), snapshot, &error)) << error.message;

	TestWorld noVehicle;  // the same bodies, no action
	buildVehicle(noVehicle);
	noVehicle.world()->removeAction(g_vehicles.back()->vehicle.get());
	noVehicle.run(10);
	Bytes before = stateOf(*noVehicle.world());
	EXPECT_FALSE(caliber::restoreWorldState(*noVehicle.world(), &snapshot[0], snapshot.size(), &error));
	EXPECT_NE(std::string(error.message).find("actions"), std::string::npos) << error.message;
	expectUnchanged(*noVehicle.world(), before);

	TestWorld fiveWheels;
	buildVehicle(fiveWheels);
	btRaycastVehicle::btVehicleTuning tuning;
	g_vehicles.back()->vehicle->addWheel(btVector3(0, 0, 0), btVector3(0, -1, 0), btVector3(-1, 0, 0), btScalar(0.6),
	                                     btScalar(0.4), tuning, false);
	fiveWheels.run(10);
	before = stateOf(*fiveWheels.world());
	EXPECT_FALSE(caliber::restoreWorldState(*fiveWheels.world(), &snapshot[0], snapshot.size(), &error));
	EXPECT_NE(std::string(error.message).find("wheels"), std::string::npos) << error.message;
	expectUnchanged(*fiveWheels.world(), before);
}

TEST(WorldSnapshotBadInput, SnapshotOfAnotherBroadphaseIsRefused)
{
	std::unique_ptr<TestWorld> dbvt = plainWorld(), simple = simpleBroadphaseWorld();
	buildSmall(*dbvt);
	buildSmall(*simple);
	dbvt->run(5);
	simple->run(5);
	Bytes dbvtSnapshot, simpleSnapshot;
	caliber::SnapshotError error;
	ASSERT_TRUE(caliber::saveWorldState(*dbvt->world(), dbvtSnapshot, &error)) << error.message;
	ASSERT_TRUE(caliber::saveWorldState(*simple->world(), simpleSnapshot, &error)) << error.message;
	Bytes before = stateOf(*simple->world());
	EXPECT_FALSE(caliber::restoreWorldState(*simple->world(), &dbvtSnapshot[0], dbvtSnapshot.size(), &error));
	EXPECT_NE(std::string(error.message).find("broadphase"), std::string::npos) << error.message;
	expectUnchanged(*simple->world(), before);
	before = stateOf(*dbvt->world());
	EXPECT_FALSE(caliber::restoreWorldState(*dbvt->world(), &simpleSnapshot[0], simpleSnapshot.size(), &error));
	EXPECT_NE(std::string(error.message).find("broadphase"), std::string::npos) << error.message;
	expectUnchanged(*dbvt->world(), before);

	// A 16-bit sweep's snapshot into a 32-bit sweep world, and a dbvt snapshot into a sweep world.
	std::unique_ptr<TestWorld> sweep = sweepWorld(), sweep32 = sweep32World();
	buildSmall(*sweep);
	buildSmall(*sweep32);
	sweep->run(5);
	sweep32->run(5);
	Bytes sweepSnapshot;
	ASSERT_TRUE(caliber::saveWorldState(*sweep->world(), sweepSnapshot, &error)) << error.message;
	before = stateOf(*sweep32->world());
	EXPECT_FALSE(caliber::restoreWorldState(*sweep32->world(), &sweepSnapshot[0], sweepSnapshot.size(), &error));
	EXPECT_NE(std::string(error.message).find("broadphase"), std::string::npos) << error.message;
	expectUnchanged(*sweep32->world(), before);
	before = stateOf(*sweep->world());
	EXPECT_FALSE(caliber::restoreWorldState(*sweep->world(), &dbvtSnapshot[0], dbvtSnapshot.size(), &error));
	expectUnchanged(*sweep->world(), before);
}

TEST(WorldSnapshotBadInput, CorruptedAxisSweepSnapshotsNeverCrashAndChangeNothing)
{
	// Every byte of a sweep world's snapshot flipped in turn (the edge lists included): a restore either
	// succeeds or is refused with the world unchanged, and the broadphase keeps working.
	std::unique_ptr<TestWorld> t = sweepWorld();
	buildSmall(*t);
	t->run(8);
	const Bytes good = stateOf(*t->world());
	int refused = 0;
	for (int k = 0; k < good.size(); k += 5)
	{
		Bytes bad = good;
		bad[k] ^= 0x5a;
		const Bytes before = stateOf(*t->world());
		caliber::SnapshotError error;
		if (!caliber::restoreWorldState(*t->world(), &bad[0], bad.size(), &error))
		{
			++refused;
			expectUnchanged(*t->world(), before);
		}
		ASSERT_TRUE(caliber::restoreWorldState(*t->world(), &good[0], good.size(), &error)) << error.message;
	}
	EXPECT_GT(refused, 0);
	t->run(2);
}

TEST(WorldSnapshotBadInput, SnapshotOfAnotherSolverSetUpIsRefused)
{
	// A plain world's snapshot into an Mt world built alike, and the other way round: the solvers' order
	// state does not match (kind, pool size), so the restore is refused with the world unchanged.
	std::unique_ptr<TestWorld> plain = plainWorld(), mt = mtWorld();
	buildSmall(*plain);
	buildSmall(*mt);
	plain->run(5);
	mt->run(5);
	Bytes plainSnapshot, mtSnapshot;
	caliber::SnapshotError error;
	ASSERT_TRUE(caliber::saveWorldState(*plain->world(), plainSnapshot, &error)) << error.message;
	ASSERT_TRUE(caliber::saveWorldState(*mt->world(), mtSnapshot, &error)) << error.message;
	Bytes before = stateOf(*mt->world());
	EXPECT_FALSE(caliber::restoreWorldState(*mt->world(), &plainSnapshot[0], plainSnapshot.size(), &error));
	EXPECT_NE(std::string(error.message).find("solver"), std::string::npos) << error.message;
	expectUnchanged(*mt->world(), before);
	before = stateOf(*plain->world());
	EXPECT_FALSE(caliber::restoreWorldState(*plain->world(), &mtSnapshot[0], mtSnapshot.size(), &error));
	EXPECT_NE(std::string(error.message).find("solver"), std::string::npos) << error.message;
	expectUnchanged(*plain->world(), before);

	// A pool of another size.
	TestWorld three(TestWorld::Multithreaded(), 3);
	buildSmall(three);
	three.run(5);
	before = stateOf(*three.world());
	EXPECT_FALSE(caliber::restoreWorldState(*three.world(), &mtSnapshot[0], mtSnapshot.size(), &error));
	EXPECT_NE(std::string(error.message).find("pool"), std::string::npos) << error.message;
	expectUnchanged(*three.world(), before);
}

TEST(WorldSnapshotBadInput, GhostSnapshotIntoAWorldWithOtherGhostsIsRefused)
{
	TestWorld t;
	buildGhosts(t);
	t.run(30);
	Bytes snapshot;
	caliber::SnapshotError error;
	ASSERT_TRUE(caliber::saveWorldState(*t.world(), snapshot, &error)) << error.message;

	// The same objects, but the pair-caching ghost is a plain ghost here.
	TestWorld other;
	buildGhosts(other);
	GhostOwner& owner = *g_ghosts.back();
	other.world()->removeCollisionObject(owner.cachingSensor.get());
	std::unique_ptr<btGhostObject> plain(new btGhostObject());
	plain->setCollisionShape(owner.cachingSensor->getCollisionShape());
	plain->setWorldTransform(owner.cachingSensor->getWorldTransform());
	other.world()->addCollisionObject(plain.get(), btBroadphaseProxy::SensorTrigger,
	                                  btBroadphaseProxy::AllFilter & ~btBroadphaseProxy::SensorTrigger);
	// The replacement comes last in the world's order: the objects' types no longer match index for index.
	other.run(30);
	const Bytes before = stateOf(*other.world());
	EXPECT_FALSE(caliber::restoreWorldState(*other.world(), &snapshot[0], snapshot.size(), &error));
	expectUnchanged(*other.world(), before);
	other.world()->removeCollisionObject(plain.get());
}

TEST(WorldSnapshotBadInput, CharacterSnapshotIntoAWorldWithoutItsControllerIsRefused)
{
	TestWorld t;
	buildCharacter(t);
	t.run(10);
	Bytes snapshot;
	caliber::SnapshotError error;
	ASSERT_TRUE(caliber::saveWorldState(*t.world(), snapshot, &error)) << error.message;
	// The same world with its controller removed: one action fewer.
	TestWorld other;
	buildCharacter(other);
	other.world()->removeAction(g_characters.back()->controller.get());
	other.run(10);
	const Bytes before = stateOf(*other.world());
	EXPECT_FALSE(caliber::restoreWorldState(*other.world(), &snapshot[0], snapshot.size(), &error));
	EXPECT_NE(std::string(error.message).find("actions"), std::string::npos) << error.message;
	expectUnchanged(*other.world(), before);
	// A character whose ghost left the world cannot be saved.
	t.world()->removeCollisionObject(g_characters[g_characters.size() - 2]->ghost.get());
	EXPECT_FALSE(caliber::saveWorldState(*t.world(), snapshot, &error));
	EXPECT_NE(std::string(error.message).find("ghost"), std::string::npos) << error.message;
	t.world()->removeAction(g_characters[g_characters.size() - 2]->controller.get());
}

TEST(WorldSnapshotBadInput, CompoundWithOtherChildrenIsRefusedAndChangesNothing)
{
	// The same objects, but one compound has a child more: the dispatcher's child algorithms cannot take
	// the saved ones (found while applying: the world's own state is put back).
	TestWorld t;
	buildCompoundPair(t);
	t.run(20);
	Bytes snapshot;
	caliber::SnapshotError error;
	ASSERT_TRUE(caliber::saveWorldState(*t.world(), snapshot, &error)) << error.message;

	TestWorld other;
	buildCompoundPair(other);
	btCompoundShape* compound =
	    static_cast<btCompoundShape*>(other.world()->getCollisionObjectArray()[1]->getCollisionShape());
	compound->addChildShape(pose(btVector3(0, 0.3, 0)), compound->getChildShape(0));
	other.run(20);
	const Bytes before = stateOf(*other.world());
	EXPECT_FALSE(caliber::restoreWorldState(*other.world(), &snapshot[0], snapshot.size(), &error));
	EXPECT_NE(std::string(error.message).find("compound"), std::string::npos) << error.message;
	expectUnchanged(*other.world(), before);
	other.run(2);
}

struct TickContext
{
	Bytes snapshot;
	int tick = 0;
	int restoreAt = 0;
	bool restored = false;
};

void restoringTick(btDynamicsWorld* world, btScalar)
{
	TickContext& c = *static_cast<TickContext*>(world->getWorldUserInfo());
	if (++c.tick == c.restoreAt)
		c.restored = caliber::restoreWorldState(*static_cast<btDiscreteDynamicsWorld*>(world), &c.snapshot[0],
		                                        c.snapshot.size());
}

TEST(WorldSnapshotBadInput, RestoreFromThePostTickCallbackEndsTheStepAtTheSnapshot)
{
	// Allowed from the internal tick callbacks (documented): restored in the post-tick callback of the
	// tenth step, the world ends that step in the saved state, and its next step is the one that followed
	// the snapshot.
	TickContext context;
	TestWorld t;
	buildPile(t);
	t.run(10);
	ASSERT_TRUE(caliber::saveWorldState(*t.world(), context.snapshot));
	const auto expected = runRecorded(t, 2);
	context.restoreAt = 10;
	t.world()->setInternalTickCallback(restoringTick, &context, false);
	t.run(10);
	ASSERT_TRUE(context.restored);
	caliber::SnapshotDifference difference;
	EXPECT_TRUE(caliber::compareWorldState(*t.world(), &context.snapshot[0], context.snapshot.size(), &difference))
	    << describe(difference);
	t.world()->setInternalTickCallback(0);
	EXPECT_EQ(firstDifference(expected, runRecorded(t, 2)), -1);
}

TEST(WorldSnapshotBadInput, RestoreFromThePreTickCallbackKeepsSimulating)
{
	// From the pre-tick callback the substep goes on from the restored state (without the gravity force
	// stepSimulation applied before the substeps, which the snapshot, taken between steps, does not hold).
	TickContext context;
	TestWorld t;
	buildJoints(t);
	t.run(5);
	ASSERT_TRUE(caliber::saveWorldState(*t.world(), context.snapshot));
	context.restoreAt = 4;
	t.world()->setInternalTickCallback(restoringTick, &context, true);
	t.run(8);
	EXPECT_TRUE(context.restored);
	// The chains still hang from their anchors (6 m up, 4 links of 0.6 m) and the world moved on.
	for (btRigidBody* body : t.bodies())
	{
		if (body->getInvMass() == 0) continue;
		const btVector3& origin = body->getWorldTransform().getOrigin();
		EXPECT_TRUE(origin.getY() > btScalar(2) && origin.getY() < btScalar(6.5)) << origin.getY();
	}
	EXPECT_FALSE(caliber::compareWorldState(*t.world(), &context.snapshot[0], context.snapshot.size()));
}
}  // namespace
