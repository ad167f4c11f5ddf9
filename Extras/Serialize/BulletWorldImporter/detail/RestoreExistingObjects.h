// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// Internal to the importer library (not installed): btWorldImporter's flag eRESTORE_EXISTING_OBJECTS. No
// object is created; each object of the file is matched with an object already in the world and the file's
// state and settings are written into it (docs/serialization.md, "Restoring into existing objects").
#ifndef CALIBER_RESTORE_EXISTING_OBJECTS_H
#define CALIBER_RESTORE_EXISTING_OBJECTS_H

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btHashMap.h"

#include <string>

class btCollisionObject;
class btDynamicsWorld;
class btRigidBody;
class btTypedConstraint;
struct btCollisionShapeData;
struct btCollisionObjectFloatData;
struct btCollisionObjectDoubleData;
struct btRigidBodyFloatData;
struct btRigidBodyDoubleData;
struct btTypedConstraintData;

namespace caliber
{
namespace importer
{
/// The world's objects and joints, with the names the importer recorded for them, matched one by one with
/// a file's. Matching rule: when the importer knows names for the world's objects (it loaded them, or a
/// subclass recorded them in m_objectNameMap), a named file object goes to the world object of that name;
/// otherwise to the object whose broadphase handle has the file's unique id (the rule of Bullet's
/// btMultiBodyWorldImporter). A joint goes to the world joint of its name (when joint names are known),
/// otherwise to the first unmatched world joint of its type between the same two bodies. Every refusal is
/// a warning naming the file object; refused objects are left as they are.
class ExistingObjects
{
public:
	/// world may be 0 (the importer has none): then nothing is ever matched.
	ExistingObjects(btDynamicsWorld* world, const btHashMap<btHashPtr, const char*>& names);

	/// Restores a file rigid body (shape: its shape's block, 0 when the file has none) into its match and
	/// returns the match; 0 (with a warning) when there is none.
	btCollisionObject* restore(const btRigidBodyFloatData& d, const btCollisionShapeData* shape, int index);
	btCollisionObject* restore(const btRigidBodyDoubleData& d, const btCollisionShapeData* shape, int index);
	/// Restores a file collision object (not a rigid body) into its match.
	btCollisionObject* restore(const btCollisionObjectFloatData& d, const btCollisionShapeData* shape, int index);
	btCollisionObject* restore(const btCollisionObjectDoubleData& d, const btCollisionShapeData* shape, int index);
	/// Restores a file joint (a block of the struct structName, checked by the caller) between the world
	/// bodies a and b (0: the world's fixed body).
	bool restoreJoint(btTypedConstraintData* data, const char* structName, btRigidBody* a, btRigidBody* b, int index);

private:
	template <class ObjectData>
	btCollisionObject* match(const ObjectData& d, const btCollisionShapeData* shape, bool rigid,
	                         const std::string& what);
	template <class BodyData>
	btCollisionObject* restoreBody(const BodyData& d, const btCollisionShapeData* shape, int index);
	template <class ObjectData>
	btCollisionObject* restoreObject(const ObjectData& d, const btCollisionShapeData* shape, int index);
	template <class ObjectData>
	void applyFilter(btCollisionObject* object, const ObjectData& d);

	btDynamicsWorld* m_world;
	const btHashMap<btHashPtr, const char*>& m_names;
	bool m_objectNamesKnown = false;
	bool m_jointNamesKnown = false;
	// The world's objects by broadphase unique id, and by name with how many carry each name.
	btHashMap<btHashInt, btCollisionObject*> m_byId;
	btHashMap<btHashString, btCollisionObject*> m_byName;
	btHashMap<btHashString, int> m_nameCount;
	btHashMap<btHashPtr, int> m_usedObjects;
	btHashMap<btHashPtr, int> m_usedJoints;
};
}  // namespace importer
}  // namespace caliber

#endif
