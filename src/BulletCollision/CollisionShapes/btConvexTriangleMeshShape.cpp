// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btConvexTriangleMeshShape.h"

#include "ConvexHullMassProperties.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btMatrix3x3.h"
#include "btMeshTriangleAccess.h"

btConvexTriangleMeshShape::btConvexTriangleMeshShape(btStridingMeshInterface* meshInterface, bool calcAabb)
    : m_stridingMesh(meshInterface)
{
	m_shapeType = CONVEX_TRIANGLEMESH_SHAPE_PROXYTYPE;
	btAssert(meshInterface != 0 && "btConvexTriangleMeshShape: null mesh interface");
	if (calcAabb) recalcLocalAabb();
}

btVector3 btConvexTriangleMeshShape::localGetSupportingVertexWithoutMargin(const btVector3& vec) const
{
	btVector3 support;
	batchedUnitVectorGetSupportingVertexWithoutMargin(&vec, &support, 1);
	return support;
}

btVector3 btConvexTriangleMeshShape::localGetSupportingVertex(const btVector3& vec) const
{
	return btConvexInternalShape::localGetSupportingVertex(vec);
}

void btConvexTriangleMeshShape::batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors,
                                                                                  btVector3* supportVerticesOut,
                                                                                  int numVectors) const
{
	if (numVectors <= 0) return;
	// The scores live in the w lane of each output, so no scratch memory is needed.
	for (int j = 0; j < numVectors; ++j)
	{
		supportVerticesOut[j].setValue(0, 0, 0);
		supportVerticesOut[j][3] = -BT_LARGE_FLOAT;
	}
	if (!m_stridingMesh) return;
	bool any = false;
	caliber::forEachMeshTriangle(*m_stridingMesh,
	                             [&](const btVector3* triangle, int, int)
	                             {
		                             for (int j = 0; j < numVectors; ++j)
		                             {
			                             const btVector3 dir = caliber::supportDirection(vectors[j]);
			                             for (int k = 0; k < 3; ++k)
			                             {
				                             const btScalar d = dir.dot(triangle[k]);
				                             if (!any || d > supportVerticesOut[j][3])
				                             {
					                             supportVerticesOut[j] = triangle[k];
					                             supportVerticesOut[j][3] = d;
				                             }
			                             }
		                             }
		                             any = true;
	                             });
	for (int j = 0; j < numVectors; ++j) supportVerticesOut[j][3] = btScalar(0);
}

void btConvexTriangleMeshShape::getEdge(int i, btVector3& pa, btVector3& pb) const
{
	(void)i;
	btAssert(false && "btConvexTriangleMeshShape::getEdge is not supported");
	pa.setValue(0, 0, 0);
	pb.setValue(0, 0, 0);
}

void btConvexTriangleMeshShape::getVertex(int i, btVector3& vtx) const
{
	(void)i;
	btAssert(false && "btConvexTriangleMeshShape::getVertex is not supported");
	vtx.setValue(0, 0, 0);
}

void btConvexTriangleMeshShape::getPlane(btVector3& planeNormal, btVector3& planeSupport, int i) const
{
	(void)i;
	btAssert(false && "btConvexTriangleMeshShape::getPlane is not supported");
	planeNormal.setValue(0, 0, 0);
	planeSupport.setValue(0, 0, 0);
}

bool btConvexTriangleMeshShape::isInside(const btVector3& pt, btScalar tolerance) const
{
	(void)pt;
	(void)tolerance;
	btAssert(false && "btConvexTriangleMeshShape::isInside is not supported");
	return false;
}

void btConvexTriangleMeshShape::setLocalScaling(const btVector3& scaling)
{
	btAssert(caliber::isFinite(scaling) && "setLocalScaling: non-finite scaling");
	if (!m_stridingMesh || !caliber::isFinite(scaling)) return;
	m_stridingMesh->setScaling(scaling);
	recalcLocalAabb();
}

const btVector3& btConvexTriangleMeshShape::getLocalScaling() const
{
	return m_stridingMesh ? m_stridingMesh->getScaling() : m_localScaling;
}

void btConvexTriangleMeshShape::calculatePrincipalAxisTransform(btTransform& principal, btVector3& inertia,
                                                                btScalar& volume) const
{
	btVector3 aabbMin(0, 0, 0), aabbMax(0, 0, 0);
	if (m_stridingMesh) m_stridingMesh->calculateAabbBruteForce(aabbMin, aabbMax);
	// Tetrahedra are taken from the AABB centre: near the mesh, so the signed volumes cancel with little
	// rounding.
	const btVector3 ref = btScalar(0.5) * (aabbMin + aabbMax);
	principal.setIdentity();
	principal.setOrigin(ref);
	inertia.setValue(0, 0, 0);
	volume = 0;
	if (!m_stridingMesh) return;

	// Signed sums over the tetrahedra (ref, a, b, c): volume, first moment, and the second moment
	// (covariance) C = det * A * K * A^T, K = [[2,1,1],[1,2,1],[1,1,2]] / 120, A = [a b c] (relative to ref).
	btScalar signedVolume = 0;
	btVector3 firstMoment(0, 0, 0);
	btScalar cov[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
	caliber::forEachMeshTriangle(
	    *m_stridingMesh,
	    [&](const btVector3* triangle, int, int)
	    {
		    const btVector3 a = triangle[0] - ref, b = triangle[1] - ref, c = triangle[2] - ref;
		    const btScalar det = a.dot(b.cross(c));
		    signedVolume += det / btScalar(6);
		    firstMoment += (det / btScalar(24)) * (a + b + c);
		    const btVector3 s = a + b + c;
		    for (int i = 0; i < 3; ++i)
			    for (int j = 0; j < 3; ++j)
				    cov[i][j] += det / btScalar(120) * (a[i] * a[j] + b[i] * b[j] + c[i] * c[j] + s[i] * s[j]);
	    });
	// Inward winding makes every sum negative; the solid is the same.
	const btScalar sign = signedVolume < 0 ? btScalar(-1) : btScalar(1);
	const btScalar v = sign * signedVolume;
	btVector3 extent = aabbMax - aabbMin;
	const btScalar scale = btMax(extent.x(), btMax(extent.y(), extent.z()));
	// Volumes below this are rounding noise of a flat or open mesh.
	if (!(v > scale * scale * scale * btScalar(1e-6))) return;
	const btVector3 centre = (sign / v) * firstMoment;
	btMatrix3x3 tensor;
	for (int i = 0; i < 3; ++i)
		for (int j = 0; j < 3; ++j)
		{
			// Covariance about the centre of mass (parallel axis), then I = trace(C) Id - C.
			tensor[i][j] = sign * cov[i][j] - v * centre[i] * centre[j];
		}
	const btScalar trace = tensor[0][0] + tensor[1][1] + tensor[2][2];
	btMatrix3x3 inertiaTensor;
	for (int i = 0; i < 3; ++i)
		for (int j = 0; j < 3; ++j) inertiaTensor[i][j] = (i == j ? trace : btScalar(0)) - tensor[i][j];
	btMatrix3x3 rotation;
	rotation.setIdentity();
	inertiaTensor.diagonalize(rotation, btScalar(1e-5), 20);
	principal.setBasis(rotation);
	principal.setOrigin(ref + centre);
	inertia.setValue(inertiaTensor[0][0], inertiaTensor[1][1], inertiaTensor[2][2]);
	inertia /= v;
	volume = v;
}

void btConvexTriangleMeshShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const
{
	if (!caliber::checkMass(mass, inertia)) return;
	btAlignedObjectArray<btVector3> points;
	if (m_stridingMesh)
		caliber::forEachMeshTriangle(*m_stridingMesh,
		                             [&](const btVector3* triangle, int, int)
		                             {
			                             for (int k = 0; k < 3; ++k) points.push_back(triangle[k]);
		                             });
	if (points.size() >= 4 && caliber::solidHullInertia(&points[0], points.size(), mass, inertia) &&
	    caliber::isFinite(inertia))
		return;
	caliber::aabbBoxInertia(*this, mass, inertia);
}
