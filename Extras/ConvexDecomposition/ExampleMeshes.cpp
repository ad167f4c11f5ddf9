// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "ConvexDecomposition/ExampleMeshes.h"

namespace caliber
{
namespace
{
void addTriangle(ExampleMesh& mesh, int a, int b, int c)
{
	mesh.indices.push_back(a);
	mesh.indices.push_back(b);
	mesh.indices.push_back(c);
}
}  // namespace

ExampleMesh makeBoxMesh(const btVector3& half)
{
	ExampleMesh mesh;
	for (int i = 0; i < 8; ++i)
		mesh.vertices.push_back(
		    btVector3((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(), (i & 4) ? half.z() : -half.z()));
	// Each face as two triangles, counter-clockwise seen from outside.
	const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
	for (const auto& f : faces)
	{
		addTriangle(mesh, f[0], f[1], f[2]);
		addTriangle(mesh, f[0], f[2], f[3]);
	}
	return mesh;
}

ExampleMesh makeRevolvedMesh(const btAlignedObjectArray<btVector3>& profile, int segments)
{
	ExampleMesh mesh;
	const int n = profile.size();
	if (n < 3 || segments < 3) return mesh;
	// Vertex index of profile point p at segment s; a pole (r = 0) has one vertex for all segments.
	btAlignedObjectArray<int> first;
	for (int p = 0; p < n; ++p)
	{
		first.push_back(mesh.vertices.size());
		const btScalar r = profile[p].x(), z = profile[p].y();
		if (r == 0)
		{
			mesh.vertices.push_back(btVector3(0, 0, z));
			continue;
		}
		for (int s = 0; s < segments; ++s)
		{
			const btScalar angle = SIMD_2_PI * btScalar(s) / btScalar(segments);
			mesh.vertices.push_back(btVector3(r * btCos(angle), r * btSin(angle), z));
		}
	}
	const auto vertex = [&](int p, int s) { return profile[p].x() == 0 ? first[p] : first[p] + s % segments; };
	for (int p = 0; p < n; ++p)
	{
		const int q = (p + 1) % n;
		for (int s = 0; s < segments; ++s)
		{
			// The quad between profile edge p -> q and angles s, s + 1; outward for a counter-clockwise profile.
			const int a = vertex(p, s), b = vertex(q, s), c = vertex(q, s + 1), d = vertex(p, s + 1);
			if (a != d) addTriangle(mesh, a, d, b);
			if (b != c) addTriangle(mesh, b, d, c);
		}
	}
	return mesh;
}

ExampleMesh makeTorusMesh(btScalar R, btScalar r, int segmentsAround, int segmentsTube)
{
	btAlignedObjectArray<btVector3> profile;
	for (int k = 0; k < segmentsTube; ++k)
	{
		const btScalar angle = SIMD_2_PI * btScalar(k) / btScalar(segmentsTube);
		profile.push_back(btVector3(R + r * btCos(angle), r * btSin(angle), 0));
	}
	return makeRevolvedMesh(profile, segmentsAround);
}

ExampleMesh makeCupMesh(btScalar outerRadius, btScalar wall, btScalar height, btScalar floor, int segments)
{
	// The cup's cross-section right of the axis, counter-clockwise in (r, z).
	btAlignedObjectArray<btVector3> profile;
	profile.push_back(btVector3(0, 0, 0));
	profile.push_back(btVector3(outerRadius, 0, 0));
	profile.push_back(btVector3(outerRadius, height, 0));
	profile.push_back(btVector3(outerRadius - wall, height, 0));
	profile.push_back(btVector3(outerRadius - wall, floor, 0));
	profile.push_back(btVector3(0, floor, 0));
	return makeRevolvedMesh(profile, segments);
}

ExampleMesh makeLBracketMesh(btScalar leg, btScalar width, btScalar depth)
{
	ExampleMesh mesh;
	const btScalar outline[6][2] = {{0, 0}, {leg, 0}, {leg, width}, {width, width}, {width, leg}, {0, leg}};
	for (int layer = 0; layer < 2; ++layer)
		for (const auto& p : outline) mesh.vertices.push_back(btVector3(p[0], p[1], layer ? depth : 0));
	// Bottom (seen from -z: clockwise outline) and top: fans from corner 0, which sees the whole L.
	for (int i = 1; i < 5; ++i)
	{
		addTriangle(mesh, 0, i + 1, i);
		addTriangle(mesh, 6, 6 + i, 6 + i + 1);
	}
	for (int i = 0; i < 6; ++i)
	{
		const int j = (i + 1) % 6;
		addTriangle(mesh, i, j, 6 + j);
		addTriangle(mesh, i, 6 + j, 6 + i);
	}
	return mesh;
}
}  // namespace caliber
