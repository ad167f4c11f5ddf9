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
#include "BulletCollision/CollisionShapes/btPolyhedralConvexShape.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "BulletSoftBody/btSoftBody.h"
#include "LinearMath/btSideTable.h"
#include "LinearMath/btTransformUtil.h"
#include "btSoftBodyFaceContacts.h"
#include "btSoftBodyClusters.h"
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

// Forced inline: the node search calls it per node (a call per node cost 2% of a scene of balls on a box).
SIMD_FORCE_INLINE bool closestOnBox(const btBoxShape& box, const btTransform& t, const btVector3& q, SurfacePoint& out)
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
	btVector3 motion{0, 0, 0};  // the node's move over the step (predicted minus start)
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
		// Meshes are thin: the side is the one the node came from. A node resting on the triangle starts on
		// its plane (within rounding: 0.1 mm), where that side is unclear: then it is the side the node moves
		// away from (a resting node is pulled into the surface by gravity each step).
		const btScalar side = n.dot(query - tri[0]);
		if (btFabs(side) > btScalar(1e-4) ? side < 0 : n.dot(motion) > 0) n = -n;
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
	nearest.motion = xl - nearest.query;
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
	btAlignedObjectArray<btSoftBody::RContact>* out;  // where the contacts found go
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
		out->push_back(c);
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

namespace
{
// Node contacts are gathered in chunks of this many nodes, on the task scheduler when there are several.
const int kContactChunk = 1024;

// The node contacts each chunk found this step (a side table keyed by the body; kept to reuse its storage).
struct NodeContactChunks
{
	btAlignedObjectArray<btAlignedObjectArray<btSoftBody::RContact>> chunks;
};

// Whether a free node's move this step meets the box [lo, hi].
inline bool mayTouch(const btSoftBody::Node& n, const btVector3& lo, const btVector3& hi)
{
	if (n.m_im <= 0) return false;
	btVector3 nlo = n.m_q, nhi = n.m_q;
	nlo.setMin(n.m_x);
	nhi.setMax(n.m_x);
	return !(nlo.x() > hi.x() || nhi.x() < lo.x() || nlo.y() > hi.y() || nhi.y() < lo.y() || nlo.z() > hi.z() ||
	         nhi.z() < lo.z());
}

// The node contacts with one shape of chunks [begin, end) of nodes: the first chunk's into the search's list,
// chunk k's into lists[k] (the body's list is only appended to by the first chunk while the others run).
struct NodeGather : btIParallelForBody
{
	ContactSearch search;
	btSoftBody::Node* nodes;
	int count;
	const btCollisionShape* shape;
	const btTransform* t;
	btVector3 lo, hi;  // the shape's box grown by the margin
	btAlignedObjectArray<btSoftBody::RContact>* lists = 0;
	explicit NodeGather(const ContactSearch& s) : search(s) {}
	void forLoop(int begin, int end) const override
	{
		ContactSearch s = search;
		// Locals: the contacts written below could alias the members for the compiler.
		const btVector3 lo = this->lo, hi = this->hi;
		btSoftBody::Node* const nodes = this->nodes;
		const btCollisionShape* const shape = this->shape;
		const btTransform& t = *this->t;
		for (int k = begin; k < end; ++k)
		{
			s.out = k == 0 ? search.out : &lists[k];  // the first chunk's go straight to the body's list
			if (k > 0) s.out->resize(0);
			const int last = btMin((k + 1) * kContactChunk, count);
			for (int i = k * kContactChunk; i < last; ++i)
			{
				btSoftBody::Node& n = nodes[i];
				if (mayTouch(n, lo, hi)) s.collide(n, shape, t);
			}
		}
	}
};
}  // namespace

void caliber::releaseNodeContactChunks(const btSoftBody& body) { sideTable<NodeContactChunks>().release(&body); }

caliber::SoftFaceContacts& caliber::softFaceContacts(const btSoftBody& body)
{
	return sideTable<SoftFaceContacts>().acquire(&body);
}

void caliber::releaseSoftFaceContacts(const btSoftBody& body) { sideTable<SoftFaceContacts>().release(&body); }

namespace
{
// Every face's box over the step (start and predicted corners), bucketed by low x (a counting sort
// into as many buckets of equal width as there are faces, at most): linear in the faces whatever
// their order, and deterministic.
void buildFaceBoxes(btSoftBody& body, caliber::SoftFaceContacts& out)
{
	const int count = body.m_faces.size();
	btAlignedObjectArray<caliber::SoftFaceContacts::FaceBox>& unsorted = out.scratch;
	unsorted.resize(count);
	out.widest = 0;
	btScalar minX = BT_LARGE_FLOAT, maxX = -BT_LARGE_FLOAT;
	for (int k = 0; k < count; ++k)
	{
		caliber::SoftFaceContacts::FaceBox& box = unsorted[k];
		const btSoftBody::Face& f = body.m_faces[k];
		box.face = k;
		box.lo = box.hi = f.m_n[0]->m_x;
		for (int j = 0; j < 3; ++j)
		{
			box.lo.setMin(f.m_n[j]->m_x);
			box.lo.setMin(f.m_n[j]->m_q);
			box.hi.setMax(f.m_n[j]->m_x);
			box.hi.setMax(f.m_n[j]->m_q);
		}
		out.widest = btMax(out.widest, box.hi.x() - box.lo.x());
		minX = btMin(minX, box.lo.x());
		maxX = btMax(maxX, box.lo.x());
	}
	const int buckets = btMax(1, btMin(count, 4096));
	out.minX = minX;
	out.cell = maxX > minX ? (maxX - minX) / btScalar(buckets) * btScalar(1.0001) : btScalar(1);
	btAlignedObjectArray<int>& start = out.bucketStart;
	start.resize(buckets + 1);
	for (int i = 0; i <= buckets; ++i) start[i] = 0;
	for (int k = 0; k < count; ++k) ++start[out.bucketOf(unsorted[k].lo.x(), buckets) + 1];
	for (int i = 0; i < buckets; ++i) start[i + 1] += start[i];
	out.boxes.resize(count);
	btAlignedObjectArray<int>& fill = out.fill;
	fill.resize(buckets);
	for (int i = 0; i < buckets; ++i) fill[i] = start[i];
	for (int k = 0; k < count; ++k) out.boxes[fill[out.bucketOf(unsorted[k].lo.x(), buckets)]++] = unsorted[k];
	out.boxesValid = true;
}

// Polyhedra with more corners than this are left to the node contacts (their corners are blunt).
const int kMaxCorners = 64;

// A box is held by its corners, three points along each edge and its faces' centres (8 + 36 + 6):
// its edges and faces can pass between the nodes of a coarse cloth as well as its corners can.
const int kBoxPoints = 50;
btVector3 boxPoint(const btVector3& h, int i)
{
	if (i < 8) return btVector3((i & 1) ? -h.x() : h.x(), (i & 2) ? -h.y() : h.y(), (i & 4) ? -h.z() : h.z());
	i -= 8;
	if (i < 36)
	{
		// Edge points: along axis a at -h/2, 0, h/2; the other two axes at their signs.
		const int a = i / 12, k = (i / 4) % 3, signs = i % 4;
		btVector3 p;
		p[a] = h[a] * btScalar(k - 1) * btScalar(0.5);
		p[(a + 1) % 3] = (signs & 1) ? -h[(a + 1) % 3] : h[(a + 1) % 3];
		p[(a + 2) % 3] = (signs & 2) ? -h[(a + 2) % 3] : h[(a + 2) % 3];
		return p;
	}
	i -= 36;
	btVector3 p(0, 0, 0);  // face centres
	p[i / 2] = (i & 1) ? -h[i / 2] : h[i / 2];
	return p;
}

// Rigid corners against soft faces (see btSoftBodyFaceContacts.h): each corner of a polyhedral shape,
// moved along its body's velocity over the step, against each face whose box its path comes within
// the margin of. The corner is judged against the face from where both started the step (the side it
// is kept on) and where both are predicted to end (a contact when it then comes within the margin and
// its projection falls on the face).
void collideCornersWithFaces(btSoftBody& body, caliber::SoftFaceContacts& out, const btCollisionObject* object,
                             const btCollisionShape* shape, const btTransform& start, const btTransform& end,
                             btScalar margin, btScalar hardness, bool dynamic)
{
	if (shape->getShapeType() == COMPOUND_SHAPE_PROXYTYPE)
	{
		const btCompoundShape* compound = static_cast<const btCompoundShape*>(shape);
		for (int i = 0; i < compound->getNumChildShapes(); ++i)
			collideCornersWithFaces(body, out, object, compound->getChildShape(i),
			                        start * compound->getChildTransform(i), end * compound->getChildTransform(i),
			                        margin, hardness, dynamic);
		return;
	}
	if (!shape->isPolyhedral()) return;
	const btPolyhedralConvexShape* poly = static_cast<const btPolyhedralConvexShape*>(shape);
	const bool isBox = shape->getShapeType() == BOX_SHAPE_PROXYTYPE;
	// A moving box also brings points along its edges and on its faces; static boxes (grounds, walls)
	// only their corners.
	const bool boxPoints = isBox && dynamic;
	const int count = boxPoints ? kBoxPoints : poly->getNumVertices();
	if (count <= 0 || count > kMaxCorners) return;
	// A box's points include its margin; other polyhedra are rounded by theirs.
	const btScalar thickness = isBox ? btScalar(0) : shape->getMargin();
	const btScalar reach = margin + thickness;
	// Only corners whose path comes within reach of the body's bounds (a ground box's corners are far
	// from everything on it).
	btVector3 bodyLo, bodyHi;
	body.getAabb(bodyLo, bodyHi);
	const btVector3 r(reach, reach, reach);
	bodyLo -= r;
	bodyHi += r;
	btVector3 corner0[kMaxCorners], corner1[kMaxCorners], local[kMaxCorners];
	btVector3 lo(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT), hi(-lo);
	int corners = 0;
	for (int i = 0; i < count; ++i)
	{
		if (boxPoints)
			local[corners] = boxPoint(static_cast<const btBoxShape*>(shape)->getHalfExtentsWithMargin(), i);
		else
			poly->getVertex(i, local[corners]);
		corner0[corners] = start * local[corners];
		corner1[corners] = end * local[corners];
		btVector3 clo = corner0[corners], chi = corner0[corners];
		clo.setMin(corner1[corners]);
		chi.setMax(corner1[corners]);
		if (clo.x() > bodyHi.x() || chi.x() < bodyLo.x() || clo.y() > bodyHi.y() || chi.y() < bodyLo.y() ||
		    clo.z() > bodyHi.z() || chi.z() < bodyLo.z())
			continue;
		lo.setMin(clo);
		hi.setMax(chi);
		++corners;
	}
	if (corners == 0) return;
	if (!out.boxesValid) buildFaceBoxes(body, out);
	// The object's transform maps the shape's frame (a compound child's) to the world: store corners in
	// the object's own frame, where the solver finds them again.
	const btTransform toObject = object->getWorldTransform().inverse() * start;
	lo -= r;
	hi += r;
	const btScalar edgeTolerance = btScalar(1e-3);
	const btAlignedObjectArray<caliber::SoftFaceContacts::FaceBox>& boxes = out.boxes;
	// The buckets of the faces whose low x can reach the object's range.
	const int buckets = out.bucketStart.size() - 1;
	const int firstBucket = out.bucketOf(lo.x() - out.widest, buckets), lastBucket = out.bucketOf(hi.x(), buckets);
	const int stop = out.bucketStart[lastBucket + 1];
	for (int b = out.bucketStart[firstBucket]; b < stop; ++b)
	{
		const btVector3& flo = boxes[b].lo;
		const btVector3& fhi = boxes[b].hi;
		if (flo.x() > hi.x() || fhi.x() < lo.x() || flo.y() > hi.y() || fhi.y() < lo.y() || flo.z() > hi.z() ||
		    fhi.z() < lo.z())
			continue;
		btSoftBody::Face& f = body.m_faces[boxes[b].face];
		const btSoftBody::Node* n0 = f.m_n[0];
		const btSoftBody::Node* n1 = f.m_n[1];
		const btSoftBody::Node* n2 = f.m_n[2];
		if (n0->m_im <= 0 && n1->m_im <= 0 && n2->m_im <= 0) continue;  // a fixed face is moved by nothing
		const btVector3 startNormal = (n1->m_q - n0->m_q).cross(n2->m_q - n0->m_q);
		btVector3 normal = (n1->m_x - n0->m_x).cross(n2->m_x - n0->m_x);
		const btScalar area2 = normal.length2();
		if (area2 <= SIMD_EPSILON * SIMD_EPSILON || startNormal.length2() <= SIMD_EPSILON * SIMD_EPSILON) continue;
		normal /= btSqrt(area2);
		const btVector3 e0 = n1->m_x - n0->m_x, e1 = n2->m_x - n0->m_x;
		const btScalar d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
		const btScalar denom = d00 * d11 - d01 * d01;
		if (btFabs(denom) <= SIMD_EPSILON) continue;
		// The side a point is kept on is the one it started the step on (a fast point is judged from where
		// it came from).
		for (int i = 0; i < corners; ++i)
		{
			const btScalar cornerSide = startNormal.dot(corner0[i] - n0->m_q);
			const btScalar side = cornerSide >= 0 ? btScalar(1) : btScalar(-1);
			const btVector3 rel = corner1[i] - n0->m_x;
			const btScalar distance = side * normal.dot(rel);
			if (distance >= reach) continue;  // cannot reach the face this step
			// Barycentric weights of the corner's projection onto the face.
			const btScalar d20 = rel.dot(e0), d21 = rel.dot(e1);
			const btScalar wb = (d11 * d20 - d01 * d21) / denom, wc = (d00 * d21 - d01 * d20) / denom;
			const btScalar wa = 1 - wb - wc;
			if (wa < -edgeTolerance || wb < -edgeTolerance || wc < -edgeTolerance) continue;
			caliber::SoftFaceContact c;
			c.face = &f;
			c.object = object;
			c.local = toObject * local[i];
			c.weights.setValue(btMax(wa, btScalar(0)), btMax(wb, btScalar(0)), btMax(wc, btScalar(0)));
			c.weights /= c.weights[0] + c.weights[1] + c.weights[2];
			c.side = side;
			c.thickness = thickness;
			c.hardness = hardness;
			out.contacts.push_back(c);
		}
	}
}
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
	    &body.m_rcontacts, object, margin, body.m_cfg.kDF * object->getFriction(),
	    object->isStaticOrKinematicObject() ? btScalar(1) : btClamped(body.m_cfg.kCHR, btScalar(0), btScalar(1))};
	const int chunks = (body.m_nodes.size() + kContactChunk - 1) / kContactChunk;
	if (chunks <= 1)
	{
		for (int i = 0; i < body.m_nodes.size(); ++i)
			if (mayTouch(body.m_nodes[i], lo, hi)) search.collide(body.m_nodes[i], shape, t);
	}
	else
	{
		NodeGather gather(search);
		gather.nodes = &body.m_nodes[0];
		gather.count = body.m_nodes.size();
		gather.shape = shape;
		gather.t = &t;
		gather.lo = lo;
		gather.hi = hi;
		// Chunks of nodes on the task scheduler, each into its own list; the lists are joined in chunk
		// order, so the contacts and their order are those of one thread.
		NodeContactChunks& lists = sideTable<NodeContactChunks>().acquire(&body);
		if (lists.chunks.size() < chunks) lists.chunks.resize(chunks);
		gather.lists = &lists.chunks[0];
		btParallelFor(0, chunks, 1, gather);
		for (int k = 1; k < chunks; ++k)
			for (int i = 0; i < lists.chunks[k].size(); ++i) body.m_rcontacts.push_back(lists.chunks[k][i]);
	}
	if (body.m_faces.size() == 0) return;
	// Corners of polyhedra against faces, along the object's motion over the step.
	btTransform end = t;
	if (const btRigidBody* rb = btRigidBody::upcast(object))
		if (!rb->isStaticObject())
			btTransformUtil::integrateTransform(t, rb->getLinearVelocity(), rb->getAngularVelocity(), body.m_sst.sdt,
			                                    end);
	SoftFaceContacts& faceContacts = softFaceContacts(body);
	collideCornersWithFaces(body, faceContacts, object, shape, t, end, margin, search.hardness,
	                        !object->isStaticOrKinematicObject());
}

void btSoftBody::defaultCollisionHandler(const btCollisionObjectWrapper* pcoWrap)
{
	if (!pcoWrap) return;
	if (!(m_cfg.collisions & (fCollision::SDF_RS | fCollision::CL_RS))) return;
	if (m_collisionDisabledObjects.findLinearSearch(pcoWrap->getCollisionObject()) != m_collisionDisabledObjects.size())
		return;
	// CL_RS: the clusters' hulls against the object's convex parts; node contacts serve SDF_RS, and CL_RS
	// when the body has no clusters or the object no convex part (meshes, planes).
	bool clustered = false;
	if ((m_cfg.collisions & fCollision::CL_RS) && m_clusters.size() > 0)
		clustered = caliber::collideClustersWithRigid(*this, *pcoWrap);
	if ((m_cfg.collisions & fCollision::SDF_RS) || !clustered) caliber::collideSoftWithRigid(*this, *pcoWrap);
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
	if (!psb || psb == this) return;  // self-collision (CL_SELF) is found by solveConstraints
	const int flags = m_cfg.collisions | psb->m_cfg.collisions;
	if ((flags & fCollision::CL_SS) && m_clusters.size() > 0 && psb->m_clusters.size() > 0)
		caliber::collideClustersWithClusters(*this, *psb);
	if (!(flags & fCollision::VF_SS)) return;
	// Nodes stay half the smaller margin away from the other body's faces; contacts are looked for
	// within the margins.
	const btScalar marginA = getCollisionShape()->getMargin(), marginB = psb->getCollisionShape()->getMargin();
	const btScalar thickness = btScalar(0.5) * btMin(marginA, marginB);
	const btScalar friction = btMax(m_cfg.kDF, psb->m_cfg.kDF);
	collideNodesWithFaces(*this, *psb, thickness, marginA, friction);
	collideNodesWithFaces(*psb, *this, thickness, marginB, friction);
}
