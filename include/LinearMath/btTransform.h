// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_TRANSFORM_H
#define BT_TRANSFORM_H

/// btTransform: a rigid transform (rotation basis plus origin), no scaling or shear.

#include "LinearMath/btMatrix3x3.h"

#ifdef BT_USE_DOUBLE_PRECISION
#define btTransformData btTransformDoubleData
#else
#define btTransformData btTransformFloatData
#endif

struct btTransformFloatData;
struct btTransformDoubleData;

/// A rigid transform x -> basis * x + origin.
ATTRIBUTE_ALIGNED16(class)
btTransform
{
	btMatrix3x3 m_basis;
	btVector3 m_origin;

public:
	/// Uninitialised.
	btTransform() {}
	/// Rotation q, translation c.
	explicit SIMD_FORCE_INLINE btTransform(const btQuaternion& q,
	                                       const btVector3& c = btVector3(btScalar(0), btScalar(0), btScalar(0)))
	    : m_basis(q), m_origin(c)
	{
	}
	/// Basis b (should be a rotation), translation c.
	explicit SIMD_FORCE_INLINE btTransform(const btMatrix3x3& b,
	                                       const btVector3& c = btVector3(btScalar(0), btScalar(0), btScalar(0)))
	    : m_basis(b), m_origin(c)
	{
	}

	/// this = t1 * t2.
	SIMD_FORCE_INLINE void mult(const btTransform& t1, const btTransform& t2)
	{
		m_basis = t1.m_basis * t2.m_basis;
		m_origin = t1(t2.m_origin);
	}

	/// Transforms a point.
	SIMD_FORCE_INLINE btVector3 operator()(const btVector3& x) const { return m_basis * x + m_origin; }
	/// Transforms a point.
	SIMD_FORCE_INLINE btVector3 operator*(const btVector3& x) const { return (*this)(x); }
	/// Composes the rotations: getRotation() * q.
	SIMD_FORCE_INLINE btQuaternion operator*(const btQuaternion& q) const { return getRotation() * q; }

	SIMD_FORCE_INLINE btMatrix3x3& getBasis() { return m_basis; }
	SIMD_FORCE_INLINE const btMatrix3x3& getBasis() const { return m_basis; }
	SIMD_FORCE_INLINE btVector3& getOrigin() { return m_origin; }
	SIMD_FORCE_INLINE const btVector3& getOrigin() const { return m_origin; }

	/// The rotation as a unit quaternion.
	btQuaternion getRotation() const
	{
		btQuaternion q;
		m_basis.getRotation(q);
		return q;
	}

	/// From a column-major OpenGL 4x4 matrix (16 scalars; the last row is ignored).
	void setFromOpenGLMatrix(const btScalar* m)
	{
		m_basis.setFromOpenGLSubMatrix(m);
		m_origin.setValue(m[12], m[13], m[14]);
	}
	/// To a column-major OpenGL 4x4 matrix (16 scalars).
	void getOpenGLMatrix(btScalar * m) const
	{
		m_basis.getOpenGLSubMatrix(m);
		m[12] = m_origin.x();
		m[13] = m_origin.y();
		m[14] = m_origin.z();
		m[15] = btScalar(1.0);
	}

	SIMD_FORCE_INLINE void setOrigin(const btVector3& origin) { m_origin = origin; }
	/// basis^T * (inVec - origin): the inverse transform of a point.
	SIMD_FORCE_INLINE btVector3 invXform(const btVector3& inVec) const
	{
		const btVector3 v = inVec - m_origin;
		return v * m_basis;
	}
	SIMD_FORCE_INLINE void setBasis(const btMatrix3x3& basis) { m_basis = basis; }
	SIMD_FORCE_INLINE void setRotation(const btQuaternion& q) { m_basis.setRotation(q); }

	void setIdentity()
	{
		m_basis.setIdentity();
		m_origin.setValue(btScalar(0.0), btScalar(0.0), btScalar(0.0));
	}

	/// this = this * t.
	btTransform& operator*=(const btTransform& t)
	{
		m_origin += m_basis * t.m_origin;
		m_basis *= t.m_basis;
		return *this;
	}

	/// The inverse (basis transposed), valid because the basis is a rotation.
	btTransform inverse() const
	{
		const btMatrix3x3 inv = m_basis.transpose();
		return btTransform(inv, inv * -m_origin);
	}
	/// this^-1 * t, without forming the inverse.
	btTransform inverseTimes(const btTransform& t) const;
	/// this * t.
	btTransform operator*(const btTransform& t) const;

	/// The identity transform.
	static const btTransform& getIdentity()
	{
		static const btTransform identity(btMatrix3x3::getIdentity());
		return identity;
	}

	void serialize(struct btTransformData & dataOut) const;
	void serializeFloat(struct btTransformFloatData & dataOut) const;
	void deSerialize(const struct btTransformData& dataIn);
	void deSerializeDouble(const struct btTransformDoubleData& dataIn);
	void deSerializeFloat(const struct btTransformFloatData& dataIn);
};

SIMD_FORCE_INLINE btTransform btTransform::inverseTimes(const btTransform& t) const
{
	const btVector3 v = t.getOrigin() - m_origin;
	return btTransform(m_basis.transposeTimes(t.m_basis), v * m_basis);
}

SIMD_FORCE_INLINE btTransform btTransform::operator*(const btTransform& t) const
{
	return btTransform(m_basis * t.m_basis, (*this)(t.m_origin));
}

/// Exact equality of basis and origin.
SIMD_FORCE_INLINE bool operator==(const btTransform& t1, const btTransform& t2)
{
	return t1.getBasis() == t2.getBasis() && t1.getOrigin() == t2.getOrigin();
}

/// Serialised form of a transform in single precision.
struct btTransformFloatData
{
	btMatrix3x3FloatData m_basis;
	btVector3FloatData m_origin;
};
/// Serialised form of a transform in double precision.
struct btTransformDoubleData
{
	btMatrix3x3DoubleData m_basis;
	btVector3DoubleData m_origin;
};

SIMD_FORCE_INLINE void btTransform::serialize(btTransformData& dataOut) const
{
	m_basis.serialize(dataOut.m_basis);
	m_origin.serialize(dataOut.m_origin);
}
SIMD_FORCE_INLINE void btTransform::serializeFloat(btTransformFloatData& dataOut) const
{
	m_basis.serializeFloat(dataOut.m_basis);
	m_origin.serializeFloat(dataOut.m_origin);
}
SIMD_FORCE_INLINE void btTransform::deSerialize(const btTransformData& dataIn)
{
	m_basis.deSerialize(dataIn.m_basis);
	m_origin.deSerialize(dataIn.m_origin);
}
SIMD_FORCE_INLINE void btTransform::deSerializeFloat(const btTransformFloatData& dataIn)
{
	m_basis.deSerializeFloat(dataIn.m_basis);
	m_origin.deSerializeFloat(dataIn.m_origin);
}
SIMD_FORCE_INLINE void btTransform::deSerializeDouble(const btTransformDoubleData& dataIn)
{
	m_basis.deSerializeDouble(dataIn.m_basis);
	m_origin.deSerializeDouble(dataIn.m_origin);
}

namespace caliber
{
/// True when the basis and the origin are finite.
SIMD_FORCE_INLINE bool isFinite(const btTransform& t)
{
	const btMatrix3x3& m = t.getBasis();
#ifdef BT_USE_SSE
	// Lane by lane: a NaN residue anywhere makes its lane's sum NaN.
	return residuesAreZero(_mm_add_ps(_mm_add_ps(nonFiniteResidues(m[0]), nonFiniteResidues(m[1])),
	                                  _mm_add_ps(nonFiniteResidues(m[2]), nonFiniteResidues(t.getOrigin()))));
#else
	return nonFiniteResidue(m[0]) + nonFiniteResidue(m[1]) + nonFiniteResidue(m[2]) + nonFiniteResidue(t.getOrigin()) ==
	       btScalar(0);
#endif
}
}  // namespace caliber

#endif  // BT_TRANSFORM_H
