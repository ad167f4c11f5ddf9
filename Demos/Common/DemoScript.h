// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_COMMON_DEMO_SCRIPT_H
#define CALIBER_DEMOS_COMMON_DEMO_SCRIPT_H
// A scripted demo's run (the vehicle, fork lift and character demos): steps its world by a fixed step
// while --frames' budget lasts, keeps the simulated time, and counts the failed checks; the check of a
// phase that --frames cut short is skipped, and said so. Demo-side code.

#include <stdio.h>

#include "DemoPictures.h"
#include "btBulletDynamicsCommon.h"

namespace caliber
{
namespace demo
{
class DemoScript
{
public:
	DemoScript(btDynamicsWorld& world, btScalar step, const StepBudget& budget)
	    : m_world(world), m_step(step), m_budget(budget)
	{
	}
	/// Steps the world steps times, or until the budget is spent.
	void run(int steps)
	{
		for (int i = 0; i < steps && !m_budget.spent(); ++i)
		{
			m_world.stepSimulation(m_step, 1, m_step);
			m_budget.count();
			m_time += m_step;
		}
	}
	/// True once --frames' budget is used up: nothing steps any more.
	bool spent() const { return m_budget.spent(); }
	/// The simulated time so far.
	btScalar time() const { return m_time; }
	/// Prints "  check: WHAT: ok" (or FAILED, counted).
	void check(bool ok, const char* what)
	{
		printf("  check: %s: %s\n", what, ok ? "ok" : "FAILED");
		if (!ok) ++m_failures;
	}
	/// check, unless --frames cut the phase short.
	void judge(bool ok, const char* what)
	{
		if (m_budget.reached(what)) check(ok, what);
	}
	/// Prints "NAME: all checks passed" (or FAILED) and returns the exit code, 1 when a check failed.
	int verdict(const char* name) const
	{
		printf("%s: %s\n", name, m_failures ? "FAILED" : "all checks passed");
		return m_failures ? 1 : 0;
	}

private:
	btDynamicsWorld& m_world;
	btScalar m_step;
	StepBudget m_budget;
	btScalar m_time = 0;
	int m_failures = 0;
};
}  // namespace demo
}  // namespace caliber

#endif
