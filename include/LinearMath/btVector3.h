// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_VECTOR3_H
#define BT_VECTOR3_H

/// btVector3 (a 3D vector padded to 4 scalars, 16-byte aligned) and btVector4.
///
/// With BT_USE_SSE (single precision on x86-64) the hot operations run on a __m128. They are written
/// to perform the same floating point operations in the same order as the scalar path (for example
/// dot is (x*x + y*y) + z*z in both), so both paths give the same bits for the same input.
/// The fourth component w is padding: constructors set it to 0, btVector3 comparisons ignore it.

#include "LinearMath/btScalar.h"
#include "LinearMath/btMinMax.h"
#include "LinearMath/btAlignedAllocator.h"

#ifdef BT_USE_DOUBLE_PRECISION
#define btVector3Data btVector3DoubleData
#define btVector3DataName "btVector3DoubleData"
#else
#define btVector3Data btVector3FloatData
#define btVector3DataName "btVector3FloatData"
#endif

#ifdef BT_USE_SSE
/// The SIMD register type behind btVector3 in SSE builds.
typedef __m128 btSimdFloat4;
// Lane selector for _mm_shuffle_ps: result lanes take (a, b, c, d).
#define CALIBER_SHUFFLE(a, b, c, d) (((d) << 6) | ((c) << 4) | ((b) << 2) | (a))
// Broadcasts one lane of v to all four.
#define CALIBER_SPLAT(v, lane) _mm_shuffle_ps((v), (v), CALIBER_SHUFFLE(lane, lane, lane, lane))
// Clears the w lane in registers (writing m_floats[3] instead would stall on store forwarding).
#define CALIBER_CLEAR_W(v) _mm_and_ps((v), _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0)))
#endif

struct btVector3FloatData;
struct btVector3DoubleData;

/// A 3D vector (positions, directions, velocities); the workhorse type of the whole API.
ATTRIBUTE_ALIGNED16(class)
btVector3
{
public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

#ifdef BT_USE_SSE
	union
	{
		btSimdFloat4 mVec128;
		btScalar m_floats[4];
	};
	/// The SIMD register holding x, y, z, w.
	SIMD_FORCE_INLINE btSimdFloat4 get128() const { return mVec128; }
	/// Sets all four lanes from a SIMD register.
	SIMD_FORCE_INLINE void set128(btSimdFloat4 v128) { mVec128 = v128; }
	/// Wraps a SIMD register.
	SIMD_FORCE_INLINE btVector3(const btSimdFloat4 v128) { mVec128 = v128; }
#else
	btScalar m_floats[4];
#endif

	/// Uninitialised, like a built-in type (hot code constructs many vectors it overwrites at once).
	SIMD_FORCE_INLINE btVector3() {}
	/// (x, y, z) with w = 0.
	SIMD_FORCE_INLINE btVector3(const btScalar& x, const btScalar& y, const btScalar& z)
	{
#ifdef BT_USE_SSE
		// Built in a register: four scalar stores read back as one vector would stall store forwarding.
		mVec128 = _mm_setr_ps(x, y, z, btScalar(0.));
#else
		m_floats[0] = x;
		m_floats[1] = y;
		m_floats[2] = z;
		m_floats[3] = btScalar(0.);
#endif
	}

	SIMD_FORCE_INLINE btVector3& operator+=(const btVector3& v)
	{
#ifdef BT_USE_SSE
		mVec128 = _mm_add_ps(mVec128, v.mVec128);
#else
		m_floats[0] += v.m_floats[0];
		m_floats[1] += v.m_floats[1];
		m_floats[2] += v.m_floats[2];
#endif
		return *this;
	}

	SIMD_FORCE_INLINE btVector3& operator-=(const btVector3& v)
	{
#ifdef BT_USE_SSE
		mVec128 = _mm_sub_ps(mVec128, v.mVec128);
#else
		m_floats[0] -= v.m_floats[0];
		m_floats[1] -= v.m_floats[1];
		m_floats[2] -= v.m_floats[2];
#endif
		return *this;
	}

	SIMD_FORCE_INLINE btVector3& operator*=(const btScalar& s)
	{
#ifdef BT_USE_SSE
		mVec128 = _mm_mul_ps(mVec128, _mm_set1_ps(s));
#else
		m_floats[0] *= s;
		m_floats[1] *= s;
		m_floats[2] *= s;
#endif
		return *this;
	}

	/// Divides each component by s (a true division, not a multiplication by 1/s). s must not be 0.
	SIMD_FORCE_INLINE btVector3& operator/=(const btScalar& s)
	{
		btAssert(s != btScalar(0.0));
#ifdef BT_USE_SSE
		mVec128 = CALIBER_CLEAR_W(_mm_div_ps(mVec128, _mm_set1_ps(s)));
#else
		m_floats[0] /= s;
		m_floats[1] /= s;
		m_floats[2] /= s;
#endif
		return *this;
	}

	/// Component-wise product.
	SIMD_FORCE_INLINE btVector3& operator*=(const btVector3& v)
	{
#ifdef BT_USE_SSE
		mVec128 = _mm_mul_ps(mVec128, v.mVec128);
#else
		m_floats[0] *= v.m_floats[0];
		m_floats[1] *= v.m_floats[1];
		m_floats[2] *= v.m_floats[2];
#endif
		return *this;
	}

	/// Dot product, computed as (x*x' + y*y') + z*z' on both code paths.
	SIMD_FORCE_INLINE btScalar dot(const btVector3& v) const
	{
#ifdef BT_USE_SSE
		const __m128 products = _mm_mul_ps(mVec128, v.mVec128);
		__m128 sum = _mm_add_ss(products, CALIBER_SPLAT(products, 1));
		sum = _mm_add_ss(sum, CALIBER_SPLAT(products, 2));
		return _mm_cvtss_f32(sum);
#else
		return m_floats[0] * v.m_floats[0] + m_floats[1] * v.m_floats[1] + m_floats[2] * v.m_floats[2];
#endif
	}

	/// Squared length.
	SIMD_FORCE_INLINE btScalar length2() const { return dot(*this); }
	/// Length.
	SIMD_FORCE_INLINE btScalar length() const { return btSqrt(length2()); }
	/// Length (Bullet's alias).
	SIMD_FORCE_INLINE btScalar norm() const { return length(); }
	/// Length, or 0 when the squared length is below SIMD_EPSILON^2.
	SIMD_FORCE_INLINE btScalar safeNorm() const
	{
		const btScalar d = length2();
		return d > SIMD_EPSILON * SIMD_EPSILON ? btSqrt(d) : btScalar(0);
	}
	/// Squared distance to v.
	SIMD_FORCE_INLINE btScalar distance2(const btVector3& v) const;
	/// Distance to v.
	SIMD_FORCE_INLINE btScalar distance(const btVector3& v) const;

	/// Normalizes when the length is at least SIMD_EPSILON; otherwise (zero, tiny or NaN vectors) sets
	/// (1, 0, 0). Never asserts. Very long vectors (length2 overflows) are normalised correctly.
	SIMD_FORCE_INLINE btVector3& safeNormalize()
	{
		const btScalar l2 = length2();
		if (btLikely(l2 >= SIMD_EPSILON * SIMD_EPSILON && l2 <= SIMD_INFINITY)) return *this /= btSqrt(l2);
		return normalizeSlowPath(false);
	}

	/// Makes the length 1. A zero, NaN or infinite vector is a caller error: it asserts in builds with
	/// asserts, and in release builds the vector becomes (1, 0, 0). Tiny (but non-zero) and very long
	/// vectors are normalised correctly by rescaling first.
	SIMD_FORCE_INLINE btVector3& normalize()
	{
		const btScalar l2 = length2();
		if (btLikely(l2 >= SIMD_EPSILON * SIMD_EPSILON && l2 <= SIMD_INFINITY)) return *this /= btSqrt(l2);
		return normalizeSlowPath(true);
	}

	/// A normalised copy (same rules as normalize()).
	SIMD_FORCE_INLINE btVector3 normalized() const;

	/// This vector rotated by angle (radians) about the unit axis wAxis.
	SIMD_FORCE_INLINE btVector3 rotate(const btVector3& wAxis, const btScalar angle) const;

	/// Angle in radians between this and v (0 when either has zero length; asserts in that case).
	SIMD_FORCE_INLINE btScalar angle(const btVector3& v) const
	{
		const btScalar s = btSqrt(length2() * v.length2());
		btAssert(s != btScalar(0.0));
		if (!(s > btScalar(0.0))) return btScalar(0.0);
		return btAcos(dot(v) / s);
	}

	/// Component-wise absolute value.
	SIMD_FORCE_INLINE btVector3 absolute() const
	{
#ifdef BT_USE_SSE
		const __m128 signMask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
		return btVector3(_mm_and_ps(mVec128, signMask));
#else
		return btVector3(btFabs(m_floats[0]), btFabs(m_floats[1]), btFabs(m_floats[2]));
#endif
	}

	/// Cross product; lane by lane the same operations as the scalar formula.
	SIMD_FORCE_INLINE btVector3 cross(const btVector3& v) const
	{
#ifdef BT_USE_SSE
		// c = a * b.yzx - a.yzx * b holds (z, x, y) of the cross product, each lane computed as the
		// scalar formula does; one more shuffle puts it in order. Three shuffles instead of four.
		const __m128 a_yzx = _mm_shuffle_ps(mVec128, mVec128, CALIBER_SHUFFLE(1, 2, 0, 3));
		const __m128 b_yzx = _mm_shuffle_ps(v.mVec128, v.mVec128, CALIBER_SHUFFLE(1, 2, 0, 3));
		const __m128 c = _mm_sub_ps(_mm_mul_ps(mVec128, b_yzx), _mm_mul_ps(a_yzx, v.mVec128));
		const btVector3 result(CALIBER_CLEAR_W(_mm_shuffle_ps(c, c, CALIBER_SHUFFLE(1, 2, 0, 3))));
		return result;
#else
		return btVector3(m_floats[1] * v.m_floats[2] - m_floats[2] * v.m_floats[1],
		                 m_floats[2] * v.m_floats[0] - m_floats[0] * v.m_floats[2],
		                 m_floats[0] * v.m_floats[1] - m_floats[1] * v.m_floats[0]);
#endif
	}

	/// Scalar triple product this . (v1 x v2).
	SIMD_FORCE_INLINE btScalar triple(const btVector3& v1, const btVector3& v2) const { return dot(v1.cross(v2)); }

	/// Index (0, 1 or 2) of the smallest component.
	SIMD_FORCE_INLINE int minAxis() const
	{
		return m_floats[0] < m_floats[1] ? (m_floats[0] < m_floats[2] ? 0 : 2) : (m_floats[1] < m_floats[2] ? 1 : 2);
	}
	/// Index (0, 1 or 2) of the largest component.
	SIMD_FORCE_INLINE int maxAxis() const
	{
		return m_floats[0] < m_floats[1] ? (m_floats[1] < m_floats[2] ? 2 : 1) : (m_floats[0] < m_floats[2] ? 2 : 0);
	}
	/// Index of the component with the smallest magnitude (Bullet's naming).
	SIMD_FORCE_INLINE int furthestAxis() const { return absolute().minAxis(); }
	/// Index of the component with the largest magnitude (Bullet's naming).
	SIMD_FORCE_INLINE int closestAxis() const { return absolute().maxAxis(); }

	/// this = v0 * (1 - rt) + v1 * rt.
	SIMD_FORCE_INLINE void setInterpolate3(const btVector3& v0, const btVector3& v1, btScalar rt)
	{
		const btScalar s = btScalar(1.0) - rt;
		m_floats[0] = s * v0.m_floats[0] + rt * v1.m_floats[0];
		m_floats[1] = s * v0.m_floats[1] + rt * v1.m_floats[1];
		m_floats[2] = s * v0.m_floats[2] + rt * v1.m_floats[2];
	}

	/// Linear interpolation from this (t = 0) to v (t = 1).
	SIMD_FORCE_INLINE btVector3 lerp(const btVector3& v, const btScalar& t) const
	{
		return btVector3(m_floats[0] + (v.m_floats[0] - m_floats[0]) * t,
		                 m_floats[1] + (v.m_floats[1] - m_floats[1]) * t,
		                 m_floats[2] + (v.m_floats[2] - m_floats[2]) * t);
	}

	SIMD_FORCE_INLINE const btScalar& getX() const { return m_floats[0]; }
	SIMD_FORCE_INLINE const btScalar& getY() const { return m_floats[1]; }
	SIMD_FORCE_INLINE const btScalar& getZ() const { return m_floats[2]; }
	SIMD_FORCE_INLINE void setX(btScalar x) { m_floats[0] = x; }
	SIMD_FORCE_INLINE void setY(btScalar y) { m_floats[1] = y; }
	SIMD_FORCE_INLINE void setZ(btScalar z) { m_floats[2] = z; }
	/// Sets the padding component (btVector4 and plane equations use it).
	SIMD_FORCE_INLINE void setW(btScalar w) { m_floats[3] = w; }
	SIMD_FORCE_INLINE const btScalar& x() const { return m_floats[0]; }
	SIMD_FORCE_INLINE const btScalar& y() const { return m_floats[1]; }
	SIMD_FORCE_INLINE const btScalar& z() const { return m_floats[2]; }
	SIMD_FORCE_INLINE const btScalar& w() const { return m_floats[3]; }

	/// Raw access to the 4 scalars (x, y, z, w).
	SIMD_FORCE_INLINE operator btScalar*() { return &m_floats[0]; }
	SIMD_FORCE_INLINE operator const btScalar*() const { return &m_floats[0]; }

	/// Exact equality of x, y and z (w is padding and ignored).
	SIMD_FORCE_INLINE bool operator==(const btVector3& other) const
	{
		return m_floats[0] == other.m_floats[0] && m_floats[1] == other.m_floats[1] && m_floats[2] == other.m_floats[2];
	}
	SIMD_FORCE_INLINE bool operator!=(const btVector3& other) const { return !(*this == other); }

	/// Component-wise maximum; where a component of either is NaN, other's component is taken.
	SIMD_FORCE_INLINE void setMax(const btVector3& other)
	{
#ifdef BT_USE_SSE
		mVec128 = _mm_max_ps(mVec128, other.mVec128);
#else
		for (int i = 0; i < 4; ++i) m_floats[i] = m_floats[i] > other.m_floats[i] ? m_floats[i] : other.m_floats[i];
#endif
	}
	/// Component-wise minimum; where a component of either is NaN, other's component is taken.
	SIMD_FORCE_INLINE void setMin(const btVector3& other)
	{
#ifdef BT_USE_SSE
		mVec128 = _mm_min_ps(mVec128, other.mVec128);
#else
		for (int i = 0; i < 4; ++i) m_floats[i] = m_floats[i] < other.m_floats[i] ? m_floats[i] : other.m_floats[i];
#endif
	}

	/// Sets x, y, z and w = 0.
	SIMD_FORCE_INLINE void setValue(const btScalar& x, const btScalar& y, const btScalar& z)
	{
#ifdef BT_USE_SSE
		mVec128 = _mm_setr_ps(x, y, z, btScalar(0.));
#else
		m_floats[0] = x;
		m_floats[1] = y;
		m_floats[2] = z;
		m_floats[3] = btScalar(0.);
#endif
	}

	/// The rows of the cross-product matrix [v]x, so that [v]x * u == v.cross(u).
	void getSkewSymmetricMatrix(btVector3 * v0, btVector3 * v1, btVector3 * v2) const
	{
		v0->setValue(0., -z(), y());
		v1->setValue(z(), 0., -x());
		v2->setValue(-y(), x(), 0.);
	}

	/// Sets all four components to 0.
	void setZero()
	{
#ifdef BT_USE_SSE
		mVec128 = _mm_setzero_ps();
#else
		setValue(btScalar(0.), btScalar(0.), btScalar(0.));
#endif
	}
	/// True when x, y and z are exactly 0.
	SIMD_FORCE_INLINE bool isZero() const
	{
		return m_floats[0] == btScalar(0) && m_floats[1] == btScalar(0) && m_floats[2] == btScalar(0);
	}
	/// True when the squared length is below SIMD_EPSILON^2.
	SIMD_FORCE_INLINE bool fuzzyZero() const { return length2() < SIMD_EPSILON * SIMD_EPSILON; }

	/// Index of the array element with the largest dot product with this (the first such index on ties;
	/// NaN products never win); -1 for an empty array. dotOut receives that product (-SIMD_INFINITY if none).
	long maxDot(const btVector3* array, long arrayCount, btScalar& dotOut) const;
	/// Index of the array element with the smallest dot product with this; see maxDot.
	long minDot(const btVector3* array, long arrayCount, btScalar& dotOut) const;

	/// (this . v0, this . v1, this . v2).
	SIMD_FORCE_INLINE btVector3 dot3(const btVector3& v0, const btVector3& v1, const btVector3& v2) const
	{
		return btVector3(dot(v0), dot(v1), dot(v2));
	}

	SIMD_FORCE_INLINE void serialize(struct btVector3Data & dataOut) const;
	SIMD_FORCE_INLINE void deSerialize(const struct btVector3DoubleData& dataIn);
	SIMD_FORCE_INLINE void deSerialize(const struct btVector3FloatData& dataIn);
	SIMD_FORCE_INLINE void serializeFloat(struct btVector3FloatData & dataOut) const;
	SIMD_FORCE_INLINE void deSerializeFloat(const struct btVector3FloatData& dataIn);
	SIMD_FORCE_INLINE void serializeDouble(struct btVector3DoubleData & dataOut) const;
	SIMD_FORCE_INLINE void deSerializeDouble(const struct btVector3DoubleData& dataIn);

private:
	// Zero, tiny, huge or non-finite input to normalize()/safeNormalize(); out of line, rarely taken.
	btVector3& normalizeSlowPath(bool assertOnDegenerate);
};

// ---- free operators -------------------------------------------------------------------------------

SIMD_FORCE_INLINE btVector3 operator+(const btVector3& v1, const btVector3& v2)
{
	btVector3 r = v1;
	return r += v2;
}
/// Component-wise product.
SIMD_FORCE_INLINE btVector3 operator*(const btVector3& v1, const btVector3& v2)
{
	btVector3 r = v1;
	return r *= v2;
}
SIMD_FORCE_INLINE btVector3 operator-(const btVector3& v1, const btVector3& v2)
{
	btVector3 r = v1;
	return r -= v2;
}
SIMD_FORCE_INLINE btVector3 operator-(const btVector3& v)
{
#ifdef BT_USE_SSE
	const __m128 signBit = _mm_castsi128_ps(_mm_set1_epi32(int(0x80000000u)));
	return btVector3(CALIBER_CLEAR_W(_mm_xor_ps(v.mVec128, signBit)));
#else
	return btVector3(-v.m_floats[0], -v.m_floats[1], -v.m_floats[2]);
#endif
}
SIMD_FORCE_INLINE btVector3 operator*(const btVector3& v, const btScalar& s)
{
	btVector3 r = v;
	return r *= s;
}
SIMD_FORCE_INLINE btVector3 operator*(const btScalar& s, const btVector3& v) { return v * s; }
/// Divides each component by s.
SIMD_FORCE_INLINE btVector3 operator/(const btVector3& v, const btScalar& s)
{
	btVector3 r = v;
	return r /= s;
}
/// Component-wise quotient (w of the result is 0).
SIMD_FORCE_INLINE btVector3 operator/(const btVector3& v1, const btVector3& v2)
{
#ifdef BT_USE_SSE
	return btVector3(CALIBER_CLEAR_W(_mm_div_ps(v1.mVec128, v2.mVec128)));
#else
	return btVector3(v1.m_floats[0] / v2.m_floats[0], v1.m_floats[1] / v2.m_floats[1], v1.m_floats[2] / v2.m_floats[2]);
#endif
}

SIMD_FORCE_INLINE btScalar btDot(const btVector3& v1, const btVector3& v2) { return v1.dot(v2); }
SIMD_FORCE_INLINE btScalar btDistance2(const btVector3& v1, const btVector3& v2) { return v1.distance2(v2); }
SIMD_FORCE_INLINE btScalar btDistance(const btVector3& v1, const btVector3& v2) { return v1.distance(v2); }
SIMD_FORCE_INLINE btScalar btAngle(const btVector3& v1, const btVector3& v2) { return v1.angle(v2); }
SIMD_FORCE_INLINE btVector3 btCross(const btVector3& v1, const btVector3& v2) { return v1.cross(v2); }
SIMD_FORCE_INLINE btScalar btTriple(const btVector3& v1, const btVector3& v2, const btVector3& v3)
{
	return v1.triple(v2, v3);
}
/// Linear interpolation from v1 (t = 0) to v2 (t = 1).
SIMD_FORCE_INLINE btVector3 lerp(const btVector3& v1, const btVector3& v2, const btScalar& t) { return v1.lerp(v2, t); }

SIMD_FORCE_INLINE btScalar btVector3::distance2(const btVector3& v) const { return (v - *this).length2(); }
SIMD_FORCE_INLINE btScalar btVector3::distance(const btVector3& v) const { return (v - *this).length(); }

SIMD_FORCE_INLINE btVector3 btVector3::normalized() const
{
	btVector3 copy = *this;
	return copy.normalize();
}

SIMD_FORCE_INLINE btVector3 btVector3::rotate(const btVector3& wAxis, const btScalar rotationAngle) const
{
	// Rodrigues: keep the part along the axis, turn the perpendicular part in the plane it spans
	// with axis x this.
	const btVector3 alongAxis = wAxis * wAxis.dot(*this);
	const btVector3 perpendicular = *this - alongAxis;
	const btVector3 turned = wAxis.cross(*this);
	return alongAxis + perpendicular * btCos(rotationAngle) + turned * btSin(rotationAngle);
}

/// A btVector3 whose fourth component is meaningful (colours, plane equations).
ATTRIBUTE_ALIGNED16(class)
btVector4 : public btVector3{public : SIMD_FORCE_INLINE btVector4(){} SIMD_FORCE_INLINE btVector4(
	            const btScalar& x, const btScalar& y, const btScalar& z, const btScalar& w){setValue(x, y, z, w);
}
#ifdef BT_USE_SSE
SIMD_FORCE_INLINE btVector4(const btSimdFloat4 v128) : btVector3(v128) {}
#endif
SIMD_FORCE_INLINE btVector4(const btVector3& v) : btVector3(v) {}

/// Component-wise absolute value of all four components.
SIMD_FORCE_INLINE btVector4 absolute4() const
{
	return btVector4(btFabs(m_floats[0]), btFabs(m_floats[1]), btFabs(m_floats[2]), btFabs(m_floats[3]));
}
btScalar getW() const { return m_floats[3]; }

/// Index (0..3) of the largest of the four components.
SIMD_FORCE_INLINE int maxAxis4() const
{
	int best = 0;
	for (int i = 1; i < 4; ++i)
		if (m_floats[i] > m_floats[best]) best = i;
	return best;
}
/// Index (0..3) of the smallest of the four components.
SIMD_FORCE_INLINE int minAxis4() const
{
	int best = 0;
	for (int i = 1; i < 4; ++i)
		if (m_floats[i] < m_floats[best]) best = i;
	return best;
}
/// Index of the component with the largest magnitude.
SIMD_FORCE_INLINE int closestAxis4() const { return absolute4().maxAxis4(); }

/// Sets all four components.
SIMD_FORCE_INLINE void setValue(const btScalar& x, const btScalar& y, const btScalar& z, const btScalar& w)
{
#ifdef BT_USE_SSE
	mVec128 = _mm_setr_ps(x, y, z, w);
#else
	m_floats[0] = x;
	m_floats[1] = y;
	m_floats[2] = z;
	m_floats[3] = w;
#endif
}

/// Exact equality of all four components.
SIMD_FORCE_INLINE bool operator==(const btVector4& other) const
{
	return btVector3::operator==(other) && m_floats[3] == other.m_floats[3];
}
SIMD_FORCE_INLINE bool operator!=(const btVector4& other) const { return !(*this == other); }
}
;

/// Reverses the byte order of one scalar (for reading data written on another machine).
SIMD_FORCE_INLINE void btSwapScalarEndian(const btScalar& sourceVal, btScalar& destVal)
{
	const unsigned char* src = reinterpret_cast<const unsigned char*>(&sourceVal);
	unsigned char* dst = reinterpret_cast<unsigned char*>(&destVal);
	for (size_t i = 0; i < sizeof(btScalar); ++i) dst[i] = src[sizeof(btScalar) - 1 - i];
}
/// Reverses the byte order of each component of a vector.
SIMD_FORCE_INLINE void btSwapVector3Endian(const btVector3& sourceVec, btVector3& destVec)
{
	for (int i = 0; i < 4; ++i) btSwapScalarEndian(sourceVec[i], destVec[i]);
}
/// In-place version of btSwapVector3Endian.
SIMD_FORCE_INLINE void btUnSwapVector3Endian(btVector3& vector)
{
	btVector3 swapped;
	btSwapVector3Endian(vector, swapped);
	vector = swapped;
}

/// Given a unit vector n, makes p and q so that (n, p, q) is an orthonormal right-handed basis.
template <class T>
SIMD_FORCE_INLINE void btPlaneSpace1(const T& n, T& p, T& q)
{
	// p lies in the coordinate plane that drops axis `dropped`: x when n leans towards z, z otherwise,
	// so that n's projection onto that plane (squared length a) is never short. (dropped, first, second)
	// is a cyclic order of the axes, which makes q = n x p come out with the signs below.
	const int dropped = btFabs(n[2]) > SIMDSQRT12 ? 0 : 2;
	const int first = dropped == 0 ? 1 : 0;
	const int second = dropped == 0 ? 2 : 1;
	const btScalar a = n[first] * n[first] + n[second] * n[second];
	const btScalar k = btRecipSqrt(a);
	p[dropped] = 0;
	p[first] = -n[second] * k;
	p[second] = n[first] * k;
	q[dropped] = a * k;
	q[first] = -n[dropped] * p[second];
	q[second] = n[dropped] * p[first];
}

/// Serialised form of a vector in single precision.
struct btVector3FloatData
{
	float m_floats[4];
};
/// Serialised form of a vector in double precision.
struct btVector3DoubleData
{
	double m_floats[4];
};

SIMD_FORCE_INLINE void btVector3::serializeFloat(struct btVector3FloatData& dataOut) const
{
	for (int i = 0; i < 4; ++i) dataOut.m_floats[i] = float(m_floats[i]);
}
SIMD_FORCE_INLINE void btVector3::deSerializeFloat(const struct btVector3FloatData& dataIn)
{
	for (int i = 0; i < 4; ++i) m_floats[i] = btScalar(dataIn.m_floats[i]);
}
SIMD_FORCE_INLINE void btVector3::serializeDouble(struct btVector3DoubleData& dataOut) const
{
	for (int i = 0; i < 4; ++i) dataOut.m_floats[i] = double(m_floats[i]);
}
SIMD_FORCE_INLINE void btVector3::deSerializeDouble(const struct btVector3DoubleData& dataIn)
{
	for (int i = 0; i < 4; ++i) m_floats[i] = btScalar(dataIn.m_floats[i]);
}
SIMD_FORCE_INLINE void btVector3::serialize(struct btVector3Data& dataOut) const
{
	for (int i = 0; i < 4; ++i) dataOut.m_floats[i] = m_floats[i];
}
SIMD_FORCE_INLINE void btVector3::deSerialize(const struct btVector3FloatData& dataIn) { deSerializeFloat(dataIn); }
SIMD_FORCE_INLINE void btVector3::deSerialize(const struct btVector3DoubleData& dataIn) { deSerializeDouble(dataIn); }

namespace caliber
{
/// x - x for every component, summed: exactly 0 when all are finite, NaN when any is NaN or infinite
/// (inf - inf is NaN and NaN spreads through the sum, which cannot overflow). One compare instead of a
/// branch per component: the test runs for every contact point and body pose of a step.
SIMD_FORCE_INLINE btScalar nonFiniteResidue(const btVector3& v)
{
	return (v.x() - v.x()) + (v.y() - v.y()) + (v.z() - v.z());
}
#ifdef BT_USE_SSE
/// The residues v - v of x, y and z side by side: each 0 when finite, NaN when not (w is not read).
SIMD_FORCE_INLINE __m128 nonFiniteResidues(const btVector3& v) { return _mm_sub_ps(v.get128(), v.get128()); }
/// True when the x, y and z lanes of residues are all 0.
SIMD_FORCE_INLINE bool residuesAreZero(__m128 residues)
{
	return (_mm_movemask_ps(_mm_cmpeq_ps(residues, _mm_setzero_ps())) & 7) == 7;
}
#endif
/// True when x, y and z are all finite (not NaN, not infinite); the unused fourth lane is not read.
SIMD_FORCE_INLINE bool isFinite(const btVector3& v)
{
#ifdef BT_USE_SSE
	return residuesAreZero(nonFiniteResidues(v));
#else
	return nonFiniteResidue(v) == btScalar(0);
#endif
}
}  // namespace caliber

#endif  // BT_VECTOR3_H
