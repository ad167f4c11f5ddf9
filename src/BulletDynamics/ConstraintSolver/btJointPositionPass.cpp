// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/ConstraintSolver/btJointPositionPass.h"

#include "BulletDynamics/ConstraintSolver/btConeTwistConstraint.h"
#include "BulletDynamics/ConstraintSolver/btHingeConstraint.h"
#include "BulletDynamics/ConstraintSolver/btPoint2PointConstraint.h"

#include <typeinfo>

namespace
{
// joint as a Joint (Caliber's own class or a subclass of it), or 0. The type tag alone is not enough:
// a user's joint written straight on btTypedConstraint may borrow a tag (Bullet's tests and examples do),
// and must then be left alone. The exact type is compared first, which is cheap; only other classes pay
// for the dynamic cast.
template <class Joint>
const Joint* asJoint(const btTypedConstraint& joint)
{
	if (typeid(joint) == typeid(Joint)) return static_cast<const Joint*>(&joint);
	return dynamic_cast<const Joint*>(&joint);
}

// The anchors of a joint placed by two frames (hinge, cone-twist): their origins. None when the joint
// is not really a Joint, or holds angles only.
template <class Joint>
bool frameAnchors(const btTypedConstraint& joint, btVector3& anchorInA, btVector3& anchorInB)
{
	const Joint* framed = asJoint<Joint>(joint);
	if (!framed || framed->getAngularOnly()) return false;
	anchorInA = framed->getAFrame().getOrigin();
	anchorInB = framed->getBFrame().getOrigin();
	return true;
}
}  // namespace

namespace caliber
{
bool correctsPosition(const btTypedConstraint& joint)
{
	switch (joint.getConstraintType())
	{
		case POINT2POINT_CONSTRAINT_TYPE:
			return asJoint<btPoint2PointConstraint>(joint) != 0;
		case HINGE_CONSTRAINT_TYPE:
			return asJoint<btHingeConstraint>(joint) != 0;
		case CONETWIST_CONSTRAINT_TYPE:
			return asJoint<btConeTwistConstraint>(joint) != 0;
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
			const btPoint2PointConstraint* ball = asJoint<btPoint2PointConstraint>(joint);
			if (!ball) return false;
			anchorInA = ball->getPivotInA();
			anchorInB = ball->getPivotInB();
			return true;
		}
		case HINGE_CONSTRAINT_TYPE:
			return frameAnchors<btHingeConstraint>(joint, anchorInA, anchorInB);
		case CONETWIST_CONSTRAINT_TYPE:
			return frameAnchors<btConeTwistConstraint>(joint, anchorInA, anchorInB);
		default:
			return false;
	}
}
}  // namespace caliber
