// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// ObjDemo: Wavefront OBJ import (Extras/ObjLoader). A level (a bowl of quads and a ramp, two groups) becomes
// one static BVH mesh; a set of pieces (a crate of quads, a hexagonal prism with six-sided faces) becomes
// convex hulls, dropped into the bowl. Then a malformed file is refused with its line number.
// Usage: ObjDemo [level.obj [pieces.obj]] [--png PATH]. Exit 1 when a check fails.

#include "DemoPictures.h"

#include <math.h>
#include <stdio.h>

#include <memory>
#include <string>
#include <vector>

#include "ObjLoader/MeshShapes.h"
#include "ObjLoader/ObjLoader.h"
#include "ObjScene.h"

namespace
{
bool load(const char* path, const std::string& builtIn, caliber::ObjModel& model)
{
	const bool ok =
	    path ? caliber::loadObjFile(path, model) : caliber::loadObjFromMemory(builtIn.data(), builtIn.size(), model);
	if (!ok) printf("ObjDemo: %s:\n%s", path ? path : "built-in model", model.describeErrors().c_str());
	return ok;
}
}  // namespace

int main(int argc, char** argv)
{
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "ObjDemo";
	commandLine.maxPositional = 2;
	commandLine.positionalUsage = "[level.obj [pieces.obj]]";
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();
	const std::vector<std::string>& files = pictures.positional();
	caliber::ObjModel level, pieces;
	if (!load(files.size() > 0 ? files[0].c_str() : 0, obj_demo::levelText(), level)) return 1;
	if (!load(files.size() > 1 ? files[1].c_str() : 0, obj_demo::piecesText(), pieces)) return 1;
	for (const caliber::ObjMesh& mesh : level.meshes)
		printf("level group '%s': %d vertices, %d triangles\n", mesh.name.c_str(), mesh.vertices.size(),
		       mesh.numTriangles());
	for (const caliber::ObjMesh& mesh : pieces.meshes)
		printf("piece group '%s': %d vertices, %d triangles\n", mesh.name.c_str(), mesh.vertices.size(),
		       mesh.numTriangles());

	caliber::StaticMeshShape levelShape = caliber::buildStaticMeshShape(level);
	std::vector<std::unique_ptr<btConvexHullShape>> hulls = caliber::buildConvexHullShapes(pieces);
	if (!levelShape.shape || hulls.empty())
	{
		printf("ObjDemo: the models gave no shapes\n");
		return 1;
	}

	obj_demo::Scene scene(levelShape.shape.get(), hulls);  // ObjScene.h: the bowl and six pieces
	btDiscreteDynamicsWorld& world = scene.world();
	const std::vector<std::unique_ptr<btRigidBody>>& bodies = scene.bodies();

	for (int step = 0; step < 300; ++step) world.stepSimulation(btScalar(1) / 60, 0);
	// Each piece rests in the bowl: slower than 5 cm/s, inside its rim, and never below its surface
	// (y = 0.04 r^2 under the piece's centre, less the piece's half size of at most 0.87 m).
	int resting = 0, inside = 0;
	for (const auto& body : bodies)
	{
		const btVector3& p = body->getCenterOfMassPosition();
		resting += body->getLinearVelocity().length() < btScalar(0.05);
		inside += btFabs(p.x()) < 6 && btFabs(p.z()) < 6 &&
		          p.y() > btScalar(0.04) * (p.x() * p.x() + p.z() * p.z()) - btScalar(0.87);
		printf("  piece at (%.2f %.2f %.2f), speed %.3f m/s\n", p.x(), p.y(), p.z(),
		       body->getLinearVelocity().length());
	}
	pictures.capture(world);
	const bool settled = resting == int(bodies.size()) && inside == int(bodies.size());
	printf("check: all %d pieces rest inside the bowl, on its surface: %s\n", int(bodies.size()),
	       settled ? "ok" : "FAILED");

	// A malformed file: the loader names the line.
	const char broken[] = "v 0 0 0\nv 1 0 0\nv 0 1\nf 1 2 3\n";
	caliber::ObjModel bad;
	const bool refused =
	    !caliber::loadObjFromMemory(broken, sizeof(broken) - 1, bad) && !bad.errors.empty() && bad.errors[0].line == 3;
	printf("a file with a vertex of two coordinates:\n%s", bad.describeErrors().c_str());
	printf("check: the malformed file is refused at line 3: %s\n", refused ? "ok" : "FAILED");
	return pictures.finish(settled && refused ? 0 : 1);
}
