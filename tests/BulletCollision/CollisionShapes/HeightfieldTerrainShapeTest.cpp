// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btHeightfieldTerrainShape against an independent model of the grid built here from the height samples:
// triangle queries, ray walks, AABB, centring, scaling and bad input.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h"
#include "BulletCollision/CollisionShapes/btTriangleInfoMap.h"
#include "BulletCollision/CollisionShapes/ShapesCoreTestUtil.h"

using namespace shapes_core_test;

namespace
{
// Coordinates are a few products and sums of values of order 10 (the model works in double): a few
// roundings of relative size SIMD_EPSILON on values up to ~20, with a wide factor.
const btScalar kCoordTolerance = btScalar(2000) * SIMD_EPSILON;
// Box-overlap decisions within this distance of a box face are ambiguous after rounding and are not checked.
const btScalar kBoundarySlack = btScalar(1e-3);

typedef std::pair<int, int> TriangleId;  // (partId, triangleIndex) = (2 * x + k, y)

struct Triangle
{
	btVector3 v[3];
};

class Collector : public btTriangleCallback
{
public:
	std::map<TriangleId, Triangle> triangles;
	int duplicates = 0;
	void processTriangle(btVector3* triangle, int partId, int triangleIndex) override
	{
		const TriangleId id(partId, triangleIndex);
		if (triangles.count(id)) ++duplicates;
		Triangle t;
		for (int i = 0; i < 3; ++i) t.v[i] = triangle[i];
		triangles[id] = t;
	}
};

// The independent model: heights after scaling and clamping, the same layout rules as the documentation.
struct Grid
{
	int width = 0, length = 0, upAxis = 1;
	std::vector<double> heights;  // NaN for a non-finite sample
	double minHeight = 0, maxHeight = 0;
	btVector3 scaling{1, 1, 1};
	bool flip = false, diamond = false, zigzag = false;

	int gridAxis0() const { return upAxis == 0 ? 1 : 0; }
	int gridAxis1() const { return upAxis == 2 ? 1 : 2; }

	btVector3 vertex(int x, int y) const
	{
		double h = heights[y * width + x];
		h = std::min(std::max(h, minHeight), maxHeight);
		btVector3 p;
		p[gridAxis0()] = btScalar((x - 0.5 * (width - 1)) * scaling[gridAxis0()]);
		p[gridAxis1()] = btScalar((y - 0.5 * (length - 1)) * scaling[gridAxis1()]);
		p[upAxis] = btScalar((h - 0.5 * (minHeight + maxHeight)) * scaling[upAxis]);
		p[3] = 0;
		return p;
	}
	bool finite(int x, int y) const { return std::isfinite(heights[y * width + x]); }

	// The triangle with id (2x+k, y) and whether all its samples are finite.
	bool triangle(int x, int y, int k, Triangle& out) const
	{
		const bool mainDiagonal = flip || (diamond && (x + y) % 2 == 0) || (zigzag && y % 2 == 0);
		const int corners[4][2] = {{x, y}, {x + 1, y}, {x + 1, y + 1}, {x, y + 1}};
		static const int kMain[2][3] = {{0, 1, 2}, {0, 2, 3}};
		static const int kOther[2][3] = {{0, 1, 3}, {1, 2, 3}};
		const int* pick = mainDiagonal ? kMain[k] : kOther[k];
		bool ok = true;
		for (int i = 0; i < 3; ++i)
		{
			const int cx = corners[pick[i]][0], cy = corners[pick[i]][1];
			ok = ok && finite(cx, cy);
			out.v[i] = vertex(cx, cy);
		}
		return ok;
	}

	int cellsX() const { return width - 1; }
	int cellsY() const { return length - 1; }
};

void triangleAabb(const Triangle& t, btVector3& lo, btVector3& hi)
{
	lo = hi = t.v[0];
	for (int i = 1; i < 3; ++i)
	{
		lo.setMin(t.v[i]);
		hi.setMax(t.v[i]);
	}
}

bool boxesOverlap(const btVector3& aMin, const btVector3& aMax, const btVector3& bMin, const btVector3& bMax,
                  btScalar grow)
{
	for (int i = 0; i < 3; ++i)
		if (aMin[i] > bMax[i] + grow || aMax[i] < bMin[i] - grow) return false;
	return true;
}

// Same vertices as expected (in any order) and facing +up (scaling is positive in these tests).
::testing::AssertionResult sameTriangle(const Triangle& got, const Triangle& want, int upAxis, btScalar tolerance)
{
	bool used[3] = {false, false, false};
	for (int i = 0; i < 3; ++i)
	{
		bool matched = false;
		for (int j = 0; j < 3 && !matched; ++j)
			if (!used[j] && got.v[i].distance(want.v[j]) <= tolerance) matched = used[j] = true;
		if (!matched)
			return ::testing::AssertionFailure()
			       << "vertex (" << got.v[i].x() << ", " << got.v[i].y() << ", " << got.v[i].z() << ") not expected";
	}
	const btVector3 normal = (got.v[1] - got.v[0]).cross(got.v[2] - got.v[0]);
	if (!(normal[upAxis] > 0)) return ::testing::AssertionFailure() << "normal up component " << normal[upAxis];
	return ::testing::AssertionSuccess();
}

// True when the 2D segment a-b comes within grow of the rectangle [x0, x1] x [y0, y1] (slab clipping).
bool segmentNearRect(double ax, double ay, double bx, double by, double x0, double x1, double y0, double y1,
                     double grow)
{
	double t0 = 0, t1 = 1;
	const double from[2] = {ax, ay}, delta[2] = {bx - ax, by - ay}, lo[2] = {x0 - grow, y0 - grow},
	             hi[2] = {x1 + grow, y1 + grow};
	for (int i = 0; i < 2; ++i)
	{
		if (delta[i] == 0)
		{
			if (from[i] < lo[i] || from[i] > hi[i]) return false;
			continue;
		}
		double ta = (lo[i] - from[i]) / delta[i], tb = (hi[i] - from[i]) / delta[i];
		if (ta > tb) std::swap(ta, tb);
		t0 = std::max(t0, ta);
		t1 = std::min(t1, tb);
	}
	return t0 <= t1;
}

struct Fixture
{
	Grid grid;
	std::vector<float> floats;
	std::vector<double> doubles;
	std::vector<short> shorts;
	std::vector<unsigned char> bytes;
	btHeightfieldTerrainShape* shape = nullptr;
	~Fixture() { delete shape; }

	void build(PHY_ScalarType type, int width, int length, int upAxis, unsigned seed)
	{
		Random random(seed);
		grid.width = width;
		grid.length = length;
		grid.upAxis = upAxis;
		grid.heights.assign(size_t(width * length), 0.0);
		btScalar heightScale = 1;
		for (int i = 0; i < width * length; ++i)
		{
			switch (type)
			{
				case PHY_FLOAT:
					floats.push_back(float(random.uniform(-3, 5)));
					grid.heights[size_t(i)] = double(btScalar(floats.back()));
					break;
				case PHY_DOUBLE:
					doubles.push_back(double(random.uniform(-3, 5)));
					grid.heights[size_t(i)] = double(btScalar(doubles.back()));
					break;
				case PHY_SHORT:
					heightScale = btScalar(0.01);
					shorts.push_back(short(std::lround(double(random.uniform(-300, 500)))));
					grid.heights[size_t(i)] = double(btScalar(shorts.back()) * heightScale);
					break;
				default:
					heightScale = btScalar(0.03);
					bytes.push_back((unsigned char)(std::lround(double(random.uniform(0, 255)))));
					grid.heights[size_t(i)] = double(btScalar(bytes.back()) * heightScale);
					break;
			}
		}
		grid.minHeight = -3.5;
		grid.maxHeight = type == PHY_UCHAR ? 8.0 : 5.5;
		const void* data = type == PHY_FLOAT    ? static_cast<const void*>(floats.data())
		                   : type == PHY_DOUBLE ? static_cast<const void*>(doubles.data())
		                   : type == PHY_SHORT  ? static_cast<const void*>(shorts.data())
		                                        : static_cast<const void*>(bytes.data());
		shape = new btHeightfieldTerrainShape(width, length, data, heightScale, btScalar(grid.minHeight),
		                                      btScalar(grid.maxHeight), upAxis, type, false);
	}

	void setSplit(int mode)
	{
		grid.flip = mode == 1;
		grid.diamond = mode == 2;
		grid.zigzag = mode == 3;
		shape->setFlipQuadEdges(grid.flip);
		shape->setUseDiamondSubdivision(grid.diamond);
		shape->setUseZigzagSubdivision(grid.zigzag);
	}

	// Checks one query box against the model. Allowed superset: triangles whose AABB is within kBoundarySlack
	// of the box; required: every triangle whose AABB overlaps the box shrunk by kBoundarySlack.
	void checkQuery(const btVector3& boxMin, const btVector3& boxMax)
	{
		Collector collector;
		shape->processAllTriangles(&collector, boxMin, boxMax);
		EXPECT_EQ(0, collector.duplicates);
		for (int y = 0; y < grid.cellsY(); ++y)
			for (int x = 0; x < grid.cellsX(); ++x)
				for (int k = 0; k < 2; ++k)
				{
					Triangle want;
					const bool valid = grid.triangle(x, y, k, want);
					btVector3 lo, hi;
					triangleAabb(want, lo, hi);
					const auto found = collector.triangles.find(TriangleId(2 * x + k, y));
					const bool reported = found != collector.triangles.end();
					if (reported)
					{
						EXPECT_TRUE(valid) << "triangle with a non-finite sample reported, cell " << x << "," << y;
						EXPECT_TRUE(boxesOverlap(lo, hi, boxMin, boxMax, kBoundarySlack))
						    << "triangle outside the query reported, cell " << x << "," << y << " k " << k;
						EXPECT_TRUE(sameTriangle(found->second, want, grid.upAxis, kCoordTolerance))
						    << "cell " << x << "," << y << " k " << k;
					}
					else if (valid && boxesOverlap(lo, hi, boxMin, boxMax, -kBoundarySlack))
						ADD_FAILURE() << "missing triangle cell " << x << "," << y << " k " << k;
				}
		// Ids outside the grid would be ignored by the loop above: every reported id must be a real cell.
		for (const auto& entry : collector.triangles)
		{
			EXPECT_GE(entry.first.first, 0);
			EXPECT_LT(entry.first.first, 2 * grid.cellsX());
			EXPECT_GE(entry.first.second, 0);
			EXPECT_LT(entry.first.second, grid.cellsY());
		}
	}
};

const PHY_ScalarType kTypes[] = {PHY_FLOAT, PHY_DOUBLE, PHY_SHORT, PHY_UCHAR};

// Möller-Trumbore segment/triangle test; true only for hits clearly inside (margin in barycentric units and
// in segment parameter), so rounding cannot decide the answer.
bool segmentHitsTriangleClearly(const btVector3& from, const btVector3& to, const Triangle& t)
{
	const double margin = 1e-3;
	const btVector3 dir = to - from;
	const btVector3 e1 = t.v[1] - t.v[0], e2 = t.v[2] - t.v[0];
	const btVector3 p = dir.cross(e2);
	const double det = double(e1.dot(p));
	if (std::fabs(det) < 1e-9) return false;
	const btVector3 s = from - t.v[0];
	const double u = double(s.dot(p)) / det;
	const btVector3 q = s.cross(e1);
	const double v = double(dir.dot(q)) / det;
	const double param = double(e2.dot(q)) / det;
	return u > margin && v > margin && u + v < 1 - margin && param > margin && param < 1 - margin;
}
}  // namespace

TEST(HeightfieldTerrainShapeTest, ProcessAllTrianglesMatchesBruteForceForEveryTypeAxisAndSplit)
{
	unsigned seed = 11;
	for (PHY_ScalarType type : kTypes)
		for (int upAxis = 0; upAxis < 3; ++upAxis)
			for (int split = 0; split < 4; ++split)
			{
				SCOPED_TRACE(::testing::Message() << "type " << int(type) << " up " << upAxis << " split " << split);
				Fixture f;
				f.build(type, 7, 5, upAxis, seed++);
				f.setSplit(split);
				const btScalar big = BT_LARGE_FLOAT;
				f.checkQuery(btVector3(-big, -big, -big), btVector3(big, big, big));
				Random random(seed * 7);
				for (int q = 0; q < 25; ++q)
				{
					const btVector3 c = random.vector(5), h = random.vector(2).absolute();
					f.checkQuery(c - h, c + h);
				}
				// A flat box (zero thickness along every axis in turn) still finds the triangles it touches.
				for (int axis = 0; axis < 3; ++axis)
				{
					btVector3 lo = random.vector(2), hi = lo + btVector3(1, 1, 1);
					hi[axis] = lo[axis];
					f.checkQuery(lo, hi);
				}
			}
}

TEST(HeightfieldTerrainShapeTest, FullQueryReportsEveryTriangleOnce)
{
	Fixture f;
	f.build(PHY_FLOAT, 6, 9, 1, 5);
	Collector collector;
	const btScalar big = BT_LARGE_FLOAT;
	f.shape->processAllTriangles(&collector, btVector3(-big, -big, -big), btVector3(big, big, big));
	EXPECT_EQ(0, collector.duplicates);
	EXPECT_EQ(size_t(2 * 5 * 8), collector.triangles.size());
}

TEST(HeightfieldTerrainShapeTest, DiamondAndZigzagAlternateTheDiagonal)
{
	Fixture f;
	f.build(PHY_FLOAT, 4, 4, 1, 3);
	f.setSplit(2);  // diamond
	Collector collector;
	const btScalar big = BT_LARGE_FLOAT;
	f.shape->processAllTriangles(&collector, btVector3(-big, -big, -big), btVector3(big, big, big));
	// Cell (0, 0) uses the (0,0)-(1,1) diagonal, so its first triangle contains sample (1, 1); cell (1, 0) uses
	// the other diagonal, so its first triangle contains sample (1, 0)... and not sample (2, 1).
	const btVector3 s11 = f.grid.vertex(1, 1), s21 = f.grid.vertex(2, 1);
	const Triangle& t00 = collector.triangles.at(TriangleId(0, 0));
	const Triangle& t10 = collector.triangles.at(TriangleId(2, 0));
	bool has11 = false, has21 = false;
	for (int i = 0; i < 3; ++i)
	{
		has11 = has11 || t00.v[i].distance(s11) < kCoordTolerance;
		has21 = has21 || t10.v[i].distance(s21) < kCoordTolerance;
	}
	EXPECT_TRUE(has11);
	EXPECT_FALSE(has21);
}

TEST(HeightfieldTerrainShapeTest, AabbIsCentredAndMatchesGridAndHeightRange)
{
	for (int upAxis = 0; upAxis < 3; ++upAxis)
	{
		SCOPED_TRACE(upAxis);
		Fixture f;
		f.build(PHY_FLOAT, 7, 5, upAxis, 21);
		const btVector3 scaling(btScalar(2), btScalar(0.5), btScalar(3));
		f.shape->setLocalScaling(scaling);
		f.grid.scaling = scaling;
		btVector3 aabbMin, aabbMax;
		f.shape->getAabb(btTransform::getIdentity(), aabbMin, aabbMax);
		btVector3 expectedHalf;
		expectedHalf[f.grid.gridAxis0()] = btScalar(0.5 * 6) * scaling[f.grid.gridAxis0()];
		expectedHalf[f.grid.gridAxis1()] = btScalar(0.5 * 4) * scaling[f.grid.gridAxis1()];
		expectedHalf[upAxis] = btScalar(0.5 * (f.grid.maxHeight - f.grid.minHeight)) * scaling[upAxis];
		EXPECT_TRUE(vectorsNear(aabbMax, expectedHalf, kCoordTolerance));
		EXPECT_TRUE(vectorsNear(aabbMin, -expectedHalf, kCoordTolerance));

		// Every triangle, under a rotated transform, lies inside the transformed AABB.
		Random random(77);
		const btTransform t = random.transform();
		f.shape->getAabb(t, aabbMin, aabbMax);
		Collector collector;
		const btScalar big = BT_LARGE_FLOAT;
		f.shape->processAllTriangles(&collector, btVector3(-big, -big, -big), btVector3(big, big, big));
		for (const auto& entry : collector.triangles)
			for (int i = 0; i < 3; ++i)
			{
				const btVector3 p = t * entry.second.v[i];
				for (int a = 0; a < 3; ++a)
				{
					EXPECT_GE(p[a], aabbMin[a] - kCoordTolerance);
					EXPECT_LE(p[a], aabbMax[a] + kCoordTolerance);
				}
			}
	}
}

TEST(HeightfieldTerrainShapeTest, LocalOriginIsTheMiddleOfGridAndHeightRange)
{
	// 3 x 2 samples, heights 0..10 declared; the top sample sits at +5 and the corner at (-1, ., -0.5).
	const float heights[6] = {0, 10, 4, 2, 6, 8};
	btHeightfieldTerrainShape shape(3, 2, heights, 1, 0, 10, 1, PHY_FLOAT, false);
	btVector3 v;
	shape.getVertex(1, 0, v);
	EXPECT_TRUE(vectorsNear(v, btVector3(0, 5, btScalar(-0.5)), kCoordTolerance));
	shape.getVertex(0, 0, v);
	EXPECT_TRUE(vectorsNear(v, btVector3(-1, -5, btScalar(-0.5)), kCoordTolerance));
	shape.getVertex(2, 1, v);
	EXPECT_TRUE(vectorsNear(v, btVector3(1, 3, btScalar(0.5)), kCoordTolerance));
}

TEST(HeightfieldTerrainShapeTest, LocalScalingScalesGridSpacingAndHeights)
{
	Fixture f;
	f.build(PHY_SHORT, 5, 6, 2, 8);
	const btVector3 scaling(btScalar(1.5), btScalar(2.5), btScalar(0.25));
	btVector3 before[30];
	for (int y = 0; y < 6; ++y)
		for (int x = 0; x < 5; ++x) f.shape->getVertex(x, y, before[y * 5 + x]);
	f.shape->setLocalScaling(scaling);
	EXPECT_TRUE(vectorsNear(f.shape->getLocalScaling(), scaling, 0));
	for (int y = 0; y < 6; ++y)
		for (int x = 0; x < 5; ++x)
		{
			btVector3 after;
			f.shape->getVertex(x, y, after);
			EXPECT_TRUE(vectorsNear(after, before[y * 5 + x] * scaling, kCoordTolerance));
		}
	// Queries under scaling still match the model.
	f.grid.scaling = scaling;
	Random random(9);
	for (int q = 0; q < 20; ++q)
	{
		const btVector3 c = random.vector(4), h = random.vector(2).absolute();
		f.checkQuery(c - h, c + h);
	}
}

TEST(HeightfieldTerrainShapeTest, PerformRaycastReportsEveryTriangleTheSegmentHits)
{
	for (int upAxis = 0; upAxis < 3; ++upAxis)
	{
		SCOPED_TRACE(upAxis);
		Fixture f;
		f.build(PHY_FLOAT, 12, 9, upAxis, 40 + upAxis);
		f.setSplit(2);
		const btVector3 scaling(btScalar(1.5), btScalar(1.25), btScalar(0.75));
		f.shape->setLocalScaling(scaling);
		f.grid.scaling = scaling;
		const int a0 = f.grid.gridAxis0(), a1 = f.grid.gridAxis1();
		Random random(101 + upAxis);
		int hitsChecked = 0;
		for (int r = 0; r < 300; ++r)
		{
			btVector3 from = random.vector(12), to = random.vector(12);
			if (r >= 150)
			{
				// Short segments through a random point inside a random triangle, so that hits near a cell's
				// lowest or highest sample are exercised too.
				Triangle t;
				const int cx = int(random.uniform(0, btScalar(f.grid.cellsX()) - btScalar(0.001)));
				const int cy = int(random.uniform(0, btScalar(f.grid.cellsY()) - btScalar(0.001)));
				f.grid.triangle(cx, cy, r % 2, t);
				const btScalar u = random.uniform(btScalar(0.05), btScalar(0.9));
				const btScalar v = random.uniform(btScalar(0.05), btScalar(0.95) - u);
				const btVector3 onSurface = t.v[0] + (t.v[1] - t.v[0]) * u + (t.v[2] - t.v[0]) * v;
				const btVector3 direction = random.unitVector() * random.uniform(btScalar(0.1), 3);
				from = onSurface - direction;
				to = onSurface + direction;
			}
			if (r % 10 == 0 || r % 10 == 2)
			{
				// Vertical (exactly, or nearly: a thousandth of a cell of drift) through the whole height range.
				to = from;
				to[upAxis] = -from[upAxis];
				if (r % 10 == 0) to[a0] += btScalar(0.001);
			}
			if (r % 10 == 1)
			{
				to[a0] = from[a0];  // moves along grid axis 1 only
				to[a1] = from[a1] + random.uniform(-20, 20);
			}
			Collector collector;
			f.shape->performRaycast(&collector, from, to);
			EXPECT_EQ(0, collector.duplicates);
			// Required: every triangle the segment clearly hits.
			for (int y = 0; y < f.grid.cellsY(); ++y)
				for (int x = 0; x < f.grid.cellsX(); ++x)
					for (int k = 0; k < 2; ++k)
					{
						Triangle t;
						if (!f.grid.triangle(x, y, k, t) || !segmentHitsTriangleClearly(from, to, t)) continue;
						++hitsChecked;
						EXPECT_TRUE(collector.triangles.count(TriangleId(2 * x + k, y)))
						    << "ray " << r << " misses cell " << x << "," << y << " k " << k;
					}
			// Allowed: only triangles of cells whose rectangle the segment's grid-plane projection passes within
			// 0.02 grid cells of (the walk's slack is 0.001 cells).
			const auto gridU = [&](const btVector3& p)
			{ return double(p[a0] / scaling[a0]) + 0.5 * (f.grid.width - 1); };
			const auto gridV = [&](const btVector3& p)
			{ return double(p[a1] / scaling[a1]) + 0.5 * (f.grid.length - 1); };
			for (const auto& entry : collector.triangles)
			{
				const int x = entry.first.first / 2, y = entry.first.second;
				EXPECT_TRUE(segmentNearRect(gridU(from), gridV(from), gridU(to), gridV(to), x, x + 1, y, y + 1, 0.02))
				    << "ray " << r << " reported far cell " << x << "," << y;
			}
		}
		EXPECT_GT(hitsChecked, 60);  // the rays do cross the surface
	}
}

TEST(HeightfieldTerrainShapeTest, RayOutsideTheGridReportsNothing)
{
	Fixture f;
	f.build(PHY_FLOAT, 5, 5, 1, 2);
	Collector collector;
	f.shape->performRaycast(&collector, btVector3(10, 0, -10), btVector3(10, 0, 10));
	f.shape->performRaycast(&collector, btVector3(0, 100, 0), btVector3(1, 50, 1));  // above all heights
	EXPECT_TRUE(collector.triangles.empty());
}

TEST(HeightfieldTerrainShapeTest, LegacyConstructorScalesBytesByMaxHeightOver65535)
{
	const unsigned char bytes[4] = {0, 255, 128, 64};
	btHeightfieldTerrainShape shape(2, 2, bytes, btScalar(65535), 1, false, false);
	btVector3 v;
	shape.getVertex(1, 0, v);
	// Heights 0..65535 declared, origin at 32767.5: sample 255 -> 255 - 32767.5.
	EXPECT_NEAR(double(v.y()), 255.0 - 32767.5, 0.01);
	const float floats[4] = {1, 2, 3, 4};
	btHeightfieldTerrainShape floatShape(2, 2, floats, 4, 2, true, false);
	floatShape.getVertex(1, 1, v);
	EXPECT_NEAR(double(v.z()), 4.0 - 2.0, 1e-6);
	EXPECT_EQ(2, floatShape.getUpAxis());
}

TEST(HeightfieldTerrainShapeTest, TypedConstructorsReadShortAndByteSamples)
{
	const short shorts[4] = {-100, 100, 0, 50};
	btHeightfieldTerrainShape shortShape(2, 2, shorts, btScalar(0.1), -10, 10, 1, false);
	btVector3 v;
	shortShape.getVertex(0, 0, v);
	EXPECT_NEAR(double(v.y()), -10.0, 1e-5);
	const unsigned char bytes[4] = {0, 200, 0, 0};
	btHeightfieldTerrainShape byteShape(2, 2, bytes, btScalar(0.05), 0, 10, 1, false);
	byteShape.getVertex(1, 0, v);
	EXPECT_NEAR(double(v.y()), 10.0 - 5.0, 1e-5);
}

TEST(HeightfieldTerrainShapeTest, LegacyAndTypedCallsWithFloatPointersPickTheIntendedConstructor)
{
	// Bullet 2.x legacy calls and Bullet 3 typed calls with a float or double pointer must both compile and
	// mean what they meant there.
	float floats[4] = {1, 2, 3, 4};
	double doubles[4] = {1, 2, 3, 4};
	const float maxHeight = 8;
	btHeightfieldTerrainShape legacyFloat(2, 2, floats, maxHeight, 1, true, false);  // heights 0..8, as floats
	btHeightfieldTerrainShape typedFloat(2, 2, floats, btScalar(-4), btScalar(4), 1, false);
	btHeightfieldTerrainShape typedDouble(2, 2, doubles, btScalar(0), btScalar(4), 2, false);
	btHeightfieldTerrainShape legacyDouble(2, 2, doubles, btScalar(8), 1, true, false);
	btVector3 v;
	legacyFloat.getVertex(1, 1, v);
	EXPECT_NEAR(double(v.y()), 4.0 - 4.0, 1e-6);
	typedFloat.getVertex(1, 1, v);
	EXPECT_NEAR(double(v.y()), 4.0, 1e-6);
	typedDouble.getVertex(0, 1, v);
	EXPECT_NEAR(double(v.z()), 3.0 - 2.0, 1e-6);
	EXPECT_EQ(2, typedDouble.getUpAxis());
	// A legacy-style call with a double pointer resolves to the legacy overload (upAxis is its fifth argument).
	EXPECT_EQ(1, legacyDouble.getUpAxis());
}

TEST(HeightfieldTerrainShapeTest, IdentityInertiaAndUserData)
{
	const float heights[4] = {0, 0, 0, 0};
	btHeightfieldTerrainShape shape(2, 2, heights, 1, -1, 1, 1, PHY_FLOAT, false);
	EXPECT_STREQ("HEIGHTFIELD", shape.getName());
	EXPECT_EQ(int(TERRAIN_SHAPE_PROXYTYPE), shape.getShapeType());
	EXPECT_TRUE(shape.isConcave());
	btVector3 inertia(1, 1, 1);
	shape.calculateLocalInertia(10, inertia);
	EXPECT_TRUE(vectorsNear(inertia, btVector3(0, 0, 0), 0));
	EXPECT_EQ(btScalar(0), shape.getUserValue3());
	shape.setUserValue3(btScalar(2.5));
	EXPECT_EQ(btScalar(2.5), shape.getUserValue3());
	EXPECT_EQ(nullptr, shape.getTriangleInfoMap());
	btTriangleInfoMap map;
	shape.setTriangleInfoMap(&map);
	EXPECT_EQ(&map, shape.getTriangleInfoMap());
	shape.buildAccelerator();
	shape.clearAccelerator();
}

TEST(HeightfieldTerrainShapeTest, NonFiniteSampleSkipsOnlyItsTriangles)
{
	Fixture f;
	f.build(PHY_FLOAT, 5, 5, 1, 31);
	f.floats[2 * 5 + 2] = std::numeric_limits<float>::quiet_NaN();
	f.floats[0] = std::numeric_limits<float>::infinity();
	f.grid.heights[2 * 5 + 2] = std::numeric_limits<double>::quiet_NaN();
	f.grid.heights[0] = std::numeric_limits<double>::infinity();
	const btScalar big = BT_LARGE_FLOAT;
	f.checkQuery(btVector3(-big, -big, -big), btVector3(big, big, big));
	btVector3 aabbMin, aabbMax;
	f.shape->getAabb(btTransform::getIdentity(), aabbMin, aabbMax);
	EXPECT_TRUE(isFiniteVector(aabbMin) && isFiniteVector(aabbMax));
	Collector collector;
	f.shape->performRaycast(&collector, btVector3(0, 10, 0), btVector3(0, -10, 0));  // through sample (2, 2)
	for (const auto& entry : collector.triangles)
		for (int i = 0; i < 3; ++i) EXPECT_TRUE(isFiniteVector(entry.second.v[i]));
}

TEST(HeightfieldTerrainShapeTest, SamplesOutsideTheDeclaredRangeAreClamped)
{
	const float heights[4] = {-50, 50, 0, 0};
	btHeightfieldTerrainShape shape(2, 2, heights, 1, -1, 1, 1, PHY_FLOAT, false);
	btVector3 v;
	shape.getVertex(0, 0, v);
	EXPECT_NEAR(double(v.y()), -1.0, 1e-6);
	shape.getVertex(1, 0, v);
	EXPECT_NEAR(double(v.y()), 1.0, 1e-6);
}

namespace
{
void expectEmpty(const btHeightfieldTerrainShape& shape)
{
	Collector collector;
	const btScalar big = BT_LARGE_FLOAT;
	shape.processAllTriangles(&collector, btVector3(-big, -big, -big), btVector3(big, big, big));
	shape.performRaycast(&collector, btVector3(0, 10, 0), btVector3(0, -10, 0));
	EXPECT_TRUE(collector.triangles.empty());
	btVector3 aabbMin, aabbMax;
	shape.getAabb(btTransform(btQuaternion::getIdentity(), btVector3(1, 2, 3)), aabbMin, aabbMax);
	EXPECT_TRUE(vectorsNear(aabbMin, btVector3(1, 2, 3), 0));
	EXPECT_TRUE(vectorsNear(aabbMax, btVector3(1, 2, 3), 0));
}
}  // namespace

TEST(HeightfieldTerrainShapeTest, BadConstructorInputGivesAnEmptyShape)
{
	const float heights[6] = {0, 1, 2, 3, 4, 5};
	const int ints[4] = {0, 1, 2, 3};
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btHeightfieldTerrainShape(1, 6, heights, 1, 0, 5, 1, PHY_FLOAT, false), "assertion failed");
	EXPECT_DEATH(btHeightfieldTerrainShape(3, 2, static_cast<const void*>(nullptr), 1, 0, 5, 1, PHY_FLOAT, false),
	             "assertion failed");
	EXPECT_DEATH(btHeightfieldTerrainShape(2, 2, ints, 1, 0, 5, 1, PHY_INTEGER, false), "assertion failed");
	(void)expectEmpty;
#else
	expectEmpty(btHeightfieldTerrainShape(1, 6, heights, 1, 0, 5, 1, PHY_FLOAT, false));
	expectEmpty(btHeightfieldTerrainShape(0, 0, heights, 1, 0, 5, 1, PHY_FLOAT, false));
	expectEmpty(btHeightfieldTerrainShape(3, 2, static_cast<const void*>(nullptr), 1, 0, 5, 1, PHY_FLOAT, false));
	expectEmpty(btHeightfieldTerrainShape(2, 2, ints, 1, 0, 5, 1, PHY_INTEGER, false));
	expectEmpty(btHeightfieldTerrainShape(3, 2, heights, 1, 0, std::numeric_limits<btScalar>::quiet_NaN(), 1, PHY_FLOAT,
	                                      false));
#endif
}

TEST(HeightfieldTerrainShapeTest, SwappedHeightRangeAndBadUpAxisAreRepaired)
{
	const float heights[6] = {0, 1, 2, 3, 4, 5};
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btHeightfieldTerrainShape(3, 2, heights, 1, 5, 0, 1, PHY_FLOAT, false), "assertion failed");
	EXPECT_DEATH(btHeightfieldTerrainShape(3, 2, heights, 1, 0, 5, 3, PHY_FLOAT, false), "assertion failed");
#else
	btHeightfieldTerrainShape swapped(3, 2, heights, 1, 5, 0, 1, PHY_FLOAT, false);
	btHeightfieldTerrainShape reference(3, 2, heights, 1, 0, 5, 1, PHY_FLOAT, false);
	btHeightfieldTerrainShape badAxis(3, 2, heights, 1, 0, 5, 7, PHY_FLOAT, false);
	EXPECT_EQ(1, badAxis.getUpAxis());
	for (int y = 0; y < 2; ++y)
		for (int x = 0; x < 3; ++x)
		{
			btVector3 a, b, c;
			swapped.getVertex(x, y, a);
			reference.getVertex(x, y, b);
			badAxis.getVertex(x, y, c);
			EXPECT_TRUE(vectorsNear(a, b, 0));
			EXPECT_TRUE(vectorsNear(c, b, 0));
		}
#endif
}

TEST(HeightfieldTerrainShapeTest, BadQueriesAndScalingAreRejected)
{
	const float heights[4] = {0, 1, 2, 3};
	btHeightfieldTerrainShape shape(2, 2, heights, 1, 0, 3, 1, PHY_FLOAT, false);
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
#if CALIBER_ASSERTS_ENABLED
	Collector collector;
	EXPECT_DEATH(shape.processAllTriangles(&collector, btVector3(nan, 0, 0), btVector3(1, 1, 1)), "assertion failed");
	EXPECT_DEATH(shape.performRaycast(&collector, btVector3(nan, 0, 0), btVector3(1, 1, 1)), "assertion failed");
	EXPECT_DEATH(shape.setLocalScaling(btVector3(1, 0, 1)), "assertion failed");
#else
	Collector collector;
	shape.processAllTriangles(&collector, btVector3(nan, 0, 0), btVector3(1, 1, 1));
	shape.performRaycast(&collector, btVector3(nan, 0, 0), btVector3(1, 1, 1));
	shape.processAllTriangles(nullptr, btVector3(0, 0, 0), btVector3(1, 1, 1));
	EXPECT_TRUE(collector.triangles.empty());
	shape.setLocalScaling(btVector3(1, 0, 1));
	shape.setLocalScaling(btVector3(nan, 1, 1));
	EXPECT_TRUE(vectorsNear(shape.getLocalScaling(), btVector3(1, 1, 1), 0));
#endif
}

TEST(HeightfieldTerrainShapeTest, WindingFacesTheOpenSideUnderMirroringScalingAndFlip)
{
	// Normal along +up for positive scaling; a mirror in a grid axis keeps it, a mirror of the up axis turns the
	// terrain over so the open side (towards higher raw heights) and the normal point along -up;
	// setFlipTriangleWinding reverses all of this.
	const float heights[9] = {0, 1, 0, 2, 1, 3, 1, 0, 2};
	struct Case
	{
		btVector3 scaling;
		bool flipWinding;
		btScalar expectedSign;
	};
	const Case cases[] = {{btVector3(1, 1, 1), false, 1},   {btVector3(-1, 1, 1), false, 1},
	                      {btVector3(1, -1, 1), false, -1}, {btVector3(1, 1, -2), false, 1},
	                      {btVector3(1, 1, 1), true, -1},   {btVector3(1, -1, 1), true, 1}};
	for (int upAxis = 0; upAxis < 3; ++upAxis)
		for (const Case& c : cases)
		{
			btVector3 scaling = c.scaling;
			// Move the up-axis mirror of the table onto this up axis (the table is written for up axis 1).
			std::swap(scaling[1], scaling[upAxis]);
			SCOPED_TRACE(::testing::Message() << "up " << upAxis << " scaling " << scaling.x() << "," << scaling.y()
			                                  << "," << scaling.z() << " flip " << c.flipWinding);
			btHeightfieldTerrainShape shape(3, 3, heights, 1, 0, 3, upAxis, PHY_FLOAT, false);
			shape.setLocalScaling(scaling);
			shape.setFlipTriangleWinding(c.flipWinding);
			Collector collector;
			const btScalar big = BT_LARGE_FLOAT;
			shape.processAllTriangles(&collector, btVector3(-big, -big, -big), btVector3(big, big, big));
			ASSERT_EQ(size_t(8), collector.triangles.size());
			for (const auto& entry : collector.triangles)
			{
				const Triangle& t = entry.second;
				const btVector3 normal = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
				EXPECT_GT(double(normal[upAxis] * c.expectedSign), 0.0) << "normal " << normal[upAxis];
			}
		}
}
