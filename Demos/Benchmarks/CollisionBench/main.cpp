// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// CollisionBench: one Google Benchmark program for the collision layer. Each *Bench.cpp file in this
// folder registers the benchmarks of one area (GJK/EPA, box-box, clipping, BVH queries, ...).
#include <benchmark/benchmark.h>

#include "LinearMath/btScalar.h"

int main(int argc, char** argv)
{
	benchmark::Initialize(&argc, argv);
	if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
	benchmark::AddCustomContext("caliber_btScalar", btIsDoublePrecision() ? "double" : "float");
	benchmark::RunSpecifiedBenchmarks();
	benchmark::Shutdown();
	return 0;
}
