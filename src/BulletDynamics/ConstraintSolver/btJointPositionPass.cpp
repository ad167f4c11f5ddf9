// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/ConstraintSolver/btJointPositionPass.h"

#include "BulletDynamics/ConstraintSolver/btConeTwistConstraint.h"
#include "BulletDynamics/ConstraintSolver/btHingeConstraint.h"
#include "BulletDynamics/ConstraintSolver/btPoint2PointConstraint.h"

namespace caliber
{
bool correctsPosition(const btTypedConstraint& joint)
{
	switch (joint.getConstraintType())
	{
		case POINT2POINT_CONSTRAINT_TYPE:
		case HINGE_CONSTRAINT_TYPE:
		case CONETWIST_CONSTRAINT_TYPE:
			return true;
		default:
			return false;
	}
}

bool jointAnchors(const btTypedConstraint& joint, btVector3& anchorInA, btVector3& anchorInB)
{
	switch (joint.getConstraintType())
	{
		case POINT2POINT_CONSTRAINT_TYPE:
		{
			const btPoint2PointConstraint& ball = static_cast<const btPoint2PointConstraint&>(joint);
			anchorInA = ball.getPivotInA();
			anchorInB = ball.getPivotInB();
			return true;
		}
		case HINGE_CONSTRAINT_TYPE:
		{
			const btHingeConstraint& hinge = static_cast<const btHingeConstraint&>(joint);
			if (hinge.getAngularOnly()) return false;
			anchorInA = hinge.getAFrame().getOrigin();
			anchorInB = hinge.getBFrame().getOrigin();
			return true;
		}
		case CONETWIST_CONSTRAINT_TYPE:
		{
			const btConeTwistConstraint& cone = static_cast<const btConeTwistConstraint&>(joint);
			if (cone.getAngularOnly()) return false;
			anchorInA = cone.getAFrame().getOrigin();
			anchorInB = cone.getBFrame().getOrigin();
			return true;
		}
		default:
			return false;
	}
}
}  // namespace caliber
