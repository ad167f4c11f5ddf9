// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btHashMap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <unordered_map>
#include <vector>

namespace
{
// A key whose hash puts everything in one chain, to exercise the chain relinking in remove.
struct CollidingKey
{
	int id;
	CollidingKey(int value) : id(value) {}
	unsigned int getHash() const { return 7u; }
	bool equals(const CollidingKey& other) const { return id == other.id; }
};

// Checks that map and reference hold exactly the same entries, via find and via the dense arrays.
template <class Map>
void expectSameContents(const Map& map, const std::unordered_map<int, int>& reference, int step)
{
	ASSERT_EQ(map.size(), int(reference.size())) << "step " << step;
	for (const auto& entry : reference)
	{
		const int* found = map.find(btHashInt(entry.first));
		ASSERT_NE(found, nullptr) << "key " << entry.first << " lost at step " << step;
		ASSERT_EQ(*found, entry.second) << "key " << entry.first << " at step " << step;
	}
	for (int i = 0; i < map.size(); ++i)
	{
		const int key = map.getKeyAtIndex(i).getUid1();
		const auto it = reference.find(key);
		ASSERT_NE(it, reference.end()) << "stale key " << key << " at index " << i << ", step " << step;
		ASSERT_EQ(*map.getAtIndex(i), it->second) << "index " << i << ", step " << step;
		ASSERT_EQ(map.findIndex(btHashInt(key)), i) << "step " << step;
	}
}
}  // namespace

TEST(HashMap, RandomInsertRemoveFindMatchesUnorderedMap)
{
	btHashMap<btHashInt, int> map;
	std::unordered_map<int, int> reference;
	std::mt19937 rng(20260101);
	std::uniform_int_distribution<int> keyDist(-1500, 1500);
	std::uniform_int_distribution<int> opDist(0, 9);
	for (int step = 0; step < 40000; ++step)
	{
		const int key = keyDist(rng);
		const int op = opDist(rng);
		if (op < 5)
		{
			map.insert(btHashInt(key), step);
			reference[key] = step;
		}
		else if (op < 8)
		{
			map.remove(btHashInt(key));
			reference.erase(key);
		}
		else
		{
			const int* found = map[btHashInt(key)];
			const auto it = reference.find(key);
			if (it == reference.end())
				ASSERT_EQ(found, nullptr) << "absent key " << key << " found at step " << step;
			else
			{
				ASSERT_NE(found, nullptr) << "key " << key << " missing at step " << step;
				ASSERT_EQ(*found, it->second) << "key " << key << " at step " << step;
			}
		}
		if (step % 2000 == 0) expectSameContents(map, reference, step);
	}
	expectSameContents(map, reference, -1);
}

TEST(HashMap, InsertOfExistingKeyReplacesTheValue)
{
	btHashMap<btHashInt, int> map;
	map.insert(btHashInt(3), 30);
	map.insert(btHashInt(3), 31);
	EXPECT_EQ(map.size(), 1);
	ASSERT_NE(map.find(btHashInt(3)), nullptr);
	EXPECT_EQ(*map.find(btHashInt(3)), 31);
}

TEST(HashMap, AbsentKeysGiveNullAndMinusOne)
{
	btHashMap<btHashInt, int> map;
	EXPECT_EQ(map[btHashInt(1)], nullptr);
	EXPECT_EQ(map.findIndex(btHashInt(1)), -1);
	map.remove(btHashInt(1));
	map.insert(btHashInt(2), 20);
	EXPECT_EQ(map[btHashInt(1)], nullptr);
	EXPECT_EQ(map.findIndex(btHashInt(1)), -1);
	const btHashMap<btHashInt, int>& constMap = map;
	EXPECT_EQ(constMap[btHashInt(1)], nullptr);
	ASSERT_NE(constMap[btHashInt(2)], nullptr);
	EXPECT_EQ(*constMap[btHashInt(2)], 20);
}

TEST(HashMap, RemoveKeepsEveryOtherEntryFindableInOneLongChain)
{
	btHashMap<CollidingKey, int> map;
	const int count = 200;
	for (int i = 0; i < count; ++i) map.insert(CollidingKey(i), i * 3);
	std::vector<int> order(count);
	for (int i = 0; i < count; ++i) order[i] = i;
	std::shuffle(order.begin(), order.end(), std::mt19937(77));
	std::vector<bool> present(count, true);
	for (int removed = 0; removed < count; ++removed)
	{
		map.remove(CollidingKey(order[removed]));
		present[order[removed]] = false;
		ASSERT_EQ(map.size(), count - removed - 1);
		for (int k = 0; k < count; ++k)
		{
			const int* found = map.find(CollidingKey(k));
			if (present[k])
			{
				ASSERT_NE(found, nullptr) << "key " << k << " lost after removing " << removed + 1 << " keys";
				ASSERT_EQ(*found, k * 3);
			}
			else
			{
				ASSERT_EQ(found, nullptr) << "removed key " << k << " still found";
			}
		}
	}
}

TEST(HashMap, StringKeysAreCopied)
{
	btHashMap<btHashString, int> map;
	char name[16] = "sphere";
	map.insert(btHashString(name), 1);
	map.insert("box", 2);
	name[0] = 'S';  // the map must not see the caller's buffer change
	ASSERT_NE(map.find("sphere"), nullptr);
	EXPECT_EQ(*map.find("sphere"), 1);
	EXPECT_EQ(map.find("Sphere"), nullptr);
	EXPECT_EQ(*map.find("box"), 2);
	EXPECT_STREQ(map.getKeyAtIndex(1).m_string1.c_str(), "box");
	EXPECT_EQ(btHashString("abc").getHash(), btHashString("abc").getHash());
	EXPECT_TRUE(btHashString("abc").equals(btHashString("abc")));
	EXPECT_FALSE(btHashString("abc").equals(btHashString("abd")));
	EXPECT_LT(btHashString("").portableStringCompare("abc", "abd"), 0);
	EXPECT_EQ(btHashString("").portableStringCompare("abc", "abc"), 0);
}

TEST(HashMap, PointerKeysCompareByAddress)
{
	int objects[64];
	btHashMap<btHashPtr, int> map;
	for (int i = 0; i < 64; ++i) map.insert(btHashPtr(&objects[i]), i);
	for (int i = 0; i < 64; i += 2) map.remove(btHashPtr(&objects[i]));
	EXPECT_EQ(map.size(), 32);
	for (int i = 0; i < 64; ++i)
	{
		const int* found = map.find(btHashPtr(&objects[i]));
		if (i % 2 == 0)
			EXPECT_EQ(found, nullptr) << "object " << i;
		else
		{
			ASSERT_NE(found, nullptr) << "object " << i;
			EXPECT_EQ(*found, i);
		}
	}
	EXPECT_EQ(map.getKeyAtIndex(0).getPointer(), static_cast<const void*>(&objects[63]));
}

TEST(HashMap, TypedIntKeysWork)
{
	btHashMap<btHashKey<float>, float> values;
	btHashMap<btHashKeyPtr<int>, int*> pointers;
	int target = 5;
	for (int i = 0; i < 100; ++i)
	{
		values.insert(btHashKey<float>(i), float(i) * 0.5f);
		pointers.insert(btHashKeyPtr<int>(i), &target);
	}
	EXPECT_EQ(*values.find(btHashKey<float>(40)), 20.0f);
	EXPECT_EQ(*pointers[btHashKeyPtr<int>(99)], &target);
	EXPECT_EQ(values.getKeyAtIndex(7).getUid1(), 7);
	EXPECT_EQ(values.find(btHashKey<float>(100)), nullptr);
}

TEST(HashMap, NonTrivialValuesSurviveGrowthAndRemoval)
{
	btHashMap<btHashInt, std::string> map;
	for (int i = 0; i < 1000; ++i) map.insert(i, "value number " + std::to_string(i));
	for (int i = 0; i < 1000; i += 3) map.remove(i);
	for (int i = 0; i < 1000; ++i)
	{
		const std::string* found = map.find(i);
		if (i % 3 == 0)
			ASSERT_EQ(found, nullptr) << "key " << i;
		else
		{
			ASSERT_NE(found, nullptr) << "key " << i;
			ASSERT_EQ(*found, "value number " + std::to_string(i));
		}
	}
}

TEST(HashMap, ClearEmptiesTheMapAndItCanBeReused)
{
	btHashMap<btHashInt, int> map;
	for (int i = 0; i < 100; ++i) map.insert(i, i);
	map.clear();
	EXPECT_EQ(map.size(), 0);
	EXPECT_EQ(map.find(5), nullptr);
	map.insert(5, 50);
	EXPECT_EQ(map.size(), 1);
	EXPECT_EQ(*map.find(5), 50);
}

TEST(HashMap, IntKeysHashToDifferentValues)
{
	// Neighbouring ints should not share a hash (the map re-mixes anyway; this guards the key type).
	std::unordered_map<unsigned int, int> seen;
	for (int i = -1000; i < 1000; ++i) ++seen[btHashInt(i).getHash()];
	EXPECT_EQ(seen.size(), 2000u);
}

#if CALIBER_ASSERTS_ENABLED
TEST(HashMapDeathTest, BadIndexAsserts)
{
	btHashMap<btHashInt, int> map;
	map.insert(1, 1);
	EXPECT_DEATH((void)map.getAtIndex(1), "assertion failed");
	EXPECT_DEATH((void)map.getAtIndex(-1), "assertion failed");
	EXPECT_DEATH((void)map.getKeyAtIndex(2), "assertion failed");
}
#else
TEST(HashMap, BadValueIndexGivesNullInRelease)
{
	btHashMap<btHashInt, int> map;
	map.insert(1, 1);
	EXPECT_EQ(map.getAtIndex(1), nullptr);
	EXPECT_EQ(map.getAtIndex(-1), nullptr);
}
#endif

namespace
{
// A user map written against Bullet 2.89's protected interface: it walks the bucket chains itself.
class ChainCountingMap : public btHashMap<btHashInt, int>
{
public:
	// Entries reachable from the bucket heads through m_next; each entry is in exactly one chain.
	int reachableEntries() const
	{
		int reached = 0;
		for (int b = 0; b < m_hashTable.size(); ++b)
			for (int i = m_hashTable[b]; i >= 0; i = m_next[i]) ++reached;
		return reached;
	}
	int bucketCount() const { return m_hashTable.size(); }
	int keyOfEntry(int i) const { return m_keyArray[i].getUid1(); }
	void grow() { growTables(btHashInt(0)); }
};
}  // namespace

TEST(HashMap, SubclassSeesBulletsProtectedChainsAndGrowTables)
{
	ChainCountingMap map;
	EXPECT_EQ(map.reachableEntries(), 0);
	for (int k = 0; k < 100; ++k) map.insert(btHashInt(k * 7), k);
	EXPECT_EQ(map.reachableEntries(), 100) << "every entry hangs in one bucket chain";
	EXPECT_GE(map.bucketCount(), 100) << "load factor at most 1";
	EXPECT_EQ(map.keyOfEntry(5), 35) << "m_keyArray holds the keys in insertion order";
	const int buckets = map.bucketCount();
	map.grow();
	EXPECT_EQ(map.bucketCount(), buckets) << "growTables leaves a big enough table alone";
	for (int k = 0; k < 100; k += 2) map.remove(btHashInt(k * 7));
	EXPECT_EQ(map.reachableEntries(), 50);
	for (int k = 1; k < 100; k += 2) ASSERT_NE(map.find(btHashInt(k * 7)), nullptr) << k;
}
