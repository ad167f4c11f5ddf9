// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SIMD_QUADWORD_H
#define BT_SIMD_QUADWORD_H

/// btQuadWord: four scalars, 16-byte aligned; the base of btQuaternion.

#include "LinearMath/btScalar.h"
#include "LinearMath/btMinMax.h"
#include "LinearMath/btAlignedAllocator.h"

/// Four scalars (x, y, z, w) with the alignment and SIMD layout of btVector3.
ATTRIBUTE_ALIGNED16(class)
btQuadWord
{
protected:
#ifdef BT_USE_SSE
	union
	{
		__m128 mVec128;
		btScalar m_floats[4];
	};

public:
	/// The SIMD register holding x, y, z, w.
	SIMD_FORCE_INLINE __m128 get128() const { return mVec128; }
	/// Sets all four lanes from a SIMD register.
	SIMD_FORCE_INLINE void set128(__m128 v128) { mVec128 = v128; }
	/// Wraps a SIMD register.
	SIMD_FORCE_INLINE btQuadWord(const __m128 v128) { mVec128 = v128; }
#else
	btScalar m_floats[4];
#endif

public:
	SIMD_FORCE_INLINE const btScalar& getX() const { return m_floats[0]; }
	SIMD_FORCE_INLINE const btScalar& getY() const { return m_floats[1]; }
	SIMD_FORCE_INLINE const btScalar& getZ() const { return m_floats[2]; }
	SIMD_FORCE_INLINE void setX(btScalar x) { m_floats[0] = x; }
	SIMD_FORCE_INLINE void setY(btScalar y) { m_floats[1] = y; }
	SIMD_FORCE_INLINE void setZ(btScalar z) { m_floats[2] = z; }
	SIMD_FORCE_INLINE void setW(btScalar w) { m_floats[3] = w; }
	SIMD_FORCE_INLINE const btScalar& x() const { return m_floats[0]; }
	SIMD_FORCE_INLINE const btScalar& y() const { return m_floats[1]; }
	SIMD_FORCE_INLINE const btScalar& z() const { return m_floats[2]; }
	SIMD_FORCE_INLINE const btScalar& w() const { return m_floats[3]; }

	/// Raw access to the four scalars.
	SIMD_FORCE_INLINE operator btScalar*() { return &m_floats[0]; }
	SIMD_FORCE_INLINE operator const btScalar*() const { return &m_floats[0]; }

	/// Exact equality of all four components.
	SIMD_FORCE_INLINE bool operator==(const btQuadWord& other) const
	{
		return m_floats[0] == other.m_floats[0] && m_floats[1] == other.m_floats[1] &&
		       m_floats[2] == other.m_floats[2] && m_floats[3] == other.m_floats[3];
	}
	SIMD_FORCE_INLINE bool operator!=(const btQuadWord& other) const { return !(*this == other); }

	/// Sets x, y, z and w = 0.
	SIMD_FORCE_INLINE void setValue(const btScalar& x, const btScalar& y, const btScalar& z)
	{
		setValue(x, y, z, btScalar(0));
	}
	/// Sets all four components.
	SIMD_FORCE_INLINE void setValue(const btScalar& x, const btScalar& y, const btScalar& z, const btScalar& w)
	{
#ifdef BT_USE_SSE
		// Built in a register: four scalar stores read back as one vector would stall store forwarding.
		mVec128 = _mm_setr_ps(x, y, z, w);
#else
		m_floats[0] = x;
		m_floats[1] = y;
		m_floats[2] = z;
		m_floats[3] = w;
#endif
	}

	/// Uninitialised.
	SIMD_FORCE_INLINE btQuadWord() {}
	/// (x, y, z) with w = 0.
	SIMD_FORCE_INLINE btQuadWord(const btScalar& x, const btScalar& y, const btScalar& z) { setValue(x, y, z); }
	/// All four components.
	SIMD_FORCE_INLINE btQuadWord(const btScalar& x, const btScalar& y, const btScalar& z, const btScalar& w)
	{
		setValue(x, y, z, w);
	}

	/// Component-wise maximum of all four components.
	SIMD_FORCE_INLINE void setMax(const btQuadWord& other)
	{
		for (int i = 0; i < 4; ++i) m_floats[i] = m_floats[i] > other.m_floats[i] ? m_floats[i] : other.m_floats[i];
	}
	/// Component-wise minimum of all four components.
	SIMD_FORCE_INLINE void setMin(const btQuadWord& other)
	{
		for (int i = 0; i < 4; ++i) m_floats[i] = m_floats[i] < other.m_floats[i] ? m_floats[i] : other.m_floats[i];
	}
};

#endif  // BT_SIMD_QUADWORD_H
