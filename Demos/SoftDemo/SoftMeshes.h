// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_SOFT_MESHES_H
#define CALIBER_DEMOS_SOFT_MESHES_H
// Procedural meshes for SoftDemo (our own shapes, made here, no stored vertex data): a torus, a blob (a
// lumpy closed body standing in for Bullet's bunny) and a cube cut into tetras in TetGen's text format.

#include <string>

#include "btBulletSoftBodyCommon.h"

namespace soft_demo
{
/// A closed torus about the y axis through centre: ring radius R, tube radius r, ring x tube segments,
/// faces wound outwards.
btSoftBody* makeTorus(btSoftBodyWorldInfo& info, const btVector3& centre, btScalar R, btScalar r, int ring,
                      int tube);
/// A blob: an ellipsoid of about res nodes whose radius swells and shrinks with direction (by up to 30%),
/// so that it is closed, star-shaped and not convex; its rest lengths are its lumpy shape.
btSoftBody* makeBlob(btSoftBodyWorldInfo& info, const btVector3& centre, btScalar radius, int res);

/// A cube of side size, n cells a side, each cut into 6 tetras along its diagonal: TetGen .node, .ele and
/// .face text (the faces are the boundary's, wound outwards).
struct TetGenText
{
	std::string node, ele, face;
};
TetGenText makeTetCube(const btVector3& centre, btScalar size, int n);

/// The sum of a body's tetras' volumes.
btScalar tetraVolume(const btSoftBody& body);
}  // namespace soft_demo

#endif
