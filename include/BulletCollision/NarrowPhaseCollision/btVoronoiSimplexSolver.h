// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_VORONOI_SIMPLEX_SOLVER_H
#define BT_VORONOI_SIMPLEX_SOLVER_H

/// btVoronoiSimplexSolver: the simplex bookkeeping of GJK (closest point of a point, segment, triangle
/// or tetrahedron to the origin, found by Voronoi regions, robust to degenerate simplices).

#include "LinearMath/btVector3.h"

/// Room for one vertex more than a tetrahedron: GJK adds a vertex before reducing the simplex.
#define VORONOI_SIMPLEX_MAX_VERTS 5

#ifdef BT_USE_DOUBLE_PRECISION
/// Default squared distance below which a new vertex counts as already in the simplex.
#define VORONOI_DEFAULT_EQUAL_VERTEX_THRESHOLD 1e-12
#else
/// Default squared distance below which a new vertex counts as already in the simplex.
#define VORONOI_DEFAULT_EQUAL_VERTEX_THRESHOLD 0.0001f
#endif

/// Which of up to four simplex vertices a closest point uses.
struct btUsageBitfield
{
	/// All vertices unused.
	btUsageBitfield() { reset(); }
	/// Marks all vertices unused.
	void reset()
	{
		usedVertexA = false;
		usedVertexB = false;
		usedVertexC = false;
		usedVertexD = false;
	}
	/// Vertex 0 is used.
	unsigned short usedVertexA : 1;
	/// Vertex 1 is used.
	unsigned short usedVertexB : 1;
	/// Vertex 2 is used.
	unsigned short usedVertexC : 1;
	/// Vertex 3 is used.
	unsigned short usedVertexD : 1;
	/// Padding, kept for layout compatibility.
	unsigned short unused1 : 1;
	/// Padding, kept for layout compatibility.
	unsigned short unused2 : 1;
	/// Padding, kept for layout compatibility.
	unsigned short unused3 : 1;
	/// Padding, kept for layout compatibility.
	unsigned short unused4 : 1;
};

/// The closest point of a simplex to the origin, as barycentric coordinates over its vertices.
struct btSubSimplexClosestResult
{
	/// The closest point itself.
	btVector3 m_closestPointOnSimplex;
	/// The vertices with a non-zero weight (the smallest sub-simplex holding the closest point).
	btUsageBitfield m_usedVertices;
	/// Weight of each vertex; the used ones sum to 1.
	btScalar m_barycentricCoords[4];
	/// True when the simplex was degenerate (collinear, coplanar or repeated vertices).
	bool m_degenerate;

	/// Clears the result (no vertex used, all weights 0).
	void reset()
	{
		m_degenerate = false;
		setBarycentricCoordinates();
		m_usedVertices.reset();
	}
	/// True when the weights are all non-negative (a point of the simplex).
	bool isValid() const
	{
		return m_barycentricCoords[0] >= btScalar(0.) && m_barycentricCoords[1] >= btScalar(0.) &&
		       m_barycentricCoords[2] >= btScalar(0.) && m_barycentricCoords[3] >= btScalar(0.);
	}
	/// Sets the four weights.
	void setBarycentricCoordinates(btScalar a = btScalar(0.), btScalar b = btScalar(0.), btScalar c = btScalar(0.),
	                               btScalar d = btScalar(0.))
	{
		m_barycentricCoords[0] = a;
		m_barycentricCoords[1] = b;
		m_barycentricCoords[2] = c;
		m_barycentricCoords[3] = d;
	}
};

/// GJK's simplex: vertices w = p - q of the Minkowski difference with their support points p (on A)
/// and q (on B); finds the point of the simplex closest to the origin and drops unused vertices.
ATTRIBUTE_ALIGNED16(class)
btVoronoiSimplexSolver
{
public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// An empty simplex with the default equal-vertex threshold.
	btVoronoiSimplexSolver();

	/// Empties the simplex.
	void reset();
	/// Adds the vertex w = p - q with its support points p (on A) and q (on B). At most
	/// VORONOI_SIMPLEX_MAX_VERTS vertices: a further vertex asserts and is ignored in release builds.
	void addVertex(const btVector3& w, const btVector3& p, const btVector3& q);
	/// Sets the squared distance under which inSimplex() treats two vertices as equal.
	void setEqualVertexThreshold(btScalar threshold) { m_equalVertexThreshold = threshold; }
	/// The squared distance under which inSimplex() treats two vertices as equal.
	btScalar getEqualVertexThreshold() const { return m_equalVertexThreshold; }
	/// Reduces the simplex to the vertices supporting its closest point to the origin and writes that
	/// point to v. Returns false (v = 0) for an empty simplex or non-finite vertices.
	bool closest(btVector3 & v);
	/// The largest squared length of the simplex vertices (a scale for GJK's tolerances).
	btScalar maxVertex();
	/// True when the simplex is a tetrahedron (after closest(): the origin is inside it).
	bool fullSimplex() const { return m_numVertices == 4; }
	/// Copies the vertices' support points on A (pBuf), on B (qBuf) and w (yBuf); returns their number.
	int getSimplex(btVector3 * pBuf, btVector3 * qBuf, btVector3 * yBuf) const;
	/// True when w is within the equal-vertex threshold of a vertex or of the last vertex added.
	bool inSimplex(const btVector3& w);
	/// Writes the last closest point found to v.
	void backup_closest(btVector3 & v);
	/// True when the simplex has no vertex.
	bool emptySimplex() const { return m_numVertices == 0; }
	/// The closest points on A (p1) and on B (p2) that correspond to the closest point of the simplex.
	void compute_points(btVector3 & p1, btVector3 & p2);
	/// Number of vertices in the simplex.
	int numVertices() const { return m_numVertices; }

	/// Number of vertices in the simplex (Bullet exposes the data members).
	int m_numVertices;
	/// The vertices w = p - q.
	btVector3 m_simplexVectorW[VORONOI_SIMPLEX_MAX_VERTS];
	/// The support points on A.
	btVector3 m_simplexPointsP[VORONOI_SIMPLEX_MAX_VERTS];
	/// The support points on B.
	btVector3 m_simplexPointsQ[VORONOI_SIMPLEX_MAX_VERTS];
	/// Closest point on A of the last closest() call.
	btVector3 m_cachedP1;
	/// Closest point on B of the last closest() call.
	btVector3 m_cachedP2;
	/// Closest point of the simplex to the origin of the last closest() call.
	btVector3 m_cachedV;
	/// The vertex added last.
	btVector3 m_lastW;
	/// Squared distance under which vertices count as equal.
	btScalar m_equalVertexThreshold;
	/// Whether the cached closest point is valid.
	bool m_cachedValidClosest;
	/// Barycentric description of the cached closest point.
	btSubSimplexClosestResult m_cachedBC;
	/// True when vertices changed since the closest point was computed.
	bool m_needsUpdate;

	/// Removes the vertex at index (the last vertex takes its place).
	void removeVertex(int index);
	/// Keeps only the vertices marked used.
	void reduceVertices(const btUsageBitfield& usedVerts);
	/// Recomputes the closest point and the support points; returns whether the result is valid.
	bool updateClosestVectorAndPoints();
};

#endif  // BT_VORONOI_SIMPLEX_SOLVER_H
