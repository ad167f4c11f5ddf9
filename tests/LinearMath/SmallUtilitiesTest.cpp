// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Bullet 2's small LinearMath utilities: the intrusive list btGEN_List keeps its order through
// insertions and removals, and btCpuFeatureUtility reports only the bits it defines, agreeing with the
// instruction sets the build itself requires.

#include <gtest/gtest.h>

#include <vector>

#include "LinearMath/btCpuFeatureUtility.h"
#include "LinearMath/btList.h"

namespace
{
struct Item : btGEN_Link
{
	int value;
	explicit Item(int v) : value(v) {}
};

std::vector<int> contents(const btGEN_List& list)
{
	std::vector<int> values;
	for (btGEN_Link* link = list.getHead(); !link->isTail(); link = link->getNext())
		values.push_back(static_cast<Item*>(link)->value);
	return values;
}
}  // namespace

TEST(GenList, KeepsOrderThroughInsertionAndRemoval)
{
	btGEN_List list;
	EXPECT_TRUE(list.getHead()->isTail()) << "an empty list's first link is the tail sentinel";
	EXPECT_TRUE(list.getTail()->isHead());
	Item one(1), two(2), three(3), four(4);
	list.addTail(&two);
	list.addHead(&one);
	list.addTail(&four);
	three.insertBefore(&four);
	EXPECT_EQ(contents(list), (std::vector<int>{1, 2, 3, 4}));
	two.remove();
	EXPECT_EQ(contents(list), (std::vector<int>{1, 3, 4}));
	one.remove();
	four.remove();
	EXPECT_EQ(contents(list), (std::vector<int>{3}));
	EXPECT_EQ(list.getHead(), list.getTail());
}

TEST(CpuFeatureUtility, ReportsOnlyItsOwnBitsAndWhatTheBuildRequires)
{
	const int features = btCpuFeatureUtility::getCpuFeatures();
	const int known = btCpuFeatureUtility::CPU_FEATURE_FMA3 | btCpuFeatureUtility::CPU_FEATURE_SSE4_1 |
	                  btCpuFeatureUtility::CPU_FEATURE_NEON_HPFP;
	EXPECT_EQ(features & ~known, 0);
	EXPECT_EQ(features, btCpuFeatureUtility::getCpuFeatures()) << "found once, the same every time";
#if defined(__SSE4_1__)
	// A build that requires SSE4.1 runs only where the processor has it.
	EXPECT_TRUE(features & btCpuFeatureUtility::CPU_FEATURE_SSE4_1);
#endif
}
