// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "btSoftBodyTethers.h"

#include <cstring>
#include <queue>
#include <utility>
#include <vector>

#include "LinearMath/btSideTable.h"
#include "btSoftBodyInternal.h"
#include "btSoftBodyLinkSweep.h"

namespace
{
// A link counts as inextensible when the body's sweeps close at least 99% of its error in a step
// (caliber::inextensibleLinks): its spring is then too stiff to matter against a tether.
// Links of one material are usually stored together: the last answer is kept.
struct InextensibleTest
{
	const btSoftBody& body;
	const btSoftBody::Material* material = 0;
	bool answer = false;

	bool operator()(const btSoftBody::Link& l)
	{
		if (l.m_material != material)
		{
			material = l.m_material;
			answer = caliber::inextensibleLinks(material ? material->m_kLST : btScalar(0), body.m_cfg.piterations);
		}
		return answer;
	}
};

// A cheap fingerprint of what the tethers depend on: which nodes are fixed, and the links' part
// (SoftLinkSweep::tetherSignature: which links are inextensible, and their rest lengths, taken by the
// step's one pass over the links). O(nodes) once per step.
unsigned fingerprint(const btSoftBody& body, unsigned linkSignature)
{
	unsigned h = 2166136261u;
	auto mix = [&h](unsigned v) { h = (h ^ v) * 16777619u; };
	for (int i = 0; i < body.m_nodes.size(); ++i) mix(body.m_nodes[i].m_im > 0 ? 1u : 2u);
	mix(linkSignature);
	return h;
}

void build(btSoftBody& body, caliber::SoftBodyTethers& t)
{
	t.tethers.resize(0);
	const int n = body.m_nodes.size();
	{
		InextensibleTest inextensible{body};
		bool all = body.m_links.size() > 0 && body.m_faces.size() > 0;
		for (int i = 0; i < body.m_links.size() && all; ++i) all = inextensible(body.m_links[i]);
		t.inextensibleSkin = all;
		t.restVolume = all ? body.getVolume() : btScalar(0);
	}
	btSoftBody::Node* base = n ? &body.m_nodes[0] : 0;
	// Adjacency over inextensible links.
	std::vector<std::vector<std::pair<int, btScalar>>> adjacent(n);
	bool anyFixed = false;
	for (int i = 0; i < n && !anyFixed; ++i) anyFixed = body.m_nodes[i].m_im <= 0;
	if (!anyFixed) return;
	InextensibleTest inextensible{body};
	for (int i = 0; i < body.m_links.size(); ++i)
	{
		const btSoftBody::Link& l = body.m_links[i];
		if (!inextensible(l)) continue;
		const int a = int(l.m_n[0] - base), b = int(l.m_n[1] - base);
		adjacent[a].emplace_back(b, l.m_rl);
		adjacent[b].emplace_back(a, l.m_rl);
	}
	// Multi-source Dijkstra from every fixed node: each node learns its nearest fixed node.
	std::vector<btScalar> distance(n, BT_LARGE_FLOAT);
	std::vector<int> source(n, -1);
	typedef std::pair<btScalar, int> Item;
	std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
	for (int i = 0; i < n; ++i)
		if (body.m_nodes[i].m_im <= 0)
		{
			distance[i] = 0;
			source[i] = i;
			queue.push(Item(btScalar(0), i));
		}
	while (!queue.empty())
	{
		const Item top = queue.top();
		queue.pop();
		if (top.first > distance[top.second]) continue;
		for (const auto& edge : adjacent[top.second])
		{
			const btScalar d = top.first + edge.second;
			if (d < distance[edge.first])
			{
				distance[edge.first] = d;
				source[edge.first] = source[top.second];
				queue.push(Item(d, edge.first));
			}
		}
	}
	for (int i = 0; i < n; ++i)
		if (body.m_nodes[i].m_im > 0 && source[i] >= 0)
		{
			caliber::SoftBodyTethers::Tether tether;
			tether.node = i;
			tether.anchor = source[i];
			tether.reach = distance[i];
			t.tethers.push_back(tether);
		}
}
}  // namespace

caliber::SoftBodyTethers& caliber::softBodyTethers(btSoftBody& body, bool refresh)
{
	if (refresh) return refreshSoftBodyTethers(body, packSoftLinks(body, body.m_cfg.piterations).tetherSignature);
	SoftBodyTethers& t = sideTable<SoftBodyTethers>().acquire(&body);
	if (t.nodeCount == body.m_nodes.size() && t.linkCount == body.m_links.size()) return t;
	return refreshSoftBodyTethers(body, packSoftLinks(body, body.m_cfg.piterations).tetherSignature);
}

caliber::SoftBodyTethers& caliber::refreshSoftBodyTethers(btSoftBody& body, unsigned linkSignature)
{
	SoftBodyTethers& t = sideTable<SoftBodyTethers>().acquire(&body);
	const unsigned signature = fingerprint(body, linkSignature);
	if (t.nodeCount != body.m_nodes.size() || t.linkCount != body.m_links.size() || t.signature != signature)
	{
		build(body, t);
		t.nodeCount = body.m_nodes.size();
		t.linkCount = body.m_links.size();
		t.signature = signature;
	}
	return t;
}

void caliber::releaseSoftBodyTethers(const btSoftBody& body) { sideTable<SoftBodyTethers>().release(&body); }

void caliber::solveTethers(btSoftBody& body, const SoftBodyTethers& t)
{
	if (t.tethers.size() == 0) return;
	// Each tether moves its own free node (one tether per node) towards a fixed node (which no tether
	// moves), so chunks of tethers on the task scheduler give the bits of one thread.
	btSoftBody::Node* nodes = &body.m_nodes[0];
	const SoftBodyTethers::Tether* tethers = &t.tethers[0];
	forEachChunk(t.tethers.size(), [nodes, tethers](int begin, int end) {
		for (int i = begin; i < end; ++i)
		{
			const SoftBodyTethers::Tether& tether = tethers[i];
			btSoftBody::Node& node = nodes[tether.node];
			const btVector3& anchor = nodes[tether.anchor].m_x;
			const btVector3 d = node.m_x - anchor;
			const btScalar len2 = d.length2();
			if (len2 <= tether.reach * tether.reach) continue;
			node.m_x = anchor + d * (tether.reach / btSqrt(len2));
		}
	});
}
