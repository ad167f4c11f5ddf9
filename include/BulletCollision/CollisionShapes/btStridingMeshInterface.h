// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_STRIDING_MESH_INTERFACE_H
#define BT_STRIDING_MESH_INTERFACE_H

#include "BulletCollision/CollisionShapes/btConcaveShape.h"
#include "BulletCollision/CollisionShapes/btTriangleCallback.h"
#include "LinearMath/btVector3.h"

class btSerializer;

/// Access to triangle mesh data that stays in the user's arrays: each subpart is a vertex array and an
/// index array (three indices per triangle), both with a byte stride. Vertices may be PHY_FLOAT or
/// PHY_DOUBLE (three components read per vertex), indices PHY_INTEGER, PHY_SHORT or PHY_UCHAR. Readers
/// skip (and assert on) triangles with an index out of range or a non-finite vertex, and subparts with
/// an unsupported type, a null base or a stride too small for three components.
ATTRIBUTE_ALIGNED16(class)
btStridingMeshInterface
{
protected:
	/// Scaling applied to every vertex as it is read (the owning mesh shape's local scaling).
	btVector3 m_scaling;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// A mesh interface with scaling (1, 1, 1).
	btStridingMeshInterface() : m_scaling(btScalar(1), btScalar(1), btScalar(1)) {}
	/// Interfaces are deleted through base pointers.
	virtual ~btStridingMeshInterface();

	/// Calls callback for every readable triangle of every subpart, vertices scaled by getScaling(). The
	/// box is not used for culling (as in Bullet): every triangle is reported.
	virtual void InternalProcessAllTriangles(btInternalTriangleIndexCallback * callback, const btVector3& aabbMin,
	                                         const btVector3& aabbMax) const;

	/// The AABB of every readable triangle (scaled); (0, 0, 0) twice for a mesh with no readable triangle.
	void calculateAabbBruteForce(btVector3 & aabbMin, btVector3 & aabbMax);

	/// Gives writable access to the arrays of subpart; pair with unLockVertexBase(subpart).
	virtual void getLockedVertexIndexBase(unsigned char** vertexbase, int& numverts, PHY_ScalarType& type, int& stride,
	                                      unsigned char** indexbase, int& indexstride, int& numfaces,
	                                      PHY_ScalarType& indicestype, int subpart = 0) = 0;

	/// Gives read-only access to the arrays of subpart; pair with unLockReadOnlyVertexBase(subpart).
	virtual void getLockedReadOnlyVertexIndexBase(const unsigned char** vertexbase, int& numverts, PHY_ScalarType& type,
	                                              int& stride, const unsigned char** indexbase, int& indexstride,
	                                              int& numfaces, PHY_ScalarType& indicestype, int subpart = 0)
	    const = 0;

	/// Ends a getLockedVertexIndexBase of subpart.
	virtual void unLockVertexBase(int subpart) = 0;
	/// Ends a getLockedReadOnlyVertexIndexBase of subpart.
	virtual void unLockReadOnlyVertexBase(int subpart) const = 0;

	/// Number of subparts (separately stored vertex/index array pairs).
	virtual int getNumSubParts() const = 0;

	/// Hint that numverts vertices will be added.
	virtual void preallocateVertices(int numverts) = 0;
	/// Hint that numindices indices will be added.
	virtual void preallocateIndices(int numindices) = 0;

	/// True when the user supplied the AABB (setPremadeAabb) instead of having it computed.
	virtual bool hasPremadeAabb() const { return false; }
	/// Stores a user-supplied AABB (ignored by interfaces that do not keep one).
	virtual void setPremadeAabb(const btVector3& aabbMin, const btVector3& aabbMax) const
	{
		(void)aabbMin;
		(void)aabbMax;
	}
	/// The user-supplied AABB (unchanged outputs when there is none).
	virtual void getPremadeAabb(btVector3 * aabbMin, btVector3 * aabbMax) const
	{
		(void)aabbMin;
		(void)aabbMax;
	}

	/// The scaling applied to vertices as they are read.
	const btVector3& getScaling() const { return m_scaling; }
	/// Sets the scaling; a non-finite scaling asserts and is ignored in release builds.
	void setScaling(const btVector3& scaling);

public:
	/// Bytes of btStridingMeshInterfaceData.
	virtual int calculateSerializeBufferSize() const;
	/// Writes the mesh (its parts, vertices and indices as chunks of their own) into dataBuffer and
	/// returns the struct's name.
	virtual const char* serialize(void* dataBuffer, btSerializer* serializer) const;
};

// clang-format off
/// File layout of btIntIndexData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btIntIndexData
{
	int m_value;
};

/// File layout of btShortIntIndexData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btShortIntIndexData
{
	short m_value;
	char m_pad[2];
};

/// File layout of btShortIntIndexTripletData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btShortIntIndexTripletData
{
	short m_values[3];
	char m_pad[2];
};

/// File layout of btCharIndexTripletData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btCharIndexTripletData
{
	char m_values[3];
	char m_pad;
};

/// File layout of btMeshPartData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btMeshPartData
{
	btVector3FloatData* m_vertices3f;
	btVector3DoubleData* m_vertices3d;
	btIntIndexData* m_indices32;
	btShortIntIndexTripletData* m_3indices16;
	btCharIndexTripletData* m_3indices8;
	btShortIntIndexData* m_indices16;
	int m_numTriangles;
	int m_numVertices;
};

/// File layout of btStridingMeshInterfaceData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btStridingMeshInterfaceData
{
	btMeshPartData* m_meshPartsPtr;
	btVector3FloatData m_scaling;
	int m_numMeshParts;
	char m_padding[4];
};

// clang-format on

#endif  // BT_STRIDING_MESH_INTERFACE_H
