// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btConvexPolyhedron.h"

namespace
{
// Two unit edge directions closer than this (squared chord, about 1e-3 rad) count as the same axis:
// parallel edges of one polytope differ only by rounding, far below it.
const btScalar kSameDirectionChord2 = btScalar(1e-6);

bool faceIsUsable(const btFace& face, int vertexCount)
{
	if (face.m_indices.size() < 3) return false;
	for (int i = 0; i < face.m_indices.size(); ++i)
	{
		if (face.m_indices[i] < 0 || face.m_indices[i] >= vertexCount) return false;
	}
	return true;
}
}  // namespace

btConvexPolyhedron::btConvexPolyhedron()
    : m_localCenter(0, 0, 0), m_extents(0, 0, 0), m_radius(0), mC(0, 0, 0), mE(0, 0, 0)
{
}

btConvexPolyhedron::~btConvexPolyhedron() {}

void btConvexPolyhedron::initialize()
{
	m_uniqueEdges.resize(0);
	const int vertexCount = m_vertices.size();
	for (int f = 0; f < m_faces.size(); ++f)
	{
		const btFace& face = m_faces[f];
		const int n = face.m_indices.size();
		for (int i = 0; i < n; ++i)
		{
			const int a = face.m_indices[i];
			const int b = face.m_indices[(i + 1) % n];
			if (a < 0 || a >= vertexCount || b < 0 || b >= vertexCount) continue;
			btVector3 edge = m_vertices[b] - m_vertices[a];
			const btScalar length = edge.length();
			if (!(length > SIMD_EPSILON)) continue;
			edge /= length;
			bool known = false;
			for (int k = 0; k < m_uniqueEdges.size() && !known; ++k)
			{
				known = (m_uniqueEdges[k] - edge).length2() < kSameDirectionChord2 ||
				        (m_uniqueEdges[k] + edge).length2() < kSameDirectionChord2;
			}
			if (!known) m_uniqueEdges.push_back(edge);
		}
	}
	initialize2();
}

void btConvexPolyhedron::initialize2()
{
	const int vertexCount = m_vertices.size();
	m_localCenter.setValue(0, 0, 0);
	m_extents.setValue(0, 0, 0);
	m_radius = 0;
	mC.setValue(0, 0, 0);
	mE.setValue(0, 0, 0);
	if (vertexCount == 0) return;

	btVector3 aabbMin = m_vertices[0], aabbMax = m_vertices[0];
	btVector3 vertexMean(0, 0, 0);
	for (int i = 0; i < vertexCount; ++i)
	{
		aabbMin.setMin(m_vertices[i]);
		aabbMax.setMax(m_vertices[i]);
		vertexMean += m_vertices[i];
	}
	vertexMean /= btScalar(vertexCount);
	mC = (aabbMin + aabbMax) * btScalar(0.5);
	mE = (aabbMax - aabbMin) * btScalar(0.5);

	// Centre of volume by a fan of tetrahedra from the vertex mean; centre of area if flat.
	btScalar volume6 = 0, area2 = 0;
	btVector3 volumeMoment(0, 0, 0), areaMoment(0, 0, 0);
	for (int f = 0; f < m_faces.size(); ++f)
	{
		const btFace& face = m_faces[f];
		btAssert(faceIsUsable(face, vertexCount));
		if (!faceIsUsable(face, vertexCount)) continue;
		const btVector3& a = m_vertices[face.m_indices[0]];
		for (int i = 1; i + 1 < face.m_indices.size(); ++i)
		{
			const btVector3& b = m_vertices[face.m_indices[i]];
			const btVector3& c = m_vertices[face.m_indices[i + 1]];
			const btScalar tetra6 = (a - vertexMean).dot((b - vertexMean).cross(c - vertexMean));
			volume6 += tetra6;
			volumeMoment += tetra6 * (a + b + c + vertexMean) * btScalar(0.25);
			const btScalar triangle2 = (b - a).cross(c - a).length();
			area2 += triangle2;
			areaMoment += triangle2 * (a + b + c) / btScalar(3);
		}
	}
	// A volume below this share of the bounding box's counts as flat (rounding of a planar face set).
	const btScalar boxVolume = btScalar(8) * mE.x() * mE.y() * mE.z();
	if (volume6 > btScalar(6) * boxVolume * btScalar(1e-6) && volume6 > 0)
		m_localCenter = volumeMoment / volume6;
	else if (area2 > 0)
		m_localCenter = areaMoment / area2;
	else
		m_localCenter = vertexMean;

	bool anyFace = false;
	btScalar radius = SIMD_INFINITY;
	for (int f = 0; f < m_faces.size(); ++f)
	{
		if (!faceIsUsable(m_faces[f], vertexCount)) continue;
		const btFace& face = m_faces[f];
		const btVector3 normal(face.m_plane[0], face.m_plane[1], face.m_plane[2]);
		const btScalar depth = -(normal.dot(m_localCenter) + face.m_plane[3]);
		anyFace = true;
		if (depth < radius) radius = depth;
	}
	m_radius = (anyFace && radius > 0 && btIsFinite(radius)) ? radius : btScalar(0);

	// The cube inscribed in the inner sphere is inside; then each axis grows by bisection as long as
	// the box stays inside (a bigger box rejects more in SAT culling).
	const btScalar cube = m_radius / btSqrt(btScalar(3));
	m_extents.setValue(cube, cube, cube);
	if (m_radius <= 0) return;
	for (int axis = 0; axis < 3; ++axis)
	{
		btScalar inside = m_extents[axis];
		btScalar outside = mE[axis] + btScalar(2) * mC.distance(m_localCenter) + m_radius;
		for (int step = 0; step < 16; ++step)
		{
			const btScalar trial = btScalar(0.5) * (inside + outside);
			m_extents[axis] = trial;
			if (testContainment())
				inside = trial;
			else
				outside = trial;
		}
		m_extents[axis] = inside;
	}
}

bool btConvexPolyhedron::testContainment() const
{
	for (int corner = 0; corner < 8; ++corner)
	{
		const btVector3 point = m_localCenter + btVector3((corner & 1) ? m_extents.x() : -m_extents.x(),
		                                                  (corner & 2) ? m_extents.y() : -m_extents.y(),
		                                                  (corner & 4) ? m_extents.z() : -m_extents.z());
		for (int f = 0; f < m_faces.size(); ++f)
		{
			const btFace& face = m_faces[f];
			const btScalar distance = face.m_plane[0] * point.x() + face.m_plane[1] * point.y() +
			                          face.m_plane[2] * point.z() + face.m_plane[3];
			if (distance > 0) return false;
		}
	}
	return true;
}

void btConvexPolyhedron::project(const btTransform& trans, const btVector3& dir, btScalar& minProj, btScalar& maxProj,
                                 btVector3& witnesPtMin, btVector3& witnesPtMax) const
{
	const btScalar originProj = trans.getOrigin().dot(dir);
	btAssert(m_vertices.size() > 0);
	const btVector3 localDir = dir * trans.getBasis();
	btScalar localMax = 0, localMin = 0;
	const long maxIndex = m_vertices.size() > 0 ? localDir.maxDot(&m_vertices[0], m_vertices.size(), localMax) : -1;
	const long minIndex = m_vertices.size() > 0 ? localDir.minDot(&m_vertices[0], m_vertices.size(), localMin) : -1;
	if (maxIndex < 0 || minIndex < 0)
	{
		minProj = maxProj = originProj;
		witnesPtMin = witnesPtMax = trans.getOrigin();
		return;
	}
	minProj = localMin + originProj;
	maxProj = localMax + originProj;
	witnesPtMin = trans(m_vertices[int(minIndex)]);
	witnesPtMax = trans(m_vertices[int(maxIndex)]);
}
