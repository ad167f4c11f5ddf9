// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btConcaveShape.h"

btConcaveShape::btConcaveShape() : m_collisionMargin(btScalar(0)) {}

btConcaveShape::~btConcaveShape() {}

void btConcaveShape::setMargin(btScalar collisionMargin)
{
	const bool valid = collisionMargin >= btScalar(0) && btIsFinite(collisionMargin);
	btAssert(valid);
	m_collisionMargin = valid ? collisionMargin : btScalar(0);
}
