// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// LinearMathBench: Google Benchmark over the LinearMath functions that have an SSE path. The same
// source builds LinearMathBench (this build's path) and LinearMathBenchScalar (CALIBER_NO_SIMD,
// linked against a scalar LinearMath); compare the two to see what the SIMD path buys.
// Each benchmark walks arrays of kBatch inputs (16 KiB per array: they stay in L1) so that the
// compiler cannot fold the work away, and reports items (operations) per second.

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btMatrix3x3.h"
#include "LinearMath/btQuaternion.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

#include <benchmark/benchmark.h>

#include <stdint.h>

namespace
{
constexpr int kBatch = 1024;

/// Deterministic inputs, the same in both binaries.
class BenchRandom
{
public:
	explicit BenchRandom(uint32_t seed) : m_state(seed) {}
	btScalar uniform(btScalar lo, btScalar hi)
	{
		m_state = m_state * 1664525u + 1013904223u;
		return lo + btScalar(double(m_state >> 8) / double(1u << 24)) * (hi - lo);
	}
	btVector3 vector() { return btVector3(uniform(-10, 10), uniform(-10, 10), uniform(-10, 10)); }
	btQuaternion rotation()
	{
		btVector3 axis = vector();
		if (axis.length2() < btScalar(1e-4)) axis.setValue(1, 0, 0);
		return btQuaternion(axis.normalized(), uniform(-SIMD_PI, SIMD_PI));
	}

private:
	uint32_t m_state;
};

/// Input arrays shared by all benchmarks.
struct Inputs
{
	btAlignedObjectArray<btVector3> a;
	btAlignedObjectArray<btVector3> b;
	btAlignedObjectArray<btQuaternion> qa;
	btAlignedObjectArray<btQuaternion> qb;
	btMatrix3x3 matrix;
	btTransform transform;

	Inputs()
	{
		BenchRandom random(89);
		for (int i = 0; i < kBatch; ++i)
		{
			a.push_back(random.vector());
			b.push_back(random.vector());
			qa.push_back(random.rotation());
			qb.push_back(random.rotation());
		}
		matrix.setRotation(random.rotation());
		matrix = matrix.scaled(btVector3(btScalar(1.5), btScalar(0.5), btScalar(2)));
		transform.setRotation(random.rotation());
		transform.setOrigin(random.vector());
	}
};

const Inputs& inputs()
{
	static const Inputs shared;
	return shared;
}

void finish(benchmark::State& state, int itemsPerIteration)
{
	state.SetItemsProcessed(int64_t(state.iterations()) * itemsPerIteration);
}

void BM_Vector3Dot(benchmark::State& state)
{
	const Inputs& in = inputs();
	for (auto _ : state)
	{
		btScalar sum = 0;
		for (int i = 0; i < kBatch; ++i) sum += in.a[i].dot(in.b[i]);
		benchmark::DoNotOptimize(sum);
	}
	finish(state, kBatch);
}

void BM_Vector3Cross(benchmark::State& state)
{
	const Inputs& in = inputs();
	btAlignedObjectArray<btVector3> out;
	out.resize(kBatch, btVector3(0, 0, 0));
	for (auto _ : state)
	{
		for (int i = 0; i < kBatch; ++i) out[i] = in.a[i].cross(in.b[i]);
		benchmark::DoNotOptimize(&out[0]);
		benchmark::ClobberMemory();
	}
	finish(state, kBatch);
}

void BM_Vector3Normalize(benchmark::State& state)
{
	const Inputs& in = inputs();
	btAlignedObjectArray<btVector3> out;
	out.resize(kBatch, btVector3(0, 0, 0));
	for (auto _ : state)
	{
		for (int i = 0; i < kBatch; ++i)
		{
			out[i] = in.a[i];
			out[i].normalize();
		}
		benchmark::DoNotOptimize(&out[0]);
		benchmark::ClobberMemory();
	}
	finish(state, kBatch);
}

void BM_Vector3SetMinMax(benchmark::State& state)
{
	const Inputs& in = inputs();
	for (auto _ : state)
	{
		btVector3 lo(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
		btVector3 hi(-BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT);
		for (int i = 0; i < kBatch; ++i)
		{
			lo.setMin(in.a[i]);
			hi.setMax(in.a[i]);
		}
		benchmark::DoNotOptimize(lo);
		benchmark::DoNotOptimize(hi);
	}
	finish(state, kBatch);
}

void BM_Matrix3x3TimesVector3(benchmark::State& state)
{
	const Inputs& in = inputs();
	btAlignedObjectArray<btVector3> out;
	out.resize(kBatch, btVector3(0, 0, 0));
	for (auto _ : state)
	{
		for (int i = 0; i < kBatch; ++i) out[i] = in.matrix * in.a[i];
		benchmark::DoNotOptimize(&out[0]);
		benchmark::ClobberMemory();
	}
	finish(state, kBatch);
}

void BM_TransformTimesVector3(benchmark::State& state)
{
	const Inputs& in = inputs();
	btAlignedObjectArray<btVector3> out;
	out.resize(kBatch, btVector3(0, 0, 0));
	for (auto _ : state)
	{
		for (int i = 0; i < kBatch; ++i) out[i] = in.transform * in.a[i];
		benchmark::DoNotOptimize(&out[0]);
		benchmark::ClobberMemory();
	}
	finish(state, kBatch);
}

void BM_QuaternionProduct(benchmark::State& state)
{
	const Inputs& in = inputs();
	btAlignedObjectArray<btQuaternion> out;
	out.resize(kBatch, btQuaternion(0, 0, 0, 1));
	for (auto _ : state)
	{
		for (int i = 0; i < kBatch; ++i) out[i] = in.qa[i] * in.qb[i];
		benchmark::DoNotOptimize(&out[0]);
		benchmark::ClobberMemory();
	}
	finish(state, kBatch);
}

/// The support-point search of convex shapes: the array vertex furthest along a direction.
void BM_Vector3MaxDot(benchmark::State& state)
{
	const Inputs& in = inputs();
	const long count = long(state.range(0));
	int direction = 0;
	for (auto _ : state)
	{
		btScalar bestDot = 0;
		const long best = in.b[direction].maxDot(&in.a[0], count, bestDot);
		benchmark::DoNotOptimize(best);
		benchmark::DoNotOptimize(bestDot);
		direction = (direction + 1) & (kBatch - 1);
	}
	finish(state, int(count));
}
}  // namespace

BENCHMARK(BM_Vector3Dot);
BENCHMARK(BM_Vector3Cross);
BENCHMARK(BM_Vector3Normalize);
BENCHMARK(BM_Vector3SetMinMax);
BENCHMARK(BM_Matrix3x3TimesVector3);
BENCHMARK(BM_TransformTimesVector3);
BENCHMARK(BM_QuaternionProduct);
BENCHMARK(BM_Vector3MaxDot)->Arg(8)->Arg(64)->Arg(kBatch);

int main(int argc, char** argv)
{
#ifdef BT_USE_SSE
	benchmark::AddCustomContext("caliber_math_path", "SSE");
#else
	benchmark::AddCustomContext("caliber_math_path", "scalar");
#endif
	benchmark::AddCustomContext("caliber_btScalar", btIsDoublePrecision() ? "double" : "float");
	benchmark::Initialize(&argc, argv);
	if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
	benchmark::RunSpecifiedBenchmarks();
	benchmark::Shutdown();
	return 0;
}
