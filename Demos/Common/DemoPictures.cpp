// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "DemoPictures.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "Png.h"
#include "WorldScene.h"
#include "btBulletCollisionCommon.h"

namespace caliber
{
namespace demo
{
namespace
{
// A whole number from lo to hi, the whole argument (no trailing text).
bool parseInt(const char* text, long lo, long hi, int& value)
{
	if (!text || !*text) return false;
	errno = 0;
	char* end = nullptr;
	const long parsed = std::strtol(text, &end, 10);
	if (errno != 0 || *end != '\0' || parsed < lo || parsed > hi) return false;
	value = int(parsed);
	return true;
}

bool parseSize(const char* text, int& width, int& height)
{
	const char* x = text ? std::strchr(text, 'x') : nullptr;
	if (!x) return false;
	const std::string w(text, std::size_t(x - text));
	return parseInt(w.c_str(), 1, kMaxImageSide, width) && parseInt(x + 1, 1, kMaxImageSide, height);
}

bool parseDraw(const std::string& list, int& mode)
{
	mode = 0;
	std::size_t start = 0;
	while (start <= list.size())
	{
		const std::size_t comma = list.find(',', start);
		const std::string item = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
		if (item == "joints")
			mode |= btIDebugDraw::DBG_DrawConstraints | btIDebugDraw::DBG_DrawConstraintLimits;
		else if (item == "contacts")
			mode |= btIDebugDraw::DBG_DrawContactPoints;
		else if (item == "aabbs")
			mode |= btIDebugDraw::DBG_DrawAabb;
		else if (item == "wireframe")
			mode |= btIDebugDraw::DBG_DrawWireframe;
		else if (item == "frames")
			mode |= btIDebugDraw::DBG_DrawFrames;
		else if (item != "none")
			return false;
		if (comma == std::string::npos) break;
		start = comma + 1;
	}
	return true;
}
SceneRecording* gRecording = nullptr;

DemoCommandLine namedCommandLine(const char* name)
{
	DemoCommandLine commandLine;
	commandLine.name = name;
	return commandLine;
}
}  // namespace

void setSceneRecording(SceneRecording* recording) { gRecording = recording; }

bool StepBudget::reached(const char* what) const
{
	if (!spent() || !m_shortened) return true;
	std::printf("  check: %s: not reached (--frames %d)\n", what, m_frames);
	return false;
}

DemoPictures::DemoPictures(int argc, char** argv, const char* name)
    : DemoPictures(argc, argv, namedCommandLine(name))
{
}

DemoPictures::DemoPictures(int argc, char** argv, const DemoCommandLine& commandLine)
    : m_commandLine(commandLine), m_frames(commandLine.defaultFrames), m_recording(gRecording)
{
	m_debugMode = commandLine.debugDrawMode;
	m_options.width = commandLine.defaultWidth;
	m_options.height = commandLine.defaultHeight;
	const std::string program = argc > 0 && argv && argv[0] ? argv[0] : commandLine.name;
	auto usage = [&](FILE* out)
	{
		std::fprintf(
		    out, "usage: %s%s%s [--png PATH]%s%s [--size WxH] [--draw joints,contacts,aabbs,wireframe,frames|none]\n",
		    program.c_str(), *commandLine.positionalUsage ? " " : "", commandLine.positionalUsage,
		    commandLine.defaultFrames > 0 ? " [--frames N]" : "",
		    commandLine.sequences ? " [--png-sequence DIR [--every K]]" : "");
	};
	bool everyGiven = false;
	for (int i = 1; i < argc && m_ok; ++i)
	{
		const std::string option = argv[i] ? argv[i] : "";
		const char* value = i + 1 < argc ? argv[i + 1] : nullptr;
		bool needsValue = true;
		bool valueOk = value != nullptr;
		if (option == "--help" || option == "-h")
		{
			usage(stdout);
			m_ok = false;
			m_exitCode = 0;
			return;
		}
		else if (option == "--png")
		{
			valueOk = valueOk && *value;
			if (valueOk) m_pngPath = value;
		}
		else if (option == "--frames" && commandLine.defaultFrames > 0)
		{
			const int limit = commandLine.maxFrames > 0 ? commandLine.maxFrames : 10000000;
			valueOk = valueOk && parseInt(value, 1, limit, m_frames);
			m_framesGiven = true;
		}
		else if (option == "--png-sequence" && commandLine.sequences)
		{
			valueOk = valueOk && *value;
			if (valueOk) m_sequenceDir = value;
		}
		else if (option == "--every" && commandLine.sequences)
		{
			valueOk = valueOk && parseInt(value, 1, 10000000, m_every);
			everyGiven = true;
		}
		else if (option == "--size")
		{
			valueOk = valueOk && parseSize(value, m_options.width, m_options.height);
			m_sizeGiven = true;
		}
		else if (option == "--draw")
			valueOk = valueOk && parseDraw(value, m_debugMode);
		else if (option.size() > 1 && option[0] == '-')
		{
			const bool known = option == "--frames" || option == "--png-sequence" || option == "--every";
			std::fprintf(stderr, "%s: %s\n", commandLine.name,
			             known ? ("option " + option + " is not available in this demo").c_str()
			                   : ("unknown option " + option).c_str());
			usage(stderr);
			m_ok = false;
			m_exitCode = 2;
			return;
		}
		else
		{
			needsValue = false;
			if (int(m_positional.size()) >= commandLine.maxPositional)
			{
				std::fprintf(stderr, "%s: unexpected argument '%s'\n", commandLine.name, option.c_str());
				usage(stderr);
				m_ok = false;
				m_exitCode = 2;
				return;
			}
			m_positional.push_back(option);
		}
		if (needsValue)
		{
			if (!valueOk)
			{
				const std::string limit = std::to_string(commandLine.maxFrames > 0 ? commandLine.maxFrames : 10000000);
				const std::string expected =
				    option == "--size" ? "WIDTHxHEIGHT, each side 1 to 8192"
				    : option == "--draw"
				        ? "a comma-separated list of joints, contacts, aabbs, wireframe, frames or none"
				    : option == "--frames" ? "a whole number from 1 to " + limit
				    : option == "--every"  ? "a whole number from 1 to 10000000"
				                           : "a path";
				std::fprintf(stderr, "%s: %s needs %s, got '%s'\n", commandLine.name, option.c_str(), expected.c_str(),
				             value ? value : "(nothing)");
				usage(stderr);
				m_ok = false;
				m_exitCode = 2;
				return;
			}
			++i;
		}
	}
	if (everyGiven && m_sequenceDir.empty())
	{
		std::fprintf(stderr, "%s: --every needs --png-sequence DIR\n", commandLine.name);
		m_ok = false;
		m_exitCode = 2;
		return;
	}
	if (m_recording && (!m_pngPath.empty() || !m_sequenceDir.empty()))
	{
		std::fprintf(stderr, "%s: pictures are not written while the browser records the scenes\n", commandLine.name);
		m_ok = false;
		m_exitCode = 2;
		return;
	}
	if (wanted() && !m_recording && !pngAvailable())
	{
		std::fprintf(stderr,
		             "%s: pictures are unavailable: this build has no libpng (install the Debian package libpng-dev "
		             "and reconfigure)\n",
		             commandLine.name);
		m_ok = false;
		m_exitCode = 2;
		return;
	}
	if (!m_sequenceDir.empty())
	{
		std::error_code error;
		std::filesystem::create_directories(m_sequenceDir, error);
		if (error)
		{
			std::fprintf(stderr, "%s: cannot create the folder '%s': %s\n", commandLine.name, m_sequenceDir.c_str(),
			             error.message().c_str());
			m_ok = false;
			m_exitCode = 2;
		}
	}
}

void DemoPictures::setFocus(const btVector3& aabbMin, const btVector3& aabbMax)
{
	m_focusMin = aabbMin;
	m_focusMax = aabbMax;
	m_hasFocus = true;
}

void DemoPictures::fail(const std::string& message)
{
	if (!m_failed) std::fprintf(stderr, "%s: %s\n", m_commandLine.name, message.c_str());
	m_failed = true;
}

void DemoPictures::focusOf(const Scene& scene, btVector3& focusMin, btVector3& focusMax) const
{
	// What to frame: the demo's own focus, else the scene's (what moves), else everything in it.
	focusMin = btVector3(-1, -1, -1);
	focusMax = btVector3(1, 1, 1);
	if (m_hasFocus)
	{
		focusMin = m_focusMin;
		focusMax = m_focusMax;
	}
	else if (scene.hasFocus())
	{
		focusMin = scene.focusMin();
		focusMax = scene.focusMax();
	}
	else
		scene.contentBounds(focusMin, focusMax);
}

void DemoPictures::record(const Scene& scene)
{
	m_recording->shots.emplace_back();
	SceneRecording::Shot& shot = m_recording->shots.back();
	shot.scene = scene;
	focusOf(scene, shot.focusMin, shot.focusMax);
	shot.viewDirection = m_viewDirection;
}

bool DemoPictures::renderScene(Scene& scene, Image& image, bool sequence)
{
	btVector3 focusMin, focusMax;
	focusOf(scene, focusMin, focusMax);
	if (sequence)
	{
		// A sequence keeps one camera that only widens, so that its pictures can be compared side by side.
		if (m_sequenceFramed)
		{
			focusMin.setMin(m_sequenceFocusMin);
			focusMax.setMax(m_sequenceFocusMax);
		}
		m_sequenceFocusMin = focusMin;
		m_sequenceFocusMax = focusMax;
		m_sequenceFramed = true;
	}
	Scene framing;
	framing.focusOn(focusMin, focusMax);
	const Camera camera = frameScene(framing, m_options, m_viewDirection);
	std::string error;
	if (!render(scene, camera, m_options, image, error))
	{
		fail(error);
		return false;
	}
	return true;
}

void DemoPictures::buildWorldScene(btCollisionWorld& world)
{
	m_scene.clear();
	WorldStyle style;
	style.debugMode = m_debugMode;
	addWorld(m_scene, world, style);
	if (m_decorator) m_decorator(m_scene);
}

void DemoPictures::frame(btCollisionWorld& world, int n)
{
	if (!wanted()) return;
	if (m_recording)
	{
		buildWorldScene(world);
		record(m_scene);
		return;
	}
	const bool sequence = !m_sequenceDir.empty() && n % m_every == 0;
	if (!sequence && (n != m_frames || m_pngPath.empty())) return;
	buildWorldScene(world);
	Image image;
	if (!renderScene(m_scene, image, sequence)) return;
	if (sequence)
	{
		char name[64];
		// Numbered in order, not by frame: a demo that runs several worlds restarts n for each.
		std::snprintf(name, sizeof(name), "%s-%04d.png", m_commandLine.name, m_sequenceWritten + 1);
		std::string error;
		if (writePng((std::filesystem::path(m_sequenceDir) / name).string(), image, error))
			++m_sequenceWritten;
		else
			fail(error);
	}
	if (n == m_frames)
	{
		m_last = std::move(image);
		m_captured = true;
	}
}

void DemoPictures::capture(btCollisionWorld& world)
{
	if (m_recording)
	{
		buildWorldScene(world);
		record(m_scene);
		return;
	}
	if (m_pngPath.empty()) return;
	buildWorldScene(world);
	m_captured = renderScene(m_scene, m_last, false);
}

void DemoPictures::capture(const Scene& scene)
{
	if (m_recording)
	{
		record(scene);
		return;
	}
	if (m_pngPath.empty()) return;
	m_scene = scene;
	m_captured = renderScene(m_scene, m_last, false);
}

void DemoPictures::capture(const Image& image)
{
	if (m_pngPath.empty()) return;
	m_last = image;
	m_captured = true;
}

int DemoPictures::finish(int exitCode)
{
	if (!m_pngPath.empty())
	{
		std::string error;
		if (!m_captured)
			fail("no picture was taken (the demo never reached its last frame)");
		else if (writePng(m_pngPath, m_last, error))
			std::printf("picture: %s (%d x %d)\n", m_pngPath.c_str(), m_last.width, m_last.height);
		else
			fail(error);
	}
	if (!m_sequenceDir.empty())
		std::printf("picture sequence: %d pictures in %s, every %d frames\n", m_sequenceWritten, m_sequenceDir.c_str(),
		            m_every);
	return m_failed && exitCode == 0 ? 1 : exitCode;
}
}  // namespace demo
}  // namespace caliber
