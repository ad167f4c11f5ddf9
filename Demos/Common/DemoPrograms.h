// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_COMMON_DEMO_PROGRAMS_H
#define CALIBER_DEMOS_COMMON_DEMO_PROGRAMS_H
// The demos without a world to step, as functions: each headless program's main() calls its own, and
// the demo browser runs them with a SceneRecording set (DemoPictures.h) to show what they computed.
// Each takes the program's command line and returns its exit code; what it prints is its report.
// Defined in Demos/<Name>/<Name>.cpp.

namespace caliber
{
namespace demo
{
int linearMathDemo(int argc, char** argv);
int simplexDemo(int argc, char** argv);
int gjkConvexCastDemo(int argc, char** argv);
int collisionInterfaceDemo(int argc, char** argv);
int raytracerDemo(int argc, char** argv);
int userCollisionAlgorithmDemo(int argc, char** argv);
}  // namespace demo
}  // namespace caliber

#endif
