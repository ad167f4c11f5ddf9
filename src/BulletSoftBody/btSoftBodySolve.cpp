// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btSoftBody's step: forces, prediction, the position solve (links, anchors, rigid contacts, pose
// matching) and the velocity update. The model is explained in docs/soft-bodies.md.

#include <atomic>

#include "BulletSoftBody/btSoftBody.h"
#include "LinearMath/btPolarDecomposition.h"
#include "btSoftBodyClusters.h"
#include "btSoftBodyFaceContacts.h"
#include "btSoftBodyInternal.h"
#include "btSoftBodyLinkColours.h"
#include "btSoftBodyLinkSweep.h"
#include "btSoftBodyTethers.h"

namespace caliber
{
// A rigid body that can be moved by the soft body (dynamic, in or out of a world).
bool isMovable(const btRigidBody* body) { return body && body->getInvMass() > 0 && !body->isStaticOrKinematicObject(); }

// Inverse effective mass of a rigid body at offset r along unit direction n.
btScalar rigidInverseMass(const btRigidBody* body, const btVector3& r, const btVector3& n)
{
	if (!isMovable(body)) return 0;
	const btVector3 rn = r.cross(n);
	return body->getInvMass() + rn.dot(body->getInvInertiaTensorWorld() * rn);
}

// Moves a dynamic body by a position-level impulse p (kg m) at offset r, over a step dt: its pose moves
// by the corresponding displacement and its velocity by that displacement over dt times velocityShare,
// so that rigid and soft see the same correction (position based coupling). A share below 1 moves the
// body out of a penetration without launching it.
void moveRigid(btRigidBody* body, const btVector3& p, const btVector3& r, btScalar dt, btScalar velocityShare)
{
	const btVector3 dx = p * body->getInvMass();
	const btVector3 dw = body->getInvInertiaTensorWorld() * r.cross(p);
	btTransform t = body->getWorldTransform();
	t.setOrigin(t.getOrigin() + dx);
	const btScalar angle = dw.length();
	if (angle > SIMD_EPSILON)
	{
		btQuaternion q(dw / angle, angle);
		btQuaternion rot = q * t.getRotation();
		rot.normalize();
		t.setRotation(rot);
	}
	body->setWorldTransform(t);
	body->setInterpolationWorldTransform(t);
	body->setLinearVelocity(body->getLinearVelocity() + dx * (velocityShare / dt));
	body->setAngularVelocity(body->getAngularVelocity() + dw * (velocityShare / dt));
	body->updateInertiaTensor();
}

void turnRigid(btRigidBody* body, const btVector3& l, btScalar dt, btScalar velocityShare)
{
	const btVector3 dw = body->getInvInertiaTensorWorld() * l;
	const btScalar angle = dw.length();
	if (angle <= SIMD_EPSILON) return;
	btTransform t = body->getWorldTransform();
	btQuaternion rot = btQuaternion(dw / angle, angle) * t.getRotation();
	rot.normalize();
	t.setRotation(rot);
	body->setWorldTransform(t);
	body->setInterpolationWorldTransform(t);
	body->setAngularVelocity(body->getAngularVelocity() + dw * (velocityShare / dt));
	body->updateInertiaTensor();
}
}  // namespace caliber

using caliber::complianceFactor;
using caliber::isMovable;
using caliber::kReferenceStep;
using caliber::moveRigid;
using caliber::rigidInverseMass;

namespace
{
// The most substeps a soft body's step is cut into: a substep's move must stay well above the rounding of
// the positions, or the velocities taken from the moves are lost (200 substeps of 1/60 s move a node
// g h^2 = 7e-8 m: nothing, at 5 m from the origin in single precision).
const int kMaxSubsteps = 4;

// Air force on a surface element of area `area` and unit normal n moving at rel against the air.
// Drag along -rel with coefficient kDG, lift across rel with kLF; projected area |n . rel|.
btVector3 aeroForce(const btVector3& rel, const btVector3& n, btScalar area, btScalar density, btScalar kDG,
                    btScalar kLF, bool oneSided)
{
	const btScalar speed2 = rel.length2();
	if (speed2 <= SIMD_EPSILON || area <= 0) return btVector3(0, 0, 0);
	const btScalar speed = btSqrt(speed2);
	const btVector3 dir = rel / speed;
	btScalar cosine = n.dot(dir);
	if (oneSided && cosine < 0) return btVector3(0, 0, 0);
	const btScalar q = btScalar(0.5) * density * speed2 * area;
	btVector3 force = -dir * (q * kDG * btFabs(cosine));
	if (kLF > 0)
	{
		// Lift is perpendicular to the flow, in the plane of the flow and the normal, pushing the surface
		// away from the side the air hits.
		btVector3 across = n - dir * cosine;
		const btScalar len = across.length();
		if (len > SIMD_EPSILON)
		{
			const btScalar sine = len;
			force -= (across / len) * (q * kLF * btFabs(cosine) * sine) * (cosine >= 0 ? 1 : -1);
		}
	}
	return force;
}
}  // namespace

void btSoftBody::updateLinkConstants()
{
	// A link is a spring solved by XPBD. m_kLST keeps Bullet's meaning, the fraction of a lone link's
	// error one iteration closes at 60 Hz; piterations iterations close kStep = 1 - (1 - kLST)^piterations
	// of it. The spring that closes kStep in one implicit step of h_ref = 1/60 s has the constant
	// k = kStep / ((1 - kStep) w h_ref^2), w the link's inverse masses: that is the link's stiffness,
	// whatever the step and iteration count used later, and its own frequency is
	// sqrt(kStep / (1 - kStep)) / h_ref. m_c0 keeps w; the solver multiplies in the factor of the
	// material's current kLST (complianceFactor).
	for (int i = 0; i < m_links.size(); ++i)
	{
		Link& l = m_links[i];
		l.m_c0 = l.m_n[0]->m_im + l.m_n[1]->m_im;
		l.m_c1 = l.m_rl * l.m_rl;
	}
	// A tetra's volume constraint gets its stiffness the same way, from m_kVST: m_c1 keeps its
	// W = sum of im_i |dV/dx_i|^2 now (the shape the constants are built at, normally the rest shape), so
	// that the constraint closes kStep of a lone tetra's volume error in one step of h_ref and its
	// stiffness dP/dV is kStep / ((1 - kStep) W h_ref^2), whatever the step and sweep count.
	for (int i = 0; i < m_tetras.size(); ++i)
	{
		Tetra& t = m_tetras[i];
		caliber::tetraGradients(t);
		t.m_c1 = 0;
		for (int j = 0; j < 4; ++j) t.m_c1 += t.m_n[j]->m_im * t.m_c0[j].length2();
	}
}

void btSoftBody::updateArea(bool averageArea)
{
	(void)averageArea;
	for (int i = 0; i < m_nodes.size(); ++i) m_nodes[i].m_area = 0;
	for (int i = 0; i < m_faces.size(); ++i)
	{
		Face& f = m_faces[i];
		const btScalar a =
		    btScalar(0.5) * (f.m_n[1]->m_x - f.m_n[0]->m_x).cross(f.m_n[2]->m_x - f.m_n[0]->m_x).length();
		f.m_ra = a;
		for (int j = 0; j < 3; ++j) f.m_n[j]->m_area += a / 3;
	}
}

void btSoftBody::updateConstants()
{
	updateLinkConstants();
	updateArea();
	m_bUpdateRtCst = false;
}

void btSoftBody::setPose(bool bvolume, bool bframe)
{
	m_pose.m_bvolume = bvolume;
	m_pose.m_bframe = bframe;
	const int n = m_nodes.size();
	// Fixed nodes weigh as much as ten times the free ones together, so they anchor the frame.
	btScalar freeMass = getTotalMass();
	if (!(freeMass > 0)) freeMass = 1;
	m_pose.m_wgh.resize(n);
	btScalar total = 0;
	for (int i = 0; i < n; ++i)
	{
		m_pose.m_wgh[i] = m_nodes[i].m_im > 0 ? btScalar(1) / m_nodes[i].m_im : 10 * freeMass;
		total += m_pose.m_wgh[i];
	}
	for (int i = 0; i < n; ++i) m_pose.m_wgh[i] /= total > 0 ? total : btScalar(1);
	btVector3 com(0, 0, 0);
	for (int i = 0; i < n; ++i) com += m_nodes[i].m_x * m_pose.m_wgh[i];
	m_pose.m_com = com;
	m_pose.m_pos.resize(n);
	btMatrix3x3 aqq(0, 0, 0, 0, 0, 0, 0, 0, 0);
	for (int i = 0; i < n; ++i)
	{
		const btVector3 p = m_nodes[i].m_x - com;
		m_pose.m_pos[i] = p;
		const btScalar w = m_pose.m_wgh[i];
		for (int r = 0; r < 3; ++r)
			for (int c = 0; c < 3; ++c) aqq[r][c] += w * p[r] * p[c];
	}
	// A flat or linear body has a singular second moment: only its rotation is fitted then.
	m_pose.m_aqq = btFabs(aqq.determinant()) > SIMD_EPSILON * SIMD_EPSILON ? aqq.inverse() : btMatrix3x3::getIdentity();
	m_pose.m_rot.setIdentity();
	m_pose.m_scl.setIdentity();
	m_pose.m_volume = bvolume ? getVolume() : btScalar(0);
}

void btSoftBody::updatePose()
{
	const int n = m_nodes.size();
	if (!m_pose.m_bframe || m_pose.m_pos.size() != n) return;
	btVector3 com(0, 0, 0);
	for (int i = 0; i < n; ++i) com += m_nodes[i].m_x * m_pose.m_wgh[i];
	btMatrix3x3 apq(0, 0, 0, 0, 0, 0, 0, 0, 0);
	for (int i = 0; i < n; ++i)
	{
		const btVector3 a = (m_nodes[i].m_x - com) * m_pose.m_wgh[i];
		const btVector3& b = m_pose.m_pos[i];
		for (int r = 0; r < 3; ++r)
			for (int c = 0; c < 3; ++c) apq[r][c] += a[r] * b[c];
	}
	btMatrix3x3 rot, scl;
	polarDecompose(apq, rot, scl);
	// A reflection is not a rotation: flip it (happens only for inverted bodies).
	if (rot.determinant() < 0) rot = rot * btMatrix3x3(-1, 0, 0, 0, 1, 0, 0, 0, 1);
	m_pose.m_com = com;
	m_pose.m_rot = rot;
	m_pose.m_scl = apq * m_pose.m_aqq;
}

void btSoftBody::applyForces()
{
	const btScalar dt = m_sst.sdt;
	// A closed body whose skin cannot stretch holds its gas by a volume constraint instead (solveConstraints).
	if (m_cfg.kPR != 0 && m_faces.size() > 0 && !caliber::softBodyTethers(*this, false).inextensibleSkin)
	{
		// Gas pressure P = kPR / V (P V = n R T, isothermal), acting on each face as P times its area
		// along its normal, a third to each node. The sign of V says which way the faces are wound, so
		// inward-wound bodies are pushed outward too. (Volume conservation, kVC, is a constraint of the
		// position solve: as a force it would be too stiff for an explicit step.)
		const btScalar v = getVolume();
		const btScalar absV = btFabs(v);
		if (absV > SIMD_EPSILON)
		{
			const btScalar p = m_cfg.kPR / absV;
			const btScalar scale = p * (v < 0 ? btScalar(-1) : btScalar(1)) / btScalar(6);  // half cross, a third each
			for (int i = 0; i < m_faces.size(); ++i)
			{
				Face& f = m_faces[i];
				const btVector3 an = (f.m_n[1]->m_x - f.m_n[0]->m_x).cross(f.m_n[2]->m_x - f.m_n[0]->m_x) * scale;
				for (int j = 0; j < 3; ++j) f.m_n[j]->m_f += an;
			}
		}
	}
	if ((m_cfg.kDG > 0 || m_cfg.kLF > 0) && m_worldInfo)
	{
		const btVector3 wind = m_windVelocity;
		switch (m_cfg.aeromodel)
		{
			case eAeroModel::V_Point:
			case eAeroModel::V_TwoSided:
			case eAeroModel::V_TwoSidedLiftDrag:
			case eAeroModel::V_OneSided:
				for (int i = 0; i < m_nodes.size(); ++i) addAeroForceToNode(wind, i);
				break;
			default:
				for (int i = 0; i < m_faces.size(); ++i) addAeroForceToFace(wind, i);
				break;
		}
	}
	for (int i = 0; i < m_nodes.size(); ++i)
	{
		Node& n = m_nodes[i];
		if (n.m_im > 0) n.m_v += n.m_f * (n.m_im * dt);
		n.m_f.setValue(0, 0, 0);
	}
}

void btSoftBody::addAeroForceToNode(const btVector3& windVelocity, int nodeIndex)
{
	if (!caliber::validIndex(nodeIndex, m_nodes.size()) || !m_worldInfo) return;
	Node& n = m_nodes[nodeIndex];
	if (n.m_im <= 0) return;
	const btVector3 rel = n.m_v - windVelocity;
	btVector3 normal = n.m_n;
	btScalar lift = m_cfg.kLF;
	if (m_cfg.aeromodel == eAeroModel::V_Point)
	{
		// Point model: drag only, on the node's area as if facing the flow.
		const btScalar speed = rel.length();
		if (speed <= SIMD_EPSILON) return;
		normal = rel / speed;
		lift = 0;
	}
	n.m_f += aeroForce(rel, normal, n.m_area, m_worldInfo->air_density, m_cfg.kDG, lift,
	                   m_cfg.aeromodel == eAeroModel::V_OneSided);
}

void btSoftBody::addAeroForceToFace(const btVector3& windVelocity, int faceIndex)
{
	if (!caliber::validIndex(faceIndex, m_faces.size()) || !m_worldInfo) return;
	Face& f = m_faces[faceIndex];
	const btVector3 v = (f.m_n[0]->m_v + f.m_n[1]->m_v + f.m_n[2]->m_v) / btScalar(3);
	const btVector3 cross = (f.m_n[1]->m_x - f.m_n[0]->m_x).cross(f.m_n[2]->m_x - f.m_n[0]->m_x);
	const btScalar len = cross.length();
	if (len <= SIMD_EPSILON) return;
	const btVector3 force = aeroForce(v - windVelocity, cross / len, len / 2, m_worldInfo->air_density, m_cfg.kDG,
	                                  m_cfg.kLF, m_cfg.aeromodel == eAeroModel::F_OneSided) /
	                        btScalar(3);
	for (int j = 0; j < 3; ++j)
		if (f.m_n[j]->m_im > 0) f.m_n[j]->m_f += force;
}

void btSoftBody::predictMotion(btScalar dt)
{
	if (m_bUpdateRtCst) updateConstants();
	// The step's one pass over the links packs them for the sweeps and fingerprints them: the tethers and the
	// skin's rest volume are (re)built from the shape before this step moves it, the colouring with them.
	const caliber::SoftLinkSweep& packedLinks = caliber::packSoftLinks(*this, m_cfg.piterations);
	caliber::refreshSoftBodyTethers(*this, packedLinks.tetherSignature);
	if (m_links.size() > caliber::kLinkBlock) caliber::refreshSoftLinkColours(*this, packedLinks.nodeSignature);
	m_sst.sdt = dt * m_cfg.timescale;
	m_sst.isdt = m_sst.sdt > 0 ? btScalar(1) / m_sst.sdt : btScalar(0);
	m_sst.velmrg = m_sst.sdt * 3;
	m_sst.radmrg = m_collisionShape ? m_collisionShape->getMargin() : btScalar(0);
	m_sst.updmrg = m_sst.radmrg * btScalar(0.25);
	m_rcontacts.resize(0);
	m_scontacts.resize(0);
	if (m_clusters.size() > 0)
	{
		caliber::clusterState(*this).contacts.resize(0);
		caliber::clusterState(*this).weights.resize(0);
	}
	if (m_faces.size() > 0)  // only faces take corner contacts (ropes skip the side table)
	{
		caliber::SoftFaceContacts& faceContacts = caliber::softFaceContacts(*this);
		faceContacts.contacts.resize(0);
		faceContacts.boxesValid = false;
	}
	const btVector3 gravity = m_worldInfo ? m_worldInfo->m_gravity : btVector3(0, 0, 0);
	const btScalar maxMove = m_worldInfo ? m_worldInfo->m_maxDisplacement : btScalar(1000);
	// Forces that depend on the velocity (air) see the velocity the step starts with.
	applyForces();
	struct Predict : btIParallelForBody
	{
		btSoftBody::Node* nodes;
		btVector3 gravity;
		btScalar dt, maxMove;
		void forLoop(int begin, int end) const override
		{
			for (int i = begin; i < end; ++i)
			{
				Node& n = nodes[i];
				if (n.m_im > 0) n.m_v += gravity * dt;
				n.m_q = n.m_x;
				n.m_vn = n.m_v;
				if (n.m_im <= 0) continue;
				btVector3 move = n.m_v * dt;
				const btScalar len = move.length();
				if (len > maxMove) move *= maxMove / len;
				n.m_x += move;
			}
		}
	};
	if (m_nodes.size() > 0)
	{
		Predict predict;
		predict.nodes = &m_nodes[0];
		predict.gravity = gravity;
		predict.dt = m_sst.sdt;
		predict.maxMove = maxMove;
		caliber::forEachNodeChunk(m_nodes.size(), predict);
	}
	// The clusters' frames at the predicted positions, for the collision pass.
	for (int i = 0; i < m_clusters.size(); ++i) caliber::refreshCluster(*m_clusters[i], m_sst.sdt);
	if (m_clusters.size() > 0) caliber::updateClusterTree(*this);
	updateBounds();
}

namespace
{
// Tetra volumes (m_kVST): each tetra's signed volume V = V0 (its rest volume m_rv) by XPBD, with the
// compliance that m_kVST gives through complianceFactor, as links get theirs from m_kLST (W in m_c1,
// updateLinkConstants); the multiplier accumulates in m_c2 over the step. The signed volume keeps a
// tetra from turning inside out.
void solveTetras(btSoftBody& body, btScalar dt)
{
	const btScalar idt2 = btScalar(1) / (dt * dt);
	const btSoftBody::Material* lastMaterial = 0;
	btScalar factor = -1;
	for (int i = 0; i < body.m_tetras.size(); ++i)
	{
		btSoftBody::Tetra& t = body.m_tetras[i];
		if (t.m_material != lastMaterial)
		{
			lastMaterial = t.m_material;
			factor = complianceFactor(t.m_material ? t.m_material->m_kVST : btScalar(1), body.m_cfg.piterations);
		}
		if (factor < 0 || !(t.m_c1 > 0)) continue;
		const btScalar volume = caliber::tetraGradients(t);
		btScalar w = 0;
		for (int j = 0; j < 4; ++j) w += t.m_n[j]->m_im * t.m_c0[j].length2();
		const btScalar alpha = factor * t.m_c1 * idt2;
		if (!(w + alpha > 0)) continue;
		const btScalar dlambda = (-(volume - t.m_rv) - alpha * t.m_c2) / (w + alpha);
		t.m_c2 += dlambda;
		for (int j = 0; j < 4; ++j) t.m_n[j]->m_x += t.m_c0[j] * (dlambda * t.m_n[j]->m_im);
	}
}

// Volume conservation (kVC): the constraint V = V0 of the whole closed surface with the compliance
// 1 / kVC, so that a lost volume dV holds the pressure kVC dV (XPBD; lambda accumulates over the step).
// The compliance may differ below and above the target (the gas of an inextensible skin, below).
void solveVolume(btSoftBody& body, btScalar dt, btScalar target, btScalar complianceShrunk, btScalar complianceGrown,
                 btScalar& lambda, btAlignedObjectArray<btVector3>& grad)
{
	const int n = body.m_nodes.size();
	if (n == 0) return;
	grad.resize(n);
	for (int i = 0; i < n; ++i) grad[i].setValue(0, 0, 0);
	const btVector3 org = body.m_nodes[0].m_x;
	btSoftBody::Node* base = &body.m_nodes[0];
	btScalar volume = 0;
	for (int i = 0; i < body.m_faces.size(); ++i)
	{
		const btSoftBody::Face& f = body.m_faces[i];
		const btVector3 a = f.m_n[0]->m_x - org, b = f.m_n[1]->m_x - org, c = f.m_n[2]->m_x - org;
		volume += a.dot(b.cross(c));
		grad[int(f.m_n[0] - base)] += b.cross(c);
		grad[int(f.m_n[1] - base)] += c.cross(a);
		grad[int(f.m_n[2] - base)] += a.cross(b);
	}
	volume /= 6;
	btScalar denom = 0;
	for (int i = 0; i < n; ++i)
	{
		grad[i] /= 6;
		denom += body.m_nodes[i].m_im * grad[i].length2();
	}
	const btScalar alpha = (btFabs(volume) < btFabs(target) ? complianceShrunk : complianceGrown) / (dt * dt);
	denom += alpha;
	if (!(denom > 0)) return;
	const btScalar dlambda = (-(volume - target) - alpha * lambda) / denom;
	lambda += dlambda;
	for (int i = 0; i < n; ++i) body.m_nodes[i].m_x += grad[i] * (dlambda * body.m_nodes[i].m_im);
}

void solveAnchors(btSoftBody& body, btScalar dt)
{
	const btScalar hardness = btClamped(body.m_cfg.kAHR, btScalar(0), btScalar(1));
	for (int i = 0; i < body.m_anchors.size(); ++i)
	{
		btSoftBody::Anchor& a = body.m_anchors[i];
		btSoftBody::Node& n = *a.m_node;
		const btTransform& t = a.m_body->getWorldTransform();
		const btVector3 target = t * a.m_local;
		const btVector3 err = n.m_x - target;
		if (err.length2() <= SIMD_EPSILON * SIMD_EPSILON) continue;
		const btVector3 r = target - t.getOrigin();
		a.m_c1 = r;
		const btScalar len = err.length();
		const btVector3 dir = err / len;
		const btScalar wb = isMovable(a.m_body) ? rigidInverseMass(a.m_body, r, dir) * a.m_influence : btScalar(0);
		const btScalar w = n.m_im + wb;
		if (w <= 0) continue;
		// A position impulse along the error, shared by node and body by their inverse masses.
		const btScalar lambda = -len * hardness / w;
		n.m_x += dir * (lambda * n.m_im);
		if (wb > 0)
		{
			moveRigid(a.m_body, -dir * (lambda * a.m_influence), r, dt);
			a.m_body->activate();
		}
	}
}

// Rigid contacts.
// Rigid corners against faces (btSoftBodyFaceContacts.h): the corner kept on its side of the face, the
// correction shared by the body (at the corner, with its inertia) and the face's nodes (by barycentric
// weights and inverse masses), with the node contacts' inelastic velocity share.
void solveFaceContacts(btScalar dt, btScalar margin, caliber::SoftFaceContacts& faceContacts)
{
	for (int i = 0; i < faceContacts.contacts.size(); ++i)
	{
		const caliber::SoftFaceContact& c = faceContacts.contacts[i];
		btSoftBody::Node* f[3] = {c.face->m_n[0], c.face->m_n[1], c.face->m_n[2]};
		btVector3 normal = (f[1]->m_x - f[0]->m_x).cross(f[2]->m_x - f[0]->m_x);
		const btScalar len = normal.length();
		if (len <= SIMD_EPSILON) continue;
		normal *= c.side / len;  // towards the side the corner is kept on
		const btTransform& t = c.object->getWorldTransform();
		const btVector3 corner = t * c.local;
		const btVector3 p = f[0]->m_x * c.weights[0] + f[1]->m_x * c.weights[1] + f[2]->m_x * c.weights[2];
		const btScalar gap = normal.dot(corner - p) - c.thickness;
		// A point more than three margins behind the face has gone through it (or the face folded over
		// it): pulling it back across would fling body and cloth apart (the benchmark's pinned cloth with
		// 25 boxes blew up so); shallower, it is pulled back (a falling box's points are caught so).
		if (gap >= 0 || gap < -3 * margin) continue;
		btRigidBody* rb = const_cast<btRigidBody*>(btRigidBody::upcast(c.object));
		const bool movable = isMovable(rb);
		const btVector3 r = corner - t.getOrigin();
		btScalar w = movable ? rigidInverseMass(rb, r, normal) : btScalar(0);
		for (int k = 0; k < 3; ++k) w += c.weights[k] * c.weights[k] * f[k]->m_im;
		if (w <= 0) continue;
		const btScalar lambda = -gap * c.hardness / w;
		// The rate at which face and corner approach along the normal; velocities change only as far as
		// stops it, the rest of the push moves positions alone (as for node contacts).
		const btVector3 faceMove = (f[0]->m_x - f[0]->m_q) * c.weights[0] + (f[1]->m_x - f[1]->m_q) * c.weights[1] +
		                           (f[2]->m_x - f[2]->m_q) * c.weights[2];
		const btVector3 cornerVelocity = movable ? rb->getVelocityInLocalPoint(r) : btVector3(0, 0, 0);
		const btScalar approach = (faceMove / dt - cornerVelocity).dot(normal);
		const btScalar change = lambda * w / dt;
		const btScalar share = change > 0 ? btClamped(approach / change, btScalar(0), btScalar(1)) : btScalar(1);
		for (int k = 0; k < 3; ++k)
		{
			const btVector3 move = normal * (lambda * c.weights[k] * f[k]->m_im);
			f[k]->m_x -= move;
			f[k]->m_q -= move * (1 - share);
		}
		if (movable)
		{
			moveRigid(rb, normal * lambda, r, dt, share);
			rb->activate();
		}
	}
}

void solveContacts(btSoftBody& body, btScalar dt, caliber::SoftFaceContacts* faceContacts)
{
	if (faceContacts) solveFaceContacts(dt, body.m_sst.radmrg, *faceContacts);
	for (int i = 0; i < body.m_rcontacts.size(); ++i)
	{
		btSoftBody::RContact& c = body.m_rcontacts[i];
		btSoftBody::Node& n = *c.m_node;
		if (n.m_im <= 0) continue;
		btRigidBody* rb = const_cast<btRigidBody*>(btRigidBody::upcast(c.m_cti.m_colObj));
		const btTransform& t = c.m_cti.m_colObj->getWorldTransform();
		// The contact plane moves with its object: local point m_c1, local normal in m_c0's first row.
		const btVector3 p = t * c.m_c1;
		const btVector3 normal = t.getBasis() * c.m_c0[0];
		const btScalar depth = normal.dot(n.m_x - p);
		if (depth >= 0) continue;
		const btVector3 r = p - t.getOrigin();
		const bool movable = isMovable(rb);
		const btScalar wb = movable ? rigidInverseMass(rb, r, normal) : btScalar(0);
		const btScalar wn = n.m_im;
		const btScalar w = wn + wb;
		if (w <= 0) continue;
		const btScalar lambda = -depth * c.m_c4 / w;
		const btVector3 nodeBefore = n.m_x;
		n.m_x += normal * (lambda * wn);
		btVector3 impulse = -normal * lambda;
		// Friction (Coulomb, at position level): the node's slide relative to the surface this step is
		// undone while it is within m_c3 times the normal correction, cut by that much otherwise.
		if (c.m_c3 > 0)
		{
			const btVector3 surfaceMove = rb ? rb->getVelocityInLocalPoint(r) * dt : btVector3(0, 0, 0);
			btVector3 slide = (n.m_x - n.m_q) - surfaceMove;
			slide -= normal * normal.dot(slide);
			const btScalar slideLen = slide.length();
			if (slideLen > SIMD_EPSILON)
			{
				const btVector3 sdir = slide / slideLen;
				const btScalar wt = n.m_im + (movable ? rigidInverseMass(rb, r, sdir) : btScalar(0));
				btScalar mu = -slideLen / wt;
				const btScalar limit = c.m_c3 * lambda;
				if (-mu > limit) mu = -limit;
				n.m_x += sdir * (mu * n.m_im);
				impulse -= sdir * mu;
			}
		}
		if (movable)
		{
			// Velocities change only as far as node and body stop approaching each other (an inelastic
			// contact), both by the same share of the correction, so momentum is conserved; the rest of
			// the push moves positions alone (the node's start moves with it), as a split impulse does,
			// so that resolving a penetration never launches either.
			btScalar share = 1;
			const btScalar approach =
			    rb->getVelocityInLocalPoint(r).dot(normal) - (nodeBefore - n.m_q).dot(normal) / dt;
			const btScalar change = lambda * w / dt;
			if (change > 0) share = btClamped(approach / change, btScalar(0), btScalar(1));
			n.m_q += normal * (lambda * wn * (1 - share));
			moveRigid(rb, -normal * lambda, r, dt, share);
			if (impulse != -normal * lambda) moveRigid(rb, impulse + normal * lambda, r, dt);
			rb->activate();
		}
	}
}
}  // namespace

namespace
{
// Soft-soft contacts (VF_SS): a node of this body kept on its side of another body's face, at the
// distance m_margin; the correction is shared by the node and the face's nodes by their inverse masses
// and barycentric weights, so momentum is conserved; Coulomb friction with the larger kDF.
void solveSoftContacts(btSoftBody& body, btScalar dt)
{
	for (int i = 0; i < body.m_scontacts.size(); ++i)
	{
		btSoftBody::SContact& c = body.m_scontacts[i];
		btSoftBody::Node& n = *c.m_node;
		btSoftBody::Node* f[3] = {c.m_face->m_n[0], c.m_face->m_n[1], c.m_face->m_n[2]};
		btVector3 normal = (f[1]->m_x - f[0]->m_x).cross(f[2]->m_x - f[0]->m_x);
		const btScalar len = normal.length();
		if (len <= SIMD_EPSILON) continue;
		normal *= c.m_cfm[0] / len;  // the side the node came from
		const btVector3 p = f[0]->m_x * c.m_weights[0] + f[1]->m_x * c.m_weights[1] + f[2]->m_x * c.m_weights[2];
		const btScalar gap = normal.dot(n.m_x - p) - c.m_margin;
		if (gap >= 0) continue;
		btScalar w = n.m_im;
		for (int k = 0; k < 3; ++k) w += c.m_weights[k] * c.m_weights[k] * f[k]->m_im;
		if (w <= 0) continue;
		const btScalar lambda = -gap / w;
		// As for rigid contacts: velocities change only as far as node and face stop approaching (an
		// inelastic contact), the rest moves positions alone (the start points move with them).
		btVector3 faceMove = (f[0]->m_x - f[0]->m_q) * c.m_weights[0] + (f[1]->m_x - f[1]->m_q) * c.m_weights[1] +
		                     (f[2]->m_x - f[2]->m_q) * c.m_weights[2];
		const btScalar approach = (faceMove - (n.m_x - n.m_q)).dot(normal) / dt;
		const btScalar change = lambda * w / dt;
		const btScalar positionOnly = 1 - (change > 0 ? btClamped(approach / change, btScalar(0), btScalar(1)) : 1);
		n.m_x += normal * (lambda * n.m_im);
		n.m_q += normal * (lambda * n.m_im * positionOnly);
		for (int k = 0; k < 3; ++k)
		{
			const btVector3 move = normal * (lambda * c.m_weights[k] * f[k]->m_im);
			f[k]->m_x -= move;
			f[k]->m_q -= move * positionOnly;
		}
		if (!(c.m_friction > 0)) continue;
		// Coulomb friction, as against rigid objects: the node's slide over the face this step is undone
		// while it needs less than m_friction times the normal correction, cut by that much otherwise;
		// shared by the node and the face's nodes as the normal correction is (momentum is conserved).
		faceMove = (f[0]->m_x - f[0]->m_q) * c.m_weights[0] + (f[1]->m_x - f[1]->m_q) * c.m_weights[1] +
		           (f[2]->m_x - f[2]->m_q) * c.m_weights[2];
		btVector3 slide = (n.m_x - n.m_q) - faceMove;
		slide -= normal * normal.dot(slide);
		const btScalar slideLength = slide.length();
		if (slideLength <= SIMD_EPSILON) continue;
		const btScalar mu = btMin(slideLength / w, c.m_friction * lambda);
		const btVector3 dir = slide / slideLength;
		n.m_x -= dir * (mu * n.m_im);
		for (int k = 0; k < 3; ++k) f[k]->m_x += dir * (mu * c.m_weights[k] * f[k]->m_im);
	}
}
}  // namespace

namespace
{
// Substeps ("small steps", Macklin, Storey, Lu et al. 2019; docs/soft-bodies.md, "Substeps"). Under a steady
// load a Gauss-Seidel sweep leaves an error that grows with the load's move per step, g h^2, and contacts with
// friction keep it from step to step; the same sweeps over n substeps cut that move by n^2 (bench_soft's
// cloth_drape: worst link 1.40 -> 1.21). The stiffness stays the one kLST and piterations define (the
// compliance is taken over the substep's h^2).

// Bodies with clusters or joints (whose stage runs once per step, after this solve), anchored to or touching a
// movable rigid body (its pose moves once per step, so the velocity its share of a substep's push gave it would
// be felt by the next substeps without the body moving), or with soft-soft contacts of their own (they compare
// the other body's move over the whole step with this body's) keep the single step.
bool canSubstep(const btSoftBody& body, const caliber::SoftFaceContacts* faceContacts)
{
	if (body.m_clusters.size() > 0 || body.m_joints.size() > 0 || body.m_scontacts.size() > 0) return false;
	for (int i = 0; i < body.m_anchors.size(); ++i)
		if (isMovable(body.m_anchors[i].m_body)) return false;
	for (int i = 0; i < body.m_rcontacts.size(); ++i)
		if (isMovable(btRigidBody::upcast(body.m_rcontacts[i].m_cti.m_colObj))) return false;
	for (int i = 0; faceContacts && i < faceContacts->contacts.size(); ++i)
		if (isMovable(btRigidBody::upcast(faceContacts->contacts[i].object))) return false;
	return true;
}

// A substep's prediction. The first substep starts from the step's start (kept in start for finishSubsteps):
// the prediction's move over the whole step (forces, gravity, pushes by other bodies' contacts) becomes its
// velocity; a later one takes the last substep's move as its velocity. Gravity is added per substep. Each
// substep is an XPBD step of its own, so the multipliers start at zero (the links' in the substep's first
// sweep, which saves a pass over them).
void predictNodes(btSoftBody::Node* nodes, btVector3* starts, int begin, int end, btScalar dt, btScalar h,
                  btVector3 gravity, bool first)
{
	for (int i = begin; i < end; ++i)
	{
		btSoftBody::Node& n = nodes[i];
		if (first) starts[i] = n.m_q;
		if (n.m_im <= 0) continue;
		if (first)
		{
			n.m_v = (n.m_x - n.m_q) / dt - gravity * dt;
			n.m_x = n.m_q;
		}
		else
			n.m_v = (n.m_x - n.m_q) / h;
		n.m_v += gravity * h;
		n.m_q = n.m_x;
		n.m_x += n.m_v * h;
	}
}

void predictSubstep(btSoftBody& body, btScalar dt, btScalar h, const btVector3& gravity, bool first,
                    btAlignedObjectArray<btVector3>& start)
{
	if (first) start.resize(body.m_nodes.size());
	btSoftBody::Node* nodes = body.m_nodes.size() > 0 ? &body.m_nodes[0] : 0;
	btVector3* starts = first && start.size() > 0 ? &start[0] : 0;
	// Each node on its own: in chunks on the task scheduler for a large body (the work in a function of
	// plain values, so that the loop keeps them in registers).
	caliber::forEachChunk(body.m_nodes.size(), [=](int begin, int end) {
		predictNodes(nodes, starts, begin, end, dt, h, gravity, first);
	});
	for (int i = 0; i < body.m_tetras.size(); ++i) body.m_tetras[i].m_c2 = 0;
}

// integrateMotion takes the velocity as (x - q) / dt: the last substep's move over h. A node gone non-finite gets its
// step's start back as q, where integrateMotion puts it (docs/bad-input.md).
void finishNodes(btSoftBody::Node* nodes, const btVector3* starts, int begin, int end, btScalar dt, btScalar h)
{
	for (int i = begin; i < end; ++i)
	{
		btSoftBody::Node& n = nodes[i];
		if (n.m_im <= 0) continue;
		n.m_v = (n.m_x - n.m_q) / h;
		n.m_q = n.m_x - n.m_v * dt;
		if (!caliber::isFinite(n.m_q)) n.m_q = starts[i];
	}
}

void finishSubsteps(btSoftBody& body, btScalar dt, btScalar h, const btAlignedObjectArray<btVector3>& start)
{
	btSoftBody::Node* nodes = body.m_nodes.size() > 0 ? &body.m_nodes[0] : 0;
	const btVector3* starts = start.size() > 0 ? &start[0] : 0;
	caliber::forEachChunk(body.m_nodes.size(),
	                      [=](int begin, int end) { finishNodes(nodes, starts, begin, end, dt, h); });
}

// Pose matching (kMT) for nodes [begin, end): each free node goes k of the way to its place in the rest shape.
void matchPose(btSoftBody::Node* nodes, const btSoftBody::Pose& pose, int begin, int end, btScalar k)
{
	const btVector3 com = pose.m_com;
	const btMatrix3x3 rot = pose.m_rot;
	for (int i = begin; i < end; ++i)
	{
		btSoftBody::Node& n = nodes[i];
		if (n.m_im <= 0) continue;
		const btVector3 goal = com + rot * pose.m_pos[i];
		n.m_x += (goal - n.m_x) * k;
	}
}
}  // namespace

void btSoftBody::solveConstraints()
{
	const btScalar dt = m_sst.sdt;
	if (!(dt > 0)) return;
	// Anchors whose body has left its world (no broadphase handle while this body is in one) let go.
	if (getBroadphaseHandle())
		for (int i = m_anchors.size() - 1; i >= 0; --i)
			if (!m_anchors[i].m_body->getBroadphaseHandle())
			{
				btAssert(!"btSoftBody: an anchored rigid body was removed from the world");
				caliber::softBodyWarning(
				    "Caliber: btSoftBody: an anchored rigid body was removed from the world; the anchor is removed\n");
				m_anchors[i].m_node->m_battach = 0;
				m_anchors.swap(i, m_anchors.size() - 1);
				m_anchors.pop_back();
			}
	// This step's links, packed for the sweeps by predictMotion (with the compliance of the materials' kLST).
	caliber::SoftLinkSweep& packedLinks = caliber::startSoftLinkStep(*this, m_cfg.piterations);
	for (int i = 0; i < m_tetras.size(); ++i) m_tetras[i].m_c2 = 0;
	const bool keepVolume = m_cfg.kVC > 0 && m_pose.m_bvolume && m_faces.size() > 0;
	const caliber::SoftBodyTethers& tethers = caliber::softBodyTethers(*this, false);
	// Bodies of one block of links need no colouring (nor its side table lookup).
	const caliber::SoftLinkColours* linkColours =
	    m_links.size() > caliber::kLinkBlock ? &caliber::softLinkColours(*this, false) : 0;
	// A pressurised closed body whose skin cannot stretch holds its rest volume V0: its skin's tension
	// balances any pressure above V0 (a closed surface of rigid triangles cannot grow), and the gas resists
	// compression with the stiffness of P V = kPR, dP / dV = -kPR / V0^2, i.e. the compliance V0^2 / kPR.
	// (Applied as a force, the pressure would be undone by Gauss-Seidel sweeps only slowly, since each
	// link pulls tangentially against a uniform inflation.)
	const bool gasVolume = m_cfg.kPR > 0 && tethers.inextensibleSkin && tethers.restVolume != 0;
	btScalar gasLambda = 0;
	btScalar volumeLambda = 0;
	// Scratch of the volume constraint, reused from step to step on each thread.
	static thread_local btAlignedObjectArray<btVector3> volumeGradient;
	caliber::SoftFaceContacts* faceContacts = m_faces.size() > 0 ? &caliber::softFaceContacts(*this) : 0;
	const int iterations = btMax(m_cfg.piterations, 1);
	// Substeps (docs/soft-bodies.md, "Substeps"): the sweeps run in up to kMaxSubsteps substeps of h / n.
	const bool substeps = iterations > 1 && canSubstep(*this, faceContacts);
	const int stepCount = substeps ? btMin(iterations, kMaxSubsteps) : 1;
	const btScalar h = dt / btScalar(stepCount);
	const btVector3 gravity = m_worldInfo ? m_worldInfo->m_gravity : btVector3(0, 0, 0);
	static thread_local btAlignedObjectArray<btVector3> stepStart;
	int linearPerSweep = 0;
	for (int s = 0; s < m_cfg.m_psequence.size(); ++s) linearPerSweep += m_cfg.m_psequence[s] == ePSolver::Linear;
	for (int sub = 0; sub < stepCount; ++sub)
	{
		// This substep's sweeps: the iterations shared out, the first substeps taking the remainder.
		const int sweeps = iterations / stepCount + (sub < iterations % stepCount ? 1 : 0);
		if (substeps)
		{
			predictSubstep(*this, dt, h, gravity, sub == 0, stepStart);
			volumeLambda = gasLambda = 0;
		}
		// The link sweeps of this substep, counted so that the first starts the multipliers at zero and the
		// last keeps none.
		const int linkSolves = sweeps * linearPerSweep;
		int linkSolve = 0;
		for (int sweep = 0; sweep < sweeps; ++sweep)
			for (int s = 0; s < m_cfg.m_psequence.size(); ++s) switch (m_cfg.m_psequence[s])
				{
					case ePSolver::Linear:
						caliber::solveSoftLinks(*this, packedLinks, h, linkColours, linkSolve == 0,
						                        linkSolve + 1 == linkSolves);
						++linkSolve;
						if (m_tetras.size() > 0) solveTetras(*this, h);
						caliber::solveTethers(*this, tethers);
						if (keepVolume)
							solveVolume(*this, h, m_pose.m_volume, 1 / m_cfg.kVC, 1 / m_cfg.kVC, volumeLambda,
							            volumeGradient);
						if (gasVolume)
							solveVolume(*this, h, tethers.restVolume,
							            tethers.restVolume * tethers.restVolume / m_cfg.kPR, 0, gasLambda,
							            volumeGradient);
						break;
					case ePSolver::Anchors:
						solveAnchors(*this, h);
						break;
					case ePSolver::RContacts:
						solveContacts(*this, h, faceContacts);
						break;
					case ePSolver::SContacts:
						solveSoftContacts(*this, h);
						break;
					default:
						break;
				}
		if (substeps)
		{
			// The substep ends out of the rigid objects; its velocity is its move (taken by the next).
			solveContacts(*this, h, faceContacts);
		}
	}
	if (substeps) finishSubsteps(*this, dt, h, stepStart);
	if (m_cfg.kMT > 0 && m_pose.m_bframe)
	{
		updatePose();
		const btScalar k = btClamped(m_cfg.kMT, btScalar(0), btScalar(1));
		Node* nodes = m_nodes.size() > 0 ? &m_nodes[0] : 0;
		const Pose* pose = &m_pose;
		caliber::forEachChunk(m_nodes.size(), [=](int begin, int end) { matchPose(nodes, *pose, begin, end, k); });
	}
	// Clusters: self-collision (found now, as the soft-soft pairs of the collision pass), then the
	// cluster contacts and joints.
	if ((m_cfg.collisions & fCollision::CL_SELF) && m_clusters.size() > 1)
	{
		for (int i = 0; i < m_clusters.size(); ++i) caliber::refreshCluster(*m_clusters[i], dt);
		caliber::updateClusterTree(*this);  // the node solves moved the clusters since the prediction
		caliber::collideClustersWithClusters(*this, *this);
	}
	if (m_clusters.size() > 0 || m_joints.size() > 0)
	{
		// The default solver runs the cluster stages of its bodies together, then finishes each body.
		if (caliber::clusterState(*this).deferred) return;
		caliber::solveClusterStage(*this, dt);
	}
	// Contacts have the last word: the links (and pose matching) of the last sweep must not leave nodes
	// inside rigid objects, nor rigid points behind faces.
	solveContacts(*this, dt, faceContacts);
}

void caliber::finishSoftSolve(btSoftBody& body)
{
	solveContacts(body, body.m_sst.sdt, body.m_faces.size() > 0 ? &caliber::softFaceContacts(body) : 0);
}

void btSoftBody::staticSolve(int iterations)
{
	if (m_bUpdateRtCst) updateConstants();
	// Packed with the compliance of one sweep a step; the next solve packs its own.
	caliber::SoftLinkSweep& packedLinks = caliber::packSoftLinks(*this, 1);
	packedLinks.unsolved = false;
	const caliber::SoftLinkColours* colours =
	    m_links.size() > caliber::kLinkBlock ? &caliber::refreshSoftLinkColours(*this, packedLinks.nodeSignature) : 0;
	for (int it = 0; it < iterations; ++it)
		caliber::solveSoftLinks(*this, packedLinks, kReferenceStep, colours, it == 0, it + 1 == iterations);
}

void btSoftBody::solveCommonConstraints(btSoftBody** bodies, int count, int iterations)
{
	(void)bodies;
	(void)count;
	(void)iterations;
}

void btSoftBody::integrateMotion()
{
	// Velocities from the step's moves, once every body of the world has been solved (soft-soft
	// contacts move the nodes of both bodies).
	if (m_sst.sdt > 0)
	{
		struct Velocities : btIParallelForBody
		{
			btSoftBody::Node* nodes;
			btScalar scale;
			mutable std::atomic<bool> repaired{false};
			void forLoop(int begin, int end) const override
			{
				for (int i = begin; i < end; ++i)
				{
					Node& n = nodes[i];
					if (n.m_im <= 0)
					{
						n.m_v.setValue(0, 0, 0);
						continue;
					}
					n.m_v = (n.m_x - n.m_q) * scale;
					if (!caliber::isFinite(n.m_x) || !caliber::isFinite(n.m_v))
					{
						n.m_x = n.m_q;
						n.m_v.setValue(0, 0, 0);
						repaired.store(true, std::memory_order_relaxed);
					}
				}
			}
		};
		Velocities velocities;
		velocities.nodes = m_nodes.size() > 0 ? &m_nodes[0] : 0;
		velocities.scale = m_sst.isdt * (1 - btClamped(m_cfg.kDP, btScalar(0), btScalar(1)));
		caliber::forEachNodeChunk(m_nodes.size(), velocities);
		if (velocities.repaired.load(std::memory_order_relaxed))
			caliber::softBodyWarning(
			    "Caliber: btSoftBody: a node's state became non-finite; it is put back where it started the step\n");
	}
	if (m_clusters.size() > 0) dampClusters();
	// The nodes moved: face boxes are rebuilt by the next collision pass, whoever runs it.
	if (m_faces.size() > 0) caliber::softFaceContacts(*this).boxesValid = false;
	updateNormals();
	updateBounds();
}
