// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btQuickprof.h"

#include <gtest/gtest.h>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

// These tests never assert that something took longer than a fixed time. Where an order of times
// is needed, the longer zone waits until the clock has passed the shorter zone's measured total.

namespace
{
// Zone names are compared by pointer, so each name is one object used everywhere.
const char kOuter[] = "outer";
const char kInner[] = "inner";
const char kSecond[] = "second";
const char kRecursive[] = "recursive";

// Fresh tree for the calling thread, whatever earlier tests in this process left behind.
class QuickprofTest : public ::testing::Test
{
protected:
	void SetUp() override
	{
		btSetCustomEnterProfileZoneFunc(nullptr);
		btSetCustomLeaveProfileZoneFunc(nullptr);
		CProfileManager::CleanupMemory();
		CProfileManager::Reset();
	}
	void TearDown() override
	{
		btSetCustomEnterProfileZoneFunc(nullptr);
		btSetCustomLeaveProfileZoneFunc(nullptr);
		CProfileManager::CleanupMemory();
	}
};

// Spins until at least the given number of nanoseconds have passed on the profiler's clock.
void spinFor(unsigned long long nanoseconds)
{
	btClock clock;
	while (clock.getTimeNanoseconds() <= nanoseconds)
	{
	}
}

void recurse(int depth)
{
	BT_PROFILE(kRecursive);
	if (depth > 1) recurse(depth - 1);
}

// Returns the number of children of the iterator's parent, leaving the iterator on the first one.
int countChildren(CProfileIterator* it)
{
	int count = 0;
	for (it->First(); !it->Is_Done(); it->Next()) ++count;
	it->First();
	return count;
}

// Checks, for every node below the iterator's parent, that each child took no longer than its
// parent and that the children together took no longer than the parent (with float-sum slack).
// The root has no time of its own; its span is the time since the last reset, read after all zones
// closed.
void expectChildrenWithinParent(CProfileIterator* it)
{
	const float parentMs =
	    it->Is_Root() ? CProfileManager::Get_Time_Since_Reset() : it->Get_Current_Parent_Total_Time();
	float sumMs = 0.0f;
	int count = 0;
	for (it->First(); !it->Is_Done(); it->Next(), ++count)
	{
		const float childMs = it->Get_Current_Total_Time();
		EXPECT_GE(childMs, 0.0f) << it->Get_Current_Name();
		// Totals are integer nanoseconds of nested intervals on one monotonic clock, and the
		// conversion to float ms is monotonic, so a child never exceeds its parent: no slack.
		EXPECT_LE(childMs, parentMs) << it->Get_Current_Name();
		sumMs += childMs;
	}
	// The float sum of the rounded child totals may exceed the rounded parent total by a few ulps
	// per addend; 1e-5 relative (about 100 float ulps) covers any realistic number of children.
	EXPECT_LE(sumMs, parentMs * (1.0f + 1e-5f) + 1e-9f) << it->Get_Current_Parent_Name();
	for (int i = 0; i < count; ++i)
	{
		it->Enter_Child(i);
		expectChildrenWithinParent(it);
		it->Enter_Parent();
	}
}
}  // namespace

TEST_F(QuickprofTest, NestedZonesBuildMatchingTree)
{
	{
		BT_PROFILE(kOuter);
		{
			BT_PROFILE(kInner);
		}
		{
			BT_PROFILE(kSecond);
		}
	}
	CProfileIterator* it = CProfileManager::Get_Iterator();
	ASSERT_NE(it, nullptr);
	EXPECT_TRUE(it->Is_Root());
	ASSERT_EQ(countChildren(it), 1);
	EXPECT_EQ(it->Get_Current_Name(), kOuter);
	EXPECT_EQ(it->Get_Current_Total_Calls(), 1);

	it->Enter_Child(0);
	EXPECT_FALSE(it->Is_Root());
	EXPECT_EQ(it->Get_Current_Parent_Name(), kOuter);
	ASSERT_EQ(countChildren(it), 2);
	// Children are listed in the order they were first entered.
	EXPECT_EQ(it->Get_Current_Name(), kInner);
	it->Next();
	EXPECT_EQ(it->Get_Current_Name(), kSecond);
	it->Next();
	EXPECT_TRUE(it->Is_Done());

	it->Enter_Child(0);
	EXPECT_EQ(it->Get_Current_Parent_Name(), kInner);
	EXPECT_TRUE(it->Is_Done());  // a leaf has no children
	CProfileManager::Release_Iterator(it);
}

TEST_F(QuickprofTest, CallCountsAccumulateOverRepeatedEntries)
{
	for (int i = 0; i < 5; ++i)
	{
		BT_PROFILE(kOuter);
		for (int j = 0; j < 3; ++j)
		{
			BT_PROFILE(kInner);
		}
	}
	CProfileIterator* it = CProfileManager::Get_Iterator();
	ASSERT_EQ(countChildren(it), 1);
	EXPECT_EQ(it->Get_Current_Total_Calls(), 5);
	it->Enter_Child(0);
	EXPECT_EQ(it->Get_Current_Parent_Total_Calls(), 5);
	ASSERT_EQ(countChildren(it), 1);
	EXPECT_EQ(it->Get_Current_Name(), kInner);
	EXPECT_EQ(it->Get_Current_Total_Calls(), 15);
	CProfileManager::Release_Iterator(it);
}

TEST_F(QuickprofTest, RecursionOfSameNameCountsCallsOnOneNode)
{
	recurse(4);
	recurse(2);
	CProfileIterator* it = CProfileManager::Get_Iterator();
	ASSERT_EQ(countChildren(it), 1);
	EXPECT_EQ(it->Get_Current_Name(), kRecursive);
	EXPECT_EQ(it->Get_Current_Total_Calls(), 6);
	it->Enter_Child(0);
	EXPECT_TRUE(it->Is_Done()) << "recursion must not create a child node";
	CProfileManager::Release_Iterator(it);

	// Every open zone was closed: a new zone lands at the root again.
	{
		BT_PROFILE(kOuter);
	}
	it = CProfileManager::Get_Iterator();
	EXPECT_EQ(countChildren(it), 2);
	CProfileManager::Release_Iterator(it);
}

TEST_F(QuickprofTest, NamesAreComparedByPointerNotByText)
{
	static const char firstCopy[] = "same";
	static const char secondCopy[] = "same";
	CProfileManager::Start_Profile(firstCopy);
	CProfileManager::Stop_Profile();
	CProfileManager::Start_Profile(secondCopy);
	CProfileManager::Stop_Profile();
	CProfileIterator* it = CProfileManager::Get_Iterator();
	ASSERT_EQ(countChildren(it), 2);
	EXPECT_EQ(it->Get_Current_Name(), firstCopy);
	it->Next();
	EXPECT_EQ(it->Get_Current_Name(), secondCopy);
	CProfileManager::Release_Iterator(it);
}

TEST_F(QuickprofTest, TimesAreNonNegativeAndChildrenNeverExceedParent)
{
	static const char* const kLeaves[] = {"leafA", "leafB", "leafC"};
	for (int frame = 0; frame < 20; ++frame)
	{
		BT_PROFILE(kOuter);
		for (const char* leaf : kLeaves)
		{
			BT_PROFILE(kInner);
			{
				BT_PROFILE(leaf);
				spinFor(1000);
			}
			spinFor(500);
		}
		recurse(3);
		CProfileManager::Increment_Frame_Counter();
	}
	CProfileIterator* it = CProfileManager::Get_Iterator();
	expectChildrenWithinParent(it);
	it->First();
	EXPECT_GT(it->Get_Current_Total_Time(), 0.0f);  // 20 frames of spinning take more than 0 ns
	EXPECT_GE(CProfileManager::Get_Time_Since_Reset(), 0.0f);
	EXPECT_EQ(CProfileManager::Get_Frame_Count_Since_Reset(), 20);
	CProfileManager::Release_Iterator(it);
}

TEST_F(QuickprofTest, IteratorNavigationStaysInsideTheTree)
{
	{
		BT_PROFILE(kOuter);
		BT_PROFILE(kInner);  // two samples in one scope nest in order
	}
	{
		BT_PROFILE(kSecond);
	}
	CProfileIterator* it = CProfileManager::Get_Iterator();
	ASSERT_EQ(countChildren(it), 2);

	// Out-of-range and negative indices leave the position unchanged.
	it->Enter_Child(2);
	EXPECT_TRUE(it->Is_Root());
	it->Enter_Child(-1);
	EXPECT_TRUE(it->Is_Root());
	// Enter_Parent at the root stays at the root.
	it->Enter_Parent();
	EXPECT_TRUE(it->Is_Root());
	EXPECT_EQ(it->Get_Current_Name(), kOuter);

	it->Enter_Child(1);
	EXPECT_EQ(it->Get_Current_Parent_Name(), kSecond);
	it->Enter_Parent();
	EXPECT_TRUE(it->Is_Root());
	it->Enter_Child(0);
	ASSERT_EQ(countChildren(it), 1);
	EXPECT_EQ(it->Get_Current_Name(), kInner);
	it->Enter_Child(0);
	it->Enter_Parent();
	EXPECT_EQ(it->Get_Current_Parent_Name(), kOuter);

	// Past the last child, the current-child accessors return neutral values.
	it->Next();
	ASSERT_TRUE(it->Is_Done());
	it->Next();
	EXPECT_TRUE(it->Is_Done());
	EXPECT_STREQ(it->Get_Current_Name(), "");
	EXPECT_EQ(it->Get_Current_Total_Calls(), 0);
	EXPECT_EQ(it->Get_Current_Total_Time(), 0.0f);
	EXPECT_EQ(it->Get_Current_UserPointer(), nullptr);
	it->Set_Current_UserPointer(it);  // ignored
	CProfileManager::Release_Iterator(it);
}

TEST_F(QuickprofTest, EnterLargestChildPicksTheLongestZone)
{
	{
		BT_PROFILE(kOuter);
		{
			BT_PROFILE(kInner);
		}
	}
	CProfileIterator* it = CProfileManager::Get_Iterator();
	it->Enter_Child(0);
	it->First();
	const float innerMs = it->Get_Current_Total_Time();
	CProfileManager::Release_Iterator(it);
	{
		BT_PROFILE(kOuter);
		{
			BT_PROFILE(kSecond);
			// Lasts longer than everything "inner" has accumulated, so "second" must win.
			spinFor(static_cast<unsigned long long>(double(innerMs) * 1e6) + 1000000ull);
		}
	}
	it = CProfileManager::Get_Iterator();
	it->Enter_Largest_Child();
	EXPECT_EQ(it->Get_Current_Parent_Name(), kOuter);
	it->Enter_Largest_Child();
	EXPECT_EQ(it->Get_Current_Parent_Name(), kSecond);
	it->Enter_Largest_Child();  // a leaf: no effect
	EXPECT_EQ(it->Get_Current_Parent_Name(), kSecond);
	CProfileManager::Release_Iterator(it);
}

TEST_F(QuickprofTest, UserPointerIsStoredPerNode)
{
	{
		BT_PROFILE(kOuter);
	}
	{
		BT_PROFILE(kSecond);
	}
	int marker = 0;
	CProfileIterator* it = CProfileManager::Get_Iterator();
	EXPECT_EQ(it->Get_Current_UserPointer(), nullptr);
	it->Set_Current_UserPointer(&marker);
	it->Next();
	EXPECT_EQ(it->Get_Current_UserPointer(), nullptr);
	it->First();
	EXPECT_EQ(it->Get_Current_UserPointer(), &marker);
	CProfileManager::Release_Iterator(it);
}

TEST_F(QuickprofTest, ResetZeroesCountsButKeepsNodes)
{
	for (int i = 0; i < 3; ++i)
	{
		BT_PROFILE(kOuter);
		BT_PROFILE(kInner);
		CProfileManager::Increment_Frame_Counter();
	}
	EXPECT_EQ(CProfileManager::Get_Frame_Count_Since_Reset(), 3);
	CProfileManager::Reset();
	EXPECT_EQ(CProfileManager::Get_Frame_Count_Since_Reset(), 0);

	CProfileIterator* it = CProfileManager::Get_Iterator();
	ASSERT_EQ(countChildren(it), 1);
	EXPECT_EQ(it->Get_Current_Name(), kOuter);
	EXPECT_EQ(it->Get_Current_Total_Calls(), 0);
	EXPECT_EQ(it->Get_Current_Total_Time(), 0.0f);
	it->Enter_Child(0);
	ASSERT_EQ(countChildren(it), 1);
	EXPECT_EQ(it->Get_Current_Total_Calls(), 0);
	EXPECT_EQ(it->Get_Current_Total_Time(), 0.0f);
	CProfileManager::Release_Iterator(it);

	// The same nodes count again after the reset.
	{
		BT_PROFILE(kOuter);
	}
	it = CProfileManager::Get_Iterator();
	ASSERT_EQ(countChildren(it), 1);
	EXPECT_EQ(it->Get_Current_Total_Calls(), 1);
	CProfileManager::Release_Iterator(it);
}

TEST_F(QuickprofTest, ResetInsideAnOpenZoneKeepsTheTreeConsistent)
{
	{
		BT_PROFILE(kOuter);
		{
			BT_PROFILE(kInner);
			CProfileManager::Reset();
		}
		{
			BT_PROFILE(kSecond);
		}
	}
	CProfileIterator* it = CProfileManager::Get_Iterator();
	ASSERT_EQ(countChildren(it), 1);
	EXPECT_EQ(it->Get_Current_Total_Calls(), 0);  // the call was counted before the reset
	it->Enter_Child(0);
	ASSERT_EQ(countChildren(it), 2);
	EXPECT_EQ(it->Get_Current_Total_Calls(), 0);
	it->Next();
	EXPECT_EQ(it->Get_Current_Total_Calls(), 1);
	CProfileManager::Release_Iterator(it);
	it = CProfileManager::Get_Iterator();
	expectChildrenWithinParent(it);
	CProfileManager::Release_Iterator(it);
}

TEST_F(QuickprofTest, CleanupMemoryRemovesAllNodes)
{
	{
		BT_PROFILE(kOuter);
		BT_PROFILE(kInner);
	}
	CProfileManager::CleanupMemory();
	CProfileIterator* it = CProfileManager::Get_Iterator();
	EXPECT_TRUE(it->Is_Done());
	CProfileManager::Release_Iterator(it);
}

TEST_F(QuickprofTest, UnbalancedStopIsIgnored)
{
	CProfileManager::Stop_Profile();
	CProfileManager::Stop_Profile();
	{
		BT_PROFILE(kOuter);
	}
	CProfileManager::Stop_Profile();
	{
		BT_PROFILE(kSecond);
	}
	CProfileIterator* it = CProfileManager::Get_Iterator();
	EXPECT_EQ(countChildren(it), 2);  // both zones are still children of the root
	CProfileManager::Release_Iterator(it);
	CProfileManager::Release_Iterator(nullptr);
}

namespace
{
std::vector<std::string>* gHookLog = nullptr;
void recordEnter(const char* name) { gHookLog->push_back(std::string("enter ") + name); }
void recordLeave() { gHookLog->push_back("leave"); }
}  // namespace

TEST_F(QuickprofTest, CustomEnterAndLeaveHooksReplaceTheProfiler)
{
	std::vector<std::string> log;
	gHookLog = &log;
	btSetCustomEnterProfileZoneFunc(&recordEnter);
	btSetCustomLeaveProfileZoneFunc(&recordLeave);
	EXPECT_EQ(btGetCurrentEnterProfileZoneFunc(), &recordEnter);
	EXPECT_EQ(btGetCurrentLeaveProfileZoneFunc(), &recordLeave);
	{
		BT_PROFILE(kOuter);
		{
			CProfileSample sample(kInner);
		}
	}
	const std::vector<std::string> expected = {"enter outer", "enter inner", "leave", "leave"};
	EXPECT_EQ(log, expected);

	// The built-in profiler did not see those zones.
	CProfileIterator* it = CProfileManager::Get_Iterator();
	EXPECT_TRUE(it->Is_Done());
	CProfileManager::Release_Iterator(it);

	// Null restores the built-in functions.
	btSetCustomEnterProfileZoneFunc(nullptr);
	btSetCustomLeaveProfileZoneFunc(nullptr);
	EXPECT_NE(btGetCurrentEnterProfileZoneFunc(), &recordEnter);
	EXPECT_NE(btGetCurrentLeaveProfileZoneFunc(), &recordLeave);
	{
		BT_PROFILE(kOuter);
	}
	EXPECT_EQ(log.size(), expected.size());
	it = CProfileManager::Get_Iterator();
	EXPECT_EQ(countChildren(it), 1);
	CProfileManager::Release_Iterator(it);
	gHookLog = nullptr;
}

TEST_F(QuickprofTest, DumpAllReportsEveryZoneName)
{
	for (int frame = 0; frame < 2; ++frame)
	{
		BT_PROFILE(kOuter);
		{
			BT_PROFILE(kInner);
		}
		{
			BT_PROFILE(kSecond);
		}
		CProfileManager::Increment_Frame_Counter();
	}
	testing::internal::CaptureStdout();
	CProfileManager::dumpAll();
	const std::string report = testing::internal::GetCapturedStdout();
	EXPECT_NE(report.find("outer"), std::string::npos) << report;
	EXPECT_NE(report.find("inner"), std::string::npos) << report;
	EXPECT_NE(report.find("second"), std::string::npos) << report;
	EXPECT_NE(report.find("2 calls"), std::string::npos) << report;
	EXPECT_NE(report.find("% of parent"), std::string::npos) << report;
	EXPECT_NE(report.find("ms/frame"), std::string::npos) << report;
	// Deeper zones are indented further than their parents.
	const size_t outerLine = report.rfind('\n', report.find("outer"));
	const size_t innerLine = report.rfind('\n', report.find("inner"));
	ASSERT_NE(outerLine, std::string::npos);
	ASSERT_NE(innerLine, std::string::npos);
	EXPECT_GT(report.find_first_not_of(' ', innerLine + 1) - innerLine,
	          report.find_first_not_of(' ', outerLine + 1) - outerLine)
	    << report;

	// An iterator left where it was, and an empty tree prints nothing.
	CProfileIterator* it = CProfileManager::Get_Iterator();
	it->Enter_Child(0);
	testing::internal::CaptureStdout();
	CProfileManager::dumpRecursive(it, 2);
	const std::string subReport = testing::internal::GetCapturedStdout();
	EXPECT_EQ(subReport.find("second"), subReport.rfind("second")) << subReport;
	EXPECT_EQ(it->Get_Current_Parent_Name(), kOuter);
	CProfileManager::Release_Iterator(it);

	CProfileManager::CleanupMemory();
	testing::internal::CaptureStdout();
	CProfileManager::dumpAll();
	EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
}

TEST_F(QuickprofTest, EachThreadProfilesIntoItsOwnTree)
{
	const int kThreads = 4;
	static const char* const kThreadZones[kThreads] = {"thread0", "thread1", "thread2", "thread3"};
	{
		BT_PROFILE(kOuter);
	}
	std::vector<unsigned> indices(kThreads);
	std::vector<int> rootChildren(kThreads), calls(kThreads);
	std::vector<const char*> names(kThreads);
	std::vector<std::thread> threads;
	for (int t = 0; t < kThreads; ++t)
	{
		threads.emplace_back(
		    [&, t]
		    {
			    indices[t] = btQuickprofGetCurrentThreadIndex2();
			    // A fresh tree per thread slot (a reused slot keeps earlier totals).
			    CProfileManager::CleanupMemory();
			    for (int i = 0; i < 1000; ++i)
			    {
				    BT_PROFILE(kThreadZones[t]);
				    BT_PROFILE(kInner);
			    }
			    CProfileIterator* it = CProfileManager::Get_Iterator();
			    rootChildren[t] = countChildren(it);
			    names[t] = it->Get_Current_Name();
			    calls[t] = it->Get_Current_Total_Calls();
			    CProfileManager::Release_Iterator(it);
		    });
	}
	for (int i = 0; i < 1000; ++i)
	{
		BT_PROFILE(kSecond);  // the main thread profiles at the same time
	}
	for (std::thread& thread : threads) thread.join();

	const unsigned mainIndex = btQuickprofGetCurrentThreadIndex2();
	// Some threads may have finished before others started and reused their slot, so only the
	// main thread's slot is guaranteed distinct from each worker's.
	for (int t = 0; t < kThreads; ++t)
	{
		EXPECT_NE(indices[t], mainIndex);
		EXPECT_LT(indices[t], unsigned(BT_QUICKPROF_MAX_THREAD_COUNT));
		EXPECT_EQ(rootChildren[t], 1);
		EXPECT_EQ(names[t], kThreadZones[t]);
		EXPECT_EQ(calls[t], 1000);
	}
	CProfileIterator* it = CProfileManager::Get_Iterator();
	ASSERT_EQ(countChildren(it), 2);
	EXPECT_EQ(it->Get_Current_Name(), kOuter);
	it->Next();
	EXPECT_EQ(it->Get_Current_Name(), kSecond);
	EXPECT_EQ(it->Get_Current_Total_Calls(), 1000);
	CProfileManager::Release_Iterator(it);
}

TEST_F(QuickprofTest, ThreadsBeyondTheSlotLimitAreSkippedSafely)
{
	const int kThreads = BT_QUICKPROF_MAX_THREAD_COUNT + 4;
	std::mutex mutex;
	std::condition_variable allArrived;
	int arrived = 0;
	std::vector<unsigned> indices(kThreads);
	std::vector<int> hadIterator(kThreads);
	std::vector<std::thread> threads;
	for (int t = 0; t < kThreads; ++t)
	{
		threads.emplace_back(
		    [&, t]
		    {
			    indices[t] = btQuickprofGetCurrentThreadIndex2();
			    {
				    // Every thread holds its slot until all have asked, so the table must overflow.
				    std::unique_lock<std::mutex> lock(mutex);
				    if (++arrived == kThreads) allArrived.notify_all();
				    allArrived.wait(lock, [&] { return arrived == kThreads; });
			    }
			    {
				    BT_PROFILE(kOuter);
			    }
			    CProfileIterator* it = CProfileManager::Get_Iterator();
			    hadIterator[t] = it != nullptr;
			    CProfileManager::Release_Iterator(it);
			    CProfileManager::dumpRecursive(nullptr, 0);
		    });
	}
	for (std::thread& thread : threads) thread.join();

	std::set<unsigned> slotted;
	int skipped = 0;
	for (int t = 0; t < kThreads; ++t)
	{
		if (indices[t] == unsigned(BT_QUICKPROF_MAX_THREAD_COUNT))
		{
			++skipped;
			EXPECT_FALSE(hadIterator[t]);
		}
		else
		{
			EXPECT_LT(indices[t], unsigned(BT_QUICKPROF_MAX_THREAD_COUNT));
			EXPECT_TRUE(slotted.insert(indices[t]).second) << "slot " << indices[t] << " given twice";
			EXPECT_TRUE(hadIterator[t]);
		}
	}
	EXPECT_GE(skipped, 4);

	// The slots came back when those threads exited.
	unsigned laterIndex = 0;
	std::thread later([&] { laterIndex = btQuickprofGetCurrentThreadIndex2(); });
	later.join();
	EXPECT_LT(laterIndex, unsigned(BT_QUICKPROF_MAX_THREAD_COUNT));
}

TEST(QuickprofClockTest, ReadingsNeverDecreaseAndResetRestarts)
{
	btClock earlier;
	btClock clock;
	unsigned long long previous = 0;
	for (int i = 0; i < 1000; ++i)
	{
		const unsigned long long now = clock.getTimeNanoseconds();
		EXPECT_GE(now, previous);
		previous = now;
	}
	EXPECT_GE(clock.getTimeSeconds(), btScalar(0));

	btClock copy(clock);
	const unsigned long long beforeCopyRead = clock.getTimeNanoseconds();
	EXPECT_GE(copy.getTimeNanoseconds(), beforeCopyRead);  // the copy shares the start time

	clock.reset();
	// Read the reset clock first: the older clock started earlier and is read later.
	const unsigned long long sinceReset = clock.getTimeMicroseconds();
	EXPECT_GE(earlier.getTimeMicroseconds(), sinceReset);
	const unsigned long long sinceResetMs = clock.getTimeMilliseconds();
	EXPECT_GE(earlier.getTimeMilliseconds(), sinceResetMs);

	btClock assigned;
	assigned = earlier;
	const unsigned long long earlierNs = earlier.getTimeNanoseconds();
	EXPECT_GE(assigned.getTimeNanoseconds(), earlierNs);
}
