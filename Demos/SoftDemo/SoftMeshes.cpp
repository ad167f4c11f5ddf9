// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "SoftMeshes.h"

#include <stdio.h>

#include <algorithm>
#include <array>
#include <map>
#include <vector>

namespace soft_demo
{
btSoftBody* makeTorus(btSoftBodyWorldInfo& info, const btVector3& centre, btScalar R, btScalar r, int ring, int tube)
{
	std::vector<btScalar> v;
	for (int i = 0; i < ring; ++i)
		for (int j = 0; j < tube; ++j)
		{
			const btScalar u = SIMD_2_PI * btScalar(i) / btScalar(ring), w = SIMD_2_PI * btScalar(j) / btScalar(tube);
			const btScalar d = R + r * btCos(w);
			v.push_back(centre.x() + d * btCos(u));
			v.push_back(centre.y() + r * btSin(w));
			v.push_back(centre.z() + d * btSin(u));
		}
	std::vector<int> t;
	auto at = [ring, tube](int i, int j) { return ((i + ring) % ring) * tube + (j + tube) % tube; };
	for (int i = 0; i < ring; ++i)
		for (int j = 0; j < tube; ++j)
		{
			// Wound so that the normals (b - a) x (c - a) point out of the tube.
			const int a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
			const int tri[6] = {a, c, b, a, d, c};
			t.insert(t.end(), tri, tri + 6);
		}
	btSoftBody* body = btSoftBodyHelpers::CreateFromTriMesh(info, &v[0], &t[0], int(t.size() / 3), false);
	return body;
}

btSoftBody* makeBlob(btSoftBodyWorldInfo& info, const btVector3& centre, btScalar radius, int res)
{
	btSoftBody* body = btSoftBodyHelpers::CreateEllipsoid(info, btVector3(0, 0, 0), btVector3(1, 1, 1), res);
	for (int i = 0; i < body->m_nodes.size(); ++i)
	{
		btSoftBody::Node& n = body->m_nodes[i];
		const btVector3 d = n.m_x.normalized();
		// Two lobes on top (ears, loosely), a wider bottom: a smooth bump function of the direction.
		const btScalar bump = btScalar(0.3) * d.y() * d.y() * d.y() * btCos(3 * btAtan2(d.z(), d.x())) +
		                      btScalar(0.15) * (1 - d.y()) * btScalar(0.5);
		n.m_x = centre + d * radius * (1 + bump);
		n.m_q = n.m_x;
	}
	body->resetLinkRestLengths();
	body->updateNormals();
	body->updateBounds();
	return body;
}

TetGenText makeTetCube(const btVector3& centre, btScalar size, int n)
{
	TetGenText out;
	const int m = n + 1;
	const btVector3 low = centre - btVector3(size, size, size) / 2;
	const btScalar h = size / btScalar(n);
	char line[128];
	snprintf(line, sizeof line, "%d 3 0 0\n", m * m * m);
	out.node = line;
	std::vector<btVector3> x;
	for (int k = 0; k < m; ++k)
		for (int j = 0; j < m; ++j)
			for (int i = 0; i < m; ++i)
			{
				x.push_back(low + btVector3(btScalar(i), btScalar(j), btScalar(k)) * h);
				snprintf(line, sizeof line, "%d %.9g %.9g %.9g\n", int(x.size()) - 1, double(x.back().x()),
				         double(x.back().y()), double(x.back().z()));
				out.node += line;
			}
	auto id = [m](int i, int j, int k) { return (k * m + j) * m + i; };
	// Each cell in 6 tetras, one per order of the axes, along the diagonal from its low corner (the same
	// diagonal in every cell, so neighbouring cells' faces match).
	std::vector<std::array<int, 4>> tets;
	const int orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
	for (int k = 0; k < n; ++k)
		for (int j = 0; j < n; ++j)
			for (int i = 0; i < n; ++i)
				for (const auto& o : orders)
				{
					int c[3] = {i, j, k};
					std::array<int, 4> t;
					t[0] = id(c[0], c[1], c[2]);
					for (int s = 0; s < 3; ++s)
					{
						++c[o[s]];
						t[size_t(s + 1)] = id(c[0], c[1], c[2]);
					}
					// TetGen's positive orientation: the fourth node on the positive side of the first three.
					const btVector3 &a = x[size_t(t[0])], &b = x[size_t(t[1])], &cc = x[size_t(t[2])], &d = x[size_t(t[3])];
					if ((b - a).cross(cc - a).dot(d - a) < 0) std::swap(t[1], t[2]);
					tets.push_back(t);
				}
	snprintf(line, sizeof line, "%d 4 0\n", int(tets.size()));
	out.ele = line;
	// Boundary faces: the tetra faces no other tetra shares, wound outwards.
	std::map<std::array<int, 3>, std::array<int, 4>> faces;  // sorted nodes -> wound nodes, count
	for (size_t e = 0; e < tets.size(); ++e)
	{
		const std::array<int, 4>& t = tets[e];
		snprintf(line, sizeof line, "%d %d %d %d %d\n", int(e), t[0], t[1], t[2], t[3]);
		out.ele += line;
		const int wound[4][3] = {{t[0], t[2], t[1]}, {t[0], t[1], t[3]}, {t[1], t[2], t[3]}, {t[0], t[3], t[2]}};
		for (const auto& w : wound)
		{
			std::array<int, 3> key = {w[0], w[1], w[2]};
			std::sort(key.begin(), key.end());
			auto it = faces.find(key);
			if (it == faces.end())
				faces[key] = {w[0], w[1], w[2], 1};
			else
				++it->second[3];
		}
	}
	int boundary = 0;
	std::string body;
	for (const auto& f : faces)
		if (f.second[3] == 1)
		{
			snprintf(line, sizeof line, "%d %d %d %d\n", boundary++, f.second[0], f.second[1], f.second[2]);
			body += line;
		}
	snprintf(line, sizeof line, "%d 0\n", boundary);
	out.face = line + body;
	return out;
}

btScalar tetraVolume(const btSoftBody& body)
{
	btScalar v = 0;
	for (int i = 0; i < body.m_tetras.size(); ++i)
	{
		const btSoftBody::Tetra& t = body.m_tetras[i];
		const btVector3 a = t.m_n[0]->m_x;
		v += (t.m_n[1]->m_x - a).cross(t.m_n[2]->m_x - a).dot(t.m_n[3]->m_x - a) / 6;
	}
	return v;
}
}  // namespace soft_demo
