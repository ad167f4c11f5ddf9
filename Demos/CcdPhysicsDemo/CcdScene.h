// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_CCD_SCENE_H
#define CALIBER_DEMOS_CCD_SCENE_H
// CcdPhysicsDemo's scene: twenty small spheres (radius 5 cm) fired at 100 to 290 m/s at a static wall
// 1 cm thick, with one of three kinds of collision detection. Used by CcdPhysicsDemo, which counts
// the spheres that got through, and by the demo browser.

#include <memory>
#include <vector>

#include "DemoWorld.h"
#include "btBulletDynamicsCommon.h"

namespace ccd_demo
{
/// How the world detects the spheres' collisions with the wall.
enum Mode
{
	kDiscreteOnly,  ///< dispatch info m_useContinuous = false: the spheres pass through
	kSpeculative,   ///< the default: speculative contacts
	kSweptCcd       ///< speculative contacts plus Bullet's swept CCD on each sphere
};

/// The world, the wall and the spheres, ready to step.
class Scene
{
public:
	explicit Scene(Mode mode);
	~Scene();
	btDiscreteDynamicsWorld& world() { return m_physics.world(); }
	/// How many spheres are beyond the wall (x > 0).
	int spheresThrough() const;

private:
	caliber::demo::DemoWorld m_physics;  // the world, first in and last out
	btBoxShape m_wallShape;
	std::unique_ptr<btRigidBody> m_wall;
	btSphereShape m_ballShape;
	std::vector<std::unique_ptr<btRigidBody>> m_balls;
};
}  // namespace ccd_demo

#endif
