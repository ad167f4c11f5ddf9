// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// caliber::saveWorldState / restoreWorldState / compareWorldState (include/Caliber/WorldSnapshot.h;
// docs/serialization.md, "Snapshot and restore"). A snapshot is, in order: the header, the world's time,
// every collision object's step state, the collision state (btWorldSnapshotCollision.cpp), every joint's
// state with its warm-start impulses, and the solver's order state. Each part is described once, as a
// list of fields that one template walks for writing, reading and dry-run checking alike.

#include "Caliber/WorldSnapshot.h"

#include <typeinfo>

#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h"
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
}  // namespace snapshot_access

namespace snapshot
{
namespace
{
using namespace snapshot_access;

const char kMagic[8] = {'C', 'A', 'L', 'S', 'N', 'A', 'P', 0};
const unsigned kVersion = 1;
const unsigned kByteOrderMark = 0x01020304u;
const int kSolverSequentialImpulse = 1;

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

btSequentialImpulseConstraintSolver* solverOf(btDiscreteDynamicsWorld& world)
{
	return dynamic_cast<btSequentialImpulseConstraintSolver*>(world.getConstraintSolver());
}

void setError(char* error, size_t errorSize, const char* format, ...)
{
	va_list args;
	va_start(args, format);
	vsnprintf(error, errorSize, format, args);
	va_end(args);
}

// What the snapshot cannot hold; checked before saving and before restoring.
bool worldSupported(btDiscreteDynamicsWorld& world, char* error, size_t errorSize)
{
	if (worldActions(world).size())
	{
		setError(error, errorSize, "world: it has actions (vehicles, character controllers), whose state is not held");
		return false;
	}
	if (predictiveManifolds(world).size())
	{
		setError(error, errorSize, "world: it has predictive manifolds, which are not held");
		return false;
	}
	if (!solverOf(world))
	{
		setError(error, errorSize, "solver: only btSequentialImpulseConstraintSolver (and subclasses) is supported");
		return false;
	}
	for (int i = 0; i < world.getNumCollisionObjects(); ++i)
	{
		const btCollisionObject* object = world.getCollisionObjectArray()[i];
		const int type = object->getInternalType();
		if (type != btCollisionObject::CO_COLLISION_OBJECT && type != btCollisionObject::CO_RIGID_BODY)
		{
			setError(error, errorSize, "object %d: internal type %d (soft bodies, ghosts) is not supported", i, type);
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

	btSequentialImpulseConstraintSolver& solver = *solverOf(world);
	JointWarmStartStore& warmStarts = solverScratchOf(solver).warmStarts;
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
	out.context("solver", -1);
	out.field("kind", kSolverSequentialImpulse);
	out.field("m_btSeed2", static_cast<unsigned long long>(solver.getRandSeed()));
	out.field("solve count", solverScratchOf(solver).solveCount);
	// The world numbers its solver batches (SolveIndexScope): the next step's row order depends on it.
	out.field("world solve count", caliber::stepContextOf(world).solveCounter);

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

	btSequentialImpulseConstraintSolver* solver = solverOf(world);
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
		if (in.ok() && apply && solver)
		{
			JointWarmStartStore& store = solverScratchOf(*solver).warmStarts;
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
	const int solverKind = in.value<int>("solver kind");
	if (in.ok() && solverKind != kSolverSequentialImpulse) in.fail("solver: unknown kind %d", solverKind);
	const unsigned long long seed = in.value<unsigned long long>("m_btSeed2");
	const unsigned solveCount = in.value<unsigned>("solve count");
	const unsigned worldSolveCount = in.value<unsigned>("world solve count");
	if (in.ok() && in.remaining() != 0) in.fail("trailing bytes after the snapshot");
	if (in.ok() && apply && solver)
	{
		solver->setRandSeed(static_cast<unsigned long>(seed));
		solverScratchOf(*solver).solveCount = solveCount;
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
}  // namespace snapshot

bool saveWorldState(const btDiscreteDynamicsWorld& world, btAlignedObjectArray<unsigned char>& buffer,
                    SnapshotError* error)
{
	char message[256] = {0};
	// Saving reads only; the accessors are written for the restore, hence the cast.
	const bool saved =
	    snapshot::saveAll(const_cast<btDiscreteDynamicsWorld&>(world), buffer, 0, message, sizeof(message));
	if (!saved) snapshot::noteError(error, message);
	return saved;
}

bool restoreWorldState(btDiscreteDynamicsWorld& world, const unsigned char* data, size_t size, SnapshotError* error)
{
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

bool compareWorldState(const btDiscreteDynamicsWorld& world, const unsigned char* data, size_t size,
                       SnapshotDifference* difference, SnapshotError* error)
{
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
