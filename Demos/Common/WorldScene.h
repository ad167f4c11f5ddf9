// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_COMMON_WORLD_SCENE_H
#define CALIBER_DEMOS_COMMON_WORLD_SCENE_H
// Fills a Scene from a btCollisionWorld: every object's shape as a solid (grounds and walls, static and
// at least 4 m across two ways, grey with a 1 m checker; the others in a palette by their order; soft bodies
// through SoftBodyScene, framed on their nodes), plus whatever the
// world's debugDrawWorld() draws for the chosen btIDebugDraw modes (joint frames and limits, AABBs, contact points,
// wireframes). SceneDebugDraw is the btIDebugDraw that records into a Scene; any code can use it. Demo-side code.

#include "LinearMath/btIDebugDraw.h"
#include "Scene.h"

class btCollisionWorld;
class btRaycastVehicle;

namespace caliber
{
namespace demo
{
/// A btIDebugDraw that records lines and contact points into a Scene.
class SceneDebugDraw : public btIDebugDraw
{
public:
	explicit SceneDebugDraw(Scene& scene, int debugMode = DBG_DrawConstraints | DBG_DrawConstraintLimits)
	    : m_scene(scene), m_mode(debugMode)
	{
	}
	void drawLine(const btVector3& from, const btVector3& to, const btVector3& color) override;
	/// A contact point: a dot, and its normal as a short line (length 0.2 in the scene's units).
	void drawContactPoint(const btVector3& pointOnB, const btVector3& normalOnB, btScalar distance, int lifeTime,
	                      const btVector3& color) override;
	/// Prints the warning to stderr.
	void reportErrorWarning(const char* warningString) override;
	/// Text is not drawn (the renderer has no font).
	void draw3dText(const btVector3&, const char*) override {}
	void setDebugMode(int debugMode) override { m_mode = debugMode; }
	int getDebugMode() const override { return m_mode; }

private:
	Scene& m_scene;
	int m_mode;
};

/// What addWorld() draws besides the solid shapes.
struct WorldStyle
{
	/// btIDebugDraw::DebugDrawModes bits for debugDrawWorld(); 0 draws no overlay.
	int debugMode = btIDebugDraw::DBG_DrawConstraints | btIDebugDraw::DBG_DrawConstraintLimits;
	/// Draw the solid shapes (off: only the debug overlay).
	bool solids = true;
};

/// Adds world's objects (and its debug drawing) to scene, and focuses the scene on the objects that
/// move (every finite object when none moves). The world's own debug drawer is put back afterwards.
/// Returns how many objects had a shape the mesher cannot draw (they are left out).
int addWorld(Scene& scene, btCollisionWorld& world, const WorldStyle& style = WorldStyle());

/// Adds a raycast vehicle's wheels (not collision objects, so addWorld() cannot see them) as dark
/// cylinders of the given width at the vehicle's wheel transforms.
void addVehicleWheels(Scene& scene, btRaycastVehicle& vehicle, btScalar width);

/// The colour addWorld() gives the index-th object that is not a ground.
btVector3 paletteColor(int index);
}  // namespace demo
}  // namespace caliber

#endif
