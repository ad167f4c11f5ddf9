// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SIDE_TABLE_H
#define CALIBER_SIDE_TABLE_H

// Internal state that belongs to an object of a Bullet-declared class but that Bullet's class does not
// declare: the public classes stay exactly Bullet's, and their Caliber-only state lives here, keyed by
// the object's address. The owner creates its entry when it is built and erases it in its destructor;
// the hot code looks its entry up once per step (or per solve), never per row.

#include <memory>
#include <mutex>
#include <unordered_map>

namespace caliber
{
template <class State>
class SideTable
{
public:
	/// The state of owner, made (value-initialised) if owner has none yet.
	State& acquire(const void* owner)
	{
		std::lock_guard<std::mutex> lock(m_mutex);
		std::unique_ptr<State>& state = m_states[owner];
		if (!state) state.reset(new State());
		return *state;
	}
	/// The state of owner, or null if it has none (nothing is made).
	State* find(const void* owner)
	{
		std::lock_guard<std::mutex> lock(m_mutex);
		auto it = m_states.find(owner);
		return it == m_states.end() ? nullptr : it->second.get();
	}
	/// Drops owner's state (nothing if it has none).
	void release(const void* owner)
	{
		std::unique_ptr<State> doomed;
		{
			std::lock_guard<std::mutex> lock(m_mutex);
			auto it = m_states.find(owner);
			if (it == m_states.end()) return;
			doomed = std::move(it->second);
			m_states.erase(it);
		}
	}

private:
	// Worlds and solvers may be built and stepped on different threads at once, so the map is locked;
	// an entry itself is only used by its owner's thread.
	std::mutex m_mutex;
	std::unordered_map<const void*, std::unique_ptr<State>> m_states;
};

/// The one table for State, alive until the process ends (never destroyed, so an owner with static
/// storage duration can still release its entry during static destruction).
template <class State>
SideTable<State>& sideTable()
{
	static SideTable<State>* table = new SideTable<State>();
	return *table;
}
}  // namespace caliber

#endif  // CALIBER_SIDE_TABLE_H
