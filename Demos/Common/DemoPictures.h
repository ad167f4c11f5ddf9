// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_COMMON_DEMO_PICTURES_H
#define CALIBER_DEMOS_COMMON_DEMO_PICTURES_H
// The command line every demo shares, and its pictures. A demo makes one DemoPictures from argc and
// argv, runs pictures.frames() steps calling pictures.frame(world, n) after each, and returns
// pictures.finish(exitCode). Options (docs/demos.md):
//   --png PATH            a picture of the last frame
//   --frames N            steps to run instead of the demo's default
//   --png-sequence DIR    a picture every K frames, DIR/<demo>-0001.png, -0002, ... (demos that allow it)
//   --every K             the K of --png-sequence (default 30)
//   --size WxH            picture size (default 640x480)
//   --draw LIST           overlays: joints, contacts, aabbs, wireframe, frames, or none (default: the demo's)
//   --help
// Demo-side code.

#include <functional>
#include <string>
#include <vector>

#include "Renderer.h"
#include "Scene.h"

class btCollisionWorld;

namespace caliber
{
namespace demo
{
/// What a demo accepts besides the shared options.
struct DemoCommandLine
{
	/// The demo's name (file names of sequences, messages).
	const char* name = "demo";
	/// Steps the demo runs when --frames is not given; 0 for a demo without a frame loop (it then
	/// rejects --frames).
	int defaultFrames = 0;
	/// The most steps --frames may ask for (a scripted demo's script length); 0 for no limit.
	int maxFrames = 0;
	/// Whether --png-sequence is allowed.
	bool sequences = false;
	/// The picture size when --size is not given (a long row of things wants a wide picture).
	int defaultWidth = 640;
	int defaultHeight = 480;
	/// The overlay when --draw is not given: btIDebugDraw::DebugDrawModes bits, 0 for solids only.
	int debugDrawMode = 0;
	/// How many positional (non-option) arguments the demo takes, and how its usage line shows them.
	int maxPositional = 0;
	const char* positionalUsage = "";
};

/// What the demos drew, kept instead of pictures while a recording is set (setSceneRecording): the
/// demo browser shows the demos without a world of their own to step this way. One shot per picture
/// a demo takes (capture()) and per frame() of its run, each with the camera the picture would use.
struct SceneRecording
{
	struct Shot
	{
		Scene scene;
		btVector3 focusMin, focusMax, viewDirection;
	};
	std::vector<Shot> shots;
};

/// While recording is set (not null), every DemoPictures made records its scenes there instead of
/// writing pictures (wanted() and recording() are true, --png is refused); null ends it. One thread:
/// the browser sets it around one run of a demo.
void setSceneRecording(SceneRecording* recording);

/// A scripted demo's step budget under --frames: counts the steps, says when the budget is spent (no
/// phase steps any more) and whether a phase's check may be judged.
class StepBudget
{
public:
	/// frames: the steps allowed; shortened: whether --frames cut the demo's default run.
	StepBudget(int frames, bool shortened) : m_frames(frames), m_shortened(shortened) {}
	/// True once the budget is used up.
	bool spent() const { return m_steps >= m_frames; }
	/// Counts one step.
	void count() { ++m_steps; }
	/// False, after printing "check: WHAT: not reached (--frames N)", when --frames cut the phase of
	/// this check short; true when it may be judged.
	bool reached(const char* what) const;

private:
	int m_frames;
	bool m_shortened;
	int m_steps = 0;
};

/// Parses the shared options and writes the demo's pictures.
class DemoPictures
{
public:
	DemoPictures(int argc, char** argv, const DemoCommandLine& commandLine);
	/// A demo whose command line is the default one but for its name (no frames, no positional arguments).
	DemoPictures(int argc, char** argv, const char* name);

	/// False when the command line was wrong, --help was asked for, or pictures were asked for in a
	/// build without libpng: the message is printed and the demo should return exitCode() at once.
	bool ok() const { return m_ok; }
	/// 0 after --help, 2 after a usage error.
	int exitCode() const { return m_exitCode; }
	/// Steps to run: --frames N, else the demo's default.
	int frames() const { return m_frames; }
	/// The step budget of a scripted demo: frames() steps.
	StepBudget stepBudget() const { return StepBudget(m_frames, shortened()); }
	/// True when --frames was given.
	bool framesGiven() const { return m_framesGiven; }
	/// True when --frames asked for fewer steps than the demo's default: checks that need the whole run
	/// are skipped then (each demo says which).
	bool shortened() const { return m_frames < m_commandLine.defaultFrames; }
	/// The positional arguments, in order.
	const std::vector<std::string>& positional() const { return m_positional; }
	/// True when --png or --png-sequence was given (a demo may skip building a picture scene otherwise).
	bool wanted() const { return !m_pngPath.empty() || !m_sequenceDir.empty() || m_recording; }
	/// True while the browser records the demo's scenes (setSceneRecording).
	bool recording() const { return m_recording != nullptr; }

	/// Call after step n (1-based) of a world: writes a sequence picture every K frames, and keeps a
	/// picture of the world when n == frames() (the last frame).
	void frame(btCollisionWorld& world, int n);
	/// Keeps a picture of world now, as the last frame (for demos whose last frame is not step frames()).
	void capture(btCollisionWorld& world);
	/// Keeps a picture of a scene the demo built itself (demos without a dynamics world).
	void capture(const Scene& scene);
	/// Keeps a picture the demo made itself (the Raytracer's image).
	void capture(const Image& image);
	/// The --size asked for, or the default 640 x 480; sizeGiven() says whether --size was given.
	int width() const { return m_options.width; }
	int height() const { return m_options.height; }
	bool sizeGiven() const { return m_sizeGiven; }
	/// Looks at the scene from this direction instead of the default (front, above, right).
	void setViewDirection(const btVector3& direction) { m_viewDirection = direction; }
	/// Frames this box instead of the moving objects.
	void setFocus(const btVector3& aabbMin, const btVector3& aabbMax);
	/// Adds what the world does not hold (a vehicle's wheels, a path) to every world picture; it runs
	/// after the world's objects are in the scene and may widen its focus with Scene::focusOn().
	void setDecorator(std::function<void(Scene&)> decorator) { m_decorator = std::move(decorator); }

	/// Writes the --png picture, prints where the pictures went, and returns exitCode, or 1 when a
	/// picture could not be made or written (exitCode 0 only).
	int finish(int exitCode);

private:
	bool renderScene(Scene& scene, Image& image, bool sequence);
	void focusOf(const Scene& scene, btVector3& focusMin, btVector3& focusMax) const;
	void record(const Scene& scene);
	void buildWorldScene(btCollisionWorld& world);
	void fail(const std::string& message);

	DemoCommandLine m_commandLine;
	bool m_ok = true;
	int m_exitCode = 0;
	int m_frames = 0;
	bool m_framesGiven = false;
	bool m_sizeGiven = false;
	std::vector<std::string> m_positional;
	std::string m_pngPath, m_sequenceDir;
	int m_every = 30;
	int m_debugMode = 0;
	RenderOptions m_options;
	btVector3 m_viewDirection{-0.55f, -0.45f, -1};
	btVector3 m_focusMin{0, 0, 0}, m_focusMax{0, 0, 0};
	bool m_hasFocus = false;
	std::function<void(Scene&)> m_decorator;
	Scene m_scene;
	Image m_last;
	bool m_captured = false;
	int m_sequenceWritten = 0;
	btVector3 m_sequenceFocusMin{0, 0, 0}, m_sequenceFocusMax{0, 0, 0};
	bool m_sequenceFramed = false;
	bool m_failed = false;
	SceneRecording* m_recording = nullptr;
};
}  // namespace demo
}  // namespace caliber

#endif
