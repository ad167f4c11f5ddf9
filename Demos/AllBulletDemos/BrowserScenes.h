// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_ALL_BULLET_DEMOS_BROWSER_SCENES_H
#define CALIBER_ALL_BULLET_DEMOS_BROWSER_SCENES_H
// The demos AllBulletDemos lists: each owns a world that the browser steps, draws and lets the user
// poke. The scenes are the demos' own (BenchmarkScenes, ConstraintScene, Ragdoll, ...), shared with
// the headless programs. The demos without a world to step (LinearMathDemo, SimplexDemo, ...) run
// their program once and the browser replays what they drew (DemoPictures' SceneRecording), in a
// world of their own that holds only the boxes the user shoots.

#include <memory>
#include <string>
#include <vector>

#include "BenchmarkScenes.h"
#include "Scene.h"

namespace all_bullet_demos
{
/// The keys a driven demo reads each step (the vehicle, the character, the fork lift): arrows and
/// U / D (the fork), each -1, 0 or 1.
struct Controls
{
	int forward = 0;     ///< up arrow 1, down arrow -1
	int turn = 0;        ///< left arrow 1, right arrow -1
	int lift = 0;        ///< U 1, D -1
	bool brake = false;  ///< Enter: brake, or jump for the character
};

/// One demo in the browser: its world and how it steps.
class BrowserDemo
{
public:
	virtual ~BrowserDemo() {}
	virtual btDiscreteDynamicsWorld& world() = 0;
	/// One 1/60 s step, with whatever the demo does around it (a motor's torque, ray casts).
	virtual void step() = 0;
	/// True for a demo the arrow keys drive (they then no longer switch demos).
	virtual bool driven() const { return false; }
	/// The keys held for the next step (called before step() when driven()).
	virtual void control(const Controls& /*controls*/) {}
	/// Where the driven body is (the car, the character, the fork lift), for --hold's report.
	virtual btVector3 driverPosition() { return btVector3(0, 0, 0); }
	/// Adds what the world does not hold (a raycast vehicle's wheels) to the drawing.
	virtual void decorate(caliber::demo::Scene& /*scene*/) {}
	/// A line for the on-screen text (a replay's progress, why a demo is missing), or empty.
	virtual std::string notice() const { return std::string(); }
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
