// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// The DNA our serializer writes must describe our structs exactly: a reader computes each field's
// offset by adding up the sizes before it, so every struct needs sizeof == the DNA's length and every
// field offsetof == the DNA's sum (no hidden padding). Checked for every struct tools/makedna found.
#include <gtest/gtest.h>

#include <stddef.h>
#include <string.h>

#include <string>
#include <vector>

#include "BulletFileLoader/bDNA.h"
#include "LinearMath/SerializerDnaExtras.h"
#include "LinearMath/btSerializer.h"
#include "btBulletDynamicsCommon.h"
#include "BulletCollision/CollisionShapes/btMultiSphereShape.h"
#include "BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btTriangleInfoMap.h"
#include "BulletDynamics/ConstraintSolver/btGearConstraint.h"
#include "BulletDynamics/ConstraintSolver/btGeneric6DofSpring2Constraint.h"
#include "BulletSoftBody/btSoftBodyData.h"

namespace
{
struct LayoutEntry
{
	const char* structName;
	const char* field;  // null for the struct's own entry
	size_t offset;
	size_t size;
};

#define CALIBER_DNA_STRUCT(S) {#S, nullptr, 0, sizeof(S)},
#define CALIBER_DNA_FIELD(S, F) {#S, #F, offsetof(S, F), sizeof(S)},
const LayoutEntry kLayout[] = {
#include "Serialize/DnaLayoutFields.inc"
};
#undef CALIBER_DNA_STRUCT
#undef CALIBER_DNA_FIELD

bParse::bDNA& memoryDna()
{
	static bParse::bDNA dna;
	static bool done = false;
	if (!done)
	{
		dna.init(const_cast<char*>(btDefaultSerializer::getMemoryDna()),
		         btDefaultSerializer::getMemoryDnaSizeInBytes());
		done = true;
	}
	return dna;
}
}  // namespace

TEST(DnaLayout, EveryStructHasTheSizeAndFieldOffsetsTheDnaImplies)
{
	bParse::bDNA& dna = memoryDna();
	ASSERT_GT(dna.getNumStructs(), 50) << "the DNA block did not parse";
	EXPECT_EQ(dna.getPointerSize(), int(sizeof(void*))) << "ListBase must give the pointer size";
	int structsChecked = 0;
	short* strc = 0;
	int fieldIndex = 0;
	int dnaOffset = 0;
	for (const LayoutEntry& e : kLayout)
	{
		if (!e.field)
		{
			const int s = dna.getReverseType(e.structName);
			ASSERT_GE(s, 0) << e.structName << " is missing from the DNA";
			strc = dna.getStruct(s);
			EXPECT_EQ(size_t(dna.getLength(strc[0])), e.size) << "sizeof(" << e.structName << ") differs from the DNA";
			fieldIndex = 0;
			dnaOffset = 0;
			++structsChecked;
			continue;
		}
		ASSERT_TRUE(strc);
		ASSERT_LT(fieldIndex, strc[1]) << e.structName << " has more fields than its DNA";
		const short type = strc[2 + 2 * fieldIndex], name = strc[3 + 2 * fieldIndex];
		EXPECT_EQ(size_t(dnaOffset), e.offset) << e.structName << "::" << e.field << " is not where the DNA puts it";
		dnaOffset += dna.getElementSize(type, name);
		++fieldIndex;
	}
	EXPECT_EQ(structsChecked, dna.getNumStructs());
}

TEST(DnaLayout, BulletsStructNamesAreDescribed)
{
	// The names Bullet's importer looks for (a file without them loads nothing in Bullet).
	const char* names[] = {"btRigidBodyFloatData",       "btRigidBodyDoubleData",
	                       "btCollisionObjectFloatData", "btCollisionShapeData",
	                       "btConvexInternalShapeData",  "btVector3FloatData",
	                       "btTransformFloatData",       "btMatrix3x3FloatData",
	                       "btCompoundShapeData",        "btConvexHullShapeData",
	                       "btStaticPlaneShapeData",     "btCapsuleShapeData",
	                       "btTriangleMeshShapeData",    "btStridingMeshInterfaceData",
	                       "btDynamicsWorldFloatData",   "btTypedConstraintData",
	                       "btHingeConstraintFloatData", "btGeneric6DofSpring2ConstraintData",
	                       "btGearConstraintFloatData",  "ListBase"};
	for (const char* n : names) EXPECT_GE(memoryDna().getReverseType(n), 0) << n;
}
