// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// btDefaultSerializer: the file layout (header, chunk headers, DNA last), unique ids, names, the
// caller's buffer, determinism, and misuse.
#include <gtest/gtest.h>

#include <stdint.h>

#include "Serialize/SerializeTestUtil.h"

using caliber_test::bytesOf;
using caliber_test::TestWorld;
using caliber_test::WarningLog;

namespace
{
struct ChunkView
{
	int code;
	int length;
	uint64_t oldPtr;
	int dnaNr;
	int number;
	size_t dataOffset;
};

// Walks the chunks as a reader would (native pointer size and byte order: our own files).
std::vector<ChunkView> chunksOf(const std::vector<char>& file)
{
	std::vector<ChunkView> out;
	size_t pos = BT_HEADER_LENGTH;
	while (pos + sizeof(btChunk) <= file.size())
	{
		btChunk c;
		memcpy(&c, &file[pos], sizeof(btChunk));
		ChunkView v{c.m_chunkCode, c.m_length, uint64_t(uintptr_t(c.m_oldPtr)),
		            c.m_dna_nr,    c.m_number, pos + sizeof(btChunk)};
		out.push_back(v);
		pos += sizeof(btChunk) + size_t(c.m_length);
	}
	EXPECT_EQ(pos, file.size()) << "the chunks must exactly fill the file";
	return out;
}

int countCode(const std::vector<ChunkView>& chunks, int code)
{
	int n = 0;
	for (const ChunkView& c : chunks) n += c.code == code;
	return n;
}
}  // namespace

TEST(Serializer, HeaderNamesPrecisionPointerSizeByteOrderAndVersion)
{
	TestWorld w;
	const std::vector<char> file = w.save();
	ASSERT_GE(file.size(), size_t(BT_HEADER_LENGTH));
#ifdef BT_USE_DOUBLE_PRECISION
	EXPECT_EQ(std::string(&file[0], 7), "BULLETd");
#else
	EXPECT_EQ(std::string(&file[0], 7), "BULLETf");
#endif
	EXPECT_EQ(file[7], sizeof(void*) == 8 ? '-' : '_');
	const uint16_t probe = 1;
	EXPECT_EQ(file[8], *reinterpret_cast<const char*>(&probe) == 1 ? 'v' : 'V');
	EXPECT_EQ(std::string(&file[9], 3), "289");
}

TEST(Serializer, ChunksFillTheFileAndTheDnaComesLast)
{
	TestWorld w;
	btCollisionShape* box = w.shape(new btBoxShape(btVector3(1, 2, 3)));
	w.body(box, 1, btVector3(0, 5, 0));
	w.body(box, 0, btVector3(0, 0, 0));
	const std::vector<char> file = w.save();
	const std::vector<ChunkView> chunks = chunksOf(file);
	ASSERT_FALSE(chunks.empty());
	EXPECT_EQ(chunks.back().code, BT_DNA_CODE);
	EXPECT_EQ(countCode(chunks, BT_DYNAMICSWORLD_CODE), 1);
	EXPECT_EQ(countCode(chunks, BT_RIGIDBODY_CODE), 2);
	// One shape chunk although two bodies use the shape.
	EXPECT_EQ(countCode(chunks, BT_SHAPE_CODE), 1);
	// Every struct chunk names a DNA struct; each body points at the shape chunk's id.
	uint64_t shapeId = 0;
	for (const ChunkView& c : chunks)
	{
		if (c.code == BT_SHAPE_CODE) shapeId = c.oldPtr;
		if (c.code != BT_DNA_CODE)
		{
			EXPECT_GE(c.dnaNr, 0);
		}
		EXPECT_GE(c.number, 1);
	}
	for (const ChunkView& c : chunks)
		if (c.code == BT_RIGIDBODY_CODE)
		{
			btRigidBodyData body;
			ASSERT_EQ(size_t(c.length), sizeof(body));
			memcpy(&body, &file[c.dataOffset], sizeof(body));
			EXPECT_EQ(uint64_t(uintptr_t(body.m_collisionObjectData.m_collisionShape)), shapeId);
			EXPECT_EQ(body.m_collisionObjectData.m_broadphaseHandle, nullptr);
		}
}

TEST(Serializer, UniquePointersAreStablePerObjectAndNullStaysNull)
{
	btDefaultSerializer s;
	s.startSerialization();
	int a = 0, b = 0;
	void* idA = s.getUniquePointer(&a);
	EXPECT_NE(idA, nullptr);
	EXPECT_EQ(s.getUniquePointer(&a), idA);
	EXPECT_NE(s.getUniquePointer(&b), idA);
	EXPECT_EQ(s.getUniquePointer(0), nullptr);
	// Skipped pointers are left out of the file.
	s.m_skipPointers.insert(btHashPtr(&b), 0);
	int c = 0;
	s.m_skipPointers.insert(btHashPtr(&c), 0);
	EXPECT_EQ(s.getUniquePointer(&c), nullptr);
	s.finishSerialization();
}

TEST(Serializer, RegisteredNamesAreWrittenAsTerminatedCharChunks)
{
	TestWorld w;
	btRigidBody* body = w.body(w.shape(new btSphereShape(1)), 1, btVector3(0, 0, 0));
	btDefaultSerializer s;
	s.registerNameForPointer(body, "crate");
	const std::vector<char> file = w.save(&s);
	const std::vector<ChunkView> chunks = chunksOf(file);
	uint64_t nameId = 0;
	for (const ChunkView& c : chunks)
		if (c.code == BT_ARRAY_CODE && c.dnaNr < 0 && c.length >= 6 && !memcmp(&file[c.dataOffset], "crate", 6))
		{
			nameId = c.oldPtr;
			EXPECT_EQ(c.length % 4, 0) << "names are padded to 4 bytes";
		}
	ASSERT_NE(nameId, 0u) << "no name chunk";
	for (const ChunkView& c : chunks)
		if (c.code == BT_RIGIDBODY_CODE)
		{
			btRigidBodyData data;
			memcpy(&data, &file[c.dataOffset], sizeof(data));
			EXPECT_EQ(uint64_t(uintptr_t(data.m_collisionObjectData.m_name)), nameId);
		}
}

TEST(Serializer, SameWorldGivesTheSameBytesEveryTime)
{
	TestWorld w;
	w.body(w.shape(new btCapsuleShape(0.5, 2)), 2, btVector3(1, 2, 3));
	const std::vector<char> first = w.save();
	btDefaultSerializer reused;
	const std::vector<char> second = w.save(&reused);
	const std::vector<char> third = w.save(&reused);
	EXPECT_EQ(first, second);
	EXPECT_EQ(second, third);
}

TEST(Serializer, CallersBufferIsUsedWhenLargeEnough)
{
	TestWorld w;
	w.body(w.shape(new btSphereShape(1)), 1, btVector3(0, 0, 0));
	const std::vector<char> reference = w.save();
	std::vector<unsigned char> buffer(reference.size() + 64);
	btDefaultSerializer s(int(buffer.size()), buffer.data());
	w.world.serialize(&s);
	EXPECT_EQ(s.getBufferPointer(), buffer.data());
	EXPECT_EQ(bytesOf(s), reference);
}

TEST(Serializer, TooSmallCallersBufferFallsBackToOwnBufferWithWarning)
{
	TestWorld w;
	w.body(w.shape(new btSphereShape(1)), 1, btVector3(0, 0, 0));
	const std::vector<char> reference = w.save();
	std::vector<unsigned char> buffer(32, 0xab);
	WarningLog log;
	btDefaultSerializer s(int(buffer.size()), buffer.data());
	w.world.serialize(&s);
	EXPECT_TRUE(log.contains("caller's buffer")) << log.all();
	EXPECT_NE(s.getBufferPointer(), buffer.data());
	EXPECT_EQ(bytesOf(s), reference);
	EXPECT_EQ(buffer[0], 0xab) << "the caller's buffer must not be overrun";
}

#if CALIBER_ASSERTS_ENABLED
TEST(SerializerDeathTest, NonsenseChunkSizesAndIndicesAssert)
{
	btDefaultSerializer s;
	s.startSerialization();
	EXPECT_DEATH((void)s.allocate(16, -1), "assertion failed");
	EXPECT_DEATH((void)s.allocate(size_t(1) << 30, 4), "assertion failed");
	EXPECT_DEATH((void)s.getChunk(5), "assertion failed");
	btChunk* chunk = s.allocate(4, 1);
	EXPECT_DEATH(s.finalizeChunk(chunk, "NoSuchStruct", BT_ARRAY_CODE, &s), "assertion failed");
	s.finishSerialization();
}
#else
TEST(Serializer, NonsenseChunkSizesGiveNoChunkAndAWarningInRelease)
{
	btDefaultSerializer s;
	s.startSerialization();
	WarningLog log;
	EXPECT_EQ(s.allocate(16, -1), nullptr);
	EXPECT_EQ(s.allocate(size_t(1) << 30, 4), nullptr);
	EXPECT_EQ(s.getChunk(5), nullptr);
	btChunk* chunk = s.allocate(4, 1);
	s.finalizeChunk(chunk, "NoSuchStruct", BT_ARRAY_CODE, &s);
	EXPECT_EQ(chunk->m_dna_nr, -1);
	EXPECT_GE(log.count(), 3);
	s.finishSerialization();
	EXPECT_GT(s.getCurrentBufferSize(), BT_HEADER_LENGTH);
}
#endif
