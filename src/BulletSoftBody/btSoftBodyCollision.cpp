// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Soft-rigid contacts: each free node against one rigid object's shape. A contact is the plane of the
// shape's surface point closest to where the node started the step (so a fast node is judged from the
// side it came from), kept when the node's predicted position comes within the soft body's margin of
// it; the solver (btSoftBodySolve.cpp) then keeps the node on the outer side of that plane.

#include "BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btCompoundShape.h"
#include "BulletCollision/CollisionShapes/btConcaveShape.h"
#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btStaticPlaneShape.h"
#include "BulletCollision/CollisionShapes/btTriangleCallback.h"
#include "BulletCollision/NarrowPhaseCollision/ClosestPointOnTriangle.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkEpa2.h"
#include "BulletSoftBody/btSoftBody.h"
#include "btSoftBodyInternal.h"

namespace
{
struct SurfacePoint
{
	btVector3 point;   // on the surface, world
	btVector3 normal;  // out of the shape, world
};

bool closestOnSphere(const btSphereShape& sphere, const btTransform& t, const btVector3& q, SurfacePoint& out)
{
	const btVector3 c = t.getOrigin();
	btVector3 d = q - c;
	const btScalar len = d.length();
	out.normal = len > SIMD_EPSILON ? d / len : btVector3(0, 1, 0);
	out.point = c + out.normal * sphere.getRadius();
	return true;
}

bool closestOnBox(const btBoxShape& box, const btTransform& t, const btVector3& q, SurfacePoint& out)
{
	const btVector3 h = box.getHalfExtentsWithMargin();
	const btVector3 local = t.invXform(q);
	btVector3 clamped = local;
	clamped.setMax(-h);
	clamped.setMin(h);
	btVector3 nLocal;
	btVector3 pLocal;
	if ((clamped - local).length2() > 0)
	{
		// Outside: the clamped point; the normal from it to q.
		pLocal = clamped;
		nLocal = (local - clamped).normalized();
	}
	else
	{
		// Inside: out through the nearest face.
		int axis = 0;
		btScalar best = BT_LARGE_FLOAT;
		for (int a = 0; a < 3; ++a)
		{
			const btScalar gap = h[a] - btFabs(local[a]);
			if (gap < best)
			{
				best = gap;
				axis = a;
			}
		}
		pLocal = local;
		const btScalar s = local[axis] >= 0 ? btScalar(1) : btScalar(-1);
		pLocal[axis] = s * h[axis];
		nLocal.setValue(0, 0, 0);
		nLocal[axis] = s;
	}
	out.point = t * pLocal;
	out.normal = t.getBasis() * nLocal;
	return true;
}

bool closestOnPlane(const btStaticPlaneShape& plane, const btTransform& t, const btVector3& q, SurfacePoint& out)
{
	const btVector3 n = t.getBasis() * plane.getPlaneNormal();
	const btVector3 origin = t * (plane.getPlaneNormal() * plane.getPlaneConstant());
	out.normal = n;
	out.point = q - n * n.dot(q - origin);
	return true;
}

bool closestOnConvex(const btConvexShape& shape, const btTransform& t, const btVector3& q, SurfacePoint& out)
{
	btGjkEpaSolver2::sResults res;
	const btScalar d = btGjkEpaSolver2::SignedDistance(q, 0, &shape, t, res);
	if (d == SIMD_INFINITY) return false;
	out.point = res.witnesses[0];
	btVector3 n = d >= 0 ? q - out.point : out.point - q;
	if (n.length2() > SIMD_EPSILON * SIMD_EPSILON && btFabs(d) > SIMD_EPSILON)
		out.normal = n.normalized();
	else if (res.normal.length2() > SIMD_EPSILON)
		out.normal = -res.normal.normalized();  // res.normal points from the query point into the shape
	else
		return false;
	return true;
}

// The triangle of a concave shape nearest to the node's start (in the shape's frame).
struct NearestTriangle : btTriangleCallback
{
	btVector3 query;
	btScalar bestDistance2 = BT_LARGE_FLOAT;
	btVector3 point{0, 0, 0};
	btVector3 normal{0, 0, 0};
	bool found = false;

	void processTriangle(btVector3* tri, int, int) override
	{
		btVector3 n = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
		const btScalar len = n.length();
		if (len <= SIMD_EPSILON) return;  // degenerate triangles have no side
		const btVector3 p = caliber::closestPointOnTriangle(query, tri[0], tri[1], tri[2]);
		const btScalar d2 = (query - p).length2();
		if (d2 >= bestDistance2) return;
		n /= len;
		// Meshes are thin: the side is the one the node came from.
		if (n.dot(query - tri[0]) < 0) n = -n;
		bestDistance2 = d2;
		point = p;
		normal = n;
		found = true;
	}
};

bool closestOnConcave(const btConcaveShape& shape, const btTransform& t, const btVector3& q, const btVector3& x,
                      btScalar reach, SurfacePoint& out)
{
	NearestTriangle nearest;
	nearest.query = t.invXform(q);
	const btVector3 xl = t.invXform(x);
	btVector3 lo = nearest.query, hi = nearest.query;
	lo.setMin(xl);
	hi.setMax(xl);
	const btVector3 r(reach, reach, reach);
	shape.processAllTriangles(&nearest, lo - r, hi + r);
	if (!nearest.found) return false;
	out.point = t * nearest.point;
	out.normal = t.getBasis() * nearest.normal;
	return true;
}

struct ContactSearch
{
	btSoftBody& body;
	const btCollisionObject* object;
	btScalar margin;
	btScalar friction;
	btScalar hardness;

	void addContact(btSoftBody::Node& node, const SurfacePoint& s)
	{
		if (s.normal.dot(node.m_x - s.point) >= margin) return;  // cannot reach the surface this step
		const btTransform& t = object->getWorldTransform();
		btSoftBody::RContact c;
		c.m_cti.m_colObj = object;
		c.m_cti.m_normal = s.normal;
		c.m_cti.m_offset = -s.normal.dot(s.point);
		c.m_cti.m_bary.setValue(0, 0, 0);
		c.m_node = &node;
		c.m_c0.setIdentity();
		c.m_c0[0] = t.getBasis().transpose() * s.normal;
		c.m_c1 = t.invXform(s.point);
		c.m_c2 = node.m_im;
		c.m_c3 = friction;
		c.m_c4 = hardness;
		body.m_rcontacts.push_back(c);
	}

	void collide(btSoftBody::Node& node, const btCollisionShape* shape, const btTransform& t)
	{
		SurfacePoint s;
		bool ok = false;
		switch (shape->getShapeType())
		{
			case SPHERE_SHAPE_PROXYTYPE:
				ok = closestOnSphere(*static_cast<const btSphereShape*>(shape), t, node.m_q, s);
				break;
			case BOX_SHAPE_PROXYTYPE:
				ok = closestOnBox(*static_cast<const btBoxShape*>(shape), t, node.m_q, s);
				break;
			case STATIC_PLANE_PROXYTYPE:
				ok = closestOnPlane(*static_cast<const btStaticPlaneShape*>(shape), t, node.m_q, s);
				break;
			case COMPOUND_SHAPE_PROXYTYPE:
			{
				const btCompoundShape* compound = static_cast<const btCompoundShape*>(shape);
				for (int i = 0; i < compound->getNumChildShapes(); ++i)
					collide(node, compound->getChildShape(i), t * compound->getChildTransform(i));
				return;
			}
			default:
				if (shape->isConvex())
					ok = closestOnConvex(*static_cast<const btConvexShape*>(shape), t, node.m_q, s);
				else if (shape->isConcave())
					ok = closestOnConcave(*static_cast<const btConcaveShape*>(shape), t, node.m_q, node.m_x, margin, s);
				break;
		}
		if (ok) addContact(node, s);
	}
};
}  // namespace

void caliber::collideSoftWithRigid(btSoftBody& body, const btCollisionObjectWrapper& rigid)
{
	const btCollisionObject* object = rigid.getCollisionObject();
	const btCollisionShape* shape = rigid.getCollisionShape();
	if (!object || !shape || !object->hasContactResponse()) return;
	const btTransform& t = rigid.getWorldTransform();
	const btScalar margin = body.getCollisionShape()->getMargin();
	btVector3 lo, hi;
	shape->getAabb(t, lo, hi);
	const btVector3 m(margin, margin, margin);
	lo -= m;
	hi += m;
	ContactSearch search{
	    body, object, margin, body.m_cfg.kDF * object->getFriction(),
	    object->isStaticOrKinematicObject() ? btScalar(1) : btClamped(body.m_cfg.kCHR, btScalar(0), btScalar(1))};
	for (int i = 0; i < body.m_nodes.size(); ++i)
	{
		btSoftBody::Node& n = body.m_nodes[i];
		if (n.m_im <= 0) continue;
		btVector3 nlo = n.m_q, nhi = n.m_q;
		nlo.setMin(n.m_x);
		nhi.setMax(n.m_x);
		if (nlo.x() > hi.x() || nhi.x() < lo.x() || nlo.y() > hi.y() || nhi.y() < lo.y() || nlo.z() > hi.z() ||
		    nhi.z() < lo.z())
			continue;
		search.collide(n, shape, t);
	}
}

void btSoftBody::defaultCollisionHandler(const btCollisionObjectWrapper* pcoWrap)
{
	if (!pcoWrap) return;
	// Node-rigid contacts serve both SDF_RS and CL_RS until clusters exist.
	if (!(m_cfg.collisions & (fCollision::SDF_RS | fCollision::CL_RS))) return;
	if (m_collisionDisabledObjects.findLinearSearch(pcoWrap->getCollisionObject()) != m_collisionDisabledObjects.size())
		return;
	caliber::collideSoftWithRigid(*this, *pcoWrap);
}

namespace
{
// Contacts of nodes's free nodes with faces's faces (VF_SS): for each node whose move this step comes
// within reach of a face, the face point closest to the node's predicted position (as barycentric
// weights) and the side of the face the node started on. Faces are culled by their boxes.
void collideNodesWithFaces(btSoftBody& nodes, btSoftBody& faces, btScalar thickness, btScalar reach, btScalar friction)
{
	const btVector3 r(reach, reach, reach);
	btVector3 lo, hi;
	faces.getAabb(lo, hi);
	for (int i = 0; i < nodes.m_nodes.size(); ++i)
	{
		btSoftBody::Node& n = nodes.m_nodes[i];
		if (n.m_im <= 0) continue;
		btVector3 nlo = n.m_q, nhi = n.m_q;
		nlo.setMin(n.m_x);
		nhi.setMax(n.m_x);
		nlo -= r;
		nhi += r;
		if (nlo.x() > hi.x() || nhi.x() < lo.x() || nlo.y() > hi.y() || nhi.y() < lo.y() || nlo.z() > hi.z() ||
		    nhi.z() < lo.z())
			continue;
		// Only the nearest face: other faces' planes pass beside a node outside a convex body too.
		btSoftBody::SContact best;
		btScalar bestDistance2 = BT_LARGE_FLOAT;
		for (int k = 0; k < faces.m_faces.size(); ++k)
		{
			btSoftBody::Face& f = faces.m_faces[k];
			const btVector3& a = f.m_n[0]->m_x;
			const btVector3& b = f.m_n[1]->m_x;
			const btVector3& c = f.m_n[2]->m_x;
			btVector3 flo = a, fhi = a;
			flo.setMin(b);
			flo.setMin(c);
			fhi.setMax(b);
			fhi.setMax(c);
			if (nlo.x() > fhi.x() || nhi.x() < flo.x() || nlo.y() > fhi.y() || nhi.y() < flo.y() || nlo.z() > fhi.z() ||
			    nhi.z() < flo.z())
				continue;
			const btVector3 normal = (b - a).cross(c - a);
			const btScalar area2 = normal.length2();
			if (area2 <= SIMD_EPSILON * SIMD_EPSILON) continue;
			// The side the node came from, judged against the face where it started the step too.
			const btVector3 startNormal = (f.m_n[1]->m_q - f.m_n[0]->m_q).cross(f.m_n[2]->m_q - f.m_n[0]->m_q);
			const btScalar side = startNormal.dot(n.m_q - f.m_n[0]->m_q) >= 0 ? btScalar(1) : btScalar(-1);
			const btVector3 p = caliber::closestPointOnTriangle(n.m_x, a, b, c);
			const btScalar distance2 = (n.m_x - p).length2();
			if (distance2 >= (thickness + reach) * (thickness + reach) || distance2 >= bestDistance2) continue;
			// Barycentric weights of p.
			const btVector3 v0 = b - a, v1 = c - a, v2 = p - a;
			const btScalar d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1), d20 = v2.dot(v0), d21 = v2.dot(v1);
			const btScalar denom = d00 * d11 - d01 * d01;
			if (btFabs(denom) <= SIMD_EPSILON) continue;
			const btScalar wb = (d11 * d20 - d01 * d21) / denom, wc = (d00 * d21 - d01 * d20) / denom;
			btSoftBody::SContact contact;
			contact.m_node = &n;
			contact.m_face = &f;
			contact.m_weights.setValue(1 - wb - wc, wb, wc);
			contact.m_normal = normal * (side / btSqrt(area2));
			contact.m_margin = thickness;
			contact.m_friction = friction;
			contact.m_cfm[0] = side;
			contact.m_cfm[1] = 0;
			bestDistance2 = distance2;
			best = contact;
		}
		if (bestDistance2 < BT_LARGE_FLOAT) nodes.m_scontacts.push_back(best);
	}
}
}  // namespace

void btSoftBody::defaultCollisionHandler(btSoftBody* psb)
{
	if (!psb || psb == this) return;  // self-collision is not implemented yet
	if (!((m_cfg.collisions | psb->m_cfg.collisions) & fCollision::VF_SS)) return;
	// Nodes stay half the smaller margin away from the other body's faces; contacts are looked for
	// within the margins.
	const btScalar marginA = getCollisionShape()->getMargin(), marginB = psb->getCollisionShape()->getMargin();
	const btScalar thickness = btScalar(0.5) * btMin(marginA, marginB);
	const btScalar friction = btMax(m_cfg.kDF, psb->m_cfg.kDF);
	collideNodesWithFaces(*this, *psb, thickness, marginA, friction);
	collideNodesWithFaces(*psb, *this, thickness, marginB, friction);
}
