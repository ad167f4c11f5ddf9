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

void btSoftBody::defaultCollisionHandler(btSoftBody* psb) { (void)psb; }
