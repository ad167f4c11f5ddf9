// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_OBJ_SCENE_H
#define CALIBER_DEMOS_OBJ_SCENE_H
// ObjDemo's world: a level imported from OBJ as one static BVH mesh, and six pieces (OBJ groups made
// convex hulls, taken in turn) dropped into it, tilted, from 4 to 6.5 m. The built-in level (a bowl of
// quads and a ramp) and pieces (a crate, a hexagonal prism) are OBJ text. Used by ObjDemo, which checks
// that the pieces come to rest in the bowl, and by the demo browser.

#include <string>

#include "LevelScene.h"

namespace obj_demo
{
/// The built-in level and pieces, as OBJ files' text.
std::string levelText();
std::string piecesText();

/// The world around a level shape and the pieces' hulls (both must outlive the scene), ready to step.
class Scene : public caliber::demo::LevelScene
{
public:
	Scene(btCollisionShape* level, const std::vector<std::unique_ptr<btConvexHullShape>>& hulls);
};
}  // namespace obj_demo

#endif
