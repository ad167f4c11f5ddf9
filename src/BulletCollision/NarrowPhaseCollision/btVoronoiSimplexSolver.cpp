// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"

// Closest point of a simplex to the origin by Voronoi regions (after Ericson, "Real-Time Collision
// Detection", ch. 5). Degenerate simplices never divide by a vanishing quantity: the convex hull of
// collinear points is the union of their segments and the hull of coplanar points is the union of
// their triangles (Caratheodory), so a flat simplex is answered exactly by its best sub-simplex.

namespace
{
// A closest point in terms of vertex indices 0..3 of the simplex being examined.
struct ClosestFeature
{
	btVector3 point;
	btScalar weight[4];
	int usedMask;  // bit i set: vertex i has a weight
	bool degenerate;
};

void setVertex(ClosestFeature& out, const btVector3* w, int i)
{
	out.point = w[i];
	out.weight[0] = out.weight[1] = out.weight[2] = out.weight[3] = btScalar(0);
	out.weight[i] = btScalar(1);
	out.usedMask = 1 << i;
}

void closestOnSegment(const btVector3* w, int ia, int ib, ClosestFeature& out)
{
	const btVector3& a = w[ia];
	const btVector3 ab = w[ib] - a;
	const btScalar lengthSquared = ab.length2();
	const btScalar t = -a.dot(ab);
	out.degenerate = false;
	if (!(lengthSquared > btScalar(0)))
	{
		// Both ends coincide: the segment is the point a.
		out.degenerate = true;
		setVertex(out, w, ia);
		return;
	}
	if (t <= btScalar(0))
	{
		setVertex(out, w, ia);
		return;
	}
	if (t >= lengthSquared)
	{
		setVertex(out, w, ib);
		return;
	}
	const btScalar s = t / lengthSquared;
	out.weight[0] = out.weight[1] = out.weight[2] = out.weight[3] = btScalar(0);
	out.weight[ia] = btScalar(1) - s;
	out.weight[ib] = s;
	out.point = a + ab * s;
	out.usedMask = (1 << ia) | (1 << ib);
}

// Keeps in best whichever of best and candidate lies closer to the origin.
void keepCloser(ClosestFeature& best, const ClosestFeature& candidate, bool& haveBest)
{
	if (!haveBest || candidate.point.length2() < best.point.length2())
	{
		best = candidate;
		haveBest = true;
	}
}

void closestOnTriangle(const btVector3* w, int ia, int ib, int ic, ClosestFeature& out)
{
	const btVector3& a = w[ia];
	const btVector3& b = w[ib];
	const btVector3& c = w[ic];
	const btVector3 ab = b - a;
	const btVector3 ac = c - a;
	const btScalar crossSquared = ab.cross(ac).length2();
	// Flat when sin^2 of the angle at a is below SIMD_EPSILON: the face formula would then divide by a
	// quantity dominated by rounding, while the best edge is within the triangle's tiny height.
	if (!(crossSquared > SIMD_EPSILON * ab.length2() * ac.length2()))
	{
		ClosestFeature edge;
		bool haveBest = false;
		closestOnSegment(w, ia, ib, edge);
		keepCloser(out, edge, haveBest);
		closestOnSegment(w, ib, ic, edge);
		keepCloser(out, edge, haveBest);
		closestOnSegment(w, ia, ic, edge);
		keepCloser(out, edge, haveBest);
		out.degenerate = true;
		return;
	}
	out.degenerate = false;
	const btScalar d1 = -ab.dot(a);
	const btScalar d2 = -ac.dot(a);
	if (d1 <= btScalar(0) && d2 <= btScalar(0))
	{
		setVertex(out, w, ia);
		return;
	}
	const btScalar d3 = -ab.dot(b);
	const btScalar d4 = -ac.dot(b);
	if (d3 >= btScalar(0) && d4 <= d3)
	{
		setVertex(out, w, ib);
		return;
	}
	const btScalar vc = d1 * d4 - d3 * d2;
	if (vc <= btScalar(0) && d1 >= btScalar(0) && d3 <= btScalar(0))
	{
		closestOnSegment(w, ia, ib, out);
		return;
	}
	const btScalar d5 = -ab.dot(c);
	const btScalar d6 = -ac.dot(c);
	if (d6 >= btScalar(0) && d5 <= d6)
	{
		setVertex(out, w, ic);
		return;
	}
	const btScalar vb = d5 * d2 - d1 * d6;
	if (vb <= btScalar(0) && d2 >= btScalar(0) && d6 <= btScalar(0))
	{
		closestOnSegment(w, ia, ic, out);
		return;
	}
	const btScalar va = d3 * d6 - d5 * d4;
	if (va <= btScalar(0) && (d4 - d3) >= btScalar(0) && (d5 - d6) >= btScalar(0))
	{
		closestOnSegment(w, ib, ic, out);
		return;
	}
	const btScalar sum = va + vb + vc;
	const btScalar v = vb / sum;
	const btScalar u = vc / sum;
	out.weight[0] = out.weight[1] = out.weight[2] = out.weight[3] = btScalar(0);
	out.weight[ia] = btScalar(1) - v - u;
	out.weight[ib] = v;
	out.weight[ic] = u;
	out.point = a + ab * v + ac * u;
	out.usedMask = (1 << ia) | (1 << ib) | (1 << ic);
}

void closestOnTetrahedron(const btVector3* w, ClosestFeature& out)
{
	static const int kFaces[4][4] = {{0, 1, 2, 3}, {0, 3, 1, 2}, {0, 2, 3, 1}, {1, 3, 2, 0}};
	const btVector3 ab = w[1] - w[0];
	const btVector3 ac = w[2] - w[0];
	const btVector3 ad = w[3] - w[0];
	const btScalar volume6 = ab.dot(ac.cross(ad));
	// Flat when volume^2 / (|ab| |ac| |ad|)^2 is below SIMD_EPSILON (same scale-free test as triangles).
	const bool flat = !(volume6 * volume6 > SIMD_EPSILON * ab.length2() * ac.length2() * ad.length2());
	bool haveBest = false;
	ClosestFeature face;
	for (int f = 0; f < 4; ++f)
	{
		const int* idx = kFaces[f];
		if (!flat)
		{
			// The face matters only when the origin lies strictly on the other side of it from the
			// opposite vertex.
			const btVector3 normal = (w[idx[1]] - w[idx[0]]).cross(w[idx[2]] - w[idx[0]]);
			const btScalar originSide = -normal.dot(w[idx[0]]);
			const btScalar vertexSide = normal.dot(w[idx[3]] - w[idx[0]]);
			if (!(originSide * vertexSide < btScalar(0))) continue;
		}
		closestOnTriangle(w, idx[0], idx[1], idx[2], face);
		keepCloser(out, face, haveBest);
	}
	if (flat)
	{
		out.degenerate = true;
		return;
	}
	if (haveBest) return;
	// The origin is inside: its weights are the volumes of the tetrahedra it makes with each face.
	const btVector3 toOrigin = -w[0];
	const btScalar wb = toOrigin.dot(ac.cross(ad)) / volume6;
	const btScalar wc = ab.dot(toOrigin.cross(ad)) / volume6;
	const btScalar wd = ab.dot(ac.cross(toOrigin)) / volume6;
	out.weight[1] = wb;
	out.weight[2] = wc;
	out.weight[3] = wd;
	out.weight[0] = btScalar(1) - wb - wc - wd;
	out.point.setValue(btScalar(0), btScalar(0), btScalar(0));
	out.usedMask = 15;
	out.degenerate = false;
}

bool isFiniteVector(const btVector3& v) { return btIsFinite(v.x()) && btIsFinite(v.y()) && btIsFinite(v.z()); }
}  // namespace

btVoronoiSimplexSolver::btVoronoiSimplexSolver() : m_equalVertexThreshold(VORONOI_DEFAULT_EQUAL_VERTEX_THRESHOLD)
{
	reset();
}

void btVoronoiSimplexSolver::reset()
{
	m_numVertices = 0;
	m_cachedValidClosest = false;
	m_needsUpdate = true;
	m_cachedBC.reset();
	m_cachedV.setValue(btScalar(0), btScalar(0), btScalar(0));
	m_cachedP1 = m_cachedV;
	m_cachedP2 = m_cachedV;
	m_lastW.setValue(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
}

void btVoronoiSimplexSolver::addVertex(const btVector3& w, const btVector3& p, const btVector3& q)
{
	btAssert(m_numVertices < VORONOI_SIMPLEX_MAX_VERTS);
	if (m_numVertices >= VORONOI_SIMPLEX_MAX_VERTS) return;
	m_lastW = w;
	m_needsUpdate = true;
	m_simplexVectorW[m_numVertices] = w;
	m_simplexPointsP[m_numVertices] = p;
	m_simplexPointsQ[m_numVertices] = q;
	++m_numVertices;
}

void btVoronoiSimplexSolver::removeVertex(int index)
{
	btAssert(index >= 0 && index < m_numVertices);
	if (index < 0 || index >= m_numVertices) return;
	--m_numVertices;
	m_simplexVectorW[index] = m_simplexVectorW[m_numVertices];
	m_simplexPointsP[index] = m_simplexPointsP[m_numVertices];
	m_simplexPointsQ[index] = m_simplexPointsQ[m_numVertices];
}

void btVoronoiSimplexSolver::reduceVertices(const btUsageBitfield& usedVerts)
{
	// From the back, so that removeVertex's swap never moves a vertex not yet examined.
	if (m_numVertices >= 4 && !usedVerts.usedVertexD) removeVertex(3);
	if (m_numVertices >= 3 && !usedVerts.usedVertexC) removeVertex(2);
	if (m_numVertices >= 2 && !usedVerts.usedVertexB) removeVertex(1);
	if (m_numVertices >= 1 && !usedVerts.usedVertexA) removeVertex(0);
}

bool btVoronoiSimplexSolver::updateClosestVectorAndPoints()
{
	if (!m_needsUpdate) return m_cachedValidClosest;
	m_needsUpdate = false;
	m_cachedBC.reset();
	const btVector3 zero(btScalar(0), btScalar(0), btScalar(0));
	bool finite = m_numVertices > 0;
	for (int i = 0; i < m_numVertices && finite; ++i) finite = isFiniteVector(m_simplexVectorW[i]);
	// A fifth vertex is never examined: GJK reduces before adding, so it cannot occur in practice.
	if (!finite || m_numVertices > 4)
	{
		m_cachedV = zero;
		m_cachedP1 = zero;
		m_cachedP2 = zero;
		m_cachedValidClosest = false;
		return false;
	}
	ClosestFeature feature;
	feature.degenerate = false;
	switch (m_numVertices)
	{
		case 1:
			setVertex(feature, m_simplexVectorW, 0);
			break;
		case 2:
			closestOnSegment(m_simplexVectorW, 0, 1, feature);
			break;
		case 3:
			closestOnTriangle(m_simplexVectorW, 0, 1, 2, feature);
			break;
		default:
			closestOnTetrahedron(m_simplexVectorW, feature);
			break;
	}
	for (int i = m_numVertices; i < 4; ++i) feature.weight[i] = btScalar(0);
	m_cachedBC.m_closestPointOnSimplex = feature.point;
	m_cachedBC.setBarycentricCoordinates(feature.weight[0], feature.weight[1], feature.weight[2], feature.weight[3]);
	m_cachedBC.m_usedVertices.usedVertexA = (feature.usedMask & 1) != 0;
	m_cachedBC.m_usedVertices.usedVertexB = (feature.usedMask & 2) != 0;
	m_cachedBC.m_usedVertices.usedVertexC = (feature.usedMask & 4) != 0;
	m_cachedBC.m_usedVertices.usedVertexD = (feature.usedMask & 8) != 0;
	m_cachedBC.m_degenerate = feature.degenerate;

	btVector3 p1 = zero;
	btVector3 p2 = zero;
	for (int i = 0; i < m_numVertices; ++i)
	{
		p1 += m_simplexPointsP[i] * feature.weight[i];
		p2 += m_simplexPointsQ[i] * feature.weight[i];
	}
	m_cachedP1 = p1;
	m_cachedP2 = p2;
	m_cachedV = feature.point;
	reduceVertices(m_cachedBC.m_usedVertices);
	m_cachedValidClosest = isFiniteVector(m_cachedV);
	if (!m_cachedValidClosest)
	{
		m_cachedV = zero;
		m_cachedP1 = zero;
		m_cachedP2 = zero;
	}
	return m_cachedValidClosest;
}

bool btVoronoiSimplexSolver::closest(btVector3& v)
{
	const bool valid = updateClosestVectorAndPoints();
	v = m_cachedV;
	return valid;
}

btScalar btVoronoiSimplexSolver::maxVertex()
{
	btScalar maxLength2 = btScalar(0);
	for (int i = 0; i < m_numVertices; ++i)
	{
		const btScalar l2 = m_simplexVectorW[i].length2();
		if (l2 > maxLength2) maxLength2 = l2;
	}
	return maxLength2;
}

int btVoronoiSimplexSolver::getSimplex(btVector3* pBuf, btVector3* qBuf, btVector3* yBuf) const
{
	for (int i = 0; i < m_numVertices; ++i)
	{
		if (pBuf) pBuf[i] = m_simplexPointsP[i];
		if (qBuf) qBuf[i] = m_simplexPointsQ[i];
		if (yBuf) yBuf[i] = m_simplexVectorW[i];
	}
	return m_numVertices;
}

bool btVoronoiSimplexSolver::inSimplex(const btVector3& w)
{
	for (int i = 0; i < m_numVertices; ++i)
	{
		if (m_simplexVectorW[i].distance2(w) <= m_equalVertexThreshold) return true;
	}
	// The last vertex may have been reduced away; adding it again would make GJK cycle.
	return w == m_lastW;
}

void btVoronoiSimplexSolver::backup_closest(btVector3& v) { v = m_cachedV; }

void btVoronoiSimplexSolver::compute_points(btVector3& p1, btVector3& p2)
{
	updateClosestVectorAndPoints();
	p1 = m_cachedP1;
	p2 = m_cachedP2;
}
