// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btMeshContactCollector.h"

#include "BulletCollision/CollisionDispatch/btConvexTriangleClipping.h"
#include "BulletCollision/CollisionShapes/btTriangleShape.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "LinearMath/btAlignedObjectArray.h"

namespace caliber
{
namespace
{
// Same tolerance as face clipping: a normal within about 2.5 degrees of the triangle's is its face's.
const btScalar kFaceNormalCosine = btScalar(0.999);

// A point on an edge or a vertex of its triangle whose normal leans further than this from the face's
// (about 0.26 degrees) is that edge's or vertex's, even within kFaceNormalCosine: a sphere beside a
// triangle it is not over meets the triangle's edge at a normal leaning by asin(offset / radius), a few
// degrees when the edge is centimetres away, and that lean pushed a rolling sphere up by a centimetre.
const btScalar kExactFaceNormalCosine = btScalar(0.99999);

// A point closer than this fraction of the triangle's longest edge to a vertex or an edge is on it
// (GJK's closest points carry about that much rounding in float).
const btScalar kFeatureTolerance = btScalar(1e-3);

// Vertices this close to a face's plane, as a fraction of the face's size, are in it (flat ground).
const btScalar kCoplanarTolerance = btScalar(1e-4);

struct CollectedTriangle
{
	btVector3 vertices[3];  // in the concave's space, exactly as the shape reported them
	btVector3 faceNormal;   // in world space, not normalised (its length is twice the area)
	btScalar faceLimit2;    // a normal n is the face's when (faceNormal . n)^2 reaches this (found once)
	int partId;
	int index;
	bool faceContact;       // some point of it lies on its face: its edges and vertices are covered
	bool planeKnown;        // localNormal and size are set (asked of face-contact triangles only)
	btVector3 localNormal;  // unit, in the concave's space; zero for a degenerate triangle
	btScalar size;
};

// The plane of a face-contact triangle, found once per frame however many points ask.
void knowPlane(CollectedTriangle& triangle)
{
	if (triangle.planeKnown) return;
	triangle.planeKnown = true;
	const btVector3* face = triangle.vertices;
	const btVector3 normal = (face[1] - face[0]).cross(face[2] - face[0]);
	const btScalar length = normal.length();
	triangle.localNormal = length > 0 ? normal / length : btVector3(0, 0, 0);
	triangle.size = btSqrt(btMax((face[1] - face[0]).length2(), (face[2] - face[0]).length2()));
}

struct CollectedPoint
{
	btVector3 normal;
	btVector3 point;
	btScalar depth;
	int triangle;
	bool onFace;  // its normal is its triangle's: never an internal edge's
};
}  // namespace

struct MeshContactScratch
{
	btAlignedObjectArray<CollectedTriangle> triangles;
	btAlignedObjectArray<CollectedPoint> points;
	btAlignedObjectArray<btVector3> positions;
	btAlignedObjectArray<btScalar> depths;
	btAlignedObjectArray<int> kept;
	btAlignedObjectArray<int> faces;  // the triangles with a face contact, in order (built by flush when asked)
	int faceTriangles = 0;  // how many triangles have a face contact
	// The concave side of each flushed point: its vertices are set for the point's triangle.
	btTriangleShape triangle{btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(0, 0, 0)};
};

namespace
{
// One per thread: pairs are collided one at a time on a thread, and the arrays keep their capacity.
MeshContactScratch& scratch()
{
	static thread_local MeshContactScratch perThread;
	return perThread;
}

// The edge or vertex of the triangle (world corners) the point lies on, as vertex bits; 0 inside the face.
// Edges, their lengths and the point's offsets are found once, before any test, so that the independent
// arithmetic overlaps (the tests' early returns would otherwise serialise it).
int featureOf(const btVector3* corners, const btVector3& point)
{
	const btVector3 edges[3] = {corners[1] - corners[0], corners[2] - corners[1], corners[0] - corners[2]};
	const btScalar lengths2[3] = {edges[0].length2(), edges[1].length2(), edges[2].length2()};
	const btVector3 offsets[3] = {point - corners[0], point - corners[1], point - corners[2]};
	const btScalar tolerance2 =
	    kFeatureTolerance * kFeatureTolerance * btMax(btMax(btMax(btScalar(0), lengths2[0]), lengths2[1]), lengths2[2]);
	for (int k = 0; k < 3; ++k)
		if (offsets[k].length2() <= tolerance2) return 1 << k;
	for (int k = 0; k < 3; ++k)
	{
		if (!(lengths2[k] > 0)) continue;
		const btScalar t = btMax(btScalar(0), btMin(btScalar(1), offsets[k].dot(edges[k]) / lengths2[k]));
		if ((offsets[k] - edges[k] * t).length2() <= tolerance2) return (1 << k) | (1 << (k == 2 ? 0 : k + 1));
	}
	return 0;
}

// Exact equality of two vertices' coordinates, without a branch per coordinate (vertices of nearby
// triangles differ in unpredictable coordinates, and mispredicted branches cost more than the compares).
inline bool sameVertex(const btVector3& a, const btVector3& b)
{
	return (a.x() == b.x()) & (a.y() == b.y()) & (a.z() == b.z());
}

// True when the edge or vertex point of triangle `self` is internal: each of its feature vertices is a
// corner of a triangle on whose face a point lies (shared vertices are reported bit-identical by meshes
// and height fields, so exact comparison finds them), or the triangle lies in the plane of such a face
// (a flat region: the faces the convex lies on already hold it, and no feature of that plane can push it
// sideways).
// `faces` lists the face-contact triangles: only they are scanned (most collected triangles are not).
bool isInternalFeature(btAlignedObjectArray<CollectedTriangle>& triangles, const btAlignedObjectArray<int>& faces,
                       int self, int featureVertices)
{
	const CollectedTriangle& triangle = triangles[self];
	bool allShared = true;
	for (int k = 0; k < 3 && allShared; ++k)
	{
		if (!(featureVertices & (1 << k))) continue;
		const btVector3& vertex = triangle.vertices[k];
		bool shared = false;
		for (int f = 0; f < faces.size() && !shared; ++f)
		{
			const int t = faces[f];
			if (t == self) continue;
			const btVector3* other = triangles[t].vertices;
			shared = sameVertex(other[0], vertex) | sameVertex(other[1], vertex) | sameVertex(other[2], vertex);
		}
		allShared = shared;
	}
	if (allShared) return true;
	for (int f = 0; f < faces.size(); ++f)
	{
		const int t = faces[f];
		if (t == self) continue;
		CollectedTriangle& face = triangles[t];
		knowPlane(face);
		if (!(face.localNormal.length2() > 0)) continue;
		bool coplanar = true;
		for (int k = 0; k < 3 && coplanar; ++k)
			coplanar = btFabs((triangle.vertices[k] - face.vertices[0]).dot(face.localNormal)) <=
			           kCoplanarTolerance * face.size;
		if (coplanar) return true;
	}
	return false;
}
}  // namespace

MeshContactCollector::MeshContactCollector(btManifoldResult& pairResult, bool convexIsBody0, btScalar triangleMargin,
                                           bool holdFacePoints)
    : btManifoldResult(pairResult),
      m_pairResult(pairResult),
      m_scratch(scratch()),
      m_convexIsBody0(convexIsBody0),
      m_holdFacePoints(holdFacePoints),
      m_triangleMargin(triangleMargin)
{
	m_scratch.triangles.resizeNoInitialize(0);
	m_scratch.points.resizeNoInitialize(0);
	m_scratch.faceTriangles = 0;
}

void MeshContactCollector::addContactPoint(const btVector3& normalOnBInWorld, const btVector3& pointInWorld,
                                           btScalar depth)
{
	if (!m_manifoldPtr || !m_body0Wrap || !m_body1Wrap) return;
	// Points the pair's result would drop are not worth keeping (or choosing among).
	if (!(depth <= m_manifoldPtr->getContactBreakingThreshold() + m_closestPointDistanceThreshold)) return;
	const btCollisionObjectWrapper* triangleWrap = m_convexIsBody0 ? m_body1Wrap : m_body0Wrap;
	const btCollisionShape* shape = triangleWrap->getCollisionShape();
	if (!shape || shape->getShapeType() != TRIANGLE_SHAPE_PROXYTYPE) return;
	const btTriangleShape* triangle = static_cast<const btTriangleShape*>(shape);
	const int partId = m_convexIsBody0 ? m_partId1 : m_partId0;
	const int index = m_convexIsBody0 ? m_index1 : m_index0;

	MeshContactScratch& s = m_scratch;
	// The callback visits each triangle once and its algorithm reports its points together.
	int slot = s.triangles.size() - 1;
	if (slot < 0 || s.triangles[slot].partId != partId || s.triangles[slot].index != index)
	{
		CollectedTriangle& added = s.triangles.expandNonInitializing();
		for (int k = 0; k < 3; ++k) added.vertices[k] = triangle->m_vertices1[k];
		added.faceNormal = triangleWrap->getWorldTransform().getBasis() *
		                   (added.vertices[1] - added.vertices[0]).cross(added.vertices[2] - added.vertices[0]);
		added.faceLimit2 = kFaceNormalCosine * kFaceNormalCosine * added.faceNormal.length2();
		added.partId = partId;
		added.index = index;
		added.faceContact = false;
		added.planeKnown = false;
		slot = s.triangles.size() - 1;
	}
	CollectedTriangle& collected = s.triangles[slot];
	const btScalar along = collected.faceNormal.dot(normalOnBInWorld);
	bool onFace = along * along >= collected.faceLimit2 && along != 0;
	if (onFace && along * along < kExactFaceNormalCosine * kExactFaceNormalCosine * collected.faceNormal.length2())
	{
		// Near the face's normal but not on it: the face's only if the point lies inside the face.
		const btTransform& transform = triangleWrap->getWorldTransform();
		const btVector3 corners[3] = {transform(collected.vertices[0]), transform(collected.vertices[1]),
		                              transform(collected.vertices[2])};
		onFace = featureOf(corners, pointInWorld - normalOnBInWorld * m_triangleMargin) == 0;
	}
	if (onFace && !collected.faceContact)
	{
		collected.faceContact = true;
		++s.faceTriangles;
	}
	if (onFace && !m_holdFacePoints)
	{
		// Never an internal edge's point, and one triangle's own: straight to the pair's result.
		if (m_convexIsBody0)
		{
			const btCollisionObjectWrapper* saved = m_pairResult.getBody1Wrap();
			m_pairResult.setBody1Wrap(m_body1Wrap);
			m_pairResult.setShapeIdentifiersB(partId, index);
			m_pairResult.addContactPoint(normalOnBInWorld, pointInWorld, depth);
			m_pairResult.setBody1Wrap(saved);
		}
		else
		{
			const btCollisionObjectWrapper* saved = m_pairResult.getBody0Wrap();
			m_pairResult.setBody0Wrap(m_body0Wrap);
			m_pairResult.setShapeIdentifiersA(partId, index);
			m_pairResult.addContactPoint(normalOnBInWorld, pointInWorld, depth);
			m_pairResult.setBody0Wrap(saved);
		}
		return;
	}

	CollectedPoint& point = s.points.expandNonInitializing();
	point.normal = normalOnBInWorld;
	point.point = pointInWorld;
	point.depth = depth;
	point.triangle = slot;
	point.onFace = onFace;
}

void MeshContactCollector::flush(const btCollisionObjectWrapper* concaveWrap)
{
	MeshContactScratch& s = m_scratch;
	if (s.points.size() == 0) return;

	// A point on an internal edge or vertex is dropped: the faces the convex lies on already hold it, and
	// the edge's normal leans across the surface (a ghost bump, or a wall where there is none). Only a face
	// contact on another triangle can make a point internal.
	s.kept.resizeNoInitialize(0);
	s.faces.resizeNoInitialize(0);
	const btTransform& transform = concaveWrap->getWorldTransform();
	for (int i = 0; i < s.points.size(); ++i)
	{
		const CollectedPoint& point = s.points[i];
		const CollectedTriangle& triangle = s.triangles[point.triangle];
		const int otherFaces = s.faceTriangles - (triangle.faceContact ? 1 : 0);
		if (point.onFace || otherFaces == 0)
		{
			s.kept.push_back(i);
			continue;
		}
		const btVector3 corners[3] = {transform(triangle.vertices[0]), transform(triangle.vertices[1]),
		                              transform(triangle.vertices[2])};
		const int feature = featureOf(corners, point.point - point.normal * m_triangleMargin);
		if (feature != 0 && s.faces.size() == 0)
			for (int t = 0; t < s.triangles.size(); ++t)
				if (s.triangles[t].faceContact) s.faces.push_back(t);
		if (feature == 0 || !isInternalFeature(s.triangles, s.faces, point.triangle, feature)) s.kept.push_back(i);
	}
	if (s.kept.size() == 0) return;

	// At most 4 (a manifold's size), spanning the largest area across the normal of the deepest.
	int chosen[4];
	int numChosen = 0;
	if (s.kept.size() <= 4)
	{
		for (int i = 0; i < s.kept.size(); ++i) chosen[numChosen++] = i;
	}
	else
	{
		s.positions.resizeNoInitialize(s.kept.size());
		s.depths.resizeNoInitialize(s.kept.size());
		int deepest = 0;
		for (int i = 0; i < s.kept.size(); ++i)
		{
			s.positions[i] = s.points[s.kept[i]].point;
			s.depths[i] = s.points[s.kept[i]].depth;
			if (s.depths[i] < s.depths[deepest]) deepest = i;
		}
		numChosen = chooseManifoldPoints(&s.positions[0], &s.depths[0], s.kept.size(), s.points[s.kept[deepest]].normal,
		                                 chosen);
	}

	const btCollisionObjectWrapper* savedWrap =
	    m_convexIsBody0 ? m_pairResult.getBody1Wrap() : m_pairResult.getBody0Wrap();
	// One triangle shape serves every point: its vertices are set for each point's triangle.
	btTriangleShape& triangle = s.triangle;
	triangle.setMargin(m_triangleMargin);
	for (int c = 0; c < numChosen; ++c)
	{
		const CollectedPoint& point = s.points[s.kept[chosen[c]]];
		const CollectedTriangle& source = s.triangles[point.triangle];
		for (int k = 0; k < 3; ++k) triangle.m_vertices1[k] = source.vertices[k];
		btCollisionObjectWrapper triangleWrap(concaveWrap, &triangle, concaveWrap->getCollisionObject(), transform,
		                                      source.partId, source.index);
		if (m_convexIsBody0)
		{
			m_pairResult.setBody1Wrap(&triangleWrap);
			m_pairResult.setShapeIdentifiersB(source.partId, source.index);
		}
		else
		{
			m_pairResult.setBody0Wrap(&triangleWrap);
			m_pairResult.setShapeIdentifiersA(source.partId, source.index);
		}
		m_pairResult.addContactPoint(point.normal, point.point, point.depth);
	}
	if (m_convexIsBody0)
		m_pairResult.setBody1Wrap(savedWrap);
	else
		m_pairResult.setBody0Wrap(savedWrap);
}
}  // namespace caliber
