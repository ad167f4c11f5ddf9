// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/BroadphaseCollision/btDispatcher.h"

// Out of line so that the vtable has one home.
btDispatcher::~btDispatcher() {}
