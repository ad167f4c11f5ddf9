// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// Every joint kind the format describes, written with its world and read into a fresh world:
// bodies, frames, limits, motors, springs and the common settings come back. Joint data keeps the
// build's precision (float layouts in float builds, the "DoubleData2" layouts in double builds), so
// everything compares exactly.
#include <gtest/gtest.h>

#include "BulletDynamics/ConstraintSolver/btFixedConstraint.h"
#include "BulletDynamics/ConstraintSolver/btGearConstraint.h"
#include "BulletDynamics/ConstraintSolver/btGeneric6DofSpring2Constraint.h"
#include "BulletWorldImporter/btBulletWorldImporter.h"
#include "Serialize/SerializeTestUtil.h"

using caliber_test::TestWorld;
using caliber_test::WarningLog;

namespace
{
const btScalar kHingeTolerance = 0;

void expectSameTransform(const btTransform& a, const btTransform& b)
{
	for (int i = 0; i < 3; ++i)
	{
		EXPECT_EQ(a.getOrigin()[i], b.getOrigin()[i]);
		for (int k = 0; k < 3; ++k) EXPECT_EQ(a.getBasis()[i][k], b.getBasis()[i][k]);
	}
}

// A world with two boxes to join, a third body, and the loaded copy.
struct JointScene
{
	TestWorld original;
	btRigidBody* a;
	btRigidBody* b;
	JointScene()
	{
		btCollisionShape* box = original.shape(new btBoxShape(btVector3(0.5, 0.5, 0.5)));
		a = original.body(box, 1, btVector3(0, 2, 0));
		b = original.body(box, 2, btVector3(1, 2, 0));
	}
	const btTransform frameA() const
	{
		return btTransform(btQuaternion(btVector3(0, 1, 0), 0.3), btVector3(0.5, 0, 0));
	}
	const btTransform frameB() const
	{
		return btTransform(btQuaternion(btVector3(1, 0, 0), -0.2), btVector3(-0.5, 0, 0));
	}
};

// Saves scene.original (with joint named "joint"), loads it into loaded, returns the loaded joint.
template <class J>
J* roundTrip(JointScene& scene, J* joint, TestWorld& loaded, btBulletWorldImporter& importer)
{
	joint->setBreakingImpulseThreshold(123);
	joint->setOverrideNumSolverIterations(17);
	joint->setDbgDrawSize(0.5);
	joint->enableFeedback(true);
	joint->setUserConstraintType(7);
	btDefaultSerializer s;
	s.registerNameForPointer(joint, "joint");
	const std::vector<char> file = scene.original.save(&s);
	EXPECT_TRUE(importer.loadFileFromMemory(const_cast<char*>(file.data()), int(file.size())));
	EXPECT_EQ(importer.getNumRigidBodies(), 2);
	EXPECT_EQ(importer.getNumConstraints(), 1);
	btTypedConstraint* read = importer.getConstraintByName("joint");
	EXPECT_NE(read, nullptr);
	if (!read) return nullptr;
	EXPECT_EQ(read->getConstraintType(), joint->getConstraintType());
	EXPECT_EQ(read->getBreakingImpulseThreshold(), 123);
	EXPECT_EQ(read->getOverrideNumSolverIterations(), 17);
	EXPECT_EQ(read->getDbgDrawSize(), btScalar(0.5));
	EXPECT_TRUE(read->needsFeedback());
	EXPECT_EQ(read->getUserConstraintType(), 7);
	EXPECT_EQ(loaded.world.getNumConstraints(), 1);
	// The joined bodies are the loaded copies of the original bodies.
	EXPECT_EQ(&read->getRigidBodyA(), importer.getRigidBodyByIndex(0));
	EXPECT_EQ(&read->getRigidBodyB(), importer.getRigidBodyByIndex(1));
	return static_cast<J*>(read);
}

struct Loaded
{
	TestWorld world;
	btBulletWorldImporter importer{&world.world};
	~Loaded() { importer.deleteAllData(); }
};
}  // namespace

TEST(JointRoundTrip, PointToPointKeepsPivots)
{
	JointScene scene;
	auto* j = scene.original.joint(
	    new btPoint2PointConstraint(*scene.a, *scene.b, btVector3(0.5, 0, 0), btVector3(-0.5, 0.1, 0)));
	Loaded loaded;
	auto* r = roundTrip(scene, j, loaded.world, loaded.importer);
	ASSERT_TRUE(r);
	for (int i = 0; i < 3; ++i)
	{
		EXPECT_EQ(r->getPivotInA()[i], j->getPivotInA()[i]);
		EXPECT_EQ(r->getPivotInB()[i], j->getPivotInB()[i]);
	}
}

TEST(JointRoundTrip, HingeKeepsFramesLimitsAndMotor)
{
	JointScene scene;
	auto* j =
	    scene.original.joint(new btHingeConstraint(*scene.a, *scene.b, scene.frameA(), scene.frameB(), true), true);
	j->setLimit(-0.5, 0.75, 0.8, 0.25, 0.9);
	j->enableAngularMotor(true, 1.5, 3.0);
	j->setAngularOnly(true);
	Loaded loaded;
	auto* r = roundTrip(scene, j, loaded.world, loaded.importer);
	ASSERT_TRUE(r);
	expectSameTransform(r->getAFrame(), j->getAFrame());
	expectSameTransform(r->getBFrame(), j->getBFrame());
	EXPECT_NEAR(r->getLowerLimit(), j->getLowerLimit(), kHingeTolerance);
	EXPECT_NEAR(r->getUpperLimit(), j->getUpperLimit(), kHingeTolerance);
	EXPECT_NEAR(r->getLimitSoftness(), j->getLimitSoftness(), kHingeTolerance);
	EXPECT_NEAR(r->getLimitBiasFactor(), j->getLimitBiasFactor(), kHingeTolerance);
	EXPECT_NEAR(r->getLimitRelaxationFactor(), j->getLimitRelaxationFactor(), kHingeTolerance);
	EXPECT_TRUE(r->getEnableAngularMotor());
	EXPECT_NEAR(r->getMotorTargetVelocity(), 1.5, kHingeTolerance);
	EXPECT_NEAR(r->getMaxMotorImpulse(), 3.0, kHingeTolerance);
	EXPECT_TRUE(r->getAngularOnly());
	EXPECT_TRUE(r->getUseReferenceFrameA());
	// "No collision between the joined bodies" survives: the loaded bodies list the joint.
	EXPECT_EQ(r->getRigidBodyA().getNumConstraintRefs(), 1);
}

TEST(JointRoundTrip, ConeTwistKeepsFramesSpansAndDamping)
{
	JointScene scene;
	auto* j = scene.original.joint(new btConeTwistConstraint(*scene.a, *scene.b, scene.frameA(), scene.frameB()));
	j->setLimit(0.6, 0.4, 0.3, 0.9, 0.2, 0.8);
	j->setDamping(0.05);
	Loaded loaded;
	auto* r = roundTrip(scene, j, loaded.world, loaded.importer);
	ASSERT_TRUE(r);
	expectSameTransform(r->getAFrame(), j->getAFrame());
	expectSameTransform(r->getBFrame(), j->getBFrame());
	EXPECT_EQ(r->getSwingSpan1(), j->getSwingSpan1());
	EXPECT_EQ(r->getSwingSpan2(), j->getSwingSpan2());
	EXPECT_EQ(r->getTwistSpan(), j->getTwistSpan());
}

TEST(JointRoundTrip, SliderKeepsFramesAndLimits)
{
	JointScene scene;
	auto* j = scene.original.joint(new btSliderConstraint(*scene.a, *scene.b, scene.frameA(), scene.frameB(), false));
	j->setLowerLinLimit(-1);
	j->setUpperLinLimit(2);
	j->setLowerAngLimit(-0.5);
	j->setUpperAngLimit(0.25);
	Loaded loaded;
	auto* r = roundTrip(scene, j, loaded.world, loaded.importer);
	ASSERT_TRUE(r);
	expectSameTransform(r->getFrameOffsetA(), j->getFrameOffsetA());
	expectSameTransform(r->getFrameOffsetB(), j->getFrameOffsetB());
	EXPECT_EQ(r->getLowerLinLimit(), -1);
	EXPECT_EQ(r->getUpperLinLimit(), 2);
	EXPECT_EQ(r->getLowerAngLimit(), j->getLowerAngLimit());
	EXPECT_EQ(r->getUpperAngLimit(), j->getUpperAngLimit());
	EXPECT_EQ(r->getUseLinearReferenceFrameA(), j->getUseLinearReferenceFrameA());
}

TEST(JointRoundTrip, Generic6DofKeepsFramesAndLimits)
{
	JointScene scene;
	auto* j =
	    scene.original.joint(new btGeneric6DofConstraint(*scene.a, *scene.b, scene.frameA(), scene.frameB(), true));
	j->setLinearLowerLimit(btVector3(-1, -2, -3));
	j->setLinearUpperLimit(btVector3(1, 2, 3));
	j->setAngularLowerLimit(btVector3(-0.1, -0.2, -0.3));
	j->setAngularUpperLimit(btVector3(0.1, 0.2, 0.3));
	Loaded loaded;
	auto* r = roundTrip(scene, j, loaded.world, loaded.importer);
	ASSERT_TRUE(r);
	expectSameTransform(r->getFrameOffsetA(), j->getFrameOffsetA());
	expectSameTransform(r->getFrameOffsetB(), j->getFrameOffsetB());
	btVector3 lo, hi, rlo, rhi;
	j->getLinearLowerLimit(lo);
	r->getLinearLowerLimit(rlo);
	j->getAngularUpperLimit(hi);
	r->getAngularUpperLimit(rhi);
	for (int i = 0; i < 3; ++i)
	{
		EXPECT_EQ(rlo[i], lo[i]);
		EXPECT_EQ(rhi[i], hi[i]);
	}
}

TEST(JointRoundTrip, Generic6DofSpringKeepsSprings)
{
	JointScene scene;
	auto* j = scene.original.joint(
	    new btGeneric6DofSpringConstraint(*scene.a, *scene.b, scene.frameA(), scene.frameB(), true));
	for (int i = 0; i < 6; ++i)
	{
		j->enableSpring(i, i % 2 == 0);
		j->setStiffness(i, btScalar(10 + i));
		j->setDamping(i, btScalar(0.1 * (i + 1)));
		j->setEquilibriumPoint(i, btScalar(0.01 * i));
	}
	Loaded loaded;
	auto* r = roundTrip(scene, j, loaded.world, loaded.importer);
	ASSERT_TRUE(r);
	for (int i = 0; i < 6; ++i)
	{
		EXPECT_EQ(r->isSpringEnabled(i), j->isSpringEnabled(i)) << i;
		EXPECT_EQ(r->getStiffness(i), j->getStiffness(i)) << i;
		EXPECT_EQ(r->getDamping(i), j->getDamping(i)) << i;
		EXPECT_EQ(r->getEquilibriumPoint(i), j->getEquilibriumPoint(i)) << i;
	}
}

TEST(JointRoundTrip, Spring2KeepsEveryMotorAndSpringSetting)
{
	JointScene scene;
	auto* j = scene.original.joint(
	    new btGeneric6DofSpring2Constraint(*scene.a, *scene.b, scene.frameA(), scene.frameB(), RO_ZYX));
	j->setLinearLowerLimit(btVector3(-1, 0, 0));
	j->setLinearUpperLimit(btVector3(1, 0, 0));
	j->setAngularLowerLimit(btVector3(-0.5, 0, 0));
	j->setAngularUpperLimit(btVector3(0.5, 0, 0));
	j->enableMotor(3, true);
	j->setTargetVelocity(3, 2.0);
	j->setMaxMotorForce(3, 4.0);
	j->enableSpring(0, true);
	j->setStiffness(0, 50);
	j->setDamping(0, 0.5);
	j->setBounce(1, 0.3);
	Loaded loaded;
	auto* r = roundTrip(scene, j, loaded.world, loaded.importer);
	ASSERT_TRUE(r);
	EXPECT_EQ(r->getRotationOrder(), RO_ZYX);
	expectSameTransform(r->getFrameOffsetA(), j->getFrameOffsetA());
	const btRotationalLimitMotor2* m = r->getRotationalLimitMotor(0);
	const btRotationalLimitMotor2* o = j->getRotationalLimitMotor(0);
	EXPECT_EQ(m->m_enableMotor, o->m_enableMotor);
	EXPECT_EQ(m->m_targetVelocity, o->m_targetVelocity);
	EXPECT_EQ(m->m_maxMotorForce, o->m_maxMotorForce);
	EXPECT_EQ(m->m_loLimit, o->m_loLimit);
	EXPECT_EQ(m->m_hiLimit, o->m_hiLimit);
	const btTranslationalLimitMotor2* lm = r->getTranslationalLimitMotor();
	const btTranslationalLimitMotor2* lo = j->getTranslationalLimitMotor();
	for (int i = 0; i < 3; ++i)
	{
		EXPECT_EQ(lm->m_enableSpring[i], lo->m_enableSpring[i]);
		EXPECT_EQ(lm->m_springStiffness[i], lo->m_springStiffness[i]);
		EXPECT_EQ(lm->m_springDamping[i], lo->m_springDamping[i]);
		EXPECT_EQ(lm->m_bounce[i], lo->m_bounce[i]);
		EXPECT_EQ(lm->m_lowerLimit[i], lo->m_lowerLimit[i]);
		EXPECT_EQ(lm->m_upperLimit[i], lo->m_upperLimit[i]);
	}
}

TEST(JointRoundTrip, GearKeepsAxesAndRatio)
{
	JointScene scene;
	auto* j =
	    scene.original.joint(new btGearConstraint(*scene.a, *scene.b, btVector3(0, 1, 0), btVector3(1, 0, 0), 2.5));
	Loaded loaded;
	auto* r = roundTrip(scene, j, loaded.world, loaded.importer);
	ASSERT_TRUE(r);
	EXPECT_EQ(r->getRatio(), 2.5);
	for (int i = 0; i < 3; ++i)
	{
		EXPECT_EQ(r->getAxisA()[i], j->getAxisA()[i]);
		EXPECT_EQ(r->getAxisB()[i], j->getAxisB()[i]);
	}
}

TEST(JointRoundTrip, FixedJointLoadsAsALockedSpring2)
{
	JointScene scene;
	auto* j = scene.original.joint(new btFixedConstraint(*scene.a, *scene.b, scene.frameA(), scene.frameB()));
	Loaded loaded;
	btDefaultSerializer s;
	const std::vector<char> file = scene.original.save(&s);
	ASSERT_TRUE(loaded.importer.loadFileFromMemory(const_cast<char*>(file.data()), int(file.size())));
	ASSERT_EQ(loaded.importer.getNumConstraints(), 1);
	btGeneric6DofSpring2Constraint* r =
	    static_cast<btGeneric6DofSpring2Constraint*>(loaded.importer.getConstraintByIndex(0));
	for (int i = 0; i < 3; ++i)
	{
		EXPECT_EQ(r->getTranslationalLimitMotor()->m_lowerLimit[i], j->getTranslationalLimitMotor()->m_lowerLimit[i]);
		EXPECT_EQ(r->getTranslationalLimitMotor()->m_upperLimit[i], j->getTranslationalLimitMotor()->m_upperLimit[i]);
		EXPECT_EQ(r->getRotationalLimitMotor(i)->m_loLimit, j->getRotationalLimitMotor(i)->m_loLimit);
	}
}

TEST(JointRoundTrip, JointToTheWorldKeepsItsSingleBody)
{
	TestWorld original;
	btRigidBody* body = original.body(original.shape(new btSphereShape(0.5)), 1, btVector3(0, 3, 0));
	original.joint(new btPoint2PointConstraint(*body, btVector3(0, 1, 0)));
	const std::vector<char> file = original.save();
	Loaded loaded;
	ASSERT_TRUE(loaded.importer.loadFileFromMemory(const_cast<char*>(file.data()), int(file.size())));
	ASSERT_EQ(loaded.importer.getNumConstraints(), 1);
	btTypedConstraint* r = loaded.importer.getConstraintByIndex(0);
	EXPECT_EQ(&r->getRigidBodyA(), loaded.importer.getRigidBodyByIndex(0));
	EXPECT_EQ(&r->getRigidBodyB(), &btTypedConstraint::getFixedBody());
}
