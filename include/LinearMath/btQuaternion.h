// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SIMD__QUATERNION_H_
#define BT_SIMD__QUATERNION_H_

/// btQuaternion: rotations as unit quaternions (x, y, z, w), with Bullet's Euler conventions.

#include "LinearMath/btVector3.h"
#include "LinearMath/btQuadWord.h"

#ifdef BT_USE_DOUBLE_PRECISION
#define btQuaternionData btQuaternionDoubleData
#define btQuaternionDataName "btQuaternionDoubleData"
#else
#define btQuaternionData btQuaternionFloatData
#define btQuaternionDataName "btQuaternionFloatData"
#endif

struct btQuaternionFloatData;
struct btQuaternionDoubleData;

/// A quaternion x i + y j + z k + w; unit quaternions represent rotations.
class btQuaternion : public btQuadWord
{
public:
	/// Uninitialised.
	btQuaternion() {}
#ifdef BT_USE_SSE
	SIMD_FORCE_INLINE btQuaternion(const __m128 v128) : btQuadWord(v128) {}
#endif
	/// From the four components.
	btQuaternion(const btScalar& x, const btScalar& y, const btScalar& z, const btScalar& w) : btQuadWord(x, y, z, w) {}
	/// Rotation of angle radians about axis (need not be unit length; must not be zero).
	btQuaternion(const btVector3& axis, const btScalar& angle) { setRotation(axis, angle); }
	/// From Euler angles: yaw about Y, pitch about X, roll about Z (setEuler), or Z-Y-X when the
	/// program defines BT_EULER_DEFAULT_ZYX, as in Bullet.
	btQuaternion(const btScalar& yaw, const btScalar& pitch, const btScalar& roll)
	{
#ifndef BT_EULER_DEFAULT_ZYX
		setEuler(yaw, pitch, roll);
#else
		setEulerZYX(yaw, pitch, roll);
#endif
	}

	/// Rotation of angle radians about axis. A zero axis asserts; in release builds it gives the identity.
	void setRotation(const btVector3& axis, const btScalar& angle)
	{
		const btScalar axisLength = axis.length();
		btAssert(axisLength != btScalar(0.0));
		if (!(axisLength > btScalar(0.0)))
		{
			setValue(btScalar(0), btScalar(0), btScalar(0), btScalar(1));
			return;
		}
		const btScalar s = btSin(angle * btScalar(0.5)) / axisLength;
		setValue(axis.x() * s, axis.y() * s, axis.z() * s, btCos(angle * btScalar(0.5)));
	}

	/// q = qY(yaw) * qX(pitch) * qZ(roll): roll about Z first, then pitch about X, then yaw about Y.
	void setEuler(const btScalar& yaw, const btScalar& pitch, const btScalar& roll)
	{
		const btQuaternion aboutY(btScalar(0), btSin(yaw * btScalar(0.5)), btScalar(0), btCos(yaw * btScalar(0.5)));
		const btQuaternion aboutX(btSin(pitch * btScalar(0.5)), btScalar(0), btScalar(0), btCos(pitch * btScalar(0.5)));
		const btQuaternion aboutZ(btScalar(0), btScalar(0), btSin(roll * btScalar(0.5)), btCos(roll * btScalar(0.5)));
		*this = aboutY;
		*this *= aboutX;
		*this *= aboutZ;
	}

	/// q = qZ(yawZ) * qY(pitchY) * qX(rollX): about X first, then Y, then Z.
	void setEulerZYX(const btScalar& yawZ, const btScalar& pitchY, const btScalar& rollX)
	{
		const btQuaternion aboutZ(btScalar(0), btScalar(0), btSin(yawZ * btScalar(0.5)), btCos(yawZ * btScalar(0.5)));
		const btQuaternion aboutY(btScalar(0), btSin(pitchY * btScalar(0.5)), btScalar(0),
		                          btCos(pitchY * btScalar(0.5)));
		const btQuaternion aboutX(btSin(rollX * btScalar(0.5)), btScalar(0), btScalar(0), btCos(rollX * btScalar(0.5)));
		*this = aboutZ;
		*this *= aboutY;
		*this *= aboutX;
	}

	/// Inverse of setEulerZYX for a unit quaternion; at gimbal lock (pitch +-pi/2) rollX is 0.
	void getEulerZYX(btScalar& yawZ, btScalar& pitchY, btScalar& rollX) const;

	SIMD_FORCE_INLINE btQuaternion& operator+=(const btQuaternion& q)
	{
#ifdef BT_USE_SSE
		mVec128 = _mm_add_ps(mVec128, q.mVec128);
#else
		for (int i = 0; i < 4; ++i) m_floats[i] += q.m_floats[i];
#endif
		return *this;
	}
	btQuaternion& operator-=(const btQuaternion& q)
	{
#ifdef BT_USE_SSE
		mVec128 = _mm_sub_ps(mVec128, q.mVec128);
#else
		for (int i = 0; i < 4; ++i) m_floats[i] -= q.m_floats[i];
#endif
		return *this;
	}
	btQuaternion& operator*=(const btScalar& s)
	{
#ifdef BT_USE_SSE
		mVec128 = _mm_mul_ps(mVec128, _mm_set1_ps(s));
#else
		for (int i = 0; i < 4; ++i) m_floats[i] *= s;
#endif
		return *this;
	}

	/// Hamilton product: this = this * q (apply q first, then this).
	btQuaternion& operator*=(const btQuaternion& q)
	{
#ifdef BT_USE_SSE
		// Each lane performs the scalar formula's operations in the same order (see the #else branch):
		// ((A + B') + C') - D, where ' negates the w lane.
		const __m128 a = mVec128;
		const __m128 b = q.mVec128;
		const __m128 negW = _mm_castsi128_ps(_mm_setr_epi32(0, 0, 0, int(0x80000000u)));
		const __m128 termA = _mm_mul_ps(_mm_shuffle_ps(a, a, CALIBER_SHUFFLE(3, 3, 3, 3)), b);
		const __m128 termB = _mm_mul_ps(_mm_shuffle_ps(a, a, CALIBER_SHUFFLE(0, 1, 2, 0)),
		                                _mm_shuffle_ps(b, b, CALIBER_SHUFFLE(3, 3, 3, 0)));
		const __m128 termC = _mm_mul_ps(_mm_shuffle_ps(a, a, CALIBER_SHUFFLE(1, 2, 0, 1)),
		                                _mm_shuffle_ps(b, b, CALIBER_SHUFFLE(2, 0, 1, 1)));
		const __m128 termD = _mm_mul_ps(_mm_shuffle_ps(a, a, CALIBER_SHUFFLE(2, 0, 1, 2)),
		                                _mm_shuffle_ps(b, b, CALIBER_SHUFFLE(1, 2, 0, 2)));
		mVec128 = _mm_sub_ps(_mm_add_ps(_mm_add_ps(termA, _mm_xor_ps(termB, negW)), _mm_xor_ps(termC, negW)), termD);
#else
		const btScalar ax = m_floats[0], ay = m_floats[1], az = m_floats[2], aw = m_floats[3];
		const btScalar bx = q.x(), by = q.y(), bz = q.z(), bw = q.w();
		setValue(aw * bx + ax * bw + ay * bz - az * by, aw * by + ay * bw + az * bx - ax * bz,
		         aw * bz + az * bw + ax * by - ay * bx, aw * bw - ax * bx - ay * by - az * bz);
#endif
		return *this;
	}

	/// Four-component dot product.
	btScalar dot(const btQuaternion& q) const
	{
		return m_floats[0] * q.x() + m_floats[1] * q.y() + m_floats[2] * q.z() + m_floats[3] * q.w();
	}
	btScalar length2() const { return dot(*this); }
	btScalar length() const { return btSqrt(length2()); }

	/// Normalises when the length exceeds SIMD_EPSILON; otherwise leaves the quaternion unchanged.
	btQuaternion& safeNormalize()
	{
		const btScalar l = length();
		if (l > SIMD_EPSILON) return *this /= l;
		return *this;
	}

	/// Makes the length 1. A zero or non-finite quaternion asserts; release builds set the identity.
	btQuaternion& normalize()
	{
		const btScalar l = length();
		btAssert(l > btScalar(0) && l <= SIMD_INFINITY);
		if (btUnlikely(!(l > btScalar(0) && l <= SIMD_INFINITY)))
		{
			setValue(btScalar(0), btScalar(0), btScalar(0), btScalar(1));
			return *this;
		}
		return *this /= l;
	}

	SIMD_FORCE_INLINE btQuaternion operator*(const btScalar& s) const
	{
		btQuaternion r = *this;
		return r *= s;
	}
	btQuaternion operator/(const btScalar& s) const
	{
		btQuaternion r = *this;
		return r /= s;
	}
	/// Divides each component by s (must not be 0).
	btQuaternion& operator/=(const btScalar& s)
	{
		btAssert(s != btScalar(0.0));
		for (int i = 0; i < 4; ++i) m_floats[i] /= s;
		return *this;
	}
	/// A normalised copy.
	btQuaternion normalized() const
	{
		btQuaternion r = *this;
		return r.normalize();
	}

	/// Half the rotation angle between this and q (Bullet's definition), in [0, pi].
	btScalar angle(const btQuaternion& q) const
	{
		const btScalar s = btSqrt(length2() * q.length2());
		btAssert(s != btScalar(0.0));
		if (!(s > btScalar(0.0))) return btScalar(0.0);
		return btAcos(dot(q) / s);
	}
	/// The rotation angle from this to q along the shortest path, in [0, pi].
	btScalar angleShortestPath(const btQuaternion& q) const
	{
		const btScalar s = btSqrt(length2() * q.length2());
		btAssert(s != btScalar(0.0));
		if (!(s > btScalar(0.0))) return btScalar(0.0);
		return btAcos(btFabs(dot(q)) / s) * btScalar(2.0);
	}
	/// Rotation angle in [0, 2 pi].
	btScalar getAngle() const { return btScalar(2.) * btAcos(m_floats[3]); }
	/// Rotation angle in [0, pi] (the shorter way round).
	btScalar getAngleShortestPath() const { return btScalar(2.) * btAcos(btFabs(m_floats[3])); }
	/// Unit rotation axis; (1, 0, 0) when the rotation is (nearly) the identity.
	btVector3 getAxis() const
	{
		const btScalar s2 = btScalar(1.) - m_floats[3] * m_floats[3];
		if (s2 < btScalar(10.) * SIMD_EPSILON) return btVector3(1.0, 0.0, 0.0);
		const btScalar invS = btScalar(1.) / btSqrt(s2);
		return btVector3(m_floats[0] * invS, m_floats[1] * invS, m_floats[2] * invS);
	}
	/// The conjugate, which is the inverse rotation for a unit quaternion.
	btQuaternion inverse() const { return btQuaternion(-m_floats[0], -m_floats[1], -m_floats[2], m_floats[3]); }

	SIMD_FORCE_INLINE btQuaternion operator+(const btQuaternion& q) const
	{
		btQuaternion r = *this;
		return r += q;
	}
	SIMD_FORCE_INLINE btQuaternion operator-(const btQuaternion& q) const
	{
		btQuaternion r = *this;
		return r -= q;
	}
	SIMD_FORCE_INLINE btQuaternion operator-() const
	{
		return btQuaternion(-m_floats[0], -m_floats[1], -m_floats[2], -m_floats[3]);
	}
	/// qd or -qd (same rotation), whichever is further from this.
	SIMD_FORCE_INLINE btQuaternion farthest(const btQuaternion& qd) const
	{
		const btQuaternion diff = *this - qd, sum = *this + qd;
		return diff.dot(diff) > sum.dot(sum) ? qd : (-qd);
	}
	/// qd or -qd (same rotation), whichever is nearer to this.
	SIMD_FORCE_INLINE btQuaternion nearest(const btQuaternion& qd) const
	{
		const btQuaternion diff = *this - qd, sum = *this + qd;
		return diff.dot(diff) < sum.dot(sum) ? qd : (-qd);
	}

	/// Spherical linear interpolation from this (t = 0) to q (t = 1) along the shorter arc.
	btQuaternion slerp(const btQuaternion& q, const btScalar& t) const;

	/// The identity rotation.
	static const btQuaternion& getIdentity()
	{
		static const btQuaternion identity(btScalar(0.), btScalar(0.), btScalar(0.), btScalar(1.));
		return identity;
	}

	SIMD_FORCE_INLINE const btScalar& getW() const { return m_floats[3]; }

	SIMD_FORCE_INLINE void serialize(struct btQuaternionData& dataOut) const;
	SIMD_FORCE_INLINE void deSerialize(const struct btQuaternionFloatData& dataIn);
	SIMD_FORCE_INLINE void deSerialize(const struct btQuaternionDoubleData& dataIn);
	SIMD_FORCE_INLINE void serializeFloat(struct btQuaternionFloatData& dataOut) const;
	SIMD_FORCE_INLINE void deSerializeFloat(const struct btQuaternionFloatData& dataIn);
	SIMD_FORCE_INLINE void serializeDouble(struct btQuaternionDoubleData& dataOut) const;
	SIMD_FORCE_INLINE void deSerializeDouble(const struct btQuaternionDoubleData& dataIn);
};

/// Hamilton product q1 * q2 (rotate by q2, then by q1).
SIMD_FORCE_INLINE btQuaternion operator*(const btQuaternion& q1, const btQuaternion& q2)
{
	btQuaternion r = q1;
	return r *= q2;
}

/// q * (v, 0).
SIMD_FORCE_INLINE btQuaternion operator*(const btQuaternion& q, const btVector3& v)
{
	return btQuaternion(q.w() * v.x() + q.y() * v.z() - q.z() * v.y(), q.w() * v.y() + q.z() * v.x() - q.x() * v.z(),
	                    q.w() * v.z() + q.x() * v.y() - q.y() * v.x(), -q.x() * v.x() - q.y() * v.y() - q.z() * v.z());
}

/// (v, 0) * q.
SIMD_FORCE_INLINE btQuaternion operator*(const btVector3& v, const btQuaternion& q)
{
	return btQuaternion(v.x() * q.w() + v.y() * q.z() - v.z() * q.y(), v.y() * q.w() + v.z() * q.x() - v.x() * q.z(),
	                    v.z() * q.w() + v.x() * q.y() - v.y() * q.x(), -v.x() * q.x() - v.y() * q.y() - v.z() * q.z());
}

SIMD_FORCE_INLINE btScalar dot(const btQuaternion& q1, const btQuaternion& q2) { return q1.dot(q2); }
SIMD_FORCE_INLINE btScalar length(const btQuaternion& q) { return q.length(); }
/// Half the angle between two rotations (see btQuaternion::angle).
SIMD_FORCE_INLINE btScalar btAngle(const btQuaternion& q1, const btQuaternion& q2) { return q1.angle(q2); }
SIMD_FORCE_INLINE btQuaternion inverse(const btQuaternion& q) { return q.inverse(); }
SIMD_FORCE_INLINE btQuaternion slerp(const btQuaternion& q1, const btQuaternion& q2, const btScalar& t)
{
	return q1.slerp(q2, t);
}

/// v rotated by the unit quaternion rotation (rotation * v * rotation^-1).
SIMD_FORCE_INLINE btVector3 quatRotate(const btQuaternion& rotation, const btVector3& v)
{
	// v' = v + w t + u x t with u the vector part and t = 2 u x v: the sandwich product expanded.
	const btVector3 u(rotation.x(), rotation.y(), rotation.z());
	const btVector3 t = btScalar(2) * u.cross(v);
	return v + rotation.w() * t + u.cross(t);
}

/// The shortest rotation taking unit vector v0 to unit vector v1; for opposite vectors, a half
/// turn about an axis perpendicular to v0.
SIMD_FORCE_INLINE btQuaternion shortestArcQuat(const btVector3& v0, const btVector3& v1)
{
	const btVector3 c = v0.cross(v1);
	const btScalar d = v0.dot(v1);
	if (d < -btScalar(1.0) + SIMD_EPSILON)
	{
		btVector3 n, unused;
		btPlaneSpace1(v0, n, unused);
		return btQuaternion(n.x(), n.y(), n.z(), btScalar(0.0));
	}
	// The half-way quaternion: (c, 1 + d) normalised, since |c|^2 + (1 + d)^2 = 2 (1 + d).
	const btScalar s = btSqrt((btScalar(1.0) + d) * btScalar(2.0));
	const btScalar rs = btScalar(1.0) / s;
	return btQuaternion(c.x() * rs, c.y() * rs, c.z() * rs, s * btScalar(0.5));
}

/// shortestArcQuat of the normalised inputs.
SIMD_FORCE_INLINE btQuaternion shortestArcQuatNormalize2(btVector3& v0, btVector3& v1)
{
	v0.normalize();
	v1.normalize();
	return shortestArcQuat(v0, v1);
}

inline btQuaternion btQuaternion::slerp(const btQuaternion& q, const btScalar& t) const
{
	const btScalar magnitude = btSqrt(length2() * q.length2());
	btAssert(magnitude > btScalar(0));
	if (!(magnitude > btScalar(0))) return *this;
	btScalar cosTheta = dot(q) / magnitude;
	// q and -q are the same rotation; interpolate towards the one on this side of the sphere.
	const btScalar sign = cosTheta < btScalar(0) ? btScalar(-1) : btScalar(1);
	cosTheta *= sign;
	btScalar weightThis, weightOther;
	if (cosTheta < btScalar(1.0) - btScalar(8) * SIMD_EPSILON)
	{
		const btScalar theta = btAcos(cosTheta);
		const btScalar invSinTheta = btScalar(1.0) / btSin(theta);
		weightThis = btSin((btScalar(1.0) - t) * theta) * invSinTheta;
		weightOther = btSin(t * theta) * invSinTheta;
	}
	else
	{
		// Nearly the same rotation: sin(t theta) / sin(theta) -> t, so the weights become linear.
		weightThis = btScalar(1.0) - t;
		weightOther = t;
	}
	weightOther *= sign;
	return btQuaternion(m_floats[0] * weightThis + q.x() * weightOther, m_floats[1] * weightThis + q.y() * weightOther,
	                    m_floats[2] * weightThis + q.z() * weightOther, m_floats[3] * weightThis + q.w() * weightOther);
}

inline void btQuaternion::getEulerZYX(btScalar& yawZ, btScalar& pitchY, btScalar& rollX) const
{
	// Entries of the rotation matrix R = Rz(yaw) Ry(pitch) Rx(roll) written in quaternion terms.
	const btScalar qx = m_floats[0], qy = m_floats[1], qz = m_floats[2], qw = m_floats[3];
	const btScalar sinPitch = btScalar(-2.) * (qx * qz - qw * qy);  // -R[2][0]
	if (btFabs(sinPitch) >= btScalar(0.99999))
	{
		// Gimbal lock: roll and yaw turn about the same axis; fold the whole turn into yaw.
		pitchY = sinPitch > 0 ? SIMD_HALF_PI : -SIMD_HALF_PI;
		rollX = btScalar(0.);
		const btScalar r01 = btScalar(2.) * (qx * qy - qw * qz);
		const btScalar r11 = qw * qw - qx * qx + qy * qy - qz * qz;
		yawZ = btAtan2(-r01, r11);
		return;
	}
	pitchY = btAsin(sinPitch);
	rollX = btAtan2(btScalar(2.) * (qy * qz + qw * qx), qw * qw - qx * qx - qy * qy + qz * qz);
	yawZ = btAtan2(btScalar(2.) * (qx * qy + qw * qz), qw * qw + qx * qx - qy * qy - qz * qz);
}

/// Serialised form of a quaternion in single precision.
struct btQuaternionFloatData
{
	float m_floats[4];
};
/// Serialised form of a quaternion in double precision.
struct btQuaternionDoubleData
{
	double m_floats[4];
};

SIMD_FORCE_INLINE void btQuaternion::serializeFloat(struct btQuaternionFloatData& dataOut) const
{
	for (int i = 0; i < 4; ++i) dataOut.m_floats[i] = float(m_floats[i]);
}
SIMD_FORCE_INLINE void btQuaternion::deSerializeFloat(const struct btQuaternionFloatData& dataIn)
{
	for (int i = 0; i < 4; ++i) m_floats[i] = btScalar(dataIn.m_floats[i]);
}
SIMD_FORCE_INLINE void btQuaternion::serializeDouble(struct btQuaternionDoubleData& dataOut) const
{
	for (int i = 0; i < 4; ++i) dataOut.m_floats[i] = double(m_floats[i]);
}
SIMD_FORCE_INLINE void btQuaternion::deSerializeDouble(const struct btQuaternionDoubleData& dataIn)
{
	for (int i = 0; i < 4; ++i) m_floats[i] = btScalar(dataIn.m_floats[i]);
}
SIMD_FORCE_INLINE void btQuaternion::serialize(struct btQuaternionData& dataOut) const
{
	for (int i = 0; i < 4; ++i) dataOut.m_floats[i] = m_floats[i];
}
SIMD_FORCE_INLINE void btQuaternion::deSerialize(const struct btQuaternionFloatData& dataIn)
{
	deSerializeFloat(dataIn);
}
SIMD_FORCE_INLINE void btQuaternion::deSerialize(const struct btQuaternionDoubleData& dataIn)
{
	deSerializeDouble(dataIn);
}

#endif  // BT_SIMD__QUATERNION_H_
