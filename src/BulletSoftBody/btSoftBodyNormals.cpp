// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The soft body's normals on the task scheduler's threads (btSoftBodyNormals.h).

#include "btSoftBodyNormals.h"

#include <cstdint>
#include <functional>

#include "LinearMath/btSideTable.h"
#include "LinearMath/TaskScheduler/btParallelChunks.h"
#include "LinearMath/btThreads.h"

namespace
{
const int kChunk = 1024;

// Each node's faces, in face order (a face naming a node twice is listed twice, as one thread adds its
// normal twice), and the scratch of a step.
struct NodeFaces
{
	int nodeCount = -1, faceCount = -1;
	uint64_t signature = 0;
	btAlignedObjectArray<int> start;  // node i's faces are faces[start[i], start[i + 1])
	btAlignedObjectArray<int> faces;
	btAlignedObjectArray<btVector3> faceNormals;  // this step's, not normalised
	btAlignedObjectArray<uint64_t> chunkHashes;   // this step's fingerprint of each chunk of faces
};

// Chunk k of the faces: its normals (the face's own normalised, as one thread sets it) and a fingerprint
// of its nodes' addresses (the lists depend on them; nodes moved to a new array only cost a rebuild). Loops over chunk numbers, so any split of the loop gives the
// same fingerprints.
struct FacePass : btIParallelForBody
{
	btSoftBody::Face* faces;
	int count;
	btVector3* normals;
	uint64_t* hashes;
	void forLoop(int begin, int end) const override
	{
		for (int k = begin; k < end; ++k)
		{
			uint64_t h = 1469598103934665603ull;
			const int last = btMin((k + 1) * kChunk, count);
			for (int i = k * kChunk; i < last; ++i)
			{
				btSoftBody::Face& f = faces[i];
				const btVector3 n = (f.m_n[1]->m_x - f.m_n[0]->m_x).cross(f.m_n[2]->m_x - f.m_n[0]->m_x);
				const btScalar len = n.length();
				if (len > SIMD_EPSILON) f.m_normal = n / len;
				normals[i] = n;
				for (int j = 0; j < 3; ++j) h = (h ^ uint64_t(uintptr_t(f.m_n[j]))) * 1099511628211ull;
			}
			hashes[k] = h;
		}
	}
};

// Nodes [begin, end): the sum of their faces' normals in face order, normalised.
struct NodePass : btIParallelForBody
{
	btSoftBody::Node* nodes;
	const int* start;
	const int* faces;
	const btVector3* normals;
	void forLoop(int begin, int end) const override
	{
		for (int i = begin; i < end; ++i)
		{
			btVector3 n(0, 0, 0);
			for (int k = start[i]; k < start[i + 1]; ++k) n += normals[faces[k]];
			const btScalar len = n.length();
			if (len > SIMD_EPSILON) n /= len;
			nodes[i].m_n = n;
		}
	}
};

// Returns false (and builds nothing) when a face names a node outside the body's array: a face rewritten
// by hand to point elsewhere, which one thread's pass still follows.
bool buildLists(const btSoftBody& body, NodeFaces& t)
{
	const int n = body.m_nodes.size(), f = body.m_faces.size();
	const btSoftBody::Node* base = &body.m_nodes[0];
	for (int i = 0; i < f; ++i)
		for (int j = 0; j < 3; ++j)
		{
			const btSoftBody::Node* node = body.m_faces[i].m_n[j];
			if (std::less<const btSoftBody::Node*>()(node, base) || !std::less<const btSoftBody::Node*>()(node, base + n))
				return false;
		}
	t.start.resize(n + 1);
	for (int i = 0; i <= n; ++i) t.start[i] = 0;
	for (int i = 0; i < f; ++i)
		for (int j = 0; j < 3; ++j) ++t.start[int(body.m_faces[i].m_n[j] - base) + 1];
	for (int i = 0; i < n; ++i) t.start[i + 1] += t.start[i];
	t.faces.resize(3 * f);
	btAlignedObjectArray<int> fill;
	fill.resize(n);
	for (int i = 0; i < n; ++i) fill[i] = t.start[i];
	for (int i = 0; i < f; ++i)
		for (int j = 0; j < 3; ++j) t.faces[fill[int(body.m_faces[i].m_n[j] - base)]++] = i;
	return true;
}

// The nodes' sums as one thread makes them, from this step's face normals.
void scatterNormals(btSoftBody& body, const btAlignedObjectArray<btVector3>& normals)
{
	for (int i = 0; i < body.m_nodes.size(); ++i) body.m_nodes[i].m_n.setValue(0, 0, 0);
	for (int i = 0; i < body.m_faces.size(); ++i)
		for (int j = 0; j < 3; ++j) body.m_faces[i].m_n[j]->m_n += normals[i];
	for (int i = 0; i < body.m_nodes.size(); ++i)
	{
		const btScalar len = body.m_nodes[i].m_n.length();
		if (len > SIMD_EPSILON) body.m_nodes[i].m_n /= len;
	}
}
}  // namespace

bool caliber::normalsOnThreads(const btSoftBody& body)
{
	return body.m_faces.size() > kChunk && body.m_nodes.size() > 0 && !caliber::insideParallelBody() &&
	       btGetTaskScheduler()->getNumThreads() > 1;
}

void caliber::updateNormalsOnThreads(btSoftBody& body)
{
	NodeFaces& t = sideTable<NodeFaces>().acquire(&body);
	const int f = body.m_faces.size(), chunks = (f + kChunk - 1) / kChunk;
	t.faceNormals.resize(f);
	t.chunkHashes.resize(chunks);
	FacePass facePass;
	facePass.faces = &body.m_faces[0];
	facePass.count = f;
	facePass.normals = &t.faceNormals[0];
	facePass.hashes = &t.chunkHashes[0];
	btParallelFor(0, chunks, 1, facePass);
	uint64_t signature = 1469598103934665603ull;
	for (int k = 0; k < chunks; ++k) signature = (signature ^ t.chunkHashes[k]) * 1099511628211ull;
	if (t.nodeCount != body.m_nodes.size() || t.faceCount != f || t.signature != signature)
	{
		t.nodeCount = -1;  // no lists until they are built
		if (!buildLists(body, t))
		{
			scatterNormals(body, t.faceNormals);
			return;
		}
		t.nodeCount = body.m_nodes.size();
		t.faceCount = f;
		t.signature = signature;
	}
	NodePass nodePass;
	nodePass.nodes = &body.m_nodes[0];
	nodePass.start = &t.start[0];
	nodePass.faces = t.faces.size() > 0 ? &t.faces[0] : 0;
	nodePass.normals = &t.faceNormals[0];
	btParallelFor(0, body.m_nodes.size(), kChunk, nodePass);
}

void caliber::releaseNodeFaces(const btSoftBody& body) { sideTable<NodeFaces>().release(&body); }
