// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// AllBulletDemos: the demo browser. Every demo of its list in one window (GLFW, OpenGL 3.3 core),
// drawn with the same scene the headless pictures use (Demos/Common) and stepped at 60 Hz.
//
// Mouse: left-drag a body to pull it (a point-to-point joint to the cursor, as Bullet's demos do) or
// a soft body to hold its nearest node, left-drag elsewhere to orbit, right-drag to pan, wheel to zoom.
// Keys: space pause, S single step, R reset, B shoot a box, W wireframe, A AABBs, C contact points,
// J joint frames and limits, P print the step's profile (btQuickprof), F frame the scene again,
// H hide or show the on-screen text (demo, body count, step and frame times, btQuickprof's profile),
// N / Page Down / right arrow next demo, Page Up / left arrow previous, Esc quit. In a driven demo
// (VehicleDemo, CharacterDemo, ForkLiftDemo) the arrows drive instead (up/down: throttle or walk,
// left/right: steer or turn), Enter brakes (the character jumps), U / D raise and lower the fork,
// and the camera follows the driver. The title bar shows the demo, the body count, the step time
// and the frame time.
//
// Automation: --demo NAME --frames N --screenshot PATH runs N steps without input, draws the last
// frame and writes it as a PNG (CI runs this under Xvfb with Mesa). --drag X0,Y0,X1,Y1 (window
// pixels) does what a user's left-drag would during those N steps: press at (X0, Y0), move to
// (X1, Y1), release at the end; it reports the body it picked and how far it moved, and fails when
// nothing was picked. --hold KEYS (comma-separated: up, down, left, right, enter, u, d) holds those
// keys through the N steps of a driven demo and reports how far the driver moved. --orbit DX,DY,
// --pan DX,DY and --wheel N move the camera before the first step; --keys KEY@FRAME,... presses keys
// before given steps. A scripted run prints the bodies at its start and end (with a hash of their
// exact positions) and the camera, for .ci/lib.sh's tests. --list prints the demos.

#define GLFW_INCLUDE_GLCOREARB
#define GL_GLEXT_PROTOTYPES
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "BitmapFont.h"
#include "BrowserScenes.h"
#include "GlRenderer.h"
#include "BulletSoftBody/btSoftBody.h"
#include "LinearMath/btQuickprof.h"
#include "Png.h"
#include "WorldScene.h"

namespace
{
std::string gGlfwError = "no error reported";

void onGlfwError(int code, const char* description)
{
	gGlfwError = std::string(description ? description : "unknown") + " (GLFW error " + std::to_string(code) + ")";
}

struct Options
{
	std::string demo = "BasicDemo";
	int frames = 0;  // 0: interactive
	std::string screenshot;
	int width = 1024, height = 768;
	bool drag = false;
	double dragFrom[2] = {0, 0}, dragTo[2] = {0, 0};
	bool hold = false;
	all_bullet_demos::Controls held;
	double orbit[2] = {0, 0}, pan[2] = {0, 0}, wheel = 0;
	struct KeyPress
	{
		int key;
		int frame;
	};
	std::vector<KeyPress> keys;
};

// The keys --keys knows, by name.
struct NamedKey
{
	const char* name;
	int key;
};
const NamedKey kNamedKeys[] = {
    {"space", GLFW_KEY_SPACE},
    {"s", GLFW_KEY_S},
    {"r", GLFW_KEY_R},
    {"b", GLFW_KEY_B},
    {"w", GLFW_KEY_W},
    {"a", GLFW_KEY_A},
    {"c", GLFW_KEY_C},
    {"j", GLFW_KEY_J},
    {"p", GLFW_KEY_P},
    {"f", GLFW_KEY_F},
    {"h", GLFW_KEY_H},
    {"n", GLFW_KEY_N},
    {"pagedown", GLFW_KEY_PAGE_DOWN},
    {"pageup", GLFW_KEY_PAGE_UP},
    {"left", GLFW_KEY_LEFT},
    {"right", GLFW_KEY_RIGHT},
};

// Parses --keys' list (KEY@FRAME, comma-separated) into keys; false for an unknown key or a bad frame.
bool parseKeys(const std::string& list, std::vector<Options::KeyPress>& keys)
{
	size_t start = 0;
	while (start <= list.size())
	{
		const size_t comma = std::min(list.find(',', start), list.size());
		const std::string item = list.substr(start, comma - start);
		const size_t at = item.find('@');
		if (at == std::string::npos) return false;
		const std::string name = item.substr(0, at), frameText = item.substr(at + 1);
		char* end = nullptr;
		const long frame = std::strtol(frameText.c_str(), &end, 10);
		if (frameText.empty() || *end != '\0' || frame < 0 || frame > 10000000) return false;
		int key = -1;
		for (const NamedKey& named : kNamedKeys)
			if (name == named.name) key = named.key;
		if (key < 0) return false;
		keys.push_back({key, int(frame)});
		start = comma + 1;
	}
	return true;
}

// Parses --hold's list into held; false for an unknown key.
bool parseHeld(const std::string& list, all_bullet_demos::Controls& held)
{
	size_t start = 0;
	while (start <= list.size())
	{
		const size_t comma = std::min(list.find(',', start), list.size());
		const std::string key = list.substr(start, comma - start);
		if (key == "up")
			held.forward = 1;
		else if (key == "down")
			held.forward = -1;
		else if (key == "left")
			held.turn = 1;
		else if (key == "right")
			held.turn = -1;
		else if (key == "enter")
			held.brake = true;
		else if (key == "u")
			held.lift = 1;
		else if (key == "d")
			held.lift = -1;
		else
			return false;
		start = comma + 1;
	}
	return true;
}

// Parses the command line; returns -1 to go on, else the exit code.
int parse(int argc, char** argv, Options& options)
{
	auto usage = [&](FILE* out)
	{
		std::fprintf(
		    out,
		    "usage: %s [--demo NAME] [--frames N] [--screenshot PATH] [--size WxH] [--drag X0,Y0,X1,Y1]\n"
		    "  [--hold KEYS] [--orbit DX,DY] [--pan DX,DY] [--wheel N] [--keys KEY@FRAME,...] [--list]\n"
		    "  --frames N without input: run N steps and exit; --screenshot writes the last frame as PNG\n"
		    "  --keys: space s r b w a c j p f h n pageup pagedown left right, each before step FRAME (0: first)\n",
		    argv[0]);
	};
	for (int i = 1; i < argc; ++i)
	{
		const std::string option = argv[i];
		const char* value = i + 1 < argc ? argv[i + 1] : nullptr;
		if (option == "--help" || option == "-h")
		{
			usage(stdout);
			return 0;
		}
		if (option == "--list")
		{
			for (const std::string& name : all_bullet_demos::demoNames()) std::printf("%s\n", name.c_str());
			return 0;
		}
		if (!value)
		{
			std::fprintf(stderr, "AllBulletDemos: %s needs a value\n", option.c_str());
			usage(stderr);
			return 2;
		}
		char* end = nullptr;
		char trailing = 0;
		if (option == "--demo")
			options.demo = value;
		else if (option == "--frames")
		{
			const long frames = std::strtol(value, &end, 10);
			if (*end != '\0' || frames < 1 || frames > 10000000)
			{
				std::fprintf(stderr, "AllBulletDemos: --frames needs a whole number from 1 to 10000000, got '%s'\n",
				             value);
				return 2;
			}
			options.frames = int(frames);
		}
		else if (option == "--screenshot")
			options.screenshot = value;
		else if (option == "--drag")
		{
			if (std::sscanf(value, "%lf,%lf,%lf,%lf", &options.dragFrom[0], &options.dragFrom[1], &options.dragTo[0],
			                &options.dragTo[1]) != 4)
			{
				std::fprintf(stderr, "AllBulletDemos: --drag needs X0,Y0,X1,Y1 in window pixels, got '%s'\n", value);
				return 2;
			}
			options.drag = true;
		}
		else if (option == "--hold")
		{
			if (!parseHeld(value, options.held))
			{
				std::fprintf(stderr,
				             "AllBulletDemos: --hold needs keys from up, down, left, right, enter, u, d, got '%s'\n",
				             value);
				return 2;
			}
			options.hold = true;
		}
		else if (option == "--orbit" || option == "--pan")
		{
			double* pixels = option == "--orbit" ? options.orbit : options.pan;
			if (std::sscanf(value, "%lf,%lf%c", &pixels[0], &pixels[1], &trailing) != 2 || !std::isfinite(pixels[0]) ||
			    !std::isfinite(pixels[1]) || std::fabs(pixels[0]) > 1e5 || std::fabs(pixels[1]) > 1e5)
			{
				std::fprintf(stderr, "AllBulletDemos: %s needs DX,DY in window pixels (up to 100000), got '%s'\n",
				             option.c_str(), value);
				return 2;
			}
		}
		else if (option == "--wheel")
		{
			options.wheel = std::strtod(value, &end);
			if (*end != '\0' || end == value || !(std::fabs(options.wheel) <= 100))
			{
				std::fprintf(stderr, "AllBulletDemos: --wheel needs wheel steps from -100 to 100, got '%s'\n", value);
				return 2;
			}
		}
		else if (option == "--keys")
		{
			if (!parseKeys(value, options.keys))
			{
				std::fprintf(stderr,
				             "AllBulletDemos: --keys needs KEY@FRAME,... with KEY one of space s r b w a c j p f h n "
				             "pageup pagedown left right and FRAME from 0, got '%s'\n",
				             value);
				return 2;
			}
		}
		else if (option == "--size")
		{
			if (std::sscanf(value, "%dx%d", &options.width, &options.height) != 2 || options.width < 1 ||
			    options.height < 1 || options.width > 8192 || options.height > 8192)
			{
				std::fprintf(stderr, "AllBulletDemos: --size needs WIDTHxHEIGHT, each side 1 to 8192, got '%s'\n",
				             value);
				return 2;
			}
		}
		else
		{
			std::fprintf(stderr, "AllBulletDemos: unknown option %s\n", option.c_str());
			usage(stderr);
			return 2;
		}
		++i;
	}
	const bool scripted = !options.screenshot.empty() || options.drag || options.hold || !options.keys.empty() ||
	                      options.wheel != 0 || options.orbit[0] != 0 || options.orbit[1] != 0 || options.pan[0] != 0 ||
	                      options.pan[1] != 0;
	if (scripted && options.frames == 0) options.frames = 60;
	for (const Options::KeyPress& press : options.keys)
		if (press.frame > options.frames)
		{
			std::fprintf(stderr, "AllBulletDemos: --keys: frame %d is after the last step (--frames %d)\n", press.frame,
			             options.frames);
			return 2;
		}
	if (!options.screenshot.empty() && !caliber::demo::pngAvailable())
	{
		std::fprintf(stderr, "AllBulletDemos: --screenshot is unavailable: this build has no libpng\n");
		return 2;
	}
	return -1;
}

class Browser
{
public:
	Browser(GLFWwindow* window, const std::vector<std::string>& names) : m_window(window), m_names(names) {}
	~Browser() { unload(); }

	void load(int index)
	{
		unload();
		++m_loads;
		m_index = (index % int(m_names.size()) + int(m_names.size())) % int(m_names.size());
		m_scene = all_bullet_demos::makeDemo(m_names[size_t(m_index)]);
		m_stepMs = 0;
		m_driver = m_scene->driverPosition();
		frameCamera();
	}

	// Aims the orbit camera as the headless pictures do: at what moves, from the front, above, right
	// (or where the demo says).
	void frameCamera()
	{
		caliber::demo::Scene scene;
		btVector3 focusMin, focusMax, direction(btScalar(-0.55), btScalar(-0.45), -1);
		if (m_scene->startView(focusMin, focusMax, direction))
			scene.focusOn(focusMin, focusMax);
		else
		{
			caliber::demo::WorldStyle style;
			style.solids = false;
			style.debugMode = 0;
			caliber::demo::addWorld(scene, m_scene->world(), style);
			m_scene->decorate(scene);
		}
		int width = 1, height = 1;
		glfwGetFramebufferSize(m_window, &width, &height);
		caliber::demo::RenderOptions options;
		options.width = width;
		options.height = btMax(1, height);
		const caliber::demo::Camera camera = caliber::demo::frameScene(scene, options, direction);
		m_target = camera.target;
		m_distance = (camera.eye - camera.target).length();
		const btVector3 d = (camera.target - camera.eye).normalized();
		m_pitch = btAsin(-d.y());
		m_yaw = btAtan2(-d.x(), -d.z());
	}

	caliber::demo::Camera camera() const
	{
		caliber::demo::Camera camera;
		const btVector3 d(-btCos(m_pitch) * btSin(m_yaw), -btSin(m_pitch), -btCos(m_pitch) * btCos(m_yaw));
		camera.target = m_target;
		camera.eye = m_target - d * m_distance;
		return camera;
	}

	/// Replaces the keyboard's driving keys (automation's --hold).
	void holdKeys(const all_bullet_demos::Controls& held)
	{
		m_scripted = true;
		m_held = held;
	}
	all_bullet_demos::BrowserDemo& demo() { return *m_scene; }
	/// How many times a demo was loaded (R and N load again: what was picked before is gone).
	int loads() const { return m_loads; }
	/// The name of the demo shown now.
	const std::string& name() const { return m_names[size_t(m_index)]; }

	// The driving keys held now (or the scripted ones).
	all_bullet_demos::Controls controls() const
	{
		if (m_scripted) return m_held;
		all_bullet_demos::Controls c;
		auto down = [&](int key) { return glfwGetKey(m_window, key) == GLFW_PRESS; };
		c.forward = (down(GLFW_KEY_UP) ? 1 : 0) - (down(GLFW_KEY_DOWN) ? 1 : 0);
		c.turn = (down(GLFW_KEY_LEFT) ? 1 : 0) - (down(GLFW_KEY_RIGHT) ? 1 : 0);
		c.lift = (down(GLFW_KEY_U) ? 1 : 0) - (down(GLFW_KEY_D) ? 1 : 0);
		c.brake = down(GLFW_KEY_ENTER);
		return c;
	}

	void step()
	{
		if (m_scene->driven()) m_scene->control(controls());
		if (m_pickedSoft) pullNode();
		const auto start = std::chrono::steady_clock::now();
		m_scene->step();
		m_stepMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
		if (m_scene->driven())
		{
			// The camera follows the driver.
			const btVector3 driver = m_scene->driverPosition();
			m_target += driver - m_driver;
			m_driver = driver;
		}
		// The on-screen profile: btQuickprof's zones averaged over the last kProfileSteps steps.
		CProfileManager::Increment_Frame_Counter();
		if (CProfileManager::Get_Frame_Count_Since_Reset() >= kProfileSteps)
		{
			m_profile = profileText();
			CProfileManager::Reset();
		}
	}

	// The held node follows the cursor: each step it closes a quarter of the gap, at most 0.3 m (18 m/s),
	// so a fast flick does not tear the body's links.
	void pullNode()
	{
		btSoftBody::Node& node = m_pickedSoft->m_nodes[m_pickedNode];
		btVector3 move = (m_softTarget - node.m_x) * btScalar(0.25);
		const btScalar length = move.length();
		if (length > btScalar(0.3)) move *= btScalar(0.3) / length;
		node.m_x += move;
		m_pickedSoft->activate(true);
	}

	/// The frame time the window loop measured (shown on screen and in the title).
	void setFrameTime(double ms) { m_frameMs = ms; }

	/// btQuickprof's tree (two levels below the root) as text lines: each zone's milliseconds per step.
	static std::string profileText()
	{
		const int frames = std::max(1, CProfileManager::Get_Frame_Count_Since_Reset());
		std::string text;
		CProfileIterator* it = CProfileManager::Get_Iterator();
		if (!it) return text;
		addProfileLevel(*it, frames, 0, text);
		CProfileManager::Release_Iterator(it);
		return text;
	}

	static void addProfileLevel(CProfileIterator& it, int frames, int depth, std::string& text)
	{
		int count = 0;
		for (it.First(); !it.Is_Done(); it.Next()) ++count;
		for (int i = 0; i < count && text.size() < 2000; ++i)
		{
			it.First();
			for (int k = 0; k < i; ++k) it.Next();
			char line[160];
			std::snprintf(line, sizeof(line), "%*s%-34.34s %7.3f MS\n", 2 + 2 * depth, "", it.Get_Current_Name(),
			              double(it.Get_Current_Total_Time()) / frames);
			text += line;
			if (depth < 1)
			{
				it.Enter_Child(i);
				addProfileLevel(it, frames, depth + 1, text);
				it.Enter_Parent();
			}
		}
	}

	/// What the on-screen text says: the demo, its bodies, the step and frame times, the profile.
	std::string overlayText() const
	{
		char head[256];
		std::snprintf(head, sizeof(head), "%s   BODIES %d   STEP %.2f MS   FRAME %.1f MS%s\n",
		              m_names[size_t(m_index)].c_str(), m_scene->world().getNumCollisionObjects(), m_stepMs, m_frameMs,
		              m_paused ? "   PAUSED" : "");
		std::string text = head;
		if (m_scene->driven()) text += "ARROWS DRIVE, ENTER BRAKES OR JUMPS, U/D FORK, N NEXT DEMO\n";
		if (!m_scene->notice().empty()) text += m_scene->notice() + "\n";
		text += "PROFILE, MS PER STEP (LAST 60 STEPS; H HIDES):\n";
		text += m_profile.empty() ? std::string("  (after 60 steps)\n") : m_profile;
		return text;
	}

	void draw(all_bullet_demos::GlRenderer& gl)
	{
		caliber::demo::Scene scene;
		caliber::demo::WorldStyle style;
		style.debugMode = m_debugMode;
		caliber::demo::addWorld(scene, m_scene->world(), style);
		m_scene->decorate(scene);
		int width = 0, height = 0;
		glfwGetFramebufferSize(m_window, &width, &height);
		gl.draw(scene, camera(), width, height, m_wireframe);
		if (m_showText)
		{
			m_textCells.clear();
			const float scale = width >= 900 ? 2.0f : 1.0f;
			caliber::demo::layoutText(overlayText(), 8 * scale, 8 * scale, scale, m_textCells);
			gl.drawText(m_textCells, btVector3(btScalar(0.08), btScalar(0.08), btScalar(0.14)), width, height);
		}
	}

	/// Replaces the mouse's position (automation's scripted drag).
	void setCursor(double x, double y)
	{
		m_cursorSet = true;
		m_cursorX = x;
		m_cursorY = y;
	}
	btRigidBody* picked() const { return m_picked; }

	// A ray from the eye through the cursor, in world space.
	btVector3 rayThroughCursor() const
	{
		double x = m_cursorX, y = m_cursorY;
		int width = 1, height = 1;
		if (!m_cursorSet) glfwGetCursorPos(m_window, &x, &y);
		glfwGetWindowSize(m_window, &width, &height);
		const caliber::demo::Camera c = camera();
		const btVector3 forward = (c.target - c.eye).normalized();
		const btVector3 right = forward.cross(c.up).normalized();
		const btVector3 up = right.cross(forward);
		const double t = std::tan(double(c.fieldOfViewDegrees) * M_PI / 360.0);
		const double aspect = double(width) / double(btMax(1, height));
		const double u = (2 * x / btMax(1, width) - 1) * aspect * t, v = (1 - 2 * y / btMax(1, height)) * t;
		return (forward + right * btScalar(u) + up * btScalar(v)).normalized();
	}

	void pressLeft()
	{
		const btVector3 eye = camera().eye, direction = rayThroughCursor();
		const btVector3 to = eye + direction * btScalar(1e4);
		btCollisionWorld::ClosestRayResultCallback hit(eye, to);
		m_scene->world().rayTest(eye, to, hit);
		btSoftBody* soft =
		    hit.hasHit() ? btSoftBody::upcast(const_cast<btCollisionObject*>(hit.m_collisionObject)) : nullptr;
		if (soft && pickNode(*soft, hit.m_hitPointWorld))
		{
			m_pickDistance = (hit.m_hitPointWorld - eye).length();
			return;
		}
		btRigidBody* body =
		    hit.hasHit() ? const_cast<btRigidBody*>(btRigidBody::upcast(hit.m_collisionObject)) : nullptr;
		if (!body || body->isStaticOrKinematicObject())
		{
			m_orbiting = true;
			return;
		}
		// Pull the body at the point under the cursor, as Bullet's demos do.
		m_picked = body;
		m_picked->setActivationState(DISABLE_DEACTIVATION);
		const btVector3 pivot = body->getCenterOfMassTransform().inverse()(hit.m_hitPointWorld);
		m_pickJoint.reset(new btPoint2PointConstraint(*body, pivot));
		m_pickJoint->m_setting.m_impulseClamp = 30;
		m_pickJoint->m_setting.m_tau = btScalar(0.001);
		m_scene->world().addConstraint(m_pickJoint.get(), true);
		m_pickDistance = (hit.m_hitPointWorld - eye).length();
	}

	// Takes the soft body's free node nearest to the point hit; false when every node is fixed.
	bool pickNode(btSoftBody& soft, const btVector3& at)
	{
		int nearest = -1;
		btScalar best = BT_LARGE_FLOAT;
		for (int i = 0; i < soft.m_nodes.size(); ++i)
		{
			const btScalar d = (soft.m_nodes[i].m_x - at).length2();
			if (soft.m_nodes[i].m_im > 0 && d < best)
			{
				best = d;
				nearest = i;
			}
		}
		if (nearest < 0) return false;
		m_pickedSoft = &soft;
		m_pickedNode = nearest;
		m_softTarget = soft.m_nodes[nearest].m_x;
		// While held, the node is fixed (mass 0) and moved by the cursor: the links then pull the rest of
		// the body along, however heavy, as a hand holding a cloth would. Its mass comes back on release.
		m_pickedNodeMass = soft.getMass(nearest);
		soft.setMass(nearest, 0);
		return true;
	}

	/// The soft body and node a left-drag holds (null, -1 when none).
	btSoftBody* pickedSoft() const { return m_pickedSoft; }
	int pickedNode() const { return m_pickedNode; }
	const btVector3& softTarget() const { return m_softTarget; }

	void releaseLeft()
	{
		m_orbiting = false;
		dropPick();
	}

	void drag(double dx, double dy, bool right)
	{
		if (m_pickJoint)
			m_pickJoint->setPivotB(camera().eye + rayThroughCursor() * m_pickDistance);
		else if (m_pickedSoft)
			m_softTarget = camera().eye + rayThroughCursor() * m_pickDistance;
		else if (m_orbiting && !right)
			orbit(dx, dy);
		else if (right)
			pan(dx, dy);
	}

	/// A left-drag over empty space: turns the camera around its target, 0.005 rad a pixel.
	void orbit(double dx, double dy)
	{
		m_yaw -= btScalar(dx * 0.005);
		m_pitch = btClamped(m_pitch + btScalar(dy * 0.005), btScalar(-1.5), btScalar(1.5));
	}

	/// A right-drag: moves the target with the cursor (the scene follows the mouse), in proportion to the distance.
	void pan(double dx, double dy)
	{
		const caliber::demo::Camera c = camera();
		const btVector3 forward = (c.target - c.eye).normalized();
		const btVector3 side = forward.cross(c.up).normalized();
		const btVector3 up = side.cross(forward);
		m_target += (side * btScalar(-dx) + up * btScalar(dy)) * m_distance * btScalar(0.0015);
	}

	/// The camera as text, for automation's report.
	std::string cameraText() const
	{
		char text[200];
		std::snprintf(text, sizeof(text), "target (%.3f, %.3f, %.3f), yaw %.4f, pitch %.4f, distance %.4f",
		              double(m_target.x()), double(m_target.y()), double(m_target.z()), double(m_yaw), double(m_pitch),
		              double(m_distance));
		return text;
	}

	/// The world's state as text, for automation's report: its objects, the dynamic rigid bodies' mean
	/// centre and a hash of their exact positions (equal hashes: the same state).
	std::string stateText()
	{
		btDiscreteDynamicsWorld& world = m_scene->world();
		int dynamic = 0;
		btVector3 sum(0, 0, 0);
		std::uint64_t hash = 1469598103934665603ull;  // FNV-1a over the positions' bytes
		for (int i = 0; i < world.getNumCollisionObjects(); ++i)
		{
			const btRigidBody* body = btRigidBody::upcast(world.getCollisionObjectArray()[i]);
			if (!body || body->isStaticOrKinematicObject()) continue;
			++dynamic;
			const btVector3 at = body->getCenterOfMassPosition();
			sum += at;
			for (int k = 0; k < 3; ++k)
			{
				unsigned char bytes[sizeof(btScalar)];
				std::memcpy(bytes, &at[k], sizeof(btScalar));
				for (unsigned char byte : bytes) hash = (hash ^ byte) * 1099511628211ull;
			}
		}
		const btVector3 mean = dynamic > 0 ? sum / btScalar(dynamic) : sum;
		char text[200];
		std::snprintf(text, sizeof(text), "%d objects, %d dynamic, mean centre (%.4f, %.4f, %.4f), hash %016llx%s",
		              world.getNumCollisionObjects(), dynamic, double(mean.x()), double(mean.y()), double(mean.z()),
		              static_cast<unsigned long long>(hash), m_paused ? ", paused" : "");
		return text;
	}

	void zoom(double steps) { m_distance *= btScalar(std::pow(0.9, steps)); }

	void shootBox()
	{
		const caliber::demo::Camera c = camera();
		btVector3 inertia;
		m_shotShape.calculateLocalInertia(1, inertia);
		btRigidBody::btRigidBodyConstructionInfo info(1, nullptr, &m_shotShape, inertia);
		info.m_startWorldTransform = btTransform(btQuaternion::getIdentity(), c.eye);
		m_shots.emplace_back(new btRigidBody(info));
		m_shots.back()->setLinearVelocity((c.target - c.eye).normalized() * 25);
		m_scene->world().addRigidBody(m_shots.back().get());
	}

	void key(int key)
	{
		switch (key)
		{
			case GLFW_KEY_SPACE:
				m_paused = !m_paused;
				break;
			case GLFW_KEY_S:
				m_stepOnce = true;
				break;
			case GLFW_KEY_R:
				load(m_index);
				break;
			case GLFW_KEY_B:
				shootBox();
				break;
			case GLFW_KEY_W:
				m_wireframe = !m_wireframe;
				break;
			case GLFW_KEY_A:
				m_debugMode ^= btIDebugDraw::DBG_DrawAabb;
				break;
			case GLFW_KEY_C:
				m_debugMode ^= btIDebugDraw::DBG_DrawContactPoints;
				break;
			case GLFW_KEY_J:
				m_debugMode ^= btIDebugDraw::DBG_DrawConstraints | btIDebugDraw::DBG_DrawConstraintLimits;
				break;
			case GLFW_KEY_P:
				CProfileManager::dumpAll();
				break;
			case GLFW_KEY_F:
				frameCamera();
				break;
			case GLFW_KEY_H:
				m_showText = !m_showText;
				break;
			case GLFW_KEY_RIGHT:
			case GLFW_KEY_LEFT:
				// In a driven demo the arrows steer (read each step), so only N and the page keys switch.
				if (!m_scene->driven()) load(m_index + (key == GLFW_KEY_RIGHT ? 1 : -1));
				break;
			case GLFW_KEY_N:
			case GLFW_KEY_PAGE_DOWN:
				load(m_index + 1);
				break;
			case GLFW_KEY_PAGE_UP:
				load(m_index - 1);
				break;
			case GLFW_KEY_ESCAPE:
				glfwSetWindowShouldClose(m_window, 1);
				break;
			default:
				break;
		}
	}

	// Steps unless paused (a single step when asked).
	void advance()
	{
		if (!m_paused || m_stepOnce) step();
		m_stepOnce = false;
	}

	void updateTitle(double frameMs)
	{
		char title[256];
		std::snprintf(title, sizeof(title), "AllBulletDemos - %s - %d bodies - step %.2f ms - frame %.1f ms%s",
		              m_names[size_t(m_index)].c_str(), m_scene->world().getNumCollisionObjects(), m_stepMs, frameMs,
		              m_paused ? " - paused" : "");
		glfwSetWindowTitle(m_window, title);
	}

private:
	void dropPick()
	{
		if (m_pickedSoft) m_pickedSoft->setMass(m_pickedNode, m_pickedNodeMass);
		m_pickedSoft = nullptr;
		m_pickedNode = -1;
		if (!m_pickJoint) return;
		m_scene->world().removeConstraint(m_pickJoint.get());
		m_pickJoint.reset();
		m_picked->forceActivationState(ACTIVE_TAG);
		m_picked->setDeactivationTime(0);
		m_picked = nullptr;
	}

	// Takes out what the browser added to the world, then the world itself.
	void unload()
	{
		if (!m_scene) return;
		dropPick();
		for (auto& shot : m_shots) m_scene->world().removeRigidBody(shot.get());
		m_shots.clear();
		m_scene.reset();
	}

	GLFWwindow* m_window;
	std::vector<std::string> m_names;
	int m_index = 0;
	std::unique_ptr<all_bullet_demos::BrowserDemo> m_scene;
	btVector3 m_target{0, 0, 0};
	btScalar m_yaw = 0, m_pitch = btScalar(0.4), m_distance = 20;
	bool m_paused = false, m_stepOnce = false, m_wireframe = false, m_orbiting = false;
	int m_debugMode = 0;  // solids only; W, A, C and J add the overlays
	double m_stepMs = 0;
	btRigidBody* m_picked = nullptr;
	btSoftBody* m_pickedSoft = nullptr;
	int m_pickedNode = -1;
	btScalar m_pickedNodeMass = 0;
	btVector3 m_softTarget{0, 0, 0};
	std::unique_ptr<btPoint2PointConstraint> m_pickJoint;
	btScalar m_pickDistance = 0;
	bool m_cursorSet = false;
	double m_cursorX = 0, m_cursorY = 0;
	btBoxShape m_shotShape{btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5))};
	std::vector<std::unique_ptr<btRigidBody>> m_shots;
	int m_loads = 0;
	bool m_scripted = false;
	all_bullet_demos::Controls m_held;
	btVector3 m_driver{0, 0, 0};
	static const int kProfileSteps = 60;
	double m_frameMs = 0;
	std::string m_profile;
	bool m_showText = true;
	std::vector<caliber::demo::TextCell> m_textCells;
};

Browser* browserOf(GLFWwindow* window) { return static_cast<Browser*>(glfwGetWindowUserPointer(window)); }

bool writeScreenshot(GLFWwindow* window, const std::string& path)
{
	int width = 0, height = 0;
	glfwGetFramebufferSize(window, &width, &height);
	caliber::demo::Image image;
	image.width = width;
	image.height = height;
	std::vector<std::uint8_t> rows(std::size_t(width) * std::size_t(height) * 3);
	glPixelStorei(GL_PACK_ALIGNMENT, 1);
	glReadBuffer(GL_BACK);
	glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
	// OpenGL's rows run bottom to top, a PNG's top to bottom.
	image.rgb.resize(rows.size());
	const std::size_t stride = std::size_t(width) * 3;
	for (int y = 0; y < height; ++y)
		std::memcpy(&image.rgb[std::size_t(y) * stride], &rows[std::size_t(height - 1 - y) * stride], stride);
	std::string error;
	if (!caliber::demo::writePng(path, image, error))
	{
		std::fprintf(stderr, "AllBulletDemos: %s\n", error.c_str());
		return false;
	}
	std::printf("screenshot: %s (%d x %d)\n", path.c_str(), width, height);
	return true;
}
}  // namespace

int main(int argc, char** argv)
{
	Options options;
	const int parsed = parse(argc, argv, options);
	if (parsed >= 0) return parsed;
	const std::vector<std::string> names = all_bullet_demos::demoNames();
	int index = -1;
	for (size_t i = 0; i < names.size(); ++i)
		if (names[i] == options.demo) index = int(i);
	if (index < 0)
	{
		std::fprintf(stderr, "AllBulletDemos: no demo '%s'; --list shows them\n", options.demo.c_str());
		return 2;
	}

	// --hold drives a demo: refuse one without driving keys before opening a window.
	if (options.hold && !all_bullet_demos::makeDemo(options.demo)->driven())
	{
		std::fprintf(stderr,
		             "AllBulletDemos: --hold: %s is not driven by keys (VehicleDemo, CharacterDemo and "
		             "ForkLiftDemo are)\n",
		             options.demo.c_str());
		return 2;
	}
	glfwSetErrorCallback(onGlfwError);
	if (!glfwInit())
	{
		std::fprintf(stderr, "AllBulletDemos: cannot start GLFW (no display?): %s\n", gGlfwError.c_str());
		return 1;
	}
	glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
	glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
	glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
	glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
	glfwWindowHint(GLFW_SAMPLES, 4);
	GLFWwindow* window = glfwCreateWindow(options.width, options.height, "AllBulletDemos", nullptr, nullptr);
	if (!window)
	{
		std::fprintf(stderr, "AllBulletDemos: cannot open an OpenGL 3.3 window: %s\n", gGlfwError.c_str());
		glfwTerminate();
		return 1;
	}
	glfwMakeContextCurrent(window);
	glfwSwapInterval(options.frames > 0 ? 0 : 1);
	all_bullet_demos::GlRenderer gl;
	std::string error;
	int exitCode = 0;
	if (!gl.init(error))
	{
		std::fprintf(stderr, "AllBulletDemos: %s\n", error.c_str());
		glfwDestroyWindow(window);
		glfwTerminate();
		return 1;
	}
	glEnable(GL_MULTISAMPLE);
	{
		Browser browser(window, names);
		browser.load(index);
		glfwSetWindowUserPointer(window, &browser);
		if (options.frames > 0)
		{
			// Automation: scripted input (camera moves, a drag, held keys, key presses), N steps, one drawn frame.
			if (options.orbit[0] != 0 || options.orbit[1] != 0) browser.orbit(options.orbit[0], options.orbit[1]);
			if (options.pan[0] != 0 || options.pan[1] != 0) browser.pan(options.pan[0], options.pan[1]);
			if (options.wheel != 0) browser.zoom(options.wheel);
			std::printf("start: %s\n", browser.stateText().c_str());
			btRigidBody* dragged = nullptr;
			btSoftBody* draggedSoft = nullptr;
			int draggedNode = -1;
			btVector3 dragStart(0, 0, 0), softTargetStart(0, 0, 0);
			int pickedAt = 0;
			if (options.drag)
			{
				browser.setCursor(options.dragFrom[0], options.dragFrom[1]);
				browser.pressLeft();
				pickedAt = browser.loads();
				dragged = browser.picked();
				if (dragged) dragStart = dragged->getCenterOfMassPosition();
				draggedSoft = browser.pickedSoft();
				draggedNode = browser.pickedNode();
				if (draggedSoft) dragStart = draggedSoft->m_nodes[draggedNode].m_x;
			}
			if (options.hold) browser.holdKeys(options.held);
			const btVector3 driverStart = browser.demo().driverPosition();
			auto pressKeys = [&](int frame)
			{
				for (const Options::KeyPress& press : options.keys)
					if (press.frame == frame) browser.key(press.key);
			};
			for (int frame = 0; frame < options.frames; ++frame)
			{
				pressKeys(frame);
				if (options.drag)
				{
					const double t = double(frame + 1) / options.frames;
					browser.setCursor(options.dragFrom[0] + (options.dragTo[0] - options.dragFrom[0]) * t,
					                  options.dragFrom[1] + (options.dragTo[1] - options.dragFrom[1]) * t);
					browser.drag(0, 0, false);
					if (frame == 0) softTargetStart = browser.softTarget();
				}
				browser.advance();
			}
			pressKeys(options.frames);
			if (options.drag)
			{
				if (browser.loads() != pickedAt && (dragged || draggedSoft))
				{
					// R or N during the drag: the picked body went with the demo it was in.
					std::printf("drag: the demo was loaded again during the drag; the picked body is gone\n");
					exitCode = 1;
				}
				else if (draggedSoft)
				{
					// The node the cursor holds, against where the cursor's point went.
					const btVector3 end = draggedSoft->m_nodes[draggedNode].m_x, target = browser.softTarget();
					std::printf(
					    "drag: picked node %d of a soft body at (%.2f, %.2f, %.2f), dragged to (%.2f, %.2f, "
					    "%.2f), %.2f m; the cursor's point moved %.2f m and is %.2f m from the node\n",
					    draggedNode, double(dragStart.x()), double(dragStart.y()), double(dragStart.z()),
					    double(end.x()), double(end.y()), double(end.z()), double((end - dragStart).length()),
					    double((target - softTargetStart).length()), double((target - end).length()));
				}
				else if (!dragged)
				{
					std::printf("drag: nothing to pick at (%.0f, %.0f)\n", options.dragFrom[0], options.dragFrom[1]);
					exitCode = 1;
				}
				else
				{
					const btVector3 end = dragged->getCenterOfMassPosition();
					std::printf("drag: picked a body at (%.2f, %.2f, %.2f), dragged to (%.2f, %.2f, %.2f), %.2f m\n",
					            double(dragStart.x()), double(dragStart.y()), double(dragStart.z()), double(end.x()),
					            double(end.y()), double(end.z()), double((end - dragStart).length()));
				}
				browser.releaseLeft();
			}
			if (options.hold)
			{
				const btVector3 end = browser.demo().driverPosition();
				std::printf("hold: the driver moved from (%.2f, %.2f, %.2f) to (%.2f, %.2f, %.2f), %.2f m\n",
				            double(driverStart.x()), double(driverStart.y()), double(driverStart.z()), double(end.x()),
				            double(end.y()), double(end.z()), double((end - driverStart).length()));
			}
			std::printf("end: %s\n", browser.stateText().c_str());
			std::printf("camera: %s\n", browser.cameraText().c_str());
			browser.draw(gl);
			glFinish();
			if (!options.screenshot.empty() && !writeScreenshot(window, options.screenshot)) exitCode = 1;
			std::printf("AllBulletDemos: %s, %d frames\n", browser.name().c_str(), options.frames);
		}
		else
		{
			glfwSetKeyCallback(window,
			                   [](GLFWwindow* w, int key, int, int action, int)
			                   {
				                   if (action == GLFW_PRESS || action == GLFW_REPEAT) browserOf(w)->key(key);
			                   });
			glfwSetMouseButtonCallback(window,
			                           [](GLFWwindow* w, int button, int action, int)
			                           {
				                           if (button == GLFW_MOUSE_BUTTON_LEFT && action == GLFW_PRESS)
					                           browserOf(w)->pressLeft();
				                           if (button == GLFW_MOUSE_BUTTON_LEFT && action == GLFW_RELEASE)
					                           browserOf(w)->releaseLeft();
			                           });
			glfwSetScrollCallback(window, [](GLFWwindow* w, double, double y) { browserOf(w)->zoom(y); });
			double lastX = 0, lastY = 0;
			glfwGetCursorPos(window, &lastX, &lastY);
			int frameCount = 0;
			auto last = std::chrono::steady_clock::now();
			while (!glfwWindowShouldClose(window))
			{
				glfwPollEvents();
				double x = 0, y = 0;
				glfwGetCursorPos(window, &x, &y);
				const bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
				const bool right = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
				if (left || right) browser.drag(x - lastX, y - lastY, right);
				lastX = x;
				lastY = y;
				browser.advance();
				browser.draw(gl);
				glfwSwapBuffers(window);
				const auto now = std::chrono::steady_clock::now();
				const double frameMs = std::chrono::duration<double, std::milli>(now - last).count();
				browser.setFrameTime(frameMs);
				if (++frameCount % 15 == 0) browser.updateTitle(frameMs);
				last = now;
			}
		}
		glfwSetWindowUserPointer(window, nullptr);
	}
	gl.shutdown();
	glfwDestroyWindow(window);
	glfwTerminate();
	return exitCode;
}
