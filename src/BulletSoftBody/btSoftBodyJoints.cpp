// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Cluster joints (LJoint, AJoint, CJoint), the joint sides (btSoftBody::Body) and the cluster stage of
// the position solve: cluster contacts and joints, citerations times per step, then shape matching.
// docs/soft-bodies.md, "Clusters" and "Joints".

#include <cstdio>

#include "BulletSoftBody/btSoftBody.h"
#include "btSoftBodyClusters.h"
#include "btSoftBodyInternal.h"

using caliber::softBodyWarning;

namespace
{
const btMatrix3x3& zeroMatrix()
{
	static const btMatrix3x3 zero(0, 0, 0, 0, 0, 0, 0, 0, 0);
	return zero;
}
const btTransform& identityTransform()
{
	static const btTransform identity = btTransform::getIdentity();
	return identity;
}

// The solver's view of a joint side: where its centre is, how it moves, how it is pushed.
btRigidBody* movableRigid(const btSoftBody::Body& b) { return caliber::isMovable(b.m_rigid) ? b.m_rigid : 0; }

btVector3 sideCentre(const btSoftBody::Body& b)
{
	if (b.m_soft) return b.m_soft->m_com;
	if (b.m_collisionObject) return b.m_collisionObject->getWorldTransform().getOrigin();
	return btVector3(0, 0, 0);
}

btScalar sideInverseMass(const btSoftBody::Body& b, const btVector3& r, const btVector3& n)
{
	if (b.m_soft) return caliber::clusterInverseMass(*b.m_soft, r, n);
	return caliber::rigidInverseMass(movableRigid(b), r, n);
}

btScalar sideAngularInverseMass(const btSoftBody::Body& b, const btVector3& n)
{
	if (b.m_soft) return caliber::clusterAngularInverseMass(*b.m_soft, n);
	if (btRigidBody* rb = movableRigid(b)) return n.dot(rb->getInvInertiaTensorWorld() * n);
	return 0;
}

void sidePush(const btSoftBody::Body& b, const btVector3& p, const btVector3& r, btScalar dt, btScalar share)
{
	if (b.m_soft)
		caliber::moveCluster(*b.m_soft, p, r, dt, share);
	else if (btRigidBody* rb = movableRigid(b))
	{
		caliber::moveRigid(rb, p, r, dt, share);
		rb->activate();
	}
}

void sideTurn(const btSoftBody::Body& b, const btVector3& l, btScalar dt, btScalar share)
{
	if (b.m_soft)
		caliber::turnCluster(*b.m_soft, l, dt, share);
	else if (btRigidBody* rb = movableRigid(b))
	{
		caliber::turnRigid(rb, l, dt, share);
		rb->activate();
	}
}
}  // namespace

// ---- btSoftBody::Body ------------------------------------------------------------------------------

void btSoftBody::Body::activate() const
{
	if (m_rigid) m_rigid->activate();
}

const btMatrix3x3& btSoftBody::Body::invWorldInertia() const
{
	if (m_soft) return m_soft->m_invwi;
	if (caliber::isMovable(m_rigid)) return m_rigid->getInvInertiaTensorWorld();
	return zeroMatrix();
}

btScalar btSoftBody::Body::invMass() const
{
	if (m_soft) return m_soft->m_imass;
	return caliber::isMovable(m_rigid) ? m_rigid->getInvMass() : btScalar(0);
}

const btTransform& btSoftBody::Body::xform() const
{
	if (m_soft) return m_soft->m_framexform;
	if (m_collisionObject) return m_collisionObject->getWorldTransform();
	return identityTransform();
}

btVector3 btSoftBody::Body::linearVelocity() const
{
	if (m_soft) return m_soft->m_lv;
	if (m_rigid) return m_rigid->getLinearVelocity();
	return btVector3(0, 0, 0);
}

btVector3 btSoftBody::Body::angularVelocity() const
{
	if (m_soft) return m_soft->m_av;
	if (m_rigid) return m_rigid->getAngularVelocity();
	return btVector3(0, 0, 0);
}

btVector3 btSoftBody::Body::angularVelocity(const btVector3& rpos) const { return angularVelocity().cross(rpos); }

btVector3 btSoftBody::Body::velocity(const btVector3& rpos) const { return linearVelocity() + angularVelocity(rpos); }

void btSoftBody::Body::applyVImpulse(const btVector3& impulse, const btVector3& rpos) const
{
	if (m_soft) btSoftBody::clusterVImpulse(m_soft, rpos, impulse);
	if (caliber::isMovable(m_rigid)) m_rigid->applyImpulse(impulse, rpos);
}

void btSoftBody::Body::applyDImpulse(const btVector3& impulse, const btVector3& rpos) const
{
	if (m_soft) btSoftBody::clusterDImpulse(m_soft, rpos, impulse);
	if (caliber::isMovable(m_rigid)) m_rigid->applyImpulse(impulse, rpos);
}

void btSoftBody::Body::applyImpulse(const Impulse& impulse, const btVector3& rpos) const
{
	if (impulse.m_asVelocity) applyVImpulse(impulse.m_velocity, rpos);
	if (impulse.m_asDrift) applyDImpulse(impulse.m_drift, rpos);
}

void btSoftBody::Body::applyVAImpulse(const btVector3& impulse) const
{
	if (m_soft) btSoftBody::clusterVAImpulse(m_soft, impulse);
	if (caliber::isMovable(m_rigid)) m_rigid->applyTorqueImpulse(impulse);
}

void btSoftBody::Body::applyDAImpulse(const btVector3& impulse) const
{
	if (m_soft) btSoftBody::clusterDAImpulse(m_soft, impulse);
	if (caliber::isMovable(m_rigid)) m_rigid->applyTorqueImpulse(impulse);
}

void btSoftBody::Body::applyAImpulse(const Impulse& impulse) const
{
	if (impulse.m_asVelocity) applyVAImpulse(impulse.m_velocity);
	if (impulse.m_asDrift) applyDAImpulse(impulse.m_drift);
}

void btSoftBody::Body::applyDCImpulse(const btVector3& impulse) const
{
	if (m_soft) btSoftBody::clusterDCImpulse(m_soft, impulse);
	if (caliber::isMovable(m_rigid)) m_rigid->applyCentralImpulse(impulse);
}

// ---- joints ----------------------------------------------------------------------------------------

void btSoftBody::Joint::Prepare(btScalar dt, int iterations)
{
	(void)dt;
	(void)iterations;
	m_bodies[0].activate();
	m_bodies[1].activate();
}

void btSoftBody::LJoint::Prepare(btScalar dt, int iterations) { Joint::Prepare(dt, iterations); }

void btSoftBody::LJoint::Solve(btScalar dt, btScalar sor)
{
	// The two points, carried by their sides' frames, are pulled together by a position impulse shared
	// by the sides' inverse masses at the points (erp of the gap per solve).
	const btVector3 pa = m_bodies[0].xform() * m_refs[0];
	const btVector3 pb = m_bodies[1].xform() * m_refs[1];
	const btVector3 gap = pb - pa;
	m_drift = gap;
	const btScalar len = gap.length();
	if (len <= SIMD_EPSILON) return;
	const btVector3 n = gap / len;
	m_rpos[0] = pa - sideCentre(m_bodies[0]);
	m_rpos[1] = pb - sideCentre(m_bodies[1]);
	const btScalar w = sideInverseMass(m_bodies[0], m_rpos[0], n) + sideInverseMass(m_bodies[1], m_rpos[1], n);
	if (!(w > 0)) return;
	const btScalar lambda = len * btClamped(m_erp, btScalar(0), btScalar(1)) * sor / w;
	sidePush(m_bodies[0], n * lambda, m_rpos[0], dt, 1);
	sidePush(m_bodies[1], -n * lambda, m_rpos[1], dt, 1);
}

void btSoftBody::LJoint::Terminate(btScalar dt) { (void)dt; }

void btSoftBody::AJoint::Prepare(btScalar dt, int iterations)
{
	Joint::Prepare(dt, iterations);
	if (m_icontrol) m_icontrol->Prepare(this);
}

void btSoftBody::AJoint::Solve(btScalar dt, btScalar sor)
{
	// The axes, carried by the sides' frames, are turned into line (erp of the angle per solve), then the
	// turn rate about the axis is set to what the control asks for (a motor; the default leaves it).
	m_axis[0] = (m_bodies[0].xform().getBasis() * m_refs[0]).normalized();
	m_axis[1] = (m_bodies[1].xform().getBasis() * m_refs[1]).normalized();
	const btVector3 e = m_axis[0].cross(m_axis[1]);
	const btScalar s = e.length();
	m_drift = e;
	if (s > SIMD_EPSILON)
	{
		const btVector3 u = e / s;
		const btScalar angle = btAtan2(s, m_axis[0].dot(m_axis[1]));
		const btScalar w = sideAngularInverseMass(m_bodies[0], u) + sideAngularInverseMass(m_bodies[1], u);
		if (w > 0)
		{
			const btScalar lambda = angle * btClamped(m_erp, btScalar(0), btScalar(1)) * sor / w;
			sideTurn(m_bodies[0], u * lambda, dt, 1);
			sideTurn(m_bodies[1], -u * lambda, dt, 1);
		}
	}
	if (!m_icontrol || !(dt > 0)) return;
	const btVector3 axis = m_axis[0];
	const btScalar current = (m_bodies[0].angularVelocity() - m_bodies[1].angularVelocity()).dot(axis);
	const btScalar target = m_icontrol->Speed(this, current);
	if (!(target == target) || target == current) return;  // NaN from a control: ignored
	const btScalar w = sideAngularInverseMass(m_bodies[0], axis) + sideAngularInverseMass(m_bodies[1], axis);
	if (!(w > 0)) return;
	// A turn of (target - current) dt about the axis this step changes the turn rate by target - current.
	const btScalar lambda = (target - current) * dt / w;
	sideTurn(m_bodies[0], axis * lambda, dt, 1);
	sideTurn(m_bodies[1], -axis * lambda, dt, 1);
}

void btSoftBody::AJoint::Terminate(btScalar dt) { (void)dt; }

void btSoftBody::CJoint::Prepare(btScalar dt, int iterations) { Joint::Prepare(dt, iterations); }

void btSoftBody::CJoint::Solve(btScalar dt, btScalar sor)
{
	// A one-sided point contact: the points (fixed offsets from the sides' centres) are kept from
	// approaching along m_normal beyond touching.
	const btVector3 pa = sideCentre(m_bodies[0]) + m_rpos[0];
	const btVector3 pb = sideCentre(m_bodies[1]) + m_rpos[1];
	const btScalar gap = m_normal.dot(pa - pb);
	if (gap >= 0) return;
	const btScalar w =
	    sideInverseMass(m_bodies[0], m_rpos[0], m_normal) + sideInverseMass(m_bodies[1], m_rpos[1], m_normal);
	if (!(w > 0)) return;
	const btScalar lambda = -gap * btClamped(m_erp, btScalar(0), btScalar(1)) * sor / w;
	sidePush(m_bodies[0], m_normal * lambda, m_rpos[0], dt, 0);
	sidePush(m_bodies[1], -m_normal * lambda, m_rpos[1], dt, 0);
}

void btSoftBody::CJoint::Terminate(btScalar dt)
{
	(void)dt;
	if (++m_life > m_maxlife) m_delete = true;
}

// ---- appending joints ------------------------------------------------------------------------------

namespace
{
// A joint side is usable when it is the world, a rigid object, or a live cluster.
bool usableSide(const btSoftBody::Body& b) { return !b.m_soft || caliber::clusterOwner(b.m_soft) != 0; }

template <class J>
J* newJoint()
{
	J* joint = new (btAlignedAlloc(sizeof(J), 16)) J();
	// Scratch that not every joint kind's preparation writes, but that snapshots save: never uninitialised.
	joint->m_massmatrix.setValue(0, 0, 0, 0, 0, 0, 0, 0, 0);
	return joint;
}

bool checkJoint(btSoftBody& self, btSoftBody::Cluster* body0, const btSoftBody::Body& body1, const char* what)
{
	const bool ok = body0 && caliber::clusterOwner(body0) == &self && usableSide(body1) && body1.m_soft != body0;
	btAssert(ok && "btSoftBody: joint to a missing cluster (none, another body's, released) or to itself");
	if (!ok)
	{
		char message[256];
		snprintf(message, sizeof(message),
		         "Caliber: btSoftBody::%s: the first side is not one of this body's clusters, or the second side is "
		         "a released cluster or the same cluster; no joint added\n",
		         what);
		softBodyWarning(message);
	}
	return ok;
}

void setSpecs(btSoftBody::Joint& j, const btSoftBody::Joint::Specs& specs, btSoftBody::Cluster* body0,
              const btSoftBody::Body& body1)
{
	j.m_bodies[0] = body0;
	j.m_bodies[1] = body1;
	j.m_erp = specs.erp;
	j.m_cfm = specs.cfm;
	j.m_split = specs.split;
	// Frames now (a cluster's frame follows its nodes).
	caliber::refreshCluster(*body0, 0);
	if (body1.m_soft) caliber::refreshCluster(*body1.m_soft, 0);
}

btSoftBody::Cluster* firstCluster(btSoftBody* body, const char* what)
{
	if (body && body->m_clusters.size() > 0) return body->m_clusters[0];
	btAssert(!"btSoftBody: joint to a null soft body or one without clusters");
	char message[256];
	snprintf(message, sizeof(message),
	         "Caliber: btSoftBody::%s: null soft body, or a body without clusters (call generateClusters first); no "
	         "joint added\n",
	         what);
	softBodyWarning(message);
	return 0;
}
}  // namespace

void btSoftBody::appendLinearJoint(const LJoint::Specs& specs, Cluster* body0, Body body1)
{
	if (!checkJoint(*this, body0, body1, "appendLinearJoint")) return;
	if (!caliber::isFinite(specs.position) || !(specs.erp == specs.erp))
	{
		btAssert(!"btSoftBody::appendLinearJoint: non-finite position or erp");
		softBodyWarning("Caliber: btSoftBody::appendLinearJoint: non-finite position or erp; no joint added\n");
		return;
	}
	LJoint* j = newJoint<LJoint>();
	setSpecs(*j, specs, body0, body1);
	j->m_refs[0] = j->m_bodies[0].xform().inverse() * specs.position;
	j->m_refs[1] = j->m_bodies[1].xform().inverse() * specs.position;
	m_joints.push_back(j);
}

void btSoftBody::appendLinearJoint(const LJoint::Specs& specs, Body body)
{
	if (Cluster* c = firstCluster(this, "appendLinearJoint")) appendLinearJoint(specs, c, body);
}

void btSoftBody::appendLinearJoint(const LJoint::Specs& specs, btSoftBody* body)
{
	Cluster* own = firstCluster(this, "appendLinearJoint");
	Cluster* other = own ? firstCluster(body, "appendLinearJoint") : 0;
	if (own && other) appendLinearJoint(specs, own, Body(other));
}

void btSoftBody::appendAngularJoint(const AJoint::Specs& specs, Cluster* body0, Body body1)
{
	if (!checkJoint(*this, body0, body1, "appendAngularJoint")) return;
	if (!caliber::isFinite(specs.axis) || specs.axis.length2() <= SIMD_EPSILON || !(specs.erp == specs.erp))
	{
		btAssert(!"btSoftBody::appendAngularJoint: zero or non-finite axis, or non-finite erp");
		softBodyWarning(
		    "Caliber: btSoftBody::appendAngularJoint: zero or non-finite axis, or non-finite erp; no joint added\n");
		return;
	}
	AJoint* j = newJoint<AJoint>();
	setSpecs(*j, specs, body0, body1);
	const btVector3 axis = specs.axis.normalized();
	j->m_refs[0] = j->m_bodies[0].xform().getBasis().transpose() * axis;
	j->m_refs[1] = j->m_bodies[1].xform().getBasis().transpose() * axis;
	j->m_icontrol = specs.icontrol;
	m_joints.push_back(j);
}

void btSoftBody::appendAngularJoint(const AJoint::Specs& specs, Body body)
{
	if (Cluster* c = firstCluster(this, "appendAngularJoint")) appendAngularJoint(specs, c, body);
}

void btSoftBody::appendAngularJoint(const AJoint::Specs& specs, btSoftBody* body)
{
	Cluster* own = firstCluster(this, "appendAngularJoint");
	Cluster* other = own ? firstCluster(body, "appendAngularJoint") : 0;
	if (own && other) appendAngularJoint(specs, own, Body(other));
}

// ---- the cluster stage ------------------------------------------------------------------------------

namespace
{
void deleteJoint(btSoftBody& body, int i)
{
	btSoftBody::Joint* j = body.m_joints[i];
	j->~Joint();
	btAlignedFree(j);
	body.m_joints.removeAtIndex(i);
}

// A joint side that left: a rigid body removed from the world, or a cluster released or removed from
// the world with its body, while this body is in a world.
bool sideGone(const btSoftBody& self, const btSoftBody::Body& b)
{
	if (b.m_soft)
	{
		const btSoftBody* owner = caliber::clusterOwner(b.m_soft);
		return !owner || (self.getBroadphaseHandle() && !owner->getBroadphaseHandle());
	}
	if (b.m_collisionObject) return self.getBroadphaseHandle() && !b.m_collisionObject->getBroadphaseHandle();
	return false;
}

// True when c is one of body's clusters (without the owners' registry and its lock).
bool ownCluster(const btSoftBody& body, const btSoftBody::Cluster* c)
{
	const int i = c->m_clusterIndex;
	return i >= 0 && i < body.m_clusters.size() && body.m_clusters[i] == c;
}

// Solves one contact's normal push (and its own friction when withFriction); returns the push (kg m).
btScalar solveContact(caliber::ClusterContact& c, const btAlignedObjectArray<btScalar>& weights, btScalar dt,
                      bool withFriction)
{
	// The clusters' centres and velocities are measured from their nodes at each contact: clusters share
	// nodes, so each push also moves the neighbours of the cluster pushed.
	btSoftBody::Cluster& a = *c.cluster;
	btVector3 comA, va;
	caliber::clusterMotion(a, dt, comA, va);
	btVector3 ra, rb, normal, vb(0, 0, 0);
	btScalar gap;
	btSoftBody::Body other;
	btVector3 comB(0, 0, 0);
	if (c.other)
	{
		other = btSoftBody::Body(c.other);
		caliber::clusterMotion(*c.other, dt, comB, vb);
		normal = c.normal;
		// How far each side's material point at the contact moved since it was found.
		const btVector3 pa = caliber::materialPoint(a, weights, c.weightsA);
		const btVector3 pb = caliber::materialPoint(*c.other, weights, c.weightsB);
		gap = c.distance + normal.dot((pa - c.localA) - (pb - c.localB));
		// Both pushes act at one point (between the two sides' points), so angular momentum is kept.
		const btVector3 point = (pa + pb) / 2;
		ra = point - comA;
		rb = point - comB;
		va += a.m_av.cross(ra);
		vb += c.other->m_av.cross(rb);
	}
	else
	{
		other = btSoftBody::Body(c.object);
		const btTransform& t = c.object->getWorldTransform();
		const btVector3 pa = c.node ? c.node->m_x : a.m_framexform * c.localA;
		const btVector3 pb = t * c.localB;
		ra = pa - comA;
		rb = pb - t.getOrigin();
		normal = t.getBasis() * c.normal;
		gap = normal.dot(pa - pb);
		va = c.node ? (c.node->m_x - c.node->m_q) / dt : va + a.m_av.cross(ra);
		if (other.m_rigid) vb = other.m_rigid->getVelocityInLocalPoint(rb);
	}
	if (gap >= 0) return 0;
	a.m_com = comA;  // the pushes below turn about the centres now
	if (c.other) c.other->m_com = comB;
	const btScalar wa = caliber::clusterInverseMass(a, ra, normal);
	const btScalar wb = sideInverseMass(other, rb, normal);
	const btScalar w = wa + wb;
	if (!(w > 0)) return 0;
	const btScalar correction = btMin(-gap * c.hardness, c.maxCorrection);
	const btScalar lambda = correction / w;
	// Velocities change as far as the sides stop approaching (an inelastic contact); of the rest of the push
	// (the penetration's recovery), the split factor moves positions alone and the remainder changes
	// velocities too, as Bullet's split cluster impulses: a split of 1 never launches anything, 0 turns the
	// whole recovery into a separating velocity.
	const btScalar approach = (vb - va).dot(normal);
	const btScalar change = lambda * w / dt;
	const btScalar stop = change > 0 ? btClamped(approach / change, btScalar(0), btScalar(1)) : btScalar(1);
	const btScalar share = stop + (1 - stop) * (1 - c.split);
	caliber::moveCluster(a, normal * lambda, ra, dt, share);
	sidePush(other, -normal * lambda, rb, dt, share);
	if (!withFriction || !(c.friction > 0)) return lambda;
	// Coulomb friction: the sliding of the contact points this step is undone up to friction times
	// the normal correction.
	caliber::clusterMotion(a, dt, comA, va);
	if (c.other)
	{
		btVector3 comB;
		caliber::clusterMotion(*c.other, dt, comB, vb);
		va += a.m_av.cross(ra);
		vb += c.other->m_av.cross(rb);
	}
	else
	{
		va = c.node ? (c.node->m_x - c.node->m_q) / dt : va + a.m_av.cross(ra);
		vb = other.m_rigid ? other.m_rigid->getVelocityInLocalPoint(rb) : btVector3(0, 0, 0);
	}
	btVector3 slide = (va - vb) * dt;
	slide -= normal * normal.dot(slide);
	const btScalar len = slide.length();
	if (len <= SIMD_EPSILON) return lambda;
	const btVector3 dir = slide / len;
	const btScalar wt = caliber::clusterInverseMass(a, ra, dir) + sideInverseMass(other, rb, dir);
	if (!(wt > 0)) return lambda;
	const btScalar mu = btMin(len / wt, c.friction * lambda);
	caliber::moveCluster(a, -dir * mu, ra, dt, 1);
	sidePush(other, dir * mu, rb, dt, 1);
	return lambda;
}

// Coulomb friction of a cluster's manifold against an object, as one patch: the per-point friction of a
// resting cluster answers the sideways move each point's normal push gives it by turning the cluster, so the
// pushes walk the cluster across the surface (a 1 m soft cube crept 13 cm in 3 s). The patch stops the
// sliding of its centre (the mean of its points) up to friction times the normal pushes of this solve, and
// the spin about the normal up to friction times those pushes times the points' mean distance from the
// centre (the torque of a uniform pressure over the patch).
void solvePatchFriction(caliber::ClusterContact* contacts, int count, btScalar pushed, btScalar dt)
{
	const caliber::ClusterContact& h = contacts[0];
	if (!(h.friction > 0) || !(pushed > 0)) return;
	btSoftBody::Cluster& a = *h.cluster;
	const btSoftBody::Body other(h.object);
	const btTransform& t = h.object->getWorldTransform();
	const btVector3 normal = t.getBasis() * h.normal;
	// The patch is its node points (the deepest point, the first contact, lies among them or between them),
	// or the deepest point alone.
	const int first = count > 1 ? 1 : 0;
	btVector3 point(0, 0, 0);
	for (int i = first; i < count; ++i)
		point += contacts[i].node ? contacts[i].node->m_x : a.m_framexform * contacts[i].localA;
	point /= btScalar(count - first);
	btVector3 comA, va;
	caliber::clusterMotion(a, dt, comA, va);
	a.m_com = comA;
	const btVector3 ra = point - comA, rb = point - t.getOrigin();
	va += a.m_av.cross(ra);
	const btRigidBody* rigid = other.m_rigid;
	const btVector3 vb = rigid ? rigid->getVelocityInLocalPoint(rb) : btVector3(0, 0, 0);
	const btScalar limit = h.friction * pushed;
	btVector3 slide = (va - vb) * dt;
	slide -= normal * normal.dot(slide);
	const btScalar len = slide.length();
	if (len > SIMD_EPSILON)
	{
		const btVector3 dir = slide / len;
		const btScalar wt = caliber::clusterInverseMass(a, ra, dir) + sideInverseMass(other, rb, dir);
		if (wt > 0)
		{
			const btScalar mu = btMin(len / wt, limit);
			caliber::moveCluster(a, -dir * mu, ra, dt, 1);
			sidePush(other, dir * mu, rb, dt, 1);
		}
	}
	btScalar radius = 0;
	for (int i = first; i < count; ++i)
	{
		btVector3 d = (contacts[i].node ? contacts[i].node->m_x : a.m_framexform * contacts[i].localA) - point;
		d -= normal * normal.dot(d);
		radius += d.length();
	}
	radius /= btScalar(count - first);
	const btScalar spin = (a.m_av - (rigid ? rigid->getAngularVelocity() : btVector3(0, 0, 0))).dot(normal) * dt;
	const btScalar wa = caliber::clusterAngularInverseMass(a, normal) + sideAngularInverseMass(other, normal);
	if (!(radius > 0) || !(wa > 0) || btFabs(spin) <= SIMD_EPSILON) return;
	const btScalar turn = btMin(btFabs(spin) / wa, limit * radius) * (spin > 0 ? 1 : -1);
	caliber::turnCluster(a, -normal * turn, dt, 1);
	sideTurn(other, normal * turn, dt, 1);
}

// A manifold: its contacts' normal pushes (its node points in order, or backwards, then its deepest point),
// then the patch's friction; a lone contact with its own friction.
void solveManifold(caliber::ClusterContact* contacts, int count, const btAlignedObjectArray<btScalar>& weights,
                   btScalar dt, bool backwards)
{
	if (count == 1)
	{
		solveContact(contacts[0], weights, dt, true);
		return;
	}
	btScalar pushed = 0;
	// The node points first, the deepest point (the first contact) last: where the nodes cover it, it is out by
	// then and adds nothing; pushed first, it would lift one point twice and tilt a resting cluster each solve.
	for (int k = 1; k < count; ++k) pushed += solveContact(contacts[backwards ? count - k : k], weights, dt, false);
	pushed += solveContact(contacts[0], weights, dt, false);
	solvePatchFriction(contacts, count, pushed, dt);
}
}  // namespace

namespace
{
using caliber::ClusterContact;
using caliber::ClusterState;
using caliber::clusterState;
using caliber::refreshCluster;

// The cluster stage in three parts, so that the solver can interleave the solves of several bodies
// (solveClusterStages).
bool beginClusterStage(btSoftBody& body, btScalar dt)
{
	// Joints whose other side left are dropped (as anchors are).
	for (int i = body.m_joints.size() - 1; i >= 0; --i)
	{
		btSoftBody::Joint* j = body.m_joints[i];
		if (sideGone(body, j->m_bodies[0]) || sideGone(body, j->m_bodies[1]))
		{
			btAssert(!"btSoftBody: a joint's other body was removed from the world or its cluster released");
			softBodyWarning(
			    "Caliber: btSoftBody: a joint's other body was removed from the world (or its cluster released); the "
			    "joint is removed\n");
			deleteJoint(body, i);
		}
	}
	ClusterState& state = clusterState(body);
	bool matching = false;
	for (int i = 0; i < body.m_clusters.size(); ++i) matching = matching || body.m_clusters[i]->m_matching > 0;
	if (state.contacts.size() == 0 && body.m_joints.size() == 0 && !matching) return false;
	const int iterations = btMax(body.m_cfg.citerations, 1);
	for (int i = 0; i < body.m_joints.size(); ++i) body.m_joints[i]->Prepare(dt, iterations);
	return true;
}

void clusterStageSolve(btSoftBody& body, btScalar dt, int iteration)
{
	ClusterState& state = clusterState(body);
	// Frames, inertias and velocities from the nodes before each solve: a cluster's move also moves
	// the nodes it shares with its neighbours, whose frames would otherwise go stale.
	for (int i = 0; i < body.m_clusters.size(); ++i) refreshCluster(*body.m_clusters[i], dt);
	for (int i = 0; i < state.contacts.size(); ++i)
		if (state.contacts[i].other && !ownCluster(body, state.contacts[i].other))
			refreshCluster(*state.contacts[i].other, dt);
	for (int i = 0; i < body.m_joints.size(); ++i)
		if (btSoftBody::Cluster* c = body.m_joints[i]->m_bodies[1].m_soft)
			if (!ownCluster(body, c)) refreshCluster(*c, dt);
	// Every other solve runs backwards: Gauss-Seidel favours the contacts solved first (they take the larger
	// corrections, and with them the larger friction), which would tip and slide a body resting on several.
	const int count = state.contacts.size();
	if (iteration & 1)
	{
		for (int i = count - 1; i >= 0; --i)
			if (state.contacts[i].patch > 0)
				solveManifold(&state.contacts[i], state.contacts[i].patch, state.weights, dt, true);
	}
	else
		for (int i = 0; i < count; i += btMax(state.contacts[i].patch, 1))
			solveManifold(&state.contacts[i], btMax(state.contacts[i].patch, 1), state.weights, dt, false);
	for (int i = 0; i < body.m_joints.size(); ++i) body.m_joints[i]->Solve(dt, 1);
}

void endClusterStage(btSoftBody& body, btScalar dt)
{
	ClusterState& state = clusterState(body);
	for (int i = body.m_joints.size() - 1; i >= 0; --i)
	{
		body.m_joints[i]->Terminate(dt);
		if (body.m_joints[i]->m_delete) deleteJoint(body, i);
	}
	// Shape matching: each node goes m_matching of the way to its place in its cluster's rigid rest shape.
	for (int i = 0; i < body.m_clusters.size(); ++i)
	{
		btSoftBody::Cluster& c = *body.m_clusters[i];
		if (!(c.m_matching > 0)) continue;
		refreshCluster(c, dt);
		const btScalar k = btClamped(c.m_matching, btScalar(0), btScalar(1));
		for (int j = 0; j < c.m_nodes.size(); ++j)
		{
			btSoftBody::Node& n = *c.m_nodes[j];
			if (n.m_im > 0) n.m_x += (c.m_framexform * c.m_framerefs[j] - n.m_x) * k;
		}
	}
	// Nodes held against static and kinematic objects end the stage on their surface (the clusters'
	// Gauss-Seidel moves, sharing nodes, and shape matching can leave a node behind): the node alone is put back, its
	// start point with it, so that velocities do not change (as a split impulse).
	for (int i = 0; i < state.contacts.size(); ++i)
	{
		const ClusterContact& c = state.contacts[i];
		if (!c.node || !c.object->isStaticOrKinematicObject()) continue;
		const btTransform& t = c.object->getWorldTransform();
		const btVector3 normal = t.getBasis() * c.normal;
		const btScalar gap = normal.dot(c.node->m_x - t * c.localB);
		if (gap >= 0) continue;
		c.node->m_x -= normal * gap;
		c.node->m_q -= normal * gap;
	}
}
}  // namespace

void caliber::solveClusterStage(btSoftBody& body, btScalar dt)
{
	if (!beginClusterStage(body, dt)) return;
	for (int it = 0; it < btMax(body.m_cfg.citerations, 1); ++it) clusterStageSolve(body, dt, it);
	endClusterStage(body, dt);
}

void caliber::solveClusterStages(btSoftBody* const* bodies, int count)
{
	// One Gauss-Seidel sweep over every body's cluster contacts and joints per iteration: a cluster
	// touching clusters of two other bodies (the middle of a stack) is solved against both in each sweep,
	// where stages run one body after the other would leave each body's stage to undo the last one's turn.
	btAlignedObjectArray<char> active;
	active.resize(count, 0);
	int iterations = 0;
	for (int b = 0; b < count; ++b)
	{
		active[b] = beginClusterStage(*bodies[b], bodies[b]->m_sst.sdt);
		if (active[b]) iterations = btMax(iterations, btMax(bodies[b]->m_cfg.citerations, 1));
	}
	for (int it = 0; it < iterations; ++it)
		for (int b = 0; b < count; ++b)
			if (active[b] && it < btMax(bodies[b]->m_cfg.citerations, 1))
				clusterStageSolve(*bodies[b], bodies[b]->m_sst.sdt, it);
	for (int b = 0; b < count; ++b)
		if (active[b]) endClusterStage(*bodies[b], bodies[b]->m_sst.sdt);
}
