// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// A user's program built against an installed Caliber, with the includes a Bullet program has.
// Usage: consumer [float|double]  -- with an argument, exits 2 unless btScalar is that type.

#include "btBulletDynamicsCommon.h"
#include "btBulletSoftBodyCommon.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

#include <stdio.h>
#include <string.h>

int main(int argc, char** argv)
{
	const char* precision = btIsDoublePrecision() ? "double" : "float";
	printf("Caliber consumer: Bullet API %d, btScalar is %s (%d bytes)\n", btGetVersion(), precision,
	       int(sizeof(btScalar)));
	if (argc > 1 && strcmp(argv[1], precision) != 0)
	{
		printf("error: expected btScalar to be %s\n", argv[1]);
		return 2;
	}

	// A rigid transform, a point through it and back.
	btTransform bodyToWorld;
	bodyToWorld.setIdentity();
	bodyToWorld.setRotation(btQuaternion(btVector3(0, 0, 1), SIMD_HALF_PI));
	bodyToWorld.setOrigin(btVector3(1, 2, 3));
	const btVector3 local(1, 0, 0);
	const btVector3 world = bodyToWorld * local;
	const btVector3 back = bodyToWorld.inverse() * world;
	printf("(1, 0, 0) in the body is (%.3f, %.3f, %.3f) in the world\n", double(world.x()), double(world.y()),
	       double(world.z()));

	// A library call (aligned allocation) through the container every Bullet program uses.
	btAlignedObjectArray<btVector3> points;
	for (int i = 0; i < 100; ++i) points.push_back(btVector3(btScalar(i), btScalar(2 * i), btScalar(-i)));
	btVector3 sum(0, 0, 0);
	for (int i = 0; i < points.size(); ++i) sum += points[i];
	printf("sum of %d points: (%.0f, %.0f, %.0f)\n", points.size(), double(sum.x()), double(sum.y()), double(sum.z()));

	const bool ok = (back - local).length() < btScalar(1e-5) &&
	                (world - btVector3(1, 3, 3)).length() < btScalar(1e-5) && sum == btVector3(4950, 9900, -4950);
	printf("%s\n", ok ? "consumer OK" : "consumer FAILED");
	return ok ? 0 : 1;
}
