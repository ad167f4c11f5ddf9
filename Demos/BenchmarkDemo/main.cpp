// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// BenchmarkDemo: the benchmark scenes of docs/rigid-body-dynamics.md (Bullet's benchmark scenes and
// Jolt's pyramid), headless, body for body as the reference program that measured Bullet builds them.
// For each scene it prints the bodies, the build time, the step time in ms (mean, median, max), the
// scene's sanity figures (boxes displaced from rest, bodies tunnelled through the terrain, rays that
// hit, ...) and a hash of the final state, so that speed is never read without the physics it bought.
// Exit 1 when a sanity check fails (a NaN, a body through the ground or the terrain, a ray that
// missed, a settled stack that moved).
//
//   BenchmarkDemo                      every scene, 30 steps each (a quick run, as in CI)
//   BenchmarkDemo all 600              every scene, 600 steps each (the reference length)
//   BenchmarkDemo stack1000,boxes3000 600   the named scenes (substrings of the names)
//
// As in the reference runs, deactivation is off (gDisableDeactivation), steps are 1/60 s with one
// substep, the solver runs 5 iterations (10 for pyramid_jolt) in single-threaded mode.

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "BenchmarkScenes.h"
#include "DemoPictures.h"
#include "LinearMath/btThreads.h"

namespace
{
double millisecondsSince(std::chrono::steady_clock::time_point start)
{
	return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

bool selected(const std::string& filter, const std::string& name)
{
	if (filter.empty() || filter == "all") return true;
	size_t begin = 0;
	while (begin <= filter.size())
	{
		const size_t end = std::min(filter.find(',', begin), filter.size());
		const std::string part = filter.substr(begin, end - begin);
		if (!part.empty() && name.find(part) != std::string::npos) return true;
		begin = end + 1;
	}
	return false;
}

// FNV-1a over the bits of every dynamic body's final position and orientation (7 btScalars each), as
// the reference program prints it: equal hashes mean the same simulation, bit for bit.
uint64_t stateHash(const std::vector<btRigidBody*>& bodies)
{
	uint64_t hash = 1469598103934665603ull;
	for (const btRigidBody* body : bodies)
	{
		const btTransform& pose = body->getCenterOfMassTransform();
		const btQuaternion rotation = pose.getRotation();
		const btScalar state[7] = {pose.getOrigin().x(), pose.getOrigin().y(), pose.getOrigin().z(), rotation.x(),
		                           rotation.y(),         rotation.z(),         rotation.w()};
		const unsigned char* bytes = reinterpret_cast<const unsigned char*>(state);
		for (size_t i = 0; i < sizeof(state); ++i)
		{
			hash ^= bytes[i];
			hash *= 1099511628211ull;
		}
	}
	return hash;
}
}  // namespace

int main(int argc, char** argv)
{
	// --threads N (N >= 1): the scenes in Bullet 2.89's multithreaded world with the thread pool set to
	// N threads (docs/threading.md); its state hashes are the same at every N. Taken out before the
	// picture options are read.
	int threads = 0;
	std::vector<char*> arguments;
	for (int i = 0; i < argc; ++i)
	{
		if (std::string(argv[i]) == "--threads")
		{
			threads = i + 1 < argc ? atoi(argv[i + 1]) : 0;
			if (threads < 1)
			{
				fprintf(stderr, "%s: --threads needs a count of at least 1\n", argv[0]);
				return 2;
			}
			++i;
			continue;
		}
		arguments.push_back(argv[i]);
	}
	argc = int(arguments.size());
	argv = arguments.data();
	std::unique_ptr<btITaskScheduler> scheduler;
	if (threads > 0)
	{
		scheduler.reset(btCreateDefaultTaskScheduler());
		btITaskScheduler* used = scheduler ? scheduler.get() : btGetSequentialTaskScheduler();
		btSetTaskScheduler(used);
		used->setNumThreads(threads);
		benchmark_demo::setMultithreadedWorld(true);
	}

	// Positional arguments as before: the scenes, then the frames (which --frames replaces). --png
	// pictures the last frame of the last scene run (docs/demos.md); it is drawn after the timing.
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "BenchmarkDemo";
	commandLine.defaultFrames = 30;
	commandLine.maxPositional = 2;
	commandLine.positionalUsage = "[scene[,scene...]|all] [frames > 0] [--threads N]";
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();
	const std::vector<std::string>& positional = pictures.positional();
	const std::string filter = positional.size() > 0 ? positional[0] : "all";
	const int frames =
	    pictures.framesGiven() ? pictures.frames() : (positional.size() > 1 ? atoi(positional[1].c_str()) : 30);
	if (frames <= 0)
	{
		fprintf(stderr, "usage: %s [scene[,scene...]|all] [frames > 0]\n", argv[0]);
		return 2;
	}
	gDisableDeactivation = true;
	printf(
	    "# Caliber %d.%d.%d (Bullet API %d.%02d), btScalar=%s, dt=1/60, 1 substep/frame, deactivation off, %d "
	    "frames per scene\n",
	    CALIBER_VERSION_MAJOR, CALIBER_VERSION_MINOR, CALIBER_VERSION_PATCH, btGetVersion() / 100, btGetVersion() % 100,
	    sizeof(btScalar) == 8 ? "double" : "float", frames);
	if (threads > 0)
		printf("# Bullet 2.89's multithreaded world, task scheduler %s with %d threads\n", btGetTaskScheduler()->getName(),
		       btGetTaskScheduler()->getNumThreads());
	bool allSane = true;
	int ran = 0;
	// The picture is of the last scene run; only that one is drawn (drawing 3000 boxes is not free).
	std::string lastSelected;
	for (const std::string& name : benchmark_demo::sceneNames())
		if (selected(filter, name)) lastSelected = name;
	for (const std::string& name : benchmark_demo::sceneNames())
	{
		if (!selected(filter, name)) continue;
		++ran;
		const auto buildStart = std::chrono::steady_clock::now();
		std::unique_ptr<benchmark_demo::Scene> scene = benchmark_demo::makeScene(name);
		const double buildMs = millisecondsSince(buildStart);
		std::vector<double> stepMs;
		stepMs.reserve(size_t(frames));
		for (int frame = 0; frame < frames; ++frame)
		{
			const auto start = std::chrono::steady_clock::now();
			scene->world().stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.));
			scene->afterStep();
			stepMs.push_back(millisecondsSince(start));
		}
		double total = 0;
		for (double ms : stepMs) total += ms;
		std::vector<double> sorted = stepMs;
		std::sort(sorted.begin(), sorted.end());
		if (name == lastSelected) pictures.capture(scene->world());
		std::string sanity;
		const bool sane = scene->report(sanity, frames);
		allSane = allSane && sane;
		printf(
		    "%-13s bodies %d (dynamic %d), iterations %d, frames %d, build %.1f ms, ms/step mean %.3f median %.3f max "
		    "%.3f\n",
		    name.c_str(), scene->world().getNumCollisionObjects(), int(scene->dynamicBodies().size()),
		    scene->world().getSolverInfo().m_numIterations, frames, buildMs, total / frames, sorted[sorted.size() / 2],
		    sorted.back());
		printf("  sanity: %s; hash %016llx%s\n", sanity.c_str(), (unsigned long long)stateHash(scene->dynamicBodies()),
		       sane ? "" : "  <-- FAILED");
	}
	if (ran == 0)
	{
		fprintf(stderr, "no scene matches '%s'\n", filter.c_str());
		return 2;
	}
	const int status = pictures.finish(allSane ? 0 : 1);
	btSetTaskScheduler(0);
	return status;
}
