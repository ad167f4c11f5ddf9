// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The collision half of a world snapshot: the dbvt broadphase (both trees node for node, the stage
// lists, the counters of its incremental optimisation), the pair cache's pairs in their order with the
// state of each pair's collision algorithm, and the dispatcher's manifolds in their order with every
// point. Everything here decides the order in which the next step meets pairs, contacts and rows, so
// all of it is restored exactly: pairs are re-added in the saved order, algorithms are made again by the
// dispatcher (as the near callback makes them), their lazily made manifolds and GJK warm starts are set
// as saved, and the dispatcher's manifold array is put back into the saved order.

#include <functional>
#include <typeinfo>

#include "BulletCollision/BroadphaseCollision/btAxisSweep3.h"
#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/BroadphaseCollision/btDbvtProxyIds.h"
#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"
#include "BulletCollision/BroadphaseCollision/btSimpleBroadphase.h"
#include "BulletCollision/CollisionDispatch/btBoxBoxCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btCachedCollisionAlgorithms.h"
#include "BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h"
#include "BulletCollision/CollisionDispatch/btConvexPlaneCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btEmptyCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btGhostObject.h"
#include "BulletCollision/CollisionDispatch/btSphereBoxCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btSphereSphereCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btSphereTriangleCollisionAlgorithm.h"
#include "BulletCollision/CollisionShapes/btCompoundShape.h"
#include "BulletCollision/CollisionShapes/btTriangleShape.h"
#include "BulletDynamics/Dynamics/btWorldSnapshotAccess.h"
#include "BulletDynamics/Dynamics/btWorldSnapshotInternal.h"

namespace caliber
{
namespace snapshot
{
namespace
{
using namespace snapshot_access;

const int kBroadphaseDbvt = 1;
const int kBroadphaseSimple = 2;
const int kBroadphaseSweep16 = 3;
const int kBroadphaseSweep32 = 4;
const int kPairCacheHashed = 1;

// The collision algorithms whose whole state the snapshot holds (exact classes: a subclass may keep more).
enum AlgorithmKind
{
	kNoAlgorithm = 0,
	kConvexConvex = 1,
	kConvexConcave = 2,
	kBoxBox = 3,
	kSphereSphere = 4,
	kSphereBox = 5,
	kConvexPlane = 6,
	kSphereTriangle = 7,
	kEmpty = 8,
	kCompound = 9,
	kCompoundCompound = 10,
	kStateless = 11,  // an algorithm of an upper layer without state between steps (SnapshotExtension)
	kCachedBoxBox = 12,  // caliber::CachedBoxBoxAlgorithm, the default box-box algorithm (with its contact cache)
	kUnsupported = -1
};

// Compounds inside compounds nest algorithms; deeper nesting than this is refused (and a corrupt
// snapshot cannot recurse without bound).
const int kMaxAlgorithmDepth = 8;
// Children of one compound, and child pairs of one compound-compound algorithm, at most.
const int kMaxChildren = 1 << 16;

int algorithmKind(const btCollisionAlgorithm* algorithm)
{
	if (!algorithm) return kNoAlgorithm;
	const std::type_info& type = typeid(*algorithm);
	// The cached subclass the default factory makes has the same state plus its contact cache, which is
	// saved after the rest (cachedConvexOf).
	if (type == typeid(btConvexConvexAlgorithm) || type == typeid(caliber::CachedConvexConvexAlgorithm))
		return kConvexConvex;
	if (type == typeid(btConvexConcaveCollisionAlgorithm)) return kConvexConcave;
	if (type == typeid(btBoxBoxCollisionAlgorithm)) return kBoxBox;
	if (type == typeid(btSphereSphereCollisionAlgorithm)) return kSphereSphere;
	if (type == typeid(btSphereBoxCollisionAlgorithm)) return kSphereBox;
	if (type == typeid(btConvexPlaneCollisionAlgorithm)) return kConvexPlane;
	if (type == typeid(btSphereTriangleCollisionAlgorithm)) return kSphereTriangle;
	if (type == typeid(btEmptyAlgorithm)) return kEmpty;
	if (type == typeid(btCompoundCollisionAlgorithm)) return kCompound;
	if (type == typeid(btCompoundCompoundCollisionAlgorithm)) return kCompoundCompound;
	if (type == typeid(caliber::CachedBoxBoxAlgorithm)) return kCachedBoxBox;
	if (currentExtension() && currentExtension()->statelessAlgorithm(algorithm)) return kStateless;
	return kUnsupported;
}

// The single-manifold algorithms, which make their manifold in the constructor.
bool makesOwnManifold(int kind) { return (kind >= kBoxBox && kind <= kSphereTriangle) || kind == kCachedBoxBox; }

template <class IO>
void poseCacheState(IO& io, caliber::PairPoseCache& cache)
{
	io.field("contact cache valid", cache.valid);
	io.field("contact cache offset", cache.offset);
	for (int k = 0; k < 3; ++k) io.field("contact cache turn column", cache.turnColumns[k]);
	io.field("contact cache reach", cache.reach);
	io.field("contact cache shape 0 min", cache.shapes.min0);
	io.field("contact cache shape 0 max", cache.shapes.max0);
	io.field("contact cache shape 1 min", cache.shapes.min1);
	io.field("contact cache shape 1 max", cache.shapes.max1);
	io.field("contact cache points", cache.points);
}

int objectIndex(const btCollisionWorld& world, const btCollisionObject* object)
{
	if (!object) return -1;
	const int index = object->getWorldArrayIndex();
	if (index < 0 || index >= world.getNumCollisionObjects()) return -1;
	return world.getCollisionObjectArray()[index] == object ? index : -1;
}

btCollisionObject* objectAt(btDiscreteDynamicsWorld& world, int index)
{
	return world.getCollisionObjectArray()[index];
}

int proxyObjectIndex(const btCollisionWorld& world, const btBroadphaseProxy* proxy)
{
	return proxy ? objectIndex(world, static_cast<const btCollisionObject*>(proxy->m_clientObject)) : -1;
}

void setError(char* error, size_t errorSize, const char* format, ...)
{
	va_list args;
	va_start(args, format);
	vsnprintf(error, errorSize, format, args);
	va_end(args);
}

btDbvtBroadphase* dbvtOf(btDiscreteDynamicsWorld& world)
{
	return dynamic_cast<btDbvtBroadphase*>(world.getBroadphase());
}

// btSimpleBroadphase (exactly: a subclass may keep more): its only step state is each proxy's box and
// id; it finds pairs by testing every two proxies in handle order.
btSimpleBroadphase* simpleOf(btDiscreteDynamicsWorld& world)
{
	btBroadphaseInterface* broadphase = world.getBroadphase();
	return broadphase && typeid(*broadphase) == typeid(btSimpleBroadphase)
	           ? static_cast<btSimpleBroadphase*>(broadphase)
	           : 0;
}

template <class IO>
void plainProxyFields(IO& io, btBroadphaseProxy& proxy)
{
	io.field("proxy m_uniqueId", proxy.m_uniqueId);
	io.field("proxy m_aabbMin", proxy.m_aabbMin);
	io.field("proxy m_aabbMax", proxy.m_aabbMax);
}

// Reads whether object i has a broadphase proxy; a difference from the world's object fails the read.
bool readHasProxy(SnapshotReader& in, int i, const btBroadphaseProxy* proxy)
{
	const bool has = in.flag("has proxy");
	if (in.ok() && has != (proxy != 0))
		in.fail("object %d: %s a broadphase proxy, the snapshot's %s", i, proxy ? "has" : "has no",
		        has ? "has" : "has not");
	return in.ok() && has;
}

// btAxisSweep3 / bt32BitAxisSweep3 (exactly): per axis the sorted edge list, whose order among equal
// positions decides which pairs the next moves find first, and each proxy's box. The handles' edge
// indices follow from the lists. The optional ray accelerator is held as a dbvt of its own (below).
template <class Index>
struct SweepAccess : btAxisSweep3Internal<Index>
{
	typedef btAxisSweep3Internal<Index> Sweep;
	typedef typename Sweep::Edge Edge;
	typedef typename Sweep::Handle Handle;
	static Index& numHandles(Sweep& s) { return s.*(&SweepAccess::m_numHandles); }
	static Index maxHandles(Sweep& s) { return s.*(&SweepAccess::m_maxHandles); }
	static Index sentinel(Sweep& s) { return s.*(&SweepAccess::m_handleSentinel); }
	static Edge* edges(Sweep& s, int axis) { return (s.*(&SweepAccess::m_pEdges))[axis]; }
	static Handle* handles(Sweep& s) { return s.*(&SweepAccess::m_pHandles); }
	static btDbvtBroadphase* accelerator(Sweep& s) { return s.*(&SweepAccess::m_raycastAccelerator); }
};

template <class Index>
btAxisSweep3Internal<Index>* sweepOf(btDiscreteDynamicsWorld& world);
template <>
btAxisSweep3Internal<unsigned short>* sweepOf(btDiscreteDynamicsWorld& world)
{
	btBroadphaseInterface* broadphase = world.getBroadphase();
	return broadphase && typeid(*broadphase) == typeid(btAxisSweep3) ? static_cast<btAxisSweep3*>(broadphase) : 0;
}
template <>
btAxisSweep3Internal<unsigned int>* sweepOf(btDiscreteDynamicsWorld& world)
{
	btBroadphaseInterface* broadphase = world.getBroadphase();
	return broadphase && typeid(*broadphase) == typeid(bt32BitAxisSweep3) ? static_cast<bt32BitAxisSweep3*>(broadphase)
	                                                                      : 0;
}

// The handle index of object i's proxy in sweep, 0 when it has none or it is not one of sweep's.
template <class Index>
Index sweepHandleOf(btAxisSweep3Internal<Index>& sweep, btCollisionObject* object)
{
	typedef SweepAccess<Index> A;
	btBroadphaseProxy* proxy = object->getBroadphaseHandle();
	if (!proxy) return 0;
	const typename A::Handle* first = A::handles(sweep);
	const typename A::Handle* handle = static_cast<const typename A::Handle*>(proxy);
	if (handle <= first || handle >= first + A::maxHandles(sweep)) return 0;
	return Index(handle - first);
}

template <class Index>
void saveSweep(btDiscreteDynamicsWorld& world, btAxisSweep3Internal<Index>& sweep, int kind, SnapshotWriter& out)
{
	typedef SweepAccess<Index> A;
	out.context("broadphase", -1);
	out.field("kind", kind);
	for (int i = 0; i < world.getNumCollisionObjects(); ++i)
	{
		btBroadphaseProxy* proxy = world.getCollisionObjectArray()[i]->getBroadphaseHandle();
		out.context("object", i);
		out.field("has proxy", bool(proxy != 0));
		if (proxy) plainProxyFields(out, *proxy);
	}
	out.context("broadphase", -1);
	// Two edges per handle in use, and the sentinel's two at the ends.
	const int count = 2 * int(A::numHandles(sweep)) + 2;
	out.field("edge count", count);
	for (int axis = 0; axis < 3; ++axis)
	{
		const typename A::Edge* edges = A::edges(sweep, axis);
		for (int e = 0; e < count; ++e)
		{
			out.field("edge m_pos", unsigned(edges[e].m_pos));
			out.field("edge m_handle", unsigned(edges[e].m_handle));
		}
	}
}

template <class Index>
bool readSweep(btDiscreteDynamicsWorld& world, btAxisSweep3Internal<Index>* sweep, SnapshotReader& in)
{
	typedef SweepAccess<Index> A;
	if (!sweep)
	{
		in.fail("broadphase: the snapshot's is an axis sweep of another kind than the world's broadphase");
		return false;
	}
	const int n = world.getNumCollisionObjects();
	// Which handle belongs to a world object: the edge lists must list exactly those and the sentinel.
	btAlignedObjectArray<char> inWorld;
	inWorld.resize(int(A::maxHandles(*sweep)), 0);
	for (int i = 0; i < n && in.ok(); ++i)
	{
		btCollisionObject* object = world.getCollisionObjectArray()[i];
		btBroadphaseProxy* proxy = object->getBroadphaseHandle();
		const bool has = readHasProxy(in, i, proxy);
		if (!in.ok()) break;
		if (!has) continue;
		plainProxyFields(in, *proxy);
		const Index handle = sweepHandleOf(*sweep, object);
		if (in.ok() && handle == 0) in.fail("object %d: its proxy is not a handle of the world's broadphase", i);
		if (handle) inWorld[int(handle)] = 1;
	}
	const int count = in.value<int>("edge count");
	if (in.ok() && count != 2 * int(A::numHandles(*sweep)) + 2)
		in.fail("broadphase: %d edges per axis, the world's broadphase has %d", count,
		        2 * int(A::numHandles(*sweep)) + 2);
	if (!in.ok()) return false;
	btAlignedObjectArray<unsigned> positions[3], owners[3];
	for (int axis = 0; axis < 3 && in.ok(); ++axis)
	{
		btAlignedObjectArray<char> seenMin, seenMax;
		seenMin.resize(inWorld.size(), 0);
		seenMax.resize(inWorld.size(), 0);
		for (int e = 0; e < count && in.ok(); ++e)
		{
			const unsigned pos = in.value<unsigned>("edge m_pos");
			const unsigned handle = in.value<unsigned>("edge m_handle");
			if (!in.ok()) break;
			const bool isMax = (pos & 1u) != 0;
			// The sentinel's edges close the list at both ends; every other edge is a world object's, once
			// as minimum (even position) and once as maximum (odd), the minimum first, positions sorted.
			const bool end = e == 0 || e == count - 1;
			const char* problem = 0;
			if (pos > unsigned(A::sentinel(*sweep)) || (e > 0 && pos < positions[axis][e - 1]))
				problem = "out of order";
			else if (end && (handle != 0 || isMax != (e == count - 1) ||
			                 (e == count - 1 && pos != unsigned(A::sentinel(*sweep)))))
				problem = "not the sentinel";
			else if (!end && (handle == 0 || handle >= unsigned(inWorld.size()) || !inWorld[int(handle)]))
				problem = "not a world object's handle";
			else if (!end && (isMax ? seenMax[int(handle)] : seenMin[int(handle)]))
				problem = "listed twice";
			else if (!end && isMax && !seenMin[int(handle)])
				problem = "its maximum before its minimum";
			if (problem)
			{
				in.fail("broadphase: axis %d edge %d (position %u, handle %u): %s", axis, e, pos, handle, problem);
				break;
			}
			if (!end) (isMax ? seenMax : seenMin)[int(handle)] = 1;
			positions[axis].push_back(pos);
			owners[axis].push_back(handle);
		}
	}
	if (!in.ok() || !in.applying()) return in.ok();
	typename A::Handle* handles = A::handles(*sweep);
	for (int axis = 0; axis < 3; ++axis)
	{
		typename A::Edge* edges = A::edges(*sweep, axis);
		for (int e = 0; e < count; ++e)
		{
			edges[e].m_pos = Index(positions[axis][e]);
			edges[e].m_handle = Index(owners[axis][e]);
			typename A::Handle& h = handles[owners[axis][e]];
			if (e == 0)
				h.m_minEdges[axis] = 0;
			else if (positions[axis][e] & 1u)
				h.m_maxEdges[axis] = Index(e);
			else
				h.m_minEdges[axis] = Index(e);
		}
	}
	return true;
}

void saveSimpleBroadphase(btDiscreteDynamicsWorld& world, SnapshotWriter& out)
{
	out.context("broadphase", -1);
	out.field("kind", kBroadphaseSimple);
	for (int i = 0; i < world.getNumCollisionObjects(); ++i)
	{
		btBroadphaseProxy* proxy = world.getCollisionObjectArray()[i]->getBroadphaseHandle();
		out.context("object", i);
		out.field("has proxy", bool(proxy != 0));
		if (proxy) plainProxyFields(out, *proxy);
	}
}

bool readSimpleBroadphase(btDiscreteDynamicsWorld& world, SnapshotReader& in)
{
	if (!simpleOf(world))
	{
		in.fail("broadphase: the snapshot's is a btSimpleBroadphase, the world's is not");
		return false;
	}
	for (int i = 0; i < world.getNumCollisionObjects() && in.ok(); ++i)
	{
		btBroadphaseProxy* proxy = world.getCollisionObjectArray()[i]->getBroadphaseHandle();
		const bool has = readHasProxy(in, i, proxy);
		if (!in.ok()) break;
		if (has) plainProxyFields(in, *proxy);
	}
	return in.ok();
}

btHashedOverlappingPairCache* hashedCacheOf(btDiscreteDynamicsWorld& world)
{
	return world.getBroadphase() ? dynamic_cast<btHashedOverlappingPairCache*>(world.getPairCache()) : 0;
}

// The ghost objects of the world, in the world's order (each keeps its overlapping objects, and a
// pair-caching ghost its own pairs with their algorithms).
void ghostsOf(btDiscreteDynamicsWorld& world, btAlignedObjectArray<int>& ghosts)
{
	ghosts.resize(0);
	for (int i = 0; i < world.getNumCollisionObjects(); ++i)
		if (btGhostObject::upcast(world.getCollisionObjectArray()[i])) ghosts.push_back(i);
}

btPairCachingGhostObject* cachingGhostOf(btCollisionObject* object)
{
	return dynamic_cast<btPairCachingGhostObject*>(object);
}

// The manifolds a pair's algorithm owns, in the algorithm's order.
void pairManifolds(btBroadphasePair& pair, btManifoldArray& manifolds)
{
	manifolds.resize(0);
	if (pair.m_algorithm) pair.m_algorithm->getAllContactManifolds(manifolds);
}

// ---- broadphase ---------------------------------------------------------------------------------

template <class IO>
void dbvtCounters(IO& io, btDbvtBroadphase& dbvt)
{
	// Counters the broadphase adds to are kept well below INT_MAX (a corrupt one would overflow), and the
	// percentages of leaves re-inserted per step so that their products with leaf counts stay ints.
	const int counterLimit = 0x7fff0000;
	io.field("m_prediction", dbvt.m_prediction);
	io.field("m_stageCurrent", dbvt.m_stageCurrent, 0, counterLimit);
	io.field("m_fupdates", dbvt.m_fupdates, 0, 10000);
	io.field("m_dupdates", dbvt.m_dupdates, 0, 10000);
	io.field("m_cupdates", dbvt.m_cupdates, 0, 10000);
	io.field("m_newpairs", dbvt.m_newpairs);
	io.field("m_fixedleft", dbvt.m_fixedleft, 0, counterLimit);
	io.field("m_updates_call", dbvt.m_updates_call);
	io.field("m_updates_done", dbvt.m_updates_done);
	io.field("m_updates_ratio", dbvt.m_updates_ratio);
	io.field("m_pid", dbvt.m_pid, 0, counterLimit);
	io.field("m_cid", dbvt.m_cid, 0, counterLimit);
	io.field("m_gid", dbvt.m_gid, 0, counterLimit);
	io.field("m_deferedcollide", dbvt.m_deferedcollide);
	io.field("m_needcleanup", dbvt.m_needcleanup);
}

// A btDbvtBroadphase whose proxies belong to the world's objects: the world's broadphase, or an axis
// sweep's ray accelerator (whose proxies mirror the sweep's handles).
struct DbvtView
{
	btDbvtBroadphase* dbvt;
	std::function<btDbvtProxy*(int object)> proxyOf;
};

DbvtView mainDbvtView(btDiscreteDynamicsWorld& world, btDbvtBroadphase* dbvt)
{
	return DbvtView{dbvt, [&world](int i)
	                { return static_cast<btDbvtProxy*>(world.getCollisionObjectArray()[i]->getBroadphaseHandle()); }};
}

template <class Index>
DbvtView acceleratorView(btDiscreteDynamicsWorld& world, btAxisSweep3Internal<Index>& sweep)
{
	return DbvtView{SweepAccess<Index>::accelerator(sweep),
	                [&world](int i) -> btDbvtProxy*
	                {
		                btBroadphaseProxy* handle = world.getCollisionObjectArray()[i]->getBroadphaseHandle();
		                if (!handle) return 0;
		                typedef typename btAxisSweep3Internal<Index>::Handle Handle;
		                return static_cast<btDbvtProxy*>(static_cast<Handle*>(handle)->m_dbvtProxy);
	                }};
}

// Both trees node for node, each proxy's id, box and stage, the stage lists in order and the counters.
bool saveDbvtState(btDiscreteDynamicsWorld& world, const DbvtView& view, SnapshotWriter& out, char* error,
                   size_t errorSize)
{
	btDbvtBroadphase* dbvt = view.dbvt;
	const int n = world.getNumCollisionObjects();
	int proxies = 0;
	dbvtCounters(out, *dbvt);
	for (int i = 0; i < n; ++i)
	{
		btDbvtProxy* proxy = view.proxyOf(i);
		out.context("object", i);
		out.field("has proxy", bool(proxy != 0));
		if (!proxy) continue;
		++proxies;
		plainProxyFields(out, *proxy);
		out.field("proxy set", caliber::dbvtTreeOf(*proxy));
	}
	if (proxies != dbvt->m_sets[0].m_leaves + dbvt->m_sets[1].m_leaves)
	{
		setError(error, errorSize, "broadphase: it holds proxies of objects outside the world");
		return false;
	}
	out.context("broadphase", -1);
	for (int stage = 0; stage <= btDbvtBroadphase::STAGECOUNT; ++stage)
	{
		int count = 0;
		for (btDbvtProxy* p = dbvt->m_stageRoots[stage]; p; p = p->links[1]) ++count;
		out.field("stage count", count);
		for (btDbvtProxy* p = dbvt->m_stageRoots[stage]; p; p = p->links[1])
			out.field("stage member", proxyObjectIndex(world, p));
	}
	btAlignedObjectArray<const btDbvtNode*> stack;
	for (int set = 0; set < 2; ++set)
	{
		btDbvt& tree = dbvt->m_sets[set];
		out.field("tree m_lkhd", tree.m_lkhd);
		out.field("tree m_leaves", tree.m_leaves);
		out.field("tree m_opath", tree.m_opath);
		const int nodeCount = tree.m_leaves > 0 ? 2 * tree.m_leaves - 1 : 0;
		out.field("tree nodes", nodeCount);
		int written = 0;
		stack.resize(0);
		if (tree.m_root) stack.push_back(tree.m_root);
		while (stack.size())  // preorder: a node, then its child 0's subtree, then child 1's
		{
			const btDbvtNode* node = stack[stack.size() - 1];
			stack.pop_back();
			++written;
			const bool leaf = node->isleaf();
			out.field("node leaf", leaf);
			out.field("node mins", node->volume.Mins());
			out.field("node maxs", node->volume.Maxs());
			if (leaf)
				out.field("node object", proxyObjectIndex(world, static_cast<const btBroadphaseProxy*>(node->data)));
			else
			{
				stack.push_back(node->childs[1]);
				stack.push_back(node->childs[0]);
			}
		}
		if (written != nodeCount)
		{
			setError(error, errorSize, "broadphase: tree %d has %d nodes for %d leaves", set, written, tree.m_leaves);
			return false;
		}
	}
	return true;
}

// An axis sweep's optional ray accelerator: a dbvt of its own, whose tree decides the order in which ray
// and box tests visit objects (and so which of two tied hits a closest-hit callback keeps).
template <class Index>
bool saveAccelerator(btDiscreteDynamicsWorld& world, btAxisSweep3Internal<Index>& sweep, SnapshotWriter& out,
                     char* error, size_t errorSize)
{
	const DbvtView view = acceleratorView(world, sweep);
	out.context("broadphase", -1);
	out.field("ray accelerator", bool(view.dbvt != 0));
	return !view.dbvt || saveDbvtState(world, view, out, error, errorSize);
}

bool saveBroadphase(btDiscreteDynamicsWorld& world, SnapshotWriter& out, char* error, size_t errorSize)
{
	if (simpleOf(world))
	{
		saveSimpleBroadphase(world, out);
		return true;
	}
	if (btAxisSweep3Internal<unsigned short>* sweep = sweepOf<unsigned short>(world))
	{
		saveSweep(world, *sweep, kBroadphaseSweep16, out);
		return saveAccelerator(world, *sweep, out, error, errorSize);
	}
	if (btAxisSweep3Internal<unsigned int>* sweep = sweepOf<unsigned int>(world))
	{
		saveSweep(world, *sweep, kBroadphaseSweep32, out);
		return saveAccelerator(world, *sweep, out, error, errorSize);
	}
	btDbvtBroadphase* dbvt = dbvtOf(world);
	if (!dbvt)
	{
		setError(error, errorSize,
		         "broadphase: only btDbvtBroadphase, btSimpleBroadphase, btAxisSweep3 and bt32BitAxisSweep3 are "
		         "supported");
		return false;
	}
	out.context("broadphase", -1);
	out.field("kind", kBroadphaseDbvt);
	return saveDbvtState(world, mainDbvtView(world, dbvt), out, error, errorSize);
}

struct SavedNode
{
	bool leaf;
	btVector3 mins, maxs;
	int object;
};

// Checks a preorder node list: a full binary tree whose leaves are distinct objects of this tree's set.
bool checkTree(SnapshotReader& in, const btAlignedObjectArray<SavedNode>& nodes, int leaves, int set,
               const btAlignedObjectArray<int>& proxySet, btAlignedObjectArray<char>& seen)
{
	int open = nodes.size() ? 1 : 0;
	int leafCount = 0;
	for (int i = 0; i < nodes.size(); ++i)
	{
		if (open <= 0)
		{
			in.fail("broadphase: tree %d is not a binary tree (node %d has no parent)", set, i);
			return false;
		}
		--open;
		if (!nodes[i].leaf)
		{
			open += 2;
			continue;
		}
		++leafCount;
		const int object = nodes[i].object;
		if (object < 0 || object >= proxySet.size() || proxySet[object] != set || seen[object])
		{
			in.fail("broadphase: tree %d leaf %d names object %d, which is not a proxy of this tree", set, i, object);
			return false;
		}
		seen[object] = 1;
	}
	if (open != 0 || leafCount != leaves)
	{
		in.fail("broadphase: tree %d is not a full binary tree of %d leaves", set, leaves);
		return false;
	}
	return true;
}

// Replaces a tree's internal nodes by the saved ones; the leaves stay the proxies' own nodes.
void rebuildTree(btDbvt& tree, const btAlignedObjectArray<SavedNode>& nodes, const DbvtView& view)
{
	// The old internal nodes go to the tree's free list (linked through parent, as the tree frees them);
	// the new tree needs as many, since its leaves are the same.
	btAlignedObjectArray<btDbvtNode*> stack;
	if (tree.m_root) stack.push_back(tree.m_root);
	while (stack.size())
	{
		btDbvtNode* node = stack[stack.size() - 1];
		stack.pop_back();
		if (node->isleaf()) continue;
		stack.push_back(node->childs[0]);
		stack.push_back(node->childs[1]);
		node->childs[0] = node->childs[1] = 0;
		node->parent = tree.m_free;
		tree.m_free = node;
	}
	tree.m_root = 0;
	stack.resize(0);
	for (int i = 0; i < nodes.size(); ++i)
	{
		btDbvtNode* node;
		if (nodes[i].leaf)
		{
			node = view.proxyOf(nodes[i].object)->leaf;
		}
		else
		{
			node = tree.m_free;
			tree.m_free = node->parent;
			node->childs[0] = node->childs[1] = 0;
		}
		node->volume = btDbvtVolume::FromMM(nodes[i].mins, nodes[i].maxs);
		if (!stack.size())
		{
			tree.m_root = node;
			node->parent = 0;
		}
		else
		{
			btDbvtNode* parent = stack[stack.size() - 1];
			const int slot = parent->childs[0] ? 1 : 0;
			parent->childs[slot] = node;
			node->parent = parent;
			if (slot == 1) stack.pop_back();
		}
		if (!nodes[i].leaf) stack.push_back(node);
	}
}

bool readDbvtState(btDiscreteDynamicsWorld& world, const DbvtView& view, SnapshotReader& in)
{
	const int n = world.getNumCollisionObjects();
	btDbvtBroadphase* dbvt = view.dbvt;
	dbvtCounters(in, *dbvt);

	btAlignedObjectArray<int> proxySet;  // per object: its tree, -1 without a proxy
	proxySet.resize(n, -1);
	for (int i = 0; i < n && in.ok(); ++i)
	{
		btDbvtProxy* proxy = view.proxyOf(i);
		const bool has = readHasProxy(in, i, proxy);
		if (!in.ok()) break;
		if (!has) continue;
		const int uniqueId = in.value<int>("proxy m_uniqueId");
		const btVector3 aabbMin = in.vector("proxy m_aabbMin");
		const btVector3 aabbMax = in.vector("proxy m_aabbMax");
		const int set = in.value<int>("proxy set");
		// A leaf node belongs to its tree's node blocks: a proxy cannot change trees. The tree is the id's
		// parity, so the saved id must name the saved tree too.
		const int tree = caliber::dbvtTreeOf(*proxy);
		if (in.ok() && set != tree)
			in.fail("object %d: proxy in tree %d, the snapshot's in tree %d", i, tree, set);
		if (in.ok() && (uniqueId & 1) != set)
			in.fail("object %d: proxy id %d does not belong to tree %d (odd ids are the fixed tree's)", i, uniqueId,
			        set);
		proxySet[i] = set;
		if (in.ok() && in.applying())
		{
			proxy->m_uniqueId = uniqueId;
			proxy->m_aabbMin = aabbMin;
			proxy->m_aabbMax = aabbMax;
		}
	}

	btAlignedObjectArray<int> stageMembers[btDbvtBroadphase::STAGECOUNT + 1];
	btAlignedObjectArray<char> seen;
	seen.resize(n, 0);
	for (int stage = 0; stage <= btDbvtBroadphase::STAGECOUNT && in.ok(); ++stage)
	{
		const int count = in.count("stage count", n);
		for (int k = 0; k < count && in.ok(); ++k)
		{
			const int object = in.value<int>("stage member");
			if (!in.ok()) break;
			if (object < 0 || object >= n || proxySet[object] < 0 || seen[object])
			{
				in.fail("broadphase: stage %d names object %d, which has no proxy or is listed twice", stage, object);
				break;
			}
			seen[object] = 1;
			stageMembers[stage].push_back(object);
		}
	}
	for (int i = 0; i < n && in.ok(); ++i)
		if (proxySet[i] >= 0 && !seen[i]) in.fail("broadphase: object %d is in no stage list", i);

	btAlignedObjectArray<SavedNode> nodes[2];
	int lookahead[2], leaves[2];
	unsigned path[2];
	for (int set = 0; set < 2 && in.ok(); ++set)
	{
		lookahead[set] = in.value<int>("tree m_lkhd");
		leaves[set] = in.count("tree m_leaves", n);
		path[set] = in.value<unsigned>("tree m_opath");
		const int nodeCount = in.count("tree nodes", 2 * n);
		if (in.ok() && nodeCount != (leaves[set] > 0 ? 2 * leaves[set] - 1 : 0))
			in.fail("broadphase: tree %d has %d nodes for %d leaves", set, nodeCount, leaves[set]);
		if (in.ok() && leaves[set] != dbvt->m_sets[set].m_leaves)
			in.fail("broadphase: tree %d has %d leaves, the world's %d", set, leaves[set], dbvt->m_sets[set].m_leaves);
		for (int k = 0; k < nodeCount && in.ok(); ++k)
		{
			SavedNode node;
			node.leaf = in.flag("node leaf");
			node.mins = in.vector("node mins");
			node.maxs = in.vector("node maxs");
			node.object = node.leaf ? in.value<int>("node object") : -1;
			nodes[set].push_back(node);
		}
		for (int i = 0; i < n; ++i) seen[i] = 0;
		if (in.ok()) checkTree(in, nodes[set], leaves[set], set, proxySet, seen);
	}
	if (!in.ok() || !in.applying()) return in.ok();

	// The proxies' stage lists, in the saved order.
	for (int stage = 0; stage <= btDbvtBroadphase::STAGECOUNT; ++stage)
	{
		btDbvtProxy* previous = 0;
		dbvt->m_stageRoots[stage] = 0;
		for (int k = 0; k < stageMembers[stage].size(); ++k)
		{
			btDbvtProxy* proxy = view.proxyOf(stageMembers[stage][k]);
			proxy->stage = stage;
			proxy->links[0] = previous;
			proxy->links[1] = 0;
			if (previous)
				previous->links[1] = proxy;
			else
				dbvt->m_stageRoots[stage] = proxy;
			previous = proxy;
		}
	}
	for (int set = 0; set < 2; ++set)
	{
		btDbvt& tree = dbvt->m_sets[set];
		rebuildTree(tree, nodes[set], view);
		tree.m_lkhd = lookahead[set];
		tree.m_opath = path[set];
	}
	return true;
}

template <class Index>
bool readSweepAndAccelerator(btDiscreteDynamicsWorld& world, btAxisSweep3Internal<Index>* sweep, SnapshotReader& in)
{
	if (!readSweep(world, sweep, in)) return false;
	const DbvtView view = acceleratorView(world, *sweep);
	const bool has = in.flag("ray accelerator");
	if (in.ok() && has != (view.dbvt != 0))
		in.fail("broadphase: the snapshot's axis sweep %s a ray accelerator, the world's %s", has ? "has" : "has no",
		        view.dbvt ? "has" : "has not");
	if (!in.ok()) return false;
	return !has || readDbvtState(world, view, in);
}

bool readBroadphase(btDiscreteDynamicsWorld& world, SnapshotReader& in)
{
	const int kind = in.value<int>("broadphase kind");
	if (in.ok() && kind == kBroadphaseSimple) return readSimpleBroadphase(world, in);
	if (in.ok() && kind == kBroadphaseSweep16)
	{
		btAxisSweep3Internal<unsigned short>* sweep = sweepOf<unsigned short>(world);
		if (!sweep) return readSweep(world, sweep, in);  // fails with the reason
		return readSweepAndAccelerator(world, sweep, in);
	}
	if (in.ok() && kind == kBroadphaseSweep32)
	{
		btAxisSweep3Internal<unsigned int>* sweep = sweepOf<unsigned int>(world);
		if (!sweep) return readSweep(world, sweep, in);
		return readSweepAndAccelerator(world, sweep, in);
	}
	if (in.ok() && kind != kBroadphaseDbvt) in.fail("broadphase: unknown kind %d", kind);
	btDbvtBroadphase* dbvt = dbvtOf(world);
	if (in.ok() && !dbvt) in.fail("broadphase: the world's broadphase is not a btDbvtBroadphase");
	if (!in.ok()) return false;
	return readDbvtState(world, mainDbvtView(world, dbvt), in);
}

// ---- pairs and their algorithms -----------------------------------------------------------------

caliber::CachedConvexConvexAlgorithm* cachedConvexOf(btConvexConvexAlgorithm& algorithm)
{
	return typeid(algorithm) == typeid(caliber::CachedConvexConvexAlgorithm)
	           ? static_cast<caliber::CachedConvexConvexAlgorithm*>(&algorithm)
	           : 0;
}

void convexState(SnapshotWriter& out, btConvexConvexAlgorithm& algorithm)
{
	out.field("m_haveLastSeparatingAxis", convexHaveLastAxis(algorithm));
	out.field("m_lastSeparatingAxis", convexLastAxis(algorithm));
	caliber::CachedConvexConvexAlgorithm* cached = cachedConvexOf(algorithm);
	out.field("contact cache", cached != 0);
	if (cached) poseCacheState(out, cached->poseCache());
}

// Writes an algorithm's kind and state; compound algorithms write their child algorithms after it
// (a child slot without an algorithm is kind 0), depth first.
bool saveAlgorithm(SnapshotWriter& out, btCollisionAlgorithm* algorithm, char* error, size_t errorSize, int pairIndex,
                   int depth)
{
	const int kind = algorithmKind(algorithm);
	if (kind == kUnsupported || depth > kMaxAlgorithmDepth)
	{
		setError(error, errorSize,
		         "pair %d: a collision algorithm the snapshot does not support (soft bodies, user algorithms, "
		         "compounds nested deeper than %d)",
		         pairIndex, kMaxAlgorithmDepth);
		return false;
	}
	out.field("algorithm", kind);
	if (kind == kConvexConvex)
	{
		btConvexConvexAlgorithm& convex = *static_cast<btConvexConvexAlgorithm*>(algorithm);
		out.field("owns manifold", bool(convexOwnsManifold(convex) && convexManifold(convex)));
		convexState(out, convex);
	}
	else if (kind == kConvexConcave)
	{
		btCollisionAlgorithm* triangle =
		    triangleAlgorithm(concaveCallback(*static_cast<btConvexConcaveCollisionAlgorithm*>(algorithm)));
		const int triangleKind = algorithmKind(triangle);
		if (triangleKind != kNoAlgorithm && triangleKind != kConvexConvex && triangleKind != kSphereTriangle &&
		    triangleKind != kEmpty)
		{
			setError(error, errorSize,
			         "pair %d: its mesh algorithm uses a triangle algorithm the snapshot does not support", pairIndex);
			return false;
		}
		out.field("triangle algorithm", triangleKind);
		if (triangleKind == kConvexConvex) convexState(out, *static_cast<btConvexConvexAlgorithm*>(triangle));
	}
	else if (makesOwnManifold(kind))
	{
		// Made in the constructor only when the bodies were active then (see remakeAlgorithm).
		btManifoldArray manifolds;
		algorithm->getAllContactManifolds(manifolds);
		out.field("own manifolds", manifolds.size());
		if (kind == kCachedBoxBox)
			poseCacheState(out, static_cast<caliber::CachedBoxBoxAlgorithm*>(algorithm)->poseCache());
	}
	else if (kind == kCompound)
	{
		CompoundChildAlgorithms& children = compoundChildren(*static_cast<btCompoundCollisionAlgorithm*>(algorithm));
		out.field("child count", children.size());
		for (int c = 0; c < children.size(); ++c)
			if (!saveAlgorithm(out, children[c], error, errorSize, pairIndex, depth + 1)) return false;
	}
	else if (kind == kCompoundCompound)
	{
		btCompoundCompoundCollisionAlgorithm& both = *static_cast<btCompoundCompoundCollisionAlgorithm*>(algorithm);
		CompoundChildPairs& pairs = compoundPairs(both);
		out.field("m_frame", compoundFrame(both));
		out.field("child pair count", pairs.size());
		for (int c = 0; c < pairs.size(); ++c)
		{
			const btCompoundCompoundCollisionAlgorithm::ChildPairKey key = pairs.getKeyAtIndex(c);
			const btCompoundCompoundCollisionAlgorithm::ChildPairAlgorithm* entry = pairs.getAtIndex(c);
			out.field("child 0", key.m_index0);
			out.field("child 1", key.m_index1);
			out.field("m_lastFrame", entry->m_lastFrame);
			if (!saveAlgorithm(out, entry->m_algorithm, error, errorSize, pairIndex, depth + 1)) return false;
		}
	}
	return true;
}

// Writes a pair list (the world's, or a pair-caching ghost's) with each pair's algorithm and the indices
// of the manifolds it owns in the dispatcher's array, marking them in owned.
bool savePairList(btDiscreteDynamicsWorld& world, btBroadphasePairArray& pairs, SnapshotWriter& out,
                  btAlignedObjectArray<char>& owned, char* error, size_t errorSize, const char* section)
{
	btDispatcher* dispatcher = world.getDispatcher();
	btManifoldArray manifolds;
	out.field("pair count", pairs.size());
	for (int i = 0; i < pairs.size(); ++i)
	{
		btBroadphasePair& pair = pairs[i];
		out.context(section, i);
		const int object0 = proxyObjectIndex(world, pair.m_pProxy0);
		const int object1 = proxyObjectIndex(world, pair.m_pProxy1);
		if (object0 < 0 || object1 < 0)
		{
			setError(error, errorSize, "%s %d: a proxy of an object outside the world", section, i);
			return false;
		}
		out.field("object 0", object0);
		out.field("object 1", object1);
		if (!saveAlgorithm(out, pair.m_algorithm, error, errorSize, i, 0)) return false;
		pairManifolds(pair, manifolds);
		out.field("manifold count", manifolds.size());
		for (int m = 0; m < manifolds.size(); ++m)
		{
			const int index = manifolds[m]->m_index1a;
			if (index < 0 || index >= owned.size() || dispatcher->getManifoldByIndexInternal(index) != manifolds[m] ||
			    owned[index])
			{
				setError(error, errorSize, "%s %d: a manifold the dispatcher does not list", section, i);
				return false;
			}
			owned[index] = 1;
			out.field("manifold", index);
		}
	}
	return true;
}

bool savePairs(btDiscreteDynamicsWorld& world, SnapshotWriter& out, char* error, size_t errorSize)
{
	btHashedOverlappingPairCache* cache = hashedCacheOf(world);
	if (!cache)
	{
		setError(error, errorSize, "pairs: only btHashedOverlappingPairCache is supported");
		return false;
	}
	btDispatcher* dispatcher = world.getDispatcher();
	const int manifoldCount = dispatcher->getNumManifolds();
	btAlignedObjectArray<char> owned;
	owned.resize(manifoldCount, 0);
	out.context("pairs", -1);
	out.field("cache", kPairCacheHashed);
	if (!savePairList(world, cache->getOverlappingPairArray(), out, owned, error, errorSize, "pair")) return false;

	// Ghosts: the overlapping objects in their order, and a pair-caching ghost's own pairs.
	btAlignedObjectArray<int> ghosts;
	ghostsOf(world, ghosts);
	out.context("ghosts", -1);
	out.field("ghost count", ghosts.size());
	for (int g = 0; g < ghosts.size(); ++g)
	{
		btCollisionObject* object = objectAt(world, ghosts[g]);
		btGhostObject* ghost = btGhostObject::upcast(object);
		btPairCachingGhostObject* caching = cachingGhostOf(object);
		out.context("ghost", ghosts[g]);
		out.field("object", ghosts[g]);
		out.field("pair caching", bool(caching != 0));
		btAlignedObjectArray<btCollisionObject*>& overlapping = ghost->getOverlappingPairs();
		out.field("overlapping count", overlapping.size());
		for (int k = 0; k < overlapping.size(); ++k)
		{
			const int index = objectIndex(world, overlapping[k]);
			if (index < 0)
			{
				setError(error, errorSize, "ghost %d: it overlaps an object outside the world", ghosts[g]);
				return false;
			}
			out.field("overlapping", index);
		}
		if (caching && !savePairList(world, caching->getOverlappingPairCache()->getOverlappingPairArray(), out, owned,
		                             error, errorSize, "ghost pair"))
			return false;
	}
	for (int m = 0; m < manifoldCount; ++m)
	{
		if (!owned[m])
		{
			setError(error, errorSize, "manifold %d: not owned by a pair's algorithm (user or predictive manifolds)",
			         m);
			return false;
		}
	}
	return true;
}

// An algorithm as saved: its kind and state, and for compounds where its children are.
struct SavedAlgorithm
{
	int kind;
	bool ownsManifold;
	int triangleKind;
	bool haveAxis;
	btVector3 axis;
	int ownManifolds;
	int frame;
	int firstChild, childCount;  // into the flat child list
	caliber::PairPoseCache poseCache;
	bool hasPoseCache;  // a convex-convex algorithm with a contact cache
};

// A child slot of a compound algorithm (compound-compound: a child pair with its last frame).
struct SavedChild
{
	int index0, index1, lastFrame;
	int algorithm;  // into the algorithm list; -1 for an empty slot
};

struct SavedPair
{
	int object0, object1;
	int algorithm;                     // into the algorithm list; -1 for none
	int firstManifold, manifoldCount;  // into the flat manifold list
};

struct SavedAlgorithms
{
	btAlignedObjectArray<SavedAlgorithm> algorithms;
	btAlignedObjectArray<SavedChild> children;
};

void readConvexState(SnapshotReader& in, SavedAlgorithm& a)
{
	a.haveAxis = in.flag("m_haveLastSeparatingAxis");
	a.axis = in.vector("m_lastSeparatingAxis");
	a.hasPoseCache = in.flag("contact cache");
	if (a.hasPoseCache) poseCacheState(in, a.poseCache);
}

// Gives a remade convex-convex algorithm its saved state; false when the snapshot has a contact cache and
// the dispatcher made an algorithm without one.
bool restoreConvexState(btConvexConvexAlgorithm& convex, const SavedAlgorithm& s)
{
	convexHaveLastAxis(convex) = s.haveAxis;
	convexLastAxis(convex) = s.axis;
	caliber::CachedConvexConvexAlgorithm* cached = cachedConvexOf(convex);
	if (s.hasPoseCache && !cached) return false;
	if (cached) cached->poseCache() = s.hasPoseCache ? s.poseCache : caliber::PairPoseCache();
	return true;
}

// Reads one algorithm (and, depth first, its children); the index of its record, -1 for kind 0 or on
// failure.
int readAlgorithm(SnapshotReader& in, SavedAlgorithms& saved, int pairIndex, int depth)
{
	SavedAlgorithm a;
	a.kind = in.value<int>("algorithm");
	a.ownsManifold = false;
	a.triangleKind = kNoAlgorithm;
	a.haveAxis = false;
	a.hasPoseCache = false;
	a.axis.setValue(0, 0, 0);
	a.ownManifolds = 0;
	a.frame = 0;
	a.firstChild = a.childCount = 0;
	if (!in.ok()) return -1;
	if (a.kind < kNoAlgorithm || a.kind > kCachedBoxBox || (a.kind == kStateless && !currentExtension()) ||
	    depth > kMaxAlgorithmDepth)
	{
		in.fail("pair %d: unknown algorithm %d (or nested deeper than %d)", pairIndex, a.kind, kMaxAlgorithmDepth);
		return -1;
	}
	if (a.kind == kNoAlgorithm) return -1;
	btAlignedObjectArray<SavedChild> block;  // this algorithm's children, appended once complete
	if (a.kind == kConvexConvex)
	{
		a.ownsManifold = in.flag("owns manifold");
		readConvexState(in, a);
	}
	else if (a.kind == kConvexConcave)
	{
		a.triangleKind = in.value<int>("triangle algorithm");
		if (in.ok() && a.triangleKind != kNoAlgorithm && a.triangleKind != kConvexConvex &&
		    a.triangleKind != kSphereTriangle && a.triangleKind != kEmpty)
			in.fail("pair %d: unknown triangle algorithm %d", pairIndex, a.triangleKind);
		if (a.triangleKind == kConvexConvex)
		{
			readConvexState(in, a);
		}
	}
	else if (makesOwnManifold(a.kind))
	{
		a.ownManifolds = in.count("own manifolds", 1);
		if (a.kind == kCachedBoxBox) poseCacheState(in, a.poseCache);
	}
	else if (a.kind == kCompound)
	{
		const int count = in.count("child count", kMaxChildren);
		for (int c = 0; c < count && in.ok(); ++c)
		{
			SavedChild child;
			child.index0 = c;
			child.index1 = -1;
			child.lastFrame = 0;
			child.algorithm = readAlgorithm(in, saved, pairIndex, depth + 1);
			block.push_back(child);
		}
	}
	else if (a.kind == kCompoundCompound)
	{
		a.frame = in.value<int>("m_frame");
		const int count = in.count("child pair count", kMaxChildren);
		for (int c = 0; c < count && in.ok(); ++c)
		{
			SavedChild child;
			child.index0 = in.value<int>("child 0");
			child.index1 = in.value<int>("child 1");
			child.lastFrame = in.value<int>("m_lastFrame");
			if (in.ok() && (child.index0 < 0 || child.index1 < 0))
				in.fail("pair %d: child pair %d names children %d, %d", pairIndex, c, child.index0, child.index1);
			for (int k = 0; k < c && in.ok(); ++k)
				if (block[k].index0 == child.index0 && block[k].index1 == child.index1)
					in.fail("pair %d: child pair %d, %d listed twice", pairIndex, child.index0, child.index1);
			child.algorithm = readAlgorithm(in, saved, pairIndex, depth + 1);
			if (in.ok() && child.algorithm < 0) in.fail("pair %d: a child pair without an algorithm", pairIndex);
			block.push_back(child);
		}
	}
	if (!in.ok()) return -1;
	a.firstChild = saved.children.size();
	a.childCount = block.size();
	for (int c = 0; c < block.size(); ++c) saved.children.push_back(block[c]);
	saved.algorithms.push_back(a);
	return saved.algorithms.size() - 1;
}

// Makes the triangle algorithm of a mesh pair as btConvexTriangleCallback::processTriangle makes it.
btCollisionAlgorithm* makeTriangleAlgorithm(btDispatcher* dispatcher, btConvexTriangleCallback& callback,
                                            const btCollisionObjectWrapper& convexWrap,
                                            const btCollisionObjectWrapper& meshWrap, int wantedKind)
{
	btTriangleShape triangle(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 0, 1));
	btCollisionObjectWrapper triangleWrap(&meshWrap, &triangle, meshWrap.getCollisionObject(),
	                                      meshWrap.getWorldTransform(), 0, 0);
	const ebtDispatcherQueryType queries[2] = {BT_CONTACT_POINT_ALGORITHMS, BT_CLOSEST_POINT_ALGORITHMS};
	for (int q = 0; q < 2; ++q)
	{
		btCollisionAlgorithm* algorithm =
		    dispatcher->findAlgorithm(&convexWrap, &triangleWrap, callback.m_manifoldPtr, queries[q]);
		if (algorithmKind(algorithm) == wantedKind) return algorithm;
		if (algorithm)
		{
			algorithm->~btCollisionAlgorithm();
			dispatcher->freeCollisionAlgorithm(algorithm);
		}
	}
	return 0;
}

void freeAlgorithm(btDispatcher* dispatcher, btCollisionAlgorithm*& algorithm)
{
	if (!algorithm) return;
	algorithm->~btCollisionAlgorithm();
	dispatcher->freeCollisionAlgorithm(algorithm);
	algorithm = 0;
}

// Makes the algorithm for wrap0 and wrap1 again, as the near callback (top level, shared null) or a
// compound algorithm (children, with its shared manifold) makes it, and gives it the saved state, its
// children included. False (with the reason) when the dispatcher makes another kind, a saved child does
// not exist in the shapes, or no manifold can be made; whatever was made is then in result, for the
// caller to free with the rest.
bool remakeAlgorithm(btDispatcher* dispatcher, const btCollisionObjectWrapper& wrap0,
                     const btCollisionObjectWrapper& wrap1, btPersistentManifold* shared, const SavedAlgorithms& saved,
                     int savedIndex, SnapshotReader& in, int pairIndex, btCollisionAlgorithm*& result)
{
	const SavedAlgorithm& s = saved.algorithms[savedIndex];
	btCollisionObject* object0 = const_cast<btCollisionObject*>(wrap0.getCollisionObject());
	btCollisionObject* object1 = const_cast<btCollisionObject*>(wrap1.getCollisionObject());
	result = dispatcher->findAlgorithm(&wrap0, &wrap1, shared, BT_CONTACT_POINT_ALGORITHMS);
	int kind = algorithmKind(result);
	if (makesOwnManifold(kind) && !shared)
	{
		// These algorithms make their manifold in the constructor, and only when the dispatcher's
		// needsCollision holds then: a pair made while both bodies slept has none. When the bodies'
		// restored activation gives the other answer, the algorithm is made again under the activation
		// that gives the saved one (needsCollision reads only whether either body is active), and the
		// restored activation goes back.
		btManifoldArray manifolds;
		result->getAllContactManifolds(manifolds);
		if (manifolds.size() != s.ownManifolds)
		{
			freeAlgorithm(dispatcher, result);
			const int state0 = activationState(*object0), state1 = activationState(*object1);
			const int forced = s.ownManifolds > 0 ? ACTIVE_TAG : ISLAND_SLEEPING;
			activationState(*object0) = forced;
			activationState(*object1) = forced;
			result = dispatcher->findAlgorithm(&wrap0, &wrap1, shared, BT_CONTACT_POINT_ALGORITHMS);
			activationState(*object0) = state0;
			activationState(*object1) = state1;
			kind = algorithmKind(result);
		}
	}
	if (kind != s.kind)
	{
		in.fail("pair %d: the dispatcher makes algorithm kind %d, the snapshot has %d", pairIndex, kind, s.kind);
		return false;
	}
	if (kind == kConvexConvex)
	{
		btConvexConvexAlgorithm& convex = *static_cast<btConvexConvexAlgorithm*>(result);
		if (s.ownsManifold && !convexManifold(convex))
		{
			// The manifold processCollision makes at the pair's first step.
			convexManifold(convex) = dispatcher->getNewManifold(object0, object1);
			if (!convexManifold(convex))
			{
				in.fail("pair %d: no manifold (the dispatcher's pool is full)", pairIndex);
				return false;
			}
			convexOwnsManifold(convex) = true;
		}
		if (!restoreConvexState(convex, s))
		{
			in.fail("pair %d: the snapshot has a contact cache, the dispatcher's convex algorithm has none", pairIndex);
			return false;
		}
	}
	else if (kind == kCachedBoxBox)
	{
		static_cast<caliber::CachedBoxBoxAlgorithm*>(result)->poseCache() = s.poseCache;
	}
	else if (kind == kConvexConcave)
	{
		btConvexConcaveCollisionAlgorithm& concave = *static_cast<btConvexConcaveCollisionAlgorithm*>(result);
		btConvexTriangleCallback& callback = concaveCallback(concave);
		callback.clearWrapperData();  // it kept our wrappers, which die here
		if (s.triangleKind != kNoAlgorithm)
		{
			const bool swapped = callback.m_manifoldPtr->getBody0() != object0;
			btCollisionAlgorithm* triangle = makeTriangleAlgorithm(dispatcher, callback, swapped ? wrap1 : wrap0,
			                                                       swapped ? wrap0 : wrap1, s.triangleKind);
			if (!triangle)
			{
				in.fail("pair %d: the dispatcher makes another triangle algorithm than the snapshot's", pairIndex);
				return false;
			}
			triangleAlgorithm(callback) = triangle;
			if (s.triangleKind == kConvexConvex)
			{
				btConvexConvexAlgorithm& convex = *static_cast<btConvexConvexAlgorithm*>(triangle);
				if (!restoreConvexState(convex, s))
				{
					in.fail("pair %d: the snapshot has a contact cache, the dispatcher's triangle algorithm has none",
					        pairIndex);
					return false;
				}
			}
		}
	}
	else if (kind == kCompound)
	{
		// As btCompoundCollisionAlgorithm::processCollision wraps a child: the compound's wrapper as parent,
		// the child's shape and world transform, the child index as index.
		btCompoundCollisionAlgorithm& compound = *static_cast<btCompoundCollisionAlgorithm*>(result);
		CompoundChildAlgorithms& slots = compoundChildren(compound);
		const bool swapped = compoundSwapped(compound);
		const btCollisionObjectWrapper& compoundWrap = swapped ? wrap1 : wrap0;
		const btCollisionObjectWrapper& otherWrap = swapped ? wrap0 : wrap1;
		const btCompoundShape* shape = static_cast<const btCompoundShape*>(compoundWrap.getCollisionShape());
		if (slots.size() != s.childCount || shape->getNumChildShapes() != s.childCount)
		{
			in.fail("pair %d: a compound of %d children, the snapshot's has %d", pairIndex, shape->getNumChildShapes(),
			        s.childCount);
			return false;
		}
		for (int c = 0; c < s.childCount; ++c)
		{
			const SavedChild& child = saved.children[s.firstChild + c];
			if (child.algorithm < 0) continue;
			const btTransform childWorld = compoundWrap.getWorldTransform() * shape->getChildTransform(c);
			btCollisionObjectWrapper childWrap(&compoundWrap, shape->getChildShape(c),
			                                   compoundWrap.getCollisionObject(), childWorld, -1, c);
			if (!remakeAlgorithm(dispatcher, swapped ? otherWrap : childWrap, swapped ? childWrap : otherWrap,
			                     compoundSharedManifold(compound), saved, child.algorithm, in, pairIndex, slots[c]))
				return false;
		}
	}
	else if (kind == kCompoundCompound)
	{
		// As btCompoundCompoundCollisionAlgorithm::processCollision wraps a pair of children; the pairs go
		// back into its map in the saved order (which is the order their manifolds are listed in).
		btCompoundCompoundCollisionAlgorithm& both = *static_cast<btCompoundCompoundCollisionAlgorithm*>(result);
		CompoundChildPairs& pairs = compoundPairs(both);
		const btCompoundShape* shape0 = static_cast<const btCompoundShape*>(wrap0.getCollisionShape());
		const btCompoundShape* shape1 = static_cast<const btCompoundShape*>(wrap1.getCollisionShape());
		compoundFrame(both) = s.frame;
		for (int c = 0; c < s.childCount; ++c)
		{
			const SavedChild& child = saved.children[s.firstChild + c];
			if (child.index0 >= shape0->getNumChildShapes() || child.index1 >= shape1->getNumChildShapes())
			{
				in.fail("pair %d: child pair %d, %d is not a pair of the compounds' children", pairIndex, child.index0,
				        child.index1);
				return false;
			}
			// Wrappers keep a reference to their transform: named, so that it outlives them.
			const btTransform world0 = wrap0.getWorldTransform() * shape0->getChildTransform(child.index0);
			const btTransform world1 = wrap1.getWorldTransform() * shape1->getChildTransform(child.index1);
			btCollisionObjectWrapper child0(&wrap0, shape0->getChildShape(child.index0), wrap0.getCollisionObject(),
			                                world0, -1, child.index0);
			btCollisionObjectWrapper child1(&wrap1, shape1->getChildShape(child.index1), wrap1.getCollisionObject(),
			                                world1, -1, child.index1);
			btCompoundCompoundCollisionAlgorithm::ChildPairAlgorithm entry;
			entry.m_algorithm = 0;
			entry.m_lastFrame = child.lastFrame;
			const bool made = remakeAlgorithm(dispatcher, child0, child1, compoundSharedManifold(both), saved,
			                                  child.algorithm, in, pairIndex, entry.m_algorithm);
			// Inserted even when it failed, so that the compound algorithm frees it with the others.
			if (entry.m_algorithm)
				pairs.insert(btCompoundCompoundCollisionAlgorithm::ChildPairKey(child.index0, child.index1), entry);
			if (!made) return false;
		}
	}
	return true;
}

// ---- manifolds ----------------------------------------------------------------------------------

template <class IO>
void pointFields(IO& io, btManifoldPoint& p)
{
	io.field("m_localPointA", p.m_localPointA);
	io.field("m_localPointB", p.m_localPointB);
	io.field("m_positionWorldOnB", p.m_positionWorldOnB);
	io.field("m_positionWorldOnA", p.m_positionWorldOnA);
	io.field("m_normalWorldOnB", p.m_normalWorldOnB);
	io.field("m_distance1", p.m_distance1);
	io.field("m_combinedFriction", p.m_combinedFriction);
	io.field("m_combinedRollingFriction", p.m_combinedRollingFriction);
	io.field("m_combinedSpinningFriction", p.m_combinedSpinningFriction);
	io.field("m_combinedRestitution", p.m_combinedRestitution);
	io.field("m_partId0", p.m_partId0);
	io.field("m_partId1", p.m_partId1);
	io.field("m_index0", p.m_index0);
	io.field("m_index1", p.m_index1);
	io.field("m_contactPointFlags", p.m_contactPointFlags);
	io.field("m_appliedImpulse", p.m_appliedImpulse);
	io.field("m_prevRHS", p.m_prevRHS);
	io.field("m_appliedImpulseLateral1", p.m_appliedImpulseLateral1);
	io.field("m_appliedImpulseLateral2", p.m_appliedImpulseLateral2);
	io.field("m_contactMotion1", p.m_contactMotion1);
	io.field("m_contactMotion2", p.m_contactMotion2);
	io.field("m_contactCFM", p.m_contactCFM);
	io.field("m_combinedContactStiffness1", p.m_combinedContactStiffness1);
	io.field("m_contactERP", p.m_contactERP);
	io.field("m_combinedContactDamping1", p.m_combinedContactDamping1);
	io.field("m_frictionCFM", p.m_frictionCFM);
	io.field("m_lifeTime", p.m_lifeTime);
	io.field("m_lateralFrictionDir1", p.m_lateralFrictionDir1);
	io.field("m_lateralFrictionDir2", p.m_lateralFrictionDir2);
}

template <class IO>
void manifoldFields(IO& io, btPersistentManifold& manifold)
{
	io.field("m_contactBreakingThreshold", manifoldBreakingThreshold(manifold));
	io.field("m_contactProcessingThreshold", manifoldProcessingThreshold(manifold));
	io.field("m_companionIdA", manifold.m_companionIdA);
	io.field("m_companionIdB", manifold.m_companionIdB);
}

void saveManifolds(btDiscreteDynamicsWorld& world, SnapshotWriter& out)
{
	btDispatcher* dispatcher = world.getDispatcher();
	const int count = dispatcher->getNumManifolds();
	out.context("manifolds", -1);
	out.field("manifold count", count);
	for (int m = 0; m < count; ++m)
	{
		btPersistentManifold& manifold = *dispatcher->getManifoldByIndexInternal(m);
		out.context("manifold", m);
		out.field("body 0", objectIndex(world, manifold.getBody0()));
		out.field("body 1", objectIndex(world, manifold.getBody1()));
		out.field("m_cachedPoints", manifoldPointCount(manifold));
		manifoldFields(out, manifold);
		for (int p = 0; p < manifoldPointCount(manifold); ++p)
		{
			out.context("manifold", m, p);
			pointFields(out, manifoldPoints(manifold)[p]);
		}
	}
}
}  // namespace

bool collisionStateReplaceable(btDiscreteDynamicsWorld& world, char* error, size_t errorSize)
{
	if (!dbvtOf(world) && !simpleOf(world) && !sweepOf<unsigned short>(world) && !sweepOf<unsigned int>(world))
	{
		setError(error, errorSize,
		         "broadphase: only btDbvtBroadphase, btSimpleBroadphase, btAxisSweep3 and bt32BitAxisSweep3 are "
		         "supported");
		return false;
	}
	if (!hashedCacheOf(world))
	{
		setError(error, errorSize, "pairs: only btHashedOverlappingPairCache is supported");
		return false;
	}
	// Every manifold must die with the pairs that are removed, or the saved order could not be rebuilt.
	btBroadphasePairArray& pairs = world.getPairCache()->getOverlappingPairArray();
	btManifoldArray manifolds;
	int owned = 0;
	for (int i = 0; i < pairs.size(); ++i)
	{
		pairManifolds(pairs[i], manifolds);
		owned += manifolds.size();
	}
	btAlignedObjectArray<int> ghosts;
	ghostsOf(world, ghosts);
	for (int g = 0; g < ghosts.size(); ++g)
		if (btPairCachingGhostObject* caching = cachingGhostOf(objectAt(world, ghosts[g])))
		{
			btBroadphasePairArray& ghostPairs = caching->getOverlappingPairCache()->getOverlappingPairArray();
			for (int i = 0; i < ghostPairs.size(); ++i)
			{
				pairManifolds(ghostPairs[i], manifolds);
				owned += manifolds.size();
			}
		}
	if (owned != world.getDispatcher()->getNumManifolds())
	{
		setError(error, errorSize,
		         "manifolds: the dispatcher holds manifolds no pair owns (user or predictive manifolds)");
		return false;
	}
	return true;
}

bool saveCollisionState(btDiscreteDynamicsWorld& world, SnapshotWriter& out, char* error, size_t errorSize)
{
	if (!saveBroadphase(world, out, error, errorSize)) return false;
	if (!savePairs(world, out, error, errorSize)) return false;
	saveManifolds(world, out);
	return true;
}

bool readCollisionState(btDiscreteDynamicsWorld& world, SnapshotReader& in)
{
	const int n = world.getNumCollisionObjects();
	btOverlappingPairCache* cache = hashedCacheOf(world);
	btDispatcher* dispatcher = world.getDispatcher();
	if (!cache)
	{
		in.fail("pairs: the world's pair cache is not a btHashedOverlappingPairCache");
		return false;
	}
	// In an applied restore the pairs go first: removing them frees their algorithms and manifolds, and
	// the proxies' ids (which order pairs in the cache) may only change while no pair uses them.
	if (in.applying())
	{
		btBroadphasePairArray& live = cache->getOverlappingPairArray();
		while (live.size())
		{
			btBroadphasePair& last = live[live.size() - 1];
			cache->removeOverlappingPair(last.m_pProxy0, last.m_pProxy1, dispatcher);
		}
	}
	if (!readBroadphase(world, in)) return false;

	const int cacheKind = in.value<int>("pair cache kind");
	if (in.ok() && cacheKind != kPairCacheHashed) in.fail("pairs: unknown pair cache kind %d", cacheKind);
	const int pairLimit = int(btMin<long long>(0x7fffffff, (long long)n * (n - 1) / 2));
	const int pairCount = in.count("pair count", pairLimit);
	btAlignedObjectArray<SavedPair> saved;  // the world's pairs, then each pair-caching ghost's
	SavedAlgorithms algorithms;
	btAlignedObjectArray<int> manifoldIndex;  // flat, per pair in order
	auto readPair = [&](int i)
	{
		SavedPair pair;
		pair.object0 = in.value<int>("object 0");
		pair.object1 = in.value<int>("object 1");
		if (in.ok() && (pair.object0 < 0 || pair.object0 >= n || pair.object1 < 0 || pair.object1 >= n ||
		                pair.object0 == pair.object1 || !objectAt(world, pair.object0)->getBroadphaseHandle() ||
		                !objectAt(world, pair.object1)->getBroadphaseHandle()))
			in.fail("pair %d: objects %d and %d are not two objects with proxies", i, pair.object0, pair.object1);
		pair.algorithm = in.ok() ? readAlgorithm(in, algorithms, i, 0) : -1;
		pair.manifoldCount = in.count("manifold count", 64);
		pair.firstManifold = manifoldIndex.size();
		for (int m = 0; m < pair.manifoldCount && in.ok(); ++m) manifoldIndex.push_back(in.value<int>("manifold"));
		saved.push_back(pair);
	};
	for (int i = 0; i < pairCount && in.ok(); ++i) readPair(i);

	// Ghosts, in the world's order: their overlapping objects, and a pair-caching ghost's own pairs.
	struct SavedGhost
	{
		int object;
		int firstOverlap, overlapCount;
		int firstPair, pairCount;
	};
	btAlignedObjectArray<SavedGhost> savedGhosts;
	btAlignedObjectArray<int> overlaps;
	btAlignedObjectArray<int> liveGhosts;
	ghostsOf(world, liveGhosts);
	const int ghostCount = in.value<int>("ghost count");
	if (in.ok() && ghostCount != liveGhosts.size())
		in.fail("ghosts: the world has %d ghost objects, the snapshot %d", liveGhosts.size(), ghostCount);
	for (int g = 0; g < liveGhosts.size() && in.ok(); ++g)
	{
		SavedGhost ghost;
		ghost.object = in.value<int>("object");
		const bool caching = in.flag("pair caching");
		if (in.ok() &&
		    (ghost.object != liveGhosts[g] || caching != (cachingGhostOf(objectAt(world, liveGhosts[g])) != 0)))
		{
			in.fail("ghost %d: object %d, %spair caching, is not the world's ghost %d", g, ghost.object,
			        caching ? "" : "not ", liveGhosts[g]);
			break;
		}
		ghost.overlapCount = in.count("overlapping count", n);
		ghost.firstOverlap = overlaps.size();
		for (int k = 0; k < ghost.overlapCount && in.ok(); ++k)
		{
			const int other = in.value<int>("overlapping");
			if (in.ok() && (other < 0 || other >= n || other == ghost.object))
				in.fail("ghost %d: overlapping object %d is not another object of the world", ghost.object, other);
			overlaps.push_back(other);
		}
		ghost.firstPair = saved.size();
		ghost.pairCount = caching ? in.count("pair count", pairLimit) : 0;
		for (int i = 0; i < ghost.pairCount && in.ok(); ++i) readPair(i);
		savedGhosts.push_back(ghost);
	}
	const int manifoldCount = in.count("manifold count", manifoldIndex.size());
	if (in.ok() && manifoldCount != manifoldIndex.size())
		in.fail("manifolds: %d listed by pairs, %d saved", manifoldIndex.size(), manifoldCount);
	btAlignedObjectArray<char> used;
	used.resize(manifoldCount, 0);
	for (int k = 0; k < manifoldIndex.size() && in.ok(); ++k)
	{
		const int index = manifoldIndex[k];
		if (index < 0 || index >= manifoldCount || used[index])
			in.fail("manifolds: index %d is out of range or owned twice", index);
		else
			used[index] = 1;
	}
	if (!in.ok()) return false;

	// The pairs, their algorithms, and the dispatcher's manifold array in the saved order.
	btAlignedObjectArray<btPersistentManifold*> order;
	order.resize(manifoldCount, 0);
	if (in.applying())
	{
		btManifoldArray manifolds;
		// Adds saved pair i back into cache at slot and remakes its algorithm.
		auto restorePair = [&](int i, btOverlappingPairCache* target, int slot)
		{
			btBroadphasePairArray& live = target->getOverlappingPairArray();
			btBroadphaseProxy* proxy0 = objectAt(world, saved[i].object0)->getBroadphaseHandle();
			btBroadphaseProxy* proxy1 = objectAt(world, saved[i].object1)->getBroadphaseHandle();
			btBroadphasePair* pair = target->addOverlappingPair(proxy0, proxy1);
			if (!pair || pair != &live[slot] || pair->m_pProxy0 != proxy0)
			{
				in.fail("pair %d: the pair cache does not take it back in place (filter or ids changed)", i);
				return false;
			}
			if (saved[i].algorithm < 0) return true;
			btCollisionObject* object0 = objectAt(world, saved[i].object0);
			btCollisionObject* object1 = objectAt(world, saved[i].object1);
			// As the dispatcher's near callback wraps the pair.
			btCollisionObjectWrapper wrap0(0, object0->getCollisionShape(), object0, object0->getWorldTransform(), -1,
			                               -1);
			btCollisionObjectWrapper wrap1(0, object1->getCollisionShape(), object1, object1->getWorldTransform(), -1,
			                               -1);
			if (!remakeAlgorithm(dispatcher, wrap0, wrap1, 0, algorithms, saved[i].algorithm, in, i, pair->m_algorithm))
				return false;
			pairManifolds(*pair, manifolds);
			if (manifolds.size() != saved[i].manifoldCount)
			{
				in.fail("pair %d: its algorithm has %d manifolds, the snapshot %d", i, manifolds.size(),
				        saved[i].manifoldCount);
				return false;
			}
			for (int m = 0; m < manifolds.size(); ++m) order[manifoldIndex[saved[i].firstManifold + m]] = manifolds[m];
			return true;
		};
		// The world's pairs (the ghost pair callback, if any, tells the ghosts as they come back) ...
		for (int i = 0; i < pairCount; ++i)
			if (!restorePair(i, cache, i)) return false;
		// ... then each ghost's list and own pairs as saved (those the callback made go first).
		for (int g = 0; g < savedGhosts.size(); ++g)
		{
			const SavedGhost& ghost = savedGhosts[g];
			btCollisionObject* object = objectAt(world, ghost.object);
			btAlignedObjectArray<btCollisionObject*>& list = btGhostObject::upcast(object)->getOverlappingPairs();
			list.resize(0);
			for (int k = 0; k < ghost.overlapCount; ++k)
				list.push_back(objectAt(world, overlaps[ghost.firstOverlap + k]));
			btPairCachingGhostObject* caching = cachingGhostOf(object);
			if (!caching) continue;
			btHashedOverlappingPairCache* own = caching->getOverlappingPairCache();
			btBroadphasePairArray& ownPairs = own->getOverlappingPairArray();
			while (ownPairs.size())
			{
				btBroadphasePair& last = ownPairs[ownPairs.size() - 1];
				own->removeOverlappingPair(last.m_pProxy0, last.m_pProxy1, dispatcher);
			}
			for (int k = 0; k < ghost.pairCount; ++k)
				if (!restorePair(ghost.firstPair + k, own, k)) return false;
		}
		if (dispatcher->getNumManifolds() != manifoldCount)
		{
			in.fail("manifolds: the dispatcher has %d, the snapshot %d", dispatcher->getNumManifolds(), manifoldCount);
			return false;
		}
		btPersistentManifold** array = dispatcher->getInternalManifoldPointer();
		for (int m = 0; m < manifoldCount; ++m)
		{
			array[m] = order[m];
			order[m]->m_index1a = m;
		}
	}

	// The manifolds' contents (a dry run reads them into a scratch manifold).
	btPersistentManifold scratch;
	for (int m = 0; m < manifoldCount && in.ok(); ++m)
	{
		btPersistentManifold& manifold = in.applying() ? *order[m] : scratch;
		const int body0 = in.value<int>("body 0");
		const int body1 = in.value<int>("body 1");
		if (in.ok() && (body0 < 0 || body0 >= n || body1 < 0 || body1 >= n))
			in.fail("manifold %d: bodies %d, %d are not objects of the world", m, body0, body1);
		if (in.ok() && in.applying() &&
		    (manifold.getBody0() != objectAt(world, body0) || manifold.getBody1() != objectAt(world, body1)))
			in.fail("manifold %d: made between other bodies than the snapshot's", m);
		const int points = in.count("m_cachedPoints", MANIFOLD_CACHE_SIZE);
		manifoldFields(in, manifold);
		if (in.applying())
		{
			manifold.clearManifold();
			manifoldPointCount(manifold) = points;
		}
		for (int p = 0; p < points && in.ok(); ++p)
		{
			btManifoldPoint& point = manifoldPoints(manifold)[p];
			if (in.applying()) point = btManifoldPoint();  // no user data: it is not held
			pointFields(in, point);
		}
	}
	return in.ok();
}
}  // namespace snapshot
}  // namespace caliber
