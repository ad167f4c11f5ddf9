// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_COMMON_SOFT_BODY_SCENE_H
#define CALIBER_DEMOS_COMMON_SOFT_BODY_SCENE_H
// Draws a btSoftBody into a Scene: its faces as lit triangles (smooth, with the nodes' normals), or,
// for a body without faces (a rope), its links as lines. addWorld() calls it for every soft body of a
// world, so every demo's pictures and the browser show them. Demo-side code.

#include "Scene.h"

class btSoftBody;

namespace caliber
{
namespace demo
{
/// Adds body's surface (or, without faces, its links) in colour. Returns how many faces and links it
/// added; non-finite nodes are skipped by the Scene (and counted there).
int addSoftBody(Scene& scene, const btSoftBody& body, const btVector3& color);

/// The box around body's nodes (their current positions), for the camera's framing; false for a body
/// without nodes.
bool softBodyNodeBounds(const btSoftBody& body, btVector3& aabbMin, btVector3& aabbMax);
}  // namespace demo
}  // namespace caliber

#endif
