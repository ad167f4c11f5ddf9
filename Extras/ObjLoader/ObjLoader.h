// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_EXTRAS_OBJ_LOADER_H
#define CALIBER_EXTRAS_OBJ_LOADER_H

/// Wavefront OBJ import: groups of polygons become triangle meshes (docs/extras.md, "OBJ import").

#include <cstddef>
#include <string>
#include <vector>

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btVector3.h"

namespace caliber
{
/// A problem found in an OBJ text: its 1-based line number (0 when it concerns the whole input) and what is wrong.
struct ObjMessage
{
	int line = 0;
	std::string text;
};

/// One group (`g`) or object (`o`) of an OBJ file as a triangle mesh with its own vertices.
struct ObjMesh
{
	/// The group's name ("default" for faces before any `g` or `o`).
	std::string name;
	/// The vertices this group's faces use, each once, in order of first use.
	btAlignedObjectArray<btVector3> vertices;
	/// Three indices into vertices per triangle; polygons are triangulated (ear clipping).
	btAlignedObjectArray<int> indices;

	/// Number of triangles.
	int numTriangles() const { return indices.size() / 3; }
};

/// The result of loading an OBJ text.
struct ObjModel
{
	/// One mesh per group that has faces, in order of the group's first face.
	std::vector<ObjMesh> meshes;
	/// Errors with line numbers. When there is any, the load failed and meshes is empty.
	std::vector<ObjMessage> errors;
	/// Things that were skipped or repaired without failing the load (unknown statements, degenerate faces).
	std::vector<ObjMessage> warnings;

	/// True when the text loaded without errors.
	bool ok() const { return errors.empty(); }
	/// Total triangles over all meshes.
	int numTriangles() const;
	/// "line N: text" for each error, one per line (for printing).
	std::string describeErrors() const;
};

/// Largest coordinate magnitude accepted; beyond it squared distances overflow single precision.
const double kObjMaxCoordinate = 1e15;
/// At most this many errors are collected; parsing stops after them.
const int kObjMaxErrors = 100;

/// Parses OBJ text of size bytes into model (which is cleared first). Returns model.ok().
/// A null text with a non-zero size is a programming error: btAssert, else one error and false.
bool loadObjFromMemory(const char* text, std::size_t size, ObjModel& model);

/// Reads and parses the file at path. A file that cannot be read gives one error (line 0) and false.
bool loadObjFile(const char* path, ObjModel& model);
}  // namespace caliber

#endif  // CALIBER_EXTRAS_OBJ_LOADER_H
