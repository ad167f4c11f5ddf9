// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// caliber::saveWorldState / restoreWorldState / compareWorldState (include/Caliber/WorldSnapshot.h;
// docs/serialization.md, "Snapshot and restore"). A snapshot is, in order: the header, the world's time,
// every collision object's step state, the collision state (btWorldSnapshotCollision.cpp), every joint's
// state with its warm-start impulses, and the solver's order state. Each part is described once, as a
// list of fields that one template walks for writing, reading and dry-run checking alike.

#include "Caliber/WorldSnapshot.h"

#include <typeinfo>

#include "BulletCollision/CollisionDispatch/btGhostObject.h"
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h"
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorldMt.h"
#include "BulletDynamics/ConstraintSolver/btSolverScratch.h"
#include "BulletDynamics/Dynamics/btWorldSnapshotAccess.h"
#include "BulletDynamics/Dynamics/btWorldSnapshotInternal.h"
#include "BulletDynamics/Dynamics/btWorldStepContext.h"
#include "LinearMath/btScalar.h"

namespace caliber
{
namespace snapshot_access
{
// The one explicit instantiation per member (a program may hold only one). It lives in this file, the
// one every snapshot call links, so the static library never drops it.
CALIBER_SNAPSHOT_MEMBERS(CALIBER_SNAPSHOT_BIND)

// btConstraintSolverPoolMt keeps its solvers in a private array of a private type. The pointer to that
// member is taken in an explicit instantiation (exempt from access checking) and handed out by a friend
// function whose return type is deduced, so the private type is never named.
struct PoolSolversTag
{
};
auto poolSolversMember(PoolSolversTag);
template <auto Member, class Tag>
struct DeduceMember
{
	friend auto poolSolversMember(Tag) { return Member; }
};
template struct DeduceMember<&btConstraintSolverPoolMt::m_solvers, PoolSolversTag>;
}  // namespace snapshot_access

namespace snapshot
{
namespace
{
using namespace snapshot_access;

thread_local const SnapshotExtension* t_extension = 0;

// Sets the extension of one snapshot call on this thread.
struct ExtensionScope
{
	const SnapshotExtension* previous;
	explicit ExtensionScope(const SnapshotExtension* extension) : previous(t_extension) { t_extension = extension; }
	~ExtensionScope() { t_extension = previous; }
};

const char kMagic[8] = {'C', 'A', 'L', 'S', 'N', 'A', 'P', 0};
// 2: compound algorithms, own manifold counts; 3: the sweep's ray accelerator; 4: contact caches
const unsigned kVersion = 4;
const unsigned kByteOrderMark = 0x01020304u;
const int kSolverSequentialImpulse = 1;
const int kSolverPool = 2;
const int kActionRaycastVehicle = 1;
const int kActionCharacterController = 2;

// The actions whose whole state the snapshot holds (exact classes: a subclass may keep more).
btRaycastVehicle* vehicleOf(btActionInterface* action)
{
	return action && typeid(*action) == typeid(btRaycastVehicle) ? static_cast<btRaycastVehicle*>(action) : 0;
}

btKinematicCharacterController* characterOf(btActionInterface* action)
{
	return action && typeid(*action) == typeid(btKinematicCharacterController)
	           ? static_cast<btKinematicCharacterController*>(action)
	           : 0;
}

// The character's motion between steps: walk or velocity input in progress, jump and fall state,
// positions and orientations of the step being made, the contact it touched.
template <class IO>
void characterFields(IO& io, btKinematicCharacterController& c)
{
	io.field("m_verticalVelocity", characterVerticalVelocity(c));
	io.field("m_verticalOffset", characterVerticalOffset(c));
	io.field("m_jumpSpeed", characterJumpSpeed(c));
	io.field("m_walkDirection", characterWalkDirection(c));
	io.field("m_normalizedDirection", characterNormalizedDirection(c));
	io.field("m_AngVel", characterAngularVelocity(c));
	io.field("m_jumpPosition", characterJumpPosition(c));
	io.field("m_currentPosition", characterCurrentPosition(c));
	io.field("m_currentStepOffset", characterCurrentStepOffset(c));
	io.field("m_targetPosition", characterTargetPosition(c));
	io.field("m_currentOrientation", characterCurrentOrientation(c));
	io.field("m_targetOrientation", characterTargetOrientation(c));
	io.field("m_touchingContact", characterTouchingContact(c));
	io.field("m_touchingNormal", characterTouchingNormal(c));
	io.field("m_wasOnGround", characterWasOnGround(c));
	io.field("m_wasJumping", characterWasJumping(c));
	io.field("m_useWalkDirection", characterUseWalkDirection(c));
	io.field("m_velocityTimeInterval", characterVelocityTimeInterval(c));
	io.field("m_jumpAxis", characterJumpAxis(c));
}

// A wheel's state that one substep leaves for the next (its settings and the driver's inputs, steering,
// engine force and brake, are the user's).
template <class IO>
void wheelFields(IO& io, btWheelInfo& wheel)
{
	btWheelInfo::RaycastInfo& ray = wheel.m_raycastInfo;
	io.field("m_contactNormalWS", ray.m_contactNormalWS);
	io.field("m_contactPointWS", ray.m_contactPointWS);
	io.field("m_suspensionLength", ray.m_suspensionLength);
	io.field("m_hardPointWS", ray.m_hardPointWS);
	io.field("m_wheelDirectionWS", ray.m_wheelDirectionWS);
	io.field("m_wheelAxleWS", ray.m_wheelAxleWS);
	io.field("m_isInContact", ray.m_isInContact);
	io.field("m_worldTransform", wheel.m_worldTransform);
	io.field("m_rotation", wheel.m_rotation);
	io.field("m_deltaRotation", wheel.m_deltaRotation);
	io.field("m_clippedInvContactDotSuspension", wheel.m_clippedInvContactDotSuspension);
	io.field("m_suspensionRelativeVelocity", wheel.m_suspensionRelativeVelocity);
	io.field("m_wheelsSuspensionForce", wheel.m_wheelsSuspensionForce);
	io.field("m_skidInfo", wheel.m_skidInfo);
}

template <class IO>
void objectFields(IO& io, btCollisionObject& object)
{
	io.field("m_worldTransform", worldTransform(object));
	io.field("m_interpolationWorldTransform", interpolationTransform(object));
	io.field("m_interpolationLinearVelocity", interpolationLinearVelocity(object));
	io.field("m_interpolationAngularVelocity", interpolationAngularVelocity(object));
	// Static and kinematic objects sit in other lists of the world: a snapshot may not change them.
	io.fieldKeepingBits("m_collisionFlags", collisionFlags(object),
	                    btCollisionObject::CF_STATIC_OBJECT | btCollisionObject::CF_KINEMATIC_OBJECT);
	io.field("m_islandTag1", islandTag(object));
	io.field("m_companionId", companionId(object));
	io.field("m_activationState1", activationState(object), ACTIVE_TAG, DISABLE_SIMULATION);
	io.field("m_deactivationTime", deactivationTime(object));
	io.field("m_hitFraction", hitFraction(object));
	io.field("m_updateRevision", updateRevision(object));
}

template <class IO>
void bodyFields(IO& io, btRigidBody& body)
{
	io.field("m_invInertiaTensorWorld", invInertiaTensorWorld(body));
	io.field("m_linearVelocity", linearVelocity(body));
	io.field("m_angularVelocity", angularVelocity(body));
	io.field("m_gravity", bodyGravity(body));
	io.field("m_gravity_acceleration", bodyGravityAcceleration(body));
	io.field("m_totalForce", totalForce(body));
	io.field("m_totalTorque", totalTorque(body));
	io.field("m_deltaLinearVelocity", deltaLinearVelocity(body));
	io.field("m_deltaAngularVelocity", deltaAngularVelocity(body));
	io.field("m_pushVelocity", pushVelocity(body));
	io.field("m_turnVelocity", turnVelocity(body));
}

// The joint state a step carries to the next, besides the warm-start impulses (in the solver).
template <class IO>
void jointFields(IO& io, btTypedConstraint& joint)
{
	io.field("m_isEnabled", jointEnabled(joint));
	io.field("m_appliedImpulse", jointAppliedImpulse(joint));
	if (btHingeConstraint* hinge = dynamic_cast<btHingeConstraint*>(&joint))
	{
		io.field("hinge m_lastTimeStep", hingeLastTimeStep(*hinge));
		if (btHingeAccumulatedAngleConstraint* accumulated = dynamic_cast<btHingeAccumulatedAngleConstraint*>(hinge))
			io.field("m_accumulatedAngle", hingeAccumulatedAngle(*accumulated));
	}
	if (btConeTwistConstraint* cone = dynamic_cast<btConeTwistConstraint*>(&joint))
		io.field("cone m_lastTimeStep", coneLastTimeStep(*cone));
}

// Writing goes through the same field lists; the writer always "applies" nothing.
struct WriterIO
{
	SnapshotWriter& out;
	template <class T>
	void field(const char* name, T& value)
	{
		out.field(name, value);
	}
	void field(const char* name, int& value, int min, int max) { out.field(name, value, min, max); }
	void fieldKeepingBits(const char* name, int& value, int mask) { out.fieldKeepingBits(name, value, mask); }
	bool applying() const { return false; }
};

int bodyIndex(const btDiscreteDynamicsWorld& world, const btRigidBody& body)
{
	const int index = body.getWorldArrayIndex();
	if (index < 0 || index >= world.getNumCollisionObjects()) return -1;
	return world.getCollisionObjectArray()[index] == &body ? index : -1;
}

// The solvers whose order state the snapshot holds: the world's sequential-impulse solver (kind 1), or
// each solver of its btConstraintSolverPoolMt followed by the Mt world's large-batch solver if it has one
// (kind 2). The joint warm starts live in the first one's store (a pool's solvers and the large-batch
// solver share it). False when a solver is of another kind.
bool solversOf(btDiscreteDynamicsWorld& world, btAlignedObjectArray<btSequentialImpulseConstraintSolver*>& solvers,
               int& kind)
{
	solvers.resize(0);
	kind = 0;
	btConstraintSolver* solver = world.getConstraintSolver();
	if (btSequentialImpulseConstraintSolver* single = dynamic_cast<btSequentialImpulseConstraintSolver*>(solver))
	{
		kind = kSolverSequentialImpulse;
		solvers.push_back(single);
		return true;
	}
	btConstraintSolverPoolMt* pool = dynamic_cast<btConstraintSolverPoolMt*>(solver);
	if (!pool) return false;
	auto& threadSolvers = pool->*poolSolversMember(PoolSolversTag());
	for (int i = 0; i < threadSolvers.size(); ++i)
	{
		btSequentialImpulseConstraintSolver* member =
		    dynamic_cast<btSequentialImpulseConstraintSolver*>(threadSolvers[i].solver);
		if (!member) return false;
		solvers.push_back(member);
	}
	if (btConstraintSolver* large = caliber::stepContextOf(world).largeBatchSolver)
	{
		btSequentialImpulseConstraintSolver* member = dynamic_cast<btSequentialImpulseConstraintSolver*>(large);
		if (!member) return false;
		solvers.push_back(member);
	}
	kind = kSolverPool;
	return solvers.size() > 0;
}

JointWarmStartStore& warmStartStoreOf(btSequentialImpulseConstraintSolver& first)
{
	return solverScratchOf(first).jointWarmStarts();
}

void setError(char* error, size_t errorSize, const char* format, ...)
{
	va_list args;
	va_start(args, format);
	vsnprintf(error, errorSize, format, args);
	va_end(args);
}

int objectIndexOf(const btDiscreteDynamicsWorld& world, const void* object)
{
	const btCollisionObject* o = static_cast<const btCollisionObject*>(object);
	for (int i = 0; o && i < world.getNumCollisionObjects(); ++i)
		if (world.getCollisionObjectArray()[i] == o) return i;
	return -1;
}

// What the snapshot cannot hold; checked before saving and before restoring.
bool worldSupported(btDiscreteDynamicsWorld& world, char* error, size_t errorSize)
{
	btAlignedObjectArray<btActionInterface*>& actions = worldActions(world);
	for (int a = 0; a < actions.size(); ++a)
	{
		if (btKinematicCharacterController* character = characterOf(actions[a]))
		{
			if (objectIndexOf(world, characterGhost(*character)) < 0)
			{
				setError(error, errorSize, "action %d: the character's ghost object is not in the world", a);
				return false;
			}
			continue;
		}
		btRaycastVehicle* vehicle = vehicleOf(actions[a]);
		if (!vehicle)
		{
			setError(error, errorSize,
			         "action %d: only btRaycastVehicle and btKinematicCharacterController are supported (user "
			         "actions and subclasses keep state the snapshot does not hold)",
			         a);
			return false;
		}
		if (bodyIndex(world, *vehicle->getRigidBody()) < 0)
		{
			setError(error, errorSize, "action %d: the vehicle's chassis is not a body of the world", a);
			return false;
		}
		for (int w = 0; w < vehicle->getNumWheels(); ++w)
		{
			const void* ground = vehicle->getWheelInfo(w).m_raycastInfo.m_groundObject;
			if (ground && objectIndexOf(world, ground) < 0)
			{
				setError(error, errorSize, "action %d: wheel %d stands on an object outside the world", a, w);
				return false;
			}
		}
	}
	if (predictiveManifolds(world).size())
	{
		setError(error, errorSize, "world: it has predictive manifolds, which are not held");
		return false;
	}
	btAlignedObjectArray<btSequentialImpulseConstraintSolver*> solvers;
	int solverKind;
	if (!solversOf(world, solvers, solverKind))
	{
		setError(error, errorSize,
		         "solver: only btSequentialImpulseConstraintSolver (and subclasses), alone or in a "
		         "btConstraintSolverPoolMt, is supported");
		return false;
	}
	for (int i = 0; i < world.getNumCollisionObjects(); ++i)
	{
		const btCollisionObject* object = world.getCollisionObjectArray()[i];
		const int type = object->getInternalType();
		// Ghosts of Bullet's two classes (a subclass may keep more state).
		const bool ghost =
		    type == btCollisionObject::CO_GHOST_OBJECT &&
		    (typeid(*object) == typeid(btGhostObject) || typeid(*object) == typeid(btPairCachingGhostObject));
		const bool extended = t_extension && t_extension->acceptsObject(*object);
		if (type != btCollisionObject::CO_COLLISION_OBJECT && type != btCollisionObject::CO_RIGID_BODY && !ghost &&
		    !extended)
		{
			setError(error, errorSize, "object %d: internal type %d (soft bodies, ghost subclasses) is not supported",
			         i, type);
			return false;
		}
	}
	return true;
}

bool saveAll(btDiscreteDynamicsWorld& world, btAlignedObjectArray<unsigned char>& buffer,
             btAlignedObjectArray<SnapshotField>* log, char* error, size_t errorSize)
{
	buffer.resize(0);
	if (!worldSupported(world, error, errorSize)) return false;
	SnapshotWriter out(buffer, log);
	WriterIO io = {out};
	out.context("header", -1);
	out.bytes("magic", kMagic, sizeof(kMagic));
	out.field("version", kVersion);
	out.field("byte order", kByteOrderMark);
	out.field("scalar size", unsigned(sizeof(btScalar)));
	const int sizeAt = buffer.size();
	out.field("size", unsigned(0));  // patched below

	out.context("world", -1);
	io.field("m_localTime", localTime(world));
	io.field("m_fixedTimeStep", fixedTimeStep(world));
	const int n = world.getNumCollisionObjects();
	out.field("object count", n);
	for (int i = 0; i < n; ++i)
	{
		btCollisionObject& object = *world.getCollisionObjectArray()[i];
		out.context("object", i);
		out.field("internal type", object.getInternalType());
		out.field("shape type", object.getCollisionShape() ? object.getCollisionShape()->getShapeType() : -1);
		objectFields(io, object);
		if (btRigidBody* body = btRigidBody::upcast(&object)) bodyFields(io, *body);
	}
	if (!saveCollisionState(world, out, error, errorSize))
	{
		buffer.resize(0);
		return false;
	}

	btAlignedObjectArray<btSequentialImpulseConstraintSolver*> solvers;
	int solverKind;
	solversOf(world, solvers, solverKind);
	JointWarmStartStore& warmStarts = warmStartStoreOf(*solvers[0]);
	const int joints = world.getNumConstraints();
	out.context("joints", -1);
	out.field("joint count", joints);
	for (int j = 0; j < joints; ++j)
	{
		btTypedConstraint& joint = *world.getConstraint(j);
		out.context("joint", j);
		out.field("type", int(joint.getConstraintType()));
		out.field("body A", bodyIndex(world, joint.getRigidBodyA()));
		out.field("body B", bodyIndex(world, joint.getRigidBodyB()));
		jointFields(io, joint);
		const JointImpulses* impulses = warmStarts.find(&joint);
		out.field("warm-start rows", impulses ? impulses->size() : -1);
		for (int r = 0; impulses && r < impulses->size(); ++r)
		{
			out.context("joint", j, r);
			out.field("warm-start impulse", (*impulses)[r]);
		}
	}
	btAlignedObjectArray<btActionInterface*>& actions = worldActions(world);
	out.context("actions", -1);
	out.field("action count", actions.size());
	for (int a = 0; a < actions.size(); ++a)
	{
		out.context("action", a);
		if (btKinematicCharacterController* character = characterOf(actions[a]))
		{
			out.field("kind", kActionCharacterController);
			out.field("ghost", objectIndexOf(world, characterGhost(*character)));
			characterFields(io, *character);
			continue;
		}
		btRaycastVehicle& vehicle = *vehicleOf(actions[a]);
		out.field("kind", kActionRaycastVehicle);
		out.field("chassis", bodyIndex(world, *vehicle.getRigidBody()));
		out.field("wheel count", vehicle.getNumWheels());
		out.field("m_currentVehicleSpeedKmHour", vehicleSpeed(vehicle));
		btAlignedObjectArray<btVector3>* vectors[2] = {&vehicleForwardWS(vehicle), &vehicleAxle(vehicle)};
		for (btAlignedObjectArray<btVector3>* list : vectors)
		{
			out.field("direction count", list->size());
			for (int w = 0; w < list->size(); ++w) out.field("direction", (*list)[w]);
		}
		btAlignedObjectArray<btScalar>* scalars[2] = {&vehicleForwardImpulse(vehicle), &vehicleSideImpulse(vehicle)};
		for (btAlignedObjectArray<btScalar>* list : scalars)
		{
			out.field("impulse count", list->size());
			for (int w = 0; w < list->size(); ++w) out.field("impulse", (*list)[w]);
		}
		for (int w = 0; w < vehicle.getNumWheels(); ++w)
		{
			out.context("action", a, w);
			btWheelInfo& wheel = vehicle.getWheelInfo(w);
			out.field("ground object", objectIndexOf(world, wheel.m_raycastInfo.m_groundObject));
			wheelFields(io, wheel);
		}
	}

	out.context("solver", -1);
	out.field("kind", solverKind);
	out.field("solver count", solvers.size());
	for (int i = 0; i < solvers.size(); ++i)
	{
		out.field("m_btSeed2", static_cast<unsigned long long>(solvers[i]->getRandSeed()));
		out.field("solve count", solverScratchOf(*solvers[i]).solveCount);
	}
	// The world numbers its solver batches (SolveIndexScope): the next step's row order depends on it.
	out.field("world solve count", caliber::stepContextOf(world).solveCounter);
	if (t_extension && !t_extension->save(world, out, error, errorSize))
	{
		buffer.resize(0);
		return false;
	}

	const unsigned size = unsigned(buffer.size());
	memcpy(&buffer[sizeAt], &size, sizeof(size));
	return true;
}

// Reads a whole snapshot: a dry run checks it against world, an applying run writes it into world.
bool readAll(btDiscreteDynamicsWorld& world, const unsigned char* data, size_t size, bool apply, char* error,
             size_t errorSize)
{
	SnapshotReader in(data, size, apply);
	char magic[sizeof(kMagic)];
	if (in.bytes("magic", magic, sizeof(magic)) && memcmp(magic, kMagic, sizeof(kMagic)) != 0)
		in.fail("header: not a Caliber world snapshot (wrong magic)");
	const unsigned version = in.value<unsigned>("version");
	if (in.ok() && version != kVersion) in.fail("header: snapshot version %u, this build reads %u", version, kVersion);
	const unsigned mark = in.value<unsigned>("byte order");
	if (in.ok() && mark != kByteOrderMark) in.fail("header: written on a machine of the other byte order");
	const unsigned scalarSize = in.value<unsigned>("scalar size");
	if (in.ok() && scalarSize != sizeof(btScalar))
		in.fail("header: written by a %s-precision build", scalarSize == 8 ? "double" : "single");
	const unsigned total = in.value<unsigned>("size");
	if (in.ok() && total != size) in.fail("header: the snapshot has %u bytes, the buffer %zu", total, size);

	in.field("m_localTime", localTime(world));
	in.field("m_fixedTimeStep", fixedTimeStep(world));
	const int n = world.getNumCollisionObjects();
	const int savedCount = in.value<int>("object count");
	if (in.ok() && savedCount != n) in.fail("world: %d collision objects, the snapshot has %d", n, savedCount);
	for (int i = 0; i < n && in.ok(); ++i)
	{
		btCollisionObject& object = *world.getCollisionObjectArray()[i];
		const int internalType = in.value<int>("internal type");
		const int shapeType = in.value<int>("shape type");
		const int liveShape = object.getCollisionShape() ? object.getCollisionShape()->getShapeType() : -1;
		if (in.ok() && (internalType != object.getInternalType() || shapeType != liveShape))
		{
			in.fail("object %d: internal type %d with shape type %d, the snapshot's %d with %d", i,
			        object.getInternalType(), liveShape, internalType, shapeType);
			break;
		}
		objectFields(in, object);
		if (btRigidBody* body = btRigidBody::upcast(&object)) bodyFields(in, *body);
	}
	if (in.ok()) readCollisionState(world, in);

	btAlignedObjectArray<btSequentialImpulseConstraintSolver*> solvers;
	int liveSolverKind = 0;
	if (!solversOf(world, solvers, liveSolverKind)) in.fail("solver: the world's solver is not supported");
	const int joints = world.getNumConstraints();
	const int savedJoints = in.value<int>("joint count");
	if (in.ok() && savedJoints != joints) in.fail("world: %d joints, the snapshot has %d", joints, savedJoints);
	for (int j = 0; j < joints && in.ok(); ++j)
	{
		btTypedConstraint& joint = *world.getConstraint(j);
		const int type = in.value<int>("type");
		const int bodyA = in.value<int>("body A");
		const int bodyB = in.value<int>("body B");
		if (in.ok() && (type != int(joint.getConstraintType()) || bodyA != bodyIndex(world, joint.getRigidBodyA()) ||
		                bodyB != bodyIndex(world, joint.getRigidBodyB())))
		{
			in.fail("joint %d: type %d between objects %d and %d, the snapshot's type %d between %d and %d", j,
			        int(joint.getConstraintType()), bodyIndex(world, joint.getRigidBodyA()),
			        bodyIndex(world, joint.getRigidBodyB()), type, bodyA, bodyB);
			break;
		}
		jointFields(in, joint);
		const int rows = in.value<int>("warm-start rows");
		if (in.ok() && (rows < -1 || size_t(rows) > in.remaining() / sizeof(btScalar)))
			in.fail("joint %d: %d warm-start rows", j, rows);
		btAlignedObjectArray<btScalar> impulses;
		for (int r = 0; r < rows && in.ok(); ++r) impulses.push_back(in.scalar("warm-start impulse"));
		if (in.ok() && apply)
		{
			JointWarmStartStore& store = warmStartStoreOf(*solvers[0]);
			if (rows < 0)
			{
				store.forget(&joint);
			}
			else
			{
				JointImpulses& entry = *store.entryOf(&joint);
				entry.resize(rows);
				for (int r = 0; r < rows; ++r) entry[r] = impulses[r];
			}
		}
	}
	btAlignedObjectArray<btActionInterface*>& actions = worldActions(world);
	const int actionCount = in.value<int>("action count");
	if (in.ok() && actionCount != actions.size())
		in.fail("world: %d actions, the snapshot has %d", actions.size(), actionCount);
	for (int a = 0; a < actions.size() && in.ok(); ++a)
	{
		const int kind = in.value<int>("kind");
		if (btKinematicCharacterController* character = characterOf(actions[a]))
		{
			const int ghost = in.value<int>("ghost");
			if (in.ok() &&
			    (kind != kActionCharacterController || ghost != objectIndexOf(world, characterGhost(*character))))
			{
				in.fail("action %d: kind %d on object %d, not the world's character controller on object %d", a, kind,
				        ghost, objectIndexOf(world, characterGhost(*character)));
				break;
			}
			characterFields(in, *character);
			continue;
		}
		btRaycastVehicle* vehicle = vehicleOf(actions[a]);
		if (in.ok() && (kind != kActionRaycastVehicle || !vehicle))
		{
			in.fail("action %d: kind %d, not the world's raycast vehicle", a, kind);
			break;
		}
		const int chassis = in.value<int>("chassis");
		const int wheels = in.value<int>("wheel count");
		if (in.ok() && (chassis != bodyIndex(world, *vehicle->getRigidBody()) || wheels != vehicle->getNumWheels()))
		{
			in.fail("action %d: a vehicle on object %d with %d wheels, the snapshot's on %d with %d", a,
			        bodyIndex(world, *vehicle->getRigidBody()), vehicle->getNumWheels(), chassis, wheels);
			break;
		}
		in.field("m_currentVehicleSpeedKmHour", vehicleSpeed(*vehicle));
		btAlignedObjectArray<btVector3>* vectors[2] = {&vehicleForwardWS(*vehicle), &vehicleAxle(*vehicle)};
		for (btAlignedObjectArray<btVector3>* list : vectors)
		{
			const int count = in.count("direction count", wheels);
			btAlignedObjectArray<btVector3> values;
			for (int w = 0; w < count && in.ok(); ++w) values.push_back(in.vector("direction"));
			if (in.ok() && apply) *list = values;
		}
		btAlignedObjectArray<btScalar>* scalars[2] = {&vehicleForwardImpulse(*vehicle), &vehicleSideImpulse(*vehicle)};
		for (btAlignedObjectArray<btScalar>* list : scalars)
		{
			const int count = in.count("impulse count", wheels);
			btAlignedObjectArray<btScalar> values;
			for (int w = 0; w < count && in.ok(); ++w) values.push_back(in.scalar("impulse"));
			if (in.ok() && apply) *list = values;
		}
		for (int w = 0; w < wheels && in.ok(); ++w)
		{
			btWheelInfo& wheel = vehicle->getWheelInfo(w);
			const int ground = in.value<int>("ground object");
			if (in.ok() && (ground < -1 || ground >= n))
				in.fail("action %d: wheel %d stands on object %d, not an object of the world", a, w, ground);
			wheelFields(in, wheel);
			if (in.ok() && apply)
				wheel.m_raycastInfo.m_groundObject = ground < 0 ? 0 : world.getCollisionObjectArray()[ground];
		}
	}
	const int solverKind = in.value<int>("solver kind");
	const int solverCount = in.value<int>("solver count");
	if (in.ok() && (solverKind != liveSolverKind || solverCount != solvers.size()))
		in.fail(
		    "solver: kind %d with %d solvers, the snapshot's kind %d with %d (a pool of another size, or "
		    "a large-batch solver more or less)",
		    liveSolverKind, solvers.size(), solverKind, solverCount);
	btAlignedObjectArray<unsigned long long> seeds;
	btAlignedObjectArray<unsigned> solveCounts;
	for (int i = 0; i < solverCount && in.ok(); ++i)
	{
		seeds.push_back(in.value<unsigned long long>("m_btSeed2"));
		solveCounts.push_back(in.value<unsigned>("solve count"));
	}
	const unsigned worldSolveCount = in.value<unsigned>("world solve count");
	if (in.ok() && t_extension) t_extension->read(world, in);
	if (in.ok() && in.remaining() != 0) in.fail("trailing bytes after the snapshot");
	if (in.ok() && apply)
	{
		for (int i = 0; i < solvers.size(); ++i)
		{
			solvers[i]->setRandSeed(static_cast<unsigned long>(seeds[i]));
			solverScratchOf(*solvers[i]).solveCount = solveCounts[i];
		}
		caliber::stepContextOf(world).solveCounter = worldSolveCount;
	}
	if (!in.ok()) setError(error, errorSize, "%s", in.error());
	return in.ok();
}

void noteError(SnapshotError* error, const char* message)
{
	if (error) snprintf(error->message, sizeof(error->message), "%s", message);
}
}  // namespace

const SnapshotExtension* currentExtension() { return t_extension; }
}  // namespace snapshot

bool saveWorldState(const btDiscreteDynamicsWorld& world, btAlignedObjectArray<unsigned char>& buffer,
                    SnapshotError* error)
{
	return saveWorldStateWith(world, buffer, error, 0);
}

bool restoreWorldState(btDiscreteDynamicsWorld& world, const unsigned char* data, size_t size, SnapshotError* error)
{
	return restoreWorldStateWith(world, data, size, error, 0);
}

bool compareWorldState(const btDiscreteDynamicsWorld& world, const unsigned char* data, size_t size,
                       SnapshotDifference* difference, SnapshotError* error)
{
	return compareWorldStateWith(world, data, size, difference, error, 0);
}

bool saveWorldStateWith(const btDiscreteDynamicsWorld& world, btAlignedObjectArray<unsigned char>& buffer,
                        SnapshotError* error, const snapshot::SnapshotExtension* extension)
{
	snapshot::ExtensionScope scope(extension);
	char message[256] = {0};
	// Saving reads only; the accessors are written for the restore, hence the cast.
	const bool saved =
	    snapshot::saveAll(const_cast<btDiscreteDynamicsWorld&>(world), buffer, 0, message, sizeof(message));
	if (!saved) snapshot::noteError(error, message);
	return saved;
}

bool restoreWorldStateWith(btDiscreteDynamicsWorld& world, const unsigned char* data, size_t size, SnapshotError* error,
                           const snapshot::SnapshotExtension* extension)
{
	snapshot::ExtensionScope scope(extension);
	char message[256] = {0};
	btAssert((data || !size) && "restoreWorldState: null data");
	if (!data || size == 0)
	{
		snapshot::noteError(error, "restoreWorldState: no data");
		return false;
	}
	// 1. Check the whole buffer against the world without writing anything.
	if (!snapshot::readAll(world, data, size, false, message, sizeof(message)) ||
	    !snapshot::collisionStateReplaceable(world, message, sizeof(message)))
	{
		snapshot::noteError(error, message);
		return false;
	}
	// 2. Keep the current state: what the check cannot foresee (the dispatcher making other algorithms
	//    than the snapshot's, a pair filter refusing a pair) is found only while applying.
	btAlignedObjectArray<unsigned char> backup;
	if (!snapshot::saveAll(world, backup, 0, message, sizeof(message)))
	{
		snapshot::noteError(error, message);
		return false;
	}
	// 3. Apply; on failure, put the old state back.
	if (!snapshot::readAll(world, data, size, true, message, sizeof(message)))
	{
		char undo[256];
		const bool undone = snapshot::readAll(world, &backup[0], size_t(backup.size()), true, undo, sizeof(undo));
		btAssert(undone && "restoreWorldState: the world's own state did not restore");
		(void)undone;
		snapshot::noteError(error, message);
		return false;
	}
	// The motion states show the restored poses, as after a step.
	world.synchronizeMotionStates();
	return true;
}

bool compareWorldStateWith(const btDiscreteDynamicsWorld& world, const unsigned char* data, size_t size,
                           SnapshotDifference* difference, SnapshotError* error,
                           const snapshot::SnapshotExtension* extension)
{
	snapshot::ExtensionScope scope(extension);
	if (difference)
	{
		snprintf(difference->section, sizeof(difference->section), "header");
		difference->index = -1;
		difference->field[0] = 0;
		difference->offset = 0;
	}
	char message[256] = {0};
	btAlignedObjectArray<unsigned char> current;
	btAlignedObjectArray<SnapshotField> log;
	if (!data || size == 0)
	{
		snapshot::noteError(error, "compareWorldState: no data");
		return false;
	}
	if (!snapshot::saveAll(const_cast<btDiscreteDynamicsWorld&>(world), current, &log, message, sizeof(message)))
	{
		snapshot::noteError(error, message);
		return false;
	}
	const size_t common = btMin(size, size_t(current.size()));
	size_t first = common;
	for (size_t k = 0; k < common; ++k)
	{
		if (data[k] != current[int(k)])
		{
			first = k;
			break;
		}
	}
	if (first == common && size == size_t(current.size())) return true;
	if (difference)
	{
		difference->offset = first;
		for (int f = 0; f < log.size(); ++f)
		{
			const SnapshotField& field = log[f];
			if (first >= field.offset && first < field.offset + field.size)
			{
				snprintf(difference->section, sizeof(difference->section), "%s", field.section);
				difference->index = field.index;
				if (field.subIndex >= 0)
					snprintf(difference->field, sizeof(difference->field), "[%d] %s", field.subIndex, field.name);
				else
					snprintf(difference->field, sizeof(difference->field), "%s", field.name);
				break;
			}
			if (f == log.size() - 1) snprintf(difference->field, sizeof(difference->field), "end of snapshot");
		}
	}
	snapshot::noteError(error, "the world differs from the snapshot");
	return false;
}
}  // namespace caliber
