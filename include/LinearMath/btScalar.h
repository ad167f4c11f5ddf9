// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SCALAR_H
#define BT_SCALAR_H

/// btScalar and the small helpers every Caliber header builds on: precision, inline and alignment
/// macros, math wrappers, constants and btAssert.

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>

/// The Bullet 2 API level Caliber implements (2.89); user code tests it to pick modern signatures.
#define BT_BULLET_VERSION 289
/// Caliber's own version.
#define CALIBER_VERSION_MAJOR 0
#define CALIBER_VERSION_MINOR 1
#define CALIBER_VERSION_PATCH 0

/// Returns BT_BULLET_VERSION, as Bullet does.
inline int btGetVersion() { return BT_BULLET_VERSION; }
/// 1 when btScalar is double, else 0.
inline int btIsDoublePrecision()
{
#ifdef BT_USE_DOUBLE_PRECISION
	return 1;
#else
	return 0;
#endif
}

// ---- compiler and platform macros ---------------------------------------------------------------

#if defined(_MSC_VER)
#define SIMD_FORCE_INLINE __forceinline
#define ATTRIBUTE_ALIGNED16(a) __declspec(align(16)) a
#define ATTRIBUTE_ALIGNED64(a) __declspec(align(64)) a
#define ATTRIBUTE_ALIGNED128(a) __declspec(align(128)) a
#define btLikely(x) (x)
#define btUnlikely(x) (x)
#else
#define SIMD_FORCE_INLINE inline __attribute__((always_inline))
#define ATTRIBUTE_ALIGNED16(a) a __attribute__((aligned(16)))
#define ATTRIBUTE_ALIGNED64(a) a __attribute__((aligned(64)))
#define ATTRIBUTE_ALIGNED128(a) a __attribute__((aligned(128)))
#define btLikely(x) __builtin_expect(!!(x), 1)
#define btUnlikely(x) __builtin_expect(!!(x), 0)
#endif

// The SSE path is used for single precision on x86 unless the build turned it off (CALIBER_SIMD=OFF
// defines CALIBER_NO_SIMD publicly). Layout is identical either way: btVector3 is 4 scalars, 16-byte
// aligned, so only speed differs.
#if !defined(CALIBER_NO_SIMD) && !defined(BT_USE_DOUBLE_PRECISION) && \
    (defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2))
#ifndef BT_USE_SSE
#define BT_USE_SSE
#endif
#include <emmintrin.h>
#endif

// ---- btAssert -----------------------------------------------------------------------------------

/// Prints the failed condition with its place and aborts. Called by btAssert only; always defined
/// by the library so that a debug program links against a release library and vice versa.
#if defined(_MSC_VER)
__declspec(noreturn)
#else
__attribute__((noreturn))
#endif
    void btAssertFailed(const char* condition, const char* file, int line);

#if defined(CALIBER_ASSERTS) || !defined(NDEBUG)
#define CALIBER_ASSERTS_ENABLED 1
#define btAssert(x) ((x) ? (void)0 : btAssertFailed(#x, __FILE__, __LINE__))
#else
#define CALIBER_ASSERTS_ENABLED 0
// Compiled out, but still "uses" its argument so that variables read only by asserts do not warn.
#define btAssert(x) ((void)sizeof(!(x)))
#endif
/// Bullet's expensive checks; Caliber treats them as ordinary asserts.
#define btFullAssert(x) btAssert(x)

// ---- btScalar and constants ---------------------------------------------------------------------

#ifdef BT_USE_DOUBLE_PRECISION
/// The floating point type of the whole API.
typedef double btScalar;
#define BT_LARGE_FLOAT 1e30
#define SIMD_EPSILON DBL_EPSILON
#define SIMD_INFINITY DBL_MAX
#else
/// The floating point type of the whole API.
typedef float btScalar;
#define BT_LARGE_FLOAT 1e18f
#define SIMD_EPSILON FLT_EPSILON
#define SIMD_INFINITY FLT_MAX
#endif

#define BT_ONE btScalar(1.0)
#define BT_ZERO btScalar(0.0)
#define BT_TWO btScalar(2.0)
#define BT_HALF btScalar(0.5)
#define SIMD_PI btScalar(3.1415926535897932384626433832795029)
#define SIMD_2_PI (btScalar(2.0) * SIMD_PI)
#define SIMD_HALF_PI (SIMD_PI * btScalar(0.5))
#define SIMD_RADS_PER_DEG (SIMD_2_PI / btScalar(360.0))
#define SIMD_DEGS_PER_RAD (btScalar(360.0) / SIMD_2_PI)
#define SIMDSQRT12 btScalar(0.7071067811865475244008443621048490)
#define BT_INFINITY (btScalar(HUGE_VAL))
#define BT_NAN (btScalar(NAN))

/// A link-time guard against mixing precisions: every translation unit that includes this header
/// references the marker for its own btScalar, and the library defines only the marker for the
/// precision it was built with. A float program linked to a double library (or the reverse) fails
/// to link with an undefined reference to btCaliberPrecisionMarker(float|double).
int btCaliberPrecisionMarker(btScalar);
#if defined(__GNUC__)
static int (*const btCaliberPrecisionCheck)(btScalar) __attribute__((used)) = &btCaliberPrecisionMarker;
#endif

/// The same guard for BT_THREADSAFE (docs/threading.md): a thread-safe library (CALIBER_THREADSAFE=ON,
/// the default, which defines BT_THREADSAFE=1 for its users) defines only caliber::threadSafeBuildMarker,
/// a single-threaded one only caliber::singleThreadedBuildMarker. A program compiled with the other
/// setting fails to link with an undefined reference to the marker it expected.
namespace caliber
{
#if defined(BT_THREADSAFE) && BT_THREADSAFE
int threadSafeBuildMarker();
#if defined(__GNUC__)
static int (*const threadingBuildCheck)() __attribute__((used)) = &threadSafeBuildMarker;
#endif
#else
int singleThreadedBuildMarker();
#if defined(__GNUC__)
static int (*const threadingBuildCheck)() __attribute__((used)) = &singleThreadedBuildMarker;
#endif
#endif
}  // namespace caliber

// ---- math wrappers ------------------------------------------------------------------------------

SIMD_FORCE_INLINE btScalar btSqrt(btScalar x) { return sqrt(x); }
SIMD_FORCE_INLINE btScalar btFabs(btScalar x) { return fabs(x); }
SIMD_FORCE_INLINE btScalar btCos(btScalar x) { return cos(x); }
SIMD_FORCE_INLINE btScalar btSin(btScalar x) { return sin(x); }
SIMD_FORCE_INLINE btScalar btTan(btScalar x) { return tan(x); }
/// acos with its argument clamped to [-1, 1], so rounding just outside the range gives 0 or pi.
SIMD_FORCE_INLINE btScalar btAcos(btScalar x)
{
	if (x < btScalar(-1)) x = btScalar(-1);
	if (x > btScalar(1)) x = btScalar(1);
	return acos(x);
}
/// asin with its argument clamped to [-1, 1].
SIMD_FORCE_INLINE btScalar btAsin(btScalar x)
{
	if (x < btScalar(-1)) x = btScalar(-1);
	if (x > btScalar(1)) x = btScalar(1);
	return asin(x);
}
SIMD_FORCE_INLINE btScalar btAtan(btScalar x) { return atan(x); }
SIMD_FORCE_INLINE btScalar btAtan2(btScalar y, btScalar x) { return atan2(y, x); }
SIMD_FORCE_INLINE btScalar btExp(btScalar x) { return exp(x); }
SIMD_FORCE_INLINE btScalar btLog(btScalar x) { return log(x); }
SIMD_FORCE_INLINE btScalar btPow(btScalar x, btScalar y) { return pow(x, y); }
SIMD_FORCE_INLINE btScalar btFmod(btScalar x, btScalar y) { return fmod(x, y); }
SIMD_FORCE_INLINE btScalar btRecipSqrt(btScalar x) { return btScalar(1.0) / btSqrt(x); }
SIMD_FORCE_INLINE btScalar btRecip(btScalar x) { return btScalar(1.0) / x; }

/// atan2 by a polynomial approximation, absolute error below 2e-5 rad (exactly 0 at the origin);
/// for callers that trade accuracy for speed.
SIMD_FORCE_INLINE btScalar btAtan2Fast(btScalar y, btScalar x)
{
	const btScalar absX = btFabs(x), absY = btFabs(y);
	const btScalar largest = absX > absY ? absX : absY;
	const btScalar smallest = absX > absY ? absY : absX;
	// atan(a) for a = smallest / largest in [0, 1]: Abramowitz and Stegun 4.4.49 (error <= 1e-5).
	const btScalar a = largest > btScalar(0) ? smallest / largest : btScalar(0);
	const btScalar s = a * a;
	btScalar angle =
	    a *
	    (btScalar(0.9998660) +
	     s * (btScalar(-0.3302995) + s * (btScalar(0.1801410) + s * (btScalar(-0.0851330) + s * btScalar(0.0208351)))));
	// Unfold the octant: atan(|y|/|x|) = pi/2 - atan(|x|/|y|), then the quadrant.
	if (absY > absX) angle = SIMD_HALF_PI - angle;
	if (x < btScalar(0)) angle = SIMD_PI - angle;
	return y < btScalar(0) ? -angle : angle;
}

/// True when |x| is below SIMD_EPSILON.
SIMD_FORCE_INLINE bool btFuzzyZero(btScalar x) { return btFabs(x) < SIMD_EPSILON; }
/// True when |a| <= eps (Bullet's meaning: "a equals zero within eps").
SIMD_FORCE_INLINE bool btEqual(btScalar a, btScalar eps) { return (a <= eps) && !(a < -eps); }
/// True when a > eps (Bullet's meaning).
SIMD_FORCE_INLINE bool btGreaterEqual(btScalar a, btScalar eps) { return !(a <= eps); }
/// 1 if x is negative, else 0.
SIMD_FORCE_INLINE int btIsNegative(btScalar x) { return x < btScalar(0.0) ? 1 : 0; }
/// True when x is neither infinite nor NaN.
SIMD_FORCE_INLINE bool btIsFinite(btScalar x) { return x - x == btScalar(0); }
SIMD_FORCE_INLINE btScalar btRadians(btScalar degrees) { return degrees * SIMD_RADS_PER_DEG; }
SIMD_FORCE_INLINE btScalar btDegrees(btScalar radians) { return radians * SIMD_DEGS_PER_RAD; }
/// Floating point select: valueIfNonNegative when condition >= 0, else valueIfNegative.
SIMD_FORCE_INLINE btScalar btFsel(btScalar condition, btScalar valueIfNonNegative, btScalar valueIfNegative)
{
	return condition >= btScalar(0.0) ? valueIfNonNegative : valueIfNegative;
}

/// Wraps an angle in radians into [-pi, pi].
SIMD_FORCE_INLINE btScalar btNormalizeAngle(btScalar angleInRadians)
{
	angleInRadians = btFmod(angleInRadians, SIMD_2_PI);
	if (angleInRadians < -SIMD_PI) return angleInRadians + SIMD_2_PI;
	if (angleInRadians > SIMD_PI) return angleInRadians - SIMD_2_PI;
	return angleInRadians;
}

/// True on little-endian machines.
SIMD_FORCE_INLINE bool btMachineIsLittleEndian()
{
	const unsigned int probe = 1;
	return *reinterpret_cast<const unsigned char*>(&probe) == 1;
}

/// Branch-free select on an unsigned condition: valueIfConditionNonZero when condition != 0.
SIMD_FORCE_INLINE unsigned btSelect(unsigned condition, unsigned valueIfConditionNonZero, unsigned valueIfConditionZero)
{
	const unsigned mask = 0u - unsigned(condition != 0);
	return (valueIfConditionNonZero & mask) | (valueIfConditionZero & ~mask);
}
SIMD_FORCE_INLINE int btSelect(unsigned condition, int valueIfConditionNonZero, int valueIfConditionZero)
{
	return int(btSelect(condition, unsigned(valueIfConditionNonZero), unsigned(valueIfConditionZero)));
}
SIMD_FORCE_INLINE float btSelect(unsigned condition, float valueIfConditionNonZero, float valueIfConditionZero)
{
	return condition != 0 ? valueIfConditionNonZero : valueIfConditionZero;
}

/// Swaps two values.
template <typename T>
SIMD_FORCE_INLINE void btSwap(T& a, T& b)
{
	T tmp = a;
	a = b;
	b = tmp;
}

/// Byte order helpers (used by serialisation).
SIMD_FORCE_INLINE unsigned btSwapEndian(unsigned value)
{
	return ((value & 0x000000ffu) << 24) | ((value & 0x0000ff00u) << 8) | ((value & 0x00ff0000u) >> 8) |
	       ((value & 0xff000000u) >> 24);
}
SIMD_FORCE_INLINE unsigned short btSwapEndian(unsigned short value)
{
	return static_cast<unsigned short>(((value & 0x00ffu) << 8) | ((value & 0xff00u) >> 8));
}
SIMD_FORCE_INLINE unsigned btSwapEndian(int value) { return btSwapEndian(unsigned(value)); }
SIMD_FORCE_INLINE unsigned short btSwapEndian(short value) { return btSwapEndian(static_cast<unsigned short>(value)); }

/// Base of objects that carry a type tag (constraints, soft bodies).
struct btTypedObject
{
	explicit btTypedObject(int objectType) : m_objectType(objectType) {}
	int m_objectType;
	inline int getObjectType() const { return m_objectType; }
};

/// Aligned operator new/delete for a class, so that heap instances keep their 16-byte alignment.
#define BT_DECLARE_ALIGNED_ALLOCATOR()                                                                     \
	SIMD_FORCE_INLINE void* operator new(size_t sizeInBytes) { return btAlignedAlloc(sizeInBytes, 16); }   \
	SIMD_FORCE_INLINE void operator delete(void* ptr) { btAlignedFree(ptr); }                              \
	SIMD_FORCE_INLINE void* operator new(size_t, void* ptr) { return ptr; }                                \
	SIMD_FORCE_INLINE void operator delete(void*, void*) {}                                                \
	SIMD_FORCE_INLINE void* operator new[](size_t sizeInBytes) { return btAlignedAlloc(sizeInBytes, 16); } \
	SIMD_FORCE_INLINE void operator delete[](void* ptr) { btAlignedFree(ptr); }                            \
	SIMD_FORCE_INLINE void* operator new[](size_t, void* ptr) { return ptr; }                              \
	SIMD_FORCE_INLINE void operator delete[](void*, void*) {}

#include "LinearMath/btMinMax.h"

#endif  // BT_SCALAR_H
