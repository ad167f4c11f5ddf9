// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// Clauses of the format that the round-trip tests do not pin on their own (docs/serialization.md):
// every class's serialize() names Bullet's struct for it and calculateSerializeBufferSize() is that
// struct's size; shapes without a layout of their own are written with their base struct and skipped on
// reading; universal and hinge2 joints load as the 6-DoF and spring2 joints they are in Bullet; files of
// other Bullet 2.8x / 3.x versions load; the pre-2.82 double layouts of the hinge and point-to-point
// joints load.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "BulletCollision/CollisionShapes/btConvexPointCloudShape.h"
#include "BulletCollision/CollisionShapes/btEmptyShape.h"
#include "BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h"
#include "BulletCollision/CollisionShapes/btMinkowskiSumShape.h"
#include "BulletCollision/CollisionShapes/btMultiSphereShape.h"
#include "BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btTriangleShape.h"
#include "BulletCollision/CollisionShapes/btUniformScalingShape.h"
#include "BulletDynamics/ConstraintSolver/btGearConstraint.h"
#include "BulletDynamics/ConstraintSolver/btGeneric6DofSpring2Constraint.h"
#include "BulletDynamics/ConstraintSolver/btHinge2Constraint.h"
#include "BulletDynamics/ConstraintSolver/btUniversalConstraint.h"
#include "BulletWorldImporter/btBulletWorldImporter.h"
#include "Serialize/SerializeTestUtil.h"

using caliber_test::TestWorld;
using caliber_test::WarningLog;

namespace
{
#ifdef BT_USE_DOUBLE_PRECISION
const bool kDouble = true;
#else
const bool kDouble = false;
#endif

// Serializes obj into a block of calculateSerializeBufferSize() bytes; the struct name serialize() gives.
template <class T>
std::string serializeInto(const T& obj, int& size)
{
	btDefaultSerializer s;
	s.startSerialization();
	size = obj.calculateSerializeBufferSize();
	std::vector<double> block(size_t(size) / sizeof(double) + 1, 0.0);  // double-aligned
	const char* type = obj.serialize(block.data(), &s);
	s.finishSerialization();
	return type ? type : "";
}

template <class T>
void expectLayout(const T& obj, const char* structName, size_t structSize, const char* what)
{
	int size = 0;
	EXPECT_EQ(serializeInto(obj, size), structName) << what;
	EXPECT_EQ(size_t(size), structSize) << what;
}

// A transform in the double layout whatever the build's precision.
void writeDouble(const btTransform& t, btTransformDoubleData& d)
{
	for (int r = 0; r < 3; ++r) t.getBasis()[r].serializeDouble(d.m_basis.m_el[r]);
	t.getOrigin().serializeDouble(d.m_origin);
}

// The header's version digits (bytes 9 to 11).
void setVersion(std::vector<char>& file, const char* digits)
{
	ASSERT_GT(file.size(), size_t(BT_HEADER_LENGTH));
	for (int k = 0; k < 3; ++k) file[size_t(9 + k)] = digits[k];
}

// A two-triangle mesh, owned with its arrays.
struct Mesh
{
	btScalar vertices[12] = {0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 1};
	int indices[6] = {0, 1, 2, 1, 3, 2};
	btTriangleIndexVertexArray array{2, indices, 3 * int(sizeof(int)), 4, vertices, 3 * int(sizeof(btScalar))};
};
}  // namespace

TEST(FormatAudit, EveryShapeNamesBulletsStructAndReportsItsSize)
{
	Mesh mesh;
	btBoxShape box(btVector3(1, 2, 3));
	btSphereShape sphere(1);
	btCapsuleShapeX capsuleX(0.5, 1);
	btCapsuleShape capsuleY(0.5, 1);
	btCapsuleShapeZ capsuleZ(0.5, 1);
	btCylinderShape cylinder(btVector3(1, 2, 1));
	btConeShape cone(1, 2);
	const btVector3 centres[2] = {btVector3(0, 0, 0), btVector3(1, 0, 0)};
	const btScalar radii[2] = {0.5, 0.25};
	btMultiSphereShape multi(centres, radii, 2);
	btConvexHullShape hull;
	hull.addPoint(btVector3(0, 0, 0));
	hull.addPoint(btVector3(1, 0, 0));
	hull.addPoint(btVector3(0, 1, 0));
	hull.addPoint(btVector3(0, 0, 1));
	btCompoundShape compound;
	compound.addChildShape(btTransform::getIdentity(), &box);
	btStaticPlaneShape plane(btVector3(0, 1, 0), 0);
	btBvhTriangleMeshShape bvhMesh(&mesh.array, true);
	btScaledBvhTriangleMeshShape scaled(&bvhMesh, btVector3(2, 2, 2));
	expectLayout(box, "btConvexInternalShapeData", sizeof(btConvexInternalShapeData), "box");
	expectLayout(sphere, "btConvexInternalShapeData", sizeof(btConvexInternalShapeData), "sphere");
	expectLayout(capsuleX, "btCapsuleShapeData", sizeof(btCapsuleShapeData), "capsule X");
	expectLayout(capsuleY, "btCapsuleShapeData", sizeof(btCapsuleShapeData), "capsule Y");
	expectLayout(capsuleZ, "btCapsuleShapeData", sizeof(btCapsuleShapeData), "capsule Z");
	expectLayout(cylinder, "btCylinderShapeData", sizeof(btCylinderShapeData), "cylinder");
	expectLayout(cone, "btConeShapeData", sizeof(btConeShapeData), "cone");
	expectLayout(multi, "btMultiSphereShapeData", sizeof(btMultiSphereShapeData), "multi-sphere");
	expectLayout(hull, "btConvexHullShapeData", sizeof(btConvexHullShapeData), "hull");
	expectLayout(compound, "btCompoundShapeData", sizeof(btCompoundShapeData), "compound");
	expectLayout(plane, "btStaticPlaneShapeData", sizeof(btStaticPlaneShapeData), "plane");
	expectLayout(bvhMesh, "btTriangleMeshShapeData", sizeof(btTriangleMeshShapeData), "BVH mesh");
	expectLayout(scaled, "btScaledTriangleMeshShapeData", sizeof(btScaledTriangleMeshShapeData), "scaled mesh");

	// Shapes Bullet's format has no layout for: their base class's struct, as Bullet writes them.
	float heights[9] = {0, 1, 0, 1, 2, 1, 0, 1, 0};
	btHeightfieldTerrainShape field(3, 3, heights, btScalar(0), btScalar(2), 1, false);
	btUniformScalingShape uniform(&sphere, 2);
	btMinkowskiSumShape minkowski(&sphere, &box);
	btEmptyShape empty;
	btTriangleShape triangle(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0));
	btConvexTriangleMeshShape convexMesh(&mesh.array);
	btVector3 cloud[3] = {btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0)};
	btConvexPointCloudShape pointCloud(cloud, 3, btVector3(1, 1, 1));
	expectLayout(field, "btCollisionShapeData", sizeof(btCollisionShapeData), "height field");
	expectLayout(uniform, "btCollisionShapeData", sizeof(btCollisionShapeData), "uniform scaling");
	expectLayout(empty, "btCollisionShapeData", sizeof(btCollisionShapeData), "empty");
	expectLayout(minkowski, "btConvexInternalShapeData", sizeof(btConvexInternalShapeData), "Minkowski sum");
	expectLayout(triangle, "btConvexInternalShapeData", sizeof(btConvexInternalShapeData), "triangle");
	expectLayout(convexMesh, "btConvexInternalShapeData", sizeof(btConvexInternalShapeData), "convex mesh");
	expectLayout(pointCloud, "btConvexInternalShapeData", sizeof(btConvexInternalShapeData), "point cloud");
}

TEST(FormatAudit, BodiesObjectsAndEveryJointNameBulletsStructForTheBuildsPrecision)
{
	TestWorld t;
	btCollisionShape* box = t.shape(new btBoxShape(btVector3(0.5, 0.5, 0.5)));
	btRigidBody* a = t.body(box, 1, btVector3(0, 0, 0));
	btRigidBody* b = t.body(box, 1, btVector3(1, 0, 0));
	btCollisionObject object;
	object.setCollisionShape(box);
	const btTransform frame = btTransform::getIdentity();
	const btVector3 axis(0, 0, 1), other(0, 1, 0), at(0.5, 0, 0);
	btPoint2PointConstraint point(*a, *b, at, -at);
	btHingeConstraint hinge(*a, *b, frame, frame);
	btConeTwistConstraint cone(*a, *b, frame, frame);
	btGeneric6DofConstraint dof(*a, *b, frame, frame, true);
	btGeneric6DofSpringConstraint spring(*a, *b, frame, frame, true);
	btGeneric6DofSpring2Constraint spring2(*a, *b, frame, frame);
	btSliderConstraint slider(*a, *b, frame, frame, true);
	btGearConstraint gear(*a, *b, axis, axis, 2);
	btFixedConstraint fixed(*a, *b, frame, frame);
	btUniversalConstraint universal(*a, *b, at, axis, other);
	btHinge2Constraint hinge2(*a, *b, at, other, axis);
#define CALIBER_EXPECT_LAYOUT(obj, floatStruct, doubleStruct)                                                       \
	expectLayout(obj, kDouble ? #doubleStruct : #floatStruct, kDouble ? sizeof(doubleStruct) : sizeof(floatStruct), \
	             #obj)
	CALIBER_EXPECT_LAYOUT(*a, btRigidBodyFloatData, btRigidBodyDoubleData);
	CALIBER_EXPECT_LAYOUT(object, btCollisionObjectFloatData, btCollisionObjectDoubleData);
	CALIBER_EXPECT_LAYOUT(point, btPoint2PointConstraintFloatData, btPoint2PointConstraintDoubleData2);
	CALIBER_EXPECT_LAYOUT(hinge, btHingeConstraintFloatData, btHingeConstraintDoubleData2);
	CALIBER_EXPECT_LAYOUT(cone, btConeTwistConstraintData, btConeTwistConstraintDoubleData);
	CALIBER_EXPECT_LAYOUT(dof, btGeneric6DofConstraintData, btGeneric6DofConstraintDoubleData2);
	CALIBER_EXPECT_LAYOUT(spring, btGeneric6DofSpringConstraintData, btGeneric6DofSpringConstraintDoubleData2);
	CALIBER_EXPECT_LAYOUT(spring2, btGeneric6DofSpring2ConstraintData, btGeneric6DofSpring2ConstraintDoubleData2);
	CALIBER_EXPECT_LAYOUT(slider, btSliderConstraintData, btSliderConstraintDoubleData);
	CALIBER_EXPECT_LAYOUT(gear, btGearConstraintFloatData, btGearConstraintDoubleData);
	CALIBER_EXPECT_LAYOUT(fixed, btGeneric6DofSpring2ConstraintData, btGeneric6DofSpring2ConstraintDoubleData2);
	CALIBER_EXPECT_LAYOUT(universal, btGeneric6DofConstraintData, btGeneric6DofConstraintDoubleData2);
	CALIBER_EXPECT_LAYOUT(hinge2, btGeneric6DofSpring2ConstraintData, btGeneric6DofSpring2ConstraintDoubleData2);
#undef CALIBER_EXPECT_LAYOUT
}

TEST(FormatAudit, ShapesWithoutALayoutAreWrittenAndSkippedOnReadingWithAWarning)
{
	float heights[9] = {0, 1, 0, 1, 2, 1, 0, 1, 0};
	btHeightfieldTerrainShape field(3, 3, heights, btScalar(0), btScalar(2), 1, false);
	btSphereShape sphere(1);
	btUniformScalingShape uniform(&sphere, 2);
	btCollisionShape* shapes[] = {&field, &uniform};
	for (btCollisionShape* shape : shapes)
	{
		btDefaultSerializer s;
		s.startSerialization();
		shape->serializeSingleShape(&s);
		s.finishSerialization();
		std::vector<char> file = caliber_test::bytesOf(s);
		WarningLog log;
		btBulletWorldImporter importer(0);
		EXPECT_TRUE(importer.loadFileFromMemory(file.data(), int(file.size())));
		EXPECT_EQ(importer.getNumCollisionShapes(), 0) << shape->getName();
		EXPECT_TRUE(log.contains("are not supported by the importer")) << shape->getName() << ": " << log.all();
		importer.deleteAllData();
	}
}

TEST(FormatAudit, UniversalAndHinge2JointsLoadAsTheSixDofAndSpring2JointsTheyAre)
{
	TestWorld t;
	btCollisionShape* box = t.shape(new btBoxShape(btVector3(0.5, 0.5, 0.5)));
	btRigidBody* a = t.body(box, 1, btVector3(0, 0, 0));
	btRigidBody* b = t.body(box, 1, btVector3(1, 0, 0));
	btUniversalConstraint* universal =
	    t.joint(new btUniversalConstraint(*a, *b, btVector3(0.5, 0, 0), btVector3(0, 0, 1), btVector3(0, 1, 0)));
	btHinge2Constraint* hinge2 =
	    t.joint(new btHinge2Constraint(*a, *b, btVector3(0.5, 0, 0), btVector3(0, 1, 0), btVector3(0, 0, 1)));
	btDefaultSerializer s;
	s.registerNameForPointer(universal, "universal");
	s.registerNameForPointer(hinge2, "hinge2");
	const std::vector<char> file = t.save(&s);
	TestWorld loaded;
	btBulletWorldImporter importer(&loaded.world);
	ASSERT_TRUE(importer.loadFileFromMemory(const_cast<char*>(file.data()), int(file.size())));
	btTypedConstraint* u = importer.getConstraintByName("universal");
	btTypedConstraint* h = importer.getConstraintByName("hinge2");
	ASSERT_TRUE(u && h);
	ASSERT_EQ(u->getConstraintType(), D6_CONSTRAINT_TYPE);
	ASSERT_EQ(h->getConstraintType(), D6_SPRING_2_CONSTRAINT_TYPE);
	// Frames and limits in the build's precision: bit for bit.
	const btGeneric6DofConstraint& du = *static_cast<btGeneric6DofConstraint*>(u);
	btGeneric6DofSpring2Constraint& dh = *static_cast<btGeneric6DofSpring2Constraint*>(h);
	EXPECT_EQ(du.getFrameOffsetA().getOrigin(), universal->getFrameOffsetA().getOrigin());
	EXPECT_EQ(du.getFrameOffsetB().getBasis()[1], universal->getFrameOffsetB().getBasis()[1]);
	btVector3 lo, hi, loU, hiU;
	du.getAngularLowerLimit(lo);
	du.getAngularUpperLimit(hi);
	universal->getAngularLowerLimit(loU);
	universal->getAngularUpperLimit(hiU);
	EXPECT_EQ(lo, loU);
	EXPECT_EQ(hi, hiU);
	EXPECT_EQ(dh.getFrameOffsetA().getOrigin(), hinge2->getFrameOffsetA().getOrigin());
	for (int i = 0; i < 3; ++i)
	{
		EXPECT_EQ(dh.getRotationalLimitMotor(i)->m_loLimit, hinge2->getRotationalLimitMotor(i)->m_loLimit);
		EXPECT_EQ(dh.getRotationalLimitMotor(i)->m_springStiffness,
		          hinge2->getRotationalLimitMotor(i)->m_springStiffness);
	}
	EXPECT_EQ(dh.getTranslationalLimitMotor()->m_springStiffness,
	          hinge2->getTranslationalLimitMotor()->m_springStiffness);
	importer.deleteAllData();
}

TEST(FormatAudit, FilesOfOtherBullet2And3VersionsLoadTheSameWorld)
{
	TestWorld t;
	btCollisionShape* box = t.shape(new btBoxShape(btVector3(0.5, 0.5, 0.5)));
	btRigidBody* a = t.body(box, 1, btVector3(0, 2, 0));
	btRigidBody* b = t.body(box, 2, btVector3(1, 2, 0));
	t.joint(new btHingeConstraint(*a, *b, btVector3(0.5, 0, 0), btVector3(-0.5, 0, 0), btVector3(0, 0, 1),
	                              btVector3(0, 0, 1)));
	const std::vector<char> file = t.save();
	// The copy loaded from the file as written, saved again: what a loaded world writes.
	auto loadAndSave = [](std::vector<char> bytes, const char* version)
	{
		TestWorld loaded;
		btBulletWorldImporter importer(&loaded.world);
		EXPECT_TRUE(importer.loadFileFromMemory(bytes.data(), int(bytes.size()))) << version;
		EXPECT_EQ(importer.getNumRigidBodies(), 2) << version;
		EXPECT_EQ(importer.getNumConstraints(), 1) << version;
		std::vector<char> saved = loaded.save();
		importer.deleteAllData();
		return saved;
	};
	const std::vector<char> reference = loadAndSave(file, "289");
	// The version is the header's last three digits: Bullet 2.75 to 2.89 and 3.x (3.17, 3.25) write theirs.
	for (const char* version : {"275", "281", "282", "286", "288", "317", "325"})
	{
		std::vector<char> other = file;
		setVersion(other, version);
		EXPECT_EQ(loadAndSave(other, version), reference) << version;
	}
}

TEST(FormatAudit, PreBullet282DoubleLayoutsOfHingeAndPointToPointLoad)
{
	// A file as Bullet 2.81 double builds wrote joints: the common part in btTypedConstraintData (float
	// fields), frames or pivots in double. Written chunk by chunk here, since Caliber writes the newer
	// layouts.
	TestWorld t;
	btCollisionShape* box = t.shape(new btBoxShape(btVector3(0.5, 0.5, 0.5)));
	btRigidBody* a = t.body(box, 1, btVector3(0, 2, 0));
	btRigidBody* b = t.body(box, 2, btVector3(1, 2, 0));
	btDefaultSerializer s;
	s.startSerialization();
	box->serializeSingleShape(&s);
	a->serializeSingleObject(&s);
	b->serializeSingleObject(&s);
	const btTransform frameA(btQuaternion(btVector3(0, 1, 0), btScalar(0.25)), btVector3(0.5, 0, 0));
	const btTransform frameB(btQuaternion(btVector3(1, 0, 0), btScalar(-0.5)), btVector3(-0.5, 0, 0));
	auto common = [&](btTypedConstraintData& c, int type)
	{
		c.m_rbA = static_cast<btRigidBodyData*>(s.getUniquePointer(a));
		c.m_rbB = static_cast<btRigidBodyData*>(s.getUniquePointer(b));
		c.m_objectType = type;
		c.m_isEnabled = 1;
		c.m_breakingImpulseThreshold = 77;
		c.m_overrideNumSolverIterations = -1;
		c.m_dbgDrawSize = 0.3f;
	};
	{
		btChunk* chunk = s.allocate(sizeof(btHingeConstraintDoubleData), 1);
		btHingeConstraintDoubleData* h = static_cast<btHingeConstraintDoubleData*>(chunk->m_oldPtr);
		memset(h, 0, sizeof(*h));
		common(h->m_typeConstraintData, HINGE_CONSTRAINT_TYPE);
		writeDouble(frameA, h->m_rbAFrame);
		writeDouble(frameB, h->m_rbBFrame);
		h->m_lowerLimit = -0.75f;
		h->m_upperLimit = 0.5f;
		h->m_limitSoftness = 0.9f;
		h->m_biasFactor = 0.3f;
		h->m_relaxationFactor = 1.0f;
		h->m_enableAngularMotor = 1;
		h->m_motorTargetVelocity = 2.5f;
		h->m_maxMotorImpulse = 4.0f;
		s.finalizeChunk(chunk, "btHingeConstraintDoubleData", BT_CONSTRAINT_CODE, h);
	}
	{
		btChunk* chunk = s.allocate(sizeof(btPoint2PointConstraintDoubleData), 1);
		btPoint2PointConstraintDoubleData* p = static_cast<btPoint2PointConstraintDoubleData*>(chunk->m_oldPtr);
		memset(p, 0, sizeof(*p));
		common(p->m_typeConstraintData, POINT2POINT_CONSTRAINT_TYPE);
		btVector3(0.5, 0.25, 0).serializeDouble(p->m_pivotInA);
		btVector3(-0.5, 0.25, 0).serializeDouble(p->m_pivotInB);
		s.finalizeChunk(chunk, "btPoint2PointConstraintDoubleData", BT_CONSTRAINT_CODE, p);
	}
	s.finishSerialization();
	std::vector<char> file = caliber_test::bytesOf(s);
	setVersion(file, "281");

	TestWorld loaded;
	btBulletWorldImporter importer(&loaded.world);
	ASSERT_TRUE(importer.loadFileFromMemory(file.data(), int(file.size())));
	ASSERT_EQ(importer.getNumConstraints(), 2);
	btHingeConstraint* hinge = 0;
	btPoint2PointConstraint* point = 0;
	for (int i = 0; i < 2; ++i)
	{
		btTypedConstraint* c = importer.getConstraintByIndex(i);
		if (c->getConstraintType() == HINGE_CONSTRAINT_TYPE) hinge = static_cast<btHingeConstraint*>(c);
		if (c->getConstraintType() == POINT2POINT_CONSTRAINT_TYPE) point = static_cast<btPoint2PointConstraint*>(c);
	}
	ASSERT_TRUE(hinge && point);
	// Doubles hold the build's frames exactly; the float fields are exact binary fractions.
	EXPECT_EQ(hinge->getAFrame().getOrigin(), frameA.getOrigin());
	EXPECT_EQ(hinge->getBFrame().getBasis()[2], frameB.getBasis()[2]);
	EXPECT_EQ(hinge->getLowerLimit(), btScalar(-0.75));
	EXPECT_EQ(hinge->getUpperLimit(), btScalar(0.5));
	EXPECT_TRUE(hinge->getEnableAngularMotor());
	EXPECT_EQ(hinge->getMotorTargetVelocity(), btScalar(2.5));
	EXPECT_EQ(hinge->getMaxMotorImpulse(), btScalar(4));
	EXPECT_EQ(hinge->getBreakingImpulseThreshold(), btScalar(77));
	EXPECT_EQ(point->getPivotInA(), btVector3(0.5, 0.25, 0));
	EXPECT_EQ(point->getPivotInB(), btVector3(-0.5, 0.25, 0));
	EXPECT_EQ(&point->getRigidBodyA(), importer.getRigidBodyByIndex(0));
	importer.deleteAllData();
}
