// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"

// Closest point of a simplex to the origin by Voronoi regions (after Ericson, "Real-Time Collision
// Detection", ch. 5). Degenerate simplices never divide by a vanishing quantity: the convex hull of
// collinear points is the union of their segments and the hull of coplanar points is the union of
// their triangles (Caratheodory), so a flat simplex is answered exactly by its best sub-simplex.
//
// The arithmetic is in double even in float builds. Near convergence on curved shapes GJK's vertices
// cluster within ~1e-2 of each other next to a far vertex; the region tests and barycentric weights
// are then differences of products of size |w|^2 whose result is ~1e-4 of that, and in float the
// closest point came out ~1e-5 wrong, which stalled GJK (a new vertex made the distance grow) and
// turned a 0.01-unit core distance into a normal several degrees off. Float vertices are exact in
// double, so the closest point is now as accurate as the vertices themselves.

namespace
{
/// The scalar of the closest-point computations.
typedef double Real;

/// A minimal vector of Real for the closest-point computations.
struct Vec
{
	Real x, y, z;
};

inline Vec toVec(const btVector3& v) { return Vec{Real(v.x()), Real(v.y()), Real(v.z())}; }
inline btVector3 toBt(const Vec& v) { return btVector3(btScalar(v.x), btScalar(v.y), btScalar(v.z)); }
inline Vec operator-(const Vec& a, const Vec& b) { return Vec{a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec operator+(const Vec& a, const Vec& b) { return Vec{a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec operator*(const Vec& a, Real s) { return Vec{a.x * s, a.y * s, a.z * s}; }
inline Vec operator-(const Vec& a) { return Vec{-a.x, -a.y, -a.z}; }
inline Real dot(const Vec& a, const Vec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Real length2(const Vec& a) { return dot(a, a); }
inline Vec cross(const Vec& a, const Vec& b)
{
	return Vec{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// sin^2 of the angle below which a triangle (or the analogous ratio for a tetrahedron) counts as flat.
// The inputs are float or double coordinates, exact in Real; the face formulas lose about
// 1 / sin^2 of Real's precision, so flat means that loss would reach the rounding of the vertices.
const Real kFlatness = Real(SIMD_EPSILON) > Real(1e-12) ? Real(1e-12) : Real(SIMD_EPSILON);

// A closest point in terms of vertex indices 0..3 of the simplex being examined.
struct ClosestFeature
{
	Vec point;
	Real weight[4];
	int usedMask;  // bit i set: vertex i has a weight
	bool degenerate;
};

void setVertex(ClosestFeature& out, const Vec* w, int i)
{
	out.point = w[i];
	out.weight[0] = out.weight[1] = out.weight[2] = out.weight[3] = Real(0);
	out.weight[i] = Real(1);
	out.usedMask = 1 << i;
}

void closestOnSegment(const Vec* w, int ia, int ib, ClosestFeature& out)
{
	const Vec& a = w[ia];
	const Vec ab = w[ib] - a;
	const Real lengthSquared = length2(ab);
	const Real t = -dot(a, ab);
	out.degenerate = false;
	if (!(lengthSquared > Real(0)))
	{
		// Both ends coincide: the segment is the point a.
		out.degenerate = true;
		setVertex(out, w, ia);
		return;
	}
	if (t <= Real(0))
	{
		setVertex(out, w, ia);
		return;
	}
	if (t >= lengthSquared)
	{
		setVertex(out, w, ib);
		return;
	}
	const Real s = t / lengthSquared;
	out.weight[0] = out.weight[1] = out.weight[2] = out.weight[3] = Real(0);
	out.weight[ia] = Real(1) - s;
	out.weight[ib] = s;
	out.point = a + ab * s;
	out.usedMask = (1 << ia) | (1 << ib);
}

// Keeps in best whichever of best and candidate lies closer to the origin.
void keepCloser(ClosestFeature& best, const ClosestFeature& candidate, bool& haveBest)
{
	if (!haveBest || length2(candidate.point) < length2(best.point))
	{
		best = candidate;
		haveBest = true;
	}
}

void closestOnTriangle(const Vec* w, int ia, int ib, int ic, ClosestFeature& out)
{
	const Vec& a = w[ia];
	const Vec& b = w[ib];
	const Vec& c = w[ic];
	const Vec ab = b - a;
	const Vec ac = c - a;
	const Real crossSquared = length2(cross(ab, ac));
	// Flat: the face formula would then divide by a quantity dominated by rounding, while the best
	// edge is within the triangle's tiny height.
	if (!(crossSquared > kFlatness * length2(ab) * length2(ac)))
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
	const Real d1 = -dot(ab, a);
	const Real d2 = -dot(ac, a);
	if (d1 <= Real(0) && d2 <= Real(0))
	{
		setVertex(out, w, ia);
		return;
	}
	const Real d3 = -dot(ab, b);
	const Real d4 = -dot(ac, b);
	if (d3 >= Real(0) && d4 <= d3)
	{
		setVertex(out, w, ib);
		return;
	}
	const Real vc = d1 * d4 - d3 * d2;
	if (vc <= Real(0) && d1 >= Real(0) && d3 <= Real(0))
	{
		closestOnSegment(w, ia, ib, out);
		return;
	}
	const Real d5 = -dot(ab, c);
	const Real d6 = -dot(ac, c);
	if (d6 >= Real(0) && d5 <= d6)
	{
		setVertex(out, w, ic);
		return;
	}
	const Real vb = d5 * d2 - d1 * d6;
	if (vb <= Real(0) && d2 >= Real(0) && d6 <= Real(0))
	{
		closestOnSegment(w, ia, ic, out);
		return;
	}
	const Real va = d3 * d6 - d5 * d4;
	if (va <= Real(0) && (d4 - d3) >= Real(0) && (d5 - d6) >= Real(0))
	{
		closestOnSegment(w, ib, ic, out);
		return;
	}
	const Real sum = va + vb + vc;
	const Real v = vb / sum;
	const Real u = vc / sum;
	out.weight[0] = out.weight[1] = out.weight[2] = out.weight[3] = Real(0);
	out.weight[ia] = Real(1) - v - u;
	out.weight[ib] = v;
	out.weight[ic] = u;
	out.point = a + ab * v + ac * u;
	out.usedMask = (1 << ia) | (1 << ib) | (1 << ic);
}

void closestOnTetrahedron(const Vec* w, ClosestFeature& out)
{
	static const int kFaces[4][4] = {{0, 1, 2, 3}, {0, 3, 1, 2}, {0, 2, 3, 1}, {1, 3, 2, 0}};
	const Vec ab = w[1] - w[0];
	const Vec ac = w[2] - w[0];
	const Vec ad = w[3] - w[0];
	const Real volume6 = dot(ab, cross(ac, ad));
	// Flat when volume^2 / (|ab| |ac| |ad|)^2 is below kFlatness (the same scale-free test as triangles).
	const bool flat = !(volume6 * volume6 > kFlatness * length2(ab) * length2(ac) * length2(ad));
	bool haveBest = false;
	ClosestFeature face;
	for (int f = 0; f < 4; ++f)
	{
		const int* idx = kFaces[f];
		if (!flat)
		{
			// The face matters only when the origin lies strictly on the other side of it from the
			// opposite vertex.
			const Vec normal = cross(w[idx[1]] - w[idx[0]], w[idx[2]] - w[idx[0]]);
			const Real originSide = -dot(normal, w[idx[0]]);
			const Real vertexSide = dot(normal, w[idx[3]] - w[idx[0]]);
			if (!(originSide * vertexSide < Real(0))) continue;
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
	const Vec toOrigin = -w[0];
	const Real wb = dot(toOrigin, cross(ac, ad)) / volume6;
	const Real wc = dot(ab, cross(toOrigin, ad)) / volume6;
	const Real wd = dot(ab, cross(ac, toOrigin)) / volume6;
	out.weight[1] = wb;
	out.weight[2] = wc;
	out.weight[3] = wd;
	out.weight[0] = Real(1) - wb - wc - wd;
	out.point = Vec{Real(0), Real(0), Real(0)};
	out.usedMask = 15;
	out.degenerate = false;
}

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
	for (int i = 0; i < m_numVertices && finite; ++i) finite = caliber::isFinite(m_simplexVectorW[i]);
	// A fifth vertex is never examined: GJK reduces before adding, so it cannot occur in practice.
	if (!finite || m_numVertices > 4)
	{
		m_cachedV = zero;
		m_cachedP1 = zero;
		m_cachedP2 = zero;
		m_cachedValidClosest = false;
		return false;
	}
	Vec w[4];
	for (int i = 0; i < m_numVertices; ++i) w[i] = toVec(m_simplexVectorW[i]);
	ClosestFeature feature;
	feature.degenerate = false;
	switch (m_numVertices)
	{
		case 1:
			setVertex(feature, w, 0);
			break;
		case 2:
			closestOnSegment(w, 0, 1, feature);
			break;
		case 3:
			closestOnTriangle(w, 0, 1, 2, feature);
			break;
		default:
			closestOnTetrahedron(w, feature);
			break;
	}
	for (int i = m_numVertices; i < 4; ++i) feature.weight[i] = Real(0);
	m_cachedBC.m_closestPointOnSimplex = toBt(feature.point);
	m_cachedBC.setBarycentricCoordinates(btScalar(feature.weight[0]), btScalar(feature.weight[1]),
	                                     btScalar(feature.weight[2]), btScalar(feature.weight[3]));
	m_cachedBC.m_usedVertices.usedVertexA = (feature.usedMask & 1) != 0;
	m_cachedBC.m_usedVertices.usedVertexB = (feature.usedMask & 2) != 0;
	m_cachedBC.m_usedVertices.usedVertexC = (feature.usedMask & 4) != 0;
	m_cachedBC.m_usedVertices.usedVertexD = (feature.usedMask & 8) != 0;
	m_cachedBC.m_degenerate = feature.degenerate;

	Vec p1{Real(0), Real(0), Real(0)};
	Vec p2 = p1;
	for (int i = 0; i < m_numVertices; ++i)
	{
		p1 = p1 + toVec(m_simplexPointsP[i]) * feature.weight[i];
		p2 = p2 + toVec(m_simplexPointsQ[i]) * feature.weight[i];
	}
	m_cachedV = toBt(feature.point);
	m_cachedP1 = toBt(p1);
	m_cachedP2 = toBt(p2);
	reduceVertices(m_cachedBC.m_usedVertices);
	m_cachedValidClosest = caliber::isFinite(m_cachedV);
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
