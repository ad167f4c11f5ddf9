// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/ConstraintSolver/btJointWarmStart.h"

namespace
{
// Every live store, so that a dying joint can leave all of them. Lock order: the registry, then a store.
struct StoreRegistry
{
	std::mutex mutex;
	btAlignedObjectArray<caliber::JointWarmStartStore*> stores;
};

// Never destroyed, so that joints with static storage duration can still leave it at exit.
StoreRegistry& registry()
{
	static StoreRegistry* instance = new StoreRegistry();
	return *instance;
}
}  // namespace

namespace caliber
{
JointWarmStartStore::JointWarmStartStore()
{
	StoreRegistry& all = registry();
	std::lock_guard<std::mutex> lock(all.mutex);
	all.stores.push_back(this);
}

JointWarmStartStore::~JointWarmStartStore()
{
	{
		StoreRegistry& all = registry();
		std::lock_guard<std::mutex> lock(all.mutex);
		all.stores.remove(this);
	}
	for (int i = 0; i < m_slots.size(); ++i) delete m_slots[i].impulses;
	for (int i = 0; i < m_spare.size(); ++i) delete m_spare[i];
}

void JointWarmStartStore::place(const btTypedConstraint* joint, JointImpulses* impulses)
{
	const unsigned mask = unsigned(m_slots.size()) - 1u;
	unsigned i = homeOf(joint);
	while (m_slots[int(i)].joint) i = (i + 1u) & mask;
	m_slots[int(i)].joint = joint;
	m_slots[int(i)].impulses = impulses;
}

JointImpulses* JointWarmStartStore::addEntry(const btTypedConstraint* joint)
{
	// At most half full, so that probes stay short; doubling rehashes every entry.
	if (2 * (m_count + 1) > m_slots.size())
	{
		const btAlignedObjectArray<Slot> old = m_slots;
		const int capacity = old.size() ? 2 * old.size() : 64;
		const Slot empty = {nullptr, nullptr};
		m_slots.resize(0);
		m_slots.resize(capacity, empty);
		m_shift = 64;
		for (int c = capacity; c > 1; c >>= 1) --m_shift;
		for (int i = 0; i < old.size(); ++i)
			if (old[i].joint) place(old[i].joint, old[i].impulses);
	}
	JointImpulses* entry;
	if (m_spare.size())
	{
		entry = m_spare[m_spare.size() - 1];
		m_spare.pop_back();
	}
	else
		entry = new JointImpulses();
	place(joint, entry);
	++m_count;
	return entry;
}

void JointWarmStartStore::forget(const btTypedConstraint* joint)
{
	if (!m_slots.size()) return;
	const unsigned mask = unsigned(m_slots.size()) - 1u;
	unsigned hole = homeOf(joint);
	while (m_slots[int(hole)].joint != joint)
	{
		if (!m_slots[int(hole)].joint) return;
		hole = (hole + 1u) & mask;
	}
	m_slots[int(hole)].impulses->resize(0);
	m_spare.push_back(m_slots[int(hole)].impulses);
	--m_count;
	// Backward-shift deletion: every later entry of the probe run that may sit in the hole moves into it,
	// so that lookups never need tombstones.
	for (unsigned next = (hole + 1u) & mask; m_slots[int(next)].joint; next = (next + 1u) & mask)
	{
		const unsigned home = homeOf(m_slots[int(next)].joint);
		// The entry may move back to the hole when its home is not cyclically within (hole, next].
		const bool homeAfterHole = ((home - hole) & mask) != 0 && ((home - hole) & mask) <= ((next - hole) & mask);
		if (homeAfterHole) continue;
		m_slots[int(hole)] = m_slots[int(next)];
		hole = next;
	}
	m_slots[int(hole)].joint = nullptr;
	m_slots[int(hole)].impulses = nullptr;
}

int JointWarmStartStore::size()
{
	std::lock_guard<std::mutex> lock(m_mutex);
	return m_count;
}

void forgetJoint(const btTypedConstraint* joint)
{
	StoreRegistry& all = registry();
	std::lock_guard<std::mutex> lock(all.mutex);
	for (int i = 0; i < all.stores.size(); ++i)
	{
		JointWarmStartStore* store = all.stores[i];
		std::lock_guard<std::mutex> storeLock(store->mutex());
		store->forget(joint);
	}
}
}  // namespace caliber
