// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_BSP_SCENE_H
#define CALIBER_DEMOS_BSP_SCENE_H
// BspDemo's world: a Quake 3 level's static compound of hulls (z up, metres) and 44 bodies dropped
// into it: 40 spheres, boxes and cylinders on an 8 x 5 grid 3 to 9 m up, and one box over each of the
// example room's four pillars. Used by BspDemo, which checks where they come to rest, and by the
// demo browser.

#include "LevelScene.h"

namespace bsp_demo
{
/// Quake units to metres.
const btScalar kScale = btScalar(1) / 32;

/// The world around a level shape (which must outlive the scene), with the bodies added, ready to step.
class Scene : public caliber::demo::LevelScene
{
public:
	explicit Scene(btCollisionShape* level);
};
}  // namespace bsp_demo

#endif
