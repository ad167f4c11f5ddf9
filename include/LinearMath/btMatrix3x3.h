// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_MATRIX3x3_H
#define BT_MATRIX3x3_H

/// btMatrix3x3: a 3x3 matrix stored as three row vectors (rotations, inertia tensors).

#include "LinearMath/btVector3.h"
#include "LinearMath/btQuaternion.h"

#ifdef BT_USE_DOUBLE_PRECISION
#define btMatrix3x3Data btMatrix3x3DoubleData
#else
#define btMatrix3x3Data btMatrix3x3FloatData
#endif

struct btMatrix3x3FloatData;
struct btMatrix3x3DoubleData;

/// A 3x3 matrix of three btVector3 rows; rotation matrices act on column vectors (m * v).
ATTRIBUTE_ALIGNED16(class)
btMatrix3x3
{
	btVector3 m_el[3];

public:
	/// Uninitialised.
	btMatrix3x3() {}
	/// The rotation matrix of a quaternion.
	explicit btMatrix3x3(const btQuaternion& q) { setRotation(q); }
	/// From nine values, row by row.
	btMatrix3x3(const btScalar& xx, const btScalar& xy, const btScalar& xz, const btScalar& yx, const btScalar& yy,
	            const btScalar& yz, const btScalar& zx, const btScalar& zy, const btScalar& zz)
	{
		setValue(xx, xy, xz, yx, yy, yz, zx, zy, zz);
	}
	/// From three rows.
	SIMD_FORCE_INLINE btMatrix3x3(const btVector3& v0, const btVector3& v1, const btVector3& v2)
	{
		m_el[0] = v0;
		m_el[1] = v1;
		m_el[2] = v2;
	}

	/// Column i (0..2).
	SIMD_FORCE_INLINE btVector3 getColumn(int i) const { return btVector3(m_el[0][i], m_el[1][i], m_el[2][i]); }
	/// Row i (0..2).
	SIMD_FORCE_INLINE const btVector3& getRow(int i) const
	{
		btFullAssert(0 <= i && i < 3);
		return m_el[i];
	}
	/// Row i (0..2), writable.
	SIMD_FORCE_INLINE btVector3& operator[](int i)
	{
		btFullAssert(0 <= i && i < 3);
		return m_el[i];
	}
	SIMD_FORCE_INLINE const btVector3& operator[](int i) const
	{
		btFullAssert(0 <= i && i < 3);
		return m_el[i];
	}

	/// this = this * m.
	btMatrix3x3& operator*=(const btMatrix3x3& m);
	/// Element-wise sum.
	btMatrix3x3& operator+=(const btMatrix3x3& m)
	{
		for (int i = 0; i < 3; ++i) m_el[i] += m.m_el[i];
		return *this;
	}
	/// Element-wise difference.
	btMatrix3x3& operator-=(const btMatrix3x3& m)
	{
		for (int i = 0; i < 3; ++i) m_el[i] -= m.m_el[i];
		return *this;
	}

	/// From the upper-left 3x3 of a column-major OpenGL matrix (m[0..2] is the first column; stride 4).
	void setFromOpenGLSubMatrix(const btScalar* m)
	{
		m_el[0].setValue(m[0], m[4], m[8]);
		m_el[1].setValue(m[1], m[5], m[9]);
		m_el[2].setValue(m[2], m[6], m[10]);
	}
	/// Writes the matrix as the upper-left 3x3 of a column-major OpenGL matrix (m[3], m[7], m[11] = 0).
	void getOpenGLSubMatrix(btScalar * m) const
	{
		for (int column = 0; column < 3; ++column)
		{
			m[4 * column + 0] = m_el[0][column];
			m[4 * column + 1] = m_el[1][column];
			m[4 * column + 2] = m_el[2][column];
			m[4 * column + 3] = btScalar(0.0);
		}
	}

	/// Sets nine values, row by row.
	void setValue(const btScalar& xx, const btScalar& xy, const btScalar& xz, const btScalar& yx, const btScalar& yy,
	              const btScalar& yz, const btScalar& zx, const btScalar& zy, const btScalar& zz)
	{
		m_el[0].setValue(xx, xy, xz);
		m_el[1].setValue(yx, yy, yz);
		m_el[2].setValue(zx, zy, zz);
	}

	/// The rotation matrix of q (need not be unit length). A zero quaternion asserts; release builds
	/// set the identity.
	void setRotation(const btQuaternion& q)
	{
		const btScalar d = q.length2();
		btAssert(d != btScalar(0.0));
		if (!(d > btScalar(0.0)))
		{
			setIdentity();
			return;
		}
		const btScalar s = btScalar(2.0) / d;
		const btScalar xs = q.x() * s, ys = q.y() * s, zs = q.z() * s;
		const btScalar wx = q.w() * xs, wy = q.w() * ys, wz = q.w() * zs;
		const btScalar xx = q.x() * xs, xy = q.x() * ys, xz = q.x() * zs;
		const btScalar yy = q.y() * ys, yz = q.y() * zs, zz = q.z() * zs;
		setValue(btScalar(1.0) - (yy + zz), xy - wz, xz + wy, xy + wz, btScalar(1.0) - (xx + zz), yz - wx, xz - wy,
		         yz + wx, btScalar(1.0) - (xx + yy));
	}

	/// Bullet's convention: the same as setEulerZYX(roll, pitch, yaw), i.e. yaw about Z, pitch about Y,
	/// roll about X, applied roll first.
	void setEulerYPR(const btScalar& yaw, const btScalar& pitch, const btScalar& roll)
	{
		setEulerZYX(roll, pitch, yaw);
	}

	/// R = Rz(eulerZ) * Ry(eulerY) * Rx(eulerX): a vector is turned about X first, then Y, then Z.
	void setEulerZYX(btScalar eulerX, btScalar eulerY, btScalar eulerZ)
	{
		const btScalar cx = btCos(eulerX), cy = btCos(eulerY), cz = btCos(eulerZ);
		const btScalar sx = btSin(eulerX), sy = btSin(eulerY), sz = btSin(eulerZ);
		setValue(cy * cz, sy * sx * cz - cx * sz, sy * cx * cz + sx * sz,  //
		         cy * sz, sy * sx * sz + cx * cz, sy * cx * sz - sx * cz,  //
		         -sy, cy * sx, cy * cx);
	}

	void setIdentity()
	{
		setValue(btScalar(1.0), btScalar(0.0), btScalar(0.0), btScalar(0.0), btScalar(1.0), btScalar(0.0),
		         btScalar(0.0), btScalar(0.0), btScalar(1.0));
	}
	/// Sets every element to 0.
	void setZero()
	{
		m_el[0].setZero();
		m_el[1].setZero();
		m_el[2].setZero();
	}
	/// The identity matrix.
	static const btMatrix3x3& getIdentity()
	{
		static const btMatrix3x3 identity(btScalar(1.0), btScalar(0.0), btScalar(0.0), btScalar(0.0), btScalar(1.0),
		                                  btScalar(0.0), btScalar(0.0), btScalar(0.0), btScalar(1.0));
		return identity;
	}

	/// The unit quaternion of this rotation matrix (Shepperd's method: divide by the largest of the
	/// four candidate terms, so the result is accurate for every rotation).
	void getRotation(btQuaternion & q) const;

	/// Inverse of setEulerYPR: yaw about Z, pitch about Y, roll about X. At gimbal lock yaw is 0.
	void getEulerYPR(btScalar & yaw, btScalar & pitch, btScalar & roll) const;

	/// Inverse of setEulerZYX(roll, pitch, yaw). Two solutions exist away from gimbal lock
	/// (solution_number 1: pitch in [-pi/2, pi/2]; 2: the other one); at gimbal lock yaw is 0.
	void getEulerZYX(btScalar & yaw, btScalar & pitch, btScalar & roll, unsigned int solution_number = 1) const;

	/// this * diag(s): column j scaled by s[j].
	btMatrix3x3 scaled(const btVector3& s) const
	{
		return btMatrix3x3(m_el[0].x() * s.x(), m_el[0].y() * s.y(), m_el[0].z() * s.z(), m_el[1].x() * s.x(),
		                   m_el[1].y() * s.y(), m_el[1].z() * s.z(), m_el[2].x() * s.x(), m_el[2].y() * s.y(),
		                   m_el[2].z() * s.z());
	}

	/// Determinant.
	btScalar determinant() const { return btTriple((*this)[0], (*this)[1], (*this)[2]); }
	/// The adjugate (transposed cofactor matrix): adjoint() == determinant() * inverse().
	btMatrix3x3 adjoint() const;
	/// Element-wise absolute value.
	btMatrix3x3 absolute() const { return btMatrix3x3(m_el[0].absolute(), m_el[1].absolute(), m_el[2].absolute()); }
	/// The transpose.
	btMatrix3x3 transpose() const;
	/// The inverse. A singular (or non-finite) matrix asserts; release builds return the zero matrix.
	btMatrix3x3 inverse() const;

	/// Solves this * x = b by Cramer's rule. A singular matrix gives the zero vector.
	btVector3 solve33(const btVector3& b) const
	{
		const btVector3 col1 = getColumn(0), col2 = getColumn(1), col3 = getColumn(2);
		const btScalar det = btDot(col1, btCross(col2, col3));
		if (!(det != btScalar(0)) || !btIsFinite(det)) return btVector3(btScalar(0), btScalar(0), btScalar(0));
		const btScalar invDet = btScalar(1.0) / det;
		return btVector3(invDet * btDot(b, btCross(col2, col3)), invDet * btDot(col1, btCross(b, col3)),
		                 invDet * btDot(col1, btCross(col2, b)));
	}

	/// this^T * m.
	btMatrix3x3 transposeTimes(const btMatrix3x3& m) const;
	/// this * m^T.
	btMatrix3x3 timesTranspose(const btMatrix3x3& m) const;

	/// Column 0 dotted with v (row 0 of this^T * v).
	SIMD_FORCE_INLINE btScalar tdotx(const btVector3& v) const
	{
		return m_el[0].x() * v.x() + m_el[1].x() * v.y() + m_el[2].x() * v.z();
	}
	/// Column 1 dotted with v.
	SIMD_FORCE_INLINE btScalar tdoty(const btVector3& v) const
	{
		return m_el[0].y() * v.x() + m_el[1].y() * v.y() + m_el[2].y() * v.z();
	}
	/// Column 2 dotted with v.
	SIMD_FORCE_INLINE btScalar tdotz(const btVector3& v) const
	{
		return m_el[0].z() * v.x() + m_el[1].z() * v.y() + m_el[2].z() * v.z();
	}

	/// Diagonalises this symmetric matrix with Jacobi rotations. Afterwards this is (nearly) diagonal
	/// and old_this = rot * this * rot^T. Stops when every off-diagonal element is at most threshold
	/// times the largest absolute diagonal element (or absolutely at most threshold when that is 0),
	/// or after maxSteps rotations.
	void diagonalize(btMatrix3x3 & rot, btScalar threshold, int maxSteps);

	/// m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1].
	btScalar cofac(int r1, int c1, int r2, int c2) const
	{
		return m_el[r1][c1] * m_el[r2][c2] - m_el[r1][c2] * m_el[r2][c1];
	}

	/// Refines q (in-out) towards the rotation closest to this matrix (polar decomposition by
	/// Mueller et al.'s iteration); q should start at a good guess, e.g. the previous result.
	void extractRotation(btQuaternion & q, btScalar tolerance = 1.0e-9, int maxIter = 100);

	void serialize(struct btMatrix3x3Data & dataOut) const;
	void serializeFloat(struct btMatrix3x3FloatData & dataOut) const;
	void deSerialize(const struct btMatrix3x3Data& dataIn);
	void deSerializeFloat(const struct btMatrix3x3FloatData& dataIn);
	void deSerializeDouble(const struct btMatrix3x3DoubleData& dataIn);
};

/// Matrix times vector: (row0 . v, row1 . v, row2 . v).
SIMD_FORCE_INLINE btVector3 operator*(const btMatrix3x3& m, const btVector3& v)
{
#ifdef BT_USE_SSE
	// Multiply every row by v, transpose, and add: each lane then sums (x + y) + z like btVector3::dot.
	__m128 r0 = _mm_mul_ps(m[0].get128(), v.get128());
	__m128 r1 = _mm_mul_ps(m[1].get128(), v.get128());
	__m128 r2 = _mm_mul_ps(m[2].get128(), v.get128());
	__m128 r3 = _mm_setzero_ps();
	_MM_TRANSPOSE4_PS(r0, r1, r2, r3);
	return btVector3(_mm_add_ps(_mm_add_ps(r0, r1), r2));
#else
	return btVector3(m[0].dot(v), m[1].dot(v), m[2].dot(v));
#endif
}

/// Row vector times matrix: v^T * m.
SIMD_FORCE_INLINE btVector3 operator*(const btVector3& v, const btMatrix3x3& m)
{
#ifdef BT_USE_SSE
	// v.x row0 + v.y row1 + v.z row2, summed in the order of tdotx: no transpose through memory.
	const __m128 a = v.get128();
	const __m128 sum = _mm_add_ps(
	    _mm_add_ps(_mm_mul_ps(m[0].get128(), CALIBER_SPLAT(a, 0)), _mm_mul_ps(m[1].get128(), CALIBER_SPLAT(a, 1))),
	    _mm_mul_ps(m[2].get128(), CALIBER_SPLAT(a, 2)));
	return btVector3(CALIBER_CLEAR_W(sum));
#else
	return btVector3(m.tdotx(v), m.tdoty(v), m.tdotz(v));
#endif
}

/// Matrix product.
SIMD_FORCE_INLINE btMatrix3x3 operator*(const btMatrix3x3& m1, const btMatrix3x3& m2)
{
#ifdef BT_USE_SSE
	// Row i of the product is m1[i].x * m2[0] + m1[i].y * m2[1] + m1[i].z * m2[2], summed in that order.
	btMatrix3x3 result;
	for (int i = 0; i < 3; ++i)
	{
		const __m128 row = m1[i].get128();
		const __m128 sum = _mm_add_ps(_mm_add_ps(_mm_mul_ps(CALIBER_SPLAT(row, 0), m2[0].get128()),
		                                         _mm_mul_ps(CALIBER_SPLAT(row, 1), m2[1].get128())),
		                              _mm_mul_ps(CALIBER_SPLAT(row, 2), m2[2].get128()));
		result[i] = btVector3(sum);
	}
	return result;
#else
	return btMatrix3x3(m2.tdotx(m1[0]), m2.tdoty(m1[0]), m2.tdotz(m1[0]), m2.tdotx(m1[1]), m2.tdoty(m1[1]),
	                   m2.tdotz(m1[1]), m2.tdotx(m1[2]), m2.tdoty(m1[2]), m2.tdotz(m1[2]));
#endif
}

/// Every element times k.
SIMD_FORCE_INLINE btMatrix3x3 operator*(const btMatrix3x3& m, const btScalar& k)
{
	return btMatrix3x3(m[0] * k, m[1] * k, m[2] * k);
}
SIMD_FORCE_INLINE btMatrix3x3 operator+(const btMatrix3x3& m1, const btMatrix3x3& m2)
{
	return btMatrix3x3(m1[0] + m2[0], m1[1] + m2[1], m1[2] + m2[2]);
}
SIMD_FORCE_INLINE btMatrix3x3 operator-(const btMatrix3x3& m1, const btMatrix3x3& m2)
{
	return btMatrix3x3(m1[0] - m2[0], m1[1] - m2[1], m1[2] - m2[2]);
}
/// Exact equality of all nine elements.
SIMD_FORCE_INLINE bool operator==(const btMatrix3x3& m1, const btMatrix3x3& m2)
{
	return m1[0] == m2[0] && m1[1] == m2[1] && m1[2] == m2[2];
}

SIMD_FORCE_INLINE btMatrix3x3& btMatrix3x3::operator*=(const btMatrix3x3& m)
{
	*this = *this * m;
	return *this;
}

SIMD_FORCE_INLINE btMatrix3x3 btMatrix3x3::transpose() const
{
#ifdef BT_USE_SSE
	// Shuffled in registers; the zero fourth row leaves w = 0 in every transposed row.
	__m128 r0 = m_el[0].get128(), r1 = m_el[1].get128(), r2 = m_el[2].get128(), r3 = _mm_setzero_ps();
	_MM_TRANSPOSE4_PS(r0, r1, r2, r3);
	btMatrix3x3 result;
	result[0] = btVector3(r0);
	result[1] = btVector3(r1);
	result[2] = btVector3(r2);
	return result;
#else
	return btMatrix3x3(m_el[0].x(), m_el[1].x(), m_el[2].x(), m_el[0].y(), m_el[1].y(), m_el[2].y(), m_el[0].z(),
	                   m_el[1].z(), m_el[2].z());
#endif
}

SIMD_FORCE_INLINE btMatrix3x3 btMatrix3x3::adjoint() const
{
	return btMatrix3x3(cofac(1, 1, 2, 2), cofac(0, 2, 2, 1), cofac(0, 1, 1, 2), cofac(1, 2, 2, 0), cofac(0, 0, 2, 2),
	                   cofac(0, 2, 1, 0), cofac(1, 0, 2, 1), cofac(0, 1, 2, 0), cofac(0, 0, 1, 1));
}

SIMD_FORCE_INLINE btMatrix3x3 btMatrix3x3::inverse() const
{
	const btMatrix3x3 adj = adjoint();
	// det = row 0 . column 0 of the adjugate.
	const btScalar det = m_el[0].x() * adj[0].x() + m_el[0].y() * adj[1].x() + m_el[0].z() * adj[2].x();
	const bool invertible = det != btScalar(0.0) && btIsFinite(det);
	btAssert(invertible);
	if (!invertible)
	{
		btMatrix3x3 zero;
		zero.setZero();
		return zero;
	}
	const btScalar s = btScalar(1.0) / det;
	return adj * s;
}

SIMD_FORCE_INLINE btMatrix3x3 btMatrix3x3::transposeTimes(const btMatrix3x3& m) const
{
	// (this^T m)[i][j] = column i of this . column j of m.
	btMatrix3x3 result;
#ifdef BT_USE_SSE
	// Row i of the result is this[0][i] m[0] + this[1][i] m[1] + this[2][i] m[2], summed in that order.
	for (int i = 0; i < 3; ++i)
	{
		const __m128 sum = _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_set1_ps(m_el[0][i]), m[0].get128()),
		                                         _mm_mul_ps(_mm_set1_ps(m_el[1][i]), m[1].get128())),
		                              _mm_mul_ps(_mm_set1_ps(m_el[2][i]), m[2].get128()));
		result[i] = btVector3(CALIBER_CLEAR_W(sum));
	}
#else
	for (int i = 0; i < 3; ++i)
		for (int j = 0; j < 3; ++j) result[i][j] = m_el[0][i] * m[0][j] + m_el[1][i] * m[1][j] + m_el[2][i] * m[2][j];
	for (int i = 0; i < 3; ++i) result[i][3] = btScalar(0);
#endif
	return result;
}

SIMD_FORCE_INLINE btMatrix3x3 btMatrix3x3::timesTranspose(const btMatrix3x3& m) const
{
	// (this m^T)[i][j] = row i of this . row j of m.
	return btMatrix3x3(m_el[0].dot(m[0]), m_el[0].dot(m[1]), m_el[0].dot(m[2]), m_el[1].dot(m[0]), m_el[1].dot(m[1]),
	                   m_el[1].dot(m[2]), m_el[2].dot(m[0]), m_el[2].dot(m[1]), m_el[2].dot(m[2]));
}

/// Serialised form of a matrix in single precision.
struct btMatrix3x3FloatData
{
	btVector3FloatData m_el[3];
};
/// Serialised form of a matrix in double precision.
struct btMatrix3x3DoubleData
{
	btVector3DoubleData m_el[3];
};

SIMD_FORCE_INLINE void btMatrix3x3::serialize(struct btMatrix3x3Data& dataOut) const
{
	for (int i = 0; i < 3; ++i) m_el[i].serialize(dataOut.m_el[i]);
}
SIMD_FORCE_INLINE void btMatrix3x3::serializeFloat(struct btMatrix3x3FloatData& dataOut) const
{
	for (int i = 0; i < 3; ++i) m_el[i].serializeFloat(dataOut.m_el[i]);
}
SIMD_FORCE_INLINE void btMatrix3x3::deSerialize(const struct btMatrix3x3Data& dataIn)
{
	for (int i = 0; i < 3; ++i) m_el[i].deSerialize(dataIn.m_el[i]);
}
SIMD_FORCE_INLINE void btMatrix3x3::deSerializeFloat(const struct btMatrix3x3FloatData& dataIn)
{
	for (int i = 0; i < 3; ++i) m_el[i].deSerializeFloat(dataIn.m_el[i]);
}
SIMD_FORCE_INLINE void btMatrix3x3::deSerializeDouble(const struct btMatrix3x3DoubleData& dataIn)
{
	for (int i = 0; i < 3; ++i) m_el[i].deSerializeDouble(dataIn.m_el[i]);
}

namespace caliber
{
/// True when all nine entries are finite.
SIMD_FORCE_INLINE bool isFinite(const btMatrix3x3& m)
{
	return nonFiniteResidue(m[0]) + nonFiniteResidue(m[1]) + nonFiniteResidue(m[2]) == btScalar(0);
}
}  // namespace caliber

#endif  // BT_MATRIX3x3_H
