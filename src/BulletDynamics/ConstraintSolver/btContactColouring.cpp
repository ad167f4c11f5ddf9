// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The colouring of a large solve's contact manifolds (btContactColouring.h).
//
// Gauss-Seidel gives each row the impulses of the rows solved before it, so the order of the colours is
// the order in which a stack's load travels. The serial solver meets a stack's contacts in the
// dispatcher's order, which for a stack built or landed from the bottom runs mostly level by level.
// A greedy colouring in that order (each manifold the lowest colour its bodies left free) turns it
// into 0, 2, 4, ... then 1, 3, 5, ...: a box's upper contacts find free exactly the colours its lower
// ones did not take, so every other level lands in the first colours, and a sweep carries the load
// only one level before meeting the next level's contacts already solved. Pyramids then never quite
// come to rest, and their pairs keep leaving the contact cache. So the levels are found from the
// contacts and gravity, and the colours follow them: the manifolds are taken level by level from the
// bottom of each stack, and each takes the first colour, at or after the level of its lower body's
// supports, that neither body has. A box resting on four boxes then has its four supports in four
// colours of its own level, all after the colours of the level below.
#include "BulletDynamics/ConstraintSolver/btContactColouring.h"

#include <string.h>

#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "LinearMath/btScratchArray.h"

namespace
{
const int kColours = caliber::ContactColouring::kLevelColours;
static_assert(kColours == 32, "a body's colours are the bits of a uint32_t");

// count zeros (the arrays here are a body or a manifold apiece, refilled every solve).
template <class T>
void zeroScratch(btAlignedObjectArray<T>& array, int count)
{
	caliber::resizeScratch(array, count);
	if (count > 0) memset(&array[0], 0, sizeof(T) * size_t(count));
}

// The lowest and the highest set bit of a non-zero mask.
inline int lowestBit(uint32_t mask)
{
#if defined(__GNUC__)
	return __builtin_ctz(mask);
#else
	int bit = 0;
	while (!(mask & 1u)) mask >>= 1, ++bit;
	return bit;
#endif
}
inline int highestBit(uint32_t mask)
{
#if defined(__GNUC__)
	return 31 - __builtin_clz(mask);
#else
	int bit = 31;
	while (!(mask & (uint32_t(1) << bit))) --bit;
	return bit;
#endif
}

// Level u's colour. The levels go up the colours, then back down them, then up again: where a tall
// stack wraps around, the two levels that meet are neighbours in the sweep (the last colours of one
// pass and the first of the next), not its two ends, so the load still crosses them in every sweep.
inline int levelColour(int u)
{
	const int c = u & (kColours - 1);
	return ((u / kColours) & 1) ? kColours - 1 - c : c;
}

// The first level at or after level whose colour is not taken (taken has a free colour): the rest of the
// level's pass over the colours, else the next pass, which runs the other way and meets every colour.
int firstFreeLevel(int level, uint32_t taken)
{
	const uint32_t free = ~taken;
	const int passStart = level - (level & (kColours - 1)), c = levelColour(level);
	if (((level / kColours) & 1) == 0)
	{
		const uint32_t ahead = free & (~uint32_t(0) << c);  // colours c, c + 1, ... up to the pass's end
		if (ahead) return level + lowestBit(ahead) - c;
		return passStart + kColours + (kColours - 1 - highestBit(free));
	}
	const uint32_t ahead = free & ((uint32_t(2) << c) - 1u);  // colours c, c - 1, ... down to 0 (c = 31: all)
	if (ahead) return level + c - highestBit(ahead);
	return passStart + kColours + lowestBit(free);
}

// Strictly below along up, equal heights by index: a total order on the bodies, so the stacks' edges
// never close a loop (non-finite heights compare as equal and fall back to the index).
bool isBelow(const btAlignedObjectArray<btScalar>& height, int a, int b)
{
	if (height[a] < height[b]) return true;
	if (height[b] < height[a]) return false;
	return a < b;
}

int lowestFreeColour(uint32_t taken)
{
	for (int c = 0; c < kColours; ++c)
		if (!(taken & (uint32_t(1) << c))) return c;
	return kColours;
}
}  // namespace

void caliber::ContactColouring::colour(const int* ends, int stride, int numManifolds, const btSolverBody* bodies,
                                       int numBodies, int fixedBodyId, const btVector3& up)
{
	resizeScratch(m_manifoldColour, numManifolds);
	m_numColours = 0;
	if (numManifolds == 0) return;

	// Each manifold's lower and upper end (the fixed entry is below everything), and for each body the
	// bodies resting on it, in manifold order. m_depth marks the bodies that rest on another (-1).
	resizeScratch(m_height, numBodies);
	for (int b = 0; b < numBodies; ++b) m_height[b] = up.dot(bodies[b].getWorldTransform().getOrigin());
	resizeScratch(m_lower, numManifolds);
	resizeScratch(m_upper, numManifolds);
	zeroScratch(m_aboveStart, numBodies + 1);
	zeroScratch(m_depth, numBodies);
	for (int m = 0; m < numManifolds; ++m)
	{
		const int a = ends[m * stride], b = ends[m * stride + 1];
		const bool aLower = a == fixedBodyId || (b != fixedBodyId && isBelow(m_height, a, b));
		const int lower = aLower ? a : b, upper = aLower ? b : a;
		m_lower[m] = lower;
		m_upper[m] = upper;
		if (lower == fixedBodyId || upper == fixedBodyId) continue;
		++m_aboveStart[lower + 1];
		m_depth[upper] = -1;
	}
	for (int b = 0; b < numBodies; ++b) m_aboveStart[b + 1] += m_aboveStart[b];
	resizeScratch(m_above, m_aboveStart[numBodies]);
	for (int m = 0; m < numManifolds; ++m)
	{
		const int lower = m_lower[m], upper = m_upper[m];
		if (lower != fixedBodyId && upper != fixedBodyId) m_above[m_aboveStart[lower]++] = upper;
	}
	for (int b = numBodies; b > 0; --b) m_aboveStart[b] = m_aboveStart[b - 1];
	m_aboveStart[0] = 0;

	// Depths: 1 for a body that rests on no other (on the ground, or free), then breadth first up the
	// stacks, in index order. Every body is reached (the edges follow a total order, so there are no
	// loops); a body left at -1 all the same is taken as a bottom one.
	resizeScratch(m_queue, numBodies);
	int tail = 0, deepest = 1;
	for (int b = 0; b < numBodies; ++b)
		if (m_depth[b] == 0 && b != fixedBodyId)
		{
			m_depth[b] = 1;
			m_queue[tail++] = b;
		}
	for (int head = 0; head < tail; ++head)
	{
		const int b = m_queue[head];
		for (int e = m_aboveStart[b]; e < m_aboveStart[b + 1]; ++e)
		{
			const int above = m_above[e];
			if (m_depth[above] != -1) continue;
			m_depth[above] = m_depth[b] + 1;
			deepest = btMax(deepest, m_depth[above]);
			m_queue[tail++] = above;
		}
	}

	// The manifolds from the bottom up: by the depth of their higher end (a stable counting sort, so
	// a level keeps the dispatcher's order).
	zeroScratch(m_keyStart, deepest + 2);
	for (int m = 0; m < numManifolds; ++m)
	{
		const int upper = m_upper[m];
		const int key = upper == fixedBodyId ? 0 : btMax(1, m_depth[upper]);
		m_manifoldColour[m] = key;  // the key, until the colour replaces it
		++m_keyStart[key + 1];
	}
	for (int k = 0; k <= deepest; ++k) m_keyStart[k + 1] += m_keyStart[k];
	resizeScratch(m_order, numManifolds);
	for (int m = 0; m < numManifolds; ++m) m_order[m_keyStart[m_manifoldColour[m]]++] = m;

	// Each manifold takes the first level, at or after its lower body's supports' level, whose colour
	// neither of its moving bodies has (within two turns of the colours, one is free unless a body has
	// them all); its upper body's supports then reach past that level.
	zeroScratch(m_taken, numBodies);
	zeroScratch(m_supportLevel, numBodies);
	m_overflow.resize(0);
	for (int k = 0; k < numManifolds; ++k)
	{
		const int m = m_order[k];
		const int lower = m_lower[m], upper = m_upper[m];
		const bool lowerMoves = lower != fixedBodyId, upperMoves = upper != fixedBodyId;
		const uint32_t taken = (lowerMoves ? m_taken[lower] : 0u) | (upperMoves ? m_taken[upper] : 0u);
		if (taken == ~uint32_t(0))
		{
			m_overflow.push_back(m);
			continue;
		}
		const int level = firstFreeLevel(lowerMoves ? m_supportLevel[lower] : 0, taken);
		const int colour = levelColour(level);
		if (lowerMoves) m_taken[lower] |= uint32_t(1) << colour;
		if (upperMoves)
		{
			m_taken[upper] |= uint32_t(1) << colour;
			m_supportLevel[upper] = btMax(m_supportLevel[upper], level + 1);
		}
		m_manifoldColour[m] = colour;
		m_numColours = btMax(m_numColours, colour + 1);
	}

	// A body with more manifolds than colours (a platform under many boxes): its extra manifolds are
	// coloured again in rounds of fresh colours after the level colours, each the lowest free one.
	int firstColour = kColours;
	while (m_overflow.size() > 0)
	{
		for (int i = 0; i < m_overflow.size(); ++i)
		{
			const int m = m_overflow[i];
			if (m_lower[m] != fixedBodyId) m_taken[m_lower[m]] = 0;
			if (m_upper[m] != fixedBodyId) m_taken[m_upper[m]] = 0;
		}
		int left = 0;
		for (int i = 0; i < m_overflow.size(); ++i)
		{
			const int m = m_overflow[i];
			const int lower = m_lower[m], upper = m_upper[m];
			const bool lowerMoves = lower != fixedBodyId, upperMoves = upper != fixedBodyId;
			const int colour =
			    lowestFreeColour((lowerMoves ? m_taken[lower] : 0u) | (upperMoves ? m_taken[upper] : 0u));
			if (colour == kColours)
			{
				m_overflow[left++] = m;  // left <= i: nothing still to be read is overwritten
				continue;
			}
			if (lowerMoves) m_taken[lower] |= uint32_t(1) << colour;
			if (upperMoves) m_taken[upper] |= uint32_t(1) << colour;
			m_manifoldColour[m] = firstColour + colour;
			m_numColours = btMax(m_numColours, firstColour + colour + 1);
		}
		m_overflow.resize(left);
		firstColour += kColours;
	}
}

btVector3 caliber::solveUpDirection(const btSolverBody* bodies, int numBodies)
{
	for (int b = 0; b < numBodies; ++b)
	{
		const btRigidBody* body = bodies[b].m_originalBody;
		if (!body || body->getInvMass() == btScalar(0)) continue;
		const btVector3& gravity = body->getGravity();
		if (!gravity.fuzzyZero()) return -gravity;
	}
	return btVector3(0, 0, 0);
}
