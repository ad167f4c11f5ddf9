// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BspScene.h"

namespace bsp_demo
{
Scene::Scene(btCollisionShape* level) : LevelScene(level, btVector3(0, 0, btScalar(-9.81)))
{
	btBoxShape* box = own(new btBoxShape(btVector3(btScalar(0.25), btScalar(0.25), btScalar(0.25))));
	btCollisionShape* shapes[3] = {own(new btSphereShape(btScalar(0.25))), box,
	                               own(new btCylinderShapeZ(btVector3(btScalar(0.2), btScalar(0.2), btScalar(0.3))))};
	for (int i = 0; i < 40; ++i)
	{
		// An 8 x 5 grid 1.6 m apart covering pillars (4, 4), (4, -4), (-4, 5) and the ramp (x -7 to -3).
		const btScalar x = btScalar(1.6) * btScalar(i % 8) - btScalar(5.6);
		const btScalar y = btScalar(1.6) * btScalar(i / 8) - btScalar(3.2) + btScalar(0.5) * btScalar(i % 2);
		btTransform pose(btQuaternion(btVector3(1, 0, 1).normalized(), btScalar(0.4) * btScalar(i)),
		                 btVector3(x, y, btScalar(3 + (i % 4) * 2)));
		addBody(shapes[i % 3], pose, btScalar(0.7), btScalar(0.05));
	}
	// One box over each pillar top (1 m across, 6 m up).
	const btVector3 pillarTops[4] = {btVector3(4, 4, 9), btVector3(4, -4, 9), btVector3(-4, 5, 9), btVector3(0, -5, 9)};
	for (const btVector3& top : pillarTops) addBody(box, btTransform(btQuaternion::getIdentity(), top), btScalar(0.7));
}
}  // namespace bsp_demo
