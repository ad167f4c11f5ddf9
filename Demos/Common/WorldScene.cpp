// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "WorldScene.h"

#include <cstdio>

#include "BulletSoftBody/btSoftBody.h"
#include "ShapeMesher.h"
#include "SoftBodyScene.h"
#include "btBulletDynamicsCommon.h"

namespace caliber
{
namespace demo
{
void SceneDebugDraw::drawLine(const btVector3& from, const btVector3& to, const btVector3& color)
{
	m_scene.addLine(from, to, color);
}

void SceneDebugDraw::drawContactPoint(const btVector3& pointOnB, const btVector3& normalOnB, btScalar, int,
                                      const btVector3& color)
{
	m_scene.addPoint(pointOnB, color);
	m_scene.addLine(pointOnB, pointOnB + normalOnB * btScalar(0.2), color);
}

void SceneDebugDraw::reportErrorWarning(const char* warningString)
{
	std::fprintf(stderr, "debug draw: %s\n", warningString ? warningString : "(null)");
}

btVector3 paletteColor(int index)
{
	static const btVector3 kPalette[] = {btVector3(0.95f, 0.55f, 0.20f), btVector3(0.25f, 0.50f, 0.90f),
	                                     btVector3(0.35f, 0.75f, 0.35f), btVector3(0.85f, 0.30f, 0.30f),
	                                     btVector3(0.60f, 0.40f, 0.85f), btVector3(0.95f, 0.80f, 0.25f),
	                                     btVector3(0.20f, 0.70f, 0.70f), btVector3(0.90f, 0.45f, 0.65f)};
	const int count = int(sizeof(kPalette) / sizeof(kPalette[0]));
	return kPalette[((index % count) + count) % count];
}

namespace
{
// A soft body keeps btCollisionObject's default static flag, but it moves.
bool isStill(const btCollisionObject& object) { return object.isStaticObject() && !btSoftBody::upcast(&object); }

// A box this large is a "whole world" ground or a placeholder; framing it would shrink the scene to dots.
bool isFramable(const btVector3& aabbMin, const btVector3& aabbMax)
{
	return isFinite(aabbMin) && isFinite(aabbMax) && (aabbMax - aabbMin).length() < btScalar(1e4);
}
// Grounds and walls (static, at least 4 m across in two directions, or a plane) are grey with a
// checker; every other object gets a colour of its own.
bool isGround(const btCollisionObject& object)
{
	if (!isStill(object) || object.isKinematicObject()) return false;
	const btCollisionShape* shape = object.getCollisionShape();
	if (!shape) return false;
	if (shape->getShapeType() == STATIC_PLANE_PROXYTYPE) return true;
	btVector3 aabbMin, aabbMax;
	shape->getAabb(object.getWorldTransform(), aabbMin, aabbMax);
	const btVector3 size = aabbMax - aabbMin;
	int wide = 0;
	for (int axis = 0; axis < 3; ++axis)
		if (size[axis] >= btScalar(4)) ++wide;
	return wide >= 2;
}
}  // namespace

int addWorld(Scene& scene, btCollisionWorld& world, const WorldStyle& style)
{
	const btCollisionObjectArray& objects = world.getCollisionObjectArray();
	// The focus: what moves; failing that, everything of a sensible size.
	bool anyMoving = false;
	for (int i = 0; i < objects.size(); ++i)
		if (!isStill(*objects[i])) anyMoving = true;
	for (int i = 0; i < objects.size(); ++i)
	{
		const btCollisionObject& object = *objects[i];
		const btCollisionShape* shape = object.getCollisionShape();
		btVector3 aabbMin, aabbMax;
		if (const btSoftBody* soft = btSoftBody::upcast(&object))
		{
			// Always framed (it deforms), on its nodes (the collision bounds add margins and predictions).
			if (softBodyNodeBounds(*soft, aabbMin, aabbMax)) scene.focusOn(aabbMin, aabbMax);
			continue;
		}
		if (!shape || (anyMoving && isStill(object)) || shape->getShapeType() == STATIC_PLANE_PROXYTYPE) continue;
		shape->getAabb(object.getWorldTransform(), aabbMin, aabbMax);
		if (isFramable(aabbMin, aabbMax)) scene.focusOn(aabbMin, aabbMax);
	}
	btVector3 focusMin(-5, -5, -5), focusMax(5, 5, 5);
	if (scene.hasFocus())
	{
		focusMin = scene.focusMin();
		focusMax = scene.focusMax();
	}
	int undrawable = 0;
	if (style.solids)
	{
		MeshStyle mesh;
		mesh.planeCentre = (focusMin + focusMax) * btScalar(0.5);
		mesh.planeHalfSize = (focusMax - focusMin).length() * btScalar(1.5) + 2;
		int coloured = 0;
		for (int i = 0; i < objects.size(); ++i)
		{
			const btCollisionObject& object = *objects[i];
			if (object.getCollisionFlags() & btCollisionObject::CF_DISABLE_VISUALIZE_OBJECT) continue;
			if (const btSoftBody* soft = btSoftBody::upcast(&object))
			{
				addSoftBody(scene, *soft, paletteColor(coloured++));
				continue;
			}
			if (isGround(object))
			{
				mesh.color = btVector3(0.74f, 0.74f, 0.72f);
				mesh.checker = true;
			}
			else
			{
				mesh.color = paletteColor(coloured++);
				mesh.checker = false;
			}
			if (!addShape(scene, object.getCollisionShape(), object.getWorldTransform(), mesh)) ++undrawable;
		}
	}
	if (style.debugMode != 0)
	{
		SceneDebugDraw recorder(scene, style.debugMode);
		btIDebugDraw* previous = world.getDebugDrawer();
		world.setDebugDrawer(&recorder);
		world.debugDrawWorld();
		world.setDebugDrawer(previous);
	}
	return undrawable;
}

void addVehicleWheels(Scene& scene, btRaycastVehicle& vehicle, btScalar width)
{
	MeshStyle style;
	style.color = btVector3(btScalar(0.15), btScalar(0.15), btScalar(0.17));
	for (int i = 0; i < vehicle.getNumWheels(); ++i)
	{
		vehicle.updateWheelTransform(i, true);
		const btWheelInfo& wheel = vehicle.getWheelInfo(i);
		// The wheel's axle is its transform's x axis (the vehicle's right axis in Bullet's convention).
		const btCylinderShapeX shape(btVector3(width / 2, wheel.m_wheelsRadius, wheel.m_wheelsRadius));
		addShape(scene, &shape, wheel.m_worldTransform, style);
	}
}
}  // namespace demo
}  // namespace caliber
