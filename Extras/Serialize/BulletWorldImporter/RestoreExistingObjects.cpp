// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// eRESTORE_EXISTING_OBJECTS: the file's objects are written into the world's (detail/RestoreExistingObjects.h).
// The data reaching here has been checked by btBulletWorldImporter (struct types, finite numbers).
#include "detail/RestoreExistingObjects.h"

#include "detail/ImporterSettings.h"
#include "LinearMath/btWarningHook.h"

#include <string.h>

namespace caliber
{
namespace importer
{
namespace
{
void warn(const std::string& message)
{
	btReportWarning(("Caliber: btBulletWorldImporter (eRESTORE_EXISTING_OBJECTS): " + message + "\n").c_str());
}

std::string describe(const char* kind, int index, const char* name)
{
	return std::string(kind) + " " + std::to_string(index) + (name ? std::string(" '") + name + "'" : std::string());
}

const char* nameOf(const btHashMap<btHashPtr, const char*>& names, const void* object)
{
	const char* const* found = names.find(btHashPtr(object));
	return found ? *found : 0;
}
}  // namespace

ExistingObjects::ExistingObjects(btDynamicsWorld* world, const btHashMap<btHashPtr, const char*>& names)
    : m_world(world), m_names(names)
{
	if (!world) return;
	const btCollisionObjectArray& objects = world->getCollisionObjectArray();
	for (int i = 0; i < objects.size(); ++i)
	{
		if (objects[i]->getBroadphaseHandle()) m_byId.insert(objects[i]->getBroadphaseHandle()->m_uniqueId, objects[i]);
		const char* name = nameOf(names, objects[i]);
		if (!name) continue;
		m_objectNamesKnown = true;
		const int* known = m_nameCount.find(name);
		const int count = known ? *known + 1 : 1;
		m_nameCount.insert(name, count);
		if (count == 1) m_byName.insert(name, objects[i]);
	}
	for (int i = 0; i < world->getNumConstraints(); ++i)
		m_jointNamesKnown |= nameOf(names, world->getConstraint(i)) != 0;
}

template <class ObjectData>
btCollisionObject* ExistingObjects::match(const ObjectData& d, const btCollisionShapeData* shape, bool rigid,
                                          const std::string& what)
{
	if (!m_world) return 0;
	btCollisionObject* target = 0;
	if (m_objectNamesKnown && d.m_name)
	{
		const int* count = m_nameCount.find(d.m_name);
		if (!count)
		{
			warn(what + ": no object of the world has its name; it is not restored");
			return 0;
		}
		if (*count > 1)
		{
			warn(what + ": " + std::to_string(*count) + " objects of the world have its name; it is not restored");
			return 0;
		}
		target = *m_byName.find(d.m_name);
	}
	else
	{
		btCollisionObject** found = m_byId.find(d.m_uniqueId);
		if (!found)
		{
			warn(what + ": no object of the world has its unique id " + std::to_string(d.m_uniqueId) +
			     "; it is not restored");
			return 0;
		}
		target = *found;
		const char* name = nameOf(m_names, target);
		if (name && d.m_name && strcmp(name, d.m_name))
		{
			warn(what + ": the object of its unique id is named '" + name + "'; it is not restored");
			return 0;
		}
	}
	if (m_usedObjects.find(btHashPtr(target)))
	{
		warn(what +
		     ": its object was already restored from an earlier object of the file (a duplicate name or "
		     "id); it is not restored again");
		return 0;
	}
	const bool isRigid = btRigidBody::upcast(target) != 0;
	if (isRigid != rigid || target->getInternalType() != d.m_internalType)
	{
		warn(what + ": the world's object of that name or id is of another kind (internal type " +
		     std::to_string(target->getInternalType()) + ", the file's " + std::to_string(d.m_internalType) +
		     "); it is not restored");
		return 0;
	}
	if (shape && target->getCollisionShape() && target->getCollisionShape()->getShapeType() != shape->m_shapeType)
	{
		warn(what + ": the world's object has a shape of another type (" +
		     std::to_string(target->getCollisionShape()->getShapeType()) + ", the file's " +
		     std::to_string(shape->m_shapeType) + "); it is not restored");
		return 0;
	}
	m_usedObjects.insert(btHashPtr(target), 1);
	return target;
}

// A filter the file recorded and the object lacks is applied by adding the object again (which moves it
// to the end of the world's array); an unchanged filter keeps the world's order.
template <class ObjectData>
void ExistingObjects::applyFilter(btCollisionObject* object, const ObjectData& d)
{
	btBroadphaseProxy* proxy = object->getBroadphaseHandle();
	if ((d.m_collisionFilterGroup == 0 && d.m_collisionFilterMask == 0) || !proxy ||
	    (proxy->m_collisionFilterGroup == d.m_collisionFilterGroup &&
	     proxy->m_collisionFilterMask == d.m_collisionFilterMask))
		return;
	btRigidBody* body = btRigidBody::upcast(object);
	if (body)
	{
		m_world->removeRigidBody(body);
		m_world->addRigidBody(body, d.m_collisionFilterGroup, d.m_collisionFilterMask);
	}
	else
	{
		m_world->removeCollisionObject(object);
		m_world->addCollisionObject(object, d.m_collisionFilterGroup, d.m_collisionFilterMask);
	}
}

template <class BodyData>
btCollisionObject* ExistingObjects::restoreBody(const BodyData& d, const btCollisionShapeData* shape, int index)
{
	const auto& o = d.m_collisionObjectData;
	const std::string what = describe("rigid body", index, o.m_name);
	btCollisionObject* target = match(o, shape, true, what);
	btRigidBody* body = btRigidBody::upcast(target);
	if (!body) return 0;
	// Mass decides whether the world treats the body as static; switching that would need the body added
	// anew, so it is refused rather than half done.
	if ((d.m_inverseMass == 0) != (body->getInvMass() == 0))
	{
		warn(what + ": it is " + (d.m_inverseMass == 0 ? "static" : "dynamic") + " in the file and " +
		     (body->getInvMass() == 0 ? "static" : "dynamic") + " in the world; it is not restored");
		m_usedObjects.remove(btHashPtr(target));
		return 0;
	}
	if (d.m_inverseMass != 0) body->setMassProps(btScalar(1) / btScalar(d.m_inverseMass), btVector3(0, 0, 0));
	body->setCenterOfMassTransform(xform(o.m_worldTransform));
	applyCollisionObjectData(body, o);
	applyRigidBodyData(body, d);
	body->clearForces();
	applyFilter(body, o);
	body->setGravity(vec(d.m_gravity_acceleration));
	m_world->updateSingleAabb(body);
	return body;
}

template <class ObjectData>
btCollisionObject* ExistingObjects::restoreObject(const ObjectData& d, const btCollisionShapeData* shape, int index)
{
	btCollisionObject* target = match(d, shape, false, describe("collision object", index, d.m_name));
	if (!target) return 0;
	target->setWorldTransform(xform(d.m_worldTransform));
	applyCollisionObjectData(target, d);
	applyFilter(target, d);
	m_world->updateSingleAabb(target);
	return target;
}

btCollisionObject* ExistingObjects::restore(const btRigidBodyFloatData& d, const btCollisionShapeData* shape, int index)
{
	return restoreBody(d, shape, index);
}
btCollisionObject* ExistingObjects::restore(const btRigidBodyDoubleData& d, const btCollisionShapeData* shape,
                                            int index)
{
	return restoreBody(d, shape, index);
}
btCollisionObject* ExistingObjects::restore(const btCollisionObjectFloatData& d, const btCollisionShapeData* shape,
                                            int index)
{
	return restoreObject(d, shape, index);
}
btCollisionObject* ExistingObjects::restore(const btCollisionObjectDoubleData& d, const btCollisionShapeData* shape,
                                            int index)
{
	return restoreObject(d, shape, index);
}

namespace
{
// The settings of one joint kind, frames included, written into an existing joint of that kind.
template <class D>
void restoreKind(btTypedConstraint& c, const D& d, btHingeConstraint*)
{
	btHingeConstraint& hinge = static_cast<btHingeConstraint&>(c);
	hinge.setFrames(xform(d.m_rbAFrame), xform(d.m_rbBFrame));
	hinge.setUseReferenceFrameA(d.m_useReferenceFrameA != 0);
	configure(hinge, d);
}
template <class D>
void restoreKind(btTypedConstraint& c, const D& d, btPoint2PointConstraint*)
{
	btPoint2PointConstraint& point = static_cast<btPoint2PointConstraint&>(c);
	point.setPivotA(vec(d.m_pivotInA));
	point.setPivotB(vec(d.m_pivotInB));
}
template <class D>
void restoreKind(btTypedConstraint& c, const D& d, btConeTwistConstraint*)
{
	btConeTwistConstraint& cone = static_cast<btConeTwistConstraint&>(c);
	cone.setFrames(xform(d.m_rbAFrame), xform(d.m_rbBFrame));
	configure(cone, d);
}
template <class D>
void restoreKind(btTypedConstraint& c, const D& d, btGeneric6DofConstraint*)
{
	btGeneric6DofConstraint& dof = static_cast<btGeneric6DofConstraint&>(c);
	dof.setFrames(xform(d.m_rbAFrame), xform(d.m_rbBFrame));
	configure(dof, d);
}
template <class D>
void restoreKind(btTypedConstraint& c, const D& d, btGeneric6DofSpringConstraint*)
{
	btGeneric6DofSpringConstraint& dof = static_cast<btGeneric6DofSpringConstraint&>(c);
	dof.setFrames(xform(d.m_6dofData.m_rbAFrame), xform(d.m_6dofData.m_rbBFrame));
	configureSpring(dof, d);
}
template <class D>
void restoreKind(btTypedConstraint& c, const D& d, btGeneric6DofSpring2Constraint*)
{
	btGeneric6DofSpring2Constraint& dof = static_cast<btGeneric6DofSpring2Constraint&>(c);
	dof.setFrames(xform(d.m_rbAFrame), xform(d.m_rbBFrame));
	if (d.m_rotateOrder >= RO_XYZ && d.m_rotateOrder <= RO_ZYX) dof.setRotationOrder(RotateOrder(d.m_rotateOrder));
	configure(dof, d);
}
template <class D>
void restoreKind(btTypedConstraint& c, const D& d, btSliderConstraint*)
{
	btSliderConstraint& slider = static_cast<btSliderConstraint&>(c);
	slider.setFrames(xform(d.m_rbAFrame), xform(d.m_rbBFrame));
	configure(slider, d);
}
template <class D>
void restoreKind(btTypedConstraint& c, const D& d, btGearConstraint*)
{
	btGearConstraint& gear = static_cast<btGearConstraint&>(c);
	gear.setAxisA(vec(d.m_axisInA));
	gear.setAxisB(vec(d.m_axisInB));
	gear.setRatio(btScalar(d.m_ratio));
}

// The common joint fields at the start of each layout (the spring joint nests them in its 6-DoF part).
template <class D>
auto commonOf(const D& d) -> decltype((d.m_typeConstraintData))
{
	return d.m_typeConstraintData;
}
template <class D>
auto commonOf(const D& d) -> decltype((d.m_6dofData.m_typeConstraintData))
{
	return d.m_6dofData.m_typeConstraintData;
}

template <class Kind, class D>
void restoreAs(btTypedConstraint& c, void* data)
{
	const D& d = *static_cast<const D*>(data);
	restoreKind(c, d, static_cast<Kind*>(0));
	applyJointCommon(c, commonOf(d));
}

// The struct names the importer accepts for each kind (btBulletWorldImporter checked the pairing).
bool restoreByStruct(btTypedConstraint& c, void* data, const char* s)
{
	struct Entry
	{
		const char* name;
		void (*apply)(btTypedConstraint&, void*);
	};
	static const Entry table[] = {
	    {"btPoint2PointConstraintFloatData", restoreAs<btPoint2PointConstraint, btPoint2PointConstraintFloatData>},
	    {"btPoint2PointConstraintDoubleData2", restoreAs<btPoint2PointConstraint, btPoint2PointConstraintDoubleData2>},
	    {"btPoint2PointConstraintDoubleData", restoreAs<btPoint2PointConstraint, btPoint2PointConstraintDoubleData>},
	    {"btHingeConstraintFloatData", restoreAs<btHingeConstraint, btHingeConstraintFloatData>},
	    {"btHingeConstraintDoubleData2", restoreAs<btHingeConstraint, btHingeConstraintDoubleData2>},
	    {"btHingeConstraintDoubleData", restoreAs<btHingeConstraint, btHingeConstraintDoubleData>},
	    {"btConeTwistConstraintData", restoreAs<btConeTwistConstraint, btConeTwistConstraintData>},
	    {"btConeTwistConstraintDoubleData", restoreAs<btConeTwistConstraint, btConeTwistConstraintDoubleData>},
	    {"btGeneric6DofConstraintData", restoreAs<btGeneric6DofConstraint, btGeneric6DofConstraintData>},
	    {"btGeneric6DofConstraintDoubleData2", restoreAs<btGeneric6DofConstraint, btGeneric6DofConstraintDoubleData2>},
	    {"btGeneric6DofSpringConstraintData",
	     restoreAs<btGeneric6DofSpringConstraint, btGeneric6DofSpringConstraintData>},
	    {"btGeneric6DofSpringConstraintDoubleData2",
	     restoreAs<btGeneric6DofSpringConstraint, btGeneric6DofSpringConstraintDoubleData2>},
	    {"btGeneric6DofSpring2ConstraintData",
	     restoreAs<btGeneric6DofSpring2Constraint, btGeneric6DofSpring2ConstraintData>},
	    {"btGeneric6DofSpring2ConstraintDoubleData2",
	     restoreAs<btGeneric6DofSpring2Constraint, btGeneric6DofSpring2ConstraintDoubleData2>},
	    {"btSliderConstraintData", restoreAs<btSliderConstraint, btSliderConstraintData>},
	    {"btSliderConstraintDoubleData", restoreAs<btSliderConstraint, btSliderConstraintDoubleData>},
	    {"btGearConstraintFloatData", restoreAs<btGearConstraint, btGearConstraintFloatData>},
	    {"btGearConstraintDoubleData", restoreAs<btGearConstraint, btGearConstraintDoubleData>},
	};
	for (const Entry& e : table)
		if (!strcmp(e.name, s))
		{
			e.apply(c, data);
			return true;
		}
	return false;
}
}  // namespace

bool ExistingObjects::restoreJoint(btTypedConstraintData* data, const char* structName, btRigidBody* a, btRigidBody* b,
                                   int index)
{
	const std::string what = describe("joint", index, data->m_name);
	btRigidBody* fixed = &btTypedConstraint::getFixedBody();
	btRigidBody* wantA = a ? a : fixed;
	btRigidBody* wantB = b ? b : fixed;
	btTypedConstraint* target = 0;
	if (!m_world) return false;
	const bool byName = m_jointNamesKnown && data->m_name;
	for (int i = 0; i < m_world->getNumConstraints() && !target; ++i)
	{
		btTypedConstraint* c = m_world->getConstraint(i);
		if (m_usedJoints.find(btHashPtr(c))) continue;
		if (byName)
		{
			const char* name = nameOf(m_names, c);
			if (name && !strcmp(name, data->m_name)) target = c;
		}
		else if (int(c->getConstraintType()) == data->m_objectType && &c->getRigidBodyA() == wantA &&
		         &c->getRigidBodyB() == wantB)
			target = c;
	}
	if (!target)
	{
		warn(what +
		     (byName ? ": no joint of the world has its name (or it was already restored)"
		             : ": no joint of the world joins its bodies with its type") +
		     "; it is not restored");
		return false;
	}
	if (int(target->getConstraintType()) != data->m_objectType || &target->getRigidBodyA() != wantA ||
	    &target->getRigidBodyB() != wantB)
	{
		warn(what + ": the world's joint of that name is of another type or joins other bodies; it is not restored");
		return false;
	}
	if (!restoreByStruct(*target, data, structName))
	{
		warn(what + ": its struct " + structName + " is not a joint layout; it is not restored");
		return false;
	}
	m_usedJoints.insert(btHashPtr(target), 1);
	return true;
}
}  // namespace importer
}  // namespace caliber
