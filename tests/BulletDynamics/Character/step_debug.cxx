#include <cstdio>
#include <cstdlib>
#include "../Dynamics/DynamicsWorldTestUtil.h"
#include "BulletCollision/CollisionDispatch/btGhostObject.h"
#include "BulletDynamics/Character/btKinematicCharacterController.h"
using caliber_test::TestWorld;
int main(int argc, char** argv){
  const btScalar kRadius = 0.3, kCylinder = 1.0, kHalfHeight = kRadius + kCylinder/2, kStep = 1.0/60;
  TestWorld w; w.addGround();
  btScalar height = atof(argv[1]);
  w.addBody(w.shape<btBoxShape>(btVector3(5, height / 2, 2)), 0, btVector3(0, height / 2, 4));
  btGhostPairCallback cb; w.world()->getPairCache()->setInternalGhostPairCallback(&cb);
  btCapsuleShape shape(kRadius, kCylinder); btPairCachingGhostObject ghost;
  ghost.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, kHalfHeight + 0.001, 0)));
  ghost.setCollisionShape(&shape); ghost.setCollisionFlags(btCollisionObject::CF_CHARACTER_OBJECT);
  w.world()->addCollisionObject(&ghost, btBroadphaseProxy::CharacterFilter, btBroadphaseProxy::StaticFilter | btBroadphaseProxy::DefaultFilter);
  btKinematicCharacterController c(&ghost, &shape, 0.35, btVector3(0,1,0));
  w.world()->addAction(&c);
  w.run(30, kStep);
  c.setWalkDirection(btVector3(0,0,0.05));
  for (int i=0;i<60;++i){ w.run(1,kStep); btVector3 p = ghost.getWorldTransform().getOrigin(); if (i>20 && i < 45) printf("%d y %.5f z %.4f ground %d\n", i, p.y()-kHalfHeight, p.z(), c.onGround());}
  w.world()->removeAction(&c); w.world()->removeCollisionObject(&ghost);
}
