// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// Writing soft bodies into .bullet files (docs/serialization.md, "Soft bodies"): btSoftBodyFloatData
// with its parts as array chunks, in Bullet's single-precision layout in every build.
#include "BulletSoftBody/btSoftBody.h"
#include "BulletSoftBody/btSoftBodyData.h"
#include "BulletSoftBody/btSoftRigidDynamicsWorld.h"
#include "LinearMath/btSerializer.h"
#include "LinearMath/btWarningHook.h"

#include <string.h>

namespace
{
// The collision object part in single precision. A double build's btCollisionObject::serialize writes
// the double layout, which is converted here field by field.
void writeCollisionObjectFloat(const btCollisionObject& object, btCollisionObjectFloatData& out,
                               btSerializer* serializer)
{
#ifdef BT_USE_DOUBLE_PRECISION
	btCollisionObjectDoubleData d;
	memset(&d, 0, sizeof(d));
	object.btCollisionObject::serialize(&d, serializer);
	out.m_broadphaseHandle = d.m_broadphaseHandle;
	out.m_collisionShape = d.m_collisionShape;
	out.m_rootCollisionShape = d.m_rootCollisionShape;
	out.m_name = d.m_name;
	btTransform t;
	t.deSerializeDouble(d.m_worldTransform);
	t.serializeFloat(out.m_worldTransform);
	t.deSerializeDouble(d.m_interpolationWorldTransform);
	t.serializeFloat(out.m_interpolationWorldTransform);
	btVector3 v;
	v.deSerializeDouble(d.m_interpolationLinearVelocity);
	v.serializeFloat(out.m_interpolationLinearVelocity);
	v.deSerializeDouble(d.m_interpolationAngularVelocity);
	v.serializeFloat(out.m_interpolationAngularVelocity);
	v.deSerializeDouble(d.m_anisotropicFriction);
	v.serializeFloat(out.m_anisotropicFriction);
	out.m_contactProcessingThreshold = float(d.m_contactProcessingThreshold);
	out.m_deactivationTime = float(d.m_deactivationTime);
	out.m_friction = float(d.m_friction);
	out.m_rollingFriction = float(d.m_rollingFriction);
	out.m_contactDamping = float(d.m_contactDamping);
	out.m_contactStiffness = float(d.m_contactStiffness);
	out.m_restitution = float(d.m_restitution);
	out.m_hitFraction = float(d.m_hitFraction);
	out.m_ccdSweptSphereRadius = float(d.m_ccdSweptSphereRadius);
	out.m_ccdMotionThreshold = float(d.m_ccdMotionThreshold);
	out.m_hasAnisotropicFriction = d.m_hasAnisotropicFriction;
	out.m_collisionFlags = d.m_collisionFlags;
	out.m_islandTag1 = d.m_islandTag1;
	out.m_companionId = d.m_companionId;
	out.m_activationState1 = d.m_activationState1;
	out.m_internalType = d.m_internalType;
	out.m_checkCollideWith = d.m_checkCollideWith;
	out.m_collisionFilterGroup = d.m_collisionFilterGroup;
	out.m_collisionFilterMask = d.m_collisionFilterMask;
	out.m_uniqueId = d.m_uniqueId;
#else
	object.btCollisionObject::serialize(&out, serializer);
#endif
}

// Index of a node of body in m_nodes (-1 for null).
int nodeIndex(const btSoftBody& body, const btSoftBody::Node* node)
{
	if (!node || body.m_nodes.size() == 0) return -1;
	return int(node - &body.m_nodes[0]);
}

void* uid(btSerializer* serializer, const void* p)
{
	return p ? serializer->getUniquePointer(const_cast<void*>(p)) : 0;
}

// A chunk of count structs of type T, with the id of the object at key; 0 when count is 0.
template <class T>
T* beginArray(btSerializer* serializer, int count, btChunk*& chunk)
{
	chunk = count > 0 ? serializer->allocate(sizeof(T), count) : 0;
	return chunk ? static_cast<T*>(chunk->m_oldPtr) : 0;
}

void writeBody(const btSoftBody::Body& body, void*& pointer, int& type, btSerializer* serializer)
{
	pointer = 0;
	type = 0;
	if (body.m_soft)
	{
		type = BT_JOINT_SOFT_BODY_CLUSTER;
		pointer = uid(serializer, body.m_soft);
	}
	else if (body.m_rigid)
	{
		type = BT_JOINT_RIGID_BODY;
		pointer = uid(serializer, body.m_rigid);
	}
	else if (body.m_collisionObject)
	{
		type = BT_JOINT_COLLISION_OBJECT;
		pointer = uid(serializer, body.m_collisionObject);
	}
}
}  // namespace

int btSoftBody::calculateSerializeBufferSize() const { return int(sizeof(btSoftBodyFloatData)); }

const char* btSoftBody::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btSoftBodyFloatData* sbd = static_cast<btSoftBodyFloatData*>(dataBuffer);
	writeCollisionObjectFloat(*this, sbd->m_collisionObjectData, serializer);
	btChunk* chunk = 0;

	// Materials: an array of pointers (Bullet's layout), each material a chunk of its own.
	sbd->m_numMaterials = m_materials.size();
	sbd->m_materials = static_cast<SoftBodyMaterialData**>(sbd->m_numMaterials ? uid(serializer, &m_materials) : 0);
	if (sbd->m_materials)
	{
		chunk = serializer->allocate(sizeof(SoftBodyMaterialData*), m_materials.size());
		if (chunk)
		{
			SoftBodyMaterialData** pointers = static_cast<SoftBodyMaterialData**>(chunk->m_oldPtr);
			for (int i = 0; i < m_materials.size(); ++i)
			{
				const Material* mat = m_materials[i];
				pointers[i] = static_cast<SoftBodyMaterialData*>(uid(serializer, mat));
				if (!mat || serializer->findPointer(const_cast<Material*>(mat))) continue;
				btChunk* matChunk = serializer->allocate(sizeof(SoftBodyMaterialData), 1);
				if (!matChunk) continue;
				SoftBodyMaterialData* m = static_cast<SoftBodyMaterialData*>(matChunk->m_oldPtr);
				m->m_linearStiffness = float(mat->m_kLST);
				m->m_angularStiffness = float(mat->m_kAST);
				m->m_volumeStiffness = float(mat->m_kVST);
				m->m_flags = mat->m_flags;
				serializer->finalizeChunk(matChunk, "SoftBodyMaterialData", BT_SBMATERIAL_CODE,
				                          const_cast<Material*>(mat));
			}
			serializer->finalizeChunk(chunk, "SoftBodyMaterialData", BT_ARRAY_CODE,
			                          const_cast<tMaterialArray*>(&m_materials));
		}
	}

	sbd->m_numNodes = m_nodes.size();
	sbd->m_nodes = static_cast<SoftBodyNodeData*>(m_nodes.size() ? uid(serializer, &m_nodes[0]) : 0);
	if (SoftBodyNodeData* n = beginArray<SoftBodyNodeData>(serializer, m_nodes.size(), chunk))
	{
		for (int i = 0; i < m_nodes.size(); ++i, ++n)
		{
			const Node& node = m_nodes[i];
			n->m_material = static_cast<SoftBodyMaterialData*>(uid(serializer, node.m_material));
			node.m_x.serializeFloat(n->m_position);
			node.m_q.serializeFloat(n->m_previousPosition);
			node.m_v.serializeFloat(n->m_velocity);
			node.m_f.serializeFloat(n->m_accumulatedForce);
			node.m_n.serializeFloat(n->m_normal);
			n->m_inverseMass = float(node.m_im);
			n->m_area = float(node.m_area);
			n->m_attach = node.m_battach ? 1 : 0;
			n->m_pad = 0;
		}
		serializer->finalizeChunk(chunk, "SoftBodyNodeData", BT_ARRAY_CODE, const_cast<Node*>(&m_nodes[0]));
	}

	sbd->m_numLinks = m_links.size();
	sbd->m_links = static_cast<SoftBodyLinkData*>(m_links.size() ? uid(serializer, &m_links[0]) : 0);
	if (SoftBodyLinkData* l = beginArray<SoftBodyLinkData>(serializer, m_links.size(), chunk))
	{
		for (int i = 0; i < m_links.size(); ++i, ++l)
		{
			const Link& link = m_links[i];
			l->m_material = static_cast<SoftBodyMaterialData*>(uid(serializer, link.m_material));
			l->m_nodeIndices[0] = nodeIndex(*this, link.m_n[0]);
			l->m_nodeIndices[1] = nodeIndex(*this, link.m_n[1]);
			l->m_restLength = float(link.m_rl);
			l->m_bbending = link.m_bbending ? 1 : 0;
		}
		serializer->finalizeChunk(chunk, "SoftBodyLinkData", BT_ARRAY_CODE, const_cast<Link*>(&m_links[0]));
	}

	sbd->m_numFaces = m_faces.size();
	sbd->m_faces = static_cast<SoftBodyFaceData*>(m_faces.size() ? uid(serializer, &m_faces[0]) : 0);
	if (SoftBodyFaceData* f = beginArray<SoftBodyFaceData>(serializer, m_faces.size(), chunk))
	{
		for (int i = 0; i < m_faces.size(); ++i, ++f)
		{
			const Face& face = m_faces[i];
			face.m_normal.serializeFloat(f->m_normal);
			f->m_material = static_cast<SoftBodyMaterialData*>(uid(serializer, face.m_material));
			for (int j = 0; j < 3; ++j) f->m_nodeIndices[j] = nodeIndex(*this, face.m_n[j]);
			f->m_restArea = float(face.m_ra);
		}
		serializer->finalizeChunk(chunk, "SoftBodyFaceData", BT_ARRAY_CODE, const_cast<Face*>(&m_faces[0]));
	}

	sbd->m_numTetrahedra = m_tetras.size();
	sbd->m_tetrahedra = static_cast<SoftBodyTetraData*>(m_tetras.size() ? uid(serializer, &m_tetras[0]) : 0);
	if (SoftBodyTetraData* t = beginArray<SoftBodyTetraData>(serializer, m_tetras.size(), chunk))
	{
		for (int i = 0; i < m_tetras.size(); ++i, ++t)
		{
			const Tetra& tetra = m_tetras[i];
			for (int j = 0; j < 4; ++j) tetra.m_c0[j].serializeFloat(t->m_c0[j]);
			t->m_material = static_cast<SoftBodyMaterialData*>(uid(serializer, tetra.m_material));
			for (int j = 0; j < 4; ++j) t->m_nodeIndices[j] = nodeIndex(*this, tetra.m_n[j]);
			t->m_restVolume = float(tetra.m_rv);
			t->m_c1 = float(tetra.m_c1);
			t->m_c2 = float(tetra.m_c2);
			t->m_pad = 0;
		}
		serializer->finalizeChunk(chunk, "SoftBodyTetraData", BT_ARRAY_CODE, const_cast<Tetra*>(&m_tetras[0]));
	}

	sbd->m_numAnchors = m_anchors.size();
	sbd->m_anchors = static_cast<SoftRigidAnchorData*>(m_anchors.size() ? uid(serializer, &m_anchors[0]) : 0);
	if (SoftRigidAnchorData* a = beginArray<SoftRigidAnchorData>(serializer, m_anchors.size(), chunk))
	{
		for (int i = 0; i < m_anchors.size(); ++i, ++a)
		{
			const Anchor& anchor = m_anchors[i];
			anchor.m_c0.serializeFloat(a->m_c0);
			anchor.m_c1.serializeFloat(a->m_c1);
			anchor.m_local.serializeFloat(a->m_localFrame);
			a->m_rigidBody = static_cast<btRigidBodyData*>(uid(serializer, anchor.m_body));
			a->m_nodeIndex = nodeIndex(*this, anchor.m_node);
			a->m_c2 = float(anchor.m_c2);
		}
		serializer->finalizeChunk(chunk, "SoftRigidAnchorData", BT_ARRAY_CODE, const_cast<Anchor*>(&m_anchors[0]));
	}

	SoftBodyConfigData& c = sbd->m_config;
	c.m_aeroModel = int(m_cfg.aeromodel);
	c.m_baumgarte = float(m_cfg.kVCF);
	c.m_damping = float(m_cfg.kDP);
	c.m_drag = float(m_cfg.kDG);
	c.m_lift = float(m_cfg.kLF);
	c.m_pressure = float(m_cfg.kPR);
	c.m_volume = float(m_cfg.kVC);
	c.m_dynamicFriction = float(m_cfg.kDF);
	c.m_poseMatch = float(m_cfg.kMT);
	c.m_rigidContactHardness = float(m_cfg.kCHR);
	c.m_kineticContactHardness = float(m_cfg.kKHR);
	c.m_softContactHardness = float(m_cfg.kSHR);
	c.m_anchorHardness = float(m_cfg.kAHR);
	c.m_softRigidClusterHardness = float(m_cfg.kSRHR_CL);
	c.m_softKineticClusterHardness = float(m_cfg.kSKHR_CL);
	c.m_softSoftClusterHardness = float(m_cfg.kSSHR_CL);
	c.m_softRigidClusterImpulseSplit = float(m_cfg.kSR_SPLT_CL);
	c.m_softKineticClusterImpulseSplit = float(m_cfg.kSK_SPLT_CL);
	c.m_softSoftClusterImpulseSplit = float(m_cfg.kSS_SPLT_CL);
	c.m_maxVolume = float(m_cfg.maxvolume);
	c.m_timeScale = float(m_cfg.timescale);
	c.m_velocityIterations = m_cfg.viterations;
	c.m_positionIterations = m_cfg.piterations;
	c.m_driftIterations = m_cfg.diterations;
	c.m_clusterIterations = m_cfg.citerations;
	c.m_collisionFlags = m_cfg.collisions;

	// The pose: always written (a body without setPose has empty arrays and both flags off).
	sbd->m_pose = static_cast<SoftBodyPoseData*>(uid(serializer, &m_pose));
	if (SoftBodyPoseData* p = beginArray<SoftBodyPoseData>(serializer, 1, chunk))
	{
		m_pose.m_rot.serializeFloat(p->m_rot);
		m_pose.m_scl.serializeFloat(p->m_scale);
		m_pose.m_aqq.serializeFloat(p->m_aqq);
		m_pose.m_com.serializeFloat(p->m_com);
		p->m_numPositions = m_pose.m_pos.size();
		p->m_numWeigts = m_pose.m_wgh.size();
		p->m_bvolume = m_pose.m_bvolume ? 1 : 0;
		p->m_bframe = m_pose.m_bframe ? 1 : 0;
		p->m_restVolume = float(m_pose.m_volume);
		p->m_pad = 0;
		p->m_positions = static_cast<btVector3FloatData*>(m_pose.m_pos.size() ? uid(serializer, &m_pose.m_pos[0]) : 0);
		btChunk* arrayChunk = 0;
		if (btVector3FloatData* v = beginArray<btVector3FloatData>(serializer, m_pose.m_pos.size(), arrayChunk))
		{
			for (int i = 0; i < m_pose.m_pos.size(); ++i) m_pose.m_pos[i].serializeFloat(v[i]);
			serializer->finalizeChunk(arrayChunk, "btVector3FloatData", BT_ARRAY_CODE,
			                          const_cast<btVector3*>(&m_pose.m_pos[0]));
		}
		p->m_weights = static_cast<float*>(m_pose.m_wgh.size() ? uid(serializer, &m_pose.m_wgh[0]) : 0);
		if (float* w = beginArray<float>(serializer, m_pose.m_wgh.size(), arrayChunk))
		{
			for (int i = 0; i < m_pose.m_wgh.size(); ++i) w[i] = float(m_pose.m_wgh[i]);
			serializer->finalizeChunk(arrayChunk, "float", BT_ARRAY_CODE, const_cast<btScalar*>(&m_pose.m_wgh[0]));
		}
		serializer->finalizeChunk(chunk, "SoftBodyPoseData", BT_ARRAY_CODE, const_cast<Pose*>(&m_pose));
	}

	// Clusters: the array's id is the first cluster's, so that a joint side naming that cluster finds
	// the array (Bullet's convention; other clusters have no chunk of their own).
	sbd->m_numClusters = m_clusters.size();
	sbd->m_clusters = static_cast<SoftBodyClusterData*>(m_clusters.size() ? uid(serializer, m_clusters[0]) : 0);
	if (SoftBodyClusterData* cd = beginArray<SoftBodyClusterData>(serializer, m_clusters.size(), chunk))
	{
		for (int i = 0; i < m_clusters.size(); ++i, ++cd)
		{
			const Cluster& cl = *m_clusters[i];
			cl.m_framexform.serializeFloat(cd->m_framexform);
			cl.m_locii.serializeFloat(cd->m_locii);
			cl.m_invwi.serializeFloat(cd->m_invwi);
			cl.m_com.serializeFloat(cd->m_com);
			for (int j = 0; j < 2; ++j)
			{
				cl.m_vimpulses[j].serializeFloat(cd->m_vimpulses[j]);
				cl.m_dimpulses[j].serializeFloat(cd->m_dimpulses[j]);
			}
			cl.m_lv.serializeFloat(cd->m_lv);
			cl.m_av.serializeFloat(cd->m_av);
			cd->m_numFrameRefs = cl.m_framerefs.size();
			cd->m_numNodes = cl.m_nodes.size();
			cd->m_numMasses = cl.m_masses.size();
			btChunk* arrayChunk = 0;
			cd->m_framerefs =
			    static_cast<btVector3FloatData*>(cl.m_framerefs.size() ? uid(serializer, &cl.m_framerefs[0]) : 0);
			if (btVector3FloatData* v = beginArray<btVector3FloatData>(serializer, cl.m_framerefs.size(), arrayChunk))
			{
				for (int j = 0; j < cl.m_framerefs.size(); ++j) cl.m_framerefs[j].serializeFloat(v[j]);
				serializer->finalizeChunk(arrayChunk, "btVector3FloatData", BT_ARRAY_CODE,
				                          const_cast<btVector3*>(&cl.m_framerefs[0]));
			}
			cd->m_nodeIndices = static_cast<int*>(cl.m_nodes.size() ? uid(serializer, &cl.m_nodes[0]) : 0);
			if (int* idx = beginArray<int>(serializer, cl.m_nodes.size(), arrayChunk))
			{
				for (int j = 0; j < cl.m_nodes.size(); ++j) idx[j] = nodeIndex(*this, cl.m_nodes[j]);
				serializer->finalizeChunk(arrayChunk, "int", BT_ARRAY_CODE, const_cast<Node**>(&cl.m_nodes[0]));
			}
			cd->m_masses = static_cast<float*>(cl.m_masses.size() ? uid(serializer, &cl.m_masses[0]) : 0);
			if (float* w = beginArray<float>(serializer, cl.m_masses.size(), arrayChunk))
			{
				for (int j = 0; j < cl.m_masses.size(); ++j) w[j] = float(cl.m_masses[j]);
				serializer->finalizeChunk(arrayChunk, "float", BT_ARRAY_CODE, const_cast<btScalar*>(&cl.m_masses[0]));
			}
			cd->m_idmass = float(cl.m_idmass);
			cd->m_imass = float(cl.m_imass);
			cd->m_nvimpulses = cl.m_nvimpulses;
			cd->m_ndimpulses = cl.m_ndimpulses;
			cd->m_ndamping = float(cl.m_ndamping);
			cd->m_ldamping = float(cl.m_ldamping);
			cd->m_adamping = float(cl.m_adamping);
			cd->m_matching = float(cl.m_matching);
			cd->m_maxSelfCollisionImpulse = float(cl.m_maxSelfCollisionImpulse);
			cd->m_selfCollisionImpulseFactor = float(cl.m_selfCollisionImpulseFactor);
			cd->m_containsAnchor = cl.m_containsAnchor ? 1 : 0;
			cd->m_collide = cl.m_collide ? 1 : 0;
			cd->m_clusterIndex = cl.m_clusterIndex;
		}
		serializer->finalizeChunk(chunk, "SoftBodyClusterData", BT_ARRAY_CODE, m_clusters[0]);
	}

	sbd->m_numJoints = m_joints.size();
	sbd->m_joints = static_cast<btSoftBodyJointData*>(m_joints.size() ? uid(serializer, &m_joints[0]) : 0);
	if (btSoftBodyJointData* j = beginArray<btSoftBodyJointData>(serializer, m_joints.size(), chunk))
	{
		for (int i = 0; i < m_joints.size(); ++i, ++j)
		{
			const Joint& joint = *m_joints[i];
			writeBody(joint.m_bodies[0], j->m_bodyA, j->m_bodyAtype, serializer);
			writeBody(joint.m_bodies[1], j->m_bodyB, j->m_bodyBtype, serializer);
			joint.m_refs[0].serializeFloat(j->m_refs[0]);
			joint.m_refs[1].serializeFloat(j->m_refs[1]);
			j->m_cfm = float(joint.m_cfm);
			j->m_erp = float(joint.m_erp);
			j->m_split = float(joint.m_split);
			j->m_delete = joint.m_delete ? 1 : 0;
			btVector3 rel[2] = {btVector3(0, 0, 0), btVector3(0, 0, 0)};
			if (joint.Type() == Joint::eType::Linear)
			{
				rel[0] = static_cast<const LJoint&>(joint).m_rpos[0];
				rel[1] = static_cast<const LJoint&>(joint).m_rpos[1];
			}
			else if (joint.Type() == Joint::eType::Contact)
			{
				rel[0] = static_cast<const CJoint&>(joint).m_rpos[0];
				rel[1] = static_cast<const CJoint&>(joint).m_rpos[1];
			}
			rel[0].serializeFloat(j->m_relPosition[0]);
			rel[1].serializeFloat(j->m_relPosition[1]);
			j->m_jointType = int(joint.Type());
			j->m_pad = 0;
		}
		serializer->finalizeChunk(chunk, "btSoftBodyJointData", BT_ARRAY_CODE, const_cast<Joint**>(&m_joints[0]));
	}
	return "btSoftBodyFloatData";
}

void btSoftRigidDynamicsWorld::serializeSoftBodies(btSerializer* serializer)
{
	if (!serializer)
	{
		btAssert(!"btSoftRigidDynamicsWorld::serializeSoftBodies without a serializer");
		btReportWarning(
		    "Caliber: btSoftRigidDynamicsWorld::serializeSoftBodies: no serializer given; nothing was written\n");
		return;
	}
	for (int i = 0; i < m_softBodies.size(); ++i)
	{
		const btSoftBody* body = m_softBodies[i];
		btChunk* chunk = serializer->allocate(size_t(body->calculateSerializeBufferSize()), 1);
		if (!chunk) continue;
		const char* structType = body->serialize(chunk->m_oldPtr, serializer);
		serializer->finalizeChunk(chunk, structType, BT_SOFTBODY_CODE, const_cast<btSoftBody*>(body));
	}
}

void btSoftRigidDynamicsWorld::serialize(btSerializer* serializer)
{
	if (!serializer)
	{
		btAssert(!"btSoftRigidDynamicsWorld::serialize without a serializer");
		btReportWarning("Caliber: btSoftRigidDynamicsWorld::serialize: no serializer given; nothing was written\n");
		return;
	}
	// As btDiscreteDynamicsWorld::serialize, with the soft bodies after the rigid bodies and joints (their
	// anchors and joints name rigid bodies).
	serializer->startSerialization();
	serializeDynamicsWorldInfo(serializer);
	serializeCollisionObjects(serializer);
	serializeRigidBodies(serializer);
	serializeSoftBodies(serializer);
	serializeContactManifolds(serializer);
	serializer->finishSerialization();
}
