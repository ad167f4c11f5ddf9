// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/Dynamics/btActionInterface.h"

#include "BulletDynamics/Dynamics/btRigidBody.h"

btRigidBody& btActionInterface::getFixedBody()
{
	// A function-local static: built on first use, so no static-initialisation order problems.
	static btRigidBody fixedBody(btScalar(0), 0, 0);
	fixedBody.setMassProps(btScalar(0), btVector3(0, 0, 0));
	return fixedBody;
}
