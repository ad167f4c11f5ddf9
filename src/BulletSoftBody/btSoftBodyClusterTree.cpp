// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The cluster tree (btSoftBody::m_cdbvt, as in Bullet): one leaf per colliding cluster, so that the
// cluster contacts (btSoftBodyClusterCollision.cpp) visit only the clusters near an object or another
// cluster instead of every cluster. The leaves are fat boxes; the callers keep their exact box tests and
// get the candidates in index order, so the contacts found, and their order, are those of a scan of all
// clusters (the same bits).

#include <functional>

#include "btSoftBodyClusters.h"

namespace
{
bool inTree(const btSoftBody::Cluster& c) { return c.m_collide && c.m_nodes.size() > 0; }

// The cluster's nodes' box grown by grow on every side.
btDbvtVolume nodesVolume(const btSoftBody::Cluster& c, btScalar grow)
{
	btVector3 lo = c.m_nodes[0]->m_x, hi = lo;
	for (int j = 1; j < c.m_nodes.size(); ++j)
	{
		lo.setMin(c.m_nodes[j]->m_x);
		hi.setMax(c.m_nodes[j]->m_x);
	}
	const btVector3 g(grow, grow, grow);
	return btDbvtVolume::FromMM(lo - g, hi + g);
}

struct Collect : btDbvt::ICollide
{
	btAlignedObjectArray<int>* out;
	void Process(const btDbvtNode* leaf) override
	{
		out->push_back(static_cast<const btSoftBody::Cluster*>(leaf->data)->m_clusterIndex);
	}
};
}  // namespace

btScalar caliber::clusterTreeGrow(const btSoftBody& body)
{
	// The widest box a cluster query tests: the node box grown by the margin plus a quarter of it (the
	// soft-soft contacts' reach and thickness, btSoftBodyClusterCollision.cpp).
	const btScalar margin = body.getCollisionShape() ? body.getCollisionShape()->getMargin() : btScalar(0);
	return margin * btScalar(1.25);
}

void caliber::updateClusterTree(btSoftBody& body)
{
	btDbvt& tree = body.m_cdbvt;
	// Clusters made, released or switched in or out of collision since the last update: rebuild.
	int wanted = 0;
	bool rebuild = false;
	for (int i = 0; i < body.m_clusters.size(); ++i)
	{
		const btSoftBody::Cluster& c = *body.m_clusters[i];
		if (inTree(c))
		{
			++wanted;
			rebuild = rebuild || !c.m_leaf;
		}
		else
			rebuild = rebuild || c.m_leaf;
	}
	if (rebuild || wanted != tree.m_leaves)
	{
		tree.clear();
		for (int i = 0; i < body.m_clusters.size(); ++i) body.m_clusters[i]->m_leaf = 0;
	}
	const btScalar grow = clusterTreeGrow(body);
	const btScalar slack = grow * btScalar(0.25);  // a leaf moves only when its cluster left its fat box
	for (int i = 0; i < body.m_clusters.size(); ++i)
	{
		btSoftBody::Cluster& c = *body.m_clusters[i];
		if (!inTree(c)) continue;
		btDbvtVolume v = nodesVolume(c, grow);
		if (!c.m_leaf)
			c.m_leaf = tree.insert(btDbvtVolume::FromMM(v.Mins() - btVector3(slack, slack, slack),
			                                            v.Maxs() + btVector3(slack, slack, slack)),
			                       &c);
		else
			tree.update(c.m_leaf, v, slack);
	}
}

void caliber::clustersNear(const btSoftBody& body, const btVector3& lo, const btVector3& hi,
                           btAlignedObjectArray<int>& out)
{
	out.resize(0);
	if (body.m_cdbvt.empty()) return;
	Collect collect;
	collect.out = &out;
	body.m_cdbvt.collideTV(body.m_cdbvt.m_root, btDbvtVolume::FromMM(lo, hi), collect);
	out.quickSort(std::less<int>());
}

void caliber::removeClusterLeaf(btSoftBody& body, btSoftBody::Cluster& c)
{
	if (!c.m_leaf) return;
	body.m_cdbvt.remove(c.m_leaf);
	c.m_leaf = 0;
}
