// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btConvexHull.h"

#include <limits.h>
#include <string.h>

#include "LinearMath/btConvexHullComputer.h"

namespace
{
// A hull face plane: normal . p - offset is the signed distance of p, positive outside.
struct FacePlane
{
	btVector3 normal;
	btScalar offset;
};

// A corner that is the best pick for one face in a reduction round.
struct Pick
{
	int corner;
	btScalar distance;
};

struct FartherFirst
{
	bool operator()(const Pick& a, const Pick& b) const
	{
		return a.distance > b.distance || (a.distance == b.distance && a.corner < b.corner);
	}
};

// Reads input point i; memcpy because a stride need not keep btScalars aligned.
btVector3 readPoint(const HullDesc& desc, unsigned int i)
{
	btScalar xyz[3];
	memcpy(xyz, reinterpret_cast<const char*>(desc.mVertices) + size_t(i) * desc.mVertexStride, sizeof(xyz));
	return btVector3(xyz[0], xyz[1], xyz[2]);
}

void computeHull(const btAlignedObjectArray<btVector3>& points, btConvexHullComputer& hull)
{
	hull.compute(&points[0].x(), int(sizeof(btVector3)), points.size(), btScalar(0), btScalar(0));
}

// A solid hull has at least 4 faces; flat hulls have 2, segments and points none.
bool isSolid(const btConvexHullComputer& hull) { return hull.faces.size() >= 4; }

// Corner indices of face f, counter-clockwise seen from outside.
void faceCorners(const btConvexHullComputer& hull, int f, btAlignedObjectArray<int>& corners)
{
	corners.resizeNoInitialize(0);
	const btConvexHullComputer::Edge* first = &hull.edges[hull.faces[f]];
	const btConvexHullComputer::Edge* edge = first;
	do
	{
		corners.push_back(edge->getSourceVertex());
		edge = edge->getNextEdgeOfFace();
	} while (edge != first);
}

// Outward planes of every face. Newell's normal (the sum of the edge cross products about the first
// corner) is accurate for long thin faces too; the offset is the largest over the corners, so every
// corner is on or inside the plane.
void facePlanes(const btConvexHullComputer& hull, btAlignedObjectArray<FacePlane>& planes)
{
	btAlignedObjectArray<int> corners;
	planes.resizeNoInitialize(0);
	for (int f = 0; f < hull.faces.size(); ++f)
	{
		faceCorners(hull, f, corners);
		const btVector3& origin = hull.vertices[corners[0]];
		btVector3 normal(0, 0, 0);
		for (int k = 1; k + 1 < corners.size(); ++k)
			normal += (hull.vertices[corners[k]] - origin).cross(hull.vertices[corners[k + 1]] - origin);
		normal.safeNormalize();
		btScalar offset = -SIMD_INFINITY;
		for (int k = 0; k < corners.size(); ++k) offset = btMax(offset, normal.dot(hull.vertices[corners[k]]));
		planes.push_back(FacePlane{normal, offset});
	}
}

// Index of the corner farthest from origin once the components along the (unit, orthogonal) axes are removed.
int farthestCorner(const btAlignedObjectArray<btVector3>& corners, const btVector3& origin, const btVector3* axes,
                   int axisCount)
{
	int best = 0;
	btScalar bestDistance = -1;
	for (int i = 0; i < corners.size(); ++i)
	{
		btVector3 offset = corners[i] - origin;
		for (int k = 0; k < axisCount; ++k) offset -= axes[k] * axes[k].dot(offset);
		const btScalar distance = offset.length2();
		if (distance > bestDistance)
		{
			bestDistance = distance;
			best = i;
		}
	}
	return best;
}

// Chooses at most limit of the corners (see the header for the method) and stores them in chosen.
void reduceCorners(const btAlignedObjectArray<btVector3>& corners, int limit, btScalar relativeTolerance,
                   btAlignedObjectArray<btVector3>& chosen)
{
	const int count = corners.size();
	btAlignedObjectArray<char> state;  // 0 candidate, 1 chosen, 2 known inside
	state.resize(count, 0);
	chosen.resizeNoInitialize(0);
	auto choose = [&](int i)
	{
		state[i] = 1;
		chosen.push_back(corners[i]);
	};

	// Initial tetrahedron: smallest x, the corner farthest from it, the one farthest from their line,
	// the one farthest from their plane.
	int first = 0;
	for (int i = 1; i < count; ++i)
		if (corners[i].x() < corners[first].x()) first = i;
	const btVector3 origin = corners[first];
	choose(first);
	btVector3 axes[2];
	const int second = farthestCorner(corners, origin, axes, 0);
	axes[0] = (corners[second] - origin).normalized();
	const int third = farthestCorner(corners, origin, axes, 1);
	axes[1] = corners[third] - origin;
	axes[1] -= axes[0] * axes[0].dot(axes[1]);
	axes[1].safeNormalize();
	const int fourth = farthestCorner(corners, origin, axes, 2);
	if (state[second] == 0) choose(second);
	if (state[third] == 0) choose(third);
	if (state[fourth] == 0) choose(fourth);

	btConvexHullComputer hull;
	btAlignedObjectArray<FacePlane> planes;
	btAlignedObjectArray<Pick> bestOfFace;
	btAlignedObjectArray<Pick> picks;
	btAlignedObjectArray<btScalar> planeX, planeY, planeZ, planeOffset;
	btAlignedObjectArray<int> candidates;  // corners not yet chosen nor found inside
	for (int i = 0; i < count; ++i)
		if (state[i] == 0) candidates.push_back(i);
	while (chosen.size() < limit)
	{
		computeHull(chosen, hull);
		facePlanes(hull, planes);
		btVector3 boxMin = chosen[0], boxMax = chosen[0];
		for (int i = 1; i < chosen.size(); ++i)
		{
			boxMin.setMin(chosen[i]);
			boxMax.setMax(chosen[i]);
		}
		// The box only grows, so a corner once inside stays inside and is never tested again.
		const btScalar tolerance = relativeTolerance * (boxMax - boxMin).length();

		// Planes as separate coordinate arrays, so that the max over faces below vectorises.
		const int faceCount = planes.size();
		planeX.resizeNoInitialize(faceCount);
		planeY.resizeNoInitialize(faceCount);
		planeZ.resizeNoInitialize(faceCount);
		planeOffset.resizeNoInitialize(faceCount);
		for (int f = 0; f < faceCount; ++f)
		{
			planeX[f] = planes[f].normal.x();
			planeY[f] = planes[f].normal.y();
			planeZ[f] = planes[f].normal.z();
			planeOffset[f] = planes[f].offset;
		}

		// Raw pointers: no per-access index checks in the loops below.
		const btScalar* px = &planeX[0];
		const btScalar* py = &planeY[0];
		const btScalar* pz = &planeZ[0];
		const btScalar* pd = &planeOffset[0];

		bestOfFace.resizeNoInitialize(0);
		bestOfFace.resize(faceCount, Pick{-1, 0});
		int remaining = 0;
		for (int k = 0; k < candidates.size(); ++k)
		{
			const int i = candidates[k];
			if (state[i] != 0) continue;
			const btScalar x = corners[i].x(), y = corners[i].y(), z = corners[i].z();
			// Pass 1: the largest distance (branch-free); pass 2, only for outside corners: its face.
			btScalar largest = -SIMD_INFINITY;
			for (int f = 0; f < faceCount; ++f)
			{
				const btScalar distance = px[f] * x + py[f] * y + pz[f] * z - pd[f];
				largest = distance > largest ? distance : largest;
			}
			if (!(largest > tolerance))
			{
				state[i] = 2;
				continue;
			}
			candidates[remaining++] = i;
			// Stops at the face reaching pass 1's value; the running argmax keeps this safe should the
			// compiler round the two passes differently.
			int face = 0;
			btScalar faceDistance = -SIMD_INFINITY;
			for (int f = 0; f < faceCount; ++f)
			{
				const btScalar distance = px[f] * x + py[f] * y + pz[f] * z - pd[f];
				if (distance > faceDistance)
				{
					faceDistance = distance;
					face = f;
					if (distance >= largest) break;
				}
			}
			if (bestOfFace[face].corner < 0 || faceDistance > bestOfFace[face].distance)
				bestOfFace[face] = Pick{i, faceDistance};
		}
		candidates.resizeNoInitialize(remaining);

		picks.resizeNoInitialize(0);
		for (int f = 0; f < bestOfFace.size(); ++f)
			if (bestOfFace[f].corner >= 0) picks.push_back(bestOfFace[f]);
		if (picks.size() == 0) break;  // every corner is within tolerance of the chosen hull
		picks.quickSort(FartherFirst());
		for (int k = 0; k < picks.size() && chosen.size() < limit; ++k) choose(picks[k].corner);
	}
}

void writeMesh(const btConvexHullComputer& hull, bool triangles, bool reverse, HullResult& result)
{
	result.m_OutputVertices = hull.vertices;
	result.mNumOutputVertices = unsigned(hull.vertices.size());
	result.mPolygons = !triangles;
	result.m_Indices.resizeNoInitialize(0);
	btAlignedObjectArray<int> corners;
	unsigned int faceCount = 0;
	for (int f = 0; f < hull.faces.size(); ++f)
	{
		faceCorners(hull, f, corners);
		const int n = corners.size();
		if (triangles)
		{
			for (int k = 1; k + 1 < n; ++k)
			{
				result.m_Indices.push_back(unsigned(corners[0]));
				result.m_Indices.push_back(unsigned(corners[reverse ? k + 1 : k]));
				result.m_Indices.push_back(unsigned(corners[reverse ? k : k + 1]));
				++faceCount;
			}
		}
		else
		{
			result.m_Indices.push_back(unsigned(n));
			result.m_Indices.push_back(unsigned(corners[0]));
			for (int k = 1; k < n; ++k) result.m_Indices.push_back(unsigned(corners[reverse ? n - k : k]));
			++faceCount;
		}
	}
	result.mNumFaces = faceCount;
	result.mNumIndices = unsigned(result.m_Indices.size());
}
}  // namespace

HullError HullLibrary::CreateConvexHull(const HullDesc& desc, HullResult& result)
{
	ReleaseResult(result);
	if (desc.mVertices == 0 || desc.mVcount == 0 || desc.mVcount > unsigned(INT_MAX)) return QE_FAIL;
	if (desc.mVertexStride < 3 * sizeof(btScalar) || desc.mVertexStride > unsigned(INT_MAX)) return QE_FAIL;

	// btConvexHullComputer would skip non-finite points; here they make the input invalid.
	for (unsigned int i = 0; i < desc.mVcount; ++i)
	{
		const btVector3 p = readPoint(desc, i);
		if (!btIsFinite(p.x()) || !btIsFinite(p.y()) || !btIsFinite(p.z())) return QE_FAIL;
	}

	// 2V - 4 triangles for V corners, so mMaxFaces bounds V too.
	const unsigned int faceBound = desc.mMaxFaces / 2 + 2;
	const unsigned int limit = btMin(btMin(desc.mMaxVertices, faceBound), unsigned(INT_MAX));
	if (limit < 4) return QE_FAIL;

	btConvexHullComputer hull;
	hull.compute(reinterpret_cast<const btScalar*>(desc.mVertices), int(desc.mVertexStride), int(desc.mVcount),
	             btScalar(0), btScalar(0));
	if (!isSolid(hull)) return QE_FAIL;

	if (hull.vertices.size() > int(limit))
	{
		btAlignedObjectArray<btVector3> corners(hull.vertices);
		btAlignedObjectArray<btVector3> chosen;
		reduceCorners(corners, int(limit), btMax(desc.mNormalEpsilon, btScalar(0)), chosen);
		computeHull(chosen, hull);
		if (!isSolid(hull)) return QE_FAIL;
	}

	writeMesh(hull, desc.HasHullFlag(QF_TRIANGLES), desc.HasHullFlag(QF_REVERSE_ORDER), result);
	return QE_OK;
}

HullError HullLibrary::ReleaseResult(HullResult& result)
{
	result.m_OutputVertices.clear();
	result.m_Indices.clear();
	result.mNumOutputVertices = 0;
	result.mNumFaces = 0;
	result.mNumIndices = 0;
	return QE_OK;
}
