// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// LinearMathDemo: the program is LinearMathDemo.cpp, shared with the demo browser (DemoPrograms.h).
#include "DemoPrograms.h"

int main(int argc, char** argv) { return caliber::demo::linearMathDemo(argc, argv); }
