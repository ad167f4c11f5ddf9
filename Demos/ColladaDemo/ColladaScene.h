// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_COLLADA_SCENE_H
#define CALIBER_DEMOS_COLLADA_SCENE_H
// ColladaDemo's world: a COLLADA physics document's bodies and joints (by default playground.dae: a
// stack, a rolling ball, a hinged plank) added to a world with the document's gravity. Used by
// ColladaDemo, which checks the run and the export round trip, and by the demo browser.

#include "Serialize/ColladaConverter/ColladaPhysics.h"
#include "DemoWorld.h"
#include "btBulletDynamicsCommon.h"

namespace collada_demo
{
/// A loaded document and the world that holds its bodies.
class Scene
{
public:
	~Scene();
	/// Imports the file and adds its bodies and joints to the world; false (document().error says why)
	/// when it does not load.
	bool load(const char* path);
	btDiscreteDynamicsWorld& world() { return m_physics.world(); }
	caliber::ColladaPhysicsScene& document() { return m_document; }

private:
	caliber::demo::DemoWorld m_physics;  // the world, first in and last out
	caliber::ColladaPhysicsScene m_document;
	bool m_added = false;
};
}  // namespace collada_demo

#endif
