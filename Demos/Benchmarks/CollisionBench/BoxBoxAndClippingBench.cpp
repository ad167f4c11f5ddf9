// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Box-box contacts (btBoxBoxDetector) and polyhedral SAT + clipping (btPolyhedralContactClipping) on
// resting and random pairs. Each benchmark reports the contact points found per query as a sanity
// figure ("points_per_query"), so that speed is never bought with missing contacts.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "BulletCollision/CollisionDispatch/btBoxBoxDetector.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "BulletCollision/NarrowPhaseCollision/btPolyhedralContactClipping.h"
#include "LinearMath/btQuaternion.h"

namespace
{
struct CountingResult : public btDiscreteCollisionDetectorInterface::Result
{
	long long points = 0;
	btScalar depthSum = 0;
	void setShapeIdentifiersA(int, int) override {}
	void setShapeIdentifiersB(int, int) override {}
	void addContactPoint(const btVector3&, const btVector3&, btScalar depth) override
	{
		++points;
		depthSum += depth;
	}
};

const int kPairCount = 256;

struct Pair
{
	btTransform a, b;
};

btVector3 randomUnit(std::mt19937& rng)
{
	std::uniform_real_distribution<double> u(-1, 1);
	for (;;)
	{
		const btVector3 v(btScalar(u(rng)), btScalar(u(rng)), btScalar(u(rng)));
		if (v.length2() > btScalar(0.01) && v.length2() <= 1) return v.normalized();
	}
}

// Small boxes resting on a ground box at random yaw with slight penetration.
std::vector<Pair> restingPairs()
{
	std::mt19937 rng(1);
	std::uniform_real_distribution<double> u(-1, 1);
	std::vector<Pair> pairs;
	for (int i = 0; i < kPairCount; ++i)
	{
		Pair p;
		p.a = btTransform(btQuaternion(btVector3(0, 1, 0), btScalar(3 * u(rng))),
		                  btVector3(btScalar(u(rng)), btScalar(0.5 - 0.01 - 0.01 * u(rng)), btScalar(u(rng))));
		p.b = btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0));
		pairs.push_back(p);
	}
	return pairs;
}

// Random orientations with centres close enough that most pairs overlap.
std::vector<Pair> randomPairs()
{
	std::mt19937 rng(2);
	std::uniform_real_distribution<double> u(-1, 1);
	std::vector<Pair> pairs;
	for (int i = 0; i < kPairCount; ++i)
	{
		Pair p;
		p.a = btTransform(btQuaternion(randomUnit(rng), btScalar(3 * u(rng))),
		                  btVector3(btScalar(u(rng)), btScalar(u(rng)), btScalar(u(rng))));
		p.b = btTransform(btQuaternion(randomUnit(rng), btScalar(3 * u(rng))),
		                  btVector3(btScalar(u(rng)), btScalar(u(rng)), btScalar(u(rng))));
		pairs.push_back(p);
	}
	return pairs;
}

void boxBox(benchmark::State& state, const std::vector<Pair>& pairs, const btVector3& halfA, const btVector3& halfB)
{
	btBoxShape a(halfA), b(halfB);
	btBoxBoxDetector detector(&a, &b);
	btDiscreteCollisionDetectorInterface::ClosestPointInput input;
	input.m_maximumDistanceSquared = btScalar(0.02 * 0.02);
	CountingResult result;
	size_t i = 0;
	long long queries = 0;
	for (auto _ : state)
	{
		const Pair& p = pairs[i++ % pairs.size()];
		input.m_transformA = p.a;
		input.m_transformB = p.b;
		detector.getClosestPoints(input, result, nullptr);
		++queries;
	}
	benchmark::DoNotOptimize(result.depthSum);
	state.SetItemsProcessed(queries);
	state.counters["points_per_query"] = queries ? double(result.points) / double(queries) : 0.0;
}

void BM_BoxBoxDetectorResting(benchmark::State& state)
{
	static const std::vector<Pair> pairs = restingPairs();
	boxBox(state, pairs, btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)), btVector3(5, 1, 5));
}
BENCHMARK(BM_BoxBoxDetectorResting);

void BM_BoxBoxDetectorRandom(benchmark::State& state)
{
	static const std::vector<Pair> pairs = randomPairs();
	boxBox(state, pairs, btVector3(btScalar(0.6), btScalar(0.4), btScalar(0.8)),
	       btVector3(btScalar(0.5), 1, btScalar(0.7)));
}
BENCHMARK(BM_BoxBoxDetectorRandom);

// SAT, then clipping when the hulls overlap: the per-pair work btConvexConvexAlgorithm does.
void satAndClip(benchmark::State& state, const std::vector<Pair>& pairs, const btConvexPolyhedron& hullA,
                const btConvexPolyhedron& hullB)
{
	btVertexArray scratch1, scratch2;
	CountingResult result;
	size_t i = 0;
	long long queries = 0;
	for (auto _ : state)
	{
		const Pair& p = pairs[i++ % pairs.size()];
		btVector3 sep;
		if (btPolyhedralContactClipping::findSeparatingAxis(hullA, hullB, p.a, p.b, sep, result))
			btPolyhedralContactClipping::clipHullAgainstHull(sep, hullA, hullB, p.a, p.b, btScalar(-10), btScalar(0.02),
			                                                 scratch1, scratch2, result);
		++queries;
	}
	benchmark::DoNotOptimize(result.depthSum);
	state.SetItemsProcessed(queries);
	state.counters["points_per_query"] = queries ? double(result.points) / double(queries) : 0.0;
}

void addBoxPoints(btConvexHullShape& hull, const btVector3& h)
{
	for (int i = 0; i < 8; ++i)
		hull.addPoint(btVector3((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z()));
	hull.initializePolyhedralFeatures();
}

void BM_ClippingBoxHullsResting(benchmark::State& state)
{
	static const std::vector<Pair> pairs = restingPairs();
	btConvexHullShape a, b;
	addBoxPoints(a, btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	addBoxPoints(b, btVector3(5, 1, 5));
	satAndClip(state, pairs, *a.getConvexPolyhedron(), *b.getConvexPolyhedron());
}
BENCHMARK(BM_ClippingBoxHullsResting);

void BM_ClippingBoxHullsRandom(benchmark::State& state)
{
	static const std::vector<Pair> pairs = randomPairs();
	btConvexHullShape a, b;
	addBoxPoints(a, btVector3(btScalar(0.6), btScalar(0.4), btScalar(0.8)));
	addBoxPoints(b, btVector3(btScalar(0.5), 1, btScalar(0.7)));
	satAndClip(state, pairs, *a.getConvexPolyhedron(), *b.getConvexPolyhedron());
}
BENCHMARK(BM_ClippingBoxHullsRandom);

void BM_Clipping32VertexHullsRandom(benchmark::State& state)
{
	static const std::vector<Pair> pairs = randomPairs();
	std::mt19937 rng(3);
	btConvexHullShape a, b;
	for (int i = 0; i < 32; ++i)
	{
		a.addPoint(randomUnit(rng) * btVector3(btScalar(0.8), btScalar(0.6), 1));
		b.addPoint(randomUnit(rng) * btVector3(1, btScalar(0.7), btScalar(0.6)));
	}
	a.initializePolyhedralFeatures();
	b.initializePolyhedralFeatures();
	satAndClip(state, pairs, *a.getConvexPolyhedron(), *b.getConvexPolyhedron());
}
BENCHMARK(BM_Clipping32VertexHullsRandom);
}  // namespace
