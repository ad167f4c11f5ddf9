// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_ALL_BULLET_DEMOS_BROWSER_SCENES_H
#define CALIBER_ALL_BULLET_DEMOS_BROWSER_SCENES_H
// The demos AllBulletDemos lists: each owns a world that the browser steps, draws and lets the user
// poke. The scenes are the demos' own (BenchmarkScenes, ConstraintScene, Ragdoll), shared with the
// headless programs.

#include <memory>
#include <string>
#include <vector>

#include "BenchmarkScenes.h"

namespace all_bullet_demos
{
/// One demo in the browser: its world and how it steps.
class BrowserDemo
{
public:
	virtual ~BrowserDemo() {}
	virtual btDiscreteDynamicsWorld& world() = 0;
	/// One 1/60 s step, with whatever the demo does around it (a motor's torque, ray casts).
	virtual void step() = 0;
	/// Where the camera starts: false to frame what moves from the default view, as the pictures do.
	virtual bool startView(btVector3& /*focusMin*/, btVector3& /*focusMax*/, btVector3& /*viewDirection*/) const
	{
		return false;
	}
};

/// The names of the browser's demos, in the order of its list.
std::vector<std::string> demoNames();
/// Builds the named demo (null for an unknown name).
std::unique_ptr<BrowserDemo> makeDemo(const std::string& name);
}  // namespace all_bullet_demos

#endif
