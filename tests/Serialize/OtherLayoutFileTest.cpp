// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// Files in the other pointer size and byte order, built here by hand: a file this build wrote is
// re-encoded field by field from its own DNA (pointers narrowed to 4 bytes or kept at 8, every
// number byte-swapped for big-endian), as a writer on such a machine would have produced it. The
// re-encoder below is independent of the loader: it has its own DNA walk. Each variant must load
// into the same world as the original file.
#include <gtest/gtest.h>

#include <stdint.h>

#include <algorithm>
#include <map>
#include <set>

#include "BulletCollision/CollisionDispatch/btInternalEdgeUtility.h"
#include "BulletCollision/CollisionShapes/btTriangleInfoMap.h"
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"
#include "BulletWorldImporter/btBulletWorldImporter.h"
#include "btBulletSoftBodyCommon.h"
#include "btSoftBulletWorldImporter.h"
#include "Serialize/SerializeTestUtil.h"

using caliber_test::TestWorld;

namespace
{
struct Dna
{
	std::vector<std::string> names, types;
	std::vector<short> lengths;               // as written (native pointer size)
	std::vector<std::vector<short>> structs;  // type, count, pairs
	std::map<int, int> structOfType;
};

int readInt(const char* p)
{
	int v;
	memcpy(&v, p, 4);
	return v;
}

Dna parseDna(const char* block)
{
	Dna dna;
	const char* p = block + 8;
	const int nameCount = readInt(p);
	p += 4;
	for (int i = 0; i < nameCount; ++i)
	{
		dna.names.push_back(p);
		p += strlen(p) + 1;
	}
	p = block + ((p - block + 3) & ~3) + 4;
	const int typeCount = readInt(p);
	p += 4;
	for (int i = 0; i < typeCount; ++i)
	{
		dna.types.push_back(p);
		p += strlen(p) + 1;
	}
	p = block + ((p - block + 3) & ~3) + 4;
	for (int i = 0; i < typeCount; ++i)
	{
		short v;
		memcpy(&v, p + 2 * i, 2);
		dna.lengths.push_back(v);
	}
	p += 2 * typeCount;
	p = block + ((p - block + 3) & ~3) + 4;
	const int structCount = readInt(p);
	p += 4;
	for (int s = 0; s < structCount; ++s)
	{
		short head[2];
		memcpy(head, p, 4);
		std::vector<short> st(size_t(2 + 2 * head[1]));
		memcpy(st.data(), p, st.size() * 2);
		p += st.size() * 2;
		dna.structOfType[st[0]] = int(dna.structs.size());
		dna.structs.push_back(st);
	}
	return dna;
}

bool isPointer(const std::string& name) { return name[0] == '*' || name[0] == '('; }

int arrayCount(const std::string& name)
{
	int n = 1;
	for (size_t i = 0; i < name.size(); ++i)
		if (name[i] == '[') n *= atoi(name.c_str() + i + 1);
	return n;
}

class Encoder
{
public:
	Encoder(const Dna& dna, int pointerSize, bool bigEndian) : m_dna(dna), m_ptr(pointerSize), m_big(bigEndian) {}

	// Length of type t with the target's pointers.
	int length(int type) const
	{
		auto it = m_dna.structOfType.find(type);
		if (it == m_dna.structOfType.end()) return m_dna.lengths[size_t(type)];
		const std::vector<short>& st = m_dna.structs[size_t(it->second)];
		int total = 0;
		for (int f = 0; f < st[1]; ++f)
		{
			const std::string& name = m_dna.names[size_t(st[3 + 2 * f])];
			total += (isPointer(name) ? m_ptr : length(st[2 + 2 * f])) * arrayCount(name);
		}
		return total;
	}

	// Appends one struct of type structIndex read from src (native layout); returns bytes read.
	size_t encodeStruct(int structIndex, const char* src, std::string& out) const
	{
		const std::vector<short>& st = m_dna.structs[size_t(structIndex)];
		size_t read = 0;
		for (int f = 0; f < st[1]; ++f)
		{
			const int type = st[2 + 2 * f];
			const std::string& name = m_dna.names[size_t(st[3 + 2 * f])];
			const int count = arrayCount(name);
			for (int i = 0; i < count; ++i)
			{
				if (isPointer(name))
				{
					uint64_t value;
					memcpy(&value, src + read, sizeof(void*));
					read += sizeof(void*);
					putUnsigned(out, m_ptr == 4 ? (value & 0xffffffffu) : value, m_ptr);
					continue;
				}
				auto it = m_dna.structOfType.find(type);
				if (it != m_dna.structOfType.end())
				{
					read += encodeStruct(it->second, src + read, out);
					continue;
				}
				const int size = m_dna.lengths[size_t(type)];
				uint64_t value = 0;
				memcpy(&value, src + read, size_t(size));
				read += size_t(size);
				putUnsigned(out, value, size);
			}
		}
		return read;
	}

	// Records the ids that pointer fields of type int or float hold (in the struct at src, native layout):
	// the chunks of those ids are arrays of 4-byte numbers, which a writer of the other byte order writes
	// in its order. Returns the bytes read.
	size_t collectWordArrays(int structIndex, const char* src, std::set<uint64_t>& ids) const
	{
		const std::vector<short>& st = m_dna.structs[size_t(structIndex)];
		size_t read = 0;
		for (int f = 0; f < st[1]; ++f)
		{
			const int type = st[2 + 2 * f];
			const std::string& name = m_dna.names[size_t(st[3 + 2 * f])];
			const int count = arrayCount(name);
			for (int i = 0; i < count; ++i)
			{
				if (isPointer(name))
				{
					uint64_t value;
					memcpy(&value, src + read, sizeof(void*));
					read += sizeof(void*);
					const std::string& typeName = m_dna.types[size_t(type)];
					if (value && (typeName == "int" || typeName == "float")) ids.insert(value);
					continue;
				}
				auto it = m_dna.structOfType.find(type);
				if (it != m_dna.structOfType.end())
					read += collectWordArrays(it->second, src + read, ids);
				else
					read += size_t(m_dna.lengths[size_t(type)]);
			}
		}
		return read;
	}

	// An integer of size bytes in the target byte order (the host is little-endian).
	void putUnsigned(std::string& out, uint64_t value, int size) const
	{
		for (int i = 0; i < size; ++i)
		{
			const int shift = 8 * (m_big ? size - 1 - i : i);
			out.push_back(char((value >> shift) & 0xff));
		}
	}

	std::string encodeDna() const
	{
		std::string out = "SDNANAME";
		putUnsigned(out, m_dna.names.size(), 4);
		for (const std::string& n : m_dna.names) out.append(n.c_str(), n.size() + 1);
		while (out.size() % 4) out.push_back(0);
		out += "TYPE";
		putUnsigned(out, m_dna.types.size(), 4);
		for (const std::string& t : m_dna.types) out.append(t.c_str(), t.size() + 1);
		while (out.size() % 4) out.push_back(0);
		out += "TLEN";
		for (size_t t = 0; t < m_dna.types.size(); ++t) putUnsigned(out, uint64_t(uint16_t(length(int(t)))), 2);
		while (out.size() % 4) out.push_back(0);
		out += "STRC";
		putUnsigned(out, m_dna.structs.size(), 4);
		for (const std::vector<short>& st : m_dna.structs)
			for (short v : st) putUnsigned(out, uint64_t(uint16_t(v)), 2);
		while (out.size() % 4) out.push_back(0);
		return out;
	}

private:
	const Dna& m_dna;
	int m_ptr;
	bool m_big;
};

// Re-encodes a file this build wrote (little-endian host) for pointerSize and byte order.
std::vector<char> reencode(const std::vector<char>& file, int pointerSize, bool bigEndian)
{
	const std::vector<caliber_test::ChunkAt> chunks = caliber_test::walkChunks(file);
	const caliber_test::ChunkAt* dnaChunk = caliber_test::findChunk(chunks, BT_DNA_CODE);
	const Dna dna = parseDna(&file[dnaChunk->data]);
	Encoder encoder(dna, pointerSize, bigEndian);
	std::string out(file.begin(), file.begin() + BT_HEADER_LENGTH);
	out[7] = pointerSize == 8 ? '-' : '_';
	out[8] = bigEndian ? 'V' : 'v';
	// A chunk of a struct type whose length is its count times the pointer size is an array of pointers
	// (the target of a ** field, as a soft body's materials).
	auto pointerArray = [&](const caliber_test::ChunkAt& c)
	{
		const int nativeLength = dna.lengths[size_t(dna.structs[size_t(c.dnaNr)][0])];
		return c.number > 0 && c.length == c.number * int(sizeof(void*)) && nativeLength != int(sizeof(void*));
	};
	std::set<uint64_t> wordArrays;
	for (const caliber_test::ChunkAt& c : chunks)
		if (c.code != BT_DNA_CODE && c.dnaNr >= 0 && !pointerArray(c))
			for (int e = 0; e < c.number; ++e)
				encoder.collectWordArrays(c.dnaNr, &file[c.data] + size_t(e) * (size_t(c.length) / size_t(c.number)),
				                          wordArrays);
	for (const caliber_test::ChunkAt& c : chunks)
	{
		std::string data;
		if (c.code == BT_DNA_CODE)
			data = encoder.encodeDna();
		else if (c.dnaNr >= 0 && pointerArray(c))
			for (int e = 0; e < c.number; ++e)
			{
				uint64_t value;
				memcpy(&value, &file[c.data] + size_t(e) * sizeof(void*), sizeof(void*));
				encoder.putUnsigned(data, pointerSize == 4 ? (value & 0xffffffffu) : value, pointerSize);
			}
		else if (c.dnaNr >= 0)
			for (int e = 0; e < c.number; ++e)
				encoder.encodeStruct(c.dnaNr, &file[c.data] + size_t(e) * (size_t(c.length) / size_t(c.number)), data);
		else if (wordArrays.count(c.oldPtr))
			for (int k = 0; k + 4 <= c.length; k += 4)
			{
				uint32_t word;
				memcpy(&word, &file[c.data] + k, 4);
				encoder.putUnsigned(data, word, 4);
			}
		else
			data.assign(&file[c.data], size_t(c.length));
		out.append(&file[c.header], 4);  // the code is four characters in every byte order
		encoder.putUnsigned(out, uint64_t(uint32_t(int(data.size()))), 4);
		encoder.putUnsigned(out, pointerSize == 4 ? (c.oldPtr & 0xffffffffu) : c.oldPtr, pointerSize);
		encoder.putUnsigned(out, uint64_t(uint32_t(c.dnaNr)), 4);
		encoder.putUnsigned(out, uint64_t(uint32_t(c.number)), 4);
		out += data;
	}
	return std::vector<char>(out.begin(), out.end());
}

// A world of several shape kinds, bodies and joints.
std::vector<char> sampleWorld()
{
	TestWorld w;
	btCollisionShape* box = w.shape(new btBoxShape(btVector3(0.5, 0.25, 0.75)));
	btCompoundShape* compound = w.shape(new btCompoundShape());
	compound->addChildShape(btTransform(btQuaternion(btVector3(0, 1, 0), 0.3), btVector3(1, 0, 0)), box);
	compound->addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(-1, 0, 0)),
	                        w.shape(new btSphereShape(0.4)));
	btConvexHullShape* hull = w.shape(new btConvexHullShape());
	for (int i = 0; i < 6; ++i) hull->addPoint(btVector3(btScalar(i % 2), btScalar(i / 2), btScalar(0.1 * i)));
	w.body(w.shape(new btStaticPlaneShape(btVector3(0, 1, 0), 0)), 0, btVector3(0, 0, 0));
	btRigidBody* a = w.body(box, 1, btVector3(0, 2, 0));
	btRigidBody* b = w.body(compound, 2, btVector3(0, 4, 0));
	btRigidBody* c = w.body(hull, 3, btVector3(3, 2, 0));
	a->setLinearVelocity(btVector3(1, 2, 3));
	c->setAngularVelocity(btVector3(-1, 0.5, 0.25));
	w.joint(
	    new btHingeConstraint(*a, *b, btVector3(0, 1, 0), btVector3(0, -1, 0), btVector3(1, 0, 0), btVector3(1, 0, 0)));
	w.joint(new btGeneric6DofSpring2Constraint(*b, *c, btTransform::getIdentity(), btTransform::getIdentity()));
	btDefaultSerializer s;
	s.registerNameForPointer(c, "hull body");
	return w.save(&s);
}

struct Summary
{
	bool ok = false;
	std::vector<btScalar> numbers;  // every body's transform and velocities, in order
	std::vector<int> shapeTypes;
	int joints = 0;
	bool named = false;
};

Summary loadSummary(std::vector<char> bytes)
{
	TestWorld w;
	btBulletWorldImporter importer(&w.world);
	Summary s;
	s.ok = importer.loadFileFromMemory(bytes.data(), int(bytes.size()));
	for (int i = 0; i < importer.getNumRigidBodies(); ++i)
	{
		btRigidBody* body = btRigidBody::upcast(importer.getRigidBodyByIndex(i));
		const btTransform& t = body->getWorldTransform();
		for (int k = 0; k < 3; ++k)
		{
			s.numbers.push_back(t.getOrigin()[k]);
			s.numbers.push_back(body->getLinearVelocity()[k]);
			s.numbers.push_back(body->getAngularVelocity()[k]);
			for (int m = 0; m < 3; ++m) s.numbers.push_back(t.getBasis()[k][m]);
		}
		s.shapeTypes.push_back(body->getCollisionShape()->getShapeType());
	}
	s.joints = importer.getNumConstraints();
	s.named = importer.getRigidBodyByName("hull body") != nullptr;
	importer.deleteAllData();
	return s;
}
}  // namespace

TEST(OtherLayoutFile, FourAndEightBytePointersInBothByteOrdersLoadTheSameWorld)
{
	const uint16_t probe = 1;
	if (*reinterpret_cast<const char*>(&probe) != 1 || sizeof(void*) != 8)
		GTEST_SKIP() << "the re-encoder assumes a little-endian 64-bit host";
	const std::vector<char> native = sampleWorld();
	const Summary reference = loadSummary(native);
	ASSERT_TRUE(reference.ok);
	ASSERT_EQ(reference.shapeTypes.size(), 4u);
	ASSERT_EQ(reference.joints, 2);
	ASSERT_TRUE(reference.named);
	for (int pointerSize : {4, 8})
		for (bool bigEndian : {false, true})
		{
			const std::vector<char> other = reencode(native, pointerSize, bigEndian);
			if (pointerSize == 8 && !bigEndian)
			{
				// The identity re-encoding must give back the very same bytes: the re-encoder is right.
				EXPECT_EQ(other, native);
			}
			else
				EXPECT_NE(other, native);
			const Summary s = loadSummary(other);
			EXPECT_TRUE(s.ok) << pointerSize << (bigEndian ? " big" : " little");
			EXPECT_EQ(s.numbers, reference.numbers) << pointerSize << (bigEndian ? " big" : " little");
			EXPECT_EQ(s.shapeTypes, reference.shapeTypes);
			EXPECT_EQ(s.joints, reference.joints);
			EXPECT_TRUE(s.named);
		}
}

namespace
{
// What the plain int and float arrays of a file hold once loaded: a mesh's triangle info map (keys and
// values) and a soft body's pose weights, cluster node indices and cluster masses.
struct PlainArrays
{
	bool ok = false;
	std::vector<std::pair<int, btScalar>> entries;  // key and one angle, sorted by key
	std::vector<btScalar> weights;
	std::vector<int> clusterNodes;
	std::vector<btScalar> clusterMasses;
};

PlainArrays loadPlainArrays(std::vector<char> bytes)
{
	btSoftBulletWorldImporter importer;
	PlainArrays p;
	p.ok = importer.loadFileFromMemory(bytes.data(), int(bytes.size()));
	for (int i = 0; i < importer.getNumCollisionShapes(); ++i)
		if (importer.getCollisionShapeByIndex(i)->getShapeType() == TRIANGLE_MESH_SHAPE_PROXYTYPE)
		{
			const btTriangleInfoMap* map =
			    static_cast<btBvhTriangleMeshShape*>(importer.getCollisionShapeByIndex(i))->getTriangleInfoMap();
			for (int k = 0; map && k < map->size(); ++k)
			{
				p.entries.push_back(
				    std::make_pair(map->getKeyAtIndex(k).getUid1(), map->getAtIndex(k)->m_edgeV0V1Angle));
			}
		}
	std::sort(p.entries.begin(), p.entries.end());
	if (btSoftBody* b = importer.getSoftBodyByIndex(0))
	{
		for (int i = 0; i < b->m_pose.m_wgh.size(); ++i) p.weights.push_back(b->m_pose.m_wgh[i]);
		for (int c = 0; c < b->m_clusters.size(); ++c)
			for (int j = 0; j < b->m_clusters[c]->m_nodes.size(); ++j)
			{
				p.clusterNodes.push_back(int(b->m_clusters[c]->m_nodes[j] - &b->m_nodes[0]));
				p.clusterMasses.push_back(b->m_clusters[c]->m_masses[j]);
			}
	}
	importer.deleteAllData();
	return p;
}
}  // namespace

TEST(OtherLayoutFile, PlainIntAndFloatArraysLoadFromFilesOfTheOtherByteOrder)
{
	// The triangle info map's keys, a soft body's pose weights and its clusters' node indices and masses are
	// plain arrays without a DNA struct: the loader leaves them in the writer's byte order and the importers
	// swap them. A big-endian file must give the same values as the native one.
	const uint16_t probe = 1;
	if (*reinterpret_cast<const char*>(&probe) != 1 || sizeof(void*) != 8)
		GTEST_SKIP() << "the re-encoder assumes a little-endian 64-bit host";
	btTriangleMesh mesh;
	auto height = [](int i, int j) { return btScalar(0.3) * btSin(btScalar(i)) * btCos(btScalar(0.7) * btScalar(j)); };
	for (int i = 0; i < 6; ++i)
		for (int j = 0; j < 6; ++j)
		{
			const btVector3 a(btScalar(i), height(i, j), btScalar(j)),
			    b(btScalar(i + 1), height(i + 1, j), btScalar(j));
			const btVector3 c(btScalar(i), height(i, j + 1), btScalar(j + 1));
			const btVector3 d(btScalar(i + 1), height(i + 1, j + 1), btScalar(j + 1));
			mesh.addTriangle(a, b, c);
			mesh.addTriangle(b, d, c);
		}
	btBvhTriangleMeshShape shape(&mesh, true);
	btTriangleInfoMap map;
	btGenerateInternalEdgeInfo(&shape, &map);
	ASSERT_GT(map.size(), 50);

	btSoftBodyRigidBodyCollisionConfiguration config;
	btCollisionDispatcher dispatcher(&config);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btSoftRigidDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
	btRigidBody ground(btRigidBody::btRigidBodyConstructionInfo(0, 0, &shape));
	world.addRigidBody(&ground);
	btSoftBody* cloth = btSoftBodyHelpers::CreatePatch(world.getWorldInfo(), btVector3(0, 2, 0), btVector3(3, 2, 0),
	                                                   btVector3(0, 2, 3), btVector3(3, 2, 3), 6, 6, 0, true);
	cloth->setTotalMass(2);
	cloth->setPose(true, true);
	cloth->generateClusters(3);
	world.addSoftBody(cloth);
	btDefaultSerializer serializer;
	world.serialize(&serializer);
	const std::vector<char> native = caliber_test::bytesOf(serializer);
	world.removeSoftBody(cloth);
	delete cloth;
	world.removeRigidBody(&ground);

	const PlainArrays reference = loadPlainArrays(native);
	ASSERT_TRUE(reference.ok);
	ASSERT_EQ(reference.entries.size(), size_t(map.size()));
	ASSERT_EQ(reference.weights.size(), 36u);
	ASSERT_GT(reference.clusterNodes.size(), 36u);
	for (int pointerSize : {4, 8})
		for (bool bigEndian : {false, true})
		{
			const std::vector<char> other = reencode(native, pointerSize, bigEndian);
			if (pointerSize == 8 && !bigEndian)
			{
				EXPECT_EQ(other, native);  // the re-encoder is the identity here
			}
			const PlainArrays p = loadPlainArrays(other);
			const char* what = bigEndian ? "big-endian" : "little-endian";
			EXPECT_TRUE(p.ok) << pointerSize << " " << what;
			EXPECT_EQ(p.entries, reference.entries) << pointerSize << " " << what;
			EXPECT_EQ(p.weights, reference.weights) << pointerSize << " " << what;
			EXPECT_EQ(p.clusterNodes, reference.clusterNodes) << pointerSize << " " << what;
			EXPECT_EQ(p.clusterMasses, reference.clusterMasses) << pointerSize << " " << what;
		}
}
