// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include <limits>

#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "LinearMath/btQuaternion.h"
#include "LinearMath/btWarningHook.h"

TEST(CollisionObject, DefaultsAreBulletsDefaults)
{
	btCollisionObject object;
	EXPECT_TRUE(object.isStaticObject());
	EXPECT_EQ(object.getCollisionFlags(), int(btCollisionObject::CF_STATIC_OBJECT));
	EXPECT_EQ(object.getActivationState(), ACTIVE_TAG);
	EXPECT_EQ(object.getInternalType(), int(btCollisionObject::CO_COLLISION_OBJECT));
	EXPECT_EQ(object.getFriction(), btScalar(0.5));
	EXPECT_EQ(object.getRestitution(), btScalar(0));
	EXPECT_EQ(object.getHitFraction(), btScalar(1));
	EXPECT_EQ(object.getIslandTag(), -1);
	EXPECT_EQ(object.getCompanionId(), -1);
	EXPECT_EQ(object.getWorldArrayIndex(), -1);
	EXPECT_EQ(object.getUserIndex(), -1);
	EXPECT_EQ(object.getUserIndex2(), -1);
	EXPECT_EQ(object.getUserIndex3(), -1);
	EXPECT_EQ(object.getCollisionShape(), nullptr);
	EXPECT_FALSE(object.hasAnisotropicFriction());
	EXPECT_TRUE(object.getWorldTransform().getOrigin().isZero());
}

TEST(CollisionObject, SetActivationStateRespectsDisabledStates)
{
	btCollisionObject object;
	object.setActivationState(WANTS_DEACTIVATION);
	EXPECT_EQ(object.getActivationState(), WANTS_DEACTIVATION);
	object.setActivationState(DISABLE_DEACTIVATION);
	object.setActivationState(ISLAND_SLEEPING);
	EXPECT_EQ(object.getActivationState(), DISABLE_DEACTIVATION) << "DISABLE_DEACTIVATION must stick";
	object.forceActivationState(DISABLE_SIMULATION);
	object.setActivationState(ACTIVE_TAG);
	EXPECT_EQ(object.getActivationState(), DISABLE_SIMULATION) << "DISABLE_SIMULATION must stick";
	object.forceActivationState(ISLAND_SLEEPING);
	EXPECT_EQ(object.getActivationState(), ISLAND_SLEEPING);
}

TEST(CollisionObject, ActivateWakesOnlyDynamicObjectsUnlessForced)
{
	btCollisionObject object;  // static by default
	object.forceActivationState(ISLAND_SLEEPING);
	object.setDeactivationTime(btScalar(3));
	object.activate();
	EXPECT_EQ(object.getActivationState(), ISLAND_SLEEPING);
	EXPECT_EQ(object.getDeactivationTime(), btScalar(3));
	object.activate(true);
	EXPECT_EQ(object.getActivationState(), ACTIVE_TAG);
	EXPECT_EQ(object.getDeactivationTime(), btScalar(0));

	object.setCollisionFlags(btCollisionObject::CF_DYNAMIC_OBJECT);
	object.forceActivationState(ISLAND_SLEEPING);
	object.activate();
	EXPECT_EQ(object.getActivationState(), ACTIVE_TAG);
}

TEST(CollisionObject, IsActiveExcludesSleepingDisabledAndFixedBase)
{
	btCollisionObject object;
	const int states[] = {ACTIVE_TAG,           ISLAND_SLEEPING,    WANTS_DEACTIVATION,
	                      DISABLE_DEACTIVATION, DISABLE_SIMULATION, FIXED_BASE_MULTI_BODY};
	const bool expected[] = {true, false, true, true, false, false};
	for (int i = 0; i < 6; ++i)
	{
		object.forceActivationState(states[i]);
		EXPECT_EQ(object.isActive(), expected[i]) << "state " << states[i];
	}
}

TEST(CollisionObject, FlagQueriesFollowCollisionFlags)
{
	btCollisionObject object;
	object.setCollisionFlags(btCollisionObject::CF_KINEMATIC_OBJECT);
	EXPECT_TRUE(object.isKinematicObject());
	EXPECT_FALSE(object.isStaticObject());
	EXPECT_TRUE(object.isStaticOrKinematicObject());
	EXPECT_FALSE(object.mergesSimulationIslands());
	object.setCollisionFlags(btCollisionObject::CF_DYNAMIC_OBJECT);
	EXPECT_FALSE(object.isStaticOrKinematicObject());
	EXPECT_TRUE(object.hasContactResponse());
	EXPECT_TRUE(object.mergesSimulationIslands());
	object.setCollisionFlags(btCollisionObject::CF_NO_CONTACT_RESPONSE);
	EXPECT_FALSE(object.hasContactResponse());
	EXPECT_FALSE(object.mergesSimulationIslands());
}

TEST(CollisionObject, IgnoreListControlsCheckCollideWith)
{
	btCollisionObject a, b, c;
	EXPECT_TRUE(a.checkCollideWith(&b));
	a.setIgnoreCollisionCheck(&b, true);
	a.setIgnoreCollisionCheck(&b, true);
	EXPECT_EQ(a.getNumObjectsWithoutCollision(), 1);
	EXPECT_EQ(a.getObjectWithoutCollision(0), &b);
	EXPECT_FALSE(a.checkCollideWith(&b));
	EXPECT_TRUE(a.checkCollideWith(&c));
	EXPECT_FALSE(a.checkCollideWithOverride(&b));
	a.setIgnoreCollisionCheck(&b, false);
	EXPECT_TRUE(a.checkCollideWith(&b));
	EXPECT_EQ(a.getNumObjectsWithoutCollision(), 0);
}

TEST(CollisionObject, MaterialAndCcdSettersRoundTrip)
{
	btCollisionObject object;
	const int revision = object.getUpdateRevisionInternal();
	object.setFriction(btScalar(0.7));
	object.setRestitution(btScalar(0.2));
	object.setRollingFriction(btScalar(0.05));
	object.setSpinningFriction(btScalar(0.03));
	EXPECT_GT(object.getUpdateRevisionInternal(), revision);
	EXPECT_EQ(object.getFriction(), btScalar(0.7));
	EXPECT_EQ(object.getRestitution(), btScalar(0.2));
	EXPECT_EQ(object.getRollingFriction(), btScalar(0.05));
	EXPECT_EQ(object.getSpinningFriction(), btScalar(0.03));

	object.setCcdMotionThreshold(btScalar(0.5));
	EXPECT_EQ(object.getCcdSquareMotionThreshold(), btScalar(0.25));
	object.setCcdSweptSphereRadius(btScalar(0.2));
	EXPECT_EQ(object.getCcdSweptSphereRadius(), btScalar(0.2));

	object.setContactStiffnessAndDamping(btScalar(0), btScalar(0.3));
	EXPECT_TRUE(object.getCollisionFlags() & btCollisionObject::CF_HAS_CONTACT_STIFFNESS_DAMPING);
	EXPECT_EQ(object.getContactStiffness(), SIMD_EPSILON) << "zero stiffness is raised to avoid dividing by it";
	EXPECT_EQ(object.getContactDamping(), btScalar(0.3));

	object.setAnisotropicFriction(btVector3(1, 2, 1), btCollisionObject::CF_ANISOTROPIC_ROLLING_FRICTION);
	EXPECT_TRUE(object.hasAnisotropicFriction(btCollisionObject::CF_ANISOTROPIC_ROLLING_FRICTION));
	EXPECT_FALSE(object.hasAnisotropicFriction(btCollisionObject::CF_ANISOTROPIC_FRICTION));
	object.setAnisotropicFriction(btVector3(1, 1, 1));
	EXPECT_FALSE(object.hasAnisotropicFriction(btCollisionObject::CF_ANISOTROPIC_ROLLING_FRICTION));

	btVector3 color;
	EXPECT_FALSE(object.getCustomDebugColor(color));
	object.setCustomDebugColor(btVector3(1, 0, 0));
	ASSERT_TRUE(object.getCustomDebugColor(color));
	EXPECT_EQ(color, btVector3(1, 0, 0));
	object.removeCustomDebugColor();
	EXPECT_FALSE(object.getCustomDebugColor(color));

	btSphereShape sphere(1);
	object.setCollisionShape(&sphere);
	EXPECT_EQ(object.getCollisionShape(), &sphere);
	EXPECT_EQ(object.getRootCollisionShape(), &sphere);
}

TEST(CollisionObject, NonFiniteWorldTransformIsRejected)
{
	btCollisionObject object;
	const btTransform good(btQuaternion(btVector3(0, 1, 0), btScalar(0.3)), btVector3(1, 2, 3));
	object.setWorldTransform(good);
	btTransform bad = good;
	bad.getOrigin().setX(std::numeric_limits<btScalar>::quiet_NaN());
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(object.setWorldTransform(bad), "assertion failed");
#else
	object.setWorldTransform(bad);
	EXPECT_EQ(object.getWorldTransform().getOrigin(), good.getOrigin()) << "release keeps the old transform";
#endif
}

TEST(CollisionObject, NegativeOrNonFiniteMaterialAndCcdValuesAreReportedAndIgnored)
{
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	const btScalar inf = std::numeric_limits<btScalar>::infinity();
	btCollisionObject object;
	object.setFriction(btScalar(0.7));
	object.setRestitution(btScalar(0.2));
	object.setRollingFriction(btScalar(0.05));
	object.setSpinningFriction(btScalar(0.03));
	object.setCcdMotionThreshold(btScalar(0.5));
	object.setCcdSweptSphereRadius(btScalar(0.2));
	object.setContactStiffnessAndDamping(btScalar(1000), btScalar(0.3));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(object.setFriction(-1), "finite and >= 0");
	EXPECT_DEATH(object.setRestitution(nan), "finite and >= 0");
	EXPECT_DEATH(object.setContactStiffnessAndDamping(inf, 0), "non-finite stiffness");
#else
	int warnings = 0;
	btSetWarningHook([](const char*, void* count) { ++*static_cast<int*>(count); }, &warnings);
	object.setFriction(-1);
	object.setFriction(nan);
	object.setRestitution(-btScalar(0.5));
	object.setRestitution(inf);
	object.setRollingFriction(nan);
	object.setSpinningFriction(-inf);
	object.setCcdMotionThreshold(nan);
	object.setCcdSweptSphereRadius(-1);
	object.setContactStiffnessAndDamping(nan, 0);
	object.setContactStiffnessAndDamping(1, -1);
	btSetWarningHook(0, 0);
	EXPECT_EQ(warnings, 10) << "every rejected call is reported once";
#endif
	EXPECT_EQ(object.getFriction(), btScalar(0.7)) << "the last valid values stay";
	EXPECT_EQ(object.getRestitution(), btScalar(0.2));
	EXPECT_EQ(object.getRollingFriction(), btScalar(0.05));
	EXPECT_EQ(object.getSpinningFriction(), btScalar(0.03));
	EXPECT_EQ(object.getCcdMotionThreshold(), btScalar(0.5));
	EXPECT_EQ(object.getCcdSweptSphereRadius(), btScalar(0.2));
	EXPECT_EQ(object.getContactStiffness(), btScalar(1000));
	EXPECT_EQ(object.getContactDamping(), btScalar(0.3));
	object.setRestitution(btScalar(1.5));
	EXPECT_EQ(object.getRestitution(), btScalar(1.5)) << "restitution above 1 (a bumper) is allowed";
}

TEST(CollisionObject, TemporaryShapeLeavesTheRootShapeAndRevisionAlone)
{
	btSphereShape root(1);
	btBoxShape child(btVector3(1, 1, 1));
	btCollisionObject object;
	object.setCollisionShape(&root);
	const int revision = object.getUpdateRevisionInternal();
	object.internalSetTemporaryCollisionShape(&child);
	EXPECT_EQ(object.getCollisionShape(), &child);
	EXPECT_EQ(object.getRootCollisionShape(), &root) << "the root shape is what setCollisionShape gave";
	EXPECT_EQ(object.getUpdateRevisionInternal(), revision) << "a temporary swap is not a shape change";
	object.internalSetTemporaryCollisionShape(&root);
	EXPECT_EQ(object.getCollisionShape(), &root);
}
