// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef _BT_SOFT_BODY_H
#define _BT_SOFT_BODY_H

/// btSoftBody: cloth, ropes and volumes made of point masses (nodes) held by links, faces and tetras.
/// The solver, the collision model and what differs from Bullet are in docs/soft-bodies.md; bad input
/// in docs/bad-input.md.

#include "BulletCollision/BroadphaseCollision/btDbvt.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "BulletSoftBody/btSparseSDF.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btTransform.h"

class btBroadphaseInterface;
class btDispatcher;
class btSoftBodySolver;
struct btCollisionObjectWrapper;

/// What a soft body knows of its world: media densities, the water plane, gravity and the collision
/// machinery. One is shared by every soft body of a world (btSoftRigidDynamicsWorld::getWorldInfo).
struct btSoftBodyWorldInfo
{
	/// Density of air in kg/m^3, for the aerodynamic forces.
	btScalar air_density;
	/// Density of water in kg/m^3 (0: no water).
	btScalar water_density;
	/// Offset of the water plane along water_normal.
	btScalar water_offset;
	/// Largest distance a node may travel in one step (larger moves are clamped).
	btScalar m_maxDisplacement;
	/// Normal of the water plane.
	btVector3 water_normal;
	/// The broadphase of the world (not owned).
	btBroadphaseInterface* m_broadphase;
	/// The dispatcher of the world (not owned).
	btDispatcher* m_dispatcher;
	/// Gravity acting on the nodes.
	btVector3 m_gravity;
	/// Bullet's distance-field cache (see btSparseSDF.h).
	btSparseSdf<3> m_sparsesdf;

	/// Bullet's defaults: air 1.2 kg/m^3, no water, gravity (0, -10, 0), displacement limit 1000 m.
	btSoftBodyWorldInfo()
	    : air_density(btScalar(1.2)),
	      water_density(0),
	      water_offset(0),
	      m_maxDisplacement(1000.f),
	      water_normal(0, 0, 0),
	      m_broadphase(0),
	      m_dispatcher(0),
	      m_gravity(0, -10, 0)
	{
	}
};

/// A deformable body: nodes (point masses) connected by links (distance springs), faces (cloth and
/// closed surfaces) and tetras (volumes).
class btSoftBody : public btCollisionObject
{
public:
	/// Objects the body never collides with (rigid bodies of anchors added with collisions disabled).
	btAlignedObjectArray<const class btCollisionObject*> m_collisionDisabledObjects;
	/// The solver that steps this body (set by the world; not owned).
	btSoftBodySolver* m_softBodySolver;

	/// How air acts on the body (Config::aeromodel).
	struct eAeroModel
	{
		enum _
		{
			V_Point,             ///< Drag on nodes, from each node's velocity and area.
			V_TwoSided,          ///< Drag and lift on nodes, both sides of the surface.
			V_TwoSidedLiftDrag,  ///< As V_TwoSided.
			V_OneSided,          ///< Drag and lift on nodes, front side only.
			F_TwoSided,          ///< Drag and lift on faces, both sides.
			F_TwoSidedLiftDrag,  ///< As F_TwoSided.
			F_OneSided,          ///< Drag and lift on faces, front side only.
			END
		};
	};
	/// Velocity solvers (Bullet's list; Caliber's step has none, see docs/soft-bodies.md).
	struct eVSolver
	{
		enum _
		{
			Linear,  ///< Links.
			END
		};
	};
	/// Position solvers in the order Config::m_psequence runs them.
	struct ePSolver
	{
		enum _
		{
			Linear,     ///< Links.
			Anchors,    ///< Anchors to rigid bodies.
			RContacts,  ///< Contacts with rigid bodies.
			SContacts,  ///< Contacts with soft bodies.
			END
		};
	};
	/// Presets of setSolver.
	struct eSolverPresets
	{
		enum _
		{
			Positions,   ///< Position solvers only (the default).
			Velocities,  ///< Bullet's velocity preset (Caliber runs the position solvers).
			Default = Positions,
			END
		};
	};
	/// Kinds of feature a ray can hit.
	struct eFeature
	{
		enum _
		{
			None,
			Node,
			Link,
			Face,
			Tetra,
			END
		};
	};

	typedef btAlignedObjectArray<eVSolver::_> tVSolverArray;
	typedef btAlignedObjectArray<ePSolver::_> tPSolverArray;

	/// Collision flags (Config::collisions).
	struct fCollision
	{
		enum _
		{
			RVSmask = 0x000f,   ///< Rigid-versus-soft mask.
			SDF_RS = 0x0001,    ///< Nodes against rigid shapes (the default; Caliber measures shapes directly).
			CL_RS = 0x0002,     ///< Clusters against rigid bodies (the node contacts when the body has no clusters).
			SDF_RD = 0x0004,    ///< Deformable-rigid (Bullet's later solver; not implemented).
			SVSmask = 0x00f0,   ///< Soft-versus-soft mask.
			VF_SS = 0x0010,     ///< Nodes against faces of other soft bodies (either body's flag is enough).
			CL_SS = 0x0020,     ///< Clusters against the clusters of other soft bodies.
			CL_SELF = 0x0040,   ///< Clusters against the body's own clusters that share no node.
			VF_DD = 0x0080,     ///< Deformable vertex-face (not implemented).
			RVDFmask = 0x0f00,  ///< Deformable-rigid mask.
			SDF_RDF = 0x0100,   ///< Deformable faces against rigid (not implemented).
			SDF_MDF = 0x0200,   ///< Deformable faces against multibodies (not implemented).
			SDF_RDN = 0x0400,   ///< Deformable nodes against rigid (not implemented).
			Default = SDF_RS,
			END
		};
	};
	/// Material flags.
	struct fMaterial
	{
		enum _
		{
			DebugDraw = 0x0001,  ///< Links of this material are drawn.
			Default = DebugDraw,
			END
		};
	};

	/// Result of rayTest: the first feature hit.
	struct sRayCast
	{
		btSoftBody* body;     ///< The body hit.
		eFeature::_ feature;  ///< Kind of feature hit.
		int index;            ///< Index of the feature.
		btScalar fraction;    ///< Hit point as a fraction of the ray (from + (to - from) * fraction).
	};
	/// An implicit function for refine (positive outside).
	struct ImplicitFn
	{
		virtual ~ImplicitFn() {}
		/// The function's value at x.
		virtual btScalar Eval(const btVector3& x) = 0;
	};
	/// Where a node touches a rigid object.
	struct sCti
	{
		const btCollisionObject* m_colObj;  ///< The object touched.
		btVector3 m_normal;                 ///< Contact normal, out of the object.
		btScalar m_offset;                  ///< The contact plane: m_normal . x + m_offset = 0.
		btVector3 m_bary;                   ///< Barycentric weights (face contacts; unused by node contacts).
	};
	/// The medium around a point (air or water).
	struct sMedium
	{
		btVector3 m_velocity;  ///< Velocity of the medium.
		btScalar m_pressure;   ///< Pressure of the medium.
		btScalar m_density;    ///< Density of the medium.
	};

	/// Base of every element: a user tag.
	struct Element
	{
		void* m_tag;  ///< User data.
		Element() : m_tag(0) {}
	};
	/// Stiffness of links, bending and volumes.
	struct Material : Element
	{
		btScalar m_kLST;  ///< Linear stiffness, [0, 1]: 1 is inextensible (see docs/soft-bodies.md).
		btScalar m_kAST;  ///< Angular stiffness, [0, 1] (kept for Bullet's API; unused).
		btScalar m_kVST;  ///< Volume stiffness of tetras, [0, 1]: 1 keeps each tetra's volume, 0 switches it off.
		int m_flags;      ///< fMaterial flags.
	};
	/// Base of nodes, links, faces and tetras: their material.
	struct Feature : Element
	{
		Material* m_material;  ///< The material (owned by the body).
	};
	/// A point mass.
	struct Node : Feature
	{
		btVector3 m_x;       ///< Position.
		btVector3 m_q;       ///< Position at the start of the step.
		btVector3 m_v;       ///< Velocity.
		btVector3 m_vn;      ///< Velocity at the start of the step.
		btVector3 m_f;       ///< Force accumulated for the next step.
		btVector3 m_n;       ///< Normal (average of the adjacent faces').
		btScalar m_im;       ///< Inverse mass (0: the node is fixed).
		btScalar m_area;     ///< Area of the surface around the node (a third of each adjacent face's).
		btDbvtNode* m_leaf;  ///< Leaf in the body's node tree (Caliber keeps none: 0).
		int m_battach : 1;   ///< 1 when an anchor holds the node.
		int index;           ///< Index of the node in m_nodes.
	};
	/// A distance constraint between two nodes.
	struct Link : Feature
	{
		btVector3 m_c3;      ///< Bullet's solver scratch (Caliber's solver keeps its own per step, docs/soft-bodies.md).
		Node* m_n[2];        ///< The two nodes.
		btScalar m_rl;       ///< Rest length.
		int m_bbending : 1;  ///< 1 for links made by generateBendingConstraints.
		btScalar m_c0;       ///< Inverse masses of the two nodes (the compliance is m_c0 times a factor of m_kLST).
		btScalar m_c1;       ///< Rest length squared.
		btScalar m_c2;       ///< Bullet's solver scratch (Caliber's solver keeps its own per step, docs/soft-bodies.md).
	};
	/// A triangle of the surface.
	struct Face : Feature
	{
		Node* m_n[3];        ///< The three nodes (counter-clockwise seen from the front).
		btVector3 m_normal;  ///< Unit normal.
		btScalar m_ra;       ///< Rest area.
		btDbvtNode* m_leaf;  ///< Leaf in the face tree (Caliber keeps none: 0).
		int m_index;         ///< Index of the face in m_faces.
	};
	/// A tetrahedron of a volume.
	struct Tetra : Feature
	{
		Node* m_n[4];        ///< The four nodes.
		btScalar m_rv;       ///< Rest volume.
		btDbvtNode* m_leaf;  ///< Leaf in the tetra tree (Caliber keeps none: 0).
		btVector3 m_c0[4];   ///< Volume gradients (scratch of the solver).
		btScalar m_c1;       ///< Sum of im_i |dV/dx_i|^2 (the compliance is m_c1 times a factor of m_kVST).
		btScalar m_c2;       ///< Scratch of the solver (the accumulated multiplier of the step).
	};
	/// A contact of a node with a rigid object, found this step.
	struct RContact
	{
		sCti m_cti;        ///< The object and the contact plane.
		Node* m_node;      ///< The node.
		btMatrix3x3 m_c0;  ///< Scratch.
		btVector3 m_c1;    ///< Contact point in the object's frame.
		btScalar m_c2;     ///< Inverse mass of the node.
		btScalar m_c3;     ///< Friction (the product of kDF and the object's friction).
		btScalar m_c4;     ///< Hardness (kCHR, kKHR or kSHR by the object's kind).
	};
	/// A contact of a node with a face of another soft body (VF_SS), found this step.
	struct SContact
	{
		Node* m_node;         ///< The node.
		Face* m_face;         ///< The face.
		btVector3 m_weights;  ///< Barycentric weights of the contact point on the face.
		btVector3 m_normal;   ///< Contact normal.
		btScalar m_margin;    ///< Distance kept between the node and the face.
		btScalar m_friction;  ///< Coulomb friction (the larger kDF of the two bodies).
		btScalar m_cfm[2];  ///< m_cfm[0]: the side of the face (+1 or -1 along its winding normal) the node is kept on.
	};
	/// A node held at a point of a rigid body; the body is pulled back (two-way).
	struct Anchor
	{
		Node* m_node;          ///< The node.
		btVector3 m_local;     ///< The point in the body's frame.
		btRigidBody* m_body;   ///< The body.
		btScalar m_influence;  ///< How much of the node's pull reaches the body, [0, 1].
		btMatrix3x3 m_c0;      ///< Scratch.
		btVector3 m_c1;        ///< Scratch: the point relative to the body's centre, in world axes.
		btScalar m_c2;         ///< Scratch.
	};
	/// A cluster: a group of nodes treated as one rigid body by cluster collisions (CL_RS, CL_SS,
	/// CL_SELF) and joints. Built by generateClusters; its frame follows its nodes (best-fit rotation about
	/// their centre of mass, see docs/soft-bodies.md "Clusters").
	struct Cluster
	{
		btAlignedObjectArray<btScalar> m_masses;  ///< The nodes' masses, each split among the clusters sharing it (a
		                                          ///< fixed node: 0, the cluster is immovable).
		btAlignedObjectArray<Node*> m_nodes;  ///< The nodes (neighbouring clusters share the nodes along their border).
		btAlignedObjectArray<btVector3>
		    m_framerefs;           ///< Rest positions of the nodes relative to the rest centre of mass.
		btTransform m_framexform;  ///< Current frame: the centre of mass and the best-fit rotation.
		btScalar m_idmass;         ///< Inverse mass a push sees (below m_imass when nodes are shared; see docs).
		btScalar m_imass;          ///< Inverse mass (0 when a node is fixed).
		btMatrix3x3 m_locii;       ///< Inverse inertia of the rest shape about its centre of mass.
		btMatrix3x3 m_invwi;       ///< Current inverse inertia in world axes (zero when a node is fixed).
		btVector3 m_com;           ///< Current centre of mass.
		btVector3 m_vimpulses[2];  ///< Velocity changes waiting for applyClusters: linear, angular.
		btVector3 m_dimpulses[2];  ///< Position changes (per second) waiting for applyClusters(true).
		int m_nvimpulses;          ///< Number of velocity impulses waiting.
		int m_ndimpulses;          ///< Number of position impulses waiting.
		btVector3 m_lv;            ///< Linear velocity (of the centre of mass).
		btVector3 m_av;            ///< Angular velocity.
		btDbvtNode* m_leaf;        ///< Leaf in the cluster tree (Caliber keeps none: 0).
		btScalar m_ndamping;       ///< Damping of the nodes' velocities towards the cluster's rigid motion, [0, 1].
		btScalar m_ldamping;       ///< Damping of the linear velocity per step, [0, 1].
		btScalar m_adamping;       ///< Damping of the angular velocity per step, [0, 1].
		btScalar m_matching;       ///< Shape matching: fraction of the way to the rigid rest shape per step, [0, 1].
		btScalar m_maxSelfCollisionImpulse;  ///< Largest self-collision correction per solve, in m (Caliber: a length).
		btScalar m_selfCollisionImpulseFactor;  ///< Kept for Bullet's API (unused).
		bool m_containsAnchor;                  ///< A node of the cluster is anchored to a rigid body.
		bool m_collide;                         ///< The cluster takes part in cluster collisions.
		int m_clusterIndex;                     ///< Index in m_clusters.
		Cluster()
		    : m_idmass(0),
		      m_imass(0),
		      m_nvimpulses(0),
		      m_ndimpulses(0),
		      m_leaf(0),
		      m_ndamping(0),
		      m_ldamping(0),
		      m_adamping(0),
		      m_matching(0),
		      m_maxSelfCollisionImpulse(100),
		      m_selfCollisionImpulseFactor(btScalar(0.01)),
		      m_containsAnchor(false),
		      m_collide(false),
		      m_clusterIndex(0)
		{
			m_framexform.setIdentity();
			m_locii.setIdentity();
			m_invwi.setIdentity();
			m_com.setValue(0, 0, 0);
			m_lv.setValue(0, 0, 0);
			m_av.setValue(0, 0, 0);
			m_vimpulses[0] = m_vimpulses[1] = m_dimpulses[0] = m_dimpulses[1] = btVector3(0, 0, 0);
		}
	};
	/// A velocity impulse and a position (drift) impulse, either or both.
	struct Impulse
	{
		btVector3 m_velocity;  ///< Velocity impulse (N s).
		btVector3 m_drift;     ///< Position impulse (N s, applied as a displacement over the step).
		int m_asVelocity : 1;  ///< m_velocity is used.
		int m_asDrift : 1;     ///< m_drift is used.
		Impulse() : m_velocity(0, 0, 0), m_drift(0, 0, 0), m_asVelocity(0), m_asDrift(0) {}
		Impulse operator-() const
		{
			Impulse i = *this;
			i.m_velocity = -i.m_velocity;
			i.m_drift = -i.m_drift;
			return i;
		}
		Impulse operator*(btScalar x) const
		{
			Impulse i = *this;
			i.m_velocity *= x;
			i.m_drift *= x;
			return i;
		}
	};
	/// One side of a joint or cluster contact: a cluster, a rigid body, another collision object, or
	/// nothing (the world: fixed).
	struct Body
	{
		Cluster* m_soft;                             ///< The cluster, or 0.
		btRigidBody* m_rigid;                        ///< The rigid body, or 0.
		const btCollisionObject* m_collisionObject;  ///< The collision object, or 0.
		Body() : m_soft(0), m_rigid(0), m_collisionObject(0) {}
		Body(Cluster* p) : m_soft(p), m_rigid(0), m_collisionObject(0) {}
		Body(const btCollisionObject* colObj) : m_soft(0), m_rigid(0), m_collisionObject(colObj)
		{
			m_rigid = const_cast<btRigidBody*>(btRigidBody::upcast(colObj));
		}
		/// Wakes the rigid body.
		void activate() const;
		/// Inverse inertia in world axes (zero for the world and static objects).
		const btMatrix3x3& invWorldInertia() const;
		/// Inverse mass (0 for the world and static objects).
		btScalar invMass() const;
		/// The frame (identity for the world).
		const btTransform& xform() const;
		/// Linear velocity.
		btVector3 linearVelocity() const;
		/// Angular velocity.
		btVector3 angularVelocity() const;
		/// Angular contribution to the velocity of the point at rpos from the centre of mass.
		btVector3 angularVelocity(const btVector3& rpos) const;
		/// Velocity of the point at rpos from the centre of mass.
		btVector3 velocity(const btVector3& rpos) const;
		/// Velocity impulse at rpos.
		void applyVImpulse(const btVector3& impulse, const btVector3& rpos) const;
		/// Position impulse at rpos.
		void applyDImpulse(const btVector3& impulse, const btVector3& rpos) const;
		/// Either or both, as impulse says.
		void applyImpulse(const Impulse& impulse, const btVector3& rpos) const;
		/// Angular velocity impulse.
		void applyVAImpulse(const btVector3& impulse) const;
		/// Angular position impulse.
		void applyDAImpulse(const btVector3& impulse) const;
		/// Either or both angular impulses.
		void applyAImpulse(const Impulse& impulse) const;
		/// Linear position impulse at the centre of mass.
		void applyDCImpulse(const btVector3& impulse) const;
	};
	/// A constraint between two bodies (clusters, rigid bodies or the world), solved in the soft
	/// body's position solve (see docs/soft-bodies.md "Joints").
	struct Joint
	{
		struct eType
		{
			enum _
			{
				Linear = 0,  ///< LJoint.
				Angular,     ///< AJoint.
				Contact      ///< CJoint.
			};
		};
		/// Settings common to every joint.
		struct Specs
		{
			Specs() : erp(1), cfm(1), split(1) {}
			btScalar erp;    ///< Fraction of the error closed per solve, [0, 1].
			btScalar cfm;    ///< Kept for Bullet's API (Caliber's joints are position constraints).
			btScalar split;  ///< Kept for Bullet's API.
		};
		Body m_bodies[2];          ///< The two sides.
		btVector3 m_refs[2];       ///< The joint's points or axes in each side's frame.
		btScalar m_cfm;            ///< From Specs.
		btScalar m_erp;            ///< From Specs.
		btScalar m_split;          ///< From Specs.
		btVector3 m_drift;         ///< The error at the last solve (world axes).
		btVector3 m_sdrift;        ///< Scratch.
		btMatrix3x3 m_massmatrix;  ///< Scratch.
		bool m_delete;             ///< Removed at the end of the step.
		Joint() : m_cfm(1), m_erp(1), m_split(1), m_drift(0, 0, 0), m_sdrift(0, 0, 0), m_delete(false) {}
		virtual ~Joint() {}
		/// Before the solves of a step of dt.
		virtual void Prepare(btScalar dt, int iterations);
		/// One solve; sor scales the correction.
		virtual void Solve(btScalar dt, btScalar sor) = 0;
		/// After the solves.
		virtual void Terminate(btScalar dt) = 0;
		/// The kind of joint.
		virtual eType::_ Type() const = 0;
	};
	/// A ball joint: a point of each side kept together.
	struct LJoint : Joint
	{
		/// The joint's world position when appended.
		struct Specs : Joint::Specs
		{
			btVector3 position;  ///< The joint point, in world coordinates.
		};
		btVector3 m_rpos[2];  ///< The point relative to each side's centre of mass, world axes (scratch).
		void Prepare(btScalar dt, int iterations) override;
		void Solve(btScalar dt, btScalar sor) override;
		void Terminate(btScalar dt) override;
		eType::_ Type() const override { return eType::Linear; }
	};
	/// A hinge axis: an axis of each side kept aligned; the turn about it follows IControl::Speed.
	struct AJoint : Joint
	{
		/// Controls the relative angular speed about the axis (a motor).
		struct IControl
		{
			virtual ~IControl() {}
			/// Called before each step's solves.
			virtual void Prepare(AJoint*) {}
			/// The wanted relative angular speed (rad/s) given the current one (default: free).
			virtual btScalar Speed(AJoint*, btScalar current) { return current; }
			/// The free hinge.
			static IControl* Default()
			{
				static IControl def;
				return &def;
			}
		};
		/// The joint's world axis when appended, and its control.
		struct Specs : Joint::Specs
		{
			Specs() : icontrol(IControl::Default()) {}
			btVector3 axis;      ///< The hinge axis, in world axes.
			IControl* icontrol;  ///< The control (not owned; 0: free).
		};
		btVector3 m_axis[2];   ///< The axis in world axes as each side sees it (scratch).
		IControl* m_icontrol;  ///< The control.
		AJoint() : m_icontrol(0) {}
		void Prepare(btScalar dt, int iterations) override;
		void Solve(btScalar dt, btScalar sor) override;
		void Terminate(btScalar dt) override;
		eType::_ Type() const override { return eType::Angular; }
	};
	/// A contact between two sides (Bullet keeps cluster contacts as joints; Caliber keeps them apart
	/// and solves a CJoint appended to m_joints as a one-sided point contact along m_normal).
	struct CJoint : Joint
	{
		int m_life;           ///< Steps lived.
		int m_maxlife;        ///< Steps to live (0: one).
		btVector3 m_rpos[2];  ///< The contact point relative to each side's centre of mass.
		btVector3 m_normal;   ///< From side 1 towards side 0.
		btScalar m_friction;  ///< Kept for Bullet's API.
		CJoint() : m_life(0), m_maxlife(0), m_normal(0, 1, 0), m_friction(0) {}
		void Prepare(btScalar dt, int iterations) override;
		void Solve(btScalar dt, btScalar sor) override;
		void Terminate(btScalar dt) override;
		eType::_ Type() const override { return eType::Contact; }
	};
	/// A text note attached to the body (drawn by btSoftBodyHelpers::DrawInfos).
	struct Note : Element
	{
		const char* m_text;    ///< The text (not copied).
		btVector3 m_offset;    ///< Offset from the weighted nodes.
		int m_rank;            ///< How many of m_nodes are used.
		Node* m_nodes[4];      ///< Nodes the note follows.
		btScalar m_coords[4];  ///< Weights of those nodes.
	};
	/// The rest shape for pose matching and volume preservation (setPose).
	struct Pose
	{
		bool m_bvolume;                         ///< The rest volume is kept (kVC).
		bool m_bframe;                          ///< The rest shape is matched (kMT).
		btScalar m_volume;                      ///< Rest volume.
		btAlignedObjectArray<btVector3> m_pos;  ///< Rest positions relative to the centre of mass.
		btAlignedObjectArray<btScalar> m_wgh;   ///< Mass fractions of the nodes.
		btVector3 m_com;                        ///< Current centre of mass.
		btMatrix3x3 m_rot;                      ///< Current rotation of the best fit.
		btMatrix3x3 m_scl;                      ///< Current stretch of the best fit.
		btMatrix3x3 m_aqq;                      ///< Inverse of the rest shape's second moment.
	};
	/// Settings of the body, with Bullet's defaults.
	struct Config
	{
		eAeroModel::_ aeromodel;    ///< Aerodynamic model (V_Point).
		btScalar kVCF;              ///< Velocity correction factor (1; unused by Caliber's position solver).
		btScalar kDP;               ///< Damping, [0, 1]: fraction of the velocity lost per step of 1/60 s (0).
		btScalar kDG;               ///< Drag coefficient (0).
		btScalar kLF;               ///< Lift coefficient (0).
		btScalar kPR;               ///< Pressure: the gas constant n R T of P V = kPR (0).
		btScalar kVC;               ///< Volume conservation: pressure per unit of lost volume (0).
		btScalar kDF;               ///< Dynamic friction with rigid objects, [0, 1] (0.2).
		btScalar kMT;               ///< Pose matching, [0, 1] (0).
		btScalar kCHR;              ///< Hardness of contacts with static and kinematic objects (1).
		btScalar kKHR;              ///< Hardness of contacts with kinematic objects (0.1; Caliber uses kCHR).
		btScalar kSHR;              ///< Hardness of contacts with other soft bodies (1).
		btScalar kAHR;              ///< Hardness of anchors (0.7).
		btScalar kSRHR_CL;          ///< Cluster hardness against rigid bodies (0.1).
		btScalar kSKHR_CL;          ///< Cluster hardness against kinematic bodies (1).
		btScalar kSSHR_CL;          ///< Cluster hardness against soft bodies (0.5).
		btScalar kSR_SPLT_CL;       ///< Cluster impulse split against rigid bodies (0.5).
		btScalar kSK_SPLT_CL;       ///< Cluster impulse split against kinematic bodies (0.5).
		btScalar kSS_SPLT_CL;       ///< Cluster impulse split against soft bodies (0.5).
		btScalar maxvolume;         ///< Largest volume, as a multiple of the rest volume (1).
		btScalar timescale;         ///< Time scale of the body (1).
		int viterations;            ///< Velocity iterations (0).
		int piterations;            ///< Position iterations per step (1).
		int diterations;            ///< Drift iterations (0).
		int citerations;            ///< Cluster iterations (4).
		int collisions;             ///< fCollision flags (SDF_RS).
		tVSolverArray m_vsequence;  ///< Velocity solvers in order.
		tPSolverArray m_psequence;  ///< Position solvers in order.
		tPSolverArray m_dsequence;  ///< Drift solvers in order.
	};
	/// Constants of the current step.
	struct SolverState
	{
		btScalar sdt;     ///< The step.
		btScalar isdt;    ///< 1 / sdt.
		btScalar velmrg;  ///< Velocity margin of the bounds.
		btScalar radmrg;  ///< Radial margin of contacts.
		btScalar updmrg;  ///< Margin of the bounds update.
	};

	typedef btAlignedObjectArray<btScalar> tScalarArray;
	typedef btAlignedObjectArray<Cluster*> tClusterArray;
	typedef btAlignedObjectArray<Joint*> tJointArray;
	typedef btAlignedObjectArray<btVector3> tVector3Array;
	typedef btAlignedObjectArray<Note> tNoteArray;
	typedef btAlignedObjectArray<Node> tNodeArray;
	typedef btAlignedObjectArray<Link> tLinkArray;
	typedef btAlignedObjectArray<Face> tFaceArray;
	typedef btAlignedObjectArray<Tetra> tTetraArray;
	typedef btAlignedObjectArray<Anchor> tAnchorArray;
	typedef btAlignedObjectArray<RContact> tRContactArray;
	typedef btAlignedObjectArray<SContact> tSContactArray;
	typedef btAlignedObjectArray<Material*> tMaterialArray;
	typedef btAlignedObjectArray<btSoftBody*> tSoftBodyArray;

	Config m_cfg;                         ///< Settings.
	SolverState m_sst;                    ///< Constants of the current step.
	Pose m_pose;                          ///< Rest shape (setPose).
	void* m_tag;                          ///< User data.
	btSoftBodyWorldInfo* m_worldInfo;     ///< The world's information (not owned).
	tNoteArray m_notes;                   ///< Notes.
	tNodeArray m_nodes;                   ///< Nodes.
	tLinkArray m_links;                   ///< Links (and bending links).
	tFaceArray m_faces;                   ///< Faces.
	tTetraArray m_tetras;                 ///< Tetras.
	tAnchorArray m_anchors;               ///< Anchors.
	tRContactArray m_rcontacts;           ///< Contacts with rigid objects of the current step.
	tSContactArray m_scontacts;           ///< This body's nodes' contacts with other soft bodies' faces this step.
	tMaterialArray m_materials;           ///< Materials (owned).
	tClusterArray m_clusters;             ///< Clusters (owned; generateClusters).
	tJointArray m_joints;                 ///< Joints (owned; appendLinearJoint, appendAngularJoint).
	                                      ///< (self-collision skips them).
	btScalar m_timeacc;                   ///< Time accumulator (unused: the world steps the body).
	btVector3 m_bounds[2];                ///< Bounding box of the nodes' current and predicted positions.
	bool m_bUpdateRtCst;                  ///< The constants derived from masses and rest shapes are stale.
	btDbvt m_ndbvt;                       ///< Node tree (Caliber keeps it empty).
	btDbvt m_fdbvt;                       ///< Face tree (Caliber keeps it empty).
	btDbvt m_cdbvt;                       ///< Cluster tree (empty).
	btTransform m_initialWorldTransform;  ///< The transform given to the last transform() call.
	btVector3 m_windVelocity;             ///< Velocity of the air (for the aerodynamic forces).
	btScalar m_restLengthScale;           ///< Scale of every link's rest length.
	/// [i + j * clusterCount()]: clusters i and j share a node (self-collision skips such pairs).
	btAlignedObjectArray<bool> m_clusterConnectivity;

	/// A body of node_count nodes at x with masses m (either may be null: origin, mass 1).
	btSoftBody(btSoftBodyWorldInfo* worldInfo, int node_count, const btVector3* x, const btScalar* m);
	/// An empty body.
	btSoftBody(btSoftBodyWorldInfo* worldInfo);
	/// Sets Bullet's defaults (called by the constructors).
	void initDefaults();
	virtual ~btSoftBody();

	/// The world information.
	btSoftBodyWorldInfo* getWorldInfo() { return m_worldInfo; }
	/// Soft bodies keep their own collision shape: ignored, as in Bullet.
	virtual void setCollisionShape(btCollisionShape*) {}

	/// True when a link joins the two nodes.
	bool checkLink(int node0, int node1) const;
	/// True when a link joins the two nodes.
	bool checkLink(const Node* node0, const Node* node1) const;
	/// True when a face has exactly these three nodes (in any order).
	bool checkFace(int node0, int node1, int node2) const;
	/// A new material, a copy of the first one (or Bullet's defaults for the first).
	Material* appendMaterial();
	/// A note at o with up to four nodes weighted by c.
	void appendNote(const char* text, const btVector3& o, const btVector4& c = btVector4(1, 0, 0, 0), Node* n0 = 0,
	                Node* n1 = 0, Node* n2 = 0, Node* n3 = 0);
	/// A note following a node.
	void appendNote(const char* text, const btVector3& o, Node* feature);
	/// A note following the middle of a link.
	void appendNote(const char* text, const btVector3& o, Link* feature);
	/// A note following the centre of a face.
	void appendNote(const char* text, const btVector3& o, Face* feature);
	/// A node at x with mass m (0: fixed).
	void appendNode(const btVector3& x, btScalar m);
	/// A link copying link model (or a blank one when model < 0), with mat (0: the first material).
	void appendLink(int model = -1, Material* mat = 0);
	/// A link between two nodes; with bcheckexist, nothing when they are linked already.
	void appendLink(int node0, int node1, Material* mat = 0, bool bcheckexist = false);
	/// A link between two nodes; with bcheckexist, nothing when they are linked already.
	void appendLink(Node* node0, Node* node1, Material* mat = 0, bool bcheckexist = false);
	/// A face copying face model (or a blank one), with mat.
	void appendFace(int model = -1, Material* mat = 0);
	/// A face of three nodes.
	void appendFace(int node0, int node1, int node2, Material* mat = 0);
	/// A tetra copying tetra model (or a blank one), with mat.
	void appendTetra(int model, Material* mat);
	/// A tetra of four nodes.
	void appendTetra(int node0, int node1, int node2, int node3, Material* mat = 0);
	/// Holds node at its current place on body; the body is pulled too, by influence.
	void appendAnchor(int node, btRigidBody* body, bool disableCollisionBetweenLinkedBodies = false,
	                  btScalar influence = 1);
	/// Holds node at localPivot (in body's frame) on body.
	void appendAnchor(int node, btRigidBody* body, const btVector3& localPivot,
	                  bool disableCollisionBetweenLinkedBodies = false, btScalar influence = 1);
	/// Adds force (N) to every free node, for the next step.
	void addForce(const btVector3& force);
	/// Adds force (N) to one node, for the next step.
	void addForce(const btVector3& force, int node);
	/// Adds the aerodynamic force of windVelocity on one node (the aero model's node part).
	void addAeroForceToNode(const btVector3& windVelocity, int nodeIndex);
	/// Adds the aerodynamic force of windVelocity on one face's nodes (the aero model's face part).
	void addAeroForceToFace(const btVector3& windVelocity, int faceIndex);
	/// Adds velocity to every free node.
	void addVelocity(const btVector3& velocity);
	/// Sets the velocity of every free node.
	void setVelocity(const btVector3& velocity);
	/// Adds velocity to one free node.
	void addVelocity(const btVector3& velocity, int node);
	/// Sets the mass of one node (0: fixed).
	void setMass(int node, btScalar mass);
	/// The mass of one node (0 when fixed).
	btScalar getMass(int node) const;
	/// Sum of the free nodes' masses.
	btScalar getTotalMass() const;
	/// Spreads mass over the free nodes by their share of the link lengths, or of the face areas when
	/// fromfaces is set.
	void setTotalMass(btScalar mass, bool fromfaces = false);
	/// setTotalMass(density * volume).
	void setTotalDensity(btScalar density);
	/// Spreads mass over the nodes by the tetras' volumes.
	void setVolumeMass(btScalar mass);
	/// setVolumeMass(density * sum of the tetras' volumes).
	void setVolumeDensity(btScalar density);
	/// Moves the body rigidly (positions, velocities and normals turned with it).
	void transform(const btTransform& trs);
	/// Moves the body by trs.
	void translate(const btVector3& trs);
	/// Turns the body about the origin.
	void rotate(const btQuaternion& rot);
	/// Scales positions (and rest lengths and rest volumes) about the origin.
	void scale(const btVector3& scl);
	/// Scale of every link's rest length.
	btScalar getRestLengthScale();
	/// Sets the scale of every link's rest length (from its length at creation).
	void setRestLengthScale(btScalar restLength);
	/// Records the current shape as the rest shape: its volume (bvolume, for kVC) and its frame
	/// (bframe, for kMT).
	void setPose(bool bvolume, bool bframe);
	/// Sets every link's rest length to its current length.
	void resetLinkRestLengths();
	/// Volume enclosed by the faces (0 without faces).
	btScalar getVolume() const;
	/// Centre of mass of the nodes.
	btVector3 getCenterOfMass() const { return evaluateCom(); }
	/// Adds links between nodes up to distance links apart (2: across one node). Returns the number added.
	int generateBendingConstraints(int distance, Material* mat = 0);
	/// Shuffles the order of the links (deterministically).
	void randomizeConstraints();
	/// Groups the nodes into k clusters by k-means over their positions (at most maxiterations
	/// rounds); clusters then take in the nodes of faces (or links) that cross their border, so that
	/// neighbours share nodes. k <= 0: one cluster per tetra, or per face when there are no tetras.
	/// k larger than the node count: one cluster per node, with a warning. Returns the cluster count.
	int generateClusters(int k, int maxiterations = 8192);
	/// Number of clusters.
	int clusterCount() const { return m_clusters.size(); }
	/// Centre of mass of a cluster's nodes now.
	static btVector3 clusterCom(const Cluster* cluster);
	/// Centre of mass of cluster index now (the origin for a bad index, with a warning).
	btVector3 clusterCom(int cluster) const;
	/// Velocity of the point at rpos from the cluster's centre of mass (from m_lv, m_av).
	static btVector3 clusterVelocity(const Cluster* cluster, const btVector3& rpos);
	/// A velocity impulse at rpos, waiting in m_vimpulses for applyClusters(false) (m_lv, m_av change now).
	static void clusterVImpulse(Cluster* cluster, const btVector3& rpos, const btVector3& impulse);
	/// A position impulse at rpos, waiting in m_dimpulses for applyClusters(true).
	static void clusterDImpulse(Cluster* cluster, const btVector3& rpos, const btVector3& impulse);
	/// Either or both, as impulse says.
	static void clusterImpulse(Cluster* cluster, const btVector3& rpos, const Impulse& impulse);
	/// An angular velocity impulse.
	static void clusterVAImpulse(Cluster* cluster, const btVector3& impulse);
	/// An angular position impulse.
	static void clusterDAImpulse(Cluster* cluster, const btVector3& impulse);
	/// Either or both angular impulses.
	static void clusterAImpulse(Cluster* cluster, const Impulse& impulse);
	/// A linear position impulse at the centre of mass.
	static void clusterDCImpulse(Cluster* cluster, const btVector3& impulse);
	/// Rest frames, masses and inertias of the clusters from the current shape.
	void initializeClusters();
	/// Current frames, inertias and velocities of the clusters; shape matching (m_matching).
	void updateClusters();
	/// Empties the clusters' waiting impulses.
	void cleanupClusters();
	/// Hands the clusters' waiting impulses to their nodes: velocities (drift false) or positions
	/// (drift true, moved by the impulse's velocity over the step). Each cluster moves its nodes as a
	/// rigid body would, so momentum is conserved.
	void applyClusters(bool drift);
	/// Damps the nodes' velocities towards their clusters' rigid motion (m_ndamping).
	void dampClusters();
	/// Removes cluster index (joints using it are removed too).
	void releaseCluster(int index);
	/// Removes every cluster (and the joints using them).
	void releaseClusters();
	/// A ball joint at specs.position between cluster body0 of this body and body1.
	void appendLinearJoint(const LJoint::Specs& specs, Cluster* body0, Body body1);
	/// A ball joint between this body's first cluster and body (the world when empty).
	void appendLinearJoint(const LJoint::Specs& specs, Body body = Body());
	/// A ball joint between the first clusters of this body and body.
	void appendLinearJoint(const LJoint::Specs& specs, btSoftBody* body);
	/// A hinge axis joint between cluster body0 of this body and body1.
	void appendAngularJoint(const AJoint::Specs& specs, Cluster* body0, Body body1);
	/// A hinge axis joint between this body's first cluster and body (the world when empty).
	void appendAngularJoint(const AJoint::Specs& specs, Body body = Body());
	/// A hinge axis joint between the first clusters of this body and body.
	void appendAngularJoint(const AJoint::Specs& specs, btSoftBody* body);
	/// Cuts the link between two nodes at position (0..1 along it), splitting the faces that use it.
	/// Returns false when no such link exists.
	bool cutLink(int node0, int node1, btScalar position);
	/// As above, with node pointers.
	bool cutLink(const Node* node0, const Node* node1, btScalar position);
	/// Splits the links (and, for bodies with faces, the face edges) across which ifn changes sign at a new
	/// node on its zero set, found by bisection to accurary (a fraction of the link's length), and splits the
	/// faces to match; with cut, the body is also cut along that set (each new node doubled, one for each
	/// side). The total mass is kept. Not for bodies with tetras or clusters (a warning; nothing done).
	void refine(ImplicitFn* ifn, btScalar accurary, bool cut);
	/// First face (or, for bodies without faces, nothing) hit by the segment; fills results and returns
	/// true on a hit.
	bool rayTest(const btVector3& rayFrom, const btVector3& rayTo, sRayCast& results);
	/// Chooses the solver sequence.
	void setSolver(eSolverPresets::_ preset);
	/// First part of a step of dt: forces into velocities, predicted positions, bounds.
	void predictMotion(btScalar dt);
	/// Second part: the position solve of constraints and contacts.
	void solveConstraints();
	/// Runs the link constraints alone iterations times (no time passes).
	void staticSolve(int iterations);
	/// Steps the bodies' common constraints (Caliber solves joints in each body's solveConstraints: nothing).
	static void solveCommonConstraints(btSoftBody** bodies, int count, int iterations);
	/// Third part, once every body of the world is solved: velocities from the step's moves, normals, bounds.
	void integrateMotion();
	/// Finds this step's contacts of the nodes with one rigid object.
	void defaultCollisionHandler(const btCollisionObjectWrapper* pcoWrap);
	/// Finds node-face contacts with another soft body, both ways, when either has VF_SS.
	void defaultCollisionHandler(btSoftBody* psb);

	/// Sets the velocity of the air around the body.
	void setWindVelocity(const btVector3& velocity);
	/// The velocity of the air around the body.
	const btVector3& getWindVelocity();

	/// Sets the solver (not owned).
	void setSoftBodySolver(btSoftBodySolver* softBodySolver) { m_softBodySolver = softBodySolver; }
	/// The solver (0 until the body joins a world).
	btSoftBodySolver* getSoftBodySolver() { return m_softBodySolver; }
	/// The solver (0 until the body joins a world).
	btSoftBodySolver* getSoftBodySolver() const { return m_softBodySolver; }

	/// colObj as a soft body, or 0.
	static const btSoftBody* upcast(const btCollisionObject* colObj)
	{
		if (colObj && colObj->getInternalType() == CO_SOFT_BODY) return static_cast<const btSoftBody*>(colObj);
		return 0;
	}
	/// colObj as a soft body, or 0.
	static btSoftBody* upcast(btCollisionObject* colObj)
	{
		if (colObj && colObj->getInternalType() == CO_SOFT_BODY) return static_cast<btSoftBody*>(colObj);
		return 0;
	}

	/// The bounds of the nodes (current and predicted positions, with the margin).
	virtual void getAabb(btVector3& aabbMin, btVector3& aabbMax) const
	{
		aabbMin = m_bounds[0];
		aabbMax = m_bounds[1];
	}

	/// Replaces node pointers in links, faces, tetras, anchors, notes and contacts by indices.
	void pointersToIndices();
	/// Replaces the indices written by pointersToIndices by pointers (through map when given).
	void indicesToPointers(const int* map = 0);
	/// Counts (bcountonly) or finds the first face hit by the segment; mint, feature and index describe it.
	int rayTest(const btVector3& rayFrom, const btVector3& rayTo, btScalar& mint, eFeature::_& feature, int& index,
	            bool bcountonly) const;
	/// Centre of mass of the nodes (of every node when all are fixed).
	btVector3 evaluateCom() const;
	/// Recomputes the face and node normals.
	void updateNormals();
	/// Recomputes m_bounds from the nodes.
	void updateBounds();
	/// Recomputes the pose matching fit (m_pose.m_com, m_rot, m_scl).
	void updatePose();
	/// Recomputes the constants derived from masses and rest shapes.
	void updateConstants();
	/// Recomputes the links' compliances.
	void updateLinkConstants();
	/// Recomputes the face rest areas and node areas.
	void updateArea(bool averageArea = true);
	/// Adds pressure, volume, aerodynamic and user forces into the velocities (part of predictMotion).
	void applyForces();

	/// Bytes of btSoftBodyFloatData (BulletSoftBody/btSoftBodyData.h).
	virtual int calculateSerializeBufferSize() const;
	/// Writes the body into dataBuffer and its parts (materials, nodes, links, faces, tetras, anchors, pose,
	/// clusters, joints) as chunks of their own; returns the struct's name (docs/serialization.md).
	virtual const char* serialize(void* dataBuffer, class btSerializer* serializer) const;
};

#endif  // _BT_SOFT_BODY_H
