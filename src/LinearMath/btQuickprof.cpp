// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btQuickprof.h"

#include <atomic>
#include <chrono>
#include <mutex>
#include <stdio.h>

// Threading design: every thread that profiles owns one slot, and a slot owns one tree. Only the
// owning thread reads or writes its tree, so the hot path (Start_Profile / Stop_Profile) takes no
// lock. The slot table is guarded by a mutex that is taken only when a thread first profiles and
// when it exits; that lock also orders the previous owner's writes before the next owner's reads.
// Shared counters (frame count, reset time) and the hook pointers are atomics.

namespace
{
long long steadyNowNanoseconds()
{
	return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
	    .count();
}

// The root's name is a private pointer, so no user zone can ever be taken for the root.
const char kRootName[] = "Root";

struct ThreadProfile
{
	CProfileNode root{kRootName, nullptr};
	CProfileNode* current = &root;
};

ThreadProfile* threadProfiles()
{
	// Function-local so that it is built on first use, whatever the static initialisation order.
	static ThreadProfile profiles[BT_QUICKPROF_MAX_THREAD_COUNT];
	return profiles;
}

std::mutex gSlotMutex;
bool gSlotTaken[BT_QUICKPROF_MAX_THREAD_COUNT];

const unsigned kSlotUnassigned = ~0u;
const unsigned kNoSlot = BT_QUICKPROF_MAX_THREAD_COUNT;

// Hands the slot back when its thread exits, so that short-lived threads do not use up the table.
struct ThreadSlot
{
	unsigned index = kSlotUnassigned;
	~ThreadSlot()
	{
		if (index < kNoSlot)
		{
			std::lock_guard<std::mutex> lock(gSlotMutex);
			gSlotTaken[index] = false;
		}
	}
};
thread_local ThreadSlot tThreadSlot;

std::atomic<long long>& resetTimeNanoseconds()
{
	static std::atomic<long long> resetTime{steadyNowNanoseconds()};
	return resetTime;
}

unsigned acquireSlot()
{
	resetTimeNanoseconds();  // the time since reset counts from the first use of the profiler
	std::lock_guard<std::mutex> lock(gSlotMutex);
	for (unsigned i = 0; i < kNoSlot; ++i)
	{
		if (!gSlotTaken[i])
		{
			gSlotTaken[i] = true;
			// A reused tree keeps its totals, but a zone left open by the previous owner is abandoned.
			ThreadProfile& profile = threadProfiles()[i];
			profile.current = &profile.root;
			return i;
		}
	}
	return kNoSlot;
}

// The calling thread's tree, or null when the slot table was full when the thread first profiled.
ThreadProfile* currentThreadProfile()
{
	const unsigned index = btQuickprofGetCurrentThreadIndex2();
	return index < kNoSlot ? &threadProfiles()[index] : nullptr;
}

std::atomic<int> gFrameCounter{0};

void enterProfileZoneDefault(const char* name) { CProfileManager::Start_Profile(name); }
void leaveProfileZoneDefault() { CProfileManager::Stop_Profile(); }

std::atomic<btEnterProfileZoneFunc*> gEnterProfileZoneFunc{&enterProfileZoneDefault};
std::atomic<btLeaveProfileZoneFunc*> gLeaveProfileZoneFunc{&leaveProfileZoneDefault};

const char* printableName(const char* name) { return name ? name : "(unnamed)"; }
}  // namespace

// ---- btClock --------------------------------------------------------------------------------------

btClock::btClock() : m_startNanoseconds(steadyNowNanoseconds()) {}
btClock::btClock(const btClock& other) : m_startNanoseconds(other.m_startNanoseconds) {}
btClock& btClock::operator=(const btClock& other)
{
	m_startNanoseconds = other.m_startNanoseconds;
	return *this;
}
btClock::~btClock() {}

void btClock::reset() { m_startNanoseconds = steadyNowNanoseconds(); }

unsigned long long int btClock::getTimeNanoseconds()
{
	const long long elapsed = steadyNowNanoseconds() - m_startNanoseconds;
	return elapsed > 0 ? static_cast<unsigned long long>(elapsed) : 0ull;
}
unsigned long long int btClock::getTimeMicroseconds() { return getTimeNanoseconds() / 1000ull; }
unsigned long long int btClock::getTimeMilliseconds() { return getTimeNanoseconds() / 1000000ull; }
btScalar btClock::getTimeSeconds() { return btScalar(getTimeMicroseconds()) * btScalar(1e-6); }

// ---- hooks ----------------------------------------------------------------------------------------

btEnterProfileZoneFunc* btGetCurrentEnterProfileZoneFunc() { return gEnterProfileZoneFunc.load(); }
btLeaveProfileZoneFunc* btGetCurrentLeaveProfileZoneFunc() { return gLeaveProfileZoneFunc.load(); }
void btSetCustomEnterProfileZoneFunc(btEnterProfileZoneFunc* enterFunc)
{
	gEnterProfileZoneFunc.store(enterFunc ? enterFunc : &enterProfileZoneDefault);
}
void btSetCustomLeaveProfileZoneFunc(btLeaveProfileZoneFunc* leaveFunc)
{
	gLeaveProfileZoneFunc.store(leaveFunc ? leaveFunc : &leaveProfileZoneDefault);
}

unsigned int btQuickprofGetCurrentThreadIndex2()
{
	ThreadSlot& slot = tThreadSlot;
	if (slot.index == kSlotUnassigned) slot.index = acquireSlot();
	return slot.index;
}

// ---- CProfileNode ---------------------------------------------------------------------------------

CProfileNode::CProfileNode(const char* name, CProfileNode* parent)
    : Name(name),
      TotalCalls(0),
      TotalNanoseconds(0),
      StartNanoseconds(0),
      RecursionCounter(0),
      Parent(parent),
      Child(nullptr),
      Sibling(nullptr),
      m_userPtr(nullptr)
{
}

CProfileNode::~CProfileNode() { CleanupMemory(); }

void CProfileNode::CleanupMemory()
{
	// Siblings are walked in a loop and only children recurse, so the stack grows with the tree's
	// depth, not with the number of zones at one level.
	CProfileNode* child = Child;
	Child = nullptr;
	while (child)
	{
		CProfileNode* next = child->Sibling;
		delete child;
		child = next;
	}
}

CProfileNode* CProfileNode::Get_Sub_Node(const char* name)
{
	CProfileNode* last = nullptr;
	for (CProfileNode* child = Child; child; child = child->Sibling)
	{
		if (child->Name == name) return child;
		last = child;
	}
	// Appended, so that iteration and reports follow the order in which zones were first entered.
	CProfileNode* node = new CProfileNode(name, this);
	if (last)
		last->Sibling = node;
	else
		Child = node;
	return node;
}

void CProfileNode::Reset()
{
	TotalCalls = 0;
	TotalNanoseconds = 0;
	// A zone open across the reset counts only the time after it. Parents restart before their
	// children, so a child's time still never exceeds its parent's.
	if (RecursionCounter > 0) StartNanoseconds = static_cast<unsigned long long>(steadyNowNanoseconds());
	for (CProfileNode* child = Child; child; child = child->Sibling) child->Reset();
}

void CProfileNode::Call()
{
	++TotalCalls;
	if (RecursionCounter++ == 0) StartNanoseconds = static_cast<unsigned long long>(steadyNowNanoseconds());
}

bool CProfileNode::Return()
{
	if (RecursionCounter <= 0) return false;  // unbalanced: nothing open
	if (--RecursionCounter != 0) return false;
	const unsigned long long now = static_cast<unsigned long long>(steadyNowNanoseconds());
	if (now > StartNanoseconds) TotalNanoseconds += now - StartNanoseconds;
	return true;
}

float CProfileNode::Get_Total_Time() { return static_cast<float>(double(TotalNanoseconds) * 1e-6); }

// ---- CProfileIterator -----------------------------------------------------------------------------

CProfileIterator::CProfileIterator(CProfileNode* start) : CurrentParent(start), CurrentChild(start->Get_Child()) {}

void CProfileIterator::First() { CurrentChild = CurrentParent->Get_Child(); }
void CProfileIterator::Next()
{
	if (CurrentChild) CurrentChild = CurrentChild->Get_Sibling();
}
bool CProfileIterator::Is_Done() { return CurrentChild == nullptr; }

void CProfileIterator::Enter_Child(int index)
{
	if (index < 0) return;
	CProfileNode* child = CurrentParent->Get_Child();
	while (child && index > 0)
	{
		child = child->Get_Sibling();
		--index;
	}
	if (!child) return;
	CurrentParent = child;
	CurrentChild = child->Get_Child();
}

void CProfileIterator::Enter_Largest_Child()
{
	CProfileNode* largest = nullptr;
	for (CProfileNode* child = CurrentParent->Get_Child(); child; child = child->Get_Sibling())
	{
		if (!largest || child->Get_Total_Time() > largest->Get_Total_Time()) largest = child;
	}
	if (!largest) return;
	CurrentParent = largest;
	CurrentChild = largest->Get_Child();
}

void CProfileIterator::Enter_Parent()
{
	if (CurrentParent->Get_Parent()) CurrentParent = CurrentParent->Get_Parent();
	CurrentChild = CurrentParent->Get_Child();
}

const char* CProfileIterator::Get_Current_Name() { return CurrentChild ? CurrentChild->Get_Name() : ""; }
int CProfileIterator::Get_Current_Total_Calls() { return CurrentChild ? CurrentChild->Get_Total_Calls() : 0; }
float CProfileIterator::Get_Current_Total_Time() { return CurrentChild ? CurrentChild->Get_Total_Time() : 0.0f; }
void* CProfileIterator::Get_Current_UserPointer() { return CurrentChild ? CurrentChild->GetUserPointer() : nullptr; }
void CProfileIterator::Set_Current_UserPointer(void* ptr)
{
	if (CurrentChild) CurrentChild->SetUserPointer(ptr);
}

// ---- CProfileManager ------------------------------------------------------------------------------

void CProfileManager::Start_Profile(const char* name)
{
	ThreadProfile* profile = currentThreadProfile();
	if (!profile) return;
	// Entering the zone that is already current is recursion: the same node counts another call.
	if (name != profile->current->Get_Name()) profile->current = profile->current->Get_Sub_Node(name);
	profile->current->Call();
}

void CProfileManager::Stop_Profile()
{
	ThreadProfile* profile = currentThreadProfile();
	if (!profile || profile->current == &profile->root) return;
	if (profile->current->Return()) profile->current = profile->current->Get_Parent();
}

void CProfileManager::CleanupMemory()
{
	ThreadProfile* profile = currentThreadProfile();
	if (!profile) return;
	profile->root.CleanupMemory();
	profile->current = &profile->root;
}

void CProfileManager::Reset()
{
	// The reset time is taken first, so that zones open across the reset (restarted by the node
	// reset) never count more than the time since reset.
	resetTimeNanoseconds().store(steadyNowNanoseconds());
	gFrameCounter.store(0);
	ThreadProfile* profile = currentThreadProfile();
	if (profile) profile->root.Reset();
}

void CProfileManager::Increment_Frame_Counter() { gFrameCounter.fetch_add(1); }
int CProfileManager::Get_Frame_Count_Since_Reset() { return gFrameCounter.load(); }

float CProfileManager::Get_Time_Since_Reset()
{
	const long long elapsed = steadyNowNanoseconds() - resetTimeNanoseconds().load();
	return elapsed > 0 ? static_cast<float>(double(elapsed) * 1e-6) : 0.0f;
}

CProfileIterator* CProfileManager::Get_Iterator()
{
	ThreadProfile* profile = currentThreadProfile();
	return profile ? new CProfileIterator(&profile->root) : nullptr;
}

void CProfileManager::Release_Iterator(CProfileIterator* iterator) { delete iterator; }

void CProfileManager::dumpRecursive(CProfileIterator* profileIterator, int spacing)
{
	if (!profileIterator) return;
	if (spacing < 0) spacing = 0;
	profileIterator->First();
	if (profileIterator->Is_Done()) return;

	// The root accumulates no time of its own; its span is the time since the last reset.
	const float parentMs =
	    profileIterator->Is_Root() ? Get_Time_Since_Reset() : profileIterator->Get_Current_Parent_Total_Time();
	const int frameCount = Get_Frame_Count_Since_Reset();
	const float frames = frameCount > 0 ? float(frameCount) : 1.0f;  // no frame counted: report totals
	printf("%*s%s: %.3f ms/frame, %d frame(s)\n", spacing, "",
	       printableName(profileIterator->Get_Current_Parent_Name()), parentMs / frames, frameCount);

	int childCount = 0;
	float childrenMs = 0.0f;
	for (; !profileIterator->Is_Done(); profileIterator->Next(), ++childCount)
	{
		const float childMs = profileIterator->Get_Current_Total_Time();
		childrenMs += childMs;
		const float percent = parentMs > 0.0f ? 100.0f * childMs / parentMs : 0.0f;
		printf("%*s#%d %s: %.2f%% of parent, %.3f ms/frame, %d calls\n", spacing + 2, "", childCount,
		       printableName(profileIterator->Get_Current_Name()), percent, childMs / frames,
		       profileIterator->Get_Current_Total_Calls());
	}
	const float otherMs = parentMs > childrenMs ? parentMs - childrenMs : 0.0f;
	const float otherPercent = parentMs > 0.0f ? 100.0f * otherMs / parentMs : 0.0f;
	printf("%*s(not in a child zone): %.2f%% of parent, %.3f ms/frame\n", spacing + 2, "", otherPercent,
	       otherMs / frames);

	for (int i = 0; i < childCount; ++i)
	{
		profileIterator->Enter_Child(i);
		dumpRecursive(profileIterator, spacing + 4);
		profileIterator->Enter_Parent();
	}
}

void CProfileManager::dumpAll()
{
	CProfileIterator* iterator = Get_Iterator();
	dumpRecursive(iterator, 0);
	Release_Iterator(iterator);
	fflush(stdout);
}

// ---- CProfileSample -------------------------------------------------------------------------------

CProfileSample::CProfileSample(const char* name) { gEnterProfileZoneFunc.load(std::memory_order_acquire)(name); }
CProfileSample::~CProfileSample() { gLeaveProfileZoneFunc.load(std::memory_order_acquire)(); }
