// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btSoftBodyHelpers: the makers (ropes, patches, ellipsoids, meshes, hulls). Drawing is in
// btSoftBodyDraw.cpp.

#include "BulletSoftBody/btSoftBodyHelpers.h"

#include <new>

#include "LinearMath/btConvexHullComputer.h"
#include "btSoftBodyInternal.h"

namespace
{
btSoftBody* newBody(btSoftBodyWorldInfo& worldInfo, int count, const btVector3* x, const btScalar* m)
{
	// btCollisionObject's aligned operator new: the caller deletes the body with delete, as with Bullet.
	return new btSoftBody(&worldInfo, count, x, m);
}

// An empty body, returned with a warning for input no body can be made from.
btSoftBody* emptyBody(btSoftBodyWorldInfo& worldInfo, const char* message)
{
	caliber::softBodyWarning(message);
	return newBody(worldInfo, 0, 0, 0);
}
}  // namespace

btSoftBody* btSoftBodyHelpers::CreateRope(btSoftBodyWorldInfo& worldInfo, const btVector3& from, const btVector3& to,
                                          int res, int fixeds)
{
	const bool ok = res >= 0 && caliber::isFinite(from) && caliber::isFinite(to);
	btAssert(ok && "btSoftBodyHelpers::CreateRope: negative resolution or non-finite end");
	if (!ok) return emptyBody(worldInfo, "Caliber: CreateRope: negative resolution or non-finite end; empty body\n");
	const int r = res + 2;
	btAlignedObjectArray<btVector3> x;
	btAlignedObjectArray<btScalar> m;
	x.resize(r);
	m.resize(r, btScalar(1));
	for (int i = 0; i < r; ++i) x[i] = from.lerp(to, btScalar(i) / btScalar(r - 1));
	if (fixeds & 1) m[0] = 0;
	if (fixeds & 2) m[r - 1] = 0;
	btSoftBody* psb = newBody(worldInfo, r, &x[0], &m[0]);
	for (int i = 1; i < r; ++i) psb->appendLink(i - 1, i);
	return psb;
}

btSoftBody* btSoftBodyHelpers::CreatePatch(btSoftBodyWorldInfo& worldInfo, const btVector3& corner00,
                                           const btVector3& corner10, const btVector3& corner01,
                                           const btVector3& corner11, int resx, int resy, int fixeds, bool gendiags,
                                           btScalar perturbation)
{
	const bool ok = resx >= 2 && resy >= 2 && caliber::isFinite(corner00) && caliber::isFinite(corner10) &&
	                caliber::isFinite(corner01) && caliber::isFinite(corner11) && btIsFinite(perturbation);
	btAssert(ok && "btSoftBodyHelpers::CreatePatch: resolution below 2 or non-finite corner");
	if (!ok) return emptyBody(worldInfo, "Caliber: CreatePatch: resolution below 2 or non-finite corner; empty body\n");
	const int rx = resx, ry = resy, count = rx * ry;
	btAlignedObjectArray<btVector3> x;
	btAlignedObjectArray<btScalar> m;
	x.resize(count);
	m.resize(count, btScalar(1));
	unsigned int seed = 12345u;
	for (int iy = 0; iy < ry; ++iy)
	{
		const btScalar ty = btScalar(iy) / btScalar(ry - 1);
		const btVector3 left = corner00.lerp(corner01, ty), right = corner10.lerp(corner11, ty);
		for (int ix = 0; ix < rx; ++ix)
		{
			btVector3 p = left.lerp(right, btScalar(ix) / btScalar(rx - 1));
			if (perturbation != 0)
			{
				// A fixed sequence, so that the same call always makes the same patch.
				seed = seed * 1664525u + 1013904223u;
				const btScalar u = btScalar(seed >> 8) / btScalar(1 << 24);
				p.setY(p.y() + perturbation * (2 * u - 1));
			}
			x[iy * rx + ix] = p;
		}
	}
	if (fixeds & 1) m[0] = 0;
	if (fixeds & 2) m[rx - 1] = 0;
	if (fixeds & 4) m[rx * (ry - 1)] = 0;
	if (fixeds & 8) m[rx * (ry - 1) + rx - 1] = 0;
	btSoftBody* psb = newBody(worldInfo, count, &x[0], &m[0]);
	for (int iy = 0; iy < ry; ++iy)
		for (int ix = 0; ix < rx; ++ix)
		{
			const int i00 = iy * rx + ix;
			if (ix + 1 < rx) psb->appendLink(i00, i00 + 1);
			if (iy + 1 < ry) psb->appendLink(i00, i00 + rx);
			if (ix + 1 < rx && iy + 1 < ry)
			{
				const int i10 = i00 + 1, i01 = i00 + rx, i11 = i00 + rx + 1;
				// Diagonals alternate like a checkerboard, so the patch has no preferred shear direction.
				if ((ix + iy) & 1)
				{
					psb->appendFace(i00, i10, i11);
					psb->appendFace(i00, i11, i01);
					if (gendiags) psb->appendLink(i00, i11);
				}
				else
				{
					psb->appendFace(i01, i00, i10);
					psb->appendFace(i01, i10, i11);
					if (gendiags) psb->appendLink(i01, i10);
				}
			}
		}
	return psb;
}

btSoftBody* btSoftBodyHelpers::CreatePatchUV(btSoftBodyWorldInfo& worldInfo, const btVector3& corner00,
                                             const btVector3& corner10, const btVector3& corner01,
                                             const btVector3& corner11, int resx, int resy, int fixeds, bool gendiags,
                                             float* tex_coords)
{
	btSoftBody* psb = CreatePatch(worldInfo, corner00, corner10, corner01, corner11, resx, resy, fixeds, gendiags);
	if (!tex_coords || psb->m_nodes.size() == 0) return psb;
	// The faces of each cell in the order CreatePatch appends them: u, v of each corner.
	int z = 0;
	for (int iy = 0; iy + 1 < resy; ++iy)
		for (int ix = 0; ix + 1 < resx; ++ix)
		{
			int cell[6][2];
			if ((ix + iy) & 1)
			{
				const int c[6][2] = {{ix, iy}, {ix + 1, iy},     {ix + 1, iy + 1},
				                     {ix, iy}, {ix + 1, iy + 1}, {ix, iy + 1}};
				for (int k = 0; k < 6; ++k) cell[k][0] = c[k][0], cell[k][1] = c[k][1];
			}
			else
			{
				const int c[6][2] = {{ix, iy + 1}, {ix, iy},     {ix + 1, iy},
				                     {ix, iy + 1}, {ix + 1, iy}, {ix + 1, iy + 1}};
				for (int k = 0; k < 6; ++k) cell[k][0] = c[k][0], cell[k][1] = c[k][1];
			}
			for (int k = 0; k < 6; ++k)
			{
				tex_coords[z++] = CalculateUV(resx, resy, cell[k][0], cell[k][1], 0);
				tex_coords[z++] = CalculateUV(resx, resy, cell[k][0], cell[k][1], 1);
			}
		}
	return psb;
}

float btSoftBodyHelpers::CalculateUV(int resx, int resy, int ix, int iy, int id)
{
	if (id == 0) return resx > 1 ? float(ix) / float(resx - 1) : 0.f;
	return resy > 1 ? 1.f - float(iy) / float(resy - 1) : 0.f;
}

btSoftBody* btSoftBodyHelpers::CreateEllipsoid(btSoftBodyWorldInfo& worldInfo, const btVector3& center,
                                               const btVector3& radius, int res)
{
	const bool ok = res >= 4 && caliber::isFinite(center) && caliber::isFinite(radius);
	btAssert(ok && "btSoftBodyHelpers::CreateEllipsoid: fewer than 4 points or non-finite size");
	if (!ok)
		return emptyBody(worldInfo, "Caliber: CreateEllipsoid: fewer than 4 points or non-finite size; empty body\n");
	// Points on a Fibonacci spiral: nearly even spacing, no two on one meridian.
	btAlignedObjectArray<btVector3> points;
	points.resize(res);
	const btScalar golden = SIMD_PI * (3 - btSqrt(btScalar(5)));
	for (int i = 0; i < res; ++i)
	{
		const btScalar y = 1 - (btScalar(i) + btScalar(0.5)) * 2 / btScalar(res);
		const btScalar r = btSqrt(btMax(btScalar(0), 1 - y * y));
		const btScalar a = golden * btScalar(i);
		points[i] = center + btVector3(r * btCos(a), y, r * btSin(a)) * radius;
	}
	return CreateFromConvexHull(worldInfo, &points[0], res);
}

btSoftBody* btSoftBodyHelpers::CreateFromTriMesh(btSoftBodyWorldInfo& worldInfo, const btScalar* vertices,
                                                 const int* triangles, int ntriangles, bool randomizeConstraints)
{
	bool ok = vertices && triangles && ntriangles > 0;
	int maxIndex = -1;
	for (int i = 0; ok && i < ntriangles * 3; ++i)
	{
		ok = triangles[i] >= 0;
		maxIndex = btMax(maxIndex, triangles[i]);
	}
	btAssert(ok && "btSoftBodyHelpers::CreateFromTriMesh: no triangles, null arrays or a negative index");
	if (!ok)
		return emptyBody(worldInfo,
		                 "Caliber: CreateFromTriMesh: no triangles, null arrays or a negative index; empty body\n");
	const int count = maxIndex + 1;
	btAlignedObjectArray<btVector3> x;
	x.resize(count);
	for (int i = 0; i < count; ++i) x[i].setValue(vertices[3 * i], vertices[3 * i + 1], vertices[3 * i + 2]);
	btSoftBody* psb = newBody(worldInfo, count, &x[0], 0);
	// One link per edge: an edge shared by two triangles is linked once (each node lists its
	// higher-numbered neighbours).
	btAlignedObjectArray<int> first, next, other;
	first.resize(count, -1);
	auto linked = [&](int a, int b)
	{
		for (int e = first[a]; e >= 0; e = next[e])
			if (other[e] == b) return true;
		return false;
	};
	for (int t = 0; t < ntriangles; ++t)
	{
		const int* idx = &triangles[3 * t];
		for (int k = 0; k < 3; ++k)
		{
			const int a = btMin(idx[k], idx[(k + 1) % 3]), b = btMax(idx[k], idx[(k + 1) % 3]);
			if (a == b || linked(a, b)) continue;
			other.push_back(b);
			next.push_back(first[a]);
			first[a] = other.size() - 1;
			psb->appendLink(a, b);
		}
		psb->appendFace(idx[0], idx[1], idx[2]);
	}
	if (randomizeConstraints) psb->randomizeConstraints();
	return psb;
}

btSoftBody* btSoftBodyHelpers::CreateFromConvexHull(btSoftBodyWorldInfo& worldInfo, const btVector3* vertices,
                                                    int nvertices, bool randomizeConstraints)
{
	const bool ok = vertices && nvertices >= 4;
	btAssert(ok && "btSoftBodyHelpers::CreateFromConvexHull: fewer than 4 points");
	if (!ok) return emptyBody(worldInfo, "Caliber: CreateFromConvexHull: fewer than 4 points; empty body\n");
	btConvexHullComputer hull;
	hull.compute(&vertices[0].getX(), sizeof(btVector3), nvertices, 0, 0);
	if (hull.faces.size() < 4)
		return emptyBody(worldInfo, "Caliber: CreateFromConvexHull: the points are flat or coincide; empty body\n");
	btSoftBody* psb = newBody(worldInfo, hull.vertices.size(), &hull.vertices[0], 0);
	for (int f = 0; f < hull.faces.size(); ++f)
	{
		// Faces walk counter-clockwise seen from outside: a fan from the first corner keeps that winding.
		const btConvexHullComputer::Edge* start = &hull.edges[hull.faces[f]];
		const btConvexHullComputer::Edge* e = start->getNextEdgeOfFace();
		const int a = start->getSourceVertex();
		int b = start->getTargetVertex();
		while (e != start)
		{
			const int c = e->getTargetVertex();
			if (c == a) break;
			psb->appendFace(a, b, c);
			psb->appendLink(a, b, 0, true);
			psb->appendLink(b, c, 0, true);
			psb->appendLink(c, a, 0, true);
			b = c;
			e = e->getNextEdgeOfFace();
		}
	}
	if (randomizeConstraints) psb->randomizeConstraints();
	return psb;
}

void btSoftBodyHelpers::ReoptimizeLinkOrder(btSoftBody* psb) { (void)psb; }
