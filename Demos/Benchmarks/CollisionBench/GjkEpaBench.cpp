// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// GJK/EPA micro-benchmarks: btGjkPairDetector distances of separated pairs, btGjkPairDetector on
// shallow contacts inside the margins (GJK on the cores, the common resting case), and
// btGjkEpaSolver2 penetration of deeply overlapping pairs. Each benchmark cycles through 256 pairs
// whose random transforms are drawn once, outside the timed loop, from a fixed seed. The counter
// "meanDistance" (signed, margins included) is a sanity figure: it must not change with speed work.
// The results are consumed by these sums, so no DoNotOptimize is needed (Google Benchmark 1.7's
// DoNotOptimize on a float lvalue miscompiles with g++ 12 here: the sums came out as garbage).

#include <benchmark/benchmark.h>

#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btConeShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "BulletCollision/CollisionShapes/btCylinderShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkEpa2.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h"
#include "BulletCollision/NarrowPhaseCollision/btPointCollector.h"
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"
#include "LinearMath/btQuaternion.h"
#include "LinearMath/btTransform.h"

namespace
{
const int kPairCount = 256;  // a power of two: the index wraps with a mask

/// Which shapes a benchmark pairs.
enum class PairKind
{
	SphereSphere,
	BoxBox,
	HullHull,
	CylinderCone
};

/// How far apart the pairs are placed.
enum class Placement
{
	Separated,  // centres 1.2 to 2 bounding radii apart: GJK distance only
	Shallow,    // surfaces overlapping by less than the margins: GJK on the cores, no EPA
	Deep        // centres within 0.3 of the bounding radii: the cores overlap, EPA runs
};

/// Two shapes and kPairCount transform pairs, all built before timing.
struct PairSet
{
	std::unique_ptr<btConvexShape> a, b;
	std::vector<btTransform> poseA, poseB;
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

/// Bounding radius (margin included) of the shape about its origin, from its AABB.
btScalar boundingRadius(const btConvexShape& shape)
{
	btTransform identity;
	identity.setIdentity();
	btVector3 lo, hi;
	shape.getAabb(identity, lo, hi);
	return btMax(lo.length(), hi.length());
}

btQuaternion randomRotation(std::mt19937& rng)
{
	std::uniform_real_distribution<float> unit(-1.f, 1.f);
	for (;;)
	{
		const btQuaternion q(btScalar(unit(rng)), btScalar(unit(rng)), btScalar(unit(rng)), btScalar(unit(rng)));
		const btScalar l2 = q.length2();
		if (l2 > btScalar(0.01) && l2 <= 1) return q / btSqrt(l2);
	}
}

btVector3 randomDirection(std::mt19937& rng)
{
	std::uniform_real_distribution<float> unit(-1.f, 1.f);
	for (;;)
	{
		const btVector3 v(btScalar(unit(rng)), btScalar(unit(rng)), btScalar(unit(rng)));
		const btScalar l2 = v.length2();
		if (l2 > btScalar(0.01) && l2 <= 1) return v / btSqrt(l2);
	}
}

/// The shapes of kind and kPairCount poses with the requested placement (fixed seed per kind).
PairSet makePairs(PairKind kind, Placement placement)
{
	std::mt19937 rng(1234u + 17u * unsigned(kind) + 101u * unsigned(placement));
	PairSet set;
	switch (kind)
	{
		case PairKind::SphereSphere:
			set.a.reset(new btSphereShape(btScalar(0.5)));
			set.b.reset(new btSphereShape(btScalar(0.4)));
			break;
		case PairKind::BoxBox:
			set.a.reset(new btBoxShape(btVector3(btScalar(0.5), btScalar(0.3), btScalar(0.4))));
			set.b.reset(new btBoxShape(btVector3(btScalar(0.35), btScalar(0.6), btScalar(0.25))));
			break;
		case PairKind::HullHull:
			set.a.reset(makeHull(rng));
			set.b.reset(makeHull(rng));
			break;
		case PairKind::CylinderCone:
			set.a.reset(new btCylinderShape(btVector3(btScalar(0.4), btScalar(0.5), btScalar(0.4))));
			set.b.reset(new btConeShape(btScalar(0.45), btScalar(1.0)));
			break;
	}
	const btScalar reach = boundingRadius(*set.a) + boundingRadius(*set.b);
	std::uniform_real_distribution<float> unit(0.f, 1.f);
	btVoronoiSimplexSolver simplex;
	btGjkEpaPenetrationDepthSolver depthSolver;
	while (int(set.poseA.size()) < kPairCount)
	{
		btTransform ta(randomRotation(rng), btVector3(btScalar(unit(rng)), btScalar(unit(rng)), btScalar(unit(rng))));
		btTransform tb(randomRotation(rng), ta.getOrigin());
		const btVector3 dir = randomDirection(rng);
		if (placement == Placement::Deep)
		{
			tb.setOrigin(ta.getOrigin() + dir * (btScalar(0.3) * reach * btScalar(unit(rng))));
		}
		else
		{
			const btScalar lo = placement == Placement::Separated ? btScalar(1.2) : btScalar(0.3);
			tb.setOrigin(ta.getOrigin() + dir * (reach * (lo + btScalar(0.8) * btScalar(unit(rng)))));
			if (placement == Placement::Shallow)
			{
				// Slide B along dir until the surfaces overlap by a random fraction of the margins.
				btGjkPairDetector detector(set.a.get(), set.b.get(), &simplex, &depthSolver);
				btDiscreteCollisionDetectorInterface::ClosestPointInput input;
				input.m_transformA = ta;
				input.m_transformB = tb;
				btPointCollector collector;
				detector.getClosestPoints(input, collector, nullptr);
				if (!collector.m_hasResult) continue;
				const btScalar margins = set.a->getMargin() + set.b->getMargin();
				const btScalar target = -margins * btScalar(0.8) * btScalar(unit(rng));
				// Moving B along -n (n from B to A) by s reduces the distance by s on the contact face.
				tb.getOrigin() += collector.m_normalOnBInWorld * (collector.m_distance - target);
			}
		}
		set.poseA.push_back(ta);
		set.poseB.push_back(tb);
	}
	return set;
}

/// btGjkPairDetector::getClosestPoints on the pairs, one query per iteration.
void runPairDetector(benchmark::State& state, PairKind kind, Placement placement)
{
	const PairSet set = makePairs(kind, placement);
	btVoronoiSimplexSolver simplex;
	btGjkEpaPenetrationDepthSolver depthSolver;
	btGjkPairDetector detector(set.a.get(), set.b.get(), &simplex, &depthSolver);
	btDiscreteCollisionDetectorInterface::ClosestPointInput input;
	double distanceSum = 0;
	std::int64_t reported = 0;
	int index = 0;
	for (auto _ : state)
	{
		input.m_transformA = set.poseA[index];
		input.m_transformB = set.poseB[index];
		index = (index + 1) & (kPairCount - 1);
		btPointCollector collector;
		detector.getClosestPoints(input, collector, nullptr);
		if (collector.m_hasResult)
		{
			distanceSum += double(collector.m_distance);
			++reported;
		}
	}
	state.SetItemsProcessed(state.iterations());
	state.counters["meanDistance"] = reported ? distanceSum / double(reported) : 0.0;
	state.counters["reported%"] = 100.0 * double(reported) / double(state.iterations());
}

/// btGjkEpaSolver2::Penetration on deeply overlapping pairs, one query per iteration.
void runEpaPenetration(benchmark::State& state, PairKind kind)
{
	const PairSet set = makePairs(kind, Placement::Deep);
	double depthSum = 0;
	std::int64_t penetrating = 0;
	int index = 0;
	for (auto _ : state)
	{
		const btTransform& ta = set.poseA[index];
		const btTransform& tb = set.poseB[index];
		index = (index + 1) & (kPairCount - 1);
		btGjkEpaSolver2::sResults results;
		const bool hit =
		    btGjkEpaSolver2::Penetration(set.a.get(), ta, set.b.get(), tb, tb.getOrigin() - ta.getOrigin(), results);
		if (hit)
		{
			depthSum += double((results.witnesses[1] - results.witnesses[0]).length());
			++penetrating;
		}
	}
	state.SetItemsProcessed(state.iterations());
	state.counters["meanDistance"] = penetrating ? -depthSum / double(penetrating) : 0.0;
	state.counters["reported%"] = 100.0 * double(penetrating) / double(state.iterations());
}

void BM_GjkDistance_SphereSphere(benchmark::State& s)
{
	runPairDetector(s, PairKind::SphereSphere, Placement::Separated);
}
void BM_GjkDistance_BoxBox(benchmark::State& s) { runPairDetector(s, PairKind::BoxBox, Placement::Separated); }
void BM_GjkDistance_HullHull32(benchmark::State& s) { runPairDetector(s, PairKind::HullHull, Placement::Separated); }
void BM_GjkDistance_CylinderCone(benchmark::State& s)
{
	runPairDetector(s, PairKind::CylinderCone, Placement::Separated);
}
void BM_GjkMarginContact_BoxBox(benchmark::State& s) { runPairDetector(s, PairKind::BoxBox, Placement::Shallow); }
void BM_GjkMarginContact_CylinderCone(benchmark::State& s)
{
	runPairDetector(s, PairKind::CylinderCone, Placement::Shallow);
}
void BM_EpaPenetration_BoxBox(benchmark::State& s) { runEpaPenetration(s, PairKind::BoxBox); }
void BM_EpaPenetration_HullHull32(benchmark::State& s) { runEpaPenetration(s, PairKind::HullHull); }
void BM_PairDetectorDeep_BoxBox(benchmark::State& s) { runPairDetector(s, PairKind::BoxBox, Placement::Deep); }
}  // namespace

BENCHMARK(BM_GjkDistance_SphereSphere);
BENCHMARK(BM_GjkDistance_BoxBox);
BENCHMARK(BM_GjkDistance_HullHull32);
BENCHMARK(BM_GjkDistance_CylinderCone);
BENCHMARK(BM_GjkMarginContact_BoxBox);
BENCHMARK(BM_GjkMarginContact_CylinderCone);
BENCHMARK(BM_EpaPenetration_BoxBox);
BENCHMARK(BM_EpaPenetration_HullHull32);
BENCHMARK(BM_PairDetectorDeep_BoxBox);
