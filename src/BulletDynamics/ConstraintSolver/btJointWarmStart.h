// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_JOINT_WARM_START_H
#define CALIBER_JOINT_WARM_START_H

// Joint warm starting: each joint's row impulses of its last solve, kept by the solver that solved it
// (Bullet's btTypedConstraint has no place for them). A solve resolves every joint's entry once, under
// the store's lock; rows then read and write the entry directly. An entry lives until its joint is
// destroyed (btTypedConstraint's destructor calls forgetJoint) or its solver is: a joint that sleeps,
// or is taken out of the world and put back, keeps its impulses, and a new joint built at a dead
// joint's address never starts from the dead joint's impulses.

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btScalar.h"

#include <stdint.h>

#include <mutex>

class btTypedConstraint;

namespace caliber
{
/// One joint's row impulses from its last solve (empty: none, start cold).
typedef btAlignedObjectArray<btScalar> JointImpulses;

/// One solver's warm-start entries, keyed by joint: an open-addressing table (linear probing, at most
/// half full), since a solve looks up every joint it solves. Entries are allocated when a joint is first
/// solved and recycled when it dies, so a steady state allocates nothing.
class JointWarmStartStore
{
public:
	JointWarmStartStore();
	~JointWarmStartStore();
	JointWarmStartStore(const JointWarmStartStore&) = delete;
	JointWarmStartStore& operator=(const JointWarmStartStore&) = delete;

	/// Held while a solve resolves its joints' entries (a joint may die on another thread meanwhile).
	std::mutex& mutex() { return m_mutex; }
	/// joint's entry, made empty if it has none. Call with mutex() held; the pointer stays valid until
	/// the joint or the store dies.
	JointImpulses* entryOf(const btTypedConstraint* joint)
	{
		JointImpulses* found = find(joint);
		return found ? found : addEntry(joint);
	}
	/// joint's entry, or null if it has none. Call with mutex() held.
	JointImpulses* find(const btTypedConstraint* joint)
	{
		if (!m_slots.size()) return nullptr;
		const unsigned mask = unsigned(m_slots.size()) - 1u;
		for (unsigned i = homeOf(joint);; i = (i + 1u) & mask)
		{
			const Slot& slot = m_slots[int(i)];
			if (slot.joint == joint) return slot.impulses;
			if (!slot.joint) return nullptr;
		}
	}
	/// entries[i] = entryOf(joints[i]) for i < count, with the table's layout held in registers.
	void resolve(btTypedConstraint* const* joints, int count, JointImpulses** entries)
	{
		int i = 0;
		while (i < count)
		{
			if (!m_slots.size())
			{
				entries[i] = addEntry(joints[i]);
				++i;
				continue;
			}
			const Slot* slots = &m_slots[0];
			const unsigned mask = unsigned(m_slots.size()) - 1u;
			const unsigned shift = m_shift;
			for (; i < count; ++i)
			{
				const btTypedConstraint* joint = joints[i];
				unsigned s = unsigned((uint64_t(uintptr_t(joint)) * kFibonacci) >> shift);
				while (slots[s].joint && slots[s].joint != joint) s = (s + 1u) & mask;
				if (!slots[s].joint) break;  // a new joint: added below (the table may grow)
				entries[i] = slots[s].impulses;
			}
			if (i < count)
			{
				entries[i] = addEntry(joints[i]);
				++i;
			}
		}
	}
	/// Drops joint's entry (nothing if it has none). Call with mutex() held.
	void forget(const btTypedConstraint* joint);
	/// Number of joints with an entry (for tests).
	int size();

private:
	struct Slot
	{
		const btTypedConstraint* joint;  ///< null: free
		JointImpulses* impulses;
	};
	// Fibonacci hashing: the top bits of the address times 2^64 / golden ratio (aligned addresses spread).
	unsigned homeOf(const btTypedConstraint* joint) const
	{
		return unsigned((uint64_t(uintptr_t(joint)) * kFibonacci) >> m_shift);
	}
	static const uint64_t kFibonacci = 0x9E3779B97F4A7C15ull;
	JointImpulses* addEntry(const btTypedConstraint* joint);
	void place(const btTypedConstraint* joint, JointImpulses* impulses);

	std::mutex m_mutex;
	btAlignedObjectArray<Slot> m_slots;  ///< a power of two in size, or empty
	unsigned m_shift = 64;               ///< 64 - log2(m_slots.size())
	int m_count = 0;
	btAlignedObjectArray<JointImpulses*> m_spare;
};

/// Drops joint's entries in every solver's store; btTypedConstraint's destructor calls it.
void forgetJoint(const btTypedConstraint* joint);
}  // namespace caliber

#endif  // CALIBER_JOINT_WARM_START_H
