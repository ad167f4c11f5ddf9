// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_EXTRAS_EXAMPLE_MESHES_H
#define CALIBER_EXTRAS_EXAMPLE_MESHES_H

/// Closed, outward-wound example meshes for the convex decomposition's tests and demo, each with its exact
/// volume in a comment (the tessellated volume is slightly less for the round ones).

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btVector3.h"

namespace caliber
{
/// A triangle mesh: three indices into vertices per triangle.
struct ExampleMesh
{
	btAlignedObjectArray<btVector3> vertices;
	btAlignedObjectArray<int> indices;
};

/// The box [-half, half]: 8 vertices, 12 triangles, volume 8 hx hy hz.
ExampleMesh makeBoxMesh(const btVector3& half);

/// A torus around the z axis: tube radius r around a circle of radius R, with the given numbers of
/// segments around the axis and around the tube. Volume 2 pi^2 R r^2 (for a smooth torus).
ExampleMesh makeTorusMesh(btScalar R, btScalar r, int segmentsAround, int segmentsTube);

/// A cup standing on z = 0: outer radius, wall thickness, height and floor thickness, open at the top,
/// with segments around. Volume pi (R^2 h - (R - t)^2 (h - f)) for a smooth cup.
ExampleMesh makeCupMesh(btScalar outerRadius, btScalar wall, btScalar height, btScalar floor, int segments);

/// An L-shaped bracket: the L with legs of length `leg` and width `width` in the xy plane (corner at the
/// origin), extruded by `depth` along z. Volume (2 leg width - width^2) depth.
ExampleMesh makeLBracketMesh(btScalar leg, btScalar width, btScalar depth);

/// The solid of revolution around z of a closed profile polygon (r, z), counter-clockwise in the (r, z)
/// plane; points with r = 0 become single poles.
ExampleMesh makeRevolvedMesh(const btAlignedObjectArray<btVector3>& profile, int segments);
}  // namespace caliber

#endif  // CALIBER_EXTRAS_EXAMPLE_MESHES_H
