// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/Dynamics/btActionInterface.h"

#include "BulletDynamics/Dynamics/btRigidBody.h"

btRigidBody& btActionInterface::getFixedBody()
{
	// A function-local static: built on first use, so no static-initialisation order problems.
	// Mass 0: static, with zero inverse mass and inertia.
	static btRigidBody fixedBody(btScalar(0), 0, 0);
	return fixedBody;
}
