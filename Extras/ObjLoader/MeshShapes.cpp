// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "ObjLoader/MeshShapes.h"

#include "LinearMath/btConvexHullComputer.h"

namespace caliber
{
bool OwnedTriangleIndexVertexArray::addMesh(const ObjMesh& mesh)
{
	const int numVertices = mesh.vertices.size();
	const int numIndices = mesh.indices.size();
	if (numIndices < 3 || numIndices % 3 != 0) return false;
	for (int i = 0; i < numIndices; ++i)
	{
		if (mesh.indices[i] < 0 || mesh.indices[i] >= numVertices)
		{
			btAssert(!"OwnedTriangleIndexVertexArray::addMesh: index out of range");
			return false;
		}
	}
	std::unique_ptr<Part> part(new Part);
	part->coordinates.resize(std::size_t(numVertices) * 3);
	for (int v = 0; v < numVertices; ++v)
		for (int axis = 0; axis < 3; ++axis) part->coordinates[std::size_t(v) * 3 + axis] = mesh.vertices[v][axis];
	part->indices.assign(&mesh.indices[0], &mesh.indices[0] + numIndices);

	btIndexedMesh indexed;
	indexed.m_numTriangles = numIndices / 3;
	indexed.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(part->indices.data());
	indexed.m_triangleIndexStride = 3 * sizeof(int);
	indexed.m_numVertices = numVertices;
	indexed.m_vertexBase = reinterpret_cast<const unsigned char*>(part->coordinates.data());
	indexed.m_vertexStride = 3 * sizeof(btScalar);
	addIndexedMesh(indexed, PHY_INTEGER);
	m_parts.push_back(std::move(part));
	return true;
}

StaticMeshShape buildStaticMeshShape(const ObjModel& model)
{
	StaticMeshShape result;
	if (!model.ok()) return result;
	std::unique_ptr<OwnedTriangleIndexVertexArray> mesh(new OwnedTriangleIndexVertexArray);
	int parts = 0;
	for (const ObjMesh& objMesh : model.meshes)
		if (mesh->addMesh(objMesh)) ++parts;
	if (parts == 0) return result;
	result.shape.reset(new btBvhTriangleMeshShape(mesh.get(), true));
	result.mesh = std::move(mesh);
	return result;
}

std::unique_ptr<btConvexHullShape> buildConvexHullShape(const ObjMesh& mesh)
{
	const int count = mesh.vertices.size();
	if (count < 4) return nullptr;
	// A flat or degenerate cloud has at most 2 hull faces (the polygon's two sides); a solid has 4 or more.
	btConvexHullComputer computer;
	computer.compute(&mesh.vertices[0][0], sizeof(btVector3), count, 0, 0);
	if (computer.faces.size() < 4) return nullptr;

	std::unique_ptr<btConvexHullShape> hull(new btConvexHullShape());
	for (int i = 0; i < computer.vertices.size(); ++i) hull->addPoint(computer.vertices[i], false);
	hull->recalcLocalAabb();
	return hull;
}
std::vector<std::unique_ptr<btConvexHullShape>> buildConvexHullShapes(const ObjModel& model)
{
	std::vector<std::unique_ptr<btConvexHullShape>> hulls;
	if (!model.ok()) return hulls;
	for (const ObjMesh& mesh : model.meshes) hulls.push_back(buildConvexHullShape(mesh));
	return hulls;
}
}  // namespace caliber
