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
//   BenchmarkDemo all 120 1000         then, per scene, the rollback check: save the world
//                                      (caliber::saveWorldState), step 1000 frames, restore, step them
//                                      again, and restore into a second copy of the scene and step them
//                                      there: every frame's hash must agree (docs/serialization.md)
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
#include "Caliber/WorldSnapshot.h"
#include "LinearMath/btQuickprof.h"
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

// Steps frames frames, keeping each frame's hash.
std::vector<uint64_t> hashedRun(benchmark_demo::Scene& scene, int frames)
{
	std::vector<uint64_t> hashes;
	for (int frame = 0; frame < frames; ++frame)
	{
		scene.world().stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.));
		scene.afterStep();
		hashes.push_back(stateHash(scene.dynamicBodies()));
	}
	return hashes;
}

// The first frame (1-based) whose hash differs, 0 when all agree.
int firstMismatch(const std::vector<uint64_t>& a, const std::vector<uint64_t>& b)
{
	for (size_t i = 0; i < a.size(); ++i)
		if (i >= b.size() || a[i] != b[i]) return int(i) + 1;
	return 0;
}

// The rollback check: save, step, restore, step again (same world), restore into a second copy of the
// scene and step there; each replay must repeat every frame's hash.
bool rollbackCheck(benchmark_demo::Scene& scene, const std::string& name, int frames)
{
	btAlignedObjectArray<unsigned char> snapshot;
	caliber::SnapshotError error;
	auto start = std::chrono::steady_clock::now();
	if (!caliber::saveWorldState(scene.world(), snapshot, &error))
	{
		printf("  rollback: cannot save: %s  <-- FAILED\n", error.message);
		return false;
	}
	const double saveMs = millisecondsSince(start);
	const std::vector<uint64_t> original = hashedRun(scene, frames);
	start = std::chrono::steady_clock::now();
	if (!caliber::restoreWorldState(scene.world(), &snapshot[0], size_t(snapshot.size()), &error))
	{
		printf("  rollback: cannot restore: %s  <-- FAILED\n", error.message);
		return false;
	}
	const double restoreMs = millisecondsSince(start);
	const int sameWorld = firstMismatch(original, hashedRun(scene, frames));
	std::unique_ptr<benchmark_demo::Scene> copy = benchmark_demo::makeScene(name);
	int otherWorld = -1;
	if (caliber::restoreWorldState(copy->world(), &snapshot[0], size_t(snapshot.size()), &error))
		otherWorld = firstMismatch(original, hashedRun(*copy, frames));
	const bool exact = sameWorld == 0 && otherWorld == 0;
	printf(
	    "  rollback: snapshot %.1f kB, save %.2f ms, restore %.2f ms; %d frames replayed: same world %s, second world "
	    "%s%s\n",
	    snapshot.size() / 1024.0, saveMs, restoreMs, frames,
	    sameWorld ? ("differs at frame " + std::to_string(sameWorld)).c_str() : "bit-identical",
	    otherWorld < 0 ? error.message
	                   : (otherWorld ? ("differs at frame " + std::to_string(otherWorld)).c_str() : "bit-identical"),
	    exact ? "" : "  <-- FAILED");
	return exact;
}
}  // namespace

int main(int argc, char** argv)
{
	// --threads N (N >= 1): the scenes in Bullet 2.89's multithreaded world with the thread pool set to
	// N threads (docs/threading.md); its state hashes are the same at every N. Taken out before the
	// picture options are read.
	int threads = 0;
	bool profile = false;
	std::vector<char*> arguments;
	for (int i = 0; i < argc; ++i)
	{
		// --profile: after each scene, the time the calling thread spent in each stage of the step
		// (btQuickprof's tree, as Bullet's demos print it); stages run on other threads show as the
		// time the caller waited for them.
		if (std::string(argv[i]) == "--profile")
		{
			profile = true;
			continue;
		}
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
	commandLine.maxPositional = 3;
	commandLine.positionalUsage = "[scene[,scene...]|all] [frames > 0] [rollback frames] [--threads N] [--profile]";
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();
	const std::vector<std::string>& positional = pictures.positional();
	const std::string filter = positional.size() > 0 ? positional[0] : "all";
	const int frames =
	    pictures.framesGiven() ? pictures.frames() : (positional.size() > 1 ? atoi(positional[1].c_str()) : 30);
	const int rollbackFrames = positional.size() > 2 ? atoi(positional[2].c_str()) : 0;
	if (frames <= 0 || rollbackFrames < 0)
	{
		fprintf(stderr, "usage: %s [scene[,scene...]|all] [frames > 0] [rollback frames]\n", argv[0]);
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
		if (profile) CProfileManager::Reset();
		for (int frame = 0; frame < frames; ++frame)
		{
			const auto start = std::chrono::steady_clock::now();
			scene->world().stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.));
			scene->afterStep();
			stepMs.push_back(millisecondsSince(start));
			if (profile) CProfileManager::Increment_Frame_Counter();
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
		if (profile) CProfileManager::dumpAll();
		if (rollbackFrames > 0) allSane = rollbackCheck(*scene, name, rollbackFrames) && allSane;
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
