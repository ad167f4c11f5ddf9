// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The groups of soft bodies whose solves may run at once (btSoftBodySolveGroups.h).

#include "btSoftBodySolveGroups.h"

#include <algorithm>
#include <functional>

#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "btSoftBodyClusters.h"
#include "btSoftBodyFaceContacts.h"

namespace
{
using caliber::SoftSolveGroups;

// A rigid object a solve may write (moved by a contact, anchor or joint, or woken): a rigid body that is
// neither static nor kinematic. Static and kinematic objects are only read.
const void* writtenRigid(const btCollisionObject* object)
{
	const btRigidBody* rb = btRigidBody::upcast(object);
	return rb && !rb->isStaticOrKinematicObject() ? rb : 0;
}

// Lists that body's solve writes object (consecutive repeats, as from a contact list, are listed once).
void addLink(SoftSolveGroups& g, const void* object, int body)
{
	if (!object) return;
	const int n = g.links.size();
	if (n > 0 && g.links[n - 1].object == object && g.links[n - 1].body == body) return;
	SoftSolveGroups::Link link;
	link.object = object;
	link.body = body;
	g.links.push_back(link);
}

// The soft body among the set whose face array holds f; unknown faces (a body outside the set) all map to
// one stand-in, which joins their bodies in one group.
const void* faceOwner(const SoftSolveGroups& g, const btSoftBody::Face* f)
{
	int lo = 0, hi = g.faceRanges.size();
	std::less<const btSoftBody::Face*> before;
	while (lo < hi)
	{
		const int mid = (lo + hi) / 2;
		if (before(f, g.faceRanges[mid].begin))
			hi = mid;
		else if (!before(f, g.faceRanges[mid].end))
			lo = mid + 1;
		else
			return g.faceRanges[mid].body;
	}
	return &g;
}

int findRoot(btAlignedObjectArray<int>& parent, int i)
{
	while (parent[i] != i)
	{
		parent[i] = parent[parent[i]];
		i = parent[i];
	}
	return i;
}

// The bodies' links: what each solve writes besides its own nodes.
void listLinks(btSoftBody* const* bodies, const char* solve, int count, SoftSolveGroups& g)
{
	for (int i = 0; i < count; ++i)
	{
		if (!solve[i]) continue;
		const btSoftBody& b = *bodies[i];
		addLink(g, &b, i);  // others' face contacts and cluster contacts name the body itself
		for (int k = 0; k < b.m_anchors.size(); ++k) addLink(g, writtenRigid(b.m_anchors[k].m_body), i);
		for (int k = 0; k < b.m_rcontacts.size(); ++k) addLink(g, writtenRigid(b.m_rcontacts[k].m_cti.m_colObj), i);
		for (int k = 0; k < b.m_scontacts.size(); ++k) addLink(g, faceOwner(g, b.m_scontacts[k].m_face), i);
		if (b.m_faces.size() > 0)
		{
			const caliber::SoftFaceContacts& fc = caliber::softFaceContacts(b);
			for (int k = 0; k < fc.contacts.size(); ++k) addLink(g, writtenRigid(fc.contacts[k].object), i);
		}
		if (b.m_clusters.size() > 0)
		{
			const caliber::ClusterState& state = caliber::clusterState(b);
			const btSoftBody::Cluster* lastOther = 0;
			for (int k = 0; k < state.contacts.size(); ++k)
			{
				const caliber::ClusterContact& c = state.contacts[k];
				addLink(g, writtenRigid(c.object), i);
				if (c.other && c.other != lastOther)
				{
					lastOther = c.other;
					const btSoftBody* owner = caliber::clusterOwner(c.other);
					addLink(g, owner ? static_cast<const void*>(owner) : &g, i);
				}
			}
		}
		for (int k = 0; k < b.m_joints.size(); ++k)
			for (int side = 0; side < 2; ++side)
			{
				const btSoftBody::Body& jb = b.m_joints[k]->m_bodies[side];
				if (jb.m_soft)
				{
					const btSoftBody* owner = caliber::clusterOwner(jb.m_soft);
					addLink(g, owner ? static_cast<const void*>(owner) : &g, i);
				}
				addLink(g, writtenRigid(jb.m_rigid), i);
			}
	}
}
}  // namespace

void caliber::findSoftSolveGroups(btSoftBody* const* bodies, const char* solve, int count, SoftSolveGroups& g)
{
	// The face arrays of every body of the set (solved or not: a resting body's faces are written by the
	// contacts of the bodies against it), by address, to find whose face a soft-soft contact holds.
	g.faceRanges.resize(0);
	for (int i = 0; i < count; ++i)
		if (bodies[i]->m_faces.size() > 0)
		{
			SoftSolveGroups::FaceRange r;
			r.begin = &bodies[i]->m_faces[0];
			r.end = r.begin + bodies[i]->m_faces.size();
			r.body = bodies[i];
			g.faceRanges.push_back(r);
		}
	if (g.faceRanges.size() > 1)
		std::sort(&g.faceRanges[0], &g.faceRanges[0] + g.faceRanges.size(),
	          [](const SoftSolveGroups::FaceRange& a, const SoftSolveGroups::FaceRange& b) {
		          return std::less<const btSoftBody::Face*>()(a.begin, b.begin);
	          });
	g.links.resize(0);
	listLinks(bodies, solve, count, g);
	// Bodies writing the same object are joined. The links are sorted by address, which differs from run to
	// run, but the groups they give do not (each group is the set of bodies connected through objects).
	if (g.links.size() > 1)
		std::sort(&g.links[0], &g.links[0] + g.links.size(), [](const SoftSolveGroups::Link& a, const SoftSolveGroups::Link& b) {
		return std::less<const void*>()(a.object, b.object);
	});
	g.parent.resize(count);
	for (int i = 0; i < count; ++i) g.parent[i] = i;
	for (int k = 1; k < g.links.size(); ++k)
		if (g.links[k].object == g.links[k - 1].object)
		{
			const int a = findRoot(g.parent, g.links[k].body), b = findRoot(g.parent, g.links[k - 1].body);
			if (a != b) g.parent[btMax(a, b)] = btMin(a, b);  // the root is the group's first body
		}
	// Groups numbered by their first body; each group's bodies in ascending order.
	g.groupOf.resize(count);
	g.counts.resize(0);
	for (int i = 0; i < count; ++i)
	{
		if (!solve[i]) continue;
		const int root = findRoot(g.parent, i);
		if (root == i)
		{
			g.groupOf[i] = g.counts.size();
			g.counts.push_back(0);
		}
		else
			g.groupOf[i] = g.groupOf[root];
		++g.counts[g.groupOf[i]];
	}
	const int groups = g.counts.size();
	g.starts.resize(groups + 1);
	g.starts[0] = 0;
	for (int k = 0; k < groups; ++k)
	{
		g.starts[k + 1] = g.starts[k] + g.counts[k];
		g.counts[k] = g.starts[k];  // now the next free slot of group k
	}
	g.members.resize(g.starts[groups]);
	for (int i = 0; i < count; ++i)
		if (solve[i]) g.members[g.counts[g.groupOf[i]]++] = i;
}
