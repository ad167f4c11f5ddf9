// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// SimplexDemo: the simplex bookkeeping inside GJK, headless. btVoronoiSimplexSolver receives the
// vertices of a tetrahedron one at a time, as GJK would add them, and after each one reports the point
// of the simplex closest to the origin, the vertices that point uses and their barycentric weights.
// Run 1 grows a point, a segment, a triangle and a tetrahedron that contains the origin; run 2 puts the
// apex on the far side, so the solver must drop it again. Every answer is compared with the one worked
// out by hand (in the comments below); the demo exits 1 when any of them disagrees. --png draws the
// three runs side by side: each simplex as a solid, the origin (red) and the closest point the solver
// found (green) joined by a line (docs/demos.md).

#include "DemoPictures.h"
#include "DemoPrograms.h"
#include "ShapeMesher.h"
#include "WorldScene.h"
#include "btBulletCollisionCommon.h"

#include <stdio.h>

namespace
{
/// One step of a run: the vertex added and what the solver must answer afterwards.
struct SimplexStep
{
	char label;
	btVector3 vertex;
	btVector3 expectedClosest;
	const char* expectedUsed;     // labels of the vertices that must remain, in any order
	btScalar expectedWeights[4];  // weight of each remaining vertex, in the order of expectedUsed
};

/// The solver works in double internally, so float builds are limited by btScalar rounding only.
const btScalar kTolerance = btScalar(1e-5);

/// Which of the step vertices seen so far equals w (the solver stores the vertices it is given).
char labelOf(const btVector3& w, const SimplexStep* steps, int count)
{
	for (int i = 0; i < count; ++i)
	{
		if ((steps[i].vertex - w).length() <= kTolerance)
		{
			return steps[i].label;
		}
	}
	return '?';
}

/// Adds the steps' vertices one by one; returns true when every answer matches the expected one.
bool runSimplex(const char* title, const SimplexStep* steps, int count, btVector3& lastClosest)
{
	printf("%s\n", title);
	btVoronoiSimplexSolver solver;
	solver.reset();
	bool allGood = true;
	char labelsBefore[5] = {0, 0, 0, 0, 0};
	for (int stepIndex = 0; stepIndex < count; ++stepIndex)
	{
		const SimplexStep& step = steps[stepIndex];
		// The labels in the solver's own order, before closest() reduces the simplex: its barycentric
		// result refers to this order.
		btVector3 pBuf[VORONOI_SIMPLEX_MAX_VERTS], qBuf[VORONOI_SIMPLEX_MAX_VERTS], yBuf[VORONOI_SIMPLEX_MAX_VERTS];
		const int before = solver.getSimplex(pBuf, qBuf, yBuf);
		for (int i = 0; i < before; ++i)
		{
			labelsBefore[i] = labelOf(yBuf[i], steps, stepIndex);
		}
		labelsBefore[before] = step.label;

		// GJK adds w = p - q; here B's support point is the origin, so w = p.
		solver.addVertex(step.vertex, step.vertex, btVector3(0, 0, 0));
		btVector3 closest;
		const bool valid = solver.closest(closest);
		lastClosest = closest;

		printf("  add %c (%5.2f %5.2f %5.2f): closest point (%7.4f %7.4f %7.4f), distance %.4f, uses", step.label,
		       double(step.vertex.x()), double(step.vertex.y()), double(step.vertex.z()), double(closest.x()),
		       double(closest.y()), double(closest.z()), double(closest.length()));
		const btSubSimplexClosestResult& bc = solver.m_cachedBC;
		const bool usedFlags[4] = {bc.m_usedVertices.usedVertexA != 0, bc.m_usedVertices.usedVertexB != 0,
		                           bc.m_usedVertices.usedVertexC != 0, bc.m_usedVertices.usedVertexD != 0};
		bool weightsGood = true;
		int usedCount = 0;
		for (int i = 0; i <= before; ++i)
		{
			if (!usedFlags[i])
			{
				continue;
			}
			++usedCount;
			printf(" %c=%.4f", labelsBefore[i], double(bc.m_barycentricCoords[i]));
			// Find this label among the expected ones and compare its weight.
			bool found = false;
			for (int e = 0; step.expectedUsed[e] != 0; ++e)
			{
				if (step.expectedUsed[e] == labelsBefore[i])
				{
					found = true;
					weightsGood =
					    weightsGood && btFabs(bc.m_barycentricCoords[i] - step.expectedWeights[e]) <= kTolerance;
				}
			}
			weightsGood = weightsGood && found;
		}
		int expectedCount = 0;
		while (step.expectedUsed[expectedCount] != 0)
		{
			++expectedCount;
		}
		weightsGood = weightsGood && usedCount == expectedCount && solver.numVertices() == expectedCount;
		const bool pointGood = valid && (closest - step.expectedClosest).length() <= kTolerance;
		printf("%s\n", solver.fullSimplex() ? "  (origin inside)" : "");
		if (!pointGood || !weightsGood)
		{
			printf("  WRONG: expected closest point (%.4f %.4f %.4f) using %s\n", double(step.expectedClosest.x()),
			       double(step.expectedClosest.y()), double(step.expectedClosest.z()), step.expectedUsed);
			allGood = false;
		}
	}
	return allGood;
}
}  // namespace

int caliber::demo::simplexDemo(int argc, char** argv)
{
	caliber::demo::DemoPictures pictures(argc, argv, "SimplexDemo");
	if (!pictures.ok()) return pictures.exitCode();

	// Base triangle in the plane z = 1: A(2, 1), B(-2, 1), C(0, -3). The origin projects to (0, 0, 1),
	// which lies inside it.
	const btVector3 a(2, 1, 1), b(-2, 1, 1), c(0, -3, 1);
	// Segment AB: the closest point is its midpoint (0, 1, 1), weights 1/2 each.
	// Triangle ABC: (0, 0) = wa A + wb B + wc C with wa = wb by symmetry; y: 2 wa - 3 wc = 0 and
	// 2 wa + wc = 1 give wa = wb = 3/8, wc = 1/4.
	// Apex D(0, 0, -1): the segment from (0, 0, 1) to D passes through the origin at its midpoint, so
	// the origin is inside, with weights 1/2 of the triangle's (3/16, 3/16, 1/8) and 1/2 for D.
	const SimplexStep inside[] = {
	    {'A', a, a, "A", {1, 0, 0, 0}},
	    {'B', b, btVector3(0, 1, 1), "AB", {btScalar(0.5), btScalar(0.5), 0, 0}},
	    {'C', c, btVector3(0, 0, 1), "ABC", {btScalar(0.375), btScalar(0.375), btScalar(0.25), 0}},
	    {'D',
	     btVector3(0, 0, -1),
	     btVector3(0, 0, 0),
	     "ABCD",
	     {btScalar(0.1875), btScalar(0.1875), btScalar(0.125), btScalar(0.5)}},
	};
	// Apex E(0, 0, 3): the whole tetrahedron lies in z >= 1, so the face ABC stays closest and E is
	// dropped again.
	const SimplexStep outside[] = {
	    {'A', a, a, "A", {1, 0, 0, 0}},
	    {'B', b, btVector3(0, 1, 1), "AB", {btScalar(0.5), btScalar(0.5), 0, 0}},
	    {'C', c, btVector3(0, 0, 1), "ABC", {btScalar(0.375), btScalar(0.375), btScalar(0.25), 0}},
	    {'E', btVector3(0, 0, 3), btVector3(0, 0, 1), "ABC", {btScalar(0.375), btScalar(0.375), btScalar(0.25), 0}},
	};
	// A vertex region: after A, adding F(4, 3, 1) beyond A leaves A alone as the closest feature
	// (the origin's projection onto line AF falls before A), so F is dropped.
	const SimplexStep vertexRegion[] = {
	    {'A', a, a, "A", {1, 0, 0, 0}},
	    {'F', btVector3(4, 3, 1), a, "A", {1, 0, 0, 0}},
	};

	btVector3 closest[3];
	bool good = runSimplex("1. Tetrahedron ABCD around the origin, vertex by vertex", inside, 4, closest[0]);
	good = runSimplex("2. Tetrahedron ABCE beside the origin: E is dropped", outside, 4, closest[1]) && good;
	good =
	    runSimplex("3. Segment AF pointing away: the closest feature is vertex A", vertexRegion, 2, closest[2]) && good;

	printf(good ? "All closest points and weights match the analytic answers.\n" : "MISMATCH (see above)\n");
	if (pictures.wanted())
	{
		// The runs side by side, 9 m apart along x; each simplex in the solver's frame (origin at its own origin).
		caliber::demo::Scene scene;
		const SimplexStep* runs[3] = {inside, outside, vertexRegion};
		const int counts[3] = {4, 4, 2};
		for (int r = 0; r < 3; ++r)
		{
			const btVector3 shift(btScalar(9 * r), 0, 0);
			btConvexHullShape simplex;
			for (int i = 0; i < counts[r]; ++i) simplex.addPoint(runs[r][i].vertex, false);
			simplex.recalcLocalAabb();
			caliber::demo::MeshStyle style;
			style.color = caliber::demo::paletteColor(r + 1);
			caliber::demo::addShape(scene, &simplex, btTransform(btQuaternion::getIdentity(), shift), style);
			for (int i = 0; i < counts[r]; ++i)
				for (int k = i + 1; k < counts[r]; ++k)
					scene.addLine(runs[r][i].vertex + shift, runs[r][k].vertex + shift, btVector3(0.1f, 0.1f, 0.1f));
			scene.addPoint(shift, btVector3(0.9f, 0.1f, 0.1f));
			scene.addPoint(closest[r] + shift, btVector3(0.1f, 0.7f, 0.1f));
			scene.addLine(shift, closest[r] + shift, btVector3(0.1f, 0.6f, 0.1f));
		}
		pictures.setViewDirection(btVector3(-0.3f, -0.7f, -0.6f));
		pictures.capture(scene);
	}
	return pictures.finish(good ? 0 : 1);
}
