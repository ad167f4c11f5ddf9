// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Raytracer: the program is Raytracer.cpp, shared with the demo browser (DemoPrograms.h).
#include "DemoPrograms.h"

int main(int argc, char** argv) { return caliber::demo::raytracerDemo(argc, argv); }
