// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_COMMON_SHAPE_MESHER_H
#define CALIBER_DEMOS_COMMON_SHAPE_MESHER_H
// Turns a collision shape into lit triangles of a Scene: spheres, capsules, cylinders and cones as
// smooth surfaces of revolution; boxes and other polyhedra as their flat faces; other convex shapes
// (multi-sphere, scaled, Minkowski sums) as the hull of their support points in many directions;
// triangle meshes and height fields triangle by triangle; compounds child by child; a static plane as
// a finite square patch around the scene's focus. Demo-side code.

#include "Scene.h"

class btCollisionShape;
class btTransform;

namespace caliber
{
namespace demo
{
/// How addShape() draws a shape.
struct MeshStyle
{
	/// Surface colour (0..1).
	btVector3 color{0.8f, 0.8f, 0.8f};
	/// A 1 m checker on the surface (for grounds).
	bool checker = false;
	/// Segments around a surface of revolution (spheres, capsules, cylinders, cones), at least 6.
	int segments = 48;
	/// Where a static plane's patch is centred (projected onto the plane) and its half size.
	btVector3 planeCentre{0, 0, 0};
	btScalar planeHalfSize = 20;
};

/// Adds shape, placed at transform, to scene. Returns false (adding nothing) for a null shape, a shape
/// of a type it cannot draw (soft bodies before they exist, custom shapes) or a non-finite transform;
/// the empty shape adds nothing and returns true.
bool addShape(Scene& scene, const btCollisionShape* shape, const btTransform& transform, const MeshStyle& style);
}  // namespace demo
}  // namespace caliber

#endif
