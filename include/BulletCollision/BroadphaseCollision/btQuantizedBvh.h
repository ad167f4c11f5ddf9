// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_QUANTIZED_BVH_H
#define BT_QUANTIZED_BVH_H

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btVector3.h"

class btSerializer;
struct btQuantizedBvhFloatData;
struct btQuantizedBvhDoubleData;

#ifdef BT_USE_DOUBLE_PRECISION
#define btQuantizedBvhData btQuantizedBvhDoubleData
#define btOptimizedBvhNodeData btOptimizedBvhNodeDoubleData
#define btQuantizedBvhDataName "btQuantizedBvhDoubleData"
#else
#define btQuantizedBvhData btQuantizedBvhFloatData
#define btOptimizedBvhNodeData btOptimizedBvhNodeFloatData
#define btQuantizedBvhDataName "btQuantizedBvhFloatData"
#endif

/// Subtrees at most this many bytes get a btBvhSubtreeInfo header.
#define MAX_SUBTREE_SIZE_IN_BYTES 2048
/// Bits of a quantized leaf's payload that hold the part id (the other 21 hold the triangle index).
#define MAX_NUM_PARTS_IN_BITS 10

/// A node of a quantized BVH: a 16-bit-per-axis box and either a leaf payload (part id and triangle
/// index, >= 0) or, for an internal node, minus the number of nodes in its subtree (its escape index).
ATTRIBUTE_ALIGNED16(struct)
btQuantizedBvhNode
{
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Quantized minimum corner (even values: rounded down).
	unsigned short int m_quantizedAabbMin[3];
	/// Quantized maximum corner (odd values: rounded up).
	unsigned short int m_quantizedAabbMax[3];
	/// Leaf: (partId << 21) | triangleIndex. Internal node: -(nodes in the subtree).
	int m_escapeIndexOrTriangleIndex;

	/// True for a leaf.
	bool isLeafNode() const { return m_escapeIndexOrTriangleIndex >= 0; }
	/// Number of nodes in the subtree of an internal node (the step that skips it).
	int getEscapeIndex() const
	{
		btAssert(!isLeafNode());
		return -m_escapeIndexOrTriangleIndex;
	}
	/// Triangle index of a leaf.
	int getTriangleIndex() const
	{
		btAssert(isLeafNode());
		return m_escapeIndexOrTriangleIndex & ((1 << (31 - MAX_NUM_PARTS_IN_BITS)) - 1);
	}
	/// Part id of a leaf.
	int getPartId() const
	{
		btAssert(isLeafNode());
		return m_escapeIndexOrTriangleIndex >> (31 - MAX_NUM_PARTS_IN_BITS);
	}
};

/// A node of an unquantized BVH: a float box, and the escape index (internal) or part and triangle (leaf).
ATTRIBUTE_ALIGNED16(struct)
btOptimizedBvhNode
{
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Minimum corner.
	btVector3 m_aabbMinOrg;
	/// Maximum corner.
	btVector3 m_aabbMaxOrg;
	/// -1 for a leaf; the number of nodes in the subtree for an internal node.
	int m_escapeIndex;
	/// Part id of a leaf.
	int m_subPart;
	/// Triangle index of a leaf.
	int m_triangleIndex;
	/// Keeps the node 64 bytes.
	int m_padding[5];
};

/// A subtree small enough to stay in cache, with its quantized box (quantized BVHs only).
ATTRIBUTE_ALIGNED16(class)
btBvhSubtreeInfo
{
public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Quantized minimum corner of the subtree.
	unsigned short int m_quantizedAabbMin[3];
	/// Quantized maximum corner of the subtree.
	unsigned short int m_quantizedAabbMax[3];
	/// Index of the subtree's root node.
	int m_rootNodeIndex;
	/// Number of nodes in the subtree.
	int m_subtreeSize;
	/// Keeps the header 32 bytes.
	int m_padding[3];

	/// A zeroed header.
	btBvhSubtreeInfo() : m_rootNodeIndex(0), m_subtreeSize(0)
	{
		for (int i = 0; i < 3; ++i)
		{
			m_quantizedAabbMin[i] = m_quantizedAabbMax[i] = 0;
			m_padding[i] = 0;
		}
	}
	/// Copies the box of quantizedNode.
	void setAabbFromQuantizeNode(const btQuantizedBvhNode& quantizedNode)
	{
		for (int i = 0; i < 3; ++i)
		{
			m_quantizedAabbMin[i] = quantizedNode.m_quantizedAabbMin[i];
			m_quantizedAabbMax[i] = quantizedNode.m_quantizedAabbMax[i];
		}
	}
};

/// Receives the leaves a BVH query finds.
class btNodeOverlapCallback
{
public:
	/// Callbacks are deleted through base pointers.
	virtual ~btNodeOverlapCallback() {}
	/// One leaf: the part and triangle it stands for.
	virtual void processNode(int subPart, int triangleIndex) = 0;
};

/// Unquantized nodes.
typedef btAlignedObjectArray<btOptimizedBvhNode> NodeArray;
/// Quantized nodes.
typedef btAlignedObjectArray<btQuantizedBvhNode> QuantizedNodeArray;
/// Subtree headers.
typedef btAlignedObjectArray<btBvhSubtreeInfo> BvhSubtreeInfoArray;

/// A bounding volume hierarchy over boxes (one box per leaf), stored depth-first in one array: a node's
/// left child follows it, and an internal node stores the size of its subtree so that a query skips it
/// in one step (stackless traversal, reading memory front to back). Boxes are 16-bit quantized
/// (12 bytes per node plus payload, 16 in all) or plain btVector3 pairs. Built by binned surface area
/// heuristic over leaf centroids along the widest axis. Serialized in .bullet files through the
/// btSerializer interface (serialize, deSerializeFloat, deSerializeDouble), or into one caller-owned
/// block that is later used where it lies (serialize(buffer, size, swapEndian), deSerializeInPlace), in
/// a layout of Caliber's own (docs/meshes-heightfields-and-compounds.md, "In-place buffers").
ATTRIBUTE_ALIGNED16(class)
btQuantizedBvh
{
public:
	/// Bullet's traversal modes; Caliber always runs the stackless traversal (the node order is
	/// already cache friendly), the setting is kept for source compatibility.
	enum btTraversalMode
	{
		TRAVERSAL_STACKLESS = 0,
		TRAVERSAL_STACKLESS_CACHE_FRIENDLY,
		TRAVERSAL_RECURSIVE
	};

protected:
	/// Minimum corner of the quantization box.
	btVector3 m_bvhAabbMin;
	/// Maximum corner of the quantization box.
	btVector3 m_bvhAabbMax;
	/// Quantized units per length unit, per axis.
	btVector3 m_bvhQuantization;
	/// Version tag (Bullet's 289).
	int m_bulletVersion;
	/// Number of nodes built.
	int m_curNodeIndex;
	/// True when the boxes are quantized.
	bool m_useQuantization;
	/// Unquantized leaves (input of buildInternal).
	NodeArray m_leafNodes;
	/// Unquantized tree, depth-first.
	NodeArray m_contiguousNodes;
	/// Quantized leaves (input of buildInternal).
	QuantizedNodeArray m_quantizedLeafNodes;
	/// Quantized tree, depth-first.
	QuantizedNodeArray m_quantizedContiguousNodes;
	/// Stored for compatibility (see btTraversalMode).
	btTraversalMode m_traversalMode;
	/// Headers of the cache-sized subtrees (quantized trees).
	BvhSubtreeInfoArray m_SubtreeHeaders;
	/// Number of subtree headers.
	mutable int m_subtreeHeaderCount;

	// Bullet's protected helpers, for subclasses that build and walk trees of their own leaves (Caliber's
	// buildInternal uses its own binned builder; these follow Bullet's meaning). A node index names a slot
	// of the contiguous tree (m_quantizedContiguousNodes or m_contiguousNodes, whichever m_useQuantization
	// selects); a leaf index names a slot of the leaf array (m_quantizedLeafNodes or m_leafNodes). Indices
	// out of range assert; without asserts the setters do nothing and the getters return (0, 0, 0).

	/// Sets internal node nodeIndex's minimum corner (quantized rounding down for quantized trees).
	void setInternalNodeAabbMin(int nodeIndex, const btVector3& aabbMin);
	/// Sets internal node nodeIndex's maximum corner (quantized rounding up for quantized trees).
	void setInternalNodeAabbMax(int nodeIndex, const btVector3& aabbMax);
	/// Minimum corner of leaf nodeIndex (of the leaf array; unquantized for quantized trees).
	btVector3 getAabbMin(int nodeIndex) const;
	/// Maximum corner of leaf nodeIndex (of the leaf array; unquantized for quantized trees).
	btVector3 getAabbMax(int nodeIndex) const;
	/// Stores escapeIndex (the number of nodes in the subtree rooted there) in internal node nodeIndex.
	void setInternalNodeEscapeIndex(int nodeIndex, int escapeIndex);
	/// Grows internal node nodeIndex's box to contain [newAabbMin, newAabbMax].
	void mergeInternalNodeAabb(int nodeIndex, const btVector3& newAabbMin, const btVector3& newAabbMax);
	/// Exchanges leaves firstIndex and secondIndex of the leaf array.
	void swapLeafNodes(int firstIndex, int secondIndex);
	/// Copies leaf leafNodeIndex (box and payload) into tree node internalNode.
	void assignInternalNodeFromLeafNode(int internalNode, int leafNodeIndex);

	/// Builds the subtree of leaves [startIndex, endIndex) depth-first at node m_curNodeIndex, which
	/// advances by its 2 n - 1 nodes (the leaves are reordered; the tree array grows when too short).
	/// Quantized trees get the headers of their cache-sized subtrees below nodes too big to be one
	/// (the caller adds the root's when there are none, as in Bullet). An empty or out-of-range range
	/// asserts; without asserts nothing is built.
	void buildTree(int startIndex, int endIndex);
	/// The axis (0, 1 or 2) along which the centres of leaves [startIndex, endIndex) vary most.
	int calcSplittingAxis(int startIndex, int endIndex);
	/// Puts the leaves of [startIndex, endIndex) whose centre lies above the mean centre along splitAxis
	/// first and returns the index of the first of the others: the split. A split leaving either side
	/// with fewer than a third of the leaves gives the middle instead (a balanced tree, as in Bullet).
	int sortAndCalcSplittingIndex(int startIndex, int endIndex, int splitAxis);

	/// Calls nodeCallback for every leaf of the unquantized tree whose box overlaps [aabbMin, aabbMax].
	void walkStacklessTree(btNodeOverlapCallback * nodeCallback, const btVector3& aabbMin, const btVector3& aabbMax)
	    const;
	/// As walkStacklessTreeAgainstRay for quantized trees.
	void walkStacklessQuantizedTreeAgainstRay(btNodeOverlapCallback * nodeCallback, const btVector3& raySource,
	                                          const btVector3& rayTarget, const btVector3& aabbMin,
	                                          const btVector3& aabbMax, int startNodeIndex, int endNodeIndex) const;
	/// Calls nodeCallback for every leaf among nodes [startNodeIndex, endNodeIndex) of the quantized tree
	/// (a whole subtree's range) whose box overlaps the quantized query box.
	void walkStacklessQuantizedTree(btNodeOverlapCallback * nodeCallback, unsigned short int* quantizedQueryAabbMin,
	                                unsigned short int* quantizedQueryAabbMax, int startNodeIndex, int endNodeIndex)
	    const;
	/// Calls nodeCallback for every leaf among nodes [startNodeIndex, endNodeIndex) of the unquantized tree
	/// whose box the box [aabbMin, aabbMax] (zero for a ray) swept from raySource to rayTarget touches.
	void walkStacklessTreeAgainstRay(btNodeOverlapCallback * nodeCallback, const btVector3& raySource,
	                                 const btVector3& rayTarget, const btVector3& aabbMin, const btVector3& aabbMax,
	                                 int startNodeIndex, int endNodeIndex) const;
	/// walkStacklessQuantizedTree over the subtrees (m_SubtreeHeaders) whose box overlaps the query.
	void walkStacklessQuantizedTreeCacheFriendly(btNodeOverlapCallback * nodeCallback,
	                                             unsigned short int* quantizedQueryAabbMin,
	                                             unsigned short int* quantizedQueryAabbMax) const;
	/// The same leaves as walkStacklessQuantizedTree, below currentNode, found by recursion.
	void walkRecursiveQuantizedTreeAgainstQueryAabb(
	    const btQuantizedBvhNode* currentNode, btNodeOverlapCallback* nodeCallback,
	    unsigned short int* quantizedQueryAabbMin, unsigned short int* quantizedQueryAabbMax) const;
	/// For every pair of overlapping leaves, one below treeNodeA and one below treeNodeB (nodes of quantized
	/// trees sharing this BVH's quantization), calls nodeCallback with the leaf below treeNodeA (Bullet
	/// 2.89 declares this walk without defining it).
	void walkRecursiveQuantizedTreeAgainstQuantizedTree(
	    const btQuantizedBvhNode* treeNodeA, const btQuantizedBvhNode* treeNodeB, btNodeOverlapCallback* nodeCallback)
	    const;
	/// Appends a header for each of the two children (quantized nodes) whose subtree fits in
	/// MAX_SUBTREE_SIZE_IN_BYTES, and updates m_subtreeHeaderCount.
	void updateSubtreeHeaders(int leftChildNodexIndex, int rightChildNodexIndex);

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// An empty, unquantized BVH.
	btQuantizedBvh();
	/// BVHs are deleted through base pointers.
	virtual ~btQuantizedBvh();

	/// Sets the quantization box to [bvhAabbMin, bvhAabbMax] grown by quantizationMargin on every side
	/// and turns quantization on. A non-finite or inverted box asserts and is replaced by [-1, 1]^3; an
	/// axis of zero extent gets extent 1 so that quantization stays finite.
	void setQuantizationValues(const btVector3& bvhAabbMin, const btVector3& bvhAabbMax,
	                           btScalar quantizationMargin = btScalar(1.0));

	/// The quantized leaves to fill before buildInternal.
	QuantizedNodeArray& getLeafNodeArray() { return m_quantizedLeafNodes; }

	/// Builds the tree from the leaves already stored (getLeafNodeArray for quantized BVHs).
	void buildInternal();

	/// Calls nodeCallback for every leaf whose box overlaps (or touches) [aabbMin, aabbMax]. Quantized
	/// boxes are conservative: every leaf whose true box overlaps is reported, plus possibly leaves
	/// within about two quantization steps. A non-finite box asserts and reports nothing.
	void reportAabbOverlappingNodex(btNodeOverlapCallback * nodeCallback, const btVector3& aabbMin,
	                                const btVector3& aabbMax) const;

	/// Calls nodeCallback for every leaf whose box the segment raySource -> rayTarget touches (boxes grown
	/// by a relative tolerance of about 1e-5 in single precision so that hits on box faces are not lost
	/// to rounding).
	void reportRayOverlappingNodex(btNodeOverlapCallback * nodeCallback, const btVector3& raySource,
	                               const btVector3& rayTarget) const;

	/// Calls nodeCallback for every leaf whose box is touched by the box [aabbMin, aabbMax] (relative to
	/// the moving point) swept from raySource to rayTarget.
	void reportBoxCastOverlappingNodex(btNodeOverlapCallback * nodeCallback, const btVector3& raySource,
	                                   const btVector3& rayTarget, const btVector3& aabbMin, const btVector3& aabbMax)
	    const;

	/// Quantizes point (which should lie in the quantization box) conservatively: a minimum corner
	/// (isMax == 0) rounds down to an even value, a maximum corner rounds up to an odd value, both with
	/// a small safety slack for the rounding of the scaling itself. Out-of-range values are clamped.
	SIMD_FORCE_INLINE void quantize(unsigned short* out, const btVector3& point, int isMax) const
	{
		btAssert(m_useQuantization);
		const btVector3 v = (point - m_bvhAabbMin) * m_bvhQuantization;
		// 1/16 of a step covers the float rounding of the product (a few ulp of values below 65536).
		const btScalar slack = btScalar(0.0625);
		for (int axis = 0; axis < 3; ++axis)
		{
			btScalar c = isMax ? v[axis] + slack : v[axis] - slack;
			if (!(c >= btScalar(0))) c = btScalar(0);  // also catches NaN
			if (c > btScalar(65535)) c = btScalar(65535);
			unsigned q = unsigned(c);           // floor, c being >= 0
			if (isMax && btScalar(q) < c) ++q;  // ceil
			if (q > 65535u) q = 65535u;
			out[axis] = (unsigned short)(isMax ? (q | 1u) : (q & 0xFFFEu));
		}
	}

	/// quantize after clamping point into the quantization box.
	SIMD_FORCE_INLINE void quantizeWithClamp(unsigned short* out, const btVector3& point2, int isMax) const
	{
		btAssert(m_useQuantization);
		btVector3 clamped = point2;
		clamped.setMax(m_bvhAabbMin);
		clamped.setMin(m_bvhAabbMax);
		quantize(out, clamped, isMax);
	}

	/// The point a quantized corner stands for.
	SIMD_FORCE_INLINE btVector3 unQuantize(const unsigned short* vecIn) const
	{
		return btVector3(btScalar(vecIn[0]) / m_bvhQuantization.x(), btScalar(vecIn[1]) / m_bvhQuantization.y(),
		                 btScalar(vecIn[2]) / m_bvhQuantization.z()) +
		       m_bvhAabbMin;
	}

	/// Stores the traversal mode (see btTraversalMode).
	void setTraversalMode(btTraversalMode traversalMode) { m_traversalMode = traversalMode; }

	/// The quantized tree.
	QuantizedNodeArray& getQuantizedNodeArray() { return m_quantizedContiguousNodes; }
	/// The subtree headers.
	BvhSubtreeInfoArray& getSubtreeInfoArray() { return m_SubtreeHeaders; }

	/// True when the boxes are quantized.
	bool isQuantized() { return m_useQuantization; }
	/// True when the boxes are quantized.
	bool isQuantized() const { return m_useQuantization; }

	/// Bytes serialize(buffer, size, swapEndian) needs for this tree.
	unsigned calculateSerializeBufferSize() const;
	/// Writes the tree into a 16-byte aligned block of at least calculateSerializeBufferSize() bytes,
	/// byte-swapped for a machine of the other byte order when i_swapEndian. A null, misaligned or too
	/// small block asserts and, without asserts, writes nothing and returns false.
	virtual bool serialize(void* o_alignedDataBuffer, unsigned i_dataBufferSize, bool i_swapEndian) const;
	/// The tree a block written by serialize holds, built in the block itself (its arrays point into
	/// the block, which the caller keeps alive and frees; destroy the tree with ~btQuantizedBvh(), never
	/// delete). Byte-swaps the block first when i_swapEndian. A block that is not such a tree (null or
	/// misaligned, too small, wrong magic, version, precision or byte order, counts past its end, a
	/// non-finite or inverted box, bad escape indices or subtree headers) is reported through
	/// btReportWarning and gives null, the block left as it was.
	static btQuantizedBvh* deSerializeInPlace(void* i_alignedDataBuffer, unsigned int i_dataBufferSize,
	                                          bool i_swapEndian);
	/// Slack bytes to add to an allocation that is not 16-byte aligned, to align an in-place block in it.
	static unsigned int getAlignmentSerializationPadding();

	/// Bytes of the struct serialize() writes (btQuantizedBvhFloatData or DoubleData, the build's precision).
	virtual int calculateSerializeBufferSizeNew() const;
	/// Writes the tree's struct into dataBuffer and its node and subtree arrays as chunks of their own;
	/// returns the struct's name.
	virtual const char* serialize(void* dataBuffer, btSerializer* serializer) const;
	/// Replaces this tree by the one data describes (read from a file written in single precision). A
	/// description that is not a well-formed tree (counts, escape indices, subtree headers, quantization
	/// box; docs/bad-input.md) is reported through btReportWarning and leaves an empty tree.
	virtual void deSerializeFloat(struct btQuantizedBvhFloatData & quantizedBvhFloatData);
	/// As deSerializeFloat, from a file written in double precision.
	virtual void deSerializeDouble(struct btQuantizedBvhDoubleData & quantizedBvhDoubleData);

private:
	/// Bullet's in-place deserialisation constructor (private, as in Bullet: deSerializeInPlace alone
	/// calls it). The new tree takes other's quantization box, flags, node count and subtree header
	/// count; with ownsMemory false its contiguous node and subtree header arrays view other's storage
	/// (nothing copied, other's storage must outlive the tree: the in-place block), with ownsMemory true
	/// it copies every array. other must be another object (Caliber's loader stages the tree beside the
	/// block and constructs the block's object from it, never over itself).
	btQuantizedBvh(btQuantizedBvh & other, bool ownsMemory);
};

// clang-format off
/// File layout of btBvhSubtreeInfoData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btBvhSubtreeInfoData
{
	int m_rootNodeIndex;
	int m_subtreeSize;
	short m_quantizedAabbMin[3];
	short m_quantizedAabbMax[3];
};

/// File layout of btOptimizedBvhNodeFloatData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btOptimizedBvhNodeFloatData
{
	btVector3FloatData m_aabbMinOrg;
	btVector3FloatData m_aabbMaxOrg;
	int m_escapeIndex;
	int m_subPart;
	int m_triangleIndex;
	char m_pad[4];
};

/// File layout of btOptimizedBvhNodeDoubleData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btOptimizedBvhNodeDoubleData
{
	btVector3DoubleData m_aabbMinOrg;
	btVector3DoubleData m_aabbMaxOrg;
	int m_escapeIndex;
	int m_subPart;
	int m_triangleIndex;
	char m_pad[4];
};

/// File layout of btQuantizedBvhNodeData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btQuantizedBvhNodeData
{
	short m_quantizedAabbMin[3];
	short m_quantizedAabbMax[3];
	int m_escapeIndexOrTriangleIndex;
};

/// File layout of btQuantizedBvhFloatData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btQuantizedBvhFloatData
{
	btVector3FloatData m_bvhAabbMin;
	btVector3FloatData m_bvhAabbMax;
	btVector3FloatData m_bvhQuantization;
	int m_curNodeIndex;
	int m_useQuantization;
	int m_numContiguousLeafNodes;
	int m_numQuantizedContiguousNodes;
	btOptimizedBvhNodeFloatData* m_contiguousNodesPtr;
	btQuantizedBvhNodeData* m_quantizedContiguousNodesPtr;
	btBvhSubtreeInfoData* m_subTreeInfoPtr;
	int m_traversalMode;
	int m_numSubtreeHeaders;
};

/// File layout of btQuantizedBvhDoubleData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btQuantizedBvhDoubleData
{
	btVector3DoubleData m_bvhAabbMin;
	btVector3DoubleData m_bvhAabbMax;
	btVector3DoubleData m_bvhQuantization;
	int m_curNodeIndex;
	int m_useQuantization;
	int m_numContiguousLeafNodes;
	int m_numQuantizedContiguousNodes;
	btOptimizedBvhNodeDoubleData* m_contiguousNodesPtr;
	btQuantizedBvhNodeData* m_quantizedContiguousNodesPtr;
	int m_traversalMode;
	int m_numSubtreeHeaders;
	btBvhSubtreeInfoData* m_subTreeInfoPtr;
};

// clang-format on

#endif  // BT_QUANTIZED_BVH_H
