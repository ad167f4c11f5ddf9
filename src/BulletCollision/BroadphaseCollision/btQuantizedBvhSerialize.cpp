// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// btQuantizedBvh in .bullet files: serialize writes btQuantizedBvhFloatData / DoubleData (the build's
// precision) with the node arrays and subtree headers as ARAY chunks; deSerializeFloat / Double read
// them back. A file is untrusted input: the description is checked to be a well-formed depth-first tree
// (every walk and refit then stays inside the arrays) before anything is replaced.
#include "BulletCollision/BroadphaseCollision/btQuantizedBvh.h"
#include "LinearMath/btSerializer.h"
#include "LinearMath/btWarningHook.h"
#include "QuantizedBvhTreeCheck.h"

#include <string.h>

#include <string>

namespace
{
// Quantized nodes mark leaves by a non-negative payload and internal nodes by minus their subtree size.
struct QuantizedNodes
{
	const btQuantizedBvhNodeData* nodes;
	bool isLeaf(int i) const { return nodes[i].m_escapeIndexOrTriangleIndex >= 0; }
	long long escape(int i) const { return -static_cast<long long>(nodes[i].m_escapeIndexOrTriangleIndex); }
};

// Unquantized nodes mark leaves by a negative escape index.
template <class NodeData>
struct PlainNodes
{
	const NodeData* nodes;
	bool isLeaf(int i) const { return nodes[i].m_escapeIndex < 0; }
	long long escape(int i) const { return nodes[i].m_escapeIndex; }
};

void readVector(btVector3& out, const btVector3FloatData& in) { out.deSerializeFloat(in); }
void readVector(btVector3& out, const btVector3DoubleData& in) { out.deSerializeDouble(in); }

// Judged as read: a double too large for a float build is not finite there either.
template <class V>
bool finiteAsRead(const V& in)
{
	btVector3 v;
	readVector(v, in);
	return caliber::isFinite(v);
}

// The reason data is not a tree this reader can use, or 0.
template <class Data, class NodeData>
const char* problemOf(const Data& d)
{
	if (d.m_useQuantization != 0 && d.m_useQuantization != 1) return "m_useQuantization is neither 0 nor 1";
	if (d.m_traversalMode < 0 || d.m_traversalMode > 2) return "unknown m_traversalMode";
	if (d.m_numContiguousLeafNodes < 0 || d.m_numQuantizedContiguousNodes < 0 || d.m_numSubtreeHeaders < 0)
		return "a negative count";
	if ((d.m_numContiguousLeafNodes > 0 && !d.m_contiguousNodesPtr) ||
	    (d.m_numQuantizedContiguousNodes > 0 && !d.m_quantizedContiguousNodesPtr) ||
	    (d.m_numSubtreeHeaders > 0 && !d.m_subTreeInfoPtr))
		return "an array is missing";
	const bool quantized = d.m_useQuantization == 1;
	const int available = quantized ? d.m_numQuantizedContiguousNodes : d.m_numContiguousLeafNodes;
	if (d.m_curNodeIndex < 0 || d.m_curNodeIndex > available) return "m_curNodeIndex exceeds the node array";
	const int numNodes = d.m_curNodeIndex;
	if (quantized)
	{
		if (!finiteAsRead(d.m_bvhAabbMin) || !finiteAsRead(d.m_bvhAabbMax) || !finiteAsRead(d.m_bvhQuantization))
			return "a non-finite quantization box";
		for (int a = 0; a < 3; ++a)
			if (!(d.m_bvhAabbMin.m_floats[a] <= d.m_bvhAabbMax.m_floats[a]) || !(d.m_bvhQuantization.m_floats[a] > 0))
				return "an inverted quantization box or a quantization that is not positive";
		const QuantizedNodes nodes = {d.m_quantizedContiguousNodesPtr};
		if (!caliber::wellFormedBvhTree(nodes, numNodes)) return "the nodes do not form a tree (escape indices)";
		if (!caliber::bvhSubtreeHeadersFit(nodes, numNodes, d.m_subTreeInfoPtr, d.m_numSubtreeHeaders))
			return "a subtree header outside the tree";
	}
	else
	{
		const PlainNodes<NodeData> nodes = {d.m_contiguousNodesPtr};
		for (int i = 0; i < numNodes; ++i)
		{
			const NodeData& node = d.m_contiguousNodesPtr[i];
			if (!finiteAsRead(node.m_aabbMinOrg) || !finiteAsRead(node.m_aabbMaxOrg)) return "a non-finite node box";
			if (node.m_escapeIndex < 0 && (node.m_subPart < 0 || node.m_triangleIndex < 0))
				return "a leaf with a negative part or triangle index";
		}
		if (!caliber::wellFormedBvhTree(nodes, numNodes)) return "the nodes do not form a tree (escape indices)";
		if (!caliber::bvhSubtreeHeadersFit(nodes, numNodes, d.m_subTreeInfoPtr, d.m_numSubtreeHeaders))
			return "a subtree header outside the tree";
	}
	return 0;
}

void copyNode(btQuantizedBvhNode& out, const btQuantizedBvhNodeData& in)
{
	for (int a = 0; a < 3; ++a)
	{
		out.m_quantizedAabbMin[a] = static_cast<unsigned short>(in.m_quantizedAabbMin[a]);
		out.m_quantizedAabbMax[a] = static_cast<unsigned short>(in.m_quantizedAabbMax[a]);
	}
	out.m_escapeIndexOrTriangleIndex = in.m_escapeIndexOrTriangleIndex;
}

template <class NodeData>
void copyNode(btOptimizedBvhNode& out, const NodeData& in)
{
	readVector(out.m_aabbMinOrg, in.m_aabbMinOrg);
	readVector(out.m_aabbMaxOrg, in.m_aabbMaxOrg);
	out.m_escapeIndex = in.m_escapeIndex;
	out.m_subPart = in.m_subPart;
	out.m_triangleIndex = in.m_triangleIndex;
	for (int k = 0; k < 5; ++k) out.m_padding[k] = 0;
}

void copyHeader(btBvhSubtreeInfo& out, const btBvhSubtreeInfoData& in)
{
	for (int a = 0; a < 3; ++a)
	{
		out.m_quantizedAabbMin[a] = static_cast<unsigned short>(in.m_quantizedAabbMin[a]);
		out.m_quantizedAabbMax[a] = static_cast<unsigned short>(in.m_quantizedAabbMax[a]);
	}
	out.m_rootNodeIndex = in.m_rootNodeIndex;
	out.m_subtreeSize = in.m_subtreeSize;
}

// Reaches the protected members (a pointer to member formed in a derived class; no member is added).
struct BvhFields : btQuantizedBvh
{
	template <class Data, class NodeData>
	static void read(btQuantizedBvh& bvh, const Data& d)
	{
		NodeArray& contiguous = bvh.*(&BvhFields::m_contiguousNodes);
		QuantizedNodeArray& quantized = bvh.*(&BvhFields::m_quantizedContiguousNodes);
		BvhSubtreeInfoArray& headers = bvh.*(&BvhFields::m_SubtreeHeaders);
		(bvh.*(&BvhFields::m_leafNodes)).resize(0);
		(bvh.*(&BvhFields::m_quantizedLeafNodes)).resize(0);
		const char* problem = problemOf<Data, NodeData>(d);
		if (problem)
		{
			btReportWarning(
			    (std::string("Caliber: btQuantizedBvh::deSerialize: ") + problem + "; the tree is left empty\n")
			        .c_str());
			contiguous.resize(0);
			quantized.resize(0);
			headers.resize(0);
			bvh.*(&BvhFields::m_subtreeHeaderCount) = 0;
			bvh.*(&BvhFields::m_curNodeIndex) = 0;
			bvh.*(&BvhFields::m_useQuantization) = false;
			return;
		}
		readVector(bvh.*(&BvhFields::m_bvhAabbMin), d.m_bvhAabbMin);
		readVector(bvh.*(&BvhFields::m_bvhAabbMax), d.m_bvhAabbMax);
		readVector(bvh.*(&BvhFields::m_bvhQuantization), d.m_bvhQuantization);
		(bvh.*(&BvhFields::m_bvhQuantization))[3] = 0;
		bvh.*(&BvhFields::m_curNodeIndex) = d.m_curNodeIndex;
		bvh.*(&BvhFields::m_useQuantization) = d.m_useQuantization == 1;
		bvh.*(&BvhFields::m_traversalMode) = btTraversalMode(d.m_traversalMode);
		contiguous.resize(d.m_numContiguousLeafNodes);
		for (int i = 0; i < d.m_numContiguousLeafNodes; ++i) copyNode(contiguous[i], d.m_contiguousNodesPtr[i]);
		quantized.resize(d.m_numQuantizedContiguousNodes);
		for (int i = 0; i < d.m_numQuantizedContiguousNodes; ++i)
			copyNode(quantized[i], d.m_quantizedContiguousNodesPtr[i]);
		headers.resize(d.m_numSubtreeHeaders);
		for (int h = 0; h < d.m_numSubtreeHeaders; ++h) copyHeader(headers[h], d.m_subTreeInfoPtr[h]);
		bvh.*(&BvhFields::m_subtreeHeaderCount) = d.m_numSubtreeHeaders;
	}
};

void writeNode(btOptimizedBvhNodeData& out, const btOptimizedBvhNode& in)
{
	in.m_aabbMinOrg.serialize(out.m_aabbMinOrg);
	in.m_aabbMaxOrg.serialize(out.m_aabbMaxOrg);
	out.m_escapeIndex = in.m_escapeIndex;
	out.m_subPart = in.m_subPart;
	out.m_triangleIndex = in.m_triangleIndex;
	memset(out.m_pad, 0, sizeof(out.m_pad));
}
}  // namespace

int btQuantizedBvh::calculateSerializeBufferSizeNew() const { return int(sizeof(btQuantizedBvhData)); }

const char* btQuantizedBvh::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btQuantizedBvhData* d = static_cast<btQuantizedBvhData*>(dataBuffer);
	m_bvhAabbMin.serialize(d->m_bvhAabbMin);
	m_bvhAabbMax.serialize(d->m_bvhAabbMax);
	m_bvhQuantization.serialize(d->m_bvhQuantization);
	d->m_curNodeIndex = m_curNodeIndex;
	d->m_useQuantization = m_useQuantization ? 1 : 0;
	d->m_numContiguousLeafNodes = m_contiguousNodes.size();
	d->m_numQuantizedContiguousNodes = m_quantizedContiguousNodes.size();
	d->m_traversalMode = int(m_traversalMode);
	d->m_numSubtreeHeaders = m_SubtreeHeaders.size();
	d->m_contiguousNodesPtr = 0;
	d->m_quantizedContiguousNodesPtr = 0;
	d->m_subTreeInfoPtr = 0;

	// Each array is a chunk of its own, identified by its first element.
	if (const int n = m_contiguousNodes.size())
	{
		void* id = const_cast<btOptimizedBvhNode*>(&m_contiguousNodes[0]);
		btChunk* chunk = serializer->allocate(sizeof(btOptimizedBvhNodeData), n);
		if (chunk)
		{
			d->m_contiguousNodesPtr = static_cast<btOptimizedBvhNodeData*>(serializer->getUniquePointer(id));
			btOptimizedBvhNodeData* out = static_cast<btOptimizedBvhNodeData*>(chunk->m_oldPtr);
			for (int i = 0; i < n; ++i) writeNode(out[i], m_contiguousNodes[i]);
#ifdef BT_USE_DOUBLE_PRECISION
			serializer->finalizeChunk(chunk, "btOptimizedBvhNodeDoubleData", BT_ARRAY_CODE, id);
#else
			serializer->finalizeChunk(chunk, "btOptimizedBvhNodeFloatData", BT_ARRAY_CODE, id);
#endif
		}
	}
	if (const int n = m_quantizedContiguousNodes.size())
	{
		void* id = const_cast<btQuantizedBvhNode*>(&m_quantizedContiguousNodes[0]);
		btChunk* chunk = serializer->allocate(sizeof(btQuantizedBvhNodeData), n);
		if (chunk)
		{
			d->m_quantizedContiguousNodesPtr = static_cast<btQuantizedBvhNodeData*>(serializer->getUniquePointer(id));
			btQuantizedBvhNodeData* out = static_cast<btQuantizedBvhNodeData*>(chunk->m_oldPtr);
			for (int i = 0; i < n; ++i)
			{
				const btQuantizedBvhNode& in = m_quantizedContiguousNodes[i];
				for (int a = 0; a < 3; ++a)
				{
					out[i].m_quantizedAabbMin[a] = static_cast<short>(in.m_quantizedAabbMin[a]);
					out[i].m_quantizedAabbMax[a] = static_cast<short>(in.m_quantizedAabbMax[a]);
				}
				out[i].m_escapeIndexOrTriangleIndex = in.m_escapeIndexOrTriangleIndex;
			}
			serializer->finalizeChunk(chunk, "btQuantizedBvhNodeData", BT_ARRAY_CODE, id);
		}
	}
	if (const int n = m_SubtreeHeaders.size())
	{
		void* id = const_cast<btBvhSubtreeInfo*>(&m_SubtreeHeaders[0]);
		btChunk* chunk = serializer->allocate(sizeof(btBvhSubtreeInfoData), n);
		if (chunk)
		{
			d->m_subTreeInfoPtr = static_cast<btBvhSubtreeInfoData*>(serializer->getUniquePointer(id));
			btBvhSubtreeInfoData* out = static_cast<btBvhSubtreeInfoData*>(chunk->m_oldPtr);
			for (int h = 0; h < n; ++h)
			{
				const btBvhSubtreeInfo& in = m_SubtreeHeaders[h];
				out[h].m_rootNodeIndex = in.m_rootNodeIndex;
				out[h].m_subtreeSize = in.m_subtreeSize;
				for (int a = 0; a < 3; ++a)
				{
					out[h].m_quantizedAabbMin[a] = static_cast<short>(in.m_quantizedAabbMin[a]);
					out[h].m_quantizedAabbMax[a] = static_cast<short>(in.m_quantizedAabbMax[a]);
				}
			}
			serializer->finalizeChunk(chunk, "btBvhSubtreeInfoData", BT_ARRAY_CODE, id);
		}
	}
	return btQuantizedBvhDataName;
}

void btQuantizedBvh::deSerializeFloat(btQuantizedBvhFloatData& quantizedBvhFloatData)
{
	BvhFields::read<btQuantizedBvhFloatData, btOptimizedBvhNodeFloatData>(*this, quantizedBvhFloatData);
}

void btQuantizedBvh::deSerializeDouble(btQuantizedBvhDoubleData& quantizedBvhDoubleData)
{
	BvhFields::read<btQuantizedBvhDoubleData, btOptimizedBvhNodeDoubleData>(*this, quantizedBvhDoubleData);
}
