// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include <random>

#include "BulletCollision/NarrowPhaseCollision/btSimplexSolverInterface.h"
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"

namespace
{
class Random
{
public:
	explicit Random(unsigned seed) : m_engine(seed) {}
	btScalar uniform(btScalar lo, btScalar hi)
	{
		return btScalar(std::uniform_real_distribution<double>(lo, hi)(m_engine));
	}
	btVector3 vector(btScalar range)
	{
		return btVector3(uniform(-range, range), uniform(-range, range), uniform(-range, range));
	}

private:
	std::mt19937 m_engine;
};

// Values are of order 1..4; a closest point is a few dozen operations away from the inputs, and the flat
// fallback of a nearly degenerate simplex adds at most the simplex's tiny thickness. 4096 ulps of the
// largest coordinate is far above rounding and far below any wrong Voronoi region (errors of order 1).
const btScalar kTolerance = btScalar(4096) * SIMD_EPSILON * btScalar(4);

// Reference: the closest point to the origin of the convex hull of pts, by brute force over every
// subset of the points (each subset's affine hull projection is accepted when its barycentric weights are
// all non-negative). Independent of the Voronoi-region code under test.
btVector3 bruteForceClosest(const btVector3* pts, int n)
{
	btVector3 best = pts[0];
	for (int mask = 1; mask < (1 << n); ++mask)
	{
		int idx[4];
		int m = 0;
		for (int i = 0; i < n; ++i)
			if (mask & (1 << i)) idx[m++] = i;
		if (m == 1)
		{
			if (pts[idx[0]].length2() < best.length2()) best = pts[idx[0]];
			continue;
		}
		if (m == 4) continue;  // a full tetrahedron is checked by the inside test below
		// Solve the normal equations for the projection of the origin on the affine hull (double).
		double e[2][3] = {{0, 0, 0}, {0, 0, 0}};
		for (int k = 0; k < m - 1; ++k)
			for (int c = 0; c < 3; ++c) e[k][c] = double(pts[idx[k + 1]][c]) - double(pts[idx[0]][c]);
		double g[2][2] = {{0, 0}, {0, 0}}, r[2] = {0, 0};
		for (int a = 0; a < m - 1; ++a)
		{
			r[a] = 0;
			for (int c = 0; c < 3; ++c) r[a] -= e[a][c] * double(pts[idx[0]][c]);
			for (int b = 0; b < m - 1; ++b)
			{
				g[a][b] = 0;
				for (int c = 0; c < 3; ++c) g[a][b] += e[a][c] * e[b][c];
			}
		}
		double t[2] = {0, 0};
		if (m == 2)
		{
			if (g[0][0] <= 1e-300) continue;
			t[0] = r[0] / g[0][0];
		}
		else
		{
			const double det = g[0][0] * g[1][1] - g[0][1] * g[1][0];
			if (std::fabs(det) <= 1e-12 * g[0][0] * g[1][1]) continue;
			t[0] = (r[0] * g[1][1] - g[0][1] * r[1]) / det;
			t[1] = (g[0][0] * r[1] - g[1][0] * r[0]) / det;
		}
		if (t[0] < 0 || t[1] < 0 || t[0] + t[1] > 1) continue;
		btVector3 p = pts[idx[0]];
		for (int k = 0; k < m - 1; ++k)
			p += btVector3(btScalar(e[k][0]), btScalar(e[k][1]), btScalar(e[k][2])) * btScalar(t[k]);
		if (p.length2() < best.length2()) best = p;
	}
	if (n == 4)
	{
		// Origin inside the tetrahedron: the same sign of each face's volume with the origin.
		const btVector3& a = pts[0];
		const double v = double((pts[1] - a).dot((pts[2] - a).cross(pts[3] - a)));
		const double v0 = double((pts[1] - a).dot((pts[2] - a).cross(-a)));
		const double v1 = double((pts[1] - a).dot((-a).cross(pts[3] - a)));
		const double v2 = double((-a).dot((pts[2] - a).cross(pts[3] - a)));
		const double v3 = v - v0 - v1 - v2;
		const double scale = double((pts[1] - a).length() * (pts[2] - a).length() * (pts[3] - a).length());
		if (std::fabs(v) > 1e-3 * scale && v0 / v >= 0 && v1 / v >= 0 && v2 / v >= 0 && v3 / v >= 0)
			best.setValue(0, 0, 0);
	}
	return best;
}

// Feeds pts to a fresh solver and checks closest() against the brute force, the optimality condition
// v . (w - v) >= 0 for every input vertex, and the reconstruction of v from the support points.
void checkSimplex(const btVector3* pts, int n, const char* what, int trial)
{
	btVoronoiSimplexSolver solver;
	for (int i = 0; i < n; ++i) solver.addVertex(pts[i], pts[i] * btScalar(2), pts[i]);
	btVector3 v;
	ASSERT_TRUE(solver.closest(v)) << what << " trial " << trial;
	const btVector3 expected = bruteForceClosest(pts, n);
	EXPECT_NEAR(v.length(), expected.length(), kTolerance) << what << " trial " << trial;
	EXPECT_LE((v - expected).length(), btScalar(64) * kTolerance) << what << " trial " << trial;
	for (int i = 0; i < n; ++i)
		EXPECT_GE(v.dot(pts[i] - v), -kTolerance * btScalar(16)) << what << " trial " << trial << " vertex " << i;
	// p = 2w and q = w were stored, so p1 - p2 must reproduce v.
	btVector3 p1, p2;
	solver.compute_points(p1, p2);
	EXPECT_LE((p1 - p2 - v).length(), btScalar(8) * kTolerance) << what << " trial " << trial;
	EXPECT_GE(solver.numVertices(), 1);
	EXPECT_LE(solver.numVertices(), n);
}
}  // namespace

TEST(VoronoiSimplexSolver, ClosestPointOfRandomPointsMatchesBruteForce)
{
	Random rng(11);
	for (int trial = 0; trial < 200; ++trial)
	{
		const btVector3 p = rng.vector(2);
		checkSimplex(&p, 1, "point", trial);
	}
}

TEST(VoronoiSimplexSolver, ClosestPointOfRandomSegmentsMatchesBruteForce)
{
	Random rng(12);
	for (int trial = 0; trial < 1000; ++trial)
	{
		btVector3 pts[2] = {rng.vector(2), rng.vector(2)};
		checkSimplex(pts, 2, "segment", trial);
	}
}

TEST(VoronoiSimplexSolver, ClosestPointOfRandomTrianglesMatchesBruteForce)
{
	Random rng(13);
	for (int trial = 0; trial < 2000; ++trial)
	{
		btVector3 pts[3] = {rng.vector(2), rng.vector(2), rng.vector(2)};
		checkSimplex(pts, 3, "triangle", trial);
	}
}

TEST(VoronoiSimplexSolver, ClosestPointOfRandomTetrahedraMatchesBruteForce)
{
	Random rng(14);
	int insideCount = 0;
	for (int trial = 0; trial < 2000; ++trial)
	{
		btVector3 pts[4] = {rng.vector(2), rng.vector(2), rng.vector(2), rng.vector(2)};
		checkSimplex(pts, 4, "tetrahedron", trial);
		if (bruteForceClosest(pts, 4).isZero()) ++insideCount;
	}
	// The sample must exercise the inside case too.
	EXPECT_GT(insideCount, 20);
}

TEST(VoronoiSimplexSolver, OriginInsideTetrahedronKeepsFullSimplexWithValidWeights)
{
	btVoronoiSimplexSolver solver;
	const btVector3 pts[4] = {btVector3(1, 1, 1), btVector3(-1, -1, 1), btVector3(-1, 1, -1), btVector3(1, -1, -1)};
	for (const btVector3& p : pts) solver.addVertex(p, p, btVector3(0, 0, 0));
	btVector3 v;
	ASSERT_TRUE(solver.closest(v));
	EXPECT_TRUE(v.isZero());
	EXPECT_TRUE(solver.fullSimplex());
	EXPECT_TRUE(solver.m_cachedBC.isValid());
	btScalar sum = 0;
	for (int i = 0; i < 4; ++i) sum += solver.m_cachedBC.m_barycentricCoords[i];
	EXPECT_NEAR(sum, 1, btScalar(16) * SIMD_EPSILON);
}

TEST(VoronoiSimplexSolver, DegenerateSimplicesMatchBruteForce)
{
	Random rng(15);
	for (int trial = 0; trial < 500; ++trial)
	{
		const btVector3 a = rng.vector(2);
		const btVector3 b = rng.vector(2);
		const btVector3 c = rng.vector(2);
		const btScalar s = rng.uniform(-1, 2);
		const btScalar t = rng.uniform(-1, 2);
		// Duplicate vertices.
		const btVector3 dup[3] = {a, a, b};
		checkSimplex(dup, 3, "duplicate triangle", trial);
		const btVector3 same[2] = {a, a};
		checkSimplex(same, 2, "zero-length segment", trial);
		// Collinear triangle and tetrahedron.
		const btVector3 line[4] = {a, a.lerp(b, s), b, a.lerp(b, t)};
		checkSimplex(line, 3, "collinear triangle", trial);
		checkSimplex(line, 4, "collinear tetrahedron", trial);
		// Coplanar tetrahedron, also with the origin in its plane.
		const btVector3 plane[4] = {a, b, c, a + (b - a) * s + (c - a) * t};
		checkSimplex(plane, 4, "coplanar tetrahedron", trial);
		const btVector3 shift = (plane[0] + plane[1] + plane[2]) / btScalar(3);
		const btVector3 throughOrigin[4] = {a - shift, b - shift, c - shift, plane[3] - shift};
		checkSimplex(throughOrigin, 4, "coplanar tetrahedron through origin", trial);
		// All four the same point.
		const btVector3 point[4] = {c, c, c, c};
		checkSimplex(point, 4, "point tetrahedron", trial);
	}
}

TEST(VoronoiSimplexSolver, ReducesToTheSupportingFeature)
{
	btVoronoiSimplexSolver solver;
	solver.addVertex(btVector3(1, -1, 0), btVector3(1, -1, 0), btVector3(0, 0, 0));
	solver.addVertex(btVector3(1, 1, 0), btVector3(1, 1, 0), btVector3(0, 0, 0));
	solver.addVertex(btVector3(3, 0, 0), btVector3(3, 0, 0), btVector3(0, 0, 0));
	btVector3 v;
	ASSERT_TRUE(solver.closest(v));
	EXPECT_NEAR(v.x(), 1, SIMD_EPSILON * 4);
	EXPECT_NEAR(v.y(), 0, SIMD_EPSILON * 4);
	EXPECT_EQ(solver.numVertices(), 2);
	EXPECT_NEAR(solver.maxVertex(), 2, SIMD_EPSILON * 8);
	btVector3 p[5], q[5], y[5];
	EXPECT_EQ(solver.getSimplex(p, q, y), 2);
	btVector3 backup;
	solver.backup_closest(backup);
	EXPECT_EQ(backup, v);
}

TEST(VoronoiSimplexSolver, InSimplexUsesTheSquaredThreshold)
{
	btVoronoiSimplexSolver solver;
	EXPECT_TRUE(solver.emptySimplex());
	EXPECT_EQ(solver.getEqualVertexThreshold(), btScalar(VORONOI_DEFAULT_EQUAL_VERTEX_THRESHOLD));
	solver.setEqualVertexThreshold(btScalar(0.01));
	solver.addVertex(btVector3(1, 0, 0), btVector3(1, 0, 0), btVector3(0, 0, 0));
	EXPECT_FALSE(solver.emptySimplex());
	EXPECT_TRUE(solver.inSimplex(btVector3(btScalar(1.05), 0, 0)));  // squared distance 0.0025
	EXPECT_FALSE(solver.inSimplex(btVector3(btScalar(1.2), 0, 0)));  // squared distance 0.04
	solver.reset();
	EXPECT_TRUE(solver.emptySimplex());
	btVector3 v;
	EXPECT_FALSE(solver.closest(v));
	EXPECT_TRUE(v.isZero());
}

TEST(VoronoiSimplexSolver, NonFiniteVertexGivesInvalidClosestAndZeroPoint)
{
	btVoronoiSimplexSolver solver;
	solver.addVertex(btVector3(BT_NAN, 0, 0), btVector3(0, 0, 0), btVector3(0, 0, 0));
	btVector3 v(5, 5, 5);
	EXPECT_FALSE(solver.closest(v));
	EXPECT_TRUE(v.isZero());
	btVector3 p1, p2;
	solver.compute_points(p1, p2);
	EXPECT_TRUE(p1.isZero());
	EXPECT_TRUE(p2.isZero());
}

TEST(VoronoiSimplexSolverDeathTest, AddingASixthVertexAsserts)
{
	btSimplexSolverInterface solver;
	for (int i = 0; i < VORONOI_SIMPLEX_MAX_VERTS; ++i)
		solver.addVertex(btVector3(btScalar(i), 1, 0), btVector3(btScalar(i), 1, 0), btVector3(0, 0, 0));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(solver.addVertex(btVector3(9, 9, 9), btVector3(9, 9, 9), btVector3(0, 0, 0)), "assertion failed");
#else
	// Documented release behaviour: the extra vertex is ignored.
	solver.addVertex(btVector3(9, 9, 9), btVector3(9, 9, 9), btVector3(0, 0, 0));
	EXPECT_EQ(solver.numVertices(), VORONOI_SIMPLEX_MAX_VERTS);
#endif
}
