// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// Files that are cut short, carry the wrong magic, lie about lengths or counts, have a broken DNA or
// point at the wrong things: the loader reports a clear warning and returns false (or skips the
// inconsistent object), never crashes and never reads outside the file. These run under ASan in CI,
// which turns any out-of-bounds read into a failure; every buffer handed to the loader is a heap
// block of exactly the file's size for that reason.
#include <gtest/gtest.h>

#include <stddef.h>

#include <random>

#include "BulletCollision/CollisionShapes/btMultiSphereShape.h"
#include "BulletFileLoader/btBulletFile.h"
#include "BulletWorldImporter/btBulletWorldImporter.h"
#include "Serialize/SerializeTestUtil.h"

using caliber_test::ChunkAt;
using caliber_test::findChunk;
using caliber_test::TestWorld;
using caliber_test::walkChunks;
using caliber_test::WarningLog;

namespace
{
// A world with most kinds of chunk: shapes (box, compound, hull, mesh), bodies, a joint, names.
struct SampleFile
{
	std::vector<char> bytes;
	btVector3 vertices[4] = {btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 0, 1), btVector3(1, 0, 1)};
	int indices[6] = {0, 2, 1, 1, 2, 3};
	SampleFile()
	{
		std::unique_ptr<btTriangleIndexVertexArray> mesh(
		    new btTriangleIndexVertexArray(2, indices, 3 * sizeof(int), 4, &vertices[0][0], sizeof(btVector3)));
		TestWorld w;
		btCollisionShape* box = w.shape(new btBoxShape(btVector3(0.5, 0.5, 0.5)));
		btCompoundShape* compound = w.shape(new btCompoundShape());
		compound->addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(1, 0, 0)), box);
		btConvexHullShape* hull = w.shape(new btConvexHullShape());
		for (const btVector3& v : vertices) hull->addPoint(v + btVector3(0, 1, 0));
		btBvhTriangleMeshShape* ground = w.shape(new btBvhTriangleMeshShape(mesh.get(), true));
		w.body(ground, 0, btVector3(0, 0, 0));
		btRigidBody* a = w.body(box, 1, btVector3(0, 2, 0));
		btRigidBody* b = w.body(compound, 1, btVector3(0, 4, 0));
		w.body(hull, 1, btVector3(3, 2, 0));
		w.joint(new btPoint2PointConstraint(*a, *b, btVector3(0, 1, 0), btVector3(0, -1, 0)));
		btDefaultSerializer s;
		s.registerNameForPointer(a, "a");
		bytes = w.save(&s);
	}
};

const SampleFile& sample()
{
	static SampleFile file;
	return file;
}

struct LoadResult
{
	bool ok;
	int shapes, bodies, joints;
	std::string warnings;
};

// Loads a copy of bytes (a heap block of exactly bytes.size()) into a fresh world; step: also step
// it once (for files whose damage the loader must have caught: absurd but valid numbers, which
// random damage makes, are the world's business, not the loader's).
LoadResult load(const std::vector<char>& bytes, bool step = false)
{
	WarningLog log;
	// A world only when it is stepped: most cases check the loader alone (and stay fast under ASan).
	std::unique_ptr<TestWorld> w(step ? new TestWorld() : nullptr);
	btBulletWorldImporter importer(w ? &w->world : nullptr);
	std::unique_ptr<char[]> copy(new char[bytes.size() ? bytes.size() : 1]);
	if (!bytes.empty()) memcpy(copy.get(), bytes.data(), bytes.size());
	LoadResult r;
	r.ok = importer.loadFileFromMemory(bytes.empty() ? nullptr : copy.get(), int(bytes.size()));
	r.shapes = importer.getNumCollisionShapes();
	r.bodies = importer.getNumRigidBodies();
	r.joints = importer.getNumConstraints();
	if (w) w->world.stepSimulation(btScalar(1) / 60, 0);
	importer.deleteAllData();
	r.warnings = log.all();
	return r;
}

template <class T>
void poke(std::vector<char>& bytes, size_t offset, T value)
{
	ASSERT_LE(offset + sizeof(T), bytes.size());
	memcpy(&bytes[offset], &value, sizeof(T));
}
}  // namespace

TEST(CorruptFile, TheSampleFileLoadsCompletely)
{
	const LoadResult r = load(sample().bytes, true);
	EXPECT_TRUE(r.ok) << r.warnings;
	EXPECT_EQ(r.bodies, 4);
	EXPECT_EQ(r.joints, 1);
	EXPECT_EQ(r.warnings, "");
}

TEST(CorruptFile, EmptyAndHeaderOnlyBuffersAreRejected)
{
	const LoadResult empty = load({});
	EXPECT_FALSE(empty.ok);
	EXPECT_NE(empty.warnings.find("no buffer"), std::string::npos) << empty.warnings;
	// A default-constructed file object is simply empty (Bullet builds files to write that way).
	WarningLog log;
	bParse::btBulletFile nothing;
	EXPECT_FALSE(nothing.ok());
	EXPECT_EQ(log.count(), 0);
	std::vector<char> header(sample().bytes.begin(), sample().bytes.begin() + BT_HEADER_LENGTH);
	const LoadResult r = load(header);
	EXPECT_FALSE(r.ok);
	EXPECT_NE(r.warnings.find("no DNA1 chunk"), std::string::npos) << r.warnings;
}

TEST(CorruptFile, WrongMagicPrecisionPointerMarkOrVersionIsRejected)
{
	const struct
	{
		size_t offset;
		char value;
		const char* reason;
	} cases[] = {{0, 'X', "magic"},
	             {6, 'q', "precision"},
	             {7, '*', "pointer size"},
	             {8, 'x', "byte order"},
	             {10, 'a', "version"}};
	for (const auto& c : cases)
	{
		std::vector<char> bytes = sample().bytes;
		bytes[c.offset] = c.value;
		const LoadResult r = load(bytes);
		EXPECT_FALSE(r.ok) << c.reason;
		EXPECT_NE(r.warnings.find(c.reason), std::string::npos) << r.warnings;
		EXPECT_EQ(r.bodies, 0);
	}
}

TEST(CorruptFile, EveryTruncationIsRejectedWithoutReadingPastTheEnd)
{
	const std::vector<char>& full = sample().bytes;
	// Every length up to the file's: the DNA comes last, so no prefix is a complete file.
	for (size_t length = 0; length < full.size(); length += (length < 600 ? 1 : 7))
	{
		const LoadResult r = load(std::vector<char>(full.begin(), full.begin() + long(length)));
		ASSERT_FALSE(r.ok) << "a file cut to " << length << " bytes loaded";
		ASSERT_EQ(r.bodies, 0);
	}
}

TEST(CorruptFile, ChunkLengthsAndCountsBeyondTheFileAreRejected)
{
	const std::vector<ChunkAt> chunks = walkChunks(sample().bytes);
	const ChunkAt* body = findChunk(chunks, BT_RIGIDBODY_CODE);
	ASSERT_TRUE(body);
	for (int length : {0x7fffffff, -8, body->length + 1000000})
	{
		std::vector<char> bytes = sample().bytes;
		poke(bytes, body->header + offsetof(btChunk, m_length), length);
		const LoadResult r = load(bytes);
		EXPECT_FALSE(r.ok) << length;
		EXPECT_NE(r.warnings.find("claims"), std::string::npos) << r.warnings;
	}
	for (int count : {1000000000, 2, 0, -3})
	{
		std::vector<char> bytes = sample().bytes;
		poke(bytes, body->header + offsetof(btChunk, m_number), count);
		const LoadResult r = load(bytes);
		EXPECT_FALSE(r.ok) << count;
		EXPECT_NE(r.warnings.find("structs"), std::string::npos) << r.warnings;
	}
}

TEST(CorruptFile, DnaWhoseLengthsDoNotAddUpIsRejected)
{
	const std::vector<ChunkAt> chunks = walkChunks(sample().bytes);
	const ChunkAt* dna = findChunk(chunks, BT_DNA_CODE);
	ASSERT_TRUE(dna);
	std::vector<char> bytes = sample().bytes;
	// Make the TLEN entry of the first struct one byte longer than its fields.
	const std::string block(&bytes[dna->data], size_t(dna->length));
	const size_t tlen = block.find("TLEN");
	const size_t strc = block.find("STRC");
	ASSERT_NE(tlen, std::string::npos);
	ASSERT_NE(strc, std::string::npos);
	short firstStructType;
	memcpy(&firstStructType, &block[strc + 8], 2);
	const size_t entry = dna->data + tlen + 4 + 2 * size_t(firstStructType);
	short length;
	memcpy(&length, &bytes[entry], 2);
	poke(bytes, entry, short(length + 1));
	const LoadResult r = load(bytes);
	EXPECT_FALSE(r.ok);
	EXPECT_NE(r.warnings.find("DNA"), std::string::npos) << r.warnings;
}

TEST(CorruptFile, EveryByteOfTheDnaFlippedNeverCrashes)
{
	const std::vector<ChunkAt> chunks = walkChunks(sample().bytes);
	const ChunkAt* dna = findChunk(chunks, BT_DNA_CODE);
	ASSERT_TRUE(dna);
	int rejected = 0;
	// Every 11th byte: each section (counts, names, types, lengths, structs) gets many hits.
	for (int i = 0; i < dna->length; i += 11)
	{
		std::vector<char> bytes = sample().bytes;
		bytes[dna->data + size_t(i)] = char(bytes[dna->data + size_t(i)] ^ 0x5a);
		const LoadResult r = load(bytes);
		rejected += !r.ok;
		ASSERT_LE(r.bodies, 4);
	}
	EXPECT_GT(rejected, 0) << "no flip was noticed: the DNA checks see nothing";
}

TEST(CorruptFile, RandomByteDamageAnywhereNeverCrashes)
{
	std::mt19937 random(20261126);
	for (int trial = 0; trial < 300; ++trial)
	{
		std::vector<char> bytes = sample().bytes;
		std::uniform_int_distribution<size_t> where(0, bytes.size() - 1);
		const int flips = 1 + trial % 8;
		for (int f = 0; f < flips; ++f) bytes[where(random)] = char(random());
		const LoadResult r = load(bytes);
		ASSERT_LE(r.bodies, 4);
	}
}

TEST(CorruptFile, PointerToNothingOrToTheWrongKindSkipsOnlyThatObject)
{
	const std::vector<ChunkAt> chunks = walkChunks(sample().bytes);
	const ChunkAt* body = findChunk(chunks, BT_RIGIDBODY_CODE, 1);
	const ChunkAt* otherBody = findChunk(chunks, BT_RIGIDBODY_CODE, 2);
	ASSERT_TRUE(body && otherBody);
	const size_t shapeField = body->data + offsetof(btRigidBodyData, m_collisionObjectData) +
	                          offsetof(btCollisionObjectData, m_collisionShape);
	for (uint64_t target : {uint64_t(0x123456789abcull), otherBody->oldPtr})
	{
		std::vector<char> bytes = sample().bytes;
		poke(bytes, shapeField, reinterpret_cast<void*>(uintptr_t(target)));
		const LoadResult r = load(bytes, true);
		EXPECT_TRUE(r.ok);
		EXPECT_EQ(r.bodies, 3) << "only the body with the bad shape pointer is skipped";
		EXPECT_EQ(r.joints, 0) << "the joint on the skipped body goes too";
		EXPECT_NE(r.warnings.find("skipped"), std::string::npos) << r.warnings;
	}
}

TEST(CorruptFile, CountsBeyondTheirArraysSkipTheShape)
{
	const std::vector<ChunkAt> chunks = walkChunks(sample().bytes);
	for (const ChunkAt& c : chunks)
	{
		if (c.code != BT_SHAPE_CODE) continue;
		int shapeType;
		memcpy(&shapeType, &sample().bytes[c.data + offsetof(btCollisionShapeData, m_shapeType)], 4);
		std::vector<char> bytes = sample().bytes;
		if (shapeType == COMPOUND_SHAPE_PROXYTYPE)
			poke(bytes, c.data + offsetof(btCompoundShapeData, m_numChildShapes), 1000);
		else if (shapeType == CONVEX_HULL_SHAPE_PROXYTYPE)
			poke(bytes, c.data + offsetof(btConvexHullShapeData, m_numUnscaledPoints), 1 << 20);
		else
			continue;
		const LoadResult r = load(bytes, true);
		EXPECT_TRUE(r.ok);
		EXPECT_LT(r.bodies, 4) << "shape type " << shapeType;
		EXPECT_NE(r.warnings.find("inconsistent data"), std::string::npos) << r.warnings;
	}
}

TEST(CorruptFile, NegativeSizeMarginOrScalingSkipsThePrimitive)
{
	// A box's stored half extents, margin and scaling become its size: a negative one would reach the
	// box's constructor (which asserts on it) unless the loader refuses the shape first.
	const std::vector<ChunkAt> chunks = walkChunks(sample().bytes);
	int boxes = 0;
	for (const ChunkAt& c : chunks)
	{
		if (c.code != BT_SHAPE_CODE) continue;
		int shapeType;
		memcpy(&shapeType, &sample().bytes[c.data + offsetof(btCollisionShapeData, m_shapeType)], 4);
		if (shapeType != BOX_SHAPE_PROXYTYPE) continue;
		++boxes;
		const size_t fields[3] = {offsetof(btConvexInternalShapeData, m_implicitShapeDimensions),
		                          offsetof(btConvexInternalShapeData, m_collisionMargin),
		                          offsetof(btConvexInternalShapeData, m_localScaling) + sizeof(float)};
		for (size_t field : fields)
		{
			std::vector<char> bytes = sample().bytes;
			poke(bytes, c.data + field, -0.75f);
			const LoadResult r = load(bytes, true);
			EXPECT_TRUE(r.ok);
			EXPECT_LT(r.bodies, 4) << "field at " << field;
			EXPECT_NE(r.warnings.find("inconsistent data"), std::string::npos) << r.warnings;
		}
	}
	EXPECT_EQ(boxes, 1);
}

TEST(CorruptFile, MeshIndexOutsideItsVerticesSkipsTheMesh)
{
	const std::vector<ChunkAt> chunks = walkChunks(sample().bytes);
	bool found = false;
	for (const ChunkAt& c : chunks)
		if (c.code == BT_ARRAY_CODE && c.number == 6 && c.length == 6 * int(sizeof(btIntIndexData)))
		{
			std::vector<char> bytes = sample().bytes;
			poke(bytes, c.data + 4 * sizeof(btIntIndexData), 4);  // one past the last vertex
			const LoadResult r = load(bytes, true);
			EXPECT_TRUE(r.ok);
			EXPECT_EQ(r.bodies, 3);
			EXPECT_NE(r.warnings.find("inconsistent data"), std::string::npos) << r.warnings;
			found = true;
		}
	EXPECT_TRUE(found) << "no index chunk in the sample";
}

TEST(CorruptFile, BodyValuesTheWorldWouldRejectAreCaughtByTheLoader)
{
	const std::vector<ChunkAt> chunks = walkChunks(sample().bytes);
	const ChunkAt* ground = findChunk(chunks, BT_RIGIDBODY_CODE, 0);  // the static mesh body
	const ChunkAt* box = findChunk(chunks, BT_RIGIDBODY_CODE, 1);
	ASSERT_TRUE(ground && box);
	typedef decltype(btRigidBodyData().m_inverseMass) Number;
	{
		// A mass on a mesh: meshes have no inertia (btTriangleMeshShape asserts), so the body is made static.
		std::vector<char> bytes = sample().bytes;
		poke(bytes, ground->data + offsetof(btRigidBodyData, m_inverseMass), Number(1));
		const LoadResult r = load(bytes, true);
		EXPECT_TRUE(r.ok);
		EXPECT_EQ(r.bodies, 4);
		EXPECT_NE(r.warnings.find("made static"), std::string::npos) << r.warnings;
	}
	{
		// A negative linear factor (btRigidBody asserts on it): the body is skipped.
		std::vector<char> bytes = sample().bytes;
		poke(bytes, box->data + offsetof(btRigidBodyData, m_linearFactor) + sizeof(Number), Number(-1));
		const LoadResult r = load(bytes, true);
		EXPECT_TRUE(r.ok);
		EXPECT_EQ(r.bodies, 3);
		EXPECT_NE(r.warnings.find("skipped"), std::string::npos) << r.warnings;
	}
}
