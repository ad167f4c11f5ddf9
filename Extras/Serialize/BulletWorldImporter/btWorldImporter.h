// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_WORLD_IMPORTER_H
#define BT_WORLD_IMPORTER_H

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btHashMap.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

/// Builds shapes, bodies and joints from the data structs of .bullet files through virtual create*
/// factories (override them to allocate your own classes). docs/serialization.md, "The importer".

class btCollisionShape;
class btCollisionObject;
class btRigidBody;
class btTypedConstraint;
class btDynamicsWorld;
class btTriangleIndexVertexArray;
class btStridingMeshInterface;
class btOptimizedBvh;
class btBvhTriangleMeshShape;
class btPoint2PointConstraint;
class btHingeConstraint;
class btConeTwistConstraint;
class btGeneric6DofConstraint;
class btGeneric6DofSpringConstraint;
class btGeneric6DofSpring2Constraint;
class btSliderConstraint;
class btGearConstraint;
class btConvexHullShape;
class btCompoundShape;
struct btTriangleInfoMap;
struct btContactSolverInfo;
struct btCollisionShapeData;
struct btStridingMeshInterfaceData;
struct btRigidBodyFloatData;
struct btRigidBodyDoubleData;
struct btCollisionObjectFloatData;
struct btCollisionObjectDoubleData;
struct btTypedConstraintData;
struct btTypedConstraintFloatData;
struct btTypedConstraintDoubleData;
struct btVector3FloatData;
struct btVector3DoubleData;

/// Importer flags.
enum btWorldImporterFlags
{
	/// Create nothing: write the file's state and settings into the objects and joints already in the
	/// importer's world, matched by name (names the importer recorded) or else by broadphase unique id
	/// (docs/serialization.md, "Restoring into existing objects").
	eRESTORE_EXISTING_OBJECTS = 1,
};

/// The part of the importer that turns data structs into objects; btBulletWorldImporter reads files.
class btWorldImporter
{
protected:
	btDynamicsWorld* m_dynamicsWorld;
	int m_verboseMode;
	int m_importerFlags;

	btAlignedObjectArray<btCollisionShape*> m_allocatedCollisionShapes;
	btAlignedObjectArray<btCollisionObject*> m_allocatedRigidBodies;
	btAlignedObjectArray<btTypedConstraint*> m_allocatedConstraints;
	btAlignedObjectArray<btOptimizedBvh*> m_allocatedBvhs;
	btAlignedObjectArray<btTriangleInfoMap*> m_allocatedTriangleInfoMaps;
	btAlignedObjectArray<btTriangleIndexVertexArray*> m_allocatedTriangleIndexArrays;
	btAlignedObjectArray<btStridingMeshInterfaceData*> m_allocatedbtStridingMeshInterfaceDatas;
	btAlignedObjectArray<btCollisionObject*> m_allocatedCollisionObjects;
	btAlignedObjectArray<char*> m_allocatedNames;
	btAlignedObjectArray<int*> m_indexArrays;
	btAlignedObjectArray<short int*> m_shortIndexArrays;
	btAlignedObjectArray<unsigned char*> m_charIndexArrays;
	btAlignedObjectArray<btVector3FloatData*> m_floatVertexArrays;
	btAlignedObjectArray<btVector3DoubleData*> m_doubleVertexArrays;

	btHashMap<btHashPtr, btOptimizedBvh*> m_bvhMap;
	btHashMap<btHashPtr, btTriangleInfoMap*> m_timMap;
	btHashMap<btHashString, btCollisionShape*> m_nameShapeMap;
	btHashMap<btHashString, btRigidBody*> m_nameBodyMap;
	btHashMap<btHashString, btTypedConstraint*> m_nameConstraintMap;
	btHashMap<btHashPtr, const char*> m_objectNameMap;
	/// Shape data (converted chunk) to the shape made from it.
	btHashMap<btHashPtr, btCollisionShape*> m_shapeMap;
	/// Body data (converted chunk) to the body made from it.
	btHashMap<btHashPtr, btCollisionObject*> m_bodyMap;

	/// A copy of name owned by the importer (0 for 0).
	char* duplicateName(const char* name);
	/// The shape described by shapeData (0, with a warning, for a kind the importer cannot build).
	btCollisionShape* convertCollisionShape(btCollisionShapeData* shapeData);
	/// Joints of files before 2.82 (float joints, hinge and point-to-point double variants).
	void convertConstraintBackwardsCompatible281(btTypedConstraintData* constraintData, btRigidBody* rbA,
	                                             btRigidBody* rbB, int fileVersion);
	/// Joints of float files.
	void convertConstraintFloat(btTypedConstraintFloatData* constraintData, btRigidBody* rbA, btRigidBody* rbB,
	                            int fileVersion);
	/// Joints of double files.
	void convertConstraintDouble(btTypedConstraintDoubleData* constraintData, btRigidBody* rbA, btRigidBody* rbB,
	                             int fileVersion);
	/// A rigid body from float data.
	void convertRigidBodyFloat(btRigidBodyFloatData* colObjData);
	/// A rigid body from double data.
	void convertRigidBodyDouble(btRigidBodyDoubleData* colObjData);

public:
	/// world may be 0: objects are then created but added to no world.
	btWorldImporter(btDynamicsWorld* world);
	virtual ~btWorldImporter();

	/// Deletes every object the importer created (remove them from the world first or call this
	/// while the world still exists: it removes them itself).
	virtual void deleteAllData();

	void setVerboseMode(int verboseMode) { m_verboseMode = verboseMode; }
	int getVerboseMode() const { return m_verboseMode; }
	void setImporterFlags(int importerFlags) { m_importerFlags = importerFlags; }
	int getImporterFlags() const { return m_importerFlags; }

	int getNumCollisionShapes() const;
	btCollisionShape* getCollisionShapeByIndex(int index);
	int getNumRigidBodies() const;
	btCollisionObject* getRigidBodyByIndex(int index) const;
	int getNumConstraints() const;
	btTypedConstraint* getConstraintByIndex(int index) const;
	int getNumBvhs() const;
	btOptimizedBvh* getBvhByIndex(int index) const;
	int getNumTriangleInfoMaps() const;
	btTriangleInfoMap* getTriangleInfoMapByIndex(int index) const;

	/// Look-ups by the names the file recorded (0 when none has that name).
	btCollisionShape* getCollisionShapeByName(const char* name);
	btRigidBody* getRigidBodyByName(const char* name);
	btTypedConstraint* getConstraintByName(const char* name);
	/// The name recorded for an object the importer created, or 0.
	const char* getNameForPointer(const void* ptr) const;

	/// Applies the file's gravity and solver settings to the world.
	virtual void setDynamicsWorldInfo(const btVector3& gravity, const btContactSolverInfo& solverInfo);

	// Factories: each allocates one object and records it for deleteAllData.
	virtual btCollisionObject* createCollisionObject(const btTransform& startTransform, btCollisionShape* shape,
	                                                 const char* bodyName);
	virtual btRigidBody* createRigidBody(bool isDynamic, btScalar mass, const btTransform& startTransform,
	                                     btCollisionShape* shape, const char* bodyName);
	virtual btCollisionShape* createPlaneShape(const btVector3& planeNormal, btScalar planeConstant);
	virtual btCollisionShape* createBoxShape(const btVector3& halfExtents);
	virtual btCollisionShape* createSphereShape(btScalar radius);
	virtual btCollisionShape* createCapsuleShapeX(btScalar radius, btScalar height);
	virtual btCollisionShape* createCapsuleShapeY(btScalar radius, btScalar height);
	virtual btCollisionShape* createCapsuleShapeZ(btScalar radius, btScalar height);
	virtual btCollisionShape* createCylinderShapeX(btScalar radius, btScalar height);
	virtual btCollisionShape* createCylinderShapeY(btScalar radius, btScalar height);
	virtual btCollisionShape* createCylinderShapeZ(btScalar radius, btScalar height);
	virtual btCollisionShape* createConeShapeX(btScalar radius, btScalar height);
	virtual btCollisionShape* createConeShapeY(btScalar radius, btScalar height);
	virtual btCollisionShape* createConeShapeZ(btScalar radius, btScalar height);
	virtual class btTriangleIndexVertexArray* createTriangleMeshContainer();
	virtual btBvhTriangleMeshShape* createBvhTriangleMeshShape(btStridingMeshInterface* trimesh, btOptimizedBvh* bvh);
	virtual btCollisionShape* createConvexTriangleMeshShape(btStridingMeshInterface* trimesh);
	virtual btStridingMeshInterfaceData* createStridingMeshInterfaceData(btStridingMeshInterfaceData* interfaceData);
	virtual class btConvexHullShape* createConvexHullShape();
	virtual class btCompoundShape* createCompoundShape();
	virtual class btScaledBvhTriangleMeshShape* createScaledTrangleMeshShape(
	    btBvhTriangleMeshShape* meshShape, const btVector3& localScalingbtBvhTriangleMeshShape);
	virtual class btMultiSphereShape* createMultiSphereShape(const btVector3* positions, const btScalar* radi,
	                                                         int numSpheres);
	virtual btTriangleIndexVertexArray* createMeshInterface(btStridingMeshInterfaceData& meshData);
	virtual btOptimizedBvh* createOptimizedBvh();
	virtual btTriangleInfoMap* createTriangleInfoMap();

	virtual btPoint2PointConstraint* createPoint2PointConstraint(btRigidBody& rbA, btRigidBody& rbB,
	                                                             const btVector3& pivotInA, const btVector3& pivotInB);
	virtual btPoint2PointConstraint* createPoint2PointConstraint(btRigidBody& rbA, const btVector3& pivotInA);
	virtual btHingeConstraint* createHingeConstraint(btRigidBody& rbA, btRigidBody& rbB, const btTransform& rbAFrame,
	                                                 const btTransform& rbBFrame, bool useReferenceFrameA = false);
	virtual btHingeConstraint* createHingeConstraint(btRigidBody& rbA, const btTransform& rbAFrame,
	                                                 bool useReferenceFrameA = false);
	virtual btConeTwistConstraint* createConeTwistConstraint(btRigidBody& rbA, btRigidBody& rbB,
	                                                         const btTransform& rbAFrame, const btTransform& rbBFrame);
	virtual btConeTwistConstraint* createConeTwistConstraint(btRigidBody& rbA, const btTransform& rbAFrame);
	virtual btGeneric6DofConstraint* createGeneric6DofConstraint(btRigidBody& rbA, btRigidBody& rbB,
	                                                             const btTransform& frameInA,
	                                                             const btTransform& frameInB,
	                                                             bool useLinearReferenceFrameA);
	virtual btGeneric6DofConstraint* createGeneric6DofConstraint(btRigidBody& rbB, const btTransform& frameInB,
	                                                             bool useLinearReferenceFrameB);
	virtual btGeneric6DofSpringConstraint* createGeneric6DofSpringConstraint(btRigidBody& rbA, btRigidBody& rbB,
	                                                                         const btTransform& frameInA,
	                                                                         const btTransform& frameInB,
	                                                                         bool useLinearReferenceFrameA);
	virtual btGeneric6DofSpring2Constraint* createGeneric6DofSpring2Constraint(btRigidBody& rbA, btRigidBody& rbB,
	                                                                           const btTransform& frameInA,
	                                                                           const btTransform& frameInB,
	                                                                           int rotateOrder);
	virtual btSliderConstraint* createSliderConstraint(btRigidBody& rbA, btRigidBody& rbB, const btTransform& frameInA,
	                                                   const btTransform& frameInB, bool useLinearReferenceFrameA);
	virtual btSliderConstraint* createSliderConstraint(btRigidBody& rbB, const btTransform& frameInB,
	                                                   bool useLinearReferenceFrameA);
	virtual btGearConstraint* createGearConstraint(btRigidBody& rbA, btRigidBody& rbB, const btVector3& axisInA,
	                                               const btVector3& axisInB, btScalar ratio);
};

#endif
