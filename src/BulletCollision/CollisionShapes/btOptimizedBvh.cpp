// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btOptimizedBvh.h"

#include "BulletCollision/BroadphaseCollision/QuantizedBvhAccess.h"
#include "BulletCollision/BroadphaseCollision/QuantizedBvhInPlace.h"
#include "BulletCollision/CollisionShapes/btStridingMeshInterface.h"
#include "LinearMath/btAabbUtil2.h"
#include "btMeshTriangleAccess.h"

#include <new>

namespace
{
const int kTriangleIndexBits = 31 - MAX_NUM_PARTS_IN_BITS;

bool validBox(const btVector3& aabbMin, const btVector3& aabbMax)
{
	return caliber::isFinite(aabbMin) && caliber::isFinite(aabbMax) && aabbMin.x() <= aabbMax.x() &&
	       aabbMin.y() <= aabbMax.y() && aabbMin.z() <= aabbMax.z();
}

// Reads the scaled box of triangle (partId, triangleIndex), locking its part only when it changes.
bool readLeafBox(caliber::ReadOnlyMeshPart& part, const btStridingMeshInterface& mesh, int partId, int triangleIndex,
                 btVector3& aabbMin, btVector3& aabbMax)
{
	if (part.part() != partId) part.acquire(&mesh, partId);
	btVector3 triangle[3];
	if (!part.readTriangle(triangleIndex, mesh.getScaling(), triangle)) return false;
	caliber::triangleAabb(triangle, aabbMin, aabbMax);
	return true;
}
}  // namespace

btOptimizedBvh::btOptimizedBvh() {}

btOptimizedBvh::~btOptimizedBvh() {}

// The in-place block's object region is sized for btQuantizedBvh; a btOptimizedBvh is built there too.
static_assert(sizeof(btOptimizedBvh) <= caliber::kInPlaceBvhObjectBytes, "in-place object region too small");

bool btOptimizedBvh::serializeInPlace(void* o_alignedDataBuffer, unsigned i_dataBufferSize, bool i_swapEndian) const
{
	return btQuantizedBvh::serialize(o_alignedDataBuffer, i_dataBufferSize, i_swapEndian);
}

btOptimizedBvh* btOptimizedBvh::deSerializeInPlace(void* i_alignedDataBuffer, unsigned int i_dataBufferSize,
                                                   bool i_swapEndian)
{
	if (const char* problem = caliber::prepareInPlaceBvh(i_alignedDataBuffer, i_dataBufferSize, i_swapEndian))
	{
		caliber::warnInPlaceBvh("btOptimizedBvh::deSerializeInPlace", problem);
		return 0;
	}
	btOptimizedBvh* bvh = new (i_alignedDataBuffer) btOptimizedBvh();
	caliber::adoptInPlaceBvh(*bvh, i_alignedDataBuffer);
	return bvh;
}

namespace
{
void quantizedLeafFromBox(const btQuantizedBvh& bvh, btQuantizedBvhNode& node, const btVector3& aabbMin,
                          const btVector3& aabbMax)
{
	bvh.quantizeWithClamp(node.m_quantizedAabbMin, aabbMin, 0);
	bvh.quantizeWithClamp(node.m_quantizedAabbMax, aabbMax, 1);
}

void setLeafBox(btQuantizedBvh& bvh, int nodeIndex, bool valid, const btVector3& aabbMin, const btVector3& aabbMax)
{
	// An unreadable triangle gets an empty box (min above max): no query reaches it through its parents.
	const caliber::QuantizedBvhParts tree = caliber::QuantizedBvhAccess::parts(bvh);
	if (tree.useQuantization)
	{
		btQuantizedBvhNode& node = tree.quantizedContiguousNodes[nodeIndex];
		if (valid)
			quantizedLeafFromBox(bvh, node, aabbMin, aabbMax);
		else
			for (int a = 0; a < 3; ++a)
			{
				node.m_quantizedAabbMin[a] = 0xFFFE;
				node.m_quantizedAabbMax[a] = 1;
			}
	}
	else
	{
		btOptimizedBvhNode& node = tree.contiguousNodes[nodeIndex];
		if (valid)
		{
			node.m_aabbMinOrg = aabbMin;
			node.m_aabbMaxOrg = aabbMax;
		}
		else
		{
			node.m_aabbMinOrg.setValue(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
			node.m_aabbMaxOrg.setValue(-BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT);
		}
	}
}

bool leafBoxesFitQuantization(const btQuantizedBvh& bvh, const btVector3& aabbMin, const btVector3& aabbMax)
{
	const btVector3& boxMin = caliber::bvhAabbMin(bvh);
	const btVector3& boxMax = caliber::bvhAabbMax(bvh);
	return aabbMin.x() >= boxMin.x() && aabbMin.y() >= boxMin.y() && aabbMin.z() >= boxMin.z() &&
	       aabbMax.x() <= boxMax.x() && aabbMax.y() <= boxMax.y() && aabbMax.z() <= boxMax.z();
}
}  // namespace

void btOptimizedBvh::build(btStridingMeshInterface* triangles, bool useQuantizedAabbCompression,
                           const btVector3& bvhAabbMin, const btVector3& bvhAabbMax)
{
	btAssert(triangles != 0 && "btOptimizedBvh::build: null mesh");
	m_leafNodes.resize(0);
	m_quantizedLeafNodes.resize(0);
	m_useQuantization = false;

	btVector3 meshMin(0, 0, 0), meshMax(0, 0, 0);
	bool fitsPayload = true;
	if (triangles)
	{
		caliber::forEachMeshTriangle(
		    *triangles,
		    [&](const btVector3* triangle, int partId, int triangleIndex)
		    {
			    btOptimizedBvhNode leaf;
			    caliber::triangleAabb(triangle, leaf.m_aabbMinOrg, leaf.m_aabbMaxOrg);
			    leaf.m_escapeIndex = -1;
			    leaf.m_subPart = partId;
			    leaf.m_triangleIndex = triangleIndex;
			    for (int k = 0; k < 5; ++k) leaf.m_padding[k] = 0;
			    if (m_leafNodes.size() == 0)
			    {
				    meshMin = leaf.m_aabbMinOrg;
				    meshMax = leaf.m_aabbMaxOrg;
			    }
			    meshMin.setMin(leaf.m_aabbMinOrg);
			    meshMax.setMax(leaf.m_aabbMaxOrg);
			    if (partId >= (1 << MAX_NUM_PARTS_IN_BITS) || triangleIndex >= (1 << kTriangleIndexBits))
				    fitsPayload = false;
			    m_leafNodes.push_back(leaf);
		    });
	}

	if (useQuantizedAabbCompression)
	{
		btAssert(fitsPayload && "quantized BVH: more than 1024 parts or 2^21 triangles in a part");
		useQuantizedAabbCompression = fitsPayload;
	}
	if (useQuantizedAabbCompression)
	{
		// The quantization box must contain every triangle, whatever box the caller passed.
		btVector3 boxMin = meshMin, boxMax = meshMax;
		const bool callerBoxValid = validBox(bvhAabbMin, bvhAabbMax);
		btAssert(callerBoxValid && "btOptimizedBvh::build: non-finite or inverted bvh box");
		if (callerBoxValid)
		{
			if (m_leafNodes.size())
			{
				boxMin.setMin(bvhAabbMin);
				boxMax.setMax(bvhAabbMax);
			}
			else
			{
				boxMin = bvhAabbMin;
				boxMax = bvhAabbMax;
			}
		}
		setQuantizationValues(boxMin, boxMax);
		m_quantizedLeafNodes.resize(m_leafNodes.size());
		for (int i = 0; i < m_leafNodes.size(); ++i)
		{
			const btOptimizedBvhNode& leaf = m_leafNodes[i];
			btQuantizedBvhNode& q = m_quantizedLeafNodes[i];
			quantizedLeafFromBox(*this, q, leaf.m_aabbMinOrg, leaf.m_aabbMaxOrg);
			q.m_escapeIndexOrTriangleIndex = (leaf.m_subPart << kTriangleIndexBits) | leaf.m_triangleIndex;
		}
		m_leafNodes.resize(0);
	}
	caliber::buildQuantizedBvhTree(*this);
	// The leaves now live in the tree; the input arrays are not needed any more.
	m_leafNodes.resize(0);
	m_quantizedLeafNodes.resize(0);
}

void btOptimizedBvh::refit(btStridingMeshInterface* meshInterface, const btVector3& aabbMin, const btVector3& aabbMax)
{
	btAssert(meshInterface != 0 && "btOptimizedBvh::refit: null mesh");
	if (!meshInterface || m_curNodeIndex == 0) return;
	caliber::ReadOnlyMeshPart part;
	if (!m_useQuantization)
	{
		for (int i = 0; i < m_curNodeIndex; ++i)
		{
			const btOptimizedBvhNode& node = m_contiguousNodes[i];
			if (node.m_escapeIndex >= 0) continue;
			btVector3 boxMin, boxMax;
			const bool valid = readLeafBox(part, *meshInterface, node.m_subPart, node.m_triangleIndex, boxMin, boxMax);
			setLeafBox(*this, i, valid, boxMin, boxMax);
		}
		caliber::refitQuantizedBvhInternalNodes(*this);
		return;
	}

	// Quantized: read every box first, so the new quantization box can contain them all.
	btAlignedObjectArray<btVector3> boxes;
	btAlignedObjectArray<unsigned char> valid;
	boxes.resize(2 * m_curNodeIndex);
	valid.resize(m_curNodeIndex, 0);
	const bool callerBoxValid = validBox(aabbMin, aabbMax);
	btAssert(callerBoxValid && "btOptimizedBvh::refit: non-finite or inverted box");
	btVector3 boxMin = callerBoxValid ? aabbMin : m_bvhAabbMin;
	btVector3 boxMax = callerBoxValid ? aabbMax : m_bvhAabbMax;
	for (int i = 0; i < m_curNodeIndex; ++i)
	{
		const btQuantizedBvhNode& node = m_quantizedContiguousNodes[i];
		if (!node.isLeafNode()) continue;
		if (readLeafBox(part, *meshInterface, node.getPartId(), node.getTriangleIndex(), boxes[2 * i],
		                boxes[2 * i + 1]))
		{
			valid[i] = 1;
			boxMin.setMin(boxes[2 * i]);
			boxMax.setMax(boxes[2 * i + 1]);
		}
	}
	setQuantizationValues(boxMin, boxMax);
	for (int i = 0; i < m_curNodeIndex; ++i)
		if (m_quantizedContiguousNodes[i].isLeafNode())
			setLeafBox(*this, i, valid[i] != 0, boxes[2 * i], boxes[2 * i + 1]);
	caliber::refitQuantizedBvhInternalNodes(*this);
	caliber::updateQuantizedBvhSubtreeHeaders(*this);
}

void btOptimizedBvh::refitPartial(btStridingMeshInterface* meshInterface, const btVector3& aabbMin,
                                  const btVector3& aabbMax)
{
	btAssert(meshInterface != 0 && "btOptimizedBvh::refitPartial: null mesh");
	const bool finite = caliber::isFinite(aabbMin) && caliber::isFinite(aabbMax);
	btAssert(finite && "btOptimizedBvh::refitPartial: non-finite box");
	if (!meshInterface || !finite || m_curNodeIndex == 0) return;
	caliber::ReadOnlyMeshPart part;
	btAlignedObjectArray<int> visitedInternal;
	bool leftQuantizationBox = false;
	int i = 0;
	if (m_useQuantization)
	{
		// Every leaf box lies inside the quantization box, so a region outside it touches none.
		if (!TestAabbAgainstAabb2(aabbMin, aabbMax, m_bvhAabbMin, m_bvhAabbMax)) return;
		unsigned short qMin[3], qMax[3];
		quantizeWithClamp(qMin, aabbMin, 0);
		quantizeWithClamp(qMax, aabbMax, 1);
		while (i < m_curNodeIndex)
		{
			const btQuantizedBvhNode& node = m_quantizedContiguousNodes[i];
			const bool overlap = testQuantizedAabbAgainstQuantizedAabb(qMin, qMax, node.m_quantizedAabbMin,
			                                                           node.m_quantizedAabbMax) != 0;
			if (!node.isLeafNode())
			{
				if (overlap) visitedInternal.push_back(i);
				i += overlap ? 1 : node.getEscapeIndex();
				continue;
			}
			if (overlap)
			{
				btVector3 boxMin, boxMax;
				const bool valid =
				    readLeafBox(part, *meshInterface, node.getPartId(), node.getTriangleIndex(), boxMin, boxMax);
				if (valid && !leafBoxesFitQuantization(*this, boxMin, boxMax)) leftQuantizationBox = true;
				setLeafBox(*this, i, valid, boxMin, boxMax);
			}
			++i;
		}
	}
	else
	{
		while (i < m_curNodeIndex)
		{
			const btOptimizedBvhNode& node = m_contiguousNodes[i];
			const bool overlap = TestAabbAgainstAabb2(aabbMin, aabbMax, node.m_aabbMinOrg, node.m_aabbMaxOrg);
			if (node.m_escapeIndex >= 0)
			{
				if (overlap) visitedInternal.push_back(i);
				i += overlap ? 1 : node.m_escapeIndex;
				continue;
			}
			if (overlap)
			{
				btVector3 boxMin, boxMax;
				const bool valid =
				    readLeafBox(part, *meshInterface, node.m_subPart, node.m_triangleIndex, boxMin, boxMax);
				setLeafBox(*this, i, valid, boxMin, boxMax);
			}
			++i;
		}
	}
	part.release();
	if (leftQuantizationBox)
	{
		// Clamped boxes would no longer be conservative: requantize everything in a box that fits.
		refit(meshInterface, m_bvhAabbMin, m_bvhAabbMax);
		return;
	}
	// Preorder puts children after parents, so the reverse order refits bottom-up.
	for (int k = visitedInternal.size() - 1; k >= 0; --k)
		caliber::setQuantizedBvhNodeFromChildren(*this, visitedInternal[k]);
	caliber::updateQuantizedBvhSubtreeHeaders(*this);
}

void btOptimizedBvh::updateBvhNodes(btStridingMeshInterface* meshInterface, int firstNode, int endNode, int index)
{
	(void)index;
	btAssert(meshInterface != 0 && "btOptimizedBvh::updateBvhNodes: null mesh");
	if (!meshInterface) return;
	if (firstNode < 0) firstNode = 0;
	if (endNode > m_curNodeIndex) endNode = m_curNodeIndex;
	caliber::ReadOnlyMeshPart part;
	for (int i = endNode - 1; i >= firstNode; --i)
	{
		int partId, triangleIndex;
		if (m_useQuantization)
		{
			const btQuantizedBvhNode& node = m_quantizedContiguousNodes[i];
			if (!node.isLeafNode())
			{
				caliber::setQuantizedBvhNodeFromChildren(*this, i);
				continue;
			}
			partId = node.getPartId();
			triangleIndex = node.getTriangleIndex();
		}
		else
		{
			const btOptimizedBvhNode& node = m_contiguousNodes[i];
			if (node.m_escapeIndex >= 0)
			{
				caliber::setQuantizedBvhNodeFromChildren(*this, i);
				continue;
			}
			partId = node.m_subPart;
			triangleIndex = node.m_triangleIndex;
		}
		btVector3 boxMin, boxMax;
		const bool valid = readLeafBox(part, *meshInterface, partId, triangleIndex, boxMin, boxMax);
		setLeafBox(*this, i, valid, boxMin, boxMax);
	}
	caliber::updateQuantizedBvhSubtreeHeaders(*this);
}
