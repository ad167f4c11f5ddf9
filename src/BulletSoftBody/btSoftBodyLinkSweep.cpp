// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "btSoftBodyLinkSweep.h"

#include <cstdint>
#include <cstring>

#include "LinearMath/btSideTable.h"
#include "btSoftBodyInternal.h"

namespace
{
// The index of node in the body's array, or -1 when the link points elsewhere (a pointer rewritten by hand:
// the sweeps then skip the link rather than write outside the array). One unsigned compare on the addresses checks both ends, so the
// index is only taken inside the array.
int nodeIndex(const btSoftBody::Node* node, uintptr_t first, uintptr_t bytes)
{
	const uintptr_t offset = uintptr_t(node) - first;
	return offset < bytes ? int(offset / sizeof(btSoftBody::Node)) : -1;
}

// The tethers' mark of a material's links (a link without a material is not inextensible to them).
unsigned inextensibleBit(const btSoftBody::Material* material, int piterations)
{
	return material && caliber::inextensibleLinks(material->m_kLST, piterations) ? 0x80000000u : 0u;
}

// Packs the links of blocks [begin, end) and fingerprints each block (the node indices only when the body
// has several blocks: one block is not coloured). Links of one material are usually stored together: its
// factor is kept.
template <bool coloured>
void packBlocks(const btSoftBody& body, caliber::SoftLinkSweep& s, int begin, int end, int piterations)
{
	const int nodeCount = body.m_nodes.size();
	const int linkCount = body.m_links.size();
	const uintptr_t first = nodeCount > 0 ? uintptr_t(&body.m_nodes[0]) : 0;
	const uintptr_t bytes = uintptr_t(nodeCount) * sizeof(btSoftBody::Node);
	const btSoftBody::Link* links = &body.m_links[0];
	caliber::SoftLinkSweep::PackedLink* packed = &s.links[0];
	const btSoftBody::Material* lastMaterial = links[begin * caliber::kLinkBlock].m_material;
	btScalar factor = caliber::complianceFactor(lastMaterial ? lastMaterial->m_kLST : btScalar(1), piterations);
	unsigned inextensible = inextensibleBit(lastMaterial, piterations);
	for (int k = begin; k < end; ++k)
	{
		uint64_t nodes = 1469598103934665603ull;
		unsigned tethered = 2166136261u;
		const int last = btMin((k + 1) * caliber::kLinkBlock, linkCount);
		for (int i = k * caliber::kLinkBlock; i < last; ++i)
		{
			const btSoftBody::Link& l = links[i];
			if (l.m_material != lastMaterial)
			{
				lastMaterial = l.m_material;
				factor = caliber::complianceFactor(l.m_material ? l.m_material->m_kLST : btScalar(1), piterations);
				inextensible = inextensibleBit(l.m_material, piterations);
			}
			caliber::SoftLinkSweep::PackedLink& p = packed[i];
			p.a = nodeIndex(l.m_n[0], first, bytes);
			p.b = nodeIndex(l.m_n[1], first, bytes);
			p.restLength = l.m_rl;
			p.compliance = factor < 0 ? btScalar(-1) : factor * l.m_c0;
			if (p.a < 0 || p.b < 0)
			{
				btAssert(!"btSoftBody: a link's node is not one of the body's nodes");
				p.a = p.b = 0;
				p.compliance = -1;
			}
			if (coloured) nodes = (nodes ^ (uint64_t(uint32_t(p.a)) * 3u + uint64_t(uint32_t(p.b)))) * 1099511628211ull;
			unsigned bits = 0;
			const float rl = float(l.m_rl);
			std::memcpy(&bits, &rl, sizeof bits);
			tethered = (tethered ^ (bits ^ inextensible ^ 1u)) * 16777619u;
		}
		s.blocks[k].nodes = nodes;
		s.blocks[k].tethered = tethered;
	}
}

// Links [begin, end) in index order. The flags are template arguments and every input a local, so that the
// loop keeps them in registers (the node writes could alias a member).
template <bool first, bool keep>
void sweepLinks(const caliber::SoftLinkSweep::PackedLink* links, btScalar* multipliers, btSoftBody::Node* nodes,
                int begin, int end, btScalar idt2)
{
	for (int i = begin; i < end; ++i)
	{
		const caliber::SoftLinkSweep::PackedLink& l = links[i];
		// Off or between fixed nodes for the whole step: no sweep reads its multiplier.
		if (l.compliance < 0) continue;
		btSoftBody::Node& a = nodes[l.a];
		btSoftBody::Node& b = nodes[l.b];
		const btScalar w = a.m_im + b.m_im;
		if (w <= 0) continue;
		const btScalar lambda = first ? btScalar(0) : multipliers[i];
		const btVector3 d = b.m_x - a.m_x;
		const btScalar len = d.length();
		if (len <= SIMD_EPSILON)
		{
			if (keep) multipliers[i] = lambda;  // no direction this sweep: the multiplier stays
			continue;
		}
		const btScalar c = len - l.restLength;
		const btScalar alpha = l.compliance * idt2;
		const btScalar dlambda = (-c - alpha * lambda) / (w + alpha);
		if (keep) multipliers[i] = lambda + dlambda;
		const btVector3 corr = d * (dlambda / len);
		a.m_x -= corr * a.m_im;
		b.m_x += corr * b.m_im;
	}
}

// Blocks of links of one colour (no two blocks share a node; btSoftBodyLinkColours.h), blocks[begin, end),
// each block's links in index order: any split of the blocks over threads gives the bits of one thread.
struct Sweep : btIParallelForBody
{
	const caliber::SoftLinkSweep::PackedLink* links;
	btScalar* multipliers;
	btSoftBody::Node* nodes;
	const int* blocks;
	int linkCount;
	btScalar idt2;
	bool first;  // the (sub)step's first sweep: the multipliers start at zero
	bool keep;   // a later sweep of the (sub)step reads the multipliers
	void forLoop(int begin, int end) const override
	{
		for (int k = begin; k < end; ++k)
		{
			const int firstLink = blocks[k] * caliber::kLinkBlock;
			const int lastLink = btMin(firstLink + caliber::kLinkBlock, linkCount);
			if (first)
			{
				if (keep)
					sweepLinks<true, true>(links, multipliers, nodes, firstLink, lastLink, idt2);
				else
					sweepLinks<true, false>(links, multipliers, nodes, firstLink, lastLink, idt2);
			}
			else if (keep)
				sweepLinks<false, true>(links, multipliers, nodes, firstLink, lastLink, idt2);
			else
				sweepLinks<false, false>(links, multipliers, nodes, firstLink, lastLink, idt2);
		}
	}
};
}  // namespace

bool caliber::inextensibleLinks(btScalar kLST, int piterations)
{
	const btScalar k = btClamped(kLST, btScalar(0), btScalar(1));
	return 1 - btPow(1 - k, btScalar(btMax(piterations, 1))) >= btScalar(0.99);
}

caliber::SoftLinkSweep& caliber::packSoftLinks(btSoftBody& body, int piterations)
{
	SoftLinkSweep& s = sideTable<SoftLinkSweep>().acquire(&body);
	const int count = body.m_links.size();
	const int blockCount = (count + kLinkBlock - 1) / kLinkBlock;
	s.links.resize(count);
	s.blocks.resize(blockCount);
	s.unsolved = true;
	// A block per task: each writes its own links and fingerprint.
	struct Pack : btIParallelForBody
	{
		const btSoftBody* body;
		SoftLinkSweep* sweep;
		int piterations;
		void forLoop(int begin, int end) const override { packBlocks<true>(*body, *sweep, begin, end, piterations); }
	};
	Pack pack;
	pack.body = &body;
	pack.sweep = &s;
	pack.piterations = piterations;
	if (blockCount == 1)
		packBlocks<false>(body, s, 0, 1, piterations);
	else if (blockCount > 1)
		btParallelFor(0, blockCount, 1, pack);
	// The blocks' fingerprints joined in block order.
	s.nodeSignature = 1469598103934665603ull;
	s.tetherSignature = 2166136261u;
	for (int k = 0; k < blockCount; ++k)
	{
		s.nodeSignature = (s.nodeSignature ^ s.blocks[k].nodes) * 1099511628211ull;
		s.tetherSignature = (s.tetherSignature ^ s.blocks[k].tethered) * 16777619u;
	}
	return s;
}

caliber::SoftLinkSweep& caliber::startSoftLinkStep(btSoftBody& body, int piterations)
{
	SoftLinkSweep& s = sideTable<SoftLinkSweep>().acquire(&body);
	if (!s.unsolved || s.links.size() != body.m_links.size()) packSoftLinks(body, piterations);
	s.unsolved = false;
	return s;
}

void caliber::solveSoftLinks(btSoftBody& body, SoftLinkSweep& s, btScalar dt, const SoftLinkColours* colours,
                             bool first, bool last)
{
	const int links = s.links.size();
	if (links == 0 || links != body.m_links.size() || body.m_nodes.size() == 0) return;
	Sweep sweep;
	sweep.links = &s.links[0];
	sweep.keep = !last;
	if (sweep.keep && s.multipliers.size() != links) s.multipliers.resize(links);
	sweep.multipliers = s.multipliers.size() == links ? &s.multipliers[0] : 0;
	// A sweep that neither starts from zero nor may write reads what an earlier sweep kept.
	sweep.first = first || !sweep.multipliers;
	sweep.nodes = &body.m_nodes[0];
	sweep.linkCount = links;
	sweep.idt2 = btScalar(1) / (dt * dt);
	if (!colours || links <= kLinkBlock)
	{
		const int onlyBlock = 0;
		sweep.blocks = &onlyBlock;
		sweep.forLoop(0, 1);
		return;
	}
	if (colours->blocks.size() != (links + kLinkBlock - 1) / kLinkBlock) return;
	sweep.blocks = &colours->blocks[0];
	for (int c = 0; c + 1 < colours->start.size(); ++c)
	{
		const int begin = colours->start[c], end = colours->start[c + 1];
		if (end - begin > 1)
			btParallelFor(begin, end, 1, sweep);
		else
			sweep.forLoop(begin, end);
	}
}

void caliber::releaseSoftLinkSweep(const btSoftBody& body) { sideTable<SoftLinkSweep>().release(&body); }
