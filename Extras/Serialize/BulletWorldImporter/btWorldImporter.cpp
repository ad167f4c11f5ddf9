// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// Objects from data structs. The data has been checked by btBulletWorldImporter before it reaches
// these functions (pointer targets, counts, indices); what is left here is the meaning of each field,
// which follows Bullet's (docs/serialization.md, "Field meanings").
#include "btWorldImporter.h"

#include "btBulletDynamicsCommon.h"
#include "BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btTriangleInfoMap.h"
#include "BulletDynamics/ConstraintSolver/btGearConstraint.h"
#include "BulletDynamics/ConstraintSolver/btGeneric6DofSpring2Constraint.h"
#include "LinearMath/btSerializer.h"
#include "LinearMath/btWarningHook.h"
#include "detail/ImporterSettings.h"

#include <string.h>

#include <string>

namespace
{
// Deeper compound nesting than this is treated as a cycle.
const int kMaxCompoundDepth = 64;
thread_local int g_compoundDepth = 0;
using caliber::importer::vec;
using caliber::importer::xform;

}  // namespace

btWorldImporter::btWorldImporter(btDynamicsWorld* world) : m_dynamicsWorld(world), m_verboseMode(0), m_importerFlags(0)
{
}

btWorldImporter::~btWorldImporter() {}

void btWorldImporter::deleteAllData()
{
	for (int i = 0; i < m_allocatedConstraints.size(); ++i)
	{
		if (m_dynamicsWorld) m_dynamicsWorld->removeConstraint(m_allocatedConstraints[i]);
		delete m_allocatedConstraints[i];
	}
	m_allocatedConstraints.clear();
	for (int i = 0; i < m_allocatedRigidBodies.size(); ++i)
	{
		btRigidBody* body = btRigidBody::upcast(m_allocatedRigidBodies[i]);
		if (m_dynamicsWorld && body) m_dynamicsWorld->removeRigidBody(body);
		delete m_allocatedRigidBodies[i];
	}
	m_allocatedRigidBodies.clear();
	for (int i = 0; i < m_allocatedCollisionObjects.size(); ++i)
	{
		if (m_dynamicsWorld) m_dynamicsWorld->removeCollisionObject(m_allocatedCollisionObjects[i]);
		delete m_allocatedCollisionObjects[i];
	}
	m_allocatedCollisionObjects.clear();
	for (int i = 0; i < m_allocatedCollisionShapes.size(); ++i) delete m_allocatedCollisionShapes[i];
	m_allocatedCollisionShapes.clear();
	for (int i = 0; i < m_allocatedBvhs.size(); ++i) delete m_allocatedBvhs[i];
	m_allocatedBvhs.clear();
	for (int i = 0; i < m_allocatedTriangleInfoMaps.size(); ++i) delete m_allocatedTriangleInfoMaps[i];
	m_allocatedTriangleInfoMaps.clear();
	for (int i = 0; i < m_allocatedTriangleIndexArrays.size(); ++i) delete m_allocatedTriangleIndexArrays[i];
	m_allocatedTriangleIndexArrays.clear();
	for (int i = 0; i < m_allocatedNames.size(); ++i) delete[] m_allocatedNames[i];
	m_allocatedNames.clear();
	for (int i = 0; i < m_indexArrays.size(); ++i) btAlignedFree(m_indexArrays[i]);
	m_indexArrays.clear();
	for (int i = 0; i < m_floatVertexArrays.size(); ++i) btAlignedFree(m_floatVertexArrays[i]);
	m_floatVertexArrays.clear();
	for (int i = 0; i < m_doubleVertexArrays.size(); ++i) btAlignedFree(m_doubleVertexArrays[i]);
	m_doubleVertexArrays.clear();
	m_shortIndexArrays.clear();
	m_charIndexArrays.clear();
	m_allocatedbtStridingMeshInterfaceDatas.clear();
	m_bvhMap.clear();
	m_timMap.clear();
	m_nameShapeMap.clear();
	m_nameBodyMap.clear();
	m_nameConstraintMap.clear();
	m_objectNameMap.clear();
	m_shapeMap.clear();
	m_bodyMap.clear();
}

char* btWorldImporter::duplicateName(const char* name)
{
	if (!name) return 0;
	const size_t length = strlen(name);
	char* copy = new char[length + 1];
	memcpy(copy, name, length + 1);
	m_allocatedNames.push_back(copy);
	return copy;
}

// ---- shapes -----------------------------------------------------------------------------------

btTriangleIndexVertexArray* btWorldImporter::createMeshInterface(btStridingMeshInterfaceData& meshData)
{
	btTriangleIndexVertexArray* mesh = createTriangleMeshContainer();
	for (int p = 0; p < meshData.m_numMeshParts; ++p)
	{
		const btMeshPartData& part = meshData.m_meshPartsPtr[p];
		btIndexedMesh indexed;
		indexed.m_numTriangles = part.m_numTriangles;
		indexed.m_numVertices = part.m_numVertices;
		// Indices of every width become 32-bit; vertices take the build's precision.
		int* indices = static_cast<int*>(btAlignedAlloc(sizeof(int) * size_t(3 * part.m_numTriangles + 1), 16));
		m_indexArrays.push_back(indices);
		for (int t = 0; t < part.m_numTriangles; ++t)
			for (int k = 0; k < 3; ++k)
			{
				int index = 0;
				if (part.m_indices32)
					index = part.m_indices32[3 * t + k].m_value;
				else if (part.m_3indices16)
					index = static_cast<unsigned short>(part.m_3indices16[t].m_values[k]);
				else if (part.m_3indices8)
					index = static_cast<unsigned char>(part.m_3indices8[t].m_values[k]);
				else if (part.m_indices16)
					index = static_cast<unsigned short>(part.m_indices16[3 * t + k].m_value);
				indices[3 * t + k] = index;
			}
		indexed.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(indices);
		indexed.m_triangleIndexStride = 3 * int(sizeof(int));
		indexed.m_indexType = PHY_INTEGER;
#ifdef BT_USE_DOUBLE_PRECISION
		btVector3DoubleData* vertices = static_cast<btVector3DoubleData*>(
		    btAlignedAlloc(sizeof(btVector3DoubleData) * size_t(part.m_numVertices + 1), 16));
		m_doubleVertexArrays.push_back(vertices);
		indexed.m_vertexType = PHY_DOUBLE;
#else
		btVector3FloatData* vertices = static_cast<btVector3FloatData*>(
		    btAlignedAlloc(sizeof(btVector3FloatData) * size_t(part.m_numVertices + 1), 16));
		m_floatVertexArrays.push_back(vertices);
		indexed.m_vertexType = PHY_FLOAT;
#endif
		for (int v = 0; v < part.m_numVertices; ++v)
		{
			const btVector3 point = part.m_vertices3f ? vec(part.m_vertices3f[v]) : vec(part.m_vertices3d[v]);
			point.serialize(vertices[v]);
		}
		indexed.m_vertexBase = reinterpret_cast<const unsigned char*>(vertices);
		indexed.m_vertexStride = int(sizeof(vertices[0]));
		mesh->addIndexedMesh(indexed, PHY_INTEGER);
	}
	mesh->setScaling(vec(meshData.m_scaling));
	return mesh;
}

namespace
{
btCollisionShape* finishConvex(btCollisionShape* shape, const btConvexInternalShapeData& data, bool setMargin)
{
	if (!shape) return 0;
	if (setMargin) shape->setMargin(data.m_collisionMargin);
	shape->setLocalScaling(vec(data.m_localScaling));
	return shape;
}
}  // namespace

btCollisionShape* btWorldImporter::convertCollisionShape(btCollisionShapeData* shapeData)
{
	btCollisionShape* shape = 0;
	switch (shapeData->m_shapeType)
	{
		case STATIC_PLANE_PROXYTYPE:
		{
			btStaticPlaneShapeData* planeData = reinterpret_cast<btStaticPlaneShapeData*>(shapeData);
			shape = createPlaneShape(vec(planeData->m_planeNormal), planeData->m_planeConstant);
			if (shape) shape->setLocalScaling(vec(planeData->m_localScaling));
			break;
		}
		case BOX_SHAPE_PROXYTYPE:
		case SPHERE_SHAPE_PROXYTYPE:
		case CAPSULE_SHAPE_PROXYTYPE:
		case CYLINDER_SHAPE_PROXYTYPE:
		case CONE_SHAPE_PROXYTYPE:
		case MULTI_SPHERE_SHAPE_PROXYTYPE:
		case CONVEX_HULL_SHAPE_PROXYTYPE:
		{
			btConvexInternalShapeData* convexData = reinterpret_cast<btConvexInternalShapeData*>(shapeData);
			const btVector3 implicit = vec(convexData->m_implicitShapeDimensions);
			const btVector3 scaling = vec(convexData->m_localScaling);
			const btScalar margin = convexData->m_collisionMargin;
			const btVector3 margins(margin, margin, margin);
			switch (shapeData->m_shapeType)
			{
				case BOX_SHAPE_PROXYTYPE:
					// The file's box dimensions are scaled and without margin.
					shape = finishConvex(createBoxShape((implicit + margins) / scaling), *convexData, true);
					break;
				case SPHERE_SHAPE_PROXYTYPE:
					shape = finishConvex(createSphereShape(implicit.getX()), *convexData, false);
					break;
				case CAPSULE_SHAPE_PROXYTYPE:
				{
					const btVector3 dims = implicit / scaling;  // stored scaled, with the margin inside
					const int up = reinterpret_cast<btCapsuleShapeData*>(shapeData)->m_upAxis;
					if (up == 0)
						shape = createCapsuleShapeX(dims.getY(), 2 * dims.getX());
					else if (up == 1)
						shape = createCapsuleShapeY(dims.getX(), 2 * dims.getY());
					else
						shape = createCapsuleShapeZ(dims.getX(), 2 * dims.getZ());
					shape = finishConvex(shape, *convexData, false);
					break;
				}
				case CYLINDER_SHAPE_PROXYTYPE:
				{
					// Bullet's cylinder factories take the half extents (radius, half height).
					const btVector3 half = (implicit + margins) / scaling;
					const int up = reinterpret_cast<btCylinderShapeData*>(shapeData)->m_upAxis;
					if (up == 0)
						shape = createCylinderShapeX(half.getY(), half.getX());
					else if (up == 1)
						shape = createCylinderShapeY(half.getX(), half.getY());
					else
						shape = createCylinderShapeZ(half.getX(), half.getZ());
					shape = finishConvex(shape, *convexData, true);
					break;
				}
				case CONE_SHAPE_PROXYTYPE:
				{
					const int up = reinterpret_cast<btConeShapeData*>(shapeData)->m_upIndex;
					if (up == 0)
						shape = createConeShapeX(implicit.getY(), implicit.getX());
					else if (up == 1)
						shape = createConeShapeY(implicit.getX(), implicit.getY());
					else
						shape = createConeShapeZ(implicit.getX(), implicit.getZ());
					shape = finishConvex(shape, *convexData, true);
					break;
				}
				case MULTI_SPHERE_SHAPE_PROXYTYPE:
				{
					btMultiSphereShapeData* msData = reinterpret_cast<btMultiSphereShapeData*>(shapeData);
					const int count = msData->m_localPositionArraySize;
					btAlignedObjectArray<btVector3> positions;
					btAlignedObjectArray<btScalar> radii;
					positions.resize(count);
					radii.resize(count);
					for (int i = 0; i < count; ++i)
					{
						positions[i] = vec(msData->m_localPositionArrayPtr[i].m_pos);
						radii[i] = msData->m_localPositionArrayPtr[i].m_radius;
					}
					shape =
					    reinterpret_cast<btCollisionShape*>(createMultiSphereShape(&positions[0], &radii[0], count));
					shape = finishConvex(shape, *convexData, true);
					break;
				}
				case CONVEX_HULL_SHAPE_PROXYTYPE:
				{
					btConvexHullShapeData* hullData = reinterpret_cast<btConvexHullShapeData*>(shapeData);
					btConvexHullShape* hull = createConvexHullShape();
					for (int i = 0; i < hullData->m_numUnscaledPoints; ++i)
					{
						const btVector3 p = hullData->m_unscaledPointsFloatPtr
						                        ? vec(hullData->m_unscaledPointsFloatPtr[i])
						                        : vec(hullData->m_unscaledPointsDoublePtr[i]);
						hull->addPoint(p, i + 1 == hullData->m_numUnscaledPoints);
					}
					shape = finishConvex(hull, *convexData, true);
					break;
				}
				default:
					break;
			}
			break;
		}
		case TRIANGLE_MESH_SHAPE_PROXYTYPE:
		case SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE:
		{
			btTriangleMeshShapeData* meshData = reinterpret_cast<btTriangleMeshShapeData*>(shapeData);
			btTriangleIndexVertexArray* meshInterface = createMeshInterface(meshData->m_meshInterface);
			if (!meshInterface->getNumSubParts())
			{
				btReportWarning("Caliber: btWorldImporter: a triangle mesh without parts is skipped\n");
				return 0;
			}
			// A stored BVH that the loader accepted is used as is; otherwise the mesh builds its own.
			btOptimizedBvh* bvh = 0;
			void* bvhData = meshData->m_quantizedFloatBvh ? static_cast<void*>(meshData->m_quantizedFloatBvh)
			                                              : static_cast<void*>(meshData->m_quantizedDoubleBvh);
			if (btOptimizedBvh** known = bvhData ? m_bvhMap.find(btHashPtr(bvhData)) : 0) bvh = *known;
			btBvhTriangleMeshShape* meshShape = createBvhTriangleMeshShape(meshInterface, bvh);
			if (btTriangleInfoMap** map =
			        meshData->m_triangleInfoMap ? m_timMap.find(btHashPtr(meshData->m_triangleInfoMap)) : 0)
				meshShape->setTriangleInfoMap(*map);
			meshShape->setMargin(meshData->m_collisionMargin);
			shape = meshShape;
			if (shapeData->m_shapeType == SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE)
			{
				btScaledTriangleMeshShapeData* scaledData = reinterpret_cast<btScaledTriangleMeshShapeData*>(shapeData);
				shape = reinterpret_cast<btCollisionShape*>(
				    createScaledTrangleMeshShape(meshShape, vec(scaledData->m_localScaling)));
			}
			break;
		}
		case COMPOUND_SHAPE_PROXYTYPE:
		{
			btCompoundShapeData* compoundData = reinterpret_cast<btCompoundShapeData*>(shapeData);
			if (g_compoundDepth >= kMaxCompoundDepth)
			{
				btReportWarning("Caliber: btWorldImporter: compound shapes nest too deeply (a cycle?); skipped\n");
				return 0;
			}
			++g_compoundDepth;
			btCompoundShape* compound = createCompoundShape();
			for (int i = 0; i < compoundData->m_numChildShapes; ++i)
			{
				btCompoundShapeChildData& child = compoundData->m_childShapePtr[i];
				btCollisionShape* childShape = 0;
				btCollisionShape** known = m_shapeMap.find(btHashPtr(child.m_childShape));
				if (known)
					childShape = *known;
				else if (child.m_childShape)
				{
					childShape = convertCollisionShape(child.m_childShape);
					if (childShape) m_shapeMap.insert(btHashPtr(child.m_childShape), childShape);
				}
				if (childShape) compound->addChildShape(xform(child.m_transform), childShape);
			}
			--g_compoundDepth;
			shape = reinterpret_cast<btCollisionShape*>(compound);
			break;
		}
		default:
		{
			const std::string message = "Caliber: btWorldImporter: shapes of type " +
			                            std::to_string(shapeData->m_shapeType) +
			                            " are not supported by the importer; skipped\n";
			btReportWarning(message.c_str());
			return 0;
		}
	}
	if (shape && shapeData->m_name)
	{
		char* name = duplicateName(shapeData->m_name);
		m_objectNameMap.insert(btHashPtr(shape), name);
		m_nameShapeMap.insert(btHashString(name), shape);
	}
	return shape;
}

// ---- bodies -----------------------------------------------------------------------------------

namespace
{
using caliber::importer::applyCollisionObjectData;

// Re-adds an object with the file's filter when the file recorded one.
template <class ObjectData>
void applyFilter(btDynamicsWorld* world, btCollisionObject* object, const ObjectData& d)
{
	if (!world || (d.m_collisionFilterGroup == 0 && d.m_collisionFilterMask == 0)) return;
	btRigidBody* body = btRigidBody::upcast(object);
	if (body)
	{
		world->removeRigidBody(body);
		world->addRigidBody(body, d.m_collisionFilterGroup, d.m_collisionFilterMask);
	}
	else
	{
		world->removeCollisionObject(object);
		world->addCollisionObject(object, d.m_collisionFilterGroup, d.m_collisionFilterMask);
	}
}

template <class BodyData>
btRigidBody* convertBody(btWorldImporter& importer, btHashMap<btHashPtr, btCollisionShape*>& shapes,
                         btDynamicsWorld* world, BodyData* d)
{
	btCollisionShape** shape = shapes.find(btHashPtr(d->m_collisionObjectData.m_collisionShape));
	if (!shape || !*shape)
	{
		btReportWarning(
		    "Caliber: btWorldImporter: a rigid body's shape is missing from the file; the body is skipped\n");
		return 0;
	}
	const btScalar mass = d->m_inverseMass != 0 ? btScalar(1) / btScalar(d->m_inverseMass) : btScalar(0);
	btRigidBody* body = importer.createRigidBody(mass != 0, mass, xform(d->m_collisionObjectData.m_worldTransform),
	                                             *shape, d->m_collisionObjectData.m_name);
	if (!body) return 0;
	applyCollisionObjectData(body, d->m_collisionObjectData);
	caliber::importer::applyRigidBodyData(body, *d);
	applyFilter(world, body, d->m_collisionObjectData);
	// After the world has given the body its gravity: the file's own.
	body->setGravity(vec(d->m_gravity_acceleration));
	return body;
}
}  // namespace

void btWorldImporter::convertRigidBodyFloat(btRigidBodyFloatData* colObjData)
{
	btRigidBody* body = convertBody(*this, m_shapeMap, m_dynamicsWorld, colObjData);
	if (body) m_bodyMap.insert(btHashPtr(colObjData), body);
}

void btWorldImporter::convertRigidBodyDouble(btRigidBodyDoubleData* colObjData)
{
	btRigidBody* body = convertBody(*this, m_shapeMap, m_dynamicsWorld, colObjData);
	if (body) m_bodyMap.insert(btHashPtr(colObjData), body);
}

// ---- joints -----------------------------------------------------------------------------------

namespace
{
template <class Common>
void applyCommon(btDynamicsWorld* world, btTypedConstraint* c, const Common& d,
                 btHashMap<btHashString, btTypedConstraint*>& names, btHashMap<btHashPtr, const char*>& objectNames,
                 char* name)
{
	caliber::importer::applyJointCommon(*c, d);
	if (name)
	{
		names.insert(btHashString(name), c);
		objectNames.insert(btHashPtr(c), name);
	}
	if (world) world->addConstraint(c, d.m_disableCollisionsBetweenLinkedBodies != 0);
}

// The joint kinds, one template per data layout family (float and double share field names): made with
// their bodies and frames, then given the file's settings (detail/ImporterSettings.h).
template <class D>
btTypedConstraint* makeHinge(btWorldImporter& imp, btRigidBody& a, btRigidBody& b, const D& d)
{
	btHingeConstraint* hinge =
	    imp.createHingeConstraint(a, b, xform(d.m_rbAFrame), xform(d.m_rbBFrame), d.m_useReferenceFrameA != 0);
	caliber::importer::configure(*hinge, d);
	return hinge;
}

template <class D>
btTypedConstraint* makeConeTwist(btWorldImporter& imp, btRigidBody& a, btRigidBody& b, const D& d)
{
	btConeTwistConstraint* cone = imp.createConeTwistConstraint(a, b, xform(d.m_rbAFrame), xform(d.m_rbBFrame));
	caliber::importer::configure(*cone, d);
	return cone;
}

template <class D>
btTypedConstraint* make6Dof(btWorldImporter& imp, btRigidBody& a, btRigidBody& b, const D& d)
{
	btGeneric6DofConstraint* dof = imp.createGeneric6DofConstraint(a, b, xform(d.m_rbAFrame), xform(d.m_rbBFrame),
	                                                               d.m_useLinearReferenceFrameA != 0);
	caliber::importer::configure(*dof, d);
	return dof;
}

template <class D>
btTypedConstraint* make6DofSpring(btWorldImporter& imp, btRigidBody& a, btRigidBody& b, const D& d)
{
	const auto& base = d.m_6dofData;
	btGeneric6DofSpringConstraint* dof = imp.createGeneric6DofSpringConstraint(
	    a, b, xform(base.m_rbAFrame), xform(base.m_rbBFrame), base.m_useLinearReferenceFrameA != 0);
	caliber::importer::configureSpring(*dof, d);
	return dof;
}

template <class D>
btTypedConstraint* makeSpring2(btWorldImporter& imp, btRigidBody& a, btRigidBody& b, const D& d)
{
	btGeneric6DofSpring2Constraint* dof =
	    imp.createGeneric6DofSpring2Constraint(a, b, xform(d.m_rbAFrame), xform(d.m_rbBFrame), d.m_rotateOrder);
	caliber::importer::configure(*dof, d);
	return dof;
}

template <class D>
btTypedConstraint* makeSlider(btWorldImporter& imp, btRigidBody& a, btRigidBody& b, const D& d)
{
	btSliderConstraint* slider =
	    imp.createSliderConstraint(a, b, xform(d.m_rbAFrame), xform(d.m_rbBFrame), d.m_useLinearReferenceFrameA != 0);
	caliber::importer::configure(*slider, d);
	return slider;
}

template <class D>
btTypedConstraint* makeGear(btWorldImporter& imp, btRigidBody& a, btRigidBody& b, const D& d)
{
	return imp.createGearConstraint(a, b, vec(d.m_axisInA), vec(d.m_axisInB), btScalar(d.m_ratio));
}

template <class D>
btTypedConstraint* makePoint(btWorldImporter& imp, btRigidBody& a, btRigidBody& b, const D& d)
{
	return imp.createPoint2PointConstraint(a, b, vec(d.m_pivotInA), vec(d.m_pivotInB));
}
}  // namespace

// A missing body is the world's fixed body (joints to the world are written with a null body).
#define CALIBER_IMPORT_BODIES                                        \
	btRigidBody& a = rbA ? *rbA : btTypedConstraint::getFixedBody(); \
	btRigidBody& b = rbB ? *rbB : btTypedConstraint::getFixedBody();

void btWorldImporter::convertConstraintFloat(btTypedConstraintFloatData* data, btRigidBody* rbA, btRigidBody* rbB,
                                             int fileVersion)
{
	(void)fileVersion;
	CALIBER_IMPORT_BODIES
	btTypedConstraint* c = 0;
	switch (data->m_objectType)
	{
		case POINT2POINT_CONSTRAINT_TYPE:
			c = makePoint(*this, a, b, *reinterpret_cast<btPoint2PointConstraintFloatData*>(data));
			break;
		case HINGE_CONSTRAINT_TYPE:
			c = makeHinge(*this, a, b, *reinterpret_cast<btHingeConstraintFloatData*>(data));
			break;
		case CONETWIST_CONSTRAINT_TYPE:
			c = makeConeTwist(*this, a, b, *reinterpret_cast<btConeTwistConstraintData*>(data));
			break;
		case D6_CONSTRAINT_TYPE:
			c = make6Dof(*this, a, b, *reinterpret_cast<btGeneric6DofConstraintData*>(data));
			break;
		case D6_SPRING_CONSTRAINT_TYPE:
			c = make6DofSpring(*this, a, b, *reinterpret_cast<btGeneric6DofSpringConstraintData*>(data));
			break;
		case D6_SPRING_2_CONSTRAINT_TYPE:
		case FIXED_CONSTRAINT_TYPE:
			c = makeSpring2(*this, a, b, *reinterpret_cast<btGeneric6DofSpring2ConstraintData*>(data));
			break;
		case SLIDER_CONSTRAINT_TYPE:
			c = makeSlider(*this, a, b, *reinterpret_cast<btSliderConstraintData*>(data));
			break;
		case GEAR_CONSTRAINT_TYPE:
			c = makeGear(*this, a, b, *reinterpret_cast<btGearConstraintFloatData*>(data));
			break;
		default:
			break;
	}
	if (!c) return;
	applyCommon(m_dynamicsWorld, c, *data, m_nameConstraintMap, m_objectNameMap, duplicateName(data->m_name));
}

void btWorldImporter::convertConstraintDouble(btTypedConstraintDoubleData* data, btRigidBody* rbA, btRigidBody* rbB,
                                              int fileVersion)
{
	(void)fileVersion;
	CALIBER_IMPORT_BODIES
	btTypedConstraint* c = 0;
	switch (data->m_objectType)
	{
		case POINT2POINT_CONSTRAINT_TYPE:
			c = makePoint(*this, a, b, *reinterpret_cast<btPoint2PointConstraintDoubleData2*>(data));
			break;
		case HINGE_CONSTRAINT_TYPE:
			c = makeHinge(*this, a, b, *reinterpret_cast<btHingeConstraintDoubleData2*>(data));
			break;
		case CONETWIST_CONSTRAINT_TYPE:
			c = makeConeTwist(*this, a, b, *reinterpret_cast<btConeTwistConstraintDoubleData*>(data));
			break;
		case D6_CONSTRAINT_TYPE:
			c = make6Dof(*this, a, b, *reinterpret_cast<btGeneric6DofConstraintDoubleData2*>(data));
			break;
		case D6_SPRING_CONSTRAINT_TYPE:
			c = make6DofSpring(*this, a, b, *reinterpret_cast<btGeneric6DofSpringConstraintDoubleData2*>(data));
			break;
		case D6_SPRING_2_CONSTRAINT_TYPE:
		case FIXED_CONSTRAINT_TYPE:
			c = makeSpring2(*this, a, b, *reinterpret_cast<btGeneric6DofSpring2ConstraintDoubleData2*>(data));
			break;
		case SLIDER_CONSTRAINT_TYPE:
			c = makeSlider(*this, a, b, *reinterpret_cast<btSliderConstraintDoubleData*>(data));
			break;
		case GEAR_CONSTRAINT_TYPE:
			c = makeGear(*this, a, b, *reinterpret_cast<btGearConstraintDoubleData*>(data));
			break;
		default:
			break;
	}
	if (!c) return;
	applyCommon(m_dynamicsWorld, c, *data, m_nameConstraintMap, m_objectNameMap, duplicateName(data->m_name));
}

void btWorldImporter::convertConstraintBackwardsCompatible281(btTypedConstraintData* data, btRigidBody* rbA,
                                                              btRigidBody* rbB, int fileVersion)
{
	(void)fileVersion;
	CALIBER_IMPORT_BODIES
	btTypedConstraint* c = 0;
	// The older double layouts of the two joints that had them; the other kinds share the float layout.
	switch (data->m_objectType)
	{
		case POINT2POINT_CONSTRAINT_TYPE:
			c = makePoint(*this, a, b, *reinterpret_cast<btPoint2PointConstraintDoubleData*>(data));
			break;
		case HINGE_CONSTRAINT_TYPE:
			c = makeHinge(*this, a, b, *reinterpret_cast<btHingeConstraintDoubleData*>(data));
			break;
		default:
			convertConstraintFloat(reinterpret_cast<btTypedConstraintFloatData*>(data), rbA, rbB, fileVersion);
			return;
	}
	if (!c) return;
	applyCommon(m_dynamicsWorld, c, *data, m_nameConstraintMap, m_objectNameMap, duplicateName(data->m_name));
}
#undef CALIBER_IMPORT_BODIES

// ---- queries ----------------------------------------------------------------------------------

int btWorldImporter::getNumCollisionShapes() const { return m_allocatedCollisionShapes.size(); }
btCollisionShape* btWorldImporter::getCollisionShapeByIndex(int index)
{
	return (index >= 0 && index < m_allocatedCollisionShapes.size()) ? m_allocatedCollisionShapes[index] : 0;
}
int btWorldImporter::getNumRigidBodies() const { return m_allocatedRigidBodies.size(); }
btCollisionObject* btWorldImporter::getRigidBodyByIndex(int index) const
{
	return (index >= 0 && index < m_allocatedRigidBodies.size()) ? m_allocatedRigidBodies[index] : 0;
}
int btWorldImporter::getNumConstraints() const { return m_allocatedConstraints.size(); }
btTypedConstraint* btWorldImporter::getConstraintByIndex(int index) const
{
	return (index >= 0 && index < m_allocatedConstraints.size()) ? m_allocatedConstraints[index] : 0;
}
int btWorldImporter::getNumBvhs() const { return m_allocatedBvhs.size(); }
btOptimizedBvh* btWorldImporter::getBvhByIndex(int index) const
{
	return (index >= 0 && index < m_allocatedBvhs.size()) ? m_allocatedBvhs[index] : 0;
}
int btWorldImporter::getNumTriangleInfoMaps() const { return m_allocatedTriangleInfoMaps.size(); }
btTriangleInfoMap* btWorldImporter::getTriangleInfoMapByIndex(int index) const
{
	return (index >= 0 && index < m_allocatedTriangleInfoMaps.size()) ? m_allocatedTriangleInfoMaps[index] : 0;
}

btCollisionShape* btWorldImporter::getCollisionShapeByName(const char* name)
{
	btCollisionShape** found = name ? m_nameShapeMap.find(btHashString(name)) : 0;
	return found ? *found : 0;
}
btRigidBody* btWorldImporter::getRigidBodyByName(const char* name)
{
	btRigidBody** found = name ? m_nameBodyMap.find(btHashString(name)) : 0;
	return found ? *found : 0;
}
btTypedConstraint* btWorldImporter::getConstraintByName(const char* name)
{
	btTypedConstraint** found = name ? m_nameConstraintMap.find(btHashString(name)) : 0;
	return found ? *found : 0;
}
const char* btWorldImporter::getNameForPointer(const void* ptr) const
{
	const char* const* found = m_objectNameMap.find(btHashPtr(ptr));
	return found ? *found : 0;
}

// ---- factories --------------------------------------------------------------------------------

void btWorldImporter::setDynamicsWorldInfo(const btVector3& gravity, const btContactSolverInfo& solverInfo)
{
	if (!m_dynamicsWorld) return;
	m_dynamicsWorld->setGravity(gravity);
	m_dynamicsWorld->getSolverInfo() = solverInfo;
}

btCollisionObject* btWorldImporter::createCollisionObject(const btTransform& startTransform, btCollisionShape* shape,
                                                          const char* bodyName)
{
	btCollisionObject* object = new btCollisionObject();
	object->setWorldTransform(startTransform);
	object->setCollisionShape(shape);
	if (m_dynamicsWorld) m_dynamicsWorld->addCollisionObject(object);
	if (bodyName)
	{
		char* name = duplicateName(bodyName);
		m_objectNameMap.insert(btHashPtr(object), name);
	}
	m_allocatedCollisionObjects.push_back(object);
	return object;
}

btRigidBody* btWorldImporter::createRigidBody(bool isDynamic, btScalar mass, const btTransform& startTransform,
                                              btCollisionShape* shape, const char* bodyName)
{
	btVector3 localInertia(0, 0, 0);
	if (!isDynamic) mass = 0;
	if (mass != 0 && shape && shape->isNonMoving())
	{
		// Meshes and planes have no inertia (their calculateLocalInertia asserts): such a body is static.
		btReportWarning(
		    "Caliber: btWorldImporter: a body with mass has a static-only shape (mesh, plane); it is made static\n");
		mass = 0;
	}
	if (!btIsFinite(mass) || mass < 0)
	{
		// An inverse mass so small that the mass overflows (btRigidBody asserts on it).
		btReportWarning("Caliber: btWorldImporter: a body's mass is not a finite number; it is made static\n");
		mass = 0;
	}
	if (mass != 0 && shape) shape->calculateLocalInertia(mass, localInertia);
	for (int axis = 0; axis < 3; ++axis)
		if (!btIsFinite(localInertia[axis]) || localInertia[axis] < 0)
		{
			// Huge shapes overflow their inertia; the file's inverse inertia is applied afterwards anyway.
			btReportWarning("Caliber: btWorldImporter: a body's shape gives no finite inertia; zero is used\n");
			localInertia.setValue(0, 0, 0);
			break;
		}
	btRigidBody::btRigidBodyConstructionInfo info(mass, 0, shape, localInertia);
	info.m_startWorldTransform = startTransform;
	btRigidBody* body = new btRigidBody(info);
	if (m_dynamicsWorld) m_dynamicsWorld->addRigidBody(body);
	if (bodyName)
	{
		char* name = duplicateName(bodyName);
		m_objectNameMap.insert(btHashPtr(body), name);
		m_nameBodyMap.insert(btHashString(name), body);
	}
	m_allocatedRigidBodies.push_back(body);
	return body;
}

#define CALIBER_KEEP_SHAPE(expr)                 \
	btCollisionShape* shape = (expr);            \
	m_allocatedCollisionShapes.push_back(shape); \
	return shape

btCollisionShape* btWorldImporter::createPlaneShape(const btVector3& n, btScalar c)
{
	CALIBER_KEEP_SHAPE(new btStaticPlaneShape(n, c));
}
btCollisionShape* btWorldImporter::createBoxShape(const btVector3& h) { CALIBER_KEEP_SHAPE(new btBoxShape(h)); }
btCollisionShape* btWorldImporter::createSphereShape(btScalar r) { CALIBER_KEEP_SHAPE(new btSphereShape(r)); }
btCollisionShape* btWorldImporter::createCapsuleShapeX(btScalar r, btScalar h)
{
	CALIBER_KEEP_SHAPE(new btCapsuleShapeX(r, h));
}
btCollisionShape* btWorldImporter::createCapsuleShapeY(btScalar r, btScalar h)
{
	CALIBER_KEEP_SHAPE(new btCapsuleShape(r, h));
}
btCollisionShape* btWorldImporter::createCapsuleShapeZ(btScalar r, btScalar h)
{
	CALIBER_KEEP_SHAPE(new btCapsuleShapeZ(r, h));
}
btCollisionShape* btWorldImporter::createCylinderShapeX(btScalar r, btScalar h)
{
	CALIBER_KEEP_SHAPE(new btCylinderShapeX(btVector3(h, r, r)));
}
btCollisionShape* btWorldImporter::createCylinderShapeY(btScalar r, btScalar h)
{
	CALIBER_KEEP_SHAPE(new btCylinderShape(btVector3(r, h, r)));
}
btCollisionShape* btWorldImporter::createCylinderShapeZ(btScalar r, btScalar h)
{
	CALIBER_KEEP_SHAPE(new btCylinderShapeZ(btVector3(r, r, h)));
}
btCollisionShape* btWorldImporter::createConeShapeX(btScalar r, btScalar h)
{
	CALIBER_KEEP_SHAPE(new btConeShapeX(r, h));
}
btCollisionShape* btWorldImporter::createConeShapeY(btScalar r, btScalar h)
{
	CALIBER_KEEP_SHAPE(new btConeShape(r, h));
}
btCollisionShape* btWorldImporter::createConeShapeZ(btScalar r, btScalar h)
{
	CALIBER_KEEP_SHAPE(new btConeShapeZ(r, h));
}
btCollisionShape* btWorldImporter::createConvexTriangleMeshShape(btStridingMeshInterface* trimesh)
{
	CALIBER_KEEP_SHAPE(new btConvexTriangleMeshShape(trimesh));
}
#undef CALIBER_KEEP_SHAPE

btTriangleIndexVertexArray* btWorldImporter::createTriangleMeshContainer()
{
	btTriangleIndexVertexArray* mesh = new btTriangleIndexVertexArray();
	m_allocatedTriangleIndexArrays.push_back(mesh);
	return mesh;
}

btBvhTriangleMeshShape* btWorldImporter::createBvhTriangleMeshShape(btStridingMeshInterface* trimesh,
                                                                    btOptimizedBvh* bvh)
{
	btBvhTriangleMeshShape* shape = bvh ? new btBvhTriangleMeshShape(trimesh, bvh->isQuantized(), false)
	                                    : new btBvhTriangleMeshShape(trimesh, true);
	// The tree was built for the mesh's scaling (read from the file with the mesh): keep it.
	if (bvh) shape->setOptimizedBvh(bvh, trimesh->getScaling());
	m_allocatedCollisionShapes.push_back(shape);
	return shape;
}

btStridingMeshInterfaceData* btWorldImporter::createStridingMeshInterfaceData(
    btStridingMeshInterfaceData* interfaceData)
{
	// The importer keeps the converted file data alive only during the load; callers wanting to keep
	// it must copy it. Returned as is (Bullet's importer copies it; Caliber does not need the copy).
	m_allocatedbtStridingMeshInterfaceDatas.push_back(interfaceData);
	return interfaceData;
}

btConvexHullShape* btWorldImporter::createConvexHullShape()
{
	btConvexHullShape* shape = new btConvexHullShape();
	m_allocatedCollisionShapes.push_back(shape);
	return shape;
}

btCompoundShape* btWorldImporter::createCompoundShape()
{
	btCompoundShape* shape = new btCompoundShape();
	m_allocatedCollisionShapes.push_back(shape);
	return shape;
}

btScaledBvhTriangleMeshShape* btWorldImporter::createScaledTrangleMeshShape(btBvhTriangleMeshShape* meshShape,
                                                                            const btVector3& localScaling)
{
	btScaledBvhTriangleMeshShape* shape = new btScaledBvhTriangleMeshShape(meshShape, localScaling);
	m_allocatedCollisionShapes.push_back(shape);
	return shape;
}

btMultiSphereShape* btWorldImporter::createMultiSphereShape(const btVector3* positions, const btScalar* radi,
                                                            int numSpheres)
{
	btMultiSphereShape* shape = new btMultiSphereShape(positions, radi, numSpheres);
	m_allocatedCollisionShapes.push_back(shape);
	return shape;
}

btOptimizedBvh* btWorldImporter::createOptimizedBvh()
{
	btOptimizedBvh* bvh = new btOptimizedBvh();
	m_allocatedBvhs.push_back(bvh);
	return bvh;
}

btTriangleInfoMap* btWorldImporter::createTriangleInfoMap()
{
	btTriangleInfoMap* map = new btTriangleInfoMap();
	m_allocatedTriangleInfoMaps.push_back(map);
	return map;
}

#define CALIBER_KEEP_JOINT(Type, expr)       \
	Type* joint = (expr);                    \
	m_allocatedConstraints.push_back(joint); \
	return joint

btPoint2PointConstraint* btWorldImporter::createPoint2PointConstraint(btRigidBody& rbA, btRigidBody& rbB,
                                                                      const btVector3& pivotInA,
                                                                      const btVector3& pivotInB)
{
	CALIBER_KEEP_JOINT(btPoint2PointConstraint, new btPoint2PointConstraint(rbA, rbB, pivotInA, pivotInB));
}
btPoint2PointConstraint* btWorldImporter::createPoint2PointConstraint(btRigidBody& rbA, const btVector3& pivotInA)
{
	CALIBER_KEEP_JOINT(btPoint2PointConstraint, new btPoint2PointConstraint(rbA, pivotInA));
}
btHingeConstraint* btWorldImporter::createHingeConstraint(btRigidBody& rbA, btRigidBody& rbB,
                                                          const btTransform& rbAFrame, const btTransform& rbBFrame,
                                                          bool useReferenceFrameA)
{
	CALIBER_KEEP_JOINT(btHingeConstraint, new btHingeConstraint(rbA, rbB, rbAFrame, rbBFrame, useReferenceFrameA));
}
btHingeConstraint* btWorldImporter::createHingeConstraint(btRigidBody& rbA, const btTransform& rbAFrame,
                                                          bool useReferenceFrameA)
{
	CALIBER_KEEP_JOINT(btHingeConstraint, new btHingeConstraint(rbA, rbAFrame, useReferenceFrameA));
}
btConeTwistConstraint* btWorldImporter::createConeTwistConstraint(btRigidBody& rbA, btRigidBody& rbB,
                                                                  const btTransform& rbAFrame,
                                                                  const btTransform& rbBFrame)
{
	CALIBER_KEEP_JOINT(btConeTwistConstraint, new btConeTwistConstraint(rbA, rbB, rbAFrame, rbBFrame));
}
btConeTwistConstraint* btWorldImporter::createConeTwistConstraint(btRigidBody& rbA, const btTransform& rbAFrame)
{
	CALIBER_KEEP_JOINT(btConeTwistConstraint, new btConeTwistConstraint(rbA, rbAFrame));
}
btGeneric6DofConstraint* btWorldImporter::createGeneric6DofConstraint(btRigidBody& rbA, btRigidBody& rbB,
                                                                      const btTransform& frameInA,
                                                                      const btTransform& frameInB,
                                                                      bool useLinearReferenceFrameA)
{
	CALIBER_KEEP_JOINT(btGeneric6DofConstraint,
	                   new btGeneric6DofConstraint(rbA, rbB, frameInA, frameInB, useLinearReferenceFrameA));
}
btGeneric6DofConstraint* btWorldImporter::createGeneric6DofConstraint(btRigidBody& rbB, const btTransform& frameInB,
                                                                      bool useLinearReferenceFrameB)
{
	CALIBER_KEEP_JOINT(btGeneric6DofConstraint, new btGeneric6DofConstraint(rbB, frameInB, useLinearReferenceFrameB));
}
btGeneric6DofSpringConstraint* btWorldImporter::createGeneric6DofSpringConstraint(btRigidBody& rbA, btRigidBody& rbB,
                                                                                  const btTransform& frameInA,
                                                                                  const btTransform& frameInB,
                                                                                  bool useLinearReferenceFrameA)
{
	CALIBER_KEEP_JOINT(btGeneric6DofSpringConstraint,
	                   new btGeneric6DofSpringConstraint(rbA, rbB, frameInA, frameInB, useLinearReferenceFrameA));
}
btGeneric6DofSpring2Constraint* btWorldImporter::createGeneric6DofSpring2Constraint(btRigidBody& rbA, btRigidBody& rbB,
                                                                                    const btTransform& frameInA,
                                                                                    const btTransform& frameInB,
                                                                                    int rotateOrder)
{
	if (rotateOrder < RO_XYZ || rotateOrder > RO_ZYX) rotateOrder = RO_XYZ;
	CALIBER_KEEP_JOINT(btGeneric6DofSpring2Constraint,
	                   new btGeneric6DofSpring2Constraint(rbA, rbB, frameInA, frameInB, RotateOrder(rotateOrder)));
}
btSliderConstraint* btWorldImporter::createSliderConstraint(btRigidBody& rbA, btRigidBody& rbB,
                                                            const btTransform& frameInA, const btTransform& frameInB,
                                                            bool useLinearReferenceFrameA)
{
	CALIBER_KEEP_JOINT(btSliderConstraint,
	                   new btSliderConstraint(rbA, rbB, frameInA, frameInB, useLinearReferenceFrameA));
}
btSliderConstraint* btWorldImporter::createSliderConstraint(btRigidBody& rbB, const btTransform& frameInB,
                                                            bool useLinearReferenceFrameA)
{
	CALIBER_KEEP_JOINT(btSliderConstraint, new btSliderConstraint(rbB, frameInB, useLinearReferenceFrameA));
}
btGearConstraint* btWorldImporter::createGearConstraint(btRigidBody& rbA, btRigidBody& rbB, const btVector3& axisInA,
                                                        const btVector3& axisInB, btScalar ratio)
{
	CALIBER_KEEP_JOINT(btGearConstraint, new btGearConstraint(rbA, rbB, axisInA, axisInB, ratio));
}
#undef CALIBER_KEEP_JOINT
