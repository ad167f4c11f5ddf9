// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_MATERIAL_H
#define BT_MATERIAL_H

#include "LinearMath/btScalar.h"

/// One surface material of a btMultimaterialTriangleMeshShape: the record layout users store in the
/// material table of a btTriangleIndexVertexMaterialArray (materialStride = sizeof(btMaterial)).
class btMaterial
{
public:
	btScalar m_friction;
	btScalar m_restitution;
	/// Keeps the record 16 bytes in single precision, as Bullet's.
	int pad[2];

	/// Uninitialised, like a plain record in a user's array.
	btMaterial() {}
	btMaterial(btScalar friction, btScalar restitution) : m_friction(friction), m_restitution(restitution)
	{
		pad[0] = 0;
		pad[1] = 0;
	}
};

#endif  // BT_MATERIAL_H
