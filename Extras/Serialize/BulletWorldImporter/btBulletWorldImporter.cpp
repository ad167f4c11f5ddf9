// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// Loading .bullet files: the file is parsed (BulletFileLoader), every converted struct is checked
// against the chunk it came from (pointer targets of the right struct, counts within the arrays,
// indices within the vertices, finite numbers), and only then turned into objects by
// btWorldImporter. docs/serialization.md, "Bad input".
#include "btBulletWorldImporter.h"

#include "../BulletFileLoader/btBulletFile.h"
#include "btBulletDynamicsCommon.h"
#include "BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h"
#include "BulletDynamics/ConstraintSolver/btGearConstraint.h"
#include "BulletDynamics/ConstraintSolver/btGeneric6DofSpring2Constraint.h"
#include "LinearMath/btSerializer.h"
#include "LinearMath/btWarningHook.h"
#include "detail/DnaChecks.h"
#include "detail/RestoreExistingObjects.h"

#include <math.h>
#include <string.h>

#include <string>
#include <type_traits>

namespace
{
using caliber::importer::finite;
using caliber::importer::finiteTransform;
using caliber::importer::memoryDna;

class Checker
{
public:
	explicit Checker(bParse::btBulletFile& file) : m_file(file), m_blocks(caliber::importer::blockInfo(file))
	{
		for (int i = 0; i < file.m_collisionShapes.size(); ++i)
			m_shapes.insert(btHashPtr(file.m_collisionShapes[i]), 1);
		for (int i = 0; i < file.m_rigidBodies.size(); ++i) m_bodies.insert(btHashPtr(file.m_rigidBodies[i]), 1);
	}

	// The struct name of the block at p (0 when p is no block start).
	const char* structOf(const void* p) const
	{
		const bParse::bChunkInd* info = p ? m_blocks.find(btHashPtr(p)) : 0;
		if (!info || info->dna_nr < 0) return 0;
		return m_file.getFileDNA() ? memoryType(info->dna_nr) : 0;
	}
	// Elements in the block at p.
	int countOf(const void* p) const
	{
		const bParse::bChunkInd* info = p ? m_blocks.find(btHashPtr(p)) : 0;
		return info ? info->nr : 0;
	}
	bool isA(const void* p, const char* type, long long count = 1) const
	{
		const char* s = structOf(p);
		return s && strcmp(s, type) == 0 && count >= 0 && countOf(p) >= count;
	}
	// A name pointer must point at a plain (terminated) block; anything else is dropped.
	void fixName(char*& name) const
	{
		if (!name) return;
		const bParse::bChunkInd* info = m_blocks.find(btHashPtr(name));
		if (!info || info->dna_nr >= 0) name = 0;
	}
	// A plain (struct-less) block holding at least count ints, such as a triangle info map's keys.
	bool holdsInts(const void* p, long long count) const
	{
		const bParse::bChunkInd* info = p ? m_blocks.find(btHashPtr(p)) : 0;
		return info && info->dna_nr < 0 && count >= 0 && info->len >= 4 * count;
	}

	// A stored BVH whose arrays are blocks of the right structs holding at least their counts (the tree
	// itself is checked by deSerializeFloat / Double).
	template <class BvhData>
	bool bvhComplete(const BvhData* b, const char* nodeStruct) const
	{
		const int nc = b->m_numContiguousLeafNodes, nq = b->m_numQuantizedContiguousNodes, nh = b->m_numSubtreeHeaders;
		if (nc < 0 || nq < 0 || nh < 0) return false;
		return (nc == 0 || isA(b->m_contiguousNodesPtr, nodeStruct, nc)) &&
		       (nq == 0 || isA(b->m_quantizedContiguousNodesPtr, "btQuantizedBvhNodeData", nq)) &&
		       (nh == 0 || isA(b->m_subTreeInfoPtr, "btBvhSubtreeInfoData", nh));
	}
	bool bvhBlockComplete(void* p) const
	{
		if (isA(p, "btQuantizedBvhFloatData"))
			return bvhComplete(static_cast<btQuantizedBvhFloatData*>(p), "btOptimizedBvhNodeFloatData");
		if (isA(p, "btQuantizedBvhDoubleData"))
			return bvhComplete(static_cast<btQuantizedBvhDoubleData*>(p), "btOptimizedBvhNodeDoubleData");
		return false;
	}
	bool triangleInfoMapComplete(void* p) const
	{
		if (!isA(p, "btTriangleInfoMapData")) return false;
		const btTriangleInfoMapData* d = static_cast<btTriangleInfoMapData*>(p);
		return d->m_numKeys >= 0 && d->m_numValues == d->m_numKeys &&
		       (d->m_numKeys == 0 || (holdsInts(d->m_keyArrayPtr, d->m_numKeys) &&
		                              isA(d->m_valueArrayPtr, "btTriangleInfoData", d->m_numValues)));
	}

	bool isShape(const void* p) const { return p && m_shapes.find(btHashPtr(p)); }
	bool isBody(const void* p) const { return p && m_bodies.find(btHashPtr(p)); }

	// Valid shapes may be converted; the answer is remembered (compound children are asked again).
	bool shapeIsValid(btCollisionShapeData* shape, int depth = 0)
	{
		if (!isShape(shape)) return false;
		int* known = m_verdicts.find(btHashPtr(shape));
		if (known) return *known == 1;
		m_verdicts.insert(btHashPtr(shape), 2);  // a compound reaching itself is invalid
		const bool valid = depth <= 64 && checkShape(shape, depth);
		m_verdicts.insert(btHashPtr(shape), valid ? 1 : 2);
		return valid;
	}

private:
	// Every shape struct starts with btCollisionShapeData: only blocks of these are read as shapes.
	static bool isShapeStruct(const char* type)
	{
		static const char* const names[] = {
		    "btCollisionShapeData",          "btConvexInternalShapeData", "btCapsuleShapeData",
		    "btCylinderShapeData",           "btConeShapeData",           "btStaticPlaneShapeData",
		    "btMultiSphereShapeData",        "btConvexHullShapeData",     "btTriangleMeshShapeData",
		    "btScaledTriangleMeshShapeData", "btCompoundShapeData"};
		for (const char* n : names)
			if (!strcmp(n, type)) return true;
		return false;
	}

	bool checkShape(btCollisionShapeData* shape, int depth)
	{
		const char* type = structOf(shape);
		if (!type || !isShapeStruct(type)) return false;
		fixName(shape->m_name);
		switch (shape->m_shapeType)
		{
			case BOX_SHAPE_PROXYTYPE:
			case SPHERE_SHAPE_PROXYTYPE:
				return !strcmp(type, "btConvexInternalShapeData") && convexFinite(shape) && primitiveSized(shape);
			case CAPSULE_SHAPE_PROXYTYPE:
				return !strcmp(type, "btCapsuleShapeData") && convexFinite(shape) && primitiveSized(shape);
			case CYLINDER_SHAPE_PROXYTYPE:
				return !strcmp(type, "btCylinderShapeData") && convexFinite(shape) && primitiveSized(shape);
			case CONE_SHAPE_PROXYTYPE:
				return !strcmp(type, "btConeShapeData") && convexFinite(shape) && primitiveSized(shape);
			case STATIC_PLANE_PROXYTYPE:
			{
				if (strcmp(type, "btStaticPlaneShapeData")) return false;
				const btStaticPlaneShapeData* d = reinterpret_cast<btStaticPlaneShapeData*>(shape);
				return finite(d->m_planeNormal) && finite(d->m_localScaling) && isfinite(d->m_planeConstant);
			}
			case MULTI_SPHERE_SHAPE_PROXYTYPE:
			{
				if (strcmp(type, "btMultiSphereShapeData") || !convexFinite(shape)) return false;
				btMultiSphereShapeData* d = reinterpret_cast<btMultiSphereShapeData*>(shape);
				if (d->m_localPositionArraySize <= 0 ||
				    !isA(d->m_localPositionArrayPtr, "btPositionAndRadius", d->m_localPositionArraySize))
					return false;
				for (int i = 0; i < d->m_localPositionArraySize; ++i)
					if (!finite(d->m_localPositionArrayPtr[i].m_pos) ||
					    !isfinite(d->m_localPositionArrayPtr[i].m_radius))
						return false;
				return true;
			}
			case CONVEX_HULL_SHAPE_PROXYTYPE:
			{
				if (strcmp(type, "btConvexHullShapeData") || !convexFinite(shape)) return false;
				btConvexHullShapeData* d = reinterpret_cast<btConvexHullShapeData*>(shape);
				const int n = d->m_numUnscaledPoints;
				if (n <= 0) return false;
				if (d->m_unscaledPointsFloatPtr)
				{
					if (!isA(d->m_unscaledPointsFloatPtr, "btVector3FloatData", n)) return false;
					for (int i = 0; i < n; ++i)
						if (!finite(d->m_unscaledPointsFloatPtr[i])) return false;
					return true;
				}
				if (!isA(d->m_unscaledPointsDoublePtr, "btVector3DoubleData", n)) return false;
				for (int i = 0; i < n; ++i)
					if (!finite(d->m_unscaledPointsDoublePtr[i])) return false;
				return true;
			}
			case TRIANGLE_MESH_SHAPE_PROXYTYPE:
				return !strcmp(type, "btTriangleMeshShapeData") &&
				       checkMesh(*reinterpret_cast<btTriangleMeshShapeData*>(shape));
			case SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE:
			{
				if (strcmp(type, "btScaledTriangleMeshShapeData")) return false;
				btScaledTriangleMeshShapeData* d = reinterpret_cast<btScaledTriangleMeshShapeData*>(shape);
				return finite(d->m_localScaling) && checkMesh(d->m_trimeshShapeData);
			}
			case COMPOUND_SHAPE_PROXYTYPE:
			{
				if (strcmp(type, "btCompoundShapeData") || depth > 64) return false;
				btCompoundShapeData* d = reinterpret_cast<btCompoundShapeData*>(shape);
				if (d->m_numChildShapes < 0) return false;
				if (d->m_numChildShapes == 0) return true;
				if (!isA(d->m_childShapePtr, "btCompoundShapeChildData", d->m_numChildShapes)) return false;
				for (int i = 0; i < d->m_numChildShapes; ++i)
				{
					btCompoundShapeChildData& c = d->m_childShapePtr[i];
					if (!finiteTransform(c.m_transform)) return false;
					// A child must itself be a valid shape of the file (which excludes cycles).
					if (!shapeIsValid(c.m_childShape, depth + 1)) return false;
				}
				return true;
			}
			default:
				return true;  // unknown kinds are reported and skipped by the converter
		}
	}

public:
	// No number of the block is NaN, and every number inside a transform, pivot or axis is finite
	// (other fields may be infinite: a joint's breaking threshold is by default).
	bool numbersSane(const void* block) const
	{
		const bParse::bChunkInd* info = block ? m_blocks.find(btHashPtr(block)) : 0;
		if (!info || info->dna_nr < 0) return false;
		return caliber::importer::numbersSane(info->dna_nr, static_cast<const char*>(block), false);
	}

private:
	btHashMap<btHashPtr, int> m_verdicts;
	const char* memoryType(int memoryStruct) const
	{
		short* s = memoryDna().getStruct(memoryStruct);
		return s ? memoryDna().getType(s[0]) : 0;
	}

	bool convexFinite(btCollisionShapeData* shape) const
	{
		const btConvexInternalShapeData* d = reinterpret_cast<btConvexInternalShapeData*>(shape);
		if (!finite(d->m_implicitShapeDimensions) || !finite(d->m_localScaling) || !isfinite(d->m_collisionMargin))
			return false;
		// Scaling divides the stored dimensions: zero scaling cannot be undone, and shapes keep it positive
		// (Bullet's and Caliber's setLocalScaling store its absolute value), as they keep margins.
		for (int i = 0; i < 3; ++i)
			if (!(d->m_localScaling.m_floats[i] > 0)) return false;
		return d->m_collisionMargin >= 0;
	}

	// A box, sphere, capsule, cylinder or cone: the stored dimensions are sizes, never negative.
	bool primitiveSized(btCollisionShapeData* shape) const
	{
		const btConvexInternalShapeData* d = reinterpret_cast<btConvexInternalShapeData*>(shape);
		for (int i = 0; i < 3; ++i)
			if (!(d->m_implicitShapeDimensions.m_floats[i] >= 0)) return false;
		return true;
	}

	// Every leaf of the stored tree names a triangle of the mesh (the mesh query reads that triangle).
	template <class BvhData>
	static bool leavesFit(const BvhData* b, const btStridingMeshInterfaceData& m)
	{
		const int used = b->m_useQuantization ? b->m_numQuantizedContiguousNodes : b->m_numContiguousLeafNodes;
		if (b->m_curNodeIndex < 0 || b->m_curNodeIndex > used) return false;
		for (int i = 0; i < b->m_curNodeIndex; ++i)
		{
			int part, triangle;
			if (b->m_useQuantization)
			{
				const int v = b->m_quantizedContiguousNodesPtr[i].m_escapeIndexOrTriangleIndex;
				if (v < 0) continue;
				part = v >> (31 - MAX_NUM_PARTS_IN_BITS);
				triangle = v & ((1 << (31 - MAX_NUM_PARTS_IN_BITS)) - 1);
			}
			else
			{
				if (b->m_contiguousNodesPtr[i].m_escapeIndex >= 0) continue;
				part = b->m_contiguousNodesPtr[i].m_subPart;
				triangle = b->m_contiguousNodesPtr[i].m_triangleIndex;
			}
			if (part < 0 || part >= m.m_numMeshParts || triangle < 0 ||
			    triangle >= m.m_meshPartsPtr[part].m_numTriangles)
				return false;
		}
		return true;
	}

	// A stored tree or map that does not fit is dropped (the mesh then builds its own tree).
	void checkMeshExtras(btTriangleMeshShapeData& mesh) const
	{
		const btStridingMeshInterfaceData& m = mesh.m_meshInterface;
		if (mesh.m_quantizedFloatBvh && !(isA(mesh.m_quantizedFloatBvh, "btQuantizedBvhFloatData") &&
		                                  bvhComplete(mesh.m_quantizedFloatBvh, "btOptimizedBvhNodeFloatData") &&
		                                  leavesFit(mesh.m_quantizedFloatBvh, m)))
		{
			btReportWarning(
			    "Caliber: btBulletWorldImporter: a mesh's stored BVH does not fit the mesh; it is rebuilt\n");
			mesh.m_quantizedFloatBvh = 0;
		}
		if (mesh.m_quantizedDoubleBvh && !(isA(mesh.m_quantizedDoubleBvh, "btQuantizedBvhDoubleData") &&
		                                   bvhComplete(mesh.m_quantizedDoubleBvh, "btOptimizedBvhNodeDoubleData") &&
		                                   leavesFit(mesh.m_quantizedDoubleBvh, m)))
		{
			btReportWarning(
			    "Caliber: btBulletWorldImporter: a mesh's stored BVH does not fit the mesh; it is rebuilt\n");
			mesh.m_quantizedDoubleBvh = 0;
		}
		if (mesh.m_triangleInfoMap && !triangleInfoMapComplete(mesh.m_triangleInfoMap))
		{
			btReportWarning("Caliber: btBulletWorldImporter: a mesh's triangle info map is malformed; it is dropped\n");
			mesh.m_triangleInfoMap = 0;
		}
	}

	bool checkMesh(btTriangleMeshShapeData& mesh)
	{
		btStridingMeshInterfaceData& m = mesh.m_meshInterface;
		if (!finite(m.m_scaling) || m.m_numMeshParts <= 0 || !isA(m.m_meshPartsPtr, "btMeshPartData", m.m_numMeshParts))
			return false;
		for (int p = 0; p < m.m_numMeshParts; ++p)
		{
			btMeshPartData& part = m.m_meshPartsPtr[p];
			const int nv = part.m_numVertices, nt = part.m_numTriangles;
			if (nv <= 0 || nt <= 0) return false;
			if (part.m_vertices3f)
			{
				if (!isA(part.m_vertices3f, "btVector3FloatData", nv)) return false;
				for (int v = 0; v < nv; ++v)
					if (!finite(part.m_vertices3f[v])) return false;
			}
			else
			{
				if (!isA(part.m_vertices3d, "btVector3DoubleData", nv)) return false;
				for (int v = 0; v < nv; ++v)
					if (!finite(part.m_vertices3d[v])) return false;
			}
			long long triangles = nt;
			if (part.m_indices32)
			{
				if (!isA(part.m_indices32, "btIntIndexData", 3 * triangles)) return false;
				for (long long i = 0; i < 3 * triangles; ++i)
					if (part.m_indices32[i].m_value < 0 || part.m_indices32[i].m_value >= nv) return false;
			}
			else if (part.m_3indices16)
			{
				if (!isA(part.m_3indices16, "btShortIntIndexTripletData", triangles)) return false;
				for (long long t = 0; t < triangles; ++t)
					for (int k = 0; k < 3; ++k)
						if (static_cast<unsigned short>(part.m_3indices16[t].m_values[k]) >= nv) return false;
			}
			else if (part.m_3indices8)
			{
				if (!isA(part.m_3indices8, "btCharIndexTripletData", triangles)) return false;
				for (long long t = 0; t < triangles; ++t)
					for (int k = 0; k < 3; ++k)
						if (static_cast<unsigned char>(part.m_3indices8[t].m_values[k]) >= nv) return false;
			}
			else if (part.m_indices16)
			{
				if (!isA(part.m_indices16, "btShortIntIndexData", 3 * triangles)) return false;
				for (long long i = 0; i < 3 * triangles; ++i)
					if (static_cast<unsigned short>(part.m_indices16[i].m_value) >= nv) return false;
			}
			else
				return false;
		}
		checkMeshExtras(mesh);
		return true;
	}

	bParse::btBulletFile& m_file;
	const btHashMap<btHashPtr, bParse::bChunkInd>& m_blocks;
	btHashMap<btHashPtr, int> m_shapes;
	btHashMap<btHashPtr, int> m_bodies;
};

void readTransform(btTransform& t, const btTransformFloatData& d) { t.deSerializeFloat(d); }
void readTransform(btTransform& t, const btTransformDoubleData& d) { t.deSerializeDouble(d); }

void warn(const std::string& message)
{
	btReportWarning(("Caliber: btBulletWorldImporter: " + message + "\n").c_str());
}

template <class ObjectData>
bool objectFinite(const ObjectData& d)
{
	return finiteTransform(d.m_worldTransform) && finiteTransform(d.m_interpolationWorldTransform) &&
	       finite(d.m_interpolationLinearVelocity) && finite(d.m_interpolationAngularVelocity) &&
	       finite(d.m_anisotropicFriction);
}

// Factors scale the solver's response: btRigidBody accepts none below zero.
template <class V>
bool nonNegative(const V& v)
{
	return v.m_floats[0] >= 0 && v.m_floats[1] >= 0 && v.m_floats[2] >= 0;
}

template <class BodyData>
bool bodyFinite(const BodyData& d)
{
	return objectFinite(d.m_collisionObjectData) && finite(d.m_linearVelocity) && finite(d.m_angularVelocity) &&
	       finite(d.m_gravity_acceleration) && finite(d.m_invInertiaLocal) && finite(d.m_linearFactor) &&
	       finite(d.m_angularFactor) && nonNegative(d.m_linearFactor) && nonNegative(d.m_angularFactor) &&
	       nonNegative(d.m_invInertiaLocal) && isfinite(d.m_inverseMass) && d.m_inverseMass >= 0;
}

// The number of leaves among the tree nodes a stored BVH lists.
template <class BvhData>
int storedLeafCount(const BvhData& d)
{
	const int used = d.m_useQuantization ? d.m_numQuantizedContiguousNodes : d.m_numContiguousLeafNodes;
	if (d.m_curNodeIndex < 0 || d.m_curNodeIndex > used) return -1;
	int leaves = 0;
	for (int i = 0; i < d.m_curNodeIndex; ++i)
		leaves += d.m_useQuantization ? d.m_quantizedContiguousNodesPtr[i].m_escapeIndexOrTriangleIndex >= 0
		                              : d.m_contiguousNodesPtr[i].m_escapeIndex < 0;
	return leaves;
}

// The number of leaves a query with an all-covering box reaches.
int reachableLeaves(const btQuantizedBvh& bvh)
{
	struct Count : btNodeOverlapCallback
	{
		int leaves = 0;
		void processNode(int, int) override { ++leaves; }
	} count;
	const btVector3 huge(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
	bvh.reportAabbOverlappingNodex(&count, -huge, huge);
	return count.leaves;
}

// The struct each joint kind has in float and in double files (and the older double layouts).
bool jointStructMatches(int objectType, const char* type)
{
	struct Entry
	{
		int kind;
		const char* names[3];
	};
	static const Entry table[] = {
	    {POINT2POINT_CONSTRAINT_TYPE,
	     {"btPoint2PointConstraintFloatData", "btPoint2PointConstraintDoubleData2",
	      "btPoint2PointConstraintDoubleData"}},
	    {HINGE_CONSTRAINT_TYPE,
	     {"btHingeConstraintFloatData", "btHingeConstraintDoubleData2", "btHingeConstraintDoubleData"}},
	    {CONETWIST_CONSTRAINT_TYPE, {"btConeTwistConstraintData", "btConeTwistConstraintDoubleData", 0}},
	    {D6_CONSTRAINT_TYPE, {"btGeneric6DofConstraintData", "btGeneric6DofConstraintDoubleData2", 0}},
	    {D6_SPRING_CONSTRAINT_TYPE,
	     {"btGeneric6DofSpringConstraintData", "btGeneric6DofSpringConstraintDoubleData2", 0}},
	    {D6_SPRING_2_CONSTRAINT_TYPE,
	     {"btGeneric6DofSpring2ConstraintData", "btGeneric6DofSpring2ConstraintDoubleData2", 0}},
	    {FIXED_CONSTRAINT_TYPE, {"btGeneric6DofSpring2ConstraintData", "btGeneric6DofSpring2ConstraintDoubleData2", 0}},
	    {SLIDER_CONSTRAINT_TYPE, {"btSliderConstraintData", "btSliderConstraintDoubleData", 0}},
	    {GEAR_CONSTRAINT_TYPE, {"btGearConstraintFloatData", "btGearConstraintDoubleData", 0}},
	};
	for (const Entry& e : table)
		if (e.kind == objectType)
			for (const char* name : e.names)
				if (name && !strcmp(name, type)) return true;
	return false;
}

bool isJointStruct(const char* type)
{
	for (int kind = POINT2POINT_CONSTRAINT_TYPE; kind < MAX_CONSTRAINT_TYPE; ++kind)
		if (jointStructMatches(kind, type)) return true;
	return false;
}

bool isDoubleJoint(const char* type)
{
	return !strcmp(type, "btPoint2PointConstraintDoubleData2") || !strcmp(type, "btHingeConstraintDoubleData2") ||
	       !strcmp(type, "btConeTwistConstraintDoubleData") || !strcmp(type, "btGeneric6DofConstraintDoubleData2") ||
	       !strcmp(type, "btGeneric6DofSpringConstraintDoubleData2") ||
	       !strcmp(type, "btGeneric6DofSpring2ConstraintDoubleData2") ||
	       !strcmp(type, "btSliderConstraintDoubleData") || !strcmp(type, "btGearConstraintDoubleData");
}
}  // namespace

btBulletWorldImporter::btBulletWorldImporter(btDynamicsWorld* world) : btWorldImporter(world) {}

btBulletWorldImporter::~btBulletWorldImporter() {}

bool btBulletWorldImporter::loadFile(const char* fileName, const char* preSwapFilenameOut)
{
	bParse::btBulletFile file(fileName);
	if (!file.ok()) return false;
	file.parse(m_verboseMode);
	if (preSwapFilenameOut && file.ok()) file.write(preSwapFilenameOut);
	return loadFileFromMemory(&file);
}

bool btBulletWorldImporter::loadFileFromMemory(char* memoryBuffer, int len)
{
	if (!memoryBuffer || len <= 0)
	{
		warn("no buffer, or an empty one, was given; nothing was loaded");
		return false;
	}
	bParse::btBulletFile file(memoryBuffer, len);
	if (!file.ok()) return false;
	file.parse(m_verboseMode);
	return loadFileFromMemory(&file);
}

bool btBulletWorldImporter::loadFileFromMemory(bParse::btBulletFile* file)
{
	if (!file || !file->ok())
	{
		warn("the file is not a valid .bullet file; nothing was loaded");
		return false;
	}
	return convertAllObjects(file);
}

bool btBulletWorldImporter::convertAllObjects(bParse::btBulletFile* file)
{
	if (!file || !file->ok()) return false;
	// These maps are keyed by the converted blocks of one file: blocks of an earlier file are gone (and
	// their addresses may come back), so each load starts them empty.
	m_shapeMap.clear();
	m_bodyMap.clear();
	m_bvhMap.clear();
	m_timMap.clear();
	const bool restoring = (m_importerFlags & eRESTORE_EXISTING_OBJECTS) != 0;
	if (restoring && !m_dynamicsWorld)
	{
		warn("eRESTORE_EXISTING_OBJECTS needs the importer's world, and it was given none; nothing was loaded");
		return false;
	}
	caliber::importer::ExistingObjects existing(restoring ? m_dynamicsWorld : 0, m_objectNameMap);
	bool allRestored = true;
	Checker check(*file);
	// 1. World settings (the first record).
	if (file->m_dynamicsWorldInfo.size() > 0)
	{
		// Start from the world's settings: a field the file lacks (older writers) keeps its value.
		btContactSolverInfo solverInfo = m_dynamicsWorld ? m_dynamicsWorld->getSolverInfo() : btContactSolverInfo();
		btVector3 gravity = m_dynamicsWorld ? m_dynamicsWorld->getGravity() : btVector3(0, -10, 0);
		bParse::bDNA* fileDna = file->getFileDNA();
		auto read = [&](const auto& d, const char* worldStruct, const char* infoStruct)
		{
			auto has = [&](const char* structName, const char* field)
			{
				short* st = fileDna ? fileDna->getStruct(fileDna->getReverseType(structName)) : 0;
				for (int f = 0; st && f < st[1]; ++f)
				{
					const char* name = fileDna->getName(st[3 + 2 * f]);
					if (name && !strncmp(name, field, strlen(field)) &&
					    (name[strlen(field)] == 0 || name[strlen(field)] == '['))
						return true;
				}
				return false;
			};
			if (has(worldStruct, "m_gravity"))
				gravity = btVector3(btScalar(d.m_gravity.m_floats[0]), btScalar(d.m_gravity.m_floats[1]),
				                    btScalar(d.m_gravity.m_floats[2]));
			if (!has(worldStruct, "m_solverInfo")) return;
			const auto& i = d.m_solverInfo;
			// Each setting is taken when the file has it and it is a non-negative number.
#define CALIBER_TAKE(field) \
	if (has(infoStruct, #field) && i.field >= 0 && isfinite(double(i.field))) solverInfo.field = btScalar(i.field);
			CALIBER_TAKE(m_tau)
			CALIBER_TAKE(m_damping)
			CALIBER_TAKE(m_friction)
			CALIBER_TAKE(m_timeStep)
			CALIBER_TAKE(m_restitution)
			CALIBER_TAKE(m_maxErrorReduction)
			CALIBER_TAKE(m_sor)
			CALIBER_TAKE(m_erp)
			CALIBER_TAKE(m_erp2)
			CALIBER_TAKE(m_globalCfm)
			CALIBER_TAKE(m_splitImpulsePenetrationThreshold)
			CALIBER_TAKE(m_splitImpulseTurnErp)
			CALIBER_TAKE(m_linearSlop)
			CALIBER_TAKE(m_warmstartingFactor)
			CALIBER_TAKE(m_maxGyroscopicForce)
			CALIBER_TAKE(m_singleAxisRollingFrictionThreshold)
#undef CALIBER_TAKE
			if (has(infoStruct, "m_numIterations") && i.m_numIterations >= 1 && i.m_numIterations <= 100000)
				solverInfo.m_numIterations = i.m_numIterations;
			if (has(infoStruct, "m_solverMode")) solverInfo.m_solverMode = i.m_solverMode;
			if (has(infoStruct, "m_restingContactRestitutionThreshold"))
				solverInfo.m_restingContactRestitutionThreshold = i.m_restingContactRestitutionThreshold;
			if (has(infoStruct, "m_minimumSolverBatchSize") && i.m_minimumSolverBatchSize >= 0)
				solverInfo.m_minimumSolverBatchSize = i.m_minimumSolverBatchSize;
			if (has(infoStruct, "m_splitImpulse")) solverInfo.m_splitImpulse = i.m_splitImpulse != 0;
		};
		void* info = file->m_dynamicsWorldInfo[0];
		bool known = true;
		if (check.isA(info, "btDynamicsWorldFloatData"))
			read(*static_cast<btDynamicsWorldFloatData*>(info), "btDynamicsWorldFloatData",
			     "btContactSolverInfoFloatData");
		else if (check.isA(info, "btDynamicsWorldDoubleData"))
			read(*static_cast<btDynamicsWorldDoubleData*>(info), "btDynamicsWorldDoubleData",
			     "btContactSolverInfoDoubleData");
		else
			known = false;
		if (known && isfinite(gravity.x()) && isfinite(gravity.y()) && isfinite(gravity.z()))
			setDynamicsWorldInfo(gravity, solverInfo);
		else
			warn("the world settings are malformed; the world's own are kept");
	}
	// 1b. Stored BVHs and triangle info maps, shared by the meshes that point at them (a tree is kept only
	// when deSerialize accepted it: a full-box query then finds every leaf the file lists).
	for (int i = 0; i < file->m_bvhs.size() && !restoring; ++i)
	{
		void* block = file->m_bvhs[i];
		if (!check.bvhBlockComplete(block))
		{
			warn("BVH " + std::to_string(i) + " is malformed; meshes using it rebuild their own");
			continue;
		}
		btOptimizedBvh* bvh = createOptimizedBvh();
		int leaves = 0;
		if (check.isA(block, "btQuantizedBvhFloatData"))
		{
			btQuantizedBvhFloatData* d = static_cast<btQuantizedBvhFloatData*>(block);
			bvh->deSerializeFloat(*d);
			leaves = storedLeafCount(*d);
		}
		else
		{
			btQuantizedBvhDoubleData* d = static_cast<btQuantizedBvhDoubleData*>(block);
			bvh->deSerializeDouble(*d);
			leaves = storedLeafCount(*d);
		}
		if (reachableLeaves(*bvh) == leaves)
			m_bvhMap.insert(btHashPtr(block), bvh);
		else
			warn("BVH " + std::to_string(i) + " is not a well-formed tree; meshes using it rebuild their own");
	}
	const bool swapped = (file->getFlags() & bParse::FD_ENDIAN_SWAP) != 0;
	for (int i = 0; i < file->m_triangleInfoMaps.size() && !restoring; ++i)
	{
		void* block = file->m_triangleInfoMaps[i];
		if (!check.triangleInfoMapComplete(block))
		{
			warn("triangle info map " + std::to_string(i) + " is malformed; it is skipped");
			continue;
		}
		btTriangleInfoMapData* d = static_cast<btTriangleInfoMapData*>(block);
		// The keys are a plain int array: the converter leaves them in the writer's byte order.
		if (swapped)
			for (int k = 0; k < d->m_numKeys; ++k)
			{
				unsigned char* b = reinterpret_cast<unsigned char*>(&d->m_keyArrayPtr[k]);
				btSwap(b[0], b[3]);
				btSwap(b[1], b[2]);
			}
		btTriangleInfoMap* map = createTriangleInfoMap();
		map->deSerialize(*d);
		if (map->size() == d->m_numKeys) m_timMap.insert(btHashPtr(block), map);
	}
	// 2. Shapes (compound children convert on demand through the shape map).
	for (int i = 0; i < file->m_collisionShapes.size() && !restoring; ++i)
	{
		btCollisionShapeData* shapeData = reinterpret_cast<btCollisionShapeData*>(file->m_collisionShapes[i]);
		if (!check.shapeIsValid(shapeData))
		{
			warn("shape " + std::to_string(i) + " has inconsistent data; it is skipped");
			continue;
		}
		if (m_shapeMap.find(btHashPtr(shapeData))) continue;
		btCollisionShape* shape = convertCollisionShape(shapeData);
		if (shape) m_shapeMap.insert(btHashPtr(shapeData), shape);
	}
	// The file's shape of an object, for the type check of a restore (0 when it is not a valid shape).
	auto fileShape = [&](void* shape) { return check.isShape(shape) ? static_cast<btCollisionShapeData*>(shape) : 0; };
	// 3. Rigid bodies.
	for (int i = 0; i < file->m_rigidBodies.size(); ++i)
	{
		auto convert = [&](auto* d)
		{
			check.fixName(d->m_collisionObjectData.m_name);
			if (!bodyFinite(*d) || !check.numbersSane(d))
			{
				warn("rigid body " + std::to_string(i) + " has non-finite data; it is skipped");
				allRestored = false;
			}
			else if (!restoring)
			{
				if constexpr (std::is_same<decltype(d), btRigidBodyFloatData*>::value)
					convertRigidBodyFloat(d);
				else
					convertRigidBodyDouble(d);
			}
			else if (btCollisionObject* target =
			             existing.restore(*d, fileShape(d->m_collisionObjectData.m_collisionShape), i))
				m_bodyMap.insert(btHashPtr(d), target);
			else
				allRestored = false;
		};
		void* body = file->m_rigidBodies[i];
		if (check.isA(body, "btRigidBodyFloatData"))
			convert(static_cast<btRigidBodyFloatData*>(body));
		else if (check.isA(body, "btRigidBodyDoubleData"))
			convert(static_cast<btRigidBodyDoubleData*>(body));
	}
	// 4. Plain collision objects.
	for (int i = 0; i < file->m_collisionObjects.size(); ++i)
	{
		void* object = file->m_collisionObjects[i];
		auto convert = [&](auto* d)
		{
			check.fixName(d->m_name);
			if (restoring)
			{
				btCollisionObject* target = objectFinite(*d) && check.numbersSane(d)
				                                ? existing.restore(*d, fileShape(d->m_collisionShape), i)
				                                : 0;
				if (target) m_bodyMap.insert(btHashPtr(d), target);
				allRestored &= target != 0;
				return;
			}
			btCollisionShape** shape = m_shapeMap.find(btHashPtr(d->m_collisionShape));
			if (!shape || !objectFinite(*d) || !check.numbersSane(d))
			{
				warn("collision object " + std::to_string(i) + " has no valid shape or non-finite data; it is skipped");
				return;
			}
			btTransform t;
			readTransform(t, d->m_worldTransform);
			btCollisionObject* created = createCollisionObject(t, *shape, d->m_name);
			created->setFriction(btScalar(d->m_friction));
			created->setRestitution(btScalar(d->m_restitution));
			created->setRollingFriction(btScalar(d->m_rollingFriction));
			created->setCollisionFlags(d->m_collisionFlags);
			if (m_dynamicsWorld && (d->m_collisionFilterGroup || d->m_collisionFilterMask))
			{
				m_dynamicsWorld->removeCollisionObject(created);
				m_dynamicsWorld->addCollisionObject(created, d->m_collisionFilterGroup, d->m_collisionFilterMask);
			}
			m_bodyMap.insert(btHashPtr(d), created);
		};
		if (check.isA(object, "btCollisionObjectFloatData"))
			convert(static_cast<btCollisionObjectFloatData*>(object));
		else if (check.isA(object, "btCollisionObjectDoubleData"))
			convert(static_cast<btCollisionObjectDoubleData*>(object));
	}
	// 5. Joints: both bodies must be rigid bodies of this file (or null: the world).
	for (int i = 0; i < file->m_constraints.size(); ++i)
	{
		void* joint = file->m_constraints[i];
		const char* type = check.structOf(joint);
		btTypedConstraintData* common = static_cast<btTypedConstraintData*>(joint);
		// The type field is read only once the block is known to be a joint struct.
		if (!type || !isJointStruct(type) || !jointStructMatches(common->m_objectType, type))
		{
			warn("joint " + std::to_string(i) + " has a struct that does not match its type; it is skipped");
			allRestored = false;
			continue;
		}
		if (!check.numbersSane(joint))
		{
			warn("joint " + std::to_string(i) + " has NaN or non-finite frames; it is skipped");
			allRestored = false;
			continue;
		}
		check.fixName(common->m_name);
		void* bodyA = common->m_rbA;
		void* bodyB = common->m_rbB;
		btCollisionObject** a = bodyA ? m_bodyMap.find(btHashPtr(bodyA)) : 0;
		btCollisionObject** b = bodyB ? m_bodyMap.find(btHashPtr(bodyB)) : 0;
		btRigidBody* rbA = a ? btRigidBody::upcast(*a) : 0;
		btRigidBody* rbB = b ? btRigidBody::upcast(*b) : 0;
		if ((bodyA && !rbA) || (bodyB && !rbB) || (!rbA && !rbB) || (bodyA && !check.isBody(bodyA)) ||
		    (bodyB && !check.isBody(bodyB)))
		{
			warn("joint " + std::to_string(i) +
			     (restoring ? " refers to a body that was not restored; it is not restored"
			                : " refers to a body that is not in the file; it is skipped"));
			allRestored = false;
			continue;
		}
		if (restoring)
		{
			allRestored &= existing.restoreJoint(common, type, rbA, rbB, i);
			continue;
		}
		if (isDoubleJoint(type))
			convertConstraintDouble(static_cast<btTypedConstraintDoubleData*>(joint), rbA, rbB, file->getVersion());
		else if (!strcmp(type, "btPoint2PointConstraintDoubleData") || !strcmp(type, "btHingeConstraintDoubleData"))
			convertConstraintBackwardsCompatible281(common, rbA, rbB, file->getVersion());
		else
			convertConstraintFloat(static_cast<btTypedConstraintFloatData*>(joint), rbA, rbB, file->getVersion());
	}
	return !restoring || allRestored;
}
