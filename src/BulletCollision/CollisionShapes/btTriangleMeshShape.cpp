// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btTriangleMeshShape.h"

#include "LinearMath/btAabbUtil2.h"
#include "btMeshTriangleAccess.h"

btTriangleMeshShape::btTriangleMeshShape(btStridingMeshInterface* meshInterface)
    : m_localAabbMin(0, 0, 0), m_localAabbMax(0, 0, 0), m_meshInterface(meshInterface), m_fallbackScaling(1, 1, 1)
{
	m_shapeType = TRIANGLE_MESH_SHAPE_PROXYTYPE;
	btAssert(meshInterface != 0 && "btTriangleMeshShape: null mesh interface");
	if (m_meshInterface && m_meshInterface->hasPremadeAabb())
		m_meshInterface->getPremadeAabb(&m_localAabbMin, &m_localAabbMax);
	else
		recalcLocalAabb();
}

btTriangleMeshShape::~btTriangleMeshShape() {}

btVector3 btTriangleMeshShape::localGetSupportingVertex(const btVector3& vec) const
{
	btVector3 best(0, 0, 0);
	if (!m_meshInterface) return best;
	const btVector3 dir = caliber::supportDirection(vec);
	btScalar bestDot = -BT_LARGE_FLOAT;
	bool any = false;
	caliber::forEachMeshTriangle(*m_meshInterface,
	                             [&](const btVector3* triangle, int, int)
	                             {
		                             for (int k = 0; k < 3; ++k)
		                             {
			                             const btScalar d = dir.dot(triangle[k]);
			                             if (!any || d > bestDot)
			                             {
				                             any = true;
				                             bestDot = d;
				                             best = triangle[k];
			                             }
		                             }
	                             });
	return best;
}

void btTriangleMeshShape::recalcLocalAabb()
{
	m_localAabbMin.setValue(0, 0, 0);
	m_localAabbMax.setValue(0, 0, 0);
	if (m_meshInterface) m_meshInterface->calculateAabbBruteForce(m_localAabbMin, m_localAabbMax);
}

void btTriangleMeshShape::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const
{
	if (!caliber::checkAabbTransform(t, aabbMin, aabbMax)) return;
	btTransformAabb(m_localAabbMin, m_localAabbMax, getMargin(), t, aabbMin, aabbMax);
}

void btTriangleMeshShape::processAllTriangles(btTriangleCallback* callback, const btVector3& aabbMin,
                                              const btVector3& aabbMax) const
{
	btAssert(callback != 0);
	if (!callback || !m_meshInterface) return;
	caliber::forEachMeshTriangle(*m_meshInterface,
	                             [&](const btVector3* triangle, int partId, int triangleIndex)
	                             {
		                             btVector3 triMin, triMax;
		                             caliber::triangleAabb(triangle, triMin, triMax);
		                             if (!TestAabbAgainstAabb2(triMin, triMax, aabbMin, aabbMax)) return;
		                             btVector3 copy[3] = {triangle[0], triangle[1], triangle[2]};
		                             callback->processTriangle(copy, partId, triangleIndex);
	                             });
}

void btTriangleMeshShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const
{
	btAssert(mass == btScalar(0) && "triangle mesh shapes are static: use mass 0");
	(void)mass;
	inertia.setValue(0, 0, 0);
}

void btTriangleMeshShape::setLocalScaling(const btVector3& scaling)
{
	btAssert(caliber::isFinite(scaling) && "setLocalScaling: non-finite scaling");
	if (!m_meshInterface || !caliber::isFinite(scaling)) return;
	m_meshInterface->setScaling(scaling);
	recalcLocalAabb();
}

const btVector3& btTriangleMeshShape::getLocalScaling() const
{
	return m_meshInterface ? m_meshInterface->getScaling() : m_fallbackScaling;
}
