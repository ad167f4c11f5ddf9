// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Debug drawing of joints: frames (DBG_DrawConstraints) and limits (DBG_DrawConstraintLimits).
#include "BulletDynamics/ConstraintSolver/btConeTwistConstraint.h"
#include "BulletDynamics/ConstraintSolver/btGearConstraint.h"
#include "BulletDynamics/ConstraintSolver/btGeneric6DofConstraint.h"
#include "BulletDynamics/ConstraintSolver/btGeneric6DofSpring2Constraint.h"
#include "BulletDynamics/ConstraintSolver/btHingeConstraint.h"
#include "BulletDynamics/ConstraintSolver/btPoint2PointConstraint.h"
#include "BulletDynamics/ConstraintSolver/btSliderConstraint.h"
#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h"
#include "LinearMath/btIDebugDraw.h"

namespace
{
const btVector3 kLimitColor(0, 0, 0);

void drawFrames(btIDebugDraw* drawer, const btTransform& a, const btTransform& b, btScalar size)
{
	drawer->drawTransform(a, size);
	drawer->drawTransform(b, size);
}

// The two 6-DoF families share their drawing: both frames, and the box the linear limits allow (free
// axes drawn as the frame size).
template <class SixDof>
void drawSixDof(btIDebugDraw* drawer, SixDof* d6, btScalar size, bool drawFramesToo, bool drawLimits)
{
	d6->calculateTransforms();
	const btTransform& frameA = d6->getCalculatedTransformA();
	if (drawFramesToo) drawFrames(drawer, frameA, d6->getCalculatedTransformB(), size);
	if (!drawLimits) return;
	btVector3 low, high;
	d6->getLinearLowerLimit(low);
	d6->getLinearUpperLimit(high);
	for (int k = 0; k < 3; ++k)
		if (low[k] > high[k])
		{
			low[k] = -size;
			high[k] = size;
		}
	drawer->drawBox(low, high, frameA, kLimitColor);
}
}  // namespace

void btDiscreteDynamicsWorld::debugDrawConstraint(btTypedConstraint* constraint)
{
	btIDebugDraw* drawer = getDebugDrawer();
	if (!drawer || !constraint) return;
	const int mode = drawer->getDebugMode();
	const bool drawFramesToo = (mode & btIDebugDraw::DBG_DrawConstraints) != 0;
	const bool drawLimits = (mode & btIDebugDraw::DBG_DrawConstraintLimits) != 0;
	const btScalar size = constraint->getDbgDrawSize();
	if (size <= btScalar(0)) return;
	const btTransform& bodyA = constraint->getRigidBodyA().getCenterOfMassTransform();
	const btTransform& bodyB = constraint->getRigidBodyB().getCenterOfMassTransform();
	switch (constraint->getConstraintType())
	{
		case POINT2POINT_CONSTRAINT_TYPE:
		{
			btPoint2PointConstraint* p2p = dynamic_cast<btPoint2PointConstraint*>(constraint);
			if (!p2p) goto bodiesOnly;  // a user joint that borrows the tag
			btTransform pivotA(btQuaternion::getIdentity(), bodyA(p2p->getPivotInA()));
			btTransform pivotB(btQuaternion::getIdentity(), bodyB(p2p->getPivotInB()));
			if (drawFramesToo) drawFrames(drawer, pivotA, pivotB, size);
			break;
		}
		case HINGE_CONSTRAINT_TYPE:
		{
			btHingeConstraint* hinge = dynamic_cast<btHingeConstraint*>(constraint);
			if (!hinge) goto bodiesOnly;  // a user joint that borrows the tag
			const btTransform frameA = bodyA * hinge->getAFrame();
			if (drawFramesToo) drawFrames(drawer, frameA, bodyB * hinge->getBFrame(), size);
			if (drawLimits && hinge->hasLimit())
			{
				// The allowed arc, in the plane of the hinge, measured from A's frame X axis.
				const btVector3 axis = frameA.getBasis().getColumn(2);
				const btVector3 start = frameA.getBasis().getColumn(0);
				drawer->drawArc(frameA.getOrigin(), axis, start, size, size, hinge->getLowerLimit(),
				                hinge->getUpperLimit(), kLimitColor, true);
			}
			break;
		}
		case CONETWIST_CONSTRAINT_TYPE:
		{
			btConeTwistConstraint* cone = dynamic_cast<btConeTwistConstraint*>(constraint);
			if (!cone) goto bodiesOnly;  // a user joint that borrows the tag
			const btTransform frameA = bodyA * cone->getAFrame();
			if (drawFramesToo) drawFrames(drawer, frameA, bodyB * cone->getBFrame(), size);
			if (drawLimits && cone->getSwingSpan1() < SIMD_PI && cone->getSwingSpan2() < SIMD_PI)
			{
				// The cone's rim as a ring of segments, with spokes to the apex.
				const int segments = 32;
				btVector3 previous = frameA(cone->GetPointForAngle(0, size));
				for (int i = 1; i <= segments; ++i)
				{
					const btScalar angle = SIMD_2_PI * btScalar(i) / btScalar(segments);
					const btVector3 point = frameA(cone->GetPointForAngle(angle, size));
					drawer->drawLine(previous, point, kLimitColor);
					if (i % (segments / 4) == 0) drawer->drawLine(frameA.getOrigin(), point, kLimitColor);
					previous = point;
				}
			}
			break;
		}
		case SLIDER_CONSTRAINT_TYPE:
		{
			btSliderConstraint* slider = dynamic_cast<btSliderConstraint*>(constraint);
			if (!slider) goto bodiesOnly;  // a user joint that borrows the tag
			const btTransform& frameA = slider->getCalculatedTransformA();
			if (drawFramesToo) drawFrames(drawer, frameA, slider->getCalculatedTransformB(), size);
			if (drawLimits && slider->getLowerLinLimit() <= slider->getUpperLinLimit())
			{
				// The travel allowed along the axis.
				const btVector3 axis = frameA.getBasis().getColumn(0);
				drawer->drawLine(frameA.getOrigin() + axis * slider->getLowerLinLimit(),
				                 frameA.getOrigin() + axis * slider->getUpperLinLimit(), kLimitColor);
			}
			break;
		}
		case D6_CONSTRAINT_TYPE:
		case D6_SPRING_CONSTRAINT_TYPE:
			if (btGeneric6DofConstraint* sixDof = dynamic_cast<btGeneric6DofConstraint*>(constraint))
			{
				drawSixDof(drawer, sixDof, size, drawFramesToo, drawLimits);
				break;
			}
			goto bodiesOnly;
		case D6_SPRING_2_CONSTRAINT_TYPE:
			// Also btHinge2Constraint and btFixedConstraint.
			if (btGeneric6DofSpring2Constraint* spring2 = dynamic_cast<btGeneric6DofSpring2Constraint*>(constraint))
			{
				drawSixDof(drawer, spring2, size, drawFramesToo, drawLimits);
				break;
			}
			goto bodiesOnly;
		default:
		bodiesOnly:
			// Other joints: the two bodies' centres, linked.
			if (drawFramesToo) drawer->drawLine(bodyA.getOrigin(), bodyB.getOrigin(), btVector3(1, 1, 0));
			break;
	}
}
