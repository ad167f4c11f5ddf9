// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_EXTRAS_COLLADA_PHYSICS_H
#define CALIBER_EXTRAS_COLLADA_PHYSICS_H

/// COLLADA 1.4 physics import and export: rigid bodies, their shapes and materials, 6-DoF joints, gravity and time step
/// (docs/extras.md, "COLLADA physics"). Needs tinyxml2 (Debian libtinyxml2-dev).

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "btBulletDynamicsCommon.h"

namespace caliber
{
/// What a COLLADA document described, owning every object made for it.
class ColladaPhysicsScene
{
public:
	ColladaPhysicsScene() = default;
	ColladaPhysicsScene(const ColladaPhysicsScene&) = delete;
	ColladaPhysicsScene& operator=(const ColladaPhysicsScene&) = delete;
	/// Takes the bodies out of the world they were added to before deleting them: that world must still exist
	/// (call removeFrom first when the world goes before the scene).
	~ColladaPhysicsScene();

	/// The rigid bodies, in document order, at their nodes' poses, with their velocities (no motion states).
	std::vector<std::unique_ptr<btRigidBody>> bodies;
	/// Each body's sid in the physics model (or its name when it has one).
	std::vector<std::string> bodyNames;
	/// The physics scene's gravity and time step (COLLADA's defaults when absent: 0 and 1/60 s).
	btVector3 gravity = btVector3(0, 0, 0);
	btScalar timeStep = btScalar(1) / 60;
	/// Why the import failed ("line N: ..."); empty on success.
	std::string error;

	bool ok() const { return error.empty(); }
	/// Adds every body to world and sets its gravity; removeFrom (or the destructor) takes them out.
	void addTo(btDiscreteDynamicsWorld& world);
	void removeFrom(btDiscreteDynamicsWorld& world);

	/// The joints (btGeneric6DofConstraint, from rigid_constraint), in document order, with their sids.
	std::vector<std::unique_ptr<btTypedConstraint>> constraints;
	std::vector<std::string> constraintNames;
	/// For each joint, whether its bodies may interpenetrate (COLLADA's interpenetrate: addConstraint's
	/// disableCollisionsBetweenLinkedBodies).
	std::vector<bool> constraintsInterpenetrate;

	/// Objects the bodies use (shapes, compound children, triangle meshes); kept alive by the scene.
	std::vector<std::unique_ptr<btCollisionShape>> shapes;
	std::vector<std::unique_ptr<btStridingMeshInterface>> meshes;

private:
	btDiscreteDynamicsWorld* m_world = nullptr;
};

/// Reads a COLLADA document of size bytes into scene (which must be fresh: no bodies yet). Returns scene.ok().
/// The document's <asset> unit and up axis are converted into metres and a y-up world; polylist and polygons
/// meshes are triangulated as fans; a dynamic body's mass_frame puts it on its centre of mass (shapes in a compound).
/// Any problem fails the whole import with one message naming the line: malformed XML, a missing or
/// dangling reference, a number that is not finite, a count that does not match, a non-positive size, a
/// dynamic body without a positive mass, a node transform with scale or shear, an unsupported shape.
/// A null text with a non-zero size is a programming error: btAssert, else a failed import.
bool importColladaPhysics(const char* text, std::size_t size, ColladaPhysicsScene& scene);

/// importColladaPhysics of the file at path.
bool importColladaPhysicsFile(const char* path, ColladaPhysicsScene& scene);

/// Writes world's rigid bodies (shapes: box, sphere, static plane, cylinder, capsule, convex hull, BVH
/// triangle mesh, and compounds of these), their materials, poses and velocities, its btGeneric6DofConstraint
/// joints between two of its bodies (frames, limits, enabled, interpenetrate), and the world's gravity with
/// timeStep, as a COLLADA 1.4.1 document in out. Numbers are printed with enough digits to read back bit for
/// bit. A collision object that is not a rigid body, a shape or joint of another kind, or a joint to the
/// world, fails the export with a message in error and leaves out empty.
bool exportColladaPhysics(const btDiscreteDynamicsWorld& world, btScalar timeStep, std::string& out,
                          std::string& error);
}  // namespace caliber

#endif  // CALIBER_EXTRAS_COLLADA_PHYSICS_H
