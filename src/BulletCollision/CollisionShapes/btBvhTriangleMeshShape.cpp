// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"

#include "BulletCollision/BroadphaseCollision/QuantizedBvhCast.h"
#include "BvhMeshCast.h"
#include "LinearMath/btAabbUtil2.h"
#include "btMeshTriangleAccess.h"

namespace
{
// Turns the leaves a tree query finds into triangles; a part stays locked while consecutive leaves use it.
class MeshNodeCallback : public btNodeOverlapCallback
{
public:
	MeshNodeCallback(const btStridingMeshInterface& mesh, btTriangleCallback* callback)
	    : m_mesh(mesh), m_scaling(mesh.getScaling()), m_callback(callback)
	{
	}
	void processNode(int partId, int triangleIndex) override
	{
		if (m_part.part() != partId) m_part.acquire(&m_mesh, partId);
		btVector3 triangle[3];
		if (m_part.readTriangle(triangleIndex, m_scaling, triangle))
			m_callback->processTriangle(triangle, partId, triangleIndex);
	}

private:
	const btStridingMeshInterface& m_mesh;
	const btVector3 m_scaling;
	btTriangleCallback* m_callback;
	caliber::ReadOnlyMeshPart m_part;
};

// The fallback without a tree: every triangle whose box overlaps [aabbMin, aabbMax].
void bruteForceBoxQuery(const btStridingMeshInterface& mesh, btTriangleCallback* callback, const btVector3& aabbMin,
                        const btVector3& aabbMax)
{
	caliber::forEachMeshTriangle(mesh,
	                             [&](const btVector3* triangle, int partId, int triangleIndex)
	                             {
		                             btVector3 triMin, triMax;
		                             caliber::triangleAabb(triangle, triMin, triMax);
		                             if (!TestAabbAgainstAabb2(triMin, triMax, aabbMin, aabbMax)) return;
		                             btVector3 copy[3] = {triangle[0], triangle[1], triangle[2]};
		                             callback->processTriangle(copy, partId, triangleIndex);
	                             });
}
}  // namespace

btBvhTriangleMeshShape::btBvhTriangleMeshShape(btStridingMeshInterface* meshInterface, bool useQuantizedAabbCompression,
                                               bool buildBvh)
    : btTriangleMeshShape(meshInterface),
      m_bvh(0),
      m_triangleInfoMap(0),
      m_useQuantizedAabbCompression(useQuantizedAabbCompression),
      m_ownsBvh(false)
{
	m_shapeType = TRIANGLE_MESH_SHAPE_PROXYTYPE;
	if (buildBvh) buildOptimizedBvh();
}

btBvhTriangleMeshShape::btBvhTriangleMeshShape(btStridingMeshInterface* meshInterface, bool useQuantizedAabbCompression,
                                               const btVector3& bvhAabbMin, const btVector3& bvhAabbMax, bool buildBvh)
    : btTriangleMeshShape(meshInterface),
      m_bvh(0),
      m_triangleInfoMap(0),
      m_useQuantizedAabbCompression(useQuantizedAabbCompression),
      m_ownsBvh(false)
{
	m_shapeType = TRIANGLE_MESH_SHAPE_PROXYTYPE;
	if (buildBvh)
	{
		m_bvh = new btOptimizedBvh();
		m_ownsBvh = true;
		m_bvh->build(m_meshInterface, m_useQuantizedAabbCompression, bvhAabbMin, bvhAabbMax);
	}
}

btBvhTriangleMeshShape::~btBvhTriangleMeshShape()
{
	if (m_ownsBvh) delete m_bvh;
}

void btBvhTriangleMeshShape::buildOptimizedBvh()
{
	if (m_ownsBvh) delete m_bvh;
	m_bvh = new btOptimizedBvh();
	m_ownsBvh = true;
	m_bvh->build(m_meshInterface, m_useQuantizedAabbCompression, m_localAabbMin, m_localAabbMax);
}

void btBvhTriangleMeshShape::processAllTriangles(btTriangleCallback* callback, const btVector3& aabbMin,
                                                 const btVector3& aabbMax) const
{
	btAssert(callback != 0);
	if (!callback || !m_meshInterface) return;
	if (!m_bvh)
	{
		btTriangleMeshShape::processAllTriangles(callback, aabbMin, aabbMax);
		return;
	}
	MeshNodeCallback nodes(*m_meshInterface, callback);
	m_bvh->reportAabbOverlappingNodex(&nodes, aabbMin, aabbMax);
}

void btBvhTriangleMeshShape::performRaycast(btTriangleCallback* callback, const btVector3& raySource,
                                            const btVector3& rayTarget)
{
	const btVector3 zero(0, 0, 0);
	performConvexcast(callback, raySource, rayTarget, zero, zero);
}

void btBvhTriangleMeshShape::performConvexcast(btTriangleCallback* callback, const btVector3& boxSource,
                                               const btVector3& boxTarget, const btVector3& boxMin,
                                               const btVector3& boxMax)
{
	caliber::castAgainstBvhMesh(*this, callback, boxSource, boxTarget, boxMin, boxMax, 0);
}

void caliber::castAgainstBvhMesh(btBvhTriangleMeshShape& mesh, btTriangleCallback* callback, const btVector3& boxSource,
                                 const btVector3& boxTarget, const btVector3& boxMin, const btVector3& boxMax,
                                 const btScalar* maxFraction)
{
	btAssert(callback != 0);
	const btStridingMeshInterface* meshInterface = mesh.getMeshInterface();
	if (!callback || !meshInterface) return;
	const btOptimizedBvh* bvh = mesh.getOptimizedBvh();
	if (!bvh)
	{
		const bool finite = caliber::isFinite(boxSource) && caliber::isFinite(boxTarget) && caliber::isFinite(boxMin) &&
		                    caliber::isFinite(boxMax);
		btAssert(finite && "performConvexcast: non-finite input");
		if (!finite) return;
		btVector3 sweepMin = boxSource, sweepMax = boxSource;
		sweepMin.setMin(boxTarget);
		sweepMax.setMax(boxTarget);
		bruteForceBoxQuery(*meshInterface, callback, sweepMin + boxMin, sweepMax + boxMax);
		return;
	}
	MeshNodeCallback nodes(*meshInterface, callback);
	caliber::reportBoxCastOverlappingNodes(*bvh, &nodes, boxSource, boxTarget, boxMin, boxMax, maxFraction);
}

void btBvhTriangleMeshShape::refitTree(const btVector3& aabbMin, const btVector3& aabbMax)
{
	if (m_bvh && m_meshInterface) m_bvh->refit(m_meshInterface, aabbMin, aabbMax);
	recalcLocalAabb();
}

void btBvhTriangleMeshShape::partialRefitTree(const btVector3& aabbMin, const btVector3& aabbMax)
{
	const bool finite = caliber::isFinite(aabbMin) && caliber::isFinite(aabbMax);
	btAssert(finite && "partialRefitTree: non-finite box");
	if (!finite) return;
	if (m_bvh && m_meshInterface) m_bvh->refitPartial(m_meshInterface, aabbMin, aabbMax);
	m_localAabbMin.setMin(aabbMin);
	m_localAabbMax.setMax(aabbMax);
}

void btBvhTriangleMeshShape::setLocalScaling(const btVector3& scaling)
{
	btAssert(caliber::isFinite(scaling) && "setLocalScaling: non-finite scaling");
	if (!caliber::isFinite(scaling)) return;
	if ((getLocalScaling() - scaling).length2() > SIMD_EPSILON)
	{
		btTriangleMeshShape::setLocalScaling(scaling);
		buildOptimizedBvh();
	}
}

void btBvhTriangleMeshShape::setOptimizedBvh(btOptimizedBvh* bvh, const btVector3& scaling)
{
	if (m_ownsBvh) delete m_bvh;
	m_bvh = bvh;
	m_ownsBvh = false;
	// The tree was built for scaling: take it over without rebuilding.
	if ((getLocalScaling() - scaling).length2() > SIMD_EPSILON) btTriangleMeshShape::setLocalScaling(scaling);
}
