// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The wide sweep of coloured contact batches (btWideContactRows.h) gives the bits of the row-by-row
// sweep, at any thread count: worlds stepped with it on and off end bit for bit the same.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "BulletCollision/CollisionDispatch/btCollisionDispatcherMt.h"
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolverMt.h"
#include "BulletDynamics/ConstraintSolver/btWideContactRows.h"
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorldMt.h"
#include "LinearMath/btThreads.h"
#include "MtSolverTestUtil.h"
#include "TestThreadsUtil.h"
#include "btBulletDynamicsCommon.h"

namespace
{
enum class Scene
{
	BoxPile,         // boxes on a ground box: 4-point manifolds next to 1- and 2-point ones
	SpheresRolling,  // spheres with rolling friction on the ground: one point per manifold, rolling rows
	FloatingCluster  // boxes and spheres thrown together in zero gravity: no static body at all
};

// A solver whose contact rows push body B a little harder than they pull body A (its second linear
// direction is not the first one negated): rows the wide blocks cannot hold.
class LopsidedRowsSolver : public btSequentialImpulseConstraintSolverMt
{
protected:
	void convertContacts(btPersistentManifold** manifolds, int numManifolds, const btContactSolverInfo& info) override
	{
		btSequentialImpulseConstraintSolverMt::convertContacts(manifolds, numManifolds, info);
		for (int i = 0; i < m_tmpSolverContactConstraintPool.size(); ++i)
		{
			btSolverConstraint& row = m_tmpSolverContactConstraintPool[i];
			row.m_contactNormal2 = -row.m_contactNormal1 * btScalar(1.001);
		}
	}
};

// A small Mt world with every solve coloured.
struct World
{
	explicit World(Scene scene, int solverMode, bool lopsided = false)
	{
		btDefaultCollisionConstructionInfo info;
		info.m_defaultMaxPersistentManifoldPoolSize = 4096;
		info.m_defaultMaxCollisionAlgorithmPoolSize = 4096;
		config.reset(new btDefaultCollisionConfiguration(info));
		dispatcher.reset(new btCollisionDispatcherMt(config.get(), 16));
		pool.reset(new btConstraintSolverPoolMt(BT_MAX_THREAD_COUNT));
		solver.reset(lopsided ? new LopsidedRowsSolver() : new btSequentialImpulseConstraintSolverMt());
		broadphase.reset(new btDbvtBroadphase());
		world.reset(
		    new btDiscreteDynamicsWorldMt(dispatcher.get(), broadphase.get(), pool.get(), solver.get(), config.get()));
		world->getSolverInfo().m_solverMode = solverMode;
		box.reset(new btBoxShape(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5))));
		sphere.reset(new btSphereShape(btScalar(0.4)));
		ground.reset(new btBoxShape(btVector3(20, 1, 20)));
		if (scene == Scene::FloatingCluster)
		{
			world->setGravity(btVector3(0, 0, 0));
			for (int i = 0; i < 27; ++i)
			{
				const btVector3 at(btScalar(i % 3) * btScalar(1.1), btScalar((i / 3) % 3) * btScalar(1.1),
				                   btScalar(i / 9) * btScalar(1.1));
				btRigidBody* body = add(1, (i & 1) ? sphere.get() : box.get(), at);
				// Every body heads for the middle: they meet and press together.
				body->setLinearVelocity((btVector3(btScalar(1.1), btScalar(1.1), btScalar(1.1)) - at) * btScalar(2));
			}
			return;
		}
		world->setGravity(btVector3(0, -10, 0));
		add(0, ground.get(), btVector3(0, -1, 0));
		for (int i = 0; i < 30; ++i)
		{
			const btVector3 at(btScalar(i % 5) * btScalar(1.3) + btScalar(0.1) * btScalar(i / 10),
			                   btScalar(0.5) + btScalar(i / 10) * btScalar(1.05), btScalar((i / 5) % 2) * btScalar(1.3));
			btRigidBody* body = add(1, scene == Scene::BoxPile ? box.get() : sphere.get(), at);
			body->setLinearVelocity(btVector3(btScalar(0.3) * btScalar(i % 3), 0, btScalar(-0.2) * btScalar(i % 2)));
			body->setAngularVelocity(btVector3(0, btScalar(i % 4), 0));
			if (scene == Scene::SpheresRolling)
			{
				body->setRollingFriction(btScalar(0.05));
				body->setSpinningFriction(btScalar(0.05));
			}
		}
	}
	~World()
	{
		for (auto& body : bodies) world->removeRigidBody(body.get());
	}
	btRigidBody* add(btScalar mass, btCollisionShape* shape, const btVector3& at)
	{
		btVector3 inertia(0, 0, 0);
		if (mass != 0) shape->calculateLocalInertia(mass, inertia);
		btRigidBody::btRigidBodyConstructionInfo info(mass, 0, shape, inertia);
		info.m_startWorldTransform.setOrigin(at);
		bodies.emplace_back(new btRigidBody(info));
		bodies.back()->setActivationState(DISABLE_DEACTIVATION);
		world->addRigidBody(bodies.back().get());
		return bodies.back().get();
	}
	// The bits of every body's pose and velocities.
	std::vector<btScalar> state() const { return caliber_test::bodyStateBits(bodies); }

	std::unique_ptr<btDefaultCollisionConfiguration> config;
	std::unique_ptr<btCollisionDispatcher> dispatcher;
	std::unique_ptr<btConstraintSolverPoolMt> pool;
	std::unique_ptr<btSequentialImpulseConstraintSolverMt> solver;
	std::unique_ptr<btBroadphaseInterface> broadphase;
	std::unique_ptr<btDiscreteDynamicsWorld> world;
	std::unique_ptr<btCollisionShape> box, sphere, ground;
	std::vector<std::unique_ptr<btRigidBody>> bodies;
};

// Every solve coloured (these scenes have far fewer than the default 250 manifolds), and the wide sweep
// as it was found afterwards.
struct ColourEverySolve
{
	caliber_test::ScopedManifoldBatchingThreshold colourAll;
	bool savedWide = caliber::wideContactRowsEnabled();
	int savedLanes = caliber::wideContactLanes() == 4 && caliber::wideContactEightLanesAvailable() ? 4 : 0;
	~ColourEverySolve()
	{
		caliber::setWideContactRowsEnabled(savedWide);
		caliber::setWideContactLanes(savedLanes);
	}
};

// Steps a world with the wide sweep and one without, side by side, and compares their bits.
void expectWideSweepGivesRowByRowBits(Scene scene, int solverMode, int threads, int steps, int lanes)
{
	ColourEverySolve colourAll;
	caliber::setWideContactLanes(lanes);
	caliber_test::ScopedTaskScheduler scheduler(threads);
	World wide(scene, solverMode), rowByRow(scene, solverMode);
	const std::vector<btScalar> start = wide.state();
	for (int i = 0; i < steps; ++i)
	{
		caliber::setWideContactRowsEnabled(true);
		wide.world->stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
		caliber::setWideContactRowsEnabled(false);
		rowByRow.world->stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
	}
	const std::vector<btScalar> a = wide.state(), b = rowByRow.state();
	ASSERT_EQ(a.size(), b.size());
	// Something happened (the comparison is not of two worlds at rest where they started).
	EXPECT_NE(0, std::memcmp(a.data(), start.data(), a.size() * sizeof(btScalar)));
	EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(btScalar)))
	    << "scene " << int(scene) << ", solver mode " << solverMode << ", " << threads << " threads, " << lanes
	    << " lanes";
}
}  // namespace

// Four lanes everywhere; eight where the processor has AVX2 (elsewhere the eight-lane runs take four
// lanes again, and say so).
class WideContactRowsLanes : public ::testing::TestWithParam<int>
{
protected:
	void SetUp() override
	{
		if (GetParam() == 8 && !caliber::wideContactEightLanesAvailable())
			std::printf("note: eight lanes are not available here; the sweep takes four\n");
	}
};

TEST_P(WideContactRowsLanes, BoxPileGivesTheRowByRowBits)
{
	for (int threads : {1, 2})
		expectWideSweepGivesRowByRowBits(Scene::BoxPile, SOLVER_USE_WARMSTARTING | SOLVER_SIMD, threads, 60, GetParam());
}

TEST_P(WideContactRowsLanes, TwoFrictionDirectionsGiveTheRowByRowBits)
{
	expectWideSweepGivesRowByRowBits(Scene::BoxPile, SOLVER_USE_WARMSTARTING | SOLVER_SIMD | SOLVER_USE_2_FRICTION_DIRECTIONS,
	                                 2, 60, GetParam());
}

TEST_P(WideContactRowsLanes, RollingSpheresGiveTheRowByRowBits)
{
	expectWideSweepGivesRowByRowBits(Scene::SpheresRolling, SOLVER_USE_WARMSTARTING | SOLVER_SIMD, 2, 60, GetParam());
}

TEST_P(WideContactRowsLanes, ClusterWithoutStaticBodyGivesTheRowByRowBits)
{
	// No fixed solver entry: the padding lanes use zero bodies of their own.
	expectWideSweepGivesRowByRowBits(Scene::FloatingCluster, SOLVER_USE_WARMSTARTING | SOLVER_SIMD, 2, 60, GetParam());
}

INSTANTIATE_TEST_SUITE_P(FourAndEight, WideContactRowsLanes, ::testing::Values(4, 8));

TEST(WideContactRows, EightLanesAreChosenWhereAvailableAndFourCanBeAskedFor)
{
	ColourEverySolve restore;
	caliber::setWideContactLanes(0);
	EXPECT_EQ(caliber::wideContactLanes(), caliber::wideContactEightLanesAvailable() ? 8 : 4);
	caliber::setWideContactLanes(4);
	EXPECT_EQ(caliber::wideContactLanes(), 4);
	caliber::setWideContactLanes(8);
	EXPECT_EQ(caliber::wideContactLanes(), caliber::wideContactEightLanesAvailable() ? 8 : 4);
	// Any other count means the automatic choice.
	for (int nonsense : {-1, 5, 16})
	{
		caliber::setWideContactLanes(nonsense);
		EXPECT_EQ(caliber::wideContactLanes(), caliber::wideContactEightLanesAvailable() ? 8 : 4) << nonsense;
	}
}

TEST(WideContactRows, TurningItOffAndOnBetweenStepsIsSafe)
{
	// The switch is read when a solve is set up; flipping it every step mixes the two sweeps, which give
	// the same bits, so the world matches one stepped with the wide sweep throughout.
	ColourEverySolve colourAll;
	World flipped(Scene::BoxPile, SOLVER_USE_WARMSTARTING | SOLVER_SIMD), wide(Scene::BoxPile, SOLVER_USE_WARMSTARTING | SOLVER_SIMD);
	for (int i = 0; i < 30; ++i)
	{
		caliber::setWideContactRowsEnabled(i % 2 == 0);
		flipped.world->stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
		caliber::setWideContactRowsEnabled(true);
		wide.world->stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
	}
	const std::vector<btScalar> a = flipped.state(), b = wide.state();
	ASSERT_EQ(a.size(), b.size());
	EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(btScalar)));
}

TEST(WideContactRows, RowsTheBlocksCannotHoldAreSweptRowByRow)
{
	// The blocks keep one linear direction per row and negate it for body B; a subclass's rows that do not
	// have that shape send the solve back to the row-by-row sweep, with its bits.
	ColourEverySolve colourAll;
	World wide(Scene::BoxPile, SOLVER_USE_WARMSTARTING | SOLVER_SIMD, true);
	World rowByRow(Scene::BoxPile, SOLVER_USE_WARMSTARTING | SOLVER_SIMD, true);
	for (int i = 0; i < 30; ++i)
	{
		caliber::setWideContactRowsEnabled(true);
		wide.world->stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
		caliber::setWideContactRowsEnabled(false);
		rowByRow.world->stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
	}
	const std::vector<btScalar> a = wide.state(), b = rowByRow.state();
	ASSERT_EQ(a.size(), b.size());
	EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(btScalar)));
}

namespace
{
// Rows whose every field the blocks keep has a value of its own (row i, field f: i + f / 64, exact in
// float and double), their second linear direction the first negated.
btSolverConstraint numberedRow(int i, int bodyA, int bodyB)
{
	btSolverConstraint row;
	std::memset(static_cast<void*>(&row), 0, sizeof(row));
	const auto v = [i](int f) { return btScalar(i) + btScalar(f) / btScalar(64); };
	row.m_contactNormal1.setValue(v(0), v(1), v(2));
	row.m_contactNormal2 = -row.m_contactNormal1;
	row.m_relpos1CrossNormal.setValue(v(3), v(4), v(5));
	row.m_relpos2CrossNormal.setValue(v(6), v(7), v(8));
	row.m_angularComponentA.setValue(v(9), v(10), v(11));
	row.m_angularComponentB.setValue(v(12), v(13), v(14));
	row.m_rhs = v(15);
	row.m_cfm = v(16);
	row.m_jacDiagABInv = v(17);
	row.m_lowerLimit = v(18);
	row.m_upperLimit = v(19);
	row.m_friction = v(20);
	row.m_appliedImpulse = v(21);
	row.m_appliedPushImpulse = v(22);  // not kept
	row.m_solverBodyIdA = bodyA;
	row.m_solverBodyIdB = bodyB;
	return row;
}

// Manifolds with 1 to 4 points in two batches, filled with a rotation: every lane of every block holds the
// row the row-by-row sweep would solve there (with all its fields), padding lanes hold zeros and row -1.
template <int W>
void expectBlocksHoldTheRows(caliber::WideContactRows& wide, const caliber::WideLayout<W>& layout)
{
	const int frictionRows = 2;
	const int pointCounts[] = {3, 1, 4, 2, 4, 1, 1, 3, 2, 4, 4, 1, 2};  // 13 manifolds
	const int numManifolds = 13;
	btAlignedObjectArray<int> manifoldFirstRow, orderedManifolds, batchManifoldBegin, batchPaddingBody;
	manifoldFirstRow.push_back(0);
	for (int m = 0; m < numManifolds; ++m) manifoldFirstRow.push_back(manifoldFirstRow[m] + pointCounts[m]);
	// Batch 0: manifolds 12, 0, 5, 7, 3, 9, 1, 10, 2 (more than eight: two groups at eight lanes);
	// batch 1: 4, 8, 11, 6.
	for (int m : {12, 0, 5, 7, 3, 9, 1, 10, 2, 4, 8, 11, 6}) orderedManifolds.push_back(m);
	for (int b : {0, 9, 13}) batchManifoldBegin.push_back(b);
	const int numBodies = 2 * numManifolds + 2;
	for (int b : {numBodies - 2, numBodies - 1}) batchPaddingBody.push_back(b);
	btAlignedObjectArray<btSolverBody> bodies;
	bodies.resize(numBodies);
	for (int i = 0; i < numBodies; ++i)
	{
		std::memset(static_cast<void*>(&bodies[i]), 0, sizeof(btSolverBody));
		bodies[i].m_invMass.setValue(btScalar(i), btScalar(i) + btScalar(0.25), btScalar(i) + btScalar(0.5));
		bodies[i].m_angularFactor.setValue(-btScalar(i), btScalar(0.125), btScalar(i) * 2);
	}
	btConstraintArray contacts, friction;
	const int numRows = manifoldFirstRow[numManifolds];
	for (int m = 0; m < numManifolds; ++m)
		for (int r = manifoldFirstRow[m]; r < manifoldFirstRow[m + 1]; ++r)
		{
			contacts.push_back(numberedRow(r, 2 * m, 2 * m + 1));
			for (int f = 0; f < frictionRows; ++f)
				friction.push_back(numberedRow(1000 + frictionRows * r + f, 2 * m, 2 * m + 1));
		}
	ASSERT_EQ(contacts.size(), numRows);

	const unsigned int solveCount = 7;
	wide.plan(orderedManifolds, batchManifoldBegin, manifoldFirstRow, frictionRows);
	ASSERT_EQ(wide.lanes, W);
	ASSERT_TRUE(wide.fill(0, 2, orderedManifolds, batchManifoldBegin, manifoldFirstRow, batchPaddingBody, solveCount,
	                      &bodies[0], contacts, friction));

	const auto expectLane = [](const caliber::WideRowBlockT<W>& block, int k, const btSolverConstraint* row, int index)
	{
		SCOPED_TRACE(testing::Message() << "lane " << k << " row " << index);
		EXPECT_EQ(block.row[k], index);
		const btSolverConstraint zero = [] {
			btSolverConstraint z;
			std::memset(static_cast<void*>(&z), 0, sizeof(z));
			return z;
		}();
		const btSolverConstraint& r = row ? *row : zero;
		for (int c = 0; c < 3; ++c)
		{
			EXPECT_EQ(block.normal1[c][k], r.m_contactNormal1[c]);
			EXPECT_EQ(block.relpos1CrossNormal[c][k], r.m_relpos1CrossNormal[c]);
			EXPECT_EQ(block.relpos2CrossNormal[c][k], r.m_relpos2CrossNormal[c]);
			EXPECT_EQ(block.angularA[c][k], r.m_angularComponentA[c]);
			EXPECT_EQ(block.angularB[c][k], r.m_angularComponentB[c]);
		}
		EXPECT_EQ(block.rhs[k], r.m_rhs);
		EXPECT_EQ(block.cfm[k], r.m_cfm);
		EXPECT_EQ(block.jacDiagABInv[k], r.m_jacDiagABInv);
		EXPECT_EQ(block.lower[k], r.m_lowerLimit);
		EXPECT_EQ(block.upper[k], r.m_upperLimit);
		EXPECT_EQ(block.friction[k], r.m_friction);
		EXPECT_EQ(block.applied[k], r.m_appliedImpulse);
	};
	int checkedRows = 0;
	for (int b = 0; b < 2; ++b)
	{
		ASSERT_EQ(wide.batchFirstGroup[b + 1] - wide.batchFirstGroup[b],
		          (batchManifoldBegin[b + 1] - batchManifoldBegin[b] + W - 1) / W);
		for (int g = wide.batchFirstGroup[b]; g < wide.batchFirstGroup[b + 1]; ++g)
		{
			const caliber::WideGroupT<W>& group = layout.groups[g];
			const int first = batchManifoldBegin[b] + (g - wide.batchFirstGroup[b]) * W;
			int most = 0;
			for (int k = 0; k < W; ++k)
			{
				const bool real = first + k < batchManifoldBegin[b + 1];
				const int m = real ? orderedManifolds[first + k] : -1;
				EXPECT_EQ(group.bodyA[k], real ? 2 * m : batchPaddingBody[b]);
				EXPECT_EQ(group.bodyB[k], real ? 2 * m + 1 : batchPaddingBody[b]);
				for (int c = 0; c < 3; ++c)
				{
					EXPECT_EQ(group.invMassA[c][k], bodies[group.bodyA[k]].m_invMass[c]);
					EXPECT_EQ(group.angularFactorB[c][k], bodies[group.bodyB[k]].m_angularFactor[c]);
				}
				if (real) most = std::max(most, pointCounts[m]);
			}
			ASSERT_EQ(group.numBlocks, most);
			for (int s = 0; s < group.numBlocks; ++s)
				for (int k = 0; k < W; ++k)
				{
					const bool real = first + k < batchManifoldBegin[b + 1];
					const int m = real ? orderedManifolds[first + k] : -1;
					const bool has = real && s < pointCounts[m];
					// The row-by-row sweep starts each manifold at point solveCount % count.
					const int row = has ? manifoldFirstRow[m] + int((s + solveCount) % unsigned(pointCounts[m])) : -1;
					checkedRows += has ? 1 : 0;
					expectLane(layout.normalBlocks[group.firstBlock + s], k, has ? &contacts[row] : nullptr, row);
					for (int f = 0; f < frictionRows; ++f)
					{
						const int frictionRow = has ? row * frictionRows + f : -1;
						expectLane(layout.frictionBlocks[(group.firstBlock + s) * frictionRows + f], k,
						           has ? &friction[frictionRow] : nullptr, frictionRow);
					}
				}
		}
	}
	EXPECT_EQ(checkedRows, numRows);

	// One row whose second direction is not its first negated, anywhere in a block: the blocks cannot hold
	// the solve. Padding lanes do not count.
	for (int r : {0, numRows - 1})
	{
		btConstraintArray& pool = r == 0 ? contacts : friction;
		const int index = r == 0 ? 0 : friction.size() - 1;
		const btVector3 kept = pool[index].m_contactNormal2;
		pool[index].m_contactNormal2[1] = pool[index].m_contactNormal2[1] * btScalar(1.5);
		EXPECT_FALSE(wide.fill(0, 2, orderedManifolds, batchManifoldBegin, manifoldFirstRow, batchPaddingBody,
		                       solveCount, &bodies[0], contacts, friction))
		    << r;
		pool[index].m_contactNormal2 = kept;
	}
	EXPECT_TRUE(wide.fill(0, 2, orderedManifolds, batchManifoldBegin, manifoldFirstRow, batchPaddingBody, solveCount,
	                      &bodies[0], contacts, friction));
}
}  // namespace

TEST(WideContactRows, BlocksHoldTheRowsOfTheRowByRowSweepAtFourLanes)
{
	ColourEverySolve restore;
	caliber::setWideContactLanes(4);
	caliber::WideContactRows wide;
	expectBlocksHoldTheRows<4>(wide, wide.four);
}

TEST(WideContactRows, BlocksHoldTheRowsOfTheRowByRowSweepAtEightLanes)
{
	if (!caliber::wideContactEightLanesAvailable()) GTEST_SKIP() << "no eight lanes on this processor or build";
	ColourEverySolve restore;
	caliber::setWideContactLanes(8);
	caliber::WideContactRows wide;
	expectBlocksHoldTheRows<8>(wide, wide.eight);
}
