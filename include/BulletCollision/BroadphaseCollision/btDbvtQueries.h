// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_DBVT_QUERIES_H
#define BT_DBVT_QUERIES_H

// The templated queries of btDbvt (included by btDbvt.h; include btDbvt.h, not this file). Every query
// walks the tree with an explicit stack: either a member array (collideTT) or the caller's array
// (collideTVNoStackAlloc, rayTestInternal) reused between calls, or a stack on the C++ stack that only
// moves to the heap for trees deeper than its inline capacity (the static queries).

#include "BulletCollision/BroadphaseCollision/btDbvt.h"

DBVT_PREFIX
inline void btDbvt::enumNodes(const btDbvtNode* root, DBVT_IPOLICY)
{
	if (!root) return;
	caliber::DbvtLocalStack<const btDbvtNode*, 128> stack;
	stack.push(root);
	while (!stack.empty())
	{
		const btDbvtNode* node = stack.pop();
		policy.Process(node);
		if (node->isinternal())
		{
			stack.push(node->childs[1]);  // pushed first so that childs[0]'s subtree comes first
			stack.push(node->childs[0]);
		}
	}
}

DBVT_PREFIX
inline void btDbvt::enumLeaves(const btDbvtNode* root, DBVT_IPOLICY)
{
	if (!root) return;
	caliber::DbvtLocalStack<const btDbvtNode*, 128> stack;
	stack.push(root);
	while (!stack.empty())
	{
		const btDbvtNode* node = stack.pop();
		if (node->isinternal())
		{
			stack.push(node->childs[1]);
			stack.push(node->childs[0]);
		}
		else
			policy.Process(node);
	}
}

DBVT_PREFIX
inline void btDbvt::collideTT(const btDbvtNode* root0, const btDbvtNode* root1, DBVT_IPOLICY)
{
	if (!root0 || !root1) return;
	m_stkStack.resizeNoInitialize(0);
	m_stkStack.push_back(sStkNN(root0, root1));
	while (m_stkStack.size() > 0)
	{
		const sStkNN pair = m_stkStack[m_stkStack.size() - 1];
		m_stkStack.pop_back();
		const btDbvtNode* a = pair.a;
		const btDbvtNode* b = pair.b;
		if (a == b)
		{
			// A subtree against itself: its two halves against themselves and against each other, so
			// that every unordered pair of distinct leaves is met exactly once.
			if (a->isinternal())
			{
				m_stkStack.push_back(sStkNN(a->childs[0], a->childs[0]));
				m_stkStack.push_back(sStkNN(a->childs[1], a->childs[1]));
				m_stkStack.push_back(sStkNN(a->childs[0], a->childs[1]));
			}
			continue;
		}
		if (!Intersect(a->volume, b->volume)) continue;
		const bool aInternal = a->isinternal();
		const bool bInternal = b->isinternal();
		if (!aInternal && !bInternal)
		{
			policy.Process(a, b);
			continue;
		}
		// Open the bigger box (fewer pairs reach the leaves than when opening both).
		bool openA = aInternal;
		if (aInternal && bInternal)
		{
			const btVector3 la = a->volume.Lengths(), lb = b->volume.Lengths();
			openA = la.x() + la.y() + la.z() >= lb.x() + lb.y() + lb.z();
		}
		if (openA)
		{
			m_stkStack.push_back(sStkNN(a->childs[0], b));
			m_stkStack.push_back(sStkNN(a->childs[1], b));
		}
		else
		{
			m_stkStack.push_back(sStkNN(a, b->childs[0]));
			m_stkStack.push_back(sStkNN(a, b->childs[1]));
		}
	}
}

DBVT_PREFIX
inline void btDbvt::collideTTpersistentStack(const btDbvtNode* root0, const btDbvtNode* root1, DBVT_IPOLICY)
{
	collideTT(root0, root1, policy);
}

DBVT_PREFIX
inline void btDbvt::collideTVNoStackAlloc(const btDbvtNode* root, const btDbvtVolume& volume, btNodeStack& stack,
                                          DBVT_IPOLICY) const
{
	if (!root) return;
	stack.resizeNoInitialize(0);
	stack.push_back(root);
	while (stack.size() > 0)
	{
		const btDbvtNode* node = stack[stack.size() - 1];
		stack.pop_back();
		if (!Intersect(node->volume, volume)) continue;
		if (node->isinternal())
		{
			stack.push_back(node->childs[0]);
			stack.push_back(node->childs[1]);
		}
		else
			policy.Process(node);
	}
}

DBVT_PREFIX
inline void btDbvt::collideTV(const btDbvtNode* root, const btDbvtVolume& volume, DBVT_IPOLICY) const
{
	if (!root) return;
	caliber::DbvtLocalStack<const btDbvtNode*, 128> stack;
	stack.push(root);
	while (!stack.empty())
	{
		const btDbvtNode* node = stack.pop();
		if (!Intersect(node->volume, volume)) continue;
		if (node->isinternal())
		{
			stack.push(node->childs[0]);
			stack.push(node->childs[1]);
		}
		else
			policy.Process(node);
	}
}

DBVT_PREFIX
inline void btDbvt::rayTest(const btDbvtNode* root, const btVector3& rayFrom, const btVector3& rayTo, DBVT_IPOLICY)
{
	if (!root) return;
	const btVector3 segment = rayTo - rayFrom;
	const bool finite = btIsFinite(rayFrom.x()) && btIsFinite(rayFrom.y()) && btIsFinite(rayFrom.z()) &&
	                    btIsFinite(segment.x()) && btIsFinite(segment.y()) && btIsFinite(segment.z());
	btAssert(finite && "btDbvt::rayTest: non-finite ray");
	if (!finite) return;
	// Parametrise the segment by its length along a unit direction; a zero component of the direction
	// gets a large finite inverse (never infinity, so that no 0 * inf appears in the slab test).
	btScalar length = segment.length();
	btVector3 direction = length > btScalar(0) ? segment / length : btVector3(1, 0, 0);
	if (!(length > btScalar(0))) length = btScalar(0);
	btVector3 inverse;
	unsigned int signs[3];
	for (int axis = 0; axis < 3; ++axis)
	{
		inverse[axis] = direction[axis] == btScalar(0) ? btScalar(BT_LARGE_FLOAT) : btScalar(1) / direction[axis];
		signs[axis] = inverse[axis] < btScalar(0) ? 1u : 0u;
	}
	caliber::DbvtLocalStack<const btDbvtNode*, 128> stack;
	stack.push(root);
	while (!stack.empty())
	{
		const btDbvtNode* node = stack.pop();
		const btVector3 bounds[2] = {node->volume.Mins(), node->volume.Maxs()};
		btScalar tmin;
		if (length == btScalar(0))
		{
			if (!Intersect(node->volume, rayFrom)) continue;
		}
		else if (!btRayAabb2(rayFrom, inverse, signs, bounds, tmin, btScalar(0), length))
			continue;
		if (node->isinternal())
		{
			stack.push(node->childs[0]);
			stack.push(node->childs[1]);
		}
		else
			policy.Process(node);
	}
}

DBVT_PREFIX
inline void btDbvt::rayTestInternal(const btDbvtNode* root, const btVector3& rayFrom, const btVector3& /*rayTo*/,
                                    const btVector3& rayDirectionInverse, unsigned int signs[3], btScalar lambda_max,
                                    const btVector3& aabbMin, const btVector3& aabbMax,
                                    btAlignedObjectArray<const btDbvtNode*>& stack, DBVT_IPOLICY) const
{
	if (!root) return;
	stack.resizeNoInitialize(0);
	stack.push_back(root);
	while (stack.size() > 0)
	{
		const btDbvtNode* node = stack[stack.size() - 1];
		stack.pop_back();
		// Growing the node by the swept box turns the box-cast into a ray cast.
		const btVector3 bounds[2] = {node->volume.Mins() - aabbMax, node->volume.Maxs() - aabbMin};
		btScalar tmin;
		if (!btRayAabb2(rayFrom, rayDirectionInverse, signs, bounds, tmin, btScalar(0), lambda_max)) continue;
		if (node->isinternal())
		{
			stack.push_back(node->childs[0]);
			stack.push_back(node->childs[1]);
		}
		else
			policy.Process(node);
	}
}

DBVT_PREFIX
inline void btDbvt::collideKDOP(const btDbvtNode* root, const btVector3* normals, const btScalar* offsets, int count,
                                DBVT_IPOLICY)
{
	if (!root) return;
	btAssert(count >= 0 && count <= 32 && "btDbvt::collideKDOP: 0..32 planes");
	if (count > 32) count = 32;
	if (count < 0) count = 0;
	int signs[32];
	for (int i = 0; i < count; ++i)
		signs[i] = (normals[i].x() >= 0 ? 1 : 0) + (normals[i].y() >= 0 ? 2 : 0) + (normals[i].z() >= 0 ? 4 : 0);
	const unsigned allInside = count == 32 ? ~0u : ((1u << count) - 1u);
	caliber::DbvtLocalStack<sStkNP, 128> stack;
	stack.push(sStkNP(root, 0u));
	while (!stack.empty())
	{
		const sStkNP entry = stack.pop();
		unsigned mask = static_cast<unsigned>(entry.mask);
		bool outside = false;
		for (int i = 0; i < count && mask != allInside; ++i)
		{
			const unsigned bit = 1u << i;
			if (mask & bit) continue;
			const int side = entry.node->volume.Classify(normals[i], offsets[i], signs[i]);
			if (side < 0)
			{
				outside = true;
				break;
			}
			if (side > 0) mask |= bit;
		}
		if (outside) continue;
		if (entry.node->isinternal())
		{
			stack.push(sStkNP(entry.node->childs[0], mask));
			stack.push(sStkNP(entry.node->childs[1], mask));
		}
		else
			policy.Process(entry.node);
	}
}

DBVT_PREFIX
inline void btDbvt::collideOCL(const btDbvtNode* root, const btVector3* normals, const btScalar* offsets,
                               const btVector3& sortaxis, int count, DBVT_IPOLICY, bool fullsort)
{
	if (!root) return;
	btAssert(count >= 0 && count <= 32 && "btDbvt::collideOCL: 0..32 planes");
	if (count > 32) count = 32;
	if (count < 0) count = 0;
	int signs[32];
	for (int i = 0; i < count; ++i)
		signs[i] = (normals[i].x() >= 0 ? 1 : 0) + (normals[i].y() >= 0 ? 2 : 0) + (normals[i].z() >= 0 ? 4 : 0);
	const unsigned sortSigns =
	    (sortaxis.x() >= 0 ? 1u : 0u) + (sortaxis.y() >= 0 ? 2u : 0u) + (sortaxis.z() >= 0 ? 4u : 0u);
	const unsigned allInside = count == 32 ? ~0u : ((1u << count) - 1u);
	// fullsort: a binary min-heap on the sort value (a child never sorts before its parent, so leaves
	// come out in increasing order); otherwise a depth-first stack with the nearer child on top.
	caliber::DbvtLocalStack<sStkNPS, 128> open;
	open.push(sStkNPS(root, 0u, root->volume.ProjectMinimum(sortaxis, sortSigns)));
	while (!open.empty())
	{
		sStkNPS entry;
		if (fullsort)
		{
			entry = open.m_data[0];
			open.m_data[0] = open.m_data[--open.m_size];
			for (int at = 0;;)
			{
				int smallest = at;
				const int left = 2 * at + 1, right = left + 1;
				if (left < open.m_size && open.m_data[left].value < open.m_data[smallest].value) smallest = left;
				if (right < open.m_size && open.m_data[right].value < open.m_data[smallest].value) smallest = right;
				if (smallest == at) break;
				const sStkNPS swap = open.m_data[at];
				open.m_data[at] = open.m_data[smallest];
				open.m_data[smallest] = swap;
				at = smallest;
			}
		}
		else
			entry = open.pop();
		unsigned mask = static_cast<unsigned>(entry.mask);
		bool outside = false;
		for (int i = 0; i < count && mask != allInside; ++i)
		{
			const unsigned bit = 1u << i;
			if (mask & bit) continue;
			const int side = entry.node->volume.Classify(normals[i], offsets[i], signs[i]);
			if (side < 0)
			{
				outside = true;
				break;
			}
			if (side > 0) mask |= bit;
		}
		if (outside || !policy.Descent(entry.node)) continue;
		if (entry.node->isleaf())
		{
			policy.Process(entry.node, entry.value);
			continue;
		}
		sStkNPS children[2];
		for (int c = 0; c < 2; ++c)
		{
			const btDbvtNode* child = entry.node->childs[c];
			children[c] = sStkNPS(child, mask, child->volume.ProjectMinimum(sortaxis, sortSigns));
		}
		if (fullsort)
		{
			for (int c = 0; c < 2; ++c)
			{
				open.push(children[c]);
				for (int at = open.m_size - 1; at > 0;)
				{
					const int up = (at - 1) / 2;
					if (!(open.m_data[at].value < open.m_data[up].value)) break;
					const sStkNPS swap = open.m_data[at];
					open.m_data[at] = open.m_data[up];
					open.m_data[up] = swap;
					at = up;
				}
			}
		}
		else
		{
			const int nearer = children[1].value < children[0].value ? 1 : 0;
			open.push(children[1 - nearer]);
			open.push(children[nearer]);
		}
	}
}

DBVT_PREFIX
inline void btDbvt::collideTU(const btDbvtNode* root, DBVT_IPOLICY)
{
	if (!root) return;
	caliber::DbvtLocalStack<const btDbvtNode*, 128> stack;
	stack.push(root);
	while (!stack.empty())
	{
		const btDbvtNode* node = stack.pop();
		if (!policy.Descent(node)) continue;
		if (node->isinternal())
		{
			stack.push(node->childs[1]);
			stack.push(node->childs[0]);
		}
		else
			policy.Process(node);
	}
}

#endif  // BT_DBVT_QUERIES_H
