// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SOFT_BODY_INTERNAL_H
#define CALIBER_SOFT_BODY_INTERNAL_H

// Internal helpers of the soft body layer: the collision shape a soft body shows the broadphase, and
// the shared bad-input reporting.

#include "BulletCollision/CollisionShapes/btCollisionShape.h"
#include "BulletSoftBody/btSoftBody.h"
#include "LinearMath/btThreads.h"
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

/// The step at which a link's stiffness m_kLST (a tetra's m_kVST) is defined (see updateLinkConstants).
const btScalar kReferenceStep = btScalar(1) / btScalar(60);

/// Compliance per unit of a constraint's inverse mass for stiffness kLST (or kVST) and iterations sweeps a
/// step, as explained in updateLinkConstants; -1 when the stiffness is zero or NaN: the constraint is
/// skipped (docs/bad-input.md).
inline btScalar complianceFactor(btScalar kLST, int iterations)
{
	if (!(kLST > 0)) return -1;
	const btScalar k = btMin(kLST, btScalar(1));
	if (k >= 1) return 0;
	const btScalar kStep = 1 - btPow(1 - k, btScalar(btMax(iterations, 1)));
	return (1 - kStep) / kStep * kReferenceStep * kReferenceStep;
}

/// Reports a soft body bad-input warning (docs/bad-input.md) through btReportWarning.
void softBodyWarning(const char* message);

/// True when index addresses one of count elements.
inline bool validIndex(int index, int count) { return index >= 0 && index < count; }

/// Runs loop over the node indices [0, count) in chunks on the task scheduler (serially for a small body,
/// or inside another parallel loop). For loops whose iterations touch only their own node, so that every
/// thread count gives the same bits.
inline void forEachNodeChunk(int count, const btIParallelForBody& loop)
{
	const int grain = 1024;
	if (count <= 0) return;
	if (count <= grain)
		loop.forLoop(0, count);
	else
		btParallelFor(0, count, grain, loop);
}

/// forEachNodeChunk with a callable f(begin, end): for loops over nodes or links whose iterations touch only
/// their own item.
template <class F>
void forEachChunk(int count, const F& f)
{
	struct Loop : btIParallelForBody
	{
		const F* f;
		void forLoop(int begin, int end) const override { (*f)(begin, end); }
	};
	Loop loop;
	loop.f = &f;
	forEachNodeChunk(count, loop);
}

/// A tetra's signed volume (as tetraVolume: (x1 - x0) . ((x2 - x0) x (x3 - x0)) / 6) and its gradients with
/// respect to the four nodes, written to t.m_c0 (the tetra volume constraint, btSoftBodySolve.cpp).
inline btScalar tetraGradients(btSoftBody::Tetra& t)
{
	const btVector3 e1 = t.m_n[1]->m_x - t.m_n[0]->m_x;
	const btVector3 e2 = t.m_n[2]->m_x - t.m_n[0]->m_x;
	const btVector3 e3 = t.m_n[3]->m_x - t.m_n[0]->m_x;
	const btScalar sixth = btScalar(1) / btScalar(6);
	t.m_c0[1] = e2.cross(e3) * sixth;
	t.m_c0[2] = e3.cross(e1) * sixth;
	t.m_c0[3] = e1.cross(e2) * sixth;
	t.m_c0[0] = -(t.m_c0[1] + t.m_c0[2] + t.m_c0[3]);
	return e1.dot(t.m_c0[1]);
}

/// A rigid body that a soft body can move (dynamic, in or out of a world).
bool isMovable(const btRigidBody* body);
/// Inverse effective mass of a rigid body at offset r (from its centre of mass) along unit direction n
/// (0 when it cannot move).
btScalar rigidInverseMass(const btRigidBody* body, const btVector3& r, const btVector3& n);
/// Moves a dynamic body by the position impulse p (kg m) at offset r over a step dt; its velocities change
/// by velocityShare of the move (btSoftBodySolve.cpp).
void moveRigid(btRigidBody* body, const btVector3& p, const btVector3& r, btScalar dt, btScalar velocityShare = 1);
/// Turns a dynamic body by the angular position impulse l (kg m^2), as moveRigid.
void turnRigid(btRigidBody* body, const btVector3& l, btScalar dt, btScalar velocityShare = 1);

/// The dispatcher's soft-rigid pair (either order): hands the rigid object to the soft body's solver (or
/// its default handler) unless the body disabled collisions with it. Returns the soft body (0 when the
/// pair has none or two) and the rigid object in rigidOut (btSoftRigidCollisionAlgorithm.cpp; also
/// btSoftBodyConcaveCollisionAlgorithm's).
btSoftBody* collideSoftRigidPair(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
                                 btCollisionObject** rigidOut = 0);
/// The soft-rigid contact search of one node set against one rigid object (btSoftBodyCollision.cpp).
void collideSoftWithRigid(btSoftBody& body, const btCollisionObjectWrapper& rigid);
}  // namespace caliber

#endif  // CALIBER_SOFT_BODY_INTERNAL_H
