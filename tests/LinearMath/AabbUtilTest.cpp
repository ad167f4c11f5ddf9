// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btAabbUtil2.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "MathTestUtil.h"

using caliber_test::kTightTolerance;
using caliber_test::Random;

namespace
{
struct Box
{
	btVector3 min;
	btVector3 max;
};

// A box whose bounds lie on a coarse integer grid, so that touching faces, edges and corners (shared
// coordinates) are frequent and every comparison is exact.
Box randomGridBox(Random& rng, int gridSize)
{
	Box box;
	for (int axis = 0; axis < 3; ++axis)
	{
		const int a = rng.integer(0, gridSize);
		const int b = rng.integer(0, gridSize);
		box.min[axis] = btScalar(btMin(a, b));
		box.max[axis] = btScalar(btMax(a, b));
	}
	box.min.setW(0);
	box.max.setW(0);
	return box;
}

// A box with continuous random bounds: centre in [-range, range]^3, half extents in [0.2, 2].
Box randomBox(Random& rng, btScalar range)
{
	const btVector3 centre = rng.vector(range);
	const btVector3 half(rng.uniform(btScalar(0.2), 2), rng.uniform(btScalar(0.2), 2), rng.uniform(btScalar(0.2), 2));
	return Box{centre - half, centre + half};
}

// Independent formulation: two closed intervals meet when the larger lower end is not above the
// smaller upper end; boxes meet when their intervals meet on every axis.
bool intervalsMeet(btScalar lo1, btScalar hi1, btScalar lo2, btScalar hi2)
{
	return btMax(lo1, lo2) <= btMin(hi1, hi2);
}

bool boxesMeet(const Box& a, const Box& b)
{
	for (int axis = 0; axis < 3; ++axis)
		if (!intervalsMeet(a.min[axis], a.max[axis], b.min[axis], b.max[axis])) return false;
	return true;
}

bool pointInBox(const btVector3& p, const Box& box, btScalar shrink = 0)
{
	for (int axis = 0; axis < 3; ++axis)
		if (!intervalsMeet(p[axis], p[axis], box.min[axis] + shrink, box.max[axis] - shrink)) return false;
	return true;
}

std::string describe(const btVector3& v)
{
	return "(" + std::to_string(double(v.x())) + ", " + std::to_string(double(v.y())) + ", " +
	       std::to_string(double(v.z())) + ")";
}
std::string describe(const Box& box) { return describe(box.min) + ".." + describe(box.max); }
}  // namespace

// ---- overlap and containment -------------------------------------------------------------------

TEST(AabbUtilOverlap, AabbAgainstAabbMatchesIntervalFormulation)
{
	Random rng(501);
	int overlaps = 0, touches = 0;
	for (int i = 0; i < 20000; ++i)
	{
		const Box a = randomGridBox(rng, 6);
		const Box b = randomGridBox(rng, 6);
		const bool expected = boxesMeet(a, b);
		ASSERT_EQ(TestAabbAgainstAabb2(a.min, a.max, b.min, b.max), expected)
		    << "case " << i << ": " << describe(a) << " vs " << describe(b);
		ASSERT_EQ(TestAabbAgainstAabb2(b.min, b.max, a.min, a.max), expected) << "not symmetric, case " << i;
		overlaps += expected;
		// Touching: meeting, but with an empty open intersection on some axis.
		for (int axis = 0; axis < 3 && expected; ++axis)
			if (btMax(a.min[axis], b.min[axis]) == btMin(a.max[axis], b.max[axis]))
			{
				++touches;
				break;
			}
	}
	// The grid makes both outcomes, and touching contacts, common.
	EXPECT_GT(overlaps, 2000);
	EXPECT_LT(overlaps, 18000);
	EXPECT_GT(touches, 500);
}

TEST(AabbUtilOverlap, TouchingBoxesOverlap)
{
	const btVector3 min(0, 0, 0), max(1, 1, 1);
	// Face, edge and corner contact.
	EXPECT_TRUE(TestAabbAgainstAabb2(min, max, btVector3(1, 0, 0), btVector3(2, 1, 1)));
	EXPECT_TRUE(TestAabbAgainstAabb2(min, max, btVector3(1, 1, 0), btVector3(2, 2, 1)));
	EXPECT_TRUE(TestAabbAgainstAabb2(min, max, btVector3(-1, -1, -1), btVector3(0, 0, 0)));
	// A hair apart is apart.
	const btScalar gap = btScalar(1) + SIMD_EPSILON;
	EXPECT_FALSE(TestAabbAgainstAabb2(min, max, btVector3(gap, 0, 0), btVector3(2, 1, 1)));
	// Degenerate (flat or point) boxes still follow the closed-interval rule.
	EXPECT_TRUE(TestAabbAgainstAabb2(min, max, btVector3(btScalar(0.5), btScalar(0.5), 1),
	                                 btVector3(btScalar(0.5), btScalar(0.5), 1)));
}

TEST(AabbUtilOverlap, PointAgainstAabbMatchesIntervalFormulation)
{
	Random rng(502);
	int inside = 0, onBoundary = 0;
	for (int i = 0; i < 20000; ++i)
	{
		const Box box = randomGridBox(rng, 6);
		const btVector3 p(btScalar(rng.integer(0, 6)), btScalar(rng.integer(0, 6)), btScalar(rng.integer(0, 6)));
		const bool expected = pointInBox(p, box);
		ASSERT_EQ(TestPointAgainstAabb2(box.min, box.max, p), expected)
		    << "case " << i << ": " << describe(p) << " in " << describe(box);
		inside += expected;
		if (expected && !pointInBox(p, box, btScalar(0.5))) ++onBoundary;
	}
	EXPECT_GT(inside, 2000);
	EXPECT_LT(inside, 18000);
	EXPECT_GT(onBoundary, 1000) << "grid should put many points on faces";
}

TEST(AabbUtilOverlap, TriangleAgainstAabbIsConservative)
{
	Random rng(503);
	int hits = 0;
	for (int i = 0; i < 3000; ++i)
	{
		const Box box = randomBox(rng, 3);
		const btVector3 vertices[3] = {rng.vector(5), rng.vector(5), rng.vector(5)};
		const bool reported = TestTriangleAgainstAabb2(vertices, box.min, box.max);
		// Documented formulation: exactly the overlap of the triangle's own bounding box with the box.
		Box triangleBox{vertices[0], vertices[0]};
		for (int v = 1; v < 3; ++v)
		{
			triangleBox.min.setMin(vertices[v]);
			triangleBox.max.setMax(vertices[v]);
		}
		EXPECT_EQ(reported, boxesMeet(triangleBox, box)) << "case " << i;
		// Conservative: if any point of the triangle is in the box, the test must report an overlap.
		bool sampleInside = false;
		const int kSamples = 24;
		for (int s = 0; s <= kSamples && !sampleInside; ++s)
			for (int t = 0; s + t <= kSamples && !sampleInside; ++t)
			{
				const btScalar u = btScalar(s) / kSamples, v = btScalar(t) / kSamples;
				const btVector3 p = vertices[0] + u * (vertices[1] - vertices[0]) + v * (vertices[2] - vertices[0]);
				sampleInside = pointInBox(p, box);
			}
		if (sampleInside)
		{
			++hits;
			EXPECT_TRUE(reported) << "triangle point inside the box, case " << i;
		}
	}
	EXPECT_GT(hits, 100);

	// A triangle cutting diagonally past a box corner: its bounding box overlaps, the triangle does not;
	// the conservative test still reports an overlap.
	const btVector3 corner[3] = {btVector3(btScalar(1.5), 0, 0), btVector3(0, btScalar(1.5), 0),
	                             btVector3(btScalar(1.5), btScalar(1.5), 0)};
	EXPECT_TRUE(TestTriangleAgainstAabb2(corner, btVector3(0, 0, -1), btVector3(btScalar(0.5), btScalar(0.5), 1)));
	// A triangle entirely beside the box on one axis is rejected.
	const btVector3 beside[3] = {btVector3(2, 0, 0), btVector3(3, 1, 0), btVector3(2, 1, 1)};
	EXPECT_FALSE(TestTriangleAgainstAabb2(beside, btVector3(0, 0, 0), btVector3(1, 1, 1)));
}

TEST(AabbUtilOutcode, BitsNameTheSidesOutside)
{
	const btVector3 half(1, 2, 3);
	// Each axis: below (-), inside, above (+); the documented bits are -x 1, -y 2, -z 4, +x 8, +y 16, +z 32.
	const btScalar offsets[3] = {btScalar(-1.5), btScalar(0), btScalar(1.5)};
	const int belowBit[3] = {0x01, 0x02, 0x04};
	const int aboveBit[3] = {0x08, 0x10, 0x20};
	for (int ix = 0; ix < 3; ++ix)
		for (int iy = 0; iy < 3; ++iy)
			for (int iz = 0; iz < 3; ++iz)
			{
				const int region[3] = {ix, iy, iz};
				btVector3 p(0, 0, 0);
				int expected = 0;
				for (int axis = 0; axis < 3; ++axis)
				{
					p[axis] = offsets[region[axis]] * half[axis];
					if (region[axis] == 0) expected |= belowBit[axis];
					if (region[axis] == 2) expected |= aboveBit[axis];
				}
				EXPECT_EQ(btOutcode(p, half), expected) << "point " << describe(p);
			}
	// Points on the boundary are inside (the box is closed).
	EXPECT_EQ(btOutcode(btVector3(1, -2, 3), half), 0);
	EXPECT_EQ(btOutcode(btVector3(-1, 2, -3), half), 0);
	EXPECT_EQ(btOutcode(btVector3(1 + SIMD_EPSILON * 2, 0, 0), half), 0x08);
}

// ---- btRayAabb / btRayAabb2 ---------------------------------------------------------------------

namespace
{
struct Segment
{
	btVector3 from;
	btVector3 to;
};

btVector3 randomPointIn(Random& rng, const Box& box)
{
	return btVector3(rng.uniform(box.min.x(), box.max.x()), rng.uniform(box.min.y(), box.max.y()),
	                 rng.uniform(box.min.z(), box.max.z()));
}

// A tenth of the segments start inside the box, half aim at a random point inside it (so hits are
// common), the rest are random.
Segment randomSegment(Random& rng, const Box& box)
{
	Segment s;
	const int kind = rng.integer(0, 9);
	s.from = kind == 0 ? randomPointIn(rng, box) : rng.vector(8);
	if (kind >= 5)
		s.to = s.from + (randomPointIn(rng, box) - s.from) * rng.uniform(btScalar(0.5), btScalar(2));
	else
		s.to = rng.vector(8);
	return s;
}

// Scenes are of size ~10 (coordinates up to 8, segment lengths up to ~30): positions derived from a
// parameter carry a few eps of that scale, so kTightTolerance * 32 absolute covers them.
const btScalar kSceneTolerance = kTightTolerance * 32;
}  // namespace

TEST(AabbUtilRay, RandomSegmentsAgreeWithGeometry)
{
	Random rng(601);
	int hits = 0, misses = 0, startsInside = 0;
	for (int i = 0; i < 4000; ++i)
	{
		const Box box = randomBox(rng, 4);
		const Segment seg = randomSegment(rng, box);
		const btVector3 dir = seg.to - seg.from;
		btScalar param = 1;
		btVector3 normal(9, 9, 9);
		const bool hit = btRayAabb(seg.from, seg.to, box.min, box.max, param, normal);
		const std::string context = "case " + std::to_string(i) + ": " + describe(seg.from) + " -> " +
		                            describe(seg.to) + " vs " + describe(box);
		if (hit)
		{
			++hits;
			ASSERT_GE(param, btScalar(0)) << context;
			ASSERT_LE(param, btScalar(1)) << context;
			const btVector3 point = seg.from + dir * param;
			if (pointInBox(seg.from, box))
			{
				++startsInside;
				EXPECT_EQ(param, btScalar(0)) << context;
				EXPECT_EQ(normal, btVector3(0, 0, 0)) << context;
				continue;
			}
			// The entry point lies in the box (within tolerance) ...
			Box grown{box.min - btVector3(kSceneTolerance, kSceneTolerance, kSceneTolerance),
			          box.max + btVector3(kSceneTolerance, kSceneTolerance, kSceneTolerance)};
			EXPECT_TRUE(pointInBox(point, grown)) << "hit point " << describe(point) << ", " << context;
			// ... on the face whose outward normal is reported: one axis, unit, against the motion.
			ASSERT_EQ(normal.length2(), btScalar(1)) << describe(normal) << ", " << context;
			const int axis = normal.closestAxis();
			ASSERT_EQ(btFabs(normal[axis]), btScalar(1)) << context;
			const btScalar facePlane = normal[axis] > 0 ? box.max[axis] : box.min[axis];
			EXPECT_NEAR(point[axis], facePlane, kSceneTolerance) << context;
			EXPECT_LT(normal[axis] * dir[axis], btScalar(0)) << "normal must face the incoming segment, " << context;
			// A point slightly before the entry, `margin` outside the face plane along the normal, is
			// outside the box. (Skipped when the start is closer than that to the face.)
			const btScalar margin = btScalar(1e-3);
			const btScalar before = param - margin / btFabs(dir[axis]);
			if (before >= 0)
			{
				EXPECT_FALSE(pointInBox(seg.from + dir * before, box))
				    << "point before the entry is inside, " << context;
			}
			// And no earlier point of the segment is deep inside the box (the entry is the first one).
			const int kSamples = 64;
			for (int s = 0; s < kSamples; ++s)
			{
				const btScalar t = param * btScalar(s) / kSamples;
				EXPECT_FALSE(pointInBox(seg.from + dir * t, box, kSceneTolerance))
				    << "segment is inside before the reported entry at t = " << t << ", " << context;
			}
		}
		else
		{
			++misses;
			EXPECT_EQ(param, btScalar(1)) << "param changed on a miss, " << context;
			// Dense samples: none lies inside the box shrunk by the tolerance.
			const int kSamples = 512;
			for (int s = 0; s <= kSamples; ++s)
			{
				const btScalar t = btScalar(s) / kSamples;
				ASSERT_FALSE(pointInBox(seg.from + dir * t, box, kSceneTolerance))
				    << "missed segment passes through the box at t = " << t << ", " << context;
			}
		}
	}
	EXPECT_GT(hits, 1000);
	EXPECT_GT(misses, 1000);
	EXPECT_GT(startsInside, 200);
}

TEST(AabbUtilRay, SegmentStartingInsideHitsAtZeroWithZeroNormal)
{
	const btVector3 min(-1, -1, -1), max(1, 1, 1);
	const btVector3 targets[] = {btVector3(5, 0, 0), btVector3(0, 0, 0), btVector3(-3, 4, 2)};
	const btVector3 starts[] = {btVector3(0, 0, 0), btVector3(btScalar(0.9), btScalar(-0.5), 0),
	                            btVector3(1, 0, 0) /* on a face, leaving */, btVector3(-1, -1, -1) /* corner */};
	for (const btVector3& from : starts)
		for (const btVector3& to : targets)
		{
			btScalar param = 1;
			btVector3 normal(9, 9, 9);
			ASSERT_TRUE(btRayAabb(from, to, min, max, param, normal)) << describe(from) << " -> " << describe(to);
			EXPECT_EQ(param, btScalar(0)) << describe(from) << " -> " << describe(to);
			EXPECT_EQ(normal, btVector3(0, 0, 0)) << describe(from) << " -> " << describe(to);
		}
}

TEST(AabbUtilRay, AxisParallelSegments)
{
	const btVector3 min(0, 0, 0), max(1, 1, 1);
	const btScalar half = btScalar(0.5);
	btScalar param;
	btVector3 normal;
	// Along +x through the middle: enters the -x face at fraction (0 - -4) / 8 = 0.5 (exact).
	param = 1;
	ASSERT_TRUE(btRayAabb(btVector3(-4, half, half), btVector3(4, half, half), min, max, param, normal));
	EXPECT_EQ(param, btScalar(0.5));
	EXPECT_EQ(normal, btVector3(-1, 0, 0));
	// Along -x: enters the +x face at (4 - 1) / 8.
	param = 1;
	ASSERT_TRUE(btRayAabb(btVector3(4, half, half), btVector3(-4, half, half), min, max, param, normal));
	EXPECT_EQ(param, btScalar(0.375));
	EXPECT_EQ(normal, btVector3(1, 0, 0));
	// Along -z from above.
	param = 1;
	ASSERT_TRUE(btRayAabb(btVector3(half, half, 3), btVector3(half, half, -1), min, max, param, normal));
	EXPECT_EQ(param, btScalar(0.5));
	EXPECT_EQ(normal, btVector3(0, 0, 1));
	// Along +y, but beside the box in x: miss.
	param = 1;
	EXPECT_FALSE(btRayAabb(btVector3(2, -4, half), btVector3(2, 4, half), min, max, param, normal));
	EXPECT_EQ(param, btScalar(1));
	// Sliding exactly along a face plane (y = 1): the closed box is touched.
	param = 1;
	ASSERT_TRUE(btRayAabb(btVector3(-4, 1, half), btVector3(4, 1, half), min, max, param, normal));
	EXPECT_EQ(param, btScalar(0.5));
	EXPECT_EQ(normal, btVector3(-1, 0, 0));
	// Along an edge line (y = 0, z = 1).
	param = 1;
	ASSERT_TRUE(btRayAabb(btVector3(-4, 0, 1), btVector3(4, 0, 1), min, max, param, normal));
	EXPECT_EQ(param, btScalar(0.5));
	// Too short to reach.
	param = 1;
	EXPECT_FALSE(btRayAabb(btVector3(-4, half, half), btVector3(-1, half, half), min, max, param, normal));
	// Ending exactly on the face: touching counts, at fraction 1.
	param = 1;
	ASSERT_TRUE(btRayAabb(btVector3(-4, half, half), btVector3(0, half, half), min, max, param, normal));
	EXPECT_EQ(param, btScalar(1));
	EXPECT_EQ(normal, btVector3(-1, 0, 0));
}

TEST(AabbUtilRay, ParamIsAnUpperBoundForAcceptedHits)
{
	// Boxes along +x, entered at fractions 0.25, 0.5 and 0.75 of the segment from x = 0 to x = 8.
	const btVector3 from(0, 0, 0), to(8, 0, 0);
	const btVector3 size(1, 1, 1);
	const btVector3 nearMin(2, -1, -1), midMin(4, -1, -1), farMin(6, -1, -1);
	btScalar param = 1;
	btVector3 normal(0, 0, 0);
	ASSERT_TRUE(btRayAabb(from, to, midMin, midMin + size * 2, param, normal));
	EXPECT_EQ(param, btScalar(0.5));
	// The farther box is not accepted and changes nothing.
	const btVector3 normalBefore = normal;
	EXPECT_FALSE(btRayAabb(from, to, farMin, farMin + size * 2, param, normal));
	EXPECT_EQ(param, btScalar(0.5));
	EXPECT_EQ(normal, normalBefore);
	// The nearer one is.
	EXPECT_TRUE(btRayAabb(from, to, nearMin, nearMin + size * 2, param, normal));
	EXPECT_EQ(param, btScalar(0.25));
	EXPECT_EQ(normal, btVector3(-1, 0, 0));
	// Entered exactly at the bound: accepted (closed).
	param = btScalar(0.75);
	EXPECT_TRUE(btRayAabb(from, to, farMin, farMin + size * 2, param, normal));
	EXPECT_EQ(param, btScalar(0.75));

	// Random: a box hit with the full segment is rejected when param is set just before its entry.
	Random rng(602);
	int checked = 0;
	for (int i = 0; i < 2000; ++i)
	{
		const Box box = randomBox(rng, 4);
		const Segment seg = randomSegment(rng, box);
		btScalar full = 1;
		if (!btRayAabb(seg.from, seg.to, box.min, box.max, full, normal) || full < btScalar(0.01)) continue;
		btScalar limited = full * btScalar(0.99);
		EXPECT_FALSE(btRayAabb(seg.from, seg.to, box.min, box.max, limited, normal)) << "case " << i;
		EXPECT_EQ(limited, full * btScalar(0.99));
		++checked;
	}
	EXPECT_GT(checked, 500);
}

namespace
{
// Calls btRayAabb2 on the segment from -> to with lambda in [0, 1].
bool rayAabb2OnSegment(const btVector3& from, const btVector3& to, const Box& box, btScalar& tmin)
{
	const btVector3 dir = to - from;
	btVector3 inverse;
	unsigned int signs[3];
	for (int axis = 0; axis < 3; ++axis)
	{
		inverse[axis] =
		    dir[axis] == btScalar(0) ? (std::signbit(dir[axis]) ? -BT_INFINITY : BT_INFINITY) : btScalar(1) / dir[axis];
		signs[axis] = inverse[axis] < btScalar(0) ? 1u : 0u;
	}
	const btVector3 bounds[2] = {box.min, box.max};
	return btRayAabb2(from, inverse, signs, bounds, tmin, btScalar(0), btScalar(1));
}
}  // namespace

TEST(AabbUtilRay, RayAabb2AgreesWithRayAabb)
{
	Random rng(603);
	int hits = 0;
	for (int i = 0; i < 4000; ++i)
	{
		const Box box = randomBox(rng, 4);
		Segment seg = randomSegment(rng, box);
		// Every fourth segment is made parallel to one face pair (a zero direction component), every eighth
		// to two, and every sixteenth also lies in a face plane (where 0 * inf is NaN in btRayAabb2).
		if (i % 4 == 0)
		{
			const int axis = rng.integer(0, 2);
			if (i % 16 == 0) seg.from[axis] = rng.integer(0, 1) ? box.min[axis] : box.max[axis];
			seg.to[axis] = seg.from[axis];
		}
		if (i % 8 == 0)
		{
			const int axis = rng.integer(0, 2);
			seg.to[axis] = seg.from[axis];
		}
		btScalar param = 1;
		btVector3 normal;
		const bool hit = btRayAabb(seg.from, seg.to, box.min, box.max, param, normal);
		btScalar tmin = -1;
		const bool hit2 = rayAabb2OnSegment(seg.from, seg.to, box, tmin);
		ASSERT_EQ(hit2, hit) << "case " << i << ": " << describe(seg.from) << " -> " << describe(seg.to) << " vs "
		                     << describe(box);
		if (hit)
		{
			++hits;
			// Both are the same slab computation; allow an eps-relative difference in the fraction.
			EXPECT_NEAR(tmin, param, kTightTolerance) << "case " << i;
		}
	}
	EXPECT_GT(hits, 1000);
}

TEST(AabbUtilRay, RayAabb2HandlesRaysInFacePlanesAndLambdaRange)
{
	const Box box{btVector3(0, 0, 0), btVector3(1, 1, 1)};
	btScalar tmin = -1;
	// Parallel to x in the face plane y = 0 (0 * inf would be NaN): touching counts.
	EXPECT_TRUE(rayAabb2OnSegment(btVector3(-1, 0, btScalar(0.5)), btVector3(3, 0, btScalar(0.5)), box, tmin));
	EXPECT_EQ(tmin, btScalar(0.25));
	// Parallel, outside the slab.
	EXPECT_FALSE(rayAabb2OnSegment(btVector3(-1, 2, btScalar(0.5)), btVector3(3, 2, btScalar(0.5)), box, tmin));
	// Starting inside: clamped to lambda_min.
	EXPECT_TRUE(
	    rayAabb2OnSegment(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)), btVector3(3, 2, 1), box, tmin));
	EXPECT_EQ(tmin, btScalar(0));
	// lambda_max limits the ray: the box entered at t = 0.5 is missed with lambda in [0, 0.4].
	const btVector3 from(-1, btScalar(0.5), btScalar(0.5));
	const btVector3 inverse(btScalar(0.25), BT_INFINITY, BT_INFINITY);  // direction (4, 0, 0)
	const unsigned int signs[3] = {0, 0, 0};
	const btVector3 bounds[2] = {box.min, box.max};
	EXPECT_FALSE(btRayAabb2(from, inverse, signs, bounds, tmin, btScalar(0), btScalar(0.2)));
	EXPECT_TRUE(btRayAabb2(from, inverse, signs, bounds, tmin, btScalar(0), btScalar(0.3)));
	EXPECT_EQ(tmin, btScalar(0.25));
	// lambda_min beyond the entry: clamped to lambda_min.
	EXPECT_TRUE(btRayAabb2(from, inverse, signs, bounds, tmin, btScalar(0.4), btScalar(1)));
	EXPECT_EQ(tmin, btScalar(0.4));
}

// ---- btTransformAabb ---------------------------------------------------------------------------

namespace
{
// Checks that [aabbMin, aabbMax] contains the 8 corners within tolerance and that each of its 6 faces is
// touched by some corner (the box is the tightest axis-aligned one).
::testing::AssertionResult containsAndTouches(const btVector3 corners[8], const btVector3& aabbMin,
                                              const btVector3& aabbMax, btScalar tolerance)
{
	for (int c = 0; c < 8; ++c)
		for (int axis = 0; axis < 3; ++axis)
			if (corners[c][axis] < aabbMin[axis] - tolerance || corners[c][axis] > aabbMax[axis] + tolerance)
				return ::testing::AssertionFailure() << "corner " << describe(corners[c]) << " outside "
				                                     << describe(aabbMin) << ".." << describe(aabbMax);
	for (int axis = 0; axis < 3; ++axis)
	{
		btScalar lowest = SIMD_INFINITY, highest = -SIMD_INFINITY;
		for (int c = 0; c < 8; ++c)
		{
			lowest = btMin(lowest, corners[c][axis]);
			highest = btMax(highest, corners[c][axis]);
		}
		if (btFabs(lowest - aabbMin[axis]) > tolerance || btFabs(highest - aabbMax[axis]) > tolerance)
			return ::testing::AssertionFailure()
			       << "axis " << axis << ": corners span " << lowest << ".." << highest << ", box " << aabbMin[axis]
			       << ".." << aabbMax[axis] << " (tolerance " << tolerance << ")";
	}
	return ::testing::AssertionSuccess();
}

void transformedCorners(const btVector3& localMin, const btVector3& localMax, const btTransform& t,
                        btVector3 corners[8])
{
	for (int c = 0; c < 8; ++c)
		corners[c] = t(btVector3((c & 1) ? localMax.x() : localMin.x(), (c & 2) ? localMax.y() : localMin.y(),
		                         (c & 4) ? localMax.z() : localMin.z()));
}
}  // namespace

TEST(AabbUtilTransform, CentredBoxContainsTransformedCornersAndIsTight)
{
	Random rng(701);
	for (int i = 0; i < 1000; ++i)
	{
		const btVector3 half(rng.uniform(0, 3), rng.uniform(0, 3), rng.uniform(0, 3));
		const btScalar margin = (i % 3 == 0) ? btScalar(0) : rng.uniform(0, btScalar(0.5));
		const btTransform t(rng.rotation(), rng.vector(10));
		btVector3 aabbMin, aabbMax;
		btTransformAabb(half, margin, t, aabbMin, aabbMax);
		const btVector3 grown = half + btVector3(margin, margin, margin);
		btVector3 corners[8];
		transformedCorners(-grown, grown, t, corners);
		// Coordinates up to ~16, each through a rotation (3 products and sums) and one addition: a few eps
		// of 16, kTightTolerance * 16.
		EXPECT_TRUE(containsAndTouches(corners, aabbMin, aabbMax, kTightTolerance * 16)) << "case " << i;
	}
}

TEST(AabbUtilTransform, OffCentreBoxContainsTransformedCornersAndIsTight)
{
	Random rng(702);
	for (int i = 0; i < 1000; ++i)
	{
		const btVector3 a = rng.vector(4), b = rng.vector(4);
		btVector3 localMin = a, localMax = a;
		localMin.setMin(b);
		localMax.setMax(b);
		const btScalar margin = (i % 3 == 0) ? btScalar(0) : rng.uniform(0, btScalar(0.5));
		const btTransform t(rng.rotation(), rng.vector(10));
		btVector3 aabbMin, aabbMax;
		btTransformAabb(localMin, localMax, margin, t, aabbMin, aabbMax);
		const btVector3 m(margin, margin, margin);
		btVector3 corners[8];
		transformedCorners(localMin - m, localMax + m, t, corners);
		// Coordinates up to ~18: same reasoning as above.
		EXPECT_TRUE(containsAndTouches(corners, aabbMin, aabbMax, kTightTolerance * 18)) << "case " << i;
	}
}

TEST(AabbUtilTransform, IdentityTransformKeepsBoxGrownByMargin)
{
	btVector3 aabbMin, aabbMax;
	btTransformAabb(btVector3(1, 2, 3), btScalar(0.5), btTransform::getIdentity(), aabbMin, aabbMax);
	EXPECT_EQ(aabbMin, btVector3(btScalar(-1.5), btScalar(-2.5), btScalar(-3.5)));
	EXPECT_EQ(aabbMax, btVector3(btScalar(1.5), btScalar(2.5), btScalar(3.5)));
	btTransformAabb(btVector3(-1, 0, 2), btVector3(3, 1, 4), btScalar(0.25), btTransform::getIdentity(), aabbMin,
	                aabbMax);
	EXPECT_EQ(aabbMin, btVector3(btScalar(-1.25), btScalar(-0.25), btScalar(1.75)));
	EXPECT_EQ(aabbMax, btVector3(btScalar(3.25), btScalar(1.25), btScalar(4.25)));
}

// ---- quantised boxes and AabbExpand -----------------------------------------------------------

TEST(AabbUtilQuantized, AgreesWithFloatTestOnQuantisedBoxes)
{
	Random rng(801);
	int overlaps = 0;
	for (int i = 0; i < 20000; ++i)
	{
		unsigned short min1[3], max1[3], min2[3], max2[3];
		// A narrow range around an arbitrary base makes touching common; every tenth case uses the full
		// 16-bit range, including 0 and 65535.
		const int base = (i % 10 == 0) ? 0 : rng.integer(0, 65535 - 8);
		const int span = (i % 10 == 0) ? 65535 : 8;
		for (int axis = 0; axis < 3; ++axis)
		{
			const int a1 = base + rng.integer(0, span), b1 = base + rng.integer(0, span);
			const int a2 = base + rng.integer(0, span), b2 = base + rng.integer(0, span);
			min1[axis] = static_cast<unsigned short>(btMin(a1, b1));
			max1[axis] = static_cast<unsigned short>(btMax(a1, b1));
			min2[axis] = static_cast<unsigned short>(btMin(a2, b2));
			max2[axis] = static_cast<unsigned short>(btMax(a2, b2));
		}
		// Every 16-bit integer is exact in float and double.
		const btVector3 fMin1(min1[0], min1[1], min1[2]), fMax1(max1[0], max1[1], max1[2]);
		const btVector3 fMin2(min2[0], min2[1], min2[2]), fMax2(max2[0], max2[1], max2[2]);
		const bool expected = TestAabbAgainstAabb2(fMin1, fMax1, fMin2, fMax2);
		ASSERT_EQ(testQuantizedAabbAgainstQuantizedAabb(min1, max1, min2, max2), expected ? 1u : 0u)
		    << "case " << i << ": " << describe(fMin1) << ".." << describe(fMax1) << " vs " << describe(fMin2) << ".."
		    << describe(fMax2);
		overlaps += expected;
	}
	EXPECT_GT(overlaps, 1000);
	EXPECT_LT(overlaps, 19000);
	const unsigned short lo[3] = {0, 0, 0}, hi[3] = {65535, 65535, 65535}, mid[3] = {100, 65535, 0};
	EXPECT_EQ(testQuantizedAabbAgainstQuantizedAabb(lo, hi, mid, mid), 1u);
	EXPECT_EQ(testQuantizedAabbAgainstQuantizedAabb(hi, hi, lo, lo), 0u);
	EXPECT_EQ(testQuantizedAabbAgainstQuantizedAabb(lo, mid, mid, hi), 1u) << "touching at the corner";
}

TEST(AabbUtilExpand, AddsExpansionToEachBound)
{
	btVector3 aabbMin(-1, -2, -3), aabbMax(1, 2, 3);
	AabbExpand(aabbMin, aabbMax, btVector3(btScalar(-0.5), 0, btScalar(0.25)),
	           btVector3(btScalar(0.5), btScalar(1.5), 0));
	// Dyadic values: exact.
	EXPECT_EQ(aabbMin, btVector3(btScalar(-1.5), -2, btScalar(-2.75)));
	EXPECT_EQ(aabbMax, btVector3(btScalar(1.5), btScalar(3.5), 3));
	// Expanding by (motion, 0) mins / (0, motion) maxes makes a swept box that holds both positions.
	Random rng(802);
	for (int i = 0; i < 200; ++i)
	{
		const Box box = randomBox(rng, 5);
		const btVector3 motion = rng.vector(3);
		btVector3 expandMin(0, 0, 0), expandMax(0, 0, 0);
		expandMin.setMin(motion);
		expandMax.setMax(motion);
		btVector3 sweptMin = box.min, sweptMax = box.max;
		AabbExpand(sweptMin, sweptMax, expandMin, expandMax);
		EXPECT_TRUE(TestPointAgainstAabb2(sweptMin, sweptMax, box.min)) << "case " << i;
		EXPECT_TRUE(TestPointAgainstAabb2(sweptMin, sweptMax, box.max)) << "case " << i;
		// The moved box's corners, up to rounding of one addition (relative eps of ~8).
		const btVector3 slack(kTightTolerance * 8, kTightTolerance * 8, kTightTolerance * 8);
		EXPECT_TRUE(TestPointAgainstAabb2(sweptMin - slack, sweptMax + slack, box.min + motion)) << "case " << i;
		EXPECT_TRUE(TestPointAgainstAabb2(sweptMin - slack, sweptMax + slack, box.max + motion)) << "case " << i;
	}
}
