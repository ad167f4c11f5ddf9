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
#include "btBulletDynamicsCommon.h"

namespace
{
// The bowl y = 0.04 (x^2 + z^2) over [-6, 6]^2 in 1 m quads, and a ramp beside it.
std::string levelText()
{
	std::string text = "# ObjDemo's level: a bowl of quads and a ramp\ng bowl\n";
	const int n = 12;
	char line[128];
	for (int j = 0; j <= n; ++j)
		for (int i = 0; i <= n; ++i)
		{
			const double x = -6 + i, z = -6 + j;
			snprintf(line, sizeof(line), "v %g %g %g\n", x, 0.04 * (x * x + z * z), z);
			text += line;
		}
	for (int j = 0; j < n; ++j)
		for (int i = 0; i < n; ++i)
		{
			const int a = j * (n + 1) + i + 1;  // OBJ indices are 1-based
			// Counter-clockwise seen from above: normals up.
			snprintf(line, sizeof(line), "f %d %d %d %d\n", a, a + n + 1, a + n + 2, a + 1);
			text += line;
		}
	text += "g ramp\nv 6 2.88 -2\nv 6 2.88 2\nv 9 4 2\nv 9 4 -2\nf -4 -3 -2 -1\n";
	return text;
}

// A unit crate (quads) and a hexagonal prism (hexagons and quads), as separate groups.
std::string piecesText()
{
	std::string text = "# ObjDemo's pieces\ng crate\n";
	text += "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n"
	        "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n"
	        "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
	text += "g prism\n";
	char line[128];
	for (int k = 0; k < 2; ++k)
		for (int i = 0; i < 6; ++i)
		{
			const double angle = i * M_PI / 3;
			snprintf(line, sizeof(line), "v %g %g %g\n", 0.4 * cos(angle), k ? 0.3 : -0.3, 0.4 * sin(angle));
			text += line;
		}
	// Relative indices: the prism's 12 vertices are -12 .. -1.
	text += "f -12 -11 -10 -9 -8 -7\nf -1 -2 -3 -4 -5 -6\n";
	for (int i = 0; i < 6; ++i)
	{
		const int a = -12 + i, b = -12 + (i + 1) % 6;
		snprintf(line, sizeof(line), "f %d %d %d %d\n", a, a + 6, b + 6, b);
		text += line;
	}
	return text;
}

bool load(const char* path, const std::string& builtIn, caliber::ObjModel& model)
{
	const bool ok = path ? caliber::loadObjFile(path, model) : caliber::loadObjFromMemory(builtIn.data(), builtIn.size(), model);
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
	if (!load(files.size() > 0 ? files[0].c_str() : 0, levelText(), level)) return 1;
	if (!load(files.size() > 1 ? files[1].c_str() : 0, piecesText(), pieces)) return 1;
	for (const caliber::ObjMesh& mesh : level.meshes)
		printf("level group '%s': %d vertices, %d triangles\n", mesh.name.c_str(), mesh.vertices.size(), mesh.numTriangles());
	for (const caliber::ObjMesh& mesh : pieces.meshes)
		printf("piece group '%s': %d vertices, %d triangles\n", mesh.name.c_str(), mesh.vertices.size(), mesh.numTriangles());

	caliber::StaticMeshShape levelShape = caliber::buildStaticMeshShape(level);
	std::vector<std::unique_ptr<btConvexHullShape>> hulls = caliber::buildConvexHullShapes(pieces);
	if (!levelShape.shape || hulls.empty())
	{
		printf("ObjDemo: the models gave no shapes\n");
		return 1;
	}

	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
	world.setGravity(btVector3(0, btScalar(-9.81), 0));
	btRigidBody levelBody(0, 0, levelShape.shape.get());
	world.addRigidBody(&levelBody);
	std::vector<std::unique_ptr<btRigidBody>> bodies;
	for (int k = 0; k < 6; ++k)
	{
		btConvexHullShape* hull = hulls[k % hulls.size()].get();
		if (!hull) continue;
		btVector3 inertia;
		hull->calculateLocalInertia(1, inertia);
		bodies.emplace_back(new btRigidBody(1, 0, hull, inertia));
		const btScalar x = btScalar(-2.5 + k), z = btScalar(k % 2 ? 1 : -1);
		bodies.back()->setWorldTransform(btTransform(btQuaternion(btVector3(1, 1, 0).normalized(), btScalar(0.3 * k)),
		                                             btVector3(x, 4 + btScalar(0.5) * k, z)));
		world.addRigidBody(bodies.back().get());
	}

	for (int step = 0; step < 300; ++step) world.stepSimulation(btScalar(1) / 60, 0);
	// Each piece rests in the bowl: slower than 5 cm/s, inside its rim, and never below its surface
	// (y = 0.04 r^2 under the piece's centre, less the piece's half size of at most 0.87 m).
	int resting = 0, inside = 0;
	for (const auto& body : bodies)
	{
		const btVector3& p = body->getCenterOfMassPosition();
		resting += body->getLinearVelocity().length() < btScalar(0.05);
		inside += btFabs(p.x()) < 6 && btFabs(p.z()) < 6 && p.y() > btScalar(0.04) * (p.x() * p.x() + p.z() * p.z()) - btScalar(0.87);
		printf("  piece at (%.2f %.2f %.2f), speed %.3f m/s\n", p.x(), p.y(), p.z(), body->getLinearVelocity().length());
	}
	pictures.capture(world);
	for (const auto& body : bodies) world.removeRigidBody(body.get());
	world.removeRigidBody(&levelBody);
	const bool settled = resting == int(bodies.size()) && inside == int(bodies.size());
	printf("check: all %d pieces rest inside the bowl, on its surface: %s\n", int(bodies.size()), settled ? "ok" : "FAILED");

	// A malformed file: the loader names the line.
	const char broken[] = "v 0 0 0\nv 1 0 0\nv 0 1\nf 1 2 3\n";
	caliber::ObjModel bad;
	const bool refused = !caliber::loadObjFromMemory(broken, sizeof(broken) - 1, bad) && !bad.errors.empty() && bad.errors[0].line == 3;
	printf("a file with a vertex of two coordinates:\n%s", bad.describeErrors().c_str());
	printf("check: the malformed file is refused at line 3: %s\n", refused ? "ok" : "FAILED");
	return pictures.finish(settled && refused ? 0 : 1);
}
