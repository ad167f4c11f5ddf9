// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CPU_FEATURE_UTILITY_H
#define BT_CPU_FEATURE_UTILITY_H

#include "LinearMath/btScalar.h"

namespace caliber
{
/// The btCpuFeatureUtility bits of the processor running the program.
inline int detectCpuFeatures()
{
	int features = 0;
#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
	__builtin_cpu_init();
	if (__builtin_cpu_supports("fma")) features |= 1;      // CPU_FEATURE_FMA3
	if (__builtin_cpu_supports("sse4.1")) features |= 2;   // CPU_FEATURE_SSE4_1
#elif defined(__ARM_NEON) && defined(__ARM_FP16_FORMAT_IEEE)
	features |= 4;  // CPU_FEATURE_NEON_HPFP
#endif
	return features;
}
}  // namespace caliber

/// Which instruction-set extensions the processor running the program has (Bullet's query, used to pick
/// kernels at run time). Caliber chooses its kernels at compile time; this only reports.
class btCpuFeatureUtility
{
public:
	enum btCpuFeature
	{
		CPU_FEATURE_FMA3 = 1,
		CPU_FEATURE_SSE4_1 = 2,
		CPU_FEATURE_NEON_HPFP = 4
	};

	/// A bit set of btCpuFeature, found once.
	static int getCpuFeatures()
	{
		static const int features = caliber::detectCpuFeatures();
		return features;
	}
};

#endif  // BT_CPU_FEATURE_UTILITY_H
