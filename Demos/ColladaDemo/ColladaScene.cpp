// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "ColladaScene.h"

namespace collada_demo
{
bool Scene::load(const char* path)
{
	if (m_added || !caliber::importColladaPhysicsFile(path, m_document)) return false;
	m_document.addTo(world());
	m_added = true;
	return true;
}

Scene::~Scene()
{
	// The bodies leave the world before either is destroyed.
	if (m_added) m_document.removeFrom(world());
}
}  // namespace collada_demo
