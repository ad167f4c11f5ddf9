// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "ObjScene.h"

#include <math.h>
#include <stdio.h>

namespace obj_demo
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
	text +=
	    "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n"
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

Scene::Scene(btCollisionShape* level, const std::vector<std::unique_ptr<btConvexHullShape>>& hulls)
    : LevelScene(level, btVector3(0, btScalar(-9.81), 0))
{
	for (int k = 0; k < 6 && !hulls.empty(); ++k)
	{
		btConvexHullShape* hull = hulls[k % hulls.size()].get();
		if (!hull) continue;
		const btScalar x = btScalar(-2.5 + k), z = btScalar(k % 2 ? 1 : -1);
		addBody(hull, btTransform(btQuaternion(btVector3(1, 1, 0).normalized(), btScalar(0.3 * k)),
		                          btVector3(x, 4 + btScalar(0.5) * k, z)));
	}
}
}  // namespace obj_demo
