// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_COMMON_DEMO_WORLD_H
#define CALIBER_DEMOS_COMMON_DEMO_WORLD_H
// The demos' usual world: Bullet's default collision configuration, a dispatcher, a dbvt broadphase
// and the sequential-impulse solver, owned together with the dynamics world they make (no gravity
// set: each scene sets its own). Demo-side code.

#include "btBulletDynamicsCommon.h"

namespace caliber
{
namespace demo
{
class DemoWorld
{
public:
	btDiscreteDynamicsWorld& world() { return m_world; }

private:
	btDefaultCollisionConfiguration m_configuration;
	btCollisionDispatcher m_dispatcher{&m_configuration};
	btDbvtBroadphase m_broadphase;
	btSequentialImpulseConstraintSolver m_solver;
	btDiscreteDynamicsWorld m_world{&m_dispatcher, &m_broadphase, &m_solver, &m_configuration};
};
}  // namespace demo
}  // namespace caliber

#endif
