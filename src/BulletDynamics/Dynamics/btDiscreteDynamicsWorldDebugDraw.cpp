// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Debug drawing of joints: frames (DBG_DrawConstraints) and limits (DBG_DrawConstraintLimits).
#include "BulletDynamics/ConstraintSolver/btPoint2PointConstraint.h"
#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h"
#include "LinearMath/btIDebugDraw.h"

void btDiscreteDynamicsWorld::debugDrawConstraint(btTypedConstraint* constraint)
{
	btIDebugDraw* drawer = getDebugDrawer();
	if (!drawer || !constraint) return;
	const int mode = drawer->getDebugMode();
	const bool drawFrames = (mode & btIDebugDraw::DBG_DrawConstraints) != 0;
	const btScalar size = constraint->getDbgDrawSize();
	if (size <= btScalar(0) || !drawFrames) return;
	switch (constraint->getConstraintType())
	{
		case POINT2POINT_CONSTRAINT_TYPE:
		{
			btPoint2PointConstraint* p2p = static_cast<btPoint2PointConstraint*>(constraint);
			btTransform pivot;
			pivot.setIdentity();
			pivot.setOrigin(p2p->getRigidBodyA().getCenterOfMassTransform()(p2p->getPivotInA()));
			drawer->drawTransform(pivot, size);
			pivot.setOrigin(p2p->getRigidBodyB().getCenterOfMassTransform()(p2p->getPivotInB()));
			drawer->drawTransform(pivot, size);
			break;
		}
		default:
			break;
	}
}
