// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// debugDrawWorld draws joints' frames and limits only when the drawer asks for them.

#include <gtest/gtest.h>

#include "JointTestUtil.h"

using caliber_test::TestWorld;

namespace
{
class LineCounter : public btIDebugDraw
{
public:
	int m_lines = 0;
	int m_mode = 0;
	void drawLine(const btVector3&, const btVector3&, const btVector3&) override { ++m_lines; }
	void drawContactPoint(const btVector3&, const btVector3&, btScalar, int, const btVector3&) override {}
	void reportErrorWarning(const char*) override {}
	void draw3dText(const btVector3&, const char*) override {}
	void setDebugMode(int mode) override { m_mode = mode; }
	int getDebugMode() const override { return m_mode; }
};

int linesDrawn(TestWorld& w, int mode)
{
	LineCounter drawer;
	drawer.setDebugMode(mode);
	w.world()->setDebugDrawer(&drawer);
	w.world()->debugDrawWorld();
	w.world()->setDebugDrawer(0);
	return drawer.m_lines;
}
}  // namespace

TEST(ConstraintDebugDraw, FramesAndLimitsAreDrawnOnRequestOnly)
{
	TestWorld w(btVector3(0, 0, 0));
	btCollisionShape* ball = w.shape<btSphereShape>(btScalar(0.2));
	btRigidBody* a = w.addBody(ball, 1, btVector3(0, 0, 0));
	btRigidBody* b = w.addBody(ball, 1, btVector3(3, 0, 0));
	btRigidBody* c = w.addBody(ball, 1, btVector3(6, 0, 0));
	w.addJoint<btPoint2PointConstraint>(false, *a, btVector3(0, 1, 0));
	btHingeConstraint* hinge = w.addJoint<btHingeConstraint>(false, *b, btVector3(0, 1, 0), btVector3(0, 0, 1));
	btConeTwistConstraint* cone = w.addJoint<btConeTwistConstraint>(false, *c, btTransform::getIdentity());
	EXPECT_EQ(linesDrawn(w, 0), 0);
	const int frames = linesDrawn(w, btIDebugDraw::DBG_DrawConstraints);
	EXPECT_EQ(frames, 3 * 2 * 3) << "two frames of three axes per joint";
	EXPECT_EQ(linesDrawn(w, btIDebugDraw::DBG_DrawConstraintLimits), 0) << "no limits set yet";
	cone->setLimit(btScalar(0.5), btScalar(0.5), btScalar(0.5));
	EXPECT_EQ(linesDrawn(w, btIDebugDraw::DBG_DrawConstraintLimits), 32 + 4) << "the cone's rim and spokes";
	hinge->setLimit(-1, 1);
	EXPECT_GT(linesDrawn(w, btIDebugDraw::DBG_DrawConstraintLimits), 36) << "now the hinge's arc too";
}

TEST(ConstraintDebugDraw, SixDofDrawsItsFramesAndItsLinearLimitBox)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* a = w.addBody(w.shape<btSphereShape>(btScalar(0.2)), 1, btVector3(0, 0, 0));
	w.addJoint<btGeneric6DofConstraint>(false, *a, btTransform::getIdentity(), true);
	EXPECT_EQ(linesDrawn(w, btIDebugDraw::DBG_DrawConstraints), 2 * 3);
	EXPECT_EQ(linesDrawn(w, btIDebugDraw::DBG_DrawConstraintLimits), 12) << "the edges of one box";
}

TEST(ConstraintDebugDraw, SixDofSpring2DrawsItsFramesAndItsLinearLimitBox)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* a = w.addBody(w.shape<btSphereShape>(btScalar(0.2)), 1, btVector3(0, 0, 0));
	w.addJoint<btGeneric6DofSpring2Constraint>(false, *a, btTransform::getIdentity());
	EXPECT_EQ(linesDrawn(w, btIDebugDraw::DBG_DrawConstraints), 2 * 3);
	EXPECT_EQ(linesDrawn(w, btIDebugDraw::DBG_DrawConstraintLimits), 12) << "the edges of one box";
}

namespace
{
// A joint written straight on btTypedConstraint that borrows Bullet's ball-joint tag, as Bullet's own
// examples of user joints do; it has no rows of its own.
class TaggedUserJoint : public btTypedConstraint
{
public:
	TaggedUserJoint(btRigidBody& a, btRigidBody& b) : btTypedConstraint(POINT2POINT_CONSTRAINT_TYPE, a, b) {}
	void getInfo1(btConstraintInfo1* info) override
	{
		info->m_numConstraintRows = 0;
		info->nub = 0;
	}
	void getInfo2(btConstraintInfo2*) override {}
	void setParam(int, btScalar, int) override {}
	btScalar getParam(int, int) const override { return 0; }
};
}  // namespace

TEST(ConstraintDebugDraw, UserJointThatBorrowsATagIsDrawnAsALinkNotReadAsThatJoint)
{
	// Drawing (and the joint position correction) must not read such a joint as a btPoint2PointConstraint:
	// that would be undefined behaviour (the sanitizer build checks). It is drawn as a link between the
	// bodies' centres, the stepping leaves it alone.
	TestWorld w(btVector3(0, -10, 0));
	btCollisionShape* ball = w.shape<btSphereShape>(btScalar(0.2));
	btRigidBody* a = w.addBody(ball, 1, btVector3(0, 0, 0));
	btRigidBody* b = w.addBody(ball, 1, btVector3(3, 0, 0));
	w.addJoint<TaggedUserJoint>(false, *a, *b);
	EXPECT_EQ(linesDrawn(w, btIDebugDraw::DBG_DrawConstraints), 1);
	w.run(10);
	EXPECT_NEAR(a->getCenterOfMassPosition().x(), 0, 1e-5) << "no correction pulled the bodies together";
	EXPECT_NEAR(b->getCenterOfMassPosition().x(), 3, 1e-5);
}
