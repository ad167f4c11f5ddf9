// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Convex cast micro-benchmarks: btSubsimplexConvexCast, btGjkConvexCast and btContinuousConvexCollision
// (translation only, and with a quarter turn of A) on sphere-sphere, box-box and hull-hull pairs. Each
// benchmark cycles through 256 casts drawn once, outside the timed loop, from a fixed seed: A starts 2
// to 4 bounding radii from B and moves past B's centre (aimed within half a bounding radius of it), so
// most casts hit. The counters "hitRate" and "meanFraction" are sanity figures: they must not change
// with speed work.

#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <vector>

#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/NarrowPhaseCollision/btContinuousConvexCollision.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkConvexCast.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h"
#include "BulletCollision/NarrowPhaseCollision/btSubSimplexConvexCast.h"
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"
#include "LinearMath/btQuaternion.h"
#include "LinearMath/btTransform.h"

namespace
{
const int kCastCount = 256;  // a power of two: the index wraps with a mask

/// Which shapes a benchmark pairs.
enum class PairKind
{
	SphereSphere,
	BoxBox,
	HullHull
};

/// Which cast runs.
enum class CastKind
{
	Subsimplex,
	Gjk,
	Continuous,
	ContinuousRotating
};

/// Two shapes and kCastCount motions, all built before timing.
struct CastSet
{
	std::unique_ptr<btConvexShape> a, b;
	std::vector<btTransform> fromA, toA, poseB;
};

/// A hull of 32 points on an ellipsoid of semi-axes (0.6, 0.45, 0.35), from a fixed seed.
btConvexShape* makeHull(std::mt19937& rng)
{
	std::uniform_real_distribution<float> unit(-1.f, 1.f);
	btConvexHullShape* hull = new btConvexHullShape();
	for (int i = 0; i < 32;)
	{
		const btVector3 p(btScalar(unit(rng)), btScalar(unit(rng)), btScalar(unit(rng)));
		const btScalar l2 = p.length2();
		if (l2 < btScalar(0.05) || l2 > 1) continue;
		const btVector3 q = p / btSqrt(l2);
		hull->addPoint(btVector3(q.x() * btScalar(0.6), q.y() * btScalar(0.45), q.z() * btScalar(0.35)), false);
		++i;
	}
	hull->recalcLocalAabb();
	return hull;
}

btConvexShape* makeShape(PairKind kind, std::mt19937& rng)
{
	switch (kind)
	{
		case PairKind::SphereSphere:
			return new btSphereShape(btScalar(0.5));
		case PairKind::BoxBox:
			return new btBoxShape(btVector3(btScalar(0.6), btScalar(0.45), btScalar(0.35)));
		default:
			return makeHull(rng);
	}
}

btVector3 randomUnit(std::mt19937& rng)
{
	std::uniform_real_distribution<float> unit(-1.f, 1.f);
	for (;;)
	{
		const btVector3 v(btScalar(unit(rng)), btScalar(unit(rng)), btScalar(unit(rng)));
		const btScalar l2 = v.length2();
		if (l2 > btScalar(0.01) && l2 <= 1) return v / btSqrt(l2);
	}
}

const CastSet& castSet(PairKind kind, bool rotating)
{
	static CastSet sets[3][2];
	CastSet& set = sets[int(kind)][rotating ? 1 : 0];
	if (set.a) return set;
	std::mt19937 rng(4242u + unsigned(kind));
	std::uniform_real_distribution<float> unit(0.f, 1.f), angle(-3.14159f, 3.14159f);
	set.a.reset(makeShape(kind, rng));
	set.b.reset(makeShape(kind, rng));
	const btScalar radius = btScalar(0.75);  // bounding radius of each shape, margin included
	for (int i = 0; i < kCastCount; ++i)
	{
		const btQuaternion rotA(randomUnit(rng), btScalar(angle(rng)));
		const btQuaternion rotB(randomUnit(rng), btScalar(angle(rng)));
		const btVector3 start = randomUnit(rng) * (radius * btScalar(2 + 2 * unit(rng)));
		const btVector3 aim = randomUnit(rng) * (btScalar(0.5) * radius * btScalar(unit(rng)));
		const btVector3 end = start + (aim - start) * btScalar(2);
		set.fromA.push_back(btTransform(rotA, start));
		const btQuaternion turn =
		    rotating ? btQuaternion(randomUnit(rng), btScalar(SIMD_HALF_PI)) : btQuaternion::getIdentity();
		set.toA.push_back(btTransform(turn * rotA, end));
		set.poseB.push_back(btTransform(rotB, btVector3(0, 0, 0)));
	}
	return set;
}

void runCasts(benchmark::State& state, PairKind pair, CastKind cast)
{
	const CastSet& set = castSet(pair, cast == CastKind::ContinuousRotating);
	btVoronoiSimplexSolver simplex;
	btGjkEpaPenetrationDepthSolver epa;
	btSubsimplexConvexCast subsimplex(set.a.get(), set.b.get(), &simplex);
	btGjkConvexCast gjk(set.a.get(), set.b.get(), &simplex);
	btContinuousConvexCollision continuous(set.a.get(), set.b.get(), &simplex, &epa);
	btConvexCast* caster = cast == CastKind::Subsimplex ? static_cast<btConvexCast*>(&subsimplex)
	                       : cast == CastKind::Gjk      ? static_cast<btConvexCast*>(&gjk)
	                                                    : static_cast<btConvexCast*>(&continuous);
	int index = 0;
	double hits = 0, fractionSum = 0, casts = 0;
	for (auto _ : state)
	{
		btConvexCast::CastResult result;
		const bool hit =
		    caster->calcTimeOfImpact(set.fromA[index], set.toA[index], set.poseB[index], set.poseB[index], result);
		benchmark::DoNotOptimize(hit);
		if (hit)
		{
			hits += 1;
			fractionSum += double(result.m_fraction);
		}
		casts += 1;
		index = (index + 1) & (kCastCount - 1);
	}
	state.SetItemsProcessed(state.iterations());
	state.counters["hitRate"] = casts > 0 ? hits / casts : 0;
	state.counters["meanFraction"] = hits > 0 ? fractionSum / hits : 0;
}

#define CALIBER_CAST_BENCH(Pair, Cast)                                                                               \
	void BM_ConvexCast_##Cast##_##Pair(benchmark::State& state) { runCasts(state, PairKind::Pair, CastKind::Cast); } \
	BENCHMARK(BM_ConvexCast_##Cast##_##Pair)

CALIBER_CAST_BENCH(SphereSphere, Subsimplex);
CALIBER_CAST_BENCH(BoxBox, Subsimplex);
CALIBER_CAST_BENCH(HullHull, Subsimplex);
CALIBER_CAST_BENCH(SphereSphere, Gjk);
CALIBER_CAST_BENCH(BoxBox, Gjk);
CALIBER_CAST_BENCH(HullHull, Gjk);
CALIBER_CAST_BENCH(SphereSphere, Continuous);
CALIBER_CAST_BENCH(BoxBox, Continuous);
CALIBER_CAST_BENCH(HullHull, Continuous);
CALIBER_CAST_BENCH(SphereSphere, ContinuousRotating);
CALIBER_CAST_BENCH(BoxBox, ContinuousRotating);
CALIBER_CAST_BENCH(HullHull, ContinuousRotating);
}  // namespace
