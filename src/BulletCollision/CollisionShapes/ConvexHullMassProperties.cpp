// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/ConvexHullMassProperties.h"

#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "LinearMath/btConvexHullComputer.h"

namespace caliber
{
bool buildConvexPolyhedron(const btVector3* points, int count, btConvexPolyhedron& poly)
{
	poly.m_vertices.resize(0);
	poly.m_faces.resize(0);
	poly.m_uniqueEdges.resize(0);
	btConvexHullComputer hull;
	if (points != 0 && count > 0)
	{
		// btVector3 holds 4 scalars; the hull computer reads the first 3 at each stride.
		hull.compute(&points[0].x(), int(sizeof(btVector3)), count, 0, 0);
	}
	if (hull.faces.size() == 0)
	{
		poly.initialize();
		return false;
	}
	poly.m_vertices.resize(hull.vertices.size());
	for (int i = 0; i < hull.vertices.size(); ++i) poly.m_vertices[i] = hull.vertices[i];

	// The faces are built in place: growing an array of faces would copy every face built so far (their
	// index arrays with them).
	poly.m_faces.resize(hull.faces.size());
	for (int f = 0; f < hull.faces.size(); ++f)
	{
		btFace& face = poly.m_faces[f];
		const btConvexHullComputer::Edge* first = &hull.edges[hull.faces[f]];
		const btConvexHullComputer::Edge* edge = first;
		do
		{
			face.m_indices.push_back(edge->getSourceVertex());
			edge = edge->getNextEdgeOfFace();
		} while (edge != first && face.m_indices.size() <= hull.vertices.size());

		// Newell's normal: robust for any planar polygon, whatever its first corner looks like.
		btVector3 normal(0, 0, 0), centre(0, 0, 0);
		const int n = face.m_indices.size();
		for (int i = 0; i < n; ++i)
		{
			const btVector3& p = poly.m_vertices[face.m_indices[i]];
			const btVector3& q = poly.m_vertices[face.m_indices[(i + 1) % n]];
			normal += p.cross(q);
			centre += p;
		}
		centre /= btScalar(n);
		const btScalar length = normal.length();
		if (length > 0) normal /= length;
		face.m_plane[0] = normal.x();
		face.m_plane[1] = normal.y();
		face.m_plane[2] = normal.z();
		face.m_plane[3] = -normal.dot(centre);
	}
	poly.initialize();
	return true;
}

bool solidPolyhedronInertia(const btConvexPolyhedron& poly, btScalar mass, btVector3& inertia)
{
	const int vertexCount = poly.m_vertices.size();
	if (vertexCount < 4) return false;
	// Accumulate in double about the vertex mean: each fan triangle (a, b, c) of a face and the
	// reference point make a signed tetrahedron. Its second moment integral of x x^T over the
	// tetrahedron with one corner at the origin is det / 120 * (sum v v^T + (sum v)(sum v)^T).
	double ref[3] = {0, 0, 0};
	for (int i = 0; i < vertexCount; ++i)
		for (int k = 0; k < 3; ++k) ref[k] += double(poly.m_vertices[i][k]);
	for (int k = 0; k < 3; ++k) ref[k] /= double(vertexCount);

	double volume6 = 0, firstMoment[3] = {0, 0, 0}, second[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
	for (int f = 0; f < poly.m_faces.size(); ++f)
	{
		const btFace& face = poly.m_faces[f];
		const int n = face.m_indices.size();
		if (n < 3) continue;
		bool valid = true;
		for (int i = 0; i < n; ++i) valid = valid && face.m_indices[i] >= 0 && face.m_indices[i] < vertexCount;
		if (!valid) continue;
		double a[3];
		for (int k = 0; k < 3; ++k) a[k] = double(poly.m_vertices[face.m_indices[0]][k]) - ref[k];
		for (int i = 1; i + 1 < n; ++i)
		{
			double b[3], c[3];
			for (int k = 0; k < 3; ++k)
			{
				b[k] = double(poly.m_vertices[face.m_indices[i]][k]) - ref[k];
				c[k] = double(poly.m_vertices[face.m_indices[i + 1]][k]) - ref[k];
			}
			const double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
			                   a[2] * (b[0] * c[1] - b[1] * c[0]);
			volume6 += det;
			double sum[3];
			for (int k = 0; k < 3; ++k)
			{
				sum[k] = a[k] + b[k] + c[k];
				firstMoment[k] += det * sum[k] / 24.0;
			}
			for (int r = 0; r < 3; ++r)
				for (int s = 0; s < 3; ++s)
					second[r][s] += det / 120.0 * (a[r] * a[s] + b[r] * b[s] + c[r] * c[s] + sum[r] * sum[s]);
		}
	}
	const double volume = volume6 / 6.0;
	if (!(volume > 0) || !(volume < 1e300)) return false;
	double centre[3];
	for (int k = 0; k < 3; ++k) centre[k] = firstMoment[k] / volume;
	// Move the second moment to the centre of volume, then I = trace(C) Id - C, scaled by density.
	for (int r = 0; r < 3; ++r)
		for (int s = 0; s < 3; ++s) second[r][s] -= volume * centre[r] * centre[s];
	const double density = double(mass) / volume;
	const double trace = second[0][0] + second[1][1] + second[2][2];
	inertia.setValue(btScalar(density * (trace - second[0][0])), btScalar(density * (trace - second[1][1])),
	                 btScalar(density * (trace - second[2][2])));
	return true;
}

bool solidHullInertia(const btVector3* points, int count, btScalar mass, btVector3& inertia)
{
	btConvexPolyhedron poly;
	if (!buildConvexPolyhedron(points, count, poly)) return false;
	return solidPolyhedronInertia(poly, mass, inertia);
}

bool sampledSupportInertia(const btConvexShape& shape, btScalar mass, btVector3& inertia)
{
	btAlignedObjectArray<btVector3> points;
	points.resize(kInertiaSampleDirections);
	// Fibonacci sphere: z evenly spaced, longitude advancing by the golden angle.
	const btScalar goldenAngle = SIMD_PI * (btScalar(3) - btSqrt(btScalar(5)));
	for (int i = 0; i < kInertiaSampleDirections; ++i)
	{
		const btScalar z = btScalar(1) - (btScalar(2) * btScalar(i) + btScalar(1)) / btScalar(kInertiaSampleDirections);
		const btScalar r = btSqrt(btMax(btScalar(0), btScalar(1) - z * z));
		const btScalar phi = goldenAngle * btScalar(i);
		points[i] = shape.localGetSupportingVertex(btVector3(r * btCos(phi), r * btSin(phi), z));
	}
	return solidHullInertia(&points[0], points.size(), mass, inertia);
}

void aabbBoxInertia(const btConvexShape& shape, btScalar mass, btVector3& inertia)
{
	btVector3 aabbMin, aabbMax;
	shape.getAabb(btTransform::getIdentity(), aabbMin, aabbMax);
	btVector3 sides = aabbMax - aabbMin;
	for (int k = 0; k < 3; ++k)
		if (!btIsFinite(sides[k])) sides[k] = 0;
	const btVector3 s2 = sides * sides;
	inertia = (mass / btScalar(12)) * btVector3(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y());
}
}  // namespace caliber
