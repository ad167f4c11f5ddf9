// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "btSoftBodyLinkColours.h"

#include <cstdint>
#include <vector>

#include "LinearMath/btSideTable.h"
#include "btSoftBodyLinkSweep.h"

namespace
{
// Greedy colouring: each block, in order, takes the lowest colour none of its nodes has yet. At most
// one colour per block; per node a bit set of the colours of the blocks that touch it.
void build(const btSoftBody& body, caliber::SoftLinkColours& c)
{
	const int n = body.m_nodes.size();
	const int links = body.m_links.size();
	c.blocks.resize(0);
	c.start.resize(0);
	c.start.push_back(0);
	if (links == 0 || n == 0) return;
	const btSoftBody::Node* base = &body.m_nodes[0];
	const int blockCount = (links + caliber::kLinkBlock - 1) / caliber::kLinkBlock;
	const int words = (blockCount + 63) / 64;
	std::vector<uint64_t> used(size_t(n) * size_t(words), 0);
	std::vector<uint64_t> taken(static_cast<size_t>(words));
	std::vector<int> colour(static_cast<size_t>(blockCount));
	std::vector<int> count;
	for (int b = 0; b < blockCount; ++b)
	{
		const int first = b * caliber::kLinkBlock;
		const int last = first + caliber::kLinkBlock < links ? first + caliber::kLinkBlock : links;
		for (int w = 0; w < words; ++w) taken[size_t(w)] = 0;
		for (int i = first; i < last; ++i)
			for (int e = 0; e < 2; ++e)
			{
				const uint64_t* u = &used[size_t(body.m_links[i].m_n[e] - base) * size_t(words)];
				for (int w = 0; w < words; ++w) taken[size_t(w)] |= u[w];
			}
		int k = 0;
		for (int w = 0; w < words; ++w)
			if (~taken[size_t(w)])
			{
				int bit = 0;
				while ((taken[size_t(w)] >> bit) & 1u) ++bit;
				k = w * 64 + bit;
				break;
			}
		colour[size_t(b)] = k;
		for (int i = first; i < last; ++i)
			for (int e = 0; e < 2; ++e)
				used[size_t(body.m_links[i].m_n[e] - base) * size_t(words) + size_t(k / 64)] |= uint64_t(1) << (k % 64);
		if (k >= int(count.size())) count.resize(size_t(k) + 1, 0);
		++count[size_t(k)];
	}
	for (size_t k = 0; k < count.size(); ++k) c.start.push_back(c.start[c.start.size() - 1] + count[k]);
	c.blocks.resize(blockCount);
	std::vector<int> fill(count.size());
	for (size_t k = 0; k < fill.size(); ++k) fill[k] = c.start[int(k)];
	for (int b = 0; b < blockCount; ++b) c.blocks[fill[size_t(colour[size_t(b)])]++] = b;
}
}  // namespace

caliber::SoftLinkColours& caliber::softLinkColours(btSoftBody& body, bool refresh)
{
	SoftLinkColours& c = sideTable<SoftLinkColours>().acquire(&body);
	if (!refresh && c.nodeCount == body.m_nodes.size() && c.linkCount == body.m_links.size()) return c;
	return refreshSoftLinkColours(body, packSoftLinks(body, body.m_cfg.piterations).nodeSignature);
}

caliber::SoftLinkColours& caliber::refreshSoftLinkColours(btSoftBody& body, uint64_t signature)
{
	SoftLinkColours& c = sideTable<SoftLinkColours>().acquire(&body);
	if (c.nodeCount != body.m_nodes.size() || c.linkCount != body.m_links.size() || c.signature != signature)
	{
		build(body, c);
		c.nodeCount = body.m_nodes.size();
		c.linkCount = body.m_links.size();
		c.signature = signature;
	}
	return c;
}

void caliber::releaseSoftLinkColours(const btSoftBody& body) { sideTable<SoftLinkColours>().release(&body); }
