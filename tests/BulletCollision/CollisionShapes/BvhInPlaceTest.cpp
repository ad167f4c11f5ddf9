// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Bullet's in-place BVH block (btQuantizedBvh::serialize(buffer, size, swapEndian), deSerializeInPlace,
// btOptimizedBvh::serializeInPlace / deSerializeInPlace): a loaded tree answers every box query as the
// tree it was written from, lives in the block without allocating, survives a byte-order round trip,
// and a corrupted block is refused with a warning, never a crash.

#include <gtest/gtest.h>

#include "BulletCollision/BroadphaseCollision/QuantizedBvhAccess.h"
#include "BulletCollision/BroadphaseCollision/QuantizedBvhInPlace.h"
#include "BulletCollision/CollisionShapes/btOptimizedBvh.h"
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"
#include "LinearMath/btWarningHook.h"

#include <stdint.h>
#include <string.h>

#include <limits>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace
{
// A bumpy grid of 2 * n * n triangles.
void buildGrid(btTriangleMesh& mesh, int n)
{
	for (int i = 0; i < n; ++i)
		for (int j = 0; j < n; ++j)
		{
			const auto h = [](int x, int z)
			{ return btScalar(0.3) * btSin(btScalar(x) * btScalar(0.7) + btScalar(z)); };
			const btVector3 a(btScalar(i), h(i, j), btScalar(j)), b(btScalar(i + 1), h(i + 1, j), btScalar(j));
			const btVector3 c(btScalar(i), h(i, j + 1), btScalar(j + 1));
			const btVector3 d(btScalar(i + 1), h(i + 1, j + 1), btScalar(j + 1));
			mesh.addTriangle(a, b, c);
			mesh.addTriangle(b, d, c);
		}
}

struct Collector : btNodeOverlapCallback
{
	std::set<std::pair<int, int>> hits;
	void processNode(int subPart, int triangleIndex) override { hits.insert(std::make_pair(subPart, triangleIndex)); }
};

std::set<std::pair<int, int>> query(const btQuantizedBvh& bvh, const btVector3& lo, const btVector3& hi)
{
	Collector c;
	bvh.reportAabbOverlappingNodex(&c, lo, hi);
	return c.hits;
}

// The same answers as reference for 200 random boxes over the grid (and some beyond it).
void expectSameAnswers(const btQuantizedBvh& reference, const btQuantizedBvh& loaded, int n)
{
	std::mt19937 rng(7);
	std::uniform_real_distribution<float> pos(-2.0f, float(n) + 2.0f), size(0.0f, 3.0f);
	for (int q = 0; q < 200; ++q)
	{
		const btVector3 lo(pos(rng), -1, pos(rng));
		const btVector3 hi = lo + btVector3(size(rng), 2, size(rng));
		ASSERT_EQ(query(reference, lo, hi), query(loaded, lo, hi)) << "query " << q;
	}
}

// A 16-byte aligned block owned by the test.
struct Block
{
	std::vector<unsigned char> storage;
	unsigned char* data;
	explicit Block(unsigned bytes) : storage(bytes + 16u)
	{
		data = storage.data() + (16u - reinterpret_cast<uintptr_t>(storage.data()) % 16u) % 16u;
	}
};

struct WarningCount
{
	int count = 0;
	std::string last;
	WarningCount()
	{
		btSetWarningHook(
		    [](const char* message, void* self)
		    {
			    ++static_cast<WarningCount*>(self)->count;
			    static_cast<WarningCount*>(self)->last = message;
		    },
		    this);
	}
	~WarningCount() { btSetWarningHook(0, 0); }
};

// A grid mesh, its tree, and the tree written into a block of its own.
struct WrittenGrid
{
	btTriangleMesh mesh;
	btOptimizedBvh bvh;
	unsigned bytes = 0;
	std::unique_ptr<Block> block;
	bool written = false;

	WrittenGrid(int n, bool quantized, bool swapEndian)
	{
		buildGrid(mesh, n);
		bvh.build(&mesh, quantized, btVector3(-1, -1, -1), btVector3(btScalar(n + 1), 1, btScalar(n + 1)));
		bytes = bvh.calculateSerializeBufferSize();
		block.reset(new Block(bytes));
		written = bvh.serializeInPlace(block->data, bytes, swapEndian);
	}
};

const int kGrid = 24;
}  // namespace

TEST(BvhInPlace, QuantizedAndPlainTreesAnswerEveryQueryAsTheOriginal)
{
	for (int quantized = 0; quantized < 2; ++quantized)
	{
		WrittenGrid grid(kGrid, quantized == 1, false);
		ASSERT_TRUE(grid.written);
		Block& block = *grid.block;
		btOptimizedBvh* loaded = btOptimizedBvh::deSerializeInPlace(block.data, grid.bytes, false);
		ASSERT_NE(loaded, nullptr);
		EXPECT_EQ(static_cast<void*>(loaded), static_cast<void*>(block.data)) << "built in the block itself";
		EXPECT_EQ(loaded->isQuantized(), quantized == 1);
		EXPECT_EQ(caliber::bvhNodeCount(*loaded), caliber::bvhNodeCount(grid.bvh));
		// The arrays are the block's memory, not copies.
		const void* nodes = quantized ? static_cast<const void*>(&loaded->getQuantizedNodeArray()[0])
		                              : static_cast<const void*>(&caliber::bvhNodeArray(*loaded)[0]);
		EXPECT_TRUE(nodes > static_cast<const void*>(block.data) &&
		            nodes < static_cast<const void*>(block.data + grid.bytes));
		expectSameAnswers(grid.bvh, *loaded, kGrid);
		loaded->~btOptimizedBvh();  // frees nothing: the block is the caller's
	}
}

// Bullet declares the in-place constructor btQuantizedBvh(btQuantizedBvh&, bool ownsMemory) private:
// code written for Bullet cannot call it, and neither can ours.
static_assert(!std::is_constructible<btQuantizedBvh, btQuantizedBvh&, bool>::value,
              "Bullet's in-place constructor is private");

TEST(BvhInPlace, InPlaceConstructorTakesTheStateAndViewsTheBlockWithoutCopying)
{
	for (int quantized = 0; quantized < 2; ++quantized)
	{
		WrittenGrid grid(kGrid, quantized == 1, false);
		ASSERT_TRUE(grid.written);
		unsigned char* data = grid.block->data;
		btQuantizedBvh* loaded = btQuantizedBvh::deSerializeInPlace(data, grid.bytes, false);
		ASSERT_NE(loaded, nullptr);
		EXPECT_EQ(loaded->isQuantized(), quantized == 1);
		EXPECT_EQ(caliber::bvhNodeCount(*loaded), caliber::bvhNodeCount(grid.bvh));
		// The quantization box is the original's bit for bit (a quantized corner maps to the same point).
		EXPECT_EQ(caliber::bvhAabbMin(*loaded), caliber::bvhAabbMin(grid.bvh));
		EXPECT_EQ(caliber::bvhAabbMax(*loaded), caliber::bvhAabbMax(grid.bvh));
		EXPECT_EQ(caliber::bvhQuantization(*loaded), caliber::bvhQuantization(grid.bvh));
		// Every array the constructor took views the block (ownsMemory false): nodes and subtree headers.
		const auto inBlock = [&](const void* p)
		{ return p >= data && p < static_cast<const void*>(data + grid.bytes); };
		const void* nodes = quantized ? static_cast<const void*>(&loaded->getQuantizedNodeArray()[0])
		                              : static_cast<const void*>(&caliber::bvhNodeArray(*loaded)[0]);
		EXPECT_TRUE(inBlock(nodes));
		EXPECT_EQ(loaded->getSubtreeInfoArray().size(), grid.bvh.getSubtreeInfoArray().size());
		if (quantized)
		{
			ASSERT_GT(loaded->getSubtreeInfoArray().size(), 0);
			EXPECT_TRUE(inBlock(&loaded->getSubtreeInfoArray()[0]));
		}
		expectSameAnswers(grid.bvh, *loaded, kGrid);
		loaded->~btQuantizedBvh();  // frees nothing: the block is the caller's
	}
}

TEST(BvhInPlace, ByteSwappedBlockLoadsOnlyWhenAskedToSwap)
{
	WrittenGrid grid(kGrid, true, true);
	ASSERT_TRUE(grid.written);
	unsigned char* data = grid.block->data;
	{
		WarningCount warnings;
		const std::vector<unsigned char> before(data, data + grid.bytes);
		EXPECT_EQ(btOptimizedBvh::deSerializeInPlace(data, grid.bytes, false), nullptr)
		    << "a block for the other byte order is refused";
		EXPECT_EQ(warnings.count, 1);
		EXPECT_NE(warnings.last.find("byte order"), std::string::npos) << warnings.last;
		EXPECT_EQ(memcmp(before.data(), data, grid.bytes), 0) << "a refused block is left as it was";
	}
	btQuantizedBvh* loaded = btQuantizedBvh::deSerializeInPlace(data, grid.bytes, true);
	ASSERT_NE(loaded, nullptr);
	expectSameAnswers(grid.bvh, *loaded, kGrid);
	loaded->~btQuantizedBvh();
}

TEST(BvhInPlace, RefitWorksOnALoadedTree)
{
	WrittenGrid grid(8, true, false);
	ASSERT_TRUE(grid.written);
	btTriangleMesh& mesh = grid.mesh;
	btOptimizedBvh* loaded = btOptimizedBvh::deSerializeInPlace(grid.block->data, grid.bytes, false);
	ASSERT_NE(loaded, nullptr);
	// Raise every vertex by 5: after a refit, a box around the raised grid finds all 128 triangles.
	unsigned char* vertexBase;
	int numVerts, stride, indexStride, numFaces;
	PHY_ScalarType type, indexType;
	unsigned char* indexBase;
	mesh.getLockedVertexIndexBase(&vertexBase, numVerts, type, stride, &indexBase, indexStride, numFaces, indexType);
	for (int v = 0; v < numVerts; ++v) reinterpret_cast<btScalar*>(vertexBase + v * stride)[1] += btScalar(5);
	mesh.unLockVertexBase(0);
	loaded->refit(&mesh, btVector3(-1, -1, -1), btVector3(9, 7, 9));
	EXPECT_EQ(query(*loaded, btVector3(-1, 4, -1), btVector3(9, 6, 9)).size(), 128u);
	loaded->~btOptimizedBvh();
}

TEST(BvhInPlace, CorruptedBlocksAreRefusedWithAWarning)
{
	WrittenGrid grid(6, true, false);
	ASSERT_TRUE(grid.written);
	const unsigned bytes = grid.bytes;
	Block& good = *grid.block;
	const std::vector<unsigned char> pristine(good.data, good.data + bytes);
	const unsigned header = caliber::kInPlaceBvhObjectBytes;  // where the header starts (magic first)

	struct Case
	{
		const char* name;
		void (*corrupt)(unsigned char* data, unsigned header, unsigned bytes);
		unsigned size;  // 0: the full size
		const char* expected;
	};
	const Case cases[] = {
	    {"wrong magic", [](unsigned char* d, unsigned h, unsigned) { d[h] ^= 0xFF; }, 0, "magic"},
	    {"unknown version", [](unsigned char* d, unsigned h, unsigned) { d[h + 4] = 99; }, 0, "version"},
	    {"other precision", [](unsigned char* d, unsigned h, unsigned) { d[h + 8] = 2; }, 0, "precision"},
	    {"negative node count",
	     [](unsigned char* d, unsigned h, unsigned)
	     {
		     const int32_t minus = -5;
		     memcpy(d + h + 24, &minus, 4);
	     },
	     0, "negative"},
	    {"node count past the end",
	     [](unsigned char* d, unsigned h, unsigned)
	     {
		     const int32_t huge = 0x7FFFFFFF;
		     memcpy(d + h + 24, &huge, 4);
	     },
	     0, "past the end"},
	    {"truncated block", [](unsigned char*, unsigned, unsigned) {}, 100, "smaller than its header"},
	    {"truncated arrays", [](unsigned char*, unsigned, unsigned) {}, 1, "past the end"},
	    {"non-finite quantization",
	     [](unsigned char* d, unsigned h, unsigned)
	     {
		     const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
		     memcpy(d + h + 48 + 8 * sizeof(btScalar), &nan, sizeof(btScalar));
	     },
	     0, "non-finite"},
	    {"broken escape index",
	     [](unsigned char* d, unsigned h, unsigned)
	     {
		     // The root's escape index (bytes 12..15 of the first quantized node) made absurd.
		     const unsigned nodes = (h + 48 + 12 * sizeof(btScalar) + 15u) & ~15u;
		     const int32_t escape = -1000000;
		     memcpy(d + nodes + 12, &escape, 4);
	     },
	     0, "escape"},
	};
	for (const Case& c : cases)
	{
		Block block(bytes);
		memcpy(block.data, pristine.data(), bytes);
		c.corrupt(block.data, header, bytes);
		const unsigned size = c.size == 0 ? bytes : c.size == 1 ? bytes - 16 : c.size;
		WarningCount warnings;
		EXPECT_EQ(btOptimizedBvh::deSerializeInPlace(block.data, size, false), nullptr) << c.name;
		EXPECT_EQ(warnings.count, 1) << c.name;
		EXPECT_NE(warnings.last.find(c.expected), std::string::npos) << c.name << ": " << warnings.last;
	}
	WarningCount warnings;
	EXPECT_EQ(btQuantizedBvh::deSerializeInPlace(0, bytes, false), nullptr) << "null block";
	EXPECT_EQ(btQuantizedBvh::deSerializeInPlace(good.data + 4, bytes - 4, false), nullptr) << "misaligned block";
	EXPECT_EQ(warnings.count, 2);
	EXPECT_EQ(memcmp(good.data, pristine.data(), bytes), 0);
}

TEST(BvhInPlace, EmptyTreeRoundTrips)
{
	btOptimizedBvh empty;
	const unsigned bytes = empty.calculateSerializeBufferSize();
	Block block(bytes);
	ASSERT_TRUE(empty.serializeInPlace(block.data, bytes, false));
	btOptimizedBvh* loaded = btOptimizedBvh::deSerializeInPlace(block.data, bytes, false);
	ASSERT_NE(loaded, nullptr);
	EXPECT_TRUE(query(*loaded, btVector3(-10, -10, -10), btVector3(10, 10, 10)).empty());
	loaded->~btOptimizedBvh();
	EXPECT_EQ(btQuantizedBvh::getAlignmentSerializationPadding(), 16u);
}

TEST(BvhInPlaceDeathTest, SerializingIntoATooSmallBlockAssertsOrReturnsFalse)
{
	WrittenGrid grid(4, true, false);
	btOptimizedBvh& original = grid.bvh;
	const unsigned bytes = grid.bytes;
	Block& block = *grid.block;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(original.serializeInPlace(block.data, bytes - 1, false), "too small");
	EXPECT_DEATH(original.serializeInPlace(block.data + 4, bytes, false), "misaligned");
#else
	EXPECT_FALSE(original.serializeInPlace(block.data, bytes - 1, false));
	EXPECT_FALSE(original.serializeInPlace(block.data + 4, bytes, false));
#endif
}
