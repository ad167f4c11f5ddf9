// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The cluster tree (btSoftBody::m_cdbvt, src/BulletSoftBody/btSoftBodyClusterTree.cpp): its queries find
// every cluster a scan of all clusters finds (so cluster contacts are the same with it), cull the far
// ones, and follow clusters made, released and moved.

#include <gtest/gtest.h>

#include <set>

#include "BulletSoftBody/btSoftBodyClusters.h"
#include "SoftBodyTestUtil.h"

using caliber_test::SoftTestWorld;

namespace
{
btSoftBody* clusteredBall(SoftTestWorld& w, const btVector3& centre, int clusters)
{
	btSoftBody* b = btSoftBodyHelpers::CreateEllipsoid(w.info(), centre, btVector3(1, 1, 1), 128);
	b->setTotalMass(1, true);
	b->m_cfg.kPR = 100;
	b->m_cfg.collisions = btSoftBody::fCollision::CL_RS | btSoftBody::fCollision::CL_SS;
	b->generateClusters(clusters);
	return w.addSoft(b);
}

// The clusters a scan of all finds: those that collide and whose nodes' box grown by grow meets [lo, hi].
std::set<int> scan(const btSoftBody& b, const btVector3& lo, const btVector3& hi, btScalar grow)
{
	std::set<int> found;
	for (int i = 0; i < b.m_clusters.size(); ++i)
	{
		const btSoftBody::Cluster& c = *b.m_clusters[i];
		if (!c.m_collide || c.m_nodes.size() == 0) continue;
		btVector3 clo = c.m_nodes[0]->m_x, chi = clo;
		for (int j = 1; j < c.m_nodes.size(); ++j)
		{
			clo.setMin(c.m_nodes[j]->m_x);
			chi.setMax(c.m_nodes[j]->m_x);
		}
		const btVector3 g(grow, grow, grow);
		clo -= g;
		chi += g;
		if (clo.x() <= hi.x() && chi.x() >= lo.x() && clo.y() <= hi.y() && chi.y() >= lo.y() && clo.z() <= hi.z() &&
		    chi.z() >= lo.z())
			found.insert(i);
	}
	return found;
}

// Checks that the tree's answer for [lo, hi] holds every cluster the scan finds, in ascending order
// without repeats; returns how many it gave.
int checkQuery(const btSoftBody& b, const btVector3& lo, const btVector3& hi)
{
	btAlignedObjectArray<int> near;
	caliber::clustersNear(b, lo, hi, near);
	for (int k = 1; k < near.size(); ++k) EXPECT_LT(near[k - 1], near[k]);
	std::set<int> got;
	for (int k = 0; k < near.size(); ++k) got.insert(near[k]);
	for (int i : scan(b, lo, hi, caliber::clusterTreeGrow(b))) EXPECT_TRUE(got.count(i)) << "cluster " << i;
	return near.size();
}

// Every colliding cluster has a leaf whose data is that cluster, and the tree has no other leaves.
void checkLeaves(const btSoftBody& b)
{
	int colliding = 0;
	for (int i = 0; i < b.m_clusters.size(); ++i)
	{
		const btSoftBody::Cluster& c = *b.m_clusters[i];
		if (!c.m_collide || c.m_nodes.size() == 0) continue;
		++colliding;
		ASSERT_NE(c.m_leaf, nullptr);
		EXPECT_EQ(c.m_leaf->data, &c);
	}
	EXPECT_EQ(b.m_cdbvt.m_leaves, colliding);
}
}  // namespace

TEST(SoftBodyClusterTree, QueriesFindEveryClusterAScanFindsAndCullTheFarOnes)
{
	SoftTestWorld w;
	w.addGround();
	btSoftBody* b = clusteredBall(w, btVector3(0, btScalar(1.6), 0), 32);
	btScalar fewest = BT_LARGE_FLOAT;
	for (int frame = 0; frame < 30; ++frame)  // falling, landing, squashed: the leaves follow the clusters
	{
		w.step(1);
		checkLeaves(*b);
		btVector3 lo, hi;
		b->getAabb(lo, hi);
		const btVector3 size = hi - lo;
		// Boxes of a tenth of the body's size along a diagonal through it, and the whole body.
		for (int k = 0; k <= 10; ++k)
		{
			const btVector3 at = lo + size * (btScalar(k) / 10);
			fewest = btMin(fewest, btScalar(checkQuery(*b, at - size / 20, at + size / 20)));
		}
		EXPECT_EQ(checkQuery(*b, lo, hi), b->m_clusters.size());
	}
	// A box at one end of the body meets a few of its 32 clusters, not all.
	EXPECT_LT(fewest, 16);
}

TEST(SoftBodyClusterTree, FollowsClustersMadeReleasedAndSwitchedOff)
{
	SoftTestWorld w;
	btSoftBody* b = clusteredBall(w, btVector3(0, 3, 0), 16);
	w.step(1);
	checkLeaves(*b);
	b->releaseCluster(3);  // its leaf leaves the tree at once: no leaf refers to a released cluster
	EXPECT_EQ(b->m_cdbvt.m_leaves, 15);
	checkLeaves(*b);
	b->generateClusters(8);
	w.step(1);
	checkLeaves(*b);
	b->m_clusters[2]->m_collide = false;
	w.step(1);
	checkLeaves(*b);
	btVector3 lo, hi;
	b->getAabb(lo, hi);
	EXPECT_EQ(checkQuery(*b, lo, hi), 7);
	b->releaseClusters();
	EXPECT_EQ(b->m_cdbvt.m_leaves, 0);
	w.step(1);
	EXPECT_TRUE(b->m_cdbvt.empty());
}

TEST(SoftBodyClusterTree, ContactsAreTheSameAsWithoutTheTree)
{
	// Two balls of 24 clusters pressed together: the contacts found through the tree equal those of a scan
	// of every pair of clusters (collideClustersWithClusters run on bodies whose trees hold every cluster
	// under one huge box: the tree then culls nothing).
	SoftTestWorld w(btVector3(0, 0, 0));
	btSoftBody* a = clusteredBall(w, btVector3(0, 0, 0), 24);
	btSoftBody* b = clusteredBall(w, btVector3(1.9, 0.3, 0), 24);
	w.step(1);
	caliber::ClusterState& state = caliber::clusterState(*a);
	state.contacts.resize(0);
	state.weights.resize(0);
	caliber::collideClustersWithClusters(*a, *b);
	const int withTree = state.contacts.size();
	ASSERT_GT(withTree, 0);
	std::vector<std::pair<const void*, const void*>> pairs;
	std::vector<btScalar> distances;
	for (int i = 0; i < withTree; ++i)
	{
		pairs.emplace_back(state.contacts[i].cluster, state.contacts[i].other);
		distances.push_back(state.contacts[i].distance);
	}
	// The same without culling: every leaf of b as big as the world.
	for (int j = 0; j < b->m_clusters.size(); ++j)
	{
		btDbvtVolume huge = btDbvtVolume::FromMM(btVector3(-1e4, -1e4, -1e4), btVector3(1e4, 1e4, 1e4));
		b->m_cdbvt.update(b->m_clusters[j]->m_leaf, huge);
	}
	btVector3 lo(-1, -1, -1), hi(1, 1, 1);
	btAlignedObjectArray<int> near;
	caliber::clustersNear(*b, lo * 1e3, hi * 1e3, near);
	ASSERT_EQ(near.size(), b->m_clusters.size());
	state.contacts.resize(0);
	state.weights.resize(0);
	caliber::collideClustersWithClusters(*a, *b);
	ASSERT_EQ(state.contacts.size(), withTree);
	for (int i = 0; i < withTree; ++i)
	{
		EXPECT_EQ(pairs[size_t(i)].first, state.contacts[i].cluster);
		EXPECT_EQ(pairs[size_t(i)].second, state.contacts[i].other);
		EXPECT_EQ(distances[size_t(i)], state.contacts[i].distance);
	}
}
