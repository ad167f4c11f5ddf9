// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_QUICK_PROF_H
#define BT_QUICK_PROF_H

/// A hierarchical, per-thread wall-clock profiler (BT_PROFILE, CProfileManager) and btClock.
///
/// Each thread that enters a profile zone gets its own tree (see btQuickprofGetCurrentThreadIndex2);
/// every CProfileManager function works on the tree of the calling thread, so threads never share
/// mutable profiling state. Zone names are compared by pointer: pass string literals. All times
/// reported by nodes, iterators and the manager are in milliseconds.

#include "LinearMath/btScalar.h"

/// Measures elapsed wall-clock time with a monotonic clock (std::chrono::steady_clock).
class btClock
{
public:
	/// Starts the clock at construction.
	btClock();
	/// Copies the start time of another clock.
	btClock(const btClock& other);
	/// Copies the start time of another clock.
	btClock& operator=(const btClock& other);
	/// Nothing to release; kept for API compatibility.
	~btClock();

	/// Restarts the clock: elapsed times count from now.
	void reset();
	/// Whole milliseconds since construction or the last reset.
	unsigned long long int getTimeMilliseconds();
	/// Whole microseconds since construction or the last reset.
	unsigned long long int getTimeMicroseconds();
	/// Nanoseconds since construction or the last reset.
	unsigned long long int getTimeNanoseconds();
	/// Seconds since construction or the last reset, with microsecond resolution.
	btScalar getTimeSeconds();

private:
	long long m_startNanoseconds;  // steady_clock time point, in ns since the clock's epoch
};

/// Signature of a function called on entering a profile zone (by CProfileSample and BT_PROFILE).
typedef void(btEnterProfileZoneFunc)(const char* msg);
/// Signature of a function called on leaving the innermost profile zone.
typedef void(btLeaveProfileZoneFunc)();

/// The function BT_PROFILE currently calls on entering a zone (the built-in one by default).
btEnterProfileZoneFunc* btGetCurrentEnterProfileZoneFunc();
/// The function BT_PROFILE currently calls on leaving a zone (the built-in one by default).
btLeaveProfileZoneFunc* btGetCurrentLeaveProfileZoneFunc();
/// Routes zone entries to enterFunc instead of the built-in profiler; null restores the built-in one.
void btSetCustomEnterProfileZoneFunc(btEnterProfileZoneFunc* enterFunc);
/// Routes zone exits to leaveFunc instead of the built-in profiler; null restores the built-in one.
void btSetCustomLeaveProfileZoneFunc(btLeaveProfileZoneFunc* leaveFunc);

/// How many threads can have a profile tree at the same time.
#define BT_QUICKPROF_MAX_THREAD_COUNT 64

/// The calling thread's profiler slot, in [0, BT_QUICKPROF_MAX_THREAD_COUNT). Slots are handed out
/// in order of first use and returned when a thread exits. A thread that finds all slots taken gets
/// BT_QUICKPROF_MAX_THREAD_COUNT for its whole life, and its zones are not recorded.
unsigned int btQuickprofGetCurrentThreadIndex2();

/// One zone in a profile tree: its name, call count and accumulated time, linked to its parent,
/// first child and next sibling.
class CProfileNode
{
public:
	/// Makes a node called name (a pointer that must outlive the node) below parent (null for a root).
	CProfileNode(const char* name, CProfileNode* parent);
	/// Deletes the whole subtree below this node.
	~CProfileNode();

	/// The child with this name pointer, created (as the last child) if there is none yet.
	CProfileNode* Get_Sub_Node(const char* name);
	/// The node above this one; null for a root.
	CProfileNode* Get_Parent() { return Parent; }
	/// The next node with the same parent; null for the last one.
	CProfileNode* Get_Sibling() { return Sibling; }
	/// The first node below this one; null for a leaf.
	CProfileNode* Get_Child() { return Child; }

	/// Deletes every node below this one.
	void CleanupMemory();
	/// Zeroes call counts and times of this node and its whole subtree (keeps the nodes).
	void Reset();
	/// Counts one call and, unless the zone is already open (recursion), starts its timer.
	void Call();
	/// Closes one call; true when the outermost call of a recursion closed and its time was added.
	bool Return();

	/// The name pointer given at creation.
	const char* Get_Name() { return Name; }
	/// Calls since creation or the last reset.
	int Get_Total_Calls() { return TotalCalls; }
	/// Milliseconds spent in completed calls since creation or the last reset.
	float Get_Total_Time();

	/// An opaque pointer the application can attach to the node (null by default).
	void* GetUserPointer() const { return m_userPtr; }
	/// Attaches an opaque pointer to the node.
	void SetUserPointer(void* ptr) { m_userPtr = ptr; }

protected:
	const char* Name;                     ///< the zone's name pointer
	int TotalCalls;                       ///< calls since creation or reset
	unsigned long long TotalNanoseconds;  ///< time of completed calls; integer, so nested totals compare exactly
	unsigned long long StartNanoseconds;  ///< clock reading when the outermost open call began
	int RecursionCounter;                 ///< how many calls of this zone are open

	CProfileNode* Parent;   ///< node above, null for a root
	CProfileNode* Child;    ///< first node below
	CProfileNode* Sibling;  ///< next node with the same parent
	void* m_userPtr;        ///< application data

private:
	CProfileNode(const CProfileNode&) = delete;
	CProfileNode& operator=(const CProfileNode&) = delete;
};

/// Walks a profile tree: it stands on a parent node and steps through that node's children.
/// When Is_Done() is true the Get_Current_* accessors return "" / 0 / null.
class CProfileIterator
{
public:
	/// Stands on start, with its first child current.
	explicit CProfileIterator(CProfileNode* start);

	/// Makes the first child current.
	void First();
	/// Makes the next sibling current (no effect once done).
	void Next();
	/// True when there is no current child (past the last one, or the parent is a leaf).
	bool Is_Done();
	/// True when standing on the root of the tree.
	bool Is_Root() { return CurrentParent->Get_Parent() == 0; }

	/// Descends into the index-th child (0-based); no effect on the position if there is no such child.
	void Enter_Child(int index);
	/// Descends into the child with the largest total time; no effect if there are no children.
	void Enter_Largest_Child();
	/// Moves up to the parent (stays at the root), with its first child current.
	void Enter_Parent();

	/// Name of the current child.
	const char* Get_Current_Name();
	/// Calls of the current child.
	int Get_Current_Total_Calls();
	/// Total milliseconds of the current child.
	float Get_Current_Total_Time();
	/// User pointer of the current child.
	void* Get_Current_UserPointer();
	/// Sets the user pointer of the current child (no effect once done).
	void Set_Current_UserPointer(void* ptr);

	/// Name of the node the iterator stands on.
	const char* Get_Current_Parent_Name() { return CurrentParent->Get_Name(); }
	/// Calls of the node the iterator stands on.
	int Get_Current_Parent_Total_Calls() { return CurrentParent->Get_Total_Calls(); }
	/// Total milliseconds of the node the iterator stands on.
	float Get_Current_Parent_Total_Time() { return CurrentParent->Get_Total_Time(); }

protected:
	CProfileNode* CurrentParent;  ///< the node the iterator stands on
	CProfileNode* CurrentChild;   ///< the current child, null when done
};

/// The profiler's entry points. Every function acts on the calling thread's tree; the frame counter
/// and reset time are shared by all threads.
class CProfileManager
{
public:
	/// Opens the zone name below the current one (or re-enters it if it is the current one).
	static void Start_Profile(const char* name);
	/// Closes the innermost open zone; ignored when no zone is open.
	static void Stop_Profile();

	/// Deletes every node of the calling thread's tree; zones still open are abandoned.
	static void CleanupMemory();
	/// Zeroes the calling thread's counts and times, the frame counter and the time since reset.
	static void Reset();
	/// Counts one frame (for the per-frame figures of the report).
	static void Increment_Frame_Counter();
	/// Frames counted since the last Reset.
	static int Get_Frame_Count_Since_Reset();
	/// Milliseconds since the last Reset (before any, since the first thread started profiling).
	static float Get_Time_Since_Reset();

	/// A new iterator on the calling thread's root (null if the thread has no slot); free it with
	/// Release_Iterator.
	static CProfileIterator* Get_Iterator();
	/// Frees an iterator from Get_Iterator (null is ignored).
	static void Release_Iterator(CProfileIterator* iterator);

	/// Prints the subtree below the iterator's parent to stdout, indented by spacing; the iterator is
	/// left on the same parent.
	static void dumpRecursive(CProfileIterator* profileIterator, int spacing);
	/// Prints the calling thread's whole tree to stdout.
	static void dumpAll();
};

/// Opens a profile zone for its lifetime through the current enter/leave functions.
class CProfileSample
{
public:
	/// Enters zone name (a string literal or another pointer that outlives the profile).
	CProfileSample(const char* name);
	/// Leaves the zone.
	~CProfileSample();

private:
	CProfileSample(const CProfileSample&) = delete;
	CProfileSample& operator=(const CProfileSample&) = delete;
};

/// Token pasting helpers that give each BT_PROFILE sample a name unique to its line.
#define BT_PROFILE_CONCAT_INNER(a, b) a##b
/// Pastes a and b after expanding them.
#define BT_PROFILE_CONCAT(a, b) BT_PROFILE_CONCAT_INNER(a, b)

#ifndef BT_NO_PROFILE
/// Profiles the rest of the enclosing scope as zone name.
#define BT_PROFILE(name) CProfileSample BT_PROFILE_CONCAT(btProfileSample_, __LINE__)(name)
#else
/// Profiling compiled out: the name is not evaluated.
#define BT_PROFILE(name) ((void)0)
#endif

#endif  // BT_QUICK_PROF_H
