// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_ALL_BULLET_DEMOS_BROWSER_SCENES_H
#define CALIBER_ALL_BULLET_DEMOS_BROWSER_SCENES_H
// The demos AllBulletDemos lists: each builds a world (a benchmark_demo::Scene, which owns everything
// in it) that the browser steps, draws and lets the user poke.

#include <memory>
#include <string>
#include <vector>

#include "BenchmarkScenes.h"

namespace all_bullet_demos
{
/// The names of the browser's demos, in the order of its list.
std::vector<std::string> demoNames();
/// Builds the named demo's world (null for an unknown name).
std::unique_ptr<benchmark_demo::Scene> makeDemo(const std::string& name);
}  // namespace all_bullet_demos

#endif
