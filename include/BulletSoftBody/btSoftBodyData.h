// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SOFTBODY_FLOAT_DATA
#define BT_SOFTBODY_FLOAT_DATA

/// File layouts of soft bodies in .bullet files: Bullet's struct and field names and field order, so that
/// readers map them by name (tools/makedna reads this header into the DNA). Bullet has one layout, in
/// single precision, for every build: a double build writes these floats too (docs/serialization.md,
/// "Soft bodies"). Pointers are ids of other chunks; node references are indices into m_nodes.

#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"

// clang-format off
/// A material (btSoftBody::Material).
struct SoftBodyMaterialData
{
	float m_linearStiffness;   // kLST
	float m_angularStiffness;  // kAST
	float m_volumeStiffness;   // kVST
	int m_flags;
};

/// A node.
struct SoftBodyNodeData
{
	SoftBodyMaterialData *m_material;
	btVector3FloatData m_position;          // m_x
	btVector3FloatData m_previousPosition;  // m_q
	btVector3FloatData m_velocity;          // m_v
	btVector3FloatData m_accumulatedForce;  // m_f
	btVector3FloatData m_normal;            // m_n
	float m_inverseMass;
	float m_area;
	int m_attach;
	int m_pad;
};

/// A link.
struct SoftBodyLinkData
{
	SoftBodyMaterialData *m_material;
	int m_nodeIndices[2];
	float m_restLength;
	int m_bbending;
};

/// A face.
struct SoftBodyFaceData
{
	btVector3FloatData m_normal;
	SoftBodyMaterialData *m_material;
	int m_nodeIndices[3];
	float m_restArea;
};

/// A tetra (with its solver scratch values m_c0, m_c1, m_c2).
struct SoftBodyTetraData
{
	btVector3FloatData m_c0[4];
	SoftBodyMaterialData *m_material;
	int m_nodeIndices[4];
	float m_restVolume;
	float m_c1;
	float m_c2;
	int m_pad;
};

/// An anchor of a node to a rigid body.
struct SoftRigidAnchorData
{
	btMatrix3x3FloatData m_c0;
	btVector3FloatData m_c1;
	btVector3FloatData m_localFrame;  // the point in the body's frame
	btRigidBodyData *m_rigidBody;
	int m_nodeIndex;
	float m_c2;
};

/// btSoftBody::Config (names as Bullet's file calls them; the Config member in the comment).
struct SoftBodyConfigData
{
	int m_aeroModel;
	float m_baumgarte;                       // kVCF
	float m_damping;                         // kDP
	float m_drag;                            // kDG
	float m_lift;                            // kLF
	float m_pressure;                        // kPR
	float m_volume;                          // kVC
	float m_dynamicFriction;                 // kDF
	float m_poseMatch;                       // kMT
	float m_rigidContactHardness;            // kCHR
	float m_kineticContactHardness;          // kKHR
	float m_softContactHardness;             // kSHR
	float m_anchorHardness;                  // kAHR
	float m_softRigidClusterHardness;        // kSRHR_CL
	float m_softKineticClusterHardness;      // kSKHR_CL
	float m_softSoftClusterHardness;         // kSSHR_CL
	float m_softRigidClusterImpulseSplit;    // kSR_SPLT_CL
	float m_softKineticClusterImpulseSplit;  // kSK_SPLT_CL
	float m_softSoftClusterImpulseSplit;     // kSS_SPLT_CL
	float m_maxVolume;
	float m_timeScale;
	int m_velocityIterations;
	int m_positionIterations;
	int m_driftIterations;
	int m_clusterIterations;
	int m_collisionFlags;
};

/// btSoftBody::Pose.
struct SoftBodyPoseData
{
	btMatrix3x3FloatData m_rot;
	btMatrix3x3FloatData m_scale;
	btMatrix3x3FloatData m_aqq;
	btVector3FloatData m_com;
	btVector3FloatData *m_positions;
	float *m_weights;
	int m_numPositions;
	int m_numWeigts;  // (sic: Bullet's field name)
	int m_bvolume;
	int m_bframe;
	float m_restVolume;
	int m_pad;
};

/// A cluster.
struct SoftBodyClusterData
{
	btTransformFloatData m_framexform;
	btMatrix3x3FloatData m_locii;
	btMatrix3x3FloatData m_invwi;
	btVector3FloatData m_com;
	btVector3FloatData m_vimpulses[2];
	btVector3FloatData m_dimpulses[2];
	btVector3FloatData m_lv;
	btVector3FloatData m_av;
	btVector3FloatData *m_framerefs;
	int *m_nodeIndices;
	float *m_masses;
	int m_numFrameRefs;
	int m_numNodes;
	int m_numMasses;
	float m_idmass;
	float m_imass;
	int m_nvimpulses;
	int m_ndimpulses;
	float m_ndamping;
	float m_ldamping;
	float m_adamping;
	float m_matching;
	float m_maxSelfCollisionImpulse;
	float m_selfCollisionImpulseFactor;
	int m_containsAnchor;
	int m_collide;
	int m_clusterIndex;
};

/// What a joint side's pointer refers to (btSoftBodyJointData::m_bodyAtype, m_bodyBtype; 0: the world).
enum btSoftJointBodyType
{
	BT_JOINT_SOFT_BODY_CLUSTER = 1,
	BT_JOINT_RIGID_BODY,
	BT_JOINT_COLLISION_OBJECT
};

/// A joint (btSoftBody::LJoint or AJoint).
struct btSoftBodyJointData
{
	void *m_bodyA;
	void *m_bodyB;
	btVector3FloatData m_refs[2];
	float m_cfm;
	float m_erp;
	float m_split;
	int m_delete;
	btVector3FloatData m_relPosition[2];
	int m_bodyAtype;
	int m_bodyBtype;
	int m_jointType;
	int m_pad;
};

/// A soft body: its collision object, then its parts as arrays of their own chunks.
struct btSoftBodyFloatData
{
	btCollisionObjectFloatData m_collisionObjectData;
	SoftBodyPoseData *m_pose;
	SoftBodyMaterialData **m_materials;
	SoftBodyNodeData *m_nodes;
	SoftBodyLinkData *m_links;
	SoftBodyFaceData *m_faces;
	SoftBodyTetraData *m_tetrahedra;
	SoftRigidAnchorData *m_anchors;
	SoftBodyClusterData *m_clusters;
	btSoftBodyJointData *m_joints;
	int m_numMaterials;
	int m_numNodes;
	int m_numLinks;
	int m_numFaces;
	int m_numTetrahedra;
	int m_numAnchors;
	int m_numClusters;
	int m_numJoints;
	SoftBodyConfigData m_config;
};
// clang-format on

#endif  // BT_SOFTBODY_FLOAT_DATA
