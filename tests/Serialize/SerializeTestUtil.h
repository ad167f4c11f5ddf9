// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_TESTS_SERIALIZE_TEST_UTIL_H
#define CALIBER_TESTS_SERIALIZE_TEST_UTIL_H

#include <stdint.h>
#include <string.h>

#include <memory>
#include <string>
#include <vector>

#include "LinearMath/btSerializer.h"
#include "LinearMath/btWarningHook.h"
#include "btBulletDynamicsCommon.h"

namespace caliber_test
{
/// Collects the warnings reported through btReportWarning while it lives.
class WarningLog
{
public:
	WarningLog() { btSetWarningHook(&WarningLog::hook, this); }
	~WarningLog() { btSetWarningHook(0, 0); }
	int count() const { return int(m_messages.size()); }
	bool contains(const char* text) const
	{
		for (const std::string& m : m_messages)
			if (m.find(text) != std::string::npos) return true;
		return false;
	}
	std::string all() const
	{
		std::string out;
		for (const std::string& m : m_messages) out += m;
		return out;
	}

private:
	static void hook(const char* message, void* self) { static_cast<WarningLog*>(self)->m_messages.push_back(message); }
	std::vector<std::string> m_messages;
};

/// The finished file of a serializer, as bytes.
inline std::vector<char> bytesOf(const btDefaultSerializer& s)
{
	const char* p = reinterpret_cast<const char*>(s.getBufferPointer());
	return std::vector<char>(p, p + s.getCurrentBufferSize());
}

/// One chunk of a file written by this build (native pointer size and byte order).
struct ChunkAt
{
	int code;
	int length;
	uint64_t oldPtr;
	int dnaNr;
	int number;
	size_t header;  // offset of the chunk header
	size_t data;    // offset of the chunk's data
};

/// The chunks of a file this build wrote, in order.
inline std::vector<ChunkAt> walkChunks(const std::vector<char>& file)
{
	std::vector<ChunkAt> out;
	size_t pos = BT_HEADER_LENGTH;
	while (pos + sizeof(btChunk) <= file.size())
	{
		btChunk c;
		memcpy(&c, &file[pos], sizeof(btChunk));
		out.push_back(ChunkAt{c.m_chunkCode, c.m_length, uint64_t(uintptr_t(c.m_oldPtr)), c.m_dna_nr, c.m_number, pos,
		                      pos + sizeof(btChunk)});
		pos += sizeof(btChunk) + size_t(c.m_length);
	}
	return out;
}

/// The first chunk with code, or 0.
inline const ChunkAt* findChunk(const std::vector<ChunkAt>& chunks, int code, int skip = 0)
{
	for (const ChunkAt& c : chunks)
		if (c.code == code && skip-- == 0) return &c;
	return 0;
}

/// A small dynamics world that owns everything added to it.
struct TestWorld
{
	btDefaultCollisionConfiguration config;
	btCollisionDispatcher dispatcher{&config};
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
	std::vector<std::unique_ptr<btCollisionShape>> shapes;
	std::vector<std::unique_ptr<btRigidBody>> bodies;
	std::vector<std::unique_ptr<btTypedConstraint>> joints;

	TestWorld() { world.setGravity(btVector3(0, -10, 0)); }
	~TestWorld()
	{
		for (auto& j : joints) world.removeConstraint(j.get());
		for (auto& b : bodies) world.removeRigidBody(b.get());
	}
	template <class S>
	S* shape(S* s)
	{
		shapes.emplace_back(s);
		return s;
	}
	btRigidBody* body(btCollisionShape* s, btScalar mass, const btVector3& at)
	{
		btVector3 inertia(0, 0, 0);
		if (mass > 0) s->calculateLocalInertia(mass, inertia);
		btRigidBody::btRigidBodyConstructionInfo info(mass, 0, s, inertia);
		info.m_startWorldTransform.setIdentity();
		info.m_startWorldTransform.setOrigin(at);
		bodies.emplace_back(new btRigidBody(info));
		world.addRigidBody(bodies.back().get());
		return bodies.back().get();
	}
	template <class J>
	J* joint(J* j, bool disableCollisions = false)
	{
		joints.emplace_back(j);
		world.addConstraint(j, disableCollisions);
		return j;
	}
	std::vector<char> save(btDefaultSerializer* serializer = 0)
	{
		btDefaultSerializer own;
		btDefaultSerializer* s = serializer ? serializer : &own;
		world.serialize(s);
		return bytesOf(*s);
	}
};
}  // namespace caliber_test

#endif
