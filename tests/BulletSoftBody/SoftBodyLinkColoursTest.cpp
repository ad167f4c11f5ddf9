// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The link sweeps' colouring (src/BulletSoftBody/btSoftBodyLinkColours.h): blocks of consecutive links,
// no two blocks of a colour sharing a node, so a colour's blocks can run on any threads with the bits
// of one (SoftBodyThreadsTest checks the bits).

#include <gtest/gtest.h>

#include <memory>
#include <set>
#include <vector>

#include "BulletSoftBody/btSoftBodyLinkColours.h"
#include "SoftBodyTestUtil.h"

using caliber::kLinkBlock;
using caliber::SoftLinkColours;

namespace
{
// Checks that colours lists every block once and that the blocks of a colour share no node; returns
// the largest number of blocks in one colour.
int checkColouring(const btSoftBody& body, const SoftLinkColours& colours)
{
	const int links = body.m_links.size();
	const int blockCount = (links + kLinkBlock - 1) / kLinkBlock;
	EXPECT_EQ(colours.blocks.size(), blockCount);
	std::vector<int> seen(size_t(blockCount), 0);
	int widest = 0;
	for (int c = 0; c + 1 < colours.start.size(); ++c)
	{
		std::set<const btSoftBody::Node*> nodes;
		widest = btMax(widest, colours.start[c + 1] - colours.start[c]);
		for (int k = colours.start[c]; k < colours.start[c + 1]; ++k)
		{
			const int b = colours.blocks[k];
			EXPECT_TRUE(b >= 0 && b < blockCount);
			if (b < 0 || b >= blockCount) continue;
			++seen[size_t(b)];
			// The nodes this block touches must be new to the colour.
			std::set<const btSoftBody::Node*> mine;
			for (int i = b * kLinkBlock; i < btMin((b + 1) * kLinkBlock, links); ++i)
				for (int e = 0; e < 2; ++e) mine.insert(body.m_links[i].m_n[e]);
			for (const btSoftBody::Node* n : mine) EXPECT_TRUE(nodes.insert(n).second) << "colour " << c;
		}
	}
	for (int b = 0; b < blockCount; ++b) EXPECT_EQ(seen[size_t(b)], 1) << "block " << b;
	return widest;
}

btSoftBody* cloth(btSoftBodyWorldInfo& info, int n)
{
	return btSoftBodyHelpers::CreatePatch(info, btVector3(-3, 4, -3), btVector3(3, 4, -3), btVector3(-3, 4, 3),
	                                      btVector3(3, 4, 3), n, n, 1 + 2, true);
}
}  // namespace

TEST(SoftBodyLinkColours, BlocksOfAColourShareNoNodeAndSeveralRunTogether)
{
	btSoftBodyWorldInfo info;
	std::unique_ptr<btSoftBody> body(cloth(info, 64));
	body->generateBendingConstraints(2, body->m_materials[0]);
	ASSERT_GT(body->m_links.size(), 8 * kLinkBlock);
	const int widest = checkColouring(*body, caliber::softLinkColours(*body));
	// A cloth made row by row: blocks a few rows apart share no node, so colours hold several blocks
	// (work for several threads).
	EXPECT_GE(widest, 2);
}

TEST(SoftBodyLinkColours, ASmallBodyIsOneBlockSweptInIndexOrder)
{
	btSoftBodyWorldInfo info;
	std::unique_ptr<btSoftBody> body(cloth(info, 10));
	ASSERT_LE(body->m_links.size(), kLinkBlock);
	const SoftLinkColours& colours = caliber::softLinkColours(*body);
	ASSERT_EQ(colours.blocks.size(), 1);
	EXPECT_EQ(colours.start.size(), 2);
}

TEST(SoftBodyLinkColours, ColouringFollowsLinksAddedOrReordered)
{
	// Links appended after a step, or shuffled by randomizeConstraints, change the blocks: the colouring
	// is rebuilt before the next solve and stays valid.
	caliber_test::SoftTestWorld w;
	btSoftBody* body = w.addSoft(cloth(w.info(), 40));
	w.step(2);
	checkColouring(*body, caliber::softLinkColours(*body, false));
	body->generateBendingConstraints(2, body->m_materials[0]);
	w.step(2);
	checkColouring(*body, caliber::softLinkColours(*body, false));
	body->randomizeConstraints();
	w.step(2);
	checkColouring(*body, caliber::softLinkColours(*body, false));
	for (int i = 0; i < body->m_nodes.size(); ++i) ASSERT_TRUE(caliber::isFinite(body->m_nodes[i].m_x));
}
