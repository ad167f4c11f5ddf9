// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btScalar.h"

#include <stdio.h>

// Defined only for the precision this library was built with; see btScalar.h.
int btCaliberPrecisionMarker(btScalar) { return int(sizeof(btScalar)); }

// Defined only for the BT_THREADSAFE setting this library was built with; see btScalar.h.
#if defined(BT_THREADSAFE) && BT_THREADSAFE
int caliber::threadSafeBuildMarker() { return 1; }
#else
int caliber::singleThreadedBuildMarker() { return 0; }
#endif

void btAssertFailed(const char* condition, const char* file, int line)
{
	fprintf(stderr, "Caliber: assertion failed: %s (%s:%d)\n", condition, file, line);
	fflush(stderr);
	abort();
}
