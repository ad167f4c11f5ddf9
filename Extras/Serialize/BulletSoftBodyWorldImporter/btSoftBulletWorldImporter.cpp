// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// Loading soft bodies from .bullet files. Every array a body points to is checked against the chunk it
// came from (struct and count), every node index against the node count and every number for being
// finite before anything is built; docs/serialization.md, "Soft bodies".
#include "btSoftBulletWorldImporter.h"

#include "BulletFileLoader/btBulletFile.h"
#include "BulletSoftBody/btSoftBodyClusters.h"
#include "BulletSoftBody/btSoftBodyData.h"
#include "BulletSoftBody/btSoftRigidDynamicsWorld.h"
#include "LinearMath/btSerializer.h"
#include "LinearMath/btWarningHook.h"
#include "detail/DnaChecks.h"

#include <math.h>
#include <string.h>

#include <string>

namespace
{
void warn(const std::string& message)
{
	btReportWarning(("Caliber: btSoftBulletWorldImporter: " + message + "\n").c_str());
}

using caliber::importer::memoryDna;

bool finiteFloat(float x) { return isfinite(x) != 0; }

class SoftChecker
{
public:
	explicit SoftChecker(bParse::btBulletFile& file) : m_blocks(caliber::importer::blockInfo(file)) {}

	const bParse::bChunkInd* info(const void* p) const { return p ? m_blocks.find(btHashPtr(p)) : 0; }
	// The block at p holds at least count structs named type (count 0: p may be null).
	bool holds(const void* p, const char* type, int count) const
	{
		if (count < 0) return false;
		if (count == 0) return true;
		const bParse::bChunkInd* i = info(p);
		if (!i || i->dna_nr < 0 || i->nr < count) return false;
		short* st = memoryDna().getStruct(i->dna_nr);
		return st && !strcmp(memoryDna().getType(st[0]), type);
	}
	// Plain (struct-less) block of at least count 4-byte numbers.
	bool holdsPlain(const void* p, int count) const
	{
		if (count < 0) return false;
		if (count == 0) return true;
		const bParse::bChunkInd* i = info(p);
		return i && i->dna_nr == -1 && i->len >= 4 * (long long)count;
	}
	bool isPointerArray(const void* p, int count) const
	{
		const bParse::bChunkInd* i = info(p);
		return i && i->dna_nr == bParse::kPointerArrayDna && i->nr >= count;
	}
	int structIndex(const char* type) const { return memoryDna().getReverseType(type); }
	bool finite(const void* p, const char* type, int count) const
	{
		const int s = structIndex(type);
		if (s < 0) return false;
		const int size = memoryDna().getLength(memoryDna().getStruct(s)[0]);
		for (int i = 0; i < count; ++i)
			if (!caliber::importer::numbersSane(s, static_cast<const char*>(p) + size_t(i) * size_t(size), true))
				return false;
		return true;
	}

private:
	const btHashMap<btHashPtr, bParse::bChunkInd>& m_blocks;
};

// A plain array of 4-byte numbers in the writer's byte order: swapped in place for the other order.
void swapPlain(void* p, int count)
{
	unsigned char* b = static_cast<unsigned char*>(p);
	for (int k = 0; k < count; ++k, b += 4)
	{
		btSwap(b[0], b[3]);
		btSwap(b[1], b[2]);
	}
}

// A rotation to float precision (what a float file can hold).
bool isRotation(const btMatrix3x3& m)
{
	const btMatrix3x3 e = m * m.transpose();
	for (int r = 0; r < 3; ++r)
		for (int c = 0; c < 3; ++c)
			if (!(btFabs(e[r][c] - (r == c ? 1 : 0)) < btScalar(1e-4))) return false;
	return m.determinant() > 0;
}

bool indicesValid(const int* idx, int n, int nodeCount)
{
	for (int i = 0; i < n; ++i)
		if (idx[i] < 0 || idx[i] >= nodeCount) return false;
	return true;
}

// Everything a body's struct points to, checked before anything is built; the reason when not.
std::string checkBody(const SoftChecker& c, btSoftBodyFloatData* d, bool swapped)
{
	if (!c.finite(d, "btSoftBodyFloatData", 1)) return "non-finite numbers";
	const btCollisionObjectFloatData& o = d->m_collisionObjectData;
	if (o.m_friction < 0 || o.m_restitution < 0 || o.m_rollingFriction < 0 || o.m_ccdMotionThreshold < 0 ||
	    o.m_ccdSweptSphereRadius < 0)
		return "a negative friction, restitution or CCD setting";
	btTransform t;
	t.deSerializeFloat(o.m_worldTransform);
	if (!isRotation(t.getBasis())) return "a world transform that is not a rotation";
	t.deSerializeFloat(o.m_interpolationWorldTransform);
	if (!isRotation(t.getBasis())) return "a world transform that is not a rotation";
	const int n = d->m_numNodes;
	if (d->m_numMaterials < 0 || (d->m_numMaterials > 0 && !c.isPointerArray(d->m_materials, d->m_numMaterials)))
		return "a material list that is not an array of material pointers";
	for (int i = 0; i < d->m_numMaterials; ++i)
		if (d->m_materials[i] && !c.holds(d->m_materials[i], "SoftBodyMaterialData", 1))
			return "a material pointer to something else";
	if (!c.holds(d->m_nodes, "SoftBodyNodeData", n)) return "a node array shorter than its count";
	if (!c.holds(d->m_links, "SoftBodyLinkData", d->m_numLinks)) return "a link array shorter than its count";
	if (!c.holds(d->m_faces, "SoftBodyFaceData", d->m_numFaces)) return "a face array shorter than its count";
	if (!c.holds(d->m_tetrahedra, "SoftBodyTetraData", d->m_numTetrahedra))
		return "a tetra array shorter than its count";
	if (!c.holds(d->m_anchors, "SoftRigidAnchorData", d->m_numAnchors)) return "an anchor array shorter than its count";
	if (!c.holds(d->m_clusters, "SoftBodyClusterData", d->m_numClusters))
		return "a cluster array shorter than its count";
	if (!c.holds(d->m_joints, "btSoftBodyJointData", d->m_numJoints)) return "a joint array shorter than its count";
	if (!c.finite(d->m_nodes, "SoftBodyNodeData", n) || !c.finite(d->m_links, "SoftBodyLinkData", d->m_numLinks) ||
	    !c.finite(d->m_faces, "SoftBodyFaceData", d->m_numFaces) ||
	    !c.finite(d->m_tetrahedra, "SoftBodyTetraData", d->m_numTetrahedra) ||
	    !c.finite(d->m_anchors, "SoftRigidAnchorData", d->m_numAnchors) ||
	    !c.finite(d->m_clusters, "SoftBodyClusterData", d->m_numClusters) ||
	    !c.finite(d->m_joints, "btSoftBodyJointData", d->m_numJoints))
		return "non-finite numbers";
	for (int i = 0; i < n; ++i)
		if (d->m_nodes[i].m_inverseMass < 0) return "a negative inverse mass";
	for (int i = 0; i < d->m_numLinks; ++i)
	{
		const int* idx = d->m_links[i].m_nodeIndices;
		if (!indicesValid(idx, 2, n) || idx[0] == idx[1]) return "a link with bad node indices";
	}
	for (int i = 0; i < d->m_numFaces; ++i)
	{
		const int* idx = d->m_faces[i].m_nodeIndices;
		if (!indicesValid(idx, 3, n) || idx[0] == idx[1] || idx[1] == idx[2] || idx[0] == idx[2])
			return "a face with bad node indices";
	}
	for (int i = 0; i < d->m_numTetrahedra; ++i)
	{
		const int* idx = d->m_tetrahedra[i].m_nodeIndices;
		if (!indicesValid(idx, 4, n)) return "a tetra with bad node indices";
		for (int a = 0; a < 4; ++a)
			for (int b = 0; b < a; ++b)
				if (idx[a] == idx[b]) return "a tetra with bad node indices";
	}
	for (int i = 0; i < d->m_numAnchors; ++i)
		if (!indicesValid(&d->m_anchors[i].m_nodeIndex, 1, n)) return "an anchor with a bad node index";
	if (d->m_pose)
	{
		SoftBodyPoseData* p = d->m_pose;
		if (!c.holds(p, "SoftBodyPoseData", 1) || !c.finite(p, "SoftBodyPoseData", 1)) return "a malformed pose";
		if (!c.holds(p->m_positions, "btVector3FloatData", p->m_numPositions) ||
		    !c.finite(p->m_positions, "btVector3FloatData", p->m_numPositions) ||
		    !c.holdsPlain(p->m_weights, p->m_numWeigts))
			return "a pose whose arrays are shorter than their counts";
		if ((p->m_numPositions != 0 && p->m_numPositions != n) || (p->m_numWeigts != 0 && p->m_numWeigts != n))
			return "a pose whose arrays do not match the nodes";
	}
	for (int i = 0; i < d->m_numClusters; ++i)
	{
		SoftBodyClusterData& cl = d->m_clusters[i];
		if (!c.holds(cl.m_framerefs, "btVector3FloatData", cl.m_numFrameRefs) ||
		    !c.finite(cl.m_framerefs, "btVector3FloatData", cl.m_numFrameRefs) ||
		    !c.holdsPlain(cl.m_nodeIndices, cl.m_numNodes) || !c.holdsPlain(cl.m_masses, cl.m_numMasses))
			return "a cluster whose arrays are shorter than their counts";
		if (cl.m_numMasses != cl.m_numNodes || (cl.m_numFrameRefs != 0 && cl.m_numFrameRefs != cl.m_numNodes))
			return "a cluster whose arrays disagree";
	}
	// Plain arrays stay in the writer's byte order: swapped once here, then checked.
	if (swapped)
	{
		if (d->m_pose && d->m_pose->m_numWeigts > 0) swapPlain(d->m_pose->m_weights, d->m_pose->m_numWeigts);
		for (int i = 0; i < d->m_numClusters; ++i)
		{
			if (d->m_clusters[i].m_numNodes > 0) swapPlain(d->m_clusters[i].m_nodeIndices, d->m_clusters[i].m_numNodes);
			if (d->m_clusters[i].m_numMasses > 0) swapPlain(d->m_clusters[i].m_masses, d->m_clusters[i].m_numMasses);
		}
	}
	if (d->m_pose)
		for (int i = 0; i < d->m_pose->m_numWeigts; ++i)
			if (!finiteFloat(d->m_pose->m_weights[i])) return "non-finite pose weights";
	for (int i = 0; i < d->m_numClusters; ++i)
	{
		const SoftBodyClusterData& cl = d->m_clusters[i];
		if (!indicesValid(cl.m_nodeIndices, cl.m_numNodes, n)) return "a cluster with bad node indices";
		for (int j = 0; j < cl.m_numMasses; ++j)
			if (!finiteFloat(cl.m_masses[j]) || cl.m_masses[j] < 0) return "a cluster with bad masses";
	}
	return std::string();
}

template <class Data>
void readVector(btVector3& v, const Data& d)
{
	v.deSerializeFloat(d);
}

// The part of a cluster's state that appending a joint refreshes from the nodes: read again after the joints.
void readClusterMotion(btSoftBody::Cluster& cl, const SoftBodyClusterData& cd)
{
	cl.m_framexform.deSerializeFloat(cd.m_framexform);
	cl.m_invwi.deSerializeFloat(cd.m_invwi);
	readVector(cl.m_com, cd.m_com);
	readVector(cl.m_lv, cd.m_lv);
	readVector(cl.m_av, cd.m_av);
}
}  // namespace

btSoftBulletWorldImporter::btSoftBulletWorldImporter(btSoftRigidDynamicsWorld* world)
    : btBulletWorldImporter(world), m_softRigidWorld(world)
{
}

btSoftBulletWorldImporter::~btSoftBulletWorldImporter() {}

btSoftBody* btSoftBulletWorldImporter::getSoftBodyByIndex(int index) const
{
	return index >= 0 && index < m_softBodies.size() ? m_softBodies[index] : 0;
}

void btSoftBulletWorldImporter::deleteAllData()
{
	for (int i = 0; i < m_softBodies.size(); ++i)
	{
		if (m_softRigidWorld) m_softRigidWorld->removeSoftBody(m_softBodies[i]);
		delete m_softBodies[i];
	}
	m_softBodies.clear();
	m_clusterBodyMap.clear();
	m_softBodyMap.clear();
	btBulletWorldImporter::deleteAllData();
}

bool btSoftBulletWorldImporter::convertAllObjects(bParse::btBulletFile* file)
{
	const bool rigidPartOk = btBulletWorldImporter::convertAllObjects(file);
	if (m_importerFlags & eRESTORE_EXISTING_OBJECTS)
	{
		// Writing a file into existing soft bodies is not supported: a soft world snapshot does that exactly.
		if (file && file->m_softBodies.size() > 0)
			warn("eRESTORE_EXISTING_OBJECTS: the file's " + std::to_string(file->m_softBodies.size()) +
			     " soft bodies are not written into the world's (not supported; Caliber/SoftWorldSnapshot.h restores "
			     "soft bodies); they are skipped");
		return rigidPartOk && file->m_softBodies.size() == 0;
	}
	if (!rigidPartOk) return false;
	// Keyed by this file's converted blocks (an earlier file's are gone; their addresses may come back).
	m_softBodyMap.clear();
	m_clusterBodyMap.clear();
	SoftChecker check(*file);
	const bool swapped = (file->getFlags() & bParse::FD_ENDIAN_SWAP) != 0;
	btSoftBodyWorldInfo& info = m_softRigidWorld ? m_softRigidWorld->getWorldInfo() : m_ownWorldInfo;
	for (int b = 0; b < file->m_softBodies.size(); ++b)
	{
		void* block = file->m_softBodies[b];
		if (!check.holds(block, "btSoftBodyFloatData", 1))
		{
			warn("soft body " + std::to_string(b) + " is not a btSoftBodyFloatData; it is skipped");
			continue;
		}
		btSoftBodyFloatData* d = static_cast<btSoftBodyFloatData*>(block);
		const std::string reason = checkBody(check, d, swapped);
		if (!reason.empty())
		{
			warn("soft body " + std::to_string(b) + " has " + reason + "; it is skipped");
			continue;
		}
		btSoftBody* psb = new btSoftBody(&info);
		// Materials: the body's default material takes the first one, so that a body written and read has
		// the same material list.
		btHashMap<btHashPtr, btSoftBody::Material*> materials;
		for (int i = 0; i < d->m_numMaterials; ++i)
		{
			const SoftBodyMaterialData* md = d->m_materials[i];
			btSoftBody::Material* m = i == 0 ? psb->m_materials[0] : psb->appendMaterial();
			if (md)
			{
				m->m_kLST = md->m_linearStiffness;
				m->m_kAST = md->m_angularStiffness;
				m->m_kVST = md->m_volumeStiffness;
				m->m_flags = md->m_flags;
				materials.insert(btHashPtr(md), m);
			}
		}
		auto material = [&](const SoftBodyMaterialData* md)
		{
			btSoftBody::Material** m = md ? materials.find(btHashPtr(md)) : 0;
			return m ? *m : psb->m_materials[0];
		};
		psb->m_nodes.reserve(d->m_numNodes);
		for (int i = 0; i < d->m_numNodes; ++i)
		{
			const SoftBodyNodeData& nd = d->m_nodes[i];
			btVector3 x;
			readVector(x, nd.m_position);
			psb->appendNode(x, 1);
			btSoftBody::Node& node = psb->m_nodes[i];
			node.m_material = material(nd.m_material);
			readVector(node.m_q, nd.m_previousPosition);
			readVector(node.m_v, nd.m_velocity);
			readVector(node.m_f, nd.m_accumulatedForce);
			readVector(node.m_n, nd.m_normal);
			node.m_im = nd.m_inverseMass;
			node.m_area = nd.m_area;
			node.m_battach = nd.m_attach ? 1 : 0;
		}
		for (int i = 0; i < d->m_numLinks; ++i)
		{
			const SoftBodyLinkData& ld = d->m_links[i];
			psb->appendLink(ld.m_nodeIndices[0], ld.m_nodeIndices[1], material(ld.m_material));
			btSoftBody::Link& link = psb->m_links[psb->m_links.size() - 1];
			link.m_rl = ld.m_restLength;
			link.m_bbending = ld.m_bbending ? 1 : 0;
		}
		for (int i = 0; i < d->m_numFaces; ++i)
		{
			const SoftBodyFaceData& fd = d->m_faces[i];
			psb->appendFace(fd.m_nodeIndices[0], fd.m_nodeIndices[1], fd.m_nodeIndices[2], material(fd.m_material));
			btSoftBody::Face& face = psb->m_faces[psb->m_faces.size() - 1];
			readVector(face.m_normal, fd.m_normal);
			face.m_ra = fd.m_restArea;
		}
		for (int i = 0; i < d->m_numTetrahedra; ++i)
		{
			const SoftBodyTetraData& td = d->m_tetrahedra[i];
			psb->appendTetra(td.m_nodeIndices[0], td.m_nodeIndices[1], td.m_nodeIndices[2], td.m_nodeIndices[3],
			                 material(td.m_material));
			btSoftBody::Tetra& tetra = psb->m_tetras[psb->m_tetras.size() - 1];
			for (int j = 0; j < 4; ++j) readVector(tetra.m_c0[j], td.m_c0[j]);
			tetra.m_rv = td.m_restVolume;
			tetra.m_c1 = td.m_c1;
			tetra.m_c2 = td.m_c2;
		}
		for (int i = 0; i < d->m_numAnchors; ++i)
		{
			const SoftRigidAnchorData& ad = d->m_anchors[i];
			btCollisionObject** object = ad.m_rigidBody ? m_bodyMap.find(btHashPtr(ad.m_rigidBody)) : 0;
			btRigidBody* body = object ? btRigidBody::upcast(*object) : 0;
			if (!body)
			{
				warn("soft body " + std::to_string(b) + ": anchor " + std::to_string(i) +
				     " names no rigid body of the file; it is skipped");
				continue;
			}
			btVector3 local;
			readVector(local, ad.m_localFrame);
			psb->appendAnchor(ad.m_nodeIndex, body, local);
			btSoftBody::Anchor& anchor = psb->m_anchors[psb->m_anchors.size() - 1];
			anchor.m_c0.deSerializeFloat(ad.m_c0);
			readVector(anchor.m_c1, ad.m_c1);
			anchor.m_c2 = ad.m_c2;
		}
		// appendNode and appendAnchor set the masses and attach flags their way; the file's values win.
		for (int i = 0; i < d->m_numNodes; ++i)
		{
			psb->m_nodes[i].m_im = d->m_nodes[i].m_inverseMass;
			psb->m_nodes[i].m_battach = d->m_nodes[i].m_attach ? 1 : 0;
		}
		const SoftBodyConfigData& c = d->m_config;
		if (c.m_aeroModel >= 0 && c.m_aeroModel < btSoftBody::eAeroModel::END)
			psb->m_cfg.aeromodel = btSoftBody::eAeroModel::_(c.m_aeroModel);
		else
			warn("soft body " + std::to_string(b) + " has an unknown aerodynamic model; V_Point is used");
		psb->m_cfg.kVCF = c.m_baumgarte;
		psb->m_cfg.kDP = c.m_damping;
		psb->m_cfg.kDG = c.m_drag;
		psb->m_cfg.kLF = c.m_lift;
		psb->m_cfg.kPR = c.m_pressure;
		psb->m_cfg.kVC = c.m_volume;
		psb->m_cfg.kDF = c.m_dynamicFriction;
		psb->m_cfg.kMT = c.m_poseMatch;
		psb->m_cfg.kCHR = c.m_rigidContactHardness;
		psb->m_cfg.kKHR = c.m_kineticContactHardness;
		psb->m_cfg.kSHR = c.m_softContactHardness;
		psb->m_cfg.kAHR = c.m_anchorHardness;
		psb->m_cfg.kSRHR_CL = c.m_softRigidClusterHardness;
		psb->m_cfg.kSKHR_CL = c.m_softKineticClusterHardness;
		psb->m_cfg.kSSHR_CL = c.m_softSoftClusterHardness;
		psb->m_cfg.kSR_SPLT_CL = c.m_softRigidClusterImpulseSplit;
		psb->m_cfg.kSK_SPLT_CL = c.m_softKineticClusterImpulseSplit;
		psb->m_cfg.kSS_SPLT_CL = c.m_softSoftClusterImpulseSplit;
		psb->m_cfg.maxvolume = c.m_maxVolume;
		psb->m_cfg.timescale = c.m_timeScale;
		// Iteration counts below 0 are nonsense: 0 (the step clamps what it needs).
		psb->m_cfg.viterations = c.m_velocityIterations > 0 ? c.m_velocityIterations : 0;
		psb->m_cfg.piterations = c.m_positionIterations > 0 ? c.m_positionIterations : 0;
		psb->m_cfg.diterations = c.m_driftIterations > 0 ? c.m_driftIterations : 0;
		psb->m_cfg.citerations = c.m_clusterIterations > 0 ? c.m_clusterIterations : 0;
		psb->m_cfg.collisions = c.m_collisionFlags;
		if (const SoftBodyPoseData* p = d->m_pose)
		{
			psb->m_pose.m_rot.deSerializeFloat(p->m_rot);
			psb->m_pose.m_scl.deSerializeFloat(p->m_scale);
			psb->m_pose.m_aqq.deSerializeFloat(p->m_aqq);
			readVector(psb->m_pose.m_com, p->m_com);
			psb->m_pose.m_pos.resize(p->m_numPositions);
			for (int i = 0; i < p->m_numPositions; ++i) readVector(psb->m_pose.m_pos[i], p->m_positions[i]);
			psb->m_pose.m_wgh.resize(p->m_numWeigts);
			for (int i = 0; i < p->m_numWeigts; ++i) psb->m_pose.m_wgh[i] = p->m_weights[i];
			psb->m_pose.m_bvolume = p->m_bvolume != 0;
			psb->m_pose.m_bframe = p->m_bframe != 0;
			psb->m_pose.m_volume = p->m_restVolume;
		}
		for (int i = 0; i < d->m_numClusters; ++i)
		{
			const SoftBodyClusterData& cd = d->m_clusters[i];
			btSoftBody::Cluster* cl = caliber::appendCluster(*psb);
			readClusterMotion(*cl, cd);
			cl->m_locii.deSerializeFloat(cd.m_locii);
			for (int j = 0; j < 2; ++j)
			{
				readVector(cl->m_vimpulses[j], cd.m_vimpulses[j]);
				readVector(cl->m_dimpulses[j], cd.m_dimpulses[j]);
			}
			cl->m_framerefs.resize(cd.m_numFrameRefs);
			for (int j = 0; j < cd.m_numFrameRefs; ++j) readVector(cl->m_framerefs[j], cd.m_framerefs[j]);
			cl->m_nodes.resize(cd.m_numNodes);
			for (int j = 0; j < cd.m_numNodes; ++j) cl->m_nodes[j] = &psb->m_nodes[cd.m_nodeIndices[j]];
			cl->m_masses.resize(cd.m_numMasses);
			for (int j = 0; j < cd.m_numMasses; ++j) cl->m_masses[j] = cd.m_masses[j];
			cl->m_idmass = cd.m_idmass;
			cl->m_imass = cd.m_imass;
			cl->m_nvimpulses = cd.m_nvimpulses;
			cl->m_ndimpulses = cd.m_ndimpulses;
			cl->m_ndamping = cd.m_ndamping;
			cl->m_ldamping = cd.m_ldamping;
			cl->m_adamping = cd.m_adamping;
			cl->m_matching = cd.m_matching;
			cl->m_maxSelfCollisionImpulse = cd.m_maxSelfCollisionImpulse;
			cl->m_selfCollisionImpulseFactor = cd.m_selfCollisionImpulseFactor;
			cl->m_containsAnchor = cd.m_containsAnchor != 0;
			cl->m_collide = cd.m_collide != 0;
		}
		// Clusters sharing a node are neighbours (self-collision skips them), as generateClusters records.
		const int count = psb->m_clusters.size();
		psb->m_clusterConnectivity.resize(count * count);
		for (int i = 0; i < count * count; ++i) psb->m_clusterConnectivity[i] = false;
		if (count > 0)
		{
			btAlignedObjectArray<btAlignedObjectArray<int>> memberOf;
			memberOf.resize(psb->m_nodes.size());
			for (int i = 0; i < count; ++i)
				for (int j = 0; j < psb->m_clusters[i]->m_nodes.size(); ++j)
				{
					btAlignedObjectArray<int>& m = memberOf[int(psb->m_clusters[i]->m_nodes[j] - &psb->m_nodes[0])];
					if (m.size() == 0 || m[m.size() - 1] != i) m.push_back(i);
				}
			for (int n = 0; n < memberOf.size(); ++n)
				for (int a = 0; a < memberOf[n].size(); ++a)
					for (int bb = 0; bb < memberOf[n].size(); ++bb)
						psb->m_clusterConnectivity[memberOf[n][a] + memberOf[n][bb] * count] = true;
		}
		// The collision object part.
		const btCollisionObjectFloatData& o = d->m_collisionObjectData;
		btTransform t;
		t.deSerializeFloat(o.m_worldTransform);
		psb->setWorldTransform(t);
		t.deSerializeFloat(o.m_interpolationWorldTransform);
		psb->setInterpolationWorldTransform(t);
		psb->setFriction(o.m_friction);
		psb->setRestitution(o.m_restitution);
		psb->setRollingFriction(o.m_rollingFriction);
		psb->setContactProcessingThreshold(o.m_contactProcessingThreshold);
		psb->setCcdMotionThreshold(o.m_ccdMotionThreshold);
		psb->setCcdSweptSphereRadius(o.m_ccdSweptSphereRadius);
		psb->setHitFraction(o.m_hitFraction);
		psb->setCollisionFlags(o.m_collisionFlags);
		psb->setDeactivationTime(o.m_deactivationTime);
		if (o.m_activationState1 >= ACTIVE_TAG && o.m_activationState1 <= DISABLE_SIMULATION)
			psb->forceActivationState(o.m_activationState1);
		psb->updateBounds();
		m_softBodies.push_back(psb);
		m_softBodyMap.insert(btHashPtr(d), psb);
		if (d->m_numClusters > 0) m_clusterBodyMap.insert(btHashPtr(d->m_clusters), psb);
		if (m_softRigidWorld)
		{
			if (o.m_collisionFilterGroup || o.m_collisionFilterMask)
				m_softRigidWorld->addSoftBody(psb, o.m_collisionFilterGroup, o.m_collisionFilterMask);
			else
				m_softRigidWorld->addSoftBody(psb);
		}
	}
	// Joints, once every body exists (a side may name another body's cluster). A side naming a cluster
	// finds only a body's first cluster (the array's id; other clusters have no chunk): side A is this
	// body's first cluster, as in Bullet.
	for (int b = 0; b < file->m_softBodies.size(); ++b)
	{
		btSoftBody** found = m_softBodyMap.find(btHashPtr(static_cast<void*>(file->m_softBodies[b])));
		if (!found) continue;
		btSoftBody* psb = *found;
		const btSoftBodyFloatData* d = reinterpret_cast<const btSoftBodyFloatData*>(file->m_softBodies[b]);
		for (int i = 0; i < d->m_numJoints; ++i)
		{
			const btSoftBodyJointData& jd = d->m_joints[i];
			const std::string where = "soft body " + std::to_string(b) + ": joint " + std::to_string(i);
			if (jd.m_jointType != btSoftBody::Joint::eType::Linear &&
			    jd.m_jointType != btSoftBody::Joint::eType::Angular)
				continue;  // contact joints live for a step; not rebuilt
			if (psb->m_clusters.size() == 0 || jd.m_bodyAtype != BT_JOINT_SOFT_BODY_CLUSTER)
			{
				warn(where + " is not on a cluster of its body; it is skipped");
				continue;
			}
			// A side names a cluster by its address, and only the first cluster's address is a chunk id
			// (the cluster array's): a joint on another cluster cannot be told where it was, so it is not
			// moved to the first one silently.
			if (jd.m_bodyA != static_cast<void*>(d->m_clusters))
			{
				warn(where +
				     " is on a cluster other than its body's first, which the format cannot name (only the "
				     "first cluster's address is a chunk id); it is skipped");
				continue;
			}
			btSoftBody::Body other;
			bool ok = true;
			switch (jd.m_bodyBtype)
			{
				case 0:
					ok = jd.m_bodyB == 0;
					break;
				case BT_JOINT_SOFT_BODY_CLUSTER:
				{
					btSoftBody** sb = jd.m_bodyB ? m_clusterBodyMap.find(btHashPtr(jd.m_bodyB)) : 0;
					ok = sb != 0;
					if (ok) other = btSoftBody::Body((*sb)->m_clusters[0]);
					break;
				}
				case BT_JOINT_RIGID_BODY:
				case BT_JOINT_COLLISION_OBJECT:
				{
					btCollisionObject** co = jd.m_bodyB ? m_bodyMap.find(btHashPtr(jd.m_bodyB)) : 0;
					ok = co != 0;
					if (ok) other = btSoftBody::Body(*co);
					break;
				}
				default:
					ok = false;
			}
			if (!ok)
			{
				warn(where +
				     "'s other side is not an object of the file (or a cluster other than a body's first, "
				     "which the format cannot name); it is skipped");
				continue;
			}
			btSoftBody::Cluster* first = psb->m_clusters[0];
			btVector3 refA;
			readVector(refA, jd.m_refs[0]);
			// What appending would assert on (a joint to its own cluster, a zero axis) is file data here.
			if (other.m_soft == first ||
			    (jd.m_jointType == btSoftBody::Joint::eType::Angular && !(refA.length2() > SIMD_EPSILON)))
			{
				warn(where + " joins a cluster to itself or has a zero axis; it is skipped");
				continue;
			}
			const int before = psb->m_joints.size();
			if (jd.m_jointType == btSoftBody::Joint::eType::Linear)
			{
				btSoftBody::LJoint::Specs specs;
				btVector3 ref;
				readVector(ref, jd.m_refs[0]);
				specs.position = first->m_framexform * ref;
				specs.erp = jd.m_erp;
				specs.cfm = jd.m_cfm;
				specs.split = jd.m_split;
				psb->appendLinearJoint(specs, first, other);
			}
			else
			{
				btSoftBody::AJoint::Specs specs;
				btVector3 ref;
				readVector(ref, jd.m_refs[0]);
				specs.axis = first->m_framexform.getBasis() * ref;
				specs.erp = jd.m_erp;
				specs.cfm = jd.m_cfm;
				specs.split = jd.m_split;
				psb->appendAngularJoint(specs, first, other);
			}
			if (psb->m_joints.size() == before) continue;
			// The stored references and state win over the ones computed from the frames.
			btSoftBody::Joint* joint = psb->m_joints[psb->m_joints.size() - 1];
			readVector(joint->m_refs[0], jd.m_refs[0]);
			readVector(joint->m_refs[1], jd.m_refs[1]);
			joint->m_delete = jd.m_delete != 0;
			if (jd.m_jointType == btSoftBody::Joint::eType::Linear)
			{
				btSoftBody::LJoint* l = static_cast<btSoftBody::LJoint*>(joint);
				readVector(l->m_rpos[0], jd.m_relPosition[0]);
				readVector(l->m_rpos[1], jd.m_relPosition[1]);
			}
		}
	}
	for (int b = 0; b < file->m_softBodies.size(); ++b)
	{
		btSoftBody** found = m_softBodyMap.find(btHashPtr(static_cast<void*>(file->m_softBodies[b])));
		if (!found) continue;
		const btSoftBodyFloatData* d = reinterpret_cast<const btSoftBodyFloatData*>(file->m_softBodies[b]);
		for (int i = 0; i < d->m_numClusters; ++i) readClusterMotion(*(*found)->m_clusters[i], d->m_clusters[i]);
	}
	return true;
}
