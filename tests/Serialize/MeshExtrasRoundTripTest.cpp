// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// The parts of a .bullet file beyond shapes and bodies: a mesh's BVH (btQuantizedBvhFloatData /
// DoubleData) and triangle info map, and contact manifolds (BT_SERIALIZE_CONTACT_MANIFOLDS). Written,
// read back, compared field by field; a mesh read with its stored tree must answer ray tests exactly as
// the original; damaged trees, maps and manifolds give a warning and never a read out of bounds.
#include <gtest/gtest.h>

#include <limits.h>
#include <string.h>

#include <limits>

#include <vector>

#include "BulletCollision/BroadphaseCollision/QuantizedBvhAccess.h"
#include "BulletCollision/CollisionDispatch/btInternalEdgeUtility.h"
#include "BulletCollision/CollisionShapes/btTriangleInfoMap.h"
#include "SerializeTestUtil.h"
#include "btBulletFile.h"
#include "btBulletWorldImporter.h"

using namespace caliber_test;

namespace
{
// A bumpy grid of 2 * n * n triangles (two parts so part ids matter), with 32-bit indices.
struct Terrain
{
	std::vector<btVector3> vertices[2];
	std::vector<int> indices[2];
	btTriangleIndexVertexArray mesh;

	explicit Terrain(int n)
	{
		for (int p = 0; p < 2; ++p)
		{
			for (int i = 0; i <= n; ++i)
				for (int j = 0; j <= n; ++j)
				{
					const btScalar x = btScalar(i) + btScalar(p * n), z = btScalar(j);
					vertices[p].push_back(btVector3(x, btSin(x * btScalar(0.7)) + btCos(z * btScalar(1.3)), z));
				}
			for (int i = 0; i < n; ++i)
				for (int j = 0; j < n; ++j)
				{
					const int a = i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
					const int tri[6] = {a, b, c, b, d, c};
					indices[p].insert(indices[p].end(), tri, tri + 6);
				}
			btIndexedMesh part;
			part.m_numTriangles = int(indices[p].size() / 3);
			part.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(&indices[p][0]);
			part.m_triangleIndexStride = 3 * sizeof(int);
			part.m_numVertices = int(vertices[p].size());
			part.m_vertexBase = reinterpret_cast<const unsigned char*>(&vertices[p][0]);
			part.m_vertexStride = sizeof(btVector3);
#ifdef BT_USE_DOUBLE_PRECISION
			part.m_vertexType = PHY_DOUBLE;
#endif
			mesh.addIndexedMesh(part, PHY_INTEGER);
		}
	}
};

// The protected state of a tree, for field-by-field comparison.
struct TreeState
{
	btVector3 aabbMin, aabbMax, quantization;
	int nodes;
	bool quantized;
	std::vector<btQuantizedBvhNode> qnodes;
	std::vector<btOptimizedBvhNode> pnodes;
	std::vector<btBvhSubtreeInfo> headers;
};

TreeState stateOf(btQuantizedBvh& bvh)
{
	caliber::QuantizedBvhParts p = caliber::QuantizedBvhAccess::parts(bvh);
	TreeState s;
	s.aabbMin = caliber::bvhAabbMin(bvh);
	s.aabbMax = caliber::bvhAabbMax(bvh);
	s.quantization = caliber::bvhQuantization(bvh);
	s.nodes = p.curNodeIndex;
	s.quantized = p.useQuantization;
	for (int i = 0; i < p.quantizedContiguousNodes.size(); ++i) s.qnodes.push_back(p.quantizedContiguousNodes[i]);
	for (int i = 0; i < p.contiguousNodes.size(); ++i) s.pnodes.push_back(p.contiguousNodes[i]);
	for (int i = 0; i < p.subtreeHeaders.size(); ++i) s.headers.push_back(p.subtreeHeaders[i]);
	EXPECT_EQ(p.subtreeHeaderCount, p.subtreeHeaders.size());
	return s;
}

bool sameVector(const btVector3& a, const btVector3& b) { return a.x() == b.x() && a.y() == b.y() && a.z() == b.z(); }

void expectSameTree(btQuantizedBvh& original, btQuantizedBvh& read)
{
	const TreeState a = stateOf(original), b = stateOf(read);
	EXPECT_TRUE(sameVector(a.aabbMin, b.aabbMin));
	EXPECT_TRUE(sameVector(a.aabbMax, b.aabbMax));
	EXPECT_TRUE(sameVector(a.quantization, b.quantization));
	EXPECT_EQ(a.nodes, b.nodes);
	EXPECT_EQ(a.quantized, b.quantized);
	ASSERT_EQ(a.qnodes.size(), b.qnodes.size());
	for (size_t i = 0; i < a.qnodes.size(); ++i)
	{
		EXPECT_EQ(0, memcmp(a.qnodes[i].m_quantizedAabbMin, b.qnodes[i].m_quantizedAabbMin, 6)) << i;
		EXPECT_EQ(0, memcmp(a.qnodes[i].m_quantizedAabbMax, b.qnodes[i].m_quantizedAabbMax, 6)) << i;
		EXPECT_EQ(a.qnodes[i].m_escapeIndexOrTriangleIndex, b.qnodes[i].m_escapeIndexOrTriangleIndex) << i;
	}
	ASSERT_EQ(a.pnodes.size(), b.pnodes.size());
	for (size_t i = 0; i < a.pnodes.size(); ++i)
	{
		EXPECT_TRUE(sameVector(a.pnodes[i].m_aabbMinOrg, b.pnodes[i].m_aabbMinOrg)) << i;
		EXPECT_TRUE(sameVector(a.pnodes[i].m_aabbMaxOrg, b.pnodes[i].m_aabbMaxOrg)) << i;
		EXPECT_EQ(a.pnodes[i].m_escapeIndex, b.pnodes[i].m_escapeIndex) << i;
		EXPECT_EQ(a.pnodes[i].m_subPart, b.pnodes[i].m_subPart) << i;
		EXPECT_EQ(a.pnodes[i].m_triangleIndex, b.pnodes[i].m_triangleIndex) << i;
	}
	ASSERT_EQ(a.headers.size(), b.headers.size());
	for (size_t h = 0; h < a.headers.size(); ++h)
	{
		EXPECT_EQ(0, memcmp(a.headers[h].m_quantizedAabbMin, b.headers[h].m_quantizedAabbMin, 6)) << h;
		EXPECT_EQ(0, memcmp(a.headers[h].m_quantizedAabbMax, b.headers[h].m_quantizedAabbMax, 6)) << h;
		EXPECT_EQ(a.headers[h].m_rootNodeIndex, b.headers[h].m_rootNodeIndex) << h;
		EXPECT_EQ(a.headers[h].m_subtreeSize, b.headers[h].m_subtreeSize) << h;
	}
}

// A world holding one static mesh shape, for ray tests.
struct RayWorld
{
	btDefaultCollisionConfiguration config;
	btCollisionDispatcher dispatcher{&config};
	btDbvtBroadphase broadphase;
	btCollisionWorld world{&dispatcher, &broadphase, &config};
	btCollisionObject object;
	explicit RayWorld(btCollisionShape* shape)
	{
		object.setCollisionShape(shape);
		world.addCollisionObject(&object);
	}
	~RayWorld() { world.removeCollisionObject(&object); }
};

struct Hit
{
	bool hit;
	btScalar fraction;
	btVector3 normal;
	int part, triangle;
};

struct TriangleRayCallback : btCollisionWorld::ClosestRayResultCallback
{
	int part = -1, triangle = -1;
	TriangleRayCallback(const btVector3& from, const btVector3& to) : ClosestRayResultCallback(from, to) {}
	btScalar addSingleResult(btCollisionWorld::LocalRayResult& r, bool normalInWorldSpace) override
	{
		part = r.m_localShapeInfo ? r.m_localShapeInfo->m_shapePart : -1;
		triangle = r.m_localShapeInfo ? r.m_localShapeInfo->m_triangleIndex : -1;
		return ClosestRayResultCallback::addSingleResult(r, normalInWorldSpace);
	}
};

// Slanted rays from above over the shape's box and a little beyond: most hit, some miss, some graze.
std::vector<Hit> castRays(btCollisionShape* shape)
{
	RayWorld w(shape);
	btTransform identity;
	identity.setIdentity();
	btVector3 low, high;
	shape->getAabb(identity, low, high);
	std::vector<Hit> hits;
	for (int i = 0; i < 40; ++i)
		for (int j = 0; j < 12; ++j)
		{
			const btScalar x = low.x() - 1 + (high.x() - low.x() + 2) * btScalar(i) / 39;
			const btScalar z = low.z() + (high.z() - low.z()) * btScalar(j) / 11;
			const btVector3 from(x, high.y() + 2, z);
			const btVector3 to = from + btVector3(btScalar(0.1) * btScalar(j - 6), low.y() - high.y() - 4, btScalar(0.3));
			TriangleRayCallback cb(from, to);
			w.world.rayTest(from, to, cb);
			hits.push_back(Hit{cb.hasHit(), cb.m_closestHitFraction, cb.m_hitNormalWorld, cb.part, cb.triangle});
		}
	return hits;
}

void expectSameHits(const std::vector<Hit>& a, const std::vector<Hit>& b)
{
	ASSERT_EQ(a.size(), b.size());
	int hits = 0;
	for (size_t i = 0; i < a.size(); ++i)
	{
		EXPECT_EQ(a[i].hit, b[i].hit) << i;
		EXPECT_EQ(a[i].fraction, b[i].fraction) << i;
		EXPECT_TRUE(sameVector(a[i].normal, b[i].normal)) << i;
		EXPECT_EQ(a[i].part, b[i].part) << i;
		EXPECT_EQ(a[i].triangle, b[i].triangle) << i;
		hits += a[i].hit;
	}
	// The rays must exercise the tree: most hit, some miss.
	EXPECT_GT(hits, int(a.size()) / 2);
	EXPECT_LT(hits, int(a.size()));
}

std::vector<char> saveShape(btCollisionShape* shape, int flags = 0)
{
	btDefaultSerializer s;
	s.setSerializationFlags(flags);
	s.startSerialization();
	shape->serializeSingleShape(&s);
	s.finishSerialization();
	return bytesOf(s);
}

// An importer into no world that deletes what it made (btWorldImporter's destructor leaves that to
// deleteAllData, as Bullet's does).
struct OwningImporter : btBulletWorldImporter
{
	OwningImporter() : btBulletWorldImporter(0) {}
	~OwningImporter() override { deleteAllData(); }
};

btBvhTriangleMeshShape* onlyMesh(btBulletWorldImporter& importer)
{
	EXPECT_EQ(importer.getNumCollisionShapes(), 1);
	return importer.getNumCollisionShapes() == 1
	           ? dynamic_cast<btBvhTriangleMeshShape*>(importer.getCollisionShapeByIndex(0))
	           : 0;
}
}  // namespace

TEST(MeshExtras, QuantizedAndPlainTreesReadBackFieldByFieldAndAnswerRaysAlike)
{
	for (int quantized = 0; quantized < 2; ++quantized)
	{
		SCOPED_TRACE(quantized ? "quantized" : "plain");
		Terrain terrain(12);
		// A quantization box larger than the mesh: a rebuilt tree would differ from the stored one.
		btBvhTriangleMeshShape original(&terrain.mesh, quantized != 0, btVector3(-7, -9, -5), btVector3(40, 8, 20));
		std::vector<char> file = saveShape(&original);
		ASSERT_TRUE(findChunk(walkChunks(file), BT_QUANTIZED_BVH_CODE));

		OwningImporter importer;
		WarningLog log;
		ASSERT_TRUE(importer.loadFileFromMemory(&file[0], int(file.size())));
		EXPECT_EQ(log.count(), 0) << log.all();
		btBvhTriangleMeshShape* read = onlyMesh(importer);
		ASSERT_TRUE(read);
		ASSERT_EQ(importer.getNumBvhs(), 1);
		EXPECT_EQ(read->getOptimizedBvh(), importer.getBvhByIndex(0));  // the stored tree, not a rebuilt one
		EXPECT_FALSE(read->getOwnsBvh());
		EXPECT_EQ(read->usesQuantizedAabbCompression(), quantized != 0);
		expectSameTree(*original.getOptimizedBvh(), *read->getOptimizedBvh());
		expectSameHits(castRays(&original), castRays(read));
	}
}

TEST(MeshExtras, ScaledMeshKeepsItsScalingWithTheStoredTree)
{
	Terrain terrain(6);
	terrain.mesh.setScaling(btVector3(2, btScalar(0.5), 3));
	btBvhTriangleMeshShape original(&terrain.mesh, true);
	std::vector<char> file = saveShape(&original);
	OwningImporter importer;
	ASSERT_TRUE(importer.loadFileFromMemory(&file[0], int(file.size())));
	btBvhTriangleMeshShape* read = onlyMesh(importer);
	ASSERT_TRUE(read);
	EXPECT_TRUE(sameVector(read->getLocalScaling(), original.getLocalScaling()));
	EXPECT_EQ(read->getOptimizedBvh(), importer.getBvhByIndex(0));
	expectSameTree(*original.getOptimizedBvh(), *read->getOptimizedBvh());
	expectSameHits(castRays(&original), castRays(read));
}

TEST(MeshExtras, TriangleInfoMapReadsBackEveryEntryAndTolerance)
{
	Terrain terrain(5);
	btBvhTriangleMeshShape original(&terrain.mesh, true);
	btTriangleInfoMap map;
	map.m_convexEpsilon = btScalar(0.01);  // every tolerance differs from the default
	map.m_planarEpsilon = btScalar(0.002);
	map.m_equalVertexThreshold = btScalar(0.0003);
	map.m_edgeDistanceThreshold = btScalar(0.04);
	map.m_zeroAreaThreshold = btScalar(0.0005);
	btGenerateInternalEdgeInfo(&original, &map);
	ASSERT_GT(map.size(), 50);
	std::vector<char> file = saveShape(&original);
	ASSERT_TRUE(findChunk(walkChunks(file), BT_TRIANLGE_INFO_MAP));

	OwningImporter importer;
	ASSERT_TRUE(importer.loadFileFromMemory(&file[0], int(file.size())));
	btBvhTriangleMeshShape* read = onlyMesh(importer);
	ASSERT_TRUE(read);
	const btTriangleInfoMap* back = read->getTriangleInfoMap();
	ASSERT_TRUE(back);
	ASSERT_EQ(back->size(), map.size());
	// The file holds floats: in double builds the numbers come back rounded to float.
	auto f = [](btScalar x) { return btScalar(float(x)); };
	EXPECT_EQ(back->m_convexEpsilon, f(map.m_convexEpsilon));
	EXPECT_EQ(back->m_planarEpsilon, f(map.m_planarEpsilon));
	EXPECT_EQ(back->m_equalVertexThreshold, f(map.m_equalVertexThreshold));
	EXPECT_EQ(back->m_edgeDistanceThreshold, f(map.m_edgeDistanceThreshold));
	EXPECT_EQ(back->m_zeroAreaThreshold, f(map.m_zeroAreaThreshold));
	for (int i = 0; i < map.size(); ++i)
	{
		const btHashInt key = map.getKeyAtIndex(i);
		const btTriangleInfo* a = map.find(key);
		const btTriangleInfo* b = back->find(key);
		ASSERT_TRUE(a && b) << key.getUid1();
		EXPECT_EQ(a->m_flags, b->m_flags);
		EXPECT_EQ(f(a->m_edgeV0V1Angle), b->m_edgeV0V1Angle);
		EXPECT_EQ(f(a->m_edgeV1V2Angle), b->m_edgeV1V2Angle);
		EXPECT_EQ(f(a->m_edgeV2V0Angle), b->m_edgeV2V0Angle);
	}
}

TEST(MeshExtras, NoBvhAndNoTriangleInfoMapFlagsLeaveThemOut)
{
	Terrain terrain(4);
	btBvhTriangleMeshShape original(&terrain.mesh, true);
	btTriangleInfoMap map;
	btGenerateInternalEdgeInfo(&original, &map);
	std::vector<char> file = saveShape(&original, BT_SERIALIZE_NO_BVH | BT_SERIALIZE_NO_TRIANGLEINFOMAP);
	const std::vector<ChunkAt> chunks = walkChunks(file);
	EXPECT_FALSE(findChunk(chunks, BT_QUANTIZED_BVH_CODE));
	EXPECT_FALSE(findChunk(chunks, BT_TRIANLGE_INFO_MAP));
	OwningImporter importer;
	ASSERT_TRUE(importer.loadFileFromMemory(&file[0], int(file.size())));
	btBvhTriangleMeshShape* read = onlyMesh(importer);
	ASSERT_TRUE(read);
	EXPECT_TRUE(read->getOwnsBvh());  // rebuilt from the mesh
	EXPECT_FALSE(read->getTriangleInfoMap());
	expectSameHits(castRays(&original), castRays(read));
}

TEST(MeshExtras, SerializeSingleBvhAndMapWriteOneChunkEachThatLoads)
{
	Terrain terrain(4);
	btBvhTriangleMeshShape original(&terrain.mesh, true);
	btTriangleInfoMap map;
	btGenerateInternalEdgeInfo(&original, &map);
	btDefaultSerializer s;
	s.startSerialization();
	original.serializeSingleBvh(&s);
	original.serializeSingleTriangleInfoMap(&s);
	s.finishSerialization();
	std::vector<char> file = bytesOf(s);
	const std::vector<ChunkAt> chunks = walkChunks(file);
	EXPECT_TRUE(findChunk(chunks, BT_QUANTIZED_BVH_CODE) && !findChunk(chunks, BT_QUANTIZED_BVH_CODE, 1));
	EXPECT_TRUE(findChunk(chunks, BT_TRIANLGE_INFO_MAP) && !findChunk(chunks, BT_TRIANLGE_INFO_MAP, 1));
	EXPECT_FALSE(findChunk(chunks, BT_SHAPE_CODE));
	OwningImporter importer;
	ASSERT_TRUE(importer.loadFileFromMemory(&file[0], int(file.size())));
	ASSERT_EQ(importer.getNumBvhs(), 1);
	ASSERT_EQ(importer.getNumTriangleInfoMaps(), 1);
	expectSameTree(*original.getOptimizedBvh(), *importer.getBvhByIndex(0));
	EXPECT_EQ(importer.getTriangleInfoMapByIndex(0)->size(), map.size());

	// Without a tree or map there is nothing to write.
	btBvhTriangleMeshShape bare(&terrain.mesh, true, false);
	s.startSerialization();
	bare.serializeSingleBvh(&s);
	bare.serializeSingleTriangleInfoMap(&s);
	EXPECT_EQ(s.getNumChunks(), 0);
	s.finishSerialization();
}

TEST(MeshExtras, ContactManifoldsReadBackFieldByField)
{
	TestWorld w;
	btCollisionShape* ground = w.shape(new btBoxShape(btVector3(10, 1, 10)));
	btCollisionShape* box = w.shape(new btBoxShape(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5))));
	w.body(ground, 0, btVector3(0, -1, 0));
	for (int i = 0; i < 3; ++i) w.body(box, 1, btVector3(btScalar(i) * btScalar(1.5), btScalar(0.6), btScalar(0.1) * i));
	for (int i = 0; i < 20; ++i) w.world.stepSimulation(btScalar(1) / 60, 0);
	ASSERT_EQ(w.dispatcher.getNumManifolds(), 3);

	btDefaultSerializer s;
	s.setSerializationFlags(BT_SERIALIZE_CONTACT_MANIFOLDS);
	std::vector<char> file = w.save(&s);
	bParse::btBulletFile parsed(&file[0], int(file.size()));
	parsed.parse(0);
	ASSERT_TRUE(parsed.ok());
	ASSERT_EQ(parsed.m_contactManifolds.size(), 3);
	for (int m = 0; m < 3; ++m)
	{
		const btPersistentManifold* a = w.dispatcher.getManifoldByIndexInternal(m);
		btPersistentManifold b;
		b.deSerialize(reinterpret_cast<btPersistentManifoldData*>(parsed.m_contactManifolds[m]));
		ASSERT_GT(a->getNumContacts(), 0);
		ASSERT_EQ(a->getNumContacts(), b.getNumContacts());
		EXPECT_EQ(a->getContactBreakingThreshold(), b.getContactBreakingThreshold());
		EXPECT_EQ(a->getContactProcessingThreshold(), b.getContactProcessingThreshold());
		EXPECT_EQ(a->m_companionIdA, b.m_companionIdA);
		EXPECT_EQ(a->m_companionIdB, b.m_companionIdB);
		EXPECT_EQ(a->m_index1a, b.m_index1a);
		for (int i = 0; i < a->getNumContacts(); ++i)
		{
			const btManifoldPoint& p = a->getContactPoint(i);
			const btManifoldPoint& q = b.getContactPoint(i);
			EXPECT_TRUE(sameVector(p.m_localPointA, q.m_localPointA));
			EXPECT_TRUE(sameVector(p.m_localPointB, q.m_localPointB));
			EXPECT_TRUE(sameVector(p.m_positionWorldOnA, q.m_positionWorldOnA));
			EXPECT_TRUE(sameVector(p.m_positionWorldOnB, q.m_positionWorldOnB));
			EXPECT_TRUE(sameVector(p.m_normalWorldOnB, q.m_normalWorldOnB));
			EXPECT_TRUE(sameVector(p.m_lateralFrictionDir1, q.m_lateralFrictionDir1));
			EXPECT_TRUE(sameVector(p.m_lateralFrictionDir2, q.m_lateralFrictionDir2));
			EXPECT_EQ(p.m_distance1, q.m_distance1);
			EXPECT_EQ(p.m_appliedImpulse, q.m_appliedImpulse);
			EXPECT_EQ(p.m_prevRHS, q.m_prevRHS);
			EXPECT_EQ(p.m_combinedFriction, q.m_combinedFriction);
			EXPECT_EQ(p.m_combinedRollingFriction, q.m_combinedRollingFriction);
			EXPECT_EQ(p.m_combinedSpinningFriction, q.m_combinedSpinningFriction);
			EXPECT_EQ(p.m_combinedRestitution, q.m_combinedRestitution);
			EXPECT_EQ(p.m_partId0, q.m_partId0);
			EXPECT_EQ(p.m_partId1, q.m_partId1);
			EXPECT_EQ(p.m_index0, q.m_index0);
			EXPECT_EQ(p.m_index1, q.m_index1);
			EXPECT_EQ(p.m_contactPointFlags, q.m_contactPointFlags);
			EXPECT_EQ(p.m_appliedImpulseLateral1, q.m_appliedImpulseLateral1);
			EXPECT_EQ(p.m_appliedImpulseLateral2, q.m_appliedImpulseLateral2);
			EXPECT_EQ(p.m_contactMotion1, q.m_contactMotion1);
			EXPECT_EQ(p.m_contactMotion2, q.m_contactMotion2);
			EXPECT_EQ(p.m_contactCFM, q.m_contactCFM);
			EXPECT_EQ(p.m_combinedContactStiffness1, q.m_combinedContactStiffness1);
			EXPECT_EQ(p.m_contactERP, q.m_contactERP);
			EXPECT_EQ(p.m_combinedContactDamping1, q.m_combinedContactDamping1);
			EXPECT_EQ(p.m_frictionCFM, q.m_frictionCFM);
			EXPECT_EQ(p.m_lifeTime, q.m_lifeTime);
		}
	}
	// Without the flag no manifold is written.
	btDefaultSerializer plain;
	std::vector<char> without = w.save(&plain);
	EXPECT_FALSE(findChunk(walkChunks(without), BT_CONTACTMANIFOLD_CODE));
}

// ---- bad input --------------------------------------------------------------------------------

namespace
{
void readInto(btQuantizedBvh& bvh, btQuantizedBvhData& d)
{
#ifdef BT_USE_DOUBLE_PRECISION
	bvh.deSerializeDouble(d);
#else
	bvh.deSerializeFloat(d);
#endif
}
}  // namespace

TEST(MeshExtrasBadInput, DamagedTreesAreRefusedWithAWarningAndLeaveAnEmptyTree)
{
	Terrain terrain(3);
	btBvhTriangleMeshShape shape(&terrain.mesh, true);
	btOptimizedBvh* source = shape.getOptimizedBvh();
	caliber::QuantizedBvhParts parts = caliber::QuantizedBvhAccess::parts(*source);
	const int n = parts.curNodeIndex;
	ASSERT_GT(n, 10);
	// Node and header arrays as a file would give them.
	std::vector<btQuantizedBvhNodeData> nodes(size_t(parts.quantizedContiguousNodes.size()));
	for (size_t i = 0; i < nodes.size(); ++i)
	{
		for (int a = 0; a < 3; ++a)
		{
			nodes[i].m_quantizedAabbMin[a] = short(parts.quantizedContiguousNodes[int(i)].m_quantizedAabbMin[a]);
			nodes[i].m_quantizedAabbMax[a] = short(parts.quantizedContiguousNodes[int(i)].m_quantizedAabbMax[a]);
		}
		nodes[i].m_escapeIndexOrTriangleIndex = parts.quantizedContiguousNodes[int(i)].m_escapeIndexOrTriangleIndex;
	}
	std::vector<btBvhSubtreeInfoData> headers(size_t(parts.subtreeHeaders.size()));
	for (size_t h = 0; h < headers.size(); ++h)
	{
		headers[h].m_rootNodeIndex = parts.subtreeHeaders[int(h)].m_rootNodeIndex;
		headers[h].m_subtreeSize = parts.subtreeHeaders[int(h)].m_subtreeSize;
		for (int a = 0; a < 3; ++a)
		{
			headers[h].m_quantizedAabbMin[a] = short(parts.subtreeHeaders[int(h)].m_quantizedAabbMin[a]);
			headers[h].m_quantizedAabbMax[a] = short(parts.subtreeHeaders[int(h)].m_quantizedAabbMax[a]);
		}
	}
	ASSERT_GE(headers.size(), 1u);
	btQuantizedBvhData good;
	memset(&good, 0, sizeof(good));
	caliber::bvhAabbMin(*source).serialize(good.m_bvhAabbMin);
	caliber::bvhAabbMax(*source).serialize(good.m_bvhAabbMax);
	caliber::bvhQuantization(*source).serialize(good.m_bvhQuantization);
	good.m_curNodeIndex = n;
	good.m_useQuantization = 1;
	good.m_numQuantizedContiguousNodes = int(nodes.size());
	good.m_quantizedContiguousNodesPtr = &nodes[0];
	good.m_numSubtreeHeaders = int(headers.size());
	good.m_subTreeInfoPtr = &headers[0];

	{
		btOptimizedBvh bvh;
		WarningLog log;
		readInto(bvh, good);
		EXPECT_EQ(log.count(), 0) << log.all();
		expectSameTree(*source, bvh);  // the hand-made data is right before it is damaged
	}
	struct Damage
	{
		const char* what;
		void (*apply)(btQuantizedBvhData&, std::vector<btQuantizedBvhNodeData>&, std::vector<btBvhSubtreeInfoData>&);
	};
	const Damage damages[] = {
	    {"node count beyond the array", [](btQuantizedBvhData& d, auto&, auto&) { d.m_curNodeIndex += 1000; }},
	    {"negative count", [](btQuantizedBvhData& d, auto&, auto&) { d.m_numSubtreeHeaders = -1; }},
	    {"missing array", [](btQuantizedBvhData& d, auto&, auto&) { d.m_quantizedContiguousNodesPtr = 0; }},
	    {"root escape too long", [](btQuantizedBvhData&, auto& nodes, auto&) { nodes[0].m_escapeIndexOrTriangleIndex -= 5; }},
	    {"escape of INT_MIN", [](btQuantizedBvhData&, auto& nodes, auto&) { nodes[1].m_escapeIndexOrTriangleIndex = INT_MIN; }},
	    {"inner escape off by one",
	     [](btQuantizedBvhData&, auto& nodes, auto&)
	     {
		     for (size_t i = 1; i < nodes.size(); ++i)
			     if (nodes[i].m_escapeIndexOrTriangleIndex < 0)
			     {
				     nodes[i].m_escapeIndexOrTriangleIndex += 1;
				     return;
			     }
	     }},
	    {"header beyond the tree", [](btQuantizedBvhData&, auto&, auto& headers) { headers[0].m_rootNodeIndex = 1 << 20; }},
	    {"header of the wrong size", [](btQuantizedBvhData&, auto&, auto& headers) { headers[0].m_subtreeSize += 1; }},
	    {"non-finite quantization",
	     [](btQuantizedBvhData& d, auto&, auto&) { d.m_bvhQuantization.m_floats[1] = std::numeric_limits<btScalar>::quiet_NaN(); }},
	    {"unknown quantization flag", [](btQuantizedBvhData& d, auto&, auto&) { d.m_useQuantization = 7; }},
	};
	for (const Damage& damage : damages)
	{
		SCOPED_TRACE(damage.what);
		btQuantizedBvhData d = good;
		std::vector<btQuantizedBvhNodeData> damagedNodes = nodes;
		std::vector<btBvhSubtreeInfoData> damagedHeaders = headers;
		d.m_quantizedContiguousNodesPtr = d.m_quantizedContiguousNodesPtr ? &damagedNodes[0] : 0;
		d.m_subTreeInfoPtr = &damagedHeaders[0];
		damage.apply(d, damagedNodes, damagedHeaders);
		btOptimizedBvh bvh;
		WarningLog log;
		readInto(bvh, d);
		EXPECT_TRUE(log.contains("btQuantizedBvh::deSerialize")) << log.all();
		EXPECT_EQ(caliber::bvhNodeCount(bvh), 0);
		struct Count : btNodeOverlapCallback
		{
			int leaves = 0;
			void processNode(int, int) override { ++leaves; }
		} count;
		bvh.reportAabbOverlappingNodex(&count, btVector3(-1e9, -1e9, -1e9), btVector3(1e9, 1e9, 1e9));
		EXPECT_EQ(count.leaves, 0);
	}
}

namespace
{
// Writes the terrain shape (with its tree and map), lets damage change the converted data of the file
// before the importer builds objects, and loads.
template <class Damage>
void loadDamaged(Damage damage, const char* expectedWarning, bool expectStoredTree)
{
	Terrain terrain(4);
	btBvhTriangleMeshShape original(&terrain.mesh, true);
	btTriangleInfoMap map;
	btGenerateInternalEdgeInfo(&original, &map);
	std::vector<char> file = saveShape(&original);
	bParse::btBulletFile parsed(&file[0], int(file.size()));
	parsed.parse(0);
	ASSERT_TRUE(parsed.ok());
	ASSERT_EQ(parsed.m_bvhs.size(), 1);
	ASSERT_EQ(parsed.m_triangleInfoMaps.size(), 1);
	damage(parsed);
	OwningImporter importer;
	WarningLog log;
	ASSERT_TRUE(importer.loadFileFromMemory(&parsed));
	if (expectedWarning)
		EXPECT_TRUE(log.contains(expectedWarning)) << log.all();
	else
		EXPECT_EQ(log.count(), 0) << log.all();
	btBvhTriangleMeshShape* read = onlyMesh(importer);
	ASSERT_TRUE(read);  // the mesh itself still loads
	EXPECT_EQ(read->getOwnsBvh(), !expectStoredTree);
	expectSameHits(castRays(&original), castRays(read));
}
}  // namespace

TEST(MeshExtrasBadInput, ImporterRebuildsTreesThatDoNotFitTheirMesh)
{
	// A leaf naming a triangle the mesh does not have: the mesh query would read outside the indices.
	loadDamaged(
	    [](bParse::btBulletFile& f)
	    {
		    btQuantizedBvhData* d = reinterpret_cast<btQuantizedBvhData*>(f.m_bvhs[0]);
		    for (int i = 0; i < d->m_curNodeIndex; ++i)
			    if (d->m_quantizedContiguousNodesPtr[i].m_escapeIndexOrTriangleIndex >= 0)
			    {
				    d->m_quantizedContiguousNodesPtr[i].m_escapeIndexOrTriangleIndex = 5000;
				    return;
			    }
	    },
	    "does not fit the mesh", false);
	// A leaf of a part the mesh does not have.
	loadDamaged(
	    [](bParse::btBulletFile& f)
	    {
		    btQuantizedBvhData* d = reinterpret_cast<btQuantizedBvhData*>(f.m_bvhs[0]);
		    for (int i = 0; i < d->m_curNodeIndex; ++i)
			    if (d->m_quantizedContiguousNodesPtr[i].m_escapeIndexOrTriangleIndex >= 0)
			    {
				    d->m_quantizedContiguousNodesPtr[i].m_escapeIndexOrTriangleIndex = 9 << 21;
				    return;
			    }
	    },
	    "does not fit the mesh", false);
	// More nodes claimed than the node chunk holds (a truncated array).
	loadDamaged(
	    [](bParse::btBulletFile& f)
	    {
		    btQuantizedBvhData* d = reinterpret_cast<btQuantizedBvhData*>(f.m_bvhs[0]);
		    d->m_numQuantizedContiguousNodes += 100;
		    d->m_curNodeIndex += 100;
	    },
	    "malformed", false);
	// A node array pointer that names no chunk (a bad pointer becomes null on reading).
	loadDamaged([](bParse::btBulletFile& f)
	            { reinterpret_cast<btQuantizedBvhData*>(f.m_bvhs[0])->m_quantizedContiguousNodesPtr = 0; },
	            "malformed", false);
	// A broken escape index: refused by deSerialize, so the mesh builds its own tree.
	loadDamaged([](bParse::btBulletFile& f)
	            { reinterpret_cast<btQuantizedBvhData*>(f.m_bvhs[0])->m_quantizedContiguousNodesPtr[0].m_escapeIndexOrTriangleIndex = -3; },
	            "btQuantizedBvh::deSerialize", false);
	// Undamaged, the stored tree is used.
	loadDamaged([](bParse::btBulletFile&) {}, 0, true);
}

TEST(MeshExtrasBadInput, DamagedTriangleInfoMapsAreDropped)
{
	loadDamaged([](bParse::btBulletFile& f)
	            { reinterpret_cast<btTriangleInfoMapData*>(f.m_triangleInfoMaps[0])->m_numKeys += 1; },
	            "triangle info map", true);
	loadDamaged(
	    [](bParse::btBulletFile& f)
	    {
		    btTriangleInfoMapData* d = reinterpret_cast<btTriangleInfoMapData*>(f.m_triangleInfoMaps[0]);
		    d->m_numKeys += 1000;  // beyond the key chunk
		    d->m_numValues += 1000;
	    },
	    "triangle info map", true);
	btTriangleInfoMapData d;
	memset(&d, 0, sizeof(d));
	d.m_numKeys = d.m_numValues = 3;  // arrays missing
	btTriangleInfoMap map;
	WarningLog log;
	map.deSerialize(d);
	EXPECT_TRUE(log.contains("btTriangleInfoMap::deSerialize")) << log.all();
	EXPECT_EQ(map.size(), 0);
}

TEST(MeshExtrasBadInput, ManifoldsWithBadCountsOrNumbersAreLeftEmpty)
{
	btPersistentManifoldData d;
	memset(&d, 0, sizeof(d));
	d.m_numCachedPoints = 2;
	d.m_contactBreakingThreshold = btScalar(0.02);
	d.m_contactProcessingThreshold = btScalar(0.02);
	{
		btPersistentManifold m;
		WarningLog log;
		m.deSerialize(&d);
		EXPECT_EQ(log.count(), 0) << log.all();
		EXPECT_EQ(m.getNumContacts(), 2);
	}
	btPersistentManifoldData bad = d;
	bad.m_numCachedPoints = 5;
	btPersistentManifoldData nan = d;
	nan.m_pointCacheAppliedImpulse[1] = std::numeric_limits<btScalar>::quiet_NaN();
	for (btPersistentManifoldData* data : {&bad, &nan})
	{
		btPersistentManifold m;
		WarningLog log;
		m.deSerialize(data);
		EXPECT_TRUE(log.contains("btPersistentManifold::deSerialize")) << log.all();
		EXPECT_EQ(m.getNumContacts(), 0);
	}
}
