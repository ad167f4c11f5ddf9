// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btSoftBody::refine: new nodes where an implicit function changes sign along the links and face edges,
// the faces split to match, and optionally the body cut in two along the function's zero set.
//
// The work is done on node indices (links and faces hold pointers into m_nodes, which may move while
// nodes are appended): the new links and faces are planned first, then the arrays are rebuilt.

#include <map>
#include <utility>
#include <vector>

#include "BulletSoftBody/btSoftBody.h"
#include "btSoftBodyInternal.h"

using caliber::softBodyWarning;

namespace
{
// Bisection on ifn along a -> b for the crossing (the sides differ at the ends); the result is within
// accuracy (a fraction of the segment) of the crossing, for any function continuous along the segment.
btScalar findCrossing(btSoftBody::ImplicitFn* ifn, const btVector3& a, const btVector3& b, bool sideA,
                      btScalar accuracy)
{
	btScalar lo = 0, hi = 1;
	for (int i = 0; i < 64 && hi - lo > accuracy; ++i)
	{
		const btScalar mid = (lo + hi) / 2;
		const btScalar f = ifn->Eval(a.lerp(b, mid));
		// A non-finite value counts as the far side: the bisection still ends inside the segment.
		if (btIsFinite(f) && (f > 0) == sideA)
			lo = mid;
		else
			hi = mid;
	}
	return (lo + hi) / 2;
}

struct PlannedLink
{
	int a, b;
	int model;  // the link it comes from (material, bending flag), -1 for links across a split face
	btSoftBody::Material* material;
	btScalar restLength;  // < 0: the current distance
};

struct PlannedFace
{
	int n[3];
	int model;  // the face it comes from
};
}  // namespace

void btSoftBody::refine(ImplicitFn* ifn, btScalar accurary, bool cut)
{
	btAssert(ifn && "btSoftBody::refine: null implicit function");
	if (!ifn)
	{
		softBodyWarning("Caliber: btSoftBody::refine: null implicit function; nothing done\n");
		return;
	}
	const bool goodAccuracy = btIsFinite(accurary) && accurary > 0 && accurary < 1;
	btAssert(goodAccuracy && "btSoftBody::refine: accuracy must lie in (0, 1)");
	if (!goodAccuracy)
	{
		softBodyWarning("Caliber: btSoftBody::refine: accuracy not in (0, 1); 0.0001 used\n");
		accurary = btScalar(0.0001);
	}
	if (m_tetras.size() > 0 || m_clusters.size() > 0)
	{
		btAssert(false && "btSoftBody::refine: bodies with tetras or clusters cannot be refined");
		softBodyWarning("Caliber: btSoftBody::refine: the body has tetras or clusters; nothing done\n");
		return;
	}
	const int nodeCount = m_nodes.size();
	if (nodeCount == 0) return;
	std::vector<char> side(size_t(nodeCount), 0);
	for (int i = 0; i < nodeCount; ++i)
	{
		const btScalar f = ifn->Eval(m_nodes[i].m_x);
		if (!btIsFinite(f))
		{
			btAssert(false && "btSoftBody::refine: the implicit function is not finite at a node");
			softBodyWarning("Caliber: btSoftBody::refine: the implicit function is not finite at a node; nothing done\n");
			return;
		}
		side[size_t(i)] = f > 0;
	}
	const btScalar massBefore = getTotalMass();
	Node* base = &m_nodes[0];
	auto index = [base](const Node* n) { return int(n - base); };

	// The new nodes: one per crossing edge (face edges; for bodies without faces, links), planned first.
	struct NewNode
	{
		int a, b;
		btScalar t;
	};
	std::vector<NewNode> added;
	std::map<std::pair<int, int>, int> onEdge;  // (low, high) node indices -> the new node's index
	auto splitEdge = [&](int a, int b) -> int
	{
		const std::pair<int, int> key(btMin(a, b), btMax(a, b));
		const auto it = onEdge.find(key);
		if (it != onEdge.end()) return it->second;
		const NewNode n = {key.first, key.second,
		                   findCrossing(ifn, m_nodes[key.first].m_x, m_nodes[key.second].m_x, side[size_t(key.first)] != 0,
		                                accurary)};
		added.push_back(n);
		const int id = nodeCount + int(added.size()) - 1;
		onEdge[key] = id;
		return id;
	};
	auto crosses = [&side](int a, int b) { return side[size_t(a)] != side[size_t(b)]; };
	auto newNodeT = [&](int a, int p)
	{
		// The crossing's parameter from a towards b.
		const NewNode& n = added[size_t(p - nodeCount)];
		return n.a == a ? n.t : 1 - n.t;
	};

	std::vector<PlannedFace> faces;
	std::vector<PlannedLink> links;
	for (int i = 0; i < m_faces.size(); ++i)
	{
		const Face& f = m_faces[i];
		const int n[3] = {index(f.m_n[0]), index(f.m_n[1]), index(f.m_n[2])};
		// With two sides, a face has no crossing edge or exactly two, meeting at the lone node.
		int lone = -1;
		for (int k = 0; k < 3; ++k)
			if (crosses(n[k], n[(k + 1) % 3]) && crosses(n[k], n[(k + 2) % 3])) lone = k;
		if (lone < 0)
		{
			faces.push_back({{n[0], n[1], n[2]}, i});
			continue;
		}
		const int a = n[lone], b = n[(lone + 1) % 3], c = n[(lone + 2) % 3];
		const int p = splitEdge(a, b), q = splitEdge(a, c);
		// a p b c q is the face's outline in its own order: one triangle at a, the quad split along p-c.
		faces.push_back({{a, p, q}, i});
		faces.push_back({{p, b, c}, i});
		faces.push_back({{p, c, q}, i});
		Material* mat = f.m_material;
		links.push_back({p, q, -1, mat, -1});
		links.push_back({p, c, -1, mat, -1});
	}
	const bool hasFaces = m_faces.size() > 0;
	for (int i = 0; i < m_links.size(); ++i)
	{
		const Link& l = m_links[i];
		const int a = index(l.m_n[0]), b = index(l.m_n[1]);
		if (!crosses(a, b))
		{
			links.push_back({a, b, i, l.m_material, l.m_rl});
			continue;
		}
		const bool edge = onEdge.count(std::make_pair(btMin(a, b), btMax(a, b))) > 0;
		if (hasFaces && !edge)
		{
			// A link across the set that is no face edge (bending): kept whole, or dropped by the cut.
			if (!cut) links.push_back({a, b, i, l.m_material, l.m_rl});
			continue;
		}
		const int p = splitEdge(a, b);
		const btScalar t = newNodeT(a, p);
		links.push_back({a, p, i, l.m_material, l.m_rl * t});
		links.push_back({p, b, i, l.m_material, l.m_rl * (1 - t)});
	}
	if (added.empty()) return;

	// With cut, each new node gets a twin: the new node serves the positive side, its twin the other.
	const int newCount = int(added.size());
	auto twin = [&](int p) { return p + newCount; };
	if (cut)
	{
		auto sideOf = [&](const int* n, int count) -> int
		{
			for (int k = 0; k < count; ++k)
				if (n[k] < nodeCount) return side[size_t(n[k])];
			return -1;
		};
		const size_t linkCount = links.size();
		for (size_t i = 0; i < linkCount; ++i)
		{
			PlannedLink& l = links[i];
			int n[2] = {l.a, l.b};
			const int s = sideOf(n, 2);
			if (s < 0)
			{
				// Both ends on the cut (a link along it): one copy for each side.
				PlannedLink copy = l;
				copy.a = twin(l.a);
				copy.b = twin(l.b);
				links.push_back(copy);
				continue;
			}
			if (s == 0)
			{
				if (l.a >= nodeCount) l.a = twin(l.a);
				if (l.b >= nodeCount) l.b = twin(l.b);
			}
		}
		for (PlannedFace& f : faces)
		{
			if (sideOf(f.n, 3) != 0) continue;
			for (int k = 0; k < 3; ++k)
				if (f.n[k] >= nodeCount) f.n[k] = twin(f.n[k]);
		}
	}

	// Append the nodes (appendNode keeps the existing pointers valid), then rebuild links and faces.
	for (int pass = 0; pass < (cut ? 2 : 1); ++pass)
		for (const NewNode& n : added)
		{
			const Node& a = m_nodes[n.a];
			const Node& b = m_nodes[n.b];
			const btScalar ma = a.m_im > 0 ? 1 / a.m_im : 0, mb = b.m_im > 0 ? 1 / b.m_im : 0;
			btScalar m = (ma > 0 && mb > 0) ? ma + (mb - ma) * n.t : btMax(ma, mb);
			if (cut) m /= 2;
			const btVector3 x = a.m_x.lerp(b.m_x, n.t), q = a.m_q.lerp(b.m_q, n.t), v = a.m_v.lerp(b.m_v, n.t);
			Material* mat = a.m_material;
			appendNode(x, m);
			Node& made = m_nodes[m_nodes.size() - 1];
			made.m_q = q;
			made.m_v = v;
			made.m_material = mat;
		}
	m_rcontacts.resize(0);
	m_scontacts.resize(0);
	base = &m_nodes[0];
	btAlignedObjectArray<Link> newLinks;
	newLinks.reserve(int(links.size()));
	for (const PlannedLink& pl : links)
	{
		Link l;
		if (pl.model >= 0)
			l = m_links[pl.model];
		else
		{
			l.m_tag = 0;
			l.m_bbending = 0;
			l.m_c0 = l.m_c1 = l.m_c2 = 0;
			l.m_c3.setValue(0, 0, 0);
		}
		l.m_material = pl.material;
		l.m_n[0] = base + pl.a;
		l.m_n[1] = base + pl.b;
		l.m_rl = pl.restLength >= 0 ? pl.restLength : (l.m_n[0]->m_x - l.m_n[1]->m_x).length();
		l.m_c1 = l.m_rl * l.m_rl;
		newLinks.push_back(l);
	}
	m_links = newLinks;
	btAlignedObjectArray<Face> newFaces;
	newFaces.reserve(int(faces.size()));
	for (const PlannedFace& pf : faces)
	{
		Face f = m_faces[pf.model];
		for (int k = 0; k < 3; ++k) f.m_n[k] = base + pf.n[k];
		f.m_index = newFaces.size();
		f.m_leaf = 0;
		f.m_ra = btScalar(0.5) * (f.m_n[1]->m_x - f.m_n[0]->m_x).cross(f.m_n[2]->m_x - f.m_n[0]->m_x).length();
		newFaces.push_back(f);
	}
	m_faces = newFaces;
	// The new nodes took their mass from the interpolation: scale the free nodes back to the old total.
	const btScalar massAfter = getTotalMass();
	if (massBefore > 0 && massAfter > 0)
	{
		const btScalar scale = massAfter / massBefore;  // inverse masses scale the other way
		for (int i = 0; i < m_nodes.size(); ++i) m_nodes[i].m_im *= scale;
	}
	if (m_pose.m_bframe || m_pose.m_bvolume) setPose(m_pose.m_bvolume, m_pose.m_bframe);
	m_bUpdateRtCst = true;
	updateNormals();
	updateBounds();
}
