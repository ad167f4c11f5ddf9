// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btCompoundShape.h"

#include <new>

#include "BulletCollision/BroadphaseCollision/btDbvt.h"
#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "LinearMath/btAabbUtil2.h"

namespace
{
/// The leaf data of child index: the index in the pointer (Bullet's convention) and, so that dataAsInt
/// is the member written last, in dataAsInt as well.
void setLeafIndex(btDbvtNode* node, int index)
{
	node->data = reinterpret_cast<void*>(static_cast<size_t>(index));
	node->dataAsInt = index;
}

bool isValidScaling(const btVector3& s)
{
	return caliber::isFinite(s) && s.x() != btScalar(0) && s.y() != btScalar(0) && s.z() != btScalar(0);
}

void childAabb(const btCompoundShapeChild& child, btVector3& aabbMin, btVector3& aabbMax)
{
	child.m_childShape->getAabb(child.m_transform, aabbMin, aabbMax);
}

// Removes child index (the last child takes its place) without touching the compound's box.
void removeChild(btAlignedObjectArray<btCompoundShapeChild>& children, btDbvt* tree, int& updateRevision, int index)
{
	++updateRevision;
	if (tree && children[index].m_node) tree->remove(children[index].m_node);
	const int last = children.size() - 1;
	if (index != last)
	{
		children.swap(index, last);
		if (children[index].m_node) setLeafIndex(children[index].m_node, index);
	}
	children.pop_back();
}

// What the transform getters return for an out-of-range index: the identity, reset on every such call
// (the caller may write to it), one per thread.
btTransform& invalidChildTransform()
{
	static thread_local btTransform transform;
	transform.setIdentity();
	return transform;
}
}  // namespace

btCompoundShape::btCompoundShape(bool enableDynamicAabbTree, const int initialChildCapacity)
    : m_localAabbMin(0, 0, 0),
      m_localAabbMax(0, 0, 0),
      m_dynamicAabbTree(0),
      m_updateRevision(1),
      m_collisionMargin(0),
      m_localScaling(1, 1, 1)
{
	m_shapeType = COMPOUND_SHAPE_PROXYTYPE;
	if (enableDynamicAabbTree)
	{
		void* memory = btAlignedAlloc(sizeof(btDbvt), 16);
		m_dynamicAabbTree = new (memory) btDbvt();
	}
	if (initialChildCapacity > 0) m_children.reserve(initialChildCapacity);
}

btCompoundShape::~btCompoundShape()
{
	if (m_dynamicAabbTree)
	{
		m_dynamicAabbTree->~btDbvt();
		btAlignedFree(m_dynamicAabbTree);
	}
}

void btCompoundShape::addChildShape(const btTransform& localTransform, btCollisionShape* shape)
{
	btAssert(shape && "btCompoundShape::addChildShape: null shape");
	if (!shape) return;
	btAssert(caliber::isFinite(localTransform) && "btCompoundShape::addChildShape: non-finite transform");
	if (!caliber::isFinite(localTransform)) return;

	++m_updateRevision;
	btCompoundShapeChild child;
	child.m_transform = localTransform;
	child.m_childShape = shape;
	child.m_childShapeType = shape->getShapeType();
	child.m_childMargin = shape->getMargin();
	child.m_node = 0;

	btVector3 aabbMin, aabbMax;
	shape->getAabb(localTransform, aabbMin, aabbMax);
	if (m_children.size() == 0)
	{
		m_localAabbMin = aabbMin;
		m_localAabbMax = aabbMax;
	}
	else
	{
		m_localAabbMin.setMin(aabbMin);
		m_localAabbMax.setMax(aabbMax);
	}
	const int index = m_children.size();
	if (m_dynamicAabbTree)
	{
		child.m_node = m_dynamicAabbTree->insert(btDbvtVolume::FromMM(aabbMin, aabbMax), 0);
		setLeafIndex(child.m_node, index);
	}
	m_children.push_back(child);
}

void btCompoundShape::removeChildShapeByIndex(int childShapeIndex)
{
	const bool valid = childShapeIndex >= 0 && childShapeIndex < m_children.size();
	btAssert(valid && "btCompoundShape::removeChildShapeByIndex: index out of range");
	if (!valid) return;
	removeChild(m_children, m_dynamicAabbTree, m_updateRevision, childShapeIndex);
	// Unlike Bullet, the local AABB shrinks at once: a stale box would only be conservative, but queries
	// against the compound would then visit space no child occupies.
	recalculateLocalAabb();
}

void btCompoundShape::removeChildShape(btCollisionShape* shape)
{
	// From the back, so that the child moved into a hole has already been checked.
	for (int i = m_children.size() - 1; i >= 0; --i)
	{
		if (m_children[i].m_childShape == shape) removeChild(m_children, m_dynamicAabbTree, m_updateRevision, i);
	}
	recalculateLocalAabb();
}

btCollisionShape* btCompoundShape::getChildShape(int index)
{
	const bool valid = index >= 0 && index < m_children.size();
	btAssert(valid && "btCompoundShape::getChildShape: index out of range");
	return valid ? m_children[index].m_childShape : 0;
}

const btCollisionShape* btCompoundShape::getChildShape(int index) const
{
	const bool valid = index >= 0 && index < m_children.size();
	btAssert(valid && "btCompoundShape::getChildShape: index out of range");
	return valid ? m_children[index].m_childShape : 0;
}

btTransform& btCompoundShape::getChildTransform(int index)
{
	const bool valid = index >= 0 && index < m_children.size();
	btAssert(valid && "btCompoundShape::getChildTransform: index out of range");
	if (valid) return m_children[index].m_transform;
	return invalidChildTransform();
}

const btTransform& btCompoundShape::getChildTransform(int index) const
{
	const bool valid = index >= 0 && index < m_children.size();
	btAssert(valid && "btCompoundShape::getChildTransform: index out of range");
	if (valid) return m_children[index].m_transform;
	return invalidChildTransform();
}

void btCompoundShape::updateChildTransform(int childIndex, const btTransform& newChildTransform,
                                           bool shouldRecalculateLocalAabb)
{
	const bool valid = childIndex >= 0 && childIndex < m_children.size();
	btAssert(valid && "btCompoundShape::updateChildTransform: index out of range");
	if (!valid) return;
	btAssert(caliber::isFinite(newChildTransform) && "btCompoundShape::updateChildTransform: non-finite transform");
	if (!caliber::isFinite(newChildTransform)) return;

	m_children[childIndex].m_transform = newChildTransform;
	if (m_dynamicAabbTree && m_children[childIndex].m_node)
	{
		btVector3 aabbMin, aabbMax;
		childAabb(m_children[childIndex], aabbMin, aabbMax);
		btDbvtVolume bounds = btDbvtVolume::FromMM(aabbMin, aabbMax);
		m_dynamicAabbTree->update(m_children[childIndex].m_node, bounds);
	}
	if (shouldRecalculateLocalAabb) recalculateLocalAabb();
}

void btCompoundShape::recalculateLocalAabb()
{
	if (m_children.size() == 0)
	{
		m_localAabbMin.setValue(0, 0, 0);
		m_localAabbMax.setValue(0, 0, 0);
		return;
	}
	childAabb(m_children[0], m_localAabbMin, m_localAabbMax);
	for (int i = 1; i < m_children.size(); ++i)
	{
		btVector3 aabbMin, aabbMax;
		childAabb(m_children[i], aabbMin, aabbMax);
		m_localAabbMin.setMin(aabbMin);
		m_localAabbMax.setMax(aabbMax);
	}
}

void btCompoundShape::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const
{
	if (!caliber::checkAabbTransform(t, aabbMin, aabbMax)) return;
	btTransformAabb(m_localAabbMin, m_localAabbMax, m_collisionMargin, t, aabbMin, aabbMax);
}

void btCompoundShape::setLocalScaling(const btVector3& scaling)
{
	btAssert(isValidScaling(scaling) && "btCompoundShape::setLocalScaling: zero or non-finite scaling");
	if (!isValidScaling(scaling)) return;
	const btVector3 ratio = scaling / m_localScaling;
	for (int i = 0; i < m_children.size(); ++i)
	{
		btCollisionShape* shape = m_children[i].m_childShape;
		shape->setLocalScaling(shape->getLocalScaling() * ratio);
		btTransform childTransform = m_children[i].m_transform;
		childTransform.setOrigin(childTransform.getOrigin() * ratio);
		updateChildTransform(i, childTransform, false);
	}
	m_localScaling = scaling;
	recalculateLocalAabb();
}

void btCompoundShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const
{
	if (!caliber::checkMass(mass, inertia)) return;
	if (m_children.size() == 0)
	{
		inertia.setValue(0, 0, 0);
		return;
	}
	btVector3 aabbMin, aabbMax;
	btTransform identity;
	identity.setIdentity();
	getAabb(identity, aabbMin, aabbMax);
	const btVector3 size = aabbMax - aabbMin;
	const btScalar x2 = size.x() * size.x(), y2 = size.y() * size.y(), z2 = size.z() * size.z();
	inertia = (mass / btScalar(12)) * btVector3(y2 + z2, x2 + z2, x2 + y2);
}

void btCompoundShape::createAabbTreeFromChildren()
{
	if (m_dynamicAabbTree) return;
	void* memory = btAlignedAlloc(sizeof(btDbvt), 16);
	m_dynamicAabbTree = new (memory) btDbvt();
	for (int i = 0; i < m_children.size(); ++i)
	{
		btVector3 aabbMin, aabbMax;
		childAabb(m_children[i], aabbMin, aabbMax);
		m_children[i].m_node = m_dynamicAabbTree->insert(btDbvtVolume::FromMM(aabbMin, aabbMax), 0);
		setLeafIndex(m_children[i].m_node, i);
	}
}

void btCompoundShape::calculatePrincipalAxisTransform(const btScalar* masses, btTransform& principal,
                                                      btVector3& inertia) const
{
	principal.setIdentity();
	inertia.setValue(0, 0, 0);
	const int n = m_children.size();
	if (n == 0) return;
	btAssert(masses && "calculatePrincipalAxisTransform: null masses");
	if (!masses) return;
	bool valid = true;
	btScalar totalMass = 0;
	for (int k = 0; k < n; ++k)
	{
		valid = valid && masses[k] >= btScalar(0) && btIsFinite(masses[k]);
		totalMass += masses[k];
	}
	valid = valid && totalMass > btScalar(0) && btIsFinite(totalMass);
	btAssert(valid && "calculatePrincipalAxisTransform: masses must be finite, >= 0 and not all 0");
	if (!valid) return;

	btVector3 centre(0, 0, 0);
	for (int k = 0; k < n; ++k) centre += m_children[k].m_transform.getOrigin() * masses[k];
	centre /= totalMass;

	btMatrix3x3 tensor(0, 0, 0, 0, 0, 0, 0, 0, 0);
	for (int k = 0; k < n; ++k)
	{
		btVector3 local;
		m_children[k].m_childShape->calculateLocalInertia(masses[k], local);
		// The child's tensor in the compound frame: R diag(local) R^T.
		const btMatrix3x3& r = m_children[k].m_transform.getBasis();
		const btMatrix3x3 rotated = r.scaled(local) * r.transpose();
		// Parallel axis theorem: + m (|o|^2 E - o o^T) for the offset o from the centre of mass.
		const btVector3 o = m_children[k].m_transform.getOrigin() - centre;
		const btScalar m = masses[k];
		const btScalar o2 = o.length2();
		for (int i = 0; i < 3; ++i)
		{
			for (int j = 0; j < 3; ++j) tensor[i][j] += rotated[i][j] + m * ((i == j ? o2 : btScalar(0)) - o[i] * o[j]);
		}
	}
	btMatrix3x3 axes;
	axes.setIdentity();
	// Relative threshold: the off-diagonal terms end below 1e-6 of the largest moment (far below the
	// accuracy of the children's inertias, still reachable in single precision).
	tensor.diagonalize(axes, btScalar(1e-6), 50);
	principal.setBasis(axes);
	principal.setOrigin(centre);
	inertia.setValue(tensor[0][0], tensor[1][1], tensor[2][2]);
}
