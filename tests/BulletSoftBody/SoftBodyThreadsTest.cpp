// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The soft-body stages on the task scheduler (docs/soft-bodies.md, "Threads"): the bodies' prediction and
// velocity update run one body per task, a large body's node loops and node contact search in chunks, its
// link sweeps in blocks of one colour at a time, and the cluster contacts with rigid shapes a cluster per
// task; the results are the same bits at any thread count. The bodies' position solves run in groups that
// share nothing (btSoftBodySolveGroups.h), a group per task: the same bits again, at 1, 2, 3, 4 and 8
// threads and with a scheduler that splits loops unevenly.

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <utility>
#include <vector>

#include "BulletCollision/CollisionDispatch/btCollisionDispatcherMt.h"
#include "BulletSoftBody/btSoftBodyClusters.h"
#include "BulletSoftBody/btSoftBodyNormals.h"
#include "BulletSoftBody/btSoftBodySolveGroups.h"
#include "LinearMath/btThreads.h"
#include "SoftBodyTestUtil.h"
#include "TestThreadsUtil.h"

using caliber_test::hashNodes;
using caliber_test::SoftTestWorld;
using caliber_test::UnevenSplitScheduler;

namespace
{
// The sanitizers run the scene 25 to 50 times slower: fewer steps there keep their stages short (every
// stage above still runs from the first steps: the box touches the cloth, the clusters the ground).
#if defined(__SANITIZE_THREAD__) || defined(__SANITIZE_ADDRESS__)
const int kSteps = 10;
#else
const int kSteps = 40;
#endif

// A scene with a large pinned cloth (2500 nodes: its node loops and contact search are split in chunks of
// 1024, its 7000 links in blocks of 1024 whose colours hold several; btSoftBodyLinkColours.h), a box
// falling on it, three gas balls, a rope and two balls of clusters, stepped kSteps times on the current scheduler: each
// soft body's node positions, hashed.
std::vector<uint64_t> runScene()
{
	SoftTestWorld w;
	w.addGround();
	std::vector<btSoftBody*> bodies;
	btSoftBody* cloth =
	    w.addSoft(btSoftBodyHelpers::CreatePatch(w.info(), btVector3(-3, 4, -3), btVector3(3, 4, -3),
	                                             btVector3(-3, 4, 3), btVector3(3, 4, 3), 50, 50, 1 + 2 + 4 + 8, true));
	cloth->setTotalMass(2);
	cloth->m_cfg.piterations = 4;
	bodies.push_back(cloth);
	// Just above the cloth: its node contacts with the cloth are searched in chunks from the first steps.
	w.addRigid(1, btVector3(0.2, btScalar(4.45), 0.1), w.shape<btBoxShape>(btVector3(0.3, 0.3, 0.3)));
	for (int i = 0; i < 3; ++i)
	{
		btSoftBody* ball = w.addSoft(btSoftBodyHelpers::CreateEllipsoid(
		    w.info(), btVector3(btScalar(5 + 1.2 * i), btScalar(1 + 1.5 * i), 0), btVector3(0.5, 0.5, 0.5), 96));
		ball->setTotalMass(1, true);
		ball->m_cfg.kPR = 100;
		ball->m_cfg.collisions |= btSoftBody::fCollision::VF_SS;
		bodies.push_back(ball);
	}
	btSoftBody* rope =
	    w.addSoft(btSoftBodyHelpers::CreateRope(w.info(), btVector3(-6, 5, 0), btVector3(-4, 5, 0), 20, 1));
	rope->setTotalMass(btScalar(0.5));
	bodies.push_back(rope);
	// Two balls of 16 clusters, one dropped on the other (CL_RS, CL_SS): the clusters' contacts with the
	// ground are found on the task scheduler, a cluster per task.
	for (int i = 0; i < 2; ++i)
	{
		btSoftBody* ball = w.addSoft(btSoftBodyHelpers::CreateEllipsoid(
		    w.info(), btVector3(btScalar(8 + 0.3 * i), btScalar(1.2 + 2.2 * i), 4), btVector3(1, 1, 1), 128));
		ball->setTotalMass(1, true);
		ball->m_cfg.kPR = 100;
		ball->m_cfg.collisions = btSoftBody::fCollision::CL_RS | btSoftBody::fCollision::CL_SS;
		ball->generateClusters(16);
		bodies.push_back(ball);
	}
	w.step(kSteps);
	// The searches ran: the cloth's node contacts (with the box) and the lower ball's cluster contacts (with
	// the ground) of the last step.
	EXPECT_GT(cloth->m_rcontacts.size(), 0);
	EXPECT_GT(caliber::clusterState(*bodies.back()).contacts.size() +
	              caliber::clusterState(*bodies[bodies.size() - 2]).contacts.size(),
	          0);
	std::vector<uint64_t> hashes;
	for (const btSoftBody* b : bodies) hashes.push_back(hashNodes(*b));
	return hashes;
}
}  // namespace

TEST(SoftBodyThreads, NodePositionsHaveTheSameBitsAtAnyThreadCountAndSplit)
{
#if defined(BT_THREADSAFE) && BT_THREADSAFE
	btSetTaskScheduler(btGetSequentialTaskScheduler());
	const std::vector<uint64_t> reference = runScene();
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	ASSERT_NE(pool.get(), nullptr);
	for (int threads : {1, 2, 3, 4, 8})
	{
		pool->setNumThreads(threads);
		ASSERT_EQ(pool->getNumThreads(), btMin(threads, pool->getMaxNumThreads()));
		btSetTaskScheduler(pool.get());
		EXPECT_EQ(runScene(), reference) << threads << " threads";
		btSetTaskScheduler(0);
	}
	UnevenSplitScheduler uneven;
	btSetTaskScheduler(&uneven);
	EXPECT_EQ(runScene(), reference) << "uneven splits";
	btSetTaskScheduler(0);
#else
	// A single-threaded library has no thread pool: the stages run on the calling thread, with the same
	// bits with the sequential scheduler as with none.
	btSetTaskScheduler(0);
	const std::vector<uint64_t> reference = runScene();
	btSetTaskScheduler(btGetSequentialTaskScheduler());
	EXPECT_EQ(runScene(), reference);
	btSetTaskScheduler(0);
#endif
}

namespace
{
void mixBytes(uint64_t& h, const void* data, size_t size)
{
	const unsigned char* bytes = static_cast<const unsigned char*>(data);
	for (size_t i = 0; i < size; ++i) h = (h ^ bytes[i]) * 1099511628211ull;
}

// SoftDemo-like scenes at once, each starting in contact so that every stage runs from the first steps:
// a 40 x 40 cloth draped on a static sphere (substeps; its node passes, pose matching and link constants
// in chunks), three gas balls on the ground, two ropes holding one dynamic box and a rope anchored to a
// static post, two VF_SS balls resting one on the other (soft-soft contact), two cluster balls one on the
// other (CL_RS, CL_SS), and a cluster ball joined to a dynamic box that a rope also holds (a joint). Returns
// the hash of every soft body's nodes and every rigid body's pose, after kSteps steps on the current
// scheduler; groups, when given, gets the last step's solve groups.
uint64_t runGroupScene(caliber::SoftSolveGroups* groups = 0)
{
	SoftTestWorld w;
	w.addGround();
	std::vector<btRigidBody*> rigids;
	w.addRigid(0, btVector3(0, 1, 0), w.shape<btSphereShape>(btScalar(1)));
	btSoftBody* cloth =
	    w.addSoft(btSoftBodyHelpers::CreatePatch(w.info(), btVector3(-2, btScalar(2.05), -2), btVector3(2, btScalar(2.05), -2),
	                                             btVector3(-2, btScalar(2.05), 2), btVector3(2, btScalar(2.05), 2), 40, 40, 0, true));
	cloth->setTotalMass(2);
	cloth->m_cfg.piterations = 4;
	cloth->m_cfg.kDF = btScalar(0.5);
	cloth->setPose(false, true);
	cloth->m_cfg.kMT = btScalar(0.02);
	for (int i = 0; i < 3; ++i)
	{
		btSoftBody* ball = w.addSoft(
		    btSoftBodyHelpers::CreateEllipsoid(w.info(), btVector3(btScalar(4 + 1.2 * i), btScalar(0.55), 0), btVector3(0.5, 0.5, 0.5), 64));
		ball->setTotalMass(1, true);
		ball->m_cfg.kPR = 100;
		ball->m_cfg.piterations = 2;
	}
	btCollisionShape* box = w.shape<btBoxShape>(btVector3(0.2, 0.2, 0.2));
	rigids.push_back(w.addRigid(1, btVector3(-5, 2, 0), box));
	for (int i = 0; i < 2; ++i)
	{
		btSoftBody* rope = w.addSoft(btSoftBodyHelpers::CreateRope(
		    w.info(), btVector3(btScalar(-5.5 + i), 4, 0), btVector3(btScalar(-5.2 + 0.4 * i), btScalar(2.2), 0), 12, 1));
		rope->setTotalMass(btScalar(0.2));
		rope->m_cfg.piterations = 4;
		rope->appendAnchor(rope->m_nodes.size() - 1, rigids[0]);
	}
	btRigidBody* post = w.addRigid(0, btVector3(-8, 4, 0), box);
	btSoftBody* hung =
	    w.addSoft(btSoftBodyHelpers::CreateRope(w.info(), btVector3(-8, btScalar(3.8), 0), btVector3(-7, 2, 0), 12, 0));
	hung->setTotalMass(btScalar(0.2));
	hung->appendAnchor(0, post);
	for (int i = 0; i < 2; ++i)
	{
		btSoftBody* ball = w.addSoft(
		    btSoftBodyHelpers::CreateEllipsoid(w.info(), btVector3(0, btScalar(0.5 + 1.02 * i), 5), btVector3(0.5, 0.5, 0.5), 64));
		ball->setTotalMass(1, true);
		ball->m_cfg.kPR = 100;
		ball->m_cfg.collisions |= btSoftBody::fCollision::VF_SS;
	}
	for (int i = 0; i < 2; ++i)
	{
		btSoftBody* ball = w.addSoft(btSoftBodyHelpers::CreateEllipsoid(
		    w.info(), btVector3(btScalar(5 + 0.3 * i), btScalar(1 + 2.02 * i), 5), btVector3(1, 1, 1), 96));
		ball->setTotalMass(1, true);
		ball->m_cfg.kPR = 100;
		ball->m_cfg.collisions = btSoftBody::fCollision::CL_RS | btSoftBody::fCollision::CL_SS;
		ball->generateClusters(8);
	}
	rigids.push_back(w.addRigid(1, btVector3(9, 3, -4), box));
	btSoftBody* joined =
	    w.addSoft(btSoftBodyHelpers::CreateEllipsoid(w.info(), btVector3(9, 1, -4), btVector3(0.6, 0.6, 0.6), 64));
	joined->setTotalMass(1, true);
	joined->m_cfg.kPR = 50;
	joined->m_cfg.collisions = btSoftBody::fCollision::CL_RS;
	joined->generateClusters(1);
	btSoftBody::LJoint::Specs specs;
	specs.position = btVector3(9, btScalar(1.8), -4);
	joined->appendLinearJoint(specs, btSoftBody::Body(rigids[1]));
	btSoftBody* holder =
	    w.addSoft(btSoftBodyHelpers::CreateRope(w.info(), btVector3(9, 6, -4), btVector3(9, btScalar(3.2), -4), 12, 1));
	holder->setTotalMass(btScalar(0.2));
	holder->appendAnchor(holder->m_nodes.size() - 1, rigids[1]);
	w.step(kSteps);
	uint64_t h = 1469598103934665603ull;
	btSoftBodyArray& softs = w.world().getSoftBodyArray();
	for (int i = 0; i < softs.size(); ++i)
		for (int k = 0; k < softs[i]->m_nodes.size(); ++k) mixBytes(h, &softs[i]->m_nodes[k].m_x, sizeof(btVector3));
	for (const btRigidBody* r : rigids) mixBytes(h, &r->getWorldTransform(), sizeof(btTransform));
	// The contacts that join bodies were found: the VF_SS balls' and the cluster balls' (of the last step).
	EXPECT_GT(softs[7]->m_scontacts.size() + softs[8]->m_scontacts.size(), 0);
	EXPECT_GT(caliber::clusterState(*softs[9]).contacts.size() + caliber::clusterState(*softs[10]).contacts.size(), 0);
	if (groups)
	{
		std::vector<char> solve(softs.size(), 1);
		caliber::findSoftSolveGroups(&softs[0], solve.data(), softs.size(), *groups);
	}
	return h;
}
}  // namespace

TEST(SoftBodyThreads, SolveGroupsGiveTheBitsOfOneThreadAtAnyThreadCountAndSplit)
{
	btSetTaskScheduler(0);
	caliber::SoftSolveGroups groups;
	const uint64_t reference = runGroupScene(&groups);
	// The scene has groups of one body and of several, so several groups run at once: the cloth, the three
	// gas balls and the post's rope alone; the box's two ropes; the VF_SS balls; the cluster balls; the
	// joined ball with the rope that holds its box.
	ASSERT_EQ(groups.groupCount(), 9);
	const int expected[9][3] = {{0, -1, -1}, {1, -1, -1}, {2, -1, -1}, {3, -1, -1}, {4, 5, -1},
	                            {6, -1, -1}, {7, 8, -1},  {9, 10, -1}, {11, 12, -1}};
	for (int g = 0; g < 9; ++g)
	{
		const int size = expected[g][1] < 0 ? 1 : 2;
		ASSERT_EQ(groups.starts[g + 1] - groups.starts[g], size) << "group " << g;
		for (int k = 0; k < size; ++k) EXPECT_EQ(groups.members[groups.starts[g] + k], expected[g][k]) << "group " << g;
	}
#if defined(BT_THREADSAFE) && BT_THREADSAFE
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	ASSERT_NE(pool.get(), nullptr);
	for (int threads : {1, 2, 3, 4, 8})
	{
		pool->setNumThreads(threads);
		btSetTaskScheduler(pool.get());
		EXPECT_EQ(runGroupScene(), reference) << threads << " threads";
		btSetTaskScheduler(0);
	}
#endif
	UnevenSplitScheduler uneven;
	btSetTaskScheduler(&uneven);
	EXPECT_EQ(runGroupScene(), reference) << "uneven splits";
	btSetTaskScheduler(0);
}

namespace
{
// The node and face normals of a body, hashed.
uint64_t hashNormals(const btSoftBody& b)
{
	uint64_t h = 1469598103934665603ull;
	for (int i = 0; i < b.m_nodes.size(); ++i) mixBytes(h, &b.m_nodes[i].m_n, sizeof(btVector3));
	for (int i = 0; i < b.m_faces.size(); ++i) mixBytes(h, &b.m_faces[i].m_normal, sizeof(btVector3));
	return h;
}

// updateNormals on the current scheduler, against the same on the calling thread alone.
void expectSerialNormals(btSoftBody& b, const char* what)
{
	b.updateNormals();
	const uint64_t threaded = hashNormals(b);
	btITaskScheduler* scheduler = btGetTaskScheduler();
	btSetTaskScheduler(0);
	ASSERT_FALSE(caliber::normalsOnThreads(b));
	b.updateNormals();
	EXPECT_EQ(threaded, hashNormals(b)) << what;
	btSetTaskScheduler(scheduler);
}
}  // namespace

TEST(SoftBodyThreads, NormalsOnThreadsHaveTheBitsOfOneThread)
{
	SoftTestWorld w;
	btSoftBody* cloth = w.addSoft(btSoftBodyHelpers::CreatePatch(w.info(), btVector3(-2, 1, -2), btVector3(2, 1, -2),
	                                                             btVector3(-2, 1, 2), btVector3(2, 1, 2), 40, 40, 0, true),
	                              false);
	btSoftBody* other = w.addSoft(btSoftBodyHelpers::CreateRope(w.info(), btVector3(5, 1, 0), btVector3(6, 1, 0), 3, 0), false);
	// A crumpled cloth (3042 faces), so that every node's normal is a sum of different faces' normals.
	for (int i = 0; i < cloth->m_nodes.size(); ++i)
		cloth->m_nodes[i].m_x += btVector3(btSin(btScalar(i)), btSin(btScalar(i * 7 + 1)), btSin(btScalar(i * 13 + 2))) * btScalar(0.05);
	std::vector<std::unique_ptr<btITaskScheduler>> schedulers;
#if defined(BT_THREADSAFE) && BT_THREADSAFE
	schedulers.emplace_back(btCreateDefaultTaskScheduler());
	ASSERT_NE(schedulers.back().get(), nullptr);
	schedulers.back()->setNumThreads(2);
#endif
	schedulers.emplace_back(new UnevenSplitScheduler());
	for (const auto& scheduler : schedulers)
	{
		btSetTaskScheduler(scheduler.get());
		ASSERT_TRUE(caliber::normalsOnThreads(*cloth)) << scheduler->getName();  // the threaded path runs
		expectSerialNormals(*cloth, "crumpled");
		// A face turned over (two nodes swapped) and the nodes moved: the node-to-face lists are rebuilt.
		std::swap(cloth->m_faces[5].m_n[0], cloth->m_faces[5].m_n[1]);
		for (int i = 0; i < cloth->m_nodes.size(); ++i) cloth->m_nodes[i].m_x.setY(cloth->m_nodes[i].m_x.y() * btScalar(1.5));
		expectSerialNormals(*cloth, "a face turned over");
		// A face added: one more face, and three nodes in one more face each.
		cloth->appendFace(0, 41, 82);
		expectSerialNormals(*cloth, "a face added");
		// A face pointed by hand at another body's node: no lists can be built, the nodes' sums are made as
		// one thread makes them (the other node's normal included).
		btSoftBody::Node* kept = cloth->m_faces[7].m_n[2];
		cloth->m_faces[7].m_n[2] = &other->m_nodes[1];
		expectSerialNormals(*cloth, "a face on another body's node");
		cloth->m_faces[7].m_n[2] = kept;
		btSetTaskScheduler(0);
	}
}

namespace
{
// A cloth dropped on four dynamic boxes that stand on a static ground, with a rope over one of them and a
// small pile of rigid boxes beside: the soft bodies have pairs with several rigid objects each, among many
// rigid pairs. Stepped with dispatcherMt (grain of one pair, so the pairs spread over many chunks) or the
// plain dispatcher; the hashes of every node and rigid state.
uint64_t runDispatcherScene(bool dispatcherMt)
{
	btSoftBodyRigidBodyCollisionConfiguration configuration;
	std::unique_ptr<btCollisionDispatcher> dispatcher(dispatcherMt ? new btCollisionDispatcherMt(&configuration, 1)
	                                                                : new btCollisionDispatcher(&configuration));
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btSoftRigidDynamicsWorld world(dispatcher.get(), &broadphase, &solver, &configuration);
	const btVector3 gravity(0, -10, 0);
	world.setGravity(gravity);
	world.getWorldInfo().m_gravity = gravity;
	btBoxShape ground(btVector3(20, 1, 20));
	btBoxShape box(btVector3(btScalar(0.4), btScalar(0.4), btScalar(0.4)));
	std::vector<std::unique_ptr<btRigidBody>> bodies;
	const auto addBox = [&](btScalar mass, btCollisionShape* shape, const btVector3& at) {
		btVector3 inertia(0, 0, 0);
		if (mass > 0) shape->calculateLocalInertia(mass, inertia);
		btRigidBody::btRigidBodyConstructionInfo info(mass, 0, shape, inertia);
		info.m_startWorldTransform.setIdentity();
		info.m_startWorldTransform.setOrigin(at);
		bodies.emplace_back(new btRigidBody(info));
		world.addRigidBody(bodies.back().get());
	};
	addBox(0, &ground, btVector3(0, -1, 0));
	for (int i = 0; i < 4; ++i) addBox(1, &box, btVector3(btScalar(i % 2) * 2 - 1, btScalar(0.4), btScalar(i / 2) * 2 - 1));
	for (int i = 0; i < 8; ++i) addBox(1, &box, btVector3(6 + btScalar(i % 2), btScalar(0.4) + btScalar(i / 2) * btScalar(0.81), 0));
	btSoftBody* cloth = btSoftBodyHelpers::CreatePatch(world.getWorldInfo(), btVector3(-2, 1.2, -2), btVector3(2, 1.2, -2),
	                                                   btVector3(-2, 1.2, 2), btVector3(2, 1.2, 2), 17, 17, 0, true);
	cloth->setTotalMass(1);
	world.addSoftBody(cloth);
	btSoftBody* rope = btSoftBodyHelpers::CreateRope(world.getWorldInfo(), btVector3(-2, 1.5, -1), btVector3(2, 1.5, -1), 16, 0);
	rope->setTotalMass(btScalar(0.2));
	world.addSoftBody(rope);
	for (int i = 0; i < 30; ++i) world.stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
	// The soft bodies met the boxes (the cloth rests on them).
	EXPECT_GT(cloth->m_rcontacts.size(), 0);
	uint64_t h = hashNodes(*cloth) ^ (hashNodes(*rope) * 31);
	for (const auto& body : bodies)
	{
		const btTransform& t = body->getWorldTransform();
		const btVector3 values[] = {t.getOrigin(), t.getBasis()[0], t.getBasis()[1], t.getBasis()[2],
		                            body->getLinearVelocity(), body->getAngularVelocity()};
		for (const btVector3& v : values) mixBytes(h, &v.x(), 3 * sizeof(btScalar));
	}
	world.removeSoftBody(rope);
	world.removeSoftBody(cloth);
	delete rope;
	delete cloth;
	for (const auto& body : bodies) world.removeRigidBody(body.get());
	return h;
}
}  // namespace

// btCollisionDispatcherMt runs a soft body's pairs on the calling thread after the other pairs (each writes
// the body's contact lists): the same bits as the plain dispatcher, at any thread count and split.
TEST(SoftBodyThreads, DispatcherMtGivesThePlainDispatchersBitsWithSoftBodies)
{
	btSetTaskScheduler(0);
	const uint64_t reference = runDispatcherScene(false);
	std::vector<std::unique_ptr<btITaskScheduler>> schedulers;
#if defined(BT_THREADSAFE) && BT_THREADSAFE
	for (int threads : {2, 4})
	{
		schedulers.emplace_back(btCreateDefaultTaskScheduler());
		ASSERT_NE(schedulers.back().get(), nullptr);
		schedulers.back()->setNumThreads(threads);
	}
#endif
	schedulers.emplace_back(new UnevenSplitScheduler());
	for (const auto& scheduler : schedulers)
	{
		btSetTaskScheduler(scheduler.get());
		EXPECT_EQ(runDispatcherScene(true), reference) << scheduler->getName() << " " << scheduler->getNumThreads();
		btSetTaskScheduler(0);
	}
}
