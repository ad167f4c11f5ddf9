// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SOFT_BODY_INTERNAL_H
#define CALIBER_SOFT_BODY_INTERNAL_H

// Internal helpers of the soft body layer: the collision shape a soft body shows the broadphase, and
// the shared bad-input reporting.

#include "BulletCollision/CollisionShapes/btCollisionShape.h"
#include "BulletSoftBody/btSoftBody.h"
#include "LinearMath/btWarningHook.h"

namespace caliber
{
/// The shape of a soft body in the collision world: its box is the body's bounds (current and
/// predicted node positions with the margin); the dispatcher hands pairs with it to
/// btSoftRigidCollisionAlgorithm, and the world's ray test asks the body itself.
class SoftBodyCollisionShape : public btCollisionShape
{
public:
	explicit SoftBodyCollisionShape(btSoftBody* body) : m_body(body), m_margin(btScalar(0.25)), m_scaling(1, 1, 1)
	{
		m_shapeType = SOFTBODY_SHAPE_PROXYTYPE;
	}
	void getAabb(const btTransform&, btVector3& aabbMin, btVector3& aabbMax) const override
	{
		m_body->getAabb(aabbMin, aabbMax);
	}
	void setLocalScaling(const btVector3& scaling) override { m_scaling = scaling; }
	const btVector3& getLocalScaling() const override { return m_scaling; }
	void calculateLocalInertia(btScalar, btVector3& inertia) const override { inertia.setValue(0, 0, 0); }
	const char* getName() const override { return "SoftBody"; }
	void setMargin(btScalar margin) override { m_margin = margin; }
	btScalar getMargin() const override { return m_margin; }

private:
	btSoftBody* m_body;
	btScalar m_margin;
	btVector3 m_scaling;
};

/// Reports a soft body bad-input warning (docs/bad-input.md) through btReportWarning.
void softBodyWarning(const char* message);

/// True when index addresses one of count elements.
inline bool validIndex(int index, int count) { return index >= 0 && index < count; }

/// The soft-rigid contact search of one node set against one rigid object (btSoftBodyCollision.cpp).
void collideSoftWithRigid(btSoftBody& body, const btCollisionObjectWrapper& rigid);
}  // namespace caliber

#endif  // CALIBER_SOFT_BODY_INTERNAL_H
