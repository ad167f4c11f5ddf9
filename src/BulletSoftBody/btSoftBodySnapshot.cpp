// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// caliber::saveSoftWorldState / restoreSoftWorldState / compareSoftWorldState (include/Caliber/
// SoftWorldSnapshot.h; docs/serialization.md, "Soft bodies in snapshots"): the rigid world's snapshot
// (btWorldSnapshot.cpp) with an extension that lets soft bodies and their stateless collision algorithms
// in and appends each soft body's state. Each soft body starts with its topology (counts and indices),
// which a restore compares with the live body before anything is written.

#include "Caliber/SoftWorldSnapshot.h"

#include <typeinfo>

#include "BulletDynamics/Dynamics/btWorldSnapshotInternal.h"
#include "BulletSoftBody/btSoftBody.h"
#include "BulletSoftBody/btSoftBodyTethers.h"
#include "BulletSoftBody/btSoftRigidCollisionAlgorithm.h"
#include "BulletSoftBody/btSoftRigidDynamicsWorld.h"
#include "BulletSoftBody/btSoftSoftCollisionAlgorithm.h"

namespace caliber
{
namespace
{
using caliber::SnapshotReader;
using caliber::SnapshotWriter;

// Joint sides and other references are written as indices (the snapshot holds no addresses).
int objectIndexOf(const btCollisionWorld& world, const btCollisionObject* object)
{
	if (!object) return -1;
	const int i = object->getWorldArrayIndex();
	return i >= 0 && i < world.getNumCollisionObjects() && world.getCollisionObjectArray()[i] == object ? i : -2;
}

int nodeIndexOf(const btSoftBody& body, const btSoftBody::Node* node)
{
	return node && body.m_nodes.size() ? int(node - &body.m_nodes[0]) : -1;
}

// A joint side: kind (0 world, 1 cluster, 2 collision object) and index (the cluster's soft body index in the
// world's soft body array times 2^16 plus the cluster index, or the object's index).
void sideOf(const btSoftRigidDynamicsWorld& world, const btSoftBody::Body& side, int& kind, int& index)
{
	kind = 0;
	index = -1;
	if (side.m_soft)
	{
		kind = 1;
		const btSoftBodyArray& bodies = world.getSoftBodyArray();
		for (int b = 0; b < bodies.size() && index < 0; ++b)
		{
			const int c = bodies[b]->m_clusters.findLinearSearch(side.m_soft);
			if (c < bodies[b]->m_clusters.size()) index = b * 65536 + c;
		}
	}
	else if (side.m_collisionObject || side.m_rigid)
	{
		kind = 2;
		index = objectIndexOf(world, side.m_collisionObject ? side.m_collisionObject : side.m_rigid);
	}
}

// The topology of a body: what a restore requires to be unchanged. Written as a list of ints; the reader
// compares it with the live body's.
void topologyOf(const btSoftRigidDynamicsWorld& world, const btSoftBody& b, btAlignedObjectArray<int>& t)
{
	t.resize(0);
	t.push_back(objectIndexOf(world, &b));
	t.push_back(b.m_nodes.size());
	t.push_back(b.m_links.size());
	t.push_back(b.m_faces.size());
	t.push_back(b.m_tetras.size());
	t.push_back(b.m_anchors.size());
	t.push_back(b.m_clusters.size());
	t.push_back(b.m_joints.size());
	for (int i = 0; i < b.m_links.size(); ++i)
		for (int j = 0; j < 2; ++j) t.push_back(nodeIndexOf(b, b.m_links[i].m_n[j]));
	for (int i = 0; i < b.m_faces.size(); ++i)
		for (int j = 0; j < 3; ++j) t.push_back(nodeIndexOf(b, b.m_faces[i].m_n[j]));
	for (int i = 0; i < b.m_tetras.size(); ++i)
		for (int j = 0; j < 4; ++j) t.push_back(nodeIndexOf(b, b.m_tetras[i].m_n[j]));
	for (int i = 0; i < b.m_anchors.size(); ++i)
	{
		t.push_back(nodeIndexOf(b, b.m_anchors[i].m_node));
		t.push_back(objectIndexOf(world, b.m_anchors[i].m_body));
	}
	for (int i = 0; i < b.m_clusters.size(); ++i)
	{
		const btSoftBody::Cluster& c = *b.m_clusters[i];
		t.push_back(c.m_nodes.size());
		for (int j = 0; j < c.m_nodes.size(); ++j) t.push_back(nodeIndexOf(b, c.m_nodes[j]));
	}
	for (int i = 0; i < b.m_joints.size(); ++i)
	{
		const btSoftBody::Joint& j = *b.m_joints[i];
		t.push_back(int(j.Type()));
		for (int s = 0; s < 2; ++s)
		{
			int kind, index;
			sideOf(world, j.m_bodies[s], kind, index);
			t.push_back(kind);
			t.push_back(index);
		}
	}
}

// The state a step leaves for the next (the settings, masses, rest shapes and topology are the user's).
template <class IO>
void bodyFields(IO& io, btSoftBody& b)
{
	io.field("m_bounds[0]", b.m_bounds[0]);
	io.field("m_bounds[1]", b.m_bounds[1]);
	io.field("m_bUpdateRtCst", b.m_bUpdateRtCst);
	io.field("m_timeacc", b.m_timeacc);
	io.field("m_sst.sdt", b.m_sst.sdt);
	io.field("m_sst.isdt", b.m_sst.isdt);
	io.field("m_sst.velmrg", b.m_sst.velmrg);
	io.field("m_sst.radmrg", b.m_sst.radmrg);
	io.field("m_sst.updmrg", b.m_sst.updmrg);
	io.field("m_pose.m_com", b.m_pose.m_com);
	io.field("m_pose.m_rot", b.m_pose.m_rot);
	io.field("m_pose.m_scl", b.m_pose.m_scl);
	for (int i = 0; i < b.m_nodes.size(); ++i)
	{
		btSoftBody::Node& n = b.m_nodes[i];
		io.field("node m_x", n.m_x);
		io.field("node m_q", n.m_q);
		io.field("node m_v", n.m_v);
		io.field("node m_vn", n.m_vn);
		io.field("node m_f", n.m_f);
		io.field("node m_n", n.m_n);
		io.field("node m_area", n.m_area);
	}
	for (int i = 0; i < b.m_links.size(); ++i)
	{
		btSoftBody::Link& l = b.m_links[i];
		io.field("link m_c0", l.m_c0);
		io.field("link m_c1", l.m_c1);
		io.field("link m_c2", l.m_c2);
		io.field("link m_c3", l.m_c3);
	}
	for (int i = 0; i < b.m_faces.size(); ++i)
	{
		io.field("face m_normal", b.m_faces[i].m_normal);
		io.field("face m_ra", b.m_faces[i].m_ra);
	}
	for (int i = 0; i < b.m_tetras.size(); ++i)
	{
		btSoftBody::Tetra& t = b.m_tetras[i];
		for (int j = 0; j < 4; ++j) io.field("tetra m_c0", t.m_c0[j]);
		io.field("tetra m_c1", t.m_c1);
		io.field("tetra m_c2", t.m_c2);
	}
	for (int i = 0; i < b.m_anchors.size(); ++i)
	{
		btSoftBody::Anchor& a = b.m_anchors[i];
		io.field("anchor m_c0", a.m_c0);
		io.field("anchor m_c1", a.m_c1);
		io.field("anchor m_c2", a.m_c2);
	}
	for (int i = 0; i < b.m_clusters.size(); ++i)
	{
		btSoftBody::Cluster& c = *b.m_clusters[i];
		io.field("cluster m_framexform", c.m_framexform);
		io.field("cluster m_com", c.m_com);
		io.field("cluster m_invwi", c.m_invwi);
		io.field("cluster m_lv", c.m_lv);
		io.field("cluster m_av", c.m_av);
		for (int j = 0; j < 2; ++j)
		{
			io.field("cluster m_vimpulses", c.m_vimpulses[j]);
			io.field("cluster m_dimpulses", c.m_dimpulses[j]);
		}
		io.field("cluster m_nvimpulses", c.m_nvimpulses);
		io.field("cluster m_ndimpulses", c.m_ndimpulses);
	}
	for (int i = 0; i < b.m_joints.size(); ++i)
	{
		btSoftBody::Joint& j = *b.m_joints[i];
		io.field("joint m_drift", j.m_drift);
		io.field("joint m_sdrift", j.m_sdrift);
		io.field("joint m_massmatrix", j.m_massmatrix);
		io.field("joint m_delete", j.m_delete);
		if (j.Type() == btSoftBody::Joint::eType::Linear)
		{
			btSoftBody::LJoint& l = static_cast<btSoftBody::LJoint&>(j);
			io.field("joint m_rpos[0]", l.m_rpos[0]);
			io.field("joint m_rpos[1]", l.m_rpos[1]);
		}
		else if (j.Type() == btSoftBody::Joint::eType::Angular)
		{
			btSoftBody::AJoint& a = static_cast<btSoftBody::AJoint&>(j);
			io.field("joint m_axis[0]", a.m_axis[0]);
			io.field("joint m_axis[1]", a.m_axis[1]);
		}
		else
		{
			btSoftBody::CJoint& c = static_cast<btSoftBody::CJoint&>(j);
			io.field("joint m_life", c.m_life);
			io.field("joint m_rpos[0]", c.m_rpos[0]);
			io.field("joint m_rpos[1]", c.m_rpos[1]);
			io.field("joint m_normal", c.m_normal);
		}
	}
}

// The tethers and the skin's rest volume: a cache built from the shape when the topology, fixed nodes or
// rest lengths change, whose rest volume depends on the shape at that moment (a fresh world would build
// it from the restored, deformed shape). Reading it on save builds it if the body never stepped, as the
// next step would from the same shape.
void saveTethers(SnapshotWriter& out, btSoftBody& b)
{
	SoftBodyTethers& t = softBodyTethers(b, false);
	out.field("tethers inextensibleSkin", t.inextensibleSkin);
	out.field("tethers restVolume", t.restVolume);
	out.field("tethers nodeCount", t.nodeCount);
	out.field("tethers linkCount", t.linkCount);
	out.field("tethers signature", t.signature);
	out.field("tether count", t.tethers.size());
	for (int i = 0; i < t.tethers.size(); ++i)
	{
		out.field("tether node", t.tethers[i].node);
		out.field("tether anchor", t.tethers[i].anchor);
		out.field("tether reach", t.tethers[i].reach);
	}
}

void readTethers(SnapshotReader& in, btSoftBody& b, int index)
{
	SoftBodyTethers saved;
	saved.inextensibleSkin = in.flag("tethers inextensibleSkin");
	saved.restVolume = in.scalar("tethers restVolume");
	saved.nodeCount = in.value<int>("tethers nodeCount");
	saved.linkCount = in.value<int>("tethers linkCount");
	saved.signature = in.value<unsigned>("tethers signature");
	const int n = b.m_nodes.size();
	const int count = in.count("tether count", n);
	for (int i = 0; i < count && in.ok(); ++i)
	{
		SoftBodyTethers::Tether tether;
		tether.node = in.value<int>("tether node");
		tether.anchor = in.value<int>("tether anchor");
		tether.reach = in.scalar("tether reach");
		if (in.ok() && (tether.node < 0 || tether.node >= n || tether.anchor < 0 || tether.anchor >= n))
			in.fail("soft body %d: tether %d joins nodes %d and %d of %d", index, i, tether.node, tether.anchor, n);
		saved.tethers.push_back(tether);
	}
	if (in.ok() && (saved.nodeCount != n || saved.linkCount != b.m_links.size()))
		in.fail("soft body %d: its tethers were built for %d nodes and %d links, the body has %d and %d", index,
		        saved.nodeCount, saved.linkCount, n, b.m_links.size());
	if (in.ok() && in.applying()) softBodyTethers(b, false) = saved;
}

btSoftRigidDynamicsWorld* softWorldOf(btDiscreteDynamicsWorld& world)
{
	return world.getWorldType() == BT_SOFT_RIGID_DYNAMICS_WORLD ? static_cast<btSoftRigidDynamicsWorld*>(&world) : 0;
}

bool acceptsObject(const btCollisionObject& object)
{
	// Bullet's class exactly (a subclass may keep more state), and only bodies the world steps as soft
	// bodies (checked in save).
	return object.getInternalType() == btCollisionObject::CO_SOFT_BODY && typeid(object) == typeid(btSoftBody);
}

bool statelessAlgorithm(const btCollisionAlgorithm* algorithm)
{
	// Both find their contacts afresh each step (the soft body keeps them, cleared in predictMotion).
	const std::type_info& type = typeid(*algorithm);
	return type == typeid(btSoftRigidCollisionAlgorithm) || type == typeid(btSoftSoftCollisionAlgorithm);
}

bool saveSoft(btDiscreteDynamicsWorld& base, SnapshotWriter& out, char* error, size_t errorSize)
{
	btSoftRigidDynamicsWorld* world = softWorldOf(base);
	if (!world)
	{
		snprintf(error, errorSize, "world: not a btSoftRigidDynamicsWorld");
		return false;
	}
	const btSoftBodyArray& bodies = world->getSoftBodyArray();
	int softObjects = 0;
	for (int i = 0; i < world->getNumCollisionObjects(); ++i)
		if (world->getCollisionObjectArray()[i]->getInternalType() == btCollisionObject::CO_SOFT_BODY) ++softObjects;
	if (softObjects != bodies.size())
	{
		snprintf(error, errorSize, "world: %d soft collision objects, %d soft bodies (one added as a plain object?)",
		         softObjects, bodies.size());
		return false;
	}
	out.context("soft bodies", -1);
	out.field("soft body count", bodies.size());
	btAlignedObjectArray<int> topology;
	for (int i = 0; i < bodies.size(); ++i)
	{
		btSoftBody& b = *bodies[i];
		out.context("soft body", i);
		topologyOf(*world, b, topology);
		for (int k = 0; k < topology.size(); ++k)
			if (topology[k] == -2)
			{
				snprintf(error, errorSize, "soft body %d: an anchor or joint names an object outside the world", i);
				return false;
			}
		out.field("topology size", topology.size());
		if (topology.size()) out.bytes("topology", &topology[0], sizeof(int) * size_t(topology.size()));
		bodyFields(out, b);
		saveTethers(out, b);
	}
	return true;
}

void readSoft(btDiscreteDynamicsWorld& base, SnapshotReader& in)
{
	btSoftRigidDynamicsWorld* world = softWorldOf(base);
	if (!world)
	{
		in.fail("world: not a btSoftRigidDynamicsWorld");
		return;
	}
	const btSoftBodyArray& bodies = world->getSoftBodyArray();
	const int count = in.value<int>("soft body count");
	if (in.ok() && count != bodies.size()) in.fail("world: %d soft bodies, the snapshot has %d", bodies.size(), count);
	btAlignedObjectArray<int> live, saved;
	for (int i = 0; i < bodies.size() && in.ok(); ++i)
	{
		btSoftBody& b = *bodies[i];
		topologyOf(*world, b, live);
		const int size = in.value<int>("topology size");
		if (in.ok() && size != live.size())
		{
			in.fail(
			    "soft body %d: its topology changed (%d nodes, %d links, %d faces, %d tetras, %d anchors, %d "
			    "clusters, %d joints; the snapshot's differs)",
			    i, b.m_nodes.size(), b.m_links.size(), b.m_faces.size(), b.m_tetras.size(), b.m_anchors.size(),
			    b.m_clusters.size(), b.m_joints.size());
			return;
		}
		saved.resize(size);
		if (size && !in.bytes("topology", &saved[0], sizeof(int) * size_t(size))) return;
		for (int k = 0; k < size; ++k)
			if (saved[k] != live[k])
			{
				in.fail(
				    "soft body %d: its topology changed (entry %d is %d, the snapshot's %d: other nodes, links, "
				    "faces, tetras, anchors, clusters or joints)",
				    i, k, live[k], saved[k]);
				return;
			}
		bodyFields(in, b);
		readTethers(in, b, i);
	}
}

const snapshot::SnapshotExtension kSoftExtension = {acceptsObject, statelessAlgorithm, saveSoft, readSoft};
}  // namespace

bool saveSoftWorldState(const btSoftRigidDynamicsWorld& world, btAlignedObjectArray<unsigned char>& buffer,
                        SnapshotError* error)
{
	return saveWorldStateWith(world, buffer, error, &kSoftExtension);
}

bool restoreSoftWorldState(btSoftRigidDynamicsWorld& world, const unsigned char* data, size_t size,
                           SnapshotError* error)
{
	return restoreWorldStateWith(world, data, size, error, &kSoftExtension);
}

bool compareSoftWorldState(const btSoftRigidDynamicsWorld& world, const unsigned char* data, size_t size,
                           SnapshotDifference* difference, SnapshotError* error)
{
	return compareWorldStateWith(world, data, size, difference, error, &kSoftExtension);
}
}  // namespace caliber
