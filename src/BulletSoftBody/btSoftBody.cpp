// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btSoftBody: construction, topology (nodes, links, faces, tetras, anchors, notes), masses, rigid
// moves and queries. The step is in btSoftBodySolve.cpp, contacts in btSoftBodyCollision.cpp.

#include "BulletSoftBody/btSoftBody.h"

#include <cstdio>

#include "BulletSoftBody/btSoftBodySolvers.h"
#include "btSoftBodyInternal.h"
#include "btSoftBodyClusters.h"
#include "btSoftBodyFaceContacts.h"
#include "btSoftBodyLinkColours.h"
#include "btSoftBodyLinkSweep.h"
#include "btSoftBodyNormals.h"
#include "btSoftBodyTethers.h"

namespace caliber
{
void softBodyWarning(const char* message) { btReportWarning(message); }
}  // namespace caliber

using caliber::softBodyWarning;
using caliber::validIndex;

namespace
{
// Node pointers are stored in links, faces, ... as pointers into m_nodes; before the array may move,
// they are turned into indices (pointersToIndices) and back.
inline btSoftBody::Node* indexAsPointer(int i) { return reinterpret_cast<btSoftBody::Node*>(static_cast<size_t>(i)); }
inline int pointerAsIndex(const btSoftBody::Node* p) { return static_cast<int>(reinterpret_cast<size_t>(p)); }

btScalar tetraVolume(const btVector3& a, const btVector3& b, const btVector3& c, const btVector3& d)
{
	return (b - a).dot((c - a).cross(d - a)) / btScalar(6);
}
}  // namespace

btSoftBody::btSoftBody(btSoftBodyWorldInfo* worldInfo, int node_count, const btVector3* x, const btScalar* m)
    : m_softBodySolver(0), m_worldInfo(worldInfo)
{
	initDefaults();
	btAssert(node_count >= 0 && "btSoftBody: negative node count");
	if (node_count < 0)
	{
		softBodyWarning("Caliber: btSoftBody: negative node count; the body starts empty\n");
		node_count = 0;
	}
	m_nodes.reserve(node_count);
	for (int i = 0; i < node_count; ++i) appendNode(x ? x[i] : btVector3(0, 0, 0), m ? m[i] : btScalar(1));
	updateBounds();
}

btSoftBody::btSoftBody(btSoftBodyWorldInfo* worldInfo) : m_softBodySolver(0), m_worldInfo(worldInfo) { initDefaults(); }

void btSoftBody::initDefaults()
{
	m_internalType = CO_SOFT_BODY;
	m_cfg.aeromodel = eAeroModel::V_Point;
	m_cfg.kVCF = 1;
	m_cfg.kDG = 0;
	m_cfg.kLF = 0;
	m_cfg.kDP = 0;
	m_cfg.kPR = 0;
	m_cfg.kVC = 0;
	m_cfg.kDF = btScalar(0.2);
	m_cfg.kMT = 0;
	m_cfg.kCHR = btScalar(1.0);
	m_cfg.kKHR = btScalar(0.1);
	m_cfg.kSHR = btScalar(1.0);
	m_cfg.kAHR = btScalar(0.7);
	m_cfg.kSRHR_CL = btScalar(0.1);
	m_cfg.kSKHR_CL = 1;
	m_cfg.kSSHR_CL = btScalar(0.5);
	m_cfg.kSR_SPLT_CL = btScalar(0.5);
	m_cfg.kSK_SPLT_CL = btScalar(0.5);
	m_cfg.kSS_SPLT_CL = btScalar(0.5);
	m_cfg.maxvolume = 1;
	m_cfg.timescale = 1;
	m_cfg.viterations = 0;
	m_cfg.piterations = 1;
	m_cfg.diterations = 0;
	m_cfg.citerations = 4;
	m_cfg.collisions = fCollision::Default;
	m_sst.sdt = btScalar(1) / btScalar(60);
	m_sst.isdt = 60;
	m_sst.velmrg = 0;
	m_sst.radmrg = 0;
	m_sst.updmrg = 0;
	m_pose.m_bvolume = false;
	m_pose.m_bframe = false;
	m_pose.m_volume = 0;
	m_pose.m_com.setValue(0, 0, 0);
	m_pose.m_rot.setIdentity();
	m_pose.m_scl.setIdentity();
	m_pose.m_aqq.setIdentity();
	m_tag = 0;
	m_timeacc = 0;
	m_bUpdateRtCst = true;
	m_bounds[0].setValue(0, 0, 0);
	m_bounds[1].setValue(0, 0, 0);
	m_worldTransform.setIdentity();
	m_initialWorldTransform.setIdentity();
	m_windVelocity.setValue(0, 0, 0);
	m_restLengthScale = 1;
	setSolver(eSolverPresets::Positions);
	// The first material: every feature without one of its own uses it.
	if (m_materials.size() == 0)
	{
		Material* pm = appendMaterial();
		pm->m_kLST = 1;
		pm->m_kAST = 1;
		pm->m_kVST = 1;
		pm->m_flags = fMaterial::Default;
	}
	if (!m_collisionShape) m_collisionShape = new caliber::SoftBodyCollisionShape(this);
}

btSoftBody::~btSoftBody()
{
	releaseClusters();
	for (int i = 0; i < m_joints.size(); ++i)
	{
		m_joints[i]->~Joint();
		btAlignedFree(m_joints[i]);
	}
	m_joints.resize(0);
	caliber::releaseClusterState(*this);
	caliber::releaseSoftBodyTethers(*this);
	caliber::releaseSoftLinkColours(*this);
	caliber::releaseSoftLinkSweep(*this);
	caliber::releaseSoftFaceContacts(*this);
	caliber::releaseNodeContactChunks(*this);
	caliber::releaseNodeFaces(*this);
	delete m_collisionShape;
	m_collisionShape = 0;
	for (int i = 0; i < m_materials.size(); ++i) btAlignedFree(m_materials[i]);
}

bool btSoftBody::checkLink(int node0, int node1) const
{
	if (!validIndex(node0, m_nodes.size()) || !validIndex(node1, m_nodes.size())) return false;
	return checkLink(&m_nodes[node0], &m_nodes[node1]);
}

bool btSoftBody::checkLink(const Node* node0, const Node* node1) const
{
	for (int i = 0; i < m_links.size(); ++i)
	{
		const Link& l = m_links[i];
		if ((l.m_n[0] == node0 && l.m_n[1] == node1) || (l.m_n[0] == node1 && l.m_n[1] == node0)) return true;
	}
	return false;
}

bool btSoftBody::checkFace(int node0, int node1, int node2) const
{
	if (!validIndex(node0, m_nodes.size()) || !validIndex(node1, m_nodes.size()) || !validIndex(node2, m_nodes.size()))
		return false;
	const Node* n[3] = {&m_nodes[node0], &m_nodes[node1], &m_nodes[node2]};
	for (int i = 0; i < m_faces.size(); ++i)
	{
		const Face& f = m_faces[i];
		int found = 0;
		for (int j = 0; j < 3; ++j)
			if (f.m_n[j] == n[0] || f.m_n[j] == n[1] || f.m_n[j] == n[2]) ++found;
		if (found == 3) return true;
	}
	return false;
}

btSoftBody::Material* btSoftBody::appendMaterial()
{
	Material* pm = new (btAlignedAlloc(sizeof(Material), 16)) Material();
	if (m_materials.size() > 0)
		*pm = *m_materials[0];
	else
	{
		pm->m_kLST = 1;
		pm->m_kAST = 1;
		pm->m_kVST = 1;
		pm->m_flags = fMaterial::Default;
	}
	m_materials.push_back(pm);
	return pm;
}

void btSoftBody::appendNote(const char* text, const btVector3& o, const btVector4& c, Node* n0, Node* n1, Node* n2,
                            Node* n3)
{
	Note n;
	n.m_text = text;
	n.m_offset = o;
	n.m_rank = 0;
	Node* nodes[4] = {n0, n1, n2, n3};
	for (int i = 0; i < 4; ++i)
	{
		n.m_nodes[i] = 0;
		n.m_coords[i] = 0;
	}
	for (int i = 0; i < 4; ++i)
		if (nodes[i])
		{
			n.m_nodes[n.m_rank] = nodes[i];
			n.m_coords[n.m_rank] = c[i];
			++n.m_rank;
		}
	m_notes.push_back(n);
}

void btSoftBody::appendNote(const char* text, const btVector3& o, Node* feature)
{
	appendNote(text, o, btVector4(1, 0, 0, 0), feature);
}

void btSoftBody::appendNote(const char* text, const btVector3& o, Link* feature)
{
	const btScalar w = btScalar(0.5);
	appendNote(text, o, btVector4(w, w, 0, 0), feature->m_n[0], feature->m_n[1]);
}

void btSoftBody::appendNote(const char* text, const btVector3& o, Face* feature)
{
	const btScalar w = btScalar(1) / btScalar(3);
	appendNote(text, o, btVector4(w, w, w, 0), feature->m_n[0], feature->m_n[1], feature->m_n[2]);
}

void btSoftBody::appendNode(const btVector3& x, btScalar m)
{
	btVector3 pos = x;
	const bool finitePos = caliber::isFinite(x);
	btAssert(finitePos && "btSoftBody::appendNode: non-finite position");
	if (!finitePos)
	{
		softBodyWarning("Caliber: btSoftBody::appendNode: non-finite position; the node is fixed at the origin\n");
		pos.setValue(0, 0, 0);
		m = 0;
	}
	const bool goodMass = btIsFinite(m) && m >= 0;
	btAssert(goodMass && "btSoftBody::appendNode: negative or non-finite mass");
	if (!goodMass)
	{
		softBodyWarning("Caliber: btSoftBody::appendNode: negative or non-finite mass; the node is fixed\n");
		m = 0;
	}
	// Links, faces, ... point into m_nodes: keep them valid when the array grows.
	if (m_nodes.capacity() == m_nodes.size())
	{
		pointersToIndices();
		m_nodes.reserve(m_nodes.size() * 2 + 1);
		indicesToPointers();
	}
	Node n;
	n.m_tag = 0;
	n.m_material = m_materials[0];
	n.m_x = pos;
	n.m_q = pos;
	n.m_v.setValue(0, 0, 0);
	n.m_vn.setValue(0, 0, 0);
	n.m_f.setValue(0, 0, 0);
	n.m_n.setValue(0, 0, 0);
	n.m_im = m > 0 ? btScalar(1) / m : btScalar(0);
	n.m_area = 0;
	n.m_leaf = 0;
	n.m_battach = 0;
	n.index = m_nodes.size();
	m_nodes.push_back(n);
	m_bUpdateRtCst = true;
}

void btSoftBody::appendLink(int model, Material* mat)
{
	Link l;
	if (validIndex(model, m_links.size()))
		l = m_links[model];
	else
	{
		l.m_tag = 0;
		l.m_n[0] = l.m_n[1] = 0;
		l.m_rl = 0;
		l.m_bbending = 0;
		l.m_c0 = l.m_c1 = l.m_c2 = 0;
		l.m_c3.setValue(0, 0, 0);
	}
	l.m_material = mat ? mat : m_materials[0];
	m_links.push_back(l);
}

void btSoftBody::appendLink(int node0, int node1, Material* mat, bool bcheckexist)
{
	const bool ok = validIndex(node0, m_nodes.size()) && validIndex(node1, m_nodes.size()) && node0 != node1;
	btAssert(ok && "btSoftBody::appendLink: node index out of range or both ends the same node");
	if (!ok)
	{
		softBodyWarning("Caliber: btSoftBody::appendLink: bad node indices; no link added\n");
		return;
	}
	appendLink(&m_nodes[node0], &m_nodes[node1], mat, bcheckexist);
}

void btSoftBody::appendLink(Node* node0, Node* node1, Material* mat, bool bcheckexist)
{
	const bool ok = node0 && node1 && node0 != node1;
	btAssert(ok && "btSoftBody::appendLink: null node or both ends the same node");
	if (!ok)
	{
		softBodyWarning("Caliber: btSoftBody::appendLink: bad nodes; no link added\n");
		return;
	}
	if (bcheckexist && checkLink(node0, node1)) return;
	appendLink(-1, mat);
	Link& l = m_links[m_links.size() - 1];
	l.m_n[0] = node0;
	l.m_n[1] = node1;
	l.m_rl = (node0->m_x - node1->m_x).length();
	l.m_c1 = l.m_rl * l.m_rl;
	m_bUpdateRtCst = true;
}

void btSoftBody::appendFace(int model, Material* mat)
{
	Face f;
	if (validIndex(model, m_faces.size()))
		f = m_faces[model];
	else
	{
		f.m_tag = 0;
		f.m_n[0] = f.m_n[1] = f.m_n[2] = 0;
		f.m_normal.setValue(0, 0, 0);
		f.m_ra = 0;
		f.m_leaf = 0;
	}
	f.m_material = mat ? mat : m_materials[0];
	f.m_index = m_faces.size();
	m_faces.push_back(f);
}

void btSoftBody::appendFace(int node0, int node1, int node2, Material* mat)
{
	const int n = m_nodes.size();
	const bool ok = validIndex(node0, n) && validIndex(node1, n) && validIndex(node2, n) && node0 != node1 &&
	                node1 != node2 && node0 != node2;
	btAssert(ok && "btSoftBody::appendFace: node index out of range or repeated (degenerate face)");
	if (!ok)
	{
		softBodyWarning("Caliber: btSoftBody::appendFace: bad or repeated node indices; no face added\n");
		return;
	}
	appendFace(-1, mat);
	Face& f = m_faces[m_faces.size() - 1];
	f.m_n[0] = &m_nodes[node0];
	f.m_n[1] = &m_nodes[node1];
	f.m_n[2] = &m_nodes[node2];
	f.m_ra = btScalar(0.5) * (f.m_n[1]->m_x - f.m_n[0]->m_x).cross(f.m_n[2]->m_x - f.m_n[0]->m_x).length();
	m_bUpdateRtCst = true;
}

void btSoftBody::appendTetra(int model, Material* mat)
{
	Tetra t;
	if (validIndex(model, m_tetras.size()))
		t = m_tetras[model];
	else
	{
		t.m_tag = 0;
		for (int i = 0; i < 4; ++i)
		{
			t.m_n[i] = 0;
			t.m_c0[i].setValue(0, 0, 0);
		}
		t.m_rv = 0;
		t.m_leaf = 0;
		t.m_c1 = t.m_c2 = 0;
	}
	t.m_material = mat ? mat : m_materials[0];
	m_tetras.push_back(t);
}

void btSoftBody::appendTetra(int node0, int node1, int node2, int node3, Material* mat)
{
	const int n = m_nodes.size();
	const int idx[4] = {node0, node1, node2, node3};
	bool ok = true;
	for (int i = 0; i < 4; ++i)
	{
		ok = ok && validIndex(idx[i], n);
		for (int j = 0; j < i; ++j) ok = ok && idx[i] != idx[j];
	}
	btAssert(ok && "btSoftBody::appendTetra: node index out of range or repeated (degenerate tetra)");
	if (!ok)
	{
		softBodyWarning("Caliber: btSoftBody::appendTetra: bad or repeated node indices; no tetra added\n");
		return;
	}
	appendTetra(-1, mat);
	Tetra& t = m_tetras[m_tetras.size() - 1];
	for (int i = 0; i < 4; ++i) t.m_n[i] = &m_nodes[idx[i]];
	t.m_rv = tetraVolume(t.m_n[0]->m_x, t.m_n[1]->m_x, t.m_n[2]->m_x, t.m_n[3]->m_x);
	m_bUpdateRtCst = true;
}

void btSoftBody::appendAnchor(int node, btRigidBody* body, bool disableCollisionBetweenLinkedBodies, btScalar influence)
{
	const bool ok = body && validIndex(node, m_nodes.size());
	btAssert(ok && "btSoftBody::appendAnchor: null body or node index out of range");
	if (!ok)
	{
		softBodyWarning("Caliber: btSoftBody::appendAnchor: null body or bad node index; no anchor added\n");
		return;
	}
	const btVector3 local = body->getWorldTransform().inverse() * m_nodes[node].m_x;
	appendAnchor(node, body, local, disableCollisionBetweenLinkedBodies, influence);
}

void btSoftBody::appendAnchor(int node, btRigidBody* body, const btVector3& localPivot,
                              bool disableCollisionBetweenLinkedBodies, btScalar influence)
{
	const bool ok = body && validIndex(node, m_nodes.size()) && caliber::isFinite(localPivot) && btIsFinite(influence);
	btAssert(ok && "btSoftBody::appendAnchor: null body, node index out of range or non-finite pivot");
	if (!ok)
	{
		softBodyWarning(
		    "Caliber: btSoftBody::appendAnchor: null body, bad node index or non-finite pivot; no anchor added\n");
		return;
	}
	if (disableCollisionBetweenLinkedBodies &&
	    m_collisionDisabledObjects.findLinearSearch(body) == m_collisionDisabledObjects.size())
		m_collisionDisabledObjects.push_back(body);
	Anchor a;
	a.m_node = &m_nodes[node];
	a.m_body = body;
	a.m_local = localPivot;
	a.m_influence = btClamped(influence, btScalar(0), btScalar(1));
	a.m_c0.setIdentity();
	a.m_c1.setValue(0, 0, 0);
	a.m_c2 = 0;
	a.m_node->m_battach = 1;
	m_anchors.push_back(a);
}

void btSoftBody::addForce(const btVector3& force)
{
	const bool ok = caliber::isFinite(force);
	btAssert(ok && "btSoftBody::addForce: non-finite force");
	if (!ok)
	{
		softBodyWarning("Caliber: btSoftBody::addForce: non-finite force; ignored\n");
		return;
	}
	for (int i = 0; i < m_nodes.size(); ++i)
		if (m_nodes[i].m_im > 0) m_nodes[i].m_f += force;
}

void btSoftBody::addForce(const btVector3& force, int node)
{
	const bool ok = caliber::isFinite(force) && validIndex(node, m_nodes.size());
	btAssert(ok && "btSoftBody::addForce: non-finite force or node index out of range");
	if (!ok)
	{
		softBodyWarning("Caliber: btSoftBody::addForce: non-finite force or bad node index; ignored\n");
		return;
	}
	if (m_nodes[node].m_im > 0) m_nodes[node].m_f += force;
}

void btSoftBody::addVelocity(const btVector3& velocity)
{
	for (int i = 0; i < m_nodes.size(); ++i) addVelocity(velocity, i);
}

void btSoftBody::setVelocity(const btVector3& velocity)
{
	const bool ok = caliber::isFinite(velocity);
	btAssert(ok && "btSoftBody::setVelocity: non-finite velocity");
	if (!ok)
	{
		softBodyWarning("Caliber: btSoftBody::setVelocity: non-finite velocity; ignored\n");
		return;
	}
	for (int i = 0; i < m_nodes.size(); ++i)
		if (m_nodes[i].m_im > 0) m_nodes[i].m_v = velocity;
}

void btSoftBody::addVelocity(const btVector3& velocity, int node)
{
	const bool ok = caliber::isFinite(velocity) && validIndex(node, m_nodes.size());
	btAssert(ok && "btSoftBody::addVelocity: non-finite velocity or node index out of range");
	if (!ok)
	{
		softBodyWarning("Caliber: btSoftBody::addVelocity: non-finite velocity or bad node index; ignored\n");
		return;
	}
	if (m_nodes[node].m_im > 0) m_nodes[node].m_v += velocity;
}

void btSoftBody::setMass(int node, btScalar mass)
{
	const bool ok = validIndex(node, m_nodes.size()) && btIsFinite(mass) && mass >= 0;
	btAssert(ok && "btSoftBody::setMass: node index out of range or negative/non-finite mass");
	if (!ok)
	{
		softBodyWarning("Caliber: btSoftBody::setMass: bad node index or mass; ignored\n");
		return;
	}
	m_nodes[node].m_im = mass > 0 ? btScalar(1) / mass : btScalar(0);
	m_bUpdateRtCst = true;
}

btScalar btSoftBody::getMass(int node) const
{
	if (!validIndex(node, m_nodes.size())) return 0;
	return m_nodes[node].m_im > 0 ? btScalar(1) / m_nodes[node].m_im : btScalar(0);
}

btScalar btSoftBody::getTotalMass() const
{
	btScalar mass = 0;
	for (int i = 0; i < m_nodes.size(); ++i) mass += getMass(i);
	return mass;
}

void btSoftBody::setTotalMass(btScalar mass, bool fromfaces)
{
	const bool ok = btIsFinite(mass) && mass > 0;
	btAssert(ok && "btSoftBody::setTotalMass: mass must be positive and finite");
	if (!ok)
	{
		softBodyWarning("Caliber: btSoftBody::setTotalMass: mass not positive or not finite; ignored\n");
		return;
	}
	if (fromfaces && m_faces.size() > 0)
	{
		// Each free node weighs the third of its faces' areas.
		btAlignedObjectArray<btScalar> area;
		area.resize(m_nodes.size(), btScalar(0));
		for (int i = 0; i < m_faces.size(); ++i)
		{
			const Face& f = m_faces[i];
			const btScalar a = (f.m_n[1]->m_x - f.m_n[0]->m_x).cross(f.m_n[2]->m_x - f.m_n[0]->m_x).length();
			for (int j = 0; j < 3; ++j) area[int(f.m_n[j] - &m_nodes[0])] += a;
		}
		for (int i = 0; i < m_nodes.size(); ++i)
			if (m_nodes[i].m_im > 0 && area[i] > 0) m_nodes[i].m_im = btScalar(1) / area[i];
	}
	const btScalar current = getTotalMass();
	if (!(current > 0))
	{
		softBodyWarning("Caliber: btSoftBody::setTotalMass: every node is fixed; nothing to give mass to\n");
		return;
	}
	const btScalar factor = current / mass;  // scales inverse masses
	for (int i = 0; i < m_nodes.size(); ++i) m_nodes[i].m_im *= factor;
	m_bUpdateRtCst = true;
}

void btSoftBody::setTotalDensity(btScalar density) { setTotalMass(getVolume() * density, true); }

void btSoftBody::setVolumeMass(btScalar mass)
{
	const bool ok = btIsFinite(mass) && mass > 0 && m_tetras.size() > 0;
	btAssert(ok && "btSoftBody::setVolumeMass: mass must be positive and the body must have tetras");
	if (!ok)
	{
		softBodyWarning("Caliber: btSoftBody::setVolumeMass: mass not positive or no tetras; ignored\n");
		return;
	}
	btAlignedObjectArray<btScalar> share;
	share.resize(m_nodes.size(), btScalar(0));
	btScalar total = 0;
	for (int i = 0; i < m_tetras.size(); ++i)
	{
		const Tetra& t = m_tetras[i];
		const btScalar v = btFabs(tetraVolume(t.m_n[0]->m_x, t.m_n[1]->m_x, t.m_n[2]->m_x, t.m_n[3]->m_x));
		for (int j = 0; j < 4; ++j) share[int(t.m_n[j] - &m_nodes[0])] += v / 4;
		total += v;
	}
	if (!(total > 0))
	{
		softBodyWarning("Caliber: btSoftBody::setVolumeMass: the tetras have no volume; ignored\n");
		return;
	}
	for (int i = 0; i < m_nodes.size(); ++i)
		if (m_nodes[i].m_im > 0 && share[i] > 0) m_nodes[i].m_im = total / (share[i] * mass);
	m_bUpdateRtCst = true;
}

void btSoftBody::setVolumeDensity(btScalar density)
{
	btScalar volume = 0;
	for (int i = 0; i < m_tetras.size(); ++i)
	{
		const Tetra& t = m_tetras[i];
		volume += btFabs(tetraVolume(t.m_n[0]->m_x, t.m_n[1]->m_x, t.m_n[2]->m_x, t.m_n[3]->m_x));
	}
	setVolumeMass(volume * density);
}

void btSoftBody::transform(const btTransform& trs)
{
	const bool ok = caliber::isFinite(trs);
	btAssert(ok && "btSoftBody::transform: non-finite transform");
	if (!ok)
	{
		softBodyWarning("Caliber: btSoftBody::transform: non-finite transform; ignored\n");
		return;
	}
	const btMatrix3x3& basis = trs.getBasis();
	for (int i = 0; i < m_nodes.size(); ++i)
	{
		Node& n = m_nodes[i];
		n.m_x = trs * n.m_x;
		n.m_q = trs * n.m_q;
		n.m_v = basis * n.m_v;
		n.m_vn = basis * n.m_vn;
		n.m_n = basis * n.m_n;
	}
	for (int i = 0; i < m_faces.size(); ++i) m_faces[i].m_normal = basis * m_faces[i].m_normal;
	if (m_pose.m_bframe)
	{
		m_pose.m_com = trs * m_pose.m_com;
		m_pose.m_rot = basis * m_pose.m_rot;
	}
	m_initialWorldTransform = trs;
	updateBounds();
}

void btSoftBody::translate(const btVector3& trs)
{
	btTransform t;
	t.setIdentity();
	t.setOrigin(trs);
	transform(t);
}

void btSoftBody::rotate(const btQuaternion& rot)
{
	btTransform t;
	t.setIdentity();
	t.setRotation(rot);
	transform(t);
}

void btSoftBody::scale(const btVector3& scl)
{
	const bool ok = caliber::isFinite(scl);
	btAssert(ok && "btSoftBody::scale: non-finite scale");
	if (!ok)
	{
		softBodyWarning("Caliber: btSoftBody::scale: non-finite scale; ignored\n");
		return;
	}
	for (int i = 0; i < m_nodes.size(); ++i)
	{
		m_nodes[i].m_x *= scl;
		m_nodes[i].m_q *= scl;
	}
	// The scaled shape is the new rest shape.
	resetLinkRestLengths();
	for (int i = 0; i < m_tetras.size(); ++i)
	{
		Tetra& t = m_tetras[i];
		t.m_rv = tetraVolume(t.m_n[0]->m_x, t.m_n[1]->m_x, t.m_n[2]->m_x, t.m_n[3]->m_x);
	}
	if (m_pose.m_bvolume || m_pose.m_bframe) setPose(m_pose.m_bvolume, m_pose.m_bframe);
	m_bUpdateRtCst = true;
	updateNormals();
	updateBounds();
}

btScalar btSoftBody::getRestLengthScale() { return m_restLengthScale; }

void btSoftBody::setRestLengthScale(btScalar restLength)
{
	const bool ok = btIsFinite(restLength) && restLength > 0;
	btAssert(ok && "btSoftBody::setRestLengthScale: scale must be positive and finite");
	if (!ok)
	{
		softBodyWarning("Caliber: btSoftBody::setRestLengthScale: scale not positive or not finite; ignored\n");
		return;
	}
	for (int i = 0; i < m_links.size(); ++i)
	{
		Link& l = m_links[i];
		l.m_rl = l.m_rl / m_restLengthScale * restLength;
		l.m_c1 = l.m_rl * l.m_rl;
	}
	m_restLengthScale = restLength;
}

void btSoftBody::resetLinkRestLengths()
{
	for (int i = 0; i < m_links.size(); ++i)
	{
		Link& l = m_links[i];
		l.m_rl = (l.m_n[0]->m_x - l.m_n[1]->m_x).length();
		l.m_c1 = l.m_rl * l.m_rl;
	}
}

btScalar btSoftBody::getVolume() const
{
	if (m_faces.size() == 0) return 0;
	// Sum of the signed tetra volumes from a reference point (the first node) to each face.
	const btVector3 org = m_nodes[0].m_x;
	btScalar vol = 0;
	for (int i = 0; i < m_faces.size(); ++i)
	{
		const Face& f = m_faces[i];
		vol += (f.m_n[0]->m_x - org).dot((f.m_n[1]->m_x - org).cross(f.m_n[2]->m_x - org));
	}
	return vol / btScalar(6);
}

int btSoftBody::generateBendingConstraints(int distance, Material* mat)
{
	if (distance < 2) return 0;
	const int n = m_nodes.size();
	// Neighbour lists from the links (stretch links only, as the graph of the body).
	btAlignedObjectArray<int> first, next, other;
	first.resize(n, -1);
	for (int i = 0; i < m_links.size(); ++i)
	{
		const int a = int(m_links[i].m_n[0] - &m_nodes[0]), b = int(m_links[i].m_n[1] - &m_nodes[0]);
		other.push_back(b);
		next.push_back(first[a]);
		first[a] = other.size() - 1;
		other.push_back(a);
		next.push_back(first[b]);
		first[b] = other.size() - 1;
	}
	// Breadth-first search to depth `distance` from each node; a link to each node first reached at
	// depth >= 2 (depth 1 are the existing links). mark[] holds the source that last visited a node.
	btAlignedObjectArray<int> mark, depth, queue;
	mark.resize(n, -1);
	depth.resize(n, 0);
	int added = 0;
	for (int s = 0; s < n; ++s)
	{
		queue.resize(0);
		queue.push_back(s);
		mark[s] = s;
		depth[s] = 0;
		for (int qi = 0; qi < queue.size(); ++qi)
		{
			const int u = queue[qi];
			if (depth[u] >= distance) continue;
			for (int e = first[u]; e >= 0; e = next[e])
			{
				const int v = other[e];
				if (mark[v] == s) continue;
				mark[v] = s;
				depth[v] = depth[u] + 1;
				queue.push_back(v);
				if (depth[v] >= 2 && v > s)
				{
					appendLink(&m_nodes[s], &m_nodes[v], mat, false);
					m_links[m_links.size() - 1].m_bbending = 1;
					++added;
				}
			}
		}
	}
	return added;
}

void btSoftBody::randomizeConstraints()
{
	// A fixed linear congruential sequence: the same shuffle on every run and platform.
	unsigned int seed = 1;
	auto nextRandom = [&seed](int bound)
	{
		seed = seed * 1664525u + 1013904223u;
		return int((seed >> 8) % unsigned(bound));
	};
	for (int i = m_links.size() - 1; i > 0; --i) m_links.swap(i, nextRandom(i + 1));
	for (int i = m_faces.size() - 1; i > 0; --i) m_faces.swap(i, nextRandom(i + 1));
	for (int i = 0; i < m_faces.size(); ++i) m_faces[i].m_index = i;
}

bool btSoftBody::cutLink(int node0, int node1, btScalar position)
{
	if (!validIndex(node0, m_nodes.size()) || !validIndex(node1, m_nodes.size()))
	{
		btAssert(false && "btSoftBody::cutLink: node index out of range");
		softBodyWarning("Caliber: btSoftBody::cutLink: bad node index; nothing cut\n");
		return false;
	}
	return cutLink(&m_nodes[node0], &m_nodes[node1], position);
}

bool btSoftBody::cutLink(const Node* node0, const Node* node1, btScalar position)
{
	int li = -1;
	for (int i = 0; i < m_links.size() && li < 0; ++i)
	{
		const Link& l = m_links[i];
		if ((l.m_n[0] == node0 && l.m_n[1] == node1) || (l.m_n[0] == node1 && l.m_n[1] == node0)) li = i;
	}
	if (li < 0) return false;
	if (!btIsFinite(position)) position = btScalar(0.5);
	const btScalar t = btClamped(position, btScalar(0.01), btScalar(0.99));
	const int a = int(m_links[li].m_n[0] - &m_nodes[0]), b = int(m_links[li].m_n[1] - &m_nodes[0]);
	// Two new nodes at the cut, one for each side, sharing the mass of the two ends' neighbourhood.
	const btVector3 x = m_nodes[a].m_x.lerp(m_nodes[b].m_x, t);
	const btVector3 v = m_nodes[a].m_v.lerp(m_nodes[b].m_v, t);
	const btScalar ma = getMass(a), mb = getMass(b);
	const btScalar m = (ma > 0 && mb > 0) ? (ma * (1 - t) + mb * t) / 2 : (ma > 0 ? ma / 2 : mb / 2);
	appendNode(x, m);
	appendNode(x, m);
	const int na = m_nodes.size() - 2, nb = m_nodes.size() - 1;
	m_nodes[na].m_v = v;
	m_nodes[nb].m_v = v;
	Link& l = m_links[li];
	const btScalar rl = l.m_rl;
	Material* mat = l.m_material;
	l.m_n[0] = &m_nodes[a];
	l.m_n[1] = &m_nodes[na];
	l.m_rl = rl * t;
	l.m_c1 = l.m_rl * l.m_rl;
	appendLink(nb, b, mat);
	m_links[m_links.size() - 1].m_rl = rl * (1 - t);
	m_links[m_links.size() - 1].m_c1 = rl * (1 - t) * rl * (1 - t);
	// Faces across the cut edge: (a, b, c) becomes (a, na, c) and (nb, b, c), order kept.
	const int faceCount = m_faces.size();
	for (int i = 0; i < faceCount; ++i)
	{
		Face& f = m_faces[i];
		for (int k = 0; k < 3; ++k)
		{
			const int i0 = int(f.m_n[k] - &m_nodes[0]), i1 = int(f.m_n[(k + 1) % 3] - &m_nodes[0]);
			const int c = int(f.m_n[(k + 2) % 3] - &m_nodes[0]);
			const bool forward = i0 == a && i1 == b, backward = i0 == b && i1 == a;
			if (!forward && !backward) continue;
			const int nearA = na, nearB = nb;
			Material* fm = f.m_material;
			if (forward)
			{
				f.m_n[(k + 1) % 3] = &m_nodes[nearA];
				appendFace(nearB, b, c, fm);
			}
			else
			{
				f.m_n[k] = &m_nodes[nearB];
				appendFace(a, nearA, c, fm);
			}
			appendLink(c, nearA, mat, true);
			appendLink(c, nearB, mat, true);
			break;
		}
	}
	m_bUpdateRtCst = true;
	return true;
}

bool btSoftBody::rayTest(const btVector3& rayFrom, const btVector3& rayTo, sRayCast& results)
{
	results.body = this;
	results.feature = eFeature::None;
	results.index = -1;
	results.fraction = 1;
	if (!caliber::isFinite(rayFrom) || !caliber::isFinite(rayTo) || m_faces.size() == 0) return false;
	btScalar mint = 1;
	eFeature::_ feature = eFeature::None;
	int index = -1;
	if (rayTest(rayFrom, rayTo, mint, feature, index, false) > 0)
	{
		results.feature = feature;
		results.index = index;
		results.fraction = mint;
		return true;
	}
	return false;
}

int btSoftBody::rayTest(const btVector3& rayFrom, const btVector3& rayTo, btScalar& mint, eFeature::_& feature,
                        int& index, bool bcountonly) const
{
	// Both-sided segment-triangle test (Moller-Trumbore) against every face.
	const btVector3 dir = rayTo - rayFrom;
	int hits = 0;
	for (int i = 0; i < m_faces.size(); ++i)
	{
		const Face& f = m_faces[i];
		const btVector3 e1 = f.m_n[1]->m_x - f.m_n[0]->m_x, e2 = f.m_n[2]->m_x - f.m_n[0]->m_x;
		const btVector3 p = dir.cross(e2);
		const btScalar det = e1.dot(p);
		if (btFabs(det) < SIMD_EPSILON * e1.length() * e2.length() * dir.length() || det == 0) continue;
		const btScalar inv = btScalar(1) / det;
		const btVector3 s = rayFrom - f.m_n[0]->m_x;
		const btScalar u = s.dot(p) * inv;
		if (u < 0 || u > 1) continue;
		const btVector3 q = s.cross(e1);
		const btScalar v = dir.dot(q) * inv;
		if (v < 0 || u + v > 1) continue;
		const btScalar t = e2.dot(q) * inv;
		if (t < 0 || t > mint) continue;
		++hits;
		if (!bcountonly)
		{
			mint = t;
			feature = eFeature::Face;
			index = i;
		}
	}
	return hits;
}

void btSoftBody::setSolver(eSolverPresets::_ preset)
{
	m_cfg.m_vsequence.clear();
	m_cfg.m_psequence.clear();
	m_cfg.m_dsequence.clear();
	// Both presets run the position solvers: Caliber's step has no separate velocity pass.
	(void)preset;
	m_cfg.m_psequence.push_back(ePSolver::Anchors);
	m_cfg.m_psequence.push_back(ePSolver::RContacts);
	m_cfg.m_psequence.push_back(ePSolver::SContacts);
	m_cfg.m_psequence.push_back(ePSolver::Linear);
}

void btSoftBody::setWindVelocity(const btVector3& velocity)
{
	const bool ok = caliber::isFinite(velocity);
	btAssert(ok && "btSoftBody::setWindVelocity: non-finite velocity");
	if (!ok)
	{
		softBodyWarning("Caliber: btSoftBody::setWindVelocity: non-finite velocity; ignored\n");
		return;
	}
	m_windVelocity = velocity;
}

const btVector3& btSoftBody::getWindVelocity() { return m_windVelocity; }

void btSoftBody::pointersToIndices()
{
	Node* base = m_nodes.size() ? &m_nodes[0] : 0;
	if (!base) return;
	for (int i = 0; i < m_links.size(); ++i)
		for (int j = 0; j < 2; ++j) m_links[i].m_n[j] = indexAsPointer(int(m_links[i].m_n[j] - base));
	for (int i = 0; i < m_faces.size(); ++i)
		for (int j = 0; j < 3; ++j) m_faces[i].m_n[j] = indexAsPointer(int(m_faces[i].m_n[j] - base));
	for (int i = 0; i < m_tetras.size(); ++i)
		for (int j = 0; j < 4; ++j) m_tetras[i].m_n[j] = indexAsPointer(int(m_tetras[i].m_n[j] - base));
	for (int i = 0; i < m_anchors.size(); ++i) m_anchors[i].m_node = indexAsPointer(int(m_anchors[i].m_node - base));
	for (int i = 0; i < m_rcontacts.size(); ++i)
		m_rcontacts[i].m_node = indexAsPointer(int(m_rcontacts[i].m_node - base));
	for (int i = 0; i < m_notes.size(); ++i)
		for (int j = 0; j < m_notes[i].m_rank; ++j)
			m_notes[i].m_nodes[j] = indexAsPointer(int(m_notes[i].m_nodes[j] - base));
	for (int i = 0; i < m_clusters.size(); ++i)
		for (int j = 0; j < m_clusters[i]->m_nodes.size(); ++j)
			m_clusters[i]->m_nodes[j] = indexAsPointer(int(m_clusters[i]->m_nodes[j] - base));
}

void btSoftBody::indicesToPointers(const int* map)
{
	if (m_nodes.size() == 0) return;
	Node* base = &m_nodes[0];
	auto toPointer = [&](Node* p) { return base + (map ? map[pointerAsIndex(p)] : pointerAsIndex(p)); };
	for (int i = 0; i < m_links.size(); ++i)
		for (int j = 0; j < 2; ++j) m_links[i].m_n[j] = toPointer(m_links[i].m_n[j]);
	for (int i = 0; i < m_faces.size(); ++i)
		for (int j = 0; j < 3; ++j) m_faces[i].m_n[j] = toPointer(m_faces[i].m_n[j]);
	for (int i = 0; i < m_tetras.size(); ++i)
		for (int j = 0; j < 4; ++j) m_tetras[i].m_n[j] = toPointer(m_tetras[i].m_n[j]);
	for (int i = 0; i < m_anchors.size(); ++i) m_anchors[i].m_node = toPointer(m_anchors[i].m_node);
	for (int i = 0; i < m_rcontacts.size(); ++i) m_rcontacts[i].m_node = toPointer(m_rcontacts[i].m_node);
	for (int i = 0; i < m_notes.size(); ++i)
		for (int j = 0; j < m_notes[i].m_rank; ++j) m_notes[i].m_nodes[j] = toPointer(m_notes[i].m_nodes[j]);
	for (int i = 0; i < m_clusters.size(); ++i)
		for (int j = 0; j < m_clusters[i]->m_nodes.size(); ++j)
			m_clusters[i]->m_nodes[j] = toPointer(m_clusters[i]->m_nodes[j]);
}

btVector3 btSoftBody::evaluateCom() const
{
	btVector3 com(0, 0, 0);
	btScalar mass = 0;
	for (int i = 0; i < m_nodes.size(); ++i)
	{
		const btScalar m = m_nodes[i].m_im > 0 ? btScalar(1) / m_nodes[i].m_im : btScalar(0);
		com += m_nodes[i].m_x * m;
		mass += m;
	}
	if (mass > 0) return com / mass;
	// Every node fixed: the plain average.
	for (int i = 0; i < m_nodes.size(); ++i) com += m_nodes[i].m_x;
	return m_nodes.size() ? com / btScalar(m_nodes.size()) : com;
}

void btSoftBody::updateNormals()
{
	// A large body with several threads free: the same bits from chunks on the task scheduler.
	if (caliber::normalsOnThreads(*this))
	{
		caliber::updateNormalsOnThreads(*this);
		return;
	}
	for (int i = 0; i < m_nodes.size(); ++i) m_nodes[i].m_n.setValue(0, 0, 0);
	for (int i = 0; i < m_faces.size(); ++i)
	{
		Face& f = m_faces[i];
		const btVector3 n = (f.m_n[1]->m_x - f.m_n[0]->m_x).cross(f.m_n[2]->m_x - f.m_n[0]->m_x);
		const btScalar len = n.length();
		// Degenerate (zero-area) faces keep their last normal and add nothing to the nodes'.
		if (len > SIMD_EPSILON) f.m_normal = n / len;
		for (int j = 0; j < 3; ++j) f.m_n[j]->m_n += n;
	}
	for (int i = 0; i < m_nodes.size(); ++i)
	{
		const btScalar len = m_nodes[i].m_n.length();
		if (len > SIMD_EPSILON) m_nodes[i].m_n /= len;
	}
}

void btSoftBody::updateBounds()
{
	if (m_nodes.size() == 0)
	{
		m_bounds[0].setValue(0, 0, 0);
		m_bounds[1].setValue(0, 0, 0);
		return;
	}
	btVector3 lo = m_nodes[0].m_x, hi = lo;
	for (int i = 0; i < m_nodes.size(); ++i)
	{
		lo.setMin(m_nodes[i].m_x);
		hi.setMax(m_nodes[i].m_x);
		lo.setMin(m_nodes[i].m_q);
		hi.setMax(m_nodes[i].m_q);
	}
	const btScalar margin = m_collisionShape ? m_collisionShape->getMargin() : btScalar(0);
	const btVector3 mrg(margin, margin, margin);
	m_bounds[0] = lo - mrg;
	m_bounds[1] = hi + mrg;
}
