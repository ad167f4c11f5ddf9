// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btTriangleCallback.h"

btTriangleCallback::~btTriangleCallback() {}

btInternalTriangleIndexCallback::~btInternalTriangleIndexCallback() {}
