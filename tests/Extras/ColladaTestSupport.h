// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// What the COLLADA tests share: importing a string, editing a document, an empty world, and the check that
// cut and randomly edited documents import or fail but never crash.
#ifndef CALIBER_TESTS_EXTRAS_COLLADA_TEST_SUPPORT_H
#define CALIBER_TESTS_EXTRAS_COLLADA_TEST_SUPPORT_H

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "Serialize/ColladaConverter/ColladaPhysics.h"

namespace collada_test
{
inline bool import(const std::string& text, caliber::ColladaPhysicsScene& scene)
{
	return caliber::importColladaPhysics(text.data(), text.size(), scene);
}

// text with its first from replaced by to (a failed expectation when from is missing).
inline std::string replaced(std::string text, const std::string& from, const std::string& to)
{
	const std::size_t at = text.find(from);
	EXPECT_NE(at, std::string::npos) << from;
	if (at != std::string::npos) text.replace(at, from.size(), to);
	return text;
}

struct EmptyWorld
{
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher{&configuration};
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration};
};

// Every step-th prefix of text fails (a cut document misses its closing tag), and trials copies with 3
// random bytes changed (fixed seed) import or fail; some must fail. A crash or sanitizer report fails the test.
inline void expectCutOrEditedDocumentsNeverCrash(const std::string& text, std::size_t step, int trials, unsigned seed)
{
	int loaded = 0;
	for (std::size_t length = 0; length < text.size(); length += step)
	{
		caliber::ColladaPhysicsScene scene;
		loaded += import(text.substr(0, length), scene);
	}
	EXPECT_EQ(loaded, 0) << "a cut document misses its closing tag";
	std::mt19937 random(seed);
	int failed = 0;
	for (int trial = 0; trial < trials; ++trial)
	{
		std::string damaged = text;
		for (int e = 0; e < 3; ++e) damaged[random() % damaged.size()] = char(random() % 256);
		caliber::ColladaPhysicsScene scene;
		failed += !import(damaged, scene);
	}
	EXPECT_GT(failed, 0);
}
}  // namespace collada_test

#endif  // CALIBER_TESTS_EXTRAS_COLLADA_TEST_SUPPORT_H
