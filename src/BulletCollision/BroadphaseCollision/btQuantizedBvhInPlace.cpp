// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// Bullet's in-place BVH buffer: a tree written into one caller-owned block that a later load uses
// where it lies, without copying or allocating (the layout is in QuantizedBvhInPlace.h). The bytes are
// untrusted on the way in: every count, offset, box and escape index is checked before an object is
// built over them.
#include "QuantizedBvhInPlace.h"

#include "LinearMath/btWarningHook.h"
#include "QuantizedBvhTreeCheck.h"

#include <stdint.h>
#include <string.h>

#include <new>
#include <string>

namespace
{
const uint32_t kMagic = 0x48564243u;  // "CBVH" read as a little-endian word
const uint32_t kVersion = 1;

struct InPlaceBvhHeader
{
	uint32_t magic;
	uint32_t version;
	uint32_t scalarBytes;
	uint32_t objectBytes;
	int32_t useQuantization;
	int32_t curNodeIndex;
	int32_t numNodes;
	int32_t numSubtreeHeaders;
	int32_t traversalMode;
	int32_t unused[3];
	btScalar aabbMin[4];
	btScalar aabbMax[4];
	btScalar quantization[4];
};

unsigned long long roundUp16(unsigned long long bytes) { return (bytes + 15u) & ~15ull; }

const unsigned long long kHeaderOffset = caliber::kInPlaceBvhObjectBytes;
const unsigned long long kNodesOffset = kHeaderOffset + roundUp16(sizeof(InPlaceBvhHeader));

struct InPlaceLayout
{
	unsigned long long subtreeHeadersOffset;
	unsigned long long total;
};

// Counts are checked to be non-negative 32-bit values first, so 64-bit sums cannot overflow.
InPlaceLayout layoutOf(bool quantized, long long numNodes, long long numSubtreeHeaders)
{
	const unsigned long long nodeBytes = quantized ? sizeof(btQuantizedBvhNode) : sizeof(btOptimizedBvhNode);
	InPlaceLayout layout;
	layout.subtreeHeadersOffset = kNodesOffset + roundUp16(nodeBytes * (unsigned long long)numNodes);
	layout.total = layout.subtreeHeadersOffset + sizeof(btBvhSubtreeInfo) * (unsigned long long)numSubtreeHeaders;
	return layout;
}

template <class T>
void swapBytes(T& value)
{
	unsigned char bytes[sizeof(T)];
	memcpy(bytes, &value, sizeof(T));
	for (size_t i = 0; i < sizeof(T) / 2; ++i)
	{
		const unsigned char t = bytes[i];
		bytes[i] = bytes[sizeof(T) - 1 - i];
		bytes[sizeof(T) - 1 - i] = t;
	}
	memcpy(&value, bytes, sizeof(T));
}

template <class T, int N>
void swapEach(T (&values)[N])
{
	for (int i = 0; i < N; ++i) swapBytes(values[i]);
}

void swapHeader(InPlaceBvhHeader& h)
{
	swapBytes(h.magic);
	swapBytes(h.version);
	swapBytes(h.scalarBytes);
	swapBytes(h.objectBytes);
	swapBytes(h.useQuantization);
	swapBytes(h.curNodeIndex);
	swapBytes(h.numNodes);
	swapBytes(h.numSubtreeHeaders);
	swapBytes(h.traversalMode);
	swapEach(h.unused);
	swapEach(h.aabbMin);
	swapEach(h.aabbMax);
	swapEach(h.quantization);
}

void swapVector(btVector3& v)
{
	btScalar s[4] = {v[0], v[1], v[2], v[3]};
	swapEach(s);
	v.setValue(s[0], s[1], s[2]);
	v[3] = s[3];
}

// Byte-swaps the node and subtree-header arrays (an involution: swapping twice restores them).
void swapArrays(unsigned char* base, const InPlaceBvhHeader& h)
{
	const InPlaceLayout layout = layoutOf(h.useQuantization == 1, h.numNodes, h.numSubtreeHeaders);
	if (h.useQuantization == 1)
	{
		btQuantizedBvhNode* nodes = reinterpret_cast<btQuantizedBvhNode*>(base + kNodesOffset);
		for (int i = 0; i < h.numNodes; ++i)
		{
			swapEach(nodes[i].m_quantizedAabbMin);
			swapEach(nodes[i].m_quantizedAabbMax);
			swapBytes(nodes[i].m_escapeIndexOrTriangleIndex);
		}
	}
	else
	{
		btOptimizedBvhNode* nodes = reinterpret_cast<btOptimizedBvhNode*>(base + kNodesOffset);
		for (int i = 0; i < h.numNodes; ++i)
		{
			swapVector(nodes[i].m_aabbMinOrg);
			swapVector(nodes[i].m_aabbMaxOrg);
			swapBytes(nodes[i].m_escapeIndex);
			swapBytes(nodes[i].m_subPart);
			swapBytes(nodes[i].m_triangleIndex);
		}
	}
	btBvhSubtreeInfo* headers = reinterpret_cast<btBvhSubtreeInfo*>(base + layout.subtreeHeadersOffset);
	for (int i = 0; i < h.numSubtreeHeaders; ++i)
	{
		swapEach(headers[i].m_quantizedAabbMin);
		swapEach(headers[i].m_quantizedAabbMax);
		swapBytes(headers[i].m_rootNodeIndex);
		swapBytes(headers[i].m_subtreeSize);
	}
}

struct QuantizedNodes
{
	const btQuantizedBvhNode* nodes;
	bool isLeaf(int i) const { return nodes[i].m_escapeIndexOrTriangleIndex >= 0; }
	long long escape(int i) const { return -static_cast<long long>(nodes[i].m_escapeIndexOrTriangleIndex); }
};

struct PlainNodes
{
	const btOptimizedBvhNode* nodes;
	bool isLeaf(int i) const { return nodes[i].m_escapeIndex < 0; }
	long long escape(int i) const { return nodes[i].m_escapeIndex; }
};

bool finite3(const btScalar* v) { return caliber::isFinite(btVector3(v[0], v[1], v[2])); }

// The reason the header cannot describe a tree in a buffer of bufferSize bytes, or null.
const char* headerProblem(const InPlaceBvhHeader& h, unsigned bufferSize)
{
	if (h.magic != kMagic) return "not an in-place BVH buffer, or written in the other byte order (magic)";
	if (h.version != kVersion) return "an unknown version";
	if (h.scalarBytes != sizeof(btScalar)) return "written with the other btScalar precision";
	if (h.objectBytes != caliber::kInPlaceBvhObjectBytes) return "written by a build with another object size";
	if (h.useQuantization != 0 && h.useQuantization != 1) return "useQuantization is neither 0 nor 1";
	if (h.traversalMode < 0 || h.traversalMode > 2) return "an unknown traversal mode";
	if (h.numNodes < 0 || h.numSubtreeHeaders < 0 || h.curNodeIndex < 0) return "a negative count";
	if (h.curNodeIndex > h.numNodes) return "the node count exceeds the node array";
	if (layoutOf(h.useQuantization == 1, h.numNodes, h.numSubtreeHeaders).total > bufferSize)
		return "the arrays run past the end of the buffer";
	if (h.useQuantization == 1)
	{
		if (!finite3(h.aabbMin) || !finite3(h.aabbMax) || !finite3(h.quantization))
			return "a non-finite quantization box";
		for (int a = 0; a < 3; ++a)
			if (!(h.aabbMin[a] <= h.aabbMax[a]) || !(h.quantization[a] > 0))
				return "an inverted quantization box or a quantization that is not positive";
	}
	return 0;
}

// The reason the (native-order) arrays are not a tree every walk can use, or null.
const char* treeProblem(const unsigned char* base, const InPlaceBvhHeader& h)
{
	const InPlaceLayout layout = layoutOf(h.useQuantization == 1, h.numNodes, h.numSubtreeHeaders);
	const btBvhSubtreeInfo* headers = reinterpret_cast<const btBvhSubtreeInfo*>(base + layout.subtreeHeadersOffset);
	const int numNodes = h.curNodeIndex;
	if (h.useQuantization == 1)
	{
		const QuantizedNodes nodes = {reinterpret_cast<const btQuantizedBvhNode*>(base + kNodesOffset)};
		if (!caliber::wellFormedBvhTree(nodes, numNodes)) return "the nodes do not form a tree (escape indices)";
		if (!caliber::bvhSubtreeHeadersFit(nodes, numNodes, headers, h.numSubtreeHeaders))
			return "a subtree header outside the tree";
		return 0;
	}
	const PlainNodes nodes = {reinterpret_cast<const btOptimizedBvhNode*>(base + kNodesOffset)};
	for (int i = 0; i < numNodes; ++i)
	{
		const btOptimizedBvhNode& node = nodes.nodes[i];
		if (!caliber::isFinite(node.m_aabbMinOrg) || !caliber::isFinite(node.m_aabbMaxOrg))
			return "a non-finite node box";
		if (node.m_escapeIndex < 0 && (node.m_subPart < 0 || node.m_triangleIndex < 0))
			return "a leaf with a negative part or triangle index";
	}
	if (!caliber::wellFormedBvhTree(nodes, numNodes)) return "the nodes do not form a tree (escape indices)";
	if (!caliber::bvhSubtreeHeadersFit(nodes, numNodes, headers, h.numSubtreeHeaders))
		return "a subtree header outside the tree";
	return 0;
}

// Reaches the protected members (pointers to members formed in a derived class; nothing is added).
struct InPlaceFields : btQuantizedBvh
{
	static bool write(const btQuantizedBvh& bvh, unsigned char* base, unsigned bufferSize, bool swapEndian)
	{
		const bool quantized = bvh.*(&InPlaceFields::m_useQuantization);
		const QuantizedNodeArray& qnodes = bvh.*(&InPlaceFields::m_quantizedContiguousNodes);
		const NodeArray& nodes = bvh.*(&InPlaceFields::m_contiguousNodes);
		const BvhSubtreeInfoArray& subtrees = bvh.*(&InPlaceFields::m_SubtreeHeaders);
		const int numNodes = quantized ? qnodes.size() : nodes.size();
		const InPlaceLayout layout = layoutOf(quantized, numNodes, subtrees.size());
		if (layout.total > bufferSize) return false;

		InPlaceBvhHeader h;
		memset(&h, 0, sizeof(h));
		h.magic = kMagic;
		h.version = kVersion;
		h.scalarBytes = sizeof(btScalar);
		h.objectBytes = caliber::kInPlaceBvhObjectBytes;
		h.useQuantization = quantized ? 1 : 0;
		h.curNodeIndex = bvh.*(&InPlaceFields::m_curNodeIndex);
		h.numNodes = numNodes;
		h.numSubtreeHeaders = subtrees.size();
		h.traversalMode = int32_t(bvh.*(&InPlaceFields::m_traversalMode));
		for (int a = 0; a < 3; ++a)
		{
			h.aabbMin[a] = (bvh.*(&InPlaceFields::m_bvhAabbMin))[a];
			h.aabbMax[a] = (bvh.*(&InPlaceFields::m_bvhAabbMax))[a];
			h.quantization[a] = (bvh.*(&InPlaceFields::m_bvhQuantization))[a];
		}
		// The object region is filled in by a load; it is zeroed so the buffer's bytes are all defined.
		memset(base, 0, size_t(layout.total));
		if (quantized && numNodes > 0) memcpy(base + kNodesOffset, &qnodes[0], sizeof(btQuantizedBvhNode) * numNodes);
		if (!quantized && numNodes > 0) memcpy(base + kNodesOffset, &nodes[0], sizeof(btOptimizedBvhNode) * numNodes);
		if (subtrees.size() > 0)
			memcpy(base + layout.subtreeHeadersOffset, &subtrees[0], sizeof(btBvhSubtreeInfo) * subtrees.size());
		if (swapEndian)
		{
			swapArrays(base, h);  // while h is still in this machine's order
			swapHeader(h);
		}
		memcpy(base + kHeaderOffset, &h, sizeof(h));
		return true;
	}

	static void adopt(btQuantizedBvh& bvh, unsigned char* base)
	{
		InPlaceBvhHeader h;
		memcpy(&h, base + kHeaderOffset, sizeof(h));
		const InPlaceLayout layout = layoutOf(h.useQuantization == 1, h.numNodes, h.numSubtreeHeaders);
		bvh.*(&InPlaceFields::m_bvhAabbMin) = btVector3(h.aabbMin[0], h.aabbMin[1], h.aabbMin[2]);
		bvh.*(&InPlaceFields::m_bvhAabbMax) = btVector3(h.aabbMax[0], h.aabbMax[1], h.aabbMax[2]);
		bvh.*(&InPlaceFields::m_bvhQuantization) = btVector3(h.quantization[0], h.quantization[1], h.quantization[2]);
		bvh.*(&InPlaceFields::m_curNodeIndex) = h.curNodeIndex;
		bvh.*(&InPlaceFields::m_useQuantization) = h.useQuantization == 1;
		bvh.*(&InPlaceFields::m_traversalMode) = btTraversalMode(h.traversalMode);
		if (h.useQuantization == 1)
			(bvh.*(&InPlaceFields::m_quantizedContiguousNodes))
			    .initializeFromBuffer(base + kNodesOffset, h.numNodes, h.numNodes);
		else
			(bvh.*(&InPlaceFields::m_contiguousNodes))
			    .initializeFromBuffer(base + kNodesOffset, h.numNodes, h.numNodes);
		(bvh.*(&InPlaceFields::m_SubtreeHeaders))
		    .initializeFromBuffer(base + layout.subtreeHeadersOffset, h.numSubtreeHeaders, h.numSubtreeHeaders);
		bvh.*(&InPlaceFields::m_subtreeHeaderCount) = h.numSubtreeHeaders;
	}
};

bool usableBuffer(const void* buffer) { return buffer != 0 && reinterpret_cast<uintptr_t>(buffer) % 16 == 0; }
}  // namespace

namespace caliber
{
const char* prepareInPlaceBvh(void* buffer, unsigned bufferSize, bool swapEndian)
{
	if (!usableBuffer(buffer)) return "the buffer is null or not 16-byte aligned";
	if (bufferSize < kNodesOffset) return "the buffer is smaller than its header";
	unsigned char* base = static_cast<unsigned char*>(buffer);
	InPlaceBvhHeader h;
	memcpy(&h, base + kHeaderOffset, sizeof(h));
	if (swapEndian) swapHeader(h);
	if (const char* problem = headerProblem(h, bufferSize)) return problem;
	if (swapEndian) swapArrays(base, h);
	if (const char* problem = treeProblem(base, h))
	{
		if (swapEndian) swapArrays(base, h);  // give the caller back the bytes it passed
		return problem;
	}
	memcpy(base + kHeaderOffset, &h, sizeof(h));
	return 0;
}

void adoptInPlaceBvh(btQuantizedBvh& bvh, void* buffer)
{
	InPlaceFields::adopt(bvh, static_cast<unsigned char*>(buffer));
}

void warnInPlaceBvh(const char* caller, const char* problem)
{
	btReportWarning((std::string("Caliber: ") + caller + ": " + problem + "; nothing is loaded\n").c_str());
}
}  // namespace caliber

unsigned btQuantizedBvh::calculateSerializeBufferSize() const
{
	const int numNodes = m_useQuantization ? m_quantizedContiguousNodes.size() : m_contiguousNodes.size();
	return unsigned(layoutOf(m_useQuantization, numNodes, m_SubtreeHeaders.size()).total);
}

bool btQuantizedBvh::serialize(void* o_alignedDataBuffer, unsigned i_dataBufferSize, bool i_swapEndian) const
{
	btAssert(usableBuffer(o_alignedDataBuffer) && "btQuantizedBvh::serialize: null or misaligned buffer");
	btAssert(i_dataBufferSize >= calculateSerializeBufferSize() && "btQuantizedBvh::serialize: buffer too small");
	if (!usableBuffer(o_alignedDataBuffer)) return false;
	return InPlaceFields::write(*this, static_cast<unsigned char*>(o_alignedDataBuffer), i_dataBufferSize,
	                            i_swapEndian);
}

btQuantizedBvh* btQuantizedBvh::deSerializeInPlace(void* i_alignedDataBuffer, unsigned int i_dataBufferSize,
                                                   bool i_swapEndian)
{
	if (const char* problem = caliber::prepareInPlaceBvh(i_alignedDataBuffer, i_dataBufferSize, i_swapEndian))
	{
		caliber::warnInPlaceBvh("btQuantizedBvh::deSerializeInPlace", problem);
		return 0;
	}
	// The tree is staged beside the block (its arrays already viewing the block) and the block's object
	// is constructed from it, so nothing is read from storage whose lifetime is just beginning.
	btQuantizedBvh staged;
	caliber::adoptInPlaceBvh(staged, i_alignedDataBuffer);
	return new (i_alignedDataBuffer) btQuantizedBvh(staged, false);
}

namespace
{
// Points array at other's elements without copying them (an empty array when other has none).
template <typename Array>
void viewStorageOf(Array& array, Array& other)
{
	if (other.size() > 0)
		array.initializeFromBuffer(&other[0], other.size(), other.size());
	else
		array.clear();
}
}  // namespace

btQuantizedBvh::btQuantizedBvh(btQuantizedBvh& other, bool ownsMemory)
    : m_bvhAabbMin(other.m_bvhAabbMin),
      m_bvhAabbMax(other.m_bvhAabbMax),
      m_bvhQuantization(other.m_bvhQuantization),
      m_bulletVersion(289),
      m_curNodeIndex(other.m_curNodeIndex),
      m_useQuantization(other.m_useQuantization),
      m_traversalMode(other.m_traversalMode),
      m_subtreeHeaderCount(other.m_subtreeHeaderCount)
{
	btAssert(&other != this && "btQuantizedBvh(other, ownsMemory): other must be another object");
	if (ownsMemory)
	{
		m_leafNodes.copyFromArray(other.m_leafNodes);
		m_contiguousNodes.copyFromArray(other.m_contiguousNodes);
		m_quantizedLeafNodes.copyFromArray(other.m_quantizedLeafNodes);
		m_quantizedContiguousNodes.copyFromArray(other.m_quantizedContiguousNodes);
		m_SubtreeHeaders.copyFromArray(other.m_SubtreeHeaders);
		return;
	}
	// The leaf arrays are only the builder's input; a viewing tree is a built tree without them.
	viewStorageOf(m_contiguousNodes, other.m_contiguousNodes);
	viewStorageOf(m_quantizedContiguousNodes, other.m_quantizedContiguousNodes);
	viewStorageOf(m_SubtreeHeaders, other.m_SubtreeHeaders);
}

unsigned int btQuantizedBvh::getAlignmentSerializationPadding() { return 16u; }
